/* report.h — results.json, results.csv, summary.md and report.html for one run.
 *
 * Reads only the in-memory results model (core/dm_results.h); never touches
 * GL or runs anything.  Every string from a sweep file or the environment
 * is HTML-escaped.  Image paths are relative to the run directory and are
 * refused if they would leave it.
 *
 * results.json encoding (docs/exports.md names; additions are marked +):
 *  - PSNR of identical images is +infinity, which JSON cannot hold: it is
 *    written "PSNR": null together with "PSNR_infinite": true (+, always
 *    present, false otherwise).  Any other non-finite number is null and
 *    reads back as NaN.  A NULL string is null.
 *  - params/group values that are canonical numbers ("32", "0.5") are JSON
 *    numbers, all others strings; reading turns numbers back into the same
 *    text, so write → read → write is byte-identical.
 *  - counters: timed {unit, deterministic+, partial+, median, ci95[lo,hi],
 *    samples[], mean, min, max, stddev, mad, cv, outliers, nonfinite+};
 *    single value {unit, deterministic+, partial+, value}; unavailable
 *    {unit, deterministic+, unavailable: "reason"} (never a 0).
 *  - added: run.finished, run.sweep_hash, quality.MaxError,
 *    quality.PctOverThreshold, quality.FLIP/FLIPQ1/FLIPMedian/FLIPQ3/
 *    FLIPMax/FLIPPixelsPerDegree (null when not computed),
 *    quality.reference, images.reference, images.flip, config.log, fit.formula/response/rmse/mape/n_points/n_excluded/
 *    termination/measured/predicted/point_labels, top-level warnings[],
 *    top-level schema_version, per config label and pareto (derived, not
 *    read back); the shape is docs/results.schema.json.
 *
 * results.csv: one row per configuration, RFC 4180 (CRLF, quoted fields);
 * columns key, scene, status, reason, the union of params, per timing
 * counter <name>_median_ms/_ci_lo_ms/_ci_hi_ms, each deterministic counter,
 * then RMSE, PSNR_dB ("inf" when infinite), SSIM, MaxError, SilhouetteError,
 * DepthRMSE, CrackPixels, NonFinitePixels, FLIP, FLIPMedian, FLIPMax, label,
 * pareto (0/1); unavailable = empty field.
 *
 * report.html opens with the answer: per scene the Pareto front as a
 * compact table (technique, varying axes, ms ± CI, the error metric, cost
 * relative to the fastest, statistically tied members marked), then a table
 * of contents, warnings and the environment folded in a <details>.  Scene
 * tables show the key columns first (the rest behind a toggle), sort, filter
 * and scroll in their own box.  Per scene: error vs time with CI whiskers and
 * numbered points, time per configuration of that scene (svg_chart.c), time
 * vs tess_level when it varies and the counter breakdown (chart.c).  The
 * gallery embeds each reference once (PNG thumbnail, data: URI, at most
 * 192 px) and links renders and heatmaps from img/ (a render flips to its
 * reference on click; the heatmap has its colour scale); per fit, predicted
 * vs measured and residuals.
 *
 * Pareto metric (reports/metric.h): the run's environment entry
 * "pareto_metric" (default ssim) picks the error of every front; it is
 * named in the answer, the chart axis, the scene tables and summary.md.
 * Noisy configurations (95 % CI of the median wider than ±5 %, or unknown;
 * docs/measurement.md) are listed in a warning box and in summary.md.
 */
#ifndef REPORTS_REPORT_H
#define REPORTS_REPORT_H

#include "core/dm_results.h"
#include "core/dm_util.h"

/* What report_write writes and where (report_model.h builds what it shows).
 * dir: the run directory image paths are relative to (thumbnails embedded,
 * missing files marked; NULL links images without checking them); out: the
 * folder the files go into, which must exist (NULL: dir), the images the
 * run names and published.json being copied there from dir so out opens on
 * its own; href: prefixed to every image link of report.html (NULL: "");
 * trends: the trend lines of the store (NULL: none); file: the name of one
 * row of the writer table ("results.json", "front.tex") to write only that
 * file (NULL: every row, and nothing copied); path: with file, where it
 * goes (NULL: out/file). */
struct report_model;
typedef struct report_trends report_trends;
typedef struct report_desc {
    const char *dir;
    const char *out;
    const char *href;
    const report_trends *trends;
    const char *file;
    const char *path;
} report_desc;
/* Writes the files of the writer table (report_write.c) from the model m
 * (built with the same desc).  Returns 0 or the writer's code (DM_ERR_IO:
 * err names the file); stops at the first failure; DM_ERR_ARG for a file
 * name that is no row (err lists the rows). */
int report_write(const struct report_model *m, const report_desc *d, char *err, size_t errlen);
/* report_model_build, report_write and report_model_free in one call. */
int report_write_run(const dm_run_result *run, const report_desc *d, char *err, size_t errlen);

/* A configuration's median WallTime (ns) in the runs of the store on the
 * same machine fingerprint, oldest first, this run last (run/trends.h
 * builds them from the store).  report.html draws a small trend line per
 * configuration that has two or more. */
typedef struct report_trend {
    char *key;
    double *median_ns;
    size_t n;
} report_trend;
struct report_trends {
    report_trend *items;
    size_t n;
};
void report_trends_free(report_trends *t);

/* The one label of a configuration, the same in every file and on the
 * terminal: the scene (mesh, resolution with ×, and only the scene settings
 * that differ between the run's scenes) · the technique and the axes that
 * take two or more values in its scene (failed configurations included),
 * e.g. "cube 480×270 · pom steps=8". */
void report_config_label(const dm_run_result *run, const dm_config_result *c, dm_str *out);
/* The scene part alone, e.g. "cube 480×270". */
void report_scene_label(const dm_run_result *run, const char *scene, dm_str *out);
/* The same among the n scene ids of all (duplicates allowed), for callers
 * without a run (the runner's progress lines). */
void report_scene_label_among(const char *scene, const char *const *all, size_t n, dm_str *out);
/* The scene settings every scene of the run shares ("camera.elevation=35"),
 * said once in headers; nothing when there are none. */
void report_scene_constants(const dm_run_result *run, dm_str *out);
/* report_config_label, with " [key]" appended only when two configurations
 * would otherwise share it.  Used as results.json "label" and as the
 * benchmark name of every export. */
void report_config_name(const dm_run_result *run, const dm_config_result *c, dm_str *out);
/* results.json "schema_version": the major version of docs/results.schema.json;
 * raised only when a field changes meaning or goes away (additions keep it). */
#define REPORT_SCHEMA_VERSION 1

/* Writes a cJSON document, pretty-printed with a final newline, atomically
 * to path (root stays the caller's).  0, DM_ERR_NOMEM or DM_ERR_IO. */
struct cJSON;
int report_write_cjson(const struct cJSON *root, const char *path);
/* Rewrites every finite number of the tree as the fewest of 15..17
 * significant digits that read back bit for bit, so results.json and the
 * exports carry exactly the values of the store. */
void report_json_exact_numbers(struct cJSON *node);
/* One fit as its results.json "fits" entry (cJSON; the caller deletes it). */
struct cJSON *report_fit_to_json(const dm_fit_result *f);
/* Reads a results.json back (for compare/merge) into *out (zeroed first;
 * release with dm_run_free).  DM_ERR_ARG when not a regular file (never
 * opened: dm_input_file), DM_ERR_IO when missing or unreadable, DM_ERR_PARSE when malformed or without "run"/"configs"/config
 * keys; err names the path and why. */
int report_read_json(const char *path, dm_run_result *out, char *err, size_t errlen);

#endif
