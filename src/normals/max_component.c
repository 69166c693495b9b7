/* max_component.c - claim D4: the normal divided by its largest |component| (a point on the surface
 * of the cube [-1,1]^3), quantized with the talk's quantizer. Uses only the cube's boundary cells. */
#include "normals_internal.h"

uint32_t sol_normals_encode_max_component(const double unit[3])
{
    double m = sol_normals_max_abs(unit);
    double v[3] = {unit[0] / m, unit[1] / m, unit[2] / m};
    return sol_normals_quantize3(v);
}
