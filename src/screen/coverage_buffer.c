/* coverage_buffer.c - claim M1: the coverage buffer. The previous frame's depth is reduced to a
 * low resolution with a max() filter (conservative: a texel is never nearer than the geometry it
 * stands for), a min/max mip hierarchy is built on top, and a box's screen bounds are tested
 * from the level where they cover at most 2x2 texels, refining undecided texels at finer levels
 * (talk, "Occlusion culling" slide and notes; the same idea as Hi-Z, Greene et al. 1993). */
#include "sol_screen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int half_up(int n)
{
    return (n + 1) / 2;
}

/* Level 0: one value per block x block pixels (partial blocks at the right/bottom edge). */
static void downscale_level0(const float *depth, int width, int height, int block, sol_downscale mode,
                             int out_w, int out_h, float *out)
{
    for (int ty = 0; ty < out_h; ++ty)
        for (int tx = 0; tx < out_w; ++tx) {
            double lo = INFINITY, hi = -INFINITY, sum = 0.0;
            int count = 0;
            for (int py = ty * block; py < height && py < (ty + 1) * block; ++py)
                for (int px = tx * block; px < width && px < (tx + 1) * block; ++px) {
                    double z = depth[(size_t)py * (size_t)width + (size_t)px];
                    lo = fmin(lo, z);
                    hi = fmax(hi, z);
                    sum += z;
                    ++count;
                }
            double value = mode == SOL_DOWNSCALE_MAX ? hi : mode == SOL_DOWNSCALE_MIN ? lo : sum / count;
            out[(size_t)ty * (size_t)out_w + (size_t)tx] = (float)value;
        }
}

/* Level l+1 from level l: min of the children's zmin, max of their zmax. */
static void reduce_level(sol_cbuffer *b, int l)
{
    const int w = b->width[l], h = b->height[l], pw = b->width[l + 1], ph = b->height[l + 1];
    for (int ty = 0; ty < ph; ++ty)
        for (int tx = 0; tx < pw; ++tx) {
            float lo = INFINITY, hi = -INFINITY;
            for (int cy = 2 * ty; cy < h && cy <= 2 * ty + 1; ++cy)
                for (int cx = 2 * tx; cx < w && cx <= 2 * tx + 1; ++cx) {
                    size_t i = (size_t)cy * (size_t)w + (size_t)cx;
                    lo = fminf(lo, b->zmin[l][i]);
                    hi = fmaxf(hi, b->zmax[l][i]);
                }
            b->zmin[l + 1][(size_t)ty * (size_t)pw + (size_t)tx] = lo;
            b->zmax[l + 1][(size_t)ty * (size_t)pw + (size_t)tx] = hi;
        }
}

sol_status sol_cbuffer_build(const float *depth, int width, int height, const sol_cbuffer_options *options,
                             sol_cbuffer *out)
{
    if (!depth || !out)
        return SOL_ERR_NULL_ARG;
    sol_cbuffer_options opt = options ? *options : (sol_cbuffer_options){0};
    int block = opt.block ? opt.block : 4;
    if (width < 1 || height < 1 || block < 1 || (unsigned)opt.downscale > SOL_DOWNSCALE_MEAN)
        return SOL_ERR_INVALID_ARG;
    for (size_t i = 0; i < (size_t)width * (size_t)height; ++i)
        if (!isfinite(depth[i]))
            return SOL_ERR_NONFINITE;
    sol_cbuffer b;
    memset(&b, 0, sizeof b);
    b.block = block;
    b.full_width = width;
    b.full_height = height;
    b.width[0] = (width - 1) / block + 1; /* ceil(width / block); width + block - 1 overflows int */
    b.height[0] = (height - 1) / block + 1;
    for (b.levels = 1; b.width[b.levels - 1] > 1 || b.height[b.levels - 1] > 1; ++b.levels) {
        if (b.levels == SOL_CBUFFER_MAX_LEVELS)
            return SOL_ERR_LIMIT; /* level 0 wider or taller than 2^23 texels (see the header) */
        b.width[b.levels] = half_up(b.width[b.levels - 1]);
        b.height[b.levels] = half_up(b.height[b.levels - 1]);
    }
    for (int l = 0; l < b.levels; ++l) {
        size_t n = (size_t)b.width[l] * (size_t)b.height[l];
        b.zmin[l] = malloc(n * sizeof(float));
        b.zmax[l] = l ? malloc(n * sizeof(float)) : b.zmin[0]; /* level 0 holds one value */
        if (!b.zmin[l] || !b.zmax[l]) {
            sol_cbuffer_free(&b);
            return SOL_ERR_NO_MEMORY;
        }
    }
    downscale_level0(depth, width, height, block, opt.downscale, b.width[0], b.height[0], b.zmin[0]);
    for (int l = 0; l + 1 < b.levels; ++l)
        reduce_level(&b, l);
    *out = b;
    return SOL_OK;
}

void sol_cbuffer_free(sol_cbuffer *buffer)
{
    if (!buffer)
        return;
    for (int l = 0; l < SOL_CBUFFER_MAX_LEVELS; ++l) {
        if (buffer->zmax[l] != buffer->zmin[l])
            free(buffer->zmax[l]);
        free(buffer->zmin[l]);
    }
    memset(buffer, 0, sizeof *buffer);
}

/* The query in texel terms: the full-resolution pixel rectangle the bounds touch. */
typedef struct query {
    const sol_cbuffer *b;
    int px0, py0, px1, py1; /* inclusive full-resolution pixel range */
    float znear;
    int stop_level; /* finest level the refinement may reach */
    int visited;
} query;

/* 1 when the texel (l, tx, ty), restricted to the query rectangle, provably hides the box. */
static int texel_occludes(query *q, int l, int tx, int ty)
{
    const sol_cbuffer *b = q->b;
    size_t i = (size_t)ty * (size_t)b->width[l] + (size_t)tx;
    q->visited++;
    if (q->znear > b->zmax[l][i])
        return 1; /* everything stored here is nearer than the box's nearest point */
    if (q->znear < b->zmin[l][i] || l <= q->stop_level)
        return 0; /* in front of everything here, or undecided with no finer level allowed */
    /* child texel size in full-resolution pixels; 64-bit: block << level can pass INT_MAX */
    const int64_t span = (int64_t)b->block << (l - 1);
    int cx0 = (int)(q->px0 / span), cx1 = (int)(q->px1 / span), cy0 = (int)(q->py0 / span), cy1 = (int)(q->py1 / span);
    for (int cy = 2 * ty; cy <= 2 * ty + 1 && cy < b->height[l - 1]; ++cy)
        for (int cx = 2 * tx; cx <= 2 * tx + 1 && cx < b->width[l - 1]; ++cx)
            if (cx >= cx0 && cx <= cx1 && cy >= cy0 && cy <= cy1 && !texel_occludes(q, l - 1, cx, cy))
                return 0;
    return 1;
}

/* Clips [lo, hi] to the pixel cells [0, size-1] it touches; returns 0 if nothing remains. */
static int clip_range(double lo, double hi, int size, int *first, int *last)
{
    if (hi < 0.0 || lo >= size)
        return 0;
    *first = lo <= 0.0 ? 0 : (int)floor(lo);
    *last = hi >= size ? size - 1 : (int)floor(hi);
    return 1;
}

sol_status sol_cbuffer_test(const sol_cbuffer *buffer, const sol_screen_bounds *bounds, int max_refine,
                            int *occluded, int *texels_visited)
{
    if (!buffer || !bounds || !occluded || !buffer->levels)
        return SOL_ERR_NULL_ARG;
    if (isnan(bounds->x0) || isnan(bounds->x1) || isnan(bounds->y0) || isnan(bounds->y1) ||
        !isfinite(bounds->znear))
        return SOL_ERR_NONFINITE;
    if (bounds->x1 < bounds->x0 || bounds->y1 < bounds->y0)
        return SOL_ERR_INVALID_ARG;
    query q = {.b = buffer, .znear = (float)bounds->znear};
    if (!clip_range(bounds->x0, bounds->x1, buffer->full_width, &q.px0, &q.px1) ||
        !clip_range(bounds->y0, bounds->y1, buffer->full_height, &q.py0, &q.py1)) {
        *occluded = 0;
        if (texels_visited)
            *texels_visited = 0;
        return SOL_OK;
    }
    /* Start level: the finest one where the rectangle spans at most 2 texels on each axis. */
    int start = 0;
    while (start + 1 < buffer->levels) {
        int64_t span = (int64_t)buffer->block << start;
        if (q.px1 / span - q.px0 / span <= 1 && q.py1 / span - q.py0 / span <= 1)
            break;
        ++start;
    }
    q.stop_level = max_refine < 0 || max_refine > start ? 0 : start - max_refine;
    /* The float znear is rounded down so the float comparisons stay conservative. */
    if ((double)q.znear > bounds->znear)
        q.znear = nextafterf(q.znear, -INFINITY);
    const int64_t span = (int64_t)buffer->block << start;
    int hidden = 1;
    for (int ty = (int)(q.py0 / span); hidden && ty <= (int)(q.py1 / span); ++ty)
        for (int tx = (int)(q.px0 / span); hidden && tx <= (int)(q.px1 / span); ++tx)
            hidden = texel_occludes(&q, start, tx, ty);
    *occluded = hidden;
    if (texels_visited)
        *texels_visited = q.visited;
    return SOL_OK;
}
