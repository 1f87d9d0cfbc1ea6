/* compare_input.c — where the regression gate's runs come from: results
 * files, run directories, the store, and accepted baselines (compare.h). */
#include "gate/compare.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "store/store.h"
#include "reports/report.h"

static int compare__is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* A run directory without results.json: load it from the store beside it
 * (run id = the directory's name). */
static int compare__load_dir_store(const char *dir, dm_run_result *out, dm_str *err)
{
    char real[PATH_MAX];
    if (!realpath(dir, real)) {
        dm_str_printf(err, "%s: no such run directory", dir);
        return DM_ERR_NOTFOUND;
    }
    char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
    char *store_path = dm_xasprintf("%s/dmbench.sqlite", dirname(a));
    int rc = DM_ERR_NOTFOUND;
    if (dm_file_exists(store_path))
        rc = compare_load_store(store_path, basename(b), NULL, out, err);
    else
        dm_str_printf(err, "%s: neither results.json nor a store beside it (%s)", dir, store_path);
    free(store_path);
    free(a);
    free(b);
    return rc;
}

/* A results file with a negative or infinite time is damaged or forged:
 * the geometric mean of ratios would be NaN.  DM_ERR_PARSE naming it. */
static int compare__times_ok(const char *path, const dm_run_result *r, dm_str *err)
{
    for (size_t i = 0; i < r->n_configs; i++)
        for (size_t k = 0; k < r->configs[i].n_counters; k++) {
            const dm_counter_result *c = &r->configs[i].counters[k];
            int time = c->unit && strcmp(c->unit, "ns") == 0;
            double v[3] = { c->value, c->median, c->n_samples ? c->min : NAN };
            for (int j = 0; time && j < 3; j++)
                if (v[j] < 0 || isinf(v[j])) {
                    dm_str_printf(err, "%s: configuration %s: %s is %g ns; a time is finite and "
                                  ">= 0 (is the file damaged?)", path, r->configs[i].key,
                                  c->name, v[j]);
                    return DM_ERR_PARSE;
                }
        }
    return 0;
}

int compare_load_path(const char *path, dm_run_result *out, dm_str *err)
{
    memset(out, 0, sizeof *out);
    if (!compare__is_dir(path)) {
        char e[512] = "";
        int rc = dm_file_exists(path) ? report_read_json(path, out, e, sizeof e) : DM_ERR_NOTFOUND;
        if (rc == DM_ERR_NOTFOUND)
            dm_str_printf(err, "%s: no such file or run directory", path);
        else if (rc)
            dm_str_printf(err, "%s", e);
        if (rc == 0 && (rc = compare__times_ok(path, out, err)) != 0)
            dm_run_free(out);   /* refused: nothing half-loaded is handed back */
        return rc;
    }
    char *json = dm_xasprintf("%s/results.json", path);
    char *latest = dm_xasprintf("%s/latest", path);
    int rc;
    if (dm_file_exists(json))
        rc = compare_load_path(json, out, err);
    else if (compare__is_dir(latest))   /* an output root */
        rc = compare_load_path(latest, out, err);
    else
        rc = compare__load_dir_store(path, out, err);
    free(json);
    free(latest);
    return rc;
}

int compare_load_store(const char *store_path, const char *run_id, const char *tag,
                       dm_run_result *out, dm_str *err)
{
    memset(out, 0, sizeof *out);
    if (!dm_file_exists(store_path)) {
        dm_str_printf(err, "%s: no such results store", store_path);
        return DM_ERR_NOTFOUND;
    }
    store *st = NULL;
    int rc = store_open(store_path, &st, err);
    if (rc)
        return rc;
    char *id = run_id ? dm_xstrdup(run_id) : NULL;
    if (!id && (rc = store_latest_run(st, tag, &id)) != 0)
        dm_str_printf(err, "%s: no run%s%s%s", store_path, tag ? " tagged '" : "", tag ? tag : "",
                      tag ? "'" : "");
    if (!rc && (rc = store_run_load(st, id, out)) != 0)
        dm_str_printf(err, "%s: run '%s' %s", store_path, id,
                      rc == DM_ERR_NOTFOUND ? "not found" : store_last_error(st));
    free(id);
    store_close(st);
    return rc;
}

char *compare_baselines_path(const char *store_path)
{
    char *a = dm_xstrdup(store_path);
    char *p = dm_xasprintf("%s/baselines.json", dirname(a));
    free(a);
    return p;
}

/* Parsed baselines.json (an empty list when the file does not exist). */
static int compare__baselines_read(const char *path, cJSON **root, dm_str *err)
{
    char *text = NULL;
    if (!dm_file_exists(path)) {
        *root = cJSON_CreateObject();
        cJSON_AddArrayToObject(*root, "baselines");
        return 0;
    }
    char why[256] = "";
    if (dm_input_file(path, why, sizeof why) != 0 || dm_read_file(path, &text, NULL) != 0) {
        dm_str_printf(err, "%s: cannot read: %s", path, why[0] ? why : strerror(errno));
        return DM_ERR_IO;
    }
    *root = cJSON_Parse(text);
    free(text);
    if (!*root || !cJSON_IsArray(cJSON_GetObjectItemCaseSensitive(*root, "baselines"))) {
        cJSON_Delete(*root);
        *root = NULL;
        dm_str_printf(err, "%s: malformed (expected {\"baselines\": [...]})", path);
        return DM_ERR_PARSE;
    }
    return 0;
}

int compare_baseline_accept(const char *store_path, const char *run_id, const char *reason,
                            dm_str *err)
{
    if (!reason || !*reason) {
        dm_str_cat(err, "baseline accept: --reason TEXT is required (why the change is intended)");
        return DM_ERR_ARG;
    }
    dm_run_result run;
    int rc = compare_load_store(store_path, run_id, NULL, &run, err);
    if (rc)
        return rc;
    char *path = compare_baselines_path(store_path);
    cJSON *root = NULL;
    if ((rc = compare__baselines_read(path, &root, err)) == 0) {
        char now[32];
        dm_iso8601_now(now);
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "run", run_id);
        cJSON_AddStringToObject(e, "sweep", run.sweep ? run.sweep : "");
        cJSON_AddStringToObject(e, "reason", reason);
        cJSON_AddStringToObject(e, "accepted", now);
        cJSON_AddItemToArray(cJSON_GetObjectItemCaseSensitive(root, "baselines"), e);
        char *text = cJSON_Print(root);
        rc = text ? dm_write_file(path, text, strlen(text)) : DM_ERR_NOMEM;
        if (rc)
            dm_str_printf(err, "%s: cannot write: %s", path, strerror(errno));
        free(text);
    }
    cJSON_Delete(root);
    free(path);
    dm_run_free(&run);
    return rc;
}

int compare_baseline_latest(const char *store_path, const char *sweep, char **run_id,
                            char **reason, dm_str *err)
{
    char *path = compare_baselines_path(store_path);
    cJSON *root = NULL;
    int rc = compare__baselines_read(path, &root, err);
    *run_id = NULL;
    if (rc == 0) {
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(root, "baselines"), *e, *hit = NULL;
        cJSON_ArrayForEach(e, list) {   /* append order: the last match is the newest */
            const char *s = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(e, "sweep"));
            if (cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(e, "run")) &&
                (!sweep || (s && strcmp(s, sweep) == 0)))
                hit = e;
        }
        if (hit) {
            *run_id = dm_xstrdup(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(hit, "run")));
            if (reason)
                *reason = dm_xstrdup(cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(hit, "reason")));
        } else {
            dm_str_printf(err, "%s: no accepted baseline%s%s (use `dmbench baseline accept RUN "
                          "--reason TEXT`)", path, sweep ? " for sweep " : "", sweep ? sweep : "");
            rc = DM_ERR_NOTFOUND;
        }
    }
    cJSON_Delete(root);
    free(path);
    return rc;
}
