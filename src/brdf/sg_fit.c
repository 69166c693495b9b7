/* sg_fit.c - fits sums of isotropic Spherical Gaussians (and one anisotropic SG) to the anisotropic
 * Ward NDF with Ceres through sol_lsq_solve (claim D15: "~7 lobes in the vast majority of cases"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sol_brdf.h"

/* Points over the hemisphere of half vectors in Ward's scaled slope coordinates: h is parallel to
 * (ax u, ay v, 1), so the NDF is exp(-(u^2 + v^2)) / (pi ax ay cos^4 th) and its peak region is a
 * unit disk whatever the roughness. Polar (r, psi) with r = R t / (1 - t), t Gauss-Legendre on
 * (0, 1): the whole hemisphere (r -> inf is the horizon) with half the nodes inside r < R.
 * dw = ax ay cos^3 th r dr dpsi. The target is the NDF scaled by pi ax ay (peak ~1). */
typedef struct ward_nodes {
    int n;
    double *dir;    /* 3 per node */
    double *weight; /* solid angle of each node */
    double *target; /* pi ax ay D(h) */
} ward_nodes;

enum { RADIAL_SCALE_NUM = 5, RADIAL_SCALE_DEN = 2 }; /* R = 2.5: exp(-R^2) = 2e-3 */

static void ward_nodes_free(ward_nodes *w)
{
    free(w->dir);
    free(w->weight);
    free(w->target);
    memset(w, 0, sizeof *w);
}

static sol_status ward_nodes_build(double ax, double ay, int n_radial, int n_angular, ward_nodes *out)
{
    int n = n_radial * n_angular;
    ward_nodes w = {n, malloc(3 * (size_t)n * sizeof(double)), malloc((size_t)n * sizeof(double)),
                    malloc((size_t)n * sizeof(double))};
    double *t = malloc(2 * (size_t)n_radial * sizeof(double));
    if (!w.dir || !w.weight || !w.target || !t) {
        free(t);
        ward_nodes_free(&w);
        return SOL_ERR_NO_MEMORY;
    }
    sol_gauss_legendre(n_radial, t, t + n_radial); /* n_radial <= 256 checked by the caller */
    for (int i = 0; i < n_radial; ++i) { /* [-1, 1] -> [0, 1] */
        t[i] = 0.5 * (1.0 - t[i]);
        t[n_radial + i] *= 0.5;
    }
    const double R = (double)RADIAL_SCALE_NUM / RADIAL_SCALE_DEN;
    for (int i = 0; i < n_radial; ++i) {
        double ti = t[i], r = R * ti / (1.0 - ti), dr = R / ((1.0 - ti) * (1.0 - ti)) * t[n_radial + i];
        for (int j = 0; j < n_angular; ++j) {
            double psi = 2.0 * M_PI * (j + 0.5) / n_angular;
            double u = r * cos(psi), v = r * sin(psi);
            double px = ax * u, py = ay * v, len = sqrt(1.0 + px * px + py * py);
            double c = 1.0 / len;
            int k = i * n_angular + j;
            w.dir[3 * k] = px * c;
            w.dir[3 * k + 1] = py * c;
            w.dir[3 * k + 2] = c;
            w.weight[k] = ax * ay * c * c * c * r * dr * (2.0 * M_PI / n_angular);
            w.target[k] = exp(-r * r) * (len * len) * (len * len);
        }
    }
    free(t);
    *out = w;
    return SOL_OK;
}

/* Fit parameters per lobe: polar angle, azimuth, log sharpness, amplitude (target units). */
enum { LOBE_PARAMS = 4 };

static void lobe_from_params(const double *p, sol_sg *g)
{
    double st = sin(p[0]), ct = cos(p[0]);
    g->axis[0] = st * cos(p[1]);
    g->axis[1] = st * sin(p[1]);
    g->axis[2] = ct;
    g->sharpness = exp(p[2]);
    g->amplitude = p[3];
}

/* The exponential factor exp(x) of a lobe, x = sharpness (axis.h - 1) <= 0. Below -746 exp rounds
 * to +0 (the smallest subnormal is exp(-744.4), and exp(x) < 2^-1075 rounds to 0 from
 * x < -745.13), so the factor is 0 without the call, whose underflow path (errno, flags) is slow;
 * far-away nodes of sharp lobes hit it often. Bit for bit exp(x) for every x. */
static inline double lobe_exp(double x)
{
    return x < -746.0 ? 0.0 : exp(x);
}

/* The residual callback's state. Ceres evaluates the residuals alone at a trial point and, when it
 * accepts the step, the residuals with the Jacobian at the same point: the exponential factors of
 * the first call (n per lobe) are kept with its parameters and reused by the second, so each
 * accepted step costs one exp per node and lobe instead of two (same values: same arithmetic). */
typedef struct sg_fit_ctx {
    const ward_nodes *nodes;
    const double *sqrt_w; /* sqrt(weight) / ||target|| */
    int k;
    double *e_cache;      /* n * k factors of the last evaluation (NULL: no cache) */
    double *p_cache;      /* its LOBE_PARAMS * k parameters */
    int cache_valid;
} sg_fit_ctx;

static int sg_residuals(void *vctx, const double *params, double *res, double *jac)
{
    sg_fit_ctx *c = vctx;
    const ward_nodes *w = c->nodes;
    int np = LOBE_PARAMS * c->k;
    int reuse = c->cache_valid && memcmp(c->p_cache, params, (size_t)np * sizeof *params) == 0;
    for (int i = 0; i < w->n; ++i)
        res[i] = -w->target[i] * c->sqrt_w[i];
    for (int k = 0; k < c->k; ++k) {
        const double *p = params + LOBE_PARAMS * k;
        double *ek = c->e_cache + (size_t)k * (size_t)w->n;
        sol_sg g;
        lobe_from_params(p, &g);
        double st = sin(p[0]), ct = cos(p[0]), sp = sin(p[1]), cp = cos(p[1]);
        double d_theta[3] = {ct * cp, ct * sp, -st}, d_phi[3] = {-st * sp, st * cp, 0.0};
        for (int i = 0; i < w->n; ++i) {
            const double *h = w->dir + 3 * i;
            double e = reuse ? ek[i] : lobe_exp(g.sharpness * (sol_dot3(g.axis, h) - 1.0));
            ek[i] = e;
            double s = c->sqrt_w[i];
            res[i] += s * g.amplitude * e;
            if (jac) {
                double ale = s * g.amplitude * e * g.sharpness;
                double *row = jac + (size_t)i * np + LOBE_PARAMS * k;
                row[0] = ale * sol_dot3(d_theta, h);
                row[1] = ale * sol_dot3(d_phi, h);
                row[2] = ale * (sol_dot3(g.axis, h) - 1.0);
                row[3] = s * e;
            }
        }
    }
    memcpy(c->p_cache, params, (size_t)np * sizeof *params);
    c->cache_valid = 1;
    return 0;
}

static double sg_sum(const sol_sg *lobes, int k, const double h[3])
{
    double s = 0.0;
    for (int j = 0; j < k; ++j)
        s += sol_sg_eval(&lobes[j], h);
    return s;
}

/* Errors of an SG sum given in target units (pi ax ay D) on the evaluation nodes. */
static void nodes_error(const ward_nodes *w, const sol_sg *lobes, int k, sol_sg_fit_error *e)
{
    double num = 0.0, den = 0.0, max_diff = 0.0, max_t = 0.0, es = 0.0, ed = 0.0;
    for (int i = 0; i < w->n; ++i) {
        const double *h = w->dir + 3 * i;
        double s = sg_sum(lobes, k, h), t = w->target[i], d = s - t;
        num += w->weight[i] * d * d;
        den += w->weight[i] * t * t;
        es += w->weight[i] * s * h[2];
        ed += w->weight[i] * t * h[2];
        max_diff = fabs(d) > max_diff ? fabs(d) : max_diff;
        max_t = t > max_t ? t : max_t;
    }
    e->rel_l2 = sqrt(num / den);
    e->max_rel = max_diff / max_t;
    e->energy = es / ed - 1.0;
}

static sol_status check_alpha(double ax, double ay)
{
    if (isnan(ax) || isnan(ay))
        return SOL_ERR_NONFINITE;
    if (!(ax >= 1e-3 && ax <= 10.0 && ay >= 1e-3 && ay <= 10.0))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

typedef struct fit_setup {
    sol_sg_fit_options o;
    ward_nodes fit, eval;
    double *sqrt_w;
} fit_setup;

static void fit_setup_free(fit_setup *s)
{
    ward_nodes_free(&s->fit);
    ward_nodes_free(&s->eval);
    free(s->sqrt_w);
}

static sol_status fit_setup_init(double ax, double ay, const sol_sg_fit_options *opts, fit_setup *s)
{
    memset(s, 0, sizeof *s);
    s->o = opts ? *opts : (sol_sg_fit_options){0};
    sol_sg_fit_options *o = &s->o;
    o->radial_samples = o->radial_samples > 0 ? o->radial_samples : 20;
    o->angular_samples = o->angular_samples > 0 ? o->angular_samples : 24;
    o->eval_radial = o->eval_radial > 0 ? o->eval_radial : 64;
    o->eval_angular = o->eval_angular > 0 ? o->eval_angular : 96;
    o->max_iterations = o->max_iterations > 0 ? o->max_iterations : 200;
    if (o->radial_samples > 256 || o->angular_samples > 4096 || o->eval_radial > 256 || o->eval_angular > 4096)
        return SOL_ERR_INVALID_ARG;
    if (o->extra_starts < 0 || o->extra_starts > 1024 ||
        (o->linear_solver != SOL_LSQ_DENSE_NORMAL_CHOLESKY && o->linear_solver != SOL_LSQ_DENSE_QR))
        return SOL_ERR_INVALID_ARG;
    /* Isotropic lobes along the long axis of an anisotropic NDF are narrow in the scaled slope
     * coordinates; more azimuthal fit nodes keep them from hiding between nodes. */
    double ratio = ax > ay ? ax / ay : ay / ax;
    int angular = o->angular_samples * (int)ceil(sqrt(ratio));
    sol_status st = ward_nodes_build(ax, ay, o->radial_samples, angular, &s->fit);
    if (st == SOL_OK)
        st = ward_nodes_build(ax, ay, o->eval_radial, o->eval_angular, &s->eval);
    if (st == SOL_OK && !(s->sqrt_w = malloc((size_t)s->fit.n * sizeof(double))))
        st = SOL_ERR_NO_MEMORY;
    if (st != SOL_OK) {
        fit_setup_free(s);
        return st;
    }
    double norm = 0.0;
    for (int i = 0; i < s->fit.n; ++i)
        norm += s->fit.weight[i] * s->fit.target[i] * s->fit.target[i];
    for (int i = 0; i < s->fit.n; ++i)
        s->sqrt_w[i] = sqrt(s->fit.weight[i] / norm);
    return SOL_OK;
}

/* Seeds the new lobe k (0-based) at the fit node with the largest positive residual. */
static void seed_lobe(const fit_setup *s, const double *params, int k, double lambda0, double *p_new)
{
    sol_sg lobes[16];
    for (int j = 0; j < k; ++j)
        lobe_from_params(params + LOBE_PARAMS * j, &lobes[j]);
    int best = 0;
    double best_r = -INFINITY;
    for (int i = 0; i < s->fit.n; ++i) {
        double r = (s->fit.target[i] - sg_sum(lobes, k, s->fit.dir + 3 * i)) * s->sqrt_w[i];
        if (r > best_r) {
            best_r = r;
            best = i;
        }
    }
    const double *h = s->fit.dir + 3 * best;
    double resid = s->fit.target[best] - sg_sum(lobes, k, h);
    p_new[0] = acos(h[2] < 1.0 ? h[2] : 1.0);
    p_new[1] = atan2(h[1], h[0]);
    p_new[2] = log(lambda0);
    p_new[3] = resid > 0.0 ? resid : 0.0;
}

static const double LOG_SHARPNESS_MIN = -4.605170185988091; /* ln 0.01 */
static const double LOG_SHARPNESS_MAX = 13.815510557964274; /* ln 1e6 */
static const double AMPLITUDE_MAX = 1e3;

/* Splits the lobe of largest energy (amplitude / sharpness) of the first k into two concentric
 * halves, one twice as sharp and one half as sharp (the new one goes to slot k): the start that
 * lets concentric lobes shape a radial profile, which a lobe at the largest residual does not. */
static void split_lobe(double *params, int k, double log_sharpness_cap)
{
    int widest = 0;
    for (int j = 1; j < k; ++j) {
        const double *a = params + LOBE_PARAMS * j, *b = params + LOBE_PARAMS * widest;
        if (a[3] * exp(-a[2]) > b[3] * exp(-b[2]))
            widest = j;
    }
    double *old = params + LOBE_PARAMS * widest, *fresh = params + LOBE_PARAMS * k;
    memcpy(fresh, old, LOBE_PARAMS * sizeof(double));
    old[3] *= 0.5;
    fresh[3] *= 0.5;
    old[2] = fmin(old[2] + M_LN2, log_sharpness_cap);
    fresh[2] = fmax(fresh[2] - M_LN2, LOG_SHARPNESS_MIN);
}

/* Buffers of one greedy fit with up to k_max lobes: current fit, bounds, the start being solved,
 * the best start so far, and the outputs (fits for every k in triangle layout, errors, summaries). */
typedef struct sg_fit_work {
    int k_max;
    double *params, *lower, *upper, *trial, *best; /* LOBE_PARAMS * k_max each, one block */
    sol_sg *scratch, *out;
    sol_sg_fit_error *errs;
    sol_lsq_summary *sums;
    double *e_cache, *p_cache; /* the residual callback's cache (sg_fit_ctx), n fit nodes x k_max */
    double ax, ay;         /* the roughness being fitted */
    double lambda0;        /* sharpness of a new lobe at the default width */
    double log_lambda_cap; /* upper bound of log sharpness for this roughness */
} sg_fit_work;

static void sg_fit_work_free(sg_fit_work *w)
{
    free(w->params);
    free(w->scratch);
    free(w->out);
    free(w->errs);
    free(w->sums);
    free(w->e_cache);
    free(w->p_cache);
}

/* Allocates every buffer; on failure the caller still frees w (free(NULL) is a no-op). */
static sol_status sg_fit_work_alloc(int k_max, int n_nodes, sg_fit_work *w)
{
    int np_max = LOBE_PARAMS * k_max;
    memset(w, 0, sizeof *w);
    w->k_max = k_max;
    w->params = calloc((size_t)np_max * 5, sizeof(double));
    w->scratch = malloc((size_t)k_max * sizeof *w->scratch);
    w->out = malloc((size_t)(k_max * (k_max + 1) / 2) * sizeof(sol_sg));
    w->errs = malloc((size_t)k_max * sizeof *w->errs);
    w->sums = calloc((size_t)k_max, sizeof *w->sums);
    w->e_cache = malloc((size_t)n_nodes * (size_t)k_max * sizeof *w->e_cache);
    w->p_cache = malloc((size_t)np_max * sizeof *w->p_cache);
    if (!w->params || !w->scratch || !w->out || !w->errs || !w->sums || !w->e_cache || !w->p_cache)
        return SOL_ERR_NO_MEMORY;
    w->lower = w->params + np_max;
    w->upper = w->lower + np_max;
    w->trial = w->upper + np_max;
    w->best = w->trial + np_max;
    return SOL_OK;
}

/* Start sharpness and parameter bounds, which depend on the roughness only. */
static void sg_fit_work_limits(double ax, double ay, sg_fit_work *w)
{
    /* Lobes sharper than 4x the target's sharpest curvature would fall between fit nodes. */
    w->ax = ax, w->ay = ay;
    double amin = ax < ay ? ax : ay;
    w->log_lambda_cap = fmin(log(8.0 / (amin * amin)), LOG_SHARPNESS_MAX);
    for (int j = 0; j < w->k_max; ++j) {
        double *lo = w->lower + LOBE_PARAMS * j, *hi = w->upper + LOBE_PARAMS * j;
        lo[0] = 0.0, hi[0] = 0.5 * M_PI;
        lo[1] = -1e3, hi[1] = 1e3;
        lo[2] = LOG_SHARPNESS_MIN, hi[2] = LOG_SHARPNESS_MAX;
        lo[3] = 0.0, hi[3] = AMPLITUDE_MAX;
        if (hi[2] > w->log_lambda_cap)
            hi[2] = w->log_lambda_cap;
    }
    /* Curvature of the NDF at its peak, averaged over azimuth: exp(-lambda th^2 / 2) matches
     * exp(-th^2 (1/ax^2 + 1/ay^2) / 2). */
    double lambda0 = 1.0 / (ax * ax) + 1.0 / (ay * ay);
    if (lambda0 > 1e6)
        lambda0 = 1e6;
    if (log(lambda0) > w->log_lambda_cap)
        lambda0 = exp(w->log_lambda_cap);
    w->lambda0 = lambda0;
}

/* Puts a start inside the solver's bounds (sol_lsq_solve rejects a start outside them). The
 * widths, splits and residual amplitudes of the starts can leave them at the alpha edges: a lobe
 * 4x wider than lambda0 = 0.02 at alpha 10 is below the sharpness floor 0.01, one 4x sharper at
 * alpha 0.002 above the cap 1e6, a residual near the horizon at alpha 10 above the amplitude cap. */
static void clamp_to_bounds(const sg_fit_work *w, int np, double *p)
{
    for (int i = 0; i < np; ++i)
        p[i] = fmin(fmax(p[i], w->lower[i]), w->upper[i]);
}

/* Writes start c of the k-lobe fit into w->trial: the k-1 fit plus a lobe at the largest residual
 * at width factor c (c < 3), or the k-1 fit with its widest lobe split (c == 3). */
static void make_start(const fit_setup *s, sg_fit_work *w, int k, int c)
{
    static const double width_factor[3] = {0.25, 1.0, 4.0};
    int np = LOBE_PARAMS * k;
    memcpy(w->trial, w->params, (size_t)(np - LOBE_PARAMS) * sizeof(double));
    double lam = k == 1 || c == 3 ? w->lambda0 : w->lambda0 * width_factor[c];
    if (log(lam) > w->log_lambda_cap)
        lam = exp(w->log_lambda_cap);
    if (k == 1) {
        w->trial[0] = 0.0, w->trial[1] = 0.0, w->trial[2] = log(lam), w->trial[3] = 1.0;
    } else if (c == 3) {
        split_lobe(w->trial, k - 1, w->log_lambda_cap);
    } else {
        seed_lobe(s, w->params, k - 1, lam, w->trial + np - LOBE_PARAMS);
    }
    clamp_to_bounds(w, np, w->trial);
}

/* A non-greedy start: k lobes on a line along the NDF's long axis, evenly spaced over +-spread
 * times its long roughness (in slope units), each as sharp as the short axis's curvature
 * (exp(-lambda th^2 / 2) = exp(-th^2 / a_short^2)) and with the amplitude that makes the row of
 * lobes add up to the target's profile. */
static void line_start(sg_fit_work *w, int k, double spread)
{
    int long_is_y = w->ay >= w->ax;
    double a_long = long_is_y ? w->ay : w->ax, a_short = long_is_y ? w->ax : w->ay;
    double lam = fmin(2.0 / (a_short * a_short), exp(w->log_lambda_cap));
    double step = k > 1 ? 2.0 * spread / (k - 1) : 0.0; /* in units of a_long */
    for (int j = 0; j < k; ++j) {
        double t = k > 1 ? -spread + step * j : 0.0, slope = t * a_long;
        double *p = w->trial + LOBE_PARAMS * j;
        p[0] = atan(fabs(slope));
        p[1] = (long_is_y ? 0.5 * M_PI : 0.0) + (slope < 0.0 ? M_PI : 0.0);
        p[2] = log(lam);
        p[3] = exp(-t * t) * fmin(1.0, k > 1 ? step * a_long / (sqrt(M_PI) * a_short) : 1.0);
    }
    for (int i = 0; i < LOBE_PARAMS * k; ++i)
        w->trial[i] = fmin(fmax(w->trial[i], w->lower[i]), w->upper[i]);
}

/* A fresh random start: every lobe's axis at a fit node drawn with probability proportional to the
 * target's weight there, log sharpness uniform between the long and short axes' curvatures
 * (2 / a^2, widened by a factor 2 either way), amplitude uniform in (0.2, 1). */
static void random_start(const fit_setup *s, sg_fit_work *w, int k, uint64_t *rng)
{
    double total = 0.0;
    for (int i = 0; i < s->fit.n; ++i)
        total += s->fit.target[i] * s->fit.weight[i];
    double amax = fmax(w->ax, w->ay), amin = fmin(w->ax, w->ay);
    double lo = log(0.5 * 2.0 / (amax * amax)), hi = log(2.0 * 2.0 / (amin * amin));
    for (int j = 0; j < k; ++j) {
        double u = sol_rng_uniform(rng, 0.0, total), acc = 0.0;
        int pick = s->fit.n - 1;
        for (int i = 0; i < s->fit.n; ++i) {
            acc += s->fit.target[i] * s->fit.weight[i];
            if (acc > u) {
                pick = i;
                break;
            }
        }
        const double *h = s->fit.dir + 3 * pick;
        double *p = w->trial + LOBE_PARAMS * j;
        p[0] = acos(h[2] < 1.0 ? h[2] : 1.0);
        p[1] = atan2(h[1], h[0]);
        p[2] = sol_rng_uniform(rng, lo, hi);
        p[3] = sol_rng_uniform(rng, 0.2, 1.0);
    }
    for (int i = 0; i < LOBE_PARAMS * k; ++i)
        w->trial[i] = fmin(fmax(w->trial[i], w->lower[i]), w->upper[i]);
}

/* Moves every lobe of the start in w->trial by a random step of about its own width (axis offset
 * up to 1/sqrt(lambda) in a random tangent direction), scales its sharpness by up to e^+-0.5 and its
 * amplitude by 0.7..1.3, then clamps into the bounds: one hop of a basin-hopping search. */
static void perturb_start(const sg_fit_work *w, int k, uint64_t *rng)
{
    for (int j = 0; j < k; ++j) {
        double *p = w->trial + LOBE_PARAMS * j;
        sol_sg g;
        lobe_from_params(p, &g);
        double st = sin(p[0]), ct = cos(p[0]), sp = sin(p[1]), cp = cos(p[1]);
        double t1[3] = {ct * cp, ct * sp, -st}, t2[3] = {-sp, cp, 0.0}; /* orthonormal tangents */
        double step = sol_rng_uniform(rng, 0.0, 1.0) / sqrt(g.sharpness > 1e-3 ? g.sharpness : 1e-3);
        double dir = sol_rng_uniform(rng, 0.0, 2.0 * M_PI), c = cos(dir) * step, d = sin(dir) * step;
        double a[3] = {g.axis[0] + c * t1[0] + d * t2[0], g.axis[1] + c * t1[1] + d * t2[1],
                       g.axis[2] + c * t1[2] + d * t2[2]};
        double len = sqrt(sol_dot3(a, a));
        a[0] /= len, a[1] /= len, a[2] /= len;
        if (a[2] < 0.0)
            a[2] = -a[2];
        p[0] = acos(a[2] < 1.0 ? a[2] : 1.0);
        p[1] = atan2(a[1], a[0]);
        p[2] += sol_rng_uniform(rng, -0.5, 0.5);
        p[3] *= sol_rng_uniform(rng, 0.7, 1.3);
    }
    for (int i = 0; i < LOBE_PARAMS * k; ++i)
        w->trial[i] = fmin(fmax(w->trial[i], w->lower[i]), w->upper[i]);
}

/* Solves the k-lobe fit from w->trial in place; *rel_l2 is its error on the (finer) evaluation
 * nodes, which ranks the starts. */
static sol_status solve_start(const fit_setup *s, sg_fit_work *w, int k, sol_lsq_summary *sum, double *rel_l2)
{
    sg_fit_ctx ctx = {&s->fit, s->sqrt_w, k, w->e_cache, w->p_cache, 0};
    sol_lsq_problem prob = {LOBE_PARAMS * k, s->fit.n, sg_residuals, &ctx, w->lower, w->upper, s->o.max_iterations,
                            s->o.linear_solver};
    sol_status st = sol_lsq_solve(&prob, w->trial, sum);
    if (st != SOL_OK)
        return st;
    for (int j = 0; j < k; ++j)
        lobe_from_params(w->trial + LOBE_PARAMS * j, &w->scratch[j]);
    sol_sg_fit_error e;
    nodes_error(&s->eval, w->scratch, k, &e);
    *rel_l2 = e.rel_l2;
    return SOL_OK;
}

/* The best start of one greedy step so far, and the time and iterations of all its starts. */
typedef struct start_pick {
    double best_l2;
    sol_lsq_summary best_sum;
    int have_best;
    double total_seconds;
    int total_iterations;
} start_pick;

/* Solves the start in w->trial and keeps it in w->best when it beats pick->best_l2. */
static sol_status solve_and_keep(const fit_setup *s, sg_fit_work *w, int k, start_pick *pick)
{
    sol_lsq_summary sum;
    double l2;
    sol_status st = solve_start(s, w, k, &sum, &l2);
    if (st != SOL_OK)
        return st;
    if (l2 < pick->best_l2) {
        pick->best_l2 = l2;
        pick->best_sum = sum;
        memcpy(w->best, w->trial, (size_t)(LOBE_PARAMS * k) * sizeof(double));
        pick->have_best = 1;
    }
    pick->total_seconds += sum.solve_seconds;
    pick->total_iterations += sum.iterations;
    return SOL_OK;
}

/* Greedy step to k lobes: every start is solved and the best by evaluation error wins; the k-1 fit
 * padded with a zero lobe is kept when no start beats it (*prev_l2), so the error never rises with
 * k. The summary of step k reports the winner but the time and iterations of all starts. */
static sol_status fit_k_lobes(const fit_setup *s, sg_fit_work *w, int k, double *prev_l2)
{
    int np = LOBE_PARAMS * k, n_cand = k == 1 ? 1 : 4;
    start_pick pick = {.best_l2 = *prev_l2};
    for (int c = 0; c < n_cand; ++c) {
        make_start(s, w, k, c);
        sol_status st = solve_and_keep(s, w, k, &pick);
        if (st != SOL_OK)
            return st;
    }
    /* Extra starts of the last fit (multi-start check): lines, random starts and basin hops. */
    uint64_t rng = sol_mix64(0x5347u * 131u + (uint64_t)k);
    for (int r = 0; k > 1 && k == w->k_max && r < s->o.extra_starts; ++r) {
        static const double spreads[3] = {1.0, 1.5, 2.0};
        if (r < 3) {
            line_start(w, k, spreads[r]);
        } else if (r % 2 == 1) {
            random_start(s, w, k, &rng);
        } else {
            if (pick.have_best)
                memcpy(w->trial, w->best, (size_t)np * sizeof(double));
            else
                make_start(s, w, k, 1);
            perturb_start(w, k, &rng);
        }
        sol_status st = solve_and_keep(s, w, k, &pick);
        if (st != SOL_OK)
            return st;
    }
    sol_lsq_summary *sum_k = &w->sums[k - 1];
    if (pick.have_best) {
        memcpy(w->params, w->best, (size_t)np * sizeof(double));
        *prev_l2 = pick.best_l2;
        *sum_k = pick.best_sum;
    } else { /* keep fit k-1 and give the new lobe zero amplitude */
        double *fresh = w->params + np - LOBE_PARAMS;
        fresh[0] = 0.0, fresh[1] = 0.0, fresh[2] = log(w->lambda0), fresh[3] = 0.0;
        *sum_k = k > 1 ? w->sums[k - 2] : pick.best_sum;
    }
    sum_k->solve_seconds = pick.total_seconds;
    sum_k->iterations = pick.total_iterations;
    return SOL_OK;
}

/* Stores the current k-lobe fit into its slot of w->out with its evaluation error, converting the
 * amplitudes from target units (pi ax ay D) to NDF units. */
static void store_fit(const fit_setup *s, sg_fit_work *w, int k, double ax, double ay)
{
    sol_sg *fit = w->out + k * (k - 1) / 2;
    for (int j = 0; j < k; ++j)
        lobe_from_params(w->params + LOBE_PARAMS * j, &fit[j]);
    nodes_error(&s->eval, fit, k, &w->errs[k - 1]);
    for (int j = 0; j < k; ++j)
        fit[j].amplitude /= M_PI * ax * ay;
}

sol_status sol_ward_sg_fit(double alpha_x, double alpha_y, int k_max, const sol_sg_fit_options *opts, sol_sg *lobes,
                           sol_sg_fit_error *errors, sol_lsq_summary *summaries)
{
    if (!lobes || !errors)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_alpha(alpha_x, alpha_y);
    if (st != SOL_OK)
        return st;
    if (k_max < 1 || k_max > 16)
        return SOL_ERR_INVALID_ARG;
    fit_setup s;
    if ((st = fit_setup_init(alpha_x, alpha_y, opts, &s)) != SOL_OK)
        return st;
    sg_fit_work w;
    if ((st = sg_fit_work_alloc(k_max, s.fit.n, &w)) == SOL_OK) {
        sg_fit_work_limits(alpha_x, alpha_y, &w);
        double prev_l2 = INFINITY;
        for (int k = 1; k <= k_max && st == SOL_OK; ++k)
            if ((st = fit_k_lobes(&s, &w, k, &prev_l2)) == SOL_OK)
                store_fit(&s, &w, k, alpha_x, alpha_y);
    }
    if (st == SOL_OK) { /* outputs are written only on success */
        memcpy(lobes, w.out, (size_t)(k_max * (k_max + 1) / 2) * sizeof(sol_sg));
        memcpy(errors, w.errs, (size_t)k_max * sizeof *w.errs);
        if (summaries)
            memcpy(summaries, w.sums, (size_t)k_max * sizeof *w.sums);
    }
    sg_fit_work_free(&w);
    fit_setup_free(&s);
    return st;
}

sol_status sol_ward_sg_error(double alpha_x, double alpha_y, const sol_sg *lobes, int k,
                             const sol_sg_fit_options *opts, sol_sg_fit_error *error)
{
    if (!lobes || !error)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_alpha(alpha_x, alpha_y);
    if (st != SOL_OK)
        return st;
    if (k < 1 || k > 4096)
        return SOL_ERR_INVALID_ARG;
    fit_setup s;
    if ((st = fit_setup_init(alpha_x, alpha_y, opts, &s)) != SOL_OK)
        return st;
    sol_sg *scaled = malloc((size_t)k * sizeof *scaled);
    if (!scaled) {
        fit_setup_free(&s);
        return SOL_ERR_NO_MEMORY;
    }
    for (int j = 0; j < k; ++j) {
        scaled[j] = lobes[j];
        scaled[j].amplitude *= M_PI * alpha_x * alpha_y;
    }
    nodes_error(&s.eval, scaled, k, error);
    free(scaled);
    fit_setup_free(&s);
    return SOL_OK;
}

/* ---- one anisotropic SG (Xu et al. 2013) in the shading frame: params ln lx, ln ly, c ---- */

typedef struct asg_fit_ctx {
    const ward_nodes *nodes;
    const double *sqrt_w;
} asg_fit_ctx;

static int asg_residuals(void *vctx, const double *p, double *res, double *jac)
{
    const asg_fit_ctx *c = vctx;
    double lx = exp(p[0]), ly = exp(p[1]);
    for (int i = 0; i < c->nodes->n; ++i) {
        const double *h = c->nodes->dir + 3 * i;
        double q = h[2] * exp(-lx * h[0] * h[0] - ly * h[1] * h[1]), s = c->sqrt_w[i];
        res[i] = s * (p[2] * q - c->nodes->target[i]);
        if (jac) {
            jac[3 * i] = -s * p[2] * q * lx * h[0] * h[0];
            jac[3 * i + 1] = -s * p[2] * q * ly * h[1] * h[1];
            jac[3 * i + 2] = s * q;
        }
    }
    return 0;
}

sol_status sol_ward_asg_fit(double alpha_x, double alpha_y, const sol_sg_fit_options *opts, sol_asg *lobe,
                            sol_sg_fit_error *error, sol_lsq_summary *summary)
{
    if (!lobe || !error)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_alpha(alpha_x, alpha_y);
    if (st != SOL_OK)
        return st;
    fit_setup s;
    if ((st = fit_setup_init(alpha_x, alpha_y, opts, &s)) != SOL_OK)
        return st;
    /* Near the peak exp(-lx x^2) matches exp(-x^2 / ax^2). */
    double p[3] = {-2.0 * log(alpha_x), -2.0 * log(alpha_y), 1.0};
    double lower[3] = {LOG_SHARPNESS_MIN, LOG_SHARPNESS_MIN, 0.0};
    double upper[3] = {LOG_SHARPNESS_MAX, LOG_SHARPNESS_MAX, AMPLITUDE_MAX};
    for (int i = 0; i < 2; ++i)
        p[i] = p[i] > upper[i] ? upper[i] : p[i];
    asg_fit_ctx ctx = {&s.fit, s.sqrt_w};
    sol_lsq_problem prob = {3, s.fit.n, asg_residuals, &ctx, lower, upper, s.o.max_iterations, s.o.linear_solver};
    sol_lsq_summary sum;
    if ((st = sol_lsq_solve(&prob, p, &sum)) == SOL_OK) {
        sol_asg g = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, exp(p[0]), exp(p[1]), p[2]};
        /* Error on the evaluation nodes, in target units. */
        double num = 0.0, den = 0.0, maxd = 0.0, maxt = 0.0, es = 0.0, ed = 0.0;
        for (int i = 0; i < s.eval.n; ++i) {
            const double *h = s.eval.dir + 3 * i;
            double a = sol_asg_eval(&g, h), t = s.eval.target[i], d = a - t;
            num += s.eval.weight[i] * d * d;
            den += s.eval.weight[i] * t * t;
            es += s.eval.weight[i] * a * h[2];
            ed += s.eval.weight[i] * t * h[2];
            maxd = fabs(d) > maxd ? fabs(d) : maxd;
            maxt = t > maxt ? t : maxt;
        }
        error->rel_l2 = sqrt(num / den);
        error->max_rel = maxd / maxt;
        error->energy = es / ed - 1.0;
        g.amplitude /= M_PI * alpha_x * alpha_y;
        *lobe = g;
        if (summary)
            *summary = sum;
    }
    fit_setup_free(&s);
    return st;
}
