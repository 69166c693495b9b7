/* normal_methods.c - input validation and the method dispatcher of the normals module. */
#include "normals_internal.h"

sol_status sol_normals_unit_input(const double n[3], double unit[3])
{
    if (!n || !unit)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2]))
        return SOL_ERR_NONFINITE;
    double m = sol_normals_max_abs(n);
    if (m == 0.0)
        return SOL_ERR_ZERO_LENGTH;
    /* Dividing by the largest component first keeps the squares away from under/overflow. */
    double s[3] = {n[0] / m, n[1] / m, n[2] / m};
    double len = sqrt(sol_dot3(s, s));
    for (int i = 0; i < 3; ++i)
        unit[i] = s[i] / len + 0.0; /* + 0.0 turns -0.0 into +0.0 */
    return SOL_OK;
}

uint32_t sol_quantize255(double c)
{
    return sol_unorm_encode(c * 0.5 + 0.5, 8); /* talk, appendix A: round(saturate(c*.5+.5)*255) */
}

double sol_dequantize255(uint32_t code)
{
    return (double)code / 255.0 * 2.0 - 1.0;
}

static const struct {
    const char *name;
    int bits;
} method_info[SOL_NORMAL_METHOD_COUNT] = {
    [SOL_NORMAL_XYZ_NORMALIZED] = {"xyz-normalized", 24},
    [SOL_NORMAL_XYZ_MAX_COMPONENT] = {"xyz-max-component", 24},
    [SOL_NORMAL_XYZ_BEST_FIT] = {"best-fit-search", 24},
    [SOL_NORMAL_XYZ_BEST_FIT_FLOAT] = {"best-fit-search-float", 24},
    [SOL_NORMAL_OCTAHEDRAL_12] = {"octahedral-12", 24},
    [SOL_NORMAL_OCTAHEDRAL_12_PRECISE] = {"octahedral-12-precise", 24},
    [SOL_NORMAL_SPHERICAL_12] = {"spherical-12", 24},
    [SOL_NORMAL_SPHERICAL_Z_12] = {"spherical-z-12", 24},
    [SOL_NORMAL_MITTRING_12] = {"mittring-12", 24},
    [SOL_NORMAL_MITTRING_8] = {"mittring-8", 16},
};

static int method_valid(sol_normal_method method)
{
    return (int)method >= 0 && method < SOL_NORMAL_METHOD_COUNT;
}

const char *sol_normal_method_name(sol_normal_method method)
{
    return method_valid(method) ? method_info[method].name : "unknown";
}

int sol_normal_method_bits(sol_normal_method method)
{
    return method_valid(method) ? method_info[method].bits : 0;
}

sol_status sol_normal_encode(sol_normal_method method, const double n[3], uint32_t *code)
{
    if (!n || !code)
        return SOL_ERR_NULL_ARG;
    if (!method_valid(method))
        return SOL_ERR_INVALID_ARG;
    double u[3];
    sol_status st = sol_normals_unit_input(n, u);
    if (st != SOL_OK)
        return st;
    double t;
    switch (method) {
    case SOL_NORMAL_XYZ_NORMALIZED: *code = sol_normals_encode_xyz(u); break;
    case SOL_NORMAL_XYZ_MAX_COMPONENT: *code = sol_normals_encode_max_component(u); break;
    case SOL_NORMAL_XYZ_BEST_FIT: *code = sol_normals_encode_best_fit(u, &t); break;
    case SOL_NORMAL_XYZ_BEST_FIT_FLOAT: *code = sol_normals_encode_best_fit_float(u); break;
    case SOL_NORMAL_OCTAHEDRAL_12: *code = sol_normals_encode_octahedral(u, 0); break;
    case SOL_NORMAL_OCTAHEDRAL_12_PRECISE: *code = sol_normals_encode_octahedral(u, 1); break;
    case SOL_NORMAL_SPHERICAL_12: *code = sol_normals_encode_spherical(u); break;
    case SOL_NORMAL_SPHERICAL_Z_12: *code = sol_normals_encode_spherical_z(u); break;
    case SOL_NORMAL_MITTRING_12: *code = sol_normals_encode_mittring(u, 12); break;
    case SOL_NORMAL_MITTRING_8: *code = sol_normals_encode_mittring(u, 8); break;
    default: return SOL_ERR_INVALID_ARG;
    }
    return SOL_OK;
}

sol_status sol_normal_decode(sol_normal_method method, uint32_t code, double n[3])
{
    if (!n)
        return SOL_ERR_NULL_ARG;
    if (!method_valid(method) || code >> method_info[method].bits)
        return SOL_ERR_INVALID_ARG;
    switch (method) {
    case SOL_NORMAL_XYZ_NORMALIZED:
    case SOL_NORMAL_XYZ_MAX_COMPONENT:
    case SOL_NORMAL_XYZ_BEST_FIT:
    case SOL_NORMAL_XYZ_BEST_FIT_FLOAT: sol_normals_decode_xyz(code, n); break;
    case SOL_NORMAL_OCTAHEDRAL_12:
    case SOL_NORMAL_OCTAHEDRAL_12_PRECISE: sol_normals_decode_octahedral(code, n); break;
    case SOL_NORMAL_SPHERICAL_12: sol_normals_decode_spherical(code, n); break;
    case SOL_NORMAL_SPHERICAL_Z_12: sol_normals_decode_spherical_z(code, n); break;
    case SOL_NORMAL_MITTRING_12: sol_normals_decode_mittring(code, 12, n); break;
    case SOL_NORMAL_MITTRING_8: sol_normals_decode_mittring(code, 8, n); break;
    default: return SOL_ERR_INVALID_ARG;
    }
    return SOL_OK;
}
