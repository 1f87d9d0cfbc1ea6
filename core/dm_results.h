/* dm_results.h — the in-memory model of one run's results.
 *
 * store/ fills it (store_run_load: the SQLite store is the single source of truth);
 * models/ adds fits; reports/ renders it to HTML/JSON/CSV/Markdown.  It is
 * plain data: every string and array is owned by the structure and released
 * by dm_run_free().  Field names follow the results.json contract (docs/exports.md).
 */
#ifndef CORE_DM_RESULTS_H
#define CORE_DM_RESULTS_H

#include <stddef.h>

typedef struct dm_kv {
    char *key;
    char *value;
} dm_kv;

/* One counter of one configuration.  Timing counters carry samples and
 * summary statistics (per frame, nanoseconds); deterministic counters carry
 * a single value.  available == 0 means the driver cannot provide it: the
 * reason is set and no value is meaningful (never read it as 0). */
typedef struct dm_counter_result {
    char *name;
    char *unit;              /* "ns", "items", "bytes", "ratio", "percent" */
    int available;
    char *unavailable_reason;
    int deterministic;
    int partial;             /* GPUTime on a driver whose timer covers a fraction */
    double value;            /* deterministic counters; median for timed ones */
    int has_samples;
    double *samples;         /* raw per-frame values, ns */
    size_t n_samples;
    double median, mean, min, max, stddev, mad, cv;
    double ci_lo, ci_hi;     /* 95% CI of the median */
    int n_outliers;          /* Tukey fences */
    int n_nonfinite;         /* non-finite samples excluded from statistics */
    int unreadable;          /* read back missing or not finite (dm_counter_read_check): the
                                record is damaged, so no verdict may pass over it */
    /* With the machine's drift removed (models/drift.h; docs/measurement.md,
     * "Drift removed"): corrected 1 when the figures below are set, 0 when
     * only the raw figures above exist (the scene's dm_scene_precision
     * says why).  The raw median and CI above are never replaced.
     * corr_ci_* is the CI within the run (conditional on the run's median
     * machine speed: for ties and picks inside the run); corr_between_* the
     * CI for comparing with another run (that speed's own uncertainty in
     * it), set when corr_between is 1 — at the end of a run or a merge,
     * not kept in the store. */
    int corrected;
    double corr_median, corr_ci_lo, corr_ci_hi;
    int corr_between;
    double corr_between_lo, corr_between_hi;
} dm_counter_result;

typedef struct dm_quality {
    int present;
    double rmse, psnr, ssim, max_error, pct_over_threshold;
    double silhouette_error, depth_rmse;
    long crack_pixels, nonfinite_pixels;
    /* LDR-FLIP (imaging/flip.h): mean, error-weighted quartiles, maximum,
     * and the pixels per degree it was computed for; NaN when not computed
     * (results from before FLIP). */
    double flip, flip_q1, flip_median, flip_q3, flip_max, flip_ppd;
    char *reference;         /* description of what the reference was */
} dm_quality;

/* The frame times of a configuration on a camera path (docs/motion.md):
 * its path replayed `replays` times, each of its `frames` frames timed on
 * its own; frame_ns[s * frames + f] is frame f of replay s, ns (NaN: not
 * measured).  frames 0: a still configuration, nothing else is set.  The
 * summary is models/frame_series' over frame_ns, made when measured and
 * kept beside the series (as a counter's statistics beside its samples);
 * NaN where no frame time was finite. */
typedef struct dm_path_series {
    size_t frames, replays;
    double *frame_ns;
    double p50, p95, p99;         /* ns, type-7 quantiles of the per-frame medians */
    double low1_ns, low1_fps;     /* the 1 % low, as a time and as a frame rate */
    size_t n_stutters;
    long *stutter_at;             /* the stutters' frame indices, in path order */
    double replay_spread;         /* NaN with one replay */
    int noisy;                    /* 1 noisy, 0 not, -1 unknown (one replay) */
} dm_path_series;
/* Quality along a camera path (run/mpath_quality.h; docs/motion.md,
 * "Quality along a path"): a reference every K-th frame of one pass of F
 * frames (frames 0, K, 2K, ... <= F - 1), the configuration's FLIP mean and
 * SSIM against each, the temporal error over the steps between them, and
 * popping.  present 0 and reason NULL: none asked (a still configuration,
 * or a run from before paths); present 0 with reason: asked but not
 * computed, reason says why.  results.json "path_quality". */

/* One frame of the path written as images for the report's filmstrip
 * (run/mpath_quality.h, MPATH_SHOTS_MAX): the configuration's frame, its
 * reference frame and their FLIP map, paths relative to the run directory
 * (NULL where that image could not be written). */
typedef struct dm_path_shot {
    long frame;              /* along the path: one of the reference frames */
    char *img_test, *img_ref, *img_flip;
} dm_path_shot;

typedef struct dm_path_quality {
    int present;
    long frames;             /* F */
    long every;              /* K, as used (the default rule applied) */
    size_t n;                /* reference frames; frame i of the series is i*K */
    double *flip, *ssim;     /* n each; NaN where not computed */
    double temporal_mean, temporal_p99;   /* NaN: fewer than two reference frames */
    double popping;          /* largest |FLIP_i - FLIP_(i-1)|; NaN: none */
    long popping_frame;      /* the frame (along the path) the largest jump lands on */
    char *img_temporal;      /* the temporal error map, relative to the run directory */
    char *reason;
    dm_path_shot *shots;     /* the frames written as images, in path order; none in a run
                                from before they were written (store schema < 8) */
    size_t n_shots;
} dm_path_quality;

typedef struct dm_config_result {
    char *key;               /* stable hash of relevant params (16 hex) */
    char *scene;             /* scene id: mesh/camera/lights/material/resolution */
    dm_kv *params;
    size_t n_params;
    int ok;                  /* status "ok" (1) or "failed" (0) */
    char *reason;            /* failure reason, NULL when ok */
    char *log;               /* shader info log / GL debug messages, may be NULL */
    dm_counter_result *counters;
    size_t n_counters;
    dm_quality quality;
    char *img_render;        /* paths relative to the run directory */
    char *img_heatmap;
    char *img_reference;
    char *img_flip;          /* FLIP map on the fixed [0,1] scale, may be NULL */
    dm_path_series path;     /* frame times along its camera path (frames 0: still) */
    dm_path_quality path_quality;
} dm_config_result;

typedef struct dm_left_out {
    dm_kv *params;
    size_t n_params;
    char *reason;
} dm_left_out;

typedef struct dm_fit_param {
    char *name;
    double value, stderr_;
} dm_fit_param;

typedef struct dm_fit_result {
    char *model;             /* model name or formula */
    char *formula;
    char *response;
    dm_kv *group;
    size_t n_group;
    dm_fit_param *params;
    size_t n_params;
    double r2, rmse, mape, cv_mape;
    double condition;        /* 2-norm condition number of the scaled Jacobian (>= 1); 0 = not computed, INFINITY = rank deficient */
    int n_points, n_excluded;
    char *termination;
    char **warnings;
    size_t n_warnings;
    /* predicted vs measured, for plots: n_points pairs */
    double *measured, *predicted;
    double *cv_predicted;    /* each point predicted by the cross-validation fit that held it out
                                (NaN when none did); in memory only, not stored */
    char **point_labels;     /* config keys, may be NULL */
} dm_fit_result;

/* One round of a scene's timing samples (run/measure.c): the
 * configurations in the order it sampled them, so a run's order is on
 * record and can be checked, and the calibration kernel timed with it. */
typedef struct dm_round {
    char *scene;
    long seq;                /* 0, 1, ... within the scene, in the order measured */
    char *keys;              /* configuration keys, space-separated, in sampling order */
    double calib_ns;         /* the calibration kernel's time in this round; NaN: not measured */
} dm_round;

/* The drift of one scene and what removing it left (models/drift.h):
 * relative robust SDs (0.01 = 1 %). */
typedef struct dm_scene_precision {
    char *scene;
    int corrected;           /* 1: its configurations have corrected figures */
    char *reason;            /* when not, why (raw figures only); may be NULL */
    char *predictor;         /* the better predictor of the drift on this run: "common mode",
                                "calibration" or "neither"; NULL when not measured */
    int n_rounds;            /* rounds with a common mode */
    double machine_spread;   /* how far the machine's speed moved between rounds */
    double raw_noise;        /* spread of the samples, uncorrected */
    double loo_noise;        /* after the round's common mode */
    double calib_noise;      /* after the calibration workload's ratio; NaN: not measured */
    double resolvable;       /* smallest relative difference between two of its configurations
                                the run resolves: sqrt(2) x the median CI half-width used */
    int between_runs;        /* 1: reference_spread is measured (at the end of a run or a merge;
                                not kept in the store) */
    double reference_spread; /* the uncertainty of the run's median machine speed that the
                                corrected figures are relative to (robust SD, relative): the
                                bootstrap's spread of it and the run's slow drift (run/precision.h)
                                together */
    double half_shift;       /* how far the machine's speed moved between the halves of the
                                scene's rounds (log ratio, models/drift.h); NaN: not measured */
} dm_scene_precision;

typedef struct dm_run_result {
    char *id;
    char *sweep;             /* sweep name */
    char *started;           /* ISO-8601 */
    char *finished;
    char *sweep_hash;
    dm_kv *environment;      /* renderer, gl_version, lp_num_threads, cpu, fingerprint, ... */
    size_t n_environment;
    double gpu_time_coverage;
    char *timer_verdict;     /* "partial" | "full" | "unknown" */
    dm_config_result *configs;
    size_t n_configs;
    dm_left_out *left_out;
    size_t n_left_out;
    dm_fit_result *fits;
    size_t n_fits;
    char **warnings;
    size_t n_warnings;
    dm_round *rounds;        /* by scene, then seq */
    size_t n_rounds;
    dm_scene_precision *precision;   /* one per scene measured, after the run's end */
    size_t n_precision;
} dm_run_result;

/* Lookup helpers; return NULL when absent. */
/* The columns of a configuration's row in results.csv that are neither a
 * parameter nor a counter: DM_RESULT_LEAD_COLUMNS come first, then the
 * parameters and counters, then DM_RESULT_TRAIL_COLUMNS and, in a run with a
 * camera path, DM_RESULT_PATH_COLUMNS (reports/report_csv.c).
 * A parameter by one of these names would be a second column of that name,
 * so user techniques may not declare one (dm_result_column_reserved). */
#define DM_RESULT_LEAD_COLUMNS "key", "scene", "status", "reason"
#define DM_RESULT_TRAIL_COLUMNS "label", "pareto", "WallTime_corr_median_ms", \
    "WallTime_corr_ci_lo_ms", "WallTime_corr_ci_hi_ms", "drift_correction"
/* Last, in a run with a configuration on a camera path (docs/motion.md). */
#define DM_RESULT_PATH_COLUMNS "path_p50_ms", "path_p95_ms", "path_p99_ms", \
    "path_one_percent_low_ms", "path_one_percent_low_fps", "path_stutters", \
    "path_temporal_error_mean", "path_temporal_error_p99", "path_popping", "path_popping_frame"
/* 1 when name is one of the columns above. */
int dm_result_column_reserved(const char *name);

const char *dm_kv_get(const dm_kv *kv, size_t n, const char *key);
/* Axes that stay out of a configuration's parameters at their default, so
 * its key is the one it had before the axis existed (the planner drops them
 * there: techniques/axes.c reads this list): that default, or NULL for any
 * other name. */
const char *dm_param_left_out_default(const char *name);
/* A configuration's value of param `name`: its own; the default of an axis
 * left out at its default (so a still camera path reads "still" beside a
 * dolly, and cull "back" beside "none"); else NULL (the technique does not
 * read it, or a condition dropped it). */
const char *dm_param_value(const dm_kv *params, size_t n, const char *name);
const dm_counter_result *dm_config_counter(const dm_config_result *c, const char *name);
const dm_fit_param *dm_fit_param_find(const dm_fit_result *f, const char *name);
/* The first configuration of run with that key. */
const dm_config_result *dm_run_config(const dm_run_result *run, const char *key);
/* The one rule for a counter read back (results store, results.json): an
 * available counter whose value (median, for one with samples) is missing
 * or not finite is made unavailable, its reason naming what was read and
 * from where (source), so it is never a PASS, a fit point or a printed
 * interval.  Returns 1 when it did so. */
int dm_counter_read_check(dm_counter_result *c, const char *source);
/* 1 when some ok configuration of run has counter name available. */
int dm_run_has_counter(const dm_run_result *run, const char *name);
/* 1 when param k has another value (or none) in some configuration of run,
 * so that it tells configurations apart; 0 when all share it. */
int dm_run_param_varies(const dm_run_result *run, const dm_kv *k);
/* Appends a copy of key/value to a kv array (realloc'd). */
void dm_kv_push(dm_kv **kv, size_t *n, const char *key, const char *value);
void dm_kv_free(dm_kv *kv, size_t n);

/* The run's noise floor: the median over configurations with WallTime of
 * its relative CI half-width (corrected where corrected, else raw) into
 * *floor, and sqrt(2) times it, the smallest relative difference between two
 * configurations the run resolves, into *resolvable.  Returns the number
 * of configurations used (0: both NaN). */
size_t dm_run_noise_floor(const dm_run_result *run, double *floor, double *resolvable);

void dm_counter_result_free(dm_counter_result *c);
void dm_config_result_free(dm_config_result *c);
void dm_fit_result_free(dm_fit_result *f);
/* Frees everything the run owns and zeroes it. */
void dm_run_free(dm_run_result *run);

#endif
