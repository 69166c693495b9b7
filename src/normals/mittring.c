/* mittring.c - claim S1: Mittring 2009 ("A bit more deferred - CryEngine 3"), view-space normals
 * in two scalars G = normalize(N.xy) * sqrt(N.z * 0.5 + 0.5), each stored as an UNORM channel of
 * `bits` bits (8 or 12). |G|^2 = (N.z + 1) / 2, so z is recovered from the length of G and the
 * xy direction from its direction; precision gathers at large |G|, i.e. normals facing +z. */
#include "normals_internal.h"

uint32_t sol_normals_encode_mittring(const double unit[3], int bits)
{
    double r = hypot(unit[0], unit[1]);
    double dx = r > 0.0 ? unit[0] / r : 1.0, dy = r > 0.0 ? unit[1] / r : 0.0;
    double len = sqrt(unit[2] * 0.5 + 0.5);
    uint32_t gx = sol_unorm_encode(dx * len * 0.5 + 0.5, bits), gy = sol_unorm_encode(dy * len * 0.5 + 0.5, bits);
    return gx | (gy << bits);
}

void sol_normals_decode_mittring(uint32_t code, int bits, double n[3])
{
    uint32_t mask = (1u << bits) - 1u;
    double gx = sol_unorm_decode(code & mask, bits) * 2.0 - 1.0;
    double gy = sol_unorm_decode((code >> bits) & mask, bits) * 2.0 - 1.0;
    double len2 = gx * gx + gy * gy;
    if (len2 == 0.0) {
        n[0] = 0.0;
        n[1] = 0.0;
        n[2] = -1.0;
        return;
    }
    double z = 2.0 * len2 - 1.0;
    z = z > 1.0 ? 1.0 : z; /* corner codes have |G| > 1 */
    double s = sqrt(1.0 - z * z) / sqrt(len2);
    double v[3] = {gx * s, gy * s, z};
    double l = sqrt(sol_dot3(v, v));
    for (int i = 0; i < 3; ++i)
        n[i] = v[i] / l;
}
