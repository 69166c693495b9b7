/* normalmaps_internal.h - what the files of src/normalmaps share (not part of the public API). */
#ifndef SOL_NORMALMAPS_INTERNAL_H
#define SOL_NORMALMAPS_INTERNAL_H

#include "sol_normalmaps.h"
#include <math.h>

#include <math.h>

/* Palette of every ordered anchor pair in DECODED units (2 v - 1, in [-1, 1]): table[e0 << 8 | e1].
 * Built once per precision (thread-safe); precision must be valid. */
const double (*sol_nm_palettes(sol_bc4_precision precision))[8];

/* One anchor pair and its per-channel bound score. */
typedef struct sol_nm_pair {
    double score;
    uint16_t pair; /* e0 << 8 | e1 */
} sol_nm_pair;

/* Per-channel scoring of anchor pairs against 16 target components t (decoded units).
 * term_p = min_k (pal_k - t_p)^2 (tight) or, for the pixels whose bit is set in `loose`, the squared distance of t_p to the
 * nearest interval [pal_k / sqrt(1 + pal_k^2), pal_k] (x of a decoded normal whose z was clamped to
 * 0 lies there: pal_k / r with 1 < r = sqrt(pal_k^2 + b^2) <= sqrt(1 + pal_k^2)), times a per-pixel
 * weight plus an offset (1 and 0 unless set). score = sum_p term_p, or max_p term_p when `use_max`. */
typedef struct sol_nm_channel {
    double t[16];
    int order[16]; /* pixels visited extremes first, so early exits come early */
    const double (*palettes)[8];
    sol_bc4_precision precision;
    int use_max;
    uint16_t loose; /* bit p: pixel p takes the loose term */
    uint8_t e0_lo, e0_hi, e1_lo, e1_hi;
    /* loose pixels: term_p = loose_off[p] + loose_w[p] * (loose distance)^2 (init: 0 and 1; set by
     * sol_nm_channel_rim_weight for pixels pointing away, see bc5.c) */
    double loose_w[16], loose_off[16];
    double loose_reach[16]; /* |t| / sqrt(1 - t^2): the largest |entry| whose loose interval holds t */
} sol_nm_channel;

void sol_nm_channel_init(sol_nm_channel *ch, const double t[16], sol_bc4_precision precision, int use_max,
                         unsigned loose, uint8_t e0_lo, uint8_t e0_hi, uint8_t e1_lo, uint8_t e1_hi);
/* The reference pixel order of sol_nm_channel_init (ch->order): smallest, largest, then by decreasing
 * |t - mean| (ties: lower pixel first). */
void sol_nm_reference_order(const double t[16], int order[16]);
/* The loose distance^2 of t to palette pal alone (the unweighted loose term above). */
double sol_nm_loose_term(const double pal[8], double t);
/* Gives loose pixel p the term offset + weight * (loose distance)^2 (weight, offset >= 0). */
void sol_nm_channel_rim_weight(sol_nm_channel *ch, int p, double weight, double offset);
/* The pair of least score in the ranges (first in e0-major order on ties); *score receives it. */
int sol_nm_channel_argmin(const sol_nm_channel *ch, double *score);
/* Every pair in the ranges with score <= budget, in e0-major order; returns the count.
 * out holds at least (e0_hi - e0_lo + 1) (e1_hi - e1_lo + 1) entries. */
size_t sol_nm_channel_collect(const sol_nm_channel *ch, double budget, sol_nm_pair *out);
/* The enumeration's mask of high anchors (anchor_bounds.c, for the tests): bit H of out (H in
 * [hmin, hmax]) set when the palette of low anchor low and high anchor H, divisions = 7 (8-value
 * mode) or 5 (6-value mode, six_value = 1: -1 and +1 count too), has a lattice entry
 * A(low) + (k / divisions) (A(H) - A(low)), k = 0..divisions, within r of t (a superset: the interval
 * ends are widened by 1e-6 code; NaN ends give the whole range). simd = 0: the scalar form, 1: the
 * AVX2 form where the processor has it (bit-identical). */
void sol_nm_reachable_mask(int simd, double t, int low, int divisions, int six_value, double r, int hmin, int hmax,
                           uint64_t out[4]);
/* The enumeration's span mask (anchor_bounds.c, for the tests): bit d of out set unless every pair
 * of span d = H - L in the mode (six_value: 6-value, e0 <= e1; else 8-value) scores above tb against
 * the targets t (sum metric, every pixel tight) by the span bound of sol_nm_span_bounds; every bit
 * in 6-value mode when a target lies within sqrt(tb) of -1 or +1. */
void sol_nm_span_mask(const double t[16], int six_value, sol_bc4_precision precision, double tb, uint64_t out[4]);

/* The exact least-squares BC4 pair over all 65536 ordered pairs (bc4_common.c): the same pair and
 * score as sol_nm_channel_argmin on the full range with use_max = 0 and no loose pixels (least
 * score, then least e0 << 8 | e1), by branch and bound over boxes of anchor codes. */
int sol_nm_bc4_common(const double t[16], sol_bc4_precision precision, double *score);
/* The palette of pair = e0 << 8 | e1 as the common search computes it (bc4_common.c: from two 26 KB
 * tables of the anchors' and interpolants' values instead of the 4 MB table): its row of
 * sol_nm_palettes(precision), bit for bit. */
void sol_nm_small_palette(sol_bc4_precision precision, int pair, double out[8]);
/* Lower bounds (bc4_span_bound.c), for SOL_NM_SPAN_BOUND_LANES steps at once, of sum_p min_j
 * (e_j - t_p)^2 over every palette whose lattice entries e_j lie within delta of a lattice phi + step
 * Z (any phase phi; the ends and fixed entries ignored): the least circular sum of squares of the
 * targets modulo step, computed in single precision, less an allowance for that rounding. sorted:
 * the 16 targets in ascending order; out[k] = 0 when step[k] <= 0, and INFINITY when the bound is
 * above limit (then it is not computed: the search only compares it with limit; limit = INFINITY
 * gives every bound). */
#define SOL_NM_SPAN_LANES 4
#define SOL_NM_SPAN_BOUND_LANES 8
void sol_nm_span_bounds(const double sorted[16], const double step[SOL_NM_SPAN_BOUND_LANES], double delta,
                        double limit, double out[SOL_NM_SPAN_BOUND_LANES]);
/* The 16 values in ascending order, by a branch-free sorting network (bc4_span_bound.c; equal values,
 * -0 and +0 among them, in either order). */
void sol_nm_sort16(const double in[16], double out[16]);
/* The same bounds for step[0 .. n), into out[0 .. n): 16 lanes at a time where the processor has
 * AVX-512, else 8 (the same values either way). step and out hold n rounded up to a multiple of 16,
 * the steps past n 0 (their lanes answer 0). */
void sol_nm_span_bounds_all(const double sorted[16], const double *step, int n, double delta, double limit,
                            double *out);
/* The same bound at one phase (bc4_span_bound.c): for a span's step, the 16 cut sequences of the
 * targets' phases (v: sum of squares about the mean, mean: relative to base = the least target), of
 * which n are kept; floor: at most every dropped cut's v (INFINITY: none dropped; 0: no bound).
 * sol_nm_span_cuts4 fills four (a lane of step <= 0 gives the bound 0); sol_nm_span_cuts_keep drops
 * the cuts whose v exceeds limit (any limit: the bound stays valid); sol_nm_span_phase_bound is a
 * lower bound of sum_p min_j (e_j - t_p)^2 over every palette whose lattice entries lie within delta
 * of phase + step Z (the ends and fixed entries ignored): a pair (L, L + span) at phase A(L). */
typedef struct sol_nm_span_cuts {
    double step, inv, base, floor, slack;
    int n;
    double v[16], mean[16];
} sol_nm_span_cuts;
/* The part of the bound before the decoder rounding: at most min_c [v_c + 16 cd(mean_c - psi)^2]
 * with psi = phase - base and cd the distance to the nearest multiple of step, less the rounding of
 * the cut sums (slack) and of the phases (1e-14 on cd); the bound is F - 8 delta sqrt(F). Inline: the
 * search calls it for every low anchor of a span it visits. */
static inline double sol_nm_span_phase_f(const sol_nm_span_cuts *cu, double phase)
{
    const double s = cu->step, psi = phase - cu->base;
    double f = cu->floor;
    for (int c = 0; c < cu->n; ++c) {
        double x = cu->mean[c] - psi;
        /* x - s round(x / s), round to nearest by the 1.5 2^52 addition (|x / s| < 2^51) */
        double m = (x * cu->inv + 0x1.8p52) - 0x1.8p52;
        double cd = fabs(x - s * m) - 1e-14;
        cd = cd > 0.0 ? cd : 0.0;
        double v = cu->v[c] + 16.0 * cd * cd;
        f = v < f ? v : f;
    }
    return f - cu->slack;
}
void sol_nm_span_cuts4(const double sorted[16], const double step[SOL_NM_SPAN_LANES],
                       sol_nm_span_cuts out[SOL_NM_SPAN_LANES]);
void sol_nm_span_cuts_keep(sol_nm_span_cuts *cu, double limit);
/* sol_nm_span_phase_f (below) at the phases A(l) = 2 l / 255 - 1, l = l1 .. l1 + count - 1 (count <=
 * 256), into out[0 .. count): the same values, computed four (AVX-512: eight) at a time. */
void sol_nm_span_phase_fs(const sol_nm_span_cuts *cu, int l1, int count, double out[256]);
double sol_nm_span_phase_bound(const sol_nm_span_cuts *cu, double delta, double phase);
/* Every palette entry of the 65536 pairs indexed by value (bc4_entries.c): value[0..count) the
 * distinct decoded entries, ascending; the pairs holding value[i] are pair[start[i] .. start[i+1]),
 * ascending, and gap[j] is at most the distance from value[i] to the nearest other entry of pair[j]
 * (INFINITY if it has none). */
typedef struct sol_nm_entry_index {
    size_t count;
    const double *value;
    const uint32_t *start;
    const uint16_t *pair;
    const float *gap;
} sol_nm_entry_index;
/* The index of a precision (valid), built once on first use (thread-safe); NULL if out of memory. */
const sol_nm_entry_index *sol_nm_entry_index_get(sol_bc4_precision precision);
/* The first value of that index above x (its count if none; 0 if the index cannot be built), as the
 * common search finds it (bc4_common.c, from a table of bucket edges; for the tests). */
size_t sol_nm_entry_first_above(sol_bc4_precision precision, double x);
/* The BC4 encoders' input check and mapping: UNORM values in [0, 1] to targets t = 2 v - 1 in the
 * decoded units; SOL_ERR_NONFINITE or SOL_ERR_OUT_OF_RANGE (t partly written) otherwise. */
sol_status sol_nm_bc4_targets(const double values[16], double t[16]);

/* Index of the palette entry nearest to t (the first on ties): BC4's per-value index choice. */
int sol_nm_nearest_index(const double pal[8], double t);
/* sol_nm_nearest_index of each of the 16 targets, by the fast encoder's branch-free scan (bc4_fast.c:
 * the same entries for every target, AVX2 or SSE2 where the processor has them; issue 13: the
 * common encoder's 32 scalar scans per block were 5% of its time). */
void sol_nm_nearest_indices(const double pal[8], const double t[16], uint8_t index[16]);

/* The fast BC4 encoder (bc4_fast.c) on targets in decoded units [-1, 1]. */
void sol_nm_bc4_fast(const double t[16], sol_bc4_block *out);
/* The same with the nearest-entry scan chosen: 0 the widest the processor runs (what sol_nm_bc4_fast
 * uses), 1 scalar, 2 SSE2, 3 AVX2 (each falls back to the next narrower one where it is not
 * available). Every path gives the same block; the tests compare them. */
void sol_nm_bc4_fast_path(const double t[16], int path, sol_bc4_block *out);
/* The fast encoder's anchor codes: lo / hi the least and largest code of the 16 targets (the 8-value
 * pair is hi, lo when hi > lo), lo6 / hi6 those of the codes other than 0 and 255 (the 6-value pair;
 * both lo when every code is 0 or 255). Codes: lrint((t + 1) 127.5) clamped to 0..255. Also the
 * common encoder's first incumbents (bc4_common.c). */
void sol_nm_bc4_fast_anchors(const double t[16], int *lo, int *hi, int *lo6, int *hi6);

/* Nonzero: the BC5 searches use their scalar forms even where the AVX2 forms could run (bc5.c; the
 * results are bit-identical either way, the tests compare them). Zero (the default) otherwise. */
extern int sol_nm_simd_disable;

/* The channel side of palette pal against targets t (bc5_side.c; bc5.c's exact search and bc5_window.c's window
 * search): for pixel k, v[k stride] the first nearest entry's value, m1[k stride] its squared
 * distance, m2[k stride] the least squared distance of an entry of another value (INFINITY if none),
 * in one pass over the entries (proof in bc5_side.c). The AVX2
 * form needs a CPU with AVX2 (the caller checks); the scalar form is its reference. */
void sol_nm_channel_side_scalar(const double pal[8], const double t[16], double *v, double *m1, double *m2,
                               size_t stride);
void sol_nm_channel_side_avx2(const double pal[8], const double t[16], double *v, double *m1, double *m2,
                             size_t stride);

/* At least the largest cosine between unit n (nz < 0: a pixel pointing away) and the 64 decodes
 * (a_i, b_j, z rebuilt or clamped) of x palette a and y palette b, less than 1e-15 above it
 * (bc5_away.c): the coupled bound of pixels pointing away. Bit-identical in its scalar and AVX2
 * forms (sol_nm_simd_disable picks scalar). */
double sol_nm_away_cosine(const double a[8], const double b[8], const double n[3]);
/* A cheaper, looser form (bc5_away.c): at least the largest (a_i nx + b_j ny) / max(1, |(a_i, b_j)|)
 * (the z term, <= 0 for nz < 0, dropped; no roots per decode), less than 1e-15 above it. */
double sol_nm_away_cosine_rim(const double a[8], const double b[8], const double n[3]);
/* The coupled row bounds of the exact search (bc5_couple.c; scratch from sol_nm_couple_new, NULL if
 * out of memory). sol_nm_couple_cosines: out[p] >= the largest cosine between n[p] and any decode
 * (a, b) (channel c holds a: c = 1 swaps the decode's components) with b in one of the ns <= 8
 * intervals [lo[k], hi[k]]. sol_nm_couple_reduce: drops from both lists (order kept) the pairs whose
 * every candidate with the other list has objective (internal units: sum or max of dN^2) >= margin.
 * sol_nm_couple_descent: up to 4 candidates (x pair, y pair) by alternating best partners from x
 * pair start_x, for the caller to evaluate; returns their count. */
typedef struct sol_nm_couple sol_nm_couple;
sol_nm_couple *sol_nm_couple_new(void);
void sol_nm_couple_free(sol_nm_couple *cs);
void sol_nm_couple_cosines(double a, const double n[16][3], int c, const double *lo, const double *hi, int ns,
                           double out[16]);
void sol_nm_couple_reduce(sol_nm_couple *cs, const double n[16][3], int use_max, double margin,
                          const double (*pal)[8], sol_bc4_precision precision, sol_nm_pair *xl, size_t *nx,
                          sol_nm_pair *yl, size_t *ny, uint64_t *work);
int sol_nm_couple_descent(sol_nm_couple *cs, const double n[16][3], int use_max, const double (*pal)[8],
                          sol_bc4_precision precision, const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl,
                          size_t ny, int start_x, int out[][2], uint64_t *work);
/* The exact search's objectives (bc5.c) for blocks whose pixels repeat normals: group[p] is the first
 * pixel q <= p whose normal is bit-identical to n[p]. sol_nm_bc5_joint_objective_grouped equals
 * sol_nm_bc5_joint_objective(a, b, n, use_max, budget, NULL, NULL) and
 * sol_nm_bc5_joint_objective_lower_grouped equals sol_nm_bc5_joint_objective_lower(a, b, n, order,
 * away_off, use_max, best, budget, work), bit for bit (work counted alike), computing each group's
 * term once. a, b: the 8 decoded palette values of each channel; order: a permutation of 0..15;
 * away_off: per visiting position, equal for equal normals. */
double sol_nm_bc5_joint_objective_grouped(const double a[8], const double b[8], const double n[16][3],
                                          const int group[16], int use_max, double budget);
double sol_nm_bc5_joint_objective_lower_grouped(const double a[8], const double b[8], const double n[16][3],
                                                const int group[16], const int order[16],
                                                const double away_off[16], int use_max, double best, double budget,
                                                uint64_t *work);
double sol_nm_bc5_joint_objective(const double a[8], const double b[8], const double n[16][3], int use_max,
                                  double budget, uint8_t *ix, uint8_t *iy);
double sol_nm_bc5_joint_objective_lower(const double a[8], const double b[8], const double n[16][3],
                                        const int order[16], const double away_off[16], int use_max, double best,
                                        double budget, uint64_t *work);
/* The exact search's sort of an anchor-pair list (bc5.c): list[0..count) in increasing (score, pair),
 * the order qsort gives with score first and the pair's code breaking ties (pairs distinct). tmp:
 * count elements of scratch, or NULL (then qsort itself). Radix passes from 1024 pairs, a merge sort
 * below; qsort for a negative or NaN score. A score of -0 is stored as +0. */
void sol_nm_bc5_sort_pairs(sol_nm_pair *list, size_t count, sol_nm_pair *tmp);
/* The exact search's pair screen (bc5.c) on one candidate, for the tests: 1 if it rules out the x pair
 * pair_x with the y pair pair_y (e0 << 8 | e1) at incumbent best (their objective, sum or max of dN^2,
 * is then at least best), 0 if it lets the candidate through, -1 if out of memory. screen: the
 * screen's tables (~13 MB) from sol_nm_screen_new, reused across calls (freed by sol_nm_screen_free),
 * or NULL: allocated and freed inside the call. */
typedef struct sol_nm_screen sol_nm_screen;
sol_nm_screen *sol_nm_screen_new(void);
void sol_nm_screen_free(sol_nm_screen *screen);
int sol_nm_screen_rules_out(sol_nm_screen *screen, const double n[16][3], int use_max, double best,
                            sol_bc4_precision precision, int pair_x, int pair_y);
/* The exact search's pixel floor (bc5.c, max metric) on one candidate's values, for the tests: per
 * pixel p (0..15) of unit normals n, out[p] = 1 if every decode (a, b) of x pair pair_x's values a and
 * y pair pair_y's values b gives pixel p a squared angle >= best[p], computed as the objective
 * computes a pixel's term (so the test is exact to the last bit); 0 if one decode is below best[p], or
 * if the pixel's ball at best[p] constrains nothing (a budget near (pi / 2)^2 or above, or
 * n = (0, 0, -1)). Returns 0, or -1 if out of memory (out untouched). */
int sol_nm_floor_rules_out(const double n[16][3], const double best[16], sol_bc4_precision precision, int pair_x,
                           int pair_y, int out[16]);
/* The adaptive encoder's threshold level of an objective err (sum of dN^2, or max dN^2 when
 * use_max): the RMS angle sqrt(err / 16) (or the max angle sqrt(err)) in degrees. The block is
 * searched when it exceeds options.threshold_deg. Monotone in err. */
static inline double sol_nm_threshold_level(double err, int use_max)
{
    return (use_max ? sqrt(err) : sqrt(err / 16.0)) * (180.0 / M_PI);
}
/* The adaptive encoder's threshold test (bc5_adaptive.c) of block b (palettes palx, paly of its
 * anchors, decoded units) against unit normals t (t[c][p]: component c of pixel p) from chord
 * bounds of the angles, without atan2: 0 if the exact objective's level is <= threshold_deg, 1 if
 * it is above, -1 if the bounds cannot tell (then compute the exact objective). Never contradicts
 * the exact test. */
int sol_nm_threshold_test(const double palx[8], const double paly[8], const sol_bc5_block *b, const double t[3][16],
                          int use_max, double threshold_deg);
/* The chord bounds of sol_nm_threshold_test: lower <= the exact objective (sum of dN^2, or max of dN^2
 * when use_max, as bc5.c computes it) <= upper, for block b's own indices. */
void sol_nm_chord_bounds(const double palx[8], const double paly[8], const sol_bc5_block *b, const double t[3][16],
                         int use_max, double *lower, double *upper);
/* sol_nm_threshold_test's decision from bounds lower <= err <= upper of a block's objective: 0 if
 * level(err) <= threshold_deg (keep the base), 1 if above (search), -1 if the bounds cannot tell. */
int sol_nm_threshold_decide(double lower, double upper, int use_max, double threshold_deg);
/* The adaptive encoder's gap bound (bc5_adaptive.c; proof at sol_bc5_options.gap): from the two
 * channels' least-squares sums sx, sy (sol_nm_bc4_common), the unit normals t (t[2][p] = nz_p) and a
 * cap (any value; the encoder passes the base block's upper chord bound), a value at most the
 * computed objective (internal units: sum, or max when use_max, of dN^2) of EVERY block with any
 * anchors and indices: the larger of min(sx + sy, min_p nz_p^2) ((sx + sy) / 16 for the max) and,
 * when every nz_p > 0, the tilt bound min(B, T) (B / 16 for the max), T = min(cap, min_p nz_p^2),
 * B = the largest of sx + sy, (1 + alpha) sx + (1 - beta) sy and the same with x and y swapped
 * (alpha, beta from the pixels' least and largest |nx|, |ny| and nz); lowered for rounding. */
double sol_nm_gap_bound(double sx, double sy, const double t[3][16], int use_max, double cap);
/* The gap test from bounds lower <= err <= upper of a block's objective: 0 if err <= limit (skip),
 * 1 if err > limit (search), -1 if the bounds cannot tell. */
int sol_nm_gap_test(double lower, double upper, double limit);
/* The unit normals of block (bx, by) of a 3-channel image whose pixels sol_nm_unit_normals accepts,
 * bit for bit as it computes them (the same length and quotients; a finite non-zero float pixel
 * never takes its rescaling path), as n[p][c] and again as t[c][p]. */
void sol_nm_unit_pixels(const sol_image *img, int bx, int by, double n[16][3], double t[3][16]);

/* Validates and normalises 16 source normals. */
sol_status sol_nm_unit_normals(const double in[16][3], double out[16][3]);

#endif
