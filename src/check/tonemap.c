/* tonemap.c - an engine's sampled tone curve against sol_tonemap_apply, and its lower bound
 * c_min / l against sol_tonemap_lower_bound (claims D10-D12, S3). */
#include "check_internal.h"

#include <math.h>
#include <string.h>

sol_status sol_check_tonemap(sol_tonemap op, const double *x, const double *y, size_t n, sol_check_report *report)
{
    if (!x || !y || !report)
        return SOL_ERR_NULL_ARG;
    if (n == 0 || op < 0 || op >= SOL_TONEMAP_COUNT)
        return SOL_ERR_INVALID_ARG;
    check_acc acc;
    check_begin(&acc, "linear", SOL_CHECK_TOL_TONEMAP);
    for (size_t i = 0; i < n; ++i) {
        sol_check_item it;
        memset(&it, 0, sizeof it);
        it.index = i;
        it.input[0] = x[i];
        it.expected[0] = sol_tonemap_apply(op, x[i]);
        it.got[0] = y[i];
        double d = fabs(y[i] - it.expected[0]);
        if (isnan(it.expected[0]) && isnan(y[i]))
            d = 0.0; /* NaN in, NaN out is sol's behaviour too */
        it.error = isnan(d) ? INFINITY : d;
        check_add(&acc, &it, y[i] != it.expected[0], !(it.error <= SOL_CHECK_TOL_TONEMAP));
    }
    check_end(&acc, report);
    return SOL_OK;
}

sol_status sol_check_tonemap_bound(sol_tonemap op, const double *x, const double *y, size_t n, double threshold,
                                   double *engine_c_min, double *sol_c_min)
{
    if (!x || !y || !engine_c_min || !sol_c_min)
        return SOL_ERR_NULL_ARG;
    if (threshold == 0.0)
        threshold = 0.5 / 255.0;
    if (n == 0 || !(threshold > 0.0 && threshold < 1.0))
        return SOL_ERR_INVALID_ARG;
    double ref, best = INFINITY;
    sol_status st = sol_tonemap_lower_bound(op, threshold, &ref);
    if (st != SOL_OK)
        return st;
    for (size_t i = 0; i < n; ++i)
        if (y[i] >= threshold && x[i] < best)
            best = x[i];
    if (isinf(best))
        return SOL_ERR_OUT_OF_RANGE;
    *engine_c_min = best;
    *sol_c_min = ref;
    return SOL_OK;
}

sol_status sol_check_tonemap_inverse(sol_tonemap op, const double *x, const double *y, size_t n, double *mean_ev,
                                     double *max_ev, size_t *used)
{
    if (!x || !y || !mean_ev || !max_ev)
        return SOL_ERR_NULL_ARG;
    if (n == 0 || op < 0 || op >= SOL_TONEMAP_COUNT)
        return SOL_ERR_INVALID_ARG;
    double sum = 0.0, worst = 0.0;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        double xi;
        if (!(x[i] > 0.0) || !isfinite(x[i]) || !(y[i] > 0.0) ||
            sol_tonemap_inverse(op, y[i], &xi) != SOL_OK || !(xi > 0.0))
            continue;
        double ev = fabs(log2(xi / x[i]));
        sum += ev;
        worst = ev > worst ? ev : worst;
        ++k;
    }
    if (k == 0)
        return SOL_ERR_OUT_OF_RANGE;
    *mean_ev = sum / (double)k;
    *max_ev = worst;
    if (used)
        *used = k;
    return SOL_OK;
}
