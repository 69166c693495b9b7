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

/* A triangle mesh in world space with its BVH (scene_mesh.c). */
typedef struct sol_mesh sol_mesh;
struct sol_mesh {
    int tri_count;
    float *v;     /* tri_count * 9 positions */
    float *n;     /* tri_count * 9 vertex normals (zero: use the face normal) */
    float *color; /* tri_count * 3 base colours (linear) */
    float *uv;    /* tri_count * 6 texture coordinates (first UV channel, assimp's convention:
                     v up, KHR_texture_transform / UV transforms already applied) */
    int *tri_tex; /* tri_count base-colour texture indices into tex, -1 = none */
    int tex_count;
    sol_image *tex; /* base-colour textures (PNG files next to the model), sRGB codes in [0,1] */
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
void sol_mesh_free(sol_mesh *mesh);
/* Closest hit along o + t d, t in (0, tmax): t, shading normal (unit), base colour (the colour
 * factor times the sRGB-decoded base-colour texture, bilinear with repeat, where it has one). */
int sol_mesh_intersect(const sol_mesh *mesh, const double o[3], const double d[3], double tmax, double *t,
                       double n[3], double color[3]);

#endif
