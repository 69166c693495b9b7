/* pack.c - bit-exact checks of an engine's packed HDR values (R11G11B10F, fp16, RGBM, RGB10 0..2,
 * two-channel depth) against sol_hdr.h's encoders (claims D9, M2, S9). */
#include "check_internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

static const char *const pack_names[SOL_CHECK_PACK_COUNT] = {"r11g11b10f", "fp16", "rgbm", "rgb10", "depth-rg8"};

const char *sol_check_pack_name(sol_check_pack_format format)
{
    return format >= 0 && format < SOL_CHECK_PACK_COUNT ? pack_names[format] : NULL;
}

int sol_check_pack_inputs(sol_check_pack_format format)
{
    switch (format) {
    case SOL_CHECK_PACK_R11G11B10F:
    case SOL_CHECK_PACK_RGBM:
    case SOL_CHECK_PACK_RGB10: return 3;
    case SOL_CHECK_PACK_FP16:
    case SOL_CHECK_PACK_DEPTH_RG8: return 1;
    default: return 0;
    }
}

static double rgbm_range(double param)
{
    return param == 0.0 ? 6.0 : param;
}

sol_status sol_check_pack_reference(sol_check_pack_format format, const float *value, double param, uint32_t *bits)
{
    if (!value || !bits)
        return SOL_ERR_NULL_ARG;
    uint8_t b[4];
    switch (format) {
    case SOL_CHECK_PACK_R11G11B10F: *bits = sol_r11g11b10f_pack(value); return SOL_OK;
    case SOL_CHECK_PACK_FP16: *bits = sol_half_from_float(value[0]); return SOL_OK;
    case SOL_CHECK_PACK_RGBM: {
        sol_status st = sol_rgbm_encode(value, rgbm_range(param), b);
        if (st != SOL_OK)
            return st;
        *bits = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        return SOL_OK;
    }
    case SOL_CHECK_PACK_RGB10:
        *bits = sol_rgb10_scaled_encode(value[0]) | sol_rgb10_scaled_encode(value[1]) << 10 |
                sol_rgb10_scaled_encode(value[2]) << 20;
        return SOL_OK;
    case SOL_CHECK_PACK_DEPTH_RG8:
        sol_depth_rg8_encode(value[0], b);
        *bits = (uint32_t)b[0] | (uint32_t)b[1] << 8;
        return SOL_OK;
    default: return SOL_ERR_INVALID_ARG;
    }
}

/* Decoded values of packed bits (up to 3). */
static int unpack(sol_check_pack_format format, uint32_t bits, double param, double out[3])
{
    float f[3];
    uint8_t b[4] = {(uint8_t)bits, (uint8_t)(bits >> 8), (uint8_t)(bits >> 16), (uint8_t)(bits >> 24)};
    switch (format) {
    case SOL_CHECK_PACK_R11G11B10F:
        sol_r11g11b10f_unpack(bits, f);
        break;
    case SOL_CHECK_PACK_FP16:
        out[0] = sol_half_to_float((uint16_t)bits);
        return 1;
    case SOL_CHECK_PACK_RGBM:
        sol_rgbm_decode(b, rgbm_range(param), f);
        break;
    case SOL_CHECK_PACK_RGB10:
        for (int c = 0; c < 3; ++c)
            f[c] = sol_rgb10_scaled_decode((bits >> (10 * c)) & 1023u);
        break;
    default:
        out[0] = sol_depth_rg8_decode(b);
        return 1;
    }
    for (int c = 0; c < 3; ++c)
        out[c] = f[c];
    return 3;
}

/* Bits are equal, or both NaN of the format (any payload). */
static int same_bits(sol_check_pack_format format, uint32_t a, uint32_t b)
{
    if (a == b)
        return 1;
    if (format == SOL_CHECK_PACK_FP16)
        return (a & 0x7c00u) == 0x7c00u && (a & 0x3ffu) && (b & 0x7c00u) == 0x7c00u && (b & 0x3ffu) &&
               !(b >> 16);
    if (format == SOL_CHECK_PACK_R11G11B10F) {
        static const int shift[3] = {0, 11, 22}, mbits[3] = {6, 6, 5};
        for (int c = 0; c < 3; ++c) {
            uint32_t w = c == 2 ? 10 : 11, m = (1u << w) - 1u;
            uint32_t fa = (a >> shift[c]) & m, fb = (b >> shift[c]) & m, e = 31u << mbits[c];
            uint32_t mm = (1u << mbits[c]) - 1u;
            int nan_a = (fa & e) == e && (fa & mm), nan_b = (fb & e) == e && (fb & mm);
            if (fa != fb && !(nan_a && nan_b))
                return 0;
        }
        return 1;
    }
    return 0;
}

sol_status sol_check_pack(sol_check_pack_format format, const float *values, const uint32_t *bits, size_t n,
                          double param, sol_check_report *report)
{
    if (!values || !bits || !report)
        return SOL_ERR_NULL_ARG;
    int k = sol_check_pack_inputs(format);
    if (n == 0 || k == 0 || (format == SOL_CHECK_PACK_RGBM && (!isfinite(param) || param < 0.0)))
        return SOL_ERR_INVALID_ARG;
    check_acc acc;
    check_begin(&acc, "rel", 0.0);
    for (size_t i = 0; i < n; ++i) {
        const float *v = values + i * (size_t)k;
        uint32_t ref;
        sol_status st = sol_check_pack_reference(format, v, param, &ref);
        if (st != SOL_OK)
            return st; /* only RGBM with a bad range fails, and that was checked above */
        sol_check_item it;
        memset(&it, 0, sizeof it);
        it.index = i;
        for (int c = 0; c < k; ++c)
            it.input[c] = v[c];
        it.input[3] = bits[i];
        int m = unpack(format, ref, param, it.expected);
        unpack(format, bits[i], param, it.got);
        double worst = 0.0;
        for (int c = 0; c < m; ++c) {
            double e = it.expected[c], g = it.got[c], d;
            if (isnan(e) || isnan(g))
                d = isnan(e) && isnan(g) ? 0.0 : INFINITY;
            else if (isinf(e) || isinf(g))
                d = e == g ? 0.0 : INFINITY;
            else
                d = fabs(g - e) / fmax(fabs(e), 0x1p-14);
            worst = d > worst ? d : worst;
        }
        it.error = worst;
        int mismatch = !same_bits(format, ref, bits[i]);
        check_add(&acc, &it, mismatch, mismatch);
    }
    check_end(&acc, report);
    return SOL_OK;
}

/* Edge floats: signed zeros, denormals, fp16/R11G11B10F limits and their ties, overflow, Inf, NaN. */
static const float edge_floats[] = {
    0.0f, -0.0f, 1.0f, 0.5f, 2.0f, 6.0f, 8.0f, 0.18f, 1.0f / 3.0f,
    FLT_MIN, 1e-45f, -1e-45f, 0x1p-24f, 0x1p-25f, 0x1.8p-24f, 0x1p-14f, 0x1p-15f, 0x1p-20f, 6.0e-5f,
    65504.0f, 65519.0f, 65520.0f, 65536.0f, -65504.0f, 65024.0f, 64512.0f, 65023.0f, 64511.0f, 66000.0f,
    1.0f + 0x1p-7f, 1.0f + 0x1p-6f, 1.0f + 0x1.8p-7f, 1.0f + 0x1.8p-6f, 1.0f + 0x1p-11f, 1.0f + 0x1.8p-11f,
    1.0f + 0x1p-12f, 0.999f, 1.999f, 2.0f - 0x1p-10f, 5.99f, 6.001f, 1e10f, FLT_MAX, -1.0f, -FLT_MAX,
    INFINITY, -INFINITY, NAN,
};

const float *sol_check_edge_floats(size_t *count)
{
    if (count)
        *count = sizeof edge_floats / sizeof edge_floats[0];
    return edge_floats;
}
