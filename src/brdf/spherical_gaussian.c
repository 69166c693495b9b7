/* spherical_gaussian.c - Spherical Gaussian algebra (Wang et al. 2009) and anisotropic SGs (Xu et al.
 * 2013), stable for sharpness from 0 to 1e6 and beyond (claims D15, D16). */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <string.h>

#include "sol_brdf.h"

/* |a - b|^2 / 2 equals 1 - a.b for unit vectors without the cancellation near a = b. */
static double one_minus_dot(const double a[3], const double b[3])
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return 0.5 * (d0 * d0 + d1 * d1 + d2 * d2);
}

double sol_sg_eval(const sol_sg *g, const double v[3])
{
    double d = one_minus_dot(g->axis, v);
    if (d == 0.0 && !isnan(g->sharpness)) /* v on the axis: exp(0) = 1 even for sharpness = Inf */
        return g->amplitude;
    double r = g->amplitude * exp(-g->sharpness * d);
    return isinf(r) ? copysign(DBL_MAX, r) : r; /* a negative sharpness can overflow: saturate */
}

/* Integral of exp(lambda (mu.v - 1)) over the sphere: 2 pi (1 - exp(-2 lambda)) / lambda. */
static double unit_sg_integral(double lambda)
{
    if (!(lambda > 0.0))
        return isnan(lambda) ? NAN : 4.0 * M_PI;
    return 2.0 * M_PI * -expm1(-2.0 * lambda) / lambda;
}

double sol_sg_integral(const sol_sg *g)
{
    return g->amplitude * unit_sg_integral(g->sharpness);
}

/* The product's sharpness and the log of its amplitude factor exp(lm - l1 - l2), the latter as
 * -l1 l2 |mu1 - mu2|^2 / (l1 + l2 + lm): never positive, no cancellation. */
static double product_parts(const sol_sg *a, const sol_sg *b, double axis[3], double *log_factor)
{
    double s[3];
    for (int i = 0; i < 3; ++i)
        s[i] = a->sharpness * a->axis[i] + b->sharpness * b->axis[i];
    double lm = sqrt(sol_dot3(s, s));
    for (int i = 0; i < 3; ++i)
        axis[i] = lm > 0.0 ? s[i] / lm : a->axis[i];
    double denom = a->sharpness + b->sharpness + lm;
    *log_factor = denom > 0.0 ? -a->sharpness * (b->sharpness / denom) * 2.0 * one_minus_dot(a->axis, b->axis) : 0.0;
    return lm;
}

sol_sg sol_sg_product(const sol_sg *a, const sol_sg *b)
{
    sol_sg p;
    double log_factor;
    p.sharpness = product_parts(a, b, p.axis, &log_factor);
    p.amplitude = a->amplitude * b->amplitude * exp(log_factor);
    return p;
}

double sol_sg_inner_product(const sol_sg *a, const sol_sg *b)
{
    double axis[3], log_factor;
    double lm = product_parts(a, b, axis, &log_factor);
    return a->amplitude * b->amplitude * exp(log_factor) * unit_sg_integral(lm);
}

/* The integral of a spherical convolution is the product of the integrals; the amplitude is set so
 * that this holds exactly, which reduces to Wang et al.'s 2 pi a1 a2 / (l1 + l2) for narrow lobes
 * and stays finite when both sharpnesses are 0. */
sol_sg sol_sg_convolve(const sol_sg *a, const sol_sg *b)
{
    sol_sg c;
    memcpy(c.axis, a->axis, sizeof c.axis);
    double sum = a->sharpness + b->sharpness;
    c.sharpness = sum > 0.0 ? a->sharpness * (b->sharpness / sum) : 0.0;
    c.amplitude = sol_sg_integral(a) * sol_sg_integral(b) / unit_sg_integral(c.sharpness);
    return c;
}

/* Azimuthal integral of max(A + B cos phi, 0) over [0, 2 pi], B >= 0 (closed form). */
static double clamped_azimuthal(double A, double B)
{
    if (A >= B)
        return 2.0 * M_PI * A;
    if (A <= -B)
        return 0.0;
    double q = -A / B;
    return 2.0 * (A * acos(q) + B * sqrt((1.0 - q) * (1.0 + q)));
}

/* In polar coordinates (t, phi) about the SG axis the integral is
 * a * int_0^pi exp(-lambda (1 - cos t)) P(t) sin t dt, P the closed-form azimuthal integral. P has
 * kinks where |A| = B (t1 and pi - t1), which become breakpoints; the exponential is cut where it
 * falls below e^-52 (relative 3e-23), and the rest is split into 12 equal pieces of 24-point
 * Gauss-Legendre, enough for a Gaussian-like factor over any width. */
/* The 24-point Gauss-Legendre rule of sol_sg_cosine_convolve, computed once (thread-safe): the
 * function is called per lobe per pixel (D16 lobe culling, the scene renderer), and rebuilding the
 * nodes by Newton iteration on every call cost about as much as the quadrature itself. */
enum { CONVOLVE_ORDER = 24 };
static double convolve_x[CONVOLVE_ORDER], convolve_w[CONVOLVE_ORDER];
static pthread_once_t convolve_once = PTHREAD_ONCE_INIT;

static void convolve_rule_init(void)
{
    sol_gauss_legendre(CONVOLVE_ORDER, convolve_x, convolve_w); /* order in range: cannot fail */
}

double sol_sg_cosine_convolve(const sol_sg *g, const double n[3])
{
    double c = sol_dot3(g->axis, n);
    if (isnan(c) || isnan(g->sharpness) || isnan(g->amplitude))
        return NAN;
    c = c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c);
    double s = sqrt(one_minus_dot(g->axis, n) * (1.0 + c)); /* sin of the axis-normal angle */
    if (s > 1.0)
        s = 1.0;
    double lambda = g->sharpness > 0.0 ? g->sharpness : 0.0;
    double t_max = lambda > 26.0 ? 2.0 * asin(sqrt(26.0 / lambda)) : M_PI; /* 1 - cos t = 52 / lambda */
    double t1 = atan2(fabs(c), s);
    double kinks[2] = {t1, M_PI - t1};
    enum { PIECES = 12, ORDER = CONVOLVE_ORDER };
    double breaks[PIECES + 3];
    int nb = 0, k = 0;
    for (int i = 0; i <= PIECES; ++i) {
        double b = t_max * i / PIECES;
        while (k < 2 && kinks[k] < b) {
            if (kinks[k] > 0.0 && (nb == 0 || kinks[k] > breaks[nb - 1]))
                breaks[nb++] = kinks[k];
            ++k;
        }
        if (nb == 0 || b > breaks[nb - 1])
            breaks[nb++] = b;
    }
    pthread_once(&convolve_once, convolve_rule_init);
    const double *x = convolve_x, *w = convolve_w;
    double sum = 0.0;
    for (int i = 0; i + 1 < nb; ++i) {
        double mid = 0.5 * (breaks[i] + breaks[i + 1]), half = 0.5 * (breaks[i + 1] - breaks[i]);
        for (int j = 0; j < ORDER; ++j) {
            double t = mid + half * x[j], st = sin(t), ct = cos(t);
            double one_minus_cos = 2.0 * sin(0.5 * t) * sin(0.5 * t);
            sum += w[j] * half * exp(-lambda * one_minus_cos) * clamped_azimuthal(c * ct, s * st) * st;
        }
    }
    return g->amplitude * sum;
}

sol_sg sol_sg_rotate(const sol_sg *g, const double rotation[9])
{
    sol_sg r = *g;
    for (int i = 0; i < 3; ++i)
        r.axis[i] = rotation[3 * i] * g->axis[0] + rotation[3 * i + 1] * g->axis[1] + rotation[3 * i + 2] * g->axis[2];
    return r;
}

double sol_asg_eval(const sol_asg *g, const double v[3])
{
    double z = sol_dot3(g->z, v);
    if (isnan(z))
        return NAN;
    if (!(z > 0.0))
        return 0.0;
    double x = sol_dot3(g->x, v), y = sol_dot3(g->y, v);
    return g->amplitude * z * exp(-g->lambda_x * x * x - g->lambda_y * y * y);
}
