/* check_tonemap.c - check an engine's filmic tone map (Hejl-Burgess-Dawson) against sol.
 *
 * Build against an installed sol:  cc check_tonemap.c $(pkg-config --cflags --libs sol)
 * The engine's float curve is sampled at 4096 log-spaced exposures and compared with
 * sol_tonemap_apply; the sampled lower bound c_min / l is printed next to sol's. Exit 0 = pass. */
#include <math.h>
#include <stdio.h>

#include <sol/sol.h>

static float engine_filmic(float x) /* returns linear display value */
{
    x = fmaxf(0.0f, x - 0.004f);
    float g = x * (6.2f * x + 0.5f) / (x * (6.2f * x + 1.7f) + 0.06f);
    return powf(g, 2.2f);
}

int main(void)
{
    enum { N = 4096 };
    static double x[N], y[N];
    for (int i = 0; i < N; ++i) {
        x[i] = exp2(-16.0 + 24.0 * i / (N - 1));
        y[i] = engine_filmic((float)x[i]);
    }
    sol_check_report r;
    double engine_cmin, sol_cmin;
    if (sol_check_tonemap(SOL_TONEMAP_FILMIC_HBD, x, y, N, &r) != SOL_OK ||
        sol_check_tonemap_bound(SOL_TONEMAP_FILMIC_HBD, x, y, N, 0.0, &engine_cmin, &sol_cmin) != SOL_OK)
        return 2;
    printf("filmic-hbd: %s, max |dy| %.3g (tolerance %.3g), c_min/l engine %.5f sol %.5f\n",
           r.passed ? "pass" : "FAIL", r.max, r.tolerance, engine_cmin, sol_cmin);
    return r.passed ? 0 : 1;
}
