/* cmd_check.c - `sol check TECHNIQUE ...`: reads an engine's own output (CSV, .dds, PNG, .cube),
 * runs the matching sol_check_* call (src/check/sol_check.h) and prints its report, as text or
 * --json. Exit status: 0 pass, 1 beyond tolerance, 2 bad input or usage (cli.h).
 *
 * Each subcommand also has --emit FILE, which writes the inputs sol suggests the engine be run on
 * (sol's edge cases plus a deterministic spread), in the format the check then reads back. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sol_check.h"
#include "sol_core.h"
#include "sol_hdr.h"
#include "sol_normalmaps.h"
#include "sol_normals.h"

typedef struct args {
    const char *csv, *dds, *decoded, *source, *cube, *chart, *emit, *directions, *gbuffer;
    const char *method, *format, *op, *precision;
    const char *reference; /* bc5 --source: common (default) or optimal */
    int json, exact, count, size, have_tolerance;
    double tolerance, range;
    sol_grade look;
} args;

static const char *prog = "sol check";

static int usage_error(const char *fmt, const char *what)
{
    fprintf(stderr, "%s: ", prog);
    fprintf(stderr, fmt, what);
    fprintf(stderr, " (see 'sol check help')\n");
    return CLI_EXIT_USAGE;
}

static int bad_file(const char *path, const char *problem)
{
    fprintf(stderr, "%s: %s: %s\n", prog, path, problem);
    return CLI_EXIT_USAGE;
}

static void help(FILE *to)
{
    fprintf(to, "usage: sol check TECHNIQUE [OPTIONS]   compare an engine's output with sol's reference\n"
                "\n"
                "  normals --method M --csv FILE [--exact]  CSV rows x,y,z,code: the engine's encoder output\n"
                "          M: xyz-normalized xyz-max-component best-fit-search octahedral-12 spherical-12 ...\n"
            "  normals --method M --directions EXR --gbuffer PNG|EXR   a G-buffer dump: the engine encoded each\n"
            "          direction of the EXR (from --emit FILE.exr) into an 8-bit RGB(A) PNG, code = r | g<<8 | b<<16\n"
                "          (or an EXR holding each channel's code as the UNORM value code/255)\n"
                "  bc5 --dds FILE --decoded PNG [--precision 16|8|float] [--tolerance CODES]\n"
                "          the engine's decoder: its decoded texels (R = x, G = y) against sol's decoder\n"
                "  bc5 --dds FILE --source IMAGE [--reference common|optimal]   the engine's encoder: angular\n"
                "          error against the source normals (PNG/EXR, xyz in [-1,1] as (v+1)/2 for PNG) vs sol's\n"
                "          common (default) or optimal encoder (pass: mean within 5%% of it; optimal ~0.1-50 ms/block)\n"
                "  bc1 --dds FILE --decoded PNG [--tolerance CODES]   the engine's BC1 decoder, bit-exact\n"
            "  bc1 --dds FILE --source PNG              the engine's BC1 encoder: RGB error against the source\n"
            "          (mean within 5%% of sol's encoder)\n"
                "  pack --format F --csv FILE [--range R]   CSV rows: value(s), the engine's packed bits\n"
                "          F: r11g11b10f fp16 rgbm rgb10 depth-rg8 (rgbm: --range, default 6)\n"
                "  tonemap --op OP --csv FILE               CSV rows x,y: the engine's curve, y linear display\n"
                "          OP: exponential reinhard filmic-hbd filmic-slide aces-fit aces-rrt-odt\n"
                "  lut (--cube FILE | --chart PNG [--size N]) [LOOK]   the engine's 3D LUT vs sol's bake\n"
                "          LOOK: --saturation S --contrast C --hue DEG --lift R,G,B --gamma R,G,B --gain R,G,B\n"
                "  srgb --csv FILE                          CSV rows linear,code: the engine's 8-bit sRGB codes\n"
                "\n"
                "  --emit FILE [--count N]  (normals, pack, tonemap, srgb; lut: a .cube of sol's bake, --size N;\n"
            "          normals with FILE.exr: an N x N float direction image, --size N, default 1024)\n"
                "          write the inputs to run the engine on: sol's edge cases plus N spread values\n"
                "  --json   machine-readable report on stdout\n"
                "\n"
                "exit status: 0 pass, 1 beyond tolerance, 2 bad input or usage\n");
}

static int parse_triple(const char *s, double v[3])
{
    char *e;
    for (int c = 0; c < 3; ++c) {
        v[c] = strtod(s, &e);
        if (e == s || (c < 2 && *e != ',') || (c == 2 && *e))
            return 0;
        s = e + 1;
    }
    return 1;
}

static int parse_double(const char *s, double *v)
{
    char *e;
    *v = strtod(s, &e);
    return e != s && !*e && isfinite(*v);
}

static int parse_args(int argc, char **argv, args *a)
{
    memset(a, 0, sizeof *a);
    for (int i = 2; i < argc; ++i) {
        const char *o = argv[i];
        if (!strcmp(o, "--json")) {
            a->json = 1;
            continue;
        }
        if (!strcmp(o, "--exact")) {
            a->exact = 1;
            continue;
        }
        if (i + 1 >= argc)
            return usage_error("option '%s' needs a value or is unknown", o);
        const char *v = argv[++i];
        double d, t[3];
        if (!strcmp(o, "--csv"))
            a->csv = v;
        else if (!strcmp(o, "--dds"))
            a->dds = v;
        else if (!strcmp(o, "--decoded"))
            a->decoded = v;
        else if (!strcmp(o, "--source"))
            a->source = v;
        else if (!strcmp(o, "--cube"))
            a->cube = v;
        else if (!strcmp(o, "--chart"))
            a->chart = v;
        else if (!strcmp(o, "--emit"))
            a->emit = v;
        else if (!strcmp(o, "--directions"))
            a->directions = v;
        else if (!strcmp(o, "--gbuffer"))
            a->gbuffer = v;
        else if (!strcmp(o, "--method"))
            a->method = v;
        else if (!strcmp(o, "--format"))
            a->format = v;
        else if (!strcmp(o, "--op"))
            a->op = v;
        else if (!strcmp(o, "--precision"))
            a->precision = v;
        else if (!strcmp(o, "--reference"))
            a->reference = v;
        else if (!strcmp(o, "--count") || !strcmp(o, "--size")) {
            if (!parse_double(v, &d) || d < 1 || d > 1e8 || d != floor(d))
                return usage_error("%s needs a positive integer", o);
            *(o[2] == 'c' ? &a->count : &a->size) = (int)d;
        } else if (!strcmp(o, "--tolerance") || !strcmp(o, "--range") || !strcmp(o, "--saturation") ||
                   !strcmp(o, "--contrast") || !strcmp(o, "--hue")) {
            if (!parse_double(v, &d) || (o[2] != 'h' && o[2] != 's' && d < 0))
                return usage_error("%s needs a finite number", o);
            if (o[2] == 't') {
                a->tolerance = d;
                a->have_tolerance = 1;
            } else if (o[2] == 'r')
                a->range = d;
            else if (o[2] == 's')
                a->look.saturation = d;
            else if (o[2] == 'c')
                a->look.contrast = d;
            else
                a->look.hue_degrees = d;
        } else if (!strcmp(o, "--lift") || !strcmp(o, "--gamma") || !strcmp(o, "--gain")) {
            if (!parse_triple(v, t))
                return usage_error("%s needs three numbers R,G,B", o);
            memcpy(o[2] == 'l' ? a->look.lift : o[4] == 'm' ? a->look.gamma : a->look.gain, t, sizeof t);
        } else
            return usage_error("unknown option '%s'", o);
    }
    return -1;
}

/* ---- report output ---- */

static void print_vals(FILE *f, const double *v, int n, int json)
{
    fputs(json ? "[" : "(", f);
    for (int i = 0; i < n; ++i) {
        if (isnan(v[i]) || isinf(v[i]))
            fprintf(f, json ? "%s\"%g\"" : "%s%g", i ? ", " : "", v[i]);
        else
            fprintf(f, "%s%.10g", i ? ", " : "", v[i]);
    }
    fputs(json ? "]" : ")", f);
}

static double json_num(double v)
{
    return isfinite(v) ? v : (v > 0 ? 1e308 : -1e308);
}

static int report(const args *a, const char *what, const char *variant, const sol_check_report *r, int nin, int nout,
                  const char *extra_text, const char *extra_json)
{
    if (a->json) {
        printf("{\"check\": \"%s\", \"variant\": \"%s\", \"passed\": %s, \"count\": %zu, \"mismatches\": %zu, "
               "\"failures\": %zu, \"unit\": \"%s\", \"mean\": %.10g, \"max\": %.10g, \"tolerance\": %.10g%s%s, "
               "\"worst\": [",
               what, variant, r->passed ? "true" : "false", r->count, r->mismatches, r->failures, r->unit,
               json_num(r->mean), json_num(r->max), r->tolerance, extra_json ? ", " : "", extra_json ? extra_json : "");
        for (int i = 0; i < r->worst_count; ++i) {
            const sol_check_item *it = &r->worst[i];
            printf("%s{\"index\": %zu, \"error\": %.10g, \"input\": ", i ? ", " : "", it->index, json_num(it->error));
            print_vals(stdout, it->input, nin, 1);
            printf(", \"sol\": ");
            print_vals(stdout, it->expected, nout, 1);
            printf(", \"engine\": ");
            print_vals(stdout, it->got, nout, 1);
            printf("}");
        }
        printf("]}\n");
    } else {
        printf("sol check %s (%s): %s\n", what, variant, r->passed ? "PASS" : "FAIL");
        printf("  %zu values compared, %zu differ from sol, %zu beyond tolerance\n", r->count, r->mismatches,
               r->failures);
        printf("  error (%s): mean %.6g, max %.6g, tolerance %.6g\n", r->unit, r->mean, r->max, r->tolerance);
        if (extra_text)
            printf("%s", extra_text);
        if (r->worst_count && r->max > 0)
            printf("  worst inputs:\n");
        for (int i = 0; i < r->worst_count && r->max > 0; ++i) {
            const sol_check_item *it = &r->worst[i];
            if (it->error == 0 && i > 0)
                break;
            printf("    #%zu input ", it->index);
            print_vals(stdout, it->input, nin, 0);
            printf(" sol ");
            print_vals(stdout, it->expected, nout, 0);
            printf(" engine ");
            print_vals(stdout, it->got, nout, 0);
            printf(" error %.6g\n", it->error);
        }
    }
    return r->passed ? CLI_EXIT_OK : CLI_EXIT_FAILED;
}

/* ---- reading ---- */

static int read_table(const char *path, size_t cols, sol_check_table *t)
{
    size_t line = 0;
    sol_status st = sol_check_table_read(path, NULL, t, &line);
    if (st == SOL_ERR_FORMAT) {
        if (line)
            fprintf(stderr, "%s: %s: line %zu: bad row (not %zu numbers like the rows before)\n", prog, path, line,
                    cols);
        else
            fprintf(stderr, "%s: %s: no numeric rows\n", prog, path);
        return CLI_EXIT_USAGE;
    }
    if (st != SOL_OK)
        return bad_file(path, sol_status_string(st));
    if (t->cols != cols) {
        fprintf(stderr, "%s: %s: %zu columns, this check needs %zu\n", prog, path, t->cols, cols);
        sol_check_table_free(t);
        return CLI_EXIT_USAGE;
    }
    return -1;
}

static int read_dds(const char *path, sol_dds_format want, sol_dds *d)
{
    const char *problem = NULL;
    sol_status st = sol_dds_read(path, NULL, d, &problem);
    if (st != SOL_OK)
        return bad_file(path, problem ? problem : sol_status_string(st));
    if (d->format != want) {
        sol_dds_free(d);
        return bad_file(path, want == SOL_DDS_BC5 ? "not a BC5 (ATI2/BC5U) texture" : "not a BC1 (DXT1) texture");
    }
    if (d->width % 4 || d->height % 4) {
        sol_dds_free(d);
        return bad_file(path, "width and height must be multiples of 4");
    }
    return -1;
}

/* A decoded PNG as integer codes at its bit depth. */
static int read_codes(const char *path, int w, int h, int min_channels, uint16_t **codes, int *channels, int *bits)
{
    sol_image img = {0};
    sol_status st = sol_png_read(path, &img, bits);
    if (st != SOL_OK)
        return bad_file(path, sol_status_string(st));
    if (img.width != w || img.height != h || img.channels < min_channels) {
        fprintf(stderr, "%s: %s: %dx%d with %d channels, the .dds is %dx%d (needs >= %d channels)\n", prog, path,
                img.width, img.height, img.channels, w, h, min_channels);
        sol_image_free(&img);
        return CLI_EXIT_USAGE;
    }
    size_t n = (size_t)w * (size_t)h * (size_t)img.channels;
    uint16_t *c = malloc(n * sizeof *c);
    if (!c) {
        sol_image_free(&img);
        return bad_file(path, "out of memory");
    }
    double m = (double)((1u << *bits) - 1u);
    for (size_t i = 0; i < n; ++i)
        c[i] = (uint16_t)floor(img.data[i] * m + 0.5);
    *channels = img.channels;
    *codes = c;
    sol_image_free(&img);
    return -1;
}

/* ---- emitting inputs ---- */

/* Emitted files are written to PATH.tmp and renamed on success (no partial files). */
static char emit_tmp[4096];

static FILE *emit_open(const char *path)
{
    FILE *f = NULL;
    if ((size_t)snprintf(emit_tmp, sizeof emit_tmp, "%s.tmp", path) < sizeof emit_tmp)
        f = fopen(emit_tmp, "w");
    if (!f)
        fprintf(stderr, "%s: %s: cannot write\n", prog, path);
    return f;
}

static int emit_close(FILE *f, const char *path)
{
    int ok = !ferror(f);
    ok = fclose(f) == 0 && ok;
    ok = ok && rename(emit_tmp, path) == 0;
    if (!ok) {
        remove(emit_tmp);
        fprintf(stderr, "%s: %s: write failed\n", prog, path);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

/* ---- subcommands ---- */

static int find_normal_method(const char *name)
{
    for (int m = 0; m < SOL_NORMAL_METHOD_COUNT; ++m)
        if (!strcmp(name, sol_normal_method_name((sol_normal_method)m)))
            return m;
    return -1;
}

/* The direction image: sol's edge directions first, then R2 directions, row-major. */
static int emit_direction_image(const args *a)
{
    int size = a->size ? a->size : 1024;
    sol_image img = {0};
    sol_status st = sol_image_alloc(&img, size, size, 3);
    if (st != SOL_OK)
        return bad_file(a->emit, sol_status_string(st));
    size_t ne, n = (size_t)size * (size_t)size;
    const double(*e)[3] = sol_check_edge_normals(&ne);
    for (size_t i = 0; i < n; ++i) {
        double d[3], u, v;
        if (i < ne)
            memcpy(d, e[i], sizeof d);
        else {
            sol_r2_point((uint64_t)(i - ne), &u, &v);
            sol_sphere_uniform(u, v, d);
        }
        for (int c = 0; c < 3; ++c)
            img.data[3 * i + (size_t)c] = (float)d[c];
    }
    st = sol_exr_write(a->emit, &img, 0);
    sol_image_free(&img);
    return st == SOL_OK ? CLI_EXIT_OK : bad_file(a->emit, sol_status_string(st));
}

/* An EXR G-buffer holds each 8-bit code as the UNORM value code/255 (what an RGBA8 target reads
 * back as); half floats keep k/255 within 0.07 codes, so a value more than 0.25 codes from an
 * integer code in [0, 255] is not a code and the file is refused. -1: all values are codes. */
static int check_unorm8_values(const char *path, const sol_image *gb)
{
    size_t n = (size_t)gb->width * (size_t)gb->height;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            double code = gb->data[i * (size_t)gb->channels + (size_t)k] * 255.0;
            if (!(code >= -0.25 && code <= 255.25) || fabs(code - floor(code + 0.5)) > 0.25) {
                fprintf(stderr, "%s: %s: pixel %zu channel %d: %g is not an 8-bit UNORM code (code/255)\n", prog,
                        path, i, k, code / 255.0);
                return CLI_EXIT_USAGE;
            }
        }
    return -1;
}

/* A G-buffer dump: directions (float EXR) and the engine's codes as 8-bit RGB(A) PNG, or as an
 * RGB(A) EXR of the UNORM values code/255. */
static int check_gbuffer(const args *a, int m)
{
    if (!a->directions || !a->gbuffer)
        return usage_error("%s needs both --directions EXR and --gbuffer PNG", "normals");
    sol_image dir = {0}, gb = {0};
    int bits = 0, rc = -1;
    sol_status st = sol_exr_read(a->directions, &dir);
    if (st != SOL_OK)
        return bad_file(a->directions, sol_status_string(st));
    size_t name_len = strlen(a->gbuffer);
    int exr = name_len > 4 && !strcmp(a->gbuffer + name_len - 4, ".exr");
    st = exr ? sol_exr_read(a->gbuffer, &gb) : sol_png_read(a->gbuffer, &gb, &bits);
    if (st != SOL_OK)
        rc = bad_file(a->gbuffer, sol_status_string(st));
    else if ((!exr && bits != 8) || gb.channels < 3)
        rc = bad_file(a->gbuffer, "the G-buffer must be 8-bit RGB(A) PNG or an RGB(A) EXR of 8-bit UNORM values");
    else if (exr)
        rc = check_unorm8_values(a->gbuffer, &gb);
    else if (dir.channels < 3 || gb.width != dir.width || gb.height != dir.height)
        rc = bad_file(a->gbuffer, "size differs from the directions image (or it has fewer than 3 channels)");
    size_t n = (size_t)dir.width * (size_t)dir.height;
    double(*dirs)[3] = rc < 0 ? malloc(n * sizeof *dirs) : NULL;
    uint32_t *codes = rc < 0 ? malloc(n * sizeof *codes) : NULL;
    if (rc < 0 && (!dirs || !codes))
        rc = bad_file(a->gbuffer, "out of memory");
    for (size_t i = 0; rc < 0 && i < n; ++i) {
        const float *d = dir.data + i * (size_t)dir.channels, *g = gb.data + i * (size_t)gb.channels;
        uint32_t c;
        for (int k = 0; k < 3; ++k)
            dirs[i][k] = d[k];
        codes[i] = (uint32_t)floor(g[0] * 255.0f + 0.5f) | (uint32_t)floor(g[1] * 255.0f + 0.5f) << 8 |
                   (uint32_t)floor(g[2] * 255.0f + 0.5f) << 16;
        if (sol_normal_encode((sol_normal_method)m, dirs[i], &c) != SOL_OK) {
            fprintf(stderr, "%s: %s: pixel %zu: direction is zero or not finite\n", prog, a->directions, i);
            rc = CLI_EXIT_USAGE;
        }
    }
    if (rc < 0) {
        sol_check_report r;
        sol_check_normal_options o = {.exact = a->exact};
        st = sol_check_normals((sol_normal_method)m, (const double(*)[3])dirs, codes, n, &o, &r);
        rc = st != SOL_OK ? bad_file(a->gbuffer, sol_status_string(st))
                          : report(a, "normals", a->method, &r, 3, 2, NULL, NULL);
    }
    free(dirs);
    free(codes);
    sol_image_free(&dir);
    sol_image_free(&gb);
    return rc;
}

static int check_normals(const args *a)
{
    if (!a->method)
        return usage_error("%s needs --method", "normals");
    int m = find_normal_method(a->method);
    if (m < 0)
        return usage_error("unknown normal method '%s'", a->method);
    size_t elen = a->emit ? strlen(a->emit) : 0;
    if (a->emit && elen > 4 && !strcmp(a->emit + elen - 4, ".exr"))
        return emit_direction_image(a);
    if (a->directions || a->gbuffer)
        return check_gbuffer(a, m);
    if (a->emit) {
        FILE *f = emit_open(a->emit);
        if (!f)
            return CLI_EXIT_USAGE;
        size_t ne;
        const double(*e)[3] = sol_check_edge_normals(&ne);
        fprintf(f, "# x,y,z: directions to encode with %s (sol's edge cases, then R2 directions)\n", a->method);
        for (size_t i = 0; i < ne; ++i)
            fprintf(f, "%.17g,%.17g,%.17g\n", e[i][0], e[i][1], e[i][2]);
        int n = a->count ? a->count : 100000;
        for (int i = 0; i < n; ++i) {
            double u, v, d[3];
            sol_r2_point((uint64_t)i, &u, &v);
            sol_sphere_uniform(u, v, d);
            fprintf(f, "%.17g,%.17g,%.17g\n", d[0], d[1], d[2]);
        }
        return emit_close(f, a->emit);
    }
    if (!a->csv)
        return usage_error("%s needs --csv FILE (rows x,y,z,code) or --emit FILE", "normals");
    sol_check_table t;
    int rc = read_table(a->csv, 4, &t);
    if (rc >= 0)
        return rc;
    double(*dirs)[3] = malloc(t.rows * sizeof *dirs);
    uint32_t *codes = malloc(t.rows * sizeof *codes);
    rc = -1;
    for (size_t i = 0; dirs && codes && i < t.rows && rc < 0; ++i) {
        const double *row = t.values + 4 * i;
        memcpy(dirs[i], row, sizeof dirs[i]);
        uint32_t c;
        if (!(row[3] >= 0 && row[3] < 16777216.0 && row[3] == floor(row[3])) ||
            sol_normal_encode((sol_normal_method)m, dirs[i], &c) != SOL_OK) {
            fprintf(stderr, "%s: %s: row %zu: direction must be finite and non-zero, code an integer 0..2^24-1\n", prog,
                    a->csv, i + 1);
            rc = CLI_EXIT_USAGE;
        }
        codes[i] = (uint32_t)row[3];
    }
    if (rc < 0 && (!dirs || !codes))
        rc = bad_file(a->csv, "out of memory");
    if (rc < 0) {
        sol_check_report r;
        sol_check_normal_options o = {.exact = a->exact};
        sol_status st = sol_check_normals((sol_normal_method)m, (const double(*)[3])dirs, codes, t.rows, &o, &r);
        rc = st != SOL_OK ? bad_file(a->csv, sol_status_string(st))
                          : report(a, "normals", a->method, &r, 3, 2, NULL, NULL);
    }
    free(dirs);
    free(codes);
    sol_check_table_free(&t);
    return rc;
}

static int parse_precision(const char *s, sol_bc4_precision *p)
{
    if (!s || !strcmp(s, "16"))
        *p = SOL_BC4_INTERP_16BIT;
    else if (!strcmp(s, "8"))
        *p = SOL_BC4_INTERP_8BIT;
    else if (!strcmp(s, "float"))
        *p = SOL_BC4_INTERP_FLOAT;
    else
        return 0;
    return 1;
}

static int check_blocks(const args *a, int bc5)
{
    const char *what = bc5 ? "bc5" : "bc1";
    sol_bc4_precision prec;
    if (!parse_precision(a->precision, &prec))
        return usage_error("--precision must be 16, 8 or float, not '%s'", a->precision);
    if (!a->dds || (!a->decoded && !a->source))
        return usage_error("%s needs --dds FILE and --decoded PNG or --source IMAGE", what);
    sol_bc5_encoder refenc = SOL_BC5_COMMON;
    if (a->reference) {
        if (!bc5 || !a->source)
            return usage_error("--reference applies to bc5 --source only%s", "");
        if (!strcmp(a->reference, "optimal"))
            refenc = SOL_BC5_OPTIMAL;
        else if (strcmp(a->reference, "common"))
            return usage_error("--reference must be common or optimal, not '%s'", a->reference);
    }
    const char *refname = refenc == SOL_BC5_OPTIMAL ? "optimal" : "common";
    sol_dds d;
    int rc = read_dds(a->dds, bc5 ? SOL_DDS_BC5 : SOL_DDS_BC1, &d);
    if (rc >= 0)
        return rc;
    sol_check_report r;
    if (a->decoded) {
        uint16_t *codes = NULL;
        int channels = 0, bits = 0;
        rc = read_codes(a->decoded, d.width, d.height, bc5 ? 2 : 3, &codes, &channels, &bits);
        if (rc < 0) {
            double tol = a->have_tolerance ? a->tolerance : SOL_CHECK_TOL_DECODE_CODES;
            sol_status st =
                bc5 ? sol_check_bc5_decode(d.blocks, d.width, d.height, prec, codes, channels, bits, tol, &r)
                    : sol_check_bc1_decode(d.blocks, d.width, d.height, codes, channels, bits, tol, &r);
            char variant[64];
            snprintf(variant, sizeof variant, "decoder, %d-bit texels%s%s", bits, bc5 ? ", interpolants " : "",
                     bc5 ? (a->precision ? a->precision : "16") : "");
            rc = st != SOL_OK ? bad_file(a->decoded, sol_status_string(st))
                              : report(a, what, variant, &r, 2, bc5 ? 2 : 3, NULL, NULL);
        }
        free(codes);
    } else {
        sol_image src = {0};
        if (!bc5) {
            sol_status st = sol_png_read(a->source, &src, NULL);
            double ref = 0;
            if (st == SOL_OK && (src.width != d.width || src.height != d.height || src.channels < 3))
                rc = bad_file(a->source, "size differs from the .dds or fewer than 3 channels");
            else if (st != SOL_OK)
                rc = bad_file(a->source, sol_status_string(st));
            else if ((st = sol_check_bc1_encode(&src, d.blocks, &r, &ref)) != SOL_OK)
                rc = bad_file(a->source, sol_status_string(st));
            else {
                char text[160], json[96];
                snprintf(text, sizeof text,
                         "  sol's encoder on the same source: mean %.6g codes (pass: engine <= %.0f%% of it)\n", ref,
                         100.0 * (1.0 + SOL_CHECK_BC1_ENCODER_SLACK));
                snprintf(json, sizeof json, "\"sol_mean\": %.10g", ref);
                rc = report(a, what, "encoder vs source", &r, 2, 3, text, json);
            }
            sol_image_free(&src);
            sol_dds_free(&d);
            return rc;
        }
        size_t n = strlen(a->source);
        int exr = n > 4 && !strcmp(a->source + n - 4, ".exr");
        sol_status st = exr ? sol_exr_read(a->source, &src) : sol_png_read(a->source, &src, NULL);
        if (st != SOL_OK)
            rc = bad_file(a->source, sol_status_string(st));
        else if (src.width != d.width || src.height != d.height || src.channels < 3) {
            rc = bad_file(a->source, "size differs from the .dds or fewer than 3 channels");
        } else {
            if (!exr) /* PNG stores (v + 1) / 2 */
                for (size_t i = 0; i < (size_t)src.width * (size_t)src.height * (size_t)src.channels; ++i)
                    src.data[i] = 2.0f * src.data[i] - 1.0f;
            double ref = 0;
            uint64_t bounded = 0;
            st = sol_check_bc5_encode_against(&src, d.blocks, prec, refenc, &r, &ref, &bounded);
            char text[512], json[256], variant[64];
            /* distance: the engine's mean minus the reference's (deg) and their ratio */
            double dist = r.mean - ref, ratio = ref > 0 ? r.mean / ref : (r.mean > 0 ? INFINITY : 1.0);
            int k = snprintf(text, sizeof text,
                             "  sol's %s encoder on the same source: mean %.6g deg (pass: engine <= %.0f%% of it)\n"
                             "  engine's distance from it: %+.6g deg (%.4g x)\n",
                             refname, ref, 100.0 * (1.0 + SOL_CHECK_BC5_ENCODER_SLACK), dist, ratio);
            if (refenc == SOL_BC5_OPTIMAL && k > 0 && (size_t)k < sizeof text)
                snprintf(text + k, sizeof text - (size_t)k,
                         "  blocks where the optimal search hit its work bound (best found, not proven): %llu\n",
                         (unsigned long long)bounded);
            snprintf(json, sizeof json,
                     "\"reference\": \"%s\", \"sol_mean\": %.10g, \"sol_%s_mean\": %.10g, "
                     "\"distance\": %.10g, \"ratio\": %.10g, \"bounded_blocks\": %llu",
                     refname, ref, refname, ref, json_num(dist), json_num(ratio), (unsigned long long)bounded);
            snprintf(variant, sizeof variant, "encoder vs source, reference %s", refname);
            rc = st != SOL_OK ? bad_file(a->source, st == SOL_ERR_INVALID_ARG ? "a source normal is zero or not finite"
                                                                              : sol_status_string(st))
                              : report(a, what, variant, &r, 2, 3, text, json);
        }
        sol_image_free(&src);
    }
    sol_dds_free(&d);
    return rc;
}

static int check_pack(const args *a)
{
    int f = -1;
    for (int i = 0; i < SOL_CHECK_PACK_COUNT && a->format; ++i)
        if (!strcmp(a->format, sol_check_pack_name((sol_check_pack_format)i)))
            f = i;
    if (f < 0)
        return usage_error("pack needs --format r11g11b10f|fp16|rgbm|rgb10|depth-rg8%s", "");
    int k = sol_check_pack_inputs((sol_check_pack_format)f);
    if (a->emit) {
        FILE *out = emit_open(a->emit);
        if (!out)
            return CLI_EXIT_USAGE;
        size_t ne;
        const float *e = sol_check_edge_floats(&ne);
        fprintf(out, "# values to pack as %s (sol's edge floats, then a spread; %%a hex floats are exact)\n",
                a->format);
        int n = a->count ? a->count : 10000;
        uint64_t rng = 1;
        for (size_t i = 0; i < ne + (size_t)n; ++i) {
            for (int c = 0; c < k; ++c) {
                float v =
                    i < ne
                        ? e[(i + (size_t)c * 7) % ne]
                        : (float)(exp2(sol_rng_uniform(&rng, -20.0, 17.0)) * (f == SOL_CHECK_PACK_DEPTH_RG8 ? 0 : 1));
                if (f == SOL_CHECK_PACK_DEPTH_RG8 && i >= ne)
                    v = (float)sol_rng_uniform(&rng, 0.0, 1.0);
                fprintf(out, "%s%a", c ? "," : "", v);
            }
            fprintf(out, "\n");
        }
        return emit_close(out, a->emit);
    }
    if (!a->csv)
        return usage_error("%s needs --csv FILE (rows: value(s), packed bits) or --emit FILE", "pack");
    sol_check_table t;
    int rc = read_table(a->csv, (size_t)k + 1, &t);
    if (rc >= 0)
        return rc;
    float *vals = malloc(t.rows * (size_t)k * sizeof *vals);
    uint32_t *bits = malloc(t.rows * sizeof *bits);
    for (size_t i = 0; vals && bits && i < t.rows && rc < 0; ++i) {
        const double *row = t.values + i * (size_t)(k + 1);
        for (int c = 0; c < k; ++c)
            vals[i * (size_t)k + (size_t)c] = (float)row[c];
        double b = row[k];
        if (!(b >= 0 && b <= 4294967295.0 && b == floor(b))) {
            fprintf(stderr, "%s: %s: row %zu: packed bits must be an integer 0..2^32-1\n", prog, a->csv, i + 1);
            rc = CLI_EXIT_USAGE;
        }
        bits[i] = (uint32_t)b;
    }
    if (rc < 0 && (!vals || !bits))
        rc = bad_file(a->csv, "out of memory");
    if (rc < 0) {
        sol_check_report r;
        sol_status st = sol_check_pack((sol_check_pack_format)f, vals, bits, t.rows, a->range, &r);
        rc = st != SOL_OK ? bad_file(a->csv, sol_status_string(st))
                          : report(a, "pack", a->format, &r, k + 1, k, NULL, NULL);
    }
    free(vals);
    free(bits);
    sol_check_table_free(&t);
    return rc;
}

static int check_tonemap(const args *a)
{
    int op = -1;
    for (int i = 0; i < SOL_TONEMAP_COUNT && a->op; ++i)
        if (!strcmp(a->op, sol_tonemap_name((sol_tonemap)i)))
            op = i;
    if (op < 0)
        return usage_error("tonemap needs --op exponential|reinhard|filmic-hbd|filmic-slide|aces-fit|aces-rrt-odt%s",
                           "");
    if (a->emit) {
        FILE *f = emit_open(a->emit);
        if (!f)
            return CLI_EXIT_USAGE;
        int n = a->count ? a->count : 4096;
        fprintf(f, "# x = c / l to tone map with %s (log-spaced 2^-16..2^8, then the toe and edge cases)\n", a->op);
        for (int i = 0; i < n; ++i)
            fprintf(f, "%.17g\n", exp2(-16.0 + 24.0 * i / (n > 1 ? n - 1 : 1)));
        static const double edge[] = {0.0, -0.0, -1.0, 0.004, 0.0040001, 0.003999, 1e-300, 1e6};
        for (size_t i = 0; i < sizeof edge / sizeof edge[0]; ++i)
            fprintf(f, "%.17g\n", edge[i]);
        return emit_close(f, a->emit);
    }
    if (!a->csv)
        return usage_error("%s needs --csv FILE (rows x,y) or --emit FILE", "tonemap");
    sol_check_table t;
    int rc = read_table(a->csv, 2, &t);
    if (rc >= 0)
        return rc;
    double *x = malloc(t.rows * sizeof *x), *y = malloc(t.rows * sizeof *y);
    if (!x || !y)
        rc = bad_file(a->csv, "out of memory");
    for (size_t i = 0; rc < 0 && i < t.rows; ++i) {
        x[i] = t.values[2 * i];
        y[i] = t.values[2 * i + 1];
    }
    if (rc < 0) {
        sol_check_report r;
        sol_status st = sol_check_tonemap((sol_tonemap)op, x, y, t.rows, &r);
        double ec = 0, sc = 0, mev = 0, xev = 0;
        size_t used = 0;
        char text[400] = "", json[240] = "";
        int tl = 0, jl = 0;
        if (sol_check_tonemap_bound((sol_tonemap)op, x, y, t.rows, 0.0, &ec, &sc) == SOL_OK) {
            tl = snprintf(text, sizeof text, "  lower bound c_min/l (y >= 0.5/255): engine's samples %.6g, sol %.6g\n",
                          ec, sc);
            jl = snprintf(json, sizeof json, "\"engine_c_min\": %.10g, \"sol_c_min\": %.10g", ec, sc);
        }
        if (sol_check_tonemap_inverse((sol_tonemap)op, x, y, t.rows, &mev, &xev, &used) == SOL_OK) {
            snprintf(text + tl, sizeof text - (size_t)tl,
                     "  through sol's inverse: exposure error mean %.3g EV, max %.3g EV (%zu samples)\n", mev, xev,
                     used);
            snprintf(json + jl, sizeof json - (size_t)jl, "%s\"inverse_mean_ev\": %.10g, \"inverse_max_ev\": %.10g",
                     jl ? ", " : "", mev, xev);
        }
        rc = st != SOL_OK ? bad_file(a->csv, sol_status_string(st))
                          : report(a, "tonemap", a->op, &r, 1, 1, text[0] ? text : NULL, json[0] ? json : NULL);
    }
    free(x);
    free(y);
    sol_check_table_free(&t);
    return rc;
}

static void grade_fn(const double in[3], double out[3], void *ctx)
{
    sol_grade_apply((const sol_grade *)ctx, in, out);
}

static int check_lut(const args *a)
{
    sol_lut3d lut = {0};
    sol_cube_info info;
    memset(&info, 0, sizeof info);
    for (int c = 0; c < 3; ++c)
        info.domain_max[c] = 1.0;
    if (a->emit) {
        sol_status st = sol_lut3d_bake(a->size ? a->size : 33, grade_fn, (void *)&a->look, &lut);
        if (st == SOL_OK)
            st = sol_cube_write(a->emit, &lut, "sol reference bake");
        sol_lut3d_free(&lut);
        return st == SOL_OK ? CLI_EXIT_OK : bad_file(a->emit, sol_status_string(st));
    }
    const char *path = a->cube ? a->cube : a->chart;
    if (!path)
        return usage_error("%s needs --cube FILE or --chart PNG", "lut");
    if (a->cube) {
        size_t line = 0;
        const char *problem = NULL;
        sol_status st = sol_cube_read(a->cube, NULL, &lut, &info, &line, &problem);
        if (st != SOL_OK) {
            if (line)
                fprintf(stderr, "%s: %s: line %zu: %s\n", prog, path, line, problem ? problem : sol_status_string(st));
            else
                fprintf(stderr, "%s: %s: %s\n", prog, path, problem ? problem : sol_status_string(st));
            return CLI_EXIT_USAGE;
        }
    } else {
        sol_image img = {0};
        int size = a->size ? a->size : 16;
        sol_status st = sol_png_read(a->chart, &img, NULL);
        if (st == SOL_OK)
            st = sol_lut3d_chart_read(&img, 0, 0, size, &lut);
        sol_image_free(&img);
        if (st != SOL_OK)
            return bad_file(path, st == SOL_ERR_INVALID_ARG ? "not an unwrapped size^2 x size chart (--size)"
                                                            : sol_status_string(st));
    }
    sol_check_report r;
    sol_status st = sol_check_lut(&lut, info.domain_min, info.domain_max, &a->look, &r);
    char variant[48];
    snprintf(variant, sizeof variant, "%d^3 lattice", lut.size);
    int rc = st != SOL_OK ? bad_file(path, sol_status_string(st)) : report(a, "lut", variant, &r, 3, 3, NULL, NULL);
    sol_lut3d_free(&lut);
    return rc;
}

static int check_srgb(const args *a)
{
    if (a->emit) {
        FILE *f = emit_open(a->emit);
        if (!f)
            return CLI_EXIT_USAGE;
        int n = a->count ? a->count : 2000000;
        fprintf(f, "# linear values to encode as 8-bit sRGB: i/%d, then the threshold and edge cases\n", n);
        for (int i = 0; i <= n; ++i)
            fprintf(f, "%.17g\n", (double)i / n);
        static const double edge[] = {0.0031308, 0.00313079, 0.00313081, -0.0, -1.0, 2.0, 1e-300};
        for (size_t i = 0; i < sizeof edge / sizeof edge[0]; ++i)
            fprintf(f, "%.17g\n", edge[i]);
        return emit_close(f, a->emit);
    }
    if (!a->csv)
        return usage_error("%s needs --csv FILE (rows linear,code) or --emit FILE", "srgb");
    sol_check_table t;
    int rc = read_table(a->csv, 2, &t);
    if (rc >= 0)
        return rc;
    double *lin = malloc(t.rows * sizeof *lin);
    uint8_t *codes = malloc(t.rows);
    if (!lin || !codes)
        rc = bad_file(a->csv, "out of memory");
    for (size_t i = 0; rc < 0 && i < t.rows; ++i) {
        double c = t.values[2 * i + 1];
        lin[i] = t.values[2 * i];
        if (!(c >= 0 && c <= 255 && c == floor(c))) {
            fprintf(stderr, "%s: %s: row %zu: code must be an integer 0..255\n", prog, a->csv, i + 1);
            rc = CLI_EXIT_USAGE;
        } else
            codes[i] = (uint8_t)c;
    }
    if (rc < 0) {
        sol_check_report r;
        sol_status st = sol_check_srgb(lin, codes, t.rows, &r);
        char text[160];
        snprintf(text, sizeof text, "  tie rule: one code off is accepted within %g codes of a half-way point\n",
                 SOL_CHECK_SRGB_TIE_CODES);
        rc = st != SOL_OK ? bad_file(a->csv, sol_status_string(st))
                          : report(a, "srgb", "8-bit codes", &r, 2, 1, text, NULL);
    }
    free(lin);
    free(codes);
    sol_check_table_free(&t);
    return rc;
}

int cli_check_main(int argc, char **argv)
{
    if (argc < 2) {
        help(stderr);
        return CLI_EXIT_USAGE;
    }
    const char *t = argv[1];
    if (!strcmp(t, "help") || !strcmp(t, "--help") || !strcmp(t, "-h")) {
        help(stdout);
        return CLI_EXIT_OK;
    }
    args a;
    int rc = parse_args(argc, argv, &a);
    if (rc >= 0)
        return rc;
    if (!strcmp(t, "normals"))
        return check_normals(&a);
    if (!strcmp(t, "bc5"))
        return check_blocks(&a, 1);
    if (!strcmp(t, "bc1"))
        return check_blocks(&a, 0);
    if (!strcmp(t, "pack"))
        return check_pack(&a);
    if (!strcmp(t, "tonemap"))
        return check_tonemap(&a);
    if (!strcmp(t, "lut"))
        return check_lut(&a);
    if (!strcmp(t, "srgb"))
        return check_srgb(&a);
    return usage_error("unknown technique '%s'", t);
}
