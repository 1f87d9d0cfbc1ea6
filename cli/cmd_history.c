/* cmd_history.c — `dmbench history [--store DB] [--run ID] [KEY...]
 * [--technique T] [--scene S]`: each selected configuration's median
 * WallTime (and Instructions where present) across the runs of the store
 * made on the same machine fingerprint, oldest first, with the change points
 * the regression gate's statistics find (models/changepoint.h).
 *
 * The configurations are those of the reference run (--run, default the
 * newest), narrowed by KEYs or by technique/scene.
 */
#include "cli.h"
#include "core/dm_error.h"
#include "models/changepoint.h"
#include "reports/report.h"
#include "store/store.h"
#include "store/store_history.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HISTORY_MAX_KEYS 64

typedef struct history__opts {
    const char *store, *run, *technique, *scene;
    const char *keys[HISTORY_MAX_KEYS];
    size_t n_keys;
} history__opts;

const cli_option cli_history_options[] = {
    { .name = "store", .kind = CLI_OPT_STRING, .offset = offsetof(history__opts, store),
      .value_name = "DB", .def = "results/dmbench.sqlite", .help = "the results store" },
    CLI_STRING("run", history__opts, run, "ID", "the configurations of this run (default: the newest)"),
    CLI_STRING("technique", history__opts, technique, "T", "only this technique"),
    CLI_STRING("scene", history__opts, scene, "S", "only this scene"),
    CLI_OPT_END
};

/* Options, then the KEYs; returns -1 to go on or an exit code. */
static int history__options(const cli_command *self, int argc, char **argv, history__opts *o)
{
    int rc = cli_parse(self, argc, argv, o, &argc);
    if (rc >= 0)
        return rc;
    if (argc > HISTORY_MAX_KEYS)
        return cli_usage_error("history: at most %d KEYs", HISTORY_MAX_KEYS);
    for (int i = 0; i < argc; i++)
        o->keys[o->n_keys++] = argv[i];
    return -1;
}

/* 1 when configuration c is selected by the options. */
static int history__wanted(const history__opts *o, const dm_config_result *c)
{
    for (size_t i = 0; i < o->n_keys; i++)
        if (c->key && strcmp(c->key, o->keys[i]) == 0)
            return 1;
    if (o->n_keys)
        return 0;
    const char *t = dm_kv_get(c->params, c->n_params, "technique");
    return (!o->technique || (t && strcmp(t, o->technique) == 0)) &&
           (!o->scene || (c->scene && strcmp(c->scene, o->scene) == 0));
}

/* Prints one configuration's series; returns its number of runs. */
static size_t history__print(store *st, const dm_run_result *run, const dm_config_result *c,
                             const char *fp)
{
    store_history_point *p;
    size_t n;
    if (store_history(st, c->key, fp, &p, &n) != 0)
        return 0;
    changepoint_series *s = dm_xcalloc(n + 1, sizeof *s);
    unsigned char *change = dm_xcalloc(n + 1, 1);
    double *q = dm_xcalloc(n + 1, sizeof *q);
    for (size_t i = 0; i < n; i++)
        s[i] = (changepoint_series){ p[i].samples, p[i].n_samples, p[i].median };
    size_t nc = changepoint_find(s, n, 0, 0, change, q);
    dm_str name = {0};
    report_config_name(run, c, &name);
    printf("\n%s  [%s]  %zu run%s, %zu change point%s\n", dm_str_get(&name), c->key, n,
           n == 1 ? "" : "s", nc, nc == 1 ? "" : "s");
    printf("  %-17s %-21s %10s  %-20s %14s\n", "run", "started", "median ms", "95% CI ms", "Instructions");
    for (size_t i = 0; i < n; i++) {
        char ci[48], ins[32] = "-";
        snprintf(ci, sizeof ci, "[%.4g, %.4g]", p[i].ci_lo / 1e6, p[i].ci_hi / 1e6);
        if (isfinite(p[i].instructions))
            snprintf(ins, sizeof ins, "%.6g", p[i].instructions);
        printf("  %-17s %-21s %10.4f  %-20s %14s", p[i].run_id, p[i].started ? p[i].started : "",
               p[i].median / 1e6, ci, ins);
        if (change[i])
            printf("  change %+.1f%% (q=%.2g)", (p[i].median / p[i - 1].median - 1) * 100, q[i]);
        printf("\n");
    }
    dm_str_free(&name);
    free(s);
    free(change);
    free(q);
    store_history_free(p, n);
    return n;
}

/* Opens the store and loads the reference run; -1 to go on or an exit code. */
static int history__open(const history__opts *o, store **st, dm_run_result *run, char **fp)
{
    dm_str err = {0};
    char *id = NULL;
    int rc = -1, e = 0;
    if (!dm_file_exists(o->store))
        rc = cli_usage_error("history: %s: no such store (give --store FILE)", o->store);
    else if ((e = store_open(o->store, st, &err)) != 0)
        rc = cli_error(e, "history: %s", dm_str_get(&err));
    else if (!o->run && store_latest_run(*st, NULL, &id) != 0)
        rc = cli_usage_error("history: %s holds no run", o->store);
    else if ((e = store_run_load(*st, o->run ? o->run : id, run)) == DM_ERR_NOTFOUND)
        rc = cli_usage_error("history: run %s is not in %s", o->run ? o->run : id, o->store);
    else if (e != 0)
        rc = cli_error(e, "history: %s", store_last_error(*st));
    else if (store_run_fingerprint(*st, run->id, fp) != 0)
        rc = cli_usage_error("history: %s: %s", o->store, store_last_error(*st));
    free(id);
    dm_str_free(&err);
    return rc;
}

/* --technique / --scene must name one of the run's (which = "technique" or
 * NULL for the scene); -1 to go on, or exit 2 with a did-you-mean. */
static int history__known(const dm_run_result *run, const char *opt, const char *value, int technique)
{
    if (!value)
        return -1;
    const char **seen = dm_xcalloc(run->n_configs + 1, sizeof *seen);
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const char *v = technique ? dm_kv_get(c->params, c->n_params, "technique") : c->scene;
        size_t k = 0;
        while (v && k < n && strcmp(seen[k], v) != 0)
            k++;
        if (v && k == n)
            seen[n++] = v;
        if (v && strcmp(v, value) == 0) {
            free(seen);
            return -1;
        }
    }
    dm_str m = {0};
    dm_str_printf(&m, "history: --%s '%s' is not in run %s", opt, value, run->id ? run->id : "?");
    dm_str_suggest(&m, value, seen, n, technique ? "techniques of the run" : "scenes of the run");
    int rc = cli_usage_error("%s", dm_str_get(&m));
    dm_str_free(&m);
    free(seen);
    return rc;
}

int cli_history(const cli_command *self, int argc, char **argv)
{
    history__opts o = {0};
    int rc = history__options(self, argc, argv, &o);
    store *st = NULL;
    dm_run_result run = {0};
    char *fp = NULL;
    if (rc < 0)
        rc = history__open(&o, &st, &run, &fp);
    if (rc < 0)
        rc = history__known(&run, "technique", o.technique, 1);
    if (rc < 0)
        rc = history__known(&run, "scene", o.scene, 0);
    size_t shown = 0, header = 0;
    for (size_t i = 0; rc < 0 && i < run.n_configs; i++) {
        if (!run.configs[i].ok || !history__wanted(&o, &run.configs[i]))
            continue;
        if (!header++)
            printf("history of the configurations of run %s on machine fingerprint %s (%s)\n",
                   run.id, fp ? fp : "(none: every run)", o.store);
        shown += history__print(st, &run, &run.configs[i], fp) > 0;
    }
    if (rc < 0 && !shown)
        rc = cli_usage_error("history: no timed configuration of run %s matches%s%s%s%s", run.id,
                              o.technique ? " --technique " : "", o.technique ? o.technique : "",
                              o.scene ? " --scene " : "", o.scene ? o.scene : "");
    free(fp);
    dm_run_free(&run);
    store_close(st);
    return rc < 0 ? 0 : rc;
}
