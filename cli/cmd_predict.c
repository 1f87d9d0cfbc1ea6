/* cmd_predict.c — `dmbench predict SWEEP --from RUN[,RUN...]`: each
 * configuration's Instructions, stage shares and WallTime, predicted from
 * per-variant costs fitted to measured runs (docs/models.md, "Prediction").
 *
 * The invocation counts of the new configurations are read exactly, with
 * one frame each of a statistics pass in this process (no Valgrind, no
 * timing); the costs per invocation come from the stage-instructions fits
 * of the runs, one per shader variant; frame time from the
 * time-from-instructions fit.  A configuration of a variant the runs never
 * measured is listed with the reason, never guessed. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "run/env.h"
#include "run/fitting.h"
#include "run/gl_context.h"
#include "run/measure.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct predict_args {
    const char *from;
    int allow_env_mismatch;
} predict_args;

const cli_option cli_predict_options[] = {
    CLI_STRING("from", predict_args, from, "RUN[,RUN...]",
               "run directories whose configurations the models are fitted to (required)"),
    CLI_BOOL("allow-env-mismatch", predict_args, allow_env_mismatch,
             "use runs of another machine fingerprint (their instruction counts may not hold here)"),
    CLI_OPT_END
};

/* What the fits read, by counter, and the invocation counts measured here. */
static const char *const predict__needed[] = {"Instructions", "VSInvocations", "TESInvocations",
                                              "ClippingOutputPrimitives", "FSInvocations"};
/* TCSPatches is read too, for stage-instructions' patches term; a fit
 * from runs without it has dropped that term and ignores it. */
static const char *const predict__counts[] = {"VSInvocations", "TESInvocations", "ClippingOutputPrimitives",
                                              "FSInvocations", "TCSPatches"};
static const char *const predict__stages[] = {"GeometryInstructions", "RasterInstructions",
                                              "FragmentInstructions"};
#define PREDICT__N_COUNTS 5

typedef struct predict_fits {
    const dm_run_result *train;   /* the pooled runs */
    dm_fit_result *instr, *stage[3], *time;
    size_t n_instr, n_stage[3], n_time;
} predict_fits;

/* 1 when some ok configuration of run has counter name available. */
static int predict__has(const dm_run_result *run, const char *name)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_counter_result *r = run->configs[i].ok ? dm_config_counter(&run->configs[i], name) : NULL;
        if (r && r->available)
            return 1;
    }
    return 0;
}

/* Refuses (exit 2) a run without a counter the fits need, naming it and
 * the sweep option that adds it; -1 to go on. */
static int predict__check_counters(const dm_run_result *runs, size_t n, char **dirs)
{
    for (size_t k = 0; k < n; k++)
        for (size_t i = 0; i < sizeof predict__needed / sizeof *predict__needed; i++)
            if (!predict__has(&runs[k], predict__needed[i]))
                return cli_usage_error("predict: %s has no counter '%s': add %s to measure.counters of "
                                       "its sweep and run it again (docs/models.md)", dirs[k],
                                       predict__needed[i], predict__needed[i]);
    return -1;
}

/* Refuses (exit 2) runs of another machine fingerprint, naming the keys
 * that differ (the fingerprint's keys but LP_NUM_THREADS), unless allowed;
 * -1 to go on. */
static int predict__check_env(const dm_run_result *runs, size_t n, char **dirs, int allow)
{
    dm_str err = {0}, diff = {0};
    gl_context *gl = NULL;
    dm_kv *here = NULL;
    size_t nh = 0;
    int gl_ok = gl_context_create(NULL, &gl, &err) == 0;
    env_collect(&here, &nh, gl_ok);
    gl_context_destroy(gl);
    for (size_t k = 0; k < n; k++)
        for (const char *const *key = env_fingerprint_keys(); *key; key++) {
            if (strcmp(*key, "lp_num_threads") == 0)
                continue;   /* a setting of the timed runs; the counting child always uses 0 */
            const char *a = dm_kv_get(runs[k].environment, runs[k].n_environment, *key);
            const char *b = dm_kv_get(here, nh, *key);
            if ((a || b) && (!a || !b || strcmp(a, b) != 0))
                dm_str_printf(&diff, "%s%s: %s (run %s, here %s)", diff.len ? "; " : "", dirs[k], *key,
                              a ? a : "none", b ? b : "none");
        }
    int rc = -1;
    if (diff.len && !allow)
        rc = cli_usage_error("predict: runs of another machine fingerprint: %s; their costs may not hold "
                             "here (--allow-env-mismatch uses them anyway)", dm_str_get(&diff));
    else if (diff.len)
        fprintf(stderr, "dmbench: predict: warning: machine fingerprints differ: %s\n", dm_str_get(&diff));
    dm_kv_free(here, nh);
    dm_str_free(&diff);
    dm_str_free(&err);
    return rc;
}

/* The union of the runs' configurations (shallow: the runs own them). */
static dm_run_result predict__union(const dm_run_result *runs, size_t n)
{
    dm_run_result u = runs[0];
    u.configs = NULL;
    u.n_configs = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t i = 0; i < runs[k].n_configs; i++)
            DM_VEC_PUSH(u.configs, u.n_configs, runs[k].configs[i]);
    return u;
}

static void predict__fit(const dm_run_result *u, const char *model, const char *response, dm_fit_result **fits,
                         size_t *n)
{
    fitting_spec spec = { .name = model, .response = response };
    dm_str warn = {0}, err = {0};
    fitting_run(&spec, u, fits, n, &warn, &err);
    dm_str_free(&warn);
    dm_str_free(&err);
}

/* The fit of `variant` among fits, or NULL. */
static const dm_fit_result *predict__of(const dm_fit_result *fits, size_t n, const char *variant)
{
    for (size_t i = 0; i < n; i++)
        if (fits[i].n_group == 1 && strcmp(fits[i].group[0].value, variant) == 0)
            return &fits[i];
    return NULL;
}

/* Predicts fit's response for configuration pc whose counts are in c
 * (train: the runs the fit was made from). */
static int predict__one(const dm_fit_result *fit, const dm_run_result *train, const plan_config *pc,
                        dm_config_result *c, double *v, dm_str *why)
{
    dm_run_result one = { .configs = c, .n_configs = 1 };
    return fitting_predict_dropped(fit, train, pc->params, pc->n_params, pc->key, &one, 1, v, why);
}

/* One line of the table, or the reason the configuration is unpredictable. */
static void predict__config(const predict_fits *f, const plan_config *pc, const double *counts, dm_str *unpred)
{
    char *variant = fitting_variant(pc->params, pc->n_params);
    dm_config_result c = { .key = (char *)pc->key, .ok = 1 };
    dm_counter_result cr[PREDICT__N_COUNTS];
    memset(cr, 0, sizeof cr);
    for (size_t k = 0; k < PREDICT__N_COUNTS; k++)
        cr[k] = (dm_counter_result){ .name = (char *)predict__counts[k], .available = isfinite(counts[k]),
                                     .value = counts[k] };
    c.counters = cr;
    c.n_counters = PREDICT__N_COUNTS;
    const dm_fit_result *fi = predict__of(f->instr, f->n_instr, variant);
    double instr = NAN;
    dm_str why = {0};
    if (!fi)
        dm_str_printf(&why, "variant '%s' was never measured by the runs", variant);
    else
        predict__one(fi, f->train, pc, &c, &instr, &why);
    if (!isfinite(instr)) {
        dm_str_printf(unpred, "  %s  %s: %s\n", pc->key, pc->scene, dm_str_get(&why));
        dm_str_free(&why);
        free(variant);
        return;
    }
    double ei = 2 * fi->cv_mape / 100, part[3] = {NAN, NAN, NAN};
    printf("%s  %-40s %-28s %12.6g [%.6g, %.6g]", pc->key, pc->scene, variant, instr, instr * (1 - ei),
           instr * (1 + ei));
    for (int s = 0; s < 3; s++) {
        const dm_fit_result *fs = predict__of(f->stage[s], f->n_stage[s], variant);
        if (fs)
            predict__one(fs, f->train, pc, &c, &part[s], &why);
    }
    double sum = part[0] + part[1] + part[2];
    if (isfinite(sum) && sum > 0)
        printf("  geometry %2.0f %% raster %2.0f %% fragment %2.0f %%", 100 * part[0] / sum, 100 * part[1] / sum,
               100 * part[2] / sum);
    else
        printf("  stages: unavailable (the runs lack the stage counters)");
    if (f->n_time == 1) {
        const dm_fit_result *t = &f->time[0];
        double a = NAN, b = NAN;
        for (size_t i = 0; i < t->n_params; i++)
            *(strcmp(t->params[i].name, "a") == 0 ? &a : &b) = t->params[i].value;
        double ms = (a + b * instr) / 1e6, et = sqrt(ei * ei + pow(2 * t->cv_mape / 100, 2));
        printf("  WallTime %.3f ms [%.3f, %.3f]", ms, ms * (1 - et), ms * (1 + et));
    }
    printf("\n");
    dm_str_free(&why);
    free(variant);
}

/* Loads the --from runs into *runs (n of them, dirs[] their names). */
static int predict__load(const char *from, dm_run_result **runs, char ***dirs, size_t *n)
{
    char *list = dm_xstrdup(from), *save = NULL;
    int rc = 0;
    for (char *t = strtok_r(list, ",", &save); rc == 0 && t; t = strtok_r(NULL, ",", &save)) {
        dm_run_result r = {0};
        dm_str err = {0};
        if (cli_load_run(t, &r, &err) != 0)
            rc = cli_usage_error("predict: --from %s: %s", t, dm_str_get(&err));
        else {
            DM_VEC_PUSH(*runs, *n, r);
            size_t nd = *n - 1;
            DM_VEC_PUSH(*dirs, nd, dm_xstrdup(t));
        }
        dm_str_free(&err);
    }
    free(list);
    return rc ? rc : -1;
}

int cli_predict(int argc, char **argv)
{
    predict_args a = {0};
    int rc = cli_parse(argc, argv, &a, &argc);
    if (rc < 0 && argc != 1)
        rc = cli_usage_error("predict: give one sweep file (the configurations to predict)");
    if (rc < 0 && !a.from)
        rc = cli_usage_error("predict: --from RUN[,RUN...] is required (the measured runs)");
    if (rc >= 0)
        return rc;
    sweep s = {0};
    plan p = {0};
    dm_str err = {0};
    if (sweep_load(argv[0], &s, &err) != 0 || plan_build(&s, &p, &err) != 0)
        rc = cli_usage_error("%s", dm_str_get(&err));
    dm_run_result *runs = NULL;
    char **dirs = NULL;
    size_t nr = 0;
    rc = rc < 0 ? predict__load(a.from, &runs, &dirs, &nr) : rc;
    rc = rc < 0 ? predict__check_counters(runs, nr, dirs) : rc;
    rc = rc < 0 ? predict__check_env(runs, nr, dirs, a.allow_env_mismatch) : rc;
    double *counts = rc < 0 ? dm_xcalloc(p.n_configs * PREDICT__N_COUNTS + 1, sizeof *counts) : NULL;
    if (rc < 0 && measure_counts(p.configs, p.n_configs, predict__counts, PREDICT__N_COUNTS, counts, &err) != 0)
        rc = cli_error(DM_ERR_GL, "predict: %s", dm_str_get(&err));
    if (rc < 0) {
        dm_run_result u = predict__union(runs, nr);
        predict_fits f = { .train = &u };
        predict__fit(&u, "stage-instructions", "Instructions", &f.instr, &f.n_instr);
        for (int st = 0; st < 3; st++)
            if (predict__has(&u, predict__stages[st]))
                predict__fit(&u, "stage-instructions", predict__stages[st], &f.stage[st], &f.n_stage[st]);
        if (predict__has(&u, "WallTime"))
            predict__fit(&u, "time-from-instructions", "WallTime", &f.time, &f.n_time);
        printf("%-16s  %-40s %-28s %12s %s\n", "key", "scene", "variant", "Instructions", "[±2 CV-MAPE]");
        dm_str unpred = {0};
        for (size_t i = 0; i < p.n_configs; i++)
            predict__config(&f, &p.configs[i], counts + i * PREDICT__N_COUNTS, &unpred);
        if (unpred.len)
            printf("not predicted (never guessed):\n%s", dm_str_get(&unpred));
        dm_str_free(&unpred);
        for (size_t i = 0; i < f.n_instr; i++)
            dm_fit_result_free(&f.instr[i]);
        for (int st = 0; st < 3; st++) {
            for (size_t i = 0; i < f.n_stage[st]; i++)
                dm_fit_result_free(&f.stage[st][i]);
            free(f.stage[st]);
        }
        for (size_t i = 0; i < f.n_time; i++)
            dm_fit_result_free(&f.time[i]);
        free(f.instr);
        free(f.time);
        free(u.configs);
        rc = DM_EXIT_OK;
    }
    free(counts);
    for (size_t k = 0; k < nr; k++) {
        dm_run_free(&runs[k]);
        free(dirs[k]);
    }
    free(runs);
    free(dirs);
    plan_free(&p);
    sweep_free(&s);
    dm_str_free(&err);
    return rc;
}
