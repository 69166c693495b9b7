/* cache.c - renders main.c makes and claims.c needs again (the same shipped scene, unmodified, the
 * same size, path and reference_effects): main.c keeps the ones on claims.c's list
 * (scenes_cache_wanted) instead of freeing them, claims.c takes them (scenes_cache_take) instead
 * of rendering them a second time. A render depends only on the scene file, its plan and the
 * options, so a kept render is the one claims.c would make; a key not kept is rendered as before. */
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

typedef struct {
    char scene[64];
    int reference;
    unsigned reference_effects;
    int full;
    sol_render_result result;
    sol_render_stats stats;
} entry;

enum { MAX_ENTRIES = 32 };
static entry cache[MAX_ENTRIES];
static int cache_count;

static entry *find(const char *scene, int reference, unsigned reference_effects)
{
    for (int i = 0; i < cache_count; ++i)
        if (!strcmp(cache[i].scene, scene) && cache[i].reference == reference &&
            cache[i].reference_effects == reference_effects)
            return &cache[i];
    return NULL;
}

void scenes_cache_want(const char *scene, int reference, unsigned reference_effects)
{
    if (find(scene, reference, reference_effects) || cache_count == MAX_ENTRIES || strlen(scene) >= sizeof cache[0].scene)
        return;
    entry *e = &cache[cache_count++];
    memset(e, 0, sizeof *e);
    strcpy(e->scene, scene);
    e->reference = reference;
    e->reference_effects = reference_effects;
}

int scenes_cache_put(const char *scene, int reference, unsigned reference_effects, sol_render_result *r,
                     const sol_render_stats *st)
{
    entry *e = find(scene, reference, reference_effects);
    if (!e || e->full)
        return 0;
    e->result = *r;
    if (st)
        e->stats = *st;
    e->full = 1;
    memset(r, 0, sizeof *r);
    return 1;
}

int scenes_cache_take(const char *scene, int reference, unsigned reference_effects, sol_render_result *r,
                      sol_render_stats *st)
{
    entry *e = find(scene, reference, reference_effects);
    if (!e || !e->full)
        return 0;
    *r = e->result;
    if (st)
        *st = e->stats;
    e->full = 0;
    memset(&e->result, 0, sizeof e->result);
    return 1;
}

void scenes_cache_clear(void)
{
    for (int i = 0; i < cache_count; ++i)
        if (cache[i].full)
            sol_render_result_free(&cache[i].result);
    cache_count = 0;
}
