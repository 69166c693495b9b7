/* renorm.c - per-channel range ("histogram") renormalisation of color textures (claims T1, T2).
 *
 * Talk, slide "Histogram renormalization": the texture's color range is stretched to [0,1] before
 * block compression and the original min/max are kept as two shader constants that restore it
 * after the texture fetch (value = lo + stored * (hi - lo)). */
#include <float.h>
#include <math.h>

#include "sol_textures.h"

static size_t value_count(const sol_image *image)
{
    return (size_t)image->width * (size_t)image->height * (size_t)image->channels;
}

static sol_status check_image(const sol_image *image)
{
    if (!image || !image->data)
        return SOL_ERR_NULL_ARG;
    if (image->width <= 0 || image->height <= 0 || image->channels < 1 || image->channels > 4)
        return SOL_ERR_INVALID_ARG;
    size_t n = value_count(image);
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(image->data[i]))
            return SOL_ERR_NONFINITE;
    return SOL_OK;
}

sol_status sol_renorm_fit(const sol_image *image, sol_renorm *out)
{
    sol_status st = check_image(image);
    if (st)
        return st;
    if (!out)
        return SOL_ERR_NULL_ARG;
    sol_renorm r = {.channels = image->channels};
    for (int c = 0; c < image->channels; ++c)
        r.lo[c] = r.hi[c] = image->data[c];
    size_t n = value_count(image);
    for (size_t i = 0; i < n; ++i) {
        int c = (int)(i % (size_t)image->channels);
        r.lo[c] = fminf(r.lo[c], image->data[i]);
        r.hi[c] = fmaxf(r.hi[c], image->data[i]);
    }
    *out = r;
    return SOL_OK;
}

static sol_status check_pair(const sol_renorm *range, const sol_image *image)
{
    if (!range)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_image(image);
    if (st)
        return st;
    if (range->channels != image->channels)
        return SOL_ERR_INVALID_ARG;
    for (int c = 0; c < range->channels; ++c)
        if (!isfinite(range->lo[c]) || !isfinite(range->hi[c]))
            return SOL_ERR_NONFINITE;
    return SOL_OK;
}

/* Stretch [lo, hi] to [0, 1] (clamped; a flat channel stores 0) or map stored [0, 1] back. */
static float apply_value(float v, float lo, float hi)
{
    float span = hi - lo;
    if (isinf(span)) /* [-FLT_MAX, FLT_MAX]: the float span overflows, the double one does not */
        return (float)fmin(1.0, fmax(0.0, ((double)v - lo) / ((double)hi - lo)));
    float t = span > 0.0f ? (v - lo) / span : 0.0f;
    return fminf(1.0f, fmaxf(0.0f, t));
}

static float undo_value(float v, float lo, float hi)
{
    if (isinf(hi - lo)) {
        double r = (double)lo + (double)v * ((double)hi - lo);
        return fabs(r) > FLT_MAX ? (float)copysign(INFINITY, r) : (float)r; /* no out-of-range cast */
    }
    return lo + v * (hi - lo);
}

static sol_status map_values(const sol_renorm *range, sol_image *image, float (*map)(float, float, float))
{
    sol_status st = check_pair(range, image);
    if (st)
        return st;
    size_t n = value_count(image);
    /* first pass: a stored value outside [0, 1] can map past FLT_MAX; refuse before writing */
    for (size_t i = 0; i < n; ++i) {
        int c = (int)(i % (size_t)image->channels);
        if (!isfinite(map(image->data[i], range->lo[c], range->hi[c])))
            return SOL_ERR_OUT_OF_RANGE;
    }
    for (size_t i = 0; i < n; ++i) {
        int c = (int)(i % (size_t)image->channels);
        image->data[i] = map(image->data[i], range->lo[c], range->hi[c]);
    }
    return SOL_OK;
}

sol_status sol_renorm_apply(const sol_renorm *range, sol_image *image)
{
    return map_values(range, image, apply_value);
}

sol_status sol_renorm_undo(const sol_renorm *range, sol_image *image)
{
    return map_values(range, image, undo_value);
}
