/* d13_clip_volumes - D13: "Deferred light source w/o shadows tend to bleed ... Solution: use
 * artist-defined clipping geometry: clip volumes" (talk, "Clip Volumes for Deferred Lighting").
 *
 * Floor plan: two rooms, A (x < 0) and B (x > 0), 12 m x 8 m together, split by a 3 m wall at
 * x = 0. A point light of radius 5 m hangs in room A. The floor is lit three ways: unshadowed
 * (what a deferred light without shadows does), unshadowed with the clip volume "room A" (the
 * stencil mask), and with ray-traced visibility (the reference). Measured: the light landing in
 * room B (the leak) relative to what lands in room A, the error of each mode in each room, the
 * leak against the light's distance to the wall, the share of the light volume's pixels the
 * stencil rejects (work saved), and the same with a door in the wall, where the clip volume also
 * removes the light that really passes through the door.
 *
 * The scene is described once, in experiments/scenes/wall_bleed.json (the scenes driver renders it
 * with and without its clip volume, D13 row there): this driver reads it through the scene layer
 * and takes its floor plan from it (floor plan x, y = the scene's x, z; height = the scene's y). */
#include "exp_harness.h"
#include "sol_lighting.h"
#include "sol_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SCENE_FILE "experiments/scenes/wall_bleed.json"
#define MAX_WALLS 16
#define WIDTH 480  /* pixels across the floor's x extent (12 m) */
#define HEIGHT 320 /* pixels across its y extent (8 m) */

/* The floor plan of the scene: every box is a wall, the segment along its longer horizontal side
 * through the middle of its shorter one, all of one height; the first point light with its clip
 * volume; the floor measured is the rectangle the walls span. */
typedef struct floor_plan {
    sol_wall walls[MAX_WALLS];
    sol_room_scene room;
    sol_clip_box clip;
    double x0, y0, x1, y1; /* the floor measured */
} floor_plan;

static void plan_from_scene(const char *path, floor_plan *fp)
{
    sol_scene s;
    sol_scene_error err;
    if (sol_scene_load(path, &s, &err) != SOL_OK)
        exp_die("d13: %s: %s: %s", err.file, err.pointer, err.message);
    memset(fp, 0, sizeof *fp);
    fp->x0 = fp->y0 = INFINITY;
    fp->x1 = fp->y1 = -INFINITY;
    int n = 0;
    for (int i = 0; i < s.object_count; ++i) {
        const sol_scene_object *o = &s.objects[i];
        if (o->kind != SOL_GEOM_BOX)
            continue;
        if (n == MAX_WALLS)
            exp_die("d13: %s: more than %d walls", path, MAX_WALLS);
        if (n > 0 && o->b[1] != fp->room.wall_height)
            exp_die("d13: %s: /objects/%d: walls of different heights", path, i);
        fp->room.wall_height = o->b[1];
        double cx = 0.5 * (o->a[0] + o->b[0]), cz = 0.5 * (o->a[2] + o->b[2]);
        sol_wall w = {0};
        if (o->b[0] - o->a[0] <= o->b[2] - o->a[2])
            w = (sol_wall){cx, o->a[2], cx, o->b[2], 0, 0, 0};
        else
            w = (sol_wall){o->a[0], cz, o->b[0], cz, 0, 0, 0};
        fp->walls[n++] = w;
        fp->x0 = fmin(fp->x0, fmin(w.x0, w.x1)), fp->x1 = fmax(fp->x1, fmax(w.x0, w.x1));
        fp->y0 = fmin(fp->y0, fmin(w.y0, w.y1)), fp->y1 = fmax(fp->y1, fmax(w.y0, w.y1));
    }
    const sol_scene_light *l = NULL;
    for (int i = 0; i < s.light_count && !l; ++i)
        if (s.lights[i].kind == SOL_LIGHT_POINT && s.lights[i].clip >= 0)
            l = &s.lights[i];
    if (n == 0 || !l)
        exp_die("d13: %s: needs walls (boxes) and a point light with a clip volume", path);
    fp->room = (sol_room_scene){fp->walls, n, fp->room.wall_height, {l->position[0], l->position[2], l->position[1]},
                                l->radius};
    const sol_scene_clip *c = &s.clips[l->clip];
    fp->clip = (sol_clip_box){c->min[0], c->min[2], c->max[0], c->max[2]};
    sol_scene_free(&s);
}

typedef struct room_totals {
    double a[3], b[3]; /* floor light (irradiance x area) in rooms A and B, per mode */
    double lit_pixels_unshadowed, rejected_by_clip;
} room_totals;

static room_totals measure(const floor_plan *fp, const sol_room_scene *scene, const exp_run *exp,
                           const char *image_prefix)
{
    const sol_clip_box *clip = &fp->clip;
    const double pixel_area = (fp->x1 - fp->x0) / WIDTH * (fp->y1 - fp->y0) / HEIGHT;
    room_totals t = {{0, 0, 0}, {0, 0, 0}, 0, 0};
    sol_image img[3] = {{0}};
    if (image_prefix)
        for (int m = 0; m < 3; ++m)
            exp_check(sol_image_alloc(&img[m], WIDTH, HEIGHT, 1), "image");
    for (int j = 0; j < HEIGHT; ++j)
        for (int i = 0; i < WIDTH; ++i) {
            double x = fp->x0 + (fp->x1 - fp->x0) * (i + 0.5) / WIDTH, y = fp->y0 + (fp->y1 - fp->y0) * (j + 0.5) / HEIGHT;
            for (int m = 0; m < 3; ++m) {
                double e;
                exp_check(sol_room_irradiance(scene, clip, (sol_light_mode)m, x, y, &e), "irradiance");
                if (x < scene->walls[0].x0) /* room A: the light's side of the first wall */
                    t.a[m] += e * pixel_area;
                else
                    t.b[m] += e * pixel_area;
                if (m == SOL_LIGHT_UNSHADOWED && e > 0) {
                    t.lit_pixels_unshadowed += 1;
                    double clipped;
                    sol_room_irradiance(scene, clip, SOL_LIGHT_CLIPPED, x, y, &clipped);
                    t.rejected_by_clip += clipped == 0.0;
                }
                if (image_prefix) { /* top view, y up; the wall drawn grey */
                    double v = 4.0 * e / (1.0 + 4.0 * e);
                    const sol_wall *w = &scene->walls[0];
                    double t_along = (y - w->y0) / (w->y1 - w->y0);
                    if (fabs(x - w->x0) < 0.05 && !(w->door_t1 > w->door_t0 && t_along > w->door_t0 && t_along < w->door_t1))
                        v = 0.5;
                    img[m].data[(size_t)(HEIGHT - 1 - j) * WIDTH + i] = (float)v;
                }
            }
        }
    if (image_prefix) {
        static const char *names[3] = {"unshadowed", "clipped", "shadowed"};
        for (int m = 0; m < 3; ++m) {
            char file[256];
            snprintf(file, sizeof file, "%s_%s.png", image_prefix, names[m]);
            exp_check(sol_png_write(exp_path(exp, file), &img[m], 8), "writing %s", file);
            sol_image_free(&img[m]);
        }
    }
    return t;
}

static void scenario_rows(exp_table *tab, const char *name, const room_totals *t)
{
    static const char *modes[3] = {"unshadowed", "unshadowed + clip volume", "ray-traced shadows (reference)"};
    for (int m = 0; m < 3; ++m)
        exp_table_row(tab, "%s|%s|%.4f|%.4f|%+.1f%%|%+.1f%%", name, modes[m], t->a[m], t->b[m],
                      100.0 * (t->a[m] - t->a[2]) / t->a[2], 100.0 * (t->b[m] - t->b[2]) / t->a[2]);
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d13_clip_volumes", argc, argv);
    if (exp.bench)
        return 0; /* no accuracy knob */

    floor_plan fp;
    plan_from_scene(SCENE_FILE, &fp);
    /* the first wall (between the rooms, along y) also with a 1 m door in its middle, 2.2 m high */
    const sol_wall *first = &fp.walls[0];
    if (first->x0 != first->x1 || first->x0 != fp.clip.x1 || !(fp.room.light[0] < first->x0))
        exp_die("d13: %s: the first wall must run along z at the clip volume's +x face, the light on its -x side",
                SCENE_FILE);
    double half_door = 0.5 / fabs(first->y1 - first->y0);
    sol_wall door[MAX_WALLS];
    memcpy(door, fp.walls, sizeof door);
    door[0].door_t0 = 0.5 - half_door, door[0].door_t1 = 0.5 + half_door, door[0].door_height = 2.2;
    sol_room_scene scene = fp.room;
    const sol_wall *solid = fp.walls;

    exp_table *tab = exp_table_new("Light on the floor of each room (irradiance x area); errors relative to room A's reference light",
                                   "wall,mode,room A,room B,room A error,room B error (leak)");
    room_totals solid_t = measure(&fp, &scene, &exp, "solid_wall");
    scenario_rows(tab, "solid", &solid_t);
    scene.walls = door;
    room_totals door_t = measure(&fp, &scene, &exp, "door");
    scenario_rows(tab, "1 m door", &door_t);
    exp_table_write(tab, &exp, "room_light");

    /* Leak against the light's distance to the wall (solid wall). */
    scene.walls = solid;
    FILE *f = exp_open(&exp, "leak_vs_distance.csv");
    fprintf(f, "distance_m,leak_unshadowed,leak_clipped,rejected_share\n");
    const int steps = exp.quick ? 5 : 20;
    for (int k = 0; k < steps; ++k) {
        double d = 0.25 + 4.75 * k / (steps - 1);
        scene.light[0] = first->x0 - d;
        room_totals t = measure(&fp, &scene, &exp, NULL);
        fprintf(f, "%.3f,%.6f,%.6f,%.4f\n", d, t.b[0] / t.a[2], t.b[1] / t.a[2], t.rejected_by_clip / t.lit_pixels_unshadowed);
    }
    fclose(f);
    exp_plot(&exp, "leak_vs_distance",
             "set datafile separator comma\nset xlabel 'distance of the light to the wall (m), radius 5 m'\n"
             "set ylabel 'light in the next room / light in its own room'\nset y2label 'light-volume pixels rejected by the clip volume'\n"
             "set y2tics\nset ytics nomirror\nset key top right\nset grid\n"
             "plot 'leak_vs_distance.csv' every ::1 using 1:2 with linespoints pt 7 title 'leak, unshadowed', "
             "'' every ::1 using 1:3 with linespoints pt 6 title 'leak, with clip volume', "
             "'' every ::1 using 1:4 axes x1y2 with lines dt 2 title 'pixels rejected (right axis)'\n");

    char fig[256];
    snprintf(fig, sizeof fig, "leak into the next room: %.1f%% of the room's own light unshadowed, %.1f%% clipped",
             100.0 * solid_t.b[0] / solid_t.a[2], 100.0 * solid_t.b[1] / solid_t.a[2]);
    exp_number(&exp, "D13-leak-unshadowed", "%.0f\\%%", 100.0 * solid_t.b[0] / solid_t.a[2]);
    exp_number(&exp, "D13-door-share", "%.0f\\%%", 100.0 * door_t.b[2] / door_t.a[2]);
    exp_number(&exp, "D13-stencil-rejected", "%.0f\\%%", 100.0 * solid_t.rejected_by_clip / solid_t.lit_pixels_unshadowed);
    int ok = solid_t.b[0] > 0.0 && solid_t.b[1] == 0.0 && fabs(solid_t.a[1] - solid_t.a[0]) < 1e-12;
    exp_claim(&exp, "D13", "clip volumes stop unshadowed deferred lights bleeding through walls", fig,
              "leak > 0 without, exactly 0 with the clip volume, room A unchanged",
              ok ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "floor plan of scene wall_bleed.json: light %.3g m from a %.3g m wall, %.3g m high, radius %.3g m; the "
              "stencil rejects %.0f%% of the light volume's pixels; with a 1 m door the box-shaped clip volume also "
              "removes the light that really passes the door (%.1f%% of room A's)",
              first->x0 - fp.room.light[0], fp.room.wall_height, fp.room.light[2], fp.room.radius,
              100.0 * solid_t.rejected_by_clip / solid_t.lit_pixels_unshadowed, 100.0 * door_t.b[2] / door_t.a[2]);
    return 0;
}
