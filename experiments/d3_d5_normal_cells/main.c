/* d3_d5_normal_cells - claims D3, D4, D5: how many of the 16777216 cells of a 24-bit XYZ normal
 * (the 256^3 cube of the talk's quantizer) each storage method uses, under explicit definitions:
 *  - image: the cells the encoder returns for some direction. For normalized normals this is
 *    exactly the set of cells whose box the unit sphere meets (integer test); for the max-component
 *    method the cube's boundary cells.
 *  - fixed: the cells that come back unchanged when their own centre direction is encoded
 *    (for the best-fit search: the cells that win their own ray).
 *  - distinct directions: cells whose odd integer coordinates have gcd 1 (an upper bound for any
 *    method that never stores two codes of one direction).
 * Plus the image over the driver's 10^7 R2 directions, to show how a finite sample undercounts. */
#include "exp_harness.h"
#include "sol_normals.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CUBE_CELLS 16777216.0
/* The talk's cell counts (slides on best-fit normals), the claims' expectations. */
#define TALK_D3_CELLS 289880
#define TALK_D4_CELLS 390152
#define TALK_D5_CELLS 16482364

typedef struct count_row {
    const char *claim, *method, *definition;
    uint64_t cells;
} count_row;

/* Distinct codes the encoder produces over n R2 directions (a bitmap over the 2^24 codes). */
static uint64_t sampled_image(sol_normal_method method, uint64_t n)
{
    uint32_t *codes = malloc(sizeof *codes * n);
    uint8_t *seen = calloc(1u << 24, 1);
    if (!codes || !seen)
        exp_die("out of memory");
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < (int64_t)n; ++i) {
        double u, v, d[3];
        sol_r2_point((uint64_t)i, &u, &v);
        sol_sphere_uniform(u, v, d);
        sol_normal_encode(method, d, &codes[i]); /* unit R2 directions: cannot fail */
    }
    uint64_t distinct = 0;
    for (uint64_t i = 0; i < n; ++i) {
        distinct += !seen[codes[i]];
        seen[codes[i]] = 1;
    }
    free(codes);
    free(seen);
    return distinct;
}

/* Fixed cells over all 256 slices (or, with --quick, 16 slices scaled up: not for the claims). */
static uint64_t fixed_cells(const exp_run *exp, sol_normal_method method)
{
    uint64_t total = 0;
    int step = exp->quick ? 16 : 1;
    for (int r = 0; r < 256; r += step) {
        uint64_t slice;
        exp_check(sol_normal_cells_fixed(method, r, r + 1, &slice), "fixed cells of %s",
                      sol_normal_method_name(method));
        total += slice * (uint64_t)step;
        exp_progress(sol_normal_method_name(method), (size_t)r + 1, 256);
    }
    exp_progress_done(sol_normal_method_name(method));
    return total;
}

static const count_row *find(const count_row *rows, int n, const char *method, const char *definition)
{
    for (int i = 0; i < n; ++i)
        if (!strcmp(rows[i].method, method) && !strcmp(rows[i].definition, definition))
            return &rows[i];
    exp_die("no row %s/%s", method, definition);
    return NULL;
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d3_d5_normal_cells", argc, argv);
    if (exp.bench) /* counts have no accuracy knob; timing lives in d6_d7_s1_s5_normal_encodings */
        return 0;
    uint64_t samples = exp.quick ? 1000000 : 10000000;
    char sample_def[64];
    snprintf(sample_def, sizeof sample_def, "image of %.0e R2 directions", (double)samples);
    count_row rows[20];
    int n = 0;
    uint64_t c;
    exp_check(sol_normal_cells_on_sphere(256, &c), "sphere cells");
    rows[n++] = (count_row){"D3", "normalized", "image (cells the sphere meets)", c};
    rows[n++] = (count_row){"D3", "normalized", "fixed (own centre encodes back)",
                            fixed_cells(&exp, SOL_NORMAL_XYZ_NORMALIZED)};
    rows[n++] = (count_row){"D3", "normalized", sample_def, sampled_image(SOL_NORMAL_XYZ_NORMALIZED, samples)};
    static char series_def[3][64];
    for (int k = 0; k < 3; ++k) { /* how the sampled image grows with the sample size */
        uint64_t m = (uint64_t)(exp.quick ? 100000 : 1000000) * (k == 0 ? 1 : k == 1 ? 3 : 30);
        snprintf(series_def[k], sizeof series_def[k], "image of %.0e R2 directions", (double)m);
        rows[n++] = (count_row){"D3", "normalized", series_def[k], sampled_image(SOL_NORMAL_XYZ_NORMALIZED, m)};
    }
    rows[n++] = (count_row){"D4", "max component", "fixed (own centre encodes back)",
                            fixed_cells(&exp, SOL_NORMAL_XYZ_MAX_COMPONENT)};
    rows[n++] = (count_row){"D4", "max component", "image (= cube boundary, 256^3 - 254^3)",
                            (uint64_t)256 * 256 * 256 - (uint64_t)254 * 254 * 254};
    rows[n++] = (count_row){"D4", "max component", sample_def, sampled_image(SOL_NORMAL_XYZ_MAX_COMPONENT, samples)};
    rows[n++] = (count_row){"D5", "best fit (double search)", "fixed (own centre encodes back)",
                            fixed_cells(&exp, SOL_NORMAL_XYZ_BEST_FIT)};
    rows[n++] = (count_row){"D5", "best fit (float search)", "fixed (own centre encodes back)",
                            fixed_cells(&exp, SOL_NORMAL_XYZ_BEST_FIT_FLOAT)};
    exp_check(sol_normal_cells_distinct_directions(256, &c), "distinct directions");
    rows[n++] = (count_row){"D5", "any XYZ method", "distinct directions (gcd 1)", c};
    rows[n++] = (count_row){"D5", "best fit (double search)", sample_def, sampled_image(SOL_NORMAL_XYZ_BEST_FIT, samples)};

    exp_table *t = exp_table_new("Cells of the 256^3 cube used per method (D3-D5)",
                                 "claim,method,definition,cells,percent of 2^24,log2 cells");
    for (int i = 0; i < n; ++i)
        exp_table_row(t, "%s|%s|%s|%llu|%.3f|%.2f", rows[i].claim, rows[i].method, rows[i].definition,
                      (unsigned long long)rows[i].cells, 100.0 * rows[i].cells / CUBE_CELLS, log2((double)rows[i].cells));
    exp_table_write(t, &exp, "cells");

    const count_row *sphere = find(rows, n, "normalized", "image (cells the sphere meets)");
    const count_row *fixed3 = find(rows, n, "normalized", "fixed (own centre encodes back)");
    const count_row *sampled3 = find(rows, n, "normalized", sample_def);
    const count_row *cube = find(rows, n, "max component", "fixed (own centre encodes back)");
    const count_row *fit = find(rows, n, "best fit (double search)", "fixed (own centre encodes back)");
    const count_row *fitf = find(rows, n, "best fit (float search)", "fixed (own centre encodes back)");
    const count_row *distinct = find(rows, n, "any XYZ method", "distinct directions (gcd 1)");
    char s[256];
    snprintf(s, sizeof s, "%llu (%.2f%%) over %.0e directions; all: %llu (%.2f%%)", (unsigned long long)sampled3->cells,
             100.0 * sampled3->cells / CUBE_CELLS, (double)samples, (unsigned long long)sphere->cells,
             100.0 * sphere->cells / CUBE_CELLS);
    /* D3 counts as reproduced only if a sample-free definition gives the talk's figure: a sampled
     * count can be made to match by the choice of sample size. */
    int d3_exact = llabs((long long)sphere->cells - TALK_D3_CELLS) <= 2899 || llabs((long long)fixed3->cells - TALK_D3_CELLS) <= 2899;
    int d3_sampled = llabs((long long)sampled3->cells - TALK_D3_CELLS) <= 2899;
    exp_claim(&exp, "D3", "~289880 of 16777216 cells, ~1.73%", s, "1% of the count",
              d3_exact ? EXP_REPRODUCED : EXP_DIFFERS_EXPLAINED,
              "no sample-free definition gives the talk's figure: the sphere meets %llu cells (%.2f%%) and %llu cells "
              "map back to themselves; the distinct codes of %.0e uniform directions %s the talk's figure, a count "
              "that grows with the sample size (table), so the talk's number reads as a sampled count",
              (unsigned long long)sphere->cells, 100.0 * sphere->cells / CUBE_CELLS, (unsigned long long)fixed3->cells,
              (double)samples, d3_sampled ? "match" : "do not match");
    snprintf(s, sizeof s, "%llu (%.2f%%)", (unsigned long long)cube->cells, 100.0 * cube->cells / CUBE_CELLS);
    exp_claim(&exp, "D4", "~390152 cells, ~2.33%", s, "exact", cube->cells == TALK_D4_CELLS ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the boundary cells of the cube, 256^3 - 254^3, whether counted as image or as fixed cells");
    snprintf(s, sizeof s, "%llu (%.2f%%) double; %llu (%.2f%%) float; %.1f/%.1f bits vs %.1f/%.1f bits", 
             (unsigned long long)fit->cells, 100.0 * fit->cells / CUBE_CELLS, (unsigned long long)fitf->cells,
             100.0 * fitf->cells / CUBE_CELLS, log2((double)fit->cells), log2((double)fitf->cells),
             log2((double)sampled3->cells), log2((double)cube->cells));
    /* The talk's figure is the double search's fixed cells within 1%, but the exact count rests on how
     * rounding breaks the tie between a cell and its odd multiples (both quantize exactly), and the
     * two other parts of D5 ("two orders of magnitude more", "~17 bits") do not hold as stated. */
    double ratio_lo = (double)fit->cells / (double)cube->cells, ratio_hi = (double)fit->cells / (double)sampled3->cells;
    exp_claim(&exp, "D5", "~16482364 cells, ~98.2%; two orders more; old methods ~17 bits", s, "1% of the count",
              EXP_DIFFERS_EXPLAINED,
              "the double search is within %.2f%% of the talk's count, but a cell ties exactly with its odd multiples "
              "on its own ray, so the count depends on rounding (the float search keeps exactly the %llu distinct "
              "directions, %.2f%%); best fit uses %.0f-%.0fx the old methods' cells (%.1f-%.1f orders, not two), and "
              "the old methods use log2 = %.1f-%.1f bits (the talk's own counts give %.1f and %.1f, not 17)",
              100.0 * fabs((double)fit->cells - TALK_D5_CELLS) / TALK_D5_CELLS, (unsigned long long)distinct->cells,
              100.0 * distinct->cells / CUBE_CELLS, ratio_lo, ratio_hi, log10(ratio_lo), log10(ratio_hi),
              log2((double)sampled3->cells), log2((double)cube->cells), log2(TALK_D3_CELLS), log2(TALK_D4_CELLS));
    return 0;
}
