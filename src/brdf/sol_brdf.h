/* sol_brdf.h - BRDFs, sphere quadrature, Spherical Gaussians, the Ward-to-SG fit (Ceres) and the
 * principal Phong lobe extraction of the talk's "anisotropic deferred materials" (claims D2, D8,
 * D14, D15, D16).
 *
 * Conventions: directions are unit double[3] vectors in the shading frame unless said otherwise
 * (normal = +z, tangent = +x, bitangent = +y); angles in radians; BRDF values in 1/sr. Functions
 * that cannot fail return their value directly and are total: NaN input gives NaN output, every
 * other input (including +-Inf, subnormals and the largest doubles) gives a finite value (clamped
 * cosines, no division by zero; where a product or quotient would under- or overflow although
 * the answer is representable, it is computed scaled or in logs, e.g. the Blinn-Phong factor at
 * n = 1e160 is 3.98e158). A true value above DBL_MAX (the delta-like limits alpha -> 0, n -> inf,
 * e.g. D at the peak for alpha < ~1e-154) saturates to DBL_MAX. Direction arguments far from
 * unit length (or with an infinite component) are outside the domain: the result is then finite
 * or NaN, never +-Inf. Fallible functions return
 * sol_status and leave outputs untouched on error.
 */
#ifndef SOL_BRDF_H
#define SOL_BRDF_H

#include <stddef.h>
#include <stdint.h>

#include "sol_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================= BRDF models (brdf_models.c) ======================= */

/* Reflection of v about unit n: 2 (n.v) n - v. v points away from the surface. */
void sol_reflect(const double v[3], const double n[3], double r[3]);

/* Phong, reflection-vector form (Phong 1975; normalisation: Lewis 1994, the talk's slide on
 * "Lighting consistency"): raw (r.l)_+^n and normalised (n+2)/(2 pi) (r.l)_+^n. With r = normal the
 * normalised lobe times cos(theta_l) integrates to exactly 1 over the hemisphere (claim D8).
 * `r_dot_l` is clamped to [0,1]; exponent n >= 0 (negative n is treated as 0). */
double sol_phong_raw(double r_dot_l, double n);
double sol_phong_normalized(double r_dot_l, double n);
/* (n+2)/(2 pi): makes the cosine-weighted lobe about the normal integrate to 1. */
double sol_phong_norm_factor(double n);
/* (n+1)/(2 pi): makes the lobe itself (no cosine) integrate to 1 over the sphere; this is the
 * kernel a prefiltered environment map is convolved with. */
double sol_phong_lobe_norm_factor(double n);

/* Blinn-Phong (n.h)_+^n. Exact normalisation for v = normal (Giesen 2009 derivation):
 * (n+2)(n+4) / (8 pi (2^(-n/2) + n)); the common approximation (n+8)/(8 pi) (Akenine-Moeller et
 * al., Real-Time Rendering 3rd ed.). */
double sol_blinn_phong_raw(double n_dot_h, double n);
double sol_blinn_phong_norm_factor_exact(double n);
double sol_blinn_phong_norm_factor_approx(double n);

/* Anisotropic Ward NDF over half vectors h in the shading frame (Ward 1992, in Walter's 2005
 * microfacet form): D(h) = exp(-tan^2(th) (cos^2 ph/ax^2 + sin^2 ph/ay^2)) / (pi ax ay cos^4 th),
 * zero for h.z <= 0; normalised so that the integral of D(h) (n.h) over the hemisphere is 1.
 * alpha_x, alpha_y are roughnesses in (0, inf); the caller validates them (values <= 0 give 0). */
double sol_ward_ndf(const double h[3], double alpha_x, double alpha_y);
/* Ward's original BRDF (Ward 1992, eq. 5a) with rho_s = 1:
 * exp(...) / (4 pi ax ay sqrt(cos th_i cos th_o)); zero below either horizon. */
double sol_ward_brdf(const double v[3], const double l[3], double alpha_x, double alpha_y);

/* Isotropic microfacet terms (Walter et al. 2007): Beckmann and GGX NDFs (normalised like the
 * Ward NDF), Smith's masking G1 for each (GGX exact; Beckmann with Walter's rational
 * approximation), Schlick's Fresnel (Schlick 1994). cos arguments are clamped to [0,1]. Any alpha
 * in (0, +Inf] is accepted (alpha <= 0 gives D = 0); Fresnel with f0 = +-Inf gives 1 at v.h <= 0
 * and +-DBL_MAX otherwise. */
double sol_beckmann_ndf(double n_dot_h, double alpha);
double sol_ggx_ndf(double n_dot_h, double alpha);
double sol_smith_g1_ggx(double n_dot_v, double alpha);
double sol_smith_g1_beckmann(double n_dot_v, double alpha);
double sol_fresnel_schlick(double f0, double v_dot_h);

typedef enum sol_ndf_kind { SOL_NDF_GGX = 0, SOL_NDF_BECKMANN } sol_ndf_kind;
/* Cook-Torrance BRDF D G F / (4 (n.l)(n.v)) with the chosen NDF, the separable Smith G = G1(v)G1(l)
 * and Schlick's F with reflectance f0. Zero when n.l <= 0 or n.v <= 0. At grazing angles (n.v n.l
 * underflowing, e.g. v = l at the horizon) it is evaluated as D F (G1(v)/n.v) (G1(l)/n.l) / 4,
 * which stays finite; where D saturates (alpha -> 0 at the peak) the BRDF gives +-DBL_MAX.
 * Claim D14 splits it into the
 * NDF part (lighting) and G F (deferred). */
double sol_cook_torrance(const double v[3], const double l[3], sol_ndf_kind ndf, double alpha, double f0);

/* ======================= sphere quadrature (sphere_quadrature.c) ======================= */

/* Integrand over unit directions. */
typedef double (*sol_sphere_fn)(const double dir[3], void *ctx);

typedef struct sol_quad_options {
    double abs_tol;     /* absolute error target; 0 = 1e-10 */
    double rel_tol;     /* relative error target; 0 = 1e-8 */
    int max_intervals;  /* subdivision budget per 1D level; 0 = 400 */
    double theta_max;   /* integrate polar angle theta in [0, theta_max] about `pole`; 0 = pi
                         * (whole sphere); pi/2 = the hemisphere around the pole */
} sol_quad_options;

/* Adaptive nested Gauss-Kronrod (7/15 points) over the sphere in polar coordinates about `pole`
 * (a unit vector; put it on the integrand's peak so sharp lobes are resolved). Both the theta and
 * phi integrals subdivide the interval with the largest error estimate until the targets are met.
 * result: the integral; error (may be NULL): the estimated absolute error.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_ZERO_LENGTH (pole), SOL_ERR_NONFINITE (pole or a NaN
 * integrand value), SOL_ERR_NO_CONVERGENCE (budget exhausted; the estimate is still written). */
sol_status sol_sphere_integrate(sol_sphere_fn f, void *ctx, const double pole[3], const sol_quad_options *opts,
                                double *result, double *error);

/* Gauss-Legendre rule of order n (1..256) on [-1, 1]: nodes x (descending) and weights w, by Newton's
 * iteration on P_n. Exact for polynomials of degree 2n - 1. Errors: SOL_ERR_NULL_ARG,
 * SOL_ERR_INVALID_ARG (n outside 1..256). */
sol_status sol_gauss_legendre(int n, double *x, double *w);

/* Stratified Monte Carlo over the whole sphere: `strata` x `strata` cells of the equal-area
 * cylinder map, one jittered sample each (deterministic for a given seed). error: the standard
 * error estimated from the spread between cells (may be NULL). Errors: SOL_ERR_NULL_ARG,
 * SOL_ERR_INVALID_ARG (strata < 2), SOL_ERR_NONFINITE (a NaN integrand value). */
sol_status sol_sphere_integrate_mc(sol_sphere_fn f, void *ctx, int strata, uint64_t seed, double *result,
                                   double *error);

/* ======================= Spherical Gaussians (spherical_gaussian.c) ======================= */

/* G(v) = amplitude * exp(sharpness * (axis.v - 1)) (Wang et al. 2009). The value is in [0,
 * amplitude] for every sharpness >= 0 (no exp overflow: the exponent is never positive); with
 * sharpness = +Inf it is the amplitude on the axis and 0 elsewhere. A negative sharpness (outside
 * the domain) can overflow; the value then saturates at +-DBL_MAX. */
typedef struct sol_sg {
    double axis[3];   /* unit vector */
    double sharpness; /* lambda >= 0 */
    double amplitude; /* a */
} sol_sg;

double sol_sg_eval(const sol_sg *g, const double v[3]);
/* Integral over the sphere: 2 pi a (1 - exp(-2 lambda)) / lambda, via expm1; 4 pi a at lambda = 0. */
double sol_sg_integral(const sol_sg *g);
/* Product of two SGs is an SG (exact): axis along lambda1 mu1 + lambda2 mu2, sharpness its length,
 * amplitude a1 a2 exp(lambda_m - lambda1 - lambda2) with the exponent formed without cancellation.
 * When the two axes cancel exactly (lambda_m = 0) the axis is set to mu1. */
sol_sg sol_sg_product(const sol_sg *a, const sol_sg *b);
/* Integral of the product of two SGs over the sphere (exact; the "convolution" of a BRDF lobe
 * with a lighting lobe at one pixel, claim D16). Computed in log space: finite for any sharpness. */
double sol_sg_inner_product(const sol_sg *a, const sol_sg *b);
/* Spherical convolution of lighting SG `a` with a kernel SG `b` whose axis is taken as the pole
 * (Wang et al. 2009, sec. 4): approximately an SG with a's axis, sharpness l1 l2/(l1 + l2) and
 * amplitude 2 pi a1 a2 /(l1 + l2) (variances add, integral = product of integrals; exact in the
 * narrow-lobe limit). */
sol_sg sol_sg_convolve(const sol_sg *a, const sol_sg *b);
/* Clamped-cosine convolution: integral of G(w) max(n.w, 0) over the sphere (irradiance from an
 * SG light). Exact up to a 1D Gauss-Legendre integral (the azimuthal integral is closed-form),
 * error below 1e-6 of the SG's integral for sharpness 0..1e6 (tested), at any axis-normal angle. `n` unit. */
double sol_sg_cosine_convolve(const sol_sg *g, const double n[3]);
/* Rotation: axis <- R axis, with R a row-major 3x3 rotation matrix. */
sol_sg sol_sg_rotate(const sol_sg *g, const double rotation[9]);

/* Anisotropic SG (Xu et al. 2013): c max(v.z, 0) exp(-lx (v.x)^2 - ly (v.y)^2) in the frame (x,y,z). */
typedef struct sol_asg {
    double x[3], y[3], z[3];
    double lambda_x, lambda_y; /* >= 0 */
    double amplitude;
} sol_asg;
double sol_asg_eval(const sol_asg *g, const double v[3]);

/* ======================= least squares through Ceres (ceres_fit.cpp) ======================= */

/* A bounded nonlinear least-squares problem given by a C callback: minimise
 * 1/2 sum_i r_i(p)^2 over p in [lower, upper]. The callback writes the n_residuals residuals and,
 * when `jacobian` is not NULL, the n_residuals x n_params Jacobian (row-major); it returns 0 on
 * success and non-zero when p is outside its domain. */
typedef int (*sol_lsq_residual_fn)(void *ctx, const double *params, double *residuals, double *jacobian);

/* Linear solver of each Levenberg-Marquardt step. */
typedef enum sol_lsq_linear_solver {
    SOL_LSQ_DENSE_NORMAL_CHOLESKY = 0, /* Cholesky of J^T J: the default, ~4x cheaper than QR */
    SOL_LSQ_DENSE_QR                   /* QR of J: for ill-conditioned Jacobians */
} sol_lsq_linear_solver;

typedef struct sol_lsq_problem {
    int n_params, n_residuals;
    sol_lsq_residual_fn fn;
    void *ctx;
    const double *lower, *upper; /* n_params bounds each, or NULL for unbounded */
    int max_iterations;          /* 0 = 100 */
    int linear_solver;           /* a sol_lsq_linear_solver (an int: the C++ shim checks any value);
                                  * 0 = dense normal Cholesky */
} sol_lsq_problem;

typedef struct sol_lsq_summary {
    double initial_cost, final_cost; /* 1/2 sum r^2 */
    int iterations;
    int converged;                   /* Ceres reported convergence (not just the iteration limit) */
    double solve_seconds;
} sol_lsq_summary;

/* Solves with Ceres (Levenberg-Marquardt, dense normal Cholesky or QR, one thread, silent). `params` holds the start
 * point and receives the solution on SOL_OK; `summary` may be NULL. Deterministic.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (sizes < 1, start outside bounds, unknown linear_solver),
 * SOL_ERR_NONFINITE (start point), SOL_ERR_SOLVER (Ceres failed or threw; params untouched). */
sol_status sol_lsq_solve(const sol_lsq_problem *problem, double *params, sol_lsq_summary *summary);

/* ======================= Ward NDF -> SG fit (sg_fit.c, claim D15) ======================= */

typedef struct sol_sg_fit_options {
    int radial_samples;  /* fit samples along the radius of the Ward slope disk; 0 = 20 */
    int angular_samples; /* fit samples in azimuth; 0 = 24, times ceil(sqrt(max/min alpha)) */
    int eval_radial;     /* error evaluation quadrature (finer than the fit); 0 = 64 */
    int eval_angular;    /* 0 = 96 */
    int max_iterations;  /* Ceres iterations per fit; 0 = 200 */
    int extra_starts;    /* multi-start check of the last fit (K = k_max >= 2 only): starts beyond the
                          * four greedy ones, see sol_ward_sg_fit; 0 = none */
    sol_lsq_linear_solver linear_solver; /* passed to sol_lsq_solve; 0 = dense normal Cholesky */
} sol_sg_fit_options;

typedef struct sol_sg_fit_error {
    double rel_l2;      /* ||S - D|| / ||D|| in L2 over the hemisphere */
    double max_rel;     /* max |S - D| / max D over the evaluation nodes */
    double energy;      /* integral of S (n.h) over the hemisphere minus 1 (that of D) */
} sol_sg_fit_error;

/* Fits K = 1..k_max isotropic SG lobes to the Ward NDF (alpha_x, alpha_y) in the shading frame by
 * minimising the relative L2 error on the fit nodes (analytic Jacobian, Ceres through
 * sol_lsq_solve). Greedy: fit K starts from fit K-1 plus one lobe at the largest residual, tried
 * at three widths, and from fit K-1 with its widest lobe split in two; the start whose Ceres
 * result has the smallest error on the (finer) evaluation nodes wins, and fit K-1 padded with a
 * zero lobe is kept when none beats it, so the error never rises with K. With extra_starts = S > 0
 * the last fit (K = k_max) also tries S more starts, the best is kept: the first three put the K
 * lobes on a line along the long axis (spread 1, 1.5, 2 x the long roughness, sharpness of the
 * short axis), then fresh random starts (axes drawn from the target, SplitMix64, fixed seed)
 * alternate with basin hops (the best fit so far with every lobe moved by up to its width). Bounds: sharpness in
 * [0.01, min(1e6, 8 / min(alpha)^2)] (sharper lobes would fall between fit nodes), amplitude in
 * [0, 1e3] x the NDF's peak scale, axis in the upper hemisphere; every start is clamped into these
 * bounds, so the whole documented alpha range [1e-3, 10] fits for every k_max.
 * lobes: k_max * (k_max + 1) / 2 entries, fit K at offset K (K - 1) / 2; errors, summaries: k_max
 * entries each (summaries may be NULL; costs are those of the chosen start, iterations and
 * solve_seconds are summed over the four starts). Amplitudes are in the NDF's units.
 * Deterministic. Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (alpha outside [1e-3, 10], k_max
 * outside 1..16, radial node counts above 256, azimuthal above 4096, extra_starts outside 0..1024,
 * an unknown linear_solver), SOL_ERR_NONFINITE (NaN
 * alpha), SOL_ERR_NO_MEMORY, SOL_ERR_SOLVER (outputs untouched). */
sol_status sol_ward_sg_fit(double alpha_x, double alpha_y, int k_max, const sol_sg_fit_options *opts, sol_sg *lobes,
                           sol_sg_fit_error *errors, sol_lsq_summary *summaries);
/* The same error measures for any SG sum (e.g. a hand-made one). */
sol_status sol_ward_sg_error(double alpha_x, double alpha_y, const sol_sg *lobes, int k,
                             const sol_sg_fit_options *opts, sol_sg_fit_error *error);
/* One ASG lobe (Xu et al. 2013) fitted to the same NDF (frame = shading frame; lambda_x, lambda_y,
 * amplitude fitted), with its error. Same errors as sol_ward_sg_fit. */
sol_status sol_ward_asg_fit(double alpha_x, double alpha_y, const sol_sg_fit_options *opts, sol_asg *lobe,
                            sol_sg_fit_error *error, sol_lsq_summary *summary);

/* ======================= principal Phong lobe extraction (lobe_extraction.c, D16) ======================= */

/* Warps an NDF lobe over half vectors into a lobe over light directions for view v (Wang et al.
 * 2009, spherical warping): axis reflect(v, mu), sharpness lambda / (4 |mu.v|), amplitude kept.
 * Lobes whose axis faces away from v (mu.v <= 0) get amplitude 0. */
sol_sg sol_sg_warp_ndf_lobe(const sol_sg *ndf_lobe, const double v[3]);

typedef struct sol_phong_lobe {
    double normal[3];  /* the normal to store in the G-buffer */
    double glossiness; /* Phong exponent for reflect(v, normal) */
    double energy;     /* sum of the BRDF-lobe x light-lobe products (lighting-weighted energy) */
    /* Energy-preserving alternative to `glossiness`: the exponent g whose lobe-normalised Phong lobe
     * (g + 1) / (2 pi) (r.l)^g has the same peak as the weighted mixture of the warped lobes, each
     * normalised to unit integral, evaluated at the mixture's mean axis: g = 2 pi peak - 1 (>= 0).
     * For one lobe of warped sharpness lambda it is lambda / (1 - exp(-2 lambda)) - 1 (the variance
     * match gives lambda); for lobes spread apart the mean axis falls between them and it is lower. */
    double glossiness_energy;
    /* Work counters, counted as the extraction runs (claim D16's cost is checked on these, not on
     * timings): SG warps evaluated (one per BRDF lobe) and BRDF-lobe x light-lobe inner products
     * evaluated (n_brdf * n_light: the O(n*m) loop). */
    int warps;
    int products;
} sol_phong_lobe;

/* Extracts the principal Phong lobe of an SG NDF (n_brdf lobes over half vectors, world frame)
 * under SG lighting (n_light lobes) for view v: each NDF lobe is warped to light space and
 * convolved (sol_sg_inner_product) with each light lobe, O(n_brdf * n_light). The products weight
 * the NDF lobe axes (-> normal); the glossiness matches the angular variance of the weighted
 * mixture of warped lobes (each lobe's 2 / lambda plus the spread of their axes), g = 2 / variance;
 * glossiness_energy matches the mixture's peak at the same energy instead (see sol_phong_lobe).
 * With no light reaching any lobe, the lobes' own energies are the weights. `warps` and `products`
 * count the warps and inner products evaluated (n_brdf and n_brdf * n_light on success).
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_INVALID_ARG (counts < 1, n_brdf > 64), SOL_ERR_ZERO_LENGTH
 * (weighted normal vanishes or all lobes face away from v), SOL_ERR_NONFINITE. */
sol_status sol_extract_phong_lobe(const sol_sg *brdf, int n_brdf, const sol_sg *light, int n_light,
                                  const double v[3], sol_phong_lobe *out);

/* Keeps at most `keep` lighting lobes for a surface with normal n ("cut down to ~7 by
 * hemisphere"): drops lobes whose clamped-cosine convolution with n is below 1e-6 of the
 * largest, then keeps the `keep` largest by that convolution (ties by index). Writes the kept
 * lobes in input order to `out` and their count to *n_out. Errors: SOL_ERR_NULL_ARG,
 * SOL_ERR_INVALID_ARG (n_light < 0, keep < 1). */
sol_status sol_cull_light_lobes(const sol_sg *light, int n_light, const double n[3], int keep, sol_sg *out,
                                int *n_out);

#ifdef __cplusplus
}
#endif
#endif
