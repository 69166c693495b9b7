/* dds_read.c - reads the top level of a BC1/BC4/BC5 .dds file (DirectDraw Surface: Microsoft's
 * "DDS_HEADER" and "DDS_HEADER_DXT10" documentation), bounded by sol_read_limits. */
#include "sol_core.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { DDS_HEADER = 128, DDS_DX10 = 20, DDPF_FOURCC = 0x4, DDSCAPS2_CUBEMAP = 0x200, DDSCAPS2_VOLUME = 0x200000 };

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static sol_status fail(sol_status st, const char *why, const char **problem)
{
    if (problem)
        *problem = why;
    return st;
}

sol_status sol_dds_parse(const uint8_t *data, size_t size, const sol_read_limits *limits, sol_dds *out,
                         const char **problem)
{
    if (!data || !out)
        return SOL_ERR_NULL_ARG;
    if (size < 4 || memcmp(data, "DDS ", 4))
        return fail(SOL_ERR_FORMAT, "not a DDS file (no 'DDS ' magic)", problem);
    if (size < DDS_HEADER)
        return fail(SOL_ERR_FORMAT, "truncated DDS header (fewer than 128 bytes)", problem);
    if (get32(data + 4) != 124 || get32(data + 76) != 32)
        return fail(SOL_ERR_FORMAT, "DDS header or pixel-format size is not 124/32", problem);
    uint32_t height = get32(data + 12), width = get32(data + 16);
    if (get32(data + 112) & (DDSCAPS2_CUBEMAP | DDSCAPS2_VOLUME))
        return fail(SOL_ERR_UNSUPPORTED, "DDS cube maps and volumes are not supported", problem);
    if (!(get32(data + 80) & DDPF_FOURCC))
        return fail(SOL_ERR_UNSUPPORTED, "DDS pixel format has no FourCC (uncompressed data)", problem);
    const uint8_t *cc = data + 84;
    size_t offset = DDS_HEADER;
    sol_dds_format format;
    if (!memcmp(cc, "DXT1", 4))
        format = SOL_DDS_BC1;
    else if (!memcmp(cc, "ATI1", 4) || !memcmp(cc, "BC4U", 4))
        format = SOL_DDS_BC4;
    else if (!memcmp(cc, "ATI2", 4) || !memcmp(cc, "BC5U", 4))
        format = SOL_DDS_BC5;
    else if (!memcmp(cc, "DX10", 4)) {
        if (size < DDS_HEADER + DDS_DX10)
            return fail(SOL_ERR_FORMAT, "truncated DDS DX10 header extension", problem);
        uint32_t dxgi = get32(data + DDS_HEADER), dim = get32(data + DDS_HEADER + 4);
        uint32_t array = get32(data + DDS_HEADER + 12);
        if (dim != 3 || array > 1)
            return fail(SOL_ERR_UNSUPPORTED, "DDS DX10 texture is not a single 2D texture", problem);
        if (dxgi == 71 || dxgi == 72)
            format = SOL_DDS_BC1;
        else if (dxgi == 80)
            format = SOL_DDS_BC4;
        else if (dxgi == 83)
            format = SOL_DDS_BC5;
        else
            return fail(SOL_ERR_UNSUPPORTED, "DDS DXGI format is not BC1, BC4_UNORM or BC5_UNORM", problem);
        offset += DDS_DX10;
    } else
        return fail(SOL_ERR_UNSUPPORTED, "DDS FourCC is not DXT1, ATI1/BC4U, ATI2/BC5U or DX10", problem);
    if (width == 0 || height == 0 || width > INT32_MAX || height > INT32_MAX)
        return fail(SOL_ERR_FORMAT, "DDS width or height is zero or too large", problem);
    sol_status st = sol_read_limits_check(limits, width, height, 1, 4);
    if (st != SOL_OK)
        return fail(st, "DDS size is beyond the read limits", problem);
    size_t bw = (width + 3u) / 4u, bh = (height + 3u) / 4u, blocks, bytes;
    if (!sol_size_mul(&blocks, bw, bh) || !sol_size_mul(&bytes, blocks, format == SOL_DDS_BC5 ? 16u : 8u))
        return fail(SOL_ERR_LIMIT, "DDS size overflows", problem);
    if (size - offset < bytes)
        return fail(SOL_ERR_FORMAT, "truncated DDS: fewer block bytes than width x height needs", problem);
    uint8_t *copy = malloc(bytes);
    if (!copy)
        return SOL_ERR_NO_MEMORY;
    memcpy(copy, data + offset, bytes);
    out->format = format;
    out->width = (int)width;
    out->height = (int)height;
    out->size = bytes;
    out->blocks = copy;
    return SOL_OK;
}

sol_status sol_file_read_all(const char *path, uint64_t max_bytes, uint8_t **data, size_t *size)
{
    if (!path || !data || !size)
        return SOL_ERR_NULL_ARG;
    uint64_t cap = max_bytes ? max_bytes : SOL_READ_MAX_BYTES_DEFAULT;
    FILE *f = fopen(path, "rb");
    if (!f)
        return SOL_ERR_IO;
    size_t used = 0, alloc = 0;
    uint8_t *buf = NULL;
    sol_status st = SOL_OK;
    for (;;) {
        if (alloc - used < 2) { /* room for at least one byte and the NUL */
            size_t grow = alloc ? alloc : 65536;
            uint8_t *nb = alloc > SIZE_MAX / 2 ? NULL : realloc(buf, alloc + grow);
            if (!nb) {
                st = SOL_ERR_NO_MEMORY;
                break;
            }
            buf = nb;
            alloc += grow;
        }
        size_t got = fread(buf + used, 1, alloc - used - 1, f);
        used += got;
        if (used > cap) {
            st = SOL_ERR_LIMIT;
            break;
        }
        if (got == 0) {
            if (ferror(f))
                st = SOL_ERR_IO;
            break;
        }
    }
    fclose(f);
    if (st != SOL_OK) {
        free(buf);
        return st;
    }
    buf[used] = 0;
    *data = buf;
    *size = used;
    return SOL_OK;
}

sol_status sol_dds_read(const char *path, const sol_read_limits *limits, sol_dds *out, const char **problem)
{
    if (!path || !out)
        return SOL_ERR_NULL_ARG;
    uint64_t max = limits && limits->max_bytes ? limits->max_bytes : SOL_READ_MAX_BYTES_DEFAULT;
    uint8_t *data;
    size_t size;
    sol_status st = sol_file_read_all(path, max + DDS_HEADER + DDS_DX10, &data, &size);
    if (st != SOL_OK)
        return fail(st, st == SOL_ERR_IO ? "cannot read the file" : "file is beyond the read limits", problem);
    st = sol_dds_parse(data, size, limits, out, problem);
    free(data);
    return st;
}

void sol_dds_free(sol_dds *dds)
{
    if (!dds)
        return;
    free(dds->blocks);
    memset(dds, 0, sizeof *dds);
}
