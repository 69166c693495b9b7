/* inputs.c - the test textures of the color-texture driver: synthetic 16-bit ones (ramps, smooth
 * noise with varied histograms) and game textures of Debian's colobot-common-textures package
 * (8-bit sRGB PNGs; absent files are skipped with a note on stderr). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "textures_exp.h"

static const char *game_dir = "/usr/share/games/colobot/textures";
static const char *game_files[] = {"desert4.png", "desert5.png", "dirty01.png", "dirty02.png", "dirty03.png",
                                   "dirty04.png", "green01.png", "lava04.png",  "mars001.png", "mars003.png",
                                   "mars005.png", "mix01.png",   "moon103.png", "chili01.png"};
enum { GAME_FILES = sizeof game_files / sizeof game_files[0] };

double display255(double linear, double light)
{
    double v = linear * light;
    return 255.0 * sol_srgb_encode(v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v));
}

static double hash01(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (h & 0xffffff) / 16777215.0;
}

/* Smooth value noise in [0,1]: two octaves of bilinearly interpolated lattice values. */
static double value_noise(double x, double y, uint32_t seed)
{
    double total = 0.0, amp = 0.65, cell = 24.0;
    for (int o = 0; o < 2; ++o, amp = 0.35, cell /= 4.0) {
        double fx = x / cell, fy = y / cell;
        int ix = (int)floor(fx), iy = (int)floor(fy);
        double tx = fx - ix, ty = fy - iy;
        tx = tx * tx * (3 - 2 * tx);
        ty = ty * ty * (3 - 2 * ty);
        double a = hash01(ix, iy, seed + o), b = hash01(ix + 1, iy, seed + o);
        double c = hash01(ix, iy + 1, seed + o), d = hash01(ix + 1, iy + 1, seed + o);
        total += amp * ((a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty);
    }
    return total;
}

static double to16(double v) { return sol_unorm_decode(sol_unorm_encode(v, 16), 16); }

static tex_input *grow(tex_input **set, int *count)
{
    *set = realloc(*set, sizeof **set * (size_t)(*count + 1));
    if (!*set)
        exp_die("out of memory");
    tex_input *t = &(*set)[(*count)++];
    memset(t, 0, sizeof *t);
    return t;
}

/* Linear value lo + (hi - lo) u^skew per texel, u a ramp or noise coordinate; channels tinted. */
static void synth(tex_input *t, int size, int noise, double lo, double hi, double skew, uint32_t seed)
{
    static const double tint[3] = {1.0, 0.93, 0.85};
    exp_check(sol_image_alloc(&t->linear, size, size, 3), "allocating a texture");
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double u = noise ? value_noise(x, y, seed) : (x + 0.5) / size;
            double v = lo + (hi - lo) * pow(fmin(1.0, fmax(0.0, u)), skew);
            for (int c = 0; c < 3; ++c)
                sol_image_pixel(&t->linear, x, y)[c] = (float)to16(v * tint[c]);
        }
    t->source_bits = 16;
    snprintf(t->kind, sizeof t->kind, "%s", noise ? "noise" : "ramp");
    snprintf(t->name, sizeof t->name, "%s [%.2f,%.2f]^%.1f", t->kind, lo, hi, skew);
}

/* A game texture: 8-bit sRGB decoded to linear and box-downsampled 2x2 in linear light (so its
 * values fall between the 8-bit codes, like a higher-precision source), then scaled by `scale`.
 * Returns 0 if the file is absent or unreadable. */
static int load_game(tex_input *t, const char *file, int size, double scale)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", game_dir, file);
    sol_image src = {0};
    int bits;
    if (access(path, R_OK) != 0 || sol_png_read(path, &src, &bits) != SOL_OK || src.channels < 3 ||
        src.width < 32 || src.height < 32) {
        sol_image_free(&src);
        return 0;
    }
    size = size < src.width / 2 ? size : src.width / 2; /* top-left crop, at most the whole file */
    size = size < src.height / 2 ? size : src.height / 2;
    exp_check(sol_image_alloc(&t->linear, size, size, 3), "allocating a texture");
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int k = 0; k < 4; ++k)
                    sum += sol_srgb_decode(sol_image_pixel(&src, 2 * x + (k & 1), 2 * y + (k >> 1))[c]);
                sol_image_pixel(&t->linear, x, y)[c] = (float)(sum / 4.0 * scale);
            }
    sol_image_free(&src);
    t->source_bits = bits;
    snprintf(t->kind, sizeof t->kind, "game texture");
    snprintf(t->name, sizeof t->name, "%s", file);
    return 1;
}

static int add_game_textures(tex_input **set, int *count, int size, int darken, int limit)
{
    int found = 0;
    for (int i = 0; i < GAME_FILES && found < limit; ++i) {
        tex_input *t = grow(set, count);
        double scale = 1.0;
        if (darken) { /* mean linear albedo brought to 0.02: a dark material */
            if (!load_game(t, game_files[i], size, 1.0)) {
                --*count;
                continue;
            }
            double mean = 0.0;
            size_t n = (size_t)t->linear.width * (size_t)t->linear.height * 3;
            for (size_t k = 0; k < n; ++k)
                mean += t->linear.data[k];
            mean /= (double)n;
            scale = fmin(1.0, 0.02 / mean);
            for (size_t k = 0; k < n; ++k)
                t->linear.data[k] = (float)(t->linear.data[k] * scale);
            snprintf(t->name, sizeof t->name, "%s x%.2f", game_files[i], scale);
            ++found;
            continue;
        }
        if (load_game(t, game_files[i], size, scale))
            ++found;
        else
            --*count;
    }
    if (!found)
        fprintf(stderr, "note: no game textures under %s (Debian package colobot-common-textures); "
                        "running on synthetic textures only\n", game_dir);
    return found;
}

int inputs_storage_set(tex_input **out, int quick)
{
    tex_input *set = NULL;
    int count = 0, size = quick ? 32 : 64;
    const double los[] = {0.0, 0.02, 0.1, 0.2, 0.4}, spans[] = {0.1, 0.4, 1.0}, skews[] = {0.5, 1.0, 2.0};
    uint32_t seed = 1;
    for (int noise = 0; noise < 2; ++noise)
        for (int a = 0; a < 5; ++a)
            for (int s = 0; s < 3; ++s)
                for (int k = 0; k < 3; ++k) {
                    double hi = fmin(1.0, los[a] + spans[s]);
                    if (quick && (a + s + k) % 3)
                        continue;
                    synth(grow(&set, &count), size, noise, los[a], hi, skews[k], seed++);
                }
    add_game_textures(&set, &count, quick ? 32 : 128, 0, quick ? 3 : GAME_FILES);
    *out = set;
    return count;
}

int inputs_dark_set(tex_input **out, int quick)
{
    tex_input *set = NULL;
    int count = 0, size = quick ? 64 : 256;
    synth(grow(&set, &count), size, 1, 0.002, 0.03, 1.0, 101);
    snprintf(set[count - 1].name, sizeof set[count - 1].name, "dark noise [0.002,0.03]");
    synth(grow(&set, &count), size, 1, 0.0, 0.012, 2.0, 202);
    snprintf(set[count - 1].name, sizeof set[count - 1].name, "very dark noise [0,0.012]^2");
    synth(grow(&set, &count), size, 0, 0.005, 0.04, 1.0, 303);
    snprintf(set[count - 1].name, sizeof set[count - 1].name, "dark ramp [0.005,0.04]");
    add_game_textures(&set, &count, size, 1, quick ? 2 : 6);
    *out = set;
    return count;
}

void inputs_free(tex_input *set, int count)
{
    for (int i = 0; i < count; ++i)
        sol_image_free(&set[i].linear);
    free(set);
}
