/* cmd_merge.c — `dmbench merge OUT DIR...`: the union of shard runs.
 *
 * Every DIR is a run directory (its store is the dmbench.sqlite beside it).
 * The runs must come from the same sweep file and the same environment
 * fingerprint; their configurations are united by key into a new run in
 * OUT (OUT/dmbench.sqlite, OUT/<run-id>/ with images and report, OUT/latest).
 */
#include "cli.h"
#include "core/dm_error.h"
#include "store/store.h"
#include "reports/report.h"

#include <dirent.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Loads the run of a run directory; returns -1 on success or an exit code. */
static int merge__load(const char *dir, dm_run_result *out)
{
    char real[PATH_MAX];
    if (!realpath(dir, real))
        return cli_usage_error("merge: %s: no such run directory", dir);
    char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
    char *store_path = dm_xasprintf("%s/dmbench.sqlite", dirname(a));
    store *st = NULL;
    dm_str err = {0};
    int rc = -1;
    if (store_open(store_path, &st, &err) != 0)
        rc = cli_usage_error("merge: %s", dm_str_get(&err));
    else if (store_run_load(st, basename(b), out) != 0)
        rc = cli_usage_error("merge: %s: run %s is not in %s", dir, basename(b), store_path);
    store_close(st);
    dm_str_free(&err);
    free(store_path);
    free(a);
    free(b);
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
        if (!dm_file_exists(to) && dm_read_file(from, &data, &len) == 0)
            dm_write_file(to, data, len);
        free(data);
        free(from);
        free(to);
    }
    if (d)
        closedir(d);
    free(sdir);
}

/* Refuses runs that are not shards of one sweep in one environment. */
static int merge__compatible(const dm_run_result *a, const dm_run_result *b, const char *dir)
{
    const char *fa = dm_kv_get(a->environment, a->n_environment, "fingerprint");
    const char *fb = dm_kv_get(b->environment, b->n_environment, "fingerprint");
    if (!a->sweep_hash || !b->sweep_hash || strcmp(a->sweep_hash, b->sweep_hash) != 0)
        return cli_usage_error("merge: %s was made from a different sweep file (hash %s vs %s)", dir,
                                b->sweep_hash ? b->sweep_hash : "?", a->sweep_hash ? a->sweep_hash : "?");
    if (!fa || !fb || strcmp(fa, fb) != 0)
        return cli_usage_error("merge: %s was measured in a different environment "
                                "(fingerprint %s vs %s)", dir, fb ? fb : "?", fa ? fa : "?");
    return -1;
}

/* Moves the configurations and left-outs of src into dst (by key, first wins). */
static void merge__unite(dm_run_result *dst, dm_run_result *src)
{
    for (size_t i = 0; i < src->n_configs; i++) {
        int dup = 0;
        for (size_t j = 0; j < dst->n_configs && !dup; j++)
            dup = strcmp(dst->configs[j].key, src->configs[i].key) == 0;
        if (dup) {
            dm_config_result_free(&src->configs[i]);
            continue;
        }
        dst->configs = dm_xrealloc(dst->configs, (dst->n_configs + 1) * sizeof *dst->configs);
        dst->configs[dst->n_configs++] = src->configs[i];
    }
    src->n_configs = 0;
    dst->left_out = dm_xrealloc(dst->left_out, (dst->n_left_out + src->n_left_out + 1) * sizeof *dst->left_out);
    memcpy(dst->left_out + dst->n_left_out, src->left_out, src->n_left_out * sizeof *src->left_out);
    dst->n_left_out += src->n_left_out;
    src->n_left_out = 0;
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
    if (rc < 0 && store_open(store_path, &st, &err) != 0)
        rc = cli_usage_error("merge: %s", dm_str_get(&err));
    if (rc < 0 && store_run_begin(st, m, "merged") != 0)
        rc = cli_usage_error("merge: %s", store_last_error(st));
    for (size_t i = 0; rc < 0 && i < m->n_configs; i++)
        if (store_config_put(st, m->id, &m->configs[i]) != 0)
            rc = cli_usage_error("merge: %s", store_last_error(st));
    for (size_t i = 0; rc < 0 && i < m->n_left_out; i++)
        store_left_out_put(st, m->id, &m->left_out[i]);
    for (int i = 0; rc < 0 && i < n; i++)
        merge__copy_images(dirs[i], run_dir);
    char e[512] = "";
    if (rc < 0 && report_write_all(m, run_dir, e, sizeof e) != 0)
        rc = cli_usage_error("merge: report: %s", e);
    if (rc < 0) {
        char *link = dm_xasprintf("%s/latest", out);
        unlink(link);
        if (symlink(m->id, link) != 0)
            dm_log(DM_LOG_WARN, "%s: cannot create the 'latest' link", link);
        free(link);
        printf("merged %d runs, %zu configurations: %s/report.html\n", n, m->n_configs, run_dir);
        rc = 0;
    }
    store_close(st);
    dm_str_free(&err);
    free(store_path);
    free(img);
    free(run_dir);
    return rc;
}

int cli_merge(int argc, char **argv)
{
    int rc = cli_parse(argc, argv, NULL, &argc);
    if (rc >= 0)
        return rc;
    if (argc < 2)
        return cli_usage_error("usage: dmbench merge OUT DIR...   (DIR: run directories of shards)");
    dm_run_result merged = {0};
    rc = merge__load(argv[1], &merged);
    for (int i = 2; rc < 0 && i < argc; i++) {
        dm_run_result r = {0};
        rc = merge__load(argv[i], &r);
        if (rc < 0)
            rc = merge__compatible(&merged, &r, argv[i]);
        if (rc < 0)
            merge__unite(&merged, &r);
        dm_run_free(&r);
    }
    if (rc < 0)
        rc = merge__write(&merged, argv[0], argv + 1, argc - 1);
    dm_run_free(&merged);
    return rc;
}
