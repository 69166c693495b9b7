/* scenes.h - shared by the scenes driver's files. */
#ifndef SCENES_H
#define SCENES_H

#include "exp_harness.h"

#define SCENES_DIR "experiments/scenes"

/* The claims rows measured on the shipped scenes (claims.c), rendered at width x height
 * (0 x 0 = each scene's camera size). */
void scenes_claims(const exp_run *exp, int width, int height);

#endif
