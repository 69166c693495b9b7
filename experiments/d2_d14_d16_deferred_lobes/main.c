/* d2_d14_d16_deferred_lobes - the talk's deferred BRDF claims:
 *  D2  glossiness cannot be deferred: specular from several lights accumulated without the
 *      per-pixel exponent cannot be corrected afterwards;
 *  D14 Fresnel and geometry applied after lighting vs the full microfacet BRDF;
 *  D16 principal Phong lobe extraction from an SG NDF under SG lighting: rendered error and highlight
 *      shift vs lighting lobes m (with the hemisphere cut to ~7) and BRDF lobes n, and the O(n*m)
 *      cost per pixel.
 * The D16 measurements shade single pixels (normal, view, lighting lobes) analytically, with no
 * geometry, so the scene layer (experiments/scenes/aniso_sg.json renders D15/D16 in an image) has
 * nothing to replace here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sol_brdf.h"
#include "exp_harness.h"

#define DEG (M_PI / 180.0)
enum { MAX_LIGHTS = 32, K_MAX = 12 };

/* ======================= shared pieces ======================= */

static void normalize3(double v[3])
{
    double l = sqrt(sol_dot3(v, v));
    for (int i = 0; i < 3; ++i)
        v[i] /= l;
}

static void spherical(double theta, double phi, double out[3])
{
    out[0] = sin(theta) * cos(phi), out[1] = sin(theta) * sin(phi), out[2] = cos(theta);
}

static sol_sg sg_with_integral(const double axis[3], double sharpness, double integral)
{
    sol_sg g = {{axis[0], axis[1], axis[2]}, sharpness, 1.0};
    g.amplitude = integral / sol_sg_integral(&g);
    return g;
}

typedef struct environment {
    const char *name;
    int n;
    sol_sg lobe[MAX_LIGHTS];
} environment;

/* The sky the 32-lobe environment is fitted to: ground and sky levels and a glow around the sun. */
static double sky_radiance(const double d[3], const double sun[3])
{
    double s = sol_dot3(d, sun) > 0 ? pow(sol_dot3(d, sun), 8) : 0.0;
    return 0.1 + (d[2] > 0 ? 0.4 * d[2] : 0.0) + 2.0 * s;
}

enum { FIT_POINTS = 2048 };

typedef struct env_fit_ctx {
    environment *env;
    const double *dirs;   /* FIT_POINTS directions */
    const double *target; /* sky radiance at them */
} env_fit_ctx;

/* Residuals sum_j a_j G_j(d_i) - L(d_i); linear in the amplitudes, so the Jacobian is G_j(d_i). */
static int env_residuals(void *vctx, const double *amp, double *res, double *jac)
{
    const env_fit_ctx *c = vctx;
    int n = c->env->n;
    for (int i = 0; i < FIT_POINTS; ++i) {
        res[i] = -c->target[i];
        for (int j = 0; j < n; ++j) {
            sol_sg g = c->env->lobe[j];
            g.amplitude = 1.0;
            double e = sol_sg_eval(&g, c->dirs + 3 * i);
            res[i] += amp[j] * e;
            if (jac)
                jac[(size_t)i * n + j] = e;
        }
    }
    return 0;
}

/* Three SG lighting environments: a sun plus sky and ground, six local lights, and a 32-lobe
 * environment whose amplitudes are fitted (Ceres, amplitudes >= 0) to a smooth sky with a bright
 * region around the sun, the kind of per-object SG lighting the talk fits on the CPU. */
static void make_environments(environment env[3], double *fit_rel_rms)
{
    double sun[3], up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
    spherical(35 * DEG, 20 * DEG, sun);
    env[0] = (environment){.name = "sun + sky", .n = 3};
    env[0].lobe[0] = sg_with_integral(sun, 300.0, 10.0);
    env[0].lobe[1] = sg_with_integral(up, 1.5, 3.0);
    env[0].lobe[2] = sg_with_integral(down, 1.0, 0.5);

    env[1] = (environment){.name = "6 lights", .n = 6};
    for (int i = 0; i < 6; ++i) {
        double u, v, d[3];
        sol_r2_point((uint64_t)i + 7, &u, &v);
        spherical(acos(1.0 - 0.9 * u), 2 * M_PI * v, d);
        env[1].lobe[i] = sg_with_integral(d, 100.0, 1.0 + 0.5 * i);
    }

    env[2] = (environment){.name = "32-lobe SG environment", .n = 32};
    const double golden = M_PI * (3.0 - sqrt(5.0));
    double amp[32], lower[32], dirs[3 * FIT_POINTS], target[FIT_POINTS];
    for (int i = 0; i < 32; ++i) {
        double z = 1.0 - (2.0 * i + 1.0) / 32.0, d[3];
        spherical(acos(z), golden * i, d);
        env[2].lobe[i] = (sol_sg){{d[0], d[1], d[2]}, 6.0, 1.0};
        amp[i] = sky_radiance(d, sun) * 6.0 / (2.0 * M_PI); /* start: radiance x lobe spacing */
        lower[i] = 0.0;
    }
    for (int i = 0; i < FIT_POINTS; ++i) {
        double u, v;
        sol_r2_point((uint64_t)i, &u, &v);
        sol_sphere_uniform(u, v, dirs + 3 * i);
        target[i] = sky_radiance(dirs + 3 * i, sun);
    }
    env_fit_ctx ctx = {&env[2], dirs, target};
    sol_lsq_problem prob = {32, FIT_POINTS, env_residuals, &ctx, lower, NULL, 50, SOL_LSQ_DENSE_NORMAL_CHOLESKY};
    sol_lsq_summary sum;
    exp_check(sol_lsq_solve(&prob, amp, &sum), "fitting the SG environment");
    for (int i = 0; i < 32; ++i)
        env[2].lobe[i].amplitude = amp[i];
    double norm = 0.0;
    for (int i = 0; i < FIT_POINTS; ++i)
        norm += target[i] * target[i];
    if (fit_rel_rms)
        *fit_rel_rms = sqrt(2.0 * sum.final_cost / norm);
}

/* A pixel: a shading frame (tangent, bitangent, normal as the rows of `to_local`) and a view. */
typedef struct pixel {
    double to_local[9]; /* rows t, b, n */
    double to_world[9]; /* transpose */
    double n[3], v[3];  /* world */
} pixel;

static void make_pixel(int index, pixel *p)
{
    double u1, u2, u3, u4;
    sol_r2_point((uint64_t)index + 1, &u1, &u2);
    sol_r2_point((uint64_t)index + 1001, &u3, &u4);
    double n[3], t[3], b[3];
    spherical(30 * DEG * u1, 2 * M_PI * u2, n); /* normal-mapped: tilted up to 30 deg */
    /* Tangent: a rotation about n by an angle spread over the pixels. */
    double psi = 2 * M_PI * fmod(index * 0.6180339887, 1.0);
    double helper[3] = {cos(psi), sin(psi), 0.0};
    double d = sol_dot3(helper, n);
    for (int i = 0; i < 3; ++i)
        t[i] = helper[i] - d * n[i];
    normalize3(t);
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
    for (int i = 0; i < 3; ++i) {
        p->to_local[i] = t[i], p->to_local[3 + i] = b[i], p->to_local[6 + i] = n[i];
        p->to_world[3 * i] = t[i], p->to_world[3 * i + 1] = b[i], p->to_world[3 * i + 2] = n[i];
        p->n[i] = n[i];
    }
    double v_local[3];
    spherical(70 * DEG * sqrt(u3), 2 * M_PI * u4, v_local);
    for (int i = 0; i < 3; ++i)
        p->v[i] = p->to_world[3 * i] * v_local[0] + p->to_world[3 * i + 1] * v_local[1] +
                  p->to_world[3 * i + 2] * v_local[2];
}

static void mat_vec(const double m[9], const double x[3], double y[3])
{
    for (int i = 0; i < 3; ++i)
        y[i] = m[3 * i] * x[0] + m[3 * i + 1] * x[1] + m[3 * i + 2] * x[2];
}

static double integrate(sol_sphere_fn f, void *ctx, const double pole[3], double rel_tol)
{
    sol_quad_options o = {.rel_tol = rel_tol, .abs_tol = 1e-12, .max_intervals = 1000};
    double v, e;
    sol_status st = sol_sphere_integrate(f, ctx, pole, &o, &v, &e);
    if (st != SOL_OK && st != SOL_ERR_NO_CONVERGENCE) /* budget hit: the estimate is still good */
        exp_check(st, "integrating");
    return v;
}

/* ======================= D16 ======================= */

/* Ward NDF part of the microfacet BRDF times the cosine: D(h) / (4 n.v) for n.l > 0 (F = G = 1,
 * they are applied after lighting), times one optional light lobe. */
typedef struct ward_ctx {
    const pixel *px;
    double ax, ay;
    const sol_sg *light; /* NULL: uniform radiance 1 */
} ward_ctx;

static double ward_lit(const double l[3], void *vctx)
{
    const ward_ctx *c = vctx;
    double nl = sol_dot3(c->px->n, l), nv = sol_dot3(c->px->n, c->px->v);
    if (!(nl > 0.0) || !(nv > 0.0))
        return 0.0;
    double h[3] = {l[0] + c->px->v[0], l[1] + c->px->v[1], l[2] + c->px->v[2]}, hl[3];
    normalize3(h);
    mat_vec(c->px->to_local, h, hl);
    double f = sol_ward_ndf(hl, c->ax, c->ay) / (4.0 * nv);
    return c->light ? f * sol_sg_eval(c->light, l) : f;
}

/* The deferred pass's normalised Phong lobe with the extracted normal, times one light lobe. */
typedef struct phong_ctx {
    double r[3], n[3], g;
    const sol_sg *light;
} phong_ctx;

static double phong_lit(const double l[3], void *vctx)
{
    const phong_ctx *c = vctx;
    double nl = sol_dot3(c->n, l);
    if (!(nl > 0.0))
        return 0.0;
    double f = sol_phong_normalized(sol_dot3(c->r, l), c->g) * nl;
    return c->light ? f * sol_sg_eval(c->light, l) : f;
}

static double ward_radiance(const pixel *px, double ax, double ay, const environment *env)
{
    double s = 0.0;
    for (int j = 0; j < env->n; ++j) {
        ward_ctx c = {px, ax, ay, &env->lobe[j]};
        s += integrate(ward_lit, &c, env->lobe[j].axis, 1e-5);
    }
    return s;
}

static double phong_radiance(phong_ctx *c, const environment *env)
{
    double s = 0.0;
    for (int j = 0; j < env->n; ++j) {
        c->light = &env->lobe[j];
        s += integrate(phong_lit, c, env->lobe[j].axis, 1e-5);
    }
    c->light = NULL;
    return s;
}

typedef struct extraction_result {
    double i_ext, i_ref; /* rendered with the extracted lobe, and with the full anisotropic BRDF */
    double rel_error;    /* |I_ext - I_ref| / I_ref */
    double shift_deg; /* angle between the extracted and the geometric reflection direction */
    double normal_shift_vs_full_deg; /* extracted normal with the cut vs with all lobes */
    double i_ext_energy;             /* rendered with the energy-preserving glossiness (NAN: not computed) */
} extraction_result;

/* Renders one pixel with the extracted lobe: the deferred Phong pass sees all lights, the
 * extraction only the `keep` lobes kept by the hemisphere cut. The Phong result is scaled by the
 * ratio of the two lobes' energies under uniform white light (a light-independent per-pixel factor
 * the shading pass applies with Fresnel and geometry). */
static void extract_and_render(const pixel *px, double ax, double ay, const sol_sg *ndf_local, int k,
                               const environment *env, int keep, double i_ref, double e_ref,
                               const double full_normal[3], extraction_result *out, double normal_out[3],
                               int energy_too)
{
    sol_sg brdf[K_MAX], kept[MAX_LIGHTS];
    for (int i = 0; i < k; ++i)
        brdf[i] = sol_sg_rotate(&ndf_local[i], px->to_world);
    int m;
    if (keep == 0) { /* light-independent baseline: the extraction sees a uniform white sky */
        kept[0] = (sol_sg){{0, 0, 1}, 0.0, 1.0};
        m = 1;
    } else {
        exp_check(sol_cull_light_lobes(env->lobe, env->n, px->n, keep, kept, &m), "culling lobes");
    }
    sol_phong_lobe lobe;
    exp_check(sol_extract_phong_lobe(brdf, k, kept, m, px->v, &lobe), "extracting the Phong lobe");
    phong_ctx c = {.g = lobe.glossiness};
    memcpy(c.n, lobe.normal, sizeof c.n);
    sol_reflect(px->v, lobe.normal, c.r);
    double e_phong = integrate(phong_lit, &c, c.r, 1e-6);
    double i_ext = phong_radiance(&c, env) * e_ref / e_phong;
    double r_geo[3];
    sol_reflect(px->v, px->n, r_geo);
    out->i_ext = i_ext;
    out->i_ext_energy = NAN;
    if (energy_too) { /* the same normal with the energy-preserving (peak-matching) glossiness */
        phong_ctx ce = c;
        ce.g = lobe.glossiness_energy;
        double e_phong_e = integrate(phong_lit, &ce, ce.r, 1e-6);
        out->i_ext_energy = phong_radiance(&ce, env) * e_ref / e_phong_e;
    }
    out->i_ref = i_ref;
    out->rel_error = fabs(i_ext - i_ref) / i_ref;
    out->shift_deg = sol_angle3(c.r, r_geo) / DEG;
    out->normal_shift_vs_full_deg = full_normal ? sol_angle3(lobe.normal, full_normal) / DEG : 0.0;
    if (normal_out)
        memcpy(normal_out, lobe.normal, 3 * sizeof(double));
    (void)ax, (void)ay;
}

/* Image-level relative L2 error over the pixels: sqrt(sum (I_ext - I_ref)^2 / sum I_ref^2). */
static double image_rel_l2(const extraction_result *r, int n)
{
    double num = 0, den = 0;
    for (int p = 0; p < n; ++p) {
        num += (r[p].i_ext - r[p].i_ref) * (r[p].i_ext - r[p].i_ref);
        den += r[p].i_ref * r[p].i_ref;
    }
    return sqrt(num / den);
}

/* The same with the energy-preserving glossiness. */
static double image_rel_l2_energy(const extraction_result *r, int n)
{
    double num = 0, den = 0;
    for (int p = 0; p < n; ++p) {
        num += (r[p].i_ext_energy - r[p].i_ref) * (r[p].i_ext_energy - r[p].i_ref);
        den += r[p].i_ref * r[p].i_ref;
    }
    return sqrt(num / den);
}

static const int K_LIST[] = {1, 2, 3, 5, 7, 12};
static const int CUT_LIST[] = {1, 2, 3, 5, 7, 32};
enum { N_K = 6, N_CUT = 6 };

typedef struct timing_ctx {
    sol_sg brdf[K_MAX], light[MAX_LIGHTS];
    int n, m, pixels;
    double v[3];
    double sink;
    long warps, products, calls; /* the library's counted work and the extractions done */
} timing_ctx;

static void run_extraction(void *vctx)
{
    timing_ctx *t = vctx;
    for (int p = 0; p < t->pixels; ++p) {
        sol_phong_lobe lobe;
        t->v[0] = 0.3 + 1e-6 * p; /* a different pixel each time, same cost */
        if (sol_extract_phong_lobe(t->brdf, t->n, t->light, t->m, t->v, &lobe) == SOL_OK) {
            t->sink += lobe.glossiness;
            t->warps += lobe.warps;
            t->products += lobe.products;
        }
        ++t->calls;
    }
}

/* Solves the 3x3 system a x = b by Cramer's rule (a row-major). */
static void solve3(const double a[9], const double b[3], double x[3])
{
    double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                 a[2] * (a[3] * a[7] - a[4] * a[6]);
    for (int c = 0; c < 3; ++c) {
        double m[9];
        memcpy(m, a, sizeof m);
        for (int r = 0; r < 3; ++r)
            m[3 * r + c] = b[r];
        x[c] = (m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                m[2] * (m[3] * m[7] - m[4] * m[6])) /
               det;
    }
}

/* Least-squares fit of y = c0 + c1 n + c2 n m over cnt points (xs rows: 1, n, n m); returns R^2. */
static double fit_cost_model(const double xs[][3], const double *ys, int cnt, double coef[3])
{
    double ata[9] = {0}, atb[3] = {0}, mean = 0, ss_tot = 0, ss_res = 0;
    for (int i = 0; i < cnt; ++i) {
        for (int r = 0; r < 3; ++r) {
            atb[r] += xs[i][r] * ys[i];
            for (int q = 0; q < 3; ++q)
                ata[3 * r + q] += xs[i][r] * xs[i][q];
        }
        mean += ys[i] / cnt;
    }
    solve3(ata, atb, coef);
    for (int i = 0; i < cnt; ++i) {
        double fit = coef[0] + coef[1] * xs[i][1] + coef[2] * xs[i][2];
        ss_res += (ys[i] - fit) * (ys[i] - fit);
        ss_tot += (ys[i] - mean) * (ys[i] - mean);
    }
    return 1.0 - ss_res / ss_tot;
}

/* D16's cost against n and m, fitted to c0 + c1 n + c2 n m (per pixel, per BRDF lobe (warp), per lobe
 * pair (convolution)) twice: on the work the library counts (warps + lobe products per pixel: the
 * deterministic measure the verdict follows) and on the median time per pixel (information only: on
 * a loaded machine its R^2 moves from run to run). */
typedef struct d16_cost {
    double work_r2, work_per_pair; /* fit of counted work per pixel: R^2 and c2 (products per lobe pair) */
    int work_exact;                /* every (n, m) counted exactly n warps + n*m products per pixel */
    double time_r2, time_per_pair_ns; /* the same fit on timings (information only) */
} d16_cost;

static void d16_timing(const exp_run *exp, const sol_sg *ndf, const environment *env, d16_cost *cost)
{
    static const int ns[] = {1, 3, 7, 12}, ms[] = {1, 2, 4, 8, 16, 32};
    exp_table *t = exp_table_new("Principal Phong lobe extraction: counted work and time per pixel vs BRDF lobes n and "
                                 "lighting lobes m (the verdict uses the counts; times are information)",
                                 "n,m,n*m,warps per pixel,lobe products per pixel,ns per pixel");
    double xs[24][3], ys[24], work[24];
    int cnt = 0;
    cost->work_exact = 1;
    static timing_ctx c;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 6; ++b) {
            memset(&c, 0, sizeof c);
            c.n = ns[a], c.m = ms[b], c.pixels = exp->quick ? 200 : 2000;
            const sol_sg *ndf_k = ndf + ns[a] * (ns[a] - 1) / 2;
            for (int i = 0; i < c.n; ++i)
                c.brdf[i] = ndf_k[i];
            for (int j = 0; j < c.m; ++j)
                c.light[j] = env->lobe[j % env->n];
            c.v[0] = 0.3, c.v[1] = 0.1, c.v[2] = sqrt(1 - 0.1);
            double ns_pp = exp_cpu_time_per_item_ns(run_extraction, &c, (size_t)c.pixels, exp->quick ? 3 : 7);
            double calls = c.calls ? (double)c.calls : 1.0;
            double work_pp = (double)(c.warps + c.products) / calls;
            cost->work_exact &= c.calls > 0 && c.warps == c.calls * c.n && c.products == c.calls * c.n * c.m;
            exp_table_row(t, "%d|%d|%d|%.2f|%.2f|%.1f", c.n, c.m, c.n * c.m, (double)c.warps / calls,
                          (double)c.products / calls, ns_pp);
            xs[cnt][0] = 1.0, xs[cnt][1] = c.n, xs[cnt][2] = (double)(c.n * c.m);
            work[cnt] = work_pp;
            ys[cnt++] = ns_pp;
        }
    exp_table_write(t, exp, "d16_timing");
    double wcoef[3], coef[3];
    cost->work_r2 = fit_cost_model((const double(*)[3])xs, work, cnt, wcoef);
    cost->work_per_pair = wcoef[2];
    cost->time_r2 = fit_cost_model((const double(*)[3])xs, ys, cnt, coef);
    cost->time_per_pair_ns = coef[2];
    /* The fitted time goes in the data file (a timing column), not into the plot script, so the
     * script is the same on every run. */
    FILE *f = exp_open(exp, "timing.dat");
    fprintf(f, "# n, m, n*m, ns per pixel, fitted ns per pixel\n");
    for (int i = 0; i < cnt; ++i)
        fprintf(f, "%d %d %d %.6g %.6g\n", (int)xs[i][1], (int)(xs[i][2] / xs[i][1]), (int)xs[i][2], ys[i],
                coef[0] + coef[1] * xs[i][1] + coef[2] * xs[i][2]);
    fclose(f);
    exp_plot(exp, "d16_timing",
             "set xlabel 'n*m (BRDF lobes x lighting lobes)'; set ylabel 'ns per pixel'; set grid; set key top left;"
             "plot for [n in '1 3 7 12'] 'timing.dat' u ($1==n+0?$3:1/0):4 w lp t 'n = '.n,"
             " for [n in '1 3 7 12'] 'timing.dat' u ($1==n+0?$3:1/0):5 w l dt 2 lc rgb 'gray' notitle");
}

/* Per-pixel D16 results, indexed [env][k or cut][pixel]. */
typedef struct d16_results {
    int n_pix;
    pixel *px;
    double *i_ref, *e_ref;          /* reference radiance per [env][pixel]; reference lit energy per pixel */
    extraction_result *res_k;       /* 3 environments x N_K lobe counts, all lighting lobes */
    extraction_result *res_cut;     /* N_CUT hemisphere cuts of the SG environment, n = 7 */
    extraction_result *res_base;    /* 3 environments, 7 lobes reduced without the lighting */
} d16_results;

static void d16_results_alloc(int n_pix, d16_results *d)
{
    d->n_pix = n_pix;
    d->px = malloc((size_t)n_pix * sizeof *d->px);
    d->i_ref = malloc(3 * (size_t)n_pix * sizeof *d->i_ref);
    d->e_ref = malloc((size_t)n_pix * sizeof *d->e_ref);
    d->res_k = malloc(3 * N_K * (size_t)n_pix * sizeof *d->res_k);
    d->res_cut = malloc(N_CUT * (size_t)n_pix * sizeof *d->res_cut);
    d->res_base = malloc(3 * (size_t)n_pix * sizeof *d->res_base);
    if (!d->px || !d->i_ref || !d->e_ref || !d->res_k || !d->res_cut || !d->res_base)
        exp_die("out of memory");
}

static void d16_results_free(d16_results *d)
{
    free(d->px);
    free(d->i_ref);
    free(d->e_ref);
    free(d->res_k);
    free(d->res_cut);
    free(d->res_base);
}

/* Pixel p: references, every lobe count in each environment, the light-independent lobe, and the
 * hemisphere cuts of the SG environment (the last cut keeps all lobes and gives the reference normal). */
static void d16_pixel(int p, double ax, double ay, const sol_sg *ndf, const environment *env, d16_results *d)
{
    int n_pix = d->n_pix;
    pixel *x = &d->px[p];
    make_pixel(p, x);
    double r_geo[3];
    sol_reflect(x->v, x->n, r_geo);
    ward_ctx w = {x, ax, ay, NULL};
    d->e_ref[p] = integrate(ward_lit, &w, r_geo, 1e-6);
    const sol_sg *ndf7 = ndf + 7 * 6 / 2;
    for (int e = 0; e < 3; ++e) {
        double i_ref = d->i_ref[e * n_pix + p] = ward_radiance(x, ax, ay, &env[e]);
        for (int k = 0; k < N_K; ++k)
            extract_and_render(x, ax, ay, ndf + K_LIST[k] * (K_LIST[k] - 1) / 2, K_LIST[k], &env[e], MAX_LIGHTS,
                               i_ref, d->e_ref[p], NULL, &d->res_k[(e * N_K + k) * n_pix + p], NULL, K_LIST[k] == 7);
        extract_and_render(x, ax, ay, ndf7, 7, &env[e], 0, i_ref, d->e_ref[p], NULL, &d->res_base[e * n_pix + p],
                           NULL, 1);
    }
    double full_normal[3];
    extract_and_render(x, ax, ay, ndf7, 7, &env[2], MAX_LIGHTS, d->i_ref[2 * n_pix + p], d->e_ref[p], NULL,
                       &d->res_cut[(N_CUT - 1) * n_pix + p], full_normal, 0);
    for (int c = 0; c < N_CUT; ++c)
        extract_and_render(x, ax, ay, ndf7, 7, &env[2], CUT_LIST[c], d->i_ref[2 * n_pix + p], d->e_ref[p], full_normal,
                           &d->res_cut[c * n_pix + p], NULL, 0);
}

static void d16_render(double ax, double ay, const sol_sg *ndf, const environment *env, d16_results *d)
{
    int done = 0;
#pragma omp parallel for schedule(dynamic, 1)
    for (int p = 0; p < d->n_pix; ++p) {
        d16_pixel(p, ax, ay, ndf, env, d);
#pragma omp critical(progress)
        exp_progress("D16 pixels", (size_t)++done, (size_t)d->n_pix);
    }
    exp_progress_done("D16 pixels");
}

/* Error vs BRDF lobes n per environment (table and plot); image errors go to l2_k. */
static void d16_error_vs_n(const exp_run *exp, const d16_results *d, const environment *env,
                           const sol_sg_fit_error *fit_err, double l2_k[3][N_K])
{
    int n_pix = d->n_pix;
    exp_table *t = exp_table_new("Extracted Phong lobe vs full anisotropic Ward (ax 0.1, ay 0.3) over pixels, by BRDF "
                                 "lobes n (all lighting lobes): image relative L2 error, worst pixel's relative error, "
                                 "highlight shift; 'fixed' = the same 7-lobe NDF reduced to one lobe without the lighting",
                                 "environment,n,NDF fit rel L2,image rel L2,max pixel rel error,mean shift deg,"
                                 "max shift deg");
    FILE *f = exp_open(exp, "error_vs_n.dat");
    fprintf(f, "# n then image relative L2 error for the three environments\n");
    for (int e = 0; e < 3; ++e) {
        for (int k = 0; k < N_K + 1; ++k) {
            const extraction_result *r = k < N_K ? &d->res_k[(e * N_K + k) * n_pix] : &d->res_base[e * n_pix];
            double mx = 0, sh = 0, shmax = 0;
            for (int p = 0; p < n_pix; ++p) {
                mx = fmax(mx, r[p].rel_error);
                sh += r[p].shift_deg;
                shmax = fmax(shmax, r[p].shift_deg);
            }
            double l2 = image_rel_l2(r, n_pix);
            if (k < N_K) {
                l2_k[e][k] = l2;
                exp_table_row(t, "%s|%d|%.4f|%.4f|%.4f|%.2f|%.2f", env[e].name, K_LIST[k],
                              fit_err[K_LIST[k] - 1].rel_l2, l2, mx, sh / n_pix, shmax);
            } else {
                exp_table_row(t, "%s|7 fixed|%.4f|%.4f|%.4f|%.2f|%.2f", env[e].name, fit_err[6].rel_l2, l2, mx,
                              sh / n_pix, shmax);
            }
        }
    }
    for (int k = 0; k < N_K; ++k)
        fprintf(f, "%d %.6g %.6g %.6g\n", K_LIST[k], l2_k[0][k], l2_k[1][k], l2_k[2][k]);
    fclose(f);
    exp_table_write(t, exp, "d16_error_vs_n");
    exp_plot(exp, "d16_error_vs_n",
             "set xlabel 'BRDF SG lobes n'; set ylabel 'image relative L2 error'; set grid; set key top right;"
             "plot 'error_vs_n.dat' u 1:2 w lp t 'sun + sky', '' u 1:3 w lp t '6 lights', '' u 1:4 w lp t '32-lobe SG env'");
}

static void d16_environments_table(const exp_run *exp, const environment *env, double env_fit)
{
    exp_table *en = exp_table_new("Lighting environments of D14/D16", "environment,SG lobes,fit rel RMS error");
    exp_table_row(en, "%s|%d|-", env[0].name, env[0].n);
    exp_table_row(en, "%s|%d|-", env[1].name, env[1].n);
    exp_table_row(en, "%s|%d|%.4f", env[2].name, env[2].n, env_fit);
    exp_table_write(en, exp, "d16_environments");
}

/* Hemisphere cut of the SG environment to m lobes (table); image errors go to rms_cut. */
static void d16_cut_table(const exp_run *exp, const d16_results *d, double rms_cut[N_CUT])
{
    int n_pix = d->n_pix;
    exp_table *c = exp_table_new("Hemisphere cut of the 32-lobe SG environment to m lobes for the extraction (n = 7; the "
                                 "deferred pass still sees every lobe)",
                                 "m kept,image rel L2,max pixel rel error,mean shift deg,mean normal change vs all lobes deg");
    for (int k = 0; k < N_CUT; ++k) {
        const extraction_result *r = &d->res_cut[k * n_pix];
        double mx = 0, sh = 0, ns = 0;
        for (int p = 0; p < n_pix; ++p) {
            mx = fmax(mx, r[p].rel_error);
            sh += r[p].shift_deg;
            ns += r[p].normal_shift_vs_full_deg;
        }
        rms_cut[k] = image_rel_l2(r, n_pix);
        exp_table_row(c, "%d|%.4f|%.4f|%.2f|%.3f", CUT_LIST[k], rms_cut[k], mx, sh / n_pix, ns / n_pix);
    }
    exp_table_write(c, exp, "d16_cut");
}

/* D16, split in two rows: (1) O(n*m) cost (fit of the counted work; timings beside it) and the cut to ~7 lobes; (2) "the highlight
 * is slightly shifted, a rather small issue": the light-weighted lobe's highlight shift and its
 * rendered error against the lobe extracted without lighting, with the variance-matched and the
 * energy-preserving glossiness. */
static void d16_claim(const exp_run *exp, const d16_results *d, double l2_k[3][N_K], const double rms_cut[N_CUT],
                      const d16_cost *cost)
{
    int n_pix = d->n_pix;
    (void)l2_k;
    char fig[400];
    snprintf(fig, sizeof fig,
             "counted work (warps + lobe products per pixel) fits c0 + c1 n + c2 n*m (R^2 %.3f, %.2f products per lobe "
             "pair%s); cut to 7 lobes: image error %.3f vs %.3f with all 32",
             cost->work_r2, cost->work_per_pair, cost->work_exact ? ", exactly n*m at every (n, m)" : "", rms_cut[4],
             rms_cut[N_CUT - 1]);
    exp_verdict v = cost->work_r2 >= 0.95 && rms_cut[4] <= 1.25 * rms_cut[N_CUT - 1] + 0.01 ? EXP_REPRODUCED
                                                                                          : EXP_NOT_REPRODUCED;
    exp_claim(exp, "D16", "O(n*m) per pixel; lighting cut to ~7 lobes by hemisphere", fig,
              "R^2 of the counted-work fit >= 0.95; cut-to-7 image error within 1.25x (+0.01) of all lobes", v,
              "work counted by sol_extract_phong_lobe, with the time per pixel beside it (d16_timing); timing, "
              "information only, varies per run: the same fit on time gives R^2 %.2f, %.0f ns per lobe pair; "
              "hemisphere cut table (d16_cut)",
              cost->time_r2, cost->time_per_pair_ns);
    exp_number(exp, "D16-work-r2", "%.3f", cost->work_r2);
    exp_number(exp, "D16-r2-timing", "%.3f", cost->time_r2); /* from timings: information only */
    exp_number(exp, "D16-pair-ns", "%.1f", cost->time_per_pair_ns);
    exp_number(exp, "D16-cut7-err", "%.3f", rms_cut[4]);
    exp_number(exp, "D16-cutall-err", "%.3f", rms_cut[N_CUT - 1]);

    /* Row 2, per environment at n = 7: mean shift, image error light-weighted vs light-independent,
     * each with both glossiness fits. */
    exp_table *t = exp_table_new("D16 at n = 7: light-weighted vs light-independent lobe, variance-matched vs "
                                 "energy-preserving (peak-matching) glossiness: image relative L2 error and mean "
                                 "highlight shift",
                                 "environment,mean shift deg (weighted),mean shift deg (independent),"
                                 "weighted: err variance gloss,weighted: err energy gloss,independent: err variance gloss,"
                                 "independent: err energy gloss");
    static const char *env_names[3] = {"sun + sky", "6 lights", "32-lobe SG env"};
    double worst_ratio = 0.0, max_shift = 0.0;
    for (int e = 0; e < 3; ++e) {
        const extraction_result *w = &d->res_k[(e * N_K + 4) * n_pix], *b = &d->res_base[e * n_pix];
        double sw = 0, sb = 0;
        for (int p = 0; p < n_pix; ++p) {
            sw += w[p].shift_deg;
            sb += b[p].shift_deg;
        }
        sw /= n_pix, sb /= n_pix;
        double wv = image_rel_l2(w, n_pix), we = image_rel_l2_energy(w, n_pix);
        double bv = image_rel_l2(b, n_pix), be = image_rel_l2_energy(b, n_pix);
        exp_table_row(t, "%s|%.2f|%.2f|%.4f|%.4f|%.4f|%.4f", env_names[e], sw, sb, wv, we, bv, be);
        worst_ratio = fmax(worst_ratio, fmin(wv, we) / fmin(bv, be));
        max_shift = fmax(max_shift, sw);
        if (e == 2) {
            exp_number(exp, "D16-shift-env32-deg", "%.1f", sw);
            exp_number(exp, "D16-weighted-var-err", "%.3f", wv);
            exp_number(exp, "D16-weighted-energy-err", "%.3f", we);
            exp_number(exp, "D16-indep-var-err", "%.3f", bv);
            exp_number(exp, "D16-indep-energy-err", "%.3f", be);
        }
    }
    exp_table_write(t, exp, "d16_gloss_fits");
    exp_number(exp, "D16-max-mean-shift-deg", "%.1f", max_shift);
    exp_number(exp, "D16-worst-weighted-over-indep", "%.2f", worst_ratio);
    snprintf(fig, sizeof fig,
             "mean highlight shift up to %.1f deg over the 3 scenes; best light-weighted lobe renders %.2fx the error of "
             "the best light-independent one (worst scene; both glossiness fits tried)",
             max_shift, worst_ratio);
    int small = max_shift <= 2.0 && worst_ratio <= 1.0;
    exp_claim(exp, "D16", "highlight slightly shifted, a rather small issue", fig,
              "mean shift <= 2 deg and the light-weighted lobe renders no worse than the light-independent one",
              small ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "the light-weighted normal leans towards the lights; with the energy-preserving (peak-matching) glossiness "
              "as well as the variance match (d16_gloss_fits table) the light-weighted lobe %s the lobe extracted without "
              "lighting%s",
              worst_ratio <= 1.0 ? "renders no worse than" : "still renders worse than",
              worst_ratio > 1.0 ? ": the weighting, not the glossiness fit, costs the accuracy"
              : max_shift > 2.0 ? ", but the highlight moves by more than 2 deg" : "");
}

/* Core-ns per pixel of what the engine runs per pixel for one setting, on the D16 pixels, in two
 * parts: cut_ns, the hemisphere cut to `keep` lighting lobes (sol_cull_light_lobes; keep 0: none, the
 * light-independent lobe under a uniform white sky), and ext_ns, the k NDF lobes rotated to world
 * space and the extraction. */
static void d16_ns_per_pixel(const d16_results *d, const sol_sg *ndf_local, int k, const environment *env, int keep,
                             int reps, double *cut_ns, double *ext_ns)
{
    sol_sg *kept = malloc((size_t)d->n_pix * MAX_LIGHTS * sizeof *kept);
    int *m = malloc((size_t)d->n_pix * sizeof *m);
    if (!kept || !m)
        exp_die("out of memory");
    double start = exp_thread_cpu_ns();
    for (int r = 0; r < reps; ++r) /* the cut alone, its kept lobes stored for the extraction */
        for (int p = 0; p < d->n_pix; ++p) {
            if (keep == 0) {
                kept[(size_t)p * MAX_LIGHTS] = (sol_sg){{0, 0, 1}, 0.0, 1.0};
                m[p] = 1;
            } else {
                exp_check(sol_cull_light_lobes(env->lobe, env->n, d->px[p].n, keep, kept + (size_t)p * MAX_LIGHTS, &m[p]),
                          "culling lobes");
            }
        }
    double mid = exp_thread_cpu_ns(), sink = 0.0;
    for (int r = 0; r < reps; ++r)
        for (int p = 0; p < d->n_pix; ++p) {
            sol_sg brdf[K_MAX];
            for (int i = 0; i < k; ++i)
                brdf[i] = sol_sg_rotate(&ndf_local[i], d->px[p].to_world);
            sol_phong_lobe lobe;
            exp_check(sol_extract_phong_lobe(brdf, k, kept + (size_t)p * MAX_LIGHTS, m[p], d->px[p].v, &lobe),
                      "extracting the Phong lobe");
            sink += lobe.glossiness;
        }
    double end = exp_thread_cpu_ns();
    static volatile double keep_alive; /* the loop's result is used: not optimised away */
    keep_alive = sink;
    (void)keep_alive;
    *cut_ns = keep == 0 ? 0.0 : (mid - start) / ((double)reps * d->n_pix);
    *ext_ns = (end - mid) / ((double)reps * d->n_pix);
    free(kept);
    free(m);
}

/* Image relative L2, worst pixel's relative error and mean highlight shift of one setting's results;
 * energy: with the energy-preserving glossiness instead of the variance match. */
static void d16_errors(const extraction_result *r, int n_pix, int energy, double *l2, double *mx, double *shift)
{
    *l2 = energy ? image_rel_l2_energy(r, n_pix) : image_rel_l2(r, n_pix);
    *mx = 0.0, *shift = 0.0;
    for (int p = 0; p < n_pix; ++p) {
        double i_ext = energy ? r[p].i_ext_energy : r[p].i_ext;
        *mx = fmax(*mx, fabs(i_ext - r[p].i_ref) / r[p].i_ref);
        *shift += r[p].shift_deg / n_pix;
    }
}

/* --bench: D16's accuracy knobs, rendered error against the per-pixel cost of the extraction: BRDF
 * lobes n, lighting lobes m kept by the hemisphere cut, the glossiness fit, with the peer (the same
 * 7-lobe NDF reduced without the lighting) in the same table. Written only with --bench (d16_knobs). */
static void d16_knobs_table(const exp_run *exp, const d16_results *d, const sol_sg *ndf, const environment *env)
{
    const int n_pix = d->n_pix, reps = exp->quick ? 20 : 50;
    const sol_sg *ndf7 = ndf + 7 * 6 / 2;
    exp_table *t = exp_table_new("D16 knobs: extracted Phong lobe vs full anisotropic Ward (ax 0.1, ay 0.3), image "
                                 "relative L2 error, worst pixel, mean highlight shift, and the extraction's time per "
                                 "pixel, one thread: the hemisphere cut of the lighting lobes (sol_cull_light_lobes) and "
                                 "the NDF rotation + extraction; peer: the same 7-lobe NDF reduced without the lighting "
                                 "(no cut; it could be precomputed per material)",
                                 "knob,setting,environment,image rel L2,max pixel rel error,mean shift deg,"
                                 "cut core-ns per pixel,extraction core-ns per pixel");
    double l2, mx, sh, cut, ext, cut_b, ext_b;
    for (int e = 0; e < 3; ++e)
        for (int k = 0; k < N_K; ++k) {
            d16_errors(&d->res_k[(e * N_K + k) * n_pix], n_pix, 0, &l2, &mx, &sh);
            d16_ns_per_pixel(d, ndf + K_LIST[k] * (K_LIST[k] - 1) / 2, K_LIST[k], &env[e], MAX_LIGHTS, reps, &cut, &ext);
            exp_table_row(t, "BRDF lobes n (all lighting lobes)|%d|%s|%.4f|%.4f|%.2f|%.0f|%.0f", K_LIST[k], env[e].name,
                          l2, mx, sh, cut, ext);
        }
    for (int c = 0; c < N_CUT; ++c) {
        d16_errors(&d->res_cut[c * n_pix], n_pix, 0, &l2, &mx, &sh);
        d16_ns_per_pixel(d, ndf7, 7, &env[2], CUT_LIST[c], reps, &cut, &ext);
        exp_table_row(t, "lighting lobes m kept (n = 7)|%d|%s|%.4f|%.4f|%.2f|%.0f|%.0f", CUT_LIST[c], env[2].name, l2,
                      mx, sh, cut, ext);
    }
    static const char *fits[2] = {"variance match", "energy (peak) match"};
    for (int e = 0; e < 3; ++e) {
        d16_ns_per_pixel(d, ndf7, 7, &env[e], MAX_LIGHTS, reps, &cut, &ext);
        d16_ns_per_pixel(d, ndf7, 7, &env[e], 0, reps, &cut_b, &ext_b);
        for (int g = 0; g < 2; ++g) { /* both glossiness values come out of the same extraction call */
            d16_errors(&d->res_k[(e * N_K + 4) * n_pix], n_pix, g, &l2, &mx, &sh);
            exp_table_row(t, "glossiness fit (n = 7, light-weighted)|%s|%s|%.4f|%.4f|%.2f|%.0f|%.0f", fits[g],
                          env[e].name, l2, mx, sh, cut, ext);
            d16_errors(&d->res_base[e * n_pix], n_pix, g, &l2, &mx, &sh);
            exp_table_row(t, "peer: light-independent lobe (n = 7)|%s|%s|%.4f|%.4f|%.2f|%.0f|%.0f", fits[g],
                          env[e].name, l2, mx, sh, cut_b, ext_b);
        }
    }
    exp_table_write(t, exp, "d16_knobs");
}

static void d16(const exp_run *exp)
{
    const double ax = 0.1, ay = 0.3;
    sol_sg ndf[K_MAX * (K_MAX + 1) / 2];
    sol_sg_fit_error fit_err[K_MAX];
    exp_check(sol_ward_sg_fit(ax, ay, K_MAX, NULL, ndf, fit_err, NULL), "fitting the Ward NDF");
    environment env[3];
    double env_fit;
    make_environments(env, &env_fit);

    d16_cost cost;
    d16_timing(exp, ndf, &env[2], &cost);

    d16_results d;
    d16_results_alloc(exp->quick ? 8 : 48, &d);
    d16_render(ax, ay, ndf, env, &d);
    if (exp->bench) { /* the knobs' error-vs-time table only */
        d16_knobs_table(exp, &d, ndf, env);
        d16_results_free(&d);
        return;
    }
    double l2_k[3][N_K], rms_cut[N_CUT];
    d16_error_vs_n(exp, &d, env, fit_err, l2_k);
    d16_environments_table(exp, env, env_fit);
    d16_cut_table(exp, &d, rms_cut);
    d16_claim(exp, &d, l2_k, rms_cut, &cost);
    d16_results_free(&d);
}

/* ======================= D14 ======================= */

typedef struct ct_ctx {
    double v[3], alpha, f0;
    int full; /* 1: D G F / (4 n.v); 0: D / (4 n.v) */
    const sol_sg *light;
} ct_ctx;

static double ct_lit(const double l[3], void *vctx)
{
    const ct_ctx *c = vctx;
    if (!(l[2] > 0.0))
        return 0.0;
    double f;
    if (c->full) {
        f = sol_cook_torrance(c->v, l, SOL_NDF_GGX, c->alpha, c->f0) * l[2];
    } else {
        double h[3] = {l[0] + c->v[0], l[1] + c->v[1], l[2] + c->v[2]};
        normalize3(h);
        f = sol_ggx_ndf(h[2], c->alpha) / (4.0 * c->v[2]);
    }
    return c->light ? f * sol_sg_eval(c->light, l) : f;
}

static void d14(const exp_run *exp)
{
    static const double alphas[] = {0.05, 0.1, 0.2, 0.3, 0.5, 0.8};
    static const double views[] = {0, 30, 60, 75, 85};
    const double f0 = 0.04;
    environment env[3];
    make_environments(env, NULL);
    exp_table *t = exp_table_new("Deferring Fresnel and geometry (GGX, Smith, Schlick f0 = 0.04): relative error of "
                                 "[lighting with D only] x F(n.v) G1(n.v) G1(n.r) vs the full BRDF, uniform sky / sun + sky",
                                 "alpha,view 0,view 30,view 60,view 75,view 85,sun+sky 0,sun+sky 30,sun+sky 60,sun+sky 75,"
                                 "sun+sky 85");
    double err[6][2][5];
    double worst_sky = 0, worst_sun = 0, worst_all = 0;
#pragma omp parallel for collapse(2) schedule(dynamic, 1)
    for (int a = 0; a < 6; ++a)
        for (int w = 0; w < 5; ++w) {
            ct_ctx c = {.alpha = alphas[a], .f0 = f0};
            spherical(views[w] * DEG, M_PI, c.v);
            double r[3], n[3] = {0, 0, 1};
            sol_reflect(c.v, n, r);
            double deferred_factor = sol_fresnel_schlick(f0, c.v[2]) * sol_smith_g1_ggx(c.v[2], c.alpha) *
                                     sol_smith_g1_ggx(r[2], c.alpha);
            for (int e = 0; e < 2; ++e) {
                double full = 0, d_only = 0;
                int nl = e == 0 ? 1 : env[0].n;
                for (int j = 0; j < nl; ++j) {
                    c.light = e == 0 ? NULL : &env[0].lobe[j];
                    const double *pole = e == 0 ? r : env[0].lobe[j].axis;
                    c.full = 1;
                    full += integrate(ct_lit, &c, pole, 1e-6);
                    c.full = 0;
                    d_only += integrate(ct_lit, &c, pole, 1e-6);
                }
                err[a][e][w] = fabs(d_only * deferred_factor - full) / full;
            }
        }
    for (int a = 0; a < 6; ++a) {
        exp_table_row(t, "%.2f|%.3f|%.3f|%.3f|%.3f|%.3f|%.3f|%.3f|%.3f|%.3f|%.3f", alphas[a], err[a][0][0], err[a][0][1],
                      err[a][0][2], err[a][0][3], err[a][0][4], err[a][1][0], err[a][1][1], err[a][1][2], err[a][1][3],
                      err[a][1][4]);
        for (int w = 0; w < 5; ++w)
            for (int e = 0; e < 2; ++e) {
                worst_all = fmax(worst_all, err[a][e][w]);
                if (views[w] <= 60 && alphas[a] <= 0.3) {
                    double *worst = e == 0 ? &worst_sky : &worst_sun;
                    *worst = fmax(*worst, err[a][e][w]);
                }
            }
    }
    exp_table_write(t, exp, "d14_deferred_fresnel_geometry");
    char fig[200];
    snprintf(fig, sizeof fig,
             "view <= 60 deg, alpha <= 0.3: max rel. error %.1f%% under a uniform sky, %.0f%% under sun + sky; up to %.0f%% "
             "at grazing",
             100 * worst_sky, 100 * worst_sun, 100 * worst_all);
    exp_claim(exp, "D14", "qualitative: F and G deferrable", fig, "<= 10% for view <= 60 deg, alpha <= 0.3",
              fmax(worst_sky, worst_sun) <= 0.10 ? EXP_REPRODUCED : EXP_DIFFERS_EXPLAINED,
              "deferral is exact in the narrow-lobe limit and within a few percent for smooth lobes near the mirror "
              "direction; it fails for rough lobes, grazing views and bright lights in the lobe's tail, where F and G "
              "differ from their values at the lobe centre");
}

/* ======================= D2 ======================= */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void d2(const exp_run *exp)
{
    static const int lights[] = {1, 2, 4, 8};
    static const double gloss[] = {5, 20, 120, 250};
    const double g0 = 32.0; /* the fixed exponent of method A */
    const int trials = exp->quick ? 200 : 2000;
    exp_table *t = exp_table_new(
        "Accumulating specular without the per-pixel glossiness g: median (90th percentile) relative error over random "
        "light sets within 25 deg of r. A: lights accumulated with a fixed exponent 32, normalised for g afterwards. "
        "B: sum of I (r.l) and of I accumulated, the exponent g applied to their ratio afterwards",
        "lights,g,A median,A p90,B median,B p90");
    double *ea = malloc((size_t)trials * sizeof *ea), *eb = malloc((size_t)trials * sizeof *eb);
    double b_single = 0, b_four[4] = {0};
    for (int li = 0; li < 4; ++li)
        for (int gi = 0; gi < 4; ++gi) {
            uint64_t state = 42u + (uint64_t)(li * 4 + gi);
            double g = gloss[gi];
            for (int tr = 0; tr < trials; ++tr) {
                double exact = 0, acc_a = 0, acc_dot = 0, acc_i = 0;
                for (int k = 0; k < lights[li]; ++k) {
                    double ang = 25 * DEG * sqrt(sol_rng_uniform(&state, 0.0, 1.0)), inten = 0.2 + sol_rng_uniform(&state, 0.0, 1.0);
                    double c = cos(ang);
                    exact += inten * sol_phong_normalized(c, g);
                    acc_a += inten * sol_phong_raw(c, g0);
                    acc_dot += inten * c;
                    acc_i += inten;
                }
                double a = sol_phong_norm_factor(g) * acc_a;
                double b = acc_i * sol_phong_normalized(acc_dot / acc_i, g);
                ea[tr] = fabs(a - exact) / exact;
                eb[tr] = fabs(b - exact) / exact;
            }
            qsort(ea, (size_t)trials, sizeof *ea, cmp_double);
            qsort(eb, (size_t)trials, sizeof *eb, cmp_double);
            int p50 = trials / 2, p90 = trials * 9 / 10;
            exp_table_row(t, "%d|%g|%.3g|%.3g|%.3g|%.3g", lights[li], g, ea[p50], ea[p90], eb[p50], eb[p90]);
            if (lights[li] == 1)
                b_single = fmax(b_single, eb[trials - 1]);
            if (lights[li] == 4)
                b_four[gi] = eb[p50];
        }
    free(ea);
    free(eb);
    exp_table_write(t, exp, "d2_glossiness_deferral");
    char fig[200];
    snprintf(fig, sizeof fig,
             "exponent applied after accumulation: exact for 1 light; 4 lights: median error %.1f%%, %.0f%%, %.0f%%, %.0f%% "
             "at g = 5, 20, 120, 250",
             100 * b_four[0], 100 * b_four[1], 100 * b_four[2], 100 * b_four[3]);
    exp_claim(exp, "D2", "qualitative: glossiness needed at accumulation", fig,
              "exact for 1 light; median error > 10% for 4 lights at g >= 120",
              b_single < 1e-12 && b_four[2] > 0.10 && b_four[3] > 0.10 ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "a sum of I_k (r.l_k)^g over lights is a different function of g for every light set; only nearly linear "
              "lobes (g = 5, lights within 25 deg) survive a power applied after the sum");
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d2_d14_d16_deferred_lobes", argc, argv);
    d16(&exp);
    if (exp.bench)
        return 0;
    d14(&exp);
    d2(&exp);
    return 0;
}
