/* report.c — report_write_all and the helpers shared by the writers. */
#include "reports/report.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int report__safe_relpath(const char *p)
{
    return p && *p && p[0] != '/' && !strstr(p, "..");
}

void report__fmt_num(double v, char buf[32])
{
    snprintf(buf, 32, "%1.15g", v);
    if (strtod(buf, NULL) != v)
        snprintf(buf, 32, "%1.17g", v);
}

int report__is_canonical_num(const char *s)
{
    char *end, buf[32];
    if (!s || !*s)
        return 0;
    double v = strtod(s, &end);
    if (*end || !isfinite(v))
        return 0;
    report__fmt_num(v, buf);
    return strcmp(buf, s) == 0;
}

const dm_counter_result *report__frame_time(const dm_config_result *c)
{
    const dm_counter_result *t = dm_config_counter(c, "WallTime");
    return t && t->available && t->has_samples ? t : NULL;
}

/* Appends name to the set (array of borrowed pointers) unless present. */
static void add_unique(const char ***set, size_t *n, const char *name)
{
    for (size_t i = 0; i < *n; i++)
        if (strcmp((*set)[i], name) == 0)
            return;
    *set = dm_xrealloc(*set, (*n + 1) * sizeof **set);
    (*set)[(*n)++] = name;
}

size_t report__scenes(const dm_run_result *run, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++)
        add_unique(out, &n, run->configs[i].scene ? run->configs[i].scene : "");
    return n;
}

static int in_scene(const dm_config_result *c, const char *scene)
{
    return !scene || strcmp(c->scene ? c->scene : "", scene) == 0;
}

size_t report__param_names(const dm_run_result *run, const char *scene, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++)
        if (in_scene(&run->configs[i], scene))
            for (size_t k = 0; k < run->configs[i].n_params; k++)
                add_unique(out, &n, run->configs[i].params[k].key);
    return n;
}

static int counter_kind_matches(const dm_counter_result *c, enum report__counter_kind kind)
{
    if (kind == REPORT__TIMED)
        return !c->deterministic && c->available && c->has_samples;
    return c->deterministic;
}

size_t report__counter_names(const dm_run_result *run, const char *scene,
                             enum report__counter_kind kind, const char ***out)
{
    size_t n = 0;
    *out = NULL;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!in_scene(c, scene))
            continue;
        for (size_t k = 0; k < c->n_counters; k++)
            if (counter_kind_matches(&c->counters[k], kind))
                add_unique(out, &n, c->counters[k].name);
    }
    return n;
}

const char *report__technique(const dm_config_result *c)
{
    const char *t = dm_kv_get(c->params, c->n_params, "technique");
    return t ? t : "?";
}

int report__save(const dm_str *s, const char *path)
{
    return dm_write_file(path, s->buf ? s->buf : "", s->len);
}

/* Writes the four files; stops at the first failure and names that file. */
int report_write_all(const dm_run_result *run, const char *dir, char *err, size_t errlen)
{
    static const char *names[] = {"results.json", "results.csv", "summary.md", "report.html"};
    if (!run || !dir) {
        snprintf(err, errlen, "report_write_all: no run or no directory");
        return DM_ERR_ARG;
    }
    for (int i = 0; i < 4; i++) {
        char *path = dm_xasprintf("%s/%s", dir, names[i]);
        int rc = i == 0 ? report_write_json(run, path)
               : i == 1 ? report_write_csv(run, path)
               : i == 2 ? report_write_markdown(run, path)
                        : report_write_html(run, dir, path);
        if (rc) {
            snprintf(err, errlen, "%s: cannot write (%s)", path, dm_strerror(rc));
            free(path);
            return rc;
        }
        free(path);
    }
    return 0;
}
