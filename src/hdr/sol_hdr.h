/* sol_hdr.h - HDR storage formats, tone maps and their inverses, 3D LUT colour grading,
 * CIEDE2000 and automatic exposure (claims D9-D12, M2, M4, S3, S6, S9).
 *
 * Units: "scene" values are linear radiance-like numbers >= 0; tone maps take x = c / l (the
 * colour c divided by the average frame luminance l, as on the talk's slide "HDR on consoles:
 * lower bound estimator") and return a LINEAR display value in [0, 1]. "Display codes" are the
 * 8-bit sRGB codes round(255 * srgb_encode(y)).
 *
 * Conventions as in sol_core.h: statuses, untouched outputs on error, no printing.
 */
#ifndef SOL_HDR_H
#define SOL_HDR_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================================
 * Small floats (bit-exact with the GPU definitions)
 * ====================================================================================== */

/* IEEE 754 binary16. Round to nearest, ties to even; denormals kept; |f| >= 65520 rounds to
 * +-Inf (IEEE overflow rule); Inf stays Inf; NaN becomes a quiet NaN with the sign kept
 * (0x7e00 | sign). -0.0 gives 0x8000. Exact for every input (no double rounding). */
uint16_t sol_half_from_float(float f);
/* Exact: every half is a float. */
float sol_half_to_float(uint16_t h);

/* Unsigned small floats of GL_EXT_packed_float / DXGI_FORMAT_R11G11B10_FLOAT: 5 exponent bits
 * (bias 15), no sign, 6 (11-bit) or 5 (10-bit) mantissa bits. Conversion as the extension
 * specifies it, with round-to-nearest-even as the rounding mode: negative values, -0.0 and -Inf
 * give 0; finite values above the largest finite value (65024 for 11 bits, 64512 for 10 bits)
 * give that value; +Inf gives +Inf; any NaN gives a positive NaN (exponent 31, mantissa 1). */
uint32_t sol_uf11_from_float(float f);
uint32_t sol_uf10_from_float(float f);
float sol_uf11_to_float(uint32_t bits);
float sol_uf10_to_float(uint32_t bits);

/* R11G11B10F: red in bits 0-10, green in bits 11-21, blue in bits 22-31 (D3D/GL layout). */
uint32_t sol_r11g11b10f_pack(const float rgb[3]);
void sol_r11g11b10f_unpack(uint32_t packed, float rgb[3]);

/* ======================================================================================
 * 8/10-bit HDR encodings
 * ====================================================================================== */

/* RGBM (RGBK) in RGBA8 (claim D9): m = ceil(255 * max(r,g,b) / range) / 255, each channel is
 * stored as the UNORM8 code of c / (m * range), alpha holds m. `range` is the largest value the
 * encoding represents (6 or 8 are common); values above it are clamped to it, negative values
 * and NaN to 0 (documented clamping, like a render target write). Black encodes as (0,0,0,0)
 * and decodes to 0. Errors: NULL pointers, range not finite or <= 0 (SOL_ERR_INVALID_ARG); decode
 * also SOL_ERR_OUT_OF_RANGE when a decoded value exceeds FLT_MAX (range > FLT_MAX; rgb untouched). */
sol_status sol_rgbm_encode(const float rgb[3], double range, uint8_t rgbm[4]);
sol_status sol_rgbm_decode(const uint8_t rgbm[4], double range, float rgb[3]);

/* Tesseract's fallback light buffer (claim S9): UNORM10 storing v / 2, so 0..2 with step
 * 2/1023. Negative and NaN give 0, values above 2 give 2. */
uint32_t sol_rgb10_scaled_encode(float v);
float sol_rgb10_scaled_decode(uint32_t code);

/* Two-channel linear depth (claim M2): depth = x + y / 255 with x, y UNORM8 codes / 255.
 * x = floor(255 d) / 255 and y = round(255 * frac(255 d)) (the hi/lo split the talk describes),
 * so the step is 1/65025 and the worst error 0.5/65025 over [0, 1]. d is clamped to [0, 1];
 * NaN gives 0. */
void sol_depth_rg8_encode(double depth, uint8_t xy[2]);
double sol_depth_rg8_decode(const uint8_t xy[2]);
/* The same split but with x written by a rounding UNORM8 write (x_code = round(255 d)) while y
 * still stores frac(255 d): what happens when a shader forgets to subtract the fraction before
 * the hardware rounds x. Kept to measure the edge error (one x step = 1/255). */
void sol_depth_rg8_encode_rounded_x(double depth, uint8_t xy[2]);

/* ======================================================================================
 * Tone maps (claims D10-D12, S3)
 * ====================================================================================== */

typedef enum sol_tonemap {
    SOL_TONEMAP_EXPONENTIAL,  /* 1 - exp(-x), the talk's exponential operator (D11) */
    SOL_TONEMAP_REINHARD,     /* x / (1 + x) */
    SOL_TONEMAP_FILMIC_HBD,   /* Hejl-Burgess-Dawson: g = x'(6.2x'+0.5)/(x'(6.2x'+1.7)+0.06),
                                 x' = max(0, x - 0.004), returned linear as g^2.2 (D12) */
    SOL_TONEMAP_FILMIC_SLIDE, /* the formula as printed on the talk's slide:
                                 (x'(6.2x'+0.5) / (x'(6.2(x'+1.7)+0.06)))^2.2, 0 at x' = 0 */
    SOL_TONEMAP_ACES_FIT,     /* Narkowicz: x(2.51x+0.03)/(x(2.43x+0.59)+0.14), clamped to 1 (S3) */
    SOL_TONEMAP_ACES_REF,     /* ACES 1.0 RRT + ODT Rec.709 100 nits dim, neutral input, BT.1886
                                 2.4 gamma removed (see sol_aces_reference) */
    SOL_TONEMAP_COUNT
} sol_tonemap;

/* Short name ("exponential", "filmic-hbd", ...); "unknown" for bad values. */
const char *sol_tonemap_name(sol_tonemap op);

/* Forward map of x = c / l to a linear display value in [0, 1].
 * x <= 0 (and -0.0) give 0; +Inf gives the curve's limit; NaN propagates (returns NaN). */
double sol_tonemap_apply(sol_tonemap op, double x);

/* Closed-form inverse: the smallest x >= 0 with apply(x) >= y (for the slide's filmic, whose
 * curve jumps from 0 to (0.5/10.6)^2.2 just above the toe, smaller y give the toe 0.004).
 * SOL_TONEMAP_ACES_REF has no closed form here: it is solved with the safeguarded Newton of
 * sol_tonemap_inverse_iterative to a relative 1e-14.
 * Errors: NULL x, op out of range (SOL_ERR_INVALID_ARG); y NaN (SOL_ERR_NONFINITE); y < 0 or
 * y at/above the curve's supremum (SOL_ERR_OUT_OF_RANGE: 1 for the asymptotic curves). Every y
 * below the supremum gives a finite x: the filmic inverses form 1 - y^(1/2.2) without rounding
 * it to 0, so y = 1 - 2^-53 gives x ~ 4e15, not +Inf. */
sol_status sol_tonemap_inverse(sol_tonemap op, double y, double *x);

/* Iterative inverse (for operators without a closed form, and to measure accuracy vs time).
 * Brackets [0, hi] by doubling, then runs `method`: bisection, or Newton with a bisection
 * safeguard (numeric derivative). Stops when the bracket is narrower than `tolerance * x`, when
 * no double lies strictly inside it (x = its upper end: the smallest double reaching y), or
 * after `max_iterations`. Zero option fields mean: bisection, tolerance 1e-12, 200 iterations. */
typedef enum sol_root_method { SOL_ROOT_BISECTION = 0, SOL_ROOT_SAFE_NEWTON } sol_root_method;
typedef struct sol_root_options {
    sol_root_method method;
    double tolerance;   /* relative width of the final bracket; 0 = 1e-12 */
    int max_iterations; /* 0 = 200 */
} sol_root_options;
/* Errors as sol_tonemap_inverse, plus SOL_ERR_NO_CONVERGENCE when max_iterations ran out (x is
 * then still written with the best estimate, and *iterations with the count). `options` and
 * `iterations` may be NULL. */
sol_status sol_tonemap_inverse_iterative(sol_tonemap op, double y, const sol_root_options *options, double *x,
                                         int *iterations);

/* HDR lower bound of the talk's dynamic range scaling (D10): c_min / l = inverse(threshold),
 * the darkest scene value that still reaches the display threshold (the talk: 0.5/255 = 1/510).
 * `threshold` in (0, 1); errors as sol_tonemap_inverse. */
sol_status sol_tonemap_lower_bound(sol_tonemap op, double threshold, double *c_min_over_l);

/* ACES reference tone scale for a neutral (grey) scene value x in ACES2065-1 (0.18 = mid grey):
 * RRT (segmented spline c5) then ODT (segmented spline c9, 48-nit cinema parameters, black 0.02 and
 * white 48 mapped to 0..1, dim-surround gamma 0.9811 on Y) as in ACES 1.0's
 * ODT.Academy.Rec709_100nits_dim, output linear (before the BT.1886 inverse-EOTF), clamped to
 * [0, 1]. For a grey input the glow, red-modifier, desaturation and gamut steps are identities,
 * so the chain is this scalar function. x <= 0 is clamped like the reference (to HALF_MIN). */
double sol_aces_reference(double x);

/* Stephen Hill's fit of the ACES RRT + ODT ("ACESFitted", published with the BakingLab sample,
 * 2016): the second ACES reference of claim S3. sol_aces_hill_curve is the per-channel rational
 * RRTAndODTFit (v (v + 0.0245786) - 0.000090537) / (v (0.983729 v + 0.4329510) + 0.238081), defined
 * for every finite v (the denominator is >= 0.19); sol_aces_hill_fit applies Hill's input matrix
 * (linear sRGB -> AP1 with the RRT's saturation), the curve per channel, the output matrix (the
 * ODT's saturation -> linear sRGB) and clamps to [0, 1]. Both matrices have rows summing to 1
 * (to 5 digits), so a grey input gives the curve's value on each channel. Output is display-linear
 * (before the sRGB encoding). NaN input, or +Inf and -Inf in one input, give NaN on the channels
 * they reach; every other input (huge values and +-Inf included) gives a value in [0, 1].
 * `out` may alias `rgb`. */
double sol_aces_hill_curve(double v);
void sol_aces_hill_fit(const double rgb[3], double out[3]);

/* 8-bit display code (sRGB curve from sol_core.h) of a linear value: round(255 * sol_srgb_encode(y)). */
int sol_display_code8(double linear);

/* ======================================================================================
 * Colour difference and grading (claim M4)
 * ====================================================================================== */

/* sRGB-encoded [0,1] RGB (D65) to CIE L*a*b* (D65 white). Inputs outside [0,1] are clamped. */
void sol_srgb_to_lab(const double srgb[3], double lab[3]);
/* CIEDE2000 colour difference (Sharma, Wu, Dalal 2005), kL = kC = kH = 1. */
double sol_ciede2000(const double lab1[3], const double lab2[3]);

/* A global grading transform on sRGB-encoded colours in [0, 1] (the "rgb cube to rgb cube"
 * mappings of the talk's colour-grading slide). Zero fields mean identity. Applied in this order:
 * lift/gamma/gain per channel, contrast S-curve around 0.5, saturation about Rec.709 luma,
 * hue rotation about the grey axis. Output clamped to [0, 1]. */
typedef struct sol_grade {
    double saturation;  /* multiplier minus 1: 0 = unchanged, -1 = grey, 0.5 = 1.5x */
    double contrast;    /* 0 = linear; > 0 steepens a smoothstep-blended S-curve, in [0, 1] */
    double lift[3];     /* out = gain * (x + lift * (1 - x))^(1 / gamma); lift 0 = none */
    double gamma[3];    /* 0 = 1 */
    double gain[3];     /* 0 = 1 */
    double hue_degrees; /* rotation about the grey axis */
} sol_grade;
/* grade must not be NULL; NaN inputs are treated as 0. */
void sol_grade_apply(const sol_grade *grade, const double in[3], double out[3]);

/* A size^3 RGB table on [0,1]^3, red index fastest: entry (r,g,b) at 3*(r + size*(g + size*b)). */
typedef struct sol_lut3d {
    int size;
    float *data;
} sol_lut3d;

/* Any colour transform, for baking. */
typedef void (*sol_color_fn)(const double in[3], double out[3], void *ctx);

/* Bakes fn at the lattice points i/(size-1). size 2..256. Errors: NULL fn/out, bad size
 * (SOL_ERR_INVALID_ARG), SOL_ERR_NO_MEMORY. Free with sol_lut3d_free. */
sol_status sol_lut3d_bake(int size, sol_color_fn fn, void *ctx, sol_lut3d *out);
void sol_lut3d_free(sol_lut3d *lut);

typedef enum sol_lut_interp { SOL_LUT_TRILINEAR = 0, SOL_LUT_TETRAHEDRAL } sol_lut_interp;
/* Looks up one colour (inputs clamped to [0,1], NaN treated as 0). Trilinear blends the 8 cell
 * corners; tetrahedral splits the cell into 6 tetrahedra along the grey diagonal and blends 4
 * corners (exact on the grey axis for any grey-preserving table). No checks: lut must be valid. */
void sol_lut3d_apply(const sol_lut3d *lut, sol_lut_interp interp, const double in[3], double out[3]);

/* The talk's chart workflow: the table unwrapped into `size` slices of size x size placed side by
 * side (slice b at x offset b*size; inside a slice red runs along x, green along y), written
 * into `image` (3 or 4 channels) at (x0, y0). Errors: NULL, image too small or < 3 channels
 * (SOL_ERR_INVALID_ARG). */
sol_status sol_lut3d_chart_write(const sol_lut3d *lut, sol_image *image, int x0, int y0);
/* Reads such a chart back into a new table of the given size. Errors as above + NO_MEMORY. */
sol_status sol_lut3d_chart_read(const sol_image *image, int x0, int y0, int size, sol_lut3d *out);

/* .cube 3D LUT files (Adobe "Cube LUT Specification" 1.0, as Resolve and grading tools write
 * them): keywords TITLE "text", LUT_3D_SIZE N (2..256), DOMAIN_MIN/DOMAIN_MAX r g b (default 0 0 0
 * and 1 1 1), Resolve's LUT_3D_INPUT_RANGE lo hi (the same domain on all channels), '#' comments
 * and blank lines anywhere; then exactly N^3 lines "r g b", red changing fastest (sol_lut3d's
 * order). Keywords must come before the data; other keywords there are ignored.
 * Reading checks N^3 against `limits` (12 bytes per entry) before allocating.
 * Errors: SOL_ERR_FORMAT (no LUT_3D_SIZE, a bad line, wrong entry count, DOMAIN_MIN >= MAX),
 * SOL_ERR_UNSUPPORTED (a 1D LUT), SOL_ERR_LIMIT, SOL_ERR_IO, SOL_ERR_NO_MEMORY; *bad_line (may be
 * NULL) = the 1-based line at fault (0 when no single line is), *problem (may be NULL) a static
 * description. `info` may be NULL. Free the table with sol_lut3d_free. */
typedef struct sol_cube_info {
    char title[128]; /* truncated to 127 bytes */
    double domain_min[3], domain_max[3];
} sol_cube_info;
sol_status sol_cube_parse(const char *text, size_t length, const sol_read_limits *limits, sol_lut3d *out,
                          sol_cube_info *info, size_t *bad_line, const char **problem);
sol_status sol_cube_read(const char *path, const sol_read_limits *limits, sol_lut3d *out, sol_cube_info *info,
                         size_t *bad_line, const char **problem);
/* Writes `lut` on the domain [0,1]^3 with %.9g entries (a float round-trips), to a temporary name
 * renamed on success. title may be NULL. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (bad
 * table), SOL_ERR_IO. */
sol_status sol_cube_write(const char *path, const sol_lut3d *lut, const char *title);

/* ======================================================================================
 * Automatic exposure (claim S6)
 * ====================================================================================== */

/* EV100 of a luminance (cd/m^2): L = 0.125 * 2^EV100 (Narkowicz's notes, after Reed 2014).
 * Plain math at the edges: L = 0 gives -Inf, L < 0 NaN; an EV100 above ~1026 gives +Inf (the
 * luminance exceeds DBL_MAX). sol_exposure_from_luminance is the checked form. */
double sol_ev100_from_luminance(double luminance);
double sol_luminance_from_ev100(double ev100);
/* Krawczyk, Myszkowski, Seidel 2005 key value: 1.03 - 2 / (log10(L + 1) + 2), in [0.03, 1.03];
 * L <= 0 is taken as 0 (0.03), +Inf gives 1.03, NaN gives NaN. */
double sol_krawczyk_key(double luminance);

/* Histogram metering: log2-luminance histogram of `bins` bins over [ev_min, ev_max) (EV100),
 * each pixel split linearly between its two nearest bins; the darkest `skip_dark` and
 * brightest `skip_bright` fractions of the pixels are dropped and the rest averaged in log2
 * (a geometric mean). Zero fields mean 64 bins, EV -8..24, skip_dark 0.6, skip_bright 0.1;
 * a negative skip means "skip none". Non-finite or negative luminances are ignored (counted in
 * *ignored when not NULL). Errors: NULL, n == 0 or no usable pixel (SOL_ERR_INVALID_ARG),
 * skip_dark + skip_bright >= 1 or ev_max <= ev_min (SOL_ERR_INVALID_ARG), SOL_ERR_NO_MEMORY. */
typedef struct sol_meter_options {
    int bins;
    double ev_min, ev_max;
    double skip_dark, skip_bright;
} sol_meter_options;
sol_status sol_histogram_meter(const float *luminance, size_t n, const sol_meter_options *options,
                               double *metered_luminance, size_t *ignored);

/* Exponential temporal adaptation: prev + (target - prev) * (1 - exp(-dt * rate)). dt and rate
 * in seconds and 1/seconds; non-finite or negative dt/rate return prev unchanged. Finite prev
 * and target give a finite value between them, even +-DBL_MAX apart. */
double sol_adapt_exponential(double previous, double target, double dt, double rate);

/* Exposure multiplier 0.18 * 2^ec / L for a metered luminance L and a compensation ec in EV
 * (Narkowicz's form with an 18% middle grey), computed scaled so that any representable answer
 * is returned (ec = 1e4 with L = 1e300 is fine; an answer below the smallest subnormal is 0).
 * Errors: NULL, L or ec not finite (SOL_ERR_NONFINITE), L <= 0 (SOL_ERR_INVALID_ARG), an answer
 * above DBL_MAX (SOL_ERR_OUT_OF_RANGE; *exposure untouched). */
sol_status sol_exposure_from_luminance(double luminance, double compensation_ev, double *exposure);

#ifdef __cplusplus
}
#endif
#endif
