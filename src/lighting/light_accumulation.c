/* light_accumulation.c - S2: Mittring 2009 (seed 004), "Options for the light accumulation
 * texture": 6 channels keep diffuse and specular RGB; 4 channels keep diffuse RGB and a specular
 * strength, and rebuild specular as diffuse * strength. Here the strength is the sum of the
 * specular luminances (additive, so it can be blended light by light) and the rebuilt specular is
 * D * A / lum(D): its luminance is always right, only its hue can be wrong. */
#include "sol_lighting.h"

double sol_luminance(const double rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

sol_status sol_light_accum_add(sol_light_accum *acc, const double colour[3], double diffuse, double specular)
{
    if (!acc || !colour)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(colour[0]) || !isfinite(colour[1]) || !isfinite(colour[2]) || !isfinite(diffuse) ||
        !isfinite(specular))
        return SOL_ERR_NONFINITE;
    if (colour[0] < 0.0 || colour[1] < 0.0 || colour[2] < 0.0 || diffuse < 0.0 || specular < 0.0)
        return SOL_ERR_INVALID_ARG;
    for (int c = 0; c < 3; ++c) {
        acc->diffuse[c] += colour[c] * diffuse;
        acc->specular[c] += colour[c] * specular;
    }
    acc->strength += sol_luminance(colour) * specular;
    return SOL_OK;
}

sol_status sol_light_accum_specular4(const sol_light_accum *acc, double specular[3])
{
    if (!acc || !specular)
        return SOL_ERR_NULL_ARG;
    double lum = sol_luminance(acc->diffuse);
    for (int c = 0; c < 3; ++c)
        specular[c] = lum > 0.0 ? (acc->diffuse[c] / lum) * acc->strength : acc->strength; /* ratio <= 1/0.0722 */
    return SOL_OK;
}
