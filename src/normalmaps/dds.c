/* dds.c - a minimal .dds writer for BC4 ("ATI1") and BC5 ("ATI2", 3Dc) textures, one mip level,
 * so the encoders' output opens in other tools (DirectDraw Surface header, Microsoft docs). */
#include "sol_normalmaps.h"

#include <stdio.h>
#include <string.h>

static void put32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (uint8_t)(v >> (8 * i));
}

sol_status sol_dds_write_bc(const char *path, const uint8_t *blocks, int width, int height, int channels)
{
    if (!path || !blocks)
        return SOL_ERR_NULL_ARG;
    if (width <= 0 || height <= 0 || width % 4 || height % 4 || (channels != 1 && channels != 2))
        return SOL_ERR_INVALID_ARG;
    const size_t bytes = (size_t)(width / 4) * (size_t)(height / 4) * (channels == 2 ? 16u : 8u);
    if (bytes > UINT32_MAX)
        return SOL_ERR_INVALID_ARG;
    uint8_t h[128] = {0};
    memcpy(h, "DDS ", 4);
    put32(h + 4, 124);                                       /* header size */
    put32(h + 8, 0x1u | 0x2u | 0x4u | 0x1000u | 0x80000u);   /* CAPS HEIGHT WIDTH PIXELFORMAT LINEARSIZE */
    put32(h + 12, (uint32_t)height);
    put32(h + 16, (uint32_t)width);
    put32(h + 20, (uint32_t)bytes);                          /* linear size of the top level */
    put32(h + 28, 1);                                        /* mip levels */
    put32(h + 76, 32);                                       /* pixel format size */
    put32(h + 80, 0x4u);                                     /* DDPF_FOURCC */
    memcpy(h + 84, channels == 2 ? "ATI2" : "ATI1", 4);
    put32(h + 108, 0x1000u);                                 /* DDSCAPS_TEXTURE */
    /* a temporary beside `path`, renamed over it only once everything is written (sol_core.h) */
    sol_file_out out;
    sol_status status = sol_file_out_open(&out, path);
    if (status != SOL_OK)
        return status;
    int ok = fwrite(h, 1, sizeof h, out.file) == sizeof h && fwrite(blocks, 1, bytes, out.file) == bytes;
    status = sol_file_out_close(&out, ok);
    return ok ? status : SOL_ERR_IO;
}
