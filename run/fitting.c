/* fitting.c — from results to fit_desc (see fitting.h). */
#include "fitting.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "models/bounds.h"
#include "models/catalog.h"
#include "models/formula.h"
#include "sweep/sweep.h"
#include "techniques/axes.h"
#include "techniques/render.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The share of a frame's evaluations x primitives that llvmpipe's vertex
 * walk covers when the frame's patches are drawn in calls of at most
 * per_call: sum over calls of (call's patches / patches)^2, each call's
 * evaluations and primitives taken in proportion to its patches. */
double fitting_call_share(size_t patches, size_t per_call)
{
    if (!patches || !per_call || per_call >= patches)
        return 1.0;
    double q = (double)(patches / per_call), r = (double)(patches % per_call), c = (double)per_call,
           n = (double)patches;
    return (q * c * c + r * r) / (n * n);
}

/* FITTING_TESS_WALK of a configuration: its TessWalkCalls (`calls`, the
 * sum measured per draw call) when it has one; else from its
 * TESInvocations, ClippingOutputPrimitives and ClippingInputPrimitives
 * (tes, prims, in; in NaN when not counted) and its axes: tes x prims x
 * the share of its draw calls (render_patch_calls), each call's counts in
 * proportion to its patches; 0 without evaluations or when the clipper
 * passed every primitive unchanged (prims == in: no vertex outside the
 * view, so llvmpipe's draw module emits the primitives without its
 * pipeline stages and never walks); NaN when a count is missing or the
 * calls cannot be told. */
static double fitting__tess_walk(const dm_kv *params, size_t n, double calls, double tes, double prims, double in)
{
    if (isfinite(calls))
        return calls;
    if (!isfinite(tes) || !isfinite(prims))
        return NAN;
    if (tes == 0 || prims == 0 || (isfinite(in) && in == prims))
        return 0;
    size_t patches = 0, per_call = 0;
    dm_str log = {0};
    int rc = render_patch_calls(params, n, &patches, &per_call, &log);
    dm_str_free(&log);
    return rc ? NAN : tes * prims * fitting_call_share(patches, per_call);
}

/* 1 when a formula reads id as a variable wherever the run has it: a
 * counter, an axis or FITTING_TESS_WALK. */
static int fitting__is_variable(const char *id)
{
    return axes_find(id) || counters_find(id) || strcmp(id, FITTING_TESS_WALK) == 0;
}

static int fitting__has_name(const char *const *names, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return 1;
    return 0;
}

/* Collects variable names: counters then params, each once; then
 * FITTING_TESS_WALK when the run has both counts it is made of. */
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
    if (fitting__has_name(*names, *n, "TESInvocations") && fitting__has_name(*names, *n, "ClippingOutputPrimitives")
        && !fitting__has_name(*names, *n, FITTING_TESS_WALK)) {
        DM_VEC_PUSH(*names, *n, FITTING_TESS_WALK);
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
    if (strcmp(name, FITTING_TESS_WALK) == 0)
        return fitting__tess_walk(c->params, c->n_params, fitting__value(run, c, FITTING_TESS_WALK_CALLS),
                                  fitting__value(run, c, "TESInvocations"),
                                  fitting__value(run, c, "ClippingOutputPrimitives"),
                                  fitting__value(run, c, "ClippingInputPrimitives"));
    const dm_counter_result *r = dm_config_counter(c, name);
    return r ? fitting__counter_value(run, r) : fitting__param_value(c->params, c->n_params, name);
}

char *fitting_variant(const dm_kv *params, size_t n)
{
    const char *t = dm_kv_get(params, n, "technique");
    dm_str v = {0};
    dm_str_cat(&v, t ? t : "?");
    for (size_t i = 0; i < n; i++) {
        const axis_info *a = axes_find(params[i].key);
        int shader = a && !a->scene && (a->kind == AXIS_ENUM || (a->kind == AXIS_INT && params[i].value &&
                                                                 strcmp(params[i].value, "auto") == 0));
        if (shader || (a && strcmp(a->name, "virtual_texture") == 0))
            dm_str_printf(&v, " %s=%s", params[i].key, params[i].value ? params[i].value : "");
    }
    return dm_str_take(&v);
}

/* The value of group key `name` for a configuration: FITTING_VARIANT is
 * computed (malloc'd, *owned set), any other key is the axis value. */
static const char *fitting__group_value(const dm_kv *params, size_t n, const char *name, char **owned)
{
    *owned = NULL;
    if (strcmp(name, FITTING_VARIANT) != 0)
        return dm_kv_get(params, n, name);
    return *owned = fitting_variant(params, n);
}

static int fitting__same_group(const fitting_spec *s, const dm_config_result *a, const dm_config_result *b)
{
    int same = 1;
    for (size_t i = 0; same && i < s->n_group_by; i++) {
        char *ox, *oy;
        const char *x = fitting__group_value(a->params, a->n_params, s->group_by[i], &ox);
        const char *y = fitting__group_value(b->params, b->n_params, s->group_by[i], &oy);
        same = !((x || y) && (!x || !y || strcmp(x, y) != 0));
        free(ox);
        free(oy);
    }
    return same;
}

/* Says whether identifier `id` of a built-in model's term is missing (its
 * term is then dropped). */
typedef int (*fitting__missing_fn)(const char *id, const void *user);

/* Run level: a counter the run did not record (names: the run's variables). */
typedef struct fitting__names_ctx { const char **names; size_t nv; } fitting__names_ctx;

static int fitting__missing_counter(const char *id, const void *user)
{
    const fitting__names_ctx *c = user;
    for (size_t i = 0; i < c->nv; i++)
        if (strcmp(c->names[i], id) == 0)
            return 0;
    return counters_find(id) != NULL || strcmp(id, FITTING_TESS_WALK) == 0;
}

/* Group level: a variable with no finite value in any point of the group
 * (an axis the group's technique does not read, a counter it lacks), or
 * an axis no configuration of the run has. */
typedef struct fitting__group_ctx { const char **names; size_t nv, np; const double *x; } fitting__group_ctx;

static int fitting__missing_in_group(const char *id, const void *user)
{
    const fitting__group_ctx *g = user;
    for (size_t k = 0; k < g->nv; k++) {
        if (strcmp(g->names[k], id) != 0)
            continue;
        for (size_t i = 0; i < g->np; i++)
            if (isfinite(g->x[i * g->nv + k]))
                return 0;
        return 1;
    }
    return axes_find(id) != NULL;
}

/* 1 when an identifier of the term [t, t+len) is missing. */
static int fitting__term_missing(const char *t, size_t len, fitting__missing_fn missing, const void *user)
{
    for (size_t i = 0; i < len;) {
        if (!(t[i] == '_' || isalpha((unsigned char)t[i]))) {
            i++;
            continue;
        }
        size_t j = i;
        while (j < len && (t[j] == '_' || t[j] == '.' || isalnum((unsigned char)t[j])))
            j++;
        char id[64];
        if (j - i < sizeof id) {
            memcpy(id, t + i, j - i);
            id[j - i] = '\0';
            if (missing(id, user))
                return 1;
        }
        i = j;
    }
    return 0;
}

/* A built-in model (a sum of terms) without the terms that use a missing
 * identifier: a missing counter is not a parameter.  Each dropped term is
 * named in warnings (when warnings is not NULL, with `why`); bounds of
 * parameters that no longer appear are dropped too.  Returns the formula
 * (malloc'd). */
static char *fitting__drop_missing(const models_builtin *b, fitting__missing_fn missing, const void *user,
                                   fit_bound *bounds, size_t *n_bounds, const char *why, dm_str *warnings)
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
        if (!fitting__term_missing(t, len, missing, user))
            dm_str_printf(&out, "%s%.*s", dm_str_get(&out)[0] ? " + " : "", (int)len, t);
        else if (warnings)
            dm_str_printf(warnings, "model %s: term '%.*s' dropped: %s\n", b->name, (int)len, t, why);
        t = *e ? e + 1 : e;
    }
    *n_bounds = 0;
    for (size_t i = 0; i < b->n_bounds; i++)
        if (strstr(dm_str_get(&out), b->bounds[i].param))
            bounds[(*n_bounds)++] = b->bounds[i];
    return dm_str_take(&out);
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
    /* a built-in model's terms over a variable this group has no value of
     * (an axis its technique does not read) are not part of its model */
    fitting__group_ctx gc = { names, nv, np, x };
    fit_bound *gb = b ? dm_xcalloc(b->n_bounds + 1, sizeof *gb) : NULL;
    size_t ngb = 0;
    char *gf = b ? fitting__drop_missing(b, fitting__missing_in_group, &gc, gb, &ngb, NULL, NULL) : NULL;
    fit_desc d = { .model = s->name, .formula = gf && *gf ? gf : s->formula, .response = s->response,
                   .variables = names, .n_vars = nv, .x = x, .y = y, .n_points = np,
                   .point_labels = labels, .bounds = gf && *gf ? gb : b ? b->bounds : NULL,
                   .n_bounds = gf && *gf ? ngb : b ? b->n_bounds : 0, .loss = s->loss, .seed = 1,
                   .relative = s->relative };
    dm_fit_result fr = {0};
    dm_str err = {0};
    if (fit_run(&d, &fr, &err) == 0) {
        for (size_t i = 0; i < s->n_group_by; i++) {
            char *own;
            dm_kv_push(&fr.group, &fr.n_group, s->group_by[i],
                       fitting__group_value(lead->params, lead->n_params, s->group_by[i], &own));
            free(own);
        }
        DM_VEC_PUSH(*fits, *nf, fr);
    } else {
        dm_str_printf(warnings, "model %s", s->name);
        for (size_t i = 0; i < s->n_group_by; i++) {
            char *own;
            const char *gv = fitting__group_value(lead->params, lead->n_params, s->group_by[i], &own);
            dm_str_printf(warnings, " %s=%s", s->group_by[i], gv ? gv : "");
            free(own);
        }
        dm_str_printf(warnings, ": not fitted: %s\n", dm_str_get(&err));
    }
    dm_str_free(&err);
    free(gf);
    free(gb);
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
    if (b && b->group_by && s.n_group_by == 0) {   /* the model's own grouping (stage-instructions: variant) */
        s.group_by = &b->group_by;
        s.n_group_by = 1;
    }
    const char **names = NULL;
    size_t nv = 0;
    fitting__names(run, &names, &nv);
    models_builtin reduced;
    fit_bound *bounds = NULL;
    char *formula = NULL;
    if (b) {
        reduced = *b;
        bounds = dm_xcalloc(b->n_bounds + 1, sizeof *bounds);
        fitting__names_ctx nc = { names, nv };
        formula = fitting__drop_missing(b, fitting__missing_counter, &nc, bounds, &reduced.n_bounds,
                                        "the run did not record its counter", warnings);
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
    int in = 1;
    for (size_t i = 0; in && i < fit->n_group; i++) {
        char *own;
        const char *v = fitting__group_value(params, n, fit->group[i].key, &own);
        in = v && fit->group[i].value && strcmp(v, fit->group[i].value) == 0;
        free(own);
    }
    return in;
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

static double fitting__var_value(const char *id, const dm_kv *params, size_t n_params, const char *key,
                                 const dm_run_result *runs, size_t n_runs);

/* Values of the variables for the configuration: its axes, else counters
 * stored for its key.  DM_ERR_NOTFOUND naming the first one without. */
static int fitting__variables(const char *const *vars, size_t nv, const dm_kv *params,
                              size_t n_params, const char *key, const dm_run_result *runs,
                              size_t n_runs, double *x, dm_str *why)
{
    for (size_t v = 0; v < nv; v++) {
        x[v] = fitting__var_value(vars[v], params, n_params, key, runs, n_runs);
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

/* The value of variable id (an axis, else a counter stored for key in runs)
 * for a configuration; NaN when it has none. */
static double fitting__var_value(const char *id, const dm_kv *params, size_t n_params, const char *key,
                                 const dm_run_result *runs, size_t n_runs)
{
    if (strcmp(id, FITTING_TESS_WALK) == 0)
        return fitting__tess_walk(params, n_params, fitting__stored_counter(runs, n_runs, key, FITTING_TESS_WALK_CALLS),
                                  fitting__stored_counter(runs, n_runs, key, "TESInvocations"),
                                  fitting__stored_counter(runs, n_runs, key, "ClippingOutputPrimitives"),
                                  fitting__stored_counter(runs, n_runs, key, "ClippingInputPrimitives"));
    double v = fitting__param_value(params, n_params, id);
    return isfinite(v) ? v : fitting__stored_counter(runs, n_runs, key, id);
}

/* Checks the variables of dropped term [t, t+len) of fit: every one that
 * was constant over the group's configurations in train must have that
 * value here (the term's cost is then inside the other terms).  0, or
 * DM_ERR_NOTFOUND with why. */
static int fitting__dropped_ok(const dm_fit_result *fit, const dm_run_result *train, const char *t, size_t len,
                               const dm_kv *params, size_t n_params, const char *key,
                               const dm_run_result *runs, size_t n_runs, dm_str *why)
{
    for (size_t i = 0; i < len;) {
        size_t j = i;
        while (j < len && (t[j] == '_' || t[j] == '.' || isalnum((unsigned char)t[j])))
            j++;
        char id[64];
        snprintf(id, sizeof id, "%.*s", (int)(j - i), t + i);
        i = j > i ? j : i + 1;
        if (!fitting__is_variable(id))
            continue;
        double lo = INFINITY, hi = -INFINITY;
        for (size_t k = 0; k < train->n_configs; k++) {
            const dm_config_result *c = &train->configs[k];
            if (!c->ok || !fitting__in_group(fit, c->params, c->n_params))
                continue;
            double v = fitting__var_value(id, c->params, c->n_params, c->key, train, 1);
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        double here = fitting__var_value(id, params, n_params, key, runs, n_runs);
        if (lo == hi && !(fabs(here - lo) <= 1e-9 * fabs(lo))) {
            dm_str_printf(why, "the fitted runs never varied %s in this group (%g), this configuration has %g: "
                          "they cannot tell the cost of '%.*s'", id, lo, here, (int)len, t);
            return DM_ERR_NOTFOUND;
        }
    }
    return 0;
}

/* The top-level term of formula text f that names identifier id, as
 * [*t, *t + *len); 0 when none does. */
static int fitting__term_of(const char *f, const char *id, const char **t, size_t *len)
{
    size_t il = strlen(id);
    for (const char *s = f; *s;) {
        const char *e = s;
        for (int depth = 0; *e && !(depth == 0 && (*e == '+' || *e == ';')); e++)
            depth += (*e == '(') - (*e == ')');
        for (const char *p = s; p + il <= e; p++)
            if (strncmp(p, id, il) == 0 && (p == s || !(isalnum((unsigned char)p[-1]) || p[-1] == '_')) &&
                !(isalnum((unsigned char)p[il]) || p[il] == '_')) {
                while (*s == ' ')
                    s++;
                while (e > s && e[-1] == ' ')
                    e--;
                *t = s;
                *len = (size_t)(e - s);
                return 1;
            }
        if (*e != '+')
            break;
        s = e + 1;
    }
    return 0;
}

int fitting_predict_dropped(const dm_fit_result *fit, const dm_run_result *train, const dm_kv *params,
                            size_t n_params, const char *key, const dm_run_result *runs, size_t n_runs,
                            double *value, dm_str *why)
{
    formula *f = NULL, *names = NULL;
    const char **vars = NULL;
    size_t nv = 0;
    *value = NAN;
    int rc = fit->formula ? fitting__parse_fit(fit, &f, &names, &vars, &nv, why) : DM_ERR_PARSE;
    dm_fit_result ext = *fit;   /* shallow, with the dropped parameters added as 0 */
    ext.params = dm_xcalloc(fit->n_params + nv + 1, sizeof *ext.params);
    memcpy(ext.params, fit->params, fit->n_params * sizeof *ext.params);
    for (size_t v = 0; rc == 0 && v < nv; v++) {
        const char *t = NULL;
        size_t len = 0;
        if (fitting__is_variable(vars[v]) || !fitting__term_of(fit->formula, vars[v], &t, &len))
            continue;
        rc = fitting__dropped_ok(fit, train, t, len, params, n_params, key, runs, n_runs, why);
        ext.params[ext.n_params++] = (dm_fit_param){ (char *)vars[v], 0.0, NAN };
    }
    rc = rc ? rc : fitting_predict(&ext, params, n_params, key, runs, n_runs, value, why);
    free(ext.params);
    free(vars);
    formula_free(f);
    formula_free(names);
    return rc;
}

/* Every counter and axis name: the names a formula reads as variables. */
static const char **fitting__known_names(size_t *n)
{
    *n = counters_count() + axes_count() + 1;
    const char **names = dm_xcalloc(*n + 1, sizeof *names);
    names[*n - 1] = FITTING_TESS_WALK;
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
    if (strlen(param) < 4 || counters_find(param) || axes_find(param) || strcmp(param, FITTING_TESS_WALK) == 0)
        return NULL;
    return dm_closest(param, known, n);
}

int fitting_check_formula(const char *text, dm_str *why)
{
    size_t n_known = 0;
    const char **known = fitting__known_names(&n_known);
    char *expr = NULL;
    fit_bound *bounds = NULL;
    size_t nb = 0;
    formula *f = NULL;
    int rc = bounds_split(text, &expr, &bounds, &nb, why);
    rc = rc ? rc : formula_parse(expr, NULL, 0, &f, why);
    for (size_t j = 0; rc == 0 && j < formula_n_params(f); j++) {
        const char *p = formula_param_name(f, j), *near = fitting__misspelled(p, known, n_known);
        if (near) {
            dm_str_printf(why, "'%s' would be a fitted parameter; did you mean '%s'? (names "
                          "that are not counters or axes are parameters)", p, near);
            rc = DM_ERR_UNKNOWN;
        }
    }
    formula_free(f);
    bounds_free(bounds, nb);
    free(expr);
    free(known);
    return rc;
}

/* Checks one model of the sweep (see fitting_check_models). */
static int fitting__check_model(const sweep *s, const sweep_model *m, dm_str *err)
{
    if (!m->formula) {
        if (models_builtin_find(m->name))
            return 0;
        dm_str_printf(err, "%s:%d: models: '%s' is not a built-in model and has no formula",
                      s->path, m->line, m->name);
        return DM_ERR_UNKNOWN;
    }
    dm_str why = {0};
    int rc = fitting_check_formula(m->formula, &why);
    if (rc)
        dm_str_printf(err, "%s:%d: models: %s: %s", s->path, m->line, m->name, dm_str_get(&why));
    dm_str_free(&why);
    return rc;
}

int fitting_check_name(const char *name, int axis_only, dm_str *why)
{
    if (axes_find(name) || (!axis_only && counters_find(name)) ||
        (axis_only && strcmp(name, FITTING_VARIANT) == 0))
        return 0;
    size_t n = 0;
    const char **known = fitting__known_names(&n);
    if (axis_only) {   /* the axes and the variant */
        for (size_t i = 0; i < axes_count(); i++)
            known[i] = axes_at(i)->name;
        known[axes_count()] = FITTING_VARIANT;
        n = axes_count() + 1;
    }
    dm_str_printf(why, "unknown %s '%s'", axis_only ? "--group-by axis" : "--response", name);
    dm_str_suggest(why, name, known, n, axis_only ? "axes" : "counters and axes");
    free(known);
    return DM_ERR_UNKNOWN;
}

int fitting_check_models(const sweep *s, dm_str *err)
{
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < s->n_models; i++)
        rc = fitting__check_model(s, &s->models[i], err);
    return rc;
}
