/* trends.c — trend lines for report.html from the store (trends.h). */
#include "run/trends.h"

#include "core/dm_error.h"
#include "store/store_history.h"

#include <stdlib.h>
#include <string.h>

/* The medians of points[0..k], k = the position of run_id; 0 when absent. */
static size_t trends__upto(const store_history_point *p, size_t n, const char *run_id, double **out)
{
    size_t k = 0;
    while (k < n && strcmp(p[k].run_id, run_id) != 0)
        k++;
    if (k == n)
        return 0;
    *out = dm_xcalloc(k + 1, sizeof **out);
    for (size_t i = 0; i <= k; i++)
        (*out)[i] = p[i].median;
    return k + 1;
}

int run_trends(store *st, const dm_run_result *run, report_trends *out)
{
    memset(out, 0, sizeof *out);
    char *fp = NULL;
    if (!run->id || store_run_fingerprint(st, run->id, &fp) != 0)
        return DM_ERR_STORE;
    out->items = dm_xcalloc(run->n_configs + 1, sizeof *out->items);
    int rc = 0;
    for (size_t i = 0; i < run->n_configs && !rc; i++) {
        const dm_config_result *c = &run->configs[i];
        store_history_point *p;
        size_t n;
        if (!c->ok || !c->key)
            continue;
        rc = store_history(st, c->key, fp, &p, &n);
        report_trend *t = &out->items[out->n];
        if (!rc && (t->n = trends__upto(p, n, run->id, &t->median_ns)) > 0) {
            t->key = dm_xstrdup(c->key);
            out->n++;
        }
        if (!rc)
            store_history_free(p, n);
    }
    free(fp);
    if (rc)
        report_trends_free(out), memset(out, 0, sizeof *out);
    return rc;
}
