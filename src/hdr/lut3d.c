/* lut3d.c - global colour grading baked into a 3D LUT, trilinear and tetrahedral lookup, and
 * the talk's "chart" workflow (claim M4; talk, slides "Color grading", after Selan 2007,
 * "Using Lookup Tables to Accelerate Color Transformations", GPU Gems 2 ch. 24).
 * Tetrahedral interpolation: Kasson, Nin, Plouffe, Hafner, "Performing color space conversions
 * with three-dimensional linear interpolation", J. Electronic Imaging 4(3), 1995. */
#include "sol_hdr.h"

#include <math.h>
#include <stdlib.h>

enum { LUT_MIN_SIZE = 2, LUT_MAX_SIZE = 256 };

static sol_status lut_alloc(int size, sol_lut3d *out)
{
    size_t n = (size_t)size * (size_t)size * (size_t)size * 3u;
    float *data = malloc(n * sizeof *data);
    if (!data)
        return SOL_ERR_NO_MEMORY;
    out->size = size;
    out->data = data;
    return SOL_OK;
}

static float *lut_entry(const sol_lut3d *lut, int r, int g, int b)
{
    return lut->data + 3 * ((size_t)r + (size_t)lut->size * ((size_t)g + (size_t)lut->size * (size_t)b));
}

sol_status sol_lut3d_bake(int size, sol_color_fn fn, void *ctx, sol_lut3d *out)
{
    if (!fn || !out)
        return SOL_ERR_NULL_ARG;
    if (size < LUT_MIN_SIZE || size > LUT_MAX_SIZE)
        return SOL_ERR_INVALID_ARG;
    sol_lut3d lut;
    sol_status st = lut_alloc(size, &lut);
    if (st != SOL_OK)
        return st;
    double step = 1.0 / (size - 1);
    for (int b = 0; b < size; ++b)
        for (int g = 0; g < size; ++g)
            for (int r = 0; r < size; ++r) {
                double in[3] = {r * step, g * step, b * step}, res[3];
                fn(in, res, ctx);
                float *e = lut_entry(&lut, r, g, b);
                for (int c = 0; c < 3; ++c)
                    e[c] = (float)res[c];
            }
    *out = lut;
    return SOL_OK;
}

void sol_lut3d_free(sol_lut3d *lut)
{
    if (!lut)
        return;
    free(lut->data);
    lut->data = NULL;
    lut->size = 0;
}

/* Cell index (0..size-2) and fraction of a coordinate; NaN and out-of-range inputs clamp. */
static int cell_of(double v, int size, double *frac)
{
    double p = (v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0) * (size - 1);
    int i = (int)p;
    if (i > size - 2)
        i = size - 2;
    *frac = p - i;
    return i;
}

static void lookup_trilinear(const sol_lut3d *lut, const int i[3], const double t[3], double out[3])
{
    const float *base = lut_entry(lut, i[0], i[1], i[2]);
    const size_t step[3] = {3, 3 * (size_t)lut->size, 3 * (size_t)lut->size * (size_t)lut->size};
    out[0] = out[1] = out[2] = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        int dr = corner & 1, dg = (corner >> 1) & 1, db = corner >> 2;
        double w = (dr ? t[0] : 1 - t[0]) * (dg ? t[1] : 1 - t[1]) * (db ? t[2] : 1 - t[2]);
        const float *e = base + dr * step[0] + dg * step[1] + db * step[2];
        for (int c = 0; c < 3; ++c)
            out[c] += w * e[c];
    }
}

/* The cell's 6 tetrahedra share the diagonal (0,0,0)-(1,1,1); the ordering of the fractions picks
 * one, and the path from corner 000 to 111 steps along the largest fraction first. */
static void lookup_tetrahedral(const sol_lut3d *lut, const int i[3], const double t[3], double out[3])
{
    int order[3] = {0, 1, 2};
    for (int a = 0; a < 2; ++a) /* sort axes by decreasing fraction */
        for (int b = 0; b < 2 - a; ++b)
            if (t[order[b]] < t[order[b + 1]]) {
                int s = order[b];
                order[b] = order[b + 1];
                order[b + 1] = s;
            }
    int corner[3] = {0, 0, 0};
    const float *v0 = lut_entry(lut, i[0], i[1], i[2]);
    double w_prev = 1.0, acc[3];
    for (int c = 0; c < 3; ++c)
        acc[c] = 0.0;
    const float *prev = v0;
    for (int k = 0; k < 3; ++k) {
        double w = t[order[k]];
        for (int c = 0; c < 3; ++c)
            acc[c] += (w_prev - w) * prev[c];
        corner[order[k]] = 1;
        prev = lut_entry(lut, i[0] + corner[0], i[1] + corner[1], i[2] + corner[2]);
        w_prev = w;
    }
    for (int c = 0; c < 3; ++c)
        out[c] = acc[c] + w_prev * prev[c];
}

void sol_lut3d_apply(const sol_lut3d *lut, sol_lut_interp interp, const double in[3], double out[3])
{
    int i[3];
    double t[3];
    for (int c = 0; c < 3; ++c)
        i[c] = cell_of(in[c], lut->size, &t[c]);
    if (interp == SOL_LUT_TETRAHEDRAL)
        lookup_tetrahedral(lut, i, t, out);
    else
        lookup_trilinear(lut, i, t, out);
}

static int chart_fits(const sol_image *image, int x0, int y0, int size)
{
    return image->data && image->channels >= 3 && x0 >= 0 && y0 >= 0 && size >= LUT_MIN_SIZE &&
           size <= LUT_MAX_SIZE && (long)x0 + (long)size * size <= image->width && (long)y0 + size <= image->height;
}

sol_status sol_lut3d_chart_write(const sol_lut3d *lut, sol_image *image, int x0, int y0)
{
    if (!lut || !image || !lut->data)
        return SOL_ERR_NULL_ARG;
    if (!chart_fits(image, x0, y0, lut->size))
        return SOL_ERR_INVALID_ARG;
    int n = lut->size;
    for (int b = 0; b < n; ++b)
        for (int g = 0; g < n; ++g)
            for (int r = 0; r < n; ++r) {
                float *px = sol_image_pixel(image, x0 + b * n + r, y0 + g);
                const float *e = lut_entry(lut, r, g, b);
                px[0] = e[0];
                px[1] = e[1];
                px[2] = e[2];
            }
    return SOL_OK;
}

sol_status sol_lut3d_chart_read(const sol_image *image, int x0, int y0, int size, sol_lut3d *out)
{
    if (!image || !out)
        return SOL_ERR_NULL_ARG;
    if (!chart_fits(image, x0, y0, size))
        return SOL_ERR_INVALID_ARG;
    sol_lut3d lut;
    sol_status st = lut_alloc(size, &lut);
    if (st != SOL_OK)
        return st;
    for (int b = 0; b < size; ++b)
        for (int g = 0; g < size; ++g)
            for (int r = 0; r < size; ++r) {
                const float *px = sol_image_pixel(image, x0 + b * size + r, y0 + g);
                float *e = lut_entry(&lut, r, g, b);
                e[0] = px[0];
                e[1] = px[1];
                e[2] = px[2];
            }
    *out = lut;
    return SOL_OK;
}
