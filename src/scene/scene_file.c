/* scene_file.c - reads sol's scene file (JSON through Debian's libcjson) into a sol_scene.
 *
 * One rule for every field: absent means its documented default (docs/scene-format.md); present
 * means it must have the right JSON type and lie in its domain, else the load fails with the
 * field's JSON pointer. Unknown keys are errors too (a misspelt "roughnes" must not silently fall
 * back to a default). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sol_hdr.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"
#include "scene_internal.h"
#include "sol_scene.h"

typedef struct ctx {
    const char *file;
    char base[SOL_SCENE_PATH_MAX]; /* folder of the scene file, "" = current */
    sol_scene_error *err;
} ctx;

static sol_status fail(ctx *c, sol_status st, const char *ptr, const char *fmt, ...)
{
    if (c->err) {
        memset(c->err, 0, sizeof *c->err);
        snprintf(c->err->file, sizeof c->err->file, "%s", c->file);
        snprintf(c->err->pointer, sizeof c->err->pointer, "%s", ptr);
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(c->err->message, sizeof c->err->message, fmt, ap);
        va_end(ap);
    }
    return st;
}

#define PTR(buf, parent, ...)                                                                                          \
    char buf[256];                                                                                                     \
    do {                                                                                                               \
        int n_ = snprintf(buf, sizeof buf, "%s/", parent);                                                             \
        if (n_ > 0 && (size_t)n_ < sizeof buf)                                                                          \
            snprintf(buf + n_, sizeof buf - (size_t)n_, __VA_ARGS__);                                                  \
    } while (0)

#define TRY(expr)                                                                                                      \
    do {                                                                                                               \
        sol_status st_ = (expr);                                                                                       \
        if (st_ != SOL_OK)                                                                                             \
            return st_;                                                                                                \
    } while (0)

/* Every key of `obj` must be one of `allowed` (NULL-terminated). */
static sol_status check_keys(ctx *c, const cJSON *obj, const char *ptr, const char *const *allowed)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        int ok = 0;
        for (const char *const *a = allowed; *a && !ok; ++a)
            ok = it->string && !strcmp(it->string, *a);
        if (!ok) {
            PTR(p, ptr, "%s", it->string ? it->string : "");
            return fail(c, SOL_ERR_FORMAT, p, "unknown field");
        }
    }
    return SOL_OK;
}

static sol_status need_object(ctx *c, const cJSON *v, const char *ptr)
{
    return cJSON_IsObject(v) ? SOL_OK : fail(c, SOL_ERR_FORMAT, ptr, "must be an object");
}

/* A number in [lo, hi] (open at lo when lo_open). Absent: *out = def. */
static sol_status get_num(ctx *c, const cJSON *obj, const char *key, const char *ptr, double def, double lo,
                          double hi, int lo_open, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    PTR(p, ptr, "%s", key);
    if (!v) {
        *out = def;
        return SOL_OK;
    }
    if (!cJSON_IsNumber(v))
        return fail(c, SOL_ERR_FORMAT, p, "must be a number");
    double x = v->valuedouble;
    if (!isfinite(x))
        return fail(c, SOL_ERR_NONFINITE, p, "must be finite");
    if (x < lo || x > hi || (lo_open && x == lo))
        return fail(c, SOL_ERR_OUT_OF_RANGE, p, "must be in %s%g, %g] (got %g)", lo_open ? "(" : "[", lo, hi, x);
    *out = x;
    return SOL_OK;
}

static sol_status get_int(ctx *c, const cJSON *obj, const char *key, const char *ptr, int def, int lo, int hi,
                          int *out)
{
    double x;
    TRY(get_num(c, obj, key, ptr, def, lo, hi, 0, &x));
    if (x != floor(x)) {
        PTR(p, ptr, "%s", key);
        return fail(c, SOL_ERR_FORMAT, p, "must be an integer (got %g)", x);
    }
    *out = (int)x;
    return SOL_OK;
}

static sol_status get_bool(ctx *c, const cJSON *obj, const char *key, const char *ptr, int def, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) {
        *out = def;
        return SOL_OK;
    }
    if (!cJSON_IsBool(v)) {
        PTR(p, ptr, "%s", key);
        return fail(c, SOL_ERR_FORMAT, p, "must be true or false");
    }
    *out = cJSON_IsTrue(v);
    return SOL_OK;
}

/* An array of n numbers, each in [lo, hi]. nonzero: the vector must not be all zeros. */
static sol_status get_vec(ctx *c, const cJSON *obj, const char *key, const char *ptr, const double *def, int n,
                          double lo, double hi, int nonzero, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    PTR(p, ptr, "%s", key);
    if (!v) {
        memcpy(out, def, (size_t)n * sizeof *out);
        return SOL_OK;
    }
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return fail(c, SOL_ERR_FORMAT, p, "must be an array of %d numbers", n);
    double tmp[4];
    int i = 0, any = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        PTR(q, p, "%d", i);
        if (!cJSON_IsNumber(e))
            return fail(c, SOL_ERR_FORMAT, q, "must be a number");
        if (!isfinite(e->valuedouble))
            return fail(c, SOL_ERR_NONFINITE, q, "must be finite");
        if (e->valuedouble < lo || e->valuedouble > hi)
            return fail(c, SOL_ERR_OUT_OF_RANGE, q, "must be in [%g, %g] (got %g)", lo, hi, e->valuedouble);
        tmp[i] = e->valuedouble;
        any |= tmp[i] != 0.0;
    }
    if (nonzero && !any)
        return fail(c, SOL_ERR_ZERO_LENGTH, p, "must not be the zero vector");
    memcpy(out, tmp, (size_t)n * sizeof *out);
    return SOL_OK;
}

/* One of `names` (count entries; NULL entries are skipped). Absent: *out = def. */
static sol_status get_enum(ctx *c, const cJSON *obj, const char *key, const char *ptr, const char *const *names,
                           int count, int def, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    PTR(p, ptr, "%s", key);
    if (!v) {
        *out = def;
        return SOL_OK;
    }
    if (!cJSON_IsString(v))
        return fail(c, SOL_ERR_FORMAT, p, "must be a string");
    for (int i = 0; i < count; ++i)
        if (names[i] && !strcmp(names[i], v->valuestring)) {
            *out = i;
            return SOL_OK;
        }
    char list[200] = "";
    for (int i = 0; i < count; ++i)
        if (names[i] && strlen(list) + strlen(names[i]) + 3 < sizeof list) {
            strcat(list, *list ? ", " : "");
            strcat(list, names[i]);
        }
    return fail(c, SOL_ERR_FORMAT, p, "unknown value \"%.40s\" (one of: %s)", v->valuestring, list);
}

/* A file name relative to the scene file's folder; the file must exist. */
static sol_status get_file(ctx *c, const cJSON *obj, const char *key, const char *ptr, char *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    PTR(p, ptr, "%s", key);
    if (!cJSON_IsString(v) || !*v->valuestring)
        return fail(c, SOL_ERR_FORMAT, p, "must be a non-empty file name");
    char path[SOL_SCENE_PATH_MAX];
    int n = v->valuestring[0] == '/' || !*c->base
                ? snprintf(path, sizeof path, "%s", v->valuestring)
                : snprintf(path, sizeof path, "%s/%s", c->base, v->valuestring);
    if (n < 0 || (size_t)n >= sizeof path)
        return fail(c, SOL_ERR_LIMIT, p, "file name too long");
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(c, SOL_ERR_IO, p, "cannot open file %s: %s", path, strerror(errno));
    fclose(f);
    memcpy(out, path, (size_t)n + 1);
    return SOL_OK;
}

static int has_suffix(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    if (a < b)
        return 0;
    for (size_t i = 0; i < b; ++i)
        if ((s[a - b + i] | 0x20) != suffix[i])
            return 0;
    return 1;
}

static sol_status load_image(ctx *c, const char *file, const char *ptr, sol_image *img, int *bits)
{
    sol_status st;
    *bits = 0;
    if (has_suffix(file, ".png"))
        st = sol_png_read(file, img, bits);
    else if (has_suffix(file, ".exr"))
        st = sol_exr_read(file, img);
    else
        return fail(c, SOL_ERR_FORMAT, ptr, "%s: only .png and .exr images are read", file);
    if (st != SOL_OK)
        return fail(c, st, ptr, "%s: %s", file, sol_status_string(st));
    return SOL_OK;
}

/* A lat-long environment (docs/scene-format.md): an RGB EXR of at most SOL_SCENE_ENV_MAX_PIXELS
 * pixels (checked by sol_read_limits before anything is allocated), every value finite and >= 0
 * (radiance), all checked here, before anything is rendered. */
static sol_status load_environment(ctx *c, const char *file, const char *ptr, sol_image *img)
{
    if (!has_suffix(file, ".exr"))
        return fail(c, SOL_ERR_FORMAT, ptr, "%s: an environment is a lat-long .exr image", file);
    sol_read_limits lim = {SOL_SCENE_ENV_MAX_PIXELS, 0};
    sol_image im;
    sol_status st = sol_exr_read_ex(file, &lim, &im);
    if (st == SOL_ERR_LIMIT)
        return fail(c, st, ptr, "%s: larger than %d pixels (the environment limit)", file, SOL_SCENE_ENV_MAX_PIXELS);
    if (st != SOL_OK)
        return fail(c, st, ptr, "%s: %s", file, sol_status_string(st));
    if (im.channels < 3) {
        int ch = im.channels;
        sol_image_free(&im);
        return fail(c, SOL_ERR_FORMAT, ptr, "%s: needs R, G, B channels (has %d channel%s)", file, ch, ch == 1 ? "" : "s");
    }
    if (im.width < 2 || im.height < 1) {
        sol_image_free(&im);
        return fail(c, SOL_ERR_FORMAT, ptr, "%s: a lat-long map needs at least 2 x 1 pixels", file);
    }
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            for (int k = 0; k < 3; ++k) {
                float v = sol_image_pixel(&im, x, y)[k];
                if (!isfinite(v) || v < 0) {
                    sol_image_free(&im);
                    return fail(c, isfinite(v) ? SOL_ERR_OUT_OF_RANGE : SOL_ERR_NONFINITE, ptr,
                                "%s: pixel (%d, %d) channel %c is %g (radiance must be finite and >= 0)", file, x, y,
                                "RGB"[k], v);
                }
            }
    *img = im;
    return SOL_OK;
}

static const char *const texture_keys[] = {"file", "procedural", "bits", "storage", "scale", "colors",
                                           "amplitude", NULL};

static sol_status parse_texture(ctx *c, const cJSON *v, const char *ptr, int normal_map, sol_scene_texture *t)
{
    TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, texture_keys));
    const cJSON *file = cJSON_GetObjectItemCaseSensitive(v, "file");
    const cJSON *proc = cJSON_GetObjectItemCaseSensitive(v, "procedural");
    if (!file == !proc)
        return fail(c, SOL_ERR_FORMAT, ptr, "needs exactly one of \"file\" and \"procedural\"");
    static const char *const procs[] = {NULL, NULL, "checker", "bumps"};
    static const char *const storages[] = {"srgb", "linear"};
    double bits;
    int src = 0;
    if (proc) {
        TRY(get_enum(c, v, "procedural", ptr, procs, 4, 0, &src));
        PTR(p, ptr, "procedural");
        if ((src == SOL_TEX_BUMPS) != normal_map)
            return fail(c, SOL_ERR_FORMAT, p, normal_map ? "a normal map is \"bumps\"" : "an albedo texture is \"checker\"");
        t->source = (sol_texture_source)src;
    } else {
        t->source = SOL_TEX_FILE;
        TRY(get_file(c, v, "file", ptr, t->file));
    }
    TRY(get_num(c, v, "bits", ptr, 8, 8, 16, 0, &bits));
    if (bits != 8 && bits != 16) {
        PTR(p, ptr, "bits");
        return fail(c, SOL_ERR_OUT_OF_RANGE, p, "must be 8 or 16 (got %g)", bits);
    }
    t->bits = (int)bits;
    TRY(get_enum(c, v, "storage", ptr, storages, 2, normal_map, &t->linear));
    TRY(get_num(c, v, "scale", ptr, 1, 0, 1e6, 1, &t->scale));
    const double amp_def = 0.3;
    TRY(get_num(c, v, "amplitude", ptr, amp_def, 0, 10, 0, &t->low[0]));
    const cJSON *colors = cJSON_GetObjectItemCaseSensitive(v, "colors");
    if (colors) {
        PTR(p, ptr, "colors");
        if (!cJSON_IsArray(colors) || cJSON_GetArraySize(colors) != 2)
            return fail(c, SOL_ERR_FORMAT, p, "must be an array of two colours");
        const cJSON *e0 = cJSON_GetArrayItem(colors, 0), *e1 = cJSON_GetArrayItem(colors, 1);
        cJSON *tmp = cJSON_CreateObject();
        if (!tmp)
            return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
        cJSON_AddItemReferenceToObject(tmp, "0", (cJSON *)e0);
        cJSON_AddItemReferenceToObject(tmp, "1", (cJSON *)e1);
        static const double zero[3] = {0, 0, 0};
        sol_status st = get_vec(c, tmp, "0", p, zero, 3, 0, 1, 0, t->low);
        if (st == SOL_OK)
            st = get_vec(c, tmp, "1", p, zero, 3, 0, 1, 0, t->high);
        cJSON_Delete(tmp);
        TRY(st);
    } else if (!normal_map) {
        for (int i = 0; i < 3; ++i) {
            t->low[i] = 0.02; /* a dark checker by default: what T2's dark textures look like */
            t->high[i] = 0.12;
        }
    }
    if (t->source == SOL_TEX_FILE) {
        int file_bits;
        PTR(p, ptr, "file");
        TRY(load_image(c, t->file, p, &t->image, &file_bits));
        if (t->image.channels < 3 && !(t->image.channels == 1 && !normal_map)) {
            sol_image_free(&t->image);
            return fail(c, SOL_ERR_FORMAT, p, "%s: needs RGB channels", t->file);
        }
    }
    return SOL_OK;
}

static const char *const material_keys[] = {"name", "albedo", "specular", "gloss", "phong_exponent",
                                            "anisotropic", "albedo_texture", "normal_map", NULL};

static sol_status parse_material(ctx *c, const cJSON *v, const char *ptr, sol_scene_material *m)
{
    static const double grey[3] = {0.5, 0.5, 0.5}, xaxis[3] = {1, 0, 0};
    TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, material_keys));
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(v, "name");
    if (name) {
        PTR(p, ptr, "name");
        if (!cJSON_IsString(name) || strlen(name->valuestring) >= SOL_SCENE_NAME_MAX)
            return fail(c, SOL_ERR_FORMAT, p, "must be a string of at most %d bytes", SOL_SCENE_NAME_MAX - 1);
        strcpy(m->name, name->valuestring);
    }
    TRY(get_vec(c, v, "albedo", ptr, grey, 3, 0, 1, 0, m->albedo));
    TRY(get_num(c, v, "specular", ptr, 0.04, 0, 1, 0, &m->specular));
    TRY(get_num(c, v, "gloss", ptr, 0.5, 0, 1, 0, &m->gloss));
    TRY(get_num(c, v, "phong_exponent", ptr, 0, 0, 1e6, 0, &m->phong_exponent));
    const cJSON *an = cJSON_GetObjectItemCaseSensitive(v, "anisotropic");
    if (an) {
        static const char *const aniso_keys[] = {"model", "roughness", "tangent", NULL};
        static const char *const models[] = {NULL, "ward", "ggx"};
        static const double def_r[2] = {0.1, 0.1};
        PTR(p, ptr, "anisotropic");
        int model;
        TRY(need_object(c, an, p));
        TRY(check_keys(c, an, p, aniso_keys));
        TRY(get_enum(c, an, "model", p, models, 3, SOL_ANISO_WARD, &model));
        m->aniso = (sol_aniso_model)model;
        TRY(get_vec(c, an, "roughness", p, def_r, 2, 1e-3, 10, 0, m->roughness));
        TRY(get_vec(c, an, "tangent", p, xaxis, 3, -1e6, 1e6, 1, m->tangent));
    } else {
        memcpy(m->tangent, xaxis, sizeof xaxis);
    }
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(v, "albedo_texture");
    if (t) {
        PTR(p, ptr, "albedo_texture");
        TRY(parse_texture(c, t, p, 0, &m->albedo_texture));
    }
    t = cJSON_GetObjectItemCaseSensitive(v, "normal_map");
    if (t) {
        PTR(p, ptr, "normal_map");
        TRY(parse_texture(c, t, p, 1, &m->normal_map));
    }
    return SOL_OK;
}

static sol_status resolve_material(ctx *c, const cJSON *obj, const char *ptr, const sol_scene *s, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "material");
    PTR(p, ptr, "material");
    if (!v) {
        if (s->material_count < 1)
            return fail(c, SOL_ERR_FORMAT, p, "no materials are defined");
        *out = 0;
        return SOL_OK;
    }
    if (cJSON_IsString(v)) {
        for (int i = 0; i < s->material_count; ++i)
            if (!strcmp(s->materials[i].name, v->valuestring)) {
                *out = i;
                return SOL_OK;
            }
        return fail(c, SOL_ERR_FORMAT, p, "no material named \"%.60s\"", v->valuestring);
    }
    if (cJSON_IsNumber(v) && v->valuedouble >= 0 && v->valuedouble < s->material_count &&
        v->valuedouble == floor(v->valuedouble)) {
        *out = (int)v->valuedouble;
        return SOL_OK;
    }
    return fail(c, SOL_ERR_FORMAT, p, "must be a material name or an index below %d", s->material_count);
}

static const char *const object_keys[] = {"type", "material", "point", "normal", "half_extent", "min", "max",
                                          "center", "radius", "origin", "size", "amplitude", "frequency", "file",
                                          NULL};
#define BIG 1e9 /* coordinates are limited to |x| <= 1e9 so products stay finite */

static sol_status parse_object(ctx *c, const cJSON *v, const char *ptr, const sol_scene *s, sol_scene_object *o)
{
    static const char *const kinds[] = {"plane", "box", "sphere", "heightfield", "mesh"};
    static const double zero[3] = {0, 0, 0}, up[3] = {0, 1, 0}, one[3] = {1, 1, 1}, hf[2] = {10, 10};
    TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, object_keys));
    int kind;
    if (!cJSON_GetObjectItemCaseSensitive(v, "type")) {
        PTR(p, ptr, "type");
        return fail(c, SOL_ERR_FORMAT, p, "is required (plane, box, sphere, heightfield or mesh)");
    }
    TRY(get_enum(c, v, "type", ptr, kinds, 5, 0, &kind));
    o->kind = (sol_geom_kind)kind;
    TRY(resolve_material(c, v, ptr, s, &o->material));
    switch (o->kind) {
    case SOL_GEOM_PLANE:
        TRY(get_vec(c, v, "point", ptr, zero, 3, -BIG, BIG, 0, o->a));
        TRY(get_vec(c, v, "normal", ptr, up, 3, -BIG, BIG, 1, o->b));
        TRY(get_num(c, v, "half_extent", ptr, 0, 0, BIG, 0, &o->radius));
        break;
    case SOL_GEOM_BOX: {
        static const double m1[3] = {-1, -1, -1};
        TRY(get_vec(c, v, "min", ptr, m1, 3, -BIG, BIG, 0, o->a));
        TRY(get_vec(c, v, "max", ptr, one, 3, -BIG, BIG, 0, o->b));
        for (int i = 0; i < 3; ++i)
            if (o->a[i] > o->b[i]) {
                PTR(p, ptr, "max/%d", i);
                return fail(c, SOL_ERR_INVALID_ARG, p, "max must be >= min (%g < %g)", o->b[i], o->a[i]);
            }
        break;
    }
    case SOL_GEOM_SPHERE:
        TRY(get_vec(c, v, "center", ptr, zero, 3, -BIG, BIG, 0, o->a));
        TRY(get_num(c, v, "radius", ptr, 1, 0, BIG, 1, &o->radius));
        break;
    case SOL_GEOM_HEIGHTFIELD: {
        double size[2];
        TRY(get_vec(c, v, "origin", ptr, zero, 3, -BIG, BIG, 0, o->a));
        TRY(get_vec(c, v, "size", ptr, hf, 2, 0, BIG, 0, size));
        for (int i = 0; i < 2; ++i)
            if (!(size[i] > 0)) {
                PTR(p, ptr, "size/%d", i);
                return fail(c, SOL_ERR_OUT_OF_RANGE, p, "must be > 0 (a zero-area patch)");
            }
        o->b[0] = size[0];
        o->b[2] = size[1];
        TRY(get_num(c, v, "amplitude", ptr, 0.2, 0, BIG, 0, &o->b[1]));
        TRY(get_num(c, v, "frequency", ptr, 1, 0, 1e6, 1, &o->radius));
        break;
    }
    case SOL_GEOM_MESH: {
        TRY(get_file(c, v, "file", ptr, o->file));
        PTR(p, ptr, "file");
        char msg[256];
        sol_mesh *m = calloc(1, sizeof *m);
        if (!m)
            return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
        sol_status st = sol_mesh_load(o->file, m, msg, sizeof msg);
        if (st != SOL_OK) {
            free(m);
            return fail(c, st, p, "%s: %s", o->file, msg);
        }
        o->mesh = m;
        break;
    }
    }
    return SOL_OK;
}

static const char *const light_keys[] = {"type", "color", "intensity", "position", "direction", "radius", "cone",
                                         "shadows", "clip", "file", "lobes", NULL};

static sol_status parse_light(ctx *c, const cJSON *v, const char *ptr, int clip_count, sol_scene_light *l)
{
    static const char *const kinds[] = {"sun", "point", "spot", "environment"};
    static const double white[3] = {1, 1, 1}, zero[3] = {0, 0, 0}, down[3] = {0, -1, 0};
    TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, light_keys));
    int kind;
    if (!cJSON_GetObjectItemCaseSensitive(v, "type")) {
        PTR(p, ptr, "type");
        return fail(c, SOL_ERR_FORMAT, p, "is required (sun, point, spot or environment)");
    }
    TRY(get_enum(c, v, "type", ptr, kinds, 4, 0, &kind));
    l->kind = (sol_light_kind)kind;
    TRY(get_vec(c, v, "color", ptr, white, 3, 0, 1e6, 0, l->color));
    TRY(get_num(c, v, "intensity", ptr, 1, 0, 1e9, 0, &l->intensity));
    TRY(get_vec(c, v, "position", ptr, zero, 3, -BIG, BIG, 0, l->position));
    TRY(get_vec(c, v, "direction", ptr, down, 3, -BIG, BIG, 1, l->direction));
    TRY(get_num(c, v, "radius", ptr, 10, 0, BIG, 1, &l->radius));
    TRY(get_num(c, v, "cone", ptr, 30, 0, 89.9, 1, &l->cone_deg));
    TRY(get_bool(c, v, "shadows", ptr, 0, &l->shadows));
    l->clip = -1;
    if (cJSON_GetObjectItemCaseSensitive(v, "clip")) {
        if (clip_count < 1) {
            PTR(p, ptr, "clip");
            return fail(c, SOL_ERR_FORMAT, p, "no clip_volumes are defined");
        }
        TRY(get_int(c, v, "clip", ptr, 0, 0, clip_count - 1, &l->clip));
    }
    if (l->kind == SOL_LIGHT_ENV) {
        const cJSON *lobes = cJSON_GetObjectItemCaseSensitive(v, "lobes");
        int has_file = cJSON_GetObjectItemCaseSensitive(v, "file") != NULL;
        if (has_file == (lobes != NULL))
            return fail(c, SOL_ERR_FORMAT, ptr, "an environment needs exactly one of \"file\" and \"lobes\"");
        if (has_file) {
            PTR(p, ptr, "file");
            TRY(get_file(c, v, "file", ptr, l->env_file));
            TRY(load_environment(c, l->env_file, p, &l->env_image));
        } else {
            PTR(p, ptr, "lobes");
            int n = cJSON_IsArray(lobes) ? cJSON_GetArraySize(lobes) : -1;
            if (n < 1)
                return fail(c, SOL_ERR_FORMAT, p, "must be a non-empty array of lobes");
            if (n > SOL_SCENE_MAX_ITEMS)
                return fail(c, SOL_ERR_LIMIT, p, "more than %d lobes", SOL_SCENE_MAX_ITEMS);
            l->lobes = calloc((size_t)n, sizeof *l->lobes);
            if (!l->lobes)
                return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
            l->lobe_count = n;
            static const char *const lobe_keys[] = {"axis", "sharpness", "color", NULL};
            int i = 0;
            for (const cJSON *e = lobes->child; e; e = e->next, ++i) {
                PTR(q, p, "%d", i);
                sol_scene_sg_lobe *g = &l->lobes[i];
                static const double upz[3] = {0, 1, 0};
                TRY(need_object(c, e, q));
                TRY(check_keys(c, e, q, lobe_keys));
                TRY(get_vec(c, e, "axis", q, upz, 3, -BIG, BIG, 1, g->axis));
                TRY(get_num(c, e, "sharpness", q, 1, 0, 1e6, 0, &g->sharpness));
                TRY(get_vec(c, e, "color", q, white, 3, 0, 1e6, 0, g->amplitude));
                double len = sqrt(sol_dot3(g->axis, g->axis));
                for (int k = 0; k < 3; ++k)
                    g->axis[k] /= len;
            }
        }
    }
    if (l->kind == SOL_LIGHT_SUN || l->kind == SOL_LIGHT_SPOT) {
        double len = sqrt(sol_dot3(l->direction, l->direction));
        for (int k = 0; k < 3; ++k)
            l->direction[k] /= len;
    }
    return SOL_OK;
}

/* ---- pipeline ---- */

static const char *const pipeline_keys[] = {
    "gbuffer_normals", "normal_map_codec", "normal_map_encoder", "albedo_codec", "albedo_renormalize",
    "albedo_storage", "light_buffer", "light_range", "range_scaling", "tonemap", "exposure", "lut_size", "look",
    "ssao", "ssao_radius", "ssao_samples", "ssao_half_res", "aa", "culling", "reference_supersample", "sg_lobes",
    "env_lobes", NULL};

static sol_status parse_pipeline(ctx *c, const cJSON *v, const char *ptr, sol_scene_pipeline *pl)
{
    const char *normal_names[SOL_NORMAL_METHOD_COUNT + 1];
    normal_names[0] = "float";
    for (int i = 0; i < SOL_NORMAL_METHOD_COUNT; ++i)
        normal_names[i + 1] = sol_normal_method_name((sol_normal_method)i);
    const char *tonemaps[SOL_TONEMAP_COUNT];
    for (int i = 0; i < SOL_TONEMAP_COUNT; ++i)
        tonemaps[i] = sol_tonemap_name((sol_tonemap)i);
    static const char *const nm_codecs[] = {"auto", "none", "bc5"}, *const alb_codecs[] = {"auto", "none", "bc1"};
    static const char *const encoders[] = {"common", "optimal", "adaptive"};
    static const char *const storages[] = {"auto", "gamma", "linear"};
    static const char *const buffers[] = {"float", "r11g11b10f", "rgbm", "rgb10"};
    static const char *const aas[] = {"none", "post", "temporal"};
    static const char *const culls[] = {"auto", "off", "on"};
    static const cJSON empty = {0};
    if (!v)
        v = &empty; /* every field at its default */
    else
        TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, pipeline_keys));
    int k;
    TRY(get_enum(c, v, "gbuffer_normals", ptr, normal_names, SOL_NORMAL_METHOD_COUNT + 1,
                 1 + SOL_NORMAL_XYZ_BEST_FIT, &k));
    pl->gbuffer_normals = k - 1;
    TRY(get_enum(c, v, "normal_map_codec", ptr, nm_codecs, 3, 0, &k));
    pl->normal_map_codec = (sol_codec_choice)k;
    TRY(get_enum(c, v, "normal_map_encoder", ptr, encoders, 3, SOL_BC5_COMMON, &pl->normal_map_encoder));
    TRY(get_enum(c, v, "albedo_codec", ptr, alb_codecs, 3, 0, &k));
    pl->albedo_codec = (sol_codec_choice)k;
    TRY(get_bool(c, v, "albedo_renormalize", ptr, 1, &pl->albedo_renormalize));
    TRY(get_enum(c, v, "albedo_storage", ptr, storages, 3, 0, &k));
    pl->albedo_storage = k - 1;
    TRY(get_enum(c, v, "light_buffer", ptr, buffers, 4, SOL_LB_R11G11B10F, &k));
    pl->light_buffer = (sol_light_buffer)k;
    TRY(get_num(c, v, "light_range", ptr, 8, 0, 65504, 1, &pl->light_range));
    TRY(get_bool(c, v, "range_scaling", ptr, 1, &pl->range_scaling));
    TRY(get_enum(c, v, "tonemap", ptr, tonemaps, SOL_TONEMAP_COUNT, SOL_TONEMAP_FILMIC_HBD, &pl->tonemap));
    TRY(get_num(c, v, "exposure", ptr, 1, 0, 1e9, 1, &pl->exposure));
    TRY(get_int(c, v, "lut_size", ptr, 16, 2, 64, &pl->lut_size));
    const cJSON *look = cJSON_GetObjectItemCaseSensitive(v, "look");
    if (look) {
        static const char *const look_keys[] = {"saturation", "contrast", "hue", "gain", NULL};
        static const double one[3] = {1, 1, 1};
        PTR(p, ptr, "look");
        TRY(need_object(c, look, p));
        TRY(check_keys(c, look, p, look_keys));
        pl->has_look = 1;
        TRY(get_num(c, look, "saturation", p, 0, -1, 10, 0, &pl->look_saturation));
        TRY(get_num(c, look, "contrast", p, 0, 0, 1, 0, &pl->look_contrast));
        TRY(get_num(c, look, "hue", p, 0, -360, 360, 0, &pl->look_hue_deg));
        TRY(get_vec(c, look, "gain", p, one, 3, 0, 10, 0, pl->look_gain));
    }
    TRY(get_bool(c, v, "ssao", ptr, 0, &pl->ssao));
    TRY(get_num(c, v, "ssao_radius", ptr, 0.5, 0, 1e6, 1, &pl->ssao_radius));
    TRY(get_int(c, v, "ssao_samples", ptr, 4, 1, 4096, &pl->ssao_samples));
    TRY(get_bool(c, v, "ssao_half_res", ptr, 1, &pl->ssao_half_res));
    TRY(get_enum(c, v, "aa", ptr, aas, 3, SOL_AA_NONE, &k));
    pl->aa = (sol_aa_mode)k;
    TRY(get_enum(c, v, "culling", ptr, culls, 3, 0, &k));
    pl->culling = k == 0 ? -1 : k - 1;
    TRY(get_int(c, v, "reference_supersample", ptr, 3, 1, 8, &pl->reference_supersample));
    TRY(get_int(c, v, "sg_lobes", ptr, 4, 1, 16, &pl->sg_lobes));
    TRY(get_int(c, v, "env_lobes", ptr, 24, 1, 48, &pl->env_lobes));
    return SOL_OK;
}

static const char *const camera_keys[] = {"position", "look_at", "up", "fov", "width", "height",
                                          "znear", "zfar", "path", NULL};

static sol_status parse_camera(ctx *c, const cJSON *v, const char *ptr, sol_scene_camera *cam)
{
    static const double pos[3] = {0, 1, -5}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    static const cJSON empty = {0};
    if (!v)
        v = &empty;
    else
        TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, camera_keys));
    TRY(get_vec(c, v, "position", ptr, pos, 3, -BIG, BIG, 0, cam->position));
    TRY(get_vec(c, v, "look_at", ptr, at, 3, -BIG, BIG, 0, cam->look_at));
    TRY(get_vec(c, v, "up", ptr, up, 3, -BIG, BIG, 1, cam->up));
    TRY(get_num(c, v, "fov", ptr, 60, 0, 179, 1, &cam->fov_deg));
    TRY(get_int(c, v, "width", ptr, 960, 1, 16384, &cam->width));
    TRY(get_int(c, v, "height", ptr, 540, 1, 16384, &cam->height));
    if ((int64_t)cam->width * cam->height > SOL_SCENE_MAX_PIXELS) {
        PTR(p, ptr, "height");
        return fail(c, SOL_ERR_LIMIT, p, "width * height above %d pixels", SOL_SCENE_MAX_PIXELS);
    }
    TRY(get_num(c, v, "znear", ptr, 0.05, 0, BIG, 1, &cam->znear));
    TRY(get_num(c, v, "zfar", ptr, 1000, 0, BIG, 1, &cam->zfar));
    if (cam->zfar <= cam->znear) {
        PTR(p, ptr, "zfar");
        return fail(c, SOL_ERR_INVALID_ARG, p, "must be > znear");
    }
    double d[3];
    for (int i = 0; i < 3; ++i)
        d[i] = cam->look_at[i] - cam->position[i];
    double cr[3] = {d[1] * cam->up[2] - d[2] * cam->up[1], d[2] * cam->up[0] - d[0] * cam->up[2],
                    d[0] * cam->up[1] - d[1] * cam->up[0]};
    if (sol_dot3(d, d) == 0 || sol_dot3(cr, cr) <= 1e-12 * sol_dot3(d, d) * sol_dot3(cam->up, cam->up)) {
        PTR(p, ptr, "look_at");
        return fail(c, SOL_ERR_INVALID_ARG, p, "must differ from position and not lie along up");
    }
    const cJSON *path = cJSON_GetObjectItemCaseSensitive(v, "path");
    if (path) {
        PTR(p, ptr, "path");
        int n = cJSON_IsArray(path) ? cJSON_GetArraySize(path) : -1;
        if (n < 2)
            return fail(c, SOL_ERR_FORMAT, p, "must be an array of at least 2 positions");
        if (n > SOL_SCENE_MAX_ITEMS)
            return fail(c, SOL_ERR_LIMIT, p, "more than %d frames", SOL_SCENE_MAX_ITEMS);
        cam->frames = calloc((size_t)n, sizeof *cam->frames);
        if (!cam->frames)
            return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
        cam->frame_count = n;
        cJSON *tmp = cJSON_CreateObject();
        if (!tmp)
            return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
        int i = 0;
        sol_status st = SOL_OK;
        for (const cJSON *e = path->child; e && st == SOL_OK; e = e->next, ++i) {
            char key[16];
            snprintf(key, sizeof key, "%d", i);
            cJSON_AddItemReferenceToObject(tmp, key, (cJSON *)e);
            st = get_vec(c, tmp, key, p, pos, 3, -BIG, BIG, 0, cam->frames[i]);
        }
        cJSON_Delete(tmp);
        TRY(st);
    }
    return SOL_OK;
}

/* Parses an array field into `*items` (count via *n). */
typedef sol_status (*item_fn)(ctx *c, const cJSON *v, const char *ptr, void *item, void *arg);

static sol_status parse_array(ctx *c, const cJSON *root, const char *key, size_t item_size, void **items, int *n,
                              item_fn fn, void *arg)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, key);
    PTR(p, "", "%s", key);
    if (!v)
        return SOL_OK;
    if (!cJSON_IsArray(v))
        return fail(c, SOL_ERR_FORMAT, p, "must be an array");
    int count = cJSON_GetArraySize(v);
    if (count > SOL_SCENE_MAX_ITEMS)
        return fail(c, SOL_ERR_LIMIT, p, "more than %d items", SOL_SCENE_MAX_ITEMS);
    if (count == 0)
        return SOL_OK;
    *items = calloc((size_t)count, item_size);
    if (!*items)
        return fail(c, SOL_ERR_NO_MEMORY, p, "out of memory");
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        PTR(q, p, "%d", i);
        *n = i + 1; /* the partly filled item is freed with the rest on failure */
        TRY(fn(c, e, q, (char *)*items + (size_t)i * item_size, arg));
    }
    return SOL_OK;
}

static sol_status material_item(ctx *c, const cJSON *v, const char *ptr, void *item, void *arg)
{
    (void)arg;
    return parse_material(c, v, ptr, item);
}
static sol_status object_item(ctx *c, const cJSON *v, const char *ptr, void *item, void *arg)
{
    return parse_object(c, v, ptr, arg, item);
}
static sol_status light_item(ctx *c, const cJSON *v, const char *ptr, void *item, void *arg)
{
    return parse_light(c, v, ptr, *(const int *)arg, item);
}
static sol_status clip_item(ctx *c, const cJSON *v, const char *ptr, void *item, void *arg)
{
    static const char *const keys[] = {"min", "max", NULL};
    static const double m1[3] = {-1, -1, -1}, one[3] = {1, 1, 1};
    sol_scene_clip *b = item;
    (void)arg;
    TRY(need_object(c, v, ptr));
    TRY(check_keys(c, v, ptr, keys));
    TRY(get_vec(c, v, "min", ptr, m1, 3, -BIG, BIG, 0, b->min));
    TRY(get_vec(c, v, "max", ptr, one, 3, -BIG, BIG, 0, b->max));
    for (int i = 0; i < 3; ++i)
        if (!(b->max[i] > b->min[i])) {
            PTR(p, ptr, "max/%d", i);
            return fail(c, SOL_ERR_INVALID_ARG, p, "max must be > min (a clip volume needs a volume)");
        }
    return SOL_OK;
}

static const char *const root_keys[] = {"name", "camera", "materials", "objects", "lights", "clip_volumes",
                                        "ambient", "pipeline", "description", NULL};

static sol_status parse_root(ctx *c, const cJSON *root, sol_scene *s)
{
    static const double amb[3] = {0.03, 0.03, 0.03};
    TRY(need_object(c, root, ""));
    TRY(check_keys(c, root, "", root_keys));
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(root, "name");
    if (name) {
        if (!cJSON_IsString(name) || strlen(name->valuestring) >= SOL_SCENE_NAME_MAX)
            return fail(c, SOL_ERR_FORMAT, "/name", "must be a string of at most %d bytes", SOL_SCENE_NAME_MAX - 1);
        strcpy(s->name, name->valuestring);
    }
    const cJSON *desc = cJSON_GetObjectItemCaseSensitive(root, "description");
    if (desc && !cJSON_IsString(desc))
        return fail(c, SOL_ERR_FORMAT, "/description", "must be a string");
    TRY(parse_camera(c, cJSON_GetObjectItemCaseSensitive(root, "camera"), "/camera", &s->camera));
    TRY(get_vec(c, root, "ambient", "", amb, 3, 0, 1e6, 0, s->ambient));
    TRY(parse_pipeline(c, cJSON_GetObjectItemCaseSensitive(root, "pipeline"), "/pipeline", &s->pipeline));
    TRY(parse_array(c, root, "clip_volumes", sizeof *s->clips, (void **)&s->clips, &s->clip_count, clip_item, NULL));
    TRY(parse_array(c, root, "materials", sizeof *s->materials, (void **)&s->materials, &s->material_count,
                    material_item, NULL));
    TRY(parse_array(c, root, "objects", sizeof *s->objects, (void **)&s->objects, &s->object_count, object_item, s));
    TRY(parse_array(c, root, "lights", sizeof *s->lights, (void **)&s->lights, &s->light_count, light_item,
                    &s->clip_count));
    return SOL_OK;
}

void sol_scene_free(sol_scene *scene)
{
    if (!scene)
        return;
    for (int i = 0; i < scene->material_count; ++i) {
        sol_image_free(&scene->materials[i].albedo_texture.image);
        sol_image_free(&scene->materials[i].normal_map.image);
    }
    for (int i = 0; i < scene->light_count; ++i) {
        sol_image_free(&scene->lights[i].env_image);
        free(scene->lights[i].lobes);
    }
    for (int i = 0; i < scene->object_count; ++i)
        if (scene->objects[i].mesh) {
            sol_mesh_free(scene->objects[i].mesh);
            free(scene->objects[i].mesh);
        }
    free(scene->camera.frames);
    free(scene->materials);
    free(scene->objects);
    free(scene->lights);
    free(scene->clips);
    memset(scene, 0, sizeof *scene);
}

sol_status sol_scene_parse(const char *text, size_t len, const char *path, sol_scene *out, sol_scene_error *err)
{
    ctx c = {.file = path ? path : "<memory>", .err = err};
    if (!text || !out)
        return fail(&c, SOL_ERR_NULL_ARG, "", "no scene text");
    if (len > SOL_SCENE_MAX_FILE_BYTES)
        return fail(&c, SOL_ERR_LIMIT, "", "scene file larger than %zu bytes", SOL_SCENE_MAX_FILE_BYTES);
    if (path) {
        const char *slash = strrchr(path, '/');
        size_t n = slash ? (size_t)(slash - path) : 0;
        if (slash && n == 0)
            n = 1; /* "/scene.json": the root folder */
        if (n >= sizeof c.base)
            return fail(&c, SOL_ERR_LIMIT, "", "path too long");
        memcpy(c.base, path, n);
        c.base[n] = 0;
    }
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    if (!root) {
        sol_status st = fail(&c, SOL_ERR_FORMAT, "", "JSON syntax error");
        if (err) {
            int line = 1;
            size_t at = end && end >= text && end <= text + len ? (size_t)(end - text) : 0;
            for (size_t i = 0; i < at; ++i)
                line += text[i] == '\n';
            err->line = line;
            snprintf(err->message, sizeof err->message, "JSON syntax error at line %d", line);
        }
        return st;
    }
    sol_scene s;
    memset(&s, 0, sizeof s);
    snprintf(s.path, sizeof s.path, "%s", c.file);
    sol_status st = parse_root(&c, root, &s);
    cJSON_Delete(root);
    if (st != SOL_OK) {
        sol_scene_free(&s);
        return st;
    }
    if (!*s.name) { /* the file name without folder and extension */
        const char *b = strrchr(s.path, '/');
        b = b ? b + 1 : s.path;
        snprintf(s.name, sizeof s.name, "%.63s", b);
        char *dot = strrchr(s.name, '.');
        if (dot && dot != s.name)
            *dot = 0;
    }
    *out = s;
    return SOL_OK;
}

sol_status sol_scene_from_model(const char *path, sol_scene *out, sol_scene_error *err)
{
    ctx c = {.file = path ? path : "<null>", .err = err};
    if (!path || !out)
        return fail(&c, SOL_ERR_NULL_ARG, "", "no model path");
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(&c, SOL_ERR_IO, "", "cannot open: %s", strerror(errno));
    fclose(f);
    static const char empty_scene[] = "{}";
    sol_scene s;
    sol_status st = sol_scene_parse(empty_scene, sizeof empty_scene - 1, path, &s, NULL);
    if (st != SOL_OK)
        return fail(&c, st, "", "out of memory");
    s.objects = calloc(1, sizeof *s.objects);
    s.materials = calloc(1, sizeof *s.materials);
    s.lights = calloc(64 + 2, sizeof *s.lights);
    sol_mesh *m = calloc(1, sizeof *m);
    if (!s.objects || !s.materials || !s.lights || !m) {
        free(m);
        sol_scene_free(&s);
        return fail(&c, SOL_ERR_NO_MEMORY, "", "out of memory");
    }
    char msg[256];
    st = sol_mesh_load(path, m, msg, sizeof msg);
    if (st != SOL_OK) {
        free(m);
        sol_scene_free(&s);
        return fail(&c, st, "", "%s", msg);
    }
    s.object_count = 1;
    s.objects[0].kind = SOL_GEOM_MESH;
    s.objects[0].mesh = m;
    snprintf(s.objects[0].file, sizeof s.objects[0].file, "%s", path);
    s.material_count = 1;
    sol_scene_material *mat = &s.materials[0];
    snprintf(mat->name, sizeof mat->name, "model");
    mat->albedo[0] = mat->albedo[1] = mat->albedo[2] = 0.8;
    mat->specular = 0.04;
    mat->gloss = 0.5;
    mat->tangent[0] = 1;
    /* camera: the model's first camera, else one framing its bounds */
    sol_scene_camera *cam = &s.camera;
    double centre[3], radius = 0;
    for (int i = 0; i < 3; ++i) {
        centre[i] = 0.5 * (m->bmin[i] + m->bmax[i]);
        radius += 0.25 * (m->bmax[i] - m->bmin[i]) * (m->bmax[i] - m->bmin[i]);
    }
    radius = sqrt(radius) > 1e-6 ? sqrt(radius) : 1;
    if (m->has_camera) {
        memcpy(cam->position, m->cam_pos, sizeof cam->position);
        memcpy(cam->look_at, m->cam_look, sizeof cam->look_at);
        memcpy(cam->up, m->cam_up, sizeof cam->up);
        cam->fov_deg = m->cam_fov_deg;
    } else {
        static const double dir[3] = {0.45, 0.5, 1.0};
        double len = sqrt(sol_dot3(dir, dir));
        for (int i = 0; i < 3; ++i) {
            cam->position[i] = centre[i] + dir[i] / len * radius / sin(0.5 * cam->fov_deg * M_PI / 180) * 1.1;
            cam->look_at[i] = centre[i];
        }
    }
    cam->znear = radius * 1e-3;
    cam->zfar = radius * 1e3 + sqrt(sol_dot3(cam->position, cam->position)) * 10;
    /* lights: the model's punctual lights, else a sun; always a sky lobe */
    for (int i = 0; i < m->light_count; ++i) {
        sol_scene_light *l = &s.lights[s.light_count++];
        l->kind = m->lights[i].kind == 0 ? SOL_LIGHT_SUN : m->lights[i].kind == 2 ? SOL_LIGHT_SPOT : SOL_LIGHT_POINT;
        memcpy(l->position, m->lights[i].position, sizeof l->position);
        memcpy(l->direction, m->lights[i].direction, sizeof l->direction);
        memcpy(l->color, m->lights[i].color, sizeof l->color);
        double len = sqrt(sol_dot3(l->direction, l->direction));
        if (!(len > 0))
            l->direction[1] = -1, len = 1;
        for (int k = 0; k < 3; ++k)
            l->direction[k] /= len;
        l->intensity = 1;
        l->radius = 10 * radius;
        l->cone_deg = fmin(89, fmax(1, m->lights[i].cone_deg));
        l->shadows = 1;
        l->clip = -1;
    }
    if (m->light_count == 0) {
        sol_scene_light *l = &s.lights[s.light_count++];
        l->kind = SOL_LIGHT_SUN;
        l->color[0] = l->color[1] = l->color[2] = 1;
        l->intensity = 3;
        double d[3] = {-0.4, -1, -0.6}, len = sqrt(sol_dot3(d, d));
        for (int k = 0; k < 3; ++k)
            l->direction[k] = d[k] / len;
        l->shadows = 1;
        l->clip = -1;
    }
    sol_scene_light *sky = &s.lights[s.light_count++];
    sky->kind = SOL_LIGHT_ENV;
    sky->intensity = 1;
    sky->clip = -1;
    sky->lobes = calloc(1, sizeof *sky->lobes);
    if (!sky->lobes) {
        sol_scene_free(&s);
        return fail(&c, SOL_ERR_NO_MEMORY, "", "out of memory");
    }
    sky->lobe_count = 1;
    sky->lobes[0].axis[1] = 1;
    sky->lobes[0].sharpness = 1;
    sky->lobes[0].amplitude[0] = 0.25, sky->lobes[0].amplitude[1] = 0.3, sky->lobes[0].amplitude[2] = 0.4;
    *out = s;
    return SOL_OK;
}

sol_status sol_scene_load(const char *path, sol_scene *out, sol_scene_error *err)
{
    ctx c = {.file = path ? path : "<null>", .err = err};
    if (!path || !out)
        return fail(&c, SOL_ERR_NULL_ARG, "", "no scene path");
    if (has_suffix(path, ".gltf") || has_suffix(path, ".glb") || has_suffix(path, ".obj"))
        return sol_scene_from_model(path, out, err);
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(&c, SOL_ERR_IO, "", "cannot open: %s", strerror(errno));
    char *buf = malloc(SOL_SCENE_MAX_FILE_BYTES + 1);
    if (!buf) {
        fclose(f);
        return fail(&c, SOL_ERR_NO_MEMORY, "", "out of memory");
    }
    size_t n = fread(buf, 1, SOL_SCENE_MAX_FILE_BYTES + 1, f);
    int bad = ferror(f);
    fclose(f);
    sol_status st;
    if (bad)
        st = fail(&c, SOL_ERR_IO, "", "read error");
    else if (n > SOL_SCENE_MAX_FILE_BYTES)
        st = fail(&c, SOL_ERR_LIMIT, "", "scene file larger than %zu bytes", SOL_SCENE_MAX_FILE_BYTES);
    else
        st = sol_scene_parse(buf, n, path, out, err);
    free(buf);
    return st;
}
