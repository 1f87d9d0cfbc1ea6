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

/* A configuration index with its key, for sorting by key. */
typedef struct recommend_run__keyed {
    const char *key;
    size_t i;
} recommend_run__keyed;

static int recommend_run__by_key(const void *a, const void *b)
{
    return strcmp(((const recommend_run__keyed *)a)->key, ((const recommend_run__keyed *)b)->key);
}

/* idx[0..n) in the order of their configurations' keys: an order the
 * measuring does not move (a run stores configurations in the order they
 * were measured). */
static void recommend_run__sort_by_key(const dm_run_result *run, size_t *idx, size_t n)
{
    recommend_run__keyed *k = dm_xcalloc(n + 1, sizeof *k);
    for (size_t i = 0; i < n; i++)
        k[i] = (recommend_run__keyed){ run->configs[idx[i]].key, idx[i] };
    qsort(k, n, sizeof *k, recommend_run__by_key);
    for (size_t i = 0; i < n; i++)
        idx[i] = k[i].i;
    free(k);
}

/* The scene's points (ok configurations with a frame time) and their
 * config indexes, in the order of their keys; returns the count.  *p and
 * *idx are malloc'd.  With corrected, a frame time with the drift removed
 * gives its corrected median and CI (run/precision.h), the others their
 * raw ones. */
static size_t recommend_run__points(const dm_run_result *run, const char *scene, int corrected,
                                    recommend_point **p, size_t **idx)
{
    size_t nr = report__scene_rows(run, scene, idx), n = 0;
    recommend_run__sort_by_key(run, *idx, nr);
    report_metric m = report_metric_of_run(run);
    *p = dm_xcalloc(nr + 1, sizeof **p);
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[(*idx)[i]];
        const dm_counter_result *t = report__frame_time(c);
        if (!t)
            continue;
        int corr = corrected && t->corrected;
        (*p)[n] = (recommend_point){corr ? t->corr_median : t->median, corr ? t->corr_ci_lo : t->ci_lo,
                                    corr ? t->corr_ci_hi : t->ci_hi, report_metric_error(&c->quality, m),
                                    report_family(c)};
        (*idx)[n++] = (*idx)[i];
    }
    return n;
}

static size_t recommend_run__map(const size_t *idx, size_t i)
{
    return i == RECOMMEND_NONE ? RECOMMEND_NONE : idx[i];
}

double report_resolvable(const dm_run_result *run)
{
    double floor, resolvable;
    return dm_run_noise_floor(run, &floor, &resolvable) ? resolvable : NAN;
}

/* report_recommend on the raw or the corrected figures. */
static size_t recommend_run__recommend(const dm_run_result *run, const char *scene, int corrected,
                                       recommend_result *out)
{
    recommend_point *p;
    size_t *idx, n = recommend_run__points(run, scene, corrected, &p, &idx);
    double res = report_resolvable(run);
    recommend_desc d = {.budget = report_budget_ms(run) * 1e6,
                        .epsilon = report_metric_epsilon(report_metric_of_run(run)),
                        .resolvable = isfinite(res) ? res : 0, .check_budget = 1};
    recommend_scene(p, n, &d, out);
    out->pick = recommend_run__map(idx, out->pick);
    out->pick_tie = recommend_run__map(idx, out->pick_tie);
    out->fastest = recommend_run__map(idx, out->fastest);
    out->knee = recommend_run__map(idx, out->knee);
    out->near_miss = recommend_run__map(idx, out->near_miss);
    out->moved_pick = recommend_run__map(idx, out->moved_pick);
    for (int f = 0; f < RECOMMEND_FAMILY_COUNT; f++) {
        out->family_best[f] = recommend_run__map(idx, out->family_best[f]);
        out->family_fastest[f] = recommend_run__map(idx, out->family_fastest[f]);
    }
    free(p);
    free(idx);
    return n;
}

size_t report_recommend(const dm_run_result *run, const char *scene, recommend_result *out)
{
    return recommend_run__recommend(run, scene, 0, out);
}

/* 1 when some ok configuration of the scene has its frame time corrected. */
static int recommend_run__scene_corrected(const dm_run_result *run, const char *scene)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const dm_counter_result *t = c->ok && c->scene && strcmp(c->scene, scene) == 0
                                         ? report__frame_time(c) : NULL;
        if (t && t->corrected)
            return 1;
    }
    return 0;
}

int report_recommend_corrected(const dm_run_result *run, const char *scene, recommend_result *out)
{
    if (!recommend_run__scene_corrected(run, scene))
        return 0;
    recommend_run__recommend(run, scene, 1, out);
    return 1;
}

int report_answer_disagree(const dm_run_result *run, const char *scene, dm_str *out)
{
    recommend_result r, c;
    if (report_untimed_reason(run, scene) || !report_recommend_corrected(run, scene, &c))
        return 0;
    size_t had = out->len;
    report_recommend(run, scene, &r);
    dm_str a = {0}, b = {0};
    if (r.pick != c.pick) {
        if (r.pick != RECOMMEND_NONE)
            report__config_label(run, &run->configs[r.pick], &a);
        if (c.pick != RECOMMEND_NONE)
            report__config_label(run, &run->configs[c.pick], &b);
        if (c.pick == RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed nothing fits the budget; the answer reads the raw figures.");
        else if (r.pick == RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick is %s; the answer reads the raw figures, where nothing "
                          "fits.", dm_str_get(&b));
        else
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick is %s, not %s; the answer reads the raw figures.",
                          dm_str_get(&b), dm_str_get(&a));
    } else if (r.pick_tie != c.pick_tie) {
        size_t t = c.pick_tie != RECOMMEND_NONE ? c.pick_tie : r.pick_tie;
        report__config_label(run, &run->configs[t], &b);
        if (c.pick_tie != RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick ties with %s%s.", dm_str_get(&b),
                          r.pick_tie != RECOMMEND_NONE ? " instead" : "");
        else
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick does not tie with %s; its time is told apart.", dm_str_get(&b));
    }
    dm_str_free(&a);
    dm_str_free(&b);
    return out->len > had;
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
