/* tonemap.c - tone maps, their inverses and the HDR lower bound of dynamic range scaling
 * (claims D10, D11, D12, S3).
 *
 * Sources of the curves:
 *  - exponential 1 - exp(-c/l): the talk, slide "HDR on consoles: lower bound estimator";
 *  - filmic: J. Hejl and R. Burgess-Dawson's curve as published by J. Hable ("Uncharted 2: HDR
 *    Lighting", GDC 2010): x' = max(0, x - 0.004), g = x'(6.2x'+0.5)/(x'(6.2x'+1.7)+0.06), g is
 *    gamma-encoded so the linear value is g^2.2 (the talk raises it to 2.2 too);
 *  - the same slide prints the denominator as c'(6.2(c'+1.7)+0.06): kept as its own operator so
 *    that the bound it gives can be reported next to the original curve's;
 *  - ACES fit: K. Narkowicz, "ACES Filmic Tone Mapping Curve" (2016);
 *  - Reinhard: E. Reinhard et al., "Photographic Tone Reproduction", SIGGRAPH 2002 (simple form).
 */
#include "sol_hdr.h"

#include <math.h>

#define FILMIC_TOE 0.004
#define FILMIC_GAMMA 2.2

/* Rational curves are evaluated divided through by x^2 above 1, so huge inputs cannot overflow. */
static double filmic_hbd_encoded(double xp)
{
    if (xp > 1.0)
        return (6.2 + 0.5 / xp) / (6.2 + (1.7 + 0.06 / xp) / xp);
    return xp * (6.2 * xp + 0.5) / (xp * (6.2 * xp + 1.7) + 0.06);
}

/* The slide's printed form: c'(6.2c'+0.5) / (c'(6.2(c'+1.7)+0.06)); c' cancels for c' > 0. */
static double filmic_slide_encoded(double xp)
{
    if (xp > 1.0)
        return (6.2 + 0.5 / xp) / (6.2 + 10.6 / xp);
    return xp > 0.0 ? (6.2 * xp + 0.5) / (6.2 * (xp + 1.7) + 0.06) : 0.0;
}

static double aces_fit(double x)
{
    double y = x > 1.0 ? (2.51 + 0.03 / x) / (2.43 + (0.59 + 0.14 / x) / x)
                       : x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return y < 1.0 ? y : 1.0;
}

const char *sol_tonemap_name(sol_tonemap op)
{
    switch (op) {
    case SOL_TONEMAP_EXPONENTIAL: return "exponential";
    case SOL_TONEMAP_REINHARD: return "reinhard";
    case SOL_TONEMAP_FILMIC_HBD: return "filmic-hbd";
    case SOL_TONEMAP_FILMIC_SLIDE: return "filmic-slide";
    case SOL_TONEMAP_ACES_FIT: return "aces-fit";
    case SOL_TONEMAP_ACES_REF: return "aces-rrt-odt";
    default: return "unknown";
    }
}

double sol_tonemap_apply(sol_tonemap op, double x)
{
    if (isnan(x))
        return x;
    if (!(x > 0.0))
        return 0.0;
    switch (op) {
    case SOL_TONEMAP_EXPONENTIAL: return -expm1(-x);
    case SOL_TONEMAP_REINHARD: return isinf(x) ? 1.0 : x / (1.0 + x);
    case SOL_TONEMAP_FILMIC_HBD:
        return isinf(x) ? 1.0 : pow(filmic_hbd_encoded(fmax(0.0, x - FILMIC_TOE)), FILMIC_GAMMA);
    case SOL_TONEMAP_FILMIC_SLIDE:
        return isinf(x) ? 1.0 : pow(filmic_slide_encoded(fmax(0.0, x - FILMIC_TOE)), FILMIC_GAMMA);
    case SOL_TONEMAP_ACES_FIT: return isinf(x) ? 1.0 : aces_fit(x);
    case SOL_TONEMAP_ACES_REF: return sol_aces_reference(x);
    default: return NAN;
    }
}

/* Largest y an operator's inverse accepts: curves that approach 1 only at infinity exclude 1. */
static int y_in_domain(sol_tonemap op, double y)
{
    if (op == SOL_TONEMAP_ACES_FIT || op == SOL_TONEMAP_ACES_REF)
        return y >= 0.0 && y <= 1.0;
    return y >= 0.0 && y < 1.0;
}

static sol_status check_inverse_args(sol_tonemap op, double y, const double *x)
{
    if (!x)
        return SOL_ERR_NULL_ARG;
    if ((int)op < 0 || op >= SOL_TONEMAP_COUNT)
        return SOL_ERR_INVALID_ARG;
    if (isnan(y))
        return SOL_ERR_NONFINITE;
    if (!y_in_domain(op, y))
        return SOL_ERR_OUT_OF_RANGE;
    return SOL_OK;
}

/* Positive root of a t^2 + b t - c = 0 with a > 0, c >= 0, in the cancellation-free form. */
static double positive_root(double a, double b, double c)
{
    double d = sqrt(b * b + 4.0 * a * c);
    return b >= 0.0 ? 2.0 * c / (b + d) : (d - b) / (2.0 * a);
}

sol_status sol_tonemap_inverse(sol_tonemap op, double y, double *x)
{
    sol_status st = check_inverse_args(op, y, x);
    if (st != SOL_OK)
        return st;
    if (y == 0.0) {
        *x = 0.0;
        return SOL_OK;
    }
    double g = pow(y, 1.0 / FILMIC_GAMMA), slide_floor = filmic_slide_encoded(1e-300);
    /* 1 - g from 1 - y without rounding g to 1 first (y = 1 - 1e-16 gave g = 1 and x = +Inf):
     * 1 - y^(1/2.2) = -expm1(log1p(-(1 - y)) / 2.2); 1 - y is exact for y >= 0.5 */
    double one_minus_g = -expm1(log1p(-(1.0 - y)) / FILMIC_GAMMA);
    switch (op) {
    case SOL_TONEMAP_EXPONENTIAL: *x = -log1p(-y); return SOL_OK;
    case SOL_TONEMAP_REINHARD: *x = y / (1.0 - y); return SOL_OK;
    case SOL_TONEMAP_FILMIC_HBD:
        /* g (x'(6.2x'+1.7)+0.06) = x'(6.2x'+0.5)  <=>  6.2(1-g) x'^2 + (0.5-1.7g) x' - 0.06g = 0 */
        *x = FILMIC_TOE + positive_root(6.2 * one_minus_g, 0.5 - 1.7 * g, 0.06 * g);
        return SOL_OK;
    case SOL_TONEMAP_FILMIC_SLIDE:
        /* g = (6.2x'+0.5)/(6.2x'+10.6) for x' > 0, which never goes below 0.5/10.6: smaller y
         * are first reached just above the toe (the infimum 0.004 is returned). */
        *x = FILMIC_TOE + (g <= slide_floor ? 0.0 : (10.6 * g - 0.5) / (6.2 * one_minus_g));
        return SOL_OK;
    case SOL_TONEMAP_ACES_FIT:
        /* y (2.43x^2+0.59x+0.14) = 2.51x^2+0.03x */
        *x = positive_root(2.51 - 2.43 * y, 0.03 - 0.59 * y, 0.14 * y);
        return SOL_OK;
    default: {
        /* 2200 iterations: bisection alone reaches a relative 1e-14 bracket from [0, 1] down to
         * the subnormals (1074 + 47 halvings), so tiny y (1e-300) converge too */
        sol_root_options tight = {SOL_ROOT_SAFE_NEWTON, 1e-14, 2200};
        return sol_tonemap_inverse_iterative(op, y, &tight, x, NULL);
    }
    }
}

/* f(x) - y, for root finding. */
static double residual(sol_tonemap op, double x, double y)
{
    return sol_tonemap_apply(op, x) - y;
}

/* Safeguarded Newton step inside [lo, hi], central-difference slope; NAN asks for bisection. */
static double newton_step(sol_tonemap op, double x, double fx, double lo, double hi)
{
    double h = 1e-7 * fmax(x, 1e-9), left = fmax(x - h, 0.0);
    double slope = (residual(op, x + h, 0.0) - residual(op, left, 0.0)) / (x + h - left);
    if (!(slope > 0.0))
        return NAN;
    double next = x - fx / slope;
    return next > lo && next < hi ? next : NAN;
}

sol_status sol_tonemap_inverse_iterative(sol_tonemap op, double y, const sol_root_options *options, double *x,
                                         int *iterations)
{
    sol_status st = check_inverse_args(op, y, x);
    if (st != SOL_OK)
        return st;
    sol_root_options opt = options ? *options : (sol_root_options){0};
    double tol = opt.tolerance > 0.0 ? opt.tolerance : 1e-12;
    int max_iter = opt.max_iterations > 0 ? opt.max_iterations : 200;
    double lo = 0.0, hi = 1.0;
    int it = 0;
    if (y == 0.0) {
        *x = 0.0;
        if (iterations)
            *iterations = 0;
        return SOL_OK;
    }
    while (residual(op, hi, y) < 0.0) { /* bracket: f(lo) < y <= f(hi) */
        lo = hi;
        hi *= 2.0;
        if (hi > 1e300)
            return SOL_ERR_OUT_OF_RANGE;
    }
    double guess = 0.5 * (lo + hi);
    /* also stop when no double lies strictly between lo and hi: hi is then the answer (this ends
     * the search when the infimum is 0, e.g. ACES at y = 1e-300, where the relative width never
     * shrinks) */
    while (hi - lo > tol * hi && nextafter(lo, INFINITY) < hi && it < max_iter) {
        double f = residual(op, guess, y);
        if (f < 0.0)
            lo = guess;
        else
            hi = guess;
        ++it;
        double next = opt.method == SOL_ROOT_SAFE_NEWTON ? newton_step(op, guess, f, lo, hi) : NAN;
        if (!isnan(next) && fabs(next - guess) <= tol * next) { /* Newton converged */
            guess = next;
            lo = hi = next;
            break;
        }
        guess = isnan(next) ? 0.5 * (lo + hi) : next;
    }
    int adjacent = lo < hi && nextafter(lo, INFINITY) >= hi;
    *x = lo == hi ? lo : adjacent ? hi : guess;
    if (iterations)
        *iterations = it;
    return hi - lo > tol * hi && !adjacent ? SOL_ERR_NO_CONVERGENCE : SOL_OK;
}

sol_status sol_tonemap_lower_bound(sol_tonemap op, double threshold, double *c_min_over_l)
{
    if (!c_min_over_l)
        return SOL_ERR_NULL_ARG;
    if (isnan(threshold))
        return SOL_ERR_NONFINITE;
    if (!(threshold > 0.0 && threshold < 1.0))
        return SOL_ERR_OUT_OF_RANGE;
    return sol_tonemap_inverse(op, threshold, c_min_over_l);
}

int sol_display_code8(double linear)
{
    return (int)sol_unorm_encode(sol_srgb_encode(linear), 8);
}
