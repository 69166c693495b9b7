/* exp_timing.c - median wall-clock time per item, and terminal-only progress. */
#include "exp_harness.h"

#include <omp.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

double exp_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double exp_time_per_item_ns(void (*fn)(void *ctx), void *ctx, size_t items, int repeats)
{
    if (repeats < 1)
        repeats = 1;
    double *times = malloc(sizeof *times * (size_t)repeats);
    if (!times)
        exp_die("out of memory");
    fn(ctx); /* warm caches and page in buffers */
    for (int i = 0; i < repeats; ++i) {
        double start = exp_now_ns();
        fn(ctx);
        times[i] = exp_now_ns() - start;
    }
    qsort(times, (size_t)repeats, sizeof *times, compare_doubles);
    double median = repeats % 2 ? times[repeats / 2] : 0.5 * (times[repeats / 2 - 1] + times[repeats / 2]);
    free(times);
    return median / (double)(items ? items : 1);
}

double exp_thread_cpu_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

double exp_cpu_time_per_item_ns(void (*fn)(void *ctx), void *ctx, size_t items, int repeats)
{
    if (repeats < 1)
        repeats = 1;
    double *times = malloc(sizeof *times * (size_t)repeats);
    if (!times)
        exp_die("out of memory");
    int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    fn(ctx); /* warm caches and page in buffers */
    for (int i = 0; i < repeats; ++i) {
        double start = exp_thread_cpu_ns();
        fn(ctx);
        times[i] = exp_thread_cpu_ns() - start;
    }
    omp_set_num_threads(threads);
    qsort(times, (size_t)repeats, sizeof *times, compare_doubles);
    double median = repeats % 2 ? times[repeats / 2] : 0.5 * (times[repeats / 2 - 1] + times[repeats / 2]);
    free(times);
    return median / (double)(items ? items : 1);
}

void exp_progress(const char *label, size_t done, size_t total)
{
    static double last;
    if (!isatty(STDERR_FILENO))
        return;
    double now = exp_now_ns();
    if (done != total && now - last < 2e8) /* at most 5 updates a second */
        return;
    last = now;
    fprintf(stderr, "\r%s: %zu/%zu (%.0f%%)  ", label, done, total, total ? 100.0 * (double)done / (double)total : 100.0);
}

void exp_progress_done(const char *label)
{
    if (isatty(STDERR_FILENO))
        fprintf(stderr, "\r%s: done%30s\n", label, "");
}
