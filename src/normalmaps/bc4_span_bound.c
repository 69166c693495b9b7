/* bc4_span_bound.c - a lower bound of the BC4 least-squares score of every pair of one span, for the
 * exact common search on wide blocks (bc4_common.c's span_search).
 *
 * For a mode and a span d = H - L (codes), the lattice entries of the palette are
 *     e_j = A(L) + j s,  s = (A(H) - A(L)) / den = 2 d / (255 den),  j = 0..den,
 * each rounded by the decoder by at most delta (the rounding is the same for every L - the decoder
 * interpolates integers and 257 L or L is an integer - but the bound does not need that). So every
 * pair of span d, whatever its L, has its lattice entries on the infinite lattice phi + s Z for some
 * phase phi, and the term of target t is at least (c(t - phi) - delta)_+^2 with c the distance to
 * the nearest multiple of s (circular distance modulo s). Hence, for every pair of span d,
 *     S >= sum_p (c_p - delta)_+^2 >= B - 2 delta sum_p c_p >= B - 8 delta sqrt(B)   (Cauchy-Schwarz)
 * with B = min over phi of sum_p c(t_p - phi)^2: the least circular sum of squares of the 16 phases
 * u_p = t_p mod s. Sorted, the optimal phi splits the circle at phi + s/2, so B is the least, over
 * the 16 cut points, of the sum of squares about the mean of the unwrapped sequence (u_c, ..,
 * u_15, u_0 + s, .., u_{c-1} + s), each from running sums in O(1).
 * The bound ignores that a palette holds only den + 1 lattice entries (the ends) and the 6-value
 * mode's fixed entries -1 and +1: the caller handles those (the ends by a separate bound, the fixed
 * entries by using the bound only when they are out of every useful target's reach).
 * Why it pays: on wide blocks (rough terrain, ridges) the targets fit a lattice of few spans only -
 * measured on the benchmark maps, 4-9 of the 50-60 spans the region allows survive, against the
 * optimum's score. */
#include "normalmaps_internal.h"

#include <math.h>
#include <string.h>

/* Compiled for AVX2 as well and picked at run time (as bc4_common.c's hot functions): the four
 * spans are independent lanes, the same operations in either build. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SPAN_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SPAN_CLONES
#endif

/* Batcher's odd-even merge sort of 16 values: 63 compare-exchanges, branch-free, the same for every
 * lane (checked on all 2^16 zero-one inputs, which is enough for a comparator network). */
static const unsigned char network[63][2] = {
    {0, 1},   {2, 3},   {0, 2},   {1, 3},   {1, 2},   {4, 5},   {6, 7},   {4, 6},   {5, 7},   {5, 6},   {0, 4},
    {2, 6},   {2, 4},   {1, 5},   {3, 7},   {3, 5},   {1, 2},   {3, 4},   {5, 6},   {8, 9},   {10, 11}, {8, 10},
    {9, 11},  {9, 10},  {12, 13}, {14, 15}, {12, 14}, {13, 15}, {13, 14}, {8, 12},  {10, 14}, {10, 12}, {9, 13},
    {11, 15}, {11, 13}, {9, 10},  {11, 12}, {13, 14}, {0, 8},   {4, 12},  {4, 8},   {2, 10},  {6, 14},  {6, 10},
    {2, 4},   {6, 8},   {10, 12}, {1, 9},   {5, 13},  {5, 9},   {3, 11},  {7, 15},  {7, 11},  {3, 5},   {7, 9},
    {11, 13}, {1, 2},   {3, 4},   {5, 6},   {7, 8},   {9, 10},  {11, 12}, {13, 14}};

/* mask ? a : b, lane by lane */
#define SELECT(vf, vi, mask, a, b) ((vf)(((vi)(a) & (mask)) | ((vi)(b) & ~(mask))))

void sol_nm_sort16(const double in[16], double out[16])
{
    /* one-lane vectors with a bitwise select: the compiler turned the scalar form's exchanges into
     * branches, mispredicted on half of them */
    typedef double v1d __attribute__((vector_size(sizeof(double))));
    typedef long long v1l __attribute__((vector_size(sizeof(long long))));
    v1d u[16];
    memcpy(u, in, sizeof u);
    /* fully unrolled: the indices are constants, u stays in registers */
#pragma GCC unroll 63
    for (int c = 0; c < 63; ++c) {
        const v1d x = u[network[c][0]], y = u[network[c][1]];
        const v1l lt = y < x;
        u[network[c][0]] = SELECT(v1d, v1l, lt, y, x);
        u[network[c][1]] = SELECT(v1d, v1l, lt, x, y);
    }
    memcpy(out, u, sizeof u);
}

typedef double v4d __attribute__((vector_size(4 * sizeof(double))));
typedef long long v4l __attribute__((vector_size(4 * sizeof(long long))));

/* mask ? a : b, lane by lane (a macro: a function passing 32-byte vectors warns about its ABI) */
#define select4(mask, a, b) ((v4d)(((v4l)(a) & (mask)) | ((v4l)(b) & ~(mask))))

/* The phases u_p = (t_p - t_0) mod step of the 16 sorted targets, ascending, for four steps at once
 * (*step: the steps, *inverse: their inverses; pointers, as passing 32-byte vectors warns about its
 * ABI); an always-inlined helper of the two functions below. */
static inline __attribute__((always_inline)) void sorted_phases(const double sorted[16], const v4d *step,
                                                                const v4d *inverse, v4d u[16])
{
    const v4d zero = {0.0, 0.0, 0.0, 0.0}, magic = zero + 0x1.8p52, st = *step, inv = *inverse;
    for (int p = 0; p < 16; ++p) {
        /* any representative works (only t mod s matters): v - s round(v / s) (round to nearest by
         * the 1.5 2^52 addition; v / s < 2^51), then one correction step each way keeps it in [0, s) */
        const v4d v = zero + (sorted[p] - sorted[0]);
        v4d m = (v * inv + magic) - magic, r = v - st * m;
        r = select4(r < zero, r + st, r);
        r = select4(r >= st, r - st, r);
        u[p] = r;
    }
    /* fully unrolled, so that the indices are constants and u stays in registers */
#pragma GCC unroll 63
    for (int c = 0; c < 63; ++c) {
        v4d x = u[network[c][0]], y = u[network[c][1]];
        v4l lt = x < y;
        u[network[c][0]] = select4(lt, x, y);
        u[network[c][1]] = select4(lt, y, x);
    }
}

/* The bound in single precision, eight (AVX-512: sixteen) steps at once (what the search spends most
 * of its time on: every span of the region is bounded, most of them only to be dismissed). Steps of the same
 * operations as above, in floats: the phases u_p = v_p - s round(v_p / s) of v_p = t_p - t_0 (any
 * representatives within one period work, so no correction into [0, s)), sorted by the same network,
 * the 16 cut sequences' sums of squares about their means, the least of them, B_f. The allowance:
 * - each computed phase is an exact phase (modulo the exact step s) of a target moved by at most
 *   eta = 16 eps (W + s) (eps = 2^-24, W = t_15 - t_0: the rounding of v_p, of s, of the product
 *   m s with |m| <= W / s + 1 and of the difference, and the phases past s/2 by the rounding of
 *   m), and a target moved by eta moves sqrt of the circular sum by at most 4 eta over the 16
 *   targets (Cauchy-Schwarz: the sum's square root is a 2-norm of 1-Lipschitz distances); the
 *   shifted phases (u + s in floats) are off by at most eps s each, within the same allowance;
 * - the running sums (values below 2 s, magnitudes below 24 s and 36 s^2, a few dozen float
 *   operations) are off by less than 2^-10 s^2 in the sum of squares about the mean.
 * So sqrt(B) >= sqrt(B_f - 2^-10 s^2) - 4 eta =: r, and the pair's score is at least r^2 - 8 delta r
 * (as above, with r in place of sqrt(B): x^2 - 8 delta x is increasing for x >= 4 delta, and below
 * that it is negative, answered 0). With a finite limit (the incumbent's score), a lane whose bound
 * is above it is answered INFINITY without its square root: the bound exceeds limit when r > rho =
 * 4 delta + sqrt(16 delta^2 + limit) (where r^2 - 8 delta r = limit); the lanes are tested in floats
 * with margins far above the tests' own rounding (below). */
/* The body, for LANES steps at once (8: the AVX2 and baseline builds; 16: AVX-512, where the 32
 * vector registers hold the 16 phases): the same operations lane by lane, so the lanes' values do
 * not depend on the width. */
#define SPAN_BOUNDS_FN(NAME, LANES, ATTRS)                                                                             \
    ATTRS void NAME(const double sorted[16], const double step[LANES], double delta, double limit, double out[LANES])            \
    {                                                                                                                  \
        typedef float vf __attribute__((vector_size(LANES * sizeof(float))));                                          \
        typedef int vi __attribute__((vector_size(LANES * sizeof(int))));                                              \
        const vf zero = {0.0f}, one = zero + 1.0f, magic = zero + 0x1.8p23f;                                           \
        vf st = zero;                                                                                                  \
        for (int k = 0; k < LANES; ++k)                                                                                \
            st[k] = (float)step[k];                                                                                    \
        const vi has = st > zero;                                                                                      \
        st = SELECT(vf, vi, has, st, one); /* a lane without a step: any value, answered 0 below */                   \
        const vf inv = one / st;                                                                                       \
        vf u[16];                                                                                                      \
        _Pragma("GCC unroll 16") for (int p = 0; p < 16; ++p)                                                          \
        {                                                                                                              \
            /* |v / s| < 2^22, so the 1.5 2^23 addition rounds to nearest */                                          \
            const vf v = zero + (float)(sorted[p] - sorted[0]);                                                        \
            const vf m = (v * inv + magic) - magic;                                                                    \
            u[p] = v - st * m;                                                                                         \
        }                                                                                                              \
        _Pragma("GCC unroll 63") for (int c = 0; c < 63; ++c)                                                          \
        {                                                                                                              \
            vf x = u[network[c][0]], y = u[network[c][1]];                                                             \
            vi lt = x < y;                                                                                             \
            u[network[c][0]] = SELECT(vf, vi, lt, x, y);                                                               \
            u[network[c][1]] = SELECT(vf, vi, lt, y, x);                                                               \
        }                                                                                                              \
        vf sum = zero, sum2 = zero;                                                                                    \
        _Pragma("GCC unroll 16") for (int p = 0; p < 16; ++p)                                                          \
        {                                                                                                              \
            sum += u[p];                                                                                               \
            sum2 += u[p] * u[p];                                                                                       \
        }                                                                                                              \
        const vf st2 = st * st, two_st = st + st;                                                                      \
        vf b = sum2 - sum * sum * 0.0625f;                                                                             \
        _Pragma("GCC unroll 15") for (int c = 0; c < 15; ++c)                                                          \
        { /* cut after u_c: u_c moves up by one period */                                                              \
            sum += st;                                                                                                 \
            sum2 += two_st * u[c] + st2;                                                                               \
            vf var = sum2 - sum * sum * 0.0625f;                                                                       \
            b = SELECT(vf, vi, var < b, var, b);                                                                       \
        }                                                                                                              \
        /* the lanes above the limit, without a square root: the bound exceeds limit when r > rho =                   \
         * 4 delta + sqrt(16 delta^2 + limit) (where r^2 - 8 delta r = limit), i.e. when                               \
         * B_f - 2^-10 s^2 > (rho + 4 eta)^2; tested as B_f > (rho + 4 eta)^2 (1 + 2^-12) + 2^-9 s^2                   \
         * in floats (the margins far above their rounding) */                                                        \
        const float w = (float)(sorted[15] - sorted[0]);                                                               \
        const double rho =                                                                                             \
            limit < INFINITY ? 4.0 * delta + sqrt(16.0 * delta * delta + (limit > 0.0 ? limit : 0.0)) : 0.0;           \
        const vf eta4 = (w + st) * 0x1p-18f, reach = (float)rho + eta4;                                                \
        const vi above = b > reach * reach * (1.0f + 0x1p-12f) + st2 * 0x1p-9f;                                        \
        const double wd = sorted[15] - sorted[0];                                                                      \
        for (int k = 0; k < LANES; ++k) {                                                                              \
            if (!has[k]) {                                                                                             \
                out[k] = 0.0;                                                                                          \
                continue;                                                                                              \
            }                                                                                                          \
            if (limit < INFINITY && above[k]) {                                                                        \
                out[k] = INFINITY;                                                                                     \
                continue;                                                                                              \
            }                                                                                                          \
            const double s = step[k], eta = 0x1p-20 * (wd + s), bf = (double)b[k] - 0x1p-10 * s * s;                  \
            const double r = bf > 0.0 ? sqrt(bf) - 4.0 * eta : 0.0, lb = r > 0.0 ? r * (r - 8.0 * delta) : 0.0;       \
            out[k] = lb > 0.0 ? lb * (1.0 - 1e-9) : 0.0;                                                               \
        }                                                                                                              \
    }

SPAN_BOUNDS_FN(sol_nm_span_bounds, 8, SPAN_CLONES)

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
SPAN_BOUNDS_FN(span_bounds16, 16, __attribute__((target("avx512f"))) static)
SPAN_BOUNDS_FN(span_bounds8_avx512, 8, __attribute__((target("avx512f"))) static)
#define HAVE_BOUNDS16 1
#else
#define HAVE_BOUNDS16 0
#endif

void sol_nm_span_bounds_all(const double sorted[16], const double *step, int n, double delta, double limit,
                            double *out)
{
#if HAVE_BOUNDS16
    if (__builtin_cpu_supports("avx512f")) {
        /* a last group of at most 8 steps in one AVX-512 register instead of two (the search bounds
         * ~27 spans a mode on the terrain map: issue 13, common-speed) */
        int i = 0;
        for (; n - i > 8; i += 16)
            span_bounds16(sorted, step + i, delta, limit, out + i);
        if (i < n)
            span_bounds8_avx512(sorted, step + i, delta, limit, out + i);
        return;
    }
#endif
    for (int i = 0; i < n; i += 8)
        sol_nm_span_bounds(sorted, step + i, delta, limit, out + i);
}

/* ---- the same bound at a given phase, for the low anchors of one span ----
 * For a phase phi (a pair's low anchor A(L): its lattice entries lie within delta of phi + s Z), the
 * bound above before the minimum over phi is F(phi) = sum_p c(t_p - phi)^2. With psi = phi - t_0
 * and the sorted phases u_p, the nearest lattice point of each u_p is psi + j s with u_p + k_p s
 * in [psi - s/2, psi + s/2): the u_p below a threshold get one period more than the others, which
 * is one of the 16 cut sequences y^c above shifted by a whole number m of periods. Every other
 * choice of (c, m) puts each target at least as far from psi, so, with V_c the sum of squares of
 * y^c about its mean M_c and cd the circular distance modulo s,
 *     F(phi) = min_c min_m sum_p (y^c_p + m s - psi)^2 = min_c [V_c + 16 cd(M_c - psi)^2]
 * exactly, and the pair scores at least F - 8 delta sqrt(F) as above (for F >= 16 delta^2 this is
 * increasing in F, and below it is negative, so any lower value of F gives a lower bound too).
 * A cut with V_c above what can reach the incumbent cannot make F smaller than that; the search
 * drops such cuts (sol_nm_span_cuts_keep) and keeps the least dropped V_c as a floor, so that the
 * bound holds whatever was dropped. */
SPAN_CLONES void sol_nm_span_cuts4(const double sorted[16], const double step[SOL_NM_SPAN_LANES],
                                   sol_nm_span_cuts out[SOL_NM_SPAN_LANES])
{
    const v4d zero = {0.0, 0.0, 0.0, 0.0}, one = zero + 1.0;
    v4d st = {step[0], step[1], step[2], step[3]};
    const v4l has = st > zero;
    st = select4(has, st, one);
    const v4d inv = one / st;
    v4d u[16], sum = zero, sum2 = zero;
    sorted_phases(sorted, &st, &inv, u);
    for (int p = 0; p < 16; ++p) {
        sum += u[p];
        sum2 += u[p] * u[p];
    }
    for (int c = 0; c < 16; ++c) {
        if (c > 0) { /* cut after u_{c-1}: it moves up by one period */
            sum += st;
            sum2 += st * (2.0 * u[c - 1] + st);
        }
        const v4d var = sum2 - sum * sum / 16.0, mean = sum / 16.0;
        for (int k = 0; k < 4; ++k) {
            out[k].v[c] = var[k];
            out[k].mean[c] = mean[k];
        }
    }
    for (int k = 0; k < 4; ++k) {
        out[k].step = st[k];
        out[k].inv = inv[k];
        out[k].slack = 1e-13 * 64.0 * st[k] * st[k];
        out[k].base = sorted[0];
        out[k].n = has[k] ? 16 : 0;
        out[k].floor = has[k] ? INFINITY : 0.0; /* no step: no bound */
    }
}

void sol_nm_span_cuts_keep(sol_nm_span_cuts *cu, double limit)
{
    /* which cuts stay (a bit each) and the least dropped v, in one pass without stores; then the
     * few kept ones moved down, bit by bit */
    unsigned keep = 0;
    double floor = cu->floor;
    for (int c = 0; c < cu->n; ++c) {
        const double v = cu->v[c], dropped = v <= limit ? INFINITY : v;
        keep |= (unsigned)(v <= limit) << c;
        floor = dropped < floor ? dropped : floor;
    }
    int n = 0;
    for (; keep; keep &= keep - 1) {
        const int c = __builtin_ctz(keep);
        cu->v[n] = cu->v[c];
        cu->mean[n++] = cu->mean[c];
    }
    cu->floor = floor;
    cu->n = n;
}

double sol_nm_span_phase_bound(const sol_nm_span_cuts *cu, double delta, double phase)
{
    double f = sol_nm_span_phase_f(cu, phase);
    double lb = f > 0.0 ? f - 8.0 * delta * sqrt(f) : 0.0;
    return lb > 0.0 ? lb * (1.0 - 1e-9) : 0.0;
}

/* sol_nm_span_phase_f at the phases A(l) = 2 l / 255 - 1 of the low anchors l = l1 .. l1 + count - 1
 * (count <= 256), LANES at a time: the same operations in the same order per lane, so the values are
 * those of sol_nm_span_phase_f (the tests compare them). */
#define PHASE_FS_FN(NAME, LANES, ATTRS)                                                                                \
    ATTRS void NAME(const sol_nm_span_cuts *cu, int l1, int count, double out[256])                                     \
    {                                                                                                                  \
        typedef double vd __attribute__((vector_size(LANES * sizeof(double))));                                        \
        typedef long long vl __attribute__((vector_size(LANES * sizeof(long long))));                                  \
        const vd zero = {0.0}, magic = zero + 0x1.8p52, s = zero + cu->step, inv = zero + cu->inv;                     \
        const vl abs_mask = (vl){0} + 0x7fffffffffffffffLL;                                                            \
        for (int i = 0; i < count; i += LANES) {                                                                       \
            vd psi;                                                                                                    \
            for (int k = 0; k < LANES; ++k)                                                                            \
                psi[k] = (2.0 * (l1 + i + k) / 255.0 - 1.0) - cu->base;                                                \
            vd f = zero + cu->floor;                                                                                   \
            for (int c = 0; c < cu->n; ++c) {                                                                          \
                const vd x = cu->mean[c] - psi, m = (x * inv + magic) - magic;                                         \
                vd cd = (vd)((vl)(x - s * m) & abs_mask) - 1e-14;                                                      \
                cd = SELECT(vd, vl, cd > zero, cd, zero);                                                              \
                const vd v = cu->v[c] + 16.0 * cd * cd;                                                                \
                f = SELECT(vd, vl, v < f, v, f);                                                                       \
            }                                                                                                          \
            f -= cu->slack;                                                                                            \
            for (int k = 0; k < LANES && i + k < count; ++k)                                                           \
                out[i + k] = f[k];                                                                                     \
        }                                                                                                              \
    }

PHASE_FS_FN(phase_fs4, 4, SPAN_CLONES static)
#if HAVE_BOUNDS16
PHASE_FS_FN(phase_fs8, 8, __attribute__((target("avx512f"))) static)
#endif

/* four lanes at a time (AVX2, baseline), eight where the processor has AVX-512 */
void sol_nm_span_phase_fs(const sol_nm_span_cuts *cu, int l1, int count, double out[256])
{
#if HAVE_BOUNDS16
    if (__builtin_cpu_supports("avx512f")) {
        phase_fs8(cu, l1, count, out);
        return;
    }
#endif
    phase_fs4(cu, l1, count, out);
}
