/* sol_lighting.h - lighting details from the notes beside the talk: split-sum DFG term and its
 * analytical fits (S4), hemicube texel weights (S7), the Tesseract 4-tap PCF (S8), 4- vs
 * 6-channel light accumulation (S2) and clip volumes for unshadowed deferred lights (D13).
 *
 * Conventions (see sol_core.h): every fallible function returns a sol_status, leaves its outputs
 * untouched on error, never prints. Angles in radians, directions are unit vectors in a frame whose
 * +z is the surface normal unless a function says otherwise. */
#ifndef SOL_LIGHTING_H
#define SOL_LIGHTING_H

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================= S4: split-sum DFG term (Karis 2013, Narkowicz 2014) =======================
 * The split-sum approximation factors image-based specular lighting into a prefiltered
 * environment and DFG(alpha, n.v) = F0 * scale + bias with
 *   scale = integral over l of  f(v,l)/F * (1 - Fc) * n.l dl,   bias = integral of f/F * Fc * n.l dl,
 * Fc = (1 - v.h)^5 (Schlick), f = D G F / (4 n.v n.l), D = GGX with width alpha, G = separable
 * Smith for GGX. Gloss maps to alpha by Narkowicz's remap alpha = (1 - gloss)^4. */

/* alpha = (1 - gloss)^4; gloss is clamped to [0,1]; NaN gives NaN. */
double sol_dfg_alpha_from_gloss(double gloss);

/* Reference DFG by deterministic quadrature over the half vector h, distributed by the GGX inverse
 * CDF (importance sampling without randomness): per row of the CDF, the azimuth of h is integrated
 * only where n.l > 0 (a closed-form interval), and the rows are split where that interval starts to
 * shrink and where it vanishes (theta_h = pi/4 -+ theta_v/2), with rows clustered at both ends of the
 * second band. `samples` rows and `samples` azimuths per band (2 samples^2 evaluations); the error
 * falls roughly as 1/samples (s4_dfg_fit measures it) and the result is reproducible.
 * alpha in [0,1], n_dot_v in [0,1] (n_dot_v = 0 is the grazing limit; with alpha = 0 as well the
 * integral is degenerate and gives scale = bias = 0; alpha = 0 otherwise gives Schlick's Fresnel
 * exactly), samples in 1..65536.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE (NaN/Inf input), SOL_ERR_INVALID_ARG (out of range). */
sol_status sol_dfg_integrate(double alpha, double n_dot_v, int samples, double *scale, double *bias);

/* The form of Narkowicz's "EnvDFGPolynomial" with x = gloss, y = n.v:
 *   bias  = saturate(min(b0 x + b1 x^2, b2 + b3 y + b4 y^2 + b5 y^3)),
 *   delta = saturate(d0 + d1 x + d2 y + d3 x^2 + d4 x y + d5 y^2 + d6 x^3),  scale = delta - bias. */
typedef struct sol_dfg_polynomial {
    double bias[6];
    double delta[7];
} sol_dfg_polynomial;

/* His published constants. */
extern const sol_dfg_polynomial sol_dfg_polynomial_narkowicz;

/* Evaluates the form with the given constants. Inputs in [0,1]. Errors as sol_dfg_integrate. */
sol_status sol_dfg_eval_polynomial(const sol_dfg_polynomial *p, double gloss, double n_dot_v, double *scale,
                                   double *bias);
/* Narkowicz's polynomial fit with his published constants. Errors as sol_dfg_integrate. */
sol_status sol_dfg_fit_polynomial(double gloss, double n_dot_v, double *scale, double *bias);

/* Refits the constants of the same form to `count` samples (gloss, n.v, scale, bias) by least
 * squares, without the saturates: delta is linear in its constants; the bias's min of two branches
 * is fitted by alternating branch assignment and per-branch least squares, starting from the
 * published constants. Deterministic. Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE,
 * SOL_ERR_INVALID_ARG (count < 16, inputs outside [0,1]), SOL_ERR_NO_MEMORY,
 * SOL_ERR_NO_CONVERGENCE (singular system). */
sol_status sol_dfg_refit_polynomial(const double *gloss, const double *n_dot_v, const double *scale, const double *bias,
                                    size_t count, sol_dfg_polynomial *out);
/* Narkowicz's "EnvDFGLazarov": Lazarov 2013's analytical form refitted by Narkowicz for GGX and
 * his gloss remap, with his published constants. Inputs in [0,1]. Errors as sol_dfg_integrate. */
sol_status sol_dfg_fit_lazarov(double gloss, double n_dot_v, double *scale, double *bias);

/* A DFG lookup table: size x size texels of (scale, bias) indexed by gloss (x) and n.v (y), texel
 * centres at (i + 0.5) / size, read with clamp-to-edge bilinear filtering like a GPU would. */
typedef struct sol_dfg_lut {
    int size;
    float *scale_bias; /* size * size * 2 floats, row y = n.v index */
} sol_dfg_lut;

/* Builds the table with sol_dfg_integrate(samples) at each texel centre (OpenMP over rows;
 * identical results for any thread count). size in 2..4096.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG, SOL_ERR_NO_MEMORY. */
sol_status sol_dfg_lut_build(int size, int samples, sol_dfg_lut *out);
/* Bilinear lookup. Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE, SOL_ERR_INVALID_ARG (input outside
 * [0,1] or an empty table). */
sol_status sol_dfg_lut_sample(const sol_dfg_lut *lut, double gloss, double n_dot_v, double *scale, double *bias);
/* Frees the table and zeroes the struct; safe on NULL or a zeroed struct. */
void sol_dfg_lut_free(sol_dfg_lut *lut);

/* ======================= S7: hemicube and single-plane texel weights =======================
 * A face is the plane z = 1 seen from the origin; a texel is the rectangle [x0,x1] x [y0,y1]. */

/* Solid angle subtended by the rectangle [0,x] x [0,y] of the plane z = 1 (signed like x*y):
 * atan2(x*y, sqrt(x^2 + y^2 + 1)) (the "ElementArea" of Narkowicz's note, after Driscoll 2012). */
double sol_plane_element_area(double x, double y);
/* Cosine-weighted solid angle (projected solid angle about +z) of the rectangle [0,x] x [0,y] of
 * the plane z = 1: the integral of dA / (1 + u^2 + v^2)^2, in closed form
 *   x/(2 sqrt(1+x^2)) atan(y/sqrt(1+x^2)) + y/(2 sqrt(1+y^2)) atan(x/sqrt(1+y^2)).
 * Signed like x*y. */
double sol_plane_cosine_area(double x, double y);
/* Projected solid angle about +z of the rectangle u in [0,u], z in [z0,z1] of a side face x = 1
 * (a hemicube side face, z being the height along the normal):
 *   1/2 [ atan(u/sqrt(1+z0^2))/sqrt(1+z0^2) - atan(u/sqrt(1+z1^2))/sqrt(1+z1^2) ]. */
double sol_side_cosine_area(double u, double z0, double z1);

/* Per-texel weights of one texel of a face, without normalisation. */
typedef struct sol_texel_weight {
    double solid_angle;      /* exact, by the ElementArea formula */
    double cosine_at_centre; /* solid_angle * cos(theta at the texel centre): Narkowicz's weight */
    double cosine_exact;     /* the exact projected solid angle of the texel */
} sol_texel_weight;

/* Weights of a size x size texel image covering [-half_extent, half_extent]^2 of the plane z = 1
 * (the single-plane capture: half_extent 2 gives the 2*atan(2) = 126.87 degree field of view; a
 * hemicube's front face has half_extent 1). `weights` has size*size entries, row-major.
 * size in 1..65536, half_extent finite and > 0. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG,
 * SOL_ERR_NONFINITE. */
sol_status sol_plane_weights(int size, double half_extent, sol_texel_weight *weights);

/* Sums of the weights of a whole hemicube with size x size texels on the front face (size even, so
 * each of the 4 side faces is size x size/2 texels): the exact sums are 2*pi (solid angle) and pi
 * (projected solid angle). Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (size odd or outside
 * 2..65536). */
sol_status sol_hemicube_weight_sums(int size, double *solid_angle, double *cosine_at_centre, double *cosine_exact);

/* ======================= S8: 3x3 weighted-box PCF (Tesseract) =======================
 * A shadow map is a width x height array of depths; a comparison "lit" is 1 when the receiver's
 * depth <= the stored depth. Coordinates are in texels with texel (i,j) covering [i,i+1] x [j,j+1]
 * (texture-rectangle convention), so texel centres are at i + 0.5. */
typedef enum sol_pcf_method {
    SOL_PCF_BOX_EXACT = 0,    /* 16 comparisons weighted by the 3x3-texel box's overlap areas */
    SOL_PCF_BILINEAR4_EXACT,  /* 4 bilinear comparison taps placed with divisions (exact box) */
    SOL_PCF_BILINEAR4_FAST,   /* Tesseract's 4 taps: tap positions without division */
    SOL_PCF_METHOD_COUNT
} sol_pcf_method;

/* The effective 1D weights (sum 3) that a method gives to texels i-1, i, i+1, i+2 when the sample
 * point is at i + 0.5 + f, f in [0,1). The box: (1-f, 1, 1, f). Tesseract's fast taps place the
 * two bilinear taps at fractions (1+f)/2 and f/2 instead of 1/(2-f) and f/(1+f), giving
 * ((2-f)(1-f)/2, (2-f)(1+f)/2, (1+f)(2-f)/2, (1+f)f/2): slightly more weight in the middle.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE, SOL_ERR_INVALID_ARG (f outside [0,1], bad method). */
sol_status sol_pcf_weights_1d(sol_pcf_method method, double f, double weights[4]);

/* Filtered shadow value in [0,1] at (x, y) for a receiver at `depth`, sampling `map` (width x height
 * depths, row-major) like a GPU shadow sampler: clamp-to-edge addressing, bilinear taps blend the
 * 0/1 comparison results of their 4 texels. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (sizes
 * < 1, bad method), SOL_ERR_NONFINITE (x, y or depth NaN/Inf). */
sol_status sol_pcf_filter(const float *map, int width, int height, double x, double y, double depth,
                          sol_pcf_method method, double *lit);

/* ======================= S2: light accumulation in 4 or 6 channels (Mittring 2009) =======================
 * Deferred lighting accumulates, per pixel, diffuse light D (RGB) and specular light S (RGB):
 * 6 channels. The 4-channel layout keeps D (RGB) and one specular "strength" A = sum of the
 * specular luminances, and reconstructs S ~ D * A / lum(D) ("specular approximated by
 * diffuse * strength"): right when every light has the same colour, wrong in hue otherwise. */

/* Rec. 709 luminance of linear RGB. */
double sol_luminance(const double rgb[3]);

typedef struct sol_light_accum {
    double diffuse[3];  /* sum over lights of colour * diffuse term */
    double specular[3]; /* sum of colour * specular term (6-channel layout) */
    double strength;    /* sum of lum(colour) * specular term (4-channel layout's alpha) */
} sol_light_accum;

/* Adds one light's contribution: colour (linear RGB, >= 0), its diffuse and specular terms (>= 0,
 * e.g. n.l and the normalised Phong lobe times n.l). Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE,
 * SOL_ERR_INVALID_ARG (negative input). */
sol_status sol_light_accum_add(sol_light_accum *acc, const double colour[3], double diffuse, double specular);
/* Specular RGB as the 4-channel layout reconstructs it: D * A / lum(D); where lum(D) is 0 (no
 * diffuse light, e.g. n.l = 0) the hue is unknown and it returns grey A * (1,1,1).
 * Errors: SOL_ERR_NULL_ARG. */
sol_status sol_light_accum_specular4(const sol_light_accum *acc, double specular[3]);

/* ======================= D13: clip volumes for unshadowed deferred lights =======================
 * A floor plan of rooms: the floor z = 0, vertical walls of height wall_height given as 2D segments,
 * each optionally with one door opening (an interval along the segment, full height up to
 * door_height). A point light at `light` (x, y, z) of radius `radius` lights floor points with the
 * irradiance falloff cos / d^2 times a smooth window (1 - (d/radius)^2)^2. */
typedef struct sol_wall {
    double x0, y0, x1, y1;       /* the segment */
    double door_t0, door_t1;     /* door along the segment, as fractions 0..1; equal = no door */
    double door_height;          /* top of the door opening */
} sol_wall;

typedef struct sol_room_scene {
    const sol_wall *walls;
    int wall_count;
    double wall_height;
    double light[3];
    double radius;
} sol_room_scene;

/* How a floor point is lit. */
typedef enum sol_light_mode {
    SOL_LIGHT_UNSHADOWED = 0, /* deferred light without shadows: everything inside the radius */
    SOL_LIGHT_CLIPPED,        /* unshadowed, masked by the clip volume (stencil test) */
    SOL_LIGHT_SHADOWED        /* reference: ray-traced visibility to the light */
} sol_light_mode;

/* An axis-aligned clip volume in the floor plane: the light only lands where x0<=x<=x1, y0<=y<=y1. */
typedef struct sol_clip_box {
    double x0, y0, x1, y1;
} sol_clip_box;

/* Irradiance at floor point (x, y) (normal +z). `clip` is used by SOL_LIGHT_CLIPPED only (it may be
 * NULL otherwise). Distances are scaled before squaring, so any finite scene gives the
 * representable answer. Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE, SOL_ERR_INVALID_ARG (radius <= 0,
 * light at or below the floor, bad mode, negative wall count), SOL_ERR_OUT_OF_RANGE (the
 * irradiance exceeds DBL_MAX, e.g. a light 1e-300 right above the point; *irradiance untouched). */
sol_status sol_room_irradiance(const sol_room_scene *scene, const sol_clip_box *clip, sol_light_mode mode,
                               double x, double y, double *irradiance);

#ifdef __cplusplus
}
#endif
#endif
