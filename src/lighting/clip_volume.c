/* clip_volume.c - D13: a deferred point light without shadows lands on every G-buffer pixel inside
 * its radius, including the floor of the room behind a wall; the talk's clip volumes (artist
 * stencil geometry, slide "Clip Volumes for Deferred Lighting") mask those pixels. This file lights
 * the floor of a small floor plan three ways: unshadowed, unshadowed with a clip volume, and with
 * ray-traced visibility (the reference), so the leak and what the clip volume removes can be
 * measured. */
#include "sol_lighting.h"

#include <float.h>
#include <math.h>

/* Does the segment light -> floor point pass through the solid part of `w`? */
static int wall_blocks(const sol_wall *w, double wall_height, const double light[3], double x, double y)
{
    double dx = x - light[0], dy = y - light[1];    /* light -> point, parameter s */
    double ex = w->x1 - w->x0, ey = w->y1 - w->y0;  /* wall, parameter t */
    double denom = dx * ey - dy * ex;
    if (denom == 0.0)
        return 0; /* parallel: grazing the wall's plane does not block */
    double qx = w->x0 - light[0], qy = w->y0 - light[1];
    double s = (qx * ey - qy * ex) / denom;
    double t = (qx * dy - qy * dx) / denom;
    if (s <= 0.0 || s >= 1.0 || t < 0.0 || t > 1.0)
        return 0;
    double z = light[2] * (1.0 - s); /* height of the ray where it crosses the wall */
    if (z >= wall_height)
        return 0;
    if (w->door_t1 > w->door_t0 && t >= w->door_t0 && t <= w->door_t1 && z < w->door_height)
        return 0;
    return 1;
}

sol_status sol_room_irradiance(const sol_room_scene *scene, const sol_clip_box *clip, sol_light_mode mode,
                               double x, double y, double *irradiance)
{
    if (!scene || !irradiance || (scene->wall_count > 0 && !scene->walls) || (mode == SOL_LIGHT_CLIPPED && !clip))
        return SOL_ERR_NULL_ARG;
    if (!isfinite(x) || !isfinite(y) || !isfinite(scene->light[0]) || !isfinite(scene->light[1]) ||
        !isfinite(scene->light[2]) || !isfinite(scene->radius))
        return SOL_ERR_NONFINITE;
    if (!(scene->radius > 0.0) || !(scene->light[2] > 0.0) || scene->wall_count < 0 || mode < 0 ||
        mode > SOL_LIGHT_SHADOWED)
        return SOL_ERR_INVALID_ARG;
    double dx = x - scene->light[0], dy = y - scene->light[1], dz = scene->light[2];
    double d2 = dx * dx + dy * dy + dz * dz;
    double q = d2 / (scene->radius * scene->radius);
    double e = 0.0;
    if (!(d2 >= 1e-200 && d2 <= 1e200)) {
        /* d^2 under- or overflows (a light 1e-300 above the floor, far-away points): the same
         * quantities with the offsets divided by m = their largest magnitude, d = m n */
        double m = fmax(fmax(fabs(dx), fabs(dy)), dz), ux = dx / m, uy = dy / m, uz = dz / m;
        double n = sqrt(ux * ux + uy * uy + uz * uz), dr = m / scene->radius * n;
        q = dr * dr;
        if (q < 1.0)
            e = uz / (n * n * n) / m / m * (1.0 - q) * (1.0 - q);
    } else if (q < 1.0) /* cos(theta) / d^2 with cos = height / d, windowed to zero at the radius */
        e = dz / (d2 * sqrt(d2)) * (1.0 - q) * (1.0 - q);
    if (mode == SOL_LIGHT_CLIPPED && !(x >= clip->x0 && x <= clip->x1 && y >= clip->y0 && y <= clip->y1))
        e = 0.0;
    if (mode == SOL_LIGHT_SHADOWED && e > 0.0)
        for (int i = 0; i < scene->wall_count; ++i)
            if (wall_blocks(&scene->walls[i], scene->wall_height, scene->light, x, y)) {
                e = 0.0;
                break;
            }
    if (!(e <= DBL_MAX))
        return SOL_ERR_OUT_OF_RANGE; /* e.g. a light 1e-300 above the point: height / d^3 = 1e600 */
    *irradiance = e;
    return SOL_OK;
}
