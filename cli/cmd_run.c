/* cmd_run.c — `dmbench run [SWEEP.yaml]`: measure a sweep into a run directory. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "run/runner.h"
#include "sweep/sweep.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct run_args {
    runner_opts o;
    int quick;
    int print_default;
} run_args;

/* --shard K/N and --seed N: checked by the runner's own parsers
 * (runner_parse_shard, runner_parse_seed), which name the valid form. */
static int run__shard(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    runner_opts *o = &((run_args *)args)->o;
    (void)opt;
    return runner_parse_shard(v, &o->shard_k, &o->shard_n, err);
}

static int run__seed(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    (void)opt;
    return runner_parse_seed(v, &((run_args *)args)->o.seed, err);
}

/* Seconds > 0 and finite into *b ("inf" would plan as if there were no
 * budget); what names what they are for the message. */
static int run__seconds(const cli_option *opt, const char *v, double *b, const char *what, dm_str *err)
{
    char *end = NULL;
    *b = strtod(v, &end);
    if (!*v || *end || !(*b > 0) || !isfinite(*b)) {
        dm_str_printf(err, "--%s '%s': expected %s, > 0 and finite", opt->name, v, what);
        return DM_ERR_ARG;
    }
    return 0;
}

static int run__budget(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    return run__seconds(opt, v, &((run_args *)args)->o.budget_s, "seconds per configuration", err);
}

/* Seconds of extra rounds for the default sweep when --extra-time is not
 * given: its configurations within ±3 % with the drift removed went from
 * 56-65 % without extra rounds to 73-92 % with 60 s, and the sweep from
 * 98-109 s to 162-175 s, within the 3 minutes the issue allows
 * (docs/measurement.md, "Precision").  A sweep file gets none unless asked. */
#define RUN_DEFAULT_EXTRA_S 60.0

/* --extra-time SEC: 0 (none) or more, finite. */
static int run__extra_time(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    double *b = &((run_args *)args)->o.extra_s;
    char *end = NULL;
    *b = strtod(v, &end);
    if (!*v || *end || !(*b >= 0) || !isfinite(*b)) {
        dm_str_printf(err, "--%s '%s': expected seconds for the whole run, 0 (none) or more and finite",
                      opt->name, v);
        return DM_ERR_ARG;
    }
    return 0;
}

const cli_option cli_run_options[] = {
    { .name = "out", .kind = CLI_OPT_STRING, .offset = offsetof(run_args, o.out_root),
      .value_name = "DIR", .help = "output root: DIR/dmbench.sqlite, DIR/<run-id>/, DIR/latest",
      .def = "results" },
    CLI_BOOL("resume", run_args, o.resume,
             "continue the newest unfinished run of the store; nothing finished is redone"),
    { .name = "shard", .kind = CLI_OPT_STRING, .value_name = "K/N", .parse = run__shard,
      .help = "run the K-th of N deterministic shares of the configurations" },
    { .name = "budget", .kind = CLI_OPT_DOUBLE, .value_name = "SEC", .parse = run__budget,
      .help = "leave out configurations predicted to take longer than SEC seconds" },
    { .name = "extra-time", .kind = CLI_OPT_DOUBLE, .value_name = "SEC", .parse = run__extra_time,
      .help = "up to SEC seconds more for the configurations short of samples.target_ci (judged "
              "with the machine's drift removed where it is): extra rounds, the noisiest first; 0: "
              "none (default: 60 for the default sweep, none for --quick or a sweep file)" },
    { .name = "seed", .kind = CLI_OPT_UINT64, .value_name = "N", .parse = run__seed,
      .help = "seed of the round order (0 = 1)" },
    { .name = "count-jobs", .kind = CLI_OPT_INT, .offset = offsetof(run_args, o.count_jobs),
      .value_name = "N", .min = 0, .max = 256,
      .help = "Valgrind children counting Instructions side by side (0 = DMBENCH_COUNT_JOBS, "
              "else the online CPUs, at most 8)" },
    CLI_STRING("tag", run_args, o.tag, "NAME",
               "a name stored with the run (compare --base-tag/--new-tag)"),
    CLI_BOOL("quick", run_args, quick,
             "without SWEEP.yaml: a smaller default sweep that takes seconds"),
    CLI_BOOL("print-default", run_args, print_default,
             "print the default sweep (with --quick: the quick one) as YAML and exit, to copy "
             "as a start of your own"),
    CLI_BOOL("dry-run", run_args, o.dry_run,
             "print the planned configurations (folded, left out with reasons, estimated time "
             "from a stored model) and exit without measuring"),
    CLI_BOOL("quiet", run_args, o.quiet, "no progress output"),
    CLI_BOOL("verbose", run_args, o.verbose,
             "debug logging, and why a stored model could not predict a configuration"),
    CLI_OPT_END
};

/* `dmbench run [SWEEP.yaml]`: loads the sweep (or the embedded default),
 * runs it and prints where the report is.  Exit 2 for a bad sweep or
 * option, else the runner's error mapped by dm_exit_from_error. */
int cli_run(const cli_command *self, int argc, char **argv)
{
    run_args args = {0}, *a = &args;
    a->o.extra_s = NAN;   /* not given: the default below, once the sweep is known */
    int rc = cli_parse(self, argc, argv, a, &argc);
    if (rc < 0 && argc > 1)
        rc = cli_usage_error("run: only one sweep file may be given ('%s' and '%s')", argv[0], argv[1]);
    if (rc >= 0)
        return rc;
    if (a->print_default) {
        fputs(sweep_default_text(a->quick), stdout);
        return DM_EXIT_OK;
    }
    const char *file = argc ? argv[0] : NULL;
    if (isnan(a->o.extra_s))
        a->o.extra_s = !file && !a->quick ? RUN_DEFAULT_EXTRA_S : 0;
    if (a->o.verbose)
        dm_log_set_level(DM_LOG_DEBUG);
    sweep s;
    dm_str err = {0};
    rc = file ? sweep_load(file, &s, &err)
                  : sweep_parse(sweep_default_text(a->quick), a->quick ? "<default --quick>" : "<default>",
                                &s, &err);
    if (rc != 0) {   /* 2, or 4 for a map too large for the memory (DM_ERR_NOMEM) */
        rc = cli_error(rc, "%s", dm_str_get(&err));
        dm_str_free(&err);
        return rc;
    }
    if (s.n_drivers && !getenv(CLI_DRIVERS_CHILD) && !a->o.dry_run) {   /* one run per driver */
        sweep_free(&s);
        if (a->o.resume || a->o.shard_n)
            return cli_usage_error("run: %s names drivers: --%s is not available with `drivers:` "
                                   "(run each driver with DMBENCH_DRIVER instead)", file,
                                   a->o.resume ? "resume" : "shard");
        char seed[24] = "";
        if (a->o.seed)
            snprintf(seed, sizeof seed, "%llu", (unsigned long long)a->o.seed);
        fprintf(stderr, "dmbench: %s names drivers: one run per driver (dmbench drivers)\n", file);
        return cli_drivers_main(file, NULL, a->o.out_root, a->o.seed ? seed : NULL, a->o.quiet, 0);
    }
    if (s.n_drivers && !getenv(CLI_DRIVERS_CHILD)) {   /* the dry run of each driver's run */
        rc = cli_drivers_dry_run(file, &s, a->o.out_root);
        sweep_free(&s);
        return rc;
    }
    char *dir = NULL;
    rc = runner_run(&s, &a->o, &dir, &err);
    sweep_free(&s);
    if (rc != 0) {
        char *b;
        fprintf(stderr, "dmbench: error: %s\n", dm_term_safe(dm_str_get(&err), &b));
        free(b);
        dm_str_free(&err);
        return dm_exit_from_error(rc);
    }
    if (!a->o.quiet && dir)
        printf("report: %s/report.html\n", dir);
    free(dir);
    return DM_EXIT_OK;
}
