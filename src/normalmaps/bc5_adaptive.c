/* bc5_adaptive.c - the adaptive 3Dc encoder's cheap steps (T13): the threshold test decided through
 * chord bounds instead of 16 atan2, and the unit normals of a block read straight from image rows.
 *
 * Talk (seed 000, "3Dc encoder improvements, cont'd"): "1. Compress the block with a usual 3Dc
 * compression approach 2. Measure the directional deviation 3. If the error is higher than some
 * threshold, initiate the improved compression stage ... the performance overhead introduced is
 * minimal". Step 2 decides only whether the block is searched; where no caller needs the error
 * itself (an image encode), it is decided from bounds, and the exact angles are computed only when
 * the bounds cannot decide. The decision is always the one the exact angles give (derivation below).
 */
#include "normalmaps_internal.h"

#include <math.h>

/* ---- the threshold test ----
 * The exact test (bc5.c's own_index_objective and encode_unit): each pixel's angle e_p =
 * sol_angle3(u_p, n_p) between the decoded u_p = (a, b, rebuild_z(a, b)) and the unit source n_p,
 * err = the sum in pixel order of e_p^2 (or the max of e_p^2), and the block is searched unless
 * level(err) <= threshold, level(x) = sqrt(x / 16) (180 / pi) (or sqrt(x) (180 / pi)).
 *
 * Bounds. Let c be the chord |u / |u| - n| (u as decoded in floating point, the same vector the
 * exact test measures) and theta the real angle, theta = 2 asin(c / 2). Since x <= asin(x) <=
 * x / sqrt(1 - x^2) on [0, 1), c^2 <= theta^2 <= c^2 / (1 - c^2 / 4); and for C = c^2 <= 2,
 * 1 / (1 - x) = 1 + x + x^2 / (1 - x) <= 1 + x + 2 x^2 at x = C / 4 <= 1/2 gives
 *   theta^2 <= hi(C) = C (1 + C / 4 (1 + C / 2))   (no division; slope <= 3.5 on [0, 2]),
 * and for C > 2 (angles above 90 degrees) hi = 10 > pi^2 >= theta^2.
 * The computed C (below) differs from c^2 by gamma and sol_angle3's result from theta by delta:
 *   - where z is rebuilt (1 - a^2 - b^2 > 0 in floating point), u is taken as is: its length is
 *     1 within 6e-16 (z^2 = fl(1 - a^2 - b^2) within 3 ulps), so with the rounding of the three
 *     differences and squares, |gamma| <= 1e-14; where z is clamped to 0, u / |u| is formed
 *     (|u| >= 1) with the same order of error;
 *   - sol_angle3 takes atan2(|u x n|, u . n) with |u| in [1, sqrt(2)], |n| = 1: its components are
 *     off by a few ulps of 1 and atan2's slope is 1 / (|u| |n|) <= 1, so |delta| <= 1e-14.
 * So e_p^2 (computed) lies in [C - 2 pi delta - gamma, hi(C + gamma) + 2 pi delta + delta^2]: a
 * per-pixel slack TAU = 1e-10 covers that 1000 times over. hi's own rounding (a few ulps) and the
 * rounding of the sums (or maxima) of the bounds and of the exact squares are at most 20 ulps
 * relative; REL = 1e-9 covers them. Then L <= err <= U for
 *   L = max(0, sum (C_p) - 16 TAU) (1 - REL),   U = (sum hi(C_p) + 16 TAU) (1 + REL)
 * (max forms: max_p instead of the sums, one TAU). level is monotone (a division by 16, sqrt and a
 * product, each correctly rounded, never decrease), so level(U) <= threshold proves the exact test
 * keeps the block and level(L) > threshold proves it searches it; otherwise (the band between, a
 * relative width of about C / 4 around the threshold, or an RMS angle below 1e-5 rad at threshold
 * 0) the caller computes the exact angles. The tests check every case at thresholds exactly at a
 * block's level and one ulp either side (where the slack is needed: without it they fail). */
#define TAU 1e-10
#define REL 1e-9

/* AVX2 forms (4 pixels per instruction, picked at run time where the CPU has AVX2 and
 * sol_nm_simd_disable is not set), with the same IEEE operations per pixel as the scalar forms
 * (sub, mul, add, div, sqrt correctly rounded; comparisons and blends select as the ternaries; no
 * FMA): bit-identical results (the tests run both). */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#include <immintrin.h>
#define ADAPTIVE_AVX2 1
#define AVX2_FN __attribute__((target("avx2")))
static int use_avx2(void)
{
    return !sol_nm_simd_disable && __builtin_cpu_supports("avx2");
}
#else
#define ADAPTIVE_AVX2 0
#endif

#if ADAPTIVE_AVX2
/* (x, y, z) / sqrt(x x + y y + z z), 4 pixels at a time: sol_nm_unit_normals' operations. */
AVX2_FN static void unit_avx2(const double x[16], const double y[16], const double z[16], double tx[16], double ty[16],
                              double tz[16])
{
    for (int p = 0; p < 16; p += 4) {
        __m256d a = _mm256_loadu_pd(x + p), b = _mm256_loadu_pd(y + p), c = _mm256_loadu_pd(z + p);
        __m256d len = _mm256_sqrt_pd(
            _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a, a), _mm256_mul_pd(b, b)), _mm256_mul_pd(c, c)));
        _mm256_storeu_pd(tx + p, _mm256_div_pd(a, len));
        _mm256_storeu_pd(ty + p, _mm256_div_pd(b, len));
        _mm256_storeu_pd(tz + p, _mm256_div_pd(c, len));
    }
}
#endif

/* Pixel p's squared chord C and its upper bound hi(C) (see above). */
static inline void chord_terms(double a, double c, double nx, double ny, double nz, double *cc_out, double *up_out)
{
    double zz = 1.0 - a * a - c * c, dx, dy, dz; /* rebuild_z's test: the same expression */
    if (zz > 0.0) {
        dx = a - nx;
        dy = c - ny;
        dz = sqrt(zz) - nz;
    } else { /* z clamped to 0: the direction of (a, c, 0) */
        double r = sqrt(a * a + c * c);
        dx = a / r - nx;
        dy = c / r - ny;
        dz = 0.0 - nz;
    }
    double cc = dx * dx + dy * dy + dz * dz;
    *cc_out = cc;
    *up_out = cc <= 2.0 ? cc * (1.0 + 0.25 * cc * (1.0 + 0.5 * cc)) : 10.0;
}

#if ADAPTIVE_AVX2
AVX2_FN static void chord_terms_avx2(const double a[16], const double c[16], const double t[3][16], double cc[16],
                                     double up[16])
{
    const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd(), two = _mm256_set1_pd(2.0),
                  quarter = _mm256_set1_pd(0.25), half = _mm256_set1_pd(0.5), ten = _mm256_set1_pd(10.0);
    for (int p = 0; p < 16; p += 4) {
        __m256d va = _mm256_loadu_pd(a + p), vc = _mm256_loadu_pd(c + p);
        __m256d aa = _mm256_mul_pd(va, va), cc2 = _mm256_mul_pd(vc, vc);
        __m256d zz = _mm256_sub_pd(_mm256_sub_pd(one, aa), cc2);
        __m256d pos = _mm256_cmp_pd(zz, zero, _CMP_GT_OQ);
        __m256d ux = va, uy = vc, uz = _mm256_sqrt_pd(_mm256_max_pd(zz, zero)); /* 0 where clamped */
        if (_mm256_movemask_pd(pos) != 15) { /* a clamped lane: (a, c, 0) / r there */
            __m256d r = _mm256_sqrt_pd(_mm256_add_pd(aa, cc2)); /* r may be 0 in a lane not clamped: */
            ux = _mm256_blendv_pd(_mm256_div_pd(va, r), va, pos); /* its NaN quotient is not selected */
            uy = _mm256_blendv_pd(_mm256_div_pd(vc, r), vc, pos);
        }
        __m256d dx = _mm256_sub_pd(ux, _mm256_loadu_pd(t[0] + p)), dy = _mm256_sub_pd(uy, _mm256_loadu_pd(t[1] + p));
        __m256d dz = _mm256_sub_pd(uz, _mm256_loadu_pd(t[2] + p));
        __m256d s = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
        __m256d hi = _mm256_mul_pd(s, _mm256_add_pd(one, _mm256_mul_pd(_mm256_mul_pd(quarter, s),
                                                                       _mm256_add_pd(one, _mm256_mul_pd(half, s)))));
        _mm256_storeu_pd(cc + p, s);
        _mm256_storeu_pd(up + p, _mm256_blendv_pd(ten, hi, _mm256_cmp_pd(s, two, _CMP_LE_OQ)));
    }
}
#endif

void sol_nm_chord_bounds(const double palx[8], const double paly[8], const sol_bc5_block *b, const double t[3][16],
                         int use_max, double *lower, double *upper)
{
    double a[16], c[16], cc[16], up[16];
    for (int p = 0; p < 16; ++p) {
        a[p] = palx[b->x.index[p]];
        c[p] = paly[b->y.index[p]];
    }
#if ADAPTIVE_AVX2
    if (use_avx2())
        chord_terms_avx2(a, c, t, cc, up);
    else
#endif
        for (int p = 0; p < 16; ++p)
            chord_terms(a[p], c[p], t[0][p], t[1][p], t[2][p], &cc[p], &up[p]);
    /* sums (or maxima) in four lanes, pixel p into lane p % 4, then lanes (0 + 1) + (2 + 3) */
    double lo4[4], hi4[4];
    for (int k = 0; k < 4; ++k) {
        lo4[k] = cc[k];
        hi4[k] = up[k];
    }
    for (int p = 4; p < 16; ++p) {
        int k = p & 3;
        if (use_max) {
            lo4[k] = cc[p] > lo4[k] ? cc[p] : lo4[k];
            hi4[k] = up[p] > hi4[k] ? up[p] : hi4[k];
        } else {
            lo4[k] += cc[p];
            hi4[k] += up[p];
        }
    }
    double lo, hi;
    if (use_max) {
        lo = fmax(fmax(lo4[0], lo4[1]), fmax(lo4[2], lo4[3]));
        hi = fmax(fmax(hi4[0], hi4[1]), fmax(hi4[2], hi4[3]));
    } else {
        lo = (lo4[0] + lo4[1]) + (lo4[2] + lo4[3]);
        hi = (hi4[0] + hi4[1]) + (hi4[2] + hi4[3]);
    }
    double slack = use_max ? TAU : 16.0 * TAU;
    *lower = lo - slack > 0.0 ? (lo - slack) * (1.0 - REL) : 0.0;
    *upper = (hi + slack) * (1.0 + REL);
}

int sol_nm_threshold_decide(double lower, double upper, int use_max, double threshold_deg)
{
    if (sol_nm_threshold_level(upper, use_max) <= threshold_deg)
        return 0;
    if (sol_nm_threshold_level(lower, use_max) > threshold_deg)
        return 1;
    return -1;
}

int sol_nm_threshold_test(const double palx[8], const double paly[8], const sol_bc5_block *b, const double t[3][16],
                          int use_max, double threshold_deg)
{
    double L, U;
    sol_nm_chord_bounds(palx, paly, b, t, use_max, &L, &U);
    return sol_nm_threshold_decide(L, U, use_max, threshold_deg);
}

/* ---- the gap test: a lower bound of every block's objective ----
 * (the proofs are at sol_bc5_options.gap in sol_normalmaps.h: the separable bound min(Sx + Sy, min_p
 * nz_p^2) and the tilt bound min((1 + alpha) Sa + (1 - beta) Sb, T).) The rounding: Sx and Sy are the
 * computed least sums, at most the computed sum of the exact minimiser, i.e. within 20 ulps relative
 * above the exact minimum or below it (REL). The computed angle of any decode is within 1e-14 rad of
 * the true angle (above), so its square is within 2 pi 1e-14 + 1e-28 of the true square; the unit
 * normals are unit within 2e-16, which moves the chord's xy part and |nz| by at most 3e-16, the
 * squares by 1e-15: each pixel's computed term is >= its true bound less 1e-13, far inside TAU. So
 * every computed objective (sum, or max, of the computed squared angles, rounded by 20 ulps at most)
 * is >= max(0, LB - 16 TAU) (1 - REL) (max metric: one TAU).
 * The tilt bound's own rounding: the cap's radius r is sqrt(T) raised by a relative 1e-9 and then by
 * 1e-12, which covers the computed unit normals' distance to the true ones (3e-16 per component) and
 * the rounding of 2 |n| -+ r and 2 nz +- r (half an ulp of values <= 4, 5e-16): the computed
 * numerators and denominators of sqrt(K) and sqrt(C) lie on the safe side of the true ones; the
 * quotients and squares round by 3 ulps, K and C by 4e-16 relative at most, alpha = K beta / (beta +
 * C) by 1e-15, and alpha is lowered by a relative 1e-12 (ALPHA_LOWER), below every pixel's true limit.
 * T = min(cap, nz_p^2) may exceed the true nz_p^2 by 1e-15 (a pixel whose decode is clamped then has
 * chord^2 >= T - 1e-15), inside TAU; the final sums round by a few ulps, inside REL. */
#define ALPHA_LOWER (1.0 - 1e-12)

/* The gain of one side (channel a gains, channel b loses): (1 + alpha) sa + (1 - beta) sb at the beta
 * in (0, 1] that maximises it for alpha(beta) = k beta / (beta + c) (k = K of channel a, c = C of
 * channel b): f(beta) = k beta / (beta + c) sa - beta sb is concave, f'(beta) = 0 at
 * beta = sqrt(k c sa / sb) - c (1 when sb = 0: f increases). 0 (no gain) when the side has none. */
static double tilt_side(double k, double c, double sa, double sb)
{
    if (!(k > 0.0) || !(c > 0.0) || !(sa > 0.0))
        return 0.0;
    double beta = sb > 0.0 ? sqrt(k * c * sa / sb) - c : 1.0;
    beta = beta < 1.0 ? beta : 1.0;
    if (!(beta > 0.0))
        return 0.0;
    double alpha = k * beta / (beta + c) * ALPHA_LOWER;
    return (1.0 + alpha) * sa + (1.0 - beta) * sb;
}

double sol_nm_gap_bound(double sx, double sy, const double t[3][16], int use_max, double cap)
{
    double s = sx + sy, z2 = INFINITY, nzmin = INFINITY;
    for (int p = 0; p < 16; ++p) {
        double z = t[2][p];
        z2 = z * z < z2 ? z * z : z2;
        nzmin = z < nzmin ? z : nzmin;
    }
    double lb = use_max ? s / 16.0 : s;
    lb = z2 < lb ? z2 : lb;
    /* the tilt bound: every pixel above the equator, a cap T = min(cap, min_p nz_p^2) > 0 */
    double T = cap < z2 ? cap : z2;
    if (nzmin > 0.0 && T > 0.0 && T < INFINITY) {
        double ax_lo = INFINITY, ay_lo = INFINITY, ax_hi = 0.0, ay_hi = 0.0, nzmax = 0.0;
        for (int p = 0; p < 16; ++p) {
            double ax = fabs(t[0][p]), ay = fabs(t[1][p]), z = t[2][p];
            ax_lo = ax < ax_lo ? ax : ax_lo;
            ay_lo = ay < ay_lo ? ay : ay_lo;
            ax_hi = ax > ax_hi ? ax : ax_hi;
            ay_hi = ay > ay_hi ? ay : ay_hi;
            nzmax = z > nzmax ? z : nzmax;
        }
        double r = sqrt(T) * (1.0 + 1e-9) + 1e-12, lo = 2.0 * nzmin - r, hi = 2.0 * nzmax + r;
        if (lo > 0.0) {
            double gx = 2.0 * ax_lo - r > 0.0 ? (2.0 * ax_lo - r) / hi : 0.0;
            double gy = 2.0 * ay_lo - r > 0.0 ? (2.0 * ay_lo - r) / hi : 0.0;
            double hx = (2.0 * ax_hi + r) / lo, hy = (2.0 * ay_hi + r) / lo;
            double b = s, bx = tilt_side(gx * gx, hy * hy, sx, sy), by = tilt_side(gy * gy, hx * hx, sy, sx);
            b = bx > b ? bx : b;
            b = by > b ? by : b;
            b = use_max ? b / 16.0 : b;
            b = b < T ? b : T;
            lb = b > lb ? b : lb;
        }
    }
    double slack = use_max ? TAU : 16.0 * TAU;
    return lb - slack > 0.0 ? (lb - slack) * (1.0 - REL) : 0.0;
}

int sol_nm_gap_test(double lower, double upper, double limit)
{
    if (upper <= limit)
        return 0;
    if (lower > limit)
        return 1;
    return -1;
}

/* ---- unit normals straight from image rows ---- */

void sol_nm_unit_pixels(const sol_image *img, int bx, int by, double n[16][3], double t[3][16])
{
    double x[16], y[16], z[16];
    for (int r = 0; r < 4; ++r) {
        const float *v = sol_image_pixel(img, 4 * bx, 4 * by + r);
        for (int k = 0; k < 4; ++k) {
            x[4 * r + k] = v[3 * k];
            y[4 * r + k] = v[3 * k + 1];
            z[4 * r + k] = v[3 * k + 2];
        }
    }
    double *tx = t[0], *ty = t[1], *tz = t[2];
#if ADAPTIVE_AVX2
    if (use_avx2())
        unit_avx2(x, y, z, tx, ty, tz);
    else
#endif
        for (int p = 0; p < 16; ++p) {
            double len = sqrt(x[p] * x[p] + y[p] * y[p] + z[p] * z[p]);
            tx[p] = x[p] / len;
            ty[p] = y[p] / len;
            tz[p] = z[p] / len;
        }
    for (int p = 0; p < 16; ++p) {
        n[p][0] = tx[p];
        n[p][1] = ty[p];
        n[p][2] = tz[p];
    }
}
