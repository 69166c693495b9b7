/* hdr_encodings.c - HDR in 8/10-bit fixed point: RGBM/RGBK (claim D9), Tesseract's RGB10 scaled
 * to 0..2 (claim S9) and the two-channel rational depth x + y/255 (claim M2). */
#include "sol_hdr.h"

#include <float.h>
#include <math.h>

/* Clamps to [0, hi]; NaN gives 0 (the D3D float-to-UNORM rule). */
static double clamp_store(double v, double hi)
{
    if (!(v > 0.0))
        return 0.0;
    return v < hi ? v : hi;
}

/* RGBM as in the talk's PS3 path ("RGBK (aka RGBM) compression", slide "HDR on consoles"):
 * a shared multiplier in alpha, rounded UP so that every channel / (m * range) stays <= 1. */
sol_status sol_rgbm_encode(const float rgb[3], double range, uint8_t rgbm[4])
{
    if (!rgb || !rgbm)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(range) || range <= 0.0)
        return SOL_ERR_INVALID_ARG;
    double c[3], peak = 0.0;
    for (int i = 0; i < 3; ++i) {
        c[i] = clamp_store(rgb[i], range);
        peak = c[i] > peak ? c[i] : peak;
    }
    if (peak == 0.0) {
        rgbm[0] = rgbm[1] = rgbm[2] = rgbm[3] = 0;
        return SOL_OK;
    }
    double m_code = ceil(peak / range * 255.0);
    if (m_code < 1.0)
        m_code = 1.0;
    double scale = m_code / 255.0 * range;
    for (int i = 0; i < 3; ++i)
        rgbm[i] = (uint8_t)sol_unorm_encode(c[i] / scale, 8);
    rgbm[3] = (uint8_t)m_code;
    return SOL_OK;
}

sol_status sol_rgbm_decode(const uint8_t rgbm[4], double range, float rgb[3])
{
    if (!rgb || !rgbm)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(range) || range <= 0.0)
        return SOL_ERR_INVALID_ARG;
    double scale = sol_unorm_decode(rgbm[3], 8) * range, v[3];
    for (int i = 0; i < 3; ++i) {
        v[i] = sol_unorm_decode(rgbm[i], 8) * scale;
        if (v[i] > FLT_MAX) /* a range above FLT_MAX: the float output cannot hold it */
            return SOL_ERR_OUT_OF_RANGE;
    }
    for (int i = 0; i < 3; ++i)
        rgb[i] = (float)v[i];
    return SOL_OK;
}

/* Tesseract notes: "a fallback RGB10 fixed-point format ... scaled to a 0..2 range". */
uint32_t sol_rgb10_scaled_encode(float v)
{
    return sol_unorm_encode(clamp_store(v, 2.0) * 0.5, 10);
}

float sol_rgb10_scaled_decode(uint32_t code)
{
    return (float)(2.0 * sol_unorm_decode(code & 0x3ffu, 10));
}

/* Talk, "SSAO improvements": linear depth as a rational depth = x + y/255 in two 8-bit channels.
 * x keeps the integer part of 255 d, y the remaining fraction at 8 bits. */
void sol_depth_rg8_encode(double depth, uint8_t xy[2])
{
    double scaled = clamp_store(depth, 1.0) * 255.0;
    double hi = floor(scaled);
    xy[0] = (uint8_t)hi;
    xy[1] = (uint8_t)sol_unorm_encode(scaled - hi, 8);
}

double sol_depth_rg8_decode(const uint8_t xy[2])
{
    return (double)xy[0] / 255.0 + (double)xy[1] / (255.0 * 255.0);
}

void sol_depth_rg8_encode_rounded_x(double depth, uint8_t xy[2])
{
    double scaled = clamp_store(depth, 1.0) * 255.0;
    xy[0] = (uint8_t)sol_unorm_encode(scaled / 255.0, 8);
    xy[1] = (uint8_t)sol_unorm_encode(scaled - floor(scaled), 8);
}
