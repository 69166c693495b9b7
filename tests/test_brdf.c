/* test_brdf.c - BRDF normalisation (D8), SG identities against quadrature (D15, D16), the Ceres
 * shim, the Ward-to-SG fit on reference cases (D15), lobe extraction (D16) and the hard cases. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "sol_brdf.h"

static const double Z[3] = {0.0, 0.0, 1.0};

static double integrate(sol_sphere_fn f, void *ctx, const double pole[3], double theta_max)
{
    sol_quad_options o = {.rel_tol = 1e-10, .abs_tol = 1e-14, .theta_max = theta_max, .max_intervals = 2000};
    double v = NAN, e;
    sol_status st = sol_sphere_integrate(f, ctx, pole, &o, &v, &e);
    cr_assert(st == SOL_OK || st == SOL_ERR_NO_CONVERGENCE, "quadrature failed: %s", sol_status_string(st));
    return v;
}

/* ---------------- BRDF normalisation (D8) ---------------- */

typedef struct lobe_ctx {
    double r[3], n, ax, ay;
} lobe_ctx;

static double normalized_phong_cos(const double l[3], void *c)
{
    const lobe_ctx *p = c;
    return sol_phong_normalized(sol_dot3(p->r, l), p->n) * (l[2] > 0 ? l[2] : 0);
}

Test(brdf, d8_normalized_phong_albedo_is_one_at_normal_for_n_1_to_1e4)
{
    static const double ns[] = {0, 1, 5, 120, 250, 1e4};
    for (int i = 0; i < 6; ++i) {
        lobe_ctx c = {{0, 0, 1}, ns[i], 0, 0};
        cr_assert_float_eq(integrate(normalized_phong_cos, &c, Z, 0), 1.0, 1e-7, "n = %g", ns[i]);
    }
}

Test(brdf, d8_normalized_phong_albedo_at_grazing_reflection_is_below_one)
{
    lobe_ctx c = {{1, 0, 0}, 20, 0, 0};
    double a = integrate(normalized_phong_cos, &c, c.r, 0);
    cr_assert(a > 0.0 && a < 0.5, "albedo %g", a);
}

typedef struct blinn_ctx {
    double n, factor;
} blinn_ctx;

static double blinn_cos(const double l[3], void *c)
{
    const blinn_ctx *b = c;
    if (!(l[2] > 0))
        return 0;
    return b->factor * sol_blinn_phong_raw(sqrt(0.5 * (1 + l[2])), b->n) * l[2];
}

Test(brdf, d8_blinn_phong_exact_factor_normalizes_and_approximation_is_close)
{
    static const double ns[] = {0, 1, 10, 100, 1000};
    for (int i = 0; i < 5; ++i) {
        blinn_ctx c = {ns[i], sol_blinn_phong_norm_factor_exact(ns[i])};
        cr_assert_float_eq(integrate(blinn_cos, &c, Z, 0.5 * M_PI), 1.0, 1e-7, "n = %g", ns[i]);
        double ratio = sol_blinn_phong_norm_factor_approx(ns[i]) / c.factor;
        cr_assert(ratio > 0.99 && ratio < 1.08, "n = %g ratio %g", ns[i], ratio);
    }
}

static double ward_ndf_cos(const double h[3], void *c)
{
    const lobe_ctx *p = c;
    return sol_ward_ndf(h, p->ax, p->ay) * (h[2] > 0 ? h[2] : 0);
}

Test(brdf, ward_ndf_is_normalized_from_alpha_1e_4_to_1)
{
    static const double a[][2] = {{0.1, 0.3}, {1.0, 1.0}, {1e-3, 1e-2}, {1e-4, 1e-4}, {0.05, 1.0}};
    for (int i = 0; i < 5; ++i) {
        lobe_ctx c = {{0}, 0, a[i][0], a[i][1]};
        cr_assert_float_eq(integrate(ward_ndf_cos, &c, Z, 0.5 * M_PI), 1.0, 1e-6, "alpha %g %g", a[i][0], a[i][1]);
    }
}

typedef struct iso_ctx {
    int ggx;
    double alpha;
} iso_ctx;

static double iso_ndf_cos(const double h[3], void *c)
{
    const iso_ctx *p = c;
    double d = p->ggx ? sol_ggx_ndf(h[2], p->alpha) : sol_beckmann_ndf(h[2], p->alpha);
    return d * (h[2] > 0 ? h[2] : 0);
}

Test(brdf, beckmann_and_ggx_are_normalized)
{
    static const double alphas[] = {1e-3, 0.1, 0.5, 1.0};
    for (int g = 0; g < 2; ++g)
        for (int i = 0; i < 4; ++i) {
            iso_ctx c = {g, alphas[i]};
            /* GGX's tail decays like theta^-4: a looser tolerance for the widest lobe. */
            cr_assert_float_eq(integrate(iso_ndf_cos, &c, Z, 0.5 * M_PI), 1.0, 1e-5, "ggx %d alpha %g", g, alphas[i]);
        }
}

Test(brdf, microfacet_terms_at_their_edges)
{
    cr_assert_float_eq(sol_fresnel_schlick(0.04, 1.0), 0.04, 1e-15);
    cr_assert_float_eq(sol_fresnel_schlick(0.04, 0.0), 1.0, 1e-15);
    cr_assert_float_eq(sol_fresnel_schlick(0.04, -0.0), 1.0, 1e-15);
    cr_assert_float_eq(sol_smith_g1_ggx(1.0, 0.5), 1.0, 1e-15);
    cr_assert_eq(sol_smith_g1_ggx(0.0, 0.5), 0.0);
    cr_assert_eq(sol_smith_g1_beckmann(1.0, 0.5), 1.0);
    cr_assert_eq(sol_smith_g1_beckmann(0.0, 0.5), 0.0);
    for (double c = 1e-6; c <= 1.0; c *= 3.0) {
        double g = sol_smith_g1_beckmann(c, 0.3), h = sol_smith_g1_ggx(c, 0.3);
        cr_assert(g >= 0 && g <= 1.0 + 1e-12 && h >= 0 && h <= 1.0 + 1e-12);
    }
    /* Tiny roughness: the peak is finite and exactly 1 / (pi alpha^2). */
    cr_assert_float_eq(sol_ggx_ndf(1.0, 1e-4), 1.0 / (M_PI * 1e-8), 1e-3);
    cr_assert(isfinite(sol_beckmann_ndf(1.0, 1e-4)));
    cr_assert_eq(sol_beckmann_ndf(0.99, 1e-4), 0.0); /* far in the tail: underflow to 0, not NaN */
    cr_assert_eq(sol_ggx_ndf(0.5, 0.0), 0.0);
}

Test(brdf, brdfs_are_finite_at_grazing_and_propagate_nan)
{
    double v[3] = {1.0, 0.0, 1e-300}, l[3] = {-1.0, 0.0, 1e-300}, l2[3] = {0.0, 1.0, 0.0};
    cr_assert(isfinite(sol_cook_torrance(v, l, SOL_NDF_GGX, 0.3, 0.04)));
    cr_assert(isfinite(sol_cook_torrance(v, l, SOL_NDF_BECKMANN, 1e-4, 0.04)));
    cr_assert(isfinite(sol_ward_brdf(v, l, 0.1, 0.3)));
    cr_assert_eq(sol_ward_brdf(v, l2, 0.1, 0.3), 0.0); /* light on the horizon */
    double h[3] = {1.0, 0.0, 0.0}, hz[3] = {0.0, 0.0, -0.0};
    cr_assert_eq(sol_ward_ndf(h, 0.1, 0.3), 0.0);
    cr_assert_eq(sol_ward_ndf(hz, 0.1, 0.3), 0.0);
    double hn[3] = {NAN, 0.0, 1.0};
    cr_assert(isnan(sol_ward_ndf(hn, 0.1, 0.3)));
    cr_assert(isnan(sol_phong_normalized(NAN, 10)));
    cr_assert(isnan(sol_ggx_ndf(NAN, 0.1)));
    cr_assert(isnan(sol_cook_torrance(v, hn, SOL_NDF_GGX, 0.3, 0.04)));
    cr_assert_eq(sol_phong_raw(-0.0, 0.0), 0.0);
    cr_assert_eq(sol_phong_raw(1.0, 1e6), 1.0);
    cr_assert(isfinite(sol_phong_normalized(0.999, 1e300)));
}

/* ---------------- sphere quadrature ---------------- */

static double constant_one(const double d[3], void *c)
{
    (void)d, (void)c;
    return 1.0;
}

static double nan_at_pole(const double d[3], void *c)
{
    (void)c;
    return d[2] > 0.999 ? NAN : 1.0;
}

Test(brdf, sphere_quadrature_areas_and_errors)
{
    double v = -1, e;
    double pole[3] = {0.3, -0.2, 0.9};
    cr_assert_float_eq(integrate(constant_one, NULL, pole, 0), 4 * M_PI, 1e-10);
    cr_assert_float_eq(integrate(constant_one, NULL, Z, 0.5 * M_PI), 2 * M_PI, 1e-10);
    double zero[3] = {0, 0, 0}, bad[3] = {NAN, 0, 1};
    cr_assert_eq(sol_sphere_integrate(constant_one, NULL, zero, NULL, &v, &e), SOL_ERR_ZERO_LENGTH);
    cr_assert_eq(sol_sphere_integrate(constant_one, NULL, bad, NULL, &v, &e), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_sphere_integrate(NULL, NULL, Z, NULL, &v, &e), SOL_ERR_NULL_ARG);
    cr_assert_eq(sol_sphere_integrate(nan_at_pole, NULL, Z, NULL, &v, &e), SOL_ERR_NONFINITE);
    cr_assert_eq(v, -1); /* untouched on error */
    cr_assert_eq(sol_sphere_integrate_mc(constant_one, NULL, 1, 0, &v, &e), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_sphere_integrate_mc(nan_at_pole, NULL, 64, 0, &v, &e), SOL_ERR_NONFINITE);
}

Test(brdf, gauss_legendre_is_exact_for_degree_2n_minus_1)
{
    double x[256], w[256];
    static const int orders[] = {1, 2, 7, 24, 256};
    for (int o = 0; o < 5; ++o) {
        int n = orders[o];
        cr_assert_eq(sol_gauss_legendre(n, x, w), SOL_OK);
        double deg = n > 8 ? 14 : 2 * n - 2; /* even power (odd ones vanish by symmetry) */
        double s = 0.0, s1 = 0.0;
        for (int i = 0; i < n; ++i) {
            s += w[i] * pow(x[i], deg);
            s1 += w[i];
        }
        cr_assert_float_eq(s, 2.0 / (deg + 1.0), 1e-13, "n = %d", n);
        cr_assert_float_eq(s1, 2.0, 1e-13);
    }
    cr_assert_eq(sol_gauss_legendre(0, x, w), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_gauss_legendre(257, x, w), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_gauss_legendre(4, NULL, w), SOL_ERR_NULL_ARG);
}

Test(brdf, stratified_mc_agrees_with_adaptive_quadrature)
{
    lobe_ctx c = {{0.6, 0, 0.8}, 20, 0, 0};
    double exact = integrate(normalized_phong_cos, &c, c.r, 0), v, e;
    cr_assert_eq(sol_sphere_integrate_mc(normalized_phong_cos, &c, 256, 7, &v, &e), SOL_OK);
    cr_assert(fabs(v - exact) < 4 * e + 1e-12, "mc %g +- %g vs %g", v, e, exact);
}

/* ---------------- Spherical Gaussians ---------------- */

static sol_sg sg(double theta, double phi, double lambda, double a)
{
    sol_sg g = {{sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)}, lambda, a};
    return g;
}

static double sg_fn(const double d[3], void *c)
{
    return sol_sg_eval(c, d);
}

typedef struct pair_ctx {
    const sol_sg *a, *b;
} pair_ctx;

static double sg_pair_fn(const double d[3], void *c)
{
    const pair_ctx *p = c;
    return sol_sg_eval(p->a, d) * sol_sg_eval(p->b, d);
}

Test(brdf, sg_integral_matches_quadrature_for_sharpness_0_to_1e6)
{
    static const double ls[] = {0.0, 1e-300, 1e-3, 1.0, 100.0, 1e4, 1e6};
    for (int i = 0; i < 7; ++i) {
        sol_sg g = sg(0.4, 1.0, ls[i], 2.5);
        double q = integrate(sg_fn, &g, g.axis, 0), s = sol_sg_integral(&g);
        cr_assert(isfinite(s));
        cr_assert_float_eq(s / q, 1.0, 1e-7, "lambda %g: %g vs %g", ls[i], s, q);
    }
    sol_sg z = sg(0, 0, 0.0, 1.0);
    cr_assert_float_eq(sol_sg_integral(&z), 4 * M_PI, 1e-15);
}

Test(brdf, sg_product_is_exact_and_inner_product_matches_quadrature)
{
    sol_sg a = sg(0.3, 0.2, 30.0, 1.5), b = sg(0.9, 2.0, 12.0, 0.7);
    sol_sg p = sol_sg_product(&a, &b);
    for (int i = 0; i < 50; ++i) {
        double u, v, d[3];
        sol_r2_point((uint64_t)i, &u, &v);
        sol_sphere_uniform(u, v, d);
        double direct = sol_sg_eval(&a, d) * sol_sg_eval(&b, d);
        cr_assert(fabs(sol_sg_eval(&p, d) - direct) <= 1e-12 * (1 + direct));
    }
    pair_ctx c = {&a, &b};
    cr_assert_float_eq(sol_sg_inner_product(&a, &b) / integrate(sg_pair_fn, &c, p.axis, 0), 1.0, 1e-7);
}

Test(brdf, sg_algebra_stays_finite_at_extreme_sharpness)
{
    sol_sg a = sg(0, 0, 1e6, 1.0), b = sg(M_PI, 0, 1e6, 1.0), c = sg(1e-4, 0, 1e6, 1.0);
    cr_assert_eq(sol_sg_inner_product(&a, &b), 0.0); /* opposite, sharp: exp(-2e6) underflows cleanly */
    sol_sg p = sol_sg_product(&a, &b);
    cr_assert(isfinite(p.sharpness) && isfinite(p.amplitude) && isfinite(p.axis[2]));
    double ip = sol_sg_inner_product(&a, &c);
    cr_assert(isfinite(ip) && ip > 0);
    pair_ctx pc = {&a, &c};
    sol_sg pr = sol_sg_product(&a, &c);
    cr_assert_float_eq(ip / integrate(sg_pair_fn, &pc, pr.axis, 0), 1.0, 1e-6);
    sol_sg conv = sol_sg_convolve(&a, &c);
    cr_assert(isfinite(conv.amplitude) && fabs(conv.sharpness - 5e5) < 1e-6);
    sol_sg zero = sg(0, 0, 0, 1.0);
    sol_sg cz = sol_sg_convolve(&zero, &zero);
    cr_assert_float_eq(sol_sg_integral(&cz), 16 * M_PI * M_PI, 1e-9);
    cr_assert_eq(sol_sg_eval(&a, Z), 1.0);
}

typedef struct conv_ctx {
    const sol_sg *a, *kernel;
    double at[3];
} conv_ctx;

static double conv_fn(const double d[3], void *c)
{
    const conv_ctx *p = c;
    /* The kernel's axis is moved to the evaluation point: k(at . d). */
    sol_sg k = *p->kernel;
    memcpy(k.axis, p->at, sizeof k.axis);
    return sol_sg_eval(p->a, d) * sol_sg_eval(&k, d);
}

Test(brdf, sg_convolution_preserves_the_integral_and_matches_narrow_lobes)
{
    sol_sg a = sg(0.2, 0.5, 200.0, 1.0), k = sg(0, 0, 300.0, 2.0);
    sol_sg c = sol_sg_convolve(&a, &k);
    cr_assert_float_eq(sol_sg_integral(&c) / (sol_sg_integral(&a) * sol_sg_integral(&k)), 1.0, 1e-12);
    conv_ctx ctx = {&a, &k, {a.axis[0], a.axis[1], a.axis[2]}};
    double direct = integrate(conv_fn, &ctx, a.axis, 0);
    cr_assert_float_eq(sol_sg_eval(&c, a.axis) / direct, 1.0, 1e-2);
}

typedef struct cos_ctx {
    const sol_sg *g;
    double n[3];
} cos_ctx;

static double sg_cos_fn(const double d[3], void *c)
{
    const cos_ctx *p = c;
    double cn = sol_dot3(p->n, d);
    return cn > 0 ? sol_sg_eval(p->g, d) * cn : 0.0;
}

Test(brdf, sg_cosine_convolution_matches_quadrature_including_horizon)
{
    static const double ls[] = {0.0, 0.5, 10.0, 1e3, 1e6};
    static const double angles[] = {0.0, 0.7, M_PI / 2, 2.0, M_PI};
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
            sol_sg g = sg(angles[j], 0.3, ls[i], 1.3);
            cos_ctx c = {&g, {0, 0, 1}};
            double q = integrate(sg_cos_fn, &c, g.axis, 0), s = sol_sg_cosine_convolve(&g, c.n);
            double scale = sol_sg_integral(&g);
            cr_assert(fabs(s - q) <= 1e-6 * scale, "lambda %g angle %g: %.12g vs %.12g", ls[i], angles[j], s, q);
        }
    sol_sg bad = sg(0, 0, NAN, 1.0);
    cr_assert(isnan(sol_sg_cosine_convolve(&bad, Z)));
}

Test(brdf, sg_rotation_and_asg)
{
    sol_sg g = sg(0, 0, 5, 1);
    const double rot_x90[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0};
    sol_sg r = sol_sg_rotate(&g, rot_x90);
    cr_assert_float_eq(r.axis[1], -1.0, 1e-15);
    cr_assert_eq(r.sharpness, 5);
    sol_asg a = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 10, 100, 2.0};
    cr_assert_float_eq(sol_asg_eval(&a, Z), 2.0, 1e-15);
    double below[3] = {0, 0, -1}, nan_v[3] = {0, 0, NAN};
    cr_assert_eq(sol_asg_eval(&a, below), 0.0);
    cr_assert(isnan(sol_asg_eval(&a, nan_v)));
}

/* ---------------- Ceres shim ---------------- */

/* Residuals y_i - a exp(-b t_i) for data made with a = 2, b = 0.5. */
static int decay_residuals(void *ctx, const double *p, double *r, double *jac)
{
    (void)ctx;
    for (int i = 0; i < 10; ++i) {
        double t = 0.3 * i, e = exp(-p[1] * t);
        r[i] = p[0] * e - 2.0 * exp(-0.5 * t);
        if (jac) {
            jac[2 * i] = e;
            jac[2 * i + 1] = -p[0] * t * e;
        }
    }
    return 0;
}

static int failing_residuals(void *ctx, const double *p, double *r, double *jac)
{
    (void)ctx, (void)p, (void)r, (void)jac;
    return 1;
}

Test(brdf, ceres_shim_solves_respects_bounds_and_reports_failure)
{
    double p[2] = {1.0, 1.0};
    sol_lsq_problem prob = {2, 10, decay_residuals, NULL, NULL, NULL, 0, SOL_LSQ_DENSE_NORMAL_CHOLESKY};
    sol_lsq_summary s;
    cr_assert_eq(sol_lsq_solve(&prob, p, &s), SOL_OK);
    cr_assert_float_eq(p[0], 2.0, 1e-6);
    cr_assert_float_eq(p[1], 0.5, 1e-6);
    cr_assert(s.final_cost < 1e-12 && s.converged);

    double lo[2] = {0.0, 0.8}, hi[2] = {10.0, 2.0}, q[2] = {1.0, 1.0};
    prob.lower = lo, prob.upper = hi;
    cr_assert_eq(sol_lsq_solve(&prob, q, NULL), SOL_OK);
    cr_assert_float_eq(q[1], 0.8, 1e-9); /* the optimum 0.5 is outside: stops at the bound */

    double out_of_bounds[2] = {1.0, 3.0}, nan_start[2] = {NAN, 1.0}, keep[2] = {1.0, 1.0};
    cr_assert_eq(sol_lsq_solve(&prob, out_of_bounds, NULL), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_lsq_solve(&prob, nan_start, NULL), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_lsq_solve(NULL, keep, NULL), SOL_ERR_NULL_ARG);
    sol_lsq_problem bad = {2, 10, failing_residuals, NULL, NULL, NULL, 0, SOL_LSQ_DENSE_NORMAL_CHOLESKY};
    cr_assert_eq(sol_lsq_solve(&bad, keep, NULL), SOL_ERR_SOLVER);
    cr_assert(keep[0] == 1.0 && keep[1] == 1.0);
    sol_lsq_problem empty = {0, 10, decay_residuals, NULL, NULL, NULL, 0, SOL_LSQ_DENSE_NORMAL_CHOLESKY};
    cr_assert_eq(sol_lsq_solve(&empty, keep, NULL), SOL_ERR_INVALID_ARG);
    /* Both linear solvers reach the same optimum; an unknown one is rejected, params untouched. */
    double r[2] = {1.0, 1.0};
    sol_lsq_problem qr = {2, 10, decay_residuals, NULL, NULL, NULL, 0, SOL_LSQ_DENSE_QR};
    cr_assert_eq(sol_lsq_solve(&qr, r, NULL), SOL_OK);
    cr_assert_float_eq(r[0], 2.0, 1e-6);
    cr_assert_float_eq(r[1], 0.5, 1e-6);
    sol_lsq_problem unknown = {2, 10, decay_residuals, NULL, NULL, NULL, 0, 7};
    cr_assert_eq(sol_lsq_solve(&unknown, keep, NULL), SOL_ERR_INVALID_ARG);
    cr_assert(keep[0] == 1.0 && keep[1] == 1.0);
}

/* ---------------- Ward -> SG fit (D15) ---------------- */

Test(brdf, d15_fit_quality_on_reference_cells)
{
    sol_sg lobes[21];
    sol_sg_fit_error e[6];
    sol_lsq_summary s[6];
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.1, 1, NULL, lobes, e, s), SOL_OK);
    cr_assert(e[0].rel_l2 < 0.01, "isotropic 0.1, K = 1: %g", e[0].rel_l2);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.2, 6, NULL, lobes, e, s), SOL_OK);
    for (int k = 1; k < 6; ++k)
        cr_assert(e[k].rel_l2 <= e[k - 1].rel_l2, "error rose at K = %d", k + 1);
    cr_assert(e[4].rel_l2 < 0.02, "ax 0.1 ay 0.2, K = 5: %g", e[4].rel_l2);
    cr_assert(fabs(e[4].energy) < 0.01);
    /* The fitted lobes, in NDF units, reproduce the stated error through sol_ward_sg_error. */
    sol_sg_fit_error again;
    cr_assert_eq(sol_ward_sg_error(0.1, 0.2, lobes + 10, 5, NULL, &again), SOL_OK);
    cr_assert_float_eq(again.rel_l2, e[4].rel_l2, 1e-12);
    for (int j = 0; j < 5; ++j)
        cr_assert(lobes[10 + j].sharpness <= 1e6 && lobes[10 + j].amplitude >= 0);
}

Test(brdf, d15_fit_rejects_bad_input_without_touching_outputs)
{
    sol_sg lobes[3] = {{{0, 0, 0}, 7, 7}};
    sol_sg_fit_error e[2] = {{7, 7, 7}};
    cr_assert_eq(sol_ward_sg_fit(NAN, 0.1, 2, NULL, lobes, e, NULL), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_ward_sg_fit(1e-4, 0.1, 2, NULL, lobes, e, NULL), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.1, 0, NULL, lobes, e, NULL), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.1, 2, NULL, NULL, e, NULL), SOL_ERR_NULL_ARG);
    cr_assert(lobes[0].sharpness == 7 && e[0].rel_l2 == 7);
}

/* Issue 12 item 5: at the documented alpha edges (1e-3 and 10) every start must lie inside the
 * solver's bounds (the sharpness cap 1e6 and floor 0.01, the amplitude cap), for every k_max. */
Test(brdf, d15_fit_works_at_the_documented_alpha_edges)
{
    static const double edges[][2] = {{1e-3, 1e-3}, {1e-3, 0.1}, {0.002, 0.002}, {1.5e-3, 10.0},
                                      {10.0, 10.0}, {10.0, 0.5},  {0.1, 10.0},   {5.0, 10.0}};
    /* Coarse nodes: this test is about the starts and bounds, not the quality (at ratio 6667 the
     * default azimuthal count grows 82x). */
    sol_sg_fit_options coarse = {.radial_samples = 8, .angular_samples = 6, .eval_radial = 16, .eval_angular = 24};
    sol_sg lobes[10];
    sol_sg_fit_error e[4];
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; ++i) {
        double ax = edges[i][0], ay = edges[i][1];
        for (int k_max = 1; k_max <= 4; ++k_max) {
            cr_assert_eq(sol_ward_sg_fit(ax, ay, k_max, &coarse, lobes, e, NULL), SOL_OK, "alpha (%g, %g), k_max %d",
                         ax, ay, k_max);
            for (int k = 0; k < k_max; ++k)
                cr_assert(isfinite(e[k].rel_l2) && (k == 0 || e[k].rel_l2 <= e[k - 1].rel_l2),
                          "alpha (%g, %g), K %d: error %g", ax, ay, k + 1, e[k].rel_l2);
            for (int j = 0; j < k_max * (k_max + 1) / 2; ++j)
                cr_assert(lobes[j].sharpness >= 0.01 * (1 - 1e-12) && lobes[j].sharpness <= 1e6 * (1 + 1e-12) &&
                          lobes[j].amplitude >= 0 && isfinite(lobes[j].amplitude));
        }
    }
    /* A sharp isotropic lobe is still one SG: the cap 1e6 on the sharpness binds at alpha 1e-3
     * (the NDF's curvature asks for 2e6), so the error is not tiny, but it is bounded. */
    cr_assert_eq(sol_ward_sg_fit(1e-3, 1e-3, 1, NULL, lobes, e, NULL), SOL_OK);
    cr_assert(e[0].rel_l2 < 0.5, "alpha 1e-3, K 1: %g", e[0].rel_l2);
}

/* The multi-start check of the last fit never raises its error, leaves the fits below k_max as
 * they were, and is deterministic; the two linear solvers give the same fits. */
Test(brdf, d15_extra_starts_only_lower_the_last_fit)
{
    sol_sg_fit_options base = {.radial_samples = 10, .angular_samples = 12, .eval_radial = 32, .eval_angular = 48};
    sol_sg_fit_options more = base, again = base, qr = base;
    more.extra_starts = again.extra_starts = 5;
    qr.linear_solver = SOL_LSQ_DENSE_QR;
    sol_sg l0[10], l1[10], l2[10], l3[10];
    sol_sg_fit_error e0[4], e1[4], e2[4], e3[4];
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 4, &base, l0, e0, NULL), SOL_OK);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 4, &more, l1, e1, NULL), SOL_OK);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 4, &again, l2, e2, NULL), SOL_OK);
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 4, &qr, l3, e3, NULL), SOL_OK);
    for (int k = 0; k < 3; ++k)
        cr_assert(e1[k].rel_l2 == e0[k].rel_l2, "K %d changed", k + 1);
    cr_assert(e1[3].rel_l2 <= e0[3].rel_l2);
    cr_assert(memcmp(l1, l2, sizeof l1) == 0 && e1[3].rel_l2 == e2[3].rel_l2);
    for (int k = 0; k < 4; ++k)
        cr_assert(fabs(e3[k].rel_l2 - e0[k].rel_l2) < 1e-3, "K %d: QR %g, Cholesky %g", k + 1, e3[k].rel_l2,
                  e0[k].rel_l2);
    sol_sg_fit_options bad = {.extra_starts = -1};
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 2, &bad, l0, e0, NULL), SOL_ERR_INVALID_ARG);
    bad = (sol_sg_fit_options){.linear_solver = (sol_lsq_linear_solver)2};
    cr_assert_eq(sol_ward_sg_fit(0.1, 0.3, 2, &bad, l0, e0, NULL), SOL_ERR_INVALID_ARG);
}

Test(brdf, d15_one_asg_fits_an_anisotropic_ward_lobe)
{
    sol_asg g;
    sol_sg_fit_error e;
    cr_assert_eq(sol_ward_asg_fit(0.05, 0.3, NULL, &g, &e, NULL), SOL_OK);
    cr_assert(e.rel_l2 < 0.05, "ASG error %g", e.rel_l2);
    cr_assert(g.lambda_x > g.lambda_y);
}

/* ---------------- lobe extraction (D16) ---------------- */

Test(brdf, d16_single_lobe_extraction_returns_its_axis_and_warped_sharpness)
{
    sol_sg ndf = sg(0.1, 0.0, 200.0, 1.0), light = sg(0.3, 0.0, 50.0, 1.0);
    double v[3] = {sin(0.2), 0, cos(0.2)};
    sol_phong_lobe lobe;
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 1, &light, 1, v, &lobe), SOL_OK);
    for (int i = 0; i < 3; ++i)
        cr_assert_float_eq(lobe.normal[i], ndf.axis[i], 1e-12);
    sol_sg w = sol_sg_warp_ndf_lobe(&ndf, v);
    cr_assert_float_eq(lobe.glossiness, w.sharpness, 1e-9);
    cr_assert_float_eq(w.sharpness, 200.0 / (4.0 * sol_dot3(ndf.axis, v)), 1e-9);
    /* Energy-preserving glossiness of one lobe: lambda / (1 - exp(-2 lambda)) - 1. */
    cr_assert_float_eq(lobe.glossiness_energy, w.sharpness / -expm1(-2.0 * w.sharpness) - 1.0, 1e-9);
    /* A wide lobe (lambda 0.05): the normalised peak is below a uniform hemisphere's, g clamps at 0. */
    sol_sg wide = sg(0.0, 0.0, 0.05, 1.0);
    cr_assert_eq(sol_extract_phong_lobe(&wide, 1, &light, 1, Z, &lobe), SOL_OK);
    cr_assert(lobe.glossiness_energy >= 0.0 && lobe.glossiness_energy < 0.1, "%g", lobe.glossiness_energy);
}

Test(brdf, d16_symmetric_lobes_and_lights_give_the_symmetric_normal)
{
    sol_sg ndf[2] = {sg(0.2, 0.0, 100, 1), sg(0.2, M_PI, 100, 1)};
    sol_sg light[2] = {sg(0.5, 0.0, 20, 1), sg(0.5, M_PI, 20, 1)};
    sol_phong_lobe lobe;
    cr_assert_eq(sol_extract_phong_lobe(ndf, 2, light, 2, Z, &lobe), SOL_OK);
    cr_assert_float_eq(lobe.normal[2], 1.0, 1e-12);
    /* The spread of the two lobes lowers the glossiness below each lobe's own warped sharpness. */
    cr_assert(lobe.glossiness < sol_sg_warp_ndf_lobe(&ndf[0], Z).sharpness);
    /* A light on one side pulls the normal towards it. */
    cr_assert_eq(sol_extract_phong_lobe(ndf, 2, light, 1, Z, &lobe), SOL_OK);
    cr_assert(lobe.normal[0] > 0.1);
}

/* The documented work counters: n warps and n * m inner products, whatever the lighting (D16's
 * O(n*m) verdict follows these counts, not timings). */
Test(brdf, d16_extraction_counts_n_warps_and_n_times_m_products)
{
    sol_sg ndf[12], light[32];
    for (int i = 0; i < 12; ++i)
        ndf[i] = sg(0.05 * i, 0.5 * i, 50.0 + 10.0 * i, 1.0);
    for (int j = 0; j < 32; ++j)
        light[j] = sg(0.1 * j, 0.7 * j, 5.0 + j, j % 3 ? 1.0 : 0.0); /* some lobes dark, some below */
    static const int ns[] = {1, 3, 7, 12}, ms[] = {1, 2, 7, 32};
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            sol_phong_lobe lobe;
            cr_assert_eq(sol_extract_phong_lobe(ndf, ns[a], light, ms[b], Z, &lobe), SOL_OK);
            cr_assert_eq(lobe.warps, ns[a]);
            cr_assert_eq(lobe.products, ns[a] * ms[b]);
        }
    /* Light entirely below the lobes: the fallback still evaluated every product. */
    sol_sg below = sg(M_PI, 0, 1e6, 1);
    sol_phong_lobe lobe;
    cr_assert_eq(sol_extract_phong_lobe(ndf, 3, &below, 1, Z, &lobe), SOL_OK);
    cr_assert_eq(lobe.warps, 3);
    cr_assert_eq(lobe.products, 3);
}

Test(brdf, d16_extraction_hard_cases)
{
    sol_sg ndf = sg(0, 0, 100, 1), light = sg(0, 0, 10, 1), nan_light = sg(0, 0, NAN, 1);
    double away[3] = {0, 0, -1}, nan_v[3] = {NAN, 0, 1};
    sol_phong_lobe lobe = {{7, 7, 7}, 7, 7, 7, 7, 7};
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 1, &light, 1, away, &lobe), SOL_ERR_ZERO_LENGTH);
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 1, &nan_light, 1, Z, &lobe), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 1, &light, 1, nan_v, &lobe), SOL_ERR_NONFINITE);
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 0, &light, 1, Z, &lobe), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_extract_phong_lobe(NULL, 1, &light, 1, Z, &lobe), SOL_ERR_NULL_ARG);
    cr_assert(lobe.glossiness == 7 && lobe.glossiness_energy == 7 && lobe.warps == 7 && lobe.products == 7);
    /* A light entirely below the horizon of the lobe: falls back to the NDF's own weights. */
    sol_sg below = sg(M_PI, 0, 1e6, 1);
    cr_assert_eq(sol_extract_phong_lobe(&ndf, 1, &below, 1, Z, &lobe), SOL_OK);
    cr_assert_float_eq(lobe.normal[2], 1.0, 1e-12);
    /* Sharpness 0 BRDF lobe: glossiness stays finite. */
    sol_sg flat = sg(0, 0, 0, 1);
    cr_assert_eq(sol_extract_phong_lobe(&flat, 1, &light, 1, Z, &lobe), SOL_OK);
    cr_assert(isfinite(lobe.glossiness));
    cr_assert(isfinite(lobe.glossiness_energy) && lobe.glossiness_energy >= 0.0);
}

Test(brdf, d16_hemisphere_cut_keeps_the_brightest_visible_lobes_in_order)
{
    sol_sg light[5] = {sg(0.1, 0, 50, 1), sg(M_PI, 0, 1e4, 100), sg(0.5, 1, 50, 3), sg(1.0, 2, 50, 0.5),
                       sg(0.2, 3, 50, 2)};
    sol_sg out[5];
    int m = -1;
    cr_assert_eq(sol_cull_light_lobes(light, 5, Z, 2, out, &m), SOL_OK);
    cr_assert_eq(m, 2);
    cr_assert_eq(out[0].amplitude, 3); /* input order kept */
    cr_assert_eq(out[1].amplitude, 2);
    cr_assert_eq(sol_cull_light_lobes(light, 5, Z, 10, out, &m), SOL_OK);
    cr_assert_eq(m, 4); /* the lobe pointing straight down is culled */
    cr_assert_eq(sol_cull_light_lobes(light, 5, Z, 0, out, &m), SOL_ERR_INVALID_ARG);
    cr_assert_eq(sol_cull_light_lobes(light, 0, Z, 3, out, &m), SOL_OK);
    cr_assert_eq(m, 0);
}
