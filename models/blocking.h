/* blocking.h — blocking by round: removing a shared machine's common speed
 * changes from the samples of the configurations of one scene.
 *
 * The runner samples the configurations of a scene in rounds, each round
 * visiting every configuration still sampling once, in a shuffled order
 * (run/measure.c), so sample r of every configuration was taken in round r,
 * seconds apart from the others.  A machine that slows down for a while
 * (another job, a host that takes the CPU away) slows every configuration
 * of that round alike.  Blocking estimates that round's common speed factor
 * and divides it out:
 *
 *   f(c, r) = median over the OTHER configurations k with a sample in
 *             round r of x_k[r] / median(x_k)
 *   corrected x_c[r] = x_c[r] / f(c, r)
 *
 * Leave-one-out (f of c never uses c's own sample) keeps a configuration's
 * own noise out of its correction, so its corrected CI is not made narrow
 * by construction.  A round with fewer than BLOCKING_MIN_OTHERS other
 * configurations is not corrected (f = 1).  The correction is relative to
 * each configuration's own median, so it leaves medians where they were
 * and cannot hide a change between two runs: it only removes what moved
 * all configurations together within one run.
 *
 * Non-finite samples are left as they are and never enter a factor.
 */
#ifndef MODELS_BLOCKING_H
#define MODELS_BLOCKING_H

#include <stddef.h>

#define BLOCKING_MIN_OTHERS 2

/* The samples of one configuration: x[r] was taken in round r. */
typedef struct blocking_series {
    const double *x;
    size_t n;
} blocking_series;

/* Writes the corrected samples of each series into out[i] (n_series
 * arrays of series[i].n values each, owned by the caller).  Returns the
 * number of series that had at least one round corrected. */
size_t blocking_correct(const blocking_series *series, size_t n_series, double *const *out);

/* The common speed factor of each round over all series (the median of
 * x_k[r] / median(x_k), NaN for a round with fewer than
 * BLOCKING_MIN_OTHERS + 1 series) into factors[0..n_rounds); returns the
 * number of rounds with a factor. */
size_t blocking_round_factors(const blocking_series *series, size_t n_series, double *factors,
                              size_t n_rounds);

/* How far the machine's speed moved within a run: exp(half the range of
 * the log factors) - 1 over the finite factors (0 when fewer than 2). */
double blocking_spread(const double *factors, size_t n);

#endif
