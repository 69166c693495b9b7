/* scene_render.c - a small CPU deferred renderer with a reference path and an engine path.
 *
 * The order of a frame (engine path; the reference path is the same code with every effect in
 * its reference version and reference_supersample^2 samples per pixel):
 *   1. textures: albedo through 8-bit storage (T3-T7), BC1 (T1/T2), renormalisation (T1/T2);
 *      normal maps through BC5 (T8-T14). Done once per render.
 *   2. culling (M1): occluder depth max-downscaled to 4x4-pixel texels (coverage buffer), object bounds tested.
 *   3. G-buffer pass: a primary ray per pixel finds the surface; normal encoded in 24 bits (D3-D7);
 *      anisotropic materials replaced by their principal Phong lobe (D15/D16).
 *   4. obscurance (M3) from the depth buffer.
 *   5. light loop: sun, point, spot, SG environment lobes, lat-long environment maps (as SG lobes
 *      in the engine path, env-sg; integrated exactly in the reference); clip volumes (D13) for unshadowed
 *      lights; diffuse and specular sums stored in the light buffer format (D9, S9) with range
 *      scaling (D10).
 *   6. composition, temporal accumulation over the camera path (D18), exposure + tone map,
 *      grading through a LUT (M4), post AA (D17).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sol_brdf.h"
#include "sol_hdr.h"
#include "sol_lighting.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"
#include "scene_internal.h"
#include "sol_scene.h"
#include "sol_screen.h"
#include "sol_textures.h"

#define TEX_SIZE 256     /* procedural textures are baked at this size */
#define MAX_SG_LIGHTS 64 /* lighting lobes used for the D16 extraction */
#define EPS 1e-4

/* ---------------- small vector helpers ---------------- */

static void v_set(double o[3], double x, double y, double z) { o[0] = x, o[1] = y, o[2] = z; }
static void v_sub(double o[3], const double a[3], const double b[3])
{
    for (int i = 0; i < 3; ++i)
        o[i] = a[i] - b[i];
}
static void v_cross(double o[3], const double a[3], const double b[3])
{
    double t[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(o, t, sizeof t);
}
static double v_norm(double v[3])
{
    double l = sqrt(sol_dot3(v, v));
    if (l > 0)
        for (int i = 0; i < 3; ++i)
            v[i] /= l;
    return l;
}

/* ---------------- prepared scene ---------------- */

typedef struct prepared_material {
    sol_image albedo;     /* linear albedo texels as this path sees them (or empty) */
    sol_image normal_map; /* tangent-space normals as this path sees them (or empty) */
    double albedo_scale, normal_scale;
    int k;                /* SG lobes of the Ward NDF fit (engine, sg-lobes) */
    sol_sg lobes[16];     /* in the shading frame (x = tangent, z = normal) */
} prepared_material;

/* A mesh's textures as this path sees them (prepared like a material's), and the SG lobes of its
 * anisotropic materials (engine, sg-lobes). */
typedef struct prepared_mesh {
    sol_image *tex; /* per sol_mesh.tex */
    int *k;         /* per model material: lobes (0 = none) */
    sol_sg (*lobes)[16];
} prepared_mesh;

typedef struct frame {
    const sol_scene *s;
    int reference;
    unsigned on; /* bit e: effect e runs in its engine version */
    int width, height;
    double eye[3], fwd[3], right[3], up[3], focal;
    prepared_material *mats;
    prepared_mesh *meshes; /* per object (meshes only) */
    unsigned char *culled; /* per object */
    sol_lut3d lut;
    sol_grade grade;
    sol_render_stats *stats;
    float **irradiance; /* per light, per SG lobe: IRR_TABLE values of the clamped-cosine convolution */
    struct env_light *env; /* per light: its SG lobes as shaded, and a lat-long map's tables */
    const sol_bestfit_table *bestfit; /* D6: the baked best-fit table the shader uses (xyz-best-fit) */
    double light_scale;        /* D10: range scaling of the light buffer (see prepare) */
} frame;

#define IRR_TABLE 2049 /* irradiance of a unit SG lobe against cos(normal, axis) in [-1, 1] */

/* Irradiance of environment lobe j of light li at normal n, from the table built in prepare()
 * (sol_sg_cosine_convolve at IRR_TABLE cosines, linearly interpolated). */
static double lobe_irradiance(const struct frame *f, int li, int j, const double axis[3], const double n[3])
{
    const float *t = f->irradiance[li] + (size_t)j * IRR_TABLE;
    double x = (sol_dot3(axis, n) + 1) * 0.5 * (IRR_TABLE - 1);
    x = x < 0 ? 0 : x > IRR_TABLE - 1 ? IRR_TABLE - 1 : x;
    int i = (int)x;
    if (i >= IRR_TABLE - 1)
        return t[IRR_TABLE - 1];
    return t[i] + (x - i) * (t[i + 1] - t[i]);
}

static int fx(const frame *f, sol_effect e) { return (f->on >> e) & 1u; }

/* ---------------- lat-long environments ----------------
 * Convention (docs/scene-format.md): column u = 0.5 + atan2(x, -z) / (2 pi), row v = acos(y) / pi,
 * row 0 at the top (+y), so the middle of the image looks along -z. Texel (x, y) covers the
 * longitudes 2 pi [x/W - 1/2, (x+1)/W - 1/2] and the polar angles pi [y/H, (y+1)/H]; its solid
 * angle is (2 pi / W)(cos theta0 - cos theta1). */

#define ENV_WORK_TEXELS 32768 /* texels of the map the exact sums and the SG fit run over */
#define ENV_IRR_W 128         /* reference irradiance table: normals on a lat-long grid */
#define ENV_IRR_H 64

typedef struct env_light {
    const sol_scene_sg_lobe *lobes; /* the lobes the light is shaded with (SG light, or the env-sg fit) */
    int lobe_count;
    sol_scene_sg_lobe *fitted;      /* owned: the env-sg fit of a map */
    int fitted_count;
    const sol_image *map;           /* the scene's map (radiance before colour and intensity) */
    float *irr;                     /* reference: ENV_IRR_W x ENV_IRR_H x 3 irradiance (colour included) */
} env_light;

static void env_dir(double u, double v, double d[3])
{
    double phi = 2 * M_PI * (u - 0.5), th = M_PI * v;
    d[0] = sin(th) * sin(phi), d[1] = cos(th), d[2] = -sin(th) * cos(phi);
}

/* Bilinear lookup of an RGB lat-long image at direction d (wraps in u, clamps in v). */
static void env_lookup(const sol_image *im, int stride_rgb, const double d[3], double out[3])
{
    double y1 = d[1] < -1 ? -1 : d[1] > 1 ? 1 : d[1];
    double u = 0.5 + atan2(d[0], -d[2]) / (2 * M_PI), v = acos(y1) / M_PI;
    double x = u * im->width - 0.5, y = v * im->height - 0.5;
    double fx0 = floor(x), fy0 = floor(y), ax = x - fx0, ay = y - fy0;
    int x0 = (int)fx0, y0 = (int)fy0;
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            int xi = ((x0 + i) % im->width + im->width) % im->width;
            int yi = y0 + j < 0 ? 0 : y0 + j >= im->height ? im->height - 1 : y0 + j;
            double w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            const float *px = stride_rgb ? im->data + ((size_t)yi * im->width + xi) * 3 : sol_image_pixel(im, xi, yi);
            for (int c = 0; c < 3; ++c)
                out[c] += w * px[c];
        }
}

/* The map as cells to sum over, each with its solid angle, radiance (times `color`) and the
 * direction of its centre. The map is taken as piecewise constant over its texels. A small map's
 * texels are cut into s x s cells (s the largest leaving at most ENV_WORK_TEXELS cells: the
 * cosine and the SGs vary within a texel); a large map's b x b blocks are merged into one cell
 * (b the smallest leaving at most ENV_WORK_TEXELS), of the solid-angle-weighted mean radiance. */
static sol_status env_work(const sol_image *im, const double color[3], int *count, double **dir, double **omega,
                           double **rgb)
{
    int b = 1, sub = 1;
    while ((long)((im->width + b - 1) / b) * ((im->height + b - 1) / b) > ENV_WORK_TEXELS)
        ++b;
    if (b == 1)
        while ((long)im->width * im->height * (sub + 1) * (sub + 1) <= ENV_WORK_TEXELS)
            ++sub;
    int w = b > 1 ? (im->width + b - 1) / b : im->width * sub, h = b > 1 ? (im->height + b - 1) / b : im->height * sub;
    int n = w * h;
    double *D = calloc((size_t)n * 3, sizeof *D), *O = calloc((size_t)n, sizeof *O), *C = calloc((size_t)n * 3, sizeof *C);
    if (!D || !O || !C) {
        free(D), free(O), free(C);
        return SOL_ERR_NO_MEMORY;
    }
    if (b == 1) { /* cells of texels */
        for (int y = 0; y < h; ++y) {
            double om = 2 * M_PI / w * (cos(M_PI * y / h) - cos(M_PI * (y + 1.0) / h));
            for (int x = 0; x < w; ++x) {
                int k = y * w + x;
                const float *px = sol_image_pixel(im, x / sub, y / sub);
                O[k] = om;
                env_dir((x + 0.5) / w, (y + 0.5) / h, &D[3 * k]);
                for (int c = 0; c < 3; ++c)
                    C[3 * k + c] = px[c] * color[c];
            }
        }
    } else { /* blocks of texels */
        for (int y = 0; y < im->height; ++y) {
            double om = 2 * M_PI / im->width * (cos(M_PI * y / im->height) - cos(M_PI * (y + 1.0) / im->height));
            for (int x = 0; x < im->width; ++x) {
                int k = (y / b) * w + x / b;
                const float *px = sol_image_pixel(im, x, y);
                O[k] += om;
                for (int c = 0; c < 3; ++c)
                    C[3 * k + c] += om * px[c] * color[c];
            }
        }
        for (int k = 0; k < n; ++k) {
            int bx = k % w, by = k / w;
            double x0 = (double)bx * b, x1 = fmin((double)(bx + 1) * b, im->width);
            double y0 = (double)by * b, y1 = fmin((double)(by + 1) * b, im->height);
            env_dir(0.5 * (x0 + x1) / im->width, 0.5 * (y0 + y1) / im->height, &D[3 * k]);
            for (int c = 0; c < 3; ++c)
                C[3 * k + c] = O[k] > 0 ? C[3 * k + c] / O[k] : 0;
        }
    }
    *count = n, *dir = D, *omega = O, *rgb = C;
    return SOL_OK;
}

/* Reference diffuse: E(n) = sum over texels L omega max(n.w, 0) at the normals of an
 * ENV_IRR_W x ENV_IRR_H lat-long grid (looked up bilinearly; irradiance is smooth). */
static sol_status env_irradiance_table(const sol_image *im, const double color[3], float **out)
{
    int n;
    double *D, *O, *C;
    sol_status st = env_work(im, color, &n, &D, &O, &C);
    if (st != SOL_OK)
        return st;
    float *t = malloc(sizeof *t * ENV_IRR_W * ENV_IRR_H * 3);
    if (!t) {
        free(D), free(O), free(C);
        return SOL_ERR_NO_MEMORY;
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < ENV_IRR_H; ++y)
        for (int x = 0; x < ENV_IRR_W; ++x) {
            double nn[3], e[3] = {0, 0, 0};
            env_dir((x + 0.5) / ENV_IRR_W, (y + 0.5) / ENV_IRR_H, nn);
            for (int k = 0; k < n; ++k) {
                double c = nn[0] * D[3 * k] + nn[1] * D[3 * k + 1] + nn[2] * D[3 * k + 2];
                if (c > 0)
                    for (int q = 0; q < 3; ++q)
                        e[q] += C[3 * k + q] * O[k] * c;
            }
            for (int q = 0; q < 3; ++q)
                t[((size_t)y * ENV_IRR_W + x) * 3 + q] = (float)e[q];
        }
    free(D), free(O), free(C);
    *out = t;
    return SOL_OK;
}

/* env-sg (D15/D16 applied to the environment): K SG lobes with fixed axes (a spherical Fibonacci
 * set) and one sharpness 1.5 / (1 - cos(spacing)), spacing = sqrt(4 pi / K) (neighbouring lobes
 * overlap at exp(-1.5)); the RGB amplitudes minimise the solid-angle-weighted squared error over
 * the map's texels, kept >= 0 (projected Gauss-Seidel on the normal equations, a fixed number of
 * sweeps: deterministic). */
static sol_status env_fit_lobes(const sol_image *im, const double color[3], int k, sol_scene_sg_lobe **out)
{
    int n;
    double *D, *O, *C;
    sol_status st = env_work(im, color, &n, &D, &O, &C);
    if (st != SOL_OK)
        return st;
    sol_scene_sg_lobe *g = calloc((size_t)k, sizeof *g);
    double *A = calloc((size_t)k * k, sizeof *A), *B = calloc((size_t)k * 3, sizeof *B), *G = malloc(sizeof *G * (size_t)k);
    if (!g || !A || !B || !G) {
        free(D), free(O), free(C), free(g), free(A), free(B), free(G);
        return SOL_ERR_NO_MEMORY;
    }
    double spacing = sqrt(4 * M_PI / k), lambda = 1.5 / (1 - cos(fmin(spacing, M_PI)));
    const double golden = M_PI * (3 - sqrt(5.0));
    for (int j = 0; j < k; ++j) {
        double y = 1 - (2 * j + 1.0) / k, r = sqrt(fmax(0, 1 - y * y)), ph = golden * j;
        v_set(g[j].axis, r * cos(ph), y, r * sin(ph));
        g[j].sharpness = lambda;
    }
    for (int t = 0; t < n; ++t) {
        for (int j = 0; j < k; ++j)
            G[j] = exp(lambda * (sol_dot3(g[j].axis, &D[3 * t]) - 1));
        for (int i = 0; i < k; ++i) {
            for (int j = 0; j < k; ++j)
                A[i * k + j] += O[t] * G[i] * G[j];
            for (int q = 0; q < 3; ++q)
                B[i * 3 + q] += O[t] * G[i] * C[3 * t + q];
        }
    }
    for (int q = 0; q < 3; ++q)
        for (int sweep = 0; sweep < 400; ++sweep)
            for (int i = 0; i < k; ++i) {
                double r = B[i * 3 + q];
                for (int j = 0; j < k; ++j)
                    if (j != i)
                        r -= A[i * k + j] * g[j].amplitude[q];
                g[i].amplitude[q] = A[i * k + i] > 0 ? fmax(0, r / A[i * k + i]) : 0;
            }
    free(D), free(O), free(C), free(A), free(B), free(G);
    *out = g;
    return SOL_OK;
}

static void env_irradiance(const env_light *e, const double n[3], double out[3])
{
    sol_image t = {ENV_IRR_W, ENV_IRR_H, 3, e->irr};
    env_lookup(&t, 1, n, out);
}

/* ---------------- geometry: ray casting ---------------- */

typedef struct hit {
    double t;
    int object;
    double p[3], n[3]; /* position, geometric normal (facing the ray) */
    int mesh;          /* the object is a mesh: `mh` holds its hit */
    sol_mesh_hit mh;
} hit;

/* Height field y = base + A (1 + sin(2 pi f x) sin(2 pi f z)) / 2 in local x, z. */
static double hf_height(const sol_scene_object *o, double x, double z)
{
    double w = 2 * M_PI * o->radius;
    return o->a[1] + o->b[1] * 0.5 * (1 + sin(w * (x - o->a[0])) * sin(w * (z - o->a[2])));
}

static int intersect(const sol_scene_object *o, const double org[3], const double dir[3], double tmax, double *t_out,
                     double n[3], sol_mesh_hit *mh)
{
    switch (o->kind) {
    case SOL_GEOM_PLANE: {
        double nn[3] = {o->b[0], o->b[1], o->b[2]};
        v_norm(nn);
        double dn = sol_dot3(dir, nn);
        if (fabs(dn) < 1e-12)
            return 0;
        double d[3];
        v_sub(d, o->a, org);
        double t = sol_dot3(d, nn) / dn;
        if (!(t > EPS && t < tmax))
            return 0;
        if (o->radius > 0)
            for (int i = 0; i < 3; ++i)
                if (fabs(org[i] + t * dir[i] - o->a[i]) > o->radius)
                    return 0;
        *t_out = t;
        memcpy(n, nn, sizeof nn);
        return 1;
    }
    case SOL_GEOM_BOX: {
        double t0 = EPS, t1 = tmax;
        int axis0 = -1;
        for (int i = 0; i < 3; ++i) {
            double inv = 1.0 / dir[i];
            double a = (o->a[i] - org[i]) * inv, b = (o->b[i] - org[i]) * inv;
            if (a > b) {
                double tmp = a;
                a = b;
                b = tmp;
            }
            if (a > t0) {
                t0 = a;
                axis0 = i;
            }
            if (b < t1)
                t1 = b;
            if (t0 > t1)
                return 0;
        }
        if (axis0 < 0)
            return 0; /* the origin is inside the box */
        *t_out = t0;
        v_set(n, 0, 0, 0);
        n[axis0] = 1;
        return 1;
    }
    case SOL_GEOM_SPHERE: {
        double oc[3];
        v_sub(oc, org, o->a);
        double a = sol_dot3(dir, dir), b = sol_dot3(oc, dir), c = sol_dot3(oc, oc) - o->radius * o->radius;
        double disc = b * b - a * c; /* dir need not be unit length */
        if (disc < 0)
            return 0;
        double sq = sqrt(disc), t = (-b - sq) / a;
        if (t <= EPS)
            t = (-b + sq) / a;
        if (!(t > EPS && t < tmax))
            return 0;
        *t_out = t;
        for (int i = 0; i < 3; ++i)
            n[i] = (org[i] + t * dir[i] - o->a[i]) / o->radius;
        return 1;
    }
    case SOL_GEOM_HEIGHTFIELD: {
        /* ray march inside the bounding box, then bisection on the sign change */
        double lo[3] = {o->a[0], o->a[1], o->a[2]}, hi[3] = {o->a[0] + o->b[0], o->a[1] + o->b[1], o->a[2] + o->b[2]};
        double t0 = EPS, t1 = tmax;
        for (int i = 0; i < 3; ++i) {
            double inv = 1.0 / dir[i];
            double a = (lo[i] - org[i]) * inv, b = (hi[i] - org[i]) * inv;
            if (a > b) {
                double tmp = a;
                a = b;
                b = tmp;
            }
            t0 = fmax(t0, a);
            t1 = fmin(t1, b);
        }
        if (!(t0 <= t1))
            return 0;
        const int steps = 96;
        double dt = (t1 - t0) / steps, ta = t0;
        double fa = org[1] + ta * dir[1] - hf_height(o, org[0] + ta * dir[0], org[2] + ta * dir[2]);
        if (fa < 0)
            return 0; /* starts below the surface */
        for (int s = 1; s <= steps; ++s) {
            double tb = t0 + s * dt;
            double fb = org[1] + tb * dir[1] - hf_height(o, org[0] + tb * dir[0], org[2] + tb * dir[2]);
            if (fb <= 0) {
                for (int k = 0; k < 12; ++k) {
                    double tm = 0.5 * (ta + tb);
                    double fm = org[1] + tm * dir[1] - hf_height(o, org[0] + tm * dir[0], org[2] + tm * dir[2]);
                    if (fm > 0)
                        ta = tm;
                    else
                        tb = tm;
                }
                double x = org[0] + tb * dir[0] - o->a[0], z = org[2] + tb * dir[2] - o->a[2];
                double w = 2 * M_PI * o->radius, A = 0.5 * o->b[1];
                v_set(n, -A * w * cos(w * x) * sin(w * z), 1, -A * w * sin(w * x) * cos(w * z));
                v_norm(n);
                *t_out = tb;
                return 1;
            }
            ta = tb;
            fa = fb;
        }
        return 0;
    }
    case SOL_GEOM_MESH: /* triangles through the mesh's BVH */
        if (!o->mesh || !sol_mesh_intersect(o->mesh, org, dir, tmax, mh))
            return 0;
        *t_out = mh->t;
        memcpy(n, mh->n, sizeof mh->n);
        return 1;
    }
    return 0;
}

/* Closest hit along a ray; `skip_culled` leaves out culled objects (camera rays only). */
static int trace(const frame *f, const double org[3], const double dir[3], double tmax, int skip_culled, hit *h)
{
    const sol_scene *s = f->s;
    int found = 0;
    double best = tmax, n[3];
    for (int i = 0; i < s->object_count; ++i) {
        double t;
        sol_mesh_hit mh;
        if (skip_culled && f->culled && f->culled[i])
            continue;
        if (intersect(&s->objects[i], org, dir, best, &t, n, &mh)) {
            best = t;
            found = 1;
            h->object = i;
            memcpy(h->n, n, sizeof n);
            h->mesh = s->objects[i].kind == SOL_GEOM_MESH;
            if (h->mesh)
                h->mh = mh;
        }
    }
    if (!found)
        return 0;
    h->t = best;
    for (int i = 0; i < 3; ++i)
        h->p[i] = org[i] + best * dir[i];
    if (sol_dot3(h->n, dir) > 0)
        for (int i = 0; i < 3; ++i)
            h->n[i] = -h->n[i];
    return 1;
}

static int occluded(const frame *f, const double p[3], const double n[3], const double l[3], double dist)
{
    double org[3];
    for (int i = 0; i < 3; ++i)
        org[i] = p[i] + n[i] * 1e-3;
    hit h;
    return trace(f, org, l, dist, 0, &h);
}

/* Ray through screen point (sx, sy) of the current camera; dir has unit view-z component, so t is
 * the view depth. */
static void camera_ray(const frame *f, double sx, double sy, double dir[3])
{
    double x = (sx - 0.5 * f->width) / f->focal, y = (sy - 0.5 * f->height) / f->focal;
    for (int i = 0; i < 3; ++i)
        dir[i] = f->fwd[i] + x * f->right[i] - y * f->up[i];
}

/* ---------------- textures ---------------- */

static void tex_sample(const sol_image *img, double u, double v, double out[3])
{
    double x = (u - floor(u)) * img->width - 0.5, y = (v - floor(v)) * img->height - 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx_ = x - x0, fy = y - y0;
    out[0] = out[1] = out[2] = 0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            int xi = ((x0 + i) % img->width + img->width) % img->width;
            int yi = ((y0 + j) % img->height + img->height) % img->height;
            double w = (i ? fx_ : 1 - fx_) * (j ? fy : 1 - fy);
            const float *p = sol_image_pixel(img, xi, yi);
            for (int c = 0; c < 3; ++c)
                out[c] += w * p[img->channels >= 3 ? c : 0];
        }
}

/* Planar mapping by the dominant axis of the normal: texture coordinates and tangent frame. */
static void surface_frame(const double p[3], const double n[3], double uv[2], double t[3], double b[3])
{
    double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
    if (ay >= ax && ay >= az) {
        uv[0] = p[0], uv[1] = p[2];
        v_set(t, 1, 0, 0);
    } else if (ax >= az) {
        uv[0] = p[2], uv[1] = p[1];
        v_set(t, 0, 0, 1);
    } else {
        uv[0] = p[0], uv[1] = p[1];
        v_set(t, 1, 0, 0);
    }
    double d = sol_dot3(t, n);
    for (int i = 0; i < 3; ++i)
        t[i] -= d * n[i];
    v_norm(t);
    v_cross(b, n, t);
}

static sol_status bake_procedural(const sol_scene_texture *t, int normal_map, sol_image *out)
{
    sol_status st = sol_image_alloc(out, TEX_SIZE, TEX_SIZE, 3);
    if (st != SOL_OK)
        return st;
    for (int y = 0; y < TEX_SIZE; ++y)
        for (int x = 0; x < TEX_SIZE; ++x) {
            double u = (x + 0.5) / TEX_SIZE, v = (y + 0.5) / TEX_SIZE;
            float *p = sol_image_pixel(out, x, y);
            if (normal_map) { /* bumps: h = sin(8 pi u) sin(8 pi v) / (8 pi), n = (-A dh/du, -A dh/dv, 1) */
                double w = 8 * M_PI, a = t->low[0];
                double n[3] = {-a * cos(w * u) * sin(w * v), -a * sin(w * u) * cos(w * v), 1};
                v_norm(n);
                for (int c = 0; c < 3; ++c)
                    p[c] = (float)n[c];
            } else { /* checker of 8 x 8 cells with a soft gradient inside each cell */
                int cell = ((x / 32) + (y / 32)) & 1;
                double g = 0.75 + 0.25 * sin(M_PI * (x % 32 + 0.5) / 32) * sin(M_PI * (y % 32 + 0.5) / 32);
                for (int c = 0; c < 3; ++c)
                    p[c] = (float)(g * (cell ? t->high[c] : t->low[c]));
            }
        }
    return SOL_OK;
}

/* The albedo texture as the path sees it: float (reference), or through the planned effects. */
static sol_status prepare_albedo(frame *f, const sol_scene_texture *t, sol_image *out)
{
    sol_image img = {0};
    sol_status st;
    if (t->source == SOL_TEX_FILE) {
        st = sol_image_alloc(&img, t->image.width, t->image.height, 3);
        if (st != SOL_OK)
            return st;
        for (size_t i = 0; i < (size_t)img.width * img.height; ++i)
            for (int c = 0; c < 3; ++c) {
                double v = t->image.data[i * t->image.channels + (t->image.channels >= 3 ? c : 0)];
                img.data[i * 3 + c] = (float)(t->linear ? v : sol_srgb_decode(v));
            }
    } else if ((st = bake_procedural(t, 0, &img)) != SOL_OK)
        return st;
    if (t->bits != 8 || f->reference) {
        *out = img;
        return SOL_OK;
    }
    size_t n = (size_t)img.width * img.height * 3;
    sol_renorm range;
    int renorm = fx(f, SOL_FX_ALBEDO_RENORM);
    if (renorm) { /* T1/T2: stretch each channel's range to [0,1] before storage */
        f->stats->effect_runs[SOL_FX_ALBEDO_RENORM]++;
        if ((st = sol_renorm_fit(&img, &range)) != SOL_OK || (st = sol_renorm_apply(&range, &img)) != SOL_OK)
            goto fail;
    }
    sol_transfer curve = {SOL_TRANSFER_SRGB, 0};
    if (fx(f, SOL_FX_ALBEDO_STORAGE)) { /* T4: gamma or linear storage, 8-bit codes */
        f->stats->effect_runs[SOL_FX_ALBEDO_STORAGE]++;
        int storage = f->s->pipeline.albedo_storage;
        if (storage < 0) {
            sol_storage choice;
            if ((st = sol_storage_classify(&img, NULL, &choice, NULL)) != SOL_OK)
                goto fail;
            storage = choice == SOL_STORAGE_LINEAR;
        }
        if (storage == 1)
            curve.kind = SOL_TRANSFER_LINEAR;
    }
    for (size_t i = 0; i < n; ++i) { /* into storage space */
        double e;
        sol_transfer_encode(&curve, img.data[i], &e);
        img.data[i] = (float)e;
    }
    if (fx(f, SOL_FX_ALBEDO_BC1)) { /* T7: BC1 blocks (5:6:5 endpoints, 2-bit indices) */
        f->stats->effect_runs[SOL_FX_ALBEDO_BC1]++;
        uint8_t *blocks = malloc(sol_bc1_size(img.width, img.height));
        sol_image dec = {0};
        if (!blocks) {
            st = SOL_ERR_NO_MEMORY;
            goto fail;
        }
        st = sol_bc1_encode(&img, NULL, blocks);
        if (st == SOL_OK)
            st = sol_bc1_decode(blocks, img.width, img.height, &dec);
        free(blocks);
        if (st != SOL_OK)
            goto fail;
        sol_image_free(&img);
        img = dec;
    } else if (fx(f, SOL_FX_ALBEDO_STORAGE)) {
        for (size_t i = 0; i < n; ++i)
            img.data[i] = (float)(sol_unorm_encode(img.data[i], 8) / 255.0);
    }
    for (size_t i = 0; i < n; ++i) { /* the sampler's de-gamma */
        double l;
        sol_transfer_decode(&curve, img.data[i], &l);
        img.data[i] = (float)l;
    }
    if (renorm && (st = sol_renorm_undo(&range, &img)) != SOL_OK)
        goto fail;
    *out = img;
    return SOL_OK;
fail:
    sol_image_free(&img);
    return st;
}

static sol_status prepare_normal_map(frame *f, const sol_scene_texture *t, sol_image *out)
{
    sol_image img = {0};
    sol_status st;
    if (t->source == SOL_TEX_FILE) {
        st = sol_image_alloc(&img, t->image.width, t->image.height, 3);
        if (st != SOL_OK)
            return st;
        for (size_t i = 0; i < (size_t)img.width * img.height; ++i) {
            double n[3];
            for (int c = 0; c < 3; ++c)
                n[c] = 2.0 * t->image.data[i * t->image.channels + c] - 1.0;
            if (v_norm(n) == 0)
                v_set(n, 0, 0, 1);
            for (int c = 0; c < 3; ++c)
                img.data[i * 3 + c] = (float)n[c];
        }
    } else if ((st = bake_procedural(t, 1, &img)) != SOL_OK)
        return st;
    if (!f->reference && fx(f, SOL_FX_NORMAL_MAP_BC5) && img.width % 4 == 0 && img.height % 4 == 0) {
        f->stats->effect_runs[SOL_FX_NORMAL_MAP_BC5]++;
        sol_bc5_options o = {0};
        o.encoder = (sol_bc5_encoder)f->s->pipeline.normal_map_encoder;
        uint8_t *blocks = malloc((size_t)img.width * img.height);
        sol_image dec = {0};
        if (!blocks) {
            sol_image_free(&img);
            return SOL_ERR_NO_MEMORY;
        }
        st = sol_bc5_encode_image(&img, &o, blocks, NULL);
        if (st == SOL_OK)
            st = sol_bc5_decode_image(blocks, img.width, img.height, o.precision, &dec);
        free(blocks);
        sol_image_free(&img);
        if (st != SOL_OK)
            return st;
        img = dec;
    }
    *out = img;
    return SOL_OK;
}

/* ---------------- shading ---------------- */

typedef struct surface {
    int object, material;
    double p[3], ng[3], n[3]; /* position, geometric normal, shading normal (what the G-buffer holds) */
    double n_exact[3];        /* the float shading normal, before any encoding */
    double albedo[3];
    double exponent;          /* Phong exponent */
    double lobe_scale;        /* specular scale from the lobe extraction (1 otherwise) */
    int exact_ward;           /* shade with the exact anisotropic BRDF (reference of sg-lobes) */
    int ggx;                  /* that BRDF is anisotropic GGX (else Ward) */
    double ax, ay;            /* Ward roughness pair */
    int quad_base;            /* first R2 point of this sample's quadrature (reference supersampling) */
    double t_axis[3], b_axis[3];
    double depth;             /* view z */
} surface;

static double phong_exponent(const sol_scene_material *m)
{
    return m->phong_exponent > 0 ? m->phong_exponent : pow(2.0, 13.0 * m->gloss);
}

/* One punctual light at p: direction to it, its irradiance at normal incidence, distance. */
static int light_at(const sol_scene_light *l, const double p[3], double dir[3], double e[3], double *dist)
{
    double k = l->intensity;
    if (l->kind == SOL_LIGHT_SUN) {
        for (int i = 0; i < 3; ++i)
            dir[i] = -l->direction[i];
        *dist = 1e30;
    } else {
        v_sub(dir, l->position, p);
        double d = v_norm(dir);
        if (d >= l->radius || d == 0)
            return 0;
        double w = 1 - (d / l->radius) * (d / l->radius);
        k *= w * w / (d * d + 1e-2); /* inverse square, windowed to the light's radius */
        if (l->kind == SOL_LIGHT_SPOT) {
            double c = -sol_dot3(dir, l->direction), c0 = cos(l->cone_deg * M_PI / 180);
            double c1 = cos(fmax(0, l->cone_deg - 5) * M_PI / 180);
            double s = (c - c0) / fmax(c1 - c0, 1e-9);
            s = s < 0 ? 0 : s > 1 ? 1 : s;
            k *= s * s * (3 - 2 * s);
        }
        *dist = d;
    }
    for (int i = 0; i < 3; ++i)
        e[i] = l->color[i] * k;
    return k > 0;
}

static int inside_clip(const sol_scene_clip *c, const double p[3])
{
    for (int i = 0; i < 3; ++i)
        if (p[i] < c->min[i] - 1e-3 || p[i] > c->max[i] + 1e-3)
            return 0;
    return 1;
}

/* The lights as SG lobes over light directions, for the lobe extraction (D16): each environment
 * lobe as it is, each punctual light as a sharp lobe (sharpness 1000) of the same irradiance. */
static int lights_as_sgs(const frame *f, const double p[3], sol_sg *out)
{
    int n = 0;
    for (int i = 0; i < f->s->light_count && n < MAX_SG_LIGHTS; ++i) {
        const sol_scene_light *l = &f->s->lights[i];
        if (l->kind == SOL_LIGHT_ENV) { /* SG lobes, or the env-sg fit of a map */
            const env_light *el = &f->env[i];
            const sol_scene_sg_lobe *lb = el->lobes ? el->lobes : el->fitted;
            int count = el->lobes ? el->lobe_count : el->fitted_count;
            for (int j = 0; j < count && n < MAX_SG_LIGHTS; ++j, ++n) {
                memcpy(out[n].axis, lb[j].axis, sizeof out[n].axis);
                out[n].sharpness = lb[j].sharpness;
                out[n].amplitude = l->intensity * sol_luminance(lb[j].amplitude);
            }
        } else {
            double dir[3], e[3], d;
            if (!light_at(l, p, dir, e, &d))
                continue;
            memcpy(out[n].axis, dir, sizeof dir);
            out[n].sharpness = 1000;
            out[n].amplitude = sol_luminance(e) * 1000 / (2 * M_PI);
            ++n;
        }
    }
    return n;
}

/* Smith's Lambda of anisotropic GGX for direction w in the shading frame (Heitz 2014,
 * "Understanding the masking-shadowing function in microfacet-based BRDFs", JCGT 3(2), eq. 86). */
static double ggx_aniso_lambda(const double w[3], double ax, double ay)
{
    double z2 = w[2] * w[2];
    if (z2 <= 0)
        return 1e300;
    double a2 = (ax * ax * w[0] * w[0] + ay * ay * w[1] * w[1]) / z2;
    return 0.5 * (-1 + sqrt(1 + a2));
}

/* Anisotropic GGX microfacet BRDF with rho_s = 1 (no Fresnel, like Ward's): D G2 / (4 n.v n.l),
 * D(h) = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2) (Heitz 2014 eq. 85; with ax = ay it is
 * sol_ggx_ndf), height-correlated G2 = 1 / (1 + Lambda(v) + Lambda(l)) (Heitz 2014 eq. 99).
 * v, l in the shading frame (x = tangent, z = normal); zero below either horizon. */
static double ggx_aniso_brdf(const double v[3], const double l[3], double ax, double ay)
{
    if (v[2] <= 0 || l[2] <= 0)
        return 0;
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    if (!(hl > 0))
        return 0;
    for (int i = 0; i < 3; ++i)
        h[i] /= hl;
    double q = h[0] * h[0] / (ax * ax) + h[1] * h[1] / (ay * ay) + h[2] * h[2];
    double d = 1 / (M_PI * ax * ay * q * q);
    double g = 1 / (1 + ggx_aniso_lambda(v, ax, ay) + ggx_aniso_lambda(l, ax, ay));
    return d * g / (4 * v[2] * l[2]);
}

/* Specular BRDF value times cos for light direction l (per unit F0). */
static double specular(const surface *sf, const double v[3], const double l[3])
{
    double nl = sol_dot3(sf->n, l);
    if (nl <= 0)
        return 0;
    if (sf->exact_ward) { /* the Ward or GGX BRDF in the shading frame (rho_s = 1) */
        double vl[3] = {sol_dot3(v, sf->t_axis), sol_dot3(v, sf->b_axis), sol_dot3(v, sf->n)};
        double ll[3] = {sol_dot3(l, sf->t_axis), sol_dot3(l, sf->b_axis), nl};
        if (sf->ggx)
            return ggx_aniso_brdf(vl, ll, sf->ax, sf->ay) * nl;
        return sol_ward_brdf(vl, ll, sf->ax, sf->ay) * nl;
    }
    double r[3];
    double vn = sol_dot3(v, sf->n);
    for (int i = 0; i < 3; ++i)
        r[i] = 2 * vn * sf->n[i] - v[i];
    return sf->lobe_scale * sol_phong_normalized(sol_dot3(r, l), sf->exponent) * nl;
}

/* The G-buffer of one camera ray: surface, material, normal as the path stores it. */
/* The anisotropic frame from a tangent direction: t projected into the surface (Gram-Schmidt
 * against sf->n) becomes the t axis and n x t the b axis; a tangent (nearly) along the normal
 * leaves the frame as it was. */
static void set_tangent(surface *sf, const double tangent[3])
{
    double t[3], d = sol_dot3(tangent, sf->n);
    for (int i = 0; i < 3; ++i)
        t[i] = tangent[i] - d * sf->n[i];
    if (v_norm(t) > 1e-6) {
        memcpy(sf->t_axis, t, sizeof t);
        v_cross(sf->b_axis, sf->n, t);
    }
}

static int gbuffer_sample(const frame *f, double sx, double sy, surface *sf)
{
    double dir[3];
    camera_ray(f, sx, sy, dir);
    hit h;
    if (!trace(f, f->eye, dir, f->s->camera.zfar, 1, &h))
        return 0;
    const sol_scene_object *o = &f->s->objects[h.object];
    const sol_scene_material *m = &f->s->materials[o->material];
    const prepared_material *pm = &f->mats[o->material];
    memset(sf, 0, sizeof *sf);
    sf->object = h.object;
    sf->material = o->material;
    sf->depth = h.t;
    memcpy(sf->p, h.p, sizeof h.p);
    memcpy(sf->ng, h.n, sizeof h.n);
    double uv[2];
    surface_frame(h.p, h.n, uv, sf->t_axis, sf->b_axis);
    memcpy(sf->n, h.n, sizeof h.n);
    /* a mesh: its tangent frame (tangent orthogonalised against the normal, bitangent n x t with
     * the sign of the mesh's), its material's textures at its texture coordinates */
    const prepared_mesh *pmesh = h.mesh && f->meshes ? &f->meshes[h.object] : NULL;
    const sol_mesh_material *mm = NULL;
    int mi = h.mesh ? h.mh.material : -1;
    if (h.mesh && mi >= 0 && o->mesh && mi < o->mesh->mat_count)
        mm = &o->mesh->mats[mi];
    int has_tan = 0;
    if (h.mesh) {
        double mt[3], mb[3];
        memcpy(mt, h.mh.tangent, sizeof mt);
        double d = sol_dot3(mt, h.n);
        for (int i = 0; i < 3; ++i)
            mt[i] -= d * h.n[i];
        if (v_norm(mt) > 1e-9) {
            v_cross(mb, h.n, mt);
            if (sol_dot3(mb, h.mh.bitangent) < 0)
                for (int i = 0; i < 3; ++i)
                    mb[i] = -mb[i];
            memcpy(sf->t_axis, mt, sizeof mt);
            memcpy(sf->b_axis, mb, sizeof mb);
            has_tan = 1;
        }
    }
    if (mm && mm->normal_tex >= 0 && has_tan && pmesh && pmesh->tex[mm->normal_tex].data) {
        double tn[3]; /* assimp's v is up; the image's row 0 is the top */
        tex_sample(&pmesh->tex[mm->normal_tex], h.mh.uv[0], 1 - h.mh.uv[1], tn);
        tn[0] *= mm->normal_scale; /* glTF normalTexture.scale: (x s, y s, z), renormalised below */
        tn[1] *= mm->normal_scale;
        for (int i = 0; i < 3; ++i)
            sf->n[i] = tn[0] * sf->t_axis[i] + tn[1] * sf->b_axis[i] + tn[2] * h.n[i];
        if (v_norm(sf->n) == 0 || sol_dot3(sf->n, h.n) <= 0)
            memcpy(sf->n, h.n, sizeof h.n);
    }
    if (pm->normal_map.data && !h.mesh) {
        double tn[3];
        tex_sample(&pm->normal_map, uv[0] * pm->normal_scale, uv[1] * pm->normal_scale, tn);
        for (int i = 0; i < 3; ++i)
            sf->n[i] = tn[0] * sf->t_axis[i] + tn[1] * sf->b_axis[i] + tn[2] * h.n[i];
        if (v_norm(sf->n) == 0 || sol_dot3(sf->n, h.n) <= 0)
            memcpy(sf->n, h.n, sizeof h.n);
    }
    memcpy(sf->albedo, m->albedo, sizeof sf->albedo);
    if (h.mesh) { /* the base colour factor times the base-colour texture */
        memcpy(sf->albedo, h.mh.color, sizeof sf->albedo);
        if (mm && mm->base_tex >= 0 && pmesh && pmesh->tex[mm->base_tex].data) {
            double a[3];
            tex_sample(&pmesh->tex[mm->base_tex], h.mh.uv[0], 1 - h.mh.uv[1], a);
            for (int i = 0; i < 3; ++i)
                sf->albedo[i] *= a[i];
        }
    } else if (pm->albedo.data) {
        double a[3];
        tex_sample(&pm->albedo, uv[0] * pm->albedo_scale, uv[1] * pm->albedo_scale, a);
        for (int i = 0; i < 3; ++i)
            sf->albedo[i] = a[i]; /* a texture replaces the material's albedo */
    }
    sf->exponent = phong_exponent(m);
    sf->lobe_scale = 1;
    if (m->aniso != SOL_ANISO_NONE) {
        /* the tangent of the material, projected into the surface */
        set_tangent(sf, m->tangent);
        sf->ax = m->roughness[0];
        sf->ay = m->roughness[1];
        sf->exact_ward = 1;
        sf->ggx = m->aniso == SOL_ANISO_GGX;
    }
    const sol_sg *ndf_lobes = pm->lobes;
    int ndf_k = pm->k;
    if (mm && mm->aniso) {
        /* KHR_materials_anisotropy: anisotropic GGX with alpha_t = mix(alpha, 1, strength^2) along
         * the tangent rotated by anisotropyRotation towards the bitangent, alpha_b = alpha */
        double c = cos(mm->aniso_rotation), sn = sin(mm->aniso_rotation), t[3];
        for (int i = 0; i < 3; ++i)
            t[i] = c * sf->t_axis[i] + sn * sf->b_axis[i];
        set_tangent(sf, t);
        double st2 = mm->aniso_strength * mm->aniso_strength;
        sf->ax = fmax(1e-3, mm->alpha + (1 - mm->alpha) * st2);
        sf->ay = fmax(1e-3, mm->alpha);
        sf->exact_ward = 1;
        sf->ggx = 1;
        ndf_lobes = pmesh && pmesh->k ? pmesh->lobes[mi] : NULL;
        ndf_k = pmesh && pmesh->k ? pmesh->k[mi] : 0;
    }
    (void)has_tan;
    memcpy(sf->n_exact, sf->n, sizeof sf->n);
    if (sf->exact_ward && !f->reference && fx(f, SOL_FX_SG_LOBES) && ndf_k > 0) {
        /* D15/D16: the NDF as SG lobes (world frame), lit by the lights as SGs; the principal Phong
         * lobe replaces the material in the G-buffer (normal, exponent). */
        sol_sg ndf[16], lights[MAX_SG_LIGHTS];
        for (int k = 0; k < ndf_k; ++k) {
            ndf[k] = ndf_lobes[k];
            for (int i = 0; i < 3; ++i)
                ndf[k].axis[i] = ndf_lobes[k].axis[0] * sf->t_axis[i] + ndf_lobes[k].axis[1] * sf->b_axis[i] +
                                 ndf_lobes[k].axis[2] * sf->n[i];
        }
        int nl = lights_as_sgs(f, sf->p, lights);
        double v[3];
        for (int i = 0; i < 3; ++i)
            v[i] = -dir[i];
        v_norm(v);
        sol_phong_lobe lobe;
        if (nl > 0 && sol_extract_phong_lobe(ndf, ndf_k, lights, nl, v, &lobe) == SOL_OK &&
            sol_dot3(lobe.normal, h.n) > 0) {
            memcpy(sf->n, lobe.normal, sizeof lobe.normal);
            v_norm(sf->n);
            sf->exponent = fmax(1, lobe.glossiness);
            sf->exact_ward = 0;
        }
    }
    if (!f->reference && fx(f, SOL_FX_GBUFFER_NORMALS)) { /* D3-D7: 24-bit normal */
        uint32_t code;
        double dec[3];
        sol_normal_method mth = (sol_normal_method)f->s->pipeline.gbuffer_normals;
        if (f->bestfit) { /* the shader's path: the baked 512^2 8-bit table, bilinear (D6) */
            if (sol_normal_encode_bestfit_table(f->bestfit, SOL_TABLE_BILINEAR, sf->n, &code) == SOL_OK &&
                sol_normal_decode(SOL_NORMAL_XYZ_NORMALIZED, code, dec) == SOL_OK)
                memcpy(sf->n, dec, sizeof dec);
        } else if (sol_normal_encode(mth, sf->n, &code) == SOL_OK && sol_normal_decode(mth, code, dec) == SOL_OK)
            memcpy(sf->n, dec, sizeof dec);
    }
    return 1;
}

/* The light loop at one G-buffer sample: diffuse irradiance and specular radiance (per unit F0). */
static void light_loop(const frame *f, const surface *sf, const double v[3], double diff[3], double spec[3])
{
    const sol_scene *s = f->s;
    diff[0] = diff[1] = diff[2] = spec[0] = spec[1] = spec[2] = 0;
    for (int li = 0; li < s->light_count; ++li) {
        const sol_scene_light *l = &s->lights[li];
        if (l->kind == SOL_LIGHT_ENV && !f->env[li].lobes) { /* a lat-long map, integrated exactly */
            const env_light *el = &f->env[li];
            double e[3], sp[3] = {0, 0, 0}, L[3];
            env_irradiance(el, sf->n, e);
            /* specular: R2 points, 32 per sample in the supersampled reference (each sample taking
             * the next 32), 128 in the engine path; the exact anisotropic BRDF over uniform sphere
             * directions, the normalised Phong lobe by importance sampling it (pdf (n+1)/(2 pi)
             * (r.l)^n, so each direction weighs (n+2)/(n+1) n.l) */
            const int count = f->reference ? 32 : 128;
            if (sf->exact_ward) {
                for (int k = 0; k < count; ++k) {
                    double u, w, d[3];
                    sol_r2_point((uint64_t)(sf->quad_base + k), &u, &w);
                    sol_sphere_uniform(u, w, d);
                    double b = specular(sf, v, d);
                    if (b > 0) {
                        env_lookup(el->map, 0, d, L);
                        for (int c = 0; c < 3; ++c)
                            sp[c] += L[c] * b;
                    }
                }
                for (int c = 0; c < 3; ++c)
                    sp[c] *= 4 * M_PI / count;
            } else {
                double r[3], t[3], b[3], vn = sol_dot3(v, sf->n), ne = sf->exponent;
                for (int i = 0; i < 3; ++i)
                    r[i] = 2 * vn * sf->n[i] - v[i];
                v_norm(r);
                v_set(t, fabs(r[0]) < 0.9 ? 1 : 0, fabs(r[0]) < 0.9 ? 0 : 1, 0);
                double d0 = sol_dot3(t, r);
                for (int i = 0; i < 3; ++i)
                    t[i] -= d0 * r[i];
                v_norm(t);
                v_cross(b, r, t);
                for (int k = 0; k < count; ++k) {
                    double u, w, d[3];
                    sol_r2_point((uint64_t)(sf->quad_base + k), &u, &w);
                    double ca = pow(1 - u, 1 / (ne + 1)), sa = sqrt(fmax(0, 1 - ca * ca)), ph = 2 * M_PI * w;
                    for (int i = 0; i < 3; ++i)
                        d[i] = sa * cos(ph) * t[i] + sa * sin(ph) * b[i] + ca * r[i];
                    double nl = sol_dot3(d, sf->n);
                    if (nl > 0) {
                        env_lookup(el->map, 0, d, L);
                        for (int c = 0; c < 3; ++c)
                            sp[c] += L[c] * nl;
                    }
                }
                for (int c = 0; c < 3; ++c)
                    sp[c] *= sf->lobe_scale * (ne + 2) / (ne + 1) / count;
            }
            for (int c = 0; c < 3; ++c) {
                diff[c] += l->intensity * e[c];
                spec[c] += l->intensity * l->color[c] * sp[c];
            }
            continue;
        }
        if (l->kind == SOL_LIGHT_ENV) {
            const sol_scene_sg_lobe *lobes = f->env[li].lobes;
            for (int j = 0; j < f->env[li].lobe_count; ++j) {
                sol_sg g = {{lobes[j].axis[0], lobes[j].axis[1], lobes[j].axis[2]}, lobes[j].sharpness, 1};
                double e = l->intensity * lobe_irradiance(f, li, j, g.axis, sf->n);
                double sp;
                if (sf->exact_ward) {
                    /* quadrature over R2 directions on the sphere: 128 per pixel in the engine
                     * path; in the supersampled reference 32 per sample, each sample taking the
                     * next 32 points of the sequence (288 per pixel at 3x3) */
                    const int count = f->reference ? 32 : 128;
                    sp = 0;
                    for (int k = 0; k < count; ++k) {
                        double u, w, d[3];
                        sol_r2_point((uint64_t)(sf->quad_base + k), &u, &w);
                        sol_sphere_uniform(u, w, d);
                        sp += sol_sg_eval(&g, d) * specular(sf, v, d);
                    }
                    sp *= l->intensity * 4 * M_PI / count;
                } else { /* the Phong lobe as an SG about the reflection vector, times n.r */
                    double r[3], vn = sol_dot3(v, sf->n);
                    for (int i = 0; i < 3; ++i)
                        r[i] = 2 * vn * sf->n[i] - v[i];
                    sol_sg ph = {{r[0], r[1], r[2]}, sf->exponent, sol_phong_norm_factor(sf->exponent)};
                    sp = l->intensity * sf->lobe_scale * sol_sg_inner_product(&g, &ph) * fmax(0, sol_dot3(r, sf->n));
                }
                for (int c = 0; c < 3; ++c) {
                    diff[c] += e * lobes[j].amplitude[c];
                    spec[c] += sp * lobes[j].amplitude[c];
                }
            }
            continue;
        }
        double dir[3], e[3], dist;
        if (!light_at(l, sf->p, dir, e, &dist) || sol_dot3(sf->ng, dir) <= 0)
            continue;
        /* visibility: the reference traces a shadow ray for every light (exact lighting). The
         * engine traces only lights with shadows; a clipped light uses its clip volume (D13, in
         * its reference version a shadow ray); other lights are unshadowed deferred lights */
        int clipped = l->clip >= 0 && !l->shadows;
        if (clipped && !f->reference && fx(f, SOL_FX_CLIP_VOLUMES)) {
            if (!inside_clip(&s->clips[l->clip], sf->p))
                continue;
        } else if (l->shadows || clipped || f->reference) {
            if (occluded(f, sf->p, sf->ng, dir, dist))
                continue;
        }
        double nl = fmax(0, sol_dot3(sf->n, dir));
        double sp = specular(sf, v, dir);
        for (int c = 0; c < 3; ++c) {
            diff[c] += e[c] * nl;
            spec[c] += e[c] * sp;
        }
    }
}

/* One light-buffer value through the configured format (D9, S9), with range scaling (D10). */
static double store_light(const frame *f, double v, double scale)
{
    float x = (float)(v * scale);
    switch (f->s->pipeline.light_buffer) {
    case SOL_LB_R11G11B10F:
        x = sol_uf11_to_float(sol_uf11_from_float(x));
        break;
    case SOL_LB_RGB10:
        x = sol_rgb10_scaled_decode(sol_rgb10_scaled_encode(x));
        break;
    default:
        break;
    }
    return x / scale;
}

static void store_light3(const frame *f, double rgb[3], double scale)
{
    if (f->s->pipeline.light_buffer == SOL_LB_RGBM) {
        float in[3] = {(float)(rgb[0] * scale), (float)(rgb[1] * scale), (float)(rgb[2] * scale)}, out[3];
        uint8_t code[4];
        sol_rgbm_encode(in, f->s->pipeline.light_range, code);
        sol_rgbm_decode(code, f->s->pipeline.light_range, out);
        for (int c = 0; c < 3; ++c)
            rgb[c] = out[c] / scale;
        return;
    }
    for (int c = 0; c < 3; ++c)
        rgb[c] = store_light(f, rgb[c], scale);
}

/* Shades one sample: the colour (linear radiance) the composition gives, with obscurance `ao`. */
static void shade(const frame *f, const surface *sf, double ao, double rgb[3])
{
    const sol_scene_material *m = &f->s->materials[sf->material];
    double v[3];
    v_sub(v, f->eye, sf->p);
    v_norm(v);
    double diff[3], spec[3];
    light_loop(f, sf, v, diff, spec);
    if (!f->reference && fx(f, SOL_FX_LIGHT_BUFFER)) {
        double scale = fx(f, SOL_FX_RANGE_SCALING) ? f->light_scale : 1.0;
        store_light3(f, diff, scale);
        store_light3(f, spec, scale);
    }
    for (int c = 0; c < 3; ++c)
        rgb[c] = sf->albedo[c] / M_PI * diff[c] + m->specular * spec[c] + sf->albedo[c] * f->s->ambient[c] * ao;
}

/* ---------------- camera, culling, obscurance ---------------- */

static void set_camera(frame *f, const double eye[3])
{
    const sol_scene_camera *c = &f->s->camera;
    memcpy(f->eye, eye, sizeof f->eye);
    v_sub(f->fwd, c->look_at, c->position); /* a path translates the camera: orientation kept */
    v_norm(f->fwd);
    v_cross(f->right, c->up, f->fwd);
    v_norm(f->right);
    v_cross(f->up, f->fwd, f->right);
    f->focal = 0.5 * f->height / tan(0.5 * c->fov_deg * M_PI / 180);
}

static sol_camera screen_camera(const frame *f)
{
    sol_camera c = {f->width, f->height, f->focal, f->s->camera.znear, f->s->camera.zfar};
    return c;
}

/* M1: occluder depth at every pixel centre, downscaled with the max filter to the coverage
 * buffer's 4x4-pixel texels (sol_cbuffer_build, block 4: conservative for every pixel centre the
 * camera rays use), and each box's screen bounds tested against it; culled boxes are left out of
 * the camera rays. */
static sol_status cull(frame *f)
{
    const sol_scene *s = f->s;
    int w = f->width, h = f->height;
    float *depth = malloc((size_t)w * h * sizeof *depth);
    if (!depth)
        return SOL_ERR_NO_MEMORY;
    memset(f->culled, 0, (size_t)s->object_count);
#pragma omp parallel for schedule(dynamic, 4)
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double dir[3];
            camera_ray(f, x + 0.5, y + 0.5, dir);
            hit hh;
            depth[(size_t)y * w + x] = trace(f, f->eye, dir, s->camera.zfar, 0, &hh) ? (float)hh.t : (float)s->camera.zfar;
        }
    sol_cbuffer cb;
    sol_cbuffer_options o = {4, SOL_DOWNSCALE_MAX};
    sol_status st = sol_cbuffer_build(depth, w, h, &o, &cb);
    free(depth);
    if (st != SOL_OK)
        return st;
    for (int i = 0; i < s->object_count; ++i) {
        const sol_scene_object *ob = &s->objects[i];
        if (ob->kind != SOL_GEOM_BOX)
            continue;
        sol_screen_bounds b = {1e300, 1e300, -1e300, -1e300, 1e300};
        int ok = 1;
        for (int k = 0; k < 8 && ok; ++k) {
            double p[3] = {(k & 1) ? ob->b[0] : ob->a[0], (k & 2) ? ob->b[1] : ob->a[1], (k & 4) ? ob->b[2] : ob->a[2]};
            double d[3];
            v_sub(d, p, f->eye);
            double z = sol_dot3(d, f->fwd);
            if (z < s->camera.znear) {
                ok = 0;
                break;
            }
            double sx = 0.5 * f->width + f->focal * sol_dot3(d, f->right) / z;
            double sy = 0.5 * f->height - f->focal * sol_dot3(d, f->up) / z;
            b.x0 = fmin(b.x0, sx), b.x1 = fmax(b.x1, sx), b.y0 = fmin(b.y0, sy), b.y1 = fmax(b.y1, sy);
            b.znear = fmin(b.znear, z);
        }
        int occ = 0;
        if (ok && sol_cbuffer_test(&cb, &b, -1, &occ, NULL) == SOL_OK && occ) {
            f->culled[i] = 1;
            f->stats->objects_culled++;
        }
    }
    sol_cbuffer_free(&cb);
    return SOL_OK;
}

/* ---------------- one frame ---------------- */

typedef struct frame_buffers {
    float *hdr;     /* width * height * 3 */
    float *depth;   /* view z, zfar for background */
    float *normals; /* width * height * 3 */
    float *ao;
} frame_buffers;

/* Renders one frame at screen offset (jx, jy) (engine) or supersampled (reference). `ao_frame`
 * selects the obscurance samples (temporal accumulation uses new ones every frame). */
static sol_status render_frame(frame *f, double jx, double jy, unsigned ao_frame, frame_buffers *fb)
{
    const sol_scene *s = f->s;
    const int W = f->width, H = f->height;
    const size_t n = (size_t)W * H;
    if (!f->reference && fx(f, SOL_FX_CULLING)) {
        f->stats->effect_runs[SOL_FX_CULLING]++;
        sol_status st = cull(f);
        if (st != SOL_OK)
            return st;
    } else if (f->culled) {
        memset(f->culled, 0, (size_t)s->object_count);
    }
    /* the per-pixel effects run inside the passes below; they are counted once per pass */
    static const sol_effect per_pixel[] = {SOL_FX_GBUFFER_NORMALS, SOL_FX_LIGHT_BUFFER, SOL_FX_RANGE_SCALING,
                                           SOL_FX_CLIP_VOLUMES, SOL_FX_ENV_SG};
    for (size_t k = 0; k < sizeof per_pixel / sizeof per_pixel[0]; ++k)
        if (!f->reference && fx(f, per_pixel[k]))
            f->stats->effect_runs[per_pixel[k]]++;
    /* depth and normals at the pixel centres (jittered in the engine path). With one sample per
     * pixel and no obscurance (which needs the whole depth buffer first) the same pass shades. */
    const int ss = f->reference ? s->pipeline.reference_supersample : 1;
    const int one_pass = ss == 1 && !s->pipeline.ssao;
#pragma omp parallel for schedule(dynamic, 4)
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            surface sf;
            size_t i = (size_t)y * W + x;
            if (one_pass)
                fb->hdr[3 * i] = fb->hdr[3 * i + 1] = fb->hdr[3 * i + 2] = 0;
            if (gbuffer_sample(f, x + 0.5 + jx, y + 0.5 + jy, &sf)) {
                fb->depth[i] = (float)sf.depth;
                for (int c = 0; c < 3; ++c)
                    fb->normals[3 * i + c] = (float)sf.n[c];
                if (one_pass) {
                    double rgb[3];
                    shade(f, &sf, 1.0, rgb);
                    for (int c = 0; c < 3; ++c)
                        fb->hdr[3 * i + c] = (float)rgb[c];
                }
            } else {
                fb->depth[i] = (float)s->camera.zfar;
                fb->normals[3 * i] = fb->normals[3 * i + 1] = fb->normals[3 * i + 2] = 0;
            }
        }
    /* obscurance (M3) */
    for (size_t i = 0; i < n; ++i)
        fb->ao[i] = 1;
    if (s->pipeline.ssao) {
        sol_camera cam = screen_camera(f);
        sol_vo_options vo = {s->pipeline.ssao_radius, s->pipeline.ssao_samples, ao_frame, 0};
        sol_status st = SOL_OK;
        if (f->reference || !fx(f, SOL_FX_SSAO)) {
            vo.samples = 256;
            vo.frame = 0;
            st = sol_vo_compute(&cam, fb->depth, &vo, fb->ao);
        } else {
            f->stats->effect_runs[SOL_FX_SSAO]++;
            if (s->pipeline.ssao_half_res && W > 1 && H > 1) {
                int hw = (W + 1) / 2, hh = (H + 1) / 2;
                float *hd = malloc((size_t)hw * hh * sizeof *hd), *hv = malloc((size_t)hw * hh * sizeof *hv);
                sol_camera half = {hw, hh, f->focal / 2, cam.znear, cam.zfar};
                st = !hd || !hv ? SOL_ERR_NO_MEMORY : sol_depth_half(fb->depth, W, H, hd);
                if (st == SOL_OK)
                    st = sol_vo_compute(&half, hd, &vo, hv);
                if (st == SOL_OK)
                    st = sol_bilateral_upsample(hv, hd, fb->depth, W, H, fb->ao);
                free(hd);
                free(hv);
            } else {
                st = sol_vo_compute(&cam, fb->depth, &vo, fb->ao);
            }
        }
        if (st != SOL_OK)
            return st;
        for (size_t i = 0; i < n; ++i) /* obscurance 0.5 on a flat floor: visibility 2 (1 - vo) */
            fb->ao[i] = fb->depth[i] >= (float)s->camera.zfar ? 1.0f : fminf(1.0f, 2.0f * (1.0f - fb->ao[i]));
    }
    if (one_pass)
        return SOL_OK;
    /* lighting and composition */
#pragma omp parallel for schedule(dynamic, 2)
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + x;
            double sum[3] = {0, 0, 0};
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    surface sf;
                    double px = ss == 1 ? x + 0.5 + jx : x + (sx + 0.5) / ss, py = ss == 1 ? y + 0.5 + jy : y + (sy + 0.5) / ss;
                    double rgb[3] = {0, 0, 0};
                    if (gbuffer_sample(f, px, py, &sf)) {
                        sf.quad_base = 32 * (sy * ss + sx);
                        shade(f, &sf, fb->ao[i], rgb);
                    }
                    for (int c = 0; c < 3; ++c)
                        sum[c] += rgb[c];
                }
            for (int c = 0; c < 3; ++c)
                fb->hdr[3 * i + c] = (float)(sum[c] / (ss * ss));
        }
    return SOL_OK;
}

/* ---------------- display ---------------- */

static void grade_fn(const double in[3], double out[3], void *ctx) { sol_grade_apply(ctx, in, out); }

static sol_status to_display(frame *f, const float *hdr, sol_image *display)
{
    const sol_scene_pipeline *pl = &f->s->pipeline;
    const size_t n = (size_t)f->width * f->height;
    int lut = pl->has_look && !f->reference && fx(f, SOL_FX_LUT_GRADING);
    if (lut)
        f->stats->effect_runs[SOL_FX_LUT_GRADING]++;
#pragma omp parallel for schedule(static)
    for (long i = 0; i < (long)n; ++i) {
        double c[3], g[3];
        for (int k = 0; k < 3; ++k)
            c[k] = sol_srgb_encode(sol_tonemap_apply((sol_tonemap)pl->tonemap, hdr[3 * i + k] * pl->exposure));
        if (lut)
            sol_lut3d_apply(&f->lut, SOL_LUT_TRILINEAR, c, g);
        else if (pl->has_look)
            sol_grade_apply(&f->grade, c, g);
        else
            memcpy(g, c, sizeof c);
        for (int k = 0; k < 3; ++k)
            display->data[3 * i + k] = (float)fmin(1, fmax(0, g[k]));
    }
    if (pl->aa == SOL_AA_POST && !f->reference && fx(f, SOL_FX_POST_AA)) {
        f->stats->effect_runs[SOL_FX_POST_AA]++;
        sol_image out;
        sol_status st = sol_postaa_filter(display, NULL, &out);
        if (st != SOL_OK)
            return st;
        sol_image_free(display);
        *display = out;
    }
    return SOL_OK;
}

/* ---------------- the public entry points ---------------- */

void sol_render_result_free(sol_render_result *r)
{
    if (!r)
        return;
    sol_image_free(&r->hdr);
    sol_image_free(&r->display);
    sol_image_free(&r->normals);
}

static void free_frame(frame *f)
{
    if (f->mats)
        for (int i = 0; i < f->s->material_count; ++i) {
            sol_image_free(&f->mats[i].albedo);
            sol_image_free(&f->mats[i].normal_map);
        }
    free(f->mats);
    if (f->meshes)
        for (int i = 0; i < f->s->object_count; ++i) {
            if (f->meshes[i].tex && f->s->objects[i].mesh)
                for (int t = 0; t < f->s->objects[i].mesh->tex_count; ++t)
                    sol_image_free(&f->meshes[i].tex[t]);
            free(f->meshes[i].tex);
            free(f->meshes[i].k);
            free(f->meshes[i].lobes);
        }
    free(f->meshes);
    free(f->culled);
    if (f->irradiance)
        for (int i = 0; i < f->s->light_count; ++i)
            free(f->irradiance[i]);
    free(f->irradiance);
    if (f->env)
        for (int i = 0; i < f->s->light_count; ++i) {
            free(f->env[i].fitted);
            free(f->env[i].irr);
        }
    free(f->env);
    sol_lut3d_free(&f->lut);
}

/* D15: K isotropic SG lobes fitted to the Ward NDF of the pair (Ceres); fit K at offset K(K-1)/2.
 * A GGX material gets the lobes of the Ward NDF with the same roughness pair (the talk fits Ward,
 * D15); GGX's longer tail that they miss is part of this effect's error against the reference,
 * which shades the exact GGX BRDF. */
static sol_status fit_ndf_lobes(frame *f, double ax, double ay, sol_sg out[16], int *k_out)
{
    int k = f->s->pipeline.sg_lobes;
    sol_sg *all = malloc(sizeof(sol_sg) * (size_t)(k * (k + 1) / 2));
    sol_sg_fit_error *errs = malloc(sizeof *errs * (size_t)k);
    sol_status st = !all || !errs ? SOL_ERR_NO_MEMORY : sol_ward_sg_fit(ax, ay, k, NULL, all, errs, NULL);
    if (st == SOL_OK) {
        memcpy(out, all + k * (k - 1) / 2, sizeof(sol_sg) * (size_t)k);
        *k_out = k;
        f->stats->effect_runs[SOL_FX_SG_LOBES]++;
    }
    free(all);
    free(errs);
    return st;
}

/* The IRR_TABLE values of lobe_irradiance for a unit SG lobe of sharpness `lambda`, into t. They
 * depend on the sharpness only, so the tables of the first IRR_CACHE sharpnesses met are kept for
 * the process (reachable until it ends) and copied from there: every render of a scene used to
 * compute them again (2049 quadratures per lobe, serial). A new one is computed in parallel (each
 * value on its own, so identical for any thread count). */
enum { IRR_CACHE = 64 };
static void irradiance_table(double lambda, float *t)
{
    static struct {
        double lambda;
        float *t;
    } cache[IRR_CACHE];
    static int count;
    int found = 0;
#pragma omp critical(sol_scene_irradiance)
    {
        for (int i = 0; i < count && !found; ++i)
            if (cache[i].lambda == lambda) {
                memcpy(t, cache[i].t, sizeof *t * IRR_TABLE);
                found = 1;
            }
    }
    if (found)
        return;
    sol_sg g = {{0, 0, 1}, lambda, 1};
#pragma omp parallel for schedule(static)
    for (int k = 0; k < IRR_TABLE; ++k) {
        double c = -1 + 2.0 * k / (IRR_TABLE - 1), n[3] = {sqrt(fmax(0, 1 - c * c)), 0, c};
        t[k] = (float)sol_sg_cosine_convolve(&g, n);
    }
#pragma omp critical(sol_scene_irradiance)
    {
        int present = 0;
        for (int i = 0; i < count; ++i)
            present |= cache[i].lambda == lambda;
        float *copy = present || count == IRR_CACHE ? NULL : malloc(sizeof *copy * IRR_TABLE);
        if (copy) { /* no memory: simply not kept */
            memcpy(copy, t, sizeof *copy * IRR_TABLE);
            cache[count].lambda = lambda;
            cache[count++].t = copy;
        }
    }
}

/* D6's baked table (512^2, 8-bit) depends on nothing in the scene, so it is built once, by the
 * first render that needs it, and shared read-only by every render after (it took ~0.1 s of
 * every engine render). It stays allocated until the process ends (reachable, not a leak); a
 * failed build leaves it unbuilt and the next render tries again. */
static sol_status shared_bestfit(const sol_bestfit_table **out)
{
    static sol_bestfit_table table;
    sol_status st = SOL_OK;
#pragma omp critical(sol_scene_bestfit)
    {
        if (!table.scale)
            st = sol_bestfit_table_build(512, 8, &table);
    }
    if (st == SOL_OK)
        *out = &table;
    return st;
}

static sol_status prepare(frame *f)
{
    const sol_scene *s = f->s;
    sol_status st;
    f->mats = calloc((size_t)(s->material_count > 0 ? s->material_count : 1), sizeof *f->mats);
    f->culled = calloc((size_t)(s->object_count > 0 ? s->object_count : 1), 1);
    f->meshes = calloc((size_t)(s->object_count > 0 ? s->object_count : 1), sizeof *f->meshes);
    f->irradiance = calloc((size_t)(s->light_count > 0 ? s->light_count : 1), sizeof *f->irradiance);
    f->env = calloc((size_t)(s->light_count > 0 ? s->light_count : 1), sizeof *f->env);
    if (!f->mats || !f->culled || !f->irradiance || !f->env || !f->meshes)
        return SOL_ERR_NO_MEMORY;
    for (int li = 0; li < s->light_count; ++li) {
        const sol_scene_light *l = &s->lights[li];
        env_light *el = &f->env[li];
        if (l->kind != SOL_LIGHT_ENV)
            continue;
        if (l->env_image.data) {
            el->map = &l->env_image;
            /* the engine path fits the lobes (the lights as SGs of the D16 extraction use them too);
             * it shades with them when env-sg runs, else with the map like the reference */
            if (!f->reference &&
                (st = env_fit_lobes(&l->env_image, l->color, s->pipeline.env_lobes, &el->fitted)) != SOL_OK)
                return st;
            el->fitted_count = el->fitted ? s->pipeline.env_lobes : 0;
            if (!f->reference && fx(f, SOL_FX_ENV_SG)) {
                f->stats->effect_runs[SOL_FX_ENV_SG]++;
                el->lobes = el->fitted;
                el->lobe_count = el->fitted_count;
            } else if ((st = env_irradiance_table(&l->env_image, l->color, &el->irr)) != SOL_OK)
                return st;
        } else {
            el->lobes = l->lobes;
            el->lobe_count = l->lobe_count;
        }
        if (el->lobe_count == 0)
            continue;
        float *t = malloc(sizeof *t * (size_t)el->lobe_count * IRR_TABLE);
        if (!t)
            return SOL_ERR_NO_MEMORY;
        f->irradiance[li] = t;
        for (int j = 0; j < el->lobe_count; ++j)
            irradiance_table(el->lobes[j].sharpness, t + (size_t)j * IRR_TABLE);
    }
    for (int i = 0; i < s->material_count; ++i) {
        const sol_scene_material *m = &s->materials[i];
        prepared_material *pm = &f->mats[i];
        if (m->albedo_texture.source != SOL_TEX_NONE) {
            pm->albedo_scale = m->albedo_texture.scale;
            if ((st = prepare_albedo(f, &m->albedo_texture, &pm->albedo)) != SOL_OK)
                return st;
        }
        if (m->normal_map.source != SOL_TEX_NONE) {
            pm->normal_scale = m->normal_map.scale;
            if ((st = prepare_normal_map(f, &m->normal_map, &pm->normal_map)) != SOL_OK)
                return st;
        }
        if (m->aniso != SOL_ANISO_NONE && !f->reference && fx(f, SOL_FX_SG_LOBES) &&
            (st = fit_ndf_lobes(f, m->roughness[0], m->roughness[1], pm->lobes, &pm->k)) != SOL_OK)
            return st;
    }
    /* meshes: their textures through the same effects as a material's (a base-colour texture is
     * an sRGB albedo texture of its PNG's bits, a normal texture a linear normal map), and the SG
     * lobes of their KHR_materials_anisotropy materials */
    for (int i = 0; i < s->object_count; ++i) {
        const sol_mesh *mesh = s->objects[i].mesh;
        if (s->objects[i].kind != SOL_GEOM_MESH || !mesh)
            continue;
        prepared_mesh *pmesh = &f->meshes[i];
        pmesh->tex = calloc((size_t)(mesh->tex_count > 0 ? mesh->tex_count : 1), sizeof *pmesh->tex);
        pmesh->k = calloc((size_t)(mesh->mat_count > 0 ? mesh->mat_count : 1), sizeof *pmesh->k);
        pmesh->lobes = calloc((size_t)(mesh->mat_count > 0 ? mesh->mat_count : 1), sizeof *pmesh->lobes);
        if (!pmesh->tex || !pmesh->k || !pmesh->lobes)
            return SOL_ERR_NO_MEMORY;
        for (int t = 0; t < mesh->tex_count; ++t) {
            sol_scene_texture *tt = malloc(sizeof *tt);
            if (!tt)
                return SOL_ERR_NO_MEMORY;
            memset(tt, 0, sizeof *tt);
            tt->source = SOL_TEX_FILE;
            tt->bits = mesh->tex[t].bits;
            tt->linear = mesh->tex[t].normal;
            tt->scale = 1;
            tt->image = mesh->tex[t].image; /* borrowed: read only */
            st = mesh->tex[t].normal ? prepare_normal_map(f, tt, &pmesh->tex[t]) : prepare_albedo(f, tt, &pmesh->tex[t]);
            free(tt);
            if (st != SOL_OK)
                return st;
        }
        for (int k = 0; k < mesh->mat_count; ++k) {
            const sol_mesh_material *mm = &mesh->mats[k];
            if (!mm->aniso || f->reference || !fx(f, SOL_FX_SG_LOBES))
                continue;
            double ax = fmax(1e-3, mm->alpha + (1 - mm->alpha) * mm->aniso_strength * mm->aniso_strength);
            if ((st = fit_ndf_lobes(f, ax, fmax(1e-3, mm->alpha), pmesh->lobes[k], &pmesh->k[k])) != SOL_OK)
                return st;
        }
    }
    /* D10 range scaling: the light buffer's window ends where the display saturates. The tone map
     * reaches the last display code (254.5/255, sRGB) at x_white = T^-1(y); a pixel's radiance is
     * at most the stored irradiance / pi (albedo <= 1), so irradiance up to pi x_white / exposure
     * matters and is mapped onto the format's largest value (RGBM range, 2 for RGB10, 65024 for
     * R11G11B10F's 11-bit floats). Everything darker keeps the format's relative precision. */
    f->light_scale = 1.0;
    if (s->pipeline.light_buffer != SOL_LB_FLOAT) {
        double y = sol_srgb_decode(254.5 / 255.0), x_white;
        double top = s->pipeline.light_buffer == SOL_LB_RGBM    ? s->pipeline.light_range
                     : s->pipeline.light_buffer == SOL_LB_RGB10 ? 2.0
                                                                : 65024.0;
        if (sol_tonemap_inverse((sol_tonemap)s->pipeline.tonemap, y, &x_white) == SOL_OK && x_white > 0)
            f->light_scale = top * s->pipeline.exposure / (M_PI * x_white);
        else
            f->light_scale = s->pipeline.exposure;
    }
    if (!f->reference && fx(f, SOL_FX_GBUFFER_NORMALS) && s->pipeline.gbuffer_normals == SOL_NORMAL_XYZ_BEST_FIT &&
        (st = shared_bestfit(&f->bestfit)) != SOL_OK)
        return st;
    if (s->pipeline.has_look) {
        sol_grade *g = &f->grade;
        g->saturation = s->pipeline.look_saturation;
        g->contrast = s->pipeline.look_contrast;
        g->hue_degrees = s->pipeline.look_hue_deg;
        memcpy(g->gain, s->pipeline.look_gain, sizeof g->gain);
        if (!f->reference && fx(f, SOL_FX_LUT_GRADING) &&
            (st = sol_lut3d_bake(s->pipeline.lut_size, grade_fn, g, &f->lut)) != SOL_OK)
            return st;
    }
    return SOL_OK;
}

sol_status sol_scene_render(const sol_scene *scene, const sol_scene_plan *plan, const sol_render_options *options,
                            sol_render_result *out, sol_render_stats *stats)
{
    if (!scene || !plan || !out)
        return SOL_ERR_NULL_ARG;
    sol_render_options opt = {0};
    if (options)
        opt = *options;
    frame f;
    memset(&f, 0, sizeof f);
    f.s = scene;
    f.reference = opt.reference != 0;
    f.width = opt.width > 0 ? opt.width : scene->camera.width;
    f.height = opt.height > 0 ? opt.height : scene->camera.height;
    if (opt.width < 0 || opt.height < 0 || (int64_t)f.width * f.height > SOL_SCENE_MAX_PIXELS)
        return SOL_ERR_INVALID_ARG;
    for (int e = 0; e < SOL_FX_COUNT; ++e)
        if (plan->run[e] && !((opt.reference_effects >> e) & 1u))
            f.on |= 1u << e;
    if (f.reference)
        f.on = 0;
    sol_render_stats st_local;
    memset(&st_local, 0, sizeof st_local);
    f.stats = &st_local;
    double t0 = omp_get_wtime();
    clock_t c0 = clock();
    const size_t n = (size_t)f.width * f.height;
    sol_render_result r;
    memset(&r, 0, sizeof r);
    frame_buffers fb = {0};
    sol_history hist[2];
    memset(hist, 0, sizeof hist);
    sol_status st = prepare(&f);
    double t1 = omp_get_wtime();
    clock_t c1 = clock();
    st_local.prepare_seconds = t1 - t0;
    if (st == SOL_OK && (st = sol_image_alloc(&r.hdr, f.width, f.height, 3)) == SOL_OK &&
        (st = sol_image_alloc(&r.display, f.width, f.height, 3)) == SOL_OK)
        st = sol_image_alloc(&r.normals, f.width, f.height, 3);
    if (st == SOL_OK) {
        fb.hdr = r.hdr.data;
        fb.normals = r.normals.data;
        fb.depth = malloc(n * sizeof *fb.depth);
        fb.ao = malloc(n * sizeof *fb.ao);
        if (!fb.depth || !fb.ao)
            st = SOL_ERR_NO_MEMORY;
    }
    const sol_scene_camera *cam = &scene->camera;
    int temporal = !f.reference && fx(&f, SOL_FX_TEMPORAL);
    if (st == SOL_OK && temporal) {
        /* D18: every frame of the path, jittered, accumulated by reprojection; the result is the
         * history of the last frame */
        if ((st = sol_history_alloc(&hist[0], f.width, f.height, 3)) == SOL_OK)
            st = sol_history_alloc(&hist[1], f.width, f.height, 3);
        sol_temporal_options to = {0};
        to.edge_tolerant = 1;
        for (int k = 0; k < cam->frame_count && st == SOL_OK; ++k) {
            double jx = 0, jy = 0;
            if (scene->pipeline.aa == SOL_AA_TEMPORAL)
                sol_jitter_offset((unsigned)k, &jx, &jy);
            set_camera(&f, cam->frames[k]);
            f.stats->effect_runs[SOL_FX_TEMPORAL]++;
            if ((st = render_frame(&f, jx, jy, (unsigned)k, &fb)) != SOL_OK)
                break;
            double motion[3] = {0, 0, 0}, d[3];
            if (k > 0) {
                v_sub(d, cam->frames[k], cam->frames[k - 1]);
                motion[0] = sol_dot3(d, f.right);
                motion[1] = -sol_dot3(d, f.up);
                motion[2] = sol_dot3(d, f.fwd);
            }
            sol_camera sc = screen_camera(&f);
            sol_history *prev = &hist[k & 1], *next = &hist[(k + 1) & 1];
            st = sol_temporal_accumulate(&sc, fb.depth, fb.hdr, motion, &to, prev, next);
        }
        if (st == SOL_OK)
            memcpy(fb.hdr, hist[cam->frame_count & 1].values, n * 3 * sizeof *fb.hdr);
        st_local.frames = cam->frame_count;
    } else if (st == SOL_OK) {
        set_camera(&f, cam->frame_count > 0 ? cam->frames[cam->frame_count - 1] : cam->position);
        st = render_frame(&f, 0, 0, 0, &fb);
        st_local.frames = 1;
    }
    if (st == SOL_OK)
        st = to_display(&f, fb.hdr, &r.display);
    sol_history_free(&hist[0]);
    sol_history_free(&hist[1]);
    free(fb.depth);
    free(fb.ao);
    free_frame(&f);
    if (st != SOL_OK) {
        sol_render_result_free(&r);
        return st;
    }
    st_local.seconds = omp_get_wtime() - t1;
    st_local.cpu_seconds = (double)(clock() - c1) / CLOCKS_PER_SEC;
    (void)c0;
    *out = r;
    if (stats)
        *stats = st_local;
    return SOL_OK;
}

sol_status sol_render_compare(const sol_render_result *a, const sol_render_result *b, sol_render_error *out)
{
    if (!a || !b || !out || !a->display.data || !b->display.data)
        return SOL_ERR_NULL_ARG;
    if (a->display.width != b->display.width || a->display.height != b->display.height)
        return SOL_ERR_INVALID_ARG;
    const long n = (long)a->display.width * a->display.height;
    /* The rows are cut into CHUNKS fixed runs; each run is summed in pixel order and the runs are
     * added in order afterwards, so the sums do not depend on the thread count (an OpenMP
     * reduction's order would). */
    enum { CHUNKS = 64 };
    double part[CHUNKS][6];
    long part_nn[CHUNKS];
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < CHUNKS; ++k) {
        double r_sq = 0, r_mx = 0, r_de = 0, r_demax = 0, r_ang = 0, r_angmax = 0;
        long r_nn = 0;
        for (long i = n * k / CHUNKS; i < n * (k + 1) / CHUNKS; ++i) {
            const float *pa = a->display.data + 3 * i, *pb = b->display.data + 3 * i;
            double ca[3], cb[3], la[3], lb[3];
            int same = 1;
            for (int c = 0; c < 3; ++c) {
                ca[c] = pa[c];
                cb[c] = pb[c];
                double d = 255.0 * ca[c] - 255.0 * cb[c];
                r_sq += d * d;
                r_mx = fmax(r_mx, fabs(d));
                same &= memcmp(&pa[c], &pb[c], sizeof pa[c]) == 0 && isfinite(ca[c]);
            }
            /* equal finite colours: the same Lab (sol_srgb_to_lab clamps to [0,1]) and
             * sol_ciede2000(x, x) = +0 exactly (every difference term is 0 and S_L, S_C, S_H >= 1),
             * so the conversions are skipped */
            double e = 0;
            if (!same) {
                sol_srgb_to_lab(ca, la);
                sol_srgb_to_lab(cb, lb);
                e = sol_ciede2000(la, lb);
            }
            r_de += e;
            r_demax = fmax(r_demax, e);
            double na[3], nb[3];
            for (int c = 0; c < 3; ++c) {
                na[c] = a->normals.data[3 * i + c];
                nb[c] = b->normals.data[3 * i + c];
            }
            if (sol_dot3(na, na) > 0 && sol_dot3(nb, nb) > 0) {
                double g = sol_angle3(na, nb) * 180 / M_PI;
                r_ang += g;
                r_angmax = fmax(r_angmax, g);
                ++r_nn;
            }
        }
        part[k][0] = r_sq, part[k][1] = r_mx, part[k][2] = r_de, part[k][3] = r_demax;
        part[k][4] = r_ang, part[k][5] = r_angmax, part_nn[k] = r_nn;
    }
    double sq = 0, mx = 0, de = 0, demax = 0, ang = 0, angmax = 0;
    long nn = 0;
    for (int k = 0; k < CHUNKS; ++k) {
        sq += part[k][0];
        mx = fmax(mx, part[k][1]);
        de += part[k][2];
        demax = fmax(demax, part[k][3]);
        ang += part[k][4];
        angmax = fmax(angmax, part[k][5]);
        nn += part_nn[k];
    }
    out->rms_code = sqrt(sq / (3.0 * n));
    out->max_code = mx;
    out->de2000_mean = de / n;
    out->de2000_max = demax;
    out->normal_mean_deg = nn ? ang / nn : 0;
    out->normal_max_deg = angmax;
    return SOL_OK;
}
