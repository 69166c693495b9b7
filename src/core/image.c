/* image.c - allocation of sol_image. */
#include "sol_core.h"

#include <stdint.h>
#include <stdlib.h>

sol_status sol_image_alloc(sol_image *out, int width, int height, int channels)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4)
        return SOL_ERR_INVALID_ARG;
    size_t count = (size_t)width * (size_t)height * (size_t)channels;
    if (count > SIZE_MAX / sizeof(float)) /* width, height < 2^31, so count itself cannot wrap */
        return SOL_ERR_INVALID_ARG;
    float *data = calloc(count, sizeof *data);
    if (!data)
        return SOL_ERR_NO_MEMORY;
    out->width = width;
    out->height = height;
    out->channels = channels;
    out->data = data;
    return SOL_OK;
}

void sol_image_free(sol_image *image)
{
    if (!image)
        return;
    free(image->data);
    image->data = NULL;
    image->width = image->height = image->channels = 0;
}
