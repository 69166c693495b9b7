/* limits.c - the one size-limit policy of every reader (see sol_read_limits in sol_core.h). */
#include "sol_core.h"

sol_status sol_read_limits_check(const sol_read_limits *limits, int64_t width, int64_t height, int64_t depth,
                                 uint64_t bytes_per_pixel)
{
    if (width < 1 || height < 1 || depth < 1)
        return SOL_ERR_INVALID_ARG;
    uint64_t max_pixels = limits && limits->max_pixels ? limits->max_pixels : SOL_READ_MAX_PIXELS_DEFAULT;
    uint64_t max_bytes = limits && limits->max_bytes ? limits->max_bytes : SOL_READ_MAX_BYTES_DEFAULT;
    /* Each factor is checked before it multiplies, so no product can wrap. */
    uint64_t w = (uint64_t)width, h = (uint64_t)height, d = (uint64_t)depth;
    if (w > max_pixels || h > max_pixels / w || d > max_pixels / (w * h))
        return SOL_ERR_LIMIT;
    uint64_t pixels = w * h * d;
    if (bytes_per_pixel && pixels > max_bytes / bytes_per_pixel)
        return SOL_ERR_LIMIT;
    return SOL_OK;
}
