/* metric.c — the Pareto front's error metric (see metric.h). */
#include "reports/metric.h"

#include "core/dm_error.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const metric_names[] = {
#define METRIC__NAME(id, name) name,
    REPORT_METRICS(METRIC__NAME)
#undef METRIC__NAME
};

/* Label of the shown value and the word used in sentences, per metric. */
static const char *const metric_labels[REPORT_METRIC_COUNT] = {
    [REPORT_METRIC_SSIM] = "1 - SSIM",
    [REPORT_METRIC_PSNR] = "PSNR (dB, higher is better)",
    [REPORT_METRIC_RMSE] = "RMSE",
    [REPORT_METRIC_MAX_ERROR] = "max error",
    [REPORT_METRIC_SILHOUETTE] = "silhouette error (1 - IoU)",
    [REPORT_METRIC_DEPTH_RMSE] = "depth RMSE",
    [REPORT_METRIC_FLIP] = "FLIP (mean)",
};

double report_metric_epsilon(report_metric m)
{
    static const double eps[REPORT_METRIC_COUNT] = {
        [REPORT_METRIC_SSIM] = 0.001, [REPORT_METRIC_PSNR] = 0.1, [REPORT_METRIC_RMSE] = 0.0005,
        [REPORT_METRIC_MAX_ERROR] = 0.01, [REPORT_METRIC_SILHOUETTE] = 0.001,
        [REPORT_METRIC_DEPTH_RMSE] = 0.0005, [REPORT_METRIC_FLIP] = 0.001};
    return (size_t)m < REPORT_METRIC_COUNT ? eps[m] : eps[0];
}

size_t report_metric_names(const char *const **names)
{
    *names = metric_names;
    return REPORT_METRIC_COUNT;
}

int report_metric_parse(const char *name, report_metric *out)
{
    for (size_t i = 0; name && i < REPORT_METRIC_COUNT; i++)
        if (strcmp(name, metric_names[i]) == 0) {
            *out = (report_metric)i;
            return 0;
        }
    return DM_ERR_ARG;
}

void report_metric_unknown(const char *name, dm_str *err)
{
    dm_str_printf(err, "unknown metric '%s'", name ? name : "(none)");
    dm_str_suggest(err, name, metric_names, REPORT_METRIC_COUNT, "metrics");
}

const char *report_metric_name(report_metric m)
{
    return (size_t)m < REPORT_METRIC_COUNT ? metric_names[m] : metric_names[0];
}

const char *report_metric_label(report_metric m)
{
    return (size_t)m < REPORT_METRIC_COUNT ? metric_labels[m] : metric_labels[0];
}

double report_metric_shown(const dm_quality *q, report_metric m)
{
    if (!q->present)
        return NAN;
    switch (m) {
    case REPORT_METRIC_PSNR: return q->psnr;
    case REPORT_METRIC_RMSE: return q->rmse;
    case REPORT_METRIC_MAX_ERROR: return q->max_error;
    case REPORT_METRIC_SILHOUETTE: return q->silhouette_error;
    case REPORT_METRIC_DEPTH_RMSE: return q->depth_rmse;
    case REPORT_METRIC_FLIP: return q->flip;
    default: return 1.0 - q->ssim;
    }
}

double report_metric_error(const dm_quality *q, report_metric m)
{
    double v = report_metric_shown(q, m);
    if (m != REPORT_METRIC_PSNR)
        return v;
    return isinf(v) && v > 0 ? -DBL_MAX : -v;
}

const char *report_metric_format(report_metric m)
{
    /* PSNR to a hundredth of a dB; max error (a channel's range) to a
     * thousandth; the others are small fractions read to four decimals */
    return m == REPORT_METRIC_PSNR ? "%.2f" : m == REPORT_METRIC_MAX_ERROR ? "%.3f" : "%.4f";
}

void report_metric_text(const dm_quality *q, report_metric m, dm_str *out)
{
    double v = report_metric_shown(q, m);
    if (m == REPORT_METRIC_SSIM)
        dm_str_printf(out, "SSIM %.3f", q->present ? q->ssim : NAN);
    else if (m == REPORT_METRIC_PSNR && isinf(v) && v > 0)
        dm_str_cat(out, "PSNR inf dB (identical)");
    else if (m == REPORT_METRIC_PSNR)
        dm_str_printf(out, "PSNR %.1f dB", v);
    else if (m == REPORT_METRIC_FLIP)
        dm_str_printf(out, "FLIP %.4f", v);
    else
        dm_str_printf(out, "%s %.3g", report_metric_label(m), v);
}

report_metric report_metric_of_run(const dm_run_result *run)
{
    const char *name = dm_kv_get(run->environment, run->n_environment, REPORT_METRIC_KEY);
    report_metric m = REPORT_METRIC_SSIM;
    if (name && report_metric_parse(name, &m) != 0)
        dm_log(DM_LOG_WARN, "run %s: stored %s '%s' is not a metric; using ssim",
               run->id ? run->id : "?", REPORT_METRIC_KEY, name);
    return m;
}

int report_metric_set(dm_run_result *run, const char *name)
{
    report_metric m;
    if (report_metric_parse(name, &m) != 0)
        return DM_ERR_ARG;
    for (size_t i = 0; i < run->n_environment; i++)
        if (strcmp(run->environment[i].key, REPORT_METRIC_KEY) == 0) {
            free(run->environment[i].value);
            run->environment[i].value = dm_xstrdup(name);
            return 0;
        }
    dm_kv_push(&run->environment, &run->n_environment, REPORT_METRIC_KEY, name);
    return 0;
}
