/* sol_normals.h - unit normals in 24 G-buffer bits (claims D3-D7, S1, S5).
 *
 * Every method maps a direction to a 24-bit code (uint32_t, bits 24..31 zero) and back:
 *  - three-channel methods (XYZ 8:8:8) pack channel codes r | g << 8 | b << 16; their channel
 *    value is the talk's quantizer (Kaplanyan 2010, appendix A, quantize255):
 *        code = round(255 * clamp(c * 0.5 + 0.5, 0, 1)),  c' = code / 255 * 2 - 1,
 *    and decoding is one normalization of (r', g', b') (talk, "reconstruction is just a
 *    normalization"). No code decodes to the zero vector: every c' is an odd multiple of 1/255.
 *  - two-channel methods (12:12) pack a | b << 12.
 *
 * Input: any finite non-zero vector; it is normalized first (in double precision, scaled by its
 * largest component so denormal and huge vectors work), so `n` need not be unit length.
 * Errors: SOL_ERR_NULL_ARG (NULL pointer), SOL_ERR_NONFINITE (NaN or Inf component),
 * SOL_ERR_ZERO_LENGTH (all components +-0), SOL_ERR_INVALID_ARG (unknown method, code above
 * 2^24 - 1, bad table). On error outputs are untouched. Decoded normals are unit length (double).
 * Sign convention: -0.0 is treated as +0.0 (sign(0) = +1) everywhere.
 */
#ifndef SOL_NORMALS_H
#define SOL_NORMALS_H
#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sol_normal_method {
    /* D3: normalize, then quantize255 each component (the classic RGBA8 G-buffer). */
    SOL_NORMAL_XYZ_NORMALIZED,
    /* D4: divide by the largest |component| (a point on the cube [-1,1]^3), then quantize255. */
    SOL_NORMAL_XYZ_MAX_COMPONENT,
    /* D5/D6: best fit by the exact along-the-ray search of the talk's appendix A, in double
     * precision: over the 126 probes t = s / 127.5, s = 1.5, 2.5, ..., 127.5, of the normal
     * divided by its largest component, keep the first probe whose quantized value has the least
     * max-norm deviation |q - p|_inf / t (the appendix's error measure). Not real-time (~126
     * quantizations); see sol_bestfit_table for the shader's baked path. */
    SOL_NORMAL_XYZ_BEST_FIT,
    /* The same search evaluated in single precision, as the appendix's HLSL does (float
     * arithmetic, input rounded to float). Ties between a cell and its odd multiples, exact in
     * double, break by rounding noise here. */
    SOL_NORMAL_XYZ_BEST_FIT_FLOAT,
    /* S5: octahedral map (Cigolle et al. 2014; Narkowicz's notes), 12:12 bits ("oct24"). The
     * unit vector is projected onto |x|+|y|+|z| = 1 and, for z < 0, folded:
     * (u, v) = ((1-|y|) sgn x, (1-|x|) sgn y) with sgn(0) = +1. Each coordinate u in [-1,1] is a
     * 12-bit SNORM value, as in Cigolle et al.: k = floor(u * 2047 + 0.5) in -2047..2047, stored
     * as k + 2047 (codes 0..4094; 0 is exact, +z is code 2047 | 2047 << 12). Code = a | b << 12.
     * Decoding: u = (code - 2047) / 2047 (code 4095, never produced, clamps to +1).
     * This is NOT the UNORM rule round((u * 0.5 + 0.5) * 4095), which has no exact 0 (+z is 2048,
     * 2048 there) and agrees with this one on both codes for only about a quarter of directions;
     * sol_oct_encode offers it (SOL_OCT_UNORM). */
    SOL_NORMAL_OCTAHEDRAL_12,
    /* S5: octahedral 12:12 with Cigolle et al.'s "precise" encoding: of the 4 codes around the
     * projected point (floor and floor + 1 of u * 2047 per coordinate, codes above 4094 skipped),
     * the one whose decoded direction is closest in angle, the first in the order
     * (0,0), (1,0), (0,1), (1,1) on ties ("oct24P"). Same code layout and decoder as above. */
    SOL_NORMAL_OCTAHEDRAL_12_PRECISE,
    /* S5: spherical coordinates 12:12: theta = acos(z) in [0, pi] as round(theta / pi * 4095)
     * (poles exact), phi = atan2(y, x) as round(phi / (2 pi) * 4096) mod 4096 (periodic). */
    SOL_NORMAL_SPHERICAL_12,
    /* S5: the spherical variant of Narkowicz's notes: phi = atan2(y, x) and z itself (not theta),
     * each a 12-bit UNORM of (phi / pi) * 0.5 + 0.5 and z * 0.5 + 0.5 (equal-area in z). */
    SOL_NORMAL_SPHERICAL_Z_12,
    /* S1: Mittring 2009's view-space 2-scalar encoding G = normalize(N.xy) * sqrt(N.z*0.5+0.5),
     * each G component in [-1,1] stored as 12 bits round((g * 0.5 + 0.5) * 4095) (12:12, 24 bits).
     * Decoding: z = 2|G|^2 - 1, xy = normalize(G) * sqrt(1 - z^2). N.xy = 0 encodes with
     * normalize(N.xy) := (1, 0); |G| = 0 decodes to (0, 0, -1). */
    SOL_NORMAL_MITTRING_12,
    /* S1: the same with 8:8 bits (16 bits; Mittring's slides store G in two 8-bit channels). */
    SOL_NORMAL_MITTRING_8,
    SOL_NORMAL_METHOD_COUNT
} sol_normal_method;

/* Short stable name ("xyz-normalized", "octahedral-12", ...); "unknown" for bad values. */
const char *sol_normal_method_name(sol_normal_method method);
/* Bits a code of the method uses (24, or 16 for SOL_NORMAL_MITTRING_8); 0 for bad values. */
int sol_normal_method_bits(sol_normal_method method);

/* Encodes direction `n` (any finite non-zero vector) into `*code`. */
sol_status sol_normal_encode(sol_normal_method method, const double n[3], uint32_t *code);
/* Decodes `code` into the unit vector `n`. */
sol_status sol_normal_decode(sol_normal_method method, uint32_t code, double n[3]);

/* The talk's channel quantizer (appendix A quantize255) and its inverse: c in [-1,1] -> 0..255
 * (clamped; NaN gives 0), code -> code / 255 * 2 - 1. */
uint32_t sol_quantize255(double c);
double sol_dequantize255(uint32_t code);

/* ---- S5: the octahedral map at any bit count (Cigolle et al. 2014) ----
 * The same projection and fold as SOL_NORMAL_OCTAHEDRAL_12, with `bits` per coordinate and a choice
 * of quantizer for u in [-1, 1]:
 *  - SOL_OCT_SNORM (default): S = 2^(bits-1) - 1, code = floor(u * S + 0.5) + S (0..2S), decoded
 *    as (code - S) / S; code 2^bits - 1 clamps to +1. bits = 12 gives SOL_NORMAL_OCTAHEDRAL_12's
 *    codes (code[0] = a, code[1] = b).
 *  - SOL_OCT_UNORM: M = 2^bits - 1, code = floor((u * 0.5 + 0.5) * M + 0.5), decoded as
 *    code / M * 2 - 1 (no exact 0; the quantizer of many engines and of L. Tyler, "Analyzing
 *    Octahedral Encoded Normals", whose 12:12 table sol reproduces in d6_d7).
 * precise = 1 picks, of the 4 codes around the projected point, the one closest in angle (first in
 * the order (0,0), (1,0), (0,1), (1,1) on ties; codes past the range are skipped).
 * Options zero-initialised: bits 0 means 12, SNORM, nearest rounding; NULL options mean the same. */
typedef enum sol_oct_quantizer { SOL_OCT_SNORM = 0, SOL_OCT_UNORM = 1 } sol_oct_quantizer;
typedef struct sol_oct_options {
    int bits;                    /* per coordinate, 2..16; 0 = 12 */
    int precise;                 /* 0 nearest, 1 best of four by angle */
    sol_oct_quantizer quantizer; /* SOL_OCT_SNORM (0) or SOL_OCT_UNORM */
} sol_oct_options;
/* Encodes `n` (any finite non-zero vector; the module's input rules and errors) into code[0..1].
 * Bad options give SOL_ERR_INVALID_ARG. */
sol_status sol_oct_encode(const sol_oct_options *opt, const double n[3], uint32_t code[2]);
/* Decodes code[0..1] (each at most 2^bits - 1, else SOL_ERR_INVALID_ARG) into the unit vector n. */
sol_status sol_oct_decode(const sol_oct_options *opt, const uint32_t code[2], double n[3]);

/* ---- D6: the baked best-fit table, as the talk's shader uses it ----
 * One face of the cube map, reduced by the 8 octants and the diagonal symmetry, stored as a
 * size x size 2D texture. The shader's lookup (appendix A, CompressNormalToUnsignedGBuffer):
 * a = |n| sorted descending (a0 >= a1 >= a2, n unit length); texture coordinate
 * (u, v) = (a1, a2 / a1) (v = 0 when a1 = 0): "divide y by x to expand the triangle to a quad".
 * Texel (i, j) holds the best-fit scale t of the direction at its centre u = (i + 0.5) / size,
 * v = (j + 0.5) / size, i.e. (a0, a1, a2) proportional to (sqrt(1 - u^2 - (u v)^2), u, u v);
 * texels with 2u^2 + (uv)^2 > 1 (a1 would exceed a0, outside the domain) hold the value of the
 * direction (1, 1, v) so bilinear filtering near the edge stays sensible.
 * The encoder scales n / a0 by the looked-up t and quantizes with quantize255.
 * The stored scale is kept at `bits` precision: 8 or 16 (UNORM, as an 8/16-bit texture) or
 * 0 (float). The scale t lies in [1.5/127.5, 1]. */
typedef struct sol_bestfit_table {
    int size;     /* texels per side */
    int bits;     /* 8, 16 or 0 (float) */
    float *scale; /* size * size values, row j = v, column i = u; owned, sol_bestfit_table_free */
} sol_bestfit_table;

/* Bakes the table with the double-precision exact search (OpenMP; identical for any thread
 * count). size 1..16384, bits 0, 8 or 16, else SOL_ERR_INVALID_ARG; SOL_ERR_NO_MEMORY. */
sol_status sol_bestfit_table_build(int size, int bits, sol_bestfit_table *out);
/* Next mip level: 2x2 box average of `src` (size even, >= 2), re-quantized to src->bits. */
sol_status sol_bestfit_table_downsample(const sol_bestfit_table *src, sol_bestfit_table *out);
/* Frees the texels and zeroes the struct; safe on NULL or a zeroed table. */
void sol_bestfit_table_free(sol_bestfit_table *table);

typedef enum sol_table_filter {
    SOL_TABLE_NEAREST = 0, /* point sampling */
    SOL_TABLE_BILINEAR     /* bilinear, clamp to edge (a GPU's tex2D with a linear sampler) */
} sol_table_filter;

/* Encodes `n` through the table (the shader's path); the code decodes with
 * sol_normal_decode(SOL_NORMAL_XYZ_NORMALIZED, ...) (reconstruction is one normalization). */
sol_status sol_normal_encode_bestfit_table(const sol_bestfit_table *table, sol_table_filter filter,
                                           const double n[3], uint32_t *code);
/* The best-fit scale t for `n` by the exact double search (the value a table texel stores). */
sol_status sol_bestfit_scale(const double n[3], double *t);

/* ---- D3-D5: which cells of the 256^3 cube a method uses ----
 * A cell is the code (r, g, b); its centre is (r', g', b') = 2 code / 255 - 1 (odd multiples of
 * 1/255). Definitions (all exact integer or deterministic computations, OpenMP over r):
 *  - fixed cells of an XYZ method: cells whose own centre direction encodes back to the same code
 *    ("the method can produce this cell for some direction and returns it for its own").
 *    Counts cells with r in [r_begin, r_end) (0 <= r_begin <= r_end <= 256), so a test can check
 *    a slice; methods other than the four XYZ ones give SOL_ERR_INVALID_ARG.
 *  - cells on the sphere: cells of an L^3 grid (L even, 2..4096) whose closed box meets the unit
 *    sphere, i.e. the image of "normalize then round" over all directions; exact in integers.
 *  - distinct directions: cells of an L^3 grid (L even) whose odd integer centre coordinates
 *    (2 code - (L - 1)) have gcd 1; a cell with gcd k > 1 points where its 1/k multiple does.
 *  - cells near the sphere (D3's sample-free count): cells of an L^3 grid (L even, 2..4096) whose
 *    centre's length lies within half_width / (L - 1) of 1, i.e. with odd integer centre c,
 *    |sqrt(c.c) - (L - 1)| <= half_width (half_width in half-cell units, finite, >= 0, else
 *    SOL_ERR_INVALID_ARG). For L = 256 and half_width = sqrt(2) (half a face diagonal of a cell)
 *    this is the talk's 289880; every half_width in [1.41178, 1.42738) gives the same count. */
sol_status sol_normal_cells_fixed(sol_normal_method method, int r_begin, int r_end, uint64_t *count);
sol_status sol_normal_cells_on_sphere(int levels, uint64_t *count);
sol_status sol_normal_cells_distinct_directions(int levels, uint64_t *count);
sol_status sol_normal_cells_near_sphere(int levels, double half_width, uint64_t *count);

/* ---- D5: the cells the best-fit search produces, under the rounding choices that decide ties ----
 * In exact arithmetic the search returns, for any direction, the first cell of least error along
 * the ray; a cell k*c (k odd) ties exactly with c, so only cells with gcd 1 could win, and the
 * image would be the distinct directions (minus the 8 cells (+-1,+-1,+-1)/255, below the first
 * probe). In floating point those ties break by last-bit noise, which depends on how the input is
 * prepared and on the precision, so the count has a spread; sol_normal_cells_bestfit measures it.
 * For every cell with r in [r_begin, r_end) (0 <= r_begin <= r_end <= 256), its centre
 * ((2r-255)/255, (2g-255)/255, (2b-255)/255) is searched (SOL_NORMAL_XYZ_BEST_FIT's search,
 * appendix A) with:
 *  - single: 0 double arithmetic, 1 float arithmetic as the appendix's HLSL;
 *  - input: SOL_BESTFIT_INPUT_UNIT, the centre normalised first (what sol_normal_encode does);
 *    SOL_BESTFIT_INPUT_RAW, the centre divided by its largest |component| only, as the appendix
 *    (`normal /= max(...)`) does; SOL_BESTFIT_INPUT_HALF, the centre rounded to half precision
 *    first (the appendix's argument is a half3), then as RAW.
 * out->image: distinct codes the searches return (the encoder's image over these centres);
 * out->fixed: cells whose centre returns the cell itself. Options zero = double, UNIT (NULL the
 * same); bad options or range: SOL_ERR_INVALID_ARG; SOL_ERR_NO_MEMORY (a 2 MB bitmap). Exact
 * integer counts: identical for any thread count. */
typedef enum sol_bestfit_input {
    SOL_BESTFIT_INPUT_UNIT = 0,
    SOL_BESTFIT_INPUT_RAW,
    SOL_BESTFIT_INPUT_HALF
} sol_bestfit_input;
typedef struct sol_bestfit_cells_options {
    int single;              /* 0 double, 1 float */
    sol_bestfit_input input; /* how the centre reaches the search */
} sol_bestfit_cells_options;
typedef struct sol_bestfit_cells {
    uint64_t image, fixed;
} sol_bestfit_cells;
sol_status sol_normal_cells_bestfit(const sol_bestfit_cells_options *opt, int r_begin, int r_end,
                                    sol_bestfit_cells *out);

#ifdef __cplusplus
}
#endif
#endif
