/* srgb.c - the sRGB transfer curve (IEC 61966-2-1), shared by the textures and hdr modules. */
#include "sol_core.h"

static double clamp01(double v)
{
    return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; /* NaN fails both tests and gives 0 */
}

double sol_srgb_encode(double linear)
{
    double v = clamp01(linear);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

double sol_srgb_decode(double encoded)
{
    double v = clamp01(encoded);
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}
