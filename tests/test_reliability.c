/* test_reliability.c - regression tests of issue 12 (numeric half): size arithmetic that must not
 * wrap (items 3), extreme magnitudes that must stay finite or give a documented status (item 6),
 * sol_angle3 at any magnitude (item 7). Each test here failed before its fix. */
#include <criterion/criterion.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sol_brdf.h"
#include "sol_core.h"
#include "sol_hdr.h"
#include "sol_lighting.h"
#include "sol_normalmaps.h"
#include "sol_pipeline.h"
#include "sol_screen.h"
#include "sol_textures.h"

/* ---- item 7: sol_angle3 at extreme magnitudes ---- */

Test(reliability, angle3_is_scale_invariant_from_1e_minus_300_to_1e300)
{
    static const double scales[] = {1e-320, 1e-300, 1e-200, 1e-160, 1e-100, 1.0, 1e100, 1e160, 1e200, 1e300, 0x1p1023};
    const double u[3] = {1.0, 0.25, -0.5}, v[3] = {0.5, -1.0, 0.125};
    const double ref = sol_angle3(u, v);
    for (size_t i = 0; i < sizeof scales / sizeof *scales; ++i)
        for (size_t j = 0; j < sizeof scales / sizeof *scales; ++j) {
            double a[3], b[3];
            for (int c = 0; c < 3; ++c) {
                a[c] = u[c] * scales[i];
                b[c] = v[c] * scales[j];
            }
            double got = sol_angle3(a, b);
            /* subnormal components keep fewer digits */
            double tol = scales[i] < 1e-307 || scales[j] < 1e-307 ? 1e-3 : 1e-14;
            cr_assert(fabs(got - ref) <= tol, "scales %g %g: %.17g vs %.17g", scales[i], scales[j], got, ref);
        }
    const double big[3] = {DBL_MAX, DBL_MAX, -DBL_MAX}, x[3] = {1.0, 0.0, 0.0};
    cr_assert_float_eq(sol_angle3(big, x), acos(1.0 / sqrt(3.0)), 1e-15);
}

Test(reliability, angle3_tiny_angle_between_huge_or_tiny_vectors)
{
    const double a[3] = {1e200, 0.0, 0.0}, b[3] = {1e200, 1e191, 0.0};
    cr_assert_float_eq(sol_angle3(a, b), 1e-9, 1e-22);
    const double c[3] = {1e-200, 0.0, 0.0}, d[3] = {1e-200, 1e-209, 0.0};
    cr_assert_float_eq(sol_angle3(c, d), 1e-9, 1e-22);
    /* an angle of 1e-300 (its square underflows) */
    const double e[3] = {1.0, 0.0, 0.0}, f[3] = {1.0, 1e-300, 0.0};
    cr_assert_float_eq(sol_angle3(e, f), 1e-300, 1e-312);
    /* antiparallel at 1e-300 */
    const double g[3] = {-1e-300, 0.0, 0.0};
    cr_assert_float_eq(sol_angle3(c, g), M_PI, 1e-15);
    /* documented: zero vector gives 0, NaN or Inf gives NaN */
    const double z[3] = {0.0, -0.0, 0.0}, n[3] = {NAN, 0.0, 0.0}, inf[3] = {INFINITY, 0.0, 0.0};
    cr_assert_eq(sol_angle3(z, a), 0.0);
    const double huge[3] = {DBL_MAX, DBL_MAX, DBL_MAX};
    cr_assert_eq(sol_angle3(z, huge), 0.0);
    cr_assert(isnan(sol_angle3(z, n)));
    cr_assert(isnan(sol_angle3(n, a)));
    cr_assert(isnan(sol_angle3(a, inf)));
}

/* ---- item 3: UNORM with 32 bits and out-of-range bit counts ---- */

Test(reliability, unorm_32_bits_has_no_shift_overflow)
{
    cr_assert_eq(sol_unorm_encode(1.0, 32), UINT32_MAX);
    cr_assert_eq(sol_unorm_encode(0.5, 32), 2147483648u);
    cr_assert_eq(sol_unorm_encode(nextafter(1.0, 0.0), 32), UINT32_MAX);
    cr_assert_eq(sol_unorm_decode(UINT32_MAX, 32), 1.0);
    cr_assert_eq(sol_unorm_encode(1.0, 31), 0x7FFFFFFFu);
    cr_assert_eq(sol_unorm_encode(1.0, 1), 1u);
    /* documented: no such format */
    cr_assert_eq(sol_unorm_encode(1.0, 0), 0u);
    cr_assert_eq(sol_unorm_encode(1.0, 33), 0u);
    cr_assert_eq(sol_unorm_encode(1.0, -1), 0u);
    cr_assert_eq(sol_unorm_decode(5, 0), 0.0);
    cr_assert_eq(sol_unorm_decode(5, 64), 0.0);
}

/* ---- item 3: BC1 sizes ---- */

Test(reliability, bc1_size_at_int_max_does_not_overflow)
{
    cr_assert_eq(sol_bc1_size(INT_MAX, 1), (size_t)536870912 * 8u);
    cr_assert_eq(sol_bc1_size(1, INT_MAX), (size_t)536870912 * 8u);
    if (sizeof(size_t) >= 8)
        cr_assert_eq(sol_bc1_size(INT_MAX, INT_MAX), (size_t)536870912 * 536870912u * 8u);
    cr_assert_eq(sol_bc1_size(INT_MIN, 4), 0u);
    cr_assert_eq(sol_bc1_size(4, 0), 0u);
}

/* ---- item 3: G-buffer bytes ---- */

Test(reliability, gbuffer_bytes_is_exact_or_out_of_range)
{
    const sol_gbuffer_layout *layout = NULL;
    uint64_t bytes = 12345;
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CLASSIC_WIDE, &layout), SOL_OK); /* 144 bits */
    /* INT_MAX^2 * 8 * 144 / 8 = 144 * (2^31-1)^2 > 2^64: refused, output untouched */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 8, &bytes), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(bytes, 12345u);
    /* INT_MAX^2 * 1 * 18 bytes: 2^62 * 18 > 2^64, refused */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 1, &bytes), SOL_ERR_OUT_OF_RANGE);
    /* 2^31-1 x 2^20 x 8 x 18 bytes = 18 * 8 * 2^20 * (2^31-1) fits: exact */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, 1 << 20, 8, &bytes), SOL_OK);
    cr_assert_eq(bytes, (uint64_t)INT_MAX * (1u << 20) * 8u * 18u);
    /* the product w*h*samples*bits (2^62 * 8 * 64 = 2^71) passes 2^64 but the answer (2^68 / 8...)
     * CryENGINE 3 layout: 64 bits = 8 bytes; 2^31-1 squared * 8 * 8 bytes > 2^64: refused */
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, &layout), SOL_OK);
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 8, &bytes), SOL_ERR_OUT_OF_RANGE);
    /* 2^31-1 x 2^24 x 8 samples x 8 bytes: w*h*s*bits = 2^(31+24+3+6) wraps 2^64, the answer
     * 2^(31+24+3+3) - ... does not */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, 1 << 24, 8, &bytes), SOL_OK);
    cr_assert_eq(bytes, (uint64_t)INT_MAX * (1u << 24) * 64u);
}

/* ---- item 3: adaptive BC5 window of INT_MAX ---- */

static void bumpy_block(double n[16][3])
{
    for (int i = 0; i < 16; ++i) {
        double x = 0.6 * sin(1.7 * i), y = 0.5 * cos(2.3 * i + 0.4);
        n[i][0] = x;
        n[i][1] = y;
        n[i][2] = sqrt(1.0 - x * x - y * y);
    }
}

Test(reliability, bc5_adaptive_window_int_max_searches_every_code)
{
    double n[16][3];
    bumpy_block(n);
    sol_bc5_options big = {.encoder = SOL_BC5_ADAPTIVE, .window = INT_MAX};
    sol_bc5_options all = {.encoder = SOL_BC5_ADAPTIVE, .window = 255};
    sol_bc5_options some = {.encoder = SOL_BC5_ADAPTIVE, .window = 2};
    sol_bc5_block b1, b2, b3;
    sol_bc5_info i1 = {0}, i2 = {0}, i3 = {0};
    cr_assert_eq(sol_bc5_encode_block(n, &big, &b1, &i1), SOL_OK);
    cr_assert_eq(sol_bc5_encode_block(n, &all, &b2, &i2), SOL_OK);
    cr_assert_eq(sol_bc5_encode_block(n, &some, &b3, &i3), SOL_OK);
    cr_assert_eq(i1.candidates, i2.candidates, "INT_MAX tried %g candidates, 255 tried %g", (double)i1.candidates,
                 (double)i2.candidates);
    cr_assert_eq(memcmp(&b1, &b2, sizeof b1), 0);
    cr_assert_geq(i1.candidates, i3.candidates);
    cr_assert_leq(i1.error, i3.error);
}

/* ---- item 3: coverage buffer with a huge block ---- */

Test(reliability, cbuffer_huge_block_is_one_texel_and_tests_in_bounds)
{
    float depth[6 * 5];
    for (int i = 0; i < 6 * 5; ++i)
        depth[i] = 1.0f + (float)i;
    static const int blocks[] = {6, 7, 1 << 20, INT_MAX - 1, INT_MAX};
    for (size_t k = 0; k < sizeof blocks / sizeof *blocks; ++k) {
        sol_cbuffer_options opt = {.block = blocks[k]};
        sol_cbuffer cb;
        cr_assert_eq(sol_cbuffer_build(depth, 6, 5, &opt, &cb), SOL_OK);
        cr_assert_eq(cb.levels, 1, "block %d", blocks[k]);
        cr_assert_eq(cb.width[0], 1);
        cr_assert_eq(cb.height[0], 1);
        cr_assert_eq(cb.zmax[0][0], 30.0f); /* the farthest depth */
        sol_screen_bounds near = {.x0 = 0, .x1 = 5.5, .y0 = 0, .y1 = 4.5, .znear = 0.5};
        sol_screen_bounds far = {.x0 = 2, .x1 = 3, .y0 = 1, .y1 = 2, .znear = 40.0};
        int occluded = -1, visited = -1;
        cr_assert_eq(sol_cbuffer_test(&cb, &near, -1, &occluded, &visited), SOL_OK);
        cr_assert_eq(occluded, 0);
        cr_assert_eq(visited, 1);
        cr_assert_eq(sol_cbuffer_test(&cb, &far, -1, &occluded, &visited), SOL_OK);
        cr_assert_eq(occluded, 1);
        sol_cbuffer_free(&cb);
    }
}

/* ---- item 6: microfacet terms at tiny and huge alpha, grazing v = l, huge exponents ---- */

static long double ggx_ref(long double c, long double a)
{
    /* alpha^2 c^2 + sin^2: c^2 (alpha^2 - 1) + 1 cancels even in long double at alpha < 1e-4 */
    long double a2 = a * a, d = a2 * c * c + (1.0L - c) * (1.0L + c);
    return a2 / (3.14159265358979323846264338327950288L * d * d);
}

static long double beckmann_ref(long double c, long double a)
{
    long double c2 = c * c, t2 = (1.0L - c) * (1.0L + c) / c2;
    return expl(-t2 / (a * a)) / (3.14159265358979323846264338327950288L * a * a * c2 * c2);
}

static void assert_rel(double got, long double want, double tol, const char *what)
{
    cr_assert(isfinite(got), "%s: %g not finite", what, got);
    cr_assert(fabsl((long double)got - want) <= tol * fabsl(want), "%s: %.17g vs %.17Lg", what, got, want);
}

Test(reliability, ndf_peak_at_tiny_alpha_is_finite)
{
    static const double tiny[] = {1e-160, 1e-200, 1e-300, 5e-324};
    for (size_t i = 0; i < sizeof tiny / sizeof *tiny; ++i) {
        cr_assert_eq(sol_ggx_ndf(1.0, tiny[i]), DBL_MAX, "ggx alpha %g", tiny[i]);
        cr_assert_eq(sol_beckmann_ndf(1.0, tiny[i]), DBL_MAX, "beckmann alpha %g", tiny[i]);
        double h[3] = {0.0, 0.0, 1.0};
        cr_assert_eq(sol_ward_ndf(h, tiny[i], tiny[i]), DBL_MAX, "ward alpha %g", tiny[i]);
        /* off the peak the lobe is 0, not NaN */
        double g = sol_ggx_ndf(0.999, tiny[i]);
        cr_assert(g >= 0.0 && g < 1e-300, "%g", g);
        cr_assert_eq(sol_beckmann_ndf(0.999, tiny[i]), 0.0);
    }
    /* alpha^2 subnormal but the answer representable: computed scaled */
    assert_rel(sol_ggx_ndf(1.0, 1e-154), 1.0L / (3.14159265358979323846264338327950288L * 1e-308L), 1e-13, "ggx 1e-154");
    assert_rel(sol_beckmann_ndf(1.0, 1e-154), 1.0L / (3.14159265358979323846264338327950288L * 1e-308L), 1e-12,
               "beckmann 1e-154");
}

Test(reliability, ndf_below_alpha_1e_minus_4_matches_long_double)
{
    static const double alphas[] = {9e-5, 1e-5, 1e-7, 1e-10};
    for (size_t i = 0; i < sizeof alphas / sizeof *alphas; ++i) {
        double a = alphas[i];
        static const double offs[] = {0.0, 0.25, 1.0, 3.0};
        for (size_t k = 0; k < sizeof offs / sizeof *offs; ++k) {
            /* theta_h = offs * alpha: inside the lobe */
            double c = cos(offs[k] * a);
            assert_rel(sol_ggx_ndf(c, a), ggx_ref(c, a), 1e-9, "ggx");
            assert_rel(sol_beckmann_ndf(c, a), beckmann_ref(c, a), 1e-9, "beckmann");
        }
    }
}

Test(reliability, huge_and_infinite_alpha_stay_finite)
{
    static const double big[] = {1e154, 1e200, DBL_MAX, INFINITY};
    static const double cs[] = {1.0, 0.5, 1e-3, 1e-200, 0.0};
    for (size_t i = 0; i < sizeof big / sizeof *big; ++i)
        for (size_t k = 0; k < sizeof cs / sizeof *cs; ++k) {
            double a = big[i], c = cs[k];
            double v[] = {sol_ggx_ndf(c, a), sol_beckmann_ndf(c, a), sol_smith_g1_ggx(c, a),
                          sol_smith_g1_beckmann(c, a)};
            for (int j = 0; j < 4; ++j)
                cr_assert(isfinite(v[j]) && v[j] >= 0.0, "alpha %g c %g term %d: %g", a, c, j, v[j]);
            cr_assert_leq(v[2], 1.0);
        }
    /* G1 at alpha = 1e200, c = 0.5: 2c / (c + sqrt(alpha^2 s^2 + c^2)) ~ 1 / (alpha * 0.866) */
    assert_rel(sol_smith_g1_ggx(0.5, 1e200), 1.0L / (1e200L * sqrtl(0.75L) + 0.5L), 1e-12, "g1 ggx");
}

Test(reliability, cook_torrance_at_grazing_v_equal_l)
{
    /* v = l at the horizon: h = v, so D = D(h.z -> 0) and G1(v)/v.z -> 2/alpha (GGX); the whole
     * BRDF tends to f0 / pi for GGX at alpha = 0.5 (D -> alpha^2 / pi) */
    const double v[3] = {1.0, 0.0, 1e-200};
    double g = sol_cook_torrance(v, v, SOL_NDF_GGX, 0.5, 0.04);
    assert_rel(g, 0.04L / 3.14159265358979323846264338327950288L, 1e-12, "ct ggx grazing");
    double b = sol_cook_torrance(v, v, SOL_NDF_BECKMANN, 0.5, 0.04);
    cr_assert(isfinite(b) && b >= 0.0, "beckmann grazing %g", b);
    /* continuous with a merely low angle */
    double w[3] = {1.0, 0.0, 1e-6};
    double n = sqrt(sol_dot3(w, w));
    for (int i = 0; i < 3; ++i)
        w[i] /= n;
    assert_rel(sol_cook_torrance(w, w, SOL_NDF_GGX, 0.5, 0.04), 0.04L / 3.14159265358979323846264338327950288L, 1e-5,
               "ct ggx low");
    /* subnormal cosines, tiny alpha, infinite f0: finite */
    const double s[3] = {1.0, 0.0, 5e-324};
    cr_assert(isfinite(sol_cook_torrance(s, s, SOL_NDF_GGX, 0.5, 0.04)));
    cr_assert(isfinite(sol_cook_torrance(s, s, SOL_NDF_GGX, 1e-300, 0.04)));
    const double up[3] = {0.0, 0.0, 1.0};
    cr_assert_eq(sol_cook_torrance(up, up, SOL_NDF_GGX, 1e-200, 0.04), DBL_MAX);
    cr_assert(isfinite(sol_cook_torrance(up, up, SOL_NDF_BECKMANN, 0.5, INFINITY)));
    cr_assert(isfinite(sol_cook_torrance(v, v, SOL_NDF_BECKMANN, 1e-300, -INFINITY)));
    cr_assert(isfinite(sol_ward_brdf(v, v, 0.3, 0.3)));
    cr_assert(isfinite(sol_ward_brdf(up, up, 1e-200, 1e-200)));
}

Test(reliability, blinn_phong_exponents_above_1000)
{
    /* exact factor (n+2)(n+4) / (8 pi (2^(-n/2) + n)) */
    static const double ns[] = {1000.0, 2048.0, 1e4, 1e6, 1e12, 1e100, 1e160, 1e300, DBL_MAX};
    for (size_t i = 0; i < sizeof ns / sizeof *ns; ++i) {
        long double n = ns[i];
        long double want = (n + 2.0L) / (8.0L * 3.14159265358979323846264338327950288L) *
                           ((n + 4.0L) / (exp2l(-0.5L * n) + n));
        assert_rel(sol_blinn_phong_norm_factor_exact(ns[i]), want, 1e-14, "blinn exact");
        assert_rel(sol_blinn_phong_norm_factor_approx(ns[i]), (n + 8.0L) / (8.0L * 3.14159265358979323846264338327950288L),
                   1e-14, "blinn approx");
        cr_assert(isfinite(sol_phong_normalized(1.0, ns[i])));
    }
    assert_rel(sol_blinn_phong_norm_factor_exact(1e160), 1e160L / (8.0L * 3.14159265358979323846264338327950288L), 1e-14,
               "1e160");
    /* raw lobe at n = 2000: cos^n (theta) for a small theta */
    assert_rel(sol_blinn_phong_raw(cos(0.01), 2000.0), powl(cosl(0.01L), 2000.0L), 1e-12, "raw 2000");
}

Test(reliability, infinite_exponent_and_sharpness_are_not_nan)
{
    cr_assert_eq(sol_phong_raw(1.0, INFINITY), 1.0);
    cr_assert_eq(sol_phong_raw(0.999, INFINITY), 0.0);
    cr_assert_eq(sol_phong_normalized(1.0, INFINITY), DBL_MAX);
    cr_assert_eq(sol_phong_normalized(0.999, INFINITY), 0.0);
    cr_assert_eq(sol_phong_norm_factor(INFINITY), DBL_MAX);
    cr_assert_eq(sol_phong_lobe_norm_factor(INFINITY), DBL_MAX);
    cr_assert_eq(sol_blinn_phong_norm_factor_exact(INFINITY), DBL_MAX);
    cr_assert_eq(sol_blinn_phong_norm_factor_approx(INFINITY), DBL_MAX);
    sol_sg g = {.axis = {0.0, 0.0, 1.0}, .sharpness = INFINITY, .amplitude = 2.0};
    const double on[3] = {0.0, 0.0, 1.0}, off[3] = {0.0, 1e-8, 1.0};
    cr_assert_eq(sol_sg_eval(&g, on), 2.0);
    cr_assert_eq(sol_sg_eval(&g, off), 0.0);
    cr_assert_eq(sol_sg_integral(&g), 0.0);
    cr_assert_eq(sol_fresnel_schlick(INFINITY, 1.0), DBL_MAX);
    cr_assert_eq(sol_fresnel_schlick(INFINITY, 0.0), 1.0);
    cr_assert_eq(sol_fresnel_schlick(-INFINITY, 0.5), -DBL_MAX);
}

/* ---- item 6: inverse tone maps near 1, exposure, RGBM, lights, renormalisation ---- */

Test(reliability, filmic_inverses_near_one_are_finite_and_consistent)
{
    static const sol_tonemap ops[] = {SOL_TONEMAP_EXPONENTIAL, SOL_TONEMAP_REINHARD, SOL_TONEMAP_FILMIC_HBD,
                                      SOL_TONEMAP_FILMIC_SLIDE};
    static const double ys[] = {1.0 - 1e-16, 1.0 - 1e-15, 1.0 - 1e-12, 1.0 - 1e-9, 1.0 - 1e-6};
    for (size_t i = 0; i < sizeof ops / sizeof *ops; ++i) {
        double prev = 0.0;
        for (size_t k = sizeof ys / sizeof *ys; k-- > 0;) {
            double x = -1.0;
            cr_assert_eq(sol_tonemap_inverse(ops[i], ys[k], &x), SOL_OK);
            cr_assert(isfinite(x) && x > prev, "%s y = 1 - %g: x = %g", sol_tonemap_name(ops[i]), 1.0 - ys[k], x);
            prev = x;
        }
        double x = 123.0;
        cr_assert_eq(sol_tonemap_inverse(ops[i], 1.0, &x), SOL_ERR_OUT_OF_RANGE);
        cr_assert_eq(x, 123.0);
    }
    /* HBD near 1: g = 1 - eps, 6.2 eps x'^2 ~ 1.2 x'  =>  x' ~ 1.2 / (6.2 (1 - g)) */
    double y = 1.0 - 1e-12, x = 0.0;
    cr_assert_eq(sol_tonemap_inverse(SOL_TONEMAP_FILMIC_HBD, y, &x), SOL_OK);
    long double omg = -expm1l(log1pl(-(1.0L - (long double)y)) / 2.2L);
    long double a = 6.2L * omg, b = 0.5L - 1.7L * (1.0L - omg), c = 0.06L * (1.0L - omg);
    long double want = 0.004L + (-b + sqrtl(b * b + 4.0L * a * c)) / (2.0L * a);
    assert_rel(x, want, 1e-9, "hbd inverse at 1 - 1e-12");
    /* the forward map of the inverse gives y back to its conditioning */
    cr_assert(fabs(sol_tonemap_apply(SOL_TONEMAP_FILMIC_HBD, x) - y) < 1e-15);
}

Test(reliability, exposure_at_extreme_compensation)
{
    double e = -1.0;
    cr_assert_eq(sol_exposure_from_luminance(1.0, 1e4, &e), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(e, -1.0);
    /* representable although 2^ec overflows: 0.18 * 2^1100 / 2^1000 = 0.18 * 2^100 */
    cr_assert_eq(sol_exposure_from_luminance(0x1p1000, 1100.0, &e), SOL_OK);
    assert_rel(e, 0.18L * 0x1p100L, 1e-15, "exposure 2^1100 / 2^1000");
    /* tiny luminance, ordinary compensation: 0.18 / 2^-1070 */
    cr_assert_eq(sol_exposure_from_luminance(0x1p-1070, 0.0, &e), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(sol_exposure_from_luminance(0x1p-1000, -100.0, &e), SOL_OK);
    assert_rel(e, 0.18L * 0x1p900L, 1e-15, "exposure 2^-100 / 2^-1000");
    /* underflow is documented as 0 (or a subnormal) */
    cr_assert_eq(sol_exposure_from_luminance(1.0, -1e4, &e), SOL_OK);
    cr_assert_eq(e, 0.0);
    cr_assert_eq(sol_exposure_from_luminance(DBL_MAX, -40.0, &e), SOL_OK); /* 9e-322 */
    cr_assert(e > 0.0 && e < DBL_MIN);
}

Test(reliability, rgbm_decode_with_a_huge_range)
{
    const uint8_t px[4] = {255, 128, 0, 255};
    float rgb[3] = {7.0f, 7.0f, 7.0f};
    cr_assert_eq(sol_rgbm_decode(px, 1e300, rgb), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(rgb[0], 7.0f);
    cr_assert_eq(sol_rgbm_decode(px, DBL_MAX, rgb), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(sol_rgbm_decode(px, FLT_MAX, rgb), SOL_OK);
    cr_assert(isfinite(rgb[0]) && rgb[0] == FLT_MAX);
    /* a huge range with a small multiplier still decodes when it fits */
    const uint8_t small[4] = {1, 0, 0, 1};
    cr_assert_eq(sol_rgbm_decode(small, 1e40, rgb), SOL_OK);
    cr_assert(isfinite(rgb[0]) && rgb[0] > 1e35f);
}

Test(reliability, light_just_above_the_floor)
{
    sol_room_scene scene = {.walls = NULL, .wall_count = 0, .wall_height = 3.0, .light = {0.0, 0.0, 1e-300},
                            .radius = 10.0};
    double e = -1.0;
    /* right below: height / d^3 = 1e600 */
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0.0, 0.0, &e), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(e, -1.0);
    /* one unit away: cos / d^2 = 1e-300 * (1 - 0.01)^2 */
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 1.0, 0.0, &e), SOL_OK);
    assert_rel(e, 1e-300L * 0.99L * 0.99L, 1e-14, "irradiance 1 away");
    /* 1e-110 away from a light 1e-120 high: d^2 = 1e-220 underflows nothing after scaling */
    scene.light[2] = 1e-120;
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 1e-110, 0.0, &e), SOL_OK);
    assert_rel(e, 1e-120L / 1e-330L, 1e-12, "irradiance tiny distances");
    /* a huge scene: light 1e160 high with radius 1e161 (d^2 = 1e320 overflows) */
    scene.light[2] = 1e160;
    scene.radius = 1e161;
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0.0, 0.0, &e), SOL_OK);
    assert_rel(e, 1e-320L * 0.99L * 0.99L, 1e-3, "irradiance huge scene"); /* a subnormal answer */
}

Test(reliability, renormalisation_of_the_full_float_range)
{
    float data[4] = {-FLT_MAX, 0.0f, FLT_MAX, 1e30f};
    sol_image img = {.width = 4, .height = 1, .channels = 1, .data = data};
    sol_renorm r;
    cr_assert_eq(sol_renorm_fit(&img, &r), SOL_OK);
    cr_assert_eq(sol_renorm_apply(&r, &img), SOL_OK);
    cr_assert_eq(data[0], 0.0f);
    cr_assert_eq(data[1], 0.5f);
    cr_assert_eq(data[2], 1.0f);
    for (int i = 0; i < 4; ++i)
        cr_assert(isfinite(data[i]) && data[i] >= 0.0f && data[i] <= 1.0f);
    cr_assert_eq(sol_renorm_undo(&r, &img), SOL_OK);
    cr_assert_eq(data[0], -FLT_MAX);
    cr_assert_eq(data[1], 0.0f);
    cr_assert_eq(data[2], FLT_MAX);
    cr_assert(isfinite(data[3])); /* 1e30 is below the float step of the stored value there */
    /* a stored value of 3 maps past FLT_MAX: refused, image untouched */
    float bad[2] = {0.5f, 3.0f};
    sol_image img2 = {.width = 2, .height = 1, .channels = 1, .data = bad};
    cr_assert_eq(sol_renorm_undo(&r, &img2), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(bad[0], 0.5f);
}

Test(reliability, adaptation_between_the_largest_values_is_finite)
{
    double r = sol_adapt_exponential(-DBL_MAX, DBL_MAX, 1.0, 1.0);
    cr_assert(isfinite(r) && r > 0.0, "%g", r);
    assert_rel(r, (long double)DBL_MAX * (1.0L - 2.0L * expl(-1.0L)), 1e-15, "adapt");
    cr_assert(isfinite(sol_adapt_exponential(DBL_MAX, -DBL_MAX, 1e300, 1.0)));
    cr_assert_eq(sol_adapt_exponential(DBL_MAX, -DBL_MAX, 0.0, 1.0), DBL_MAX);
}
