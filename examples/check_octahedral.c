/* check_octahedral.c - check an engine's octahedral G-buffer normal encoder against sol.
 *
 * Build against an installed sol:  cc check_octahedral.c $(pkg-config --cflags --libs sol)
 * The "engine" encoder below is the usual shader snippet in float; sol_check_normals compares its
 * codes with sol's on sol's edge-case directions plus 100000 spread directions. Exit 0 = pass. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <sol/sol.h>

static float sign_not_zero(float v)
{
    return v >= 0.0f ? 1.0f : -1.0f; /* HLSL's sign() returns 0 at 0: a classic bug */
}

static uint32_t engine_encode(const double d[3])
{
    float x = (float)d[0], y = (float)d[1], z = (float)d[2];
    float m = fmaxf(fabsf(x), fmaxf(fabsf(y), fabsf(z)));
    x /= m, y /= m, z /= m;
    float s = fabsf(x) + fabsf(y) + fabsf(z);
    x /= s, y /= s;
    if (z < 0.0f) {
        float fx = (1.0f - fabsf(y)) * sign_not_zero(x), fy = (1.0f - fabsf(x)) * sign_not_zero(y);
        x = fx, y = fy;
    }
    /* sol's octahedral-12 codes: round(2047 u) + 2047 per coordinate, x in the low 12 bits */
    return (uint32_t)(lrintf(x * 2047.0f) + 2047) | (uint32_t)(lrintf(y * 2047.0f) + 2047) << 12;
}

int main(void)
{
    size_t edges, n = 100000;
    const double (*edge)[3] = sol_check_edge_normals(&edges);
    double (*dirs)[3] = malloc((edges + n) * sizeof *dirs);
    uint32_t *codes = malloc((edges + n) * sizeof *codes);
    if (!dirs || !codes)
        return 2;
    for (size_t i = 0; i < edges + n; ++i) {
        if (i < edges) {
            for (int c = 0; c < 3; ++c)
                dirs[i][c] = edge[i][c];
        } else {
            double u, v;
            sol_r2_point(i - edges, &u, &v);
            sol_sphere_uniform(u, v, dirs[i]);
        }
        codes[i] = engine_encode(dirs[i]);
    }
    sol_check_report r;
    sol_status st = sol_check_normals(SOL_NORMAL_OCTAHEDRAL_12, (const double (*)[3])dirs, codes, edges + n, NULL, &r);
    free(dirs);
    free(codes);
    if (st != SOL_OK) {
        fprintf(stderr, "check failed to run: %s\n", sol_status_string(st));
        return 2;
    }
    printf("octahedral-12: %s, %zu codes, %zu differ (ties), max %.4f deg (bound %.4f)\n", r.passed ? "pass" : "FAIL",
           r.count, r.mismatches, r.max, r.tolerance);
    return r.passed ? 0 : 1;
}
