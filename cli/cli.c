/* cli.c — `dmbench run`, `dmbench report`, `dmbench info` and shared helpers. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_util.h"
#include "run/info.h"
#include "run/runner.h"
#include "store/store.h"
#include "sweep/sweep.h"
#include "reports/metric.h"
#include "reports/report.h"

#include <libgen.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli__usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "dmbench: error: ");
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return 2;
}

int cli__unknown_option(const char *cmd, const char *opt, const char *const *valid, size_t n)
{
    dm_str s = {0};
    const char *close = dm_closest(opt, valid, n);
    dm_str_printf(&s, "%s: unknown option '%s'", cmd, opt);
    if (close)
        dm_str_printf(&s, "; did you mean '%s'?", close);
    dm_str_cat(&s, " valid options: ");
    dm_str_cat_list(&s, valid, n);
    int rc = cli__usage_error("%s", dm_str_get(&s));
    dm_str_free(&s);
    return rc;
}

const char *cli__value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        cli__usage_error("%s: %s needs a value", argv[0], argv[*i]);
        return NULL;
    }
    return argv[++*i];
}

/* Parses run's options into o; returns -1 to go on or an exit code. */
static int cli__run_options(int argc, char **argv, runner_opts *o, const char **file, int *quick)
{
    static const char *const valid[] = { "--out", "--resume", "--shard", "--seed", "--tag",
                                         "--quick", "--quiet", "--verbose", "--budget" };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        if (a[0] != '-') {
            if (*file)
                return cli__usage_error("run: only one sweep file may be given ('%s' and '%s')", *file, a);
            *file = a;
        } else if (strcmp(a, "--out") == 0) {
            if (!(o->out_root = cli__value(argc, argv, &i)))
                return 2;
        } else if (strcmp(a, "--resume") == 0) {
            o->resume = 1;
        } else if (strcmp(a, "--shard") == 0) {
            if (!(v = cli__value(argc, argv, &i)))
                return 2;
            dm_str e = {0};
            if (runner_parse_shard(v, &o->shard_k, &o->shard_n, &e) != 0) {
                cli__usage_error("run: %s", dm_str_get(&e));
                dm_str_free(&e);
                return 2;
            }
        } else if (strcmp(a, "--seed") == 0) {
            if (!(v = cli__value(argc, argv, &i)))
                return 2;
            dm_str e = {0};
            if (runner_parse_seed(v, &o->seed, &e) != 0) {
                cli__usage_error("run: %s", dm_str_get(&e));
                dm_str_free(&e);
                return 2;
            }
        } else if (strcmp(a, "--budget") == 0) {
            if (!(v = cli__value(argc, argv, &i)))
                return 2;
            char *end = NULL;
            o->budget_s = strtod(v, &end);
            if (!*v || *end || !(o->budget_s > 0))
                return cli__usage_error("run: --budget '%s': expected seconds per configuration, > 0", v);
        } else if (strcmp(a, "--tag") == 0) {
            if (!(o->tag = cli__value(argc, argv, &i)))
                return 2;
        } else if (strcmp(a, "--quick") == 0) {
            *quick = 1;
        } else if (strcmp(a, "--quiet") == 0) {
            o->quiet = 1;
        } else if (strcmp(a, "--verbose") == 0) {
            o->verbose = 1;
            dm_log_set_level(DM_LOG_DEBUG);
        } else {
            return cli__unknown_option("run", a, valid, sizeof valid / sizeof *valid);
        }
    }
    return -1;
}

int cli_run(int argc, char **argv)
{
    runner_opts o = {0};
    const char *file = NULL;
    int quick = 0;
    int rc = cli__run_options(argc, argv, &o, &file, &quick);
    if (rc >= 0)
        return rc;
    sweep s;
    dm_str err = {0};
    rc = file ? sweep_load(file, &s, &err)
              : sweep_parse(sweep_default_text(quick), quick ? "<default --quick>" : "<default>", &s, &err);
    if (rc != 0) {
        char *b;
        fprintf(stderr, "dmbench: error: %s\n", dm_term_safe(dm_str_get(&err), &b));
        free(b);
        dm_str_free(&err);
        return 2;
    }
    char *dir = NULL;
    rc = runner_run(&s, &o, &dir, &err);
    sweep_free(&s);
    if (rc != 0) {
        char *b;
        fprintf(stderr, "dmbench: error: %s\n", dm_term_safe(dm_str_get(&err), &b));
        free(b);
        dm_str_free(&err);
        return dm_exit_code(rc);
    }
    if (!o.quiet)
        printf("report: %s/report.html\n", dir);
    free(dir);
    return 0;
}

int cli__load_run(const char *dir, dm_run_result *run, dm_str *err)
{
    char *store_path = NULL, *run_id = NULL;
    char real[PATH_MAX];
    int rc = 0;
    if (!realpath(dir, real)) {
        dm_str_printf(err, "%s: no such run directory", dir);
        return DM_ERR_ARG;
    }
    char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
    run_id = dm_xstrdup(basename(a));
    store_path = dm_xasprintf("%s/dmbench.sqlite", dirname(b));
    store *st = NULL;
    if (!dm_file_exists(store_path)) {
        dm_str_printf(err, "%s: not a run directory: no results store beside it (%s)", dir, store_path);
        rc = DM_ERR_ARG;
    }
    rc = rc ? rc : store_open(store_path, &st, err);
    rc = rc ? rc : store_check(st, err);
    if (rc == 0 && (rc = store_run_load(st, run_id, run)) != 0) {
        if (rc == DM_ERR_NOTFOUND)
            dm_str_printf(err, "%s: run %s is not in %s", dir, run_id, store_path);
        else
            dm_str_cat(err, store_last_error(st));
        rc = rc == DM_ERR_NOTFOUND ? DM_ERR_ARG : DM_ERR_STORE;
    }
    store_close(st);
    free(a);
    free(b);
    free(store_path);
    free(run_id);
    return rc;
}

/* Parses report's arguments: DIR [--metric NAME].  Returns -1 to go on or
 * an exit code (2 for a usage error, naming the valid metrics). */
static int cli__report_options(int argc, char **argv, const char **dir, const char **metric)
{
    static const char *const valid[] = { "--metric" };
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--metric") == 0) {
            report_metric m;
            if (!(*metric = cli__value(argc, argv, &i)))
                return 2;
            if (report_metric_parse(*metric, &m) != 0) {
                dm_str e = {0};
                report_metric_unknown(*metric, &e);
                int rc = cli__usage_error("report: --metric: %s", dm_str_get(&e));
                dm_str_free(&e);
                return rc;
            }
        } else if (argv[i][0] == '-') {
            return cli__unknown_option("report", argv[i], valid, 1);
        } else if (*dir) {
            return cli__usage_error("report: only one run directory may be given ('%s' and '%s')",
                                    *dir, argv[i]);
        } else {
            *dir = argv[i];
        }
    }
    if (!*dir)
        return cli__usage_error("usage: dmbench report DIR [--metric NAME]   (a run directory, "
                                "e.g. results/latest)");
    return -1;
}

/* Rebuilds a run's report files from the store; --metric overrides the
 * Pareto metric the run recorded (for these files only; the store keeps it). */
int cli_report(int argc, char **argv)
{
    const char *dir = NULL, *metric = NULL;
    int rc = cli__report_options(argc, argv, &dir, &metric);
    dm_str err = {0};
    dm_run_result run = {0};
    int lrc = rc < 0 ? cli__load_run(dir, &run, &err) : 0;
    if (lrc != 0) {
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        rc = dm_exit_code(lrc);
    }
    if (rc < 0 && metric)
        report_metric_set(&run, metric);   /* validated above */
    char e[512] = "";
    if (rc < 0 && report_write_all(&run, dir, e, sizeof e) != 0)
        rc = cli__usage_error("report: %s", e);
    if (rc < 0) {
        printf("report: %s/report.html\n", dir);
        rc = 0;
    }
    dm_run_free(&run);
    dm_str_free(&err);
    return rc;
}

int cli_info(int argc, char **argv)
{
    int json = 0;
    static const char *const valid[] = { "--json" };
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else
            return cli__unknown_option("info", argv[i], valid, 1);
    }
    return info_main(json);
}
