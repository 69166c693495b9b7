/* sol_pipeline.h - deferred pipeline bookkeeping: render-target formats and G-buffer layouts
 * (claim D1: classic deferred shading 112-144, light pre-pass 96, CryENGINE 3's partial deferred
 * lighting 64 bits per pixel).
 *
 * A layout is a list of render targets, each a pixel format plus what its channels hold, so the
 * bits per pixel are computed from the formats rather than typed. Conventions as in sol_core.h. */
#ifndef SOL_PIPELINE_H
#define SOL_PIPELINE_H

#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Render-target and depth formats of the console/D3D9-D3D10 era. */
typedef enum sol_pixel_format {
    SOL_FORMAT_D24S8,          /* depth 24 + stencil 8 */
    SOL_FORMAT_RGBA8,          /* A8R8G8B8 */
    SOL_FORMAT_RG8,            /* R8G8 (16 bits) */
    SOL_FORMAT_R16,            /* one 16-bit channel */
    SOL_FORMAT_RGBA16F,        /* A16B16G16R16F */
    SOL_FORMAT_R11G11B10F,     /* packed float */
    SOL_FORMAT_RGB10A2,        /* A2R10G10B10 */
    SOL_FORMAT_R32F,           /* one float channel */
    SOL_PIXEL_FORMAT_COUNT
} sol_pixel_format;

/* Bits per pixel of a format; 0 for a value outside the enum. */
unsigned sol_pixel_format_bits(sol_pixel_format format);
/* D3D-style name ("A8R8G8B8"); "unknown" for a value outside the enum. */
const char *sol_pixel_format_name(sol_pixel_format format);

#define SOL_GBUFFER_MAX_TARGETS 6

typedef struct sol_render_target {
    sol_pixel_format format;
    const char *contents; /* what the channels hold, e.g. "normal 24 + glossiness 8" */
} sol_render_target;

typedef struct sol_gbuffer_layout {
    const char *name;    /* e.g. "partial deferred lighting (CryENGINE 3)" */
    const char *source;  /* where the layout comes from, and what was assumed */
    int target_count;    /* 1..SOL_GBUFFER_MAX_TARGETS, depth-stencil included */
    sol_render_target targets[SOL_GBUFFER_MAX_TARGETS];
} sol_gbuffer_layout;

/* The layouts the talk compares (slide "Deferred pipelines bandwidth"). The talk names the
 * stored attributes but not the formats of the classic layout, so it comes in two variants: the
 * narrowest and the widest assembly of its attributes from common formats. */
typedef enum sol_gbuffer_kind {
    SOL_GBUFFER_CLASSIC_NARROW,   /* classic deferred shading, 8-bit normals */
    SOL_GBUFFER_CLASSIC_WIDE,     /* classic deferred shading, half-float normals */
    SOL_GBUFFER_LIGHT_PREPASS,    /* full deferred lighting (light pre-pass), best case */
    SOL_GBUFFER_CRYENGINE3,       /* partial deferred lighting: depth + normal + glossiness */
    SOL_GBUFFER_KIND_COUNT
} sol_gbuffer_kind;

/* The built-in layout of `kind` (static storage). SOL_ERR_INVALID_ARG for an unknown kind. */
sol_status sol_gbuffer_layout_get(sol_gbuffer_kind kind, const sol_gbuffer_layout **out);

/* Sum of the targets' bits per pixel. SOL_ERR_INVALID_ARG if target_count is out of range or a
 * format is unknown; `*bits` is written only on success. */
sol_status sol_gbuffer_bits_per_pixel(const sol_gbuffer_layout *layout, unsigned *bits);

/* Bytes the G-buffer occupies (and is written once per frame) at width x height with `samples`
 * MSAA samples per pixel (1, 2, 4 or 8): every sample stores the whole layout, which is why the
 * talk calls MSAA with a G-buffer super-sampling in bandwidth. bytes = floor(w*h*samples*bits/8),
 * computed exactly for any int sizes. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (size <= 0,
 * other sample counts, a bad layout), SOL_ERR_OUT_OF_RANGE (the answer exceeds 2^64 - 1, e.g.
 * INT_MAX x INT_MAX x 8 samples); `*bytes` is written only on success. */
sol_status sol_gbuffer_bytes(const sol_gbuffer_layout *layout, int width, int height, int samples, uint64_t *bytes);

#ifdef __cplusplus
}
#endif
#endif
