/* normals_internal.h - helpers shared by the normals module's files (not installed, not public). */
#ifndef SOL_NORMALS_INTERNAL_H
#define SOL_NORMALS_INTERNAL_H
#include "sol_normals.h"

/* Validates `n` (finite, non-zero) and writes its unit vector to `unit`. Scales by the largest
 * |component| first so denormal and huge inputs normalize without underflow or overflow. */
sol_status sol_normals_unit_input(const double n[3], double unit[3]);

/* Largest |component| of a vector. */
static inline double sol_normals_max_abs(const double v[3])
{
    double a = fabs(v[0]), b = fabs(v[1]), c = fabs(v[2]);
    double m = a > b ? a : b;
    return m > c ? m : c;
}

/* Sign with sign(+-0) = +1 (so -0.0 behaves like +0.0). */
static inline double sol_normals_sign(double x)
{
    return x < 0.0 ? -1.0 : 1.0;
}

/* sol_quantize255 for c in [-1, 1] (the search's probes), inlined for the best-fit inner loop:
 * the argument of the truncation is >= 0.5, so truncation is floor. Same results. */
static inline uint32_t sol_normals_quantize255_fast(double c)
{
    return (uint32_t)((c * 0.5 + 0.5) * 255.0 + 0.5);
}

/* Three 8-bit channel codes <-> one 24-bit code (r | g << 8 | b << 16). */
static inline uint32_t sol_normals_pack3(const uint32_t c[3])
{
    return c[0] | (c[1] << 8) | (c[2] << 16);
}

/* Quantizes each component of `v` with quantize255 and packs the three codes. */
static inline uint32_t sol_normals_quantize3(const double v[3])
{
    uint32_t c[3] = {sol_quantize255(v[0]), sol_quantize255(v[1]), sol_quantize255(v[2])};
    return sol_normals_pack3(c);
}

/* Per-method encoders (unit input, cannot fail) and decoders (code already range-checked). */
uint32_t sol_normals_encode_xyz(const double unit[3]);
uint32_t sol_normals_encode_max_component(const double unit[3]);
void sol_normals_decode_xyz(uint32_t code, double n[3]);
/* The best-fit searches divide their input by its largest |component| themselves, so they also
 * take unnormalised vectors (the appendix's path); _float rounds the input to float, _half to half. */
uint32_t sol_normals_encode_best_fit(const double v[3], double *t);
uint32_t sol_normals_encode_best_fit_float(const double v[3]);
uint32_t sol_normals_encode_best_fit_half(const double v[3]);
uint32_t sol_normals_encode_best_fit_half_double(const double v[3]);
uint32_t sol_normals_encode_octahedral(const double unit[3], int precise);
void sol_normals_decode_octahedral(uint32_t code, double n[3]);
uint32_t sol_normals_encode_spherical(const double unit[3]);
void sol_normals_decode_spherical(uint32_t code, double n[3]);
uint32_t sol_normals_encode_spherical_z(const double unit[3]);
void sol_normals_decode_spherical_z(uint32_t code, double n[3]);
uint32_t sol_normals_encode_mittring(const double unit[3], int bits);
void sol_normals_decode_mittring(uint32_t code, int bits, double n[3]);

#endif
