/* compare_stats.c — regression-gate statistics (see compare_stats.h). */
#include "models/compare_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "models/rng.h"
#include "models/stats.h"

/* Median of a bootstrap resample of the m values s, using scratch tmp. */
static double compare__resample_median(const double *s, size_t m, double *tmp, rng_state *r)
{
    for (size_t i = 0; i < m; i++)
        tmp[i] = s[rng_below(r, m)];
    return stats_median(tmp, m);
}

int compare_stats_ratio_ci(const double *base, size_t n_base, const double *new_, size_t n_new,
                           double level, uint64_t seed, compare_ratio *out)
{
    size_t mb, mn;
    double *sb = stats_sorted_finite(base, n_base, &mb), *sn = stats_sorted_finite(new_, n_new, &mn);
    int rc = DM_ERR_ARG;
    memset(out, 0, sizeof *out);
    if (!mb || !mn || !(level > 0.0 && level < 1.0) || stats_quantile_sorted(sb, mb, 0.5) == 0.0)
        goto out;
    out->ratio = stats_quantile_sorted(sn, mn, 0.5) / stats_quantile_sorted(sb, mb, 0.5);
    if (mb == mn && memcmp(sb, sn, mb * sizeof *sb) == 0) {
        /* the same sample on both sides (a run against itself): resampling
         * both with the same draws — they are one sample — gives a ratio of
         * exactly 1 every time, so the CI is [1, 1], never a guess */
        out->lo = out->hi = 1.0;
        rc = 0;
        goto out;
    }
    double *ratios = dm_xmalloc(STATS_BOOTSTRAP_B * sizeof *ratios);
    double *tmp = dm_xmalloc((mb > mn ? mb : mn) * sizeof *tmp);
    rng_state r = rng_seed(seed);
    for (size_t b = 0; b < STATS_BOOTSTRAP_B; b++) {
        double mdb = compare__resample_median(sb, mb, tmp, &r);
        ratios[b] = compare__resample_median(sn, mn, tmp, &r) / mdb;
    }
    /* a resampled base median of 0 gives +-Inf/NaN; stats_quantile drops
     * non-finite values, which is the conservative choice for a gate */
    out->lo = stats_quantile(ratios, STATS_BOOTSTRAP_B, (1.0 - level) / 2.0);
    out->hi = stats_quantile(ratios, STATS_BOOTSTRAP_B, 1.0 - (1.0 - level) / 2.0);
    free(tmp);
    free(ratios);
    rc = 0;
out:
    free(sb);
    free(sn);
    return rc;
}

/* Exact two-sided p of U = u: c[i][j][k] counts arrangements with U = k
 * for sizes (i, j): c[i-1][j][k-j] + c[i][j-1][k] (the largest value
 * comes from a, beating all j of b, or from b). */
static double compare__exact_p(size_t na, size_t nb, double u)
{
    size_t umax = na * nb, W = umax + 1;
    double *c = dm_xcalloc((na + 1) * (nb + 1) * W, sizeof *c);
#define C(i, j, k) c[((i) * (nb + 1) + (j)) * W + (k)]
    for (size_t i = 0; i <= na; i++)
        for (size_t j = 0; j <= nb; j++)
            for (size_t k = 0; k <= i * j; k++)
                C(i, j, k) = (i == 0 || j == 0) ? (k == 0)
                           : (k >= j ? C(i - 1, j, k - j) : 0.0) + C(i, j - 1, k);
    double below = 0.0, above = 0.0, total = 0.0;
    for (size_t k = 0; k <= umax; k++) {
        total += C(na, nb, k);
        below += (double)k <= u ? C(na, nb, k) : 0.0;
        above += (double)k >= u ? C(na, nb, k) : 0.0;
    }
#undef C
    free(c);
    return fmin(1.0, 2.0 * fmin(below, above) / total);
}

typedef struct compare__item { double v; int from_a; } compare__item;

static int compare__cmp(const void *x, const void *y)
{
    double a = ((const compare__item *)x)->v, b = ((const compare__item *)y)->v;
    return (a > b) - (a < b);
}

/* Rank sum of sample a (midranks) and the tie term sum(t^3 - t). */
static double compare__rank_sum(compare__item *it, size_t n, double *ties)
{
    double ra = 0.0;
    *ties = 0.0;
    qsort(it, n, sizeof *it, compare__cmp);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && it[j].v == it[i].v)
            j++;
        double t = (double)(j - i), mid = (double)(i + j + 1) / 2.0;
        *ties += t * t * t - t;
        for (size_t k = i; k < j; k++)
            ra += it[k].from_a ? mid : 0.0;
        i = j;
    }
    return ra;
}

double compare_stats_mann_whitney(const double *a, size_t na, const double *b, size_t nb,
                                  double *u)
{
    compare__item *it = dm_xmalloc((na + nb + 1) * sizeof *it);
    size_t n1 = 0, n = 0;
    for (size_t i = 0; i < na; i++)
        if (isfinite(a[i]))
            it[n++] = (compare__item){ a[i], 1 };
    n1 = n;
    for (size_t i = 0; i < nb; i++)
        if (isfinite(b[i]))
            it[n++] = (compare__item){ b[i], 0 };
    size_t n2 = n - n1;
    double ties = 0.0;
    double ua = n1 && n2 ? compare__rank_sum(it, n, &ties) - (double)(n1 * (n1 + 1)) / 2.0 : NAN;
    free(it);
    if (u)
        *u = ua;
    if (!n1 || !n2)
        return NAN;
    if (ties == 0.0 && n1 <= COMPARE_STATS_EXACT_MAX && n2 <= COMPARE_STATS_EXACT_MAX)
        return compare__exact_p(n1, n2, ua);
    double N = (double)n, mu = (double)(n1 * n2) / 2.0;
    double var = (double)(n1 * n2) / 12.0 * ((N + 1.0) - ties / (N * (N - 1.0)));
    if (!(var > 0.0))
        return 1.0;
    double z = fmax(0.0, fabs(ua - mu) - 0.5) / sqrt(var);
    return erfc(z / sqrt(2.0));
}

static int compare__idx_cmp(const void *x, const void *y, void *pv)
{
    const double *p = pv;
    double a = p[*(const size_t *)x], b = p[*(const size_t *)y];
    return (a > b) - (a < b);
}

void compare_stats_bh(const double *p, size_t n, double *q)
{
    size_t *idx = dm_xmalloc((n ? n : 1) * sizeof *idx);
    double *pv = dm_xmalloc((n ? n : 1) * sizeof *pv);
    memcpy(pv, p, n * sizeof *pv);
    for (size_t i = 0; i < n; i++)
        idx[i] = i;
    qsort_r(idx, n, sizeof *idx, compare__idx_cmp, pv);
    double run = 1.0;
    for (size_t k = n; k > 0; k--) {
        run = fmin(run, pv[idx[k - 1]] * (double)n / (double)k);
        q[idx[k - 1]] = run;
    }
    free(pv);
    free(idx);
}
