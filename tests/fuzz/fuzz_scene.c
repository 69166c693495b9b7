/* fuzz_scene.c - libFuzzer target for the scene file reader (sol_scene_parse). Every input must
 * either load (and then free cleanly) or fail with a named field, without leaks or crashes. */
#include <stdint.h>
#include <stddef.h>

#include "sol_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sol_scene scene;
    sol_scene_error err;
    if (sol_scene_parse((const char *)data, size, "fuzz.json", &scene, &err) == SOL_OK)
        sol_scene_free(&scene);
    return 0;
}
