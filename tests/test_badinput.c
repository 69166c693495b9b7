/* test_badinput.c - issue 12: table-driven bad input for the public API, one Test per module.
 * Each case calls a public function with NULL, bad enums, zero/negative/huge sizes, NaN, +-Inf,
 * subnormals, -0, the largest finite values or a documented edge, and checks the documented
 * status (outputs untouched on error, sentinel values) or, for total functions, that the result
 * is finite for every non-NaN input (and never +-Inf). Every Test logs its totals
 * ("badinput <module>: N cases, M passing") and fails if any case fails. */
#include <criterion/criterion.h>
#include <criterion/logging.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <string.h>

#include "sol_brdf.h"
#include "sol_core.h"
#include "sol_hdr.h"
#include "sol_lighting.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"
#include "sol_pipeline.h"
#include "sol_screen.h"
#include "sol_textures.h"

static int cases, passing;

static void check(int ok, const char *what, int line)
{
    ++cases;
    if (ok)
        ++passing;
    else
        cr_log_error("bad-input case failed (line %d): %s", line, what);
}

/* status equals the documented one */
#define ST(call, want) check((call) == (want), #call " == " #want, __LINE__)
/* a condition (untouched output, finite value) */
#define OK(cond) check((cond), #cond, __LINE__)
/* total function: never +-Inf; NaN only if an input was NaN */
#define TOTAL(expr, nan_in)                                                                                    \
    do {                                                                                                       \
        double v_ = (expr);                                                                                    \
        check(!isinf(v_) && ((nan_in) || !isnan(v_)), #expr " finite", __LINE__);                              \
    } while (0)

static void report(const char *module)
{
    cr_log_info("badinput %s: %d cases, %d passing", module, cases, passing);
    fprintf(stderr, "badinput %s: %d cases, %d passing\n", module, cases, passing);
    cr_assert_eq(cases, passing, "%s: %d of %d bad-input cases failed", module, cases - passing, cases);
}

static const double specials[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 5e-324, -5e-324, DBL_MIN, 1e-300, 1e-160,
                                  1e-5, 0.5, 1.0, 1000.5, 1e160, 1e300, DBL_MAX, -DBL_MAX, -1.0};
#define NSPEC (sizeof specials / sizeof *specials)

/* Unit-ish and extreme direction vectors (axis, near-axis, grazing, huge, tiny, zero, NaN). */
static const double dirs[][3] = {{0, 0, 1},     {0, 0, -1},   {1, 0, 0},       {0, 1e-300, 1},      {1, 0, 1e-300},
                                 {1, 0, 5e-324}, {0.6, 0, 0.8}, {1e300, 0, 1e300}, {1e-300, 0, 1e-300}, {0, 0, 0},
                                 {-0.0, -0.0, 1}, {NAN, 0, 1},  {INFINITY, 0, 1}, {0, 0, DBL_MAX}};
#define NDIRS (sizeof dirs / sizeof *dirs)

static int has_nan3(const double v[3])
{
    return isnan(v[0]) || isnan(v[1]) || isnan(v[2]);
}

/* within rounding of unit length (the zero vector counts: it has a documented answer) */
static int unitish(const double v[3])
{
    double n = sqrt(sol_dot3(v, v));
    return n == 0.0 || fabs(n - 1.0) < 1e-6;
}

Test(badinput, brdf)
{
    for (size_t i = 0; i < NSPEC; ++i)
        for (size_t j = 0; j < NSPEC; ++j) {
            double a = specials[i], b = specials[j];
            int nan_in = isnan(a) || isnan(b);
            TOTAL(sol_phong_raw(a, b), nan_in);
            TOTAL(sol_phong_normalized(a, b), nan_in);
            TOTAL(sol_blinn_phong_raw(a, b), nan_in);
            TOTAL(sol_beckmann_ndf(a, b), nan_in);
            TOTAL(sol_ggx_ndf(a, b), nan_in);
            TOTAL(sol_smith_g1_ggx(a, b), nan_in);
            TOTAL(sol_smith_g1_beckmann(a, b), nan_in);
            TOTAL(sol_fresnel_schlick(a, b), nan_in);
        }
    for (size_t i = 0; i < NSPEC; ++i) {
        double n = specials[i];
        TOTAL(sol_phong_norm_factor(n), isnan(n));
        TOTAL(sol_phong_lobe_norm_factor(n), isnan(n));
        TOTAL(sol_blinn_phong_norm_factor_exact(n), isnan(n));
        TOTAL(sol_blinn_phong_norm_factor_approx(n), isnan(n));
    }
    /* microfacet BRDFs over directions x alpha (f0 = 0.04 and extremes) */
    static const double alphas[] = {NAN, 0.0, -1.0, 5e-324, 1e-300, 1e-160, 1e-5, 0.3, 1.0, 1e160, DBL_MAX, INFINITY};
    for (size_t i = 0; i < NDIRS; ++i)
        for (size_t j = 0; j < NDIRS; ++j)
            for (size_t k = 0; k < sizeof alphas / sizeof *alphas; ++k) {
                const double *v = dirs[i], *l = dirs[j];
                double al = alphas[k];
                /* directions far from unit length (or with an Inf) are outside the documented
                 * domain: for them NaN-or-finite (never Inf) is what is checked */
                int nan_in = has_nan3(v) || has_nan3(l) || isnan(al) || !unitish(v) || !unitish(l);
                TOTAL(sol_cook_torrance(v, l, SOL_NDF_GGX, al, 0.04), nan_in);
                TOTAL(sol_cook_torrance(v, l, SOL_NDF_BECKMANN, al, 1.0), nan_in);
                TOTAL(sol_ward_brdf(v, l, al, 0.2), nan_in);
                TOTAL(sol_ward_ndf(v, al, al), has_nan3(v) || isnan(al) || !unitish(v));
            }
    /* Spherical Gaussians: sharpness from 0 to +Inf */
    for (size_t i = 0; i < NSPEC; ++i)
        for (size_t j = 0; j < NDIRS; ++j) {
            double s = specials[i];
            sol_sg g = {.axis = {0, 0, 1}, .sharpness = s, .amplitude = 1.0};
            int nan_in = isnan(s) || has_nan3(dirs[j]) || !unitish(dirs[j]);
            if (isinf(s) && s < 0.0)
                nan_in = 1; /* -Inf sharpness on the axis: -Inf * 0 */
            TOTAL(sol_sg_eval(&g, dirs[j]), nan_in);
        }
    sol_sg inf_sg = {.axis = {0, 0, 1}, .sharpness = INFINITY, .amplitude = 3.0};
    OK(sol_sg_eval(&inf_sg, dirs[0]) == 3.0);
    OK(sol_sg_integral(&inf_sg) == 0.0);
    /* fallible: quadrature and Gauss-Legendre */
    double x[4] = {7, 7, 7, 7}, w[4] = {7, 7, 7, 7};
    ST(sol_gauss_legendre(0, x, w), SOL_ERR_INVALID_ARG);
    ST(sol_gauss_legendre(-1, x, w), SOL_ERR_INVALID_ARG);
    ST(sol_gauss_legendre(257, x, w), SOL_ERR_INVALID_ARG);
    ST(sol_gauss_legendre(INT_MAX, x, w), SOL_ERR_INVALID_ARG);
    ST(sol_gauss_legendre(4, NULL, w), SOL_ERR_NULL_ARG);
    ST(sol_gauss_legendre(4, x, NULL), SOL_ERR_NULL_ARG);
    OK(x[0] == 7 && w[0] == 7);
    ST(sol_gauss_legendre(1, x, w), SOL_OK);
    OK(x[0] == 0.0 && w[0] == 2.0);
    double res = 7, err = 7;
    const double zero[3] = {0, 0, 0}, nanv[3] = {NAN, 0, 1}, up[3] = {0, 0, 1};
    ST(sol_sphere_integrate(NULL, NULL, up, NULL, &res, &err), SOL_ERR_NULL_ARG);
    ST(sol_sphere_integrate_mc(NULL, NULL, 4, 1, &res, &err), SOL_ERR_NULL_ARG);
    OK(res == 7 && err == 7);
    (void)zero;
    (void)nanv;
    /* Ward SG fit: NaN, Inf, zero, negative alpha and k_max out of range are refused untouched */
    sol_sg lobes[4];
    memset(lobes, 0x5a, sizeof lobes);
    sol_sg_fit_error e[2];
    static const double bad_alpha[] = {NAN, INFINITY, 0.0, -0.1, -INFINITY};
    for (size_t i = 0; i < sizeof bad_alpha / sizeof *bad_alpha; ++i) {
        OK(sol_ward_sg_fit(bad_alpha[i], 0.2, 1, NULL, lobes, e, NULL) != SOL_OK);
        OK(sol_ward_sg_fit(0.2, bad_alpha[i], 1, NULL, lobes, e, NULL) != SOL_OK);
    }
    OK(sol_ward_sg_fit(0.2, 0.2, 0, NULL, lobes, e, NULL) != SOL_OK);
    OK(sol_ward_sg_fit(0.2, 0.2, -1, NULL, lobes, e, NULL) != SOL_OK);
    ST(sol_ward_sg_fit(0.2, 0.2, 1, NULL, NULL, e, NULL), SOL_ERR_NULL_ARG);
    unsigned char pattern[sizeof lobes];
    memset(pattern, 0x5a, sizeof pattern);
    OK(memcmp(lobes, pattern, sizeof lobes) == 0);
    report("brdf");
}

Test(badinput, core)
{
    /* angle3 over every pair of directions: finite unless a NaN or Inf component */
    for (size_t i = 0; i < NDIRS; ++i)
        for (size_t j = 0; j < NDIRS; ++j) {
            double a = sol_angle3(dirs[i], dirs[j]);
            int bad = has_nan3(dirs[i]) || has_nan3(dirs[j]) || isinf(dirs[i][0]) || isinf(dirs[j][0]);
            OK(bad ? isnan(a) : (a >= 0.0 && a <= M_PI));
        }
    for (int bits = -1; bits <= 34; ++bits)
        for (size_t i = 0; i < NSPEC; ++i) {
            uint32_t c = sol_unorm_encode(specials[i], bits);
            OK(bits >= 1 && bits <= 32 ? c <= (UINT32_MAX >> (32 - bits)) : c == 0);
            double d = sol_unorm_decode(c, bits);
            OK(isfinite(d) && d >= 0.0 && d <= 1.0);
        }
    size_t out = 77;
    OK(sol_size_mul(&out, SIZE_MAX, 2) == 0 && out == 77);
    OK(sol_size_mul(&out, SIZE_MAX, 1) == 1 && out == SIZE_MAX);
    OK(sol_size_mul(&out, 0, SIZE_MAX) == 1 && out == 0);
    sol_image img = {.width = 5};
    ST(sol_image_alloc(&img, 0, 4, 3), SOL_ERR_INVALID_ARG);
    ST(sol_image_alloc(&img, -1, 4, 3), SOL_ERR_INVALID_ARG);
    ST(sol_image_alloc(&img, 4, 4, 0), SOL_ERR_INVALID_ARG);
    ST(sol_image_alloc(&img, 4, 4, 5), SOL_ERR_INVALID_ARG);
    ST(sol_image_alloc(NULL, 4, 4, 3), SOL_ERR_NULL_ARG);
    OK(img.width == 5 && img.data == NULL);
    sol_image_free(NULL);
    OK(sol_status_string((sol_status)-1) != NULL);
    OK(sol_status_string(SOL_STATUS_COUNT) != NULL);
    for (size_t i = 0; i < NSPEC; ++i) {
        double s = sol_srgb_encode(specials[i]), d = sol_srgb_decode(specials[i]);
        OK(isfinite(s) && s >= 0.0 && s <= 1.0 && isfinite(d) && d >= 0.0 && d <= 1.0);
    }
    ST(sol_read_limits_check(NULL, 0, 1, 1, 4), SOL_ERR_INVALID_ARG);
    ST(sol_read_limits_check(NULL, -5, 1, 1, 4), SOL_ERR_INVALID_ARG);
    ST(sol_read_limits_check(NULL, INT64_MAX, INT64_MAX, 1, 4), SOL_ERR_LIMIT);
    ST(sol_read_limits_check(NULL, 1 << 20, 1 << 20, 1, 4), SOL_ERR_LIMIT);
    ST(sol_read_limits_check(NULL, 64, 64, 1, UINT64_MAX), SOL_ERR_LIMIT);
    ST(sol_read_limits_check(NULL, 64, 64, 1, 4), SOL_OK);
    report("core");
}

Test(badinput, pipeline)
{
    const sol_gbuffer_layout *layout = (const sol_gbuffer_layout *)&cases;
    ST(sol_gbuffer_layout_get((sol_gbuffer_kind)-1, &layout), SOL_ERR_INVALID_ARG);
    ST(sol_gbuffer_layout_get((sol_gbuffer_kind)1000, &layout), SOL_ERR_INVALID_ARG);
    ST(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, NULL), SOL_ERR_NULL_ARG);
    OK(layout == (const sol_gbuffer_layout *)&cases);
    ST(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, &layout), SOL_OK);
    unsigned bits = 9;
    ST(sol_gbuffer_bits_per_pixel(NULL, &bits), SOL_ERR_NULL_ARG);
    ST(sol_gbuffer_bits_per_pixel(layout, NULL), SOL_ERR_NULL_ARG);
    OK(bits == 9);
    uint64_t bytes = 5;
    static const int sizes[] = {0, -1, INT_MIN};
    for (size_t i = 0; i < 3; ++i) {
        ST(sol_gbuffer_bytes(layout, sizes[i], 720, 1, &bytes), SOL_ERR_INVALID_ARG);
        ST(sol_gbuffer_bytes(layout, 1280, sizes[i], 1, &bytes), SOL_ERR_INVALID_ARG);
    }
    static const int samples[] = {0, -1, 3, 16, INT_MAX};
    for (size_t i = 0; i < sizeof samples / sizeof *samples; ++i)
        ST(sol_gbuffer_bytes(layout, 1280, 720, samples[i], &bytes), SOL_ERR_INVALID_ARG);
    ST(sol_gbuffer_bytes(NULL, 1280, 720, 1, &bytes), SOL_ERR_NULL_ARG);
    ST(sol_gbuffer_bytes(layout, 1280, 720, 1, NULL), SOL_ERR_NULL_ARG);
    ST(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 8, &bytes), SOL_ERR_OUT_OF_RANGE);
    OK(bytes == 5);
    ST(sol_gbuffer_bytes(layout, INT_MAX, 1, 8, &bytes), SOL_OK);
    OK(bytes == (uint64_t)INT_MAX * 64u);
    OK(strcmp(sol_pixel_format_name((sol_pixel_format)-7), "unknown") == 0);
    OK(sol_pixel_format_bits((sol_pixel_format)INT_MAX) == 0);
    report("pipeline");
}

Test(badinput, textures)
{
    static const sol_transfer curves[] = {{SOL_TRANSFER_LINEAR, 0}, {SOL_TRANSFER_POWER, 0}, {SOL_TRANSFER_SRGB, 0},
                                          {SOL_TRANSFER_X360_PWL, 0}, {SOL_TRANSFER_POWER, 1e-300}};
    for (size_t c = 0; c < sizeof curves / sizeof *curves; ++c)
        for (size_t i = 0; i < NSPEC; ++i) {
            double x = specials[i], out = 42.0;
            sol_status st = sol_transfer_encode(&curves[c], x, &out);
            OK(isfinite(x) ? (st == SOL_OK && isfinite(out) && out >= 0.0 && out <= 1.0)
                           : (st == SOL_ERR_NONFINITE && out == 42.0));
            out = 42.0;
            st = sol_transfer_decode(&curves[c], x, &out);
            OK(isfinite(x) ? (st == SOL_OK && isfinite(out) && out >= 0.0 && out <= 1.0)
                           : (st == SOL_ERR_NONFINITE && out == 42.0));
        }
    static const sol_transfer bad[] = {{(sol_transfer_kind)-1, 0},   {SOL_TRANSFER_KIND_COUNT, 0},
                                       {SOL_TRANSFER_POWER, -1.0},   {SOL_TRANSFER_POWER, NAN},
                                       {SOL_TRANSFER_POWER, INFINITY}};
    for (size_t c = 0; c < sizeof bad / sizeof *bad; ++c) {
        double out = 42.0;
        uint8_t code = 9;
        ST(sol_transfer_encode(&bad[c], 0.5, &out), SOL_ERR_INVALID_ARG);
        ST(sol_transfer_decode(&bad[c], 0.5, &out), SOL_ERR_INVALID_ARG);
        ST(sol_transfer_quantize8(&bad[c], 0.5, &code), SOL_ERR_INVALID_ARG);
        OK(out == 42.0 && code == 9);
    }
    double out = 42.0;
    ST(sol_transfer_encode(NULL, 0.5, &out), SOL_ERR_NULL_ARG);
    ST(sol_transfer_encode(&curves[0], 0.5, NULL), SOL_ERR_NULL_ARG);
    ST(sol_transfer_slope(&curves[1], 0.0, &out), SOL_ERR_OUT_OF_RANGE);
    ST(sol_transfer_slope(&curves[2], 1.5, &out), SOL_ERR_OUT_OF_RANGE);
    ST(sol_transfer_slope(&curves[2], -0.0, &out), SOL_OK);
    OK(isfinite(out));
    /* BC1 sizes */
    OK(sol_bc1_size(0, 4) == 0 && sol_bc1_size(-4, 4) == 0 && sol_bc1_size(INT_MIN, INT_MIN) == 0);
    OK(sol_bc1_size(INT_MAX, 1) == (size_t)536870912 * 8u);
    OK(sol_bc1_size(1, 1) == 8 && sol_bc1_size(5, 5) == 32);
    float rgb[16][3];
    for (int i = 0; i < 16; ++i)
        rgb[i][0] = rgb[i][1] = rgb[i][2] = 0.5f;
    uint8_t block[8] = {1, 2, 3, 4, 5, 6, 7, 8}, keep[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    static const float badv[] = {NAN, INFINITY, -INFINITY, -1e-30f, 1.0000001f, FLT_MAX, -FLT_MAX};
    for (size_t i = 0; i < sizeof badv / sizeof *badv; ++i) {
        rgb[5][1] = badv[i];
        sol_status st = sol_bc1_encode_block((const float(*)[3])rgb, NULL, block);
        OK(st == (isfinite(badv[i]) ? SOL_ERR_OUT_OF_RANGE : SOL_ERR_NONFINITE));
        OK(memcmp(block, keep, 8) == 0);
    }
    rgb[5][1] = 5e-45f; /* a float subnormal is in range */
    ST(sol_bc1_encode_block((const float(*)[3])rgb, NULL, block), SOL_OK);
    rgb[5][1] = -0.0f;
    ST(sol_bc1_encode_block((const float(*)[3])rgb, NULL, block), SOL_OK);
    ST(sol_bc1_encode_block(NULL, NULL, block), SOL_ERR_NULL_ARG);
    sol_image img = {0};
    ST(sol_bc1_decode(block, 0, 4, &img), SOL_ERR_INVALID_ARG);
    ST(sol_bc1_decode(block, -4, 4, &img), SOL_ERR_INVALID_ARG);
    ST(sol_bc1_decode(NULL, 4, 4, &img), SOL_ERR_NULL_ARG);
    OK(img.data == NULL);
    /* renorm at the float range */
    float data[3] = {-FLT_MAX, FLT_MAX, 1.0f};
    sol_image im = {.width = 3, .height = 1, .channels = 1, .data = data};
    sol_renorm r;
    ST(sol_renorm_fit(&im, &r), SOL_OK);
    ST(sol_renorm_apply(&r, &im), SOL_OK);
    OK(isfinite(data[0]) && isfinite(data[1]) && isfinite(data[2]) && data[0] == 0.0f && data[1] == 1.0f);
    data[2] = NAN;
    float before = data[0];
    ST(sol_renorm_apply(&r, &im), SOL_ERR_NONFINITE);
    OK(data[0] == before);
    ST(sol_renorm_fit(NULL, &r), SOL_ERR_NULL_ARG);
    im.channels = 5;
    ST(sol_renorm_fit(&im, &r), SOL_ERR_INVALID_ARG);
    im.channels = 0;
    ST(sol_renorm_fit(&im, &r), SOL_ERR_INVALID_ARG);
    report("textures");
}

Test(badinput, hdr)
{
    for (size_t i = 0; i < NSPEC; ++i) {
        double x = specials[i];
        for (int op = 0; op < SOL_TONEMAP_COUNT; ++op) {
            double y = sol_tonemap_apply((sol_tonemap)op, x);
            OK(isnan(x) ? isnan(y) : (y >= 0.0 && y <= 1.0));
            double inv = 42.0;
            sol_status st = sol_tonemap_inverse((sol_tonemap)op, x, &inv);
            if (isnan(x))
                OK(st == SOL_ERR_NONFINITE && inv == 42.0);
            else if (st == SOL_OK)
                OK(isfinite(inv) && inv >= 0.0);
            else
                OK(st == SOL_ERR_OUT_OF_RANGE && inv == 42.0 && (x < 0.0 || x >= 1.0 || isinf(x)));
        }
        TOTAL(sol_krawczyk_key(x), isnan(x));
        for (size_t j = 0; j < NSPEC; ++j)
            if (isfinite(x) && isfinite(specials[j]))
                TOTAL(sol_adapt_exponential(x, specials[j], 0.5, 2.0), 0);
        TOTAL(sol_dfg_alpha_from_gloss(x), isnan(x));
        uint8_t xy[2] = {0, 0};
        sol_depth_rg8_encode(x, xy);
        double d = sol_depth_rg8_decode(xy);
        OK(isfinite(d) && d >= 0.0 && d <= 1.0 + 1.0 / 255.0);
        double e = 42.0;
        sol_status st = sol_exposure_from_luminance(x, 0.0, &e);
        OK(st == SOL_OK ? isfinite(e) : e == 42.0);
        st = sol_exposure_from_luminance(0.18, x, &e);
        OK(st == SOL_OK ? isfinite(e) : (e == 42.0 || isfinite(e)));
        float f = (float)x;
        float back = sol_half_to_float(sol_half_from_float(f));
        OK(isnan(f) ? isnan(back) : (isinf(f) ? isinf(back) : !isnan(back)));
    }
    double e = 42.0;
    ST(sol_exposure_from_luminance(1.0, 1e4, &e), SOL_ERR_OUT_OF_RANGE);
    ST(sol_exposure_from_luminance(1.0, -1e4, &e), SOL_OK);
    OK(e == 0.0);
    ST(sol_exposure_from_luminance(0.0, 0.0, &e), SOL_ERR_INVALID_ARG);
    ST(sol_exposure_from_luminance(-0.0, 0.0, &e), SOL_ERR_INVALID_ARG);
    ST(sol_exposure_from_luminance(NAN, 0.0, &e), SOL_ERR_NONFINITE);
    ST(sol_exposure_from_luminance(1.0, INFINITY, &e), SOL_ERR_NONFINITE);
    ST(sol_exposure_from_luminance(5e-324, 0.0, &e), SOL_ERR_OUT_OF_RANGE);
    ST(sol_exposure_from_luminance(1.0, 0.0, NULL), SOL_ERR_NULL_ARG);
    double inv = 42.0;
    ST(sol_tonemap_inverse((sol_tonemap)-1, 0.5, &inv), SOL_ERR_INVALID_ARG);
    ST(sol_tonemap_inverse(SOL_TONEMAP_COUNT, 0.5, &inv), SOL_ERR_INVALID_ARG);
    ST(sol_tonemap_inverse(SOL_TONEMAP_REINHARD, 0.5, NULL), SOL_ERR_NULL_ARG);
    OK(inv == 42.0);
    for (int op = 0; op < SOL_TONEMAP_COUNT; ++op) {
        ST(sol_tonemap_inverse((sol_tonemap)op, nextafter(1.0, 0.0), &inv), SOL_OK);
        OK(isfinite(inv));
    }
    /* RGBM */
    const float big[3] = {FLT_MAX, 1.0f, NAN};
    uint8_t px[4] = {1, 2, 3, 4};
    float rgb[3] = {9, 9, 9};
    ST(sol_rgbm_encode(big, 6.0, px), SOL_OK);
    static const double bad_range[] = {0.0, -0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad_range / sizeof *bad_range; ++i) {
        ST(sol_rgbm_encode(big, bad_range[i], px), SOL_ERR_INVALID_ARG);
        ST(sol_rgbm_decode(px, bad_range[i], rgb), SOL_ERR_INVALID_ARG);
    }
    OK(rgb[0] == 9);
    const uint8_t white[4] = {255, 255, 255, 255};
    ST(sol_rgbm_decode(white, DBL_MAX, rgb), SOL_ERR_OUT_OF_RANGE);
    ST(sol_rgbm_decode(white, 1e39, rgb), SOL_ERR_OUT_OF_RANGE);
    OK(rgb[0] == 9);
    ST(sol_rgbm_decode(white, 5e-324, rgb), SOL_OK);
    OK(isfinite(rgb[0]));
    ST(sol_rgbm_decode(NULL, 6.0, rgb), SOL_ERR_NULL_ARG);
    ST(sol_rgbm_encode(NULL, 6.0, px), SOL_ERR_NULL_ARG);
    report("hdr");
}

Test(badinput, lighting)
{
    sol_room_scene scene = {.wall_height = 3.0, .light = {0.0, 0.0, 2.0}, .radius = 10.0};
    double e = 42.0;
    for (size_t i = 0; i < NSPEC; ++i)
        for (size_t j = 0; j < NSPEC; ++j) {
            double px = specials[i], py = specials[j];
            e = 42.0;
            sol_status st = sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, px, py, &e);
            OK(isfinite(px) && isfinite(py) ? (st == SOL_OK && isfinite(e) && e >= 0.0)
                                            : (st == SOL_ERR_NONFINITE && e == 42.0));
        }
    for (size_t i = 0; i < NSPEC; ++i) {
        double h = specials[i];
        scene.light[2] = h;
        e = 42.0;
        sol_status st = sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0.5, 0.0, &e);
        if (!isfinite(h))
            OK(st == SOL_ERR_NONFINITE && e == 42.0);
        else if (!(h > 0.0))
            OK(st == SOL_ERR_INVALID_ARG && e == 42.0);
        else
            OK(st == SOL_OK ? isfinite(e) : (st == SOL_ERR_OUT_OF_RANGE && e == 42.0));
        st = sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0.0, 0.0, &e);
        OK(st == SOL_OK || st == SOL_ERR_OUT_OF_RANGE || st == SOL_ERR_NONFINITE || st == SOL_ERR_INVALID_ARG);
        OK(st == SOL_OK ? isfinite(e) : 1);
    }
    scene.light[2] = 2.0;
    e = 42.0;
    ST(sol_room_irradiance(&scene, NULL, (sol_light_mode)-1, 0, 0, &e), SOL_ERR_INVALID_ARG);
    ST(sol_room_irradiance(&scene, NULL, (sol_light_mode)77, 0, 0, &e), SOL_ERR_INVALID_ARG);
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_CLIPPED, 0, 0, &e), SOL_ERR_NULL_ARG);
    ST(sol_room_irradiance(NULL, NULL, SOL_LIGHT_UNSHADOWED, 0, 0, &e), SOL_ERR_NULL_ARG);
    scene.radius = 0.0;
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0, 0, &e), SOL_ERR_INVALID_ARG);
    scene.radius = -0.0;
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0, 0, &e), SOL_ERR_INVALID_ARG);
    scene.radius = 5e-324;
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0, 0, &e), SOL_OK);
    OK(e == 0.0);
    scene.radius = 10.0;
    scene.wall_count = -1;
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 0, 0, &e), SOL_ERR_INVALID_ARG);
    scene.wall_count = 1;
    ST(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, 0, 0, &e), SOL_ERR_NULL_ARG);
    OK(e == 0.0);
    /* DFG */
    double s = 42.0, b = 42.0;
    for (size_t i = 0; i < NSPEC; ++i) {
        double v = specials[i];
        sol_status st = sol_dfg_integrate(v, 0.5, 4, &s, &b);
        if (isnan(v) || isinf(v))
            OK(st == SOL_ERR_NONFINITE);
        else if (v < 0.0 || v > 1.0)
            OK(st == SOL_ERR_INVALID_ARG);
        else
            OK(st == SOL_OK && isfinite(s) && isfinite(b));
        st = sol_dfg_fit_polynomial(0.5, v, &s, &b);
        OK(st == SOL_OK ? isfinite(s) && isfinite(b) : 1);
    }
    s = b = 42.0;
    ST(sol_dfg_integrate(0.5, 0.5, 0, &s, &b), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_integrate(0.5, 0.5, -1, &s, &b), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_integrate(0.5, 0.5, 65537, &s, &b), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_integrate(0.5, 0.5, INT_MAX, &s, &b), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_integrate(0.5, 0.5, 4, NULL, &b), SOL_ERR_NULL_ARG);
    OK(s == 42.0 && b == 42.0);
    ST(sol_dfg_integrate(0.0, 0.0, 4, &s, &b), SOL_OK);
    OK(s == 0.0 && b == 0.0);
    sol_dfg_lut lut = {.size = 3};
    ST(sol_dfg_lut_build(1, 4, &lut), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_lut_build(4097, 4, &lut), SOL_ERR_INVALID_ARG);
    ST(sol_dfg_lut_build(INT_MIN, 4, &lut), SOL_ERR_INVALID_ARG);
    OK(lut.size == 3);
    report("lighting");
}

Test(badinput, screen)
{
    float depth[16];
    for (int i = 0; i < 16; ++i)
        depth[i] = 1.0f;
    sol_cbuffer cb;
    memset(&cb, 0x33, sizeof cb);
    sol_cbuffer keep;
    memcpy(&keep, &cb, sizeof cb);
    sol_cbuffer_options o = {.block = -1};
    ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_ERR_INVALID_ARG);
    o.block = INT_MIN;
    ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_ERR_INVALID_ARG);
    o.block = 2;
    o.downscale = (sol_downscale)-1;
    ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_ERR_INVALID_ARG);
    o.downscale = (sol_downscale)3;
    ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_ERR_INVALID_ARG);
    o.downscale = SOL_DOWNSCALE_MAX;
    ST(sol_cbuffer_build(depth, 0, 4, &o, &cb), SOL_ERR_INVALID_ARG);
    ST(sol_cbuffer_build(depth, 4, -4, &o, &cb), SOL_ERR_INVALID_ARG);
    ST(sol_cbuffer_build(NULL, 4, 4, &o, &cb), SOL_ERR_NULL_ARG);
    static const float baddepth[] = {NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < 3; ++i) {
        depth[7] = baddepth[i];
        ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_ERR_NONFINITE);
    }
    OK(memcmp(&cb, &keep, sizeof cb) == 0);
    depth[7] = FLT_MAX;
    depth[8] = -FLT_MAX;
    depth[9] = 1e-45f;
    static const int blocks[] = {0, 1, 3, 4, 5, 1 << 30, INT_MAX};
    for (size_t k = 0; k < sizeof blocks / sizeof *blocks; ++k) {
        o.block = blocks[k];
        ST(sol_cbuffer_build(depth, 4, 4, &o, &cb), SOL_OK);
        for (size_t i = 0; i < NSPEC; ++i) {
            double v = specials[i];
            sol_screen_bounds bb[] = {{.x0 = v, .x1 = 3, .y0 = 0, .y1 = 3, .znear = 0.5},
                                      {.x0 = 0, .x1 = v, .y0 = 0, .y1 = 3, .znear = 0.5},
                                      {.x0 = 0, .x1 = 3, .y0 = -DBL_MAX, .y1 = DBL_MAX, .znear = v}};
            for (int q = 0; q < 3; ++q) {
                int occ = 7, vis = 7;
                sol_status st = sol_cbuffer_test(&cb, &bb[q], -1, &occ, &vis);
                int nan_in = isnan(bb[q].x0) || isnan(bb[q].x1) || isnan(bb[q].y0) || isnan(bb[q].y1) ||
                             !isfinite(bb[q].znear);
                if (nan_in)
                    OK(st == SOL_ERR_NONFINITE && occ == 7);
                else if (bb[q].x1 < bb[q].x0)
                    OK(st == SOL_ERR_INVALID_ARG && occ == 7);
                else
                    OK(st == SOL_OK && (occ == 0 || occ == 1) && vis >= 0);
            }
        }
        sol_cbuffer_free(&cb);
    }
    sol_cbuffer_free(NULL);
    int occ = 7;
    sol_cbuffer empty = {0};
    sol_screen_bounds b = {.x0 = 0, .x1 = 1, .y0 = 0, .y1 = 1, .znear = 1};
    ST(sol_cbuffer_test(&empty, &b, -1, &occ, NULL), SOL_ERR_NULL_ARG);
    ST(sol_cbuffer_test(NULL, &b, -1, &occ, NULL), SOL_ERR_NULL_ARG);
    OK(occ == 7);
    report("screen");
}

Test(badinput, normals)
{
    static const sol_normal_method methods[] = {SOL_NORMAL_XYZ_NORMALIZED, SOL_NORMAL_XYZ_MAX_COMPONENT};
    for (size_t m = 0; m < 2; ++m)
        for (size_t i = 0; i < NDIRS; ++i) {
            uint32_t code = 0xdeadbeef;
            sol_status st = sol_normal_encode(methods[m], dirs[i], &code);
            int nonfinite = has_nan3(dirs[i]) || isinf(dirs[i][0]);
            int zero = dirs[i][0] == 0 && dirs[i][1] == 0 && dirs[i][2] == 0;
            if (nonfinite)
                OK(st == SOL_ERR_NONFINITE && code == 0xdeadbeef);
            else if (zero)
                OK(st == SOL_ERR_ZERO_LENGTH && code == 0xdeadbeef);
            else {
                OK(st == SOL_OK);
                double back[3];
                OK(sol_normal_decode(methods[m], code, back) == SOL_OK && isfinite(sol_angle3(back, dirs[i])));
            }
        }
    uint32_t code = 0xdeadbeef;
    ST(sol_normal_encode((sol_normal_method)-1, dirs[0], &code), SOL_ERR_INVALID_ARG);
    ST(sol_normal_encode((sol_normal_method)1000, dirs[0], &code), SOL_ERR_INVALID_ARG);
    ST(sol_normal_encode(SOL_NORMAL_XYZ_NORMALIZED, NULL, &code), SOL_ERR_NULL_ARG);
    ST(sol_normal_encode(SOL_NORMAL_XYZ_NORMALIZED, dirs[0], NULL), SOL_ERR_NULL_ARG);
    OK(code == 0xdeadbeef);
    double n[3] = {7, 7, 7};
    ST(sol_normal_decode(SOL_NORMAL_XYZ_NORMALIZED, 1u << 24, n), SOL_ERR_INVALID_ARG);
    ST(sol_normal_decode(SOL_NORMAL_XYZ_NORMALIZED, UINT32_MAX, n), SOL_ERR_INVALID_ARG);
    ST(sol_normal_decode((sol_normal_method)-1, 0, n), SOL_ERR_INVALID_ARG);
    OK(n[0] == 7);
    uint64_t count = 99;
    ST(sol_normal_cells_fixed(SOL_NORMAL_XYZ_NORMALIZED, -1, 4, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_fixed(SOL_NORMAL_XYZ_NORMALIZED, 4, 257, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_fixed(SOL_NORMAL_XYZ_NORMALIZED, 5, 4, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_on_sphere(3, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_on_sphere(0, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_on_sphere(INT_MAX - 1, &count), SOL_ERR_INVALID_ARG);
    ST(sol_normal_cells_on_sphere(-2, &count), SOL_ERR_INVALID_ARG);
    OK(count == 99);
    sol_bestfit_table t = {.size = 3};
    ST(sol_bestfit_table_build(0, 8, &t), SOL_ERR_INVALID_ARG);
    ST(sol_bestfit_table_build(16385, 8, &t), SOL_ERR_INVALID_ARG);
    ST(sol_bestfit_table_build(8, 7, &t), SOL_ERR_INVALID_ARG);
    ST(sol_bestfit_table_build(INT_MIN, 8, &t), SOL_ERR_INVALID_ARG);
    OK(t.size == 3);
    for (size_t i = 0; i < NDIRS; ++i) {
        double s = 42.0;
        sol_status st = sol_bestfit_scale(dirs[i], &s);
        OK(st == SOL_OK ? (isfinite(s) && s > 0.0 && s <= 1.0) : s == 42.0);
    }
    for (size_t i = 0; i < NSPEC; ++i)
        OK(sol_quantize255(specials[i]) <= 255u);
    report("normals");
}

Test(badinput, normalmaps)
{
    double pal[8] = {7, 7, 7, 7, 7, 7, 7, 7};
    ST(sol_bc4_palette(0, 255, (sol_bc4_precision)-1, pal), SOL_ERR_INVALID_ARG);
    ST(sol_bc4_palette(0, 255, SOL_BC4_PRECISION_COUNT, pal), SOL_ERR_INVALID_ARG);
    ST(sol_bc4_palette(0, 255, SOL_BC4_INTERP_16BIT, NULL), SOL_ERR_NULL_ARG);
    OK(pal[0] == 7);
    sol_bc4_block blk = {0};
    blk.index[3] = 8;
    uint8_t packed[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    ST(sol_bc4_pack(&blk, packed), SOL_ERR_INVALID_ARG);
    OK(packed[0] == 1);
    double vals[16];
    for (int i = 0; i < 16; ++i)
        vals[i] = 0.5;
    static const double badv[] = {NAN, INFINITY, -INFINITY, -1e-300, 1.0000000001, DBL_MAX};
    for (size_t i = 0; i < sizeof badv / sizeof *badv; ++i) {
        vals[9] = badv[i];
        sol_bc4_block out;
        memset(&out, 0x77, sizeof out);
        sol_status st = sol_bc4_encode_block(vals, SOL_BC4_INTERP_16BIT, &out, NULL);
        OK(st == (isnan(badv[i]) ? SOL_ERR_NONFINITE : SOL_ERR_OUT_OF_RANGE) || (isinf(badv[i]) && st == SOL_ERR_NONFINITE));
        OK(out.e0 == 0x77);
    }
    vals[9] = -0.0;
    sol_bc4_block out;
    ST(sol_bc4_encode_block(vals, SOL_BC4_INTERP_16BIT, &out, NULL), SOL_OK);
    vals[9] = 5e-324;
    ST(sol_bc4_encode_block(vals, SOL_BC4_INTERP_16BIT, &out, NULL), SOL_OK);
    /* BC5 block encoder: NaN/zero normals, bad options, huge/tiny magnitudes */
    double n[16][3];
    for (int i = 0; i < 16; ++i) {
        n[i][0] = 0.1 * (i % 4);
        n[i][1] = -0.1 * (i / 4);
        n[i][2] = 1.0;
    }
    sol_bc5_block b5;
    memset(&b5, 0x66, sizeof b5);
    sol_bc5_options bad_enc = {.encoder = (sol_bc5_encoder)9};
    ST(sol_bc5_encode_block((const double(*)[3])n, &bad_enc, &b5, NULL), SOL_ERR_INVALID_ARG);
    sol_bc5_options bad_prec = {.precision = (sol_bc4_precision)-3};
    ST(sol_bc5_encode_block((const double(*)[3])n, &bad_prec, &b5, NULL), SOL_ERR_INVALID_ARG);
    sol_bc5_options bad_thr = {.encoder = SOL_BC5_ADAPTIVE, .threshold_deg = NAN};
    OK(sol_bc5_encode_block((const double(*)[3])n, &bad_thr, &b5, NULL) != SOL_OK);
    ST(sol_bc5_encode_block(NULL, NULL, &b5, NULL), SOL_ERR_NULL_ARG);
    double save = n[4][1];
    n[4][1] = NAN;
    ST(sol_bc5_encode_block((const double(*)[3])n, NULL, &b5, NULL), SOL_ERR_NONFINITE);
    n[4][1] = INFINITY;
    ST(sol_bc5_encode_block((const double(*)[3])n, NULL, &b5, NULL), SOL_ERR_NONFINITE);
    n[4][1] = save;
    double z0 = n[2][0];
    n[2][0] = n[2][1] = n[2][2] = 0.0;
    ST(sol_bc5_encode_block((const double(*)[3])n, NULL, &b5, NULL), SOL_ERR_ZERO_LENGTH);
    n[2][0] = z0;
    n[2][1] = -0.0;
    n[2][2] = 1.0;
    unsigned char pat[sizeof b5];
    memset(pat, 0x66, sizeof pat);
    OK(memcmp(&b5, pat, sizeof b5) == 0);
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
            n[i][c] *= 1e300;
    ST(sol_bc5_encode_block((const double(*)[3])n, NULL, &b5, NULL), SOL_OK);
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
            n[i][c] = n[i][c] * 1e-300 * 1e-300; /* 1e300 -> 1e-300 */
    ST(sol_bc5_encode_block((const double(*)[3])n, NULL, &b5, NULL), SOL_OK);
    sol_bc5_options wide = {.encoder = SOL_BC5_ADAPTIVE, .window = INT_MIN};
    ST(sol_bc5_encode_block((const double(*)[3])n, &wide, &b5, NULL), SOL_OK);
    /* images: bad sizes */
    sol_image img = {.width = 6, .height = 4, .channels = 3};
    float px[6 * 4 * 3] = {0};
    img.data = px;
    uint8_t blocks[64];
    ST(sol_bc5_encode_image(&img, NULL, blocks, NULL), SOL_ERR_INVALID_ARG);
    img.width = 4;
    img.channels = 4;
    ST(sol_bc5_encode_image(&img, NULL, blocks, NULL), SOL_ERR_INVALID_ARG);
    img.channels = 3;
    img.height = -4;
    ST(sol_bc5_encode_image(&img, NULL, blocks, NULL), SOL_ERR_INVALID_ARG);
    ST(sol_bc5_encode_image(NULL, NULL, blocks, NULL), SOL_ERR_NULL_ARG);
    sol_image dec = {0};
    ST(sol_bc5_decode_image(blocks, 0, 4, SOL_BC4_INTERP_16BIT, &dec), SOL_ERR_INVALID_ARG);
    ST(sol_bc5_decode_image(blocks, 4, 4, (sol_bc4_precision)-1, &dec), SOL_ERR_INVALID_ARG);
    OK(dec.data == NULL);
    report("normalmaps");
}
