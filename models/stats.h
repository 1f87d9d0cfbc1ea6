/* stats.h — descriptive statistics for timing samples.
 *
 * All functions take plain arrays, ignore non-finite values (and count
 * them), and never modify their input.  Bootstrap resampling is seeded so
 * results are reproducible.
 */
#ifndef MODELS_STATS_H
#define MODELS_STATS_H

#include <stddef.h>
#include <stdint.h>

typedef struct stats_summary {
    size_t n;                /* finite values used */
    size_t n_nonfinite;      /* NaN/Inf values excluded */
    double median, mean, min, max, stddev, mad, cv;
    double ci_lo, ci_hi;     /* 95% CI of the median */
    double ci_rel;           /* half-width of the CI relative to the median */
    int n_outliers;          /* outside Tukey fences (1.5 IQR) */
} stats_summary;

/* Quantile with linear interpolation (type 7, as R's default); NaN if empty. */
double stats_quantile(const double *x, size_t n, double q);
double stats_median(const double *x, size_t n);
/* Fills out; returns 0 or DM_ERR_ARG when no finite value exists. The CI of
 * the median is the distribution-free order-statistic interval when n >= 6,
 * else a seeded bootstrap percentile interval. */
int stats_summarize(const double *x, size_t n, uint64_t seed, stats_summary *out);

#endif
