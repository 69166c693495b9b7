/* gbuffer_layout.c - render-target formats and the G-buffer layouts of claim D1. */
#include "sol_pipeline.h"

static const struct {
    unsigned bits;
    const char *name;
} format_table[SOL_PIXEL_FORMAT_COUNT] = {
    [SOL_FORMAT_D24S8] = {32, "D24S8"},
    [SOL_FORMAT_RGBA8] = {32, "A8R8G8B8"},
    [SOL_FORMAT_RG8] = {16, "R8G8"},
    [SOL_FORMAT_R16] = {16, "R16"},
    [SOL_FORMAT_RGBA16F] = {64, "A16B16G16R16F"},
    [SOL_FORMAT_R11G11B10F] = {32, "R11G11B10F"},
    [SOL_FORMAT_RGB10A2] = {32, "A2R10G10B10"},
    [SOL_FORMAT_R32F] = {32, "R32F"},
};

unsigned sol_pixel_format_bits(sol_pixel_format format)
{
    return (unsigned)format < SOL_PIXEL_FORMAT_COUNT ? format_table[format].bits : 0;
}

const char *sol_pixel_format_name(sol_pixel_format format)
{
    return (unsigned)format < SOL_PIXEL_FORMAT_COUNT ? format_table[format].name : "unknown";
}

/* D1. Attributes per layout are the talk's (slide "Deferred pipelines bandwidth"); the formats of
 * the classic layout are our assumption (S.T.A.L.K.E.R., GPU Gems 2 ch. 9, used several). */
static const sol_gbuffer_layout layouts[SOL_GBUFFER_KIND_COUNT] = {
    [SOL_GBUFFER_CLASSIC_NARROW] =
        {"classic deferred shading, 8-bit normals",
         "attributes from the talk (S.T.A.L.K.E.R., GPU Gems 2); formats assumed: the narrowest common choice",
         4,
         {{SOL_FORMAT_D24S8, "depth 24 + stencil 8"},
          {SOL_FORMAT_RGBA8, "normal 24 + glossiness 8"},
          {SOL_FORMAT_RGBA8, "albedo 24 + occlusion 8"},
          {SOL_FORMAT_R16, "material index 16"}}},
    [SOL_GBUFFER_CLASSIC_WIDE] =
        {"classic deferred shading, half-float normals",
         "attributes from the talk; formats assumed: normal and glossiness in half floats",
         4,
         {{SOL_FORMAT_D24S8, "depth 24 + stencil 8"},
          {SOL_FORMAT_RGBA16F, "normal 48 + glossiness 16"},
          {SOL_FORMAT_RGBA8, "albedo 24 + occlusion 8"},
          {SOL_FORMAT_R16, "material index 16"}}},
    [SOL_GBUFFER_LIGHT_PREPASS] =
        {"full deferred lighting (light pre-pass)",
         "attributes from the talk (Engel 2009); best case: everything in 8-bit channels",
         3,
         {{SOL_FORMAT_D24S8, "depth 24 + stencil 8"},
          {SOL_FORMAT_RGBA8, "normal 24 + glossiness 8"},
          {SOL_FORMAT_RGBA8, "albedo 24 + unused 8"}}},
    [SOL_GBUFFER_CRYENGINE3] =
        {"partial deferred lighting (CryENGINE 3)",
         "the talk's slide 'G-Buffer. The smaller the better!' (Mittring 2009)",
         2,
         {{SOL_FORMAT_D24S8, "depth 24 + stencil 8"}, {SOL_FORMAT_RGBA8, "normal 24 + glossiness 8"}}},
};

sol_status sol_gbuffer_layout_get(sol_gbuffer_kind kind, const sol_gbuffer_layout **out)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)kind >= SOL_GBUFFER_KIND_COUNT)
        return SOL_ERR_INVALID_ARG;
    *out = &layouts[kind];
    return SOL_OK;
}

sol_status sol_gbuffer_bits_per_pixel(const sol_gbuffer_layout *layout, unsigned *bits)
{
    if (!layout || !bits)
        return SOL_ERR_NULL_ARG;
    if (layout->target_count < 1 || layout->target_count > SOL_GBUFFER_MAX_TARGETS)
        return SOL_ERR_INVALID_ARG;
    unsigned sum = 0;
    for (int i = 0; i < layout->target_count; ++i) {
        unsigned target_bits = sol_pixel_format_bits(layout->targets[i].format);
        if (!target_bits)
            return SOL_ERR_INVALID_ARG;
        sum += target_bits;
    }
    *bits = sum;
    return SOL_OK;
}

sol_status sol_gbuffer_bytes(const sol_gbuffer_layout *layout, int width, int height, int samples, uint64_t *bytes)
{
    if (!layout || !bytes)
        return SOL_ERR_NULL_ARG;
    if (width <= 0 || height <= 0 || (samples != 1 && samples != 2 && samples != 4 && samples != 8))
        return SOL_ERR_INVALID_ARG;
    unsigned bits;
    sol_status status = sol_gbuffer_bits_per_pixel(layout, &bits);
    if (status != SOL_OK)
        return status;
    /* bytes = p * bits / 8 with p = w*h*samples < 2^65: split p = 8q + r so that nothing wraps
     * past 2^64 unless the answer itself does */
    uint64_t wh = (uint64_t)width * (uint64_t)height; /* < 2^62 */
    uint64_t q = wh / 8u * (uint64_t)samples + wh % 8u * (uint64_t)samples / 8u, r = wh % 8u * (uint64_t)samples % 8u;
    if (bits && q > (UINT64_MAX - (uint64_t)r * bits / 8u) / bits)
        return SOL_ERR_OUT_OF_RANGE;
    *bytes = q * bits + (uint64_t)r * bits / 8u;
    return SOL_OK;
}
