/* cmd_fit.c — `dmbench fit DIR | --data FILE.csv [--model NAME | --formula F] ...`. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "run/fitting.h"
#include "store/store.h"
#include "models/catalog.h"
#include "models/fit_data.h"
#include "reports/report.h"

#include <cjson/cJSON.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct fit_args {
    const char *dir, *data, *model, *formula, *response, *group_by;
    fit_loss loss;
    int json;
} fit_args;

/* --loss huber|cauchy|none (unset: the fit's default). */
static int fit__loss(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    static const fit_loss loss[] = { FIT_LOSS_HUBER, FIT_LOSS_CAUCHY, FIT_LOSS_NONE };
    int i = 0;
    if (cli_option_choice(opt, v, &i, err) != 0)
        return DM_ERR_ARG;
    ((fit_args *)args)->loss = loss[i];
    return 0;
}

static const char *const fit__losses[] = { "huber", "cauchy", "none", NULL };

const cli_option cli_fit_options[] = {
    CLI_STRING("data", fit_args, data, "FILE.csv",
               "fit a CSV (one column per variable) instead of a run"),
    CLI_STRING("model", fit_args, model, "NAME",
               "a built-in model (dmbench list models) [default pipeline-linear]"),
    CLI_STRING("formula", fit_args, formula, "F",
               "a formula such as \"a + b*tess_level^p; a >= 0\" (docs/models.md)"),
    CLI_STRING("response", fit_args, response, "NAME",
               "the measured quantity to fit [default the model's, or WallTime]"),
    CLI_STRING("group-by", fit_args, group_by, "A,B",
               "one fit per value of these axes (run directories only)"),
    { .name = "loss", .kind = CLI_OPT_CHOICE, .value_name = "LOSS", .choices = fit__losses,
      .parse = fit__loss, .help = "robust loss of the fit" },
    CLI_BOOL("json", fit_args, json, "print the fits as JSON"),
    CLI_OPT_END
};

/* A typo must not become a free parameter or a bogus group (exit 2 with
 * a suggestion): formula names close to a counter or axis, --group-by
 * keys that are not axes, a --response of a run that is not a counter or
 * axis (a CSV's columns are checked when it is read).  -1 to go on. */
static int fit__check_names(const fit_args *a)
{
    dm_str why = {0};
    int rc = a->formula ? fitting_check_formula(a->formula, &why) : 0;
    char *gb = a->group_by ? dm_xstrdup(a->group_by) : NULL, *save = NULL;
    for (char *t = gb ? strtok_r(gb, ",", &save) : NULL; rc == 0 && t; t = strtok_r(NULL, ",", &save))
        rc = fitting_check_name(t, 1, &why);
    if (rc == 0 && a->response && a->dir)
        rc = fitting_check_name(a->response, 0, &why);
    free(gb);
    int code = rc ? cli_usage_error("fit: %s", dm_str_get(&why)) : -1;
    dm_str_free(&why);
    return code;
}

/* Checks the combination of arguments; -1 to go on, else an exit code. */
static int fit__check(fit_args *a, int argc, char **argv)
{
    if (argc > 1)
        return cli_usage_error("fit: only one results directory may be given");
    a->dir = argc ? argv[0] : NULL;
    if (!a->dir == !a->data)
        return cli_usage_error("fit: give a results directory or --data FILE.csv (one of them)");
    if (a->model && a->formula)
        return cli_usage_error("fit: give --model or --formula, not both");
    if (a->model && !models_builtin_find(a->model)) {
        const char *names[64];
        size_t n = 0;
        for (; n < models_builtin_count() && n < 64; n++)
            names[n] = models_builtin_at(n)->name;
        dm_str s = {0};
        dm_str_printf(&s, "fit: unknown model '%s'", a->model);
        dm_str_suggest(&s, a->model, names, n, "models");
        int rc = cli_usage_error("%s", dm_str_get(&s));
        dm_str_free(&s);
        return rc;
    }
    if (a->data && a->group_by)
        return cli_usage_error("fit: --group-by needs a results directory (a CSV has no axes)");
    return fit__check_names(a);
}

/* A fit statistic as printf would with fmt, or "unavailable" when it is
 * not finite (too few points, no residual degrees of freedom): a number
 * that is not one is never printed. */
static const char *fit__num(char buf[32], const char *fmt, double v)
{
    if (!isfinite(v))
        return "unavailable";
    snprintf(buf, 32, fmt, v);
    return buf;
}

static void fit__print(const dm_fit_result *f)
{
    char b1[32], b2[32], b3[32], b4[32];
    printf("model %s: %s = %s", f->model, f->response ? f->response : "?", f->formula ? f->formula : "");
    for (size_t i = 0; i < f->n_group; i++)
        printf("%s%s=%s", i ? ", " : "  [", f->group[i].key, f->group[i].value);
    printf("%s\n", f->n_group ? "]" : "");
    for (size_t i = 0; i < f->n_params; i++)
        printf("  %-10s = %14s  ± %s\n", f->params[i].name, fit__num(b1, "%.6g", f->params[i].value),
               fit__num(b2, "%.3g", f->params[i].stderr_));
    printf("  R² %s  RMSE %s  MAPE %s  CV-MAPE %s  points %d (excluded %d)  %s\n",
           fit__num(b1, "%.5f", f->r2), fit__num(b2, "%.4g", f->rmse), fit__num(b3, "%.2f%%", f->mape),
           fit__num(b4, "%.2f%%", f->cv_mape), f->n_points, f->n_excluded,
           f->termination ? f->termination : "");
    if (isinf(f->condition))
        printf("  condition: infinite (rank deficient)\n");
    else if (f->condition > 0.0)
        printf("  condition %.3g%s\n", f->condition,
               f->condition > FIT_ILL_CONDITIONED ? " (ill-conditioned)" : "");
    for (size_t i = 0; i < f->n_warnings; i++)
        printf("  warning: %s\n", f->warnings[i]);
}

/* The response of the fit asked for: --response, else WallTime for a
 * --formula, else the built-in model's. */
static const char *fit__response(const fit_args *a, const models_builtin *b)
{
    return a->response ? a->response : a->formula ? "WallTime" : b->response;
}

static int fit__from_csv(const fit_args *a, dm_fit_result **fits, size_t *n, dm_str *err)
{
    fit_data d = {0};
    const models_builtin *b = models_builtin_find(a->model ? a->model : "pipeline-linear");
    const char *formula = a->formula ? a->formula : b->formula;
    const char *response = fit__response(a, b);
    fit_desc desc;
    int rc = fit_data_load_csv(a->data, &d, err);
    rc = rc ? rc : fit_data_desc(&d, formula, response, &desc, err);
    if (rc == 0) {
        desc.model = a->model ? a->model : a->formula ? "formula" : b->name;
        desc.loss = a->loss;
        if (!a->formula) {
            desc.bounds = b->bounds;
            desc.n_bounds = b->n_bounds;
        }
        *fits = dm_xcalloc(1, sizeof **fits);
        rc = fit_run(&desc, *fits, err);
        *n = rc == 0;
    }
    fit_data_free(&d);
    return rc;
}

static int fit__from_dir(const fit_args *a, dm_fit_result **fits, size_t *n, dm_str *warn, dm_str *err)
{
    dm_run_result run = {0};
    int rc = cli_load_run(a->dir, &run, err);
    char *groups[16];
    size_t ng = 0;
    char *gb = a->group_by ? dm_xstrdup(a->group_by) : NULL;
    for (char *t = gb ? strtok(gb, ",") : NULL; t && ng < 16; t = strtok(NULL, ","))
        groups[ng++] = t;
    fitting_spec spec = { .name = a->model ? a->model : a->formula ? "formula" : "pipeline-linear",
                          .formula = a->formula, .response = a->response,
                          .group_by = (const char *const *)groups, .n_group_by = ng, .loss = a->loss };
    const models_builtin *b = a->formula ? NULL : models_builtin_find(spec.name);
    /* a counter the model is about (fragment-trips: LoopTrips) is not
     * dropped like an axis a technique does not read: refused */
    char *req = b && b->requires ? dm_xstrdup(b->requires) : NULL, *save = NULL;
    for (char *t = req ? strtok_r(req, " ", &save) : NULL; rc == 0 && t; t = strtok_r(NULL, " ", &save))
        if (!dm_run_has_counter(&run, t)) {
            dm_str_printf(err, "%s has no counter '%s', which model %s is about: add %s to measure.counters of "
                          "its sweep and run it again (docs/counters.md)", a->dir, t, spec.name, t);
            rc = DM_ERR_NOTFOUND;
        }
    free(req);
    /* a response the run never recorded: nothing to fit, and the sweep
     * option that adds it (a response that is an axis is checked by
     * fitting_run) */
    const char *resp = fit__response(a, models_builtin_find(a->model ? a->model : "pipeline-linear"));
    int axis = 0;
    for (size_t i = 0; rc == 0 && i < run.n_configs && !axis; i++)
        axis = dm_kv_get(run.configs[i].params, run.configs[i].n_params, resp) != NULL;
    if (rc == 0 && !axis && !dm_run_has_counter(&run, resp)) {
        dm_str_printf(err, "%s has no counter '%s'", a->dir, resp);
        if (!a->response)
            dm_str_printf(err, a->formula ? " (a formula's response unless --response names another)"
                                          : " (the response of model %s)", spec.name);
        dm_str_printf(err, ": add %s to measure.counters of its sweep and run it again (docs/counters.md)", resp);
        rc = DM_ERR_NOTFOUND;
    }
    if (rc == 0)
        rc = fitting_run(&spec, &run, fits, n, warn, err);
    free(gb);
    dm_run_free(&run);
    return rc;
}

int cli_fit(const cli_command *self, int argc, char **argv)
{
    fit_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
    if (rc < 0)
        rc = fit__check(&a, argc, argv);
    if (rc >= 0)
        return rc;
    dm_fit_result *fits = NULL;
    size_t n = 0;
    dm_str warn = {0}, err = {0};
    rc = a.data ? fit__from_csv(&a, &fits, &n, &err) : fit__from_dir(&a, &fits, &n, &warn, &err);
    if (rc != 0) {
        fprintf(stderr, "dmbench: error: fit: %s\n", dm_str_get(&err));
    } else if (a.json) {
        cJSON *arr = cJSON_CreateArray();
        for (size_t i = 0; i < n; i++)
            cJSON_AddItemToArray(arr, report_fit_to_json(&fits[i]));
        char *s = cJSON_Print(arr);
        puts(s);
        free(s);
        cJSON_Delete(arr);
    } else {
        for (size_t i = 0; i < n; i++)
            fit__print(&fits[i]);
    }
    if (warn.len)
        fprintf(stderr, "%s", dm_str_get(&warn));
    for (size_t i = 0; i < n; i++)
        dm_fit_result_free(&fits[i]);
    free(fits);
    dm_str_free(&warn);
    dm_str_free(&err);
    if (rc == 0 && n == 0)
        return DM_EXIT_FAILED;     /* nothing could be fitted: a failed check */
    return dm_exit_from_error(rc);
}
