/* cmd_scene.c - `sol plan SCENE` and `sol render SCENE --out DIR`: the scene layer's front end.
 *
 * plan: loads the scene (errors name file and field, exit 2) and prints every effect of the
 * effect graph: those that run with the scene element calling for them, those skipped and why.
 * render: renders the reference path and the engine path, writes both as EXR + PNG, a
 * difference image and the attribution table (the engine path re-run with one effect at a time
 * in its reference version). Files are written under temporary names and renamed at the end, so
 * a failed render leaves no partial output. */
#include <errno.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "sol_scene.h"

static int load(const char *cmd, const char *path, sol_scene *scene)
{
    sol_scene_error err;
    sol_status st = sol_scene_load(path, scene, &err);
    if (st == SOL_OK)
        return 0;
    if (err.line)
        fprintf(stderr, "sol %s: %s: %s\n", cmd, err.file, err.message);
    else
        fprintf(stderr, "sol %s: %s: %s: %s (%s)\n", cmd, err.file, *err.pointer ? err.pointer : "/", err.message,
                sol_status_string(st));
    return -1;
}

static void json_string(FILE *to, const char *s)
{
    fputc('"', to);
    for (; *s; ++s) {
        if (*s == '"' || *s == '\\')
            fprintf(to, "\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            fprintf(to, "\\u%04x", *s);
        else
            fputc(*s, to);
    }
    fputc('"', to);
}

static void print_plan(FILE *to, const sol_scene *scene, const sol_scene_plan *plan, int json)
{
    if (json) {
        fprintf(to, "{\"scene\": ");
        json_string(to, scene->name);
        fprintf(to, ", \"effects\": [");
        for (int e = 0; e < SOL_FX_COUNT; ++e) {
            const sol_effect_info *info = sol_effect_get((sol_effect)e);
            fprintf(to, "%s\n  {\"effect\": \"%s\", \"claims\": \"%s\", \"run\": %s, \"element\": ", e ? "," : "",
                    info->name, info->claims, plan->run[e] ? "true" : "false");
            json_string(to, plan->element[e]);
            fprintf(to, ", \"reason\": ");
            json_string(to, plan->reason[e]);
            fprintf(to, "}");
        }
        fprintf(to, "\n]}\n");
        return;
    }
    fprintf(to, "scene %s: effects that run\n", scene->name);
    for (int e = 0; e < SOL_FX_COUNT; ++e)
        if (plan->run[e]) {
            const sol_effect_info *info = sol_effect_get((sol_effect)e);
            fprintf(to, "  %-16s %-14s called for by %s: %s\n", info->name, info->claims, plan->element[e],
                    plan->reason[e]);
        }
    fprintf(to, "skipped\n");
    for (int e = 0; e < SOL_FX_COUNT; ++e)
        if (!plan->run[e]) {
            const sol_effect_info *info = sol_effect_get((sol_effect)e);
            fprintf(to, "  %-16s %-14s %s\n", info->name, info->claims, plan->reason[e]);
        }
}

int cli_plan_main(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (argv[i][0] == '-' || path) {
            fprintf(stderr, "usage: sol plan SCENE.json|MODEL.gltf [--json]\n");
            return CLI_EXIT_USAGE;
        } else
            path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "usage: sol plan SCENE.json|MODEL.gltf [--json]\n");
        return CLI_EXIT_USAGE;
    }
    sol_scene scene;
    if (load("plan", path, &scene))
        return CLI_EXIT_USAGE;
    sol_scene_plan plan;
    sol_scene_plan_build(&scene, &plan);
    print_plan(stdout, &scene, &plan, json);
    sol_scene_free(&scene);
    return CLI_EXIT_OK;
}

/* ---------------- render ---------------- */

#define MAX_OUT 16
typedef struct outputs {
    int count;
    char tmp[MAX_OUT][1200], final[MAX_OUT][1200];
} outputs;

static const char *out_name(outputs *o, const char *dir, const char *name)
{
    if (o->count >= MAX_OUT)
        return NULL;
    snprintf(o->final[o->count], sizeof o->final[0], "%s/%s", dir, name);
    snprintf(o->tmp[o->count], sizeof o->tmp[0], "%s/.%s.tmp%ld", dir, name, (long)getpid());
    return o->tmp[o->count++];
}

/* Interrupted (SIGINT, SIGTERM, SIGHUP): the temporary files and a folder this run made are removed
 * before the signal's default action, so a killed render leaves nothing behind either. Only
 * async-signal-safe calls (unlink, rmdir, signal, raise; lock-free atomics).
 *
 * Two steps must not be cut in half: making the folder and recording it (a signal in between left
 * the folder behind: the test cli_render_killed_leaves_nothing failed under heavy load), and
 * renaming the finished files into place (a signal in between left a partial folder). Around them
 * interrupt_hold is set; a signal that arrives then, on any thread (OpenMP's threads do not block
 * signals), is only recorded in interrupt_pending and acted on by interrupt_release once the step
 * is whole. The handler records the signal before it reads the hold, and the release clears the
 * hold before it reads the record, so no signal is lost (at worst both act: the clean-up is
 * idempotent and both end in the default action). */
static outputs *volatile interrupt_out;
static const char *volatile interrupt_dir;
static atomic_int interrupt_hold, interrupt_pending;

static void on_interrupt(int sig)
{
    atomic_store(&interrupt_pending, sig);
    if (atomic_load(&interrupt_hold))
        return;
    outputs *o = interrupt_out;
    for (int i = 0; o && i < o->count; ++i)
        unlink(o->tmp[i]);
    if (interrupt_dir)
        rmdir(interrupt_dir);
    signal(sig, SIG_DFL);
    raise(sig);
}

static void interrupt_release(void)
{
    atomic_store(&interrupt_hold, 0);
    int sig = atomic_load(&interrupt_pending);
    if (sig)
        on_interrupt(sig);
}

/* A signal the caller ignores (e.g. SIGINT for a background job of a script, nohup's SIGHUP) stays
 * ignored. */
static void catch_signal(int sig)
{
    if (signal(sig, on_interrupt) == SIG_IGN)
        signal(sig, SIG_IGN);
}

static void out_discard(outputs *o)
{
    for (int i = 0; i < o->count; ++i)
        remove(o->tmp[i]);
}

static int out_commit(outputs *o)
{
    for (int i = 0; i < o->count; ++i)
        if (rename(o->tmp[i], o->final[i]) != 0)
            return -1;
    return 0;
}

static sol_status write_pair(outputs *o, const char *dir, const char *stem, const sol_render_result *r)
{
    char name[256];
    snprintf(name, sizeof name, "%s.exr", stem);
    const char *p = out_name(o, dir, name);
    sol_status st = p ? sol_exr_write(p, &r->hdr, 0) : SOL_ERR_LIMIT;
    if (st != SOL_OK)
        return st;
    snprintf(name, sizeof name, "%s.png", stem);
    p = out_name(o, dir, name);
    return p ? sol_png_write(p, &r->display, 8) : SOL_ERR_LIMIT;
}

static sol_status write_difference(outputs *o, const char *dir, const sol_render_result *a, const sol_render_result *b)
{
    sol_image d;
    sol_status st = sol_image_alloc(&d, a->display.width, a->display.height, 3);
    if (st != SOL_OK)
        return st;
    size_t n = (size_t)d.width * d.height * 3;
    for (size_t i = 0; i < n; ++i) /* |engine - reference| in display codes, x8 so one code shows */
        d.data[i] = fminf(1.0f, 8.0f * fabsf(a->display.data[i] - b->display.data[i]));
    const char *p = out_name(o, dir, "difference.png");
    st = p ? sol_png_write(p, &d, 8) : SOL_ERR_LIMIT;
    sol_image_free(&d);
    return st;
}

static void usage_render(void)
{
    fprintf(stderr, "usage: sol render SCENE.json|MODEL.gltf --out DIR [--size WxH] [--no-attribution] [--json]\n"
                    "writes DIR/{reference,engine}.{exr,png}, difference.png, attribution.tsv, plan.txt\n");
}

int cli_render_main(int argc, char **argv)
{
    const char *path = NULL, *dir = NULL;
    int w = 0, h = 0, attribution = 1, json = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            if (sscanf(argv[++i], "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384) {
                fprintf(stderr, "sol render: --size: expected WxH, e.g. 320x180 (got '%s')\n", argv[i]);
                return CLI_EXIT_USAGE;
            }
        } else if (!strcmp(argv[i], "--no-attribution"))
            attribution = 0;
        else if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (argv[i][0] == '-' || path) {
            usage_render();
            return CLI_EXIT_USAGE;
        } else
            path = argv[i];
    }
    if (!path || !dir) {
        usage_render();
        return CLI_EXIT_USAGE;
    }
    sol_scene scene;
    if (load("render", path, &scene))
        return CLI_EXIT_USAGE;
    /* The output folder is made (or checked) before rendering, which can take minutes, so an
     * unusable --out fails at once; a folder made here is removed again if the render fails. */
    int made_dir = 0;
    struct stat sb;
    catch_signal(SIGINT);
    catch_signal(SIGTERM);
    catch_signal(SIGHUP);
    atomic_store(&interrupt_hold, 1);
    made_dir = mkdir(dir, 0777) == 0;
    int mkdir_errno = errno;
    if (made_dir)
        interrupt_dir = dir;
    interrupt_release();
    errno = mkdir_errno;
    if (!made_dir && (errno != EEXIST || stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode) || access(dir, W_OK | X_OK) != 0)) {
        int e = errno == EEXIST ? ENOTDIR : errno;
        fprintf(stderr, "sol render: --out %s: cannot create or write the folder: %s\n", dir, strerror(e));
        sol_scene_free(&scene);
        return CLI_EXIT_USAGE;
    }
    sol_scene_plan plan;
    sol_scene_plan_build(&scene, &plan);
    sol_render_options opt = {w, h, 0, 0};
    sol_render_result eng = {0}, ref = {0};
    sol_render_stats es, rs;
    sol_render_error err;
    int progress = isatty(2);
    if (progress)
        fprintf(stderr, "sol render: %s: engine path...\n", scene.name);
    sol_status st = sol_scene_render(&scene, &plan, &opt, &eng, &es);
    if (st == SOL_OK) {
        if (progress)
            fprintf(stderr, "sol render: %s: reference path...\n", scene.name);
        opt.reference = 1;
        st = sol_scene_render(&scene, &plan, &opt, &ref, &rs);
        opt.reference = 0;
    }
    if (st == SOL_OK)
        st = sol_render_compare(&eng, &ref, &err);
    if (st != SOL_OK) {
        fprintf(stderr, "sol render: %s: rendering failed: %s\n", path, sol_status_string(st));
        if (made_dir)
            rmdir(dir);
        sol_render_result_free(&eng);
        sol_render_result_free(&ref);
        sol_scene_free(&scene);
        return CLI_EXIT_USAGE;
    }
    /* attribution: one effect at a time in its reference version */
    struct row {
        int effect;
        sol_render_error err; /* engine with this effect in its reference version, vs the reference */
        sol_render_error own; /* the effect's own error: engine vs engine with this effect swapped */
        double seconds;
    } rows[SOL_FX_COUNT + 1];
    int nrows = 0;
    for (int e = 0; e < SOL_FX_COUNT && attribution && st == SOL_OK; ++e) {
        if (!plan.run[e])
            continue;
        if (progress)
            fprintf(stderr, "sol render: %s: attribution, %s in its reference version...\n", scene.name,
                    sol_effect_get((sol_effect)e)->name);
        sol_render_result r = {0};
        sol_render_stats s;
        opt.reference_effects = 1u << e;
        st = sol_scene_render(&scene, &plan, &opt, &r, &s);
        if (st == SOL_OK)
            st = sol_render_compare(&r, &ref, &rows[nrows].err);
        if (st == SOL_OK)
            st = sol_render_compare(&eng, &r, &rows[nrows].own);
        rows[nrows].effect = e;
        rows[nrows].seconds = s.seconds;
        nrows += st == SOL_OK;
        sol_render_result_free(&r);
    }
    static outputs o; /* static: 16 x 2 x 1200 bytes, and reachable from on_interrupt */
    interrupt_out = &o;
    if (st == SOL_OK)
        st = write_pair(&o, dir, "engine", &eng);
    if (st == SOL_OK)
        st = write_pair(&o, dir, "reference", &ref);
    if (st == SOL_OK)
        st = write_difference(&o, dir, &eng, &ref);
    FILE *tsv = NULL, *pf = NULL;
    if (st == SOL_OK) {
        const char *p = out_name(&o, dir, "attribution.tsv"), *q = out_name(&o, dir, "plan.txt");
        tsv = p ? fopen(p, "w") : NULL;
        pf = q ? fopen(q, "w") : NULL;
        if (!tsv || !pf)
            st = SOL_ERR_IO;
    }
    if (st == SOL_OK) {
        fprintf(tsv, "row\tclaims\trms_code\tmax_code\tde2000_mean\tde2000_max\tnormal_mean_deg\tnormal_max_deg\tseconds"
                     "\town_rms_code\town_max_code\town_de2000_mean\town_normal_mean_deg\n");
        fprintf(tsv, "engine\t-\t%.4f\t%.0f\t%.4f\t%.3f\t%.4f\t%.3f\t%.3f\t-\t-\t-\t-\n", err.rms_code, err.max_code,
                err.de2000_mean, err.de2000_max, err.normal_mean_deg, err.normal_max_deg, es.seconds);
        for (int i = 0; i < nrows; ++i) {
            const sol_effect_info *info = sol_effect_get((sol_effect)rows[i].effect);
            const sol_render_error *x = &rows[i].err;
            const sol_render_error *y = &rows[i].own;
            fprintf(tsv, "without %s\t%s\t%.4f\t%.0f\t%.4f\t%.3f\t%.4f\t%.3f\t%.3f\t%.4f\t%.0f\t%.4f\t%.4f\n", info->name,
                    info->claims, x->rms_code, x->max_code, x->de2000_mean, x->de2000_max, x->normal_mean_deg,
                    x->normal_max_deg, rows[i].seconds, y->rms_code, y->max_code, y->de2000_mean, y->normal_mean_deg);
        }
        fprintf(tsv, "reference\t-\t0\t0\t0\t0\t0\t0\t%.3f\t-\t-\t-\t-\n", rs.seconds);
        print_plan(pf, &scene, &plan, 0);
        if (fclose(tsv) != 0)
            st = SOL_ERR_IO;
        tsv = NULL;
        if (fclose(pf) != 0)
            st = SOL_ERR_IO;
        pf = NULL;
    }
    if (tsv)
        fclose(tsv);
    if (pf)
        fclose(pf);
    atomic_store(&interrupt_hold, 1);
    if (st == SOL_OK && out_commit(&o) != 0)
        st = SOL_ERR_IO;
    interrupt_out = NULL; /* committed (or discarded just below): nothing left to clean */
    interrupt_dir = NULL;
    if (st != SOL_OK) {
        out_discard(&o);
        if (made_dir)
            rmdir(dir);
    }
    interrupt_release(); /* a signal during the renames ends the run here, its output whole or gone */
    if (st != SOL_OK) {
        fprintf(stderr, "sol render: writing %s failed: %s\n", dir, sol_status_string(st));
    } else if (json) {
        printf("{\"scene\": ");
        json_string(stdout, scene.name);
        printf(", \"engine_seconds\": %.3f, \"reference_seconds\": %.3f, \"rms_code\": %.4f, \"max_code\": %.0f, "
               "\"de2000_mean\": %.4f, \"normal_mean_deg\": %.4f, \"attribution\": [",
               es.seconds, rs.seconds, err.rms_code, err.max_code, err.de2000_mean, err.normal_mean_deg);
        for (int i = 0; i < nrows; ++i)
            printf("%s{\"without\": \"%s\", \"rms_code\": %.4f, \"de2000_mean\": %.4f, \"own_rms_code\": %.4f, "
                   "\"own_de2000_mean\": %.4f, \"seconds\": %.3f}",
                   i ? ", " : "", sol_effect_get((sol_effect)rows[i].effect)->name, rows[i].err.rms_code,
                   rows[i].err.de2000_mean, rows[i].own.rms_code, rows[i].own.de2000_mean, rows[i].seconds);
        printf("]}\n");
    } else {
        printf("%s: engine %.2f s (%.2f s CPU), reference %.2f s (%.2f s CPU); engine vs reference: display RMS %.3f codes (max %.0f), "
               "CIEDE2000 mean %.3f, normals %.3f deg mean\n",
               scene.name, es.seconds, es.cpu_seconds, rs.seconds, rs.cpu_seconds, err.rms_code, err.max_code, err.de2000_mean, err.normal_mean_deg);
        for (int i = 0; i < nrows; ++i)
            printf("  without %-16s vs reference: RMS %.3f dE %.3f normals %.3f deg; own error: RMS %.3f (max %.0f) "
                   "dE %.3f normals %.3f deg; %.2f s\n",
                   sol_effect_get((sol_effect)rows[i].effect)->name, rows[i].err.rms_code, rows[i].err.de2000_mean,
                   rows[i].err.normal_mean_deg, rows[i].own.rms_code, rows[i].own.max_code, rows[i].own.de2000_mean,
                   rows[i].own.normal_mean_deg, rows[i].seconds);
    }
    sol_render_result_free(&eng);
    sol_render_result_free(&ref);
    sol_scene_free(&scene);
    return st == SOL_OK ? CLI_EXIT_OK : CLI_EXIT_USAGE;
}
