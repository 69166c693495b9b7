/* exposure.c - automatic exposure after Narkowicz's notes "Automatic Exposure" (claim S6): EV100
 * units (L = 0.125 * 2^EV100, after N. Reed 2014), histogram metering that drops the darkest and
 * brightest pixels, the Krawczyk-Myszkowski-Seidel 2005 key value curve, exponential adaptation. */
#include "sol_hdr.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

double sol_ev100_from_luminance(double luminance) { return log2(luminance / 0.125); }
double sol_luminance_from_ev100(double ev100) { return 0.125 * exp2(ev100); }

double sol_krawczyk_key(double luminance)
{
    if (!(luminance > 0.0)) /* a negative luminance (log10 of <= 0) is taken as 0; NaN stays NaN */
        return isnan(luminance) ? luminance : 1.03 - 2.0 / 2.0;
    return 1.03 - 2.0 / (log10(luminance + 1.0) + 2.0);
}

double sol_adapt_exponential(double previous, double target, double dt, double rate)
{
    if (!(dt >= 0.0) || !(rate >= 0.0) || isinf(dt) || isinf(rate))
        return previous;
    double k = -expm1(-dt * rate), d = target - previous;
    if (isinf(d) && isfinite(previous) && isfinite(target)) /* +-DBL_MAX apart: convex form instead */
        return previous * (1.0 - k) + target * k;
    return previous + d * k;
}

sol_status sol_exposure_from_luminance(double luminance, double compensation_ev, double *exposure)
{
    if (!exposure)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(luminance) || !isfinite(compensation_ev))
        return SOL_ERR_NONFINITE;
    if (luminance <= 0.0)
        return SOL_ERR_INVALID_ARG;
    double e = 0.18 * exp2(compensation_ev) / luminance;
    if (!(e <= DBL_MAX) || !(e >= DBL_MIN)) {
        /* exp2(ec) or the quotient over/underflowed: with L = m 2^k (m in [0.5, 1)) and
         * ec = i + f (i integer, f in [0, 1)), e = (0.18 2^f / m) 2^(i - k); the ldexp rounds once */
        int k;
        double m = frexp(luminance, &k), ei = floor(compensation_ev), scale = ei - k;
        if (scale > 2100.0)
            return SOL_ERR_OUT_OF_RANGE;
        e = scale < -2100.0 ? 0.0 : ldexp(0.18 * exp2(compensation_ev - ei) / m, (int)scale);
        if (!(e <= DBL_MAX))
            return SOL_ERR_OUT_OF_RANGE;
    }
    *exposure = e;
    return SOL_OK;
}

/* Takes `amount` of weight off one end of the histogram (walking from `from` in steps of `dir`). */
static void trim_histogram(double *hist, int bins, double amount, int from, int dir)
{
    for (int i = from; i >= 0 && i < bins && amount > 0.0; i += dir) {
        double take = hist[i] < amount ? hist[i] : amount;
        hist[i] -= take;
        amount -= take;
    }
}

sol_status sol_histogram_meter(const float *luminance, size_t n, const sol_meter_options *options,
                               double *metered_luminance, size_t *ignored)
{
    if (!luminance || !metered_luminance)
        return SOL_ERR_NULL_ARG;
    sol_meter_options o = options ? *options : (sol_meter_options){0};
    int bins = o.bins > 0 ? o.bins : 64;
    double ev_min = o.ev_min, ev_max = o.ev_max;
    if (ev_min == 0.0 && ev_max == 0.0) {
        ev_min = -8.0;
        ev_max = 24.0;
    }
    double dark = o.skip_dark == 0.0 ? 0.6 : (o.skip_dark < 0.0 ? 0.0 : o.skip_dark);
    double bright = o.skip_bright == 0.0 ? 0.1 : (o.skip_bright < 0.0 ? 0.0 : o.skip_bright);
    if (n == 0 || !(ev_max > ev_min) || !(dark + bright < 1.0))
        return SOL_ERR_INVALID_ARG;
    double *hist = calloc((size_t)bins, sizeof *hist);
    if (!hist)
        return SOL_ERR_NO_MEMORY;
    size_t skipped = 0;
    double bin_width = (ev_max - ev_min) / bins;
    for (size_t k = 0; k < n; ++k) {
        double l = luminance[k];
        if (!isfinite(l) || l < 0.0) {
            ++skipped;
            continue;
        }
        /* Fractional position between bin centres; a pixel feeds its two nearest bins. */
        double pos = (sol_ev100_from_luminance(l) - ev_min) / bin_width - 0.5;
        pos = pos < 0.0 ? 0.0 : (pos > bins - 1 ? bins - 1 : pos);
        int i = (int)pos;
        double w = pos - i;
        hist[i] += 1.0 - w;
        if (w > 0.0)
            hist[i + 1] += w;
    }
    size_t used = n - skipped;
    sol_status st = SOL_ERR_INVALID_ARG;
    if (used > 0) {
        trim_histogram(hist, bins, dark * (double)used, 0, 1);
        trim_histogram(hist, bins, bright * (double)used, bins - 1, -1);
        double weight = 0.0, ev_sum = 0.0;
        for (int i = 0; i < bins; ++i) {
            weight += hist[i];
            ev_sum += hist[i] * (ev_min + (i + 0.5) * bin_width);
        }
        if (weight > 0.0) {
            *metered_luminance = sol_luminance_from_ev100(ev_sum / weight);
            if (ignored)
                *ignored = skipped;
            st = SOL_OK;
        }
    }
    free(hist);
    return st;
}
