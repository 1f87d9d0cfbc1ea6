/* cmd_predict.c — `dmbench predict SWEEP --from RUN[,RUN...]`: each
 * configuration's Instructions, stage shares and WallTime, predicted from
 * per-variant costs fitted to measured runs (docs/models.md, "Prediction").
 *
 * The invocation counts of the new configurations are read exactly, with
 * one frame each of a statistics pass in this process (no Valgrind, no
 * timing); the costs per invocation come from the fits of run/predict.c
 * (per shader variant and stage).  A configuration of a variant the runs
 * never measured is listed with the reason, never guessed. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "run/env.h"
#include "run/gl_context.h"
#include "run/measure.h"
#include "run/predict.h"
#include "run/probe.h"
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

/* Refuses (exit 2) a run without a counter the fits need, naming it and
 * the sweep option that adds it; -1 to go on. */
static int predict__check_counters(const dm_run_result *runs, size_t n, char **dirs)
{
    for (size_t k = 0; k < n; k++) {
        const char *miss = predict_run_missing(&runs[k]);
        if (miss)
            return cli_usage_error("predict: %s has no counter '%s': add %s to measure.counters of "
                                   "its sweep and run it again (docs/models.md)", dirs[k], miss, miss);
    }
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

/* "[lo, hi]" (each divided by scale, printed with fmt), or why there is no
 * interval: a bound that is not finite is never printed. */
static void predict__interval(const char *fmt, double lo, double hi, double scale)
{
    if (!isfinite(lo) || !isfinite(hi)) {
        printf("[interval unavailable: too few configurations to hold one out]");
        return;
    }
    printf("[");
    printf(fmt, lo / scale);
    printf(", ");
    printf(fmt, hi / scale);
    printf("]");
}

/* A held-out error "X.XX %", or "unavailable" when there is none. */
static void predict__pct(double v)
{
    if (isfinite(v))
        printf("%.2f %%", v);
    else
        printf("unavailable (too few configurations to hold one out)");
}

/* One line of the table, or the reason the configuration is unpredictable. */
static void predict__config(const predict_model *m, const plan_config *pc, const double *counts, dm_str *unpred)
{
    predict_result r;
    dm_str why = {0};
    if (predict_config(m, pc, counts, &r, &why) != 0) {
        dm_str_printf(unpred, "  %s  %s: %s\n", pc->key, pc->scene, dm_str_get(&why));
    } else {
        printf("%s  %-40s %-28s %12.6g ", pc->key, pc->scene, r.variant, r.instr);
        predict__interval("%.6g", r.instr_lo, r.instr_hi, 1);
        double sum = r.part[0] + r.part[1] + r.part[2];
        if (isfinite(sum) && sum > 0)
            printf("  geometry %2.0f %% raster %2.0f %% fragment %2.0f %%", 100 * r.part[0] / sum,
                   100 * r.part[1] / sum, 100 * r.part[2] / sum);
        else
            printf("  stages: unavailable (the runs lack the stage counters)");
        if (isfinite(r.wall_ns)) {
            printf("  WallTime %.3f ms ", r.wall_ns / 1e6);
            predict__interval("%.3f", r.wall_lo, r.wall_hi, 1e6);
        }
        static const char *const stage[3] = {"geometry", "raster", "fragment"};
        if (r.beyond_stage >= 0)
            printf("  (extrapolated: %s %.3g x the largest the runs measured)", stage[r.beyond_stage], r.beyond);
        printf("\n");
    }
    predict_result_free(&r);
    dm_str_free(&why);
}

/* How well each variant's Instructions predicted the runs' own
 * configurations held out of the fits: the stage models' sum, and the
 * one-formula stage-instructions beside it. */
static void predict__heldout_print(const predict_model *m)
{
    if (m->n_heldout)
        printf("held-out error of Instructions on the runs' configurations (k-fold CV-MAPE), per variant:\n");
    for (size_t i = 0; i < m->n_heldout; i++) {
        const predict_heldout *h = &m->heldout[i];
        const dm_fit_result *one = predict_fit_of(m->instr, m->n_instr, h->variant);
        int use_one = predict_heldout_prefers_one(m, one);
        printf("  %s\n    stages summed ", h->variant);
        if (isfinite(h->cv_mape))
            printf("%5.2f %% over %d configurations%s", h->cv_mape, h->n, use_one ? "" : " (used)");
        else
            printf("%sunavailable: too few configurations to hold one out", use_one ? "" : "(used) ");
        if (one && isfinite(one->cv_mape))
            printf("; stage-instructions %5.2f %%%s", one->cv_mape, use_one ? " (used)" : "");
        printf("\n");
    }
}

/* How well each way of predicting WallTime did on the runs' own
 * configurations held out of the fits, and which one is used. */
static void predict__time_heldout_print(const predict_model *m)
{
    const predict_heldout *h = &m->time_heldout;
    int stage_times = predict_has_stage_times(m);
    const dm_fit_result *st = m->n_time_st == 1 ? &m->time_st[0] : NULL;
    const dm_fit_result *ti = m->n_time == 1 ? &m->time[0] : NULL;
    if (!ti && !st)
        return;
    int st_used = !stage_times && predict_prefers_time_from_stages(m);
    printf("held-out error of WallTime on the runs' configurations (k-fold CV-MAPE):\n  ");
    if (stage_times) {
        printf("stage times summed ");
        predict__pct(h->cv_mape);
        printf(" over %d configurations (used); ", h->n);
    } else {
        printf("stage times: unavailable (%s); ", st ? "the runs lack GeometryTime or MinimalShadingTime: add both "
                                                       "to measure.counters"
                                                     : "the runs lack the stage counters");
    }
    if (st) {
        printf("time-from-stages ");
        predict__pct(st->cv_mape);
        printf("%s; ", st_used ? " (used)" : "");
    }
    if (ti) {
        printf("time-from-instructions ");
        predict__pct(ti->cv_mape);
        printf("%s", !stage_times && !st_used ? " (used)" : "");
    }
    printf("\n");
}

/* Loads the --from runs into *runs (n of them, dirs[] their names); -1 when
 * all loaded, else the exit code.  Each run once: a run named twice (also
 * as `latest` and its id) would weigh its points double in every fit. */
static int predict__load(const char *from, dm_run_result **runs, char ***dirs, size_t *n)
{
    dm_str err = {0};
    size_t np = 0;
    int rc = dm_split_paths(from, "predict: --from", dirs, &np, &err) ? cli_usage_error("%s", dm_str_get(&err)) : 0;
    for (size_t k = 0; rc == 0 && k < np; k++) {
        dm_run_result r = {0};
        int lrc = cli_load_run((*dirs)[k], &r, &err);
        if (lrc != 0) {
            rc = cli_error(lrc, "predict: --from %s", dm_str_get(&err));
            break;
        }
        for (size_t j = 0; rc == 0 && j < *n; j++)
            if (strcmp((*runs)[j].id, r.id) == 0)
                rc = cli_usage_error("predict: --from names run %s twice (%s and %s); name each run once",
                                     r.id, (*dirs)[j], (*dirs)[k]);
        DM_VEC_PUSH(*runs, *n, r);
    }
    for (size_t k = *n; k < np; k++)   /* dirs[] holds one name a loaded run */
        free((*dirs)[k]);
    dm_str_free(&err);
    return rc ? rc : -1;
}

int cli_predict(const cli_command *self, int argc, char **argv)
{
    predict_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
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
    int prc = rc < 0 ? probe_user_techniques(&err) : 0;   /* compiled in a child: it may crash */
    if (prc != 0)
        rc = cli_error(prc, "predict: %s", dm_str_get(&err));
    dm_run_result *runs = NULL;
    char **dirs = NULL;
    size_t nr = 0;
    rc = rc < 0 ? predict__load(a.from, &runs, &dirs, &nr) : rc;
    rc = rc < 0 ? predict__check_counters(runs, nr, dirs) : rc;
    rc = rc < 0 ? predict__check_env(runs, nr, dirs, a.allow_env_mismatch) : rc;
    double *counts = rc < 0 ? dm_xcalloc(p.n_configs * PREDICT_N_COUNTS + 1, sizeof *counts) : NULL;
    if (rc < 0 && measure_counts(p.configs, p.n_configs, predict_counts, PREDICT_N_COUNTS, counts, &err) != 0)
        rc = cli_error(DM_ERR_GL, "predict: %s", dm_str_get(&err));
    if (rc < 0) {
        predict_model m;
        predict_fit(runs, nr, &m);
        printf("%-16s  %-40s %-28s %12s %s\n", "key", "scene", "variant", "Instructions", "[±2 CV-MAPE]");
        dm_str unpred = {0};
        for (size_t i = 0; i < p.n_configs; i++)
            predict__config(&m, &p.configs[i], counts + i * PREDICT_N_COUNTS, &unpred);
        if (unpred.len)
            printf("not predicted (never guessed):\n%s", dm_str_get(&unpred));
        dm_str left = {0};
        if (predict_left_out(runs, nr, &left))
            printf("left out of the fits (a counter they need is unavailable there):\n%s", dm_str_get(&left));
        dm_str_free(&left);
        predict__heldout_print(&m);
        predict__time_heldout_print(&m);
        dm_str_free(&unpred);
        predict_free(&m);
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
