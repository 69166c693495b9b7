/* exr_io.c - scanline OpenEXR files through the OpenEXR 3 core C API (never the C++ library).
 *
 * Channels are matched by name because the core keeps them sorted alphabetically (A, B, G, R).
 * Each channel is decoded into its own float plane and interleaved here: OpenEXR 3.1's decoder
 * mis-orders channels when it unpacks half data straight into an interleaved float buffer.
 * Channels we do not keep still get a destination (see aim_decoder): 3.1's half-to-float fast
 * paths write every channel of a 3- or 4-channel file, NULL pointer or not. */
#include "sol_core.h"

#include <errno.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Channel names for 1..4 channels, in sol_image's interleaved order. */
static const char *const channel_names[4][4] = {
    {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};

/* The core reports errors through this hook; the library must not print, so it is silent. */
static void silent_handler(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

static exr_context_initializer_t silent_initializer(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = silent_handler;
    return init;
}

static int has_channel(const exr_attr_chlist_t *list, const char *name)
{
    for (int i = 0; i < list->num_channels; ++i)
        if (!strcmp(list->entries[i].name.str, name))
            return list->entries[i].x_sampling == 1 && list->entries[i].y_sampling == 1;
    return 0;
}

/* 4 for RGBA, 3 for RGB, 2 for YA, 1 for Y; 0 if the file has none of these layouts. */
static int pick_layout(const exr_attr_chlist_t *list)
{
    int alpha = has_channel(list, "A");
    if (has_channel(list, "R") && has_channel(list, "G") && has_channel(list, "B"))
        return alpha ? 4 : 3;
    if (has_channel(list, "Y"))
        return alpha ? 2 : 1;
    return 0;
}

/* Points each decoder channel we keep at its plane row, and every other channel at a one-row
 * scratch (line stride 0) in the channel's stored type. A NULL destination is not enough in 3.1:
 * when a file holds 3 or 4 half channels and all outputs are float, the core picks a fast path
 * that writes all of them (a NULL one segfaults) and assumes no subsampling. Leaving the unkept
 * channels in their own type makes the output types differ, so the core falls back to its
 * generic unpacker, which honours strides and sampling. */
static void aim_decoder(exr_decode_pipeline_t *decoder, float *const planes[4], int channels, int width,
                        int first_row, uint8_t *scratch)
{
    for (int c = 0; c < decoder->channel_count; ++c) {
        exr_coding_channel_info_t *info = &decoder->channels[c];
        info->decode_to_ptr = scratch;
        info->user_pixel_stride = info->bytes_per_element;
        info->user_line_stride = 0;
        info->user_data_type = info->data_type;
        info->user_bytes_per_element = info->bytes_per_element;
        for (int k = 0; k < channels; ++k) {
            if (strcmp(info->channel_name, channel_names[channels - 1][k]))
                continue;
            info->decode_to_ptr = (uint8_t *)(planes[k] + (size_t)first_row * (size_t)width);
            info->user_pixel_stride = (int32_t)sizeof(float);
            info->user_line_stride = (int32_t)sizeof(float) * width;
            info->user_data_type = EXR_PIXEL_FLOAT;
            info->user_bytes_per_element = (int16_t)sizeof(float);
        }
    }
}

/* `scratch` holds one row of 4-byte values: the widest line an unkept channel can have. */
static exr_result_t decode_planes(exr_context_t ctx, exr_attr_box2i_t window, float *const planes[4], int channels,
                                  uint8_t *scratch)
{
    int32_t lines_per_chunk = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines_per_chunk);
    exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
    int width = window.max.x - window.min.x + 1, initialised = 0;
    /* 64-bit row: a window ending near INT32_MAX must not overflow the step past its end */
    for (int64_t y = window.min.y; rv == EXR_ERR_SUCCESS && y <= window.max.y; y += lines_per_chunk) {
        exr_chunk_info_t chunk;
        rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &chunk);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = initialised ? exr_decoding_update(ctx, 0, &chunk, &decoder)
                         : exr_decoding_initialize(ctx, 0, &chunk, &decoder);
        if (rv != EXR_ERR_SUCCESS)
            break;
        initialised = 1;
        aim_decoder(&decoder, planes, channels, width, chunk.start_y - window.min.y, scratch);
        rv = exr_decoding_choose_default_routines(ctx, 0, &decoder);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_decoding_run(ctx, 0, &decoder);
    }
    if (initialised)
        exr_decoding_destroy(ctx, &decoder);
    return rv;
}

static void interleave(const sol_image *image, float *const planes[4])
{
    size_t pixels = (size_t)image->width * (size_t)image->height;
    for (size_t i = 0; i < pixels; ++i)
        for (int k = 0; k < image->channels; ++k)
            image->data[i * (size_t)image->channels + (size_t)k] = planes[k][i];
}

/* Decodes the chosen channels of `image` (already sized) through planes and a scratch row, one
 * allocation: pixels * channels floats, then `width` floats of scratch. */
static sol_status decode_image(exr_context_t ctx, exr_attr_box2i_t window, const sol_image *image)
{
    size_t pixels = (size_t)image->width * (size_t)image->height;
    float *buffer = calloc(pixels * (size_t)image->channels + (size_t)image->width, sizeof(float));
    if (!buffer)
        return SOL_ERR_NO_MEMORY;
    float *planes[4] = {NULL};
    for (int k = 0; k < image->channels; ++k)
        planes[k] = buffer + (size_t)k * pixels;
    uint8_t *scratch = (uint8_t *)(buffer + pixels * (size_t)image->channels);
    exr_result_t rv = decode_planes(ctx, window, planes, image->channels, scratch);
    if (rv == EXR_ERR_SUCCESS)
        interleave(image, planes);
    free(buffer);
    if (rv == EXR_ERR_OUT_OF_MEMORY)
        return SOL_ERR_NO_MEMORY;
    return rv == EXR_ERR_SUCCESS ? SOL_OK : SOL_ERR_FORMAT; /* truncated or corrupt chunks */
}

/* The header's sizes against the caller's limits, before anything is sized from them (see
 * sol_exr_read_ex in sol_core.h): sol's own buffers (the image and the decoding planes, 8 bytes
 * per kept channel and pixel) and the core's chunk buffers (packed and unpacked chunk, twice the
 * bytes of every channel of the file over width x min(scanlines per chunk, height) pixels; its chunk offset
 * table, 8 bytes per chunk, is smaller than sol's image). */
static sol_status check_limits(exr_context_t ctx, const sol_read_limits *limits, const exr_attr_chlist_t *list,
                               int channels, int64_t width, int64_t height)
{
    if (list->num_channels > SOL_EXR_MAX_CHANNELS)
        return SOL_ERR_LIMIT;
    int32_t lines_per_chunk = 0;
    if (exr_get_scanlines_per_chunk(ctx, 0, &lines_per_chunk) != EXR_ERR_SUCCESS || lines_per_chunk < 1)
        return SOL_ERR_FORMAT;
    uint64_t file_bytes_per_pixel = 0;
    for (int i = 0; i < list->num_channels; ++i)
        file_bytes_per_pixel += list->entries[i].pixel_type == EXR_PIXEL_HALF ? 2u : 4u;
    sol_status status = sol_read_limits_check(limits, width, height, 1, 8u * (uint64_t)channels);
    if (status == SOL_OK)
        status = sol_read_limits_check(limits, width, lines_per_chunk < height ? lines_per_chunk : height, 1,
                                       2u * file_bytes_per_pixel);
    return status == SOL_ERR_INVALID_ARG ? SOL_ERR_FORMAT : status;
}

/* Reads an opened context into a new image; `*out` is written only on success. */
static sol_status read_context(exr_context_t ctx, const sol_read_limits *limits, sol_image *out)
{
    exr_storage_t storage;
    exr_attr_box2i_t window;
    const exr_attr_chlist_t *list = NULL;
    if (exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE ||
        exr_get_data_window(ctx, 0, &window) != EXR_ERR_SUCCESS || exr_get_channels(ctx, 0, &list) != EXR_ERR_SUCCESS)
        return SOL_ERR_FORMAT;
    int channels = pick_layout(list);
    int64_t width = (int64_t)window.max.x - window.min.x + 1, height = (int64_t)window.max.y - window.min.y + 1;
    /* the core takes line strides in bytes as int32_t; a wider plane row cannot be described */
    if (!channels || width < 1 || height < 1 || width > INT32_MAX / (int64_t)sizeof(float) || height > INT32_MAX)
        return SOL_ERR_FORMAT;
    sol_status status = check_limits(ctx, limits, list, channels, width, height);
    if (status != SOL_OK)
        return status;
    sol_image image = {0};
    status = sol_image_alloc(&image, (int)width, (int)height, channels);
    if (status == SOL_ERR_INVALID_ARG) /* a data window too large to address is the file's fault */
        return SOL_ERR_FORMAT;
    if (status == SOL_OK)
        status = decode_image(ctx, window, &image);
    if (status != SOL_OK) {
        sol_image_free(&image);
        return status;
    }
    *out = image;
    return SOL_OK;
}

/* fopen alone succeeds on a directory; reading one byte tells "cannot read" (IO) apart from
 * "readable but not an EXR" (FORMAT, decided by the core). */
static int readable(const char *path)
{
    FILE *probe = fopen(path, "rb");
    if (!probe)
        return 0;
    (void)fgetc(probe);
    int ok = !ferror(probe);
    fclose(probe);
    return ok;
}

sol_status sol_exr_read(const char *path, sol_image *out)
{
    return sol_exr_read_ex(path, NULL, out);
}

sol_status sol_exr_read_ex(const char *path, const sol_read_limits *limits, sol_image *out)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    if (!readable(path))
        return SOL_ERR_IO;
    exr_context_initializer_t init = silent_initializer();
    exr_context_t ctx = NULL;
    if (exr_start_read(&ctx, path, &init) != EXR_ERR_SUCCESS) {
        exr_finish(&ctx);
        return SOL_ERR_FORMAT;
    }
    sol_status status = read_context(ctx, limits, out);
    exr_finish(&ctx);
    return status;
}

static sol_status check_exr_values(const sol_image *image, int half_precision)
{
    size_t count = (size_t)image->width * (size_t)image->height * (size_t)image->channels;
    for (size_t i = 0; i < count; ++i) {
        if (!isfinite(image->data[i]))
            return SOL_ERR_NONFINITE;
        if (half_precision && fabsf(image->data[i]) > 65504.0f)
            return SOL_ERR_OUT_OF_RANGE;
    }
    return SOL_OK;
}

/* Points each encoder channel at its interleaved float values; the core converts to the
 * channel's stored type (half or float) while packing. */
static void aim_encoder(exr_encode_pipeline_t *encoder, const sol_image *image, int first_row)
{
    for (int c = 0; c < encoder->channel_count; ++c) {
        exr_coding_channel_info_t *info = &encoder->channels[c];
        for (int k = 0; k < image->channels; ++k) {
            if (strcmp(info->channel_name, channel_names[image->channels - 1][k]))
                continue;
            info->encode_from_ptr = (const uint8_t *)(sol_image_pixel(image, 0, first_row) + k);
            info->user_pixel_stride = (int32_t)sizeof(float) * image->channels;
            info->user_line_stride = (int32_t)sizeof(float) * image->channels * image->width;
            info->user_data_type = EXR_PIXEL_FLOAT;
            info->user_bytes_per_element = (int16_t)sizeof(float);
        }
    }
}

static exr_result_t encode_rows(exr_context_t ctx, const sol_image *image)
{
    int32_t lines_per_chunk = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines_per_chunk);
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    int initialised = 0;
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < image->height; y += lines_per_chunk) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctx, 0, y, &chunk);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = initialised ? exr_encoding_update(ctx, 0, &chunk, &encoder)
                         : exr_encoding_initialize(ctx, 0, &chunk, &encoder);
        if (rv != EXR_ERR_SUCCESS)
            break;
        initialised = 1;
        aim_encoder(&encoder, image, chunk.start_y);
        rv = exr_encoding_choose_default_routines(ctx, 0, &encoder);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctx, 0, &encoder);
    }
    if (initialised)
        exr_encoding_destroy(ctx, &encoder);
    return rv;
}

static exr_result_t write_header(exr_context_t ctx, const sol_image *image, int half_precision)
{
    int part = 0;
    exr_result_t rv = exr_add_part(ctx, "main", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, image->width, image->height, EXR_COMPRESSION_ZIP);
    for (int k = 0; rv == EXR_ERR_SUCCESS && k < image->channels; ++k)
        rv = exr_add_channel(ctx, part, channel_names[image->channels - 1][k],
                             half_precision ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    return rv;
}

/* The core's custom write hook (openexr_context.h, exr_write_func_ptr_t): positioned writes to
 * the temporary sol_file_out opened, so the core never names a file itself. */
static int64_t write_to_fd(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t size, uint64_t offset,
                           exr_stream_error_func_ptr_t error_cb)
{
    int fd = *(const int *)userdata;
    uint64_t done = 0;
    while (done < size) {
        if (offset + done > (uint64_t)INT64_MAX)
            break;
        ssize_t n = pwrite(fd, (const uint8_t *)buffer + done, (size_t)(size - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        done += (uint64_t)n;
    }
    if (done < size) {
        if (error_cb)
            error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed");
        return -1;
    }
    return (int64_t)done;
}

sol_status sol_exr_write(const char *path, const sol_image *image, int half_precision)
{
    if (!path || !image || !image->data)
        return SOL_ERR_NULL_ARG;
    if (image->width <= 0 || image->height <= 0 || image->channels < 1 || image->channels > 4)
        return SOL_ERR_INVALID_ARG;
    if ((int64_t)image->width * image->channels > INT32_MAX / (int64_t)sizeof(float))
        return SOL_ERR_INVALID_ARG; /* the core's line stride (bytes, int32_t) cannot span the row */
    sol_status status = check_exr_values(image, half_precision);
    if (status != SOL_OK)
        return status;
    sol_file_out out;
    status = sol_file_out_open(&out, path);
    if (status != SOL_OK)
        return status;
    int fd = fileno(out.file); /* written through write_to_fd only, never through stdio */
    exr_context_initializer_t init = silent_initializer();
    init.user_data = &fd;
    init.write_fn = write_to_fd;
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_header(ctx, image, half_precision);
    if (rv == EXR_ERR_SUCCESS)
        rv = encode_rows(ctx, image);
    if (exr_finish(&ctx) != EXR_ERR_SUCCESS)
        rv = EXR_ERR_WRITE_IO;
    /* the temporary becomes `path` only if the core wrote everything, offset tables included */
    status = sol_file_out_close(&out, rv == EXR_ERR_SUCCESS);
    if (rv == EXR_ERR_OUT_OF_MEMORY)
        return SOL_ERR_NO_MEMORY;
    return rv == EXR_ERR_SUCCESS ? status : SOL_ERR_IO;
}
