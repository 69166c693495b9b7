/* sol_screen.h - screen-space techniques of the talk: the coverage buffer for occlusion culling
 * (claim M1), volumetric obscurance SSAO with temporal accumulation (M3), the deviation-driven
 * post-process anti-aliasing filter (D17) and temporal anti-aliasing by reprojection (D18), plus
 * the small analytic scene (a pinhole camera and axis-aligned boxes) the experiments render.
 *
 * Conventions (see sol_core.h for the library-wide ones):
 *  - View space: the camera sits at the origin looking along +z; x grows to the right of the
 *    image, y grows down the image. "Depth" is the view-space z (linear, larger = farther).
 *  - Pixel (px, py) covers [px, px+1) x [py, py+1) in screen coordinates; its sample is its
 *    centre (px + 0.5, py + 0.5). Depth buffers are row-major float arrays, width * height.
 *  - Every function returns SOL_OK or an error code and leaves its outputs untouched on error.
 */
#ifndef SOL_SCREEN_H
#define SOL_SCREEN_H

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================= analytic scene: pinhole camera and boxes ======================= */

/* A pinhole camera. Screen x = width/2 + focal * X / Z, screen y = height/2 + focal * Y / Z. */
typedef struct sol_camera {
    int width, height; /* image size in pixels, >= 1 */
    double focal;      /* focal length in pixels, > 0 */
    double znear;      /* > 0: nothing nearer is rendered or projected */
    double zfar;       /* > znear: depth of the background (pixels that hit nothing) */
} sol_camera;

/* An axis-aligned box in view space, min[i] <= max[i]. Zero extents (flat boxes) are allowed. */
typedef struct sol_box {
    double min[3], max[3];
} sol_box;

/* Checks a camera: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE (NaN/Inf focal or planes),
 * SOL_ERR_INVALID_ARG (size < 1, focal <= 0, znear <= 0, zfar <= znear). */
sol_status sol_camera_check(const sol_camera *camera);

/* Checks a box against a camera: SOL_ERR_NONFINITE for NaN/Inf corners, SOL_ERR_INVALID_ARG for
 * min > max on an axis or a box reaching nearer than camera->znear (it could not be projected). */
sol_status sol_box_check(const sol_camera *camera, const sol_box *box);

/* Renders the depth buffer of `count` boxes by casting the ray through every pixel centre:
 * depth[py * width + px] = z of the first box surface hit, or camera->zfar if none (or if the hit
 * lies beyond zfar). count may be 0 (then boxes may be NULL). Errors: the camera's and boxes'
 * checks, SOL_ERR_NULL_ARG. Parallel over rows; the result does not depend on the thread count. */
sol_status sol_boxes_render_depth(const sol_camera *camera, const sol_box *boxes, size_t count, float *depth);

/* Traces one ray through the screen point (sx, sy) (any sub-pixel position): *depth = z of the
 * first box hit (or camera->zfar), *index = that box's index (or -1). Errors: as above, plus
 * SOL_ERR_NONFINITE for a NaN/Inf screen point. */
sol_status sol_boxes_trace(const sol_camera *camera, const sol_box *boxes, size_t count, double sx, double sy,
                           double *depth, long *index);

/* Screen-space bounds of a box: the rectangle [x0,x1] x [y0,y1] (screen coordinates, not
 * clipped to the image) that holds the projection of all 8 corners, hence of the whole box, and
 * the box's nearest depth znear = box->min[2]. Errors: as sol_box_check. */
typedef struct sol_screen_bounds {
    double x0, y0, x1, y1;
    double znear;
} sol_screen_bounds;
sol_status sol_box_screen_bounds(const sol_camera *camera, const sol_box *box, sol_screen_bounds *out);

/* Exact visibility of a box against a depth buffer at the buffer's own samples (the "rasterized
 * reference" of M1): *visible = 1 if at some pixel centre the ray hits the box strictly in front
 * of depth[] there, else 0. The depth buffer has the camera's size and finite values
 * (SOL_ERR_NONFINITE otherwise, checked only on the pixels the box covers). */
sol_status sol_box_visible(const sol_camera *camera, const float *depth, const sol_box *box, int *visible);

/* ======================= M1: coverage buffer (hierarchical occlusion culling) ============== */

/* How the full-resolution depth is reduced to the coverage buffer's resolution. Only MAX is
 * conservative (a texel is never nearer than any depth it stands for); MIN and MEAN are the
 * non-conservative alternatives the experiment measures against it. */
typedef enum sol_downscale {
    SOL_DOWNSCALE_MAX = 0, /* the farthest depth of the block (talk, slide "Occlusion culling") */
    SOL_DOWNSCALE_MIN,     /* the nearest depth of the block */
    SOL_DOWNSCALE_MEAN     /* the average depth of the block */
} sol_downscale;

#define SOL_CBUFFER_MAX_LEVELS 24

typedef struct sol_cbuffer_options {
    int block;               /* full-resolution pixels per coverage texel side; 0 = 4 */
    sol_downscale downscale; /* 0 = SOL_DOWNSCALE_MAX */
} sol_cbuffer_options;

/* A min/max depth hierarchy. Level 0 is the downscaled depth (zmin = zmax = the downscaled
 * value); level l+1 holds the min of its 2x2 children's zmin and the max of their zmax (an odd
 * size rounds up; the last texel then has fewer children). The top level is 1x1. */
typedef struct sol_cbuffer {
    int levels;
    int block;
    int full_width, full_height;
    int width[SOL_CBUFFER_MAX_LEVELS], height[SOL_CBUFFER_MAX_LEVELS];
    float *zmin[SOL_CBUFFER_MAX_LEVELS], *zmax[SOL_CBUFFER_MAX_LEVELS];
} sol_cbuffer;

/* Builds the hierarchy from a full-resolution depth buffer (width x height finite values).
 * Any block >= 1 works (a block at least as large as the image gives a 1x1 level 0; sizes are
 * computed without int overflow up to block = INT_MAX).
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (size < 1, block < 0, unknown downscale),
 * SOL_ERR_NONFINITE (a NaN/Inf depth), SOL_ERR_LIMIT (level 0 is wider or taller than 2^23
 * texels: more than SOL_CBUFFER_MAX_LEVELS levels), SOL_ERR_NO_MEMORY. Free with
 * sol_cbuffer_free. */
sol_status sol_cbuffer_build(const float *depth, int width, int height, const sol_cbuffer_options *options,
                             sol_cbuffer *out);
/* Frees the levels and zeroes the struct; safe on a zeroed or NULL buffer. */
void sol_cbuffer_free(sol_cbuffer *buffer);

/* Occlusion test of screen bounds (in full-resolution screen coordinates) against the hierarchy,
 * as the talk's notes describe it: pick the level where the bounds cover at most 2x2 texels; a
 * texel whose zmax is nearer than bounds->znear occludes its part; a texel whose zmin is farther
 * than znear means "visible" at once; a texel in between is refined at the next finer level,
 * at most `max_refine` levels below the starting one (negative: down to level 0). Where
 * refinement stops undecided the answer is "visible". *occluded = 1 only when every texel under
 * the bounds occludes. Bounds entirely outside the image give *occluded = 0 (frustum culling is
 * another test). texels_visited (may be NULL) receives the number of texels read: the test cost.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_NONFINITE (NaN bounds or znear), SOL_ERR_INVALID_ARG
 * (x1 < x0 or y1 < y0). */
sol_status sol_cbuffer_test(const sol_cbuffer *buffer, const sol_screen_bounds *bounds, int max_refine,
                            int *occluded, int *texels_visited);

/* ======================= D17: deviation-driven post-process anti-aliasing ================== */

/* Which fetches gather the 8-neighbourhood of a pixel. */
typedef enum sol_postaa_taps {
    /* 4 bilinear taps at (+1,+1/2), (-1/2,+1), (-1,-1/2), (+1/2,-1) pixels from the centre: each
     * tap averages two neighbours, together they weight all 8 neighbours by exactly 1/8. */
    SOL_POSTAA_PINWHEEL4 = 0,
    /* 4 bilinear taps at (+-1/2, +-1/2): each averages a 2x2 quad that includes the centre; the
     * mean of the taps is the 3x3 tent [1 2 1; 2 4 2; 1 2 1] / 16. */
    SOL_POSTAA_DIAGONAL4,
    /* 8 point fetches: the definition d = sum |s_i - s_0| the talk states. */
    SOL_POSTAA_DIRECT8
} sol_postaa_taps;

typedef struct sol_postaa_options {
    sol_postaa_taps taps; /* 0 = SOL_POSTAA_PINWHEEL4 */
    /* Deviation (mean over the fetches of the channel-summed |fetch - centre|) at which the blur
     * reaches full strength; below it the blur weight is deviation / threshold. 0 = 0.5
     * (full blur once half the neighbours differ by a unit step in one channel). */
    double threshold;
} sol_postaa_options;

/* The neighbourhood statistics of pixel (x, y), edges clamped: `mean` (channels values) is the
 * mean of the fetches, `deviation` the mean over the fetches of sum_c |fetch_c - centre_c| (so
 * DIRECT8 gives the talk's d / 8). Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (bad image,
 * pixel outside it, unknown taps). */
sol_status sol_postaa_neighbourhood(const sol_image *image, int x, int y, sol_postaa_taps taps, float *mean,
                                    float *deviation);

/* Filters `in` into `out` (allocated here with in's size; free with sol_image_free):
 * out = s0 + w (B - s0), w = min(1, deviation / threshold), where B is the 3x3 blur the taps give:
 * the box (s0 + 8 mean) / 9 for PINWHEEL4 and DIRECT8, the tent `mean` itself for DIAGONAL4.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (bad image or options, threshold < 0),
 * SOL_ERR_NONFINITE (NaN/Inf pixel or threshold), SOL_ERR_NO_MEMORY. */
sol_status sol_postaa_filter(const sol_image *in, const sol_postaa_options *options, sol_image *out);

/* ======================= M3: volumetric obscurance (SSAO) =============================== */

typedef struct sol_vo_options {
    double radius;  /* radius of the obscurance sphere in view-space units; 0 = 1 */
    int samples;    /* line samples per pixel, 1..4096; 0 = 4 (the talk's count) */
    unsigned frame; /* which samples: frame f uses points f*samples .. (f+1)*samples-1 of the R2
                     * sequence, so successive frames add new samples for temporal accumulation */
    int same_rotation_everywhere; /* nonzero: no per-pixel rotation of the pattern (reference) */
} sol_vo_options;

/* Volumetric obscurance (Loos & Sloan, I3D 2010) with line samples: for each pixel with depth z_p,
 * the sphere of the given radius around the pixel's surface point is cut by lines along the view
 * axis through points (u, v) of its central disk; the depth buffer is taken as a height field
 * (everything behind a stored depth is solid). Each line of half length h = R sqrt(1 - |uv|^2)
 * contributes its solid part clamp(z_p + h - z_s, 0, 2h), where z_s is the stored depth at the
 * line's pixel (nearest pixel, edges clamped); vo = sum(solid) / sum(2h). A flat surface facing
 * the camera gives 0.5; creases more, ridges less. The disk points are R2 points (radius sqrt(u)
 * for area uniformity), rotated per pixel by interleaved gradient noise (Jimenez 2014) unless
 * same_rotation_everywhere. Pixels at the background depth (>= camera->zfar) get 0.
 * Errors: the camera's check, SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (radius < 0, samples out of
 * range), SOL_ERR_NONFINITE (NaN/Inf radius or depth). Parallel over rows, thread-count-stable. */
sol_status sol_vo_compute(const sol_camera *camera, const float *depth, const sol_vo_options *options, float *vo);

/* Half resolution: out (ceil(w/2) x ceil(h/2)) takes the depth of the top-left pixel of each 2x2
 * block (a real surface depth, never a blend across an edge). Errors: NULL, size < 1. */
sol_status sol_depth_half(const float *depth, int width, int height, float *out);

/* Depth-aware (bilateral) upsampling of a half-resolution signal: each full-resolution pixel
 * blends the 4 nearest half-resolution texels with bilinear weights times 1 / (eps + |dz| / z),
 * eps = 1e-3, dz the depth difference. Sizes: half is ceil(w/2) x ceil(h/2). Errors: NULL,
 * size < 1. */
sol_status sol_bilateral_upsample(const float *half_values, const float *half_depth, const float *full_depth,
                                  int width, int height, float *out);

/* ======================= D18 / M3: temporal accumulation by reprojection ================== */

/* Per-pixel history of an accumulated signal, for one camera frame. */
typedef struct sol_history {
    int width, height, channels;
    float *values; /* width * height * channels accumulated values */
    float *depth;  /* the depth buffer of the frame the history belongs to */
    float *frames; /* frames accumulated per pixel (0: empty) */
} sol_history;

/* Allocates an empty history (frames 0). Errors: NULL, size < 1, channels outside 1..4,
 * SOL_ERR_NO_MEMORY. Free with sol_history_free (safe on a zeroed or NULL history). */
sol_status sol_history_alloc(sol_history *out, int width, int height, int channels);
void sol_history_free(sol_history *history);

/* How the history is fetched at the reprojected (fractional) position. */
typedef enum sol_history_filter {
    SOL_HISTORY_BILINEAR = 0, /* 2x2 taps: cheap, but every re-fetch blurs the history a little */
    SOL_HISTORY_CATMULL_ROM   /* 4x4 taps, Catmull-Rom weights (Keys 1981 with a = -1/2; Catmull and
                               * Rom 1974): interpolating and sharper, as production TAA fetches its
                               * history; may overshoot near edges (no clamp here) */
} sol_history_filter;

typedef struct sol_temporal_options {
    double max_frames;      /* the current frame gets weight max(1/(n+1), 1/max_frames); 0 = 16 */
    double depth_tolerance; /* relative depth change |z_hist - z_expected| / z_expected above which
                             * the history is a cache miss (talk, D18); 0 = 0.01 */
    int no_depth_test;      /* nonzero: reproject without the depth test (for ghosting studies) */
    /* nonzero: the depth test passes when the expected depth lies within the tolerance of the
     * [min, max] of the previous depths in the 3x3 pixels around the reprojected point, instead of
     * the nearest pixel alone. With jittered frames a silhouette pixel sees either surface from
     * frame to frame; this keeps accumulating there (the talk's "take into account edge
     * discontinuities") at the price of up to one pixel of ghosting around moving objects. */
    int edge_tolerant;
    sol_history_filter filter; /* 0 = bilinear. Catmull-Rom: the inner 2x2 taps decide the miss and the
                                * frame count exactly as bilinear does; an outer tap outside the image
                                * or empty takes the value of the nearest inner tap */
} sol_temporal_options;

/* One accumulation step (reverse reprojection caching, Nehab et al. 2007, as the talk uses it):
 * for each pixel, its surface point P = depth * ray is moved into the previous camera by
 * `motion` (the camera translation from the previous frame to this one, view-space units; the
 * cameras differ by translation only), projected, and the previous history is fetched there
 * (bilinear, edges of the image are misses). The history counts as a hit when the point lands in
 * the image and (unless no_depth_test) the previous depth at the nearest pixel (or, with
 * edge_tolerant, the 3x3 depth range there) is within the tolerance of P's previous depth; then next = lerp(history, current, w), otherwise next = current
 * and the count restarts at 1. `current` holds camera-size * channels values (channels = the
 * histories' channels); prev may be an empty history. next must not alias prev.
 * Errors: NULL, SOL_ERR_INVALID_ARG (history sizes differ from the camera's, negative options, an
 * unknown filter),
 * SOL_ERR_NONFINITE (NaN/Inf motion, depth or current values). */
sol_status sol_temporal_accumulate(const sol_camera *camera, const float *depth, const float *current,
                                   const double motion[3], const sol_temporal_options *options,
                                   const sol_history *prev, sol_history *next);

/* The sub-pixel jitter of frame n: the n-th R2 point minus 1/2, in pixels, in [-1/2, 1/2)^2. */
void sol_jitter_offset(unsigned frame, double *dx, double *dy);

#ifdef __cplusplus
}
#endif
#endif
