/* predict.h — what a configuration never measured will cost: its
 * Instructions, stage shares and WallTime from per-variant costs fitted to
 * measured runs and its own invocation counts (docs/models.md,
 * "Prediction").  Used by `dmbench predict` and by `run --budget`.
 *
 * The costs per invocation come from fits per shader variant: one per
 * stage counter with that stage's own model (geometry-, raster- and
 * fragment-instructions) when the runs have the stage counters, else the
 * whole-frame stage-instructions.  Frame time: of the ways the runs allow
 * (the stage times summed with one shared fixed cost, time-from-stages,
 * time-from-instructions; every time fit of relative error), the one with
 * the lowest held-out error on the runs' own configurations, never one
 * above PREDICT_MAX_HELDOUT; its interval from those held-out errors.  A
 * configuration of a variant the runs never measured is not predicted,
 * never guessed.
 */
#ifndef RUN_PREDICT_H
#define RUN_PREDICT_H

#include <stddef.h>
#include "core/dm_results.h"
#include "models/stats.h"
#include "core/dm_util.h"
#include "sweep/plan.h"

/* The invocation counts a prediction reads, in this order (inproc_counts
 * or the pilot frame measure them for the configurations to predict). */
#define PREDICT_N_COUNTS 10
extern const char *const predict_counts[PREDICT_N_COUNTS];

/* How far the machine's own speed may move a frame time between two runs
 * (the fitted runs and the one predicted): compare's --run-spread default
 * (docs/ci-gating.md, "The machine interval").  Part of every predicted
 * WallTime's interval; it is a time of another run being predicted. */
#define PREDICT_RUN_SPREAD 0.10

/* A way of predicting WallTime whose held-out error on the runs is above
 * this (percent) is never used for a value. */
#define PREDICT_MAX_HELDOUT 50.0
/* The coverage an interval aims at, and the configurations held out it
 * needs (models/stats.h stats_bound90): with at least
 * PREDICT_CONFORMAL_HELDOUT (9) the ceil((n + 1) * 0.9)-th smallest of n
 * held-out errors bounds a new one with probability >= 0.9 (split
 * conformal); with PREDICT_MIN_HELDOUT (2) to 8 the normal-theory
 * prediction bound of their log errors does (exactly, for normal errors);
 * with fewer, no interval. */
#define PREDICT_COVERAGE 0.9
#define PREDICT_MIN_HELDOUT 2
#define PREDICT_CONFORMAL_HELDOUT STATS_BOUND90_CONFORMAL

/* The ways of predicting WallTime, in the order printed. */
typedef enum predict_way {
    PREDICT_WAY_STAGE_TIMES,         /* geometry-, raster-, fragment-time, one shared fixed cost */
    PREDICT_WAY_TIME_FROM_STAGES,
    PREDICT_WAY_TIME_FROM_INSTRUCTIONS,
    PREDICT_N_WAYS
} predict_way;
extern const char *const predict_way_names[PREDICT_N_WAYS];

/* How well a way predicted the runs' own frames held out of its fits. */
typedef struct predict_way_score {
    double cv_mape;   /* percent; NaN: none held out */
    int n;            /* configurations held out */
    double q;         /* the PREDICT_COVERAGE bound of |ln(predicted / measured)| (stats_bound90); NaN
                       * when n < PREDICT_MIN_HELDOUT */
    const char *q_how;   /* "conformal" (n >= 9), "normal" (2-8), NULL */
    char *why;        /* NULL: available; else why the runs do not allow it */
} predict_way_score;

/* The counters the runs must have for any prediction (the stage counters,
 * with SamplesPassed, are used when present). */
#define PREDICT_N_NEEDED 5
extern const char *const predict_needed[PREDICT_N_NEEDED];

/* How well the runs' own Instructions are predicted when held out: per
 * variant, the k-fold held-out predictions of the three stage models
 * (each config predicted by fits that never saw it), summed. */
typedef struct predict_heldout {
    char *variant;
    double cv_mape;   /* percent; NaN when no configuration was predicted by all three */
    int n;            /* configurations it covers */
} predict_heldout;

/* The interval's calibration for configurations at an axis value the runs
 * never measured (docs/models.md, "Intervals"): held-out groups.  A group
 * is the configurations that share one value of a numeric axis (the
 * resolution's pixel count, steps, tess_level, mesh_density ...); the
 * models are fitted again without it and predict it, as they predict a
 * target at a new value.  Only an axis the runs measured at
 * PREDICT_GROUP_VALUES values or more is held out: with two, the rest has
 * one, and a model loses every term in it (a constant column) -- on the
 * 14:30 bench runs that gave errors up to +96 %, not what a target that
 * the fit saw at two values meets.  The PREDICT_COVERAGE bound
 * (stats_bound90) of the held-out log errors, per response, pooled over
 * the axes held out. */
#define PREDICT_GROUP_VALUES 3
typedef struct predict_axis_count {
    char *key;
    int n_values;        /* distinct values the runs' ok configurations have */
} predict_axis_count;
typedef struct predict_groups {
    predict_axis_count *axes;   /* every numeric axis of the runs */
    size_t n_axes;
    int n_groups;        /* groups held out that gave a held-out prediction */
    double instr_q;      /* bound of |ln(predicted / measured)| Instructions; NaN: unavailable */
    int instr_n;
    double wall_q;       /* the same of WallTime (the way each refit chose) */
    int wall_n;
} predict_groups;

/* A frame time predicted from runs is a time of another run: the
 * machine's speed between runs, measured where the runs share a
 * configuration (the PREDICT_COVERAGE bound of |ln(W_a / W_b)| of a
 * configuration measured in two runs, scaled by sqrt((1 + 1/R) / 2) for a
 * new run against the mean of R), else PREDICT_RUN_SPREAD. */
typedef struct predict_between {
    double q;        /* log bound used in every WallTime interval */
    int n;           /* configurations measured in two runs or more; 0: PREDICT_RUN_SPREAD */
} predict_between;

typedef struct predict_model {
    dm_run_result train;   /* the pooled runs (shallow: the caller's runs own the configurations) */
    dm_fit_result *instr, *stage[3], *time, *time_st;   /* time_st: time-from-stages */
    size_t n_instr, n_stage[3], n_time, n_time_st;
    double stage_max[3];   /* the largest value of each stage counter the runs measured */
    double instr_max;      /* and of Instructions */
    predict_heldout *heldout;   /* per variant, when the runs have the stage counters */
    size_t n_heldout;
    double instr_q;   /* their PREDICT_COVERAGE bound of |ln(sum / Instructions)|, pooled (stats_bound90);
                         NaN: fewer than 2 */
    /* geometry-, raster- and fragment-time: each stage's time from its
     * instructions, when the runs have the timed passes (GeometryTime,
     * MinimalShadingTime) and the stage counters; summed, their constants
     * give way to shared_a, the one fixed cost of a frame (each pass's
     * sample ends in one glFinish, which the passes' differences cancel
     * only as far as the fits' constants happen to) */
    dm_fit_result *time_stage[3];
    size_t n_time_stage[3];
    double shared_a;
    predict_way_score way[PREDICT_N_WAYS];
    int way_used;      /* the way of the lowest held-out error at most PREDICT_MAX_HELDOUT, -1: none */
    int calibrated;    /* groups and between are computed (predict_fit; not its refits) */
    predict_groups groups;
    predict_between between;
} predict_model;

typedef struct predict_result {
    char *variant;           /* "pom steps=auto ..." (fitting_variant) */
    double instr, instr_lo, instr_hi;   /* frame Instructions, ×/÷ (1 + 2 CV-MAPE), at least the pooled bound */
    double part[3];          /* geometry, raster, fragment; NaN without the stage counters */
    double wall_ns, wall_lo, wall_hi;   /* NaN without a WallTime fit */
    const char *wall_by;     /* the way it was predicted: "stage times", "time-from-stages", ... */
    const char *wall_override;   /* why wall_by is not the way of the lowest held-out error (NULL: it is) */
    int beyond_stage;        /* the stage whose part is the most beyond the runs' largest, -1 = none is */
    double beyond;           /* that part over the largest the runs measured (> 1) */
    /* For the writers: where the Instructions come from ("stage models
     * summed" or "stage-instructions"), and in words why a value or an
     * interval is missing (NULL: it is there; owned, predict_result_free). */
    const char *instr_by;
    const char *instr_pooled;   /* the interval is the other variants' pooled bound, and why (static
                                   text); NULL: the variant's own */
    char *instr_why;         /* no Instructions interval */
    char *part_why;          /* no stage shares */
    char *wall_why;          /* no WallTime (wall_by NULL), or no interval around it */
    /* Which calibration the intervals are: "leave-one-out" (every numeric
     * axis value of the configuration was measured by the runs),
     * "held-out groups" (one was not: the wider of the two bounds), or
     * "leave-one-out, groups unavailable" (one was not, along an axis the
     * runs measured at fewer than PREDICT_GROUP_VALUES values: no
     * Instructions interval, the WallTime's from leave-one-out and the
     * machine between runs). */
    const char *calibration;
    char *calibration_why;   /* "resolution=288x192 never measured by the runs" (owned); NULL: leave-one-out */
    char *instr_blocked;     /* why held-out groups cannot calibrate it, the second half of
                                instr_why when that is the reason (owned); NULL otherwise */
} predict_result;

/* Appends to out one line ("  KEY  SCENE: COUNTER unavailable (reason)")
 * for each ok configuration of runs[0..n) the fits leave out because a
 * counter they need (predict_needed, the stage counters) is unavailable
 * there, such as a value read back missing or not finite; returns how many. */
size_t predict_left_out(const dm_run_result *runs, size_t n, dm_str *out);

/* The first of predict_needed that run lacks, or NULL when it has them all. */
const char *predict_run_missing(const dm_run_result *run);

/* Fits the models to runs[0..n) (kept by the caller until predict_free),
 * and calibrates the intervals: held-out groups (predict_groups) and the
 * machine between runs (predict_between). */
void predict_fit(const dm_run_result *runs, size_t n, predict_model *m);

/* The fit of `variant` (a one-group fit per variant) among fits, or NULL. */
const dm_fit_result *predict_fit_of(const dm_fit_result *fits, size_t n, const char *variant);

/* The held-out error of variant's Instructions (predict_heldout), or NULL. */
const predict_heldout *predict_heldout_of(const predict_model *m, const char *variant);

/* 1 when the variant's one-formula fit `one` (stage-instructions)
 * predicted the runs' held-out Instructions better than the stage models'
 * sum: predict_config then gives its value (the stage shares stay the
 * stage models'). */
int predict_heldout_prefers_one(const predict_model *m, const dm_fit_result *one);

/* 1 when way is usable for a value: the runs allow it and its held-out
 * error is known and at most PREDICT_MAX_HELDOUT. */
int predict_way_usable(const predict_model *m, predict_way way);

/* How many ok configurations of the runs are of variant (fitting_variant). */
size_t predict_variant_count(const predict_model *m, const char *variant);

/* Predicts configuration pc, whose invocation counts are counts[0..
 * PREDICT_N_COUNTS) (NaN: not measured).  0 with *out filled, or
 * DM_ERR_UNKNOWN with why (the variant was never measured, or a value it
 * needs was never varied) and out->variant still set.  A bound that cannot
 * be computed is NaN, with the reason in out->instr_why / wall_why. */
int predict_config(const predict_model *m, const plan_config *pc, const double *counts, predict_result *out,
                   dm_str *why);

void predict_result_free(predict_result *r);
void predict_free(predict_model *m);

#endif
