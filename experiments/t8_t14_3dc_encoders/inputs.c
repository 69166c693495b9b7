/* inputs.c - synthetic normal maps: bumps, ridges, fractal noise and a smooth car-hood-like panel
 * (the talk's banding example, T14). Normals come from analytic height-field gradients:
 * n = normalize(-dh/du, -dh/dv, 1) with u, v the texel coordinates scaled to [0, 1). */
#include "inputs.h"

#include "exp_harness.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

const char *input_name(input_kind kind)
{
    static const char *names[INPUT_COUNT] = {"bumps", "ridges", "noise", "hood"};
    return names[kind];
}

/* Deterministic hash to [0, 1): a lattice value for noise and bump placement. */
static double hash01(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    h ^= h >> 16;
    return (double)h / 4294967296.0;
}

/* Smooth value noise with its gradient (quintic fade), periodic with `period` cells. */
static void value_noise(double u, double v, int period, uint32_t seed, double *gu, double *gv)
{
    double x = u * period, y = v * period;
    int ix = (int)floor(x), iy = (int)floor(y);
    double fx = x - ix, fy = y - iy;
    double sx = fx * fx * fx * (fx * (fx * 6 - 15) + 10), sy = fy * fy * fy * (fy * (fy * 6 - 15) + 10);
    double dsx = 30 * fx * fx * (fx - 1) * (fx - 1), dsy = 30 * fy * fy * (fy - 1) * (fy - 1);
    uint32_t x0 = (uint32_t)(ix % period), y0 = (uint32_t)(iy % period);
    uint32_t x1 = (x0 + 1) % (uint32_t)period, y1 = (y0 + 1) % (uint32_t)period;
    double a = hash01(x0, y0, seed), b = hash01(x1, y0, seed), c = hash01(x0, y1, seed), d = hash01(x1, y1, seed);
    *gu = period * dsx * ((b - a) + sy * (a - b - c + d));
    *gv = period * dsy * ((c - a) + sx * (a - b - c + d));
}

static void height_gradient(input_kind kind, double u, double v, double *gu, double *gv)
{
    *gu = *gv = 0.0;
    switch (kind) {
    case INPUT_BUMPS: /* 40 Gaussian bumps and dents of random radius */
        for (uint32_t i = 0; i < 40; ++i) {
            double cu = hash01(i, 1, 7), cv = hash01(i, 2, 7), r = 0.03 + 0.07 * hash01(i, 3, 7);
            double amp = (hash01(i, 4, 7) < 0.5 ? -1.0 : 1.0) * 0.6 * r;
            double du = u - cu, dv = v - cv;
            du -= round(du);
            dv -= round(dv);
            double g = amp * exp(-(du * du + dv * dv) / (2 * r * r)) / (r * r);
            *gu += -du * g;
            *gv += -dv * g;
        }
        break;
    case INPUT_RIDGES: { /* sharp-crested ridges: h = A |sin(k . x)| along two directions */
        const double k1[2] = {2 * M_PI * 9, 2 * M_PI * 3}, k2[2] = {-2 * M_PI * 4, 2 * M_PI * 11};
        double s1 = sin(k1[0] * u + k1[1] * v), s2 = sin(k2[0] * u + k2[1] * v);
        double d1 = 0.01 * (s1 >= 0 ? 1 : -1) * cos(k1[0] * u + k1[1] * v);
        double d2 = 0.006 * (s2 >= 0 ? 1 : -1) * cos(k2[0] * u + k2[1] * v);
        *gu = d1 * k1[0] + d2 * k2[0];
        *gv = d1 * k1[1] + d2 * k2[1];
        break;
    }
    case INPUT_NOISE: /* 5 octaves of value noise */
        for (int o = 0; o < 5; ++o) {
            double a, b, amp = 0.12 / (1 << o) / (1 << o);
            value_noise(u, v, 4 << o, (uint32_t)o + 11, &a, &b);
            *gu += amp * a / (4 << o) * 8;
            *gv += amp * b / (4 << o) * 8;
        }
        break;
    default: /* hood: a gently curved panel (the bonnet of a car) with one soft crease */
        *gu = 0.55 * (u - 0.5) + 0.08 * tanh((u - 0.62) * 12.0);
        *gv = 0.35 * (v - 0.35) + 0.05 * sin(2.0 * M_PI * u);
        break;
    }
}

void input_normals(input_kind kind, int size, sol_image *out)
{
    exp_check(sol_image_alloc(out, size, size, 3), "allocating a %dx%d normal map", size, size);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double gu, gv;
            height_gradient(kind, (x + 0.5) / size, (y + 0.5) / size, &gu, &gv);
            double len = sqrt(gu * gu + gv * gv + 1.0);
            float *p = sol_image_pixel(out, x, y);
            p[0] = (float)(-gu / len);
            p[1] = (float)(-gv / len);
            p[2] = (float)(1.0 / len);
        }
}

void input_quantize(const sol_image *exact, int bits, sol_image *out)
{
    exp_check(sol_image_alloc(out, exact->width, exact->height, 3), "allocating a normal map");
    size_t n = (size_t)exact->width * (size_t)exact->height;
    for (size_t i = 0; i < n; ++i) {
        double v[3], len = 0.0;
        for (int c = 0; c < 3; ++c) {
            v[c] = 2.0 * sol_unorm_decode(sol_unorm_encode(0.5 * (exact->data[3 * i + c] + 1.0), bits), bits) - 1.0;
            len += v[c] * v[c];
        }
        len = sqrt(len);
        for (int c = 0; c < 3; ++c)
            out->data[3 * i + c] = (float)(v[c] / len);
    }
}

/* A real terrain-derived map: the luminance of a game terrain texture (Debian's
 * colobot-common-textures, desert4.png, 512x512) as a periodic height field, bilinearly resampled to
 * `size` and differentiated by central differences: n = normalize(-dh/du, -dh/dv, 1), h = 0.01 lum. */
int input_terrain_normals(int size, sol_image *out)
{
    static const char *path = "/usr/share/games/colobot/textures/desert4.png";
    sol_image tex;
    int bits;
    if (sol_png_read(path, &tex, &bits) != SOL_OK)
        return 0;
    int w = tex.width, h = tex.height;
    double *lum = malloc(sizeof *lum * (size_t)w * (size_t)h);
    if (!lum)
        exp_die("out of memory");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float *p = sol_image_pixel(&tex, x, y);
            lum[(size_t)y * w + x] = tex.channels >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
        }
    sol_image_free(&tex);
    exp_check(sol_image_alloc(out, size, size, 3), "allocating a %dx%d normal map", size, size);
    const double amp = 0.01, step = 1.0 / size;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double hv[4];
            const int off[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (int k = 0; k < 4; ++k) { /* bilinear, wrapping */
                double u = (x + 0.5 + off[k][0]) * w / size - 0.5, v = (y + 0.5 + off[k][1]) * h / size - 0.5;
                int x0 = (int)floor(u), y0 = (int)floor(v);
                double fx = u - x0, fy = v - y0;
                int xa = ((x0 % w) + w) % w, xb = (xa + 1) % w, ya = ((y0 % h) + h) % h, yb = (ya + 1) % h;
                hv[k] = amp * ((1 - fy) * ((1 - fx) * lum[(size_t)ya * w + xa] + fx * lum[(size_t)ya * w + xb]) +
                               fy * ((1 - fx) * lum[(size_t)yb * w + xa] + fx * lum[(size_t)yb * w + xb]));
            }
            double gu = (hv[0] - hv[1]) / (2 * step), gv = (hv[2] - hv[3]) / (2 * step);
            double len = sqrt(gu * gu + gv * gv + 1.0);
            float *p = sol_image_pixel(out, x, y);
            p[0] = (float)(-gu / len);
            p[1] = (float)(-gv / len);
            p[2] = (float)(1.0 / len);
        }
    free(lum);
    return 1;
}
