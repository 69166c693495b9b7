/* d10_d12_tonemap_bounds - the HDR lower bound of dynamic range scaling (claims D10, D11, D12).
 *
 * Talk, slides "HDR on consoles: dynamic range" and "... lower bound estimator": the darkest HDR
 * value that still matters is the inverse tone map of the LDR threshold 0.5/255 = 1/510. This
 * driver computes c_min / l for every tone map of src/hdr (closed form and iterative), checks the
 * bound against 8-bit output codes, and measures the inverse solvers' accuracy against time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp_harness.h"
#include "sol_hdr.h"

static const double ldr_threshold = 0.5 / 255.0;

static const char *curve_formula(sol_tonemap op)
{
    switch (op) {
    case SOL_TONEMAP_EXPONENTIAL: return "1 - exp(-x)";
    case SOL_TONEMAP_REINHARD: return "x/(1+x)";
    case SOL_TONEMAP_FILMIC_HBD: return "HBD g(x-0.004)^2.2, g=t(6.2t+0.5)/(t(6.2t+1.7)+0.06)";
    case SOL_TONEMAP_FILMIC_SLIDE: return "slide as printed: (t(6.2t+0.5)/(t(6.2(t+1.7)+0.06)))^2.2";
    case SOL_TONEMAP_ACES_FIT: return "Narkowicz ACES fit";
    default: return "ACES RRT+ODT Rec.709 100 nits (grey)";
    }
}

/* Smallest 8-bit linear code reached just below and at the bound: proves c_min is the code-1 edge. */
static int linear_code(double y) { return (int)sol_unorm_encode(y, 8); }

/* Writes the table, fills bounds[] (linear output) and srgb_bounds[] (sRGB-encoded output), and returns
 * whether every c_min is the code-0/code-1 edge (the D10 check). */
static int lower_bound_table(const exp_run *exp, double bounds[SOL_TONEMAP_COUNT], double srgb_bounds[SOL_TONEMAP_COUNT])
{
    int all_edges = 1;
    exp_table *t = exp_table_new("HDR lower bound c_min / l for the LDR threshold 1/510",
                                 "tone map,formula,c_min/l (linear output),code below/at,"
                                 "c_min/l (sRGB-encoded output),ratio to exponential");
    double srgb_threshold = sol_srgb_decode(ldr_threshold); /* 0.5/255 in the encoded output */
    for (int op = 0; op < SOL_TONEMAP_COUNT; ++op) {
        double c, c_srgb;
        exp_check(sol_tonemap_lower_bound((sol_tonemap)op, ldr_threshold, &c), "lower bound");
        exp_check(sol_tonemap_lower_bound((sol_tonemap)op, srgb_threshold, &c_srgb), "lower bound (sRGB)");
        bounds[op] = c;
        srgb_bounds[op] = c_srgb;
        double below = sol_tonemap_apply((sol_tonemap)op, c * (1.0 - 1e-9)), at = sol_tonemap_apply((sol_tonemap)op, c * (1.0 + 1e-9));
        all_edges &= linear_code(below) == 0 && linear_code(at) == 1;
        exp_table_row(t, "%s|%s|%.9f|%d/%d|%.9f|%.3f", sol_tonemap_name((sol_tonemap)op), curve_formula((sol_tonemap)op),
                      c, linear_code(below), linear_code(at), c_srgb, c / bounds[0]);
    }
    exp_table_write(t, exp, "lower_bounds");
    return all_edges;
}

/* The curves near black, with the threshold: where each crosses 1/510 is its c_min. */
static void curves_plot(const exp_run *exp)
{
    FILE *f = exp_open(exp, "curves.csv");
    fputs("x", f);
    for (int op = 0; op < SOL_TONEMAP_COUNT; ++op)
        fprintf(f, ",%s", sol_tonemap_name((sol_tonemap)op));
    fputc('\n', f);
    for (int i = 0; i <= 400; ++i) {
        double x = pow(10.0, -4.0 + 5.0 * i / 400.0);
        fprintf(f, "%.6e", x);
        for (int op = 0; op < SOL_TONEMAP_COUNT; ++op)
            fprintf(f, ",%.6e", sol_tonemap_apply((sol_tonemap)op, x));
        fputc('\n', f);
    }
    fclose(f);
    exp_plot(exp, "curves_near_black",
             "set datafile separator comma\nset logscale xy\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
             "set xlabel 'x = c / l'\nset ylabel 'tone-mapped linear output'\nset key top left\nset grid\n"
             "set yrange [1e-5:1.2]\n"
             "plot for [i=2:7] 'curves.csv' using 1:i with lines lw 2 title columnheader(i), "
             "%.9g with lines dt 2 lc rgb 'black' title 'LDR threshold 1/510'",
             ldr_threshold);
}

/* ---- accuracy vs time of the inverse solvers ---- */
enum { SOLVE_BATCH = 512 };
typedef struct solve_job {
    sol_tonemap op;
    int closed_form;
    sol_root_options options;
    double y[SOLVE_BATCH], x[SOLVE_BATCH];
} solve_job;

static void run_solves(void *ctx)
{
    solve_job *job = ctx;
    for (int i = 0; i < SOLVE_BATCH; ++i) {
        if (job->closed_form)
            (void)sol_tonemap_inverse(job->op, job->y[i], &job->x[i]);
        else
            (void)sol_tonemap_inverse_iterative(job->op, job->y[i], &job->options, &job->x[i], NULL);
    }
}

/* Relative error of the batch against the closed form (or the tight solve for ACES_REF). */
static double worst_relative_error(const solve_job *job, const double *exact)
{
    double worst = 0.0;
    for (int i = 0; i < SOLVE_BATCH; ++i)
        worst = fmax(worst, fabs(job->x[i] - exact[i]) / exact[i]);
    return worst;
}

static void solver_sweep(const exp_run *exp)
{
    exp_table *t = exp_table_new("Inverse tone map: accuracy vs time",
                                 "tone map,solver,tolerance,max relative error,ns per inverse");
    FILE *csv = exp_open(exp, "solver_curves.csv");
    FILE *closed = exp_open(exp, "solver_closed_form.csv");
    fputs("op,ns\n", closed);
    const sol_tonemap ops[] = {SOL_TONEMAP_FILMIC_HBD, SOL_TONEMAP_ACES_FIT, SOL_TONEMAP_ACES_REF};
    const double tolerances[] = {1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14};
    const int repeats = exp->quick ? 3 : 9;
    static solve_job job;
    double exact[SOLVE_BATCH];
    for (size_t o = 0; o < sizeof ops / sizeof ops[0]; ++o) {
        job.op = ops[o];
        for (int i = 0; i < SOLVE_BATCH; ++i) /* outputs spread over the display range, log-spaced */
            job.y[i] = pow(10.0, -3.0 + 2.95 * (i + 0.5) / SOLVE_BATCH);
        if (ops[o] != SOL_TONEMAP_ACES_REF) {
            job.closed_form = 1;
            double ns = exp_cpu_time_per_item_ns(run_solves, &job, SOLVE_BATCH, repeats);
            for (int i = 0; i < SOLVE_BATCH; ++i)
                exact[i] = job.x[i];
            exp_table_row(t, "%s|closed form|-|0|%.1f", sol_tonemap_name(ops[o]), ns);
            fprintf(closed, "%s,%.3f\n", sol_tonemap_name(ops[o]), ns);
        } else { /* reference: the tightest safeguarded Newton, then checked by the forward map */
            job.closed_form = 1;
            run_solves(&job);
            for (int i = 0; i < SOLVE_BATCH; ++i)
                exact[i] = job.x[i];
        }
        job.closed_form = 0;
        for (int m = 0; m < 2; ++m) {
            fputs("op,method,tolerance,max_rel_error,ns\n", csv); /* each gnuplot block has its header */
            for (size_t k = 0; k < sizeof tolerances / sizeof tolerances[0]; ++k) {
                job.options = (sol_root_options){(sol_root_method)m, tolerances[k], 400};
                double ns = exp_cpu_time_per_item_ns(run_solves, &job, SOLVE_BATCH, repeats);
                double err = worst_relative_error(&job, exact);
                const char *name = m ? "safeguarded Newton" : "bisection";
                exp_table_row(t, "%s|%s|%.0e|%.2e|%.1f", sol_tonemap_name(ops[o]), name, tolerances[k], err, ns);
                fprintf(csv, "%s,%s,%.0e,%.6e,%.3f\n", sol_tonemap_name(ops[o]), m ? "newton" : "bisection",
                        tolerances[k], fmax(err, 1e-17), ns);
            }
            fputs("\n\n", csv);
        }
    }
    fclose(csv);
    fclose(closed);
    exp_table_write(t, exp, "solver_sweep");
    if (!exp->bench)
        exp_plot(exp, "solver_accuracy_vs_time",
                 "set datafile separator comma\nset logscale xy\nset xlabel 'ns per inverse (median)'\n"
                 "set ylabel 'max relative error of c'\nset grid\nset key outside right\nset format y '10^{%%L}'\nset yrange [1e-17:1e-1]\n"
                 "plot 'solver_curves.csv' index 0 using 5:4 with linespoints title 'filmic-hbd bisection', "
                 "'' index 1 using 5:4 with linespoints title 'filmic-hbd Newton', "
                 "'' index 2 using 5:4 with linespoints title 'aces-fit bisection', "
                 "'' index 3 using 5:4 with linespoints title 'aces-fit Newton', "
                 "'' index 4 using 5:4 with linespoints title 'aces-rrt-odt bisection', "
                 "'' index 5 using 5:4 with linespoints title 'aces-rrt-odt Newton', "
                 "'solver_closed_form.csv' using 2:(1e-16) with points pt 7 ps 1.5 title 'closed forms (exact; drawn at 1e-16)'");
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d10_d12_tonemap_bounds", argc, argv);
    solver_sweep(&exp);
    if (exp.bench)
        return 0;
    double b[SOL_TONEMAP_COUNT], b_srgb[SOL_TONEMAP_COUNT];
    int all_edges = lower_bound_table(&exp, b, b_srgb);
    curves_plot(&exp);

    char fig[256];
    snprintf(fig, sizeof fig, "0.5/255 = 1/510 = %.8f; c_min = T^-1(1/510) is exactly the edge of linear code 1",
             ldr_threshold);
    exp_claim(&exp, "D10", "LDR threshold 0.5/255 = 1/510; c_min from the inverse tone map", fig, "exact",
              all_edges ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "for every tone map x slightly below c_min/l gives linear 8-bit code 0 and slightly above gives 1; "
              "if the threshold is taken in the sRGB-encoded output instead, c_min is ~%.0fx lower (table lower_bounds)",
              b[SOL_TONEMAP_EXPONENTIAL] / b_srgb[SOL_TONEMAP_EXPONENTIAL]);
    snprintf(fig, sizeof fig, "l ln(510/509) = %.9f l", b[SOL_TONEMAP_EXPONENTIAL]);
    exp_claim(&exp, "D11", "c_min = -l ln(510/509) ~ 0.00196271 l", fig, "6 significant digits",
              fabs(b[SOL_TONEMAP_EXPONENTIAL] - 0.00196271) < 5e-9 ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "1 - exp(-c/l) = 1/510 gives c = l ln(510/509) = -l ln(509/510): the slide's minus sign belongs to "
              "ln(509/510); the magnitude agrees to all printed digits");
    snprintf(fig, sizeof fig, "%.7f l (Hejl-Burgess-Dawson curve); %.7f l (slide's printed formula)",
             b[SOL_TONEMAP_FILMIC_HBD], b[SOL_TONEMAP_FILMIC_SLIDE]);
    exp_claim(&exp, "D12", "c_min ~ 0.0119052 l; filmic much less sensitive to dark colours", fig,
              "6 significant digits",
              fabs(b[SOL_TONEMAP_FILMIC_HBD] - 0.0119052) < 5e-8 ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the original curve x'=x-0.004, (x'(6.2x'+0.5)/(x'(6.2x'+1.7)+0.06))^2.2 gives the talk's digits; the "
              "denominator as printed, x'(6.2(x'+1.7)+0.06), cancels x' and gives %.4f; the filmic bound is %.2fx the "
              "exponential one",
              b[SOL_TONEMAP_FILMIC_SLIDE], b[SOL_TONEMAP_FILMIC_HBD] / b[SOL_TONEMAP_EXPONENTIAL]);
    return 0;
}
