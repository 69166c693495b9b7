/* box_scene.c - the analytic test scene of the screen-space experiments: a pinhole camera and
 * axis-aligned boxes, rendered by casting one ray per pixel centre (exact depth at the samples,
 * so the M1 reference visibility and the M3 depth buffers carry no rasterisation error). */
#include "sol_screen.h"

#include <math.h>

sol_status sol_camera_check(const sol_camera *camera)
{
    if (!camera)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(camera->focal) || !isfinite(camera->znear) || !isfinite(camera->zfar))
        return SOL_ERR_NONFINITE;
    if (camera->width < 1 || camera->height < 1 || camera->focal <= 0.0 || camera->znear <= 0.0 ||
        camera->zfar <= camera->znear)
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

sol_status sol_box_check(const sol_camera *camera, const sol_box *box)
{
    if (!camera || !box)
        return SOL_ERR_NULL_ARG;
    for (int i = 0; i < 3; ++i)
        if (!isfinite(box->min[i]) || !isfinite(box->max[i]))
            return SOL_ERR_NONFINITE;
    for (int i = 0; i < 3; ++i)
        if (box->min[i] > box->max[i])
            return SOL_ERR_INVALID_ARG;
    return box->min[2] < camera->znear ? SOL_ERR_INVALID_ARG : SOL_OK;
}

/* Direction (z component 1) of the ray through screen point (sx, sy): its parameter is depth. */
static void pixel_ray(const sol_camera *camera, double sx, double sy, double dir[3])
{
    dir[0] = (sx - 0.5 * camera->width) / camera->focal;
    dir[1] = (sy - 0.5 * camera->height) / camera->focal;
    dir[2] = 1.0;
}

/* Depth where the ray from the origin along dir (dir[2] = 1) enters the box, or INFINITY. Slab
 * test; a zero direction component is handled apart so flat boxes never produce 0/0. */
static double ray_box_depth(const double dir[3], const sol_box *box)
{
    double enter = 0.0, leave = INFINITY;
    for (int i = 0; i < 3; ++i) {
        if (dir[i] == 0.0) {
            if (box->min[i] > 0.0 || box->max[i] < 0.0)
                return INFINITY;
            continue;
        }
        double t0 = box->min[i] / dir[i], t1 = box->max[i] / dir[i];
        if (t0 > t1) {
            double t = t0;
            t0 = t1;
            t1 = t;
        }
        enter = fmax(enter, t0);
        leave = fmin(leave, t1);
    }
    return enter <= leave ? enter : INFINITY;
}

sol_status sol_boxes_trace(const sol_camera *camera, const sol_box *boxes, size_t count, double sx, double sy,
                           double *depth, long *index)
{
    sol_status status = sol_camera_check(camera);
    if (status != SOL_OK)
        return status;
    if (!depth || !index || (count && !boxes))
        return SOL_ERR_NULL_ARG;
    if (!isfinite(sx) || !isfinite(sy))
        return SOL_ERR_NONFINITE;
    for (size_t i = 0; i < count; ++i)
        if ((status = sol_box_check(camera, &boxes[i])) != SOL_OK)
            return status;
    double dir[3], nearest = camera->zfar;
    long hit = -1;
    pixel_ray(camera, sx, sy, dir);
    for (size_t i = 0; i < count; ++i) {
        double t = ray_box_depth(dir, &boxes[i]);
        if (t < nearest) {
            nearest = t;
            hit = (long)i;
        }
    }
    *depth = nearest;
    *index = hit;
    return SOL_OK;
}

sol_status sol_boxes_render_depth(const sol_camera *camera, const sol_box *boxes, size_t count, float *depth)
{
    sol_status status = sol_camera_check(camera);
    if (status != SOL_OK)
        return status;
    if (!depth || (count && !boxes))
        return SOL_ERR_NULL_ARG;
    for (size_t i = 0; i < count; ++i)
        if ((status = sol_box_check(camera, &boxes[i])) != SOL_OK)
            return status;
    const int width = camera->width, height = camera->height;
#pragma omp parallel for schedule(dynamic, 4)
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            double dir[3], nearest = camera->zfar;
            pixel_ray(camera, px + 0.5, py + 0.5, dir);
            for (size_t i = 0; i < count; ++i)
                nearest = fmin(nearest, ray_box_depth(dir, &boxes[i]));
            depth[(size_t)py * (size_t)width + (size_t)px] = (float)nearest;
        }
    return SOL_OK;
}

sol_status sol_box_screen_bounds(const sol_camera *camera, const sol_box *box, sol_screen_bounds *out)
{
    sol_status status = sol_camera_check(camera);
    if (status == SOL_OK)
        status = sol_box_check(camera, box);
    if (status != SOL_OK)
        return status;
    if (!out)
        return SOL_ERR_NULL_ARG;
    sol_screen_bounds b = {INFINITY, INFINITY, -INFINITY, -INFINITY, box->min[2]};
    for (int corner = 0; corner < 8; ++corner) {
        double x = corner & 1 ? box->max[0] : box->min[0];
        double y = corner & 2 ? box->max[1] : box->min[1];
        double z = corner & 4 ? box->max[2] : box->min[2];
        double sx = 0.5 * camera->width + camera->focal * x / z;
        double sy = 0.5 * camera->height + camera->focal * y / z;
        b.x0 = fmin(b.x0, sx);
        b.x1 = fmax(b.x1, sx);
        b.y0 = fmin(b.y0, sy);
        b.y1 = fmax(b.y1, sy);
    }
    *out = b;
    return SOL_OK;
}

/* Pixel index range whose cells meet [lo, hi], clipped to [0, size-1]; empty when *first > *last.
 * Whole cells (not only centres) keep it a superset of the pixels whose centre the box covers. */
static void pixel_range(double lo, double hi, int size, int *first, int *last)
{
    *first = lo <= 0.0 ? 0 : lo >= size ? size : (int)floor(lo);
    *last = hi < 0.0 ? -1 : hi >= size ? size - 1 : (int)floor(hi);
}

sol_status sol_box_visible(const sol_camera *camera, const float *depth, const sol_box *box, int *visible)
{
    sol_screen_bounds b;
    sol_status status = sol_box_screen_bounds(camera, box, &b);
    if (status != SOL_OK)
        return status;
    if (!depth || !visible)
        return SOL_ERR_NULL_ARG;
    int x0, x1, y0, y1, seen = 0;
    pixel_range(b.x0, b.x1, camera->width, &x0, &x1);
    pixel_range(b.y0, b.y1, camera->height, &y0, &y1);
    for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px) {
            float stored = depth[(size_t)py * (size_t)camera->width + (size_t)px];
            if (!isfinite(stored))
                return SOL_ERR_NONFINITE;
            double dir[3];
            pixel_ray(camera, px + 0.5, py + 0.5, dir);
            if (ray_box_depth(dir, box) < stored)
                seen = 1;
        }
    *visible = seen;
    return SOL_OK;
}
