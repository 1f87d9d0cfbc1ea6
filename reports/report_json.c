/* report_json.c — results.json (docs/exports.md) written and read back with cJSON.
 *
 * Encoding choices (stable; scripts rely on them):
 *  - a NULL string is JSON null; a non-finite double is null (cJSON's rule);
 *  - PSNR of identical images (+infinity) is written as "PSNR": null with
 *    "PSNR_infinite": true (always present, false otherwise);
 *  - a param value that is a canonical number (what the writer would print
 *    for it, e.g. "32", "0.5") is a JSON number, everything else a string;
 *    reading prints numbers back the same way, so write → read → write gives
 *    identical text;
 *  - counters: {unit, deterministic, unavailable} when unavailable,
 *    {unit, deterministic, partial, median, ci95, samples, mean, min, max,
 *    stddev, mad, cv, outliers, nonfinite} with samples, else
 *    {unit, deterministic, partial, value};
 *  - "schema_version" (REPORT_SCHEMA_VERSION) at the top; per configuration a
 *    readable "label" (report_config_name) and "pareto" (on its scene's
 *    front); both are derived, so reading ignores them.  The whole shape is
 *    docs/results.schema.json.
 * Written from the report model (report_model.h: names, front flags,
 * warnings); reading builds a dm_run_result.
 */
#include "reports/report.h"
#include "reports/proxy.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"
#include "core/dm_util.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- writing ------------------------------------------------------------ */

static void report_json__add_str(cJSON *o, const char *name, const char *s)
{
    if (s)
        cJSON_AddStringToObject(o, name, s);
    else
        cJSON_AddNullToObject(o, name);
}

static cJSON *report_json__kv_object(const dm_kv *kv, size_t n, int typed)
{
    cJSON *o = cJSON_CreateObject();
    for (size_t i = 0; i < n; i++) {
        if (typed && report__is_canonical_num(kv[i].value))
            cJSON_AddNumberToObject(o, kv[i].key, strtod(kv[i].value, NULL));
        else
            report_json__add_str(o, kv[i].key, kv[i].value);
    }
    return o;
}

static cJSON *report_json__num_array(const double *v, size_t n)
{
    if (!v)
        return cJSON_CreateNull();
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

static cJSON *report_json__str_array(char *const *v, size_t n)
{
    if (!v && n)
        return cJSON_CreateNull();
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++)
        cJSON_AddItemToArray(a, v[i] ? cJSON_CreateString(v[i]) : cJSON_CreateNull());
    return a;
}

/* The drift-corrected figures of a counter with samples: an object, or
 * null when its scene kept the raw figures only (the run's "precision"
 * says why).  ci95 is the CI within the run (for ties and picks in it);
 * ci95_between_runs the CI for comparing with another run, or null with
 * the reason in between_runs_unavailable. */
static cJSON *report_json__corrected_json(const dm_counter_result *c)
{
    if (!c->corrected)
        return cJSON_CreateNull();
    cJSON *o = cJSON_CreateObject();
    double ci[2] = {c->corr_ci_lo, c->corr_ci_hi}, bci[2] = {c->corr_between_lo, c->corr_between_hi};
    cJSON_AddNumberToObject(o, "median", c->corr_median);
    cJSON_AddItemToObject(o, "ci95", report_json__num_array(ci, 2));
    if (c->corr_between) {
        cJSON_AddItemToObject(o, "ci95_between_runs", report_json__num_array(bci, 2));
    } else {
        cJSON_AddNullToObject(o, "ci95_between_runs");
        cJSON_AddStringToObject(o, "between_runs_unavailable", REPORT_BETWEEN_UNAVAILABLE);
    }
    cJSON_AddStringToObject(o, "method", REPORT_DRIFT_METHOD);
    return o;
}

static cJSON *report_json__counter_json(const dm_counter_result *c)
{
    cJSON *o = cJSON_CreateObject();
    report_json__add_str(o, "unit", c->unit);
    cJSON_AddBoolToObject(o, "deterministic", c->deterministic);
    if (!c->available) {
        report_json__add_str(o, "unavailable", c->unavailable_reason ? c->unavailable_reason : "unavailable");
        return o;
    }
    cJSON_AddBoolToObject(o, "partial", c->partial);
    if (!c->has_samples) {
        cJSON_AddNumberToObject(o, "value", c->value);
        return o;
    }
    double ci[2] = {c->ci_lo, c->ci_hi};
    cJSON_AddNumberToObject(o, "median", c->median);
    cJSON_AddItemToObject(o, "ci95", report_json__num_array(ci, 2));
    cJSON_AddItemToObject(o, "corrected", report_json__corrected_json(c));
    cJSON_AddItemToObject(o, "samples", c->samples ? report_json__num_array(c->samples, c->n_samples)
                                                   : cJSON_CreateArray());
    cJSON_AddNumberToObject(o, "mean", c->mean);
    cJSON_AddNumberToObject(o, "min", c->min);
    cJSON_AddNumberToObject(o, "max", c->max);
    cJSON_AddNumberToObject(o, "stddev", c->stddev);
    cJSON_AddNumberToObject(o, "mad", c->mad);
    cJSON_AddNumberToObject(o, "cv", c->cv);
    cJSON_AddNumberToObject(o, "outliers", c->n_outliers);
    cJSON_AddNumberToObject(o, "nonfinite", c->n_nonfinite);
    return o;
}

static cJSON *report_json__quality_json(const dm_quality *q)
{
    if (!q->present)
        return cJSON_CreateNull();
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "RMSE", q->rmse);
    cJSON_AddNumberToObject(o, "PSNR", q->psnr);   /* non-finite → null */
    cJSON_AddBoolToObject(o, "PSNR_infinite", isinf(q->psnr) && q->psnr > 0);
    cJSON_AddNumberToObject(o, "SSIM", q->ssim);
    cJSON_AddNumberToObject(o, "SilhouetteError", q->silhouette_error);
    cJSON_AddNumberToObject(o, "DepthRMSE", q->depth_rmse);
    cJSON_AddNumberToObject(o, "CrackPixels", (double)q->crack_pixels);
    cJSON_AddNumberToObject(o, "NonFinitePixels", (double)q->nonfinite_pixels);
    cJSON_AddNumberToObject(o, "MaxError", q->max_error);
    cJSON_AddNumberToObject(o, "PctOverThreshold", q->pct_over_threshold);
    cJSON_AddNumberToObject(o, "FLIP", q->flip);   /* NaN (not computed) → null */
    cJSON_AddNumberToObject(o, "FLIPQ1", q->flip_q1);
    cJSON_AddNumberToObject(o, "FLIPMedian", q->flip_median);
    cJSON_AddNumberToObject(o, "FLIPQ3", q->flip_q3);
    cJSON_AddNumberToObject(o, "FLIPMax", q->flip_max);
    cJSON_AddNumberToObject(o, "FLIPPixelsPerDegree", q->flip_ppd);
    report_json__add_str(o, "reference", q->reference);
    return o;
}

/* A configuration's frame times along its camera path (docs/motion.md):
 * the summary in ms and fps, the stutters' frame indices, the noise as
 * true, false or "unknown", and the series as one array per replay (ns). */
static cJSON *report_json__path_json(const dm_path_series *p)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "frames", (double)p->frames);
    cJSON_AddNumberToObject(o, "replays", (double)p->replays);
    cJSON_AddNumberToObject(o, "p50_ms", p->p50 / 1e6);
    cJSON_AddNumberToObject(o, "p95_ms", p->p95 / 1e6);
    cJSON_AddNumberToObject(o, "p99_ms", p->p99 / 1e6);
    cJSON_AddNumberToObject(o, "one_percent_low_ms", p->low1_ns / 1e6);
    cJSON_AddNumberToObject(o, "one_percent_low_fps", p->low1_fps);
    cJSON_AddNumberToObject(o, "stutters", (double)p->n_stutters);
    cJSON *at = cJSON_AddArrayToObject(o, "stutter_frames");
    for (size_t i = 0; i < p->n_stutters; i++)
        cJSON_AddItemToArray(at, cJSON_CreateNumber((double)p->stutter_at[i]));
    cJSON_AddNumberToObject(o, "replay_spread", p->replay_spread);   /* one replay: null */
    if (p->noisy < 0)
        cJSON_AddStringToObject(o, "noisy", "unknown");
    else
        cJSON_AddBoolToObject(o, "noisy", p->noisy);
    cJSON *rows = cJSON_AddArrayToObject(o, "frame_ns");
    for (size_t s = 0; p->frame_ns && s < p->replays; s++)
        cJSON_AddItemToArray(rows, report_json__num_array(p->frame_ns + s * p->frames, p->frames));
    return o;
}

/* Quality along a camera path (dm_path_quality): null when none was asked;
 * "computed": false with the reason when it could not be computed. */
static cJSON *report_json__path_quality_json(const dm_path_quality *pq)
{
    if (!pq->present && !pq->reason)
        return cJSON_CreateNull();
    cJSON *o = cJSON_CreateObject();
    cJSON_AddBoolToObject(o, "computed", pq->present);
    report_json__add_str(o, "reason", pq->reason);
    cJSON_AddNumberToObject(o, "frames", (double)pq->frames);
    cJSON_AddNumberToObject(o, "every", (double)pq->every);
    cJSON *f = cJSON_AddArrayToObject(o, "reference_frames");
    for (size_t i = 0; i < pq->n; i++)
        cJSON_AddItemToArray(f, cJSON_CreateNumber((double)i * (double)pq->every));
    cJSON_AddItemToObject(o, "FLIP", report_json__num_array(pq->flip, pq->n));
    cJSON_AddItemToObject(o, "SSIM", report_json__num_array(pq->ssim, pq->n));
    cJSON_AddNumberToObject(o, "temporal_error_mean", pq->temporal_mean);   /* NaN → null */
    cJSON_AddNumberToObject(o, "temporal_error_p99", pq->temporal_p99);
    cJSON_AddNumberToObject(o, "popping", pq->popping);
    if (pq->popping_frame >= 0)
        cJSON_AddNumberToObject(o, "popping_frame", (double)pq->popping_frame);
    else
        cJSON_AddNullToObject(o, "popping_frame");
    cJSON *im = cJSON_AddObjectToObject(o, "images");
    report_json__add_str(im, "temporal", pq->img_temporal);
    cJSON *fr = cJSON_AddArrayToObject(o, "frames_shown");
    for (size_t i = 0; i < pq->n_shots; i++) {
        const dm_path_shot *sh = &pq->shots[i];
        cJSON *f1 = cJSON_CreateObject();
        cJSON_AddNumberToObject(f1, "frame", (double)sh->frame);
        report_json__add_str(f1, "test", sh->img_test);
        report_json__add_str(f1, "reference", sh->img_ref);
        report_json__add_str(f1, "flip", sh->img_flip);
        cJSON_AddItemToArray(fr, f1);
    }
    return o;
}

static cJSON *report_json__config_json(const report_model_row *row)
{
    const dm_config_result *c = row->config;
    cJSON *o = cJSON_CreateObject();
    report_json__add_str(o, "key", c->key);
    report_json__add_str(o, "label", row->name);
    cJSON_AddBoolToObject(o, "pareto", row->front);
    report_json__add_str(o, "scene", c->scene);
    cJSON_AddItemToObject(o, "params", report_json__kv_object(c->params, c->n_params, 1));
    cJSON_AddStringToObject(o, "status", c->ok ? "ok" : "failed");
    report_json__add_str(o, "reason", c->reason);
    cJSON *ctr = cJSON_AddObjectToObject(o, "counters");
    for (size_t i = 0; i < c->n_counters; i++)
        cJSON_AddItemToObject(ctr, c->counters[i].name, report_json__counter_json(&c->counters[i]));
    cJSON_AddItemToObject(o, "quality", report_json__quality_json(&c->quality));
    cJSON *im = cJSON_AddObjectToObject(o, "images");
    report_json__add_str(im, "render", c->img_render);
    report_json__add_str(im, "heatmap", c->img_heatmap);
    report_json__add_str(im, "reference", c->img_reference);
    report_json__add_str(im, "flip", c->img_flip);
    if (c->path.frames)   /* a still configuration has none */
        cJSON_AddItemToObject(o, "path", report_json__path_json(&c->path));
    cJSON_AddItemToObject(o, "path_quality", report_json__path_quality_json(&c->path_quality));
    report_json__add_str(o, "log", c->log);
    return o;
}

cJSON *report_fit_to_json(const dm_fit_result *f)
{
    cJSON *o = cJSON_CreateObject();
    report_json__add_str(o, "model", f->model);
    report_json__add_str(o, "formula", f->formula);
    report_json__add_str(o, "response", f->response);
    cJSON_AddItemToObject(o, "group", report_json__kv_object(f->group, f->n_group, 1));
    cJSON *p = cJSON_AddObjectToObject(o, "params");
    for (size_t i = 0; i < f->n_params; i++) {
        cJSON *v = cJSON_AddObjectToObject(p, f->params[i].name);
        cJSON_AddNumberToObject(v, "value", f->params[i].value);
        cJSON_AddNumberToObject(v, "stderr", f->params[i].stderr_);
    }
    cJSON_AddNumberToObject(o, "r2", f->r2);
    cJSON_AddNumberToObject(o, "rmse", f->rmse);
    cJSON_AddNumberToObject(o, "mape", f->mape);
    cJSON_AddNumberToObject(o, "cv_mape", f->cv_mape);
    cJSON_AddNumberToObject(o, "n_points", f->n_points);
    cJSON_AddNumberToObject(o, "n_excluded", f->n_excluded);
    report_json__add_str(o, "termination", f->termination);
    cJSON_AddNumberToObject(o, "condition", f->condition);   /* null when infinite */
    cJSON_AddBoolToObject(o, "condition_infinite", isinf(f->condition));
    cJSON_AddItemToObject(o, "warnings", report_json__str_array(f->warnings, f->n_warnings));
    size_t np = f->n_points > 0 ? (size_t)f->n_points : 0;
    cJSON_AddItemToObject(o, "measured", report_json__num_array(f->measured, np));
    cJSON_AddItemToObject(o, "predicted", report_json__num_array(f->predicted, np));
    cJSON_AddItemToObject(o, "point_labels",
                          f->point_labels ? report_json__str_array(f->point_labels, np) : cJSON_CreateNull());
    return o;
}

/* "instructions_proxy" (WallTime ≈ a + b·Instructions, reports/proxy.h)
 * when the run has both counters, and "passes": counter -> its pass. */
static void report_json__proxy_json(cJSON *root, const dm_run_result *r)
{
    report_proxy p;
    if (report_proxy_fit(r, &p) == 0) {
        cJSON *o = cJSON_AddObjectToObject(root, "instructions_proxy");
        cJSON_AddStringToObject(o, "model", "WallTime_ns = a_ns + ns_per_instruction * Instructions");
        cJSON_AddNumberToObject(o, "configurations", (double)p.n);
        cJSON_AddNumberToObject(o, "a_ns", p.a_ns);
        cJSON_AddNumberToObject(o, "ns_per_instruction", p.ns_per_instruction);
        cJSON_AddNumberToObject(o, "r2", isfinite(p.r2) ? p.r2 : 0);
        cJSON *a = cJSON_AddArrayToObject(o, "strays");
        for (size_t i = 0; i < p.n_strays; i++) {
            cJSON *s = cJSON_CreateObject();
            report_json__add_str(s, "key", p.strays[i].key);
            report_json__add_str(s, "configuration", p.strays[i].label);
            cJSON_AddNumberToObject(s, "walltime_ns", p.strays[i].wall_ns);
            cJSON_AddNumberToObject(s, "predicted_ns", p.strays[i].predicted_ns);
            cJSON_AddNumberToObject(s, "residual_rel", p.strays[i].residual_rel);
            cJSON_AddItemToArray(a, s);
        }
    }
    cJSON *passes = cJSON_AddObjectToObject(root, "passes");
    for (size_t i = 0; i < r->n_configs; i++)
        for (size_t k = 0; k < r->configs[i].n_counters; k++) {
            const dm_counter_result *c = &r->configs[i].counters[k];
            if (!cJSON_GetObjectItemCaseSensitive(passes, c->name))
                cJSON_AddStringToObject(passes, c->name, report_proxy_pass(c));
        }
}

/* "precision": the run's noise floor, the method, and per scene whether the
 * drift was removed (or why not), how far the machine moved, what each
 * predictor left, the smallest resolvable difference and where the raw and
 * corrected verdicts disagree. */
static cJSON *report_json__precision_json(const report_model *m)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "noise_floor", m->noise_floor);   /* NaN → null */
    cJSON_AddNumberToObject(o, "resolvable", m->resolvable);
    cJSON_AddStringToObject(o, "method", REPORT_DRIFT_METHOD);
    report_json__add_str(o, "text", m->precision_text);
    cJSON *a = cJSON_AddArrayToObject(o, "scenes");
    for (size_t i = 0; i < m->n_scenes; i++) {
        const report_model_scene *sc = &m->scenes[i];
        const dm_scene_precision *p = sc->precision;
        if (!p)   /* no record (a store from before drift removal): its figures are raw */
            continue;
        cJSON *s = cJSON_CreateObject();
        report_json__add_str(s, "scene", sc->name);
        cJSON_AddBoolToObject(s, "corrected", p->corrected);
        report_json__add_str(s, "reason", p->reason);
        report_json__add_str(s, "predictor", p->predictor);
        cJSON_AddNumberToObject(s, "rounds", p->n_rounds);
        cJSON_AddNumberToObject(s, "machine_spread", p->machine_spread);
        cJSON_AddNumberToObject(s, "raw_noise", p->raw_noise);
        cJSON_AddNumberToObject(s, "loo_noise", p->loo_noise);
        cJSON_AddNumberToObject(s, "calib_noise", p->calib_noise);
        cJSON_AddNumberToObject(s, "resolvable", p->resolvable);
        if (p->between_runs)
            cJSON_AddNumberToObject(s, "reference_spread", p->reference_spread);
        else
            cJSON_AddNullToObject(s, "reference_spread");
        cJSON_AddNumberToObject(s, "half_shift", p->half_shift);   /* NaN → null */
        report_json__add_str(s, "disagreement", sc->disagree);
        cJSON_AddItemToArray(a, s);
    }
    return o;
}

static cJSON *report_json__run_json(const report_model *m)
{
    const dm_run_result *r = m->run;
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "schema_version", REPORT_SCHEMA_VERSION);
    cJSON *run = cJSON_AddObjectToObject(root, "run");
    report_json__add_str(run, "id", r->id);
    report_json__add_str(run, "sweep", r->sweep);
    report_json__add_str(run, "started", r->started);
    report_json__add_str(run, "finished", r->finished);
    report_json__add_str(run, "sweep_hash", r->sweep_hash);
    cJSON_AddItemToObject(run, "environment", report_json__kv_object(r->environment, r->n_environment, 0));
    cJSON *t = cJSON_AddObjectToObject(run, "timer");
    cJSON_AddNumberToObject(t, "gpu_time_coverage", r->gpu_time_coverage);
    report_json__add_str(t, "verdict", r->timer_verdict);
    cJSON *a = cJSON_AddArrayToObject(root, "configs");
    for (size_t i = 0; i < m->n_rows; i++)
        cJSON_AddItemToArray(a, report_json__config_json(&m->rows[i]));
    a = cJSON_AddArrayToObject(root, "left_out");
    for (size_t i = 0; i < r->n_left_out; i++) {
        cJSON *l = cJSON_CreateObject();
        cJSON_AddItemToObject(l, "params",
                              report_json__kv_object(r->left_out[i].params, r->left_out[i].n_params, 1));
        report_json__add_str(l, "reason", r->left_out[i].reason);
        cJSON_AddItemToArray(a, l);
    }
    a = cJSON_AddArrayToObject(root, "fits");
    for (size_t i = 0; i < r->n_fits; i++)
        cJSON_AddItemToArray(a, report_fit_to_json(&r->fits[i]));
    /* the report's list, word for word */
    cJSON_AddItemToObject(root, "warnings", report_json__str_array(m->warnings, m->n_warnings));
    cJSON_AddItemToObject(root, "precision", report_json__precision_json(m));
    report_json__proxy_json(root, r);
    return root;
}

int report_write_cjson(const cJSON *root, const char *path)
{
    char *text = cJSON_Print(root);
    if (!text)
        return DM_ERR_NOMEM;
    dm_str s = {0};
    dm_str_cat(&s, text);
    dm_str_cat(&s, "\n");
    cJSON_free(text);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}

/* Every finite number of the tree as raw text in the fewest of 15..17
 * significant digits that reads back to the same double, bit for bit.
 * cJSON 1.7 keeps its 15-digit text whenever that reads back within
 * DBL_EPSILON of the value, so a ratio could come back one ULP off and a
 * results.json no longer matched the store it was written from (issue 27).
 * Non-finite numbers stay numbers (cJSON writes them as null). */
void report_json_exact_numbers(cJSON *node)
{
    for (; node; node = node->next) {
        report_json_exact_numbers(node->child);
        double v = node->valuedouble;
        if (!cJSON_IsNumber(node) || !isfinite(v))
            continue;
        char buf[40];
        for (int digits = 15; digits <= 17; digits++) {
            snprintf(buf, sizeof buf, "%.*g", digits, v);
            if (strtod(buf, NULL) == v)
                break;
        }
        char *text = cJSON_malloc(strlen(buf) + 1);
        if (!text)
            continue;   /* keeps cJSON's own number text */
        strcpy(text, buf);
        node->type = cJSON_Raw;
        node->valuestring = text;
    }
}

int report__write_json(const report_model *m, const report_desc *d, const char *path)
{
    (void)d;
    cJSON *root = report_json__run_json(m);
    report_json_exact_numbers(root);
    int rc = report_write_cjson(root, path);
    cJSON_Delete(root);
    return rc;
}

/* ---- reading ------------------------------------------------------------ */

static char *report_json__get_str(const cJSON *o, const char *name)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, name);
    return cJSON_IsString(v) ? dm_xstrdup(v->valuestring) : NULL;
}

/* Number, or NaN when null/missing (the writer's encoding of non-finite). */
static double report_json__get_num(const cJSON *o, const char *name)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, name);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static int report_json__get_bool(const cJSON *o, const char *name)
{
    return cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, name));
}

static void report_json__read_kv(const cJSON *o, dm_kv **kv, size_t *n)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, o) {
        char num[32];
        const char *v = NULL;
        if (cJSON_IsNumber(it)) {
            report__fmt_num(it->valuedouble, num);
            v = num;
        } else if (cJSON_IsString(it)) {
            v = it->valuestring;
        } else if (cJSON_IsBool(it)) {
            v = cJSON_IsTrue(it) ? "true" : "false";
        }
        dm_kv_push(kv, n, it->string, v);
    }
}

static double *report_json__read_nums(const cJSON *a, size_t *n)
{
    *n = 0;
    if (!cJSON_IsArray(a))
        return NULL;
    size_t cnt = (size_t)cJSON_GetArraySize(a);
    double *v = dm_xcalloc(cnt ? cnt : 1, sizeof *v);
    const cJSON *it;
    cJSON_ArrayForEach(it, a) v[(*n)++] = cJSON_IsNumber(it) ? it->valuedouble : NAN;
    return v;
}

static char **report_json__read_strs(const cJSON *a, size_t *n)
{
    *n = 0;
    if (!cJSON_IsArray(a))
        return NULL;
    size_t cnt = (size_t)cJSON_GetArraySize(a);
    char **v = dm_xcalloc(cnt ? cnt : 1, sizeof *v);
    const cJSON *it;
    cJSON_ArrayForEach(it, a) v[(*n)++] = cJSON_IsString(it) ? dm_xstrdup(it->valuestring) : NULL;
    return v;
}

/* A count field: NaN, negative or beyond INT_MAX (a damaged file) reads as 0
 * rather than an undefined conversion. */
static int report_json__get_count(const cJSON *o, const char *name)
{
    double v = report_json__get_num(o, name);
    return v >= 0 && v <= INT_MAX ? (int)v : 0;
}

static void report_json__read_counter(const cJSON *o, dm_counter_result *c)
{
    c->name = dm_xstrdup(o->string);
    c->unit = report_json__get_str(o, "unit");
    c->deterministic = report_json__get_bool(o, "deterministic");
    c->unavailable_reason = report_json__get_str(o, "unavailable");
    c->available = c->unavailable_reason == NULL;
    c->partial = report_json__get_bool(o, "partial");
    const cJSON *samples = cJSON_GetObjectItemCaseSensitive(o, "samples");
    if (!cJSON_IsArray(samples)) {
        c->value = report_json__get_num(o, "value");
        return;
    }
    size_t nci;
    double *ci = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "ci95"), &nci);
    c->ci_lo = nci > 0 ? ci[0] : NAN;
    c->ci_hi = nci > 1 ? ci[1] : NAN;
    free(ci);
    c->has_samples = 1;
    c->samples = report_json__read_nums(samples, &c->n_samples);
    c->value = c->median = report_json__get_num(o, "median");
    c->mean = report_json__get_num(o, "mean");
    c->min = report_json__get_num(o, "min");
    c->max = report_json__get_num(o, "max");
    c->stddev = report_json__get_num(o, "stddev");
    c->mad = report_json__get_num(o, "mad");
    c->cv = report_json__get_num(o, "cv");
    c->n_outliers = report_json__get_count(o, "outliers");
    c->n_nonfinite = report_json__get_count(o, "nonfinite");
    const cJSON *corr = cJSON_GetObjectItemCaseSensitive(o, "corrected");
    if (cJSON_IsObject(corr)) {   /* the drift-corrected figures, when written */
        double *cci = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(corr, "ci95"), &nci);
        c->corr_median = report_json__get_num(corr, "median");
        c->corr_ci_lo = nci > 0 ? cci[0] : NAN;
        c->corr_ci_hi = nci > 1 ? cci[1] : NAN;
        c->corrected = isfinite(c->corr_median) && nci == 2;
        free(cci);
        double *bci = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(corr, "ci95_between_runs"), &nci);
        c->corr_between = c->corrected && nci == 2 && isfinite(bci[0]) && isfinite(bci[1]);
        c->corr_between_lo = c->corr_between ? bci[0] : 0;
        c->corr_between_hi = c->corr_between ? bci[1] : 0;
        free(bci);
    }
}

static void report_json__read_quality(const cJSON *o, dm_quality *q)
{
    if (!cJSON_IsObject(o))
        return;
    q->present = 1;
    q->rmse = report_json__get_num(o, "RMSE");
    q->psnr = report_json__get_bool(o, "PSNR_infinite") ? INFINITY : report_json__get_num(o, "PSNR");
    q->ssim = report_json__get_num(o, "SSIM");
    q->silhouette_error = report_json__get_num(o, "SilhouetteError");
    q->depth_rmse = report_json__get_num(o, "DepthRMSE");
    q->crack_pixels = report_json__get_count(o, "CrackPixels");
    q->nonfinite_pixels = report_json__get_count(o, "NonFinitePixels");
    q->max_error = report_json__get_num(o, "MaxError");
    q->pct_over_threshold = report_json__get_num(o, "PctOverThreshold");
    q->flip = report_json__get_num(o, "FLIP");
    q->flip_q1 = report_json__get_num(o, "FLIPQ1");
    q->flip_median = report_json__get_num(o, "FLIPMedian");
    q->flip_q3 = report_json__get_num(o, "FLIPQ3");
    q->flip_max = report_json__get_num(o, "FLIPMax");
    q->flip_ppd = report_json__get_num(o, "FLIPPixelsPerDegree");
    q->reference = report_json__get_str(o, "reference");
}

/* The ns a figure written in ms stood for: the double whose ms the writer
 * prints as the same text (x / 1e6 of x = ms * 1e6 can be one ulp off). */
static double report_json__ns_of_ms(double ms)
{
    double ns = ms * 1e6;
    for (int i = 0; i < 4 && isfinite(ns) && ns / 1e6 != ms; i++)
        ns = nextafter(ns, ns / 1e6 < ms ? INFINITY : -INFINITY);
    return ns;
}

/* "path" of a configuration (report_json__path_json), when written; its
 * shape was checked (report_json__shape_path). */
static void report_json__read_path(const cJSON *o, dm_path_series *p)
{
    if (!cJSON_IsObject(o))
        return;
    p->frames = (size_t)report_json__get_count(o, "frames");
    p->replays = (size_t)report_json__get_count(o, "replays");
    p->frame_ns = dm_xcalloc(p->frames * p->replays + 1, sizeof *p->frame_ns);
    const cJSON *row;
    size_t s = 0, n;
    cJSON_ArrayForEach(row, cJSON_GetObjectItemCaseSensitive(o, "frame_ns")) {
        double *v = report_json__read_nums(row, &n);
        memcpy(p->frame_ns + s++ * p->frames, v, n * sizeof *v);
        free(v);
    }
    p->p50 = report_json__ns_of_ms(report_json__get_num(o, "p50_ms"));
    p->p95 = report_json__ns_of_ms(report_json__get_num(o, "p95_ms"));
    p->p99 = report_json__ns_of_ms(report_json__get_num(o, "p99_ms"));
    p->low1_ns = report_json__ns_of_ms(report_json__get_num(o, "one_percent_low_ms"));
    p->low1_fps = report_json__get_num(o, "one_percent_low_fps");
    p->replay_spread = report_json__get_num(o, "replay_spread");
    const cJSON *noisy = cJSON_GetObjectItemCaseSensitive(o, "noisy");
    p->noisy = cJSON_IsBool(noisy) ? cJSON_IsTrue(noisy) : -1;
    size_t na = 0;
    double *at = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "stutter_frames"), &na);
    p->stutter_at = dm_xcalloc(na + 1, sizeof *p->stutter_at);
    for (size_t i = 0; i < na; i++)
        p->stutter_at[i] = (long)at[i];
    p->n_stutters = na;
    free(at);
}

static void report_json__read_path_quality(const cJSON *o, dm_path_quality *pq)
{
    if (!cJSON_IsObject(o))
        return;                  /* null or missing: none asked (or a run from before paths) */
    pq->present = report_json__get_bool(o, "computed");
    pq->reason = report_json__get_str(o, "reason");
    pq->frames = (long)report_json__get_count(o, "frames");
    pq->every = (long)report_json__get_count(o, "every");
    size_t ns = 0;
    pq->flip = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "FLIP"), &pq->n);
    pq->ssim = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "SSIM"), &ns);
    if (ns < pq->n)              /* a damaged record: keep the shorter series */
        pq->n = ns;
    pq->temporal_mean = report_json__get_num(o, "temporal_error_mean");
    pq->temporal_p99 = report_json__get_num(o, "temporal_error_p99");
    pq->popping = report_json__get_num(o, "popping");
    double at = report_json__get_num(o, "popping_frame");
    pq->popping_frame = isfinite(at) ? (long)at : -1;
    pq->img_temporal = report_json__get_str(cJSON_GetObjectItemCaseSensitive(o, "images"), "temporal");
    const cJSON *f1;   /* frames_shown: absent in a run from before the filmstrip */
    cJSON_ArrayForEach(f1, cJSON_GetObjectItemCaseSensitive(o, "frames_shown")) {
        if (!cJSON_IsObject(f1))
            continue;
        dm_path_shot *sh = dm_vec_push(&pq->shots, &pq->n_shots, NULL, sizeof *pq->shots);
        sh->frame = (long)report_json__get_count(f1, "frame");
        sh->img_test = report_json__get_str(f1, "test");
        sh->img_ref = report_json__get_str(f1, "reference");
        sh->img_flip = report_json__get_str(f1, "flip");
    }
}

static void report_json__read_config(const cJSON *o, dm_config_result *c)
{
    c->key = report_json__get_str(o, "key");
    c->scene = report_json__get_str(o, "scene");
    report_json__read_kv(cJSON_GetObjectItemCaseSensitive(o, "params"), &c->params, &c->n_params);
    const cJSON *st = cJSON_GetObjectItemCaseSensitive(o, "status");
    c->ok = cJSON_IsString(st) && strcmp(st->valuestring, "ok") == 0;
    c->reason = report_json__get_str(o, "reason");
    c->log = report_json__get_str(o, "log");
    const cJSON *ctr = cJSON_GetObjectItemCaseSensitive(o, "counters");
    size_t n = (size_t)cJSON_GetArraySize(ctr);
    c->counters = dm_xcalloc(n ? n : 1, sizeof *c->counters);
    const cJSON *it;
    cJSON_ArrayForEach(it, ctr) {
        report_json__read_counter(it, &c->counters[c->n_counters]);
        dm_counter_read_check(&c->counters[c->n_counters++], "results.json");
    }
    report_json__read_quality(cJSON_GetObjectItemCaseSensitive(o, "quality"), &c->quality);
    const cJSON *im = cJSON_GetObjectItemCaseSensitive(o, "images");
    c->img_render = report_json__get_str(im, "render");
    c->img_heatmap = report_json__get_str(im, "heatmap");
    c->img_reference = report_json__get_str(im, "reference");
    c->img_flip = report_json__get_str(im, "flip");
    report_json__read_path(cJSON_GetObjectItemCaseSensitive(o, "path"), &c->path);
    report_json__read_path_quality(cJSON_GetObjectItemCaseSensitive(o, "path_quality"), &c->path_quality);
}

static void report_json__read_fit(const cJSON *o, dm_fit_result *f)
{
    f->model = report_json__get_str(o, "model");
    f->formula = report_json__get_str(o, "formula");
    f->response = report_json__get_str(o, "response");
    report_json__read_kv(cJSON_GetObjectItemCaseSensitive(o, "group"), &f->group, &f->n_group);
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(o, "params"), *it;
    size_t n = (size_t)cJSON_GetArraySize(p);
    f->params = dm_xcalloc(n ? n : 1, sizeof *f->params);
    cJSON_ArrayForEach(it, p) {
        dm_fit_param *fp = &f->params[f->n_params++];
        fp->name = dm_xstrdup(it->string);
        fp->value = report_json__get_num(it, "value");
        fp->stderr_ = report_json__get_num(it, "stderr");
    }
    f->r2 = report_json__get_num(o, "r2");
    f->rmse = report_json__get_num(o, "rmse");
    f->mape = report_json__get_num(o, "mape");
    f->cv_mape = report_json__get_num(o, "cv_mape");
    f->n_points = report_json__get_count(o, "n_points");
    f->n_excluded = report_json__get_count(o, "n_excluded");
    f->termination = report_json__get_str(o, "termination");
    f->condition = report_json__get_bool(o, "condition_infinite") ? INFINITY
                 : cJSON_HasObjectItem(o, "condition") ? report_json__get_num(o, "condition") : 0.0;
    f->warnings = report_json__read_strs(cJSON_GetObjectItemCaseSensitive(o, "warnings"), &f->n_warnings);
    size_t nm, np, nl;
    f->measured = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "measured"), &nm);
    f->predicted = report_json__read_nums(cJSON_GetObjectItemCaseSensitive(o, "predicted"), &np);
    f->point_labels = report_json__read_strs(cJSON_GetObjectItemCaseSensitive(o, "point_labels"), &nl);
}

/* The scenes' drift records of "precision" (report_json__precision_json), when written. */
static void report_json__read_precision(const cJSON *o, dm_run_result *r)
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, "scenes"), *it;
    if (!cJSON_IsArray(a))
        return;
    r->precision = dm_xcalloc((size_t)cJSON_GetArraySize(a) + 1, sizeof *r->precision);
    cJSON_ArrayForEach(it, a) {
        dm_scene_precision *p = &r->precision[r->n_precision++];
        p->scene = report_json__get_str(it, "scene");
        p->corrected = report_json__get_bool(it, "corrected");
        p->reason = report_json__get_str(it, "reason");
        p->predictor = report_json__get_str(it, "predictor");
        p->n_rounds = report_json__get_count(it, "rounds");
        p->machine_spread = report_json__get_num(it, "machine_spread");
        p->raw_noise = report_json__get_num(it, "raw_noise");
        p->loo_noise = report_json__get_num(it, "loo_noise");
        p->calib_noise = report_json__get_num(it, "calib_noise");
        p->resolvable = report_json__get_num(it, "resolvable");
        p->reference_spread = report_json__get_num(it, "reference_spread");
        p->between_runs = isfinite(p->reference_spread);
        p->half_shift = report_json__get_num(it, "half_shift");
    }
}

static void report_json__read_run(const cJSON *root, dm_run_result *r)
{
    const cJSON *run = cJSON_GetObjectItemCaseSensitive(root, "run"), *it;
    r->id = report_json__get_str(run, "id");
    r->sweep = report_json__get_str(run, "sweep");
    r->started = report_json__get_str(run, "started");
    r->finished = report_json__get_str(run, "finished");
    r->sweep_hash = report_json__get_str(run, "sweep_hash");
    report_json__read_kv(cJSON_GetObjectItemCaseSensitive(run, "environment"), &r->environment,
                         &r->n_environment);
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(run, "timer");
    r->gpu_time_coverage = report_json__get_num(t, "gpu_time_coverage");
    r->timer_verdict = report_json__get_str(t, "verdict");
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(root, "configs");
    r->configs = dm_xcalloc((size_t)cJSON_GetArraySize(a) + 1, sizeof *r->configs);
    cJSON_ArrayForEach(it, a) report_json__read_config(it, &r->configs[r->n_configs++]);
    report_json__read_precision(cJSON_GetObjectItemCaseSensitive(root, "precision"), r);
    a = cJSON_GetObjectItemCaseSensitive(root, "left_out");
    r->left_out = dm_xcalloc((size_t)cJSON_GetArraySize(a) + 1, sizeof *r->left_out);
    cJSON_ArrayForEach(it, a) {
        dm_left_out *l = &r->left_out[r->n_left_out++];
        report_json__read_kv(cJSON_GetObjectItemCaseSensitive(it, "params"), &l->params, &l->n_params);
        l->reason = report_json__get_str(it, "reason");
    }
    a = cJSON_GetObjectItemCaseSensitive(root, "fits");
    r->fits = dm_xcalloc((size_t)cJSON_GetArraySize(a) + 1, sizeof *r->fits);
    cJSON_ArrayForEach(it, a) report_json__read_fit(it, &r->fits[r->n_fits++]);
    r->warnings = report_json__read_strs(cJSON_GetObjectItemCaseSensitive(root, "warnings"), &r->n_warnings);
}

/* 1 when field name of o is absent, null or of the type is_type checks. */
static int shape__field_ok(const cJSON *o, const char *name, cJSON_bool (*is_type)(const cJSON *))
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, name);
    return !v || cJSON_IsNull(v) || is_type(v);
}

/* The types of one configuration's counters (an object of objects with
 * number or null statistics and an array of numbers as samples), so a
 * hand-edited file with "median": "fast" is refused rather than read as NaN. */
static const char *shape__counters(const cJSON *cfg)
{
    static const char *const nums[] = { "value", "median", "mean", "min", "max", "stddev",
                                        "mad", "cv", "outliers" };
    const cJSON *ctr = cJSON_GetObjectItemCaseSensitive(cfg, "counters"), *k, *x;
    if (ctr && !cJSON_IsObject(ctr))
        return "a config's \"counters\" is not an object";
    cJSON_ArrayForEach(k, ctr) {
        if (!cJSON_IsObject(k))
            return "a counter is not an object";
        for (size_t i = 0; i < sizeof nums / sizeof *nums; i++)
            if (!shape__field_ok(k, nums[i], cJSON_IsNumber))
                return "a counter statistic is not a number";
        if (!shape__field_ok(k, "samples", cJSON_IsArray) || !shape__field_ok(k, "unit", cJSON_IsString))
            return "a counter's \"samples\" is not an array or its \"unit\" not a string";
        cJSON_ArrayForEach(x, cJSON_GetObjectItemCaseSensitive(k, "samples"))
            if (!cJSON_IsNumber(x) && !cJSON_IsNull(x))
                return "a counter sample is not a number";
    }
    return NULL;
}

/* A configuration's "path", when present: frames >= 2 and replays >= 1
 * (whole numbers), "frame_ns" one array of `frames` numbers or nulls per
 * replay, "stutter_frames" indices below frames, the figures numbers or
 * null, so the reader never reads a series short or past its end. */
static const char *report_json__shape_path(const cJSON *cfg)
{
    static const char *const nums[] = { "p50_ms", "p95_ms", "p99_ms", "one_percent_low_ms",
                                        "one_percent_low_fps", "stutters", "replay_spread" };
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(cfg, "path"), *x, *row;
    if (!p || cJSON_IsNull(p))
        return NULL;
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(p, "frames"), *r = cJSON_GetObjectItemCaseSensitive(p, "replays");
    if (!cJSON_IsObject(p) || !cJSON_IsNumber(f) || !cJSON_IsNumber(r) || f->valuedouble < 2 ||
        f->valuedouble > 1e6 || r->valuedouble < 1 || r->valuedouble > 1e6 ||
        f->valuedouble != floor(f->valuedouble) || r->valuedouble != floor(r->valuedouble))
        return "a config's \"path\" needs whole numbers \"frames\" (2 or more) and \"replays\" (1 or more)";
    for (size_t i = 0; i < sizeof nums / sizeof *nums; i++)
        if (!shape__field_ok(p, nums[i], cJSON_IsNumber))
            return "a path figure is not a number";
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(p, "frame_ns");
    if (!cJSON_IsArray(rows) || cJSON_GetArraySize(rows) != (int)r->valuedouble)
        return "a path's \"frame_ns\" is not one array per replay";
    cJSON_ArrayForEach(row, rows) {
        if (!cJSON_IsArray(row) || cJSON_GetArraySize(row) != (int)f->valuedouble)
            return "a path's \"frame_ns\" row does not hold one time per frame";
        cJSON_ArrayForEach(x, row)
            if (!cJSON_IsNumber(x) && !cJSON_IsNull(x))
                return "a path frame time is not a number";
    }
    const cJSON *at = cJSON_GetObjectItemCaseSensitive(p, "stutter_frames");
    if (at && !cJSON_IsArray(at))
        return "a path's \"stutter_frames\" is not an array";
    cJSON_ArrayForEach(x, at)
        if (!cJSON_IsNumber(x) || x->valuedouble < 0 || x->valuedouble >= f->valuedouble)
            return "a path's stutter frame is not a frame index of the path";
    return NULL;
}

/* Checks the skeleton the reader relies on; names the first missing part. */
static const char *report_json__shape_error(const cJSON *root)
{
    if (!cJSON_IsObject(root))
        return "top level is not an object";
    if (!cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(root, "run")))
        return "\"run\" object missing";
    const cJSON *c = cJSON_GetObjectItemCaseSensitive(root, "configs"), *it;
    if (!cJSON_IsArray(c))
        return "\"configs\" array missing";
    cJSON_ArrayForEach(it, c)
        if (!cJSON_IsObject(it) || !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(it, "key")))
            return "a config without a \"key\" string";
    cJSON_ArrayForEach(it, c)
        if (shape__counters(it))
            return shape__counters(it);
    cJSON_ArrayForEach(it, c)
        if (report_json__shape_path(it))
            return report_json__shape_path(it);
    return NULL;
}

int report_read_json(const char *path, dm_run_result *out, char *err, size_t errlen)
{
    char *text = NULL;
    size_t len = 0;
    if (!path || !out)
        return DM_ERR_ARG;
    char reason[256];
    int rc = dm_input_file(path, reason, sizeof reason);   /* never read a FIFO or /dev/zero */
    if (rc) {
        snprintf(err, errlen, "%s: cannot read: %s", path, reason);
        return rc == DM_ERR_ARG ? rc : DM_ERR_IO;
    }
    if (dm_read_file(path, &text, &len)) {
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        return DM_ERR_IO;
    }
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    const char *why = root ? report_json__shape_error(root) : "malformed JSON";
    if (why) {
        snprintf(err, errlen, "%s: %s (near byte %ld)", path, why,
                 root ? 0L : (long)((end ? end : text) - text));
        cJSON_Delete(root);
        free(text);
        return DM_ERR_PARSE;
    }
    memset(out, 0, sizeof *out);
    report_json__read_run(root, out);
    cJSON_Delete(root);
    free(text);
    return 0;
}
