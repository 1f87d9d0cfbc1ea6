/* export.c — gbench, bmf, gab-smaller and gab-bigger reporters (export.h),
 * reading the report model's rows (names, frame times) and the run's
 * environment and counters through it. */
#include "reports/export.h"
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/report_model.h"

#include "core/dm_error.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void export__num(cJSON *o, const char *name, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, name, v);
}

/* One configuration as an exporter sees it: its result, its time, its name
 * (report_config_name) and its index among the timed configurations. */
typedef struct export__config {
    const dm_config_result *c;
    const dm_counter_result *t;
    const char *name;
    size_t index;
    int bigger;   /* github-action-benchmark: the bigger-is-better list */
} export__config;

/* Adds what a format writes for one configuration to out. */
typedef void (*export__add_fn)(cJSON *out, const export__config *e);

/* Calls add for each configuration of run that has a time, in run order
 * (the others are left out of every format). */
static void export__each(const report_model *m, cJSON *out, int bigger, export__add_fn add)
{
    size_t index = 0;
    for (size_t i = 0; i < m->n_rows; i++) {
        const report_model_row *r = &m->rows[i];
        if (!r->config->ok || !r->frame_time)   /* the timed WallTime of an ok configuration */
            continue;
        export__config e = { r->config, r->frame_time, r->name, index++, bigger };
        add(out, &e);
    }
}

/* ---- Google Benchmark ---------------------------------------------------- */

static cJSON *export__gbench_context(const dm_run_result *run)
{
    cJSON *ctx = cJSON_CreateObject();
    const char *cpus = dm_kv_get(run->environment, run->n_environment, "cpu_count");
    const char *load = dm_kv_get(run->environment, run->n_environment, "load_average");
    cJSON_AddStringToObject(ctx, "date", run->started ? run->started : "");
    cJSON_AddStringToObject(ctx, "executable", "dmbench");
    cJSON_AddStringToObject(ctx, "dmbench_run", run->id ? run->id : "");
    cJSON_AddStringToObject(ctx, "dmbench_sweep", run->sweep ? run->sweep : "");
    cJSON_AddNumberToObject(ctx, "num_cpus", cpus ? atoi(cpus) : 0);
    cJSON_AddNumberToObject(ctx, "mhz_per_cpu", 0);
    cJSON_AddBoolToObject(ctx, "cpu_scaling_enabled", 0);
    cJSON *la = cJSON_AddArrayToObject(ctx, "load_avg");
    for (const char *p = load; p && *p;) {
        char *end;
        double v = strtod(p, &end);
        if (end == p)
            break;
        cJSON_AddItemToArray(la, cJSON_CreateNumber(v));
        p = end;
    }
    cJSON_AddStringToObject(ctx, "library_build_type", "release");
    return ctx;
}

/* Deterministic counters and the quality metrics as user counters. */
static void export__user_counters(cJSON *o, const dm_config_result *c)
{
    for (size_t i = 0; i < c->n_counters; i++) {
        const dm_counter_result *k = &c->counters[i];
        if (k->deterministic && k->available && !k->has_samples)
            export__num(o, k->name, k->value);
    }
    if (c->quality.present) {
        export__num(o, "SSIM", c->quality.ssim);
        export__num(o, "PSNR_dB", c->quality.psnr);
        export__num(o, "RMSE", c->quality.rmse);
        export__num(o, "FLIP", c->quality.flip);   /* absent when not computed */
    }
}

/* One benchmark of the "benchmarks" list. */
static void export__gbench_add(cJSON *list, const export__config *e)
{
    const dm_config_result *c = e->c;
    const dm_counter_result *t = e->t, *cpu = dm_config_counter(c, "CPUTime");
    cJSON *b = cJSON_CreateObject();
    cJSON_AddStringToObject(b, "name", e->name);
    cJSON_AddNumberToObject(b, "family_index", (double)e->index);
    cJSON_AddNumberToObject(b, "per_family_instance_index", 0);
    cJSON_AddStringToObject(b, "run_name", e->name);
    cJSON_AddStringToObject(b, "run_type", "iteration");
    cJSON_AddNumberToObject(b, "repetitions", 1);
    cJSON_AddNumberToObject(b, "repetition_index", 0);
    cJSON_AddNumberToObject(b, "threads", 1);
    cJSON_AddNumberToObject(b, "iterations", (double)t->n_samples);
    cJSON_AddNumberToObject(b, "real_time", t->median);
    cJSON_AddNumberToObject(b, "cpu_time", cpu && cpu->available && cpu->has_samples &&
                            isfinite(cpu->median) ? cpu->median : t->median);
    cJSON_AddStringToObject(b, "time_unit", "ns");
    cJSON_AddStringToObject(b, "label", c->key ? c->key : "");
    export__user_counters(b, c);
    cJSON_AddItemToArray(list, b);
}

static cJSON *export__gbench(const report_model *m)
{
    const dm_run_result *run = m->run;
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "context", export__gbench_context(run));
    export__each(m, cJSON_AddArrayToObject(root, "benchmarks"), 0, export__gbench_add);
    return root;
}

/* ---- Bencher Metric Format --------------------------------------------- */

/* "SamplesPassed" -> "samples-passed", "VSInvocations" -> "vs-invocations"
 * (Bencher measure slugs: a word starts at a capital after a small letter or
 * digit, or at the last capital of a run followed by a small letter). */
static char *export__kebab(const char *name)
{
    dm_str s = {0};
    for (const char *p = name; *p; p++) {
        int up = isupper((unsigned char)*p), prev_up = p != name && isupper((unsigned char)p[-1]);
        if (up && p != name && (!prev_up || islower((unsigned char)p[1])))
            dm_str_cat(&s, "-");
        char ch = (char)tolower((unsigned char)*p);
        dm_str_catn(&s, &ch, 1);
    }
    char *out = dm_xstrdup(dm_str_get(&s));
    dm_str_free(&s);
    return out;
}

static void export__bmf_value(cJSON *o, const char *measure, double v)
{
    if (!isfinite(v))
        return;
    cJSON *m = cJSON_AddObjectToObject(o, measure);
    cJSON_AddNumberToObject(m, "value", v);
}

/* One benchmark: latency, quality and the deterministic counters. */
static void export__bmf_add(cJSON *root, const export__config *e)
{
    const dm_config_result *c = e->c;
    cJSON *b = cJSON_AddObjectToObject(root, e->name);
    cJSON *lat = cJSON_AddObjectToObject(b, "latency");
    cJSON_AddNumberToObject(lat, "value", e->t->median);
    export__num(lat, "lower_value", e->t->ci_lo);
    export__num(lat, "upper_value", e->t->ci_hi);
    if (c->quality.present) {
        export__bmf_value(b, "ssim", c->quality.ssim);
        export__bmf_value(b, "psnr-db", c->quality.psnr);
        export__bmf_value(b, "flip", c->quality.flip);
    }
    for (size_t k = 0; k < c->n_counters; k++) {
        const dm_counter_result *d = &c->counters[k];
        if (!d->deterministic || !d->available || d->has_samples)
            continue;
        char *slug = export__kebab(d->name);
        export__bmf_value(b, slug, d->value);
        free(slug);
    }
}

static cJSON *export__bmf(const report_model *m)
{
    cJSON *root = cJSON_CreateObject();
    export__each(m, root, 0, export__bmf_add);
    return root;
}

/* ---- github-action-benchmark ------------------------------------------- */

/* One entry; suffix (NULL for the time) is appended as " (SUFFIX)". */
static void export__gab_entry(cJSON *list, const char *name, const char *suffix,
                              const char *unit, double value, const char *range, const char *extra)
{
    if (!isfinite(value))
        return;
    cJSON *e = cJSON_CreateObject();
    char *n = suffix ? dm_xasprintf("%s (%s)", name, suffix) : dm_xstrdup(name);
    cJSON_AddStringToObject(e, "name", n);
    cJSON_AddStringToObject(e, "unit", unit);
    cJSON_AddNumberToObject(e, "value", value);
    if (range)
        cJSON_AddStringToObject(e, "range", range);
    cJSON_AddStringToObject(e, "extra", extra);
    cJSON_AddItemToArray(list, e);
    free(n);
}

/* The entries of one configuration: its time and RMSE (smaller is better)
 * or its SSIM and PSNR (bigger is better). */
static void export__gab_add(cJSON *list, const export__config *e)
{
    const dm_counter_result *t = e->t;
    const dm_quality *q = &e->c->quality;
    char *extra = dm_xasprintf("key %s; median of %zu samples; 95%% CI [%.6g, %.6g] ms", e->c->key,
                               t->n_samples, t->ci_lo / 1e6, t->ci_hi / 1e6);
    char *range = dm_xasprintf("± %.4g", (t->ci_hi - t->ci_lo) / 2e6);
    if (!e->bigger) {
        export__gab_entry(list, e->name, NULL, "ms", t->median / 1e6,
                          isfinite(t->ci_hi - t->ci_lo) ? range : NULL, extra);
        if (q->present)
            export__gab_entry(list, e->name, "RMSE", "RMSE", q->rmse, NULL, extra);
        if (q->present && isfinite(q->flip))        /* FLIP: smaller is better */
            export__gab_entry(list, e->name, "FLIP", "FLIP", q->flip, NULL, extra);
    } else if (q->present) {
        export__gab_entry(list, e->name, "SSIM", "SSIM", q->ssim, NULL, extra);
        export__gab_entry(list, e->name, "PSNR", "dB", q->psnr, NULL, extra);
    }
    free(extra);
    free(range);
}

static cJSON *export__gab(const report_model *m, int bigger)
{
    cJSON *list = cJSON_CreateArray();
    export__each(m, list, bigger, export__gab_add);
    return list;
}

static cJSON *export__gab_smaller(const report_model *m) { return export__gab(m, 0); }
static cJSON *export__gab_bigger(const report_model *m) { return export__gab(m, 1); }

/* ---- the table --------------------------------------------------------- */

static const export_format formats[] = {
    { "gbench", "Google Benchmark JSON (compare.py from libbenchmark-tools)", export__gbench },
    { "bmf", "Bencher Metric Format JSON", export__bmf },
    { "gab-smaller", "github-action-benchmark customSmallerIsBetter (time ms, RMSE, FLIP)", export__gab_smaller },
    { "gab-bigger", "github-action-benchmark customBiggerIsBetter (SSIM, PSNR dB)", export__gab_bigger },
};

const export_format *export_formats(size_t *n)
{
    *n = sizeof formats / sizeof *formats;
    return formats;
}

const export_format *export_find(const char *name)
{
    for (size_t i = 0; name && i < sizeof formats / sizeof *formats; i++)
        if (strcmp(formats[i].name, name) == 0)
            return &formats[i];
    return NULL;
}

int export_write(const report_model *m, const export_format *f, const char *path)
{
    cJSON *root = f->build(m);
    report_json_exact_numbers(root);
    int rc = 0;
    if (path && strcmp(path, "-") != 0) {
        rc = report_write_cjson(root, path);
    } else {
        char *text = cJSON_Print(root);
        rc = !text ? DM_ERR_NOMEM : (printf("%s\n", text) < 0 || fflush(stdout) != 0) ? DM_ERR_IO : 0;
        cJSON_free(text);
    }
    cJSON_Delete(root);
    return rc;
}
