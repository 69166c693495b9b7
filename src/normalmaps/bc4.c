/* bc4.c - BC4 palettes, block packing and the least-squares BC4 encoder (the "alpha block" half of
 * a 3Dc block, T10). The per-channel anchor-pair bounds it searches with are in anchor_bounds.c. */
#include "normalmaps_internal.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

/* Palette entry i in [0,1] for the D3D10 BC4 rules (see sol_normalmaps.h). The interpolated entries
 * are num / den with num = w0 e0 + w1 e1; 8-bit decoders round them to a code, 16-bit decoders to
 * a 16-bit code (255 * 257 = 65535), float decoders keep them exact. */
static double interpolant(int num, int den, sol_bc4_precision precision)
{
    switch (precision) {
    case SOL_BC4_INTERP_8BIT:
        return (double)((2 * num + den) / (2 * den)) / 255.0; /* round half up; num/den never ties */
    case SOL_BC4_INTERP_16BIT:
        return (double)((2 * num * 257 + den) / (2 * den)) / 65535.0;
    default:
        return (double)num / ((double)den * 255.0);
    }
}

static void palette_values(int e0, int e1, sol_bc4_precision precision, double out[8])
{
    out[0] = e0 / 255.0;
    out[1] = e1 / 255.0;
    if (e0 > e1) {
        for (int i = 2; i < 8; ++i)
            out[i] = interpolant((8 - i) * e0 + (i - 1) * e1, 7, precision);
    } else {
        for (int i = 2; i < 6; ++i)
            out[i] = interpolant((6 - i) * e0 + (i - 1) * e1, 5, precision);
        out[6] = 0.0;
        out[7] = 1.0;
    }
}

sol_status sol_bc4_palette(uint8_t e0, uint8_t e1, sol_bc4_precision precision, double out[8])
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)precision >= SOL_BC4_PRECISION_COUNT)
        return SOL_ERR_INVALID_ARG;
    palette_values(e0, e1, precision, out);
    return SOL_OK;
}

/* 65536 palettes x 8 entries per precision, decoded units; 4 MB each, built on first use. */
static double palette_table[SOL_BC4_PRECISION_COUNT][65536][8];
static pthread_once_t palette_once[SOL_BC4_PRECISION_COUNT] = {PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT,
                                                               PTHREAD_ONCE_INIT};

static void build_table(sol_bc4_precision precision)
{
    for (int pair = 0; pair < 65536; ++pair) {
        double v[8];
        palette_values(pair >> 8, pair & 255, precision, v);
        for (int i = 0; i < 8; ++i)
            palette_table[precision][pair][i] = 2.0 * v[i] - 1.0;
    }
}
static void build_16bit(void) { build_table(SOL_BC4_INTERP_16BIT); }
static void build_8bit(void) { build_table(SOL_BC4_INTERP_8BIT); }
static void build_float(void) { build_table(SOL_BC4_INTERP_FLOAT); }

const double (*sol_nm_palettes(sol_bc4_precision precision))[8]
{
    static void (*const builders[SOL_BC4_PRECISION_COUNT])(void) = {build_16bit, build_8bit, build_float};
    pthread_once(&palette_once[precision], builders[precision]);
    return (const double(*)[8])palette_table[precision];
}

sol_status sol_bc4_pack(const sol_bc4_block *block, uint8_t out[8])
{
    if (!block || !out)
        return SOL_ERR_NULL_ARG;
    uint64_t bits = 0;
    for (int p = 0; p < 16; ++p) {
        if (block->index[p] > 7)
            return SOL_ERR_INVALID_ARG;
        bits |= (uint64_t)block->index[p] << (3 * p);
    }
    out[0] = block->e0;
    out[1] = block->e1;
    for (int i = 0; i < 6; ++i)
        out[2 + i] = (uint8_t)(bits >> (8 * i));
    return SOL_OK;
}

sol_status sol_bc4_unpack(const uint8_t in[8], sol_bc4_block *out)
{
    if (!in || !out)
        return SOL_ERR_NULL_ARG;
    uint64_t bits = 0;
    for (int i = 0; i < 6; ++i)
        bits |= (uint64_t)in[2 + i] << (8 * i);
    out->e0 = in[0];
    out->e1 = in[1];
    for (int p = 0; p < 16; ++p)
        out->index[p] = (uint8_t)((bits >> (3 * p)) & 7);
    return SOL_OK;
}

/* ---- least-squares BC4 ---- */

int sol_nm_nearest_index(const double pal[8], double t)
{
    int best = 0;
    for (int i = 1; i < 8; ++i)
        if (fabs(pal[i] - t) < fabs(pal[best] - t))
            best = i;
    return best;
}

sol_status sol_nm_bc4_targets(const double values[16], double t[16])
{
    for (int p = 0; p < 16; ++p) {
        if (!isfinite(values[p]))
            return SOL_ERR_NONFINITE;
        if (values[p] < 0.0 || values[p] > 1.0)
            return SOL_ERR_OUT_OF_RANGE;
        t[p] = 2.0 * values[p] - 1.0;
    }
    return SOL_OK;
}

sol_status sol_bc4_encode_block(const double values[16], sol_bc4_precision precision, sol_bc4_block *out,
                                double *squared_error)
{
    if (!values || !out)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)precision >= SOL_BC4_PRECISION_COUNT)
        return SOL_ERR_INVALID_ARG;
    double t[16];
    sol_status st = sol_nm_bc4_targets(values, t);
    if (st != SOL_OK)
        return st;
    double score;
    int pair = sol_nm_bc4_common(t, precision, &score);
    const double *pal = sol_nm_palettes(precision)[pair];
    out->e0 = (uint8_t)(pair >> 8);
    out->e1 = (uint8_t)(pair & 255);
    sol_nm_nearest_indices(pal, t, out->index);
    if (squared_error)
        *squared_error = score / 4.0; /* decoded units are 2 v - 1 */
    return SOL_OK;
}
