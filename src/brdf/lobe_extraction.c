/* lobe_extraction.c - principal Phong lobe of an SG NDF under SG lighting, and the hemisphere cut of
 * the lighting lobes (claim D16; the talk's "Anisotropic deferred materials, part II"). */
#include <math.h>
#include <stdlib.h>

#include "sol_brdf.h"

/* Wang et al. 2009 sec. 5.1: near its axis an NDF lobe over h maps to a lobe over l = reflect(v, h)
 * whose width grows by the Jacobian dh/dl = 1 / (4 |h.v|). */
sol_sg sol_sg_warp_ndf_lobe(const sol_sg *ndf_lobe, const double v[3])
{
    sol_sg w = *ndf_lobe;
    double c = sol_dot3(ndf_lobe->axis, v);
    sol_reflect(v, ndf_lobe->axis, w.axis);
    if (!(c > 0.0)) {
        w.amplitude = isnan(c) ? NAN : 0.0;
        w.sharpness = 0.0;
        return w;
    }
    w.sharpness = ndf_lobe->sharpness / (4.0 * c);
    return w;
}

static int finite_sg(const sol_sg *g)
{
    return isfinite(g->axis[0]) && isfinite(g->axis[1]) && isfinite(g->axis[2]) && isfinite(g->sharpness) &&
           isfinite(g->amplitude);
}

sol_status sol_extract_phong_lobe(const sol_sg *brdf, int n_brdf, const sol_sg *light, int n_light,
                                  const double v[3], sol_phong_lobe *out)
{
    if (!brdf || !light || !v || !out)
        return SOL_ERR_NULL_ARG;
    if (n_brdf < 1 || n_light < 1)
        return SOL_ERR_INVALID_ARG;
    if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
        return SOL_ERR_NONFINITE;
    for (int i = 0; i < n_light; ++i)
        if (!finite_sg(&light[i]))
            return SOL_ERR_NONFINITE;
    /* Weights: the light each warped lobe receives (the O(n*m) loop of the talk), or, when no light
     * reaches any lobe, the lobes' own energies. */
    double weight[64], energy[64], lit = 0.0, own = 0.0;
    int warps = 0, products = 0; /* work counters (D16's cost, counted rather than timed) */
    sol_sg warped[64];
    if (n_brdf > 64)
        return SOL_ERR_INVALID_ARG;
    for (int i = 0; i < n_brdf; ++i) {
        if (!finite_sg(&brdf[i]))
            return SOL_ERR_NONFINITE;
        warped[i] = sol_sg_warp_ndf_lobe(&brdf[i], v);
        ++warps;
        weight[i] = 0.0;
        for (int j = 0; j < n_light; ++j, ++products)
            weight[i] += sol_sg_inner_product(&warped[i], &light[j]);
        energy[i] = sol_sg_integral(&warped[i]);
        lit += weight[i];
        own += energy[i];
    }
    const double *w = lit > 0.0 ? weight : energy;
    double total = lit > 0.0 ? lit : own;
    if (!(total > 0.0))
        return SOL_ERR_ZERO_LENGTH;
    /* Normal: weighted mean of the NDF lobe axes. Glossiness by matching the angular variance of the
     * weighted mixture of warped lobes, E[theta^2] = 2 / lambda for an SG (small-angle): each lobe's own
     * 2 / lambda_i plus the spread of the lobe axes about their mean, 2 (1 - |mean resultant|). */
    double normal[3] = {0, 0, 0}, mean_r[3] = {0, 0, 0}, var = 0.0;
    for (int i = 0; i < n_brdf; ++i) {
        for (int k = 0; k < 3; ++k) {
            normal[k] += w[i] * brdf[i].axis[k];
            mean_r[k] += w[i] * warped[i].axis[k];
        }
        if (w[i] > 0.0)
            var += w[i] * (warped[i].sharpness > 0.0 ? 2.0 / warped[i].sharpness : 4.0);
    }
    double len = sqrt(sol_dot3(normal, normal));
    if (!(len > 0.0))
        return SOL_ERR_ZERO_LENGTH;
    double resultant = sqrt(sol_dot3(mean_r, mean_r)) / total;
    var = var / total + 2.0 * (1.0 - (resultant < 1.0 ? resultant : 1.0));
    if (!isfinite(len) || !isfinite(var) || !(var > 0.0))
        return SOL_ERR_NONFINITE;
    /* Peak of the mixture of unit-integral lobes at its mean axis (the mean of the warped axes, or
     * the reflection about the normal when they cancel). */
    double r_mean[3], rl = sqrt(sol_dot3(mean_r, mean_r)), peak = 0.0;
    if (rl > 0.0) {
        for (int k = 0; k < 3; ++k)
            r_mean[k] = mean_r[k] / rl;
    } else {
        double nn[3] = {normal[0] / len, normal[1] / len, normal[2] / len};
        sol_reflect(v, nn, r_mean);
    }
    for (int i = 0; i < n_brdf; ++i)
        if (w[i] > 0.0) {
            double e = sol_sg_integral(&warped[i]);
            if (e > 0.0)
                peak += w[i] / total * sol_sg_eval(&warped[i], r_mean) / e;
        }
    double g_energy = 2.0 * M_PI * peak - 1.0;
    if (!isfinite(g_energy))
        return SOL_ERR_NONFINITE;
    for (int k = 0; k < 3; ++k)
        out->normal[k] = normal[k] / len;
    out->glossiness = 2.0 / var;
    out->energy = total;
    out->glossiness_energy = g_energy > 0.0 ? g_energy : 0.0;
    out->warps = warps;
    out->products = products;
    return SOL_OK;
}

typedef struct scored_lobe {
    double score;
    int index;
} scored_lobe;

static int by_score_desc(const void *a, const void *b)
{
    const scored_lobe *x = a, *y = b;
    if (x->score != y->score)
        return x->score < y->score ? 1 : -1;
    return x->index - y->index;
}

static int by_index(const void *a, const void *b)
{
    return ((const scored_lobe *)a)->index - ((const scored_lobe *)b)->index;
}

sol_status sol_cull_light_lobes(const sol_sg *light, int n_light, const double n[3], int keep, sol_sg *out,
                                int *n_out)
{
    if (!light || !n || !out || !n_out)
        return SOL_ERR_NULL_ARG;
    if (n_light < 0 || keep < 1)
        return SOL_ERR_INVALID_ARG;
    if (n_light == 0) {
        *n_out = 0;
        return SOL_OK;
    }
    scored_lobe *s = malloc((size_t)n_light * sizeof *s);
    if (!s)
        return SOL_ERR_NO_MEMORY;
    double best = 0.0;
    for (int i = 0; i < n_light; ++i) {
        s[i].score = sol_sg_cosine_convolve(&light[i], n);
        s[i].index = i;
        if (isnan(s[i].score)) {
            free(s);
            return SOL_ERR_NONFINITE;
        }
        best = s[i].score > best ? s[i].score : best;
    }
    qsort(s, (size_t)n_light, sizeof *s, by_score_desc);
    int m = 0;
    while (m < n_light && m < keep && s[m].score > 1e-6 * best)
        ++m;
    qsort(s, (size_t)m, sizeof *s, by_index);
    for (int i = 0; i < m; ++i)
        out[i] = light[s[i].index];
    *n_out = m;
    free(s);
    return SOL_OK;
}
