/* test_hdr.c - small floats (bit-exact, hand-checked), HDR encodings, tone-map bounds (D10-D12),
 * the ACES reference and fit (S3), 3D LUTs and charts (M4), CIEDE2000, exposure (S6). */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sol_hdr.h"

/* ---------------- binary16 ---------------- */

Test(hdr, half_encodes_hand_checked_values)
{
    cr_assert_eq(sol_half_from_float(1.0f), 0x3c00);
    cr_assert_eq(sol_half_from_float(-2.0f), 0xc000);
    cr_assert_eq(sol_half_from_float(0.1f), 0x2e66);            /* 0.0999755859375 */
    cr_assert_eq(sol_half_from_float(1.0f / 3.0f), 0x3555);     /* 0.333251953125 */
    cr_assert_eq(sol_half_from_float(65504.0f), 0x7bff);        /* largest finite */
    cr_assert_eq(sol_half_from_float(65519.0f), 0x7bff);        /* below the overflow midpoint */
    cr_assert_eq(sol_half_from_float(65520.0f), 0x7c00);        /* midpoint: ties to even = Inf */
    cr_assert_eq(sol_half_from_float(ldexpf(1.0f, -14)), 0x0400); /* smallest normal */
    cr_assert_eq(sol_half_from_float(ldexpf(1.0f, -24)), 0x0001); /* smallest denormal */
    cr_assert_eq(sol_half_from_float(ldexpf(1.0f, -25)), 0x0000); /* tie -> even (0) */
    cr_assert_eq(sol_half_from_float(ldexpf(3.0f, -25)), 0x0002); /* 1.5 ulp, tie -> even (2) */
    cr_assert_eq(sol_half_from_float(1.0f + ldexpf(1.0f, -11)), 0x3c00);
    cr_assert_eq(sol_half_from_float(1.0f + ldexpf(3.0f, -11)), 0x3c02);
    cr_assert_eq(sol_half_from_float(ldexpf(1023.5f, -24)), 0x0400); /* denormal rounds up to normal */
    cr_assert_eq(sol_half_from_float(-0.0f), 0x8000);
    cr_assert_eq(sol_half_from_float(INFINITY), 0x7c00);
    cr_assert_eq(sol_half_from_float(-INFINITY), 0xfc00);
    cr_assert_eq(sol_half_from_float(NAN), 0x7e00);
    cr_assert_eq(sol_half_from_float(1e30f), 0x7c00);
    cr_assert_eq(sol_half_from_float(1e-30f), 0x0000);
    cr_assert_eq(sol_half_from_float(-1e-30f), 0x8000);
}

Test(hdr, half_decodes_hand_checked_values)
{
    cr_assert_eq(sol_half_to_float(0x0001), ldexpf(1.0f, -24));
    cr_assert_eq(sol_half_to_float(0x03ff), ldexpf(1023.0f, -24));
    cr_assert_eq(sol_half_to_float(0x7bff), 65504.0f);
    cr_assert_eq(sol_half_to_float(0x3555), 0.333251953125f);
    cr_assert(isinf(sol_half_to_float(0x7c00)) && sol_half_to_float(0x7c00) > 0);
    cr_assert(isnan(sol_half_to_float(0x7e00)));
    cr_assert(signbit(sol_half_to_float(0x8000)));
}

Test(hdr, half_round_trips_every_code_and_matches_the_compiler)
{
    for (uint32_t h = 0; h < 0x10000u; ++h) {
        float f = sol_half_to_float((uint16_t)h);
        if (isnan(f))
            continue;
        cr_assert_eq(sol_half_from_float(f), h, "code %04x", h);
    }
#ifdef __FLT16_MAX__
    /* Every float whose top 19 bits vary (covers all exponents and the rounding bits). */
    for (uint32_t hi = 0; hi < (1u << 19); ++hi) {
        uint32_t bits = (hi << 13) | 0x1000u * (hi & 1u) | (hi * 2654435761u >> 20);
        float f;
        memcpy(&f, &bits, sizeof f);
        if (isnan(f))
            continue;
        _Float16 ref = (_Float16)f;
        uint16_t ref_bits;
        memcpy(&ref_bits, &ref, sizeof ref_bits);
        cr_assert_eq(sol_half_from_float(f), ref_bits, "float bits %08x", bits);
    }
#endif
}

/* ---------------- R11G11B10F (GL_EXT_packed_float) ---------------- */

Test(hdr, uf11_uf10_hand_checked_values)
{
    cr_assert_eq(sol_uf11_from_float(1.0f), 15u << 6);
    cr_assert_eq(sol_uf10_from_float(1.0f), 15u << 5);
    cr_assert_eq(sol_uf11_from_float(65024.0f), 0x7bfu); /* largest finite 11-bit */
    cr_assert_eq(sol_uf11_from_float(65536.0f), 0x7bfu); /* finite overflow saturates */
    cr_assert_eq(sol_uf11_from_float(3e38f), 0x7bfu);
    cr_assert_eq(sol_uf10_from_float(64512.0f), 0x3dfu); /* largest finite 10-bit */
    cr_assert_eq(sol_uf10_from_float(65000.0f), 0x3dfu);
    cr_assert_eq(sol_uf11_from_float(ldexpf(1.0f, -20)), 0x001u); /* smallest denormal */
    cr_assert_eq(sol_uf11_from_float(ldexpf(1.0f, -21)), 0x000u); /* below it: tie to even 0 */
    cr_assert_eq(sol_uf11_from_float(ldexpf(1.5f, -21)), 0x001u);
    cr_assert_eq(sol_uf10_from_float(ldexpf(1.0f, -19)), 0x001u);
    cr_assert_eq(sol_uf11_from_float(ldexpf(1.0f, -14)), 0x040u); /* smallest normal */
    cr_assert_eq(sol_uf11_from_float(1.0f + 1.0f / 128.0f), 0x3c0u); /* tie to even */
    cr_assert_eq(sol_uf11_from_float(1.0f + 3.0f / 128.0f), 0x3c2u);
    cr_assert_eq(sol_uf11_from_float(-1.0f), 0u);
    cr_assert_eq(sol_uf11_from_float(-0.0f), 0u);
    cr_assert_eq(sol_uf11_from_float(-INFINITY), 0u);
    cr_assert_eq(sol_uf11_from_float(INFINITY), 0x7c0u);
    cr_assert_eq(sol_uf11_from_float(NAN), 0x7c1u);
    cr_assert_eq(sol_uf11_from_float(-NAN), 0x7c1u);
    cr_assert_eq(sol_uf11_to_float(0x7bfu), 65024.0f);
    cr_assert_eq(sol_uf10_to_float(0x3dfu), 64512.0f);
    cr_assert_eq(sol_uf11_to_float(0x001u), ldexpf(1.0f, -20));
    cr_assert(isnan(sol_uf10_to_float(0x3e1u)));
}

Test(hdr, uf11_uf10_round_trip_every_code)
{
    for (uint32_t c = 0; c < 0x7c0u; ++c)
        cr_assert_eq(sol_uf11_from_float(sol_uf11_to_float(c)), c);
    for (uint32_t c = 0; c < 0x3e0u; ++c)
        cr_assert_eq(sol_uf10_from_float(sol_uf10_to_float(c)), c);
}

Test(hdr, r11g11b10f_layout)
{
    const float one[3] = {1.0f, 1.0f, 1.0f};
    cr_assert_eq(sol_r11g11b10f_pack(one), 0x781e03c0u);
    const float rgb[3] = {0.25f, 1000.0f, 1000.0f};
    float back[3];
    sol_r11g11b10f_unpack(sol_r11g11b10f_pack(rgb), back);
    cr_assert_eq(back[0], 0.25f);
    cr_assert_eq(back[1], 1000.0f); /* 2^9 * (1 + 61/64): exact with 6 mantissa bits */
    cr_assert_eq(back[2], 992.0f);  /* 2^9 * (1 + 30.5/32): tie, rounds to even 30/32 */
}

/* ---------------- RGBM, RGB10 scaled, depth ---------------- */

Test(hdr, rgbm_black_clamping_and_errors)
{
    uint8_t code[4] = {9, 9, 9, 9};
    float black[3] = {0.0f, -1.0f, NAN}, out[3] = {7, 7, 7};
    cr_assert_eq(sol_rgbm_encode(black, 6.0, code), SOL_OK);
    cr_assert(code[0] == 0 && code[1] == 0 && code[2] == 0 && code[3] == 0);
    cr_assert_eq(sol_rgbm_decode(code, 6.0, out), SOL_OK);
    cr_assert(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
    float big[3] = {100.0f, 3.0f, INFINITY};
    cr_assert_eq(sol_rgbm_encode(big, 6.0, code), SOL_OK);
    cr_assert_eq(code[3], 255);
    cr_assert_eq(code[0], 255);
    cr_assert_eq(code[2], 255);
    uint8_t untouched[4] = {1, 2, 3, 4};
    cr_assert_eq(sol_rgbm_encode(big, 0.0, untouched), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_rgbm_encode(big, NAN, untouched), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_rgbm_encode(NULL, 6.0, untouched), SOL_ERR_NULL_ARG);
    cr_assert_eq(untouched[0], 1);
}

Test(hdr, rgbm_hand_checked_and_relative_error)
{
    const float rgb[3] = {1.0f, 0.5f, 0.25f};
    uint8_t code[4];
    cr_assert_eq(sol_rgbm_encode(rgb, 6.0, code), SOL_OK);
    cr_assert_eq(code[3], 43); /* ceil(255 / 6) */
    cr_assert_eq(code[0], 252); /* round(255 * 1 / (43/255*6)) = round(252.03) */
    for (int i = 1; i < 2000; ++i) {
        float v = (float)(6.0 * i / 2000.0), c[3] = {v, v, v}, d[3];
        cr_assert_eq(sol_rgbm_encode(c, 6.0, code), SOL_OK);
        cr_assert_eq(sol_rgbm_decode(code, 6.0, d), SOL_OK);
        /* half a code of the shared scale m * range <= v + range / 255 */
        cr_assert_leq(fabs(d[0] - v), 0.5 / 255.0 * (v + 6.0 / 255.0) + 1e-7, "v %g -> %g", v, d[0]);
    }
}

Test(hdr, rgb10_scaled_is_0_to_2_step_2_over_1023)
{
    cr_assert_eq(sol_rgb10_scaled_encode(2.0f), 1023u);
    cr_assert_eq(sol_rgb10_scaled_encode(5.0f), 1023u);
    cr_assert_eq(sol_rgb10_scaled_encode(-1.0f), 0u);
    cr_assert_eq(sol_rgb10_scaled_encode(NAN), 0u);
    cr_assert_eq(sol_rgb10_scaled_encode(1.0f), 512u); /* 511.5 rounds up */
    cr_assert_float_eq(sol_rgb10_scaled_decode(1u), 2.0f / 1023.0f, 1e-9);
}

Test(hdr, m2_depth_rg8_precision_and_rounded_x_edge)
{
    uint8_t xy[2];
    sol_depth_rg8_encode(0.0, xy);
    cr_assert(xy[0] == 0 && xy[1] == 0);
    sol_depth_rg8_encode(1.0, xy);
    cr_assert(xy[0] == 255 && xy[1] == 0);
    sol_depth_rg8_encode(NAN, xy);
    cr_assert(xy[0] == 0 && xy[1] == 0);
    sol_depth_rg8_encode(2.0, xy);
    cr_assert_eq(sol_depth_rg8_decode(xy), 1.0);
    double worst = 0.0, worst_rounded = 0.0;
    for (int i = 0; i <= 200000; ++i) {
        double d = i / 200000.0;
        sol_depth_rg8_encode(d, xy);
        worst = fmax(worst, fabs(sol_depth_rg8_decode(xy) - d));
        sol_depth_rg8_encode_rounded_x(d, xy);
        worst_rounded = fmax(worst_rounded, fabs(sol_depth_rg8_decode(xy) - d));
    }
    cr_assert_leq(worst, 0.5 / 65025.0 + 1e-15);
    cr_assert_gt(worst_rounded, 0.9 / 255.0); /* one x step lost when frac >= 0.5 */
}

/* ---------------- tone maps and the lower bounds (D10-D12) ---------------- */

Test(hdr, d11_exponential_lower_bound_to_the_talks_digits)
{
    double c;
    cr_assert_eq(sol_tonemap_lower_bound(SOL_TONEMAP_EXPONENTIAL, 1.0 / 510.0, &c), SOL_OK);
    cr_assert_float_eq(c, log(510.0 / 509.0), 1e-15);
    cr_assert_float_eq(c, 0.00196271, 5e-9); /* the talk's figure (its sign is a slip: -ln(509/510)) */
}

Test(hdr, d12_filmic_lower_bound_original_curve_gives_the_talks_digits)
{
    double c;
    cr_assert_eq(sol_tonemap_lower_bound(SOL_TONEMAP_FILMIC_HBD, 1.0 / 510.0, &c), SOL_OK);
    cr_assert_float_eq(c, 0.0119052, 5e-8);
    /* the formula as printed on the slide gives a different bound (documented difference) */
    cr_assert_eq(sol_tonemap_lower_bound(SOL_TONEMAP_FILMIC_SLIDE, 1.0 / 510.0, &c), SOL_OK);
    cr_assert_gt(c, 0.02);
    cr_assert_float_eq(sol_tonemap_apply(SOL_TONEMAP_FILMIC_SLIDE, c), 1.0 / 510.0, 1e-12);
}

Test(hdr, tonemap_inverse_round_trips_and_agrees_with_the_solver)
{
    for (int op = 0; op < SOL_TONEMAP_COUNT; ++op)
        for (int i = 1; i < 200; ++i) {
            double y = i / 200.0, x, xi;
            if (op == SOL_TONEMAP_FILMIC_SLIDE && y < 0.0013)
                continue; /* below the slide curve's jump */
            cr_assert_eq(sol_tonemap_inverse((sol_tonemap)op, y, &x), SOL_OK);
            cr_assert_float_eq(sol_tonemap_apply((sol_tonemap)op, x), y, 1e-9, "%s y %g", sol_tonemap_name(op), y);
            sol_root_options opt = {SOL_ROOT_SAFE_NEWTON, 1e-13, 300};
            cr_assert_eq(sol_tonemap_inverse_iterative((sol_tonemap)op, y, &opt, &xi, NULL), SOL_OK);
            cr_assert_float_eq(xi, x, 1e-9 * fmax(1.0, x), "%s y %g", sol_tonemap_name(op), y);
        }
}

Test(hdr, tonemap_edges)
{
    for (int op = 0; op < SOL_TONEMAP_COUNT; ++op) {
        sol_tonemap t = (sol_tonemap)op;
        cr_assert_eq(sol_tonemap_apply(t, 0.0), 0.0);
        cr_assert_eq(sol_tonemap_apply(t, -0.0), 0.0);
        cr_assert_eq(sol_tonemap_apply(t, -5.0), 0.0);
        cr_assert(isnan(sol_tonemap_apply(t, NAN)));
        cr_assert_float_eq(sol_tonemap_apply(t, INFINITY), 1.0, 1e-12);
        double tiny = sol_tonemap_apply(t, 4.9e-324), huge = sol_tonemap_apply(t, 1e300);
        cr_assert(isfinite(tiny) && tiny >= 0.0);
        cr_assert(huge <= 1.0 && huge > 0.99);
        double x = 42.0;
        cr_assert_eq(sol_tonemap_inverse(t, NAN, &x), SOL_ERR_NONFINITE);
        cr_assert_eq(sol_tonemap_inverse(t, -0.1, &x), SOL_ERR_OUT_OF_RANGE);
        cr_assert_eq(sol_tonemap_inverse(t, 1.5, &x), SOL_ERR_OUT_OF_RANGE);
        cr_assert_eq(sol_tonemap_inverse(t, 0.5, NULL), SOL_ERR_NULL_ARG);
        cr_assert_eq(x, 42.0);
        cr_assert_eq(sol_tonemap_inverse(t, 0.0, &x), SOL_OK);
        cr_assert_eq(x, 0.0);
    }
    double x = 1.0;
    cr_assert_eq(sol_tonemap_inverse(SOL_TONEMAP_EXPONENTIAL, 1.0, &x), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(sol_tonemap_inverse(SOL_TONEMAP_ACES_FIT, 1.0, &x), SOL_OK); /* the fit reaches 1 */
    cr_assert_eq(sol_tonemap_inverse(SOL_TONEMAP_COUNT, 0.5, &x), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_tonemap_lower_bound(SOL_TONEMAP_EXPONENTIAL, 0.0, &x), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(sol_tonemap_lower_bound(SOL_TONEMAP_EXPONENTIAL, NAN, &x), SOL_ERR_NONFINITE);
    sol_root_options starved = {SOL_ROOT_BISECTION, 1e-15, 3};
    int it = 0;
    cr_assert_eq(sol_tonemap_inverse_iterative(SOL_TONEMAP_REINHARD, 0.5, &starved, &x, &it), SOL_ERR_NO_CONVERGENCE);
    cr_assert_eq(it, 3);
    cr_assert(isfinite(x));
}

/* ---------------- ACES (S3) ---------------- */

Test(hdr, s3_aces_reference_mid_grey_and_fit_error)
{
    /* both splines pass through their mid anchors: 0.18 -> 4.8 nits -> 4.8 cd/m^2 */
    cr_assert_float_eq(sol_aces_reference(0.18), pow((4.8 - 0.02) / (48.0 - 0.02), 0.9811), 1e-9);
    cr_assert_eq(sol_aces_reference(0.0), sol_aces_reference(-1.0));
    cr_assert_eq(sol_aces_reference(1e9), 1.0);
    double worst = 0.0;
    for (int i = 0; i <= 20000; ++i) {
        double x = 16.0 * i / 20000.0;
        worst = fmax(worst, fabs(sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x) - sol_aces_reference(2.0 * x)));
    }
    cr_assert_float_eq(worst, 0.0138, 5e-4, "one-stop pre-exposed max error %g", worst);
}

/* Hill's ACESFitted (S3's second reference): the published curve at mid grey, grey in -> grey out
 * (matrix rows sum to 1), saturated colours stay in [0, 1], and the extremes. */
Test(hdr, s3_hill_aces_fit_curve_grey_and_extremes)
{
    double v = 0.18, expect = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
    cr_assert_float_eq(sol_aces_hill_curve(0.18), expect, 1e-15);
    cr_assert_float_eq(sol_aces_hill_curve(1e300), 1.0 / 0.983729, 1e-12);
    cr_assert_float_eq(sol_aces_hill_curve(INFINITY), 1.0 / 0.983729, 1e-12);
    cr_assert(isnan(sol_aces_hill_curve(NAN)));
    cr_assert(sol_aces_hill_curve(0.0) < 0.0 && sol_aces_hill_curve(0.0) > -4e-4, "a small negative toe");
    cr_assert(isfinite(sol_aces_hill_curve(-0.22)) && isfinite(sol_aces_hill_curve(5e-324)));
    double grey[3] = {0.18, 0.18, 0.18}, out[3];
    sol_aces_hill_fit(grey, out);
    for (int c = 0; c < 3; ++c)
        cr_assert_float_eq(out[c], expect, 1e-4, "channel %d: %g", c, out[c]);
    const double cases[][3] = {{1e300, 0, 0}, {DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, DBL_MAX, 0}, {INFINITY, 0, 0},
                               {-INFINITY, 1, 1}, {5e-324, 0, -0.0}, {100, 0, 0}, {0, 0, 100}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        sol_aces_hill_fit(cases[i], out);
        for (int c = 0; c < 3; ++c)
            cr_assert(out[c] >= 0.0 && out[c] <= 1.0, "case %zu channel %d: %g", i, c, out[c]);
    }
    double aliased[3] = {2, 1, 0.5}, copy[3];
    sol_aces_hill_fit(aliased, copy);
    sol_aces_hill_fit(aliased, aliased);
    cr_assert(memcmp(copy, aliased, sizeof copy) == 0);
    double nan_in[3] = {NAN, 0.5, 0.5};
    sol_aces_hill_fit(nan_in, out);
    cr_assert(isnan(out[0]));
    /* Against the ACES 1.0 Rec.709 reference on grey the fit stays within a few hundredths. */
    double worst = 0.0;
    for (int i = 0; i <= 4000; ++i) {
        double x = 16.0 * i / 4000.0;
        worst = fmax(worst, fabs(fmin(fmax(sol_aces_hill_curve(x), 0.0), 1.0) - sol_aces_reference(x)));
    }
    cr_assert(worst < 0.05, "Hill vs ACES 1.0 reference on grey: %g", worst);
}

/* ---------------- LUTs and charts (M4) ---------------- */

static void identity(const double in[3], double out[3], void *ctx)
{
    (void)ctx;
    memcpy(out, in, 3 * sizeof *out);
}

static void linear_mix(const double in[3], double out[3], void *ctx)
{
    (void)ctx;
    out[0] = 0.5 * in[0] + 0.3 * in[1] + 0.2 * in[2];
    out[1] = 0.1 * in[0] + 0.8 * in[1] + 0.1 * in[2];
    out[2] = 0.2 * in[0] + 0.2 * in[1] + 0.6 * in[2];
}

Test(hdr, m4_lut_is_exact_on_affine_maps_for_both_interpolations)
{
    sol_lut3d id = {0}, mix = {0};
    cr_assert_eq(sol_lut3d_bake(5, identity, NULL, &id), SOL_OK);
    cr_assert_eq(sol_lut3d_bake(2, linear_mix, NULL, &mix), SOL_OK);
    for (int i = 0; i < 1000; ++i) {
        double u, v, in[3], a[3], b[3];
        sol_r2_point((uint64_t)i, &u, &v);
        in[0] = u;
        in[1] = v;
        in[2] = fmod(u + v * 0.37, 1.0);
        for (int interp = 0; interp < 2; ++interp) {
            double want[3];
            sol_lut3d_apply(&id, (sol_lut_interp)interp, in, a);
            sol_lut3d_apply(&mix, (sol_lut_interp)interp, in, b);
            linear_mix(in, want, NULL);
            for (int c = 0; c < 3; ++c) {
                cr_assert_float_eq(a[c], in[c], 1e-6);
                cr_assert_float_eq(b[c], want[c], 1e-6);
            }
        }
    }
    double edge[3] = {-1.0, NAN, 2.0}, out[3];
    sol_lut3d_apply(&id, SOL_LUT_TETRAHEDRAL, edge, out);
    cr_assert(out[0] == 0.0 && out[1] == 0.0 && out[2] == 1.0f);
    sol_lut3d lut = {0};
    cr_assert_eq(sol_lut3d_bake(1, identity, NULL, &lut), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_lut3d_bake(4, NULL, NULL, &lut), SOL_ERR_NULL_ARG);
    cr_assert_null(lut.data);
    sol_lut3d_free(&id);
    sol_lut3d_free(&mix);
    sol_lut3d_free(&id); /* a second free is harmless: the first one reset the table */
    cr_assert(id.data == NULL && id.size == 0);
}

static char *temp_png(void)
{
    static char path[] = "/tmp/sol_hdr_chart_XXXXXX";
    int fd = mkstemp(path);
    cr_assert_geq(fd, 0);
    close(fd);
    return path;
}

Test(hdr, m4_chart_round_trip_through_an_8bit_png_is_exact_for_16)
{
    sol_lut3d id = {0}, back = {0};
    sol_image image = {0}, read = {0};
    cr_assert_eq(sol_lut3d_bake(16, identity, NULL, &id), SOL_OK);
    cr_assert_eq(sol_image_alloc(&image, 300, 20, 3), SOL_OK);
    cr_assert_eq(sol_lut3d_chart_write(&id, &image, 10, 2), SOL_OK);
    cr_assert_eq(sol_lut3d_chart_write(&id, &image, 50, 2), SOL_ERR_INVALID_ARG); /* 50 + 256 > 300 */
    char *path = temp_png();
    cr_assert_eq(sol_png_write(path, &image, 8), SOL_OK);
    cr_assert_eq(sol_png_read(path, &read, NULL), SOL_OK);
    unlink(path);
    cr_assert_eq(sol_lut3d_chart_read(&read, 10, 2, 16, &back), SOL_OK);
    for (int i = 0; i < 16 * 16 * 16 * 3; ++i)
        cr_assert_eq(back.data[i], id.data[i], "entry %d", i); /* i/15 = 17i/255: exact in 8 bits */
    sol_lut3d_free(&id);
    sol_lut3d_free(&back);
    sol_image_free(&image);
    sol_image_free(&read);
}

/* ---------------- CIEDE2000 (Sharma, Wu, Dalal 2005, table 1) ---------------- */

Test(hdr, ciede2000_matches_sharmas_test_pairs)
{
    const double pairs[][7] = {
        {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
        {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
        {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
        {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
        {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; ++i) {
        cr_assert_float_eq(sol_ciede2000(pairs[i], pairs[i] + 3), pairs[i][6], 1e-4, "pair %zu", i);
        cr_assert_float_eq(sol_ciede2000(pairs[i] + 3, pairs[i]), pairs[i][6], 1e-4, "pair %zu swapped", i);
    }
    double white[3] = {1, 1, 1}, lab[3];
    sol_srgb_to_lab(white, lab);
    cr_assert_float_eq(lab[0], 100.0, 1e-2);
    cr_assert_float_eq(lab[1], 0.0, 1e-2);
    cr_assert_float_eq(lab[2], 0.0, 1e-2);
}

Test(hdr, grade_zero_is_identity_and_output_stays_in_the_cube)
{
    sol_grade none = {0}, wild = {.saturation = 3.0, .contrast = 1.0, .hue_degrees = 77.0,
                                  .lift = {0.1, -0.5, 0}, .gamma = {2, 0.3, 1}, .gain = {1.5, 1, 0.2}};
    for (int i = 0; i < 500; ++i) {
        double u, v, in[3], out[3];
        sol_r2_point((uint64_t)i, &u, &v);
        in[0] = u;
        in[1] = v;
        in[2] = 1.0 - u;
        sol_grade_apply(&none, in, out);
        for (int c = 0; c < 3; ++c)
            cr_assert_float_eq(out[c], in[c], 1e-12);
        sol_grade_apply(&wild, in, out);
        for (int c = 0; c < 3; ++c)
            cr_assert(out[c] >= 0.0 && out[c] <= 1.0);
    }
}

/* ---------------- exposure (S6) ---------------- */

Test(hdr, s6_ev_key_adaptation)
{
    cr_assert_float_eq(sol_ev100_from_luminance(0.125), 0.0, 1e-15);
    cr_assert_float_eq(sol_luminance_from_ev100(10.0), 128.0, 1e-12);
    cr_assert_float_eq(sol_krawczyk_key(0.0), 0.03, 1e-15);
    cr_assert_float_eq(sol_krawczyk_key(9.0), 1.03 - 2.0 / 3.0, 1e-15);
    cr_assert_eq(sol_adapt_exponential(1.0, 5.0, 0.0, 3.0), 1.0);
    cr_assert_float_eq(sol_adapt_exponential(1.0, 5.0, 1e3, 3.0), 5.0, 1e-12);
    cr_assert_eq(sol_adapt_exponential(1.0, 5.0, NAN, 3.0), 1.0);
    cr_assert_eq(sol_adapt_exponential(1.0, 5.0, -1.0, 3.0), 1.0);
    double e = 7.0;
    cr_assert_eq(sol_exposure_from_luminance(0.0, 0.0, &e), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_exposure_from_luminance(NAN, 0.0, &e), SOL_ERR_NONFINITE);
    cr_assert_eq(e, 7.0);
    cr_assert_eq(sol_exposure_from_luminance(0.18, 1.0, &e), SOL_OK);
    cr_assert_float_eq(e, 2.0, 1e-12);
}

Test(hdr, s6_histogram_meter_constant_image_skips_and_errors)
{
    float lum[1000];
    for (int i = 0; i < 1000; ++i)
        lum[i] = 3.0f;
    double m = 0.0;
    sol_meter_options none = {.skip_dark = -1, .skip_bright = -1};
    cr_assert_eq(sol_histogram_meter(lum, 1000, &none, &m, NULL), SOL_OK);
    cr_assert_float_eq(m, 3.0, 1e-6); /* the two-bin split keeps the mean EV exact */
    cr_assert_eq(sol_histogram_meter(lum, 1000, NULL, &m, NULL), SOL_OK);
    cr_assert_float_eq(sol_ev100_from_luminance(m), sol_ev100_from_luminance(3.0), 0.5); /* within a bin */
    /* half the pixels at EV 0, half at EV 12: default skip (60% dark) meters the bright half */
    for (int i = 0; i < 1000; ++i)
        lum[i] = i < 500 ? 0.125f : 512.0f;
    lum[7] = NAN;
    lum[8] = -1.0f;
    size_t ignored = 0;
    cr_assert_eq(sol_histogram_meter(lum, 1000, NULL, &m, &ignored), SOL_OK);
    cr_assert_eq(ignored, 2);
    cr_assert_float_eq(sol_ev100_from_luminance(m), 12.0, 0.5);
    double untouched = 5.0;
    cr_assert_eq(sol_histogram_meter(lum, 0, NULL, &untouched, NULL), SOL_ERR_INVALID_ARG);
    sol_meter_options greedy = {.skip_dark = 0.7, .skip_bright = 0.4};
    cr_assert_eq(sol_histogram_meter(lum, 1000, &greedy, &untouched, NULL), SOL_ERR_INVALID_ARG);
    float nans[3] = {NAN, NAN, INFINITY};
    cr_assert_eq(sol_histogram_meter(nans, 3, NULL, &untouched, NULL), SOL_ERR_INVALID_ARG);
    cr_assert_eq(untouched, 5.0);
}
