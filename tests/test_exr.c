/* test_exr.c - OpenEXR files through the core C API: round trips of sol's own files, files sol did
 * not write (crafted with other channel sets, types, sampling and data windows), broken files and
 * refusals. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sol_core.h"

/* ---- scratch folder: one per test, removed with its files ---- */

static char folder[64];

static void make_folder(void)
{
    strcpy(folder, "/tmp/sol_test_exr_XXXXXX");
    cr_assert_not_null(mkdtemp(folder));
}

static const char *in_folder(const char *name)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    return path;
}

static void remove_folder(const char *const *names, int count)
{
    for (int i = 0; i < count; ++i)
        unlink(in_folder(names[i]));
    cr_assert_eq(rmdir(folder), 0, "a test left a file behind in %s", folder);
}

/* ---- round trips of sol's own files ---- */

/* Values exactly representable in half: small integers over powers of two, and a large one. */
static float half_exact_value(int i)
{
    static const float values[8] = {0.0f, 1.0f, 0.5f, 65504.0f, 0.000061035156f, -2.25f, 1024.0f, 0.099975586f};
    return values[i % 8] * (float)(1 << (i % 3)); /* powers of two keep them exact */
}

static void round_trip(int channels, int half_precision)
{
    sol_image image = {0}, back = {0};
    cr_assert_eq(sol_image_alloc(&image, 7, 5, channels), SOL_OK);
    for (int i = 0; i < 35 * channels; ++i)
        image.data[i] = half_precision ? fminf(half_exact_value(i), 65504.0f) : (float)i * 1.37e5f - 3.0f;
    make_folder();
    const char *path = in_folder("round_trip.exr");
    cr_assert_eq(sol_exr_write(path, &image, half_precision), SOL_OK);
    cr_assert_eq(sol_exr_read(path, &back), SOL_OK);
    cr_assert_eq(back.width, 7);
    cr_assert_eq(back.height, 5);
    cr_assert_eq(back.channels, channels);
    for (int i = 0; i < 35 * channels; ++i)
        cr_assert_eq(back.data[i], image.data[i], "%d channels, half %d, value %d: %g != %g", channels,
                     half_precision, i, back.data[i], image.data[i]);
    remove_folder((const char *const[]){"round_trip.exr"}, 1);
    sol_image_free(&image);
    sol_image_free(&back);
}

Test(exr, round_trips_every_layout_in_half_and_float_bit_exactly)
{
    for (int channels = 1; channels <= 4; ++channels) {
        round_trip(channels, 1);
        round_trip(channels, 0);
    }
}

Test(exr, a_tall_image_spans_many_chunks)
{
    sol_image image = {0}, back = {0};
    cr_assert_eq(sol_image_alloc(&image, 3, 101, 3), SOL_OK);
    for (int i = 0; i < 3 * 101 * 3; ++i)
        image.data[i] = (float)i;
    make_folder();
    const char *path = in_folder("tall.exr");
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_OK);
    cr_assert_eq(sol_exr_read(path, &back), SOL_OK);
    cr_assert_eq(memcmp(back.data, image.data, sizeof(float) * 3 * 101 * 3), 0);
    remove_folder((const char *const[]){"tall.exr"}, 1);
    sol_image_free(&image);
    sol_image_free(&back);
}

Test(exr, write_refuses_bad_values_and_leaves_no_file)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 2, 2, 3), SOL_OK);
    make_folder();
    const char *path = in_folder("bad.exr");
    image.data[5] = NAN;
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_ERR_NONFINITE);
    image.data[5] = -INFINITY;
    cr_assert_eq(sol_exr_write(path, &image, 1), SOL_ERR_NONFINITE);
    image.data[5] = 65520.0f; /* rounds to Inf in half */
    cr_assert_eq(sol_exr_write(path, &image, 1), SOL_ERR_OUT_OF_RANGE);
    cr_assert_neq(access(path, F_OK), 0);
    cr_assert_eq(sol_exr_write(path, &image, 0), SOL_OK); /* fine as float */
    cr_assert_eq(sol_exr_write(NULL, &image, 0), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_exr_write("/nonexistent/dir/x.exr", &image, 0), SOL_ERR_IO);
    remove_folder((const char *const[]){"bad.exr"}, 1);
    sol_image_free(&image);
}

/* ---- crafted files ---- */

typedef struct crafted_channel {
    const char *name;
    exr_pixel_type_t type;
    int sampling; /* the same in x and y */
} crafted_channel;

/* Value stored at pixel i (row-major over the channel's own, possibly subsampled, grid) of the
 * k-th crafted channel: distinct per channel and exact in half. uint channels hold integers, and
 * pixel 0 holds 3e9, which a signed conversion would get wrong (and which float holds exactly). */
static float crafted_value(int k, int i, exr_pixel_type_t type)
{
    if (type == EXR_PIXEL_UINT)
        return i == 0 ? 3e9f : (float)(k * 100 + i);
    return (float)(k * 100 + i) * 0.5f;
}

/* One plane per channel in the type handed to the encoder: uint32 for uint channels, float
 * otherwise (the core converts float to half while packing). */
static void *crafted_plane(int k, const crafted_channel *ch, int w, int h)
{
    int count = (w / ch->sampling) * (h / ch->sampling);
    uint32_t *plane = malloc(sizeof(uint32_t) * (size_t)count);
    cr_assert_not_null(plane);
    for (int i = 0; i < count; ++i) {
        float v = crafted_value(k, i, ch->type);
        if (ch->type == EXR_PIXEL_UINT)
            plane[i] = (uint32_t)v;
        else
            memcpy(&plane[i], &v, sizeof v);
    }
    return plane;
}

/* Points the encoder at the block of the planes whose top-left pixel is (col, row) of the window. */
static void aim_crafted(exr_encode_pipeline_t *enc, const crafted_channel *chans, int n, void *const *planes,
                        int w, int col, int row)
{
    for (int e = 0; e < enc->channel_count; ++e) {
        int k = 0;
        while (k < n && strcmp(chans[k].name, enc->channels[e].channel_name))
            ++k;
        cr_assert_lt(k, n);
        int s = chans[k].sampling;
        size_t first = (size_t)(row / s) * (size_t)(w / s) + (size_t)(col / s);
        enc->channels[e].encode_from_ptr = (const uint8_t *)planes[k] + first * 4;
        enc->channels[e].user_pixel_stride = 4;
        enc->channels[e].user_line_stride = 4 * (w / s);
        enc->channels[e].user_data_type = chans[k].type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
        enc->channels[e].user_bytes_per_element = 4;
    }
}

static void encode_crafted(exr_context_t ctx, exr_encode_pipeline_t *enc, const exr_chunk_info_t *chunk, int first,
                           const crafted_channel *chans, int n, void *const *planes, int w, int col, int row)
{
    if (first)
        cr_assert_eq(exr_encoding_initialize(ctx, 0, chunk, enc), EXR_ERR_SUCCESS);
    else
        cr_assert_eq(exr_encoding_update(ctx, 0, chunk, enc), EXR_ERR_SUCCESS);
    aim_crafted(enc, chans, n, planes, w, col, row);
    cr_assert_eq(exr_encoding_choose_default_routines(ctx, 0, enc), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_encoding_run(ctx, 0, enc), EXR_ERR_SUCCESS);
}

/* All chunks must be written: 3.1's exr_finish deletes a file with chunks missing. */
static void write_crafted_chunks(exr_context_t ctx, const crafted_channel *chans, int n, void *const *planes,
                                 exr_attr_box2i_t window, int tile)
{
    int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    int32_t lines = 0;
    if (!tile)
        cr_assert_eq(exr_get_scanlines_per_chunk(ctx, 0, &lines), EXR_ERR_SUCCESS);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_chunk_info_t chunk;
    if (tile) { /* w and h are multiples of the tile size */
        for (int ty = 0; ty < h / tile; ++ty)
            for (int tx = 0; tx < w / tile; ++tx) {
                cr_assert_eq(exr_write_tile_chunk_info(ctx, 0, tx, ty, 0, 0, &chunk), EXR_ERR_SUCCESS);
                encode_crafted(ctx, &enc, &chunk, !tx && !ty, chans, n, planes, w, tx * tile, ty * tile);
            }
    } else {
        for (int y = window.min.y; y <= window.max.y; y += lines) {
            cr_assert_eq(exr_write_scanline_chunk_info(ctx, 0, y, &chunk), EXR_ERR_SUCCESS);
            encode_crafted(ctx, &enc, &chunk, y == window.min.y, chans, n, planes, w, 0, chunk.start_y - window.min.y);
        }
    }
    exr_encoding_destroy(ctx, &enc);
}

static void quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* Writes a ZIP file, scanline or (`tiled`) in 4x4 tiles, with the given channels over `window`. */
static void craft(const char *path, const crafted_channel *chans, int n, exr_attr_box2i_t window, int tiled)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet; /* a failure shows up in the asserted result codes */
    exr_context_t ctx = NULL;
    exr_attr_v2f_t centre = {.x = 0.0f, .y = 0.0f};
    int part = 0, w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    cr_assert_eq(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_add_part(ctx, "crafted", tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_initialize_required_attr(ctx, part, &window, &window, 1.0f, &centre, 1.0f,
                                              EXR_LINEORDER_INCREASING_Y, EXR_COMPRESSION_ZIP),
                 EXR_ERR_SUCCESS);
    for (int k = 0; k < n; ++k)
        cr_assert_eq(exr_add_channel(ctx, part, chans[k].name, chans[k].type, EXR_PERCEPTUALLY_LOGARITHMIC,
                                     chans[k].sampling, chans[k].sampling),
                     EXR_ERR_SUCCESS);
    if (tiled)
        cr_assert_eq(exr_set_tile_descriptor(ctx, part, 4, 4, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_write_header(ctx), EXR_ERR_SUCCESS);
    void *planes[8] = {NULL};
    for (int k = 0; k < n; ++k)
        planes[k] = crafted_plane(k, &chans[k], w, h);
    write_crafted_chunks(ctx, chans, n, planes, window, tiled ? 4 : 0);
    for (int k = 0; k < n; ++k)
        free(planes[k]);
    cr_assert_eq(exr_finish(&ctx), EXR_ERR_SUCCESS);
    cr_assert_eq(access(path, F_OK), 0);
}

static exr_attr_box2i_t box(int x0, int y0, int w, int h)
{
    exr_attr_box2i_t b = {.min = {.x = x0, .y = y0}, .max = {.x = x0 + w - 1, .y = y0 + h - 1}};
    return b;
}

/* Reads `path` and checks that channel j of the image holds crafted channel index `from[j]`. */
static void expect_read(const char *path, int w, int h, int channels, const int *from, const crafted_channel *chans)
{
    sol_image image = {0};
    cr_assert_eq(sol_exr_read(path, &image), SOL_OK);
    cr_assert_eq(image.width, w);
    cr_assert_eq(image.height, h);
    cr_assert_eq(image.channels, channels);
    for (int i = 0; i < w * h; ++i)
        for (int j = 0; j < channels; ++j)
            cr_assert_eq(image.data[i * channels + j], crafted_value(from[j], i, chans[from[j]].type),
                         "pixel %d channel %d: %g", i, j, image.data[i * channels + j]);
    sol_image_free(&image);
}

static void expect_refused(const char *path, sol_status expected)
{
    sol_image image = {.width = 17, .data = NULL};
    cr_assert_eq(sol_exr_read(path, &image), expected, "%s", path);
    cr_assert_eq(image.width, 17);
    cr_assert_null(image.data);
}

/* ---- files with channels sol does not keep ---- */

/* OpenEXR 3.1 picks a half-to-float fast path for files of 3 or 4 half channels that writes every
 * channel, so an unkept one (depth Z here) once made the reader write through NULL. */
Test(exr, rgb_half_with_an_extra_channel_loads_by_name)
{
    const crafted_channel chans[] = {{"Z", EXR_PIXEL_HALF, 1}, {"B", EXR_PIXEL_HALF, 1},
                                     {"R", EXR_PIXEL_HALF, 1}, {"G", EXR_PIXEL_HALF, 1}};
    make_folder();
    craft(in_folder("bgrz.exr"), chans, 4, box(0, 0, 7, 5), 0);
    expect_read(in_folder("bgrz.exr"), 7, 5, 3, (const int[]){2, 3, 1}, chans);
    remove_folder((const char *const[]){"bgrz.exr"}, 1);
}

Test(exr, y_alpha_half_with_an_extra_channel_loads_by_name)
{
    const crafted_channel chans[] = {{"Y", EXR_PIXEL_HALF, 1}, {"depth", EXR_PIXEL_HALF, 1}, {"A", EXR_PIXEL_HALF, 1}};
    make_folder();
    craft(in_folder("yaz.exr"), chans, 3, box(0, 0, 5, 7), 0);
    expect_read(in_folder("yaz.exr"), 5, 7, 2, (const int[]){0, 2}, chans);
    remove_folder((const char *const[]){"yaz.exr"}, 1);
}

/* What OpenEXR's own RgbaOutputFile writes in WRITE_YC mode: full-resolution Y, chroma
 * subsampled 2x2. Only Y is kept, and the chroma must not disturb it. */
Test(exr, luminance_chroma_file_loads_its_luminance)
{
    const crafted_channel chans[] = {{"Y", EXR_PIXEL_HALF, 1}, {"RY", EXR_PIXEL_HALF, 2}, {"BY", EXR_PIXEL_HALF, 2}};
    make_folder();
    craft(in_folder("yc.exr"), chans, 3, box(0, 0, 6, 20), 0); /* 20 rows: two ZIP chunks */
    expect_read(in_folder("yc.exr"), 6, 20, 1, (const int[]){0}, chans);
    remove_folder((const char *const[]){"yc.exr"}, 1);
}

Test(exr, mixed_types_and_extra_channels_load_as_float_by_name)
{
    const crafted_channel chans[] = {{"A", EXR_PIXEL_HALF, 1}, {"Y", EXR_PIXEL_FLOAT, 1}, {"G", EXR_PIXEL_FLOAT, 1},
                                     {"B", EXR_PIXEL_UINT, 1}, {"R", EXR_PIXEL_HALF, 1}, {"Z", EXR_PIXEL_FLOAT, 1}};
    make_folder();
    craft(in_folder("mixed.exr"), chans, 6, box(0, 0, 4, 3), 0);
    expect_read(in_folder("mixed.exr"), 4, 3, 4, (const int[]){4, 2, 3, 0}, chans); /* R,G,B win over Y */
    remove_folder((const char *const[]){"mixed.exr"}, 1);
}

Test(exr, uint_channels_load_as_float)
{
    const crafted_channel chans[] = {{"Y", EXR_PIXEL_UINT, 1}, {"A", EXR_PIXEL_UINT, 1}};
    make_folder();
    craft(in_folder("uint.exr"), chans, 2, box(0, 0, 3, 2), 0);
    expect_read(in_folder("uint.exr"), 3, 2, 2, (const int[]){0, 1}, chans);
    remove_folder((const char *const[]){"uint.exr"}, 1);
}

/* ---- data windows ---- */

/* The image is the data window; a negative, odd origin and a last chunk of 8 of 16 rows. */
Test(exr, data_window_away_from_the_origin_gives_its_own_size)
{
    const crafted_channel chans[] = {{"R", EXR_PIXEL_HALF, 1}, {"G", EXR_PIXEL_HALF, 1},
                                     {"B", EXR_PIXEL_HALF, 1}, {"A", EXR_PIXEL_HALF, 1}};
    make_folder();
    craft(in_folder("window.exr"), chans, 4, box(-3, 1001, 9, 40), 0);
    expect_read(in_folder("window.exr"), 9, 40, 4, (const int[]){0, 1, 2, 3}, chans);
    remove_folder((const char *const[]){"window.exr"}, 1);
}

/* ---- refusals ---- */

Test(exr, files_without_a_known_layout_or_not_scanline_are_refused)
{
    const crafted_channel rg[] = {{"R", EXR_PIXEL_HALF, 1}, {"G", EXR_PIXEL_HALF, 1}};
    const crafted_channel sub[] = {{"Y", EXR_PIXEL_HALF, 2}}; /* Y exists, but not at full resolution */
    const crafted_channel rgb[] = {{"R", EXR_PIXEL_HALF, 1}, {"G", EXR_PIXEL_HALF, 1}, {"B", EXR_PIXEL_HALF, 1}};
    make_folder();
    craft(in_folder("rg.exr"), rg, 2, box(0, 0, 4, 4), 0);
    craft(in_folder("sub.exr"), sub, 1, box(0, 0, 4, 4), 0);
    craft(in_folder("tiled.exr"), rgb, 3, box(0, 0, 8, 8), 1);
    expect_refused(in_folder("rg.exr"), SOL_ERR_FORMAT);
    expect_refused(in_folder("sub.exr"), SOL_ERR_FORMAT);
    expect_refused(in_folder("tiled.exr"), SOL_ERR_FORMAT);
    remove_folder((const char *const[]){"rg.exr", "sub.exr", "tiled.exr"}, 3);
}

/* Every cut of a valid file fails cleanly: header cuts in the core, chunk cuts in decoding. */
Test(exr, truncated_files_are_refused_and_leave_the_output_alone)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 7, 20, 4), SOL_OK);
    for (int i = 0; i < 7 * 20 * 4; ++i)
        image.data[i] = (float)(i % 61) * 0.25f;
    make_folder();
    cr_assert_eq(sol_exr_write(in_folder("whole.exr"), &image, 1), SOL_OK);
    FILE *f = fopen(in_folder("whole.exr"), "rb");
    cr_assert_not_null(f);
    unsigned char bytes[8192];
    size_t size = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    cr_assert(size > 64 && size < sizeof bytes);
    for (size_t cut = 0; cut < size; cut += 1 + cut / 8) {
        f = fopen(in_folder("cut.exr"), "wb");
        cr_assert_eq(fwrite(bytes, 1, cut, f), cut);
        fclose(f);
        expect_refused(in_folder("cut.exr"), SOL_ERR_FORMAT);
    }
    sol_image_free(&image);
    remove_folder((const char *const[]){"whole.exr", "cut.exr"}, 2);
}

Test(exr, a_directory_is_an_io_error)
{
    make_folder();
    expect_refused(folder, SOL_ERR_IO);
    remove_folder(NULL, 0);
}

Test(exr, read_tells_missing_from_malformed_and_leaves_output_untouched)
{
    sol_image image = {.width = 11};
    cr_assert_eq(sol_exr_read("/nonexistent/x.exr", &image), SOL_ERR_IO);
    make_folder();
    const char *path = in_folder("not.exr");
    FILE *f = fopen(path, "wb");
    fputs("v/1\x01 this is not an OpenEXR file", f);
    fclose(f);
    cr_assert_eq(sol_exr_read(path, &image), SOL_ERR_FORMAT);
    cr_assert_eq(sol_exr_read(NULL, &image), SOL_ERR_NULL_ARG);
    cr_assert_eq(image.width, 11);
    remove_folder((const char *const[]){"not.exr"}, 1);
}

Test(exr, bad_arguments_are_refused)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 2, 2, 1), SOL_OK);
    make_folder();
    const char *path = in_folder("x.exr");
    cr_assert_eq(sol_exr_read(path, NULL), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_exr_write(path, NULL, 0), SOL_ERR_NULL_ARG);
    sol_image bad = image;
    bad.data = NULL;
    cr_assert_eq(sol_exr_write(path, &bad, 0), SOL_ERR_NULL_ARG);
    bad = image;
    bad.channels = 5;
    cr_assert_eq(sol_exr_write(path, &bad, 0), SOL_ERR_INVALID_ARG);
    bad.channels = 0;
    cr_assert_eq(sol_exr_write(path, &bad, 0), SOL_ERR_INVALID_ARG);
    bad = image;
    bad.height = 0;
    cr_assert_eq(sol_exr_write(path, &bad, 1), SOL_ERR_INVALID_ARG);
    sol_image_free(&image);
    remove_folder(NULL, 0); /* rmdir fails if any refusal created the file */
}

/* ---- what sol writes ---- */

/* A round trip cannot tell half from float storage (float holds every half), so look inside. */
static void expect_stored(const char *path, exr_pixel_type_t type, int channels)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    const exr_attr_chlist_t *list = NULL;
    exr_compression_t compression;
    cr_assert_eq(exr_start_read(&ctx, path, &init), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_get_compression(ctx, 0, &compression), EXR_ERR_SUCCESS);
    cr_assert_eq(compression, EXR_COMPRESSION_ZIP);
    cr_assert_eq(exr_get_channels(ctx, 0, &list), EXR_ERR_SUCCESS);
    cr_assert_eq(list->num_channels, channels);
    for (int k = 0; k < channels; ++k)
        cr_assert_eq(list->entries[k].pixel_type, type, "channel %s", list->entries[k].name.str);
    exr_finish(&ctx);
}

Test(exr, writes_zip_with_the_requested_precision_and_names)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 3, 3, 2), SOL_OK);
    make_folder();
    cr_assert_eq(sol_exr_write(in_folder("half.exr"), &image, 1), SOL_OK);
    cr_assert_eq(sol_exr_write(in_folder("float.exr"), &image, 0), SOL_OK);
    expect_stored(in_folder("half.exr"), EXR_PIXEL_HALF, 2);
    expect_stored(in_folder("float.exr"), EXR_PIXEL_FLOAT, 2);
    const crafted_channel ya[] = {{"Y", EXR_PIXEL_HALF, 1}, {"A", EXR_PIXEL_HALF, 1}};
    craft(in_folder("other.exr"), ya, 2, box(0, 0, 2, 2), 0); /* and a crafted Y/A file reads as 2 channels */
    sol_image back = {0};
    cr_assert_eq(sol_exr_read(in_folder("other.exr"), &back), SOL_OK);
    cr_assert_eq(back.channels, 2);
    sol_image_free(&back);
    sol_image_free(&image);
    remove_folder((const char *const[]){"half.exr", "float.exr", "other.exr"}, 3);
}

/* The library never prints, even when the core has something to complain about. */
Test(exr, failures_print_nothing, .init = cr_redirect_stderr)
{
    const crafted_channel rgb[] = {{"R", EXR_PIXEL_HALF, 1}, {"G", EXR_PIXEL_HALF, 1}, {"B", EXR_PIXEL_HALF, 1}};
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, 2, 2, 3), SOL_OK);
    make_folder();
    FILE *f = fopen(in_folder("junk.exr"), "wb");
    fputs("v/1\x01 not an OpenEXR file at all", f);
    fclose(f);
    craft(in_folder("tiled.exr"), rgb, 3, box(0, 0, 8, 8), 1);
    expect_refused(in_folder("junk.exr"), SOL_ERR_FORMAT);
    expect_refused(in_folder("tiled.exr"), SOL_ERR_FORMAT);
    expect_refused("/nonexistent/x.exr", SOL_ERR_IO);
    cr_assert_eq(sol_exr_write("/nonexistent/dir/x.exr", &image, 0), SOL_ERR_IO);
    sol_image_free(&image);
    remove_folder((const char *const[]){"junk.exr", "tiled.exr"}, 2);
    fflush(stderr);
    cr_assert_stderr_eq_str("");
}
