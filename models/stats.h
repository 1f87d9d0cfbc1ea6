/* stats.h — descriptive statistics for timing samples.
 *
 * All functions take plain arrays, ignore non-finite values (and count
 * them), and never modify their input.  Bootstrap resampling is seeded so
 * results are reproducible.
 *
 * Definitions used (documented because reports quote them):
 *   stddev  sample standard deviation (divisor n - 1); NaN when n < 2.
 *   mad     RAW median absolute deviation, median(|x - median|), NOT scaled
 *           by 1.4826; multiply by 1.4826 for a normal-consistent sigma.
 *   cv      stddev / mean; NaN when mean == 0 or n < 2.
 *   ci      95% CI of the median.  n >= 6: distribution-free order-statistic
 *           interval [x(k), x(n-k+1)] (1-based order statistics) with k the
 *           LARGEST integer such that 1 - 2*P(B <= k-1) >= 0.95 for
 *           B ~ Binomial(n, 1/2); e.g. n = 6 -> [x(1), x(6)] (96.9%),
 *           n = 10 -> [x(2), x(9)] (97.9%).  n < 6 (no such k exists):
 *           percentile interval (2.5%, 97.5%, type 7) of STATS_BOOTSTRAP_B
 *           seeded bootstrap medians; n = 1 gives [x, x].
 *   ci_rel  (ci_hi - ci_lo) / 2 / |median|; NaN when median == 0.
 *   n_outliers  values strictly outside [Q1 - 1.5 IQR, Q3 + 1.5 IQR]
 *           (Q1, Q3 type 7).
 */
#ifndef MODELS_STATS_H
#define MODELS_STATS_H

#include <stddef.h>
#include <stdint.h>

#define STATS_BOOTSTRAP_B 2000

typedef struct stats_summary {
    size_t n;                /* finite values used */
    size_t n_nonfinite;      /* NaN/Inf values excluded */
    double median, mean, min, max, stddev, mad, cv;
    double ci_lo, ci_hi;     /* 95% CI of the median */
    double ci_rel;           /* half-width of the CI relative to the median */
    int n_outliers;          /* outside Tukey fences (1.5 IQR) */
} stats_summary;

/* Quantile with linear interpolation (type 7, as R's default) of the finite
 * values; NaN if none or q outside [0, 1]. */
double stats_quantile(const double *x, size_t n, double q);
double stats_median(const double *x, size_t n);
/* Fills out; returns 0 or DM_ERR_ARG when no finite value exists (out is
 * then zeroed except n_nonfinite). The CI of the median is the
 * distribution-free order-statistic interval when n >= 6, else a seeded
 * bootstrap percentile interval. */
int stats_summarize(const double *x, size_t n, uint64_t seed, stats_summary *out);

/* Index k (1-based) of the lower order statistic of the distribution-free
 * CI of the median at confidence `level` for n values, or 0 when no
 * interval reaches the level (n too small).  *coverage (optional) gets the
 * exact coverage 1 - 2*P(B <= k-1). */
size_t stats_median_ci_rank(size_t n, double level, double *coverage);

/* A bound of prediction errors at 90 % coverage (docs/models.md,
 * "Intervals"): given the signed errors e[0..n) of held-out predictions
 * (non-finite skipped; m of them finite), an h such that a new error
 * drawn like them has |e| <= h with probability >= 0.9.
 *   m >= STATS_BOUND90_CONFORMAL (9): split conformal, distribution-free:
 *     the ceil((m + 1) 0.9)-th smallest |e|;
 *   2 <= m < 9: no order statistic reaches 0.9 (the largest of m bounds
 *     a new one with probability m / (m + 1) only), so the normal-theory
 *     prediction interval: h = |mean| + t(0.95, m - 1) s sqrt(1 + 1/m), s
 *     the sample SD — exactly 0.9 for normal errors, and the symmetric
 *     bound holds the interval mean ± t s sqrt(1 + 1/m);
 *   m < 2: NaN (no spread to measure).
 * *method (optional) gets "conformal", "normal" or NULL accordingly. */
#define STATS_BOUND90_CONFORMAL 9
double stats_bound90(const double *e, size_t n, const char **method);

/* Copies the finite values of x into a new malloc'd array sorted ascending;
 * *m gets their count (the array may be NULL when m == 0).  Used by the
 * other statistics modules. */
double *stats_sorted_finite(const double *x, size_t n, size_t *m);
/* Median of v[0..m) in place (v is reordered), m > 0 finite values; NaN
 * when m is 0.  Equal to stats_median of the same values (the middle
 * value, or the mean of the two middle ones), found by selection in O(m)
 * rather than by sorting: the drift model takes millions of medians of a
 * few dozen values (models/drift.c). */
double stats_median_inplace(double *v, size_t m);
/* Type-7 quantile of an already sorted array of m > 0 finite values. */
double stats_quantile_sorted(const double *s, size_t m, double q);

#endif
