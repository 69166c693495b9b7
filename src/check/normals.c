/* normals.c - sol_check_normals: an engine's G-buffer normal codes against sol_normal_encode
 * (claims D3-D7, S1, S5), with the tie rule and bounds documented in sol_check.h. */
#include "check_internal.h"

#include <math.h>
#include <string.h>

double sol_check_normal_bound_deg(sol_normal_method method)
{
    switch (method) {
    case SOL_NORMAL_XYZ_NORMALIZED: return SOL_CHECK_BOUND_XYZ_NORMALIZED_DEG;
    case SOL_NORMAL_XYZ_MAX_COMPONENT: return SOL_CHECK_BOUND_XYZ_MAX_COMPONENT_DEG;
    case SOL_NORMAL_XYZ_BEST_FIT:
    case SOL_NORMAL_XYZ_BEST_FIT_FLOAT: return SOL_CHECK_BOUND_XYZ_BEST_FIT_DEG;
    case SOL_NORMAL_OCTAHEDRAL_12: return SOL_CHECK_BOUND_OCTAHEDRAL_12_DEG;
    case SOL_NORMAL_OCTAHEDRAL_12_PRECISE: return SOL_CHECK_BOUND_OCTAHEDRAL_12_PRECISE_DEG;
    case SOL_NORMAL_SPHERICAL_12: return SOL_CHECK_BOUND_SPHERICAL_12_DEG;
    case SOL_NORMAL_SPHERICAL_Z_12: return SOL_CHECK_BOUND_SPHERICAL_Z_12_DEG;
    case SOL_NORMAL_MITTRING_12: return SOL_CHECK_BOUND_MITTRING_12_DEG;
    case SOL_NORMAL_MITTRING_8: return SOL_CHECK_BOUND_MITTRING_8_DEG;
    default: return 0.0;
    }
}

/* d scaled to unit length through its largest component (denormal and huge vectors work). */
static void unit3(const double d[3], double u[3])
{
    double m = fmax(fabs(d[0]), fmax(fabs(d[1]), fabs(d[2])));
    double v[3] = {d[0] / m, d[1] / m, d[2] / m};
    double l = sqrt(sol_dot3(v, v));
    for (int c = 0; c < 3; ++c)
        u[c] = v[c] / l;
}

/* Every field of the two codes within one step (fields: 3 x 8 bits for the XYZ methods, else two
 * halves of the method's bits). */
static int neighbours(sol_normal_method method, uint32_t a, uint32_t b)
{
    int three = method <= SOL_NORMAL_XYZ_BEST_FIT_FLOAT;
    int fbits = three ? 8 : sol_normal_method_bits(method) / 2, fields = three ? 3 : 2;
    uint32_t mask = (1u << fbits) - 1u;
    for (int f = 0; f < fields; ++f) {
        long fa = (long)((a >> (f * fbits)) & mask), fb = (long)((b >> (f * fbits)) & mask);
        long d = fa > fb ? fa - fb : fb - fa;
        if (d > 1 && d != (long)mask) /* periodic fields (spherical phi) wrap */
            return 0;
    }
    return (a >> (fields * fbits)) == (b >> (fields * fbits));
}

sol_status sol_check_normals(sol_normal_method method, const double (*dirs)[3], const uint32_t *codes, size_t n,
                             const sol_check_normal_options *options, sol_check_report *report)
{
    if (!dirs || !codes || !report)
        return SOL_ERR_NULL_ARG;
    if (n == 0 || sol_normal_method_bits(method) == 0)
        return SOL_ERR_INVALID_ARG;
    for (size_t i = 0; i < n; ++i) { /* validate first: the report stays untouched on error */
        uint32_t c;
        if (sol_normal_encode(method, dirs[i], &c) != SOL_OK)
            return SOL_ERR_INVALID_ARG;
    }
    const int exact = options && options->exact;
    const double bound = sol_check_normal_bound_deg(method);
    const double deg = 180.0 / M_PI;
    const int bits = sol_normal_method_bits(method);
    check_acc acc;
    check_begin(&acc, "deg", bound);
    for (size_t i = 0; i < n; ++i) {
        uint32_t ref = 0;
        double nref[3], neng[3], u[3];
        unit3(dirs[i], u);
        sol_normal_encode(method, dirs[i], &ref);
        sol_normal_decode(method, ref, nref);
        sol_check_item it;
        memset(&it, 0, sizeof it);
        it.index = i;
        memcpy(it.input, dirs[i], sizeof dirs[i]);
        it.expected[0] = ref;
        it.got[0] = codes[i];
        it.expected[1] = sol_angle3(u, nref) * deg;
        int valid = codes[i] < (1u << bits) && sol_normal_decode(method, codes[i], neng) == SOL_OK;
        it.error = valid ? sol_angle3(u, neng) * deg : INFINITY;
        it.got[1] = it.error;
        int mismatch = codes[i] != ref;
        int failure = mismatch && (exact || !valid || !neighbours(method, ref, codes[i]) || !(it.error <= bound));
        check_add(&acc, &it, mismatch, failure);
    }
    check_end(&acc, report);
    return SOL_OK;
}

/* Edge-case directions: where sign(0), the fold, clamping and normalisation go wrong. */
#define T 1e-6  /* a small tilt */
#define D 0x1p-140 /* a denormal in float (and so in double): a float engine can read it */
static const double edge_normals[][3] = {
    {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
    {-0.0, 0, 1}, {0, -0.0, -1}, {-0.0, -0.0, -1}, {1, -0.0, 0}, {-0.0, 1, 0},
    /* the octahedral fold: z < 0 with x or y = 0, and the diagonals |x| + |y| = 1 at z = 0 */
    {0, 0.6, -0.8}, {0, -0.6, -0.8}, {0.6, 0, -0.8}, {-0.6, 0, -0.8}, {-0.0, 0.6, -0.8}, {0.6, -0.0, -0.8},
    {1, 1, 0}, {1, -1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, 1, -T}, {-1, -1, -T}, {1, 1, T},
    {1, 1, 1}, {-1, -1, -1}, {1, -1, 1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, 1},
    /* near the axes and the poles */
    {T, 0, 1}, {0, T, -1}, {T, T, -1}, {-T, -T, -1}, {1, T, 0}, {1, 0, T}, {-1, 0, -T},
    /* phi's branch cut (atan2 at -x) and the equator */
    {-1, 1e-30, 0}, {-1, -1e-30, 0}, {-1, -0.0, 0.5}, {0.7, 0.7, 1e-9},
    /* denormal and huge lengths, mixed scales (all representable as float) */
    {D, 0, 0}, {0, D, D}, {D, -D, -D}, {1e38, 1e38, -1e38}, {3.4e38, 0, 0}, {1e-38, 1, -1e-38},
    {0.5, 0.5, 0.7071067811865476}, {0.5, -0.5, -0.7071067811865476},
};
#undef T
#undef D

const double (*sol_check_edge_normals(size_t *count))[3]
{
    if (count)
        *count = sizeof edge_normals / sizeof edge_normals[0];
    return edge_normals;
}
