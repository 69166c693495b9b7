/* fuzz_input.h - hands a fuzz input to a reader that takes a path: the bytes go to an in-memory
 * file (memfd_create, Linux) reached as /proc/self/fd/N, so no disk is touched per run. */
#ifndef SOL_FUZZ_INPUT_H
#define SOL_FUZZ_INPUT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "sol_core.h"

/* Returns the path of a file holding exactly data[0..size), or NULL (then the run is skipped). */
static const char *fuzz_input_path(const uint8_t *data, size_t size)
{
    static int fd = -1;
    static char path[64];
    if (fd < 0) {
        fd = memfd_create("sol_fuzz", 0);
        if (fd < 0)
            return NULL;
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    if (ftruncate(fd, 0) != 0)
        return NULL;
    for (size_t done = 0; done < size;) {
        ssize_t n = pwrite(fd, data + done, size - done, (off_t)done);
        if (n <= 0)
            return NULL;
        done += (size_t)n;
    }
    return path;
}

/* The limits the image readers' targets use: 64 MiB, so that the fuzzer explores formats rather
 * than the machine's memory (the default-limit path is the same code with larger numbers). */
static const sol_read_limits FUZZ_IMAGE_LIMITS = {.max_pixels = 1u << 22, .max_bytes = 64u << 20};

/* Aborts unless a successful read gave a consistent image; every value is read, so that an
 * uninitialised or short buffer shows under the sanitizers. Returns the number of values. */
static size_t fuzz_check_image(const sol_image *image)
{
    if (image->width < 1 || image->height < 1 || image->channels < 1 || image->channels > 4 || !image->data)
        abort();
    size_t count = (size_t)image->width * (size_t)image->height * (size_t)image->channels;
    volatile float sum = 0.0f;
    for (size_t i = 0; i < count; ++i)
        sum += image->data[i];
    (void)sum;
    return count;
}

#endif
