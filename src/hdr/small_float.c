/* small_float.c - binary16 and the unsigned 11/10-bit floats of R11G11B10F (claims D9, S9).
 *
 * One encoder serves all three: the magnitude is scaled so that the wanted mantissa bits become
 * the integer part and rounded once with nearbyint (round to nearest, ties to even, the default
 * FP environment). A mantissa that rounds up to 2^M carries into the exponent field by plain
 * integer addition, which is exactly the IEEE behaviour, including denormal -> smallest normal
 * and largest finite -> overflow. Formats: IEEE 754-2008 binary16; GL_EXT_packed_float
 * (unsigned 11-bit: 5e6m, 10-bit: 5e5m, bias 15, no sign).
 */
#include "sol_hdr.h"

#include <math.h>

enum { SMALL_EXP_BIAS = 15, SMALL_EXP_MAX = 31 };

/* Field (exponent << mbits | mantissa) of a finite magnitude a >= 0, rounded to nearest even.
 * May equal or exceed 31 << mbits when a overflows; the caller decides Inf or saturation. */
static uint32_t small_float_field(double a, int mbits)
{
    if (a == 0.0)
        return 0;
    int e2;
    (void)frexp(a, &e2); /* a = f * 2^e2, f in [0.5, 1): unbiased exponent is e2 - 1 */
    int exponent = e2 - 1;
    if (exponent < 1 - SMALL_EXP_BIAS) /* denormal: step 2^(1 - bias - mbits) */
        return (uint32_t)nearbyint(ldexp(a, SMALL_EXP_BIAS - 1 + mbits));
    if (exponent > SMALL_EXP_MAX) /* far beyond the range: avoid huge integer conversions */
        return (uint32_t)SMALL_EXP_MAX << mbits;
    double mantissa = nearbyint(ldexp(a, mbits - exponent)) - ldexp(1.0, mbits); /* in [0, 2^m] */
    return ((uint32_t)(exponent + SMALL_EXP_BIAS) << mbits) + (uint32_t)mantissa;
}

static double small_float_value(uint32_t field, int mbits)
{
    uint32_t exponent = field >> mbits, mantissa = field & ((1u << mbits) - 1u);
    if (exponent == SMALL_EXP_MAX)
        return mantissa ? NAN : INFINITY;
    if (exponent == 0)
        return ldexp((double)mantissa, 1 - SMALL_EXP_BIAS - mbits);
    return ldexp((double)(mantissa + (1u << mbits)), (int)exponent - SMALL_EXP_BIAS - mbits);
}

uint16_t sol_half_from_float(float f)
{
    uint32_t sign = signbit(f) ? 0x8000u : 0u;
    if (isnan(f))
        return (uint16_t)(sign | 0x7e00u);
    if (isinf(f))
        return (uint16_t)(sign | 0x7c00u);
    uint32_t field = small_float_field(fabs((double)f), 10);
    if (field >= (uint32_t)SMALL_EXP_MAX << 10) /* IEEE: overflow after rounding gives Inf */
        field = (uint32_t)SMALL_EXP_MAX << 10;
    return (uint16_t)(sign | field);
}

float sol_half_to_float(uint16_t h)
{
    double v = small_float_value(h & 0x7fffu, 10);
    return (float)((h & 0x8000u) ? -v : v);
}

/* GL_EXT_packed_float, "Unsigned 11-Bit Floating-Point Numbers": negative -> 0, +Inf -> Inf,
 * NaN -> NaN, finite too large -> largest finite, others rounded to the closest value. */
static uint32_t unsigned_small_from_float(float f, int mbits)
{
    if (isnan(f))
        return ((uint32_t)SMALL_EXP_MAX << mbits) | 1u;
    if (signbit(f))
        return 0;
    if (isinf(f))
        return (uint32_t)SMALL_EXP_MAX << mbits;
    uint32_t field = small_float_field((double)f, mbits);
    uint32_t largest_finite = ((uint32_t)SMALL_EXP_MAX << mbits) - 1u;
    return field > largest_finite ? largest_finite : field;
}

uint32_t sol_uf11_from_float(float f) { return unsigned_small_from_float(f, 6); }
uint32_t sol_uf10_from_float(float f) { return unsigned_small_from_float(f, 5); }
float sol_uf11_to_float(uint32_t bits) { return (float)small_float_value(bits & 0x7ffu, 6); }
float sol_uf10_to_float(uint32_t bits) { return (float)small_float_value(bits & 0x3ffu, 5); }

uint32_t sol_r11g11b10f_pack(const float rgb[3])
{
    return sol_uf11_from_float(rgb[0]) | (sol_uf11_from_float(rgb[1]) << 11) | (sol_uf10_from_float(rgb[2]) << 22);
}

void sol_r11g11b10f_unpack(uint32_t packed, float rgb[3])
{
    rgb[0] = sol_uf11_to_float(packed & 0x7ffu);
    rgb[1] = sol_uf11_to_float((packed >> 11) & 0x7ffu);
    rgb[2] = sol_uf10_to_float(packed >> 22);
}
