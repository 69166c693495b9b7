/* hemicube.c - S7: texel weights of a hemicube and of Narkowicz's single wide plane (seed 001,
 * "Lightmapping in Anomaly 2 mobile"). The solid angle of a texel is the ElementArea formula of his
 * note (after Driscoll 2012, "Cubemap texel solid angle"); his weight multiplies it by the cosine at
 * the texel centre. The exact projected solid angle, integral of cos(theta) d(omega), has the closed
 * forms below, so the centre-cosine approximation can be measured rather than assumed. */
#include "sol_lighting.h"

double sol_plane_element_area(double x, double y)
{
    /* Both atan2 arguments divided by m >= 1 so that x*y and x^2 cannot overflow. */
    double m = fmax(1.0, fmax(fabs(x), fabs(y)));
    double a = x / m, b = y / m, c = 1.0 / m;
    return atan2(x * b, sqrt(a * a + b * b + c * c));
}

/* On the plane z = 1: d(omega) = dA / r^3 and cos(theta) = 1 / r, r^2 = 1 + u^2 + v^2, so the
 * projected solid angle is the integral of dA / r^4; integrating v then u gives the closed form. */
double sol_plane_cosine_area(double x, double y)
{
    double sx = hypot(1.0, x), sy = hypot(1.0, y);
    return x / (2.0 * sx) * atan(y / sx) + y / (2.0 * sy) * atan(x / sy);
}

/* On the side face x = 1 at height z: d(omega) = dA / r^3, cos(theta) = z / r; the z integral of
 * z / (a + z^2)^2 is -1 / (2 (a + z^2)), then the u integral of 1 / (b^2 + u^2) is atan(u/b)/b. */
double sol_side_cosine_area(double u, double z0, double z1)
{
    double b0 = hypot(1.0, z0), b1 = hypot(1.0, z1);
    return 0.5 * (atan(u / b0) / b0 - atan(u / b1) / b1);
}

/* Inclusion-exclusion of a corner function over the rectangle [x0,x1] x [y0,y1]. */
static double rectangle(double (*corner)(double, double), double x0, double y0, double x1, double y1)
{
    return corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
}

static sol_texel_weight front_texel(double x0, double y0, double x1, double y1)
{
    double xc = 0.5 * (x0 + x1), yc = 0.5 * (y0 + y1);
    sol_texel_weight w;
    w.solid_angle = rectangle(sol_plane_element_area, x0, y0, x1, y1);
    w.cosine_at_centre = w.solid_angle / sqrt(1.0 + xc * xc + yc * yc);
    w.cosine_exact = rectangle(sol_plane_cosine_area, x0, y0, x1, y1);
    return w;
}

sol_status sol_plane_weights(int size, double half_extent, sol_texel_weight *weights)
{
    if (!weights)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(half_extent))
        return SOL_ERR_NONFINITE;
    if (size < 1 || size > 65536 || !(half_extent > 0.0))
        return SOL_ERR_INVALID_ARG;
    const double step = 2.0 * half_extent / size;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            double x0 = -half_extent + step * i, y0 = -half_extent + step * j;
            weights[(size_t)j * (size_t)size + (size_t)i] = front_texel(x0, y0, x0 + step, y0 + step);
        }
    return SOL_OK;
}

sol_status sol_hemicube_weight_sums(int size, double *solid_angle, double *cosine_at_centre, double *cosine_exact)
{
    if (!solid_angle || !cosine_at_centre || !cosine_exact)
        return SOL_ERR_NULL_ARG;
    if (size < 2 || size > 65536 || size % 2)
        return SOL_ERR_INVALID_ARG;
    const double step = 2.0 / size;
    double front[3] = {0, 0, 0}, side[3] = {0, 0, 0};
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            sol_texel_weight w = front_texel(-1.0 + step * i, -1.0 + step * j, -1.0 + step * (i + 1),
                                             -1.0 + step * (j + 1));
            front[0] += w.solid_angle;
            front[1] += w.cosine_at_centre;
            front[2] += w.cosine_exact;
        }
    /* One side face x = 1: u across in [-1,1], z up in [0,1]; the 4 side faces are congruent. */
    for (int j = 0; j < size / 2; ++j)
        for (int i = 0; i < size; ++i) {
            double u0 = -1.0 + step * i, u1 = u0 + step, z0 = step * j, z1 = z0 + step;
            double uc = 0.5 * (u0 + u1), zc = 0.5 * (z0 + z1);
            double omega = rectangle(sol_plane_element_area, u0, z0, u1, z1);
            side[0] += omega;
            side[1] += omega * zc / sqrt(1.0 + uc * uc + zc * zc);
            side[2] += sol_side_cosine_area(u1, z0, z1) - sol_side_cosine_area(u0, z0, z1);
        }
    *solid_angle = front[0] + 4.0 * side[0];
    *cosine_at_centre = front[1] + 4.0 * side[1];
    *cosine_exact = front[2] + 4.0 * side[2];
    return SOL_OK;
}
