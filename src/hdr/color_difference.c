/* color_difference.c - sRGB to CIE L*a*b* and the CIEDE2000 difference (claim M4's perceptual
 * error). Formulas: IEC 61966-2-1 (sRGB), CIE 15:2004 (L*a*b*), G. Sharma, W. Wu, E. N. Dalal,
 * "The CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
 * mathematical observations", Color Research & Application 30(1), 2005 (equations 1-22). */
#include "sol_hdr.h"

#include <math.h>

static double deg(double rad) { return rad * (180.0 / M_PI); }
static double rad(double degrees) { return degrees * (M_PI / 180.0); }

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

void sol_srgb_to_lab(const double srgb[3], double lab[3])
{
    double r = sol_srgb_decode(srgb[0]), g = sol_srgb_decode(srgb[1]), b = sol_srgb_decode(srgb[2]);
    /* sRGB primaries, D65 white (IEC 61966-2-1), normalised by the white the same matrix gives
     * for (1,1,1), so that sRGB white is exactly L* = 100, a* = b* = 0. */
    double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / (0.4124 + 0.3576 + 0.1805);
    double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / (0.0193 + 0.1192 + 0.9505);
    double fx = lab_f(x), fy = lab_f(y), fz = lab_f(z);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

/* Hue angle in degrees [0, 360); 0 for the achromatic case (Sharma eq. 4). */
static double hue_deg(double b, double a)
{
    if (a == 0.0 && b == 0.0)
        return 0.0;
    double h = deg(atan2(b, a));
    return h < 0.0 ? h + 360.0 : h;
}

double sol_ciede2000(const double lab1[3], const double lab2[3])
{
    const double pow25_7 = 6103515625.0; /* 25^7 */
    double c1 = hypot(lab1[1], lab1[2]), c2 = hypot(lab2[1], lab2[2]);
    double c_mean7 = pow(0.5 * (c1 + c2), 7.0);
    double g = 0.5 * (1.0 - sqrt(c_mean7 / (c_mean7 + pow25_7)));
    double a1 = (1.0 + g) * lab1[1], a2 = (1.0 + g) * lab2[1];
    double cp1 = hypot(a1, lab1[2]), cp2 = hypot(a2, lab2[2]);
    double hp1 = hue_deg(lab1[2], a1), hp2 = hue_deg(lab2[2], a2);

    double dl = lab2[0] - lab1[0], dc = cp2 - cp1, dh = 0.0;
    if (cp1 * cp2 != 0.0) {
        dh = hp2 - hp1;
        if (dh > 180.0)
            dh -= 360.0;
        else if (dh < -180.0)
            dh += 360.0;
    }
    double d_big_h = 2.0 * sqrt(cp1 * cp2) * sin(rad(dh) / 2.0);

    double l_mean = 0.5 * (lab1[0] + lab2[0]), cp_mean = 0.5 * (cp1 + cp2), hp_mean = hp1 + hp2;
    if (cp1 * cp2 != 0.0) {
        if (fabs(hp1 - hp2) <= 180.0)
            hp_mean *= 0.5;
        else
            hp_mean = hp1 + hp2 < 360.0 ? 0.5 * (hp_mean + 360.0) : 0.5 * (hp_mean - 360.0);
    }
    double t = 1.0 - 0.17 * cos(rad(hp_mean - 30.0)) + 0.24 * cos(rad(2.0 * hp_mean)) +
               0.32 * cos(rad(3.0 * hp_mean + 6.0)) - 0.20 * cos(rad(4.0 * hp_mean - 63.0));
    double d_theta = 30.0 * exp(-pow((hp_mean - 275.0) / 25.0, 2.0));
    double cp_mean7 = pow(cp_mean, 7.0);
    double rc = 2.0 * sqrt(cp_mean7 / (cp_mean7 + pow25_7));
    double l50 = (l_mean - 50.0) * (l_mean - 50.0);
    double sl = 1.0 + 0.015 * l50 / sqrt(20.0 + l50), sc = 1.0 + 0.045 * cp_mean, sh = 1.0 + 0.015 * cp_mean * t;
    double rt = -sin(rad(2.0 * d_theta)) * rc;
    double tl = dl / sl, tc = dc / sc, th = d_big_h / sh;
    return sqrt(tl * tl + tc * tc + th * th + rt * tc * th);
}
