/* scenes.h - shared by the scenes driver's files. */
#ifndef SCENES_H
#define SCENES_H

#include "exp_harness.h"
#include "sol_scene.h"

#define SCENES_DIR "experiments/scenes"

/* The claims rows measured on the shipped scenes (claims.c), rendered at width x height
 * (0 x 0 = each scene's camera size). */
void scenes_claims(const exp_run *exp, int width, int height);

/* Registers the renders of unmodified shipped scenes that scenes_claims takes from the cache
 * (claims.c), so main.c keeps them instead of rendering them twice. */
void scenes_claims_want(void);

/* The render cache (cache.c), keyed by scene name, reference path and reference_effects; the run's
 * size is fixed. want: claims.c will take that render. put: keeps *r (and *st) if wanted and not
 * yet kept, then zeroes *r (ownership moves to the cache); returns 1 if kept, 0 otherwise (*r
 * untouched). take: moves a kept render into *r (and *st) and returns 1, or returns 0. clear:
 * frees what was kept and never taken, and forgets the keys. */
void scenes_cache_want(const char *scene, int reference, unsigned reference_effects);
int scenes_cache_put(const char *scene, int reference, unsigned reference_effects, sol_render_result *r,
                     const sol_render_stats *st);
int scenes_cache_take(const char *scene, int reference, unsigned reference_effects, sol_render_result *r,
                      sol_render_stats *st);
void scenes_cache_clear(void);

#endif
