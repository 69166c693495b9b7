/* fuzz_exr.c - libFuzzer target for sol_exr_read_ex (make fuzz), with the lowered limits of
 * fuzz_input.h. Each successful read must give a consistent image. */
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
    if (sol_exr_read_ex(path, &FUZZ_IMAGE_LIMITS, &image) == SOL_OK) {
        fuzz_check_image(&image);
        sol_image_free(&image);
    }
    return 0;
}
