/* cmd_drivers.c — `dmbench drivers [SWEEP]`: one sweep measured on several
 * drivers, each in its own run (own process tree, environment and
 * fingerprint), then set side by side (reports/drivers_report.h,
 * docs/drivers.md "One sweep on several drivers").
 *
 * Each driver's run is `dmbench run SWEEP --out OUT/DRIVER` started with
 * DMBENCH_DRIVER=DRIVER, so it re-executes under that driver's libraries
 * exactly as a user's run would.  With two or more drivers the runs are
 * interleaved: the sweep is cut into N shards (`run --shard K/N`, by
 * configuration key, so shard K holds the same configurations on every
 * driver) and the drivers take turns shard by shard, each shard's run in
 * OUT/DRIVER/shard-K-of-N; each driver's shards are then merged into
 * OUT/DRIVER (cli_merge_dirs).  A configuration is so measured on every
 * driver within one turn, not a whole run apart.  A driver that is not
 * installed is left out with the reason; one whose run fails (a driver that
 * hangs at start-up is killed by the run's probe watchdog) is recorded as
 * failed, runs no further shard, and the other drivers go on. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "core/dm_exit.h"
#include "gate/compare.h"
#include "reports/drivers_report.h"
#include "run/drivers.h"
#include "sweep/sweep.h"

#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct drivers_args {
    const char *drivers;   /* comma-separated; NULL = every installed one */
    const char *out;
    const char *seed;
    int quiet;
    int interleave;        /* shards the drivers take turns on; 0 = DRIVERS__SHARDS with 2+ drivers */
    int dry_run;           /* each driver's run only plans (run --dry-run) */
    const char *shard;     /* "K/N" of the run started, or NULL (a whole run) */
} drivers_args;

/* Shards of an interleaved comparison by default: three turns per driver
 * keep each configuration's measurements on the drivers minutes, not a
 * whole run, apart, for about 2 s more per shard run (its probe and
 * calibration: docs/drivers.md). */
#define DRIVERS__SHARDS 3

const cli_option cli_drivers_options[] = {
    CLI_STRING("drivers", drivers_args, drivers, "LIST",
               "comma-separated drivers: default, llvmpipe, llvmpipe-25, zink (docs/drivers.md) [default: every "
               "installed one but 'default']"),
    CLI_STRING("out", drivers_args, out, "DIR",
               "output root: DIR/DRIVER/ per driver, DIR/drivers.md and drivers.json [default "
               "results/drivers]"),
    CLI_STRING("seed", drivers_args, seed, "N", "passed to every run (the same rounds on each driver)"),
    CLI_BOOL("quiet", drivers_args, quiet, "no progress from the runs"),
    { .name = "interleave", .kind = CLI_OPT_INT, .offset = offsetof(drivers_args, interleave),
      .value_name = "N", .min = 1, .max = 64,
      .help = "the drivers take turns on N shards of the sweep, each merged after (1 = one whole run "
              "after another) [default 3 with two or more drivers]" },
    CLI_OPT_END
};

/* "unknown driver 'x' (did you mean 'y'?); the drivers are: ..." into err. */
static void drivers__unknown(const char *name, dm_str *err)
{
    dm_str names = {0};
    const char *choices[16];
    size_t nc = 0;
    for (const driver_info *d = drivers_list(); d->name && nc < 16; d++) {
        dm_str_printf(&names, "%s%s", names.len ? ", " : "", d->name);
        choices[nc++] = d->name;
    }
    const char *near = dm_closest(name, choices, nc);
    dm_str_printf(err, "unknown driver '%s'%s%s%s; the drivers are: %s", name,
                  near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "",
                  dm_str_get(&names));
    dm_str_free(&names);
}

/* The sweep file's `drivers:` list, checked ("FILE:LINE: unknown driver"). */
static int drivers__from_sweep(const sweep *s, char ***out, size_t *n)
{
    for (size_t i = 0; i < s->n_drivers; i++) {
        if (!drivers_find(s->drivers[i])) {
            dm_str e = {0};
            drivers__unknown(s->drivers[i], &e);
            int rc = cli_usage_error("%s:%d: drivers: %s", s->path, s->driver_lines[i], dm_str_get(&e));
            dm_str_free(&e);
            return rc;
        }
        DM_VEC_PUSH(*out, *n, dm_xstrdup(s->drivers[i]));
    }
    return 0;
}

/* The drivers asked for, checked: unknown names are exit 2 with the list.
 * list NULL: the sweep's `drivers:`, else every installed driver. */
static int drivers__names(const char *list, const sweep *s, char ***out, size_t *n)
{
    *out = NULL;
    *n = 0;
    if (!list && s && s->n_drivers)
        return drivers__from_sweep(s, out, n);
    if (!list) {
        for (const driver_info *d = drivers_list(); d->name; d++)
            if (strcmp(d->name, "default") != 0)
                DM_VEC_PUSH(*out, *n, dm_xstrdup(d->name));
        return 0;
    }
    char *copy = dm_xstrdup(list), *save = NULL;
    int rc = 0;
    for (char *p = strtok_r(copy, ",", &save); p && rc == 0; p = strtok_r(NULL, ",", &save)) {
        int twice = 0;
        for (size_t k = 0; k < *n; k++)
            twice |= strcmp((*out)[k], p) == 0;
        if (!drivers_find(p)) {
            dm_str e = {0};
            drivers__unknown(p, &e);
            rc = cli_usage_error("drivers: --drivers: %s", dm_str_get(&e));
            dm_str_free(&e);
        } else if (twice) {   /* as the sweep key `drivers:` refuses: one run a driver */
            rc = cli_usage_error("drivers: --drivers '%s' names %s twice; name each driver once", list, p);
        } else {
            DM_VEC_PUSH(*out, *n, dm_xstrdup(p));
        }
    }
    free(copy);
    if (rc == 0 && *n == 0)
        rc = cli_usage_error("drivers: --drivers '%s' names no driver", list);
    return rc;
}

/* Runs the sweep under one driver; 0, or the run's exit status (>0), with
 * a reason in *why. */
static int drivers__run(const char *driver, const char *sweep, const char *out,
                        const drivers_args *a, char **why)
{
    const char *argv[14];
    size_t k = 0;
    argv[k++] = "dmbench";
    argv[k++] = "run";
    if (sweep)
        argv[k++] = sweep;
    if (out) {
        argv[k++] = "--out";
        argv[k++] = out;
    }
    if (a->dry_run)
        argv[k++] = "--dry-run";
    if (a->shard) {
        argv[k++] = "--shard";
        argv[k++] = a->shard;
    }
    if (a->seed) {
        argv[k++] = "--seed";
        argv[k++] = a->seed;
    }
    if (a->quiet)
        argv[k++] = "--quiet";
    argv[k] = NULL;
    /* The run dies with `drivers` (SIGTERM or SIGKILL of it): it would
     * otherwise go on alone, holding its output's lock. */
    pid_t pid = dm_proc_fork();
    if (pid == 0) {
        setenv("DMBENCH_DRIVER", driver, 1);
        setenv(CLI_DRIVERS_CHILD, "1", 1);   /* the run measures, it does not fan out again */
        execv("/proc/self/exe", (char *const *)argv);
        fprintf(stderr, "dmbench: error: drivers: cannot execute dmbench: %s\n", strerror(errno));
        _exit(DM_EXIT_ENV);
    }
    int status = 0;
    if (pid > 0 && dm_proc_wait(pid, &status) < 0)
        pid = -1;
    if (pid < 0) {
        *why = dm_xasprintf("cannot start its run: %s", strerror(errno));
        return DM_EXIT_ENV;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return 0;
    *why = WIFEXITED(status)
               ? dm_xasprintf("its run exited %d (its message is above)", WEXITSTATUS(status))
               : dm_xasprintf("its run was killed by signal %d", WTERMSIG(status));
    return WIFEXITED(status) ? WEXITSTATUS(status) : DM_EXIT_ENV;
}

/* The sweep of path (NULL: none to read), for its `drivers:` list. */
static int drivers__sweep(const char *path, sweep *s)
{
    memset(s, 0, sizeof *s);
    dm_str err = {0};
    int rc = path && sweep_load(path, s, &err) != 0 ? cli_usage_error("%s", dm_str_get(&err)) : 0;
    dm_str_free(&err);
    return rc;
}

int cli_drivers(const cli_command *self, int argc, char **argv)
{
    drivers_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
    if (rc >= 0)
        return rc;
    if (argc > 1)
        return cli_usage_error("drivers: expected at most one SWEEP (got %d arguments)", argc);
    return cli_drivers_main(argc ? argv[0] : NULL, a.drivers, a.out, a.seed, a.quiet, a.interleave);
}

int cli_drivers_dry_run(const char *sweep_path, const sweep *s, const char *out)
{
    drivers_args a = { .out = out, .dry_run = 1 };
    char **names = NULL;
    size_t n = 0;
    int rc = drivers__from_sweep(s, &names, &n);   /* an unknown name: exit 2 at its line */
    for (size_t i = 0, known = rc == 0; known && i < n; i++) {
        char *why = NULL;
        const char *miss = drivers_missing(drivers_find(names[i]), &why);
        printf("== driver %s%s%s\n", names[i], miss ? ": left out, " : "", miss ? miss : "");
        free(why);
        why = NULL;
        fflush(stdout);
        if (miss)
            continue;
        int r = drivers__run(names[i], sweep_path, out, &a, &why);
        if (r != 0)
            fprintf(stderr, "dmbench: drivers: %s: %s\n", names[i], why);
        free(why);
        rc = r > rc ? r : rc;
    }
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    return rc;
}

/* Runs driver's turn k of shards: `run --shard k/shards` into
 * root/driver/shard-k-of-shards, or with one shard the whole sweep into
 * root/driver.  Returns 1, with the reason in *why_out, when its run failed. */
static int drivers__turn(const char *driver, const char *sweep_path, const char *root, int k, int shards,
                         drivers_args *a, char **why_out)
{
    char *out = shards > 1 ? dm_xasprintf("%s/%s/shard-%d-of-%d", root, driver, k, shards)
                           : dm_xasprintf("%s/%s", root, driver);
    char shard[32];
    snprintf(shard, sizeof shard, "%d/%d", k, shards);
    a->shard = shards > 1 ? shard : NULL;
    if (shards > 1)
        fprintf(stderr, "dmbench: drivers: %s, turn %d of %d: dmbench run %s --shard %s --out %s\n", driver, k,
                shards, sweep_path ? sweep_path : "(the default sweep)", shard, out);
    else
        fprintf(stderr, "dmbench: drivers: %s: dmbench run %s --out %s\n", driver,
                sweep_path ? sweep_path : "(the default sweep)", out);
    char *why = NULL;
    int failed = drivers__run(driver, sweep_path, out, a, &why) != 0;
    if (failed) {
        *why_out = shards > 1 ? dm_xasprintf("failed in turn %d of %d: %s", k, shards, why)
                              : dm_xasprintf("failed: %s", why);
        fprintf(stderr, "dmbench: drivers: %s %s; going on without it\n", driver, *why_out);
    }
    a->shard = NULL;
    free(why);
    free(out);
    return failed;
}

/* Merges driver's shard runs into root/driver; 0, or 1 with *why_out. */
static int drivers__merge(const char *driver, const char *root, int shards, char **why_out)
{
    char **dirs = dm_xcalloc((size_t)shards, sizeof *dirs);
    for (int k = 0; k < shards; k++)
        dirs[k] = dm_xasprintf("%s/%s/shard-%d-of-%d/latest", root, driver, k + 1, shards);
    char *out = dm_xasprintf("%s/%s", root, driver);
    int rc = cli_merge_dirs(out, dirs, shards, 0);
    if (rc != 0)
        *why_out = dm_xasprintf("failed: its %d shard runs could not be merged into %s (the reason is above)",
                                shards, out);
    for (int k = 0; k < shards; k++)
        free(dirs[k]);
    free(dirs);
    free(out);
    return rc != 0;
}

/* Marks the drivers that are not installed here (whys[i] = "left out:
 * ..."), saying so on stderr; returns how many. */
static size_t drivers__missing(char **names, size_t n, char **whys)
{
    size_t missing = 0;
    for (size_t i = 0; i < n; i++) {
        char *why = NULL;
        const char *miss = drivers_missing(drivers_find(names[i]), &why);
        if (miss) {
            whys[i] = dm_xasprintf("left out: %s", miss);
            fprintf(stderr, "dmbench: drivers: %s %s\n", names[i], whys[i]);
            missing++;
        }
        free(why);
    }
    return missing;
}

/* Loads driver's run from root/driver into *run; 0, or 1 with *why_out. */
static int drivers__load(const char *driver, const char *root, dm_run_result *run, char **why_out)
{
    char *dir = dm_xasprintf("%s/%s", root, driver);
    dm_str err = {0};
    int failed = compare_load_path(dir, run, &err) != 0;
    if (failed)
        *why_out = dm_xasprintf("failed: %s", dm_str_get(&err));
    dm_str_free(&err);
    free(dir);
    return failed;
}

int cli_drivers_main(const char *sweep_path, const char *list, const char *out, const char *seed,
                     int quiet, int interleave)
{
    drivers_args a = { .drivers = list, .out = out, .seed = seed, .quiet = quiet };
    const char *applied = getenv("DMBENCH_DRIVER");
    if (applied && *applied && strcmp(applied, "default") != 0)
        return cli_usage_error("drivers: DMBENCH_DRIVER=%s is set: unset it; `dmbench drivers` "
                               "chooses the driver of each run", applied);
    sweep sw;
    int rc = drivers__sweep(sweep_path, &sw);
    char **names = NULL;
    size_t n = 0;
    rc = rc ? rc : drivers__names(a.drivers, &sw, &names, &n);
    sweep_free(&sw);
    if (rc != 0)
        return rc;
    const char *root = a.out ? a.out : "results/drivers";
    if (dm_mkdirs(root) != 0) {
        for (size_t i = 0; i < n; i++)
            free(names[i]);
        free(names);
        return cli_usage_error("drivers: cannot create '%s'", root);
    }
    drivers_side *sides = dm_xcalloc(n + 1, sizeof *sides);
    dm_run_result *runs = dm_xcalloc(n + 1, sizeof *runs);
    char **whys = dm_xcalloc(n + 1, sizeof *whys);
    size_t missing = drivers__missing(names, n, whys), failed = 0, ran = 0;
    /* the turns: every driver still standing runs shard k before any runs k + 1 */
    int shards = interleave > 0 ? interleave : n - missing >= 2 ? DRIVERS__SHARDS : 1;
    for (int k = 1; k <= shards; k++)
        for (size_t i = 0; i < n; i++)
            if (!whys[i] && drivers__turn(names[i], sweep_path, root, k, shards, &a, &whys[i]))
                failed++;
    for (size_t i = 0; i < n; i++) {
        sides[i].driver = names[i];
        if (!whys[i] && shards > 1 && drivers__merge(names[i], root, shards, &whys[i]))
            failed++;
        if (!whys[i] && drivers__load(names[i], root, &runs[i], &whys[i]))
            failed++;
        sides[i].run = whys[i] ? NULL : &runs[i];
        sides[i].why = whys[i];
        ran += whys[i] == NULL;
    }
    dm_str err = {0};
    int we = 0;   /* drivers.md / drivers.json not written: 4 for the disk */
    if (rc == 0 && ran == 0 && failed == 0)
        rc = cli_usage_error("drivers: none of the drivers asked for is installed here "
                             "(scripts/install-mesa25 installs Mesa 25's llvmpipe and zink)");
    else if (rc == 0 && (we = drivers_report_write(sides, n, root, &err)) != 0)
        rc = cli_error(we, "drivers: %s", dm_str_get(&err));
    else if (rc == 0) {
        printf("%zu driver%s ran, %zu left out, %zu failed; side by side: %s/drivers.md\n", ran,
               ran == 1 ? "" : "s", missing, failed, root);
        rc = failed ? DM_EXIT_ENV : 0;
    }
    dm_str_free(&err);
    for (size_t i = 0; i < n; i++) {
        dm_run_free(&runs[i]);
        free(whys[i]);
        free(names[i]);
    }
    free(runs);
    free(whys);
    free(names);
    free(sides);
    return rc;
}
