/* test_scene_gltf.c - glTF materials in the scene layer: normal textures (sampled in the mesh's
 * tangent frame, through normal-map-bc5), base-colour textures through the albedo effects, and
 * KHR_materials_anisotropy (read from the JSON, as assimp 5.2 lacks it) calling for sg-lobes; and
 * their bad input. The models are written here (a quad, a .bin, PNG textures); no third-party copy. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene_internal.h"
#include "sol_scene.h"

/* Each test works in its own folder (Criterion runs tests in parallel processes). */
static char dir[128];
static char *in_dir(const char *name)
{
    static char buf[4][256];
    static int k;
    k = (k + 1) & 3;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}
static void use_dir(const char *test)
{
    char cmd[300];
    snprintf(dir, sizeof dir, "/tmp/sol_gltf_%s_%d", test, (int)getpid());
    snprintf(cmd, sizeof cmd, "rm -rf %s && mkdir -p %s", dir, dir);
    cr_assert_eq(system(cmd), 0);
}

/* A unit quad in the z = 0 plane facing -z (towards a camera at z = -3), glTF texture
 * coordinates (0,0) at its top-left corner (-1, 1, 0), so +u runs along +x and the texture's
 * "up" (+Y of a normal texture) along +y. `material` is the JSON of materials[0]. */
static void write_quad_gltf(const char *name, const char *material)
{
    const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const float nrm[12] = {0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1};
    const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint16_t idx[6] = {0, 2, 1, 0, 3, 2};
    FILE *f = fopen(in_dir("quad.bin"), "wb");
    cr_assert_not_null(f);
    fwrite(pos, 4, 12, f);
    fwrite(nrm, 4, 12, f);
    fwrite(uv, 4, 8, f);
    fwrite(idx, 2, 6, f);
    fclose(f);
    f = fopen(in_dir(name), "w");
    cr_assert_not_null(f);
    fprintf(f,
            "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_materials_anisotropy\"],"
            "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
            "\"indices\":3,\"material\":0}]}],"
            "\"buffers\":[{\"uri\":\"quad.bin\",\"byteLength\":140}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
            "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":96,\"byteLength\":32},"
            "{\"buffer\":0,\"byteOffset\":128,\"byteLength\":12}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
            "\"min\":[-1,-1,0],\"max\":[1,1,0]},"
            "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
            "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
            "{\"bufferView\":3,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
            "\"images\":[{\"uri\":\"normal.png\"},{\"uri\":\"base.png\"},{\"uri\":\"missing.png\"},{\"uri\":\"grey.png\"}],"
            "\"textures\":[{\"source\":0},{\"source\":1},{\"source\":2},{\"source\":3}],"
            "\"materials\":[%s]}",
            material);
    fclose(f);
}

/* 8x8 PNG textures: normal.png holds the tangent-space normal (0.36, 0.48, 0.8) (codes (n+1)/2),
 * base.png the sRGB colour (200, 100, 50), grey.png one channel. */
static void write_textures(void)
{
    sol_image n, b, g;
    cr_assert_eq(sol_image_alloc(&n, 8, 8, 3), SOL_OK);
    cr_assert_eq(sol_image_alloc(&b, 8, 8, 3), SOL_OK);
    cr_assert_eq(sol_image_alloc(&g, 8, 8, 1), SOL_OK);
    const double tn[3] = {0.36, 0.48, 0.8}, srgb[3] = {200, 100, 50};
    for (int i = 0; i < 64; ++i) {
        for (int c = 0; c < 3; ++c) {
            n.data[3 * i + c] = (float)(round((tn[c] + 1) * 0.5 * 255) / 255);
            b.data[3 * i + c] = (float)(srgb[c] / 255);
        }
        g.data[i] = 0.5f;
    }
    cr_assert_eq(sol_png_write(in_dir("normal.png"), &n, 8), SOL_OK);
    cr_assert_eq(sol_png_write(in_dir("base.png"), &b, 8), SOL_OK);
    cr_assert_eq(sol_png_write(in_dir("grey.png"), &g, 8), SOL_OK);
    sol_image_free(&n);
    sol_image_free(&b);
    sol_image_free(&g);
}

static void cleanup(void)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    (void)!system(cmd);
}

/* Loads quad.gltf, puts a camera looking at the quad head on (from z = -3) and builds its plan. */
static void load_quad_head_on(sol_scene *s, sol_scene_plan *p)
{
    sol_scene_error e;
    cr_assert_eq(sol_scene_load(in_dir("quad.gltf"), s, &e), SOL_OK, "%s", e.message);
    const double pos[3] = {0, 0, -3}, at[3] = {0, 0, 0};
    memcpy(s->camera.position, pos, sizeof pos);
    memcpy(s->camera.look_at, at, sizeof at);
    s->camera.fov_deg = 40;
    cr_assert_eq(sol_scene_plan_build(s, p), SOL_OK);
}

/* The quad's normal texture is sampled in its tangent frame: the reference path's normal at the
 * centre is 0.36 T + 0.48 B + 0.8 N with T = +x (along +u), B = +y (the texture's up), N = -z;
 * the plan names the glTF material's normalTexture (normal-map-bc5) and its baseColorTexture
 * (the albedo effects), and the engine path runs them. */
Test(scene_gltf, normal_and_base_colour_textures_are_sampled_and_planned)
{
    use_dir("normal");
    write_textures();
    write_quad_gltf("quad.gltf", "{\"name\":\"tiles\",\"normalTexture\":{\"index\":0},"
                                 "\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1},\"roughnessFactor\":0.5}}");
    sol_scene s;
    sol_scene_plan p;
    load_quad_head_on(&s, &p);
    cr_expect_eq(p.run[SOL_FX_NORMAL_MAP_BC5], 1);
    cr_expect_str_eq(p.element[SOL_FX_NORMAL_MAP_BC5], "/materials/0/normalTexture");
    cr_expect(strstr(p.reason[SOL_FX_NORMAL_MAP_BC5], "normal.png") && strstr(p.reason[SOL_FX_NORMAL_MAP_BC5], "tiles"),
              "%s", p.reason[SOL_FX_NORMAL_MAP_BC5]);
    for (int fxi = SOL_FX_ALBEDO_STORAGE; fxi <= SOL_FX_ALBEDO_RENORM; ++fxi) {
        cr_expect_eq(p.run[fxi], 1, "%s", sol_effect_get((sol_effect)fxi)->name);
        cr_expect_str_eq(p.element[fxi], "/materials/0/pbrMetallicRoughness/baseColorTexture");
    }
    sol_render_options o = {32, 18, 1, 0};
    sol_render_result ref, eng;
    sol_render_stats st;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &ref, NULL), SOL_OK);
    const float *n = &ref.normals.data[3 * (9 * 32 + 16)];
    double len = sqrt(0.36 * 0.36 + 0.48 * 0.48 + 0.64);
    cr_expect(fabs(n[0] - 0.36 / len) < 0.01 && fabs(n[1] - 0.48 / len) < 0.01 && fabs(n[2] + 0.8 / len) < 0.01,
              "normal (%f, %f, %f)", n[0], n[1], n[2]);
    const float *c = &ref.hdr.data[3 * (9 * 32 + 16)];
    cr_expect(c[0] > 1.5f * c[1] && c[1] > 1.5f * c[2], "base colour not sampled: (%f, %f, %f)", c[0], c[1], c[2]);
    o.reference = 0;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &eng, &st), SOL_OK);
    for (int k = 0; k < SOL_FX_COUNT; ++k)
        cr_expect_eq(st.effect_runs[k] > 0, p.run[k] != 0, "%s ran %llu times", sol_effect_get((sol_effect)k)->name,
                     (unsigned long long)st.effect_runs[k]);
    sol_render_error err;
    cr_assert_eq(sol_render_compare(&eng, &ref, &err), SOL_OK);
    cr_expect_lt(err.normal_mean_deg, 2.0, "engine normals %.3f deg off", err.normal_mean_deg);
    sol_render_result_free(&ref);
    sol_render_result_free(&eng);
    sol_scene_free(&s);
    cleanup();
}

/* glTF normalTexture.scale multiplies the sampled normal's x and y before renormalising (glTF 2.0,
 * material.normalTextureInfo): at 0.5 the quad's centre normal is normalize(0.18 T + 0.24 B + 0.8 N);
 * at 0 the map is flat (the geometric normal -z); at -1 the relief flips. A scale beyond a double's
 * range is refused (assimp's JSON reader rejects the file). */
Test(scene_gltf, normal_texture_scale_scales_xy_before_renormalising)
{
    use_dir("nscale");
    write_textures();
    const struct {
        const char *scale;
        double t, b, n;
    } cases[] = {{"0.5", 0.18, 0.24, 0.8}, {"0", 0, 0, 1}, {"-1", -0.36, -0.48, 0.8}};
    for (int k = 0; k < 3; ++k) {
        char mat[160];
        snprintf(mat, sizeof mat, "{\"name\":\"tiles\",\"normalTexture\":{\"index\":0,\"scale\":%s}}", cases[k].scale);
        write_quad_gltf("quad.gltf", mat);
        sol_scene s;
        sol_scene_plan p;
        load_quad_head_on(&s, &p);
        sol_render_options o = {32, 18, 1, 0};
        sol_render_result ref;
        cr_assert_eq(sol_scene_render(&s, &p, &o, &ref, NULL), SOL_OK);
        const float *n = &ref.normals.data[3 * (9 * 32 + 16)];
        double len = sqrt(cases[k].t * cases[k].t + cases[k].b * cases[k].b + cases[k].n * cases[k].n);
        /* world: T = +x, B = +y, N = -z */
        cr_expect(fabs(n[0] - cases[k].t / len) < 0.01 && fabs(n[1] - cases[k].b / len) < 0.01 &&
                      fabs(n[2] + cases[k].n / len) < 0.01,
                  "scale %s: normal (%f, %f, %f)", cases[k].scale, n[0], n[1], n[2]);
        sol_render_result_free(&ref);
        sol_scene_free(&s);
    }
    write_quad_gltf("quad.gltf", "{\"name\":\"tiles\",\"normalTexture\":{\"index\":0,\"scale\":1e999}}");
    sol_scene s;
    sol_scene_error e;
    sol_status st = sol_scene_load(in_dir("quad.gltf"), &s, &e);
    cr_expect_neq(st, SOL_OK, "an infinite normalTexture.scale was accepted");
    if (st == SOL_OK)
        sol_scene_free(&s);
    cleanup();
}

/* ClearCoatTest (assimp-testmodels, unmodified): RibsNormal.png is a normal texture of material 9
 * ("BaseNorm_Base"), PartialCoating_Alpha.png an 8-bit base-colour texture of material 5; the
 * JPEG normal texture (PlasticWrap_normals.jpg) is not read. */
Test(scene_gltf, clearcoat_plan_calls_for_normal_map_and_albedo_effects)
{
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(sol_scene_load("/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf", &s, &e), SOL_OK,
                 "%s", e.message);
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_NORMAL_MAP_BC5], 1);
    cr_expect_str_eq(p.element[SOL_FX_NORMAL_MAP_BC5], "/materials/9/normalTexture");
    cr_expect(strstr(p.reason[SOL_FX_NORMAL_MAP_BC5], "RibsNormal.png") != NULL, "%s", p.reason[SOL_FX_NORMAL_MAP_BC5]);
    cr_expect_eq(p.run[SOL_FX_ALBEDO_STORAGE], 1);
    cr_expect_str_eq(p.element[SOL_FX_ALBEDO_BC1], "/materials/5/pbrMetallicRoughness/baseColorTexture");
    const sol_mesh *m = s.objects[0].mesh;
    int normals = 0;
    for (int i = 0; i < m->tex_count; ++i)
        normals += m->tex[i].normal;
    cr_expect_eq(normals, 1, "RibsNormal.png is read once for the materials sharing it");
    sol_scene_free(&s);
}

/* KHR_materials_anisotropy: read from the JSON (strength, rotation, alpha = roughness^2), it
 * makes the material anisotropic GGX and calls for sg-lobes; both paths render it. */
Test(scene_gltf, khr_materials_anisotropy_calls_for_sg_lobes)
{
    use_dir("aniso");
    write_textures();
    write_quad_gltf("aniso.gltf", "{\"name\":\"brushed\",\"pbrMetallicRoughness\":{\"roughnessFactor\":0.3},"
                                  "\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":0.8,"
                                  "\"anisotropyRotation\":0.5}}}");
    sol_scene s;
    sol_scene_error e;
    cr_assert_eq(sol_scene_load(in_dir("aniso.gltf"), &s, &e), SOL_OK, "%s", e.message);
    const sol_mesh_material *mm = &s.objects[0].mesh->mats[0];
    cr_expect_eq(mm->aniso, 1);
    cr_expect_float_eq(mm->aniso_strength, 0.8, 1e-12);
    cr_expect_float_eq(mm->aniso_rotation, 0.5, 1e-12);
    cr_expect_float_eq(mm->alpha, 0.09, 1e-7);
    sol_scene_plan p;
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_SG_LOBES], 1);
    cr_expect_str_eq(p.element[SOL_FX_SG_LOBES], "/materials/0/extensions/KHR_materials_anisotropy");
    double pos[3] = {0, 0.5, -3}, at[3] = {0, 0, 0};
    memcpy(s.camera.position, pos, sizeof pos);
    memcpy(s.camera.look_at, at, sizeof at);
    sol_render_options o = {24, 14, 0, 0};
    sol_render_result r;
    sol_render_stats st;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &r, &st), SOL_OK);
    cr_expect_gt(st.effect_runs[SOL_FX_SG_LOBES], 0);
    for (size_t k = 0; k < (size_t)24 * 14 * 3; ++k)
        cr_assert(isfinite(r.hdr.data[k]));
    sol_render_result_free(&r);
    o.reference = 1;
    cr_assert_eq(sol_scene_render(&s, &p, &o, &r, NULL), SOL_OK);
    sol_render_result_free(&r);
    sol_scene_free(&s);
    /* without the extension: isotropic, sg-lobes skipped */
    write_quad_gltf("iso.gltf", "{\"name\":\"plain\",\"pbrMetallicRoughness\":{\"roughnessFactor\":0.3}}");
    cr_assert_eq(sol_scene_load(in_dir("iso.gltf"), &s, &e), SOL_OK, "%s", e.message);
    cr_assert_eq(sol_scene_plan_build(&s, &p), SOL_OK);
    cr_expect_eq(p.run[SOL_FX_SG_LOBES], 0);
    sol_scene_free(&s);
    cleanup();
}

/* Bad input of the new paths: a missing texture file is named; a one-channel normal texture and
 * an out-of-range or mistyped anisotropy field are refused naming what is wrong; nothing is output. */
Test(scene_gltf, bad_textures_and_anisotropy_are_rejected)
{
    use_dir("bad");
    write_textures();
    static const struct {
        const char *material;
        sol_status status;
        const char *says;
    } bad[] = {
        {"{\"name\":\"m\",\"normalTexture\":{\"index\":2}}", SOL_ERR_IO, "missing.png"},
        {"{\"name\":\"m\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":2}}}", SOL_ERR_IO, "missing.png"},
        {"{\"name\":\"m\",\"normalTexture\":{\"index\":3}}", SOL_ERR_FORMAT, "grey.png"},
        {"{\"name\":\"m\",\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":2}}}", SOL_ERR_OUT_OF_RANGE,
         "/materials/0/extensions/KHR_materials_anisotropy/anisotropyStrength"},
        {"{\"name\":\"m\",\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyRotation\":\"x\"}}}", SOL_ERR_FORMAT,
         "/materials/0/extensions/KHR_materials_anisotropy/anisotropyRotation"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        write_quad_gltf("bad.gltf", bad[i].material);
        sol_scene s;
        memset(&s, 0x5a, sizeof s);
        sol_scene_error e;
        cr_expect_eq(sol_scene_load(in_dir("bad.gltf"), &s, &e), bad[i].status, "case %zu: %s", i, e.message);
        cr_expect(strstr(e.message, bad[i].says) != NULL, "case %zu: '%s'", i, e.message);
        cr_expect_str_eq(e.file, in_dir("bad.gltf"));
        cr_expect_eq(((unsigned char *)&s)[0], 0x5a);
    }
    /* the grey one names its channel count */
    write_quad_gltf("bad.gltf", bad[2].material);
    sol_scene s;
    sol_scene_error e;
    cr_expect_eq(sol_scene_load(in_dir("bad.gltf"), &s, &e), SOL_ERR_FORMAT);
    cr_expect(strstr(e.message, "1 channel") != NULL, "%s", e.message);
    /* a scene file's mesh object names the field */
    FILE *f = fopen(in_dir("scene.json"), "w");
    cr_assert_not_null(f);
    fputs("{\"materials\":[{}],\"objects\":[{\"type\":\"mesh\",\"file\":\"bad.gltf\"}]}", f);
    fclose(f);
    cr_expect_eq(sol_scene_load(in_dir("scene.json"), &s, &e), SOL_ERR_FORMAT);
    cr_expect_str_eq(e.pointer, "/objects/0/file");
    cleanup();
}

/* sol_mesh_read_anisotropy_json's contract (scene_internal.h): the first mat_count materials,
 * defaults, the spec's alpha = roughnessFactor^2, errors naming the JSON pointer, and JSON that does
 * not parse (or is cut short, not NUL-terminated) read as "no extension". */
Test(scene_gltf, anisotropy_json_reader_contract)
{
    sol_mesh_material mats[2];
    memset(mats, 0, sizeof mats);
    sol_mesh m;
    memset(&m, 0, sizeof m);
    m.mat_count = 2;
    m.mats = mats;
    char msg[256] = "";
    const char *ok = "{\"materials\":[{\"pbrMetallicRoughness\":{\"roughnessFactor\":0.5},\"extensions\":"
                     "{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":0.25}}},{}, "
                     "{\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":1}}}]}";
    cr_assert_eq(sol_mesh_read_anisotropy_json(ok, strlen(ok), &m, msg, sizeof msg), SOL_OK);
    cr_assert(mats[0].aniso && mats[0].aniso_strength == 0.25 && mats[0].aniso_rotation == 0.0);
    cr_assert_float_eq(mats[0].alpha, 0.25, 1e-15);
    cr_assert(!mats[1].aniso, "a material without the extension is untouched; the third is past mat_count");
    const char *bad = "{\"materials\":[{},{\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyStrength\":-1}}}]}";
    cr_assert_eq(sol_mesh_read_anisotropy_json(bad, strlen(bad), &m, msg, sizeof msg), SOL_ERR_OUT_OF_RANGE);
    cr_assert(strstr(msg, "/materials/1/extensions/KHR_materials_anisotropy/anisotropyStrength"), "%s", msg);
    const char *type = "{\"materials\":[{\"extensions\":{\"KHR_materials_anisotropy\":{\"anisotropyRotation\":\"x\"}}}]}";
    cr_assert_eq(sol_mesh_read_anisotropy_json(type, strlen(type), &m, msg, sizeof msg), SOL_ERR_FORMAT);
    memset(mats, 0, sizeof mats);
    cr_assert_eq(sol_mesh_read_anisotropy_json(ok, 20, &m, msg, sizeof msg), SOL_OK, "cut short: no extension");
    cr_assert_eq(sol_mesh_read_anisotropy_json("", 0, &m, msg, sizeof msg), SOL_OK);
    cr_assert(!mats[0].aniso);
}
