/* test_pipeline.c - G-buffer layouts (D1): sizes from the format tables, and refusals. */
#include <criterion/criterion.h>

#include "sol_pipeline.h"

static unsigned bits_of(sol_gbuffer_kind kind)
{
    const sol_gbuffer_layout *layout = NULL;
    unsigned bits = 0;
    cr_assert_eq(sol_gbuffer_layout_get(kind, &layout), SOL_OK);
    cr_assert_eq(sol_gbuffer_bits_per_pixel(layout, &bits), SOL_OK);
    return bits;
}

Test(pipeline, d1_layouts_give_the_talks_bits_per_pixel)
{
    cr_assert_eq(bits_of(SOL_GBUFFER_CLASSIC_NARROW), 112);
    cr_assert_eq(bits_of(SOL_GBUFFER_CLASSIC_WIDE), 144);
    cr_assert_eq(bits_of(SOL_GBUFFER_LIGHT_PREPASS), 96);
    cr_assert_eq(bits_of(SOL_GBUFFER_CRYENGINE3), 64);
}

Test(pipeline, every_format_has_a_size_and_a_name)
{
    for (int f = 0; f < SOL_PIXEL_FORMAT_COUNT; ++f) {
        cr_assert_gt(sol_pixel_format_bits((sol_pixel_format)f), 0u);
        cr_assert_str_neq(sol_pixel_format_name((sol_pixel_format)f), "unknown");
    }
    cr_assert_eq(sol_pixel_format_bits(SOL_PIXEL_FORMAT_COUNT), 0u);
    cr_assert_eq(sol_pixel_format_bits((sol_pixel_format)-1), 0u);
    cr_assert_str_eq(sol_pixel_format_name((sol_pixel_format)-1), "unknown");
}

Test(pipeline, frame_bytes_scale_with_msaa_samples)
{
    const sol_gbuffer_layout *layout = NULL;
    uint64_t one = 0, four = 0;
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, &layout), SOL_OK);
    cr_assert_eq(sol_gbuffer_bytes(layout, 1280, 720, 1, &one), SOL_OK);
    cr_assert_eq(sol_gbuffer_bytes(layout, 1280, 720, 4, &four), SOL_OK);
    cr_assert_eq(one, 1280u * 720u * 8u);
    cr_assert_eq(four, 4 * one);
}

Test(pipeline, bad_layouts_and_arguments_are_refused_without_writing)
{
    const sol_gbuffer_layout *layout = NULL;
    unsigned bits = 7;
    uint64_t bytes = 9;
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_KIND_COUNT, &layout), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, NULL), SOL_ERR_NULL_ARG);
    cr_assert_null(layout);
    sol_gbuffer_layout broken = {.name = "broken", .target_count = 0};
    cr_assert_eq(sol_gbuffer_bits_per_pixel(&broken, &bits), SOL_ERR_INVALID_ARG);
    broken.target_count = 1;
    broken.targets[0].format = (sol_pixel_format)99;
    cr_assert_eq(sol_gbuffer_bits_per_pixel(&broken, &bits), SOL_ERR_INVALID_ARG);
    broken.target_count = SOL_GBUFFER_MAX_TARGETS + 1;
    cr_assert_eq(sol_gbuffer_bits_per_pixel(&broken, &bits), SOL_ERR_INVALID_ARG);
    cr_assert_eq(bits, 7u);
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, &layout), SOL_OK);
    cr_assert_eq(sol_gbuffer_bytes(layout, 0, 720, 1, &bytes), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_gbuffer_bytes(layout, 1280, 720, 3, &bytes), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_gbuffer_bytes(NULL, 1280, 720, 1, &bytes), SOL_ERR_NULL_ARG);
    cr_assert_eq(bytes, 9u);
}
