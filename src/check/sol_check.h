/* sol_check.h - checks of an engine's own output against sol's references (issue 10).
 *
 * Each sol_check_* call takes what an engine produced for given inputs (codes, packed bits,
 * decoded texels, curve samples, a LUT), recomputes sol's reference for the same inputs and fills
 * a sol_check_report: how many values were compared, how many differ from sol, the mean and the
 * largest error in the check's unit, the worst inputs, and pass/fail against the tolerance the
 * check documents (the SOL_CHECK_* constants below; each is a measured bound or an exactness rule,
 * the comment says which). The checks only compare: they never print; the `sol check` program
 * (src/cli/cmd_check.c) reads files, calls them and prints the report.
 *
 * This module depends on the technique modules (normals, normalmaps, textures, hdr); they never
 * include it. It also exports the edge-case inputs sol's own tests use, so an engine can be fed
 * the inputs where implementations usually go wrong (sol_check_edge_*).
 *
 * Conventions as in sol_core.h: every fallible call returns a sol_status (SOL_ERR_NULL_ARG,
 * SOL_ERR_INVALID_ARG for n == 0 or an unknown method/format) and leaves the report untouched on
 * error. A failed comparison is not an error: it is report->passed == 0.
 */
#ifndef SOL_CHECK_H
#define SOL_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"
#include "sol_hdr.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { SOL_CHECK_WORST = 8 }; /* how many worst inputs a report keeps */

/* One compared input: its index in the caller's arrays, the error, and up to 4 values of the input,
 * of sol's reference and of the engine's output (which values: see each check). */
typedef struct sol_check_item {
    size_t index;
    double error;
    double input[4];
    double expected[4]; /* sol */
    double got[4];      /* engine */
} sol_check_item;

typedef struct sol_check_report {
    const char *unit;       /* static: the unit of error/mean/max/tolerance ("deg", "code", ...) */
    size_t count;           /* values compared */
    size_t mismatches;      /* values whose result differs from sol's at all (0 = bit-exact) */
    size_t failures;        /* values beyond the tolerance (passed == (failures == 0)) */
    double mean, max;       /* of the error over all values */
    double tolerance;       /* the bound each value's error must meet */
    int passed;             /* 1: every value within tolerance */
    int worst_count;        /* items in worst[] (<= SOL_CHECK_WORST), largest error first */
    sol_check_item worst[SOL_CHECK_WORST];
} sol_check_report;

/* ---- normals: an engine's encode table (direction -> code) ----
 * Error unit: degrees between the input direction and sol_normal_decode of the ENGINE's code.
 * A value fails when the engine's code differs from sol's, unless it is a tie: every field of
 * the code (8-bit channels, or 12/8-bit halves) within one step of sol's and the engine's angle
 * within the method's bound below (a float encoder rounds differently from sol's double one only
 * where the exact value sits near half a step). With options->exact, every differing code fails.
 * Bounds: the largest angle of sol's own encoder, measured over 2^20 R2 directions plus
 * sol_check_edge_normals, rounded up (tests/test_check.c pins that sol stays within them). The
 * near-pole directions of the spherical-z and Mittring encodings and the near-axis edge cases of
 * the XYZ methods set the maxima; the means are far lower (0.02 deg for octahedral-12). */
#define SOL_CHECK_BOUND_XYZ_NORMALIZED_DEG 0.39
#define SOL_CHECK_BOUND_XYZ_MAX_COMPONENT_DEG 0.32
#define SOL_CHECK_BOUND_XYZ_BEST_FIT_DEG 0.32       /* also the float variant */
#define SOL_CHECK_BOUND_OCTAHEDRAL_12_DEG 0.059
#define SOL_CHECK_BOUND_OCTAHEDRAL_12_PRECISE_DEG 0.040
#define SOL_CHECK_BOUND_SPHERICAL_12_DEG 0.049
#define SOL_CHECK_BOUND_SPHERICAL_Z_12_DEG 1.22
#define SOL_CHECK_BOUND_MITTRING_12_DEG 2.6
#define SOL_CHECK_BOUND_MITTRING_8_DEG 11.4
/* The bound (degrees) of a method above; 0 for an unknown method. */
double sol_check_normal_bound_deg(sol_normal_method method);

typedef struct sol_check_normal_options {
    int exact; /* 1: any code differing from sol's fails (no tie rule) */
} sol_check_normal_options;

/* dirs: n directions (x, y, z, any length); codes: the engine's n codes. options may be NULL.
 * Report items: input = direction, expected[0] = sol's code, got[0] = engine's code,
 * expected[1]/got[1] = sol's / engine's angle (deg). */
sol_status sol_check_normals(sol_normal_method method, const double (*dirs)[3], const uint32_t *codes, size_t n,
                             const sol_check_normal_options *options, sol_check_report *report);

/* Edge-case directions (axes, +-0 components, the octahedral fold diagonals, near-axis and
 * near-diagonal tilts, denormal and huge components): *count directions, static storage. */
const double (*sol_check_edge_normals(size_t *count))[3];

/* ---- BC1 / BC5 decoders: decoded texels against sol's decoders ----
 * blocks: width/4 * height/4 blocks in row-major block order (as a .dds stores them; width and
 * height multiples of 4). texels: the engine's decoded values, row-major, `channels` per texel
 * (bc5: >= 2, red = x, green = y; bc1: >= 3, RGB), as codes at `bits` precision (8 or 16:
 * UNORM code = value * (2^bits - 1)). sol's value is requantised with sol_unorm_encode at the
 * same precision. Error unit: codes at that precision. Tolerance: SOL_CHECK_TOL_DECODE_CODES
 * (0: bit-exact with sol's documented rounding; pass a larger `tolerance_codes` to accept a
 * decoder that rounds differently, e.g. 1). Items: input[0..1] = texel x, y; expected/got = the
 * channel values as codes. */
#define SOL_CHECK_TOL_DECODE_CODES 0.0
sol_status sol_check_bc5_decode(const uint8_t *blocks, int width, int height, sol_bc4_precision precision,
                                const uint16_t *texels, int channels, int bits, double tolerance_codes,
                                sol_check_report *report);
sol_status sol_check_bc1_decode(const uint8_t *blocks, int width, int height, const uint16_t *texels, int channels,
                                int bits, double tolerance_codes, sol_check_report *report);

/* ---- BC5 encoder quality: an engine's blocks against the source normals ----
 * Error unit: degrees between each source normal (3-channel image, any length) and the engine's
 * decoded normal (both decoded at `precision`). sol encodes the same source with the `reference`
 * encoder (sol_bc5_encode_image, options otherwise default: sum-of-squares metric, default work
 * bound) and measures its mean angle the same way. Pass rule: the engine's mean angle is at most
 * (1 + SOL_CHECK_BC5_ENCODER_SLACK) times the reference's mean. report->tolerance = that bound,
 * report->mean the engine's mean, report->failures 1 when it fails, the items the engine's per-texel
 * angles. SOL_BC5_COMMON (two least-squares BC4 blocks) is the bar any decent encoder clears;
 * SOL_BC5_OPTIMAL (joint anchors and indices, T10/T11) asks whether the engine is near the best
 * BC5 can do: an engine equal to the common encoder fails it wherever the optimum is more than 5%
 * better. The optimal search costs about 0.1-50 ms per block (up to the work bound, ~1 s, on
 * pathological blocks); blocks that hit the bound hold the best block found, not a proven optimum:
 * their count goes to *reference_bounded_blocks (may be NULL; 0 for common and fast). The
 * reference's mean goes to *reference_mean_deg (may be NULL). Outputs untouched on error.
 * Errors: SOL_ERR_NULL_ARG; SOL_ERR_INVALID_ARG if width or height is not a positive multiple of
 * 4, the source has fewer than 3 channels, a source normal is zero or not finite, or `reference`
 * is not a sol_bc5_encoder; SOL_ERR_NO_MEMORY. */
#define SOL_CHECK_BC5_ENCODER_SLACK 0.05
sol_status sol_check_bc5_encode_against(const sol_image *source, const uint8_t *blocks, sol_bc4_precision precision,
                                        sol_bc5_encoder reference, sol_check_report *report,
                                        double *reference_mean_deg, uint64_t *reference_bounded_blocks);
/* sol_check_bc5_encode_against with reference SOL_BC5_COMMON (reference_mean_deg: the common mean). */
sol_status sol_check_bc5_encode(const sol_image *source, const uint8_t *blocks, sol_bc4_precision precision,
                                sol_check_report *report, double *reference_mean_deg);

/* ---- BC1 encoder quality: an engine's blocks against the source colours ----
 * Error unit: 8-bit codes, per texel sqrt of the mean over R, G, B of (255 source - decoded)^2
 * (source values in [0,1], what the texture stores, 3 or more channels). The engine passes when
 * its mean is at most (1 + SOL_CHECK_BC1_ENCODER_SLACK) times that of sol's default encoder
 * (SOL_BC1_CLUSTER) on the same source. width, height multiples of 4. reference_mean (may be NULL)
 * receives sol's mean. Errors: SOL_ERR_OUT_OF_RANGE / SOL_ERR_NONFINITE for a bad source value. */
#define SOL_CHECK_BC1_ENCODER_SLACK 0.05
sol_status sol_check_bc1_encode(const sol_image *source, const uint8_t *blocks, sol_check_report *report,
                                double *reference_mean);

/* ---- packed HDR formats: bit-exact packing of given values ----
 * values: n x `sol_check_pack_inputs(format)` floats (r, g, b or one value); bits: the engine's
 * packed result per value, as one integer (R11G11B10F: the 32-bit word, r in bits 0-10; fp16: the
 * 16 bits; RGBM: r | g << 8 | b << 16 | m << 24 with range `param` (0 = 6); RGB10 0..2: one 10-bit
 * code per channel, r | g << 10 | b << 20; depth RG8: x | y << 8). Exactness: every value must
 * give sol's bits (all these encodings are defined to the bit; NaN inputs compare by class: any
 * NaN pattern sol would give). Error unit: the relative difference of the decoded values
 * |engine - sol| / max(|sol|, 2^-14) (largest over the channels); a mismatch fails whatever it is.
 * Items: input = the value, expected/got = the decoded values. */
typedef enum sol_check_pack_format {
    SOL_CHECK_PACK_R11G11B10F = 0,
    SOL_CHECK_PACK_FP16,
    SOL_CHECK_PACK_RGBM,
    SOL_CHECK_PACK_RGB10,
    SOL_CHECK_PACK_DEPTH_RG8,
    SOL_CHECK_PACK_COUNT
} sol_check_pack_format;
/* Stable names: "r11g11b10f", "fp16", "rgbm", "rgb10", "depth-rg8"; NULL for unknown. */
const char *sol_check_pack_name(sol_check_pack_format format);
/* Floats per input value (3 or 1); 0 for unknown. */
int sol_check_pack_inputs(sol_check_pack_format format);
/* sol's packed bits of one value (what the engine must produce). */
sol_status sol_check_pack_reference(sol_check_pack_format format, const float *value, double param, uint32_t *bits);
sol_status sol_check_pack(sol_check_pack_format format, const float *values, const uint32_t *bits, size_t n,
                          double param, sol_check_report *report);
/* Edge-case floats for the packers: zeros of both signs, denormals, the formats' largest finite
 * values and their rounding ties, the overflow thresholds, Inf, NaN. Static storage. */
const float *sol_check_edge_floats(size_t *count);

/* ---- tone maps: sampled curve (x = c / l, linear display y) against sol_tonemap_apply ----
 * Error unit: |y_engine - y_sol| in linear display units. Tolerance SOL_CHECK_TOL_TONEMAP:
 * half the smallest 8-bit sRGB display step, 0.5 / 255 / 12.92 (the step at black), so an engine
 * within it can only ever land one display code away from sol. NaN samples fail. */
#define SOL_CHECK_TOL_TONEMAP 1.5e-4
sol_status sol_check_tonemap(sol_tonemap op, const double *x, const double *y, size_t n, sol_check_report *report);
/* The lower bound of the sampled curve: the smallest sampled x whose y reaches `threshold`
 * (0: 0.5/255), and sol's closed form (sol_tonemap_lower_bound), for comparison.
 * SOL_ERR_OUT_OF_RANGE when no sample reaches the threshold. */
sol_status sol_check_tonemap_bound(sol_tonemap op, const double *x, const double *y, size_t n, double threshold,
                                   double *engine_c_min, double *sol_c_min);

/* The sampled curve through sol's inverse: for each sample with 0 < y < the curve's supremum,
 * x' = sol_tonemap_inverse(op, y) is the exposure at which sol's curve gives the engine's y; the
 * error is |log2(x' / x)| in EV (stops). mean_ev and max_ev over those samples; *used (may be
 * NULL) = how many. SOL_ERR_OUT_OF_RANGE when no sample qualifies. */
sol_status sol_check_tonemap_inverse(sol_tonemap op, const double *x, const double *y, size_t n, double *mean_ev,
                                     double *max_ev, size_t *used);

/* ---- 3D LUT: an engine's table against sol's bake of the same look ----
 * Compares at the engine table's lattice points: the point domain_min + i/(size-1) (domain_max -
 * domain_min) per channel (NULL domains: [0,1]) through sol_grade_apply, and the engine's entry,
 * both as sRGB-encoded colours, converted to Lab (sol_srgb_to_lab). Error unit: CIEDE2000.
 * Tolerance SOL_CHECK_TOL_LUT_DE00: 1.0, a just-noticeable difference. Items: input = the
 * lattice colour, expected = sol, got = engine. */
#define SOL_CHECK_TOL_LUT_DE00 1.0
sol_status sol_check_lut(const sol_lut3d *engine, const double domain_min[3], const double domain_max[3],
                         const sol_grade *look, sol_check_report *report);

/* ---- sRGB: 8-bit codes of linear values ----
 * sol's code is round(255 * sol_srgb_encode(x)) in double. Tie rule: a code one away from sol's
 * is accepted when 255 * encode(x) lies within SOL_CHECK_SRGB_TIE_CODES of the half-way point
 * between the two codes; a float encoder (powf) lands on either side there. Measured: a correct
 * float encoder (1.055f * powf(x, 1/2.4f) - 0.055f, rounded) differs from sol at 11 of the 2,000,001
 * inputs i / 2,000,000, each within 1e-5 codes of a tie (tests/test_check.c); 1e-4 codes leaves a
 * 10x margin. Error unit: codes (|engine - sol|). Items: input[0] = x, input[1] = 255 * encode(x).
 * NaN inputs: sol's code is 0. */
#define SOL_CHECK_SRGB_TIE_CODES 1e-4
sol_status sol_check_srgb(const double *linear, const uint8_t *codes, size_t n, sol_check_report *report);

/* ---- numeric tables (CSV) for the checks' inputs ----
 * Reads comma/whitespace-separated numbers: '#' starts a comment, blank lines are skipped, a first
 * line that is not numeric is a header; numbers are decimal, hexadecimal integers (0x1f) or C99
 * hexadecimal floats (0x1.8p+3, exact: what printf's %a writes); "nan" and "inf" are accepted.
 * Every row must have the same number of columns (1..64). Errors:
 * SOL_ERR_FORMAT with *bad_line (may be NULL) = the 1-based line of the first bad row;
 * SOL_ERR_LIMIT past limits (cells count as pixels, 8 bytes each); SOL_ERR_IO; SOL_ERR_NO_MEMORY.
 * Free with sol_check_table_free. */
typedef struct sol_check_table {
    size_t rows, cols;
    double *values; /* rows * cols, row-major */
} sol_check_table;
sol_status sol_check_table_parse(const char *text, size_t length, const sol_read_limits *limits,
                                 sol_check_table *out, size_t *bad_line);
sol_status sol_check_table_read(const char *path, const sol_read_limits *limits, sol_check_table *out,
                                size_t *bad_line);
void sol_check_table_free(sol_check_table *table);

#ifdef __cplusplus
}
#endif
#endif
