/* dfg.c - S4: the split-sum DFG term (Karis 2013) by deterministic quadrature, a bilinear lookup
 * table of it, and Narkowicz's two published analytical fits ("Analytical DFG Term for IBL", 2014,
 * seed 001): the polynomial fit and his GGX refit of Lazarov 2013's form. The fits are evaluated
 * with the constants as published: those constants are the claim under test. */
#include "sol_lighting.h"

#include <stdlib.h>

static int in_unit_interval(double x)
{
    return x >= 0.0 && x <= 1.0;
}

static sol_status check_unit_pair(double a, double b)
{
    if (!isfinite(a) || !isfinite(b))
        return SOL_ERR_NONFINITE;
    if (!in_unit_interval(a) || !in_unit_interval(b))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

static double saturate(double x)
{
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

double sol_dfg_alpha_from_gloss(double gloss)
{
    if (isnan(gloss))
        return gloss;
    double r = 1.0 - saturate(gloss);
    return (r * r) * (r * r);
}

/* Separable Smith term for GGX folded with 1/(4 n.v n.l): G / (4 n.v n.l) = 1 / (vis(v) vis(l)),
 * vis(c) = c + sqrt(alpha^2 + (1 - alpha^2) c^2) (hypot: no underflow for denormal c). */
static double smith_vis_factor(double alpha, double c)
{
    return c + hypot(alpha, sqrt(1.0 - alpha * alpha) * c);
}

/* GGX half-vector CDF in theta_h: the e with cos^2(theta_h) = (1 - e) / (1 + (alpha^2 - 1) e). */
static double ggx_cdf_at(double alpha2, double theta_h)
{
    double c2 = cos(theta_h) * cos(theta_h);
    if (c2 >= 1.0)
        return 0.0; /* theta_h = 0; also avoids 0/0 when alpha = 0 */
    return (1.0 - c2) / (1.0 + c2 * (alpha2 - 1.0));
}

/* Midpoint quadrature of scale and bias over the half vectors with CDF value e in [e0, e1]
 * (rows) and, per row, the azimuths where n.l > 0 (columns). */
static void integrate_band(double alpha, double vx, double vz, double e0, double e1, int samples, double out[2])
{
    const double alpha2 = alpha * alpha, vis_v = smith_vis_factor(alpha, vz);
    double sum_scale = 0.0, sum_bias = 0.0, sum_de = 0.0;
    for (int j = 0; j < samples; ++j) {
        /* e = e0 + (e1 - e0) (3 s^2 - 2 s^3) clusters rows at both ends: at e0 the azimuth range
         * starts to shrink like a square root, and near e = 1 (theta_h -> 90 degrees, reached at
         * grazing n.v) the importance weight grows like 1 / cos(theta_h) ~ 1 / sqrt(1 - e). Both
         * would make the plain midpoint rule converge slowly; de = 6 s (1 - s) (e1 - e0) ds. */
        double s = (j + 0.5) / samples, e = e0 + (e1 - e0) * s * s * (3.0 - 2.0 * s);
        double de = 6.0 * s * (1.0 - s);
        sum_de += de;
        double cos_h = sqrt((1.0 - e) / (1.0 + (alpha2 - 1.0) * e));
        double sin_h = sqrt(fmax(0.0, 1.0 - cos_h * cos_h));
        /* n.l = 2 (v.h) cos_h - n.v > 0 holds for |phi| < phi_max: integrating phi over exactly that
         * interval keeps the cut-off at the interval's end, where the midpoint rule stays second
         * order (a cut inside the interval would make it first order). n.l > 0 implies v.h > 0. */
        double denom = 2.0 * vx * sin_h * cos_h, numer = vz * (1.0 - 2.0 * cos_h * cos_h);
        double c = denom > 0.0 ? numer / denom : (numer < 0.0 ? -2.0 : 2.0);
        if (c >= 1.0)
            continue;
        double phi_max = c <= -1.0 ? M_PI : acos(c);
        double row_scale = 0.0, row_bias = 0.0;
        for (int i = 0; i < samples; ++i) {
            /* phi = phi_max (1 - t^2) clusters samples at the cut-off, where n.l -> 0 and the Smith
             * term turns over sharply (within n.l ~ alpha) at grazing view angles; dphi = 2 t dt. */
            double t = (i + 0.5) / samples, phi = phi_max * (1.0 - t * t);
            double v_dot_h = vx * sin_h * cos(phi) + vz * cos_h;
            double n_dot_l = 2.0 * v_dot_h * cos_h - vz;
            if (n_dot_l <= 0.0 || v_dot_h <= 0.0)
                continue; /* rounding at the interval's end */
            /* f n.l / pdf with pdf(l) = D n.h / (4 v.h): the D cancels. */
            /* Grouped as ratios of like magnitudes so denormal n.v cannot give 0/0. */
            double weight = (n_dot_l / smith_vis_factor(alpha, n_dot_l)) * (4.0 * v_dot_h / (cos_h * vis_v));
            double m = 1.0 - v_dot_h, fc = (m * m) * (m * m) * m;
            row_scale += 2.0 * t * weight * (1.0 - fc);
            row_bias += 2.0 * t * weight * fc;
        }
        /* The row averages phi over [-pi, pi]: the symmetric interval is 2 phi_max of 2 pi. */
        sum_scale += de * row_scale * (phi_max / M_PI);
        sum_bias += de * row_bias * (phi_max / M_PI);
    }
    /* Dividing by the rule's own sum of de (not its exact integral, samples) keeps a constant
     * integrand exact, e.g. the mirror limit alpha = 0 where DFG is exactly Fresnel. The azimuth
     * weights 2 t sum to exactly `samples`. */
    double n = (double)samples * sum_de;
    out[0] = n > 0.0 ? sum_scale * (e1 - e0) / n : 0.0;
    out[1] = n > 0.0 ? sum_bias * (e1 - e0) / n : 0.0;
}

sol_status sol_dfg_integrate(double alpha, double n_dot_v, int samples, double *scale, double *bias)
{
    if (!scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(alpha, n_dot_v);
    if (st != SOL_OK)
        return st;
    if (samples < 1 || samples > 65536)
        return SOL_ERR_INVALID_ARG;
    const double alpha2 = alpha * alpha;
    const double vx = sqrt(1.0 - n_dot_v * n_dot_v);
    /* n.l > 0 for every azimuth of h below theta_start and for none above theta_end (h must stay
     * within 45 degrees of the bisector of v and the horizon): the integrand's kinks are there. */
    const double theta_v = acos(n_dot_v);
    const double e_start = ggx_cdf_at(alpha2, 0.25 * M_PI - 0.5 * theta_v);
    const double e_end = ggx_cdf_at(alpha2, 0.25 * M_PI + 0.5 * theta_v);
    double full[2], partial[2];
    integrate_band(alpha, vx, n_dot_v, 0.0, e_start, samples, full);
    integrate_band(alpha, vx, n_dot_v, e_start, e_end, samples, partial);
    *scale = full[0] + partial[0];
    *bias = full[1] + partial[1];
    return SOL_OK;
}

sol_status sol_dfg_fit_polynomial(double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    const double x = gloss, y = n_dot_v;
    /* Narkowicz 2014, EnvDFGPolynomial: bias = min of an x-polynomial and a y-polynomial. */
    double b = saturate(fmin(-0.1688 * x + 1.895 * x * x, 0.9903 - 4.853 * y + 8.404 * y * y - 5.069 * y * y * y));
    double delta = saturate(0.6045 + 1.699 * x - 0.5228 * y - 3.603 * x * x + 1.404 * x * y + 0.1939 * y * y +
                            2.661 * x * x * x);
    *scale = delta - b;
    *bias = b;
    return SOL_OK;
}

sol_status sol_dfg_fit_lazarov(double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    /* Narkowicz 2014, EnvDFGLazarov: t = gloss * p0 + p1 with his GGX-refitted p0, p1. */
    double tx = 0.5745 * gloss + 0.5753, ty = 1.548 * gloss - 0.2511;
    double tz = -0.02397 * gloss - 0.02066, tw = 1.301 * gloss + 0.4755;
    double b = saturate(tx * fmin(ty, exp2(-7.672 * n_dot_v)) + tz);
    *scale = saturate(tw) - b;
    *bias = b;
    return SOL_OK;
}

sol_status sol_dfg_lut_build(int size, int samples, sol_dfg_lut *out)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if (size < 2 || size > 4096 || samples < 1 || samples > 65536)
        return SOL_ERR_INVALID_ARG;
    float *data = malloc(sizeof *data * 2u * (size_t)size * (size_t)size);
    if (!data)
        return SOL_ERR_NO_MEMORY;
    /* Each texel is independent and written once: the result does not depend on thread count. */
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double s = 0.0, b = 0.0;
            double alpha = sol_dfg_alpha_from_gloss((x + 0.5) / size);
            (void)sol_dfg_integrate(alpha, (y + 0.5) / size, samples, &s, &b); /* arguments are valid */
            data[2 * ((size_t)y * (size_t)size + (size_t)x) + 0] = (float)s;
            data[2 * ((size_t)y * (size_t)size + (size_t)x) + 1] = (float)b;
        }
    out->size = size;
    out->scale_bias = data;
    return SOL_OK;
}

/* Texel coordinate of u in [0,1] for a clamp-to-edge bilinear fetch: lower index and weight. */
static void bilinear_coordinate(double u, int size, int *i0, double *t)
{
    double p = u * size - 0.5;
    if (p <= 0.0) {
        *i0 = 0;
        *t = 0.0;
    } else if (p >= size - 1) {
        *i0 = size - 2;
        *t = 1.0;
    } else {
        *i0 = (int)p;
        *t = p - *i0;
    }
}

sol_status sol_dfg_lut_sample(const sol_dfg_lut *lut, double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!lut || !scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    if (!lut->scale_bias || lut->size < 2)
        return SOL_ERR_INVALID_ARG;
    int x0, y0;
    double tx, ty;
    bilinear_coordinate(gloss, lut->size, &x0, &tx);
    bilinear_coordinate(n_dot_v, lut->size, &y0, &ty);
    const float *row0 = lut->scale_bias + 2 * (size_t)y0 * (size_t)lut->size;
    const float *row1 = row0 + 2 * (size_t)lut->size;
    double out[2];
    for (int c = 0; c < 2; ++c) {
        double top = row0[2 * x0 + c] + tx * (row0[2 * x0 + 2 + c] - row0[2 * x0 + c]);
        double bottom = row1[2 * x0 + c] + tx * (row1[2 * x0 + 2 + c] - row1[2 * x0 + c]);
        out[c] = top + ty * (bottom - top);
    }
    *scale = out[0];
    *bias = out[1];
    return SOL_OK;
}

void sol_dfg_lut_free(sol_dfg_lut *lut)
{
    if (!lut)
        return;
    free(lut->scale_bias);
    lut->scale_bias = NULL;
    lut->size = 0;
}
