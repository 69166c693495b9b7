/* best_fit.c - claims D5, D6: best-fit normals (Kaplanyan 2010, "Normals precision for shading,
 * part III" and appendix A). The exact search walks the normal's ray through the 256^3 cube and
 * keeps the cell whose centre deviates least from the ray; the baked table stores the winning
 * scale per direction for the shader's one-lookup path. */
#include <stdlib.h>

#include "normals_internal.h"

enum { PROBES = 127 }; /* s = 3, 5, ..., 255 (the appendix's nStep = 1.5, 2.5, ..., 127.5) */

/* The probe loops below run 2 (SSE2), 4 (AVX2) or 8 (AVX-512) lanes wide, picked at run time
 * (GCC function multi-versioning): every lane does the scalar IEEE operations (mul, add, div,
 * truncating conversion, compare; no FMA contraction under -std=c11), so every width returns the
 * same code bit for bit. The searches are d3_d5's and d6_d7's hot loop (~10^10 probes). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) /* clang cannot vectorize the clones */
#define SOL_BESTFIT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define SOL_BESTFIT_CLONES
#endif
/* The minimum reductions below vectorize under GCC's omp simd; clang -O1 (the fuzz build) cannot
 * and would warn, so it gets the plain loop. */
#if defined(__clang__)
#define SOL_SIMD_MIN_M
#else
#define SOL_SIMD_MIN_M _Pragma("omp simd reduction(min : m)")
#endif

/* Index of the first minimum of the probes' errors (the appendix's scan keeps the first of equal
 * errors): the minimum value by a vectorized reduction (exact in any order: the errors are finite
 * and non-negative), then the first probe holding it. The same index as the scan
 * `if (err[k] < err[best]) best = k`, without its load-compare chain through `best`. */
#define SOL_DEFINE_FIRST_MIN(name, type)                                                           \
    static inline int name(const type *err)                                                        \
    {                                                                                              \
        type m = err[0];                                                                           \
        SOL_SIMD_MIN_M                                                                             \
        for (int k = 1; k < PROBES; ++k)                                                           \
            m = err[k] < m ? err[k] : m;                                                           \
        int best = 0;                                                                              \
        while (best < PROBES - 1 && err[best] != m) /* no NaN reaches here, but never overrun */ \
            ++best;                                                                                \
        return best;                                                                               \
    }
/* one body for the double and float searches */
SOL_DEFINE_FIRST_MIN(first_min_double, double)
SOL_DEFINE_FIRST_MIN(first_min_float, float)

/* Appendix A's FindMinimumQuantizationError in double precision. Probes sit at t = s / 255 for
 * odd s = 3..255 (the appendix's nStep = 1.5 .. 127.5 over 127.5): exactly the levels where the
 * ray's largest component crosses a cell centre. The error is the max-norm deviation of the
 * quantized probe divided by t (an angle-like relative error); the first minimum wins.
 * The probes' errors are computed in one loop the compiler vectorizes (every operation is the
 * scalar IEEE one, so the errors are bit for bit the scalar loop's), then scanned in order.
 * `v` need not be unit length: it is divided by its largest |component| first. */
SOL_BESTFIT_CLONES uint32_t sol_normals_encode_best_fit(const double v[3], double *t_out)
{
    double m = sol_normals_max_abs(v);
    double d0 = v[0] / m, d1 = v[1] / m, d2 = v[2] / m;
    double err[PROBES];
#pragma omp simd
    for (int k = 0; k < PROBES; ++k) {
        double t = (double)(2 * k + 3) / 255.0;
        double p0 = d0 * t, p1 = d1 * t, p2 = d2 * t;
        /* quantize255 of a probe in [-1, 1] (argument >= 0.5: truncation is floor), then back */
        double q0 = (double)(int32_t)((p0 * 0.5 + 0.5) * 255.0 + 0.5) / 255.0 * 2.0 - 1.0;
        double q1 = (double)(int32_t)((p1 * 0.5 + 0.5) * 255.0 + 0.5) / 255.0 * 2.0 - 1.0;
        double q2 = (double)(int32_t)((p2 * 0.5 + 0.5) * 255.0 + 0.5) / 255.0 * 2.0 - 1.0;
        double e0 = fabs(q0 - p0), e1 = fabs(q1 - p1), e2 = fabs(q2 - p2);
        double dev = e0 > e1 ? e0 : e1;
        dev = e2 > dev ? e2 : dev;
        /* max(|q-p|) / t equals the appendix's max(|q-p| / t): division is monotonic */
        err[k] = dev / t;
    }
    int best = first_min_double(err);
    double t = (double)(2 * best + 3) / 255.0;
    double p[3] = {d0 * t, d1 * t, d2 * t};
    *t_out = t;
    return sol_normals_pack3((uint32_t[3]){sol_normals_quantize255_fast(p[0]), sol_normals_quantize255_fast(p[1]),
                                           sol_normals_quantize255_fast(p[2])});
}

/* The search in single precision, statement by statement as the appendix's HLSL (HLSL's round()
 * taken as round-half-up, like sol_quantize255), errors vectorized as above. */
SOL_BESTFIT_CLONES static uint32_t best_fit_float(float n0, float n1, float n2)
{
    float m = fmaxf(fabsf(n0), fmaxf(fabsf(n1), fabsf(n2)));
    n0 /= m;
    n1 /= m;
    n2 /= m;
    float err[PROBES];
#pragma omp simd
    for (int k = 0; k < PROBES; ++k) {
        float t = (1.5f + (float)k) / 127.5f;
        float p0 = n0 * t, p1 = n1 * t, p2 = n2 * t;
        /* saturate: the probes lie in [-1, 1], so c * .5 + .5 is already in [0, 1] */
        float r0 = (float)(int32_t)((p0 * .5f + .5f) * 255.f + .5f);
        float r1 = (float)(int32_t)((p1 * .5f + .5f) * 255.f + .5f);
        float r2 = (float)(int32_t)((p2 * .5f + .5f) * 255.f + .5f);
        float e0 = fabsf(r0 / 255.f * 2.f - 1.f - p0), e1 = fabsf(r1 / 255.f * 2.f - 1.f - p1),
              e2 = fabsf(r2 / 255.f * 2.f - 1.f - p2);
        float dev = e0 > e1 ? e0 : e1; /* the HLSL's max (no NaN here), as a compare the loop vectorizes */
        dev = e2 > dev ? e2 : dev;
        err[k] = dev / t; /* = the appendix's max of |q-p|/t: division is monotonic */
    }
    int best = first_min_float(err); /* the appendix starts from fMinError = 100000: every error is below it */
    float t = (1.5f + (float)best) / 127.5f, p[3] = {n0 * t, n1 * t, n2 * t};
    uint32_t c[3];
    for (int i = 0; i < 3; ++i)
        c[i] = (uint32_t)((p[i] * .5f + .5f) * 255.f + .5f);
    return sol_normals_pack3(c);
}

/* Input rounded to float (the HLSL's arithmetic), then the float search. */
uint32_t sol_normals_encode_best_fit_float(const double v[3])
{
    return best_fit_float((float)v[0], (float)v[1], (float)v[2]);
}

/* A float rounded to half precision (11 significant bits, ties to even); the inputs here are
 * normal halves (|x| in [2^-14, 65504]) or zero. */
static float round_to_half(float x)
{
    if (x == 0.0f)
        return x;
    int e;
    double m = frexp((double)x, &e);
    return (float)ldexp(nearbyint(ldexp(m, 11)), e - 11);
}

/* The appendix's signature, FindMinimumQuantizationError(half3 normal): input rounded to half,
 * then the float search (_half) or the double search (_half_double). */
uint32_t sol_normals_encode_best_fit_half(const double v[3])
{
    return best_fit_float(round_to_half((float)v[0]), round_to_half((float)v[1]), round_to_half((float)v[2]));
}

uint32_t sol_normals_encode_best_fit_half_double(const double v[3])
{
    double h[3] = {round_to_half((float)v[0]), round_to_half((float)v[1]), round_to_half((float)v[2])}, t;
    return sol_normals_encode_best_fit(h, &t);
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
