/* s3_s6_aces_exposure - Narkowicz's ACES fit against the ACES reference (claim S3) and automatic
 * exposure on a sequence of synthetic HDR frames (claim S6).
 *
 * S3: the blog note says the fit x(2.51x+0.03)/(x(2.43x+0.59)+0.14) was fitted to ODT(RRT(x))
 * (Rec.709 D65 with its 2.4 gamma removed), "pre-exposed" so that 1 maps to ~0.8, with max fit
 * error 0.0138, and that the original curve is obtained by multiplying the input by 0.6. The
 * reference here is sol_aces_reference (ACES 1.0 RRT + ODT Rec.709 100 nits dim, grey input).
 * The input scale s in fit(x) ~ ref(s x) is the unknown: the driver reports the error for the
 * scales the note implies (1/0.6) and for a one-stop pre-exposure (2), and sweeps s to show where
 * the error is smallest. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp_harness.h"
#include "sol_hdr.h"

static const double fit_x_max = 16.0; /* the fit is clamped to 1 from x ~ 7.24 on */

typedef struct fit_error {
    double max_abs, at_x, max_abs_srgb, mean_abs;
} fit_error;

static fit_error measure_fit(double scale, double x_max, int samples)
{
    fit_error e = {0, 0, 0, 0};
    for (int i = 0; i <= samples; ++i) {
        double x = x_max * i / samples;
        double f = sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x), r = sol_aces_reference(scale * x);
        double d = fabs(f - r), ds = fabs(sol_srgb_encode(f) - sol_srgb_encode(r));
        if (d > e.max_abs) {
            e.max_abs = d;
            e.at_x = x;
        }
        e.max_abs_srgb = fmax(e.max_abs_srgb, ds);
        e.mean_abs += d / (samples + 1);
    }
    return e;
}

typedef struct eval_job {
    int use_fit;
    double sink;
} eval_job;

static void run_evals(void *ctx)
{
    eval_job *job = ctx;
    double acc = 0.0;
    for (int i = 0; i < 4096; ++i) {
        double x = 8.0 * i / 4096.0;
        acc += job->use_fit ? sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x) : sol_aces_reference(2.0 * x);
    }
    job->sink = acc;
}

/* ---- S3, second reference: Stephen Hill's ACESFitted (sol_aces_hill_fit) ---- */
typedef struct hill_result {
    double fit_vs_hill_2x, fit_vs_hill_stated, best_scale, best_err, hill_vs_ref, hill_vs_ref_at, colour_err;
} hill_result;

/* max |Narkowicz(x) - Hill(s x)| on grey, x in [0, x_max] */
static double fit_vs_hill(double scale, double x_max, int samples)
{
    double worst = 0.0;
    for (int i = 0; i <= samples; ++i) {
        double x = x_max * i / samples, g[3] = {scale * x, scale * x, scale * x}, h[3];
        sol_aces_hill_fit(g, h);
        worst = fmax(worst, fabs(sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x) - h[1]));
    }
    return worst;
}

static hill_result s3_hill(const exp_run *exp)
{
    const int samples = exp->quick ? 2000 : 16000;
    hill_result r = {0};
    r.fit_vs_hill_2x = fit_vs_hill(2.0, fit_x_max, samples);
    r.fit_vs_hill_stated = fit_vs_hill(1.0 / 0.6, fit_x_max, samples);
    r.best_err = INFINITY;
    for (int k = 0; k <= (exp->quick ? 150 : 750); ++k) { /* scale 1.0 .. 2.5 */
        double sc = 1.0 + 1.5 * k / (exp->quick ? 150 : 750), e = fit_vs_hill(sc, fit_x_max, samples / 8);
        if (e < r.best_err)
            r.best_err = e, r.best_scale = sc;
    }
    r.best_err = fit_vs_hill(r.best_scale, fit_x_max, samples);
    /* The two references on grey: Hill's fit (sRGB ODT) vs ACES 1.0 Rec.709 100 nits dim. */
    for (int i = 0; i <= samples; ++i) {
        double x = fit_x_max * i / samples, g[3] = {x, x, x}, h[3];
        sol_aces_hill_fit(g, h);
        double d = fabs(h[1] - sol_aces_reference(x));
        if (d > r.hill_vs_ref)
            r.hill_vs_ref = d, r.hill_vs_ref_at = x;
    }
    /* Colour: Narkowicz per channel (one-stop pre-exposed) vs Hill's matrices on saturated colours,
     * 12 hues x exposures 2^-4 .. 2^4. */
    for (int hue = 0; hue < 12; ++hue)
        for (int ev = -4; ev <= 4; ++ev) {
            double a = 2.0 * M_PI * hue / 12.0, c[3];
            for (int k = 0; k < 3; ++k)
                c[k] = ldexp(fmax(0.0, cos(a - 2.0 * M_PI * k / 3.0)) + 0.02, ev);
            double h[3], two[3] = {2 * c[0], 2 * c[1], 2 * c[2]};
            sol_aces_hill_fit(two, h);
            for (int k = 0; k < 3; ++k)
                r.colour_err = fmax(r.colour_err, fabs(sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, c[k]) - h[k]));
        }
    exp_table *t = exp_table_new("Second reference: Stephen Hill's ACESFitted (RRT + sRGB ODT fit), grey x in [0,16] "
                                 "unless said",
                                 "comparison,input scale s,max abs error,at x");
    exp_table_row(t, "Narkowicz fit(x) vs Hill(s x), one stop|2.0000|%.4f|-", r.fit_vs_hill_2x);
    exp_table_row(t, "Narkowicz fit(x) vs Hill(s x), note's 1/0.6|%.4f|%.4f|-", 1.0 / 0.6, r.fit_vs_hill_stated);
    exp_table_row(t, "Narkowicz fit(x) vs Hill(s x), best s|%.4f|%.4f|-", r.best_scale, r.best_err);
    exp_table_row(t, "Hill(x) vs ACES 1.0 Rec.709 dim reference (x)|1.0000|%.4f|%.3f", r.hill_vs_ref, r.hill_vs_ref_at);
    exp_table_row(t, "Narkowicz per channel vs Hill's saturation matrices, 12 saturated hues x 2^-4..2^4|2.0000|%.4f|-",
                  r.colour_err);
    exp_table_write(t, exp, "hill_reference");
    if (exp->bench)
        return r;
    FILE *csv = exp_open(exp, "hill_curves.csv");
    fputs("x,narkowicz,hill_2x,aces_ref_2x\n", csv);
    for (int i = 0; i <= 800; ++i) {
        double x = 8.0 * i / 800.0, g[3] = {2 * x, 2 * x, 2 * x}, h[3];
        sol_aces_hill_fit(g, h);
        fprintf(csv, "%.4f,%.6f,%.6f,%.6f\n", x, sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x), h[1],
                sol_aces_reference(2.0 * x));
    }
    fclose(csv);
    exp_plot(exp, "aces_two_references",
             "set datafile separator comma\nset key autotitle columnhead bottom right\nset grid\n"
             "set xlabel 'x (scene value)'\nset ylabel 'linear display value'\n"
             "plot 'hill_curves.csv' using 1:2 with lines lw 2 title 'Narkowicz fit(x)', "
             "'' using 1:3 with lines lw 2 title 'Hill ACESFitted(2x)', '' using 1:4 with lines dt 2 title 'ACES 1.0 ref(2x)'");
    exp_number(exp, "S3-hill-fit-err-2x", "%.4f", r.fit_vs_hill_2x);
    exp_number(exp, "S3-hill-fit-err-best", "%.4f", r.best_err);
    exp_number(exp, "S3-hill-best-scale", "%.3f", r.best_scale);
    exp_number(exp, "S3-hill-vs-ref", "%.4f", r.hill_vs_ref);
    exp_number(exp, "S3-hill-colour-err", "%.4f", r.colour_err);
    return r;
}

static double s3_aces_fit(const exp_run *exp)
{
    const int samples = exp->quick ? 2000 : 16000;
    /* Sweep of the input scale (each scale independent: parallel and order-free). */
    const double s_lo = 1.0, s_step = exp->quick ? 0.01 : 0.002;
    const int n_scales = (int)((2.5 - s_lo) / s_step) + 1;
    double *sweep = malloc(sizeof *sweep * (size_t)n_scales);
    if (!sweep)
        exp_die("out of memory");
#pragma omp parallel for schedule(dynamic, 4)
    for (int k = 0; k < n_scales; ++k)
        sweep[k] = measure_fit(s_lo + k * s_step, fit_x_max, samples / 4).max_abs;
    int best = 0;
    FILE *csv = exp_open(exp, "scale_sweep_curve.csv");
    fputs("scale,max_abs_error\n", csv);
    for (int k = 0; k < n_scales; ++k) {
        fprintf(csv, "%.4f,%.6f\n", s_lo + k * s_step, sweep[k]);
        best = sweep[k] < sweep[best] ? k : best;
    }
    fclose(csv);
    double s_best = s_lo + best * s_step, sweep_min = sweep[best];
    free(sweep);

    exp_table *t = exp_table_new("ACES fit vs ACES 1.0 RRT+ODT (Rec.709 100 nits dim, grey, linear), x in [0,16]",
                                 "input scale s in ref(s x),s,max abs error,at x,max abs error (sRGB-encoded),mean abs error");
    const struct { const char *label; double s; } rows[] = {
        {"none", 1.0}, {"note's 'multiply input by 0.6' (1/0.6)", 1.0 / 0.6}, {"one stop pre-exposure", 2.0},
        {"smallest max error in the sweep", s_best}};
    double one_stop = 0.0, one_stop_at = 0.0;
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
        fit_error e = measure_fit(rows[r].s, fit_x_max, samples);
        if (rows[r].s == 2.0)
            one_stop = e.max_abs, one_stop_at = e.at_x;
        exp_table_row(t, "%s|%.4f|%.4f|%.3f|%.4f|%.4f", rows[r].label, rows[r].s, e.max_abs, e.at_x, e.max_abs_srgb,
                      e.mean_abs);
    }
    exp_table_write(t, exp, "fit_error");

    exp_table *ranges = exp_table_new("ACES fit error (one stop pre-exposure) over the input range",
                                      "x range,max abs error,at x");
    const double x_max[] = {0.5, 1.0, 2.0, 4.0, 16.0, 100.0};
    for (size_t r = 0; r < sizeof x_max / sizeof x_max[0]; ++r) {
        fit_error e = measure_fit(2.0, x_max[r], samples);
        exp_table_row(ranges, "[0, %g]|%.4f|%.3f", x_max[r], e.max_abs, e.at_x);
    }
    exp_table_write(ranges, exp, "fit_error_ranges");

    eval_job fit = {1, 0}, ref = {0, 0};
    double ns_fit = exp_cpu_time_per_item_ns(run_evals, &fit, 4096, exp->quick ? 3 : 9);
    double ns_ref = exp_cpu_time_per_item_ns(run_evals, &ref, 4096, exp->quick ? 3 : 9);
    exp_table *cost = exp_table_new("ACES: fit vs reference, accuracy vs time", "curve,max abs error,ns per value");
    exp_table_row(cost, "ACES fit (Narkowicz)|%.4f|%.1f", one_stop, ns_fit);
    exp_table_row(cost, "RRT+ODT reference (grey)|0|%.1f", ns_ref);
    exp_table_write(cost, exp, "fit_cost");
    if (exp->bench)
        return one_stop;

    csv = exp_open(exp, "aces_curves.csv");
    fputs("x,fit,ref_2x,ref_x_over_0.6,error_2x\n", csv);
    for (int i = 0; i <= 800; ++i) {
        double x = 8.0 * i / 800.0, f = sol_tonemap_apply(SOL_TONEMAP_ACES_FIT, x);
        fprintf(csv, "%.4f,%.6f,%.6f,%.6f,%.6f\n", x, f, sol_aces_reference(2.0 * x), sol_aces_reference(x / 0.6),
                f - sol_aces_reference(2.0 * x));
    }
    fclose(csv);
    exp_plot(exp, "aces_fit_vs_reference",
             "set datafile separator comma\nset key autotitle columnhead bottom right\nset grid\n"
             "set xlabel 'x (scene value)'\nset ylabel 'linear display value'\nset y2label 'fit - ref(2x)'\n"
             "set y2tics\nset ytics nomirror\n"
             "plot 'aces_curves.csv' using 1:2 with lines lw 2 title 'ACES fit', "
             "'' using 1:3 with lines lw 2 title 'RRT+ODT ref(2x)', '' using 1:4 with lines dt 2 title 'ref(x/0.6)', "
             "'' using 1:5 axes x1y2 with lines lc rgb 'red' title 'fit - ref(2x) (right axis)'");
    exp_plot(exp, "fit_error_vs_scale",
             "set datafile separator comma\nset grid\nset xlabel 'input scale s in ref(s x)'\n"
             "set ylabel 'max |fit(x) - ref(s x)|, x in [0,16]'\nset logscale y\n"
             "plot 'scale_sweep_curve.csv' using 1:2 with lines lw 2 notitle");
    hill_result hill = s3_hill(exp);
    fit_error stated = measure_fit(1.0 / 0.6, fit_x_max, samples);
    exp_number(exp, "S3-fit-err-2x", "%.4f", one_stop);
    exp_number(exp, "S3-fit-err-2x-at", "%.1f", one_stop_at);
    exp_number(exp, "S3-fit-err-stated", "%.4f", stated.max_abs);
    exp_number(exp, "S3-stated-over-2x", "%.1f", stated.max_abs / one_stop);
    exp_number(exp, "S3-sweep-best-scale", "%.3f", s_best);
    exp_number(exp, "S3-sweep-min", "%.4f", sweep_min);
    char fig[256];
    snprintf(fig, sizeof fig, "%.4f with ref(2x) (one stop pre-exposure); %.4f with ref(x/0.6)", one_stop,
             stated.max_abs);
    exp_claim(exp, "S3", "ACES fit max error 0.0138", fig, "+-0.0005",
              fabs(one_stop - 0.0138) <= 5e-4 ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "reference: ACES 1.0 RRT + ODT Rec.709 100 nits dim on grey, linear (2.4 gamma removed), x in [0,16]; the "
              "fit matches ref(2x), a one-stop pre-exposure (smallest max error %.4f at s = %.3f), not the note's "
              "'multiply by 0.6' (s = 1/0.6); second reference, Hill's ACESFitted: fit(x) vs Hill(2x) %.4f, best %.4f at "
              "s = %.3f, Hill vs the ACES 1.0 reference %.4f on grey (hill_reference table)%s",
              sweep_min, s_best, hill.fit_vs_hill_2x, hill.best_err, hill.best_scale, hill.hill_vs_ref,
              fabs(hill.fit_vs_hill_2x - 0.0138) <= 5e-4 ? "; Hill's fit as the reference also gives 0.0138 within the tolerance"
                                                         : "; Hill's fit as the reference does not give 0.0138 within the "
                                                           "tolerance, so the figure belongs to the ACES 1.0 transforms "
                                                           "themselves; per channel on saturated colours the fit departs "
                                                           "from Hill's matrices (hill_reference table)");
    return one_stop;
}

/* ---- S6: a camera walking from a dark interior out into sunlight ---- */
enum { FRAME_W = 96, FRAME_H = 64 };

/* Deterministic hash noise in [0, 1) for texture. */
static double hash01(unsigned x, unsigned y, unsigned f)
{
    unsigned h = x * 374761393u + y * 668265263u + f * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return (double)((h ^ (h >> 16)) & 0xffffu) / 65536.0;
}

/* Frame `f` of `n`: the doorway (outdoor region) grows from 5% to 100% of the frame; the sun
 * (1e6 cd/m^2, 0.3% of the pixels) is in view during the middle third. Luminances in cd/m^2. */
static void render_frame(int f, int n, float *lum)
{
    double open = 0.05 + 0.95 * fmin(1.0, fmax(0.0, (f - 0.2 * n) / (0.6 * n)));
    int door_w = (int)(open * FRAME_W), door_x = (FRAME_W - door_w) / 2;
    int sun = f > n / 3 && f < 2 * n / 3;
    for (int y = 0; y < FRAME_H; ++y)
        for (int x = 0; x < FRAME_W; ++x) {
            double t = hash01((unsigned)x, (unsigned)y, 7u), v;
            if (x >= door_x && x < door_x + door_w)
                v = y < FRAME_H / 3 ? 6000.0 + 2000.0 * t : 800.0 + 2500.0 * t; /* sky / sunlit ground */
            else
                v = 0.3 + 8.0 * t * t; /* interior */
            if (sun && (x - FRAME_W / 2) * (x - FRAME_W / 2) + (y - 6) * (y - 6) <= 2)
                v = 1e6;
            lum[y * FRAME_W + x] = (float)v;
        }
}

static double log_average(const float *lum, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += log2(lum[i]);
    return exp2(s / n);
}

static double arithmetic_mean(const float *lum, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i)
        s += lum[i];
    return s / n;
}

static void s6_exposure(const exp_run *exp)
{
    const int frames = 180;
    const double dt = 1.0 / 30.0, rate = 1.5;
    float lum[FRAME_W * FRAME_H];
    FILE *csv = exp_open(exp, "exposure_frames.csv");
    fputs("time_s,ev_arithmetic_mean,ev_log_average,ev_metered_no_skip,ev_metered,ev_adapted,key,exposure_ev\n", csv);
    exp_table *t = exp_table_new("Automatic exposure over a dark-interior-to-sunlight walk (EV100)",
                                 "frame,sun in view,mean EV,log-average EV,histogram EV (no skip),histogram EV (skip 60%/10%),"
                                 "adapted EV,Krawczyk key");
    double adapted = 0.0, jump[3] = {0, 0, 0}, prev[3] = {0, 0, 0};
    sol_meter_options no_skip = {.skip_dark = -1, .skip_bright = -1};
    for (int f = 0; f < frames; ++f) {
        render_frame(f, frames, lum);
        double mean = arithmetic_mean(lum, FRAME_W * FRAME_H), avg = log_average(lum, FRAME_W * FRAME_H), meter_all, meter;
        exp_check(sol_histogram_meter(lum, FRAME_W * FRAME_H, &no_skip, &meter_all, NULL), "metering");
        exp_check(sol_histogram_meter(lum, FRAME_W * FRAME_H, NULL, &meter, NULL), "metering");
        adapted = f == 0 ? meter : sol_adapt_exponential(adapted, meter, dt, rate);
        double key = sol_krawczyk_key(adapted), exposure;
        exp_check(sol_exposure_from_luminance(adapted, 0.0, &exposure), "exposure");
        double now[3] = {log2(mean), log2(avg), log2(meter)};
        for (int k = 0; k < 3; ++k) {
            if (f == frames / 3 + 1) /* the sun enters the frame */
                jump[k] = now[k] - prev[k];
            prev[k] = now[k];
        }
        fprintf(csv, "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", f * dt, sol_ev100_from_luminance(mean),
                sol_ev100_from_luminance(avg),
                sol_ev100_from_luminance(meter_all), sol_ev100_from_luminance(meter), sol_ev100_from_luminance(adapted),
                key, log2(exposure));
        if (f % 20 == 0 || f == frames / 3 + 1)
            exp_table_row(t, "%d|%s|%.2f|%.2f|%.2f|%.2f|%.2f|%.3f", f,
                          f > frames / 3 && f < 2 * frames / 3 ? "yes" : "no", sol_ev100_from_luminance(mean),
                          sol_ev100_from_luminance(avg), sol_ev100_from_luminance(meter_all),
                          sol_ev100_from_luminance(meter), sol_ev100_from_luminance(adapted), key);
    }
    fclose(csv);
    exp_table_write(t, exp, "exposure_sequence");
    FILE *kc = exp_open(exp, "krawczyk_curve.csv");
    fputs("ev100,key\n", kc);
    for (int i = 0; i <= 200; ++i) {
        double ev = -4.0 + 20.0 * i / 200.0;
        fprintf(kc, "%.3f,%.5f\n", ev, sol_krawczyk_key(sol_luminance_from_ev100(ev)));
    }
    fclose(kc);
    exp_plot(exp, "exposure_over_time",
             "set datafile separator comma\nset key autotitle columnhead top left\nset grid\n"
             "set xlabel 'time (s)'\nset ylabel 'EV100'\n"
             "plot for [i=2:5] 'exposure_frames.csv' using 1:i with lines lw 2, '' using 1:6 with lines lw 4");
    exp_plot(exp, "krawczyk_key",
             "set datafile separator comma\nset grid\nset xlabel 'EV100'\nset ylabel 'key value'\n"
             "plot 'krawczyk_curve.csv' using 1:2 with lines lw 2 title '1.03 - 2/(log10(L+1)+2)'");
    char fig[256];
    snprintf(fig, sizeof fig, "sun entering the frame: mean %+.2f EV, log-average %+.2f EV, histogram (skip 60%%/10%%) %+.2f EV",
             jump[0], jump[1], jump[2]);
    exp_number(exp, "S6-frames", "%d", frames);
    exp_number(exp, "S6-jump-mean-ev", "%.2f", jump[0]);
    exp_number(exp, "S6-jump-logavg-ev", "%.2f", jump[1]);
    exp_number(exp, "S6-jump-meter-ev", "%.2f", jump[2]);
    /* The verdict checks what the note states: the sun moves the mean most, the trimmed histogram least. */
    const int trimmed_ignores_sun = fabs(jump[2]) <= fabs(jump[1]) && fabs(jump[1]) < fabs(jump[0]);
    exp_claim(exp, "S6", "EV units, histogram metering skipping darkest/brightest, Krawczyk key, exponential adaptation",
              fig, "qualitative", trimmed_ignores_sun ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "a 180-frame interior-to-sunlight walk: a 1e6 cd/m2 sun on 5 of 6144 pixels moves the arithmetic mean, "
              "barely the log average and not the trimmed histogram; the trimmed meter follows the bright part "
              "(~1-6 EV above the log average) and the adaptation (rate %.1f/s) smooths the step",
              rate);
}

/* ---- --bench: the histogram meter's bin count, EV error vs time ---- */
static int cmp_ev(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The meter without a histogram: EV100 of every pixel sorted, the darkest 60% and brightest 10% of
 * the pixels dropped (fractional pixels at the cuts), the rest averaged: the limit of
 * sol_histogram_meter's default as its bins get narrow (the scene's EVs lie inside -8..24). */
static double exact_meter_ev(const float *lum, int n, double *ev)
{
    for (int i = 0; i < n; ++i)
        ev[i] = sol_ev100_from_luminance(lum[i]);
    qsort(ev, (size_t)n, sizeof *ev, cmp_ev);
    const double lo = 0.6 * n, hi = (1.0 - 0.1) * n;
    double sum = 0.0, weight = 0.0;
    for (int i = 0; i < n; ++i) {
        double w = fmin(i + 1.0, hi) - fmax((double)i, lo); /* pixel i covers [i, i + 1) */
        if (w > 0.0) {
            sum += w * ev[i];
            weight += w;
        }
    }
    return sum / weight;
}

typedef struct meter_timing {
    const float *frames;
    int count, bins; /* bins 0: the exact sorted meter */
    double *scratch, sink;
} meter_timing;

static void time_meter(void *ctx)
{
    meter_timing *c = ctx;
    const int n = FRAME_W * FRAME_H;
    for (int f = 0; f < c->count; ++f) {
        const float *lum = c->frames + (size_t)f * n;
        if (c->bins == 0) {
            c->sink += exact_meter_ev(lum, n, c->scratch);
        } else {
            sol_meter_options o = {.bins = c->bins};
            double m;
            exp_check(sol_histogram_meter(lum, (size_t)n, &o, &m, NULL), "metering");
            c->sink += m;
        }
    }
}

/* Written only with --bench (meter_knobs): the bin count of sol_histogram_meter (over EV -8..24,
 * skipping 60%/10%) against the exact sorted meter on the S6 walk's frames, with its time per pixel
 * beside the exact meter's (the peer: a sort instead of a histogram). */
static void bench_meter(const exp_run *exp)
{
    const int frames = exp->quick ? 60 : 180, n = FRAME_W * FRAME_H;
    float *lum = malloc(sizeof *lum * (size_t)frames * n);
    double *scratch = malloc(sizeof *scratch * n), *exact = malloc(sizeof *exact * frames);
    if (!lum || !scratch || !exact)
        exp_die("out of memory");
    for (int f = 0; f < frames; ++f) {
        render_frame(f, frames, lum + (size_t)f * n);
        exact[f] = exact_meter_ev(lum + (size_t)f * n, n, scratch);
    }
    exp_table *t = exp_table_new("Histogram metering (S6): bins over EV -8..24 vs the exact trimmed log average of the "
                                 "walk's frames, EV error and time per pixel (one thread)",
                                 "meter,bins,bin width EV,mean abs error EV,max abs error EV,core-ns per pixel");
    static const int bins[] = {0, 8, 16, 32, 64, 128, 256, 1024};
    for (size_t b = 0; b < sizeof bins / sizeof *bins; ++b) {
        double mean = 0.0, mx = 0.0;
        for (int f = 0; f < frames && bins[b] > 0; ++f) {
            sol_meter_options o = {.bins = bins[b]};
            double m;
            exp_check(sol_histogram_meter(lum + (size_t)f * n, (size_t)n, &o, &m, NULL), "metering");
            double e = fabs(sol_ev100_from_luminance(m) - exact[f]);
            mean += e / frames;
            mx = fmax(mx, e);
        }
        meter_timing c = {lum, frames, bins[b], scratch, 0.0};
        double ns = exp_cpu_time_per_item_ns(time_meter, &c, (size_t)frames * n, exp->quick ? 3 : 5);
        if (bins[b] == 0)
            exp_table_row(t, "peer: exact (sorted EVs)|-|0|0|0|%.1f", ns);
        else
            exp_table_row(t, "histogram%s|%d|%.3f|%.4f|%.4f|%.1f", bins[b] == 64 ? " (default)" : "", bins[b],
                          32.0 / bins[b], mean, mx, ns);
    }
    exp_table_write(t, exp, "meter_knobs");
    free(lum);
    free(scratch);
    free(exact);
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "s3_s6_aces_exposure", argc, argv);
    double err = s3_aces_fit(&exp);
    (void)err;
    if (!exp.bench)
        s6_exposure(&exp);
    else
        bench_meter(&exp);
    return 0;
}
