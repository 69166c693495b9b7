/* fuzz_cube.c - libFuzzer target for sol_cube_parse (the .cube 3D LUT reader, src/hdr/cube_io.c). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sol_hdr.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sol_read_limits limits = {.max_pixels = 1u << 18, .max_bytes = 1u << 24};
    sol_lut3d lut;
    sol_cube_info info;
    size_t line;
    const char *problem;
    if (sol_cube_parse((const char *)data, size, &limits, &lut, &info, &line, &problem) == SOL_OK) {
        volatile float sum = 0;
        size_t n = (size_t)lut.size * (size_t)lut.size * (size_t)lut.size * 3;
        for (size_t i = 0; i < n; ++i)
            sum += lut.data[i];
        (void)sum; /* clang: set but not used; volatile keeps the reads */
        (void)strlen(info.title);
        sol_lut3d_free(&lut);
    }
    return 0;
}
