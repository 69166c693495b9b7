/* m2_depth_packing - linear depth in two 8-bit channels as the rational x + y/255 (claim M2).
 *
 * Talk, slide "SSAO improvements": "Encode depth as 2 channel 16-bits value [0;1], linear depth
 * as a rational: depth = x + y/255", stored in an ARGB8 target beside the SSAO terms. This driver
 * measures the precision of that split against 16- and 24-bit UNORM depth, what the 8-bit
 * rounding of x and y does at the cell edges, and that filtering the two channels filters depth. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp_harness.h"
#include "sol_hdr.h"

typedef enum depth_code { UNORM16, UNORM24, RG8_RATIONAL, RG8_ROUNDED_X, CODE_COUNT } depth_code;
static const char *code_name[CODE_COUNT] = {"UNORM16", "UNORM24", "RG8 x + y/255 (x = floor)",
                                            "RG8 x + y/255, x rounded by the UNORM write"};

static double round_trip(depth_code c, double d)
{
    uint8_t xy[2];
    switch (c) {
    case UNORM16: return sol_unorm_decode(sol_unorm_encode(d, 16), 16);
    case UNORM24: return (double)(uint32_t)floor(d * 16777215.0 + 0.5) / 16777215.0; /* sol_unorm_* stop at 16 */
    case RG8_RATIONAL: sol_depth_rg8_encode(d, xy); return sol_depth_rg8_decode(xy);
    default: sol_depth_rg8_encode_rounded_x(d, xy); return sol_depth_rg8_decode(xy);
    }
}

typedef struct depth_error {
    double max_abs, rms, pct_over_half_x_step; /* share of depths off by more than 1/510 */
} depth_error;

/* Dense sweep of [0, 1]; partial sums per fixed chunk, combined in order (thread-count independent). */
static depth_error measure(depth_code c, int samples)
{
    enum { CHUNKS = 64 };
    double part_max[CHUNKS] = {0}, part_sq[CHUNKS] = {0}, part_big[CHUNKS] = {0};
#pragma omp parallel for schedule(static)
    for (int ch = 0; ch < CHUNKS; ++ch)
        for (int i = ch; i <= samples; i += CHUNKS) {
            double d = (double)i / samples, e = fabs(round_trip(c, d) - d);
            part_max[ch] = fmax(part_max[ch], e);
            part_sq[ch] += e * e;
            part_big[ch] += e > 1.0 / 510.0;
        }
    depth_error r = {0, 0, 0};
    for (int ch = 0; ch < CHUNKS; ++ch) {
        r.max_abs = fmax(r.max_abs, part_max[ch]);
        r.rms += part_sq[ch];
        r.pct_over_half_x_step += part_big[ch];
    }
    r.rms = sqrt(r.rms / (samples + 1.0));
    r.pct_over_half_x_step *= 100.0 / (samples + 1.0);
    return r;
}

typedef struct time_job {
    depth_code code;
    double sink;
} time_job;

static void run_round_trips(void *ctx)
{
    time_job *job = ctx;
    double acc = 0.0;
    for (int i = 0; i < 65536; ++i)
        acc += round_trip(job->code, i / 65535.0 * 0.999);
    job->sink = acc;
}

/* Every one of the 65536 (x, y) code pairs: how many distinct depths, how many above 1. */
static void code_space(int *distinct_in_unit, int *above_one, int *redundant)
{
    int seen = 0, over = 0;
    /* x/255 + y/65025 = (255x + y)/65025: distinct values are the distinct integers 255x + y. */
    static unsigned char hit[255 * 255 + 256];
    for (int x = 0; x < 256; ++x)
        for (int y = 0; y < 256; ++y) {
            int v = 255 * x + y;
            if (!hit[v]) {
                hit[v] = 1;
                seen += v <= 65025;
                over += v > 65025;
            }
        }
    *distinct_in_unit = seen;
    *above_one = over;
    *redundant = 65536 - seen - over;
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "m2_depth_packing", argc, argv);
    const int samples = exp.quick ? 1000003 : 16000057; /* not a multiple of 255: no aligned sampling */
    exp_table *t = exp_table_new("Linear depth encodings over [0, 1]",
                                 "encoding,bits,step,max abs error,RMS error,% depths off > 1/510,"
                                 "max error at 1 km far plane (mm),ns per round trip");
    depth_error err[CODE_COUNT];
    const int bits[CODE_COUNT] = {16, 24, 16, 16};
    const double step[CODE_COUNT] = {1.0 / 65535.0, 1.0 / 16777215.0, 1.0 / 65025.0, 1.0 / 65025.0};
    for (int c = 0; c < CODE_COUNT; ++c) {
        err[c] = measure((depth_code)c, samples);
        time_job job = {(depth_code)c, 0};
        double ns = exp_cpu_time_per_item_ns(run_round_trips, &job, 65536, exp.quick ? 3 : 9);
        exp_table_row(t, "%s|%d|%.3e|%.3e|%.3e|%.3f|%.3f|%.1f", code_name[c], bits[c], step[c], err[c].max_abs,
                      err[c].rms, err[c].pct_over_half_x_step, err[c].max_abs * 1e6, ns);
    }
    exp_table_write(t, &exp, "depth_precision");
    if (exp.bench)
        return 0;

    int distinct, above, redundant;
    code_space(&distinct, &above, &redundant);
    exp_table *cs = exp_table_new("The 65536 (x, y) code pairs of x + y/255", "quantity,count");
    exp_table_row(cs, "distinct depths in [0, 1]|%d", distinct);
    exp_table_row(cs, "distinct depths above 1 (x = 255, y > 0)|%d", above);
    exp_table_row(cs, "pairs duplicating another (y = 255 equals x + 1, y = 0)|%d", redundant);
    exp_table_write(cs, &exp, "code_space");

    /* Filtering the two channels (bilinear, bilateral taps) filters depth: decode is linear. */
    double worst_filter = 0.0;
    for (int i = 0; i < 100000; ++i) {
        double a = i / 100000.0, b = fmod(a * 7.31 + 0.123, 1.0), w = fmod(a * 13.7, 1.0);
        uint8_t ca[2], cb[2];
        sol_depth_rg8_encode(a, ca);
        sol_depth_rg8_encode(b, cb);
        double fx = (1 - w) * ca[0] + w * cb[0], fy = (1 - w) * ca[1] + w * cb[1];
        double filtered = fx / 255.0 + fy / 65025.0;
        double expect = (1 - w) * sol_depth_rg8_decode(ca) + w * sol_depth_rg8_decode(cb);
        worst_filter = fmax(worst_filter, fabs(filtered - expect));
    }

    FILE *f = exp_open(&exp, "edge_errors.csv");
    fputs("depth,UNORM16,rational,rounded_x\n", f);
    const double lo = 100.0 / 255.0 - 1.0 / 255.0, hi = 100.0 / 255.0 + 1.0 / 255.0;
    for (int i = 0; i <= 4000; ++i) {
        double d = lo + (hi - lo) * i / 4000.0;
        fprintf(f, "%.9f,%.6e,%.6e,%.6e\n", d, fabs(round_trip(UNORM16, d) - d), fabs(round_trip(RG8_RATIONAL, d) - d),
                fabs(round_trip(RG8_ROUNDED_X, d) - d));
    }
    fclose(f);
    exp_plot(&exp, "edge_errors",
             "set datafile separator comma\nset grid\nset logscale y\nset format y '10^{%%L}'\nset yrange [1e-9:1e-2]\n"
             "set xlabel 'linear depth (around x = 100/255)'\nset ylabel '|decoded - depth|'\nset key top left\n"
             "plot 'edge_errors.csv' using 1:($2+1e-12) with lines title 'UNORM16', "
             "'' using 1:($3+1e-12) with lines lw 2 title 'x + y/255 (x = floor)', "
             "'' using 1:($4+1e-12) with lines title 'x rounded by the UNORM write'");

    char fig[256];
    snprintf(fig, sizeof fig, "step 1/65025 (UNORM16 1/65535); max error %.3e (UNORM16 %.3e); rounded x: %.3e",
             err[RG8_RATIONAL].max_abs, err[UNORM16].max_abs, err[RG8_ROUNDED_X].max_abs);
    int as_good = err[RG8_RATIONAL].max_abs <= 0.5 / 65025.0 * (1.0 + 1e-9);
    exp_claim(&exp, "M2", "linear depth as x + y/255 in two 8-bit channels", fig, "max error <= half a step",
              as_good ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the split keeps %d distinct depths in [0,1] (16-bit UNORM: 65536) with worst error half a step; x must be "
              "floor(255 d) - if the 8-bit write rounds x instead, %.1f%% of depths are off by up to one x step (1/255); "
              "filtering the channels filters depth exactly (max deviation %.1e)",
              distinct, err[RG8_ROUNDED_X].pct_over_half_x_step, worst_filter);
    return 0;
}
