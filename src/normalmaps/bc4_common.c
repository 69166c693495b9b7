/* bc4_common.c - the exact least-squares BC4 search of the common encoder (T10 "usual" per-channel
 * 3Dc encoding, T13's baseline) by branch and bound over boxes of anchor codes.
 *
 * Problem: 16 targets t_p (decoded units 2 v - 1), find the ordered anchor pair (e0, e1) of least
 * score S(e0, e1) = sum_p min_k (pal_k - t_p)^2 over all 65536 pairs, ties to the smallest
 * pair = e0 << 8 | e1 - exactly what sol_nm_channel_argmin returns on the full range (the same
 * score, summed in the same pixel order, so equal scores are bit-identical).
 *
 * Bounds. Write L for the low anchor and H for the high one (8-value mode e0 = H > e1 = L, 6-value
 * mode e0 = L <= e1 = H) and A(c) = 2 c / 255 - 1. Every palette entry is an anchor or an
 * interpolant (1 - w) A(L) + w A(H) with a fixed weight w (8-value: w = j / 7, j = 1..6; 6-value:
 * w = j / 5, j = 1..4) rounded by the decoder by at most delta (decoded units: 1/65535 for 16-bit
 * interpolants, 1/255 for 8-bit, 0 for float); the 6-value mode adds the fixed entries -1 and +1.
 * Since w is in [0, 1], an entry is non-decreasing in both A(L) and A(H), so over a box of codes
 * L in [L1, L2], H in [H1, H2] entry k stays inside the interval
 *     I_k = [(1 - w) A(L1) + w A(H1) - delta, (1 - w) A(L2) + w A(H2) + delta]
 * and every pair of the box scores at least
 *     LB(box) = sum_p min_k dist(t_p, I_k)^2.
 * A second bound counts entries: the targets' terms are each at most best, so the entries they use
 * lie in the window [tmin - r, tmax + r] (r = sqrt(best), width W); consecutive lattice entries are
 * at least step - 2 delta apart (step = (A(H) - A(L)) / den >= (A(H1) - A(L2)) / den over the box), so
 * at most floor(W / (step - 2 delta)) + 1 of them (plus the fixed entries inside the window) serve
 * the 16 targets, and the score is at least q[m], the least sum of squares of the targets to m free
 * points (1-D optimal quantisation: contiguous groups of the sorted targets, a small dynamic
 * programme). This is what prunes the long thin strips of pairs that have ONE entry near a narrow
 * block (the interval bound alone cannot: one entry is enough to make it zero).
 * Before the search, per mode, the same two facts give the region that can still reach the
 * incumbent (mode_region): L <= l_max, H >= h_min, H - L <= span_max.
 *
 * When at most one lattice entry fits in the window, a single entry e serves all 16 targets and the
 * score is exactly q[1] + 16 (e - mean)^2, so the bound adds 16 dist(mean, I_k)^2 (nearest interval):
 * this prunes the pairs of narrow blocks whose one entry misses the targets' mean. A box all of whose
 * pairs have at most one entry in the window is not split further: the pairs that can reach the
 * incumbent are those with an entry within R = sqrt((best - q[1]) / 16) (+ slack) of the mean,
 * listed directly per low anchor and weight as intervals of the high anchor (one_entry_scan) - the
 * interval bound cannot see this until its boxes are single pairs (blocks of an 8-bit source hold
 * two or three values, and hundreds of pairs put one entry on the same 16-bit value).
 * Wide blocks (at least WIDE_CODES codes) are searched by span instead (span_search: every pair of a
 * span shares one lattice step, so its score is bounded by the targets' fit to that lattice at any
 * phase, bc4_span_bound.c, in floats for eight or sixteen spans at a time; in a span that
 * survives, each low anchor L fixes the phase, A(L), and the same fit at that phase bounds the pair
 * (L, L + span): only the L whose phase is near one of the targets' best phases are scored).
 * Search: the incumbent is the best of the fast encoder's two candidate pairs (extreme_seeds) refined
 * by a least-squares refit of its anchors (refine) and, for blocks narrower than a few codes, palettes of
 * span 1-4 codes centred on the targets (narrow_seeds: the fast pair has span 0 there, and the refit
 * of a span-0 palette is singular), improved by steps to the best neighbouring pair (descend), all
 * scored exactly. On a smooth 16-bit map (blocks 0.2 codes wide) this is the optimum, and the
 * region below then holds a few dozen pairs instead of most of the 65536. Boxes are split in halves of the longer side,
 * the child of smaller bound visited first; a box is dropped when LB > best, or when LB >= best
 * and its smallest pair index is above the incumbent's (no pair inside can win the tie rule).
 * Boxes of at most SMALL_BOX pairs are scored pair by pair with the reference order and early
 * exit. Blocks of few distinct values (flat blocks, 8-bit sources) are searched by a walk over the
 * palette entry values instead (narrow_walk, below), which decides tied anchors by a rule. The bounds are lowered by a relative 1e-9 and delta is raised by 1e-12, far above the
 * rounding of these sums, so no bound exceeds the computed score of a pair it covers: the result is
 * the exhaustive search's, pair for pair (tests compare with the literal brute force). */
#include "normalmaps_internal.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

/* The hot functions (box_bound, try_pair, quantisation_bound) are also compiled for AVX2 and picked
 * at run time (GCC target_clones on x86-64), the quantisation programme's rows also for AVX-512: the
 * same operations in wider lanes - no FMA contraction (C11 mode), sums in the same order - so the
 * results are bit-identical to the baseline build. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define HOT_CLONES __attribute__((noinline, target_clones("avx512f", "avx2", "default")))
#else
#define HOT_CLONES __attribute__((noinline))
#endif

typedef double v4d __attribute__((vector_size(4 * sizeof(double))));
typedef long long v4l __attribute__((vector_size(4 * sizeof(long long))));
typedef double v8d __attribute__((vector_size(8 * sizeof(double))));
typedef long long v8l __attribute__((vector_size(8 * sizeof(long long))));

static inline double anchor(int c)
{
    return 2.0 * c / 255.0 - 1.0;
}

/* A pair's palette from its two codes (the search scores pairs at scattered indices, and a load from
 * the 4 MB palette table, sol_nm_palettes, missed the caches on most of them): every entry is an
 * anchor, an interpolant of weight numerator num = w0 e0 + w1 e1 over den 7 (8-value mode, e0 > e1:
 * entry i = 2..7 has num = (8 - i) e0 + (i - 1) e1) or den 5 (6-value mode: entry i = 2..5 has num =
 * (6 - i) e0 + (i - 1) e1), or the 6-value mode's fixed -1, +1, and the decoder's value of an
 * interpolant depends only on (num, den) (bc4.c). The tables below (26 KB per precision, cached) are
 * copied from the palette table itself, so every palette they give is bit-identical to its row.
 * (The same block holds the span search's lattice steps, for the same reason: no division per span.) */
typedef struct small_palettes {
    double anchor[256];
    double over7[7 * 255 + 1], over5[5 * 255 + 1];
    double step[2][256]; /* span_search's lattice steps (A(d) + 1) / den, den = 7 ([0]), 5 ([1]) */
} small_palettes;

static small_palettes smalls[SOL_BC4_PRECISION_COUNT];
static pthread_once_t smalls_once[SOL_BC4_PRECISION_COUNT] = {PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT,
                                                              PTHREAD_ONCE_INIT};

static void build_smalls(sol_bc4_precision precision)
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    small_palettes *sp = &smalls[precision];
    for (int d = 0; d < 256; ++d) {
        sp->step[0][d] = (anchor(d) + 1.0) / 7;
        sp->step[1][d] = (anchor(d) + 1.0) / 5;
    }
    for (int e0 = 0; e0 < 256; ++e0) {
        sp->anchor[e0] = pal[e0 << 8][0];
        for (int e1 = 0; e1 < 256; ++e1) {
            const double *row = pal[e0 << 8 | e1];
            if (e0 > e1)
                for (int i = 2; i < 8; ++i)
                    sp->over7[(8 - i) * e0 + (i - 1) * e1] = row[i];
            else
                for (int i = 2; i < 6; ++i)
                    sp->over5[(6 - i) * e0 + (i - 1) * e1] = row[i];
        }
    }
}
static void build_smalls_16bit(void) { build_smalls(SOL_BC4_INTERP_16BIT); }
static void build_smalls_8bit(void) { build_smalls(SOL_BC4_INTERP_8BIT); }
static void build_smalls_float(void) { build_smalls(SOL_BC4_INTERP_FLOAT); }

static const small_palettes *small_palettes_get(sol_bc4_precision precision)
{
    static void (*const builders[SOL_BC4_PRECISION_COUNT])(void) = {build_smalls_16bit, build_smalls_8bit,
                                                                    build_smalls_float};
    pthread_once(&smalls_once[precision], builders[precision]);
    return &smalls[precision];
}

/* The palette of pair = e0 << 8 | e1, as its row of the palette table. */
static inline __attribute__((always_inline)) void small_palette(const small_palettes *sp, int pair, double pal[8])
{
    const int e0 = pair >> 8, e1 = pair & 255;
    pal[0] = sp->anchor[e0];
    pal[1] = sp->anchor[e1];
    if (e0 > e1) {
        for (int i = 2; i < 8; ++i)
            pal[i] = sp->over7[(8 - i) * e0 + (i - 1) * e1];
    } else {
        for (int i = 2; i < 6; ++i)
            pal[i] = sp->over5[(6 - i) * e0 + (i - 1) * e1];
        pal[6] = -1.0;
        pal[7] = 1.0;
    }
}

void sol_nm_small_palette(sol_bc4_precision precision, int pair, double out[8])
{
    small_palette(small_palettes_get(precision), pair, out);
}

typedef struct common_ctx {
    const double *t;
    double to[16]; /* the targets in the reference order */
    const small_palettes *sp;
    const double (*pal)[8]; /* the palette table (try_pair_row) */
    double delta;
    double best;
    int best_pair;
    double tmin, tmax, mean;
    double window_best, wlo, whi; /* update_window */
    /* quantisation bound: q[m] = least sum of squares of the targets to m free points (m = 1..8),
     * rows of the dynamic programme computed on demand (q_rows of them so far) */
    double sorted[16], prefix[17], prefix2[17];
    double dp[9][16];
    double q[9], q_slack;
    int q_rows;
    double gcost[16][16]; /* group_cost(i, j) for i >= 1, tabulated with row 2 */
    const uint32_t *fa; /* first_above's bucket table (blocks that walk) */
} common_ctx;

/* Sum of squares of sorted[i..j] about their mean. */
static inline double group_cost(const common_ctx *c, int i, int j)
{
    static const double inv[17] = {0.0,       1.0,       1.0 / 2,  1.0 / 3,  1.0 / 4,  1.0 / 5,
                                   1.0 / 6,   1.0 / 7,   1.0 / 8,  1.0 / 9,  1.0 / 10, 1.0 / 11,
                                   1.0 / 12,  1.0 / 13,  1.0 / 14, 1.0 / 15, 1.0 / 16};
    double s = c->prefix[j + 1] - c->prefix[i], s2 = c->prefix2[j + 1] - c->prefix2[i];
    double v = s2 - s * s * inv[j - i + 1]; /* s^2 / n within a rounding (q_slack) */
    return v > 0.0 ? v : 0.0;
}

/* Row r >= 2 of the quantisation programme before its clean-up: b[j] = min over i of
 * dp[r - 1][i - 1] + gcost[i][j] (i from r - 1), i by i, each i updating every j at once (independent
 * lanes, no chain of dependent minima): four lanes of four (vector types: the compiler kept the 16
 * minima in scalars) for the AVX2 and baseline builds, two lanes of eight (one AVX-512 register each)
 * where the processor has AVX-512 - the minimum of the same sums either way. */
static inline __attribute__((always_inline)) void dp_row4(const common_ctx *c, int r, double b[16])
{
    const v4d zero = {0.0, 0.0, 0.0, 0.0};
    v4d b0 = zero + INFINITY, b1 = b0, b2 = b0, b3 = b0, g, v;
    v4l lt;
#define DP_LANE(bq, q)                                                                                                 \
    memcpy(&g, &c->gcost[i][4 * (q)], sizeof g);                                                                       \
    v = base + g;                                                                                                      \
    lt = v < bq;                                                                                                       \
    bq = (v4d)(((v4l)v & lt) | ((v4l)bq & ~lt))
    /* gcost[i][j] is infinite for j < i: lanes wholly below i are skipped */
    int i = r - 1;
    for (; i < 4; ++i) {
        const v4d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b0, 0);
        DP_LANE(b1, 1);
        DP_LANE(b2, 2);
        DP_LANE(b3, 3);
    }
    for (; i < 8; ++i) {
        const v4d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b1, 1);
        DP_LANE(b2, 2);
        DP_LANE(b3, 3);
    }
    for (; i < 12; ++i) {
        const v4d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b2, 2);
        DP_LANE(b3, 3);
    }
    for (; i < 16; ++i) {
        const v4d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b3, 3);
    }
#undef DP_LANE
    memcpy(b, &b0, sizeof b0);
    memcpy(b + 4, &b1, sizeof b1);
    memcpy(b + 8, &b2, sizeof b2);
    memcpy(b + 12, &b3, sizeof b3);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define HAVE_DP_ROW8 1
static __attribute__((noinline, target("avx512f"))) void dp_row8(const common_ctx *c, int r, double b[16])
{
    const v8d zero = {0.0};
    v8d b0 = zero + INFINITY, b1 = b0, g, v;
    v8l lt;
#define DP_LANE(bq, q)                                                                                                 \
    memcpy(&g, &c->gcost[i][8 * (q)], sizeof g);                                                                       \
    v = base + g;                                                                                                      \
    lt = v < bq;                                                                                                       \
    bq = (v8d)(((v8l)v & lt) | ((v8l)bq & ~lt))
    /* gcost[i][j] is infinite for j < i: the lane wholly below i is skipped */
    int i = r - 1;
    for (; i < 8; ++i) {
        const v8d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b0, 0);
        DP_LANE(b1, 1);
    }
    for (; i < 16; ++i) {
        const v8d base = zero + c->dp[r - 1][i - 1];
        DP_LANE(b1, 1);
    }
#undef DP_LANE
    memcpy(b, &b0, sizeof b0);
    memcpy(b + 8, &b1, sizeof b1);
}
#else
#define HAVE_DP_ROW8 0
#endif

/* q[m]: 1-D optimal m-point quantisation of the 16 targets (contiguous groups of the sorted values).
 * Row r of the programme, dp[r][j] = min over i of dp[r - 1][i - 1] + cost(i..j), is taken i by i,
 * each i updating every j >= i at once (independent lanes, no chain of dependent minima); the minimum
 * of the same sums whatever the order. */
static HOT_CLONES double quantisation_bound(common_ctx *c, int m)
{
    while (c->q_rows < m) {
        int r = ++c->q_rows;
        if (r == 1) {
            for (int j = 0; j < 16; ++j)
                c->dp[1][j] = group_cost(c, 0, j);
        } else {
            if (r == 2) /* group_cost(i, j), in 16 lanes (j < i: no group, infinite cost, so that every
                         * row below runs all 16 lanes; inv_n[15 + n] = 1 / n) */
                for (int i = 1; i < 16; ++i) {
                    static const double inv_n[32] = {0.0,      0.0,      0.0,      0.0,      0.0,      0.0,
                                                     0.0,      0.0,      0.0,      0.0,      0.0,      0.0,
                                                     0.0,      0.0,      0.0,      0.0,      1.0,      1.0 / 2,
                                                     1.0 / 3,  1.0 / 4,  1.0 / 5,  1.0 / 6,  1.0 / 7,  1.0 / 8,
                                                     1.0 / 9,  1.0 / 10, 1.0 / 11, 1.0 / 12, 1.0 / 13, 1.0 / 14,
                                                     1.0 / 15, 1.0 / 16};
                    const double pi = c->prefix[i], p2i = c->prefix2[i];
                    for (int j = 0; j < 16; ++j) {
                        double sj = c->prefix[j + 1] - pi, s2 = c->prefix2[j + 1] - p2i;
                        double v = s2 - sj * sj * inv_n[j - i + 16];
                        v = v > 0.0 ? v : 0.0;
                        c->gcost[i][j] = j < i ? INFINITY : v;
                    }
                }
            double b[16];
#if HAVE_DP_ROW8
            if (__builtin_cpu_supports("avx512f"))
                dp_row8(c, r, b);
            else
#endif
                dp_row4(c, r, b);
            for (int j = 0; j < 16; ++j)
                c->dp[r][j] = r - 1 > j ? 0.0 : b[j];
        }
        c->q[r] = c->dp[r][15];
    }
    return c->q[m];
}

static inline int make_pair(int six, int l, int h)
{
    return six ? (l << 8 | h) : (h << 8 | l);
}


/* Exact score of a pair in the reference order, with early exit once above budget (checked after
 * the first 8 targets). The per-target minimum is exact whatever the order it is taken in, and the
 * 16 terms are added one by one in the reference order, so the sum is bit-identical to the brute
 * force's. Written target-parallel, 8 targets at a time, so that the compiler vectorises it. */
static inline __attribute__((always_inline)) double exact_score(const common_ctx *c, const double pal[8],
                                                                double budget)
{
    double s = 0.0;
    for (int k0 = 0; k0 < 16; k0 += 8) {
        double m[8];
        for (int k = 0; k < 8; ++k) {
            double d = pal[0] - c->to[k0 + k];
            m[k] = d * d;
        }
#pragma GCC unroll 7
        for (int i = 1; i < 8; ++i)
            for (int k = 0; k < 8; ++k) {
                double d = pal[i] - c->to[k0 + k];
                d *= d;
                m[k] = d < m[k] ? d : m[k];
            }
        for (int k = 0; k < 8; ++k)
            s += m[k];
        if (s > budget)
            return s;
    }
    return s;
}

/* Bound on the rounding error of the computed mean of the 16 targets (|t| <= 1: 15 additions of
 * at most 16 in magnitude, then an exact division by 16), for the one-entry bound below. */
#define MEAN_ERR 4e-15

/* The window [tmin - r, tmax + r] of the entries the targets use, r = sqrt(best) (with slack), for
 * the incumbent's current score (recomputed when it changes). */
static inline void update_window(common_ctx *c)
{
    if (c->window_best == c->best)
        return;
    double r = sqrt(c->best) * (1.0 + 1e-9) + 1e-12;
    c->wlo = c->tmin - r;
    c->whi = c->tmax + r;
    c->window_best = c->best;
}

/* At most how many entries of a pair of the box (low anchors up to l2, high anchors from h1) lie in
 * the window (8 when the box allows entries closer than 2 delta). */
static inline int box_used(common_ctx *c, int six, int l2, int h1)
{
    const int den = six ? 5 : 7;
    update_window(c);
    const double gap = (anchor(h1) - anchor(l2)) / den - 2.0 * c->delta;
    if (!(gap > 0.0))
        return 8;
    double fit = floor((c->whi - c->wlo) / gap) + 1.0;
    int used = fit < (double)(den + 1) ? (int)fit : den + 1;
    if (six)
        used += (c->wlo <= -1.0) + (c->whi >= 1.0);
    return used;
}

/* Lower bound of the score of every pair of the box (see the top of the file); stops once above budget. */
static HOT_CLONES double box_bound(common_ctx *c, int six, int l1, int l2, int h1, int h2, double budget)
{
    const int den = six ? 5 : 7;
    const double al1 = anchor(l1), al2 = anchor(l2), ah1 = anchor(h1), ah2 = anchor(h2), d = c->delta;
    /* the used entries lie within r = sqrt(best) of a target, so in a window of width W; entries are
     * at least step - 2 delta apart, so at most floor(W / (step - 2 delta)) + 1 of them are there */
    const int used = box_used(c, six, l2, h1);
    if (used > 1 && used < 8) {
        double qb = quantisation_bound(c, used) * (1.0 - 1e-9) - c->q_slack;
        if (qb > budget)
            return qb;
    }
    /* the entries' intervals: the anchors (with a 1e-12 margin for their rounding), the interpolants
     * of weight w = j / den, each widened by delta (the 6-value mode's fixed entries -1, +1 below) */
    double lo[8], hi[8];
    lo[0] = al1 - 1e-12;
    hi[0] = al2 + 1e-12;
    lo[1] = ah1 - 1e-12;
    hi[1] = ah2 + 1e-12;
    for (int j = 1; j < den; ++j) {
        double w = (double)j / den;
        lo[j + 1] = (1.0 - w) * al1 + w * ah1 - d;
        hi[j + 1] = (1.0 - w) * al2 + w * ah2 + d;
    }
    if (used == 1) { /* one entry e serves all 16 targets: score = q[1] + 16 (e - mean)^2 */
        double dm = INFINITY;
        for (int i = 0; i <= den; ++i) {
            double e = lo[i] > c->mean ? lo[i] - c->mean : (hi[i] < c->mean ? c->mean - hi[i] : 0.0);
            dm = e < dm ? e : dm;
        }
        if (six) /* the fixed entries */
            dm = fmin(dm, fmin(fabs(c->mean + 1.0), fabs(c->mean - 1.0)));
        dm = dm > MEAN_ERR ? dm - MEAN_ERR : 0.0;
        double qb = (quantisation_bound(c, 1) + 16.0 * dm * dm) * (1.0 - 1e-9) - c->q_slack;
        if (qb > budget)
            return qb;
    }
    if (six) {
        lo[6] = hi[6] = -1.0;
        lo[7] = hi[7] = 1.0;
    }
    /* interval by interval, four targets at a time (independent lanes, 8 intervals in either mode:
     * the compiler vectorises it), the outer sorted targets first (the likeliest to be far from a
     * poor palette), stopping once above budget (a partial sum is a bound too) */
    static const int chunk_order[4] = {0, 12, 4, 8};
    double s = 0.0;
    for (int q = 0; q < 4; ++q) {
        const double *tp = c->sorted + chunk_order[q];
        double m[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
        for (int i = 0; i < 8; ++i) {
            const double l = lo[i], h = hi[i];
            for (int p = 0; p < 4; ++p) {
                /* dist^2 = max(lo - t, 0)^2 + max(t - hi, 0)^2 (one of them is 0), branch-free with
                 * max(x, 0) = (x + |x|) / 2 (exact) */
                double a = l - tp[p], b = tp[p] - h;
                double pa = a + fabs(a), pb = b + fabs(b);
                double e2 = 0.25 * (pa * pa + pb * pb);
                m[p] = m[p] < e2 ? m[p] : e2;
            }
        }
        s += (m[0] + m[1]) + (m[2] + m[3]);
        if (s * (1.0 - 1e-12) > budget)
            break;
    }
    return s * (1.0 - 1e-12);
}

typedef struct box {
    double bound;
    uint8_t l1, l2, h1, h2;
} box;

/* The smallest pair index of a box: 8-value pairs are H << 8 | L, 6-value pairs L << 8 | H. */
static inline int box_min_pair(int six, const box *b)
{
    return six ? (b->l1 << 8 | b->h1) : (b->h1 << 8 | b->l1);
}

static inline int box_hopeless(const common_ctx *c, int six, const box *b)
{
    return b->bound > c->best || (b->bound >= c->best && box_min_pair(six, b) > c->best_pair);
}

/* The part of a mode's pairs that can still reach the incumbent (computed once per mode): low anchor
 * L <= l_max, high anchor H >= h_min, span H - L <= span_max codes. */
typedef struct region {
    int gap; /* 8-value: H >= L + 1; 6-value: H >= L */
    int l_max, h_min, span_max;
} region;

/* Clips a box to the region; 0 if no pair is left. */
static int box_clip(const region *g, int l1, int l2, int h1, int h2, box *b)
{
    l2 = l2 < g->l_max ? l2 : g->l_max;
    h1 = h1 > g->h_min ? h1 : g->h_min;
    if (h1 < l1 + g->gap)
        h1 = l1 + g->gap;
    if (l2 > h2 - g->gap)
        l2 = h2 - g->gap;
    if (h2 > l2 + g->span_max)
        h2 = l2 + g->span_max;
    if (l1 < h1 - g->span_max)
        l1 = h1 - g->span_max;
    if (l1 > l2 || h1 > h2)
        return 0;
    b->l1 = (uint8_t)l1;
    b->l2 = (uint8_t)l2;
    b->h1 = (uint8_t)h1;
    b->h2 = (uint8_t)h2;
    return 1;
}

static int code_floor(double v)
{
    double c = floor((v + 1.0) * 127.5 + 1e-7);
    return c < 0.0 ? -1 : (c > 255.0 ? 255 : (int)c);
}

static int code_ceil(double v)
{
    double c = ceil((v + 1.0) * 127.5 - 1e-7);
    return c < 0.0 ? 0 : (c > 255.0 ? 256 : (int)c);
}

/* The region of a mode from the incumbent (score `best`); 0 if the whole mode is out of reach.
 * - Every entry of an 8-value palette lies in [A(L), A(H)], so the smallest target, whose term is at
 *   most best, needs A(L) <= tmin + r and A(H) >= tmax - r, r = sqrt(best) (6-value: unless the
 *   fixed -1 / +1 entry is within r of it).
 * - The entries the targets use lie in the window [tmin - r, tmax + r] of width W, so (as in
 *   box_bound) a palette of step s holds at most floor(W / (s - 2 delta)) + 1 lattice entries
 *   there, plus the fixed entries inside the window; with m_min the fewest entries whose
 *   quantisation bound q[m] does not exceed best, s <= W / (m_min - fixed - 1) + 2 delta, and the
 *   span H - L = den s (decoded units) follows. */
static int mode_region(common_ctx *c, int six, region *g)
{
    double r = sqrt(c->best) * (1.0 + 1e-9) + 1e-12, wlo = c->tmin - r, whi = c->tmax + r;
    int den = six ? 5 : 7, fixed = six ? (wlo <= -1.0) + (whi >= 1.0) : 0;
    g->gap = six ? 0 : 1;
    g->l_max = six && wlo <= -1.0 ? 255 : code_floor(c->tmin + r);
    g->h_min = six && whi >= 1.0 ? 0 : code_ceil(c->tmax - r);
    g->span_max = 255;
    int m_min = 0;
    for (int m = 1; m <= den + 1 + fixed && !m_min; ++m)
        if (quantisation_bound(c, m) * (1.0 - 1e-9) - c->q_slack <= c->best)
            m_min = m;
    if (!m_min)
        return 0;
    if (m_min - fixed >= 2) {
        double step = (whi - wlo) / (m_min - fixed - 1) + 2.0 * c->delta;
        double span = floor(den * step * 127.5 + 1e-7);
        g->span_max = span < 255.0 ? (int)span : 255;
    }
    return g->l_max >= 0 && g->h_min <= 255;
}

static HOT_CLONES void try_pair(common_ctx *c, int pair)
{
    double pal[8];
    small_palette(c->sp, pair, pal);
    double v = exact_score(c, pal, c->best);
    if (v < c->best || (v == c->best && pair < c->best_pair)) {
        c->best = v;
        c->best_pair = pair;
    }
}

/* The same with the palette read from its table row: the walk below scores the pairs holding a
 * value, and on smooth 8-bit maps neighbouring blocks hold the same values, so those rows stay in
 * the caches and the load is cheaper than building the palette. */
static HOT_CLONES void try_pair_row(common_ctx *c, int pair)
{
    double v = exact_score(c, c->pal[pair], c->best);
    if (v < c->best || (v == c->best && pair < c->best_pair)) {
        c->best = v;
        c->best_pair = pair;
    }
}

/* try_pair on pairs[0 .. n), in that order. */
static void try_pairs(common_ctx *c, const int *pairs, int n)
{
    for (int i = 0; i < n; ++i)
        try_pair(c, pairs[i]);
}

/* Boxes of at most this many pairs are scored pair by pair (exact scores exit early; cheaper than
 * splitting further, measured on the benchmark maps). */
#define SMALL_BOX 16

/* A box whose pairs have at most one entry in the window (box_used == 1): such a pair reaches the
 * incumbent only if its one serving entry e has q[1] + 16 (e - mean)^2 <= best, i.e. lies within
 * R of the mean. Its pairs are listed directly instead of split further (the interval bound cannot
 * see this until the boxes are single pairs): for each low anchor L, the row when A(L) is within
 * R, the high anchors H with A(H) within R, and for each interpolant weight w the H whose exact
 * entry (1 - w) A(L) + w A(H) is within R + delta (an interval of H). Returns 0 (nothing done) when
 * a 6-value fixed entry is within R: then every pair qualifies.
 * A row (or column) whose anchor A is within R needs only its least pair: every pair of it scores at
 * most S = sum_p (A - t_p)^2 (A is one of its entries); if S <= best, each of its pairs scores <= best,
 * so its one entry in the window serves every target, and that entry is A (A is in the window):
 * every pair scores exactly S, the same terms added in the same order; if S > best, a pair scoring
 * <= best would be served by its one window entry, A, and score S: none does. The least pair of a
 * row of low anchor L is the least H in either mode (8-value H << 8 | L, 6-value L << 8 | H), of a
 * column the least L. */
static int one_entry_scan(common_ctx *c, int six, const box *b)
{
    const int den = six ? 5 : 7, gap = six ? 0 : 1;
    double slack = c->best * (1.0 + 2e-9) + 2.0 * c->q_slack - quantisation_bound(c, 1) * (1.0 - 1e-9);
    const double r = sqrt((slack > 0.0 ? slack : 0.0) / 16.0) * (1.0 + 1e-9) + MEAN_ERR + 1e-12, m = c->mean;
    if (six && (fabs(m + 1.0) <= r || fabs(m - 1.0) <= r))
        return 0;
    const int a_lo = code_ceil(m - r), a_hi = code_floor(m + r); /* anchors within r */
    for (int h = a_lo > b->h1 ? a_lo : b->h1; h <= a_hi && h <= b->h2; ++h) /* the high anchor: a column */
        if (b->l1 + gap <= h)
            try_pair(c, make_pair(six, b->l1, h)); /* its least pair (see below) */
    for (int l = b->l1; l <= b->l2; ++l) {
        const int h_lo = b->h1 > l + gap ? b->h1 : l + gap;
        const double al = anchor(l);
        if (l >= a_lo && l <= a_hi) { /* the low anchor itself: a row, its least pair */
            if (h_lo <= b->h2)
                try_pair(c, make_pair(six, l, h_lo));
            continue;
        }
        for (int j = 1; j < den; ++j) { /* interpolant of weight w = j / den */
            double w = (double)j / den, reach = r + c->delta;
            int h1 = code_ceil(al + (m - reach - al) / w), h2 = code_floor(al + (m + reach - al) / w);
            h1 = h1 > h_lo ? h1 : h_lo;
            h2 = h2 < b->h2 ? h2 : b->h2;
            for (int h = h1; h <= h2; ++h)
                try_pair(c, make_pair(six, l, h));
        }
    }
    return 1;
}

static void search_mode(common_ctx *c, int six)
{
    box stack[64];
    int top = 0;
    region g;
    if (!mode_region(c, six, &g) || !box_clip(&g, 0, 255, 0, 255, &stack[0]))
        return;
    stack[0].bound = 0.0;
    top = 1;
    while (top > 0) {
        box b = stack[--top];
        if (box_hopeless(c, six, &b))
            continue;
        if ((b.l2 - b.l1 + 1) * (b.h2 - b.h1 + 1) <= SMALL_BOX) { /* score its pairs directly */
            if (six) /* pairs in table order (L << 8 | H): neighbouring palettes */
                for (int l = b.l1; l <= b.l2; ++l)
                    for (int h = b.h1 > l ? b.h1 : l; h <= b.h2; ++h)
                        try_pair(c, l << 8 | h);
            else /* H << 8 | L */
                for (int h = b.h1; h <= b.h2; ++h)
                    for (int l = b.l1; l <= b.l2 && l < h; ++l)
                        try_pair(c, h << 8 | l);
            continue;
        }
        if (box_used(c, six, b.l2, b.h1) == 1 && one_entry_scan(c, six, &b))
            continue;
        box kid[2];
        int nk = 0;
        if (b.l2 - b.l1 >= b.h2 - b.h1) {
            int mid = (b.l1 + b.l2) >> 1;
            nk += box_clip(&g, b.l1, mid, b.h1, b.h2, &kid[nk]);
            nk += box_clip(&g, mid + 1, b.l2, b.h1, b.h2, &kid[nk]);
        } else {
            int mid = (b.h1 + b.h2) >> 1;
            nk += box_clip(&g, b.l1, b.l2, b.h1, mid, &kid[nk]);
            nk += box_clip(&g, b.l1, b.l2, mid + 1, b.h2, &kid[nk]);
        }
        for (int i = 0; i < nk; ++i)
            kid[i].bound = box_bound(c, six, kid[i].l1, kid[i].l2, kid[i].h1, kid[i].h2, c->best);
        if (nk == 2 && kid[1].bound > kid[0].bound) { /* push the better one last: visited first */
            box tmp = kid[0];
            kid[0] = kid[1];
            kid[1] = tmp;
        }
        for (int i = 0; i < nk; ++i)
            if (!box_hopeless(c, six, &kid[i]))
                stack[top++] = kid[i];
    }
}

/* Span search: the same pairs as search_mode, by span. Every pair of span d = H - L is bounded by
 * the larger of two lower bounds that hold whatever L is:
 * - the lattice bound (sol_nm_span_bounds): the targets against an infinite lattice of the span's
 *   step, any phase;
 * - the ends bound: the entries lie in [A(L) - delta, A(H) + delta], an interval of width
 *   D = A(d) + 1 + 2 delta, so of the disjoint pairs of sorted targets (t_i, t_15-i) at least
 *   (t_15-i - t_i - D) is left outside, and the two terms sum to at least half its square.
 * The spans of the region whose bound reaches the incumbent are visited least bound first; in each,
 * the low anchors of the region whose phase bound (sol_nm_span_phase_bound: the lattice fit at the
 * phase A(L), from the span's 16 cut sequences; its F for all the span's L at once, four lanes at a
 * time, by sol_nm_span_phase_fs) reaches the incumbent are scored exactly (early exit)
 * in ascending order, so ties go to the least pair as in the reference (a skipped pair scores above
 * the incumbent). Used for wide blocks, whose region is long in the span direction
 * and whose few surviving spans hold a few pairs each (on the benchmark maps 5-10% of the region's
 * pairs), where the boxes' per-target intervals, blind to the phase all entries share, had to be
 * split to single pairs. The 6-value mode uses it only when the fixed entries -1, +1 are out of
 * reach of every target (no pair scoring <= best uses them); otherwise the box search. */
static double ends_bound(const common_ctx *c, double width)
{
    double s = 0.0;
    for (int i = 0; i < 8; ++i) {
        double e = c->sorted[15 - i] - c->sorted[i] - width;
        if (!(e > 0.0))
            break; /* the pairs narrow inward */
        s += 0.5 * e * e;
    }
    return s * (1.0 - 1e-9);
}

static void span_search(common_ctx *c, int six)
{
    region g;
    if (!mode_region(c, six, &g))
        return;
    if (six) {
        double r = sqrt(c->best) * (1.0 + 1e-9) + 1e-12;
        if (c->tmin - r <= -1.0 || c->tmax + r >= 1.0) {
            search_mode(c, six);
            return;
        }
    }
    int d_lo = g.h_min - g.l_max, d_hi = g.span_max;
    d_lo = d_lo > g.gap ? d_lo : g.gap;
    int spans[256], n = 0;
    double lb[256];
    /* the ends bound is non-increasing in the span (its width grows, each term shrinks), so the spans
     * it leaves are those from the first it leaves on */
    int d_first = d_lo;
    while (d_first <= d_hi && ends_bound(c, anchor(d_first) + 1.0 + 2.0 * c->delta + 1e-12) > c->best)
        ++d_first;
    /* the lattice bound of each, and the ends bound of those it leaves */
    const int nd = d_hi - d_first + 1;
    double steps[256 + 16], lat[256 + 16];
    for (int k = 0; k < nd; ++k)
        steps[k] = c->sp->step[six][d_first + k]; /* (A(d) + 1) / den, tabulated */
    for (int k = nd > 0 ? nd : 0; k % 16; ++k) /* padding lanes: no step */
        steps[k] = 0.0;
    sol_nm_span_bounds_all(c->sorted, steps, nd, c->delta, c->best, lat);
    for (int k = 0; k < nd; ++k) {
        if (lat[k] > c->best)
            continue;
        const double e = ends_bound(c, anchor(d_first + k) + 1.0 + 2.0 * c->delta + 1e-12);
        double l = lat[k] > e ? lat[k] : e;
        if (l > c->best)
            continue;
        int q = n++; /* insertion by bound, then span */
        for (; q > 0 && lb[q - 1] > l; --q) {
            lb[q] = lb[q - 1];
            spans[q] = spans[q - 1];
        }
        lb[q] = l;
        spans[q] = d_first + k;
    }
    sol_nm_span_cuts cuts[SOL_NM_SPAN_LANES];
    for (int i = 0; i < n && lb[i] <= c->best; ++i) {
        if (i % SOL_NM_SPAN_LANES == 0) { /* the cut data of the next four spans to visit */
            double step[SOL_NM_SPAN_LANES];
            for (int k = 0; k < SOL_NM_SPAN_LANES; ++k)
                step[k] = i + k < n ? c->sp->step[six][spans[i + k]] : 0.0;
            sol_nm_span_cuts4(c->sorted, step, cuts);
        }
        sol_nm_span_cuts *cu = &cuts[i % SOL_NM_SPAN_LANES];
        /* a low anchor whose F exceeds fstar = F* (1 + 1e-6), F* = (4 delta + sqrt(16 delta^2 + best))^2
         * (where F - 8 delta sqrt(F) = best; increasing beyond), has a bound above best (1 + 1e-6)
         * (since F* - 4 delta sqrt(F*) >= best): it cannot reach the incumbent. Only the cuts with
         * v <= fstar can bring F below fstar. */
        double r = 4.0 * c->delta + sqrt(16.0 * c->delta * c->delta + c->best), fstar = r * r * (1.0 + 1e-6);
        sol_nm_span_cuts_keep(cu, fstar + cu->slack);
        int d = spans[i], l1 = g.h_min - d, l2 = 255 - d;
        l1 = l1 > 0 ? l1 : 0;
        l2 = l2 < g.l_max ? l2 : g.l_max;
        if (l1 > l2)
            continue;
        double f[256];
        sol_nm_span_phase_fs(cu, l1, l2 - l1 + 1, f);
        int pairs[256], np = 0;
        for (int l = l1; l <= l2; ++l) { /* branch-free: each written, the kept ones advance */
            pairs[np] = make_pair(six, l, l + d);
            np += f[l - l1] <= fstar;
        }
        try_pairs(c, pairs, np);
    }
}

/* Scores the pair (L = a, H = b) of a mode if it is a valid pair of that mode; when it becomes the
 * incumbent, (*nl, *nh) move to it (the incumbent searches below walk this way). */
static void try_move(common_ctx *c, int six, int a, int b, int *nl, int *nh)
{
    if (a < 0 || b > 255 || b < a + !six)
        return;
    int before = c->best_pair;
    try_pair(c, make_pair(six, a, b));
    if (c->best_pair != before) {
        *nl = a;
        *nh = b;
    }
}

/* A better incumbent for the bounds: from a pair of a mode, a least-squares refit of the two anchors
 * to the targets' lattice positions (the classic alpha-block refinement), rounded both ways, a few
 * times. Only an incumbent: the search below proves or improves it. */
static void refine(common_ctx *c, int six, int l, int h)
{
    static const double weight[2][8] = {{0.0, 1.0 / 7, 2.0 / 7, 3.0 / 7, 4.0 / 7, 5.0 / 7, 6.0 / 7, 1.0},
                                        {0.0, 1.0 / 5, 2.0 / 5, 3.0 / 5, 4.0 / 5, 1.0, 0.0, 0.0}};
    const int den = six ? 5 : 7;
    int l_prev = -1000, h_prev = -1000; /* the previous round's rounded refit */
    for (int round = 0; round < 3; ++round) {
        double al = anchor(l), ah = anchor(h), step = (ah - al) / den, inv = step > 0.0 ? 1.0 / step : 0.0;
        double saa = 0.0, sab = 0.0, sbb = 0.0, sat = 0.0, sbt = 0.0;
        for (int p = 0; p < 16; ++p) {
            /* the nearest lattice position (round to nearest by the 1.5 2^52 addition: |k| < 2^51) */
            double t = c->t[p], k = ((t - al) * inv + 0x1.8p52) - 0x1.8p52;
            k = k < 0.0 ? 0.0 : (k > den ? den : k);
            const double below = fabs(t + 1.0), above = fabs(t - 1.0); /* the fixed entries' distances */
            if (six && fabs(t - (al + k * step)) > (above < below ? above : below))
                continue; /* served by a fixed entry */
            double b = weight[six][(int)k], a = 1.0 - b; /* k / den */
            saa += a * a;
            sab += a * b;
            sbb += b * b;
            sat += a * t;
            sbt += b * t;
        }
        double det = saa * sbb - sab * sab;
        if (!(fabs(det) > 1e-12))
            return;
        double fl = (sat * sbb - sbt * sab) / det, fh = (sbt * saa - sat * sab) / det;
        int l0 = code_floor(fl), h0 = code_floor(fh), nl = l, nh = h;
        /* the same refit as the previous round's: its four pairs are scored already, and scoring a
         * pair again cannot change the incumbent (it is at least as good as that pair, and no later
         * than it on a tie) - the usual end of the refit (issue 13, common-speed) */
        if (l0 == l_prev && h0 == h_prev)
            return;
        l_prev = l0;
        h_prev = h0;
        for (int dl = 0; dl < 2; ++dl)
            for (int dh = 0; dh < 2; ++dh)
                try_move(c, six, l0 + dl, h0 + dh, &nl, &nh);
        if (nl == l && nh == h)
            return;
        l = nl;
        h = nh;
    }
}

/* Incumbent: from a pair of a mode, steps to the best of its 8 neighbours (L +- 1, H +- 1) while
 * that improves the score (a local minimum of the pair grid). */
static void descend(common_ctx *c, int six, int l, int h)
{
    for (int round = 0; round < 64; ++round) {
        int nl = l, nh = h;
        for (int dl = -1; dl <= 1; ++dl)
            for (int dh = -1; dh <= 1; ++dh)
                if (dl | dh)
                    try_move(c, six, l + dl, h + dh, &nl, &nh);
        if (nl == l && nh == h)
            return;
        l = nl;
        h = nh;
    }
}

/* Incumbent seeds: the usual fast encoder's two candidates (bc4_fast.c: anchors at the block's
 * extreme codes, 8-value (max, min), 6-value (min, max) of the codes the fixed entries do not serve),
 * both scored exactly at this precision (the fast encoder keeps one by its 8-bit error and computes
 * indices this search does not need). */
static void extreme_seeds(common_ctx *c)
{
    int lo, hi, lo6, hi6;
    sol_nm_bc4_fast_anchors(c->t, &lo, &hi, &lo6, &hi6);
    if (hi > lo)
        try_pair(c, hi << 8 | lo);
    try_pair(c, lo6 << 8 | hi6);
}

/* Incumbent seeds for narrow blocks: per mode, palettes of small span S (codes) whose lattice is
 * centred on the targets' range (the fast encoder's pair has span 0 there, and its refit fails). */
static void narrow_seeds(common_ctx *c)
{
    double centre = 0.5 * (c->tmin + c->tmax), range = (c->tmax - c->tmin) * 127.5;
    int smax = (int)range + 2;
    smax = smax > 4 ? 4 : smax;
    for (int six = 0; six < 2; ++six)
        for (int s = 1; s <= smax; ++s) {
            int l0 = (int)floor((centre + 1.0) * 127.5 - 0.5 * s);
            for (int l = l0; l <= l0 + 1; ++l)
                if (l >= 0 && l + s <= 255)
                    try_pair(c, make_pair(six, l, l + s));
        }
}

/* ---- blocks of few distinct values (8-bit sources, flat blocks): a walk over the entry values ----
 * A pair's term for a target t is min_i (pal_i - t)^2 over its entries, so it is decided by the entry
 * of its palette nearest to t; every entry is one of the distinct values V of the entry index
 * (bc4_entries.c). Pick the target value u held by the most targets and walk V outward from u in
 * order of d(e) = (e - u)^2 (the value just below u or just above it, whichever is nearer, then the
 * next, ...), scoring exactly every pair that holds the visited value. A pair none of whose entries
 * has been visited has a term >= d for the targets equal to u, and every target's term is at least
 * lb(t) = the least (e - t)^2 over all of V (at the value just below or just above t: (e - t)^2 as
 * computed is monotone in |e - t| on either side), so, floating-point addition being monotone, it
 * scores at least LB(d) = the reference-order sum of d (targets equal to u) and lb(t) (the others).
 * The walk stops when LB(d) > best: every pair that could still reach the incumbent (score < best,
 * or = best with a smaller index) has been scored, so the result is the exhaustive search's.
 * The values are listed with the pairs holding them; a value e held by a pair whose other entries
 * are all at least 2 D away (D = the largest |e - t| over the targets) serves every target of the
 * block for that pair (the others are no nearer to any target), so all such pairs of e score exactly
 * the same sum of (e - t)^2 in the same order: only the least of them is scored (the later ones can
 * only tie with a larger index). This is the rule that decides the tied anchors of flat blocks:
 * with 16 equal targets the walk stops after the nearest value(s), whose least holder wins, and an
 * anchor value held by ~500 pairs costs one score plus a pass over its list.
 * Returns 0 if the walk lists more than max_work pairs (the values -1 and +1 the 6-value mode holds
 * in every palette, targets far apart): then the box search below finishes from the incumbent found
 * so far. */
/* The block's distinct values, each with its least term over every entry value and how many
 * targets hold it, and per target (reference order) its least term and which value it is. */
typedef struct walk_plan {
    int nv;
    double val[16], term[16];
    int count[16];
    double lb[16];
    int of[16];
} walk_plan;

static int distinct_values(const common_ctx *c)
{
    int nv = 1;
    for (int p = 1; p < 16; ++p)
        nv += c->sorted[p] != c->sorted[p - 1];
    return nv;
}

/* The first entry value above x in value[lo .. hi) (hi if none), by bisection. */
static size_t bisect_above(const double *value, size_t lo, size_t hi, double x)
{
    while (lo < hi) {
        size_t mid = (lo + hi) >> 1;
        if (value[mid] <= x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The bisection of first_above started from a bucket: above[b] = the first entry value above the
 * edge -1 + b / FA_BUCKETS * 2 (b = 0 .. FA_BUCKETS), per precision, so that x between two edges
 * has its answer between theirs (first_above is non-decreasing in x) and the bisection runs over a
 * few dozen values near x instead of the ~10^5-10^6 of the index, whose first ~15 levels missed the
 * caches (issue 13, common-speed: the walk's ~3 searches per distinct value were most of
 * sol_nm_bc4_common's own time on the noise map, perf). */
#define FA_BUCKETS 4096
static uint32_t fa_table[SOL_BC4_PRECISION_COUNT][FA_BUCKETS + 1];
static pthread_once_t fa_once[SOL_BC4_PRECISION_COUNT] = {PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT};

static inline double fa_edge(int b)
{
    return -1.0 + b * (2.0 / FA_BUCKETS); /* exact: b 2^-11 */
}

static void build_fa(sol_bc4_precision precision)
{
    const sol_nm_entry_index *ix = sol_nm_entry_index_get(precision);
    for (int b = 0; b <= FA_BUCKETS; ++b)
        fa_table[precision][b] = ix ? (uint32_t)bisect_above(ix->value, 0, ix->count, fa_edge(b)) : 0;
}
static void build_fa_16bit(void) { build_fa(SOL_BC4_INTERP_16BIT); }
static void build_fa_8bit(void) { build_fa(SOL_BC4_INTERP_8BIT); }
static void build_fa_float(void) { build_fa(SOL_BC4_INTERP_FLOAT); }

static const uint32_t *fa_get(sol_bc4_precision precision)
{
    static void (*const builders[SOL_BC4_PRECISION_COUNT])(void) = {build_fa_16bit, build_fa_8bit, build_fa_float};
    pthread_once(&fa_once[precision], builders[precision]);
    return fa_table[precision];
}

/* The first entry value above x (count if none): the same index as bisect_above over the whole
 * index (tested against it), from the bucket table fa of the index's precision. */
static size_t first_above(const sol_nm_entry_index *ix, const uint32_t *fa, double x)
{
    if (x != x)
        return 0; /* no value is <= NaN: the bisection's answer */
    const double y = (x + 1.0) * (FA_BUCKETS / 2);
    int b = y < 0.0 ? -1 : (y >= FA_BUCKETS ? FA_BUCKETS : (int)y);
    while (b >= 0 && x < fa_edge(b)) /* the rounding of y aside: edge(b) <= x < edge(b + 1) */
        --b;
    while (b >= 0 && b < FA_BUCKETS && x >= fa_edge(b + 1))
        ++b;
    const size_t lo = b < 0 ? 0 : fa[b], hi = b < 0 ? fa[0] : (b == FA_BUCKETS ? ix->count : fa[b + 1]);
    return bisect_above(ix->value, lo, hi, x);
}

size_t sol_nm_entry_first_above(sol_bc4_precision precision, double x)
{
    const sol_nm_entry_index *ix = sol_nm_entry_index_get(precision);
    return ix ? first_above(ix, fa_get(precision), x) : 0;
}

static void walk_prepare(const common_ctx *c, const sol_nm_entry_index *ix, walk_plan *w)
{
    w->nv = 0;
    for (int i = 0; i < 16;) {
        int j = i;
        while (j < 16 && c->sorted[j] == c->sorted[i])
            ++j;
        const double t = c->sorted[i];
        const size_t a = first_above(ix, c->fa, t);
        double m = INFINITY;
        if (a > 0)
            m = (ix->value[a - 1] - t) * (ix->value[a - 1] - t);
        if (a < ix->count) {
            double d = (ix->value[a] - t) * (ix->value[a] - t);
            m = d < m ? d : m;
        }
        w->val[w->nv] = t;
        w->term[w->nv] = m;
        w->count[w->nv++] = j - i;
        i = j;
    }
    for (int k = 0; k < 16; ++k) {
        int i = 0;
        while (w->val[i] != c->to[k])
            ++i;
        w->lb[k] = w->term[i];
        w->of[k] = i;
    }
}

/* About how many pairs the walk from value i lists at the incumbent's score (those holding a value
 * within R of it, R^2 = least term + (best - LB) / count). */
static size_t walk_work(const common_ctx *c, const sol_nm_entry_index *ix, const walk_plan *w, int i)
{
    double lb = 0.0;
    for (int k = 0; k < 16; ++k)
        lb += w->lb[k];
    double slack = c->best * (1.0 + 1e-9) - lb;
    if (!(slack < INFINITY))
        return SIZE_MAX;
    double r = sqrt((slack > 0.0 ? slack : 0.0) / w->count[i] + w->term[i]) * (1.0 + 1e-9) + 1e-15;
    return ix->start[first_above(ix, c->fa, w->val[i] + r)] - ix->start[first_above(ix, c->fa, w->val[i] - r)];
}

/* The least float at least x (x finite, well inside the float range): for a float g, g >= x exactly
 * when g >= float_at_least(x), so the walk compares the index's float gaps in floats. */
static float float_at_least(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* The first j in [j, b) with gap[j] < far (b if none), eight gaps at a time (most holders of a
 * value are far from every other entry: the walk skips them). */
typedef float v4f __attribute__((vector_size(4 * sizeof(float))));
typedef int v4i __attribute__((vector_size(4 * sizeof(int))));
static uint32_t next_near(const float *gap, uint32_t j, uint32_t b, float far)
{
    const v4f farv = {far, far, far, far};
    for (; j + 8 <= b; j += 8) {
        v4f g0, g1;
        memcpy(&g0, gap + j, sizeof g0);
        memcpy(&g1, gap + j + 4, sizeof g1);
        const v4i near = (g0 < farv) | (g1 < farv);
        uint64_t w[2];
        memcpy(w, &near, sizeof w);
        if (w[0] | w[1])
            break;
    }
    while (j < b && gap[j] >= far)
        ++j;
    return j;
}

static int narrow_walk(common_ctx *c, const sol_nm_entry_index *ix, const walk_plan *w, int iu, size_t max_work)
{
    const double u = w->val[iu];
    size_t hi = first_above(ix, c->fa, u), lo = hi, n = ix->count, work = 0; /* next values above and below u */
    while (lo > 0 || hi < n) {
        double dlo = lo > 0 ? (ix->value[lo - 1] - u) * (ix->value[lo - 1] - u) : INFINITY;
        double dhi = hi < n ? (ix->value[hi] - u) * (ix->value[hi] - u) : INFINITY;
        size_t v = dlo <= dhi ? --lo : hi++;
        double d = dlo <= dhi ? dlo : dhi, s = 0.0;
        for (int k = 0; k < 16; ++k)
            s += w->of[k] == iu ? d : w->lb[k];
        if (s > c->best)
            break;
        const double e = ix->value[v];
        const double far = 2.0 * fmax(fabs(e - c->tmin), fabs(e - c->tmax)) * (1.0 + 1e-9);
        const uint32_t a = ix->start[v], b = ix->start[v + 1];
        work += b - a;
        if (work > max_work)
            return 0;
        int alone = 0; /* the least pair whose other entries are all far has been scored */
        const float far_f = float_at_least(far);
        for (uint32_t j = a; j < b;) {
            if (ix->gap[j] >= far_f) {
                if (alone) {
                    j = next_near(ix->gap, j + 1, b, far_f);
                    continue;
                }
                alone = 1;
            }
            try_pair_row(c, ix->pair[j++]);
        }
    }
    return 1;
}

/* Blocks the walk is considered for: at most this many distinct values (8-bit sources; smooth 16-bit
 * blocks hold 16 and are cheaper in the box search) ... */
#ifndef WALK_MAX_VALUES
#define WALK_MAX_VALUES 8
#endif
/* ... and the most pairs it may list (measured on the benchmark maps: about what the box search
 * costs); flat blocks walk before any incumbent is known, up to FLAT_MAX_WORK pairs. */
#ifndef WALK_MAX_WORK
#define WALK_MAX_WORK 1024
#endif
#define FLAT_MAX_WORK 4096
#ifndef WALK_FIRST_VALUES
#define WALK_FIRST_VALUES 4
#endif

/* Blocks at least this many codes wide use span_search (see there; measured on the benchmark maps). */
#ifndef WIDE_CODES
#define WIDE_CODES 3.0
#endif

int sol_nm_bc4_common(const double t[16], sol_bc4_precision precision, double *score)
{
    int order[16];
    sol_nm_reference_order(t, order);
    common_ctx c;
    c.t = t;
    for (int k = 0; k < 16; ++k)
        c.to[k] = t[order[k]];
    c.sp = small_palettes_get(precision);
    c.pal = sol_nm_palettes(precision);
    /* sorted: wide blocks by the branch-free network (an insertion sort mispredicts there), narrow
     * ones by an insertion sort (their few distinct values make its branches predictable, and it
     * stops early) - the same values in the same order, zeros of either sign aside */
    double lo = t[0], hi = t[0];
    for (int p = 1; p < 16; ++p) {
        lo = t[p] < lo ? t[p] : lo;
        hi = t[p] > hi ? t[p] : hi;
    }
    if ((hi - lo) * 127.5 >= WIDE_CODES)
        sol_nm_sort16(t, c.sorted);
    else
        for (int p = 0; p < 16; ++p) {
            int q = p;
            for (; q > 0 && c.sorted[q - 1] > t[p]; --q)
                c.sorted[q] = c.sorted[q - 1];
            c.sorted[q] = t[p];
        }
    c.tmin = c.sorted[0];
    c.window_best = -1.0;
    c.tmax = c.sorted[15];
    /* prefix sums of the targets about their mean (less cancellation in the group costs); q_slack
     * covers what is left of the rounding */
    double mean = 0.0;
    for (int p = 0; p < 16; ++p)
        mean += c.sorted[p];
    mean /= 16.0;
    c.mean = mean;
    c.prefix[0] = c.prefix2[0] = 0.0;
    for (int p = 0; p < 16; ++p) {
        double v = c.sorted[p] - mean;
        c.prefix[p + 1] = c.prefix[p] + v;
        c.prefix2[p + 1] = c.prefix2[p] + v * v;
    }
    c.q_slack = 1e-13 * c.prefix2[16] + 1e-300;
    c.q_rows = 0;
    c.delta = (precision == SOL_BC4_INTERP_8BIT ? 1.0 / 255.0 : precision == SOL_BC4_INTERP_16BIT ? 1.0 / 65535.0 : 0.0) +
              1e-12;
    const int nv = distinct_values(&c);
    const sol_nm_entry_index *ix = nv <= WALK_MAX_VALUES ? sol_nm_entry_index_get(precision) : NULL;
    walk_plan wp;
    int walk_pair = -1;
    if (ix) {
        c.fa = fa_get(precision);
        walk_prepare(&c, ix, &wp);
        if (nv <= WALK_FIRST_VALUES) { /* flat: the walk needs no incumbent */
            c.best = INFINITY;
            c.best_pair = 65536;
            /* one value: the walk lists the holders of the nearest value (and of an equidistant one
             * on its other side) and stops, so it has no cap: up to 2 x 33151 pairs (the values -1 and
             * +1, held by every 6-value pair), most skipped by one comparison, well below the box
             * search's cost there (~1.5 ms) */
            if (narrow_walk(&c, ix, &wp, 0, nv == 1 ? SIZE_MAX : FLAT_MAX_WORK)) {
                *score = c.best;
                return c.best_pair;
            }
            walk_pair = c.best_pair;
        }
    }
    c.best = INFINITY;
    c.best_pair = 65536;
    extreme_seeds(&c);
    {
        int e0 = c.best_pair >> 8, e1 = c.best_pair & 255;
        if (e0 > e1)
            refine(&c, 0, e1, e0);
        else
            refine(&c, 1, e0, e1);
    }
    if (walk_pair >= 0 && walk_pair < 65536)
        try_pair(&c, walk_pair);
    const int wide = (c.tmax - c.tmin) * 127.5 >= WIDE_CODES;
    if (!wide)
        narrow_seeds(&c);
    {
        int e0 = c.best_pair >> 8, e1 = c.best_pair & 255, six = e0 <= e1;
        if (!wide)
            descend(&c, six, six ? e0 : e1, six ? e1 : e0);
    }
    if (ix) { /* the walk from the value it lists the fewest pairs for, if that is few */
        int iu = 0;
        size_t least = SIZE_MAX;
        for (int i = 0; i < wp.nv; ++i) {
            size_t work = walk_work(&c, ix, &wp, i);
            if (work < least) {
                least = work;
                iu = i;
            }
        }
        if (least <= WALK_MAX_WORK && narrow_walk(&c, ix, &wp, iu, SIZE_MAX)) {
            *score = c.best;
            return c.best_pair;
        }
    }
    if (wide) {
        span_search(&c, 0);
        span_search(&c, 1);
    } else {
        search_mode(&c, 0);
        search_mode(&c, 1);
    }
    *score = c.best;
    return c.best_pair;
}
