/* sol_textures.h - color textures: transfer functions (pure power gamma, sRGB, the Xbox 360
 * piecewise-linear gamma), 8-bit quantisation, the Xbox 360 texture-cache de-gamma, equal-density
 * points of linear vs gamma storage, a BC1 (DXT1) encoder and decoder, per-channel range
 * ("histogram") renormalisation and the linear/gamma storage classifier of the talk's
 * color-texture section (claims T1-T7).
 *
 * Conventions: "linear" values are in [0,1] (light-linear albedo), "encoded" values are the
 * transfer function's output in [0,1] (what an 8-bit texel stores, divided by 255). Every function
 * that can fail returns a sol_status and leaves its outputs untouched on error. */
#ifndef SOL_TEXTURES_H
#define SOL_TEXTURES_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- transfer functions (transfer.c) ------------------------------------------------------ */

typedef enum sol_transfer_kind {
    SOL_TRANSFER_LINEAR = 0, /* identity: the texture stores linear values */
    SOL_TRANSFER_POWER,      /* encoded = linear^(1/gamma) */
    SOL_TRANSFER_SRGB,       /* IEC 61966-2-1: 12.92 x below 0.0031308, else 1.055 x^(1/2.4) - 0.055 */
    SOL_TRANSFER_X360_PWL,   /* Xbox 360 (Xenos) piecewise-linear gamma, four segments, see below */
    SOL_TRANSFER_KIND_COUNT
} sol_transfer_kind;

/* A transfer curve. Zero-initialised = linear; `gamma` is used by SOL_TRANSFER_POWER only
 * (0 = 2.2; must be finite and > 0).
 *
 * SOL_TRANSFER_X360_PWL is the continuous curve through the Xenos knots, in (linear, encoded)
 * pairs: (0,0), (64/1023, 64/255), (128/1023, 96/255), (512/1023, 192/255), (1,1). The knots and
 * the 10-bit-linear/8-bit-gamma units are those of Xenia's xenos.cc PWLGammaToLinear /
 * LinearToPWLGamma (which reproduce the Direct3D 9 code of Xbox 360 titles and the Source
 * Engine's X360GammaToLinear / X360LinearToGamma). The hardware's exact integer mapping is
 * sol_x360_pwl_gamma8_to_linear10 below; the continuous curve differs from it by at most 4/1023 (in
 * the top segment, where the hardware's truncation fix-up stretches 504 linear steps to 511). */
typedef struct sol_transfer {
    sol_transfer_kind kind;
    double gamma;
} sol_transfer;

/* encoded = curve(linear). Linear values outside [0,1] are clamped (as the GPU saturates).
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (unknown kind, bad gamma), SOL_ERR_NONFINITE
 * (NaN or infinite input). */
sol_status sol_transfer_encode(const sol_transfer *curve, double linear, double *encoded);
/* linear = curve^-1(encoded); the inverse of sol_transfer_encode on [0,1]. Same errors. */
sol_status sol_transfer_decode(const sol_transfer *curve, double encoded, double *linear);
/* d encoded / d linear at `linear` in [0,1] (right derivative at the PWL knots). The quantisation
 * step of an 8-bit encoded texture, in linear units, is 1 / (255 * slope): the slope is the
 * storage's code density relative to linear storage. A pure power curve with gamma > 1 has an
 * infinite slope at 0: SOL_ERR_OUT_OF_RANGE there. Other errors as sol_transfer_encode, and
 * linear outside [0,1] gives SOL_ERR_OUT_OF_RANGE. */
sol_status sol_transfer_slope(const sol_transfer *curve, double linear, double *slope);
/* 8-bit texel code of a linear value: round(255 * encode(linear)). Errors as sol_transfer_encode. */
sol_status sol_transfer_quantize8(const sol_transfer *curve, double linear, uint8_t *code);
/* Linear value of an 8-bit code: decode(code / 255). */
sol_status sol_transfer_dequantize8(const sol_transfer *curve, uint8_t code, double *linear);

/* Equal-density points (claims T3, T5): the linear values where the curve's slope is 1, i.e.
 * where 8-bit gamma storage and 8-bit linear storage have the same quantisation step. Gamma
 * storage is denser below, linear storage above. Returns the interval [lo, hi] of linear values
 * whose slope s satisfies |s - 1| <= rel_tol: for a smooth curve and rel_tol = 0, lo = hi = the
 * root; for the PWL curve a whole segment can qualify (its third segment has slope
 * 1023/1020). If no value qualifies, lo = hi = the point where the slope crosses 1.
 * Errors: SOL_ERR_NULL_ARG; SOL_ERR_INVALID_ARG for the linear curve (every point has slope 1),
 * a power curve with gamma <= 1 (slope never decreases through 1), rel_tol < 0 or not finite. */
sol_status sol_transfer_equal_density(const sol_transfer *curve, double rel_tol, double *lo, double *hi);

/* The Xbox 360's exact integer PWL mapping from an 8-bit gamma code to a 10-bit linear value
 * (0..1023), with its truncation fix-up (Xenia xenos.cc PWLGammaToLinear). */
uint16_t sol_x360_pwl_gamma8_to_linear10(uint8_t gamma_code);
/* Claim T6: a gamma texel fetched without the _AS16 suffix is de-gammaed and stored back into
 * 8 bits (linear) in the texture cache. Returns that 8-bit linear code: the 10-bit linear value
 * rounded to the nearest 8-bit code. (The rounding mode of the cache is not documented publicly;
 * round-to-nearest is sol's assumption.) */
uint8_t sol_x360_cache_degamma8(uint8_t gamma_code);

/* ---- BC1 / DXT1 (bc1.c) ------------------------------------------------------------------- */

/* Decoding rule (sol_bc1_decode_block): endpoints are expanded from 5:6:5 to 8 bits by bit
 * replication; with c0 > c1 (as 16-bit integers) the palette is c0, c1, (2 c0 + c1)/3,
 * (c0 + 2 c1)/3, each channel rounded to the nearest integer ((2a + b + 1) / 3 in integers);
 * with c0 <= c1 it is c0, c1, (c0 + c1)/2 rounded half up, and transparent black. The D3D10
 * functional specification defines the 2/3, 1/3 interpolation in floating point and allows a
 * small tolerance; round-to-nearest of the exact value is the centre of that tolerance. */
enum { SOL_BC1_BLOCK_BYTES = 8 };

typedef enum sol_bc1_effort {
    SOL_BC1_EFFORT_DEFAULT = 0, /* = SOL_BC1_CLUSTER */
    SOL_BC1_RANGE,              /* endpoints at the bounding box corners along the main diagonal */
    SOL_BC1_PCA,                /* extremes of the projections onto the principal axis */
    SOL_BC1_PCA_REFINE,         /* PCA, then `iterations` rounds of index assignment + least squares */
    SOL_BC1_CLUSTER,            /* every ordered 4-cluster partition along the axis, least squares on
                                   the 5:6:5 grid, re-ordered along the new axis up to `iterations` times */
    SOL_BC1_CLUSTER_SEARCH,     /* SOL_BC1_CLUSTER, then hill climbing of the six endpoint codes by +-1 */
    SOL_BC1_EFFORT_COUNT
} sol_bc1_effort;

typedef struct sol_bc1_options {
    sol_bc1_effort effort; /* 0 = SOL_BC1_CLUSTER */
    int iterations;        /* refinement rounds for PCA_REFINE / CLUSTER*; 0 = 4; max 64 */
} sol_bc1_options;

/* Bytes of the BC1 data of a width x height image: ceil(w/4) * ceil(h/4) * 8, computed without
 * int overflow (INT_MAX x 1 gives 536870912 * 8). 0 if w or h <= 0, or if the size does not fit
 * a size_t (only possible where size_t has 32 bits). */
size_t sol_bc1_size(int width, int height);
/* Encodes one 4x4 block of linear-in-storage values (whatever the texture stores, each in
 * [0,1], row-major texels, RGB). Always uses the four-color mode (c0 > c1) unless the block is one
 * color whose endpoints coincide. The error minimised is the sum of squared 8-bit RGB
 * differences (uniform weights). Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE, SOL_ERR_OUT_OF_RANGE
 * (a value outside [0,1]), SOL_ERR_INVALID_ARG (bad options). */
sol_status sol_bc1_encode_block(const float rgb[16][3], const sol_bc1_options *options, uint8_t block[8]);
/* Decodes one block into 8-bit RGBA texels (rule above). Never fails. */
void sol_bc1_decode_block(const uint8_t block[8], uint8_t rgba[16][4]);
/* Encodes an image (channels >= 3; channels beyond RGB are ignored). Images whose size is not a
 * multiple of 4 are padded by repeating the last column / row. `blocks` holds sol_bc1_size bytes;
 * blocks are in row-major block order. Parallel over blocks (identical for any thread count).
 * Errors as sol_bc1_encode_block, plus SOL_ERR_INVALID_ARG for channels < 3. */
sol_status sol_bc1_encode(const sol_image *image, const sol_bc1_options *options, uint8_t *blocks);
/* Decodes into a newly allocated RGB image (values code / 255); `out` is written on success only.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (size <= 0), SOL_ERR_NO_MEMORY. */
sol_status sol_bc1_decode(const uint8_t *blocks, int width, int height, sol_image *out);

/* ---- range renormalisation (renorm.c), claims T1, T2 ---------------------------------------- */

/* Per-channel range of a texture: the shader restores value = lo + stored * (hi - lo)
 * (two constants per texture: a scale and a bias). */
typedef struct sol_renorm {
    int channels;
    float lo[4], hi[4];
} sol_renorm;

/* Per-channel min and max. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (empty image),
 * SOL_ERR_NONFINITE. */
sol_status sol_renorm_fit(const sol_image *image, sol_renorm *out);
/* In place: stored = (value - lo) / (hi - lo), clamped to [0,1]; a channel with hi == lo stores 0.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (channel count differs), SOL_ERR_NONFINITE
 * (checked before anything is written). */
sol_status sol_renorm_apply(const sol_renorm *range, sol_image *image);
/* In place: value = lo + stored * (hi - lo), the shader's reconstruction. Both work for any
 * finite range, [-FLT_MAX, FLT_MAX] included (the span is then taken in double). Errors as apply,
 * plus SOL_ERR_OUT_OF_RANGE when a result would exceed FLT_MAX (a stored value far outside
 * [0, 1]); the image is then untouched. */
sol_status sol_renorm_undo(const sol_renorm *range, sol_image *image);

/* ---- linear vs gamma storage (storage.c), claim T4 ------------------------------------------ */

typedef enum sol_storage { SOL_STORAGE_GAMMA = 0, SOL_STORAGE_LINEAR } sol_storage;

typedef struct sol_storage_options {
    double median;    /* linear value above which linear storage is denser; 0 = the equal-density
                         point of the 2.2 power curve (0.2356), not the talk's 5/11 */
    double threshold; /* store linear if more than this fraction of values is above the median;
                         0 = 0.75 (the talk's rule of thumb) */
} sol_storage_options;

/* Classifies a texture given in linear values (16-bit or float source): counts the channel values
 * (RGB, or all channels if fewer than 3) above `median` and picks linear storage when their share
 * exceeds `threshold`. `fraction_above` may be NULL. Errors: SOL_ERR_NULL_ARG,
 * SOL_ERR_INVALID_ARG (empty image, median or threshold outside (0,1)), SOL_ERR_NONFINITE. */
sol_status sol_storage_classify(const sol_image *linear_image, const sol_storage_options *options,
                                sol_storage *choice, double *fraction_above);

#ifdef __cplusplus
}
#endif
#endif
