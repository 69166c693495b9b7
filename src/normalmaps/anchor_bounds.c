/* anchor_bounds.c - per-channel scoring of BC4 anchor pairs against target components, and the
 * enumeration of the pairs whose score fits a budget: the separable lower bounds of the joint BC5
 * search (bc5.c) and the exact least-squares BC4 search (bc4.c). */
#include "normalmaps_internal.h"

#include <math.h>
#include <string.h>

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#include <immintrin.h>
#define LOOSE_AVX2 1
#else
#define LOOSE_AVX2 0
#endif

/* ---- per-channel scoring ---- */

/* The largest |a| whose loose interval (term_loose) holds |t|: |t| / sqrt(1 - t^2) (infinite for |t| >= 1). */
static inline double loose_reach(double t)
{
    double tt = fabs(t);
    return tt < 1.0 ? tt / sqrt((1.0 - tt) * (1.0 + tt)) : INFINITY;
}


void sol_nm_channel_init(sol_nm_channel *ch, const double t[16], sol_bc4_precision precision, int use_max,
                         unsigned loose, uint8_t e0_lo, uint8_t e0_hi, uint8_t e1_lo, uint8_t e1_hi)
{
    memcpy(ch->t, t, sizeof ch->t);
    ch->palettes = sol_nm_palettes(precision);
    ch->precision = precision;
    ch->use_max = use_max;
    ch->loose = (uint16_t)loose;
    ch->e0_lo = e0_lo;
    ch->e0_hi = e0_hi;
    ch->e1_lo = e1_lo;
    ch->e1_hi = e1_hi;
    for (int p = 0; p < 16; ++p) {
        ch->loose_w[p] = 1.0;
        ch->loose_off[p] = 0.0;
        ch->loose_reach[p] = loose_reach(t[p]);
    }
    sol_nm_reference_order(t, ch->order);
}

void sol_nm_reference_order(const double t[16], int order[16])
{
    /* Order: smallest, largest, then by decreasing distance from the mean - the pixels most likely
     * to be far from a poor palette come first (ties: the lower pixel first; an insertion sort, stable). */
    double mean = 0.0;
    for (int p = 0; p < 16; ++p)
        mean += t[p];
    mean /= 16.0;
    /* the extremes' values kept beside their indices (the same comparisons: vlo = t[lo]), so that
     * no comparison waits for a load at the index just chosen (issue 13, common-speed: that chain of
     * loads was a quarter of this function's time, perf) */
    int lo = 0, hi = 0;
    double vlo = t[0], vhi = t[0];
    for (int p = 1; p < 16; ++p) {
        const double v = t[p];
        lo = v < vlo ? p : lo;
        vlo = v < vlo ? v : vlo;
        hi = v > vhi ? p : hi;
        vhi = v > vhi ? v : vhi;
    }
    int n = 0;
    order[n++] = lo;
    if (hi != lo)
        order[n++] = hi;
    const int first = n;
    double key[16];
    for (int p = 0; p < 16; ++p) {
        if (p == lo || p == hi)
            continue;
        double k = fabs(t[p] - mean);
        int q = n++;
        for (; q > first && key[q - 1] < k; --q) {
            key[q] = key[q - 1];
            order[q] = order[q - 1];
        }
        key[q] = k;
        order[q] = p;
    }
}

void sol_nm_channel_rim_weight(sol_nm_channel *ch, int p, double weight, double offset)
{
    ch->loose_w[p] = weight;
    ch->loose_off[p] = offset;
}

static inline double term_tight(const double pal[8], double t)
{
    double m = (pal[0] - t) * (pal[0] - t);
    for (int i = 1; i < 8; ++i) {
        double d = (pal[i] - t) * (pal[i] - t);
        m = d < m ? d : m;
    }
    return m;
}

/* Distance^2 from t to the nearest interval between a / sqrt(1 + a^2) and a over the entries a: the
 * x of a decoded normal with code value a is a when x^2 + y^2 <= 1, and a / r with
 * r = sqrt(a^2 + y^2) in (1, sqrt(1 + a^2)] (|y| <= 1) when z is clamped. f(a) = a / sqrt(1 + a^2) is
 * increasing; mirrored so that t >= 0, the interval of a holds t iff t <= a <= reach = f^-1(t); an
 * entry above reach is f(a) - t away, the least such a the closest; one below t is t - max(a, f(a))
 * away, the largest such a the closest. So two square roots per palette at most. f is rounded towards
 * zero by a relative 1e-15 (and distances below 0 are 0), so that rounding only lowers the term. */
static inline double term_loose(const double pal[8], double t, double reach)
{
    double sgn = t < 0.0 ? -1.0 : 1.0, tt = fabs(t), above = INFINITY, below = -INFINITY;
    for (int i = 0; i < 8; ++i) {
        double a = sgn * pal[i];
        if (a >= tt) {
            if (a <= reach)
                return 0.0;
            above = a < above ? a : above;
        } else {
            below = a > below ? a : below;
        }
    }
    double m = INFINITY;
    if (above < INFINITY) {
        double d = above / sqrt(1.0 + above * above) * (1.0 - 1e-15) - tt;
        d = d > 0.0 ? d : 0.0;
        m = d * d;
    }
    if (below > -INFINITY) {
        double e = below >= 0.0 ? below : below / sqrt(1.0 + below * below) * (1.0 - 1e-15);
        double d = tt - e;
        d = d > 0.0 ? d : 0.0;
        m = d * d < m ? d * d : m;
    }
    return m;
}

double sol_nm_loose_term(const double pal[8], double t)
{
    return term_loose(pal, t, loose_reach(t));
}

/* Score with early exit: returns a value > budget as soon as the partial score exceeds it. The
 * palette comes from the common search's small tables (sol_nm_small_palette: the palette table's
 * row, bit for bit, from 26 KB of anchors and interpolants that stay in the caches): the
 * enumeration scores pairs 256 rows apart in the 4 MB table, and the load of each row missed the
 * caches (perf, issue 13: ~40% of score_pair's time on the 8-bit hood map, whose lists are long). */
static inline double score_pair(const sol_nm_channel *ch, int pair, double budget)
{
    double pal[8];
    sol_nm_small_palette(ch->precision, pair, pal);
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        double t = ch->t[ch->order[k]];
        int p = ch->order[k];
        double term = (ch->loose >> p) & 1 ? ch->loose_off[p] + ch->loose_w[p] * term_loose(pal, t, ch->loose_reach[p])
                                           : term_tight(pal, t);
        s = ch->use_max ? (term > s ? term : s) : s + term;
        if (s > budget)
            return s;
    }
    return s;
}

/* ---- score_pair for channels whose 16 pixels are all loose, 4 pixels per instruction ----
 *
 * Rims and blocks pointing away make every pixel loose; then enumerate_pairs scores all 65536 pairs
 * through term_loose (issue 13: 7-25 ms of a block's set-up). loose_lanes holds the pixels in the
 * visiting order (|t|, its sign, reach, weight, offset); score_loose_avx2 computes 4 visiting
 * positions' terms at once with term_loose's operations per lane (the least entry >= |t| above the
 * reach and the largest below |t| by min / max, which select as its ternaries do; 0 if an entry lies
 * in [|t|, reach]; the same quotient, root and clamps, no FMA), then folds them one pixel at a time in
 * the visiting order and stops where score_pair stops: the same double, bit for bit (the tests
 * compare both forms over whole enumerations). */
typedef struct loose_lanes {
    double tt[16], sgn[16], reach[16], w[16], off[16];
} loose_lanes;

static void loose_lanes_init(const sol_nm_channel *ch, loose_lanes *ll)
{
    for (int k = 0; k < 16; ++k) {
        int p = ch->order[k];
        double t = ch->t[p];
        ll->sgn[k] = t < 0.0 ? -1.0 : 1.0;
        ll->tt[k] = fabs(t);
        ll->reach[k] = ch->loose_reach[p];
        ll->w[k] = ch->loose_w[p];
        ll->off[k] = ch->loose_off[p];
    }
}

#if LOOSE_AVX2
static __attribute__((target("avx2"))) double score_loose_avx2(const sol_nm_channel *ch, const loose_lanes *ll,
                                                               const double pal[8], double budget)
{
    const __m256d inf = _mm256_set1_pd(INFINITY), ninf = _mm256_set1_pd(-INFINITY), zero = _mm256_setzero_pd();
    const __m256d one = _mm256_set1_pd(1.0), shrink = _mm256_set1_pd(1.0 - 1e-15);
    double s = 0.0;
    for (int k = 0; k < 16; k += 4) {
        __m256d tt = _mm256_loadu_pd(ll->tt + k), sgn = _mm256_loadu_pd(ll->sgn + k);
        __m256d reach = _mm256_loadu_pd(ll->reach + k);
        __m256d above = inf, below = ninf, in = zero;
        for (int i = 0; i < 8; ++i) {
            __m256d a = _mm256_mul_pd(sgn, _mm256_set1_pd(pal[i]));
            __m256d ge = _mm256_cmp_pd(a, tt, _CMP_GE_OQ), le = _mm256_cmp_pd(a, reach, _CMP_LE_OQ);
            in = _mm256_or_pd(in, _mm256_and_pd(ge, le));
            above = _mm256_blendv_pd(above, _mm256_min_pd(a, above), _mm256_andnot_pd(le, ge));
            below = _mm256_blendv_pd(_mm256_max_pd(a, below), below, ge);
        }
        __m256d m = zero;
        if (_mm256_movemask_pd(in) != 0xf) {
            /* (skipped where every lane has an entry in its interval: the last blend gives 0 in each;
             * issue 13: most terms of rims and blocks pointing away)
             * above: above / sqrt(1 + above^2) (1 - 1e-15) - |t|, clamped at 0, squared (none: INFINITY) */
            __m256d q = _mm256_mul_pd(_mm256_div_pd(above, _mm256_sqrt_pd(_mm256_add_pd(one, _mm256_mul_pd(above, above)))), shrink);
            __m256d d = _mm256_max_pd(_mm256_sub_pd(q, tt), zero);
            m = _mm256_blendv_pd(_mm256_mul_pd(d, d), inf, _mm256_cmp_pd(above, inf, _CMP_EQ_OQ));
            /* below: |t| - (below >= 0 ? below : its quotient), clamped, squared; the least of both */
            __m256d qb = _mm256_mul_pd(_mm256_div_pd(below, _mm256_sqrt_pd(_mm256_add_pd(one, _mm256_mul_pd(below, below)))), shrink);
            __m256d e = _mm256_blendv_pd(qb, below, _mm256_cmp_pd(below, zero, _CMP_GE_OQ));
            __m256d db = _mm256_max_pd(_mm256_sub_pd(tt, e), zero);
            __m256d mb = _mm256_min_pd(_mm256_mul_pd(db, db), m);
            m = _mm256_blendv_pd(mb, m, _mm256_cmp_pd(below, ninf, _CMP_EQ_OQ));
            m = _mm256_blendv_pd(m, zero, in);
        }
        __m256d term = _mm256_add_pd(_mm256_loadu_pd(ll->off + k), _mm256_mul_pd(_mm256_loadu_pd(ll->w + k), m));
        double tl[4];
        _mm256_storeu_pd(tl, term);
        for (int j = 0; j < 4; ++j) {
            s = ch->use_max ? (tl[j] > s ? tl[j] : s) : s + tl[j];
            if (s > budget)
                return s;
        }
    }
    return s;
}
#endif

#if LOOSE_AVX2
/* score_pair for channels whose pixels are all tight, 4 visiting positions at a time: term_tight's
 * operations per lane ((e - t)^2, then d < m ? d : m, which is what vminpd(d, m) computes, entries
 * in the same order, no FMA), folded one pixel at a time in the visiting order with score_pair's
 * early exit (the terms past the exit are computed and dropped): the same double, bit for bit.
 * tv: the targets in visiting order (lattice_lanes.t). */
static __attribute__((target("avx2"))) double score_tight_avx2(const double tv[16], const double pal[8], int use_max,
                                                               double budget)
{
    __m256d e[8];
    for (int i = 0; i < 8; ++i)
        e[i] = _mm256_set1_pd(pal[i]);
    double s = 0.0;
    for (int k = 0; k < 16; k += 4) {
        const __m256d t = _mm256_loadu_pd(tv + k);
        __m256d d = _mm256_sub_pd(e[0], t), m = _mm256_mul_pd(d, d);
        for (int i = 1; i < 8; ++i) {
            d = _mm256_sub_pd(e[i], t);
            m = _mm256_min_pd(_mm256_mul_pd(d, d), m);
        }
        double tl[4];
        _mm256_storeu_pd(tl, m);
        for (int j = 0; j < 4; ++j) {
            s = use_max ? (tl[j] > s ? tl[j] : s) : s + tl[j];
            if (s > budget)
                return s;
        }
    }
    return s;
}
#endif

/* 1 when score_loose_avx2 may score ch's pairs: every pixel loose, AVX2 present and not disabled. */
static int loose_avx2(const sol_nm_channel *ch)
{
#if LOOSE_AVX2
    return ch->loose == 0xffffu && !sol_nm_simd_disable && __builtin_cpu_supports("avx2");
#else
    (void)ch;
    return 0;
#endif
}

/* A lower bound of score_pair without the palette table: with low anchor value al and step s the
 * exact (float) decoder's entries are al + k s, k = 0..divisions (and -1, +1 in 6-value mode); a
 * rounding decoder moves each by at most delta. So a tight term is at least (dist(t, lattice) -
 * delta)^2, the nearest lattice point found by rounding (t - al) / s; loose pixels count 0. The
 * arithmetic replaces 8 table entries (a cache line of a 4 MB table) per pixel; pairs that pass are
 * scored exactly. */
static inline double score_lower(const sol_nm_channel *ch, double al, double s, int divisions, int six,
                                 double delta, double budget, int *used)
{
    const double inv_s = s > 0.0 ? 1.0 / s : 0.0;
    double sum = 0.0;
    for (int k = 0; k < 16; ++k) {
        int p = ch->order[k];
        if ((ch->loose >> p) & 1)
            continue;
        double t = ch->t[p], u = (t - al) * inv_s;
        int kk = u <= 0.0 ? 0 : (int)(u + 0.5);
        kk = kk > divisions ? divisions : kk;
        double d = fabs(t - (al + kk * s)) - delta, term = d > 0.0 ? d * d : 0.0;
        if (six) {
            double lo = (t + 1.0) * (t + 1.0), hi = (t - 1.0) * (t - 1.0);
            term = lo < term ? lo : term;
            term = hi < term ? hi : term;
        }
        sum = ch->use_max ? (term > sum ? term : sum) : sum + term;
        if (sum > budget) {
            *used = k + 1;
            return sum;
        }
    }
    *used = 16;
    return sum;
}

/* score_lower's bound for 4 visiting positions per instruction (AVX2), over all 16 pixels at once: the
 * same per-pixel terms by the same operations (the nearest lattice point by rounding, floor(u + 0.5)
 * being (int)(u + 0.5) for u > 0, clamped to 0..divisions; the distance lowered by delta and clamped
 * at 0, squared; the 6-value mode's -1 and +1 by min; 0 for loose pixels; no FMA), summed (or their
 * max) in lanes and lowered by a relative 1e-12: a sum of 16 non-negative terms in another order
 * differs from score_pair's by at most ~16 ulps relative, so the lowered value stays below the
 * computed score even where the bound equals the score (a flat channel served by -1 or +1). *used is
 * 16: with the whole sum the skip after a rejection (see enumerate_pairs) jumps over the high anchors
 * the lattice bound rules out, instead of the few that a sum stopped just above the budget allows.
 * enumerate_pairs keeps exactly the pairs whose score (score_pair) fits the budget, whichever valid
 * bound filtered them, so the lists are the scalar form's (the tests compare both with the brute
 * force). */
typedef struct lattice_lanes {
    double t[16], tight[16], six_min[16]; /* in visiting order; tight: all-ones bits or 0 */
} lattice_lanes;

static void lattice_lanes_init(const sol_nm_channel *ch, lattice_lanes *ll)
{
    for (int k = 0; k < 16; ++k) {
        int p = ch->order[k];
        double t = ch->t[p], lo = (t + 1.0) * (t + 1.0), hi = (t - 1.0) * (t - 1.0);
        uint64_t bits = (ch->loose >> p) & 1 ? 0 : ~UINT64_C(0);
        ll->t[k] = t;
        memcpy(&ll->tight[k], &bits, sizeof bits);
        ll->six_min[k] = lo < hi ? lo : hi;
    }
}

#if LOOSE_AVX2
static __attribute__((target("avx2"))) double score_lower_avx2(const sol_nm_channel *ch, const lattice_lanes *ll,
                                                               double al, double s, int divisions, int six,
                                                               double delta, double budget, int *used)
{
    const __m256d inv = _mm256_set1_pd(s > 0.0 ? 1.0 / s : 0.0), vs = _mm256_set1_pd(s), val = _mm256_set1_pd(al);
    const __m256d zero = _mm256_setzero_pd(), half = _mm256_set1_pd(0.5), top = _mm256_set1_pd((double)divisions);
    const __m256d vd = _mm256_set1_pd(delta), sign = _mm256_set1_pd(-0.0);
    __m256d acc = zero;
    for (int k = 0; k < 16; k += 4) {
        __m256d t = _mm256_loadu_pd(ll->t + k);
        __m256d u = _mm256_mul_pd(_mm256_sub_pd(t, val), inv);
        /* (int)(u + 0.5) for u > 0, else 0; then at most divisions (u <= 0 gives floor(0.5) = 0) */
        __m256d kk = _mm256_floor_pd(_mm256_add_pd(_mm256_max_pd(u, zero), half));
        kk = _mm256_min_pd(kk, top);
        __m256d d = _mm256_sub_pd(_mm256_andnot_pd(sign, _mm256_sub_pd(t, _mm256_add_pd(val, _mm256_mul_pd(kk, vs)))), vd);
        d = _mm256_max_pd(d, zero);
        __m256d term = _mm256_mul_pd(d, d);
        if (six)
            term = _mm256_min_pd(term, _mm256_loadu_pd(ll->six_min + k));
        term = _mm256_and_pd(term, _mm256_loadu_pd(ll->tight + k));
        acc = ch->use_max ? _mm256_max_pd(acc, term) : _mm256_add_pd(acc, term);
    }
    __m128d h = ch->use_max ? _mm_max_pd(_mm256_castpd256_pd128(acc), _mm256_extractf128_pd(acc, 1))
                            : _mm_add_pd(_mm256_castpd256_pd128(acc), _mm256_extractf128_pd(acc, 1));
    h = ch->use_max ? _mm_max_sd(h, _mm_unpackhi_pd(h, h)) : _mm_add_sd(h, _mm_unpackhi_pd(h, h));
    double sum = _mm_cvtsd_f64(h) * (1.0 - 1e-12);
    (void)budget;
    *used = 16;
    return sum;
}
#endif

/* ---- enumeration of the pairs that can score <= budget ----
 *
 * Tight terms: a pair can only score <= budget if the smallest and the largest target each lie
 * within r = sqrt(budget) of a palette entry. With the low anchor L fixed, the entries are
 * A(L) + (k / D) (A(H) - A(L)), k = 0..D (D = 7 or 5, plus -1 and +1 in 6-value mode), so for each k
 * the high anchors H that bring entry k within r of a target form one interval: at most D + 1
 * intervals per target, intersected as 256-bit masks. Rounded decoders move an entry by at most
 * `delta` (half a code of their precision), added to r. The masks are a superset of the pairs
 * within budget; each survivor is then scored exactly with early exit. Loose terms scan all pairs. */

typedef struct anchor_mask {
    uint64_t w[4];
} anchor_mask;

/* below[n]: the 256-bit mask of the codes < n, n = 0..256 (a range [lo, hi] is below[hi + 1] minus
 * below[lo]: two loads a word instead of a loop over the words with shifts). */
#define BELOW_W(n, w) ((n) >= 64 * (w) + 64 ? ~UINT64_C(0) : (n) <= 64 * (w) ? UINT64_C(0) : (UINT64_C(1) << (((n) - 64 * (w)) & 63)) - 1)
#define BELOW_1(n) {{BELOW_W(n, 0), BELOW_W(n, 1), BELOW_W(n, 2), BELOW_W(n, 3)}}
#define BELOW_4(n) BELOW_1(n), BELOW_1(n + 1), BELOW_1(n + 2), BELOW_1(n + 3)
#define BELOW_16(n) BELOW_4(n), BELOW_4(n + 4), BELOW_4(n + 8), BELOW_4(n + 12)
#define BELOW_64(n) BELOW_16(n), BELOW_16(n + 16), BELOW_16(n + 32), BELOW_16(n + 48)
static const anchor_mask below[257] = {BELOW_64(0), BELOW_64(64), BELOW_64(128), BELOW_64(192), BELOW_1(256)};

/* m |= the codes lo..hi (clamped to 0..255; nothing if lo > hi after clamping). */
static inline void mask_set_range(anchor_mask *m, int lo, int hi)
{
    lo = lo < 0 ? 0 : lo;
    hi = hi > 255 ? 255 : hi;
    if (lo > hi)
        return;
    for (int w = 0; w < 4; ++w)
        m->w[w] |= below[hi + 1].w[w] & ~below[lo].w[w];
}

/* A(c) = 2 c / 255 - 1 and the lattice steps (A(d) + 1) / 7 and / 5 of span d, tabulated: the same
 * expressions folded at compile time (correctly rounded as at run time), so the same doubles without
 * the divisions (the enumeration's per-low loop and span_alive took one or two per code). */
#define ANCHOR_OF(c) (2.0 * (c) / 255.0 - 1.0)
#define ANCHOR_1(c) ANCHOR_OF(c)
#define ANCHOR_4(c) ANCHOR_1(c), ANCHOR_1(c + 1), ANCHOR_1(c + 2), ANCHOR_1(c + 3)
#define ANCHOR_16(c) ANCHOR_4(c), ANCHOR_4(c + 4), ANCHOR_4(c + 8), ANCHOR_4(c + 12)
#define ANCHOR_64(c) ANCHOR_16(c), ANCHOR_16(c + 16), ANCHOR_16(c + 32), ANCHOR_16(c + 48)
static const double anchor_table[256] = {ANCHOR_64(0), ANCHOR_64(64), ANCHOR_64(128), ANCHOR_64(192)};
#undef ANCHOR_1
#define ANCHOR_1(c) ((ANCHOR_OF(c) + 1.0) / 7)
static const double step7_table[256] = {ANCHOR_64(0), ANCHOR_64(64), ANCHOR_64(128), ANCHOR_64(192)};
#undef ANCHOR_1
#define ANCHOR_1(c) ((ANCHOR_OF(c) + 1.0) / 5)
static const double step5_table[256] = {ANCHOR_64(0), ANCHOR_64(64), ANCHOR_64(128), ANCHOR_64(192)};

static inline double anchor_value(int code)
{
    return anchor_table[code];
}

/* divisions / k, k = 1..8, for the 8-value mode (7 / k) and the 6-value mode (5 / k; the k above
 * divisions pad the vector form's lanes and are never used): the correctly rounded quotients,
 * folded at compile time. */
static const double scale7[8] = {7.0 / 1, 7.0 / 2, 7.0 / 3, 7.0 / 4, 7.0 / 5, 7.0 / 6, 7.0 / 7, 7.0 / 8};
static const double scale5[8] = {5.0 / 1, 5.0 / 2, 5.0 / 3, 5.0 / 4, 5.0 / 5, 5.0 / 6, 5.0 / 7, 5.0 / 8};

/* The high anchors H in [hmin, hmax] whose palette (low anchor L, D = divisions intervals) has an
 * entry within r of t: every H if the low anchor (entry 0) or, in 6-value mode, -1 or +1 is within r;
 * else for each k = 1..D, entry k = A(L) + (k / D) (A(H) - A(L)) lies in [t - r, t + r] iff
 *     A(H) in [A(L) + (D / k) (t - r - A(L)), A(L) + (D / k) (t + r - A(L))]
 * (k / D > 0), and A(H) = 2 H / 255 - 1, so H in [ceil((lo + 1) 127.5), floor((hi + 1) 127.5)],
 * each end widened by 1e-6 code (far above the rounding of these few operations: the mask is a
 * superset, the caller scores what passes). The ends are clamped in doubles before conversion
 * (x > y ? x : y, which keeps y for a NaN x: a NaN end gives the whole range, a superset); the lower
 * end at most 256 and the upper at least -1, so an empty interval gives below[hi + 1] minus
 * below[lo] = nothing. reachable_scalar and reachable_avx2 (the D intervals in two vectors of 4, the
 * same operations per lane, no FMA) give the same mask, bit for bit (tested). */
static inline int reach_all(double t, double al, int six_value, double r)
{
    return fabs(al - t) <= r || (six_value && (fabs(t + 1.0) <= r || fabs(t - 1.0) <= r));
}

static anchor_mask reachable_scalar(double t, int low, int divisions, int six_value, double r, int hmin, int hmax)
{
    anchor_mask m = {{0, 0, 0, 0}};
    const double al = anchor_value(low);
    if (reach_all(t, al, six_value, r)) {
        mask_set_range(&m, hmin, hmax);
        return m;
    }
    const double *scale = divisions == 7 ? scale7 : scale5, lo_t = t - r - al, hi_t = t + r - al;
    for (int k = 1; k <= divisions; ++k) {
        double h_lo = ceil((al + scale[k - 1] * lo_t + 1.0) * 127.5 - 1e-6);
        double h_hi = floor((al + scale[k - 1] * hi_t + 1.0) * 127.5 + 1e-6);
        h_lo = h_lo > hmin ? h_lo : hmin;
        h_lo = h_lo < 256.0 ? h_lo : 256.0;
        h_hi = h_hi < hmax ? h_hi : hmax;
        h_hi = h_hi > -1.0 ? h_hi : -1.0;
        int lo = (int)h_lo, hi = (int)h_hi;
        for (int w = 0; w < 4; ++w)
            m.w[w] |= below[hi + 1].w[w] & ~below[lo].w[w];
    }
    return m;
}

#if LOOSE_AVX2
static __attribute__((target("avx2"))) anchor_mask reachable_avx2(double t, int low, int divisions, int six_value,
                                                                  double r, int hmin, int hmax)
{
    anchor_mask m = {{0, 0, 0, 0}};
    const double al = anchor_value(low);
    if (reach_all(t, al, six_value, r)) {
        mask_set_range(&m, hmin, hmax);
        return m;
    }
    const double *scale = divisions == 7 ? scale7 : scale5;
    const __m256d val = _mm256_set1_pd(al), lo_t = _mm256_set1_pd(t - r - al), hi_t = _mm256_set1_pd(t + r - al);
    const __m256d one = _mm256_set1_pd(1.0), half_codes = _mm256_set1_pd(127.5), eps = _mm256_set1_pd(1e-6);
    const __m256d vmin = _mm256_set1_pd((double)hmin), vmax = _mm256_set1_pd((double)hmax);
    const __m256d top = _mm256_set1_pd(256.0), bottom = _mm256_set1_pd(-1.0);
    int lo[8], hi[8];
    for (int h = 0; h < 2; ++h) {
        __m256d s = _mm256_loadu_pd(scale + 4 * h);
        __m256d a = _mm256_add_pd(_mm256_add_pd(val, _mm256_mul_pd(s, lo_t)), one);
        __m256d b = _mm256_add_pd(_mm256_add_pd(val, _mm256_mul_pd(s, hi_t)), one);
        __m256d h_lo = _mm256_ceil_pd(_mm256_sub_pd(_mm256_mul_pd(a, half_codes), eps));
        __m256d h_hi = _mm256_floor_pd(_mm256_add_pd(_mm256_mul_pd(b, half_codes), eps));
        h_lo = _mm256_min_pd(_mm256_max_pd(h_lo, vmin), top);
        h_hi = _mm256_max_pd(_mm256_min_pd(h_hi, vmax), bottom);
        _mm_storeu_si128((__m128i *)(lo + 4 * h), _mm256_cvttpd_epi32(h_lo));
        _mm_storeu_si128((__m128i *)(hi + 4 * h), _mm256_cvttpd_epi32(h_hi));
    }
    __m256i acc = _mm256_setzero_si256();
    for (int k = 0; k < divisions; ++k) {
        __m256i up = _mm256_loadu_si256((const __m256i *)below[hi[k] + 1].w);
        __m256i down = _mm256_loadu_si256((const __m256i *)below[lo[k]].w);
        acc = _mm256_or_si256(acc, _mm256_andnot_si256(down, up));
    }
    _mm256_storeu_si256((__m256i *)m.w, acc);
    return m;
}
#endif

/* reachable_avx2 where avx2 is set (the caller checked the processor), else reachable_scalar. */
static inline anchor_mask reachable(int avx2, double t, int low, int divisions, int six_value, double r, int hmin,
                                    int hmax)
{
#if LOOSE_AVX2
    if (avx2)
        return reachable_avx2(t, low, divisions, six_value, r, hmin, hmax);
#else
    (void)avx2;
#endif
    return reachable_scalar(t, low, divisions, six_value, r, hmin, hmax);
}

static double rounding_delta(sol_bc4_precision precision)
{
    /* decoded units (2 v - 1): half a code of the interpolant's precision, times 2 */
    if (precision == SOL_BC4_INTERP_8BIT)
        return 1.0 / 255.0;
    if (precision == SOL_BC4_INTERP_16BIT)
        return 1.0 / 65535.0;
    return 0.0;
}

void sol_nm_reachable_mask(int simd, double t, int low, int divisions, int six_value, double r, int hmin, int hmax,
                           uint64_t out[4])
{
#if LOOSE_AVX2
    simd = simd && __builtin_cpu_supports("avx2");
#endif
    anchor_mask m = reachable(simd, t, low, divisions, six_value, r, hmin, hmax);
    memcpy(out, m.w, sizeof m.w);
}

/* The mean bound of the sum metric (every pixel tight). For any point c, the distance to the set S of
 * a pair's decoded entries is 1-Lipschitz: dist(t_p, S) >= dist(c, S) - a_p with a_p = |t_p - c|. So
 * the pair's score sum_p dist(t_p, S)^2 >= f(dist(c, S)) with f(d) = sum_p max(0, d - a_p)^2, which
 * is non-decreasing in d. A pair can score <= T only if f(dist(c, S)) <= T, i.e. dist(c, S) <= D(T),
 * D(T) the largest d with f(d) <= T: some entry within D(T) of c, that is some lattice point
 * A(L) + k s within D(T) + delta of c (the decoder moves each entry by at most delta; reachable()
 * also covers the anchors themselves and the 6-value mode's -1 and +1). c is the targets' mean, where
 * f grows fastest: for a block of width w the mask keeps the lattice points within about
 * sqrt(T / 16) + w / 2 of it, where the three extreme pixels' masks keep those within sqrt(T) of all
 * three (an interval of width 2 sqrt(T) - w): on the narrow blocks of smooth maps about 4x fewer high
 * anchors per low anchor, each of which the lattice bound would otherwise reject on its own (issue 13:
 * the lists' enumeration was ~70% of the optimal encoder's time on the terrain-derived map, perf).
 * D(T) is found by bisection on f in doubles, from T raised by a relative 1e-9, and raised by a
 * relative 1e-9 and 1e-12 absolute: far above the rounding of f, of a_p and of the computed scores,
 * so only pairs that cannot score <= T leave the mask, and the pairs collected (and the argmin) are
 * the same. */
typedef struct mean_bound {
    double c, a[16];
    double tb, reach; /* the last budget asked and its D, with the slack above */
} mean_bound;

static void mean_bound_init(mean_bound *mb, const double t[16])
{
    double c = 0.0;
    for (int p = 0; p < 16; ++p)
        c += t[p];
    c /= 16.0;
    mb->c = c;
    for (int p = 0; p < 16; ++p)
        mb->a[p] = fabs(t[p] - c);
    mb->tb = -1.0;
    mb->reach = INFINITY;
}

static double mean_bound_f(const mean_bound *mb, double d)
{
    double f = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = d - mb->a[p];
        f += e > 0.0 ? e * e : 0.0;
    }
    return f;
}

/* D(tb) with its slack (see above), cached for the last tb. */
static double mean_bound_reach(mean_bound *mb, double tb)
{
    if (tb == mb->tb)
        return mb->reach;
    const double t_up = tb * (1.0 + 1e-9);
    double lo = 0.0, hi = sqrt(t_up) + 2.0; /* f(hi) >= (hi - 2)^2 = t_up: every a_p <= 2 */
    for (int it = 0; it < 60 && hi - lo > 1e-13 * hi; ++it) {
        double mid = 0.5 * (lo + hi);
        if (mean_bound_f(mb, mid) <= t_up)
            lo = mid;
        else
            hi = mid;
    }
    mb->tb = tb;
    mb->reach = hi * (1.0 + 1e-9) + 1e-12;
    return mb->reach;
}

/* The span bound's masks (sum metric, every pixel tight). Every pair of span d = H - L, whatever L,
 * has its lattice entries A(L) + j s, s = 2 d / (255 D), within delta of the infinite lattice
 * A(L) + s Z, so it scores at least sol_nm_span_bounds's bound for the step s (bc4_span_bound.c: the
 * targets' least circular sum of squares modulo s over every phase, less the rounding allowance; the
 * ends of the palette ignored, which only lowers it). In 6-value mode the fixed entries -1 and +1 are
 * off the lattice: the bound holds for a pair scoring <= T only if no target lies within sqrt(T) of
 * either (then no pixel whose term is <= T can use them), so that mode gets every span otherwise.
 * alive->w: bit d set unless span d's bound exceeds tb; the caller shifts it by L (bit L + d = H) into
 * the low anchor's mask. On wide blocks few spans fit (bc4_span_bound.c: 4-9 of 50-60 against the
 * optimum), and the per-low masks of the mean and the extreme pixels, blind to the phase all
 * entries share, keep many high anchors that the lattice bound then rejects one by one (issue 13:
 * that walk was ~60% of the optimal encoder's time on terrain and ridges). The bound is the one the
 * common search prunes with, so the mask only drops pairs that cannot score <= tb. */
static void span_alive(const double sorted[16], int six, double delta, double tb, anchor_mask *alive)
{
    const double r = sqrt(tb) * (1.0 + 1e-9) + 1e-12;
    if (six && (sorted[0] - r <= -1.0 || sorted[15] + r >= 1.0)) {
        mask_set_range(alive, 0, 255);
        return;
    }
    /* the ends: a pair scoring <= tb has entries within r + delta of the smallest and the largest
     * target, and its entries lie in [A(L) - delta, A(H) + delta] (-1 and +1 out of reach in 6-value
     * mode, see above), so A(H) - A(L) = 2 d / 255 >= tmax - tmin - 2 (r + delta): the spans below
     * d0 (lowered by 1e-6 code) cannot, and their bounds are not computed (in lanes of 16 from d0) */
    double d0 = floor(((sorted[15] - sorted[0]) - 2.0 * (r + delta)) * 127.5 - 1e-6);
    const int first = d0 <= 0.0 ? 0 : (d0 >= 255.0 ? 255 : (int)d0) & ~15;
    double lb[256];
    sol_nm_span_bounds_all(sorted, (six ? step5_table : step7_table) + first, 256 - first, delta, tb, lb + first);
    for (int d = 0; d < first; ++d)
        lb[d] = INFINITY;
    for (int w = 0; w < 4; ++w) {
        uint64_t bits = 0;
        for (int b = 0; b < 64; ++b)
            bits |= (uint64_t)(lb[64 * w + b] <= tb) << b;
        alive->w[w] = bits;
    }
}

/* The mask a with bit d moved to bit d + s (0 <= s <= 255; bits past 255 drop out). */
static inline anchor_mask mask_shift_up(const anchor_mask *a, int s)
{
    anchor_mask m = {{0, 0, 0, 0}};
    const int q = s >> 6, b = s & 63;
    for (int w = q; w < 4; ++w)
        m.w[w] = (a->w[w - q] << b) | (b && w > q ? a->w[w - q - 1] >> (64 - b) : 0);
    return m;
}

void sol_nm_span_mask(const double t[16], int six_value, sol_bc4_precision precision, double tb, uint64_t out[4])
{
    double sorted[16];
    anchor_mask alive = {{0, 0, 0, 0}};
    sol_nm_sort16(t, sorted);
    span_alive(sorted, six_value, rounding_delta(precision) + 1e-12, tb, &alive);
    memcpy(out, alive.w, sizeof alive.w);
}

/* Blocks at least this many codes wide (largest - smallest target) use span_alive: on narrower ones
 * every step fits at some phase and its 32 bound evaluations per mode would be wasted. */
#define SPAN_MASK_CODES 3.0

/* Visits candidate pairs: argmin (budget shrinks to the best score; *best_pair updated with the
 * least (score, pair)) or collect (fixed budget, survivors appended to out). Returns the count. */
static size_t enumerate_pairs(const sol_nm_channel *ch, double *budget, int *best_pair, sol_nm_pair *out)
{
    size_t n = 0;
    const int collect = out != NULL;
    const double delta = rounding_delta(ch->precision) + 1e-12;
    /* the high-anchor skip (below), per number u of pixels the lattice bound used: the norm's step
     * per code, its inverse, and the least bound that skips a step at the current budget */
    double norm_step[17], inv_norm_step[17], skip_floor[17], skip_budget = -1.0, root_budget = 0.0;
    for (int u = 1; u <= 16; ++u) {
        norm_step[u] = (2.0 / 255.0) * (ch->use_max ? 1.0 : sqrt((double)u));
        inv_norm_step[u] = 1.0 / norm_step[u];
    }
    /* the loose pixels' offsets: every score is at least `floor`; the lattice bound and the masks
     * (tight pixels only) work against what the budget leaves above it (tb below) */
    double floor = 0.0;
    for (int p = 0; p < 16; ++p)
        if ((ch->loose >> p) & 1)
            floor = ch->use_max ? (ch->loose_off[p] > floor ? ch->loose_off[p] : floor) : floor + ch->loose_off[p];
    floor *= 1.0 - 1e-12; /* below every score's computed sum or max of the same offsets */
    loose_lanes ll;
    const int lanes = loose_avx2(ch);
    if (lanes)
        loose_lanes_init(ch, &ll);
    if (collect && ch->loose == 0xffffu) {
        /* every pixel loose: no mask or lattice bound excludes a pair (they use tight pixels only), so
         * the walk below visits every pair of the ranges (each is in one mode: e0 > e1 or e0 <= e1);
         * visited here in table order instead, whose reads stream through the 4 MB palette table
         * (the walk's steps of 256 pairs touched a new page at each pair: most of the scoring's time).
         * The same pairs and scores, in e0-major order. */
        double tb = ch->use_max ? (floor > *budget ? -1.0 : *budget) : *budget - floor;
        if (tb < 0.0)
            return 0;
        /* 6-value pairs (e0 <= e1) hold the entries -1 and +1. If for every pixel the entry of t's
         * sign lies in its loose interval (|t| <= 1 <= reach: |t| >= 1 / sqrt(2), rims and blocks
         * pointing away near an axis), term_loose is 0 there whatever the other entries (it returns
         * 0 at that entry; score_loose_avx2's lane is blended to 0), so every 6-value pair scores
         * the same fold of off + w 0, computed once by the same function on the first of them
         * (issue 13: half of such a channel's 65536 scorings). */
        int six_same = 1;
        for (int p = 0; p < 16; ++p)
            six_same &= fabs(ch->t[p]) <= 1.0 && ch->loose_reach[p] >= 1.0;
        double six_score = 0.0;
        int six_known = 0;
        for (int e0 = ch->e0_lo; e0 <= ch->e0_hi; ++e0)
            for (int e1 = ch->e1_lo; e1 <= ch->e1_hi; ++e1) {
                int pair = e0 << 8 | e1;
                double v;
                if (six_same && e0 <= e1 && six_known) {
                    v = six_score;
                } else {
#if LOOSE_AVX2
                    v = lanes ? score_loose_avx2(ch, &ll, ch->palettes[pair], *budget) : score_pair(ch, pair, *budget);
#else
                    v = score_pair(ch, pair, *budget);
#endif
                    if (six_same && e0 <= e1) {
                        six_score = v;
                        six_known = 1;
                    }
                }
                if (v <= *budget) {
                    out[n].score = v;
                    out[n].pair = (uint16_t)pair;
                    ++n;
                }
            }
        return n;
    }
    /* the lattice bound 4 pixels at a time where AVX2 runs (score_lower_avx2) */
    lattice_lanes lat_ll;
#if LOOSE_AVX2
    const int lat = !sol_nm_simd_disable && __builtin_cpu_supports("avx2");
#else
    const int lat = 0;
#endif
    if (lat)
        lattice_lanes_init(ch, &lat_ll);
    const int tight_lanes = lat && ch->loose == 0; /* score_tight_avx2 scores the pairs */
    /* the mean bound (see mean_bound): sum metric, every pixel tight */
    const int meanb = !ch->use_max && ch->loose == 0;
    mean_bound mb = {0.0, {0.0}, -1.0, INFINITY};
    if (meanb)
        mean_bound_init(&mb, ch->t);
    /* the span bound's masks (see span_alive): the sum metric, every pixel tight, wide blocks */
    double sorted[16];
    anchor_mask alive = {{0, 0, 0, 0}};
    const int spanb = meanb && (ch->t[ch->order[1]] - ch->t[ch->order[0]]) * 127.5 >= SPAN_MASK_CODES;
    if (spanb)
        sol_nm_sort16(ch->t, sorted);
    for (int six = 0; six < 2; ++six) {
        /* 8-value: e0 > e1, low anchor e1; 6-value: e0 <= e1, low anchor e0 */
        int low_lo = six ? ch->e0_lo : ch->e1_lo, low_hi = six ? ch->e0_hi : ch->e1_hi;
        int high_lo = six ? ch->e1_lo : ch->e0_lo, high_hi = six ? ch->e1_hi : ch->e0_hi;
        /* lows visited outward from the smallest target's code: good pairs early, budget shrinks */
        if (spanb) /* at the budget now: it only shrinks (argmin), so the mask stays a superset */
            span_alive(sorted, six, delta, *budget, &alive);
        int centre = (int)lround((ch->t[ch->order[0]] + 1.0) * 127.5);
        centre = centre < low_lo ? low_lo : (centre > low_hi ? low_hi : centre);
        for (int step = 0; step <= 2 * (low_hi - low_lo); ++step) {
            int low = centre + (step & 1 ? -(step + 1) / 2 : step / 2);
            if (low < low_lo || low > low_hi)
                continue;
            int hmin = high_lo > low + !six ? high_lo : low + !six;
            if (hmin > high_hi)
                continue;
            double tb = ch->use_max ? (floor > *budget ? -1.0 : *budget) : *budget - floor;
            if (tb < 0.0)
                return n; /* no pair scores within the budget (it only shrinks) */
            anchor_mask m = {{0, 0, 0, 0}};
            /* every 8-value entry is >= the low anchor: it must reach the smallest target */
            double t0 = ch->t[ch->order[0]];
            if (!((ch->loose >> ch->order[0]) & 1) && anchor_value(low) > t0 + sqrt(tb) + delta &&
                (!six || (t0 + 1.0) * (t0 + 1.0) > tb))
                continue;
            const int divisions = six ? 5 : 7;
            mask_set_range(&m, hmin, high_hi);
            if (spanb) {
                anchor_mask a = mask_shift_up(&alive, low);
                for (int w = 0; w < 4; ++w)
                    m.w[w] &= a.w[w];
                if (!(m.w[0] | m.w[1] | m.w[2] | m.w[3]))
                    continue;
            }
            if (meanb) { /* the mean bound's mask first: the most selective on narrow blocks */
                double reach = mean_bound_reach(&mb, tb) + delta;
                /* 8-value entries are >= A(low) - delta: none within reach of c if A(low) is above c + reach
                 * (6-value: unless -1 or +1 is within reach, which reachable() then lets through) */
                if (!six && anchor_value(low) > mb.c + reach)
                    continue;
                anchor_mask b = reachable(lat, mb.c, low, divisions, six, reach, hmin, high_hi);
                for (int w = 0; w < 4; ++w)
                    m.w[w] &= b.w[w];
            }
            /* the three extreme pixels' reachable masks (a loose pixel constrains nothing) */
            double r = sqrt(tb) + delta;
            for (int k = 0; k < 3 && (m.w[0] | m.w[1] | m.w[2] | m.w[3]); ++k) {
                if ((ch->loose >> ch->order[k]) & 1)
                    continue;
                anchor_mask b = reachable(lat, ch->t[ch->order[k]], low, divisions, six, r, hmin, high_hi);
                for (int w = 0; w < 4; ++w)
                    m.w[w] &= b.w[w];
            }
            int next_high = 0;
            if (tb != skip_budget) { /* argmin: the budget shrank */
                skip_budget = tb;
                root_budget = sqrt(skip_budget);
                for (int u = 1; u <= 16; ++u)
                    skip_floor[u] = (root_budget + norm_step[u]) * (root_budget + norm_step[u]);
            }
            for (int w = 0; w < 4; ++w) {
                uint64_t bits = m.w[w];
                while (bits) {
                    int high = 64 * w + __builtin_ctzll(bits);
                    bits &= bits - 1;
                    if (high < next_high)
                        continue;
                    int pair = six ? (low << 8 | high) : (high << 8 | low);
                    double al = anchor_value(low), spacing = (anchor_value(high) - al) / divisions;
                    int used;
#if LOOSE_AVX2
                    double lb = lat ? score_lower_avx2(ch, &lat_ll, al, spacing, divisions, six, delta, tb, &used)
                                    : score_lower(ch, al, spacing, divisions, six, delta, tb, &used);
#else
                    double lb = score_lower(ch, al, spacing, divisions, six, delta, tb, &used);
#endif
                    if (lb > tb) {
                        /* the lattice bound's pixel distances move by at most one code (2 / 255) per
                         * step of the high anchor, so the L2 norm of the `used` pixels' distances (or
                         * their max) by at most sqrt(used) codes: skip the steps it cannot recover
                         * (root_budget may be stale, i.e. larger: a shorter skip) */
                        if (lb > skip_floor[used]) {
                            double skip = (sqrt(lb) - root_budget) * inv_norm_step[used] * (1.0 - 1e-9) - 1e-6;
                            if (skip >= 1.0)
                                next_high = high + 1 + (skip > 512.0 ? 512 : (int)skip);
                        }
                        continue;
                    }
#if LOOSE_AVX2
                    double v;
                    if (tight_lanes) {
                        double pal[8];
                        sol_nm_small_palette(ch->precision, pair, pal);
                        v = score_tight_avx2(lat_ll.t, pal, ch->use_max, *budget);
                    } else {
                        v = lanes ? score_loose_avx2(ch, &ll, ch->palettes[pair], *budget) : score_pair(ch, pair, *budget);
                    }
#else
                    double v = score_pair(ch, pair, *budget);
#endif
                    if (collect) {
                        if (v <= *budget) {
                            out[n].score = v;
                            out[n].pair = (uint16_t)pair;
                            ++n;
                        }
                    } else if (v < *budget || (v == *budget && pair < *best_pair)) {
                        *budget = v;
                        *best_pair = pair;
                    }
                }
            }
        }
    }
    return n;
}

int sol_nm_channel_argmin(const sol_nm_channel *ch, double *score)
{
    /* start from the corner pair (full span, 8-value mode) if it is in range, else the first pair */
    int lo = (int)floor((ch->t[ch->order[0]] + 1.0) * 127.5), hi = (int)ceil((ch->t[ch->order[1]] + 1.0) * 127.5);
    lo = lo < 0 ? 0 : (lo > 255 ? 255 : lo);
    hi = hi < 0 ? 0 : (hi > 255 ? 255 : hi);
    int best = ch->e0_lo << 8 | ch->e1_lo;
    if (hi >= ch->e0_lo && hi <= ch->e0_hi && lo >= ch->e1_lo && lo <= ch->e1_hi)
        best = hi << 8 | lo;
    double budget = score_pair(ch, best, INFINITY);
    /* a short descent over the neighbouring pairs (both modes) gives a tight budget before the
     * exhaustive enumeration, whose masks shrink with the budget */
    for (int improved = 1, rounds = 0; improved && rounds < 64; ++rounds) {
        improved = 0;
        int e0 = best >> 8, e1 = best & 255;
        for (int d0 = -2; d0 <= 2; ++d0)
            for (int d1 = -2; d1 <= 2; ++d1) {
                int a = e0 + d0, b = e1 + d1;
                if (a < ch->e0_lo || a > ch->e0_hi || b < ch->e1_lo || b > ch->e1_hi)
                    continue;
                double v = score_pair(ch, a << 8 | b, budget);
                if (v < budget) {
                    budget = v;
                    best = a << 8 | b;
                    improved = 1;
                }
            }
        int swapped = (best & 255) << 8 | best >> 8; /* the same span in the other mode */
        if ((swapped >> 8) >= ch->e0_lo && (swapped >> 8) <= ch->e0_hi && (swapped & 255) >= ch->e1_lo &&
            (swapped & 255) <= ch->e1_hi) {
            double v = score_pair(ch, swapped, budget);
            if (v < budget) {
                budget = v;
                best = swapped;
                improved = 1;
            }
        }
    }
    enumerate_pairs(ch, &budget, &best, NULL);
    *score = budget;
    return best;
}

size_t sol_nm_channel_collect(const sol_nm_channel *ch, double budget, sol_nm_pair *out)
{
    return enumerate_pairs(ch, &budget, NULL, out);
}
