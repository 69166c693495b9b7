/* octahedral.c - claim S5: octahedral normal encoding (Cigolle, Donow, Evangelakos, Mara, McGuire,
 * Meyer, "A Survey of Efficient Representations for Independent Unit Vectors", JCGT 3(2), 2014;
 * Narkowicz's notes). The 12:12 G-buffer methods store each coordinate as a 12-bit SNORM value
 * round(clamp(u,-1,1) * 2047), offset by 2047 (codes 0..4094), as in Cigolle et al.'s oct24;
 * sol_oct_encode/decode give any bit count and also the UNORM quantizer
 * round((u * 0.5 + 0.5) * (2^bits - 1)) that many engines (and L. Tyler's error tables) use. */
#include "normals_internal.h"

/* The lower half's fold across the diagonals (its own inverse): (x, y) -> ((1-|y|) sgn x, (1-|x|) sgn y). */
static void oct_fold(double *x, double *y)
{
    double fx = (1.0 - fabs(*y)) * sol_normals_sign(*x), fy = (1.0 - fabs(*x)) * sol_normals_sign(*y);
    *x = fx;
    *y = fy;
}

/* Projects a unit vector onto the octahedron |x|+|y|+|z| = 1 and unfolds it to [-1,1]^2. */
static void oct_project(const double n[3], double p[2])
{
    double s = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
    double x = n[0] / s, y = n[1] / s;
    if (n[2] < 0.0) /* lower half */
        oct_fold(&x, &y);
    p[0] = x;
    p[1] = y;
}

static void oct_unproject(double x, double y, double n[3])
{
    double z = 1.0 - fabs(x) - fabs(y);
    if (z < 0.0)
        oct_fold(&x, &y);
    double v[3] = {x, y, z};
    double len = sqrt(sol_dot3(v, v)); /* >= 1/sqrt(3) on the octahedron */
    for (int i = 0; i < 3; ++i)
        n[i] = v[i] / len;
}

/* One quantizer. Values are rounded on a grid of integer positions k (k = round(u * scale) for
 * SNORM, round((u * 0.5 + 0.5) * scale) for UNORM) and stored as code = k + offset. */
typedef struct oct_quant {
    int unorm;      /* 0: SNORM, 1: UNORM */
    double scale;   /* SNORM: 2^(bits-1) - 1; UNORM: 2^bits - 1 */
    int offset;     /* SNORM: scale (code of 0); UNORM: 0 */
    int max_valid;  /* largest code of a value in [-1, 1] */
    uint32_t last;  /* largest code, 2^bits - 1 */
} oct_quant;

static oct_quant oct_quant_of(int bits, sol_oct_quantizer quantizer)
{
    oct_quant q;
    q.unorm = quantizer == SOL_OCT_UNORM;
    q.scale = q.unorm ? (double)((1u << bits) - 1u) : (double)((1u << (bits - 1)) - 1u);
    q.offset = q.unorm ? 0 : (int)q.scale;
    q.max_valid = q.unorm ? (int)q.scale : 2 * (int)q.scale;
    q.last = (1u << bits) - 1u;
    return q;
}

/* Position of value u on the integer grid (before the offset). */
static double oct_grid(const oct_quant *q, double u)
{
    return q->unorm ? (u * 0.5 + 0.5) * q->scale : u * q->scale;
}

static double oct_value(const oct_quant *q, uint32_t code)
{
    if (q->unorm)
        return (double)code / q->scale * 2.0 - 1.0;
    /* SNORM: code 2^bits - 1 lies outside the range and clamps to +1, like a GPU's SNORM read */
    int k = (int)code - q->offset;
    return k > q->offset ? 1.0 : k / q->scale;
}

static void oct_decode_q(const oct_quant *q, uint32_t cx, uint32_t cy, double n[3])
{
    oct_unproject(oct_value(q, cx), oct_value(q, cy), n);
}

/* Nearest code (round half up) or, precise, the best of the 4 surrounding codes by angle. */
static void oct_encode_q(const oct_quant *q, const double unit[3], int precise, uint32_t code[2])
{
    double p[2];
    oct_project(unit, p);
    double gx = oct_grid(q, p[0]), gy = oct_grid(q, p[1]);
    if (!precise) {
        code[0] = (uint32_t)((int)floor(gx + 0.5) + q->offset);
        code[1] = (uint32_t)((int)floor(gy + 0.5) + q->offset);
        return;
    }
    /* Cigolle et al.'s precise variant: the best of the four surrounding codes by angle. */
    double best_angle = HUGE_VAL;
    for (int k = 0; k < 4; ++k) {
        int cx = (int)floor(gx) + (k & 1) + q->offset, cy = (int)floor(gy) + (k >> 1) + q->offset;
        if (cx > q->max_valid || cy > q->max_valid)
            continue;
        double back[3];
        oct_decode_q(q, (uint32_t)cx, (uint32_t)cy, back);
        double angle = sol_angle3(unit, back);
        if (angle < best_angle) {
            best_angle = angle;
            code[0] = (uint32_t)cx;
            code[1] = (uint32_t)cy;
        }
    }
}

void sol_normals_decode_octahedral(uint32_t code, double n[3])
{
    oct_quant q = oct_quant_of(12, SOL_OCT_SNORM);
    oct_decode_q(&q, code & 4095u, code >> 12, n);
}

uint32_t sol_normals_encode_octahedral(const double unit[3], int precise)
{
    oct_quant q = oct_quant_of(12, SOL_OCT_SNORM);
    uint32_t c[2];
    oct_encode_q(&q, unit, precise, c);
    return c[0] | (c[1] << 12);
}

/* The quantiser the options ask for (zero-initialised options: 12 bits, SNORM, plain rounding). */
static sol_status oct_options(const sol_oct_options *opt, oct_quant *q)
{
    sol_oct_options o = opt ? *opt : (sol_oct_options){0};
    int b = o.bits ? o.bits : 12;
    if (b < 2 || b > 16 || (o.quantizer != SOL_OCT_SNORM && o.quantizer != SOL_OCT_UNORM) || o.precise < 0 ||
        o.precise > 1)
        return SOL_ERR_INVALID_ARG;
    *q = oct_quant_of(b, o.quantizer);
    return SOL_OK;
}

sol_status sol_oct_encode(const sol_oct_options *opt, const double n[3], uint32_t code[2])
{
    if (!n || !code)
        return SOL_ERR_NULL_ARG;
    oct_quant q;
    sol_status st = oct_options(opt, &q);
    if (st != SOL_OK)
        return st;
    double u[3];
    if ((st = sol_normals_unit_input(n, u)) != SOL_OK)
        return st;
    oct_encode_q(&q, u, opt ? opt->precise : 0, code);
    return SOL_OK;
}

sol_status sol_oct_decode(const sol_oct_options *opt, const uint32_t code[2], double n[3])
{
    if (!code || !n)
        return SOL_ERR_NULL_ARG;
    oct_quant q;
    sol_status st = oct_options(opt, &q);
    if (st != SOL_OK)
        return st;
    if (code[0] > q.last || code[1] > q.last)
        return SOL_ERR_INVALID_ARG;
    oct_decode_q(&q, code[0], code[1], n);
    return SOL_OK;
}
