/* test_scene.c - the scene file (defaults, every error names its field), the effect graph
 * (sol_scene_plan) and the two-path renderer. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdarg.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sol_scene.h"

#include "scratch.h"

/* system() on a formatted command line. */
static int shell(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int shell(const char *fmt, ...)
{
    char cmd[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    return system(cmd);
}

static sol_status parse(const char *json, sol_scene *s, sol_scene_error *e)
{
    return sol_scene_parse(json, strlen(json), "mem/test.json", s, e);
}

Test(scene, empty_document_gets_every_documented_default)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse("{}", &s, &e), SOL_OK, "%s %s", e.pointer, e.message);
    cr_expect_eq(s.camera.width, 960);
    cr_expect_eq(s.camera.height, 540);
    cr_expect_float_eq(s.camera.fov_deg, 60.0, 0);
    cr_expect_eq(s.pipeline.light_buffer, SOL_LB_R11G11B10F);
    cr_expect_eq(s.pipeline.lut_size, 16);
    cr_expect_eq(s.pipeline.ssao, 0);
    cr_expect_eq(s.pipeline.aa, SOL_AA_NONE);
    cr_expect_eq(s.pipeline.reference_supersample, 3);
    cr_expect_str_eq(s.name, "test");
    cr_expect_eq(s.object_count, 0);
    sol_scene_free(&s);
    sol_scene_free(&s); /* free zeroes: a second free is harmless */
    sol_scene_free(NULL);
}

Test(scene, full_scene_parses_materials_objects_lights_by_name)
{
    const char *json = "{\"name\":\"t\",\"camera\":{\"position\":[0,2,-6],\"path\":[[0,2,-6],[0.1,2,-6]]},"
                       "\"materials\":[{\"name\":\"paint\",\"albedo\":[0.8,0.1,0.1],\"gloss\":0.9,"
                       "\"normal_map\":{\"procedural\":\"bumps\",\"amplitude\":0.2}},"
                       "{\"name\":\"brushed\",\"anisotropic\":{\"model\":\"ward\",\"roughness\":[0.05,0.3]},"
                       "\"albedo_texture\":{\"procedural\":\"checker\",\"bits\":8}}],"
                       "\"objects\":[{\"type\":\"plane\"},{\"type\":\"sphere\",\"radius\":0.5,\"material\":\"brushed\"},"
                       "{\"type\":\"box\",\"min\":[0,0,0],\"max\":[1,1,1],\"material\":1},"
                       "{\"type\":\"heightfield\",\"size\":[4,4]}],"
                       "\"clip_volumes\":[{\"min\":[-1,-1,-1],\"max\":[1,1,1]}],"
                       "\"lights\":[{\"type\":\"sun\",\"direction\":[0,-2,0]},{\"type\":\"point\",\"clip\":0},"
                       "{\"type\":\"environment\",\"lobes\":[{\"axis\":[0,1,0],\"sharpness\":2}]}],"
                       "\"pipeline\":{\"light_buffer\":\"rgbm\",\"gbuffer_normals\":\"octahedral-12\","
                       "\"look\":{\"saturation\":0.2},\"aa\":\"temporal\",\"ssao\":true}}";
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse(json, &s, &e), SOL_OK, "%s %s", e.pointer, e.message);
    cr_expect_eq(s.material_count, 2);
    cr_expect_eq(s.object_count, 4);
    cr_expect_eq(s.objects[1].material, 1);
    cr_expect_eq(s.objects[2].material, 1);
    cr_expect_eq(s.objects[0].material, 0);
    cr_expect_eq(s.materials[1].aniso, SOL_ANISO_WARD);
    cr_expect_float_eq(s.materials[1].roughness[1], 0.3, 0);
    cr_expect_eq(s.materials[0].normal_map.source, SOL_TEX_BUMPS);
    cr_expect_eq(s.materials[1].albedo_texture.source, SOL_TEX_CHECKER);
    cr_expect_eq(s.lights[1].clip, 0);
    cr_expect_eq(s.lights[0].clip, -1);
    cr_expect_float_eq(s.lights[0].direction[1], -1.0, 1e-15); /* normalised */
    cr_expect_eq(s.lights[2].lobe_count, 1);
    cr_expect_eq(s.camera.frame_count, 2);
    cr_expect_eq(s.pipeline.light_buffer, SOL_LB_RGBM);
    cr_expect_eq(s.pipeline.has_look, 1);
    cr_expect_eq(s.pipeline.aa, SOL_AA_TEMPORAL);
    sol_scene_free(&s);
}

/* Each bad document: the status and the JSON pointer the error must name. */
static const struct {
    const char *json;
    sol_status status;
    const char *pointer;
} bad_docs[] = {
    {"{\"materials\":[{\"anisotropic\":{\"roughness\":[-0.1,0.2]}}]}", SOL_ERR_OUT_OF_RANGE,
     "/materials/0/anisotropic/roughness/0"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"sphere\",\"center\":[0,1e999,0]}]}", SOL_ERR_NONFINITE,
     "/objects/0/center/1"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"sphere\",\"radius\":0}]}", SOL_ERR_OUT_OF_RANGE,
     "/objects/0/radius"},
    {"{\"lights\":[{\"type\":\"point\",\"radius\":0}]}", SOL_ERR_OUT_OF_RANGE, "/lights/0/radius"},
    {"{\"lights\":[{\"type\":\"spot\",\"cone\":0}]}", SOL_ERR_OUT_OF_RANGE, "/lights/0/cone"},
    {"{\"lights\":[{\"type\":\"sun\",\"direction\":[0,0,0]}]}", SOL_ERR_ZERO_LENGTH, "/lights/0/direction"},
    {"{\"lights\":[{\"type\":\"laser\"}]}", SOL_ERR_FORMAT, "/lights/0/type"},
    {"{\"lights\":[{\"type\":\"point\",\"clip\":0}]}", SOL_ERR_FORMAT, "/lights/0/clip"},
    {"{\"materials\":[{\"roughnes\":1}]}", SOL_ERR_FORMAT, "/materials/0/roughnes"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"box\",\"min\":[0,0,0],\"max\":[1,-1,1]}]}",
     SOL_ERR_INVALID_ARG, "/objects/0/max/1"},
    {"{\"objects\":[{\"type\":\"plane\"}]}", SOL_ERR_FORMAT, "/objects/0/material"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"plane\",\"material\":\"steel\"}]}", SOL_ERR_FORMAT,
     "/objects/0/material"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"heightfield\",\"size\":[0,1]}]}", SOL_ERR_OUT_OF_RANGE,
     "/objects/0/size/0"},
    {"{\"camera\":{\"width\":0}}", SOL_ERR_OUT_OF_RANGE, "/camera/width"},
    {"{\"camera\":{\"width\":16384,\"height\":16384}}", SOL_ERR_LIMIT, "/camera/height"},
    {"{\"camera\":{\"position\":[0,0,0],\"look_at\":[0,0,0]}}", SOL_ERR_INVALID_ARG, "/camera/look_at"},
    {"{\"camera\":{\"znear\":2,\"zfar\":1}}", SOL_ERR_INVALID_ARG, "/camera/zfar"},
    {"{\"camera\":{\"path\":[[0,0,0]]}}", SOL_ERR_FORMAT, "/camera/path"},
    {"{\"camera\":{\"path\":[[0,0,0],[0,\"x\",0]]}}", SOL_ERR_FORMAT, "/camera/path/1/1"},
    {"{\"pipeline\":{\"light_buffer\":\"rgb9e5\"}}", SOL_ERR_FORMAT, "/pipeline/light_buffer"},
    {"{\"pipeline\":{\"exposure\":0}}", SOL_ERR_OUT_OF_RANGE, "/pipeline/exposure"},
    {"{\"pipeline\":{\"lut_size\":16.5}}", SOL_ERR_FORMAT, "/pipeline/lut_size"},
    {"{\"pipeline\":{\"ssao\":1}}", SOL_ERR_FORMAT, "/pipeline/ssao"},
    {"{\"materials\":[{\"albedo_texture\":{\"file\":\"no-such.png\"}}]}", SOL_ERR_IO,
     "/materials/0/albedo_texture/file"},
    {"{\"materials\":[{\"albedo_texture\":{\"procedural\":\"bumps\"}}]}", SOL_ERR_FORMAT,
     "/materials/0/albedo_texture/procedural"},
    {"{\"materials\":[{\"albedo_texture\":{\"procedural\":\"checker\",\"colors\":[[0,0,0],[2,0,0]]}}]}",
     SOL_ERR_OUT_OF_RANGE, "/materials/0/albedo_texture/colors/1/0"},
    {"{\"materials\":[{}],\"objects\":[{\"type\":\"mesh\",\"file\":\"missing.gltf\"}]}", SOL_ERR_IO,
     "/objects/0/file"},
    {"{\"lights\":[{\"type\":\"environment\"}]}", SOL_ERR_FORMAT, "/lights/0"},
    {"[1,2]", SOL_ERR_FORMAT, ""},
};

Test(scene, every_bad_value_is_rejected_naming_file_and_field)
{
    for (size_t i = 0; i < sizeof bad_docs / sizeof bad_docs[0]; ++i) {
        sol_scene s;
        memset(&s, 0x5a, sizeof s);
        sol_scene_error e;
        sol_status st = parse(bad_docs[i].json, &s, &e);
        cr_expect_eq(st, bad_docs[i].status, "doc %zu: status %d (%s %s)", i, st, e.pointer, e.message);
        cr_expect_str_eq(e.pointer, bad_docs[i].pointer, "doc %zu: %s", i, e.message);
        cr_expect_str_eq(e.file, "mem/test.json");
        cr_expect_eq(((unsigned char *)&s)[0], 0x5a, "doc %zu: output written on error", i);
    }
}

Test(scene, syntax_error_names_the_line)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse("{\n\"name\": \"x\",\n\"camera\": {,}\n}", &s, &e), SOL_ERR_FORMAT);
    cr_expect_eq(e.line, 3);
    cr_expect(strstr(e.message, "line 3") != NULL, "%s", e.message);
    cr_expect_eq(sol_scene_parse(NULL, 0, NULL, &s, &e), SOL_ERR_NULL_ARG);
}

Test(scene, load_names_a_missing_scene_file_and_reads_a_real_one)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(sol_scene_load("/nonexistent/x.json", &s, &e), SOL_ERR_IO);
    cr_expect_str_eq(e.file, "/nonexistent/x.json");
    FILE *f = fopen(scratch("sol_test_scene.json"), "w");
    cr_assert(f);
    fputs("{\"name\":\"disk\"}", f);
    fclose(f);
    cr_assert_eq(sol_scene_load(scratch("sol_test_scene.json"), &s, &e), SOL_OK);
    cr_expect_str_eq(s.name, "disk");
    sol_scene_free(&s);
    remove(scratch("sol_test_scene.json"));
}

/* ---------------- the effect graph and the renderer ---------------- */

static const char *const mixed_scene =
    "{\"camera\":{\"position\":[0,2,-6],\"look_at\":[0,0.5,0],\"width\":48,\"height\":27},"
    "\"materials\":[{\"name\":\"floor\",\"albedo_texture\":{\"procedural\":\"checker\",\"scale\":0.5}},"
    "{\"name\":\"paint\",\"albedo\":[0.6,0.05,0.05],\"gloss\":0.8,\"normal_map\":{\"procedural\":\"bumps\"}}],"
    "\"objects\":[{\"type\":\"plane\",\"material\":\"floor\"},{\"type\":\"sphere\",\"center\":[0,1,0],"
    "\"material\":\"paint\"}],"
    "\"lights\":[{\"type\":\"sun\",\"direction\":[0.5,-1,0.8],\"intensity\":3,\"shadows\":true}],"
    "\"pipeline\":{\"ssao\":true,\"normal_map_codec\":\"none\"}}";

Test(scene, plan_names_the_calling_element_and_why_others_are_skipped)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse(mixed_scene, &s, &e), SOL_OK, "%s %s", e.pointer, e.message);
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_GBUFFER_NORMALS], 1);
    cr_expect_eq(p.run[SOL_FX_ALBEDO_STORAGE], 1);
    cr_expect_str_eq(p.element[SOL_FX_ALBEDO_STORAGE], "/materials/0/albedo_texture");
    cr_expect_eq(p.run[SOL_FX_NORMAL_MAP_BC5], 0);
    cr_expect_str_eq(p.element[SOL_FX_NORMAL_MAP_BC5], "/pipeline/normal_map_codec");
    cr_expect_eq(p.run[SOL_FX_SSAO], 1);
    cr_expect_eq(p.run[SOL_FX_SG_LOBES], 0);
    cr_expect(strstr(p.reason[SOL_FX_SG_LOBES], "anisotropic") != NULL);
    cr_expect_eq(p.run[SOL_FX_TEMPORAL], 0);
    cr_expect_eq(p.run[SOL_FX_CULLING], 0);
    cr_expect_eq(p.run[SOL_FX_CLIP_VOLUMES], 0);
    for (int i = 0; i < SOL_FX_COUNT; ++i)
        cr_expect(sol_effect_get((sol_effect)i) && *sol_effect_get((sol_effect)i)->name);
    cr_expect_null(sol_effect_get(SOL_FX_COUNT));
    cr_expect_eq(sol_scene_plan_build(NULL, &p), SOL_ERR_NULL_ARG);
    sol_scene_free(&s);
}

Test(scene, skipped_effects_never_run_and_planned_ones_do)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse(mixed_scene, &s, &e), SOL_OK);
    sol_scene_plan p;
    sol_scene_plan_build(&s, &p);
    sol_render_result r;
    sol_render_stats st;
    cr_assert_eq(sol_scene_render(&s, &p, NULL, &r, &st), SOL_OK);
    for (int i = 0; i < SOL_FX_COUNT; ++i) {
        if (p.run[i])
            cr_expect_gt(st.effect_runs[i], 0, "%s planned but never ran", sol_effect_get((sol_effect)i)->name);
        else
            cr_expect_eq(st.effect_runs[i], 0, "%s skipped but ran", sol_effect_get((sol_effect)i)->name);
    }
    /* swapping an effect for its reference version stops its code too */
    sol_render_options o = {0};
    o.reference_effects = 1u << SOL_FX_SSAO;
    sol_render_result r2;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &r2, &st), SOL_OK);
    cr_expect_eq(st.effect_runs[SOL_FX_SSAO], 0);
    /* and the reference path runs none */
    o.reference = 1;
    sol_render_result r3;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &r3, &st), SOL_OK);
    for (int i = 0; i < SOL_FX_COUNT; ++i)
        cr_expect_eq(st.effect_runs[i], 0, "%s ran in the reference path", sol_effect_get((sol_effect)i)->name);
    sol_render_error err;
    cr_assert_eq(sol_render_compare(&r, &r3, &err), SOL_OK);
    cr_expect_gt(err.rms_code, 0.0);
    cr_expect_lt(err.rms_code, 40.0);
    cr_assert_eq(sol_render_compare(&r, &r, &err), SOL_OK);
    cr_expect_eq(err.rms_code, 0.0);
    cr_expect_eq(err.normal_max_deg, 0.0);
    sol_render_result_free(&r);
    sol_render_result_free(&r2);
    sol_render_result_free(&r3);
    sol_scene_free(&s);
}

Test(scene, render_is_deterministic_for_any_thread_count)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse(mixed_scene, &s, &e), SOL_OK);
    sol_scene_plan p;
    sol_scene_plan_build(&s, &p);
    sol_render_result a, b;
    omp_set_num_threads(1);
    cr_assert_eq(sol_scene_render(&s, &p, NULL, &a, NULL), SOL_OK);
    omp_set_num_threads(2);
    cr_assert_eq(sol_scene_render(&s, &p, NULL, &b, NULL), SOL_OK);
    size_t n = (size_t)a.display.width * a.display.height * 3;
    cr_expect_eq(memcmp(a.display.data, b.display.data, n * sizeof(float)), 0);
    cr_expect_eq(memcmp(a.hdr.data, b.hdr.data, n * sizeof(float)), 0);
    sol_render_result_free(&a);
    sol_render_result_free(&b);
    sol_render_options o = {0};
    o.width = -1;
    cr_expect_eq(sol_scene_render(&s, &p, &o, &a, NULL), SOL_ERR_INVALID_ARG);
    cr_expect_eq(sol_scene_render(NULL, &p, NULL, &a, NULL), SOL_ERR_NULL_ARG);
    sol_scene_free(&s);
}

/* sol_render_compare: the same figures for any thread count (its sums run in a fixed order), and
 * exactly 0 for an image against itself; a second render, which takes the SG irradiance tables
 * and the best-fit normal table (the default G-buffer normals) the first one built (kept per
 * process), is the same image. */
Test(scene, compare_is_the_same_for_any_thread_count_and_renders_repeat_exactly)
{
    static const char *const lobes =
        "{\"camera\":{\"position\":[0,2,-6],\"look_at\":[0,0.5,0],\"width\":40,\"height\":23},"
        "\"materials\":[{\"name\":\"floor\",\"albedo_texture\":{\"procedural\":\"checker\",\"scale\":0.5}},"
        "{\"name\":\"paint\",\"albedo\":[0.6,0.05,0.05],\"gloss\":0.8}],"
        "\"objects\":[{\"type\":\"plane\",\"material\":\"floor\"},{\"type\":\"sphere\",\"center\":[0,1,0],"
        "\"material\":\"paint\"}],"
        "\"lights\":[{\"type\":\"sun\",\"direction\":[0.5,-1,0.8],\"intensity\":3,\"shadows\":true},"
        "{\"type\":\"environment\",\"lobes\":[{\"axis\":[0,1,0],\"sharpness\":3.25,\"color\":[0.3,0.35,0.45]}]}]}";
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(parse(lobes, &s, &e), SOL_OK, "%s", e.message);
    sol_scene_plan p;
    sol_scene_plan_build(&s, &p);
    sol_render_options o = {0};
    sol_render_result eng, ref, again;
    omp_set_num_threads(2);
    cr_assert_eq(sol_scene_render(&s, &p, &o, &eng, NULL), SOL_OK);
    o.reference = 1;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &ref, NULL), SOL_OK);
    sol_render_error e1, e2, self;
    omp_set_num_threads(1);
    cr_assert_eq(sol_render_compare(&eng, &ref, &e1), SOL_OK);
    o.reference = 0;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &again, NULL), SOL_OK);
    omp_set_num_threads(2);
    cr_assert_eq(sol_render_compare(&eng, &ref, &e2), SOL_OK);
    cr_expect_gt(e1.de2000_mean, 0.0);
    cr_expect_eq(memcmp(&e1, &e2, sizeof e1), 0, "compare differs between 1 and 2 threads");
    cr_assert_eq(sol_render_compare(&ref, &ref, &self), SOL_OK);
    cr_expect_eq(self.rms_code, 0.0);
    cr_expect_eq(self.de2000_mean, 0.0);
    cr_expect_eq(self.de2000_max, 0.0);
    size_t n = (size_t)eng.display.width * eng.display.height * 3;
    cr_expect_eq(memcmp(eng.display.data, again.display.data, n * sizeof(float)), 0);
    cr_expect_eq(memcmp(eng.hdr.data, again.hdr.data, n * sizeof(float)), 0);
    cr_expect_eq(memcmp(eng.normals.data, again.normals.data, n * sizeof(float)), 0);
    cr_expect_eq(sol_render_compare(&eng, NULL, &self), SOL_ERR_NULL_ARG);
    ref.display.width = eng.display.width + 1;
    cr_expect_eq(sol_render_compare(&eng, &ref, &self), SOL_ERR_INVALID_ARG);
    ref.display.width = eng.display.width;
    sol_render_result_free(&eng);
    sol_render_result_free(&ref);
    sol_render_result_free(&again);
    sol_scene_free(&s);
}

/* ---------------- the shipped scenes (experiments/scenes/) ---------------- */

/* Per shipped scene: the effects its plan runs, and the engine-vs-reference error of a 64x36
 * render (display-code RMS, CIEDE2000 mean) recorded when the scene was added. A change of the
 * renderer or of a technique that moves these figures beyond the tolerance must be looked at. */
static const struct shipped {
    const char *name;
    const char *runs; /* the effects that run, space-separated, in effect order */
    double rms, de;
} shipped[] = {
#include "scene_expected.inc"
};

static void effects_run(const sol_scene_plan *p, char *out, size_t size)
{
    out[0] = 0;
    for (int e = 0; e < SOL_FX_COUNT; ++e)
        if (p->run[e]) {
            if (*out)
                strncat(out, " ", size - strlen(out) - 1);
            strncat(out, sol_effect_get((sol_effect)e)->name, size - strlen(out) - 1);
        }
}

Test(scene, shipped_scenes_plan_and_small_render_match_their_expected_figures, .timeout = 600)
{
    int print = getenv("SOL_SCENE_EXPECT_PRINT") != NULL;
    for (size_t i = 0; i < sizeof shipped / sizeof shipped[0]; ++i) {
        char path[256], runs[512];
        snprintf(path, sizeof path, "experiments/scenes/%s.json", shipped[i].name);
        sol_scene s;
        sol_scene_error e;
        cr_assert_eq(sol_scene_load(path, &s, &e), SOL_OK, "%s: %s %s", path, e.pointer, e.message);
        sol_scene_plan p;
        cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
        effects_run(&p, runs, sizeof runs);
        sol_render_options o = {64, 36, 0, 0};
        sol_render_result eng, ref;
        sol_render_stats st;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &eng, &st), SOL_OK, "%s", path);
        for (int k = 0; k < SOL_FX_COUNT; ++k)
            cr_expect_eq(st.effect_runs[k] > 0, p.run[k] != 0, "%s: %s ran %llu times", shipped[i].name,
                         sol_effect_get((sol_effect)k)->name, (unsigned long long)st.effect_runs[k]);
        o.reference = 1;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &ref, NULL), SOL_OK, "%s", path);
        sol_render_error err;
        cr_assert_eq(sol_render_compare(&eng, &ref, &err), SOL_OK);
        if (print)
            printf("    {\"%s\", \"%s\", %.3f, %.3f},\n", shipped[i].name, runs, err.rms_code, err.de2000_mean);
        else {
            cr_expect_str_eq(runs, shipped[i].runs, "%s: plan changed", shipped[i].name);
            cr_expect(fabs(err.rms_code - shipped[i].rms) <= 0.15 * shipped[i].rms + 0.3, "%s: RMS %.3f, expected %.3f",
                      shipped[i].name, err.rms_code, shipped[i].rms);
            cr_expect(fabs(err.de2000_mean - shipped[i].de) <= 0.15 * shipped[i].de + 0.05,
                      "%s: dE %.3f, expected %.3f", shipped[i].name, err.de2000_mean, shipped[i].de);
        }
        sol_render_result_free(&eng);
        sol_render_result_free(&ref);
        sol_scene_free(&s);
    }
}

/* ---------------- models through assimp (assimp-testmodels) ---------------- */

#define GLTF2 "/usr/share/assimp/models/glTF2/"

Test(scene, real_gltf_models_load_plan_and_render_unmodified, .timeout = 300)
{
    static const char *const models[] = {GLTF2 "ClearCoat-glTF/ClearCoatTest.gltf", GLTF2 "cameras/Cameras.gltf",
                                         GLTF2 "BoxTextured-glTF/BoxTextured.gltf"};
    for (size_t i = 0; i < sizeof models / sizeof models[0]; ++i) {
        sol_scene s;
        sol_scene_error e;
        cr_assert_eq(sol_scene_load(models[i], &s, &e), SOL_OK, "%s: %s", models[i], e.message);
        cr_expect_eq(s.object_count, 1);
        cr_expect_eq(s.objects[0].kind, SOL_GEOM_MESH);
        sol_scene_plan p;
        cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
        cr_expect_eq(p.run[SOL_FX_GBUFFER_NORMALS], 1);
        sol_render_options o = {48, 27, 0, 0};
        sol_render_result r;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &r, NULL), SOL_OK, "%s", models[i]);
        size_t covered = 0;
        for (size_t k = 0; k < (size_t)48 * 27; ++k)
            covered += r.normals.data[3 * k] != 0 || r.normals.data[3 * k + 1] != 0 || r.normals.data[3 * k + 2] != 0;
        cr_expect_gt(covered, 0, "%s: the model covers no pixel", models[i]);
        sol_render_result_free(&r);
        sol_scene_free(&s);
    }
}

/* OBJ through the same import: a tiny file written here (a red quad as two faces of a mesh with a
 * material library, plus a triangle), loaded directly and as a mesh object of a scene file, then
 * planned and rendered; and the OBJ box shipped with assimp-testmodels where it is installed. */
Test(scene, obj_models_load_plan_and_render, .timeout = 300)
{
    char dir[] = "/tmp/sol_obj_XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char obj[256], mtl[256], json[256];
    snprintf(obj, sizeof obj, "%s/quad.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/quad.mtl", dir);
    snprintf(json, sizeof json, "%s/scene.json", dir);
    FILE *fp = fopen(mtl, "w");
    cr_assert_not_null(fp);
    fputs("newmtl red\nKd 0.8 0.1 0.1\n", fp);
    fclose(fp);
    fp = fopen(obj, "w");
    cr_assert_not_null(fp);
    fputs("mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 0.5\n"
          "usemtl red\nf 1 2 3 4\nf 1 2 5\n",
          fp);
    fclose(fp);
    fp = fopen(json, "w");
    cr_assert_not_null(fp);
    fputs("{\"camera\": {\"position\": [0, 0, -4], \"look_at\": [0, 0, 0]}, \"materials\": [{\"name\": \"m\"}],"
          " \"objects\": [{\"type\": \"mesh\", \"file\": \"quad.obj\", \"material\": \"m\"}],"
          " \"lights\": [{\"type\": \"sun\", \"direction\": [0, 0, 1]}]}",
          fp);
    fclose(fp);
    const char *paths[] = {obj, json, "/usr/share/assimp/models/OBJ/box.obj"};
    for (size_t i = 0; i < 3; ++i) {
        struct stat sb;
        if (stat(paths[i], &sb) != 0)
            continue; /* assimp-testmodels not installed: the written files still run */
        sol_scene s;
        sol_scene_error e;
        cr_assert_eq(sol_scene_load(paths[i], &s, &e), SOL_OK, "%s: %s %s", paths[i], e.pointer, e.message);
        cr_assert_eq(s.object_count, 1, "%s", paths[i]);
        cr_expect_eq(s.objects[0].kind, SOL_GEOM_MESH);
        sol_scene_plan p;
        cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
        cr_expect_eq(p.run[SOL_FX_GBUFFER_NORMALS], 1);
        sol_render_options o = {32, 18, 0, 0};
        sol_render_result r;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &r, NULL), SOL_OK, "%s", paths[i]);
        size_t covered = 0, reddish = 0;
        for (size_t k = 0; k < (size_t)32 * 18; ++k) {
            int hit = r.normals.data[3 * k] != 0 || r.normals.data[3 * k + 1] != 0 || r.normals.data[3 * k + 2] != 0;
            covered += hit;
            reddish += hit && r.hdr.data[3 * k] > 2 * r.hdr.data[3 * k + 1];
        }
        cr_expect_gt(covered, 0, "%s: the model covers no pixel", paths[i]);
        if (i < 2) /* the written quad's material library gives it its red Kd */
            cr_expect_gt(reddish, covered / 2, "%s: %zu of %zu pixels red", paths[i], reddish, covered);
        sol_render_result_free(&r);
        sol_scene_free(&s);
    }
    remove(obj);
    remove(mtl);
    remove(json);
    rmdir(dir);
}

/* An anisotropic GGX material is shaded as GGX, not as Ward: its reference render differs from the
 * same scene with "ward", is finite, and both still plan the SG-lobe effect. */
Test(scene, ggx_anisotropic_material_is_shaded_as_ggx, .timeout = 300)
{
    static const char *const fmt =
        "{\"camera\":{\"position\":[0,2,-4],\"look_at\":[0,0,0],\"width\":24,\"height\":14},"
        "\"materials\":[{\"name\":\"brushed\",\"specular\":0.5,\"anisotropic\":{\"model\":\"%s\",\"roughness\":[0.05,0.4]}}],"
        "\"objects\":[{\"type\":\"sphere\",\"center\":[0,0,0],\"radius\":1,\"material\":\"brushed\"}],"
        "\"lights\":[{\"type\":\"sun\",\"direction\":[0.3,-1,0.6],\"intensity\":3}],"
        "\"pipeline\":{\"reference_supersample\":1}}";
    double sum[2] = {0, 0}, diff = 0;
    float *img[2] = {NULL, NULL};
    const char *models[2] = {"ward", "ggx"};
    for (int m = 0; m < 2; ++m) {
        char json[1024];
        snprintf(json, sizeof json, fmt, models[m]);
        sol_scene s;
        sol_scene_error e;
        cr_assert_eq(parse(json, &s, &e), SOL_OK, "%s %s", e.pointer, e.message);
        cr_expect_eq(s.materials[0].aniso, m ? SOL_ANISO_GGX : SOL_ANISO_WARD);
        sol_scene_plan p;
        cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
        cr_expect_eq(p.run[SOL_FX_SG_LOBES], 1);
        sol_render_options o = {24, 14, 1, 0};
        sol_render_result r;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &r, NULL), SOL_OK);
        size_t n = (size_t)24 * 14 * 3;
        img[m] = malloc(n * sizeof(float));
        cr_assert_not_null(img[m]);
        for (size_t k = 0; k < n; ++k) {
            cr_assert(isfinite(r.hdr.data[k]));
            img[m][k] = r.hdr.data[k];
            sum[m] += r.hdr.data[k];
        }
        sol_render_result_free(&r);
        sol_scene_free(&s);
    }
    for (size_t k = 0; k < (size_t)24 * 14 * 3; ++k)
        diff += fabs(img[0][k] - img[1][k]);
    cr_expect_gt(sum[1], 0);
    cr_expect_gt(diff, 1e-3 * sum[0], "GGX and Ward render alike (|diff| %g, sum %g)", diff, sum[0]);
    free(img[0]);
    free(img[1]);
}

/* glTF base-colour textures are sampled: BoxTextured (a white box factor with the Cesium logo
 * texture: blue sky, green hills) shows both blue- and green-dominated pixels, which a box shaded
 * by its base-colour factor alone cannot. */
Test(scene, gltf_base_colour_texture_is_sampled, .timeout = 300)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(sol_scene_load(GLTF2 "BoxTextured-glTF/BoxTextured.gltf", &s, &e), SOL_OK, "%s", e.message);
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    sol_render_options o = {96, 54, 0, 0};
    sol_render_result r;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &r, NULL), SOL_OK);
    size_t blue = 0, green = 0;
    for (size_t k = 0; k < (size_t)96 * 54; ++k) {
        const float *c = &r.hdr.data[3 * k];
        blue += c[2] > 1.3f * c[0] && c[2] > c[1];
        green += c[1] > 1.3f * c[0] && c[1] > 1.3f * c[2];
    }
    cr_expect_gt(blue, 20, "%zu blue pixels", blue);
    cr_expect_gt(green, 20, "%zu green pixels", green);
    sol_render_result_free(&r);
    sol_scene_free(&s);
}

Test(scene, broken_gltf_models_are_rejected_with_a_clear_error)
{
    static const struct {
        const char *path;
        sol_status status;
        const char *says;
    } broken[] = {
        {GLTF2 "IndexOutOfRange/IndexOutOfRange.gltf", SOL_ERR_FORMAT, "out-of-range"},
        {GLTF2 "IndexOutOfRange/AllIndicesOutOfRange.gltf", SOL_ERR_FORMAT, "no faces"},
        {GLTF2 "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", SOL_ERR_NONFINITE, "not finite"},
        {GLTF2 "MissingBin/BoxTextured.gltf", SOL_ERR_FORMAT, "BoxTextured0.bin"},
        {GLTF2 "SchemaFailures/sceneWrongType.gltf", SOL_ERR_FORMAT, "scene"},
        {"/nonexistent/model.gltf", SOL_ERR_IO, "cannot open"},
    };
    for (size_t i = 0; i < sizeof broken / sizeof broken[0]; ++i) {
        sol_scene s;
        memset(&s, 0x5a, sizeof s);
        sol_scene_error e;
        cr_expect_eq(sol_scene_load(broken[i].path, &s, &e), broken[i].status, "%s: %s", broken[i].path, e.message);
        cr_expect(strstr(e.message, broken[i].says) != NULL, "%s: message '%s'", broken[i].path, e.message);
        cr_expect_str_eq(e.file, broken[i].path);
        cr_expect_eq(((unsigned char *)&s)[0], 0x5a);
    }
    /* a scene file naming a broken mesh names the field */
    FILE *f = fopen(scratch("sol_test_mesh_scene.json"), "w");
    cr_assert(f);
    fputs("{\"materials\":[{}],\"objects\":[{\"type\":\"mesh\",\"file\":\"" GLTF2 "MissingBin/BoxTextured.gltf\"}]}", f);
    fclose(f);
    sol_scene s;
    sol_scene_error e;
    cr_expect_eq(sol_scene_load(scratch("sol_test_mesh_scene.json"), &s, &e), SOL_ERR_FORMAT);
    cr_expect_str_eq(e.pointer, "/objects/0/file");
    remove(scratch("sol_test_mesh_scene.json"));
}

/* ---------------- the sol program ---------------- */

Test(scene, cli_exit_status_and_no_output_on_bad_input)
{
    FILE *f = fopen(scratch("sol_cli_bad.json"), "w");
    cr_assert(f);
    fputs("{\"materials\":[{\"gloss\":-1}]}", f);
    fclose(f);
    (void)!shell("rm -rf %s", scratch("sol_cli_out"));
    int rc = shell("build/sol render %s --out %s 2>/dev/null", scratch("sol_cli_bad.json"), scratch("sol_cli_out"));
    cr_expect(WIFEXITED(rc) && WEXITSTATUS(rc) == 2, "render of a bad scene: status %d", rc);
    struct stat st;
    cr_expect_neq(stat(scratch("sol_cli_out"), &st), 0, "output written for a bad scene");
    rc = shell("build/sol plan %s 2>&1 | grep -q '/materials/0/gloss'", scratch("sol_cli_bad.json"));
    cr_expect_eq(rc, 0, "the message names the field");
    rc = system("build/sol plan experiments/scenes/wall_bleed.json --json | grep -q "
                "'\"clip-volumes\", \"claims\": \"D13\", \"run\": true'");
    cr_expect_eq(rc, 0, "plan --json");
    rc = system("build/sol plan 2>/dev/null");
    cr_expect(WIFEXITED(rc) && WEXITSTATUS(rc) == 2);
    remove(scratch("sol_cli_bad.json"));
}

/* An unusable --out (a regular file, a missing parent) fails before rendering, which can take
 * minutes, with exit 2 and a message naming --out and the reason; nothing is created. */
Test(scene, cli_render_unusable_out_fails_at_once)
{
    FILE *f = fopen(scratch("sol_cli_outfile"), "w");
    cr_assert(f);
    fputs("keep", f);
    fclose(f);
    int rc = shell("build/sol render experiments/scenes/car_hood.json --out %s --size 8x8 2>%s >/dev/null",
                   scratch("sol_cli_outfile"), scratch("sol_cli_outfile.err"));
    cr_expect(WIFEXITED(rc) && WEXITSTATUS(rc) == 2, "render into a file: status %d", rc);
    rc = shell("grep -q -- '--out %s: .*Not a directory' %s", scratch("sol_cli_outfile"), scratch("sol_cli_outfile.err"));
    cr_expect_eq(rc, 0, "the message names --out and the reason");
    rc = shell("grep -q 'keep' %s", scratch("sol_cli_outfile"));
    cr_expect_eq(rc, 0, "the file given as --out is untouched");
    (void)!shell("rm -rf %s", scratch("sol_cli_noparent"));
    rc = shell("build/sol render experiments/scenes/car_hood.json --out %s/x --size 8x8 2>/dev/null >/dev/null",
               scratch("sol_cli_noparent"));
    cr_expect(WIFEXITED(rc) && WEXITSTATUS(rc) == 2, "render under a missing folder: status %d", rc);
    struct stat st;
    cr_expect_neq(stat(scratch("sol_cli_noparent"), &st), 0, "nothing created");
    remove(scratch("sol_cli_outfile"));
    remove(scratch("sol_cli_outfile.err"));
}

/* A render killed mid-way (SIGTERM as soon as its --out folder exists) leaves nothing: neither
 * the folder it made nor temporary files; the exit status is still the signal's. */
Test(scene, cli_render_killed_leaves_nothing)
{
    /* the folder carries the shell's pid ($$), so concurrent test runs do not share it */
    int rc = system("d=/tmp/sol_cli_kill_$$; rm -rf $d; "
                    "build/sol render experiments/scenes/car_hood.json --out $d --size 960x540 "
                    ">/dev/null 2>&1 & p=$!; i=0; "
                    "while [ ! -d $d ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; "
                    "kill -TERM $p; wait $p; s=$?; test $s -eq 143 && test ! -e $d; r=$?; rm -rf $d; exit $r");
    cr_expect_eq(rc, 0, "killed render left its --out folder or exited otherwise (status %d)", rc);
}

/* ... but a signal its caller ignores (trap '' INT) stays ignored: the render finishes. */
Test(scene, cli_render_keeps_ignored_signals)
{
    int rc = system("d=/tmp/sol_cli_ign_$$; rm -rf $d; trap '' INT; "
                    "build/sol render experiments/scenes/car_hood.json --out $d --size 320x180 "
                    ">/dev/null 2>&1 & p=$!; i=0; "
                    "while [ ! -d $d ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; "
                    "kill -INT $p; wait $p && test -s $d/attribution.tsv; r=$?; rm -rf $d; exit $r");
    cr_expect_eq(rc, 0, "an ignored SIGINT stopped the render (status %d)", rc);
}
