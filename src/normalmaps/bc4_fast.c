/* bc4_fast.c - the usual fast BC4 ("alpha block") encoder, the per-channel encoder the talk calls
 * usual (T10, T13): anchors at the block's extremes, as the DXT5 alpha encoders of libsquish
 * (S. Brown) and NVIDIA Texture Tools' fast path choose them, palettes interpolated at 8 bits.
 *
 * Two candidates, the better kept by their squared error against the 8-bit palettes:
 *   8-value mode: e0 = the largest value's code, e1 = the smallest's (e0 > e1);
 *   6-value mode: e0 = the smallest, e1 = the largest code of the values that are not served
 *                 exactly by the mode's fixed entries 0 and 255.
 * Each value takes its nearest palette entry. No search over anchors: one pass over the block.
 *
 * Speed: the two palettes are computed from the anchors (the 8-bit decoder's rounding, as
 * sol_nm_palettes builds its table) through a 256-entry table of decoded codes instead of read from
 * the 4 MB table (two rows of it per channel were two cache misses), and the nearest entry of every
 * value is taken by a branch-free scan over the 8 entries, 2 (SSE2) or 4 (AVX2, chosen at run time)
 * values at a time. Same entries, same comparisons in the same order: the same blocks as the scalar
 * scan (sol_nm_nearest_index on the table's rows; pinned by a test for every path). */
#include "normalmaps_internal.h"

#include <math.h>

/* Decoded value of 8-bit code q, 2 (q / 255) - 1: what sol_nm_palettes(SOL_BC4_INTERP_8BIT) stores
 * for every entry rounded to code q (constant-folded with the run time's IEEE rounding). */
#define DEC1(q) (2.0 * ((q) / 255.0) - 1.0)
#define DEC4(q) DEC1(q), DEC1((q) + 1), DEC1((q) + 2), DEC1((q) + 3)
#define DEC16(q) DEC4(q), DEC4((q) + 4), DEC4((q) + 8), DEC4((q) + 12)
#define DEC64(q) DEC16(q), DEC16((q) + 16), DEC16((q) + 32), DEC16((q) + 48)
static const double decoded[256] = {DEC64(0), DEC64(64), DEC64(128), DEC64(192)};

/* The 8-bit palette of anchors e0, e1 in decoded units (bc4.c's palette_values: entries rounded
 * half up to a code, (2 num + den) / (2 den)). */
static void palette8(int e0, int e1, double pal[8])
{
    pal[0] = decoded[e0];
    pal[1] = decoded[e1];
    if (e0 > e1) {
        for (int i = 2; i < 8; ++i)
            pal[i] = decoded[(2 * ((8 - i) * e0 + (i - 1) * e1) + 7) / 14];
    } else {
        for (int i = 2; i < 6; ++i)
            pal[i] = decoded[(2 * ((6 - i) * e0 + (i - 1) * e1) + 5) / 10];
        pal[6] = -1.0;
        pal[7] = 1.0;
    }
}

/* Nearest entry of each value (the first on ties, sol_nm_nearest_index's rule) and the sum of the
 * squared distances in pixel order. The scan runs entry by entry over all 16 values, two at a time
 * with SSE2 (x86-64's baseline) or four at a time with AVX2 where the processor has it (chosen at
 * run time); d < best keeps the earlier entry on ties, as the scalar scan's strict < does, and
 * min(d, best) is exactly that choice. Subtraction, absolute value, comparison and minimum are
 * exact or correctly rounded in every width: the three paths give the same bits. */
static double squared_error_scalar(const double pal[8], const double t[16], uint8_t index[16])
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        int i = sol_nm_nearest_index(pal, t[p]);
        index[p] = (uint8_t)i;
        s += (pal[i] - t[p]) * (pal[i] - t[p]);
    }
    return s;
}

#if defined(__SSE2__)
#include <emmintrin.h>
static double sum_in_order(const double best[16], const double which[16], uint8_t index[16])
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        index[p] = (uint8_t)which[p];
        s += best[p] * best[p]; /* |x|^2 == x^2 exactly */
    }
    return s;
}

static double squared_error_sse2(const double pal[8], const double t[16], uint8_t index[16])
{
    double bs[16], ws[16];
    const __m128d sign = _mm_set1_pd(-0.0), e0 = _mm_set1_pd(pal[0]);
    for (int h = 0; h < 16; h += 8) { /* 8 values at a time: the 12 vectors stay in registers */
        const __m128d t0 = _mm_loadu_pd(t + h), t1 = _mm_loadu_pd(t + h + 2), t2 = _mm_loadu_pd(t + h + 4),
                      t3 = _mm_loadu_pd(t + h + 6);
        __m128d b0 = _mm_andnot_pd(sign, _mm_sub_pd(e0, t0)), b1 = _mm_andnot_pd(sign, _mm_sub_pd(e0, t1)),
                b2 = _mm_andnot_pd(sign, _mm_sub_pd(e0, t2)), b3 = _mm_andnot_pd(sign, _mm_sub_pd(e0, t3));
        __m128d w0 = _mm_setzero_pd(), w1 = w0, w2 = w0, w3 = w0;
        for (int i = 1; i < 8; ++i) {
            const __m128d e = _mm_set1_pd(pal[i]), ii = _mm_set1_pd((double)i);
#define SOL_FAST_STEP(b, w, tk)                                                                                        \
    do {                                                                                                               \
        __m128d d = _mm_andnot_pd(sign, _mm_sub_pd(e, tk)), less = _mm_cmplt_pd(d, b);                                 \
        w = _mm_or_pd(_mm_and_pd(less, ii), _mm_andnot_pd(less, w));                                                   \
        b = _mm_min_pd(d, b); /* d < b ? d : b */                                                                      \
    } while (0)
            SOL_FAST_STEP(b0, w0, t0);
            SOL_FAST_STEP(b1, w1, t1);
            SOL_FAST_STEP(b2, w2, t2);
            SOL_FAST_STEP(b3, w3, t3);
#undef SOL_FAST_STEP
        }
        _mm_storeu_pd(bs + h, b0);
        _mm_storeu_pd(bs + h + 2, b1);
        _mm_storeu_pd(bs + h + 4, b2);
        _mm_storeu_pd(bs + h + 6, b3);
        _mm_storeu_pd(ws + h, w0);
        _mm_storeu_pd(ws + h + 2, w1);
        _mm_storeu_pd(ws + h + 4, w2);
        _mm_storeu_pd(ws + h + 6, w3);
    }
    return sum_in_order(bs, ws, index);
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#define SOL_FAST_AVX2 1
__attribute__((target("avx2"))) static double squared_error_avx2(const double pal[8], const double t[16],
                                                                  uint8_t index[16])
{
    /* named variables rather than arrays, so that the 12 vectors stay in registers */
    const __m256d sign = _mm256_set1_pd(-0.0), t0 = _mm256_loadu_pd(t), t1 = _mm256_loadu_pd(t + 4),
                  t2 = _mm256_loadu_pd(t + 8), t3 = _mm256_loadu_pd(t + 12), e0 = _mm256_set1_pd(pal[0]);
    __m256d b0 = _mm256_andnot_pd(sign, _mm256_sub_pd(e0, t0)), b1 = _mm256_andnot_pd(sign, _mm256_sub_pd(e0, t1)),
            b2 = _mm256_andnot_pd(sign, _mm256_sub_pd(e0, t2)), b3 = _mm256_andnot_pd(sign, _mm256_sub_pd(e0, t3));
    __m256d w0 = _mm256_setzero_pd(), w1 = w0, w2 = w0, w3 = w0;
    for (int i = 1; i < 8; ++i) {
        const __m256d e = _mm256_set1_pd(pal[i]), ii = _mm256_set1_pd((double)i);
#define SOL_FAST_STEP(b, w, tk)                                                                                        \
    do {                                                                                                               \
        __m256d d = _mm256_andnot_pd(sign, _mm256_sub_pd(e, tk));                                                      \
        w = _mm256_blendv_pd(w, ii, _mm256_cmp_pd(d, b, _CMP_LT_OQ));                                                  \
        b = _mm256_min_pd(d, b); /* d < b ? d : b */                                                                   \
    } while (0)
        SOL_FAST_STEP(b0, w0, t0);
        SOL_FAST_STEP(b1, w1, t1);
        SOL_FAST_STEP(b2, w2, t2);
        SOL_FAST_STEP(b3, w3, t3);
#undef SOL_FAST_STEP
    }
    double bs[16], ws[16];
    _mm256_storeu_pd(bs, b0);
    _mm256_storeu_pd(bs + 4, b1);
    _mm256_storeu_pd(bs + 8, b2);
    _mm256_storeu_pd(bs + 12, b3);
    _mm256_storeu_pd(ws, w0);
    _mm256_storeu_pd(ws + 4, w1);
    _mm256_storeu_pd(ws + 8, w2);
    _mm256_storeu_pd(ws + 12, w3);
    return sum_in_order(bs, ws, index);
}
#endif

#endif /* __SSE2__ */

/* The scan of `path` (sol_nm_bc4_fast_path), or the widest one the processor runs if it has not. */
static double squared_error(const double pal[8], const double t[16], uint8_t index[16], int path)
{
#ifdef SOL_FAST_AVX2
    if (path != 1 && path != 2 && __builtin_cpu_supports("avx2"))
        return squared_error_avx2(pal, t, index);
#endif
#if defined(__SSE2__)
    if (path != 1)
        return squared_error_sse2(pal, t, index);
#endif
    (void)path;
    return squared_error_scalar(pal, t, index);
}

/* Code of decoded value t: lrint((t + 1) 127.5) clamped to 0..255. The magic constant 1.5 2^52 makes
 * the addition round v to an integer exactly as lrint does (the current rounding mode, v in
 * (0, 255)) without a library call. */
static inline int code_of(double t)
{
    double v = (t + 1.0) * 127.5;
    if (!(v > 0.0))
        return 0;
    if (v >= 255.0)
        return 255;
    const double magic = 6755399441055744.0;
    return (int)((v + magic) - magic);
}

void sol_nm_nearest_indices(const double pal[8], const double t[16], uint8_t index[16])
{
    (void)squared_error(pal, t, index, 0);
}

void sol_nm_bc4_fast(const double t[16], sol_bc4_block *out)
{
    sol_nm_bc4_fast_path(t, 0, out);
}

void sol_nm_bc4_fast_anchors(const double t[16], int *lo, int *hi, int *lo6, int *hi6)
{
    /* codes of the targets (decoded units 2 v - 1 -> 0..255) */
    int l = 255, h = 0, l6 = 255, h6 = 0;
    for (int p = 0; p < 16; ++p) {
        int c = code_of(t[p]);
        l = c < l ? c : l;
        h = c > h ? c : h;
        if (c != 0 && c != 255) {
            l6 = c < l6 ? c : l6;
            h6 = c > h6 ? c : h6;
        }
    }
    if (l6 > h6) /* every value is 0 or 255: the fixed entries serve them */
        l6 = h6 = l;
    *lo = l;
    *hi = h;
    *lo6 = l6;
    *hi6 = h6;
}

void sol_nm_bc4_fast_path(const double t[16], int path, sol_bc4_block *out)
{
    int lo, hi, lo6, hi6;
    sol_nm_bc4_fast_anchors(t, &lo, &hi, &lo6, &hi6);
    double pal[8];
    sol_bc4_block eight = {(uint8_t)hi, (uint8_t)lo, {0}}, six = {(uint8_t)lo6, (uint8_t)hi6, {0}};
    palette8(six.e0, six.e1, pal);
    double e6 = squared_error(pal, t, six.index, path);
    if (hi > lo) {
        palette8(eight.e0, eight.e1, pal);
        double e8 = squared_error(pal, t, eight.index, path);
        if (e8 <= e6) {
            *out = eight;
            return;
        }
    }
    *out = six;
}

sol_status sol_bc4_encode_block_fast(const double values[16], sol_bc4_block *out)
{
    if (!values || !out)
        return SOL_ERR_NULL_ARG;
    double t[16];
    sol_status st = sol_nm_bc4_targets(values, t);
    if (st != SOL_OK)
        return st;
    sol_nm_bc4_fast(t, out);
    return SOL_OK;
}
