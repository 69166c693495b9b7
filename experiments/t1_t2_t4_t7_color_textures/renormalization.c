/* renormalization.c - range renormalisation through BC1 (T1, T2), sol's BC1 encoder next to
 * libsquish, and the encoder's accuracy vs time.
 *
 * Talk, slides "Histogram renormalization": the color range is stretched before DXT compression
 * and restored in the shader with two constants, which "significantly reduces the color banding
 * and deviation introduced by 5:6:5 quantization and block compression" of dark textures under
 * strong HDR light; renormalising an 8 b/ch source "would produce a quantization in the
 * renormalized histogram, thus leading to a larger color distortion".
 *
 * Textures are stored in sRGB gamma (as albedo textures usually are); the light multiplies the
 * decoded linear albedo; the display shows sRGB(min(1, light * albedo)). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textures_exp.h"

static const double lights[] = {1.0, 8.0, 16.0, 64.0};
enum { LIGHTS = sizeof lights / sizeof lights[0], LIGHT_16 = 2 };

static sol_image image_like(const sol_image *src)
{
    sol_image out = {0};
    exp_check(sol_image_alloc(&out, src->width, src->height, src->channels), "allocating an image");
    memcpy(out.data, src->data, sizeof *src->data * (size_t)src->width * src->height * src->channels);
    return out;
}

static double geometric_mean(double sum_of_logs, int n) { return n > 0 ? exp(sum_of_logs / n) : 0.0; }

static size_t values(const sol_image *im) { return (size_t)im->width * im->height * im->channels; }

/* The texture as stored: sRGB-encoded linear albedo, 16-bit (or 8-bit when `bits8`). */
static sol_image stored_of(const sol_image *linear, int bits8)
{
    sol_image s = image_like(linear);
    for (size_t i = 0; i < values(&s); ++i) {
        double e = sol_srgb_encode(s.data[i]);
        s.data[i] = (float)sol_unorm_decode(sol_unorm_encode(e, bits8 ? 8 : 16), bits8 ? 8 : 16);
    }
    return s;
}

/* Stored image -> (renormalise) -> BC1 (sol, default effort) -> decode -> (restore). */
static sol_image through_bc1(const sol_image *stored, int renorm)
{
    sol_image in = image_like(stored), out;
    sol_renorm range;
    if (renorm) {
        exp_check(sol_renorm_fit(&in, &range), "renorm fit");
        exp_check(sol_renorm_apply(&range, &in), "renorm apply");
    }
    uint8_t *blocks = malloc(sol_bc1_size(in.width, in.height));
    if (!blocks)
        exp_die("out of memory");
    exp_check(sol_bc1_encode(&in, NULL, blocks), "BC1 encode");
    exp_check(sol_bc1_decode(blocks, in.width, in.height, &out), "BC1 decode");
    if (renorm)
        exp_check(sol_renorm_undo(&range, &out), "renorm undo");
    free(blocks);
    sol_image_free(&in);
    return out;
}

typedef struct lit_error {
    double rms, max, log_rms;
    int levels; /* distinct display codes of the green channel */
} lit_error;

static lit_error lit_compare(const sol_image *stored, const sol_image *ref_stored, double light)
{
    lit_error e = {0};
    char seen[256] = {0};
    double sq = 0.0, lsq = 0.0;
    size_t n = values(stored);
    for (size_t i = 0; i < n; ++i) {
        double lin = sol_srgb_decode(stored->data[i]), ref = sol_srgb_decode(ref_stored->data[i]);
        double d = display255(lin, light) - display255(ref, light);
        double l = log2((lin + 1e-4) / (ref + 1e-4));
        sq += d * d;
        lsq += l * l;
        e.max = fmax(e.max, fabs(d));
        if (i % 3 == 1) {
            int code = (int)lrint(display255(lin, light));
            e.levels += !seen[code];
            seen[code] = 1;
        }
    }
    e.rms = sqrt(sq / (double)n);
    e.log_rms = sqrt(lsq / (double)n);
    return e;
}

/* Distinct renormalised green values, and the largest gap between neighbours (in 1/255). */
static void renorm_histogram(const sol_image *stored, int *levels, double *max_gap)
{
    sol_image in = image_like(stored);
    sol_renorm range;
    exp_check(sol_renorm_fit(&in, &range), "renorm fit");
    exp_check(sol_renorm_apply(&range, &in), "renorm apply");
    static char seen[65536];
    memset(seen, 0, sizeof seen);
    for (size_t i = 1; i < values(&in); i += 3)
        seen[sol_unorm_encode(in.data[i], 16)] = 1;
    *levels = 0;
    *max_gap = 0.0;
    int last = -1;
    for (int c = 0; c < 65536; ++c)
        if (seen[c]) {
            ++*levels;
            if (last >= 0)
                *max_gap = fmax(*max_gap, (c - last) / 65535.0 * 255.0);
            last = c;
        }
    sol_image_free(&in);
}

static void write_figure(const exp_run *exp, const char *file, const sol_image *ref, const sol_image *plain, const sol_image *renorm,
                         double light)
{
    const int size = ref->width < 128 ? ref->width : 128, scale = 2;
    const sol_image *panels[3] = {ref, plain, renorm};
    sol_image fig = {0};
    exp_check(sol_image_alloc(&fig, 3 * size * scale, size * scale, 3), "allocating the figure");
    for (int p = 0; p < 3; ++p)
        for (int y = 0; y < size * scale; ++y)
            for (int x = 0; x < size * scale; ++x)
                for (int c = 0; c < 3; ++c) {
                    double lin = sol_srgb_decode(sol_image_pixel(panels[p], x / scale, y / scale)[c]);
                    sol_image_pixel(&fig, p * size * scale + x, y)[c] = (float)(display255(lin, light) / 255.0);
                }
    exp_check(sol_png_write(exp_path(exp, file), &fig, 8), "writing the figure");
    sol_image_free(&fig);
}

/* ---- encoders side by side: sol's effort levels and libsquish, quality and time per texel ---- */

typedef struct encoder {
    const char *name;
    int squish_effort;    /* >= 0: libsquish with this effort, 8-bit input */
    sol_bc1_effort effort; /* sol */
    int iterations;
    int input8; /* sol fed the same 8-bit input as libsquish */
} encoder;

static const encoder encoders[] = {
    {"sol range (bounding box)", -1, SOL_BC1_RANGE, 0, 0},
    {"sol PCA range", -1, SOL_BC1_PCA, 0, 0},
    {"sol PCA + 1 least-squares round", -1, SOL_BC1_PCA_REFINE, 1, 0},
    {"sol PCA + 8 least-squares rounds", -1, SOL_BC1_PCA_REFINE, 8, 0},
    {"sol cluster fit, 1 ordering", -1, SOL_BC1_CLUSTER, 1, 0},
    {"sol cluster fit, 4 orderings", -1, SOL_BC1_CLUSTER, 4, 0},
    {"sol cluster fit + endpoint search", -1, SOL_BC1_CLUSTER_SEARCH, 4, 0},
    {"sol cluster fit, 4 orderings (8-bit input)", -1, SOL_BC1_CLUSTER, 4, 1},
    {"sol cluster fit + endpoint search (8-bit input)", -1, SOL_BC1_CLUSTER_SEARCH, 4, 1},
    {"libsquish range fit (8-bit input)", 0, 0, 0, 1},
    {"libsquish cluster fit (8-bit input)", 1, 0, 0, 1},
    {"libsquish iterative cluster fit (8-bit input)", 2, 0, 0, 1},
};
enum { ENCODERS = sizeof encoders / sizeof encoders[0] };

typedef struct encode_job {
    const encoder *enc;
    const sol_image *input; /* float input (8-bit values when enc->input8) */
    uint8_t *rgba;          /* 8-bit copy for libsquish */
    uint8_t *blocks;
} encode_job;

static void run_encode(void *ctx)
{
    encode_job *j = ctx;
    if (j->enc->squish_effort >= 0) {
        squish_bc1_encode(j->rgba, j->input->width, j->input->height, j->blocks, j->enc->squish_effort);
        return;
    }
    sol_bc1_options o = {.effort = j->enc->effort, .iterations = j->enc->iterations};
    exp_check(sol_bc1_encode(j->input, &o, j->blocks), "BC1 encode");
}

/* RMS error in 8-bit units of the decoded blocks against the float (16-bit) target. */
static double stored_rms(const uint8_t *blocks, const sol_image *target)
{
    sol_image dec;
    exp_check(sol_bc1_decode(blocks, target->width, target->height, &dec), "BC1 decode");
    double sq = 0.0;
    for (int y = 0; y < target->height; ++y)
        for (int x = 0; x < target->width; ++x)
            for (int c = 0; c < 3; ++c) {
                double d = (sol_image_pixel(&dec, x, y)[c] - sol_image_pixel(target, x, y)[c]) * 255.0;
                sq += d * d;
            }
    sol_image_free(&dec);
    return sqrt(sq / (3.0 * target->width * target->height));
}

static void compare_encoders(const exp_run *exp, sol_image *targets, int count)
{
    double rms[ENCODERS] = {0}, ns[ENCODERS] = {0};
    size_t texels = 0;
    for (int t = 0; t < count; ++t)
        texels += (size_t)targets[t].width * targets[t].height;
    int threads = omp_get_max_threads();
    omp_set_num_threads(1); /* libsquish is single-threaded: time both on one thread */
    for (int t = 0; t < count; ++t) {
        const sol_image *target = &targets[t];
        size_t n = (size_t)target->width * target->height;
        sol_image in8 = image_like(target);
        uint8_t *rgba = malloc(4 * n), *blocks = malloc(sol_bc1_size(target->width, target->height));
        if (!rgba || !blocks)
            exp_die("out of memory");
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) {
                rgba[4 * i + c] = (uint8_t)sol_unorm_encode(target->data[3 * i + c], 8);
                in8.data[3 * i + c] = rgba[4 * i + c] / 255.0f;
            }
            rgba[4 * i + 3] = 255;
        }
        for (int e = 0; e < ENCODERS; ++e) {
            encode_job job = {&encoders[e], encoders[e].input8 ? &in8 : target, rgba, blocks};
            double per = exp_cpu_time_per_item_ns(run_encode, &job, n, exp->quick ? 1 : 3);
            ns[e] += per * (double)n / (double)texels;
            double r = stored_rms(blocks, target);
            rms[e] += r * r * (double)n / (double)texels;
        }
        sol_image_free(&in8);
        free(rgba);
        free(blocks);
    }
    omp_set_num_threads(threads);
    exp_table *tab = exp_table_new("BC1 encoders on the renormalised dark textures (one thread): RMS error vs the "
                                   "16-bit target in 8-bit units, and time",
                                   "encoder,RMS error,ns per texel");
    FILE *f = exp_open(exp, "encoder_points.csv");
    fputs("encoder,rms,ns_per_texel,is_squish\n", f);
    for (int e = 0; e < ENCODERS; ++e) {
        exp_table_row(tab, "%s|%.4f|%.1f", encoders[e].name, sqrt(rms[e]), ns[e]);
        fprintf(f, "\"%s\",%.5f,%.3f,%d\n", encoders[e].name, sqrt(rms[e]), ns[e], encoders[e].squish_effort >= 0);
    }
    fclose(f);
    exp_table_write(tab, exp, "encoders");
    if (!exp->bench)
        exp_plot(exp, "encoders",
                 "set datafile separator comma\nset grid\nset logscale x\nset key top right\n"
                 "set xlabel 'ns per texel (one thread)'\nset ylabel 'RMS error (8-bit units)'\n"
                 "plot 'encoder_points.csv' skip 1 using ($4==0?$3:1/0):2 with points pt 7 ps 1.2 title 'sol', "
                 "'' skip 1 using ($4==1?$3:1/0):2 with points pt 5 ps 1.2 title 'libsquish'");
}

void run_renormalization(const exp_run *exp)
{
    tex_input *set;
    int count = inputs_dark_set(&set, exp->quick);
    sol_image *renorm_targets = calloc((size_t)count, sizeof *renorm_targets);
    if (!renorm_targets)
        exp_die("out of memory");
    for (int t = 0; t < count; ++t) {
        sol_image s = stored_of(&set[t].linear, 0);
        sol_renorm range;
        exp_check(sol_renorm_fit(&s, &range), "renorm fit");
        exp_check(sol_renorm_apply(&range, &s), "renorm apply");
        renorm_targets[t] = s;
    }
    compare_encoders(exp, renorm_targets, count < 4 ? count : 4); /* timing: the first four textures */
    for (int t = 0; t < count; ++t)
        sol_image_free(&renorm_targets[t]);
    free(renorm_targets);
    if (exp->bench) {
        inputs_free(set, count);
        return;
    }

    exp_table *t2 = exp_table_new("T2: dark textures through BC1 under a light scale, without and with renormalisation "
                                  "(display codes; green-channel levels)",
                                  "texture,light,RMS plain,RMS renorm,max plain,max renorm,log2 RMS plain,"
                                  "log2 RMS renorm,levels reference,levels plain,levels renorm");
    exp_table *t1 = exp_table_new("T1: renormalising a 16-bit vs an 8-bit source (light x16)",
                                  "texture,source bits,renormalised green levels (16-bit src),(8-bit src),"
                                  "largest gap 8-bit src (1/255),RMS 16-bit renorm,RMS 8-bit renorm,RMS 8-bit plain,"
                                  "RMS 8-bit src no BC1 (control),8-bit renorm / independent sum");
    int t2_wins = 0, t2_cases = 0, t1_worse = 0, t1_excess = 0, game_figure = 0;
    double ratio_sum = 0.0, t1_ratio_sum = 0.0, t1_excess_sum = 0.0, control_max = 0.0, gap_min = INFINITY, gap_max = 0.0;
    for (int k = 0; k < count; ++k) {
        sol_image ref = stored_of(&set[k].linear, 0), src8 = stored_of(&set[k].linear, 1);
        sol_image plain = through_bc1(&ref, 0), renorm = through_bc1(&ref, 1);
        sol_image plain8 = through_bc1(&src8, 0), renorm8 = through_bc1(&src8, 1);
        for (int l = 0; l < LIGHTS; ++l) {
            lit_error a = lit_compare(&plain, &ref, lights[l]), b = lit_compare(&renorm, &ref, lights[l]);
            lit_error r = lit_compare(&ref, &ref, lights[l]);
            exp_table_row(t2, "%s|x%.0f|%.3f|%.3f|%.1f|%.1f|%.4f|%.4f|%d|%d|%d", set[k].name, lights[l], a.rms, b.rms,
                          a.max, b.max, a.log_rms, b.log_rms, r.levels, a.levels, b.levels);
            if (lights[l] >= 8.0) {
                ++t2_cases;
                t2_wins += b.rms < a.rms;
                ratio_sum += log(a.rms / b.rms);
            }
        }
        int levels16, levels8;
        double gap16, gap8;
        renorm_histogram(&ref, &levels16, &gap16);
        renorm_histogram(&src8, &levels8, &gap8);
        lit_error e16 = lit_compare(&renorm, &ref, lights[LIGHT_16]), e8 = lit_compare(&renorm8, &ref, lights[LIGHT_16]);
        lit_error p8 = lit_compare(&plain8, &ref, lights[LIGHT_16]);
        /* Control: the 8-bit source without BC1 (renormalise + undo is the identity without a codec),
         * so c8 is the error the 8-bit source brings by itself. If the 5:6:5 stage and the source's
         * quantisation were independent, the renormalised 8-bit source would have RMS
         * sqrt(e16^2 + c8^2); a ratio above 1 is the interaction the talk describes. */
        lit_error c8 = lit_compare(&src8, &ref, lights[LIGHT_16]);
        double independent = sqrt(e16.rms * e16.rms + c8.rms * c8.rms);
        double excess = independent > 0.0 ? e8.rms / independent : 1.0;
        exp_table_row(t1, "%s|%d|%d|%d|%.2f|%.3f|%.3f|%.3f|%.3f|%.3f", set[k].name, set[k].source_bits, levels16, levels8,
                      gap8, e16.rms, e8.rms, p8.rms, c8.rms, excess);
        t1_worse += e8.rms > e16.rms;
        t1_ratio_sum += log(e8.rms / e16.rms);
        t1_excess += excess > 1.0;
        t1_excess_sum += log(excess);
        control_max = fmax(control_max, c8.rms);
        gap_min = fmin(gap_min, gap8);
        gap_max = fmax(gap_max, gap8);
        if (k == 1) /* the slide's figure: a synthetic 16-bit texture and the first game texture */
            write_figure(exp, "renormalization_x16.png", &ref, &plain, &renorm, lights[LIGHT_16]);
        if (set[k].source_bits == 8 && !game_figure++)
            write_figure(exp, "renormalization_x16_game.png", &ref, &plain, &renorm, lights[LIGHT_16]);
        sol_image *all[6] = {&ref, &src8, &plain, &renorm, &plain8, &renorm8};
        for (int i = 0; i < 6; ++i)
            sol_image_free(all[i]);
    }
    exp_table_write(t2, exp, "t2_renormalization");
    exp_table_write(t1, exp, "t1_source_bits");
    char fig[256];
    snprintf(fig, sizeof fig, "renormalised BC1 has lower display RMS in %d of %d (texture, light >= x8) cases; "
                              "geometric-mean error ratio plain/renorm %.2f",
             t2_wins, t2_cases, geometric_mean(ratio_sum, t2_cases));
    exp_claim(exp, "T2", "renormalisation before DXT1 significantly reduces banding and color deviation of dark textures "
                         "under strong light",
              fig, "qualitative: lower error in every case", t2_wins == t2_cases ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "%d dark textures (3 synthetic 16-bit, the rest colobot-common-textures game textures darkened in float), "
              "sRGB storage, sol's cluster-fit BC1, lights x8-x64, display sRGB(min(1, light albedo)); figure "
              "renormalization_x16.png: reference, plain BC1, renormalised BC1",
              count);
    exp_number(exp, "T2-textures", "%d", count);
    exp_number(exp, "T2-wins", "%d", t2_wins);
    exp_number(exp, "T2-cases", "%d", t2_cases);
    exp_number(exp, "T2-ratio", "%.2f", geometric_mean(ratio_sum, t2_cases));
    snprintf(fig, sizeof fig, "8-bit source renormalised: larger error than 16-bit source in %d of %d textures "
                              "(geometric-mean ratio %.2f at x16)",
             t1_worse, count, geometric_mean(t1_ratio_sum, count));
    exp_claim(exp, "T1", "renormalising an 8 b/ch source quantises the histogram: larger distortion through 5:6:5", fig,
              "qualitative: larger error in every case", t1_worse == count ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the 8-bit source's renormalised histogram keeps only its few 8-bit levels with gaps (table t1_source_bits)");
    snprintf(fig, sizeof fig, "8-bit source without BC1: RMS <= %.3f; renormalised 8-bit through BC1 exceeds "
                              "sqrt(RMS16^2 + control^2) in %d of %d textures (geometric-mean ratio %.2f)",
             control_max, t1_excess, count, geometric_mean(t1_excess_sum, count));
    exp_number(exp, "T1-textures", "%d", count);
    exp_number(exp, "T1-worse", "%d", t1_worse);
    exp_number(exp, "T1-ratio", "%.2f", geometric_mean(t1_ratio_sum, count));
    exp_number(exp, "T1-control-max", "%.2f", control_max);
    exp_number(exp, "T1-gap-min", "%.0f", gap_min);
    exp_number(exp, "T1-gap-max", "%.0f", gap_max);
    exp_number(exp, "T1-excess", "%d", t1_excess);
    exp_number(exp, "T1-excess-ratio", "%.2f", geometric_mean(t1_excess_sum, count));
    exp_claim(exp, "T1", "control: the extra distortion comes from renormalising the quantised histogram through 5:6:5",
              fig, "ratio > 1 in every texture",
              t1_excess == count                              ? EXP_REPRODUCED
              : geometric_mean(t1_excess_sum, count) <= 1.0 ? EXP_DIFFERS_EXPLAINED
                                                            : EXP_NOT_REPRODUCED,
              "control row: the same 8-bit source without BC1 (renormalise + undo without a codec is the identity) "
              "measures the source's own quantisation error; the ratio compares the BC1 result with the two errors "
              "added as if independent (table t1_source_bits). Reproduced if the ratio exceeds 1 in every texture; "
              "differs-explained if its geometric mean is <= 1: then the 8-bit source's extra error is, on the whole, "
              "its own quantisation, present without BC1, not an interaction with the 5:6:5 stage");
    inputs_free(set, count);
}
