/* obscurance.c - claim M3: screen-space ambient occlusion as volumetric obscurance (Loos & Sloan,
 * "Volumetric Obscurance", I3D 2010) with few line samples per pixel, computed at half resolution
 * and upsampled with depth-aware weights (talk, "SSAO improvements" slide and notes). */
#include "sol_screen.h"

#include <math.h>

/* Interleaved gradient noise (Jimenez, "Next generation post processing in Call of Duty: Advanced
 * Warfare", SIGGRAPH 2014): a per-pixel value in [0,1) whose neighbours differ strongly. */
static double pixel_noise(int x, int y)
{
    double inner = 0.06711056 * x + 0.00583715 * y;
    double v = 52.9829189 * (inner - floor(inner));
    return v - floor(v);
}

sol_status sol_vo_compute(const sol_camera *camera, const float *depth, const sol_vo_options *options, float *vo)
{
    sol_status status = sol_camera_check(camera);
    if (status != SOL_OK)
        return status;
    if (!depth || !vo)
        return SOL_ERR_NULL_ARG;
    sol_vo_options opt = options ? *options : (sol_vo_options){0};
    if (!isfinite(opt.radius))
        return SOL_ERR_NONFINITE;
    const double radius = opt.radius > 0.0 ? opt.radius : 1.0;
    const int samples = opt.samples ? opt.samples : 4;
    if (opt.radius < 0.0 || samples < 1 || samples > 4096)
        return SOL_ERR_INVALID_ARG;
    const int width = camera->width, height = camera->height;
    for (size_t i = 0; i < (size_t)width * (size_t)height; ++i)
        if (!isfinite(depth[i]))
            return SOL_ERR_NONFINITE;

    /* This frame's disk points (unit disk, area-uniform) and their line half lengths. */
    double disk[4096][2], half_len[4096];
    for (int i = 0; i < samples; ++i) {
        double u, v;
        sol_r2_point((uint64_t)opt.frame * (uint64_t)samples + (uint64_t)i, &u, &v);
        double r = sqrt(u), a = 2.0 * M_PI * v;
        disk[i][0] = r * cos(a);
        disk[i][1] = r * sin(a);
        half_len[i] = sqrt(fmax(0.0, 1.0 - u));
    }
#pragma omp parallel for schedule(dynamic, 4)
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const double zp = depth[(size_t)py * (size_t)width + (size_t)px];
            float *out = &vo[(size_t)py * (size_t)width + (size_t)px];
            if (zp >= camera->zfar) {
                *out = 0.0f;
                continue;
            }
            const double angle = opt.same_rotation_everywhere ? 0.0 : 2.0 * M_PI * pixel_noise(px, py);
            const double c = cos(angle), s = sin(angle), scale = camera->focal * radius / zp;
            double solid = 0.0, total = 0.0;
            for (int i = 0; i < samples; ++i) {
                double ox = c * disk[i][0] - s * disk[i][1], oy = s * disk[i][0] + c * disk[i][1];
                /* Clamping in floating point first keeps the integer conversion in range and
                 * makes truncation equal floor; plain comparisons avoid libm calls here. */
                double fx = px + 0.5 + scale * ox, fy = py + 0.5 + scale * oy;
                fx = fx < 0.0 ? 0.0 : fx > width - 1 ? width - 1 : fx;
                fy = fy < 0.0 ? 0.0 : fy > height - 1 ? height - 1 : fy;
                double zs = depth[(size_t)fy * (size_t)width + (size_t)fx];
                double h = radius * half_len[i], part = zp + h - zs;
                solid += part <= 0.0 ? 0.0 : part >= 2.0 * h ? 2.0 * h : part;
                total += 2.0 * h;
            }
            *out = total > 0.0 ? (float)(solid / total) : 0.5f;
        }
    return SOL_OK;
}

sol_status sol_depth_half(const float *depth, int width, int height, float *out)
{
    if (!depth || !out)
        return SOL_ERR_NULL_ARG;
    if (width < 1 || height < 1)
        return SOL_ERR_INVALID_ARG;
    const int hw = (width + 1) / 2, hh = (height + 1) / 2;
    for (int y = 0; y < hh; ++y)
        for (int x = 0; x < hw; ++x)
            out[(size_t)y * (size_t)hw + (size_t)x] = depth[(size_t)(2 * y) * (size_t)width + (size_t)(2 * x)];
    return SOL_OK;
}

sol_status sol_bilateral_upsample(const float *half_values, const float *half_depth, const float *full_depth,
                                  int width, int height, float *out)
{
    if (!half_values || !half_depth || !full_depth || !out)
        return SOL_ERR_NULL_ARG;
    if (width < 1 || height < 1)
        return SOL_ERR_INVALID_ARG;
    const int hw = (width + 1) / 2, hh = (height + 1) / 2;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            /* Half texel (i, j) was taken at full pixel (2i, 2j): its centre in half-texel units
             * is i, so this pixel sits at (x/2, y/2). */
            double hx = 0.5 * x, hy = 0.5 * y, fx = floor(hx), fy = floor(hy);
            double ax = hx - fx, ay = hy - fy, z = full_depth[(size_t)y * (size_t)width + (size_t)x];
            double sum = 0.0, weight = 0.0;
            for (int k = 0; k < 4; ++k) {
                int tx = (int)fx + (k & 1), ty = (int)fy + (k >> 1);
                tx = tx >= hw ? hw - 1 : tx;
                ty = ty >= hh ? hh - 1 : ty;
                double bw = ((k & 1) ? ax : 1.0 - ax) * ((k >> 1) ? ay : 1.0 - ay);
                size_t i = (size_t)ty * (size_t)hw + (size_t)tx;
                double dz = fabs(half_depth[i] - z) / fmax(fabs(z), 1e-30);
                double w = bw / (1e-3 + dz);
                sum += w * half_values[i];
                weight += w;
            }
            out[(size_t)y * (size_t)width + (size_t)x] = weight > 0.0 ? (float)(sum / weight) : 0.0f;
        }
    return SOL_OK;
}
