/* report.c — the helpers shared by the report writers (report_internal.h)
 * and the one label of a configuration (report.h); the writers are called
 * by report_write.c, never from here. */
#include "reports/report.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"
#include "core/dm_util.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reports/recommend.h"

/* c's value of param `name` (dm_param_value: an axis left out at its
 * default reads as that default, so a dolly beside a still path varies and
 * its label says so), NULL when it has none. */
static const char *report__param_value(const dm_config_result *c, const char *name)
{
    return dm_param_value(c->params, c->n_params, name);
}

/* 1 when param `name` takes two or more distinct values over the scene's
 * configurations (techniques that do not read it have no value and do not
 * count: a blank cell is not a variation). */
int report__param_varies(const dm_run_result *run, const char *scene, const char *name)
{
    const char *first = NULL;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!c->ok || strcmp(c->scene ? c->scene : "", scene) != 0)
            continue;
        const char *v = report__param_value(c, name);
        if (v && first && strcmp(v, first) != 0)
            return 1;
        if (v)
            first = v;
    }
    return 0;
}

/* 1 when param `name` takes two or more distinct values over all the scene's
 * configurations, failed ones included (so a name does not change when a
 * configuration fails). */
static int report__param_varies_all(const dm_run_result *run, const char *scene, const char *name)
{
    const char *first = NULL;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (strcmp(c->scene ? c->scene : "", scene) != 0)
            continue;
        const char *v = report__param_value(c, name);
        if (v && first && strcmp(v, first) != 0)
            return 1;
        first = v ? v : first;
    }
    return 0;
}

/* A row of a scene's table before sorting: its frame time (+inf when it has
 * none) and its index, which breaks ties so the order is the run's. */
typedef struct report__row {
    double time;
    size_t index;
} report__row;

static int report__by_time(const void *a, const void *b)
{
    const report__row *x = a, *y = b;
    if (x->time != y->time)
        return (x->time > y->time) - (x->time < y->time);
    return (x->index > y->index) - (x->index < y->index);
}

size_t report__scene_rows(const dm_run_result *run, const char *scene, size_t **out)
{
    report__row *rows = dm_xcalloc(run->n_configs + 1, sizeof *rows);
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!c->ok || strcmp(c->scene ? c->scene : "", scene) != 0)
            continue;
        const dm_counter_result *t = report__frame_time(c);
        rows[n++] = (report__row){.time = t ? t->median : INFINITY, .index = i};
    }
    qsort(rows, n, sizeof *rows, report__by_time);
    size_t *idx = dm_xcalloc(n + 1, sizeof *idx);
    for (size_t i = 0; i < n; i++)
        idx[i] = rows[i].index;
    free(rows);
    *out = idx;
    return n;
}

size_t report__pareto_points(const dm_run_result *run, const char *scene, report_metric m,
                             size_t *idx, double *x, double *y)
{
    size_t *rows, nr = report__scene_rows(run, scene, &rows), n = 0;
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        const dm_counter_result *t = report__frame_time(c);
        double e = report_metric_error(&c->quality, m);
        if (!t || !isfinite(e))
            continue;
        x[n] = t->median;
        y[n] = e;
        idx[n++] = rows[i];
    }
    free(rows);
    return n;
}

/* The front with the metric's tolerance (reports/recommend.h): of two
 * configurations of the same quality within it only the cheaper stays. */
size_t report__pareto(const dm_run_result *run, const char *scene, size_t **out)
{
    size_t cap = run->n_configs + 1;
    report_metric m = report_metric_of_run(run);
    double *x = dm_xcalloc(cap, sizeof *x), *y = dm_xcalloc(cap, sizeof *y);
    size_t *idx = dm_xcalloc(cap, sizeof *idx), *front = dm_xcalloc(cap, sizeof *front);
    recommend_point *p = dm_xcalloc(cap, sizeof *p);
    size_t n = report__pareto_points(run, scene, m, idx, x, y);
    for (size_t i = 0; i < n; i++)
        p[i] = (recommend_point){.time = x[i], .error = y[i]};
    size_t nf = recommend_front(p, n, report_metric_epsilon(m), front);
    for (size_t i = 0; i < nf; i++)
        front[i] = idx[front[i]];
    free(p);
    free(x);
    free(y);
    free(idx);
    *out = front;
    return nf;
}

void report__pareto_text(const dm_run_result *run, const char *scene, dm_str *out)
{
    size_t *front, nf = report__pareto(run, scene, &front);
    report_metric m = report_metric_of_run(run);
    if (nf == 0)
        dm_str_printf(out, "no configuration has both a time and a %s measurement",
                      report_metric_label(m));
    for (size_t i = 0; i < nf; i++) {
        const dm_config_result *c = &run->configs[front[i]];
        dm_str_cat(out, i ? "; then " : "");
        report__config_label(run, c, out);
        dm_str_printf(out, " (%.3g ms, ", report__frame_time(c)->median / 1e6);
        report_metric_text(&c->quality, m, out);
        dm_str_cat(out, ")");
    }
    free(front);
}


int report__safe_relpath(const char *p)
{
    return p && *p && p[0] != '/' && !strstr(p, "..");
}

void report__fmt_num(double v, char buf[32])
{
    snprintf(buf, 32, "%1.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, 32, "%1.17g", v);
}

int report__is_canonical_num(const char *s)
{
    char *end, buf[32];
    if (!s || !*s)
        return 0;
    double v = strtod(s, &end);
    if (*end || !isfinite(v))
        return 0;
    report__fmt_num(v, buf);
    return strcmp(buf, s) == 0;
}

const dm_counter_result *report__frame_time(const dm_config_result *c)
{
    const dm_counter_result *t = dm_config_counter(c, "WallTime");
    return t && t->available && t->has_samples ? t : NULL;
}

double report__ci_rel(const dm_counter_result *t)
{
    return t->median > 0 ? (t->ci_hi - t->ci_lo) / 2 / t->median : NAN;
}

/* A percentage with one decimal below 10 %, none above (the CI itself is
 * known to about two digits). */
static void report__pct(dm_str *out, double pct)
{
    dm_str_printf(out, pct < 9.95 ? "%.1f%%" : "%.0f%%", pct);
}

void report__ci_text(const dm_counter_result *t, dm_str *out)
{
    double r = report__ci_rel(t);
    if (!isfinite(r)) {
        dm_str_cat(out, "CI unknown");
        return;
    }
    double down = (t->median - t->ci_lo) / t->median * 100, up = (t->ci_hi - t->median) / t->median * 100;
    if (fmax(down, up) > REPORT__CI_ASYMMETRIC * fmin(down, up) && fabs(up - down) >= 1) {
        dm_str_cat(out, "−");
        report__pct(out, down);
        dm_str_cat(out, "/+");
        report__pct(out, up);
        return;
    }
    dm_str_cat(out, "±");
    report__pct(out, r * 100);
}

void report__ms_text(double ns, dm_str *out)
{
    double ms = ns / 1e6;
    if (!isfinite(ms) || ms <= 0) {
        dm_str_printf(out, "%g", ms);
        return;
    }
    int decimals = 2 - (int)floor(log10(ms) + 1e-12);
    dm_str_printf(out, "%.*f", decimals < 0 ? 0 : decimals > 6 ? 6 : decimals, ms);
}

void report__time_ci_text(const dm_counter_result *t, dm_str *out)
{
    report__ms_text(t->median, out);
    dm_str_cat(out, " ms");
    if (!isfinite(t->ci_lo) || !isfinite(t->ci_hi))
        return;
    dm_str_cat(out, " [");
    report__ms_text(t->ci_lo, out);
    dm_str_cat(out, ", ");
    report__ms_text(t->ci_hi, out);
    dm_str_cat(out, "]");
}

/* Insertion sort of a copy (tens of samples). */
static double *report__sorted_copy(const double *v, size_t n)
{
    double *s = dm_xcalloc(n + 1, sizeof *s);
    for (size_t i = 0; i < n; i++) {
        size_t b = i;
        while (b > 0 && s[b - 1] > v[i]) {
            s[b] = s[b - 1];
            b--;
        }
        s[b] = v[i];
    }
    return s;
}

size_t report__bimodal(const dm_counter_result *t, double *low, double *high)
{
    size_t n = t ? t->n_samples : 0, split = 0;
    if (n < 6)
        return 0;
    double *s = report__sorted_copy(t->samples, n), gap = 0;
    for (size_t i = 1; i < n; i++)
        if (s[i] - s[i - 1] > gap)
            gap = s[i] - s[i - 1], split = i;
    size_t least = n / 5 > 2 ? n / 5 : 2;
    double spread = fmax(s[split - 1] - s[0], s[n - 1] - s[split]);
    int two = split >= least && n - split >= least && gap > 3 * spread &&
              gap > 0.1 * s[n / 2];
    *low = s[(split - 1) / 2];
    *high = s[split + (n - split) / 2];
    free(s);
    return two ? n - split : 0;
}

void report__timing_marks(const dm_config_result *c, int with_ci, dm_str *mark, dm_str *why)
{
    const dm_counter_result *t = report__frame_time(c);
    double lo, hi;
    size_t up = report__bimodal(t, &lo, &hi);
    if (report__noisy(c)) {
        dm_str_cat(mark, with_ci ? "⚠ noisy: " : "⚠ noisy");
        if (with_ci && isfinite(report__ci_rel(t)))
            dm_str_cat(mark, "CI ");
        if (with_ci)
            report__ci_text(t, mark);
        dm_str_printf(why, "the 95%% CI of the median is wider than ±%.0f%% of it (or unknown)",
                      REPORT__NOISY_CI_REL * 100);
    }
    size_t dl;
    const char *drift = report__drift(c, &dl);
    if (drift) {
        dm_str_printf(mark, "%s⚠ drift %+.3g %%", mark->len ? "; " : "",
                      strtod(drift + strlen("WallTime drifted"), NULL));
        dm_str_cat(why, why->len ? "; " : "");
        dm_str_catn(why, drift, dl);
    }
    if (up) {
        dm_str_printf(mark, "%s⚠ bimodal: %zu of %zu samples near ", mark->len ? "; " : "", up,
                      t->n_samples);
        report__ms_text(hi, mark);
        dm_str_cat(mark, " ms, the rest near ");
        report__ms_text(lo, mark);
        dm_str_printf(why, "%sthe samples form two groups: the machine was busy part of the time",
                      why->len ? "; " : "");
    }
}

/* The defects of a configuration's image as one mark ("⚠ 128 crack
 * pixels; ⚠ 3 NaN pixels") and the reasons in words; nothing when the
 * image has none. */
void report__defects(const dm_config_result *c, dm_str *mark, dm_str *why)
{
    const dm_quality *q = &c->quality;
    if (q->present && q->crack_pixels > 0) {
        dm_str_printf(mark, "⚠ %ld crack pixel%s", q->crack_pixels, q->crack_pixels == 1 ? "" : "s");
        dm_str_cat(why, "background shows through the surface inside its silhouette (cracks between "
                        "patches or triangles)");
    }
    if (q->present && q->nonfinite_pixels > 0) {
        dm_str_printf(mark, "%s⚠ %ld NaN pixel%s", mark->len ? "; " : "", q->nonfinite_pixels,
                      q->nonfinite_pixels == 1 ? "" : "s");
        dm_str_printf(why, "%sthe shader wrote NaN or infinite values", why->len ? "; " : "");
    }
}

int report__noisy(const dm_config_result *c)
{
    const dm_counter_result *t = report__frame_time(c);
    return c->ok && t && !(report__ci_rel(t) <= REPORT__NOISY_CI_REL);
}

size_t report__noisy_configs(const dm_run_result *run, size_t **out)
{
    size_t n = 0;
    *out = dm_xcalloc(run->n_configs + 1, sizeof **out);
    for (size_t i = 0; i < run->n_configs; i++)
        if (report__noisy(&run->configs[i]))
            (*out)[n++] = i;
    return n;
}

/* One warning line listing the configurations whose value (by which) is
 * positive. */
static void report__count_warning(const dm_run_result *run, int which, dm_str *out)
{
    static const char *const what[2] = {"non-finite pixels", "crack pixels (background enclosed by the surface)"};
    dm_str list = {0};
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        long v = which ? c->quality.crack_pixels : c->quality.nonfinite_pixels;
        if (!c->ok || !c->quality.present || v <= 0)
            continue;
        dm_str label = {0};
        report_config_label(run, c, &label);
        dm_str_printf(&list, "%s%s (%ld)", n++ ? ", " : "", dm_str_get(&label), v);
        dm_str_free(&label);
    }
    if (n)
        dm_str_printf(out, "%zu configuration%s with %s: %s\n", n, n == 1 ? "" : "s", what[which],
                      dm_str_get(&list));
    dm_str_free(&list);
}

const char *report__drift(const dm_config_result *c, size_t *len)
{
    const char *d = c->log ? strstr(c->log, "WallTime drifted") : NULL;
    if (d && len) {
        const char *nl = strchr(d, '\n');
        *len = nl ? (size_t)(nl - d) : strlen(d);
    }
    return d;
}

/* "N configurations drifted while sampling ...: label (−9.9 %), ..." */
static void report__drift_warning(const dm_run_result *run, dm_str *out)
{
    dm_str list = {0};
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const char *d = c->ok ? report__drift(c, NULL) : NULL;
        if (!d)
            continue;
        dm_str label = {0};
        report_config_label(run, c, &label);
        dm_str_printf(&list, "%s%s (%+.3g %%)", n++ ? ", " : "", dm_str_get(&label),
                      strtod(d + strlen("WallTime drifted"), NULL));
        dm_str_free(&label);
    }
    if (n)
        dm_str_printf(out, "%zu configuration%s drifted while sampling (a trend, not noise: the "
                           "machine's load or clock changed): %s\n", n, n == 1 ? "" : "s", dm_str_get(&list));
    dm_str_free(&list);
}

static int report__has_warning(const dm_run_result *run, const char *w)
{
    for (size_t i = 0; i < run->n_warnings; i++)
        if (run->warnings[i] && strcmp(run->warnings[i], w) == 0)
            return 1;
    return 0;
}

/* The run-level warning when most timed configurations are noisy: the
 * machine was busy, with the load the run recorded and what to do. */
static void report__busy_warning(const dm_run_result *run, size_t noisy, dm_str *out)
{
    size_t timed = 0;
    for (size_t i = 0; i < run->n_configs; i++)
        timed += run->configs[i].ok && report__frame_time(&run->configs[i]) != NULL;
    if (timed < 2 || 2 * noisy <= timed)
        return;
    const char *load = dm_kv_get(run->environment, run->n_environment, "load_average");
    const char *cpus = dm_kv_get(run->environment, run->n_environment, "cpu_count");
    dm_str_printf(out, "The machine was busy: %zu of %zu timings are noisy", noisy, timed);
    if (load)
        dm_str_printf(out, " (load average %.*s at the start%s%s%s)", (int)strcspn(load, " "), load,
                      cpus ? " on " : "", cpus ? cpus : "", cpus ? " CPUs" : "");
    dm_str_cat(out, "; every pick is provisional: run again on a quieter machine, or give the "
                    "samples more time (measure.max_seconds, measure.samples.max).\n");
}

size_t report__warnings(const dm_run_result *run, char ***out)
{
    dm_str all = {0};
    if (run->timer_verdict && strcmp(run->timer_verdict, "partial") == 0)
        dm_str_printf(&all, "GPUTime is partial on this driver: it covers %.1f%% of fenced wall time; "
                            "it is recorded, never used to fit or gate.\n", run->gpu_time_coverage * 100);
    size_t *idx, nn = report__noisy_configs(run, &idx);
    free(idx);
    if (nn)
        dm_str_printf(&all, "%zu noisy configuration%s: the 95%% CI of the median frame time is wider "
                            "than ±%.0f%% of the median (or unknown); compare their times with care.\n",
                      nn, nn == 1 ? "" : "s", REPORT__NOISY_CI_REL * 100);
    report__busy_warning(run, nn, &all);
    report__drift_warning(run, &all);
    report__quality_warnings(run, &all);
    size_t n = 0;
    *out = dm_xcalloc(run->n_warnings + 16, sizeof **out);
    char *save = NULL;
    for (char *l = all.buf ? strtok_r(all.buf, "\n", &save) : NULL; l && n < 15; l = strtok_r(NULL, "\n", &save))
        if (!report__has_warning(run, l))
            (*out)[n++] = dm_xstrdup(l);
    for (size_t i = 0; i < run->n_warnings; i++)
        (*out)[n++] = dm_xstrdup(run->warnings[i] ? run->warnings[i] : "");
    dm_str_free(&all);
    return n;
}

void report__warnings_free(char **w, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(w[i]);
    free(w);
}

void report__quality_warnings(const dm_run_result *run, dm_str *out)
{
    size_t failed = 0;
    for (size_t i = 0; i < run->n_configs; i++)
        failed += !run->configs[i].ok;
    if (failed)
        dm_str_printf(out, "%zu configuration%s failed (see Failed configurations, with the reasons)\n",
                      failed, failed == 1 ? "" : "s");
    report__count_warning(run, 0, out);
    report__count_warning(run, 1, out);
}

/* Appends name to the set (array of borrowed pointers) unless present. */
static void report__add_unique(const char ***set, size_t *n, const char *name)
{
    for (size_t i = 0; i < *n; i++)
        if (strcmp((*set)[i], name) == 0)
            return;
    *set = dm_xrealloc(*set, (*n + 1) * sizeof **set);
    (*set)[(*n)++] = name;
}

size_t report__scenes(const dm_run_result *run, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++)
        report__add_unique(out, &n, run->configs[i].scene ? run->configs[i].scene : "");
    return n;
}

static int report__in_scene(const dm_config_result *c, const char *scene)
{
    return !scene || strcmp(c->scene ? c->scene : "", scene) == 0;
}

size_t report__param_names(const dm_run_result *run, const char *scene, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++)
        if (report__in_scene(&run->configs[i], scene))
            for (size_t k = 0; k < run->configs[i].n_params; k++)
                report__add_unique(out, &n, run->configs[i].params[k].key);
    return n;
}

static int report__counter_kind_matches(const dm_counter_result *c, enum report__counter_kind kind)
{
    if (kind == REPORT__TIMED)
        return !c->deterministic && c->available && c->has_samples;
    return c->deterministic;
}

size_t report__counter_names(const dm_run_result *run, const char *scene,
                             enum report__counter_kind kind, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!report__in_scene(c, scene))
            continue;
        for (size_t k = 0; k < c->n_counters; k++)
            if (report__counter_kind_matches(&c->counters[k], kind))
                report__add_unique(out, &n, c->counters[k].name);
    }
    return n;
}

const char *report__technique(const dm_config_result *c)
{
    const char *t = dm_kv_get(c->params, c->n_params, "technique");
    return t ? t : "?";
}

int report__save(const dm_str *s, const char *path)
{
    return dm_write_file(path, s->buf ? s->buf : "", s->len);
}

void report_trends_free(report_trends *t)
{
    for (size_t i = 0; t && i < t->n; i++) {
        free(t->items[i].key);
        free(t->items[i].median_ns);
    }
    if (t)
        free(t->items);
}

int report__copy_file(const char *from, const char *to, char *err, size_t errlen)
{
    char *text = NULL, *parent = dm_xstrdup(to), *slash = strrchr(parent, '/');
    size_t len = 0;
    char why[256];
    int rc = dm_input_file(from, why, sizeof why);
    if (rc)
        snprintf(err, errlen, "%s: cannot copy: %s", from, why);
    if (slash)
        *slash = 0;
    if (!rc && slash && dm_mkdirs(parent) != 0) {
        snprintf(err, errlen, "%s: cannot create the directory: %s", parent, strerror(errno));
        rc = dm_disk_errno(errno) ? DM_ERR_DISK : DM_ERR_IO;
    }
    if (!rc && dm_read_file(from, &text, &len) != 0) {
        snprintf(err, errlen, "%s: cannot read: %s", from, strerror(errno));
        rc = DM_ERR_IO;
    }
    if (!rc && (rc = dm_write_file(to, text, len)) != 0)
        snprintf(err, errlen, "%s: cannot write: %s", to, strerror(errno));
    free(text);
    free(parent);
    return rc;
}


void report__config_label(const dm_run_result *run, const dm_config_result *c, dm_str *out)
{
    const char *scene = c->scene ? c->scene : "";
    dm_str_cat(out, report__technique(c));
    for (size_t i = 0; i < c->n_params; i++)
        if (strcmp(c->params[i].key, "technique") != 0 &&
            report__param_varies_all(run, scene, c->params[i].key))
            dm_str_printf(out, " %s=%s", c->params[i].key, c->params[i].value);
}

/* 1 when the scene-name piece (",key=value" of the planner's scene id) is
 * in every one of the n scene ids. */
static int report__piece_everywhere(const char *const *all, size_t n, const char *piece, size_t len)
{
    for (size_t i = 0; i < n; i++) {
        const char *p = all[i] ? all[i] : "";
        int found = 0;
        while (!found && (p = strchr(p, ',')) != NULL) {
            p++;
            found = strncmp(p, piece, len) == 0 && (p[len] == ',' || p[len] == 0);
        }
        if (!found)
            return 0;
    }
    return 1;
}

/* Appends the pieces of scene (from its first ',') that are (shared = 1) or
 * are not (0) in every id of all, each after sep. */
static void report__pieces(const char *scene, const char *const *all, size_t n, int shared,
                           const char *sep, dm_str *out)
{
    for (const char *p = strchr(scene, ','); p && *p; p = strchr(p, ',')) {
        p++;
        size_t len = strcspn(p, ",");
        if (report__piece_everywhere(all, n, p, len) == shared) {
            dm_str_cat(out, out->len && shared ? sep : shared ? "" : sep);
            dm_str_catn(out, p, len);
        }
    }
}

void report_scene_label_among(const char *scene, const char *const *all, size_t n, dm_str *out)
{
    const char *at = strchr(scene, '@'), *comma = at ? strchr(at, ',') : NULL;
    if (!at) {
        dm_str_cat(out, scene);
        return;
    }
    dm_str_catn(out, scene, (size_t)(at - scene));
    dm_str_cat(out, " ");
    for (const char *p = at + 1; *p && p != comma; p++)
        dm_str_cat(out, *p == 'x' ? "×" : (char[2]){*p, 0});
    report__pieces(scene, all, n, 0, " ", out);
}

void report_scene_label(const dm_run_result *run, const char *scene, dm_str *out)
{
    const char **all;
    size_t n = report__scenes(run, &all);
    report_scene_label_among(scene, all, n, out);
    free(all);
}

void report_scene_constants(const dm_run_result *run, dm_str *out)
{
    const char **all;
    size_t n = report__scenes(run, &all);
    if (n)
        report__pieces(all[0], all, n, 1, ", ", out);
    free(all);
}

void report_config_label(const dm_run_result *run, const dm_config_result *c, dm_str *out)
{
    report_scene_label(run, c->scene ? c->scene : "", out);
    dm_str_cat(out, " · ");
    report__config_label(run, c, out);
}

/* The name without the uniqueness suffix. */
static void report__base_name(const dm_run_result *run, const dm_config_result *c, dm_str *out)
{
    report_config_label(run, c, out);
}

void report_config_name(const dm_run_result *run, const dm_config_result *c, dm_str *out)
{
    dm_str mine = {0};
    report__base_name(run, c, &mine);
    int clash = 0;
    for (size_t i = 0; i < run->n_configs && !clash; i++) {
        dm_str other = {0};
        if (&run->configs[i] != c) {
            report__base_name(run, &run->configs[i], &other);
            clash = strcmp(dm_str_get(&other), dm_str_get(&mine)) == 0;
        }
        dm_str_free(&other);
    }
    dm_str_cat(out, dm_str_get(&mine));
    if (clash)
        dm_str_printf(out, " [%s]", c->key ? c->key : "?");
    dm_str_free(&mine);
}

int report__tied(const dm_counter_result *a, const dm_counter_result *b)
{
    if (!a || !b || isnan(a->ci_lo) || isnan(a->ci_hi) || isnan(b->ci_lo) || isnan(b->ci_hi))
        return 0;
    return a->ci_lo <= b->ci_hi && b->ci_lo <= a->ci_hi;
}

/* The unit of the response counter: the first unit the run records for it,
 * else "units of <name>". */
static void report__response_unit(const dm_run_result *run, const char *response, dm_str *out)
{
    for (size_t i = 0; response && i < run->n_configs; i++) {
        const dm_counter_result *k = dm_config_counter(&run->configs[i], response);
        if (k && k->unit && *k->unit) {
            dm_str_cat(out, k->unit);
            return;
        }
    }
    dm_str_printf(out, "units of %s", response ? response : "the response");
}

void report__fit_unit(const dm_run_result *run, const dm_fit_result *f, const char *param, dm_str *out)
{
    const char *t = f->formula;
    size_t len = strlen(param);
    while (t && *t) {   /* each term of the sum: "param" or "param*rest" */
        t += strspn(t, " ");
        size_t n = strcspn(t, "+");
        while (n && t[n - 1] == ' ')
            n--;
        if (strncmp(t, param, len) == 0 && (n == len || t[len] == '*') && !memchr(t, '(', n)) {
            report__response_unit(run, f->response, out);
            if (n > len)
                dm_str_printf(out, " per %.*s", (int)(n - len - 1), t + len + 1);
            return;
        }
        t = strchr(t, '+');
        t = t ? t + 1 : NULL;
    }
}
