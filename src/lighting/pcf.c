/* pcf.c - S8: the 3x3-texel weighted-box PCF filter and Tesseract's approximation of it with 4
 * native bilinear shadow taps (seed 002, "filtershadow"). A bilinear comparison tap at a fraction t
 * between two texels returns (1-t) c0 + t c1 of their 0/1 comparisons, so two texels with box
 * weights (w0, w1) are covered by one tap of weight w0 + w1 at t = w1 / (w0 + w1). The exact tap
 * positions need that division; Tesseract replaces t by its linear approximation through the ends
 * (the seed of a Newton iteration for the reciprocal), which is what this file measures. */
#include "sol_lighting.h"

sol_status sol_pcf_weights_1d(sol_pcf_method method, double f, double weights[4])
{
    if (!weights)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(f))
        return SOL_ERR_NONFINITE;
    if (f < 0.0 || f > 1.0 || method < 0 || method >= SOL_PCF_METHOD_COUNT)
        return SOL_ERR_INVALID_ARG;
    if (method == SOL_PCF_BILINEAR4_FAST) {
        /* Taps of weight (2-f) at t = (1+f)/2 and (1+f) at t = f/2. */
        weights[0] = (2.0 - f) * (1.0 - f) / 2.0;
        weights[1] = (2.0 - f) * (1.0 + f) / 2.0;
        weights[2] = (1.0 + f) * (2.0 - f) / 2.0;
        weights[3] = (1.0 + f) * f / 2.0;
    } else { /* the box, whether summed texel by texel or through exactly placed bilinear taps */
        weights[0] = 1.0 - f;
        weights[1] = 1.0;
        weights[2] = 1.0;
        weights[3] = f;
    }
    return SOL_OK;
}

typedef struct shadow_map {
    const float *depth;
    int width, height;
    double receiver;
} shadow_map;

static int clamp_index(int i, int n)
{
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

static double compare_texel(const shadow_map *m, int i, int j)
{
    return m->receiver <= m->depth[(size_t)clamp_index(j, m->height) * (size_t)m->width + (size_t)clamp_index(i, m->width)]
               ? 1.0
               : 0.0;
}

/* A native bilinear shadow tap at (x, y): the 4 nearest texels' comparisons, bilinearly weighted. */
static double bilinear_tap(const shadow_map *m, double x, double y)
{
    double px = x - 0.5, py = y - 0.5;
    double fx = floor(px), fy = floor(py);
    int i = (int)fx, j = (int)fy;
    double tx = px - fx, ty = py - fy;
    double top = (1.0 - tx) * compare_texel(m, i, j) + tx * compare_texel(m, i + 1, j);
    double bottom = (1.0 - tx) * compare_texel(m, i, j + 1) + tx * compare_texel(m, i + 1, j + 1);
    return (1.0 - ty) * top + ty * bottom;
}

static double box_exact(const shadow_map *m, double x, double y)
{
    double px = x - 0.5, py = y - 0.5;
    int i = (int)floor(px), j = (int)floor(py);
    double wx[4], wy[4];
    (void)sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, px - i, wx);
    (void)sol_pcf_weights_1d(SOL_PCF_BOX_EXACT, py - j, wy);
    double sum = 0.0;
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a)
            sum += wx[a] * wy[b] * compare_texel(m, i - 1 + a, j - 1 + b);
    return sum / 9.0;
}

/* Tesseract's commented "more precise" version: tap offsets 1/size - 1 and 2 - 1/size. */
static double bilinear4_exact(const shadow_map *m, double x, double y)
{
    double fx = x - 0.5 - floor(x - 0.5), fy = y - 0.5 - floor(y - 0.5);
    double cx = x - fx, cy = y - fy;
    double lo_x = 2.0 - fx, hi_x = 1.0 + fx, lo_y = 2.0 - fy, hi_y = 1.0 + fy; /* tap weights */
    double ox0 = 1.0 / lo_x - 1.0, ox1 = 2.0 - 1.0 / hi_x, oy0 = 1.0 / lo_y - 1.0, oy1 = 2.0 - 1.0 / hi_y;
    return (lo_x * lo_y * bilinear_tap(m, cx + ox0, cy + oy0) + hi_x * lo_y * bilinear_tap(m, cx + ox1, cy + oy0) +
            lo_x * hi_y * bilinear_tap(m, cx + ox0, cy + oy1) + hi_x * hi_y * bilinear_tap(m, cx + ox1, cy + oy1)) /
           9.0;
}

/* Tesseract's shipped filter: centre moved by half the fraction, fixed offsets -0.5 and 1. */
static double bilinear4_fast(const shadow_map *m, double x, double y)
{
    double fx = x - 0.5 - floor(x - 0.5), fy = y - 0.5 - floor(y - 0.5);
    double cx = x - 0.5 * fx, cy = y - 0.5 * fy;
    double lo_x = 2.0 - fx, hi_x = 1.0 + fx, lo_y = 2.0 - fy, hi_y = 1.0 + fy;
    return (lo_x * lo_y * bilinear_tap(m, cx - 0.5, cy - 0.5) + hi_x * lo_y * bilinear_tap(m, cx + 1.0, cy - 0.5) +
            lo_x * hi_y * bilinear_tap(m, cx - 0.5, cy + 1.0) + hi_x * hi_y * bilinear_tap(m, cx + 1.0, cy + 1.0)) /
           9.0;
}

static double clamp_coordinate(double x, int n)
{
    /* Beyond 4 texels outside the map every tap reads the edge texel: clamping keeps the result and
     * keeps floor() within int range. */
    return x < -4.0 ? -4.0 : x > n + 4.0 ? n + 4.0 : x;
}

sol_status sol_pcf_filter(const float *map, int width, int height, double x, double y, double depth,
                          sol_pcf_method method, double *lit)
{
    if (!map || !lit)
        return SOL_ERR_NULL_ARG;
    if (width < 1 || height < 1 || method < 0 || method >= SOL_PCF_METHOD_COUNT)
        return SOL_ERR_INVALID_ARG;
    if (!isfinite(x) || !isfinite(y) || !isfinite(depth))
        return SOL_ERR_NONFINITE;
    shadow_map m = {map, width, height, depth};
    x = clamp_coordinate(x, width);
    y = clamp_coordinate(y, height);
    double value = method == SOL_PCF_BOX_EXACT         ? box_exact(&m, x, y)
                   : method == SOL_PCF_BILINEAR4_EXACT ? bilinear4_exact(&m, x, y)
                                                       : bilinear4_fast(&m, x, y);
    /* Rounding can leave the sum a few ulps outside [0,1]. */
    *lit = value < 0.0 ? 0.0 : value > 1.0 ? 1.0 : value;
    return SOL_OK;
}
