/* oct_sweep.c - S5's outside reference: the octahedral map's error against bit count, side by side
 * with L. Tyler's measurements ("Analyzing Octahedral Encoded Normals", 2024: 10^6 random points
 * of the cube [-1,1]^3 normalised onto the sphere, UNORM rounding to nearest) and, as a table in
 * the style of Cigolle et al. 2014 (JCGT 3(2), table of oct16..oct32), sol's SNORM octahedral map
 * at 8:8 .. 16:16 bits with plain and "precise" rounding over uniform directions. */
#include "encodings.h"

#include <math.h>
#include <stdlib.h>

/* Tyler's table (mean and max angular error in degrees, 10^6 cube-point directions), bits 8..13. */
static const struct {
    int bits;
    double mean, max;
} tyler[] = {{8, 0.350526, 0.946480},  {9, 0.174814, 0.473682},  {10, 0.087357, 0.235790},
             {11, 0.043663, 0.117949}, {12, 0.021842, 0.058642}, {13, 0.010909, 0.029560}};
enum { N_TYLER = sizeof tyler / sizeof tyler[0] };

typedef struct oct_stats {
    double mean, max;
} oct_stats;

/* Direction i of a set: random cube points normalised (Tyler's set) or uniform on the sphere,
 * each from its own SplitMix64 stream (seeded per index, so any thread count gives the same set). */
static void set_direction(int cube, uint64_t i, double d[3])
{
    uint64_t state = (cube ? 0x7c0bu : 0x5e7u) * 0x9E3779B97F4A7C15ull + i * 0xD1B54A32D192ED03ull;
    if (cube) {
        for (int k = 0; k < 3; ++k)
            d[k] = sol_rng_uniform(&state, -1.0, 1.0); /* normalised by the encoder; never all zero here */
    } else {
        double u = sol_rng_uniform(&state, 0, 1), v = sol_rng_uniform(&state, 0, 1);
        sol_sphere_uniform(u, v, d);
    }
}

/* Mean and max of err[0..n); the sum in index order, so the same for any thread count. */
static oct_stats oct_stats_of(const double *err, size_t n)
{
    oct_stats s = {0, 0};
    for (size_t i = 0; i < n; ++i) {
        s.mean += err[i];
        s.max = err[i] > s.max ? err[i] : s.max;
    }
    s.mean /= (double)n;
    return s;
}

/* Mean and max error (degrees) of one octahedral variant over n directions of a set; the sum is
 * taken in index order, so the mean is the same for any thread count. */
static oct_stats oct_errors(const sol_oct_options *o, int cube, size_t n, double *err)
{
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < (int64_t)n; ++i) {
        double d[3], back[3];
        uint32_t code[2];
        set_direction(cube, (uint64_t)i, d);
        exp_check(sol_oct_encode(o, d, code), "octahedral encode");
        exp_check(sol_oct_decode(o, code, back), "octahedral decode");
        err[i] = sol_angle3(d, back) * DEG;
    }
    return oct_stats_of(err, n);
}

void run_oct_sweep(const exp_run *exp)
{
    size_t n = exp->quick ? 100000 : 1000000; /* Tyler's 10^6 */
    double *err = malloc(sizeof *err * n);
    if (!err)
        exp_die("out of memory");
    exp_table *t = exp_table_new("Octahedral normals vs bits per coordinate (S5; Cigolle et al. 2014 style, "
                                 "Tyler 2024 side by side)",
                                 "bits,total bits,SNORM mean deg,SNORM max deg,SNORM precise mean deg,"
                                 "SNORM precise max deg,UNORM cube-points mean deg,UNORM cube-points max deg,"
                                 "Tyler mean deg,Tyler max deg,UNORM uniform mean deg,uniform vs cube mean %");
    oct_stats tyler12 = {0, 0}, uni12 = {0, 0};
    double worst_mean_off = 0.0;
    for (int bits = 8; bits <= 16; ++bits) {
        sol_oct_options plain = {bits, 0, SOL_OCT_SNORM}, precise = {bits, 1, SOL_OCT_SNORM},
                        unorm = {bits, 0, SOL_OCT_UNORM};
        oct_stats sp = oct_errors(&plain, 0, n, err), spp = oct_errors(&precise, 0, n, err);
        oct_stats uc = oct_errors(&unorm, 1, n, err), uu = oct_errors(&unorm, 0, n, err);
        char tm[32] = "-", tx[32] = "-";
        for (int k = 0; k < N_TYLER; ++k)
            if (tyler[k].bits == bits) {
                snprintf(tm, sizeof tm, "%.6f", tyler[k].mean);
                snprintf(tx, sizeof tx, "%.6f", tyler[k].max);
                double off = fabs(uc.mean / tyler[k].mean - 1.0);
                worst_mean_off = off > worst_mean_off ? off : worst_mean_off;
            }
        if (bits == 12) {
            tyler12 = uc;
            uni12 = uu;
        }
        exp_table_row(t, "%d|%d|%.6f|%.6f|%.6f|%.6f|%.6f|%.6f|%s|%s|%.6f|%+.2f", bits, 2 * bits, sp.mean, sp.max,
                      spp.mean, spp.max, uc.mean, uc.max, tm, tx, uu.mean, 100.0 * (uu.mean / uc.mean - 1.0));
        exp_progress("octahedral sweep", (size_t)bits - 7, 9);
    }
    exp_progress_done("octahedral sweep");
    exp_table_write(t, exp, "octahedral_bits");
    exp_number(exp, "S5-tyler12-mean", "%.6f", tyler12.mean);
    exp_number(exp, "S5-tyler12-max", "%.6f", tyler12.max);
    exp_number(exp, "S5-tyler12-uniform-mean", "%.6f", uni12.mean);
    exp_number(exp, "S5-tyler12-uniform-drop-percent", "%.1f", 100.0 * (1.0 - uni12.mean / tyler12.mean));
    exp_number(exp, "S5-tyler-worst-mean-offset-percent", "%.2f", 100.0 * worst_mean_off);
    free(err);
}

/* ---- --bench: the octahedral map's knobs (bits, rounding, quantizer), error vs time ---- */
typedef struct oct_timing {
    const sol_oct_options *o;      /* NULL: the 24-bit peer `method` */
    sol_normal_method method;
    const double *dirs;
    size_t n;
    double sink;
} oct_timing;

static void time_oct(void *p)
{
    oct_timing *c = p;
    double acc = 0.0;
    for (size_t i = 0; i < c->n; ++i) {
        double back[3];
        if (c->o) {
            uint32_t code[2];
            sol_oct_encode(c->o, c->dirs + 3 * i, code);
            sol_oct_decode(c->o, code, back);
        } else {
            uint32_t code;
            sol_normal_encode(c->method, c->dirs + 3 * i, &code);
            sol_normal_decode(c->method, code, back);
        }
        acc += back[0];
    }
    c->sink += acc; /* keeps the work observable */
}

/* Mean and max error of a 24-bit peer over the same uniform directions as oct_errors. */
static oct_stats peer_errors(sol_normal_method m, size_t n, double *err)
{
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < (int64_t)n; ++i) {
        double d[3], back[3];
        uint32_t code;
        set_direction(0, (uint64_t)i, d);
        exp_check(sol_normal_encode(m, d, &code), "encode");
        exp_check(sol_normal_decode(m, code, back), "decode");
        err[i] = sol_angle3(d, back) * DEG;
    }
    return oct_stats_of(err, n);
}

void run_oct_bench(const exp_run *exp)
{
    const size_t n = exp->quick ? 100000 : 1000000, tn = 4096;
    double *err = malloc(sizeof *err * n), *dirs = malloc(sizeof *dirs * 3 * tn);
    if (!err || !dirs)
        exp_die("out of memory");
    for (size_t i = 0; i < tn; ++i) /* directions the error set does not use */
        set_direction(0, 50000017 + i, dirs + 3 * i);
    exp_table *t = exp_table_new("Octahedral map knobs (S5): bits per coordinate, rounding, quantizer; angular error over "
                                 "uniform directions and time per normal (encode + decode, one thread); 24-bit peers "
                                 "on the same directions",
                                 "encoding,bits per coordinate,rounding,quantizer,mean deg,max deg,core-ns per normal");
    static const sol_normal_method peers[] = {SOL_NORMAL_XYZ_NORMALIZED, SOL_NORMAL_XYZ_BEST_FIT, SOL_NORMAL_SPHERICAL_12};
    for (size_t k = 0; k < sizeof peers / sizeof *peers; ++k) {
        oct_stats s = peer_errors(peers[k], n, err);
        oct_timing c = {NULL, peers[k], dirs, tn, 0.0};
        double ns = exp_cpu_time_per_item_ns(time_oct, &c, tn, 15);
        exp_table_row(t, "peer: %s|-|-|-|%.6f|%.6f|%.1f", sol_normal_method_name(peers[k]), s.mean, s.max, ns);
    }
    for (int bits = 8; bits <= 16; bits += 2)
        for (int v = 0; v < 3; ++v) {
            sol_oct_options o = {bits, v == 1, v == 2 ? SOL_OCT_UNORM : SOL_OCT_SNORM};
            oct_stats s = oct_errors(&o, 0, n, err);
            oct_timing c = {&o, SOL_NORMAL_OCTAHEDRAL_12, dirs, tn, 0.0};
            double ns = exp_cpu_time_per_item_ns(time_oct, &c, tn, 15);
            exp_table_row(t, "octahedral|%d|%s|%s|%.6f|%.6f|%.1f", bits, v == 1 ? "precise (best of 4)" : "nearest",
                          v == 2 ? "UNORM" : "SNORM", s.mean, s.max, ns);
        }
    exp_table_write(t, exp, "octahedral_knobs");
    free(dirs);
    free(err);
}
