/* lut.c - an engine's 3D LUT against sol's grading of the same look at the table's lattice points,
 * in CIEDE2000 (claim M4: Sharma, Wu, Dalal 2005). */
#include "check_internal.h"

#include <math.h>
#include <string.h>

sol_status sol_check_lut(const sol_lut3d *engine, const double domain_min[3], const double domain_max[3],
                         const sol_grade *look, sol_check_report *report)
{
    if (!engine || !engine->data || !look || !report)
        return SOL_ERR_NULL_ARG;
    if (engine->size < 2 || engine->size > 256)
        return SOL_ERR_INVALID_ARG;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    for (int c = 0; c < 3; ++c) {
        if (domain_min)
            lo[c] = domain_min[c];
        if (domain_max)
            hi[c] = domain_max[c];
        if (!(isfinite(lo[c]) && isfinite(hi[c]) && lo[c] < hi[c]))
            return SOL_ERR_INVALID_ARG;
    }
    const int s = engine->size;
    check_acc acc;
    check_begin(&acc, "dE00", SOL_CHECK_TOL_LUT_DE00);
    size_t i = 0;
    for (int b = 0; b < s; ++b)
        for (int g = 0; g < s; ++g)
            for (int r = 0; r < s; ++r, ++i) {
                const int idx[3] = {r, g, b};
                sol_check_item it;
                memset(&it, 0, sizeof it);
                it.index = i;
                for (int c = 0; c < 3; ++c) {
                    it.input[c] = lo[c] + (hi[c] - lo[c]) * idx[c] / (s - 1);
                    it.got[c] = engine->data[3 * i + (size_t)c];
                }
                sol_grade_apply(look, it.input, it.expected);
                double l1[3], l2[3];
                sol_srgb_to_lab(it.expected, l1);
                sol_srgb_to_lab(it.got, l2);
                it.error = sol_ciede2000(l1, l2);
                int bad = 0;
                for (int c = 0; c < 3; ++c)
                    bad |= !isfinite(it.got[c]);
                if (bad)
                    it.error = INFINITY;
                int mismatch = it.got[0] != (float)it.expected[0] || it.got[1] != (float)it.expected[1] ||
                               it.got[2] != (float)it.expected[2];
                check_add(&acc, &it, mismatch, !(it.error <= SOL_CHECK_TOL_LUT_DE00));
            }
    check_end(&acc, report);
    return SOL_OK;
}
