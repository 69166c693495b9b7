/* transfer.c - transfer functions for color textures (claims T3, T5, T6).
 *
 * Power gamma, exact sRGB (IEC 61966-2-1) and the Xbox 360 piecewise-linear gamma. The PWL knots
 * come from Xenia's src/xenia/gpu/xenos.cc (PWLGammaToLinear / LinearToPWLGamma), which in turn
 * follow the Source Engine's X360GammaToLinear / X360LinearToGamma and Direct3D 9 code found in
 * Xbox 360 executables: four segments in 10-bit linear L and 8-bit gamma e,
 *   L in [0,64): e = L;  [64,128): e = 32 + L/2;  [128,512): e = 64 + L/4;  [512,1023]: e = 128 + L/8. */
#include <math.h>

#include "sol_textures.h"

/* PWL knots as (linear, encoded) pairs; the last knot is (1,1) (see sol_textures.h). */
static const double pwl_linear[5] = {0.0, 64.0 / 1023.0, 128.0 / 1023.0, 512.0 / 1023.0, 1.0};
static const double pwl_encoded[5] = {0.0, 64.0 / 255.0, 96.0 / 255.0, 192.0 / 255.0, 1.0};

static sol_status check_curve(const sol_transfer *curve, double *gamma)
{
    if (!curve)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)curve->kind >= SOL_TRANSFER_KIND_COUNT)
        return SOL_ERR_INVALID_ARG;
    *gamma = curve->gamma == 0.0 ? 2.2 : curve->gamma;
    if (curve->kind == SOL_TRANSFER_POWER && !(isfinite(*gamma) && *gamma > 0.0))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

static double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

/* Segment index of a value on the knot table `knots` (right-continuous at knots). */
static int pwl_segment(const double knots[5], double v)
{
    int s = 0;
    while (s < 3 && v >= knots[s + 1])
        ++s;
    return s;
}

static double pwl_slope(int s)
{
    return (pwl_encoded[s + 1] - pwl_encoded[s]) / (pwl_linear[s + 1] - pwl_linear[s]);
}

static double encode_clamped(sol_transfer_kind kind, double gamma, double x)
{
    switch (kind) {
    case SOL_TRANSFER_POWER: return pow(x, 1.0 / gamma);
    case SOL_TRANSFER_SRGB: return sol_srgb_encode(x);
    case SOL_TRANSFER_X360_PWL: {
        int s = pwl_segment(pwl_linear, x);
        return fmin(1.0, pwl_encoded[s] + (x - pwl_linear[s]) * pwl_slope(s));
    }
    default: return x;
    }
}

static double decode_clamped(sol_transfer_kind kind, double gamma, double e)
{
    switch (kind) {
    case SOL_TRANSFER_POWER: return pow(e, gamma);
    case SOL_TRANSFER_SRGB: return sol_srgb_decode(e);
    case SOL_TRANSFER_X360_PWL: {
        int s = pwl_segment(pwl_encoded, e);
        return fmin(1.0, pwl_linear[s] + (e - pwl_encoded[s]) / pwl_slope(s));
    }
    default: return e;
    }
}

sol_status sol_transfer_encode(const sol_transfer *curve, double linear, double *encoded)
{
    double gamma;
    sol_status st = check_curve(curve, &gamma);
    if (st)
        return st;
    if (!encoded)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(linear))
        return SOL_ERR_NONFINITE;
    *encoded = encode_clamped(curve->kind, gamma, clamp01(linear));
    return SOL_OK;
}

sol_status sol_transfer_decode(const sol_transfer *curve, double encoded, double *linear)
{
    double gamma;
    sol_status st = check_curve(curve, &gamma);
    if (st)
        return st;
    if (!linear)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(encoded))
        return SOL_ERR_NONFINITE;
    *linear = decode_clamped(curve->kind, gamma, clamp01(encoded));
    return SOL_OK;
}

/* Slope without argument checks; x in [0,1], +Inf for a power curve at 0 with gamma > 1. */
static double slope_unchecked(sol_transfer_kind kind, double gamma, double x)
{
    switch (kind) {
    case SOL_TRANSFER_POWER: return pow(x, 1.0 / gamma - 1.0) / gamma;
    case SOL_TRANSFER_SRGB: return x <= 0.0031308 ? 12.92 : 1.055 / 2.4 * pow(x, 1.0 / 2.4 - 1.0);
    case SOL_TRANSFER_X360_PWL: return pwl_slope(pwl_segment(pwl_linear, x));
    default: return 1.0;
    }
}

sol_status sol_transfer_slope(const sol_transfer *curve, double linear, double *slope)
{
    double gamma;
    sol_status st = check_curve(curve, &gamma);
    if (st)
        return st;
    if (!slope)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(linear))
        return SOL_ERR_NONFINITE;
    if (linear < 0.0 || linear > 1.0)
        return SOL_ERR_OUT_OF_RANGE;
    double s = slope_unchecked(curve->kind, gamma, linear);
    if (!isfinite(s))
        return SOL_ERR_OUT_OF_RANGE;
    *slope = s;
    return SOL_OK;
}

sol_status sol_transfer_quantize8(const sol_transfer *curve, double linear, uint8_t *code)
{
    double e;
    if (!code)
        return SOL_ERR_NULL_ARG;
    sol_status st = sol_transfer_encode(curve, linear, &e);
    if (st)
        return st;
    *code = (uint8_t)sol_unorm_encode(e, 8);
    return SOL_OK;
}

sol_status sol_transfer_dequantize8(const sol_transfer *curve, uint8_t code, double *linear)
{
    return sol_transfer_decode(curve, sol_unorm_decode(code, 8), linear);
}

/* The x in [0,1] where the slope first satisfies s <= target (want_at_most) or s < target: the
 * slope decreases with x, so the predicate is false then true; bisection to double resolution. */
static double bisect_first_true(sol_transfer_kind kind, double gamma, double target, int want_at_most)
{
    double a = 0.0, b = 1.0;
    for (int i = 0; i < 200 && b - a > 1e-17; ++i) {
        double m = 0.5 * (a + b), s = slope_unchecked(kind, gamma, m);
        int ok = want_at_most ? s <= target : s < target;
        if (ok)
            b = m;
        else
            a = m;
    }
    return 0.5 * (a + b);
}

sol_status sol_transfer_equal_density(const sol_transfer *curve, double rel_tol, double *lo, double *hi)
{
    double gamma;
    sol_status st = check_curve(curve, &gamma);
    if (st)
        return st;
    if (!lo || !hi)
        return SOL_ERR_NULL_ARG;
    if (curve->kind == SOL_TRANSFER_LINEAR || (curve->kind == SOL_TRANSFER_POWER && gamma <= 1.0))
        return SOL_ERR_INVALID_ARG;
    if (!(isfinite(rel_tol) && rel_tol >= 0.0))
        return SOL_ERR_INVALID_ARG;
    /* Every supported curve's slope decreases (weakly) with x, so {x : |s(x) - 1| <= tol} is an
     * interval: it starts where s first drops to 1 + tol and ends where s drops below 1 - tol. */
    double start = bisect_first_true(curve->kind, gamma, 1.0 + rel_tol, 1);
    double end = bisect_first_true(curve->kind, gamma, 1.0 - rel_tol, 0);
    if (end < start) /* no x qualifies: the slope jumps over 1 at one point */
        end = start;
    *lo = start;
    *hi = end;
    return SOL_OK;
}

uint16_t sol_x360_pwl_gamma8_to_linear10(uint8_t gamma_code)
{
    /* Xenia xenos.cc PWLGammaToLinear in integers: L = e * 8 * 255 * scale + offset, then
     * L += trunc(L * scale) with scale = {1, 2, 4, 8} / 1024. */
    int e = gamma_code, mul, offset;
    if (e >= 192) {
        mul = 8;
        offset = -1024;
    } else if (e >= 96) {
        mul = 4;
        offset = -256;
    } else if (e >= 64) {
        mul = 2;
        offset = -64;
    } else {
        mul = 1;
        offset = 0;
    }
    int linear = e * mul + offset;
    linear += (linear * mul) / 1024; /* linear >= 0, so integer division is trunc */
    return (uint16_t)linear;
}

uint8_t sol_x360_cache_degamma8(uint8_t gamma_code)
{
    return (uint8_t)sol_unorm_encode(sol_x360_pwl_gamma8_to_linear10(gamma_code) / 1023.0, 8);
}
