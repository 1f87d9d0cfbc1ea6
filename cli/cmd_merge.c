/* cmd_merge.c — `dmbench merge OUT DIR... [--allow-missing]`: the union of
 * shard runs.
 *
 * Every DIR is a run directory (its store is the dmbench.sqlite beside it;
 * nothing is created when it is missing).  The rules (same sweep, each shard
 * once, each key once, missing shards reported, machines kept apart) are
 * store/merge.h's; the merged run goes into OUT (OUT/dmbench.sqlite,
 * OUT/<run-id>/ with images and report, OUT/latest).
 */
#include "cli.h"
#include "reports/published_report.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "store/merge.h"
#include "store/store.h"
#include "reports/report.h"
#include "run/precision.h"

#include <dirent.h>
#include <libgen.h>
#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Loads the run of a run directory without creating anything; returns -1
 * on success or an exit code. */
static int merge__load(const char *dir, dm_run_result *out)
{
    char *store_path = NULL, *run_id = NULL;
    store *st = NULL;
    dm_str err = {0};
    int rc = -1, e = 0;
    if (cli_run_locate(dir, &store_path, &run_id, &err) != 0)
        rc = cli_usage_error("merge: %s", dm_str_get(&err));
    else if ((e = store_open(store_path, &st, &err)) != 0 || (e = store_check(st, &err)) != 0)
        rc = cli_error(e, "merge: %s", dm_str_get(&err));
    else if ((e = store_run_load(st, run_id, out)) == DM_ERR_NOTFOUND)
        rc = cli_usage_error("merge: %s: run %s is not in %s", dir, run_id, store_path);
    else if (e != 0)
        rc = cli_error(DM_ERR_STORE, "merge: %s", store_last_error(st));
    store_close(st);
    dm_str_free(&err);
    free(store_path);
    free(run_id);
    return rc;
}

/* Copies every file of src/img into dst/img. */
static void merge__copy_images(const char *src_run, const char *dst_run)
{
    char *sdir = dm_xasprintf("%s/img", src_run);
    DIR *d = opendir(sdir);
    for (struct dirent *e; d && (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        char *from = dm_xasprintf("%s/%s", sdir, e->d_name);
        char *to = dm_xasprintf("%s/img/%s", dst_run, e->d_name);
        char *data = NULL;
        size_t len = 0;
        if (!dm_file_exists(to) && dm_input_file(from, NULL, 0) == 0 &&
            dm_read_file(from, &data, &len) == 0)
            dm_write_file(to, data, len);
        free(data);
        free(from);
        free(to);
    }
    if (d)
        closedir(d);
    free(sdir);
}

/* Writes the merged run into OUT: store, images, report, latest link. */
static int merge__write(dm_run_result *m, const char *out, char **dirs, int n)
{
    char stamp[32];
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S-merged", &tm);
    free(m->id);
    m->id = dm_xstrdup(stamp);
    char *run_dir = dm_xasprintf("%s/%s", out, m->id), *img = dm_xasprintf("%s/img", run_dir);
    char *store_path = dm_xasprintf("%s/dmbench.sqlite", out);
    store *st = NULL;
    dm_str err = {0};
    int rc = dm_mkdirs(img) == 0 ? -1 : cli_usage_error("merge: %s: cannot create the run directory", run_dir);
    int se = 0;
    if (rc < 0 && (se = store_open(store_path, &st, &err)) != 0)
        rc = cli_error(se, "merge: %s", dm_str_get(&err));
    if (rc < 0 && store_run_begin(st, m, "merged") != 0)
        rc = cli_usage_error("merge: %s", store_last_error(st));
    for (size_t i = 0; rc < 0 && i < m->n_configs; i++)
        if (store_config_put(st, m->id, &m->configs[i]) != 0)
            rc = cli_usage_error("merge: %s", store_last_error(st));
    for (size_t i = 0; rc < 0 && i < m->n_left_out; i++)
        store_left_out_put(st, m->id, &m->left_out[i]);
    for (size_t i = 0; rc < 0 && i < m->n_rounds; i++)
        store_round_put(st, m->id, &m->rounds[i]);
    if (rc < 0 && store_precision_put(st, m->id, m) != 0)
        rc = cli_usage_error("merge: %s", store_last_error(st));
    for (int i = 0; rc < 0 && i < n; i++)
        merge__copy_images(dirs[i], run_dir);
    char *pub = dm_xasprintf("%s/published.json", run_dir);   /* the same sweep: the first shard's */
    char e[512] = "";
    for (int i = 0; rc < 0 && i < n && !dm_file_exists(pub); i++)
        if (report_published_copy(dirs[i], run_dir, e, sizeof e) != 0)
            dm_log(DM_LOG_WARN, "%s; the report has no published section", e);
    free(pub);
    int we = rc < 0 ? report_write_run(m, &(report_desc){.dir = run_dir}, e, sizeof e) : 0;
    if (we)
        rc = cli_error(we, "merge: report: %s", e);
    if (rc < 0) {
        char *link = dm_xasprintf("%s/latest", out);
        unlink(link);
        if (symlink(m->id, link) != 0)
            dm_log(DM_LOG_WARN, "%s: cannot create the 'latest' link", link);
        free(link);
        printf("merged %d runs, %zu configurations: %s/report.html\n", n, m->n_configs, run_dir);
        rc = DM_EXIT_OK;
    }
    store_close(st);
    dm_str_free(&err);
    free(store_path);
    free(img);
    free(run_dir);
    return rc;
}

typedef struct merge_args {
    int allow_missing;
} merge_args;

const cli_option cli_merge_options[] = {
    CLI_BOOL("allow-missing", merge_args, allow_missing,
             "merge even with missing or incomplete shards (noted in the run)"),
    CLI_OPT_END
};

/* Refuses (exit 2) or, with --allow-missing, records missing and incomplete
 * shards as a run warning; returns -1 to go on or an exit code. */
static int merge__check_missing(merge_state *m, int allow_missing)
{
    dm_str lines = {0};
    size_t n = merge_missing(m, &lines);
    int rc = -1;
    if (n && !allow_missing) {
        rc = cli_usage_error("merge: %zu shard%s missing or incomplete:\n%s"
                              "(resume a shard with dmbench run ... --shard K/N --resume, or merge "
                              "anyway with --allow-missing)", n, n == 1 ? "" : "s", dm_str_get(&lines));
    } else if (n) {
        fprintf(stderr, "dmbench: warning: merging without %zu missing or incomplete shard%s:\n%s",
                n, n == 1 ? "" : "s", dm_str_get(&lines));
        dm_run_result *r = &m->out;
        DM_VEC_PUSH(r->warnings, r->n_warnings, dm_xasprintf("merged with --allow-missing; missing or "
                                                    "incomplete: %s", dm_str_get(&lines)));
    }
    dm_str_free(&lines);
    return rc;
}

int cli_merge(const cli_command *self, int argc, char **argv)
{
    merge_args args = {0};
    int rc = cli_parse(self, argc, argv, &args, &argc);
    if (rc >= 0)
        return rc;
    if (argc < 2)
        return cli_usage_error("usage: dmbench merge OUT DIR... [--allow-missing]   (DIR: run "
                               "directories of shards, e.g. results/s1/latest)");
    return cli_merge_dirs(argv[0], argv + 1, argc - 1, args.allow_missing);
}

int cli_merge_dirs(const char *out, char **dirs, int n, int allow_missing)
{
    int rc = -1;
    merge_state m = {0};
    for (int i = 0; rc < 0 && i < n; i++) {
        dm_run_result r = {0};
        dm_str err = {0};
        rc = merge__load(dirs[i], &r);
        if (rc < 0 && merge_add(&m, &r, dirs[i], &err) != 0)
            rc = cli_usage_error("merge: %s", dm_str_get(&err));
        dm_run_free(&r);
        dm_str_free(&err);
    }
    rc = rc < 0 ? merge__check_missing(&m, allow_missing) : rc;
    if (rc < 0) {
        merge_finish(&m);
        precision_apply(&m.out, 1);   /* the drift removed again, over the union's rounds */
        if (merge_machines(&m) > 1)
            fprintf(stderr, "dmbench: merge: %zu machines (environment fingerprints differ): "
                    "configurations are kept apart by machine, never pooled\n", merge_machines(&m));
        rc = merge__write(&m.out, out, dirs, n);
    }
    merge_free(&m);
    return rc;
}
