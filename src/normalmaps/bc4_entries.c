/* bc4_entries.c - every palette entry of the 65536 BC4 anchor pairs, indexed by its value: for each
 * distinct decoded value, the pairs whose palette holds it (ascending pair index), each with a lower
 * bound of the distance from that value to the pair's nearest other entry. The common encoder's
 * search of blocks with few distinct values (bc4_common.c, narrow_walk) walks the values outward
 * from a target and lists the pairs holding each: a pair's term for that target is decided by the
 * entry of its palette nearest to it, so this is every pair, ordered by that term.
 * Built once per decoder precision from the palette table (sol_nm_palettes), on first use. */
#include "normalmaps_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct entry_rec {
    uint64_t key; /* the value's bits, mapped so that unsigned order is numeric order */
    float gap;
    uint16_t pair;
} entry_rec;

static sol_nm_entry_index indexes[SOL_BC4_PRECISION_COUNT];
static pthread_once_t index_once[SOL_BC4_PRECISION_COUNT] = {PTHREAD_ONCE_INIT, PTHREAD_ONCE_INIT,
                                                             PTHREAD_ONCE_INIT};

static uint64_t value_key(double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return u >> 63 ? ~u : u | (UINT64_C(1) << 63);
}

static double key_value(uint64_t k)
{
    uint64_t u = k >> 63 ? k & ~(UINT64_C(1) << 63) : ~k;
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static void build_index(sol_bc4_precision precision)
{
    const double(*pal)[8] = sol_nm_palettes(precision);
    entry_rec *a = malloc(sizeof *a * 65536 * 8), *b = malloc(sizeof *b * 65536 * 8);
    uint32_t *count = malloc(sizeof *count * 65536);
    sol_nm_entry_index *ix = &indexes[precision];
    if (!a || !b || !count)
        goto done;
    /* one record per distinct entry of each pair, in pair order */
    size_t n = 0;
    for (int pair = 0; pair < 65536; ++pair) {
        double v[8];
        int nd = 0;
        for (int i = 0; i < 8; ++i) {
            double x = pal[pair][i] + 0.0; /* -0 as +0 */
            int seen = 0;
            for (int j = 0; j < nd; ++j)
                seen |= v[j] == x;
            if (!seen)
                v[nd++] = x;
        }
        for (int i = 0; i < nd; ++i) {
            double g = INFINITY;
            for (int j = 0; j < nd; ++j)
                if (j != i)
                    g = fmin(g, fabs(v[j] - v[i]));
            float gf = (float)g; /* rounded down: a lower bound */
            if ((double)gf > g)
                gf = nextafterf(gf, 0.0f);
            a[n++] = (entry_rec){value_key(v[i]), gf, (uint16_t)pair};
        }
    }
    /* stable LSD radix sort by key, 16 bits a pass: equal values keep the ascending pair order */
    for (int shift = 0; shift < 64; shift += 16) {
        memset(count, 0, sizeof *count * 65536);
        for (size_t i = 0; i < n; ++i)
            ++count[(a[i].key >> shift) & 0xffff];
        uint32_t sum = 0;
        for (int d = 0; d < 65536; ++d) {
            uint32_t c = count[d];
            count[d] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; ++i)
            b[count[(a[i].key >> shift) & 0xffff]++] = a[i];
        entry_rec *t = a;
        a = b;
        b = t;
    }
    size_t nv = 0;
    for (size_t i = 0; i < n; ++i)
        nv += i == 0 || a[i].key != a[i - 1].key;
    double *value = malloc(sizeof *value * nv);
    uint32_t *start = malloc(sizeof *start * (nv + 1));
    uint16_t *pairs = malloc(sizeof *pairs * n);
    float *gap = malloc(sizeof *gap * n);
    if (!value || !start || !pairs || !gap) {
        free(value);
        free(start);
        free(pairs);
        free(gap);
        goto done;
    }
    size_t v = 0;
    for (size_t i = 0; i < n; ++i) {
        if (i == 0 || a[i].key != a[i - 1].key) {
            value[v] = key_value(a[i].key);
            start[v++] = (uint32_t)i;
        }
        pairs[i] = a[i].pair;
        gap[i] = a[i].gap;
    }
    start[nv] = (uint32_t)n;
    ix->count = nv;
    ix->value = value;
    ix->start = start;
    ix->pair = pairs;
    ix->gap = gap;
done:
    free(a);
    free(b);
    free(count);
}

static void build_16bit(void) { build_index(SOL_BC4_INTERP_16BIT); }
static void build_8bit(void) { build_index(SOL_BC4_INTERP_8BIT); }
static void build_float(void) { build_index(SOL_BC4_INTERP_FLOAT); }

const sol_nm_entry_index *sol_nm_entry_index_get(sol_bc4_precision precision)
{
    static void (*const builders[SOL_BC4_PRECISION_COUNT])(void) = {build_16bit, build_8bit, build_float};
    pthread_once(&index_once[precision], builders[precision]);
    return indexes[precision].value ? &indexes[precision] : NULL;
}
