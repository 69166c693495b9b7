/* d6_table.c - claim D6: the baked best-fit table. Writes the 512x512 table (16-bit PNG, float
 * EXR) and one cube-map face of the exact search; sweeps table size, stored precision and
 * filtering against angular error; measures what sampling a mip level does; times the table path
 * against the exact search (the accuracy knob is the table size). */
#include "encodings.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A copy of a float table with its texels re-quantized to `bits` (8/16) as the texture would hold. */
static sol_bestfit_table requantized(const sol_bestfit_table *src, int bits)
{
    size_t n = (size_t)src->size * (size_t)src->size;
    sol_bestfit_table t = {src->size, bits, malloc(sizeof(float) * n)};
    if (!t.scale)
        exp_die("out of memory");
    for (size_t i = 0; i < n; ++i)
        t.scale[i] = bits ? (float)sol_unorm_decode(sol_unorm_encode(src->scale[i], bits), bits) : src->scale[i];
    return t;
}

static void write_table_files(const exp_run *exp)
{
    sol_bestfit_table t;
    exp_check(sol_bestfit_table_build(512, 0, &t), "512 table");
    sol_image img = {0};
    exp_check(sol_image_alloc(&img, 512, 512, 1), "image");
    memcpy(img.data, t.scale, sizeof(float) * 512 * 512);
    exp_check(sol_png_write(exp_path(exp, "best_fit_table_512.png"), &img, 16), "table PNG");
    exp_check(sol_exr_write(exp_path(exp, "best_fit_table_512.exr"), &img, 0), "table EXR");
    /* One face (+z) of the cube map the talk bakes: the scale t at direction (x, y, 1). */
    for (int j = 0; j < 512; ++j)
        for (int i = 0; i < 512; ++i) {
            double d[3] = {(i + 0.5) / 256.0 - 1.0, 1.0 - (j + 0.5) / 256.0, 1.0}, s;
            exp_check(sol_bestfit_scale(d, &s), "face texel");
            *sol_image_pixel(&img, i, j) = (float)s;
        }
    exp_check(sol_png_write(exp_path(exp, "best_fit_cube_face.png"), &img, 16), "face PNG");
    sol_image_free(&img);
    sol_bestfit_table_free(&t);
}

/* Errors of the table path, and the share of directions that get the exact search's cell. */
static error_stats table_errors(const sol_bestfit_table *t, sol_table_filter f, const uint32_t *exact, size_t n,
                                float *err, double *same)
{
    encoder e = {"table", SOL_NORMAL_XYZ_NORMALIZED, t, f};
    uint64_t agree = 0;
#pragma omp parallel for schedule(static) reduction(+ : agree)
    for (int64_t i = 0; i < (int64_t)n; ++i) {
        double d[3], back[3];
        r2_direction((uint64_t)i, d);
        uint32_t code = encode_with(&e, d);
        agree += code == exact[i];
        decode_with(&e, code, back);
        err[i] = (float)(sol_angle3(d, back) * DEG);
    }
    *same = 100.0 * (double)agree / (double)n;
    return stats_of(err, n);
}

/* One thread encoding d->tn directions through the table t with `filter` (NULL: the exact search). */
typedef struct knob_timing {
    const sol_bestfit_table *t; /* NULL: the exact search */
    sol_table_filter filter;
    const double *dirs;
    size_t n;
    uint32_t sink;
} knob_timing;

static void time_knob(void *p)
{
    knob_timing *c = p;
    for (size_t i = 0; i < c->n; ++i) {
        uint32_t code;
        if (c->t)
            sol_normal_encode_bestfit_table(c->t, c->filter, c->dirs + 3 * i, &code);
        else
            sol_normal_encode(SOL_NORMAL_XYZ_BEST_FIT, c->dirs + 3 * i, &code);
        c->sink ^= code;
    }
}

/* What every measurement shares: the R2 directions' exact-search codes and errors (the reference),
 * an error scratch array, and a small direction set for the timings. */
typedef struct d6_data {
    size_t n, tn;
    float *err;
    uint32_t *exact;
    error_stats exact_stats;
    double *dirs; /* tn directions, 3 doubles each, for the timings */
} d6_data;

static void d6_data_init(const exp_run *exp, d6_data *d)
{
    d->n = exp->quick || exp->bench ? 200000 : 2000000;
    d->err = malloc(sizeof *d->err * d->n);
    d->exact = malloc(sizeof *d->exact * d->n);
    if (!d->err || !d->exact)
        exp_die("out of memory");
    /* one search per direction gives both its code and its error (as encoder_errors computes it) */
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < (int64_t)d->n; ++i) {
        double dir[3], back[3];
        r2_direction((uint64_t)i, dir);
        sol_normal_encode(SOL_NORMAL_XYZ_BEST_FIT, dir, &d->exact[i]);
        sol_normal_decode(SOL_NORMAL_XYZ_BEST_FIT, d->exact[i], back);
        d->err[i] = (float)(sol_angle3(dir, back) * DEG);
    }
    d->exact_stats = stats_of(d->err, d->n);
    d->tn = 4096;
    d->dirs = malloc(sizeof *d->dirs * 3 * d->tn);
    if (!d->dirs)
        exp_die("out of memory");
    for (size_t i = 0; i < d->tn; ++i) /* offset: directions the error sets do not use */
        r2_direction(5000011 + 3 * i, d->dirs + 3 * i);
}

static void d6_data_free(d6_data *d)
{
    free(d->dirs);
    free(d->exact);
    free(d->err);
}

/* The sweep's axes: table size, and stored precision (0 = float). */
static const int sizes[] = {64, 128, 256, 512, 1024, 2048};
static const int precision_bits[] = {8, 16, 0};
enum { N_SIZES = sizeof sizes / sizeof sizes[0], N_BITS = sizeof precision_bits / sizeof precision_bits[0] };

/* RMS errors of the sweep, for the figure and the claim; [size][precision][filter]. */
typedef struct sweep_rms {
    double rms16[N_SIZES], rms8[N_SIZES], rms_all[N_SIZES][N_BITS][2];
} sweep_rms;

/* The accuracy knob: time per normal of the table path (nearest, 16-bit) at this size. */
static void timing_row(exp_table *knob, const d6_data *d, const sol_bestfit_table *t, int size, error_stats st)
{
    knob_timing c = {t, SOL_TABLE_NEAREST, d->dirs, d->tn, 0};
    char name[64];
    snprintf(name, sizeof name, "table %dx%d", size, size);
    exp_table_row(knob, "%s|%.1f|%.5f|%.5f", name, exp_cpu_time_per_item_ns(time_knob, &c, d->tn, 5), st.rms, st.max);
}

/* One table size at every precision and filter (--bench: 16-bit nearest only, the timed one). */
static void sweep_one_size(const exp_run *exp, d6_data *d, size_t s, exp_table *sweep, exp_table *knob, sweep_rms *r)
{
    sol_bestfit_table base;
    exp_check(sol_bestfit_table_build(sizes[s], 0, &base), "table %d", sizes[s]);
    for (size_t b = 0; b < N_BITS; ++b) {
        sol_bestfit_table t = requantized(&base, precision_bits[b]);
        for (int f = 0; f < 2; ++f) {
            if (exp->bench && (precision_bits[b] != 16 || f != SOL_TABLE_NEAREST))
                continue;
            double same;
            error_stats st = table_errors(&t, (sol_table_filter)f, d->exact, d->n, d->err, &same);
            r->rms_all[s][b][f] = st.rms;
            if (f == SOL_TABLE_NEAREST && precision_bits[b] == 16)
                r->rms16[s] = st.rms;
            if (f == SOL_TABLE_NEAREST && precision_bits[b] == 8)
                r->rms8[s] = st.rms;
            exp_table_row(sweep, "%d|%s|%s|%.5f|%.5f|%.5f|%.5f|%.2f", sizes[s],
                          precision_bits[b] == 8 ? "8-bit" : precision_bits[b] == 16 ? "16-bit" : "float",
                          f ? "bilinear" : "nearest", st.mean, st.rms, st.p99, st.max, same);
            if (f == SOL_TABLE_NEAREST && precision_bits[b] == 16)
                timing_row(knob, d, &t, sizes[s], st);
        }
        sol_bestfit_table_free(&t);
    }
    sol_bestfit_table_free(&base);
}

static void size_sweep(const exp_run *exp, d6_data *d, sweep_rms *r)
{
    exp_table *sweep = exp_table_new("Best-fit table: size, stored precision, filter vs angular error (D6)",
                                     "size,precision,filter,mean deg,rms deg,p99 deg,max deg,same cell as search %");
    exp_table *knob = exp_table_new("Best-fit table size vs time per normal (D6; nearest, 16-bit)",
                                    "encoder,ns per normal,rms deg,max deg");
    for (size_t s = 0; s < N_SIZES; ++s) {
        sweep_one_size(exp, d, s, sweep, knob, r);
        exp_progress("d6 sweep", s + 1, N_SIZES);
    }
    exp_progress_done("d6 sweep");
    exp_table_write(sweep, exp, "table_sweep");
    exp_table_write(knob, exp, "table_timing");
}

static void plot_size_sweep(const exp_run *exp, const sweep_rms *r, double exact_rms)
{
    FILE *f = exp_open(exp, "table_sweep_plot.csv"); /* one column per curve, for the figure */
    fprintf(f, "size,8-bit nearest,16-bit nearest,float nearest,16-bit bilinear\n");
    for (size_t s = 0; s < N_SIZES; ++s)
        fprintf(f, "%d,%.6f,%.6f,%.6f,%.6f\n", sizes[s], r->rms_all[s][0][0], r->rms_all[s][1][0], r->rms_all[s][2][0],
                r->rms_all[s][1][1]);
    fclose(f);
    exp_plot(exp, "table_sweep",
             "set datafile separator comma\nset logscale x 2\nset logscale y\nset xlabel 'table size (texels per side)'\n"
             "set ylabel 'RMS angular error (deg)'\nset grid\nset key top right\n"
             "plot 'table_sweep_plot.csv' skip 1 using 1:2 with linespoints lw 3 title '8-bit, nearest', "
             "'' skip 1 using 1:3 with linespoints title '16-bit, nearest', "
             "'' skip 1 using 1:4 with linespoints dt 3 title 'float, nearest', "
             "'' skip 1 using 1:5 with linespoints title '16-bit, bilinear', "
             "%.6f with lines dt 2 title 'exact search'",
             exact_rms);
}

/* Mip levels of the 512 table (2x2 box, re-quantized to 16 bits) against tables baked at the same
 * size: what a sampler that picks a coarser level does to the fit. */
static void mip_table(const exp_run *exp, d6_data *d)
{
    exp_table *mips = exp_table_new("Sampling a mip level of the 512x512 16-bit table (D6)",
                                    "level,size,filter,mip rms deg,mip max deg,baked-at-size rms deg,same cell %");
    sol_bestfit_table level;
    exp_check(sol_bestfit_table_build(512, 16, &level), "mip 0");
    for (int l = 0; l <= 4; ++l) {
        sol_bestfit_table baked;
        exp_check(sol_bestfit_table_build(level.size, 16, &baked), "baked");
        for (int f = 0; f < 2; ++f) {
            double same, same_b;
            error_stats st = table_errors(&level, (sol_table_filter)f, d->exact, d->n, d->err, &same);
            error_stats sb = table_errors(&baked, (sol_table_filter)f, d->exact, d->n, d->err, &same_b);
            exp_table_row(mips, "%d|%d|%s|%.5f|%.5f|%.5f|%.2f", l, level.size, f ? "bilinear" : "nearest", st.rms,
                          st.max, sb.rms, same);
        }
        sol_bestfit_table_free(&baked);
        sol_bestfit_table next;
        exp_check(sol_bestfit_table_downsample(&level, &next), "mip %d", l + 1);
        sol_bestfit_table_free(&level);
        level = next;
    }
    sol_bestfit_table_free(&level);
    exp_table_write(mips, exp, "mips");
}

/* The D6 row: indices 2, 3, 5 of `sizes` are 256, 512 and 2048. */
static void write_claim(const exp_run *exp, const sweep_rms *r, double exact_rms)
{
    char s[300];
    snprintf(s, sizeof s,
             "RMS deg (nearest): 256: %.4f, 512: %.4f, 2048: %.4f (16-bit); 512 8-bit %.4f; exact search %.4f",
             r->rms16[2], r->rms16[3], r->rms16[5], r->rms8[3], exact_rms);
    int bigger_helps = r->rms16[3] < 0.9 * r->rms16[2];
    int eight_ok = r->rms8[3] < 1.1 * r->rms16[3];
    exp_claim(exp, "D6", "face > 256x256; unique part 512x512 (y/x); 8 bits sufficient; mips essential", s,
              "8-bit within 10% of 16-bit; 512 at least 10% better than 256",
              bigger_helps && eight_ok ? EXP_REPRODUCED : EXP_DIFFERS_EXPLAINED,
              "nearest sampling; 8 bits are exact, not just sufficient: the search's scales t = (2s)/255 "
              "with 2s odd are 8-bit UNORM codes; bilinear filtering and coarser mip levels blend scales of different cells and "
              "lose the fit (mips table), so mips help the texture cache only, not accuracy; the performance "
              "claim is not measurable on a CPU");
}

/* --bench only (table_knobs): the table's stored precision and filter at 512x512 against the exact
 * search (the peer the table replaces), error and core-ns per encode (one thread). On a CPU the
 * texels are floats whatever the precision, so only the filter changes the time here; a GPU reads
 * 8-bit texels with half the bandwidth of 16-bit ones (timed by time_knob). */
static void table_knobs(const exp_run *exp, d6_data *d)
{
    exp_table *t = exp_table_new("Best-fit table 512x512 (D6): stored precision and filter vs angular error and time per "
                                 "encode (one thread); peer: the exact search",
                                 "encoder,precision,filter,rms deg,max deg,same cell as search %,core-ns per normal");
    knob_timing c = {NULL, SOL_TABLE_NEAREST, d->dirs, d->tn, 0};
    exp_table_row(t, "peer: exact search|double|-|%.5f|%.5f|100.00|%.1f", d->exact_stats.rms, d->exact_stats.max,
                  exp_cpu_time_per_item_ns(time_knob, &c, d->tn, 15));
    sol_bestfit_table base;
    exp_check(sol_bestfit_table_build(512, 0, &base), "table 512");
    for (size_t b = 0; b < N_BITS; ++b) {
        sol_bestfit_table tb = requantized(&base, precision_bits[b]);
        for (int f = 0; f < 2; ++f) {
            double same;
            error_stats st = table_errors(&tb, (sol_table_filter)f, d->exact, d->n, d->err, &same);
            knob_timing k = {&tb, (sol_table_filter)f, d->dirs, d->tn, 0};
            exp_table_row(t, "table 512x512|%s|%s|%.5f|%.5f|%.2f|%.1f",
                          precision_bits[b] == 8 ? "8-bit" : precision_bits[b] == 16 ? "16-bit" : "float",
                          f ? "bilinear" : "nearest", st.rms, st.max, same, exp_cpu_time_per_item_ns(time_knob, &k, d->tn, 15));
        }
        sol_bestfit_table_free(&tb);
    }
    sol_bestfit_table_free(&base);
    exp_table_write(t, exp, "table_knobs");
}

void run_d6_table(const exp_run *exp)
{
    d6_data d;
    d6_data_init(exp, &d);
    if (!exp->bench)
        write_table_files(exp);
    sweep_rms r = {{0}, {0}, {{{0}}}};
    size_sweep(exp, &d, &r);
    if (exp->bench)
        table_knobs(exp, &d);
    if (!exp->bench) { /* --bench prints only the timed size sweep */
        plot_size_sweep(exp, &r, d.exact_stats.rms);
        mip_table(exp, &d);
        write_claim(exp, &r, d.exact_stats.rms);
    }
    d6_data_free(&d);
}
