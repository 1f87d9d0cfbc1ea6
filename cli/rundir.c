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

int cli_load_run(const char *dir, dm_run_result *run, dm_str *err)
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
