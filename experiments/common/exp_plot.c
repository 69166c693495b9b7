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

void exp_plot(const exp_run *exp, const char *name, const char *script_fmt, ...)
{
    char file[512];
    snprintf(file, sizeof file, "%s.gp", name);
    FILE *f = exp_open(exp, file);
    va_list args;
    va_start(args, script_fmt);
    vfprintf(f, script_fmt, args);
    va_end(args);
    fputc('\n', f);
    if (fclose(f) != 0)
        exp_die("cannot write %s", exp_path(exp, file));
    render(exp, name, "pngcairo size 960,640 font 'Sans,11'", "png");
    render(exp, name, "pdfcairo size 5in,3.3in font 'Sans,8'", "pdf");
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
