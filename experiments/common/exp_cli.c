/* exp_cli.c - driver command line, results folder, fatal-error reporting. */
#include "exp_harness.h"

#include "sol_core.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void exp_die(const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    fputs("error: ", stderr);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
    exit(1);
}

void exp_check(int status, const char *what_fmt, ...)
{
    if (status == SOL_OK)
        return;
    va_list args;
    va_start(args, what_fmt);
    fputs("error: ", stderr);
    vfprintf(stderr, what_fmt, args);
    fprintf(stderr, ": %s\n", sol_status_string((sol_status)status));
    va_end(args);
    exit(1);
}

static void make_dirs(const char *path)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; ++p) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            exp_die("cannot create %s: %s", buf, strerror(errno));
        *p = '/';
    }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        exp_die("cannot create %s: %s", buf, strerror(errno));
}

static void usage(const char *prog)
{
    fprintf(stderr,
            "usage: %s [--bench] [--quick] [--out DIR]\n"
            "  --bench   run only the accuracy-vs-time measurements and print their tables\n"
            "  --quick   reduced problem sizes (smoke run, not for the paper)\n"
            "  --out DIR results root (default $SOL_RESULTS or ./results)\n",
            prog);
    exit(2);
}

void exp_init(exp_run *exp, const char *name, int argc, char **argv)
{
    memset(exp, 0, sizeof *exp);
    exp->name = name;
    const char *root = getenv("SOL_RESULTS");
    if (!root || !*root)
        root = "results";
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--bench"))
            exp->bench = 1;
        else if (!strcmp(argv[i], "--quick"))
            exp->quick = 1;
        else if (!strcmp(argv[i], "--out") && i + 1 < argc)
            root = argv[++i];
        else
            usage(argv[0]);
    }
    if ((size_t)snprintf(exp->dir, sizeof exp->dir, "%s/%s", root, name) >= sizeof exp->dir)
        exp_die("results path too long");
    make_dirs(exp->dir);
    if (!exp->bench) { /* a fresh claims file: rows are appended by exp_claim */
        FILE *claims = exp_open(exp, "claims.tsv");
        fputs("id\ttalk\tsol\ttolerance\tverdict\texperiment\tnote\n", claims);
        fclose(claims);
        FILE *numbers = exp_open(exp, "numbers.tex"); /* likewise for exp_number */
        fprintf(numbers, "%% numbers quoted by the paper, written by %s\n", name);
        fclose(numbers);
    }
}

const char *exp_path(const exp_run *exp, const char *file)
{
    static char paths[8][4096];
    static int next;
    char *path = paths[next++ % 8];
    if ((size_t)snprintf(path, 4096, "%s/%s", exp->dir, file) >= 4096)
        exp_die("results path too long: %s", file);
    return path;
}

FILE *exp_open(const exp_run *exp, const char *file)
{
    const char *path = exp_path(exp, file);
    FILE *f = fopen(path, "w");
    if (!f)
        exp_die("cannot write %s: %s", path, strerror(errno));
    return f;
}
