/* predict.h — what a configuration never measured will cost: its
 * Instructions, stage shares and WallTime from per-variant costs fitted to
 * measured runs and its own invocation counts (docs/models.md,
 * "Prediction").  Used by `dmbench predict` and by `run --budget`.
 *
 * The costs per invocation come from fits per shader variant: one per
 * stage counter with that stage's own model (geometry-, raster- and
 * fragment-instructions) when the runs have the stage counters, else the
 * whole-frame stage-instructions.  Frame time: the sum of each stage's
 * time (geometry-, raster- and fragment-time) when the runs have the timed
 * stage passes; else time-from-stages or time-from-instructions, whichever
 * has the lower CV-MAPE on the runs.  A
 * configuration of a variant the runs never measured is not predicted,
 * never guessed.
 */
#ifndef RUN_PREDICT_H
#define RUN_PREDICT_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "sweep/plan.h"

/* The invocation counts a prediction reads, in this order (inproc_counts
 * or the pilot frame measure them for the configurations to predict). */
#define PREDICT_N_COUNTS 7
extern const char *const predict_counts[PREDICT_N_COUNTS];

/* How far the machine's own speed may move a frame time between two runs
 * (the fitted runs and the one predicted): compare's --run-spread default
 * (docs/ci-gating.md, "The machine interval").  Part of every predicted
 * WallTime's interval; it is a time of another run being predicted. */
#define PREDICT_RUN_SPREAD 0.10

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

typedef struct predict_model {
    dm_run_result train;   /* the pooled runs (shallow: the caller's runs own the configurations) */
    dm_fit_result *instr, *stage[3], *time, *time_st;   /* time_st: time-from-stages */
    size_t n_instr, n_stage[3], n_time, n_time_st;
    double stage_max[3];   /* the largest value of each stage counter the runs measured */
    predict_heldout *heldout;   /* per variant, when the runs have the stage counters */
    size_t n_heldout;
    /* geometry-, raster- and fragment-time: each stage's time from its
     * instructions, when the runs have the timed passes (GeometryTime,
     * MinimalShadingTime) and the stage counters; their held-out
     * predictions summed against WallTime (CV-MAPE, %; NaN: none) */
    dm_fit_result *time_stage[3];
    size_t n_time_stage[3];
    predict_heldout time_heldout;
} predict_model;

typedef struct predict_result {
    char *variant;           /* "pom steps=auto ..." (fitting_variant) */
    double instr, instr_lo, instr_hi;   /* frame Instructions, ±2 CV-MAPE */
    double part[3];          /* geometry, raster, fragment; NaN without the stage counters */
    double wall_ns, wall_lo, wall_hi;   /* NaN without a WallTime fit */
    const char *wall_by;     /* the way it was predicted: "stage times", "time-from-stages", ... */
    int beyond_stage;        /* the stage whose part is the most beyond the runs' largest, -1 = none is */
    double beyond;           /* that part over the largest the runs measured (> 1) */
    /* For the writers: where the Instructions come from ("stage models
     * summed" or "stage-instructions"), and in words why a value or an
     * interval is missing (NULL: it is there; owned, predict_result_free). */
    const char *instr_by;
    char *instr_why;         /* no Instructions interval */
    char *part_why;          /* no stage shares */
    char *wall_why;          /* no WallTime (wall_by NULL), or no interval around it */
} predict_result;

/* Appends to out one line ("  KEY  SCENE: COUNTER unavailable (reason)")
 * for each ok configuration of runs[0..n) the fits leave out because a
 * counter they need (predict_needed, the stage counters) is unavailable
 * there, such as a value read back missing or not finite; returns how many. */
size_t predict_left_out(const dm_run_result *runs, size_t n, dm_str *out);

/* The first of predict_needed that run lacks, or NULL when it has them all. */
const char *predict_run_missing(const dm_run_result *run);

/* Fits the models to runs[0..n) (kept by the caller until predict_free). */
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

/* How predict_config prices a frame whose stage parts are predicted: by
 * the stage times when the runs have them (1), else by time-from-stages
 * when that fit's CV-MAPE is not above time-from-instructions' (1), else
 * by the latter. */
int predict_has_stage_times(const predict_model *m);
int predict_prefers_time_from_stages(const predict_model *m);

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
