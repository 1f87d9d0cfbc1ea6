/* predict.c — per-variant costs fitted to measured runs, applied to the
 * invocation counts of configurations never measured (predict.h). */
#include "run/predict.h"
#include "core/dm_error.h"
#include "run/fitting.h"
#include "reports/report.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const predict_counts[PREDICT_N_COUNTS] = {"VSInvocations", "TESInvocations",
                                                      "ClippingOutputPrimitives", "FSInvocations", "TCSPatches",
                                                      "SamplesPassed", "LoopTrips",
                                                      "ClippingInputPrimitives", "TessWalkCalls", "FragmentGroups"};
const char *const predict_needed[PREDICT_N_NEEDED] = {"Instructions", "VSInvocations", "TESInvocations",
                                                      "ClippingOutputPrimitives", "FSInvocations"};
static const char *const predict__stages[3] = {"GeometryInstructions", "RasterInstructions",
                                               "FragmentInstructions"};
/* each stage counter's own model (models/catalog.c); fragment shading
 * from the SIMD groups and the search loop's trips when the runs counted
 * both, else from the trips when they counted those (predict__stage_model) */
static const char *const predict__stage_models[3] = {"geometry-instructions", "raster-instructions",
                                                     "fragment-instructions"};

/* The model of stage st for runs u: fragment shading is priced by
 * fragment-groups when u has FragmentGroups and LoopTrips (per SIMD group
 * run, as llvmpipe runs the shader, not per block a triangle touches:
 * docs/models.md, "Fragment groups"), by fragment-trips when it has
 * LoopTrips only. */
static const char *predict__stage_model(const dm_run_result *u, int st)
{
    if (st != 2 || !dm_run_has_counter(u, "LoopTrips"))
        return predict__stage_models[st];
    return dm_run_has_counter(u, "FragmentGroups") ? "fragment-groups" : "fragment-trips";
}

/* each stage's time from its instructions (models/catalog.c) */
static const char *const predict__time_models[3] = {"geometry-time", "raster-time", "fragment-time"};

const char *const predict_way_names[PREDICT_N_WAYS] = {"stage times", "time-from-stages",
                                                       "time-from-instructions"};

const char *predict_run_missing(const dm_run_result *run)
{
    for (size_t i = 0; i < PREDICT_N_NEEDED; i++)
        if (!dm_run_has_counter(run, predict_needed[i]))
            return predict_needed[i];
    return NULL;
}

size_t predict_left_out(const dm_run_result *runs, size_t n, dm_str *out)
{
    size_t left = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t i = 0; i < runs[k].n_configs; i++) {
            const dm_config_result *c = &runs[k].configs[i];
            for (size_t j = 0; c->ok && j < PREDICT_N_NEEDED + 3; j++) {
                const char *name = j < PREDICT_N_NEEDED ? predict_needed[j] : predict__stages[j - PREDICT_N_NEEDED];
                const dm_counter_result *r = dm_config_counter(c, name);
                if (r && !r->available && dm_run_has_counter(&runs[k], name)) {
                    dm_str label = {0};
                    report_config_label(&runs[k], c, &label);   /* the one label form */
                    dm_str_printf(out, "  %s  %s: %s unavailable (%s)\n", c->key, dm_str_get(&label), name,
                                  r->unavailable_reason ? r->unavailable_reason : "no reason recorded");
                    dm_str_free(&label);
                    left++;
                    break;
                }
            }
        }
    return left;
}

static void predict__fit(const dm_run_result *u, const char *model, const char *response,
                         const char *const *group_by, size_t n_group_by, dm_fit_result **fits, size_t *n)
{
    /* relative error: one sweep's frames span orders of magnitude, and an
     * absolute fit lets its largest decide the smallest's costs */
    fitting_spec spec = { .name = model, .response = response, .group_by = group_by, .n_group_by = n_group_by,
                          .relative = 1 };
    dm_str warn = {0}, err = {0};
    fitting_run(&spec, u, fits, n, &warn, &err);
    dm_str_free(&warn);
    dm_str_free(&err);
}

const dm_fit_result *predict_fit_of(const dm_fit_result *fits, size_t n, const char *variant)
{
    for (size_t i = 0; i < n; i++)
        if (fits[i].n_group == 1 && strcmp(fits[i].group[0].value, variant) == 0)
            return &fits[i];
    return NULL;
}

/* fit's held-out prediction of the configuration `key`, NaN when it has none. */
static double predict__cv_of(const dm_fit_result *fit, const char *key)
{
    for (int i = 0; fit && fit->point_labels && fit->cv_predicted && i < fit->n_points; i++)
        if (strcmp(fit->point_labels[i], key) == 0)
            return fit->cv_predicted[i];
    return NAN;
}

/* The held-out predictions of f[0], f[1] and f[2] of each configuration
 * f[0] was fitted to, summed, against its `counter`: their CV-MAPE; each
 * ln(sum / measured) appended to logs (n_logs) when logs. */
static predict_heldout predict__sum_heldout(const dm_fit_result *const f[3], const dm_run_result *train,
                                            const char *counter, const char *variant, double **logs,
                                            size_t *n_logs)
{
    double ape = 0;
    int n = 0;
    for (int k = 0; f[0]->point_labels && f[1] && f[2] && k < f[0]->n_points; k++) {
        const char *key = f[0]->point_labels[k];
        double sum = predict__cv_of(f[0], key) + predict__cv_of(f[1], key) + predict__cv_of(f[2], key);
        const dm_config_result *c = dm_run_config(train, key);
        const dm_counter_result *r = c ? dm_config_counter(c, counter) : NULL;
        if (isfinite(sum) && sum > 0 && r && r->available && r->value > 0) {
            ape += fabs(sum - r->value) / r->value;
            n++;
            if (logs) {
                double e = log(sum / r->value);
                DM_VEC_PUSH(*logs, *n_logs, e);
            }
        }
    }
    return (predict_heldout){ dm_xstrdup(variant), n ? 100 * ape / n : NAN, n };
}

/* Per variant: the stage models' held-out predictions of each measured
 * configuration, summed, against its Instructions (predict_heldout); over
 * all variants, the PREDICT_COVERAGE bound of their errors (m->instr_q). */
static void predict__heldout(predict_model *m)
{
    double *logs = NULL;
    size_t n_logs = 0;
    for (size_t i = 0; i < m->n_stage[0]; i++) {
        const dm_fit_result *g = &m->stage[0][i];
        if (g->n_group != 1 || !g->point_labels)
            continue;
        const dm_fit_result *f[3] = {g, predict_fit_of(m->stage[1], m->n_stage[1], g->group[0].value),
                                     predict_fit_of(m->stage[2], m->n_stage[2], g->group[0].value)};
        predict_heldout h = predict__sum_heldout(f, &m->train, "Instructions", g->group[0].value, &logs, &n_logs);
        DM_VEC_PUSH(m->heldout, m->n_heldout, h);
    }
    m->instr_q = stats_bound90(logs, n_logs, NULL);
    free(logs);
}

const predict_heldout *predict_heldout_of(const predict_model *m, const char *variant)
{
    for (size_t i = 0; i < m->n_heldout; i++)
        if (strcmp(m->heldout[i].variant, variant) == 0)
            return &m->heldout[i];
    return NULL;
}

int predict_heldout_prefers_one(const predict_model *m, const dm_fit_result *one)
{
    const predict_heldout *h = one && one->n_group == 1 ? predict_heldout_of(m, one->group[0].value) : NULL;
    return h && h->n >= 3 && isfinite(h->cv_mape) && isfinite(one->cv_mape) && one->cv_mape < h->cv_mape;
}

int predict_way_usable(const predict_model *m, predict_way way)
{
    const predict_way_score *w = &m->way[way];
    return !w->why && isfinite(w->cv_mape) && w->cv_mape <= PREDICT_MAX_HELDOUT;
}

/* Scores held-out predictions pred[i] of measured meas[i] (i < n; pairs
 * not both positive and finite are skipped): their MAPE and the
 * PREDICT_COVERAGE bound of |ln(pred / meas)| (stats_bound90). */
static void predict__score(const double *pred, const double *meas, size_t n, predict_way_score *w)
{
    double *e = dm_xcalloc(n + 1, sizeof *e), ape = 0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(pred[i]) && pred[i] > 0 && isfinite(meas[i]) && meas[i] > 0) {
            ape += fabs(pred[i] - meas[i]) / meas[i];
            e[k++] = log(pred[i] / meas[i]);
        }
    w->n = (int)k;
    w->cv_mape = k ? 100 * ape / (double)k : NAN;
    w->q = stats_bound90(e, k, &w->q_how);
    free(e);
}

/* The PREDICT_COVERAGE bound of a one-formula fit's own k-fold held-out
 * errors (log); NaN with fewer than PREDICT_MIN_HELDOUT. */
static double predict__fit_bound(const dm_fit_result *f)
{
    predict_way_score w = {0};
    predict__score(f->cv_predicted, f->measured, f->cv_predicted ? (size_t)f->n_points : 0, &w);
    return w.q;
}

/* A one-formula time fit's score: its own k-fold held-out predictions. */
static void predict__score_fit(const dm_fit_result *f, predict_way_score *w)
{
    predict__score(f->cv_predicted, f->measured, f->cv_predicted ? (size_t)f->n_points : 0, w);
}

/* The part of fit's prediction for configuration c (whose counters hold
 * every variable) beyond its constant `a`; NaN when it predicts none. */
static double predict__variable_part(const dm_fit_result *fit, const dm_run_result *train, dm_config_result *c)
{
    dm_run_result one = { .configs = c, .n_configs = 1 };
    double v = NAN;
    dm_str why = {0};
    int rc = fitting_predict_dropped(fit, train, c->params, c->n_params, c->key, &one, 1, &v, &why);
    dm_str_free(&why);
    const dm_fit_param *a = dm_fit_param_find(fit, "a");
    return rc == 0 ? v - (a ? a->value : 0) : NAN;
}

/* The stage times' one fixed cost over the configurations of u with the
 * three stage-time fits ts: the frame's time less the fits' variable
 * parts, least squares of relative error (weights 1/WallTime^2); never
 * below 0.  NaN when no configuration has them all. */
static double predict__shared_a(const dm_fit_result *const ts[3], const dm_run_result *u)
{
    double sw = 0, sr = 0;
    for (size_t i = 0; i < u->n_configs; i++) {
        dm_config_result *c = &u->configs[i];
        const dm_counter_result *w = c->ok ? dm_config_counter(c, "WallTime") : NULL;
        double var = 0;
        for (int s = 0; s < 3 && w; s++)
            var += predict__variable_part(ts[s], u, c);
        if (w && w->available && w->value > 0 && isfinite(var)) {
            sw += 1 / (w->value * w->value);
            sr += (w->value - var) / (w->value * w->value);
        }
    }
    return sw > 0 ? fmax(0, sr / sw) : NAN;
}

/* Fits the three stage-time models to u (fits[s], one each, else 0). */
static int predict__fit_stage_times(const dm_run_result *u, dm_fit_result *fits[3], size_t n[3])
{
    int all = 1;
    for (int st = 0; st < 3; st++) {
        fits[st] = NULL;
        n[st] = 0;
        predict__fit(u, predict__time_models[st], NULL, NULL, 0, &fits[st], &n[st]);
        all = all && n[st] == 1;
    }
    return all;
}

/* The stage times' held-out predictions: k-fold over the configurations
 * that have the timed passes, each fold's frames predicted by the three
 * stage-time fits and the shared fixed cost of the other folds. */
static void predict__score_stage_times(const predict_model *m, predict_way_score *w)
{
    const dm_run_result *u = &m->train;
    size_t n = u->n_configs, k = n < 5 ? n : 5;
    double *pred = dm_xcalloc(n + 1, sizeof *pred), *meas = dm_xcalloc(n + 1, sizeof *meas);
    dm_run_result sub = *u;
    sub.configs = dm_xcalloc(n + 1, sizeof *sub.configs);
    for (size_t i = 0; i < n; i++) {
        const dm_counter_result *r = u->configs[i].ok ? dm_config_counter(&u->configs[i], "WallTime") : NULL;
        pred[i] = NAN;
        meas[i] = r && r->available ? r->value : NAN;
    }
    for (size_t fold = 0; fold < k; fold++) {
        sub.n_configs = 0;
        for (size_t i = 0; i < n; i++)
            if (i % k != fold)
                sub.configs[sub.n_configs++] = u->configs[i];
        dm_fit_result *ts[3];
        size_t nts[3];
        if (predict__fit_stage_times(&sub, ts, nts)) {
            const dm_fit_result *f[3] = {ts[0], ts[1], ts[2]};
            double a = predict__shared_a(f, &sub);
            for (size_t i = fold; i < n; i += k) {
                double v = a;
                for (int s = 0; s < 3; s++)
                    v += predict__variable_part(ts[s], &sub, &u->configs[i]);
                pred[i] = v;
            }
        }
        for (int s = 0; s < 3; s++) {
            for (size_t j = 0; j < nts[s]; j++)
                dm_fit_result_free(&ts[s][j]);
            free(ts[s]);
        }
    }
    predict__score(pred, meas, n, w);
    free(sub.configs);
    free(pred);
    free(meas);
}

/* Scores every way of predicting WallTime the runs allow and chooses the
 * one of the lowest held-out error (m->way_used). */
static void predict__choose_way(predict_model *m)
{
    const dm_run_result *u = &m->train;
    int stage_counters = m->n_stage[0] && m->n_stage[1] && m->n_stage[2];
    for (int w = 0; w < PREDICT_N_WAYS; w++)
        m->way[w] = (predict_way_score){ .cv_mape = NAN, .q = NAN };
    if (!dm_run_has_counter(u, "WallTime"))
        for (int w = 0; w < PREDICT_N_WAYS; w++)
            m->way[w].why = dm_xstrdup("the runs have no WallTime (add it to measure.counters)");
    else {
        if (!stage_counters)
            m->way[PREDICT_WAY_STAGE_TIMES].why = dm_xstrdup("the runs lack the stage counters "
                "(GeometryInstructions, RasterInstructions, FragmentInstructions)");
        else if (!dm_run_has_counter(u, "GeometryTime") || !dm_run_has_counter(u, "MinimalShadingTime"))
            m->way[PREDICT_WAY_STAGE_TIMES].why = dm_xstrdup("the runs lack GeometryTime or "
                                                             "MinimalShadingTime: add both to measure.counters");
        else if (!(m->n_time_stage[0] == 1 && m->n_time_stage[1] == 1 && m->n_time_stage[2] == 1))
            m->way[PREDICT_WAY_STAGE_TIMES].why = dm_xstrdup("too few configurations to fit the stage-time models");
        else
            predict__score_stage_times(m, &m->way[PREDICT_WAY_STAGE_TIMES]);
        if (m->n_time_st == 1)
            predict__score_fit(&m->time_st[0], &m->way[PREDICT_WAY_TIME_FROM_STAGES]);
        else
            m->way[PREDICT_WAY_TIME_FROM_STAGES].why = dm_xstrdup(stage_counters
                ? "too few configurations to fit time-from-stages" : "needs the stage counters too");
        if (m->n_time == 1)
            predict__score_fit(&m->time[0], &m->way[PREDICT_WAY_TIME_FROM_INSTRUCTIONS]);
        else
            m->way[PREDICT_WAY_TIME_FROM_INSTRUCTIONS].why =
                dm_xstrdup("too few configurations to fit time-from-instructions");
    }
    m->way_used = -1;
    for (int w = 0; w < PREDICT_N_WAYS; w++)
        if (predict_way_usable(m, (predict_way)w) &&
            (m->way_used < 0 || m->way[w].cv_mape < m->way[m->way_used].cv_mape))
            m->way_used = w;
}

/* Fits every model to m->train (its configurations m's own array, freed
 * by predict_free); the intervals' calibration is left to predict_fit. */
static void predict__fit_core(predict_model *m)
{
    const dm_run_result *u = &m->train;
    m->between.q = log1p(PREDICT_RUN_SPREAD);
    predict__fit(u, "stage-instructions", "Instructions", NULL, 0, &m->instr, &m->n_instr);
    for (int st = 0; st < 3; st++)
        if (dm_run_has_counter(u, predict__stages[st]) && dm_run_has_counter(u, "SamplesPassed"))
            predict__fit(u, predict__stage_model(u, st),
                         predict__stages[st], NULL, 0, &m->stage[st], &m->n_stage[st]);
    predict__heldout(m);
    if (dm_run_has_counter(u, "WallTime"))
        predict__fit(u, "time-from-instructions", "WallTime", NULL, 0, &m->time, &m->n_time);
    if (dm_run_has_counter(u, "WallTime") && m->n_stage[0] && m->n_stage[1] && m->n_stage[2])
        predict__fit(u, "time-from-stages", "WallTime", NULL, 0, &m->time_st, &m->n_time_st);
    /* each stage's own time, where the runs timed the isolation passes */
    if (m->n_time_st && dm_run_has_counter(u, "GeometryTime") && dm_run_has_counter(u, "MinimalShadingTime") &&
        predict__fit_stage_times(u, m->time_stage, m->n_time_stage)) {
        const dm_fit_result *f[3] = {m->time_stage[0], m->time_stage[1], m->time_stage[2]};
        m->shared_a = predict__shared_a(f, u);
    }
    predict__choose_way(m);
    for (size_t i = 0; i < u->n_configs; i++) {
        const dm_counter_result *r = u->configs[i].ok ? dm_config_counter(&u->configs[i], "Instructions") : NULL;
        if (r && r->available && isfinite(r->value) && r->value > m->instr_max)
            m->instr_max = r->value;
    }
    for (int st = 0; st < 3; st++)
        for (size_t i = 0; i < u->n_configs; i++) {
            const dm_counter_result *r = u->configs[i].ok ? dm_config_counter(&u->configs[i], predict__stages[st])
                                                          : NULL;
            if (r && r->available && isfinite(r->value) && r->value > m->stage_max[st])
                m->stage_max[st] = r->value;
        }
}

/* 1 when text is a number, or a resolution "WxH" (*x its pixel count). */
static int predict__axis_number(const char *text, double *x)
{
    char *end;
    *x = strtod(text, &end);
    if (end != text && *end == 'x' && isdigit((unsigned char)end[1]))
        *x *= strtod(end + 1, &end);
    return end != text && *end == '\0' && isfinite(*x);
}

/* A swept axis: a numeric axis of the runs' ok configurations with two
 * values or more (values point into the configurations' params). */
typedef struct predict__axis {
    const char *key;
    const char **values;
    size_t n_values;
} predict__axis;

/* The numeric axes of u's ok configurations and their distinct values
 * (*n of them; those with one value too: the caller skips them). */
static predict__axis *predict__axes(const dm_run_result *u, size_t *n)
{
    predict__axis *ax = NULL;
    *n = 0;
    for (size_t i = 0; i < u->n_configs; i++)
        for (size_t k = 0; u->configs[i].ok && k < u->configs[i].n_params; k++) {
            const dm_kv *p = &u->configs[i].params[k];
            double x;
            if (!p->value || !predict__axis_number(p->value, &x))
                continue;
            size_t a = 0;
            while (a < *n && strcmp(ax[a].key, p->key) != 0)
                a++;
            if (a == *n)
                DM_VEC_PUSH(ax, *n, ((predict__axis){ .key = p->key }));
            size_t v = 0;
            while (v < ax[a].n_values && strcmp(ax[a].values[v], p->value) != 0)
                v++;
            if (v == ax[a].n_values) {
                const char *val = p->value;
                DM_VEC_PUSH(ax[a].values, ax[a].n_values, val);
            }
        }
    return ax;
}

static void predict__axes_free(predict__axis *ax, size_t n)
{
    for (size_t a = 0; a < n; a++)
        free(ax[a].values);
    free(ax);
}

/* g's held-out predictions of c (a measured configuration g never saw):
 * ln(predicted / measured) of Instructions and WallTime, NaN where either
 * is missing. */
static void predict__group_errors(const predict_model *g, const dm_config_result *c, double *ei, double *ew)
{
    plan_config pc = { .params = c->params, .n_params = c->n_params };
    snprintf(pc.key, sizeof pc.key, "%s", c->key);
    double counts[PREDICT_N_COUNTS];
    for (size_t k = 0; k < PREDICT_N_COUNTS; k++) {
        const dm_counter_result *r = dm_config_counter(c, predict_counts[k]);
        counts[k] = r && r->available ? r->value : NAN;
    }
    predict_result r;
    dm_str why = {0};
    *ei = *ew = NAN;
    if (predict_config(g, &pc, counts, &r, &why) == 0) {
        const dm_counter_result *mi = dm_config_counter(c, "Instructions"), *mw = dm_config_counter(c, "WallTime");
        if (mi && mi->available && mi->value > 0 && r.instr > 0)
            *ei = log(r.instr / mi->value);
        if (mw && mw->available && mw->value > 0 && r.wall_ns > 0)
            *ew = log(r.wall_ns / mw->value);
    }
    predict_result_free(&r);
    dm_str_free(&why);
}

/* Holds out of m->train the configurations whose axis `key` is `value`,
 * fits the models to the rest and appends the held-out log errors to
 * ei / ew; 1 when it predicted one of them. */
static int predict__hold_group(const predict_model *m, const char *key, const char *value, double **ei, size_t *nei,
                               double **ew, size_t *nw)
{
    const dm_run_result *u = &m->train;
    predict_model g;
    memset(&g, 0, sizeof g);
    g.train = *u;
    g.train.configs = dm_xcalloc(u->n_configs + 1, sizeof *g.train.configs);
    g.train.n_configs = 0;
    for (size_t i = 0; i < u->n_configs; i++) {
        const char *x = dm_kv_get(u->configs[i].params, u->configs[i].n_params, key);
        if (!x || strcmp(x, value) != 0)
            g.train.configs[g.train.n_configs++] = u->configs[i];
    }
    predict__fit_core(&g);
    int any = 0;
    for (size_t i = 0; i < u->n_configs; i++) {
        const dm_config_result *c = &u->configs[i];
        const char *x = c->ok ? dm_kv_get(c->params, c->n_params, key) : NULL;
        double a, b;
        if (!x || strcmp(x, value) != 0)
            continue;
        predict__group_errors(&g, c, &a, &b);
        if (isfinite(a))
            DM_VEC_PUSH(*ei, *nei, a);
        if (isfinite(b))
            DM_VEC_PUSH(*ew, *nw, b);
        any = any || isfinite(a) || isfinite(b);
    }
    predict_free(&g);
    return any;
}

/* Held-out groups (predict_groups): one refit per value of each axis of
 * PREDICT_GROUP_VALUES values or more; the bounds of their errors. */
static void predict__groups(predict_model *m)
{
    predict_groups *gr = &m->groups;
    size_t na, nei = 0, nw = 0;
    predict__axis *ax = predict__axes(&m->train, &na);
    double *ei = NULL, *ew = NULL;
    gr->axes = dm_xcalloc(na + 1, sizeof *gr->axes);
    gr->n_axes = na;
    for (size_t a = 0; a < na; a++) {
        gr->axes[a] = (predict_axis_count){ dm_xstrdup(ax[a].key), (int)ax[a].n_values };
        for (size_t v = 0; ax[a].n_values >= PREDICT_GROUP_VALUES && v < ax[a].n_values; v++)
            gr->n_groups += predict__hold_group(m, ax[a].key, ax[a].values[v], &ei, &nei, &ew, &nw);
    }
    gr->instr_n = (int)nei;
    gr->wall_n = (int)nw;
    gr->instr_q = gr->n_groups >= 2 ? stats_bound90(ei, nei, NULL) : NAN;
    gr->wall_q = gr->n_groups >= 2 ? stats_bound90(ew, nw, NULL) : NAN;
    predict__axes_free(ax, na);
    free(ei);
    free(ew);
}

/* The machine between runs (predict_between): each configuration measured
 * by two of the n runs (its first two), ln(W_a / W_b) scaled to a new run
 * against the runs' mean. */
static void predict__between(predict_model *m, size_t n_runs)
{
    const dm_run_result *u = &m->train;
    double *e = NULL, scale = sqrt((1 + 1.0 / (double)n_runs) / 2);
    size_t ne = 0;
    for (size_t i = 0; i < u->n_configs; i++) {
        size_t first = i, earlier = 0;
        for (size_t j = 0; j < i; j++)
            if (strcmp(u->configs[j].key, u->configs[i].key) == 0 && earlier++ == 0)
                first = j;
        const dm_counter_result *a = u->configs[i].ok ? dm_config_counter(&u->configs[i], "WallTime") : NULL;
        const dm_counter_result *b = u->configs[first].ok ? dm_config_counter(&u->configs[first], "WallTime") : NULL;
        if (earlier == 1 && a && b && a->available && b->available && a->value > 0 && b->value > 0) {
            double x = scale * log(a->value / b->value);
            DM_VEC_PUSH(e, ne, x);
        }
    }
    double q = ne >= 2 ? stats_bound90(e, ne, NULL) : NAN;
    m->between = isfinite(q) ? (predict_between){ q, (int)ne } : (predict_between){ log1p(PREDICT_RUN_SPREAD), 0 };
    free(e);
}

void predict_fit(const dm_run_result *runs, size_t n, predict_model *m)
{
    memset(m, 0, sizeof *m);
    m->train = runs[0];
    m->train.configs = NULL;
    m->train.n_configs = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t i = 0; i < runs[k].n_configs; i++)
            DM_VEC_PUSH(m->train.configs, m->train.n_configs, runs[k].configs[i]);
    predict__fit_core(m);
    predict__groups(m);
    predict__between(m, n);
    m->calibrated = 1;
}

/* "resolution=288x192 never measured by the runs": the numeric axes of
 * pc whose value no ok configuration of the runs has; NULL when the runs
 * measured them all.  *blocked: why held-out groups cannot calibrate it
 * (an axis of fewer than PREDICT_GROUP_VALUES values, too few groups),
 * NULL when they can (owned, both). */
static char *predict__unmeasured(const predict_model *m, const plan_config *pc, char **blocked)
{
    dm_str s = {0}, b = {0};
    for (size_t k = 0; k < pc->n_params; k++) {
        double x, y;
        const dm_kv *p = &pc->params[k];
        if (!p->value || !predict__axis_number(p->value, &x))
            continue;
        int seen = 0, nv = 0;
        for (size_t i = 0; i < m->train.n_configs && !seen; i++) {
            const dm_config_result *c = &m->train.configs[i];
            const char *v = c->ok ? dm_kv_get(c->params, c->n_params, p->key) : NULL;
            seen = v && predict__axis_number(v, &y) && y == x;
        }
        if (seen)
            continue;
        dm_str_printf(&s, "%s%s=%s", s.len ? ", " : "", p->key, p->value);
        for (size_t a = 0; a < m->groups.n_axes; a++)
            if (strcmp(m->groups.axes[a].key, p->key) == 0)
                nv = m->groups.axes[a].n_values;
        if (nv < PREDICT_GROUP_VALUES && !b.len)
            dm_str_printf(&b, "the runs measured %d value%s of %s, and a group of them is held out only when "
                          "the rest still vary it (%d values)", nv, nv == 1 ? "" : "s", p->key,
                          PREDICT_GROUP_VALUES);
    }
    if (s.len && !b.len && m->groups.n_groups < 2)
        dm_str_printf(&b, "%d group held out gave a prediction; a bound needs 2", m->groups.n_groups);
    if (s.len)
        dm_str_cat(&s, " never measured by the runs");
    *blocked = b.len ? dm_str_take(&b) : NULL;
    return s.len ? dm_str_take(&s) : NULL;
}

/* fit's parameter `name` (its standard error in *se when se), NaN when
 * it has none */
static double predict__param(const dm_fit_result *fit, const char *name, double *se)
{
    const dm_fit_param *p = dm_fit_param_find(fit, name);
    if (se)
        *se = p ? p->stderr_ : NAN;
    return p ? p->value : NAN;
}

/* Predicts fit's response for configuration pc whose counts are in c. */
static int predict__one(const dm_fit_result *fit, const dm_run_result *train, const plan_config *pc,
                        dm_config_result *c, double *v, dm_str *why)
{
    dm_run_result one = { .configs = c, .n_configs = 1 };
    return fitting_predict_dropped(fit, train, pc->params, pc->n_params, pc->key, &one, 1, v, why);
}

/* The first of fits whose group holds pc and that predicts it: *v, and
 * the fit; NULL (and *v NaN) when none does. */
static const dm_fit_result *predict__any(const dm_fit_result *fits, size_t n, const dm_run_result *train,
                                         const plan_config *pc, dm_config_result *c, double *v)
{
    for (size_t i = 0; i < n; i++) {
        dm_str why = {0};
        int rc = predict__one(&fits[i], train, pc, c, v, &why);
        dm_str_free(&why);
        if (rc == 0 && isfinite(*v))
            return &fits[i];
    }
    *v = NAN;
    return NULL;
}

size_t predict_variant_count(const predict_model *m, const char *variant)
{
    size_t n = 0;
    for (size_t i = 0; i < m->train.n_configs; i++) {
        const dm_config_result *c = &m->train.configs[i];
        char *v = c->ok ? fitting_variant(c->params, c->n_params) : NULL;
        n += v && strcmp(v, variant) == 0;
        free(v);
    }
    return n;
}

/* "the runs measured N configurations of variant 'v', too few to WHAT". */
static char *predict__too_few(const predict_model *m, const char *variant, const char *what)
{
    size_t n = predict_variant_count(m, variant);
    return dm_xasprintf("the runs measured %zu configuration%s of variant '%s', too few to %s", n,
                        n == 1 ? "" : "s", variant, what);
}

/* Why the stage shares are missing (predict_result.part_why). */
static char *predict__part_why(const predict_model *m, const char *variant)
{
    for (int s = 0; s < 3; s++)
        if (!dm_run_has_counter(&m->train, predict__stages[s]) || !dm_run_has_counter(&m->train, "SamplesPassed"))
            return dm_xasprintf("the runs lack the stage counters (%s, %s, %s and SamplesPassed in "
                                "measure.counters)", predict__stages[0], predict__stages[1], predict__stages[2]);
    size_t with = 0;   /* configurations of the variant with all three stage counters */
    for (size_t i = 0; i < m->train.n_configs; i++) {
        const dm_config_result *c = &m->train.configs[i];
        char *v = c->ok ? fitting_variant(c->params, c->n_params) : NULL;
        int all = v && strcmp(v, variant) == 0;
        for (int k = 0; k < 3 && all; k++) {
            const dm_counter_result *r = dm_config_counter(c, predict__stages[k]);
            all = r && r->available && isfinite(r->value);
        }
        with += (size_t)all;
        free(v);
    }
    if (!with)
        return dm_xasprintf("the runs have no stage counters for variant '%s' (their runs lack %s, %s "
                            "and %s)", variant, predict__stages[0], predict__stages[1], predict__stages[2]);
    for (int s = 0; s < 3; s++)
        if (!predict_fit_of(m->stage[s], m->n_stage[s], variant))
            return dm_xasprintf("the runs measured the stage counters of %zu configuration%s of variant "
                                "'%s', too few to fit its stage models", with, with == 1 ? "" : "s", variant);
    return dm_xstrdup("the stage models of the variant do not cover this configuration (an axis or count "
                      "they never saw vary)");
}

/* Why no way of predicting WallTime is usable: each way's reason or
 * held-out error. */
static char *predict__no_way_why(const predict_model *m)
{
    if (m->way[0].why && m->way[1].why && m->way[2].why && strstr(m->way[0].why, "no WallTime"))
        return dm_xstrdup(m->way[0].why);
    dm_str s = {0};
    dm_str_printf(&s, "no way of predicting it held out within %.0f %% on the runs (", PREDICT_MAX_HELDOUT);
    for (int w = 0; w < PREDICT_N_WAYS; w++) {
        const predict_way_score *x = &m->way[w];
        dm_str_printf(&s, "%s%s ", w ? "; " : "", predict_way_names[w]);
        if (x->why)
            dm_str_printf(&s, "unavailable: %s", x->why);
        else if (isfinite(x->cv_mape))
            dm_str_printf(&s, "%.1f %%", x->cv_mape);
        else
            dm_str_cat(&s, "without a held-out error");
    }
    dm_str_cat(&s, ")");
    return dm_str_take(&s);
}

/* The frame time of the configuration c (its counts and predicted stage
 * parts among its counters; out's Instructions and parts filled) by way
 * w: *ns, and in *se_ns the spread the parameters' standard errors give
 * the parts beyond the largest the runs measured (INFINITY: such a part's
 * cost has none).  0 when w prices it. */
static int predict__wall_by(const predict_model *m, predict_way w, dm_config_result *c, const predict_result *out,
                            double *ns, double *se_ns)
{
    static const char *const b[3] = {"b_geo", "b_raster", "b_frag"};
    double parts = out->part[0] + out->part[1] + out->part[2], se2 = 0, se = NAN;
    *ns = NAN;
    int held = predict_way_usable(m, w) || (!m->way[w].why && !isfinite(m->way[w].cv_mape));
    if (!held || (w != PREDICT_WAY_TIME_FROM_INSTRUCTIONS && !(isfinite(parts) && parts > 0)))
        return -1;
    if (w == PREDICT_WAY_TIME_FROM_INSTRUCTIONS) {
        const dm_fit_result *t = &m->time[0];
        *ns = predict__param(t, "a", NULL) + predict__param(t, "b", &se) * out->instr;
        double excess = out->instr - m->instr_max;
        se2 = excess > 0 ? pow(se * excess, 2) : 0;
    } else {
        const dm_fit_result *t = w == PREDICT_WAY_TIME_FROM_STAGES ? &m->time_st[0] : NULL;
        *ns = t ? predict__param(t, "a", NULL) : m->shared_a;
        for (int s = 0; s < 3; s++) {
            if (t)
                *ns += predict__param(t, b[s], &se) * out->part[s];
            else {
                *ns += predict__variable_part(m->time_stage[s], &m->train, c);
                predict__param(m->time_stage[s], "b", &se);
            }
            double excess = out->part[s] - m->stage_max[s];
            se2 += excess > 0 ? pow(se * excess, 2) : 0;
        }
    }
    *se_ns = isfinite(se2) ? sqrt(se2) : INFINITY;
    return isfinite(*ns) && *ns > 0 ? 0 : -1;
}

/* out's WallTime: by the way of the lowest held-out error on the runs
 * (m->way_used), unless a documented reason overrides it (out->
 * wall_override says which), else the next that prices it; its interval
 * from that way's held-out errors (their PREDICT_COVERAGE bound),
 * the Instructions' relative half-width ei, the machine's speed between
 * runs and the parameters' standard errors beyond the runs, combined as
 * ratios (root of the sum of the squared logarithms): never below 0. */
static void predict__wall(const predict_model *m, dm_config_result *c, double ei, predict_result *out)
{
    const predict_groups *gr = &m->groups;
    int by_groups = out->calibration && strcmp(out->calibration, "held-out groups") == 0;
    int order[PREDICT_N_WAYS], n = 0;
    if (m->way_used >= 0)
        order[n++] = m->way_used;
    for (int w = 0; w < PREDICT_N_WAYS; w++)   /* the rest by their held-out error */
        if (w != m->way_used && predict_way_usable(m, (predict_way)w)) {
            int j = n++;
            for (; j > 0 && j > (m->way_used >= 0) && m->way[order[j - 1]].cv_mape > m->way[w].cv_mape; j--)
                order[j] = order[j - 1];
            order[j] = w;
        }
    /* time-from-stages prices a geometry instruction from frames it is a
     * few per cent of: beyond the runs' geometry it does not carry
     * (docs/models.md, "Frame time by stage") */
    if (n > 1 && order[0] == PREDICT_WAY_TIME_FROM_STAGES && out->part[0] > m->stage_max[0] &&
        predict_way_usable(m, PREDICT_WAY_STAGE_TIMES)) {
        for (int j = 0; j < n; j++)
            order[j] = j == 0 ? PREDICT_WAY_STAGE_TIMES : order[j] == PREDICT_WAY_STAGE_TIMES ? PREDICT_WAY_TIME_FROM_STAGES
                                                                                              : order[j];
        out->wall_override = "time-from-stages had the lower held-out error, but this configuration's geometry "
                             "lies beyond the runs', where its price of a geometry instruction does not carry";
    }
    /* no way held out at all (too few configurations): the first the runs
     * allow gives the value, its interval unavailable with that reason;
     * one held out above PREDICT_MAX_HELDOUT never does */
    for (int w = 0; n == 0 && w < PREDICT_N_WAYS; w++)
        if (!m->way[w].why && !isfinite(m->way[w].cv_mape))
            order[n++] = w;
    double se_ns = 0;
    int used = -1;
    for (int j = 0; j < n && used < 0; j++)
        if (predict__wall_by(m, (predict_way)order[j], c, out, &out->wall_ns, &se_ns) == 0)
            used = order[j];
    if (used < 0) {
        out->wall_ns = NAN;
        out->wall_override = NULL;
        out->wall_why = predict__no_way_why(m);
        return;
    }
    if (used != order[0])
        out->wall_override = "the way of the lowest held-out error needs stage parts this configuration lacks";
    out->wall_by = predict_way_names[used];
    const predict_way_score *w = &m->way[used];
    double beyond = log1p(2 * se_ns / out->wall_ns);
    double h = sqrt(pow(w->q, 2) + pow(log1p(ei), 2) + pow(m->between.q, 2) + pow(beyond, 2));
    if (by_groups)   /* the wider of leave-one-out and held-out groups (docs/models.md, "Intervals") */
        h = fmax(h, sqrt(pow(gr->wall_q, 2) + pow(m->between.q, 2) + pow(beyond, 2)));
    if (!isfinite(w->q))
        out->wall_why = dm_xasprintf("%s held out %d configuration%s of the runs; a %.0f %% interval needs %d "
                                     "(the spread of their errors)", out->wall_by, w->n, w->n == 1 ? "" : "s",
                                     100 * PREDICT_COVERAGE, PREDICT_MIN_HELDOUT);
    else if (!isfinite(ei))
        out->wall_why = dm_xstrdup("the Instructions have no interval");
    else if (by_groups && !isfinite(gr->wall_q))
        out->wall_why = dm_xasprintf("%s, and the held-out groups gave %d frame times, too few for a bound",
                                     out->calibration_why, gr->wall_n);
    else if (!isfinite(h))
        out->wall_why = dm_xstrdup("a stage beyond the runs has a cost without a standard error");
    else {
        out->wall_lo = out->wall_ns * exp(-h);
        out->wall_hi = out->wall_ns * exp(h);
    }
}

int predict_config(const predict_model *m, const plan_config *pc, const double *counts, predict_result *out,
                   dm_str *why)
{
    *out = (predict_result){ .instr = NAN, .instr_lo = NAN, .instr_hi = NAN, .part = {NAN, NAN, NAN},
                             .wall_ns = NAN, .wall_lo = NAN, .wall_hi = NAN, .beyond_stage = -1 };
    out->variant = fitting_variant(pc->params, pc->n_params);
    dm_config_result c = { .key = (char *)pc->key, .ok = 1, .params = pc->params, .n_params = pc->n_params };
    dm_counter_result cr[PREDICT_N_COUNTS + 3];   /* the counts, then the predicted stage parts */
    for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
        cr[k] = (dm_counter_result){ .name = (char *)predict_counts[k], .available = isfinite(counts[k]),
                                     .value = counts[k] };
    c.counters = cr;
    c.n_counters = PREDICT_N_COUNTS;
    const dm_fit_result *fi = predict_fit_of(m->instr, m->n_instr, out->variant);
    double instr = NAN;
    if (!fi)
        dm_str_printf(why, "variant '%s' was never measured by the runs", out->variant);
    else
        predict__one(fi, &m->train, pc, &c, &instr, why);
    if (!isfinite(instr))
        return DM_ERR_UNKNOWN;
    out->instr_by = "stage-instructions";
    /* By stage when the runs have the stage counters: each stage's costs
     * against its invocations; the frame is then their sum. */
    double ei = 2 * fi->cv_mape / 100, spread = 0;
    for (int s = 0; s < 3; s++) {
        const dm_fit_result *fs = predict__any(m->stage[s], m->n_stage[s], &m->train, pc, &c, &out->part[s]);
        spread = fs && isfinite(fs->cv_mape) && fs->cv_mape > 0 && isfinite(spread)
                 ? spread + fabs(out->part[s]) * 2 * fs->cv_mape / 100 : NAN;
    }
    double sum = out->part[0] + out->part[1] + out->part[2];
    for (int s = 0; s < 3; s++) {   /* how far beyond what the runs measured */
        double r = m->stage_max[s] > 0 ? out->part[s] / m->stage_max[s] : NAN;
        if (r > 1 && r > (out->beyond_stage < 0 ? 1 : out->beyond)) {
            out->beyond_stage = s;
            out->beyond = r;
        }
    }
    if (isfinite(sum) && sum > 0 && !predict_heldout_prefers_one(m, fi)) {
        /* the interval: how well the sum predicted the runs' own held-out
         * configurations of the variant, else each part's own error */
        const predict_heldout *h = predict_heldout_of(m, out->variant);
        instr = sum;
        out->instr_by = "stage models summed";
        ei = h && h->n >= 3 && isfinite(h->cv_mape) ? 2 * h->cv_mape / 100 : isfinite(spread) ? spread / sum : ei;
        /* no narrower than the bound of every variant's held-out errors */
        if (isfinite(ei) && isfinite(m->instr_q))
            ei = fmax(ei, expm1(m->instr_q));
    } else if (isfinite(ei) && isfinite(predict__fit_bound(fi))) {
        /* the whole-frame fit: no narrower than the bound of its own held-out errors */
        ei = fmax(ei, expm1(predict__fit_bound(fi)));
    }
    if (!isfinite(ei) && isfinite(m->instr_q)) {
        /* the variant has no held-out error of its own: the other variants' pooled */
        ei = expm1(m->instr_q);
        out->instr_pooled = "the variant has too few configurations to hold one out; the interval is the "
                            "90 % bound of the other variants' held-out errors pooled";
    }
    /* at an axis value the runs never measured the target is an
     * extrapolation, which leaving one configuration out does not mimic:
     * the wider of that bound and the held-out groups' */
    out->calibration = "leave-one-out";
    char *blocked = NULL;
    out->calibration_why = m->calibrated ? predict__unmeasured(m, pc, &blocked) : NULL;
    double ei_loo = ei;
    if (out->calibration_why && blocked)
        out->calibration = "leave-one-out, groups unavailable";
    else if (out->calibration_why) {
        out->calibration = "held-out groups";
        ei = isfinite(ei) && isfinite(m->groups.instr_q) ? fmax(ei, expm1(m->groups.instr_q)) : NAN;
    }
    out->instr = instr;
    if (!isfinite(ei_loo))
        out->instr_why = predict__too_few(m, out->variant, "hold one out for an interval");
    else if (blocked) {
        /* leave-one-out bounds held 6 of 12 such targets on the 14:30
         * bench runs: not an interval (docs/models.md, "Intervals") */
        out->instr_why = dm_xasprintf("%s, and %s", out->calibration_why, blocked);
        out->instr_blocked = dm_xstrdup(blocked);
        ei = NAN;
    } else if (!isfinite(ei))
        out->instr_why = dm_xasprintf("%s, and the held-out groups gave %d Instructions errors, too few for a bound",
                                      out->calibration_why, m->groups.instr_n);
    free(blocked);
    out->instr_lo = instr / (1 + ei);   /* a ratio either way: never below 0 */
    out->instr_hi = instr * (1 + ei);
    if (!(isfinite(sum) && sum > 0))
        out->part_why = predict__part_why(m, out->variant);
    for (int s = 0; s < 3; s++)   /* the stage parts, for the stage-time fits */
        cr[PREDICT_N_COUNTS + s] = (dm_counter_result){ .name = (char *)predict__stages[s],
                                                        .available = isfinite(out->part[s]), .value = out->part[s] };
    c.n_counters = PREDICT_N_COUNTS + 3;
    predict__wall(m, &c, ei_loo, out);
    return 0;
}

void predict_result_free(predict_result *r)
{
    free(r->variant);
    free(r->instr_why);
    free(r->part_why);
    free(r->wall_why);
    free(r->calibration_why);
    free(r->instr_blocked);
    r->variant = r->instr_why = r->part_why = r->wall_why = r->calibration_why = r->instr_blocked = NULL;
}

static void predict__free_fits(dm_fit_result *f, size_t n)
{
    for (size_t i = 0; i < n; i++)
        dm_fit_result_free(&f[i]);
    free(f);
}

void predict_free(predict_model *m)
{
    predict__free_fits(m->instr, m->n_instr);
    for (int st = 0; st < 3; st++)
        predict__free_fits(m->stage[st], m->n_stage[st]);
    predict__free_fits(m->time, m->n_time);
    predict__free_fits(m->time_st, m->n_time_st);
    for (int st = 0; st < 3; st++)
        predict__free_fits(m->time_stage[st], m->n_time_stage[st]);
    for (int w = 0; w < PREDICT_N_WAYS; w++)
        free(m->way[w].why);
    for (size_t i = 0; i < m->n_heldout; i++)
        free(m->heldout[i].variant);
    free(m->heldout);
    for (size_t a = 0; a < m->groups.n_axes; a++)
        free(m->groups.axes[a].key);
    free(m->groups.axes);
    free(m->train.configs);
    memset(m, 0, sizeof *m);
}
