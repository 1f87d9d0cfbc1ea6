/* drift.h — removing the machine's drift from the timing samples of one
 * scene, with the uncertainty of the removal in the corrected CI
 * (docs/measurement.md, "Drift removed").
 *
 * The runner samples a scene's configurations in rounds, each in a fresh
 * shuffled order (run/measure.c), so x[c][r], the sample of configuration c
 * in round r, was taken within the same second or so as every other
 * sample of round r.  On a host whose speed drifts (a vCPU slowed by its
 * neighbours, a clock that changes) a whole round moves together.  The
 * model, on log times:
 *
 *   log x[c][r] = a[c] + b[r] + e[c][r]
 *
 * a[c] the configuration's level at the run's median machine speed, b[r]
 * the round's common mode (the machine's speed in that round, median 0
 * over rounds), e the configuration's own noise.  a and b are fitted by
 * median polish (robust, and it copes with configurations that stopped
 * sampling early).  The correction of configuration c divides each of its
 * samples by exp(b'[c][r]), where b'[c][r] is the round's common mode
 * measured WITHOUT c (the median over the other configurations k of the
 * round of log x[k][r] - a[k]): a configuration's own noise never enters
 * its correction, so the corrected samples keep it whole and gain the
 * noise of the estimate of b — the CI cannot be narrowed by construction.
 * A round with fewer than DRIFT_MIN_OTHERS other configurations is not
 * corrected for c.
 *
 * Corrected CI: the hull of (a) the 95 % CI of the median of the corrected
 * samples (models/stats.h) and (b) a percentile interval of B bootstrap
 * replicates of the WHOLE procedure (polish, leave-one-out common mode,
 * median), each on n_rounds rounds drawn with replacement in blocks of
 * drift_block_rounds(n_rounds) consecutive rounds (a moving-block
 * bootstrap, circular: the host's speed in one round depends on the last
 * round's, so independent draws understate how far its median moves) — the round is
 * the unit, so the uncertainty of a[k] and b[r] is in (b).  The corrected
 * figure is the time at the run's median machine speed; each replicate is
 * shifted by the median change of all the scene's configurations, so the
 * CI is conditional on that reference (its uncertainty moves every
 * configuration alike and cancels in comparisons within the run).  That
 * within-run CI is for ties and picks inside the run.
 *
 * Between two runs the reference itself moves: each run's median machine
 * speed is an estimate from its own rounds, and two runs' corrected
 * medians differ by that common factor (on the stored default runs it was
 * most of their disagreement: docs/measurement.md, "Between runs").  The
 * between-run CI is the hull of the within-run CI and the percentile
 * interval of the same replicates NOT shifted, so the uncertainty of the
 * run's median speed is in it; reference_spread is that uncertainty alone
 * (the robust SD of the replicates' shifts).  It assumes the rounds of a
 * run are draws from the same machine states another run would draw
 * from; a machine that changes between runs beyond what its rounds showed
 * (another load, another host) is not covered, which is compare's machine
 * check.
 *
 * The calibration workload timed in every round (optional) is compared as
 * a predictor of the drift: the noise left after dividing by the
 * leave-one-out common mode, by the calibration ratio, and by nothing are
 * all reported (robust SDs of log residuals), so a run says which predicts
 * its host's drift better.  Pure functions, no I/O; seeded.
 */
#ifndef MODELS_DRIFT_H
#define MODELS_DRIFT_H

#include <stddef.h>
#include <stdint.h>

#define DRIFT_MIN_CONFIGS  3      /* configurations with samples, for a common mode */
#define DRIFT_MIN_OTHERS   2      /* other configurations in a round, to correct one */
#define DRIFT_MIN_ROUNDS   3      /* rounds with a common mode */
#define DRIFT_BOOTSTRAP_B  400    /* replicates of the whole procedure */
#define DRIFT_POLISH_ITERS 20
#define DRIFT_HELPS        2.0    /* a drift: the round factors spread over twice what noise alone gives */

/* One scene's samples: x[c * n_rounds + r] (NaN: c had no sample in r). */
typedef struct drift_desc {
    size_t n_configs, n_rounds;
    const double *x;
    const double *calib;     /* n_rounds calibration times (ns), NULL = none; NaN allowed */
    uint64_t seed;           /* of the bootstrap */
    int bootstrap;           /* replicates; 0 = DRIFT_BOOTSTRAP_B */
    size_t block;            /* rounds per block of the bootstrap; 0 = drift_block_rounds(n_rounds) */
    int point_only;          /* 1: no bootstrap: lo/hi are the CI of the corrected samples alone
                                (part (a) of the corrected CI), between_lo/hi and reference_spread
                                NaN.  A preview for deciding where extra rounds go (run/protocol.h),
                                never a figure to report: it leaves out the uncertainty of the
                                correction's own estimate. */
} drift_desc;

typedef struct drift_config {
    size_t n;                         /* finite samples */
    double raw_median, raw_lo, raw_hi;  /* models/stats.h CI of the raw samples */
    double median, lo, hi;            /* corrected, CI within the run (conditional on its median
                                         speed); NaN when not corrected */
    double between_lo, between_hi;    /* corrected, CI for comparing with another run (the run's
                                         median speed's own uncertainty in it); NaN when not */
    size_t n_corrected;               /* samples whose round had a common mode without c */
} drift_config;

typedef struct drift_result {
    int corrected;           /* 1: the corrected figures are computed */
    const char *why;         /* when not: why (static text) */
    int helps;               /* 1: there is a drift to remove: the round factors spread more than
                                DRIFT_HELPS x factor_noise */
    double *round_factor;    /* n_rounds: exp(b[r]); NaN for a round without a common mode */
    drift_config *configs;   /* n_configs */
    size_t n_rounds_used;    /* rounds with a common mode */
    /* Spreads of log figures, relative (0.01 = 1 %); robust SDs (1.4826 MAD)
     * except machine_spread: */
    double machine_spread;   /* root mean square of b[r] (not robust: a slow spell in a few
                                rounds is the drift): how far the machine's speed moved */
    double raw_noise;        /* of log x - a: the samples around their level, uncorrected */
    double loo_noise;        /* after the leave-one-out common mode */
    double calib_noise;      /* after the calibration ratio; NaN without calibration */
    double calib_spread;     /* of the log calibration ratio; NaN without */
    double reference_spread; /* the uncertainty of the run's median machine speed (robust SD of
                                the bootstrap replicates' common shift); NaN when not corrected */
    double half_shift;       /* drift_half_shift of round_factor: how far the machine's speed
                                moved between the first and second half of the scene's rounds
                                (log ratio); NaN when not corrected or too few rounds */
    double factor_noise;     /* the spread round factors would have from the configurations'
                                own noise alone: sqrt(pi/2) loo_noise / sqrt(configurations
                                per round, median) */
} drift_result;

/* Fits, corrects and bootstraps one scene.  Always fills out (caller frees
 * with drift_result_free): raw figures for every configuration; corrected
 * figures when corrected == 1, else why says what was missing (fewer than
 * DRIFT_MIN_CONFIGS configurations with samples, fewer than
 * DRIFT_MIN_ROUNDS rounds with a common mode).  Returns 0, or DM_ERR_ARG
 * for a desc without samples (n_configs or n_rounds 0, x NULL). */
int drift_correct(const drift_desc *d, drift_result *out);
void drift_result_free(drift_result *r);
/* Rounds per block of the bootstrap over rounds: n^(1/3), rounded, at
 * least 1 (the textbook order for estimating a variance). */
size_t drift_block_rounds(size_t n_rounds);
/* The log ratio of the median of the later half of the finite round
 * factors to the median of the earlier half (a round count that is odd
 * leaves the middle one out): 0.05 when the machine ran 5 % slower in the
 * later half of the scene.  How far the host's speed moves on the time
 * scale of a whole scene, which is what differs between two runs and what
 * the bootstrap over blocks of a few rounds does not see
 * (run/precision.h: the run's slow drift).  NaN with fewer than
 * 2 x DRIFT_MIN_ROUNDS finite factors. */
double drift_half_shift(const double *round_factor, size_t n_rounds);

/* Robust SD of the finite values: 1.4826 × median |v - median|; NaN when
 * fewer than 2. */
double drift_robust_sd(const double *v, size_t n);

#endif
