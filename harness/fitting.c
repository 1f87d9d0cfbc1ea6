/* fitting.c — from results to fit_desc (see fitting.h). */
#include "fitting.h"
#include "core/dm_error.h"
#include "models/catalog.h"

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
                *names = dm_xrealloc(*names, (*n + 1) * sizeof **names);
                (*names)[(*n)++] = nm;
            }
        }
    }
}

/* Numeric value of a variable in a configuration, NaN when absent. */
static double fitting__value(const dm_run_result *run, const dm_config_result *c, const char *name)
{
    const dm_counter_result *r = dm_config_counter(c, name);
    if (r) {
        int partial = r->partial || (strcmp(name, "GPUTime") == 0 && run->timer_verdict &&
                                     strcmp(run->timer_verdict, "full") != 0);
        return r->available && !partial ? r->value : NAN;
    }
    const char *v = dm_kv_get(c->params, c->n_params, name);
    int w, h;
    if (v && strcmp(name, "resolution") == 0 && sscanf(v, "%dx%d", &w, &h) == 2)
        return (double)w * h;
    char *end = NULL;
    double x = v ? strtod(v, &end) : NAN;
    return v && end && *end == '\0' ? x : NAN;
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
        *fits = dm_xrealloc(*fits, (*nf + 1) * sizeof **fits);
        (*fits)[(*nf)++] = fr;
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
    return 0;
}
