/* proxy.c — WallTime against Instructions across a run (see proxy.h). */
#include "reports/proxy.h"
#include "core/dm_error.h"
#include "counters/counters.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The pair (Instructions per frame, WallTime median ns) of an ok
 * configuration; 0 when it lacks either. */
static int proxy__pair(const dm_config_result *c, double *x, double *y)
{
    const dm_counter_result *i = dm_config_counter(c, "Instructions");
    const dm_counter_result *w = dm_config_counter(c, "WallTime");
    if (!c->ok || !i || !w || !i->available || !w->available)
        return 0;
    *x = i->value;
    *y = w->has_samples ? w->median : w->value;
    return isfinite(*x) && isfinite(*y) && *x > 0 && *y > 0;
}

/* "TECHNIQUE SCENE k=v ..." with the other params that tell c apart
 * within the run (its key when there is nothing). */
static void proxy__label(const dm_run_result *run, const dm_config_result *c, char *buf, size_t cap)
{
    const char *tech = dm_kv_get(c->params, c->n_params, "technique");
    int w0 = snprintf(buf, cap, "%s%s%s", tech ? tech : "", tech ? " " : "", c->scene ? c->scene : "");
    size_t len = w0 > 0 && (size_t)w0 < cap ? (size_t)w0 : 0;
    for (size_t i = 0; i < c->n_params && len + 1 < cap; i++) {
        const char *k = c->params[i].key;
        if (!dm_run_param_varies(run, &c->params[i]) || strcmp(k, "technique") == 0 ||
            strcmp(k, "mesh") == 0 || strcmp(k, "resolution") == 0)
            continue;
        int w = snprintf(buf + len, cap - len, "%s%s=%s", len ? " " : "", c->params[i].key,
                         c->params[i].value ? c->params[i].value : "");
        len += w > 0 ? (size_t)w : 0;
    }
    if (!buf[0])
        snprintf(buf, cap, "%s", c->key ? c->key : "?");
}

/* Keeps the REPORT_PROXY_STRAYS largest |residual_rel|, largest first. */
static void proxy__stray(report_proxy *p, const dm_run_result *run, const dm_config_result *c,
                         double y, double yhat)
{
    report_proxy_stray s = { .key = c->key, .wall_ns = y, .predicted_ns = yhat,
                             .residual_rel = (y - yhat) / yhat };
    proxy__label(run, c, s.label, sizeof s.label);
    size_t at = p->n_strays;
    while (at > 0 && fabs(p->strays[at - 1].residual_rel) < fabs(s.residual_rel))
        at--;
    if (at >= REPORT_PROXY_STRAYS)
        return;
    size_t last = p->n_strays < REPORT_PROXY_STRAYS ? p->n_strays : REPORT_PROXY_STRAYS - 1;
    memmove(&p->strays[at + 1], &p->strays[at], (last - at) * sizeof s);
    p->strays[at] = s;
    if (p->n_strays < REPORT_PROXY_STRAYS)
        p->n_strays++;
}

int report_proxy_fit(const dm_run_result *run, report_proxy *out)
{
    memset(out, 0, sizeof *out);
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, x, y;
    for (size_t i = 0; i < run->n_configs; i++)
        if (proxy__pair(&run->configs[i], &x, &y)) {
            out->n++;
            sx += x, sy += y, sxx += x * x, sxy += x * y, syy += y * y;
        }
    double n = (double)out->n, vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
    if (out->n < 3 || !(vx > 0))
        return DM_ERR_UNAVAILABLE;
    double b = (sxy - sx * sy / n) / vx, a = (sy - b * sx) / n, sse = 0;
    for (size_t i = 0; i < run->n_configs; i++)
        if (proxy__pair(&run->configs[i], &x, &y)) {
            sse += (y - a - b * x) * (y - a - b * x);
            proxy__stray(out, run, &run->configs[i], y, a + b * x);
        }
    out->a_ns = a;
    out->ns_per_instruction = b;
    out->r2 = vy > 0 ? 1 - sse / vy : NAN;
    return 0;
}

const char *report_proxy_pass(const dm_counter_result *c)
{
    const counters_info *ci = counters_find(c->name);
    if (ci && ci->backend == COUNTERS_BACKEND_CALLGRIND)
        return "instructions";
    if (ci && ci->backend == COUNTERS_BACKEND_DERIVED)
        return "derived";
    return c->has_samples && !c->deterministic ? "timing" : "statistics";
}

/* 1 when name is one of the ", "-separated entries of list. */
static int proxy__listed(const dm_str *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list->buf; p && (p = strstr(p, name)); p += n)
        if ((p == list->buf || p[-1] == ' ') && (p[n] == ',' || p[n] == '\0'))
            return 1;
    return 0;
}

void report_proxy_passes_text(const dm_run_result *run, const char *sep, dm_str *out)
{
    static const char *const passes[][2] = {
        { "timing", "timing child (timed samples, glFinish-fenced)" },
        { "statistics", "timing child, one-frame statistics pass and caller-fed values" },
        { "instructions", "Instructions pass: own child under Valgrind callgrind, LP_NUM_THREADS=0, not timed" },
        { "derived", "derived (formulas over the above)" },
    };
    for (size_t p = 0; p < sizeof passes / sizeof *passes; p++) {
        dm_str names = {0};
        for (size_t i = 0; i < run->n_configs; i++)
            for (size_t k = 0; k < run->configs[i].n_counters; k++) {
                const dm_counter_result *c = &run->configs[i].counters[k];
                if (strcmp(report_proxy_pass(c), passes[p][0]) != 0 || proxy__listed(&names, c->name))
                    continue;
                dm_str_printf(&names, "%s%s", names.len ? ", " : "", c->name);
            }
        if (names.len)
            dm_str_printf(out, "%s: %s%s", passes[p][1], dm_str_get(&names), sep);
        dm_str_free(&names);
    }
}
