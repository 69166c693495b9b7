/* file_out.c - atomic file output: every writer of sol writes a temporary file beside its target
 * and renames it over the target only once everything was written, flushed and synced, so a
 * failed write (disk full, I/O error, a refused value half-way) never leaves a partial file
 * (rename(2) replaces a name atomically within one file system; POSIX.1-2017, rename). */
#include "sol_core.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Distinguishes the temporaries of several threads of one process; the pid the processes. */
static atomic_uint temp_counter;

/* "<folder of path>/.sol-tmp-<pid>-<n>": short, so a target name near NAME_MAX still works. */
static char *temp_name(const char *path, unsigned n)
{
    const char *slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    char suffix[64];
    int len = snprintf(suffix, sizeof suffix, ".sol-tmp-%ld-%u", (long)getpid(), n);
    if (len < 0 || (size_t)len >= sizeof suffix)
        return NULL;
    char *name = malloc(dir_len + (size_t)len + 1);
    if (!name)
        return NULL;
    memcpy(name, path, dir_len);
    memcpy(name + dir_len, suffix, (size_t)len + 1);
    return name;
}

sol_status sol_file_out_open(sol_file_out *out, const char *path)
{
    if (!out || !path)
        return SOL_ERR_NULL_ARG;
    if (!*path)
        return SOL_ERR_IO;
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* a device or FIFO cannot be replaced by a rename: written in place */
        if (S_ISDIR(st.st_mode))
            return SOL_ERR_IO;
        FILE *file = fopen(path, "wb");
        if (!file)
            return SOL_ERR_IO;
        *out = (sol_file_out){.file = file, .temp_path = NULL, .path = path};
        return SOL_OK;
    }
    for (int attempt = 0; attempt < 100; ++attempt) {
        char *temp = temp_name(path, atomic_fetch_add(&temp_counter, 1u));
        if (!temp)
            return SOL_ERR_NO_MEMORY;
        /* O_EXCL: never follows or reuses someone else's file; 0666 lets umask decide, as fopen */
        int fd = open(temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            int err = errno;
            free(temp);
            if (err == EEXIST)
                continue;
            return SOL_ERR_IO;
        }
        FILE *file = fdopen(fd, "wb");
        if (!file) {
            close(fd);
            unlink(temp);
            free(temp);
            return SOL_ERR_NO_MEMORY;
        }
        *out = (sol_file_out){.file = file, .temp_path = temp, .path = path};
        return SOL_OK;
    }
    return SOL_ERR_IO;
}

sol_status sol_file_out_close(sol_file_out *out, int commit)
{
    if (!out || !out->file)
        return SOL_ERR_NULL_ARG;
    int ok = commit != 0;
    if (ok)
        ok = fflush(out->file) == 0 && !ferror(out->file);
    if (ok && out->temp_path)
        ok = fsync(fileno(out->file)) == 0;
    ok = (fclose(out->file) == 0) && ok;
    if (out->temp_path) {
        if (ok)
            ok = rename(out->temp_path, out->path) == 0;
        if (!ok)
            unlink(out->temp_path);
        free(out->temp_path);
    }
    *out = (sol_file_out){0};
    if (!commit)
        return SOL_OK;
    return ok ? SOL_OK : SOL_ERR_IO;
}
