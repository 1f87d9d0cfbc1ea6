/* report_model.h — what a report shows of one run, derived once.
 *
 * Built from a dm_run_result (and the run directory, the trend lines of the
 * store) before any file is written; every writer of the report table
 * (report_write.c: results.json, results.csv, summary.md, report.html,
 * front.tex), the answer in words (answer.c, also the terminal's), the
 * charts (svg_chart.c, chart.c), the stage bars and the drivers report
 * read it instead of deriving labels, frame times, fronts, picks and
 * warnings again, so they cannot disagree.  The model borrows the run, the
 * directory and the trends (they must outlive it) and owns everything
 * else; it is read-only once built.
 *
 * Per configuration (run order): its labels, technique and family, frame
 * time and the text of its CI, the noise marks, whether it is on its
 * scene's front, its quality as a sentence says it, its trend line and its
 * image defects with their marks.  Per scene (first-appearance order): its
 * label, the ok configurations fastest first, the axes that vary, the
 * front, the recommendation (pick, knee, best per family), whether the
 * pick is provisional, its counter table's counters, the counter breakdown
 * its chart draws (breakdown.h) and the untimed note.  Once for the run:
 * the error metric, the budget, whether any scene is timed, the units of
 * each fit's parameters, the warnings
 * list (results.json, summary.md and report.html say the same words) and
 * the published figures, read from published.json once.
 *
 * Fields are grouped by who reads them; a group added for a new reader
 * goes at the end of its struct.
 */
#ifndef REPORTS_REPORT_MODEL_H
#define REPORTS_REPORT_MODEL_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/breakdown.h"
#include "reports/metric.h"
#include "reports/recommend.h"
#include "reports/recommend_run.h"
#include "reports/report.h"

/* How the corrected figures were made, as every file names it
 * (docs/measurement.md, "Drift removed"). */
#define REPORT_DRIFT_METHOD "each round's common mode divided out (median polish of log times, " \
                            "leave-one-out), CI with the correction's own uncertainty (bootstrap over rounds)"

/* Why a corrected figure has no between-run CI (docs/measurement.md,
 * "Between runs"). */
#define REPORT_BETWEEN_UNAVAILABLE "computed at the end of a run or a merge and not kept in the store: " \
                                   "this file was written from a stored run"

/* One configuration as every file shows it. */
typedef struct report_model_row {
    const dm_config_result *config;     /* borrowed from the run */
    size_t scene;                       /* index into report_model.scenes */
    char *label;          /* technique and the axes varying in its scene ("pom steps=8") */
    char *full_label;     /* report_config_label: "cube 480×270 · pom steps=8" */
    char *name;           /* report_config_name: full_label, " [key]" when not unique */
    const dm_counter_result *frame_time;   /* WallTime with samples, or NULL */
    char *ms_text;        /* median in ms, three significant digits; NULL without frame time */
    char *ci_text;        /* "±9.1%", "−5.0%/+89%" or "CI unknown"; NULL without frame time */
    char *time_ci_text;   /* "4.43 ms [4.33, 4.53]"; NULL without frame time */
    char *marks;          /* noise, drift and bimodal marks with the CI ("" when sound) */
    char *marks_short;    /* the same for a table that shows the CI beside it */
    char *why;            /* the marks' reasons in words ("" when sound) */
    int noisy;            /* report__noisy */
    int front;            /* on its scene's Pareto front under the run's metric */
    double error;         /* its error under the run's metric; NaN when none */
    double shown;         /* the metric as shown (SSIM: 1 − SSIM, PSNR in dB); NaN when none */
    const report_trend *trend;   /* this configuration's trend line, or NULL */
    long nonfinite_pixels, crack_pixels;   /* image defects (0 without quality) */
    /* what the answer's sentences, the charts, the gallery and the stage bars read */
    const char *technique;   /* its technique param, "?" without one */
    recommend_family family; /* report_family */
    char *metric_text;       /* its quality for a sentence: "SSIM 0.950" (report_metric_text) */
    char *defects;           /* "⚠ 7 crack pixels; ⚠ 3 NaN pixels", "" when none */
    char *defects_why;       /* the defects' reasons in words, "" when none */
    /* Drift removed (docs/measurement.md, "Drift removed"): the frame time
     * with the machine's drift divided out, beside the raw figures above */
    int corrected;              /* frame_time carries corrected figures */
    char *corr_ms_text;         /* corrected median in ms; NULL when not corrected */
    char *corr_ci_text;         /* its CI as ci_text; NULL when not corrected */
    char *corr_time_ci_text;    /* "4.40 ms [4.35, 4.45]"; NULL when not corrected */
    /* Camera path (docs/motion.md): per frame 0…F−1 along the path
     * (F = config->path.frames), the median of its replays' finite times
     * (as models/frame_series takes its percentiles over) and their min
     * and max, in ms; NaN where no replay has a time.  NULL for a still
     * configuration.  report.html's frame-time plot draws them. */
    double *path_ms, *path_lo_ms, *path_hi_ms;
} report_model_row;

/* One scene of the run. */
typedef struct report_model_scene {
    const char *name;     /* the scene id, borrowed from the run */
    char *label;          /* report_scene_label: "cube 480×270" */
    size_t *rows;         /* ok configurations, fastest first (ties in run order) */
    size_t n_rows;
    const char **varying; /* the param names that take two or more values */
    size_t n_varying;
    char *same;           /* the others with their one value: "mesh=plane steps=8 " ("" when none) */
    size_t *front;        /* the Pareto front, fastest first (config indexes) */
    size_t n_front;
    char *front_text;     /* the front as one sentence */
    const char *untimed;  /* report_untimed_reason, or NULL when timed */
    recommend_result rec; /* pick, knee, best per family (config indexes) */
    size_t n_points;      /* points the recommendation considered */
    /* what the answer's sentences and the counter table read */
    size_t n_timed;       /* rows with a frame time */
    size_t n_noisy;       /* of those, the noisy ones */
    int provisional;      /* the pick may move: two or more timed and most of them noisy
                             (noisy_majority), or the times' CIs allow the default budget
                             another gap and another pick (rec.budget_moves, recommend.h) */
    int noisy_majority;
    const char **det;     /* the scene's deterministic counters, first appearance */
    size_t n_det;
    /* what chart.c draws */
    breakdown breakdown;  /* the counter breakdown chosen for its timed rows (breakdown.h) */
    /* what the gallery's legends say */
    double max_error;     /* the largest MaxError of its rows with quality (0 without) */
    int flips;            /* some row has a FLIP map */
    int heatmap_flip;     /* some row's heatmap is its FLIP map (runs since 2026-11-29) */
    int heatmap_diff;     /* some row's heatmap is |render − reference| (older runs) */
    double flip_ppd;      /* the pixels per degree of its FLIP maps (the last row's); NaN without */
    /* Drift removed: the scene's record and the verdict on the corrected figures */
    const dm_scene_precision *precision;   /* borrowed from the run; NULL: none recorded */
    int has_rec_corr;     /* 1: rec_corr holds the recommendation on the corrected figures */
    recommend_result rec_corr;
    char *disagree;       /* report_answer_disagree's sentence; NULL when raw and corrected agree */
    /* Camera paths (docs/motion.md, "In the report"): the second front,
     * temporal error mean against p99 frame time, over the scene's path
     * rows with both (n_motion_points); its members (config indexes,
     * fastest p99 first, exact errors: no epsilon) and the steadiest of
     * them whose p99 is within rec.budget (RECOMMEND_NONE: none fits) */
    size_t n_motion_points;
    size_t *motion_front;
    size_t n_motion_front;
    size_t motion_pick;
} report_model_scene;

typedef struct report_model {
    const dm_run_result *run;     /* borrowed */
    const char *dir;              /* run directory images are relative to; NULL */
    const report_trends *trends;  /* borrowed; NULL: none */
    report_metric metric;         /* the run's Pareto error metric */
    char *constants;              /* report_scene_constants: settings every scene shares ("") */
    report_model_row *rows;       /* one per configuration, run order */
    size_t n_rows;
    report_model_scene *scenes;
    size_t n_scenes;
    const char **params;          /* param names over the run, first appearance */
    size_t n_params;
    const char **timed;           /* timing counters with samples (results.csv's columns) */
    size_t n_timed;
    const char **det;             /* deterministic counters */
    size_t n_det;
    char **warnings;              /* report__warnings, in its order */
    size_t n_warnings;
    size_t *noisy;                /* indexes of the noisy configurations */
    size_t n_noisy;
    char *published_md;           /* the published section, read once; "" when none */
    char *published_html;
    /* what the answer's sentences and summary.md's header read */
    double budget_ms;             /* report_budget_ms: 0 = each scene's default */
    int any_timed;                /* some scene has a frame time (a budget and a pick) */
    /* what the fits table reads */
    char ***fit_units;            /* [fit][param]: "ns per VSInvocations"; "" when unknown */
    /* Drift removed: the run's noise floor (dm_run_noise_floor) and its sentence */
    double noise_floor;           /* median relative CI half-width; NaN without WallTime */
    double resolvable;            /* smallest resolvable relative difference; NaN likewise */
    size_t n_corrected_scenes;    /* scenes whose figures have the drift removed */
    char *precision_text;         /* the sentence every file shows; "" without WallTime */
    /* Camera paths: configurations with frame times along a path (their
     * dm_config_result.path); 0 in a still run, whose files then have no
     * path column or table */
    size_t n_path_rows;
} report_model;

/* Builds the model of run for the files d describes (report.h): d->dir
 * (or, without it, the directory of d->path) holds published.json, d->trends
 * the trend lines; d may be NULL (no directory, no trends).  Zeroes *m first;
 * release with report_model_free.  0 or DM_ERR_ARG (no run). */
int report_model_build(report_model *m, const dm_run_result *run, const report_desc *d);
void report_model_free(report_model *m);

/* 1 when c's heatmap is its FLIP map (runs since 2026-11-29 write one map,
 * FLIP's, and name it both images.heatmap and images.flip); 0 for an older
 * run's |render − reference| heatmap or none. */
int report_model_heatmap_is_flip(const dm_config_result *c);

/* The row of the configuration with this key, or NULL. */
const report_model_row *report_model_find(const report_model *m, const char *key);

#endif
