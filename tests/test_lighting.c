/* test_lighting.c - S4 DFG, S7 hemicube weights, S8 PCF, S2 light accumulation, D13 clip volumes. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "sol_lighting.h"

/* ---------------- S4: DFG ---------------- */

/* Brute force over the light direction (no importance sampling), an independent check. */
static void dfg_brute_force(double alpha, double nv, int n, double *scale, double *bias)
{
    double a2 = alpha * alpha, vx = sqrt(1 - nv * nv), s = 0, b = 0;
    double vis_v = nv + sqrt(a2 + (1 - a2) * nv * nv);
    for (int j = 0; j < n; ++j) {
        double u = (j + 0.5) / n, st = sqrt(1 - u * u); /* u = n.l */
        for (int i = 0; i < n; ++i) {
            double phi = M_PI * (i + 0.5) / n;
            double hx = st * cos(phi) + vx, hy = st * sin(phi), hz = u + nv;
            double len = sqrt(hx * hx + hy * hy + hz * hz);
            double vh = (vx * hx + nv * hz) / len, c2 = hz * hz / (len * len);
            double d = c2 * (a2 - 1) + 1, ndf = a2 / (M_PI * d * d);
            double f = ndf * u / (vis_v * (u + sqrt(a2 + (1 - a2) * u * u)));
            double fc = pow(1 - vh, 5);
            s += f * (1 - fc);
            b += f * fc;
        }
    }
    *scale = s * 2 * M_PI / ((double)n * n);
    *bias = b * 2 * M_PI / ((double)n * n);
}

Test(lighting, s4_dfg_quadrature_matches_brute_force)
{
    const double cases[][2] = {{1.0, 0.5}, {0.5, 0.9}, {0.3, 0.2}, {0.15, 0.05}, {0.8, 1.0}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k) {
        double s, b, rs, rb;
        cr_assert_eq(sol_dfg_integrate(cases[k][0], cases[k][1], 128, &s, &b), SOL_OK);
        dfg_brute_force(cases[k][0], cases[k][1], 1500, &rs, &rb);
        cr_expect_float_eq(s, rs, 2e-3, "scale alpha %g nv %g: %g vs %g", cases[k][0], cases[k][1], s, rs);
        cr_expect_float_eq(b, rb, 2e-3, "bias alpha %g nv %g: %g vs %g", cases[k][0], cases[k][1], b, rb);
    }
}

Test(lighting, s4_dfg_mirror_limit_is_schlick_fresnel)
{
    /* alpha -> 0 (gloss 1): the lobe is a mirror, DFG = Fresnel at the view angle. */
    for (double nv = 0.05; nv <= 1.0; nv += 0.15) {
        double s, b, fc = pow(1 - nv, 5);
        cr_assert_eq(sol_dfg_integrate(sol_dfg_alpha_from_gloss(1.0), nv, 16, &s, &b), SOL_OK);
        cr_expect_float_eq(s, 1 - fc, 1e-9);
        cr_expect_float_eq(b, fc, 1e-9);
        cr_assert_eq(sol_dfg_integrate(1e-6, nv, 64, &s, &b), SOL_OK); /* tiny roughness */
        cr_expect_float_eq(s + b, 1.0, 1e-4);
    }
}

Test(lighting, s4_dfg_grazing_and_edges_stay_finite)
{
    const double alphas[] = {0.0, 1e-300, 1e-8, 0.01, 0.5, 1.0};
    const double nvs[] = {0.0, DBL_MIN, 1e-12, 1e-4, 1.0};
    for (size_t a = 0; a < 6; ++a)
        for (size_t v = 0; v < 5; ++v) {
            double s = -1, b = -1;
            cr_assert_eq(sol_dfg_integrate(alphas[a], nvs[v], 32, &s, &b), SOL_OK);
            cr_assert(isfinite(s) && isfinite(b) && s >= 0 && b >= 0 && s + b <= 1.0 + 1e-9,
                      "alpha %g nv %g: %g %g", alphas[a], nvs[v], s, b);
        }
    double s, b;
    cr_assert_eq(sol_dfg_integrate(0.0, 0.0, 8, &s, &b), SOL_OK); /* documented degenerate corner */
    cr_expect_eq(s, 0.0);
    cr_expect_eq(b, 0.0);
    cr_assert_eq(sol_dfg_integrate(-0.0, 0.5, 8, &s, &b), SOL_OK);
}

Test(lighting, s4_dfg_rejects_bad_input_and_leaves_outputs)
{
    double s = 7, b = 8;
    cr_expect_eq(sol_dfg_integrate(NAN, 0.5, 8, &s, &b), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_dfg_integrate(0.5, INFINITY, 8, &s, &b), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_dfg_integrate(1.5, 0.5, 8, &s, &b), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_integrate(0.5, -0.1, 8, &s, &b), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_integrate(0.5, 0.5, 0, &s, &b), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_integrate(0.5, 0.5, 8, NULL, &b), SOL_ERR_NULL_ARG);
    cr_expect_eq(sol_dfg_fit_polynomial(NAN, 0.5, &s, &b), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_dfg_fit_lazarov(0.5, 2.0, &s, &b), SOL_ERR_INVALID_ARG);
    cr_expect_eq(s, 7);
    cr_expect_eq(b, 8);
    cr_expect(isnan(sol_dfg_alpha_from_gloss(NAN)));
    cr_expect_eq(sol_dfg_alpha_from_gloss(-3.0), 1.0);
    cr_expect_eq(sol_dfg_alpha_from_gloss(0.5), 0.0625);
}

Test(lighting, s4_fits_are_bounded_and_close_to_reference_on_average)
{
    double sum_poly = 0, sum_laz = 0;
    int count = 0;
    for (int j = 0; j <= 10; ++j)
        for (int i = 0; i <= 10; ++i) {
            double g = i / 10.0, nv = j / 10.0, s, b, ps, pb, ls, lb;
            cr_assert_eq(sol_dfg_fit_polynomial(g, nv, &ps, &pb), SOL_OK);
            cr_assert_eq(sol_dfg_fit_lazarov(g, nv, &ls, &lb), SOL_OK);
            cr_assert(pb >= 0 && pb <= 1 && ps + pb >= 0 && ps + pb <= 1); /* saturated bias and delta */
            cr_assert(lb >= 0 && lb <= 1 && ls + lb >= 0 && ls + lb <= 1);
            if (nv == 0.0)
                continue;
            cr_assert_eq(sol_dfg_integrate(sol_dfg_alpha_from_gloss(g), nv, 48, &s, &b), SOL_OK);
            sum_poly += fabs(0.04 * (ps - s) + pb - b);
            sum_laz += fabs(0.04 * (ls - s) + lb - b);
            ++count;
        }
    /* S4: the fits are good on average (a few /255); their maxima are what the experiment reports. */
    cr_expect_lt(sum_poly / count, 0.02);
    cr_expect_lt(sum_laz / count, 0.02);
}

Test(lighting, s4_lut_reproduces_texel_centres_and_clamps)
{
    sol_dfg_lut lut = {0};
    cr_assert_eq(sol_dfg_lut_build(8, 16, &lut), SOL_OK);
    double s, b, rs, rb;
    cr_assert_eq(sol_dfg_lut_sample(&lut, 2.5 / 8, 5.5 / 8, &s, &b), SOL_OK);
    sol_dfg_integrate(sol_dfg_alpha_from_gloss(2.5 / 8), 5.5 / 8, 16, &rs, &rb);
    cr_expect_float_eq(s, rs, 1e-6);
    cr_expect_float_eq(b, rb, 1e-6);
    double s0, b0;
    cr_assert_eq(sol_dfg_lut_sample(&lut, 0.0, 1.0, &s, &b), SOL_OK); /* clamp-to-edge */
    cr_assert_eq(sol_dfg_lut_sample(&lut, 0.5 / 8, 7.5 / 8, &s0, &b0), SOL_OK);
    cr_expect_float_eq(s, s0, 1e-7);
    cr_expect_eq(sol_dfg_lut_sample(&lut, NAN, 0.5, &s, &b), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_dfg_lut_sample(&lut, 0.5, 1.01, &s, &b), SOL_ERR_INVALID_ARG);
    sol_dfg_lut_free(&lut);
    cr_expect_null(lut.scale_bias);
    sol_dfg_lut_free(&lut);
    sol_dfg_lut_free(NULL);
    cr_expect_eq(sol_dfg_lut_sample(&lut, 0.5, 0.5, &s, &b), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_lut_build(1, 16, &lut), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_lut_build(8, 16, NULL), SOL_ERR_NULL_ARG);
}

/* ---------------- S7: hemicube ---------------- */

Test(lighting, s7_hemicube_weights_sum_to_hemisphere)
{
    const int sizes[] = {2, 6, 32, 128};
    for (size_t k = 0; k < 4; ++k) {
        double omega, cos_c, cos_e;
        cr_assert_eq(sol_hemicube_weight_sums(sizes[k], &omega, &cos_c, &cos_e), SOL_OK);
        cr_expect_float_eq(omega, 2 * M_PI, 1e-12);
        cr_expect_float_eq(cos_e, M_PI, 1e-12);
        cr_expect_float_eq(cos_c, M_PI, 2.0 / (sizes[k] * sizes[k])); /* centre cosine: O(texel^2) */
    }
    double a, b, c;
    cr_expect_eq(sol_hemicube_weight_sums(7, &a, &b, &c), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_hemicube_weight_sums(0, &a, &b, &c), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_hemicube_weight_sums(8, NULL, &b, &c), SOL_ERR_NULL_ARG);
}

Test(lighting, s7_closed_forms_match_numeric_integrals)
{
    const double corners[][2] = {{0.3, 0.7}, {1.0, 1.0}, {2.0, 2.0}, {5.0, 0.1}};
    for (size_t k = 0; k < 4; ++k) {
        double x = corners[k][0], y = corners[k][1], omega = 0, cosine = 0;
        const int n = 600;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                double u = x * (i + 0.5) / n, v = y * (j + 0.5) / n, r2 = 1 + u * u + v * v;
                omega += x * y / (n * n) / (r2 * sqrt(r2));
                cosine += x * y / (n * n) / (r2 * r2);
            }
        cr_expect_float_eq(sol_plane_element_area(x, y), omega, 1e-5);
        cr_expect_float_eq(sol_plane_cosine_area(x, y), cosine, 1e-5);
    }
    /* Side face: height-weighted projected solid angle over u in [0,0.8], z in [0.2,0.9]. */
    double side = 0;
    const int n = 600;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double u = 0.8 * (i + 0.5) / n, z = 0.2 + 0.7 * (j + 0.5) / n, r2 = 1 + u * u + z * z;
            side += 0.8 * 0.7 / (n * n) * z / (r2 * r2);
        }
    cr_expect_float_eq(sol_side_cosine_area(0.8, 0.2, 0.9), side, 1e-6);
    /* Signs, zero and the axis. */
    cr_expect_eq(sol_plane_element_area(0.0, 3.0), 0.0);
    cr_expect_float_eq(sol_plane_element_area(-1.0, 1.0), -sol_plane_element_area(1.0, 1.0), 1e-15);
    cr_expect_float_eq(4 * sol_plane_element_area(1e300, 1e300), 2 * M_PI, 1e-12); /* whole plane */
    cr_expect_float_eq(4 * sol_plane_cosine_area(1e8, 1e8), M_PI, 1e-6);
}

Test(lighting, s7_single_plane_fov_and_capture)
{
    /* Doubling the hemicube face's side gives half extent 2: FOV 2 atan(2) = 126.87 degrees. */
    cr_expect_float_eq(2 * atan(2.0) * 180 / M_PI, 126.87, 0.005);
    sol_texel_weight *w = malloc(sizeof *w * 64 * 64);
    cr_assert_eq(sol_plane_weights(64, 2.0, w), SOL_OK);
    double omega = 0, cosine = 0;
    for (int i = 0; i < 64 * 64; ++i) {
        omega += w[i].solid_angle;
        cosine += w[i].cosine_exact;
        cr_assert(w[i].solid_angle > 0 && w[i].cosine_at_centre > 0 && w[i].cosine_at_centre <= w[i].solid_angle);
    }
    cr_expect_float_eq(omega, 4 * atan2(4.0, 3.0), 1e-12);
    cr_expect_float_eq(cosine / M_PI, 0.8310, 1e-4); /* misses 16.9% of the cosine-weighted hemisphere */
    sol_texel_weight keep = w[0];
    cr_expect_eq(sol_plane_weights(64, NAN, w), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_plane_weights(64, 0.0, w), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_plane_weights(0, 2.0, w), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_plane_weights(64, 2.0, NULL), SOL_ERR_NULL_ARG);
    cr_expect_eq(w[0].solid_angle, keep.solid_angle);
    free(w);
}

/* ---------------- S8: PCF ---------------- */

Test(lighting, s8_weights_sum_to_three_and_fast_is_sharper)
{
    for (int i = 0; i <= 64; ++i) {
        double f = i / 64.0, we[4], wf[4];
        cr_assert_eq(sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, f, we), SOL_OK);
        cr_assert_eq(sol_pcf_weights_1d(SOL_PCF_BILINEAR4_FAST, f, wf), SOL_OK);
        cr_expect_float_eq(we[0] + we[1] + we[2] + we[3], 3.0, 1e-12);
        cr_expect_float_eq(wf[0] + wf[1] + wf[2] + wf[3], 3.0, 1e-12);
        cr_expect_geq(wf[1], we[1] - 1e-12); /* S8: inner texels gain weight: a sharper filter */
        cr_expect_leq(wf[0], we[0] + 1e-12);
        cr_expect_leq(wf[1] - we[1], 0.125 + 1e-12); /* at most (2-f)(1+f)/2 - 1 = 1/8 at f = 1/2 */
    }
    double w[4];
    cr_expect_eq(sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, NAN, w), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, 1.5, w), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_pcf_weights_1d(SOL_PCF_METHOD_COUNT, 0.5, w), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, 0.5, NULL), SOL_ERR_NULL_ARG);
}

Test(lighting, s8_exact_taps_equal_box_on_random_maps)
{
    float map[8 * 8];
    srand(7);
    for (int i = 0; i < 64; ++i)
        map[i] = (float)rand() / (float)RAND_MAX;
    for (int k = 0; k < 2000; ++k) {
        double x = -2 + 12.0 * rand() / RAND_MAX, y = -2 + 12.0 * rand() / RAND_MAX, box, taps, fast;
        cr_assert_eq(sol_pcf_filter(map, 8, 8, x, y, 0.5, SOL_PCF_BOX_EXACT, &box), SOL_OK);
        cr_assert_eq(sol_pcf_filter(map, 8, 8, x, y, 0.5, SOL_PCF_BILINEAR4_EXACT, &taps), SOL_OK);
        cr_assert_eq(sol_pcf_filter(map, 8, 8, x, y, 0.5, SOL_PCF_BILINEAR4_FAST, &fast), SOL_OK);
        cr_expect_float_eq(box, taps, 1e-12, "at (%g, %g)", x, y);
        cr_expect_leq(fabs(fast - box), 0.12); /* the exhaustive worst case is 0.118 */
    }
}

Test(lighting, s8_uniform_maps_huge_coordinates_and_bad_input)
{
    float lit[4] = {1, 1, 1, 1};
    const double coords[] = {0.0, -0.0, 0.5, 1.999999, -1e300, 1e300, DBL_MIN};
    for (int m = 0; m < SOL_PCF_METHOD_COUNT; ++m)
        for (int i = 0; i < 7; ++i) {
            double v = -1;
            cr_assert_eq(sol_pcf_filter(lit, 2, 2, coords[i], coords[6 - i], 0.5, (sol_pcf_method)m, &v), SOL_OK);
            cr_expect_eq(v, 1.0);
            cr_assert_eq(sol_pcf_filter(lit, 2, 2, coords[i], 0.3, 2.0, (sol_pcf_method)m, &v), SOL_OK);
            cr_expect_eq(v, 0.0); /* receiver behind every occluder */
        }
    float one = 1.0f;
    double v = 42;
    cr_expect_eq(sol_pcf_filter(&one, 1, 1, 0.3, 0.3, 0.0, SOL_PCF_BILINEAR4_FAST, &v), SOL_OK); /* 1x1 map */
    cr_expect_eq(v, 1.0);
    v = 42;
    cr_expect_eq(sol_pcf_filter(lit, 2, 2, NAN, 0.5, 0.5, SOL_PCF_BOX_EXACT, &v), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_pcf_filter(lit, 2, 2, 0.5, INFINITY, 0.5, SOL_PCF_BOX_EXACT, &v), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_pcf_filter(lit, 2, 2, 0.5, 0.5, NAN, SOL_PCF_BOX_EXACT, &v), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_pcf_filter(lit, 0, 2, 0.5, 0.5, 0.5, SOL_PCF_BOX_EXACT, &v), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_pcf_filter(NULL, 2, 2, 0.5, 0.5, 0.5, SOL_PCF_BOX_EXACT, &v), SOL_ERR_NULL_ARG);
    cr_expect_eq(v, 42);
}

/* ---------------- S2: light accumulation ---------------- */

Test(lighting, s2_four_channels_exact_for_one_colour_and_keep_luminance)
{
    const double white[3] = {1, 1, 1}, warm[3] = {1.0, 0.7, 0.4}, red[3] = {1, 0.1, 0.1}, blue[3] = {0.1, 0.2, 1};
    sol_light_accum acc = {0};
    double spec[3];
    cr_assert_eq(sol_light_accum_add(&acc, warm, 0.7, 0.3), SOL_OK);
    cr_assert_eq(sol_light_accum_add(&acc, warm, 0.2, 2.5), SOL_OK); /* same colour, different terms */
    cr_assert_eq(sol_light_accum_specular4(&acc, spec), SOL_OK);
    for (int c = 0; c < 3; ++c)
        cr_expect_float_eq(spec[c], acc.specular[c], 1e-12);
    sol_light_accum two = {0};
    sol_light_accum_add(&two, red, 0.9, 0.1);  /* red mostly diffuse */
    sol_light_accum_add(&two, blue, 0.1, 0.9); /* blue mostly specular */
    sol_light_accum_specular4(&two, spec);
    cr_expect_float_eq(sol_luminance(spec), sol_luminance(two.specular), 1e-12); /* S2: luminance kept */
    cr_expect_gt(spec[0], two.specular[0] * 2); /* hue follows the red diffuse: wrong */
    sol_light_accum none = {0};
    sol_light_accum_add(&none, white, 0.0, 0.5); /* n.l = 0 but a specular term: grey */
    sol_light_accum_specular4(&none, spec);
    cr_expect_eq(spec[0], 0.5);
    cr_expect_eq(spec[2], 0.5);
    sol_light_accum tiny = {0};
    const double tiny_colour[3] = {DBL_MIN, 0, 0};
    sol_light_accum_add(&tiny, tiny_colour, 1e-10, 0.0);
    sol_light_accum_add(&tiny, white, 0.0, 1.0);
    sol_light_accum_specular4(&tiny, spec);
    cr_expect(isfinite(spec[0]) && isfinite(spec[1]) && isfinite(spec[2]));
}

Test(lighting, s2_rejects_bad_input)
{
    sol_light_accum acc = {0};
    const double bad[3] = {NAN, 0, 0}, neg[3] = {-1, 0, 0}, ok[3] = {1, 1, 1};
    cr_expect_eq(sol_light_accum_add(&acc, bad, 1, 1), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_light_accum_add(&acc, ok, INFINITY, 1), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_light_accum_add(&acc, neg, 1, 1), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_light_accum_add(&acc, ok, 1, -0.5), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_light_accum_add(NULL, ok, 1, 1), SOL_ERR_NULL_ARG);
    cr_expect_eq(acc.strength, 0.0);
    cr_expect_eq(acc.diffuse[0], 0.0);
    cr_expect_eq(sol_light_accum_specular4(&acc, NULL), SOL_ERR_NULL_ARG);
}

/* ---------------- D13: clip volumes ---------------- */

Test(lighting, d13_unshadowed_light_leaks_and_clip_volume_stops_it)
{
    const sol_wall walls[] = {{0, -5, 0, 5, 0, 0, 0}}; /* a solid wall at x = 0 */
    sol_room_scene scene = {walls, 1, 3.0, {-1.0, 0.0, 2.0}, 6.0};
    const sol_clip_box room_a = {-5, -5, 0, 5};
    double unshadowed, clipped, shadowed;
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 1.0, 0.0, &unshadowed), SOL_OK);
    cr_assert_eq(sol_room_irradiance(&scene, &room_a, SOL_LIGHT_CLIPPED, 1.0, 0.0, &clipped), SOL_OK);
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, 1.0, 0.0, &shadowed), SOL_OK);
    cr_expect_gt(unshadowed, 0.0); /* D13: bleeds through the wall */
    cr_expect_eq(clipped, 0.0);
    cr_expect_eq(shadowed, 0.0);
    /* Inside room A all three agree. */
    cr_assert_eq(sol_room_irradiance(&scene, &room_a, SOL_LIGHT_CLIPPED, -2.0, 1.0, &clipped), SOL_OK);
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, -2.0, 1.0, &shadowed), SOL_OK);
    cr_expect_float_eq(clipped, shadowed, 1e-15);
    cr_expect_gt(shadowed, 0.0);
    /* Beyond the radius nothing; a light above the wall top shines over it. */
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, 10.0, 0.0, &unshadowed), SOL_OK);
    cr_expect_eq(unshadowed, 0.0);
    sol_room_scene high = {walls, 1, 1.0, {-0.5, 0.0, 2.0}, 6.0};
    cr_assert_eq(sol_room_irradiance(&high, NULL, SOL_LIGHT_SHADOWED, 3.0, 0.0, &shadowed), SOL_OK);
    cr_expect_gt(shadowed, 0.0);
}

Test(lighting, d13_door_lets_light_through_and_bad_input)
{
    const sol_wall door[] = {{0, -5, 0, 5, 0.45, 0.55, 2.5}}; /* door at y in [-0.5, 0.5] */
    sol_room_scene scene = {door, 1, 3.0, {-1.0, 0.0, 2.0}, 6.0};
    double e;
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, 1.0, 0.0, &e), SOL_OK);
    cr_expect_gt(e, 0.0);
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, 1.0, 3.0, &e), SOL_OK);
    cr_expect_eq(e, 0.0);
    e = 5;
    cr_expect_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_SHADOWED, NAN, 0.0, &e), SOL_ERR_NONFINITE);
    cr_expect_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_CLIPPED, 1.0, 0.0, &e), SOL_ERR_NULL_ARG);
    sol_room_scene low = scene;
    low.light[2] = 0.0;
    cr_expect_eq(sol_room_irradiance(&low, NULL, SOL_LIGHT_SHADOWED, 1.0, 0.0, &e), SOL_ERR_INVALID_ARG);
    low = scene;
    low.radius = -1;
    cr_expect_eq(sol_room_irradiance(&low, NULL, SOL_LIGHT_UNSHADOWED, 1.0, 0.0, &e), SOL_ERR_INVALID_ARG);
    cr_expect_eq(e, 5);
    /* Directly below the light: finite. */
    cr_assert_eq(sol_room_irradiance(&scene, NULL, SOL_LIGHT_UNSHADOWED, -1.0, 0.0, &e), SOL_OK);
    cr_expect(isfinite(e) && e > 0);
}

Test(lighting, s4_refit_recovers_constants_of_the_form)
{
    sol_dfg_polynomial truth = sol_dfg_polynomial_narkowicz, fitted;
    truth.delta[0] += 0.03;
    truth.delta[6] -= 0.2;
    truth.bias[2] -= 0.02;
    truth.bias[1] += 0.1;
    enum { N = 30 };
    static double g[N * N], v[N * N], s[N * N], b[N * N];
    for (int k = 0; k < N * N; ++k) {
        g[k] = (k % N + 0.5) / N;
        v[k] = (k / N + 0.5) / N;
        cr_assert_eq(sol_dfg_eval_polynomial(&truth, g[k], v[k], &s[k], &b[k]), SOL_OK);
    }
    cr_assert_eq(sol_dfg_refit_polynomial(g, v, s, b, N * N, &fitted), SOL_OK);
    for (int i = 0; i < 7; ++i)
        cr_expect_float_eq(fitted.delta[i], truth.delta[i], 1e-6, "delta %d", i);
    for (int i = 0; i < 6; ++i)
        cr_expect_float_eq(fitted.bias[i], truth.bias[i], 1e-6, "bias %d", i);
    sol_dfg_polynomial keep = fitted;
    g[5] = NAN;
    cr_expect_eq(sol_dfg_refit_polynomial(g, v, s, b, N * N, &fitted), SOL_ERR_NONFINITE);
    g[5] = 1.5;
    cr_expect_eq(sol_dfg_refit_polynomial(g, v, s, b, N * N, &fitted), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_refit_polynomial(g, v, s, b, 3, &fitted), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_dfg_refit_polynomial(NULL, v, s, b, N * N, &fitted), SOL_ERR_NULL_ARG);
    cr_expect_eq(fitted.delta[0], keep.delta[0]);
    double sc, bi;
    cr_expect_eq(sol_dfg_eval_polynomial(NULL, 0.5, 0.5, &sc, &bi), SOL_ERR_NULL_ARG);
}
