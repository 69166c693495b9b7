/* temporal.c - claims D18 and M3: temporal accumulation by reverse reprojection with a depth-change
 * cache miss (Nehab, Sander, Lawrence, Tatarchuk, Isidoro, "Accelerating real-time shading with
 * reverse reprojection caching", Graphics Hardware 2007; talk, "Temporal Anti-Aliasing" slide), and
 * the sub-pixel camera jitter that turns it into temporal supersampling. */
#include "sol_screen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

sol_status sol_history_alloc(sol_history *out, int width, int height, int channels)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if (width < 1 || height < 1 || channels < 1 || channels > 4)
        return SOL_ERR_INVALID_ARG;
    size_t n = (size_t)width * (size_t)height;
    sol_history h = {width, height, channels, calloc(n * (size_t)channels, sizeof(float)),
                     calloc(n, sizeof(float)), calloc(n, sizeof(float))};
    if (!h.values || !h.depth || !h.frames) {
        sol_history_free(&h);
        return SOL_ERR_NO_MEMORY;
    }
    *out = h;
    return SOL_OK;
}

void sol_history_free(sol_history *history)
{
    if (!history)
        return;
    free(history->values);
    free(history->depth);
    free(history->frames);
    memset(history, 0, sizeof *history);
}

static int history_matches(const sol_history *h, const sol_camera *camera)
{
    return h->values && h->depth && h->frames && h->width == camera->width && h->height == camera->height &&
           h->channels >= 1 && h->channels <= 4;
}

/* Bilinear fetch of the history at pixel-centre coordinates (x, y) (centres at integers); 0 when
 * any of the 4 texels is empty or outside the image (a miss: no partial histories). */
static int fetch_history(const sol_history *h, double x, double y, float *values, float *frames)
{
    if (!(x > -1.0 && x < h->width && y > -1.0 && y < h->height)) /* also keeps floor() in int range */
        return 0;
    double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    double acc[4] = {0}, n = 0.0;
    for (int k = 0; k < 4; ++k) {
        double w = ((k & 1) ? ax : 1.0 - ax) * ((k >> 1) ? ay : 1.0 - ay);
        if (w == 0.0)
            continue;
        int tx = x0 + (k & 1), ty = y0 + (k >> 1);
        if (tx < 0 || ty < 0 || tx >= h->width || ty >= h->height)
            return 0;
        size_t i = (size_t)ty * (size_t)h->width + (size_t)tx;
        if (h->frames[i] <= 0.0f)
            return 0;
        for (int c = 0; c < h->channels; ++c)
            acc[c] += w * h->values[i * (size_t)h->channels + (size_t)c];
        n += w * h->frames[i];
    }
    for (int c = 0; c < h->channels; ++c)
        values[c] = (float)acc[c];
    *frames = (float)n;
    return 1;
}

/* Catmull-Rom weights of the 4 taps at offsets -1, 0, 1, 2 for fraction t in [0, 1) (Keys 1981,
 * a = -1/2): they sum to 1 and give weight 1 to the tap at 0 when t = 0. */
static void catmull_rom_weights(double t, double w[4])
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

/* Catmull-Rom fetch: the bilinear fetch decides hit/miss and the frame count (inner 2x2 taps); the
 * values come from the 4x4 taps, an outer tap outside the image or empty replaced by the nearest
 * inner tap. */
static int fetch_history_catmull_rom(const sol_history *h, double x, double y, float *values, float *frames)
{
    float bil[4];
    if (!fetch_history(h, x, y, bil, frames))
        return 0;
    double fx = floor(x), fy = floor(y), wx[4], wy[4], acc[4] = {0};
    int x0 = (int)fx, y0 = (int)fy;
    catmull_rom_weights(x - fx, wx);
    catmull_rom_weights(y - fy, wy);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double w = wx[i] * wy[j];
            if (w == 0.0)
                continue;
            int tx = x0 - 1 + i, ty = y0 - 1 + j;
            int ix = i < 1 ? 1 : i > 2 ? 2 : i, iy = j < 1 ? 1 : j > 2 ? 2 : j; /* nearest inner tap */
            int inner_x = x0 - 1 + ix, inner_y = y0 - 1 + iy;
            int outside = tx < 0 || ty < 0 || tx >= h->width || ty >= h->height;
            size_t t = outside ? 0 : (size_t)ty * (size_t)h->width + (size_t)tx;
            if (outside || h->frames[t] <= 0.0f) {
                /* the inner tap may itself be outside when its bilinear weight was 0: clamp it */
                inner_x = inner_x < 0 ? 0 : inner_x >= h->width ? h->width - 1 : inner_x;
                inner_y = inner_y < 0 ? 0 : inner_y >= h->height ? h->height - 1 : inner_y;
                t = (size_t)inner_y * (size_t)h->width + (size_t)inner_x;
            }
            for (int c = 0; c < h->channels; ++c)
                acc[c] += w * h->values[t * (size_t)h->channels + (size_t)c];
        }
    for (int c = 0; c < h->channels; ++c)
        values[c] = (float)acc[c];
    return 1;
}

/* The cache-miss test of D18: does the previous depth around pixel (x, y) agree with the depth z
 * the point should have had? Nearest pixel, or the 3x3 depth range when edge_tolerant. */
static int depth_matches(const sol_history *prev, long x, long y, double z, double tolerance, int edge_tolerant)
{
    const int r = edge_tolerant ? 1 : 0;
    double lo = INFINITY, hi = -INFINITY;
    for (long j = y - r; j <= y + r; ++j)
        for (long i = x - r; i <= x + r; ++i) {
            if (i < 0 || j < 0 || i >= prev->width || j >= prev->height)
                continue;
            double d = prev->depth[(size_t)j * (size_t)prev->width + (size_t)i];
            lo = d < lo ? d : lo;
            hi = d > hi ? d : hi;
        }
    return z >= lo - tolerance * z && z <= hi + tolerance * z;
}

sol_status sol_temporal_accumulate(const sol_camera *camera, const float *depth, const float *current,
                                   const double motion[3], const sol_temporal_options *options,
                                   const sol_history *prev, sol_history *next)
{
    sol_status status = sol_camera_check(camera);
    if (status != SOL_OK)
        return status;
    if (!depth || !current || !motion || !prev || !next)
        return SOL_ERR_NULL_ARG;
    sol_temporal_options opt = options ? *options : (sol_temporal_options){0};
    if (!history_matches(prev, camera) || !history_matches(next, camera) || prev->channels != next->channels ||
        opt.max_frames < 0.0 || opt.depth_tolerance < 0.0 || prev->values == next->values ||
        (opt.filter != SOL_HISTORY_BILINEAR && opt.filter != SOL_HISTORY_CATMULL_ROM))
        return SOL_ERR_INVALID_ARG;
    if (!isfinite(motion[0]) || !isfinite(motion[1]) || !isfinite(motion[2]) || !isfinite(opt.max_frames) ||
        !isfinite(opt.depth_tolerance))
        return SOL_ERR_NONFINITE;
    const int width = camera->width, height = camera->height, channels = next->channels;
    const size_t n = (size_t)width * (size_t)height;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(depth[i]))
            return SOL_ERR_NONFINITE;
    for (size_t i = 0; i < n * (size_t)channels; ++i)
        if (!isfinite(current[i]))
            return SOL_ERR_NONFINITE;
    const double max_frames = opt.max_frames > 0.0 ? opt.max_frames : 16.0;
    const double tolerance = opt.depth_tolerance > 0.0 ? opt.depth_tolerance : 0.01;
#pragma omp parallel for schedule(static)
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const size_t i = (size_t)py * (size_t)width + (size_t)px;
            const double z = depth[i];
            /* The surface point in this camera, then in the previous one (pure translation). */
            double p[3] = {(px + 0.5 - 0.5 * width) / camera->focal * z + motion[0],
                           (py + 0.5 - 0.5 * height) / camera->focal * z + motion[1], z + motion[2]};
            float hist[4], frames = 0.0f;
            int hit = p[2] > camera->znear;
            double sx = 0.0, sy = 0.0;
            if (hit) {
                sx = 0.5 * width + camera->focal * p[0] / p[2] - 0.5; /* pixel-centre coordinates */
                sy = 0.5 * height + camera->focal * p[1] / p[2] - 0.5;
                hit = opt.filter == SOL_HISTORY_CATMULL_ROM ? fetch_history_catmull_rom(prev, sx, sy, hist, &frames)
                                                            : fetch_history(prev, sx, sy, hist, &frames);
            }
            if (hit && !opt.no_depth_test)
                hit = depth_matches(prev, lround(sx), lround(sy), p[2], tolerance, opt.edge_tolerant);
            const float *cur = &current[i * (size_t)channels];
            float *out = &next->values[i * (size_t)channels];
            if (hit) {
                double w = fmax(1.0 / (frames + 1.0), 1.0 / max_frames);
                for (int c = 0; c < channels; ++c)
                    out[c] = (float)(hist[c] + w * (cur[c] - hist[c]));
                next->frames[i] = (float)fmin(frames + 1.0, max_frames);
            } else {
                for (int c = 0; c < channels; ++c)
                    out[c] = cur[c];
                next->frames[i] = 1.0f;
            }
            next->depth[i] = (float)z;
        }
    return SOL_OK;
}

void sol_jitter_offset(unsigned frame, double *dx, double *dy)
{
    double u, v;
    sol_r2_point(frame, &u, &v);
    *dx = u - 0.5;
    *dy = v - 0.5;
}
