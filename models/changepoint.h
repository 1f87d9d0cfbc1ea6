/* changepoint.h — where a configuration's timing changed across runs, with
 * the regression gate's statistics (models/compare_stats.h).
 *
 * Between each pair of consecutive runs: a change when the two-sided
 * Mann-Whitney p-value of their samples, Benjamini-Hochberg adjusted over
 * the series, is below alpha AND the medians differ by more than threshold
 * (relative to the earlier one) — the same two conditions `dmbench compare`
 * needs to call a regression.
 */
#ifndef MODELS_CHANGEPOINT_H
#define MODELS_CHANGEPOINT_H

#include <stddef.h>

typedef struct changepoint_series {
    const double *samples;   /* one run's samples */
    size_t n;
    double median;
} changepoint_series;

/* For i in 1..n-1: change[i] = 1 when run i differs from run i-1 (change[0]
 * = 0); q[i] the adjusted p-value (NaN when a side has no samples; q may be
 * NULL).  alpha 0 -> 0.01, threshold 0 -> 0.05.  Returns the number of
 * changes. */
size_t changepoint_find(const changepoint_series *runs, size_t n, double alpha, double threshold,
                        unsigned char *change, double *q);

#endif
