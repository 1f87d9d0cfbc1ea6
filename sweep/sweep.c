/* sweep.c — YAML sweep files to a validated `sweep` (see sweep.h).
 *
 * libyaml loads the whole document; we walk its node tree, so every node
 * carries its own line and column for messages.  Axis names and values are
 * checked against the catalog in techniques/axes.h, counter names against
 * the registry in counters/counters.h.
 */
#include "sweep/sweep.h"
#include "sweep/fraction.h"
#include "sweep/published.h"
#include "sweep/sweep_paths.h"
#include "sweep/sweep_yaml.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "reports/metric.h"
#include "techniques/axes.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

typedef struct pctx {
    yaml_document_t *doc;
    const char *path;
    dm_str *err;
    sweep *s;
    sweep_axis **axes;          /* the axis block being read: sweep or an exclude entry */
    size_t *n_axes;
    sweep_model *model;         /* the models[] entry being read */
    unsigned char seen[64];     /* rows of the key table the file gave */
    int env;                    /* DM_ERR_NOMEM met checking a value (a map too large for
                                 * the memory): the machine's, returned instead of PARSE */
} pctx;

#define P__FOREACH_PAIR(c, map, pair)                                           \
    for (yaml_node_pair_t *pair = (map)->data.mapping.pairs.start;               \
         pair < (map)->data.mapping.pairs.top; pair++)

static int sweep__fail(pctx *c, const yaml_node_t *n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes "path:line:col: message" into the error buffer; returns DM_ERR_PARSE. */
static int sweep__fail(pctx *c, const yaml_node_t *n, const char *fmt, ...)
{
    dm_str_printf(c->err, "%s:%zu:%zu: ", c->path, n ? n->start_mark.line + 1 : 1,
                  n ? n->start_mark.column + 1 : 1);
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(c->err, fmt, ap);
    va_end(ap);
    return DM_ERR_PARSE;
}

static const char *sweep__scalar(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

static yaml_node_t *sweep__node(pctx *c, int id) { return yaml_document_get_node(c->doc, id); }

static int sweep__int(pctx *c, yaml_node_t *n, const char *what, long lo, long hi, int *out)
{
    const char *v = sweep__scalar(n);
    char *end = NULL;
    long x = v ? strtol(v, &end, 10) : 0;
    if (!v || end == v || *end || x < lo || x > hi)
        return sweep__fail(c, n, "%s: expected an integer in [%ld, %ld], got '%s'", what, lo, hi,
                       v ? v : "(not a scalar)");
    *out = (int)x;
    return 0;
}

static int sweep__real(pctx *c, yaml_node_t *n, const char *what, double lo, double hi, double *out)
{
    const char *v = sweep__scalar(n);
    char *end = NULL;
    double x = v ? strtod(v, &end) : 0;
    if (!v || end == v || *end || !isfinite(x) || x < lo || x > hi)
        return sweep__fail(c, n, "%s: expected a number in [%g, %g], got '%s'", what, lo, hi,
                       v ? v : "(not a scalar)");
    *out = x;
    return 0;
}

/* Text of an axis value node: a scalar, or a [W, H] pair for resolution. */
static char *sweep__value_text(pctx *c, yaml_node_t *n)
{
    if (n->type == YAML_SCALAR_NODE)
        return dm_xstrdup(sweep__scalar(n));
    if (n->type != YAML_SEQUENCE_NODE)
        return NULL;
    yaml_node_item_t *it = n->data.sequence.items.start;
    size_t len = (size_t)(n->data.sequence.items.top - it);
    if (len != 2 || !sweep__scalar(sweep__node(c, it[0])) || !sweep__scalar(sweep__node(c, it[1])))
        return NULL;
    return dm_xasprintf("%sx%s", sweep__scalar(sweep__node(c, it[0])), sweep__scalar(sweep__node(c, it[1])));
}

/* Validates axis=value and returns its canonical text (caller frees), or NULL
 * after writing the error. */
static char *sweep__axis_value(pctx *c, const char *axis, yaml_node_t *n)
{
    char *text = sweep_paths_resolve(c->path, axis, sweep__value_text(c, n));
    if (!text) {
        sweep__fail(c, n, "%s: expected a single value%s", axis,
                strcmp(axis, "resolution") == 0 ? " or a [width, height] pair" : "");
        return NULL;
    }
    dm_str msg = {0};
    int rc = axes_check(axis, text, &msg);
    if (rc != 0) {
        c->env = rc == DM_ERR_NOMEM ? rc : c->env;
        sweep__fail(c, n, "%s", dm_str_get(&msg));
        dm_str_free(&msg);
        free(text);
        return NULL;
    }
    dm_str_free(&msg);
    char *canon = axes_canonical(axis, text);
    free(text);
    return canon;
}

/* Sets scene default axis=v (canonical text, owned by the callee), given at
 * node at (its line is kept for later messages, sweep.scene_lines). */
static int sweep__put_scene(pctx *c, const char *axis, char *v, const yaml_node_t *at)
{
    int line = at ? (int)at->start_mark.line + 1 : 0;
    for (size_t i = 0; i < c->s->n_scene; i++) {
        if (strcmp(c->s->scene[i].key, axis) == 0) {
            free(c->s->scene[i].value);
            c->s->scene[i].value = v;
            c->s->scene_lines[i] = line;
            return 0;
        }
    }
    dm_kv_push(&c->s->scene, &c->s->n_scene, axis, v);
    c->s->scene_lines = dm_xrealloc(c->s->scene_lines, c->s->n_scene * sizeof *c->s->scene_lines);
    c->s->scene_lines[c->s->n_scene - 1] = line;
    free(v);
    return 0;
}

static int sweep__set_scene(pctx *c, const char *axis, yaml_node_t *key, yaml_node_t *val)
{
    if (!axes_find(axis)) {
        dm_str msg = {0};
        axes_check(axis, "", &msg);
        sweep__fail(c, key, "%s", dm_str_get(&msg));
        dm_str_free(&msg);
        return DM_ERR_PARSE;
    }
    char *v = sweep__axis_value(c, axis, val);
    return v ? sweep__put_scene(c, axis, v, val) : DM_ERR_PARSE;
}

/* material: { height: P, normal: P, albedo: P } -> the maps axis value
 * (sweep_paths_maps), validated (file exists, decodes, square power of two,
 * same sizes, finite) by the axis check at plan time. */
static int sweep__user_maps(pctx *c, yaml_node_t *map)
{
    const char *paths[SWEEP_PATHS_MAPS] = {0};
    yaml_node_t *first = NULL;
    for (int k = 0; k < SWEEP_PATHS_MAPS; k++) {
        P__FOREACH_PAIR(c, map, pr) {
            yaml_node_t *key = sweep__node(c, pr->key), *val = sweep__node(c, pr->value);
            if (!sweep__scalar(key) || strcmp(sweep__scalar(key), sweep_paths_map_kinds[k]) != 0)
                continue;
            if (!sweep__scalar(val) || !*sweep__scalar(val))
                return sweep__fail(c, val, "scene.material.%s: expected a file path", sweep_paths_map_kinds[k]);
            paths[k] = sweep__scalar(val);
            first = first ? first : val;
        }
    }
    if (!first)
        return 0;
    char *v = sweep_paths_maps(c->path, paths);
    dm_str msg = {0};
    int rc = axes_check("maps", v, &msg);
    c->env = rc == DM_ERR_NOMEM ? rc : c->env;
    if (rc) {
        sweep__fail(c, first, "%s", dm_str_get(&msg));
        free(v);
    } else {
        rc = sweep__put_scene(c, "maps", v, first);
    }
    dm_str_free(&msg);
    return rc;
}

/* Mappings must be mappings, and YAML keys are unique: a repeated key would
 * silently win over the first, so it is an error naming both lines. */
static int sweep__expect_map(pctx *c, yaml_node_t *n, const char *what)
{
    if (!n || n->type != YAML_MAPPING_NODE)
        return sweep__fail(c, n, "%s: expected a mapping (key: value lines)", what);
    P__FOREACH_PAIR(c, n, a) {
        const char *ka = sweep__scalar(sweep__node(c, a->key));
        for (yaml_node_pair_t *b = n->data.mapping.pairs.start; ka && b < a; b++) {
            const char *kb = sweep__scalar(sweep__node(c, b->key));
            if (kb && strcmp(ka, kb) == 0)
                return sweep__fail(c, sweep__node(c, a->key), "%s: key '%s' is given twice (first on line %zu)",
                               what, ka, sweep__node(c, b->key)->start_mark.line + 1);
        }
    }
    return 0;
}

/* ---- The key table --------------------------------------------------------
 *
 * Every key a sweep file may hold is one row below: where it stands, what
 * parses it, its range and default, and what the docs say of it.  The
 * parser walks a mapping by looking each key up here (sweep__section), the
 * defaults are filled in from here, and docs/sweep-files.md's key reference
 * is generated from here (`dmbench list keys`, which
 * scripts/update-key-reference copies in; tests/cli/keys.sh keeps the two
 * equal), so the parser and the docs cannot drift apart. */

typedef struct sweep__key sweep__key;
typedef int (*sweep__fn)(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v);

struct sweep__key {
    sweep_key doc;           /* section, name, type, default, meaning, example */
    sweep__fn fn;
    const char *arg;         /* the axis a scene key sets, the section a key opens, or what a
                                list holds (for the message when it is not a list) */
    int (*entry)(pctx *c, yaml_node_t *e);   /* lists: reads one entry */
    size_t off;              /* numeric keys: the field in `sweep` */
    double lo, hi, def;      /* numeric keys: range and default */
};

static int sweep__section(pctx *c, yaml_node_t *map, const char *section);

/* "section.name" of a row, for messages. */
static const char *sweep__what(const sweep__key *row, char *buf, size_t size)
{
    snprintf(buf, size, "%s%s%s", row->doc.section, *row->doc.section ? "." : "", row->doc.name);
    return buf;
}

static int sweep__k_int(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    char what[64];
    return sweep__int(c, v, sweep__what(row, what, sizeof what), (long)row->lo, (long)row->hi,
                  (int *)(void *)((char *)c->s + row->off));
}

static int sweep__k_real(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    char what[64];
    return sweep__real(c, v, sweep__what(row, what, sizeof what), row->lo, row->hi,
                   (double *)(void *)((char *)c->s + row->off));
}

/* A fraction key: the one grammar of flags and keys (sweep/fraction.h). */
static int sweep__k_frac(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    char what[64];
    dm_str msg = {0};
    fraction_range range = { row->lo, row->hi, 0, 0 };
    int rc = fraction_parse(sweep__scalar(v), sweep__what(row, what, sizeof what), &range,
                            (double *)(void *)((char *)c->s + row->off), &msg);
    if (rc)
        rc = sweep__fail(c, v, "%s", dm_str_get(&msg));
    dm_str_free(&msg);
    return rc;
}

/* A nested mapping: its keys are the rows of section `arg`. */
static int sweep__k_section(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    return sweep__section(c, v, row->arg);
}

/* A scene default: the axis `arg`, or the key itself when arg is NULL. */
static int sweep__k_scene_axis(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    return sweep__set_scene(c, row->arg ? row->arg : sweep__scalar(k), k, v);
}

static int sweep__k_name(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    if (!sweep__scalar(v) || !*sweep__scalar(v))
        return sweep__fail(c, v, "name: expected a non-empty string");
    if (strlen(sweep__scalar(v)) > SWEEP_NAME_MAX)   /* it titles reports, jobs and terminal lines */
        return sweep__fail(c, v, "name: %zu bytes long; at most %d", strlen(sweep__scalar(v)),
                       SWEEP_NAME_MAX);
    free(c->s->name);
    c->s->name = dm_xstrdup(sweep__scalar(v));
    return 0;
}

/* measure.samples: max may not be below min when both are given. */
static int sweep__k_samples(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    const sweep_measure *m = &c->s->measure;
    int rc = sweep__k_section(c, row, k, v);
    if (rc == 0 && m->samples_min && m->samples_max && m->samples_max < m->samples_min)
        rc = sweep__fail(c, v, "measure.samples: max (%d) is less than min (%d)", m->samples_max,
                     m->samples_min);
    return rc;
}

static int sweep__k_counters(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    if (v->type != YAML_SEQUENCE_NODE)
        return sweep__fail(c, v, "measure.counters: expected a list of counter names");
    sweep_measure *m = &c->s->measure;
    for (yaml_node_item_t *it = v->data.sequence.items.start; it < v->data.sequence.items.top; it++) {
        yaml_node_t *n = sweep__node(c, *it);
        const char *name = sweep__scalar(n);
        if (!name || !counters_find(name)) {
            size_t nc = counters_count();
            const char **names = dm_xmalloc(nc * sizeof *names);
            for (size_t i = 0; i < nc; i++)
                names[i] = counters_info_at(i)->name;
            sweep__fail(c, n, "unknown counter '%s'", name ? name : "?");
            dm_str_suggest(c->err, name, names, nc, "counters");
            free(names);
            return DM_ERR_PARSE;
        }
        DM_VEC_PUSH(m->counters, m->n_counters, dm_xstrdup(name));
    }
    return 0;
}

/* drivers: a list of names; which exist is run/drivers.h's to say, so the
 * names are kept with their lines for `dmbench drivers` to check. */
static int sweep__k_drivers(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    if (v->type != YAML_SEQUENCE_NODE || v->data.sequence.items.start == v->data.sequence.items.top)
        return sweep__fail(c, v, "drivers: expected a non-empty list of driver names, e.g. "
                             "[llvmpipe, zink] (docs/drivers.md)");
    sweep *s = c->s;
    for (yaml_node_item_t *it = v->data.sequence.items.start; it < v->data.sequence.items.top; it++) {
        yaml_node_t *n = sweep__node(c, *it);
        const char *name = sweep__scalar(n);
        if (!name || !*name)
            return sweep__fail(c, n, "drivers: expected a driver name");
        for (size_t i = 0; i < s->n_drivers; i++)
            if (strcmp(s->drivers[i], name) == 0)
                return sweep__fail(c, n, "drivers: '%s' is listed twice (line %d)", name,
                               s->driver_lines[i]);
        s->driver_lines = dm_xrealloc(s->driver_lines, (s->n_drivers + 1) * sizeof *s->driver_lines);
        s->driver_lines[s->n_drivers] = (int)n->start_mark.line + 1;
        DM_VEC_PUSH(s->drivers, s->n_drivers, dm_xstrdup(name));
    }
    return 0;
}

/* scene.material: its keys, then the user's map files as one `maps` value. */
static int sweep__k_material(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    int rc = sweep__k_section(c, row, k, v);
    return rc ? rc : sweep__user_maps(c, v) ? DM_ERR_PARSE : 0;   /* an unreadable map is bad input */
}

/* scene.material.height|normal|albedo: a file path (read by sweep__user_maps). */
static int sweep__k_map_file(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    if (!sweep__scalar(v) || !*sweep__scalar(v))
        return sweep__fail(c, v, "scene.material.%s: expected a file path", row->doc.name);
    return 0;
}

/* One axis of the `sweep` block or of an `exclude` entry: a value or a list
 * of values appended to the block being read (c->axes). */
static int sweep__k_axis_values(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row;
    const char *name = sweep__scalar(k) ? sweep__scalar(k) : "";
    if (!axes_find(name))
        return sweep__set_scene(c, name, k, v);   /* reports the unknown axis */
    sweep_axis ax = { .name = dm_xstrdup(name), .line = (int)k->start_mark.line + 1 };
    /* resolution: [1280, 720] is one value; [[640, 360], "1280x720"] is a list. */
    int is_pair = 0, rc = 0;
    if (v->type == YAML_SEQUENCE_NODE && strcmp(name, "resolution") == 0 &&
        v->data.sequence.items.top - v->data.sequence.items.start == 2) {
        const char *first = sweep__scalar(sweep__node(c, v->data.sequence.items.start[0]));
        is_pair = first && !strchr(first, 'x');
    }
    yaml_node_item_t one = 0, *it = &one, *top = &one + 1;
    if (v->type == YAML_SEQUENCE_NODE && !is_pair)
        it = v->data.sequence.items.start, top = v->data.sequence.items.top;
    for (; it < top && rc == 0; it++) {
        char *val = sweep__axis_value(c, name, it == &one ? v : sweep__node(c, *it));
        if (!val)
            rc = DM_ERR_PARSE;
        else
            dm_vec_push(&ax.values, &ax.n_values, &val, sizeof val);
    }
    if (rc == 0 && ax.n_values == 0)
        rc = sweep__fail(c, v, "axis '%s' has no values (an empty list would plan nothing)", name);
    dm_vec_push(c->axes, c->n_axes, &ax, sizeof ax);
    return rc;
}

static int sweep__k_sweep(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    c->axes = &c->s->axes, c->n_axes = &c->s->n_axes;
    return sweep__k_section(c, row, k, v);
}

/* A list whose entries the row's `entry` reads, stopping at the first
 * error. */
static int sweep__k_list(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    if (v->type != YAML_SEQUENCE_NODE)
        return sweep__fail(c, v, "%s: expected a list of %s", row->doc.name, row->arg);
    int rc = 0;
    for (yaml_node_item_t *it = v->data.sequence.items.start; rc == 0 && it < v->data.sequence.items.top; it++)
        rc = row->entry(c, sweep__node(c, *it));
    return rc;
}

/* One `exclude` entry: {axis: value | [values], ...}. */
static int sweep__exclude_entry(pctx *c, yaml_node_t *e)
{
    sweep_exclude ex = {.line = (int)e->start_mark.line + 1};
    c->axes = &ex.axes, c->n_axes = &ex.n_axes;
    int rc = sweep__section(c, e, "exclude[]");
    if (rc == 0 && ex.n_axes == 0)
        rc = sweep__fail(c, e, "exclude[]: an empty entry would exclude everything");
    dm_vec_push(&c->s->excludes, &c->s->n_excludes, &ex, sizeof ex);
    return rc;
}

/* Every override of quality.reference must be read by the reference
 * technique (checked once the map is read, as `technique` may come last);
 * with technique `same` each configuration's own technique applies. */
static int sweep__reference_readable(pctx *c, yaml_node_t *v)
{
    const char *name = c->s->ref_technique ? c->s->ref_technique : "reference-mesh";
    const technique_desc *t = strcmp(name, "same") == 0 ? NULL : technique_find(name);
    P__FOREACH_PAIR(c, v, rp) {
        yaml_node_t *rk = sweep__node(c, rp->key);
        const char *axis = sweep__scalar(rk) ? sweep__scalar(rk) : "";
        if (t && axes_find(axis) && strcmp(axis, "technique") != 0 && !technique_reads_axis(t, axis))
            return sweep__fail(c, rk, "quality.reference: technique '%s' does not read axis '%s', so it "
                           "cannot set the reference's %s", name, axis, axis);
    }
    return 0;
}

static int sweep__k_reference(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    int rc = sweep__k_section(c, row, k, v);
    return rc ? rc : sweep__reference_readable(c, v);
}

static int sweep__k_ref_technique(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    int same = sweep__scalar(v) && strcmp(sweep__scalar(v), "same") == 0;
    char *t = same ? dm_xstrdup("same") : sweep__axis_value(c, "technique", v);
    if (!t)
        return DM_ERR_PARSE;
    free(c->s->ref_technique);
    c->s->ref_technique = t;
    return 0;
}

static int sweep__unknown_key(pctx *c, yaml_node_t *k, const char *section);

/* quality.reference.<axis>: an axis value set on the reference only. */
static int sweep__k_ref_axis(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    const char *name = sweep__scalar(k) ? sweep__scalar(k) : "";
    if (!axes_find(name))
        return sweep__unknown_key(c, k, row->doc.section);
    char *val = sweep__axis_value(c, name, v);
    if (!val)
        return DM_ERR_PARSE;
    dm_kv_push(&c->s->ref_params, &c->s->n_ref_params, name, val);
    free(val);
    return 0;
}

/* quality.pareto_metric: one of reports/metric.h's names (the list is an
 * X-macro, so no link to reports/ is needed). */
static int sweep__k_pareto(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    static const char *const names[] = {
#define P__METRIC_NAME(id, name) name,
        REPORT_METRICS(P__METRIC_NAME)
#undef P__METRIC_NAME
    };
    const size_t n = sizeof names / sizeof *names;
    const char *m = sweep__scalar(v);
    for (size_t i = 0; m && i < n; i++)
        if (strcmp(m, names[i]) == 0) {
            free(c->s->pareto_metric);
            c->s->pareto_metric = dm_xstrdup(m);
            return 0;
        }
    sweep__fail(c, v, "quality.pareto_metric: unknown metric '%s'", m ? m : "(not a scalar)");
    dm_str_suggest(c->err, m, names, n, "metrics");
    return DM_ERR_PARSE;
}

/* One `models` entry: {name, formula, response, group_by}. */
static int sweep__model_entry(pctx *c, yaml_node_t *e)
{
    sweep_model md = { .line = (int)e->start_mark.line + 1 };
    c->model = &md;
    int rc = sweep__section(c, e, "models[]");
    if (rc == 0 && !md.name)
        rc = sweep__fail(c, e, "models[]: every model needs a name");
    c->model = NULL;
    dm_vec_push(&c->s->models, &c->s->n_models, &md, sizeof md);
    return rc;
}

/* models[].name|formula|response: a string (a response must be a counter). */
static int sweep__k_model_text(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)k;
    const char *name = row->doc.name, *text = sweep__scalar(v);
    if (!text || !*text)
        return sweep__fail(c, v, "models[].%s: expected a non-empty string", name);
    if (strcmp(name, "response") == 0 && !counters_find(text))
        return sweep__fail(c, v, "models: response '%s' is not a counter", text);
    char **field = strcmp(name, "name") == 0 ? &c->model->name
                 : strcmp(name, "formula") == 0 ? &c->model->formula : &c->model->response;
    free(*field);
    *field = dm_xstrdup(text);
    return 0;
}

static int sweep__k_group_by(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    if (v->type != YAML_SEQUENCE_NODE)
        return sweep__fail(c, v, "models[].group_by: expected a list of axis names");
    sweep_model *md = c->model;
    for (yaml_node_item_t *it = v->data.sequence.items.start; it < v->data.sequence.items.top; it++) {
        const char *g = sweep__scalar(sweep__node(c, *it));
        if (!g || !axes_find(g))
            return sweep__fail(c, sweep__node(c, *it), "models: group_by: '%s' is not an axis", g ? g : "?");
        char *copy = dm_xstrdup(g);
        dm_vec_push(&md->group_by, &md->n_group_by, &copy, sizeof copy);
    }
    return 0;
}

/* published: a study's figures (sweep/published.c reads the block). */
static int sweep__k_published(pctx *c, const sweep__key *row, yaml_node_t *k, yaml_node_t *v)
{
    (void)row, (void)k;
    return published_parse(c->doc, v, c->path, &c->s->published, c->err);
}

#define P__INT(sec, key, field, lo, hi, def, doc, ex) \
    { { sec, key, "integer " #lo "–" #hi, #def, doc, ex }, sweep__k_int, NULL, NULL, offsetof(sweep, field), lo, hi, def }
#define P__REAL(sec, key, field, lo, hi, def, doc, ex) \
    { { sec, key, "number " #lo "–" #hi, #def, doc, ex }, sweep__k_real, NULL, NULL, offsetof(sweep, field), lo, hi, def }
/* A fraction (sweep/fraction.h): "3%" or 0.03; a bare number above 1 is refused. */
#define P__FRAC(sec, key, field, lo, hi, def, def_text, doc, ex) \
    { { sec, key, "fraction: `3%` or `0.03`", def_text, doc, ex }, sweep__k_frac, NULL, NULL, \
      offsetof(sweep, field), lo, hi, def }
#define P__ROW(sec, key, fn, arg, type, deflt, doc, ex) { { sec, key, type, deflt, doc, ex }, fn, arg, NULL, 0, 0, 0, 0 }
#define P__AXIS(sec, key, axis, ex) { { sec, key, "a value of `" axis "`", "the axis' default", \
    "sets the `" axis "` axis", ex }, sweep__k_scene_axis, axis, NULL, 0, 0, 0, 0 }
#define P__FILE(key, doc) { { "scene.material", key, "file path", "procedural", doc, \
    "maps/" key ".png" }, sweep__k_map_file, NULL, NULL, 0, 0, 0, 0 }
#define P__MAP(sec, key, fn, opens, doc) \
    { { sec, key, "mapping", "see `" opens "`", doc, NULL }, fn, opens, NULL, 0, 0, 0, 0 }
#define P__LIST(sec, key, entry, holds, deflt, doc) \
    { { sec, key, "list of mappings", deflt, doc, NULL }, sweep__k_list, holds, entry, 0, 0, 0, 0 }

static const sweep__key sweep__keys[] = {
    P__ROW("", "name", sweep__k_name, NULL, "string", "`unnamed`",
           "name of the sweep, shown in reports and stored with the run", "tess-study"),
    P__ROW("", "resolution", sweep__k_scene_axis, "resolution", "`[W, H]` or `\"WxH\"`", "the axis' default",
           "default render size (the `resolution` axis)", "[480, 270]"),
    P__MAP("", "measure", sweep__k_section, "measure", "how each configuration is measured"),
    P__ROW("", "scene", sweep__k_section, "scene", "mapping", "catalog defaults",
           "defaults for every configuration", NULL),
    P__ROW("", "sweep", sweep__k_sweep, "sweep", "mapping", "no axes: one configuration",
           "the axes; their cartesian product is planned", NULL),
    P__LIST("", "exclude", sweep__exclude_entry, "{axis: value or [values], ...} entries", "none",
            "combinations of sweep values not to plan"),
    P__MAP("", "quality", sweep__k_section, "quality", "what images are compared with"),
    P__LIST("", "models", sweep__model_entry, "{name, formula, group_by, response}", "none",
            "cost models fitted after the run"),
    P__ROW("", "published", sweep__k_published, NULL, "mapping (see `published`)", "none",
           "a study's figures, set beside the measured ones in the report", NULL),
    P__ROW("", "drivers", sweep__k_drivers, NULL, "list of driver names", "none: the run's own driver",
           "measure the sweep once per driver, each in its own run, and set them side by side "
           "(`dmbench drivers`, docs/drivers.md)", "[llvmpipe, zink]"),

    P__INT("measure", "warmup_frames", measure.warmup_frames, 0, 100000, 8,
           "frames drawn before anything is timed; warm-up then goes on until two consecutive "
           "samples agree within 10 %", "4"),
    P__INT("measure", "frames_per_sample", measure.frames_per_sample, 1, 100000, 16,
           "K: one sample is K frames fenced by `glFinish`; frame time = sample / K", "8"),
    P__REAL("measure", "min_sample_ms", measure.min_sample_ms, 0, 10000, 20,
            "K is raised per configuration until a sample lasts this long (0: K exactly)", "20"),
    P__MAP("measure", "samples", sweep__k_samples, "measure.samples", "how many samples"),
    P__REAL("measure", "max_seconds", measure.max_seconds, 0.01, 86400, 10,
            "time cap on sampling one configuration (after `samples.min`)", "6"),
    P__REAL("measure", "timeout_s", measure.timeout_s, 1, 86400, 120,
            "watchdog: a configuration without progress for this long is killed and recorded "
            "as failed", "60"),
    P__ROW("measure", "counters", sweep__k_counters, NULL, "list of counter names",
           "WallTime, CPUTime, SubmitTime, GPUTime, the pipeline statistics, SamplesPassed, "
           "TextureBytes, MeshBytes, MeshTriangles",
           "the counters read per configuration (`dmbench list counters`)", "[WallTime, FSInvocations]"),

    P__INT("measure.samples", "min", measure.samples_min, 2, 10000, 5,
           "never fewer samples", "5"),
    P__INT("measure.samples", "max", measure.samples_max, 2, 10000, 30,
           "never more samples (raised to `min` when `min` is larger and `max` is not given)", "30"),
    P__FRAC("measure.samples", "target_ci", measure.target_ci, 0, 1, 0.03, "3%",
            "stop once the 95 % CI of the median is within ± this fraction of it", "3%"),

    P__MAP("scene", "camera", sweep__k_section, "scene.camera", "where the camera is"),
    P__MAP("scene", "lights", sweep__k_section, "scene.lights", "how the scene is lit"),
    P__MAP("scene", "material", sweep__k_material, "scene.material", "the surface's maps"),
    P__ROW("scene", "*", sweep__k_scene_axis, NULL, "a value of that axis", "the axis' default",
           "any axis (`dmbench list axes`): its value for every configuration", "mesh: cube"),

    P__AXIS("scene.camera", "distance", "camera.distance", "3.0"),
    P__AXIS("scene.camera", "azimuth", "camera.azimuth", "30"),
    P__AXIS("scene.camera", "elevation", "camera.elevation", "35"),
    P__AXIS("scene.camera", "fov", "camera.fov", "45"),

    P__AXIS("scene.lights", "model", "lighting", "blinn-phong"),
    P__AXIS("scene.lights", "count", "light_count", "1"),

    P__AXIS("scene.material", "maps", "maps", "bricks"),
    P__AXIS("scene.material", "height_scale", "height_scale", "0.06"),
    P__FILE("height", "the user's height map (relative to the sweep file); with `normal` and "
            "`albedo` it becomes the `maps` value"),
    P__FILE("normal", "the user's normal map"),
    P__FILE("albedo", "the user's albedo map"),

    P__ROW("sweep", "*", sweep__k_axis_values, NULL, "a value or a list of values", "—",
           "an axis (`dmbench list axes`) and the values it takes", "tess_level: [1, 16, 64]"),
    P__ROW("exclude[]", "*", sweep__k_axis_values, NULL, "a value or a list of values", "—",
           "a sweep axis; the entry drops combinations with one of these values on every "
           "axis it names", "technique: phong"),

    P__ROW("quality", "reference", sweep__k_reference, "quality.reference", "mapping",
           "see `quality.reference`", "the image every configuration is compared with", NULL),
    P__ROW("quality", "pareto_metric", sweep__k_pareto, NULL,
           "`ssim`, `psnr`, `rmse`, `max-error`, `silhouette`, `depth-rmse` or `flip`", "`ssim`",
           "the error the report's Pareto front uses", "psnr"),
    P__REAL("quality", "budget_ms", budget_ms, 0.001, 1e6, 0,
            "the frame budget (ms) the report's recommendation picks under; 0 or absent: per "
            "scene, the round number (1, 2, 5 × 10ᵏ ms) farthest from its lit times, in the widest "
            "gap between its fastest and slowest (docs/reports.md)", "16.7"),
    P__REAL("quality", "flip_ppd", flip_ppd, 1, 600, 67.0206,
            "pixels per degree of visual angle FLIP assumes (docs/flip.md); the default is "
            "FLIP's own, a 0.7 m wide 3840-pixel monitor seen from 0.7 m", "30"),

    P__ROW("quality.reference", "technique", sweep__k_ref_technique, NULL, "a technique or `same`",
           "`reference-mesh`", "the reference's technique; `same`: each configuration "
           "supersampled", "normal"),
    P__INT("quality.reference", "supersample", supersample, 1, 8, 4,
           "the reference is rendered this many times larger per axis, then reduced", "4"),
    P__ROW("quality.reference", "*", sweep__k_ref_axis, NULL, "a value of that axis",
           "the configuration's", "any axis the reference technique reads, set on the "
           "reference only", "maps: stones"),

    P__ROW("models[]", "name", sweep__k_model_text, NULL, "string", "— (required)",
           "the model's name; without `formula` a built-in model (`dmbench list models`)",
           "pixel-cost"),
    P__ROW("models[]", "formula", sweep__k_model_text, NULL, "formula", "the built-in's",
           "expression and bounds (see `models`)", "\"a + b*SamplesPassed\""),
    P__ROW("models[]", "response", sweep__k_model_text, NULL, "counter name", "`WallTime`",
           "the counter the formula predicts", "WallTime"),
    P__ROW("models[]", "group_by", sweep__k_group_by, NULL, "list of axes", "none",
           "one fit per distinct value of these axes", "[technique]"),
};
#define P__N_KEYS (sizeof sweep__keys / sizeof sweep__keys[0])
_Static_assert(P__N_KEYS <= sizeof ((pctx *)0)->seen, "pctx.seen is too small for the key table");

size_t sweep_keys_count(void) { return P__N_KEYS; }
const sweep_key *sweep_keys_at(size_t i) { return i < P__N_KEYS ? &sweep__keys[i].doc : NULL; }

/* The row of `name` in `section`, else the section's "*" row, else NULL. */
static const sweep__key *sweep__lookup(const char *section, const char *name)
{
    const sweep__key *any = NULL;
    for (size_t i = 0; i < P__N_KEYS; i++) {
        if (strcmp(sweep__keys[i].doc.section, section) != 0)
            continue;
        if (strcmp(sweep__keys[i].doc.name, name) == 0)
            return &sweep__keys[i];
        if (strcmp(sweep__keys[i].doc.name, "*") == 0)
            any = &sweep__keys[i];
    }
    return any;
}

/* Rejects a key that is no row of `section` (nor an axis where the section
 * takes axes), listing the valid ones and the closest match. */
static int sweep__unknown_key(pctx *c, yaml_node_t *k, const char *section)
{
    const char *key = sweep__scalar(k) ? sweep__scalar(k) : "?";
    size_t n = 0;
    const char **valid = dm_xmalloc((P__N_KEYS + axes_count()) * sizeof *valid);
    for (size_t i = 0; i < P__N_KEYS; i++)
        if (strcmp(sweep__keys[i].doc.section, section) == 0 && strcmp(sweep__keys[i].doc.name, "*") != 0)
            valid[n++] = sweep__keys[i].doc.name;
    for (size_t i = 0; sweep__lookup(section, "\x01") && i < axes_count(); i++)
        valid[n++] = axes_at(i)->name;
    sweep__fail(c, k, "unknown key '%s' in %s", key, *section ? section : "the sweep file");
    dm_str_suggest(c->err, key, valid, n, "keys");
    free(valid);
    return DM_ERR_PARSE;
}

/* Reads a mapping whose keys are the rows of `section`. */
static int sweep__section(pctx *c, yaml_node_t *map, const char *section)
{
    int rc = sweep__expect_map(c, map, *section ? section : "sweep file");
    P__FOREACH_PAIR(c, map, pr) {
        if (rc)
            break;
        yaml_node_t *k = sweep__node(c, pr->key), *v = sweep__node(c, pr->value);
        const sweep__key *row = sweep__lookup(section, sweep__scalar(k) ? sweep__scalar(k) : "");
        if (!row)
            return sweep__unknown_key(c, k, section);
        c->seen[row - sweep__keys] = 1;
        rc = row->fn(c, row, k, v);
    }
    return rc;
}

/* Numeric keys the file did not give take the table's default. */
static void sweep__numeric_defaults(pctx *c)
{
    for (size_t i = 0; i < P__N_KEYS; i++) {
        const sweep__key *row = &sweep__keys[i];
        char *field = (char *)c->s + row->off;
        if (c->seen[i] || (row->fn != sweep__k_int && row->fn != sweep__k_real && row->fn != sweep__k_frac))
            continue;
        if (row->fn == sweep__k_int)
            *(int *)(void *)field = (int)row->def;
        else
            *(double *)(void *)field = row->def;
    }
    sweep_measure *m = &c->s->measure;
    if (m->samples_max < m->samples_min)   /* only min was given, above max's default */
        m->samples_max = m->samples_min;
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
    if (!m->n_counters) {
        size_t n = sizeof counters / sizeof counters[0];
        m->counters = dm_xmalloc(n * sizeof *m->counters);
        for (size_t i = 0; i < n; i++)
            m->counters[i] = dm_xstrdup(counters[i]);
        m->n_counters = n;
    }
    if (!s->ref_technique)          /* ground truth: the CPU-displaced fine mesh (docs/sweep-files.md, Quality) */
        s->ref_technique = dm_xstrdup("reference-mesh");
    if (!s->pareto_metric)
        s->pareto_metric = dm_xstrdup("ssim");
}

/* The child of mapping n under key `name`, or NULL. */
static yaml_node_t *sweep__child(pctx *c, yaml_node_t *n, const char *name)
{
    for (yaml_node_pair_t *p = n && n->type == YAML_MAPPING_NODE ? n->data.mapping.pairs.start : NULL;
         p && p < n->data.mapping.pairs.top; p++) {
        const char *k = sweep__scalar(sweep__node(c, p->key));
        if (k && strcmp(k, name) == 0)
            return sweep__node(c, p->value);
    }
    return NULL;
}

/* Loads the user techniques (docs/user-techniques.md) that `sweep:` and
 * `scene:` name before anything else is read, so their parameters are axes
 * wherever the file puts them.  Errors are left to the regular pass, which
 * reports them at their line. */
static void sweep__preload_techniques(pctx *c, yaml_node_t *root)
{
    static const char *const sections[] = {"sweep", "scene"};
    for (size_t s = 0; s < 2; s++) {
        yaml_node_t *t = sweep__child(c, sweep__child(c, root, sections[s]), "technique");
        size_t n = t && t->type == YAML_SEQUENCE_NODE
                       ? (size_t)(t->data.sequence.items.top - t->data.sequence.items.start) : 1;
        for (size_t i = 0; t && i < n; i++) {
            yaml_node_t *v = t->type == YAML_SEQUENCE_NODE ? sweep__node(c, t->data.sequence.items.start[i]) : t;
            char *path = sweep__scalar(v) ? sweep_paths_resolve(c->path, "technique", dm_xstrdup(sweep__scalar(v))) : NULL;
            dm_str ignored = {0};
            if (path && user_technique_is_path(path))
                user_technique_load(path, NULL, &ignored);
            dm_str_free(&ignored);
            free(path);
        }
    }
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
    int rc = sweep_yaml_depth_check(&doc, path, err);
    yaml_node_t *root = yaml_document_get_root_node(&doc);
    if (rc == 0 && !root)
        rc = sweep__fail(&c, NULL, "empty sweep file (expected keys: name, sweep, ...)");
    if (rc == 0)
        sweep__preload_techniques(&c, root);
    rc = rc ? rc : sweep__section(&c, root, "");
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    if (rc == 0)
        rc = sweep__check_excludes(out, err);
    if (rc) {
        sweep_free(out);
        return c.env ? c.env : rc;
    }
    sweep__numeric_defaults(&c);
    sweep__defaults(out);
    out->hash = dm_fnv1a64(text, strlen(text), DM_FNV_SEED);
    return 0;
}

int sweep_load(const char *path, sweep *out, dm_str *err)
{
    char *text = NULL;
    size_t len = 0;
    memset(out, 0, sizeof *out);
    char why[256];
    if (dm_input_file(path, why, sizeof why) != 0) {
        dm_str_printf(err, "%s: cannot read the sweep file: %s", path, why);
        return DM_ERR_IO;
    }
    if (dm_read_file(path, &text, &len) != 0) {
        dm_str_printf(err, "%s: cannot read the sweep file: %s", path, strerror(errno));
        return DM_ERR_IO;
    }
    const char *nul = memchr(text, '\0', len);
    if (nul) {   /* the YAML parser would stop there and silently drop the rest */
        size_t line = 1;
        for (const char *p = text; p < nul; p++)
            line += *p == '\n';
        int utf16 = len >= 2 && ((unsigned char)text[0] == 0xff || (unsigned char)text[0] == 0xfe) &&
                    (unsigned char)text[0] + (unsigned char)text[1] == 0xff + 0xfe;
        if (utf16)   /* a byte-order mark FF FE or FE FF: an editor's "Unicode" */
            dm_str_printf(err, "%s:1: the file is UTF-16 text (it starts with a UTF-16 byte-order "
                          "mark); a sweep file is UTF-8: save it as UTF-8", path);
        else
            dm_str_printf(err, "%s:%zu: a NUL byte: a sweep file is UTF-8 text (is this a binary "
                          "file?)", path, line);
        free(text);
        return DM_ERR_PARSE;
    }
    int rc = sweep_parse(text, path, out, err);
    free(text);
    return rc;
}

void sweep_free(sweep *s)
{
    free(s->path);
    free(s->name);
    dm_kv_free(s->scene, s->n_scene);
    free(s->scene_lines);
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
    for (size_t i = 0; i < s->n_drivers; i++)
        free(s->drivers[i]);
    free(s->drivers);
    free(s->driver_lines);
    memset(s, 0, sizeof *s);
}
