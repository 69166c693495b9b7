/* brdf_models.c - Phong, Blinn-Phong, Ward and Cook-Torrance BRDFs (claims D8, D14, D15). */
#include <float.h>
#include <math.h>

#include "sol_brdf.h"

/* Values above DBL_MAX (a delta-like lobe: alpha -> 0, n -> inf) saturate to DBL_MAX, so every
 * non-NaN input keeps a finite answer. */
static double saturate(double x)
{
    return x > DBL_MAX ? DBL_MAX : x;
}

/* exp(e - log_den) saturated: the scaled form of exp(e) / den when den under- or overflows. */
static double exp_minus_log(double e, double log_den)
{
    double l = e - log_den;
    if (isnan(l))
        return l;
    return l > log(DBL_MAX) ? DBL_MAX : exp(l);
}

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
    return pow(c, n > 0.0 ? n : 0.0); /* pow(c < 1, inf) = 0, pow(1, inf) = 1 */
}

/* Lewis 1994: with r = normal, the integral of (r.l)^n cos over the hemisphere is 2 pi / (n + 2). */
double sol_phong_norm_factor(double n)
{
    return saturate(((n > 0.0 ? n : 0.0) + 2.0) / (2.0 * M_PI));
}

/* The integral of (r.l)^n over the hemisphere around r is 2 pi / (n + 1). */
double sol_phong_lobe_norm_factor(double n)
{
    return saturate(((n > 0.0 ? n : 0.0) + 1.0) / (2.0 * M_PI));
}

double sol_phong_normalized(double r_dot_l, double n)
{
    double raw = sol_phong_raw(r_dot_l, n);
    return raw == 0.0 ? 0.0 : saturate(sol_phong_norm_factor(n) * raw); /* no DBL_MAX * 0 */
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
    if (isinf(n))
        return DBL_MAX;
    /* (n+2)/(8 pi) * (n+4)/(2^(-n/2) + n): the product (n+2)(n+4) overflows from n ~ 1.3e154 */
    return (n + 2.0) / (8.0 * M_PI) * ((n + 4.0) / (exp2(-0.5 * n) + n));
}

double sol_blinn_phong_norm_factor_approx(double n)
{
    return saturate(((n > 0.0 ? n : 0.0) + 8.0) / (8.0 * M_PI));
}

/* The exponent -tan^2(th)(cos^2 ph / ax^2 + sin^2 ph / ay^2) written in Cartesian components. */
static double ward_exponent(const double h[3], double ax, double ay)
{
    double sx = h[0] / ax, sy = h[1] / ay, num = sx * sx + sy * sy;
    return num == 0.0 ? 0.0 : -num / (h[2] * h[2]); /* 0 / 0 when h.z^2 underflows at the peak */
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
    double c2 = h[2] * h[2], den = M_PI * alpha_x * alpha_y * c2 * c2;
    if (den >= DBL_MIN && den <= DBL_MAX)
        return saturate(exp(e) / den);
    return exp_minus_log(e, log(M_PI) + log(alpha_x) + log(alpha_y) + 4.0 * log(h[2])); /* scaled */
}

static int any_nan(const double a[3], const double b[3])
{
    return isnan(a[0]) || isnan(a[1]) || isnan(a[2]) || isnan(b[0]) || isnan(b[1]) || isnan(b[2]);
}

static int half_vector(const double v[3], const double l[3], double h[3])
{
    double s[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double len = sqrt(sol_dot3(s, s));
    if (!(len > 1e-150 && len < 1e150)) { /* |s|^2 under- or overflowed: scale by the largest component */
        double m = fmax(fmax(fabs(0.5 * v[0] + 0.5 * l[0]), fabs(0.5 * v[1] + 0.5 * l[1])), fabs(0.5 * v[2] + 0.5 * l[2]));
        if (!(m > 0.0) || isinf(m))
            return 0;
        for (int i = 0; i < 3; ++i)
            s[i] = (0.5 * v[i] + 0.5 * l[i]) / m;
        len = sqrt(sol_dot3(s, s));
    }
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
    double den = 4.0 * M_PI * alpha_x * alpha_y * sqrt(v[2] * l[2]);
    if (den >= DBL_MIN && den <= DBL_MAX)
        return saturate(exp(e) / den);
    return exp_minus_log(e, log(4.0 * M_PI) + log(alpha_x) + log(alpha_y) + 0.5 * (log(v[2]) + log(l[2])));
}

double sol_beckmann_ndf(double n_dot_h, double alpha)
{
    if (isnan(n_dot_h) || isnan(alpha))
        return NAN;
    double c = clamp01(n_dot_h);
    if (!(c > 0.0) || !(alpha > 0.0))
        return 0.0;
    /* (1 - c)(1 + c), not 1 - c^2: no cancellation near the peak (alpha < 1e-4) */
    double c2 = c * c, t2 = (1.0 - c) * (1.0 + c) / c2, a2 = alpha * alpha;
    double den = M_PI * a2 * c2 * c2;
    if (a2 >= DBL_MIN && den >= DBL_MIN && den <= DBL_MAX) {
        double e = -t2 / a2;
        if (e < -700.0)
            return 0.0;
        return saturate(exp(e) / den);
    }
    /* alpha^2 or the denominator under- or overflows (alpha <~ 1e-154 or >~ 1e154, or a grazing
     * h): exponent as -(tan / alpha)^2 and the denominator in logs */
    double t = sqrt((1.0 - c) * (1.0 + c)) / alpha / c; /* alpha = Inf, c subnormal: 0, not Inf/Inf */
    return exp_minus_log(-(t * t), log(M_PI) + 2.0 * log(alpha) + 4.0 * log(c));
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
    if (a2 >= DBL_MIN && a2 <= DBL_MAX && d * d >= DBL_MIN)
        return saturate(a2 / (M_PI * d * d));
    /* scaled for alpha^2 or d^2 out of range: D = 1 / (pi u^2), u = d / alpha = alpha c^2 + s^2 / alpha */
    double s = sqrt((1.0 - c) * (1.0 + c));
    double r = 1.0 / (alpha * c * c + s * (s / alpha)); /* u = 0 only if the true D is past DBL_MAX */
    return saturate(r * (r / M_PI));
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
    if (a2 > 1.0) /* a2 + (1 - a2) c^2 cancels (inf - inf at alpha > 1e154): sqrt(alpha^2 s^2 + c^2) */
        return 2.0 * c / (c + hypot(c < 1.0 ? alpha * sqrt((1.0 - c) * (1.0 + c)) : 0.0, c));
    return 2.0 * c / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

/* G1(c) / c for the Cook-Torrance denominator, finite at c -> 0 (grazing). */
static double ggx_g1_over_cos(double c, double alpha)
{
    double a2 = alpha * alpha;
    if (a2 > 1.0)
        return 2.0 / (c + hypot(c < 1.0 ? alpha * sqrt((1.0 - c) * (1.0 + c)) : 0.0, c));
    return 2.0 / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

static double beckmann_g1_over_cos(double c, double alpha)
{
    if (!(alpha > 0.0))
        return 1.0 / c;
    double s = sqrt((1.0 - c) * (1.0 + c)), a = c / (alpha * s);
    if (!(a < 1.6))
        return 1.0 / c;
    /* G1 = a (3.535 + 2.181 a) / (...) and a / c = 1 / (alpha s) */
    return (3.535 + 2.181 * a) / (1.0 + 2.276 * a + 2.577 * a * a) / (alpha * s);
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
    if (isinf(f0)) { /* f0 + (1 - f0) m^5 = f0 (1 - m^5) + m^5 would be inf - inf */
        double m = 1.0 - clamp01(v_dot_h);
        if (isnan(m))
            return NAN;
        return m == 1.0 ? 1.0 : (f0 > 0.0 ? DBL_MAX : -DBL_MAX);
    }
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
    double den = 4.0 * v[2] * l[2], r = d * g * f / den;
    if (den >= DBL_MIN && isfinite(r) && d < DBL_MAX)
        return r;
    /* grazing v, l (v.z l.z underflows; e.g. v = l at the horizon) or a saturated D: the same
     * value as D F (G1(v) / v.z) (G1(l) / l.z) / 4, which stays finite */
    if (d == 0.0 || f == 0.0)
        return 0.0;
    if (d == DBL_MAX) /* D itself saturated (alpha -> 0 at the peak): so does the BRDF */
        return f > 0.0 ? DBL_MAX : -DBL_MAX;
    double cv = clamp01(v[2]), cl = clamp01(l[2]);
    double gv = ndf == SOL_NDF_BECKMANN ? beckmann_g1_over_cos(cv, alpha) : ggx_g1_over_cos(cv, alpha);
    double gl = ndf == SOL_NDF_BECKMANN ? beckmann_g1_over_cos(cl, alpha) : ggx_g1_over_cos(cl, alpha);
    r = d * f / 4.0 * gv * gl;
    return r > DBL_MAX ? DBL_MAX : r < -DBL_MAX ? -DBL_MAX : r;
}
