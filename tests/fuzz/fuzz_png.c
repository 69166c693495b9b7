/* fuzz_png.c - libFuzzer target for sol_png_read_ex (make fuzz), with the lowered limits of
 * fuzz_input.h. Each successful read must give a consistent image of values in [0, 1] and a bit
 * depth of 8 or 16. */
#define _GNU_SOURCE
#include "fuzz_input.h"
#include "sol_core.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_input_path(data, size);
    if (!path)
        return 0;
    sol_image image = {0};
    int bits = 0;
    if (sol_png_read_ex(path, &FUZZ_IMAGE_LIMITS, &image, &bits) == SOL_OK) {
        size_t count = fuzz_check_image(&image);
        if (bits != 8 && bits != 16)
            abort();
        for (size_t i = 0; i < count; ++i)
            if (!(image.data[i] >= 0.0f && image.data[i] <= 1.0f))
                abort();
        sol_image_free(&image);
    }
    return 0;
}
