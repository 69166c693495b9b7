/* scene_internal.h - what the scene module's files share (not public API). */
#ifndef SOL_SCENE_INTERNAL_H
#define SOL_SCENE_INTERNAL_H

#include "sol_scene.h"

#define SOL_MESH_MAX_TRIANGLES (1 << 24)

typedef struct sol_mesh_node {
    float lo[3], hi[3];
    int first; /* leaf: first index into tri_index; interior: the right child (left is this + 1) */
    int count; /* leaf: triangles (> 0); interior: 0 */
} sol_mesh_node;

typedef struct sol_mesh_light {
    int kind; /* 0 sun, 1 point, 2 spot */
    double position[3], direction[3], color[3], cone_deg;
} sol_mesh_light;

/* A texture of a model: a PNG file beside it, as read (codes in [0,1]). */
typedef struct sol_mesh_texture {
    sol_image image;
    int bits;        /* 8 or 16 */
    int normal;      /* 1: a tangent-space normal texture (glTF normalTexture), 0: base colour (sRGB) */
    int material;    /* the model's material it belongs to */
    char name[128];  /* the file name as the model gives it */
} sol_mesh_texture;

/* A material of a model (glTF: materials[i]; assimp keeps the file's order). */
typedef struct sol_mesh_material {
    char name[64];
    int base_tex, normal_tex; /* indices into sol_mesh.tex, -1 = none */
    /* glTF normalTexture.scale (default 1): the sampled tangent-space normal's x and y are
     * multiplied by it before renormalising (glTF 2.0 spec, material.normalTextureInfo) */
    double normal_scale;
    /* KHR_materials_anisotropy (read from the .gltf JSON, scene_mesh.c): alpha = roughness^2,
     * strength and rotation (radians, from the tangent towards the bitangent) */
    int aniso;
    double alpha, aniso_strength, aniso_rotation;
    int aniso_texture; /* the material names an anisotropyTexture (not sampled) */
} sol_mesh_material;

/* A triangle mesh in world space with its BVH (scene_mesh.c). */
typedef struct sol_mesh sol_mesh;
struct sol_mesh {
    int tri_count;
    float *v;     /* tri_count * 9 positions */
    float *n;     /* tri_count * 9 vertex normals (zero: use the face normal) */
    float *color; /* tri_count * 3 base colours (linear) */
    float *uv;    /* tri_count * 6 texture coordinates (first UV channel, assimp's convention:
                     v up, KHR_texture_transform / UV transforms already applied) */
    float *tan;   /* tri_count * 18: per corner tangent and bitangent (assimp's
                     aiProcess_CalcTangentSpace, along +u and +v); zero where the mesh has none */
    int *tri_mat; /* tri_count material indices into mats, -1 = none */
    int mat_count;
    sol_mesh_material *mats;
    int tex_count;
    sol_mesh_texture *tex; /* base-colour and normal textures (PNG files next to the model) */
    int node_count;
    sol_mesh_node *nodes;
    int *tri_index;
    double bmin[3], bmax[3];
    int has_camera;
    double cam_pos[3], cam_look[3], cam_up[3], cam_fov_deg;
    int light_count;
    sol_mesh_light *lights;
};

/* Imports a model file through assimp; `message` receives the reason on failure. */
sol_status sol_mesh_load(const char *path, sol_mesh *out, char *message, size_t message_size);
/* KHR_materials_anisotropy of the first m->mat_count materials of a glTF JSON document (json need
 * not be NUL-terminated): sets aniso, aniso_strength, aniso_rotation, alpha and aniso_texture of
 * each material that has the extension. SOL_OK also when the JSON does not parse (no extension);
 * SOL_ERR_FORMAT / SOL_ERR_NONFINITE / SOL_ERR_OUT_OF_RANGE with msg naming the JSON pointer. */
sol_status sol_mesh_read_anisotropy_json(const char *json, size_t json_len, sol_mesh *m, char *msg, size_t msg_size);
void sol_mesh_free(sol_mesh *mesh);
/* What a ray hit: t, the interpolated shading normal (unit), the base colour factor (linear), the
 * texture coordinates, the interpolated tangent and bitangent (zero when the mesh has none) and
 * the triangle's material (-1 = none). Textures are sampled by the renderer (scene_render.c),
 * after the planned effects prepared them. */
typedef struct sol_mesh_hit {
    double t, n[3], color[3], uv[2], tangent[3], bitangent[3];
    int material;
} sol_mesh_hit;

/* Closest hit along o + t d, t in (0, tmax). */
int sol_mesh_intersect(const sol_mesh *mesh, const double o[3], const double d[3], double tmax, sol_mesh_hit *hit);

#endif
