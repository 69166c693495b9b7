/* fuzz_gltf_anisotropy.c - libFuzzer target for the KHR_materials_anisotropy reader
 * (sol_mesh_read_anisotropy_json, scene_mesh.c), the one part of glTF import sol parses itself
 * (assimp reads the rest). Any bytes must give SOL_OK or a documented error with a message, and
 * every material it sets must hold finite values in range. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sol_mesh_material mats[4];
    memset(mats, 0, sizeof mats);
    sol_mesh m;
    memset(&m, 0, sizeof m);
    m.mat_count = 4;
    m.mats = mats;
    char msg[256] = "";
    sol_status st = sol_mesh_read_anisotropy_json((const char *)data, size, &m, msg, sizeof msg);
    if (st != SOL_OK && st != SOL_ERR_FORMAT && st != SOL_ERR_NONFINITE && st != SOL_ERR_OUT_OF_RANGE)
        abort();
    if (st != SOL_OK && !msg[0])
        abort();
    for (int i = 0; i < 4; ++i)
        if (mats[i].aniso && (!(mats[i].aniso_strength >= 0.0 && mats[i].aniso_strength <= 1.0) ||
                              !isfinite(mats[i].aniso_rotation) || !(mats[i].alpha >= 0.0 && mats[i].alpha <= 1.0)))
            abort();
    return 0;
}
