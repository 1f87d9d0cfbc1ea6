/* rundir.c — a run directory given on the command line: the run it names,
 * loaded from the results store beside it without creating anything. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "store/store.h"

#include <libgen.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

int cli_run_locate(const char *dir, char **store_path, char **run_id, dm_str *err)
{
    char real[PATH_MAX];
    *store_path = *run_id = NULL;
    if (!realpath(dir, real)) {
        dm_str_printf(err, "%s: no such run directory", dir);
        return DM_ERR_ARG;
    }
    char *own = dm_xasprintf("%s/dmbench.sqlite", real);
    int is_root = dm_file_exists(own);
    free(own);
    if (is_root) {   /* the --out of a run, not one of its runs */
        size_t len = strlen(dir);
        while (len > 1 && dir[len - 1] == '/')
            len--;   /* "out/" names out/latest, not out//latest */
        char *latest = dm_xasprintf("%.*s/latest", (int)len, dir), lreal[PATH_MAX];
        dm_str_printf(err, "%s is a results root (it holds dmbench.sqlite), not a run directory: give "
                           "one of its runs, ", dir);
        if (realpath(latest, lreal)) {
            char *l = dm_xstrdup(lreal);
            dm_str_printf(err, "e.g. %s (the newest, %s)", latest, basename(l));
            free(l);
        } else {
            dm_str_printf(err, "e.g. %s/<run-id>", dir);
        }
        free(latest);
        return DM_ERR_ARG;
    }
    char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
    *run_id = dm_xstrdup(basename(a));
    const char *parent = dirname(b);
    *store_path = dm_xasprintf("%s/dmbench.sqlite", strcmp(parent, "/") == 0 ? "" : parent);
    free(a);
    free(b);
    if (!dm_file_exists(*store_path)) {
        dm_str_printf(err, "%s: not a run directory: no results store beside it (%s); give a run "
                           "directory, e.g. results/latest", dir, *store_path);
        free(*store_path);
        free(*run_id);
        *store_path = *run_id = NULL;
        return DM_ERR_ARG;
    }
    return 0;
}

int cli_load_run(const char *dir, dm_run_result *run, dm_str *err)
{
    char *store_path = NULL, *run_id = NULL;
    int rc = cli_run_locate(dir, &store_path, &run_id, err);
    store *st = NULL;
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
    free(store_path);
    free(run_id);
    return rc;
}
