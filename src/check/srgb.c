/* srgb.c - an engine's 8-bit sRGB codes against round(255 * sol_srgb_encode(x)) with the tie rule
 * of sol_check.h (IEC 61966-2-1). */
#include "check_internal.h"

#include <math.h>
#include <string.h>

sol_status sol_check_srgb(const double *linear, const uint8_t *codes, size_t n, sol_check_report *report)
{
    if (!linear || !codes || !report)
        return SOL_ERR_NULL_ARG;
    if (n == 0)
        return SOL_ERR_INVALID_ARG;
    check_acc acc;
    check_begin(&acc, "code", 0.0);
    for (size_t i = 0; i < n; ++i) {
        double exact = 255.0 * sol_srgb_encode(linear[i]); /* NaN encodes as 0 */
        int ref = (int)floor(exact + 0.5);
        sol_check_item it;
        memset(&it, 0, sizeof it);
        it.index = i;
        it.input[0] = linear[i];
        it.input[1] = exact;
        it.expected[0] = ref;
        it.got[0] = codes[i];
        int d = codes[i] - ref;
        it.error = fabs((double)d);
        /* A tie: one code away, and the exact value within SOL_CHECK_SRGB_TIE_CODES of the half-way
         * point between the two codes. */
        int tie = (d == 1 || d == -1) && fabs(exact - (ref + 0.5 * d)) <= SOL_CHECK_SRGB_TIE_CODES;
        check_add(&acc, &it, d != 0, d != 0 && !tie);
    }
    check_end(&acc, report);
    return SOL_OK;
}
