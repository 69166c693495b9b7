/* png_io.c - 8- and 16-bit PNG files through libpng's classic API.
 * Values are stored as codes without any gamma conversion: sol decides what a code means. */
#include "sol_core.h"

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>

/* libpng's default handlers print; the library must not, so errors only longjmp. */
static void silent_error(png_structp png, png_const_charp message)
{
    (void)message;
    png_longjmp(png, 1);
}

static void silent_warning(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message;
}

static sol_status read_rows(png_structp png, png_infop info, FILE *file, sol_image *out, int *bits_out)
{
    png_init_io(png, file);
    png_read_info(png, info);
    int color = png_get_color_type(png, info);
    int depth = png_get_bit_depth(png, info);
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (depth == 16)
        png_set_swap(png); /* little-endian host order for uint16_t access */
    png_read_update_info(png, info);

    int channels = png_get_channels(png, info);
    int bits = png_get_bit_depth(png, info);
    int width = (int)png_get_image_width(png, info), height = (int)png_get_image_height(png, info);
    size_t rowbytes = png_get_rowbytes(png, info);
    sol_image image = {0};
    sol_status status = sol_image_alloc(&image, width, height, channels);
    if (status != SOL_OK)
        return status;
    unsigned char *row = malloc(rowbytes);
    if (!row) {
        sol_image_free(&image);
        return SOL_ERR_NO_MEMORY;
    }
    const float maxcode = (float)((1 << bits) - 1); /* division, not a reciprocal: exact code/max */
    for (int y = 0; y < height; ++y) {
        png_read_row(png, row, NULL);
        float *dst = sol_image_pixel(&image, 0, y);
        for (size_t i = 0; i < (size_t)width * (size_t)channels; ++i)
            dst[i] = (bits == 16 ? (float)((const uint16_t *)(const void *)row)[i] : (float)row[i]) / maxcode;
    }
    free(row);
    *out = image;
    if (bits_out)
        *bits_out = bits;
    return SOL_OK;
}

sol_status sol_png_read(const char *path, sol_image *out, int *bits_out)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    FILE *file = fopen(path, "rb");
    if (!file)
        return SOL_ERR_IO;
    unsigned char signature[8];
    if (fread(signature, 1, 8, file) != 8 || png_sig_cmp(signature, 0, 8)) {
        fclose(file);
        return SOL_ERR_FORMAT;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, silent_error, silent_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        fclose(file);
        return SOL_ERR_NO_MEMORY;
    }
    /* libpng reports errors by longjmp; a volatile status survives it. */
    volatile sol_status status = SOL_ERR_FORMAT;
    if (!setjmp(png_jmpbuf(png))) {
        png_set_sig_bytes(png, 8);
        status = read_rows(png, info, file, out, bits_out);
    }
    png_destroy_read_struct(&png, &info, NULL);
    fclose(file);
    return status;
}

static sol_status check_writable(const sol_image *image)
{
    size_t count = (size_t)image->width * (size_t)image->height * (size_t)image->channels;
    for (size_t i = 0; i < count; ++i) {
        if (!isfinite(image->data[i]))
            return SOL_ERR_NONFINITE;
        if (image->data[i] < 0.0f || image->data[i] > 1.0f)
            return SOL_ERR_OUT_OF_RANGE;
    }
    return SOL_OK;
}

static void write_rows(png_structp png, png_infop info, FILE *file, const sol_image *image, int bits, unsigned char *row)
{
    static const int color_types[4] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                       PNG_COLOR_TYPE_RGB_ALPHA};
    png_init_io(png, file);
    png_set_IHDR(png, info, (png_uint_32)image->width, (png_uint_32)image->height, bits,
                 color_types[image->channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    if (bits == 16)
        png_set_swap(png);
    const float maxcode = (float)((1 << bits) - 1);
    for (int y = 0; y < image->height; ++y) {
        const float *src = sol_image_pixel(image, 0, y);
        for (size_t i = 0; i < (size_t)image->width * (size_t)image->channels; ++i) {
            long code = lrintf(src[i] * maxcode);
            if (bits == 16)
                ((uint16_t *)(void *)row)[i] = (uint16_t)code;
            else
                row[i] = (unsigned char)code;
        }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
}

sol_status sol_png_write(const char *path, const sol_image *image, int bits)
{
    if (!path || !image || !image->data)
        return SOL_ERR_NULL_ARG;
    if ((bits != 8 && bits != 16) || image->width <= 0 || image->height <= 0 || image->channels < 1 ||
        image->channels > 4)
        return SOL_ERR_INVALID_ARG;
    sol_status status = check_writable(image);
    if (status != SOL_OK)
        return status;
    unsigned char *row = malloc((size_t)image->width * (size_t)image->channels * 2);
    if (!row)
        return SOL_ERR_NO_MEMORY;
    FILE *file = fopen(path, "wb");
    if (!file) {
        free(row);
        return SOL_ERR_IO;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, silent_error, silent_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    volatile sol_status result = SOL_ERR_NO_MEMORY;
    if (info) {
        result = SOL_ERR_IO;
        if (!setjmp(png_jmpbuf(png))) {
            write_rows(png, info, file, image, bits, row);
            result = SOL_OK;
        }
    }
    png_destroy_write_struct(&png, &info);
    if (fclose(file) != 0 && result == SOL_OK)
        result = SOL_ERR_IO;
    free(row);
    return result;
}
