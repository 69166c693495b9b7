/* cube_io.c - .cube 3D LUT files (Adobe "Cube LUT Specification" version 1.0, 2013; Resolve's
 * LUT_3D_INPUT_RANGE), read bounded by sol_read_limits and written through a temporary name. */
#include "sol_hdr.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CUBE_MIN = 2, CUBE_MAX = 256 };

typedef struct cursor {
    const char *p, *end;
    size_t line;
} cursor;

/* Next line as [*b, *e) without the newline and surrounding blanks; 0 at the end. */
static int next_line(cursor *c, const char **b, const char **e)
{
    if (c->p >= c->end)
        return 0;
    const char *s = c->p, *n = memchr(s, '\n', (size_t)(c->end - s));
    const char *t = n ? n : c->end;
    c->p = n ? n + 1 : c->end;
    c->line++;
    while (s < t && isspace((unsigned char)*s))
        ++s;
    while (t > s && isspace((unsigned char)t[-1]))
        --t;
    *b = s;
    *e = t;
    return 1;
}

/* Parses up to `want` numbers from [b, e); returns how many, or -1 on junk. */
static int parse_numbers(const char *b, const char *e, double *v, int want)
{
    char buf[256];
    size_t len = (size_t)(e - b);
    if (len >= sizeof buf)
        return -1;
    memcpy(buf, b, len);
    buf[len] = 0;
    char *p = buf;
    int n = 0;
    for (;;) {
        while (isspace((unsigned char)*p))
            ++p;
        if (!*p)
            return n;
        if (n == want)
            return -1;
        char *q;
        errno = 0;
        double x = strtod(p, &q);
        if (q == p || !isfinite(x))
            return -1;
        v[n++] = x;
        p = q;
        if (*p && !isspace((unsigned char)*p))
            return -1;
    }
}

static int keyword(const char *b, const char *e, const char *kw)
{
    size_t n = strlen(kw);
    return (size_t)(e - b) >= n && !memcmp(b, kw, n) && (b + n == e || isspace((unsigned char)b[n]));
}

static sol_status fail(sol_status st, size_t line, const char *why, size_t *bad_line, const char **problem)
{
    if (bad_line)
        *bad_line = line;
    if (problem)
        *problem = why;
    return st;
}

sol_status sol_cube_parse(const char *text, size_t length, const sol_read_limits *limits, sol_lut3d *out,
                          sol_cube_info *info, size_t *bad_line, const char **problem)
{
    if (!text || !out)
        return SOL_ERR_NULL_ARG;
    sol_cube_info meta;
    memset(&meta, 0, sizeof meta);
    for (int c = 0; c < 3; ++c)
        meta.domain_max[c] = 1.0;
    cursor cur = {text, text + length, 0};
    const char *b, *e;
    int size = 0;
    float *data = NULL;
    size_t entries = 0, total = 0;
    while (next_line(&cur, &b, &e)) {
        if (b == e || *b == '#')
            continue;
        if (isalpha((unsigned char)*b)) {
            double v[3];
            if (data) {
                free(data);
                return fail(SOL_ERR_FORMAT, cur.line, "keyword after the LUT data", bad_line, problem);
            }
            if (keyword(b, e, "TITLE")) {
                const char *q = memchr(b, '"', (size_t)(e - b));
                const char *r = q ? memchr(q + 1, '"', (size_t)(e - q - 1)) : NULL;
                if (!r)
                    return fail(SOL_ERR_FORMAT, cur.line, "TITLE without a quoted string", bad_line, problem);
                size_t n = (size_t)(r - q - 1);
                if (n > sizeof meta.title - 1)
                    n = sizeof meta.title - 1;
                memcpy(meta.title, q + 1, n);
                meta.title[n] = 0;
            } else if (keyword(b, e, "LUT_1D_SIZE")) {
                return fail(SOL_ERR_UNSUPPORTED, cur.line, "1D LUTs (LUT_1D_SIZE) are not supported", bad_line,
                            problem);
            } else if (keyword(b, e, "LUT_3D_SIZE")) {
                if (size)
                    return fail(SOL_ERR_FORMAT, cur.line, "LUT_3D_SIZE given twice", bad_line, problem);
                if (parse_numbers(b + 11, e, v, 1) != 1 || v[0] != floor(v[0]) || v[0] < CUBE_MIN ||
                    v[0] > CUBE_MAX)
                    return fail(SOL_ERR_FORMAT, cur.line, "LUT_3D_SIZE is not an integer in 2..256", bad_line,
                                problem);
                size = (int)v[0];
                sol_status st = sol_read_limits_check(limits, size, size, size, 12);
                if (st != SOL_OK)
                    return fail(st, cur.line, "LUT_3D_SIZE is beyond the read limits", bad_line, problem);
            } else if (keyword(b, e, "DOMAIN_MIN") || keyword(b, e, "DOMAIN_MAX")) {
                if (parse_numbers(b + 10, e, v, 3) != 3)
                    return fail(SOL_ERR_FORMAT, cur.line, "DOMAIN_MIN/MAX needs three numbers", bad_line, problem);
                memcpy(b[8] == 'I' ? meta.domain_min : meta.domain_max, v, sizeof v);
            } else if (keyword(b, e, "LUT_3D_INPUT_RANGE")) {
                if (parse_numbers(b + 18, e, v, 2) != 2)
                    return fail(SOL_ERR_FORMAT, cur.line, "LUT_3D_INPUT_RANGE needs two numbers", bad_line,
                                problem);
                for (int c = 0; c < 3; ++c) {
                    meta.domain_min[c] = v[0];
                    meta.domain_max[c] = v[1];
                }
            } /* other keywords (LUT_1D_INPUT_RANGE, vendor ones) are ignored */
            continue;
        }
        /* a data line */
        if (!size) {
            free(data);
            return fail(SOL_ERR_FORMAT, cur.line, "LUT data before LUT_3D_SIZE", bad_line, problem);
        }
        if (!data) {
            for (int c = 0; c < 3; ++c)
                if (!(meta.domain_min[c] < meta.domain_max[c]))
                    return fail(SOL_ERR_FORMAT, cur.line, "DOMAIN_MIN is not below DOMAIN_MAX", bad_line, problem);
            total = (size_t)size * (size_t)size * (size_t)size;
            data = malloc(total * 3 * sizeof *data);
            if (!data)
                return SOL_ERR_NO_MEMORY;
        }
        double v[3];
        if (parse_numbers(b, e, v, 3) != 3) {
            free(data);
            return fail(SOL_ERR_FORMAT, cur.line, "LUT entry is not three numbers", bad_line, problem);
        }
        if (entries == total) {
            free(data);
            return fail(SOL_ERR_FORMAT, cur.line, "wrong entry count: more than LUT_3D_SIZE^3 entries", bad_line,
                        problem);
        }
        for (int c = 0; c < 3; ++c)
            data[3 * entries + (size_t)c] = (float)v[c];
        ++entries;
    }
    if (!size)
        return fail(SOL_ERR_FORMAT, 0, "no LUT_3D_SIZE", bad_line, problem);
    if (entries != total || !data) {
        free(data);
        return fail(SOL_ERR_FORMAT, 0, "wrong entry count: fewer than LUT_3D_SIZE^3 entries", bad_line, problem);
    }
    out->size = size;
    out->data = data;
    if (info)
        *info = meta;
    return SOL_OK;
}

sol_status sol_cube_read(const char *path, const sol_read_limits *limits, sol_lut3d *out, sol_cube_info *info,
                         size_t *bad_line, const char **problem)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    /* A 256^3 table in text is ~16.8M lines of up to ~40 bytes. */
    uint64_t max = limits && limits->max_bytes ? limits->max_bytes : SOL_READ_MAX_BYTES_DEFAULT;
    uint8_t *text;
    size_t size;
    sol_status st = sol_file_read_all(path, max, &text, &size);
    if (st != SOL_OK)
        return fail(st, 0, st == SOL_ERR_IO ? "cannot read the file" : "file is beyond the read limits", bad_line,
                    problem);
    st = sol_cube_parse((const char *)text, size, limits, out, info, bad_line, problem);
    free(text);
    return st;
}

sol_status sol_cube_write(const char *path, const sol_lut3d *lut, const char *title)
{
    if (!path || !lut || !lut->data)
        return SOL_ERR_NULL_ARG;
    if (lut->size < CUBE_MIN || lut->size > CUBE_MAX)
        return SOL_ERR_INVALID_ARG;
    size_t n = strlen(path);
    char *tmp = malloc(n + 8);
    if (!tmp)
        return SOL_ERR_NO_MEMORY;
    memcpy(tmp, path, n);
    memcpy(tmp + n, ".tmpXXX", 8);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        free(tmp);
        return SOL_ERR_IO;
    }
    int ok = 1;
    if (title && !strchr(title, '"') && !strchr(title, '\n'))
        ok = fprintf(f, "TITLE \"%s\"\n", title) > 0;
    ok = ok && fprintf(f, "LUT_3D_SIZE %d\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n", lut->size) > 0;
    size_t total = (size_t)lut->size * (size_t)lut->size * (size_t)lut->size;
    for (size_t i = 0; ok && i < total; ++i)
        ok = fprintf(f, "%.9g %.9g %.9g\n", lut->data[3 * i], lut->data[3 * i + 1], lut->data[3 * i + 2]) > 0;
    ok = (fclose(f) == 0) && ok;
    ok = ok && rename(tmp, path) == 0;
    if (!ok)
        remove(tmp);
    free(tmp);
    return ok ? SOL_OK : SOL_ERR_IO;
}
