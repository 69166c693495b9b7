/* report.c - statistics and worst inputs of a check (sol_check_report). */
#include "check_internal.h"

#include <math.h>
#include <string.h>

void check_begin(check_acc *acc, const char *unit, double tolerance)
{
    memset(acc, 0, sizeof *acc);
    acc->r.unit = unit;
    acc->r.tolerance = tolerance;
}

void check_add(check_acc *acc, const sol_check_item *item, int mismatch, int failure)
{
    sol_check_report *r = &acc->r;
    double err = isnan(item->error) ? INFINITY : item->error;
    r->count++;
    r->mismatches += mismatch != 0;
    r->failures += failure != 0;
    acc->sum += err;
    if (err > r->max || r->count == 1)
        r->max = err;
    /* Keep the SOL_CHECK_WORST worst: failures before passes, then by error; first kept among equals. */
    int fail = failure != 0, k = r->worst_count;
#define WORSE(f, e, i) ((f) > acc->fails[i] || ((f) == acc->fails[i] && (e) > r->worst[i].error))
    if (k == SOL_CHECK_WORST && !WORSE(fail, err, k - 1))
        return;
    if (k < SOL_CHECK_WORST)
        r->worst_count = ++k;
    int i = k - 1;
    while (i > 0 && WORSE(fail, err, i - 1)) {
        r->worst[i] = r->worst[i - 1];
        acc->fails[i] = acc->fails[i - 1];
        --i;
    }
#undef WORSE
    r->worst[i] = *item;
    r->worst[i].error = err;
    acc->fails[i] = fail;
}

void check_end(check_acc *acc, sol_check_report *report)
{
    acc->r.mean = acc->r.count ? acc->sum / (double)acc->r.count : 0.0;
    acc->r.passed = acc->r.failures == 0;
    *report = acc->r;
}
