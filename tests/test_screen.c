/* test_screen.c - the analytic box scene, the coverage buffer (M1), the post-process AA filter
 * (D17), volumetric obscurance (M3) and temporal AA (D18). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "sol_screen.h"

static const sol_camera test_camera = {.width = 64, .height = 32, .focal = 32.0, .znear = 0.1, .zfar = 100.0};

static uint64_t rng_state = 1; /* one deterministic core SplitMix64 stream for all tests */

static sol_box random_box(double zlo, double zhi, double size)
{
    sol_box b;
    double z = sol_rng_uniform(&rng_state, zlo, zhi);
    double c[3] = {sol_rng_uniform(&rng_state, -z, z), sol_rng_uniform(&rng_state, -0.5 * z, 0.5 * z), z};
    for (int i = 0; i < 3; ++i) {
        double h = sol_rng_uniform(&rng_state, 0.05, size);
        if (i == 2)
            h = fmin(h, 0.5 * z); /* stay in front of the near plane */
        b.min[i] = c[i] - h;
        b.max[i] = c[i] + h;
    }
    return b;
}

/* ---------------- scene ---------------- */

Test(screen, camera_and_box_checks_reject_bad_input)
{
    sol_camera cam = test_camera;
    cr_assert_eq(sol_camera_check(&cam), SOL_OK);
    cr_assert_eq(sol_camera_check(NULL), SOL_ERR_NULL_ARG);
    cam.focal = NAN;
    cr_assert_eq(sol_camera_check(&cam), SOL_ERR_NONFINITE);
    cam = test_camera;
    cam.zfar = cam.znear;
    cr_assert_eq(sol_camera_check(&cam), SOL_ERR_INVALID_ARG);
    cam = test_camera;
    cam.width = 0;
    cr_assert_eq(sol_camera_check(&cam), SOL_ERR_INVALID_ARG);
    sol_box box = {{-1, -1, 2}, {1, 1, 3}};
    cr_assert_eq(sol_box_check(&test_camera, &box), SOL_OK);
    box.max[0] = INFINITY;
    cr_assert_eq(sol_box_check(&test_camera, &box), SOL_ERR_NONFINITE);
    box.max[0] = -2; /* min > max */
    cr_assert_eq(sol_box_check(&test_camera, &box), SOL_ERR_INVALID_ARG);
    box = (sol_box){{-1, -1, 0.0}, {1, 1, 3}}; /* crosses the near plane */
    cr_assert_eq(sol_box_check(&test_camera, &box), SOL_ERR_INVALID_ARG);
}

Test(screen, depth_of_an_empty_scene_is_zfar_and_a_wall_is_exact)
{
    float depth[64 * 32];
    cr_assert_eq(sol_boxes_render_depth(&test_camera, NULL, 0, depth), SOL_OK);
    for (int i = 0; i < 64 * 32; ++i)
        cr_assert_eq(depth[i], 100.0f);
    sol_box wall = {{-100, -100, 7.5}, {100, 100, 8}};
    cr_assert_eq(sol_boxes_render_depth(&test_camera, &wall, 1, depth), SOL_OK);
    for (int i = 0; i < 64 * 32; ++i)
        cr_assert_eq(depth[i], 7.5f);
    /* A flat box (zero thickness in x) seen edge-on at x = 0 must not produce NaN. */
    sol_box flat = {{0, -1, 2}, {0, 1, 3}};
    cr_assert_eq(sol_boxes_render_depth(&test_camera, &flat, 1, depth), SOL_OK);
    for (int i = 0; i < 64 * 32; ++i)
        cr_assert(isfinite(depth[i]));
    sol_box bad = {{0, 0, NAN}, {1, 1, 1}};
    depth[0] = -1.0f;
    cr_assert_eq(sol_boxes_render_depth(&test_camera, &bad, 1, depth), SOL_ERR_NONFINITE);
    cr_assert_eq(depth[0], -1.0f, "output untouched on error");
}

Test(screen, screen_bounds_contain_every_covered_pixel_centre)
{
    float depth[64 * 32];
    for (int trial = 0; trial < 200; ++trial) {
        sol_box box = random_box(1.0, 20.0, 3.0);
        cr_assert_eq(sol_boxes_render_depth(&test_camera, &box, 1, depth), SOL_OK);
        sol_screen_bounds b;
        cr_assert_eq(sol_box_screen_bounds(&test_camera, &box, &b), SOL_OK);
        for (int py = 0; py < 32; ++py)
            for (int px = 0; px < 64; ++px)
                if (depth[py * 64 + px] < 100.0f) {
                    cr_assert(px + 0.5 >= b.x0 && px + 0.5 <= b.x1 && py + 0.5 >= b.y0 && py + 0.5 <= b.y1);
                    cr_assert_geq(depth[py * 64 + px], (float)b.znear * (1.0f - 1e-6f));
                }
    }
}

/* ---------------- M1: coverage buffer ---------------- */

Test(screen, cbuffer_rejects_bad_input_and_handles_a_1x1_buffer)
{
    sol_cbuffer cb = {.levels = 99};
    float one = 5.0f, bad[4] = {1, 2, NAN, 4};
    cr_assert_eq(sol_cbuffer_build(NULL, 1, 1, NULL, &cb), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_cbuffer_build(&one, 0, 1, NULL, &cb), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_cbuffer_build(bad, 2, 2, NULL, &cb), SOL_ERR_NONFINITE);
    sol_cbuffer_options bad_opt = {.block = -1};
    cr_assert_eq(sol_cbuffer_build(&one, 1, 1, &bad_opt, &cb), SOL_ERR_INVALID_ARG);
    bad_opt = (sol_cbuffer_options){.downscale = (sol_downscale)7};
    cr_assert_eq(sol_cbuffer_build(&one, 1, 1, &bad_opt, &cb), SOL_ERR_INVALID_ARG);
    cr_assert_eq(cb.levels, 99, "output untouched on error");
    cr_assert_eq(sol_cbuffer_build(&one, 1, 1, NULL, &cb), SOL_OK);
    cr_assert_eq(cb.levels, 1);
    int occluded = -1, visited = -1;
    sol_screen_bounds behind = {0.2, 0.2, 0.8, 0.8, 6.0}, in_front = {0.2, 0.2, 0.8, 0.8, 4.0};
    cr_assert_eq(sol_cbuffer_test(&cb, &behind, -1, &occluded, &visited), SOL_OK);
    cr_assert_eq(occluded, 1);
    cr_assert_eq(visited, 1);
    cr_assert_eq(sol_cbuffer_test(&cb, &in_front, -1, &occluded, NULL), SOL_OK);
    cr_assert_eq(occluded, 0);
    sol_screen_bounds nan_bounds = {NAN, 0, 1, 1, 6.0}, flipped = {1, 0, 0, 1, 6.0}, off = {5, 5, 9, 9, 6.0};
    cr_assert_eq(sol_cbuffer_test(&cb, &nan_bounds, -1, &occluded, NULL), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_cbuffer_test(&cb, &flipped, -1, &occluded, NULL), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_cbuffer_test(&cb, &off, -1, &occluded, NULL), SOL_OK);
    cr_assert_eq(occluded, 0, "bounds outside the image are not occlusion-culled");
    sol_cbuffer_free(&cb);
    cr_assert_eq(cb.levels, 0);
    sol_cbuffer_free(&cb);
    sol_cbuffer_free(NULL);
}

Test(screen, cbuffer_levels_hold_min_and_max_of_odd_sizes)
{
    enum { W = 13, H = 7 };
    float depth[W * H];
    for (int i = 0; i < W * H; ++i)
        depth[i] = (float)((i * 37) % 101);
    sol_cbuffer_options opt = {.block = 2};
    sol_cbuffer cb;
    cr_assert_eq(sol_cbuffer_build(depth, W, H, &opt, &cb), SOL_OK);
    cr_assert_eq(cb.width[0], 7);
    cr_assert_eq(cb.height[0], 4);
    cr_assert_eq(cb.width[cb.levels - 1], 1);
    cr_assert_eq(cb.height[cb.levels - 1], 1);
    float lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < W * H; ++i) {
        lo = fminf(lo, depth[i]);
        hi = fmaxf(hi, depth[i]);
    }
    /* The top's zmax is the farthest depth; its zmin the nearest of the block maxima. */
    cr_assert_eq(cb.zmax[cb.levels - 1][0], hi);
    cr_assert_geq(cb.zmin[cb.levels - 1][0], lo);
    sol_cbuffer_free(&cb);
}

/* M1: with the max() downscale no box that is visible at some pixel is ever culled, whatever the
 * refinement depth; min() downscale does cull visible boxes on the same scene. */
Test(screen, m1_max_downscale_never_culls_a_visible_box)
{
    enum { N_OCC = 12, N_TEST = 1500 };
    sol_box occluders[N_OCC];
    for (int i = 0; i < N_OCC; ++i)
        occluders[i] = random_box(2.0, 10.0, 4.0);
    float depth[64 * 32];
    cr_assert_eq(sol_boxes_render_depth(&test_camera, occluders, N_OCC, depth), SOL_OK);
    sol_cbuffer cons, near;
    sol_cbuffer_options max_opt = {0}, min_opt = {.downscale = SOL_DOWNSCALE_MIN};
    cr_assert_eq(sol_cbuffer_build(depth, 64, 32, &max_opt, &cons), SOL_OK);
    cr_assert_eq(sol_cbuffer_build(depth, 64, 32, &min_opt, &near), SOL_OK);
    int culled = 0, false_culls_min = 0;
    for (int t = 0; t < N_TEST; ++t) {
        sol_box box = random_box(2.0, 30.0, 1.0);
        sol_screen_bounds b;
        int visible, occluded;
        cr_assert_eq(sol_box_screen_bounds(&test_camera, &box, &b), SOL_OK);
        cr_assert_eq(sol_box_visible(&test_camera, depth, &box, &visible), SOL_OK);
        for (int refine = -1; refine <= 2; ++refine) {
            cr_assert_eq(sol_cbuffer_test(&cons, &b, refine, &occluded, NULL), SOL_OK);
            cr_assert(!(occluded && visible), "false cull of box %d (refine %d)", t, refine);
            culled += occluded;
        }
        cr_assert_eq(sol_cbuffer_test(&near, &b, -1, &occluded, NULL), SOL_OK);
        false_culls_min += occluded && visible;
    }
    cr_assert_gt(culled, 0, "the test must cull something to mean anything");
    cr_assert_gt(false_culls_min, 0, "the non-conservative min() downscale should cull visible boxes");
    sol_cbuffer_free(&cons);
    sol_cbuffer_free(&near);
}

/* ---------------- D17: post-process AA ---------------- */

/* D17: the effective 3x3 kernel of each fetch placement, from the impulse response. */
static void kernel_of(sol_postaa_taps taps, double kernel[9])
{
    sol_image img;
    cr_assert_eq(sol_image_alloc(&img, 5, 5, 1), SOL_OK);
    for (int k = 0; k < 9; ++k) {
        for (int i = 0; i < 25; ++i)
            img.data[i] = 0.0f;
        img.data[(1 + k / 3) * 5 + 1 + k % 3] = 1.0f;
        float mean, dev;
        cr_assert_eq(sol_postaa_neighbourhood(&img, 2, 2, taps, &mean, &dev), SOL_OK);
        kernel[k] = mean;
    }
    sol_image_free(&img);
}

Test(screen, d17_pinwheel_taps_are_exactly_the_8_neighbour_mean)
{
    double k[9];
    kernel_of(SOL_POSTAA_PINWHEEL4, k);
    for (int i = 0; i < 9; ++i)
        cr_assert_eq(k[i], i == 4 ? 0.0 : 0.125, "kernel[%d] = %g", i, k[i]);
    kernel_of(SOL_POSTAA_DIRECT8, k);
    for (int i = 0; i < 9; ++i)
        cr_assert_eq(k[i], i == 4 ? 0.0 : 0.125);
    kernel_of(SOL_POSTAA_DIAGONAL4, k);
    static const double tent[9] = {1, 2, 1, 2, 4, 2, 1, 2, 1};
    for (int i = 0; i < 9; ++i)
        cr_assert_eq(k[i], tent[i] / 16.0, "kernel[%d] = %g", i, k[i]);
}

Test(screen, d17_fetched_deviation_never_exceeds_the_talks_d)
{
    sol_image img;
    cr_assert_eq(sol_image_alloc(&img, 9, 7, 3), SOL_OK);
    for (int i = 0; i < 9 * 7 * 3; ++i)
        img.data[i] = (float)sol_rng_uniform(&rng_state, 0.0, 1.0);
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 9; ++x) {
            float m4[3], m8[3], d4, d8;
            cr_assert_eq(sol_postaa_neighbourhood(&img, x, y, SOL_POSTAA_PINWHEEL4, m4, &d4), SOL_OK);
            cr_assert_eq(sol_postaa_neighbourhood(&img, x, y, SOL_POSTAA_DIRECT8, m8, &d8), SOL_OK);
            cr_assert_leq(d4, d8 * (1.0f + 1e-5f) + 1e-6f);
            for (int c = 0; c < 3; ++c)
                cr_assert_float_eq(m4[c], m8[c], 1e-5f);
        }
    sol_image_free(&img);
}

Test(screen, d17_filter_edges_1x1_flat_and_bad_input)
{
    sol_image one, out = {.width = 42};
    cr_assert_eq(sol_image_alloc(&one, 1, 1, 3), SOL_OK);
    one.data[0] = 0.25f;
    cr_assert_eq(sol_postaa_filter(&one, NULL, &out), SOL_OK); /* every fetch clamps to the pixel */
    cr_assert_eq(out.data[0], 0.25f);
    sol_image_free(&out);
    one.data[1] = NAN;
    out.width = 42;
    cr_assert_eq(sol_postaa_filter(&one, NULL, &out), SOL_ERR_NONFINITE);
    cr_assert_eq(out.width, 42, "output untouched on error");
    one.data[1] = 0.0f;
    sol_postaa_options opt = {.threshold = -1.0};
    cr_assert_eq(sol_postaa_filter(&one, &opt, &out), SOL_ERR_INVALID_ARG);
    opt = (sol_postaa_options){.threshold = INFINITY};
    cr_assert_eq(sol_postaa_filter(&one, &opt, &out), SOL_ERR_NONFINITE);
    opt = (sol_postaa_options){.taps = (sol_postaa_taps)9};
    cr_assert_eq(sol_postaa_filter(&one, &opt, &out), SOL_ERR_INVALID_ARG);
    float mean[3], dev;
    cr_assert_eq(sol_postaa_neighbourhood(&one, 1, 0, SOL_POSTAA_PINWHEEL4, mean, &dev), SOL_ERR_INVALID_ARG);
    sol_image empty = {0};
    cr_assert_eq(sol_postaa_filter(&empty, NULL, &out), SOL_ERR_INVALID_ARG);
    sol_image_free(&one);
    /* A flat image has zero deviation everywhere and passes unchanged. */
    sol_image flat;
    cr_assert_eq(sol_image_alloc(&flat, 6, 4, 1), SOL_OK);
    for (int i = 0; i < 24; ++i)
        flat.data[i] = 0.7f;
    cr_assert_eq(sol_postaa_filter(&flat, NULL, &out), SOL_OK);
    for (int i = 0; i < 24; ++i)
        cr_assert_eq(out.data[i], 0.7f);
    sol_image_free(&out);
    sol_image_free(&flat);
}

Test(screen, d17_filter_softens_a_hard_edge)
{
    sol_image img, out;
    cr_assert_eq(sol_image_alloc(&img, 8, 8, 1), SOL_OK);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            img.data[y * 8 + x] = x < 4 ? 0.0f : 1.0f;
    cr_assert_eq(sol_postaa_filter(&img, NULL, &out), SOL_OK);
    cr_assert_gt(out.data[3 * 8 + 3], 0.0f);
    cr_assert_lt(out.data[3 * 8 + 4], 1.0f);
    cr_assert_eq(out.data[3 * 8 + 0], 0.0f, "pixels away from the edge keep their value");
    sol_image_free(&out);
    sol_image_free(&img);
}

/* ---------------- M3: volumetric obscurance ---------------- */

static void fill(float *v, size_t n, float value)
{
    for (size_t i = 0; i < n; ++i)
        v[i] = value;
}

Test(screen, m3_vo_of_a_facing_wall_is_one_half_and_background_is_zero)
{
    float depth[64 * 32], vo[64 * 32];
    fill(depth, 64 * 32, 5.0f);
    for (int samples = 1; samples <= 64; samples *= 4) {
        sol_vo_options opt = {.radius = 0.5, .samples = samples, .frame = 3};
        cr_assert_eq(sol_vo_compute(&test_camera, depth, &opt, vo), SOL_OK);
        for (int i = 0; i < 64 * 32; ++i)
            cr_assert_float_eq(vo[i], 0.5f, 1e-6f);
    }
    fill(depth, 64 * 32, 100.0f); /* zfar: background */
    cr_assert_eq(sol_vo_compute(&test_camera, depth, NULL, vo), SOL_OK);
    for (int i = 0; i < 64 * 32; ++i)
        cr_assert_eq(vo[i], 0.0f);
}

Test(screen, m3_vo_sees_creases_above_and_ridges_below_one_half)
{
    sol_box scene[2] = {{{-100, -100, 10}, {100, 100, 11}}, {{-1, -1, 6}, {1, 1, 7}}};
    float depth[64 * 32], vo[64 * 32];
    cr_assert_eq(sol_boxes_render_depth(&test_camera, scene, 2, depth), SOL_OK);
    sol_vo_options opt = {.radius = 1.5, .samples = 256, .same_rotation_everywhere = 1};
    cr_assert_eq(sol_vo_compute(&test_camera, depth, &opt, vo), SOL_OK);
    /* The box spans x in [32 - 32/6*1, 32 + 32/6] ~ [26.7, 37.3] pixels at depth 6. */
    cr_assert_gt(vo[16 * 64 + 24], 0.5f, "wall pixel beside the box is occluded by it");
    cr_assert_lt(vo[16 * 64 + 27], 0.5f, "box pixel at its silhouette sees open space");
    cr_assert_float_eq(vo[16 * 64 + 2], 0.5f, 1e-6f); /* wall far from the box */
}

Test(screen, m3_vo_rejects_bad_input_and_handles_1x1)
{
    const sol_camera one = {.width = 1, .height = 1, .focal = 1.0, .znear = 0.1, .zfar = 10.0};
    float depth = 2.0f, vo = -7.0f;
    cr_assert_eq(sol_vo_compute(&one, &depth, NULL, &vo), SOL_OK);
    cr_assert_float_eq(vo, 0.5f, 1e-6f); /* every sample clamps to the pixel itself */
    vo = -7.0f;
    sol_vo_options bad = {.radius = -1.0};
    cr_assert_eq(sol_vo_compute(&one, &depth, &bad, &vo), SOL_ERR_INVALID_ARG);
    bad = (sol_vo_options){.radius = NAN};
    cr_assert_eq(sol_vo_compute(&one, &depth, &bad, &vo), SOL_ERR_NONFINITE);
    bad = (sol_vo_options){.samples = 5000};
    cr_assert_eq(sol_vo_compute(&one, &depth, &bad, &vo), SOL_ERR_INVALID_ARG);
    depth = INFINITY;
    cr_assert_eq(sol_vo_compute(&one, &depth, NULL, &vo), SOL_ERR_NONFINITE);
    cr_assert_eq(vo, -7.0f, "output untouched on error");
    cr_assert_eq(sol_vo_compute(&one, NULL, NULL, &vo), SOL_ERR_NULL_ARG);
}

Test(screen, m3_half_depth_and_bilateral_upsampling)
{
    float depth[5 * 3], half[3 * 2], values[3 * 2], out[5 * 3];
    for (int i = 0; i < 15; ++i)
        depth[i] = (float)(1 + i);
    cr_assert_eq(sol_depth_half(depth, 5, 3, half), SOL_OK);
    cr_assert_eq(half[0], 1.0f);
    cr_assert_eq(half[2], 5.0f);
    cr_assert_eq(half[3], 11.0f);
    fill(values, 6, 0.3f);
    cr_assert_eq(sol_bilateral_upsample(values, half, depth, 5, 3, out), SOL_OK);
    for (int i = 0; i < 15; ++i)
        cr_assert_float_eq(out[i], 0.3f, 1e-6f, "a constant signal stays constant");
    /* Depth-aware: a pixel takes the value of the half texel at its own depth. */
    float d2[4] = {1, 1, 9, 9}, h2[1], v2[1] = {0.8f}, o2[4];
    cr_assert_eq(sol_depth_half(d2, 2, 2, h2), SOL_OK);
    cr_assert_eq(sol_bilateral_upsample(v2, h2, d2, 2, 2, o2), SOL_OK);
    cr_assert_float_eq(o2[3], 0.8f, 1e-6f);
    cr_assert_eq(sol_depth_half(depth, 0, 3, half), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_bilateral_upsample(NULL, half, depth, 5, 3, out), SOL_ERR_NULL_ARG);
}

/* ---------------- D18 / M3: temporal accumulation ---------------- */

static const sol_camera small_camera = {.width = 8, .height = 6, .focal = 8.0, .znear = 0.1, .zfar = 100.0};

Test(screen, temporal_still_camera_averages_frames_and_caps_history)
{
    sol_history h[2];
    cr_assert_eq(sol_history_alloc(&h[0], 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&h[1], 8, 6, 1), SOL_OK);
    float depth[48], cur[48];
    fill(depth, 48, 4.0f);
    const double still[3] = {0, 0, 0};
    sol_temporal_options opt = {.max_frames = 100};
    for (int f = 0; f < 4; ++f) {
        fill(cur, 48, (float)(f % 2)); /* 0, 1, 0, 1: the running mean is 0.5 */
        cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, &opt, &h[f % 2], &h[(f + 1) % 2]), SOL_OK);
    }
    for (int i = 0; i < 48; ++i) {
        cr_assert_float_eq(h[0].values[i], 0.5f, 1e-6f);
        cr_assert_eq(h[0].frames[i], 4.0f);
    }
    /* A history cap of 2 keeps the weight of the new frame at >= 1/2. */
    opt.max_frames = 2;
    fill(cur, 48, 1.0f);
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, &opt, &h[0], &h[1]), SOL_OK);
    cr_assert_float_eq(h[1].values[0], 0.75f, 1e-6f);
    sol_history_free(&h[0]);
    sol_history_free(&h[1]);
}

/* D18: a depth change is a cache miss (history dropped); without the depth test it ghosts. */
Test(screen, d18_depth_change_is_a_cache_miss_and_no_test_ghosts)
{
    sol_history prev, next;
    cr_assert_eq(sol_history_alloc(&prev, 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&next, 8, 6, 1), SOL_OK);
    fill(prev.values, 48, 1.0f);
    fill(prev.depth, 48, 4.0f);
    fill(prev.frames, 48, 8.0f);
    float depth[48], cur[48];
    fill(depth, 48, 2.0f); /* something moved in front */
    fill(cur, 48, 0.0f);
    const double still[3] = {0, 0, 0};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, NULL, &prev, &next), SOL_OK);
    cr_assert_eq(next.values[20], 0.0f);
    cr_assert_eq(next.frames[20], 1.0f);
    sol_temporal_options off = {.no_depth_test = 1};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, &off, &prev, &next), SOL_OK);
    cr_assert_float_eq(next.values[20], 8.0f / 9.0f, 1e-6f, "the old value ghosts");
    /* Motion that carries every point out of the previous image is a miss everywhere. */
    const double far_away[3] = {1000, 0, 0};
    fill(depth, 48, 4.0f);
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, far_away, &off, &prev, &next), SOL_OK);
    for (int i = 0; i < 48; ++i)
        cr_assert_eq(next.frames[i], 1.0f);
    sol_history_free(&prev);
    sol_history_free(&next);
}

/* An 8x6 history of a wall at depth 4 seen for one frame, with value x (or x^2 when quadratic) in
 * column x, an empty next history, and the current frame: the same wall, value 0. */
static void wall_histories(sol_history *prev, sol_history *next, float depth[48], float cur[48], int quadratic)
{
    cr_assert_eq(sol_history_alloc(prev, 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(next, 8, 6, 1), SOL_OK);
    for (int i = 0; i < 48; ++i) {
        double x = i % 8;
        prev->values[i] = (float)(quadratic ? x * x : x);
        prev->depth[i] = 4.0f;
        prev->frames[i] = 1.0f;
    }
    fill(depth, 48, 4.0f);
    fill(cur, 48, 0.0f);
}

Test(screen, temporal_reprojection_follows_a_sideways_camera_move)
{
    /* A wall at depth 4 and a camera moved by 4/8 units right: one pixel of parallax. */
    sol_history prev, next;
    float depth[48], cur[48];
    wall_histories(&prev, &next, depth, cur, 0);
    const double motion[3] = {0.5, 0, 0};
    sol_temporal_options opt = {.max_frames = 1e9};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, motion, &opt, &prev, &next), SOL_OK);
    /* Pixel x sees what pixel x+1 saw: history value x+1, blended 1:1 with the current 0. */
    cr_assert_float_eq(next.values[2 * 8 + 3], 0.5f * 4.0f, 1e-5f);
    cr_assert_eq(next.frames[2 * 8 + 7], 1.0f, "the right column came into view: a miss");
    sol_history_free(&prev);
    sol_history_free(&next);
}

/* D18's history filters: at a half-pixel reprojection Catmull-Rom reproduces a quadratic exactly
 * (Keys 1981: third-order accurate), bilinear is off by 1/4 of the second difference; the edge
 * columns stay finite (outer taps clamp to the inner ones) and the miss rule is bilinear's. */
Test(screen, d18_catmull_rom_history_is_exact_on_a_quadratic)
{
    sol_history prev, next;
    float depth[48], cur[48];
    wall_histories(&prev, &next, depth, cur, 1);
    const double half_pixel[3] = {0.25, 0, 0};
    sol_temporal_options cr = {.max_frames = 1e9, .filter = SOL_HISTORY_CATMULL_ROM}, bl = {.max_frames = 1e9};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, half_pixel, &cr, &prev, &next), SOL_OK);
    for (int x = 1; x <= 5; ++x)
        cr_assert_float_eq(next.values[3 * 8 + x], 0.5f * (float)((x + 0.5) * (x + 0.5)), 1e-4f, "x %d", x);
    cr_assert(isfinite(next.values[3 * 8]) && isfinite(next.values[3 * 8 + 6]));
    cr_assert_eq(next.frames[3 * 8 + 7], 1.0f, "the right column is a miss, as with bilinear");
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, half_pixel, &bl, &prev, &next), SOL_OK);
    for (int x = 1; x <= 5; ++x)
        cr_assert_float_eq(next.values[3 * 8 + x], 0.5f * (float)((x + 0.5) * (x + 0.5) + 0.25), 1e-4f, "x %d", x);
    sol_temporal_options unknown = {.filter = (sol_history_filter)5};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, half_pixel, &unknown, &prev, &next),
                 SOL_ERR_INVALID_ARG);
    sol_history_free(&prev);
    sol_history_free(&next);
}

Test(screen, temporal_rejects_bad_input)
{
    sol_history a, b, wrong;
    cr_assert_eq(sol_history_alloc(&a, 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&b, 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&wrong, 4, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&wrong, 0, 6, 1), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_history_alloc(&wrong, 8, 6, 5), SOL_ERR_INVALID_ARG);
    float depth[48], cur[48];
    fill(depth, 48, 4.0f);
    fill(cur, 48, 0.5f);
    const double still[3] = {0, 0, 0}, bad_motion[3] = {NAN, 0, 0};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, NULL, &a, &wrong), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, NULL, &a, &a), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, bad_motion, NULL, &a, &b), SOL_ERR_NONFINITE);
    sol_temporal_options neg = {.max_frames = -1};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, &neg, &a, &b), SOL_ERR_INVALID_ARG);
    depth[5] = NAN;
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, NULL, &a, &b), SOL_ERR_NONFINITE);
    cr_assert_eq(b.frames[0], 0.0f, "output untouched on error");
    sol_history_free(&a);
    sol_history_free(&b);
    sol_history_free(&wrong);
    sol_history_free(NULL);
}

Test(screen, d18_jitter_offsets_stay_inside_the_pixel)
{
    double sx = 0, sy = 0;
    for (unsigned f = 0; f < 1000; ++f) {
        double dx, dy;
        sol_jitter_offset(f, &dx, &dy);
        cr_assert(dx >= -0.5 && dx < 0.5 && dy >= -0.5 && dy < 0.5);
        sx += dx;
        sy += dy;
    }
    cr_assert_lt(fabs(sx / 1000), 0.01, "jitter is centred");
    cr_assert_lt(fabs(sy / 1000), 0.01);
}

/* D18: at a silhouette, the 3x3 depth-range test keeps the history that the 1-pixel test drops. */
Test(screen, d18_edge_tolerant_test_accepts_a_neighbouring_depth)
{
    sol_history prev, next;
    cr_assert_eq(sol_history_alloc(&prev, 8, 6, 1), SOL_OK);
    cr_assert_eq(sol_history_alloc(&next, 8, 6, 1), SOL_OK);
    for (int i = 0; i < 48; ++i) {
        prev.values[i] = 1.0f;
        prev.depth[i] = (i % 8) < 4 ? 2.0f : 9.0f; /* a silhouette between columns 3 and 4 */
        prev.frames[i] = 4.0f;
    }
    float depth[48], cur[48];
    for (int i = 0; i < 48; ++i)
        depth[i] = (i % 8) < 3 ? 2.0f : 9.0f; /* this frame's jittered sample saw the far side in column 3 */
    fill(cur, 48, 0.0f);
    const double still[3] = {0, 0, 0};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, NULL, &prev, &next), SOL_OK);
    cr_assert_eq(next.frames[2 * 8 + 3], 1.0f, "1-pixel test: a miss at the silhouette");
    sol_temporal_options edge = {.edge_tolerant = 1};
    cr_assert_eq(sol_temporal_accumulate(&small_camera, depth, cur, still, &edge, &prev, &next), SOL_OK);
    cr_assert_eq(next.frames[2 * 8 + 3], 5.0f, "3x3 test: the history is kept");
    cr_assert_eq(next.frames[2 * 8 + 1], 5.0f);
    sol_history_free(&prev);
    sol_history_free(&next);
}
