/* exp_plot.c - gnuplot figures (PNG for reading, PDF for the paper) and claims rows. */
#include "exp_harness.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static void render(const exp_run *exp, const char *name, const char *terminal, const char *ext)
{
    char command[8192];
    snprintf(command, sizeof command,
             "cd '%s' && gnuplot -e \"set terminal %s; set output '%s.%s'\" '%s.gp'", exp->dir, terminal, name,
             ext, name);
    if (system(command) != 0)
        exp_die("gnuplot failed on %s/%s.gp", exp->dir, name);
}

/* cairo (1.16) stamps each PDF with the time it was written, so two runs of the same driver give
 * different files. A plot's date says nothing about it (its data and script do), so every plot PDF
 * gets one fixed date, 1970-01-01 (SOURCE_DATE_EPOCH = 0, the reproducible-builds convention), written
 * over cairo's with the same length so the PDF's cross-reference offsets stay valid; the file is
 * replaced through a temporary name. A fixed date rather than the Makefile's SOURCE_DATE_EPOCH (the
 * last commit that changed the sources): with that, every commit rewrote all plot PDFs in results/
 * although their content had not changed. Only the paper takes the commit's date. */
static void pin_pdf_date(const char *path)
{
    static const char stamp[] = "19700101000000";
    FILE *f = fopen(path, "rb");
    if (!f)
        exp_die("cannot read %s", path);
    size_t cap = 1 << 16, n = 0;
    char *data = malloc(cap);
    for (size_t got; data && (got = fread(data + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n == cap) {
            char *bigger = realloc(data, cap *= 2);
            if (!bigger)
                free(data);
            data = bigger;
        }
    }
    fclose(f);
    if (!data)
        exp_die("out of memory reading %s", path);
    static const char key[] = "/CreationDate (D:";
    for (size_t i = 0; i + sizeof key - 1 + 14 <= n; ++i)
        if (memcmp(data + i, key, sizeof key - 1) == 0)
            memcpy(data + i + sizeof key - 1, stamp, 14);
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    f = fopen(tmp, "wb");
    if (!f || fwrite(data, 1, n, f) != n || fclose(f) != 0 || rename(tmp, path) != 0)
        exp_die("cannot rewrite %s", path);
    free(data);
}

void exp_plot(const exp_run *exp, const char *name, const char *script_fmt, ...)
{
    char file[512];
    snprintf(file, sizeof file, "%s.gp", name);
    char *script = NULL;
    va_list args;
    va_start(args, script_fmt);
    int n = vsnprintf(NULL, 0, script_fmt, args);
    va_end(args);
    if (n < 0 || !(script = malloc((size_t)n + 1)))
        exp_die("out of memory formatting %s", file);
    va_start(args, script_fmt);
    vsnprintf(script, (size_t)n + 1, script_fmt, args);
    va_end(args);
    FILE *f = exp_open(exp, file);
    /* Key titles are names (often CSV column headers such as ev_log_average), not enhanced text:
     * without this an underscore turns the rest of a title into a subscript. */
    fputs("set key noenhanced  # exp_plot: titles are plain names\n", f);
    /* Every CSV block a driver writes starts with a header line. Without being told, gnuplot reads
     * that line as a data row for pseudo-column 0, xtic() and histograms (one bar dropped, labels off
     * by one), so the header is declared for every script that does not handle it itself. */
    if (!strstr(script, "skip 1") && !strstr(script, "every ::1 ") && !strstr(script, ".dat'"))
        fputs("set datafile columnheaders  # exp_plot: each CSV block starts with a header line\n", f);
    fputs(script, f);
    fputc('\n', f);
    free(script);
    if (fclose(f) != 0)
        exp_die("cannot write %s", exp_path(exp, file));
    render(exp, name, "pngcairo size 960,640 font 'Sans,11'", "png");
    render(exp, name, "pdfcairo size 5in,3.3in font 'Sans,8'", "pdf");
    snprintf(file, sizeof file, "%s.pdf", name);
    pin_pdf_date(exp_path(exp, file));
}

/* Claims rows are tab-separated; tabs and newlines inside a field would break the row. */
static void put_field(FILE *f, const char *s, char end)
{
    for (; *s; ++s)
        fputc(*s == '\t' || *s == '\n' ? ' ' : *s, f);
    fputc(end, f);
}

void exp_claim(const exp_run *exp, const char *id, const char *talk, const char *sol, const char *tolerance,
               exp_verdict verdict, const char *note_fmt, ...)
{
    static const char *names[3] = {"reproduced", "differs-explained", "not-reproduced"};
    if (exp->bench)
        return;
    char note[2048];
    va_list args;
    va_start(args, note_fmt);
    vsnprintf(note, sizeof note, note_fmt, args);
    va_end(args);
    const char *path = exp_path(exp, "claims.tsv");
    FILE *f = fopen(path, "a");
    if (!f)
        exp_die("cannot append to %s", path);
    put_field(f, id, '\t');
    put_field(f, talk, '\t');
    put_field(f, sol, '\t');
    put_field(f, tolerance, '\t');
    put_field(f, names[verdict], '\t');
    put_field(f, exp->name, '\t');
    put_field(f, note, '\n');
    if (fclose(f) != 0)
        exp_die("cannot write %s", path);
}

void exp_number(const exp_run *exp, const char *key, const char *value_fmt, ...)
{
    if (exp->bench)
        return;
    char value[512];
    va_list args;
    va_start(args, value_fmt);
    vsnprintf(value, sizeof value, value_fmt, args);
    va_end(args);
    const char *path = exp_path(exp, "numbers.tex");
    FILE *f = fopen(path, "a");
    if (!f)
        exp_die("cannot append to %s", path);
    fprintf(f, "\\solnumdef{%s}{%s}\n", key, value);
    if (fclose(f) != 0)
        exp_die("cannot write %s", path);
}
