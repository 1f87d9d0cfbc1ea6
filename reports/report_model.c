/* report_model.c — the report model of one run (report_model.h), derived
 * once with the helpers of report.c, recommend_run.c, breakdown.c and
 * published_report.c; the writers read it and call none of those
 * derivations again. */
#include "reports/report_model.h"
#include "reports/report_internal.h"
#include "reports/recommend_run.h"
#include "reports/published_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

/* The trend of configuration key (NULL when it has fewer than two runs). */
static const report_trend *report_model__trend(const report_trends *t, const char *key)
{
    for (size_t i = 0; t && key && i < t->n; i++)
        if (t->items[i].key && strcmp(t->items[i].key, key) == 0 && t->items[i].n >= 2)
            return &t->items[i];
    return NULL;
}

static int report_model__cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The per-frame median, min and max over the replays of r's camera path,
 * in ms (report_model_row.path_ms); nothing for a still configuration. */
static void report_model__path(report_model_row *r)
{
    const dm_path_series *p = &r->config->path;
    if (!p->frames || !p->replays || !p->frame_ns)
        return;
    r->path_ms = dm_xcalloc(p->frames, sizeof *r->path_ms);
    r->path_lo_ms = dm_xcalloc(p->frames, sizeof *r->path_lo_ms);
    r->path_hi_ms = dm_xcalloc(p->frames, sizeof *r->path_hi_ms);
    double *v = dm_xcalloc(p->replays, sizeof *v);
    for (size_t f = 0; f < p->frames; f++) {
        size_t n = 0;
        for (size_t k = 0; k < p->replays; k++) {
            double t = p->frame_ns[k * p->frames + f];
            if (isfinite(t))
                v[n++] = t / 1e6;
        }
        qsort(v, n, sizeof *v, report_model__cmp);
        r->path_ms[f] = !n ? NAN : n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
        r->path_lo_ms[f] = n ? v[0] : NAN;
        r->path_hi_ms[f] = n ? v[n - 1] : NAN;
    }
    free(v);
}

/* 1 when row r has both figures of the second front. */
static int report_model__in_motion(const report_model_row *r)
{
    const dm_config_result *c = r->config;
    return c->path.frames > 0 && isfinite(c->path.p99) && c->path_quality.present &&
           isfinite(c->path_quality.temporal_mean);
}

/* Scene si's second front (report_model_scene.motion_front) and the
 * steadiest member within its budget; after the rows. */
static void report_model__motion(report_model *m, size_t si)
{
    report_model_scene *sc = &m->scenes[si];
    sc->motion_pick = RECOMMEND_NONE;
    size_t *idx = dm_xcalloc(m->n_rows + 1, sizeof *idx), *front = dm_xcalloc(m->n_rows + 1, sizeof *front);
    recommend_point *p = dm_xcalloc(m->n_rows + 1, sizeof *p);
    size_t n = 0;
    for (size_t i = 0; i < m->n_rows; i++)
        if (m->rows[i].scene == si && report_model__in_motion(&m->rows[i])) {
            const dm_config_result *c = m->rows[i].config;
            p[n] = (recommend_point){.time = c->path.p99, .ci_lo = NAN, .ci_hi = NAN,
                                     .error = c->path_quality.temporal_mean, .family = m->rows[i].family};
            idx[n++] = i;
        }
    sc->n_motion_points = n;
    sc->n_motion_front = n ? recommend_front(p, n, 0, front) : 0;
    sc->motion_front = dm_xcalloc(sc->n_motion_front + 1, sizeof *sc->motion_front);
    for (size_t k = 0; k < sc->n_motion_front; k++) {
        sc->motion_front[k] = idx[front[k]];
        if (p[front[k]].time <= sc->rec.budget)   /* fastest first: the last within is the steadiest */
            sc->motion_pick = idx[front[k]];
    }
    free(p);
    free(front);
    free(idx);
}

/* The corrected figures of a row's frame time, in the raw ones' words. */
static void report_model__row_corrected(report_model_row *r)
{
    const dm_counter_result *t = r->frame_time;
    r->corrected = t && t->corrected;
    if (!r->corrected)
        return;
    dm_counter_result c = *t;   /* the corrected figures where the texts read the raw ones */
    c.median = c.value = t->corr_median;
    c.ci_lo = t->corr_ci_lo;
    c.ci_hi = t->corr_ci_hi;
    dm_str s = {0};
    report__ms_text(c.median, &s);
    r->corr_ms_text = dm_str_take(&s);
    report__ci_text(&c, &s);
    r->corr_ci_text = dm_str_take(&s);
    report__time_ci_text(&c, &s);
    r->corr_time_ci_text = dm_str_take(&s);
}

/* The run's noise floor and drift removal in one sentence (model's
 * precision_text): "" when no configuration has WallTime. */
static void report_model__precision(report_model *m)
{
    const dm_run_result *run = m->run;
    m->noise_floor = m->resolvable = NAN;
    dm_str s = {0};
    size_t used = dm_run_noise_floor(run, &m->noise_floor, &m->resolvable);
    for (size_t i = 0; i < m->n_scenes; i++)
        m->n_corrected_scenes += m->scenes[i].precision && m->scenes[i].precision->corrected;
    if (used)
        dm_str_printf(&s, "Noise floor ±%.1f %% (the median 95 %% CI half-width of WallTime over %zu "
                      "configurations); the smallest difference between two configurations this "
                      "run resolves is %.1f %%, and the answer calls closer ones a tie. The machine's "
                      "drift was removed in %zu of %zu scenes (%s); the raw figures are kept beside "
                      "the corrected ones.", 100 * m->noise_floor, used, 100 * m->resolvable,
                      m->n_corrected_scenes, run->n_precision, REPORT_DRIFT_METHOD);
    m->precision_text = dm_str_take(&s);
}

static void report_model__row(report_model *m, report_model_row *r, const dm_config_result *c)
{
    const dm_run_result *run = m->run;
    dm_str s = {0};
    r->config = c;
    report__config_label(run, c, &s);
    r->label = dm_str_take(&s);
    report_config_label(run, c, &s);
    r->full_label = dm_str_take(&s);
    report_config_name(run, c, &s);
    r->name = dm_str_take(&s);
    r->frame_time = report__frame_time(c);
    if (r->frame_time) {
        report__ms_text(r->frame_time->median, &s);
        r->ms_text = dm_str_take(&s);
        report__ci_text(r->frame_time, &s);
        r->ci_text = dm_str_take(&s);
        report__time_ci_text(r->frame_time, &s);
        r->time_ci_text = dm_str_take(&s);
    }
    dm_str why = {0};
    report__timing_marks(c, 1, &s, &why);
    r->marks = dm_str_take(&s);
    r->why = dm_str_take(&why);
    report__timing_marks(c, 0, &s, &why);
    r->marks_short = dm_str_take(&s);
    dm_str_free(&why);   /* the same reasons again */
    r->noisy = report__noisy(c);
    r->error = c->quality.present ? report_metric_error(&c->quality, m->metric) : NAN;
    r->shown = report_metric_shown(&c->quality, m->metric);
    r->trend = report_model__trend(m->trends, c->key);
    r->nonfinite_pixels = c->quality.present ? c->quality.nonfinite_pixels : 0;
    r->crack_pixels = c->quality.present ? c->quality.crack_pixels : 0;
    r->technique = report__technique(c);
    r->family = report_family(c);
    report_metric_text(&c->quality, m->metric, &s);
    r->metric_text = dm_str_take(&s);
    report__defects(c, &s, &why);
    r->defects = dm_str_take(&s);
    r->defects_why = dm_str_take(&why);
    report_model__row_corrected(r);
}

static void report_model__scene(report_model *m, report_model_scene *sc, const char *name)
{
    const dm_run_result *run = m->run;
    dm_str s = {0};
    sc->name = name;
    report_scene_label(run, name, &s);
    sc->label = dm_str_take(&s);
    sc->n_rows = report__scene_rows(run, name, &sc->rows);
    const char **params;
    size_t np = report__param_names(run, name, &params);
    sc->varying = dm_xcalloc(np + 1, sizeof *sc->varying);
    dm_str same = {0};
    for (size_t i = 0; i < np; i++) {
        if (report__param_varies(run, name, params[i])) {
            sc->varying[sc->n_varying++] = params[i];
            continue;
        }
        const char *v = NULL;   /* one value over the ok rows that have it */
        for (size_t k = 0; k < sc->n_rows && !v; k++) {
            const dm_config_result *c = &run->configs[sc->rows[k]];
            v = dm_kv_get(c->params, c->n_params, params[i]);
        }
        if (v && strcmp(params[i], "technique") != 0)
            dm_str_printf(&same, "%s=%s ", params[i], v);
    }
    sc->same = dm_str_take(&same);
    free(params);
    sc->n_front = report__pareto(run, name, &sc->front);
    report__pareto_text(run, name, &s);
    sc->front_text = dm_str_take(&s);
    sc->untimed = report_untimed_reason(run, name);
    sc->n_points = report_recommend(run, name, &sc->rec);
    for (size_t i = 0; i < sc->n_rows; i++) {
        const dm_config_result *c = &run->configs[sc->rows[i]];
        sc->n_timed += report__frame_time(c) != NULL;
        sc->n_noisy += report__frame_time(c) && report__noisy(c);
    }
    sc->noisy_majority = sc->n_timed >= 2 && 2 * sc->n_noisy > sc->n_timed;
    sc->provisional = sc->noisy_majority || sc->rec.budget_moves;
    sc->n_det = report__counter_names(run, name, REPORT__DETERMINISTIC, &sc->det);
    size_t *timed = dm_xcalloc(sc->n_rows + 1, sizeof *timed), nt = 0;
    for (size_t i = 0; i < sc->n_rows; i++)   /* still fastest first */
        if (report__frame_time(&run->configs[sc->rows[i]]))
            timed[nt++] = sc->rows[i];
    breakdown_choose(run, timed, nt, &sc->breakdown);
    free(timed);
    sc->flip_ppd = NAN;
    for (size_t i = 0; i < sc->n_rows; i++) {
        const dm_config_result *c = &run->configs[sc->rows[i]];
        if (c->quality.present && isfinite(c->quality.max_error))
            sc->max_error = fmax(sc->max_error, c->quality.max_error);
        if (c->img_flip)
            sc->flips = 1, sc->flip_ppd = c->quality.flip_ppd;
        if (c->img_heatmap && report_model_heatmap_is_flip(c))
            sc->heatmap_flip = 1;
        else if (c->img_heatmap)
            sc->heatmap_diff = 1;
    }
    for (size_t i = 0; i < run->n_precision; i++)
        if (run->precision[i].scene && strcmp(run->precision[i].scene, name) == 0)
            sc->precision = &run->precision[i];
    sc->has_rec_corr = report_recommend_corrected(run, name, &sc->rec_corr);
    if (report_answer_disagree(run, name, &s))
        sc->disagree = dm_str_take(&s);
}

int report_model_build(report_model *m, const dm_run_result *run, const report_desc *d)
{
    memset(m, 0, sizeof *m);
    if (!run)
        return DM_ERR_ARG;
    m->run = run;
    m->dir = d ? d->dir : NULL;
    m->trends = d ? d->trends : NULL;
    m->metric = report_metric_of_run(run);
    m->budget_ms = report_budget_ms(run);
    dm_str k = {0};
    report_scene_constants(run, &k);
    m->constants = dm_str_take(&k);
    const char **names;
    m->n_scenes = report__scenes(run, &names);
    m->scenes = dm_xcalloc(m->n_scenes + 1, sizeof *m->scenes);
    for (size_t i = 0; i < m->n_scenes; i++) {
        report_model__scene(m, &m->scenes[i], names[i]);
        m->any_timed |= m->scenes[i].untimed == NULL;
    }
    m->n_rows = run->n_configs;
    m->rows = dm_xcalloc(m->n_rows + 1, sizeof *m->rows);
    for (size_t i = 0; i < m->n_rows; i++) {
        const dm_config_result *c = &run->configs[i];
        report_model__row(m, &m->rows[i], c);
        report_model__path(&m->rows[i]);
        m->n_path_rows += c->path.frames > 0;
        for (size_t k = 0; k < m->n_scenes; k++)
            if (strcmp(c->scene ? c->scene : "", names[k]) == 0)
                m->rows[i].scene = k;
    }
    free(names);
    for (size_t k = 0; k < m->n_scenes; k++)
        for (size_t f = 0; f < m->scenes[k].n_front; f++)
            m->rows[m->scenes[k].front[f]].front = 1;
    for (size_t k = 0; k < m->n_scenes; k++)
        report_model__motion(m, k);
    m->n_params = report__param_names(run, NULL, &m->params);
    m->n_timed = report__counter_names(run, NULL, REPORT__TIMED, &m->timed);
    m->n_det = report__counter_names(run, NULL, REPORT__DETERMINISTIC, &m->det);
    m->fit_units = dm_xcalloc(run->n_fits + 1, sizeof *m->fit_units);
    for (size_t i = 0; i < run->n_fits; i++) {
        const dm_fit_result *f = &run->fits[i];
        m->fit_units[i] = dm_xcalloc(f->n_params + 1, sizeof **m->fit_units);
        for (size_t k = 0; k < f->n_params; k++) {
            dm_str u = {0};
            report__fit_unit(run, f, f->params[k].name, &u);
            m->fit_units[i][k] = dm_str_take(&u);
        }
    }
    m->n_warnings = report__warnings(run, &m->warnings);
    m->n_noisy = report__noisy_configs(run, &m->noisy);
    report_model__precision(m);
    /* published.json, once: the run directory's, or beside the one file written */
    dm_str md = {0}, html = {0};
    if (d && (d->dir || d->path)) {
        char *path = report_published_path(d->dir, d->path);
        report_published_sections(run, path, &md, &html);
        free(path);
    }
    m->published_md = dm_str_take(&md);
    m->published_html = dm_str_take(&html);
    return 0;
}

void report_model_free(report_model *m)
{
    for (size_t i = 0; m->rows && i < m->n_rows; i++) {
        report_model_row *r = &m->rows[i];
        free(r->label);
        free(r->full_label);
        free(r->name);
        free(r->ms_text);
        free(r->ci_text);
        free(r->time_ci_text);
        free(r->marks);
        free(r->marks_short);
        free(r->why);
        free(r->metric_text);
        free(r->defects);
        free(r->defects_why);
        free(r->corr_ms_text);
        free(r->corr_ci_text);
        free(r->corr_time_ci_text);
        free(r->path_ms);
        free(r->path_lo_ms);
        free(r->path_hi_ms);
    }
    free(m->rows);
    for (size_t i = 0; m->scenes && i < m->n_scenes; i++) {
        report_model_scene *sc = &m->scenes[i];
        free(sc->label);
        free(sc->rows);
        free(sc->varying);
        free(sc->same);
        free(sc->front);
        free(sc->front_text);
        free(sc->det);
        breakdown_free(&sc->breakdown);
        free(sc->disagree);
        free(sc->motion_front);
    }
    free(m->scenes);
    free(m->params);
    free(m->timed);
    free(m->det);
    report__warnings_free(m->warnings, m->n_warnings);
    free(m->noisy);
    free(m->constants);
    free(m->published_md);
    free(m->published_html);
    for (size_t i = 0; m->fit_units && i < m->run->n_fits; i++) {
        for (size_t k = 0; k < m->run->fits[i].n_params; k++)
            free(m->fit_units[i][k]);
        free(m->fit_units[i]);
    }
    free(m->fit_units);
    free(m->precision_text);
    memset(m, 0, sizeof *m);
}

int report_model_heatmap_is_flip(const dm_config_result *c)
{
    return c->img_heatmap && c->img_flip && strcmp(c->img_heatmap, c->img_flip) == 0;
}

const report_model_row *report_model_find(const report_model *m, const char *key)
{
    for (size_t i = 0; key && i < m->n_rows; i++)
        if (m->rows[i].config->key && strcmp(m->rows[i].config->key, key) == 0)
            return &m->rows[i];
    return NULL;
}
