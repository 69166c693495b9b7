/* blocks.c - BC1 and BC5 checks: an engine's decoded texels against sol's bit-exact decoders
 * (sol_bc1_decode_block, sol_bc5_decode_block with its documented interpolant rounding), and an
 * engine's BC5 encoder against sol's common encoder on the same source (claims T8-T14). */
#include "check_internal.h"
#include "sol_textures.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int bad_size(int width, int height)
{
    return width <= 0 || height <= 0 || width % 4 || height % 4;
}

static uint32_t max_code(int bits)
{
    return (1u << bits) - 1u;
}

/* One texel of a decoder check: the item at (x, y) records sol's codes ref[0..n) and the engine's
 * e[0..n); its error is the largest |got[c] - ref[c]| (got: e, clamped where the caller needs it). */
static void add_texel(check_acc *acc, int x, int y, int width, int n, const uint32_t *ref, const uint16_t *e,
                      const uint32_t *got, double tolerance_codes)
{
    sol_check_item it;
    memset(&it, 0, sizeof it);
    it.index = (size_t)y * (size_t)width + (size_t)x;
    it.input[0] = x;
    it.input[1] = y;
    double worst = 0.0;
    int mismatch = 0;
    for (int c = 0; c < n; ++c) {
        it.expected[c] = ref[c];
        it.got[c] = e[c];
        double d = fabs((double)got[c] - (double)ref[c]);
        mismatch |= d != 0.0;
        worst = d > worst ? d : worst;
    }
    it.error = worst;
    check_add(acc, &it, mismatch, worst > tolerance_codes);
}

sol_status sol_check_bc5_decode(const uint8_t *blocks, int width, int height, sol_bc4_precision precision,
                                const uint16_t *texels, int channels, int bits, double tolerance_codes,
                                sol_check_report *report)
{
    if (!blocks || !texels || !report)
        return SOL_ERR_NULL_ARG;
    if (bad_size(width, height) || channels < 2 || channels > 4 || (bits != 8 && bits != 16) ||
        precision < 0 || precision >= SOL_BC4_PRECISION_COUNT || !(tolerance_codes >= 0.0))
        return SOL_ERR_INVALID_ARG;
    check_acc acc;
    check_begin(&acc, "code", tolerance_codes);
    const int bw = width / 4, bh = height / 4;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const uint8_t *p = blocks + 16 * ((size_t)by * (size_t)bw + (size_t)bx);
            sol_bc5_block blk;
            sol_bc4_unpack(p, &blk.x);
            sol_bc4_unpack(p + 8, &blk.y);
            double px[8], py[8];
            sol_bc4_palette(blk.x.e0, blk.x.e1, precision, px);
            sol_bc4_palette(blk.y.e0, blk.y.e1, precision, py);
            for (int t = 0; t < 16; ++t) {
                int x = 4 * bx + t % 4, y = 4 * by + t / 4;
                const uint16_t *e = texels + ((size_t)y * (size_t)width + (size_t)x) * (size_t)channels;
                uint32_t ref[2], got[2];
                for (int c = 0; c < 2; ++c) {
                    ref[c] = sol_unorm_encode((c ? py[blk.y.index[t]] : px[blk.x.index[t]]), bits);
                    got[c] = e[c] > max_code(bits) ? max_code(bits) + 1 : e[c];
                }
                add_texel(&acc, x, y, width, 2, ref, e, got, tolerance_codes);
            }
        }
    check_end(&acc, report);
    return SOL_OK;
}

sol_status sol_check_bc1_decode(const uint8_t *blocks, int width, int height, const uint16_t *texels, int channels,
                                int bits, double tolerance_codes, sol_check_report *report)
{
    if (!blocks || !texels || !report)
        return SOL_ERR_NULL_ARG;
    if (bad_size(width, height) || channels < 3 || channels > 4 || (bits != 8 && bits != 16) ||
        !(tolerance_codes >= 0.0))
        return SOL_ERR_INVALID_ARG;
    check_acc acc;
    check_begin(&acc, "code", tolerance_codes);
    const int bw = width / 4, bh = height / 4;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            uint8_t rgba[16][4];
            sol_bc1_decode_block(blocks + 8 * ((size_t)by * (size_t)bw + (size_t)bx), rgba);
            for (int t = 0; t < 16; ++t) {
                int x = 4 * bx + t % 4, y = 4 * by + t / 4;
                const uint16_t *e = texels + ((size_t)y * (size_t)width + (size_t)x) * (size_t)channels;
                uint32_t ref[3], got[3];
                for (int c = 0; c < 3; ++c) {
                    /* 8-bit texel at 16 bits: code * 257 (exact: 65535 / 255 = 257) */
                    ref[c] = bits == 8 ? rgba[t][c] : rgba[t][c] * 257u;
                    got[c] = e[c];
                }
                add_texel(&acc, x, y, width, 3, ref, e, got, tolerance_codes);
            }
        }
    check_end(&acc, report);
    return SOL_OK;
}

static int unit_normal(const float *v, double n[3])
{
    double l = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (!(l > 0.0) || !isfinite(l))
        return 0;
    for (int c = 0; c < 3; ++c)
        n[c] = v[c] / l;
    return 1;
}

/* Mean angle (deg) of decoded blocks against the source; items go to acc when given. */
static double mean_angle(const sol_image *src, const sol_image *dec, check_acc *acc, double tolerance)
{
    double sum = 0.0;
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; ++i) {
        double s[3], d[3] = {dec->data[3 * i], dec->data[3 * i + 1], dec->data[3 * i + 2]};
        unit_normal(src->data + i * (size_t)src->channels, s);
        double a = sol_angle3(s, d) * 180.0 / M_PI;
        sum += a;
        if (acc) {
            sol_check_item it;
            memset(&it, 0, sizeof it);
            it.index = i;
            it.input[0] = (double)(i % (size_t)src->width);
            it.input[1] = (double)(i / (size_t)src->width);
            memcpy(it.expected, s, sizeof s);
            memcpy(it.got, d, sizeof d);
            it.error = a;
            (void)tolerance;
            check_add(acc, &it, 0, 0);
        }
    }
    return sum / (double)n;
}

sol_status sol_check_bc5_encode_against(const sol_image *source, const uint8_t *blocks, sol_bc4_precision precision,
                                        sol_bc5_encoder reference, sol_check_report *report,
                                        double *reference_mean_deg, uint64_t *reference_bounded_blocks)
{
    if (!source || !source->data || !blocks || !report)
        return SOL_ERR_NULL_ARG;
    if (bad_size(source->width, source->height) || source->channels < 3)
        return SOL_ERR_INVALID_ARG;
    if ((int)reference < (int)SOL_BC5_COMMON || (int)reference > (int)SOL_BC5_FAST)
        return SOL_ERR_INVALID_ARG;
    size_t n = (size_t)source->width * (size_t)source->height;
    for (size_t i = 0; i < n; ++i) {
        double s[3];
        if (!unit_normal(source->data + i * (size_t)source->channels, s))
            return SOL_ERR_INVALID_ARG;
    }
    sol_image src3 = {0}, dec_engine = {0}, dec_ref = {0};
    uint8_t *ref_blocks = NULL;
    sol_status st = sol_image_alloc(&src3, source->width, source->height, 3);
    if (st != SOL_OK)
        return st;
    for (size_t i = 0; i < n; ++i)
        memcpy(src3.data + 3 * i, source->data + i * (size_t)source->channels, 3 * sizeof(float));
    ref_blocks = malloc(n); /* 16 bytes per 16 texels */
    if (!ref_blocks)
        st = SOL_ERR_NO_MEMORY;
    /* Defaults otherwise: sum-of-squares metric, the talk's +-4 window, the default work bound. */
    sol_bc5_options opt = {.encoder = reference, .precision = precision};
    sol_bc5_image_stats stats = {0};
    if (st == SOL_OK)
        st = sol_bc5_encode_image(&src3, &opt, ref_blocks, &stats);
    if (st == SOL_OK)
        st = sol_bc5_decode_image(ref_blocks, source->width, source->height, precision, &dec_ref);
    if (st == SOL_OK)
        st = sol_bc5_decode_image(blocks, source->width, source->height, precision, &dec_engine);
    if (st == SOL_OK) {
        double ref_mean = mean_angle(&src3, &dec_ref, NULL, 0.0);
        check_acc acc;
        check_begin(&acc, "deg", ref_mean * (1.0 + SOL_CHECK_BC5_ENCODER_SLACK));
        mean_angle(&src3, &dec_engine, &acc, 0.0);
        check_end(&acc, report);
        /* The criterion is on the mean: pass when the engine's mean is within the slack. */
        report->failures = report->mean <= report->tolerance ? 0 : 1;
        report->passed = report->failures == 0;
        if (reference_mean_deg)
            *reference_mean_deg = ref_mean;
        if (reference_bounded_blocks)
            *reference_bounded_blocks = stats.bounded_blocks;
    }
    free(ref_blocks);
    sol_image_free(&src3);
    sol_image_free(&dec_ref);
    sol_image_free(&dec_engine);
    return st;
}

sol_status sol_check_bc5_encode(const sol_image *source, const uint8_t *blocks, sol_bc4_precision precision,
                                sol_check_report *report, double *reference_mean_deg)
{
    return sol_check_bc5_encode_against(source, blocks, precision, SOL_BC5_COMMON, report, reference_mean_deg, NULL);
}

/* Mean per-texel RGB error (8-bit codes) of BC1 blocks against the source; items go to acc. */
static double bc1_mean_error(const sol_image *src, const uint8_t *blocks, check_acc *acc)
{
    double sum = 0.0;
    const int bw = src->width / 4, bh = src->height / 4;
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            uint8_t rgba[16][4];
            sol_bc1_decode_block(blocks + 8 * ((size_t)by * (size_t)bw + (size_t)bx), rgba);
            for (int t = 0; t < 16; ++t) {
                int x = 4 * bx + t % 4, y = 4 * by + t / 4;
                const float *p = sol_image_pixel(src, x, y);
                double se = 0.0;
                sol_check_item it;
                memset(&it, 0, sizeof it);
                for (int c = 0; c < 3; ++c) {
                    double d = 255.0 * p[c] - rgba[t][c];
                    se += d * d;
                    it.expected[c] = 255.0 * p[c];
                    it.got[c] = rgba[t][c];
                }
                it.error = sqrt(se / 3.0);
                sum += it.error;
                if (acc) {
                    it.index = (size_t)y * (size_t)src->width + (size_t)x;
                    it.input[0] = x;
                    it.input[1] = y;
                    check_add(acc, &it, 0, 0);
                }
            }
        }
    return sum / ((double)src->width * (double)src->height);
}

sol_status sol_check_bc1_encode(const sol_image *source, const uint8_t *blocks, sol_check_report *report,
                                double *reference_mean)
{
    if (!source || !source->data || !blocks || !report)
        return SOL_ERR_NULL_ARG;
    if (bad_size(source->width, source->height) || source->channels < 3)
        return SOL_ERR_INVALID_ARG;
    uint8_t *ref = malloc(sol_bc1_size(source->width, source->height));
    if (!ref)
        return SOL_ERR_NO_MEMORY;
    sol_status st = sol_bc1_encode(source, NULL, ref); /* validates the source values too */
    if (st == SOL_OK) {
        double ref_mean = bc1_mean_error(source, ref, NULL);
        check_acc acc;
        check_begin(&acc, "code", ref_mean * (1.0 + SOL_CHECK_BC1_ENCODER_SLACK));
        bc1_mean_error(source, blocks, &acc);
        check_end(&acc, report);
        report->failures = report->mean <= report->tolerance ? 0 : 1;
        report->passed = report->failures == 0;
        if (reference_mean)
            *reference_mean = ref_mean;
    }
    free(ref);
    return st;
}
