/* sol_normalmaps.h - BC4 / BC5 (3Dc) block codecs and normal-map encoders (claims T8-T14).
 *
 * Kaplanyan 2010, "3Dc encoder improvements" (talk seed 000, slides "3Dc encoder improvements" and
 * "cont'd"): a BC5 block stores x and y of a normal as two BC4 ("alpha") blocks; z is rebuilt as
 * sqrt(max(0, 1 - x^2 - y^2)). Usual encoders code the two channels independently (T10); the talk
 * proposes choosing the anchor pairs of x and y jointly to minimise the angular error
 * dN = acos(Nc.N / (|Nc||N|)) (T10), by brute force (~3 h per 1024^2 texture on a GPU, T11), and an
 * adaptive encoder that searches a +-4/255 window around the common anchors (T13).
 *
 * BC4 block (D3D10 "BC4_UNORM", the DXT5 alpha block): two 8-bit anchors e0, e1 and sixteen 3-bit
 * indices. The ORDER of the anchors selects the mode:
 *   e0 >  e1: 8-value mode. Palette index 0 = e0, 1 = e1, 2..7 = ((8-i) e0 + (i-1) e1) / 7.
 *   e0 <= e1: 6-value mode. Palette index 0 = e0, 1 = e1, 2..5 = ((6-i) e0 + (i-1) e1) / 5,
 *             index 6 = 0, index 7 = 255.
 * So every ordered pair (e0, e1) of the 65536 is a distinct palette, and a search over all ordered
 * pairs covers both modes. Palette values are in [0,1] (code / 255); a BC5 normal component is
 * 2 v - 1. Pixels are numbered row-major inside the 4x4 block (pixel = 4 row + column).
 *
 * Decoder precision (T9: "interpolants are produced at 16-bit precision on the majority of GPUs"):
 * the interpolated palette entries are rounded to 8 bits (round(num / 7) / 255), to 16 bits
 * (round(num * 257 / 7) / 65535) or kept exact (float). Anchors are exact in all three.
 *
 * Error of a block: each pixel's angle dN (radians) between its source normal and the decoded
 * normal; the block error is sum(dN^2) (SOL_BC5_SUM_SQUARED, default) or max(dN) (SOL_BC5_MAX).
 * For given anchors, every encoder here picks each pixel's (x, y) index pair jointly to minimise
 * that pixel's angle, except the common encoder, which picks the x and y indices independently
 * (nearest component value), as a pair of BC4 encoders does.
 *
 * Source normals are given as (x, y, z), any finite non-zero length (normalised internally); z < 0
 * is accepted but cannot be reproduced (decoded z >= 0). NaN/Inf gives SOL_ERR_NONFINITE, a zero
 * vector SOL_ERR_ZERO_LENGTH. On error no output is written.
 */
#ifndef SOL_NORMALMAPS_H
#define SOL_NORMALMAPS_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- BC4 ---- */

typedef enum sol_bc4_precision {
    SOL_BC4_INTERP_16BIT = 0, /* default: interpolants rounded to 16 bits (Xbox 360, most GPUs) */
    SOL_BC4_INTERP_8BIT,      /* interpolants rounded to 8 bits */
    SOL_BC4_INTERP_FLOAT,     /* interpolants exact (double) */
    SOL_BC4_PRECISION_COUNT
} sol_bc4_precision;

typedef struct sol_bc4_block {
    uint8_t e0, e1;     /* anchors; their order selects the mode (see above) */
    uint8_t index[16];  /* 0..7, pixel = 4 row + column */
} sol_bc4_block;

/* The 8 palette values in [0,1] of anchors (e0, e1) under a decoder precision.
 * SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (unknown precision). */
sol_status sol_bc4_palette(uint8_t e0, uint8_t e1, sol_bc4_precision precision, double out[8]);

/* 8-byte D3D layout: byte 0 = e0, byte 1 = e1, then 48 index bits, little-endian, pixel 0 first.
 * pack: SOL_ERR_INVALID_ARG if an index is > 7. */
sol_status sol_bc4_pack(const sol_bc4_block *block, uint8_t out[8]);
sol_status sol_bc4_unpack(const uint8_t in[8], sol_bc4_block *out);

/* Least-squares BC4 encoder: the anchors (over all 65536 ordered pairs, both modes) and indices
 * minimising sum (v - decoded)^2 for this decoder precision. Exact (branch and bound over boxes of
 * anchor codes from the fast encoder's incumbent, bc4_common.c; equal to the literal brute force in
 * tests). values in [0,1], else SOL_ERR_OUT_OF_RANGE; NaN: SOL_ERR_NONFINITE. squared_error (may
 * be NULL) receives the minimum. Ties (equal sums, the 16 terms added in a fixed pixel order) go to
 * the smallest e0 << 8 | e1; each value takes its nearest entry, the first on ties. */
sol_status sol_bc4_encode_block(const double values[16], sol_bc4_precision precision, sol_bc4_block *out,
                                double *squared_error);

/* The usual fast BC4 encoder (the DXT5 alpha-block encoder of libsquish and NVIDIA Texture Tools'
 * fast path, the talk's "usual" per-channel encoder): anchors at the block's extreme codes, in
 * 8-value mode (e0 = largest, e1 = smallest) or 6-value mode (e0 = smallest, e1 = largest of the
 * values other than 0 and 255, which the mode's fixed entries serve), whichever has the smaller
 * squared error under 8-bit interpolation; each value takes its nearest entry (first on ties).
 * One pass, no anchor search: not least-squares optimal. values in [0,1], else
 * SOL_ERR_OUT_OF_RANGE; NaN/Inf: SOL_ERR_NONFINITE. */
sol_status sol_bc4_encode_block_fast(const double values[16], sol_bc4_block *out);

/* ---- BC5 (3Dc) ---- */

typedef struct sol_bc5_block {
    sol_bc4_block x, y; /* x in the first 8 bytes (red), y in the second (green) */
} sol_bc5_block;

typedef enum sol_bc5_metric {
    SOL_BC5_SUM_SQUARED = 0, /* block error = sum over pixels of dN^2 (rad^2) */
    SOL_BC5_MAX              /* block error = max over pixels of dN (rad) */
} sol_bc5_metric;

typedef enum sol_bc5_encoder {
    SOL_BC5_COMMON = 0, /* x and y as two independent least-squares BC4 blocks (T10 "usual") */
    SOL_BC5_OPTIMAL,    /* joint anchors and indices minimising the block's angular error (T10/T11) */
    SOL_BC5_ADAPTIVE,   /* base (common or fast), then if above the threshold a window search around it (T13) */
    SOL_BC5_FAST        /* x and y as two sol_bc4_encode_block_fast blocks (libsquish-style usual) */
} sol_bc5_encoder;

/* The adaptive encoder's first step (the talk's "compress the block with a usual 3Dc compression
 * approach"): the encoder whose block is measured against the threshold and whose anchors centre the
 * window. */
typedef enum sol_bc5_base {
    SOL_BC5_BASE_COMMON = 0, /* sol's exact least-squares common encoder (SOL_BC5_COMMON) */
    SOL_BC5_BASE_FAST        /* the usual one-pass alpha-block encoder (SOL_BC5_FAST): the talk's step 1 */
} sol_bc5_base;

typedef struct sol_bc5_options {
    sol_bc5_encoder encoder;
    sol_bc4_precision precision; /* the decoder the error is measured for */
    sol_bc5_metric metric;       /* optimal and adaptive minimise this */
    /* Adaptive: each of the four anchors is searched within +-window codes of the base encoder's
     * anchor (clamped to 0..255), exactly (the error equals the brute force over that box). 0 = default
     * 4 (the talk's [v-4/255, v+4/255]); negative = 0, i.e. only the base anchors, with joint index
     * choice; 255 or more = every code (no int overflow). Windows up to 8 take a dedicated path (about
     * 3-20 us of one core per searched block on the 1024^2 benchmark maps with the common base, the
     * most on the rough terrain-derived map; exactly tied anchor pairs of nearly flat blocks are evaluated once per
     * class); wider ones, and blocks with normals at or near the rim (z^2 not
     * above the block's error), the optimal encoder's search restricted to it. */
    int window;
    /* Adaptive: search only blocks whose base RMS angular error (sqrt(mean dN^2), or max dN for
     * SOL_BC5_MAX, of the base encoder's block) exceeds this many degrees (and that the gap test below
     * does not skip). 0 = no threshold: every block the gap test leaves is searched.
     * Where the caller asks for no error (sol_bc5_encode_image, or info NULL) the test is decided from
     * chord bounds of the angles (c <= dN <= c / sqrt(1 - c^2 / 4), chord c, with rounding slack) and
     * the angles are computed only when the bounds straddle the threshold: the same decision as the
     * exact angles, at a fraction of their cost. SOL_BC5_THRESHOLD_ARGB8_DEG is a physical choice. */
    double threshold_deg;
    /* Optimal and adaptive: work bound per block, in work units: one pixel of one candidate through
     * the quick bound counts 1, through the joint index-pair bound 32, an exact evaluation of a
     * candidate 512 (a candidate costs 1 to 1040; about their relative costs). A search that reaches
     * it stops with the best block found so far and reports info->bounded = 1 (the result is then not
     * proven optimal). 0 = SOL_BC5_DEFAULT_WORK_LIMIT (2^26), about 0.5-1 s of one core; the hardest
     * blocks of the benchmark maps need about a third of it (2.4 x 10^7). */
    uint64_t work_limit;
    /* Adaptive: the first step's encoder (see sol_bc5_base). 0 = SOL_BC5_BASE_COMMON. */
    sol_bc5_base base;
    /* Adaptive, common base: skip the window search of a block whose base encoding is PROVABLY within
     * a factor (1 + gap) of the optimum over all anchors (not only the window's), so that searching it
     * could gain at most that. 0 = SOL_BC5_DEFAULT_GAP; negative = no gap test (every block above
     * threshold_deg is searched, as before this option); NaN or Inf: SOL_ERR_INVALID_ARG. A block is
     * searched only when BOTH tests ask for it: its level exceeds threshold_deg AND its objective
     * E_base > (1 + gap) LB. Units: the objective the metric minimises, in rad^2 (sum of dN^2, or the
     * max of dN^2), so a skipped block's RMS angle (or max angle) is within sqrt(1 + gap) of the
     * optimum's: gap 0.21 = 10%.
     * The bound LB, free from the common encoder (each channel's exact least-squares sum Sx, Sy over
     * all 65536 anchor pairs, component units 2 v - 1, which sol_bc4_encode_block minimises), is the
     * larger of the separable bound and the tilt bound:
     *   separable: min(Sx + Sy, min_p nz_p^2)        ((Sx + Sy) / 16 for SOL_BC5_MAX: max >= mean)
     *   tilt:      min(B, T)                         (B / 16 for SOL_BC5_MAX), when every nz_p > 0,
     * with T = min(U, min_p nz_p^2), U the base block's upper chord bound (>= its objective, see
     * threshold_deg), B the largest of Sx + Sy, (1 + alpha) Sx + (1 - beta) Sy and the same with x and
     * y swapped, where for r = sqrt(T), K = (max(0, 2 min_p |nx_p| - r) / (2 max_p nz_p + r))^2,
     * C = ((2 max_p |ny_p| + r) / (2 min_p nz_p - r))^2: beta in (0, 1] and alpha = K beta / (beta + C)
     * (beta = sqrt(K C Sx / Sy) - C clamped to 1, the best; 1 when Sy = 0).
     * Proof (separable): take any anchors and indices. If every pixel decodes inside the unit disk
     * (a^2 + b^2 <= 1, z rebuilt), dN_p >= chord_p = |u_p - n_p| >= sqrt((a_p - nx_p)^2 + (b_p -
     * ny_p)^2) (the chord of unit vectors is at most the angle; dropping the z difference), so the sum
     * of dN_p^2 is at least sum_p min_i (x_i - nx_p)^2 + min_j (y_j - ny_p)^2 >= Sx + Sy (the common
     * anchors minimise each channel's sum over all pairs). If some pixel p decodes with z clamped to 0,
     * its direction lies on the equator and dN_p >= asin |nz_p| >= |nz_p|, so the objective is at
     * least nz_p^2. Hence every block, the optimum's included, has objective >= LB.
     * Proof (tilt: the chord's z part, which the separable bound drops, is what tilted normals add,
     * and where one channel's error dominates it is not cancelled by the other's). Write dx = a - nx, dy = b - ny, dz = z - nz for a pixel decoding inside the disk.
     * Both vectors are unit, so dx (a + nx) + dy (b + ny) + dz (z + nz) = 0, and with z + nz > 0,
     * dz = -(G dx + H dy), G = (a + nx) / (z + nz), H = (b + ny) / (z + nz): chord^2 = dx^2 + dy^2 +
     * (G dx + H dy)^2. For alpha >= 0, beta > 0 with G^2 >= alpha (1 + H^2 / beta), the form
     * (G dx + H dy)^2 - alpha dx^2 + beta dy^2 is positive semidefinite (its determinant is beta G^2 -
     * alpha (H^2 + beta) >= 0, its dy^2 coefficient H^2 + beta > 0), so chord^2 >= (1 + alpha) dx^2
     * + (1 - beta) dy^2 =: q. Where chord^2 < T, |dx|, |dy|, |dz| < r, so G^2 >= K and H^2 <= C
     * (|a + nx| >= 2 |nx| - r, |b + ny| <= 2 |ny| + r, z + nz in (2 nz - r, 2 nz + r), 2 nz - r >=
     * nz > 0 as T <= nz^2), and alpha = K beta / (beta + C) <= G^2 beta / (beta + H^2) meets the
     * condition: chord^2 >= q. Where chord^2 >= T, and for decodes with z
     * clamped (chord^2 >= nz_p^2 >= T), chord^2 >= min(q, T). So every pixel has dN_p^2 >= min(q_p,
     * T), and (all q_p >= 0 as beta <= 1) the sum is >= min(sum_p q_p, T) >= min((1 + alpha) Sx +
     * (1 - beta) Sy, T): if some q_p >= T that term alone is T, else the sum is sum_p q_p, and
     * sum_p dx_p^2 >= Sx, sum_p dy_p^2 >= Sy with non-negative weights (the max metric: max_p min(q_p,
     * T) >= min(sum_p q_p / 16, T)). The cap U only chooses T (any T in (0, min nz^2] gives a valid
     * bound; U keeps r small, about the pixels' error, and the bound itself at most U).
     * Rounding: LB is lowered to max(0, LB - 16 TAU) (1 - REL) (TAU = 1e-10 per pixel, REL = 1e-9;
     * max metric: one TAU), which covers the rounding of the computed angles (within 1e-14 rad of the
     * true ones), of the unit normals (within 1e-16 of unit length) and of the sums (20 ulps relative)
     * a thousand times over; r is raised by a relative 1e-9 and by 1e-12 and alpha lowered by a
     * relative 1e-12, which cover the rounding of K, C and alpha (bc5_adaptive.c): the computed
     * objective of every block is >= the lowered LB. So a skipped block's computed objective is <=
     * (1 + gap) times the computed objective of every other block.
     * The base objective is decided from chord bounds of the angles where the caller asks for no error
     * (the same decision as the exact angles, see threshold_deg; U is computed on every path, so the
     * limit (1 + gap) LB, and the decision, do not depend on whether the caller asks for the error). The fast base has no skip test (its
     * step 1 computes no least-squares sums: bounding the optimum would cost the common encoder).
     * The same gap is the window search's relative tolerance, with either base: a candidate is dropped
     * once its lower bound reaches the incumbent's objective / (1 + gap), so a searched block ends
     * within a factor (1 + gap) of the window's optimum (blocks the window hands to the optimal
     * encoder's search, windows wider than 8 codes and normals near the rim, are searched exactly).
     * So with the common base every block's objective is within (1 + gap) of the window's optimum,
     * and a skipped one within (1 + gap) of the optimum over all anchors. */
    double gap;
} sol_bc5_options;

/* The gap of options.gap = 0, chosen from the measurements of T13 and make bench (experiment
 * t8_t14_3dc_encoders): a skipped block's RMS angle within 10% of the optimum's. */
#define SOL_BC5_DEFAULT_GAP 0.21

#define SOL_BC5_DEFAULT_WORK_LIMIT (UINT64_C(1) << 26)

/* A threshold_deg with a physical meaning: the RMS angle (degrees) that storing unit normals at 8 bits
 * per component (ARGB8, the format the talk measures 3Dc's precision against) leaves. Each component
 * is rounded to a step of 2/255 (units of the component in [-1, 1]), an error uniform on +-1/255,
 * variance (1/255)^2 / 3; of the error vector only the two components perpendicular to the normal turn
 * it (the radial one changes its length), so the mean squared angle is 2 (1/255)^2 / 3 and the RMS
 * angle 2 / (255 sqrt(6)) rad = 0.18346 degrees, for every direction (small-angle limit; a Monte-Carlo
 * check over the hemisphere gives 0.1836). A block whose base encoding is already within it is as
 * close to its source as an 8-bit normal map would be. (At 16 bits per component: 0.00071 degrees.) */
#define SOL_BC5_THRESHOLD_ARGB8_DEG ((2.0 / (255.0 * 2.4494897427831781)) * (180.0 / 3.14159265358979323846))

/* Anchor ranges for sol_bc5_search_block: each anchor code in [lo, hi] (inclusive). */
typedef struct sol_bc5_range {
    uint8_t x0_lo, x0_hi, x1_lo, x1_hi; /* x channel's e0 and e1 */
    uint8_t y0_lo, y0_hi, y1_lo, y1_hi;
} sol_bc5_range;

/* What an encode did: the block error in the metric's units, whether a search ran, and how many
 * (x pair, y pair) candidates were evaluated exactly. */
typedef struct sol_bc5_info {
    double error;
    int searched;
    uint64_t candidates;
    int bounded; /* 1 if the work bound (work_limit) stopped the search before its proof */
} sol_bc5_info;

/* Decodes a block to 16 normals (x, y, z), z = sqrt(max(0, 1 - x^2 - y^2)). The result is NOT
 * renormalised where x^2 + y^2 > 1 (angles are measured on the direction, so that is harmless). */
sol_status sol_bc5_decode_block(const sol_bc5_block *block, sol_bc4_precision precision, double out[16][3]);

/* Error of a block as encoded (its own indices) against source normals, in the metric's units. */
sol_status sol_bc5_block_error(const sol_bc5_block *block, const double normals[16][3],
                               sol_bc4_precision precision, sol_bc5_metric metric, double *error);

/* Given the four anchors in `block` (its indices are ignored), chooses each pixel's index pair
 * minimising its angle, writes the indices into block, and returns the block error. This is the
 * objective every joint search minimises. */
sol_status sol_bc5_choose_indices(sol_bc5_block *block, const double normals[16][3], sol_bc4_precision precision,
                                  sol_bc5_metric metric, double *error);

/* Encodes one block with options (NULL = all defaults). info may be NULL. The searching encoders
 * (adaptive, optimal) allocate their scratch on each call (up to ~30 MB, most of it touched only by
 * blocks pointing away or at rims): to encode many blocks one at a time, reuse a sol_bc5_workspace. */
sol_status sol_bc5_encode_block(const double normals[16][3], const sol_bc5_options *options, sol_bc5_block *out,
                                sol_bc5_info *info);

/* A reusable workspace for block encodes: the searches' scratch, kept (and grown on demand) between
 * calls, so that a caller encoding blocks one at a time does not allocate and fault in fresh memory
 * per block (issue 13: on the hard blocks of the degenerate survey, first-touch page faults were up
 * to half of a single block's time; sol_bc5_encode_image keeps one per thread). One workspace per
 * thread (calls with one workspace must not overlap); the results are those of sol_bc5_encode_block,
 * bit for bit, whatever blocks it encoded before.
 * sol_bc5_workspace_new: NULL if out of memory. sol_bc5_workspace_free(NULL) does nothing.
 * sol_bc5_encode_block_with: as sol_bc5_encode_block (same errors), plus SOL_ERR_NULL_ARG for a NULL
 * workspace. */
typedef struct sol_bc5_workspace sol_bc5_workspace;
sol_bc5_workspace *sol_bc5_workspace_new(void);
void sol_bc5_workspace_free(sol_bc5_workspace *workspace);
sol_status sol_bc5_encode_block_with(sol_bc5_workspace *workspace, const double normals[16][3],
                                     const sol_bc5_options *options, sol_bc5_block *out, sol_bc5_info *info);

/* The exact minimum of the joint objective (sol_bc5_choose_indices) over all anchors inside
 * `range` (NULL = all 2^32 anchor combinations), by branch and bound: separable lower bounds
 * sum_p min_a (a - Nx_p)^2 + min_b (b - Ny_p)^2 <= sum_p chord_p^2 <= sum_p dN_p^2 (and their max
 * forms) over anchor pairs sorted by bound; each candidate is rejected through lower bounds of its
 * angles (from chords, no atan2: first a quick one from each channel's nearest entries, then one
 * from each pixel's jointly best index pair) before an exact evaluation. Only options->precision,
 * ->metric and ->work_limit are used.
 * Ties: the first minimiser in the search order (incumbents - the common anchors, then the
 * full-span 6-value pairs (0, 255) - then x pairs by increasing bound and code, y pairs likewise);
 * its error equals the literal brute force's minimum exactly. Exactly tied anchor pairs (a flat
 * block has hundreds per channel: anchors whose palettes hold the same values near the targets)
 * are recognised as one class and evaluated once, which does not change the result.
 * Degenerate blocks are decided at once: flat or all-equal blocks (ties merged), normals pointing
 * straight away (0, 0, -1) (the incumbent meets the hemisphere bound asin(-z)). Pixels pointing away
 * (z < 0) are bounded through their rim direction m (dN^2 >= theta0^2 + theta0 cot(theta0) |u - m|^2,
 * theta0 = asin(-z)), rims and pixels pointing away couple x and y through a filter of the y pairs
 * per x pair, and 16 equal normals at a rim or pointing away are solved at the level of decoded
 * values (ties: the first x and y pairs of the search lists holding the best decode). Blocks with
 * pixels pointing away also keep only the anchor pairs whose entries can meet an actual value of
 * the other channel's list inside each pixel's ball under the incumbent, and merge pairs whose such
 * entries are identical (again whenever the incumbent halves its distance to the hemisphere bound),
 * which decides candidates tied with the incumbent to 1e-10 and closer. Where those lists stay long
 * (arcs pointing away or along the rim), a pair screen decides the candidates ahead of the
 * enumeration, one y pair at a time, from per-pixel bounds of each x VALUE (a sum of per-pixel
 * minima over the x pair's 8 values); it skips only candidates that cannot beat the incumbent. Cost: about
 * 0.1-200 ms per block on smooth to rough maps, 1-100 ms for varied or equal normals pointing away or
 * at rims; the work bound (work_limit) caps the rest - near-ties the bounds cannot separate (e.g.
 * smooth blocks pointing away or along a rim, measured in issue 13), where info->bounded reports that
 * the result is the best found, not a proven optimum.
 * SOL_ERR_INVALID_ARG if a range has lo > hi. */
sol_status sol_bc5_search_block(const double normals[16][3], const sol_bc5_range *range,
                                const sol_bc5_options *options, sol_bc5_block *out, sol_bc5_info *info);

/* Statistics of an image encode (integers, so identical whatever the thread count). */
typedef struct sol_bc5_image_stats {
    uint64_t blocks;
    uint64_t searched_blocks;
    uint64_t candidates;
    uint64_t bounded_blocks; /* blocks whose search the work bound stopped (see work_limit) */
    uint64_t max_block_candidates; /* the most candidates one block took, and that block (the */
    int max_block;                 /* first such, row-major block index): the costliest block */
} sol_bc5_image_stats;

/* Encodes a 3-channel normal image (x, y, z per pixel; width and height multiples of 4) into
 * blocks (16 bytes each, row-major over blocks; caller allocates width*height bytes). OpenMP over
 * blocks; the output does not depend on the thread count. stats may be NULL.
 * SOL_ERR_INVALID_ARG on a bad size or channel count. */
sol_status sol_bc5_encode_image(const sol_image *normals, const sol_bc5_options *options, uint8_t *blocks,
                                sol_bc5_image_stats *stats);

/* Decodes blocks to a newly allocated 3-channel image of normals (z rebuilt, normalised). */
sol_status sol_bc5_decode_image(const uint8_t *blocks, int width, int height, sol_bc4_precision precision,
                                sol_image *out);

/* Writes a .dds file: fourcc "ATI2" (BC5, 16 bytes per block) or "ATI1" (BC4, 8 bytes per block),
 * one mip level. channels: 1 (BC4) or 2 (BC5). SOL_ERR_IO if the file cannot be written. The file
 * is written to a temporary beside `path` and renamed over it on success (sol_file_out_open): on
 * any error no temporary is left and `path` is as it was (absent, or the old file unchanged). */
sol_status sol_dds_write_bc(const char *path, const uint8_t *blocks, int width, int height, int channels);

#ifdef __cplusplus
}
#endif
#endif
