/* cmd_baseline.c — `dmbench baseline accept RUN --reason TEXT` and
 * `dmbench baseline show`: the accepted baselines of a store, the BASE of
 * `dmbench compare --baseline`. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "gate/compare.h"

#include <libgen.h>
#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define BASELINE__DEFAULT_STORE "results/dmbench.sqlite"

typedef struct baseline_args {
    const char *reason, *store;
} baseline_args;

const char *const cli_baseline_actions[] = { "accept", "show", NULL };

const cli_option cli_baseline_options[] = {
    CLI_STRING("reason", baseline_args, reason, "TEXT",
               "accept: why this run is the new baseline (stored with it)"),
    { .name = "store", .kind = CLI_OPT_STRING, .offset = offsetof(baseline_args, store),
      .value_name = "FILE", .help = "the results store [default beside RUN, or " BASELINE__DEFAULT_STORE "]" },
    CLI_OPT_END
};

/* RUN as a run directory (store beside it, id = its name) or, with
 * --store, a run id. */
static int baseline__target(const char *run, const char *store, char **store_path, char **id)
{
    struct stat st;
    char real[PATH_MAX];
    if (stat(run, &st) == 0 && S_ISDIR(st.st_mode) && realpath(run, real)) {
        char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
        *id = dm_xstrdup(basename(a));
        *store_path = store ? dm_xstrdup(store) : dm_xasprintf("%s/dmbench.sqlite", dirname(b));
        free(a);
        free(b);
        return -1;
    }
    if (!store)
        return cli_usage_error("baseline: '%s' is not a run directory (give a run directory, or "
                                "--store FILE and a run id)", run);
    *store_path = dm_xstrdup(store);
    *id = dm_xstrdup(run);
    return -1;
}

/* show: the newest accepted baseline of the store. */
static int baseline__show(const char *store, dm_str *err)
{
    char *id = NULL, *why = NULL;
    int rc = compare_baseline_latest(store ? store : BASELINE__DEFAULT_STORE, NULL, &id, &why, err);
    char *buf = NULL;
    if (rc == 0)   /* the reason is user text: no control byte reaches the terminal */
        printf("%s\t%s\n", id, dm_term_safe(why, &buf));
    free(buf);
    free(why);
    free(id);
    return rc;
}

/* `dmbench baseline accept RUN --reason TEXT | show`.  Exit 2 when the
 * store or the run cannot be used, 4 when the store is damaged or newer. */
int cli_baseline(const cli_command *self, int argc, char **argv)
{
    baseline_args args = {0}, *a = &args;
    int rc = cli_parse(self, argc, argv, a, &argc);
    if (rc < 0 && argc < 1)
        rc = cli_usage_error("usage: dmbench baseline accept RUN --reason TEXT [--store FILE] | "
                             "baseline show [--store FILE]");
    if (rc < 0 && strcmp(argv[0], "accept") != 0 && strcmp(argv[0], "show") != 0) {
        dm_str m = {0};
        dm_str_printf(&m, "baseline: unknown action '%s'", argv[0]);
        dm_str_suggest(&m, argv[0], cli_baseline_actions, 2, "actions");
        rc = cli_usage_error("%s", dm_str_get(&m));
        dm_str_free(&m);
    }
    if (rc >= 0)
        return rc;
    if (argc > 2)
        return cli_usage_error("baseline: only one RUN may be given");
    dm_str err = {0};
    char *store_path = NULL, *id = NULL;
    if (strcmp(argv[0], "show") == 0) {
        rc = baseline__show(a->store, &err);
    } else {
        if (argc < 2)
            return cli_usage_error("baseline accept: missing RUN (a run directory, e.g. results/latest)");
        if ((rc = baseline__target(argv[1], a->store, &store_path, &id)) >= 0)
            return rc;
        rc = compare_baseline_accept(store_path, id, a->reason, &err);
        if (rc == 0)
            printf("accepted run %s as the baseline of %s\n", id, store_path);
    }
    if (rc)
        rc = cli_error(rc, "%s", dm_str_get(&err));   /* a damaged store: 4 */
    dm_str_free(&err);
    free(store_path);
    free(id);
    return rc;
}
