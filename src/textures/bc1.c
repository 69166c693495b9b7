/* bc1.c - BC1 (DXT1) encoder and decoder (claims T1, T2).
 *
 * Block layout (D3D10 functional specification, "BC1"): two little-endian 5:6:5 endpoints c0, c1,
 * then 16 two-bit indices, texel i (row-major) in bits 2i..2i+1 of the last 4 bytes. The decoding
 * rule is documented in sol_textures.h. The encoder works in 8-bit units on float input (a 16-bit
 * source keeps its precision up to the 5:6:5 grid). Its effort levels follow the classic line of
 * BC1 encoders: bounding-box range fit, principal-axis range fit, least-squares refinement of the
 * endpoints for fixed indices, and the ordered cluster fit of S. Brown's libsquish (every split of
 * the 16 texels, sorted along the principal axis, into four consecutive clusters; endpoints by
 * least squares and snapped to the 5:6:5 grid). The code is sol's own. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "sol_textures.h"

typedef struct endpoints {
    int q[2][3]; /* 5:6:5 codes of the two endpoints, (r, g, b) */
} endpoints;

static const int channel_max[3] = {31, 63, 31};
/* Weight of endpoint 0 for each index in four-color mode. */
static const float index_weight0[4] = {1.0f, 0.0f, 2.0f / 3.0f, 1.0f / 3.0f};

static int expand_code(int code, int c)
{
    return c == 1 ? (code << 2) | (code >> 4) : (code << 3) | (code >> 2);
}

/* The code whose bit-replicated expansion is nearest to v (0..255). */
static int nearest_code(float v, int c)
{
    int best = (int)lrintf(v * (float)channel_max[c] / 255.0f), best_code = 0;
    float best_d = FLT_MAX;
    for (int q = best - 1; q <= best + 1; ++q) {
        if (q < 0 || q > channel_max[c])
            continue;
        float d = fabsf((float)expand_code(q, c) - v);
        if (d < best_d) {
            best_d = d;
            best_code = q;
        }
    }
    return best_code;
}

/* Clamp to [0,255] with plain comparisons (fminf/fmaxf may be library calls in the hot loop). */
static inline float clamp255(float v) { return v < 0.0f ? 0.0f : (v > 255.0f ? 255.0f : v); }

static uint16_t pack565(const int q[3]) { return (uint16_t)(q[0] << 11 | q[1] << 5 | q[2]); }

static void unpack565(uint16_t c, int rgb[3])
{
    rgb[0] = expand_code(c >> 11, 0);
    rgb[1] = expand_code((c >> 5) & 63, 1);
    rgb[2] = expand_code(c & 31, 2);
}

/* The decoder's palette (sol_textures.h rule); alpha 0 marks transparent black. */
static void bc1_palette(uint16_t c0, uint16_t c1, int pal[4][4])
{
    unpack565(c0, pal[0]);
    unpack565(c1, pal[1]);
    pal[0][3] = pal[1][3] = pal[2][3] = pal[3][3] = 255;
    for (int c = 0; c < 3; ++c) {
        if (c0 > c1) {
            pal[2][c] = (2 * pal[0][c] + pal[1][c] + 1) / 3;
            pal[3][c] = (pal[0][c] + 2 * pal[1][c] + 1) / 3;
        } else {
            pal[2][c] = (pal[0][c] + pal[1][c] + 1) / 2;
            pal[3][c] = 0;
        }
    }
    if (c0 <= c1)
        pal[3][3] = 0;
}

void sol_bc1_decode_block(const uint8_t block[8], uint8_t rgba[16][4])
{
    uint16_t c0 = (uint16_t)(block[0] | block[1] << 8), c1 = (uint16_t)(block[2] | block[3] << 8);
    uint32_t bits = (uint32_t)block[4] | (uint32_t)block[5] << 8 | (uint32_t)block[6] << 16 | (uint32_t)block[7] << 24;
    int pal[4][4];
    bc1_palette(c0, c1, pal);
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c)
            rgba[i][c] = (uint8_t)pal[(bits >> (2 * i)) & 3][c];
}

/* Orders the endpoints for four-color mode and picks each texel's nearest palette entry.
 * Returns the squared error in 8-bit units; fills the block when `block` is not NULL. */
static float evaluate(const endpoints *e, const float pts[16][3], uint8_t *block)
{
    uint16_t c0 = pack565(e->q[0]), c1 = pack565(e->q[1]);
    if (c0 < c1) {
        uint16_t t = c0;
        c0 = c1;
        c1 = t;
    }
    int pal[4][4];
    bc1_palette(c0, c1, pal);
    int usable = c0 > c1 ? 4 : 1; /* c0 == c1: one color, keep off the transparent entry */
    float total = 0.0f;
    uint32_t bits = 0;
    for (int i = 0; i < 16; ++i) {
        float best = FLT_MAX;
        int best_k = 0;
        for (int k = 0; k < usable; ++k) {
            float d = 0.0f;
            for (int c = 0; c < 3; ++c) {
                float diff = (float)pal[k][c] - pts[i][c];
                d += diff * diff;
            }
            if (d < best) {
                best = d;
                best_k = k;
            }
        }
        total += best;
        bits |= (uint32_t)best_k << (2 * i);
    }
    if (block) {
        block[0] = (uint8_t)(c0 & 255);
        block[1] = (uint8_t)(c0 >> 8);
        block[2] = (uint8_t)(c1 & 255);
        block[3] = (uint8_t)(c1 >> 8);
        for (int b = 0; b < 4; ++b)
            block[4 + b] = (uint8_t)(bits >> (8 * b));
    }
    return total;
}

static void quantize_endpoints(const float a[3], const float b[3], endpoints *e)
{
    for (int c = 0; c < 3; ++c) {
        e->q[0][c] = nearest_code(fminf(255.0f, fmaxf(0.0f, a[c])), c);
        e->q[1][c] = nearest_code(fminf(255.0f, fmaxf(0.0f, b[c])), c);
    }
}

/* One-color block: per channel the endpoint pair whose 2/3-1/3 palette entry (as decoded) is
 * nearest the color; the index search in evaluate() then picks entry 2 or 3. */
static void fit_single_color(const float color[3], endpoints *e)
{
    for (int c = 0; c < 3; ++c) {
        float best = FLT_MAX;
        for (int q0 = 0; q0 <= channel_max[c]; ++q0)
            for (int q1 = 0; q1 <= channel_max[c]; ++q1) {
                int v = (2 * expand_code(q0, c) + expand_code(q1, c) + 1) / 3;
                float d = fabsf((float)v - color[c]);
                if (d < best) {
                    best = d;
                    e->q[0][c] = q0;
                    e->q[1][c] = q1;
                }
            }
    }
}

/* Mean and principal axis (power iteration on the covariance); returns 0 if all points coincide. */
static int principal_axis(const float pts[16][3], float mean[3], float axis[3], float cov[3][3])
{
    for (int c = 0; c < 3; ++c) {
        mean[c] = 0.0f;
        for (int i = 0; i < 16; ++i)
            mean[c] += pts[i][c];
        mean[c] /= 16.0f;
    }
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            cov[r][c] = 0.0f;
            for (int i = 0; i < 16; ++i)
                cov[r][c] += (pts[i][r] - mean[r]) * (pts[i][c] - mean[c]);
        }
    int main_c = 0;
    for (int c = 1; c < 3; ++c)
        if (cov[c][c] > cov[main_c][main_c])
            main_c = c;
    if (!(cov[main_c][main_c] > 0.0f))
        return 0;
    float v[3] = {cov[main_c][0], cov[main_c][1], cov[main_c][2]};
    for (int it = 0; it < 8; ++it) {
        float w[3];
        for (int r = 0; r < 3; ++r)
            w[r] = cov[r][0] * v[0] + cov[r][1] * v[1] + cov[r][2] * v[2];
        float m = fmaxf(fabsf(w[0]), fmaxf(fabsf(w[1]), fabsf(w[2])));
        if (!(m > 0.0f))
            break;
        for (int r = 0; r < 3; ++r)
            v[r] = w[r] / m;
    }
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; ++c)
        axis[c] = v[c] / len;
    return 1;
}

static void range_fit(const float pts[16][3], float cov[3][3], endpoints *e)
{
    float lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
        lo[c] = hi[c] = pts[0][c];
        for (int i = 1; i < 16; ++i) {
            lo[c] = fminf(lo[c], pts[i][c]);
            hi[c] = fmaxf(hi[c], pts[i][c]);
        }
    }
    int main_c = 0;
    for (int c = 1; c < 3; ++c)
        if (cov[c][c] > cov[main_c][main_c])
            main_c = c;
    for (int c = 0; c < 3; ++c) /* the diagonal of the box that follows the correlation */
        if (c != main_c && cov[main_c][c] < 0.0f) {
            float t = lo[c];
            lo[c] = hi[c];
            hi[c] = t;
        }
    quantize_endpoints(lo, hi, e);
}

static void pca_fit(const float pts[16][3], const float mean[3], const float axis[3], endpoints *e)
{
    float tmin = FLT_MAX, tmax = -FLT_MAX;
    for (int i = 0; i < 16; ++i) {
        float t = 0.0f;
        for (int c = 0; c < 3; ++c)
            t += (pts[i][c] - mean[c]) * axis[c];
        tmin = fminf(tmin, t);
        tmax = fmaxf(tmax, t);
    }
    float a[3], b[3];
    for (int c = 0; c < 3; ++c) {
        a[c] = mean[c] + tmin * axis[c];
        b[c] = mean[c] + tmax * axis[c];
    }
    quantize_endpoints(a, b, e);
}

/* Least-squares endpoints for given endpoint-0 weights; returns 0 if the system is singular. */
static int solve_endpoints(float aa, float bb, float ab, const float ax[3], const float bx[3], float a[3], float b[3])
{
    float det = aa * bb - ab * ab;
    if (!(fabsf(det) > 1e-6f))
        return 0;
    float inv = 1.0f / det;
    for (int c = 0; c < 3; ++c) {
        a[c] = (bb * ax[c] - ab * bx[c]) * inv;
        b[c] = (aa * bx[c] - ab * ax[c]) * inv;
    }
    return 1;
}

static float refine_least_squares(const float pts[16][3], endpoints *e, float err, int iterations)
{
    for (int it = 0; it < iterations; ++it) {
        uint8_t block[8];
        evaluate(e, pts, block);
        uint32_t bits = (uint32_t)block[4] | (uint32_t)block[5] << 8 | (uint32_t)block[6] << 16 | (uint32_t)block[7] << 24;
        float aa = 0, bb = 0, ab = 0, ax[3] = {0}, bx[3] = {0};
        for (int i = 0; i < 16; ++i) {
            float w = index_weight0[(bits >> (2 * i)) & 3], v = 1.0f - w;
            aa += w * w;
            bb += v * v;
            ab += w * v;
            for (int c = 0; c < 3; ++c) {
                ax[c] += w * pts[i][c];
                bx[c] += v * pts[i][c];
            }
        }
        /* evaluate() stored the endpoints ordered c0 > c1: solve for that order */
        float a[3], b[3];
        if (!solve_endpoints(aa, bb, ab, ax, bx, a, b))
            break;
        endpoints trial;
        quantize_endpoints(a, b, &trial);
        float trial_err = evaluate(&trial, pts, NULL);
        if (!(trial_err < err))
            break;
        *e = trial;
        err = trial_err;
    }
    return err;
}

/* Ordered cluster fit along `axis`; returns the snapped-grid error estimate's best endpoints. */
static void cluster_fit_once(const float pts[16][3], const float axis[3], endpoints *best_e)
{
    int order[16];
    float t[16];
    for (int i = 0; i < 16; ++i) {
        order[i] = i;
        t[i] = pts[i][0] * axis[0] + pts[i][1] * axis[1] + pts[i][2] * axis[2];
    }
    for (int i = 1; i < 16; ++i) /* insertion sort: stable, so ties keep texel order */
        for (int j = i; j > 0 && t[order[j - 1]] > t[order[j]]; --j) {
            int s = order[j];
            order[j] = order[j - 1];
            order[j - 1] = s;
        }
    float prefix[17][3];
    prefix[0][0] = prefix[0][1] = prefix[0][2] = 0.0f;
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
            prefix[i + 1][c] = prefix[i][c] + pts[order[i]][c];
    /* multiplications by constants, not divisions: this loop runs 969 times per block */
    const float third = 1.0f / 3.0f, two_thirds = 2.0f / 3.0f, ninth = 1.0f / 9.0f, four_ninths = 4.0f / 9.0f,
                two_ninths = 2.0f / 9.0f;
    float best = FLT_MAX;
    for (int i = 0; i <= 16; ++i)
        for (int j = i; j <= 16; ++j)
            for (int k = j; k <= 16; ++k) {
                /* clusters [0,i): endpoint a, [i,j): 2/3 a, [j,k): 1/3 a, [k,16): endpoint b */
                float n0 = (float)i, n1 = (float)(j - i), n2 = (float)(k - j), n3 = (float)(16 - k);
                float aa = n0 + n1 * four_ninths + n2 * ninth, bb = n3 + n1 * ninth + n2 * four_ninths;
                float ab = (n1 + n2) * two_ninths, ax[3], bx[3];
                for (int c = 0; c < 3; ++c) {
                    float x0 = prefix[i][c], x1 = prefix[j][c] - prefix[i][c];
                    float x2 = prefix[k][c] - prefix[j][c], x3 = prefix[16][c] - prefix[k][c];
                    ax[c] = x0 + x1 * two_thirds + x2 * third;
                    bx[c] = x3 + x1 * third + x2 * two_thirds;
                }
                float a[3], b[3];
                if (!solve_endpoints(aa, bb, ab, ax, bx, a, b))
                    continue;
                endpoints e;
                for (int c = 0; c < 3; ++c) { /* plain rounding to the grid: cheap, the loop runs 969 times */
                    float to_code = (float)channel_max[c] / 255.0f;
                    e.q[0][c] = (int)(clamp255(a[c]) * to_code + 0.5f);
                    e.q[1][c] = (int)(clamp255(b[c]) * to_code + 0.5f);
                }
                float err = 0.0f; /* sum |alpha a + beta b - x|^2 without the constant sum |x|^2 */
                for (int c = 0; c < 3; ++c) {
                    float qa = (float)expand_code(e.q[0][c], c), qb = (float)expand_code(e.q[1][c], c);
                    err += aa * qa * qa + bb * qb * qb + 2.0f * ab * qa * qb - 2.0f * (qa * ax[c] + qb * bx[c]);
                }
                if (err < best) {
                    best = err;
                    *best_e = e;
                }
            }
}

static float cluster_fit(const float pts[16][3], const float axis0[3], endpoints *e, float err, int iterations)
{
    float axis[3] = {axis0[0], axis0[1], axis0[2]};
    for (int it = 0; it < iterations; ++it) {
        endpoints trial;
        memcpy(&trial, e, sizeof trial);
        cluster_fit_once(pts, axis, &trial);
        float trial_err = evaluate(&trial, pts, NULL);
        if (!(trial_err < err))
            break;
        *e = trial;
        err = trial_err;
        float len = 0.0f; /* re-order along the direction of the new endpoints */
        for (int c = 0; c < 3; ++c) {
            axis[c] = (float)(expand_code(e->q[1][c], c) - expand_code(e->q[0][c], c));
            len += axis[c] * axis[c];
        }
        if (!(len > 0.0f))
            break;
    }
    return err;
}

static float hill_climb(const float pts[16][3], endpoints *e, float err)
{
    for (int pass = 0; pass < 32; ++pass) {
        int improved = 0;
        for (int p = 0; p < 2; ++p)
            for (int c = 0; c < 3; ++c)
                for (int step = -1; step <= 1; step += 2) {
                    endpoints trial = *e;
                    trial.q[p][c] += step;
                    if (trial.q[p][c] < 0 || trial.q[p][c] > channel_max[c])
                        continue;
                    float trial_err = evaluate(&trial, pts, NULL);
                    if (trial_err < err) {
                        *e = trial;
                        err = trial_err;
                        improved = 1;
                    }
                }
        if (!improved)
            break;
    }
    return err;
}

static sol_status check_options(const sol_bc1_options *options, sol_bc1_effort *effort, int *iterations)
{
    *effort = options ? options->effort : SOL_BC1_EFFORT_DEFAULT;
    *iterations = options ? options->iterations : 0;
    if ((unsigned)*effort >= SOL_BC1_EFFORT_COUNT || *iterations < 0 || *iterations > 64)
        return SOL_ERR_INVALID_ARG;
    if (*effort == SOL_BC1_EFFORT_DEFAULT)
        *effort = SOL_BC1_CLUSTER;
    if (*iterations == 0)
        *iterations = 4;
    return SOL_OK;
}

static sol_status check_value(float v)
{
    if (!isfinite(v))
        return SOL_ERR_NONFINITE;
    return v < 0.0f || v > 1.0f ? SOL_ERR_OUT_OF_RANGE : SOL_OK;
}

static void encode_block_checked(const float rgb[16][3], sol_bc1_effort effort, int iterations, uint8_t block[8])
{
    float pts[16][3], mean[3], axis[3], cov[3][3];
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
            pts[i][c] = rgb[i][c] * 255.0f;
    endpoints e;
    int one_color = 1;
    for (int i = 1; i < 16; ++i)
        one_color &= pts[i][0] == pts[0][0] && pts[i][1] == pts[0][1] && pts[i][2] == pts[0][2];
    if (one_color || !principal_axis(pts, mean, axis, cov)) {
        fit_single_color(pts[0], &e);
        evaluate(&e, pts, block);
        return;
    }
    if (effort == SOL_BC1_RANGE)
        range_fit(pts, cov, &e);
    else
        pca_fit(pts, mean, axis, &e);
    float err = evaluate(&e, pts, NULL);
    if (effort == SOL_BC1_PCA_REFINE)
        err = refine_least_squares(pts, &e, err, iterations);
    if (effort == SOL_BC1_CLUSTER || effort == SOL_BC1_CLUSTER_SEARCH)
        err = cluster_fit(pts, axis, &e, err, iterations);
    if (effort == SOL_BC1_CLUSTER_SEARCH)
        hill_climb(pts, &e, err);
    evaluate(&e, pts, block);
}

sol_status sol_bc1_encode_block(const float rgb[16][3], const sol_bc1_options *options, uint8_t block[8])
{
    if (!rgb || !block)
        return SOL_ERR_NULL_ARG;
    sol_bc1_effort effort;
    int iterations;
    sol_status st = check_options(options, &effort, &iterations);
    if (st)
        return st;
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
            if ((st = check_value(rgb[i][c])))
                return st;
    encode_block_checked(rgb, effort, iterations, block);
    return SOL_OK;
}

size_t sol_bc1_size(int width, int height)
{
    size_t blocks, bytes;
    if (width <= 0 || height <= 0)
        return 0;
    /* ((size_t)w + 3) / 4: w + 3 in int overflows at INT_MAX */
    if (!sol_size_mul(&blocks, ((size_t)width + 3) / 4, ((size_t)height + 3) / 4) ||
        !sol_size_mul(&bytes, blocks, SOL_BC1_BLOCK_BYTES))
        return 0;
    return bytes;
}

sol_status sol_bc1_encode(const sol_image *image, const sol_bc1_options *options, uint8_t *blocks)
{
    if (!image || !image->data || !blocks)
        return SOL_ERR_NULL_ARG;
    if (image->width <= 0 || image->height <= 0 || image->channels < 3)
        return SOL_ERR_INVALID_ARG;
    sol_bc1_effort effort;
    int iterations;
    sol_status st = check_options(options, &effort, &iterations);
    if (st)
        return st;
    for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x)
            for (int c = 0; c < 3; ++c)
                if ((st = check_value(sol_image_pixel(image, x, y)[c])))
                    return st;
    if (!sol_bc1_size(image->width, image->height))
        return SOL_ERR_INVALID_ARG;
    int bw = (int)(((unsigned)image->width + 3u) / 4u), bh = (int)(((unsigned)image->height + 3u) / 4u);
#pragma omp parallel for schedule(dynamic, 4)
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            float rgb[16][3];
            for (int i = 0; i < 16; ++i) {
                int x = bx * 4 + (i & 3), y = by * 4 + (i >> 2);
                const float *p = sol_image_pixel(image, x < image->width ? x : image->width - 1,
                                                 y < image->height ? y : image->height - 1);
                rgb[i][0] = p[0];
                rgb[i][1] = p[1];
                rgb[i][2] = p[2];
            }
            encode_block_checked(rgb, effort, iterations, blocks + ((size_t)by * (size_t)bw + (size_t)bx) * 8);
        }
    return SOL_OK;
}

sol_status sol_bc1_decode(const uint8_t *blocks, int width, int height, sol_image *out)
{
    if (!blocks || !out)
        return SOL_ERR_NULL_ARG;
    sol_image image = {0};
    sol_status st = sol_image_alloc(&image, width, height, 3);
    if (st)
        return st;
    int bw = (int)(((unsigned)width + 3u) / 4u), bh = (int)(((unsigned)height + 3u) / 4u);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            uint8_t rgba[16][4];
            sol_bc1_decode_block(blocks + ((size_t)by * (size_t)bw + (size_t)bx) * 8, rgba);
            for (int i = 0; i < 16; ++i) {
                int x = bx * 4 + (i & 3), y = by * 4 + (i >> 2);
                if (x < width && y < height)
                    for (int c = 0; c < 3; ++c)
                        sol_image_pixel(&image, x, y)[c] = (float)rgba[i][c] / 255.0f;
            }
        }
    *out = image;
    return SOL_OK;
}
