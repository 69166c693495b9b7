/* bc5.c - 3Dc (BC5) blocks: decoding with z rebuilt, the angular error of a block (T10), joint
 * index choice, and the exact joint anchor search by branch and bound (T10/T11). */
#include "bc5_search.h"

#include <stdlib.h>
#include <float.h>
#include <string.h>

int sol_nm_simd_disable;

/* The palette of the pair PREFETCH_AHEAD places further down a list, asked for ahead of its use: the
 * lists' pairs (sorted by score) are spread over the 4 MB palette table, and the set-up's passes over
 * them (value_set_init, usable_filter, merge_stored) waited on those loads (issue 13's profile). A
 * hint only: no result depends on it. */
enum { PREFETCH_AHEAD = 8 };
#define PREFETCH_PAIR(pal, list, i, count)                                                                   \
    do {                                                                                                     \
        if ((i) + PREFETCH_AHEAD < (count))                                                                  \
            __builtin_prefetch((pal)[(list)[(i) + PREFETCH_AHEAD].pair]);                                     \
    } while (0)

sol_status sol_nm_unit_normals(const double in[16][3], double out[16][3])
{
    for (int p = 0; p < 16; ++p) {
        if (!isfinite(in[p][0]) || !isfinite(in[p][1]) || !isfinite(in[p][2]))
            return SOL_ERR_NONFINITE;
        double len = sqrt(in[p][0] * in[p][0] + in[p][1] * in[p][1] + in[p][2] * in[p][2]);
        if (!(len > 1e-150 && len < 1e150)) { /* the squares under- or overflowed: scale first */
            double m = fmax(fmax(fabs(in[p][0]), fabs(in[p][1])), fabs(in[p][2]));
            if (!(m > 0.0))
                return SOL_ERR_ZERO_LENGTH;
            double s[3] = {in[p][0] / m, in[p][1] / m, in[p][2] / m};
            len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            for (int c = 0; c < 3; ++c)
                out[p][c] = s[c] / len;
            continue;
        }
        for (int c = 0; c < 3; ++c)
            out[p][c] = in[p][c] / len;
    }
    return SOL_OK;
}





/* The index pair (i, j) of palettes a, b whose decoded normal is closest in angle to n.
 * Candidates are compared by the cosine of their angle. A candidate with x^2 + y^2 <= 1 decodes to
 * a unit vector whose chord to n satisfies chord^2 >= (a-nx)^2 + (b-ny)^2; one with z clamped has
 * chord^2 >= nz^2; either bound above the best chord^2 so far skips the candidate.
 * The choice (the reference order): the per-channel nearest pair (i0, j0) first (the first entry of
 * least squared distance in each palette), then every pair (i, j) in i-major order, a pair replacing
 * the best only with a strictly larger cosine. The skip tests only ever get stricter as the best
 * chord^2 shrinks, so when nz^2 is above the seed's chord^2 (no clamped decode can ever be tried) the
 * rows i and columns j whose own distance da_i or db_j already fails against the seed are skipped
 * outright: the pairs visited are those of the reference walk that are not skipped, in its order,
 * and the seed is not re-tried (its cosine cannot be strictly larger than itself); so the choice is
 * the reference walk's, bit for bit, and on smooth pixels it costs the seed and a few neighbours
 * instead of 64 pairs. */
#if SEARCH_AVX2
/* sol_nm_bc5_best_pixel_index's per-channel squared distances d[k] = (p[k] - t)^2 (the same operations) and the
 * first index of their least (the scalar loop's strict comparisons keep the first). */
static inline AVX2_FN int channel_distances_avx2(const double p[8], double t, double d[8])
{
    __m256d tt = _mm256_set1_pd(t), u = _mm256_sub_pd(_mm256_loadu_pd(p), tt), v = _mm256_sub_pd(_mm256_loadu_pd(p + 4), tt);
    u = _mm256_mul_pd(u, u);
    v = _mm256_mul_pd(v, v);
    _mm256_storeu_pd(d, u);
    _mm256_storeu_pd(d + 4, v);
    __m256d m = _mm256_min_pd(u, v);
    m = _mm256_min_pd(m, _mm256_permute4x64_pd(m, 0x4e));
    m = _mm256_min_pd(m, _mm256_permute_pd(m, 5)); /* the least in every lane */
    unsigned eq = (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(u, m, _CMP_EQ_OQ)) |
                  (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(v, m, _CMP_EQ_OQ)) << 4;
    return __builtin_ctz(eq);
}

/* Bit k set where d[k] * keep <= c (the same product and comparison as the scalar loop). */
static inline AVX2_FN unsigned within_mask_avx2(const double d[8], double keep, double c)
{
    __m256d kk = _mm256_set1_pd(keep), cc = _mm256_set1_pd(c);
    __m256d u = _mm256_mul_pd(_mm256_loadu_pd(d), kk), v = _mm256_mul_pd(_mm256_loadu_pd(d + 4), kk);
    return (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(u, cc, _CMP_LE_OQ)) |
           (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(v, cc, _CMP_LE_OQ)) << 4;
}
#endif

/* sol_nm_bc5_best_pixel_index's walk; avx2: the distances and masks by the AVX2 helpers (same values). */
static inline __attribute__((always_inline)) void best_pixel_index_body(const double a[8], const double b[8],
                                                                        const double n[3], int *bi, int *bj, int avx2)
{
    const double keep = 1.0 - BOUND_SLACK;
    double da[8], db[8];
    int i0 = 0, j0 = 0;
    (void)avx2;
#if SEARCH_AVX2
    if (avx2) {
        i0 = channel_distances_avx2(a, n[0], da);
        j0 = channel_distances_avx2(b, n[1], db);
    } else
#endif
        for (int k = 0; k < 8; ++k) {
            da[k] = (a[k] - n[0]) * (a[k] - n[0]);
            db[k] = (b[k] - n[1]) * (b[k] - n[1]);
            i0 = da[k] < da[i0] ? k : i0;
            j0 = db[k] < db[j0] ? k : j0;
        }
    double nz2 = n[2] * n[2];
    /* the seed: the reference walk's first pair, tried against no incumbent (every skip test fails) */
    int best_i = -1, best_j = -1;
    double best_cos = -INFINITY, best_chord2 = INFINITY;
    {
        double r2 = a[i0] * a[i0] + b[j0] * b[j0], dot = a[i0] * n[0] + b[j0] * n[1];
        double cosine = r2 <= 1.0 ? dot + sqrt(1.0 - r2) * n[2] : dot / sqrt(r2);
        if (cosine > best_cos) {
            best_cos = cosine;
            best_chord2 = 2.0 - 2.0 * cosine;
            best_i = i0;
            best_j = j0;
        }
    }
    unsigned rows = 0xff, cols = 0xff;
    int tight = nz2 * keep > best_chord2; /* clamped decodes are skipped from here on */
    if (tight) {
        rows = cols = 0;
#if SEARCH_AVX2
        if (avx2) {
            rows = within_mask_avx2(da, keep, best_chord2);
            cols = within_mask_avx2(db, keep, best_chord2);
        } else
#endif
            for (int k = 0; k < 8; ++k) {
                rows |= (unsigned)(da[k] * keep <= best_chord2) << k;
                cols |= (unsigned)(db[k] * keep <= best_chord2) << k;
            }
        if (rows == 1u << i0 && cols == 1u << j0) { /* only the seed is left */
            *bi = best_i;
            *bj = best_j;
            return;
        }
    }
    for (unsigned rm = rows; rm; rm &= rm - 1) { /* the set bits in increasing order */
        int i = __builtin_ctz(rm);
        if (da[i] * keep > best_chord2 && nz2 * keep > best_chord2)
            continue;
        for (unsigned cm = cols; cm; cm &= cm - 1) {
            int j = __builtin_ctz(cm);
            if (tight && i == i0 && j == j0)
                continue;
            double r2 = a[i] * a[i] + b[j] * b[j], dot = a[i] * n[0] + b[j] * n[1], cosine;
            if (r2 <= 1.0) {
                if ((da[i] + db[j]) * keep > best_chord2)
                    continue;
                if (n[2] <= 0.0 && dot <= best_cos)
                    continue; /* the z term adds <= 0 (rounding is monotone) */
                cosine = dot + sqrt(1.0 - r2) * n[2];
            } else {
                if (nz2 * keep > best_chord2)
                    continue;
                /* cosine = dot / r with r > 1: no better than best_cos >= 0 if dot <= 0 or
                 * dot^2 < best_cos^2 r^2 (with a margin for the rounding of the division) */
                if (best_cos >= 0.0 && (dot <= 0.0 || dot * dot < best_cos * best_cos * r2 * (1.0 - 1e-12)))
                    continue;
                cosine = dot / sqrt(r2);
            }
            if (cosine > best_cos) {
                best_cos = cosine;
                best_chord2 = 2.0 - 2.0 * cosine;
                best_i = i;
                best_j = j;
            }
        }
    }
    *bi = best_i;
    *bj = best_j;
}

#if SEARCH_AVX2
static AVX2_FN void best_pixel_index_avx2(const double a[8], const double b[8], const double n[3], int *bi, int *bj)
{
    best_pixel_index_body(a, b, n, bi, bj, 1);
}
#endif

void sol_nm_bc5_best_pixel_index(const double a[8], const double b[8], const double n[3], int *bi, int *bj) {
#if SEARCH_AVX2
    if (search_avx2()) {
        best_pixel_index_avx2(a, b, n, bi, bj);
        return;
    }
#endif
    best_pixel_index_body(a, b, n, bi, bj, 0);
}

/* The angle (radians) of sol_nm_bc5_best_pixel_index's choice. */
double sol_nm_bc5_best_pixel(const double a[8], const double b[8], const double n[3], int *bi, int *bj) {
    sol_nm_bc5_best_pixel_index(a, b, n, bi, bj);
    return decoded_angle(a[*bi], b[*bj], n);
}

/* Block objective for palettes a, b (decoded units): sum dN^2 or max dN^2 over pixels with joint
 * index choice. Stops and returns a value >= budget once the partial value reaches it. */
double sol_nm_bc5_joint_objective(const double a[8], const double b[8], const double n[16][3], int use_max,
                                  double budget, uint8_t *ix, uint8_t *iy) {
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        int i, j;
        double e = sol_nm_bc5_best_pixel(a, b, n[p], &i, &j);
        s = fold_term(s, e * e, use_max);
        if (ix) {
            ix[p] = (uint8_t)i;
            iy[p] = (uint8_t)j;
        }
        if (s >= budget)
            return s;
    }
    return s;
}

/* A lower bound of the joint objective with the pixels visited in `order` (worst first, so that
 * hopeless candidates stop early): each pixel's jointly best index pair (the same choice as
 * sol_nm_bc5_best_pixel), its dN^2 bounded below by angle2_lower_bound. The search rejects a candidate when
 * this reaches the incumbent and re-evaluates survivors exactly with sol_nm_bc5_joint_objective. */
double sol_nm_bc5_joint_objective_lower(const double a[8], const double b[8], const double n[16][3],
                                        const int order[16], const double away_off[16], int use_max, double best,
                                        double budget, uint64_t *work) {
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        *work += 32;
        int i, j;
        const double *np = n[order[k]];
        sol_nm_bc5_best_pixel_index(a, b, np, &i, &j);
        double e2 = angle2_lower_bound(a[i], b[j], np);
        e2 = e2 > away_off[k] ? e2 : away_off[k]; /* the hemisphere bound theta0^2 */
        if (use_max && e2 < budget && e2 >= best * (1.0 - 1e-5)) {
            /* max metric, a pixel within the bounds' slack of the incumbent: its exact angle is the
             * one sol_nm_bc5_joint_objective would compute (same index pair, same function), and the max of the
             * block is at least it; so a pixel at or above the incumbent rejects the candidate
             * exactly (it cannot be strictly better), which decides exact ties of the worst pixel */
            double e = decoded_angle(a[i], b[j], np);
            if (e * e >= best)
                return budget;
        }
        s = fold_term(s, e2, use_max);
        if (s >= budget)
            return s;
    }
    return s;
}

/* ---- pixels of bit-identical normals (issue 13) ----
 *
 * A source of 8 bits per component quantises smooth maps into blocks whose pixels repeat the same
 * normal (hood 256^2 from 8 bits: most blocks hold 2-4 distinct normals). A pixel's term depends only
 * on its normal and the candidate, so the grouped forms compute one term per group (group[p]: the
 * first pixel with a bit-identical normal, group[p] <= p) and fold it at every pixel in the plain
 * forms' order: the same sums, rounding included, the same early stops and the same work counted.
 * hood 256^2 8-bit, optimal: 8.34 G -> 5.80 G instructions (callgrind). */
double sol_nm_bc5_joint_objective_grouped(const double a[8], const double b[8], const double n[16][3],
                                          const int group[16], int use_max, double budget)
{
    double term[16], s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double t;
        if (group[p] != p) {
            t = term[group[p]]; /* group[p] < p: folded already */
        } else {
            int i, j;
            double e = sol_nm_bc5_best_pixel(a, b, n[p], &i, &j);
            t = term[p] = e * e;
        }
        s = fold_term(s, t, use_max);
        if (s >= budget)
            return s;
    }
    return s;
}

/* sol_nm_bc5_joint_objective_lower with one bound per group: pixels are visited in `order`, so a
 * group's first visit computes its bound (before the hemisphere floor, which is the same for equal
 * normals) and later visits reuse it. The max metric's exact check depends on the term only, so a
 * group that passed it once passes it at every visit. */
double sol_nm_bc5_joint_objective_lower_grouped(const double a[8], const double b[8], const double n[16][3],
                                                const int group[16], const int order[16],
                                                const double away_off[16], int use_max, double best, double budget,
                                                uint64_t *work)
{
    double bound[16], s = 0.0;
    unsigned have = 0;
    for (int k = 0; k < 16; ++k) {
        *work += 32;
        const int g = group[order[k]];
        double e2;
        if ((have >> g) & 1) {
            e2 = bound[g];
        } else {
            int i, j;
            const double *np = n[order[k]];
            sol_nm_bc5_best_pixel_index(a, b, np, &i, &j);
            e2 = angle2_lower_bound(a[i], b[j], np);
            const double floored = e2 > away_off[k] ? e2 : away_off[k];
            if (use_max && floored < budget && floored >= best * (1.0 - 1e-5)) {
                double e = decoded_angle(a[i], b[j], np); /* as sol_nm_bc5_joint_objective_lower */
                if (e * e >= best)
                    return budget;
            }
            bound[g] = e2;
            have |= 1u << g;
        }
        e2 = e2 > away_off[k] ? e2 : away_off[k]; /* the hemisphere bound theta0^2 */
        s = fold_term(s, e2, use_max);
        if (s >= budget)
            return s;
    }
    return s;
}

static void away_info_init(away_info *aw, const double n[16][3], unsigned loose)
{
    aw->mask = 0;
    for (int p = 0; p < 16; ++p) {
        aw->m[0][p] = n[p][0];
        aw->m[1][p] = n[p][1];
        aw->w[p] = 0.0;
        aw->off[p] = 0.0;
        if (!((loose >> p) & 1) || !(n[p][2] < 0.0))
            continue;
        double rho = hypot(n[p][0], n[p][1]), h = -n[p][2], theta0 = atan2(h, rho);
        aw->mask |= 1u << p;
        if (rho > 0.0) {
            aw->m[0][p] = n[p][0] / rho;
            aw->m[1][p] = n[p][1] / rho;
        }
        aw->w[p] = theta0 * rho / h * (1.0 - 1e-12);
        aw->off[p] = theta0 * theta0 * (1.0 - 1e-12);
    }
}


/* The nearest-entry part of a channel side: for each target t[k], the first nearest entry's value v
 * (strict comparisons in palette order), its squared distance m1 and the least squared distance m2
 * of an entry of another value. */
/* s's nearest-entry fields for targets t (in visiting order), by the AVX2 form where it runs. */
void sol_nm_bc5_channel_side_fill(const double pal[8], const double t[16], channel_side *s) {
#if SEARCH_AVX2
    if (search_avx2()) {
        sol_nm_channel_side_avx2(pal, t, s->v, s->m1, s->m2, 1);
        return;
    }
#endif
    sol_nm_channel_side_scalar(pal, t, s->v, s->m1, s->m2, 1);
}

/* Fills s for palette pal against component c (0 = x, 1 = y) of the pixels n[order[k]]. */
void sol_nm_bc5_channel_side_init(const double pal[8], const double n[16][3], const int order[16], int c,
                                  const away_info *aw, channel_side *s) {
    double t[16];
    for (int k = 0; k < 16; ++k) {
        int p = order[k];
        s->lt[k] = (aw->mask >> p) & 1 ? aw->w[p] * sol_nm_loose_term(pal, aw->m[c][p]) : 0.0;
        t[k] = n[p][c];
    }
    sol_nm_bc5_channel_side_fill(pal, t, s);
}

/* The quick lower bound of the joint objective (pixels in `order`, stops once it reaches budget).
 * Each pixel's chord^2 bound c2 becomes a dN^2 bound c2 (1 - 3e-6) - 5e-15 <= (c (1 - 1e-6) - 1e-15)^2,
 * the rounding allowance of angle2_lower_bound; the chord of (v_x, v_y) is computed with the decoder's
 * z = sqrt(1 - a^2 - b^2). */
/* The quick bound's term of the pixel at visiting position k (normal np): the least of the chord^2
 * bounds, lowered for rounding, and at least the pointing-away term (0 unless it points away). */
static inline double quick_term(const channel_side *xs, const channel_side *ys, const double np[3], int k,
                                double away_off_k)
{
    double a = xs->v[k], b = ys->v[k], nz2 = np[2] * np[2];
    double alt = xs->m2[k] + ys->m1[k], alt2 = xs->m1[k] + ys->m2[k];
    double lb = alt < alt2 ? alt : alt2;
    lb = nz2 < lb ? nz2 : lb;
    double zz = 1.0 - a * a - b * b, c2;
    if (zz > 0.0) {
        double dz = sqrt(zz) - np[2];
        c2 = xs->m1[k] + ys->m1[k] + dz * dz;
    } else {
        c2 = nz2; /* a clamped decode */
    }
    lb = c2 < lb ? c2 : lb;
    double e2 = lb * (1.0 - 3e-6) - 5e-15;
    double away = (away_off_k + xs->lt[k] + ys->lt[k]) * (1.0 - 1e-12); /* 0 unless pointing away */
    return e2 > away ? e2 : away;
}

#if SEARCH_AVX2

/* sol_nm_bc5_joint_objective_quick's per-pixel terms e2[k], 4 pixels at a time. */
AVX2_FN void sol_nm_bc5_quick_terms_avx2(const channel_side *xs, const channel_side *ys, const double nz[16],
                                         const double away_off[16], double e2[16]) {
    const __m256d away_lower = _mm256_set1_pd(1.0 - 1e-12);
    for (int k = 0; k < 16; k += 4) {
        __m256d e = quick_tight4(xs, ys, nz, k);
        __m256d away = _mm256_add_pd(_mm256_add_pd(_mm256_loadu_pd(away_off + k), _mm256_loadu_pd(xs->lt + k)),
                                     _mm256_loadu_pd(ys->lt + k));
        _mm256_storeu_pd(e2 + k, _mm256_max_pd(e, _mm256_mul_pd(away, away_lower)));
    }
}
#endif

/* nz[k] = n[order[k]][2] (set once per block by the caller: the AVX2 form's loads). */
double sol_nm_bc5_joint_objective_quick(const channel_side *xs, const channel_side *ys, const double n[16][3],
                                        const int order[16], const double nz[16], const double away_off[16],
                                        int use_max, double budget, uint64_t *work) {
#if SEARCH_AVX2
    if (search_avx2()) { /* every pixel's term at once, then the sum and the stop as below */
        double e2[16], s = 0.0;
        sol_nm_bc5_quick_terms_avx2(xs, ys, nz, away_off, e2);
        fold_terms_until(&s, e2, 16, use_max, budget, work);
        return s;
    }
#endif
    (void)nz;
    double s = 0.0;
    for (int k = 0; k < 16; ++k) {
        ++*work;
        s = fold_term(s, quick_term(xs, ys, n[order[k]], k, away_off[k]), use_max);
        if (s >= budget)
            return s;
    }
    return s;
}

/* The coupled bound of the pixels pointing away (bc5_away.c), between the quick bound and
 * sol_nm_bc5_joint_objective_lower: per pixel (in `order`) the quick bound's term (the same formula as
 * sol_nm_bc5_joint_objective_quick's), and for a pixel pointing away dN >= acos(cos_max), cos_max the largest
 * cosine of the 64 decodes to n: one decode must point close to n with both components at once (the
 * channel scores and the quick bound let x and y reach the rim direction separately). The cosine is
 * raised by 1e-14 absolute (its rounding, see bc5_away.c) and the angle lowered by 1e-12 relative
 * (acos's), so the bound stays below the angle sol_nm_bc5_joint_objective computes for the chosen decode.
 * Two passes, each stopping once the value reaches budget: first with the cheaper rim form of the
 * cosine (sol_nm_away_cosine_rim: the z term, <= 0, dropped; one division per decode, no roots),
 * which rejects nearly every candidate of the arcs pointing away, then with the full cosine (the
 * unclamped decodes' z counted) for the candidates left. Work: 1 per pixel as the quick bound, plus
 * 5 per pixel pointing away in the first pass (~25 ns, measured) and 16 in the second (~100 ns,
 * half of sol_nm_bc5_joint_objective_lower's per-pixel cost, measured on the survey's arcs pointing away). */
static double joint_objective_away(const double a[8], const double b[8], const channel_side *xs,
                                   const channel_side *ys, const double n[16][3], const int order[16],
                                   const double away_off[16], const away_info *aw, int use_max, double budget,
                                   uint64_t *work)
{
    double s = 0.0, e2s[16];
    for (int k = 0; k < 16; ++k) {
        ++*work;
        const int p = order[k];
        const double *np = n[p];
        double e2 = quick_term(xs, ys, np, k, away_off[k]);
        if ((aw->mask >> p) & 1) {
            *work += 5;
            double cosine = sol_nm_away_cosine_rim(a, b, np) + 1e-14;
            double angle = acos(cosine < 1.0 ? cosine : 1.0) * (1.0 - 1e-12);
            e2 = e2 > angle * angle ? e2 : angle * angle;
        }
        e2s[k] = e2;
        s = fold_term(s, e2, use_max);
        if (s >= budget)
            return s;
    }
    s = 0.0; /* second pass: the full cosines of the pixels pointing away */
    for (int k = 0; k < 16; ++k) {
        const int p = order[k];
        double e2 = e2s[k];
        if ((aw->mask >> p) & 1) {
            *work += 16;
            double cosine = sol_nm_away_cosine(a, b, n[p]) + 1e-14;
            double angle = acos(cosine < 1.0 ? cosine : 1.0) * (1.0 - 1e-12);
            e2 = e2 > angle * angle ? e2 : angle * angle;
        }
        s = fold_term(s, e2, use_max);
        if (s >= budget)
            return s;
    }
    return s;
}

static sol_status check_options(const sol_bc5_options *o)
{
    if ((unsigned)o->precision >= SOL_BC4_PRECISION_COUNT || (unsigned)o->metric > SOL_BC5_MAX ||
        (unsigned)o->encoder > SOL_BC5_FAST || !isfinite(o->threshold_deg) || o->threshold_deg < 0.0 ||
        (unsigned)o->base > SOL_BC5_BASE_FAST || !isfinite(o->gap))
        return SOL_ERR_INVALID_ARG;
    return SOL_OK;
}

uint64_t sol_nm_bc5_work_limit(const sol_bc5_options *o) {
    return o->work_limit ? o->work_limit : SOL_BC5_DEFAULT_WORK_LIMIT;
}

double sol_nm_bc5_metric_value(double internal, sol_bc5_metric metric) {
    return metric == SOL_BC5_MAX ? sqrt(internal) : internal;
}

sol_status sol_bc5_decode_block(const sol_bc5_block *block, sol_bc4_precision precision, double out[16][3])
{
    if (!block || !out)
        return SOL_ERR_NULL_ARG;
    double px[8], py[8];
    if (sol_bc4_palette(block->x.e0, block->x.e1, precision, px) != SOL_OK)
        return SOL_ERR_INVALID_ARG;
    sol_bc4_palette(block->y.e0, block->y.e1, precision, py);
    for (int p = 0; p < 16; ++p)
        if (block->x.index[p] > 7 || block->y.index[p] > 7)
            return SOL_ERR_INVALID_ARG;
    for (int p = 0; p < 16; ++p) {
        double a = 2.0 * px[block->x.index[p]] - 1.0, b = 2.0 * py[block->y.index[p]] - 1.0;
        out[p][0] = a;
        out[p][1] = b;
        out[p][2] = rebuild_z(a, b);
    }
    return SOL_OK;
}

sol_status sol_bc5_block_error(const sol_bc5_block *block, const double normals[16][3],
                               sol_bc4_precision precision, sol_bc5_metric metric, double *error)
{
    if (!block || !normals || !error)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)metric > SOL_BC5_MAX)
        return SOL_ERR_INVALID_ARG;
    double n[16][3], d[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    if ((st = sol_bc5_decode_block(block, precision, d)) != SOL_OK)
        return st;
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = sol_angle3(d[p], n[p]);
        s = metric == SOL_BC5_MAX ? (e * e > s ? e * e : s) : s + e * e;
    }
    *error = sol_nm_bc5_metric_value(s, metric);
    return SOL_OK;
}

sol_status sol_bc5_choose_indices(sol_bc5_block *block, const double normals[16][3], sol_bc4_precision precision,
                                  sol_bc5_metric metric, double *error)
{
    if (!block || !normals || !error)
        return SOL_ERR_NULL_ARG;
    if ((unsigned)precision >= SOL_BC4_PRECISION_COUNT || (unsigned)metric > SOL_BC5_MAX)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    const double(*pal)[8] = sol_nm_palettes(precision);
    *error = sol_nm_bc5_metric_value(
        sol_nm_bc5_joint_objective(pal[block->x.e0 << 8 | block->x.e1], pal[block->y.e0 << 8 | block->y.e1], n,
                                   metric == SOL_BC5_MAX, INFINITY, block->x.index, block->y.index),
        metric);
    return SOL_OK;
}

/* ---- the exact joint search ---- */


static int compare_pairs(const void *pa, const void *pb)
{
    const sol_nm_pair *a = pa, *b = pb;
    if (a->score != b->score)
        return a->score < b->score ? -1 : 1;
    return (a->pair > b->pair) - (a->pair < b->pair);
}

/* Sorts list by (score, pair) as qsort with compare_pairs does (a total order on distinct pairs, so
 * the same sequence), by LSD radix over the pair's two bytes and then the score's eight (a score
 * >= 0 orders as its bits; -0 counts as +0, as the comparison has it), skipping the digits that
 * every element shares; tmp holds count elements. Lists shorter than 1024 (most blocks: ten passes
 * over 256 buckets cost more there) by a merge sort (pairs_merge_sort); qsort itself if a score is
 * negative or NaN (the lists' scores are sums of squares and offsets, never) or if tmp is NULL.
 * Issue 13: the lists of blocks pointing away hold 10^4 - 4 10^4 pairs, and qsort's calls cost 3-5 ms
 * of such a block; on the hood map from an 8-bit source qsort of the short lists was 14.5% of the
 * optimal encoder (callgrind: its indirect comparison calls), the merge sort 5.7%. */
static inline int pair_before(const sol_nm_pair *a, const sol_nm_pair *b)
{
    return a->score < b->score || (a->score == b->score && a->pair < b->pair);
}

/* list[0..count) sorted by pair_before (compare_pairs' order), tmp holds count elements: insertion
 * sort of runs of 16, then bottom-up merges between list and tmp. The order is total on distinct
 * pairs, so the sequence is qsort's. */
static void pairs_merge_sort(sol_nm_pair *list, size_t count, sol_nm_pair *tmp)
{
    enum { RUN = 16 };
    for (size_t r = 0; r < count; r += RUN) {
        size_t end = r + RUN < count ? r + RUN : count;
        for (size_t i = r + 1; i < end; ++i) {
            sol_nm_pair v = list[i];
            size_t j = i;
            for (; j > r && pair_before(&v, &list[j - 1]); --j)
                list[j] = list[j - 1];
            list[j] = v;
        }
    }
    sol_nm_pair *from = list, *to = tmp;
    for (size_t width = RUN; width < count; width *= 2) {
        for (size_t lo = 0; lo < count; lo += 2 * width) {
            size_t mid = lo + width < count ? lo + width : count, hi = lo + 2 * width < count ? lo + 2 * width : count;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi)
                to[k++] = pair_before(&from[j], &from[i]) ? from[j++] : from[i++];
            while (i < mid)
                to[k++] = from[i++];
            while (j < hi)
                to[k++] = from[j++];
        }
        sol_nm_pair *t = from;
        from = to;
        to = t;
    }
    if (from != list)
        memcpy(list, from, count * sizeof *list);
}

void sol_nm_bc5_sort_pairs(sol_nm_pair *list, size_t count, sol_nm_pair *tmp)
{
    for (size_t i = 0; tmp && i < count; ++i) {
        list[i].score += 0.0; /* -0 -> +0 */
        if (!(list[i].score >= 0.0))
            tmp = NULL;
    }
    if (!tmp || count > UINT32_MAX) {
        qsort(list, count, sizeof *list, compare_pairs);
        return;
    }
    if (count < 1024) {
        pairs_merge_sort(list, count, tmp);
        return;
    }
    sol_nm_pair *from = list, *to = tmp;
    for (int d = 0; d < 10; ++d) {
        uint32_t hist[256] = {0};
        for (size_t i = 0; i < count; ++i) {
            uint64_t bits;
            memcpy(&bits, &from[i].score, sizeof bits);
            unsigned digit = d < 2 ? (from[i].pair >> (8 * d)) & 255u : (unsigned)(bits >> (8 * (d - 2))) & 255u;
            ++hist[digit];
        }
        int shared = 0;
        for (int k = 0; k < 256; ++k)
            shared |= hist[k] == count;
        if (shared)
            continue;
        uint32_t at = 0;
        for (int k = 0; k < 256; ++k) {
            uint32_t c = hist[k];
            hist[k] = at;
            at += c;
        }
        for (size_t i = 0; i < count; ++i) {
            uint64_t bits;
            memcpy(&bits, &from[i].score, sizeof bits);
            unsigned digit = d < 2 ? (from[i].pair >> (8 * d)) & 255u : (unsigned)(bits >> (8 * (d - 2))) & 255u;
            to[hist[digit]++] = from[i];
        }
        sol_nm_pair *t = from;
        from = to;
        to = t;
    }
    if (from != list)
        memcpy(list, from, count * sizeof *list);
}

void sol_nm_bc5_channel_key_init(channel_key *k, const double t[16], unsigned loose, double budget) {
    k->count = 0;
    k->budget = budget;
    for (int p = 0; p < 16; ++p) {
        int l = (loose >> p) & 1, seen = 0;
        for (int q = 0; q < k->count && !seen; ++q)
            seen = value_bits(k->t[q]) == value_bits(t[p]) && k->loose[q] == l;
        if (!seen) {
            k->t[k->count] = t[p];
            k->loose[k->count++] = l;
        }
    }
}

static inline int usable_entry(double a, double t, int loose, double budget)
{
    double d = a - t;
    if (loose) {
        double b = a * (1.0 / M_SQRT2), lo = a < b ? a : b, hi = a < b ? b : a;
        d = t < lo ? lo - t : (t > hi ? t - hi : 0.0);
    }
    return d * d <= budget;
}


/* seed_entry of each of count <= 16 targets t, into e[0 .. count). */
static void seed_entries_scalar(const double pal[8], const double *t, int count, int *e)
{
    for (int k = 0; k < count; ++k)
        e[k] = seed_entry(pal, t[k]);
}

#if SEARCH_AVX2
/* seed_entries, 4 targets at a time: the same squared distances, d < m (ordered, strict) moves to
 * entry i as the scalar walk does, so the first least is kept. */
static AVX2_FN void seed_entries_avx2(const double pal[8], const double *t, int count, int *e)
{
    double tt[16], idx[16];
    for (int k = 0; k < 16; ++k)
        tt[k] = t[k < count ? k : 0];
    for (int k = 0; k < count; k += 4) {
        __m256d tk = _mm256_loadu_pd(tt + k), d = _mm256_sub_pd(_mm256_set1_pd(pal[0]), tk);
        __m256d m = _mm256_mul_pd(d, d), ix = _mm256_setzero_pd();
        for (int i = 1; i < 8; ++i) {
            d = _mm256_sub_pd(_mm256_set1_pd(pal[i]), tk);
            d = _mm256_mul_pd(d, d);
            ix = _mm256_blendv_pd(ix, _mm256_set1_pd((double)i), _mm256_cmp_pd(d, m, _CMP_LT_OQ));
            m = _mm256_min_pd(d, m);
        }
        _mm256_storeu_pd(idx + k, ix);
    }
    for (int k = 0; k < count; ++k)
        e[k] = (int)idx[k];
}
#endif

/* seed_entry of each of count <= 16 targets t, into e[0 .. count), by the AVX2 form where it runs. */
static void seed_entries(const double pal[8], const double *t, int count, int *e)
{
#if SEARCH_AVX2
    if (search_avx2()) {
        seed_entries_avx2(pal, t, count, e);
        return;
    }
#endif
    seed_entries_scalar(pal, t, count, e);
}


/* The usable entries' values of two palettes for each pixel, in palette order, equal bit for bit. */
static int mask_sequences_equal(const double pa[8], const uint16_t ma[8], const double pb[8], const uint16_t mb[8],
                                int count)
{
    for (int p = 0; p < count; ++p) {
        int ea = 0, eb = 0;
        for (;;) {
            while (ea < 8 && !((ma[ea] >> p) & 1))
                ++ea;
            while (eb < 8 && !((mb[eb] >> p) & 1))
                ++eb;
            if (ea == 8 || eb == 8) {
                if (ea != eb)
                    return 0;
                break;
            }
            if (value_bits(pa[ea++]) != value_bits(pb[eb++]))
                return 0;
        }
    }
    return 1;
}

/* A hash that is a function of the key (seeds, and per pixel the usable values in palette order)
 * alone: the seeds in pixel order, and the sum over entries usable for some pixel of a mix of
 * (value bits, mask); an entry's mask is that of its value, so that multiset is fixed by the key. */
static uint64_t masks_hash(const double pal[8], const uint16_t m[8], const uint64_t seed[16], int count)
{
    /* the seeds mixed each with its pixel's own constant and summed: independent multiplications
     * instead of a chain of 16 (issue 13: the chain was ~5% of a block pointing away; sol_nm_bc5_merge_classes
     * keeps the same pairs whatever the hash) */
    uint64_t h = 0, sum = 0;
    for (int p = 0; p < count; ++p)
        h += mix64(UINT64_C(0x2545F4914F6CDD1D) * (uint64_t)(p + 1), seed[p]);
    for (int e = 0; e < 8; ++e)
        if (m[e])
            sum += mix64(value_bits(pal[e]), m[e]);
    return mix64(h, sum);
}

static uint64_t pair_key_hash(const channel_key *k, const double pal[8])
{
    uint64_t h = 0;
    for (int p = 0; p < k->count; ++p) {
        int loose = k->loose[p];
        h = mix64(h, value_bits(pal[seed_entry(pal, k->t[p])]));
        for (int e = 0; e < 8; ++e)
            if (usable_entry(pal[e], k->t[p], loose, k->budget))
                h = mix64(h, value_bits(pal[e]));
        h = mix64(h, 0x5eed);
    }
    return h;
}

/* 1 if the usable entries of two palettes for pixel p (usable(ctx, pal, e, p): entry e is), taken in
 * entry order, are the same values bit for bit: the two pairs serve that pixel alike. Entries are
 * tested lazily in that order (the table's test counts work: the same tests as a plain walk). */
typedef int (*entry_usable_fn)(void *ctx, const double pal[8], int e, int p);

static inline int usable_values_equal(const double pa[8], const double pb[8], int p, entry_usable_fn usable, void *ctx)
{
    int ea = 0, eb = 0;
    for (;;) {
        while (ea < 8 && !usable(ctx, pa, ea, p))
            ++ea;
        while (eb < 8 && !usable(ctx, pb, eb, p))
            ++eb;
        if (ea == 8 || eb == 8)
            return ea == eb;
        if (value_bits(pa[ea++]) != value_bits(pb[eb++]))
            return 0;
    }
}

static int key_entry_usable(void *ctx, const double pal[8], int e, int p)
{
    const channel_key *k = ctx;
    return usable_entry(pal[e], k->t[p], k->loose[p], k->budget);
}

int sol_nm_bc5_pair_key_equal(const channel_key *k, const double pa[8], const double pb[8]) {
    for (int p = 0; p < k->count; ++p) {
        if (value_bits(pa[seed_entry(pa, k->t[p])]) != value_bits(pb[seed_entry(pb, k->t[p])]))
            return 0;
        if (!usable_values_equal(pa, pb, p, key_entry_usable, (void *)k))
            return 0;
    }
    return 1;
}

/* Keeps the first pair of each equivalence class of a sorted list (in place), classes given by a
 * hash and an equality of the pairs' palettes (open addressing in slots, at least 2 count + 64
 * entries; a slot holds the kept position + 1 in its low 17 bits and 15 bits of the hash above, so
 * that equality is only tested where those agree: equal palettes have equal hashes); work (if not
 * NULL) is charged 16 per pair before its hash. Returns the count kept (count <= 65536). */
#define SLOT_POS ((UINT32_C(1) << 17) - 1)

/* Clears the slots of a hash set for count pairs (a power of two >= 2 count, at least 64: at most half
 * full) and returns their number. */
static size_t slots_clear(uint32_t *slots, size_t count)
{
    size_t size = 64;
    while (size < 2 * count)
        size *= 2;
    memset(slots, 0, size * sizeof *slots);
    return size;
}

/* A slot's check bits: 15 bits of the hash above the position's 17. */
static uint32_t slot_tag(uint64_t hash)
{
    return (uint32_t)(hash >> 49) << 17;
}

size_t sol_nm_bc5_merge_classes(sol_nm_pair *list, size_t count, const double (*pal)[8], const pair_classes *pc,
                                uint32_t *slots) {
    const size_t size = slots_clear(slots, count);
    size_t kept = 0;
    for (size_t i = 0; i < count; ++i) {
        const double *a = pal[list[i].pair];
        if (pc->work)
            *pc->work += 16;
        uint64_t hash = pc->hash(pc->ctx, a);
        size_t h = (size_t)hash & (size - 1);
        uint32_t tag = slot_tag(hash);
        int dup = 0;
        for (; slots[h]; h = (h + 1) & (size - 1))
            if ((slots[h] & ~SLOT_POS) == tag && pc->equal(pc->ctx, pal[list[(slots[h] & SLOT_POS) - 1].pair], a)) {
                dup = 1;
                break;
            }
        if (dup)
            continue;
        list[kept] = list[i];
        slots[h] = tag | (uint32_t)++kept;
    }
    return kept;
}

static uint64_t key_hash_fn(void *ctx, const double pal[8])
{
    return pair_key_hash(ctx, pal);
}

int sol_nm_bc5_key_equal_fn(void *ctx, const double pa[8], const double pb[8]) {
    return sol_nm_bc5_pair_key_equal(ctx, pa, pb);
}

/* Keeps the first pair of each equivalence class of a sorted list (in place); returns the count. */
size_t sol_nm_bc5_merge_equivalent(sol_nm_pair *list, size_t count, const channel_key *k, const double (*pal)[8],
                                   uint32_t *slots) {
    const pair_classes pc = {key_hash_fn, sol_nm_bc5_key_equal_fn, (void *)k, NULL};
    return sol_nm_bc5_merge_classes(list, count, pal, &pc, slots);
}

/* Lower bound of every candidate's objective from the hemisphere alone: a decoded normal has
 * z >= 0, so dN_p >= asin(-nz_p) where nz_p < 0. A block of normals pointing straight away (0, 0, -1)
 * reaches it (dN = pi / 2 at every rim decode), and is decided by it at once. */
static double hemisphere_bound(const double n[16][3], int use_max)
{
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = n[p][2] < 0.0 ? asin(-n[p][2]) : 0.0;
        s = fold_term(s, e * e, use_max);
    }
    return s;
}

static int pair_in_range(int pair, uint8_t e0_lo, uint8_t e0_hi, uint8_t e1_lo, uint8_t e1_hi)
{
    int e0 = pair >> 8, e1 = pair & 255;
    return e0 >= e0_lo && e0 <= e0_hi && e1 >= e1_lo && e1 <= e1_hi;
}

/* ---- the coupling filter (rims and pixels pointing away) ----
 *
 * The channel bounds of a rim pixel (z ~ 0) or one pointing away are loose: they ask only that x and
 * y EACH can come close to the target rim direction, and a long list of x pairs meets a long list of
 * y pairs (a block of equal rim normals: tens of thousands each). What they miss is that one decode
 * (a, b) must point in that direction with both components. So for each x pair A of the list, the
 * search first computes, per constrained pixel p, the y values b that can still beat the incumbent
 * together with some entry a of A, a union of at most two intervals per entry:
 *  - a per-pixel budget T_p: the incumbent minus lower bounds of the other pixels given A (sum
 *    metric: a tight pixel's (a - nx)^2 nearest term, a pixel pointing away its theta0^2 + k (loose
 *    distance of mx)^2; pixels with a bit-identical normal share the rest equally, as their errors are
 *    equal), the incumbent itself for the max metric;
 *  - a ball |u - q| <= R around a target q on the unit sphere the decode u must reach: q = n with
 *    R^2 = T_p (dN^2 >= chord^2) for a rim pixel, q = (m, 0) with R^2 = (T_p - theta0^2) / k for one
 *    pointing away (the bound above);
 *  - an unclamped decode (a, b, z) has |u - q|^2 >= (a - qx)^2 + (b - qy)^2: b within
 *    sqrt(R^2 - (a - qx)^2) of qy (and b^2 <= 1 - a^2);
 *  - a clamped one (a, b, 0) / r has |u - q|^2 = |w - q_xy|^2 + qz^2 with w = (a, b) / r on the unit
 *    circle: w . q_xy >= (1 + |q_xy|^2 - R^2 + qz^2) / 2, i.e. w within an angle phi of q_xy's
 *    direction, a cone; the line x = a meets it in one interval, found from the cone's two edges.
 * The widest cases (phi near pi / 2, R >= 2) constrain nothing. Intervals are widened (cosine lowered
 * by 1e-9, ends moved by 1e-9) against rounding. The y list's entries are bucketed by value (4096
 * buckets of [-1, 1]); the pixel whose intervals cover the fewest entries picks the y pairs to visit
 * (whole buckets: a superset), the next most selective pixels reject those with no entry in their
 * intervals, and the survivors go through the usual per-candidate bounds in list order. Only
 * candidates that cannot beat the incumbent are skipped, so the search visits the same improving
 * candidates in the same order, and returns the same block, as without the filter. */
#define Y_BUCKETS 4096

static inline int y_bucket(double b)
{
    int k = (int)((b + 1.0) * (0.5 * Y_BUCKETS));
    return k < 0 ? 0 : (k >= Y_BUCKETS ? Y_BUCKETS - 1 : k);
}

/* One entry of a y pair: its value and the pair's list position. */
typedef struct y_item {
    double v;
    uint32_t j;
} y_item;

/* items[start[k] .. start[k + 1] - 1]: the entries in bucket k. */
typedef struct y_index {
    uint32_t start[Y_BUCKETS + 1];
    const y_item *items;
} y_index;

/* Buckets the entries of the ny pairs (items: room for 8 ny). */
static void y_index_init(y_index *ix, const sol_nm_pair *list, size_t ny, const double (*pal)[8], y_item *items)
{
    memset(ix->start, 0, sizeof ix->start);
    for (size_t j = 0; j < ny; ++j)
        for (int e = 0; e < 8; ++e)
            ++ix->start[y_bucket(pal[list[j].pair][e]) + 1];
    for (int k = 0; k < Y_BUCKETS; ++k)
        ix->start[k + 1] += ix->start[k];
    uint32_t fill[Y_BUCKETS];
    memcpy(fill, ix->start, sizeof fill);
    for (size_t j = 0; j < ny; ++j)
        for (int e = 0; e < 8; ++e)
            items[fill[y_bucket(pal[list[j].pair][e])]++] = (y_item){pal[list[j].pair][e], (uint32_t)j};
    ix->items = items;
}

/* The b interval of the line x = a inside the cone of directions within phi of d (unit), given
 * c = cos phi > 0 and s = sin phi: 0 if empty, else 1 with [*lo, *hi] (possibly infinite). */
static int cone_line(double a, double dx, double dy, double c, double s, double *lo, double *hi)
{
    int up = dy >= c, down = -dy >= c; /* (0, 1) or (0, -1) inside the cone */
    if (a == 0.0) {
        *lo = down ? -INFINITY : 0.0;
        *hi = up ? INFINITY : 0.0;
        return up || down;
    }
    const double edge[2][2] = {{dx * c + dy * s, dy * c - dx * s}, {dx * c - dy * s, dy * c + dx * s}};
    int hits = 0;
    double h[2];
    for (int k = 0; k < 2; ++k)
        if (edge[k][0] * a > 0.0)
            h[hits++] = a * edge[k][1] / edge[k][0];
    if (hits == 2) {
        *lo = h[0] < h[1] ? h[0] : h[1];
        *hi = h[0] < h[1] ? h[1] : h[0];
        return 1;
    }
    if (hits == 0)
        return 0;
    *lo = up ? h[0] : (down ? -INFINITY : h[0]);
    *hi = up ? INFINITY : h[0];
    return 1;
}

/* What the intervals of one ball (target q, squared radius R2) share across x values: (q[1], q[2])
 * in polar form (r, psi: sphere_line's; they depend on q alone, so a caller testing many radii around
 * one pixel computes them once), and the cone of the clamped decodes that reach the ball (clamped: 0
 * none, 1 the cone of half-angle acos c around (dx, dy), 2 every direction). Computing them apart
 * from the values changes no double: the same expressions on the same inputs (issue 13: the pair
 * screen asked for one value's intervals at a time, ~1.2 M calls on `away-cone s=1 sum p16`, each
 * redoing two hypots and an atan2 that depend on the pixel only). */
typedef struct ball_lines {
    const double *q;
    double R2, r, psi;
    int clamped;
    double c, sn, dx, dy;
} ball_lines;

/* bl's polar form of (q[1], q[2]) for target q (unit when exact intervals are asked). */
static void ball_lines_polar(ball_lines *bl, const double q[3])
{
    bl->q = q;
    bl->r = hypot(q[1], q[2]);
    bl->psi = atan2(q[2], q[1]);
}

/* bl's radius R2 and its cone of clamped decodes: 0, or -1 if the ball constrains nothing (R2 >= 4,
 * or a cone of half a plane or more), as the interval functions return it. */
static int ball_lines_radius(ball_lines *bl, double R2, double cone_slack)
{
    const double *q = bl->q;
    bl->R2 = R2;
    if (!(R2 < 4.0))
        return -1;
    double rq = hypot(q[0], q[1]), rc2 = R2 - q[2] * q[2];
    bl->clamped = 1;
    bl->c = bl->sn = bl->dx = bl->dy = 0.0;
    if (rc2 < 0.0) {
        bl->clamped = 0;
    } else if (rq == 0.0) {
        bl->clamped = 1.0 - rc2 <= 0.0 ? 2 : 0; /* w . q_xy = 0 >= (1 - rc2) / 2 */
    } else {
        bl->c = (1.0 + rq * rq - rc2) / (2.0 * rq) - cone_slack;
        if (bl->c > 1.0)
            bl->clamped = 0;
        else if (bl->c < 1e-3)
            return -1; /* a cone of half a plane or more */
        else {
            bl->sn = sqrt((1.0 - bl->c) * (1.0 + bl->c));
            bl->dx = q[0] / rq;
            bl->dy = q[1] / rq;
        }
    }
    return 0;
}

/* The b of the unclamped decodes (a, b, z), z = sqrt(1 - a^2 - b^2), with |u - q|^2 <= R2 for unit q
 * (bl's), exactly (z kept, not dropped as in pixel_y_intervals): a q0 + b q1 + z q2 >= 1 - R2 / 2, and
 * with (b, z) = L (cos phi, sin phi), L = sqrt(1 - a^2), phi in [0, pi], that is
 * L r cos(phi - psi) >= C' (r, psi: (q1, q2) in polar form, C' = 1 - R2 / 2 - a q0), an arc of phi
 * around psi of half-width acos(C' / (L r)), intersected with [0, pi] (b = L cos phi decreasing).
 * The half-width is widened by 1e-6 and the ends by 1e-9 against rounding (acos is steep near +-1).
 * Appends up to two intervals at lo[k], hi[k]; returns the new k. */
static int sphere_line(double a, const ball_lines *bl, double *lo, double *hi, int k)
{
    const double L2 = (1.0 - a) * (1.0 + a);
    if (!(L2 >= 0.0))
        return k;
    const double *q = bl->q, R2 = bl->R2, r = bl->r;
    const double L = sqrt(L2), C = 1.0 - 0.5 * R2 - a * q[0] - 1e-12;
    double alpha;
    if (L * r == 0.0 || C / (L * r) <= -1.0) {
        if (!(L * r == 0.0) || 0.0 >= C - 1e-12) {
            lo[k] = -L - 1e-9;
            hi[k++] = L + 1e-9;
        }
        return k;
    }
    const double kappa = C / (L * r);
    if (kappa > 1.0)
        return k;
    alpha = acos(kappa < 1.0 ? kappa : 1.0) + 1e-6;
    if (alpha >= M_PI) {
        lo[k] = -L - 1e-9;
        hi[k++] = L + 1e-9;
        return k;
    }
    const double psi = bl->psi;
    for (int s = -1; s <= 1; ++s) {
        const double c = psi + 2.0 * M_PI * s, p0 = c - alpha > 0.0 ? c - alpha : 0.0,
                     p1 = c + alpha < M_PI ? c + alpha : M_PI;
        if (p0 <= p1) {
            lo[k] = L * cos(p1) - 1e-9;
            hi[k++] = L * cos(p0) + 1e-9;
        }
    }
    return k;
}

/* The intervals of one x value a against bl's ball (one entry's part of ball_intervals_exact or
 * pixel_y_intervals): appends up
 * to five (exact) or two at lo[k], hi[k] and returns the new k. */
static int ball_lines_value(const ball_lines *bl, double a, int exact, double *lo, double *hi, int k)
{
    const double *q = bl->q;
    double da = a - q[0], rem = bl->R2 - da * da;
    if (exact) {
        k = sphere_line(a, bl, lo, hi, k);
    } else if (rem >= 0.0) { /* unclamped */
        /* max / min written out as below (only a zero's sign can differ, and -+1e-9 removes it) */
        const double s2 = (1.0 - a) * (1.0 + a), w = sqrt(rem), lim = sqrt(s2 > 0.0 ? s2 : 0.0);
        const double l = (q[1] - w > -lim ? q[1] - w : -lim) - 1e-9, h = (q[1] + w < lim ? q[1] + w : lim) + 1e-9;
        if (l <= h) {
            lo[k] = l;
            hi[k++] = h;
        }
    }
    double l, h;
    if (bl->clamped == 2) {
        l = -1.0;
        h = 1.0;
    } else if (bl->clamped == 1 && cone_line(a, bl->dx, bl->dy, bl->c, bl->sn, &l, &h) && l <= 1.0 + 1e-9 &&
               h >= -1.0 - 1e-9) {
        /* fmax / fmin written out (library calls otherwise): the same doubles for every l, h,
         * NaN included (the bound is taken) */
        l = (l > -1.0 ? l : -1.0) - 1e-9;
        h = (h < 1.0 ? h : 1.0) + 1e-9;
    } else {
        return k;
    }
    if (!exact) {
        lo[k] = l;
        hi[k++] = h;
        return k;
    }
    /* a decode is clamped only off the unit disc: |b| >= L = sqrt(1 - a^2) (widened; the root of
     * max(0, .) written out: of -0 it gives -0 where fmax may give +0, both end at -1e-9) */
    const double L2 = (1.0 - a) * (1.0 + a), L = sqrt(L2 > 0.0 ? L2 : 0.0) - 1e-9;
    if (l <= -L) {
        lo[k] = l;
        hi[k++] = h < -L ? h : -L;
    }
    if (h >= L) {
        lo[k] = l > L ? l : L;
        hi[k++] = h;
    }
    return k;
}


/* The exact intervals (z kept: sphere_line; clamped decodes only off the unit disc) of the entries
 * a[0 .. na) against the ball of squared radius R2 around bl's target: up to five per entry; their
 * count, or -1 if the ball constrains nothing or cap could overflow (constraining nothing is valid).
 * bl holds the target's polar form (ball_lines_polar, set up once per pixel), a the palette's
 * distinct entries in palette order (palette_distinct, once per palette). */
static int ball_intervals_exact(ball_lines bl, double R2, double cone_slack, const double *a, int na, int cap,
                                double *lo, double *hi)
{
    if (ball_lines_radius(&bl, R2, cone_slack) < 0)
        return -1;
    int k = 0;
    for (int e = 0; e < na; ++e) {
        if (k > cap - 5)
            return -1; /* no room for this entry's five intervals: constrain nothing (valid) */
        k = ball_lines_value(&bl, a[e], 1, lo, hi, k);
    }
    return k;
}

/* The distinct entries of palette a in palette order (the first of equal entries); their count. */
static int palette_distinct(const double a[8], double out[8])
{
    int na = 0;
    for (int e = 0; e < 8; ++e) {
        int dup = 0;
        for (int f = 0; f < e && !dup; ++f)
            dup = a[f] == a[e];
        if (!dup)
            out[na++] = a[e];
    }
    return na;
}

/* The y intervals for one pixel (target q, squared radius R2) and x palette a, from the projection
 * that drops z (ball_intervals_exact keeps it): at most two per distinct entry, so 16 always suffice;
 * their count, or -1 if the pixel constrains nothing. */
static int pixel_y_intervals(const double a[8], const double q[3], double R2, double cone_slack, double lo[16],
                             double hi[16])
{
    ball_lines bl;
    bl.q = q;
    if (ball_lines_radius(&bl, R2, cone_slack) < 0)
        return -1;
    double d[8];
    const int na = palette_distinct(a, d);
    int k = 0;
    for (int e = 0; e < na; ++e)
        k = ball_lines_value(&bl, d[e], 0, lo, hi, k);
    return k;
}

/* The coupling filter for one x palette: np constrained pixels, rank[0] the most selective; per pixel
 * up to Y_FILTER_CAP intervals (ball_intervals_exact: up to five per distinct entry). */
#define Y_FILTER_CAP 40
typedef struct y_filter {
    int np, pix[16], cnt[16], rank[16];
    double lo[16][Y_FILTER_CAP], hi[16][Y_FILTER_CAP];
    uint32_t items[16]; /* entries of the y list in the pixel's buckets */
} y_filter;

/* Sorts cnt intervals [lo, hi] by their low end and merges those that overlap; returns the new count. */
static int intervals_merge(double *lo, double *hi, int cnt)
{
    for (int i = 1; i < cnt; ++i)
        for (int j = i; j > 0 && lo[j] < lo[j - 1]; --j) {
            double t = lo[j];
            lo[j] = lo[j - 1];
            lo[j - 1] = t;
            t = hi[j];
            hi[j] = hi[j - 1];
            hi[j - 1] = t;
        }
    int k = 0;
    for (int i = 0; i < cnt; ++i) {
        if (k > 0 && lo[i] <= hi[k - 1]) {
            hi[k - 1] = hi[i] > hi[k - 1] ? hi[i] : hi[k - 1];
        } else {
            lo[k] = lo[i];
            hi[k++] = hi[i];
        }
    }
    return k;
}

static uint32_t interval_items(const y_index *ix, const double *lo, const double *hi, int cnt)
{
    uint32_t s = 0;
    for (int k = 0; k < cnt; ++k)
        s += ix->start[y_bucket(hi[k]) + 1] - ix->start[y_bucket(lo[k])];
    return s;
}

/* The ball that loose pixel p's decode must reach within the angle budget t (the metric's units): its
 * centre q (the normal, or for a pixel pointing away its rim target with z 0) and squared radius *R2
 * (t, or (t - off) / w pointing away: away_info's rim bound), widened for rounding. Returns 0 if the
 * pixel takes no part (pointing away with no positive weight), -1 if the budget is below the pixel's
 * floor (no decode reaches it), else 1. */
static int pixel_ball(const away_info *aw, const double n[16][3], int p, double t, double q[3], double *R2)
{
    double r2 = t;
    q[0] = n[p][0];
    q[1] = n[p][1];
    q[2] = n[p][2];
    if ((aw->mask >> p) & 1) {
        if (!(aw->w[p] > 0.0))
            return 0;
        r2 = (t - aw->off[p]) / aw->w[p];
        q[0] = aw->m[0][p];
        q[1] = aw->m[1][p];
        q[2] = 0.0;
    }
    if (r2 < 0.0)
        return -1;
    *R2 = r2 * (1.0 + 1e-9) + 1e-15;
    return 1;
}

/* The exact ball of a loose pixel p (a rim pixel, or one pointing away) for the angle budget t (the
 * metric's units): every decode u whose computed term dN^2 is below t lies within the chord
 * 2 sin(sqrt t / 2) of n_p (dN = 2 asin(|u - n| / 2)), so q = n_p and *R2 that chord squared, widened
 * by 1e-9 relative and 1e-12 absolute (sqrt t by 1e-12 relative) against the rounding of the angle and
 * of sin; 4 (no constraint) when sqrt t reaches pi. With ball_intervals_exact it is the set of
 * decodes within the budget itself: pixel_ball's balls (the budget as a squared chord; for a pixel
 * pointing away the rim bound's tangent around its rim target, loose away from it) hold it, and held
 * most of the arcs and cones pointing away's values that the screen then had to rule out one by one
 * (80-90% of the levels it computed came out at their cap; issue 13). */
static void pixel_chord_ball(const double n[16][3], int p, double t, double q[3], double *R2)
{
    q[0] = n[p][0];
    q[1] = n[p][1];
    q[2] = n[p][2];
    const double r = sqrt(t) * (1.0 + 1e-12);
    if (!(r < M_PI)) {
        *R2 = 4.0;
        return;
    }
    const double c = 2.0 * sin(0.5 * r);
    *R2 = c * c * (1.0 + 1e-9) + 1e-12;
}

/* Builds the filter for x palette a (its channel side xs, pixels in `order`): 1 if it filters, 0 if
 * no pixel constrains y, -1 if no y pair can beat the budget with a. */
static int y_filter_init(y_filter *f, const double a[8], const channel_side *xs, const double n[16][3],
                         const ball_lines nball[16], const int order[16], unsigned loose, const away_info *aw,
                         const double away_off[16], const int group[16], int use_max, double best,
                         const y_index *ix)
{
    /* a's distinct entries once for its pixels, the pixels' polar forms (nball: of n[p], the exact
     * balls' centre) once per search (issue 13 deg-speed: the per-palette interval call redid both per pixel, a
     * third of the cones' time) */
    double ad[8];
    const int na = palette_distinct(a, ad);
    const double budget = best * (1.0 + 1e-9);
    double lb[16], total = 0.0; /* per pixel (index p) lower bounds given a, and their sum */
    for (int k = 0; k < 16; ++k) {
        int p = order[k];
        lb[p] = (aw->mask >> p) & 1 ? away_off[k] + xs->lt[k] : ((loose >> p) & 1 ? 0.0 : xs->m1[k]);
        total += lb[p];
    }
    f->np = 0;
    for (int p = 0; p < 16; ++p) {
        if (!((loose >> p) & 1) || group[p] != p)
            continue; /* tight pixels: the channel bounds hold them; one pixel per group of equal normals */
        double t = budget, mult = 0.0, rest = total;
        for (int q = 0; q < 16; ++q)
            if (group[q] == p) {
                mult += 1.0;
                rest -= lb[q];
            }
        if (!use_max)
            t = (budget - rest * (1.0 - 1e-9)) / mult;
        double q3[3], R2;
        int ball = pixel_ball(aw, n, p, t, q3, &R2);
        if (ball == 0)
            continue;
        if (ball < 0)
            return -1;
        pixel_chord_ball(n, p, t, q3, &R2); /* the exact ball (pixel_ball: only whether p takes part) */
        int i = f->np;
        int cnt = ball_intervals_exact(nball[p], R2, 1e-9, ad, na, Y_FILTER_CAP, f->lo[i], f->hi[i]);
        if (cnt < 0)
            continue;
        if (cnt == 0)
            return -1;
        cnt = intervals_merge(f->lo[i], f->hi[i], cnt);
        f->pix[i] = p;
        f->cnt[i] = cnt;
        f->items[i] = interval_items(ix, f->lo[i], f->hi[i], cnt);
        ++f->np;
    }
    if (f->np == 0)
        return 0;
    /* most selective first: rank, by a stable insertion sort on items (the pixels' intervals stay in
     * place; moving them was a fifth of the cones' search time, issue 13's profile) */
    for (int i = 0; i < f->np; ++i)
        f->rank[i] = i;
    for (int i = 1; i < f->np; ++i)
        for (int j = i; j > 0 && f->items[f->rank[j]] < f->items[f->rank[j - 1]]; --j) {
            int t = f->rank[j];
            f->rank[j] = f->rank[j - 1];
            f->rank[j - 1] = t;
        }
    return 1;
}

/* Whether palette b has an entry in the intervals of the filter's pixels 1 .. 4 (pixel 0 chose it). */
static int y_filter_pass(const y_filter *f, const double b[8])
{
    for (int r = 1; r < f->np && r < 5; ++r) {
        const int i = f->rank[r];
        int hit = 0;
        for (int e = 0; e < 8 && !hit; ++e)
            for (int k = 0; k < f->cnt[i] && !hit; ++k)
                hit = b[e] >= f->lo[i][k] && b[e] <= f->hi[i][k];
        if (!hit)
            return 0;
    }
    return 1;
}

/* ---- the pair screen (issue 13: the arcs and cones pointing away, the jittered rims) ----
 *
 * On these blocks the per-candidate bounds reject nearly every candidate they meet (the coupled
 * cosine of bc5_away.c, or sol_nm_bc5_joint_objective_lower for rims), but the lists stay long: the x list keeps
 * ~14000 pairs under every row bound (the y list's values leave each x pair some partner), and the
 * candidates met, 1-5 million, each cost 16 x 64 decodes. The screen decides them ahead of the
 * enumeration, one y pair B at a time, through the x VALUES instead of the x pairs:
 *  - with B fixed, a candidate (A, B) gives pixel p the error e_p = dN^2 of its chosen decode
 *    (a_i, b_j), at least angle2_lower_bound(a_i, b_j, n_p) >= chord2_angle2_lower(min over i, j of
 *    the squared chord) (that conversion is non-decreasing), i.e. e_p >= min_i g_p(a_i) with
 *        g_p(v) = max(theta0_p^2, chord2_angle2_lower(min_j decode_chord2(v, b_j, n_p)))
 *    (theta0^2 = away_off: the hemisphere bound, 0 unless p points away). g depends on one x value,
 *    so it is computed once per distinct value and y pair, not per candidate;
 *  - a per-pixel floor base_p that holds for every candidate with B (B's channel side alone, as the
 *    quick bound computes it): pointing away theta0^2 + k (loose distance of my)^2, a rim pixel
 *    (loose) the loose distance of ny to B squared (dN >= chord >= the y component's distance, the
 *    component of a clamped decode lying in B's loose intervals), a tight pixel min(m1_y, nz^2)
 *    (unclamped: chord^2 >= (b - ny)^2; clamped: chord^2 >= nz^2); the latter two lowered for rounding
 *    as quick_term. So e_p >= max(base_p, min_i g_p(a_i)) for every x pair A;
 *  - sum metric: the slack S = best - sum_p base_p is split in 254 steps delta, and each value keeps
 *    per pixel the level floor((max(g, base) - base) / delta) (lowered by 1e-9 relative, at most
 *    254): a candidate's objective is at least sum_p base_p + delta L, L the sum over pixels of the
 *    least level of A's 8 values, and it cannot beat the incumbent once (sum base + delta L)
 *    (1 - 1e-12) >= best (the 1e-12 covers the objective's own summation rounding);
 *  - only values that can serve a pixel under its budget T_p = best - sum_{q != p} base_q are
 *    computed: pixel_y_intervals (the coupling filter's balls, with x and y swapped: the decode is
 *    symmetric in its components) gives a superset of them as intervals of x values; every other
 *    value keeps level 255, which means e_p > T_p, so the objective exceeds the incumbent. A pixel
 *    whose ball constrains nothing (pixel_y_intervals -1) is left out (it counts base_p);
 *  - max metric: a value gets 255 for pixel p when g_p >= best or it lies outside p's intervals (T_p =
 *    best), else 0; a candidate whose least level is 255 at some pixel cannot beat the incumbent.
 * A candidate (A, B) passes when it can still beat the incumbent at the time of the screen; the
 * enumeration then visits only the passing candidates of each row (in the same order, through the
 * same bounds and exact evaluation), so it returns the same block: every candidate skipped has an
 * objective at or above the incumbent. Values are kept by their code (value_set below: K / Q exactly);
 * the (rare) two doubles that round the same K are both evaluated, and the least g kept. Work: 1 per
 * pair tested (eight 16-byte minima), 8 per value and pixel evaluated (8 decodes), 8 per x pair set up. */
#define SCREEN_CODES 65536
#define SCREEN_PASS_MAX (1u << 19)
#define SCREEN_TESTS_MAX (1u << 26)

typedef struct pair_screen {
    /* per x value code k its slot: its rank among the codes present, before[k / 64] plus the codes
     * present below k in its word (the x list's distinct codes numbered in code order, so that the
     * per-value state below fills a few pages instead of 65536 codes' worth: on fresh memory each
     * page is a fault, ~30 ms a screen on the survey's blocks; and so that an interval of codes is an
     * interval of slots, which phase 1 marks without visiting the codes' bits one by one) */
    uint64_t bits[SCREEN_CODES / 64]; /* the codes present */
    uint32_t before[SCREEN_CODES / 64 + 1];
    uint64_t seen[SCREEN_CODES / 64]; /* value_code_add's codes met so far (slot numbering pass) */
    /* per slot: */
    uint8_t lv[SCREEN_CODES][16];  /* per pixel (visiting order): the level */
    double val[SCREEN_CODES][2];   /* the distinct doubles of the code */
    uint8_t nval[SCREEN_CODES];
    uint32_t stamp[SCREEN_CODES];  /* marked in the current y pair (then reset) */
    uint16_t done[SCREEN_CODES];   /* bit k: lv[slot][k] computed in the current y pair */
    uint16_t marked[SCREEN_CODES]; /* bit k: jm[slot][k] != 0 */
    uint8_t jm[SCREEN_CODES][16];  /* bit e: the value lies in y entry e's intervals of pixel k */
    uint32_t touched[SCREEN_CODES]; /* the slots marked in the current y pair */
    /* the rows holding each slot's value: crow[cstart[s] .. cstart[s] + cnum[s]), ascending, each row
     * once; rstamp: rows met in the current y pair (generation rgen) */
    uint32_t cstart[SCREEN_CODES], cnum[SCREEN_CODES];
    uint16_t xcode[65536][8];      /* the x list's values' slots */
    uint32_t start[65537];         /* row r's passing y positions: col[start[r] .. start[r + 1]) */
    uint32_t jstart[65537];        /* y pair j's passing rows: row[jstart[j] .. jstart[j + 1]) */
    uint32_t row[SCREEN_PASS_MAX], col[SCREEN_PASS_MAX];
    uint32_t gen;
    uint32_t crow[8 * 65536];
    uint32_t rstamp[65536];
    uint32_t rgen;
    /* the lists the rows and columns stand for (pair_screen_remap): nrows x pairs, ncols y pairs */
    size_t nrows, ncols;
    uint16_t xpair[65536], ypair[65536];
    uint32_t ymap[65536]; /* pair_screen_remap's old column -> new column */
} pair_screen;

/* A pair screen's tables, uninitialised but for the generations (pair_screen_build initialises what
 * it reads: calloc would clear, and so fault in, all of its ~13 MB), or NULL. */
static pair_screen *pair_screen_new(void)
{
    pair_screen *sc = malloc(sizeof *sc);
    if (sc)
        sc->gen = sc->rgen = 0;
    return sc;
}

/* The levels of 8 values of one x pair, least per pixel (columns masked by keep: least[k]), then
 * either 1 (some pixel at 255: ruled out) or 0 with *sum the sum of the levels. */
static inline int screen_levels(const pair_screen *sc, const uint16_t code[8], const uint8_t keep[16],
                                uint8_t least[16], unsigned *sum)
{
#if defined(__SSE2__)
    __m128i m = _mm_loadu_si128((const __m128i *)sc->lv[code[0]]);
    for (int e = 1; e < 8; ++e)
        m = _mm_min_epu8(m, _mm_loadu_si128((const __m128i *)sc->lv[code[e]]));
    m = _mm_and_si128(m, _mm_loadu_si128((const __m128i *)keep));
    _mm_storeu_si128((__m128i *)least, m);
    if (_mm_movemask_epi8(_mm_cmpeq_epi8(m, _mm_set1_epi8((char)-1))))
        return 1;
    __m128i s = _mm_sad_epu8(m, _mm_setzero_si128());
    *sum = (unsigned)(_mm_cvtsi128_si32(s) + _mm_cvtsi128_si32(_mm_srli_si128(s, 8)));
    return 0;
#else
    unsigned t = 0;
    for (int k = 0; k < 16; ++k) {
        unsigned l = sc->lv[code[0]][k];
        for (int e = 1; e < 8; ++e)
            l = sc->lv[code[e]][k] < l ? sc->lv[code[e]][k] : l;
        l &= keep[k];
        least[k] = (uint8_t)l;
        if (l == 255)
            return 1;
        t += l;
    }
    *sum = t;
    return 0;
#endif
}

/* Records value v under its code k in a code set (bits, and per code up to two distinct doubles
 * nval / val at index `slot`: palette values that round to one code can differ in their last bits):
 * 1 if the code was new, 0 if it was there (v added as its second double if new), -1 if the code
 * would need a third double (callers then give up their screen). slot: k itself (the pixel floor), or
 * the code's slot, the next free one for a new code (the pair screen). Shared by both. */
static inline int value_code_add(uint64_t *bits, uint8_t *nval, double (*val)[2], long k, long slot, double v)
{
    if (!((bits[k >> 6] >> (k & 63)) & 1)) {
        bits[k >> 6] |= UINT64_C(1) << (k & 63);
        nval[slot] = 1;
        val[slot][0] = v;
        return 1;
    }
    if (v != val[slot][0] && (nval[slot] == 1 || v != val[slot][1])) {
        if (nval[slot] == 2)
            return -1;
        val[slot][1] = v;
        nval[slot] = 2;
    }
    return 0;
}

/* The value codes (code k is the value k / half_q - 1) of an interval [lo, hi] of values, widened by
 * one code each side so that rounding cannot drop a value at its ends, clipped to [0, top]; the
 * range is empty when k0 > k1. Shared by the pair screen and the pixel floor. */
static inline void interval_codes(double lo, double hi, double half_q, long top, long *k0, long *k1)
{
    long a = (long)floor((lo + 1.0) * half_q) - 1, b = (long)ceil((hi + 1.0) * half_q) + 1;
    *k0 = a < 0 ? 0 : a;
    *k1 = b > top ? top : b;
}

/* Word w of a code bitset with only the codes [k0, k1] kept (w between k0 / 64 and k1 / 64). */
static inline uint64_t bits_in_range(const uint64_t *bits, long w, long k0, long k1)
{
    uint64_t b = bits[w];
    if (w == k0 >> 6)
        b &= ~UINT64_C(0) << (k0 & 63);
    if (w == k1 >> 6 && (k1 & 63) != 63)
        b &= (UINT64_C(1) << ((k1 & 63) + 1)) - 1;
    return b;
}

/* The number of codes present below code k (0 <= k <= SCREEN_CODES): a present code's slot. */
static inline uint32_t screen_rank(const pair_screen *sc, long k)
{
    const uint64_t below = (UINT64_C(1) << (k & 63)) - 1;
    return sc->before[k >> 6] + ((k & 63) ? (uint32_t)__builtin_popcountll(sc->bits[k >> 6] & below) : 0u);
}

/* What one row test of pair_screen_build reads. */
typedef struct screen_row_ctx {
    pair_screen *sc;
    const double *b;
    const double (*n)[3];
    const int *order;
    const double *away_off, *base;
    double delta, best;
    const uint8_t *keep;
    unsigned lmin;
    int use_max;
} screen_row_ctx;

/* The level of value code c at pixel k (visiting position) with the current y pair: the least
 * squared chord over the decodes with the entries whose intervals hold the value, as a bound of the
 * squared angle, at least the pixel's theta0^2, then 255 / 0 against the incumbent (max metric) or
 * the steps of delta above base (sum). */
static unsigned screen_level(const screen_row_ctx *x, long c, int k, uint64_t *work)
{
    const pair_screen *sc = x->sc;
    const int p = x->order[k];
    double c2 = INFINITY;
    for (int d = 0; d < sc->nval[c]; ++d)
        for (unsigned f = sc->jm[c][k]; f; f &= f - 1) {
            double t = decode_chord2(sc->val[c][d], x->b[__builtin_ctz(f)], x->n[p]);
            c2 = t < c2 ? t : c2;
            ++*work;
        }
    double g = chord2_angle2_lower(c2);
    *work += 2;
    g = g > x->away_off[k] ? g : x->away_off[k];
    unsigned lvl;
    if (x->use_max)
        lvl = g >= x->best ? 255 : 0;
    else {
    double r = x->delta > 0.0 ? (g - x->base[k]) / x->delta * (1.0 - 1e-9) : 0.0;
    lvl = r <= 0.0 ? 0 : (r >= 254.0 ? 254 : (unsigned)r);
    }
    return lvl;
}

/* Whether row i can still beat the incumbent with the current y pair (pair_screen_build's phase 2):
 * screen_levels with the levels computed so far (a level not computed yet counts 0: base_p alone, a
 * valid bound); unless that rules the row out, its values' missing levels (each computed once per y
 * pair) one pixel at a time in visiting order, the row's least level at that pixel and its level sum
 * updated after each: the levels only rise, so the row is ruled out exactly when the test with every
 * level computed would rule it out, usually after a pixel or two (issue 13: computing every missing
 * level of the row at once was most of the screen's time on the arcs and cones pointing away). */
static int screen_row(const screen_row_ctx *x, size_t i, uint64_t *work)
{
    pair_screen *sc = x->sc;
    const uint16_t *code = sc->xcode[i];
    const int use_max = x->use_max;
    unsigned sum;
    uint8_t least[16]; /* per pixel the row's least level so far, computed or not (0) */
    ++*work;
    if (screen_levels(sc, code, x->keep, least, &sum) || (!use_max && sum >= x->lmin))
        return 0;
    unsigned todo = 0;
    for (int e = 0; e < 8; ++e)
        todo |= (unsigned)(sc->marked[code[e]] & ~sc->done[code[e]]);
    for (; todo; todo &= todo - 1) {
        const int k = __builtin_ctz(todo);
        /* before: least[k] (todo holds marked pixels only, which keep unmasked; the levels computed
         * at earlier pixels are other columns, and a repeated code's new level only rises above the
         * 0 already counted) */
        const unsigned before = least[k];
        unsigned after = 255;
        for (int e = 0; e < 8; ++e) {
            const long c = code[e];
            if ((sc->marked[c] >> k) & 1 && !((sc->done[c] >> k) & 1)) {
                sc->lv[c][k] = (uint8_t)screen_level(x, c, k, work);
                sc->done[c] |= (uint16_t)(1u << k);
            }
            after = sc->lv[c][k] < after ? sc->lv[c][k] : after;
        }
        ++*work;
        if (after == 255)
            return 0;
        sum += after - before;
        if (!use_max && sum >= x->lmin)
            return 0;
    }
    return 1;
}

/* Whether code[e] repeats one of code[0 .. e). */
static inline int screen_repeat(const uint16_t code[8], int e)
{
    for (int f = 0; f < e; ++f)
        if (code[f] == code[e])
            return 1;
    return 0;
}

/* Records the lists a screen's rows and columns stand for (pair_screen_remap reads them). */
static void screen_record_lists(pair_screen *sc, const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl, size_t ny)
{
    for (size_t i = 0; i < nx; ++i)
        sc->xpair[i] = xl[i].pair;
    for (size_t j = 0; j < ny; ++j)
        sc->ypair[j] = yl[j].pair;
    sc->nrows = nx;
    sc->ncols = ny;
}

/* Builds the screen of rows x[0 .. nx) against y[0 .. ny) (y sides ys, pixels in `order`) at incumbent
 * best: 1 if built, 0 if not (a value code with more than two doubles, more passes than the screen
 * holds, or the work limit reached; then the caller enumerates without it). */
static int pair_screen_build(pair_screen *sc, const double n[16][3], const int order[16], unsigned loose,
                             const away_info *aw, const double away_off[16], int use_max, double best,
                             const double (*pal)[8], sol_bc4_precision precision, const sol_nm_pair *xl, size_t nx,
                             const sol_nm_pair *yl, size_t ny, const channel_side *ys, uint64_t *work,
                             uint64_t limit)
{
    const double half_q = precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5;
    const long top = lround(2.0 * half_q);
    /* the rows to test, sum over y pairs of the x prefix whose combined score leaves room (both lists
     * sorted by score, so the prefix shrinks as j grows): beyond SCREEN_TESTS_MAX the screen would
     * cost more than the enumeration it replaces (the cones pointing away: 16493 x 4000 pairs of
     * which the enumeration meets 12190). The count is an upper bound of the rows phase 2 tests:
     * with a selective pixel it tests only the rows holding that pixel's marked codes. The limit was
     * 2^23 until issue 13's survey measured its slowest block, away-cone2 at 0.01 rad with the sum
     * metric (16356 x 3720 pairs, 5.3e7 counted): the screen builds in 14-16 ms and the enumeration
     * after it takes 20 ms instead of 70 (102 -> 75 ms a block, 16-bit and float decoders, same
     * answer); no other survey block counts between 2^23 and 2^26, and blocks of the benchmark maps
     * never reach the screen (no rim pixels). */
    size_t tests = 0;
    for (size_t j = 0, m = nx; j < ny && tests <= SCREEN_TESTS_MAX; ++j) {
        while (m > 0 && !(combine(xl[m - 1].score, yl[j].score, use_max) * (1.0 - BOUND_SLACK) < best))
            --m;
        tests += m;
    }
    *work += nx + ny;
    if (tests > SCREEN_TESTS_MAX)
        return 0;
    memset(sc->bits, 0, sizeof sc->bits);
    memset(sc->seen, 0, sizeof sc->seen);
    memset(sc->rstamp, 0, nx * sizeof *sc->rstamp);
    sc->rgen = 0;
    /* the codes present (xcode holds the codes until the slots are known), then their ranks */
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e) {
            const long k = lround((pal[xl[i].pair][e] + 1.0) * half_q);
            sc->bits[k >> 6] |= UINT64_C(1) << (k & 63);
            sc->xcode[i][e] = (uint16_t)k;
        }
    uint32_t nid = 0; /* slots in use */
    for (long w = 0; w < SCREEN_CODES / 64; ++w) {
        sc->before[w] = nid;
        nid += (uint32_t)__builtin_popcountll(sc->bits[w]);
    }
    sc->before[SCREEN_CODES / 64] = nid;
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e) {
            const double v = pal[xl[i].pair][e];
            const long k = sc->xcode[i][e], id = screen_rank(sc, k);
            const int added = value_code_add(sc->seen, sc->nval, sc->val, k, id, v);
            if (added < 0)
                return 0;
            if (added == 1) { /* a new code: its slot's state starts clear */
                sc->stamp[id] = 0;
                sc->done[id] = sc->marked[id] = 0;
                memset(sc->jm[id], 0, 16);
                memset(sc->lv[id], 255, 16);
            }
            sc->xcode[i][e] = (uint16_t)id;
        }
    *work += 8 * nx;
    /* the rows of each code (a counting sort; a row's repeated code counted once) */
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e)
            sc->cnum[sc->xcode[i][e]] = 0;
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e)
            sc->cnum[sc->xcode[i][e]] += !screen_repeat(sc->xcode[i], e);
    uint32_t acc = 0;
    for (uint32_t id = 0; id < nid; ++id) {
        sc->cstart[id] = acc;
        acc += sc->cnum[id];
        sc->cnum[id] = 0;
    }
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e)
            if (!screen_repeat(sc->xcode[i], e)) {
                const uint16_t k = sc->xcode[i][e];
                sc->crow[sc->cstart[k] + sc->cnum[k]++] = (uint32_t)i;
            }
    *work += 8 * nx;
    double xq[16][3]; /* per visiting position: the pixel's normal with x and y swapped */
    ball_lines xball[16];
    for (int k = 0; k < 16; ++k) {
        const int p = order[k];
        xq[k][0] = n[p][1];
        xq[k][1] = n[p][0];
        xq[k][2] = n[p][2];
        ball_lines_polar(&xball[k], xq[k]);
    }
    size_t passes = 0;
    for (size_t j = 0; j < ny; ++j) {
        sc->jstart[j] = (uint32_t)passes;
        if (*work >= limit) {
            return 0;
        }
        /* the rows whose combined score leaves room (x sorted by score): x[0 .. m) */
        size_t lo = 0, hi = nx;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (combine(xl[mid].score, yl[j].score, use_max) * (1.0 - BOUND_SLACK) < best)
                lo = mid + 1;
            else
                hi = mid;
        }
        const size_t m = lo;
        if (m == 0)
            continue;
        const double *b = pal[yl[j].pair];
        const channel_side *y = &ys[j];
        double base[16], sb = 0.0;
        int dead = 0;
        for (int k = 0; k < 16 && !use_max; ++k) {
            const int p = order[k];
            if ((aw->mask >> p) & 1) {
                base[k] = (away_off[k] + y->lt[k]) * (1.0 - 1e-12);
            } else {
                double t = (loose >> p) & 1 ? sol_nm_loose_term(b, n[p][1])
                                            : (y->m1[k] < n[p][2] * n[p][2] ? y->m1[k] : n[p][2] * n[p][2]);
                t = t * (1.0 - 3e-6) - 5e-15;
                base[k] = t > 0.0 ? t : 0.0;
            }
            sb += base[k];
        }
        double delta = 0.0;
        unsigned lmin = 0;
        if (!use_max) {
            if (sb * (1.0 - 1e-12) >= best)
                continue;
            /* lmin: the least level sum that rules a candidate out; levels are at most 254, so a sum of
             * 16 * 255 is never reached (no rule from the sum where the slack is within rounding) */
            delta = (best - sb) / 254.0;
            if (delta > 0.0) {
                for (lmin = 254; lmin > 0 && (sb + delta * (lmin - 1)) * (1.0 - 1e-12) >= best; --lmin)
                    ;
                while (lmin < 16 * 255 && !((sb + delta * lmin) * (1.0 - 1e-12) >= best))
                    ++lmin;
            } else {
                lmin = 16 * 255;
            }
        }
        if (++sc->gen == 0) { /* the stamps' wrap-around: forget them all */
            memset(sc->stamp, 0, sizeof sc->stamp);
            sc->gen = 1;
        }
        uint32_t ntouched = 0;
        int npx = 0, pk[16]; /* the constrained pixels (visiting positions), in visiting order */
        size_t inc[16] = {0}; /* per pixel: the rows holding its marked codes, with repeats */
        /* phase 1: per constrained pixel and y entry b_e, mark the x value codes inside the entry's
         * intervals (bit e of jm[code][k]) */
        for (int k = 0; k < 16 && !dead; ++k) {
            const int p = order[k];
            const double T = (use_max ? best : best - sb + base[k]) * (1.0 + 1e-9);
            double q[3], R2;
            int ball = pixel_ball(aw, n, p, T, q, &R2);
            if (ball == 0)
                continue;
            if (ball < 0) {
                dead = 1;
                break;
            }
            pixel_chord_ball(n, p, T, q, &R2); /* pixel_ball decided only whether the pixel takes part */
            /* the ball's intervals of x values (ball_intervals_exact's, one entry at a time; its
             * target is the pixel's normal, x and y swapped, whatever the y pair: polar part hoisted) */
            ball_lines bl = xball[k];
            int any = 0, unconstrained = ball_lines_radius(&bl, R2, 1e-9) < 0; /* it constrains nothing */
            for (int e = 0; e < 8 && !unconstrained; ++e) {
                int dup = 0;
                for (int f = 0; f < e && !dup; ++f)
                    dup = b[f] == b[e];
                if (dup)
                    continue;
                double ilo[16], ihi[16];
                const int cnt = ball_lines_value(&bl, b[e], 1, ilo, ihi, 0);
                for (int u = 0; u < cnt; ++u) {
                    long k0, k1;
                    interval_codes(ilo[u], ihi[u], half_q, top, &k0, &k1);
                    if (k0 > k1)
                        continue;
                    /* the slots of the codes present in [k0, k1], ascending (the codes' order) */
                    const uint32_t s0 = screen_rank(sc, k0), s1 = screen_rank(sc, k1 + 1);
                    for (uint32_t code = s0; code < s1; ++code) {
                        if (sc->stamp[code] != sc->gen) {
                            sc->stamp[code] = sc->gen;
                            sc->touched[ntouched++] = code;
                        }
                        sc->jm[code][k] |= (uint8_t)(1u << e);
                        if (!((sc->marked[code] >> k) & 1))
                            inc[k] += sc->cnum[code];
                        sc->marked[code] |= (uint16_t)(1u << k);
                        sc->lv[code][k] = 0;
                    }
                    any |= s1 > s0;
                    *work += s1 - s0;
                }
            }
            if (unconstrained) { /* undo its marks: it counts base only */
                inc[k] = 0;
                for (uint32_t t = 0; t < ntouched; ++t) {
                    sc->jm[sc->touched[t]][k] = 0;
                    sc->marked[sc->touched[t]] &= (uint16_t)~(1u << k);
                    sc->lv[sc->touched[t]][k] = 255;
                }
                continue;
            }
            if (!any) {
                dead = 1;
                break;
            }
            pk[npx++] = k;
        }
        /* phase 2: per row, the least level per pixel of its 8 values and their sum (screen_levels);
         * a level not computed yet counts 0 (base_p alone: a valid bound), so a row that this rules out
         * needs nothing more; otherwise its values' missing levels are computed (once per y pair: the
         * decodes with the entries whose intervals hold the value) and the row tested again */
        uint8_t keep[16];
        for (int k = 0; k < 16; ++k)
            keep[k] = 0;
        for (int h = 0; h < npx; ++h)
            keep[pk[h]] = 255;
        /* a row can pass only if it holds a code marked for every constrained pixel (an unmarked code
         * keeps level 255 there): with a selective pixel, only the rows of its marked codes are tested
         * (each once, in any order: the rows' passing y positions are gathered per row below) */
        int sel = -1;
        for (int h = 0; h < npx; ++h)
            if (sel < 0 || inc[pk[h]] < inc[sel])
                sel = pk[h];
        const int indexed = sel >= 0 && inc[sel] < m;
        if (indexed && ++sc->rgen == 0) {
            memset(sc->rstamp, 0, sizeof sc->rstamp);
            sc->rgen = 1;
        }
        const screen_row_ctx rc = {sc, b, n, order, away_off, base, delta, best, keep, lmin, use_max};
        for (uint32_t t = 0; indexed && t < ntouched && passes != SIZE_MAX && !dead; ++t) {
            const uint32_t c = sc->touched[t];
            if (!((sc->marked[c] >> sel) & 1))
                continue;
            const uint32_t *rows = sc->crow + sc->cstart[c];
            ++*work;
            for (uint32_t u = 0; u < sc->cnum[c] && rows[u] < m; ++u) {
                const uint32_t i = rows[u];
                if (sc->rstamp[i] == sc->rgen)
                    continue;
                sc->rstamp[i] = sc->rgen;
                if (!screen_row(&rc, i, work))
                    continue;
                if (passes == SCREEN_PASS_MAX) {
                    passes = SIZE_MAX;
                    break;
                }
                sc->row[passes++] = (uint32_t)i;
            }
        }
        for (size_t i = 0; !indexed && i < m && !dead; ++i) {
            if (!screen_row(&rc, i, work))
                continue;
            if (passes == SCREEN_PASS_MAX) {
                passes = SIZE_MAX;
                break;
            }
            sc->row[passes++] = (uint32_t)i;
        }
        for (uint32_t t = 0; t < ntouched; ++t) {
            const uint32_t c = sc->touched[t];
            memset(sc->jm[c], 0, 16);
            memset(sc->lv[c], 255, 16);
            sc->done[c] = sc->marked[c] = 0;
        }
        if (passes == SIZE_MAX)
            return 0;
    }
    sc->jstart[ny] = (uint32_t)passes;
    screen_record_lists(sc, xl, nx, yl, ny);
    /* per row, its passing y positions in increasing order */
    memset(sc->start, 0, (nx + 1) * sizeof *sc->start);
    for (size_t t = 0; t < passes; ++t)
        ++sc->start[sc->row[t] + 1];
    for (size_t i = 0; i < nx; ++i)
        sc->start[i + 1] += sc->start[i];
    for (size_t j = 0; j < ny; ++j)
        for (uint32_t t = sc->jstart[j]; t < sc->jstart[j + 1]; ++t)
            sc->col[sc->start[sc->row[t]]++] = (uint32_t)j;
    for (size_t i = nx; i > 0; --i)
        sc->start[i] = sc->start[i - 1];
    sc->start[0] = 0;
    *work += 2 * passes;
    return 1;
}

/* Carries a built screen over to reduced lists instead of building it again: xl[0 .. nx) and
 * yl[0 .. ny) the lists after a reduction (value_reduce, sol_nm_couple_reduce), the screen's first
 * `skip` rows already enumerated. Sound: the reductions only drop pairs (filters, and merges that keep
 * the first of each class) and keep the order of the rest, so each remaining row and column has a
 * place in the screen; every candidate the screen rules out has an objective at or above the
 * incumbent it was built at, so at or above every later (lower) incumbent - it keeps passing a
 * superset of the candidates that can still win, and the enumeration, which replaces its incumbent
 * only by a strictly lower objective, returns the same block. Returns 1 with the rows renumbered
 * from xl[0] and the columns from yl[0] (each row's passing columns still ascending: the map is
 * increasing), or 0 if the lists are not such subsequences of the screen's (then nothing is left to
 * read and the caller builds the screen again). Work: 1 per old column and row, 1 per pass read.
 * (issue 13: on a cone pointing away the incumbent fell nine times by a few 1e-7 relative, each fall
 * a reduction that dropped under 2% of the pairs and a screen built again - most of the block's time.) */
static int pair_screen_remap(pair_screen *sc, size_t skip, const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl,
                             size_t ny, uint64_t *work)
{
    const uint32_t drop = UINT32_MAX;
    size_t k = 0;
    for (size_t j = 0; j < sc->ncols; ++j)
        sc->ymap[j] = k < ny && yl[k].pair == sc->ypair[j] ? (uint32_t)k++ : drop;
    if (k != ny || skip > sc->nrows)
        return 0;
    /* rows in order; a kept row's new index never exceeds its old one, and its columns are written
     * at or before where they are read, so the compaction runs in place */
    uint32_t lo = sc->start[skip], w = 0;
    size_t kn = 0;
    for (size_t r = skip; r < sc->nrows; ++r) {
        const uint32_t hi = sc->start[r + 1];
        if (kn < nx && xl[kn].pair == sc->xpair[r]) {
            sc->start[kn] = w;
            for (uint32_t t = lo; t < hi; ++t)
                if (sc->ymap[sc->col[t]] != drop)
                    sc->col[w++] = sc->ymap[sc->col[t]];
            ++kn;
        }
        *work += 1 + (hi - lo);
        lo = hi;
    }
    *work += sc->ncols;
    if (kn != nx)
        return 0;
    sc->start[nx] = w;
    screen_record_lists(sc, xl, nx, yl, ny);
    return 1;
}

/* ---- the pixel floor (max metric; issue 13: blocks decided by one pixel's best decode) ----
 *
 * With the max metric a candidate (A, B) beats the incumbent E only if EVERY pixel's term is below E.
 * Pixel p's term is f_p(a_i, b_j) = decoded_angle(a_i, b_j, n_p)^2 for the index pair (i, j) that
 * sol_nm_bc5_best_pixel_index picks: whichever pair it picks, the term is that function of the decode's two
 * VALUES and n_p alone (sol_nm_bc5_joint_objective computes it so), and the values lie in Vx and Vy, the distinct
 * values of the x and y lists' palettes (a candidate that can beat E has both pairs in the lists: the
 * lists only ever lose pairs that cannot). So if for one pixel p
 *     f_p(a, b) >= E   for every a in Vx and b in Vy,
 * no candidate's objective is below E: the incumbent is optimal, and since the enumeration replaces
 * its incumbent only by a strictly lower objective, the incumbent is also what the enumeration would
 * return (same block, same tie rule: no candidate is skipped that could have replaced it). This
 * decides the blocks whose optimum is one pixel's best lattice decode: a pixel pointing away takes
 * the decode whose rim direction is nearest its own, the other pixels have room, and the lists keep
 * thousands of pairs each, with as many exact ties of that pixel's term (issue 13's last work-limited
 * block: 14732 x 36093 pairs).
 * The test of pixel p runs over Vx; for each a, pixel_y_intervals gives the intervals of b whose
 * decode (a, b) lies in pixel p's ball for the budget E (pixel_ball: |u - n_p|^2 <= E as dN >= chord,
 * or for a pixel pointing away |u - m_p|^2 <= (E - theta0^2) / k, the rim bound above; both widened
 * against rounding), a superset of {b : f_p(a, b) < E}; each b of Vy in them is bounded below by
 * angle2_lower_bound (<= f_p) and, where that is below E, f_p is computed exactly, as
 * sol_nm_bc5_joint_objective does: one f_p(a, b) < E and the pixel cannot decide. The pixels tested are those
 * whose own term in the incumbent is E (the others have a decode below E: the incumbent's).
 * Values are kept by their codes as in the pair screen (K = round((v + 1) Q / 2), at most two
 * doubles per code, else no test). Work: 8 per x pair and y pair read, 1 per x value, 1 per y code
 * looked at, 2 per lower bound, 32 per exact angle (a sixteenth of an exact evaluation). */
typedef struct value_codes {
    uint64_t bits[SCREEN_CODES / 64];
    double val[SCREEN_CODES][2];
    uint8_t nval[SCREEN_CODES];
} value_codes;

enum { FLOOR_POINTS = 8, FLOOR_TRIES = 4096 };

typedef struct pixel_floor {
    value_codes v[2]; /* the x and y lists' values */
    double half_q;
    /* floor_scan's least term below the incumbent and up to FLOOR_POINTS decodes attaining it (npts;
     * FLOOR_POINTS + 1 if more) */
    double least, pts[FLOOR_POINTS][2];
    int npts;
    uint8_t ymark[65536]; /* floor_first: bit k where the y list's pair holds point k's y value */
} pixel_floor;

/* The distinct values of list[0 .. n) by code; 0 if a code holds more than two doubles. */
static int value_codes_init(value_codes *vc, const sol_nm_pair *list, size_t n, const double (*pal)[8], double half_q)
{
    memset(vc->bits, 0, sizeof vc->bits);
    for (size_t i = 0; i < n; ++i) {
        PREFETCH_PAIR(pal, list, i, n);
        for (int e = 0; e < 8; ++e) {
            double v = pal[list[i].pair][e];
            long k = lround((v + 1.0) * half_q);
            if (value_code_add(vc->bits, vc->nval, vc->val, k, k, v) < 0)
                return 0;
        }
    }
    return 1;
}

/* The value sets of the lists xl[0 .. nx), yl[0 .. ny): 1, or 0 if a code holds more than two
 * doubles (then the floor is not used). */
static int pixel_floor_init(pixel_floor *pf, const double (*pal)[8], sol_bc4_precision precision,
                            const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl, size_t ny, uint64_t *work)
{
    pf->half_q = precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5;
    *work += 8 * (nx + ny);
    return value_codes_init(&pf->v[0], xl, nx, pal, pf->half_q) && value_codes_init(&pf->v[1], yl, ny, pal, pf->half_q);
}

/* 1 if f_p(a, b) >= best for every a, b of the value sets (pixel p decides the block), else 0 (or
 * -1: the ball constrains nothing). least = 0: stops at the first decode below best; least = 1: scans
 * them all, leaving in pf the least term below best and the decodes attaining it. */
static int floor_scan(pixel_floor *pf, const double n[16][3], const away_info *aw, int p, double best, int least,
                      uint64_t *work)
{
    pf->least = best;
    pf->npts = 0;
    double q[3], R2;
    int ball = pixel_ball(aw, n, p, best * (1.0 + 1e-9), q, &R2);
    if (ball < 0)
        return 1; /* the pixel's floor theta0^2 is above the budget: no decode reaches it */
    if (ball == 0)
        return -1;
    pixel_chord_ball(n, p, best * (1.0 + 1e-9), q, &R2); /* the exact ball (pixel_ball: whether p takes part) */
    const double half_q = pf->half_q;
    const long top = lround(2.0 * half_q);
    const value_codes *vx = &pf->v[0], *vy = &pf->v[1];
    ball_lines bl; /* one ball for every x value (ball_intervals_exact's, one value at a time) */
    ball_lines_polar(&bl, q);
    const int unconstrained = ball_lines_radius(&bl, R2, 1e-9) < 0;
    for (long w = 0; w <= top >> 6; ++w)
        for (uint64_t xbits = vx->bits[w]; xbits; xbits &= xbits - 1) {
            const long c = 64 * w + __builtin_ctzll(xbits);
            for (int d = 0; d < vx->nval[c]; ++d) {
                const double a = vx->val[c][d];
                double lo[16], hi[16];
                const int cnt = unconstrained ? -1 : ball_lines_value(&bl, a, 1, lo, hi, 0);
                ++*work;
                if (cnt < 0)
                    return -1; /* the ball constrains nothing */
                for (int u = 0; u < cnt; ++u) {
                    long k0, k1;
                    interval_codes(lo[u], hi[u], half_q, top, &k0, &k1);
                    for (long v = k0 >> 6; v <= k1 >> 6 && k0 <= k1; ++v) {
                        ++*work;
                        for (uint64_t bits = bits_in_range(vy->bits, v, k0, k1); bits; bits &= bits - 1) {
                            const long k = 64 * v + __builtin_ctzll(bits);
                            for (int f = 0; f < vy->nval[k]; ++f) {
                                const double b = vy->val[k][f];
                                *work += 2;
                                if (angle2_lower_bound(a, b, n[p]) > pf->least)
                                    continue;
                                *work += 32;
                                const double e = decoded_angle(a, b, n[p]);
                                if (!(e * e < best))
                                    continue;
                                if (!least)
                                    return 0;
                                if (e * e < pf->least) {
                                    pf->least = e * e;
                                    pf->npts = 0;
                                }
                                if (e * e == pf->least) {
                                    if (pf->npts < FLOOR_POINTS) {
                                        pf->pts[pf->npts][0] = a;
                                        pf->pts[pf->npts][1] = b;
                                    }
                                    pf->npts += pf->npts <= FLOOR_POINTS;
                                }
                            }
                        }
                    }
                }
            }
        }
    return pf->least == best;
}

/* The first candidate in the enumeration's order (x list position i, then y list position j) whose
 * objective is pf->least, among those holding one of the decodes that attain it (pf->pts, all of
 * them: npts <= FLOOR_POINTS), after at most FLOOR_TRIES exact evaluations: 1 with *fi, *fj, else
 * 0. floor_scan's least term of one pixel is at most every candidate's objective (the max over
 * pixels of their terms), and a candidate attains it only if that pixel's chosen decode is one of
 * the points; so this candidate is the first of the lists whose objective is the least of all. */
static int floor_first(pixel_floor *pf, const double n[16][3], const double (*pal)[8], const sol_nm_pair *xl,
                       size_t nx, const sol_nm_pair *yl, size_t ny, size_t *fi, size_t *fj, uint64_t *candidates,
                       uint64_t *work)
{
    if (pf->npts < 1 || pf->npts > FLOOR_POINTS)
        return 0;
    for (size_t j = 0; j < ny; ++j) {
        unsigned m = 0;
        for (int k = 0; k < pf->npts; ++k)
            for (int e = 0; e < 8; ++e)
                m |= (unsigned)(pal[yl[j].pair][e] == pf->pts[k][1]) << k;
        pf->ymark[j] = (uint8_t)m;
    }
    *work += 8 * ny + 8 * nx;
    const double budget = nextafter(pf->least, INFINITY);
    int tries = 0;
    for (size_t i = 0; i < nx; ++i) {
        unsigned mx = 0;
        for (int k = 0; k < pf->npts; ++k)
            for (int e = 0; e < 8; ++e)
                mx |= (unsigned)(pal[xl[i].pair][e] == pf->pts[k][0]) << k;
        for (size_t j = 0; mx && j < ny; ++j) {
            if (!(pf->ymark[j] & mx))
                continue;
            if (tries++ == FLOOR_TRIES)
                return 0;
            ++*candidates;
            *work += 512;
            if (sol_nm_bc5_joint_objective(pal[xl[i].pair], pal[yl[j].pair], n, 1, budget, NULL, NULL) == pf->least) {
                *fi = i;
                *fj = j;
                return 1;
            }
        }
    }
    return 0;
}

/* At the set-up's incumbent (palettes a, b, objective best): 1 if a pixel whose term in it is best
 * decides the block (floor_scan); 2 if the first such pixel's least term is attained (floor_first:
 * *fi, *fj); else 0. */
static int pixel_floor_solve(pixel_floor *pf, const double n[16][3], const away_info *aw, const double (*pal)[8],
                             const double a[8], const double b[8], double best, const sol_nm_pair *xl, size_t nx,
                             const sol_nm_pair *yl, size_t ny, size_t *fi, size_t *fj, uint64_t *candidates,
                             uint64_t *work)
{
    int first = 1;
    for (int p = 0; p < 16; ++p) {
        int i, j;
        double e = sol_nm_bc5_best_pixel(a, b, n[p], &i, &j);
        *work += 32;
        if (!(e * e >= best))
            continue;
        int r = floor_scan(pf, n, aw, p, best, first, work);
        if (r == 1)
            return 1;
        if (r == 0 && first) {
            first = 0;
            if (floor_first(pf, n, pal, xl, nx, yl, ny, fi, fj, candidates, work))
                return 2;
        }
    }
    return 0;
}

/* Whether a pixel whose term in the incumbent (palettes a, b) is the incumbent's objective best decides
 * the block (floor_decides). */
static int pixel_floor_decides(pixel_floor *pf, const double n[16][3], const away_info *aw, const double a[8],
                               const double b[8], double best, uint64_t *work)
{
    for (int p = 0; p < 16; ++p) {
        int i, j;
        double e = sol_nm_bc5_best_pixel(a, b, n[p], &i, &j);
        *work += 32;
        if (e * e >= best && floor_scan(pf, n, aw, p, best, 0, work) == 1)
            return 1;
    }
    return 0;
}

/* ---- value-level usability of entries (rims and pixels pointing away) ----
 *
 * The loose channel bounds accept every pair holding an entry in a wide interval (any x in
 * [m / sqrt(1 + ...), reach] can be a clamped decode near the rim direction m, with SOME y), and the
 * equivalence key above counts every such entry as usable, so a smooth block pointing away keeps
 * tens of thousands of x pairs, each met by dozens of y pairs within a hair of the incumbent. But a
 * decode needs an actual y value: an x entry a can serve pixel p under the budget only if some value
 * b of the y list gives a decode (a, b) inside pixel p's ball (sol_nm_bc5_search_unit's per-pixel budget T_p:
 * the incumbent minus the other pixels' hemisphere bounds theta0^2 for the sum metric, the
 * incumbent for the max; the ball |u - n| <= sqrt(T_p), or |u - (m, 0)| <= sqrt((T_p - theta0^2) / k)
 * for a pixel pointing away, see "pixels pointing away"). pixel_y_intervals gives the y intervals of
 * that ball on the line x = a (a superset), and a bitmap of the y list's values (value_set, exact)
 * says whether any value lies in them: the entry is then "usable" for p. So
 *  - a pair of which no entry is usable for some pixel cannot beat the incumbent and is dropped
 *    (x against the y list's values, then y against the kept x values, and once more each way);
 *  - two pairs whose usable seeds and usable entries (palette order) are bit-identical on every
 *    pixel give every candidate the same objective whenever it can beat the incumbent (the argument
 *    of "equivalent anchor pairs" above, with this finer notion of usable; see seed_key), and are
 *    merged, then merged again by the budget-based key of that section.
 * The bounds' rounding allowances here are relative 1e-13 (budgets) and 1e-14 (cone cosines), not
 * the coupling filter's 1e-9: near the hemisphere bound the balls are microradians wide.
 * Only candidates that cannot beat the incumbent are removed, and of each merged class the first
 * in list order is kept, which is the one the enumeration would have met first: same result. */
#define VALUE_CODES 65536

/* The values of a list's pairs as integer codes: every palette value is K / Q exactly (Q = 65535 for
 * 8- and 16-bit decoders, whose values are k / 255 = 257 k / 65535 or k / 65535; Q = 35 * 255 = 8925
 * for exact decoders, whose entries are num / (7 * 255), num / (5 * 255) or codes / 255), so the
 * decoded 2 v - 1 maps back to K = round((d + 1) Q / 2) and a bitmap of the codes with ranks answers
 * "is a value in [lo, hi]" exactly (the range's code bounds are widened by 1e-6 code). */
typedef struct value_set {
    double half_q; /* Q / 2 */
    uint64_t bits[VALUE_CODES / 64];
    uint32_t before[VALUE_CODES / 64]; /* set codes in the words before */
} value_set;

static void value_set_init(value_set *s, const sol_nm_pair *list, size_t n, const double (*pal)[8],
                           sol_bc4_precision precision)
{
    s->half_q = precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5;
    memset(s->bits, 0, sizeof s->bits);
    for (size_t i = 0; i < n; ++i) {
        PREFETCH_PAIR(pal, list, i, n);
        for (int e = 0; e < 8; ++e) {
            long k = (long)((pal[list[i].pair][e] + 1.0) * s->half_q + 0.5); /* value_slot's exact code */
            s->bits[k >> 6] |= UINT64_C(1) << (k & 63);
        }
    }
    uint32_t c = 0;
    for (int w = 0; w < VALUE_CODES / 64; ++w) {
        s->before[w] = c;
        c += (uint32_t)__builtin_popcountll(s->bits[w]);
    }
}

/* Set codes among 0 .. k. */
static inline uint32_t value_rank(const value_set *s, long k)
{
    uint64_t m = (k & 63) == 63 ? ~UINT64_C(0) : (UINT64_C(1) << ((k & 63) + 1)) - 1;
    return s->before[k >> 6] + (uint32_t)__builtin_popcountll(s->bits[k >> 6] & m);
}

/* Whether a value of the set may lie in [lo, hi] (never a false "no"). */
static int value_set_any(const value_set *s, double lo, double hi)
{
    if (!(lo <= hi))
        return 0;
    double top = 2.0 * s->half_q, u = ceil((lo + 1.0) * s->half_q - 1e-6), v = floor((hi + 1.0) * s->half_q + 1e-6);
    long a = u <= 0.0 ? 0 : (long)u, b = v >= top ? (long)top : (long)v;
    if (a > b)
        return 0;
    return value_rank(s, b) > (a ? value_rank(s, a - 1) : 0);
}

/* Each pixel's ball: centre q, squared radius R2 (widened against rounding); `free`: pixels that
 * constrain nothing (R2 >= 4, or pointing straight away). */
typedef struct pixel_reach {
    unsigned free;
    double q[16][3], R2[16];
    int order[16], count; /* the constrained pixels, one per group of equal normals, smallest ball first */
    /* per channel c and constrained pixel p, value_usable's ball: q with channel c first (qc), its
     * cone (ball_lines_radius: a function of c and p alone, so set up once here instead of per value;
     * issue 13 deg-speed), and whether it constrains nothing (open) */
    double qc[2][16][3];
    ball_lines ball[2][16];
    unsigned open[2];
} pixel_reach;

/* pr's per-channel balls (pixel_reach above) for the pixels that are not free. */
static void pixel_reach_balls(pixel_reach *pr)
{
    for (int c = 0; c < 2; ++c) {
        pr->open[c] = 0;
        for (int p = 0; p < 16; ++p) {
            if ((pr->free >> p) & 1)
                continue;
            double *q = pr->qc[c][p];
            q[0] = pr->q[p][c];
            q[1] = pr->q[p][1 - c];
            q[2] = pr->q[p][2];
            const double rq = hypot(q[0], q[1]);
            /* the cone's cosine (1 + rq^2 - rc2) / (2 rq) carries a rounding error of a few 1e-16 / rq:
             * lowered by much more, but far less than the coupling filter's 1e-9, which would widen a
             * cone of a few microradians (near-ties at the hemisphere bound) to 4e-5 rad */
            pr->ball[c][p].q = q;
            if (ball_lines_radius(&pr->ball[c][p], pr->R2[p], 1e-14 + (rq > 0.0 ? 1e-15 / rq : 0.0)) < 0)
                pr->open[c] |= 1u << p;
        }
    }
}

/* Returns 0 if some pixel cannot meet its budget at all (then no candidate beats the incumbent). */
static int pixel_reach_init(pixel_reach *pr, const double n[16][3], const away_info *aw, const int group[16],
                            int use_max, double best)
{
    const double budget = best * (1.0 + 1e-13);
    double total = 0.0;
    for (int p = 0; p < 16; ++p)
        total += aw->off[p]; /* theta0^2 of the loose pixels pointing away, else 0 */
    pr->free = 0;
    pr->count = 0;
    for (int p = 0; p < 16; ++p) {
        double t = use_max ? budget : budget - (total - aw->off[p]) * (1.0 - 1e-13), R2 = t;
        if ((aw->mask >> p) & 1) {
            if (!(aw->w[p] > 0.0)) {
                pr->free |= 1u << p;
                continue;
            }
            R2 = (t - aw->off[p]) / aw->w[p];
            pr->q[p][0] = aw->m[0][p];
            pr->q[p][1] = aw->m[1][p];
            pr->q[p][2] = 0.0;
        } else {
            memcpy(pr->q[p], n[p], sizeof pr->q[p]);
        }
        if (R2 < 0.0)
            return 0;
        pr->R2[p] = R2 * (1.0 + 1e-9) + 1e-15;
        if (!(pr->R2[p] < 4.0)) {
            pr->free |= 1u << p;
            continue;
        }
        if (group[p] != p)
            continue;
        int k = pr->count++;
        for (; k > 0 && pr->R2[pr->order[k - 1]] > pr->R2[p]; --k)
            pr->order[k] = pr->order[k - 1];
        pr->order[k] = p;
    }
    pixel_reach_balls(pr);
    return 1;
}

/* Whether value v of channel c (0 = x, 1 = y) can serve pixel p with a value of the other channel's set. */
static int value_usable(double v, int c, const pixel_reach *pr, int p, const value_set *other)
{
    if ((pr->free >> p) & 1 || (pr->open[c] >> p) & 1)
        return 1;
    /* y intervals of x = v, or swapped (pixel_y_intervals of v eight times, its ball set up once) */
    double lo[16], hi[16];
    const int cnt = ball_lines_value(&pr->ball[c][p], v, 0, lo, hi, 0);
    for (int k = 0; k < cnt; ++k)
        if (value_set_any(other, lo[k], hi[k]))
            return 1;
    return 0;
}

/* Per value code (value_set): per pixel, whether usability is known and whether usable. */
typedef struct value_mask {
    uint32_t gen; /* the table's generation when filled (0: never) */
    uint16_t known, usable;
} value_mask;

typedef struct value_table {
    value_mask *slot; /* VALUE_CODES entries */
    uint32_t gen;
    int c;
    const pixel_reach *pr;
    const value_set *other;
    uint64_t *work;
} value_table;

static value_mask *value_slot(value_table *t, double v)
{
    value_mask *m = &t->slot[(long)((v + 1.0) * t->other->half_q + 0.5)]; /* the value's exact code */
    if (m->gen != t->gen)
        *m = (value_mask){t->gen, 0, 0};
    return m;
}

static inline int slot_usable(value_table *t, value_mask *s, double v, int p)
{
    unsigned bit = 1u << p;
    if (!(s->known & bit)) {
        s->known |= (uint16_t)bit;
        *t->work += 16;
        if (value_usable(v, t->c, t->pr, p, t->other))
            s->usable |= (uint16_t)bit;
    }
    return (s->usable & bit) != 0;
}

/* Drops the pairs of which no entry is usable for some constrained pixel; returns the count kept. */
static size_t usable_filter(sol_nm_pair *list, size_t count, const double (*pal)[8], value_table *t)
{
    size_t kept = 0;
    unsigned need = 0; /* the constrained pixels */
    for (int k = 0; k < t->pr->count; ++k)
        need |= 1u << t->pr->order[k];
    for (size_t i = 0; i < count; ++i) {
        PREFETCH_PAIR(pal, list, i, count);
        const double *a = pal[list[i].pair];
        value_mask *s[8];
        for (int e = 0; e < 8; ++e)
            s[e] = value_slot(t, a[e]);
        *t->work += 8;
        /* all 16 pixels at once, where the walk below would test nothing new: per pixel, the first
         * entry that is not known unusable (open: still undecided); if that one is known usable for
         * every constrained pixel that has one, the walk's answer is known (it passes iff no pixel
         * is left without one) and it would make no test, so it is skipped (the same tests, work and
         * table as the walk: it runs whenever some pixel's first such entry is unknown) */
        unsigned open = need, unknown = 0;
        for (int e = 0; e < 8; ++e) {
            unsigned stop = open & (~(unsigned)s[e]->known | s[e]->usable);
            unknown |= stop & ~(unsigned)s[e]->known;
            open &= ~stop;
        }
        if (!unknown) {
            if (!open)
                list[kept++] = list[i];
            continue;
        }
        int ok = 1;
        for (int k = 0; k < t->pr->count && ok; ++k) {
            int p = t->pr->order[k], hit = 0;
            for (int e = 0; e < 8 && !hit; ++e)
                hit = slot_usable(t, s[e], a[e], p);
            ok = hit;
        }
        if (ok)
            list[kept++] = list[i];
    }
    return kept;
}

/* The usable masks of a palette's entries (bit p: usable for pixel p), every pixel of each entry's
 * value made known (as the key below needs them all; the same tests and work as testing them one
 * pixel at a time), and each pixel's seed key: the seed entry's value if usable, else a marker: a
 * seed that is not usable starts sol_nm_bc5_best_pixel's scan from a decode outside the pixel's ball, which
 * every usable decode beats, so then only the usable entries' order decides the choice. (NaN bits:
 * never a palette value.) */
static void usable_masks(value_table *t, const double pal[8], const double tc[16], uint16_t m[8], uint64_t seed[16])
{
    for (int e = 0; e < 8; ++e) {
        value_mask *s = value_slot(t, pal[e]);
        for (int p = 0; s->known != 0xffffu && p < 16; ++p)
            slot_usable(t, s, pal[e], p);
        m[e] = s->usable;
    }
    int se[16];
    seed_entries(pal, tc, 16, se);
    for (int p = 0; p < 16; ++p)
        seed[p] = (m[se[p]] >> p) & 1 ? value_bits(pal[se[p]]) : UINT64_C(0x7ff8dead0000beef);
}

/* The key of a palette: per pixel its seed key and its usable entries' values in palette order.
 * Its hash (masks_hash) is a function of the key alone: the seed keys in pixel order, and the sum
 * over entries usable for some pixel of a mix of (value bits, mask), the mask being that of the
 * value (so the multiset of those is fixed by the key: an entry's value appears in the sequence of
 * every pixel of its mask). Equal keys give equal hashes; sol_nm_bc5_merge_classes keeps the first of each class
 * whatever the hash, so the classes and the list kept are those of the per-pixel walk. */

/* sol_nm_bc5_merge_equivalent's classes at a fraction of its cost (issue 13: on rims and blocks pointing away it
 * hashed 10^4 - 3 10^4 pairs per list, each over 16 pixels x 8 entries with a mix per usable entry,
 * 25-50 ms a block). An entry's usability for a pixel of the key (usable_entry) depends on its value
 * alone, so each value's mask over the key's distinct pixels (bit q: usable for k->t[q]) is computed
 * once, in a table of value codes (every palette value is K / Q exactly, see value_set), and a pair's
 * key is read from its 8 entries' masks and its seeds: the hash is masks_hash's (a function of the
 * key alone; sol_nm_bc5_merge_classes keeps the first pair of each class whatever the hash), the equality
 * mask_sequences_equal's, the same relation as sol_nm_bc5_pair_key_equal. So the same pairs are kept, in the
 * same order, as sol_nm_bc5_merge_equivalent keeps. */
typedef struct key_mask {
    uint32_t gen; /* the table's generation when filled (0: never) */
    uint16_t mask;
} key_mask;

typedef struct key_table {
    const channel_key *k;
    key_mask *slot; /* VALUE_CODES entries */
    uint32_t gen;
    double half_q; /* value_set's Q / 2 */
} key_table;

static void key_masks(key_table *kt, const double pal[8], uint16_t m[8], uint64_t seed[16])
{
    const channel_key *k = kt->k;
    for (int e = 0; e < 8; ++e) {
        key_mask *s = &kt->slot[(long)((pal[e] + 1.0) * kt->half_q + 0.5)]; /* the value's exact code */
        if (s->gen != kt->gen) {
            uint16_t u = 0;
            for (int q = 0; q < k->count; ++q)
                if (usable_entry(pal[e], k->t[q], k->loose[q], k->budget))
                    u |= (uint16_t)(1u << q);
            *s = (key_mask){kt->gen, u};
        }
        m[e] = s->mask;
    }
    int se[16];
    seed_entries(pal, k->t, k->count, se);
    for (int q = 0; q < k->count; ++q)
        seed[q] = value_bits(pal[se[q]]);
}

/* A kept pair's key (the seeds of the key's distinct pixels, its entries' masks). */
typedef struct pair_key {
    uint64_t seed[16];
    uint16_t m[8];
} pair_key;

/* Whether pairs of palettes pa, pb with keys ka, kb are equivalent (sol_nm_bc5_pair_key_equal): the same seeds
 * and, per pixel, the same usable values in palette order; at once when the usable entries sit at
 * the same places with the same values (then every pixel's sequence is the same). */
static int keys_equal(const double pa[8], const pair_key *ka, const double pb[8], const pair_key *kb, int count)
{
    if (memcmp(ka->seed, kb->seed, (size_t)count * sizeof ka->seed[0]) != 0)
        return 0;
    int e = 0;
    while (e < 8 && ka->m[e] == kb->m[e] && (!ka->m[e] || value_bits(pa[e]) == value_bits(pb[e])))
        ++e;
    return e == 8 || mask_sequences_equal(pa, ka->m, pb, kb->m, count);
}

/* A pair's key for merge_stored: its entries' masks m and per pixel its seed key (count pixels). */
typedef void (*pair_key_fn)(void *ctx, const double pal[8], uint16_t m[8], uint64_t seed[16]);
/* Asks for the memory pair_key_fn will read for palette pal (a hint: no result depends on it; may be NULL). */
typedef void (*pair_ahead_fn)(void *ctx, const double pal[8]);

/* sol_nm_bc5_merge_classes's walk (the same slots, hash tags and probing; work, if not NULL, charged 16 per
 * pair) for classes given by keys (key_fn; hash masks_hash, equality keys_equal over count pixels),
 * with each pair's key computed once and the kept pairs' keys stored (ws->kkey; where it cannot grow,
 * a kept pair's key is computed again): the same pairs kept, in the same order, as sol_nm_bc5_merge_classes with
 * a hash and an equality computing the keys afresh. */
static size_t merge_stored(sol_nm_pair *list, size_t count, const double (*pal)[8], pair_key_fn key_fn,
                           pair_ahead_fn ahead, void *ctx, int npix, search_workspace *ws, uint64_t *work)
{
    uint32_t *slots = ws->slots;
    const size_t size = slots_clear(slots, count);
    /* each pair's key and hash MERGE_LAG pairs before its probe, its first slot then asked for (issue
     * 13: the probe waited on the table, half of merge_stored's time). The keys are computed once
     * each, in list order, as before; key_fn's results and the work it charges do not depend on when
     * it runs (its tables fill per value, whatever the order), so the walk is the same. */
    enum { MERGE_LAG = 4, MERGE_RING = 8 }; /* the ring holds pairs i .. i + MERGE_LAG */
    pair_key ring[MERGE_RING];
    uint64_t rhash[MERGE_RING];
    size_t kept = 0;
    for (size_t j = 0; j < count + MERGE_LAG; ++j) {
        if (j < count) { /* the key of pair j */
            PREFETCH_PAIR(pal, list, j, count);
            if (ahead && j + PREFETCH_AHEAD / 2 < count) /* the tables key_fn reads for a pair further down */
                ahead(ctx, pal[list[j + PREFETCH_AHEAD / 2].pair]);
            pair_key *kj = &ring[j % MERGE_RING];
            if (work)
                *work += 16;
            key_fn(ctx, pal[list[j].pair], kj->m, kj->seed);
            rhash[j % MERGE_RING] = masks_hash(pal[list[j].pair], kj->m, kj->seed, npix);
            __builtin_prefetch(&slots[(size_t)rhash[j % MERGE_RING] & (size - 1)]);
        }
        if (j < MERGE_LAG)
            continue;
        const size_t i = j - MERGE_LAG; /* the probe of pair i */
        const double *a = pal[list[i].pair];
        const pair_key *key = &ring[i % MERGE_RING];
        pair_key other;
        const uint64_t hash = rhash[i % MERGE_RING];
        size_t h = (size_t)hash & (size - 1);
        uint32_t tag = slot_tag(hash);
        int dup = 0;
        for (; slots[h]; h = (h + 1) & (size - 1)) {
            if ((slots[h] & ~SLOT_POS) != tag)
                continue;
            size_t r = (slots[h] & SLOT_POS) - 1;
            const double *b = pal[list[r].pair];
            const pair_key *kb = r < ws->kkey_cap ? &ws->kkey[r] : &other;
            if (r >= ws->kkey_cap)
                key_fn(ctx, b, other.m, other.seed);
            if (keys_equal(b, kb, a, key, npix)) {
                dup = 1;
                break;
            }
        }
        if (dup)
            continue;
        if (kept >= ws->kkey_cap && kept < 65536) { /* room for the key of the pair kept next */
            size_t cap = ws->kkey_cap ? 2 * ws->kkey_cap : 1024;
            pair_key *grown = realloc(ws->kkey, cap * sizeof *grown);
            if (grown) {
                ws->kkey = grown;
                ws->kkey_cap = cap;
            }
        }
        if (kept < ws->kkey_cap)
            ws->kkey[kept] = *key;
        list[kept] = list[i];
        slots[h] = tag | (uint32_t)++kept;
    }
    return kept;
}

static void keyed_key_fn(void *ctx, const double pal[8], uint16_t m[8], uint64_t seed[16])
{
    key_masks(ctx, pal, m, seed);
}

static void keyed_ahead_fn(void *ctx, const double pal[8])
{
    const key_table *kt = ctx;
    for (int e = 0; e < 8; ++e)
        __builtin_prefetch(&kt->slot[(long)((pal[e] + 1.0) * kt->half_q + 0.5)]);
}

/* sol_nm_bc5_merge_equivalent(list, count, k, pal, ws->slots): the same result (above), through merge_stored;
 * sol_nm_bc5_merge_equivalent itself if the table cannot be allocated. */
static size_t merge_keyed(sol_nm_pair *list, size_t count, const channel_key *k, const double (*pal)[8],
                          sol_bc4_precision precision, search_workspace *ws)
{
    if (!ws->ktab && !(ws->ktab = calloc(VALUE_CODES, sizeof *ws->ktab)))
        return sol_nm_bc5_merge_equivalent(list, count, k, pal, ws->slots);
    if (++ws->kgen == 0) { /* wrapped: clear the generations */
        memset(ws->ktab, 0, VALUE_CODES * sizeof *ws->ktab);
        ws->kgen = 1;
    }
    key_table kt = {k, ws->ktab, ws->kgen, precision == SOL_BC4_INTERP_FLOAT ? 4462.5 : 32767.5};
    return merge_stored(list, count, pal, keyed_key_fn, keyed_ahead_fn, &kt, k->count, ws, NULL);
}

/* sol_nm_bc5_merge_equivalent with the usable entries of the table (targets tc: the channel's components of n):
 * sol_nm_bc5_merge_classes with usable_key_hash and usable_key_equal, through merge_stored (the same keys, the
 * same slot_usable tests and work: a kept pair's values were all made known by its own key). */
typedef struct usable_ctx {
    value_table *t;
    const double *tc;
} usable_ctx;

static void usable_key_fn(void *ctx, const double pal[8], uint16_t m[8], uint64_t seed[16])
{
    usable_ctx *u = ctx;
    usable_masks(u->t, pal, u->tc, m, seed);
}

static size_t merge_usable(sol_nm_pair *list, size_t count, const double (*pal)[8], value_table *t,
                           const double tc[16], search_workspace *ws)
{
    usable_ctx u = {t, tc};
    return merge_stored(list, count, pal, usable_key_fn, NULL, &u, 16, ws, t->work);
}

/* The open-addressing set of the distinct entry values of list xl (slot 8 i + e + 1 holds entry e
 * of pair xl[i]; 0 is empty): 1 if a value with bits key is in it, else 0 and *h the empty slot
 * where it goes. */
static int distinct_value_slot(const uint32_t *slots, size_t size, const double (*pal)[8], const sol_nm_pair *xl,
                               uint64_t key, size_t *h)
{
    size_t k = (size_t)mix64(0, key) & (size - 1);
    for (; slots[k]; k = (k + 1) & (size - 1))
        if (value_bits(pal[xl[(slots[k] - 1) >> 3].pair][(slots[k] - 1) & 7]) == key)
            return 1;
    *h = k;
    return 0;
}

/* ---- blocks of 16 equal normals at a rim or pointing away ----
 *
 * Every pixel then picks the same decode, so a candidate's objective is that of the best decode
 * (a, b) in its 8 x 8 grid, and thousands of x pairs holding the best a meet thousands of y pairs
 * holding the best b: exact ties the candidate loop would have to evaluate one by one. Instead the
 * search finds e* = the least angle decoded_angle(a, b) over every value a of the x list and b of
 * the y list (the lists hold every pair that can beat the incumbent): per distinct a, only the b of
 * the y list inside the coupling filter's intervals for the per-pixel budget (the incumbent's e^2,
 * shrinking as e* improves) can beat it, and those are evaluated exactly. Each pixel's error in any
 * candidate is the angle of one of these decodes, so no candidate's objective is below L = the
 * objective of 16 pixels of error e* (computed in the same floating-point order: exact). The first
 * x pair and the first y pair of the lists holding a* and b* are the answer if their objective is
 * L (it is unless their grid holds another decode of larger cosine but not smaller angle, a
 * rounding-level tie; then the candidate loop runs as usual). If L is not below the incumbent, no
 * candidate beats it and the incumbent is the answer (px, py untouched), as in the enumeration. */
static int equal_block_solve(const double n[16][3], const sol_nm_pair *xl, size_t nx, const sol_nm_pair *yl,
                             size_t ny, const double (*pal)[8], const y_index *yix, const away_info *aw,
                             int use_max, double best, uint32_t *slots, int *px, int *py, double *value,
                             uint64_t *evals)
{
    const int away = aw->mask & 1;
    if (away && !(aw->w[0] > 0.0))
        return 0; /* (0, 0, -1): the hemisphere bound decides it */
    double q[3] = {away ? aw->m[0][0] : n[0][0], away ? aw->m[1][0] : n[0][1], away ? 0.0 : n[0][2]};
    double e_best = INFINITY, a_star = 0.0, b_star = 0.0;
    double t = (use_max ? best : best / 16.0) * (1.0 + 1e-9);
    const size_t size = 2 * 65536; /* slots: a hash set of the distinct values of a */
    memset(slots, 0, size * sizeof *slots);
    size_t distinct = 0;
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e) {
            double a = pal[xl[i].pair][e];
            size_t h;
            if (distinct_value_slot(slots, size, pal, xl, value_bits(a), &h))
                continue;
            if (++distinct > size / 2)
                return 0;
            slots[h] = (uint32_t)(8 * i + (size_t)e + 1);
            double r2 = away ? (t - aw->off[0]) / aw->w[0] : t;
            if (r2 < 0.0)
                return 0; /* cannot happen: the incumbent meets its own budget */
            double a8[8] = {a, a, a, a, a, a, a, a}, lo[16], hi[16];
            int cnt = pixel_y_intervals(a8, q, r2 * (1.0 + 1e-9) + 1e-15, 1e-9, lo, hi);
            if (cnt < 0)
                return 0;
            for (int k = 0; k < cnt; ++k) {
                uint32_t s0 = yix->start[y_bucket(lo[k])], s1 = yix->start[y_bucket(hi[k]) + 1];
                for (uint32_t u = s0; u < s1; ++u) {
                    double b = yix->items[u].v;
                    if (b < lo[k] || b > hi[k])
                        continue;
                    ++*evals;
                    double ang = decoded_angle(a, b, n[0]);
                    if (ang < e_best) {
                        e_best = ang;
                        a_star = a;
                        b_star = b;
                        t = ang * ang * (1.0 + 1e-9);
                    }
                }
            }
        }
    if (!(e_best < INFINITY))
        return 0;
    int ax = -1, by = -1;
    for (size_t i = 0; i < nx && ax < 0; ++i)
        for (int e = 0; e < 8 && ax < 0; ++e)
            if (value_bits(pal[xl[i].pair][e]) == value_bits(a_star))
                ax = xl[i].pair;
    for (size_t j = 0; j < ny && by < 0; ++j)
        for (int e = 0; e < 8 && by < 0; ++e)
            if (value_bits(pal[yl[j].pair][e]) == value_bits(b_star))
                by = yl[j].pair;
    double v = sol_nm_bc5_joint_objective(pal[ax], pal[by], n, use_max, INFINITY, NULL, NULL), floor = 0.0;
    for (int p = 0; p < 16; ++p) /* the objective of 16 pixels of error e*, as sol_nm_bc5_joint_objective sums it */
        floor = fold_term(floor, e_best * e_best, use_max);
    if (best <= floor) { /* no candidate beats the incumbent: it stays (as in the enumeration) */
        *value = best;
        return 1;
    }
    if (!(v <= floor) || !(v < best))
        return 0;
    *px = ax;
    *py = by;
    *value = v;
    return 1;
}

/* ---- blocks of 16 equal normals on the full range, decided by their values (issue 13) ----
 *
 * Every pixel picks the same decode, and on the full range every value v of the index of distinct
 * palette entries (bc4_entries.c) is an entry of some x pair and of some y pair, so e* = the least
 * decoded_angle(a, b) over every value pair (a, b) bounds every candidate's pixel error, and
 * L = the objective of 16 pixels of error e* (folded as sol_nm_bc5_joint_objective folds) every candidate's
 * objective; a candidate whose objective is L is optimal. No lists of anchor pairs are built.
 *
 * The scan: as in equal_block_solve, target q (the normal, or its rim direction with weight and
 * offset if it points away and is loose) and a chord^2 budget R2 from the per-pixel budget t (the
 * incumbent's e^2, shrinking to e*^2 as it is found). A decode with value a has x component a
 * (x^2 + y^2 <= 1) or, z clamped, a / r with r = sqrt(a^2 + b^2) in (1, sqrt(1 + a^2)], between
 * f(a) = a / sqrt(1 + a^2) and a; its chord to q is at least |x - qx|, so only a with the interval
 * [min(a, f(a)), max(a, f(a))] within R = sqrt(R2) of qx can be below the budget (just a within R
 * when no clamped decode reaches the ball: qz^2 > R2): an interval of a, since a and f(a) increase.
 * The values a are visited outward from qx (first above, then below, alternately), each
 * with the b values inside pixel_y_intervals' intervals for it (a superset, widened against
 * rounding) evaluated exactly; e* and (a*, b*), the first value pair reaching it in this order,
 * are kept (strictly smaller replaces).
 * The tie rule: the answer is the first (x pair, y pair), x pairs holding a* and y pairs holding b*
 * each in ascending code order, x-major, whose objective is L (the first unless its 8 x 8 grid holds
 * another decode of larger cosine but not smaller angle, a rounding-level tie: e.g. a 6-value pair's
 * clamped (+-1, +-1) beside (a*, b*) at the rim; after EQUAL_TRIES evaluations 0, undecided, and the
 * search runs as before). If L is not
 * below the incumbent, nothing beats the incumbent, which stays (px, py untouched), as in the
 * enumeration. The blocks are tied in thousands of candidates on their anchor pairs; this decides
 * them in a few thousand angle evaluations (evals) instead. */
static inline double unclamp_x(double y)
{
    /* f^-1(y) = y / sqrt(1 - y^2) for |y| < 1: the largest |a| whose clamped x can be y */
    return y / sqrt((1.0 - y) * (1.0 + y));
}

static size_t value_lower(const double *v, size_t n, double x)
{
    size_t lo = 0, hi = n; /* first v[k] >= x */
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

enum { EQUAL_TRIES = 256 };

static int equal_value_solve(const double n[16][3], const away_info *aw, int use_max, double best,
                             sol_bc4_precision precision, int *px, int *py, double *value, uint64_t *evals)
{
    const sol_nm_entry_index *ix = sol_nm_entry_index_get(precision);
    const int away = aw->mask & 1;
    if (!ix || (away && !(aw->w[0] > 0.0)))
        return 0; /* (0, 0, -1): the hemisphere bound decides it */
    const double q[3] = {away ? aw->m[0][0] : n[0][0], away ? aw->m[1][0] : n[0][1], away ? 0.0 : n[0][2]};
    const double *val = ix->value;
    const size_t nv = ix->count;
    double e_best = INFINITY, a_star = 0.0, b_star = 0.0;
    double t = (use_max ? best : best / 16.0) * (1.0 + 1e-9);
    size_t up = value_lower(val, nv, q[0]), down = up;
    int go_up = up < nv, go_down = down > 0;
    for (int turn = 0; go_up || go_down; turn ^= 1) {
        double r2 = away ? (t - aw->off[0]) / aw->w[0] : t;
        if (r2 < 0.0)
            return 0; /* cannot happen: the incumbent meets its own budget */
        const double R2 = r2 * (1.0 + 1e-9) + 1e-15, R = sqrt(R2) * (1.0 + 1e-9) + 1e-9;
        double a_lo = q[0] - R, a_hi = q[0] + R;
        if (!(q[2] * q[2] > R2)) { /* clamped decodes may reach the ball */
            a_lo = a_lo >= 0.0 ? a_lo : (a_lo > -1.0 ? unclamp_x(a_lo) * (1.0 + 1e-9) - 1e-9 : -INFINITY);
            a_hi = a_hi <= 0.0 ? a_hi : (a_hi < 1.0 ? unclamp_x(a_hi) * (1.0 + 1e-9) + 1e-9 : INFINITY);
        }
        double a;
        if (turn == 0 && go_up) {
            if (val[up] > a_hi) {
                go_up = 0;
                continue;
            }
            a = val[up++];
            go_up = up < nv;
        } else if (turn == 1 && go_down) {
            if (val[down - 1] < a_lo) {
                go_down = 0;
                continue;
            }
            a = val[--down];
            go_down = down > 0;
        } else {
            continue;
        }
        double a8[8] = {a, a, a, a, a, a, a, a}, lo[16], hi[16];
        int cnt = pixel_y_intervals(a8, q, R2, 1e-9, lo, hi);
        if (cnt < 0)
            return 0; /* a budget that constrains nothing: the search decides it */
        for (int k = 0; k < cnt; ++k)
            for (size_t j = value_lower(val, nv, lo[k]); j < nv && val[j] <= hi[k]; ++j) {
                ++*evals;
                double ang = decoded_angle(a, val[j], n[0]);
                if (ang < e_best) {
                    e_best = ang;
                    a_star = a;
                    b_star = val[j];
                    t = ang * ang * (1.0 + 1e-9);
                }
            }
    }
    if (!(e_best < INFINITY))
        return 0;
    double floor = 0.0;
    for (int p = 0; p < 16; ++p) /* the objective of 16 pixels of error e*, as sol_nm_bc5_joint_objective folds it */
        floor = fold_term(floor, e_best * e_best, use_max);
    if (best <= floor) { /* no candidate beats the incumbent: it stays (as in the enumeration) */
        *value = best;
        return 1;
    }
    const double(*pal)[8] = sol_nm_palettes(precision);
    const size_t ka = value_lower(val, nv, a_star), kb = value_lower(val, nv, b_star);
    int tries = 0;
    for (uint32_t i = ix->start[ka]; i < ix->start[ka + 1]; ++i)
        for (uint32_t j = ix->start[kb]; j < ix->start[kb + 1]; ++j) {
            if (++tries > EQUAL_TRIES)
                return 0;
            ++*evals;
            int ax = ix->pair[i], by = ix->pair[j];
            double v = sol_nm_bc5_joint_objective(pal[ax], pal[by], n, use_max, INFINITY, NULL, NULL);
            if (v <= floor && v < best) {
                *px = ax;
                *py = by;
                *value = v;
                return 1;
            }
        }
    return 0;
}

/* ---- blocks decided by their pixels one at a time (pixels pointing away) ----
 *
 * Every candidate gives pixel p the angle of one decode (a, b), a a value of the x list and b one
 * of the y list, so e*_p = the least angle decoded_angle(a, b, n_p) over those value pairs is a lower
 * bound of pixel p's error in every candidate, and L = sum_p e*_p^2 (pixels in order 0..15, as
 * sol_nm_bc5_joint_objective sums them; rounded addition is monotone, so no candidate's computed objective is
 * below the computed L) or max_p e*_p^2 (max metric) bounds every candidate's objective. If one
 * candidate attains L it is optimal. Blocks whose pixels share a rim direction (normals pointing
 * away at one azimuth, different heights) or that one pixel dominates (max metric) have such a
 * candidate: the decode nearest to the shared rim direction serves every pixel. (The sum metric
 * tries it only when the pixels share one azimuth or hold at most SEPARABLE_GROUPS distinct normals,
 * such as rim normals on the axes, whose least decodes one candidate often holds together.)
 *
 * e*_p (pixel_least_decode) is found as in equal_block_solve: per distinct value a of the x list,
 * only the b of the y list inside the coupling filter's intervals for a budget T (the incumbent less
 * the other pixels' hemisphere bounds theta0_q^2 for the sum, the incumbent for the max; shrinking
 * to e*_p^2 as it is found) can be below it, and those are evaluated. The cosine of the angle
 * decoded_angle measures (the decoder's vector (a, b, z) with rebuild_z's z, or (a, b, 0) / r when z
 * is clamped) is computed with an error of a few 1e-16; a decode whose cosine is below the largest
 * met so far by more than 1e-13 has a true angle larger by more than 1e-13 - 1e-15 than that
 * decode's (|d cos / d angle| <= 1), far beyond the rounding of either computed angle (~1e-15), so
 * its atan2 is skipped: the least computed angle, and the first decode in scan order reaching it,
 * are those of the plain scan. The scans stop (undecided) after `cap` work units.
 *
 * Max metric: only the largest e*_p matters. Pixels are taken by decreasing theta0^2 (then index);
 * after the first, a pixel is scanned with the budget of the largest e*^2 so far, L, and stops as
 * soon as one decode has angle^2 <= L (its own e* cannot raise the max); a pixel with no decode
 * within that budget is scanned again with the full budget and raises L. The rule that decides the
 * ties: the candidates tried are the pairs of the lists holding every a*_p (x; max metric: the a* of
 * the pixel that set L) and every matching b* (y), (a*_p, b*_p) being the first least decode of p's
 * scan, x pairs in list order and with each the y pairs in list order; the first whose objective is
 * L is the answer. If none is (no pair holds them all, another pixel served worse than L in their
 * grids, or a rounding-level tie; at most SEPARABLE_TRIES evaluations), the candidate loop runs as
 * usual. Max metric: before its scan a pixel is tried with the decode of the pixel that set L, and
 * needs no scan if that one serves it within L.
 * If L is not below the incumbent, or some pixel has no decode within its budget, no candidate beats
 * the incumbent, which is the answer (px, py untouched), as in the enumeration. */
enum { SEPARABLE_TRIES = 4096 };
/* separable_solve's sum metric also takes blocks of at most this many distinct normals, whatever
 * their azimuths (sol_nm_bc5_search_unit tries rim blocks of so few normals too) */
enum { SEPARABLE_GROUPS = 4 };

typedef struct least_scan {
    const double (*pal)[8];
    const sol_nm_pair *xl;
    const uint32_t *distinct; /* 8 i + e of the first x-list entry of each distinct value */
    size_t nd;
    const y_index *yix;
    const away_info *aw;
    uint64_t evals, work, cap; /* work: 8 per interval computed, 1 per entry met, 32 per atan2 */
} least_scan;

/* Pixel p's least decode under budget t (see above): 1 with *e, *a, *b if one has angle^2 <= t (the
 * least, or with stop >= 0 the first with angle^2 <= stop), 0 if none, -1 if the pixel constrains
 * nothing (too costly to scan). */
static int pixel_least_decode(least_scan *ls, const double n[3], int p, double t, double stop, double *e, double *a_out,
                              double *b_out)
{
    const away_info *aw = ls->aw;
    const int away = (aw->mask >> p) & 1;
    const double q[3] = {away ? aw->m[0][p] : n[0], away ? aw->m[1][p] : n[1], away ? 0.0 : n[2]};
    double eb = INFINITY, cb = -INFINITY, tb = t * (1.0 + 1e-9);
    for (size_t d = 0; d < ls->nd; ++d) {
        double a = ls->pal[ls->xl[ls->distinct[d] >> 3].pair][ls->distinct[d] & 7];
        double r2 = away ? (tb - aw->off[p]) / aw->w[p] : tb;
        if (r2 < 0.0)
            break;
        double a8[8] = {a, a, a, a, a, a, a, a}, lo[16], hi[16];
        int cnt = pixel_y_intervals(a8, q, r2 * (1.0 + 1e-9) + 1e-15, 1e-9, lo, hi);
        ls->work += 8;
        if (cnt < 0 || ls->work + 32 * ls->evals > ls->cap)
            return -1;
        for (int k = 0; k < cnt; ++k) {
            uint32_t s0 = ls->yix->start[y_bucket(lo[k])], s1 = ls->yix->start[y_bucket(hi[k]) + 1];
            ls->work += s1 - s0;
            for (uint32_t u = s0; u < s1; ++u) {
                double b = ls->yix->items[u].v;
                if (b < lo[k] || b > hi[k])
                    continue;
                double zz = 1.0 - a * a - b * b; /* rebuild_z's */
                double c = zz > 0.0 ? a * n[0] + b * n[1] + sqrt(zz) * n[2] : (a * n[0] + b * n[1]) / sqrt(a * a + b * b);
                if (c < cb - 1e-13)
                    continue; /* clearly farther than a decode met already */
                cb = c > cb ? c : cb;
                ++ls->evals;
                double ang = decoded_angle(a, b, n);
                if (ang < eb) {
                    eb = ang;
                    *a_out = a;
                    *b_out = b;
                    tb = ang * ang * (1.0 + 1e-9);
                    if (stop >= 0.0 && ang * ang <= stop) {
                        *e = eb;
                        return 1;
                    }
                }
            }
        }
    }
    if (!(eb * eb <= t * (1.0 + 1e-9)))
        return 0;
    *e = eb;
    return 1;
}

static int separable_solve(const double n[16][3], const int group[16], int few, const sol_nm_pair *xl, size_t nx,
                           const sol_nm_pair *yl, size_t ny, const double (*pal)[8], const y_index *yix,
                           const away_info *aw, int use_max, double best, uint64_t cap, uint32_t *slots, int *px,
                           int *py, double *value, uint64_t *evals, uint64_t *work)
{
    for (int p = 0; p < 16; ++p)
        if (((aw->mask >> p) & 1) && !(aw->w[p] > 0.0))
            return 0; /* (0, 0, -1): every rim decode ties */
    if (!use_max && !few) /* the sum: only blocks whose pixels share one azimuth (within 0.05 rad) or that
                           * hold few distinct normals: else the scans cost much and the bound is rarely
                           * attained */
        for (int p = 1; p < 16; ++p) {
            double r0 = hypot(n[0][0], n[0][1]), rp = hypot(n[p][0], n[p][1]);
            if (!(n[0][0] * n[p][0] + n[0][1] * n[p][1] >= cos(0.05) * r0 * rp) || !(r0 * rp > 0.0))
                return 0;
        }
    const size_t size = 2 * 65536; /* slots: a hash set of the distinct values of a */
    uint32_t *distinct = malloc(65536 * sizeof *distinct);
    if (!distinct)
        return 0;
    memset(slots, 0, size * sizeof *slots);
    size_t nd = 0;
    for (size_t i = 0; i < nx; ++i)
        for (int e = 0; e < 8; ++e) {
            size_t h;
            if (distinct_value_slot(slots, size, pal, xl, value_bits(pal[xl[i].pair][e]), &h))
                continue;
            if (nd == 65536) {
                free(distinct);
                return 0;
            }
            slots[h] = (uint32_t)(8 * i + (size_t)e + 1);
            distinct[nd++] = (uint32_t)(8 * i + (size_t)e);
        }
    least_scan ls = {pal, xl, distinct, nd, yix, aw, 0, 8 * nx, cap};
    double total = 0.0, e_star[16], a_star[16], b_star[16];
    for (int p = 0; p < 16; ++p)
        total += aw->off[p];
    int order[16], top = -1, ok = 1, kept = 0; /* kept: no candidate can beat the incumbent */
    for (int p = 0; p < 16; ++p) /* by decreasing theta0^2, then index */
        order[p] = p;
    sol_nm_bc5_order_worst_first(aw->off, order);
    double L = 0.0;
    for (int k = 0; k < 16 && ok; ++k) {
        int p = order[k];
        if (group[p] != p)
            continue; /* equal normals: the first one's scan serves them */
        if (!use_max) {
            int r = pixel_least_decode(&ls, n[p], p, best - (total - aw->off[p]) * (1.0 - 1e-9), -1.0, &e_star[p],
                                       &a_star[p], &b_star[p]);
            kept = r == 0;
            ok = r == 1;
            continue;
        }
        if (top >= 0) { /* the decode of the pixel that set L may serve this one within L: no scan */
            double ang = decoded_angle(a_star[top], b_star[top], n[p]);
            ++ls.evals;
            if (ang * ang <= L)
                continue;
        }
        int r = top < 0 ? 0 : pixel_least_decode(&ls, n[p], p, L, L, &e_star[p], &a_star[p], &b_star[p]);
        if (r == 1 && e_star[p] * e_star[p] <= L)
            continue; /* at most L */
        if (r == 1) { /* the scan was complete: its least decode, above L */
            L = e_star[p] * e_star[p];
            top = p;
            continue;
        }
        if (r >= 0)
            r = pixel_least_decode(&ls, n[p], p, best, -1.0, &e_star[p], &a_star[p], &b_star[p]);
        if (r != 1) {
            kept = r == 0;
            ok = 0;
            break;
        }
        L = e_star[p] * e_star[p];
        top = p;
    }
    free(distinct);
    *evals += ls.evals;
    *work += ls.work;
    if (kept) { /* a pixel has no decode within its budget: nothing beats the incumbent */
        *value = best;
        return 1;
    }
    if (!ok)
        return 0;
    if (use_max) {
        for (int p = 0; p < 16; ++p)
            if (group[p] != p)
                e_star[p] = e_star[group[p]];
    } else {
        L = 0.0;
        for (int p = 0; p < 16; ++p) {
            if (group[p] != p) {
                e_star[p] = e_star[group[p]];
                a_star[p] = a_star[group[p]];
                b_star[p] = b_star[group[p]];
            }
            L += e_star[p] * e_star[p];
        }
    }
    if (best <= L) { /* no candidate beats the incumbent: it stays (as in the enumeration) */
        *value = best;
        return 1;
    }
    /* the pairs holding every needed a* (x) and b* (y), in list order; then the first x pair, and
     * with it the first y pair, whose objective is L (at most SEPARABLE_TRIES evaluations) */
    uint32_t *holders = malloc((nx + ny) * sizeof *holders);
    if (!holders)
        return 0;
    size_t count[2] = {0, 0};
    for (int c = 0; c < 2; ++c) {
        const sol_nm_pair *list = c ? yl : xl;
        const double *want = c ? b_star : a_star;
        uint32_t *out = holders + (c ? nx : 0);
        for (size_t i = 0; i < (c ? ny : nx); ++i) {
            const double *v = pal[list[i].pair];
            int all = 1;
            for (int p = 0; p < 16 && all; ++p) {
                if (use_max && p != top)
                    continue;
                int hit = 0;
                for (int e = 0; e < 8 && !hit; ++e)
                    hit = value_bits(v[e]) == value_bits(want[p]);
                all = hit;
            }
            if (all)
                out[count[c]++] = list[i].pair;
        }
        *work += 8 * (c ? ny : nx);
    }
    int tries = 0, done = 0;
    for (size_t i = 0; i < count[0] && !done && tries < SEPARABLE_TRIES; ++i)
        for (size_t j = 0; j < count[1] && !done && tries < SEPARABLE_TRIES; ++j, ++tries) {
            int ax = (int)holders[i], by = (int)holders[nx + j];
            double v = sol_nm_bc5_joint_objective(pal[ax], pal[by], n, use_max, L * (1.0 + 1e-15), NULL, NULL);
            *work += 512;
            if (v <= L && v < best) {
                *px = ax;
                *py = by;
                *value = v;
                done = 1;
            }
        }
    free(holders);
    return done;
}

/* The value-level filter and merge of both lists (see "value-level usability"); 0 if it could not
 * run (no memory), leaving the lists as they were. */
static int value_reduce(const double n[16][3], const away_info *aw, int use_max, double best,
                        const double (*pal)[8], sol_bc4_precision precision, search_workspace *ws, sol_nm_pair *xl, size_t *nx, sol_nm_pair *yl,
                        size_t *ny, const double tx[16], const double ty[16], unsigned loose, uint64_t *work)
{
    if (!ws->vset && !(ws->vset = malloc(sizeof *ws->vset)))
        return 0;
    if (!ws->vtab) {
        if (!(ws->vtab = calloc(VALUE_CODES, sizeof *ws->vtab)))
            return 0;
        ws->vgen = 0;
    }
    int group[16];
    for (int p = 0; p < 16; ++p) {
        group[p] = p;
        for (int q = 0; q < p && group[p] == p; ++q)
            if (memcmp(n[q], n[p], sizeof n[p]) == 0)
                group[p] = q;
    }
    pixel_reach pr;
    if (!pixel_reach_init(&pr, n, aw, group, use_max, best)) {
        *nx = *ny = 0; /* no candidate can beat the incumbent */
        return 1;
    }
    value_table t = {ws->vtab, 0, 0, &pr, ws->vset, work};
    size_t filtered_at[2] = {SIZE_MAX, SIZE_MAX}; /* the other list's count at each channel's last filter */
    for (int round = 0; round < 2; ++round) {
        for (int c = 0; c < 2; ++c) {
            sol_nm_pair *list = c ? yl : xl, *other = c ? xl : yl;
            size_t *count = c ? ny : nx, ocount = c ? *nx : *ny;
            value_set_init(ws->vset, other, ocount, pal, precision);
            *work += 8 * ocount + VALUE_CODES / 64;
            if (++ws->vgen == 0) { /* wrapped: clear the generations */
                memset(ws->vtab, 0, VALUE_CODES * sizeof *ws->vtab);
                ws->vgen = 1;
            }
            t.gen = ws->vgen;
            t.c = c;
            /* the filter again against the same other list (lists only shrink: the same count is the
             * same set, so the same values) would keep every pair it met: usability depends on the
             * value, the pixel reach and the other list's values alone (issue 13: round 1 repeated
             * round 0's x pass whenever the y pass dropped nothing, most blocks pointing away) */
            if (filtered_at[c] != ocount)
                *count = usable_filter(list, *count, pal, &t);
            filtered_at[c] = ocount;
            if (round == 1 && *count > 1) {
                *count = merge_usable(list, *count, pal, &t, c ? ty : tx, ws);
                /* and the classes of the budget-based key (each merge keeps the first of its classes,
                 * so their composition does too) */
                channel_key k;
                sol_nm_bc5_channel_key_init(&k, c ? ty : tx, loose, best * (1.0 + BOUND_SLACK));
                *count = merge_keyed(list, *count, &k, pal, precision, ws);
            }
        }
    }
    return 1;
}


/* sol_nm_channel_argmin for a channel whose 16 pixels are all loose, with, in out, every pair of
 * score <= cap from the same enumeration (*count; SIZE_MAX when not collected). Loose pixels prune
 * no anchors (enumerate_pairs scores all 65536 pairs), so sol_nm_bc5_search_unit's argmin and its later collect
 * (budget <= cap: the incumbent only falls) were two full passes; now one. The argmin is the least
 * (score, pair) of the collected pairs: it has score <= cap (the incumbent's own pair scores at most
 * the incumbent, the channel score being a lower bound of the objective), and a pair's score within
 * the budget is its full sum in either enumeration, so the pair and *score are sol_nm_channel_argmin's
 * (which it falls back to if nothing was collected, or for channels with tight pixels). */
static int argmin_collect(const sol_nm_channel *ch, unsigned loose, double cap, sol_nm_pair *out, size_t *count,
                          double *score)
{
    *count = SIZE_MAX;
    if (loose != 0xffffu)
        return sol_nm_channel_argmin(ch, score);
    size_t n = sol_nm_channel_collect(ch, cap, out), b = 0;
    if (n == 0)
        return sol_nm_channel_argmin(ch, score);
    for (size_t k = 1; k < n; ++k)
        if (out[k].score < out[b].score || (out[k].score == out[b].score && out[k].pair < out[b].pair))
            b = k;
    *count = n;
    *score = out[b].score;
    return out[b].pair;
}

/* sol_nm_channel_collect(ch, budget, out), or, if argmin_collect collected `pre` pairs into out with
 * a cap >= budget, those of them within budget (the same set; sol_nm_bc5_search_unit sorts it). */
static size_t collect_within(const sol_nm_channel *ch, double budget, sol_nm_pair *out, size_t pre)
{
    if (pre == SIZE_MAX)
        return sol_nm_channel_collect(ch, budget, out);
    size_t n = 0;
    for (size_t k = 0; k < pre; ++k)
        if (out[k].score <= budget)
            out[n++] = out[k];
    return n;
}

/* sol_nm_bc5_search_unit's shortcut for blocks of 16 equal normals on the full range (equal_value_solve),
 * at every precision and direction. (It was kept to rims, normals pointing away and the 8-bit
 * decoder until issue 13's per-block profile of the hood map from an 8-bit source: its quantised
 * normals make 27% of the blocks 16 equal normals with z > 0, which the search proved at ~225 us
 * each, 40% of the map's time, against ~5 us here; same errors, ties decided by the rule below.)
 * Returns 1 with *best, *px, *py, *candidates updated if it decided the block. */
static int equal_shortcut(const double n[16][3], int full, const search_request *rq, double *best, int *px, int *py,
                          uint64_t *candidates)
{
    if (!full)
        return 0;
    for (int p = 1; p < 16; ++p)
        if (memcmp(n[0], n[p], sizeof n[p]) != 0)
            return 0;
    const int loose = n[0][2] * n[0][2] <= *best * (1.0 + BOUND_SLACK);
    away_info aw;
    away_info_init(&aw, n, loose ? 0xffffu : 0u);
    double v;
    uint64_t evals = 0;
    int done = equal_value_solve(n, &aw, rq->use_max, *best, rq->precision, px, py, &v, &evals);
    *candidates += evals;
    if (done)
        *best = v;
    return done;
}

/* order[0..16) (a permutation) sorted by decreasing err, stable: the pixels most likely to reject a
 * candidate are visited first. Insertion sort: 16 items. */
void sol_nm_bc5_order_worst_first(const double err[16], int order[16]) {
    for (int p = 1; p < 16; ++p)
        for (int q = p; q > 0 && err[order[q - 1]] < err[order[q]]; --q) {
            int t = order[q];
            order[q] = order[q - 1];
            order[q - 1] = t;
        }
}

/* The pair screen on one candidate, for the tests (normalmaps_internal.h): sol_nm_bc5_search_unit's set-up of
 * the loose pixels and pixels pointing away at incumbent best (pixels in their own order), then
 * pair_screen_build on one-pair lists whose scores leave room. */
struct sol_nm_screen {
    pair_screen sc;
};

sol_nm_screen *sol_nm_screen_new(void)
{
    sol_nm_screen *s = malloc(sizeof *s);
    if (s)
        s->sc.gen = s->sc.rgen = 0;
    return s;
}

void sol_nm_screen_free(sol_nm_screen *screen)
{
    free(screen);
}

int sol_nm_screen_rules_out(sol_nm_screen *screen, const double n[16][3], int use_max, double best,
                            sol_bc4_precision precision, int pair_x, int pair_y)
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    pair_screen *sc = screen ? &screen->sc : pair_screen_new();
    if (!sc)
        return -1;
    unsigned loose = 0;
    for (int p = 0; p < 16; ++p)
        if (n[p][2] * n[p][2] <= best * (1.0 + BOUND_SLACK))
            loose |= 1u << p;
    away_info aw;
    away_info_init(&aw, n, loose);
    int order[16];
    double away_off[16];
    for (int k = 0; k < 16; ++k) {
        order[k] = k;
        away_off[k] = aw.off[k];
    }
    channel_side ys;
    sol_nm_bc5_channel_side_init(pal[pair_y], n, order, 1, &aw, &ys);
    sol_nm_pair xl = {0.0, (uint16_t)pair_x}, yl = {0.0, (uint16_t)pair_y};
    uint64_t work = 0;
    int built = pair_screen_build(sc, n, order, loose, &aw, away_off, use_max, best, pal, precision, &xl, 1, &yl, 1,
                                  &ys, &work, UINT64_MAX);
    int out = built ? sc->start[1] == 0 : -1;
    if (!screen)
        free(sc);
    return out;
}

/* The pixel floor on one candidate's values, for the tests (normalmaps_internal.h): per pixel p,
 * sol_nm_bc5_search_unit's set-up of the loose pixels and pixels pointing away at incumbent best[p], then
 * floor_scan of pixel p with the value sets of the one-pair lists pair_x, pair_y. */
int sol_nm_floor_rules_out(const double n[16][3], const double best[16], sol_bc4_precision precision, int pair_x,
                           int pair_y, int out[16])
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    pixel_floor *pf = malloc(sizeof *pf);
    if (!pf)
        return -1;
    sol_nm_pair xl = {0.0, (uint16_t)pair_x}, yl = {0.0, (uint16_t)pair_y};
    uint64_t work = 0;
    int built = pixel_floor_init(pf, pal, precision, &xl, 1, &yl, 1, &work);
    for (int p = 0; built && p < 16; ++p) {
        unsigned loose = 0;
        for (int q = 0; q < 16; ++q)
            if (n[q][2] * n[q][2] <= best[p] * (1.0 + BOUND_SLACK))
                loose |= 1u << q;
        away_info aw;
        away_info_init(&aw, n, loose);
        out[p] = floor_scan(pf, n, &aw, p, best[p], 0, &work) == 1;
    }
    free(pf);
    return built ? 0 : -1;
}

/* ---- the stages of the exact search (sol_nm_bc5_search_unit, in this order) ---- */

/* What the stages of one search share: the block and the request, the incumbent (objective best,
 * pairs px, py), the two lists ws->x[0 .. nx) and ws->y[0 .. ny), the counters, the loose pixels
 * and pixels pointing away, which reductions ran and the incumbents at which they run again, the
 * pixels' groups and visiting order, and the per-candidate helpers that were set up. */
typedef struct search_state {
    const double (*n)[3];
    const search_request *rq;
    search_workspace *ws;
    const double (*pal)[8];
    int use_max;
    double tx[16], ty[16];
    sol_nm_channel cx, cy;
    double best;
    int px, py;
    uint64_t candidates, work; /* work: pixel evaluations of candidates (see the work bound) */
    int bounded, solved;
    size_t nx, ny;
    unsigned loose; /* bit p: pixel p takes the loose channel terms (rims, pixels pointing away) */
    away_info aw;
    int valued;  /* the value-level filter and merge ran */
    int coupled; /* the coupled row bounds ran */
    int floored; /* the pixel floor's value sets are built */
    double floor_all, reduce_at, couple_at;
    int all_equal;  /* 16 equal normals: equal_block_solve decides them */
    int group[16];  /* the first pixel with a bit-identical normal */
    int repeats;    /* some pixel repeats an earlier one's normal */
    int order[16];  /* pixels worst-first by the incumbent's per-pixel error */
    double away_off[16], nz_ord[16]; /* theta0^2 of the pixels pointing away, and nz, in visiting order */
    int quick;  /* the y list's channel sides are set up (the quick bound runs) */
    int filter; /* the coupling filter's y index is set up */
    y_index yix;
} search_state;

/* The first two incumbents. The least-squares pairs: on the full range with the sum metric they come
 * from bc4_common.c's search: the same pair and score as sol_nm_channel_argmin, bit for bit (its
 * documented contract, tested against the brute force and against sol_nm_channel_argmin on random,
 * flat, few-valued and map blocks), at a few microseconds a channel instead of the enumeration's ~100
 * (issue 13: the two argmin enumerations were ~30% of the optimal encoder's time on the
 * terrain-derived map, perf). Flat channels (16 equal targets: flat blocks, equal normals, a rim
 * block on an axis) are decided there by a walk over the entry values instead of scoring every tied
 * pair (x = -1: 33151 pairs). Then the full-span 6-value pairs, whose entries -1 and +1 reach the rim
 * (blocks pointing away). (Starting from the adaptive window's result instead was measured: it costs
 * more than the candidates it saves on the benchmark maps.) *sx_min, *sy_min: the channels' least
 * scores. */
static void first_incumbents(search_state *st, int full, double *sx_min, double *sy_min)
{
    const sol_bc5_range *r = st->rq->range;
    const sol_bc4_precision precision = st->rq->precision;
    sol_nm_channel_init(&st->cx, st->tx, precision, st->use_max, 0, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi);
    sol_nm_channel_init(&st->cy, st->ty, precision, st->use_max, 0, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi);
    const int common = full && !st->use_max;
    st->px = common ? sol_nm_bc4_common(st->tx, precision, sx_min) : sol_nm_channel_argmin(&st->cx, sx_min);
    st->py = common ? sol_nm_bc4_common(st->ty, precision, sy_min) : sol_nm_channel_argmin(&st->cy, sy_min);
    st->pal = st->cx.palettes;
    st->best = sol_nm_bc5_joint_objective(st->pal[st->px], st->pal[st->py], st->n, st->use_max, INFINITY, NULL, NULL);
    st->candidates = 1;
    const int rim = 0x00ff;
    if (pair_in_range(rim, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi) &&
        pair_in_range(rim, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi)) {
        ++st->candidates;
        double v = sol_nm_bc5_joint_objective(st->pal[rim], st->pal[rim], st->n, st->use_max, st->best, NULL, NULL);
        if (v < st->best) {
            st->best = v;
            st->px = st->py = rim;
        }
    }
}

/* Rim pixels (nz^2 within the incumbent) take the loose channel terms, pixels pointing away their rim
 * targets, weights and offsets (see "pixels pointing away"); the pairs of least loose score, which aim
 * at the rim directions, are the third incumbent. *pre_x, *pre_y: the pairs argmin_collect collected
 * with them; *sx_min, *sy_min: the loose channels' least scores. */
static void loose_incumbent(search_state *st, size_t *pre_x, size_t *pre_y, double *sx_min, double *sy_min)
{
    const sol_bc5_range *r = st->rq->range;
    const sol_bc4_precision precision = st->rq->precision;
    const double(*n)[3] = st->n;
    unsigned loose = 0;
    for (int p = 0; p < 16; ++p)
        if (n[p][2] * n[p][2] <= st->best * (1.0 + BOUND_SLACK))
            loose |= 1u << p;
    st->loose = loose;
    away_info_init(&st->aw, n, loose);
    sol_nm_channel_init(&st->cx, st->aw.m[0], precision, st->use_max, loose, r->x0_lo, r->x0_hi, r->x1_lo, r->x1_hi);
    sol_nm_channel_init(&st->cy, st->aw.m[1], precision, st->use_max, loose, r->y0_lo, r->y0_hi, r->y1_lo, r->y1_hi);
    for (int p = 0; p < 16; ++p)
        if ((st->aw.mask >> p) & 1) {
            double off = st->use_max ? st->aw.off[p] : 0.5 * st->aw.off[p];
            sol_nm_channel_rim_weight(&st->cx, p, st->aw.w[p], off);
            sol_nm_channel_rim_weight(&st->cy, p, st->aw.w[p], off);
        }
    int lx = argmin_collect(&st->cx, loose, st->best * (1.0 + BOUND_SLACK), st->ws->x, pre_x, sx_min);
    int ly = argmin_collect(&st->cy, loose, st->best * (1.0 + BOUND_SLACK), st->ws->y, pre_y, sy_min);
    ++st->candidates;
    double v = sol_nm_bc5_joint_objective(st->pal[lx], st->pal[ly], n, st->use_max, st->best, NULL, NULL);
    if (v < st->best) {
        st->best = v;
        st->px = lx;
        st->py = ly;
    }
}

/* The lists: each channel's pairs whose score leaves room under the incumbent with the other
 * channel's least score (sum metric), sorted by score. */
static void collect_lists(search_state *st, size_t pre_x, size_t pre_y, double sx_min, double sy_min)
{
    search_workspace *ws = st->ws;
    const double room = st->best * (1.0 + BOUND_SLACK);
    st->nx = collect_within(&st->cx, st->use_max ? room : room - sy_min * (1.0 - BOUND_SLACK), ws->x, pre_x);
    st->ny = collect_within(&st->cy, st->use_max ? room : room - sx_min * (1.0 - BOUND_SLACK), ws->y, pre_y);
    if (!ws->sort_tmp)
        ws->sort_tmp = malloc(65536 * sizeof *ws->sort_tmp); /* NULL: sol_nm_bc5_sort_pairs uses qsort */
    sol_nm_bc5_sort_pairs(ws->x, st->nx, ws->sort_tmp);
    sol_nm_bc5_sort_pairs(ws->y, st->ny, ws->sort_tmp);
}

/* The incumbent at which the value-level reduction runs again on the lists' rest: once the
 * incumbent's distance to the floor of every objective halved, or fell by 64 if the last reduction
 * kept over 90% of the pairs (coarse values: it rarely pays). */
static double next_reduce_at(const search_state *st, size_t pairs_before, size_t pairs_after)
{
    return st->floor_all + (10 * pairs_after > 9 * pairs_before ? 1.0 / 64 : 0.5) * (st->best - st->floor_all);
}

/* The lists' first reductions: the value-level filter and merge (blocks with pixels pointing away),
 * else the merge of equivalent pairs; then the coupled row bounds with their descent's incumbents. */
static void reduce_lists(search_state *st)
{
    search_workspace *ws = st->ws;
    const double(*n)[3] = st->n;
    const int use_max = st->use_max;
    const sol_bc4_precision precision = st->rq->precision;
    st->all_equal = 1;
    for (int p = 1; p < 16; ++p)
        st->all_equal &= memcmp(n[0], n[p], sizeof n[p]) == 0;
    const size_t pairs_before = st->nx + st->ny;
    /* rim-only blocks (no pixel pointing away) skip it: measured (issue 13, survey of rim arcs, rims
     * with pixels a hair off, equal rim normals, and the alternating +-x axis block), it leaves the
     * same candidates to within a few % (rim-arc 2 rad: 212440 vs 219070 before the work bound)
     * and proves nothing more, while its value table and filter passes over the 33k pairs holding
     * -1 or +1 cost ~2M work units (the axis block: 2.0M instead of 58k in all) */
    if (st->aw.mask && !st->all_equal && st->nx > 1 && st->ny > 1 && st->nx * st->ny > 4096)
        st->valued = value_reduce(n, &st->aw, use_max, st->best, st->pal, precision, ws, ws->x, &st->nx, ws->y,
                                  &st->ny, st->tx, st->ty, st->loose, &st->work);
    /* the floor of every objective (hemisphere bounds) */
    st->floor_all = 0.0;
    for (int p = 0; p < 16; ++p)
        st->floor_all = fold_term(st->floor_all, st->aw.off[p], use_max);
    if (st->valued)
        st->reduce_at = next_reduce_at(st, pairs_before, st->nx + st->ny);
    /* merging pays only for long lists; one list may be a single pair: a rim block near an axis
     * (x = -1 or +1) has one y pair left and the 33151 x pairs holding -1 or +1, exact ties */
    if (!st->valued && (st->nx > 1 || st->ny > 1) && st->nx * st->ny > 256) {
        const double room = st->best * (1.0 + BOUND_SLACK);
        channel_key kx, ky;
        sol_nm_bc5_channel_key_init(&kx, st->tx, st->loose, room);
        sol_nm_bc5_channel_key_init(&ky, st->ty, st->loose, room);
        st->nx = merge_keyed(ws->x, st->nx, &kx, st->pal, precision, ws);
        st->ny = merge_keyed(ws->y, st->ny, &ky, st->pal, precision, ws);
    }
    /* the coupled row bounds (bc5_couple.c): for rims and pixels pointing away whose lists are long,
     * coordinate descent from the incumbent's x pair for a better incumbent (its candidates
     * evaluated exactly), then drop the pairs whose every candidate the channels' coupling rules
     * out under it. Both lists keep their order and only pairs that cannot beat the incumbent go:
     * the enumeration's result is unchanged except that a descent candidate met first wins exact
     * ties. (The reduction ran before the descent too until issue 13's survey showed it wasted
     * there: at the incumbent before the descent it kept 95-99% of the pairs of blocks pointing
     * away (away-zvar: x 25098 -> 24852) at 15-40 ms, while under the descent's incumbent it cuts
     * them to a few (half-away-arc: 19736 x 40789 -> 2 x 21); the descent on the unreduced lists
     * costs about the same, and finds the same candidates on the survey.) */
    if (st->loose && !st->all_equal && st->nx * st->ny > 4096 && (ws->couple || (ws->couple = sol_nm_couple_new()))) {
        st->coupled = 1;
        int cand[4][2];
        int nc = sol_nm_couple_descent(ws->couple, n, use_max, st->pal, precision, ws->x, st->nx, ws->y, st->ny,
                                       st->px, cand, &st->work);
        for (int k = 0; k < nc; ++k) {
            ++st->candidates;
            st->work += 512;
            double v = sol_nm_bc5_joint_objective(st->pal[cand[k][0]], st->pal[cand[k][1]], n, use_max, st->best,
                                                  NULL, NULL);
            if (v < st->best) {
                st->best = v;
                st->px = cand[k][0];
                st->py = cand[k][1];
            }
        }
        sol_nm_couple_reduce(ws->couple, n, use_max, st->best * (1.0 + BOUND_SLACK), st->pal, precision, ws->x,
                             &st->nx, ws->y, &st->ny, &st->work);
        st->couple_at = st->best - (st->best - st->floor_all) / 16.0;
    }
}

/* The pixel floor (see there): with the max metric one pixel may decide the block, now (the
 * incumbent, or the enumeration's first candidate attaining that pixel's least term) or at a later
 * incumbent (the value sets stay valid as the lists shrink); for long lists only, like the stages
 * above (short ones enumerate quickly; floor_first's tries would not pay). */
static void floor_stage(search_state *st)
{
    search_workspace *ws = st->ws;
    if (!st->use_max || st->nx * st->ny <= 4096 || !(ws->floor || (ws->floor = malloc(sizeof *ws->floor))))
        return;
    st->floored = pixel_floor_init(ws->floor, st->pal, st->rq->precision, ws->x, st->nx, ws->y, st->ny, &st->work);
    size_t fi, fj;
    int fs = st->floored ? pixel_floor_solve(ws->floor, st->n, &st->aw, st->pal, st->pal[st->px], st->pal[st->py],
                                             st->best, ws->x, st->nx, ws->y, st->ny, &fi, &fj, &st->candidates,
                                             &st->work)
                         : 0;
    if (fs == 2) {
        st->best = ws->floor->least;
        st->px = ws->x[fi].pair;
        st->py = ws->y[fj].pair;
    }
    st->solved = fs != 0;
}

/* The pixels' groups of bit-identical normals (they share their terms, see
 * sol_nm_bc5_joint_objective_grouped), and the order in which the bounds visit them: worst first by
 * the incumbent's per-pixel error. */
static void visiting_order(search_state *st)
{
    const double(*n)[3] = st->n;
    st->repeats = 0;
    for (int p = 0; p < 16; ++p) {
        st->group[p] = p;
        for (int q = 0; q < p && st->group[p] == p; ++q)
            if (memcmp(n[q], n[p], sizeof n[p]) == 0)
                st->group[p] = q;
        st->repeats |= st->group[p] != p;
    }
    double pixel_err[16];
    for (int p = 0; p < 16; ++p) {
        int i, j;
        pixel_err[p] = sol_nm_bc5_best_pixel(st->pal[st->px], st->pal[st->py], n[p], &i, &j);
        st->order[p] = p;
    }
    sol_nm_bc5_order_worst_first(pixel_err, st->order);
    for (int k = 0; k < 16; ++k) {
        st->away_off[k] = st->aw.off[st->order[k]];
        st->nz_ord[k] = n[st->order[k]][2];
    }
}

/* The y list's channel sides for the quick bound (while the search is not solved). */
static void y_sides_init(search_state *st)
{
    for (size_t j = 0; st->quick && !st->solved && j < st->ny; ++j)
        sol_nm_bc5_channel_side_init(st->pal[st->ws->y[j].pair], st->n, st->order, 1, &st->aw, &st->ws->yside[j]);
}

/* The per-candidate helpers: the y list's channel sides (without memory, the search runs without the
 * quick bound), and for rims and pixels pointing away, when the lists are long, the coupling filter's
 * index of the y list's entries. */
static void helpers_setup(search_state *st)
{
    search_workspace *ws = st->ws;
    const size_t ny = st->ny;
    st->quick = 1;
    if (ny > ws->yside_cap) {
        channel_side *grown = realloc(ws->yside, ny * sizeof *grown);
        if (grown) {
            ws->yside = grown;
            ws->yside_cap = ny;
        } else {
            st->quick = 0;
        }
    }
    y_sides_init(st);
    if (!st->quick || !st->loose || st->solved || st->nx * ny <= 4096)
        return;
    size_t words = (ny + 63) / 64;
    if (ws->ybucket_cap < 8 * ny) {
        y_item *grown = realloc(ws->ybucket, 8 * ny * sizeof *grown);
        if (grown) {
            ws->ybucket = grown;
            ws->ybucket_cap = 8 * ny;
        }
    }
    if (ws->ymark_cap < words) {
        uint64_t *grown = realloc(ws->ymark, words * sizeof *grown);
        if (grown) {
            ws->ymark = grown;
            ws->ymark_cap = words;
        }
    }
    if (ws->ybucket_cap >= 8 * ny && ws->ymark_cap >= words) {
        st->filter = 1;
        memset(ws->ymark, 0, words * sizeof *ws->ymark);
        y_index_init(&st->yix, ws->y, ny, st->pal, ws->ybucket);
        st->work += 8 * ny;
    }
}

/* Blocks a rule decides: 16 equal normals (equal_block_solve), blocks with pixels pointing away and
 * rim blocks of few distinct normals with the sum metric (separable_solve: the per-pixel floor is
 * cheap, a scan per distinct normal, and often attained; issue 13's survey: tied rim normals on the
 * axes, 8-bit decoder, 6088 -> 672 candidates). Equal normals pointing away that no rule decided
 * (e.g. coarse 8-bit values) get the value-level reduction at once. */
static void solve_by_rule(search_state *st)
{
    search_workspace *ws = st->ws;
    int equal = 1, groups = 0;
    for (int p = 0; p < 16; ++p) {
        equal &= st->group[p] == 0;
        groups += st->group[p] == p;
    }
    const int few = !st->use_max && groups <= SEPARABLE_GROUPS;
    double v;
    uint64_t evals = 0;
    if (equal && equal_block_solve(st->n, ws->x, st->nx, ws->y, st->ny, st->pal, &st->yix, &st->aw, st->use_max,
                                   st->best, ws->slots, &st->px, &st->py, &v, &evals)) {
        st->best = v;
        st->solved = 1;
    } else if (!equal && (st->aw.mask || few) &&
               separable_solve(st->n, st->group, few, ws->x, st->nx, ws->y, st->ny, st->pal, &st->yix, &st->aw,
                               st->use_max, st->best, st->rq->work_limit / 8, ws->slots, &st->px, &st->py, &v,
                               &evals, &st->work)) {
        st->best = v;
        st->solved = 1;
    } else if (equal && st->aw.mask && !st->valued) {
        st->valued = 1;
        st->reduce_at = INFINITY;
    }
    st->candidates += evals;
    st->work += 8 * st->nx + 32 * evals;
}

/* The pair screen's state during the enumeration: built (screened) or due to be built, its row 0
 * (x list position base) and the x rows plus y pairs it was built on. */
typedef struct screen_track {
    int screened, due;
    size_t base, pairs;
} screen_track;

/* The reductions due at row i (the incumbent fell below reduce_at or couple_at), on the lists' rest
 * ws->x[i ..) and ws->y, then the y sides, the y index and the screen brought up to date: while the
 * lists keep most of the pairs the screen was built on (the incumbent fell a little), the screen is
 * carried over to them, else built again on the rest at the new incumbent. Returns 0 if the
 * enumeration is over (a list emptied, or row i's bound reaches the incumbent). */
static int reduce_rest(search_state *st, size_t i, screen_track *sc)
{
    search_workspace *ws = st->ws;
    size_t rest = st->nx - i;
    if (st->valued && st->best < st->reduce_at) {
        const size_t pairs_before = rest + st->ny;
        value_reduce(st->n, &st->aw, st->use_max, st->best, st->pal, st->rq->precision, ws, ws->x + i, &rest, ws->y,
                     &st->ny, st->tx, st->ty, st->loose, &st->work);
        st->reduce_at = next_reduce_at(st, pairs_before, rest + st->ny);
    }
    if (st->coupled && st->best < st->couple_at) {
        sol_nm_couple_reduce(ws->couple, st->n, st->use_max, st->best * (1.0 + BOUND_SLACK), st->pal,
                             st->rq->precision, ws->x + i, &rest, ws->y, &st->ny, &st->work);
        st->couple_at = st->best - (st->best - st->floor_all) / 16.0;
    }
    st->nx = i + rest;
    if (i >= st->nx || st->ny == 0)
        return 0;
    y_sides_init(st);
    st->work += 16 * st->ny;
    if (st->filter) {
        y_index_init(&st->yix, ws->y, st->ny, st->pal, ws->ybucket);
        st->work += 8 * st->ny;
    }
    if (sc->screened) {
        if (4 * (st->nx - i + st->ny) >= 3 * sc->pairs &&
            pair_screen_remap(ws->screen, i - sc->base, ws->x + i, st->nx - i, ws->y, st->ny, &st->work)) {
            sc->base = i;
        } else {
            sc->screened = 0;
            sc->due = 1;
        }
    }
    return !(combine(ws->x[i].score, ws->y[0].score, st->use_max) * (1.0 - BOUND_SLACK) >= st->best);
}

/* Marks row i's passing y positions of the screen in ws->ymark (at least one: the caller skips empty
 * rows); *lo_word, *hi_word: the marked words. */
static void screen_marks(search_state *st, const screen_track *sc, size_t i, size_t *lo_word, size_t *hi_word)
{
    const pair_screen *s = st->ws->screen;
    const size_t row = i - sc->base;
    *lo_word = s->col[s->start[row]] >> 6;
    *hi_word = (s->col[s->start[row + 1] - 1] >> 6) + 1;
    for (uint32_t t = s->start[row]; t < s->start[row + 1]; ++t)
        st->ws->ymark[s->col[t] >> 6] |= UINT64_C(1) << (s->col[t] & 63);
    st->work += s->start[row + 1] - s->start[row];
}

/* The coupling filter of the row of x palette a: -1 if it rules the whole row out; 1 with the y
 * positions its most selective pixel lets through marked in ws->ymark (words *lo_word .. *hi_word),
 * when that pixel is selective enough to pay; else 0 (nothing marked). */
static int filter_marks(search_state *st, const double a[8], const channel_side *xside, const ball_lines nball[16],
                        y_filter *yf, size_t *lo_word, size_t *hi_word)
{
    search_workspace *ws = st->ws;
    int filtered = y_filter_init(yf, a, xside, st->n, nball, st->order, st->loose, &st->aw, st->away_off, st->group,
                                 st->use_max, st->best, &st->yix);
    st->work += 64;
    if (filtered < 0)
        return -1;
    const int r0 = filtered > 0 ? yf->rank[0] : 0;
    if (!filtered || yf->items[r0] >= st->ny)
        return 0;
    *lo_word = (st->ny + 63) / 64;
    for (int k = 0; k < yf->cnt[r0]; ++k) {
        uint32_t s0 = st->yix.start[y_bucket(yf->lo[r0][k])], s1 = st->yix.start[y_bucket(yf->hi[r0][k]) + 1];
        for (uint32_t t = s0; t < s1; ++t) {
            if (st->yix.items[t].v < yf->lo[r0][k] || st->yix.items[t].v > yf->hi[r0][k])
                continue;
            uint32_t j = st->yix.items[t].j;
            ws->ymark[j >> 6] |= UINT64_C(1) << (j & 63);
            *lo_word = j >> 6 < *lo_word ? j >> 6 : *lo_word;
            *hi_word = (j >> 6) + 1 > *hi_word ? (j >> 6) + 1 : *hi_word;
        }
        st->work += s1 - s0;
    }
    return 1;
}

/* How often joint_objective_away rejects the candidates it meets: it runs while it rejects at least 1
 * in 8 (after 1024; else on every 16th candidate only, which keeps the count current). */
typedef struct away_use {
    uint64_t tried, hits;
} away_use;

/* The candidates of row i (x palette a, its channel side xside): the y positions marked in ws->ymark
 * below word hi_word (filtered) or all of them, in list order, until the combined score reaches the
 * incumbent, the work limit is met, or a new incumbent lets the pixel floor decide the block (solved).
 * Each candidate is rejected, if it can be, by the coupling filter's remaining pixels (filtered rows
 * without the screen), the quick bound, the coupled bound of pixels pointing away, and the lower
 * bound, and evaluated exactly otherwise. */
static void enumerate_row(search_state *st, size_t i, const double a[8], const channel_side *xside, int filtered,
                          int screened, const y_filter *yf, size_t hi_word, away_use *au)
{
    search_workspace *ws = st->ws;
    const double(*n)[3] = st->n;
    const int use_max = st->use_max;
    for (size_t j = 0; j < st->ny; ++j) {
        if (filtered) { /* the next marked position */
            size_t w = j >> 6;
            uint64_t bits = w < hi_word ? ws->ymark[w] & (~UINT64_C(0) << (j & 63)) : 0;
            while (!bits && ++w < hi_word)
                bits = ws->ymark[w];
            if (!bits)
                break;
            j = 64 * w + (size_t)__builtin_ctzll(bits);
        }
        if (combine(ws->x[i].score, ws->y[j].score, use_max) * (1.0 - BOUND_SLACK) >= st->best)
            break;
        if (st->work >= st->rq->work_limit) {
            st->bounded = 1;
            break;
        }
        if (filtered && !screened) {
            st->work += 4;
            if (!y_filter_pass(yf, st->pal[ws->y[j].pair]))
                continue;
        }
        ++st->candidates;
        /* the bounds are lowered against rounding already, BOUND_SLACK is a second margin; the
         * value-reduced lists (blocks near their hemisphere bound) take 1e-12 instead, which still
         * covers the different summation orders of bound and objective */
        const double margin = st->best * (1.0 + (st->valued ? 1e-12 : BOUND_SLACK));
        if (st->quick && sol_nm_bc5_joint_objective_quick(xside, &ws->yside[j], n, st->order, st->nz_ord,
                                                          st->away_off, use_max, margin, &st->work) >= margin)
            continue;
        if (st->quick && st->aw.mask && (au->tried < 1024 || 8 * au->hits >= au->tried || (st->candidates & 15) == 0)) {
            ++au->tried;
            if (joint_objective_away(a, st->pal[ws->y[j].pair], xside, &ws->yside[j], n, st->order, st->away_off,
                                     &st->aw, use_max, margin, &st->work) >= margin) {
                ++au->hits;
                continue;
            }
        }
        const double *b = st->pal[ws->y[j].pair];
        if ((st->repeats ? sol_nm_bc5_joint_objective_lower_grouped(a, b, n, st->group, st->order, st->away_off,
                                                                    use_max, st->best, margin, &st->work)
                         : sol_nm_bc5_joint_objective_lower(a, b, n, st->order, st->away_off, use_max, st->best,
                                                            margin, &st->work)) >= margin)
            continue;
        st->work += 512;
        double v = st->repeats ? sol_nm_bc5_joint_objective_grouped(a, b, n, st->group, use_max, st->best)
                               : sol_nm_bc5_joint_objective(a, b, n, use_max, st->best, NULL, NULL);
        if (v < st->best) {
            st->best = v;
            st->px = ws->x[i].pair;
            st->py = ws->y[j].pair;
            if (st->floored && pixel_floor_decides(ws->floor, n, &st->aw, st->pal[st->px], st->pal[st->py], st->best,
                                                   &st->work)) {
                st->solved = 1;
                break;
            }
        }
    }
}

/* The double loop over the lists, rows in x list order, stopping as soon as a row's combined bound
 * reaches the incumbent: the reductions due at each row (reduce_rest), then the row's y positions
 * that can still win (the pair screen's, or the coupling filter's) and its candidates. The pair screen
 * is built where the enumeration first reads it, after the reductions due at that row (issue 13:
 * built before the loop, it was built again at row 0 whenever reductions were due there, on the same
 * incumbent - a second identical screen when they removed nothing, a third of the survey's slowest
 * block), and again after later reductions that it cannot be carried over to (sc.due, reduce_rest). */
static void enumerate_candidates(search_state *st)
{
    search_workspace *ws = st->ws;
    screen_track sc = {0, st->filter && !st->solved && (ws->screen || (ws->screen = pair_screen_new())), 0, 0};
    channel_side xside;
    y_filter yf;
    ball_lines nball[16]; /* y_filter_init's exact balls' polar forms (their centre is n[p]) */
    for (int p = 0; p < 16 && st->filter; ++p)
        ball_lines_polar(&nball[p], st->n[p]);
    away_use au = {0, 0};
    for (size_t i = 0; i < st->nx && st->ny > 0 && !st->bounded && !st->solved; ++i) {
        if (combine(ws->x[i].score, ws->y[0].score, st->use_max) * (1.0 - BOUND_SLACK) >= st->best)
            break;
        if (st->work >= st->rq->work_limit) {
            st->bounded = 1;
            break;
        }
        if (((st->valued && st->best < st->reduce_at) || (st->coupled && st->best < st->couple_at)) &&
            !reduce_rest(st, i, &sc))
            break;
        if (sc.due) {
            sc.due = 0;
            sc.base = i;
            sc.screened = pair_screen_build(ws->screen, st->n, st->order, st->loose, &st->aw, st->away_off,
                                            st->use_max, st->best, st->pal, st->rq->precision, ws->x + i, st->nx - i,
                                            ws->y, st->ny, ws->yside, &st->work, st->rq->work_limit);
            sc.pairs = st->nx - i + st->ny;
        }
        if (sc.screened && ws->screen->start[i - sc.base] == ws->screen->start[i - sc.base + 1])
            continue; /* no candidate of the row can beat the incumbent */
        const double *a = st->pal[ws->x[i].pair];
        if (st->quick)
            sol_nm_bc5_channel_side_init(a, st->n, st->order, 0, &st->aw, &xside);
        int filtered = 0;
        size_t lo_word = 0, hi_word = 0; /* the marked words of ymark */
        if (sc.screened) {
            screen_marks(st, &sc, i, &lo_word, &hi_word);
            filtered = 1;
        } else if (st->filter) {
            filtered = filter_marks(st, a, &xside, nball, &yf, &lo_word, &hi_word);
            if (filtered < 0)
                continue;
        }
        enumerate_row(st, i, a, &xside, filtered, sc.screened, &yf, hi_word, &au);
        if (filtered)
            for (size_t w = lo_word; w < hi_word; ++w)
                ws->ymark[w] = 0;
    }
}

/* Branch and bound over (x pair, y pair) inside the range, for unit normals n.
 * 1. Incumbent: the better (first on ties) of the per-channel least-squares pairs (the common
 *    anchors) and the full-span 6-value pairs (0, 255) whose entries -1 and +1 reach the rim, both
 *    with joint indices (first_incumbents). If it meets hemisphere_bound it is optimal; on the full
 *    range, blocks of 16 equal normals are decided by a rule (equal_shortcut) where their values
 *    allow it (the others go on to solve_by_rule's equal_block_solve or the value-level reduction).
 * 2. Bound: for a candidate whose pixels all decode with x^2 + y^2 <= 1, dN_p^2 >= chord_p^2 >=
 *    min_a (a - nx_p)^2 + min_b (b - ny_p)^2, so the objective >= SX + SY (sum) or max(SX, SY) (max),
 *    with SX, SY the per-channel scores. A pixel decoding with z clamped to 0 has dN_p^2 >= chord^2
 *    >= nz_p^2, so where nz_p^2 exceeds the incumbent such a decode cannot win and the tight term is
 *    a valid bound; rim pixels (nz_p^2 <= incumbent) take the loose term, valid in every case
 *    (loose_incumbent, which adds the third incumbent).
 * 3. Lists of the pairs of each channel whose score leaves room under the incumbent, sorted by
 *    score (collect_lists), reduced (reduce_lists; equivalent pairs merged, see above); with the max
 *    metric the pixel floor may decide the block (floor_stage), and some blocks are decided by a rule
 *    (solve_by_rule). The double loop (enumerate_candidates)
 *    stops as soon as the combined bound reaches the incumbent. Each candidate is first rejected, if
 *    it can be, by lower bounds of its objective without atan2 (sol_nm_bc5_joint_objective_quick, then
 *    sol_nm_bc5_joint_objective_lower), and evaluated exactly only if it survives both.
 * 4. Work bound: after work_limit work units (a pixel of a candidate through the quick bound 1,
 *    through sol_nm_bc5_joint_objective_lower 32, an exact evaluation 512: about their relative costs) the
 *    search stops with the best found (info->bounded = 1). */
void sol_nm_bc5_search_unit(const double n[16][3], const search_request *rq, search_workspace *ws, sol_bc5_block *out,
                            sol_bc5_info *info) {
    const sol_bc5_range *r = rq->range;
    search_state st; /* not zero-initialised as a whole: its y index alone is 16 KB, set up where used */
    st.n = n;
    st.rq = rq;
    st.ws = ws;
    st.use_max = rq->use_max;
    st.bounded = st.solved = 0;
    st.work = 0;
    st.loose = 0;
    st.valued = st.coupled = st.floored = 0;
    st.reduce_at = st.couple_at = -1.0;
    st.quick = st.filter = 0;
    double min_nz2 = INFINITY;
    for (int p = 0; p < 16; ++p) {
        st.tx[p] = n[p][0];
        st.ty[p] = n[p][1];
        min_nz2 = n[p][2] * n[p][2] < min_nz2 ? n[p][2] * n[p][2] : min_nz2;
    }
    const int full = r->x0_lo == 0 && r->x0_hi == 255 && r->x1_lo == 0 && r->x1_hi == 255 && r->y0_lo == 0 &&
                     r->y0_hi == 255 && r->y1_lo == 0 && r->y1_hi == 255;
    double sx_min, sy_min;
    first_incumbents(&st, full, &sx_min, &sy_min);
    if (st.best > 0.0 && st.best > hemisphere_bound(n, st.use_max) &&
        !equal_shortcut(n, full, rq, &st.best, &st.px, &st.py, &st.candidates)) {
        size_t pre_x = SIZE_MAX, pre_y = SIZE_MAX; /* pairs collected with the argmins (argmin_collect) */
        away_info_init(&st.aw, n, 0);
        if (st.best * (1.0 + BOUND_SLACK) >= min_nz2)
            loose_incumbent(&st, &pre_x, &pre_y, &sx_min, &sy_min);
        collect_lists(&st, pre_x, pre_y, sx_min, sy_min);
        reduce_lists(&st);
        floor_stage(&st);
        visiting_order(&st);
        helpers_setup(&st);
        if (st.filter && (st.loose & 1))
            solve_by_rule(&st);
        enumerate_candidates(&st);
    }
    out->x.e0 = (uint8_t)(st.px >> 8);
    out->x.e1 = (uint8_t)(st.px & 255);
    out->y.e0 = (uint8_t)(st.py >> 8);
    out->y.e1 = (uint8_t)(st.py & 255);
    double check = sol_nm_bc5_joint_objective(st.pal[st.px], st.pal[st.py], n, st.use_max, INFINITY, out->x.index,
                                              out->y.index);
    if (info) {
        info->error = sol_nm_bc5_metric_value(check, st.use_max ? SOL_BC5_MAX : SOL_BC5_SUM_SQUARED);
        info->searched = 1;
        info->candidates = st.candidates;
        info->bounded = st.bounded;
    }
}

static sol_status workspace_alloc(search_workspace *ws)
{
    ws->x = malloc(65536 * sizeof *ws->x);
    ws->y = malloc(65536 * sizeof *ws->y);
    ws->slots = malloc(2 * 65536 * sizeof *ws->slots);
    ws->yside = NULL;
    ws->yside_cap = 0;
    ws->ybucket = NULL;
    ws->ymark = NULL;
    ws->ybucket_cap = ws->ymark_cap = 0;
    ws->vset = NULL;
    ws->vtab = NULL;
    ws->couple = NULL;
    ws->screen = NULL;
    ws->floor = NULL;
    ws->vgen = 0;
    ws->ktab = NULL;
    ws->kgen = 0;
    ws->kkey = NULL;
    ws->kkey_cap = 0;
    ws->sort_tmp = NULL;
    ws->win = sol_nm_bc5_window_scratch_new();
    if (!ws->x || !ws->y || !ws->slots || !ws->win) {
        free(ws->x);
        free(ws->y);
        free(ws->slots);
        free(ws->win);
        return SOL_ERR_NO_MEMORY;
    }
    return SOL_OK;
}

static void workspace_free(search_workspace *ws)
{
    free(ws->x);
    free(ws->y);
    free(ws->slots);
    free(ws->yside);
    free(ws->ybucket);
    free(ws->ymark);
    free(ws->vset);
    free(ws->vtab);
    free(ws->ktab);
    free(ws->kkey);
    free(ws->sort_tmp);
    sol_nm_couple_free(ws->couple);
    free(ws->screen);
    free(ws->floor);
    free(ws->win);
}

static const sol_bc5_range full_range = {0, 255, 0, 255, 0, 255, 0, 255};

sol_status sol_bc5_search_block(const double normals[16][3], const sol_bc5_range *range,
                                const sol_bc5_options *options, sol_bc5_block *out, sol_bc5_info *info)
{
    static const sol_bc5_options defaults;
    if (!normals || !out)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    const sol_bc5_range *r = range ? range : &full_range;
    if (check_options(o) != SOL_OK || r->x0_lo > r->x0_hi || r->x1_lo > r->x1_hi || r->y0_lo > r->y0_hi ||
        r->y1_lo > r->y1_hi)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    search_workspace ws;
    if ((st = workspace_alloc(&ws)) != SOL_OK)
        return st;
    search_request rq = {r, o->precision, o->metric == SOL_BC5_MAX, sol_nm_bc5_work_limit(o)};
    sol_nm_bc5_search_unit(n, &rq, &ws, out, info);
    workspace_free(&ws);
    return SOL_OK;
}

/* ---- the three encoders ---- */

/* Common encoder: two independent least-squares BC4 blocks, indices by nearest component (T10).
 * tx, ty: the x and y components of the unit normals; *sx, *sy: the two channels' least sums. */
static void encode_common(const double tx[16], const double ty[16], sol_bc4_precision precision, sol_bc5_block *out,
                          double *sx, double *sy)
{
    int px = sol_nm_bc4_common(tx, precision, sx), py = sol_nm_bc4_common(ty, precision, sy);
    const double(*pal)[8] = sol_nm_palettes(precision);
    out->x.e0 = (uint8_t)(px >> 8);
    out->x.e1 = (uint8_t)(px & 255);
    out->y.e0 = (uint8_t)(py >> 8);
    out->y.e1 = (uint8_t)(py & 255);
    sol_nm_nearest_indices(pal[px], tx, out->x.index);
    sol_nm_nearest_indices(pal[py], ty, out->y.index);
}

static double own_index_objective(const sol_bc5_block *b, const double n[16][3], sol_bc4_precision precision,
                                  int use_max)
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    const double *a = pal[b->x.e0 << 8 | b->x.e1], *c = pal[b->y.e0 << 8 | b->y.e1];
    double s = 0.0;
    for (int p = 0; p < 16; ++p) {
        double e = decoded_angle(a[b->x.index[p]], c[b->y.index[p]], n[p]);
        s = fold_term(s, e * e, use_max);
    }
    return s;
}

static uint8_t clamp_code(int v)
{
    return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
}

/* One block with validated options and unit normals n (t[c][p] = n[p][c], the per-channel view). info may
 * be NULL; with want_error 0, info->error is left NAN where the block is not searched (the image
 * encoders need no error: the adaptive threshold is then decided from chord bounds,
 * sol_nm_threshold_test, and the angles computed only where the bounds cannot decide; the blocks
 * and the searched / candidates / bounded counts are the same either way). */
static void encode_unit(const double n[16][3], const double t[3][16], const sol_bc5_options *o, search_workspace *ws,
                        sol_bc5_block *out, sol_bc5_info *info, int want_error)
{
    int use_max = o->metric == SOL_BC5_MAX;
    if (o->encoder == SOL_BC5_OPTIMAL) {
        search_request rq = {&full_range, o->precision, use_max, sol_nm_bc5_work_limit(o)};
        sol_nm_bc5_search_unit(n, &rq, ws, out, info);
        return;
    }
    const double gap = o->gap == 0.0 ? SOL_BC5_DEFAULT_GAP : o->gap; /* <= 0: no gap test, exact window */
    sol_bc5_block base;
    double sx = 0.0, sy = 0.0;
    int gap_test = 0; /* the skip test (common base only) */
    if (o->encoder == SOL_BC5_FAST || (o->encoder == SOL_BC5_ADAPTIVE && o->base == SOL_BC5_BASE_FAST)) {
        sol_nm_bc4_fast(t[0], &base.x);
        sol_nm_bc4_fast(t[1], &base.y);
    } else {
        encode_common(t[0], t[1], o->precision, &base, &sx, &sy);
        gap_test = o->encoder == SOL_BC5_ADAPTIVE && gap > 0.0;
    }
    double err = NAN;
    int search = 0;
    if (o->encoder == SOL_BC5_ADAPTIVE) {
        /* adaptive: RMS (or max) angle in degrees against the threshold (T13), and the objective
         * against the gap's limit (options.gap): searched only if both ask for it. Both are decided
         * from the chord bounds lo <= err <= hi where they can be, else from the exact err; the
         * limit, (1 + gap) times the bound of every block's objective with the cap hi, is the same
         * whether or not the caller wants the error, so is the decision. */
        const double(*pal)[8] = sol_nm_palettes(o->precision);
        double lo, hi, limit = -INFINITY; /* -INFINITY: no gap test */
        sol_nm_chord_bounds(pal[base.x.e0 << 8 | base.x.e1], pal[base.y.e0 << 8 | base.y.e1], &base, t, use_max, &lo,
                            &hi);
        int by_level = sol_nm_threshold_decide(lo, hi, use_max, o->threshold_deg);
        if (gap_test && by_level != 0) { /* (a block the level keeps is kept whatever the limit) */
            /* the separable bound first (cap 0: no tilt bound): where hi is within it, the full
             * bound (at least as large) skips the block too, with either err */
            limit = (1.0 + gap) * sol_nm_gap_bound(sx, sy, t, use_max, 0.0);
            if (!(hi <= limit))
                limit = (1.0 + gap) * sol_nm_gap_bound(sx, sy, t, use_max, hi);
        }
        int by_gap = sol_nm_gap_test(lo, hi, limit);
        search = by_level == 0 || by_gap == 0 ? 0 : by_level == 1 && by_gap == 1 ? 1 : -1;
        if (want_error || search < 0) {
            err = own_index_objective(&base, n, o->precision, use_max);
            search = !(sol_nm_threshold_level(err, use_max) <= o->threshold_deg) && !(err <= limit);
        }
    } else if (want_error)
        err = own_index_objective(&base, n, o->precision, use_max);
    if (!search) {
        *out = base;
        if (info) {
            info->error = want_error ? sol_nm_bc5_metric_value(err, o->metric) : NAN;
            info->searched = 0;
            info->candidates = 1;
            info->bounded = 0;
        }
        return;
    }
    int w = o->window == 0 ? 4 : (o->window < 0 ? 0 : o->window > 255 ? 255 : o->window); /* 255: all codes */
    sol_bc5_range r = {clamp_code(base.x.e0 - w), clamp_code(base.x.e0 + w), clamp_code(base.x.e1 - w),
                       clamp_code(base.x.e1 + w), clamp_code(base.y.e0 - w), clamp_code(base.y.e0 + w),
                       clamp_code(base.y.e1 - w), clamp_code(base.y.e1 + w)};
    search_request rq = {&r, o->precision, use_max, sol_nm_bc5_work_limit(o)};
    /* the window's relative tolerance (either base): 1 / (1 + gap), 1 = exact */
    double shrink = gap > 0.0 ? 1.0 / (1.0 + gap) : 1.0;
    if (!sol_nm_bc5_window_search(n, &r, base.x.e0 << 8 | base.x.e1, base.y.e0 << 8 | base.y.e1,
                                  o->base != SOL_BC5_BASE_FAST, shrink, &rq, ws, out, info))
        sol_nm_bc5_search_unit(n, &rq, ws, out, info);
}

/* sol_bc5_encode_block's checks and encode with workspace ws (NULL: one allocated for the call, if
 * the encoder searches). */
static sol_status encode_block_in(search_workspace *ws, const double normals[16][3], const sol_bc5_options *options,
                                  sol_bc5_block *out, sol_bc5_info *info)
{
    static const sol_bc5_options defaults;
    if (!normals || !out)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    if (check_options(o) != SOL_OK)
        return SOL_ERR_INVALID_ARG;
    double n[16][3];
    sol_status st = sol_nm_unit_normals(normals, n);
    if (st != SOL_OK)
        return st;
    search_workspace own = {0};
    const int searches = o->encoder != SOL_BC5_COMMON && o->encoder != SOL_BC5_FAST;
    if (!ws && searches && (st = workspace_alloc(&own)) != SOL_OK)
        return st;
    double t[3][16];
    for (int p = 0; p < 16; ++p)
        for (int c = 0; c < 3; ++c)
            t[c][p] = n[p][c];
    encode_unit(n, (const double(*)[16])t, o, ws ? ws : &own, out, info, info != NULL);
    if (!ws)
        workspace_free(&own);
    return SOL_OK;
}

sol_status sol_bc5_encode_block(const double normals[16][3], const sol_bc5_options *options, sol_bc5_block *out,
                                sol_bc5_info *info)
{
    return encode_block_in(NULL, normals, options, out, info);
}

struct sol_bc5_workspace {
    search_workspace ws;
};

sol_bc5_workspace *sol_bc5_workspace_new(void)
{
    sol_bc5_workspace *e = malloc(sizeof *e);
    if (e && workspace_alloc(&e->ws) != SOL_OK) {
        free(e);
        e = NULL;
    }
    return e;
}

void sol_bc5_workspace_free(sol_bc5_workspace *workspace)
{
    if (!workspace)
        return;
    workspace_free(&workspace->ws);
    free(workspace);
}

sol_status sol_bc5_encode_block_with(sol_bc5_workspace *workspace, const double normals[16][3],
                                     const sol_bc5_options *options, sol_bc5_block *out, sol_bc5_info *info)
{
    if (!workspace)
        return SOL_ERR_NULL_ARG;
    return encode_block_in(&workspace->ws, normals, options, out, info);
}

/* ---- images ---- */

static void gather_block(const sol_image *img, int bx, int by, double n[16][3])
{
    for (int p = 0; p < 16; ++p) {
        const float *v = sol_image_pixel(img, 4 * bx + (p & 3), 4 * by + (p >> 2));
        for (int c = 0; c < 3; ++c)
            n[p][c] = v[c];
    }
}

static void pack_block(const sol_bc5_block *b, uint8_t out[16])
{
    sol_bc4_pack(&b->x, out);
    sol_bc4_pack(&b->y, out + 8);
}

/* SOL_OK if sol_nm_unit_normals accepts every block of img, else the status of the first block
 * it refuses (blocks in raster order). It refuses a pixel only if a component is not finite or all
 * three are zero; one pass over the pixels tells whether any does, and only then are the blocks
 * gone through in order to name the first refusal's status. */
static sol_status check_normals(const sol_image *img, int bw, int nblocks)
{
    const size_t n = (size_t)img->width * (size_t)img->height;
    int bad = 0;
    size_t i = 0;
#if defined(__SSE2__) /* 4 pixels (12 floats) at a time */
    const __m128 sign = _mm_set1_ps(-0.0f), big = _mm_set1_ps(FLT_MAX), zero = _mm_setzero_ps();
    for (; i + 4 <= n && !bad; i += 4) {
        const float *v = img->data + 3 * i;
        __m128 a = _mm_loadu_ps(v), b = _mm_loadu_ps(v + 4), c = _mm_loadu_ps(v + 8);
        int finite = _mm_movemask_ps(_mm_and_ps(_mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(sign, a), big),
                                                           _mm_cmple_ps(_mm_andnot_ps(sign, b), big)),
                                                _mm_cmple_ps(_mm_andnot_ps(sign, c), big)));
        /* bit 3 k + j: component j of pixel k is zero; a pixel is refused if its three bits are set */
        unsigned z = (unsigned)_mm_movemask_ps(_mm_cmpeq_ps(a, zero)) |
                     (unsigned)_mm_movemask_ps(_mm_cmpeq_ps(b, zero)) << 4 |
                     (unsigned)_mm_movemask_ps(_mm_cmpeq_ps(c, zero)) << 8;
        bad = finite != 15 || (z & z >> 1 & z >> 2 & 01111u) != 0;
    }
#endif
    for (; i < n && !bad; ++i) {
        const float *v = img->data + 3 * i;
        bad = !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]) || (v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f);
    }
    if (!bad)
        return SOL_OK;
    for (int b = 0; b < nblocks; ++b) {
        double raw[16][3], n16[16][3];
        gather_block(img, b % bw, b / bw, raw);
        sol_status st = sol_nm_unit_normals(raw, n16);
        if (st != SOL_OK)
            return st;
    }
    return SOL_OK;
}

/* The fast encoder on block (bx, by) of a checked image: x and y of the unit normals, each the
 * quotient sol_nm_unit_normals computes (the same length, the same division; a float pixel that is
 * not zero has a length in [1e-45, 1e39], inside the range where it skips rescaling), straight from
 * the image rows, then the two alpha blocks. */
static void encode_fast_pixels(const sol_image *img, int bx, int by, sol_bc5_block *out)
{
    double x[16], y[16], z[16], tx[16], ty[16];
    for (int p = 0; p < 16; ++p) {
        const float *v = sol_image_pixel(img, 4 * bx + (p & 3), 4 * by + (p >> 2));
        x[p] = v[0];
        y[p] = v[1];
        z[p] = v[2];
    }
#if defined(__SSE2__) /* two pixels at a time: the same correctly rounded operations in the same order */
    for (int p = 0; p < 16; p += 2) {
        __m128d a = _mm_loadu_pd(x + p), b = _mm_loadu_pd(y + p), c = _mm_loadu_pd(z + p);
        __m128d len = _mm_sqrt_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(a, a), _mm_mul_pd(b, b)), _mm_mul_pd(c, c)));
        _mm_storeu_pd(tx + p, _mm_div_pd(a, len));
        _mm_storeu_pd(ty + p, _mm_div_pd(b, len));
    }
#else
    for (int p = 0; p < 16; ++p) {
        double len = sqrt(x[p] * x[p] + y[p] * y[p] + z[p] * z[p]);
        tx[p] = x[p] / len;
        ty[p] = y[p] / len;
    }
#endif
    sol_nm_bc4_fast(tx, &out->x);
    sol_nm_bc4_fast(ty, &out->y);
}

sol_status sol_bc5_encode_image(const sol_image *normals, const sol_bc5_options *options, uint8_t *blocks,
                                sol_bc5_image_stats *stats)
{
    static const sol_bc5_options defaults;
    if (!normals || !normals->data || !blocks)
        return SOL_ERR_NULL_ARG;
    const sol_bc5_options *o = options ? options : &defaults;
    if (check_options(o) != SOL_OK || normals->channels != 3 || normals->width <= 0 || normals->height <= 0 ||
        normals->width % 4 || normals->height % 4)
        return SOL_ERR_INVALID_ARG;
    const int bw = normals->width / 4, nblocks = bw * (normals->height / 4);
    /* validate everything first, so the parallel part cannot fail on input */
    sol_status st = check_normals(normals, bw, nblocks);
    if (st != SOL_OK)
        return st;
    uint64_t searched = 0, candidates = 0, bounded = 0, max_cand = 0;
    int max_block = -1;
    int failed = 0;
#pragma omp parallel reduction(+ : searched, candidates, bounded) reduction(| : failed)
    {
        search_workspace ws = {0};
        if (o->encoder != SOL_BC5_COMMON && o->encoder != SOL_BC5_FAST && workspace_alloc(&ws) != SOL_OK)
            failed = 1;
        uint64_t my_max = 0;
        int my_block = -1;
#pragma omp for schedule(dynamic, 16)
        for (int b = 0; b < nblocks; ++b) {
            if (failed)
                continue;
            sol_bc5_block block;
            if (o->encoder == SOL_BC5_FAST) { /* no statistics to gather: candidates 1, nothing searched */
                encode_fast_pixels(normals, b % bw, b / bw, &block);
                pack_block(&block, blocks + 16 * (size_t)b);
                candidates += 1;
                if (my_block < 0) /* every block ties at 1 candidate: the first is the costliest */
                    my_block = b;
                my_max = 1;
                continue;
            }
            double n[16][3], t[3][16];
            sol_nm_unit_pixels(normals, b % bw, b / bw, n, t);
            sol_bc5_info info = {0.0, 0, 1, 0};
            encode_unit(n, (const double(*)[16])t, o, &ws, &block, &info, 0);
            pack_block(&block, blocks + 16 * (size_t)b);
            searched += (uint64_t)info.searched;
            bounded += (uint64_t)info.bounded;
            candidates += info.candidates;
            if (my_block < 0 || info.candidates > my_max) { /* blocks ascend within a thread */
                my_max = info.candidates;
                my_block = b;
            }
        }
#pragma omp critical(sol_bc5_max_block)
        if (my_block >= 0 && (max_block < 0 || my_max > max_cand || (my_max == max_cand && my_block < max_block))) {
            max_cand = my_max;
            max_block = my_block;
        }
        workspace_free(&ws);
    }
    if (failed)
        return SOL_ERR_NO_MEMORY;
    if (stats) {
        memset(stats, 0, sizeof *stats); /* padding too: callers compare stats bytewise (make bench) */
        stats->blocks = (uint64_t)nblocks;
        stats->searched_blocks = searched;
        stats->candidates = candidates;
        stats->bounded_blocks = bounded;
        stats->max_block_candidates = max_cand;
        stats->max_block = max_block;
    }
    return SOL_OK;
}

sol_status sol_bc5_decode_image(const uint8_t *blocks, int width, int height, sol_bc4_precision precision,
                                sol_image *out)
{
    if (!blocks || !out)
        return SOL_ERR_NULL_ARG;
    if (width <= 0 || height <= 0 || width % 4 || height % 4 || (unsigned)precision >= SOL_BC4_PRECISION_COUNT)
        return SOL_ERR_INVALID_ARG;
    sol_image img;
    sol_status st = sol_image_alloc(&img, width, height, 3);
    if (st != SOL_OK)
        return st;
    const int bw = width / 4, nblocks = bw * (height / 4);
    for (int b = 0; b < nblocks; ++b) {
        sol_bc5_block block;
        double d[16][3];
        sol_bc4_unpack(blocks + 16 * (size_t)b, &block.x);
        sol_bc4_unpack(blocks + 16 * (size_t)b + 8, &block.y);
        sol_bc5_decode_block(&block, precision, d);
        for (int p = 0; p < 16; ++p) {
            float *v = sol_image_pixel(&img, 4 * (b % bw) + (p & 3), 4 * (b / bw) + (p >> 2));
            double len = sqrt(d[p][0] * d[p][0] + d[p][1] * d[p][1] + d[p][2] * d[p][2]);
            for (int c = 0; c < 3; ++c)
                v[c] = (float)(d[p][c] / len);
        }
    }
    *out = img;
    return SOL_OK;
}
