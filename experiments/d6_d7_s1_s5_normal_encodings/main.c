/* d6_d7_s1_s5_normal_encodings - angular error of every 24-bit normal encoding (S1, S5 and the
 * best fit of D5/D6) over 10^7 R2 directions, the best-fit table (D6, d6_table.c), blending
 * (D7, d7_blending.c) and accuracy vs time per encoder (--bench). */
#include "encodings.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct method_result {
    encoder enc;
    error_stats stats;
    double ns;
} method_result;

/* ---- timing: encode + decode of a batch of directions, one thread ---- */
typedef struct timing_ctx {
    const encoder *enc;
    const double *dirs;
    size_t n;
    double sink;
} timing_ctx;

static void time_batch(void *p)
{
    timing_ctx *c = p;
    double acc = 0;
    for (size_t i = 0; i < c->n; ++i) {
        double back[3];
        decode_with(c->enc, encode_with(c->enc, c->dirs + 3 * i), back);
        acc += back[0];
    }
    c->sink += acc; /* keeps the work observable */
}

static double ns_per_normal(const encoder *e, const double *dirs, size_t n)
{
    timing_ctx c = {e, dirs, n, 0};
    return exp_cpu_time_per_item_ns(time_batch, &c, n, 5);
}

static double *timing_directions(size_t n)
{
    double *d = malloc(sizeof *d * 3 * n);
    if (!d)
        exp_die("out of memory");
    for (size_t i = 0; i < n; ++i)
        r2_direction(1000003 + 7 * i, d + 3 * i); /* not the error set's first points */
    return d;
}

/* ---- S1: Mittring's error as a function of the view-space z ---- */
static void mittring_by_z(const exp_run *exp, size_t n)
{
    enum { BINS = 10 };
    const sol_normal_method methods[3] = {SOL_NORMAL_MITTRING_8, SOL_NORMAL_MITTRING_12, SOL_NORMAL_OCTAHEDRAL_12};
    double sum[3][BINS] = {{0}}, worst[3][BINS] = {{0}};
    uint64_t count[BINS] = {0};
    /* Blocks of directions: the errors of a block in parallel, then summed in direction order on one
     * thread (the same sums, bit for bit, for any thread count). */
    enum { BLOCK = 1 << 16 };
    double *e = malloc(sizeof *e * 3 * BLOCK);
    int *bins = malloc(sizeof *bins * BLOCK);
    if (!e || !bins)
        exp_die("out of memory");
    for (size_t start = 0; start < n; start += BLOCK) {
        int64_t len = (int64_t)(n - start < BLOCK ? n - start : BLOCK);
#pragma omp parallel for schedule(static)
        for (int64_t j = 0; j < len; ++j) {
            double d[3], back[3];
            r2_direction(start + (size_t)j, d);
            int bin = (int)((d[2] + 1.0) * 0.5 * BINS);
            bins[j] = bin >= BINS ? BINS - 1 : bin;
            for (int m = 0; m < 3; ++m) {
                uint32_t code;
                sol_normal_encode(methods[m], d, &code);
                sol_normal_decode(methods[m], code, back);
                e[3 * j + m] = sol_angle3(d, back) * DEG;
            }
        }
        for (int64_t j = 0; j < len; ++j) { /* sequential: sums in a fixed order */
            int bin = bins[j];
            ++count[bin];
            for (int m = 0; m < 3; ++m) {
                sum[m][bin] += e[3 * j + m];
                worst[m][bin] = e[3 * j + m] > worst[m][bin] ? e[3 * j + m] : worst[m][bin];
            }
        }
    }
    free(e);
    free(bins);
    exp_table *t = exp_table_new("Angular error by view-space z (S1)",
                                 "z from,z to,mittring-8 mean deg,mittring-8 max deg,mittring-12 mean deg,"
                                 "mittring-12 max deg,octahedral-12 mean deg,octahedral-12 max deg");
    for (int b = 0; b < BINS; ++b)
        exp_table_row(t, "%.1f|%.1f|%.4f|%.3f|%.5f|%.4f|%.5f|%.4f", -1.0 + 2.0 * b / BINS, -1.0 + 2.0 * (b + 1) / BINS,
                      sum[0][b] / count[b], worst[0][b], sum[1][b] / count[b], worst[1][b], sum[2][b] / count[b],
                      worst[2][b]);
    exp_table_write(t, exp, "mittring_by_z");
    exp_plot(exp, "mittring_by_z",
             "set datafile separator comma\nset xlabel 'view-space z of the normal'\nset ylabel 'mean angular error (deg)'\n"
             "set logscale y\nset grid\nset key top right\n"
             "plot 'mittring_by_z.csv' skip 1 using (($1+$2)/2):3 with linespoints title 'Mittring 8:8', "
             "'' skip 1 using (($1+$2)/2):5 with linespoints title 'Mittring 12:12', "
             "'' skip 1 using (($1+$2)/2):7 with linespoints title 'octahedral 12:12'");
    /* Codes with |G| > 1 decode to no direction of their own: the wasted corners of the square. */
    uint64_t wasted = 0;
    for (uint32_t gy = 0; gy < 4096; ++gy)
        for (uint32_t gx = 0; gx < 4096; ++gx) {
            double x = gx / 4095.0 * 2 - 1, y = gy / 4095.0 * 2 - 1;
            wasted += x * x + y * y > 1.0;
        }
    double mean_front = 0, mean_back = 0;
    for (int b = 0; b < BINS; ++b)
        *(b < BINS / 2 ? &mean_back : &mean_front) += sum[1][b] / count[b] / (BINS / 2);
    char s[200];
    snprintf(s, sizeof s, "12:12: mean %.4f deg for z<0 vs %.4f deg for z>0; %.1f%% of codes unused", mean_back,
             mean_front, 100.0 * wasted / (4096.0 * 4096.0));
    /* |G| = cos(theta/2) for the angle theta to +z, so d theta = 2 d|G| / sin(theta/2): the radial code
     * step is finest at z = -1 and degenerates at z = +1. In D3D's left-handed view space (the camera
     * looks down +z) the normals the camera sees have z < 0: that is where the codes are finest. */
    exp_claim(exp, "S1", "G = normalize(N.xy)*sqrt(N.z*0.5+0.5); more precision where it matters", s,
              "qualitative", mean_back < mean_front ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "error per z band over R2 directions: finest for normals with z<0, i.e. facing the camera in D3D's "
              "left-handed view space (in a right-handed GL view space it would favour back-facing normals); the "
              "worst case (%.2f deg at 12:12) sits at z=+1, where |G|=cos(theta/2) is flat; |G|>1 codes are wasted",
              worst[1][BINS - 1]);
    exp_number(exp, "S1-mittring12-max-deg", "%.1f", worst[1][BINS - 1]);
    exp_number(exp, "S1-unused-percent", "%.1f", 100.0 * wasted / (4096.0 * 4096.0));
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d6_d7_s1_s5_normal_encodings", argc, argv);
    size_t n = exp.quick || exp.bench ? 1000000 : 10000000;
    sol_bestfit_table table;
    exp_check(sol_bestfit_table_build(512, 16, &table), "best-fit table");

    method_result r[SOL_NORMAL_METHOD_COUNT + 2];
    int count = 0;
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m)
        r[count++].enc = (encoder){sol_normal_method_name((sol_normal_method)m), (sol_normal_method)m, NULL, 0};
    r[count++].enc = (encoder){"best-fit-table-512-16bit-nearest", SOL_NORMAL_XYZ_NORMALIZED, &table, SOL_TABLE_NEAREST};
    r[count++].enc = (encoder){"best-fit-table-512-16bit-bilinear", SOL_NORMAL_XYZ_NORMALIZED, &table, SOL_TABLE_BILINEAR};

    float *err = malloc(sizeof *err * n);
    if (!err)
        exp_die("out of memory");
    size_t timing_n = 1 << 14;
    double *dirs = timing_directions(timing_n);
    for (int k = 0; k < count; ++k) {
        encoder_errors(&r[k].enc, n, err);
        r[k].stats = stats_of(err, n);
        r[k].ns = ns_per_normal(&r[k].enc, dirs, timing_n);
        exp_progress("encodings", (size_t)k + 1, (size_t)count);
    }
    exp_progress_done("encodings");

    if (!exp.bench) {
        char title[128];
        snprintf(title, sizeof title, "Angular error of 24-bit normal encodings over %.0e R2 directions", (double)n);
        exp_table *t = exp_table_new(title, "method,bits,mean deg,rms deg,p99 deg,max deg,effective bits");
        for (int k = 0; k < count; ++k)
            exp_table_row(t, "%s|%d|%.5f|%.5f|%.5f|%.5f|%.2f", r[k].enc.name, sol_normal_method_bits(r[k].enc.method),
                          r[k].stats.mean, r[k].stats.rms, r[k].stats.p99, r[k].stats.max, effective_bits(r[k].stats.rms));
        exp_table_write(t, &exp, "errors");
    }
    exp_table *p = exp_table_new("Accuracy vs time per normal (encode + decode, one thread)",
                                 "method,ns per normal,rms deg,max deg");
    for (int k = 0; k < count; ++k)
        exp_table_row(p, "%s|%.1f|%.5f|%.5f", r[k].enc.name, r[k].ns, r[k].stats.rms, r[k].stats.max);
    exp_table_write(p, &exp, "pareto");
    /* one key entry per encoder (point type and colour), not text labels, which overlap where
     * encoders have similar cost and error */
    char clauses[4096] = "";
    for (int k = 0; k < count; ++k) {
        size_t used = strlen(clauses);
        snprintf(clauses + used, sizeof clauses - used, "%s'pareto.csv' every ::%d::%d using 2:3 with points pt %d lc %d ps 1.5 title '%s'",
                 k ? ", " : "", k, k, k % 13 + 1, k % 8 + 1, r[k].enc.name);
    }
    exp_plot(&exp, "pareto",
             "set datafile separator comma\nset logscale xy\nset xlabel 'ns per normal (encode + decode)'\n"
             "set ylabel 'RMS angular error (deg)'\nset grid\nset key outside right top font ',8'\n"
             "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\nplot %s", clauses);

    if (!exp.bench) {
        const method_result *xyz = &r[SOL_NORMAL_XYZ_NORMALIZED], *oct = &r[SOL_NORMAL_OCTAHEDRAL_12],
                            *octp = &r[SOL_NORMAL_OCTAHEDRAL_12_PRECISE], *sph = &r[SOL_NORMAL_SPHERICAL_12],
                            *sphz = &r[SOL_NORMAL_SPHERICAL_Z_12], *fit = &r[SOL_NORMAL_XYZ_BEST_FIT];
        char s[300];
        snprintf(s, sizeof s,
                 "RMS deg: octahedral %.4f (precise %.4f), spherical %.4f (phi,z: %.4f, max %.2f), normalized XYZ "
                 "%.4f, best fit %.4f (max %.3f)",
                 oct->stats.rms, octp->stats.rms, sph->stats.rms, sphz->stats.rms, sphz->stats.max, xyz->stats.rms,
                 fit->stats.rms, fit->stats.max);
        int better = oct->stats.rms < xyz->stats.rms && oct->stats.rms < sph->stats.rms &&
                     oct->stats.rms < sphz->stats.rms && fit->stats.rms < xyz->stats.rms / 3;
        exp_claim(&exp, "S5", "octahedral beats XYZ and spherical; best fit very precise at 3 components", s,
                  "qualitative", better ? EXP_REPRODUCED : EXP_DIFFERS_EXPLAINED,
                  "all 24-bit; octahedral has the lowest RMS error (max %.4f deg vs spherical %.4f deg); best fit's "
                  "RMS is %.1fx lower than normalized XYZ but its worst case stays %.3f deg near the axes, where the "
                  "talk's quantizer has no zero code",
                  oct->stats.max, sph->stats.max, xyz->stats.rms / fit->stats.rms, fit->stats.max);
        exp_number(&exp, "S5-sphz-rms-excess-percent", "%.0f", 100.0 * (sphz->stats.rms / oct->stats.rms - 1.0));
        exp_number(&exp, "S5-sphz-max-deg", "%.2f", sphz->stats.max);
        exp_number(&exp, "S5-fit-rms-factor", "%.1f", xyz->stats.rms / fit->stats.rms);
        exp_number(&exp, "S5-fit-max-deg", "%.2f", fit->stats.max);
        exp_number(&exp, "S5-search-ns", "%.0f", fit->ns);
        exp_number(&exp, "S5-table512-ns", "%.0f", r[count - 2].ns); /* the 512^2 table, nearest */
        mittring_by_z(&exp, exp.quick ? 200000 : 2000000);
        run_oct_sweep(&exp);
    }
    free(dirs);
    free(err);
    sol_bestfit_table_free(&table);
    run_d6_table(&exp);
    if (!exp.bench)
        run_d7_blending(&exp);
    else
        run_oct_bench(&exp);
    return 0;
}
