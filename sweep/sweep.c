/* sweep.c — YAML sweep files to a validated `sweep` (see sweep.h).
 *
 * libyaml loads the whole document; we walk its node tree, so every node
 * carries its own line and column for messages.  Axis names and values are
 * checked against the catalog in techniques/axes.h, counter names against
 * the registry in counters/counters.h.
 */
#include "sweep.h"
#include "published.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "techniques/axes.h"
#include "reports/metric.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "techniques/technique.h"

typedef struct pctx {
    yaml_document_t *doc;
    const char *path;
    dm_str *err;
    sweep *s;
} pctx;

#define P__FOREACH_PAIR(c, map, pair)                                           \
    for (yaml_node_pair_t *pair = (map)->data.mapping.pairs.start;               \
         pair < (map)->data.mapping.pairs.top; pair++)

static int p__fail(pctx *c, const yaml_node_t *n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes "path:line:col: message" into the error buffer; returns DM_ERR_PARSE. */
static int p__fail(pctx *c, const yaml_node_t *n, const char *fmt, ...)
{
    dm_str_printf(c->err, "%s:%zu:%zu: ", c->path, n ? n->start_mark.line + 1 : 1,
                  n ? n->start_mark.column + 1 : 1);
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(c->err, fmt, ap);
    va_end(ap);
    return DM_ERR_PARSE;
}

static const char *p__scalar(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

static yaml_node_t *p__node(pctx *c, int id) { return yaml_document_get_node(c->doc, id); }

/* Rejects an unknown key, listing the valid ones and the closest match. */
static int p__unknown_key(pctx *c, yaml_node_t *k, const char *where,
                          const char *const *valid, size_t n)
{
    const char *key = p__scalar(k) ? p__scalar(k) : "?";
    const char *close = dm_closest(key, valid, n);
    p__fail(c, k, "unknown key '%s' in %s", key, where);
    if (close)
        dm_str_printf(c->err, "; did you mean '%s'?", close);
    dm_str_cat(c->err, " valid keys: ");
    dm_str_cat_list(c->err, valid, n);
    return DM_ERR_PARSE;
}

static int p__int(pctx *c, yaml_node_t *n, const char *what, long lo, long hi, int *out)
{
    const char *v = p__scalar(n);
    char *end = NULL;
    long x = v ? strtol(v, &end, 10) : 0;
    if (!v || end == v || *end || x < lo || x > hi)
        return p__fail(c, n, "%s: expected an integer in [%ld, %ld], got '%s'", what, lo, hi,
                       v ? v : "(not a scalar)");
    *out = (int)x;
    return 0;
}

static int p__real(pctx *c, yaml_node_t *n, const char *what, double lo, double hi, double *out)
{
    const char *v = p__scalar(n);
    char *end = NULL;
    double x = v ? strtod(v, &end) : 0;
    if (!v || end == v || *end || !isfinite(x) || x < lo || x > hi)
        return p__fail(c, n, "%s: expected a number in [%g, %g], got '%s'", what, lo, hi,
                       v ? v : "(not a scalar)");
    *out = x;
    return 0;
}

/* Text of an axis value node: a scalar, or a [W, H] pair for resolution. */
static char *p__value_text(pctx *c, yaml_node_t *n)
{
    if (n->type == YAML_SCALAR_NODE)
        return dm_xstrdup(p__scalar(n));
    if (n->type != YAML_SEQUENCE_NODE)
        return NULL;
    yaml_node_item_t *it = n->data.sequence.items.start;
    size_t len = (size_t)(n->data.sequence.items.top - it);
    if (len != 2 || !p__scalar(p__node(c, it[0])) || !p__scalar(p__node(c, it[1])))
        return NULL;
    return dm_xasprintf("%sx%s", p__scalar(p__node(c, it[0])), p__scalar(p__node(c, it[1])));
}

/* Validates axis=value and returns its canonical text (caller frees), or NULL
 * after writing the error. */
static char *p__axis_value(pctx *c, const char *axis, yaml_node_t *n)
{
    char *text = p__value_text(c, n);
    if (!text) {
        p__fail(c, n, "%s: expected a single value%s", axis,
                strcmp(axis, "resolution") == 0 ? " or a [width, height] pair" : "");
        return NULL;
    }
    dm_str msg = {0};
    int rc = axes_check(axis, text, &msg);
    if (rc != 0) {
        p__fail(c, n, "%s", dm_str_get(&msg));
        dm_str_free(&msg);
        free(text);
        return NULL;
    }
    dm_str_free(&msg);
    char *canon = axes_canonical(axis, text);
    free(text);
    return canon;
}

/* Sets scene default axis=v (canonical text, owned by the callee). */
static int p__put_scene(pctx *c, const char *axis, char *v)
{
    for (size_t i = 0; i < c->s->n_scene; i++) {
        if (strcmp(c->s->scene[i].key, axis) == 0) {
            free(c->s->scene[i].value);
            c->s->scene[i].value = v;
            return 0;
        }
    }
    dm_kv_push(&c->s->scene, &c->s->n_scene, axis, v);
    free(v);
    return 0;
}

static int p__set_scene(pctx *c, const char *axis, yaml_node_t *key, yaml_node_t *val)
{
    if (!axes_find(axis)) {
        dm_str msg = {0};
        axes_check(axis, "", &msg);
        p__fail(c, key, "%s", dm_str_get(&msg));
        dm_str_free(&msg);
        return DM_ERR_PARSE;
    }
    char *v = p__axis_value(c, axis, val);
    return v ? p__put_scene(c, axis, v) : DM_ERR_PARSE;
}

/* A user map path, made relative to the sweep file's directory. */
static char *p__map_path(pctx *c, const char *path)
{
    const char *slash = strrchr(c->path, '/');
    if (path[0] == '/' || !slash)
        return dm_xstrdup(path);
    return dm_xasprintf("%.*s/%s", (int)(slash - c->path), c->path, path);
}

/* material: { height: P, normal: P, albedo: P } -> the maps axis value
 * "height=P;normal=P;albedo=P", validated (file exists, decodes, square
 * power of two, same sizes, finite) by the axis check at plan time. */
static int p__user_maps(pctx *c, yaml_node_t *map)
{
    static const char *const kinds[] = { "height", "normal", "albedo" };
    dm_str v = {0};
    yaml_node_t *first = NULL;
    for (int k = 0; k < 3; k++) {
        P__FOREACH_PAIR(c, map, pr) {
            yaml_node_t *key = p__node(c, pr->key), *val = p__node(c, pr->value);
            if (!p__scalar(key) || strcmp(p__scalar(key), kinds[k]) != 0)
                continue;
            if (!p__scalar(val) || !*p__scalar(val)) {
                dm_str_free(&v);
                return p__fail(c, val, "scene.material.%s: expected a file path", kinds[k]);
            }
            char *path = p__map_path(c, p__scalar(val));
            dm_str_printf(&v, "%s%s=", v.len ? ";" : "", kinds[k]);
            for (const char *p = path; *p; p++)   /* a ';' in the path is written ";;" */
                dm_str_cat(&v, *p == ';' ? ";;" : (char[2]){ *p, 0 });
            free(path);
            first = first ? first : val;
        }
    }
    if (!first)
        return 0;
    dm_str msg = {0};
    int rc = axes_check("maps", dm_str_get(&v), &msg);
    if (rc)
        p__fail(c, first, "%s", dm_str_get(&msg));
    else
        rc = p__put_scene(c, "maps", dm_str_take(&v));
    dm_str_free(&msg);
    dm_str_free(&v);
    return rc;
}


/* Mappings must be mappings, and YAML keys are unique: a repeated key would
 * silently win over the first, so it is an error naming both lines. */
static int p__expect_map(pctx *c, yaml_node_t *n, const char *what)
{
    if (!n || n->type != YAML_MAPPING_NODE)
        return p__fail(c, n, "%s: expected a mapping (key: value lines)", what);
    P__FOREACH_PAIR(c, n, a) {
        const char *ka = p__scalar(p__node(c, a->key));
        for (yaml_node_pair_t *b = n->data.mapping.pairs.start; ka && b < a; b++) {
            const char *kb = p__scalar(p__node(c, b->key));
            if (kb && strcmp(ka, kb) == 0)
                return p__fail(c, p__node(c, a->key), "%s: key '%s' is given twice (first on line %zu)",
                               what, ka, p__node(c, b->key)->start_mark.line + 1);
        }
    }
    return 0;
}

/* scene: { camera: {...}, lights: {...}, material: {...}, <axis>: value } */
static int p__scene_group(pctx *c, yaml_node_t *map, const char *group,
                          const char *const *keys, const char *const *axes, size_t n)
{
    int rc = p__expect_map(c, map, group);
    if (rc)
        return rc;
    P__FOREACH_PAIR(c, map, pr) {
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k);
        size_t i = 0;
        while (i < n && (!name || strcmp(name, keys[i]) != 0))
            i++;
        if (i == n)
            return p__unknown_key(c, k, group, keys, n);
        if (axes[i] && (rc = p__set_scene(c, axes[i], k, v)))
            return rc;
    }
    return 0;
}

static int p__scene(pctx *c, yaml_node_t *map)
{
    static const char *const cam_keys[] = { "distance", "azimuth", "elevation", "fov" };
    static const char *const cam_axes[] = { "camera.distance", "camera.azimuth",
                                            "camera.elevation", "camera.fov" };
    static const char *const light_keys[] = { "model", "count" };
    static const char *const light_axes[] = { "lighting", "light_count" };
    static const char *const mat_keys[] = { "maps", "height_scale", "height", "normal", "albedo" };
    static const char *const mat_axes[] = { "maps", "height_scale", NULL, NULL, NULL };
    int rc = p__expect_map(c, map, "scene");
    if (rc)
        return rc;
    P__FOREACH_PAIR(c, map, pr) {
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "camera") == 0)
            rc = p__scene_group(c, v, "scene.camera", cam_keys, cam_axes, 4);
        else if (strcmp(name, "lights") == 0)
            rc = p__scene_group(c, v, "scene.lights", light_keys, light_axes, 2);
        else if (strcmp(name, "material") == 0)
            rc = p__scene_group(c, v, "scene.material", mat_keys, mat_axes, 5) ||
                 p__user_maps(c, v) ? DM_ERR_PARSE : 0;
        else
            rc = p__set_scene(c, name, k, v);
        if (rc)
            return rc;
    }
    return 0;
}

/* sweep: { axis: [v1, v2, ...] | v } */
/* A mapping axis -> value | [values] into (*axes, *n): the `sweep` block
 * and each `exclude` entry (`what` names it in messages). */
static int p__axis_block(pctx *c, yaml_node_t *map, const char *what, sweep_axis **axes, size_t *n_axes)
{
    int rc = p__expect_map(c, map, what);
    if (rc)
        return rc;
    P__FOREACH_PAIR(c, map, pr) {
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (!axes_find(name))
            return p__set_scene(c, name, k, v);   /* reports the unknown axis */
        for (size_t i = 0; i < *n_axes; i++)
            if (strcmp((*axes)[i].name, name) == 0)
                return p__fail(c, k, "axis '%s' is given twice (first on line %d)", name,
                               (*axes)[i].line);
        sweep_axis ax = { .name = dm_xstrdup(name), .line = (int)k->start_mark.line + 1 };
        /* resolution: [1280, 720] is one value; [[640, 360], "1280x720"] is a list. */
        int is_pair = 0;
        if (v->type == YAML_SEQUENCE_NODE && strcmp(name, "resolution") == 0 &&
            v->data.sequence.items.top - v->data.sequence.items.start == 2) {
            const char *first = p__scalar(p__node(c, v->data.sequence.items.start[0]));
            is_pair = first && !strchr(first, 'x');
        }
        if (v->type == YAML_SEQUENCE_NODE && !is_pair) {
            for (yaml_node_item_t *it = v->data.sequence.items.start; it < v->data.sequence.items.top; it++) {
                char *val = p__axis_value(c, name, p__node(c, *it));
                if (!val) {
                    rc = DM_ERR_PARSE;
                    break;
                }
                ax.values = dm_xrealloc(ax.values, (ax.n_values + 1) * sizeof *ax.values);
                ax.values[ax.n_values++] = val;
            }
        } else {
            char *val = p__axis_value(c, name, v);
            if (val) {
                ax.values = dm_xmalloc(sizeof *ax.values);
                ax.values[ax.n_values++] = val;
            } else {
                rc = DM_ERR_PARSE;
            }
        }
        if (rc == 0 && ax.n_values == 0)
            rc = p__fail(c, v, "axis '%s' has no values (an empty list would plan nothing)", name);
        *axes = dm_xrealloc(*axes, (*n_axes + 1) * sizeof **axes);
        (*axes)[(*n_axes)++] = ax;
        if (rc)
            return rc;
    }
    return 0;
}

static int p__axes(pctx *c, yaml_node_t *map)
{
    return p__axis_block(c, map, "sweep", &c->s->axes, &c->s->n_axes);
}

/* exclude: a list of {axis: value | [values], ...} entries. */
static int p__excludes(pctx *c, yaml_node_t *seq)
{
    if (seq->type != YAML_SEQUENCE_NODE)
        return p__fail(c, seq, "exclude: expected a list of {axis: value or [values], ...} entries");
    for (yaml_node_item_t *it = seq->data.sequence.items.start; it < seq->data.sequence.items.top; it++) {
        yaml_node_t *e = p__node(c, *it);
        sweep_exclude ex = {.line = (int)e->start_mark.line + 1};
        int rc = p__axis_block(c, e, "exclude[]", &ex.axes, &ex.n_axes);
        if (rc == 0 && ex.n_axes == 0)
            rc = p__fail(c, e, "exclude[]: an empty entry would exclude everything");
        c->s->excludes = dm_xrealloc(c->s->excludes, (c->s->n_excludes + 1) * sizeof *c->s->excludes);
        c->s->excludes[c->s->n_excludes++] = ex;
        if (rc)
            return rc;
    }
    return 0;
}

/* Every excluded axis must be a sweep axis and every value one of its
 * values (a typo would otherwise exclude nothing, silently). */
static int sweep__check_excludes(const sweep *s, dm_str *err)
{
    for (size_t i = 0; i < s->n_excludes; i++)
        for (size_t j = 0; j < s->excludes[i].n_axes; j++) {
            const sweep_axis *ea = &s->excludes[i].axes[j];
            const sweep_axis *sa = NULL;
            for (size_t k = 0; k < s->n_axes; k++)
                if (strcmp(s->axes[k].name, ea->name) == 0)
                    sa = &s->axes[k];
            if (!sa) {
                dm_str_printf(err, "%s:%d: exclude names axis '%s', which the sweep block does not vary; "
                              "excluded axes must be listed under sweep:", s->path, ea->line, ea->name);
                return DM_ERR_PARSE;
            }
            for (size_t v = 0; v < ea->n_values; v++) {
                int found = 0;
                for (size_t k = 0; k < sa->n_values; k++)
                    found |= strcmp(sa->values[k], ea->values[v]) == 0;
                if (found)
                    continue;
                dm_str_printf(err, "%s:%d: exclude value '%s' of %s is not one of the sweep's values (",
                              s->path, ea->line, ea->values[v], ea->name);
                for (size_t k = 0; k < sa->n_values; k++)
                    dm_str_printf(err, "%s%s", k ? ", " : "", sa->values[k]);
                dm_str_cat(err, ")");
                return DM_ERR_PARSE;
            }
        }
    return 0;
}

static void sweep__axes_free(sweep_axis *axes, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(axes[i].name);
        for (size_t j = 0; j < axes[i].n_values; j++)
            free(axes[i].values[j]);
        free(axes[i].values);
    }
    free(axes);
}

static int p__counter_list(pctx *c, yaml_node_t *seq)
{
    if (seq->type != YAML_SEQUENCE_NODE)
        return p__fail(c, seq, "measure.counters: expected a list of counter names");
    sweep_measure *m = &c->s->measure;
    for (yaml_node_item_t *it = seq->data.sequence.items.start; it < seq->data.sequence.items.top; it++) {
        yaml_node_t *n = p__node(c, *it);
        const char *name = p__scalar(n);
        if (!name || !counters_find(name)) {
            size_t nc = counters_count();
            const char **names = dm_xmalloc(nc * sizeof *names);
            for (size_t i = 0; i < nc; i++)
                names[i] = counters_info_at(i)->name;
            const char *close = name ? dm_closest(name, names, nc) : NULL;
            p__fail(c, n, "unknown counter '%s'", name ? name : "?");
            if (close)
                dm_str_printf(c->err, "; did you mean '%s'?", close);
            dm_str_cat(c->err, " valid counters: ");
            dm_str_cat_list(c->err, names, nc);
            free(names);
            return DM_ERR_PARSE;
        }
        m->counters = dm_xrealloc(m->counters, (m->n_counters + 1) * sizeof *m->counters);
        m->counters[m->n_counters++] = dm_xstrdup(name);
    }
    return 0;
}

static int p__samples(pctx *c, yaml_node_t *map)
{
    static const char *const keys[] = { "min", "max", "target_ci" };
    sweep_measure *m = &c->s->measure;
    int rc = p__expect_map(c, map, "measure.samples");
    P__FOREACH_PAIR(c, map, pr) {
        if (rc)
            break;
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "min") == 0)
            rc = p__int(c, v, "measure.samples.min", 2, 10000, &m->samples_min);
        else if (strcmp(name, "max") == 0)
            rc = p__int(c, v, "measure.samples.max", 2, 10000, &m->samples_max);
        else if (strcmp(name, "target_ci") == 0)
            rc = p__real(c, v, "measure.samples.target_ci", 0.0, 1.0, &m->target_ci);
        else
            rc = p__unknown_key(c, k, "measure.samples", keys, 3);
    }
    if (rc == 0 && m->samples_max < m->samples_min)
        rc = p__fail(c, map, "measure.samples: max (%d) is less than min (%d)", m->samples_max,
                     m->samples_min);
    return rc;
}

static int p__measure(pctx *c, yaml_node_t *map)
{
    static const char *const keys[] = { "warmup_frames", "frames_per_sample", "samples",
                                        "counters", "timeout_s", "max_seconds", "min_sample_ms" };
    sweep_measure *m = &c->s->measure;
    int rc = p__expect_map(c, map, "measure");
    P__FOREACH_PAIR(c, map, pr) {
        if (rc)
            break;
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "warmup_frames") == 0)
            rc = p__int(c, v, "measure.warmup_frames", 0, 100000, &m->warmup_frames);
        else if (strcmp(name, "frames_per_sample") == 0)
            rc = p__int(c, v, "measure.frames_per_sample", 1, 100000, &m->frames_per_sample);
        else if (strcmp(name, "samples") == 0)
            rc = p__samples(c, v);
        else if (strcmp(name, "counters") == 0)
            rc = p__counter_list(c, v);
        else if (strcmp(name, "timeout_s") == 0)
            rc = p__real(c, v, "measure.timeout_s", 1, 86400, &m->timeout_s);
        else if (strcmp(name, "max_seconds") == 0)
            rc = p__real(c, v, "measure.max_seconds", 0.01, 86400, &m->max_seconds);
        else if (strcmp(name, "min_sample_ms") == 0)
            rc = p__real(c, v, "measure.min_sample_ms", 0, 10000, &m->min_sample_ms),
            m->min_sample_set = 1;
        else
            rc = p__unknown_key(c, k, "measure", keys, 7);
    }
    return rc;
}

/* "unknown key" for quality.reference: the valid keys are technique,
 * supersample and every axis name. */
static int p__reference_unknown(pctx *c, yaml_node_t *k)
{
    size_t n = axes_count() + 2;
    const char **valid = dm_xmalloc(n * sizeof *valid);
    valid[0] = "technique";
    valid[1] = "supersample";
    for (size_t i = 2; i < n; i++)
        valid[i] = axes_at(i - 2)->name;
    int rc = p__unknown_key(c, k, "quality.reference", valid, n);
    free(valid);
    return rc;
}

/* Every override of quality.reference must be read by the reference
 * technique (checked once the map is read, as `technique` may come last);
 * with technique `same` each configuration's own technique applies. */
static int p__reference_readable(pctx *c, yaml_node_t *v)
{
    const char *name = c->s->ref_technique ? c->s->ref_technique : "reference-mesh";
    const technique_desc *t = strcmp(name, "same") == 0 ? NULL : technique_find(name);
    P__FOREACH_PAIR(c, v, rp) {
        yaml_node_t *rk = p__node(c, rp->key);
        const char *axis = p__scalar(rk) ? p__scalar(rk) : "";
        if (t && axes_find(axis) && strcmp(axis, "technique") != 0 && !technique_reads_axis(t, axis))
            return p__fail(c, rk, "quality.reference: technique '%s' does not read axis '%s', so it "
                           "cannot set the reference's %s", name, axis, axis);
    }
    return 0;
}

static int p__quality_reference(pctx *c, yaml_node_t *v)
{
    int rc = p__expect_map(c, v, "quality.reference");
    if (rc)
        return rc;
    P__FOREACH_PAIR(c, v, rp) {
        yaml_node_t *rk = p__node(c, rp->key), *rv = p__node(c, rp->value);
        const char *name = p__scalar(rk) ? p__scalar(rk) : "";
        if (strcmp(name, "technique") == 0 && p__scalar(rv) && strcmp(p__scalar(rv), "same") == 0) {
            free(c->s->ref_technique);          /* each configuration, supersampled */
            c->s->ref_technique = dm_xstrdup("same");
        } else if (strcmp(name, "technique") == 0) {
            char *t = p__axis_value(c, "technique", rv);
            if (!t)
                return DM_ERR_PARSE;
            free(c->s->ref_technique);
            c->s->ref_technique = t;
        } else if (strcmp(name, "supersample") == 0) {
            rc = p__int(c, rv, "quality.reference.supersample", 1, 8, &c->s->supersample);
        } else if (axes_find(name)) {             /* an axis value of the reference */
            char *val = p__axis_value(c, name, rv);
            if (!val)
                return DM_ERR_PARSE;
            dm_kv_push(&c->s->ref_params, &c->s->n_ref_params, name, val);
            free(val);
        } else {
            return p__reference_unknown(c, rk);
        }
        if (rc)
            return rc;
    }
    return p__reference_readable(c, v);
}

/* quality.pareto_metric: one of reports/metric.h's names (the list is an
 * X-macro, so no link to reports/ is needed). */
static int p__pareto_metric(pctx *c, yaml_node_t *v)
{
    static const char *const names[] = {
#define P__METRIC_NAME(id, name) name,
        REPORT_METRICS(P__METRIC_NAME)
#undef P__METRIC_NAME
    };
    const size_t n = sizeof names / sizeof *names;
    const char *m = p__scalar(v);
    for (size_t i = 0; m && i < n; i++)
        if (strcmp(m, names[i]) == 0) {
            free(c->s->pareto_metric);
            c->s->pareto_metric = dm_xstrdup(m);
            return 0;
        }
    const char *close = m ? dm_closest(m, names, n) : NULL;
    p__fail(c, v, "quality.pareto_metric: unknown metric '%s'", m ? m : "(not a scalar)");
    if (close)
        dm_str_printf(c->err, "; did you mean '%s'?", close);
    dm_str_cat(c->err, " valid metrics: ");
    dm_str_cat_list(c->err, names, n);
    return DM_ERR_PARSE;
}

static int p__quality(pctx *c, yaml_node_t *map)
{
    static const char *const keys[] = { "reference", "pareto_metric" };
    int rc = p__expect_map(c, map, "quality");
    if (rc)
        return rc;
    P__FOREACH_PAIR(c, map, pr) {
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "reference") == 0)
            rc = p__quality_reference(c, v);
        else if (strcmp(name, "pareto_metric") == 0)
            rc = p__pareto_metric(c, v);
        else
            return p__unknown_key(c, k, "quality", keys, 2);
        if (rc)
            return rc;
    }
    return 0;
}

static int p__model(pctx *c, yaml_node_t *map)
{
    static const char *const keys[] = { "name", "formula", "group_by", "response" };
    int rc = p__expect_map(c, map, "models[]");
    if (rc)
        return rc;
    sweep_model md = { .line = (int)map->start_mark.line + 1 };
    P__FOREACH_PAIR(c, map, pr) {
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "group_by") == 0 && v->type == YAML_SEQUENCE_NODE) {
            for (yaml_node_item_t *it = v->data.sequence.items.start; it < v->data.sequence.items.top; it++) {
                const char *g = p__scalar(p__node(c, *it));
                if (!g || !axes_find(g)) {
                    rc = p__fail(c, p__node(c, *it), "models: group_by: '%s' is not an axis",
                                 g ? g : "?");
                    break;
                }
                md.group_by = dm_xrealloc(md.group_by, (md.n_group_by + 1) * sizeof(char *));
                md.group_by[md.n_group_by++] = dm_xstrdup(g);
            }
        } else if (strcmp(name, "name") == 0 && p__scalar(v)) {
            md.name = dm_xstrdup(p__scalar(v));
        } else if (strcmp(name, "formula") == 0 && p__scalar(v)) {
            md.formula = dm_xstrdup(p__scalar(v));
        } else if (strcmp(name, "response") == 0 && p__scalar(v)) {
            if (!counters_find(p__scalar(v)))
                rc = p__fail(c, v, "models: response '%s' is not a counter", p__scalar(v));
            md.response = dm_xstrdup(p__scalar(v));
        } else {
            rc = p__unknown_key(c, k, "models[]", keys, 4);
        }
        if (rc)
            break;
    }
    if (rc == 0 && !md.name)
        rc = p__fail(c, map, "models[]: every model needs a name");
    c->s->models = dm_xrealloc(c->s->models, (c->s->n_models + 1) * sizeof *c->s->models);
    c->s->models[c->s->n_models++] = md;
    return rc;
}

static int p__models(pctx *c, yaml_node_t *seq)
{
    if (seq->type != YAML_SEQUENCE_NODE)
        return p__fail(c, seq, "models: expected a list of {name, formula, group_by, response}");
    for (yaml_node_item_t *it = seq->data.sequence.items.start; it < seq->data.sequence.items.top; it++) {
        int rc = p__model(c, p__node(c, *it));
        if (rc)
            return rc;
    }
    return 0;
}

static int p__top(pctx *c, yaml_node_t *root)
{
    static const char *const keys[] = { "name", "resolution", "measure", "scene", "sweep",
                                        "exclude", "quality", "models", "published" };
    if (!root)
        return p__fail(c, NULL, "empty sweep file (expected keys: name, sweep, ...)");
    int rc = p__expect_map(c, root, "sweep file");
    P__FOREACH_PAIR(c, root, pr) {
        if (rc)
            break;
        yaml_node_t *k = p__node(c, pr->key), *v = p__node(c, pr->value);
        const char *name = p__scalar(k) ? p__scalar(k) : "";
        if (strcmp(name, "name") == 0) {
            if (!p__scalar(v) || !*p__scalar(v))
                rc = p__fail(c, v, "name: expected a non-empty string");
            else
                c->s->name = dm_xstrdup(p__scalar(v));
        } else if (strcmp(name, "resolution") == 0) {
            rc = p__set_scene(c, "resolution", k, v);
        } else if (strcmp(name, "measure") == 0) {
            rc = p__measure(c, v);
        } else if (strcmp(name, "scene") == 0) {
            rc = p__scene(c, v);
        } else if (strcmp(name, "sweep") == 0) {
            rc = p__axes(c, v);
        } else if (strcmp(name, "quality") == 0) {
            rc = p__quality(c, v);
        } else if (strcmp(name, "models") == 0) {
            rc = p__models(c, v);
        } else if (strcmp(name, "exclude") == 0) {
            rc = p__excludes(c, v);
        } else if (strcmp(name, "published") == 0) {
            rc = published_parse(c->doc, v, c->path, &c->s->published, c->err);
        } else {
            rc = p__unknown_key(c, k, "the sweep file", keys, 9);
        }
    }
    return rc;
}

static void sweep__defaults(sweep *s)
{
    static const char *const counters[] = {
        "WallTime", "CPUTime", "SubmitTime", "GPUTime", "VerticesSubmitted",
        "PrimitivesSubmitted", "VSInvocations", "TCSPatches", "TESInvocations",
        "ClippingInputPrimitives", "ClippingOutputPrimitives", "FSInvocations",
        "SamplesPassed", "TextureBytes", "MeshBytes", "MeshTriangles" };
    sweep_measure *m = &s->measure;
    if (!s->name)
        s->name = dm_xstrdup("unnamed");
    if (!m->warmup_frames)
        m->warmup_frames = 8;
    if (!m->frames_per_sample)
        m->frames_per_sample = 16;
    if (!m->samples_min)
        m->samples_min = 5;
    if (!m->samples_max)
        m->samples_max = m->samples_min > 30 ? m->samples_min : 30;
    if (m->target_ci <= 0)
        m->target_ci = 0.03;
    if (m->timeout_s <= 0)
        m->timeout_s = 120;
    if (m->max_seconds <= 0)
        m->max_seconds = 10;
    if (!m->min_sample_set)
        m->min_sample_ms = 20;
    if (!m->n_counters) {
        size_t n = sizeof counters / sizeof counters[0];
        m->counters = dm_xmalloc(n * sizeof *m->counters);
        for (size_t i = 0; i < n; i++)
            m->counters[i] = dm_xstrdup(counters[i]);
        m->n_counters = n;
    }
    if (!s->supersample)
        s->supersample = 4;
    if (!s->ref_technique)          /* ground truth: the CPU-displaced fine mesh (docs/sweep-files.md, Quality) */
        s->ref_technique = dm_xstrdup("reference-mesh");
    if (!s->pareto_metric)
        s->pareto_metric = dm_xstrdup("ssim");
}

/* Deepest nesting of YAML collections a sweep file may have (the deepest
 * real one is 4: models, a model, group_by, ...). */
#define SWEEP__MAX_DEPTH 16

/* Refuses a document nested deeper than SWEEP__MAX_DEPTH, without
 * recursion: libyaml numbers a collection before its children, so one pass
 * in node order gives every node its depth. */
static int sweep__depth_check(yaml_document_t *doc, const char *path, dm_str *err)
{
    size_t n = (size_t)(doc->nodes.top - doc->nodes.start);
    int *depth = dm_xcalloc(n + 2, sizeof *depth), rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++) {
        yaml_node_t *nd = &doc->nodes.start[i];
        int kids[2];
        for (size_t j = 0; ; j++) {
            size_t nk = 0;
            if (nd->type == YAML_SEQUENCE_NODE &&
                nd->data.sequence.items.start + j < nd->data.sequence.items.top)
                kids[nk++] = nd->data.sequence.items.start[j];
            if (nd->type == YAML_MAPPING_NODE &&
                nd->data.mapping.pairs.start + j < nd->data.mapping.pairs.top) {
                kids[nk++] = nd->data.mapping.pairs.start[j].key;
                kids[nk++] = nd->data.mapping.pairs.start[j].value;
            }
            if (nk == 0)
                break;
            for (size_t k = 0; k < nk; k++)
                if (kids[k] >= 1 && (size_t)kids[k] <= n && depth[kids[k] - 1] < depth[i] + 1)
                    depth[kids[k] - 1] = depth[i] + 1;
        }
        if (depth[i] > SWEEP__MAX_DEPTH) {
            dm_str_printf(err, "%s:%zu:%zu: nested deeper than %d levels; a sweep file is "
                          "never that deep", path, nd->start_mark.line + 1,
                          nd->start_mark.column + 1, SWEEP__MAX_DEPTH);
            rc = DM_ERR_PARSE;
        }
    }
    free(depth);
    return rc;
}

int sweep_parse(const char *text, const char *path, sweep *out, dm_str *err)
{
    memset(out, 0, sizeof *out);
    yaml_parser_t parser;
    yaml_document_t doc;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, strlen(text));
    if (!yaml_parser_load(&parser, &doc)) {
        dm_str_printf(err, "%s:%zu:%zu: YAML syntax error: %s", path,
                      parser.problem_mark.line + 1, parser.problem_mark.column + 1,
                      parser.problem ? parser.problem : "unknown");
        if (parser.context)
            dm_str_printf(err, " (%s that started at line %zu, column %zu)", parser.context,
                          parser.context_mark.line + 1, parser.context_mark.column + 1);
        yaml_parser_delete(&parser);
        return DM_ERR_PARSE;
    }
    pctx c = { .doc = &doc, .path = path, .err = err, .s = out };
    out->path = dm_xstrdup(path);
    int rc = sweep__depth_check(&doc, path, err);
    rc = rc ? rc : p__top(&c, yaml_document_get_root_node(&doc));
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    if (rc == 0)
        rc = sweep__check_excludes(out, err);
    if (rc) {
        sweep_free(out);
        return rc;
    }
    sweep__defaults(out);
    out->hash = dm_fnv1a64(text, strlen(text), DM_FNV_SEED);
    return 0;
}

int sweep_load(const char *path, sweep *out, dm_str *err)
{
    char *text = NULL;
    size_t len = 0;
    memset(out, 0, sizeof *out);
    if (dm_file_exists(path) && !dm_regular_file(path)) {
        dm_str_printf(err, "%s: cannot read the sweep file: not a regular file (a directory, "
                      "FIFO or device)", path);
        return DM_ERR_IO;
    }
    if (dm_read_file(path, &text, &len) != 0) {
        dm_str_printf(err, "%s: cannot read the sweep file", path);
        return DM_ERR_IO;
    }
    const char *nul = memchr(text, '\0', len);
    if (nul) {   /* the YAML parser would stop there and silently drop the rest */
        size_t line = 1;
        for (const char *p = text; p < nul; p++)
            line += *p == '\n';
        dm_str_printf(err, "%s:%zu: a NUL byte: a sweep file is UTF-8 text (is this a binary "
                      "file?)", path, line);
        free(text);
        return DM_ERR_PARSE;
    }
    int rc = sweep_parse(text, path, out, err);
    free(text);
    return rc;
}

/* The embedded default sweep: every technique that exists (registry order)
 * on a small grid of axes, the built-in procedural scene and maps; no files,
 * no network, no display.  %s is replaced by the technique list. */
static const char sweep__default_yaml[] =
    "name: default\n"
    "resolution: [480, 270]\n"
    "measure:\n"
    "  warmup_frames: 4\n"
    "  frames_per_sample: 8\n"
    "  samples: { min: 5, max: 30, target_ci: 0.03 }\n"
    "  max_seconds: 6\n"
    "scene:\n"
    "  camera: { distance: 3.0, azimuth: 30, elevation: 35, fov: 45 }\n"
    "  material: { maps: bricks, height_scale: 0.06 }\n"
    "sweep:\n"
    "  mesh: [plane, cube]\n"
    "  technique: [%s]\n"
    "  tess_level: [1, 16]\n"
    "  steps: [8, 32]\n"
    "  resolution: [[240, 135], [480, 270]]\n"
    "models:\n"
    "  - { name: pixel-cost, formula: \"a + b*SamplesPassed\", response: WallTime, group_by: [technique] }\n"
    "  - { name: pipeline-linear }\n";

static const char sweep__quick_yaml[] =
    "name: quick\n"
    "resolution: [160, 90]\n"
    "measure:\n"
    "  warmup_frames: 2\n"
    "  frames_per_sample: 4\n"
    "  samples: { min: 5, max: 8, target_ci: 0.05 }\n"
    "  max_seconds: 1\n"
    "sweep:\n"
    "  mesh: [plane]\n"
    "  technique: [%s]\n"
    "  resolution: [[80, 45], [160, 90]]\n";

const char *sweep_default_text(int quick)
{
    static char *text[2];
    if (!text[quick]) {
        dm_str list = {0};
        for (const char *const *t = technique_names(); *t; t++)   /* the reference is not measured */
            if (strcmp(*t, "reference-mesh") != 0)
                dm_str_printf(&list, "%s%s", list.len ? ", " : "", *t);
        text[quick] = dm_xasprintf(quick ? sweep__quick_yaml : sweep__default_yaml, dm_str_get(&list));
        dm_str_free(&list);
    }
    return text[quick];
}

void sweep_free(sweep *s)
{
    free(s->path);
    free(s->name);
    dm_kv_free(s->scene, s->n_scene);
    sweep__axes_free(s->axes, s->n_axes);
    for (size_t i = 0; i < s->n_excludes; i++)
        sweep__axes_free(s->excludes[i].axes, s->excludes[i].n_axes);
    free(s->excludes);
    for (size_t i = 0; i < s->measure.n_counters; i++)
        free(s->measure.counters[i]);
    free(s->measure.counters);
    free(s->ref_technique);
    dm_kv_free(s->ref_params, s->n_ref_params);
    free(s->pareto_metric);
    for (size_t i = 0; i < s->n_models; i++) {
        sweep_model *m = &s->models[i];
        free(m->name);
        free(m->formula);
        free(m->response);
        for (size_t j = 0; j < m->n_group_by; j++)
            free(m->group_by[j]);
        free(m->group_by);
    }
    free(s->models);
    published_free(s->published);
    memset(s, 0, sizeof *s);
}
