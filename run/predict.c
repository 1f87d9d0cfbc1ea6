/* predict.c — per-variant costs fitted to measured runs, applied to the
 * invocation counts of configurations never measured (predict.h). */
#include "run/predict.h"
#include "core/dm_error.h"
#include "run/fitting.h"
#include "reports/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *const predict_counts[PREDICT_N_COUNTS] = {"VSInvocations", "TESInvocations",
                                                      "ClippingOutputPrimitives", "FSInvocations", "TCSPatches",
                                                      "SamplesPassed", "LoopTrips"};
const char *const predict_needed[PREDICT_N_NEEDED] = {"Instructions", "VSInvocations", "TESInvocations",
                                                      "ClippingOutputPrimitives", "FSInvocations"};
static const char *const predict__stages[3] = {"GeometryInstructions", "RasterInstructions",
                                               "FragmentInstructions"};
/* each stage counter's own model (models/catalog.c); fragment shading
 * from the search loop's trips when the runs counted them */
static const char *const predict__stage_models[3] = {"geometry-instructions", "raster-instructions",
                                                     "fragment-instructions"};

/* each stage's time from its instructions (models/catalog.c) */
static const char *const predict__time_models[3] = {"geometry-time", "raster-time", "fragment-time"};

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
    fitting_spec spec = { .name = model, .response = response, .group_by = group_by, .n_group_by = n_group_by };
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
 * f[0] was fitted to, summed, against its `counter`: their CV-MAPE. */
static predict_heldout predict__sum_heldout(const dm_fit_result *const f[3], const dm_run_result *train,
                                            const char *counter, const char *variant)
{
    double ape = 0;
    int n = 0;
    for (int k = 0; f[0]->point_labels && f[1] && f[2] && k < f[0]->n_points; k++) {
        const char *key = f[0]->point_labels[k];
        double sum = predict__cv_of(f[0], key) + predict__cv_of(f[1], key) + predict__cv_of(f[2], key);
        const dm_config_result *c = dm_run_config(train, key);
        const dm_counter_result *r = c ? dm_config_counter(c, counter) : NULL;
        if (isfinite(sum) && r && r->available && r->value > 0) {
            ape += fabs(sum - r->value) / r->value;
            n++;
        }
    }
    return (predict_heldout){ dm_xstrdup(variant), n ? 100 * ape / n : NAN, n };
}

/* Per variant: the stage models' held-out predictions of each measured
 * configuration, summed, against its Instructions (predict_heldout). */
static void predict__heldout(predict_model *m)
{
    for (size_t i = 0; i < m->n_stage[0]; i++) {
        const dm_fit_result *g = &m->stage[0][i];
        if (g->n_group != 1 || !g->point_labels)
            continue;
        const dm_fit_result *f[3] = {g, predict_fit_of(m->stage[1], m->n_stage[1], g->group[0].value),
                                     predict_fit_of(m->stage[2], m->n_stage[2], g->group[0].value)};
        predict_heldout h = predict__sum_heldout(f, &m->train, "Instructions", g->group[0].value);
        DM_VEC_PUSH(m->heldout, m->n_heldout, h);
    }
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

int predict_has_stage_times(const predict_model *m)
{
    return m->time_heldout.n >= 3 && isfinite(m->time_heldout.cv_mape);
}

int predict_prefers_time_from_stages(const predict_model *m)
{
    return m->n_time_st == 1 && (m->n_time != 1 || !(m->time[0].cv_mape < m->time_st[0].cv_mape));
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
    const dm_run_result *u = &m->train;
    predict__fit(u, "stage-instructions", "Instructions", NULL, 0, &m->instr, &m->n_instr);
    for (int st = 0; st < 3; st++)
        if (dm_run_has_counter(u, predict__stages[st]) && dm_run_has_counter(u, "SamplesPassed"))
            predict__fit(u, st == 2 && dm_run_has_counter(u, "LoopTrips") ? "fragment-trips" : predict__stage_models[st],
                         predict__stages[st], NULL, 0, &m->stage[st], &m->n_stage[st]);
    predict__heldout(m);
    if (dm_run_has_counter(u, "WallTime"))
        predict__fit(u, "time-from-instructions", "WallTime", NULL, 0, &m->time, &m->n_time);
    if (dm_run_has_counter(u, "WallTime") && m->n_stage[0] && m->n_stage[1] && m->n_stage[2])
        predict__fit(u, "time-from-stages", "WallTime", NULL, 0, &m->time_st, &m->n_time_st);
    /* each stage's own time, where the runs timed the isolation passes */
    m->time_heldout.cv_mape = NAN;
    if (m->n_time_st && dm_run_has_counter(u, "GeometryTime") && dm_run_has_counter(u, "MinimalShadingTime")) {
        for (int st = 0; st < 3; st++)
            predict__fit(u, predict__time_models[st], NULL, NULL, 0, &m->time_stage[st], &m->n_time_stage[st]);
        if (m->n_time_stage[0] == 1 && m->n_time_stage[1] == 1 && m->n_time_stage[2] == 1) {
            const dm_fit_result *f[3] = {m->time_stage[0], m->time_stage[1], m->time_stage[2]};
            m->time_heldout = predict__sum_heldout(f, u, "WallTime", "all");
        }
    }
    for (int st = 0; st < 3; st++)
        for (size_t i = 0; i < u->n_configs; i++) {
            const dm_counter_result *r = u->configs[i].ok ? dm_config_counter(&u->configs[i], predict__stages[st])
                                                          : NULL;
            if (r && r->available && isfinite(r->value) && r->value > m->stage_max[st])
                m->stage_max[st] = r->value;
        }
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

/* Why out has no WallTime or no interval around it (wall_why); et_fit is the
 * time fit's held-out error, ei the Instructions' relative half-width. */
static char *predict__wall_why(const predict_model *m, const predict_result *out, double et_fit, double ei)
{
    if (!out->wall_by)
        return dm_run_has_counter(&m->train, "WallTime")
               ? dm_xstrdup("no time fit: the runs' WallTime could not be fitted to their instructions")
               : dm_xstrdup("the runs have no WallTime (add it to measure.counters)");
    if (isfinite(out->wall_lo) && isfinite(out->wall_hi))
        return NULL;
    if (!isfinite(et_fit))
        return dm_xasprintf("the %s fit has no held-out error (too few configurations to hold one out)",
                            out->wall_by);
    if (!isfinite(ei))
        return dm_xstrdup("the Instructions have no interval");
    return dm_xstrdup("a stage beyond the runs has a cost without a standard error");
}

int predict_config(const predict_model *m, const plan_config *pc, const double *counts, predict_result *out,
                   dm_str *why)
{
    *out = (predict_result){ .instr = NAN, .instr_lo = NAN, .instr_hi = NAN, .part = {NAN, NAN, NAN},
                             .wall_ns = NAN, .wall_lo = NAN, .wall_hi = NAN, .beyond_stage = -1 };
    out->variant = fitting_variant(pc->params, pc->n_params);
    dm_config_result c = { .key = (char *)pc->key, .ok = 1 };
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
    }
    out->instr = instr;
    out->instr_lo = instr * (1 - ei);
    out->instr_hi = instr * (1 + ei);
    if (!isfinite(ei))
        out->instr_why = predict__too_few(m, out->variant, "hold one out for an interval");
    if (!(isfinite(sum) && sum > 0))
        out->part_why = predict__part_why(m, out->variant);
    /* Frame time.  With the timed stage passes: each stage's time from
     * its part, at the price of an instruction that stage's own pass
     * measured.  Else from each stage's instructions fitted to the frame's
     * time (an instruction of the geometry stages, on one thread, takes
     * longer) when that fit predicts the runs' held-out frames at least as
     * well as the one from the frame's instructions; else from the
     * frame's. */
    double se_ns = 0;   /* what the parameters' standard errors make of it beyond the runs */
    double et_fit = NAN;   /* the time fit's held-out error, % */
    double stage_ns = 0;   /* the stage times' sum: their formulas over the counts and the parts */
    int by_stage_times = predict_has_stage_times(m) && isfinite(sum) && sum > 0;
    if (by_stage_times) {
        dm_config_result cp = c;
        for (int s = 0; s < 3; s++)
            cr[PREDICT_N_COUNTS + s] = (dm_counter_result){ .name = (char *)predict__stages[s], .available = 1,
                                                            .value = out->part[s] };
        cp.n_counters = PREDICT_N_COUNTS + 3;
        for (int s = 0; s < 3 && by_stage_times; s++) {
            double v = NAN;
            dm_str w = {0};
            by_stage_times = predict__one(m->time_stage[s], &m->train, pc, &cp, &v, &w) == 0 && isfinite(v);
            stage_ns += v;
            dm_str_free(&w);
        }
    }
    if (isfinite(sum) && sum > 0 && (by_stage_times || predict_prefers_time_from_stages(m))) {
        static const char *const b[3] = {"b_geo", "b_raster", "b_frag"};
        /* Within the runs' range the time fit's held-out error says its
         * error; a stage part beyond the largest measured adds the excess
         * times its cost's standard error (the standard errors alone,
         * without their covariance, overstate the error of an
         * interpolation). */
        double se = NAN;
        const dm_fit_result *t = by_stage_times ? NULL : &m->time_st[0];
        out->wall_ns = t ? predict__param(t, "a", NULL) : stage_ns;
        for (int s = 0; s < 3; s++) {
            if (t)
                out->wall_ns += predict__param(t, b[s], &se) * out->part[s];
            else
                predict__param(m->time_stage[s], "b", &se);
            double excess = out->part[s] - m->stage_max[s];
            se_ns += excess > 0 ? (isfinite(se) ? pow(se * excess, 2) : INFINITY) : 0;
        }
        se_ns = sqrt(se_ns);
        et_fit = t ? t->cv_mape : m->time_heldout.cv_mape;
        out->wall_by = t ? "time-from-stages" : "stage times";
    } else if (m->n_time == 1) {
        const dm_fit_result *t = &m->time[0];
        out->wall_ns = predict__param(t, "a", NULL) + predict__param(t, "b", NULL) * instr;
        et_fit = t->cv_mape;
        out->wall_by = "time-from-instructions";
    }
    if (out->wall_by) {
        /* the instructions' and the time fit's errors, the machine's
         * speed between runs and, far from the configurations fitted, its
         * parameters' standard errors */
        double ep = out->wall_ns > 0 ? 2 * se_ns / out->wall_ns : 0;
        double et = sqrt(ei * ei + pow(2 * et_fit / 100, 2) + pow(PREDICT_RUN_SPREAD, 2) + ep * ep);
        out->wall_lo = fmax(0, out->wall_ns * (1 - et));   /* no frame takes less than nothing */
        out->wall_hi = out->wall_ns * (1 + et);
        if (!isfinite(out->wall_hi))
            out->wall_lo = NAN;   /* no half-known interval */
    }
    out->wall_why = predict__wall_why(m, out, et_fit, ei);
    return 0;
}

void predict_result_free(predict_result *r)
{
    free(r->variant);
    free(r->instr_why);
    free(r->part_why);
    free(r->wall_why);
    r->variant = r->instr_why = r->part_why = r->wall_why = NULL;
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
    free(m->time_heldout.variant);
    for (size_t i = 0; i < m->n_heldout; i++)
        free(m->heldout[i].variant);
    free(m->heldout);
    free(m->train.configs);
    memset(m, 0, sizeof *m);
}
