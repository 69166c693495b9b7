/* scene_mesh.c - meshes imported through assimp's C API (glTF 2.0, OBJ, ...) and a BVH to ray
 * cast them.
 *
 * Import: every mesh of every node, with the node transforms applied (world-space triangles),
 * vertex normals (assimp generates smooth ones where the file has none), the material's base
 * colour factor (glTF pbrMetallicRoughness.baseColorFactor, else the diffuse colour), the first
 * camera and the punctual lights (KHR_lights_punctual). A file assimp cannot read, or whose
 * vertices are not finite, or that holds no triangle, is rejected with assimp's message.
 * Base-colour textures (glTF baseColorTexture, else the diffuse texture, e.g. OBJ map_Kd) that are
 * PNG files beside the model are loaded and sampled with the first UV channel; assimp's
 * aiProcess_TransformUVCoords bakes KHR_texture_transform (offset, scale, rotation) into the UVs.
 * Embedded or non-PNG images, and normal textures, are not sampled (the colour factor is used). */
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

typedef struct builder {
    sol_mesh *m;
    const int *mat_tex; /* material -> index into m->tex, -1 = none */
    size_t cap;
    sol_status st;
    char msg[256];
} builder;

static void xform_point(const struct aiMatrix4x4 *t, const struct aiVector3D *v, float out[3])
{
    out[0] = t->a1 * v->x + t->a2 * v->y + t->a3 * v->z + t->a4;
    out[1] = t->b1 * v->x + t->b2 * v->y + t->b3 * v->z + t->b4;
    out[2] = t->c1 * v->x + t->c2 * v->y + t->c3 * v->z + t->c4;
}

/* Normals go through the inverse transpose; for the rigid and uniformly scaled transforms of
 * the test assets the upper 3x3 and a renormalisation give the same direction. */
static void xform_normal(const struct aiMatrix4x4 *t, const struct aiVector3D *v, float out[3])
{
    double n[3] = {t->a1 * v->x + t->a2 * v->y + t->a3 * v->z, t->b1 * v->x + t->b2 * v->y + t->b3 * v->z,
                   t->c1 * v->x + t->c2 * v->y + t->c3 * v->z};
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; ++i)
        out[i] = (float)(l > 0 ? n[i] / l : 0);
}

static void mat_mul(struct aiMatrix4x4 *out, const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b)
{
    const float *x = &a->a1, *y = &b->a1;
    float r[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            float s = 0;
            for (int k = 0; k < 4; ++k)
                s += x[4 * i + k] * y[4 * k + j];
            r[4 * i + j] = s;
        }
    memcpy(&out->a1, r, sizeof r);
}

static void add_node(builder *b, const struct aiScene *sc, const struct aiNode *node, const struct aiMatrix4x4 *parent,
                     int depth)
{
    if (b->st != SOL_OK)
        return;
    if (depth > 64) {
        b->st = SOL_ERR_FORMAT;
        snprintf(b->msg, sizeof b->msg, "node hierarchy deeper than 64 levels");
        return;
    }
    struct aiMatrix4x4 t;
    mat_mul(&t, parent, &node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes && b->st == SOL_OK; ++k) {
        if (node->mMeshes[k] >= sc->mNumMeshes)
            continue;
        const struct aiMesh *mesh = sc->mMeshes[node->mMeshes[k]];
        float color[3] = {0.8f, 0.8f, 0.8f};
        int tex = -1;
        if (mesh->mMaterialIndex < sc->mNumMaterials && b->mat_tex && mesh->mTextureCoords[0])
            tex = b->mat_tex[mesh->mMaterialIndex];
        if (mesh->mMaterialIndex < sc->mNumMaterials) {
            struct aiColor4D c;
            const struct aiMaterial *mat = sc->mMaterials[mesh->mMaterialIndex];
            if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
                aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
                color[0] = c.r, color[1] = c.g, color[2] = c.b;
            }
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices != 3)
                continue; /* points and lines */
            if (b->m->tri_count >= SOL_MESH_MAX_TRIANGLES) {
                b->st = SOL_ERR_LIMIT;
                snprintf(b->msg, sizeof b->msg, "more than %d triangles", SOL_MESH_MAX_TRIANGLES);
                return;
            }
            if ((size_t)b->m->tri_count == b->cap) {
                size_t cap = b->cap ? 2 * b->cap : 1024;
                float *v = realloc(b->m->v, cap * 9 * sizeof *v);
                if (v)
                    b->m->v = v;
                float *n = v ? realloc(b->m->n, cap * 9 * sizeof *n) : NULL;
                if (n)
                    b->m->n = n;
                float *c = n ? realloc(b->m->color, cap * 3 * sizeof *c) : NULL;
                if (c)
                    b->m->color = c;
                float *uv = c ? realloc(b->m->uv, cap * 6 * sizeof *uv) : NULL;
                if (uv)
                    b->m->uv = uv;
                int *tt = uv ? realloc(b->m->tri_tex, cap * sizeof *tt) : NULL;
                if (!tt) {
                    b->st = SOL_ERR_NO_MEMORY;
                    snprintf(b->msg, sizeof b->msg, "out of memory");
                    return;
                }
                b->m->tri_tex = tt;
                b->cap = cap;
            }
            size_t tri = (size_t)b->m->tri_count;
            for (int corner = 0; corner < 3; ++corner) {
                unsigned idx = face->mIndices[corner];
                if (idx >= mesh->mNumVertices) {
                    b->st = SOL_ERR_FORMAT;
                    snprintf(b->msg, sizeof b->msg, "mesh \"%.60s\": vertex index %u out of range (%u vertices)",
                             mesh->mName.data, idx, mesh->mNumVertices);
                    return;
                }
                const struct aiVector3D *p = &mesh->mVertices[idx];
                if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                    b->st = SOL_ERR_NONFINITE;
                    snprintf(b->msg, sizeof b->msg, "mesh \"%.60s\": vertex %u is not finite", mesh->mName.data, idx);
                    return;
                }
                xform_point(&t, p, &b->m->v[tri * 9 + 3 * corner]);
                float *uv = &b->m->uv[tri * 6 + 2 * corner];
                uv[0] = uv[1] = 0;
                if (tex >= 0 && isfinite(mesh->mTextureCoords[0][idx].x) && isfinite(mesh->mTextureCoords[0][idx].y)) {
                    uv[0] = mesh->mTextureCoords[0][idx].x;
                    uv[1] = mesh->mTextureCoords[0][idx].y;
                }
                if (mesh->mNormals && isfinite(mesh->mNormals[idx].x))
                    xform_normal(&t, &mesh->mNormals[idx], &b->m->n[tri * 9 + 3 * corner]);
                else
                    memset(&b->m->n[tri * 9 + 3 * corner], 0, 3 * sizeof(float));
                for (int i = 0; i < 3; ++i)
                    if (!isfinite(b->m->v[tri * 9 + 3 * corner + i])) {
                        b->st = SOL_ERR_NONFINITE;
                        snprintf(b->msg, sizeof b->msg, "node transform makes a vertex non-finite");
                        return;
                    }
            }
            memcpy(&b->m->color[tri * 3], color, sizeof color);
            b->m->tri_tex[tri] = tex;
            b->m->tri_count++;
        }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c)
        add_node(b, sc, node->mChildren[c], &t, depth + 1);
}

/* The global transform of a named node (cameras and lights are placed by their nodes). */
static int find_node(const struct aiNode *node, const char *name, const struct aiMatrix4x4 *parent,
                     struct aiMatrix4x4 *out, int depth)
{
    struct aiMatrix4x4 t;
    mat_mul(&t, parent, &node->mTransformation);
    if (!strcmp(node->mName.data, name)) {
        *out = t;
        return 1;
    }
    for (unsigned c = 0; c < node->mNumChildren && depth < 64; ++c)
        if (find_node(node->mChildren[c], name, &t, out, depth + 1))
            return 1;
    return 0;
}

/* ---- BVH: median split on the longest axis of the centroids, leaves of <= 4 triangles ---- */

static void tri_bounds(const sol_mesh *m, int t, float lo[3], float hi[3])
{
    for (int i = 0; i < 3; ++i) {
        lo[i] = fminf(fminf(m->v[t * 9 + i], m->v[t * 9 + 3 + i]), m->v[t * 9 + 6 + i]);
        hi[i] = fmaxf(fmaxf(m->v[t * 9 + i], m->v[t * 9 + 3 + i]), m->v[t * 9 + 6 + i]);
    }
}

static const sol_mesh *sort_mesh;
static int sort_axis;
static int by_centroid(const void *a, const void *b)
{
    int ta = *(const int *)a, tb = *(const int *)b;
    const float *v = sort_mesh->v;
    float ca = v[ta * 9 + sort_axis] + v[ta * 9 + 3 + sort_axis] + v[ta * 9 + 6 + sort_axis];
    float cb = v[tb * 9 + sort_axis] + v[tb * 9 + 3 + sort_axis] + v[tb * 9 + 6 + sort_axis];
    return ca < cb ? -1 : ca > cb ? 1 : ta - tb;
}

static int build_node(sol_mesh *m, int first, int count)
{
    int id = m->node_count++;
    sol_mesh_node *nd = &m->nodes[id];
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = first; i < first + count; ++i) {
        float a[3], b[3];
        tri_bounds(m, m->tri_index[i], a, b);
        for (int k = 0; k < 3; ++k)
            lo[k] = fminf(lo[k], a[k]), hi[k] = fmaxf(hi[k], b[k]);
    }
    memcpy(nd->lo, lo, sizeof lo);
    memcpy(nd->hi, hi, sizeof hi);
    if (count <= 4) {
        nd->first = first;
        nd->count = count;
        return id;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (hi[k] - lo[k] > hi[axis] - lo[axis])
            axis = k;
    sort_mesh = m; /* import runs single-threaded */
    sort_axis = axis;
    qsort(m->tri_index + first, (size_t)count, sizeof(int), by_centroid);
    int half = count / 2;
    nd->count = 0;
    int left = build_node(m, first, half);
    (void)left; /* the left child is id + 1 */
    int right = build_node(m, first + half, count - half);
    m->nodes[id].first = right;
    return id;
}

void sol_mesh_free(sol_mesh *m)
{
    if (!m)
        return;
    free(m->v);
    free(m->n);
    free(m->color);
    free(m->uv);
    free(m->tri_tex);
    for (int i = 0; i < m->tex_count; ++i)
        sol_image_free(&m->tex[i]);
    free(m->tex);
    free(m->nodes);
    free(m->tri_index);
    free(m->lights);
    memset(m, 0, sizeof *m);
}

/* assimp repairs some broken files silently (it drops faces whose indices are out of range and
 * says so only in its log): its log is read during the import, and a repair rejects the file. The
 * log stream is global state of assimp, so imports are serialised. */
static char import_warning[256];
static void import_log(const char *message, char *user)
{
    (void)user;
    if (!import_warning[0] && strstr(message, "out-of-range"))
        snprintf(import_warning, sizeof import_warning, "%s", message);
}

static int ends_with_png(const char *s)
{
    size_t n = strlen(s);
    return n >= 4 && (!strcmp(s + n - 4, ".png") || !strcmp(s + n - 4, ".PNG"));
}

/* Each material's base-colour texture (glTF baseColorTexture, else the diffuse one), when it is a
 * PNG file beside the model that sol_png_read reads (an unreadable one is skipped: the colour
 * factor stays, as for embedded or JPEG images). *mat_tex[i] = index into m->tex or -1. Only
 * SOL_ERR_NO_MEMORY fails. */
static sol_status load_textures(const struct aiScene *sc, const char *model, sol_mesh *m, int **mat_tex)
{
    *mat_tex = NULL;
    if (sc->mNumMaterials == 0)
        return SOL_OK;
    int *mt = malloc(sizeof *mt * sc->mNumMaterials);
    m->tex = calloc(sc->mNumMaterials, sizeof *m->tex);
    if (!mt || !m->tex) {
        free(mt);
        return SOL_ERR_NO_MEMORY;
    }
    const char *slash = strrchr(model, '/');
    int dir_len = slash ? (int)(slash - model) : 1;
    const char *dir = slash ? model : ".";
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) {
        mt[i] = -1;
        struct aiString name;
        if (aiGetMaterialTexture(sc->mMaterials[i], aiTextureType_BASE_COLOR, 0, &name, NULL, NULL, NULL, NULL, NULL,
                                 NULL) != aiReturn_SUCCESS &&
            aiGetMaterialTexture(sc->mMaterials[i], aiTextureType_DIFFUSE, 0, &name, NULL, NULL, NULL, NULL, NULL,
                                 NULL) != aiReturn_SUCCESS)
            continue;
        if (name.data[0] == '*' || name.data[0] == '/' || strstr(name.data, "..") || !ends_with_png(name.data))
            continue; /* embedded, outside the model's folder, or not PNG */
        char file[SOL_SCENE_PATH_MAX];
        int len = snprintf(file, sizeof file, "%.*s/%s", dir_len, dir, name.data);
        if (len < 0 || (size_t)len >= sizeof file)
            continue;
        sol_image img;
        int bits;
        if (sol_png_read(file, &img, &bits) != SOL_OK)
            continue;
        if (img.channels < 3) {
            sol_image_free(&img);
            continue;
        }
        m->tex[m->tex_count] = img;
        mt[i] = m->tex_count++;
    }
    *mat_tex = mt;
    return SOL_OK;
}

/* Bilinear sample with repeat of a base-colour texture at (u, v) (v up, row 0 at the top), sRGB
 * decoded to linear. */
static void tex_lookup(const sol_image *im, double u, double v, double out[3])
{
    double x = (u - floor(u)) * im->width - 0.5, y = (1 - (v - floor(v))) * im->height - 0.5;
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            int xi = ((x0 + i) % im->width + im->width) % im->width;
            int yi = ((y0 + j) % im->height + im->height) % im->height;
            double w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            const float *px = &im->data[((size_t)yi * (size_t)im->width + (size_t)xi) * (size_t)im->channels];
            for (int c = 0; c < 3; ++c)
                out[c] += w * sol_srgb_decode(px[c]);
        }
}

sol_status sol_mesh_load(const char *path, sol_mesh *out, char *message, size_t message_size)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    const struct aiScene *sc;
    char warning[256];
#pragma omp critical(sol_assimp_import)
    {
        struct aiLogStream stream = {import_log, NULL};
        import_warning[0] = 0;
        aiAttachLogStream(&stream);
        sc = aiImportFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals | aiProcess_ValidateDataStructure |
                                    aiProcess_SortByPType | aiProcess_TransformUVCoords);
        aiDetachLogStream(&stream);
        memcpy(warning, import_warning, sizeof warning);
    }
    if (sc && warning[0]) {
        size_t n = strcspn(warning, "\n");
        warning[n] = 0;
        const char *w = strstr(warning, ": ");
        if (message)
            snprintf(message, message_size, "assimp repaired the file: %.200s", w ? w + 2 : warning);
        aiReleaseImport(sc);
        return SOL_ERR_FORMAT;
    }
    if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        if (message)
            snprintf(message, message_size, "assimp cannot import it: %.200s",
                     sc ? "incomplete scene" : aiGetErrorString());
        if (sc)
            aiReleaseImport(sc);
        return SOL_ERR_FORMAT;
    }
    sol_mesh m;
    memset(&m, 0, sizeof m);
    int *mat_tex = NULL;
    sol_status tst = load_textures(sc, path, &m, &mat_tex);
    builder b = {&m, mat_tex, 0, tst, ""};
    if (tst != SOL_OK)
        snprintf(b.msg, sizeof b.msg, "out of memory");
    struct aiMatrix4x4 id = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    add_node(&b, sc, sc->mRootNode, &id, 0);
    free(mat_tex);
    if (b.st == SOL_OK && m.tri_count == 0) {
        b.st = SOL_ERR_FORMAT;
        snprintf(b.msg, sizeof b.msg, "no triangles");
    }
    if (b.st == SOL_OK && sc->mNumCameras > 0) { /* the first camera, placed by its node */
        const struct aiCamera *c = sc->mCameras[0];
        struct aiMatrix4x4 t;
        if (find_node(sc->mRootNode, c->mName.data, &id, &t, 0)) {
            struct aiVector3D p = c->mPosition, l = {c->mPosition.x + c->mLookAt.x, c->mPosition.y + c->mLookAt.y,
                                                      c->mPosition.z + c->mLookAt.z};
            float pw[3], lw[3], uw[3];
            xform_point(&t, &p, pw);
            xform_point(&t, &l, lw);
            xform_normal(&t, &c->mUp, uw);
            /* assimp stores HALF the horizontal field of view; sol wants the full vertical one */
            double fov = c->mHorizontalFOV > 0 ? 2 * atan(tan(c->mHorizontalFOV) / (c->mAspect > 0 ? c->mAspect : 1.7778)) : 1.0;
            for (int i = 0; i < 3; ++i) {
                m.cam_pos[i] = pw[i];
                m.cam_look[i] = lw[i];
                m.cam_up[i] = uw[i];
            }
            m.cam_fov_deg = fov * 180 / M_PI;
            m.has_camera = isfinite(m.cam_fov_deg) && m.cam_fov_deg > 0 && m.cam_fov_deg < 179;
        }
    }
    if (b.st == SOL_OK && sc->mNumLights > 0) { /* KHR_lights_punctual */
        m.lights = calloc(sc->mNumLights, sizeof *m.lights);
        for (unsigned i = 0; m.lights && i < sc->mNumLights && i < 64; ++i) {
            const struct aiLight *l = sc->mLights[i];
            struct aiMatrix4x4 t;
            if (!find_node(sc->mRootNode, l->mName.data, &id, &t, 0))
                continue;
            sol_mesh_light *ml = &m.lights[m.light_count];
            float p[3], d[3];
            xform_point(&t, &l->mPosition, p);
            xform_normal(&t, &l->mDirection, d);
            ml->kind = l->mType == aiLightSource_DIRECTIONAL ? 0 : l->mType == aiLightSource_SPOT ? 2 : 1;
            for (int k = 0; k < 3; ++k)
                ml->position[k] = p[k], ml->direction[k] = d[k];
            ml->color[0] = l->mColorDiffuse.r, ml->color[1] = l->mColorDiffuse.g, ml->color[2] = l->mColorDiffuse.b;
            ml->cone_deg = l->mAngleOuterCone > 0 ? l->mAngleOuterCone * 180 / M_PI : 30;
            m.light_count++;
        }
    }
    aiReleaseImport(sc);
    if (b.st == SOL_OK) {
        m.tri_index = malloc(sizeof(int) * (size_t)m.tri_count);
        m.nodes = malloc(sizeof(sol_mesh_node) * (size_t)(2 * m.tri_count));
        if (!m.tri_index || !m.nodes) {
            b.st = SOL_ERR_NO_MEMORY;
            snprintf(b.msg, sizeof b.msg, "out of memory");
        } else {
            for (int i = 0; i < m.tri_count; ++i)
                m.tri_index[i] = i;
            build_node(&m, 0, m.tri_count);
            for (int k = 0; k < 3; ++k) {
                m.bmin[k] = m.nodes[0].lo[k];
                m.bmax[k] = m.nodes[0].hi[k];
            }
        }
    }
    if (b.st != SOL_OK) {
        if (message)
            snprintf(message, message_size, "%s", b.msg);
        sol_mesh_free(&m);
        return b.st;
    }
    *out = m;
    return SOL_OK;
}

/* Moller-Trumbore against one triangle. */
static int hit_triangle(const sol_mesh *m, int t, const double o[3], const double d[3], double tmax, double *t_out,
                        double *u_out, double *v_out)
{
    const float *p = &m->v[(size_t)t * 9];
    double e1[3], e2[3], s[3], pv[3], qv[3];
    for (int i = 0; i < 3; ++i) {
        e1[i] = p[3 + i] - p[i];
        e2[i] = p[6 + i] - p[i];
        s[i] = o[i] - p[i];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1], pv[1] = d[2] * e2[0] - d[0] * e2[2], pv[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (fabs(det) < 1e-18)
        return 0;
    double inv = 1 / det, u = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) * inv;
    if (u < 0 || u > 1)
        return 0;
    qv[0] = s[1] * e1[2] - s[2] * e1[1], qv[1] = s[2] * e1[0] - s[0] * e1[2], qv[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) * inv;
    if (v < 0 || u + v > 1)
        return 0;
    double tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
    if (!(tt > 1e-6 && tt < tmax))
        return 0;
    *t_out = tt, *u_out = u, *v_out = v;
    return 1;
}

static int box_hit(const sol_mesh_node *nd, const double o[3], const double inv[3], double tmax)
{
    double t0 = 0, t1 = tmax;
    for (int i = 0; i < 3; ++i) {
        double a = (nd->lo[i] - o[i]) * inv[i], b = (nd->hi[i] - o[i]) * inv[i];
        if (a > b) {
            double x = a;
            a = b;
            b = x;
        }
        t0 = a > t0 ? a : t0;
        t1 = b < t1 ? b : t1;
        if (t0 > t1)
            return 0;
    }
    return 1;
}

int sol_mesh_intersect(const sol_mesh *m, const double o[3], const double d[3], double tmax, double *t_out,
                       double n[3], double color[3])
{
    double inv[3] = {1 / d[0], 1 / d[1], 1 / d[2]};
    int stack[128], sp = 0, best = -1;
    double bu = 0, bv = 0;
    stack[sp++] = 0;
    while (sp) {
        const sol_mesh_node *nd = &m->nodes[stack[--sp]];
        if (!box_hit(nd, o, inv, tmax))
            continue;
        if (nd->count > 0) {
            for (int i = nd->first; i < nd->first + nd->count; ++i) {
                double t, u, v;
                if (hit_triangle(m, m->tri_index[i], o, d, tmax, &t, &u, &v)) {
                    tmax = t;
                    best = m->tri_index[i];
                    bu = u, bv = v;
                }
            }
        } else if (sp + 2 <= 128) {
            stack[sp++] = nd->first;                  /* right child */
            stack[sp++] = (int)(nd - m->nodes) + 1;   /* left child */
        }
    }
    if (best < 0)
        return 0;
    const float *p = &m->v[(size_t)best * 9], *vn = &m->n[(size_t)best * 9];
    double e1[3], e2[3], s = 0;
    for (int i = 0; i < 3; ++i) {
        e1[i] = p[3 + i] - p[i];
        e2[i] = p[6 + i] - p[i];
        n[i] = (1 - bu - bv) * vn[i] + bu * vn[3 + i] + bv * vn[6 + i];
        s += n[i] * n[i];
    }
    if (!(s > 1e-12)) { /* no vertex normals: the face normal */
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        s = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    }
    s = sqrt(s);
    for (int i = 0; i < 3; ++i)
        n[i] /= s;
    for (int i = 0; i < 3; ++i)
        color[i] = m->color[(size_t)best * 3 + i];
    int tx = m->tri_tex ? m->tri_tex[best] : -1;
    if (tx >= 0 && tx < m->tex_count) {
        const float *uv = &m->uv[(size_t)best * 6];
        double c[3], w0 = 1 - bu - bv;
        tex_lookup(&m->tex[tx], w0 * uv[0] + bu * uv[2] + bv * uv[4], w0 * uv[1] + bu * uv[3] + bv * uv[5], c);
        for (int i = 0; i < 3; ++i)
            color[i] *= c[i];
    }
    *t_out = tmax;
    return 1;
}
