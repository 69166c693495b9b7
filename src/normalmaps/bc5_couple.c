/* bc5_couple.c - bounds of the exact 3Dc search per anchor pair that couple the two channels, and
 * incumbents by coordinate descent (issue 13: rims and normals pointing away).
 *
 * The per-channel scores (anchor_bounds.c, bc5.c "pixels pointing away") let x and y reach a pixel's
 * rim direction separately, so whole rows of x pairs survive that no y pair can serve, and the
 * per-candidate coupled bound (bc5_away.c) meets every candidate of such a row. Here a bound holds
 * for a whole row: with x palette a_0..a_7 fixed, pixel p decodes as (a_i, b) for some i and some b
 * among the y list's values, so its angle is at least acos(max_i C_p(a_i)) with
 *     C_p(a) = max over b in S of cos(decode(a, b), n_p),
 * S any superset of those values: here the union of at most COUPLE_SPANS intervals (the list's
 * values split at their widest gaps). Summed (or maxed) over the pixels this bounds every candidate
 * of the row from below; a row reaching the incumbent goes. The same with x and y swapped (the decode
 * is symmetric in its two components, so C for a y value is C with n's x and y swapped), in turn,
 * each channel's values shrinking the other's spans.
 *
 * C_p(a) in closed form (code_cosines). With r = a^2 + b^2 and s = sqrt(1 - a^2) (0 if |a| >= 1):
 *  - |b| < s: the decode (a, b, sqrt(s^2 - b^2)) is a unit vector on the half circle x = a, z >= 0;
 *    g(b) = a nx + b ny + sqrt(s^2 - b^2) nz, whose derivative vanishes only at b = s ny / q (a maximum,
 *    g = a nx + s q, q = |(ny, nz)|) when nz > 0, or at b = -s ny / q (a minimum) when nz < 0;
 *  - |b| >= s (z clamped to 0): the decode's direction is (a, b, 0) / sqrt(r) and
 *    g(b) = (a nx + b ny) / sqrt(r), g'(b) = a (a ny - b nx) / r^(3/2): one critical point, b = a ny / nx.
 * g is continuous (both forms are a nx + b ny at |b| = s) and differentiable but at +-s, so its largest
 * value on an interval is at an end, at +-s, or at a critical point inside; code_cosines takes the
 * largest g over all of those that lie in some span (extra points inside a span only give values g
 * attains there). The ends and +-s give one decode direction for all 16 pixels.
 *
 * Rounding: the decoder (bc5.c rebuild_z) clamps where 1 - a^2 - b^2 <= 0 in floating point, which
 * near r = 1 differs from the real clamp by a z of at most sqrt(4e-16) = 2e-8: every decode's
 * direction lies within 3e-8 rad of the real-arithmetic set above, and the roots, products and
 * divisions here add a few 1e-16. The cosine is raised by 1e-7 (covers both), acos lowered by 1e-12
 * relative, and angle^2 rounded down to float (the per-value table). A value b taken from a value
 * code lies within 1e-12 of the palette's double (spans widened by that). So no pair is dropped that
 * has a candidate below the incumbent; the tests check C against dense sampling of the decodes and
 * that it is within 2% of attained (not only valid), and the reduction against brute force.
 *
 * The row bound costs 16 table lookups per entry: C_p is kept per distinct value (value codes, as
 * bc5.c's value_set: every palette value is K / Q exactly) and filled on first use per pass. */
#include "normalmaps_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the reduction of both lists ---- */
#define COUPLE_CODES 65536
#define COUPLE_SPANS 8

struct sol_nm_couple {
    uint32_t gen;
    uint32_t stamp[COUPLE_CODES]; /* the generation in which e2[code] was filled */
    float e2[COUPLE_CODES][16];
    uint64_t bits[COUPLE_CODES / 64];
};

/* Forgets every cached e2 row at once: a row counts only if its stamp is the current generation
 * (on the rare wrap-around of the counter every stamp is cleared). */
static void next_generation(sol_nm_couple *cs)
{
    if (++cs->gen == 0) {
        memset(cs->stamp, 0, sizeof cs->stamp);
        cs->gen = 1;
    }
}

/* The code of entry value v (v = k / half_q - 1 for an integer k in 0 .. 2 half_q, to within a few
 * 1e-16): the nearest integer to (v + 1) half_q, which is >= 0, so truncating after adding 0.5 rounds
 * it as lround would (the argument lies within 1e-10 of an integer, far from a half) without the
 * library call (2-3% of a block pointing away, issue 13). */
static inline long value_code(double v, double half_q)
{
    return (long)((v + 1.0) * half_q + 0.5);
}

/* The cached row of per-pixel angle^2 floors of entry value v (its code on the q grid); *stale = 1
 * if it was not filled in this generation (it now counts as filled: the caller fills it). */
static float *entry_row(sol_nm_couple *cs, double v, double half_q, int *stale)
{
    long k = value_code(v, half_q);
    *stale = cs->stamp[k] != cs->gen;
    cs->stamp[k] = cs->gen;
    return cs->e2[k];
}

/* The block objective's fold of 16 per-pixel floors: their sum, or their max for SOL_BC5_MAX. */
static double fold_row(const float row[16], int use_max)
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p)
        s = use_max ? (row[p] > s ? row[p] : s) : s + row[p];
    return s;
}

sol_nm_couple *sol_nm_couple_new(void)
{
    return calloc(1, sizeof(sol_nm_couple));
}

void sol_nm_couple_free(sol_nm_couple *cs)
{
    free(cs);
}

/* The spans of the values of a list (at most COUPLE_SPANS intervals covering every value, split at the
 * widest gaps); returns their count. */
static int list_spans(sol_nm_couple *cs, const sol_nm_pair *list, size_t count, const double (*pal)[8],
                      double half_q, double lo[COUPLE_SPANS], double hi[COUPLE_SPANS])
{
    memset(cs->bits, 0, sizeof cs->bits);
    for (size_t i = 0; i < count; ++i)
        for (int e = 0; e < 8; ++e) {
            long k = value_code(pal[list[i].pair][e], half_q);
            cs->bits[k >> 6] |= UINT64_C(1) << (k & 63);
        }
    /* the COUPLE_SPANS - 1 widest gaps between consecutive codes (by code: values are affine in them) */
    long gap[COUPLE_SPANS - 1], at[COUPLE_SPANS - 1], first = -1, prev = -1;
    int ng = 0;
    for (int w = 0; w < COUPLE_CODES / 64; ++w)
        for (uint64_t b = cs->bits[w]; b; b &= b - 1) {
            long k = 64L * w + __builtin_ctzll(b);
            if (first < 0)
                first = k;
            if (prev >= 0 && k - prev > 1) {
                long g = k - prev;
                int q = -1;
                if (ng < COUPLE_SPANS - 1)
                    q = ng++;
                else if (g > gap[COUPLE_SPANS - 2])
                    q = COUPLE_SPANS - 2;
                for (; q > 0 && gap[q - 1] < g; --q) {
                    gap[q] = gap[q - 1];
                    at[q] = at[q - 1];
                }
                if (q >= 0) {
                    gap[q] = g;
                    at[q] = prev;
                }
            }
            prev = k;
        }
    if (first < 0)
        return 0;
    /* the cut points (the code before each gap), ascending */
    for (int i = 1; i < ng; ++i)
        for (int j = i; j > 0 && at[j - 1] > at[j]; --j) {
            long t = at[j];
            at[j] = at[j - 1];
            at[j - 1] = t;
        }
    int ns = 0;
    long start = first;
    for (int i = 0; i <= ng; ++i) {
        long end = i < ng ? at[i] : prev;
        lo[ns] = start / half_q - 1.0 - 1e-12;
        hi[ns] = end / half_q - 1.0 + 1e-12;
        ++ns;
        if (i < ng) { /* the next set code after the cut */
            long k = end + 1;
            while (!((cs->bits[k >> 6] >> (k & 63)) & 1))
                ++k;
            start = k;
        }
    }
    return ns;
}

/* The count of distinct entry values of a list (value codes). */
static size_t distinct_values(sol_nm_couple *cs, const sol_nm_pair *list, size_t count, const double (*pal)[8],
                              double half_q)
{
    memset(cs->bits, 0, sizeof cs->bits);
    for (size_t i = 0; i < count; ++i)
        for (int e = 0; e < 8; ++e) {
            long k = value_code(pal[list[i].pair][e], half_q);
            cs->bits[k >> 6] |= UINT64_C(1) << (k & 63);
        }
    size_t d = 0;
    for (int w = 0; w < COUPLE_CODES / 64; ++w)
        d += (size_t)__builtin_popcountll(cs->bits[w]);
    return d;
}

/* The pixels' normals with channel c first: (x, y, z) = (n_c, n_(1-c), nz), and per pixel the
 * critical points' ratios (see code_cosines). */
typedef struct couple_pixels {
    double x[16], y[16], z[16], q[16], yq[16], yx[16];
} couple_pixels;

static void couple_pixels_init(couple_pixels *px, const double n[16][3], int c)
{
    for (int p = 0; p < 16; ++p) {
        px->x[p] = n[p][c];
        px->y[p] = n[p][1 - c];
        px->z[p] = n[p][2];
        px->q[p] = hypot(px->y[p], px->z[p]);
        px->yq[p] = px->z[p] > 0.0 && px->q[p] > 0.0 ? px->y[p] / px->q[p] : NAN;
        px->yx[p] = px->x[p] != 0.0 ? px->y[p] / px->x[p] : NAN;
    }
}

static inline int in_spans(double b, const double *lo, const double *hi, int ns)
{
    for (int k = 0; k < ns; ++k)
        if (b >= lo[k] && b <= hi[k])
            return 1;
    return 0;
}

/* out[p] >= the largest cosine to pixel p of the decodes (a, b), b in the union of the spans: the
 * largest of g_p at the spans' ends, at +-s inside a span (where the decode starts to clamp) and at
 * g_p's critical points inside a span (see sol_nm_couple_cosine), raised by the slack. The decode's
 * direction at b depends on a and b only, so the ends cost a root each for all 16 pixels. */
static void code_cosines(double a, const couple_pixels *px, const double *lo, const double *hi, int ns,
                         double out[16])
{
    double s2 = 1.0 - a * a, s = s2 > 0.0 ? sqrt(s2) : 0.0, best[16];
    for (int p = 0; p < 16; ++p)
        best[p] = -INFINITY;
    double pts[2 * COUPLE_SPANS + 2];
    int np = 0;
    for (int k = 0; k < ns; ++k) {
        pts[np++] = lo[k];
        pts[np++] = hi[k];
    }
    if (in_spans(s, lo, hi, ns))
        pts[np++] = s;
    if (in_spans(-s, lo, hi, ns))
        pts[np++] = -s;
    for (int k = 0; k < np; ++k) {
        double b = pts[k], r = a * a + b * b, z = r < 1.0 ? sqrt(1.0 - r) : 0.0, w = r > 1.0 ? 1.0 / sqrt(r) : 1.0;
        for (int p = 0; p < 16; ++p) {
            double v = (a * px->x[p] + b * px->y[p] + z * px->z[p]) * w;
            best[p] = v > best[p] ? v : best[p];
        }
    }
    for (int p = 0; p < 16; ++p) {
        double b = s * px->yq[p]; /* unclamped piece: NAN unless nz > 0 */
        if (b == b && in_spans(b, lo, hi, ns)) {
            double v = a * px->x[p] + s * px->q[p];
            best[p] = v > best[p] ? v : best[p];
        }
        b = a * px->yx[p]; /* clamped pieces */
        if (b == b && b * b >= s2 && in_spans(b, lo, hi, ns)) {
            double v = (a * px->x[p] + b * px->y[p]) / sqrt(a * a + b * b);
            best[p] = v > best[p] ? v : best[p];
        }
        out[p] = best[p] + 1e-7;
    }
}

void sol_nm_couple_cosines(double a, const double n[16][3], int c, const double *lo, const double *hi, int ns,
                           double out[16])
{
    couple_pixels px;
    couple_pixels_init(&px, n, c);
    code_cosines(a, &px, lo, hi, ns, out);
}

/* Drops the pairs of list (channel c) whose coupled row bound against the spans reaches margin. */
static size_t row_filter(sol_nm_couple *cs, const couple_pixels *px, int use_max, double margin,
                         const double (*pal)[8], double half_q, sol_nm_pair *list, size_t count,
                         const double lo[COUPLE_SPANS], const double hi[COUPLE_SPANS], int ns, uint64_t *work)
{
    next_generation(cs);
    size_t kept = 0;
    for (size_t i = 0; i < count; ++i) {
        const double *a = pal[list[i].pair];
        float row[16];
        for (int e = 0; e < 8; ++e) {
            int stale;
            float *t = entry_row(cs, a[e], half_q, &stale);
            if (stale) {
                *work += 16 * ns;
                double cs16[16];
                code_cosines(a[e], px, lo, hi, ns, cs16);
                for (int p = 0; p < 16; ++p) {
                    double best = cs16[p];
                    double ang = acos(best < 1.0 ? best : 1.0) * (1.0 - 1e-12);
                    double e2 = ang * ang;
                    float f = (float)e2;
                    if ((double)f > e2)
                        f = nextafterf(f, 0.0f);
                    t[p] = f;
                }
            }
            for (int p = 0; p < 16; ++p)
                row[p] = e ? (t[p] < row[p] ? t[p] : row[p]) : t[p];
        }
        *work += 16;
        double s = fold_row(row, use_max);
        if (s < margin)
            list[kept++] = list[i];
    }
    return kept;
}

void sol_nm_couple_reduce(sol_nm_couple *cs, const double n[16][3], int use_max, double margin,
                          const double (*pal)[8], sol_bc4_precision precision, sol_nm_pair *xl, size_t *nx,
                          sol_nm_pair *yl, size_t *ny, uint64_t *work)
{
    const double half_q = precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5;
    /* per channel: the other list's count and span count at its last pass. The lists only shrink, so
     * the same count is the same list, the same spans and the same rows: the pass would keep every
     * pair (they all passed it). It is then skipped and its work charged as it would be: the other
     * list's spans, 16 ns per distinct value of the list and 16 per pair (issue 13: the round after
     * one that dropped nothing on one side repeated its passes). */
    size_t last_other[2] = {SIZE_MAX, SIZE_MAX};
    int last_ns[2] = {0, 0};
    for (int round = 0; round < 3; ++round) {
        size_t before = *nx + *ny;
        for (int c = 1; c >= 0; --c) {
            size_t *count = c ? ny : nx, other = c ? *nx : *ny;
            *work += 8 * other;
            if (other == last_other[c]) {
                *work += 16 * (uint64_t)last_ns[c] * distinct_values(cs, c ? yl : xl, *count, pal, half_q) + 16 * *count;
                continue;
            }
            double lo[COUPLE_SPANS], hi[COUPLE_SPANS];
            int ns = list_spans(cs, c ? xl : yl, other, pal, half_q, lo, hi);
            if (ns == 0) {
                *nx = *ny = 0;
                return;
            }
            last_other[c] = other;
            last_ns[c] = ns;
            couple_pixels px;
            couple_pixels_init(&px, n, c);
            *count = row_filter(cs, &px, use_max, margin, pal, half_q, c ? yl : xl, *count, lo, hi, ns, work);
        }
        if (*nx + *ny == before || *nx == 0 || *ny == 0)
            break;
    }
}

/* ---- incumbents by coordinate descent ---- */

/* The position in list (channel c) of the pair whose palette best serves the pixels together with
 * palette b of the other channel: least sum (or max) over pixels of the least angle^2 of the 64
 * decodes, computed through cosines (a heuristic: the caller evaluates the candidate exactly). */
static size_t best_partner(sol_nm_couple *cs, const double n[16][3], int c, int use_max, const double b[8],
                           const double (*pal)[8], double half_q, const sol_nm_pair *list, size_t count,
                           uint64_t *work)
{
    next_generation(cs);
    size_t arg = 0;
    double least = INFINITY;
    for (size_t i = 0; i < count; ++i) {
        const double *a = pal[list[i].pair];
        float row[16];
        for (int e = 0; e < 8; ++e) {
            int stale;
            float *t = entry_row(cs, a[e], half_q, &stale);
            if (stale) {
                *work += 64;
                /* the 8 decodes (a_e, b_j): z (0 where clamped) and the norm divided by (1 unless
                 * clamped) depend on the entries only, so once for the 16 pixels; each cosine is then
                 * the same expression of the same doubles as written per pixel (a clamped decode's
                 * 0 * nz adds a zero), so the same bits */
                double zj[8], dj[8];
                for (int j = 0; j < 8; ++j) {
                    double r = a[e] * a[e] + b[j] * b[j], zz = 1.0 - r;
                    zj[j] = zz > 0.0 ? sqrt(zz) : 0.0;
                    dj[j] = r > 1.0 ? sqrt(r) : 1.0;
                }
                for (int p = 0; p < 16; ++p) {
                    const double m[3] = {n[p][c], n[p][1 - c], n[p][2]};
                    double best = -INFINITY;
                    for (int j = 0; j < 8; ++j) {
                        double v = (a[e] * m[0] + b[j] * m[1] + zj[j] * m[2]) / dj[j];
                        best = v > best ? v : best;
                    }
                    double ang = acos(best < 1.0 ? best : 1.0);
                    t[p] = (float)(ang * ang);
                }
            }
            for (int p = 0; p < 16; ++p)
                row[p] = e ? (t[p] < row[p] ? t[p] : row[p]) : t[p];
        }
        *work += 16;
        double s = fold_row(row, use_max);
        if (s < least) {
            least = s;
            arg = i;
        }
    }
    return arg;
}

/* The last best_partner call of one channel: its partner pair, answer and work. */
typedef struct {
    int partner, result;
    uint64_t work;
} partner_memo;

/* best_partner for channel c against partner pair `partner`, through that channel's memo.
 * best_partner is a function of the partner pair (the lists are fixed during a descent), so a call
 * repeating the last one of its channel takes that one's answer and charges its work again (the same
 * work as calling it: each call starts a new generation, so it meets the same values and pairs). A
 * descent that settles repeats its last step before it stops (issue 13: a third of its calls). */
static int memo_partner(partner_memo *m, sol_nm_couple *cs, const double n[16][3], int c, int use_max,
                        int partner, const double (*pal)[8], double half_q, const sol_nm_pair *list,
                        size_t count, uint64_t *work)
{
    if (m->partner != partner) {
        uint64_t w0 = *work;
        m->result = list[best_partner(cs, n, c, use_max, pal[partner], pal, half_q, list, count, work)].pair;
        m->partner = partner;
        m->work = *work - w0;
    } else {
        *work += m->work;
    }
    return m->result;
}

int sol_nm_couple_descent(sol_nm_couple *cs, const double n[16][3], int use_max, const double (*pal)[8],
                          sol_bc4_precision precision, const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl,
                          size_t ny, int start_x, int out[][2], uint64_t *work)
{
    const double half_q = precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5;
    int cnt = 0, x = start_x, y = -1;
    partner_memo memo[2] = {{-1, 0, 0}, {-1, 0, 0}};
    for (int step = 0; step < 4 && nx && ny; ++step) {
        int yn = memo_partner(&memo[1], cs, n, 1, use_max, x, pal, half_q, yl, ny, work);
        int xn = memo_partner(&memo[0], cs, n, 0, use_max, yn, pal, half_q, xl, nx, work);
        if (xn == x && yn == y)
            break;
        x = xn;
        y = yn;
        out[cnt][0] = x;
        out[cnt][1] = y;
        ++cnt;
    }
    return cnt;
}

