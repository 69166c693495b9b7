/* storage.c - the linear/gamma storage classifier (claim T4).
 *
 * Talk, slide "Gamma vs linear space for color textures": "use linear if >75% of pixels are above
 * the median", the median being the equal-density point of linear and gamma storage. sol's
 * default median is the consistent equal-density point of the 2.2 power curve (see
 * sol_transfer_equal_density), not the talk's 5/11; both are options. */
#include <math.h>

#include "sol_textures.h"

static sol_status resolve_options(const sol_storage_options *options, double *median, double *threshold)
{
    *median = options ? options->median : 0.0;
    *threshold = options ? options->threshold : 0.0;
    if (*median == 0.0) {
        sol_transfer power = {SOL_TRANSFER_POWER, 2.2};
        double hi;
        sol_status st = sol_transfer_equal_density(&power, 0.0, median, &hi);
        if (st)
            return st;
    }
    if (*threshold == 0.0)
        *threshold = 0.75;
    if (!(*median > 0.0 && *median < 1.0) || !(*threshold > 0.0 && *threshold < 1.0))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

sol_status sol_storage_classify(const sol_image *linear_image, const sol_storage_options *options,
                                sol_storage *choice, double *fraction_above)
{
    if (!linear_image || !linear_image->data || !choice)
        return SOL_ERR_NULL_ARG;
    if (linear_image->width <= 0 || linear_image->height <= 0 || linear_image->channels < 1)
        return SOL_ERR_INVALID_ARG;
    double median, threshold;
    sol_status st = resolve_options(options, &median, &threshold);
    if (st)
        return st;
    int used = linear_image->channels < 3 ? linear_image->channels : 3;
    size_t above = 0, total = 0, pixels = (size_t)linear_image->width * (size_t)linear_image->height;
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < used; ++c) {
            float v = linear_image->data[p * (size_t)linear_image->channels + (size_t)c];
            if (!isfinite(v))
                return SOL_ERR_NONFINITE;
            above += v > median;
            ++total;
        }
    double fraction = (double)above / (double)total;
    *choice = fraction > threshold ? SOL_STORAGE_LINEAR : SOL_STORAGE_GAMMA;
    if (fraction_above)
        *fraction_above = fraction;
    return SOL_OK;
}
