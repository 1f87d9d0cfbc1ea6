/* report_internal.h — what reports/ shares inside itself (not public):
 * the writers of the report table, and the helpers the report model
 * (report_model.c) derives with: labels, CIs, marks, rows, fronts,
 * warnings (report.c), the charts' drawing entry points.
 *
 * All names carry the report__ prefix.  The derivations read the run
 * (dm_results.h); the writers and charts read the report model.
 */
#ifndef REPORTS_REPORT_INTERNAL_H
#define REPORTS_REPORT_INTERNAL_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/metric.h"
#include "reports/report.h"
#include "reports/report_model.h"

/* The writers of the report table (report_write.c, the only caller): each
 * writes one file at path from the model alone. */
int report__write_json(const report_model *m, const report_desc *d, const char *path);
int report__write_csv(const report_model *m, const report_desc *d, const char *path);
int report__write_md(const report_model *m, const report_desc *d, const char *path);
int report__write_html(const report_model *m, const report_desc *d, const char *path);
int report__write_tex(const report_model *m, const report_desc *d, const char *path);

/* 1 when p is a usable image path: non-empty, relative, without "..". */
int report__safe_relpath(const char *p);

/* Formats a double the way cJSON prints it (%1.15g, or %1.17g when needed to
 * read back the same double) into buf[32]. */
void report__fmt_num(double v, char buf[32]);

/* 1 when s is exactly what report__fmt_num prints for the number it denotes,
 * so writing it as a JSON number and reading it back gives s again. */
int report__is_canonical_num(const char *s);

/* The timing counter shown as "the" frame time: WallTime when it is available
 * with samples, else NULL. */
const dm_counter_result *report__frame_time(const dm_config_result *c);

/* Relative half-width of the 95 % CI of t's median ((hi − lo) / 2 / median);
 * NaN when the median is not positive. */
double report__ci_rel(const dm_counter_result *t);
/* The CI around the median as percentages: "−5.0%/+89%" when one side is
 * over REPORT__CI_ASYMMETRIC times the other and they differ by a
 * percentage point or more, else "±9.1%" (one decimal below 10 %);
 * "CI unknown" when unknown. */
#define REPORT__CI_ASYMMETRIC 1.5
void report__ci_text(const dm_counter_result *t, dm_str *out);
/* ns as milliseconds to three significant digits without an exponent
 * ("206", "4.43", "0.205"). */
void report__ms_text(double ns, dm_str *out);
/* "4.43 ms [4.33, 4.53]": the median and its 95 % CI, three significant digits. */
void report__time_ci_text(const dm_counter_result *t, dm_str *out);
/* Samples in two groups: sorted, split at the widest gap, each side holds at
 * least a fifth of them (and two), and the gap is over three times the wider
 * side's range and over 10 % of the median.  Returns the count of the upper
 * group (0: not bimodal); *low and *high get each group's middle sample. */
size_t report__bimodal(const dm_counter_result *t, double *low, double *high);
/* The marks of a configuration's timing for tables and the answer:
 * "⚠ noisy: CI −5%/+89%", "⚠ drift -9.9 %" (its log's drift line) and/or
 * "⚠ bimodal: 3 of 16 samples near 3.19 ms, the rest near 1.60" into mark, the reasons in words into why (both left
 * unchanged when the timing is sound); without with_ci (a table that shows
 * the CI beside it) the noisy mark is just "⚠ noisy". */
void report__timing_marks(const dm_config_result *c, int with_ci, dm_str *mark, dm_str *why);

/* The defects of a configuration's image as one mark ("⚠ 128 crack
 * pixels; ⚠ 3 NaN pixels") into mark and the reasons in words into why;
 * both left unchanged when the image has none. */
void report__defects(const dm_config_result *c, dm_str *mark, dm_str *why);

/* A configuration's timing is "noisy" (too noisy to trust) when it is ok
 * and the 95 % CI of its median frame time is wider than ± this fraction of
 * the median, or unknown (docs/measurement.md). */
#define REPORT__NOISY_CI_REL 0.05
int report__noisy(const dm_config_result *c);
/* Indexes of the noisy configurations in run order; *out malloc'd (caller
 * frees).  Returns the count. */
size_t report__noisy_configs(const dm_run_result *run, size_t **out);
/* Plain-text header warnings about the images and failures, one per line:
 * "N configurations failed (see Failed configurations)", "N configurations
 * with non-finite pixels: label (count), ...", "N configurations with crack
 * pixels: label (count), ...".  Appends nothing when all is well. */
void report__quality_warnings(const dm_run_result *run, dm_str *out);

/* The "WallTime drifted ..." line of a configuration's log (its length in
 * *len when len is not NULL), or NULL. */
const char *report__drift(const dm_config_result *c, size_t *len);
/* Every warning of the run as plain text, one string each, the same list in
 * results.json "warnings", summary.md and report.html: the partial timer,
 * the count of noisy configurations, drift, failures, non-finite and crack
 * pixels, then the run's stored warnings.  A computed line already among the
 * stored ones is not repeated, so read → write keeps the list as it was.
 * *out malloc'd (report__warnings_free).  Returns the count. */
size_t report__warnings(const dm_run_result *run, char ***out);
void report__warnings_free(char **w, size_t n);

/* Distinct scene names in first-appearance order; *out is malloc'd and points
 * into run (free only the array).  Returns the count. */
size_t report__scenes(const dm_run_result *run, const char ***out);

/* Distinct param names over configs
 * in first-appearance order; same ownership as report__scenes.  When scene is
 * non-NULL only that scene's configs are scanned. */
size_t report__param_names(const dm_run_result *run, const char *scene, const char ***out);

/* Distinct counter names over all configs selected by kind:
 * REPORT__TIMED = available non-deterministic counters with samples,
 * REPORT__DETERMINISTIC = deterministic counters (available or not). */
enum report__counter_kind { REPORT__TIMED = 1, REPORT__DETERMINISTIC = 2 };
size_t report__counter_names(const dm_run_result *run, const char *scene,
                             enum report__counter_kind kind, const char ***out);

/* "technique" param of a config or "?" */
const char *report__technique(const dm_config_result *c);

/* 1 when param `name` takes two or more distinct values in the scene (a
 * technique that does not read it has no value, which does not count). */
int report__param_varies(const dm_run_result *run, const char *scene, const char *name);
/* Indexes of the scene's ok configurations sorted by median frame time;
 * *out is malloc'd (caller frees). */
size_t report__scene_rows(const dm_run_result *run, const char *scene, size_t **out);
/* "technique axis=value..." with only the axes that vary in its scene. */
void report__config_label(const dm_run_result *run, const dm_config_result *c, dm_str *out);
/* The scene's ok configurations with a frame time and a finite error under
 * m, fastest first: config indexes into idx, x = median ns, y = error (each
 * array has room for run->n_configs).  Returns the count. */
size_t report__pareto_points(const dm_run_result *run, const char *scene, report_metric m,
                             size_t *idx, double *x, double *y);
/* Configurations on the Pareto front of (median time, error under the run's
 * metric), fastest first; *out malloc'd (config indexes).  And the same as
 * one sentence. */
size_t report__pareto(const dm_run_result *run, const char *scene, size_t **out);
void report__pareto_text(const dm_run_result *run, const char *scene, dm_str *out);

/* The unit of fit parameter param, from the fit's formula and the unit of
 * its response counter in the run: "ns" for a term that is the parameter
 * alone, "ns per VSInvocations" for "param*VSInvocations" (the rest of the
 * term after the first '*', as written: "ns per tess_level^p").  Appends
 * nothing when the parameter leads no term of a plain sum (an exponent, a
 * parenthesis). */
void report__fit_unit(const dm_run_result *run, const dm_fit_result *f, const char *param, dm_str *out);

/* 1 when the 95 % CIs of the two timings' medians overlap (statistically
 * tied); 0 when either CI is unknown. */
int report__tied(const dm_counter_result *a, const dm_counter_result *b);

/* Hand-written SVG charts of scene si of the model (svg_chart.c): error vs
 * time with CI whiskers, labelled points and the family legend, and time
 * per configuration of this scene only.  Nothing when the scene has no
 * timed configuration. */
void report__svg_scene(dm_str *s, const report_model *m, size_t si);

/* The frame-time plot of row r on a camera path (svg_chart.c): x = frame
 * 0…F−1, y = r->path_ms (the per-frame medians, also in the median line's
 * data-ms attribute) with the replays' min–max band, p50 and p99 as lines,
 * the stutters as marked points.  Nothing for a still row or one without a
 * single frame time. */
void report__svg_path(dm_str *s, const report_model_row *r);

/* The quality plot of row r along its camera path (svg_chart.c): FLIP mean
 * and 1 − SSIM at the reference frames 0, K, 2K, … (the values themselves,
 * SSIM not subtracted, in the lines' data-flip and data-ssim attributes),
 * popping marked at its frame.  Nothing without computed path quality. */
void report__svg_path_quality(dm_str *s, const report_model_row *r);

/* Scene si's second front (svg_chart.c): temporal error mean against p99
 * frame time of its path configurations, the front's members filled and
 * joined (report_model_scene.motion_front), each point's technique beside
 * it.  Nothing with fewer than two such configurations. */
void report__svg_motion_front(dm_str *s, const report_model *m, size_t si);

/* "Along the path" of scene si in report.html (path_html.c): per
 * configuration on a camera path, its figures (with its quality along the
 * path where computed: temporal error, popping, a link to the temporal
 * error map prefixed by href) and its frame-time and quality plots.
 * Nothing for a scene without one, so a still run's page is unchanged. */
void report__html_path_scene(dm_str *s, const report_model *m, size_t si, const char *href);

/* Charts (chart.c): inline SVG appended to an HTML document, each in a
 * <div class="chart" aria-label="title">.  Scene si's PLplot charts from the
 * model: time vs tess_level per mesh and technique, and the counter
 * breakdown the model chose (report_model_scene.breakdown: measured stage
 * times, a fit's estimate, or the key counters, with their notes).
 * Nothing is appended when there is nothing to plot. */
void report__html_charts_scene(dm_str *s, const report_model *m, size_t si);
/* The two plots of one fit (predicted vs measured with y = x; residuals in
 * percent of the measured value vs predicted), nothing without points. */
void report__html_charts_fit(dm_str *s, const dm_run_result *run, const dm_fit_result *f);

/* Copies the file from (a regular file: dm_input_file) → to, creating to's
 * directory; 0, or DM_ERR_ARG / DM_ERR_IO / DM_ERR_DISK (the disk refused
 * the write) with the file and the reason in err. */
int report__copy_file(const char *from, const char *to, char *err, size_t errlen);

/* Writes s to path (atomically, dm_write_file): 0, DM_ERR_DISK or DM_ERR_IO
 * with errno saying why; no partial file is left. */
int report__save(const dm_str *s, const char *path);

#endif
