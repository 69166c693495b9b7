/* test_normals.c - 24-bit G-buffer normals (claims D3-D7, S1, S5): hard inputs, round-trip error
 * bounds, cell counts at reduced size, the baked best-fit table. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sol_normals.h"
#include "normals_internal.h" /* the best-fit searches themselves, for the scalar-scan reference */

#define DEG (180.0 / M_PI)

/* Worst angular error (degrees) each method may show for any direction: the measured maxima of
 * results/d6_d7_s1_s5_normal_encodings/errors.md over 10^7 directions, rounded up by ~5-10%. */
static double bound_deg(sol_normal_method m)
{
    switch (m) {
    case SOL_NORMAL_XYZ_NORMALIZED: return 0.40;     /* measured 0.3857 */
    case SOL_NORMAL_XYZ_MAX_COMPONENT: return 0.33;  /* 0.3178 */
    case SOL_NORMAL_XYZ_BEST_FIT: return 0.33;       /* 0.3178 = sqrt(2)/255 rad next to an axis */
    case SOL_NORMAL_XYZ_BEST_FIT_FLOAT: return 0.33; /* the same */
    case SOL_NORMAL_OCTAHEDRAL_12: return 0.065;     /* 0.0592 */
    case SOL_NORMAL_OCTAHEDRAL_12_PRECISE: return 0.043; /* 0.0395 */
    case SOL_NORMAL_SPHERICAL_12: return 0.055;      /* 0.0491 */
    case SOL_NORMAL_SPHERICAL_Z_12: return 1.35;    /* 1.257 over 2e5 random directions, next to the poles */
    case SOL_NORMAL_MITTRING_12: return 3.0;         /* 2.86, next to N = (0, 0, +1) */
    case SOL_NORMAL_MITTRING_8: return 12.0;         /* 11.75 */
    default: return 0.0;
    }
}

static double round_trip_deg(sol_normal_method m, const double n[3])
{
    uint32_t code = 0xFFFFFFFFu;
    double back[3];
    cr_assert_eq(sol_normal_encode(m, n, &code), SOL_OK, "%s", sol_normal_method_name(m));
    cr_assert_eq(code >> sol_normal_method_bits(m), 0u);
    cr_assert_eq(sol_normal_decode(m, code, back), SOL_OK);
    cr_assert(isfinite(back[0]) && isfinite(back[1]) && isfinite(back[2]));
    cr_assert_float_eq(sol_dot3(back, back), 1.0, 1e-12);
    return sol_angle3(n, back) * DEG;
}

/* Axes, face diagonals, cube diagonals, and each nudged by 1e-7 in both directions. */
Test(normals, axes_diagonals_and_near_misses_round_trip_within_bounds)
{
    static const double base[][3] = {{1, 0, 0},  {0, 1, 0},   {0, 0, 1},  {-1, 0, 0}, {0, -1, 0}, {0, 0, -1},
                                     {1, 1, 0},  {1, -1, 0},  {0, 1, 1},  {-1, 0, 1}, {1, 1, 1},  {-1, 1, -1},
                                     {-1, -1, -1}, {1, -1, 1}};
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m)
        for (size_t b = 0; b < sizeof base / sizeof base[0]; ++b)
            for (int nudge = -1; nudge <= 1; ++nudge) {
                double n[3] = {base[b][0] + nudge * 1e-7, base[b][1] - nudge * 1e-7, base[b][2] + nudge * 3e-8};
                double err = round_trip_deg((sol_normal_method)m, n);
                cr_assert_leq(err, bound_deg((sol_normal_method)m), "%s base %zu nudge %d: %g deg",
                              sol_normal_method_name((sol_normal_method)m), b, nudge, err);
            }
}

Test(normals, random_directions_round_trip_within_bounds)
{
    uint64_t state = 7;
    for (int k = 0; k < 20000; ++k) {
        double n[3];
        sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
        for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m)
            cr_assert_leq(round_trip_deg((sol_normal_method)m, n), bound_deg((sol_normal_method)m), "%s",
                          sol_normal_method_name((sol_normal_method)m));
    }
}

Test(normals, negative_zero_denormal_and_scale_do_not_change_the_code)
{
    const double tiny = 4.9406564584124654e-324; /* smallest denormal */
    const double pairs[][2][3] = {
        {{-0.0, -0.0, 1.0}, {0.0, 0.0, 1.0}},
        {{tiny, 0.0, -0.0}, {1.0, 0.0, 0.0}},
        {{1e-310, -1e-310, 1e-310}, {1.0, -1.0, 1.0}},
        {{3e300, 4e300, -1e300}, {0.3, 0.4, -0.1}},
        {{3e-300, 4e-300, -1e-300}, {3, 4, -1}},
        {{0.2, 0.0, -0.0}, {1.0, 0.0, 0.0}},
    };
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m)
        for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; ++p) {
            uint32_t a, b;
            cr_assert_eq(sol_normal_encode((sol_normal_method)m, pairs[p][0], &a), SOL_OK);
            cr_assert_eq(sol_normal_encode((sol_normal_method)m, pairs[p][1], &b), SOL_OK);
            cr_assert_eq(a, b, "%s pair %zu", sol_normal_method_name((sol_normal_method)m), p);
        }
}

Test(normals, bad_input_gives_status_and_leaves_outputs_untouched)
{
    const double zero[3] = {0.0, -0.0, 0.0}, nan3[3] = {NAN, 0, 1}, inf3[3] = {0, -INFINITY, 1}, ok[3] = {0, 0, 1};
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m) {
        sol_normal_method method = (sol_normal_method)m;
        uint32_t code = 12345;
        cr_assert_eq(sol_normal_encode(method, zero, &code), SOL_ERR_ZERO_LENGTH);
        cr_assert_eq(sol_normal_encode(method, nan3, &code), SOL_ERR_NONFINITE);
        cr_assert_eq(sol_normal_encode(method, inf3, &code), SOL_ERR_NONFINITE);
        cr_assert_eq(sol_normal_encode(method, NULL, &code), SOL_ERR_NULL_ARG);
        cr_assert_eq(sol_normal_encode(method, ok, NULL), SOL_ERR_NULL_ARG);
        cr_assert_eq(code, 12345u);
        double n[3] = {7, 7, 7};
        cr_assert_eq(sol_normal_decode(method, 1u << 24, n), SOL_ERR_INVALID_ARG);
        cr_assert_eq(sol_normal_decode(method, 0, NULL), SOL_ERR_NULL_ARG);
        cr_assert_eq(n[0], 7.0);
    }
    uint32_t code = 1;
    cr_assert_eq(sol_normal_encode(SOL_NORMAL_METHOD_COUNT, ok, &code), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_encode((sol_normal_method)-1, ok, &code), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_decode(SOL_NORMAL_MITTRING_8, 1u << 16, (double[3]){0}), SOL_ERR_INVALID_ARG);
    cr_assert_str_eq(sol_normal_method_name(SOL_NORMAL_METHOD_COUNT), "unknown");
    cr_assert_eq(code, 1u);
}

/* Every 24-bit code decodes to a finite unit vector (the 2-channel formats include unused codes:
 * octahedral 4095, Mittring's corners with |G| > 1). Checked on a stride through all codes. */
Test(normals, every_code_decodes_to_a_unit_vector)
{
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m) {
        uint32_t limit = 1u << sol_normal_method_bits((sol_normal_method)m);
        for (uint32_t code = 0; code < limit; code += (code & 1u) ? 4093u : 1u) {
            double n[3];
            cr_assert_eq(sol_normal_decode((sol_normal_method)m, code, n), SOL_OK);
            cr_assert_float_eq(sol_dot3(n, n), 1.0, 1e-12, "%s code %u", sol_normal_method_name((sol_normal_method)m),
                               code);
        }
        double n[3];
        cr_assert_eq(sol_normal_decode((sol_normal_method)m, limit - 1, n), SOL_OK);
        cr_assert_float_eq(sol_dot3(n, n), 1.0, 1e-12);
    }
}

Test(normals, quantize255_matches_the_talks_appendix)
{
    cr_assert_eq(sol_quantize255(-1.0), 0u);
    cr_assert_eq(sol_quantize255(1.0), 255u);
    cr_assert_eq(sol_quantize255(0.0), 128u); /* 127.5 rounds up */
    cr_assert_eq(sol_quantize255(-0.0), 128u);
    cr_assert_eq(sol_quantize255(5.0), 255u);
    cr_assert_eq(sol_quantize255(NAN), 0u);
    cr_assert_float_eq(sol_dequantize255(128), 1.0 / 255.0, 1e-15);
}

/* D4: dividing by the largest component lands every normal on a boundary cell of the cube. */
Test(normals, d4_max_component_codes_lie_on_the_cube_boundary)
{
    uint64_t state = 3;
    for (int k = 0; k < 20000; ++k) {
        double n[3];
        uint32_t code;
        sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
        cr_assert_eq(sol_normal_encode(SOL_NORMAL_XYZ_MAX_COMPONENT, n, &code), SOL_OK);
        int boundary = 0;
        for (int i = 0; i < 3; ++i) {
            uint32_t c = (code >> (8 * i)) & 255u;
            boundary |= c == 0 || c == 255;
        }
        cr_assert(boundary);
    }
}

/* D3-D5 at reduced size: slices of the 256^3 cube and small grids checked against brute force. */
Test(normals, d3_d5_cell_counts_on_slices_and_small_grids)
{
    uint64_t count = 0;
    /* D4: slice r = 0 is a whole face (256^2 cells), slice r = 1 its boundary ring (4 * 255). */
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_MAX_COMPONENT, 0, 1, &count), SOL_OK);
    cr_assert_eq(count, 65536u);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_MAX_COMPONENT, 1, 2, &count), SOL_OK);
    cr_assert_eq(count, 1020u);
    /* The sphere meets every cell of a 2^3 grid; larger grids against a floating-point brute force. */
    cr_assert_eq(sol_normal_cells_on_sphere(2, &count), SOL_OK);
    cr_assert_eq(count, 8u);
    for (int levels = 4; levels <= 16; levels += 6) {
        uint64_t brute = 0;
        for (int i = 0; i < levels; ++i)
            for (int j = 0; j < levels; ++j)
                for (int k = 0; k < levels; ++k) {
                    double lo = 0, hi = 0;
                    int c[3] = {i, j, k};
                    for (int a = 0; a < 3; ++a) { /* the talk's grid: centres -1 + 2c/(L-1) */
                        double centre = fabs(-1.0 + 2.0 * c[a] / (levels - 1)), half = 1.0 / (levels - 1);
                        double near = centre > half ? centre - half : 0.0, far = centre + half;
                        lo += near * near;
                        hi += far * far;
                    }
                    brute += lo <= 1.0 + 1e-12 && hi >= 1.0 - 1e-12;
                }
        cr_assert_eq(sol_normal_cells_on_sphere(levels, &count), SOL_OK);
        cr_assert_eq(count, brute, "levels %d: %llu vs %llu", levels, (unsigned long long)count,
                     (unsigned long long)brute);
    }
    /* Distinct directions of a 4^3 grid: coordinates in {-3,-1,1,3}; gcd > 1 only for (+-3,+-3,+-3). */
    cr_assert_eq(sol_normal_cells_distinct_directions(4, &count), SOL_OK);
    cr_assert_eq(count, 64u - 8u);
    cr_assert_eq(sol_normal_cells_on_sphere(3, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_OCTAHEDRAL_12, 0, 1, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_BEST_FIT, 0, 257, &count), SOL_ERR_INVALID_ARG);
}

/* D5 at reduced size: on a slice both searches keep about as many cells as there are distinct
 * directions (gcd 1; ties between a cell and its odd multiples break by rounding noise, so
 * the sets differ a little), far more than normalized normals. */
Test(normals, d5_best_fit_keeps_most_cells_of_a_slice)
{
    uint64_t fit = 0, fit_float = 0, normalized = 0;
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_BEST_FIT, 200, 201, &fit), SOL_OK);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_BEST_FIT_FLOAT, 200, 201, &fit_float), SOL_OK);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_NORMALIZED, 200, 201, &normalized), SOL_OK);
    uint64_t distinct = 0;
    for (int g = 0; g < 256; ++g)
        for (int b = 0; b < 256; ++b) {
            int x = 2 * 200 - 255, y = abs(2 * g - 255), z = abs(2 * b - 255);
            int a = x;
            for (int v = y; v;) { int t = a % v; a = v; v = t; }
            for (int v = z; v;) { int t = a % v; a = v; v = t; }
            distinct += a == 1;
        }
    cr_assert_gt(fit, 0.95 * distinct);
    cr_assert_gt(fit_float, 0.95 * distinct);
    cr_assert_gt(fit, 0.9 * 65536);
    cr_assert_lt(normalized, 0.05 * 65536);
}

/* D6: a 128^2 table with point sampling stays within its measured worst case (0.734 deg over 2e5
 * directions); bilinear filtering blends scales of different cells and is worse on average. */
Test(normals, d6_table_path_matches_the_search_closely)
{
    sol_bestfit_table table = {0}, mip = {0};
    cr_assert_eq(sol_bestfit_table_build(0, 8, &table), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_bestfit_table_build(64, 12, &table), SOL_ERR_INVALID_ARG);
    cr_assert_null(table.scale);
    cr_assert_eq(sol_bestfit_table_build(128, 16, &table), SOL_OK);
    for (int i = 0; i < 128 * 128; ++i)
        cr_assert(table.scale[i] >= 1.5 / 127.5 - 1e-4 && table.scale[i] <= 1.0f);
    uint64_t state = 11;
    double worst = 0, sum[2] = {0, 0};
    for (int k = 0; k < 20000; ++k) {
        double n[3], back[3];
        uint32_t code;
        sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
        for (int filter = 0; filter < 2; ++filter) {
            cr_assert_eq(sol_normal_encode_bestfit_table(&table, (sol_table_filter)filter, n, &code), SOL_OK);
            sol_normal_decode(SOL_NORMAL_XYZ_NORMALIZED, code, back);
            double e = sol_angle3(n, back) * DEG;
            sum[filter] += e;
            if (filter == SOL_TABLE_NEAREST)
                worst = e > worst ? e : worst;
        }
    }
    cr_assert_leq(worst, 0.8, "table path worst %g deg", worst);
    cr_assert_gt(sum[SOL_TABLE_BILINEAR], sum[SOL_TABLE_NEAREST]);
    uint32_t code = 99;
    cr_assert_eq(sol_normal_encode_bestfit_table(&table, SOL_TABLE_NEAREST, (double[3]){0, 0, 0}, &code),
                 SOL_ERR_ZERO_LENGTH);
    cr_assert_eq(sol_normal_encode_bestfit_table(&table, (sol_table_filter)5, (double[3]){0, 0, 1}, &code),
                 SOL_ERR_INVALID_ARG);
    cr_assert_eq(code, 99u);
    cr_assert_eq(sol_bestfit_table_downsample(&table, &mip), SOL_OK);
    cr_assert_eq(mip.size, 64);
    sol_bestfit_table_free(&mip);
    sol_bestfit_table_free(&table);
    sol_bestfit_table_free(&table);
    cr_assert_null(table.scale);
}

/* D6 "8-bit precision is sufficient": every scale the search returns is t = 2s/255 with 2s odd
 * (3..255), an exact 8-bit UNORM code, so an 8-bit table stores the scales without loss. */
Test(normals, d6_best_fit_scales_are_exact_8bit_codes)
{
    uint64_t state = 5;
    for (int k = 0; k < 5000; ++k) {
        double n[3], t = -1;
        sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
        cr_assert_eq(sol_bestfit_scale(n, &t), SOL_OK);
        double code = t * 255.0;
        cr_assert_float_eq(code, nearbyint(code), 1e-9, "t = %.17g", t);
        cr_assert_eq(((long)nearbyint(code)) % 2, 1, "t * 255 = %g is even", code);
        cr_assert(code >= 3.0 - 1e-9 && code <= 255.0 + 1e-9);
    }
}

/* Concrete codes for chosen directions, for every method whose codes follow exactly from the
 * header's formulas (no transcendental functions, no ties broken by rounding noise): an encoder
 * written from sol_normals.h must produce these. Directions: +-z, +-x, +-y, the upper fold
 * diagonals (1,+-1,0)/sqrt 2, the lower half's (+-1,0,-1), (0,1,-1), and the cube diagonals. */
static const double pin_dirs[][3] = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}, {1, 1, 0},
                                     {-1, 1, 0}, {1, 0, -1}, {-1, 0, -1}, {0, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, 1, 1}};
enum { PIN_DIRS = sizeof pin_dirs / sizeof pin_dirs[0], PIN_ALL = PIN_DIRS, PIN_AXES_AND_EDGES = 11, PIN_AXES = 6 };

static void check_pinned(sol_normal_method m, const uint32_t *codes, int count)
{
    for (int i = 0; i < count; ++i) {
        uint32_t code = 0;
        cr_assert_eq(sol_normal_encode(m, pin_dirs[i], &code), SOL_OK);
        cr_assert_eq(code, codes[i], "%s direction %d: 0x%06x, pinned 0x%06x", sol_normal_method_name(m), i, code,
                     codes[i]);
    }
}

Test(normals, pinned_codes_of_exact_methods)
{
    /* XYZ: channel code = round(255 (c/2 + 1/2)); 0 -> 128 (127.5 rounds up), 1/sqrt2 -> 218 = 0xda. */
    static const uint32_t xyz[PIN_ALL] = {0xff8080, 0x008080, 0x8080ff, 0x808000, 0x80ff80, 0x800080, 0x80dada,
                                          0x80da25, 0x2580da, 0x258025, 0x25da80, 0x36c9c9, 0x363636, 0xc9c9c9};
    static const uint32_t maxc[PIN_ALL] = {0xff8080, 0x008080, 0x8080ff, 0x808000, 0x80ff80, 0x800080, 0x80ffff,
                                           0x80ff00, 0x0080ff, 0x008000, 0x00ff80, 0x00ffff, 0x000000, 0xffffff};
    /* Best fit, axes and edges: the zero components quantize to 128 (1/255) at every probe, so the
     * error (1/255)/t is least at t = 1, the max-component cell. (On the cube diagonals every probe
     * is exact and rounding noise picks the winner: not pinned.) */
    /* Octahedral SNORM: u * 2047 rounded, + 2047. +z (0,0) -> 2047|2047<<12; -z folds to (1,1) ->
     * 4094|4094<<12; (1,1,0) -> (0.5,0.5) -> 1024+2047 = 3071 = 0xbff; (1,1,-1) -> (1/3,1/3) folds
     * to (2/3,2/3) -> 1365+2047 = 3412 = 0xd54. */
    static const uint32_t oct[PIN_ALL] = {0x7ff7ff, 0xffeffe, 0x7ffffe, 0x7ff000, 0xffe7ff, 0x0007ff, 0xbffbff,
                                          0xbff400, 0xbffffe, 0xbff000, 0xffebff, 0xd54d54, 0x2aa2aa, 0xaa9aa9};
    static const uint32_t octp[PIN_ALL] = {0x7ff7ff, 0xffeffe, 0x7ffffe, 0x7ff000, 0xffe7ff, 0x0007ff, 0xbfebff,
                                           0xbfe3ff, 0xbfeffe, 0xbfe000, 0xffebfe, 0xd54d54, 0x2aa2aa, 0xaaaaa9};
    /* Mittring: G = normalize(xy) sqrt(z/2 + 1/2); +z -> (1, 0) -> (4095, 2048); -z -> G = 0 -> 2048, 2048;
     * +x -> (sqrt(1/2), 0) -> 0xda7. */
    static const uint32_t mit12[PIN_AXES] = {0x800fff, 0x800800, 0x800da7, 0x800258, 0xda7800, 0x258800};
    static const uint32_t mit8[PIN_AXES] = {0x0080ff, 0x008080, 0x0080da, 0x008025, 0x00da80, 0x002580};
    check_pinned(SOL_NORMAL_XYZ_NORMALIZED, xyz, PIN_ALL);
    check_pinned(SOL_NORMAL_XYZ_MAX_COMPONENT, maxc, PIN_ALL);
    check_pinned(SOL_NORMAL_XYZ_BEST_FIT, maxc, PIN_AXES_AND_EDGES);
    check_pinned(SOL_NORMAL_XYZ_BEST_FIT_FLOAT, maxc, PIN_AXES_AND_EDGES);
    check_pinned(SOL_NORMAL_OCTAHEDRAL_12, oct, PIN_ALL);
    check_pinned(SOL_NORMAL_OCTAHEDRAL_12_PRECISE, octp, PIN_ALL);
    check_pinned(SOL_NORMAL_MITTRING_12, mit12, PIN_AXES);
    check_pinned(SOL_NORMAL_MITTRING_8, mit8, PIN_AXES);
    /* The header's formula, checked on the pinned directions' decoded values: u = (a - 2047) / 2047. */
    double back[3];
    cr_assert_eq(sol_normal_decode(SOL_NORMAL_OCTAHEDRAL_12, 0x7ff7ff, back), SOL_OK);
    cr_assert(back[0] == 0.0 && back[1] == 0.0 && back[2] == 1.0);
    cr_assert_eq(sol_normal_decode(SOL_NORMAL_OCTAHEDRAL_12, 0xffeffe, back), SOL_OK);
    cr_assert(back[0] == 0.0 && back[1] == 0.0 && back[2] == -1.0);
}

/* sol_oct_encode/decode: bits 12 SNORM are the 12:12 method's codes; UNORM is the other common rule
 * (+z -> 2048, 2048: 0.5 * 4095 = 2047.5 rounds up); both round-trip within half a code step. */
Test(normals, oct_any_bits_matches_the_method_and_pins_unorm_codes)
{
    static const uint32_t unorm12[PIN_ALL][2] = {{2048, 2048}, {4095, 4095}, {4095, 2048}, {0, 2048},
                                                 {2048, 4095}, {2048, 0},    {3071, 3071}, {1024, 3071},
                                                 {4095, 3071}, {0, 3071},    {3071, 4095}, {3413, 3413},
                                                 {682, 682},   {2730, 2730}};
    for (int i = 0; i < PIN_DIRS; ++i) {
        uint32_t c[2], code;
        for (int precise = 0; precise < 2; ++precise) {
            sol_oct_options snorm = {12, precise, SOL_OCT_SNORM};
            cr_assert_eq(sol_oct_encode(&snorm, pin_dirs[i], c), SOL_OK);
            cr_assert_eq(sol_normal_encode(precise ? SOL_NORMAL_OCTAHEDRAL_12_PRECISE : SOL_NORMAL_OCTAHEDRAL_12,
                                           pin_dirs[i], &code),
                         SOL_OK);
            cr_assert_eq(c[0] | (c[1] << 12), code, "direction %d precise %d", i, precise);
        }
        sol_oct_options unorm = {12, 0, SOL_OCT_UNORM};
        cr_assert_eq(sol_oct_encode(&unorm, pin_dirs[i], c), SOL_OK);
        cr_assert(c[0] == unorm12[i][0] && c[1] == unorm12[i][1], "direction %d: %u,%u", i, c[0], c[1]);
    }
    /* zero options = NULL options = 12-bit SNORM nearest */
    uint32_t a[2], b[2];
    sol_oct_options zero = {0};
    cr_assert_eq(sol_oct_encode(&zero, pin_dirs[11], a), SOL_OK);
    cr_assert_eq(sol_oct_encode(NULL, pin_dirs[11], b), SOL_OK);
    cr_assert(a[0] == b[0] && a[1] == b[1] && a[0] == 0xd54);
    /* every bit count, both quantizers, random directions: error within the step's bound */
    uint64_t state = 17;
    for (int bits = 2; bits <= 16; ++bits)
        for (int q = 0; q < 2; ++q)
            for (int k = 0; k < 300; ++k) {
                double n[3], back[3];
                sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
                sol_oct_options o = {bits, k & 1, (sol_oct_quantizer)q};
                cr_assert_eq(sol_oct_encode(&o, n, a), SOL_OK);
                cr_assert(a[0] < (1u << bits) && a[1] < (1u << bits));
                cr_assert_eq(sol_oct_decode(&o, a, back), SOL_OK);
                /* a code step in u is <= 2/(2^bits - 2); the map stretches angles by less than 3 */
                double step = 2.0 / ((1 << bits) - 2);
                cr_assert_leq(sol_angle3(n, back), 3.0 * step, "bits %d q %d: %g rad", bits, q, sol_angle3(n, back));
            }
}

Test(normals, oct_bad_options_and_codes)
{
    uint32_t c[2] = {7, 7}, big[2] = {4096, 0};
    double n[3] = {5, 5, 5};
    const double up[3] = {0, 0, 1}, nan3[3] = {NAN, 0, 1}, zero3[3] = {0, 0, 0};
    sol_oct_options bad_bits = {17, 0, 0}, one_bit = {1, 0, 0}, bad_q = {12, 0, (sol_oct_quantizer)2},
                    bad_p = {12, 2, 0};
    cr_assert_eq(sol_oct_encode(&bad_bits, up, c), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_encode(&one_bit, up, c), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_encode(&bad_q, up, c), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_encode(&bad_p, up, c), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_encode(NULL, nan3, c), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_oct_encode(NULL, zero3, c), SOL_ERR_ZERO_LENGTH);
    cr_assert_eq(sol_oct_encode(NULL, NULL, c), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_oct_encode(NULL, up, NULL), SOL_ERR_NULL_ARG);
    cr_assert(c[0] == 7 && c[1] == 7);
    cr_assert_eq(sol_oct_decode(NULL, big, n), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_decode(&bad_bits, c, n), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_oct_decode(NULL, NULL, n), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_oct_decode(NULL, c, NULL), SOL_ERR_NULL_ARG);
    cr_assert_eq(n[0], 5.0);
    /* the unused SNORM code 2^bits - 1 clamps to +1: (4095, 2047) decodes like (4094, 2047) = +x */
    uint32_t top[2] = {4095, 2047};
    cr_assert_eq(sol_oct_decode(NULL, top, n), SOL_OK);
    cr_assert(n[0] == 1.0 && n[1] == 0.0 && n[2] == 0.0);
}

/* D3's sample-free count: cells whose centre length is within half_width/255 of 1. sqrt(2) gives
 * the talk's 289880 exactly, and so does every width in the measured step [1.411778, 1.427378);
 * small grids against a brute force written from the definition. */
Test(normals, d3_cells_near_the_sphere)
{
    uint64_t count = 0;
    cr_assert_eq(sol_normal_cells_near_sphere(256, sqrt(2.0), &count), SOL_OK);
    cr_assert_eq(count, 289880u);
    cr_assert_eq(sol_normal_cells_near_sphere(256, 1.4118, &count), SOL_OK);
    cr_assert_eq(count, 289880u);
    cr_assert_eq(sol_normal_cells_near_sphere(256, 1.4273, &count), SOL_OK);
    cr_assert_eq(count, 289880u);
    cr_assert_eq(sol_normal_cells_near_sphere(256, 1.4117, &count), SOL_OK);
    cr_assert_lt(count, 289880u);
    cr_assert_eq(sol_normal_cells_near_sphere(256, 1.4274, &count), SOL_OK);
    cr_assert_gt(count, 289880u);
    /* huge width: every cell; zero width: only centres exactly on the sphere (none for L = 2: sqrt 3) */
    cr_assert_eq(sol_normal_cells_near_sphere(16, 1e300, &count), SOL_OK);
    cr_assert_eq(count, 4096u);
    cr_assert_eq(sol_normal_cells_near_sphere(2, 0.0, &count), SOL_OK);
    cr_assert_eq(count, 0u);
    for (int levels = 4; levels <= 40; levels += 12)
        for (double w = 0.0; w <= 3.0; w += 0.37) {
            uint64_t brute = 0;
            for (int i = 0; i < levels; ++i)
                for (int j = 0; j < levels; ++j)
                    for (int k = 0; k < levels; ++k) {
                        double c[3] = {-1.0 + 2.0 * i / (levels - 1), -1.0 + 2.0 * j / (levels - 1),
                                       -1.0 + 2.0 * k / (levels - 1)};
                        brute += fabs(sqrt(sol_dot3(c, c)) - 1.0) <= w / (levels - 1) + 1e-12;
                    }
            cr_assert_eq(sol_normal_cells_near_sphere(levels, w, &count), SOL_OK);
            cr_assert_eq(count, brute, "levels %d width %g: %llu vs %llu", levels, w, (unsigned long long)count,
                         (unsigned long long)brute);
        }
    count = 7;
    cr_assert_eq(sol_normal_cells_near_sphere(256, NAN, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_near_sphere(256, INFINITY, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_near_sphere(256, -0.5, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_near_sphere(255, 1.0, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_near_sphere(4098, 1.0, &count), SOL_ERR_INVALID_ARG);
    cr_assert_eq(count, 7u);
    cr_assert_eq(sol_normal_cells_near_sphere(256, 1.0, NULL), SOL_ERR_NULL_ARG);
}

/* D5: the image and fixed cells of the best-fit search under each precision and input path, on a
 * slice. The normalised-input counts agree with sol_normal_cells_fixed and with a brute force over
 * sol_normal_encode; every fixed cell is in the image. */
Test(normals, d5_bestfit_cells_variants_on_a_slice)
{
    uint8_t *seen = calloc(1u << 24, 1);
    cr_assert_not_null(seen);
    uint64_t brute_image = 0;
    for (uint32_t g = 0; g < 256; ++g)
        for (uint32_t b = 0; b < 256; ++b) {
            double c[3] = {sol_dequantize255(200), sol_dequantize255(g), sol_dequantize255(b)};
            uint32_t code;
            cr_assert_eq(sol_normal_encode(SOL_NORMAL_XYZ_BEST_FIT, c, &code), SOL_OK);
            brute_image += !seen[code];
            seen[code] = 1;
        }
    free(seen);
    uint64_t fixed_d = 0, fixed_f = 0;
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_BEST_FIT, 200, 201, &fixed_d), SOL_OK);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_BEST_FIT_FLOAT, 200, 201, &fixed_f), SOL_OK);
    sol_bestfit_cells cells = {0, 0};
    cr_assert_eq(sol_normal_cells_bestfit(NULL, 200, 201, &cells), SOL_OK);
    cr_assert_eq(cells.fixed, fixed_d);
    cr_assert_eq(cells.image, brute_image);
    sol_bestfit_cells_options single = {1, SOL_BESTFIT_INPUT_UNIT};
    cr_assert_eq(sol_normal_cells_bestfit(&single, 200, 201, &cells), SOL_OK);
    cr_assert_eq(cells.fixed, fixed_f);
    for (int s = 0; s < 2; ++s)
        for (int in = 0; in < 3; ++in) {
            sol_bestfit_cells_options o = {s, (sol_bestfit_input)in};
            cr_assert_eq(sol_normal_cells_bestfit(&o, 200, 201, &cells), SOL_OK);
            cr_assert_geq(cells.image, cells.fixed);
            /* rounding the centre to half moves it by up to 2^-11 relative, off its own ray for many
             * cells (slice 200 keeps 49490 in double); the other paths keep > 90% */
            double share = in == SOL_BESTFIT_INPUT_HALF ? 0.6 : 0.9;
            cr_assert_gt(cells.fixed, share * 65536, "single %d input %d: %llu", s, in, (unsigned long long)cells.fixed);
        }
    /* an empty range counts nothing; bad options and ranges leave the output untouched */
    cr_assert_eq(sol_normal_cells_bestfit(NULL, 17, 17, &cells), SOL_OK);
    cr_assert(cells.image == 0 && cells.fixed == 0);
    cells.image = 5;
    sol_bestfit_cells_options bad_single = {2, SOL_BESTFIT_INPUT_UNIT}, bad_input = {0, (sol_bestfit_input)3};
    cr_assert_eq(sol_normal_cells_bestfit(&bad_single, 0, 1, &cells), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_bestfit(&bad_input, 0, 1, &cells), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_bestfit(NULL, -1, 1, &cells), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_bestfit(NULL, 0, 257, &cells), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_bestfit(NULL, 2, 1, &cells), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_normal_cells_bestfit(NULL, 0, 1, NULL), SOL_ERR_NULL_ARG);
    cr_assert_eq(cells.image, 5u);
}

/* S5 regression on the octahedral bit sweep (d6_d7's octahedral_bits table, 10^6 directions): the
 * mean error halves per added bit (SNORM 12:12 mean 0.0209 deg on uniform directions), the worst
 * case stays below 0.0600 deg x 2^(12-bits) (measured up to 0.0592; 0.0410 for precise rounding,
 * measured up to 0.0398 at 8:8, which also lowers the mean),
 * and UNORM rounding on random cube points normalised reproduces L. Tyler's means (12:12 0.021842,
 * 8:8 0.350526 deg) within 2% on 20000 directions. */
Test(normals, oct_bit_sweep_regression)
{
    static const double tyler_mean[] = {0.350526, 0.174814, 0.087357, 0.043663, 0.021842, 0.010909}; /* 8..13 */
    enum { N = 20000 };
    for (int bits = 8; bits <= 16; ++bits) {
        double scale = ldexp(1.0, 12 - bits), sum[3] = {0, 0, 0}, worst[3] = {0, 0, 0};
        uint64_t state = 101, cube_state = 202;
        for (int k = 0; k < N; ++k) {
            double n[3], c[3], back[3];
            uint32_t code[2];
            sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
            for (int i = 0; i < 3; ++i)
                c[i] = sol_rng_uniform(&cube_state, -1, 1);
            const double *dir[3] = {n, n, c};
            sol_oct_options o[3] = {{bits, 0, SOL_OCT_SNORM}, {bits, 1, SOL_OCT_SNORM}, {bits, 0, SOL_OCT_UNORM}};
            for (int v = 0; v < 3; ++v) {
                cr_assert_eq(sol_oct_encode(&o[v], dir[v], code), SOL_OK);
                cr_assert_eq(sol_oct_decode(&o[v], code, back), SOL_OK);
                double e = sol_angle3(dir[v], back) * DEG;
                sum[v] += e;
                worst[v] = e > worst[v] ? e : worst[v];
            }
        }
        double mean = sum[0] / N, mean_p = sum[1] / N, mean_u = sum[2] / N;
        cr_assert_float_eq(mean, 0.0209 * scale, 0.04 * 0.0209 * scale, "bits %d mean %g", bits, mean);
        cr_assert_leq(worst[0], 0.0600 * scale, "bits %d max %g", bits, worst[0]);
        cr_assert_leq(worst[1], 0.0410 * scale, "bits %d precise max %g", bits, worst[1]);
        cr_assert_lt(mean_p, mean);
        if (bits <= 13)
            cr_assert_float_eq(mean_u, tyler_mean[bits - 8], 0.02 * tyler_mean[bits - 8], "bits %d UNORM cube mean %g",
                               bits, mean_u);
    }
}

/* The appendix's search as a plain scalar loop (double, and float statement by statement as the
 * HLSL), keeping the first minimum with `if (err < best_err)`: the reference the vectorized,
 * multi-versioned searches (2/4/8 lanes, min reduction then first index) must equal bit for bit. */
static uint32_t ref_best_fit_double(const double v[3])
{
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))), d[3] = {v[0] / m, v[1] / m, v[2] / m};
    double best_err = INFINITY;
    uint32_t best = 0;
    for (int s = 3; s <= 255; s += 2) {
        double t = (double)s / 255.0, dev = 0.0;
        uint32_t c[3];
        for (int i = 0; i < 3; ++i) {
            double p = d[i] * t;
            c[i] = (uint32_t)(int32_t)((p * 0.5 + 0.5) * 255.0 + 0.5);
            double e = fabs((double)c[i] / 255.0 * 2.0 - 1.0 - p);
            dev = e > dev ? e : dev;
        }
        if (dev / t < best_err) {
            best_err = dev / t;
            best = c[0] | (c[1] << 8) | (c[2] << 16);
        }
    }
    return best;
}

static uint32_t ref_best_fit_float(const double v[3])
{
    float n[3] = {(float)v[0], (float)v[1], (float)v[2]};
    float m = fmaxf(fabsf(n[0]), fmaxf(fabsf(n[1]), fabsf(n[2])));
    for (int i = 0; i < 3; ++i)
        n[i] /= m;
    float best_err = 100000.0f;
    uint32_t best = 0;
    for (int k = 0; k < 127; ++k) {
        float t = (1.5f + (float)k) / 127.5f, dev = 0.0f;
        uint32_t c[3];
        for (int i = 0; i < 3; ++i) {
            float p = n[i] * t;
            c[i] = (uint32_t)(int32_t)((p * .5f + .5f) * 255.f + .5f);
            float e = fabsf((float)c[i] / 255.f * 2.f - 1.f - p);
            dev = e > dev ? e : dev;
        }
        if (dev / t < best_err) {
            best_err = dev / t;
            best = c[0] | (c[1] << 8) | (c[2] << 16);
        }
    }
    return best;
}

/* D5/D6: the searches equal the scalar scan on random directions, every cell centre of four slices
 * (ties between probes on a centre's ray are the common case there), axes, diagonals and
 * near-axis vectors, unnormalised as the appendix passes them. */
Test(normals, d5_best_fit_search_equals_the_scalar_scan)
{
    uint64_t state = 77;
    double t;
    for (int i = 0; i < 200000; ++i) {
        double n[3];
        sol_sphere_uniform(sol_rng_uniform(&state, 0, 1), sol_rng_uniform(&state, 0, 1), n);
        cr_assert_eq(sol_normals_encode_best_fit(n, &t), ref_best_fit_double(n), "(%a, %a, %a)", n[0], n[1], n[2]);
        cr_assert_eq(sol_normals_encode_best_fit_float(n), ref_best_fit_float(n), "(%a, %a, %a)", n[0], n[1], n[2]);
    }
    static const uint32_t slices[4] = {0, 127, 200, 255};
    for (int r = 0; r < 4; ++r)
        for (uint32_t g = 0; g < 256; ++g)
            for (uint32_t b = 0; b < 256; ++b) {
                double c[3] = {sol_dequantize255(slices[r]), sol_dequantize255(g), sol_dequantize255(b)};
                cr_assert_eq(sol_normals_encode_best_fit(c, &t), ref_best_fit_double(c));
                cr_assert_eq(sol_normals_encode_best_fit_float(c), ref_best_fit_float(c));
            }
    static const double edge[][3] = {{1, 0, 0},   {0, -1, 0},         {0, 0, 1},     {1, 1, 1},
                                     {-1, 1, -1}, {1, 1e-9, 0},       {1e-30, 0, 1e-30}, {0.5, -0.5, 1e-7},
                                     {3, 4, 0},   {1, 0x1p-30, -0x1p-30}};
    for (size_t i = 0; i < sizeof edge / sizeof edge[0]; ++i) {
        cr_assert_eq(sol_normals_encode_best_fit(edge[i], &t), ref_best_fit_double(edge[i]), "edge %zu", i);
        cr_assert_eq(sol_normals_encode_best_fit_float(edge[i]), ref_best_fit_float(edge[i]), "edge %zu", i);
    }
}
