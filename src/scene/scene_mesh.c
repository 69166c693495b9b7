/* scene_mesh.c - meshes imported through assimp's C API (glTF 2.0, OBJ, ...) and a BVH to ray
 * cast them.
 *
 * Import: every mesh of every node, with the node transforms applied (world-space triangles),
 * vertex normals (assimp generates smooth ones where the file has none), the material's base
 * colour factor (glTF pbrMetallicRoughness.baseColorFactor, else the diffuse colour), the first
 * camera and the punctual lights (KHR_lights_punctual). A file assimp cannot read, or whose
 * vertices are not finite, or that holds no triangle, is rejected with assimp's message.
 * Base-colour textures (glTF baseColorTexture, else the diffuse texture, e.g. OBJ map_Kd) and
 * normal textures (glTF normalTexture, with its scale) that are PNG files beside the model are
 * loaded (a missing one is an error naming it), with the first UV channel and assimp's tangent frames
 * (aiProcess_CalcTangentSpace); assimp's aiProcess_TransformUVCoords bakes KHR_texture_transform
 * (offset, scale, rotation) into the UVs. The renderer samples them after the planned effects
 * (albedo-*, normal-map-bc5) prepared them. Embedded or non-PNG images are not read (the colour
 * factor / the geometric normal is used). KHR_materials_anisotropy, which assimp 5.2 does not
 * read, is read from the glTF JSON (read_gltf_anisotropy). */
#include <assimp/cimport.h>
#include <cjson/cJSON.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

typedef struct builder {
    sol_mesh *m;
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
        int mat_index = mesh->mMaterialIndex < (unsigned)b->m->mat_count ? (int)mesh->mMaterialIndex : -1;
        int has_uv = mesh->mTextureCoords[0] != NULL, has_tan = has_uv && mesh->mTangents && mesh->mBitangents;
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
                float *tg = uv ? realloc(b->m->tan, cap * 18 * sizeof *tg) : NULL;
                if (tg)
                    b->m->tan = tg;
                int *tt = tg ? realloc(b->m->tri_mat, cap * sizeof *tt) : NULL;
                if (!tt) {
                    b->st = SOL_ERR_NO_MEMORY;
                    snprintf(b->msg, sizeof b->msg, "out of memory");
                    return;
                }
                b->m->tri_mat = tt;
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
                if (has_uv && isfinite(mesh->mTextureCoords[0][idx].x) && isfinite(mesh->mTextureCoords[0][idx].y)) {
                    uv[0] = mesh->mTextureCoords[0][idx].x;
                    uv[1] = mesh->mTextureCoords[0][idx].y;
                }
                float *tg = &b->m->tan[tri * 18 + 6 * corner];
                memset(tg, 0, 6 * sizeof *tg);
                if (has_tan && isfinite(mesh->mTangents[idx].x) && isfinite(mesh->mTangents[idx].y) &&
                    isfinite(mesh->mTangents[idx].z) && isfinite(mesh->mBitangents[idx].x) &&
                    isfinite(mesh->mBitangents[idx].y) && isfinite(mesh->mBitangents[idx].z)) {
                    xform_normal(&t, &mesh->mTangents[idx], tg);
                    xform_normal(&t, &mesh->mBitangents[idx], tg + 3);
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
            b->m->tri_mat[tri] = mat_index;
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
    free(m->tan);
    free(m->tri_mat);
    for (int i = 0; i < m->tex_count; ++i)
        sol_image_free(&m->tex[i].image);
    free(m->tex);
    free(m->mats);
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

/* One texture of material `mi` (a PNG file beside the model): read into m->tex, its index in
 * *index. Embedded ("*0"), non-PNG (JPEG) images and names leaving the model's folder are
 * skipped (*index = -1: the colour factor / the geometric normal stay). A PNG that is missing or
 * unreadable is an error naming it; so is a normal texture without R, G, B channels. */
static sol_status load_texture(const struct aiMaterial *mat, enum aiTextureType type, int normal, const char *model,
                               int mi, sol_mesh *m, int *index, char *msg, size_t msg_size)
{
    *index = -1;
    struct aiString name;
    if (aiGetMaterialTexture(mat, type, 0, &name, NULL, NULL, NULL, NULL, NULL, NULL) != aiReturn_SUCCESS)
        return SOL_OK;
    if (name.data[0] == '*' || name.data[0] == '/' || strstr(name.data, "..") || !ends_with_png(name.data))
        return SOL_OK; /* embedded, outside the model's folder, or not PNG */
    const char *slash = strrchr(model, '/');
    int dir_len = slash ? (int)(slash - model) : 1;
    const char *dir = slash ? model : ".";
    char file[SOL_SCENE_PATH_MAX];
    int len = snprintf(file, sizeof file, "%.*s/%s", dir_len, dir, name.data);
    const char *what = normal ? "normal texture" : "base-colour texture";
    if (len < 0 || (size_t)len >= sizeof file) {
        snprintf(msg, msg_size, "%s of material %d: file name too long", what, mi);
        return SOL_ERR_LIMIT;
    }
    for (int i = 0; i < m->tex_count; ++i) /* a file several materials share is read (and prepared) once */
        if (m->tex[i].normal == normal && !strcmp(m->tex[i].name, name.data)) {
            *index = i;
            return SOL_OK;
        }
    sol_mesh_texture *t = &m->tex[m->tex_count];
    memset(t, 0, sizeof *t);
    sol_status st = sol_png_read(file, &t->image, &t->bits);
    if (st != SOL_OK) {
        snprintf(msg, msg_size, "%s %.120s of material \"%.40s\": %s", what, file, m->mats[mi].name,
                 st == SOL_ERR_IO ? "cannot open or read it" : sol_status_string(st));
        return st;
    }
    if (normal && t->image.channels < 3) {
        snprintf(msg, msg_size, "normal texture %.120s of material \"%.40s\" has %d channel%s, needs R, G, B", file,
                 m->mats[mi].name, t->image.channels, t->image.channels == 1 ? "" : "s");
        sol_image_free(&t->image);
        return SOL_ERR_FORMAT;
    }
    t->normal = normal;
    t->material = mi;
    snprintf(t->name, sizeof t->name, "%.127s", name.data);
    *index = m->tex_count++;
    return SOL_OK;
}

/* glTF normalTexture.scale, which assimp's glTF 2.0 importer keeps as the material property
 * "$tex.scale" of the first normals texture (AI_MATKEY_GLTF_TEXTURE_SCALE in assimp/GltfMaterial.h);
 * 1 when absent (the spec's default, and every non-glTF file). Any finite value is accepted, as the
 * spec puts no range on it (0 flattens the map, a negative one flips its relief). A number beyond a
 * double's range is already refused by assimp's JSON reader; a non-finite value reaching here anyway
 * is an error naming its JSON pointer. */
static sol_status read_normal_scale(const struct aiMaterial *mat, int i, sol_mesh_material *mm, char *msg,
                                    size_t msg_size)
{
    ai_real scale = 1;
    unsigned one = 1;
    mm->normal_scale = 1;
    if (aiGetMaterialFloatArray(mat, "$tex.scale", aiTextureType_NORMALS, 0, &scale, &one) != aiReturn_SUCCESS)
        return SOL_OK;
    if (!isfinite(scale)) {
        snprintf(msg, msg_size, "/materials/%d/normalTexture/scale: must be finite", i);
        return SOL_ERR_NONFINITE;
    }
    mm->normal_scale = scale;
    return SOL_OK;
}

/* The model's materials: names, base-colour textures (glTF baseColorTexture, else the diffuse
 * one, e.g. OBJ map_Kd) and normal textures (glTF normalTexture, with its scale). */
static sol_status load_materials(const struct aiScene *sc, const char *model, sol_mesh *m, char *msg, size_t msg_size)
{
    if (sc->mNumMaterials == 0)
        return SOL_OK;
    m->mats = calloc(sc->mNumMaterials, sizeof *m->mats);
    m->tex = calloc((size_t)sc->mNumMaterials * 2, sizeof *m->tex);
    if (!m->mats || !m->tex) {
        snprintf(msg, msg_size, "out of memory");
        return SOL_ERR_NO_MEMORY;
    }
    m->mat_count = (int)sc->mNumMaterials;
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) {
        const struct aiMaterial *mat = sc->mMaterials[i];
        sol_mesh_material *mm = &m->mats[i];
        struct aiString nm;
        if (aiGetMaterialString(mat, AI_MATKEY_NAME, &nm) == aiReturn_SUCCESS)
            snprintf(mm->name, sizeof mm->name, "%.63s", nm.data);
        sol_status st = load_texture(mat, aiTextureType_BASE_COLOR, 0, model, (int)i, m, &mm->base_tex, msg, msg_size);
        if (st == SOL_OK && mm->base_tex < 0)
            st = load_texture(mat, aiTextureType_DIFFUSE, 0, model, (int)i, m, &mm->base_tex, msg, msg_size);
        if (st == SOL_OK)
            st = load_texture(mat, aiTextureType_NORMALS, 1, model, (int)i, m, &mm->normal_tex, msg, msg_size);
        if (st == SOL_OK)
            st = read_normal_scale(mat, (int)i, mm, msg, msg_size);
        if (st != SOL_OK)
            return st;
    }
    return SOL_OK;
}

/* KHR_materials_anisotropy: Debian's assimp (5.2) does not read this extension, so its fields are
 * read from the glTF JSON with libcjson, for the materials assimp imported (same order as the
 * file's "materials"). Per the extension's spec: anisotropyStrength in [0, 1] (default 0),
 * anisotropyRotation in radians (default 0, from the tangent towards the bitangent),
 * anisotropyTexture (noted, not sampled); alpha = roughnessFactor^2 (pbrMetallicRoughness,
 * default 1). A value of the wrong type or out of range is an error naming its JSON pointer; JSON
 * that does not parse has no extension (assimp has already accepted the file). Fuzzed by
 * tests/fuzz/fuzz_gltf_anisotropy.c. */
sol_status sol_mesh_read_anisotropy_json(const char *json, size_t json_len, sol_mesh *m, char *msg, size_t msg_size)
{
    cJSON *root = cJSON_ParseWithLength(json, json_len);
    const cJSON *mats = root ? cJSON_GetObjectItemCaseSensitive(root, "materials") : NULL;
    sol_status st = SOL_OK;
    int i = 0;
    for (const cJSON *mat = cJSON_IsArray(mats) ? mats->child : NULL; mat && i < m->mat_count && st == SOL_OK;
         mat = mat->next, ++i) {
        const cJSON *ext = cJSON_GetObjectItemCaseSensitive(mat, "extensions");
        const cJSON *an = ext ? cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_anisotropy") : NULL;
        if (!an)
            continue;
        static const struct {
            const char *key;
            double def, lo, hi;
        } fields[] = {{"anisotropyStrength", 0, 0, 1}, {"anisotropyRotation", 0, -1e6, 1e6}};
        double val[2];
        for (int k = 0; k < 2 && st == SOL_OK; ++k) {
            const cJSON *v = cJSON_IsObject(an) ? cJSON_GetObjectItemCaseSensitive(an, fields[k].key) : NULL;
            val[k] = fields[k].def;
            if (!cJSON_IsObject(an)) {
                snprintf(msg, msg_size, "/materials/%d/extensions/KHR_materials_anisotropy: must be an object", i);
                st = SOL_ERR_FORMAT;
            } else if (v && !cJSON_IsNumber(v)) {
                snprintf(msg, msg_size, "/materials/%d/extensions/KHR_materials_anisotropy/%s: must be a number", i,
                         fields[k].key);
                st = SOL_ERR_FORMAT;
            } else if (v && !isfinite(v->valuedouble)) {
                snprintf(msg, msg_size, "/materials/%d/extensions/KHR_materials_anisotropy/%s: must be finite", i,
                         fields[k].key);
                st = SOL_ERR_NONFINITE;
            } else if (v && (v->valuedouble < fields[k].lo || v->valuedouble > fields[k].hi)) {
                snprintf(msg, msg_size, "/materials/%d/extensions/KHR_materials_anisotropy/%s: must be in [%g, %g] (got %g)",
                         i, fields[k].key, fields[k].lo, fields[k].hi, v->valuedouble);
                st = SOL_ERR_OUT_OF_RANGE;
            } else if (v)
                val[k] = v->valuedouble;
        }
        if (st != SOL_OK)
            break;
        double rough = 1;
        const cJSON *pbr = cJSON_GetObjectItemCaseSensitive(mat, "pbrMetallicRoughness");
        const cJSON *rf = pbr ? cJSON_GetObjectItemCaseSensitive(pbr, "roughnessFactor") : NULL;
        if (cJSON_IsNumber(rf) && isfinite(rf->valuedouble))
            rough = rf->valuedouble < 0 ? 0 : rf->valuedouble > 1 ? 1 : rf->valuedouble;
        sol_mesh_material *mm = &m->mats[i];
        mm->aniso = 1;
        mm->aniso_strength = val[0];
        mm->aniso_rotation = val[1];
        mm->alpha = rough * rough;
        mm->aniso_texture = cJSON_GetObjectItemCaseSensitive(an, "anisotropyTexture") != NULL;
    }
    cJSON_Delete(root);
    return st;
}

/* The glTF JSON of a .gltf file, or a .glb's JSON chunk (12-byte header, then chunk 0: length,
 * type "JSON", data; the binary chunks after it are not read), at most 64 MiB (sol_read_limits'
 * default byte bound), handed to sol_mesh_read_anisotropy_json. Other files (OBJ) have no such
 * extension. */
static sol_status read_gltf_anisotropy(const char *path, sol_mesh *m, char *msg, size_t msg_size)
{
    size_t n = strlen(path);
    int glb = n >= 4 && !strcmp(path + n - 4, ".glb");
    if (!glb && !(n >= 5 && !strcmp(path + n - 5, ".gltf")))
        return SOL_OK;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, msg_size, "cannot reopen the model to read KHR_materials_anisotropy");
        return SOL_ERR_IO;
    }
    const long cap = 64L << 20;
    long size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1, json_len = size;
    int seek_ok = fseek(f, 0, SEEK_SET) == 0;
    if (glb && size >= 20 && seek_ok) {
        unsigned char head[20];
        uint32_t clen = 0, ctype = 0;
        if (fread(head, 1, 20, f) == 20) {
            memcpy(&clen, head + 12, 4);
            memcpy(&ctype, head + 16, 4);
        }
        if (ctype != 0x4E4F534Au || clen > (uint64_t)(size - 20)) {
            fclose(f);
            return SOL_OK; /* assimp read it; no JSON chunk we can see: no extension */
        }
        json_len = (long)clen;
    } else if (glb) {
        fclose(f);
        return SOL_OK;
    }
    if (size < 0 || !seek_ok || json_len > cap) {
        fclose(f);
        snprintf(msg, msg_size, "glTF JSON unreadable or larger than %ld bytes (reading KHR_materials_anisotropy)", cap);
        return json_len > cap ? SOL_ERR_LIMIT : SOL_ERR_IO;
    }
    char *buf = malloc((size_t)json_len + 1);
    size_t len = buf ? fread(buf, 1, (size_t)json_len, f) : 0;
    fclose(f);
    if (!buf) {
        snprintf(msg, msg_size, "out of memory");
        return SOL_ERR_NO_MEMORY;
    }
    sol_status st = sol_mesh_read_anisotropy_json(buf, len, m, msg, msg_size);
    free(buf);
    return st;
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
                                    aiProcess_SortByPType | aiProcess_TransformUVCoords | aiProcess_CalcTangentSpace);
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
    builder b = {&m, 0, SOL_OK, ""};
    b.st = load_materials(sc, path, &m, b.msg, sizeof b.msg);
    if (b.st == SOL_OK)
        b.st = read_gltf_anisotropy(path, &m, b.msg, sizeof b.msg);
    struct aiMatrix4x4 id = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    if (b.st == SOL_OK)
        add_node(&b, sc, sc->mRootNode, &id, 0);
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

int sol_mesh_intersect(const sol_mesh *m, const double o[3], const double d[3], double tmax, sol_mesh_hit *hit)
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
    double e1[3], e2[3], s = 0, *n = hit->n, w0 = 1 - bu - bv;
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
    const float *uv = &m->uv[(size_t)best * 6], *tg = &m->tan[(size_t)best * 18];
    for (int i = 0; i < 3; ++i) {
        hit->color[i] = m->color[(size_t)best * 3 + i];
        hit->tangent[i] = w0 * tg[i] + bu * tg[6 + i] + bv * tg[12 + i];
        hit->bitangent[i] = w0 * tg[3 + i] + bu * tg[9 + i] + bv * tg[15 + i];
    }
    hit->uv[0] = w0 * uv[0] + bu * uv[2] + bv * uv[4];
    hit->uv[1] = w0 * uv[1] + bu * uv[3] + bv * uv[5];
    hit->material = m->tri_mat[best];
    hit->t = tmax;
    return 1;
}
