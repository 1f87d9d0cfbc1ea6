/* protocol.h — the measuring decisions, as pure functions of the numbers
 * measured so far (docs/measurement.md, "The protocol").
 *
 * No GL, no clock, no I/O: the caller (run/measure.c) renders, reads the
 * clocks and feeds the figures in; the protocol answers how many frames to
 * time next, whether the warm-up is done, whether sampling stops and why,
 * whether the samples drift, and how long measuring a configuration would
 * take (--budget).  Modelled on Google Benchmark's
 * ShouldReportIterationResults, so unit tests drive it with made-up
 * streams (tests/test_run_protocol.c).
 *
 *   protocol_desc d;  protocol_desc_from_measure(&d, &sweep->measure, seed);
 *   protocol_warmup w;
 *   for (int f = protocol_warmup_begin(&d, &w); f > 0; )
 *       f = protocol_warmup_next(&d, &w, time_frames(f) / f);
 *   int frames = protocol_sample_frames(&d, w.settled_ns);
 *   do x[n++] = time_frames(frames) / frames;
 *   while (protocol_decide(&d, x, n, elapsed_s).stop == PROTOCOL_CONTINUE);
 */
#ifndef RUN_PROTOCOL_H
#define RUN_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "sweep/sweep.h"

/* Defaults of the protocol's own constants (zero in a desc means these). */
#define PROTOCOL_WARMUP_AGREE    0.10     /* two warm-up samples agree within 10 % */
#define PROTOCOL_WARMUP_TRIES    10       /* at most this many samples after the first agreement sample */
#define PROTOCOL_MAX_FRAMES      100000   /* frames per timing sample, at most */
#define PROTOCOL_DRIFT_LIMIT     0.05     /* trend over the samples, relative to the median */
#define PROTOCOL_DRIFT_T         3.0      /* |t| of the trend's slope that is not noise */
#define PROTOCOL_EXTRA_CLEAR     0.5      /* extra rounds: corrected CI within this share of the target */

/* The settings: the sweep's measure block plus the protocol's constants.
 * Zero means default for the constants (protocol_defaults fills them). */
typedef struct protocol_desc {
    int warmup_frames;       /* frames before the agreement samples (measure.warmup_frames) */
    int frames_per_sample;   /* K: frames per timing sample, at least */
    double min_sample_ms;    /* a timing sample lasts at least this long (0 = K exactly) */
    int samples_min, samples_max;
    double target_ci;        /* stop when the median's 95 % CI half-width / median <= this */
    double max_seconds;      /* stop (after samples_min) when sampling took longer */
    int path_frames;         /* F of a configuration on a camera path: a sample is one
                                replay of exactly F frames (run/path_timing.h); 0 = still */
    uint64_t seed;           /* of the bootstrap CI for fewer than 6 samples */
    double warmup_agree;     /* 0 = PROTOCOL_WARMUP_AGREE */
    int warmup_tries;        /* 0 = PROTOCOL_WARMUP_TRIES */
    int max_frames;          /* 0 = PROTOCOL_MAX_FRAMES */
    double drift_limit;      /* 0 = PROTOCOL_DRIFT_LIMIT */
    double drift_t;          /* 0 = PROTOCOL_DRIFT_T */
} protocol_desc;

/* Fills the zero constants of d with their defaults. */
void protocol_defaults(protocol_desc *d);
/* d from a parsed sweep's measure block (defaults filled) and the run's seed. */
void protocol_desc_from_measure(protocol_desc *d, const sweep_measure *m, uint64_t seed);

/* ---- warm-up ---------------------------------------------------------------- */

/* What the next warm-up sample is for. */
typedef enum protocol_warmup_stage {
    PROTOCOL_WARMUP_FIRST = 0,   /* the first frame alone (JIT compilation) */
    PROTOCOL_WARMUP_REST,        /* the other warmup_frames - 1 frames */
    PROTOCOL_WARMUP_AGREE_STAGE, /* samples of sample_frames until two agree */
    PROTOCOL_WARMUP_DONE
} protocol_warmup_stage;

typedef struct protocol_warmup {
    protocol_warmup_stage stage;
    double first_ns;         /* ns of the first frame */
    double rest_ns;          /* ns/frame of the rest (= first_ns when warmup_frames <= 1) */
    int sample_frames;       /* frames per agreement sample */
    int n_agree;             /* agreement samples taken */
    int agreed;              /* 1: two consecutive samples agreed; 0: tries ran out */
    double prev_ns;          /* ns/frame of the last agreement sample compared against */
    double settled_ns;       /* once done: the frame time that sizes the timing samples */
} protocol_warmup;

/* Starts a warm-up; returns the frames of the first sample (always 1). */
int protocol_warmup_begin(const protocol_desc *d, protocol_warmup *w);
/* Feeds the ns per frame of the sample just taken (of the frames the last
 * call returned); returns the frames of the next sample, or 0 when the
 * warm-up is done (then w->settled_ns is set).  The first frame is timed
 * alone, then warmup_frames - 1 frames, then samples of
 * protocol_warmup_frames() frames until two consecutive ones agree within
 * warmup_agree, at most 1 + warmup_tries of them. */
int protocol_warmup_next(const protocol_desc *d, protocol_warmup *w, double frame_ns);
/* Frames per agreement sample: K, or fewer (at least 1) when K frames of
 * frame_ns would outlast min_sample_ms; K when min_sample_ms is 0 or
 * frame_ns is not positive.  The agreement check then costs 2 frames, not
 * 2K, on configurations whose frame alone lasts min_sample_ms. */
int protocol_warmup_frames(const protocol_desc *d, double frame_ns);

/* ---- timing samples ------------------------------------------------------------ */

/* Frames per timing sample for a settled frame time: enough frames to last
 * min_sample_ms, never fewer than K, at most max_frames. */
int protocol_sample_frames(const protocol_desc *d, double frame_ns);

/* Why sampling stops (PROTOCOL_CONTINUE: it does not). */
typedef enum protocol_stop {
    PROTOCOL_CONTINUE = 0,
    PROTOCOL_CONVERGED,      /* CI within target_ci, at least samples_min samples */
    PROTOCOL_TIME_CAP,       /* sampling took longer than max_seconds, at least samples_min */
    PROTOCOL_MAX_SAMPLES,    /* samples_max samples */
    PROTOCOL_NO_STOP_COUNTER /* nothing to judge the precision by: one sample is all */
} protocol_stop;

typedef struct protocol_decision {
    protocol_stop stop;
    double ci_rel;           /* CI half-width / median of the samples so far (NaN: none) */
    int drifting;            /* the samples follow a trend (see protocol_drift) */
    double drift;            /* that trend over the samples, relative to the median */
} protocol_decision;

/* The decision after the n-th sample: x holds the per-frame values of the
 * stop counter (WallTime) so far, NULL when it is not measured; elapsed_s
 * is the configuration's own sampling time.  Stops once n >= samples_min
 * and (CI within target or elapsed_s > max_seconds), or at samples_max. */
protocol_decision protocol_decide(const protocol_desc *d, const double *x, size_t n, double elapsed_s);

/* Trend of x over its index: *drift gets the least-squares slope times
 * (n - 1) over the median (the relative change across the samples).
 * Returns 1 (drifting) when |drift| > drift_limit and the slope's
 * t-statistic exceeds drift_t, i.e. the trend is large and not noise;
 * 0 for fewer than 4 finite samples. */
int protocol_drift(const protocol_desc *d, const double *x, size_t n, double *drift);

/* Name of a stop reason for logs ("converged", "time cap", ...). */
const char *protocol_stop_name(protocol_stop s);

/* Samples a checkpoint may give back: samples_max - 1, so that a resumed
 * configuration measures at least one more. */
size_t protocol_resume_limit(const protocol_desc *d);

/* ---- extra rounds (--extra-time) ---------------------------------------------- */

/* Why the extra rounds stop, or that they go on. */
typedef enum protocol_extra_why {
    PROTOCOL_EXTRA_MORE = 0,     /* a round is planned */
    PROTOCOL_EXTRA_REACHED,      /* every configuration is within target_ci */
    PROTOCOL_EXTRA_BUDGET        /* some are short of it, but no sample fits in the budget left */
} protocol_extra_why;

/* Plans one extra round over n configurations that stopped sampling short
 * of their target: ci_rel[i] is configuration i's CI half-width / median
 * now (NaN: unknown, the noisiest of all), sample_s[i] what one more of its
 * samples takes (its mean sample so far).  The configurations with ci_rel
 * not within target_ci are taken noisiest first (largest ci_rel; equal ones
 * by index), each while the seconds taken so far plus its sample_s fit in
 * budget_s (a sample that does not fit is skipped, not waited for; a
 * sample_s that is not a finite non-negative figure never fits).  Writes
 * their indices to pick[] in that order (pick holds n) and returns how many;
 * *why says why none were taken (PROTOCOL_EXTRA_MORE when some were). */
size_t protocol_extra_round(const double *ci_rel, const double *sample_s, size_t n, double target_ci,
                            double budget_s, size_t *pick, protocol_extra_why *why);

/* The CI half-width / median each configuration of a scene would have
 * with the machine's drift removed, for deciding which configurations the
 * extra rounds sample: x[c * n_rounds + r] is configuration c's sample of
 * the stop counter in round r (NaN: none).  Where the scene's drift can be
 * removed (models/drift.h: a common mode measured, and round factors
 * spread beyond what noise gives them), ci_rel[c] is the half-width of the
 * CI of c's corrected samples (drift_desc.point_only: without the
 * bootstrap, which the figures stored at the end of the run add); else,
 * and for a configuration without samples, NaN, and the caller keeps the
 * raw CI.  Returns 1 when the drift was removed, 0 when not.  On a
 * drifting host the raw CI of a configuration stays wide however many
 * samples it gets, while its corrected CI (the one its figure is judged
 * by) may be within the target long before: deciding by the raw CI spends
 * the extra rounds where they are no longer needed (docs/measurement.md,
 * "Extra rounds"). */
int protocol_extra_corrected(const double *x, size_t n_configs, size_t n_rounds, uint64_t seed,
                             double *ci_rel);

/* 1 when a configuration waiting for extra rounds needs no more: its CI
 * with the drift removed (protocol_extra_corrected) is within
 * PROTOCOL_EXTRA_CLEAR of target_ci.  Half, not the whole target: that
 * CI leaves out the bootstrap of the correction, which the stored figure
 * adds, so a configuration stopped at the target itself would often end
 * outside it (tests/test_run_protocol.c simulates both). */
int protocol_extra_clearly_within(double corrected_ci_rel, double target_ci);

/* 1 when a timed configuration needs no extra rounds, judged by the figure
 * it will be stored with: where the scene's drift is removed (corrected
 * finite), protocol_extra_clearly_within -- whatever its raw CI, which on
 * few samples may converge while the corrected CI ends outside the target
 * -- else its raw CI within target_ci.  NaN is never within. */
int protocol_extra_done(double raw_ci_rel, double corrected_ci_rel, double target_ci);

/* Words for a stop of the extra rounds ("targets reached", "budget spent"). */
const char *protocol_extra_why_name(protocol_extra_why w);

/* ---- --budget ------------------------------------------------------------------ */

/* Seconds to measure a configuration whose frame takes frame_ns: warm-up
 * plus at most samples_max samples, each at least K frames and
 * min_sample_ms long, plus the image renders.  The sampling stops after
 * the sample that takes it past max_seconds, but not before samples_min
 * samples (protocol_decide).  On a
 * camera path (d->path_frames = F > 0) a sample is one replay of exactly F
 * frames, whatever K and min_sample_ms, and the untimed replay before the
 * first sample adds F frames. */
double protocol_predict_s(const protocol_desc *d, double frame_ns);

/* d for a configuration on a camera path of `frames` frames (F; 0 for a
 * still configuration, run/path_timing.h: path_timing_frames).  Not capped
 * at max_frames: a replay draws the whole path. */
void protocol_desc_on_path(protocol_desc *d, size_t frames);

/* ---- progress ------------------------------------------------------------------ */

/* Configurations' worth of weight the prior carries in the ETA's rate. */
#define PROTOCOL_ETA_PRIOR 2.0
/* Seconds of measuring before an ETA is printed. */
#define PROTOCOL_ETA_MIN_S 2.0

/* The seconds left that the progress line prints.  done configurations
 * took elapsed_s (from the first measuring process's start); left are
 * still to do, of total; prior_s is the plan's cost of one
 * configuration (protocol_predict_s), 0 when unknown.  The rate is
 * (elapsed_s + PROTOCOL_ETA_PRIOR × prior_s) / (done + PROTOCOL_ETA_PRIOR):
 * the measured rate, pulled toward the prior while little is done.  Returns
 * NaN, "print nothing", until it is credible: no configuration done, fewer
 * than a tenth of total done, under PROTOCOL_ETA_MIN_S measured, or nothing
 * left. */
double protocol_eta_s(double prior_s, size_t done, double elapsed_s, size_t left, size_t total);

#endif
