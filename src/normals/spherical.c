/* spherical.c - claim S5's baselines: spherical coordinates in 12:12 bits. theta in [0, pi] uses
 * 4096 levels with both poles exact; phi is periodic, so 4096 steps of 2 pi / 4096. The variant
 * of Narkowicz's notes ("Octahedron normal vector encoding", 2014) stores z instead of theta and
 * phi / pi as a plain UNORM (the seam at phi = +-pi gets two codes). */
#include "normals_internal.h"

uint32_t sol_normals_encode_spherical(const double unit[3])
{
    double theta = atan2(hypot(unit[0], unit[1]), unit[2]); /* accurate near the poles, unlike acos */
    double phi = atan2(unit[1], unit[0]);
    uint32_t ct = (uint32_t)floor(theta / M_PI * 4095.0 + 0.5);
    long cp = (long)floor(phi / (2.0 * M_PI) * 4096.0 + 0.5);
    cp = ((cp % 4096) + 4096) % 4096;
    return ct | ((uint32_t)cp << 12);
}

void sol_normals_decode_spherical(uint32_t code, double n[3])
{
    double theta = (double)(code & 4095u) * M_PI / 4095.0;
    double phi = (double)(code >> 12) * (2.0 * M_PI / 4096.0);
    n[0] = sin(theta) * cos(phi);
    n[1] = sin(theta) * sin(phi);
    n[2] = cos(theta);
}

uint32_t sol_normals_encode_spherical_z(const double unit[3])
{
    double phi = atan2(unit[1], unit[0]);
    return sol_unorm_encode(phi / M_PI * 0.5 + 0.5, 12) | (sol_unorm_encode(unit[2] * 0.5 + 0.5, 12) << 12);
}

void sol_normals_decode_spherical_z(uint32_t code, double n[3])
{
    double phi = (sol_unorm_decode(code & 4095u, 12) * 2.0 - 1.0) * M_PI;
    double z = sol_unorm_decode(code >> 12, 12) * 2.0 - 1.0;
    double r = sqrt(1.0 - z * z); /* |z| <= 1: exact codes 0 and 4095 give -1 and +1 */
    n[0] = r * cos(phi);
    n[1] = r * sin(phi);
    n[2] = z;
}
