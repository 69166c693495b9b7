/* bc5_away.c - the joint bound of the exact 3Dc search for pixels pointing away (nz < 0, issue 13):
 * the largest cosine between the pixel's normal and any of the 64 decodes of two palettes.
 *
 * The decode of entries a (x palette) and b (y palette) is, with r = a^2 + b^2, the vector
 * (a, b, z) with z = sqrt(1 - r) when r < 1, and (a, b, 0) / sqrt(r) when z is clamped; its cosine
 * to a unit n is (a nx + b ny + z nz) / sqrt(max(1, r)). The per-channel bounds of a pixel pointing
 * away (bc5.c, "pixels pointing away") let x and y reach the rim direction separately, so the channel
 * scores, and the quick bound built from them, cannot reject a candidate that they let through; this
 * cosine couples the channels: one decode must point close to n. The caller turns the largest cosine
 * into the angle bound acos(cos_max) (the pixel's chosen decode has at most that cosine).
 *
 * Rounding (an upper bound of the cosine of what the decoder builds, bc5.c's rebuild_z: z from
 * 1 - a^2 - b^2, zero where that is <= 0; the angle measured by atan2, invariant to the vector's
 * length): r and 1 - r carry absolute errors below 1e-15, so z is replaced by the lower value
 * sqrt(max(0, 1 - r (1 + 2e-15))) (0 wherever the decoder might clamp), which with nz < 0 only raises
 * the cosine; the remaining rounding of d, the roots and the division (a few 1e-16) the caller
 * covers by raising the cosine by 1e-14. The AVX2 form does the same IEEE operations in the same
 * order per decode (no FMA) and max is exact up to the sign of a zero, which both forms drop by
 * adding +0, so they return the same bits (the tests run both and compare).
 *
 * sol_nm_away_cosine_rim is the cheaper first stage: with nz < 0 the z term only lowers the cosine,
 * so (a nx + b ny) / sqrt(max(1, r)) is an upper bound too (exact for clamped decodes); its largest
 * value is found without roots through the order-preserving d |d| / max(1, r) (= sign(d) cos^2),
 * one division per decode, and the root taken once. Rounding as above (a few 1e-16). */
#include "normalmaps_internal.h"

#include <math.h>

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#include <immintrin.h>
#define AWAY_AVX2 1

static __attribute__((target("avx2"))) double away_cosine_avx2(const double a[8], const double b[8], const double n[3])
{
    const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd(), slack = _mm256_set1_pd(1.0 + 2e-15);
    const __m256d nx = _mm256_set1_pd(n[0]), ny = _mm256_set1_pd(n[1]), nz = _mm256_set1_pd(n[2]);
    __m256d a0 = _mm256_loadu_pd(a), a1 = _mm256_loadu_pd(a + 4);
    __m256d ax0 = _mm256_mul_pd(a0, nx), ax1 = _mm256_mul_pd(a1, nx);
    __m256d aa0 = _mm256_mul_pd(a0, a0), aa1 = _mm256_mul_pd(a1, a1);
    __m256d best = _mm256_set1_pd(-INFINITY);
    for (int j = 0; j < 8; ++j) {
        __m256d bj = _mm256_set1_pd(b[j]);
        __m256d by = _mm256_mul_pd(bj, ny), bb = _mm256_mul_pd(bj, bj);
        for (int h = 0; h < 2; ++h) {
            __m256d r = _mm256_add_pd(h ? aa1 : aa0, bb), d = _mm256_add_pd(h ? ax1 : ax0, by);
            __m256d zl = _mm256_sqrt_pd(_mm256_max_pd(_mm256_sub_pd(one, _mm256_mul_pd(r, slack)), zero));
            __m256d c = _mm256_div_pd(_mm256_add_pd(d, _mm256_mul_pd(zl, nz)), _mm256_sqrt_pd(_mm256_max_pd(r, one)));
            best = _mm256_max_pd(best, c);
        }
    }
    double v[4];
    _mm256_storeu_pd(v, best);
    double c = v[0];
    for (int k = 1; k < 4; ++k)
        c = v[k] > c ? v[k] : c;
    return c + 0.0; /* -0 and +0 compare equal; + 0.0 makes both +0 */
}

static __attribute__((target("avx2"))) double away_cosine_rim_avx2(const double a[8], const double b[8],
                                                                     const double n[3])
{
    const __m256d one = _mm256_set1_pd(1.0), sign = _mm256_set1_pd(-0.0);
    const __m256d nx = _mm256_set1_pd(n[0]), ny = _mm256_set1_pd(n[1]);
    __m256d a0 = _mm256_loadu_pd(a), a1 = _mm256_loadu_pd(a + 4);
    __m256d ax0 = _mm256_mul_pd(a0, nx), ax1 = _mm256_mul_pd(a1, nx);
    __m256d aa0 = _mm256_mul_pd(a0, a0), aa1 = _mm256_mul_pd(a1, a1);
    __m256d best = _mm256_set1_pd(-INFINITY);
    for (int j = 0; j < 8; ++j) {
        __m256d bj = _mm256_set1_pd(b[j]);
        __m256d by = _mm256_mul_pd(bj, ny), bb = _mm256_mul_pd(bj, bj);
        for (int h = 0; h < 2; ++h) {
            __m256d r = _mm256_max_pd(_mm256_add_pd(h ? aa1 : aa0, bb), one), d = _mm256_add_pd(h ? ax1 : ax0, by);
            best = _mm256_max_pd(best, _mm256_div_pd(_mm256_mul_pd(d, _mm256_andnot_pd(sign, d)), r));
        }
    }
    double v[4];
    _mm256_storeu_pd(v, best);
    double s = v[0];
    for (int k = 1; k < 4; ++k)
        s = v[k] > s ? v[k] : s;
    return s;
}
#else
#define AWAY_AVX2 0
#endif

double sol_nm_away_cosine_rim(const double a[8], const double b[8], const double n[3])
{
    double s;
#if AWAY_AVX2
    if (!sol_nm_simd_disable && __builtin_cpu_supports("avx2")) {
        s = away_cosine_rim_avx2(a, b, n);
        return s >= 0.0 ? sqrt(s) + 0.0 : -sqrt(-s);
    }
#endif
    s = -INFINITY;
    for (int j = 0; j < 8; ++j) {
        double by = b[j] * n[1], bb = b[j] * b[j];
        for (int i = 0; i < 8; ++i) {
            double r = a[i] * a[i] + bb, d = a[i] * n[0] + by;
            r = r > 1.0 ? r : 1.0;
            double q = d * fabs(d) / r;
            s = q > s ? q : s;
        }
    }
    return s >= 0.0 ? sqrt(s) + 0.0 : -sqrt(-s);
}

double sol_nm_away_cosine(const double a[8], const double b[8], const double n[3])
{
#if AWAY_AVX2
    if (!sol_nm_simd_disable && __builtin_cpu_supports("avx2"))
        return away_cosine_avx2(a, b, n);
#endif
    double best = -INFINITY;
    for (int j = 0; j < 8; ++j) {
        double by = b[j] * n[1], bb = b[j] * b[j];
        for (int i = 0; i < 8; ++i) {
            double r = a[i] * a[i] + bb, d = a[i] * n[0] + by;
            double zz = 1.0 - r * (1.0 + 2e-15);
            double c = (d + sqrt(zz > 0.0 ? zz : 0.0) * n[2]) / sqrt(r > 1.0 ? r : 1.0);
            best = c > best ? c : best;
        }
    }
    return best + 0.0;
}
