/* exp_table.c - one table written as CSV (data), Markdown (reading) and LaTeX (paper). */
#include "exp_harness.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

struct exp_table {
    char *title;
    char **cells; /* rows * cols strings, row 0 is the header */
    int rows, cols, capacity;
};

static char *dup_range(const char *s, size_t n)
{
    char *copy = malloc(n + 1);
    if (!copy)
        exp_die("out of memory");
    memcpy(copy, s, n);
    copy[n] = '\0';
    return copy;
}

static int split_into(exp_table *t, const char *line, char sep)
{
    int count = 0;
    for (const char *start = line;; ++count) {
        const char *end = strchr(start, sep);
        size_t n = end ? (size_t)(end - start) : strlen(start);
        if (t) {
            if (count >= t->cols)
                exp_die("table '%s': row has more than %d cells: %s", t->title, t->cols, line);
            t->cells[t->rows * t->cols + count] = dup_range(start, n);
        }
        if (!end)
            return count + 1;
        start = end + 1;
    }
}

static void add_row(exp_table *t, const char *line, char sep)
{
    if (t->rows == t->capacity) {
        t->capacity = t->capacity ? 2 * t->capacity : 16;
        t->cells = realloc(t->cells, sizeof *t->cells * (size_t)t->capacity * (size_t)t->cols);
        if (!t->cells)
            exp_die("out of memory");
    }
    int n = split_into(t, line, sep);
    if (n != t->cols)
        exp_die("table '%s': row has %d cells, header has %d: %s", t->title, n, t->cols, line);
    t->rows++;
}

exp_table *exp_table_new(const char *title, const char *columns)
{
    exp_table *t = calloc(1, sizeof *t);
    if (!t)
        exp_die("out of memory");
    t->title = dup_range(title, strlen(title));
    t->cols = split_into(NULL, columns, ',');
    add_row(t, columns, ',');
    return t;
}

void exp_table_row(exp_table *table, const char *cells_fmt, ...)
{
    char line[8192];
    va_list args;
    va_start(args, cells_fmt);
    vsnprintf(line, sizeof line, cells_fmt, args);
    va_end(args);
    add_row(table, line, '|');
}

static void write_csv_cell(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; ++s) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static void write_tex_cell(FILE *f, const char *s)
{
    if (*s == '[')
        fputs("{}", f); /* after the previous row's \\, a bare [ would start an optional argument */
    for (; *s; ++s) {
        if (strchr("&%$#_{}", *s))
            fprintf(f, "\\%c", *s);
        else if (*s == '~')
            fputs("\\textasciitilde{}", f);
        else if (*s == '^')
            fputs("\\textasciicircum{}", f);
        else if (*s == '\\')
            fputs("\\textbackslash{}", f);
        else
            fputc(*s, f);
    }
}

static void write_markdown(const exp_table *t, FILE *f)
{
    fprintf(f, "**%s**\n\n", t->title);
    for (int r = 0; r < t->rows; ++r) {
        for (int c = 0; c < t->cols; ++c)
            fprintf(f, "| %s ", t->cells[r * t->cols + c]);
        fputs("|\n", f);
        if (r == 0) {
            for (int c = 0; c < t->cols; ++c)
                fputs("|---", f);
            fputs("|\n", f);
        }
    }
}

static void write_csv(const exp_table *t, FILE *f)
{
    for (int r = 0; r < t->rows; ++r)
        for (int c = 0; c < t->cols; ++c) {
            write_csv_cell(f, t->cells[r * t->cols + c]);
            fputc(c + 1 < t->cols ? ',' : '\n', f);
        }
}

static void write_tex(const exp_table *t, FILE *f)
{
    fputs("\\begin{tabular}{l", f);
    for (int c = 1; c < t->cols; ++c)
        fputc('r', f);
    fputs("}\n\\toprule\n", f);
    for (int r = 0; r < t->rows; ++r) {
        for (int c = 0; c < t->cols; ++c) {
            write_tex_cell(f, t->cells[r * t->cols + c]);
            fputs(c + 1 < t->cols ? " & " : " \\\\\n", f);
        }
        if (r == 0)
            fputs("\\midrule\n", f);
    }
    fputs("\\bottomrule\n\\end{tabular}\n", f);
}

void exp_table_write(exp_table *table, const exp_run *exp, const char *name)
{
    static const char *exts[3] = {"csv", "md", "tex"};
    void (*writers[3])(const exp_table *, FILE *) = {write_csv, write_markdown, write_tex};
    for (int i = 0; i < 3; ++i) {
        char file[512];
        snprintf(file, sizeof file, "%s.%s", name, exts[i]);
        FILE *f = exp_open(exp, file);
        writers[i](table, f);
        if (fclose(f) != 0)
            exp_die("cannot write %s", exp_path(exp, file));
    }
    if (exp->bench) {
        write_markdown(table, stdout);
        fputc('\n', stdout);
    }
    for (int i = 0; i < table->rows * table->cols; ++i)
        free(table->cells[i]);
    free(table->cells);
    free(table->title);
    free(table);
}
