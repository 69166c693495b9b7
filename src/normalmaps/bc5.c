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
static void best_pixel_index(const double a[8], const double b[8], const double n[3], int *bi, int *bj)
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
}

/* The angle (radians) of best_pixel_index's choice. */
static double best_pixel(const double a[8], const double b[8], const double n[3], int *bi, int *bj)
{
    best_pixel_index(a, b, n, bi, bj);
    return decoded_angle(a[*bi], b[*bj], n);
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

/* A lower bound of the squared angle dN^2 of the decoded (a, b) against unit n, without atan2: the
 * chord c between the unit directions gives dN = 2 asin(c / 2), so dN^2 >= c^2 + c^4 / 12 (all the
 * series' terms are positive). c^2 is computed from components (no 2 - 2 cos cancellation); c is
 * lowered by 1e-6 relative and 1e-15 absolute to cover its rounding and that of sol_angle3's atan2,
 * so the bound stays below the computed angle squared. */
static inline double angle2_lower_bound(double a, double b, const double n[3])
{
    double r2 = a * a + b * b, c2;
    if (r2 <= 1.0) {
        double z = sqrt(1.0 - r2);
        /* z - nz = (nx^2 + ny^2 - a^2 - b^2) / (z + nz) for unit n, accurate when z ~ nz */
        double dz = z + n[2] > 0.0 ? (n[0] * n[0] + n[1] * n[1] - r2) / (z + n[2]) : z - n[2];
        c2 = (a - n[0]) * (a - n[0]) + (b - n[1]) * (b - n[1]) + dz * dz;
    } else {
        double inv = 1.0 / sqrt(r2);
        c2 = (a * inv - n[0]) * (a * inv - n[0]) + (b * inv - n[1]) * (b * inv - n[1]) + n[2] * n[2];
    }
    double c = sqrt(c2) * (1.0 - 1e-6) - 1e-15; /* relative and absolute rounding of c and of dN */
    return c > 0.0 ? c * c * (1.0 + c * c / 12.0) : 0.0;
}

/* A lower bound of the joint objective with the pixels visited in `order` (worst first, so that
 * hopeless candidates stop early): each pixel's jointly best index pair (the same choice as
 * best_pixel), its dN^2 bounded below by angle2_lower_bound. The search rejects a candidate when
 * this reaches the incumbent and re-evaluates survivors exactly with joint_objective. */
static double joint_objective_lower(const double a[8], const double b[8], const double n[16][3],
                                    const int order[16], int use_max, double budget, uint64_t *work)
{
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        *work += 32;
        int i, j;
        const double *np = n[order[k]];
        best_pixel_index(a, b, np, &i, &j);
        double e2 = angle2_lower_bound(a[i], b[j], np);
        s = use_max ? (e2 > s ? e2 : s) : s + e2;
        if (s >= budget)
            return s;
    }
    return s;
}

/* ---- the quick per-candidate bound ----
 *
 * joint_objective_lower finds each pixel's jointly best index pair (an 8 x 8 search): exact, but most
 * of the search's time on rough blocks. The quick bound needs per pixel only what each channel's
 * palette gives alone, precomputed once per anchor pair (channel_side): the nearest entry's value v,
 * its squared distance m1 and the least squared distance m2 of an entry of ANOTHER value. The decode
 * of the two nearest entries (v_x, v_y) has chord^2 c00 (with z); any other index pair (i, j) decodes
 * to a different vector and has, unclamped, chord^2 >= (a_i - nx)^2 + (b_j - ny)^2 >=
 * min(m2_x + m1_y, m1_x + m2_y), and clamped (z = 0) chord^2 >= nz^2. So every pixel's chord^2 is at
 * least min(c00, m2_x + m1_y, m1_x + m2_y, nz^2) whatever pair best_pixel picks, and dN^2 >= chord^2.
 * It equals the exact per-pixel bound whenever the nearest pair wins clearly, which on smooth and
 * rough blocks alike is most pixels; the survivors go on to joint_objective_lower. */
typedef struct channel_side {
    double v[16], m1[16], m2[16]; /* per pixel, in the search's visiting order */
} channel_side;

/* Fills s for palette pal against component c (0 = x, 1 = y) of the pixels n[order[k]]. */
static void channel_side_init(const double pal[8], const double n[16][3], const int order[16], int c,
                              channel_side *s)
{
    for (int k = 0; k < 16; ++k) {
        double t = n[order[k]][c], d[8];
        int i0 = 0;
        for (int i = 0; i < 8; ++i) {
            d[i] = (pal[i] - t) * (pal[i] - t);
            i0 = d[i] < d[i0] ? i : i0;
        }
        double m2 = INFINITY;
        for (int i = 0; i < 8; ++i)
            if (pal[i] != pal[i0] && d[i] < m2)
                m2 = d[i];
        s->v[k] = pal[i0];
        s->m1[k] = d[i0];
        s->m2[k] = m2;
    }
}

/* The quick lower bound of the joint objective (pixels in `order`, stops once it reaches budget).
 * Each pixel's chord^2 bound c2 becomes a dN^2 bound c2 (1 - 3e-6) - 5e-15 <= (c (1 - 1e-6) - 1e-15)^2,
 * the rounding allowance of angle2_lower_bound; the chord of (v_x, v_y) is computed with the decoder's
 * z = sqrt(1 - a^2 - b^2). */
static double joint_objective_quick(const channel_side *xs, const channel_side *ys, const double n[16][3],
                                    const int order[16], int use_max, double budget, uint64_t *work)
{
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        ++*work;
        const double *np = n[order[k]];
        double a = xs->v[k], b = ys->v[k], nz2 = np[2] * np[2];
        double alt = xs->m2[k] + ys->m1[k], alt2 = xs->m1[k] + ys->m2[k];
        double lb = alt < alt2 ? alt : alt2;
        lb = nz2 < lb ? nz2 : lb;
        double zz = 1.0 - a * a - b * b, c2;
        if (zz > 0.0) {
            double dz = sqrt(zz) - np[2];
            c2 = xs->m1[k] + ys->m1[k] + dz * dz;
        } else {
            c2 = nz2; /* a clamped decode */
        }
        lb = c2 < lb ? c2 : lb;
        double e2 = lb * (1.0 - 3e-6) - 5e-15;
        e2 = e2 > 0.0 ? e2 : 0.0;
        s = use_max ? (e2 > s ? e2 : s) : s + e2;
        if (s >= budget)
            return s;
    }
    return s;
}

static sol_status check_options(const sol_bc5_options *o)
{
    if ((unsigned)o->precision >= SOL_BC4_PRECISION_COUNT || (unsigned)o->metric > SOL_BC5_MAX ||
        (unsigned)o->encoder > SOL_BC5_FAST || !isfinite(o->threshold_deg) || o->threshold_deg < 0.0 ||
        (unsigned)o->base > SOL_BC5_BASE_FAST)
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

static uint64_t work_limit(const sol_bc5_options *o)
{
    return o->work_limit ? o->work_limit : SOL_BC5_DEFAULT_WORK_LIMIT;
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

/* Scratch of one thread, reused across its blocks: the lists of anchor pairs of each channel and
 * a hash table (list positions + 1) for merging equivalent pairs. */
typedef struct window_scratch window_scratch;
typedef struct search_workspace {
    sol_nm_pair *x, *y;
    uint32_t *slots;     /* 2 * 65536 entries */
    channel_side *yside; /* the y list's channel sides (quick bound), grown on demand */
    size_t yside_cap;
    window_scratch *win; /* the adaptive window path's lists (window_search) */
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

/* ---- equivalent anchor pairs (exact ties decided without enumerating them) ----
 *
 * Within a budget T >= the incumbent, a candidate can only reach the incumbent if every pixel's
 * chosen entry a has (a - t_p)^2 <= T (tight pixels: dN^2 >= chord^2 >= (a - t_p)^2, and a clamped
 * decode has dN^2 >= nz^2 > T) or, on rim pixels, the loose distance of t_p to [a / sqrt 2, a] within
 * sqrt T. Call those entries usable. best_pixel's choice is the first entry pair of largest cosine in
 * a fixed visiting order (seed pair first), and depends only on entry values; so two pairs of one
 * channel whose seeds (nearest entry) and usable entries, in palette order, have bit-identical values
 * on every pixel give every candidate the same objective whenever it can reach T. Flat blocks have
 * hundreds of such pairs per channel (different anchors spanning the same value near the target);
 * the search keeps only the first of each class in its visiting order, which is the candidate the
 * full enumeration would have kept (the first of a tied class is met first), so the result is the
 * same pair as without merging, at a fraction of the work. */
static inline uint64_t value_bits(double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

typedef struct channel_key {
    double t[16];  /* the distinct (target, loose) pixels: equal pixels give equal key parts */
    int loose[16];
    int count;
    double budget; /* T */
} channel_key;

static void channel_key_init(channel_key *k, const double t[16], unsigned loose, double budget)
{
    k->count = 0;
    k->budget = budget;
    for (int p = 0; p < 16; ++p) {
        int l = (loose >> p) & 1, seen = 0;
        for (int q = 0; q < k->count && !seen; ++q)
            seen = value_bits(k->t[q]) == value_bits(t[p]) && k->loose[q] == l;
        if (!seen) {
            k->t[k->count] = t[p];
            k->loose[k->count++] = l;
        }
    }
}

static inline int usable_entry(double a, double t, int loose, double budget)
{
    double d = a - t;
    if (loose) {
        double b = a * (1.0 / M_SQRT2), lo = a < b ? a : b, hi = a < b ? b : a;
        d = t < lo ? lo - t : (t > hi ? t - hi : 0.0);
    }
    return d * d <= budget;
}

/* The entry best_pixel seeds a pixel with: the first of least (a - t)^2. */
static inline int seed_entry(const double pal[8], double t)
{
    int i0 = 0;
    double d0 = (pal[0] - t) * (pal[0] - t);
    for (int k = 1; k < 8; ++k) {
        double d = (pal[k] - t) * (pal[k] - t);
        if (d < d0) {
            d0 = d;
            i0 = k;
        }
    }
    return i0;
}

static inline uint64_t mix64(uint64_t h, uint64_t v)
{
    h ^= v + UINT64_C(0x9E3779B97F4A7C15) + (h << 6) + (h >> 2);
    return h * UINT64_C(0xBF58476D1CE4E5B9);
}

static uint64_t pair_key_hash(const channel_key *k, const double pal[8])
{
    uint64_t h = 0;
    for (int p = 0; p < k->count; ++p) {
        int loose = k->loose[p];
        h = mix64(h, value_bits(pal[seed_entry(pal, k->t[p])]));
        for (int e = 0; e < 8; ++e)
            if (usable_entry(pal[e], k->t[p], loose, k->budget))
                h = mix64(h, value_bits(pal[e]));
        h = mix64(h, 0x5eed);
    }
    return h;
}

static int pair_key_equal(const channel_key *k, const double pa[8], const double pb[8])
{
    for (int p = 0; p < k->count; ++p) {
        int loose = k->loose[p];
        if (value_bits(pa[seed_entry(pa, k->t[p])]) != value_bits(pb[seed_entry(pb, k->t[p])]))
            return 0;
        int ea = 0, eb = 0;
        for (;;) {
            while (ea < 8 && !usable_entry(pa[ea], k->t[p], loose, k->budget))
                ++ea;
            while (eb < 8 && !usable_entry(pb[eb], k->t[p], loose, k->budget))
                ++eb;
            if (ea == 8 || eb == 8) {
                if (ea != eb)
                    return 0;
                break;
            }
            if (value_bits(pa[ea++]) != value_bits(pb[eb++]))
                return 0;
        }
    }
    return 1;
}

/* Keeps the first pair of each equivalence class of a sorted list (in place); returns the count. */
static size_t merge_equivalent(sol_nm_pair *list, size_t count, const channel_key *k, const double (*pal)[8],
                               uint32_t *slots)
{
    size_t size = 64;
    while (size < 2 * count)
        size *= 2;
    memset(slots, 0, size * sizeof *slots);
    size_t kept = 0;
    for (size_t i = 0; i < count; ++i) {
        const double *a = pal[list[i].pair];
        size_t h = (size_t)pair_key_hash(k, a) & (size - 1);
        int dup = 0;
        for (; slots[h]; h = (h + 1) & (size - 1))
            if (pair_key_equal(k, pal[list[slots[h] - 1].pair], a)) {
                dup = 1;
                break;
            }
        if (dup)
            continue;
        list[kept] = list[i];
        slots[h] = (uint32_t)++kept;
    }
    return kept;
}

/* Lower bound of every candidate's objective from the hemisphere alone: a decoded normal has
 * z >= 0, so dN_p >= asin(-nz_p) where nz_p < 0. A block of normals pointing straight away (0, 0, -1)
 * reaches it (dN = pi / 2 at every rim decode), and is decided by it at once. */
static double hemisphere_bound(const double n[16][3], int use_max)
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = n[p][2] < 0.0 ? asin(-n[p][2]) : 0.0;
        s = use_max ? (e * e > s ? e * e : s) : s + e * e;
    }
    return s;
}

static int pair_in_range(int pair, uint8_t e0_lo, uint8_t e0_hi, uint8_t e1_lo, uint8_t e1_hi)
{
    int e0 = pair >> 8, e1 = pair & 255;
    return e0 >= e0_lo && e0 <= e0_hi && e1 >= e1_lo && e1 <= e1_hi;
}

/* What search_unit is asked: range, precision, metric, work bound. */
typedef struct search_request {
    const sol_bc5_range *range;
    sol_bc4_precision precision;
    int use_max;
    uint64_t work_limit;
} search_request;

/* Branch and bound over (x pair, y pair) inside the range, for unit normals n.
 * 1. Incumbent: the better (first on ties) of the per-channel least-squares pairs (the common
 *    anchors) and the full-span 6-value pairs (0, 255) whose entries -1 and +1 reach the rim, both
 *    with joint indices. If it meets hemisphere_bound it is optimal.
 * 2. Bound: for a candidate whose pixels all decode with x^2 + y^2 <= 1, dN_p^2 >= chord_p^2 >=
 *    min_a (a - nx_p)^2 + min_b (b - ny_p)^2, so the objective >= SX + SY (sum) or max(SX, SY) (max),
 *    with SX, SY the per-channel scores. A pixel decoding with z clamped to 0 has dN_p^2 >= chord^2
 *    >= nz_p^2, so where nz_p^2 exceeds the incumbent such a decode cannot win and the tight term is
 *    a valid bound; rim pixels (nz_p^2 <= incumbent) take the loose term, valid in every case.
 * 3. Lists of the pairs of each channel whose score leaves room under the incumbent, sorted by
 *    score, equivalent pairs merged (see above); the double loop stops as soon as the combined bound
 *    reaches the incumbent. Each candidate is first rejected, if it can be, by lower bounds of its
 *    objective without atan2 (joint_objective_quick, then joint_objective_lower), and evaluated
 *    exactly only if it survives both.
 * 4. Work bound: after work_limit work units (a pixel of a candidate through the quick bound 1,
 *    through joint_objective_lower 32, an exact evaluation 512: about their relative costs) the
 *    search stops with the best found (info->bounded = 1). */
static void search_unit(const double n[16][3], const search_request *rq, search_workspace *ws, sol_bc5_block *out,
                        sol_bc5_info *info)
{
    const sol_bc5_range *r = rq->range;
    const sol_bc4_precision precision = rq->precision;
    const int use_max = rq->use_max;
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
    /* second incumbent: the full-span 6-value pairs, whose entries -1 and +1 reach the rim (blocks
     * pointing away). (Starting from the adaptive window's result instead was measured: it costs
     * more than the candidates it saves on the benchmark maps.) */
    const int rim = 0x00ff;
    if (pair_in_range(rim, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi) &&
        pair_in_range(rim, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi)) {
        ++candidates;
        double v = joint_objective(pal[rim], pal[rim], n, use_max, best, NULL, NULL);
        if (v < best) {
            best = v;
            px = py = rim;
        }
    }
    int bounded = 0;
    uint64_t work = 0; /* pixel evaluations of candidates */
    if (best > 0.0 && best > hemisphere_bound(n, use_max)) {
        unsigned loose = 0;
        if (best * (1.0 + BOUND_SLACK) >= min_nz2) { /* rim pixels: loose bounds for them */
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
        if (nx > 1 && ny > 1 && nx * ny > 256) { /* merging pays only for long lists */
            channel_key kx, ky;
            channel_key_init(&kx, tx, loose, room);
            channel_key_init(&ky, ty, loose, room);
            nx = merge_equivalent(ws->x, nx, &kx, pal, ws->slots);
            ny = merge_equivalent(ws->y, ny, &ky, pal, ws->slots);
        }
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
        /* the y list's channel sides for the quick bound (without memory, the search runs without it) */
        int quick = 1;
        if (ny > ws->yside_cap) {
            channel_side *grown = realloc(ws->yside, ny * sizeof *grown);
            if (grown) {
                ws->yside = grown;
                ws->yside_cap = ny;
            } else {
                quick = 0;
            }
        }
        for (size_t j = 0; quick && j < ny; ++j)
            channel_side_init(pal[ws->y[j].pair], n, order, 1, &ws->yside[j]);
        channel_side xside;
        for (size_t i = 0; i < nx && ny > 0 && !bounded; ++i) {
            if (combine(ws->x[i].score, ws->y[0].score, use_max) * (1.0 - BOUND_SLACK) >= best)
                break;
            const double *a = pal[ws->x[i].pair];
            if (quick)
                channel_side_init(a, n, order, 0, &xside);
            for (size_t j = 0; j < ny; ++j) {
                if (combine(ws->x[i].score, ws->y[j].score, use_max) * (1.0 - BOUND_SLACK) >= best)
                    break;
                if (work >= rq->work_limit) {
                    bounded = 1;
                    break;
                }
                ++candidates;
                double margin = best * (1.0 + BOUND_SLACK);
                if (quick && joint_objective_quick(&xside, &ws->yside[j], n, order, use_max, margin, &work) >= margin)
                    continue;
                if (joint_objective_lower(a, pal[ws->y[j].pair], n, order, use_max, margin, &work) >= margin)
                    continue;
                work += 512;
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
        info->bounded = bounded;
    }
}

/* ---- the adaptive encoder's window search (T13) ----
 *
 * The same branch and bound as search_unit, specialised to a window of at most WINDOW_PATH_MAX codes
 * around each anchor (the talk's +-4: 81 anchor pairs per channel): each pair's per-pixel nearest
 * entries (its channel side: score, quick-bound terms) are computed once, in one pass, for the
 * pairs whose score leaves room under the incumbent; no full-range scoring, hashing or merging. The
 * incumbent is the base block's anchors with joint indices. It needs every pixel's tight bound
 * (nz_p^2 above the incumbent, so no decode with z clamped can win, see search_unit 2.); blocks with
 * rim or downward pixels, and wider windows, go to search_unit. Exact within the window: the
 * result's error equals the literal brute force's minimum over the window. Ties: the first
 * minimiser in the order incumbent, then x pairs by increasing (score, code), y pairs likewise. */
enum { WINDOW_PATH_MAX = 8, WINDOW_PAIRS = (2 * WINDOW_PATH_MAX + 1) * (2 * WINDOW_PATH_MAX + 1) };

typedef sol_nm_pair window_entry; /* a pair and its channel score */

struct window_scratch {
    window_entry list[2][WINDOW_PAIRS];
    channel_side yside[WINDOW_PAIRS];    /* the sorted y list's channel sides, */
    unsigned char ready[WINDOW_PAIRS];   /* each computed when first needed */
};

/* Sorts by increasing (score, pair): insertion sort, the lists are short (<= WINDOW_PAIRS). */
static void sort_window_entries(window_entry *list, int count)
{
    for (int k = 1; k < count; ++k) {
        window_entry e = list[k];
        int q = k;
        for (; q > 0 && (list[q - 1].score > e.score || (list[q - 1].score == e.score && list[q - 1].pair > e.pair));
             --q)
            list[q] = list[q - 1];
        list[q] = e;
    }
}

/* Scores the window pairs of channel c (sum or max over pixels of the nearest entry's squared
 * distance: the tight per-channel bound) into list, in e0-major order, and returns the count; a
 * pair whose two extreme pixels (least and largest component) alone exceed budget is left out
 * (most pairs of smooth blocks). The full score: one pass over entries, all 16 pixels at a time
 * (a loop the compiler vectorises). */
static int window_channel(const double n[16][3], int c, const double (*pal)[8], int use_max, int e0_lo, int e0_hi,
                          int e1_lo, int e1_hi, double budget, window_entry *list)
{
    int count = 0, lo = 0, hi = 0;
    double t[16];
    for (int p = 0; p < 16; ++p) {
        t[p] = n[p][c];
        lo = t[p] < t[lo] ? p : lo;
        hi = t[p] > t[hi] ? p : hi;
    }
    for (int e0 = e0_lo; e0 <= e0_hi; ++e0)
        for (int e1 = e1_lo; e1 <= e1_hi; ++e1) {
            const double *a = pal[e0 << 8 | e1];
            double dlo = INFINITY, dhi = INFINITY;
            for (int i = 0; i < 8; ++i) {
                double u = (a[i] - t[lo]) * (a[i] - t[lo]), v = (a[i] - t[hi]) * (a[i] - t[hi]);
                dlo = u < dlo ? u : dlo;
                dhi = v < dhi ? v : dhi;
            }
            if ((lo == hi ? dlo : combine(dlo, dhi, use_max)) > budget)
                continue;
            double m[16];
            for (int p = 0; p < 16; ++p)
                m[p] = (a[0] - t[p]) * (a[0] - t[p]);
            for (int i = 1; i < 8; ++i)
                for (int p = 0; p < 16; ++p) {
                    double d = (a[i] - t[p]) * (a[i] - t[p]);
                    m[p] = d < m[p] ? d : m[p];
                }
            double score = 0.0;
            for (int p = 0; p < 16; ++p)
                score = use_max ? (m[p] > score ? m[p] : score) : score + m[p];
            list[count] = (window_entry){score, (uint16_t)(e0 << 8 | e1)};
            ++count;
        }
    return count;
}

/* Keeps the entries of score <= budget (in order); returns the count. */
static int window_filter(window_entry *list, int count, double budget)
{
    int kept = 0;
    for (int k = 0; k < count; ++k)
        if (list[k].score <= budget)
            list[kept++] = list[k];
    return kept;
}

/* joint_objective_lower and then, if the candidate survives it, joint_objective, with each pixel's
 * jointly best index pair found once (the same pairs, sums and early exits as the two calls in turn):
 * returns the lower bound (>= margin: rejected, *v untouched), else writes the exact objective
 * (stopped once it reaches budget, as joint_objective) to *v and the index pairs to ix, iy. */
static double joint_objective_checked(const double a[8], const double b[8], const double n[16][3],
                                      const int order[16], int use_max, double margin, double budget,
                                      uint64_t *work, double *v, uint8_t ix[16], uint8_t iy[16])
{
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        *work += 32;
        int i, j, p = order[k];
        best_pixel_index(a, b, n[p], &i, &j);
        ix[p] = (uint8_t)i;
        iy[p] = (uint8_t)j;
        double e2 = angle2_lower_bound(a[i], b[j], n[p]);
        s = use_max ? (e2 > s ? e2 : s) : s + e2;
        if (s >= margin)
            return s;
    }
    *work += 512;
    double e = 0.0;
    for (int p = 0; p < 16; ++p) {
        double d = decoded_angle(a[ix[p]], b[iy[p]], n[p]);
        e = use_max ? (d * d > e ? d * d : e) : e + d * d;
        if (e >= budget)
            break;
    }
    *v = e;
    return s;
}

/* Returns 0 (and leaves everything untouched) when the block needs search_unit (see above). */
static int window_search(const double n[16][3], const sol_bc5_range *r, int base_x, int base_y,
                         const search_request *rq, search_workspace *ws, sol_bc5_block *out, sol_bc5_info *info)
{
    if (r->x0_hi - r->x0_lo > 2 * WINDOW_PATH_MAX || r->x1_hi - r->x1_lo > 2 * WINDOW_PATH_MAX ||
        r->y0_hi - r->y0_lo > 2 * WINDOW_PATH_MAX || r->y1_hi - r->y1_lo > 2 * WINDOW_PATH_MAX)
        return 0;
    const int use_max = rq->use_max;
    const double(*pal)[8] = sol_nm_palettes(rq->precision);
    int px = base_x, py = base_y;
    uint8_t ix[16], iy[16], cx[16], cy[16]; /* the best's indices, a candidate's */
    double pixel_err[16], best = 0.0;
    for (int p = 0; p < 16; ++p) { /* joint_objective's sum, keeping each pixel's error */
        int i, j;
        double e = best_pixel(pal[px], pal[py], n[p], &i, &j);
        ix[p] = (uint8_t)i;
        iy[p] = (uint8_t)j;
        pixel_err[p] = e;
        best = use_max ? (e * e > best ? e * e : best) : best + e * e;
    }
    for (int p = 0; p < 16; ++p)
        if (!(n[p][2] > 0.0) || n[p][2] * n[p][2] <= best * (1.0 + BOUND_SLACK))
            return 0; /* a rim or downward pixel: the loose bounds of search_unit */
    uint64_t candidates = 1, work = 0;
    int bounded = 0;
    if (best > 0.0) {
        window_scratch *w = ws->win;
        double least_x = INFINITY, least_y = INFINITY, room = best * (1.0 + BOUND_SLACK);
        int nx = window_channel(n, 0, pal, use_max, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi, room, w->list[0]);
        int ny = window_channel(n, 1, pal, use_max, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi, room, w->list[1]);
        for (int k = 0; k < nx; ++k)
            least_x = w->list[0][k].score < least_x ? w->list[0][k].score : least_x;
        for (int k = 0; k < ny; ++k)
            least_y = w->list[1][k].score < least_y ? w->list[1][k].score : least_y;
        /* a pair can only pair up under the incumbent if its score leaves room for the other channel's least */
        nx = window_filter(w->list[0], nx, use_max ? room : room - least_y * (1.0 - BOUND_SLACK));
        ny = window_filter(w->list[1], ny, use_max ? room : room - least_x * (1.0 - BOUND_SLACK));
        sort_window_entries(w->list[0], nx);
        sort_window_entries(w->list[1], ny);
        double tx[16], ty[16], span = 0.0;
        for (int p = 0; p < 16; ++p) {
            tx[p] = n[p][0];
            ty[p] = n[p][1];
            span = fmax(span, fmax(fabs(tx[p] - tx[0]), fabs(ty[p] - ty[0])));
        }
        /* Exactly tied pairs (nearly flat blocks, whose targets span a few codes: anchors spanning the
         * same values near them): one per class, as search_unit. Elsewhere hashing costs more than
         * the ties it saves; the result is the same either way. */
        if (nx > 1 && ny > 1 && nx * ny > 256 && span <= 8.0 / 255.0) {
            channel_key kx, ky;
            channel_key_init(&kx, tx, 0, room);
            channel_key_init(&ky, ty, 0, room);
            nx = (int)merge_equivalent(w->list[0], (size_t)nx, &kx, pal, ws->slots);
            ny = (int)merge_equivalent(w->list[1], (size_t)ny, &ky, pal, ws->slots);
        }
        /* visit pixels worst-first (by the incumbent's per-pixel error) when rejecting candidates */
        int order[16];
        for (int p = 0; p < 16; ++p)
            order[p] = p;
        for (int p = 1; p < 16; ++p)
            for (int q = p; q > 0 && pixel_err[order[q - 1]] < pixel_err[order[q]]; --q) {
                int t = order[q];
                order[q] = order[q - 1];
                order[q - 1] = t;
            }
        memset(w->ready, 0, (size_t)ny); /* y sides are computed when first needed */
        channel_side xside;
        for (int i = 0; i < nx && ny > 0 && !bounded; ++i) {
            const window_entry *ex = &w->list[0][i];
            if (combine(ex->score, w->list[1][0].score, use_max) * (1.0 - BOUND_SLACK) >= best)
                break;
            const double *a = pal[ex->pair];
            channel_side_init(a, n, order, 0, &xside);
            for (int j = 0; j < ny; ++j) {
                const window_entry *ey = &w->list[1][j];
                if (combine(ex->score, ey->score, use_max) * (1.0 - BOUND_SLACK) >= best)
                    break;
                if (ex->pair == base_x && ey->pair == base_y)
                    continue; /* the incumbent */
                if (work >= rq->work_limit) {
                    bounded = 1;
                    break;
                }
                ++candidates;
                const double *b = pal[ey->pair];
                if (!w->ready[j]) {
                    channel_side_init(b, n, order, 1, &w->yside[j]);
                    w->ready[j] = 1;
                }
                double margin = best * (1.0 + BOUND_SLACK);
                if (joint_objective_quick(&xside, &w->yside[j], n, order, use_max, margin, &work) >= margin)
                    continue;
                double v = INFINITY;
                if (joint_objective_checked(a, b, n, order, use_max, margin, best, &work, &v, cx, cy) >= margin)
                    continue;
                if (v < best) { /* complete (below the budget): the exact objective and its indices */
                    best = v;
                    px = ex->pair;
                    py = ey->pair;
                    memcpy(ix, cx, sizeof ix);
                    memcpy(iy, cy, sizeof iy);
                }
            }
        }
    }
    out->x.e0 = (uint8_t)(px >> 8);
    out->x.e1 = (uint8_t)(px & 255);
    out->y.e0 = (uint8_t)(py >> 8);
    out->y.e1 = (uint8_t)(py & 255);
    memcpy(out->x.index, ix, sizeof ix);
    memcpy(out->y.index, iy, sizeof iy);
    if (info) {
        info->error = metric_value(best, use_max ? SOL_BC5_MAX : SOL_BC5_SUM_SQUARED);
        info->searched = 1;
        info->candidates = candidates;
        info->bounded = bounded;
    }
    return 1;
}

static sol_status workspace_alloc(search_workspace *ws)
{
    ws->x = malloc(65536 * sizeof *ws->x);
    ws->y = malloc(65536 * sizeof *ws->y);
    ws->slots = malloc(2 * 65536 * sizeof *ws->slots);
    ws->yside = NULL;
    ws->yside_cap = 0;
    ws->win = malloc(sizeof *ws->win);
    if (!ws->x || !ws->y || !ws->slots || !ws->win) {
        free(ws->x);
        free(ws->y);
        free(ws->slots);
        free(ws->win);
        return SOL_ERR_NO_MEMORY;
    }
    return SOL_OK;
}

static void workspace_free(search_workspace *ws)
{
    free(ws->x);
    free(ws->y);
    free(ws->slots);
    free(ws->yside);
    free(ws->win);
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
    search_request rq = {r, o->precision, o->metric == SOL_BC5_MAX, work_limit(o)};
    search_unit(n, &rq, &ws, out, info);
    workspace_free(&ws);
    return SOL_OK;
}

/* ---- the three encoders ---- */

/* Common encoder: two independent least-squares BC4 blocks, indices by nearest component (T10). */
static void encode_common(const double n[16][3], sol_bc4_precision precision, sol_bc5_block *out)
{
    double tx[16], ty[16], s;
    for (int p = 0; p < 16; ++p) {
        tx[p] = n[p][0];
        ty[p] = n[p][1];
    }
    int px = sol_nm_bc4_common(tx, precision, &s), py = sol_nm_bc4_common(ty, precision, &s);
    const double(*pal)[8] = sol_nm_palettes(precision);
    out->x.e0 = (uint8_t)(px >> 8);
    out->x.e1 = (uint8_t)(px & 255);
    out->y.e0 = (uint8_t)(py >> 8);
    out->y.e1 = (uint8_t)(py & 255);
    for (int p = 0; p < 16; ++p) {
        out->x.index[p] = (uint8_t)sol_nm_nearest_index(pal[px], tx[p]);
        out->y.index[p] = (uint8_t)sol_nm_nearest_index(pal[py], ty[p]);
    }
}

/* The usual fast encoder: two independent one-pass alpha blocks (bc4_fast.c). */
static void encode_fast(const double n[16][3], sol_bc5_block *out)
{
    double tx[16], ty[16];
    for (int p = 0; p < 16; ++p) {
        tx[p] = n[p][0];
        ty[p] = n[p][1];
    }
    sol_nm_bc4_fast(tx, &out->x);
    sol_nm_bc4_fast(ty, &out->y);
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
    if (o->encoder == SOL_BC5_FAST) {
        encode_fast(n, out);
        if (info) {
            info->error = metric_value(own_index_objective(out, n, o->precision, use_max), o->metric);
            info->searched = 0;
            info->candidates = 1;
            info->bounded = 0;
        }
        return;
    }
    if (o->encoder == SOL_BC5_OPTIMAL) {
        search_request rq = {&full_range, o->precision, use_max, work_limit(o)};
        search_unit(n, &rq, ws, out, info);
        return;
    }
    sol_bc5_block common;
    if (o->encoder == SOL_BC5_ADAPTIVE && o->base == SOL_BC5_BASE_FAST)
        encode_fast(n, &common);
    else
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
            info->bounded = 0;
        }
        return;
    }
    int w = o->window == 0 ? 4 : (o->window < 0 ? 0 : o->window > 255 ? 255 : o->window); /* 255: all codes */
    sol_bc5_range r = {clamp_code(common.x.e0 - w), clamp_code(common.x.e0 + w), clamp_code(common.x.e1 - w),
                       clamp_code(common.x.e1 + w), clamp_code(common.y.e0 - w), clamp_code(common.y.e0 + w),
                       clamp_code(common.y.e1 - w), clamp_code(common.y.e1 + w)};
    search_request rq = {&r, o->precision, use_max, work_limit(o)};
    if (!window_search(n, &r, common.x.e0 << 8 | common.x.e1, common.y.e0 << 8 | common.y.e1, &rq, ws, out, info))
        search_unit(n, &rq, ws, out, info);
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
    if (o->encoder != SOL_BC5_COMMON && o->encoder != SOL_BC5_FAST && (st = workspace_alloc(&ws)) != SOL_OK)
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
    uint64_t searched = 0, candidates = 0, bounded = 0, max_cand = 0;
    int max_block = -1;
    int failed = 0;
#pragma omp parallel reduction(+ : searched, candidates, bounded) reduction(| : failed)
    {
        search_workspace ws = {0};
        if (o->encoder != SOL_BC5_COMMON && o->encoder != SOL_BC5_FAST && workspace_alloc(&ws) != SOL_OK)
            failed = 1;
        uint64_t my_max = 0;
        int my_block = -1;
#pragma omp for schedule(dynamic, 16)
        for (int b = 0; b < nblocks; ++b) {
            if (failed)
                continue;
            double raw[16][3], n[16][3];
            gather_block(normals, b % bw, b / bw, raw);
            sol_nm_unit_normals(raw, n);
            sol_bc5_block block;
            sol_bc5_info info = {0.0, 0, 1, 0};
            encode_unit(n, o, &ws, &block, o->encoder == SOL_BC5_FAST ? NULL : &info); /* fast: no error needed */
            pack_block(&block, blocks + 16 * (size_t)b);
            searched += (uint64_t)info.searched;
            bounded += (uint64_t)info.bounded;
            candidates += info.candidates;
            if (my_block < 0 || info.candidates > my_max) { /* blocks ascend within a thread */
                my_max = info.candidates;
                my_block = b;
            }
        }
#pragma omp critical(sol_bc5_max_block)
        if (my_block >= 0 && (max_block < 0 || my_max > max_cand || (my_max == max_cand && my_block < max_block))) {
            max_cand = my_max;
            max_block = my_block;
        }
        workspace_free(&ws);
    }
    if (failed)
        return SOL_ERR_NO_MEMORY;
    if (stats) {
        stats->blocks = (uint64_t)nblocks;
        stats->searched_blocks = searched;
        stats->candidates = candidates;
        stats->bounded_blocks = bounded;
        stats->max_block_candidates = max_cand;
        stats->max_block = max_block;
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
