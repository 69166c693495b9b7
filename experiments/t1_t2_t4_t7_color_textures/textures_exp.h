/* textures_exp.h - what the parts of the t1_t2_t4_t7_color_textures driver share. */
#ifndef TEXTURES_EXP_H
#define TEXTURES_EXP_H

#ifdef __cplusplus
extern "C" {
#endif

/* libsquish BC1 (squish_adapter.cpp): effort 0 range fit, 1 cluster fit, 2 iterative cluster fit.
 * rgba: 8-bit RGBA, width * height texels; blocks: row-major BC1 blocks. */
void squish_bc1_encode(const unsigned char *rgba, int width, int height, void *blocks, int effort);

#ifdef __cplusplus
}

#else
#include "exp_harness.h"
#include "sol_textures.h"

/* One test texture: RGB values in linear light, [0,1]. */
typedef struct tex_input {
    char name[64];
    char kind[32];   /* "ramp", "noise", "game texture" ... */
    int source_bits; /* precision of the source: 16 (synthetic) or 8 (a PNG from a package) */
    sol_image linear;
} tex_input;

/* The texture set of the storage rule (T4): synthetic ramps and noise with varied histograms, and
 * the game textures found on this machine (skipped with a note when absent). Returns the count. */
int inputs_storage_set(tex_input **out, int quick);
/* Dark textures for renormalisation (T1, T2): synthetic 16-bit ones and darkened game textures. */
int inputs_dark_set(tex_input **out, int quick);
void inputs_free(tex_input *set, int count);

/* Display value (0..255) of a linear value lit by `light` and clamped: sRGB(min(1, light x)) * 255. */
double display255(double linear, double light);

void run_storage_rule(const exp_run *exp);   /* T4 */
void run_bright_gradient(const exp_run *exp); /* T7 */
void run_renormalization(const exp_run *exp); /* T1, T2, the libsquish comparison, effort levels */
#endif

#endif
