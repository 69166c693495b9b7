/* t3_t5_t6_equal_density - where 8-bit gamma and 8-bit linear storage have the same quantisation
 * step (claims T3, T5), and what the Xbox 360's 8-bit texture-cache de-gamma costs (T6).
 *
 * Talk, slide "Gamma vs linear space for color textures": solving x_gamma' = x' gives the
 * "median" x = 5/11 = 0.45 ~ 116/255 (linear space). Slide "Gamma vs linear space on Xbox 360":
 * for the piecewise-linear curve the median is ~90/255 linear, "25/255 in gamma space"; gamma
 * textures are de-gammaed into 8 bits in the texture cache unless sampled _AS16.
 *
 * Equal density means equal quantisation step in linear units: an 8-bit gamma texture's step at
 * linear x is 1 / (255 * curve'(x)), linear storage's is 1/255, so the point solves curve'(x) = 1.
 * For x^(1/g) that is x = g^(-g/(g-1)). The talk's 5/11 is 1/g, the root of g x = 1: the
 * derivative g x^(g-1) of the decoding power with the exponent g-1 taken as 1. */
#include <math.h>
#include <stdio.h>

#include "exp_harness.h"
#include "sol_textures.h"

enum { CURVES = 3 };
static const sol_transfer curves[CURVES] = {{SOL_TRANSFER_POWER, 2.2}, {SOL_TRANSFER_SRGB, 0}, {SOL_TRANSFER_X360_PWL, 0}};
static const char *curve_name[CURVES] = {"power 2.2", "sRGB", "Xbox 360 PWL"};

static double encode(const sol_transfer *c, double x)
{
    double e;
    exp_check(sol_transfer_encode(c, x, &e), "encoding %g", x);
    return e;
}

static void equal_density_table(const exp_run *exp, double lo[CURVES], double hi[CURVES], double strict[CURVES])
{
    exp_table *t = exp_table_new("Equal-density points: curve'(x) = 1 (8-bit gamma step = 8-bit linear step)",
                                 "curve,crossing x (linear),x * 255,gamma code of x,slope within 1% from (x*255),"
                                 "to (x*255)");
    for (int k = 0; k < CURVES; ++k) {
        double unused;
        exp_check(sol_transfer_equal_density(&curves[k], 0.0, &strict[k], &unused), "equal density");
        exp_check(sol_transfer_equal_density(&curves[k], 0.01, &lo[k], &hi[k]), "equal density");
        exp_table_row(t, "%s|%.5f|%.2f|%.2f|%.2f|%.2f", curve_name[k], strict[k], strict[k] * 255.0,
                      encode(&curves[k], strict[k]) * 255.0, lo[k] * 255.0, hi[k] * 255.0);
    }
    exp_table_write(t, exp, "equal_density");
}

/* The talk's figures next to the equations that give them. */
static void talk_equations_table(const exp_run *exp, double strict_power, double *talk_x, double *gamma_of_90_pwl,
                                 double *decode_of_90)
{
    const double g = 2.2, x90 = 90.0 / 255.0;
    *talk_x = 1.0 / g; /* root of g x = 1 */
    *gamma_of_90_pwl = encode(&curves[2], x90);
    *decode_of_90 = pow(x90, g);
    exp_table *t = exp_table_new("Which equation gives the talk's figures", "equation,x,x * 255,consistent?");
    exp_table_row(t, "g x = 1 (talk's 5/11)|%.5f|%.2f|no: d/dx x^g = g x^(g-1), not g x", *talk_x, *talk_x * 255);
    exp_table_row(t, "d/dx x^(1/g) = 1 (equal step)|%.5f|%.2f|yes", strict_power, strict_power * 255);
    exp_table_row(t, "d/ds s^g = 1 (in gamma units)|%.5f|%.2f|yes: same point in gamma space",
                  encode(&curves[0], strict_power), encode(&curves[0], strict_power) * 255);
    exp_table_row(t, "PWL encode of 90/255|%.5f|%.2f|yes: the gamma code of linear 90/255", *gamma_of_90_pwl,
                  *gamma_of_90_pwl * 255);
    exp_table_row(t, "power-2.2 encode of 90/255|%.5f|%.2f|yes", encode(&curves[0], x90), encode(&curves[0], x90) * 255);
    exp_table_row(t, "(90/255)^2.2 (talk's 25/255)|%.5f|%.2f|no: decodes a linear value", *decode_of_90,
                  *decode_of_90 * 255);
    exp_table_write(t, exp, "talk_equations");
}

static void density_plot(const exp_run *exp)
{
    FILE *f = exp_open(exp, "steps.csv");
    fputs("x,linear,power22,srgb,pwl\n", f);
    for (int i = 1; i <= 1024; ++i) {
        double x = i / 1024.0;
        fprintf(f, "%.6f,%.6e", x, 1.0);
        for (int k = 0; k < CURVES; ++k) {
            double s;
            exp_check(sol_transfer_slope(&curves[k], x, &s), "slope");
            fprintf(f, ",%.6e", 1.0 / s); /* step relative to linear storage's 1/255 */
        }
        fputc('\n', f);
    }
    fclose(f);
    exp_plot(exp, "steps",
             "set datafile separator comma\nset grid\nset logscale y 2\nset key top left\n"
             "set xlabel 'linear value x'\nset ylabel '8-bit step / linear storage step (1/255)'\n"
             "set xrange [0:1]\nset yrange [0.05:4]\n"
             "set arrow from 5.0/11,0.05 to 5.0/11,4 nohead dt 2 lc rgb 'gray'\n"
             "set label 'talk 5/11' at 5.0/11+0.01,0.08 tc rgb 'gray'\n"
             "plot 'steps.csv' using 1:2 with lines lw 2 title 'linear', '' using 1:3 with lines lw 2 title 'power 2.2', "
             "'' using 1:4 with lines title 'sRGB', '' using 1:5 with steps lw 2 title 'Xbox 360 PWL'");
}

typedef struct cache_stats {
    double rms_as16, rms_cache8, rms_linear8, max_cache8;
    int levels_as16, levels_cache8, levels_linear8;
} cache_stats;

/* T6: texels with linear values uniformly in [a, b]: stored as PWL gamma 8-bit and fetched exactly
 * (_AS16), stored as PWL gamma and fetched through the 8-bit cache, or stored linear 8-bit.
 * Errors in 1/255 linear units. */
static cache_stats cache_loss(double a, double b, int samples)
{
    const sol_transfer *pwl = &curves[2];
    cache_stats s = {0};
    int prev[3] = {-1, -1, -1};
    for (int i = 0; i < samples; ++i) {
        double x = a + (b - a) * (i + 0.5) / samples;
        uint8_t g;
        exp_check(sol_transfer_quantize8(pwl, x, &g), "quantize");
        int l10 = sol_x360_pwl_gamma8_to_linear10(g), c8 = sol_x360_cache_degamma8(g);
        int lin8 = (int)sol_unorm_encode(x, 8);
        double e16 = (l10 / 1023.0 - x) * 255.0, e8 = (c8 / 255.0 - x) * 255.0, el = (lin8 / 255.0 - x) * 255.0;
        s.rms_as16 += e16 * e16;
        s.rms_cache8 += e8 * e8;
        s.rms_linear8 += el * el;
        s.max_cache8 = fmax(s.max_cache8, fabs(e8));
        s.levels_as16 += l10 != prev[0];
        s.levels_cache8 += c8 != prev[1];
        s.levels_linear8 += lin8 != prev[2];
        prev[0] = l10;
        prev[1] = c8;
        prev[2] = lin8;
    }
    s.rms_as16 = sqrt(s.rms_as16 / samples);
    s.rms_cache8 = sqrt(s.rms_cache8 / samples);
    s.rms_linear8 = sqrt(s.rms_linear8 / samples);
    return s;
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "t3_t5_t6_equal_density", argc, argv);
    if (exp.bench) /* no accuracy knob here: closed forms and exhaustive 8-bit tables */
        return 0;
    double lo[CURVES], hi[CURVES], strict[CURVES], talk_x, gamma90, decode90;
    equal_density_table(&exp, lo, hi, strict);
    talk_equations_table(&exp, strict[0], &talk_x, &gamma90, &decode90);
    density_plot(&exp);

    const int samples = exp.quick ? 20000 : 1000000;
    const double ranges[][2] = {{0, 32 / 255.0}, {32 / 255.0, 128 / 255.0}, {128 / 255.0, 1}, {0, 1}};
    exp_table *t = exp_table_new("Xbox 360 PWL gamma texels: exact fetch (_AS16) vs 8-bit cache vs linear 8-bit "
                                 "storage (errors in 1/255 linear)",
                                 "linear range,RMS _AS16,RMS 8-bit cache,max 8-bit cache,RMS linear 8-bit,"
                                 "levels _AS16,levels 8-bit cache,levels linear 8-bit");
    cache_stats dark = {0}, all = {0};
    for (int r = 0; r < 4; ++r) {
        cache_stats s = cache_loss(ranges[r][0], ranges[r][1], samples);
        if (r == 0)
            dark = s;
        if (r == 3)
            all = s;
        exp_table_row(t, "%.0f/255 to %.0f/255|%.3f|%.3f|%.3f|%.3f|%d|%d|%d", ranges[r][0] * 255, ranges[r][1] * 255,
                      s.rms_as16, s.rms_cache8, s.max_cache8, s.rms_linear8, s.levels_as16, s.levels_cache8,
                      s.levels_linear8);
    }
    exp_table_write(t, &exp, "x360_cache");
    int distinct = 1;
    for (int e = 1; e < 256; ++e)
        distinct += sol_x360_cache_degamma8((uint8_t)e) != sol_x360_cache_degamma8((uint8_t)(e - 1));

    char sol_fig[512];
    snprintf(sol_fig, sizeof sol_fig, "%.4f = %.1f/255 linear (%.1f/255 in gamma); 5/11 = %.1f/255 is the root of g x = 1",
             strict[0], strict[0] * 255, encode(&curves[0], strict[0]) * 255, talk_x * 255);
    /* Reproduced if the equal-density point is 5/11 within 1/255; differs-explained if it is not but the
     * talk's own equation (g x = 1) has the root 5/11 within 1/255, so that equation explains the figure. */
    const double tol255 = 1.0 / 255.0, talk_t3 = 5.0 / 11.0;
    exp_verdict t3 = fabs(strict[0] - talk_t3) <= tol255  ? EXP_REPRODUCED
                     : fabs(talk_x - talk_t3) <= tol255 ? EXP_DIFFERS_EXPLAINED
                                                        : EXP_NOT_REPRODUCED;
    exp_number(&exp, "T3-point", "%.3f", strict[0]);
    exp_number(&exp, "T3-point-255", "%.0f", strict[0] * 255);
    exp_number(&exp, "T3-gamma-code-255", "%.0f", encode(&curves[0], strict[0]) * 255);
    exp_claim(&exp, "T3", "x = 5/11 = 0.45 ~ 116/255 (linear)", sol_fig, "1/255", t3,
              "equal quantisation step of 8-bit gamma-2.2 and linear storage is where d(x^(1/2.2))/dx = 1, x = "
              "2.2^(-2.2/1.2); the talk's 5/11 = 1/2.2 solves 2.2 x = 1, i.e. the derivative of x^2.2 with its exponent "
              "1.2 taken as 1 (exact sRGB: %.1f/255)",
              strict[1] * 255);
    double pwl_slopes[4]; /* at the middle of each 10-bit linear segment [0,64), [64,128), [128,512), [512,1023] */
    const double segment_mid[4] = {32.0 / 1023.0, 96.0 / 1023.0, 320.0 / 1023.0, 767.5 / 1023.0};
    for (int s = 0; s < 4; ++s)
        exp_check(sol_transfer_slope(&curves[2], segment_mid[s], &pwl_slopes[s]), "PWL slope");
    snprintf(sol_fig, sizeof sol_fig,
             "PWL slopes %.2f, %.2f, %.3f, %.2f: equal density over linear [%.1f, %.1f]/255 (crossing %.1f/255); "
             "90/255 is gamma %.1f/255; (90/255)^2.2 = %.1f/255",
             pwl_slopes[0], pwl_slopes[1], pwl_slopes[2], pwl_slopes[3], lo[2] * 255, hi[2] * 255, strict[2] * 255,
             gamma90 * 255, decode90 * 255);
    /* 90/255 must lie in the PWL curve's equal-density range; "25/255 in gamma space" agrees if the
     * gamma code of 90/255 is 25/255 within 1/255, and is explained if (90/255)^2.2 is. */
    const double talk_t5 = 90.0 / 255.0, talk_t5_gamma = 25.0 / 255.0;
    int t5_in_range = lo[2] <= talk_t5 && talk_t5 <= hi[2];
    exp_verdict t5 = !t5_in_range                                     ? EXP_NOT_REPRODUCED
                     : fabs(gamma90 - talk_t5_gamma) <= tol255  ? EXP_REPRODUCED
                     : fabs(decode90 - talk_t5_gamma) <= tol255 ? EXP_DIFFERS_EXPLAINED
                                                                : EXP_NOT_REPRODUCED;
    exp_number(&exp, "T5-range-lo-255", "%.0f", lo[2] * 255);
    exp_number(&exp, "T5-range-hi-255", "%.0f", hi[2] * 255);
    exp_number(&exp, "T5-crossing-255", "%.1f", strict[2] * 255);
    exp_number(&exp, "T5-gamma90-255", "%.0f", gamma90 * 255);
    exp_number(&exp, "T5-decode90-255", "%.1f", decode90 * 255);
    exp_claim(&exp, "T5", "~90/255 linear, \"25/255 in gamma space\"", sol_fig,
              "90/255 inside the equal-density range; 25/255 within 1/255", t5,
              "the PWL curve's third segment has slope 1023/1020, so densities match (within 1%%) for every linear value "
              "between 32/255 and 128/255 and 90/255 is one of them; but 25/255 is 90/255 pushed through the decoding "
              "power x^2.2, not its gamma-space code (%.0f/255 on the PWL curve, gamma codes are above linear ones)",
              gamma90 * 255);
    snprintf(sol_fig, sizeof sol_fig,
             "8-bit cache keeps %d of 256 gamma codes distinct; dark [0,32]/255: RMS %.3f vs %.3f with _AS16 (linear "
             "8-bit %.3f)",
             distinct, dark.rms_cache8, dark.rms_as16, dark.rms_linear8);
    /* T6 holds if the cache merges gamma codes and loses precision that the exact (_AS16) fetch keeps. */
    int precision_lost = distinct < 256 && dark.rms_cache8 > dark.rms_as16 && all.rms_cache8 > all.rms_as16;
    exp_claim(&exp, "T6", "gamma textures de-gammaed into 8 bits in the cache: precision loss unless _AS16", sol_fig,
              "qualitative", precision_lost ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "through the 8-bit cache a PWL-gamma texel is never better than a linear 8-bit texel: over [0,1] RMS %.3f "
              "(cache) vs %.3f (_AS16) vs %.3f (linear storage) in 1/255 units, the dark codes where gamma storage should "
              "win collapse 4:1 and 2:1",
              all.rms_cache8, all.rms_as16, all.rms_linear8);
    return 0;
}
