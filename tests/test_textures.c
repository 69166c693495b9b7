/* test_textures.c - transfer functions, Xbox 360 PWL gamma, BC1 codec, renormalisation and the
 * storage classifier (claims T1-T7). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sol_textures.h"

static const sol_transfer curves[] = {
    {SOL_TRANSFER_LINEAR, 0}, {SOL_TRANSFER_POWER, 0}, {SOL_TRANSFER_POWER, 2.8}, {SOL_TRANSFER_POWER, 0.5},
    {SOL_TRANSFER_SRGB, 0},   {SOL_TRANSFER_X360_PWL, 0}};
enum { CURVE_COUNT = sizeof curves / sizeof curves[0] };

Test(textures, transfer_round_trips_and_monotonic)
{
    for (int k = 0; k < CURVE_COUNT; ++k) {
        double prev = -1.0;
        for (int i = 0; i <= 4096; ++i) {
            double x = i / 4096.0, e, back;
            cr_assert_eq(sol_transfer_encode(&curves[k], x, &e), SOL_OK);
            cr_assert_eq(sol_transfer_decode(&curves[k], e, &back), SOL_OK);
            cr_assert(e >= prev, "curve %d not monotonic at %g", k, x);
            cr_assert(e >= 0.0 && e <= 1.0);
            cr_assert(fabs(back - x) < 1e-12, "curve %d: %g -> %g -> %g", k, x, e, back);
            prev = e;
        }
        double e0, e1;
        cr_assert_eq(sol_transfer_encode(&curves[k], 0.0, &e0), SOL_OK);
        cr_assert_eq(sol_transfer_encode(&curves[k], 1.0, &e1), SOL_OK);
        cr_assert(fabs(e0) < 1e-15 && fabs(e1 - 1.0) < 1e-12, "curve %d ends %g %g", k, e0, e1);
    }
}

Test(textures, transfer_slope_matches_finite_differences)
{
    for (int k = 0; k < CURVE_COUNT; ++k)
        for (int i = 1; i < 200; ++i) {
            double x = i / 200.0 + 1.234e-4, h = 1e-7, a, b, s;
            cr_assert_eq(sol_transfer_encode(&curves[k], x - h, &a), SOL_OK);
            cr_assert_eq(sol_transfer_encode(&curves[k], x + h, &b), SOL_OK);
            cr_assert_eq(sol_transfer_slope(&curves[k], x, &s), SOL_OK);
            cr_assert(fabs((b - a) / (2 * h) - s) < 1e-5 * fmax(1.0, s), "curve %d at %g: %g vs %g", k, x,
                      (b - a) / (2 * h), s);
        }
}

Test(textures, transfer_edges_clamp_and_reject_bad_input)
{
    sol_transfer power = {SOL_TRANSFER_POWER, 0}, srgb = {SOL_TRANSFER_SRGB, 0};
    double v = 42.0;
    cr_assert_eq(sol_transfer_encode(&power, NAN, &v), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_transfer_encode(&power, INFINITY, &v), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_transfer_decode(&srgb, -INFINITY, &v), SOL_ERR_NONFINITE);
    cr_assert_eq(v, 42.0);
    cr_assert_eq(sol_transfer_encode(&power, -0.0, &v), SOL_OK);
    cr_assert_eq(v, 0.0);
    cr_assert_eq(sol_transfer_encode(&power, 7.0, &v), SOL_OK);
    cr_assert_eq(v, 1.0);
    cr_assert_eq(sol_transfer_encode(&power, 1e-310, &v), SOL_OK); /* denormal stays finite */
    cr_assert(isfinite(v) && v > 0.0);
    cr_assert_eq(sol_transfer_slope(&power, 0.0, &v), SOL_ERR_OUT_OF_RANGE); /* infinite at 0 */
    cr_assert_eq(sol_transfer_slope(&power, 1.5, &v), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(sol_transfer_slope(&srgb, 0.0, &v), SOL_OK);
    cr_assert_eq(v, 12.92);
    sol_transfer bad_gamma = {SOL_TRANSFER_POWER, -1.0}, bad_kind = {(sol_transfer_kind)99, 0};
    cr_assert_eq(sol_transfer_encode(&bad_gamma, 0.5, &v), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_transfer_encode(&bad_kind, 0.5, &v), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_transfer_encode(NULL, 0.5, &v), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_transfer_encode(&power, 0.5, NULL), SOL_ERR_NULL_ARG);
    /* sRGB is continuous at its threshold */
    double below, above;
    sol_transfer_encode(&srgb, 0.0031308 - 1e-12, &below);
    sol_transfer_encode(&srgb, 0.0031308 + 1e-12, &above);
    cr_assert(fabs(above - below) < 1e-7);
}

Test(textures, quantize8_matches_known_codes)
{
    sol_transfer srgb = {SOL_TRANSFER_SRGB, 0}, lin = {SOL_TRANSFER_LINEAR, 0};
    uint8_t code;
    cr_assert_eq(sol_transfer_quantize8(&srgb, 0.5, &code), SOL_OK);
    cr_assert_eq(code, 188); /* 0.5 linear is sRGB 0.7354 */
    cr_assert_eq(sol_transfer_quantize8(&lin, 0.5, &code), SOL_OK);
    cr_assert_eq(code, 128);
    for (int c = 0; c < 256; ++c) { /* every code survives decode + encode */
        double x;
        for (int k = 0; k < CURVE_COUNT; ++k) {
            cr_assert_eq(sol_transfer_dequantize8(&curves[k], (uint8_t)c, &x), SOL_OK);
            cr_assert_eq(sol_transfer_quantize8(&curves[k], x, &code), SOL_OK);
            cr_assert_eq(code, c, "curve %d code %d", k, c);
        }
    }
}

/* T3, T5: equal-density points. */
Test(textures, equal_density_points_T3_T5)
{
    double lo, hi;
    for (double g = 1.5; g <= 3.0; g += 0.1) {
        sol_transfer p = {SOL_TRANSFER_POWER, g};
        cr_assert_eq(sol_transfer_equal_density(&p, 0.0, &lo, &hi), SOL_OK);
        cr_assert(fabs(lo - pow(g, -g / (g - 1.0))) < 1e-12, "gamma %g: %g", g, lo); /* closed form */
        cr_assert(fabs(lo - hi) < 1e-15);
    }
    sol_transfer p22 = {SOL_TRANSFER_POWER, 0};
    sol_transfer_equal_density(&p22, 0.0, &lo, &hi);
    cr_assert(fabs(lo * 255.0 - 60.08) < 0.01); /* not the talk's 5/11 = 116/255: see the paper */
    sol_transfer pwl = {SOL_TRANSFER_X360_PWL, 0};
    cr_assert_eq(sol_transfer_equal_density(&pwl, 0.01, &lo, &hi), SOL_OK);
    cr_assert(fabs(lo - 128.0 / 1023.0) < 1e-12 && fabs(hi - 512.0 / 1023.0) < 1e-12, "%g %g", lo, hi);
    cr_assert_eq(sol_transfer_equal_density(&pwl, 0.0, &lo, &hi), SOL_OK); /* strict: the crossing */
    cr_assert(fabs(lo - 512.0 / 1023.0) < 1e-12 && lo == hi);
    sol_transfer lin = {SOL_TRANSFER_LINEAR, 0}, p05 = {SOL_TRANSFER_POWER, 0.5};
    cr_assert_eq(sol_transfer_equal_density(&lin, 0.0, &lo, &hi), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_transfer_equal_density(&p05, 0.0, &lo, &hi), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_transfer_equal_density(&p22, -1.0, &lo, &hi), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_transfer_equal_density(&p22, NAN, &lo, &hi), SOL_ERR_INVALID_ARG);
}

/* T6: the hardware PWL table and the 8-bit texture-cache de-gamma. */
Test(textures, x360_pwl_table_and_cache_degamma_T6)
{
    cr_assert_eq(sol_x360_pwl_gamma8_to_linear10(0), 0);
    cr_assert_eq(sol_x360_pwl_gamma8_to_linear10(64), 64);
    cr_assert_eq(sol_x360_pwl_gamma8_to_linear10(96), 128);
    cr_assert_eq(sol_x360_pwl_gamma8_to_linear10(192), 516);
    cr_assert_eq(sol_x360_pwl_gamma8_to_linear10(255), 1023);
    sol_transfer pwl = {SOL_TRANSFER_X360_PWL, 0};
    int distinct = 1;
    for (int e = 1; e < 256; ++e) {
        cr_assert(sol_x360_pwl_gamma8_to_linear10((uint8_t)e) > sol_x360_pwl_gamma8_to_linear10((uint8_t)(e - 1)));
        double x;
        sol_transfer_dequantize8(&pwl, (uint8_t)e, &x); /* continuous curve within 4/1023 of hardware */
        cr_assert(fabs(x * 1023.0 - sol_x360_pwl_gamma8_to_linear10((uint8_t)e)) <= 4.0);
        distinct += sol_x360_cache_degamma8((uint8_t)e) != sol_x360_cache_degamma8((uint8_t)(e - 1));
    }
    cr_assert(distinct < 256, "the 8-bit cache merges dark gamma codes");
    cr_assert_eq(sol_x360_cache_degamma8(255), 255);
    cr_assert_eq(sol_x360_cache_degamma8(0), 0);
}

static void block_of(uint16_t c0, uint16_t c1, uint32_t bits, uint8_t block[8])
{
    block[0] = (uint8_t)c0;
    block[1] = (uint8_t)(c0 >> 8);
    block[2] = (uint8_t)c1;
    block[3] = (uint8_t)(c1 >> 8);
    for (int i = 0; i < 4; ++i)
        block[4 + i] = (uint8_t)(bits >> (8 * i));
}

static void assert_texel(uint8_t t[4], int r, int g, int b, int a)
{
    cr_assert(t[0] == r && t[1] == g && t[2] == b && t[3] == a, "got %d %d %d %d want %d %d %d %d", t[0], t[1],
              t[2], t[3], r, g, b, a);
}

/* Hand-computed palettes: 565 expansion by bit replication, (2a + b + 1) / 3, (a + b + 1) / 2. */
Test(textures, bc1_decoder_is_bit_exact_on_hand_checked_blocks)
{
    uint8_t block[8], t[16][4];
    block_of(0xF800, 0x001F, 0xE4E4E4E4u, block); /* red > blue: four-color mode; indices 0,1,2,3 per row */
    sol_bc1_decode_block(block, t);
    assert_texel(t[0], 255, 0, 0, 255);
    assert_texel(t[1], 0, 0, 255, 255);
    assert_texel(t[2], 170, 0, 85, 255); /* (510 + 0 + 1)/3 = 170, (0 + 255 + 1)/3 = 85 */
    assert_texel(t[3], 85, 0, 170, 255);
    assert_texel(t[15], 85, 0, 170, 255);
    block_of(0x001F, 0xF800, 0xE4E4E4E4u, block); /* c0 < c1: three colors + transparent black */
    sol_bc1_decode_block(block, t);
    assert_texel(t[0], 0, 0, 255, 255);
    assert_texel(t[2], 128, 0, 128, 255); /* (255 + 0 + 1)/2 = 128 */
    assert_texel(t[3], 0, 0, 0, 0);
    block_of(0x07E0, 0x0020, 0xE4E4E4E4u, block); /* green 63 -> 255, green 1 -> 4 */
    sol_bc1_decode_block(block, t);
    assert_texel(t[1], 0, 4, 0, 255);
    assert_texel(t[2], 0, 171, 0, 255); /* (510 + 4 + 1)/3 = 171.67 -> 171 */
    assert_texel(t[3], 0, 88, 0, 255);  /* (255 + 8 + 1)/3 = 88 */
    block_of(0x8410, 0x0841, 0x0000001Bu, block); /* r16 g32 b16 -> 132,130,132; r1 g2 b1 -> 8,8,8 */
    sol_bc1_decode_block(block, t);
    assert_texel(t[0], 49, 49, 49, 255); /* index 3: (132 + 16 + 1)/3, (130 + 16 + 1)/3 */
    assert_texel(t[1], 91, 89, 91, 255); /* index 2: (264 + 8 + 1)/3, (260 + 8 + 1)/3 */
    assert_texel(t[2], 8, 8, 8, 255);
    assert_texel(t[3], 132, 130, 132, 255);
}

static double block_error(const float rgb[16][3], const uint8_t block[8])
{
    uint8_t t[16][4];
    sol_bc1_decode_block(block, t);
    double e = 0.0;
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c) {
            double d = t[i][c] - rgb[i][c] * 255.0;
            e += d * d;
        }
    return e;
}

static double encode_error(const float rgb[16][3], sol_bc1_effort effort)
{
    sol_bc1_options o = {.effort = effort};
    uint8_t block[8];
    cr_assert_eq(sol_bc1_encode_block(rgb, &o, block), SOL_OK);
    return block_error(rgb, block);
}

Test(textures, bc1_constant_and_extreme_blocks)
{
    float rgb[16][3];
    const float colors[][3] = {{0, 0, 0}, {1, 1, 1}, {0.5f, 0.25f, 0.75f}, {0.01f, 0.99f, 0.3f}};
    for (int k = 0; k < 4; ++k) {
        for (int i = 0; i < 16; ++i)
            memcpy(rgb[i], colors[k], sizeof rgb[i]);
        for (int eff = 0; eff < SOL_BC1_EFFORT_COUNT; ++eff) {
            double e = encode_error(rgb, (sol_bc1_effort)eff);
            /* one color: every texel within 1 code per channel of the target */
            cr_assert(e <= 16 * 3 * 1.0, "color %d effort %d error %g", k, eff, e);
            if (k < 2)
                cr_assert_eq(e, 0.0);
        }
    }
}

Test(textures, bc1_two_representable_colors_are_exact)
{
    float rgb[16][3];
    for (int i = 0; i < 16; ++i) { /* red 31 -> 255 and (r 8, g 32, b 16) -> (66, 130, 132) */
        int first = (i * 7) % 3 == 0;
        rgb[i][0] = first ? 1.0f : 66.0f / 255.0f;
        rgb[i][1] = first ? 0.0f : 130.0f / 255.0f;
        rgb[i][2] = first ? 0.0f : 132.0f / 255.0f;
    }
    for (int eff = SOL_BC1_PCA; eff < SOL_BC1_EFFORT_COUNT; ++eff)
        cr_assert(encode_error(rgb, (sol_bc1_effort)eff) < 1e-6, "effort %d", eff); /* float /255 rounding */
    for (int i = 0; i < 16; ++i) /* every texel equal to one endpoint but one */
        memcpy(rgb[i], rgb[0], sizeof rgb[i]);
    rgb[5][0] = rgb[5][1] = rgb[5][2] = 0.0f;
    cr_assert(encode_error(rgb, SOL_BC1_CLUSTER) < 1e-6);
}

Test(textures, bc1_effort_levels_never_lose_to_their_starting_point)
{
    srand(7);
    double sum[SOL_BC1_EFFORT_COUNT] = {0};
    for (int n = 0; n < 300; ++n) {
        float rgb[16][3], base[3], dir[3];
        for (int c = 0; c < 3; ++c) {
            base[c] = (float)rand() / RAND_MAX * 0.5f;
            dir[c] = (float)rand() / RAND_MAX * 0.5f;
        }
        for (int i = 0; i < 16; ++i) {
            float t = (float)rand() / RAND_MAX;
            for (int c = 0; c < 3; ++c)
                rgb[i][c] = fminf(1.0f, base[c] + t * dir[c] + 0.05f * (float)rand() / RAND_MAX);
        }
        double e[SOL_BC1_EFFORT_COUNT];
        for (int eff = SOL_BC1_RANGE; eff < SOL_BC1_EFFORT_COUNT; ++eff)
            sum[eff] += e[eff] = encode_error(rgb, (sol_bc1_effort)eff);
        cr_assert(e[SOL_BC1_PCA_REFINE] <= e[SOL_BC1_PCA]);
        cr_assert(e[SOL_BC1_CLUSTER] <= e[SOL_BC1_PCA]);
        cr_assert(e[SOL_BC1_CLUSTER_SEARCH] <= e[SOL_BC1_CLUSTER]);
        /* error bound: 4 levels on a line up to 127 codes long (+ 12.75 of noise): RMSE < 16 codes */
        cr_assert(e[SOL_BC1_CLUSTER] / 48.0 < 256.0, "block %d rmse^2 %g", n, e[SOL_BC1_CLUSTER] / 48.0);
    }
    cr_assert(sum[SOL_BC1_CLUSTER] < sum[SOL_BC1_RANGE]);
}

Test(textures, bc1_rejects_bad_input_and_leaves_output_untouched)
{
    float rgb[16][3] = {{0}};
    uint8_t block[8] = {1, 2, 3, 4, 5, 6, 7, 8}, keep[8];
    memcpy(keep, block, 8);
    rgb[3][1] = NAN;
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_ERR_NONFINITE);
    rgb[3][1] = INFINITY;
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_ERR_NONFINITE);
    rgb[3][1] = 1.5f;
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_ERR_OUT_OF_RANGE);
    rgb[3][1] = -0.25f;
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_ERR_OUT_OF_RANGE);
    rgb[3][1] = -0.0f; /* -0.0 is fine */
    sol_bc1_options bad = {.effort = (sol_bc1_effort)42};
    cr_assert_eq(sol_bc1_encode_block(rgb, &bad, block), SOL_ERR_INVALID_ARG);
    bad = (sol_bc1_options){.iterations = -1};
    cr_assert_eq(sol_bc1_encode_block(rgb, &bad, block), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_bc1_encode_block(NULL, NULL, block), SOL_ERR_NULL_ARG);
    cr_assert_eq(memcmp(block, keep, 8), 0);
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_OK);
    cr_assert_eq(block_error(rgb, block), 0.0);
    for (int i = 0; i < 16; ++i) /* denormals: a black block */
        rgb[i][0] = rgb[i][1] = rgb[i][2] = (i & 1) ? 1e-40f : 0.0f;
    cr_assert_eq(sol_bc1_encode_block(rgb, NULL, block), SOL_OK);
    cr_assert(block_error(rgb, block) < 1e-9);
}

Test(textures, bc1_images_of_any_size_round_trip)
{
    const int sizes[][2] = {{1, 1}, {5, 3}, {4, 4}, {7, 9}};
    for (int s = 0; s < 4; ++s) {
        sol_image img = {0}, back = {0};
        int w = sizes[s][0], h = sizes[s][1];
        cr_assert_eq(sol_image_alloc(&img, w, h, 4), SOL_OK);
        for (int y = 0; y < h; ++y) /* a smooth gradient: what BC1 represents well */
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c)
                    sol_image_pixel(&img, x, y)[c] = 0.2f + 0.1f * (float)c + 0.04f * (float)(x + y);
        uint8_t *blocks = malloc(sol_bc1_size(w, h));
        cr_assert_eq(sol_bc1_encode(&img, NULL, blocks), SOL_OK);
        cr_assert_eq(sol_bc1_decode(blocks, w, h, &back), SOL_OK);
        cr_assert_eq(back.width, w);
        cr_assert_eq(back.channels, 3);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c)
                    cr_assert(fabsf(sol_image_pixel(&back, x, y)[c] - sol_image_pixel(&img, x, y)[c]) < 0.04f);
        free(blocks);
        sol_image_free(&img);
        sol_image_free(&back);
    }
    cr_assert_eq(sol_bc1_size(0, 4), 0);
    cr_assert_eq(sol_bc1_size(5, 5), 32);
    sol_image two = {0};
    cr_assert_eq(sol_image_alloc(&two, 4, 4, 2), SOL_OK);
    uint8_t blocks[8];
    cr_assert_eq(sol_bc1_encode(&two, NULL, blocks), SOL_ERR_INVALID_ARG);
    sol_image_free(&two);
}

/* T1, T2: the shader's reconstruction undoes the renormalisation. */
Test(textures, renorm_round_trip_and_edges_T1_T2)
{
    sol_image img = {0};
    cr_assert_eq(sol_image_alloc(&img, 3, 2, 3), SOL_OK);
    for (int i = 0; i < 18; ++i)
        img.data[i] = (i % 3 == 2) ? 0.3f : 0.02f + 0.01f * (float)i; /* blue constant */
    float orig[18];
    memcpy(orig, img.data, sizeof orig);
    sol_renorm r;
    cr_assert_eq(sol_renorm_fit(&img, &r), SOL_OK);
    cr_assert_eq(r.lo[2], 0.3f);
    cr_assert_eq(sol_renorm_apply(&r, &img), SOL_OK);
    float lo = 1, hi = 0;
    for (int i = 0; i < 18; i += 3) {
        lo = fminf(lo, img.data[i]);
        hi = fmaxf(hi, img.data[i]);
        cr_assert_eq(img.data[i + 2], 0.0f); /* constant channel stores 0 */
    }
    cr_assert(lo == 0.0f && hi == 1.0f);
    cr_assert_eq(sol_renorm_undo(&r, &img), SOL_OK);
    for (int i = 0; i < 18; ++i)
        cr_assert(fabsf(img.data[i] - orig[i]) < 1e-6f);
    img.data[4] = NAN;
    memcpy(orig, img.data, sizeof orig);
    cr_assert_eq(sol_renorm_apply(&r, &img), SOL_ERR_NONFINITE);
    cr_assert_eq(memcmp(orig, img.data, sizeof orig), 0);
    cr_assert_eq(sol_renorm_fit(&img, &r), SOL_ERR_NONFINITE);
    r.channels = 4;
    img.data[4] = 0.5f;
    cr_assert_eq(sol_renorm_apply(&r, &img), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_renorm_fit(NULL, &r), SOL_ERR_NULL_ARG);
    sol_image_free(&img);
}

/* T4: the 75% rule. */
Test(textures, storage_classifier_T4)
{
    sol_image img = {0};
    cr_assert_eq(sol_image_alloc(&img, 10, 10, 3), SOL_OK);
    for (int i = 0; i < 300; ++i)
        img.data[i] = (i / 3) < 80 ? 0.8f : 0.05f; /* 80% above either median */
    sol_storage choice;
    double frac;
    cr_assert_eq(sol_storage_classify(&img, NULL, &choice, &frac), SOL_OK);
    cr_assert_eq(choice, SOL_STORAGE_LINEAR);
    cr_assert(fabs(frac - 0.8) < 1e-12);
    sol_storage_options o = {.threshold = 0.85};
    cr_assert_eq(sol_storage_classify(&img, &o, &choice, NULL), SOL_OK);
    cr_assert_eq(choice, SOL_STORAGE_GAMMA);
    o = (sol_storage_options){.median = 5.0 / 11.0};
    img.data[0] = 0.3f; /* between 0.2356 and 5/11 */
    cr_assert_eq(sol_storage_classify(&img, &o, &choice, &frac), SOL_OK);
    cr_assert(frac < 0.8);
    o = (sol_storage_options){.threshold = 1.5};
    cr_assert_eq(sol_storage_classify(&img, &o, &choice, NULL), SOL_ERR_INVALID_ARG);
    img.data[7] = NAN;
    cr_assert_eq(sol_storage_classify(&img, NULL, &choice, NULL), SOL_ERR_NONFINITE);
    sol_image_free(&img);
}

/* T2 at reduced size: a dark 16-bit gradient through BC1 has a lower error with renormalisation. */
Test(textures, renormalisation_lowers_bc1_error_of_a_dark_texture_T2)
{
    sol_image img = {0}, plain = {0}, renorm = {0};
    cr_assert_eq(sol_image_alloc(&img, 32, 32, 3), SOL_OK);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) /* stored (gamma) values between 0.02 and 0.12 */
                sol_image_pixel(&img, x, y)[c] = 0.02f + 0.1f * (float)(x + 2 * y + c) / 99.0f;
    uint8_t blocks[8 * 64];
    cr_assert_eq(sol_bc1_encode(&img, NULL, blocks), SOL_OK);
    cr_assert_eq(sol_bc1_decode(blocks, 32, 32, &plain), SOL_OK);
    sol_image work = {0};
    cr_assert_eq(sol_image_alloc(&work, 32, 32, 3), SOL_OK);
    memcpy(work.data, img.data, sizeof(float) * 32 * 32 * 3);
    sol_renorm r;
    cr_assert_eq(sol_renorm_fit(&work, &r), SOL_OK);
    cr_assert_eq(sol_renorm_apply(&r, &work), SOL_OK);
    cr_assert_eq(sol_bc1_encode(&work, NULL, blocks), SOL_OK);
    cr_assert_eq(sol_bc1_decode(blocks, 32, 32, &renorm), SOL_OK);
    cr_assert_eq(sol_renorm_undo(&r, &renorm), SOL_OK);
    double e_plain = 0.0, e_renorm = 0.0;
    for (int i = 0; i < 32 * 32 * 3; ++i) {
        e_plain += (plain.data[i] - img.data[i]) * (plain.data[i] - img.data[i]);
        e_renorm += (renorm.data[i] - img.data[i]) * (renorm.data[i] - img.data[i]);
    }
    cr_assert(e_renorm < 0.25 * e_plain, "renorm %g plain %g", e_renorm, e_plain);
    sol_image_free(&img);
    sol_image_free(&work);
    sol_image_free(&plain);
    sol_image_free(&renorm);
}

/* T7 at reduced size: over the bright range [0.5, 0.9] 8-bit sRGB storage has fewer codes (so
 * wider bands once the contrast is stretched) than 8-bit linear storage. */
Test(textures, bright_range_has_fewer_gamma_codes_than_linear_T7)
{
    sol_transfer srgb = {SOL_TRANSFER_SRGB, 0}, lin = {SOL_TRANSFER_LINEAR, 0};
    int gamma_codes = 0, linear_codes = 0, last_g = -1, last_l = -1;
    for (int i = 0; i <= 4000; ++i) {
        double x = 0.5 + 0.4 * i / 4000.0;
        uint8_t g, l;
        cr_assert_eq(sol_transfer_quantize8(&srgb, x, &g), SOL_OK);
        cr_assert_eq(sol_transfer_quantize8(&lin, x, &l), SOL_OK);
        gamma_codes += g != last_g;
        linear_codes += l != last_l;
        last_g = g;
        last_l = l;
    }
    cr_assert(gamma_codes < linear_codes, "gamma %d linear %d", gamma_codes, linear_codes);
    cr_assert_eq(linear_codes, 103); /* round(0.5*255)=128 .. round(0.9*255)=230 */
}
