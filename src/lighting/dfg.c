/* dfg.c - S4: the split-sum DFG term (Karis 2013) by deterministic quadrature, a bilinear lookup
 * table of it, and Narkowicz's two published analytical fits ("Analytical DFG Term for IBL", 2014,
 * seed 001): the polynomial fit and his GGX refit of Lazarov 2013's form. The fits are evaluated
 * with the constants as published: those constants are the claim under test. A least-squares refit
 * of the polynomial form to the reference separates what the form can do from what its constants do. */
#include "sol_lighting.h"

#include <stdlib.h>

static int in_unit_interval(double x)
{
    return x >= 0.0 && x <= 1.0;
}

static sol_status check_unit_pair(double a, double b)
{
    if (!isfinite(a) || !isfinite(b))
        return SOL_ERR_NONFINITE;
    if (!in_unit_interval(a) || !in_unit_interval(b))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

static double saturate(double x)
{
    return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
}

double sol_dfg_alpha_from_gloss(double gloss)
{
    if (isnan(gloss))
        return gloss;
    double r = 1.0 - saturate(gloss);
    return (r * r) * (r * r);
}

/* Separable Smith term for GGX folded with 1/(4 n.v n.l): G / (4 n.v n.l) = 1 / (vis(v) vis(l)),
 * vis(c) = c + sqrt(alpha^2 + (1 - alpha^2) c^2) (hypot: no underflow for denormal c). */
static double smith_vis_factor(double alpha, double c)
{
    return c + hypot(alpha, sqrt(1.0 - alpha * alpha) * c);
}

/* GGX half-vector CDF in theta_h: the e with cos^2(theta_h) = (1 - e) / (1 + (alpha^2 - 1) e). */
static double ggx_cdf_at(double alpha2, double theta_h)
{
    double c2 = cos(theta_h) * cos(theta_h);
    if (c2 >= 1.0)
        return 0.0; /* theta_h = 0; also avoids 0/0 when alpha = 0 */
    return (1.0 - c2) / (1.0 + c2 * (alpha2 - 1.0));
}

/* Midpoint quadrature of scale and bias over the half vectors with CDF value e in [e0, e1]
 * (rows) and, per row, the azimuths where n.l > 0 (columns). */
static void integrate_band(double alpha, double vx, double vz, double e0, double e1, int samples, double out[2])
{
    const double alpha2 = alpha * alpha, vis_v = smith_vis_factor(alpha, vz);
    double sum_scale = 0.0, sum_bias = 0.0, sum_de = 0.0;
    for (int j = 0; j < samples; ++j) {
        /* e = e0 + (e1 - e0) (3 s^2 - 2 s^3) clusters rows at both ends: at e0 the azimuth range
         * starts to shrink like a square root, and near e = 1 (theta_h -> 90 degrees, reached at
         * grazing n.v) the importance weight grows like 1 / cos(theta_h) ~ 1 / sqrt(1 - e). Both
         * would make the plain midpoint rule converge slowly; de = 6 s (1 - s) (e1 - e0) ds. */
        double s = (j + 0.5) / samples, e = e0 + (e1 - e0) * s * s * (3.0 - 2.0 * s);
        double de = 6.0 * s * (1.0 - s);
        sum_de += de;
        double cos_h = sqrt((1.0 - e) / (1.0 + (alpha2 - 1.0) * e));
        double sin_h = sqrt(fmax(0.0, 1.0 - cos_h * cos_h));
        /* n.l = 2 (v.h) cos_h - n.v > 0 holds for |phi| < phi_max: integrating phi over exactly that
         * interval keeps the cut-off at the interval's end, where the midpoint rule stays second
         * order (a cut inside the interval would make it first order). n.l > 0 implies v.h > 0. */
        double denom = 2.0 * vx * sin_h * cos_h, numer = vz * (1.0 - 2.0 * cos_h * cos_h);
        double c = denom > 0.0 ? numer / denom : (numer < 0.0 ? -2.0 : 2.0);
        if (c >= 1.0)
            continue;
        double phi_max = c <= -1.0 ? M_PI : acos(c);
        double row_scale = 0.0, row_bias = 0.0;
        for (int i = 0; i < samples; ++i) {
            /* phi = phi_max (1 - t^2) clusters samples at the cut-off, where n.l -> 0 and the Smith
             * term turns over sharply (within n.l ~ alpha) at grazing view angles; dphi = 2 t dt. */
            double t = (i + 0.5) / samples, phi = phi_max * (1.0 - t * t);
            double v_dot_h = vx * sin_h * cos(phi) + vz * cos_h;
            double n_dot_l = 2.0 * v_dot_h * cos_h - vz;
            if (n_dot_l <= 0.0 || v_dot_h <= 0.0)
                continue; /* rounding at the interval's end */
            /* f n.l / pdf with pdf(l) = D n.h / (4 v.h): the D cancels. */
            /* Grouped as ratios of like magnitudes so denormal n.v cannot give 0/0. */
            double weight = (n_dot_l / smith_vis_factor(alpha, n_dot_l)) * (4.0 * v_dot_h / (cos_h * vis_v));
            double m = 1.0 - v_dot_h, fc = (m * m) * (m * m) * m;
            row_scale += 2.0 * t * weight * (1.0 - fc);
            row_bias += 2.0 * t * weight * fc;
        }
        /* The row averages phi over [-pi, pi]: the symmetric interval is 2 phi_max of 2 pi. */
        sum_scale += de * row_scale * (phi_max / M_PI);
        sum_bias += de * row_bias * (phi_max / M_PI);
    }
    /* Dividing by the rule's own sum of de (not its exact integral, samples) keeps a constant
     * integrand exact, e.g. the mirror limit alpha = 0 where DFG is exactly Fresnel. The azimuth
     * weights 2 t sum to exactly `samples`. */
    double n = (double)samples * sum_de;
    out[0] = n > 0.0 ? sum_scale * (e1 - e0) / n : 0.0;
    out[1] = n > 0.0 ? sum_bias * (e1 - e0) / n : 0.0;
}

sol_status sol_dfg_integrate(double alpha, double n_dot_v, int samples, double *scale, double *bias)
{
    if (!scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(alpha, n_dot_v);
    if (st != SOL_OK)
        return st;
    if (samples < 1 || samples > 65536)
        return SOL_ERR_INVALID_ARG;
    const double alpha2 = alpha * alpha;
    const double vx = sqrt(1.0 - n_dot_v * n_dot_v);
    /* n.l > 0 for every azimuth of h below theta_start and for none above theta_end (h must stay
     * within 45 degrees of the bisector of v and the horizon): the integrand's kinks are there. */
    const double theta_v = acos(n_dot_v);
    const double e_start = ggx_cdf_at(alpha2, 0.25 * M_PI - 0.5 * theta_v);
    const double e_end = ggx_cdf_at(alpha2, 0.25 * M_PI + 0.5 * theta_v);
    double full[2], partial[2];
    integrate_band(alpha, vx, n_dot_v, 0.0, e_start, samples, full);
    integrate_band(alpha, vx, n_dot_v, e_start, e_end, samples, partial);
    *scale = full[0] + partial[0];
    *bias = full[1] + partial[1];
    return SOL_OK;
}

/* Narkowicz 2014, EnvDFGPolynomial, his published constants. */
const sol_dfg_polynomial sol_dfg_polynomial_narkowicz = {
    {-0.1688, 1.895, 0.9903, -4.853, 8.404, -5.069},
    {0.6045, 1.699, -0.5228, -3.603, 1.404, 0.1939, 2.661}};

/* The two bias branches and the delta polynomial, unsaturated, at x = gloss, y = n.v. */
static double bias_in_gloss(const double b[6], double x)
{
    return b[0] * x + b[1] * x * x;
}

static double bias_in_nv(const double b[6], double y)
{
    return b[2] + b[3] * y + b[4] * y * y + b[5] * y * y * y;
}

static void delta_terms(double x, double y, double t[7])
{
    t[0] = 1.0;
    t[1] = x;
    t[2] = y;
    t[3] = x * x;
    t[4] = x * y;
    t[5] = y * y;
    t[6] = x * x * x;
}

sol_status sol_dfg_eval_polynomial(const sol_dfg_polynomial *p, double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!p || !scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    double t[7], delta = 0.0;
    delta_terms(gloss, n_dot_v, t);
    for (int i = 0; i < 7; ++i)
        delta += p->delta[i] * t[i];
    double b = saturate(fmin(bias_in_gloss(p->bias, gloss), bias_in_nv(p->bias, n_dot_v)));
    *scale = saturate(delta) - b;
    *bias = b;
    return SOL_OK;
}

sol_status sol_dfg_fit_polynomial(double gloss, double n_dot_v, double *scale, double *bias)
{
    return sol_dfg_eval_polynomial(&sol_dfg_polynomial_narkowicz, gloss, n_dot_v, scale, bias);
}

/* Least squares sum over rows of (a . x - y)^2 by normal equations and Gaussian elimination with
 * partial pivoting; n unknowns (n <= 7). Returns 0 if the system is singular. */
static int least_squares(int n, const double *rows, const double *targets, size_t count, double *x)
{
    double m[7][8] = {{0}};
    for (size_t k = 0; k < count; ++k)
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j)
                m[i][j] += rows[k * n + i] * rows[k * n + j];
            m[i][n] += rows[k * n + i] * targets[k];
        }
    for (int c = 0; c < n; ++c) {
        int pivot = c;
        for (int r = c + 1; r < n; ++r)
            if (fabs(m[r][c]) > fabs(m[pivot][c]))
                pivot = r;
        if (!(fabs(m[pivot][c]) > 1e-300))
            return 0;
        for (int j = 0; j <= n; ++j) {
            double tmp = m[c][j];
            m[c][j] = m[pivot][j];
            m[pivot][j] = tmp;
        }
        for (int r = c + 1; r < n; ++r) {
            double f = m[r][c] / m[c][c];
            for (int j = c; j <= n; ++j)
                m[r][j] -= f * m[c][j];
        }
    }
    for (int c = n - 1; c >= 0; --c) {
        double v = m[c][n];
        for (int j = c + 1; j < n; ++j)
            v -= m[c][j] * x[j];
        x[c] = v / m[c][c];
    }
    return 1;
}

/* Samples must be finite with gloss and n.v in [0, 1]. */
static sol_status check_refit_samples(const double *gloss, const double *n_dot_v, const double *scale,
                                      const double *bias, size_t count)
{
    for (size_t k = 0; k < count; ++k) {
        if (!isfinite(gloss[k]) || !isfinite(n_dot_v[k]) || !isfinite(scale[k]) || !isfinite(bias[k]))
            return SOL_ERR_NONFINITE;
        if (!in_unit_interval(gloss[k]) || !in_unit_interval(n_dot_v[k]))
            return SOL_ERR_INVALID_ARG;
    }
    return SOL_OK;
}

/* Design rows (7 terms) and targets scale + bias of the points whose delta prediction is not
 * saturated: only they carry gradient. Returns their count. */
static size_t gather_delta_rows(const double *delta, const double *gloss, const double *n_dot_v,
                                const double *scale, const double *bias, size_t count, double *rows,
                                double *targets)
{
    size_t active = 0;
    for (size_t k = 0; k < count; ++k) {
        double t[7], pred = 0.0;
        delta_terms(gloss[k], n_dot_v[k], t);
        for (int i = 0; i < 7; ++i)
            pred += delta[i] * t[i];
        if (pred <= 0.0 || pred >= 1.0)
            continue;
        for (int i = 0; i < 7; ++i)
            rows[7 * active + i] = t[i];
        targets[active++] = scale[k] + bias[k];
    }
    return active;
}

/* Gauss-Newton for the saturated model: a point whose prediction is saturated has a zero gradient,
 * so each step is the least-squares fit over the unsaturated points (delta is linear in its 7
 * constants); iterate until that set stops changing. Fails only if the first step cannot be made. */
static sol_status refit_delta(const double *gloss, const double *n_dot_v, const double *scale, const double *bias,
                              size_t count, double *rows, double *targets, double delta[7])
{
    for (int iteration = 0; iteration < 50; ++iteration) {
        size_t active = gather_delta_rows(delta, gloss, n_dot_v, scale, bias, count, rows, targets);
        double d[7];
        if (active < 7 || !least_squares(7, rows, targets, active, d))
            return iteration ? SOL_OK : SOL_ERR_NO_CONVERGENCE;
        double change = 0.0;
        for (int i = 0; i < 7; ++i) {
            change += fabs(d[i] - delta[i]);
            delta[i] = d[i];
        }
        if (change < 1e-12)
            break;
    }
    return SOL_OK;
}

/* Rows of the unsaturated points, each assigned to the branch of the bias model that is the smaller
 * one there: branch 0 (gloss, 2 terms) first, then branch 1 (n.v, 4 terms) right after them. */
static void gather_bias_rows(const double *b, const double *gloss, const double *n_dot_v, const double *bias,
                             size_t count, double *rows, double *targets, size_t *nx, size_t *ny)
{
    *nx = *ny = 0;
    for (int branch = 0; branch < 2; ++branch)
        for (size_t k = 0; k < count; ++k) {
            double bx = bias_in_gloss(b, gloss[k]), by = bias_in_nv(b, n_dot_v[k]);
            double pred = fmin(bx, by), y = n_dot_v[k];
            if (pred <= 0.0 || pred >= 1.0 || (branch == 0) != (bx <= by))
                continue;
            if (branch == 0) {
                rows[2 * *nx] = gloss[k];
                rows[2 * *nx + 1] = gloss[k] * gloss[k];
                targets[(*nx)++] = bias[k];
            } else {
                double *row = rows + 2 * *nx + 4 * *ny; /* after all of branch 0's rows */
                row[0] = 1.0;
                row[1] = y;
                row[2] = y * y;
                row[3] = y * y * y;
                targets[*nx + (*ny)++] = bias[k];
            }
        }
}

/* bias = saturate(min(branch in gloss, branch in n.v)): the same steps as refit_delta, with each
 * unsaturated point assigned to the branch that is the smaller one (k-planes style alternation).
 * A step that cannot be made keeps the last good branches. */
static void refit_bias(const double *gloss, const double *n_dot_v, const double *bias, size_t count, double *rows,
                       double *targets, double b[6])
{
    for (int iteration = 0; iteration < 50; ++iteration) {
        double gx[2], gy[4];
        size_t nx, ny;
        gather_bias_rows(b, gloss, n_dot_v, bias, count, rows, targets, &nx, &ny);
        /* rows/targets of branch 1 start after branch 0's: fit each from its own offset. */
        int ok_x = nx >= 2 && least_squares(2, rows, targets, nx, gx);
        int ok_y = ny >= 4 && least_squares(4, rows + 2 * nx, targets + nx, ny, gy);
        if (!ok_x || !ok_y)
            break;
        double change = fabs(gx[0] - b[0]) + fabs(gx[1] - b[1]);
        for (int i = 0; i < 4; ++i)
            change += fabs(gy[i] - b[2 + i]);
        b[0] = gx[0];
        b[1] = gx[1];
        for (int i = 0; i < 4; ++i)
            b[2 + i] = gy[i];
        if (change < 1e-12)
            break;
    }
}

sol_status sol_dfg_refit_polynomial(const double *gloss, const double *n_dot_v, const double *scale, const double *bias,
                                    size_t count, sol_dfg_polynomial *out)
{
    if (!gloss || !n_dot_v || !scale || !bias || !out)
        return SOL_ERR_NULL_ARG;
    if (count < 16)
        return SOL_ERR_INVALID_ARG;
    sol_status st = check_refit_samples(gloss, n_dot_v, scale, bias, count);
    if (st != SOL_OK)
        return st;
    double *rows = malloc(sizeof *rows * 7 * count), *targets = malloc(sizeof *targets * count);
    if (!rows || !targets) {
        free(rows);
        free(targets);
        return SOL_ERR_NO_MEMORY;
    }
    sol_dfg_polynomial p = sol_dfg_polynomial_narkowicz;
    st = refit_delta(gloss, n_dot_v, scale, bias, count, rows, targets, p.delta);
    if (st == SOL_OK)
        refit_bias(gloss, n_dot_v, bias, count, rows, targets, p.bias);
    free(rows);
    free(targets);
    if (st == SOL_OK)
        *out = p;
    return st;
}

sol_status sol_dfg_fit_lazarov(double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    /* Narkowicz 2014, EnvDFGLazarov: t = gloss * p0 + p1 with his GGX-refitted p0, p1. */
    double tx = 0.5745 * gloss + 0.5753, ty = 1.548 * gloss - 0.2511;
    double tz = -0.02397 * gloss - 0.02066, tw = 1.301 * gloss + 0.4755;
    double b = saturate(tx * fmin(ty, exp2(-7.672 * n_dot_v)) + tz);
    *scale = saturate(tw) - b;
    *bias = b;
    return SOL_OK;
}

sol_status sol_dfg_lut_build(int size, int samples, sol_dfg_lut *out)
{
    if (!out)
        return SOL_ERR_NULL_ARG;
    if (size < 2 || size > 4096 || samples < 1 || samples > 65536)
        return SOL_ERR_INVALID_ARG;
    float *data = malloc(sizeof *data * 2u * (size_t)size * (size_t)size);
    if (!data)
        return SOL_ERR_NO_MEMORY;
    /* Each texel is independent and written once: the result does not depend on thread count. */
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double s = 0.0, b = 0.0;
            double alpha = sol_dfg_alpha_from_gloss((x + 0.5) / size);
            (void)sol_dfg_integrate(alpha, (y + 0.5) / size, samples, &s, &b); /* arguments are valid */
            data[2 * ((size_t)y * (size_t)size + (size_t)x) + 0] = (float)s;
            data[2 * ((size_t)y * (size_t)size + (size_t)x) + 1] = (float)b;
        }
    out->size = size;
    out->scale_bias = data;
    return SOL_OK;
}

/* Texel coordinate of u in [0,1] for a clamp-to-edge bilinear fetch: lower index and weight. */
static void bilinear_coordinate(double u, int size, int *i0, double *t)
{
    double p = u * size - 0.5;
    if (p <= 0.0) {
        *i0 = 0;
        *t = 0.0;
    } else if (p >= size - 1) {
        *i0 = size - 2;
        *t = 1.0;
    } else {
        *i0 = (int)p;
        *t = p - *i0;
    }
}

sol_status sol_dfg_lut_sample(const sol_dfg_lut *lut, double gloss, double n_dot_v, double *scale, double *bias)
{
    if (!lut || !scale || !bias)
        return SOL_ERR_NULL_ARG;
    sol_status st = check_unit_pair(gloss, n_dot_v);
    if (st != SOL_OK)
        return st;
    if (!lut->scale_bias || lut->size < 2)
        return SOL_ERR_INVALID_ARG;
    int x0, y0;
    double tx, ty;
    bilinear_coordinate(gloss, lut->size, &x0, &tx);
    bilinear_coordinate(n_dot_v, lut->size, &y0, &ty);
    const float *row0 = lut->scale_bias + 2 * (size_t)y0 * (size_t)lut->size;
    const float *row1 = row0 + 2 * (size_t)lut->size;
    double out[2];
    for (int c = 0; c < 2; ++c) {
        double top = row0[2 * x0 + c] + tx * (row0[2 * x0 + 2 + c] - row0[2 * x0 + c]);
        double bottom = row1[2 * x0 + c] + tx * (row1[2 * x0 + 2 + c] - row1[2 * x0 + c]);
        out[c] = top + ty * (bottom - top);
    }
    *scale = out[0];
    *bias = out[1];
    return SOL_OK;
}

void sol_dfg_lut_free(sol_dfg_lut *lut)
{
    if (!lut)
        return;
    free(lut->scale_bias);
    lut->scale_bias = NULL;
    lut->size = 0;
}
