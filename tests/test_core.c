/* test_core.c - status strings, images, PNG files, low-discrepancy directions. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "sol_core.h"

Test(core, every_status_has_a_distinct_string)
{
    for (int i = 0; i < SOL_STATUS_COUNT; ++i) {
        cr_assert_str_neq(sol_status_string((sol_status)i), "unknown status");
        for (int j = 0; j < i; ++j)
            cr_assert_str_neq(sol_status_string((sol_status)i), sol_status_string((sol_status)j));
    }
    cr_assert_str_eq(sol_status_string((sol_status)-1), "unknown status");
    cr_assert_str_eq(sol_status_string(SOL_STATUS_COUNT), "unknown status");
}

Test(core, image_alloc_rejects_bad_sizes_and_leaves_output_untouched)
{
    sol_image image = {.width = 77};
    cr_assert_eq(sol_image_alloc(&image, 0, 4, 3), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_image_alloc(&image, 4, -1, 3), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_image_alloc(&image, 4, 4, 5), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_image_alloc(&image, 1 << 30, 1 << 30, 4), SOL_ERR_INVALID_ARG); /* 2^64 bytes */
    cr_assert_eq(sol_image_alloc(&image, 1 << 30, 1 << 28, 4), SOL_ERR_NO_MEMORY);  /* 2^62 bytes */
    cr_assert_eq(sol_image_alloc(NULL, 4, 4, 3), SOL_ERR_NULL_ARG);
    cr_assert_eq(image.width, 77);
    cr_assert_eq(sol_image_alloc(&image, 3, 2, 4), SOL_OK);
    cr_assert_eq(sol_image_pixel(&image, 2, 1), image.data + 20);
    sol_image_free(&image);
    cr_assert_null(image.data);
    sol_image_free(&image); /* idempotent */
    sol_image_free(NULL);
}

/* Each test runs in its own process: one scratch folder per test, removed by remove_temp(). */
static char temp_dir[] = "/tmp/sol_test_XXXXXX";
static int temp_made; /* a flag, not a look at the name: mkdtemp's random letters may be X */

static char *temp_path(const char *name)
{
    if (!temp_made)
        cr_assert_not_null(mkdtemp(temp_dir));
    temp_made = 1;
    char *path = malloc(4096);
    snprintf(path, 4096, "%s/%s", temp_dir, name);
    return path;
}

static void remove_temp(void)
{
    if (temp_made)
        rmdir(temp_dir);
}

static void png_round_trip(int channels, int bits)
{
    sol_image image = {0}, back = {0};
    cr_assert_eq(sol_image_alloc(&image, 5, 3, channels), SOL_OK);
    const int maxcode = (1 << bits) - 1;
    for (int i = 0; i < 15 * channels; ++i)
        image.data[i] = (float)((i * 7919) % (maxcode + 1)) / (float)maxcode;
    char *path = temp_path("round_trip.png");
    cr_assert_eq(sol_png_write(path, &image, bits), SOL_OK);
    int bits_read = 0;
    cr_assert_eq(sol_png_read(path, &back, &bits_read), SOL_OK);
    cr_assert_eq(bits_read, bits);
    cr_assert_eq(back.width, 5);
    cr_assert_eq(back.height, 3);
    cr_assert_eq(back.channels, channels);
    for (int i = 0; i < 15 * channels; ++i)
        cr_assert_eq(back.data[i], image.data[i], "value %d: %g != %g", i, back.data[i], image.data[i]);
    unlink(path);
    free(path);
    sol_image_free(&image);
    sol_image_free(&back);
}

Test(core, png_round_trips_are_exact_for_8_and_16_bits)
{
    for (int channels = 1; channels <= 4; ++channels) {
        png_round_trip(channels, 8);
        png_round_trip(channels, 16);
    }
    remove_temp();
}

Test(core, png_write_refuses_bad_values_and_writes_nothing)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 2, 2, 1), SOL_OK);
    char *path = temp_path("bad.png");
    image.data[3] = NAN;
    cr_assert_eq(sol_png_write(path, &image, 8), SOL_ERR_NONFINITE);
    image.data[3] = 1.5f;
    cr_assert_eq(sol_png_write(path, &image, 16), SOL_ERR_OUT_OF_RANGE);
    image.data[3] = -0.0f;
    cr_assert_eq(sol_png_write(path, &image, 12), SOL_ERR_INVALID_ARG);
    cr_assert_neq(access(path, F_OK), 0);
    cr_assert_eq(sol_png_write(NULL, &image, 8), SOL_ERR_NULL_ARG);
    free(path);
    remove_temp();
    sol_image_free(&image);
}

Test(core, png_read_reports_missing_and_malformed_files)
{
    sol_image image = {.width = 9};
    cr_assert_eq(sol_png_read("/nonexistent/x.png", &image, NULL), SOL_ERR_IO);
    char *path = temp_path("not_a.png");
    FILE *f = fopen(path, "wb");
    fputs("this is not a PNG file at all", f);
    fclose(f);
    cr_assert_eq(sol_png_read(path, &image, NULL), SOL_ERR_FORMAT);
    /* a valid signature followed by garbage: libpng's error path must not print or crash */
    f = fopen(path, "wb");
    fwrite("\x89PNG\r\n\x1a\n garbage garbage garbage", 1, 33, f);
    fclose(f);
    cr_assert_eq(sol_png_read(path, &image, NULL), SOL_ERR_FORMAT);
    cr_assert_eq(image.width, 9);
    unlink(path);
    free(path);
    remove_temp();
}

Test(core, r2_points_lie_in_the_unit_square_and_fill_it_evenly)
{
    int cells[4][4] = {{0}};
    for (uint64_t n = 0; n < 16000; ++n) {
        double u, v;
        sol_r2_point(n, &u, &v);
        cr_assert(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0);
        cells[(int)(u * 4)][(int)(v * 4)]++;
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            cr_assert(abs(cells[i][j] - 1000) < 20, "cell %d,%d has %d points", i, j, cells[i][j]);
}

Test(core, sphere_map_gives_unit_vectors_including_the_poles)
{
    double corners[4][2] = {{0, 0}, {0.999999999, 0.5}, {0.5, 0.25}, {0.25, 0.999999}};
    for (int i = 0; i < 4; ++i) {
        double d[3];
        sol_sphere_uniform(corners[i][0], corners[i][1], d);
        cr_assert_float_eq(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-12);
    }
}

Test(core, angle_is_accurate_for_nearly_parallel_and_opposite_vectors)
{
    double a[3] = {1, 0, 0}, b[3] = {1, 1e-9, 0}, c[3] = {-1, 1e-9, 0}, z[3] = {0, 0, 0};
    cr_assert_float_eq(sol_angle3(a, b), 1e-9, 1e-20);
    cr_assert_float_eq(sol_angle3(a, c), M_PI - 1e-9, 1e-15);
    cr_assert_float_eq(sol_angle3(a, a), 0.0, 0.0);
    cr_assert_float_eq(sol_angle3(a, z), 0.0, 0.0);
}

Test(core, unorm_quantisation_follows_the_d3d_rules)
{
    cr_assert_eq(sol_unorm_encode(0.5, 8), 128u);
    cr_assert_eq(sol_unorm_encode(-1.0, 8), 0u);
    cr_assert_eq(sol_unorm_encode(2.0, 16), 65535u);
    cr_assert_eq(sol_unorm_encode(NAN, 8), 0u);
    cr_assert_eq(sol_unorm_encode(INFINITY, 8), 255u);
    cr_assert_eq(sol_unorm_encode(5e-324, 8), 0u);
    for (uint32_t code = 0; code < 256; ++code)
        cr_assert_eq(sol_unorm_encode(sol_unorm_decode(code, 8), 8), code);
}

Test(core, rng_streams_are_reproducible_and_uniform)
{
    uint64_t a = 42, b = 42;
    double sum = 0.0;
    for (int i = 0; i < 100000; ++i) {
        double x = sol_rng_uniform(&a, 0.0, 1.0);
        cr_assert(x >= 0.0 && x < 1.0);
        cr_assert_eq(sol_rng_next(&b) >> 11, (uint64_t)(x * 0x1.0p53)); /* same stream, exact */
        sum += x;
    }
    cr_assert_float_eq(sum / 100000.0, 0.5, 0.005);
    double y = sol_rng_uniform(&a, -1.0, 3.0);
    cr_assert(y >= -1.0 && y < 3.0);
}

Test(core, srgb_curve_round_trips_and_clamps)
{
    cr_assert_float_eq(sol_srgb_encode(0.0031308), 12.92 * 0.0031308, 1e-15);
    cr_assert_float_eq(sol_srgb_encode(1.0), 1.0, 1e-12);
    cr_assert_float_eq(sol_srgb_decode(0.5), 0.21404114048223255, 1e-12);
    for (int i = 0; i <= 1000; ++i)
        cr_assert_float_eq(sol_srgb_decode(sol_srgb_encode(i / 1000.0)), i / 1000.0, 1e-12);
    cr_assert_eq(sol_srgb_encode(NAN), 0.0);
    cr_assert_eq(sol_srgb_encode(-1.0), 0.0);
    cr_assert_eq(sol_srgb_decode(INFINITY), 1.0);
    cr_assert_eq(sol_srgb_encode(5e-324), 12.92 * 5e-324);
}
