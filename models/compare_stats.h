/* compare_stats.h — statistics for the regression gate (docs/ci-gating.md): ratio of
 * medians with a bootstrap CI, Mann-Whitney U test, Benjamini-Hochberg.
 *
 * Non-finite values are ignored.  Resampling is seeded (reproducible).
 */
#ifndef MODELS_COMPARE_STATS_H
#define MODELS_COMPARE_STATS_H

#include <stddef.h>
#include <stdint.h>

/* Largest group size for which the exact U distribution is used. */
#define COMPARE_STATS_EXACT_MAX 20

typedef struct compare_ratio {
    double ratio;            /* median(new) / median(base) */
    double lo, hi;           /* percentile bootstrap CI at the requested level */
} compare_ratio;

/* Bootstrap CI of median(new)/median(base): STATS_BOOTSTRAP_B resamples,
 * base and new resampled independently, percentile interval (type 7) at
 * `level` (e.g. 0.95).  When both samples hold the same values (a run
 * against itself) the ratio and both bounds are exactly 1.  Returns 0, or DM_ERR_ARG when a sample has no
 * finite value, the base median is 0 or level is not in (0, 1). */
int compare_stats_ratio_ci(const double *base, size_t n_base, const double *new_, size_t n_new,
                           double level, uint64_t seed, compare_ratio *out);

/* Two-sided Mann-Whitney U test of a against b.  *u (optional) gets U of
 * sample a: the number of pairs (a_i, b_j) with a_i > b_j, ties counting
 * 1/2 (midranks).  Exact distribution when both finite sizes are
 * <= COMPARE_STATS_EXACT_MAX and there are no ties: p = min(1, 2 min(P(U <=
 * u), P(U >= u))).  Otherwise the normal approximation with tie-corrected
 * variance and continuity correction 0.5.  Returns NaN when a sample is
 * empty; 1 when all values are tied. */
double compare_stats_mann_whitney(const double *a, size_t na, const double *b, size_t nb,
                                  double *u);

/* Benjamini-Hochberg adjusted p-values (step-up, monotone, capped at 1):
 * q_(i) = min_{j >= i} p_(j) n / j over the ascending order. q may alias p. */
void compare_stats_bh(const double *p, size_t n, double *q);

#endif
