/* common.c - directions, error statistics and the encoder wrapper of the encodings driver. */
#include "encodings.h"

#include <math.h>
#include <stdlib.h>

void r2_direction(uint64_t i, double d[3])
{
    double u, v;
    sol_r2_point(i, &u, &v);
    sol_sphere_uniform(u, v, d);
}

/* k-th smallest value (Hoare's selection; deterministic, O(n) on average). */
static float select_kth(float *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        float pivot = a[lo + (hi - lo) / 2];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (a[i] < pivot)
                ++i;
            while (a[j] > pivot)
                --j;
            if (i <= j) {
                float t = a[i];
                a[i] = a[j];
                a[j] = t;
                ++i;
                if (j == 0)
                    break;
                --j;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return a[k];
    }
    return a[k];
}

error_stats stats_of(float *err, size_t n)
{
    error_stats s = {0, 0, 0, 0};
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; ++i) { /* in order: the same sum whatever the thread count */
        sum += err[i];
        sum2 += (double)err[i] * err[i];
        s.max = err[i] > s.max ? err[i] : s.max;
    }
    s.mean = sum / (double)n;
    s.rms = sqrt(sum2 / (double)n);
    s.p99 = select_kth(err, n, (size_t)(0.99 * (double)(n - 1)));
    return s;
}

double effective_bits(double rms_deg)
{
    double rms = rms_deg / DEG;
    return log2(2.0 / (rms * rms));
}

uint32_t encode_with(const encoder *e, const double n[3])
{
    uint32_t code = 0;
    sol_status st = e->table ? sol_normal_encode_bestfit_table(e->table, e->filter, n, &code)
                             : sol_normal_encode(e->method, n, &code);
    if (st != SOL_OK)
        exp_check(st, "encoding with %s", e->name);
    return code;
}

void decode_with(const encoder *e, uint32_t code, double n[3])
{
    sol_status st = sol_normal_decode(e->method, code, n);
    if (st != SOL_OK)
        exp_check(st, "decoding with %s", e->name);
}

void encoder_errors(const encoder *e, size_t n, float *err)
{
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < (int64_t)n; ++i) {
        double d[3], back[3];
        r2_direction((uint64_t)i, d);
        decode_with(e, encode_with(e, d), back);
        err[i] = (float)(sol_angle3(d, back) * DEG);
    }
}
