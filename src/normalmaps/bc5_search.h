/* bc5_search.h - what the exact 3Dc search (bc5.c) shares with its adaptive window path
 * (bc5_window.c): the SIMD switch and rounding slack, the search's request and workspace, the
 * objective's inline kernels (fold, decode, chord bounds), the channel keys and pair classes, and the
 * definitions of bc5.c that the window calls (sol_nm_bc5_*, documented at their definitions).
 * Internal to the normalmaps module's BC5 files. */
#ifndef SOL_BC5_SEARCH_H
#define SOL_BC5_SEARCH_H

#include "normalmaps_internal.h"

#include <math.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Relative slack on lower bounds: the bounds hold exactly in real arithmetic; the slack covers
 * rounding so that no candidate better than the incumbent is ever pruned. */
#define BOUND_SLACK 1e-9

/* The per-candidate helpers of the searches (channel sides, the quick bound, the window's pair
 * scores) also have an AVX2 form, 4 pixels per instruction, picked at run time on x86-64 CPUs that
 * have it: per pixel the same IEEE operations in the same order (sub, mul, add, sqrt are correctly
 * rounded in either form; min/max and the comparisons select exactly as the scalar ternaries; no FMA),
 * and sums over pixels still taken one pixel at a time in the reference order, so the results are
 * bit-identical to the scalar form (the tests run both). */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#include <immintrin.h>
#define SEARCH_AVX2 1
#define AVX2_FN __attribute__((target("avx2")))
/* 1 when the AVX2 forms may run: the CPU has AVX2 and sol_nm_simd_disable has not been set. */
static inline int search_avx2(void)
{
    return !sol_nm_simd_disable && __builtin_cpu_supports("avx2");
}
#else
#define SEARCH_AVX2 0
static inline int search_avx2(void)
{
    return 0;
}
#endif

/* ---- the quick per-candidate bound ----
 *
 * sol_nm_bc5_joint_objective_lower finds each pixel's jointly best index pair (an 8 x 8 search): exact, but most
 * of the search's time on rough blocks. The quick bound needs per pixel only what each channel's
 * palette gives alone, precomputed once per anchor pair (channel_side): the nearest entry's value v,
 * its squared distance m1 and the least squared distance m2 of an entry of ANOTHER value. The decode
 * of the two nearest entries (v_x, v_y) has chord^2 c00 (with z); any other index pair (i, j) decodes
 * to a different vector and has, unclamped, chord^2 >= (a_i - nx)^2 + (b_j - ny)^2 >=
 * min(m2_x + m1_y, m1_x + m2_y), and clamped (z = 0) chord^2 >= nz^2. So every pixel's chord^2 is at
 * least min(c00, m2_x + m1_y, m1_x + m2_y, nz^2) whatever pair sol_nm_bc5_best_pixel picks, and dN^2 >= chord^2.
 * It equals the exact per-pixel bound whenever the nearest pair wins clearly, which on smooth and
 * rough blocks alike is most pixels; the survivors go on to sol_nm_bc5_joint_objective_lower. */
typedef struct channel_side {
    double v[16], m1[16], m2[16]; /* per pixel, in the search's visiting order */
    double lt[16];                /* pixels pointing away: k (loose distance of m's component)^2, else 0 */
} channel_side;

typedef struct window_scratch window_scratch;

/* Scratch of one thread, reused across its blocks: the lists of anchor pairs of each channel and
 * a hash table (list positions + 1) for merging equivalent pairs. */
typedef struct search_workspace {
    sol_nm_pair *x, *y;
    uint32_t *slots;     /* 2 * 65536 entries */
    channel_side *yside; /* the y list's channel sides (quick bound), grown on demand */
    size_t yside_cap;
    struct y_item *ybucket; /* the y list's entries by value (y_index), grown on demand */
    uint64_t *ymark;     /* marks of y list positions (coupling filter), grown on demand */
    size_t ybucket_cap, ymark_cap;
    window_scratch *win; /* the adaptive window path's lists (window_search) */
    struct value_set *vset;   /* value-level usability (see there), allocated on demand */
    struct value_mask *vtab; /* VALUE_CODES entries */
    sol_nm_couple *couple;   /* the coupled row bounds' scratch (bc5_couple.c), allocated on demand */
    struct pair_screen *screen; /* the pair screen's tables (see there), allocated on demand */
    struct pixel_floor *floor;  /* the pixel floor's value sets (see there), allocated on demand */
    uint32_t vgen;
    struct key_mask *ktab; /* merge_keyed's per-value masks (VALUE_CODES entries), allocated on demand */
    uint32_t kgen;
    struct pair_key *kkey; /* merge_keyed's keys of the kept pairs, grown on demand */
    size_t kkey_cap;
    sol_nm_pair *sort_tmp; /* sol_nm_bc5_sort_pairs' scratch (65536 pairs), allocated on demand */
} search_workspace;

typedef struct channel_key {
    double t[16];  /* the distinct (target, loose) pixels: equal pixels give equal key parts */
    int loose[16];
    int count;
    double budget; /* T */
} channel_key;

typedef struct pair_classes {
    uint64_t (*hash)(void *ctx, const double pal[8]);
    int (*equal)(void *ctx, const double pa[8], const double pb[8]);
    void *ctx;
    uint64_t *work;
} pair_classes;

/* What sol_nm_bc5_search_unit is asked: range, precision, metric, work bound. */
typedef struct search_request {
    const sol_bc5_range *range;
    sol_bc4_precision precision;
    int use_max;
    uint64_t work_limit;
} search_request;

/* The decoded normal for components a, b: z = sqrt(max(0, 1 - a^2 - b^2)) (talk: z reconstructed). */
/* One pixel's term folded into a block objective: their sum (SOL_BC5_SUM_SQUARED) or their max
 * (SOL_BC5_MAX), the later term kept only if strictly larger. */
static inline double fold_term(double s, double term, int use_max)
{
    return use_max ? (term > s ? term : s) : s + term;
}

/* Folds terms[0 .. n) into *s in order, one work unit each, stopping as soon as *s reaches budget
 * (the quick bounds' early exit); 1 if it stopped there. */
static inline int fold_terms_until(double *s, const double *terms, int n, int use_max, double budget, uint64_t *work)
{
    for (int k = 0; k < n; ++k) {
        ++*work;
        *s = fold_term(*s, terms[k], use_max);
        if (*s >= budget)
            return 1;
    }
    return 0;
}

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

/* A lower bound of the squared angle dN^2 of the decoded (a, b) against unit n, without atan2: the
 * chord c between the unit directions gives dN = 2 asin(c / 2), so dN^2 >= c^2 + c^4 / 12 (all the
 * series' terms are positive). c^2 is computed from components (no 2 - 2 cos cancellation); c is
 * lowered by 1e-6 relative and 1e-15 absolute to cover its rounding and that of sol_angle3's atan2,
 * so the bound stays below the computed angle squared (angle2_lower_bound, below: decode_chord2
 * computes c^2, chord2_angle2_lower the rest). */
static inline double decode_chord2(double a, double b, const double n[3])
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
    return c2;
}

/* angle2_lower_bound's conversion of the squared chord c2 to the dN^2 bound: non-decreasing in c2 (in
 * each branch, and at the switch the asin branch gives (2 asin(c / 2))^2 >= c^2 (1 + c^2 / 12) for the
 * larger c), so it maps a least chord to a bound of every decode's angle. */
static inline double chord2_angle2_lower(double c2)
{
    double c = sqrt(c2) * (1.0 - 1e-6) - 1e-15; /* relative and absolute rounding of c and of dN */
    if (c > 0.2) { /* large angles (rims, pixels pointing away): the series is loose, use dN itself.
                    * There c and the computed angle (atan2 of a cross product and a dot product of
                    * magnitude ~1) carry relative rounding errors of a few 1e-16, so lowering c by a
                    * relative 1e-12 covers them (asin's relative change is at least c's); the closer
                    * bound lets near-ties at the hemisphere bound be rejected without atan2 */
        c = sqrt(c2) * (1.0 - 1e-12);
        double e = 2.0 * asin(c < 2.0 ? 0.5 * c : 1.0);
        return e * e;
    }
    return c > 0.0 ? c * c * (1.0 + c * c / 12.0) : 0.0;
}

static inline double angle2_lower_bound(double a, double b, const double n[3])
{
    return chord2_angle2_lower(decode_chord2(a, b, n));
}

static inline double combine(double sx, double sy, int use_max)
{
    return use_max ? (sx > sy ? sx : sy) : sx + sy;
}

/* ---- equivalent anchor pairs (exact ties decided without enumerating them) ----
 *
 * Within a budget T >= the incumbent, a candidate can only reach the incumbent if every pixel's
 * chosen entry a has (a - t_p)^2 <= T (tight pixels: dN^2 >= chord^2 >= (a - t_p)^2, and a clamped
 * decode has dN^2 >= nz^2 > T) or, on rim pixels, the loose distance of t_p to [a / sqrt 2, a] within
 * sqrt T. Call those entries usable. sol_nm_bc5_best_pixel's choice is the first entry pair of largest cosine in
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

/* The entry sol_nm_bc5_best_pixel seeds a pixel with: the first of least (a - t)^2. */
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

#if SEARCH_AVX2
/* sol_nm_bc5_joint_objective_quick's tight per-pixel terms for pixels k..k+3 (before the away term and the
 * clamp at 0): the square root of a clamped argument, its result selected only where zz > 0, as the
 * scalar branch. Shared by sol_nm_bc5_quick_terms_avx2 and the window's window_quick_avx2. */
static inline AVX2_FN __m256d quick_tight4(const channel_side *xs, const channel_side *ys, const double nz[16], int k)
{
    const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    const __m256d lower = _mm256_set1_pd(1.0 - 3e-6), absolute = _mm256_set1_pd(5e-15);
    __m256d a = _mm256_loadu_pd(xs->v + k), b = _mm256_loadu_pd(ys->v + k), z = _mm256_loadu_pd(nz + k);
    __m256d m1x = _mm256_loadu_pd(xs->m1 + k), m1y = _mm256_loadu_pd(ys->m1 + k);
    __m256d nz2 = _mm256_mul_pd(z, z);
    __m256d lb = _mm256_min_pd(_mm256_add_pd(_mm256_loadu_pd(xs->m2 + k), m1y),
                               _mm256_add_pd(m1x, _mm256_loadu_pd(ys->m2 + k)));
    lb = _mm256_min_pd(nz2, lb);
    __m256d zz = _mm256_sub_pd(_mm256_sub_pd(one, _mm256_mul_pd(a, a)), _mm256_mul_pd(b, b));
    __m256d up = _mm256_cmp_pd(zz, zero, _CMP_GT_OQ);
    __m256d dz = _mm256_sub_pd(_mm256_sqrt_pd(_mm256_and_pd(zz, up)), z);
    __m256d c2 = _mm256_blendv_pd(nz2, _mm256_add_pd(_mm256_add_pd(m1x, m1y), _mm256_mul_pd(dz, dz)), up);
    lb = _mm256_min_pd(c2, lb);
    return _mm256_sub_pd(_mm256_mul_pd(lb, lower), absolute);
}
#endif

/* ---- pixels pointing away (nz < 0) ----
 *
 * A decoded normal u lies on the upper hemisphere (z >= 0). Write the unit source normal as
 * n = (rho m, -h) with m the unit rim direction of its (x, y), rho = sqrt(1 - h^2), h = -nz > 0,
 * and u = (cos e w, sin e) with elevation e >= 0 and rim direction w. Then
 *     cos dN = u . n = rho cos e (w . m) - h sin e <= rho cos e (w . m) = rho (u . m),
 * and u . m = 1 - c^2 / 2 with c = |u - m| the chord from u to the rim point m. So
 *     dN >= H(c^2) = acos(rho (1 - c^2 / 2)),
 * the angle of the closest point of the hemisphere, theta0 = H(0) = atan2(h, rho) = asin(h) (the
 * hemisphere bound), growing with the chord to m. acos(y)^2 is convex on (-1, 1) (its second
 * derivative is 2 (1 - y acos(y) / sqrt(1 - y^2)) / (1 - y^2) > 0, as alpha < tan alpha for
 * y = cos alpha in (0, 1) and trivially for y <= 0), and y is affine in c^2, so H^2 lies above its
 * tangent at 0:
 *     dN^2 >= theta0^2 + k c^2,  k = 2 theta0 H'(0) = theta0 rho / h (= theta0 cot theta0).
 * The chord splits by channel like the rim pixels' loose bound, with m's components as targets:
 * an unclamped decode (a, b, z) has c^2 >= (a - mx)^2 + (b - my)^2, a clamped one (a, b, 0) / r has
 * x component a / r in [a / sqrt(1 + a^2), a] (see sol_nm_loose_term). So each channel's loose term
 * of such a pixel becomes theta0^2 (half of it per channel for the sum metric, all of it for the
 * max) + k (loose distance of mx)^2, instead of the near-zero loose distance of nx: the lists of
 * anchor pairs of a block pointing away shrink from nearly all 65536 pairs to those whose entries
 * can point the decoded rim direction at every m. rho = 0 (n = (0, 0, -1)) gives k = 0: the
 * hemisphere bound (pi / 2)^2 alone. The quick bound uses the same sum per pixel, and every
 * per-candidate bound at least theta0^2. */
typedef struct away_info {
    unsigned mask;       /* bit p: pixel p points away (and is loose) */
    double m[2][16];     /* the rim targets mx, my (the pixel's nx, ny where not away) */
    double w[16];        /* k, lowered by 1e-12 relative (rounding) */
    double off[16];      /* theta0^2, lowered likewise (0 where not away) */
} away_info;

/* bc5.c's definitions the window path shares (see each there). */
void sol_nm_bc5_best_pixel_index(const double a[8], const double b[8], const double n[3], int *bi, int *bj);
double sol_nm_bc5_best_pixel(const double a[8], const double b[8], const double n[3], int *bi, int *bj);
double sol_nm_bc5_joint_objective_lower(const double a[8], const double b[8], const double n[16][3],
                                        const int order[16], const double away_off[16], int use_max, double best,
                                        double budget, uint64_t *work);
double sol_nm_bc5_joint_objective_quick(const channel_side *xs, const channel_side *ys, const double n[16][3],
                                        const int order[16], const double nz[16], const double away_off[16],
                                        int use_max, double budget, uint64_t *work);
double sol_nm_bc5_joint_objective(const double a[8], const double b[8], const double n[16][3], int use_max,
                                  double budget, uint8_t *ix, uint8_t *iy);
void sol_nm_bc5_channel_side_fill(const double pal[8], const double t[16], channel_side *s);
void sol_nm_bc5_channel_side_init(const double pal[8], const double n[16][3], const int order[16], int c,
                                  const away_info *aw, channel_side *s);
double sol_nm_bc5_metric_value(double internal, sol_bc5_metric metric);
uint64_t sol_nm_bc5_work_limit(const sol_bc5_options *o);
void sol_nm_bc5_channel_key_init(channel_key *k, const double t[16], unsigned loose, double budget);
int sol_nm_bc5_pair_key_equal(const channel_key *k, const double pa[8], const double pb[8]);
size_t sol_nm_bc5_merge_classes(sol_nm_pair *list, size_t count, const double (*pal)[8], const pair_classes *pc,
                                uint32_t *slots);
int sol_nm_bc5_key_equal_fn(void *ctx, const double pa[8], const double pb[8]);
size_t sol_nm_bc5_merge_equivalent(sol_nm_pair *list, size_t count, const channel_key *k, const double (*pal)[8],
                                   uint32_t *slots);
void sol_nm_bc5_order_worst_first(const double err[16], int order[16]);
void sol_nm_bc5_search_unit(const double n[16][3], const search_request *rq, search_workspace *ws, sol_bc5_block *out,
                            sol_bc5_info *info);
#if SEARCH_AVX2
AVX2_FN void sol_nm_bc5_quick_terms_avx2(const channel_side *xs, const channel_side *ys, const double nz[16],
                                         const double away_off[16], double e2[16]);
#endif

/* bc5_window.c: the adaptive encoder's window search (see there), and its lists' scratch for a
 * search workspace (zeroed; NULL if out of memory). */
int sol_nm_bc5_window_search(const double n[16][3], const sol_bc5_range *r, int base_x, int base_y, int base_least,
                             double shrink, const search_request *rq, search_workspace *ws, sol_bc5_block *out,
                             sol_bc5_info *info);
window_scratch *sol_nm_bc5_window_scratch_new(void);

#endif
