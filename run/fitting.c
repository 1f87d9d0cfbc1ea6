/* fitting.c — from results to fit_desc (see fitting.h). */
#include "fitting.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "models/bounds.h"
#include "models/catalog.h"
#include "models/formula.h"
#include "sweep/sweep.h"
#include "techniques/axes.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Collects variable names: counters then params, each once. */
static void fitting__names(const dm_run_result *run, const char ***names, size_t *n)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        for (size_t k = 0; k < c->n_counters + c->n_params; k++) {
            const char *nm = k < c->n_counters ? c->counters[k].name : c->params[k - c->n_counters].key;
            size_t j = 0;
            while (j < *n && strcmp((*names)[j], nm) != 0)
                j++;
            if (j == *n) {
                DM_VEC_PUSH(*names, *n, nm);
            }
        }
    }
}

/* A counter's value for fitting, NaN when it has none: unavailable, or a
 * partial GPUTime (docs/counters.md). */
static double fitting__counter_value(const dm_run_result *run, const dm_counter_result *r)
{
    int partial = r->partial || (strcmp(r->name, "GPUTime") == 0 && run->timer_verdict &&
                                 strcmp(run->timer_verdict, "full") != 0);
    return r->available && !partial ? r->value : NAN;
}

/* Numeric value of an axis, NaN when absent or not a number; `resolution`
 * ("WxH") is the pixel count. */
static double fitting__param_value(const dm_kv *params, size_t n, const char *name)
{
    const char *v = dm_kv_get(params, n, name);
    int w, h;
    if (v && strcmp(name, "resolution") == 0 && sscanf(v, "%dx%d", &w, &h) == 2)
        return (double)w * h;
    char *end = NULL;
    double x = v ? strtod(v, &end) : NAN;
    return v && end && *end == '\0' ? x : NAN;
}

/* Numeric value of a variable in a configuration, NaN when absent. */
static double fitting__value(const dm_run_result *run, const dm_config_result *c, const char *name)
{
    const dm_counter_result *r = dm_config_counter(c, name);
    return r ? fitting__counter_value(run, r) : fitting__param_value(c->params, c->n_params, name);
}

static int fitting__same_group(const fitting_spec *s, const dm_config_result *a, const dm_config_result *b)
{
    for (size_t i = 0; i < s->n_group_by; i++) {
        const char *x = dm_kv_get(a->params, a->n_params, s->group_by[i]);
        const char *y = dm_kv_get(b->params, b->n_params, s->group_by[i]);
        if ((x || y) && (!x || !y || strcmp(x, y) != 0))
            return 0;
    }
    return 1;
}

/* Fits the group led by configuration `lead`. */
static void fitting__group(const fitting_spec *s, const models_builtin *b, const dm_run_result *run,
                           const dm_config_result *lead, const char **names, size_t nv,
                           dm_fit_result **fits, size_t *nf, dm_str *warnings)
{
    size_t np = 0;
    double *x = dm_xcalloc(run->n_configs * nv + 1, sizeof *x);
    double *y = dm_xcalloc(run->n_configs + 1, sizeof *y);
    const char **labels = dm_xcalloc(run->n_configs + 1, sizeof *labels);
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!c->ok || !fitting__same_group(s, c, lead))
            continue;
        for (size_t k = 0; k < nv; k++)
            x[np * nv + k] = fitting__value(run, c, names[k]);
        y[np] = fitting__value(run, c, s->response);
        labels[np++] = c->key;
    }
    fit_desc d = { .model = s->name, .formula = s->formula, .response = s->response,
                   .variables = names, .n_vars = nv, .x = x, .y = y, .n_points = np,
                   .point_labels = labels, .bounds = b ? b->bounds : NULL,
                   .n_bounds = b ? b->n_bounds : 0, .loss = s->loss, .seed = 1 };
    dm_fit_result fr = {0};
    dm_str err = {0};
    if (fit_run(&d, &fr, &err) == 0) {
        for (size_t i = 0; i < s->n_group_by; i++)
            dm_kv_push(&fr.group, &fr.n_group, s->group_by[i],
                       dm_kv_get(lead->params, lead->n_params, s->group_by[i]));
        DM_VEC_PUSH(*fits, *nf, fr);
    } else {
        dm_str_printf(warnings, "model %s", s->name);
        for (size_t i = 0; i < s->n_group_by; i++)
            dm_str_printf(warnings, " %s=%s", s->group_by[i],
                          dm_kv_get(lead->params, lead->n_params, s->group_by[i]));
        dm_str_printf(warnings, ": not fitted: %s\n", dm_str_get(&err));
    }
    dm_str_free(&err);
    free(x);
    free(y);
    free(labels);
}

/* 1 when the identifier [p, p+len) is a counter that is not among names. */
static int fitting__missing_counter(const char *p, size_t len, const char **names, size_t nv)
{
    char id[64];
    if (len >= sizeof id)
        return 0;
    memcpy(id, p, len);
    id[len] = '\0';
    for (size_t i = 0; i < nv; i++)
        if (strcmp(names[i], id) == 0)
            return 0;
    return counters_find(id) != NULL;
}

/* 1 when the term [t, t+len) names a counter the run did not record. */
static int fitting__term_missing(const char *t, size_t len, const char **names, size_t nv)
{
    for (size_t i = 0; i < len;) {
        if (!(t[i] == '_' || isalpha((unsigned char)t[i]))) {
            i++;
            continue;
        }
        size_t j = i;
        while (j < len && (t[j] == '_' || t[j] == '.' || isalnum((unsigned char)t[j])))
            j++;
        if (fitting__missing_counter(t + i, j - i, names, nv))
            return 1;
        i = j;
    }
    return 0;
}

/* A built-in model (a sum of terms) without the terms that use a counter
 * the run did not record: a missing counter is not a parameter.  Each
 * dropped term is named in warnings; bounds of parameters that no longer
 * appear are dropped too.  Returns the formula (malloc'd). */
static char *fitting__drop_missing(const models_builtin *b, const char **names, size_t nv,
                                   fit_bound *bounds, size_t *n_bounds, dm_str *warnings)
{
    dm_str out = {0};
    const char *f = b->formula;
    for (const char *t = f; *t;) {
        int depth = 0;
        const char *e = t;
        for (; *e && !(depth == 0 && *e == '+'); e++)
            depth += (*e == '(') - (*e == ')');
        while (*t == ' ')
            t++;
        size_t len = (size_t)(e - t);
        while (len && t[len - 1] == ' ')
            len--;
        if (fitting__term_missing(t, len, names, nv))
            dm_str_printf(warnings, "model %s: term '%.*s' dropped: the run did not record its counter\n",
                          b->name, (int)len, t);
        else
            dm_str_printf(&out, "%s%.*s", dm_str_get(&out)[0] ? " + " : "", (int)len, t);
        t = *e ? e + 1 : e;
    }
    *n_bounds = 0;
    for (size_t i = 0; i < b->n_bounds; i++)
        if (strstr(dm_str_get(&out), b->bounds[i].param))
            bounds[(*n_bounds)++] = b->bounds[i];
    return dm_str_take(&out);
}

int fitting_run(const fitting_spec *spec, const dm_run_result *run, dm_fit_result **fits,
                size_t *n, dm_str *warnings, dm_str *err)
{
    fitting_spec s = *spec;
    const models_builtin *b = models_builtin_find(s.name);
    if (!s.formula && !b) {
        dm_str_printf(err, "unknown model '%s' and no formula given; built-in models:", s.name);
        for (size_t i = 0; i < models_builtin_count(); i++)
            dm_str_printf(err, " %s", models_builtin_at(i)->name);
        return DM_ERR_UNKNOWN;
    }
    if (!s.formula)
        s.formula = b->formula;
    else
        b = NULL;                /* a user formula does not take the built-in bounds */
    if (!s.response)
        s.response = b ? b->response : "WallTime";
    const char **names = NULL;
    size_t nv = 0;
    fitting__names(run, &names, &nv);
    models_builtin reduced;
    fit_bound *bounds = NULL;
    char *formula = NULL;
    if (b) {
        reduced = *b;
        bounds = dm_xcalloc(b->n_bounds + 1, sizeof *bounds);
        formula = fitting__drop_missing(b, names, nv, bounds, &reduced.n_bounds, warnings);
        reduced.formula = s.formula = formula;
        reduced.bounds = bounds;
        b = &reduced;
    }
    int *seen = dm_xcalloc(run->n_configs + 1, sizeof *seen);
    for (size_t i = 0; i < run->n_configs; i++) {
        if (seen[i] || !run->configs[i].ok)
            continue;
        for (size_t j = i; j < run->n_configs; j++)
            if (fitting__same_group(&s, &run->configs[j], &run->configs[i]))
                seen[j] = 1;
        fitting__group(&s, b, run, &run->configs[i], names, nv, fits, n, warnings);
    }
    free(seen);
    free(names);
    free(bounds);
    free(formula);
    return 0;
}

/* ---- predictions for configurations not measured yet ---------------------- */

/* 1 when every group pair of the fit is an axis value of the configuration. */
static int fitting__in_group(const dm_fit_result *fit, const dm_kv *params, size_t n)
{
    for (size_t i = 0; i < fit->n_group; i++) {
        const char *v = dm_kv_get(params, n, fit->group[i].key);
        if (!v || !fit->group[i].value || strcmp(v, fit->group[i].value) != 0)
            return 0;
    }
    return 1;
}

/* The counter `name` stored for configuration `key` in the first of runs
 * that has a usable value; NaN when none has. */
static double fitting__stored_counter(const dm_run_result *runs, size_t n_runs, const char *key,
                                      const char *name)
{
    for (size_t k = 0; k < n_runs; k++)
        for (size_t i = 0; i < runs[k].n_configs; i++) {
            const dm_config_result *c = &runs[k].configs[i];
            const dm_counter_result *r = c->ok && strcmp(c->key, key) == 0
                                         ? dm_config_counter(c, name) : NULL;
            double v = r ? fitting__counter_value(&runs[k], r) : NAN;
            if (isfinite(v))
                return v;
        }
    return NAN;
}

/* Parses the fit's formula with every name that is not one of its fitted
 * parameters as a variable (the names are parsed once with none, so every
 * name is first a parameter).  *vars points into the first parse's names,
 * which stay valid until *names_owner is freed. */
static int fitting__parse_fit(const dm_fit_result *fit, formula **f, formula **names_owner,
                              const char ***vars, size_t *nv, dm_str *why)
{
    char *expr = NULL;   /* the expression without its bound clauses */
    fit_bound *bounds = NULL;
    size_t n_bounds = 0;
    int rc = bounds_split(fit->formula, &expr, &bounds, &n_bounds, why);
    bounds_free(bounds, n_bounds);
    rc = rc ? rc : formula_parse(expr, NULL, 0, names_owner, why);
    for (size_t j = 0; rc == 0 && j < formula_n_params(*names_owner); j++) {
        const char *nm = formula_param_name(*names_owner, j);
        size_t k = 0;
        while (k < fit->n_params && strcmp(fit->params[k].name, nm) != 0)
            k++;
        if (k == fit->n_params) {
            DM_VEC_PUSH(*vars, *nv, nm);
        }
    }
    rc = rc ? rc : formula_parse(expr, *vars, *nv, f, why);
    free(expr);
    return rc;
}

/* Values of the variables for the configuration: its axes, else counters
 * stored for its key.  DM_ERR_NOTFOUND naming the first one without. */
static int fitting__variables(const char *const *vars, size_t nv, const dm_kv *params,
                              size_t n_params, const char *key, const dm_run_result *runs,
                              size_t n_runs, double *x, dm_str *why)
{
    for (size_t v = 0; v < nv; v++) {
        x[v] = fitting__param_value(params, n_params, vars[v]);
        if (!isfinite(x[v]))
            x[v] = fitting__stored_counter(runs, n_runs, key, vars[v]);
        if (!isfinite(x[v])) {
            dm_str_printf(why, "'%s' is neither an axis of the configuration nor a counter "
                          "stored for it", vars[v]);
            return DM_ERR_NOTFOUND;
        }
    }
    return 0;
}

int fitting_predict(const dm_fit_result *fit, const dm_kv *params, size_t n_params,
                    const char *key, const dm_run_result *runs, size_t n_runs, double *value,
                    dm_str *why)
{
    *value = NAN;
    if (!fitting__in_group(fit, params, n_params)) {
        dm_str_printf(why, "the configuration is not in the fit's group");
        return DM_ERR_NOTFOUND;
    }
    formula *f = NULL, *names = NULL;
    const char **vars = NULL;
    size_t nv = 0;
    int rc = fit->formula ? fitting__parse_fit(fit, &f, &names, &vars, &nv, why) : DM_ERR_PARSE;
    double *x = dm_xcalloc(nv + 1, sizeof *x), *p = dm_xcalloc(fit->n_params + 1, sizeof *p);
    rc = rc ? rc : fitting__variables(vars, nv, params, n_params, key, runs, n_runs, x, why);
    for (size_t j = 0; rc == 0 && j < fit->n_params; j++) {
        long k = formula_param_index(f, fit->params[j].name);
        if (k >= 0)
            p[k] = fit->params[j].value;
    }
    if (rc == 0) {
        *value = formula_eval(f, x, p, NULL);
        if (!(isfinite(*value) && *value > 0.0)) {
            dm_str_printf(why, "the model predicts %g, not a positive time", *value);
            rc = DM_ERR_NUMERIC;
        }
    }
    free(x);
    free(p);
    free(vars);
    formula_free(f);
    formula_free(names);
    return rc;
}

/* Every counter and axis name: the names a formula reads as variables. */
static const char **fitting__known_names(size_t *n)
{
    *n = counters_count() + axes_count();
    const char **names = dm_xcalloc(*n + 1, sizeof *names);
    for (size_t i = 0; i < counters_count(); i++)
        names[i] = counters_info_at(i)->name;
    for (size_t i = 0; i < axes_count(); i++)
        names[counters_count() + i] = axes_at(i)->name;
    return names;
}

/* A parameter name that is probably a misspelled variable: NULL, or the
 * counter or axis it is close to. */
static const char *fitting__misspelled(const char *param, const char **known, size_t n)
{
    if (strlen(param) < 4 || counters_find(param) || axes_find(param))
        return NULL;
    return dm_closest(param, known, n);
}

/* Checks one model of the sweep (see fitting_check_models). */
static int fitting__check_model(const sweep *s, const sweep_model *m, const char **known,
                                size_t n_known, dm_str *err)
{
    if (!m->formula) {
        if (models_builtin_find(m->name))
            return 0;
        dm_str_printf(err, "%s:%d: models: '%s' is not a built-in model and has no formula",
                      s->path, m->line, m->name);
        return DM_ERR_UNKNOWN;
    }
    char *expr = NULL;
    fit_bound *bounds = NULL;
    size_t nb = 0;
    formula *f = NULL;
    dm_str why = {0};
    int rc = bounds_split(m->formula, &expr, &bounds, &nb, &why);
    rc = rc ? rc : formula_parse(expr, NULL, 0, &f, &why);
    for (size_t j = 0; rc == 0 && j < formula_n_params(f); j++) {
        const char *p = formula_param_name(f, j), *near = fitting__misspelled(p, known, n_known);
        if (near) {
            dm_str_printf(&why, "'%s' would be a fitted parameter; did you mean '%s'? (names "
                          "that are not counters or axes are parameters)", p, near);
            rc = DM_ERR_UNKNOWN;
        }
    }
    if (rc)
        dm_str_printf(err, "%s:%d: models: %s: %s", s->path, m->line, m->name, dm_str_get(&why));
    formula_free(f);
    bounds_free(bounds, nb);
    free(expr);
    dm_str_free(&why);
    return rc;
}

int fitting_check_models(const sweep *s, dm_str *err)
{
    size_t n = 0;
    const char **known = fitting__known_names(&n);
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < s->n_models; i++)
        rc = fitting__check_model(s, &s->models[i], known, n, err);
    free(known);
    return rc;
}
