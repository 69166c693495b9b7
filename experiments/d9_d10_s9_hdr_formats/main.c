/* d9_d10_s9_hdr_formats - HDR lighting stored at LDR bandwidth (claims D9, D10, S9).
 *
 * Talk, slides "HDR on consoles" and "... dynamic range": RGBK (RGBM) in RGBA8 on PS3, R11G11B10F
 * on Xbox 360 ("not enough precision for linear HDR lighting"), fixed by scaling the stored range
 * from the average luminance. Tesseract notes: R11G11B10F light accumulation, fallback RGB10
 * scaled to 0..2. This driver stores synthetic HDR scenes in each format, with three range
 * policies, tone maps them (Hejl-Burgess-Dawson filmic, x = c / l) and counts the 8-bit sRGB
 * display codes that change against the unquantised scene. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <sys/stat.h>

#include "exp_harness.h"
#include "sol_hdr.h"

enum { SCENE_W = 256, SCENE_H = 160 };

/* ---------------- scenes ---------------- */
typedef enum scene_id { INTERIOR_WINDOW, NIGHT_STREET, SKY_SUN, DARK_CAVE, SCENE_COUNT } scene_id;
static const char *scene_name[SCENE_COUNT] = {"interior_window", "night_street", "sky_sun", "dark_cave"};

static double smooth_noise(int x, int y)
{
    return 0.5 + 0.25 * sin(x * 0.11 + 1.3 * sin(y * 0.07)) + 0.25 * sin(y * 0.13 + 0.9 * cos(x * 0.05));
}

/* Radiance-like values in engine units (a daylight grey card ~ 1). */
static void scene_pixel(scene_id id, int x, int y, double c[3])
{
    double u = x / (SCENE_W - 1.0), v = y / (SCENE_H - 1.0), t = smooth_noise(x, y);
    double k = 1.0, r = 1.0, g = 1.0, b = 1.0;
    switch (id) {
    case INTERIOR_WINDOW: /* dim room, bright window with sky, sun patch on the floor */
        k = 0.02 + 0.3 * u * u * (0.6 + 0.4 * t);
        if (u > 0.6 && u < 0.9 && v > 0.15 && v < 0.55) {
            k = 40.0 + 30.0 * (0.55 - v);
            b = 1.25;
            r = 0.85;
        } else if (u > 0.45 && u < 0.8 && v > 0.75) {
            k = 12.0 * (0.8 + 0.2 * t);
            r = 1.15;
            b = 0.8;
        }
        break;
    case NIGHT_STREET: { /* very dark ambient, two sodium lamps and their pools */
        k = 0.0008 + 0.004 * t * (1.0 - v);
        for (int lamp = 0; lamp < 2; ++lamp) {
            double lx = lamp ? 0.75 : 0.25, d2 = (u - lx) * (u - lx) * 4.0 + (v - 0.2) * (v - 0.2) * 9.0;
            double pool = (u - lx) * (u - lx) * 3.0 + (v - 0.85) * (v - 0.85) * 12.0;
            k += d2 < 0.01 ? 60.0 : 0.02 / (0.02 + d2) * 0.3 + 0.5 * exp(-pool * 20.0);
        }
        r = 1.3;
        b = 0.5;
        break;
    }
    case SKY_SUN: { /* sky gradient, horizon haze, a sun disc far above half's range */
        k = 3000.0 * (1.0 - 0.7 * v) + 500.0 * t;
        r = 0.6 + 0.4 * v;
        b = 1.3 - 0.3 * v;
        double d2 = (u - 0.7) * (u - 0.7) + (v - 0.25) * (v - 0.25);
        if (d2 < 0.0006)
            k = 1.6e5;
        if (v > 0.8)
            k = 40.0 * (0.5 + t); /* dark ground */
        break;
    }
    case DARK_CAVE: /* a smooth, very dark ramp: banding shows at once */
        k = 2e-5 * pow(300.0, u) * (0.9 + 0.1 * t);
        r = 0.9;
        b = 1.1;
        break;
    default: break;
    }
    c[0] = k * r;
    c[1] = k * g;
    c[2] = k * b;
}

static void make_scene(scene_id id, sol_image *img)
{
    exp_check(sol_image_alloc(img, SCENE_W, SCENE_H, 3), "scene");
    for (int y = 0; y < SCENE_H; ++y)
        for (int x = 0; x < SCENE_W; ++x) {
            double c[3];
            scene_pixel(id, x, y, c);
            float *p = sol_image_pixel(img, x, y);
            for (int i = 0; i < 3; ++i)
                p[i] = (float)c[i];
        }
}

/* ---------------- scene files (OpenEXR through sol_exr_*) ---------------- */
/* The scenes are written as float EXR into results/<exp>/scenes/ and read back, so the
 * experiment's input is a file other tools can open. (Real HDR maps were considered: Debian's
 * blender-data ships CC0 environment maps, but they are DWAB-compressed, which OpenEXR 3.1's C core
 * API cannot decode.) */
static void load_scenes(const exp_run *exp, sol_image *out)
{
    char path[4096], file[128];
    if (mkdir(exp_path(exp, "scenes"), 0777) != 0 && errno != EEXIST)
        exp_die("cannot create %s", exp_path(exp, "scenes"));
    for (int id = 0; id < SCENE_COUNT; ++id) {
        sol_image made;
        make_scene((scene_id)id, &made);
        snprintf(file, sizeof file, "scenes/%s.exr", scene_name[id]);
        snprintf(path, sizeof path, "%s", exp_path(exp, file));
        exp_check(sol_exr_write(path, &made, 0), "writing %s", path);
        sol_image_free(&made);
        exp_check(sol_exr_read(path, &out[id]), "reading %s", path);
    }
}

static double luminance(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

static double log_average_luminance(const sol_image *img)
{
    double s = 0.0;
    int n = img->width * img->height;
    for (int i = 0; i < n; ++i)
        s += log(fmax(luminance(img->data + 3 * i), 1e-12));
    return exp(s / n);
}

/* ---------------- formats and range policies ---------------- */
typedef enum format { FP16, R11G11B10F, RGBM8, RGB10_0_2, RGB8, FORMAT_COUNT } format;
static const char *format_name[FORMAT_COUNT] = {"RGBA16F", "R11G11B10F", "RGBM (RGBA8, range 8)", "RGB10 0..2",
                                                "RGB8 0..1"};
static const int format_bits[FORMAT_COUNT] = {64, 32, 32, 32, 32};
static const double rgbm_range = 8.0;
static const double format_max[FORMAT_COUNT] = {65504.0, 65024.0, 8.0, 2.0, 1.0};

typedef enum policy { RANGE_NONE, RANGE_AVERAGE, RANGE_WINDOW, POLICY_COUNT } policy;
static const char *policy_name[POLICY_COUNT] = {"none (absolute values)", "c / l (average luminance)",
                                                "window: c_max -> format max"};

static void store(format f, const float in[3], float out[3])
{
    switch (f) {
    case FP16:
        for (int i = 0; i < 3; ++i)
            out[i] = sol_half_to_float(sol_half_from_float(in[i]));
        break;
    case R11G11B10F: sol_r11g11b10f_unpack(sol_r11g11b10f_pack(in), out); break;
    case RGBM8: {
        uint8_t code[4];
        exp_check(sol_rgbm_encode(in, rgbm_range, code), "RGBM");
        exp_check(sol_rgbm_decode(code, rgbm_range, out), "RGBM");
        break;
    }
    case RGB10_0_2:
        for (int i = 0; i < 3; ++i)
            out[i] = sol_rgb10_scaled_decode(sol_rgb10_scaled_encode(in[i]));
        break;
    default:
        for (int i = 0; i < 3; ++i)
            out[i] = (float)sol_unorm_decode(sol_unorm_encode(in[i], 8), 8);
        break;
    }
}

static const sol_tonemap display_curve = SOL_TONEMAP_FILMIC_HBD;

/* The stored-value scale of a policy for average luminance l. The window's top is the inverse
 * tone map of 1 - 1/510 (the brightest value that still changes the display), mirroring the
 * talk's analytic lower bound. */
static double policy_scale(policy p, format f, double l)
{
    if (p == RANGE_NONE)
        return 1.0;
    if (p == RANGE_AVERAGE)
        return 1.0 / l;
    double top;
    exp_check(sol_tonemap_inverse(display_curve, 1.0 - 1.0 / 510.0, &top), "window top");
    return format_max[f] / (top * l);
}

static int display_code(double c, double l)
{
    return sol_display_code8(sol_tonemap_apply(display_curve, c / l));
}

typedef struct store_error {
    double max_code, mean_code, pct_changed, pct_2codes, max_rel_window; /* window: [c_min, c_max] */
} store_error;

/* The per-pixel work of measure_store and accumulate_lights runs in parallel over blocks of pixels
 * into per-pixel slots; the sums and maxima are then taken on one thread in pixel order, so every
 * figure is bit for bit the sequential loop's for any thread count. */
enum { PIXEL_BLOCK = 1 << 16 };

typedef struct pixel_slots {
    int diff[3 * PIXEL_BLOCK]; /* |display code stored - wanted| per channel */
    double rel[3 * PIXEL_BLOCK]; /* relative error inside the window, -1 outside */
} pixel_slots;

static pixel_slots *pixel_slots_new(void)
{
    pixel_slots *ps = malloc(sizeof *ps);
    if (!ps)
        exp_die("out of memory");
    return ps;
}

static store_error measure_store(const sol_image *scene, format f, policy p, double l, sol_image *out_display)
{
    double s = policy_scale(p, f, l), c_min, c_max;
    exp_check(sol_tonemap_lower_bound(display_curve, 1.0 / 510.0, &c_min), "lower bound");
    exp_check(sol_tonemap_inverse(display_curve, 1.0 - 1.0 / 510.0, &c_max), "upper bound");
    c_min *= l;
    c_max *= l;
    store_error e = {0, 0, 0, 0, 0};
    int n = scene->width * scene->height;
    pixel_slots *ps = pixel_slots_new();
    for (int start = 0; start < n; start += PIXEL_BLOCK) {
        int len = n - start < PIXEL_BLOCK ? n - start : PIXEL_BLOCK;
#pragma omp parallel for schedule(static)
        for (int j = 0; j < len; ++j) {
            int k = start + j;
            const float *px = scene->data + 3 * k;
            float scaled[3] = {(float)(px[0] * s), (float)(px[1] * s), (float)(px[2] * s)}, back[3];
            store(f, scaled, back);
            for (int i = 0; i < 3; ++i) {
                double c = back[i] / s;
                int want = display_code(px[i], l), got = display_code(c, l);
                ps->diff[3 * j + i] = abs(got - want);
                ps->rel[3 * j + i] = px[i] >= c_min && px[i] <= c_max ? fabs(c - px[i]) / px[i] : -1.0;
                if (out_display)
                    out_display->data[3 * k + i] = (float)(got / 255.0);
            }
        }
        for (int j = 0; j < len; ++j) { /* in pixel order, as the sequential loop summed */
            double worst = 0.0;
            for (int i = 0; i < 3; ++i) {
                worst = fmax(worst, ps->diff[3 * j + i]);
                e.mean_code += ps->diff[3 * j + i] / (3.0 * n);
                if (ps->rel[3 * j + i] >= 0.0)
                    e.max_rel_window = fmax(e.max_rel_window, ps->rel[3 * j + i]);
            }
            e.max_code = fmax(e.max_code, worst);
            e.pct_changed += worst >= 1.0 ? 100.0 / n : 0.0;
            e.pct_2codes += worst >= 2.0 ? 100.0 / n : 0.0;
        }
    }
    free(ps);
    return e;
}

/* Light accumulation: the scene split into `lights` positive parts blended additively into the
 * buffer, the sum re-quantised after every blend (RGBM blends by read-back: decode, add, encode, as
 * the talk's PS3 path does). Returns the mean display-code error over the scene. */
static double accumulate_lights(const sol_image *scene, format f, policy p, double l, int lights, double *max_code)
{
    double s = policy_scale(p, f, l), mean = 0.0;
    int n = scene->width * scene->height;
    *max_code = 0.0;
    pixel_slots *ps = pixel_slots_new();
    for (int start = 0; start < n; start += PIXEL_BLOCK) {
        int len = n - start < PIXEL_BLOCK ? n - start : PIXEL_BLOCK;
#pragma omp parallel for schedule(static)
        for (int j = 0; j < len; ++j) {
            int k = start + j;
            const float *px = scene->data + 3 * k;
            float acc[3] = {0, 0, 0};
            double weight_sum = 0.0, weights[64];
            for (int m = 0; m < lights; ++m) { /* deterministic uneven split */
                weights[m] = 0.2 + fmod((k * 0.6180339887 + m * 0.7548776662) * 7.0, 1.0);
                weight_sum += weights[m];
            }
            for (int m = 0; m < lights; ++m) {
                float sum[3];
                for (int i = 0; i < 3; ++i)
                    sum[i] = acc[i] + (float)(px[i] * s * weights[m] / weight_sum);
                store(f, sum, acc);
            }
            for (int i = 0; i < 3; ++i)
                ps->diff[3 * j + i] = abs(display_code(acc[i] / s, l) - display_code(px[i], l));
        }
        for (int j = 0; j < 3 * len; ++j) { /* in pixel order, as the sequential loop summed */
            mean += ps->diff[j] / (3.0 * n);
            *max_code = fmax(*max_code, ps->diff[j]);
        }
    }
    free(ps);
    return mean;
}

/* ---------------- parts of the experiment ---------------- */
static void write_display(const exp_run *exp, const char *name, const sol_image *img)
{
    exp_check(sol_png_write(exp_path(exp, name), img, 8), "writing %s", name);
}

/* The talk's "range scaling disabled / enabled" pair, for R11G11B10F, with amplified errors. */
static void comparison_images(const exp_run *exp, const sol_image *scene, const char *scene_label, double l)
{
    sol_image ref, off, on, diff;
    const int w = scene->width, h = scene->height;
    exp_check(sol_image_alloc(&ref, w, h, 3), "image");
    exp_check(sol_image_alloc(&off, w, h, 3), "image");
    exp_check(sol_image_alloc(&on, w, h, 3), "image");
    exp_check(sol_image_alloc(&diff, w * 2, h, 3), "image");
    for (int k = 0; k < w * h * 3; ++k)
        ref.data[k] = (float)(display_code(scene->data[k], l) / 255.0);
    measure_store(scene, R11G11B10F, RANGE_NONE, l, &off);
    measure_store(scene, R11G11B10F, RANGE_AVERAGE, l, &on);
    for (int y = 0; y < h; ++y) /* |difference| x 64: disabled left, enabled right */
        for (int x = 0; x < w; ++x)
            for (int i = 0; i < 3; ++i) {
                size_t k = 3 * ((size_t)y * w + x) + i;
                sol_image_pixel(&diff, x, y)[i] = fminf(1.0f, 64.0f * fabsf(off.data[k] - ref.data[k]));
                sol_image_pixel(&diff, x + w, y)[i] = fminf(1.0f, 64.0f * fabsf(on.data[k] - ref.data[k]));
            }
    char name[128];
    snprintf(name, sizeof name, "%s_reference.png", scene_label);
    write_display(exp, name, &ref);
    snprintf(name, sizeof name, "%s_r11g11b10f_scaling_disabled.png", scene_label);
    write_display(exp, name, &off);
    snprintf(name, sizeof name, "%s_r11g11b10f_scaling_enabled.png", scene_label);
    write_display(exp, name, &on);
    snprintf(name, sizeof name, "%s_r11g11b10f_error_x64_disabled_enabled.png", scene_label);
    write_display(exp, name, &diff);
    sol_image_free(&ref);
    sol_image_free(&off);
    sol_image_free(&on);
    sol_image_free(&diff);
}

/* Relative quantisation step of every format over the stored value. */
static double relative_step(format f, double v)
{
    int e2;
    (void)frexp(v, &e2);
    int e = e2 - 1;
    switch (f) {
    case FP16: return (v < 0x1p-14 ? 0x1p-24 : ldexp(1.0, e - 10)) / v;
    case R11G11B10F: return (v < 0x1p-14 ? 0x1p-20 : ldexp(1.0, e - 6)) / v;
    case RGBM8: return ceil(v / rgbm_range * 255.0) / 255.0 * rgbm_range / 255.0 / v;
    case RGB10_0_2: return 2.0 / 1023.0 / v;
    default: return 1.0 / 255.0 / v;
    }
}

static void precision_plot(const exp_run *exp)
{
    FILE *f = exp_open(exp, "relative_step.csv");
    fputs("value", f);
    for (int k = 0; k < FORMAT_COUNT; ++k) /* quoted: a name such as "RGBM (RGBA8, range 8)" has a comma */
        fprintf(f, ",\"%s\"", format_name[k]);
    fputc('\n', f);
    for (int i = 0; i <= 600; ++i) {
        double v = pow(10.0, -7.0 + 12.0 * i / 600.0);
        fprintf(f, "%.6e", v);
        for (int k = 0; k < FORMAT_COUNT; ++k)
            v <= format_max[k] ? fprintf(f, ",%.6e", relative_step((format)k, v)) : fprintf(f, ",");
        fputc('\n', f);
    }
    fclose(f);
    /* titles from the names, not columnheader(): gnuplot cuts a quoted header at its comma */
    char clauses[2048] = "";
    for (int k = 0; k < FORMAT_COUNT; ++k) {
        size_t used = strlen(clauses);
        snprintf(clauses + used, sizeof clauses - used, "%s'relative_step.csv' using 1:%d with lines lw 2 title '%s'",
                 k ? ", " : "", k + 2, format_name[k]);
    }
    exp_plot(exp, "relative_step",
             "set datafile separator comma\nset logscale xy\nset grid\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
             "set xlabel 'stored value'\nset ylabel 'quantisation step / value'\nset yrange [1e-4:10]\n"
             "set key bottom left\nplot %s", clauses);
}

/* Mean display-code error of each format and policy as the scene's absolute level changes. */
static void level_sweep(const exp_run *exp, const sol_image *base, double *r11_none_worst, double *r11_avg_worst)
{
    const int steps = exp->quick ? 9 : 33;
    FILE *f = exp_open(exp, "level_sweep.csv");
    fputs("level", f);
    for (int k = 0; k < FORMAT_COUNT; ++k)
        for (int p = 0; p < POLICY_COUNT; ++p)
            fprintf(f, ",\"%s / %s\"", format_name[k], p == RANGE_NONE ? "none" : p == RANGE_AVERAGE ? "c/l" : "window");
    fputc('\n', f);
    sol_image scaled;
    exp_check(sol_image_alloc(&scaled, SCENE_W, SCENE_H, 3), "image");
    *r11_none_worst = *r11_avg_worst = 0.0;
    for (int i = 0; i < steps; ++i) {
        exp_progress("d9 level sweep", (size_t)i, (size_t)steps);
        double level = pow(10.0, -8.0 + 16.0 * i / (steps - 1));
        for (int k = 0; k < SCENE_W * SCENE_H * 3; ++k)
            scaled.data[k] = (float)(base->data[k] * level);
        double l = log_average_luminance(&scaled);
        fprintf(f, "%.4e", level);
        for (int k = 0; k < FORMAT_COUNT; ++k)
            for (int p = 0; p < POLICY_COUNT; ++p) {
                store_error e = measure_store(&scaled, (format)k, (policy)p, l, NULL);
                fprintf(f, ",%.5f", e.mean_code);
                if (k == R11G11B10F && p == RANGE_NONE)
                    *r11_none_worst = fmax(*r11_none_worst, e.mean_code);
                if (k == R11G11B10F && p == RANGE_AVERAGE)
                    *r11_avg_worst = fmax(*r11_avg_worst, e.mean_code);
            }
        fputc('\n', f);
    }
    exp_progress_done("d9 level sweep");
    fclose(f);
    sol_image_free(&scaled);
    exp_plot(exp, "level_sweep",
             "set datafile separator comma\nset logscale x\nset grid\nset format x '10^{%%L}'\n"
             "set xlabel 'absolute level of the interior scene (x 1)'\nset ylabel 'mean display-code error'\n"
             "set key outside right\nset logscale y\nset yrange [1e-3:200]\n"
             "plot 'level_sweep.csv' using 1:($5+1e-3) with lines lw 2 title 'R11G11B10F, no scaling', "
             "'' using 1:($6+1e-3) with lines lw 2 title 'R11G11B10F, c/l', "
             "'' using 1:($8+1e-3) with lines lw 2 title 'RGBM, no scaling', "
             "'' using 1:($10+1e-3) with lines lw 2 title 'RGBM, window', "
             "'' using 1:($3+1e-3) with lines dt 2 title 'RGBA16F, c/l', "
             "'' using 1:($13+1e-3) with lines dt 3 title 'RGB10 0..2, window'");
}

/* Tesseract's world-space RGB8 normals (S9): n * 0.5 + 0.5 per channel at 8 bits, decoded by
 * normalising; angular error over uniformly distributed directions (R2 points on the sphere). */
static void rgb8_normals(const exp_run *exp, double *mean_deg, double *max_deg)
{
    const int n = exp->quick ? 100000 : 2000000;
    enum { CHUNKS = 64 };
    double part_sum[CHUNKS] = {0}, part_max[CHUNKS] = {0};
#pragma omp parallel for schedule(static)
    for (int ch = 0; ch < CHUNKS; ++ch)
        for (int i = ch; i < n; i += CHUNKS) {
            double u, v, dir[3], back[3];
            sol_r2_point((uint64_t)i, &u, &v);
            sol_sphere_uniform(u, v, dir);
            for (int c = 0; c < 3; ++c)
                back[c] = sol_unorm_decode(sol_unorm_encode(dir[c] * 0.5 + 0.5, 8), 8) * 2.0 - 1.0;
            double deg = sol_angle3(dir, back) * (180.0 / M_PI);
            part_sum[ch] += deg;
            part_max[ch] = fmax(part_max[ch], deg);
        }
    *mean_deg = *max_deg = 0.0;
    for (int ch = 0; ch < CHUNKS; ++ch) {
        *mean_deg += part_sum[ch] / n;
        *max_deg = fmax(*max_deg, part_max[ch]);
    }
    exp_table *t = exp_table_new("World-space RGB8 normals (n/2 + 1/2 in UNORM8, normalised on decode)",
                                 "directions,mean angular error (deg),max angular error (deg)");
    exp_table_row(t, "%d|%.4f|%.4f", n, *mean_deg, *max_deg);
    exp_table_write(t, exp, "rgb8_normals");
}

/* The float formats place their window from the average alone: the window policy is not run. */
static int policy_applies(format f, policy p)
{
    return !((f == FP16 || f == R11G11B10F) && p == RANGE_WINDOW);
}

/* Per format and policy: worst scene's max code error and mean of the mean code errors. */
typedef struct format_stats {
    double worst_max[FORMAT_COUNT][POLICY_COUNT], mean_mean[FORMAT_COUNT][POLICY_COUNT];
} format_stats;

/* One scene through every format and policy: a table row each, folded into `st`. */
static void scene_format_rows(exp_table *t, const sol_image *img, scene_id id, double l, format_stats *st)
{
    for (int f = 0; f < FORMAT_COUNT; ++f)
        for (int p = 0; p < POLICY_COUNT; ++p) {
            if (!policy_applies((format)f, (policy)p))
                continue;
            store_error e = measure_store(img, (format)f, (policy)p, l, NULL);
            exp_table_row(t, "%s|%.3g|%s|%d|%s|%.0f|%.3f|%.2f|%.2f|%.4f", scene_name[id], l, format_name[f],
                          format_bits[f], policy_name[p], e.max_code, e.mean_code, e.pct_changed, e.pct_2codes,
                          e.max_rel_window);
            st->worst_max[f][p] = fmax(st->worst_max[f][p], e.max_code);
            st->mean_mean[f][p] += e.mean_code / SCENE_COUNT;
        }
}

static void format_error_table(const exp_run *exp, const sol_image scenes[SCENE_COUNT], format_stats *st)
{
    exp_table *t = exp_table_new("HDR scenes stored in each format (HBD filmic, 8-bit sRGB display codes)",
                                 "scene,l,format,bits/px,range policy,max code error,mean code error,% px changed,"
                                 "% px >= 2 codes,max rel. error in c_min..c_max");
    for (int id = 0; id < SCENE_COUNT; ++id) {
        const sol_image *img = &scenes[id];
        double l = log_average_luminance(img);
        scene_format_rows(t, img, (scene_id)id, l, st);
        if (id != SKY_SUN) /* the sky is all bright: nothing to see in the pair */
            comparison_images(exp, img, scene_name[id], l);
    }
    exp_table_write(t, exp, "format_errors");
}

static void format_summary_table(const exp_run *exp, const format_stats *st)
{
    exp_table *summary = exp_table_new("Formats over the four scenes", "format,bits/px,range policy,"
                                       "worst max code error,average mean code error");
    for (int f = 0; f < FORMAT_COUNT; ++f)
        for (int p = 0; p < POLICY_COUNT; ++p)
            if (policy_applies((format)f, (policy)p))
                exp_table_row(summary, "%s|%d|%s|%.0f|%.3f", format_name[f], format_bits[f], policy_name[p],
                              st->worst_max[f][p], st->mean_mean[f][p]);
    exp_table_write(summary, exp, "format_summary");
}

/* Each format blends with its better policy in format_summary: the window for RGBM, c / l for the rest. */
static policy accumulation_policy(format f)
{
    return f == RGBM8 ? RANGE_WINDOW : RANGE_AVERAGE;
}

/* Additive light accumulation in the interior scene; returns the mean code errors with 16 lights
 * of R11G11B10F and RGBA16F (the D9 row). */
static void light_accumulation_table(const exp_run *exp, const sol_image *interior, double *r11_many, double *fp16_many)
{
    exp_table *acc = exp_table_new("Additive light accumulation in the buffer (interior scene, re-quantised per blend)",
                                   "format,range policy,lights,max code error,mean code error");
    const int light_counts[] = {1, 4, 16, 64};
    for (int f = 0; f < FORMAT_COUNT; ++f) {
        policy p = accumulation_policy((format)f);
        for (size_t c = 0; c < sizeof light_counts / sizeof light_counts[0]; ++c) {
            if (exp->quick && light_counts[c] > 16)
                continue;
            double max_code, mean = accumulate_lights(interior, (format)f, p, log_average_luminance(interior),
                                                      light_counts[c], &max_code);
            exp_table_row(acc, "%s|%s|%d|%.0f|%.3f", format_name[f], policy_name[p], light_counts[c], max_code, mean);
            if (light_counts[c] == 16 && f == R11G11B10F)
                *r11_many = mean;
            if (light_counts[c] == 16 && f == FP16)
                *fp16_many = mean;
        }
    }
    exp_table_write(acc, exp, "light_accumulation");
}

static void claim_d9(const exp_run *exp, const format_stats *st, double r11_many, double fp16_many)
{
    char fig[256];
    snprintf(fig, sizeof fig,
             "32 bpp both; worst max / mean code error: RGBM+window %.0f / %.3f, R11G11B10F unscaled %.0f / %.3f, "
             "R11G11B10F c/l %.0f / %.3f",
             st->worst_max[RGBM8][RANGE_WINDOW], st->mean_mean[RGBM8][RANGE_WINDOW], st->worst_max[R11G11B10F][RANGE_NONE],
             st->mean_mean[R11G11B10F][RANGE_NONE], st->worst_max[R11G11B10F][RANGE_AVERAGE],
             st->mean_mean[R11G11B10F][RANGE_AVERAGE]);
    int r11_worse = st->mean_mean[R11G11B10F][RANGE_NONE] > st->mean_mean[RGBM8][RANGE_WINDOW];
    char acc_note[160];
    snprintf(acc_note, sizeof acc_note, "; 16 lights blended: R11G11B10F mean code error %.3f vs RGBA16F %.3f",
             r11_many, fp16_many);
    strncat(fig, acc_note, sizeof fig - strlen(fig) - 1);
    exp_claim(exp, "D9", "RGBK at LDR bandwidth; R11G11B10F same bandwidth, not enough precision for linear HDR",
              fig, "qualitative", r11_worse ? EXP_REPRODUCED : EXP_DIFFERS_EXPLAINED,
              "four synthetic scenes (interior, night street, sky with sun, dark cave; float EXR files) through "
              "each 32-bit format, HBD "
              "filmic at the scene's log-average, errors in 8-bit sRGB display codes: R11G11B10F's relative step "
              "(2^-6, blue 2^-5) costs about a code once scaled by 1/l, more where an unscaled dark scene falls into "
              "its denormals (dark_cave error images) and when lights are blended into it (table light_accumulation, "
              "an order of magnitude above RGBA16F); RGBM at the same 32 bits is usable only with range scaling and "
              "is not more precise (table format_summary)");
}

static void claim_d10(const exp_run *exp, double r11_none, double r11_avg)
{
    char fig[256];
    snprintf(fig, sizeof fig, "R11G11B10F mean code error over levels 1e-8..1e8: %.3f unscaled vs %.3f scaled by 1/l",
             r11_none, r11_avg);
    exp_claim(exp, "D10", "range scaling from the average luminance improves precision", fig, "qualitative",
              r11_avg < r11_none ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the interior scene at absolute levels 1e-8..1e8: scaling the stored range by 1/l keeps the error flat, "
              "without it the error grows once values fall into denormals or above 65024 (plot level_sweep)");
}

static void claim_s9_rgb10(const exp_run *exp, const format_stats *st)
{
    char fig[256];
    snprintf(fig, sizeof fig,
             "RGB10 0..2 step %.5f vs RGB8 %.5f; mean code error c/l %.3f vs %.3f, window %.3f vs %.3f; "
             "R11G11B10F c/l %.3f",
             sol_rgb10_scaled_decode(1) - sol_rgb10_scaled_decode(0), sol_unorm_decode(1, 8), st->mean_mean[RGB10_0_2][RANGE_AVERAGE], st->mean_mean[RGB8][RANGE_AVERAGE],
             st->mean_mean[RGB10_0_2][RANGE_WINDOW], st->mean_mean[RGB8][RANGE_WINDOW],
             st->mean_mean[R11G11B10F][RANGE_AVERAGE]);
    int rgb10_better = st->mean_mean[RGB10_0_2][RANGE_WINDOW] < st->mean_mean[RGB8][RANGE_WINDOW] &&
                       st->mean_mean[RGB10_0_2][RANGE_AVERAGE] < st->mean_mean[RGB8][RANGE_AVERAGE];
    exp_claim(exp, "S9", "RGB10 scaled to 0..2: overbright and better precision than RGB8", fig, "qualitative",
              rgb10_better ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "half the step of RGB8 with twice the headroom; R11G11B10F (the preferred format) keeps a constant "
              "relative step of 2^-6 (2^-5 in blue) instead (plot relative_step)");
}

/* Measures the RGB8 normals (table rgb8_normals) and writes their S9 row. */
static void claim_s9_normals(const exp_run *exp)
{
    double normal_mean, normal_max;
    rgb8_normals(exp, &normal_mean, &normal_max);
    /* Rounding n/2 + 1/2 to 8 bits moves each component of n by at most 1/255, so the stored vector is
     * within sqrt(3)/255 of the unit normal and the decoded direction within asin(sqrt(3)/255) of it. */
    const double bound_deg = asin(sqrt(3.0) / 255.0) * 180.0 / M_PI;
    char fig[256];
    snprintf(fig, sizeof fig, "RGB8 world-space normals: mean %.3f deg, max %.3f deg (rounding bound %.3f deg)",
             normal_mean, normal_max, bound_deg);
    exp_number(exp, "S9-rgb8-normals-mean-deg", "%.3f", normal_mean);
    exp_number(exp, "S9-rgb8-normals-max-deg", "%.3f", normal_max);
    exp_number(exp, "S9-rgb8-normals-bound-deg", "%.3f", bound_deg);
    exp_claim(exp, "S9", "world-space RGB8 normals", fig, "max within the rounding bound asin(sqrt(3)/255)",
              isfinite(normal_max) && normal_max <= bound_deg ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the notes make no quantitative claim; this is the precision the layout buys: n/2 + 1/2 in three UNORM8 "
              "channels, normalised on decode, over uniformly distributed directions, checked against the worst case "
              "of per-component rounding");
}

/* ---- --bench: the storage format as a precision choice, error against the cost of a store ---- */
typedef struct store_timing {
    const sol_image *scene;
    format f;
    double scale;
    double sink;
} store_timing;

static void time_store(void *ctx)
{
    store_timing *c = ctx;
    const int n = c->scene->width * c->scene->height;
    double acc = 0.0;
    for (int k = 0; k < n; ++k) {
        const float *px = c->scene->data + 3 * k;
        float scaled[3] = {(float)(px[0] * c->scale), (float)(px[1] * c->scale), (float)(px[2] * c->scale)}, back[3];
        store(c->f, scaled, back);
        acc += back[0];
    }
    c->sink += acc; /* keeps the work observable */
}

/* Written only with --bench (format_knobs): every format and applicable range policy over the four
 * scenes (format_summary's figures) with the bits per pixel and the core-ns per pixel of the
 * encode + decode round trip (one thread, interior scene): the formats are each other's peers. */
static void bench_formats(const exp_run *exp, const sol_image scenes[SCENE_COUNT])
{
    exp_table *t = exp_table_new("HDR storage formats and range policies (the precision choice of D9/D10/S9): display-code "
                                 "error over the four scenes and time per pixel of encode + decode (one thread)",
                                 "format,bits/px,range policy,worst max code error,average mean code error,"
                                 "core-ns per pixel");
    const sol_image *interior = &scenes[INTERIOR_WINDOW];
    const double l_interior = log_average_luminance(interior);
    for (int f = 0; f < FORMAT_COUNT; ++f)
        for (int p = 0; p < POLICY_COUNT; ++p) {
            if (!policy_applies((format)f, (policy)p))
                continue;
            double worst = 0.0, mean = 0.0;
            for (int id = 0; id < SCENE_COUNT; ++id) {
                store_error e = measure_store(&scenes[id], (format)f, (policy)p, log_average_luminance(&scenes[id]), NULL);
                worst = fmax(worst, e.max_code);
                mean += e.mean_code / SCENE_COUNT;
            }
            store_timing c = {interior, (format)f, policy_scale((policy)p, (format)f, l_interior), 0.0};
            double ns = exp_cpu_time_per_item_ns(time_store, &c, (size_t)interior->width * (size_t)interior->height,
                                                 exp->quick ? 3 : 5);
            exp_table_row(t, "%s|%d|%s|%.0f|%.3f|%.1f", format_name[f], format_bits[f], policy_name[p], worst, mean, ns);
        }
    exp_table_write(t, exp, "format_knobs");
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d9_d10_s9_hdr_formats", argc, argv);
    sol_image scenes[SCENE_COUNT];
    load_scenes(&exp, scenes);
    if (exp.bench) { /* the formats are fixed; the choice among them is the precision knob */
        bench_formats(&exp, scenes);
        for (int id = 0; id < SCENE_COUNT; ++id)
            sol_image_free(&scenes[id]);
        return 0;
    }
    format_stats st = {{{0}}, {{0}}};
    format_error_table(&exp, scenes, &st);
    format_summary_table(&exp, &st);
    double r11_many = 0.0, fp16_many = 0.0;
    light_accumulation_table(&exp, &scenes[INTERIOR_WINDOW], &r11_many, &fp16_many);
    precision_plot(&exp);
    double r11_none = 0.0, r11_avg = 0.0;
    level_sweep(&exp, &scenes[INTERIOR_WINDOW], &r11_none, &r11_avg);
    claim_d9(&exp, &st, r11_many, fp16_many);
    claim_d10(&exp, r11_none, r11_avg);
    claim_s9_rgb10(&exp, &st);
    claim_s9_normals(&exp);
    for (int id = 0; id < SCENE_COUNT; ++id)
        sol_image_free(&scenes[id]);
    return 0;
}
