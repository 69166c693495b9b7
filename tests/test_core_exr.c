/* test_core_exr.c - OpenEXR files through the core C API: round trips, layouts, refusals. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>

#include "sol_core.h"

static char scratch[] = "/tmp/sol_exr_XXXXXX";
static int scratch_made; /* a flag, not a look at the name: mkdtemp's random letters may be X */

static const char *scratch_file(const char *name)
{
    static char path[4096];
    if (!scratch_made)
        cr_assert_not_null(mkdtemp(scratch));
    scratch_made = 1;
    snprintf(path, sizeof path, "%s/%s", scratch, name);
    return path;
}

static void clean_scratch(const char *path)
{
    unlink(path);
    rmdir(scratch);
    memcpy(scratch + sizeof scratch - 7, "XXXXXX", 6); /* the next file gets a fresh folder */
    scratch_made = 0;
}

/* Values exactly representable in half: small integers over powers of two, and a large one. */
static float half_exact_value(int i)
{
    static const float values[8] = {0.0f, 1.0f, 0.5f, 65504.0f, 0.000061035156f, -2.25f, 1024.0f, 0.099975586f};
    return values[i % 8] * (float)(1 << (i % 3)); /* powers of two keep them exact */
}

static void round_trip(int channels, int half_precision)
{
    sol_image image = {0}, back = {0};
    cr_assert_eq(sol_image_alloc(&image, 7, 5, channels), SOL_OK);
    for (int i = 0; i < 35 * channels; ++i)
        image.data[i] = half_precision ? fminf(half_exact_value(i), 65504.0f) : (float)i * 1.37e5f - 3.0f;
    const char *path = scratch_file("round_trip.exr");
    cr_assert_eq(sol_exr_write(path, &image, half_precision), SOL_OK);
    cr_assert_eq(sol_exr_read(path, &back), SOL_OK);
    cr_assert_eq(back.width, 7);
    cr_assert_eq(back.height, 5);
    cr_assert_eq(back.channels, channels);
    for (int i = 0; i < 35 * channels; ++i)
        cr_assert_eq(back.data[i], image.data[i], "%d channels, half %d, value %d: %g != %g", channels,
                     half_precision, i, back.data[i], image.data[i]);
    clean_scratch(path);
    sol_image_free(&image);
    sol_image_free(&back);
}

Test(core_exr, round_trips_every_layout_in_half_and_float_bit_exactly)
{
    for (int channels = 1; channels <= 4; ++channels) {
        round_trip(channels, 1);
        round_trip(channels, 0);
    }
}

Test(core_exr, a_tall_image_spans_many_chunks)
{
    sol_image image = {0}, back = {0};
    cr_assert_eq(sol_image_alloc(&image, 3, 101, 3), SOL_OK);
    for (int i = 0; i < 3 * 101 * 3; ++i)
        image.data[i] = (float)i;
    const char *path = scratch_file("tall.exr");
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_OK);
    cr_assert_eq(sol_exr_read(path, &back), SOL_OK);
    cr_assert_eq(memcmp(back.data, image.data, sizeof(float) * 3 * 101 * 3), 0);
    clean_scratch(path);
    sol_image_free(&image);
    sol_image_free(&back);
}

Test(core_exr, write_refuses_bad_values_and_leaves_no_file)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 2, 2, 3), SOL_OK);
    const char *path = scratch_file("bad.exr");
    image.data[5] = NAN;
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_ERR_NONFINITE);
    image.data[5] = -INFINITY;
    cr_assert_eq(sol_exr_write(path, &image, 1), SOL_ERR_NONFINITE);
    image.data[5] = 65520.0f; /* rounds to Inf in half */
    cr_assert_eq(sol_exr_write(path, &image, 1), SOL_ERR_OUT_OF_RANGE);
    cr_assert_neq(access(path, F_OK), 0);
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_OK); /* fine as float */
    cr_assert_eq(sol_exr_write(NULL, &image, 0), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_exr_write("/nonexistent/dir/x.exr", &image, 0), SOL_ERR_IO);
    clean_scratch(path);
    sol_image_free(&image);
}

Test(core_exr, read_tells_missing_from_malformed_and_leaves_output_untouched)
{
    sol_image image = {.width = 11};
    cr_assert_eq(sol_exr_read("/nonexistent/x.exr", &image), SOL_ERR_IO);
    const char *path = scratch_file("not.exr");
    FILE *f = fopen(path, "wb");
    fputs("v/1\x01 this is not an OpenEXR file", f);
    fclose(f);
    cr_assert_eq(sol_exr_read(path, &image), SOL_ERR_FORMAT);
    cr_assert_eq(sol_exr_read(NULL, &image), SOL_ERR_NULL_ARG);
    cr_assert_eq(image.width, 11);
    clean_scratch(path);
}
