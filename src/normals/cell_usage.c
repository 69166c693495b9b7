/* cell_usage.c - claims D3, D4, D5: how many of the 256^3 cells of a 24-bit XYZ normal a method
 * uses, under explicit definitions (see sol_normals.h). Integer counts, so the OpenMP reductions
 * give the same result for any thread count. */
#include <stdlib.h>
#include <string.h>

#include "normals_internal.h"

static int is_xyz_method(sol_normal_method method)
{
    return method == SOL_NORMAL_XYZ_NORMALIZED || method == SOL_NORMAL_XYZ_MAX_COMPONENT ||
           method == SOL_NORMAL_XYZ_BEST_FIT || method == SOL_NORMAL_XYZ_BEST_FIT_FLOAT;
}

sol_status sol_normal_cells_fixed(sol_normal_method method, int r_begin, int r_end, uint64_t *count)
{
    if (!count)
        return SOL_ERR_NULL_ARG;
    if (!is_xyz_method(method) || r_begin < 0 || r_end > 256 || r_begin > r_end)
        return SOL_ERR_INVALID_ARG;
    uint64_t total = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : total)
    for (int r = r_begin; r < r_end; ++r)
        for (uint32_t g = 0; g < 256; ++g)
            for (uint32_t b = 0; b < 256; ++b) {
                uint32_t cell = (uint32_t)r | (g << 8) | (b << 16), back;
                double centre[3] = {sol_dequantize255((uint32_t)r), sol_dequantize255(g), sol_dequantize255(b)};
                sol_normal_encode(method, centre, &back); /* centres are finite and non-zero */
                total += back == cell;
            }
    *count = total;
    return SOL_OK;
}

static int levels_valid(int levels)
{
    return levels >= 2 && levels <= 4096 && levels % 2 == 0;
}

sol_status sol_normal_cells_on_sphere(int levels, uint64_t *count)
{
    if (!count)
        return SOL_ERR_NULL_ARG;
    if (!levels_valid(levels))
        return SOL_ERR_INVALID_ARG;
    /* In units of half a cell the centres are odd integers c, the box is [|c|-1, |c|+1] per axis
     * and the sphere's radius is R = levels - 1. The box meets it iff min^2 <= R^2 <= max^2. */
    int64_t r2 = (int64_t)(levels - 1) * (levels - 1);
    uint64_t total = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : total)
    for (int i = 0; i < levels; ++i) {
        int64_t a = llabs(2 * (int64_t)i - (levels - 1));
        for (int j = 0; j < levels; ++j) {
            int64_t b = llabs(2 * (int64_t)j - (levels - 1));
            for (int k = 0; k < levels; ++k) {
                int64_t c = llabs(2 * (int64_t)k - (levels - 1));
                int64_t lo = (a - 1) * (a - 1) + (b - 1) * (b - 1) + (c - 1) * (c - 1);
                int64_t hi = (a + 1) * (a + 1) + (b + 1) * (b + 1) + (c + 1) * (c + 1);
                total += lo <= r2 && r2 <= hi;
            }
        }
    }
    *count = total;
    return SOL_OK;
}

sol_status sol_normal_cells_near_sphere(int levels, double half_width, uint64_t *count)
{
    if (!count)
        return SOL_ERR_NULL_ARG;
    if (!levels_valid(levels) || !(half_width >= 0.0) || !isfinite(half_width))
        return SOL_ERR_INVALID_ARG;
    /* Half-cell units: odd centres c, radius R = levels - 1; |c| is exact in double, sqrt correctly
     * rounded, so the test is exact whenever the bound is (integer widths, perfect squares). */
    double radius = levels - 1;
    uint64_t total = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : total)
    for (int i = 0; i < levels; ++i) {
        int64_t a = 2 * (int64_t)i - (levels - 1);
        for (int j = 0; j < levels; ++j) {
            int64_t b = 2 * (int64_t)j - (levels - 1), ab = a * a + b * b;
            for (int k = 0; k < levels; ++k) {
                int64_t c = 2 * (int64_t)k - (levels - 1);
                total += fabs(sqrt((double)(ab + c * c)) - radius) <= half_width;
            }
        }
    }
    *count = total;
    return SOL_OK;
}

static int64_t gcd64(int64_t a, int64_t b)
{
    while (b) {
        int64_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

sol_status sol_normal_cells_distinct_directions(int levels, uint64_t *count)
{
    if (!count)
        return SOL_ERR_NULL_ARG;
    if (!levels_valid(levels))
        return SOL_ERR_INVALID_ARG;
    uint64_t total = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : total)
    for (int i = 0; i < levels; ++i) {
        int64_t a = llabs(2 * (int64_t)i - (levels - 1));
        for (int j = 0; j < levels; ++j) {
            int64_t ab = gcd64(a, llabs(2 * (int64_t)j - (levels - 1)));
            for (int k = 0; k < levels; ++k)
                total += gcd64(ab, llabs(2 * (int64_t)k - (levels - 1))) == 1;
        }
    }
    *count = total;
    return SOL_OK;
}

/* One best-fit search of a cell centre under the chosen precision and input path. */
static uint32_t bestfit_variant(const sol_bestfit_cells_options *o, const double centre[3])
{
    double in[3], t;
    if (o->input == SOL_BESTFIT_INPUT_UNIT)
        sol_normals_unit_input(centre, in); /* centres are finite and non-zero */
    else
        memcpy(in, centre, sizeof in);
    if (o->input == SOL_BESTFIT_INPUT_HALF)
        return o->single ? sol_normals_encode_best_fit_half(in) : sol_normals_encode_best_fit_half_double(in);
    return o->single ? sol_normals_encode_best_fit_float(in) : sol_normals_encode_best_fit(in, &t);
}

sol_status sol_normal_cells_bestfit(const sol_bestfit_cells_options *opt, int r_begin, int r_end,
                                    sol_bestfit_cells *out)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    sol_bestfit_cells_options o = opt ? *opt : (sol_bestfit_cells_options){0};
    if ((o.single != 0 && o.single != 1) || (int)o.input < 0 || o.input > SOL_BESTFIT_INPUT_HALF || r_begin < 0 ||
        r_end > 256 || r_begin > r_end)
        return SOL_ERR_INVALID_ARG;
    uint64_t *seen = calloc((size_t)1 << 18, sizeof *seen); /* one bit per 24-bit code */
    if (!seen)
        return SOL_ERR_NO_MEMORY;
    uint64_t fixed = 0, image = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : fixed)
    for (int r = r_begin; r < r_end; ++r)
        for (uint32_t g = 0; g < 256; ++g)
            for (uint32_t b = 0; b < 256; ++b) {
                uint32_t cell = (uint32_t)r | (g << 8) | (b << 16);
                double centre[3] = {sol_dequantize255((uint32_t)r), sol_dequantize255(g), sol_dequantize255(b)};
                uint32_t code = bestfit_variant(&o, centre);
                fixed += code == cell;
#pragma omp atomic
                seen[code >> 6] |= (uint64_t)1 << (code & 63u);
            }
    for (size_t w = 0; w < (size_t)1 << 18; ++w)
        for (uint64_t bits = seen[w]; bits; bits &= bits - 1)
            ++image;
    free(seen);
    out->image = image;
    out->fixed = fixed;
    return SOL_OK;
}
