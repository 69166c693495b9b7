/* png_io.c - 8- and 16-bit PNG files through libpng's classic API.
 * Values are stored as codes without any gamma conversion: sol decides what a code means.
 *
 * libpng reports errors by longjmp (libpng manual, "Setting up error handling"), so everything a
 * read allocates lives in a png_job owned by the caller of the function that calls setjmp: after
 * a longjmp the job still names every buffer, and one cleanup path frees them all. */
#include "sol_core.h"

#include <math.h>
#include <png.h>
#include <setjmp.h>
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

/* What one read owns; freed by the caller whatever happened (see the file comment). */
typedef struct png_job {
    const sol_read_limits *limits;
    sol_image image;     /* the float image; handed to the caller on success */
    unsigned char *raw;  /* one row (progressive files) or every row (interlaced files) */
    png_bytep *rows;     /* row pointers into raw, interlaced files only */
    int bits;            /* 8 or 16 after the transforms */
    sol_status status;   /* set before each step that may fail, so a longjmp leaves the right code */
} png_job;

/* Channels after the transforms read_job asks for: palette -> RGB, tRNS -> alpha. */
static int channels_after_transforms(int color, int has_trns)
{
    int channels = (color & PNG_COLOR_MASK_COLOR) ? 3 : 1;
    if ((color & PNG_COLOR_MASK_ALPHA) || has_trns)
        ++channels;
    return channels;
}

static void convert_row(const unsigned char *row, float *dst, size_t count, int bits)
{
    const float maxcode = (float)((1 << bits) - 1); /* division, not a reciprocal: exact code/max */
    for (size_t i = 0; i < count; ++i)
        dst[i] = (bits == 16 ? (float)((const uint16_t *)(const void *)row)[i] : (float)row[i]) / maxcode;
}

/* Decodes into job; may longjmp out at any libpng call. */
static void read_job(png_structp png, png_infop info, FILE *file, png_job *job)
{
    job->status = SOL_ERR_FORMAT;
    png_init_io(png, file);
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    int color = png_get_color_type(png, info);
    int depth = png_get_bit_depth(png, info);
    int interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
    png_uint_32 width32 = png_get_image_width(png, info), height32 = png_get_image_height(png, info);
    int channels = channels_after_transforms(color, png_get_valid(png, info, PNG_INFO_tRNS) != 0);
    int bits = depth == 16 ? 16 : 8;
    /* The header's sizes are checked before anything is sized from them: the float image, plus
     * the whole raw image when an interlaced file has to be decoded at once. */
    uint64_t bytes_per_pixel = (uint64_t)channels * sizeof(float) + (interlaced ? (uint64_t)channels * (uint64_t)(bits / 8) : 0);
    sol_status status = sol_read_limits_check(job->limits, (int64_t)width32, (int64_t)height32, 1, bytes_per_pixel);
    if (status != SOL_OK || width32 > INT32_MAX || height32 > INT32_MAX) {
        job->status = status == SOL_ERR_INVALID_ARG ? SOL_ERR_FORMAT : SOL_ERR_LIMIT;
        return;
    }
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (depth == 16)
        png_set_swap(png); /* little-endian host order for uint16_t access */
    int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    int width = (int)width32, height = (int)height32;
    size_t rowbytes = png_get_rowbytes(png, info);
    size_t values = (size_t)width * (size_t)channels; /* cannot wrap: within the limit above */
    if (png_get_channels(png, info) != channels || png_get_bit_depth(png, info) != bits ||
        rowbytes < values * (size_t)(bits / 8))
        return; /* SOL_ERR_FORMAT: libpng disagrees with the layout checked above */

    job->status = SOL_ERR_NO_MEMORY;
    if (sol_image_alloc(&job->image, width, height, channels) != SOL_OK)
        return;
    size_t raw_bytes = rowbytes;
    if (passes > 1 && !sol_size_mul(&raw_bytes, rowbytes, (size_t)height))
        return;
    job->raw = malloc(raw_bytes);
    if (!job->raw)
        return;
    job->status = SOL_ERR_FORMAT;
    if (passes > 1) {
        /* Adam7: every pass writes into the full image, so all rows are decoded before any is
         * converted (libpng manual, "Reading interlaced images"). */
        job->rows = malloc((size_t)height * sizeof *job->rows);
        if (!job->rows) {
            job->status = SOL_ERR_NO_MEMORY;
            return;
        }
        for (int y = 0; y < height; ++y)
            job->rows[y] = job->raw + (size_t)y * rowbytes;
        png_read_image(png, job->rows);
        for (int y = 0; y < height; ++y)
            convert_row(job->rows[y], sol_image_pixel(&job->image, 0, y), values, bits);
    } else {
        for (int y = 0; y < height; ++y) {
            png_read_row(png, job->raw, NULL);
            convert_row(job->raw, sol_image_pixel(&job->image, 0, y), values, bits);
        }
    }
    job->bits = bits;
    job->status = SOL_OK;
}

/* The only frame that calls setjmp; it modifies no local of its own after the call. */
static void run_job(png_structp png, png_infop info, FILE *file, png_job *job)
{
    if (setjmp(png_jmpbuf(png)))
        return; /* job->status already says what failed */
    read_job(png, info, file, job);
}

sol_status sol_png_read_ex(const char *path, const sol_read_limits *limits, sol_image *out, int *bits_out)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    FILE *file = fopen(path, "rb");
    if (!file)
        return SOL_ERR_IO;
    unsigned char signature[8];
    if (fread(signature, 1, 8, file) != 8 || png_sig_cmp(signature, 0, 8)) {
        int io_error = ferror(file);
        fclose(file);
        return io_error ? SOL_ERR_IO : SOL_ERR_FORMAT;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, silent_error, silent_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        fclose(file);
        return SOL_ERR_NO_MEMORY;
    }
    png_job job = {.limits = limits, .status = SOL_ERR_FORMAT};
    run_job(png, info, file, &job);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(file);
    free(job.rows);
    free(job.raw);
    if (job.status != SOL_OK) {
        sol_image_free(&job.image);
        return job.status;
    }
    *out = job.image;
    if (bits_out)
        *bits_out = job.bits;
    return SOL_OK;
}

sol_status sol_png_read(const char *path, sol_image *out, int *bits_out)
{
    return sol_png_read_ex(path, NULL, out, bits_out);
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
    size_t row_bytes;
    if (!sol_size_mul(&row_bytes, (size_t)image->width * (size_t)image->channels, 2))
        return SOL_ERR_INVALID_ARG;
    unsigned char *row = malloc(row_bytes);
    if (!row)
        return SOL_ERR_NO_MEMORY;
    sol_file_out out;
    status = sol_file_out_open(&out, path);
    if (status != SOL_OK) {
        free(row);
        return status;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, silent_error, silent_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    volatile sol_status result = SOL_ERR_NO_MEMORY;
    if (info) {
        result = SOL_ERR_IO;
        if (!setjmp(png_jmpbuf(png))) {
            write_rows(png, info, out.file, image, bits, row);
            result = SOL_OK;
        }
    }
    png_destroy_write_struct(&png, &info);
    free(row);
    /* the temporary becomes `path` only if every byte reached the file */
    sol_status closed = sol_file_out_close(&out, result == SOL_OK);
    return result == SOL_OK ? closed : result;
}
