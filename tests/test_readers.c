/* test_readers.c - reliability of sol's file readers and writers (issue 12): the files of
 * tests/data/reliability/ that broke the PNG and EXR readers (leaks when libpng aborts mid-read,
 * header-sized allocations, Adam7), the size-limit policy at its exact edges, errors after the
 * reader has allocated (every truncation of a file), and atomic writers (no partial file, no
 * temporary, the old file kept) under a full disk simulated with RLIMIT_FSIZE.
 *
 * Leaks: every loop of failing reads runs under `make sanitize` (LeakSanitizer reports fail it) and
 * `make valgrind`; in the plain build glibc's mallinfo2 shows the heap not growing. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <openexr.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "sol_core.h"
#include "sol_normalmaps.h"

#define RELIABILITY "tests/data/reliability/"

/* ---- helpers ---- */

/* Bytes the process has allocated from glibc's heap now (0 where that cannot be known, e.g. under
 * ASan, whose allocator glibc does not see: there LeakSanitizer does the job). */
static size_t heap_in_use(void)
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
#else
    return 0;
#endif
}

static char folder[64];

static void make_folder(void)
{
    strcpy(folder, "/tmp/sol_test_readers_XXXXXX");
    cr_assert_not_null(mkdtemp(folder));
}

static const char *in_folder(const char *name)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    return path;
}

/* Number of entries in the folder besides . and .. */
static int folder_entries(void)
{
    DIR *dir = opendir(folder);
    cr_assert_not_null(dir);
    int count = 0;
    for (struct dirent *e; (e = readdir(dir));)
        count += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(dir);
    return count;
}

static void remove_folder(const char *const *names, int count)
{
    for (int i = 0; i < count; ++i)
        unlink(in_folder(names[i]));
    cr_assert_eq(folder_entries(), 0, "a test left a file behind in %s", folder);
    cr_assert_eq(rmdir(folder), 0);
}

static unsigned char *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *data = malloc((size_t)n + 1);
    cr_assert_eq(fread(data, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *size = (size_t)n;
    return data;
}

static void spit(const char *path, const void *data, size_t size)
{
    unlink(path); /* a new file, not a truncated one: ext4 flushes truncate-and-rewrite on close */
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(data, 1, size, f), size);
    cr_assert_eq(fclose(f), 0);
}

/* A noisy image (compresses badly, so its file is large). */
static sol_image noisy_image(int width, int height, int channels)
{
    sol_image image = {0};
    cr_assert_eq(sol_image_alloc(&image, width, height, channels), SOL_OK);
    uint64_t state = 12345;
    for (size_t i = 0; i < (size_t)width * height * channels; ++i)
        image.data[i] = (float)sol_rng_uniform(&state, 0.0, 1.0);
    return image;
}

static const sol_image sentinel = {.width = -7, .height = -7, .channels = -7, .data = (float *)&sentinel};

static void assert_untouched(const sol_image *image)
{
    cr_assert(image->width == -7 && image->height == -7 && image->channels == -7 && image->data == sentinel.data,
              "the output was touched on error");
}

/* ---- PNG: the reliability files ---- */

Test(readers, png_files_libpng_aborts_on_are_format_errors_and_free_everything)
{
    static const char *const files[] = {"leak_on_corrupt_idat_79B.png", "leak_truncated_idat_64x64.png",
                                        "leak_corrupt_deflate_64x64.png"};
    for (int f = 0; f < 3; ++f) {
        char path[256];
        snprintf(path, sizeof path, RELIABILITY "%s", files[f]);
        sol_image image = sentinel;
        int bits = -3;
        cr_assert_eq(sol_png_read(path, &image, &bits), SOL_ERR_FORMAT, "%s", files[f]);
        assert_untouched(&image);
        cr_assert_eq(bits, -3);
        /* the images are freed on libpng's longjmp: 2000 reads leave the heap where it was
         * (the unfixed reader grew it by one 64x64 float image per read, 98 MB here) */
        size_t before = heap_in_use();
        for (int i = 0; i < 2000; ++i)
            cr_assert_eq(sol_png_read(path, &image, NULL), SOL_ERR_FORMAT);
        size_t after = heap_in_use();
        cr_assert(after <= before + 65536, "%s: heap grew by %zu bytes over 2000 failed reads", files[f],
                  after - before);
    }
}

Test(readers, png_header_asking_16_gb_is_refused_by_the_limit)
{
    sol_image image = sentinel;
    int bits = -3;
    cr_assert_eq(sol_png_read(RELIABILITY "alloc_16GB_from_header.png", &image, &bits), SOL_ERR_LIMIT);
    assert_untouched(&image);
    cr_assert_eq(bits, -3);
    /* raising the pixel limit alone is not enough: the bytes limit still holds it back */
    sol_read_limits pixels_only = {.max_pixels = UINT64_MAX};
    cr_assert_eq(sol_png_read_ex(RELIABILITY "alloc_16GB_from_header.png", &pixels_only, &image, NULL), SOL_ERR_LIMIT);
    assert_untouched(&image);
}

Test(readers, adam7_png_decodes_like_its_progressive_twin)
{
    sol_image interlaced = {0}, progressive = {0};
    int bits_i = 0, bits_p = 0;
    cr_assert_eq(sol_png_read(RELIABILITY "adam7_interlaced_16x16_gray.png", &interlaced, &bits_i), SOL_OK);
    cr_assert_eq(sol_png_read(RELIABILITY "same_image_not_interlaced.png", &progressive, &bits_p), SOL_OK);
    cr_assert(interlaced.width == 16 && interlaced.height == 16 && interlaced.channels == 1 && bits_i == 8);
    cr_assert(progressive.width == 16 && progressive.height == 16 && progressive.channels == 1 && bits_p == 8);
    int differ = 0;
    for (int i = 0; i < 256; ++i)
        differ += interlaced.data[i] != progressive.data[i];
    cr_assert_eq(differ, 0, "%d of 256 pixels differ", differ);
    sol_image_free(&interlaced);
    sol_image_free(&progressive);
}

/* ---- PNG: the limit at its exact edges ---- */

Test(readers, png_limits_hold_at_their_exact_edges_and_can_be_raised)
{
    make_folder();
    sol_image image = noisy_image(8, 4, 3), back = sentinel;
    cr_assert_eq(sol_png_write(in_folder("small.png"), &image, 16), SOL_OK);
    /* progressive: 32 pixels, 3 floats each = 384 bytes */
    sol_read_limits exact = {.max_pixels = 32, .max_bytes = 384};
    cr_assert_eq(sol_png_read_ex(in_folder("small.png"), &exact, &back, NULL), SOL_OK);
    sol_image_free(&back);
    back = sentinel;
    sol_read_limits few_pixels = {.max_pixels = 31}, few_bytes = {.max_bytes = 383};
    cr_assert_eq(sol_png_read_ex(in_folder("small.png"), &few_pixels, &back, NULL), SOL_ERR_LIMIT);
    cr_assert_eq(sol_png_read_ex(in_folder("small.png"), &few_bytes, &back, NULL), SOL_ERR_LIMIT);
    assert_untouched(&back);
    /* interlaced 16x16 gray 8-bit: 256 pixels at 4 (float) + 1 (raw) bytes = 1280 bytes */
    sol_read_limits adam7_exact = {.max_bytes = 1280}, adam7_short = {.max_bytes = 1279};
    cr_assert_eq(sol_png_read_ex(RELIABILITY "adam7_interlaced_16x16_gray.png", &adam7_exact, &back, NULL), SOL_OK);
    sol_image_free(&back);
    back = sentinel;
    cr_assert_eq(sol_png_read_ex(RELIABILITY "adam7_interlaced_16x16_gray.png", &adam7_short, &back, NULL),
                 SOL_ERR_LIMIT);
    assert_untouched(&back);
    /* NULL limits are the defaults, as in sol_png_read */
    cr_assert_eq(sol_png_read_ex(in_folder("small.png"), NULL, &back, NULL), SOL_OK);
    sol_image_free(&back);
    sol_image_free(&image);
    remove_folder((const char *const[]){"small.png"}, 1);
}

/* ---- PNG: errors after the reader allocated ---- */

/* Every prefix of a file, and the file with each byte of its first IDAT flipped: OK or FORMAT
 * only, the output untouched on error, an OK read gives the original values, nothing leaks. */
static void cut_and_flip(const char *path, const sol_image *original, size_t idat_end)
{
    size_t size = 0;
    unsigned char *data = slurp(path, &size);
    char *cut_path = strdup(in_folder("cut.png"));
    size_t before = heap_in_use();
    for (size_t n = 0; n < size; ++n) {
        spit(cut_path, data, n);
        sol_image image = sentinel;
        sol_status status = sol_png_read(cut_path, &image, NULL);
        if (n < idat_end)
            cr_assert_eq(status, SOL_ERR_FORMAT, "%s cut to %zu of %zu bytes: %s", path, n, size,
                         sol_status_string(status));
        if (status != SOL_OK) {
            cr_assert_eq(status, SOL_ERR_FORMAT);
            assert_untouched(&image);
            continue;
        }
        for (size_t i = 0; i < (size_t)original->width * original->height * original->channels; ++i)
            cr_assert_eq(image.data[i], original->data[i]);
        sol_image_free(&image);
    }
    for (size_t n = 41; n < idat_end && n < 41 + 200; ++n) {
        data[n] ^= 0x5a;
        spit(cut_path, data, size);
        data[n] ^= 0x5a;
        sol_image image = sentinel;
        cr_assert_eq(sol_png_read(cut_path, &image, NULL), SOL_ERR_FORMAT, "byte %zu flipped", n); /* CRC */
        assert_untouched(&image);
    }
    size_t after = heap_in_use();
    cr_assert(after <= before + 65536, "%s: heap grew by %zu bytes over the failed reads", path, after - before);
    unlink(cut_path);
    free(cut_path);
    free(data);
}

/* End of the IDAT chunks (offset just past the last IDAT's CRC). */
static size_t idat_end(const char *path)
{
    size_t size = 0, end = 0;
    unsigned char *data = slurp(path, &size);
    for (size_t at = 8; at + 12 <= size;) {
        size_t length = (size_t)data[at] << 24 | (size_t)data[at + 1] << 16 | (size_t)data[at + 2] << 8 | data[at + 3];
        if (!memcmp(data + at + 4, "IDAT", 4))
            end = at + 12 + length;
        at += 12 + length;
    }
    free(data);
    cr_assert_gt(end, 0);
    return end;
}

Test(readers, png_errors_after_allocation_free_everything_at_every_truncation)
{
    make_folder();
    sol_image image = noisy_image(24, 16, 4);
    cr_assert_eq(sol_png_write(in_folder("noisy.png"), &image, 16), SOL_OK);
    sol_image original = {0};
    cr_assert_eq(sol_png_read(in_folder("noisy.png"), &original, NULL), SOL_OK);
    cut_and_flip(in_folder("noisy.png"), &original, idat_end(in_folder("noisy.png")));
    sol_image_free(&original);
    cr_assert_eq(sol_png_read(RELIABILITY "adam7_interlaced_16x16_gray.png", &original, NULL), SOL_OK);
    cut_and_flip(RELIABILITY "adam7_interlaced_16x16_gray.png", &original,
                 idat_end(RELIABILITY "adam7_interlaced_16x16_gray.png"));
    sol_image_free(&original);
    sol_image_free(&image);
    remove_folder((const char *const[]){"noisy.png"}, 1);
}

/* ---- EXR ---- */

Test(readers, exr_headers_asking_3_gb_and_48_tb_are_refused_by_the_limit)
{
    sol_image image = sentinel;
    cr_assert_eq(sol_exr_read(RELIABILITY "alloc_3GB_from_header.exr", &image), SOL_ERR_LIMIT);
    cr_assert_eq(sol_exr_read(RELIABILITY "alloc_48TB_from_header.exr", &image), SOL_ERR_LIMIT);
    sol_read_limits pixels_only = {.max_pixels = UINT64_MAX};
    cr_assert_eq(sol_exr_read_ex(RELIABILITY "alloc_48TB_from_header.exr", &pixels_only, &image), SOL_ERR_LIMIT);
    assert_untouched(&image);
}

Test(readers, exr_limits_hold_at_their_exact_edges_and_can_be_raised)
{
    make_folder();
    sol_image image = noisy_image(8, 4, 3), back = sentinel;
    cr_assert_eq(sol_exr_write(in_folder("small.exr"), &image, 1), SOL_OK);
    /* 32 pixels; sol's buffers 8 bytes x 3 channels = 768 bytes; the core's chunk buffers
     * 2 x 3 half channels x 32 pixels (ZIP chunks hold 16 lines, the image 4) = 384 bytes */
    sol_read_limits exact = {.max_pixels = 32, .max_bytes = 768};
    cr_assert_eq(sol_exr_read_ex(in_folder("small.exr"), &exact, &back), SOL_OK);
    cr_assert(back.width == 8 && back.height == 4 && back.channels == 3);
    sol_image_free(&back);
    back = sentinel;
    sol_read_limits few_pixels = {.max_pixels = 31}, few_bytes = {.max_bytes = 767};
    cr_assert_eq(sol_exr_read_ex(in_folder("small.exr"), &few_pixels, &back), SOL_ERR_LIMIT);
    cr_assert_eq(sol_exr_read_ex(in_folder("small.exr"), &few_bytes, &back), SOL_ERR_LIMIT);
    assert_untouched(&back);
    cr_assert_eq(sol_exr_read_ex(in_folder("small.exr"), NULL, &back), SOL_OK);
    sol_image_free(&back);
    sol_image_free(&image);
    remove_folder((const char *const[]){"small.exr"}, 1);
}

/* A 2x2 uncompressed half file with R, G, B and `extra` more channels (all zero). */
static void write_many_channels(const char *path, int extra)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx;
    int part = 0;
    cr_assert_eq(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_add_part(ctx, "main", EXR_STORAGE_SCANLINE, &part), EXR_ERR_SUCCESS);
    cr_assert_eq(exr_initialize_required_attr_simple(ctx, part, 2, 2, EXR_COMPRESSION_NONE), EXR_ERR_SUCCESS);
    for (int c = 0; c < 3 + extra; ++c) {
        char name[16];
        snprintf(name, sizeof name, c < 3 ? (const char *[]){"R", "G", "B"}[c] : "x%04d", c);
        cr_assert_eq(exr_add_channel(ctx, part, name, EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
                     EXR_ERR_SUCCESS);
    }
    cr_assert_eq(exr_write_header(ctx), EXR_ERR_SUCCESS);
    static const uint16_t zeros[4] = {0};
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    for (int y = 0; y < 2; ++y) {
        exr_chunk_info_t chunk;
        cr_assert_eq(exr_write_scanline_chunk_info(ctx, part, y, &chunk), EXR_ERR_SUCCESS);
        cr_assert_eq(y ? exr_encoding_update(ctx, part, &chunk, &enc) : exr_encoding_initialize(ctx, part, &chunk, &enc),
                     EXR_ERR_SUCCESS);
        for (int c = 0; c < enc.channel_count; ++c) {
            enc.channels[c].encode_from_ptr = (const uint8_t *)zeros;
            enc.channels[c].user_pixel_stride = 2;
            enc.channels[c].user_line_stride = 4;
            enc.channels[c].user_data_type = EXR_PIXEL_HALF;
            enc.channels[c].user_bytes_per_element = 2;
        }
        cr_assert_eq(exr_encoding_choose_default_routines(ctx, part, &enc), EXR_ERR_SUCCESS);
        cr_assert_eq(exr_encoding_run(ctx, part, &enc), EXR_ERR_SUCCESS);
    }
    exr_encoding_destroy(ctx, &enc);
    cr_assert_eq(exr_finish(&ctx), EXR_ERR_SUCCESS);
}

Test(readers, exr_channel_count_is_limited)
{
    make_folder();
    sol_image image = sentinel;
    write_many_channels(in_folder("at_limit.exr"), SOL_EXR_MAX_CHANNELS - 3);
    cr_assert_eq(sol_exr_read(in_folder("at_limit.exr"), &image), SOL_OK);
    cr_assert(image.width == 2 && image.height == 2 && image.channels == 3);
    sol_image_free(&image);
    image = sentinel;
    write_many_channels(in_folder("over_limit.exr"), SOL_EXR_MAX_CHANNELS - 2);
    cr_assert_eq(sol_exr_read(in_folder("over_limit.exr"), &image), SOL_ERR_LIMIT);
    assert_untouched(&image);
    remove_folder((const char *const[]){"at_limit.exr", "over_limit.exr"}, 2);
}

Test(readers, exr_errors_after_allocation_free_everything_at_every_truncation)
{
    make_folder();
    sol_image image = noisy_image(16, 40, 4);
    cr_assert_eq(sol_exr_write(in_folder("noisy.exr"), &image, 0), SOL_OK);
    size_t size = 0;
    unsigned char *data = slurp(in_folder("noisy.exr"), &size);
    char *cut_path = strdup(in_folder("cut.exr"));
    size_t before = heap_in_use();
    for (size_t n = 0; n < size; n += 1 + n / 64) {
        spit(cut_path, data, n);
        sol_image back = sentinel;
        cr_assert_eq(sol_exr_read(cut_path, &back), SOL_ERR_FORMAT, "cut to %zu of %zu bytes", n, size);
        assert_untouched(&back);
    }
    size_t after = heap_in_use();
    cr_assert(after <= before + 65536, "heap grew by %zu bytes over the failed reads", after - before);
    free(cut_path);
    free(data);
    sol_image_free(&image);
    remove_folder((const char *const[]){"noisy.exr", "cut.exr"}, 2);
}

/* ---- atomic writers ---- */

static sol_status write_kind(int kind, const char *path, const sol_image *image, const uint8_t *blocks)
{
    switch (kind) {
    case 0:
        return sol_png_write(path, image, 16);
    case 1:
        return sol_exr_write(path, image, 0);
    default:
        return sol_dds_write_bc(path, blocks, image->width, image->height, 2);
    }
}

static const char *const kind_names[3] = {"out.png", "out.exr", "out.dds"};

Test(readers, writers_leave_exactly_their_file_and_replace_an_old_one)
{
    make_folder();
    sol_image image = noisy_image(64, 64, 3);
    uint8_t *blocks = calloc(16 * 16 * 16, 1);
    for (int kind = 0; kind < 3; ++kind) {
        spit(in_folder(kind_names[kind]), "old", 3);
        cr_assert_eq(write_kind(kind, in_folder(kind_names[kind]), &image, blocks), SOL_OK, "%s", kind_names[kind]);
        cr_assert_eq(folder_entries(), kind + 1, "%s: a temporary was left", kind_names[kind]);
        struct stat st;
        cr_assert_eq(stat(in_folder(kind_names[kind]), &st), 0);
        cr_assert_gt(st.st_size, 3, "%s: the old file was not replaced", kind_names[kind]);
        mode_t mask = umask(0);
        umask(mask);
        cr_assert_eq(st.st_mode & 0777, 0666 & ~mask, "%s: not created like fopen (0666 less the umask)",
                     kind_names[kind]);
    }
    sol_image back = {0};
    cr_assert_eq(sol_png_read(in_folder("out.png"), &back, NULL), SOL_OK);
    sol_image_free(&back);
    cr_assert_eq(sol_exr_read(in_folder("out.exr"), &back), SOL_OK);
    for (int i = 0; i < 64 * 64 * 3; ++i)
        cr_assert_eq(back.data[i], image.data[i]);
    sol_image_free(&back);
    free(blocks);
    sol_image_free(&image);
    remove_folder(kind_names, 3);
}

Test(readers, writers_on_a_full_disk_leave_no_file_and_keep_the_old_one)
{
    /* RLIMIT_FSIZE makes writes past 4000 bytes fail with EFBIG, as a full disk fails with ENOSPC;
     * Criterion runs each test in its own process, so the limit ends with the test. */
    make_folder();
    sol_image image = noisy_image(64, 64, 3);
    uint8_t *blocks = malloc(16 * 16 * 16);
    memset(blocks, 0xa5, 16 * 16 * 16);
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = {.rlim_cur = 4000, .rlim_max = RLIM_INFINITY};
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &limit), 0);
    for (int kind = 0; kind < 3; ++kind) {
        cr_assert_eq(write_kind(kind, in_folder(kind_names[kind]), &image, blocks), SOL_ERR_IO, "%s",
                     kind_names[kind]);
        cr_assert_eq(folder_entries(), kind, "%s: a partial file or temporary was left", kind_names[kind]);
        spit(in_folder(kind_names[kind]), "old", 3);
        cr_assert_eq(write_kind(kind, in_folder(kind_names[kind]), &image, blocks), SOL_ERR_IO);
        size_t size = 0;
        unsigned char *kept = slurp(in_folder(kind_names[kind]), &size);
        cr_assert(size == 3 && !memcmp(kept, "old", 3), "%s: the old file was damaged", kind_names[kind]);
        free(kept);
        cr_assert_eq(folder_entries(), kind + 1);
    }
    free(blocks);
    sol_image_free(&image);
    remove_folder(kind_names, 3);
}

Test(readers, writers_refuse_missing_folders_directories_and_a_full_device)
{
    make_folder();
    sol_image image = noisy_image(8, 8, 3);
    uint8_t blocks[4 * 16] = {0};
    for (int kind = 0; kind < 3; ++kind) {
        cr_assert_eq(write_kind(kind, "/nonexistent/folder/x", &image, blocks), SOL_ERR_IO);
        cr_assert_eq(write_kind(kind, folder, &image, blocks), SOL_ERR_IO); /* a directory */
        cr_assert_eq(write_kind(kind, "", &image, blocks), SOL_ERR_IO);
        /* a device is written in place (a rename cannot replace it): ENOSPC is an I/O error. The
         * test's own copy of /dev/full (char 1,7; mknod needs root, else this part is skipped):
         * a writer that removed or replaced its target on error must not take the system's. */
        struct stat st;
        if (mknod(in_folder("full"), S_IFCHR | 0666, makedev(1, 7)) == 0 || errno == EEXIST) {
            cr_assert_eq(write_kind(kind, in_folder("full"), &image, blocks), SOL_ERR_IO, "%s", kind_names[kind]);
            cr_assert(stat(in_folder("full"), &st) == 0 && S_ISCHR(st.st_mode), "%s replaced the device",
                      kind_names[kind]);
            cr_assert_eq(folder_entries(), 1, "%s left a temporary", kind_names[kind]);
        }
    }
    sol_image_free(&image);
    remove_folder((const char *const[]){"full"}, 1);
}

Test(readers, file_out_opens_commits_and_discards)
{
    make_folder();
    sol_file_out out = {.file = stdout}, untouched = out;
    cr_assert_eq(sol_file_out_open(NULL, "x"), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_file_out_open(&out, NULL), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_file_out_open(&out, "/nonexistent/folder/x"), SOL_ERR_IO);
    cr_assert(!memcmp(&out, &untouched, sizeof out), "the output was touched on error");
    /* committed: the temporary becomes the file */
    cr_assert_eq(sol_file_out_open(&out, in_folder("a.txt")), SOL_OK);
    cr_assert_not_null(out.temp_path);
    cr_assert_not_null(strstr(out.temp_path, folder), "the temporary is beside its target");
    cr_assert_eq(access(in_folder("a.txt"), F_OK), -1, "nothing exists at the target before the commit");
    cr_assert_geq(fputs("hello", out.file), 0);
    cr_assert_eq(sol_file_out_close(&out, 1), SOL_OK);
    cr_assert_null(out.file);
    size_t size = 0;
    unsigned char *data = slurp(in_folder("a.txt"), &size);
    cr_assert(size == 5 && !memcmp(data, "hello", 5));
    free(data);
    /* discarded: the old file stays, the temporary goes */
    cr_assert_eq(sol_file_out_open(&out, in_folder("a.txt")), SOL_OK);
    fputs("other", out.file);
    cr_assert_eq(sol_file_out_close(&out, 0), SOL_OK);
    data = slurp(in_folder("a.txt"), &size);
    cr_assert(size == 5 && !memcmp(data, "hello", 5));
    free(data);
    cr_assert_eq(folder_entries(), 1);
    /* closing twice, or a zeroed struct, is a NULL argument */
    cr_assert_eq(sol_file_out_close(&out, 1), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_file_out_close(NULL, 1), SOL_ERR_NULL_ARG);
    remove_folder((const char *const[]){"a.txt"}, 1);
}

Test(readers, read_ex_refuses_null_arguments_and_accepts_the_largest_limits)
{
    sol_image image = sentinel;
    int bits = -3;
    const sol_read_limits huge = {.max_pixels = UINT64_MAX, .max_bytes = UINT64_MAX};
    cr_assert_eq(sol_png_read_ex(NULL, &huge, &image, &bits), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_png_read_ex(RELIABILITY "same_image_not_interlaced.png", &huge, NULL, &bits), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_exr_read_ex(NULL, &huge, &image), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_exr_read_ex(RELIABILITY "alloc_3GB_from_header.exr", &huge, NULL), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_png_read_ex("/nonexistent/x.png", &huge, &image, &bits), SOL_ERR_IO);
    cr_assert_eq(sol_exr_read_ex("/nonexistent/x.exr", &huge, &image), SOL_ERR_IO);
    assert_untouched(&image);
    cr_assert_eq(bits, -3);
    cr_assert_eq(sol_png_read_ex(RELIABILITY "same_image_not_interlaced.png", &huge, &image, &bits), SOL_OK);
    cr_assert(image.width == 16 && bits == 8);
    sol_image_free(&image);
}
