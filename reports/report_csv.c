/* report_csv.c — results.csv: one row per configuration (RFC 4180),
 * written from the report model alone (report_model.h).
 *
 * Columns: key, scene, status, reason, every param (union over configs, in
 * first-appearance order), for each timing counter <name>_median_ms,
 * <name>_ci_lo_ms, <name>_ci_hi_ms, each deterministic counter by name, then
 * the quality metrics (PSNR_dB), then label (report_config_name) and pareto
 * (1 on its scene's front, else 0), the frame time with the drift removed;
 * in a run with configurations on a camera path (only), last the path's
 * figures (docs/motion.md): path_p50_ms, path_p95_ms, path_p99_ms,
 * path_one_percent_low_ms, path_one_percent_low_fps, path_stutters, then
 * its quality along the path: path_temporal_error_mean,
 * path_temporal_error_p99, path_popping, path_popping_frame; empty
 * for a still configuration.  Units are in the names: _ms for times,
 * _dB; counters count items or bytes (their names say which; `dmbench list
 * counters` gives every unit).  An unavailable or absent value is an empty
 * field, never 0.  Records end with CRLF; fields with , " CR or LF are
 * quoted (RFC 4180; `dmbench fit --data` reads it back).
 */
#include "reports/report.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *quality_cols[] = {"RMSE", "PSNR_dB", "SSIM", "MaxError", "SilhouetteError",
                                     "DepthRMSE", "CrackPixels", "NonFinitePixels", "FLIP",
                                     "FLIPMedian", "FLIPMax"};
#define N_QUALITY (sizeof quality_cols / sizeof quality_cols[0])

static void report_csv__field(dm_str *s, const char *text, int first)
{
    if (!first)
        dm_str_cat(s, ",");
    if (!text)
        return;
    if (!strpbrk(text, ",\"\r\n")) {
        dm_str_cat(s, text);
        return;
    }
    dm_str_cat(s, "\"");
    for (const char *p = text; *p; p++)
        dm_str_catn(s, *p == '"' ? "\"\"" : p, *p == '"' ? 2 : 1);
    dm_str_cat(s, "\"");
}

static void report_csv__num_field(dm_str *s, double v, int present)
{
    char buf[32];
    if (!present || isnan(v)) {
        report_csv__field(s, NULL, 0);
        return;
    }
    if (isinf(v))
        snprintf(buf, sizeof buf, "%s", v > 0 ? "inf" : "-inf");
    else
        snprintf(buf, sizeof buf, "%.9g", v);
    report_csv__field(s, buf, 0);
}

static void report_csv__quality_fields(dm_str *s, const dm_quality *q)
{
    double v[N_QUALITY] = {q->rmse, q->psnr, q->ssim, q->max_error, q->silhouette_error,
                           q->depth_rmse, (double)q->crack_pixels, (double)q->nonfinite_pixels,
                           q->flip, q->flip_median, q->flip_max};
    for (size_t i = 0; i < N_QUALITY; i++)
        report_csv__num_field(s, v[i], q->present);
}

/* The frame time with the machine's drift removed (empty when its scene kept
 * the raw figures) and how: the method, or why the figures are raw only
 * (the scene's reason). */
static void report_csv__corrected_fields(dm_str *s, const report_model *m, const report_model_row *r)
{
    const dm_counter_result *t = r->frame_time;
    report_csv__num_field(s, r->corrected ? t->corr_median / 1e6 : 0, r->corrected);
    report_csv__num_field(s, r->corrected ? t->corr_ci_lo / 1e6 : 0, r->corrected);
    report_csv__num_field(s, r->corrected ? t->corr_ci_hi / 1e6 : 0, r->corrected);
    const dm_scene_precision *p = m->n_scenes ? m->scenes[r->scene].precision : NULL;
    const char *raw = !p ? "no drift record for its scene; raw figures only"
                      : p->reason ? p->reason : "raw figures only";
    report_csv__field(s, r->corrected ? REPORT_DRIFT_METHOD : t ? raw : NULL, 0);
}

static const char *const report_csv__path_cols[] = {DM_RESULT_PATH_COLUMNS};
#define REPORT_CSV__N_PATH (sizeof report_csv__path_cols / sizeof report_csv__path_cols[0])
#define REPORT_CSV__N_PATH_TIMES 6   /* the first six: the frame times' */

/* The path figures of a configuration (report_csv__path_cols): its frame
 * times, empty for a still one, then its quality along the path, empty
 * where none was computed (and a NaN figure empty, as everywhere). */
static void report_csv__path_fields(dm_str *s, const dm_path_series *p, const dm_path_quality *q)
{
    double v[REPORT_CSV__N_PATH] = {p->p50 / 1e6, p->p95 / 1e6, p->p99 / 1e6, p->low1_ns / 1e6,
                                    p->low1_fps, (double)p->n_stutters, q->temporal_mean, q->temporal_p99,
                                    q->popping, (double)q->popping_frame};
    for (size_t i = 0; i < REPORT_CSV__N_PATH; i++) {
        int set = i < REPORT_CSV__N_PATH_TIMES ? p->frames > 0
                                               : q->present && (i + 1 < REPORT_CSV__N_PATH || q->popping_frame >= 0);
        report_csv__num_field(s, v[i], set);
    }
}

static void report_csv__row(dm_str *s, const report_model *m, const report_model_row *r, const char **params,
                            size_t np, const char **timed, size_t nt, const char **det, size_t nd)
{
    const dm_config_result *c = r->config;
    report_csv__field(s, c->key, 1);
    report_csv__field(s, c->scene, 0);
    report_csv__field(s, c->ok ? "ok" : "failed", 0);
    report_csv__field(s, c->reason, 0);
    for (size_t i = 0; i < np; i++)
        report_csv__field(s, dm_kv_get(c->params, c->n_params, params[i]), 0);
    for (size_t i = 0; i < nt; i++) {
        const dm_counter_result *t = dm_config_counter(c, timed[i]);
        int ok = t && t->available && t->has_samples;
        report_csv__num_field(s, ok ? t->median / 1e6 : 0, ok);
        report_csv__num_field(s, ok ? t->ci_lo / 1e6 : 0, ok);
        report_csv__num_field(s, ok ? t->ci_hi / 1e6 : 0, ok);
    }
    for (size_t i = 0; i < nd; i++) {
        const dm_counter_result *d = dm_config_counter(c, det[i]);
        report_csv__num_field(s, d ? d->value : 0, d && d->available);
    }
    report_csv__quality_fields(s, &c->quality);
    report_csv__field(s, r->name, 0);
    report_csv__field(s, r->front ? "1" : "0", 0);
    report_csv__corrected_fields(s, m, r);
    if (m->n_path_rows)
        report_csv__path_fields(s, &c->path, &c->path_quality);
    dm_str_cat(s, "\r\n");
}

static void report_csv__header(dm_str *s, const char **params, size_t np, const char **timed, size_t nt,
                               const char **det, size_t nd, int paths)
{
    static const char *lead[] = {DM_RESULT_LEAD_COLUMNS}, *trail[] = {DM_RESULT_TRAIL_COLUMNS};
    for (size_t i = 0; i < sizeof lead / sizeof lead[0]; i++)
        report_csv__field(s, lead[i], i == 0);
    for (size_t i = 0; i < np; i++)
        report_csv__field(s, params[i], 0);
    for (size_t i = 0; i < nt; i++) {
        static const char *suffix[] = {"_median_ms", "_ci_lo_ms", "_ci_hi_ms"};
        for (int k = 0; k < 3; k++) {
            char *name = dm_xasprintf("%s%s", timed[i], suffix[k]);
            report_csv__field(s, name, 0);
            free(name);
        }
    }
    for (size_t i = 0; i < nd; i++)
        report_csv__field(s, det[i], 0);
    for (size_t i = 0; i < N_QUALITY; i++)
        report_csv__field(s, quality_cols[i], 0);
    for (size_t i = 0; i < sizeof trail / sizeof trail[0]; i++)
        report_csv__field(s, trail[i], 0);
    for (size_t i = 0; paths && i < REPORT_CSV__N_PATH; i++)
        report_csv__field(s, report_csv__path_cols[i], 0);
    dm_str_cat(s, "\r\n");
}

int report__write_csv(const report_model *m, const report_desc *d, const char *path)
{
    (void)d;
    dm_str s = {0};
    report_csv__header(&s, m->params, m->n_params, m->timed, m->n_timed, m->det, m->n_det, m->n_path_rows > 0);
    for (size_t i = 0; i < m->n_rows; i++)
        report_csv__row(&s, m, &m->rows[i], m->params, m->n_params, m->timed, m->n_timed, m->det, m->n_det);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
