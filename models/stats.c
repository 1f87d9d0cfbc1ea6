/* stats.c — descriptive statistics for timing samples (see stats.h). */
#include "models/stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "models/rng.h"

static int stats__cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double *stats_sorted_finite(const double *x, size_t n, size_t *m)
{
    double *s = n ? dm_xmalloc(n * sizeof *s) : NULL;
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]))
            s[k++] = x[i];
    if (k)
        qsort(s, k, sizeof *s, stats__cmp);
    *m = k;
    return s;
}

double stats_quantile_sorted(const double *s, size_t m, double q)
{
    double h = (double)(m - 1) * q;
    size_t lo = (size_t)floor(h);
    if (lo + 1 >= m)
        return s[m - 1];
    return s[lo] + (h - (double)lo) * (s[lo + 1] - s[lo]);
}

double stats_quantile(const double *x, size_t n, double q)
{
    size_t m;
    if (!(q >= 0.0 && q <= 1.0))
        return NAN;
    double *s = stats_sorted_finite(x, n, &m);
    double v = m ? stats_quantile_sorted(s, m, q) : NAN;
    free(s);
    return v;
}

double stats_median(const double *x, size_t n)
{
    return stats_quantile(x, n, 0.5);
}

/* Reorders v[0..m) so that v[k] is its k-th smallest value (0-based), no
 * greater one before it and no smaller one after (Hoare's selection,
 * median-of-three pivot); returns v[k]. */
static double stats__select(double *v, size_t m, size_t k)
{
    size_t lo = 0, hi = m - 1;
    while (lo < hi) {
        double a = v[lo], b = v[lo + (hi - lo) / 2], c = v[hi];
        double p = a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
        size_t i = lo, j = hi;
        for (;;) {   /* v[lo..i) <= p, v(j..hi] >= p */
            while (v[i] < p)
                i++;
            while (p < v[j])
                j--;
            if (i >= j)
                break;
            double t = v[i];
            v[i++] = v[j];
            v[j--] = t;
        }
        /* v[lo..j] <= p <= v[j+1..hi] (i >= j: the scans met) */
        if (i == j && k == j)
            return v[k];
        if (k <= j && j < hi)
            hi = j;
        else if (k > j && j >= lo)
            lo = j + 1;
        else
            break;   /* no progress (not reached with finite values) */
    }
    return v[k];
}

double stats_median_inplace(double *v, size_t m)
{
    if (m == 0)
        return NAN;
    double hi = stats__select(v, m, m / 2);
    if (m % 2)
        return hi;
    double lo = v[0];   /* the largest of the lower half: v[0..m/2) <= hi */
    for (size_t i = 1; i < m / 2; i++)
        lo = v[i] > lo ? v[i] : lo;
    return (lo + hi) / 2;
}

/* P(B <= j) for B ~ Binomial(n, 1/2), summed in log space so that large n
 * neither overflows the binomial coefficient nor underflows 2^-n. */
static double stats__binom_half_cdf(size_t n, size_t j)
{
    double sum = 0.0, ln = lgamma((double)n + 1.0) - (double)n * log(2.0);
    for (size_t i = 0; i <= j && i <= n; i++)
        sum += exp(ln - lgamma((double)i + 1.0) - lgamma((double)(n - i) + 1.0));
    return sum;
}

size_t stats_median_ci_rank(size_t n, double level, double *coverage)
{
    size_t best = 0;
    double cov = NAN;
    for (size_t k = 1; 2 * k <= n; k++) {
        double c = 1.0 - 2.0 * stats__binom_half_cdf(n, k - 1);
        if (c < level)
            break;
        best = k;
        cov = c;
    }
    if (coverage)
        *coverage = cov;
    return best;
}

/* Percentile bootstrap CI of the median of the m sorted values s. */
static void stats__bootstrap_median_ci(const double *s, size_t m, uint64_t seed,
                                       double *lo, double *hi)
{
    rng_state r = rng_seed(seed);
    double *meds = dm_xmalloc(STATS_BOOTSTRAP_B * sizeof *meds);
    double *res = dm_xmalloc(m * sizeof *res);
    for (size_t b = 0; b < STATS_BOOTSTRAP_B; b++) {
        for (size_t i = 0; i < m; i++)
            res[i] = s[rng_below(&r, m)];
        qsort(res, m, sizeof *res, stats__cmp);
        meds[b] = stats_quantile_sorted(res, m, 0.5);
    }
    qsort(meds, STATS_BOOTSTRAP_B, sizeof *meds, stats__cmp);
    *lo = stats_quantile_sorted(meds, STATS_BOOTSTRAP_B, 0.025);
    *hi = stats_quantile_sorted(meds, STATS_BOOTSTRAP_B, 0.975);
    free(res);
    free(meds);
}

/* Mean, sample stddev and raw MAD of m sorted finite values. */
static void stats__moments(const double *s, size_t m, stats_summary *out)
{
    double sum = 0.0, ss = 0.0;
    for (size_t i = 0; i < m; i++)
        sum += s[i];
    out->mean = sum / (double)m;
    for (size_t i = 0; i < m; i++)
        ss += (s[i] - out->mean) * (s[i] - out->mean);
    out->stddev = m > 1 ? sqrt(ss / (double)(m - 1)) : NAN;
    out->cv = (m > 1 && out->mean != 0.0) ? out->stddev / out->mean : NAN;
    double *dev = dm_xmalloc(m * sizeof *dev);
    for (size_t i = 0; i < m; i++)
        dev[i] = fabs(s[i] - out->median);
    qsort(dev, m, sizeof *dev, stats__cmp);
    out->mad = stats_quantile_sorted(dev, m, 0.5);
    free(dev);
}

int stats_summarize(const double *x, size_t n, uint64_t seed, stats_summary *out)
{
    size_t m;
    double *s = stats_sorted_finite(x, n, &m);
    memset(out, 0, sizeof *out);
    out->n_nonfinite = n - m;
    if (m == 0) {
        free(s);
        return DM_ERR_ARG;
    }
    out->n = m;
    out->min = s[0];
    out->max = s[m - 1];
    out->median = stats_quantile_sorted(s, m, 0.5);
    stats__moments(s, m, out);
    size_t k = stats_median_ci_rank(m, 0.95, NULL);
    if (k) {
        out->ci_lo = s[k - 1];
        out->ci_hi = s[m - k];
    } else {
        stats__bootstrap_median_ci(s, m, seed, &out->ci_lo, &out->ci_hi);
    }
    out->ci_rel = out->median != 0.0 ? (out->ci_hi - out->ci_lo) / 2.0 / fabs(out->median) : NAN;
    double q1 = stats_quantile_sorted(s, m, 0.25), q3 = stats_quantile_sorted(s, m, 0.75);
    double lo = q1 - 1.5 * (q3 - q1), hi = q3 + 1.5 * (q3 - q1);
    for (size_t i = 0; i < m; i++)
        out->n_outliers += (s[i] < lo || s[i] > hi);
    free(s);
    return 0;
}

/* t(0.95, df), the 95th percentile of Student's t, df = 1 .. 8. */
static const double stats__t95[] = { 6.313752, 2.919986, 2.353363, 2.131847, 2.015048,
                                     1.943180, 1.894579, 1.859548 };

double stats_bound90(const double *e, size_t n, const char **method)
{
    size_t m = 0;
    double *a = dm_xcalloc(n + 1, sizeof *a), mean = 0, ss = 0, h = NAN;
    for (size_t i = 0; i < n; i++)
        if (isfinite(e[i])) {
            a[m++] = e[i];
            mean += e[i];
        }
    const char *how = NULL;
    if (m >= STATS_BOUND90_CONFORMAL) {
        for (size_t i = 0; i < m; i++)
            a[i] = fabs(a[i]);
        qsort(a, m, sizeof *a, stats__cmp);
        h = a[(size_t)ceil((double)(m + 1) * 0.9) - 1];   /* rank <= m for m >= 9 */
        how = "conformal";
    } else if (m >= 2) {
        mean /= (double)m;
        for (size_t i = 0; i < m; i++)
            ss += (a[i] - mean) * (a[i] - mean);
        h = fabs(mean) + stats__t95[m - 2] * sqrt(ss / (double)(m - 1)) * sqrt(1 + 1 / (double)m);
        how = "normal";
    }
    free(a);
    if (method)
        *method = how;
    return h;
}
