/* aces_reference.c - the ACES 1.0 reference tone scale for neutral colours (claim S3).
 *
 * Re-derived from the Academy's CTL (ampas/aces-dev, ACESlib.Tonescales.ctl: segmented_spline_c5_fwd
 * with RRT_PARAMS, segmented_spline_c9_fwd with ODT_48nits; ACESlib.ODT_Common.ctl: Y_2_linCV and
 * darkSurround_to_dimSurround; ODT.Academy.Rec709_100nits_dim.ctl for the order of the steps).
 * Both tone scales are uniform quadratic B-splines in log10-log10 space between three anchor
 * points, with straight (log-log) extensions outside. For a grey input every other RRT/ODT step
 * (glow, red modifier, AP0/AP1/XYZ/Rec.709 conversions, desaturations) leaves the grey unchanged,
 * so the whole chain for grey is the scalar function below. The spline coefficients are the
 * published constants of the ACES 1.0 transforms.
 */
#include "sol_hdr.h"

#include <math.h>

#define ACES_HALF_MIN 6.10352e-5 /* the CTL clamps inputs to HALF_MIN before log10 */

typedef struct log_spline {
    const double *coefs_low, *coefs_high; /* knots_low + 2 and knots_high + 2 B-spline coefficients */
    int knots_low, knots_high;
    double min_x, min_y, mid_x, mid_y, max_x, max_y; /* anchor points (linear units) */
    double slope_low, slope_high;                    /* log-log slopes of the extensions */
} log_spline;

/* Uniform quadratic B-spline segment through coefficients c[j], c[j+1], c[j+2] at t in [0,1). */
static double bspline2(const double *c, int j, double t)
{
    double a = 0.5 * c[j] - c[j + 1] + 0.5 * c[j + 2], b = c[j + 1] - c[j], d = 0.5 * (c[j] + c[j + 1]);
    return (a * t + b) * t + d;
}

static double log_spline_eval(const log_spline *s, double x)
{
    double lx = log10(fmax(x, ACES_HALF_MIN));
    double lmin = log10(s->min_x), lmid = log10(s->mid_x), lmax = log10(s->max_x), ly;
    if (lx <= lmin) {
        ly = log10(s->min_y) + s->slope_low * (lx - lmin);
    } else if (lx < lmid) {
        double k = (s->knots_low - 1) * (lx - lmin) / (lmid - lmin);
        int j = (int)k;
        ly = bspline2(s->coefs_low, j, k - j);
    } else if (lx < lmax) {
        double k = (s->knots_high - 1) * (lx - lmid) / (lmax - lmid);
        int j = (int)k;
        ly = bspline2(s->coefs_high, j, k - j);
    } else {
        ly = log10(s->max_y) + s->slope_high * (lx - lmax);
    }
    return pow(10.0, ly);
}

/* RRT tone scale (segmented spline c5, RRT_PARAMS). */
static const double rrt_low[6] = {-4.0000000000, -4.0000000000, -3.1573765773, -0.4852499958, 1.8477324706,
                                  1.8477324706};
static const double rrt_high[6] = {-0.7185482425, 2.0810307172, 3.6681241237, 4.0000000000, 4.0000000000,
                                   4.0000000000};

static double rrt_tonescale(double x)
{
    const log_spline rrt = {rrt_low, rrt_high, 4, 4, 0.18 * 0x1p-15, 1e-4, 0.18, 4.8, 0.18 * 0x1p18, 1e4, 0.0, 0.0};
    return log_spline_eval(&rrt, x);
}

/* ODT tone scale (segmented spline c9, ODT_48nits): anchors are the RRT's outputs for grey at
 * 0.18 * 2^-6.5, 0.18 and 0.18 * 2^6.5, mapped to 0.02, 4.8 and 48 cd/m^2. */
static const double odt_low[10] = {-1.6989700043, -1.6989700043, -1.4779000000, -1.2291000000, -0.8648000000,
                                   -0.4480000000, 0.0051800000,  0.4511080334,  0.9113744414,  0.9113744414};
static const double odt_high[10] = {0.5154386965, 0.8470437783, 1.1358000000, 1.3802000000, 1.5197000000,
                                    1.5985000000, 1.6467000000, 1.6746091357, 1.6878733390, 1.6878733390};

static double odt_tonescale(double oces)
{
    const log_spline odt = {odt_low, odt_high, 8, 8,
                            rrt_tonescale(0.18 * pow(2.0, -6.5)), 0.02,
                            rrt_tonescale(0.18), 4.8,
                            rrt_tonescale(0.18 * pow(2.0, 6.5)), 48.0,
                            0.0, 0.04};
    return log_spline_eval(&odt, oces);
}

double sol_aces_reference(double x)
{
    if (isnan(x))
        return x;
    const double cinema_black = 0.02, cinema_white = 48.0, dim_surround_gamma = 0.9811;
    double luminance = odt_tonescale(rrt_tonescale(isinf(x) ? 65504.0 : x));
    double linear_cv = (luminance - cinema_black) / (cinema_white - cinema_black);
    double y = pow(fmax(linear_cv, 0.0), dim_surround_gamma); /* dim surround acts on Y only */
    return y < 1.0 ? y : 1.0;
}

/* Stephen Hill's fit of the ACES RRT + sRGB ODT ("ACESFitted", BakingLab's ACES.hlsl, 2016, as
 * published with Hill's MJP BakingLab sample; written here from the published formula): input
 * matrix (sRGB -> XYZ -> D65-to-D60 -> AP1 -> RRT saturation), the rational RRTAndODTFit per
 * channel, output matrix (ODT saturation -> XYZ -> D60-to-D65 -> sRGB), clamp to [0, 1]. */
static const double hill_in[9] = {0.59719, 0.35458, 0.04823, 0.07600, 0.90834, 0.01566, 0.02840, 0.13383, 0.83777};
static const double hill_out[9] = {1.60475, -0.53108, -0.07367, -0.10208, 1.10813, -0.00605, -0.00327, -0.07276, 1.07602};

double sol_aces_hill_curve(double v)
{
    if (isnan(v))
        return v;
    /* Past |v| = 1e15 the curve equals its limit 1 / 0.983729 to double precision; clamping there
     * keeps v * v finite (1e200 would give Inf / Inf). */
    v = v > 1e15 ? 1e15 : v < -1e15 ? -1e15 : v;
    double a = v * (v + 0.0245786) - 0.000090537, b = v * (0.983729 * v + 0.4329510) + 0.238081;
    return a / b; /* b >= 0.1904 for every v (the quadratic's minimum, at v = -0.22) */
}

void sol_aces_hill_fit(const double rgb[3], double out[3])
{
    double t[3], u[3];
    for (int i = 0; i < 3; ++i) {
        double x = hill_in[3 * i] * rgb[0] + hill_in[3 * i + 1] * rgb[1] + hill_in[3 * i + 2] * rgb[2];
        if (!isfinite(x)) /* overflow of huge finite inputs: only the sign matters (the curve is at its
                           * limit past 1e15), so redo the sum scaled by 2^-1000 */
            x = hill_in[3 * i] * ldexp(rgb[0], -1000) + hill_in[3 * i + 1] * ldexp(rgb[1], -1000) +
                hill_in[3 * i + 2] * ldexp(rgb[2], -1000);
        t[i] = sol_aces_hill_curve(x);
    }
    for (int i = 0; i < 3; ++i) {
        u[i] = hill_out[3 * i] * t[0] + hill_out[3 * i + 1] * t[1] + hill_out[3 * i + 2] * t[2];
        u[i] = isnan(u[i]) ? u[i] : u[i] < 0.0 ? 0.0 : u[i] > 1.0 ? 1.0 : u[i];
    }
    for (int i = 0; i < 3; ++i)
        out[i] = u[i];
}
