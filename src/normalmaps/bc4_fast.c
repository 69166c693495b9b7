/* bc4_fast.c - the usual fast BC4 ("alpha block") encoder, the per-channel encoder the talk calls
 * usual (T10, T13): anchors at the block's extremes, as the DXT5 alpha encoders of libsquish
 * (S. Brown) and NVIDIA Texture Tools' fast path choose them, palettes interpolated at 8 bits.
 *
 * Two candidates, the better kept by their squared error against the 8-bit palettes:
 *   8-value mode: e0 = the largest value's code, e1 = the smallest's (e0 > e1);
 *   6-value mode: e0 = the smallest, e1 = the largest code of the values that are not served
 *                 exactly by the mode's fixed entries 0 and 255.
 * Each value takes its nearest palette entry. No search over anchors: one pass over the block. */
#include "normalmaps_internal.h"

#include <math.h>

static double squared_error(const double pal[8], const double t[16], uint8_t index[16])
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        int i = sol_nm_nearest_index(pal, t[p]);
        index[p] = (uint8_t)i;
        s += (pal[i] - t[p]) * (pal[i] - t[p]);
    }
    return s;
}

void sol_nm_bc4_fast(const double t[16], sol_bc4_block *out)
{
    /* codes of the targets (decoded units 2 v - 1 -> 0..255) */
    int lo = 255, hi = 0, lo6 = 255, hi6 = 0;
    for (int p = 0; p < 16; ++p) {
        double v = (t[p] + 1.0) * 127.5;
        int c = v <= 0.0 ? 0 : (v >= 255.0 ? 255 : (int)lrint(v));
        lo = c < lo ? c : lo;
        hi = c > hi ? c : hi;
        if (c != 0 && c != 255) {
            lo6 = c < lo6 ? c : lo6;
            hi6 = c > hi6 ? c : hi6;
        }
    }
    if (lo6 > hi6) /* every value is 0 or 255: the fixed entries serve them */
        lo6 = hi6 = lo;
    const double(*pal)[8] = sol_nm_palettes(SOL_BC4_INTERP_8BIT);
    sol_bc4_block eight = {(uint8_t)hi, (uint8_t)lo, {0}}, six = {(uint8_t)lo6, (uint8_t)hi6, {0}};
    double e6 = squared_error(pal[six.e0 << 8 | six.e1], t, six.index);
    if (hi > lo) {
        double e8 = squared_error(pal[eight.e0 << 8 | eight.e1], t, eight.index);
        if (e8 <= e6) {
            *out = eight;
            return;
        }
    }
    *out = six;
}

sol_status sol_bc4_encode_block_fast(const double values[16], sol_bc4_block *out)
{
    if (!values || !out)
        return SOL_ERR_NULL_ARG;
    double t[16];
    sol_status st = sol_nm_bc4_targets(values, t);
    if (st != SOL_OK)
        return st;
    sol_nm_bc4_fast(t, out);
    return SOL_OK;
}
