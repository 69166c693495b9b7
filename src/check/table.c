/* table.c - numeric CSV tables for the checks' inputs, bounded by sol_read_limits. */
#include "check_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_COLS = 64, MAX_CELL = 64 };

static int blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

/* Parses one line [b, e) into v (at most MAX_COLS); returns the column count, 0 for an empty or
 * comment line, -1 for junk. */
static int parse_row(const char *b, const char *e, double *v)
{
    int n = 0;
    const char *p = b;
    while (p < e && blank(*p))
        ++p;
    if (p == e || *p == '#')
        return 0;
    for (;;) {
        while (p < e && blank(*p))
            ++p;
        const char *q = p;
        while (q < e && *q != ',' && *q != '#' && !blank(*q))
            ++q;
        size_t len = (size_t)(q - p);
        if (len == 0 || len >= MAX_CELL || n == MAX_COLS)
            return -1;
        char cell[MAX_CELL];
        memcpy(cell, p, len);
        cell[len] = 0;
        char *end;
        double x;
        const char *digits = cell + (cell[0] == '-' || cell[0] == '+');
        if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X') && !strpbrk(cell, ".pP")) {
            errno = 0;
            unsigned long long u = strtoull(digits + 2, &end, 16);
            if (end == digits + 2 || errno)
                return -1;
            x = (double)u * (cell[0] == '-' ? -1.0 : 1.0);
        } else
            x = strtod(cell, &end);
        if (*end)
            return -1;
        v[n++] = x;
        p = q;
        while (p < e && blank(*p))
            ++p;
        if (p == e || *p == '#')
            return n;
        if (*p != ',' && !(p > b && blank(p[-1])))
            return -1;
        if (*p == ',')
            ++p;
    }
}

sol_status sol_check_table_parse(const char *text, size_t length, const sol_read_limits *limits,
                                 sol_check_table *out, size_t *bad_line)
{
    if (!text || !out)
        return SOL_ERR_NULL_ARG;
    /* Pass 1: count rows and check the shape; pass 2: fill. */
    size_t rows = 0, cols = 0, line = 0, first_data_line = 0;
    double v[MAX_COLS];
    for (int pass = 0; pass < 2; ++pass) {
        double *values = NULL;
        if (pass == 1) {
            if (rows == 0) {
                if (bad_line)
                    *bad_line = 0;
                return SOL_ERR_FORMAT; /* no numeric row at all */
            }
            sol_status st = sol_read_limits_check(limits, (int64_t)cols, (int64_t)rows, 1, 8);
            if (st != SOL_OK)
                return st;
            size_t cells;
            if (!sol_size_mul(&cells, rows, cols) || cells > SIZE_MAX / sizeof(double))
                return SOL_ERR_LIMIT;
            values = malloc(cells * sizeof(double));
            if (!values)
                return SOL_ERR_NO_MEMORY;
        }
        size_t r = 0;
        line = 0;
        const char *p = text, *end = text + length;
        while (p < end) {
            const char *nl = memchr(p, '\n', (size_t)(end - p));
            const char *e = nl ? nl : end;
            ++line;
            int n = parse_row(p, e, v);
            p = nl ? nl + 1 : end;
            if (n == 0)
                continue;
            if (n < 0) {
                /* the first non-comment line may be a header */
                if (pass == 0 && rows == 0 && first_data_line == 0) {
                    first_data_line = line;
                    continue;
                }
                if (pass == 1 && line == first_data_line && r == 0)
                    continue;
                if (bad_line)
                    *bad_line = line;
                free(values);
                return SOL_ERR_FORMAT;
            }
            if (pass == 0 && rows == 0 && first_data_line == 0)
                first_data_line = (size_t)-1; /* no header: the first row is data */
            if (pass == 0) {
                if (rows == 0)
                    cols = (size_t)n;
                else if ((size_t)n != cols) {
                    if (bad_line)
                        *bad_line = line;
                    return SOL_ERR_FORMAT;
                }
                ++rows;
            } else {
                memcpy(values + r * cols, v, cols * sizeof(double));
                ++r;
            }
        }
        if (pass == 1) {
            out->rows = rows;
            out->cols = cols;
            out->values = values;
        }
    }
    return SOL_OK;
}

sol_status sol_check_table_read(const char *path, const sol_read_limits *limits, sol_check_table *out,
                                size_t *bad_line)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    uint64_t max = limits && limits->max_bytes ? limits->max_bytes : SOL_READ_MAX_BYTES_DEFAULT;
    uint8_t *text;
    size_t size;
    sol_status st = sol_file_read_all(path, max, &text, &size);
    if (st != SOL_OK)
        return st;
    st = sol_check_table_parse((const char *)text, size, limits, out, bad_line);
    free(text);
    return st;
}

void sol_check_table_free(sol_check_table *table)
{
    if (!table)
        return;
    free(table->values);
    memset(table, 0, sizeof *table);
}
