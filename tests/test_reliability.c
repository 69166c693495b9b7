/* test_reliability.c - regression tests of issue 12 (numeric half): size arithmetic that must not
 * wrap (items 3), extreme magnitudes that must stay finite or give a documented status (item 6),
 * sol_angle3 at any magnitude (item 7). Each test here failed before its fix. */
#include <criterion/criterion.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sol_core.h"
#include "sol_normalmaps.h"
#include "sol_pipeline.h"
#include "sol_screen.h"
#include "sol_textures.h"

/* ---- item 7: sol_angle3 at extreme magnitudes ---- */

Test(reliability, angle3_is_scale_invariant_from_1e_minus_300_to_1e300)
{
    static const double scales[] = {1e-320, 1e-300, 1e-200, 1e-160, 1e-100, 1.0, 1e100, 1e160, 1e200, 1e300, 0x1p1023};
    const double u[3] = {1.0, 0.25, -0.5}, v[3] = {0.5, -1.0, 0.125};
    const double ref = sol_angle3(u, v);
    for (size_t i = 0; i < sizeof scales / sizeof *scales; ++i)
        for (size_t j = 0; j < sizeof scales / sizeof *scales; ++j) {
            double a[3], b[3];
            for (int c = 0; c < 3; ++c) {
                a[c] = u[c] * scales[i];
                b[c] = v[c] * scales[j];
            }
            double got = sol_angle3(a, b);
            /* subnormal components keep fewer digits */
            double tol = scales[i] < 1e-307 || scales[j] < 1e-307 ? 1e-3 : 1e-14;
            cr_assert(fabs(got - ref) <= tol, "scales %g %g: %.17g vs %.17g", scales[i], scales[j], got, ref);
        }
    const double big[3] = {DBL_MAX, DBL_MAX, -DBL_MAX}, x[3] = {1.0, 0.0, 0.0};
    cr_assert_float_eq(sol_angle3(big, x), acos(1.0 / sqrt(3.0)), 1e-15);
}

Test(reliability, angle3_tiny_angle_between_huge_or_tiny_vectors)
{
    const double a[3] = {1e200, 0.0, 0.0}, b[3] = {1e200, 1e191, 0.0};
    cr_assert_float_eq(sol_angle3(a, b), 1e-9, 1e-22);
    const double c[3] = {1e-200, 0.0, 0.0}, d[3] = {1e-200, 1e-209, 0.0};
    cr_assert_float_eq(sol_angle3(c, d), 1e-9, 1e-22);
    /* an angle of 1e-300 (its square underflows) */
    const double e[3] = {1.0, 0.0, 0.0}, f[3] = {1.0, 1e-300, 0.0};
    cr_assert_float_eq(sol_angle3(e, f), 1e-300, 1e-312);
    /* antiparallel at 1e-300 */
    const double g[3] = {-1e-300, 0.0, 0.0};
    cr_assert_float_eq(sol_angle3(c, g), M_PI, 1e-15);
    /* documented: zero vector gives 0, NaN or Inf gives NaN */
    const double z[3] = {0.0, -0.0, 0.0}, n[3] = {NAN, 0.0, 0.0}, inf[3] = {INFINITY, 0.0, 0.0};
    cr_assert_eq(sol_angle3(z, a), 0.0);
    const double huge[3] = {DBL_MAX, DBL_MAX, DBL_MAX};
    cr_assert_eq(sol_angle3(z, huge), 0.0);
    cr_assert(isnan(sol_angle3(z, n)));
    cr_assert(isnan(sol_angle3(n, a)));
    cr_assert(isnan(sol_angle3(a, inf)));
}

/* ---- item 3: UNORM with 32 bits and out-of-range bit counts ---- */

Test(reliability, unorm_32_bits_has_no_shift_overflow)
{
    cr_assert_eq(sol_unorm_encode(1.0, 32), UINT32_MAX);
    cr_assert_eq(sol_unorm_encode(0.5, 32), 2147483648u);
    cr_assert_eq(sol_unorm_encode(nextafter(1.0, 0.0), 32), UINT32_MAX);
    cr_assert_eq(sol_unorm_decode(UINT32_MAX, 32), 1.0);
    cr_assert_eq(sol_unorm_encode(1.0, 31), 0x7FFFFFFFu);
    cr_assert_eq(sol_unorm_encode(1.0, 1), 1u);
    /* documented: no such format */
    cr_assert_eq(sol_unorm_encode(1.0, 0), 0u);
    cr_assert_eq(sol_unorm_encode(1.0, 33), 0u);
    cr_assert_eq(sol_unorm_encode(1.0, -1), 0u);
    cr_assert_eq(sol_unorm_decode(5, 0), 0.0);
    cr_assert_eq(sol_unorm_decode(5, 64), 0.0);
}

/* ---- item 3: BC1 sizes ---- */

Test(reliability, bc1_size_at_int_max_does_not_overflow)
{
    cr_assert_eq(sol_bc1_size(INT_MAX, 1), (size_t)536870912 * 8u);
    cr_assert_eq(sol_bc1_size(1, INT_MAX), (size_t)536870912 * 8u);
    if (sizeof(size_t) >= 8)
        cr_assert_eq(sol_bc1_size(INT_MAX, INT_MAX), (size_t)536870912 * 536870912u * 8u);
    cr_assert_eq(sol_bc1_size(INT_MIN, 4), 0u);
    cr_assert_eq(sol_bc1_size(4, 0), 0u);
}

/* ---- item 3: G-buffer bytes ---- */

Test(reliability, gbuffer_bytes_is_exact_or_out_of_range)
{
    const sol_gbuffer_layout *layout = NULL;
    uint64_t bytes = 12345;
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CLASSIC_WIDE, &layout), SOL_OK); /* 144 bits */
    /* INT_MAX^2 * 8 * 144 / 8 = 144 * (2^31-1)^2 > 2^64: refused, output untouched */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 8, &bytes), SOL_ERR_OUT_OF_RANGE);
    cr_assert_eq(bytes, 12345u);
    /* INT_MAX^2 * 1 * 18 bytes: 2^62 * 18 > 2^64, refused */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 1, &bytes), SOL_ERR_OUT_OF_RANGE);
    /* 2^31-1 x 2^20 x 8 x 18 bytes = 18 * 8 * 2^20 * (2^31-1) fits: exact */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, 1 << 20, 8, &bytes), SOL_OK);
    cr_assert_eq(bytes, (uint64_t)INT_MAX * (1u << 20) * 8u * 18u);
    /* the product w*h*samples*bits (2^62 * 8 * 64 = 2^71) passes 2^64 but the answer (2^68 / 8...)
     * CryENGINE 3 layout: 64 bits = 8 bytes; 2^31-1 squared * 8 * 8 bytes > 2^64: refused */
    cr_assert_eq(sol_gbuffer_layout_get(SOL_GBUFFER_CRYENGINE3, &layout), SOL_OK);
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, INT_MAX, 8, &bytes), SOL_ERR_OUT_OF_RANGE);
    /* 2^31-1 x 2^24 x 8 samples x 8 bytes: w*h*s*bits = 2^(31+24+3+6) wraps 2^64, the answer
     * 2^(31+24+3+3) - ... does not */
    cr_assert_eq(sol_gbuffer_bytes(layout, INT_MAX, 1 << 24, 8, &bytes), SOL_OK);
    cr_assert_eq(bytes, (uint64_t)INT_MAX * (1u << 24) * 64u);
}

/* ---- item 3: adaptive BC5 window of INT_MAX ---- */

static void bumpy_block(double n[16][3])
{
    for (int i = 0; i < 16; ++i) {
        double x = 0.6 * sin(1.7 * i), y = 0.5 * cos(2.3 * i + 0.4);
        n[i][0] = x;
        n[i][1] = y;
        n[i][2] = sqrt(1.0 - x * x - y * y);
    }
}

Test(reliability, bc5_adaptive_window_int_max_searches_every_code)
{
    double n[16][3];
    bumpy_block(n);
    sol_bc5_options big = {.encoder = SOL_BC5_ADAPTIVE, .window = INT_MAX};
    sol_bc5_options all = {.encoder = SOL_BC5_ADAPTIVE, .window = 255};
    sol_bc5_options some = {.encoder = SOL_BC5_ADAPTIVE, .window = 2};
    sol_bc5_block b1, b2, b3;
    sol_bc5_info i1 = {0}, i2 = {0}, i3 = {0};
    cr_assert_eq(sol_bc5_encode_block(n, &big, &b1, &i1), SOL_OK);
    cr_assert_eq(sol_bc5_encode_block(n, &all, &b2, &i2), SOL_OK);
    cr_assert_eq(sol_bc5_encode_block(n, &some, &b3, &i3), SOL_OK);
    cr_assert_eq(i1.candidates, i2.candidates, "INT_MAX tried %g candidates, 255 tried %g", (double)i1.candidates,
                 (double)i2.candidates);
    cr_assert_eq(memcmp(&b1, &b2, sizeof b1), 0);
    cr_assert_geq(i1.candidates, i3.candidates);
    cr_assert_leq(i1.error, i3.error);
}

/* ---- item 3: coverage buffer with a huge block ---- */

Test(reliability, cbuffer_huge_block_is_one_texel_and_tests_in_bounds)
{
    float depth[6 * 5];
    for (int i = 0; i < 6 * 5; ++i)
        depth[i] = 1.0f + (float)i;
    static const int blocks[] = {6, 7, 1 << 20, INT_MAX - 1, INT_MAX};
    for (size_t k = 0; k < sizeof blocks / sizeof *blocks; ++k) {
        sol_cbuffer_options opt = {.block = blocks[k]};
        sol_cbuffer cb;
        cr_assert_eq(sol_cbuffer_build(depth, 6, 5, &opt, &cb), SOL_OK);
        cr_assert_eq(cb.levels, 1, "block %d", blocks[k]);
        cr_assert_eq(cb.width[0], 1);
        cr_assert_eq(cb.height[0], 1);
        cr_assert_eq(cb.zmax[0][0], 30.0f); /* the farthest depth */
        sol_screen_bounds near = {.x0 = 0, .x1 = 5.5, .y0 = 0, .y1 = 4.5, .znear = 0.5};
        sol_screen_bounds far = {.x0 = 2, .x1 = 3, .y0 = 1, .y1 = 2, .znear = 40.0};
        int occluded = -1, visited = -1;
        cr_assert_eq(sol_cbuffer_test(&cb, &near, -1, &occluded, &visited), SOL_OK);
        cr_assert_eq(occluded, 0);
        cr_assert_eq(visited, 1);
        cr_assert_eq(sol_cbuffer_test(&cb, &far, -1, &occluded, &visited), SOL_OK);
        cr_assert_eq(occluded, 1);
        sol_cbuffer_free(&cb);
    }
}
