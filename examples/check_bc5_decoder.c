/* check_bc5_decoder.c - check an engine's BC5 (3Dc) decoder against sol's bit-exact decoder.
 *
 * Build against an installed sol:  cc check_bc5_decoder.c $(pkg-config --cflags --libs sol)
 * Random blocks (both BC4 modes) are decoded by the "engine" (16-bit interpolants, as most GPUs)
 * and compared texel by texel with sol_bc5 at SOL_BC4_INTERP_16BIT. Exit 0 = pass. */
#include <stdio.h>
#include <stdlib.h>

#include <sol/sol.h>

/* The engine's BC4 channel decode of texel t: palette at 16 bits, round(num * 257 / d). */
static uint16_t engine_bc4(const uint8_t b[8], int t)
{
    uint64_t bits = 0;
    for (int i = 0; i < 6; ++i)
        bits |= (uint64_t)b[2 + i] << (8 * i);
    unsigned idx = (unsigned)(bits >> (3 * t)) & 7u, e0 = b[0], e1 = b[1];
    if (idx < 2)
        return (uint16_t)((idx ? e1 : e0) * 257u);
    unsigned d = e0 > e1 ? 7u : 5u;
    if (e0 <= e1 && idx >= 6)
        return idx == 6 ? 0 : 65535;
    unsigned num = ((d + 1u - idx) * e0 + (idx - 1u) * e1) * 257u;
    return (uint16_t)((num + d / 2u) / d);
}

int main(void)
{
    enum { W = 256, H = 256 };
    uint8_t *blocks = malloc(W * H); /* 16 bytes per 4x4 block */
    uint16_t *texels = malloc(sizeof(uint16_t) * 2 * W * H);
    if (!blocks || !texels)
        return 2;
    uint64_t rng = 7;
    for (size_t i = 0; i < W * H; ++i)
        blocks[i] = (uint8_t)sol_rng_next(&rng);
    for (int by = 0; by < H / 4; ++by)
        for (int bx = 0; bx < W / 4; ++bx) {
            const uint8_t *b = blocks + 16 * (by * (W / 4) + bx);
            for (int t = 0; t < 16; ++t) {
                uint16_t *p = texels + 2 * ((4 * by + t / 4) * W + 4 * bx + t % 4);
                p[0] = engine_bc4(b, t);
                p[1] = engine_bc4(b + 8, t);
            }
        }
    sol_check_report r;
    sol_status st = sol_check_bc5_decode(blocks, W, H, SOL_BC4_INTERP_16BIT, texels, 2, 16, 0.0, &r);
    free(blocks);
    free(texels);
    if (st != SOL_OK)
        return 2;
    printf("bc5 decoder: %s, %zu texels, %zu differ, max %g codes\n", r.passed ? "pass" : "FAIL", r.count,
           r.mismatches, r.max);
    return r.passed ? 0 : 1;
}
