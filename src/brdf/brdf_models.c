/* brdf_models.c - Phong, Blinn-Phong, Ward and Cook-Torrance BRDFs (claims D8, D14, D15). */
#include <math.h>

#include "sol_brdf.h"

static double clamp01(double x)
{
    if (isnan(x))
        return x;
    return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
}

void sol_reflect(const double v[3], const double n[3], double r[3])
{
    double d = 2.0 * sol_dot3(n, v);
    for (int i = 0; i < 3; ++i)
        r[i] = d * n[i] - v[i];
}

double sol_phong_raw(double r_dot_l, double n)
{
    double c = clamp01(r_dot_l);
    if (isnan(c) || isnan(n))
        return NAN;
    if (c == 0.0) /* pow(0, 0) would give 1 below the horizon */
        return 0.0;
    return pow(c, n > 0.0 ? n : 0.0);
}

/* Lewis 1994: with r = normal, the integral of (r.l)^n cos over the hemisphere is 2 pi / (n + 2). */
double sol_phong_norm_factor(double n)
{
    return ((n > 0.0 ? n : 0.0) + 2.0) / (2.0 * M_PI);
}

/* The integral of (r.l)^n over the hemisphere around r is 2 pi / (n + 1). */
double sol_phong_lobe_norm_factor(double n)
{
    return ((n > 0.0 ? n : 0.0) + 1.0) / (2.0 * M_PI);
}

double sol_phong_normalized(double r_dot_l, double n)
{
    return sol_phong_norm_factor(n) * sol_phong_raw(r_dot_l, n);
}

double sol_blinn_phong_raw(double n_dot_h, double n)
{
    return sol_phong_raw(n_dot_h, n);
}

/* Giesen 2009: for v = normal, theta_h = theta_l / 2 and the hemisphere integral of
 * cos^n(theta_l / 2) cos(theta_l) is 8 pi (2^(-n/2) + n) / ((n + 2)(n + 4)). */
double sol_blinn_phong_norm_factor_exact(double n)
{
    n = n > 0.0 ? n : 0.0;
    return (n + 2.0) * (n + 4.0) / (8.0 * M_PI * (exp2(-0.5 * n) + n));
}

double sol_blinn_phong_norm_factor_approx(double n)
{
    return ((n > 0.0 ? n : 0.0) + 8.0) / (8.0 * M_PI);
}

/* The exponent -tan^2(th)(cos^2 ph / ax^2 + sin^2 ph / ay^2) written in Cartesian components. */
static double ward_exponent(const double h[3], double ax, double ay)
{
    double sx = h[0] / ax, sy = h[1] / ay;
    return -(sx * sx + sy * sy) / (h[2] * h[2]);
}

double sol_ward_ndf(const double h[3], double alpha_x, double alpha_y)
{
    if (isnan(h[0]) || isnan(h[1]) || isnan(h[2]) || isnan(alpha_x) || isnan(alpha_y))
        return NAN;
    if (!(h[2] > 0.0) || !(alpha_x > 0.0) || !(alpha_y > 0.0))
        return 0.0;
    double e = ward_exponent(h, alpha_x, alpha_y);
    if (e < -700.0) /* exp underflows long before cos^4 does */
        return 0.0;
    double c2 = h[2] * h[2];
    return exp(e) / (M_PI * alpha_x * alpha_y * c2 * c2);
}

static int any_nan(const double a[3], const double b[3])
{
    return isnan(a[0]) || isnan(a[1]) || isnan(a[2]) || isnan(b[0]) || isnan(b[1]) || isnan(b[2]);
}

static int half_vector(const double v[3], const double l[3], double h[3])
{
    double s[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double len = sqrt(sol_dot3(s, s));
    if (!(len > 0.0))
        return 0;
    for (int i = 0; i < 3; ++i)
        h[i] = s[i] / len;
    return 1;
}

double sol_ward_brdf(const double v[3], const double l[3], double alpha_x, double alpha_y)
{
    double h[3];
    if (any_nan(v, l) || isnan(alpha_x) || isnan(alpha_y))
        return NAN;
    if (!(v[2] > 0.0) || !(l[2] > 0.0) || !(alpha_x > 0.0) || !(alpha_y > 0.0) || !half_vector(v, l, h))
        return 0.0;
    if (!(h[2] > 0.0))
        return 0.0;
    double e = ward_exponent(h, alpha_x, alpha_y);
    if (e < -700.0)
        return 0.0;
    return exp(e) / (4.0 * M_PI * alpha_x * alpha_y * sqrt(v[2] * l[2]));
}

double sol_beckmann_ndf(double n_dot_h, double alpha)
{
    if (isnan(n_dot_h) || isnan(alpha))
        return NAN;
    double c = clamp01(n_dot_h);
    if (!(c > 0.0) || !(alpha > 0.0))
        return 0.0;
    double c2 = c * c, t2 = (1.0 - c2) / c2;
    double e = -t2 / (alpha * alpha);
    if (e < -700.0)
        return 0.0;
    return exp(e) / (M_PI * alpha * alpha * c2 * c2);
}

/* Walter et al. 2007 eq. 33, written as alpha^2 / (pi (alpha^2 c^2 + s^2)^2): no 1 - c^2 cancellation
 * at the peak for tiny alpha. */
double sol_ggx_ndf(double n_dot_h, double alpha)
{
    if (isnan(n_dot_h) || isnan(alpha))
        return NAN;
    double c = clamp01(n_dot_h);
    if (!(c > 0.0) || !(alpha > 0.0))
        return 0.0;
    double a2 = alpha * alpha, c2 = c * c;
    double d = a2 * c2 + (1.0 - c) * (1.0 + c);
    return a2 / (M_PI * d * d);
}

/* Walter et al. 2007 eq. 34. */
double sol_smith_g1_ggx(double n_dot_v, double alpha)
{
    if (isnan(n_dot_v) || isnan(alpha))
        return NAN;
    double c = clamp01(n_dot_v);
    if (!(c > 0.0))
        return 0.0;
    double a2 = alpha * alpha;
    return 2.0 * c / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

/* Walter et al. 2007 eq. 27 (rational fit to Smith's Beckmann G1). */
double sol_smith_g1_beckmann(double n_dot_v, double alpha)
{
    if (isnan(n_dot_v) || isnan(alpha))
        return NAN;
    double c = clamp01(n_dot_v);
    if (!(c > 0.0))
        return 0.0;
    if (!(alpha > 0.0))
        return 1.0;
    double a = c / (alpha * sqrt((1.0 - c) * (1.0 + c)));
    if (!(a < 1.6)) /* also a = inf at normal incidence */
        return 1.0;
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

double sol_fresnel_schlick(double f0, double v_dot_h)
{
    double m = 1.0 - clamp01(v_dot_h);
    double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;
}

double sol_cook_torrance(const double v[3], const double l[3], sol_ndf_kind ndf, double alpha, double f0)
{
    double h[3];
    if (any_nan(v, l) || isnan(alpha) || isnan(f0))
        return NAN;
    if (!(v[2] > 0.0) || !(l[2] > 0.0) || !half_vector(v, l, h))
        return 0.0;
    double d, g;
    if (ndf == SOL_NDF_BECKMANN) {
        d = sol_beckmann_ndf(h[2], alpha);
        g = sol_smith_g1_beckmann(v[2], alpha) * sol_smith_g1_beckmann(l[2], alpha);
    } else {
        d = sol_ggx_ndf(h[2], alpha);
        g = sol_smith_g1_ggx(v[2], alpha) * sol_smith_g1_ggx(l[2], alpha);
    }
    double f = sol_fresnel_schlick(f0, sol_dot3(v, h));
    return d * g * f / (4.0 * v[2] * l[2]);
}
