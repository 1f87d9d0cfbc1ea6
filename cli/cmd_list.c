/* cmd_list.c — `dmbench list techniques|axes|counters|meshes|textures|models`.
 *
 * Every list is read from its registry (techniques/, counters/, meshes and
 * maps, models/catalog.c), never typed in here; --json prints any of them as
 * a JSON array of objects.
 */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "counters/counters.h"
#include "models/catalog.h"
#include "run/gl_context.h"
#include "sweep/sweep.h"
#include "techniques/axes.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

#include <cjson/cJSON.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Prints a JSON value and frees it. */
static int list__print_json(cJSON *v)
{
    char *text = cJSON_Print(v);
    puts(text);
    free(text);
    cJSON_Delete(v);
    return DM_EXIT_OK;
}

/* A NULL-terminated list of strings as a JSON array. */
static cJSON *list__strings(const char *const *s)
{
    cJSON *arr = cJSON_CreateArray();
    for (; s && *s; s++)
        cJSON_AddItemToArray(arr, cJSON_CreateString(*s));
    return arr;
}

/* Prints the JSON array of item(0..n) (NULL items are left out). */
static int list__json(size_t n, cJSON *(*item)(size_t i))
{
    cJSON *arr = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++) {
        cJSON *o = item(i);
        if (o)
            cJSON_AddItemToArray(arr, o);
    }
    return list__print_json(arr);
}

/* Technique i as JSON; NULL for a test-only technique. */
static cJSON *list__technique_json(size_t i)
{
    const technique_desc *t = technique_at(i);
    if (t->test_only)
        return NULL;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", t->name);
    cJSON_AddStringToObject(o, "summary", t->summary ? t->summary : "");
    cJSON_AddItemToObject(o, "axes", list__strings(t->axes));
    if (t->requires_ext)
        cJSON_AddStringToObject(o, "requires", t->requires_ext);
    return o;
}

static int list__techniques(void)
{
    for (size_t i = 0; i < technique_count(); i++) {
        const technique_desc *t = technique_at(i);
        if (t->test_only)
            continue;
        char *b = NULL;   /* a user technique's //@summary: its control bytes as '?' */
        printf("%-20s %s\n", t->name, dm_term_safe(t->summary ? t->summary : "", &b));
        free(b);
        dm_str axes = {0};
        for (const char *const *a = t->axes; a && *a; a++)
            dm_str_printf(&axes, "%s%s", a == t->axes ? "" : ", ", *a);
        printf("%-20s reads: scene axes%s%s\n", "", axes.len ? ", " : "", dm_str_get(&axes));
        if (t->requires_ext)
            printf("%-20s needs: %s\n", "", t->requires_ext);
        dm_str_free(&axes);
    }
    return DM_EXIT_OK;
}

static const char *list__axis_kind(const axis_info *a)
{
    return a->kind == AXIS_ENUM ? "enum" : a->kind == AXIS_SIZE2 ? "size" : a->kind == AXIS_INT ? "int" : "real";
}

static cJSON *list__axis_json(size_t i)
{
    const axis_info *a = axes_at(i);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", a->name);
    cJSON_AddStringToObject(o, "kind", list__axis_kind(a));
    cJSON_AddBoolToObject(o, "scene", a->scene);
    cJSON_AddStringToObject(o, "default", a->def);
    if (a->kind == AXIS_ENUM)
        cJSON_AddItemToObject(o, "choices", list__strings(a->choices));
    if (a->kind == AXIS_INT || a->kind == AXIS_FLOAT) {
        cJSON_AddNumberToObject(o, "min", a->min);
        cJSON_AddNumberToObject(o, "max", a->max);
    }
    return o;
}

static int list__axes(void)
{
    for (size_t i = 0; i < axes_count(); i++) {
        const axis_info *a = axes_at(i);
        dm_str v = {0};
        if (a->kind == AXIS_ENUM) {
            for (const char *const *c = a->choices; c && *c; c++)
                dm_str_printf(&v, "%s%s", c == a->choices ? "" : "|", *c);
        } else if (a->kind == AXIS_SIZE2) {
            dm_str_cat(&v, "WxH");
        } else {
            dm_str_printf(&v, "%s %g..%g", a->kind == AXIS_INT ? "int" : "real", a->min, a->max);
        }
        printf("%-18s %-6s default %-10s %s\n", a->name, a->scene ? "scene" : "", a->def,
               dm_str_get(&v));
        dm_str_free(&v);
    }
    return DM_EXIT_OK;
}

/* Counters as JSON: metadata, availability and what they count here. */
static void list__counters_json(counters_context *cc)
{
    cJSON *arr = cJSON_CreateArray();
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *c = counters_info_at(i);
        const char *why = NULL;
        int avail = cc ? counters_available(cc, c->name, &why) : 0;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", c->name);
        cJSON_AddStringToObject(o, "group", c->group);
        cJSON_AddStringToObject(o, "unit", counters_unit_name(c->unit));
        cJSON_AddBoolToObject(o, "deterministic", c->deterministic);
        cJSON_AddBoolToObject(o, "available", avail);
        if (!avail)
            cJSON_AddStringToObject(o, "unavailable", why ? why : "no GL context");
        cJSON_AddStringToObject(o, "description", cc ? counters_driver_note(cc, c->name) : c->description);
        if (c->formula)
            cJSON_AddStringToObject(o, "formula", c->formula);
        cJSON_AddItemToArray(arr, o);
    }
    list__print_json(arr);
}

static void list__counters_text(counters_context *cc)
{
    printf("%-26s %-17s %-7s %-5s %-11s %s\n", "counter", "group", "unit", "det", "available", "description");
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *c = counters_info_at(i);
        const char *why = NULL;
        int avail = cc ? counters_available(cc, c->name, &why) : 0;
        printf("%-26s %-17s %-7s %-5s %-11s %s\n", c->name, c->group, counters_unit_name(c->unit),
               c->deterministic ? "yes" : "no", avail ? "yes" : "no",
               cc ? counters_driver_note(cc, c->name) : c->description);
        if (!avail && why)
            printf("%-26s   unavailable: %s\n", "", why);
    }
}

/* The render passes a selection of counters needs (names checked by
 * list__passes); exit 2 without a GL context. */
static int list__plan(counters_context *cc, const char *passes)
{
    char *copy = dm_xstrdup(passes), *save = NULL;
    const char *names[64];
    size_t n = 0;
    for (char *t = strtok_r(copy, ",", &save); t && n < 64; t = strtok_r(NULL, ",", &save))
        names[n++] = t;
    dm_str out = {0};
    int rc = cc ? counters_plan_describe(cc, names, n, &out) : -1;
    if (rc == 0)
        fputs(dm_str_get(&out), stdout);
    else
        fprintf(stderr, "dmbench: error: %s\n", out.len ? dm_str_get(&out) : "no GL context");
    dm_str_free(&out);
    free(copy);
    return rc == 0 ? DM_EXIT_OK : DM_EXIT_USAGE;
}

/* Lists counters with their availability on the current driver. */
static int list__counters(const char *passes, int json)
{
    gl_context *gl = NULL;
    counters_context *cc = NULL;
    dm_str err = {0};
    int rc = DM_EXIT_OK;
    if (gl_context_create(NULL, &gl, &err) == 0)
        counters_context_create(&cc);
    if (passes)
        rc = list__plan(cc, passes);
    else if (json)
        list__counters_json(cc);
    else
        list__counters_text(cc);
    dm_str_free(&err);
    counters_context_destroy(cc);
    gl_context_destroy(gl);
    return rc;
}

static int list__names(const char *const *names, int json)
{
    if (json)
        return list__print_json(list__strings(names));
    for (const char *const *n = names; *n; n++)
        printf("%s\n", *n);
    return DM_EXIT_OK;
}

/* The built-in cost models of models/catalog.c. */
static int list__models(int json)
{
    cJSON *arr = json ? cJSON_CreateArray() : NULL;
    int w = 0;   /* the longest name */
    for (size_t i = 0; i < models_builtin_count(); i++)
        w = (int)strlen(models_builtin_at(i)->name) > w ? (int)strlen(models_builtin_at(i)->name) : w;
    for (size_t i = 0; i < models_builtin_count(); i++) {
        const models_builtin *m = models_builtin_at(i);
        if (!json) {
            printf("%-*s %s = %s\n%-*s %s\n", w, m->name, m->response, m->formula, w, "", m->description);
            continue;
        }
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", m->name);
        cJSON_AddStringToObject(o, "response", m->response);
        cJSON_AddStringToObject(o, "formula", m->formula);
        cJSON_AddStringToObject(o, "description", m->description);
        cJSON_AddItemToArray(arr, o);
    }
    if (json)
        return list__print_json(arr);
    printf("(or any formula: dmbench fit --formula \"a + b*tess_level^p\")\n");
    return DM_EXIT_OK;
}

/* The sweep-file keys of sweep/sweep.c's key table: the Markdown key
 * reference of docs/sweep-files.md, or a JSON array of the rows. */
static cJSON *list__key_json(size_t i)
{
    const sweep_key *k = sweep_keys_at(i);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "section", k->section);
    cJSON_AddStringToObject(o, "key", k->name);
    cJSON_AddStringToObject(o, "value", k->type);
    cJSON_AddStringToObject(o, "default", k->deflt);
    cJSON_AddStringToObject(o, "meaning", k->doc);
    if (k->example)
        cJSON_AddStringToObject(o, "example", k->example);
    return o;
}

static int list__keys(int json)
{
    if (json)
        return list__json(sweep_keys_count(), list__key_json);
    dm_str md = {0};
    sweep_keys_markdown(&md);
    fputs(dm_str_get(&md), stdout);
    dm_str_free(&md);
    return DM_EXIT_OK;
}

const char *const cli_list_lists[] = { "techniques", "axes", "counters", "meshes", "textures",
                                          "models", "keys", NULL };
#define LIST__N (sizeof cli_list_lists / sizeof *cli_list_lists - 1)

typedef struct list_args {
    const char *passes;
    int json;
} list_args;

/* --passes A,B,...: every name must be a counter of the registry. */
static int list__passes(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    char *copy = dm_xstrdup(v), *save = NULL;
    int rc = 0;
    for (char *t = strtok_r(copy, ",", &save); t && !rc; t = strtok_r(NULL, ",", &save)) {
        if (counters_find(t))
            continue;
        const char **all = dm_xmalloc(counters_count() * sizeof *all);
        for (size_t i = 0; i < counters_count(); i++)
            all[i] = counters_info_at(i)->name;
        dm_str_printf(err, "--%s: unknown counter '%s'", opt->name, t);
        dm_str_suggest(err, t, all, counters_count(), "counters");
        free(all);
        rc = DM_ERR_UNKNOWN;
    }
    free(copy);
    ((list_args *)args)->passes = v;
    return rc;
}

const cli_option cli_list_options[] = {
    { .name = "passes", .kind = CLI_OPT_STRING, .value_name = "A,B,...", .parse = list__passes,
      .help = "list counters: how many render passes this selection of counters needs" },
    CLI_BOOL("json", list_args, json, "print the list as a JSON array"),
    CLI_OPT_END
};

/* `list WHAT FILE.glsl...`: the user techniques named after the list are
 * loaded, so they and their parameters are listed; -1, or an exit code. */
static int list__user_techniques(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (!user_technique_is_path(argv[i]))
            return cli_usage_error("list: one list at a time ('%s' and '%s')", argv[0], argv[i]);
        dm_str err = {0};
        int rc = user_technique_load(argv[i], NULL, &err) ? cli_usage_error("list: %s", dm_str_get(&err)) : -1;
        dm_str_free(&err);
        if (rc >= 0)
            return rc;
    }
    return -1;
}

/* `dmbench list WHAT`: one registry's list as text or JSON. */
int cli_list(const cli_command *self, int argc, char **argv)
{
    list_args args = {0}, *a = &args;
    int rc = cli_parse(self, argc, argv, a, &argc);
    if (rc < 0 && argc == 0) {
        dm_str msg = {0};
        dm_str_cat(&msg, "list: which list? ");
        dm_str_expected(&msg, NULL, cli_list_lists, LIST__N);
        rc = cli_usage_error("%s", dm_str_get(&msg));
        dm_str_free(&msg);
    }
    if (rc < 0 && argc > 1)
        rc = list__user_techniques(argc, argv);
    if (rc >= 0)
        return rc;
    const char *w = argv[0];
    if (a->passes && strcmp(w, "counters") != 0)
        return cli_usage_error("list: --passes applies to 'list counters' only");
    if (strcmp(w, "techniques") == 0)
        return a->json ? list__json(technique_count(), list__technique_json) : list__techniques();
    if (strcmp(w, "axes") == 0)
        return a->json ? list__json(axes_count(), list__axis_json) : list__axes();
    if (strcmp(w, "counters") == 0)
        return list__counters(a->passes, a->json);
    if (strcmp(w, "meshes") == 0)
        return list__names(mesh_names(), a->json);
    if (strcmp(w, "textures") == 0)
        return list__names(maps_names(), a->json);
    if (strcmp(w, "models") == 0)
        return list__models(a->json);
    if (strcmp(w, "keys") == 0)
        return list__keys(a->json);
    dm_str msg = {0};
    dm_str_printf(&msg, "list: unknown list '%s'", w);
    dm_str_suggest(&msg, w, cli_list_lists, LIST__N, "lists");
    rc = cli_usage_error("%s", dm_str_get(&msg));
    dm_str_free(&msg);
    return rc;
}
