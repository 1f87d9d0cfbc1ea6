/* recommend_run.c — a run's configurations as recommendation points, the
 * budget, the family and why a scene has no pick (recommend_run.h); the
 * report model calls these once per run. */
#include "reports/recommend_run.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int report_budget_set(dm_run_result *run, double ms)
{
    if (!(ms > 0) || !isfinite(ms))
        return DM_ERR_ARG;
    char buf[32];
    report__fmt_num(ms, buf);
    for (size_t i = 0; i < run->n_environment; i++)
        if (strcmp(run->environment[i].key, REPORT_BUDGET_KEY) == 0) {
            free(run->environment[i].value);
            run->environment[i].value = dm_xstrdup(buf);
            return 0;
        }
    dm_kv_push(&run->environment, &run->n_environment, REPORT_BUDGET_KEY, buf);
    return 0;
}

double report_budget_ms(const dm_run_result *run)
{
    const char *v = dm_kv_get(run->environment, run->n_environment, REPORT_BUDGET_KEY);
    double ms = v ? strtod(v, NULL) : 0;
    return ms > 0 && isfinite(ms) ? ms : 0;
}

recommend_family report_family(const dm_config_result *c)
{
    if (dm_kv_get(c->params, c->n_params, "tess_level"))
        return RECOMMEND_TESSELLATION;
    if (dm_kv_get(c->params, c->n_params, "vertex_filter"))
        return RECOMMEND_VERTEX;
    if (!dm_kv_get(c->params, c->n_params, "lighting"))
        return RECOMMEND_UNLIT;
    return RECOMMEND_FRAGMENT;
}

/* The scene's points (ok configurations with a frame time) and their
 * config indexes; returns the count.  *p and *idx are malloc'd. */
static size_t recommend_run__points(const dm_run_result *run, const char *scene, recommend_point **p,
                             size_t **idx)
{
    size_t nr = report__scene_rows(run, scene, idx), n = 0;
    report_metric m = report_metric_of_run(run);
    *p = dm_xcalloc(nr + 1, sizeof **p);
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[(*idx)[i]];
        const dm_counter_result *t = report__frame_time(c);
        if (!t)
            continue;
        (*p)[n] = (recommend_point){t->median, t->ci_lo, t->ci_hi, report_metric_error(&c->quality, m),
                                    report_family(c)};
        (*idx)[n++] = (*idx)[i];
    }
    return n;
}

static size_t recommend_run__map(const size_t *idx, size_t i)
{
    return i == RECOMMEND_NONE ? RECOMMEND_NONE : idx[i];
}

size_t report_recommend(const dm_run_result *run, const char *scene, recommend_result *out)
{
    recommend_point *p;
    size_t *idx, n = recommend_run__points(run, scene, &p, &idx);
    recommend_desc d = {.budget = report_budget_ms(run) * 1e6,
                        .epsilon = report_metric_epsilon(report_metric_of_run(run))};
    recommend_scene(p, n, &d, out);
    out->pick = recommend_run__map(idx, out->pick);
    out->pick_tie = recommend_run__map(idx, out->pick_tie);
    out->fastest = recommend_run__map(idx, out->fastest);
    out->knee = recommend_run__map(idx, out->knee);
    for (int f = 0; f < RECOMMEND_FAMILY_COUNT; f++) {
        out->family_best[f] = recommend_run__map(idx, out->family_best[f]);
        out->family_fastest[f] = recommend_run__map(idx, out->family_fastest[f]);
    }
    free(p);
    free(idx);
    return n;
}

const char *report_untimed_reason(const dm_run_result *run, const char *scene)
{
    size_t *rows, nr = report__scene_rows(run, scene, &rows), timed = 0, wall = 0;
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        timed += report__frame_time(c) != NULL;
        wall += dm_config_counter(c, "WallTime") != NULL;
    }
    free(rows);
    if (timed)
        return NULL;
    if (!nr)
        return "no configuration finished: no budget or pick";
    if (wall)
        return "WallTime unavailable on every configuration: no budget or pick";
    return "no timing counter measured: no budget or pick";
}
