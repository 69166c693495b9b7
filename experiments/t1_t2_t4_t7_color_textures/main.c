/* t1_t2_t4_t7_color_textures - color textures: histogram renormalisation through BC1 (T1, T2),
 * the linear/gamma storage rule of thumb (T4) and the bright gradient (T7); sol's BC1 encoder
 * next to libsquish and its accuracy vs time (`--bench` runs only that comparison). */
#include "textures_exp.h"

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "t1_t2_t4_t7_color_textures", argc, argv);
    if (!exp.bench) {
        run_storage_rule(&exp);
        run_bright_gradient(&exp);
    }
    run_renormalization(&exp);
    return 0;
}
