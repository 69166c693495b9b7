/* make_seeds.c - writes the small seed files of tests/fuzz/corpus/{png,exr}/ (not part of the
 * build; the seeds are committed). Each seed is a tiny valid file of one layout the readers
 * accept, so the fuzzer starts from every decoder path: PNG colour types, bit depths, palette,
 * tRNS, Adam7; EXR channel sets, half/float/uint, every scanline compression the 3.1 core writes (not DWA).
 *   cc -std=c11 -D_DEFAULT_SOURCE -I/usr/include/OpenEXR -I/usr/include/Imath \
 *      tests/fuzz/make_seeds.c -o /tmp/make_seeds -lpng -lOpenEXRCore-3_1 && /tmp/make_seeds tests/fuzz/corpus */
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

static int write_png(const char *dir, const char *name, int w, int h, int color, int depth, int interlace, int trns)
{
    char path[512];
    snprintf(path, sizeof path, "%s/png/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return 1;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        fclose(f);
        return 1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color, interlace, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        png_color palette[4] = {{0, 0, 0}, {255, 0, 0}, {0, 255, 0}, {0, 0, 255}};
        png_set_PLTE(png, info, palette, 4);
    }
    if (trns) {
        png_byte alpha[4] = {0, 128, 255, 64};
        png_color_16 key = {0, 1, 1, 1, 1};
        png_set_tRNS(png, info, alpha, color == PNG_COLOR_TYPE_PALETTE ? 4 : 0, &key);
    }
    png_write_info(png, info);
    int passes = png_set_interlace_handling(png);
    unsigned char row[256];
    for (int p = 0; p < passes; ++p)
        for (int y = 0; y < h; ++y) {
            for (size_t i = 0; i < sizeof row; ++i)
                row[i] = (unsigned char)((i * 37 + (size_t)y * 11) & (color != PNG_COLOR_TYPE_PALETTE ? 0xff : depth == 8 ? 0x03 : 0x33));
            png_write_row(png, row);
        }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return fclose(f) != 0;
}

static int write_exr(const char *dir, const char *name, const char *const *channels, int count, exr_pixel_type_t type,
                     exr_compression_t compression, int w, int h)
{
    char path[512];
    snprintf(path, sizeof path, "%s/exr/%s", dir, name);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx;
    int part;
    if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS)
        return 1;
    exr_result_t rv = exr_add_part(ctx, "main", EXR_STORAGE_SCANLINE, &part);
    if (!rv)
        rv = exr_initialize_required_attr_simple(ctx, part, w, h, compression);
    for (int c = 0; !rv && c < count; ++c)
        rv = exr_add_channel(ctx, part, channels[c], type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (!rv)
        rv = exr_write_header(ctx);
    int32_t lines = 1;
    exr_get_scanlines_per_chunk(ctx, part, &lines);
    static uint8_t values[4 * 64 * 64 * 8];
    for (size_t i = 0; i < sizeof values; ++i)
        values[i] = (uint8_t)(i * 7 % 61); /* small finite halves and floats */
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int started = 0;
    for (int y = 0; !rv && y < h; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctx, part, y, &chunk);
        if (!rv)
            rv = started ? exr_encoding_update(ctx, part, &chunk, &enc) : exr_encoding_initialize(ctx, part, &chunk, &enc);
        started = 1;
        int bpe = type == EXR_PIXEL_HALF ? 2 : 4;
        for (int c = 0; !rv && c < enc.channel_count; ++c) {
            enc.channels[c].encode_from_ptr = values;
            enc.channels[c].user_pixel_stride = bpe;
            enc.channels[c].user_line_stride = bpe * w;
            enc.channels[c].user_data_type = type;
            enc.channels[c].user_bytes_per_element = (int16_t)bpe;
        }
        if (!rv)
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
        if (!rv)
            rv = exr_encoding_run(ctx, part, &enc);
    }
    if (started)
        exr_encoding_destroy(ctx, &enc);
    return (exr_finish(&ctx) != EXR_ERR_SUCCESS) | (rv != EXR_ERR_SUCCESS);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "tests/fuzz/corpus";
    int bad = 0;
    bad |= write_png(dir, "gray1.png", 9, 5, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE, 0);
    bad |= write_png(dir, "gray4_trns.png", 7, 3, PNG_COLOR_TYPE_GRAY, 4, PNG_INTERLACE_NONE, 1);
    bad |= write_png(dir, "gray16_adam7.png", 11, 9, PNG_COLOR_TYPE_GRAY, 16, PNG_INTERLACE_ADAM7, 0);
    bad |= write_png(dir, "gray_alpha8.png", 5, 4, PNG_COLOR_TYPE_GRAY_ALPHA, 8, PNG_INTERLACE_NONE, 0);
    bad |= write_png(dir, "rgb8_adam7.png", 10, 10, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_ADAM7, 0);
    bad |= write_png(dir, "rgb16_trns.png", 4, 4, PNG_COLOR_TYPE_RGB, 16, PNG_INTERLACE_NONE, 1);
    bad |= write_png(dir, "rgba16.png", 3, 6, PNG_COLOR_TYPE_RGB_ALPHA, 16, PNG_INTERLACE_NONE, 0);
    bad |= write_png(dir, "palette2_trns.png", 8, 8, PNG_COLOR_TYPE_PALETTE, 2, PNG_INTERLACE_NONE, 1);
    bad |= write_png(dir, "palette8_adam7.png", 12, 7, PNG_COLOR_TYPE_PALETTE, 8, PNG_INTERLACE_ADAM7, 0);
    static const char *const y[] = {"Y"}, *const ya[] = {"A", "Y"}, *const rgb[] = {"B", "G", "R"},
                             *const rgba[] = {"A", "B", "G", "R"}, *const odd[] = {"R", "G", "Z"};
    bad |= write_exr(dir, "y_half_none.exr", y, 1, EXR_PIXEL_HALF, EXR_COMPRESSION_NONE, 5, 3);
    bad |= write_exr(dir, "ya_float_rle.exr", ya, 2, EXR_PIXEL_FLOAT, EXR_COMPRESSION_RLE, 6, 4);
    bad |= write_exr(dir, "rgb_half_zips.exr", rgb, 3, EXR_PIXEL_HALF, EXR_COMPRESSION_ZIPS, 4, 4);
    bad |= write_exr(dir, "rgba_half_zip.exr", rgba, 4, EXR_PIXEL_HALF, EXR_COMPRESSION_ZIP, 8, 20);
    bad |= write_exr(dir, "rgba_half_piz.exr", rgba, 4, EXR_PIXEL_HALF, EXR_COMPRESSION_PIZ, 8, 40);
    bad |= write_exr(dir, "rgb_float_pxr24.exr", rgb, 3, EXR_PIXEL_FLOAT, EXR_COMPRESSION_PXR24, 6, 18);
    bad |= write_exr(dir, "rgb_half_b44.exr", rgb, 3, EXR_PIXEL_HALF, EXR_COMPRESSION_B44, 8, 8);
    bad |= write_exr(dir, "rgba_half_b44a.exr", rgba, 4, EXR_PIXEL_HALF, EXR_COMPRESSION_B44A, 8, 8);
    bad |= write_exr(dir, "y_uint_none.exr", y, 1, EXR_PIXEL_UINT, EXR_COMPRESSION_NONE, 3, 3);
    bad |= write_exr(dir, "no_layout_half.exr", odd, 3, EXR_PIXEL_HALF, EXR_COMPRESSION_NONE, 2, 2);
    if (bad)
        fprintf(stderr, "make_seeds: some seeds could not be written\n");
    return bad;
}
