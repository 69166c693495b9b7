/* xyz_normalized.c - claim D3: the classic G-buffer normal, normalized XYZ in 8:8:8 with the talk's
 * quantizer; also the decoder every XYZ method shares (one normalization, talk's "reconstruction
 * is just a normalization"). */
#include "normals_internal.h"

uint32_t sol_normals_encode_xyz(const double unit[3])
{
    return sol_normals_quantize3(unit);
}

void sol_normals_decode_xyz(uint32_t code, double n[3])
{
    double v[3];
    for (int i = 0; i < 3; ++i)
        v[i] = sol_dequantize255((code >> (8 * i)) & 255u);
    double len = sqrt(sol_dot3(v, v)); /* >= sqrt(3)/255: every channel is an odd multiple of 1/255 */
    for (int i = 0; i < 3; ++i)
        n[i] = v[i] / len;
}
