/* best_fit.c - claims D5, D6: best-fit normals (Kaplanyan 2010, "Normals precision for shading,
 * part III" and appendix A). The exact search walks the normal's ray through the 256^3 cube and
 * keeps the cell whose centre deviates least from the ray; the baked table stores the winning
 * scale per direction for the shader's one-lookup path. */
#include <stdlib.h>

#include "normals_internal.h"

/* Appendix A's FindMinimumQuantizationError in double precision. Probes sit at t = s / 255 for
 * odd s = 3..255 (the appendix's nStep = 1.5 .. 127.5 over 127.5): exactly the levels where the
 * ray's largest component crosses a cell centre. The error is the max-norm deviation of the
 * quantized probe divided by t (an angle-like relative error); the first minimum wins. */
uint32_t sol_normals_encode_best_fit(const double unit[3], double *t_out)
{
    double m = sol_normals_max_abs(unit);
    double d[3] = {unit[0] / m, unit[1] / m, unit[2] / m};
    double best_err = HUGE_VAL, best_t = 1.0;
    uint32_t best = 0;
    for (int s = 3; s <= 255; s += 2) {
        double t = s / 255.0, dev = 0.0;
        uint32_t c[3];
        for (int i = 0; i < 3; ++i) {
            double p = d[i] * t;
            c[i] = sol_normals_quantize255_fast(p);
            double e = fabs(sol_dequantize255(c[i]) - p);
            dev = e > dev ? e : dev;
        }
        /* max(|q-p|) / t equals the appendix's max(|q-p| / t): division is monotonic */
        double err = dev / t;
        if (err < best_err) {
            best_err = err;
            best_t = t;
            best = sol_normals_pack3(c);
        }
    }
    *t_out = best_t;
    return best;
}

static float quantize255_float(float c)
{
    float w = c * .5f + .5f;
    w = w < 0.f ? 0.f : (w > 1.f ? 1.f : w);
    return (float)(uint32_t)(w * 255.f + .5f); /* floor: the argument is positive */
}

/* The same search in single precision, statement by statement as the appendix's HLSL (input
 * rounded to float; HLSL's round() taken as round-half-up, like sol_quantize255). */
uint32_t sol_normals_encode_best_fit_float(const double unit[3])
{
    float n[3] = {(float)unit[0], (float)unit[1], (float)unit[2]};
    float m = fmaxf(fabsf(n[0]), fmaxf(fabsf(n[1]), fabsf(n[2])));
    for (int i = 0; i < 3; ++i)
        n[i] /= m;
    float best_err = 100000.f;
    uint32_t best = 0;
    for (float step = 1.5f; step <= 127.5f; ++step) {
        float t = step / 127.5f, dev = 0.f;
        uint32_t c[3];
        for (int i = 0; i < 3; ++i) {
            float p = n[i] * t, r = quantize255_float(p);
            c[i] = (uint32_t)r;
            dev = fmaxf(dev, fabsf(r / 255.f * 2.f - 1.f - p));
        }
        float err = dev / t; /* = the appendix's max of |q-p|/t: division is monotonic */
        if (err < best_err) {
            best_err = err;
            best = sol_normals_pack3(c);
        }
    }
    return best;
}

sol_status sol_bestfit_scale(const double n[3], double *t)
{
    if (!t)
        return SOL_ERR_NULL_ARG;
    double u[3], scale;
    sol_status st = sol_normals_unit_input(n, u);
    if (st != SOL_OK)
        return st;
    sol_normals_encode_best_fit(u, &scale);
    *t = scale;
    return SOL_OK;
}

static int table_bits_valid(int bits)
{
    return bits == 0 || bits == 8 || bits == 16;
}

/* A scale as the texture stores it: UNORM 8/16 bits or float. */
static float store_scale(double t, int bits)
{
    return bits ? (float)sol_unorm_decode(sol_unorm_encode(t, bits), bits) : (float)t;
}

static sol_status table_alloc(int size, int bits, sol_bestfit_table *out)
{
    float *scale = malloc((size_t)size * (size_t)size * sizeof *scale);
    if (!scale)
        return SOL_ERR_NO_MEMORY;
    out->size = size;
    out->bits = bits;
    out->scale = scale;
    return SOL_OK;
}

/* Direction (major, middle, minor) at the texel centre (u, v) of the shader's parametrisation. */
static void texel_direction(double u, double v, double dir[3])
{
    double a1 = u, a2 = u * v, rest = 1.0 - a1 * a1 - a2 * a2;
    if (rest < a1 * a1) { /* outside the octant's sorted wedge: clamp to the a0 = a1 edge */
        dir[0] = 1.0;
        dir[1] = 1.0;
        dir[2] = v;
        return;
    }
    dir[0] = sqrt(rest);
    dir[1] = a1;
    dir[2] = a2;
}

sol_status sol_bestfit_table_build(int size, int bits, sol_bestfit_table *out)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if (size < 1 || size > 16384 || !table_bits_valid(bits))
        return SOL_ERR_INVALID_ARG;
    sol_bestfit_table table;
    sol_status st = table_alloc(size, bits, &table);
    if (st != SOL_OK)
        return st;
#pragma omp parallel for schedule(dynamic, 8)
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            double dir[3], unit[3], t;
            texel_direction((i + 0.5) / size, (j + 0.5) / size, dir);
            sol_normals_unit_input(dir, unit);
            sol_normals_encode_best_fit(unit, &t);
            table.scale[(size_t)j * (size_t)size + (size_t)i] = store_scale(t, bits);
        }
    *out = table;
    return SOL_OK;
}

sol_status sol_bestfit_table_downsample(const sol_bestfit_table *src, sol_bestfit_table *out)
{
    if (!src || !out || !src->scale)
        return SOL_ERR_NULL_ARG;
    if (src->size < 2 || src->size % 2 || !table_bits_valid(src->bits))
        return SOL_ERR_INVALID_ARG;
    int n = src->size / 2;
    sol_bestfit_table table;
    sol_status st = table_alloc(n, src->bits, &table);
    if (st != SOL_OK)
        return st;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float *r0 = src->scale + (size_t)(2 * j) * (size_t)src->size + 2 * i;
            const float *r1 = r0 + src->size;
            table.scale[(size_t)j * (size_t)n + (size_t)i] =
                store_scale(0.25 * ((double)r0[0] + r0[1] + r1[0] + r1[1]), src->bits);
        }
    *out = table;
    return SOL_OK;
}

void sol_bestfit_table_free(sol_bestfit_table *table)
{
    if (!table)
        return;
    free(table->scale);
    table->scale = NULL;
    table->size = 0;
    table->bits = 0;
}

static double texel(const sol_bestfit_table *table, int i, int j)
{
    i = i < 0 ? 0 : (i >= table->size ? table->size - 1 : i);
    j = j < 0 ? 0 : (j >= table->size ? table->size - 1 : j);
    return table->scale[(size_t)j * (size_t)table->size + (size_t)i];
}

static double table_sample(const sol_bestfit_table *table, sol_table_filter filter, double u, double v)
{
    double x = u * table->size, y = v * table->size;
    if (filter == SOL_TABLE_NEAREST)
        return texel(table, (int)x, (int)y);
    x -= 0.5;
    y -= 0.5;
    double fx = floor(x), fy = floor(y);
    int i = (int)fx, j = (int)fy;
    double ax = x - fx, ay = y - fy;
    return (1 - ay) * ((1 - ax) * texel(table, i, j) + ax * texel(table, i + 1, j)) +
           ay * ((1 - ax) * texel(table, i, j + 1) + ax * texel(table, i + 1, j + 1));
}

/* Appendix A's CompressNormalToUnsignedGBuffer: sort |n| to (major, middle, minor), look up the
 * scale at (middle, minor / middle), scale n / major by it, quantize. */
sol_status sol_normal_encode_bestfit_table(const sol_bestfit_table *table, sol_table_filter filter,
                                           const double n[3], uint32_t *code)
{
    if (!table || !n || !code || !table->scale)
        return SOL_ERR_NULL_ARG;
    if (table->size < 1 || (filter != SOL_TABLE_NEAREST && filter != SOL_TABLE_BILINEAR))
        return SOL_ERR_INVALID_ARG;
    double u[3];
    sol_status st = sol_normals_unit_input(n, u);
    if (st != SOL_OK)
        return st;
    double a[3] = {fabs(u[0]), fabs(u[1]), fabs(u[2])};
    /* sort descending (three compare-swaps) */
    double tmp;
    if (a[0] < a[1]) { tmp = a[0]; a[0] = a[1]; a[1] = tmp; }
    if (a[1] < a[2]) { tmp = a[1]; a[1] = a[2]; a[2] = tmp; }
    if (a[0] < a[1]) { tmp = a[0]; a[0] = a[1]; a[1] = tmp; }
    double t = table_sample(table, filter, a[1], a[1] > 0.0 ? a[2] / a[1] : 0.0);
    double v[3] = {u[0] / a[0] * t, u[1] / a[0] * t, u[2] / a[0] * t};
    *code = sol_normals_quantize3(v);
    return SOL_OK;
}
