/* grading.c - the global colour transforms a 3D LUT bakes (claim M4): "color correction,
 * contrast, brightness, levels, selective colors" (talk, slide "Color grading"). Each is a plain
 * closed-form map of the sRGB-encoded cube, so the experiment can compare a LUT with the exact map. */
#include "sol_hdr.h"

#include <math.h>

static double clamp01(double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; }
static double or_one(double v) { return v == 0.0 ? 1.0 : v; }

/* ASC-CDL-like lift/gamma/gain on one channel. */
static double lift_gamma_gain(double x, double lift, double gamma, double gain)
{
    double lifted = clamp01(x + lift * (1.0 - x));
    return or_one(gain) * pow(lifted, 1.0 / or_one(gamma));
}

/* S-curve: blend of the identity and smoothstep, steeper with `contrast` in [0, 1]. */
static double contrast_curve(double x, double contrast)
{
    double v = clamp01(x), s = v * v * (3.0 - 2.0 * v);
    return v + contrast * (s - v);
}

/* Rotation about the grey axis (1,1,1)/sqrt(3) by Rodrigues' formula. */
static void rotate_hue(double c[3], double degrees)
{
    double a = degrees * (M_PI / 180.0), cs = cos(a), sn = sin(a) / sqrt(3.0), k = (1.0 - cs) / 3.0;
    double sum = c[0] + c[1] + c[2], r = c[0], g = c[1], b = c[2];
    c[0] = cs * r + k * sum + sn * (b - g);
    c[1] = cs * g + k * sum + sn * (r - b);
    c[2] = cs * b + k * sum + sn * (g - r);
}

void sol_grade_apply(const sol_grade *grade, const double in[3], double out[3])
{
    double c[3];
    for (int i = 0; i < 3; ++i) {
        c[i] = lift_gamma_gain(clamp01(isnan(in[i]) ? 0.0 : in[i]), grade->lift[i], grade->gamma[i], grade->gain[i]);
        c[i] = contrast_curve(c[i], grade->contrast);
    }
    double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    for (int i = 0; i < 3; ++i)
        c[i] = luma + (1.0 + grade->saturation) * (c[i] - luma);
    if (grade->hue_degrees != 0.0)
        rotate_hue(c, grade->hue_degrees);
    for (int i = 0; i < 3; ++i)
        out[i] = clamp01(c[i]);
}
