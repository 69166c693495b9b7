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
 * removes the light that really passes through the door. */
#include "exp_harness.h"
#include "sol_lighting.h"

#include <stdlib.h>

#define WIDTH 480  /* pixels across x in [-6, 6] */
#define HEIGHT 320 /* pixels across y in [-4, 4] */
#define PIXEL_AREA (12.0 / WIDTH * 8.0 / HEIGHT)

typedef struct room_totals {
    double a[3], b[3]; /* floor light (irradiance x area) in rooms A and B, per mode */
    double lit_pixels_unshadowed, rejected_by_clip;
} room_totals;

static room_totals measure(const sol_room_scene *scene, const sol_clip_box *clip, const exp_run *exp,
                           const char *image_prefix)
{
    room_totals t = {{0, 0, 0}, {0, 0, 0}, 0, 0};
    sol_image img[3] = {{0}};
    if (image_prefix)
        for (int m = 0; m < 3; ++m)
            exp_check(sol_image_alloc(&img[m], WIDTH, HEIGHT, 1), "image");
    for (int j = 0; j < HEIGHT; ++j)
        for (int i = 0; i < WIDTH; ++i) {
            double x = -6.0 + 12.0 * (i + 0.5) / WIDTH, y = -4.0 + 8.0 * (j + 0.5) / HEIGHT;
            for (int m = 0; m < 3; ++m) {
                double e;
                exp_check(sol_room_irradiance(scene, clip, (sol_light_mode)m, x, y, &e), "irradiance");
                if (x < 0)
                    t.a[m] += e * PIXEL_AREA;
                else
                    t.b[m] += e * PIXEL_AREA;
                if (m == SOL_LIGHT_UNSHADOWED && e > 0) {
                    t.lit_pixels_unshadowed += 1;
                    double clipped;
                    sol_room_irradiance(scene, clip, SOL_LIGHT_CLIPPED, x, y, &clipped);
                    t.rejected_by_clip += clipped == 0.0;
                }
                if (image_prefix) { /* top view, y up; the wall drawn grey */
                    double v = 4.0 * e / (1.0 + 4.0 * e);
                    if (fabs(x) < 0.05 && !(scene->walls[0].door_t1 > scene->walls[0].door_t0 && fabs(y) < 0.5))
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

    const sol_wall solid[1] = {{0.0, -4.0, 0.0, 4.0, 0.0, 0.0, 0.0}};
    const sol_wall door[1] = {{0.0, -4.0, 0.0, 4.0, 0.4375, 0.5625, 2.2}}; /* 1 m door at y in [-0.5, 0.5] */
    const sol_clip_box room_a = {-6.0, -4.0, 0.0, 4.0};
    sol_room_scene scene = {solid, 1, 3.0, {-1.0, 0.5, 2.0}, 5.0};

    exp_table *tab = exp_table_new("Light on the floor of each room (irradiance x area); errors relative to room A's reference light",
                                   "wall,mode,room A,room B,room A error,room B error (leak)");
    room_totals solid_t = measure(&scene, &room_a, &exp, "solid_wall");
    scenario_rows(tab, "solid", &solid_t);
    scene.walls = door;
    room_totals door_t = measure(&scene, &room_a, &exp, "door");
    scenario_rows(tab, "1 m door", &door_t);
    exp_table_write(tab, &exp, "room_light");

    /* Leak against the light's distance to the wall (solid wall). */
    scene.walls = solid;
    FILE *f = exp_open(&exp, "leak_vs_distance.csv");
    fprintf(f, "distance_m,leak_unshadowed,leak_clipped,rejected_share\n");
    const int steps = exp.quick ? 5 : 20;
    for (int k = 0; k < steps; ++k) {
        double d = 0.25 + 4.75 * k / (steps - 1);
        scene.light[0] = -d;
        room_totals t = measure(&scene, &room_a, &exp, NULL);
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
              "light 1 m from a 3 m wall, radius 5 m; the stencil rejects %.0f%% of the light volume's pixels; with a 1 m "
              "door the box-shaped clip volume also removes the light that really passes the door (%.1f%% of room A's)",
              100.0 * solid_t.rejected_by_clip / solid_t.lit_pixels_unshadowed, 100.0 * door_t.b[2] / door_t.a[2]);
    return 0;
}
