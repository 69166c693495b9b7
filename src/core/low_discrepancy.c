/* low_discrepancy.c - the R2 sequence and a uniform sphere map, for dense direction sets. */
#include "sol_core.h"

#include <math.h>

void sol_r2_point(uint64_t n, double *u, double *v)
{
    /* Roberts, "The unreasonable effectiveness of quasirandom sequences" (2018): the plastic
     * number g solves g^3 = g + 1 and alpha = (1/g, 1/g^2). */
    const double g = 1.32471795724474602596;
    const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
    double x = 0.5 + a1 * (double)n, y = 0.5 + a2 * (double)n;
    *u = x - floor(x);
    *v = y - floor(y);
}

void sol_sphere_uniform(double u, double v, double dir[3])
{
    /* Archimedes' hat-box theorem: z uniform in [-1,1] and phi uniform give equal area. */
    double z = 1.0 - 2.0 * u;
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    double phi = 2.0 * M_PI * v;
    dir[0] = r * cos(phi);
    dir[1] = r * sin(phi);
    dir[2] = z;
}
