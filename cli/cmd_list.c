/* cli_list.c — `dmbench list techniques|axes|counters|meshes|textures|models`. */
#include "cli.h"
#include "core/dm_util.h"
#include "counters/counters.h"
#include "run/gl_context.h"
#include "techniques/axes.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/technique.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int list__techniques(void)
{
    for (size_t i = 0; i < technique_count(); i++) {
        const technique_desc *t = technique_at(i);
        if (t->test_only)
            continue;
        printf("%-20s %s\n", t->name, t->summary ? t->summary : "");
        dm_str axes = {0};
        for (const char *const *a = t->axes; a && *a; a++)
            dm_str_printf(&axes, "%s%s", a == t->axes ? "" : ", ", *a);
        printf("%-20s reads: scene axes%s%s%s\n", "", axes.len ? ", " : "", dm_str_get(&axes),
               t->requires_ext ? "" : "");
        if (t->requires_ext)
            printf("%-20s needs: %s\n", "", t->requires_ext);
        dm_str_free(&axes);
    }
    return 0;
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
    return 0;
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
    char *text = cJSON_Print(arr);
    puts(text);
    free(text);
    cJSON_Delete(arr);
}

/* Lists counters with their availability on the current driver. */
static int list__counters(const char *passes, int json)
{
    gl_context *gl = NULL;
    counters_context *cc = NULL;
    dm_str err = {0};
    if (gl_context_create(NULL, &gl, &err) == 0)
        counters_context_create(&cc);
    if (passes) {
        char *copy = dm_xstrdup(passes);
        const char *names[64];
        size_t n = 0;
        char *save = NULL;
        for (char *t = strtok_r(copy, ",", &save); t && n < 64; t = strtok_r(NULL, ",", &save)) {
            names[n++] = t;
            if (counters_find(t))
                continue;
            const char **all = dm_xmalloc(counters_count() * sizeof *all);
            for (size_t i = 0; i < counters_count(); i++)
                all[i] = counters_info_at(i)->name;
            const char *close = dm_closest(t, all, counters_count());
            dm_str msg = {0};
            dm_str_printf(&msg, "list: --passes: unknown counter '%s'", t);
            if (close)
                dm_str_printf(&msg, "; did you mean '%s'?", close);
            dm_str_cat(&msg, " valid counters: ");
            dm_str_cat_list(&msg, all, counters_count());
            int rc = cli__usage_error("%s", dm_str_get(&msg));
            dm_str_free(&msg);
            free(all);
            free(copy);
            counters_context_destroy(cc);
            gl_context_destroy(gl);
            return rc;
        }
        dm_str out = {0};
        int rc = cc ? counters_plan_describe(cc, names, n, &out) : -1;
        if (rc == 0)
            fputs(dm_str_get(&out), stdout);
        else
            fprintf(stderr, "dmbench: error: %s\n", out.len ? dm_str_get(&out) : "no GL context");
        dm_str_free(&out);
        free(copy);
        counters_context_destroy(cc);
        gl_context_destroy(gl);
        return rc == 0 ? 0 : 2;
    }
    if (json) {
        list__counters_json(cc);
        dm_str_free(&err);
        counters_context_destroy(cc);
        gl_context_destroy(gl);
        return 0;
    }
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
    dm_str_free(&err);
    counters_context_destroy(cc);
    gl_context_destroy(gl);
    return 0;
}

static int list__names(const char *const *names)
{
    for (const char *const *n = names; *n; n++)
        printf("%s\n", *n);
    return 0;
}

int cli_list(int argc, char **argv)
{
    static const char *const what[] = { "techniques", "axes", "counters", "meshes", "textures", "models" };
    static const char *const models[] = {
        "pipeline-linear   WallTime = c0 + sum c_k*counter_k (VS, TES, clipped primitives, samples), c_k >= 0",
        "tess-power        a + b*tess_level^p",
        "resolution-linear a + b*SamplesPassed",
        "(or any formula: --formula \"a + b*tess_level^p\")", NULL };
    const char *passes = NULL;
    int json = 0;
    if (argc < 2)
        return cli__usage_error("usage: dmbench list techniques|axes|counters|meshes|textures|models");
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--passes") == 0 && strcmp(argv[1], "counters") == 0) {
            if (!(passes = cli__value(argc, argv, &i)))
                return 2;
        } else if (strcmp(argv[i], "--json") == 0 && strcmp(argv[1], "counters") == 0) {
            json = 1;
        } else {
            static const char *const valid[] = { "--passes", "--json" };
            return cli__unknown_option("list", argv[i], valid, 2);
        }
    }
    const char *w = argv[1];
    if (strcmp(w, "techniques") == 0)
        return list__techniques();
    if (strcmp(w, "axes") == 0)
        return list__axes();
    if (strcmp(w, "counters") == 0)
        return list__counters(passes, json);
    if (strcmp(w, "meshes") == 0)
        return list__names(mesh_names());
    if (strcmp(w, "textures") == 0)
        return list__names(maps_names());
    if (strcmp(w, "models") == 0)
        return list__names(models);
    const char *close = dm_closest(w, what, 6);
    return cli__usage_error("list: unknown list '%s'%s%s%s; valid: techniques, axes, counters, meshes, "
                            "textures, models", w, close ? "; did you mean '" : "", close ? close : "",
                            close ? "'?" : "");
}
