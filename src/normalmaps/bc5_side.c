/* bc5_side.c - an anchor pair's channel side (issue 13), read by the exact search's per-pixel bound
 * (bc5.c joint_objective_quick) and the adaptive encoder's window quick bound (T13).
 *
 * sol_nm_channel_side: per pixel the nearest palette entry's value v (the first one, in palette
 * order, on equal distances), its squared distance m1 and the least squared distance m2 of an entry of
 * ANOTHER value (INFINITY if every entry has v's value). The definition takes two passes (find the
 * nearest, then the least distance over the entries of other values; the tests hold it literally);
 * this takes one pass over the 8 entries.
 * Why one pass gives the same m2: m2 is the least of {d_i : pal_i != v}, the distances of the
 * entries whose value is not the final nearest one. Walk the entries in order keeping the nearest so
 * far (v, m1: replaced only on a strictly smaller d, the definition's strict comparison) and
 * m2 = the least d of the entries seen whose value is not v:
 *   - an entry with d < m1 becomes the nearest; the entries of the previous nearest value v' (all at
 *     distance m1, the same value) now count, so m2 = min(m2, m1). None of the entries seen before has
 *     the new value (it would be at the same distance d < m1, and m1 is at most its distance);
 *   - an entry with d >= m1 and a value other than v counts (m2 = min(m2, d)); one with v's value does
 *     not (it is at distance m1 and counts, through the first case, if v is ever replaced).
 * No entry seen can take the final nearest value later (that value's distance would be below m1 at
 * the time it came), so at the end m2 is the least d over exactly the entries of a value other than
 * v: the same set of doubles as the two-pass form, hence the same least value (squares are >= +0, no
 * NaN: min is exact). Values compare as numbers (!=: -0 equals +0).
 * The AVX2 form (4 pixels per instruction) takes per lane the operations of the scalar walk: the same
 * IEEE subtraction and product per entry, comparisons and blends selecting as the ternaries. */
#include "normalmaps_internal.h"

/* The scalar walk (reference; the tests compare the AVX2 form with it). */
void sol_nm_channel_side_scalar(const double pal[8], const double t[16], double *v, double *m1, double *m2,
                               size_t stride)
{
    for (int k = 0; k < 16; ++k) {
        double tk = t[k], d0 = (pal[0] - tk) * (pal[0] - tk), vk = pal[0], m1k = d0, m2k = INFINITY;
        for (int i = 1; i < 8; ++i) {
            double d = (pal[i] - tk) * (pal[i] - tk);
            if (d < m1k) {
                m2k = m1k < m2k ? m1k : m2k;
                m1k = d;
                vk = pal[i];
            } else if (pal[i] != vk) {
                m2k = d < m2k ? d : m2k;
            }
        }
        v[(size_t)k * stride] = vk;
        m1[(size_t)k * stride] = m1k;
        m2[(size_t)k * stride] = m2k;
    }
}

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#include <immintrin.h>

__attribute__((target("avx2"))) void sol_nm_channel_side_avx2(const double pal[8], const double t[16], double *v,
                                                            double *m1, double *m2, size_t stride)
{
    const __m256d inf = _mm256_set1_pd(INFINITY);
    for (int k = 0; k < 16; k += 4) {
        const __m256d tk = _mm256_loadu_pd(t + k);
        __m256d p = _mm256_set1_pd(pal[0]), d = _mm256_sub_pd(p, tk);
        __m256d m1k = _mm256_mul_pd(d, d), vk = p, m2k = inf;
        for (int i = 1; i < 8; ++i) {
            p = _mm256_set1_pd(pal[i]);
            d = _mm256_sub_pd(p, tk);
            d = _mm256_mul_pd(d, d);
            const __m256d lt = _mm256_cmp_pd(d, m1k, _CMP_LT_OQ), ne = _mm256_cmp_pd(p, vk, _CMP_NEQ_UQ);
            /* the distance that now counts: m1 where d < m1 (the old nearest value), else d where the
             * value differs from v, else none (INFINITY leaves m2 as it is) */
            const __m256d c = _mm256_blendv_pd(_mm256_blendv_pd(inf, d, ne), m1k, lt);
            m2k = _mm256_min_pd(c, m2k);
            vk = _mm256_blendv_pd(vk, p, lt);
            m1k = _mm256_min_pd(d, m1k);
        }
        double a[3][4];
        _mm256_storeu_pd(a[0], vk);
        _mm256_storeu_pd(a[1], m1k);
        _mm256_storeu_pd(a[2], m2k);
        for (int q = 0; q < 4; ++q) {
            v[(size_t)(k + q) * stride] = a[0][q];
            m1[(size_t)(k + q) * stride] = a[1][q];
            m2[(size_t)(k + q) * stride] = a[2][q];
        }
    }
}
#else
void sol_nm_channel_side_avx2(const double pal[8], const double t[16], double *v, double *m1, double *m2,
                             size_t stride)
{
    sol_nm_channel_side_scalar(pal, t, v, m1, m2, stride);
}
#endif
