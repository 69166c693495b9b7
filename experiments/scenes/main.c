/* scenes - renders the shipped scenes (the .json files of experiments/scenes/) through the scene layer:
 * for each, the plan (effects run / skipped), the engine path against the reference path, and the
 * attribution of the engine's error to each planned effect (the engine re-rendered with that one
 * effect in its reference version). Writes results/scenes/<scene>/{engine,reference,difference}.png,
 * <scene>_plan and <scene>_attribution tables, and a summary table over all scenes; --bench prints
 * the frame times against the goal (960x540 engine path <= 5 s on 2 cores, reference <= 10x).
 * claims.c adds the claims rows measured on these scenes (T2, T14, M1, M3, M4, D9, D10, D13, D16,
 * D17, D18), each with its own table. The renders of unmodified scenes that claims.c needs again
 * (engine, reference and attribution renders) are kept for it (cache.c) instead of made twice.
 *
 * The scenes regenerate the talk's image comparisons as measured figures: car hood banding (T14),
 * dark texture under strong light (T1/T2), light bleeding with and without a clip volume (D13),
 * SSAO (M3), post and temporal AA (D17, D18), coverage-buffer culling (M1), HDR interior and
 * exterior (D9, D10), anisotropic material under SG lighting (D15, D16), a graded look (M4). */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "exp_harness.h"
#include "scenes.h"
#include "sol_scene.h"

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Writes the scene's engine, reference and difference images, the three at once (one thread
 * each: PNG compression is serial per file). */
static void write_pngs(const exp_run *exp, const char *scene, const sol_image *img[3])
{
    static const char *files[3] = {"engine.png", "reference.png", "difference.png"};
    char rel[3][512], path[3][4096];
    sol_status st[3];
    for (int k = 0; k < 3; ++k) {
        snprintf(rel[k], sizeof rel[k], "%s/%s", scene, files[k]);
        snprintf(path[k], sizeof path[k], "%s", exp_path(exp, rel[k])); /* exp_path is not thread-safe */
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = 0; k < 3; ++k)
        st[k] = sol_png_write(path[k], img[k], 8);
    for (int k = 0; k < 3; ++k)
        exp_check(st[k], "writing %s", rel[k]);
}

int main(int argc, char **argv)
{
    exp_run run;
    exp_init(&run, "scenes", argc, argv);
    const exp_run *exp = &run;
    DIR *d = opendir(SCENES_DIR);
    if (!d)
        exp_die("scenes: cannot open %s (run from the repository root)", SCENES_DIR);
    char *names[256];
    int count = 0;
    for (struct dirent *e; (e = readdir(d)) && count < 256;) {
        size_t n = strlen(e->d_name);
        if (n > 5 && !strcmp(e->d_name + n - 5, ".json"))
            names[count++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)count, sizeof *names, by_name);
    /* --quick: a small frame; otherwise the goal's 960x540 (the scenes' camera size) */
    const int width = run.quick ? 192 : 0, height = run.quick ? 108 : 0;
    exp_table *summary = exp_table_new("Shipped scenes: engine path vs reference path (display codes, CIEDE2000), "
                                       "largest own error of one effect, frame times",
                                       "scene,effects run,RMS codes,max codes,dE2000 mean,normals deg,objects culled,largest effect,"
                                       "its RMS codes,engine time (s),reference time (s),time ratio");
    exp_table *bench = exp_table_new("Scene frame times (goal: engine <= 5 s at 960x540 on 2 cores, reference <= 10x "
                                     "that). Wall time moves with the machine's load; CPU s / 2 is the wall time of an "
                                     "idle 2-core machine with perfect scaling, the goal is judged on it",
                                     "scene,pixels,engine time (s),engine CPU time (s),reference time (s),reference CPU time (s),"
                                     "CPU time ratio,engine time goal met,reference time goal met");
    if (!run.bench)
        scenes_claims_want(); /* the renders below that claims.c needs again are kept for it */
    for (int i = 0; i < count; ++i) {
        char path[1024], scene_dir[512];
        snprintf(path, sizeof path, "%s/%s", SCENES_DIR, names[i]);
        sol_scene s;
        sol_scene_error err;
        if (sol_scene_load(path, &s, &err) != SOL_OK)
            exp_die("scenes: %s: %s: %s", err.file, err.pointer, err.message);
        snprintf(scene_dir, sizeof scene_dir, "%s", exp_path(exp, s.name));
        mkdir(scene_dir, 0777);
        sol_scene_plan plan;
        exp_check(sol_scene_plan_build(&s, &plan), "planning %s", s.name);
        sol_render_options opt = {width, height, 0, 0};
        sol_render_result eng, ref;
        sol_render_stats es, rs;
        sol_render_error e;
        exp_progress(s.name, (size_t)i, (size_t)count);
        exp_check(sol_scene_render(&s, &plan, &opt, &eng, &es), "rendering %s (engine)", s.name);
        opt.reference = 1;
        exp_check(sol_scene_render(&s, &plan, &opt, &ref, &rs), "rendering %s (reference)", s.name);
        opt.reference = 0;
        exp_check(sol_render_compare(&eng, &ref, &e), "comparing %s", s.name);
        char ratio[32];
        snprintf(ratio, sizeof ratio, "%.1f", rs.cpu_seconds / es.cpu_seconds);
        exp_table_row(bench, "%s|%dx%d|%.2f|%.2f|%.2f|%.2f|%s|%s|%s", s.name, eng.display.width, eng.display.height,
                      es.seconds, es.cpu_seconds, rs.seconds, rs.cpu_seconds, ratio,
                      es.cpu_seconds / 2 <= 5 ? "yes" : "no", rs.cpu_seconds / 2 <= 10 * 5 ? "yes" : "no");
        if (run.bench) {
            sol_render_result_free(&eng);
            sol_render_result_free(&ref);
            sol_scene_free(&s);
            continue;
        }
        sol_image diff;
        exp_check(sol_image_alloc(&diff, eng.display.width, eng.display.height, 3), "difference image");
        for (size_t k = 0; k < (size_t)diff.width * diff.height * 3; ++k)
            diff.data[k] = fminf(1.0f, 8.0f * fabsf(eng.display.data[k] - ref.display.data[k]));
        const sol_image *imgs[3] = {&eng.display, &ref.display, &diff};
        write_pngs(exp, s.name, imgs);
        sol_image_free(&diff);

        char title[256], tname[256];
        snprintf(title, sizeof title, "Plan of scene %s: effects that run (and the element calling for them) or are skipped (and why)",
                 s.name);
        exp_table *pt = exp_table_new(title, "effect,claims,runs,element,reason");
        char run_list[512] = "";
        for (int k = 0; k < SOL_FX_COUNT; ++k) {
            const sol_effect_info *info = sol_effect_get((sol_effect)k);
            exp_table_row(pt, "%s|%s|%s|%s|%s", info->name, info->claims, plan.run[k] ? "yes" : "no",
                          *plan.element[k] ? plan.element[k] : "-", plan.reason[k]);
            if (plan.run[k] && strlen(run_list) + strlen(info->name) + 2 < sizeof run_list) {
                strcat(run_list, *run_list ? " " : "");
                strcat(run_list, info->name);
            }
        }
        snprintf(tname, sizeof tname, "%s/plan", s.name);
        exp_table_write(pt, exp, tname);

        snprintf(title, sizeof title, "Scene %s: each planned effect's own error (engine vs engine with that effect "
                                      "in its reference version) and the engine's error vs reference without it",
                 s.name);
        exp_table *at = exp_table_new(title, "effect,claims,own RMS codes,own max codes,own dE2000,own normals deg,"
                                             "RMS vs reference without it,seconds without it");
        double largest = -1;
        const char *largest_name = "none";
        for (int k = 0; k < SOL_FX_COUNT; ++k) {
            if (!plan.run[k])
                continue;
            sol_render_result r;
            sol_render_stats st;
            sol_render_error own, vs;
            opt.reference_effects = 1u << k;
            exp_check(sol_scene_render(&s, &plan, &opt, &r, &st), "rendering %s without %s", s.name,
                      sol_effect_get((sol_effect)k)->name);
            exp_check(sol_render_compare(&eng, &r, &own), "comparing");
            exp_check(sol_render_compare(&r, &ref, &vs), "comparing");
            exp_table_row(at, "%s|%s|%.3f|%.0f|%.3f|%.3f|%.3f|%.2f", sol_effect_get((sol_effect)k)->name,
                          sol_effect_get((sol_effect)k)->claims, own.rms_code, own.max_code, own.de2000_mean,
                          own.normal_mean_deg, vs.rms_code, st.seconds);
            if (own.rms_code > largest) {
                largest = own.rms_code;
                largest_name = sol_effect_get((sol_effect)k)->name;
            }
            if (!scenes_cache_put(s.name, 0, opt.reference_effects, &r, &st))
                sol_render_result_free(&r);
        }
        opt.reference_effects = 0;
        snprintf(tname, sizeof tname, "%s/attribution", s.name);
        exp_table_write(at, exp, tname);
        exp_table_row(summary, "%s|%s|%.3f|%.0f|%.3f|%.3f|%llu of %d|%s|%.3f|%.2f|%.2f|%s", s.name,
                      *run_list ? run_list : "none", e.rms_code, e.max_code, e.de2000_mean, e.normal_mean_deg,
                      (unsigned long long)es.objects_culled, s.object_count, largest_name, fmax(largest, 0),
                      es.cpu_seconds, rs.cpu_seconds, ratio);
        char key[128];
        snprintf(key, sizeof key, "scenes-%s-rms", s.name);
        exp_number(exp, key, "%.2f", e.rms_code);
        snprintf(key, sizeof key, "scenes-%s-de", s.name);
        exp_number(exp, key, "%.2f", e.de2000_mean);
        snprintf(key, sizeof key, "scenes-%s-largest", s.name);
        exp_number(exp, key, "%s", largest_name);
        snprintf(key, sizeof key, "scenes-%s-engine-s", s.name);
        exp_number(exp, key, "%.2f", es.cpu_seconds);
        snprintf(key, sizeof key, "scenes-%s-reference-s", s.name);
        exp_number(exp, key, "%.2f", rs.cpu_seconds);
        if (!scenes_cache_put(s.name, 0, 0, &eng, &es))
            sol_render_result_free(&eng);
        if (!scenes_cache_put(s.name, 1, 0, &ref, &rs))
            sol_render_result_free(&ref);
        sol_scene_free(&s);
    }
    exp_progress_done("scenes");
    exp_table_write(bench, exp, "frame_times");
    if (!run.bench) {
        exp_table_write(summary, exp, "summary");
        scenes_claims(exp, width, height);
        scenes_cache_clear();
    }
    for (int i = 0; i < count; ++i)
        free(names[i]);
    return 0;
}
