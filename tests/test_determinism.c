/* test_determinism.c - issue 12: key computations give bit-identical results with 1 and 2 OpenMP
 * threads (the library's promise "identical for any thread count"). Each case runs once per
 * thread count and compares the raw bytes. Inputs are small so the whole file takes seconds. */
#include <criterion/criterion.h>

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "sol_brdf.h"
#include "sol_hdr.h"
#include "sol_lighting.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"
#include "sol_screen.h"
#include "sol_textures.h"

/* Runs `fn` with 1 and then 2 threads into two buffers of `bytes` and compares them. */
typedef void (*det_fn)(void *out);

static void same_for_1_and_2_threads(det_fn fn, size_t bytes, const char *what)
{
    unsigned char *a = calloc(1, bytes), *b = calloc(1, bytes);
    cr_assert(a && b);
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    fn(a);
    omp_set_num_threads(2);
    fn(b);
    omp_set_num_threads(saved);
    cr_assert_eq(memcmp(a, b, bytes), 0, "%s differs between 1 and 2 threads", what);
    free(a);
    free(b);
}

static void cells(void *out)
{
    uint64_t *c = out;
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_NORMALIZED, 120, 136, &c[0]), SOL_OK);
    cr_assert_eq(sol_normal_cells_fixed(SOL_NORMAL_XYZ_MAX_COMPONENT, 0, 16, &c[1]), SOL_OK);
    cr_assert_eq(sol_normal_cells_on_sphere(256, &c[2]), SOL_OK);
    cr_assert_eq(sol_normal_cells_distinct_directions(64, &c[3]), SOL_OK);
}

Test(determinism, normal_cells)
{
    same_for_1_and_2_threads(cells, 4 * sizeof(uint64_t), "normal cell counts");
}

static void bestfit(void *out)
{
    sol_bestfit_table t;
    cr_assert_eq(sol_bestfit_table_build(24, 0, &t), SOL_OK);
    memcpy(out, t.scale, 24 * 24 * sizeof(float));
    sol_bestfit_table_free(&t);
}

Test(determinism, bestfit_table)
{
    same_for_1_and_2_threads(bestfit, 24 * 24 * sizeof(float), "best-fit table");
}

/* A 16x16 normal map with some structure (bumps and a crease). */
static void normal_map(sol_image *img)
{
    cr_assert_eq(sol_image_alloc(img, 16, 16, 3), SOL_OK);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            double nx = 0.5 * sin(0.7 * x + 0.3 * y), ny = x > 9 ? 0.6 : 0.4 * cos(0.5 * y - 0.2 * x);
            double nz = sqrt(fmax(0.0, 1.0 - nx * nx - ny * ny));
            float *p = sol_image_pixel(img, x, y);
            p[0] = (float)nx;
            p[1] = (float)ny;
            p[2] = (float)nz;
        }
}

static void bc5_run_base(void *out, sol_bc5_encoder enc, sol_bc5_base base)
{
    sol_image img;
    normal_map(&img);
    sol_bc5_options o = {.encoder = enc, .window = 2, .base = base};
    sol_bc5_image_stats st;
    cr_assert_eq(sol_bc5_encode_image(&img, &o, out, &st), SOL_OK);
    memcpy((unsigned char *)out + 256, &st, sizeof st);
    sol_image_free(&img);
}

static void bc5_run(void *out, sol_bc5_encoder enc)
{
    bc5_run_base(out, enc, SOL_BC5_BASE_COMMON);
}

static void bc5_adaptive_fast_base(void *out)
{
    bc5_run_base(out, SOL_BC5_ADAPTIVE, SOL_BC5_BASE_FAST);
}

static void bc5_common(void *out)
{
    bc5_run(out, SOL_BC5_COMMON);
}

static void bc5_adaptive(void *out)
{
    bc5_run(out, SOL_BC5_ADAPTIVE);
}

Test(determinism, bc5_encoders)
{
    same_for_1_and_2_threads(bc5_common, 256 + sizeof(sol_bc5_image_stats), "BC5 common");
    same_for_1_and_2_threads(bc5_adaptive, 256 + sizeof(sol_bc5_image_stats), "BC5 adaptive");
    same_for_1_and_2_threads(bc5_adaptive_fast_base, 256 + sizeof(sol_bc5_image_stats), "BC5 adaptive, fast base");
}

static void bc1(void *out)
{
    sol_image img;
    normal_map(&img);
    for (size_t i = 0; i < 16 * 16 * 3; ++i)
        img.data[i] = 0.5f + 0.5f * img.data[i];
    cr_assert_eq(sol_bc1_encode(&img, NULL, out), SOL_OK);
    sol_image_free(&img);
}

Test(determinism, bc1_encoder)
{
    same_for_1_and_2_threads(bc1, sol_bc1_size(16, 16), "BC1");
}

static void sg_fit(void *out)
{
    sol_sg lobes[3];
    sol_sg_fit_error e[2];
    sol_sg_fit_options o = {.radial_samples = 8, .angular_samples = 8, .eval_radial = 16, .eval_angular = 16};
    memset(lobes, 0, sizeof lobes);
    memset(e, 0, sizeof e);
    cr_assert_eq(sol_ward_sg_fit(0.2, 0.3, 2, &o, lobes, e, NULL), SOL_OK);
    memcpy(out, lobes, sizeof lobes);
    memcpy((unsigned char *)out + sizeof lobes, e, sizeof e);
}

Test(determinism, sg_fit)
{
    same_for_1_and_2_threads(sg_fit, 3 * sizeof(sol_sg) + 2 * sizeof(sol_sg_fit_error), "Ward SG fit");
}

static void dfg(void *out)
{
    sol_dfg_lut lut;
    cr_assert_eq(sol_dfg_lut_build(8, 64, &lut), SOL_OK);
    memcpy(out, lut.scale_bias, 8 * 8 * 2 * sizeof(float));
    sol_dfg_lut_free(&lut);
}

Test(determinism, dfg_table)
{
    same_for_1_and_2_threads(dfg, 8 * 8 * 2 * sizeof(float), "DFG table");
}

/* Tone-map tables: the filmic curve and its inverse over a grid, computed in a parallel loop as a
 * driver would, and the tone map baked into a 3D LUT. */
static void filmic_rgb(const double in[3], double out[3], void *ctx)
{
    (void)ctx;
    for (int c = 0; c < 3; ++c)
        out[c] = sol_tonemap_apply(SOL_TONEMAP_FILMIC_HBD, 4.0 * in[c]);
}

static void tonemap_tables(void *out)
{
    double *t = out;
#pragma omp parallel for schedule(dynamic, 7)
    for (int i = 0; i < 1024; ++i) {
        double y = (i + 0.5) / 1024.0, x = 0.0;
        (void)sol_tonemap_inverse(SOL_TONEMAP_FILMIC_HBD, y, &x);
        t[2 * i] = x;
        t[2 * i + 1] = sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, 8.0 * i / 1024.0);
    }
    sol_lut3d lut;
    cr_assert_eq(sol_lut3d_bake(9, filmic_rgb, NULL, &lut), SOL_OK);
    memcpy(t + 2048, lut.data, 9 * 9 * 9 * 3 * sizeof(float));
    sol_lut3d_free(&lut);
}

Test(determinism, tonemap_tables)
{
    same_for_1_and_2_threads(tonemap_tables, 2048 * sizeof(double) + 9 * 9 * 9 * 3 * sizeof(float), "tone-map tables");
}

static void postaa(void *out)
{
    sol_image img, res;
    normal_map(&img);
    cr_assert_eq(sol_postaa_filter(&img, NULL, &res), SOL_OK);
    memcpy(out, res.data, 16 * 16 * 3 * sizeof(float));
    sol_image_free(&res);
    sol_image_free(&img);
}

Test(determinism, postaa_filter)
{
    same_for_1_and_2_threads(postaa, 16 * 16 * 3 * sizeof(float), "post-process AA");
}
