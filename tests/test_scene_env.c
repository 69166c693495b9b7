/* test_scene_env.c - lat-long EXR environments: loading and its bad input (NaN, negative,
 * channels, size limit, missing file), the env-sg effect in the plan, and the lighting of both
 * paths against closed forms. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sol_scene.h"

#include "scratch.h"

/* Writes an uncompressed scanline EXR of FLOAT channels B, G, R (the file format's alphabetical
 * order) by hand, so a test can store values sol_exr_write refuses (NaN, Inf) or claim a data
 * window larger than the pixels it holds (claim_w x claim_h; 0 = the real size). */
static void write_raw_exr(const char *path, int w, int h, const float *rgb, int claim_w, int claim_h)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    const uint8_t magic[8] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    fwrite(magic, 1, 8, f);
    /* channels */
    fwrite("channels\0chlist\0", 1, 16, f);
    int32_t sz = 3 * (2 + 16) + 1;
    fwrite(&sz, 4, 1, f);
    const char *names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) {
        int32_t type = 2, xs = 1, ys = 1;
        uint8_t lin[4] = {0, 0, 0, 0};
        fwrite(names[c], 1, 2, f);
        fwrite(&type, 4, 1, f);
        fwrite(lin, 1, 4, f);
        fwrite(&xs, 4, 1, f);
        fwrite(&ys, 4, 1, f);
    }
    fputc(0, f);
    fwrite("compression\0compression\0", 1, 24, f);
    sz = 1;
    fwrite(&sz, 4, 1, f);
    fputc(0, f); /* NO_COMPRESSION */
    int32_t win[4] = {0, 0, (claim_w ? claim_w : w) - 1, (claim_h ? claim_h : h) - 1};
    fwrite("dataWindow\0box2i\0", 1, 17, f);
    sz = 16;
    fwrite(&sz, 4, 1, f);
    fwrite(win, 4, 4, f);
    fwrite("displayWindow\0box2i\0", 1, 20, f);
    fwrite(&sz, 4, 1, f);
    fwrite(win, 4, 4, f);
    fwrite("lineOrder\0lineOrder\0", 1, 20, f);
    sz = 1;
    fwrite(&sz, 4, 1, f);
    fputc(0, f);
    float one = 1, zero2[2] = {0, 0};
    fwrite("pixelAspectRatio\0float\0", 1, 23, f);
    sz = 4;
    fwrite(&sz, 4, 1, f);
    fwrite(&one, 4, 1, f);
    fwrite("screenWindowCenter\0v2f\0", 1, 23, f);
    sz = 8;
    fwrite(&sz, 4, 1, f);
    fwrite(zero2, 4, 2, f);
    fwrite("screenWindowWidth\0float\0", 1, 24, f);
    sz = 4;
    fwrite(&sz, 4, 1, f);
    fwrite(&one, 4, 1, f);
    fputc(0, f);
    /* offset table: one chunk per scanline */
    long table = ftell(f);
    uint64_t offset = (uint64_t)table + 8u * (uint64_t)h;
    for (int y = 0; y < h; ++y) {
        fwrite(&offset, 8, 1, f);
        offset += 8 + (uint64_t)w * 12;
    }
    for (int y = 0; y < h; ++y) {
        int32_t yy = y, bytes = w * 12;
        fwrite(&yy, 4, 1, f);
        fwrite(&bytes, 4, 1, f);
        for (int c = 2; c >= 0; --c) /* B, G, R */
            for (int x = 0; x < w; ++x)
                fwrite(&rgb[((size_t)y * w + x) * 3 + c], 4, 1, f);
    }
    fclose(f);
}

/* The analytic sky of experiments/scenes/sky_64x32.exr (a blue sky brightening to the horizon, a
 * brown ground, a sun lobe of sharpness 30 along (0.5, 0.6, -0.6)), at direction d. */
static void sky_radiance(const double d[3], double out[3])
{
    static const double sky[3] = {0.25, 0.4, 0.8}, ground[3] = {0.12, 0.1, 0.08}, sun[3] = {40, 36, 30};
    double s[3] = {0.5, 0.6, -0.6}, l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    double c = (d[0] * s[0] + d[1] * s[1] + d[2] * s[2]) / l;
    for (int k = 0; k < 3; ++k)
        out[k] = (d[1] >= 0 ? sky[k] * (1 - 0.5 * d[1]) : ground[k]) + sun[k] * exp(30 * (c - 1));
}

/* The texel centre direction of the documented lat-long convention. */
static void texel_dir(int x, int y, int w, int h, double d[3])
{
    double phi = 2 * M_PI * ((x + 0.5) / w - 0.5), th = M_PI * (y + 0.5) / h;
    d[0] = sin(th) * sin(phi), d[1] = cos(th), d[2] = -sin(th) * cos(phi);
}

/* The shipped map is the documented analytic sky (so it can be regenerated from this formula). */
Test(scene_env, shipped_sky_map_is_the_documented_formula)
{
    sol_image im;
    cr_assert_eq(sol_exr_read("experiments/scenes/sky_64x32.exr", &im), SOL_OK);
    cr_assert_eq(im.width, 64);
    cr_assert_eq(im.height, 32);
    double worst = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            double d[3], L[3];
            texel_dir(x, y, 64, 32, d);
            sky_radiance(d, L);
            for (int k = 0; k < 3; ++k)
                worst = fmax(worst, fabs(sol_image_pixel(&im, x, y)[k] - L[k]) / (L[k] + 1e-6));
        }
    cr_expect_lt(worst, 1e-6, "relative difference %g", worst);
    sol_image_free(&im);
}

static sol_status load_env_scene(const char *exr, sol_scene *s, sol_scene_error *e)
{
    char json[512];
    snprintf(json, sizeof json,
             "{\"camera\":{\"position\":[0,0,-3],\"look_at\":[0,0,0],\"width\":24,\"height\":16,\"fov\":40},"
             "\"materials\":[{\"albedo\":[0.5,0.5,0.5],\"specular\":0}],"
             "\"objects\":[{\"type\":\"sphere\",\"radius\":1}],\"ambient\":[0,0,0],"
             "\"lights\":[{\"type\":\"environment\",\"file\":\"%s\"}],"
             "\"pipeline\":{\"light_buffer\":\"float\",\"gbuffer_normals\":\"float\",\"tonemap\":\"reinhard\","
             "\"reference_supersample\":1}}",
             exr);
    return sol_scene_parse(json, strlen(json), scratch("sol_env_test.json"), s, e);
}

/* Bad maps are refused at load, naming the file, the field and (for values) the pixel. */
Test(scene_env, bad_maps_are_rejected_before_rendering)
{
    float rgb[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; ++i)
        rgb[i] = 0.5f;
    sol_scene s;
    sol_scene_error e;
    memset(&s, 0x5a, sizeof s);
    /* NaN */
    rgb[(2 * 8 + 5) * 3 + 1] = NAN;
    write_raw_exr(scratch("sol_env_nan.exr"), 8, 4, rgb, 0, 0);
    cr_expect_eq(load_env_scene(scratch("sol_env_nan.exr"), &s, &e), SOL_ERR_NONFINITE, "%s", e.message);
    cr_expect_str_eq(e.pointer, "/lights/0/file");
    cr_expect(strstr(e.message, "sol_env_nan.exr") && strstr(e.message, "(5, 2)") && strstr(e.message, "channel G"),
              "%s", e.message);
    /* Inf */
    rgb[(2 * 8 + 5) * 3 + 1] = INFINITY;
    write_raw_exr(scratch("sol_env_inf.exr"), 8, 4, rgb, 0, 0);
    cr_expect_eq(load_env_scene(scratch("sol_env_inf.exr"), &s, &e), SOL_ERR_NONFINITE, "%s", e.message);
    /* negative radiance */
    rgb[(2 * 8 + 5) * 3 + 1] = -0.25f;
    write_raw_exr(scratch("sol_env_neg.exr"), 8, 4, rgb, 0, 0);
    cr_expect_eq(load_env_scene(scratch("sol_env_neg.exr"), &s, &e), SOL_ERR_OUT_OF_RANGE, "%s", e.message);
    /* a header claiming 100000 x 100000 pixels: refused by sol_read_limits before allocation */
    rgb[(2 * 8 + 5) * 3 + 1] = 0.5f;
    write_raw_exr(scratch("sol_env_huge.exr"), 8, 4, rgb, 100000, 100000);
    cr_expect_eq(load_env_scene(scratch("sol_env_huge.exr"), &s, &e), SOL_ERR_LIMIT, "%s", e.message);
    cr_expect(strstr(e.message, "sol_env_huge.exr") != NULL, "%s", e.message);
    /* one channel (Y) */
    sol_image grey;
    cr_assert_eq(sol_image_alloc(&grey, 8, 4, 1), SOL_OK);
    cr_assert_eq(sol_exr_write(scratch("sol_env_grey.exr"), &grey, 0), SOL_OK);
    sol_image_free(&grey);
    cr_expect_eq(load_env_scene(scratch("sol_env_grey.exr"), &s, &e), SOL_ERR_FORMAT, "%s", e.message);
    cr_expect(strstr(e.message, "1 channel") != NULL, "%s", e.message);
    /* missing, and not an EXR */
    cr_expect_eq(load_env_scene(scratch("sol_env_missing.exr"), &s, &e), SOL_ERR_IO);
    cr_expect(strstr(e.message, scratch("sol_env_missing.exr")) != NULL, "%s", e.message);
    cr_expect_eq(load_env_scene(scratch("sol_env_test.png"), &s, &e), SOL_ERR_IO);
    FILE *f = fopen(scratch("sol_env_sky.png"), "w");
    cr_assert_not_null(f);
    fputs("x", f);
    fclose(f);
    cr_expect_eq(load_env_scene(scratch("sol_env_sky.png"), &s, &e), SOL_ERR_FORMAT);
    cr_expect_eq(((unsigned char *)&s)[0], 0x5a, "scene written on error");
    /* the hand-written file itself is fine once its values are */
    write_raw_exr(scratch("sol_env_ok.exr"), 8, 4, rgb, 0, 0);
    cr_expect_eq(load_env_scene(scratch("sol_env_ok.exr"), &s, &e), SOL_OK, "%s", e.message);
    sol_scene_free(&s);
    const char *files[] = {"nan", "inf", "neg", "huge", "grey", "sky.png", "ok"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
        char p[64];
        snprintf(p, sizeof p, strchr(files[i], '.') ? "sol_env_%s" : "sol_env_%s.exr", files[i]);
        remove(scratch(p));
    }
}

/* Mean HDR value of the pixels the sphere covers, channel c. */
static double sphere_mean(const sol_render_result *r, int c)
{
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < (size_t)r->hdr.width * r->hdr.height; ++i)
        if (r->normals.data[3 * i] != 0 || r->normals.data[3 * i + 1] != 0 || r->normals.data[3 * i + 2] != 0) {
            sum += r->hdr.data[3 * i + c];
            ++n;
        }
    return n ? sum / n : -1;
}

/* A constant environment L: irradiance pi L at every normal, so a Lambertian albedo a shows a L
 * everywhere. The reference (exact sums over the texels) gets it to float precision; the engine
 * path's SG fit (env-sg) to within 2 %; both scale with the light's colour and intensity. */
Test(scene_env, constant_environment_gives_albedo_times_radiance)
{
    float rgb[16 * 8 * 3];
    for (int i = 0; i < 16 * 8; ++i)
        rgb[3 * i] = 1.0f, rgb[3 * i + 1] = 0.5f, rgb[3 * i + 2] = 0.25f;
    write_raw_exr(scratch("sol_env_const.exr"), 16, 8, rgb, 0, 0);
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(load_env_scene(scratch("sol_env_const.exr"), &s, &e), SOL_OK, "%s", e.message);
    remove(scratch("sol_env_const.exr"));
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_ENV_SG], 1);
    cr_expect_str_eq(p.element[SOL_FX_ENV_SG], "/lights/0/file");
    const double want[3] = {0.5, 0.25, 0.125};
    for (int pass = 0; pass < 3; ++pass) {
        sol_render_options o = {0};
        o.reference = pass == 0;
        if (pass == 2) { /* twice the intensity, a tinted colour */
            s.lights[0].intensity = 2;
            s.lights[0].color[1] = 0.5;
        }
        sol_render_result r;
        sol_render_stats st;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &r, &st), SOL_OK);
        cr_expect_eq(st.effect_runs[SOL_FX_ENV_SG] > 0, pass > 0);
        for (int c = 0; c < 3; ++c) {
            double k = pass == 2 ? 2 * (c == 1 ? 0.5 : 1) : 1;
            double got = sphere_mean(&r, c), tol = pass == 0 ? 1e-3 : 0.02;
            cr_expect(fabs(got - k * want[c]) <= tol * k * want[c], "pass %d channel %d: %.6f, want %.6f", pass, c, got,
                      k * want[c]);
        }
        sol_render_result_free(&r);
    }
    sol_scene_free(&s);
}

/* A mirror-like Phong lobe under the sky: the reference's importance-sampled specular converges
 * to the map seen along the reflection vector; and the sky lights the shipped scene in both
 * paths, deterministically for any thread count, with env-sg the largest share of its error. */
Test(scene_env, shipped_env_scene_renders_in_both_paths)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(sol_scene_load("experiments/scenes/env_sky.json", &s, &e), SOL_OK, "%s %s", e.pointer, e.message);
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_ENV_SG], 1);
    sol_render_options o = {48, 27, 0, 0};
    sol_render_result eng, ref, swapped;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &eng, NULL), SOL_OK);
    o.reference_effects = 1u << SOL_FX_ENV_SG;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &swapped, NULL), SOL_OK);
    o.reference_effects = 0;
    o.reference = 1;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &ref, NULL), SOL_OK);
    for (int c = 0; c < 3; ++c) {
        cr_expect_gt(sphere_mean(&eng, c), 0.01);
        cr_expect_gt(sphere_mean(&ref, c), 0.01);
    }
    sol_render_error a, b;
    cr_assert_eq(sol_render_compare(&eng, &ref, &a), SOL_OK);
    cr_assert_eq(sol_render_compare(&swapped, &ref, &b), SOL_OK);
    cr_expect_lt(b.rms_code, a.rms_code, "the exact map brings the engine closer (%.3f vs %.3f)", b.rms_code, a.rms_code);
    sol_render_result_free(&eng);
    sol_render_result_free(&swapped);
    sol_render_result_free(&ref);
    sol_scene_free(&s);
}
