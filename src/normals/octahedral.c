/* octahedral.c - claim S5: octahedral normal encoding in 12:12 bits (Cigolle, Donow, Evangelakos,
 * Mara, McGuire, Meyer, "A Survey of Efficient Representations for Independent Unit Vectors",
 * JCGT 3(2), 2014; Narkowicz's notes). Each coordinate is a 12-bit SNORM value
 * round(clamp(u,-1,1) * 2047), stored offset by 2047 (codes 0..4094), as in Cigolle et al.'s oct24. */
#include "normals_internal.h"

#define OCT_MAX 2047.0

/* The lower half's fold across the diagonals (its own inverse): (x, y) -> ((1-|y|) sgn x, (1-|x|) sgn y). */
static void oct_fold(double *x, double *y)
{
    double fx = (1.0 - fabs(*y)) * sol_normals_sign(*x), fy = (1.0 - fabs(*x)) * sol_normals_sign(*y);
    *x = fx;
    *y = fy;
}

/* Projects a unit vector onto the octahedron |x|+|y|+|z| = 1 and unfolds it to [-1,1]^2. */
static void oct_project(const double n[3], double p[2])
{
    double s = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
    double x = n[0] / s, y = n[1] / s;
    if (n[2] < 0.0) /* lower half */
        oct_fold(&x, &y);
    p[0] = x;
    p[1] = y;
}

static void oct_unproject(double x, double y, double n[3])
{
    double z = 1.0 - fabs(x) - fabs(y);
    if (z < 0.0)
        oct_fold(&x, &y);
    double v[3] = {x, y, z};
    double len = sqrt(sol_dot3(v, v)); /* >= 1/sqrt(3) on the octahedron */
    for (int i = 0; i < 3; ++i)
        n[i] = v[i] / len;
}

static uint32_t oct_pack(int cx, int cy)
{
    return (uint32_t)(cx + 2047) | ((uint32_t)(cy + 2047) << 12);
}

void sol_normals_decode_octahedral(uint32_t code, double n[3])
{
    int cx = (int)(code & 4095u) - 2047, cy = (int)(code >> 12) - 2047;
    /* code 4095 (outside the SNORM range) clamps to +1, like a GPU's SNORM read */
    double x = cx > 2047 ? 1.0 : cx / OCT_MAX, y = cy > 2047 ? 1.0 : cy / OCT_MAX;
    oct_unproject(x, y, n);
}

uint32_t sol_normals_encode_octahedral(const double unit[3], int precise)
{
    double p[2];
    oct_project(unit, p);
    double gx = p[0] * OCT_MAX, gy = p[1] * OCT_MAX;
    if (!precise)
        return oct_pack((int)floor(gx + 0.5), (int)floor(gy + 0.5));
    /* Cigolle et al.'s precise variant: the best of the four surrounding codes by angle. */
    uint32_t best = 0;
    double best_angle = HUGE_VAL;
    for (int k = 0; k < 4; ++k) {
        int cx = (int)floor(gx) + (k & 1), cy = (int)floor(gy) + (k >> 1);
        if (cx > 2047 || cy > 2047)
            continue;
        double back[3];
        oct_unproject(cx / OCT_MAX, cy / OCT_MAX, back);
        double angle = sol_angle3(unit, back);
        if (angle < best_angle) {
            best_angle = angle;
            best = oct_pack(cx, cy);
        }
    }
    return best;
}
