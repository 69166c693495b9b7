/* postaa.c - claim D17: the post-process anti-aliasing filter of the talk ("Post-process
 * Anti-Aliasing" slide): the colour deviation d = sum over the 8 neighbours of |s_i - s_0| decides
 * how strongly a pixel is blurred, and 4 bilinear fetches stand in for the 8 neighbours.
 *
 * Where the 4 fetches go is not stated in the talk. Two placements reach all 8 neighbours:
 *  - the "pinwheel" (+1,+1/2), (-1/2,+1), (-1,-1/2), (+1/2,-1): each fetch lands on the edge
 *    between two neighbours and returns their average, each neighbour is in exactly one fetch,
 *    so the mean of the 4 fetches is the 8-neighbour mean exactly;
 *  - the "diagonal" (+-1/2, +-1/2): each fetch averages a 2x2 quad that includes the centre, so
 *    the fetches weight edge neighbours twice as much as corners and include s_0 itself.
 * The deviation a fetch sees is |average - s_0|, which can cancel opposite differences: the
 * fetched deviation is a lower bound of the talk's d (triangle inequality). */
#include "sol_screen.h"

#include <math.h>
#include <string.h>

#define POSTAA_MAX_FETCHES 8

static int image_ok(const sol_image *image)
{
    return image->width >= 1 && image->height >= 1 && image->channels >= 1 && image->channels <= 4 &&
           image->data;
}

/* Bilinear fetch with clamp-to-edge addressing; (x, y) in pixel units, pixel centres at
 * integers (the shader's texture coordinate minus one half texel). */
static void bilinear(const sol_image *image, double x, double y, float *out)
{
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    const double w[4] = {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay};
    for (int c = 0; c < image->channels; ++c)
        out[c] = 0.0f;
    for (int k = 0; k < 4; ++k) {
        if (w[k] == 0.0)
            continue;
        int px = x0 + (k & 1), py = y0 + (k >> 1);
        px = px < 0 ? 0 : px >= image->width ? image->width - 1 : px;
        py = py < 0 ? 0 : py >= image->height ? image->height - 1 : py;
        const float *p = sol_image_pixel(image, px, py);
        for (int c = 0; c < image->channels; ++c)
            out[c] += (float)(w[k] * p[c]);
    }
}

/* Fetch offsets of each placement, in pixels from the centre. */
static int fetch_offsets(sol_postaa_taps taps, double offsets[POSTAA_MAX_FETCHES][2])
{
    static const double pinwheel[4][2] = {{1.0, 0.5}, {-0.5, 1.0}, {-1.0, -0.5}, {0.5, -1.0}};
    static const double diagonal[4][2] = {{0.5, 0.5}, {-0.5, 0.5}, {-0.5, -0.5}, {0.5, -0.5}};
    static const double direct[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
    switch (taps) {
    case SOL_POSTAA_PINWHEEL4:
        memcpy(offsets, pinwheel, sizeof pinwheel);
        return 4;
    case SOL_POSTAA_DIAGONAL4:
        memcpy(offsets, diagonal, sizeof diagonal);
        return 4;
    case SOL_POSTAA_DIRECT8:
        memcpy(offsets, direct, sizeof direct);
        return 8;
    }
    return 0;
}

sol_status sol_postaa_neighbourhood(const sol_image *image, int x, int y, sol_postaa_taps taps, float *mean,
                                    float *deviation)
{
    if (!image || !mean || !deviation)
        return SOL_ERR_NULL_ARG;
    double offsets[POSTAA_MAX_FETCHES][2];
    int n = fetch_offsets(taps, offsets);
    if (!image_ok(image) || !n || x < 0 || y < 0 || x >= image->width || y >= image->height)
        return SOL_ERR_INVALID_ARG;
    const float *center = sol_image_pixel(image, x, y);
    double sum[4] = {0}, dev = 0.0;
    for (int k = 0; k < n; ++k) {
        float fetch[4];
        bilinear(image, x + offsets[k][0], y + offsets[k][1], fetch);
        for (int c = 0; c < image->channels; ++c) {
            sum[c] += fetch[c];
            dev += fabs((double)fetch[c] - center[c]);
        }
    }
    for (int c = 0; c < image->channels; ++c)
        mean[c] = (float)(sum[c] / n);
    *deviation = (float)(dev / n);
    return SOL_OK;
}

sol_status sol_postaa_filter(const sol_image *in, const sol_postaa_options *options, sol_image *out)
{
    if (!in || !out)
        return SOL_ERR_NULL_ARG;
    sol_postaa_options opt = options ? *options : (sol_postaa_options){0};
    double offsets[POSTAA_MAX_FETCHES][2];
    if (!image_ok(in) || !fetch_offsets(opt.taps, offsets))
        return SOL_ERR_INVALID_ARG;
    if (!isfinite(opt.threshold))
        return SOL_ERR_NONFINITE;
    if (opt.threshold < 0.0)
        return SOL_ERR_INVALID_ARG;
    const double threshold = opt.threshold > 0.0 ? opt.threshold : 0.5;
    const size_t values = (size_t)in->width * (size_t)in->height * (size_t)in->channels;
    for (size_t i = 0; i < values; ++i)
        if (!isfinite(in->data[i]))
            return SOL_ERR_NONFINITE;
    sol_image result;
    sol_status status = sol_image_alloc(&result, in->width, in->height, in->channels);
    if (status != SOL_OK)
        return status;
    /* The 3x3 blur each placement affords: the box from the 8-neighbour mean, or the tent the
     * diagonal fetches already are. */
    const double center_share = opt.taps == SOL_POSTAA_DIAGONAL4 ? 0.0 : 1.0 / 9.0;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < in->height; ++y)
        for (int x = 0; x < in->width; ++x) {
            float mean[4], deviation;
            sol_postaa_neighbourhood(in, x, y, opt.taps, mean, &deviation);
            const double weight = fmin(1.0, deviation / threshold);
            const float *s0 = sol_image_pixel(in, x, y);
            float *o = sol_image_pixel(&result, x, y);
            for (int c = 0; c < in->channels; ++c) {
                double blur = center_share * s0[c] + (1.0 - center_share) * mean[c];
                o[c] = (float)(s0[c] + weight * (blur - s0[c]));
            }
        }
    *out = result;
    return SOL_OK;
}
