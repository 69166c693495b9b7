/* check_internal.h - the report accumulator every sol_check_* call shares (not installed). */
#ifndef SOL_CHECK_INTERNAL_H
#define SOL_CHECK_INTERNAL_H
#include "sol_check.h"

typedef struct check_acc {
    sol_check_report r;
    double sum;
    int fails[SOL_CHECK_WORST]; /* ranking: failures first, then by error */
} check_acc;

void check_begin(check_acc *acc, const char *unit, double tolerance);
/* One compared value: error (NaN counts as +Inf), whether it differs from sol at all, whether it
 * is beyond the tolerance; the item is kept when it is among the worst. */
void check_add(check_acc *acc, const sol_check_item *item, int mismatch, int failure);
/* Fills the report (mean, passed). */
void check_end(check_acc *acc, sol_check_report *report);
#endif
