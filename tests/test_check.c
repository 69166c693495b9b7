/* test_check.c - the check module (src/check) and the `sol check` program: reports, tie rules,
 * bounds, the CSV/.cube/DDS readers, and the engine fixture (tests/fixtures/engine_fixture.c)
 * whose planted bugs `sol check` must each flag with exit 1 while the correct engine exits 0. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sol_check.h"
#include "sol_core.h"
#include "sol_hdr.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"
#include "sol_textures.h"

#ifndef SOL_TEST_BUILD_DIR
#define SOL_TEST_BUILD_DIR "build"
#endif

/* ---- version ---- */

Test(check_version, macros_match_the_library)
{
    char s[32];
    snprintf(s, sizeof s, "%d.%d.%d", SOL_VERSION_MAJOR, SOL_VERSION_MINOR, SOL_VERSION_PATCH);
    cr_assert_str_eq(s, SOL_VERSION_STRING);
    cr_assert_str_eq(sol_version(), SOL_VERSION_STRING);
}

/* ---- normals ---- */

static size_t sample_dirs(double (**out)[3], size_t spread)
{
    size_t ne;
    const double(*e)[3] = sol_check_edge_normals(&ne);
    double(*d)[3] = malloc((ne + spread) * sizeof *d);
    cr_assert_not_null(d);
    memcpy(d, e, ne * sizeof *d);
    for (size_t i = 0; i < spread; ++i) {
        double u, v;
        sol_r2_point(i, &u, &v);
        sol_sphere_uniform(u, v, d[ne + i]);
    }
    *out = d;
    return ne + spread;
}

Test(check_normals, sol_passes_itself_within_each_documented_bound)
{
    double(*d)[3];
    size_t n = sample_dirs(&d, 1u << 13);
    uint32_t *c = malloc(n * sizeof *c);
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m) {
        for (size_t i = 0; i < n; ++i)
            cr_assert_eq(sol_normal_encode((sol_normal_method)m, d[i], &c[i]), SOL_OK);
        sol_check_report r;
        cr_assert_eq(sol_check_normals((sol_normal_method)m, (const double(*)[3])d, c, n, NULL, &r), SOL_OK);
        cr_assert(r.passed && r.mismatches == 0 && r.count == n);
        /* the bound is sol's own largest angle (pinned: measured over 2^20 + edges, here a subset) */
        cr_assert(r.max <= sol_check_normal_bound_deg((sol_normal_method)m), "%s: %g", sol_normal_method_name(m),
                  r.max);
        cr_assert_str_eq(r.unit, "deg");
    }
    cr_assert_eq(sol_check_normal_bound_deg(SOL_NORMAL_METHOD_COUNT), 0.0);
    free(c);
    free(d);
}

Test(check_normals, edge_set_has_the_fold_cases)
{
    size_t ne;
    const double(*e)[3] = sol_check_edge_normals(&ne);
    cr_assert(ne >= 40);
    int neg_z_zero_x = 0, minus_zero = 0;
    for (size_t i = 0; i < ne; ++i) {
        neg_z_zero_x += e[i][2] < 0 && e[i][0] == 0;
        minus_zero += signbit(e[i][0]) && e[i][0] == 0;
    }
    cr_assert(neg_z_zero_x >= 3 && minus_zero >= 2);
}

Test(check_normals, tie_rule_accepts_a_neighbour_code_within_the_bound_only)
{
    const double dir[1][3] = {{0.3, -0.2, 0.9}};
    uint32_t ref;
    cr_assert_eq(sol_normal_encode(SOL_NORMAL_OCTAHEDRAL_12, dir[0], &ref), SOL_OK);
    double ang_best = 1e9;
    uint32_t best = ref;
    for (int dx = -1; dx <= 1; ++dx) /* the best neighbour other than sol's own code */
        for (int dy = -1; dy <= 1; ++dy) {
            if (!dx && !dy)
                continue;
            uint32_t c = (uint32_t)((int)(ref & 4095u) + dx) | (uint32_t)((int)(ref >> 12) + dy) << 12;
            double n[3];
            sol_normal_decode(SOL_NORMAL_OCTAHEDRAL_12, c, n);
            double a = sol_angle3(dir[0], n) * 180 / M_PI;
            if (a < ang_best) {
                ang_best = a;
                best = c;
            }
        }
    sol_check_report r;
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, dir, &best, 1, NULL, &r), SOL_OK);
    cr_assert_eq(r.mismatches, 1);
    cr_assert_eq(r.passed, ang_best <= SOL_CHECK_BOUND_OCTAHEDRAL_12_DEG);
    sol_check_normal_options exact = {.exact = 1};
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, dir, &best, 1, &exact, &r), SOL_OK);
    cr_assert(!r.passed);
    uint32_t far = ref + 5;
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, dir, &far, 1, NULL, &r), SOL_OK);
    cr_assert(!r.passed && r.failures == 1);
    uint32_t invalid = 1u << 24;
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, dir, &invalid, 1, NULL, &r), SOL_OK);
    cr_assert(!r.passed && isinf(r.max));
}

Test(check_normals, errors_leave_the_report_untouched)
{
    const double bad[2][3] = {{0, 0, 1}, {0, 0, 0}}, nan[1][3] = {{NAN, 0, 1}};
    uint32_t c[2] = {0, 0};
    sol_check_report r;
    memset(&r, 0x5a, sizeof r);
    sol_check_report copy = r;
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, bad, c, 2, NULL, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, nan, c, 1, NULL, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, bad, c, 0, NULL, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_normals(SOL_NORMAL_METHOD_COUNT, bad, c, 1, NULL, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, NULL, c, 1, NULL, &r), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, bad, c, 1, NULL, NULL), SOL_ERR_NULL_ARG);
    cr_assert(!memcmp(&r, &copy, sizeof r));
}

Test(check_report, worst_items_rank_failures_first_then_error)
{
    /* sRGB: code errors 1 (tie, passes) and 1, 2, 3 (failures) */
    double lin[5] = {0.1635765, 0.5, 0.5, 0.5, 0.25};
    uint8_t codes[5] = {112, 189, 190, 191, 137};
    sol_check_report r;
    cr_assert_eq(sol_check_srgb(lin, codes, 5, &r), SOL_OK);
    cr_assert_eq(r.worst_count, 5);
    cr_assert_eq(r.failures, 3);
    cr_assert_eq(r.worst[0].error, 3.0);
    cr_assert_eq(r.worst[1].error, 2.0);
    cr_assert_eq(r.worst[2].error, 1.0);
    cr_assert_eq(r.worst[2].index, 1); /* the failing 1, before the tie at index 0 */
    cr_assert_eq(r.worst[3].index, 0);
    cr_assert_eq(r.worst[4].error, 0.0);
}

/* ---- sRGB tie rule ---- */

Test(check_srgb, a_float_encoder_differs_at_11_of_2000001_inputs_and_passes_by_the_tie_rule)
{
    const size_t n = 2000001;
    double *lin = malloc(n * sizeof *lin);
    uint8_t *codes = malloc(n);
    for (size_t i = 0; i < n; ++i) {
        lin[i] = (double)i / 2000000.0;
        float x = (float)lin[i];
        float e = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
        codes[i] = (uint8_t)(int)(e * 255.0f + 0.5f);
    }
    sol_check_report r;
    cr_assert_eq(sol_check_srgb(lin, codes, n, &r), SOL_OK);
    cr_assert_eq(r.mismatches, 11);
    cr_assert(r.passed);
    for (int i = 0; i < r.worst_count && r.worst[i].error > 0; ++i)
        cr_assert(fabs(r.worst[i].input[1] - floor(r.worst[i].input[1]) - 0.5) < 1e-5); /* all near ties */
    /* the threshold bug: 0.04045 in the encoder */
    for (size_t i = 0; i < n; ++i) {
        float x = (float)lin[i];
        float e = x <= 0.04045f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
        codes[i] = (uint8_t)(int)(e * 255.0f + 0.5f);
    }
    cr_assert_eq(sol_check_srgb(lin, codes, n, &r), SOL_OK);
    cr_assert(!r.passed);
    free(lin);
    free(codes);
}

Test(check_srgb, nan_and_out_of_range_inputs_follow_sol_clamping)
{
    double lin[4] = {NAN, -1.0, 2.0, -0.0};
    uint8_t ok[4] = {0, 0, 255, 0}, bad[4] = {1, 0, 255, 0};
    sol_check_report r;
    cr_assert_eq(sol_check_srgb(lin, ok, 4, &r), SOL_OK);
    cr_assert(r.passed && r.mismatches == 0);
    cr_assert_eq(sol_check_srgb(lin, bad, 4, &r), SOL_OK);
    cr_assert(!r.passed);
    cr_assert_eq(sol_check_srgb(lin, ok, 0, &r), SOL_ERR_INVALID_ARG);
}

/* ---- pack ---- */

Test(check_pack, reference_bits_are_the_gpu_encodings)
{
    float one[3] = {1, 1, 1}, half = 1.0f;
    uint32_t b;
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_FP16, &half, 0, &b), SOL_OK);
    cr_assert_eq(b, 0x3c00u);
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_R11G11B10F, one, 0, &b), SOL_OK);
    cr_assert_eq(b, 0x3c0u | 0x3c0u << 11 | 0x1e0u << 22);
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_RGBM, one, 0, &b), SOL_OK); /* range 6 */
    cr_assert_eq(b >> 24, 43u);                                                      /* ceil(255/6) */
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_RGB10, one, 0, &b), SOL_OK);
    cr_assert_eq(b & 1023u, 512u); /* round(1023 / 2) */
    float d = 0.5f;
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_DEPTH_RG8, &d, 0, &b), SOL_OK);
    cr_assert_eq(b, 127u | 128u << 8);
    cr_assert_eq(sol_check_pack_reference(SOL_CHECK_PACK_COUNT, &d, 0, &b), SOL_ERR_INVALID_ARG);
    cr_assert_str_eq(sol_check_pack_name(SOL_CHECK_PACK_R11G11B10F), "r11g11b10f");
    cr_assert_null(sol_check_pack_name(SOL_CHECK_PACK_COUNT));
    cr_assert_eq(sol_check_pack_inputs(SOL_CHECK_PACK_COUNT), 0);
}

Test(check_pack, edge_floats_pass_exactly_and_any_nan_pattern_is_a_nan)
{
    size_t n;
    const float *e = sol_check_edge_floats(&n);
    cr_assert(n >= 40);
    uint32_t *bits = malloc(n * sizeof *bits);
    for (int f = 0; f < SOL_CHECK_PACK_COUNT; ++f) {
        int k = sol_check_pack_inputs((sol_check_pack_format)f);
        float *v = malloc(n * (size_t)k * sizeof *v);
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < k; ++c)
                v[i * (size_t)k + (size_t)c] = e[(i + (size_t)c) % n];
            cr_assert_eq(sol_check_pack_reference((sol_check_pack_format)f, v + i * (size_t)k, 0, &bits[i]), SOL_OK);
        }
        sol_check_report r;
        cr_assert_eq(sol_check_pack((sol_check_pack_format)f, v, bits, n, 0, &r), SOL_OK);
        cr_assert(r.passed && r.mismatches == 0, "%s", sol_check_pack_name(f));
        free(v);
    }
    float nan = NAN;
    uint32_t other_nan = 0x7c01u;
    sol_check_report r;
    cr_assert_eq(sol_check_pack(SOL_CHECK_PACK_FP16, &nan, &other_nan, 1, 0, &r), SOL_OK);
    cr_assert(r.passed);
    float x = 1.0f + 0x1.8p-11f; /* a fp16 tie: even rounds up to 1 + 2^-9 */
    uint32_t trunc = 0x3c00u;
    cr_assert_eq(sol_check_pack(SOL_CHECK_PACK_FP16, &x, &trunc, 1, 0, &r), SOL_OK);
    cr_assert(!r.passed && r.failures == 1);
    cr_assert_eq(sol_check_pack(SOL_CHECK_PACK_RGBM, e, bits, 1, -1.0, &r), SOL_ERR_INVALID_ARG);
    free(bits);
}

/* ---- tone map ---- */

Test(check_tonemap, exact_samples_pass_and_a_constant_off_fails)
{
    double x[64], y[64];
    for (int i = 0; i < 64; ++i) {
        x[i] = exp2(-12 + i * 0.25);
        y[i] = sol_tonemap_apply(SOL_TONEMAP_FILMIC_HBD, x[i]);
    }
    sol_check_report r;
    cr_assert_eq(sol_check_tonemap(SOL_TONEMAP_FILMIC_HBD, x, y, 64, &r), SOL_OK);
    cr_assert(r.passed && r.max == 0);
    cr_assert_eq(r.tolerance, SOL_CHECK_TOL_TONEMAP);
    cr_assert(fabs(SOL_CHECK_TOL_TONEMAP - 0.5 / 255 / 12.92) < 1e-5); /* the documented derivation */
    double ec, sc;
    cr_assert_eq(sol_check_tonemap_bound(SOL_TONEMAP_FILMIC_HBD, x, y, 64, 0, &ec, &sc), SOL_OK);
    cr_assert(ec >= sc && ec <= sc * 1.2);
    double mev, xev;
    size_t used;
    cr_assert_eq(sol_check_tonemap_inverse(SOL_TONEMAP_FILMIC_HBD, x, y, 64, &mev, &xev, &used), SOL_OK);
    cr_assert(used > 30 && xev < 1e-6, "%zu %g", used, xev);
    double twice[64];
    for (int i = 0; i < 64; ++i) /* the engine exposes one stop brighter */
        twice[i] = sol_tonemap_apply(SOL_TONEMAP_FILMIC_HBD, 2 * x[i]);
    cr_assert_eq(sol_check_tonemap_inverse(SOL_TONEMAP_FILMIC_HBD, x, twice, 64, &mev, &xev, &used), SOL_OK);
    cr_assert(fabs(mev - 1) < 1e-3, "%g", mev);
    cr_assert_eq(sol_check_tonemap_inverse(SOL_TONEMAP_FILMIC_HBD, x, y, 0, &mev, &xev, &used), SOL_ERR_INVALID_ARG);
    y[10] = NAN;
    cr_assert_eq(sol_check_tonemap(SOL_TONEMAP_FILMIC_HBD, x, y, 64, &r), SOL_OK);
    cr_assert(!r.passed && r.failures == 1);
    for (int i = 0; i < 64; ++i) {
        double xp = fmax(0, x[i] - 0.004), g = xp * (6.2 * xp + 0.5) / (xp * (6.2 * xp + 1.8) + 0.06);
        y[i] = pow(g, 2.2);
    }
    cr_assert_eq(sol_check_tonemap(SOL_TONEMAP_FILMIC_HBD, x, y, 64, &r), SOL_OK);
    cr_assert(!r.passed);
    cr_assert_eq(sol_check_tonemap(SOL_TONEMAP_COUNT, x, y, 64, &r), SOL_ERR_INVALID_ARG);
    double zero[1] = {0};
    cr_assert_eq(sol_check_tonemap_bound(SOL_TONEMAP_FILMIC_HBD, zero, zero, 1, 0, &ec, &sc), SOL_ERR_OUT_OF_RANGE);
}

/* ---- LUT ---- */

static void identity(const double in[3], double out[3], void *ctx)
{
    (void)ctx;
    memcpy(out, in, 3 * sizeof *in);
}

Test(check_lut, identity_table_matches_the_identity_look)
{
    sol_lut3d lut;
    cr_assert_eq(sol_lut3d_bake(9, identity, NULL, &lut), SOL_OK);
    sol_grade none = {0}, sat = {.saturation = 0.5};
    sol_check_report r;
    cr_assert_eq(sol_check_lut(&lut, NULL, NULL, &none, &r), SOL_OK);
    cr_assert(r.passed && r.count == 729 && r.max < 1e-4);
    cr_assert_eq(sol_check_lut(&lut, NULL, NULL, &sat, &r), SOL_OK);
    cr_assert(!r.passed);
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0, 1};
    cr_assert_eq(sol_check_lut(&lut, lo, hi, &none, &r), SOL_ERR_INVALID_ARG);
    lut.data[0] = NAN;
    cr_assert_eq(sol_check_lut(&lut, NULL, NULL, &none, &r), SOL_OK);
    cr_assert(!r.passed && isinf(r.max));
    sol_lut3d_free(&lut);
}

/* ---- readers ---- */

Test(check_table, header_comments_hex_and_bad_rows)
{
    const char *ok = "x,y,code\n# comment\n1, 2.5, 0x1f\n\n-3 4e2 0x1.8p+1  # trailing\nnan,inf,7\n";
    sol_check_table t;
    size_t line = 0;
    cr_assert_eq(sol_check_table_parse(ok, strlen(ok), NULL, &t, &line), SOL_OK);
    cr_assert_eq(t.rows, 3);
    cr_assert_eq(t.cols, 3);
    cr_assert_eq(t.values[2], 31.0);
    cr_assert_eq(t.values[3], -3.0);
    cr_assert_eq(t.values[5], 3.0);
    cr_assert(isnan(t.values[6]) && isinf(t.values[7]));
    sol_check_table_free(&t);
    sol_check_table_free(&t); /* harmless twice */
    const char *bad_row = "1,2\n3,4\n5,x\n";
    cr_assert_eq(sol_check_table_parse(bad_row, strlen(bad_row), NULL, &t, &line), SOL_ERR_FORMAT);
    cr_assert_eq(line, 3);
    const char *short_row = "1,2\n3\n";
    cr_assert_eq(sol_check_table_parse(short_row, strlen(short_row), NULL, &t, &line), SOL_ERR_FORMAT);
    cr_assert_eq(line, 2);
    const char *two_headers = "a,b\nc,d\n1,2\n";
    cr_assert_eq(sol_check_table_parse(two_headers, strlen(two_headers), NULL, &t, &line), SOL_ERR_FORMAT);
    cr_assert_eq(line, 2);
    cr_assert_eq(sol_check_table_parse("", 0, NULL, &t, &line), SOL_ERR_FORMAT);
    cr_assert_eq(sol_check_table_parse("1,,2\n", 5, NULL, &t, &line), SOL_ERR_FORMAT);
    sol_read_limits tiny = {.max_pixels = 3};
    cr_assert_eq(sol_check_table_parse(bad_row, 8, &tiny, &t, &line), SOL_ERR_LIMIT);
    cr_assert_eq(sol_check_table_parse(NULL, 0, NULL, &t, &line), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_check_table_read("/nonexistent/x.csv", NULL, &t, &line), SOL_ERR_IO);
}

static char *cube_text(int size, int entries, const char *extra)
{
    size_t cap = 256 + (size_t)entries * 32;
    char *s = malloc(cap);
    int n = snprintf(s, cap, "# made by a test\nTITLE \"t\"\n%sLUT_3D_SIZE %d\n\n", extra, size);
    for (int i = 0; i < entries; ++i)
        n += snprintf(s + n, cap - (size_t)n, "%d %g 0.5\n", i % size, (double)i / entries);
    return s;
}

Test(check_cube, reads_size_domain_title_and_refuses_wrong_counts)
{
    sol_lut3d lut;
    sol_cube_info info;
    size_t line;
    const char *why;
    char *s = cube_text(2, 8, "DOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 2 1\n");
    cr_assert_eq(sol_cube_parse(s, strlen(s), NULL, &lut, &info, &line, &why), SOL_OK);
    cr_assert_eq(lut.size, 2);
    cr_assert_str_eq(info.title, "t");
    cr_assert_eq(info.domain_max[1], 2.0);
    cr_assert_eq(lut.data[3], 1.0f); /* entry 1, red */
    sol_lut3d_free(&lut);
    free(s);
    s = cube_text(2, 7, "");
    cr_assert_eq(sol_cube_parse(s, strlen(s), NULL, &lut, &info, &line, &why), SOL_ERR_FORMAT);
    cr_assert(strstr(why, "entry count"));
    free(s);
    s = cube_text(2, 9, "");
    cr_assert_eq(sol_cube_parse(s, strlen(s), NULL, &lut, &info, &line, &why), SOL_ERR_FORMAT);
    cr_assert(strstr(why, "entry count") && line == 13);
    free(s);
    s = cube_text(2, 8, "DOMAIN_MIN 1 0 0\n");
    cr_assert_eq(sol_cube_parse(s, strlen(s), NULL, &lut, &info, &line, &why), SOL_ERR_FORMAT);
    free(s);
    const char *one_d = "LUT_1D_SIZE 4\n0 0 0\n";
    cr_assert_eq(sol_cube_parse(one_d, strlen(one_d), NULL, &lut, NULL, &line, &why), SOL_ERR_UNSUPPORTED);
    const char *big = "LUT_3D_SIZE 256\n";
    sol_read_limits tiny = {.max_pixels = 1000};
    cr_assert_eq(sol_cube_parse(big, strlen(big), &tiny, &lut, NULL, &line, &why), SOL_ERR_LIMIT);
    const char *huge = "LUT_3D_SIZE 100000\n";
    cr_assert_eq(sol_cube_parse(huge, strlen(huge), NULL, &lut, NULL, &line, &why), SOL_ERR_FORMAT);
    const char *junk = "LUT_3D_SIZE 2\n0 0 zero\n";
    cr_assert_eq(sol_cube_parse(junk, strlen(junk), NULL, &lut, NULL, &line, &why), SOL_ERR_FORMAT);
    cr_assert_eq(line, 2);
    const char *early = "0 0 0\nLUT_3D_SIZE 2\n";
    cr_assert_eq(sol_cube_parse(early, strlen(early), NULL, &lut, NULL, &line, &why), SOL_ERR_FORMAT);
    cr_assert_eq(sol_cube_parse("", 0, NULL, &lut, NULL, NULL, NULL), SOL_ERR_FORMAT);
}

Test(check_cube, write_then_read_round_trips_floats)
{
    char dir[] = "/tmp/sol_check_XXXXXX", path[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/a.cube", dir);
    sol_lut3d lut, back;
    cr_assert_eq(sol_lut3d_bake(5, identity, NULL, &lut), SOL_OK);
    lut.data[7] = 0.123456789f;
    cr_assert_eq(sol_cube_write(path, &lut, "x"), SOL_OK);
    cr_assert_eq(sol_cube_read(path, NULL, &back, NULL, NULL, NULL), SOL_OK);
    cr_assert_eq(back.size, 5);
    cr_assert(!memcmp(back.data, lut.data, 125 * 3 * sizeof(float)));
    sol_lut3d_free(&lut);
    sol_lut3d_free(&back);
    remove(path);
    rmdir(dir);
}

static size_t dds_bytes(uint8_t **out, const char *fourcc, int w, int h, size_t payload)
{
    char dir[] = "/tmp/sol_check_XXXXXX", path[64];
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/a.dds", dir);
    size_t blocks = (size_t)(w / 4) * (size_t)(h / 4) * 16;
    uint8_t *b = calloc(blocks, 1);
    cr_assert_eq(sol_dds_write_bc(path, b, w, h, 2), SOL_OK);
    uint8_t *data;
    size_t size;
    cr_assert_eq(sol_file_read_all(path, 0, &data, &size), SOL_OK);
    cr_assert_eq(size, 128 + blocks);
    memcpy(data + 84, fourcc, 4);
    remove(path);
    rmdir(dir);
    free(b);
    *out = data;
    return 128 + (payload < blocks ? payload : blocks);
}

Test(check_dds, reads_what_sol_writes_and_names_each_problem)
{
    uint8_t *d;
    size_t n = dds_bytes(&d, "ATI2", 8, 4, 1000);
    sol_dds dds;
    const char *why = NULL;
    cr_assert_eq(sol_dds_parse(d, n, NULL, &dds, &why), SOL_OK);
    cr_assert_eq(dds.format, SOL_DDS_BC5);
    cr_assert_eq(dds.width, 8);
    cr_assert_eq(dds.size, 32);
    sol_dds_free(&dds);
    sol_dds_free(&dds);
    cr_assert_eq(sol_dds_parse(d, n - 1, NULL, &dds, &why), SOL_ERR_FORMAT); /* truncated */
    cr_assert(strstr(why, "truncated"));
    cr_assert_eq(sol_dds_parse(d, 100, NULL, &dds, &why), SOL_ERR_FORMAT);
    memcpy(d + 84, "DXT5", 4);
    cr_assert_eq(sol_dds_parse(d, n, NULL, &dds, &why), SOL_ERR_UNSUPPORTED);
    cr_assert(strstr(why, "FourCC"));
    memcpy(d + 84, "DXT1", 4);
    cr_assert_eq(sol_dds_parse(d, n, NULL, &dds, &why), SOL_OK);
    cr_assert(dds.format == SOL_DDS_BC1 && dds.size == 16);
    sol_dds_free(&dds);
    sol_read_limits tiny = {.max_pixels = 16};
    cr_assert_eq(sol_dds_parse(d, n, &tiny, &dds, &why), SOL_ERR_LIMIT);
    d[16] = 0xff; /* width 0x...ff: claims far more blocks than present */
    d[17] = 0xff;
    d[18] = 0xff;
    cr_assert_neq(sol_dds_parse(d, n, NULL, &dds, &why), SOL_OK);
    d[0] = 'X';
    cr_assert_eq(sol_dds_parse(d, n, NULL, &dds, &why), SOL_ERR_FORMAT);
    cr_assert(strstr(why, "magic"));
    free(d);
    /* DX10 extension: BC5_UNORM = 83 */
    uint8_t *x = calloc(148 + 16, 1);
    n = dds_bytes(&d, "DX10", 4, 4, 16);
    memcpy(x, d, 128);
    x[128] = 83;
    x[132] = 3;
    x[140] = 1;
    cr_assert_eq(sol_dds_parse(x, 148 + 16, NULL, &dds, &why), SOL_OK);
    cr_assert_eq(dds.format, SOL_DDS_BC5);
    sol_dds_free(&dds);
    x[128] = 98; /* BC7 */
    cr_assert_eq(sol_dds_parse(x, 148 + 16, NULL, &dds, &why), SOL_ERR_UNSUPPORTED);
    cr_assert_eq(sol_dds_parse(x, 140, NULL, &dds, &why), SOL_ERR_FORMAT);
    cr_assert_eq(sol_dds_read("/nonexistent.dds", NULL, &dds, &why), SOL_ERR_IO);
    free(x);
    free(d);
}

/* ---- the `sol check` program on the engine fixture ---- */

static char work[64];

static void make_work(void)
{
    snprintf(work, sizeof work, "/tmp/sol_check_cli_XXXXXX");
    cr_assert_not_null(mkdtemp(work));
}

static void clean_work(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", work);
    cr_assert_eq(system(cmd), 0);
}

/* Runs a shell command in the work folder with SOL and ENGINE set; returns its exit status. */
static int run(const char *fmt, ...)
{
    char body[1024], cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(body, sizeof body, fmt, ap);
    va_end(ap);
    char cwd[512];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    snprintf(cmd, sizeof cmd,
             "cd '%s' && SOL='%s/" SOL_TEST_BUILD_DIR "/sol' ENGINE='%s/" SOL_TEST_BUILD_DIR
             "/tests/engine_fixture' && { %s ; } >out.txt 2>err.txt",
             work, cwd, cwd, body);
    int st = system(cmd);
    cr_assert(WIFEXITED(st));
    return WEXITSTATUS(st);
}

static int err_has(const char *needle)
{
    char path[128], buf[4096] = {0};
    snprintf(path, sizeof path, "%s/err.txt", work);
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    return strstr(buf, needle) != NULL;
}

TestSuite(check_cli, .init = make_work, .fini = clean_work);

Test(check_cli, version_help_and_usage_errors)
{
    cr_assert_eq(run("$SOL version | grep -q '^sol " SOL_VERSION_STRING "$'"), 0);
    cr_assert_eq(run("$SOL check help | grep -q 'exit status'"), 0);
    cr_assert_eq(run("$SOL check"), 2);
    cr_assert_eq(run("$SOL check frobnicate"), 2);
    cr_assert(err_has("unknown technique"));
    cr_assert_eq(run("$SOL check normals --method nope --csv x"), 2);
    cr_assert(err_has("unknown normal method"));
    cr_assert_eq(run("$SOL check srgb --csv missing.csv"), 2);
    cr_assert(err_has("missing.csv"));
    cr_assert_eq(run("$SOL check pack --format fp16 --csv x.csv --bogus 1"), 2);
    /* emitted files appear whole or not at all */
    cr_assert_eq(run("$SOL check srgb --emit nodir/x.csv"), 2);
    cr_assert(err_has("cannot write"));
    cr_assert_eq(run("$SOL check srgb --emit s.csv --count 100 && test -s s.csv && ! ls *.tmp 2>/dev/null"), 0);
}

Test(check_cli, normals_octahedral_sign0_bug)
{
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --emit in.csv --count 3000"), 0);
    cr_assert_eq(run("$ENGINE normals in.csv e.csv && $SOL check normals --method octahedral-12 --csv e.csv"), 0);
    cr_assert_eq(run("$ENGINE normals in.csv e.csv && $SOL check normals --method octahedral-12 --csv e.csv --json "
                     "| grep -q '\"passed\": true'"),
                 0);
    cr_assert_eq(run("$ENGINE --bug oct-sign0 normals in.csv e.csv && "
                     "$SOL check normals --method octahedral-12 --csv e.csv"),
                 1);
}

Test(check_cli, normals_gbuffer_dump)
{
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --emit dirs.exr --size 64"), 0);
    cr_assert_eq(run("$ENGINE gbuffer dirs.exr g.png && "
                     "$SOL check normals --method octahedral-12 --directions dirs.exr --gbuffer g.png"),
                 0);
    cr_assert_eq(run("$ENGINE --bug oct-sign0 gbuffer dirs.exr g.png && "
                     "$SOL check normals --method octahedral-12 --directions dirs.exr --gbuffer g.png"),
                 1);
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --directions dirs.exr"), 2);
}

/* The same dump as an EXR of UNORM values code/255 (what an RGBA8 target reads back as). */
static void png_gbuffer_to_exr(const char *png, const char *exr)
{
    char in[128], out[128];
    snprintf(in, sizeof in, "%s/%s", work, png);
    snprintf(out, sizeof out, "%s/%s", work, exr);
    sol_image img = {0};
    cr_assert_eq(sol_png_read(in, &img, NULL), SOL_OK);
    cr_assert_eq(sol_exr_write(out, &img, 1), SOL_OK); /* half: k/255 within 0.07 codes */
    sol_image_free(&img);
}

Test(check_cli, normals_gbuffer_dump_as_exr)
{
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --emit dirs.exr --size 64 && "
                     "$ENGINE gbuffer dirs.exr g.png && $ENGINE --bug oct-sign0 gbuffer dirs.exr bug.png"),
                 0);
    png_gbuffer_to_exr("g.png", "g.exr");
    png_gbuffer_to_exr("bug.png", "bug.exr");
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --directions dirs.exr --gbuffer g.exr"), 0);
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --directions dirs.exr --gbuffer bug.exr"), 1);
    /* directions are not codes: refused, naming the file */
    cr_assert_eq(run("$SOL check normals --method octahedral-12 --directions dirs.exr --gbuffer dirs.exr"), 2);
    cr_assert(err_has("is not an 8-bit UNORM code"));
}

Test(check_cli, pack_truncation_bugs)
{
    const char *fmts[2] = {"r11g11b10f", "fp16"}, *bugs[2] = {"r11-trunc", "fp16-trunc"};
    for (int i = 0; i < 2; ++i) {
        cr_assert_eq(run("$SOL check pack --format %s --emit in.csv --count 2000", fmts[i]), 0);
        cr_assert_eq(run("$ENGINE pack %s in.csv e.csv && $SOL check pack --format %s --csv e.csv", fmts[i], fmts[i]),
                     0);
        cr_assert_eq(run("$ENGINE --bug %s pack %s in.csv e.csv && $SOL check pack --format %s --csv e.csv", bugs[i],
                         fmts[i], fmts[i]),
                     1);
    }
}

Test(check_cli, srgb_threshold_bug_and_ties)
{
    cr_assert_eq(run("$SOL check srgb --emit in.csv --count 200000"), 0);
    cr_assert_eq(run("$ENGINE srgb in.csv e.csv && $SOL check srgb --csv e.csv"), 0);
    cr_assert_eq(run("$ENGINE --bug srgb-threshold srgb in.csv e.csv && $SOL check srgb --csv e.csv"), 1);
}

Test(check_cli, tonemap_filmic_constant_bug)
{
    cr_assert_eq(run("$SOL check tonemap --op filmic-hbd --emit in.csv"), 0);
    cr_assert_eq(run("$ENGINE tonemap in.csv e.csv && $SOL check tonemap --op filmic-hbd --csv e.csv"), 0);
    cr_assert_eq(run("$ENGINE --bug filmic-constant tonemap in.csv e.csv && "
                     "$SOL check tonemap --op filmic-hbd --csv e.csv"),
                 1);
    cr_assert_eq(run("$ENGINE tonemap in.csv e.csv && $SOL check tonemap --op reinhard --csv e.csv"), 1);
}

Test(check_cli, bc5_decoder_rounding_and_encoder_bugs)
{
    cr_assert_eq(run("$ENGINE bc5 32 . && $SOL check bc5 --dds bc5.dds --decoded bc5_decoded.png"), 0);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr"), 0);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --decoded bc5_decoded.png --precision 8"), 1);
    cr_assert_eq(run("$ENGINE --bug bc5-round bc5 32 . && $SOL check bc5 --dds bc5.dds --decoded bc5_decoded.png"), 1);
    cr_assert_eq(run("$ENGINE --bug bc5-encoder bc5 32 . && $SOL check bc5 --dds bc5.dds --source source.exr"), 1);
}

Test(check_cli, bc5_encoder_reference_common_or_optimal)
{
    cr_assert_eq(run("$ENGINE bc5 32 . && $SOL check bc5 --dds bc5.dds --source source.exr --reference optimal"), 0);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr --reference optimal --json | "
                     "grep -q '\"reference\": \"optimal\".*\"sol_optimal_mean\".*\"distance\".*\"bounded_blocks\": 0'"),
                 0);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr --reference common --json | "
                     "grep -q '\"reference\": \"common\".*\"sol_common_mean\"'"),
                 0);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr --reference optimal | "
                     "grep -q \"sol's optimal encoder.*mean\""),
                 0);
    cr_assert_eq(run("$ENGINE --bug bc5-encoder bc5 32 . && "
                     "$SOL check bc5 --dds bc5.dds --source source.exr --reference optimal"),
                 1);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr --reference best"), 2);
    cr_assert(err_has("--reference must be common or optimal, not 'best'"));
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --source source.exr --reference"), 2);
    cr_assert_eq(run("$SOL check bc5 --dds bc5.dds --decoded bc5_decoded.png --reference optimal"), 2);
}

Test(check_cli, bc1_decoder_rounding_bug)
{
    cr_assert_eq(run("$ENGINE bc1 32 . && $SOL check bc1 --dds bc1.dds --decoded bc1_decoded.png"), 0);
    cr_assert_eq(run("$ENGINE --bug bc1-round bc1 32 . && $SOL check bc1 --dds bc1.dds --decoded bc1_decoded.png"), 1);
    cr_assert_eq(run("$SOL check bc1 --dds bc1.dds --decoded bc1_decoded.png --tolerance 1"), 0);
    cr_assert_eq(run("$ENGINE bc1 32 . && $SOL check bc1 --dds bc1.dds --source bc1_source.png"), 0);
    cr_assert_eq(run("$ENGINE --bug bc1-encoder bc1 32 . && $SOL check bc1 --dds bc1.dds --source bc1_source.png"), 1);
}

Test(check_cli, lut_graded_in_linear_bug)
{
    cr_assert_eq(run("$ENGINE lut 17 e.cube && $SOL check lut --cube e.cube --saturation 0.3 --contrast 0.2"), 0);
    cr_assert_eq(run("$ENGINE --bug lut-linear lut 17 e.cube && "
                     "$SOL check lut --cube e.cube --saturation 0.3 --contrast 0.2"),
                 1);
    cr_assert_eq(run("$SOL check lut --emit ref.cube --size 9 --saturation 0.3 && "
                     "$SOL check lut --cube ref.cube --saturation 0.3"),
                 0);
}

Test(check_cli, malformed_inputs_exit_2_naming_the_problem)
{
    cr_assert_eq(run("$ENGINE bc5 16 . && head -c 200 bc5.dds > short.dds && "
                     "$SOL check bc5 --dds short.dds --decoded bc5_decoded.png"),
                 2);
    cr_assert(err_has("truncated DDS"));
    cr_assert_eq(run("$ENGINE bc5 16 . && cp bc5.dds odd.dds && printf 'DXT5' | dd of=odd.dds bs=1 seek=84 "
                     "conv=notrunc 2>/dev/null && $SOL check bc5 --dds odd.dds --decoded bc5_decoded.png"),
                 2);
    cr_assert(err_has("FourCC"));
    cr_assert_eq(run("$ENGINE bc5 16 . && $SOL check bc1 --dds bc5.dds --decoded bc5_decoded.png"), 2);
    cr_assert(err_has("not a BC1"));
    cr_assert_eq(run("printf '0.5,188\\n0.25,137\\n0.1,oops\\n' > bad.csv && $SOL check srgb --csv bad.csv"), 2);
    cr_assert(err_has("line 3: bad row"));
    cr_assert_eq(run("printf '0.5,188,1\\n' > wide.csv && $SOL check srgb --csv wide.csv"), 2);
    cr_assert(err_has("3 columns"));
    cr_assert_eq(run("printf 'LUT_3D_SIZE 2\\n0 0 0\\n1 1 1\\n' > few.cube && $SOL check lut --cube few.cube"), 2);
    cr_assert(err_has("wrong entry count"));
    cr_assert_eq(run("printf '0.5,300\\n' > range.csv && $SOL check srgb --csv range.csv"), 2);
    cr_assert(err_has("0..255"));
}

/* ---- block checks at the library level ---- */

Test(check_blocks, decoders_bit_exact_and_argument_errors)
{
    uint8_t blocks[2 * 16];
    uint64_t rng = 3;
    for (int i = 0; i < 32; ++i)
        blocks[i] = (uint8_t)sol_rng_next(&rng);
    /* sol's own BC5 decode at 16 bits, as 16-bit codes */
    uint16_t tex[8 * 4 * 2];
    for (int b = 0; b < 2; ++b) {
        sol_bc5_block blk;
        sol_bc4_unpack(blocks + 16 * b, &blk.x);
        sol_bc4_unpack(blocks + 16 * b + 8, &blk.y);
        double px[8], py[8];
        sol_bc4_palette(blk.x.e0, blk.x.e1, SOL_BC4_INTERP_16BIT, px);
        sol_bc4_palette(blk.y.e0, blk.y.e1, SOL_BC4_INTERP_16BIT, py);
        for (int t = 0; t < 16; ++t) {
            uint16_t *p = tex + 2 * ((t / 4) * 8 + 4 * b + t % 4);
            p[0] = (uint16_t)sol_unorm_encode(px[blk.x.index[t]], 16);
            p[1] = (uint16_t)sol_unorm_encode(py[blk.y.index[t]], 16);
        }
    }
    sol_check_report r;
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, 0, &r), SOL_OK);
    cr_assert(r.passed && r.count == 32 && r.mismatches == 0);
    tex[5] ^= 1;
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, 0, &r), SOL_OK);
    cr_assert(!r.passed && r.failures == 1 && r.max == 1);
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, 1, &r), SOL_OK);
    cr_assert(r.passed && r.mismatches == 1);
    cr_assert_eq(sol_check_bc5_decode(blocks, 6, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, 0, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_PRECISION_COUNT, tex, 2, 16, 0, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 12, 0, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_decode(blocks, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, NAN, &r), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_decode(NULL, 8, 4, SOL_BC4_INTERP_16BIT, tex, 2, 16, 0, &r), SOL_ERR_NULL_ARG);
    /* BC1: sol's decode as 8-bit RGB, then at 16 bits (x 257) */
    uint16_t rgb8[4 * 4 * 3], rgb16[4 * 4 * 3];
    uint8_t rgba[16][4];
    sol_bc1_decode_block(blocks, rgba);
    for (int t = 0; t < 16; ++t)
        for (int c = 0; c < 3; ++c) {
            rgb8[3 * t + c] = rgba[t][c];
            rgb16[3 * t + c] = (uint16_t)(rgba[t][c] * 257);
        }
    cr_assert_eq(sol_check_bc1_decode(blocks, 4, 4, rgb8, 3, 8, 0, &r), SOL_OK);
    cr_assert(r.passed);
    cr_assert_eq(sol_check_bc1_decode(blocks, 4, 4, rgb16, 3, 16, 0, &r), SOL_OK);
    cr_assert(r.passed);
    cr_assert_eq(sol_check_bc1_decode(blocks, 4, 4, rgb8, 2, 8, 0, &r), SOL_ERR_INVALID_ARG);
}

Test(check_blocks, encoders_against_the_source)
{
    sol_image src;
    cr_assert_eq(sol_image_alloc(&src, 8, 8, 3), SOL_OK);
    for (int i = 0; i < 64; ++i) {
        src.data[3 * i] = (float)(0.3 * sin(i * 0.7));
        src.data[3 * i + 1] = (float)(0.2 * cos(i * 0.3));
        src.data[3 * i + 2] = 0.9f;
    }
    uint8_t blocks[64];
    sol_bc5_options o = {0};
    cr_assert_eq(sol_bc5_encode_image(&src, &o, blocks, NULL), SOL_OK);
    sol_check_report r;
    double ref = -1;
    cr_assert_eq(sol_check_bc5_encode(&src, blocks, SOL_BC4_INTERP_16BIT, &r, &ref), SOL_OK);
    cr_assert(r.passed && r.mean == ref && r.count == 64);
    memset(blocks, 0, sizeof blocks); /* every texel decodes to x = y = -1 */
    cr_assert_eq(sol_check_bc5_encode(&src, blocks, SOL_BC4_INTERP_16BIT, &r, NULL), SOL_OK);
    cr_assert(!r.passed);
    src.data[0] = src.data[1] = src.data[2] = 0; /* a zero normal */
    cr_assert_eq(sol_check_bc5_encode(&src, blocks, SOL_BC4_INTERP_16BIT, &r, NULL), SOL_ERR_INVALID_ARG);
    /* BC1 on colours in [0,1] */
    for (int i = 0; i < 64 * 3; ++i)
        src.data[i] = (float)(0.5 + 0.4 * sin(i * 0.37));
    uint8_t b1[32];
    cr_assert_eq(sol_bc1_encode(&src, NULL, b1), SOL_OK);
    cr_assert_eq(sol_check_bc1_encode(&src, b1, &r, &ref), SOL_OK);
    cr_assert(r.passed && r.mean == ref);
    memset(b1, 0, sizeof b1);
    cr_assert_eq(sol_check_bc1_encode(&src, b1, &r, NULL), SOL_OK);
    cr_assert(!r.passed);
    src.data[4] = 2.0f;
    cr_assert_eq(sol_check_bc1_encode(&src, b1, &r, NULL), SOL_ERR_OUT_OF_RANGE);
    sol_image_free(&src);
}

/* sol_check_bc5_encode_against: the pass rule (engine mean <= (1 + slack) x the reference's mean)
 * against sol's common and optimal encoders on a 16x16 image of varied normals. */
Test(check_blocks, bc5_encoder_against_common_or_optimal)
{
    sol_image src;
    cr_assert_eq(sol_image_alloc(&src, 16, 16, 3), SOL_OK);
    for (int i = 0; i < 256; ++i) {
        double x = 0.5 * sin(i * 0.37) * cos(i * 0.11), y = 0.45 * cos(i * 0.23 + 1.0);
        src.data[3 * i] = (float)x;
        src.data[3 * i + 1] = (float)y;
        src.data[3 * i + 2] = (float)sqrt(1.0 - x * x - y * y);
    }
    uint8_t opt_blocks[256], common_blocks[256], bad[256];
    sol_bc5_options o = {.encoder = SOL_BC5_OPTIMAL};
    sol_bc5_image_stats stats = {0};
    cr_assert_eq(sol_bc5_encode_image(&src, &o, opt_blocks, &stats), SOL_OK);
    o.encoder = SOL_BC5_COMMON;
    cr_assert_eq(sol_bc5_encode_image(&src, &o, common_blocks, NULL), SOL_OK);
    sol_check_report r;
    double opt_mean = -1, common_mean = -1, m = -1;
    uint64_t bounded = 99;
    /* the engine = sol's optimal blocks: passes against optimal with its exact mean */
    cr_assert_eq(sol_check_bc5_encode_against(&src, opt_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &opt_mean,
                                              &bounded),
                 SOL_OK);
    cr_assert(r.passed && r.failures == 0 && r.count == 256);
    cr_assert(r.mean == opt_mean && opt_mean > 0);
    cr_assert(fabs(r.tolerance - opt_mean * (1.0 + SOL_CHECK_BC5_ENCODER_SLACK)) <= 1e-12 * opt_mean);
    cr_assert_eq(bounded, stats.bounded_blocks);
    cr_assert_eq(bounded, 0); /* smooth blocks: every optimum proven */
    /* sol's common blocks against optimal: a mean >= the optimum's on this image (the optimum
     * minimises each block's sum of squared angles; the mean angle follows here) */
    cr_assert_eq(sol_check_bc5_encode_against(&src, common_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &m,
                                              NULL),
                 SOL_OK);
    cr_assert(m == opt_mean && r.mean >= opt_mean);
    cr_assert_eq(r.passed, r.mean <= r.tolerance);
    /* against common: the common blocks pass with the common mean; the wrapper agrees */
    cr_assert_eq(sol_check_bc5_encode_against(&src, common_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_COMMON, &r,
                                              &common_mean, &bounded),
                 SOL_OK);
    cr_assert(r.passed && r.mean == common_mean && bounded == 0);
    cr_assert(opt_mean <= common_mean);
    cr_assert_eq(sol_check_bc5_encode(&src, common_blocks, SOL_BC4_INTERP_16BIT, &r, &m), SOL_OK);
    cr_assert(r.passed && m == common_mean);
    /* a planted bad encoder: every texel takes anchor e0 (index bits zero) - fails both */
    memcpy(bad, common_blocks, sizeof bad);
    for (int b = 0; b < 16; ++b)
        for (int h = 0; h < 2; ++h)
            memset(bad + 16 * b + 8 * h + 2, 0, 6);
    cr_assert_eq(sol_check_bc5_encode_against(&src, bad, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, NULL, NULL),
                 SOL_OK);
    cr_assert(!r.passed && r.failures == 1 && r.mean > r.tolerance);
    cr_assert_eq(sol_check_bc5_encode_against(&src, bad, SOL_BC4_INTERP_16BIT, SOL_BC5_COMMON, &r, NULL, NULL),
                 SOL_OK);
    cr_assert(!r.passed);
    /* errors: outputs untouched */
    sol_check_report keep;
    memset(&keep, 0x5a, sizeof keep);
    r = keep;
    m = -7;
    bounded = 42;
    cr_assert_eq(sol_check_bc5_encode_against(&src, opt_blocks, SOL_BC4_INTERP_16BIT, (sol_bc5_encoder)99, &r, &m,
                                              &bounded),
                 SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_encode_against(&src, opt_blocks, SOL_BC4_INTERP_16BIT, (sol_bc5_encoder)-1, &r, &m,
                                              &bounded),
                 SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_check_bc5_encode_against(NULL, opt_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &m,
                                              &bounded),
                 SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_check_bc5_encode_against(&src, NULL, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &m, &bounded),
                 SOL_ERR_NULL_ARG);
    src.data[3] = NAN;
    cr_assert_eq(sol_check_bc5_encode_against(&src, opt_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &m,
                                              &bounded),
                 SOL_ERR_INVALID_ARG);
    cr_assert(!memcmp(&r, &keep, sizeof r) && m == -7 && bounded == 42);
    src.width = 14;
    cr_assert_eq(sol_check_bc5_encode_against(&src, opt_blocks, SOL_BC4_INTERP_16BIT, SOL_BC5_OPTIMAL, &r, &m,
                                              &bounded),
                 SOL_ERR_INVALID_ARG);
    src.width = 16;
    sol_image_free(&src);
}
