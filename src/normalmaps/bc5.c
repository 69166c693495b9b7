/* bc5.c - 3Dc (BC5) blocks: decoding with z rebuilt, the angular error of a block (T10), joint
 * index choice, and the exact joint anchor search by branch and bound (T10/T11). */
#include "normalmaps_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Relative slack on lower bounds: the bounds hold exactly in real arithmetic; the slack covers
 * rounding so that no candidate better than the incumbent is ever pruned. */
#define BOUND_SLACK 1e-9

sol_status sol_nm_unit_normals(const double in[16][3], double out[16][3])
{
    for (int p = 0; p < 16; ++p) {
        if (!isfinite(in[p][0]) || !isfinite(in[p][1]) || !isfinite(in[p][2]))
            return SOL_ERR_NONFINITE;
        double len = sqrt(in[p][0] * in[p][0] + in[p][1] * in[p][1] + in[p][2] * in[p][2]);
        if (!(len > 1e-150 && len < 1e150)) { /* the squares under- or overflowed: scale first */
            double m = fmax(fmax(fabs(in[p][0]), fabs(in[p][1])), fabs(in[p][2]));
            if (!(m > 0.0))
                return SOL_ERR_ZERO_LENGTH;
            double s[3] = {in[p][0] / m, in[p][1] / m, in[p][2] / m};
            len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            for (int c = 0; c < 3; ++c)
                out[p][c] = s[c] / len;
            continue;
        }
        for (int c = 0; c < 3; ++c)
            out[p][c] = in[p][c] / len;
    }
    return SOL_OK;
}

/* The decoded normal for components a, b: z = sqrt(max(0, 1 - a^2 - b^2)) (talk: z reconstructed). */
static inline double rebuild_z(double a, double b)
{
    double zz = 1.0 - a * a - b * b;
    return zz > 0.0 ? sqrt(zz) : 0.0;
}

/* Angle in radians between the decoded (a, b, z) and the unit source n (sol_angle3: atan2 form). */
static inline double decoded_angle(double a, double b, const double n[3])
{
    double u[3] = {a, b, rebuild_z(a, b)};
    return sol_angle3(u, n);
}

/* The index pair (i, j) of palettes a, b whose decoded normal is closest in angle to n.
 * Candidates are compared by the cosine of their angle. A candidate with x^2 + y^2 <= 1 decodes to
 * a unit vector whose chord to n satisfies chord^2 >= (a-nx)^2 + (b-ny)^2; one with z clamped has
 * chord^2 >= nz^2; either bound above the best chord^2 so far skips the candidate. */
static double best_pixel(const double a[8], const double b[8], const double n[3], int *bi, int *bj)
{
    double da[8], db[8];
    int i0 = 0, j0 = 0;
    for (int k = 0; k < 8; ++k) {
        da[k] = (a[k] - n[0]) * (a[k] - n[0]);
        db[k] = (b[k] - n[1]) * (b[k] - n[1]);
        i0 = da[k] < da[i0] ? k : i0;
        j0 = db[k] < db[j0] ? k : j0;
    }
    double nz2 = n[2] * n[2];
    int best_i = -1, best_j = -1;
    double best_cos = -INFINITY, best_chord2 = INFINITY;
    for (int pass = 0; pass < 2; ++pass) {
        for (int i = 0; i < 8; ++i) {
            if (da[i] * (1.0 - BOUND_SLACK) > best_chord2 && nz2 * (1.0 - BOUND_SLACK) > best_chord2)
                continue;
            for (int j = 0; j < 8; ++j) {
                if (pass == 0 && (i != i0 || j != j0))
                    continue; /* pass 0 seeds the incumbent with the per-channel nearest pair */
                double r2 = a[i] * a[i] + b[j] * b[j], cosine;
                if (r2 <= 1.0) {
                    if ((da[i] + db[j]) * (1.0 - BOUND_SLACK) > best_chord2)
                        continue;
                    cosine = a[i] * n[0] + b[j] * n[1] + sqrt(1.0 - r2) * n[2];
                } else {
                    if (nz2 * (1.0 - BOUND_SLACK) > best_chord2)
                        continue;
                    cosine = (a[i] * n[0] + b[j] * n[1]) / sqrt(r2);
                }
                if (cosine > best_cos) {
                    best_cos = cosine;
                    best_chord2 = 2.0 - 2.0 * cosine;
                    best_i = i;
                    best_j = j;
                }
            }
        }
    }
    *bi = best_i;
    *bj = best_j;
    return decoded_angle(a[best_i], b[best_j], n);
}

/* Block objective for palettes a, b (decoded units): sum dN^2 or max dN^2 over pixels with joint
 * index choice. Stops and returns a value >= budget once the partial value reaches it. */
static double joint_objective(const double a[8], const double b[8], const double n[16][3], int use_max,
                              double budget, uint8_t *ix, uint8_t *iy)
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        int i, j;
        double e = best_pixel(a, b, n[p], &i, &j);
        s = use_max ? (e * e > s ? e * e : s) : s + e * e;
        if (ix) {
            ix[p] = (uint8_t)i;
            iy[p] = (uint8_t)j;
        }
        if (s >= budget)
            return s;
    }
    return s;
}

/* joint_objective with the pixels visited in `order` (worst first, so that hopeless candidates stop
 * early). Its sum may differ from joint_objective's in the last bits, so the search only uses it to
 * reject, with a relative margin, and re-evaluates survivors with joint_objective. */
static double joint_objective_ordered(const double a[8], const double b[8], const double n[16][3],
                                      const int order[16], int use_max, double budget)
{
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        int i, j;
        double e = best_pixel(a, b, n[order[k]], &i, &j);
        s = use_max ? (e * e > s ? e * e : s) : s + e * e;
        if (s >= budget)
            return s;
    }
    return s;
}

static sol_status check_options(const sol_bc5_options *o)
{
    if ((unsigned)o->precision >= SOL_BC4_PRECISION_COUNT || (unsigned)o->metric > SOL_BC5_MAX ||
        (unsigned)o->encoder > SOL_BC5_ADAPTIVE || !isfinite(o->threshold_deg) || o->threshold_deg < 0.0)
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

static double metric_value(double internal, sol_bc5_metric metric)
{
    return metric == SOL_BC5_MAX ? sqrt(internal) : internal;
}

sol_status sol_bc5_decode_block(const sol_bc5_block *block, sol_bc4_precision precision, double out[16][3])
{
    if (!block || !out)
        return SOL_ERR_NULL_ARG;
    double px[8], py[8];
    if (sol_bc4_palette(block->x.e0, block->x.e1, precision, px) != SOL_OK)
        return SOL_ERR_INVALID_ARG;
    sol_bc4_palette(block->y.e0, block->y.e1, precision, py);
    for (int p = 0; p < 16; ++p)
        if (block->x.index[p] > 7 || block->y.index[p] > 7)
            return SOL_ERR_INVALID_ARG;
    for (int p = 0; p < 16; ++p) {
        double a = 2.0 * px[block->x.index[p]] - 1.0, b = 2.0 * py[block->y.index[p]] - 1.0;
        out[p][0] = a;
        out[p][1] = b;
        out[p][2] = rebuild_z(a, b);
    }
    return SOL_OK;
}

sol_status sol_bc5_block_error(const sol_bc5_block *block, const double normals[16][3],
                               sol_bc4_precision precision, sol_bc5_metric metric, double *error)
{
    if (!block || !normals || !error)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)metric > SOL_BC5_MAX)
        return SOL_ERR_INVALID_ARG;
    double n[16][3], d[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    if ((st = sol_bc5_decode_block(block, precision, d)) != SOL_OK)
        return st;
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = sol_angle3(d[p], n[p]);
        s = metric == SOL_BC5_MAX ? (e * e > s ? e * e : s) : s + e * e;
    }
    *error = metric_value(s, metric);
    return SOL_OK;
}

sol_status sol_bc5_choose_indices(sol_bc5_block *block, const double normals[16][3], sol_bc4_precision precision,
                                  sol_bc5_metric metric, double *error)
{
    if (!block || !normals || !error)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)precision >= SOL_BC4_PRECISION_COUNT || (unsigned)metric > SOL_BC5_MAX)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    const double(*pal)[8] = sol_nm_palettes(precision);
    *error = metric_value(joint_objective(pal[block->x.e0 << 8 | block->x.e1], pal[block->y.e0 << 8 | block->y.e1],
                                          n, metric == SOL_BC5_MAX, INFINITY, block->x.index, block->y.index),
                          metric);
    return SOL_OK;
}

/* ---- the exact joint search ---- */

/* Scratch lists of anchor pairs, one per channel; reused across the blocks of one thread. */
typedef struct search_workspace {
    sol_nm_pair *x, *y;
} search_workspace;

static int compare_pairs(const void *pa, const void *pb)
{
    const sol_nm_pair *a = pa, *b = pb;
    if (a->score != b->score)
        return a->score < b->score ? -1 : 1;
    return (a->pair > b->pair) - (a->pair < b->pair);
}

static double combine(double sx, double sy, int use_max)
{
    return use_max ? (sx > sy ? sx : sy) : sx + sy;
}

/* Branch and bound over (x pair, y pair) inside the range, for unit normals n.
 * 1. Incumbent: the per-channel least-squares pairs (the common anchors) with joint indices.
 * 2. Bound: for a candidate whose pixels all decode with x^2 + y^2 <= 1, dN_p^2 >= chord_p^2 >=
 *    min_a (a - nx_p)^2 + min_b (b - ny_p)^2, so the objective >= SX + SY (sum) or max(SX, SY) (max),
 *    with SX, SY the per-channel scores. A pixel decoding with z clamped to 0 has dN_p^2 >= chord^2
 *    >= nz_p^2, so where nz_p^2 exceeds the incumbent such a decode cannot win and the tight term is
 *    a valid bound; rim pixels (nz_p^2 <= incumbent) take the loose term, valid in every case.
 * 3. Lists of the pairs of each channel whose score leaves room under the incumbent, sorted by
 *    score; the double loop stops as soon as the combined bound reaches the incumbent. */
static void search_unit(const double n[16][3], const sol_bc5_range *r, sol_bc4_precision precision, int use_max,
                        search_workspace *ws, sol_bc5_block *out, sol_bc5_info *info)
{
    double tx[16], ty[16], min_nz2 = INFINITY;
    for (int p = 0; p < 16; ++p) {
        tx[p] = n[p][0];
        ty[p] = n[p][1];
        min_nz2 = n[p][2] * n[p][2] < min_nz2 ? n[p][2] * n[p][2] : min_nz2;
    }
    sol_nm_channel cx, cy;
    sol_nm_channel_init(&cx, tx, precision, use_max, 0, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi);
    sol_nm_channel_init(&cy, ty, precision, use_max, 0, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi);
    double sx_min, sy_min;
    int px = sol_nm_channel_argmin(&cx, &sx_min), py = sol_nm_channel_argmin(&cy, &sy_min);
    const double(*pal)[8] = cx.palettes;
    double best = joint_objective(pal[px], pal[py], n, use_max, INFINITY, NULL, NULL);
    uint64_t candidates = 1;
    if (best > 0.0) {
        if (best * (1.0 + BOUND_SLACK) >= min_nz2) { /* rim pixels: loose bounds for them */
            unsigned loose = 0;
            for (int p = 0; p < 16; ++p)
                if (n[p][2] * n[p][2] <= best * (1.0 + BOUND_SLACK))
                    loose |= 1u << p;
            sol_nm_channel_init(&cx, tx, precision, use_max, loose, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi);
            sol_nm_channel_init(&cy, ty, precision, use_max, loose, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi);
            sol_nm_channel_argmin(&cx, &sx_min);
            sol_nm_channel_argmin(&cy, &sy_min);
        }
        double room = best * (1.0 + BOUND_SLACK);
        size_t nx = sol_nm_channel_collect(&cx, use_max ? room : room - sy_min * (1.0 - BOUND_SLACK), ws->x);
        size_t ny = sol_nm_channel_collect(&cy, use_max ? room : room - sx_min * (1.0 - BOUND_SLACK), ws->y);
        qsort(ws->x, nx, sizeof *ws->x, compare_pairs);
        qsort(ws->y, ny, sizeof *ws->y, compare_pairs);
        /* visit pixels worst-first (by the incumbent's per-pixel error) when rejecting candidates */
        int order[16];
        double pixel_err[16];
        for (int p = 0; p < 16; ++p) {
            int i, j;
            pixel_err[p] = best_pixel(pal[px], pal[py], n[p], &i, &j);
            order[p] = p;
        }
        for (int p = 1; p < 16; ++p)
            for (int q = p; q > 0 && pixel_err[order[q - 1]] < pixel_err[order[q]]; --q) {
                int t = order[q];
                order[q] = order[q - 1];
                order[q - 1] = t;
            }
        for (size_t i = 0; i < nx && ny > 0; ++i) {
            if (combine(ws->x[i].score, ws->y[0].score, use_max) * (1.0 - BOUND_SLACK) >= best)
                break;
            const double *a = pal[ws->x[i].pair];
            for (size_t j = 0; j < ny; ++j) {
                if (combine(ws->x[i].score, ws->y[j].score, use_max) * (1.0 - BOUND_SLACK) >= best)
                    break;
                ++candidates;
                double margin = best * (1.0 + BOUND_SLACK);
                if (joint_objective_ordered(a, pal[ws->y[j].pair], n, order, use_max, margin) >= margin)
                    continue;
                double v = joint_objective(a, pal[ws->y[j].pair], n, use_max, best, NULL, NULL);
                if (v < best) {
                    best = v;
                    px = ws->x[i].pair;
                    py = ws->y[j].pair;
                }
            }
        }
    }
    out->x.e0 = (uint8_t)(px >> 8);
    out->x.e1 = (uint8_t)(px & 255);
    out->y.e0 = (uint8_t)(py >> 8);
    out->y.e1 = (uint8_t)(py & 255);
    double check = joint_objective(pal[px], pal[py], n, use_max, INFINITY, out->x.index, out->y.index);
    if (info) {
        info->error = metric_value(check, use_max ? SOL_BC5_MAX : SOL_BC5_SUM_SQUARED);
        info->searched = 1;
        info->candidates = candidates;
    }
}

static sol_status workspace_alloc(search_workspace *ws)
{
    ws->x = malloc(65536 * sizeof *ws->x);
    ws->y = malloc(65536 * sizeof *ws->y);
    if (!ws->x || !ws->y) {
        free(ws->x);
        free(ws->y);
        return SOL_ERR_NO_MEMORY;
    }
    return SOL_OK;
}

static void workspace_free(search_workspace *ws)
{
    free(ws->x);
    free(ws->y);
}

static const sol_bc5_range full_range = {0, 255, 0, 255, 0, 255, 0, 255};

sol_status sol_bc5_search_block(const double normals[16][3], const sol_bc5_range *range,
                                const sol_bc5_options *options, sol_bc5_block *out, sol_bc5_info *info)
{
    static const sol_bc5_options defaults;
    if (!normals || !out)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    const sol_bc5_range *r = range ? range : &full_range;
    if (check_options(o) != SOL_OK || r->x0_lo > r->x0_hi || r->x1_lo > r->x1_hi || r->y0_lo > r->y0_hi ||
        r->y1_lo > r->y1_hi)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    search_workspace ws;
    if ((st = workspace_alloc(&ws)) != SOL_OK)
        return st;
    search_unit(n, r, o->precision, o->metric == SOL_BC5_MAX, &ws, out, info);
    workspace_free(&ws);
    return SOL_OK;
}

/* ---- the three encoders ---- */

static int nearest(const double pal[8], double t)
{
    int best = 0;
    for (int i = 1; i < 8; ++i)
        if (fabs(pal[i] - t) < fabs(pal[best] - t))
            best = i;
    return best;
}

/* Common encoder: two independent least-squares BC4 blocks, indices by nearest component (T10). */
static void encode_common(const double n[16][3], sol_bc4_precision precision, sol_bc5_block *out)
{
    double tx[16], ty[16], s;
    for (int p = 0; p < 16; ++p) {
        tx[p] = n[p][0];
        ty[p] = n[p][1];
    }
    sol_nm_channel cx, cy;
    sol_nm_channel_init(&cx, tx, precision, 0, 0, 0, 255, 0, 255);
    sol_nm_channel_init(&cy, ty, precision, 0, 0, 0, 255, 0, 255);
    int px = sol_nm_channel_argmin(&cx, &s), py = sol_nm_channel_argmin(&cy, &s);
    out->x.e0 = (uint8_t)(px >> 8);
    out->x.e1 = (uint8_t)(px & 255);
    out->y.e0 = (uint8_t)(py >> 8);
    out->y.e1 = (uint8_t)(py & 255);
    for (int p = 0; p < 16; ++p) {
        out->x.index[p] = (uint8_t)nearest(cx.palettes[px], tx[p]);
        out->y.index[p] = (uint8_t)nearest(cy.palettes[py], ty[p]);
    }
}

static double own_index_objective(const sol_bc5_block *b, const double n[16][3], sol_bc4_precision precision,
                                  int use_max)
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    const double *a = pal[b->x.e0 << 8 | b->x.e1], *c = pal[b->y.e0 << 8 | b->y.e1];
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = decoded_angle(a[b->x.index[p]], c[b->y.index[p]], n[p]);
        s = use_max ? (e * e > s ? e * e : s) : s + e * e;
    }
    return s;
}

static uint8_t clamp_code(int v)
{
    return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
}

/* One block with validated options and unit normals. */
static void encode_unit(const double n[16][3], const sol_bc5_options *o, search_workspace *ws,
                        sol_bc5_block *out, sol_bc5_info *info)
{
    int use_max = o->metric == SOL_BC5_MAX;
    if (o->encoder == SOL_BC5_OPTIMAL) {
        search_unit(n, &full_range, o->precision, use_max, ws, out, info);
        return;
    }
    sol_bc5_block common;
    encode_common(n, o->precision, &common);
    double err = own_index_objective(&common, n, o->precision, use_max);
    /* adaptive: RMS (or max) angle in degrees against the threshold (T13) */
    double level = (use_max ? sqrt(err) : sqrt(err / 16.0)) * (180.0 / M_PI);
    if (o->encoder == SOL_BC5_COMMON || level <= o->threshold_deg) {
        *out = common;
        if (info) {
            info->error = metric_value(err, o->metric);
            info->searched = 0;
            info->candidates = 1;
        }
        return;
    }
    int w = o->window == 0 ? 4 : (o->window < 0 ? 0 : o->window > 255 ? 255 : o->window); /* 255: all codes */
    sol_bc5_range r = {clamp_code(common.x.e0 - w), clamp_code(common.x.e0 + w), clamp_code(common.x.e1 - w),
                       clamp_code(common.x.e1 + w), clamp_code(common.y.e0 - w), clamp_code(common.y.e0 + w),
                       clamp_code(common.y.e1 - w), clamp_code(common.y.e1 + w)};
    search_unit(n, &r, o->precision, use_max, ws, out, info);
}

sol_status sol_bc5_encode_block(const double normals[16][3], const sol_bc5_options *options, sol_bc5_block *out,
                                sol_bc5_info *info)
{
    static const sol_bc5_options defaults;
    if (!normals || !out)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    if (check_options(o) != SOL_OK)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    search_workspace ws = {0};
    if (o->encoder != SOL_BC5_COMMON && (st = workspace_alloc(&ws)) != SOL_OK)
        return st;
    encode_unit(n, o, &ws, out, info);
    workspace_free(&ws);
    return SOL_OK;
}

/* ---- images ---- */

static void gather_block(const sol_image *img, int bx, int by, double n[16][3])
{
    for (int p = 0; p < 16; ++p) {
        const float *v = sol_image_pixel(img, 4 * bx + (p & 3), 4 * by + (p >> 2));
        for (int c = 0; c < 3; ++c)
            n[p][c] = v[c];
    }
}

static void pack_block(const sol_bc5_block *b, uint8_t out[16])
{
    sol_bc4_pack(&b->x, out);
    sol_bc4_pack(&b->y, out + 8);
}

sol_status sol_bc5_encode_image(const sol_image *normals, const sol_bc5_options *options, uint8_t *blocks,
                                sol_bc5_image_stats *stats)
{
    static const sol_bc5_options defaults;
    if (!normals || !normals->data || !blocks)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    if (check_options(o) != SOL_OK || normals->channels != 3 || normals->width <= 0 || normals->height <= 0 ||
        normals->width % 4 || normals->height % 4)
        return SOL_ERR_INVALID_ARG;
    const int bw = normals->width / 4, nblocks = bw * (normals->height / 4);
    /* validate everything first, so the parallel part cannot fail on input */
    for (int b = 0; b < nblocks; ++b) {
        double raw[16][3], n[16][3];
        gather_block(normals, b % bw, b / bw, raw);
        sol_status st = sol_nm_unit_normals(raw, n);
        if (st != SOL_OK)
            return st;
    }
    uint64_t searched = 0, candidates = 0;
    int failed = 0;
#pragma omp parallel reduction(+ : searched, candidates) reduction(| : failed)
    {
        search_workspace ws = {0};
        if (o->encoder != SOL_BC5_COMMON && workspace_alloc(&ws) != SOL_OK)
            failed = 1;
#pragma omp for schedule(dynamic, 16)
        for (int b = 0; b < nblocks; ++b) {
            if (failed)
                continue;
            double raw[16][3], n[16][3];
            gather_block(normals, b % bw, b / bw, raw);
            sol_nm_unit_normals(raw, n);
            sol_bc5_block block;
            sol_bc5_info info;
            encode_unit(n, o, &ws, &block, &info);
            pack_block(&block, blocks + 16 * (size_t)b);
            searched += (uint64_t)info.searched;
            candidates += info.candidates;
        }
        workspace_free(&ws);
    }
    if (failed)
        return SOL_ERR_NO_MEMORY;
    if (stats) {
        stats->blocks = (uint64_t)nblocks;
        stats->searched_blocks = searched;
        stats->candidates = candidates;
    }
    return SOL_OK;
}

sol_status sol_bc5_decode_image(const uint8_t *blocks, int width, int height, sol_bc4_precision precision,
                                sol_image *out)
{
    if (!blocks || !out)
        return SOL_ERR_NULL_ARG;
    if (width <= 0 || height <= 0 || width % 4 || height % 4 || (unsigned)precision >= SOL_BC4_PRECISION_COUNT)
        return SOL_ERR_INVALID_ARG;
    sol_image img;
    sol_status st = sol_image_alloc(&img, width, height, 3);
    if (st != SOL_OK)
        return st;
    const int bw = width / 4, nblocks = bw * (height / 4);
    for (int b = 0; b < nblocks; ++b) {
        sol_bc5_block block;
        double d[16][3];
        sol_bc4_unpack(blocks + 16 * (size_t)b, &block.x);
        sol_bc4_unpack(blocks + 16 * (size_t)b + 8, &block.y);
        sol_bc5_decode_block(&block, precision, d);
        for (int p = 0; p < 16; ++p) {
            float *v = sol_image_pixel(&img, 4 * (b % bw) + (p & 3), 4 * (b / bw) + (p >> 2));
            double len = sqrt(d[p][0] * d[p][0] + d[p][1] * d[p][1] + d[p][2] * d[p][2]);
            for (int c = 0; c < 3; ++c)
                v[c] = (float)(d[p][c] / len);
        }
    }
    *out = img;
    return SOL_OK;
}
