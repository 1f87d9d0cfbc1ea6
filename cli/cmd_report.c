/* cmd_report.c — `dmbench report DIR`: rebuild a run's report files from the store. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "store/store.h"
#include "reports/flip_run.h"
#include "reports/answer.h"
#include "reports/metric.h"
#include "reports/report.h"
#include "run/trends.h"

#include <libgen.h>
#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct report_args {
    const char *metric;
    const char *out;
    double flip_ppd;
    double budget_ms;
} report_args;

/* --metric NAME: one of the report metrics (reports/metric.c). */
static int report__metric(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    report_metric m;
    if (report_metric_parse(v, &m) != 0) {
        dm_str_printf(err, "--%s: ", opt->name);
        report_metric_unknown(v, err);
        return DM_ERR_ARG;
    }
    ((report_args *)args)->metric = v;
    return 0;
}

const cli_option cli_report_options[] = {
    { .name = "metric", .kind = CLI_OPT_STRING, .value_name = "NAME", .parse = report__metric,
      .help = "Pareto error metric for these files (the store keeps the run's own)" },
    { .name = "flip-ppd", .kind = CLI_OPT_DOUBLE, .offset = offsetof(report_args, flip_ppd),
      .value_name = "N", .min = 1, .max = 600,
      .help = "FLIP again at N pixels per degree from the stored images (for these files; docs/flip.md)" },
    { .name = "budget-ms", .kind = CLI_OPT_DOUBLE, .offset = offsetof(report_args, budget_ms),
      .value_name = "MS", .min = 0.001, .max = 1e6,
      .help = "the frame budget the recommendation picks under (default: per scene, a round value in "
              "the widest gap of its lit times; docs/reports.md)" },
    CLI_STRING("out", report_args, out, "DIR",
               "write the files into DIR (created) instead of the run directory"),
    CLI_OPT_END
};

/* Rebuilds a run's report files from the store; --metric overrides the
 * Pareto metric the run recorded (for these files only; the store keeps it);
 * --flip-ppd recomputes FLIP at another viewing condition (likewise);
 * --out writes them into another directory (created) instead of the run's. */
int cli_report(const cli_command *self, int argc, char **argv)
{
    report_args args = {0};
    int rc = cli_parse(self, argc, argv, &args, &argc);
    if (rc >= 0)
        return rc;
    const char *metric = args.metric, *out = args.out;
    if (argc > 1)
        return cli_usage_error("report: only one run directory may be given ('%s' and '%s')",
                               argv[0], argv[1]);
    if (argc == 0)
        return cli_usage_error("usage: dmbench report DIR [--metric NAME] [--out DIR2]   (a run "
                               "directory, e.g. results/latest)");
    const char *dir = argv[0];
    char *store_path = NULL, *run_id = NULL;
    store *st = NULL;
    dm_str err = {0};
    if (cli_run_locate(dir, &store_path, &run_id, &err) != 0)
        rc = cli_usage_error("%s", dm_str_get(&err));
    dm_run_result run = {0};
    int se = 0;   /* a damaged or newer store is the machine's: exit 4 (cli_error) */
    if (rc < 0 && (se = store_open(store_path, &st, &err)) != 0)
        rc = cli_error(se, "%s", dm_str_get(&err));
    if (rc < 0 && (se = store_check(st, &err)) != 0)
        rc = cli_error(se, "%s", dm_str_get(&err));
    if (rc < 0 && (se = store_run_load(st, run_id, &run)) == DM_ERR_NOTFOUND)
        rc = cli_usage_error("%s: run %s is not in %s", dir, run_id, store_path);
    else if (rc < 0 && se != 0)
        rc = cli_error(DM_ERR_STORE, "%s", store_last_error(st));
    if (rc < 0 && metric)
        report_metric_set(&run, metric);   /* validated by report__metric */
    if (rc < 0 && args.budget_ms > 0)
        report_budget_set(&run, args.budget_ms);   /* range checked by the option table */
    if (rc < 0 && args.flip_ppd > 0 && flip_run_recompute(&run, dir, args.flip_ppd, &err) != 0)
        rc = cli_usage_error("report: --flip-ppd: %s", dm_str_get(&err));
    char e[512] = "";
    if (rc < 0 && out && dm_mkdirs(out) != 0)
        rc = cli_usage_error("report: --out %s: cannot create the directory", out);
    report_trends tr = {0};
    if (rc < 0)
        run_trends(st, &run, &tr);   /* none on a store failure: the report goes on */
    report_desc d = {.dir = dir, .out = out, .trends = &tr};
    int we = rc < 0 ? report_write_run(&run, &d, e, sizeof e) : 0;
    if (we)   /* a full disk or ulimit -f is 4, as for `run` */
        rc = cli_error(we, "report: %s", e);
    report_trends_free(&tr);
    if (rc < 0) {
        printf("report: %s/report.html\n", out ? out : dir);
        rc = DM_EXIT_OK;
    }
    dm_run_free(&run);
    store_close(st);
    dm_str_free(&err);
    free(store_path);
    free(run_id);
    return rc;
}
