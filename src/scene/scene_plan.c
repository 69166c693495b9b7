/* scene_plan.c - the effect graph: which of the talk's techniques a scene calls for.
 *
 * Each rule reads the loaded scene only (no I/O, no rendering) and names the element that calls
 * for the effect by its JSON pointer, or says why the effect is skipped. The renderer
 * (scene_render.c) runs an effect only when the plan says so. */
#include <stdio.h>
#include <string.h>

#include "sol_normals.h"
#include "scene_internal.h"
#include "sol_scene.h"

static const sol_effect_info effects[SOL_FX_COUNT] = {
    [SOL_FX_GBUFFER_NORMALS] = {"gbuffer-normals", "D3-D7, S1, S5", "any geometry, pipeline.gbuffer_normals not float",
                                "shading normal per pixel", "24-bit normal code, decoded normal",
                                "float normals"},
    [SOL_FX_NORMAL_MAP_BC5] = {"normal-map-bc5", "T8-T14", "a material with a normal map, codec not none",
                               "normal-map texels", "BC5 blocks, decoded normal map", "float normal map"},
    [SOL_FX_ALBEDO_STORAGE] = {"albedo-storage", "T3-T7", "a material with an 8-bit albedo texture",
                               "linear albedo texels", "8-bit codes in gamma or linear storage (T4 rule)",
                               "float albedo"},
    [SOL_FX_ALBEDO_BC1] = {"albedo-bc1", "T1, T2", "an 8-bit albedo texture, albedo_codec not none",
                           "albedo texels in storage space", "BC1 blocks, decoded texels", "uncompressed texels"},
    [SOL_FX_ALBEDO_RENORM] = {"albedo-renorm", "T1, T2", "an 8-bit albedo texture, albedo_renormalize",
                              "albedo texels", "stored range-renormalised texels + scale/bias", "no renormalisation"},
    [SOL_FX_LIGHT_BUFFER] = {"light-buffer", "D9, S2, S9", "pipeline.light_buffer not float",
                             "diffuse and specular light sums", "light buffer in r11g11b10f / rgbm / rgb10",
                             "float light buffer"},
    [SOL_FX_RANGE_SCALING] = {"range-scaling", "D9, D10", "a lossy light buffer with range_scaling",
                              "light sums, exposure, tone map", "light buffer scaled so the display's white point lands on the format's top",
                              "unscaled light values"},
    [SOL_FX_SG_LOBES] = {"sg-lobes", "D15, D16", "an object with an anisotropic material, and a light",
                         "Ward roughness pair, lights as SG lobes",
                         "SG fit of the NDF, principal Phong lobe (normal, gloss) per pixel",
                         "the exact Ward BRDF per light"},
    [SOL_FX_CLIP_VOLUMES] = {"clip-volumes", "D13", "an unshadowed light with a clip volume",
                             "light, clip box", "per-pixel stencil mask", "ray-traced shadows for that light"},
    [SOL_FX_SSAO] = {"ssao", "M3", "pipeline.ssao", "depth buffer", "ambient obscurance (few samples, half resolution)",
                     "full-resolution obscurance with 256 samples"},
    [SOL_FX_TEMPORAL] = {"temporal", "D18, M3", "a camera path with aa temporal or ssao",
                         "frames of the path, depth, jitter", "accumulated frame by reprojection",
                         "the last frame, supersampled"},
    [SOL_FX_POST_AA] = {"post-aa", "D17", "pipeline.aa post", "display image", "filtered display image",
                        "supersampling"},
    [SOL_FX_CULLING] = {"culling", "M1", "pipeline.culling on, or auto with >= 8 boxes",
                        "occluder depth (max-downscaled to 4x4-pixel texels), object bounds",
                        "objects culled before the G-buffer pass",
                        "no culling"},
    [SOL_FX_LUT_GRADING] = {"lut-grading", "M4", "pipeline.look", "display colours",
                            "graded colours through a size^3 trilinear LUT", "the grading transform itself"},
    [SOL_FX_ENV_SG] = {"env-sg", "D15, D16", "an environment light with a lat-long EXR (file), and geometry",
                       "lat-long radiance map",
                       "SG lighting lobes fitted to the map (non-negative least squares over its texels)",
                       "the map itself: exact irradiance table, importance-sampled specular"},
};

const sol_effect_info *sol_effect_get(sol_effect effect)
{
    return (unsigned)effect < SOL_FX_COUNT ? &effects[effect] : NULL;
}

static void set(sol_scene_plan *p, sol_effect e, int run, const char *element, const char *fmt, const char *arg)
{
    p->run[e] = run;
    snprintf(p->element[e], sizeof p->element[e], "%s", element);
    snprintf(p->reason[e], sizeof p->reason[e], fmt, arg);
}

/* The first material used by an object that satisfies `pred`, or -1. */
static int used_material(const sol_scene *s, int (*pred)(const sol_scene_material *))
{
    for (int m = 0; m < s->material_count; ++m) {
        if (!pred(&s->materials[m]))
            continue;
        for (int o = 0; o < s->object_count; ++o)
            if (s->objects[o].material == m)
                return m;
    }
    return -1;
}

static int has_normal_map(const sol_scene_material *m) { return m->normal_map.source != SOL_TEX_NONE; }
static int has_albedo8(const sol_scene_material *m)
{
    return m->albedo_texture.source != SOL_TEX_NONE && m->albedo_texture.bits == 8;
}
static int has_albedo(const sol_scene_material *m) { return m->albedo_texture.source != SOL_TEX_NONE; }
static int is_aniso(const sol_scene_material *m) { return m->aniso != SOL_ANISO_NONE; }

/* The first mesh object with a texture of the kind asked (normal, or 8-bit base colour when
 * bits8), or with an anisotropic material (aniso): *object, and *mat (its model material); 0 if none. */
static int mesh_calls(const sol_scene *s, int normal, int bits8, int aniso, int *object, int *mat, int *tex)
{
    for (int o = 0; o < s->object_count; ++o) {
        const sol_mesh *m = s->objects[o].kind == SOL_GEOM_MESH ? s->objects[o].mesh : NULL;
        if (!m)
            continue;
        for (int k = 0; k < m->mat_count; ++k) {
            const sol_mesh_material *mm = &m->mats[k];
            int t = aniso ? -1 : normal ? mm->normal_tex : mm->base_tex;
            if (aniso ? mm->aniso : t >= 0 && (!bits8 || m->tex[t].bits == 8)) {
                *object = o, *mat = k, *tex = t;
                return 1;
            }
        }
    }
    return 0;
}

/* The element of a model's material: the model's own JSON pointer when the scene is the model
 * (a glTF given to sol plan directly), else the scene's mesh object. */
static void mesh_element(const sol_scene *s, int object, int mat, const char *field, char *out, size_t size)
{
    const char *f = s->objects[object].file;
    size_t n = strlen(f);
    int gltf = (n >= 5 && !strcmp(f + n - 5, ".gltf")) || (n >= 4 && !strcmp(f + n - 4, ".glb"));
    if (!strcmp(s->path, f) && gltf)
        snprintf(out, size, "/materials/%d/%s", mat, field);
    else
        snprintf(out, size, "/objects/%d/file", object);
}

sol_status sol_scene_plan_build(const sol_scene *s, sol_scene_plan *out)
{
    if (!s || !out)
        return SOL_ERR_NULL_ARG;
    sol_scene_plan p;
    memset(&p, 0, sizeof p);
    const sol_scene_pipeline *pl = &s->pipeline;
    char ptr[128];
    int drawable = 0, boxes = 0;
    for (int o = 0; o < s->object_count; ++o) {
        drawable += 1;
        boxes += s->objects[o].kind == SOL_GEOM_BOX;
    }

    if (!drawable)
        set(&p, SOL_FX_GBUFFER_NORMALS, 0, "", "%sthe scene has no geometry", "");
    else if (pl->gbuffer_normals < 0)
        set(&p, SOL_FX_GBUFFER_NORMALS, 0, "/pipeline/gbuffer_normals", "%sgbuffer_normals is float", "");
    else
        set(&p, SOL_FX_GBUFFER_NORMALS, 1, "/pipeline/gbuffer_normals", "normals stored as %s",
            sol_normal_method_name((sol_normal_method)pl->gbuffer_normals));

    int m = used_material(s, has_normal_map), mo, mm, mt;
    char what[160];
    if (m < 0 && mesh_calls(s, 1, 0, 0, &mo, &mm, &mt)) { /* a model's normal texture */
        const sol_mesh *mesh = s->objects[mo].mesh;
        mesh_element(s, mo, mm, "normalTexture", ptr, sizeof ptr);
        snprintf(what, sizeof what, "normal texture %.60s of model material \"%.40s\"", mesh->tex[mt].name,
                 mesh->mats[mm].name);
    }
    if (m < 0 && !mesh_calls(s, 1, 0, 0, &mo, &mm, &mt))
        set(&p, SOL_FX_NORMAL_MAP_BC5, 0, "", "%sno drawn material has a normal map", "");
    else if (pl->normal_map_codec == SOL_CODEC_NONE)
        set(&p, SOL_FX_NORMAL_MAP_BC5, 0, "/pipeline/normal_map_codec", "%snormal_map_codec is none", "");
    else if (m >= 0) {
        snprintf(ptr, sizeof ptr, "/materials/%d/normal_map", m);
        set(&p, SOL_FX_NORMAL_MAP_BC5, 1, ptr, "normal map of material \"%s\"", s->materials[m].name);
    } else
        set(&p, SOL_FX_NORMAL_MAP_BC5, 1, ptr, "%s", what);

    m = used_material(s, has_albedo8);
    int mesh_albedo8 = m < 0 && mesh_calls(s, 0, 1, 0, &mo, &mm, &mt);
    if (mesh_albedo8) { /* a model's 8-bit base-colour texture */
        const sol_mesh *mesh = s->objects[mo].mesh;
        mesh_element(s, mo, mm, "pbrMetallicRoughness/baseColorTexture", ptr, sizeof ptr);
        snprintf(what, sizeof what, "8-bit base-colour texture %.60s of model material \"%.40s\"", mesh->tex[mt].name,
                 mesh->mats[mm].name);
        set(&p, SOL_FX_ALBEDO_STORAGE, 1, ptr, "%s", what);
        if (pl->albedo_codec == SOL_CODEC_NONE)
            set(&p, SOL_FX_ALBEDO_BC1, 0, "/pipeline/albedo_codec", "%salbedo_codec is none", "");
        else
            set(&p, SOL_FX_ALBEDO_BC1, 1, ptr, "%s", what);
        if (!pl->albedo_renormalize)
            set(&p, SOL_FX_ALBEDO_RENORM, 0, "/pipeline/albedo_renormalize", "%salbedo_renormalize is false", "");
        else
            set(&p, SOL_FX_ALBEDO_RENORM, 1, ptr, "%s", what);
    } else if (m < 0) {
        const char *why = used_material(s, has_albedo) >= 0 || mesh_calls(s, 0, 0, 0, &mo, &mm, &mt)
                              ? "%salbedo textures are 16-bit (no 8-bit storage)"
                              : "%sno drawn material has an albedo texture";
        set(&p, SOL_FX_ALBEDO_STORAGE, 0, "", why, "");
        set(&p, SOL_FX_ALBEDO_BC1, 0, "", why, "");
        set(&p, SOL_FX_ALBEDO_RENORM, 0, "", why, "");
    } else {
        snprintf(ptr, sizeof ptr, "/materials/%d/albedo_texture", m);
        set(&p, SOL_FX_ALBEDO_STORAGE, 1, ptr, "8-bit albedo texture of material \"%s\"", s->materials[m].name);
        if (pl->albedo_codec == SOL_CODEC_NONE)
            set(&p, SOL_FX_ALBEDO_BC1, 0, "/pipeline/albedo_codec", "%salbedo_codec is none", "");
        else
            set(&p, SOL_FX_ALBEDO_BC1, 1, ptr, "8-bit albedo texture of material \"%s\"", s->materials[m].name);
        if (!pl->albedo_renormalize)
            set(&p, SOL_FX_ALBEDO_RENORM, 0, "/pipeline/albedo_renormalize", "%salbedo_renormalize is false", "");
        else
            set(&p, SOL_FX_ALBEDO_RENORM, 1, ptr, "8-bit albedo texture of material \"%s\"", s->materials[m].name);
    }

    if (!drawable || s->light_count == 0) {
        set(&p, SOL_FX_LIGHT_BUFFER, 0, "", "%snothing is lit (no geometry or no lights)", "");
        set(&p, SOL_FX_RANGE_SCALING, 0, "", "%snothing is lit (no geometry or no lights)", "");
    } else if (pl->light_buffer == SOL_LB_FLOAT) {
        set(&p, SOL_FX_LIGHT_BUFFER, 0, "/pipeline/light_buffer", "%slight_buffer is float", "");
        set(&p, SOL_FX_RANGE_SCALING, 0, "/pipeline/light_buffer", "%sa float light buffer needs no scaling", "");
    } else {
        static const char *const names[] = {"float", "r11g11b10f", "rgbm", "rgb10"};
        set(&p, SOL_FX_LIGHT_BUFFER, 1, "/pipeline/light_buffer", "light buffer stored as %s", names[pl->light_buffer]);
        if (pl->range_scaling)
            set(&p, SOL_FX_RANGE_SCALING, 1, "/pipeline/range_scaling", "lossy %s light buffer",
                names[pl->light_buffer]);
        else
            set(&p, SOL_FX_RANGE_SCALING, 0, "/pipeline/range_scaling", "%srange_scaling is false", "");
    }

    m = used_material(s, is_aniso);
    int mesh_aniso = m < 0 && mesh_calls(s, 0, 0, 1, &mo, &mm, &mt);
    if (m < 0 && !mesh_aniso)
        set(&p, SOL_FX_SG_LOBES, 0, "", "%sno drawn material is anisotropic", "");
    else if (s->light_count == 0)
        set(&p, SOL_FX_SG_LOBES, 0, "/lights", "%sno lights", "");
    else if (m >= 0) {
        snprintf(ptr, sizeof ptr, "/materials/%d/anisotropic", m);
        set(&p, SOL_FX_SG_LOBES, 1, ptr, "anisotropic material \"%s\"", s->materials[m].name);
    } else {
        mesh_element(s, mo, mm, "extensions/KHR_materials_anisotropy", ptr, sizeof ptr);
        set(&p, SOL_FX_SG_LOBES, 1, ptr, "KHR_materials_anisotropy of model material \"%.60s\"",
            s->objects[mo].mesh->mats[mm].name);
    }

    int clipped = -1;
    for (int l = 0; l < s->light_count && clipped < 0; ++l)
        if (s->lights[l].clip >= 0 && !s->lights[l].shadows && s->lights[l].kind != SOL_LIGHT_ENV)
            clipped = l;
    if (clipped < 0)
        set(&p, SOL_FX_CLIP_VOLUMES, 0, "", "%sno unshadowed light has a clip volume", "");
    else {
        snprintf(ptr, sizeof ptr, "/lights/%d/clip", clipped);
        set(&p, SOL_FX_CLIP_VOLUMES, 1, ptr, "unshadowed light with a clip volume (%.60s)", ptr);
    }

    if (!pl->ssao)
        set(&p, SOL_FX_SSAO, 0, "/pipeline/ssao", "%sssao is false", "");
    else if (!drawable)
        set(&p, SOL_FX_SSAO, 0, "", "%sthe scene has no geometry", "");
    else
        set(&p, SOL_FX_SSAO, 1, "/pipeline/ssao", "ssao is true (%s resolution)", pl->ssao_half_res ? "half" : "full");

    if (s->camera.frame_count < 2)
        set(&p, SOL_FX_TEMPORAL, 0, "/camera/path", "%sno camera path", "");
    else if (pl->aa != SOL_AA_TEMPORAL && !pl->ssao)
        set(&p, SOL_FX_TEMPORAL, 0, "/pipeline/aa", "%sa camera path, but neither aa temporal nor ssao", "");
    else
        set(&p, SOL_FX_TEMPORAL, 1, "/camera/path", "camera path with %s", pl->aa == SOL_AA_TEMPORAL ? "aa temporal" : "ssao");

    if (pl->aa != SOL_AA_POST)
        set(&p, SOL_FX_POST_AA, 0, "/pipeline/aa", "%saa is not post", "");
    else
        set(&p, SOL_FX_POST_AA, 1, "/pipeline/aa", "%saa is post", "");

    if (pl->culling == 0)
        set(&p, SOL_FX_CULLING, 0, "/pipeline/culling", "%sculling is off", "");
    else if (boxes == 0)
        set(&p, SOL_FX_CULLING, 0, "/objects", "%sno boxes to cull", "");
    else if (pl->culling < 0 && boxes < 8)
        set(&p, SOL_FX_CULLING, 0, "/objects", "%sfewer than 8 boxes (culling auto)", "");
    else
        set(&p, SOL_FX_CULLING, 1, "/objects", "%s", pl->culling > 0 ? "culling is on" : ">= 8 boxes (culling auto)");

    if (!pl->has_look)
        set(&p, SOL_FX_LUT_GRADING, 0, "/pipeline/look", "%sno look", "");
    else
        set(&p, SOL_FX_LUT_GRADING, 1, "/pipeline/look", "%sa look is set", "");

    int env = -1;
    for (int l = 0; l < s->light_count && env < 0; ++l)
        if (s->lights[l].kind == SOL_LIGHT_ENV && s->lights[l].env_image.data)
            env = l;
    if (env < 0)
        set(&p, SOL_FX_ENV_SG, 0, "", "%sno environment light with a lat-long map", "");
    else if (!drawable)
        set(&p, SOL_FX_ENV_SG, 0, "", "%sthe scene has no geometry", "");
    else {
        snprintf(ptr, sizeof ptr, "/lights/%d/file", env);
        set(&p, SOL_FX_ENV_SG, 1, ptr, "lat-long environment %.120s", s->lights[env].env_file);
    }

    *out = p;
    return SOL_OK;
}
