/* sol_scene.h - scene files, the effect graph and the two-path renderer (issue 9).
 *
 * The scene layer sits ABOVE the technique modules: it reads a scene description (JSON, parsed
 * with Debian's libcjson), decides which of the talk's techniques the scene calls for (the effect
 * graph, sol_scene_plan) and renders it through a reference path and an engine path. No technique
 * module includes this header.
 *
 * The file format, every field, its default and an example are documented in
 * docs/scene-format.md; the limits and checks below are the ones that page states.
 *
 * Errors: every loader reports, besides the sol_status, a sol_scene_error naming the file and the
 * offending field as a JSON pointer (RFC 6901, e.g. "/materials/2/roughness/0"), and a message.
 * Non-finite or out-of-range values are rejected at load time, before anything is rendered.
 * Conventions as in sol_core.h (statuses, untouched outputs on error, no printing).
 */
#ifndef SOL_SCENE_H
#define SOL_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits of one scene (checked at load; more gives SOL_ERR_LIMIT). */
#define SOL_SCENE_MAX_FILE_BYTES ((size_t)16 << 20) /* 16 MiB of JSON */
#define SOL_SCENE_MAX_ITEMS 4096                    /* objects, materials, lights, frames, lobes each */
#define SOL_SCENE_MAX_PIXELS (8192 * 8192)          /* camera width * height */
#define SOL_SCENE_ENV_MAX_PIXELS (1 << 25)          /* lat-long environment EXR: 8192 x 4096 */
#define SOL_SCENE_NAME_MAX 64
#define SOL_SCENE_PATH_MAX 1024

typedef struct sol_scene_error {
    char file[SOL_SCENE_PATH_MAX]; /* the file at fault (scene, or a texture it names) */
    char pointer[256];             /* JSON pointer of the field ("" = the document itself) */
    char message[256];             /* what is wrong, e.g. "must be > 0 (got -0.2)" */
    int line;                      /* 1-based line of a JSON syntax error, else 0 */
} sol_scene_error;

/* ---- camera ---- */
typedef struct sol_scene_camera {
    double position[3], look_at[3], up[3]; /* defaults (0,1,-5), (0,0,0), (0,1,0) */
    double fov_deg;                        /* vertical field of view, (0, 179]; default 60 */
    int width, height;                     /* default 960 x 540 */
    double znear, zfar;                    /* default 0.05, 1000 */
    int frame_count;                       /* camera path: 0 = a still camera */
    double (*frames)[3];                   /* frame_count positions (the path translates the camera) */
} sol_scene_camera;

/* ---- materials ---- */
typedef enum sol_texture_source { SOL_TEX_NONE = 0, SOL_TEX_FILE, SOL_TEX_CHECKER, SOL_TEX_BUMPS } sol_texture_source;

typedef struct sol_scene_texture {
    sol_texture_source source;
    char file[SOL_SCENE_PATH_MAX]; /* resolved path (relative names are relative to the scene file) */
    int bits;                      /* storage bits 8 or 16 (default 8) */
    int linear;                    /* storage transfer: 0 = sRGB (gamma), 1 = linear (default 0 for
                                      albedo, 1 for normal maps) */
    double scale;                  /* texture repeats per unit (default 1) */
    double low[3], high[3];        /* checker: the two albedos (linear); bumps: amplitude in low[0] */
    sol_image image;               /* loaded pixels (SOL_TEX_FILE), or empty */
} sol_scene_texture;

typedef enum sol_aniso_model { SOL_ANISO_NONE = 0, SOL_ANISO_WARD, SOL_ANISO_GGX } sol_aniso_model;

typedef struct sol_scene_material {
    char name[SOL_SCENE_NAME_MAX];
    double albedo[3];      /* linear diffuse albedo in [0,1]; default 0.5 grey */
    double specular;       /* specular reflectance (F0) in [0,1]; default 0.04 */
    double gloss;          /* in [0,1]; Phong exponent = 2^(13 gloss) (default gloss 0.5) */
    double phong_exponent; /* > 0 overrides gloss; 0 = derived from gloss */
    sol_aniso_model aniso; /* anisotropic roughness pair (Ward or GGX), or none */
    double roughness[2];   /* alpha_x, alpha_y in [1e-3, 10] */
    double tangent[3];     /* world direction of alpha_x's axis; default (1,0,0) */
    sol_scene_texture albedo_texture;
    sol_scene_texture normal_map;
} sol_scene_material;

/* ---- geometry ---- */
typedef enum sol_geom_kind { SOL_GEOM_PLANE = 0, SOL_GEOM_BOX, SOL_GEOM_SPHERE, SOL_GEOM_HEIGHTFIELD,
                             SOL_GEOM_MESH } sol_geom_kind;

struct sol_mesh;

typedef struct sol_scene_object {
    sol_geom_kind kind;
    int material;      /* index into materials */
    double a[3], b[3]; /* plane: point, normal; box: min, max; sphere: centre, -; heightfield:
                          origin (min x, base y, min z), size (x extent, amplitude, z extent) */
    double radius;     /* sphere radius (> 0); plane half extent (0 = infinite); heightfield frequency */
    char file[SOL_SCENE_PATH_MAX]; /* mesh file (glTF 2.0 / OBJ) */
    struct sol_mesh *mesh;         /* the imported triangles (owned by the scene) */
} sol_scene_object;

/* ---- lights ---- */
typedef enum sol_light_kind { SOL_LIGHT_SUN = 0, SOL_LIGHT_POINT, SOL_LIGHT_SPOT, SOL_LIGHT_ENV } sol_light_kind;

typedef struct sol_scene_sg_lobe {
    double axis[3], sharpness, amplitude[3];
} sol_scene_sg_lobe;

typedef struct sol_scene_light {
    sol_light_kind kind;
    double color[3];     /* linear RGB, >= 0; default (1,1,1) */
    double intensity;    /* >= 0; default 1 */
    double position[3];  /* point / spot */
    double direction[3]; /* sun: direction the light travels; spot: axis */
    double radius;       /* point / spot: range of influence (> 0; default 10) */
    double cone_deg;     /* spot: half angle in (0, 90); default 30 */
    int shadows;         /* 1: shadowed in the engine path too; default 0 (unshadowed deferred light) */
    int clip;            /* index into clip_volumes, -1 = none */
    char env_file[SOL_SCENE_PATH_MAX]; /* environment: lat-long EXR, or "" with lobes */
    sol_image env_image;
    int lobe_count;
    sol_scene_sg_lobe *lobes;
} sol_scene_light;

typedef struct sol_scene_clip {
    double min[3], max[3]; /* world-space box the light may reach */
} sol_scene_clip;

/* ---- pipeline settings (the talk's knobs) ---- */
typedef enum sol_light_buffer { SOL_LB_FLOAT = 0, SOL_LB_R11G11B10F, SOL_LB_RGBM, SOL_LB_RGB10 } sol_light_buffer;
typedef enum sol_aa_mode { SOL_AA_NONE = 0, SOL_AA_POST, SOL_AA_TEMPORAL } sol_aa_mode;
typedef enum sol_codec_choice { SOL_CODEC_AUTO = 0, SOL_CODEC_NONE, SOL_CODEC_BC } sol_codec_choice;

typedef struct sol_scene_pipeline {
    int gbuffer_normals;       /* sol_normal_method, or -1 = float (no encoding); default best fit */
    sol_codec_choice normal_map_codec; /* auto = BC5 (3Dc) */
    int normal_map_encoder;    /* sol_bc5_encoder; default common */
    sol_codec_choice albedo_codec;     /* auto = BC1 */
    int albedo_renormalize;    /* default 1 */
    int albedo_storage;        /* -1 auto (sol_storage_classify), 0 gamma, 1 linear; default -1 */
    sol_light_buffer light_buffer; /* default R11G11B10F */
    double light_range;        /* RGBM range; default 8 */
    int range_scaling;         /* scale the light buffer by the exposure (D9/D10); default 1 */
    int tonemap;               /* sol_tonemap; default filmic-hbd */
    double exposure;           /* multiplier before the tone map, > 0; default 1 */
    int lut_size;              /* 2..64; default 16; used when a look is set */
    int has_look;
    double look_saturation, look_contrast, look_hue_deg, look_gain[3];
    int ssao;                  /* default 0 */
    double ssao_radius;        /* default 0.5 */
    int ssao_samples;          /* default 4 */
    int ssao_half_res;         /* default 1 */
    sol_aa_mode aa;            /* default none */
    int culling;               /* -1 auto (on with >= 8 boxes), 0 off, 1 on */
    int reference_supersample; /* samples per pixel side of the reference path; default 3 */
    int sg_lobes;              /* lobes of the Ward-to-SG fit (D15); default 4 */
    int env_lobes;             /* SG lobes a lat-long environment is fitted with (env-sg); default 24 */
} sol_scene_pipeline;

typedef struct sol_scene {
    char path[SOL_SCENE_PATH_MAX];
    char name[SOL_SCENE_NAME_MAX];
    sol_scene_camera camera;
    int material_count, object_count, light_count, clip_count;
    sol_scene_material *materials;
    sol_scene_object *objects;
    sol_scene_light *lights;
    sol_scene_clip *clips;
    double ambient[3]; /* constant ambient light (linear RGB), default (0.03,0.03,0.03) */
    sol_scene_pipeline pipeline;
} sol_scene;

/* Parses a scene from `text` (len bytes, need not be NUL-terminated). `path` names the document in
 * errors and is the base of relative texture/mesh names (NULL: "<memory>", base "."). Textures named
 * by files are loaded (PNG 8/16-bit, EXR) and must exist. Errors: SOL_ERR_NULL_ARG, SOL_ERR_FORMAT
 * (JSON syntax, wrong type, unknown name), SOL_ERR_NONFINITE (NaN/Inf number or a number that does
 * not fit a double), SOL_ERR_INVALID_ARG / SOL_ERR_OUT_OF_RANGE (a value outside its domain), SOL_ERR_IO
 * (a texture/mesh file missing), SOL_ERR_LIMIT (too many items, too large), SOL_ERR_NO_MEMORY.
 * `err` (may be NULL) names the file and field. Free with sol_scene_free. */
sol_status sol_scene_parse(const char *text, size_t len, const char *path, sol_scene *out, sol_scene_error *err);
/* Reads the file (at most SOL_SCENE_MAX_FILE_BYTES) and parses it. A path ending in .gltf, .glb or
 * .obj is a model, not a scene file: it is imported through assimp (sol_scene_from_model). */
sol_status sol_scene_load(const char *path, sol_scene *out, sol_scene_error *err);
/* A scene around one model file imported through assimp's C API (glTF 2.0, OBJ): its meshes with
 * node transforms, base colours (times PNG base-colour textures), PNG normal textures and
 * KHR_materials_anisotropy (docs/scene-format.md, "Model materials"), its
 * first camera (else a camera framing the model's bounds), its
 * punctual lights (KHR_lights_punctual; else a sun and a sky lobe), every pipeline setting at its
 * default. A file assimp rejects, with non-finite vertices, or without triangles gives
 * SOL_ERR_FORMAT / SOL_ERR_NONFINITE with assimp's or sol's reason in err; a missing texture
 * SOL_ERR_IO naming it, a normal texture without RGB SOL_ERR_FORMAT, a bad anisotropy field
 * SOL_ERR_FORMAT / SOL_ERR_NONFINITE / SOL_ERR_OUT_OF_RANGE naming its JSON pointer. */
sol_status sol_scene_from_model(const char *path, sol_scene *out, sol_scene_error *err);
/* Frees everything the scene owns and zeroes it; safe on NULL or a zeroed scene. */
void sol_scene_free(sol_scene *scene);

/* ======================= the effect graph (scene_plan.c) =======================
 * Each effect is one of the talk's techniques already in sol. It declares what in a scene calls
 * for it (a scene element, named by JSON pointer in the plan), what it needs and what it
 * produces. sol_scene_plan decides, for a loaded scene, which effects run and why the others are
 * skipped; the renderer runs only the planned ones (sol_render_stats.effect_runs counts every
 * time an effect's code runs, so a test can prove a skipped effect never runs). */
typedef enum sol_effect {
    SOL_FX_GBUFFER_NORMALS = 0, /* D3-D7, S1, S5: 24-bit G-buffer normal encoding */
    SOL_FX_NORMAL_MAP_BC5,      /* T8-T14: normal maps through BC5 (3Dc) */
    SOL_FX_ALBEDO_STORAGE,      /* T3-T7: 8-bit albedo storage, gamma or linear by the T4 rule */
    SOL_FX_ALBEDO_BC1,          /* T1, T2: BC1 (DXT1) albedo, its 5:6:5 stage */
    SOL_FX_ALBEDO_RENORM,       /* T1, T2: per-channel range renormalisation of albedo */
    SOL_FX_LIGHT_BUFFER,        /* D9, S9: lossy light-accumulation buffer */
    SOL_FX_RANGE_SCALING,       /* D9, D10: light buffer pre-scaled by the exposure */
    SOL_FX_SG_LOBES,            /* D15, D16: anisotropic material as SG lobes -> principal Phong lobe */
    SOL_FX_CLIP_VOLUMES,        /* D13: stencil clip volume instead of a shadow */
    SOL_FX_SSAO,                /* M3: volumetric obscurance (half resolution, few samples) */
    SOL_FX_TEMPORAL,            /* D18 (and M3's temporal accumulation): reprojection over the camera path */
    SOL_FX_POST_AA,             /* D17: deviation-driven post-process AA */
    SOL_FX_CULLING,             /* M1: coverage-buffer occlusion culling */
    SOL_FX_LUT_GRADING,         /* M4: colour grading through a size^3 LUT */
    SOL_FX_ENV_SG,              /* D15, D16: a lat-long environment map as SG lighting lobes */
    SOL_FX_COUNT
} sol_effect;

typedef struct sol_effect_info {
    const char *name;     /* stable short name ("gbuffer-normals") */
    const char *claims;   /* claim IDs ("D3-D7, S1, S5") */
    const char *called_by;/* what in a scene calls for it */
    const char *needs;    /* what it consumes */
    const char *produces; /* what it produces */
    const char *reference;/* what the reference path does instead */
} sol_effect_info;

/* The static description of an effect; NULL for an out-of-range value. */
const sol_effect_info *sol_effect_get(sol_effect effect);

typedef struct sol_scene_plan {
    int run[SOL_FX_COUNT];             /* 1: the effect runs */
    char element[SOL_FX_COUNT][128];   /* run: JSON pointer of the scene element calling for it */
    char reason[SOL_FX_COUNT][160];    /* run: what that element is; skipped: why */
} sol_scene_plan;

/* Plans a loaded scene. Deterministic, cheap, no I/O. Errors: SOL_ERR_NULL_ARG. */
sol_status sol_scene_plan_build(const sol_scene *scene, sol_scene_plan *out);

/* ======================= the two-path renderer (scene_render.c) =======================
 * A small CPU deferred renderer, written to be read (pbrt-style): primary rays find the surface
 * of each pixel (the G-buffer pass: position, view depth, normal, albedo, gloss), a light loop
 * accumulates diffuse and specular light (the light buffer), composition multiplies by albedo and
 * adds ambient light times obscurance, then exposure, tone map (sol_hdr), grading, and AA.
 *  - reference path: float everywhere, no compression, exact Ward or anisotropic GGX BRDF, ray-traced visibility for
 *    clipped lights, converged obscurance, lat-long environments integrated exactly (irradiance
 *    table over the map's texels, importance-sampled specular; docs/scene-format.md),
 *    reference_supersample^2 samples per pixel.
 *  - engine path: one sample per pixel and every planned effect in the talk's format.
 * Attribution: the engine path with one effect swapped for its reference version
 * (options.reference_effects bit e) measures that effect's share of the error and of the time.
 * Deterministic and independent of the thread count (OpenMP over rows, no shared accumulation). */
typedef struct sol_render_options {
    int width, height;            /* 0: the camera's size */
    int reference;                /* nonzero: the reference path */
    unsigned reference_effects;   /* engine path: bit e set = effect e runs in its reference version */
} sol_render_options;

typedef struct sol_render_stats {
    uint64_t effect_runs[SOL_FX_COUNT]; /* how many times each effect's code ran (per texture, pass or frame) */
    uint64_t objects_culled;            /* culling: objects removed before the G-buffer pass */
    int frames;                         /* frames rendered (camera path) */
    double seconds;                     /* wall time of the frame(s): every pass after the textures */
    double cpu_seconds;                 /* processor time of the frame(s), all threads summed (clock()) */
    double prepare_seconds;             /* wall time of texture compression and fits (offline in an engine) */
} sol_render_stats;

typedef struct sol_render_result {
    sol_image hdr;     /* linear scene radiance (RGB, before exposure) */
    sol_image display; /* display image: sRGB-encoded RGB in [0,1] after tone map, grading, AA */
    sol_image normals; /* the normals lighting used at pixel centres (world space, 0 = background) */
} sol_render_result;

/* Renders a loaded scene along its plan (sol_scene_plan_build). out's images are allocated here
 * (free with sol_render_result_free); stats may be NULL. Tables that depend on no scene (the baked
 * best-fit normal table, the SG irradiance tables per lobe sharpness) are built by the first render
 * that needs them and kept for the process (thread-safe; a few MB at most), so later renders are
 * cheaper and identical to a first one.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (size < 1 or above SOL_SCENE_MAX_PIXELS),
 * SOL_ERR_NO_MEMORY, and the technique modules' errors (e.g. SOL_ERR_SOLVER from the Ward fit). */
sol_status sol_scene_render(const sol_scene *scene, const sol_scene_plan *plan, const sol_render_options *options,
                            sol_render_result *out, sol_render_stats *stats);
void sol_render_result_free(sol_render_result *result);

/* Image error of a render against a reference render of the same size: display-code (8-bit)
 * RMS and max over RGB, CIEDE2000 mean and max (sol_ciede2000 on the display images), and the
 * angle between the normals where both have a surface (degrees). The means are summed over 64 fixed
 * runs of pixels, then the runs in order, so the result is the same for any thread count.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (sizes differ). */
typedef struct sol_render_error {
    double rms_code, max_code;
    double de2000_mean, de2000_max;
    double normal_mean_deg, normal_max_deg;
} sol_render_error;
sol_status sol_render_compare(const sol_render_result *engine, const sol_render_result *reference,
                              sol_render_error *out);

#ifdef __cplusplus
}
#endif
#endif
