/* fuzz_png.c - libFuzzer target for sol_png_read_ex (make fuzz). The limits are lowered to 64 MiB
 * so that the fuzzer explores formats, not the machine's memory; the default-limit path is the
 * same code with larger numbers. Each successful read must give a consistent image. */
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
    int bits = 0;
    if (sol_png_read_ex(path, &limits, &image, &bits) == SOL_OK) {
        if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > 4 || !image.data ||
            (bits != 8 && bits != 16))
            abort();
        size_t count = (size_t)image.width * (size_t)image.height * (size_t)image.channels;
        for (size_t i = 0; i < count; ++i)
            if (!(image.data[i] >= 0.0f && image.data[i] <= 1.0f))
                abort();
        sol_image_free(&image);
    }
    return 0;
}
