/* fuzz_exr.c - libFuzzer target for sol_exr_read_ex (make fuzz), with limits lowered to 64 MiB
 * (see fuzz_png.c). Each successful read must give a consistent image. */
#define _GNU_SOURCE
#include "fuzz_input.h"
#include "sol_core.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_input_path(data, size);
    if (!path)
        return 0;
    const sol_read_limits limits = {.max_pixels = 1u << 22, .max_bytes = 64u << 20};
    sol_image image = {0};
    if (sol_exr_read_ex(path, &limits, &image) == SOL_OK) {
        if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > 4 || !image.data)
            abort();
        volatile float sum = 0.0f; /* every value is read: an uninitialised or short buffer shows */
        size_t count = (size_t)image.width * (size_t)image.height * (size_t)image.channels;
        for (size_t i = 0; i < count; ++i)
            sum += image.data[i];
        (void)sum;
        sol_image_free(&image);
    }
    return 0;
}
