/* bc5_window.c - the adaptive encoder's window search (T13): the exact joint 3Dc objective minimised
 * over a window of at most WINDOW_PATH_MAX codes around each base anchor (the talk's +-4), with the
 * search's bounds specialised to it. bc5.c's exact search (sol_nm_bc5_search_unit) takes the blocks
 * this path does not. */
#include "bc5_search.h"

#include <stdlib.h>
#include <string.h>

/* ---- the adaptive encoder's window search (T13) ----
 *
 * The same branch and bound as sol_nm_bc5_search_unit, specialised to a window of at most WINDOW_PATH_MAX codes
 * around each anchor (the talk's +-4: 81 anchor pairs per channel): each pair's per-pixel nearest
 * entries (its channel side: score, quick-bound terms) are computed once, in one pass, for the
 * pairs whose score leaves room under the incumbent; no full-range scoring, hashing or merging. The
 * incumbent is the base block's anchors with joint indices. It needs every pixel's tight bound
 * (nz_p^2 above the incumbent, so no decode with z clamped can win, see sol_nm_bc5_search_unit 2.); blocks with
 * rim or downward pixels, and wider windows, go to sol_nm_bc5_search_unit. Exact within the window: the
 * result's error equals the literal brute force's minimum over the window. Ties: the first
 * minimiser in the order incumbent, then x pairs by increasing (score, code), y pairs likewise. */
enum { WINDOW_PATH_MAX = 8, WINDOW_PAIRS = (2 * WINDOW_PATH_MAX + 1) * (2 * WINDOW_PATH_MAX + 1) };

typedef sol_nm_pair window_entry; /* a pair and its channel score */

struct window_scratch {
    window_entry list[2][WINDOW_PAIRS];
    channel_side yside[WINDOW_PAIRS];    /* the sorted y list's channel sides, */
    unsigned char ready[WINDOW_PAIRS];   /* each computed when first needed */
    /* the y sides' v, m1, m2 by pixel, then position in the y list (window_chunk_quick's lanes); 4
     * columns of padding read by its unused lanes (zeroed at allocation, so always defined) */
    double yt[3][16][WINDOW_PAIRS + 4];
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
 * pair whose score exceeds budget is left out (no candidate can use it): first when its two extreme
 * pixels (least and largest component) alone exceed it (most pairs of smooth blocks), else once the
 * score's partial sum (pixels in order, 4 at a time; the terms are >= 0, so the partial sums never
 * decrease) exceeds it. A pair kept has the full score, summed in pixel order. (window_channel_scalar;
 * window_channel_avx2 keeps the same pairs with the same scores by other early exits.) */
#if SEARCH_AVX2
/* min_i (a_i - t_q)^2 for 4 targets t_q (_mm256_min_pd(d, m) is d < m ? d : m: the scalar loop's
 * minimum, a minimum of the same values). */
static inline AVX2_FN __m256d nearest4_avx2(const double a[8], const double t[4])
{
    __m256d tp = _mm256_loadu_pd(t), d = _mm256_sub_pd(_mm256_set1_pd(a[0]), tp);
    __m256d mp = _mm256_mul_pd(d, d);
    for (int i = 1; i < 8; ++i) {
        d = _mm256_sub_pd(_mm256_set1_pd(a[i]), tp);
        mp = _mm256_min_pd(_mm256_mul_pd(d, d), mp);
    }
    return mp;
}

/* The least squared distances of palette a to targets u and v (*du, *dv): the scalar loop's minima
 * (a minimum of the same values, whatever the order). */
static inline AVX2_FN void extreme_distances_avx2(const double a[8], double u, double v, double *du, double *dv)
{
    __m256d lo = _mm256_loadu_pd(a), hi = _mm256_loadu_pd(a + 4), tu = _mm256_set1_pd(u), tv = _mm256_set1_pd(v);
    __m256d d0 = _mm256_sub_pd(lo, tu), d1 = _mm256_sub_pd(hi, tu), d2 = _mm256_sub_pd(lo, tv), d3 = _mm256_sub_pd(hi, tv);
    __m256d mu = _mm256_min_pd(_mm256_mul_pd(d0, d0), _mm256_mul_pd(d1, d1));
    __m256d mv = _mm256_min_pd(_mm256_mul_pd(d2, d2), _mm256_mul_pd(d3, d3));
    __m256d x = _mm256_min_pd(_mm256_unpacklo_pd(mu, mv), _mm256_unpackhi_pd(mu, mv)); /* u0 v0 u2 v2 */
    __m128d y = _mm_min_pd(_mm256_castpd256_pd128(x), _mm256_extractf128_pd(x, 1));
    *du = _mm_cvtsd_f64(y);
    *dv = _mm_cvtsd_f64(_mm_unpackhi_pd(y, y));
}
#endif

/* window_channel's scalar loop, t the pixels' components, lo and hi its least and largest. */
static int window_channel_scalar(const double t[16], int lo, int hi, const double (*pal)[8], int use_max, int e0_lo,
                                 int e0_hi, int e1_lo, int e1_hi, double budget, window_entry *list)
{
    int count = 0;
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
            double score = 0.0;
            int k = 0;
            for (; k < 16; k += 4) {
                double m[4];
                for (int q = 0; q < 4; ++q)
                    m[q] = (a[0] - t[k + q]) * (a[0] - t[k + q]);
                for (int i = 1; i < 8; ++i)
                    for (int q = 0; q < 4; ++q) {
                        double d = (a[i] - t[k + q]) * (a[i] - t[k + q]);
                        m[q] = d < m[q] ? d : m[q];
                    }
                for (int q = 0; q < 4; ++q)
                    score = fold_term(score, m[q], use_max);
                if (score > budget)
                    break;
            }
            if (k < 16)
                continue;
            list[count] = (window_entry){score, (uint16_t)(e0 << 8 | e1)};
            ++count;
        }
    return count;
}

#if SEARCH_AVX2
/* window_channel_scalar's list by other means (the same pairs, the same scores): a pair is kept iff
 * its score (the terms summed in pixel order) is <= budget, as there (its early exits only drop
 * pairs whose full score exceeds budget: the partial sums of non-negative terms never decrease, and
 * a sum that includes two pixels' terms is at least their sum). Here the pixels are visited in the
 * order `visit` (window_targets: the least and largest first): first the two extreme pixels' terms
 * (window_channel_scalar's extreme test), then 4 pixels at a time, each pixel's term the same least
 * squared distance (a minimum of the same values); a pair is dropped once the visited terms' sum
 * (added in the lanes' order, so rounded differently from the pixel-order sum, by a relative
 * 16 * 2^-53 at most) lowered by a relative 1e-12 exceeds budget (the max metric: their max, exact,
 * exceeds it). A pair left has its score summed in pixel order from its terms (fold_term, as
 * window_channel_scalar) and is kept iff that is <= budget. */
static inline AVX2_FN __attribute__((always_inline)) int window_channel_avx2_body(const double tv[16], const int pos[16],
                                                                          const double (*pal)[8], int use_max,
                                                                          int e0_lo, int e0_hi, int e1_lo, int e1_hi,
                                                                          double budget, window_entry *list)
{
    int count = 0;
    for (int e0 = e0_lo; e0 <= e0_hi; ++e0)
        for (int e1 = e1_lo; e1 <= e1_hi; ++e1) {
            const double *a = pal[e0 << 8 | e1];
            double m[16], dlo, dhi;
            extreme_distances_avx2(a, tv[0], tv[1], &dlo, &dhi);
            if (combine(dlo, dhi, use_max) > budget)
                continue;
            /* the 16 terms at once (independent groups, no exit between them: on rough blocks most
             * pairs reach the last group anyway), then the lanes' sum or max against budget */
            __m256d m0 = nearest4_avx2(a, tv), m1 = nearest4_avx2(a, tv + 4), m2 = nearest4_avx2(a, tv + 8),
                    m3 = nearest4_avx2(a, tv + 12);
            _mm256_storeu_pd(m, m0);
            _mm256_storeu_pd(m + 4, m1);
            _mm256_storeu_pd(m + 8, m2);
            _mm256_storeu_pd(m + 12, m3);
            __m256d acc = use_max ? _mm256_max_pd(_mm256_max_pd(m0, m1), _mm256_max_pd(m2, m3))
                                  : _mm256_add_pd(_mm256_add_pd(m0, m1), _mm256_add_pd(m2, m3));
            __m128d h = use_max ? _mm_max_pd(_mm256_castpd256_pd128(acc), _mm256_extractf128_pd(acc, 1))
                                : _mm_add_pd(_mm256_castpd256_pd128(acc), _mm256_extractf128_pd(acc, 1));
            h = use_max ? _mm_max_sd(h, _mm_unpackhi_pd(h, h)) : _mm_add_sd(h, _mm_unpackhi_pd(h, h));
            double part = _mm_cvtsd_f64(h);
            if (use_max ? part > budget : part * (1.0 - 1e-12) > budget)
                continue;
            double score = 0.0;
            for (int p = 0; p < 16; ++p)
                score = fold_term(score, m[pos[p]], use_max);
            if (score > budget)
                continue;
            list[count] = (window_entry){score, (uint16_t)(e0 << 8 | e1)};
            ++count;
        }
    return count;
}

/* (pos[p]: pixel p's place in the visiting order; the body specialised for either metric) */
static AVX2_FN int window_channel_avx2(const double tv[16], const int pos[16], const double (*pal)[8], int use_max,
                                       int e0_lo, int e0_hi, int e1_lo, int e1_hi, double budget, window_entry *list)
{
    if (use_max)
        return window_channel_avx2_body(tv, pos, pal, 1, e0_lo, e0_hi, e1_lo, e1_hi, budget, list);
    return window_channel_avx2_body(tv, pos, pal, 0, e0_lo, e0_hi, e1_lo, e1_hi, budget, list);
}
#endif

/* One channel's pixel components for window_channel: t by pixel, lo and hi the first pixels of least
 * and largest component; for window_channel_avx2 the visiting order (lo, hi, then the other pixels
 * in pixel order: the extreme pixels first, as window_channel_scalar's extreme test) and the
 * components in that order. */
typedef struct window_targets {
    double t[16], tv[16];
    int visit[16], pos[16], lo, hi;
} window_targets;

static void window_targets_init(const double n[16][3], int c, window_targets *wt)
{
    int lo = 0, hi = 0;
    for (int p = 0; p < 16; ++p) {
        wt->t[p] = n[p][c];
        lo = wt->t[p] < wt->t[lo] ? p : lo;
        hi = wt->t[p] > wt->t[hi] ? p : hi;
    }
    wt->lo = lo;
    wt->hi = hi;
    int v = 0;
    wt->visit[v++] = lo;
    if (hi != lo)
        wt->visit[v++] = hi;
    for (int p = 0; p < 16; ++p)
        if (p != lo && p != hi)
            wt->visit[v++] = p;
    for (int q = 0; q < 16; ++q) {
        wt->tv[q] = wt->t[wt->visit[q]];
        wt->pos[wt->visit[q]] = q;
    }
}

static int window_channel(const window_targets *wt, const double (*pal)[8], int use_max, int e0_lo, int e0_hi,
                          int e1_lo, int e1_hi, double budget, window_entry *list)
{
#if SEARCH_AVX2
    if (search_avx2())
        return window_channel_avx2(wt->tv, wt->pos, pal, use_max, e0_lo, e0_hi, e1_lo, e1_hi, budget, list);
#endif
    return window_channel_scalar(wt->t, wt->lo, wt->hi, pal, use_max, e0_lo, e0_hi, e1_lo, e1_hi, budget, list);
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

/* The incumbent of the window search per pixel: its decoded components and angle. A candidate whose
 * pixel decodes to bit-identical components has bit-identical angle there (decoded_angle is a
 * function of them and the pixel), so the exact evaluation takes it from here instead of atan2: on
 * nearly flat blocks most candidates that reach the exact evaluation decode every pixel as the
 * incumbent does (ties of the incumbent, then rejected as not strictly better). */
typedef struct window_incumbent {
    double a[16], b[16], angle[16];
} window_incumbent;

static inline int same_bits(double u, double v)
{
    return value_bits(u) == value_bits(v);
}

/* sol_nm_bc5_joint_objective_lower and then, if the candidate survives it,
 * sol_nm_bc5_joint_objective, with each pixel's jointly best index pair found once (the same pairs,
 * sums and early exits as the two calls in turn):
 * returns the lower bound (>= margin: rejected, *v untouched), else writes the exact objective
 * (stopped once it reaches budget, as sol_nm_bc5_joint_objective) to *v, the index pairs to ix, iy and, when
 * complete, each pixel's angle to angle (inc: the incumbent's pixels, see window_incumbent). */
static double joint_objective_checked(const double a[8], const double b[8], const double n[16][3],
                                      const int order[16], int use_max, double margin, double budget,
                                      const window_incumbent *inc, uint64_t *work, double *v, uint8_t ix[16],
                                      uint8_t iy[16], double angle[16])
{
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        *work += 32;
        int i, j, p = order[k];
        sol_nm_bc5_best_pixel_index(a, b, n[p], &i, &j);
        ix[p] = (uint8_t)i;
        iy[p] = (uint8_t)j;
        double e2 = angle2_lower_bound(a[i], b[j], n[p]);
        s = fold_term(s, e2, use_max);
        if (s >= margin)
            return s;
    }
    *work += 512;
    double e = 0.0;
    for (int p = 0; p < 16; ++p) {
        double u = a[ix[p]], w = b[iy[p]];
        double d = same_bits(u, inc->a[p]) && same_bits(w, inc->b[p]) ? inc->angle[p] : decoded_angle(u, w, n[p]);
        angle[p] = d;
        e = fold_term(e, d * d, use_max);
        if (e >= budget)
            break;
    }
    *v = e;
    return s;
}

/* sol_nm_bc5_joint_objective_quick for the window search, whose pixels never point away (every away term 0),
 * with the pixels' nz in visiting order (nz[k] = n[order[k]][2]): the same terms, the same sum in
 * the same order and the same stop, so the same value and work; the AVX2 form computes the terms 4
 * pixels at a time, and only up to the stop (most candidates stop within the first pixels, visited
 * worst first). */
#if SEARCH_AVX2
static AVX2_FN double window_quick_avx2(const channel_side *xs, const channel_side *ys, const double nz[16],
                                        int use_max, double budget, uint64_t *work)
{
    double s = 0.0, e2[4];
    for (int k = 0; k < 16; k += 4) { /* sol_nm_bc5_quick_terms_avx2's terms, its away term 0 */
        _mm256_storeu_pd(e2, _mm256_max_pd(quick_tight4(xs, ys, nz, k), _mm256_setzero_pd()));
        if (fold_terms_until(&s, e2, 4, use_max, budget, work))
            return s;
    }
    return s;
}
#endif

static double window_quick(const channel_side *xs, const channel_side *ys, const double n[16][3], const int order[16],
                           const double nz[16], int use_max, double budget, uint64_t *work)
{
#if SEARCH_AVX2
    if (search_avx2())
        return window_quick_avx2(xs, ys, nz, use_max, budget, work);
#endif
    static const double away_off[16] = {0};
    return sol_nm_bc5_joint_objective_quick(xs, ys, n, order, nz, away_off, use_max, budget, work);
}

/* The quick bound of up to 4 consecutive candidates of one x pair (y list positions j..j+lanes-1)
 * at once, one per lane, pixel by pixel: the same terms as window_quick (quick_tight4's operations
 * on the same values, 1 - a^2 computed once per pixel of the x side, as the scalar 1.0 - a * a
 * gives the same bits) folded in the same order, so every lane's partial value after each pixel is
 * bit for bit the one window_quick reaches there. The partial values never decrease (the terms are
 * >= 0), so window_quick with budget M stops at pixel count(M) (the number of partial values below
 * M; 16: it does not stop): below[q] for the margin given, kept in prefix for a lower margin (an
 * improved incumbent within the chunk; margins only decrease). Pixels are computed until every lane
 * has reached the margin (the later partial values are then above any lower margin's stop too). */
typedef struct window_chunk {
    double prefix[16][4]; /* partial values by pixel and lane */
    double margin;        /* the margin of below */
    int below[4];         /* partial values below margin, per lane */
    int pixels;           /* pixels computed */
} window_chunk;

#if SEARCH_AVX2
static AVX2_FN void window_chunk_quick(const channel_side *xs, const double xa2[16], const window_scratch *w, int j,
                                       int lanes, const double nz[16], int use_max, double margin, window_chunk *c)
{
    const __m256d zero = _mm256_setzero_pd(), lower = _mm256_set1_pd(1.0 - 3e-6), absolute = _mm256_set1_pd(5e-15);
    const __m256d mm = _mm256_set1_pd(margin);
    const __m256d active = _mm256_castsi256_pd(
        _mm256_cmpgt_epi64(_mm256_set1_epi64x(lanes), _mm256_setr_epi64x(0, 1, 2, 3)));
    __m256d s = zero;
    __m256i count = _mm256_setzero_si256();
    int k = 0;
    while (k < 16) {
        __m256d lt = zero;
        for (int g = 0; g < 4; ++g, ++k) {
            __m256d m1x = _mm256_broadcast_sd(xs->m1 + k), m2x = _mm256_broadcast_sd(xs->m2 + k);
            __m256d z = _mm256_broadcast_sd(nz + k);
            __m256d b = _mm256_loadu_pd(&w->yt[0][k][j]), m1y = _mm256_loadu_pd(&w->yt[1][k][j]);
            __m256d m2y = _mm256_loadu_pd(&w->yt[2][k][j]);
            __m256d nz2 = _mm256_mul_pd(z, z);
            __m256d lb = _mm256_min_pd(_mm256_add_pd(m2x, m1y), _mm256_add_pd(m1x, m2y));
            lb = _mm256_min_pd(nz2, lb);
            __m256d zz = _mm256_sub_pd(_mm256_broadcast_sd(xa2 + k), _mm256_mul_pd(b, b));
            __m256d up = _mm256_cmp_pd(zz, zero, _CMP_GT_OQ);
            __m256d dz = _mm256_sub_pd(_mm256_sqrt_pd(_mm256_and_pd(zz, up)), z);
            __m256d c2 = _mm256_blendv_pd(nz2, _mm256_add_pd(_mm256_add_pd(m1x, m1y), _mm256_mul_pd(dz, dz)), up);
            lb = _mm256_min_pd(c2, lb);
            __m256d e = _mm256_max_pd(_mm256_sub_pd(_mm256_mul_pd(lb, lower), absolute), zero);
            s = use_max ? _mm256_max_pd(e, s) : _mm256_add_pd(s, e);
            _mm256_storeu_pd(c->prefix[k], s);
            lt = _mm256_and_pd(_mm256_cmp_pd(s, mm, _CMP_LT_OQ), active);
            count = _mm256_sub_epi64(count, _mm256_castpd_si256(lt));
        }
        if (!_mm256_movemask_pd(lt))
            break; /* every lane has reached the margin */
    }
    long long below[4];
    _mm256_storeu_si256((__m256i *)below, count);
    for (int q = 0; q < 4; ++q)
        c->below[q] = (int)below[q];
    c->pixels = k;
    c->margin = margin;
}
#endif

/* window_quick's stop for lane q of c with budget margin (<= c->margin): the number of partial
 * values below it (16: no stop). */
static int window_chunk_below(const window_chunk *c, int q, double margin)
{
    if (same_bits(margin, c->margin))
        return c->below[q];
    int k = 0;
    while (k < c->pixels && c->prefix[k][q] < margin)
        ++k;
    return k;
}

/* sol_nm_bc5_channel_side_init for the window search: no pixel points away (lt = 0), t the channel's
 * components in visiting order. */
static void window_side_init(const double pal[8], const double t[16], channel_side *s)
{
    memset(s->lt, 0, sizeof s->lt);
    sol_nm_bc5_channel_side_fill(pal, t, s);
}

/* sol_nm_bc5_order_worst_first's order (pixels by decreasing err, equal errors in pixel order: a stable sort),
 * from each pixel's rank (how many pixels come before it) instead of insertion: no data-dependent
 * branches. */
static void window_order(const double err[16], int order[16])
{
    for (int p = 0; p < 16; ++p) {
        int rank = 0;
        for (int q = 0; q < 16; ++q)
            rank += err[q] > err[p] || (q < p && err[q] == err[p]);
        order[rank] = p;
    }
}

/* sol_nm_bc5_merge_equivalent's result (the first pair of each class, in list order): short lists (the
 * window's, on nearly flat blocks, a few to a dozen pairs) compare each pair with the pairs kept so
 * far (sol_nm_bc5_pair_key_equal: classes of an equality of keys, so a pair equal to no kept pair opens a class
 * and one equal to a kept pair belongs to that pair's class), which costs less than hashing every
 * pair's key over all its pixels: unequal pairs differ within the first pixels. Longer lists go
 * through sol_nm_bc5_merge_classes as sol_nm_bc5_merge_equivalent does, with a hash of the seed values alone: any hash
 * that gives equal keys equal values finds the same classes (sol_nm_bc5_merge_classes compares every pair
 * met in the probe sequence with sol_nm_bc5_pair_key_equal), and the seeds cost a fraction of the usable
 * entries' hashing. */
static uint64_t window_key_hash(void *ctx, const double pal[8])
{
    const channel_key *k = ctx;
    uint64_t h = 0;
    for (int p = 0; p < k->count; ++p)
        h = mix64(h, value_bits(pal[seed_entry(pal, k->t[p])]));
    return h;
}

static int window_merge(window_entry *list, int count, const channel_key *k, const double (*pal)[8], uint32_t *slots)
{
    if (count > 16) { /* hashed by the seeds alone (a part of the key: equal keys, equal hashes) */
        const pair_classes pc = {window_key_hash, sol_nm_bc5_key_equal_fn, (void *)k, NULL};
        return (int)sol_nm_bc5_merge_classes(list, (size_t)count, pal, &pc, slots);
    }
    int kept = 0;
    for (int i = 0; i < count; ++i) {
        int dup = 0;
        for (int q = 0; q < kept && !dup; ++q)
            dup = sol_nm_bc5_pair_key_equal(k, pal[list[q].pair], pal[list[i].pair]);
        if (!dup)
            list[kept++] = list[i];
    }
    return kept;
}

/* Returns 0 (and leaves everything untouched) when the block needs sol_nm_bc5_search_unit (see above).
 * shrink = 1 / (1 + gap) in (0, 1] (options.gap; 1: the exact window): every pruning test compares
 * a lower bound with cut = best * shrink instead of best, so a candidate is dropped once its bound
 * reaches best / (1 + gap): its objective E >= bound >= best / (1 + gap) >= (final best) / (1 + gap),
 * and the result is within a factor (1 + gap) of the window's optimum (shrink = 1: cut = best exactly,
 * the exact search). The entry test (no clamped decode can go below cut) uses cut likewise. */
int sol_nm_bc5_window_search(const double n[16][3], const sol_bc5_range *r, int base_x, int base_y, int base_least,
                             double shrink, const search_request *rq, search_workspace *ws, sol_bc5_block *out,
                             sol_bc5_info *info) {
    if (r->x0_hi - r->x0_lo > 2 * WINDOW_PATH_MAX || r->x1_hi - r->x1_lo > 2 * WINDOW_PATH_MAX ||
        r->y0_hi - r->y0_lo > 2 * WINDOW_PATH_MAX || r->y1_hi - r->y1_lo > 2 * WINDOW_PATH_MAX)
        return 0;
    const int use_max = rq->use_max;
    const double(*pal)[8] = sol_nm_palettes(rq->precision);
    int px = base_x, py = base_y;
    uint8_t ix[16], iy[16], cx[16], cy[16]; /* the best's indices, a candidate's */
    double pixel_err[16], best = 0.0;
    window_incumbent inc;
    for (int p = 0; p < 16; ++p) { /* sol_nm_bc5_joint_objective's sum, keeping each pixel's error */
        int i, j;
        double e = sol_nm_bc5_best_pixel(pal[px], pal[py], n[p], &i, &j);
        ix[p] = (uint8_t)i;
        iy[p] = (uint8_t)j;
        pixel_err[p] = e;
        inc.a[p] = pal[px][i];
        inc.b[p] = pal[py][j];
        inc.angle[p] = e;
        best = fold_term(best, e * e, use_max);
    }
    double cut = best * shrink;
    for (int p = 0; p < 16; ++p)
        if (!(n[p][2] > 0.0) || n[p][2] * n[p][2] <= cut * (1.0 + BOUND_SLACK))
            return 0; /* a rim or downward pixel: the loose bounds of sol_nm_bc5_search_unit */
    uint64_t candidates = 1, work = 0;
    int bounded = 0;
    if (best > 0.0) {
        window_scratch *w = ws->win;
        double least_x = INFINITY, least_y = INFINITY, room = cut * (1.0 + BOUND_SLACK);
        /* y first: an x pair above room - least_y (sum metric) is dropped by the filter below, so
         * window_channel leaves it out at once. If the pair of least x score is left out, no x pair
         * passes the filter and there is no candidate, whatever least_x then is.
         * The y pairs kept in the end are those within room - least_x (sum metric), least_x the
         * least x score, which is at most the base x pair's score sx (the base is in the window; if
         * the base pair is filtered out, every x pair kept scores below it). So the y pairs are
         * first scored against room - sx (with the base's common anchors, usually the least x pair
         * itself): scores within that budget are the ones room - least_x keeps whenever least_x is
         * sx, and their least is the least y score whenever any is kept (that pair scores within
         * every budget a y pair is kept in). Where least_x turns out below sx, or no y pair is kept,
         * the y pairs are scored again against the original budget: the same lists as scoring y
         * against room and filtering, without scoring most of the pairs the filter drops. Only
         * where the base is likely the least x pair (base_least: the common base, least squares
         * per channel); around the fast base's anchors least_x is nearly always below sx. */
        int ny = 0, y_final = 0;
        window_targets wtx, wty;
        window_targets_init(n, 0, &wtx);
        window_targets_init(n, 1, &wty);
        if (!use_max && base_least) {
            window_entry bx;
            window_channel(&wtx, pal, 0, base_x >> 8, base_x >> 8, base_x & 255, base_x & 255, INFINITY, &bx);
            least_x = bx.score;
            ny = window_channel(&wty, pal, 0, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi,
                                room - least_x * (1.0 - BOUND_SLACK), w->list[1]);
            y_final = ny > 0;
        }
        if (!y_final)
            ny = window_channel(&wty, pal, use_max, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi, room, w->list[1]);
        for (int k = 0; k < ny; ++k)
            least_y = w->list[1][k].score < least_y ? w->list[1][k].score : least_y;
        int nx = window_channel(&wtx, pal, use_max, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi,
                                use_max ? room : room - least_y * (1.0 - BOUND_SLACK), w->list[0]);
        double guess_x = least_x;
        least_x = INFINITY;
        for (int k = 0; k < nx; ++k)
            least_x = w->list[0][k].score < least_x ? w->list[0][k].score : least_x;
        if (y_final && nx > 0 && value_bits(least_x) != value_bits(guess_x))
            ny = window_channel(&wty, pal, 0, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi,
                                room - least_x * (1.0 - BOUND_SLACK), w->list[1]);
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
         * same values near them): one per class, as sol_nm_bc5_search_unit. Elsewhere hashing costs more than
         * the ties it saves; the result is the same either way. */
        if (nx > 1 && ny > 1 && nx * ny > 4 && span <= 8.0 / 255.0) {
            channel_key kx, ky;
            sol_nm_bc5_channel_key_init(&kx, tx, 0, room);
            sol_nm_bc5_channel_key_init(&ky, ty, 0, room);
            nx = window_merge(w->list[0], nx, &kx, pal, ws->slots);
            ny = window_merge(w->list[1], ny, &ky, pal, ws->slots);
        }
        /* Set up when the first candidate needs it (most searched blocks of smooth maps have none):
         * the pixels' visiting order, worst first (by the incumbent's per-pixel error) when rejecting
         * candidates, and the y sides' marks (each y side is computed when first needed), the x
         * side per x pair. */
        int order[16], prepared = 0, chunked = 0;
        double nz[16], tord[2][16], xa2[16]; /* nz and the components in visiting order; 1 - x^2 */
        channel_side xside;
        window_chunk chunk;
#if SEARCH_AVX2
        chunked = search_avx2(); /* the quick bound 4 y pairs at a time (window_chunk_quick) */
#endif
        for (int i = 0; i < nx && ny > 0 && !bounded; ++i) {
            const window_entry *ex = &w->list[0][i];
            if (combine(ex->score, w->list[1][0].score, use_max) * (1.0 - BOUND_SLACK) >= cut)
                break;
            const double *a = pal[ex->pair];
            int x_ready = 0, chunk_start = 0, chunk_end = 0;
            for (int j = 0; j < ny; ++j) {
                const window_entry *ey = &w->list[1][j];
                if (combine(ex->score, ey->score, use_max) * (1.0 - BOUND_SLACK) >= cut)
                    break;
                if (ex->pair == base_x && ey->pair == base_y)
                    continue; /* the incumbent */
                if (work >= rq->work_limit) {
                    bounded = 1;
                    break;
                }
                ++candidates;
                if (!prepared) {
                    window_order(pixel_err, order);
                    for (int k = 0; k < 16; ++k) {
                        nz[k] = n[order[k]][2];
                        tord[0][k] = n[order[k]][0];
                        tord[1][k] = n[order[k]][1];
                    }
                    memset(w->ready, 0, (size_t)ny);
                    prepared = 1;
                }
                if (!x_ready) {
                    window_side_init(a, tord[0], &xside);
                    for (int k = 0; k < 16; ++k)
                        xa2[k] = 1.0 - xside.v[k] * xside.v[k];
                    x_ready = 1;
                }
                const double *b = pal[ey->pair];
                double margin = cut * (1.0 + BOUND_SLACK);
                if (chunked) {
#if SEARCH_AVX2
                    if (j >= chunk_end) { /* the next candidates of this x pair under the incumbent */
                        int lanes = 1;
                        while (lanes < 4 && j + lanes < ny &&
                               combine(ex->score, w->list[1][j + lanes].score, use_max) * (1.0 - BOUND_SLACK) < cut)
                            ++lanes;
                        for (int q = j; q < j + lanes; ++q)
                            if (!w->ready[q]) { /* straight into the columns window_chunk_quick reads */
                                sol_nm_channel_side_avx2(pal[w->list[1][q].pair], tord[1], &w->yt[0][0][q],
                                                        &w->yt[1][0][q], &w->yt[2][0][q], WINDOW_PAIRS + 4);
                                w->ready[q] = 1;
                            }
                        window_chunk_quick(&xside, xa2, w, j, lanes, nz, use_max, margin, &chunk);
                        chunk_start = j;
                        chunk_end = j + lanes;
                        /* the whole chunk at once where the quick bound rejects every candidate of it
                         * (the usual case) and no work check within it can stop the search: the same
                         * candidates counted and the same work added as one by one below (the
                         * incumbent, if among them, neither counted nor given work), nothing else
                         * changes (no candidate reaches the exact evaluation) */
                        if (work + 16 * (uint64_t)lanes < rq->work_limit) {
                            uint64_t add = 0;
                            int counted = 0, all = 1;
                            for (int q = 0; q < lanes && all; ++q) {
                                if (q > 0 && ex->pair == base_x && w->list[1][j + q].pair == base_y)
                                    continue;
                                all = chunk.below[q] < 16;
                                add += (uint64_t)chunk.below[q] + 1;
                                counted += q > 0;
                            }
                            if (all) {
                                candidates += (uint64_t)counted;
                                work += add;
                                j = chunk_end - 1;
                                continue;
                            }
                        }
                    }
#endif
                    int below = window_chunk_below(&chunk, j - chunk_start, margin);
                    work += (uint64_t)(below < 16 ? below + 1 : 16);
                    if (below < 16)
                        continue;
                } else {
                    if (!w->ready[j]) {
                        window_side_init(b, tord[1], &w->yside[j]);
                        w->ready[j] = 1;
                    }
                    if (window_quick(&xside, &w->yside[j], n, order, nz, use_max, margin, &work) >= margin)
                        continue;
                }
                double v = INFINITY, angle[16];
                if (joint_objective_checked(a, b, n, order, use_max, margin, best, &inc, &work, &v, cx, cy, angle) >=
                    margin)
                    continue;
                if (v < best) { /* complete (below the budget): the exact objective and its indices */
                    best = v;
                    cut = best * shrink;
                    px = ex->pair;
                    py = ey->pair;
                    memcpy(ix, cx, sizeof ix);
                    memcpy(iy, cy, sizeof iy);
                    for (int p = 0; p < 16; ++p) {
                        inc.a[p] = a[ix[p]];
                        inc.b[p] = b[iy[p]];
                        inc.angle[p] = angle[p];
                    }
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
        info->error = sol_nm_bc5_metric_value(best, use_max ? SOL_BC5_MAX : SOL_BC5_SUM_SQUARED);
        info->searched = 1;
        info->candidates = candidates;
        info->bounded = bounded;
    }
    return 1;
}

window_scratch *sol_nm_bc5_window_scratch_new(void)
{
    return calloc(1, sizeof(window_scratch)); /* zeroed: window_scratch's padding columns */
}
