/* exp_harness.h - what every experiment driver shares: command line, results files (CSV, Markdown,
 * LaTeX tables, gnuplot plots, claims rows), timing and progress.
 *
 * A driver is experiments/<name>/main.c (plus any other .c files in that folder). It writes
 * everything under results/<name>/ (or $SOL_RESULTS/<name>/). Drivers exit non-zero on failure
 * and print a clear message; the helpers here print nothing to stdout except bench tables. */
#ifndef EXP_HARNESS_H
#define EXP_HARNESS_H

#include <stddef.h>
#include <stdio.h>

/* ---- command line: `driver [--bench] [--quick] [--out DIR]` ---- */
typedef struct exp_run {
    const char *name; /* experiment name, e.g. "d3_d7_normals": the results folder */
    int bench;        /* --bench: run only the accuracy-vs-time measurements, print their table */
    int quick;        /* --quick: reduced sizes (smoke runs); results are not for the paper */
    char dir[4096];   /* results/<name>, created by exp_init */
} exp_run;

/* Parses argv, creates the results folder, clears this experiment's claims rows.
 * Prints usage and exits 2 on a bad command line (drivers are CLIs, not the library). */
void exp_init(exp_run *exp, const char *name, int argc, char **argv);
/* Path of a file in the results folder (static buffer rotated over 8 calls). */
const char *exp_path(const exp_run *exp, const char *file);
/* Opens a results file for writing; exits with a message if it cannot. */
FILE *exp_open(const exp_run *exp, const char *file);
/* Reports a failed library call and exits 1: `exp_check(st, "encoding %s", what)`. */
void exp_check(int status, const char *what_fmt, ...);
/* Prints a message on stderr and exits 1. */
void exp_die(const char *fmt, ...) __attribute__((noreturn, format(printf, 1, 2)));

/* ---- tables: one call writes <name>.csv, <name>.md and <name>.tex ---- */
typedef struct exp_table exp_table;
/* columns: comma-separated column titles, e.g. "method,bits,mean deg,max deg". */
exp_table *exp_table_new(const char *title, const char *columns);
/* Adds a row; the format yields the cells separated by '|' (e.g. "%s|%d|%.4f|%.4f"). */
void exp_table_row(exp_table *table, const char *cells_fmt, ...);
/* Writes <name>.csv, <name>.md and <name>.tex (replacing any file of those names, so raw plot data
 * needs another name) and frees the table. In bench mode also prints the Markdown on stdout. */
void exp_table_write(exp_table *table, const exp_run *exp, const char *name);

/* ---- plots: gnuplot, rendered as <name>.png (reading) and <name>.pdf (paper) ---- */
/* `script` is gnuplot commands without terminal/output lines; it runs with the results folder as
 * working directory, so data files are named plainly ("errors.csv", with `set datafile separator
 * comma`). The script is kept as <name>.gp so the figure can be re-rendered by hand.
 * Header lines: every CSV block (a file, or each block of a multi-block file read with `index`)
 * starts with one header line, and exp_plot starts the script with `set datafile columnheaders`, so
 * pseudo-column 0, xtic() and histograms count data rows only. A script that handles the header
 * itself (`skip 1`, `every ::1 using ...`) or reads headerless .dat files gets no such line; with it,
 * `every ::k::k` selects data row k (from 0). Key titles are plain text (`set key noenhanced`), so
 * underscores in column headers print as underscores. */
void exp_plot(const exp_run *exp, const char *name, const char *script_fmt, ...);

/* ---- claims rows: results/<name>/claims.tsv, gathered into results/CLAIMS.md ---- */
typedef enum exp_verdict {
    EXP_REPRODUCED,        /* sol's figure agrees with the talk's within the tolerance */
    EXP_DIFFERS_EXPLAINED, /* it differs, and the results explain which assumption yields each */
    EXP_NOT_REPRODUCED     /* it differs and no consistent derivation gives the talk's figure */
} exp_verdict;
/* id: claim ID from CLAIMS.md ("D3"); talk: the talk's figure as text; sol: sol's figure as
 * text; tolerance: what "agrees" meant; note: one sentence (why, or which definition). */
void exp_claim(const exp_run *exp, const char *id, const char *talk, const char *sol, const char *tolerance,
               exp_verdict verdict, const char *note_fmt, ...);

/* ---- numbers quoted in the paper's prose: results/<name>/numbers.tex ----
 * exp_number(exp, "D3-count", "%d", count) appends \solnumdef{D3-count}{289880}; the paper writes
 * \solnum{D3-count}, so every number in its prose comes from the run that made results/. Keys are
 * unique across experiments: start them with the claim ID. Timing values go in keys that end in
 * "-ms", "-s" or "-ns", and figures computed from timings (a fit's R^2 on times, a speed ratio) in
 * keys that end in "-timing": they are the only ones a rerun may change. */
void exp_number(const exp_run *exp, const char *key, const char *value_fmt, ...);

/* ---- timing ---- */
/* Monotonic clock in nanoseconds. */
double exp_now_ns(void);
/* Runs fn(ctx) `repeats` times and returns the median wall time per item in ns (fn processes
 * `items` items per call). One untimed warm-up call comes first. */
double exp_time_per_item_ns(void (*fn)(void *ctx), void *ctx, size_t items, int repeats);
/* Thread CPU time in ns (CLOCK_THREAD_CPUTIME_ID): a figure that does not depend on what else the
 * machine runs, for bench tables on a shared machine. */
double exp_thread_cpu_ns(void);
/* As exp_time_per_item_ns, but the median thread CPU time with OpenMP limited to one thread during
 * the calls (the library's results are identical for any thread count): core-ns per item. Name the
 * column "core-ns ..." (a timing column for compare_runs.sh). */
double exp_cpu_time_per_item_ns(void (*fn)(void *ctx), void *ctx, size_t items, int repeats);

/* ---- progress on stderr, only when stderr is a terminal ---- */
void exp_progress(const char *label, size_t done, size_t total);
void exp_progress_done(const char *label);

#endif
