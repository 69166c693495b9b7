/* inputs.h - synthetic 16-bit normal maps from height fields (T8-T14 inputs). */
#ifndef T8_T14_INPUTS_H
#define T8_T14_INPUTS_H

#include "sol_core.h"

typedef enum input_kind { INPUT_BUMPS, INPUT_RIDGES, INPUT_NOISE, INPUT_HOOD, INPUT_COUNT } input_kind;

const char *input_name(input_kind kind);
/* The exact (double) unit normals of the height field, as a 3-channel image of x, y, z. */
void input_normals(input_kind kind, int size, sol_image *out);
/* Stores every component as a `bits`-bit UNORM of (n + 1) / 2 and decodes it back (the
 * normal map file of that depth), renormalised. */
void input_quantize(const sol_image *exact, int bits, sol_image *out);

/* The real terrain-derived map of make bench (a game terrain texture's luminance as height, see
 * inputs.c); returns 0 if the texture is not installed. */
int input_terrain_normals(int size, sol_image *out);

#endif
