/* metric.h — the error metric of the Pareto front (quality against time).
 *
 * A metric reads a configuration's dm_quality two ways: as an *error* (lower
 * is better, what the front is computed on) and as the *shown* value (its
 * natural unit, what charts, tables and text print: PSNR in dB, higher is
 * better; 1 − SSIM for ssim; the error itself for the others).
 *
 * A run records its metric in its environment under REPORT_METRIC_KEY (the
 * runner copies the sweep's quality.pareto_metric there), so `dmbench report
 * DIR` reproduces it; absent means ssim.  REPORT_METRICS is a plain X-macro
 * list so that the sweep parser can validate names without linking reports/.
 */
#ifndef REPORTS_METRIC_H
#define REPORTS_METRIC_H

#include "core/dm_results.h"
#include "core/dm_util.h"

#define REPORT_METRIC_KEY "pareto_metric"

/* X(ID, "name") in the order they are listed to users; the first is the default. */
#define REPORT_METRICS(X)          \
    X(SSIM, "ssim")                \
    X(PSNR, "psnr")                \
    X(RMSE, "rmse")                \
    X(MAX_ERROR, "max-error")      \
    X(SILHOUETTE, "silhouette")    \
    X(DEPTH_RMSE, "depth-rmse")    \
    X(FLIP, "flip")

typedef enum report_metric {
#define REPORT__METRIC_ENUM(id, name) REPORT_METRIC_##id,
    REPORT_METRICS(REPORT__METRIC_ENUM)   /* REPORT_METRIC_SSIM = 0: the default */
#undef REPORT__METRIC_ENUM
    REPORT_METRIC_COUNT
} report_metric;

/* The names in list order; returns their number. */
size_t report_metric_names(const char *const **names);
/* Name → metric: 0, or DM_ERR_ARG (NULL or unknown name; *out unchanged). */
int report_metric_parse(const char *name, report_metric *out);
/* Appends "unknown metric 'x'; did you mean 'y'? valid metrics: ssim, ..." to err. */
void report_metric_unknown(const char *name, dm_str *err);
const char *report_metric_name(report_metric m);
/* Axis / column label of the shown value, e.g. "1 - SSIM", "PSNR (dB, higher is better)". */
const char *report_metric_label(report_metric m);
/* Error, lower is better: 1 − SSIM, −PSNR, RMSE, MaxError, SilhouetteError,
 * DepthRMSE, FLIP mean.  NaN when there is no quality or the value is NaN.  PSNR +∞
 * (identical images) is −DBL_MAX: the best error and still finite, so it is
 * on the front. */
double report_metric_error(const dm_quality *q, report_metric m);
/* The shown value (PSNR in dB, may be +∞; others = the error). */
double report_metric_shown(const dm_quality *q, report_metric m);
/* The printf format of the shown value in a table column: fixed decimals,
 * so a column has one precision ("%.4f" for 1 − SSIM, "%.2f" for PSNR dB). */
const char *report_metric_format(report_metric m);
/* Appends the value for a sentence, e.g. "SSIM 0.950", "PSNR 38.2 dB", "RMSE 0.0122". */
void report_metric_text(const dm_quality *q, report_metric m, dm_str *out);

/* Two errors closer than this are the same quality (the recommendation's
 * tie rule, reports/recommend.h): SSIM 0.001, PSNR 0.1 dB, RMSE and depth
 * RMSE 0.0005, max error 0.01, silhouette 0.001, FLIP 0.001. */
double report_metric_epsilon(report_metric m);

/* The run's metric (REPORT_METRIC_KEY in its environment); ssim when absent
 * or unknown (an unknown stored name is logged as a warning). */
report_metric report_metric_of_run(const dm_run_result *run);
/* Records name as the run's metric (replacing any previous one).  0, or
 * DM_ERR_ARG when name is not a metric (the run is unchanged). */
int report_metric_set(dm_run_result *run, const char *name);

#endif
