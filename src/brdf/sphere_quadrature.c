/* sphere_quadrature.c - adaptive nested Gauss-Kronrod and stratified Monte Carlo integration over
 * the sphere, shared by the BRDF and SG experiments (claims D8, D15, D16). */
#include <math.h>
#include <stdlib.h>

#include "sol_brdf.h"

/* Gauss-Kronrod 7/15 nodes and weights on [-1, 1] (Piessens et al., QUADPACK 1983). Index 7 is the
 * centre; odd indices are the Gauss-7 nodes. */
static const double gk_x[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                               0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                               0.207784955007898468, 0.0};
static const double gk_wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                                0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                                0.204432940075298892, 0.209482141084727828};
static const double gk_wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                                0.417959183673469388};

typedef double (*line_fn)(double x, void *ctx);

typedef struct interval {
    double a, b, value, error;
} interval;

static void gk15(line_fn f, void *ctx, interval *iv)
{
    double c = 0.5 * (iv->a + iv->b), h = 0.5 * (iv->b - iv->a);
    double fc = f(c, ctx);
    double k = gk_wk[7] * fc, g = gk_wg[3] * fc;
    for (int i = 0; i < 7; ++i) {
        double s = f(c - h * gk_x[i], ctx) + f(c + h * gk_x[i], ctx);
        k += gk_wk[i] * s;
        if (i & 1)
            g += gk_wg[i / 2] * s;
    }
    iv->value = k * h;
    iv->error = fabs((k - g) * h);
}

typedef struct adapt_options {
    double abs_tol, rel_tol;
    int max_intervals;
} adapt_options;

/* Adaptive bisection of the worst interval, starting from the given breakpoints (n_breaks >= 2).
 * Returns 0 when the targets were met, 1 when the budget ran out, -1 on allocation failure. */
static int adapt(line_fn f, void *ctx, const double *breaks, int n_breaks, const adapt_options *o, double *value,
                 double *error)
{
    int cap = o->max_intervals > n_breaks ? o->max_intervals : n_breaks;
    interval *iv = malloc((size_t)cap * sizeof *iv);
    if (!iv)
        return -1;
    int n = n_breaks - 1;
    for (int i = 0; i < n; ++i) {
        iv[i].a = breaks[i];
        iv[i].b = breaks[i + 1];
        gk15(f, ctx, &iv[i]);
    }
    int status = 0;
    for (;;) {
        double v = 0.0, e = 0.0;
        int worst = 0;
        for (int i = 0; i < n; ++i) {
            v += iv[i].value;
            e += iv[i].error;
            if (iv[i].error > iv[worst].error)
                worst = i;
        }
        *value = v;
        *error = e;
        if (!(e > o->abs_tol) || !(e > o->rel_tol * fabs(v)))
            break;
        if (n >= cap) {
            status = 1;
            break;
        }
        double mid = 0.5 * (iv[worst].a + iv[worst].b);
        iv[n].a = mid;
        iv[n].b = iv[worst].b;
        iv[worst].b = mid;
        gk15(f, ctx, &iv[worst]);
        gk15(f, ctx, &iv[n]);
        ++n;
    }
    free(iv);
    return status;
}

typedef struct sphere_ctx {
    sol_sphere_fn f;
    void *ctx;
    double t[3], b[3], p[3]; /* frame: tangent, bitangent, pole */
    double sin_t, cos_t;     /* current polar angle */
    adapt_options inner;
    int failed;              /* inner budget exhausted (1), allocation failure (-1), NaN (2) */
} sphere_ctx;

static double phi_integrand(double phi, void *vctx)
{
    sphere_ctx *s = vctx;
    double cp = cos(phi), sp = sin(phi), d[3];
    for (int i = 0; i < 3; ++i)
        d[i] = s->sin_t * (cp * s->t[i] + sp * s->b[i]) + s->cos_t * s->p[i];
    double y = s->f(d, s->ctx);
    if (isnan(y)) {
        s->failed = 2;
        return 0.0;
    }
    return y;
}

static double theta_integrand(double theta, void *vctx)
{
    sphere_ctx *s = vctx;
    s->sin_t = sin(theta);
    s->cos_t = cos(theta);
    static const double phi_breaks[5] = {0.0, 0.5 * M_PI, M_PI, 1.5 * M_PI, 2.0 * M_PI};
    double v, e;
    int st = adapt(phi_integrand, s, phi_breaks, 5, &s->inner, &v, &e);
    if (st != 0 && s->failed != 2)
        s->failed = st;
    return v * s->sin_t;
}

/* Any unit vector orthogonal to p, stable for every direction (Frisvad-style branch on |p.z|). */
static void orthonormal_basis(const double p[3], double t[3], double b[3])
{
    if (fabs(p[2]) < 0.9) {
        double len = sqrt(p[0] * p[0] + p[1] * p[1]);
        t[0] = -p[1] / len, t[1] = p[0] / len, t[2] = 0.0;
    } else {
        double len = sqrt(p[1] * p[1] + p[2] * p[2]);
        t[0] = 0.0, t[1] = p[2] / len, t[2] = -p[1] / len;
    }
    b[0] = p[1] * t[2] - p[2] * t[1];
    b[1] = p[2] * t[0] - p[0] * t[2];
    b[2] = p[0] * t[1] - p[1] * t[0];
}

sol_status sol_sphere_integrate(sol_sphere_fn f, void *ctx, const double pole[3], const sol_quad_options *opts,
                                double *result, double *error)
{
    if (!f || !pole || !result)
        return SOL_ERR_NULL_ARG;
    if (!isfinite(pole[0]) || !isfinite(pole[1]) || !isfinite(pole[2]))
        return SOL_ERR_NONFINITE;
    double len = sqrt(sol_dot3(pole, pole));
    if (!(len > 0.0))
        return SOL_ERR_ZERO_LENGTH;
    sol_quad_options o = opts ? *opts : (sol_quad_options){0};
    double abs_tol = o.abs_tol > 0.0 ? o.abs_tol : 1e-10, rel_tol = o.rel_tol > 0.0 ? o.rel_tol : 1e-8;
    int max_iv = o.max_intervals > 0 ? o.max_intervals : 400;
    double theta_max = o.theta_max > 0.0 && o.theta_max < M_PI ? o.theta_max : M_PI;

    sphere_ctx s = {.f = f, .ctx = ctx};
    for (int i = 0; i < 3; ++i)
        s.p[i] = pole[i] / len;
    orthonormal_basis(s.p, s.t, s.b);
    s.inner = (adapt_options){abs_tol * 0.1 / M_PI, rel_tol * 0.1, max_iv};
    /* Geometric breakpoints towards the pole: a lobe of width 1e-3 rad at theta = 0 is seen by the
     * first rule instead of slipping between the nodes of one wide interval. */
    enum { N_GEOM = 14 };
    double breaks[N_GEOM + 2];
    breaks[0] = 0.0;
    for (int i = 0; i <= N_GEOM; ++i)
        breaks[i + 1] = theta_max * ldexp(1.0, i - N_GEOM);
    adapt_options outer = {abs_tol, rel_tol, max_iv};
    double v, e;
    int st = adapt(theta_integrand, &s, breaks, N_GEOM + 2, &outer, &v, &e);
    if (st < 0 || s.failed < 0)
        return SOL_ERR_NO_MEMORY;
    if (s.failed == 2 || isnan(v))
        return SOL_ERR_NONFINITE;
    *result = v;
    if (error)
        *error = e;
    return (st != 0 || s.failed != 0) ? SOL_ERR_NO_CONVERGENCE : SOL_OK;
}

sol_status sol_gauss_legendre(int n, double *x, double *w)
{
    if (!x || !w)
        return SOL_ERR_NULL_ARG;
    if (n < 1 || n > 256)
        return SOL_ERR_INVALID_ARG;
    for (int i = 0; i < n; ++i) {
        /* Tricomi's initial guess, then Newton on the three-term recurrence. */
        double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16)
                break;
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    return SOL_OK;
}

static double unit_double(uint64_t x)
{
    return (double)(x >> 11) * 0x1.0p-53;
}

sol_status sol_sphere_integrate_mc(sol_sphere_fn f, void *ctx, int strata, uint64_t seed, double *result,
                                   double *error)
{
    if (!f || !result)
        return SOL_ERR_NULL_ARG;
    if (strata < 2 || strata > 1 << 15)
        return SOL_ERR_INVALID_ARG;
    size_t n = (size_t)strata * (size_t)strata;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
        uint64_t h = sol_mix64(seed ^ sol_mix64(i)); /* per-stratum: independent of order */
        double u = ((double)(i % (size_t)strata) + unit_double(h)) / strata;
        double w = ((double)(i / (size_t)strata) + unit_double(sol_mix64(h))) / strata;
        double d[3];
        sol_sphere_uniform(u, w, d);
        double y = f(d, ctx);
        if (isnan(y))
            return SOL_ERR_NONFINITE;
        sum += y;
        sum2 += y * y;
    }
    double mean = sum / (double)n;
    *result = 4.0 * M_PI * mean;
    if (error) {
        /* The spread between cells bounds the stratified estimator's error from above. */
        double var = sum2 / (double)n - mean * mean;
        *error = 4.0 * M_PI * sqrt((var > 0.0 ? var : 0.0) / (double)n);
    }
    return SOL_OK;
}
