/* published.c — the `published:` block of a sweep file (see published.h). */
#include "published.h"
#include "plan.h"
#include "core/dm_error.h"
#include "techniques/axes.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Parse state: the document, the file name for messages, the error. */
typedef struct pub_ctx {
    yaml_document_t *doc;
    const char *path;
    dm_str *err;
} pub_ctx;

static const char *const pub__units[] = { "fps", "seconds", "ms" };
#define PUB__N_UNITS (sizeof pub__units / sizeof *pub__units)

static int pub__fail(pub_ctx *c, const yaml_node_t *n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Writes "path:line:col: message" (the node's position) into the error;
 * returns DM_ERR_PARSE. */
static int pub__fail(pub_ctx *c, const yaml_node_t *n, const char *fmt, ...)
{
    dm_str msg = {0};
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(&msg, fmt, ap);
    va_end(ap);
    size_t line = n ? n->start_mark.line + 1 : 1, col = n ? n->start_mark.column + 1 : 1;
    dm_str_printf(c->err, "%s:%zu:%zu: %s", c->path, line, col, dm_str_get(&msg));
    dm_str_free(&msg);
    return DM_ERR_PARSE;
}

static const char *pub__text(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

/* A non-empty scalar copied into *out, else an error naming `what`. */
static int pub__string(pub_ctx *c, yaml_node_t *n, const char *what, char **out)
{
    const char *v = pub__text(n);
    if (!v || !*v)
        return pub__fail(c, n, "published.%s: expected a non-empty text", what);
    free(*out);
    *out = dm_xstrdup(v);
    return 0;
}

/* An unknown key of a published mapping: did-you-mean and the valid keys. */
static int pub__unknown(pub_ctx *c, yaml_node_t *k, const char *where,
                        const char *const *keys, size_t n)
{
    const char *key = pub__text(k) ? pub__text(k) : "?";
    pub__fail(c, k, "unknown key '%s' in %s", key, where);
    dm_str_suggest(c->err, key, keys, n, "keys");
    return DM_ERR_PARSE;
}

/* source: { study, table, gpu } — study and table are required. */
static int pub__source(pub_ctx *c, yaml_node_t *map, published *p)
{
    static const char *const keys[] = { "study", "table", "gpu" };
    if (map->type != YAML_MAPPING_NODE)
        return pub__fail(c, map, "published.source: expected a mapping {study, table, gpu}");
    char **slot[] = { &p->study, &p->table, &p->gpu };
    for (yaml_node_pair_t *pr = map->data.mapping.pairs.start; pr < map->data.mapping.pairs.top; pr++) {
        yaml_node_t *k = yaml_document_get_node(c->doc, pr->key);
        size_t i = 0;
        while (i < 3 && (!pub__text(k) || strcmp(pub__text(k), keys[i]) != 0))
            i++;
        if (i == 3)
            return pub__unknown(c, k, "published.source", keys, 3);
        int rc = pub__string(c, yaml_document_get_node(c->doc, pr->value), keys[i], slot[i]);
        if (rc)
            return rc;
    }
    if (!p->study || !p->table)
        return pub__fail(c, map, "published.source: needs 'study' (title, author, year) and "
                         "'table' (which table of it)");
    return 0;
}

static int pub__unit(pub_ctx *c, yaml_node_t *n, published *p)
{
    const char *u = pub__text(n);
    for (size_t i = 0; u && i < PUB__N_UNITS; i++)
        if (strcmp(u, pub__units[i]) == 0)
            return pub__string(c, n, "unit", &p->unit);
    pub__fail(c, n, "published.unit: unknown unit '%s'", u ? u : "(not a scalar)");
    dm_str_suggest(c->err, u ? u : "", pub__units, PUB__N_UNITS, "units");
    return DM_ERR_PARSE;
}

/* values: { label: number, ... } — every number finite and > 0, labels unique. */
static int pub__values(pub_ctx *c, yaml_node_t *map, published *p)
{
    if (map->type != YAML_MAPPING_NODE)
        return pub__fail(c, map, "published.values: expected a mapping of configuration label: value");
    for (yaml_node_pair_t *pr = map->data.mapping.pairs.start; pr < map->data.mapping.pairs.top; pr++) {
        yaml_node_t *k = yaml_document_get_node(c->doc, pr->key);
        yaml_node_t *v = yaml_document_get_node(c->doc, pr->value);
        const char *label = pub__text(k), *num = pub__text(v);
        if (!label || !*label)
            return pub__fail(c, k, "published.values: a label must be a non-empty text");
        for (size_t i = 0; i < p->n_values; i++)
            if (strcmp(p->values[i].label, label) == 0)
                return pub__fail(c, k, "published.values: label '%s' is given twice (first on line %d)",
                                 label, p->values[i].line);
        char *end = NULL;
        double x = num ? strtod(num, &end) : NAN;
        if (!num || end == num || *end || !isfinite(x) || x <= 0)
            return pub__fail(c, v, "published.values: '%s': expected a finite number > 0, got '%s'",
                             label, num ? num : "(not a scalar)");
        p->values = dm_xrealloc(p->values, (p->n_values + 1) * sizeof *p->values);
        p->values[p->n_values++] = (published_value){ .label = dm_xstrdup(label), .value = x,
                                                      .line = (int)k->start_mark.line + 1 };
    }
    return 0;
}

/* The baseline must be one of the labels; the valid ones are listed. */
static int pub__check_baseline(pub_ctx *c, yaml_node_t *bnode, const published *p)
{
    const char **labels = dm_xmalloc(p->n_values * sizeof *labels);
    for (size_t i = 0; i < p->n_values; i++) {
        if (strcmp(p->values[i].label, p->baseline) == 0) {
            free(labels);
            return 0;
        }
        labels[i] = p->values[i].label;
    }
    pub__fail(c, bnode, "published.baseline: '%s' is not one of the labels under values",
              p->baseline);
    dm_str_suggest(c->err, p->baseline, labels, p->n_values, "labels");
    free(labels);
    return DM_ERR_PARSE;
}

/* One key of the published mapping into p. */
static int pub__key(pub_ctx *c, yaml_node_t *k, yaml_node_t *v, published *p, yaml_node_t **bnode)
{
    static const char *const keys[] = { "source", "unit", "baseline", "values" };
    const char *name = pub__text(k) ? pub__text(k) : "";
    if (strcmp(name, "source") == 0)
        return pub__source(c, v, p);
    if (strcmp(name, "unit") == 0)
        return pub__unit(c, v, p);
    if (strcmp(name, "values") == 0)
        return pub__values(c, v, p);
    if (strcmp(name, "baseline") == 0) {
        *bnode = v;
        return pub__string(c, v, "baseline", &p->baseline);
    }
    return pub__unknown(c, k, "published", keys, 4);
}

int published_parse(yaml_document_t *doc, yaml_node_t *map, const char *path,
                    published **out, dm_str *err)
{
    pub_ctx c = { doc, path, err };
    *out = NULL;
    if (!map || map->type != YAML_MAPPING_NODE)
        return pub__fail(&c, map, "published: expected a mapping {source, unit, baseline, values}");
    published *p = dm_xcalloc(1, sizeof *p);
    p->line = (int)map->start_mark.line + 1;
    yaml_node_t *bnode = NULL;
    int rc = 0;
    for (yaml_node_pair_t *pr = map->data.mapping.pairs.start; rc == 0 && pr < map->data.mapping.pairs.top; pr++)
        rc = pub__key(&c, yaml_document_get_node(doc, pr->key), yaml_document_get_node(doc, pr->value),
                      p, &bnode);
    const char *missing = !p->study ? "source" : !p->unit ? "unit" : !p->n_values ? "values"
                        : !p->baseline ? "baseline" : NULL;
    if (rc == 0 && missing)
        rc = pub__fail(&c, map, "published: '%s' is missing (needs source, unit, baseline, values)",
                       missing);
    rc = rc ? rc : pub__check_baseline(&c, bnode, p);
    if (rc)
        published_free(p);
    else
        *out = p;
    return rc;
}

/* Does word ("technique" or "axis=value") hold for configuration cfg? */
static int pub__word_matches(const plan_config *cfg, const char *word)
{
    const char *eq = strchr(word, '=');
    if (!eq) {
        const char *t = dm_kv_get(cfg->params, cfg->n_params, "technique");
        return t && strcmp(t, word) == 0;
    }
    char *axis = dm_xasprintf("%.*s", (int)(eq - word), word);
    const char *have = dm_kv_get(cfg->params, cfg->n_params, axis);
    char *want = have && axes_find(axis) ? axes_canonical(axis, eq + 1) : NULL;
    int ok = want && strcmp(have, want) == 0;
    free(want);
    free(axis);
    return ok;
}

/* Does every word of label hold for cfg?  (An empty label matches nothing.) */
static int pub__label_matches(const plan_config *cfg, const char *label)
{
    char *copy = dm_xstrdup(label), *save = NULL;
    int ok = 0;
    for (char *w = strtok_r(copy, " \t", &save); w; w = strtok_r(NULL, " \t", &save))
        if (!(ok = pub__word_matches(cfg, w)))
            break;
    free(copy);
    return ok;
}

/* Does parameter `key` take two or more values over the plan? */
static int pub__varies(const plan *pl, const char *key)
{
    const char *first = NULL;
    for (size_t i = 0; i < pl->n_configs; i++) {
        const char *v = dm_kv_get(pl->configs[i].params, pl->configs[i].n_params, key);
        if (v && first && strcmp(v, first) != 0)
            return 1;
        first = first ? first : v;
    }
    return 0;
}

void published_plan_label(const plan *pl, size_t i, dm_str *out)
{
    const plan_config *cfg = &pl->configs[i];
    const char *t = dm_kv_get(cfg->params, cfg->n_params, "technique");
    dm_str_cat(out, t ? t : "?");
    for (size_t k = 0; k < cfg->n_params; k++)
        if (strcmp(cfg->params[k].key, "technique") != 0 && pub__varies(pl, cfg->params[k].key))
            dm_str_printf(out, " %s=%s", cfg->params[k].key, cfg->params[k].value);
}

/* How many words of label hold for cfg. */
static size_t pub__words_holding(const plan_config *cfg, const char *label)
{
    char *copy = dm_xstrdup(label), *save = NULL;
    size_t n = 0;
    for (char *w = strtok_r(copy, " \t", &save); w; w = strtok_r(NULL, " \t", &save))
        n += (size_t)pub__word_matches(cfg, w);
    free(copy);
    return n;
}

/* The planned label to suggest for an unmatched one: among the
 * configurations for which most of its words hold, the closest by edit
 * distance (word order in a label is free, so edit distance alone misleads). */
static const char *pub__suggestion(const plan *pl, const char *label, const char **names)
{
    size_t best = 0, n = 0;
    for (size_t i = 0; i < pl->n_configs; i++)
        best = pub__words_holding(&pl->configs[i], label) > best
             ? pub__words_holding(&pl->configs[i], label) : best;
    const char **cand = dm_xcalloc(pl->n_configs + 1, sizeof *cand);
    for (size_t i = 0; best && i < pl->n_configs; i++)
        if (pub__words_holding(&pl->configs[i], label) == best)
            cand[n++] = names[i];
    const char *pick = n ? dm_closest(label, cand, n) : dm_closest(label, names, pl->n_configs);
    pick = pick ? pick : n ? cand[0] : NULL;
    free(cand);
    return pick;
}

/* "path:line: published label 'x' names no planned configuration; did you
 * mean ...? valid planned labels: ..." */
static int pub__no_match(const published_value *v, const plan *pl, const char *path, dm_str *err)
{
    dm_str *labels = dm_xcalloc(pl->n_configs + 1, sizeof *labels);
    const char **names = dm_xcalloc(pl->n_configs + 1, sizeof *names);
    for (size_t i = 0; i < pl->n_configs; i++) {
        published_plan_label(pl, i, &labels[i]);
        names[i] = dm_str_get(&labels[i]);
    }
    dm_str_printf(err, "%s:%d: published label '%s' names no planned configuration", path,
                  v->line, v->label);
    const char *pick = pub__suggestion(pl, v->label, names);
    if (pick)
        dm_str_printf(err, "; did you mean '%s'?", pick);
    dm_str_cat(err, " valid planned labels: ");
    dm_str_cat_list(err, names, pl->n_configs);
    for (size_t i = 0; i < pl->n_configs; i++)
        dm_str_free(&labels[i]);
    free(labels);
    free(names);
    return DM_ERR_PARSE;
}

int published_resolve(published *p, const plan *pl, const char *path, dm_str *err)
{
    for (size_t k = 0; p && k < p->n_values; k++) {
        published_value *v = &p->values[k];
        size_t hit = 0, n = 0;
        for (size_t i = 0; i < pl->n_configs; i++)
            if (pub__label_matches(&pl->configs[i], v->label))
                hit = n++ ? hit : i;
        if (n == 0)
            return pub__no_match(v, pl, path, err);
        if (n > 1) {
            dm_str_printf(err, "%s:%d: published label '%s' matches %zu planned configurations; "
                          "add axis=value words until one is left, e.g. '", path, v->line, v->label, n);
            published_plan_label(pl, hit, err);
            dm_str_cat(err, "'");
            return DM_ERR_PARSE;
        }
        memcpy(v->key, pl->configs[hit].key, sizeof v->key);
    }
    return 0;
}

/* One values[] entry of published.json; NULL when cJSON runs out of memory. */
static cJSON *pub__json_value(const published_value *v)
{
    cJSON *o = cJSON_CreateObject();
    if (o && cJSON_AddStringToObject(o, "label", v->label) && cJSON_AddStringToObject(o, "key", v->key) &&
        cJSON_AddNumberToObject(o, "value", v->value))
        return o;
    cJSON_Delete(o);
    return NULL;
}

int published_write_json(const published *p, const char *path)
{
    cJSON *root = cJSON_CreateObject(), *src = cJSON_AddObjectToObject(root, "source");
    const char *fields[][2] = { { "study", p->study }, { "table", p->table }, { "gpu", p->gpu } };
    for (size_t i = 0; i < 3; i++)
        if (fields[i][1])
            cJSON_AddStringToObject(src, fields[i][0], fields[i][1]);
    cJSON_AddStringToObject(root, "unit", p->unit);
    cJSON_AddStringToObject(root, "baseline", p->baseline);
    cJSON *vals = cJSON_AddArrayToObject(root, "values");
    for (size_t i = 0; i < p->n_values; i++)
        cJSON_AddItemToArray(vals, pub__json_value(&p->values[i]));
    char *text = cJSON_Print(root);
    int rc = text ? dm_write_file(path, text, strlen(text)) : DM_ERR_NOMEM;   /* DISK: exit 4 */
    cJSON_free(text);
    cJSON_Delete(root);
    return rc;
}

void published_free(published *p)
{
    for (size_t i = 0; p && i < p->n_values; i++)
        free(p->values[i].label);
    char *owned[] = { p ? p->study : NULL, p ? p->table : NULL, p ? p->gpu : NULL,
                      p ? p->unit : NULL, p ? p->baseline : NULL, p ? (char *)p->values : NULL };
    for (size_t i = 0; i < sizeof owned / sizeof *owned; i++)
        free(owned[i]);
    free(p);
}
