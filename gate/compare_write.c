/* compare_write.c — the regression gate's outputs: terminal table, Markdown,
 * JUnit XML and JSON (see compare.h). */
#include "gate/compare.h"
#include "reports/report.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

/* The ratio and q columns of an item, as the text, Markdown and JUnit
 * outputs print them. */
typedef struct compare__cells {
    char ratio[64];   /* "1.012 [0.998, 1.025]", "1.00004 (instructions)" or "-" */
    char q[16];       /* the q-value, "-" when the item is not timed */
} compare__cells;

static compare__cells compare__item_cells(const compare_item *it)
{
    compare__cells c = { .q = "-" };
    if (it->instr)
        snprintf(c.ratio, sizeof c.ratio, "%.5f (instructions)", it->instr_new / it->instr_base);
    else if (it->timed)
        snprintf(c.ratio, sizeof c.ratio, "%.3f [%.3f, %.3f]", it->ratio, it->lo, it->hi);
    else
        snprintf(c.ratio, sizeof c.ratio, "-");
    if (it->timed)
        snprintf(c.q, sizeof c.q, "%.2g", it->q);
    return c;
}

static void compare__summary(const compare_result *r, dm_str *s)
{
    dm_str_printf(s, "%zu configuration%s: %zu REGRESSION, %zu INCONCLUSIVE, %zu IMPROVEMENT, "
                  "%zu PASS, %zu SKIPPED; %zu added, %zu removed",
                  r->n_items, r->n_items == 1 ? "" : "s", r->count[COMPARE_REGRESSION],
                  r->count[COMPARE_INCONCLUSIVE], r->count[COMPARE_IMPROVEMENT],
                  r->count[COMPARE_PASS], r->count[COMPARE_SKIPPED], r->n_added, r->n_removed);
    if (r->n_geomean)
        dm_str_printf(s, "; suite geometric-mean %s ratio %.4f over %zu", r->desc.time_counter,
                      r->geomean, r->n_geomean);
}

static void compare__text_list(FILE *f, const char *title, char **list, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char *b;
        fprintf(f, "%s: %s\n", title, dm_term_safe(list[i], &b));
        free(b);
    }
}

void compare_write_text(const compare_result *r, FILE *f)
{
    char *b1, *b2, *b3;
    fprintf(f, "compare BASE %s -> NEW %s (%s; instructions threshold %.2g%%, time threshold %.1f%%, alpha %.3g%s)\n",
            dm_term_safe(r->base_id ? r->base_id : "?", &b1),
            dm_term_safe(r->new_id ? r->new_id : "?", &b2),
            dm_term_safe(r->sweep ? r->sweep : "?", &b3),
            r->desc.threshold * 100, r->desc.time_threshold * 100, r->desc.alpha,
            r->desc.counters_only ? ", counters only" : "");
    free(b1);
    free(b2);
    free(b3);
    fprintf(f, "%-12s  %-26s  %-8s  %-16s  %s\n", "verdict", "ratio [95% CI]", "q", "key",
            "configuration / note");
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        compare__cells cell = compare__item_cells(it);
        char *b1, *b2;
        fprintf(f, "%-12s  %-26s  %-8s  %-16s  %s%s%s\n", compare_verdict_name(it->verdict),
                cell.ratio, cell.q, it->key, dm_term_safe(it->label, &b1), it->note ? " — " : "",
                it->note ? dm_term_safe(it->note, &b2) : (b2 = NULL, ""));
        free(b1);
        free(b2);
    }
    compare__text_list(f, "added", r->added, r->n_added);
    compare__text_list(f, "removed", r->removed, r->n_removed);
    compare__text_list(f, "environment", r->env_diffs, r->n_env_diffs);
    compare__text_list(f, "warning", r->warnings, r->n_warnings);
    dm_str s = {0};
    compare__summary(r, &s);
    fprintf(f, "%s\n", dm_str_get(&s));
    dm_str_free(&s);
}

static int compare__write(dm_str *s, const char *path)
{
    int rc = dm_write_file(path, dm_str_get(s), s->len) == 0 ? 0 : DM_ERR_IO;
    dm_str_free(s);
    return rc;
}

/* Markdown table cell text: plain text only (a PR comment must not get raw
 * HTML from a sweep name or a map path; see dm_str_cat_md). */
static void compare__md_cell(dm_str *s, const char *text)
{
    dm_str_cat_md(s, text);
}

int compare_write_markdown(const compare_result *r, const char *path)
{
    dm_str s = {0};
    dm_str_cat(&s, "## dmbench compare: ");
    compare__md_cell(&s, r->base_id ? r->base_id : "?");
    dm_str_cat(&s, " → ");
    compare__md_cell(&s, r->new_id ? r->new_id : "?");
    dm_str_cat(&s, "\n\n");
    compare__summary(r, &s);
    dm_str_cat(&s, "\n\n| Verdict | Configuration | Key | Ratio [95% CI] | q | Note |\n"
                   "|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        compare__cells cell = compare__item_cells(it);
        dm_str_printf(&s, "| %s | ", compare_verdict_name(it->verdict));
        compare__md_cell(&s, it->label);
        dm_str_cat(&s, " | `");
        compare__md_cell(&s, it->key);
        dm_str_printf(&s, "` | %s | %s | ", cell.ratio, cell.q);
        compare__md_cell(&s, it->note);
        dm_str_cat(&s, " |\n");
    }
    for (size_t i = 0; i < r->n_added; i++) {
        dm_str_printf(&s, "%s- added: ", i ? "" : "\n");
        compare__md_cell(&s, r->added[i]);
        dm_str_cat(&s, "\n");
    }
    for (size_t i = 0; i < r->n_removed; i++) {
        dm_str_printf(&s, "%s- removed: ", i || r->n_added ? "" : "\n");
        compare__md_cell(&s, r->removed[i]);
        dm_str_cat(&s, "\n");
    }
    for (size_t i = 0; i < r->n_warnings; i++) {
        dm_str_cat(&s, "\n> warning: ");
        compare__md_cell(&s, r->warnings[i]);
        dm_str_cat(&s, "\n");
    }
    return compare__write(&s, path);
}

int compare_write_junit(const compare_result *r, const char *path)
{
    dm_str s = {0};
    size_t skipped = r->count[COMPARE_INCONCLUSIVE] + r->count[COMPARE_SKIPPED];
    dm_str_cat(&s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"");
    dm_str_cat_html(&s, r->sweep ? r->sweep : "dmbench");
    dm_str_printf(&s, "\" tests=\"%zu\" failures=\"%zu\" errors=\"0\" skipped=\"%zu\">\n",
                  r->n_items, r->count[COMPARE_REGRESSION], skipped);
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        compare__cells cell = compare__item_cells(it);
        dm_str_cat(&s, "  <testcase classname=\"dmbench.compare\" name=\"");
        dm_str_cat_html(&s, it->label);
        dm_str_printf(&s, " [%s]\" time=\"%.9f\">\n", it->key, it->median_new / 1e9);
        const char *tag = it->verdict == COMPARE_REGRESSION ? "failure"
                          : it->verdict == COMPARE_INCONCLUSIVE || it->verdict == COMPARE_SKIPPED
                              ? "skipped" : NULL;
        if (tag) {
            dm_str_printf(&s, "    <%s message=\"%s: ", tag, compare_verdict_name(it->verdict));
            dm_str_cat_html(&s, it->note ? it->note : "");
            dm_str_printf(&s, "\"/>\n");
        }
        dm_str_printf(&s, "    <system-out>verdict=%s ratio=%s", compare_verdict_name(it->verdict), cell.ratio);
        if (it->median_new > 0)
            dm_str_printf(&s, " median_ms=%.6g", it->median_new / 1e6);
        if (it->note) {
            dm_str_cat(&s, " note=");
            dm_str_cat_html(&s, it->note);
        }
        dm_str_cat(&s, "</system-out>\n  </testcase>\n");
    }
    dm_str_cat(&s, "</testsuite>\n</testsuites>\n");
    return compare__write(&s, path);
}

/* A number, or null when not finite (JSON has no NaN/Inf). */
static void compare__json_num(cJSON *o, const char *name, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, name, v);
    else
        cJSON_AddNullToObject(o, name);
}

/* A value of BASE and NEW as the members PREFIXbase and PREFIXnew. */
static void compare__json_base_new(cJSON *o, const char *prefix, double base, double new_)
{
    char name[32];
    snprintf(name, sizeof name, "%sbase", prefix);
    compare__json_num(o, name, base);
    snprintf(name, sizeof name, "%snew", prefix);
    compare__json_num(o, name, new_);
}

static cJSON *compare__json_list(char **list, size_t n)
{
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++)
        cJSON_AddItemToArray(a, cJSON_CreateString(list[i]));
    return a;
}

static cJSON *compare__json_item(const compare_item *it)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "key", it->key);
    cJSON_AddStringToObject(o, "configuration", it->label);
    cJSON_AddStringToObject(o, "verdict", compare_verdict_name(it->verdict));
    if (it->note)
        cJSON_AddStringToObject(o, "note", it->note);
    else
        cJSON_AddNullToObject(o, "note");
    if (it->timed) {
        compare__json_num(o, "ratio", it->ratio);
        cJSON *ci = cJSON_AddArrayToObject(o, "ci95");
        cJSON_AddItemToArray(ci, isfinite(it->lo) ? cJSON_CreateNumber(it->lo) : cJSON_CreateNull());
        cJSON_AddItemToArray(ci, isfinite(it->hi) ? cJSON_CreateNumber(it->hi) : cJSON_CreateNull());
        compare__json_num(o, "p", it->p);
        compare__json_num(o, "q", it->q);
        cJSON_AddNumberToObject(o, "n_base", (double)it->n_base);
        cJSON_AddNumberToObject(o, "n_new", (double)it->n_new);
        compare__json_num(o, "detectable", it->detectable);
    }
    if (it->instr) {
        cJSON_AddNumberToObject(o, "instructions_base", it->instr_base);
        cJSON_AddNumberToObject(o, "instructions_new", it->instr_new);
        cJSON_AddNumberToObject(o, "instructions_ratio", it->instr_new / it->instr_base);
    }
    if (it->verdict == COMPARE_INCONCLUSIVE)
        cJSON_AddNumberToObject(o, "extra_samples", (double)it->extra_samples);
    cJSON *ch = cJSON_AddArrayToObject(o, "changes");
    for (size_t k = 0; k < it->n_changes; k++) {
        cJSON *c = cJSON_CreateObject();
        cJSON_AddStringToObject(c, "counter", it->changes[k].counter);
        compare__json_base_new(c, "", it->changes[k].base, it->changes[k].new_);
        if (it->changes[k].note)
            cJSON_AddStringToObject(c, "note", it->changes[k].note);
        cJSON_AddItemToArray(ch, c);
    }
    if (it->quality) {
        cJSON *q = cJSON_AddObjectToObject(o, "quality");
        compare__json_base_new(q, "PSNR_", it->psnr_base, it->psnr_new);
        compare__json_base_new(q, "SSIM_", it->ssim_base, it->ssim_new);
        compare__json_base_new(q, "FLIP_", it->flip_base, it->flip_new);
    }
    return o;
}

int compare_write_json(const compare_result *r, const char *path)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "base", r->base_id ? r->base_id : "");
    cJSON_AddStringToObject(root, "new", r->new_id ? r->new_id : "");
    cJSON *set = cJSON_AddObjectToObject(root, "settings");
    cJSON_AddNumberToObject(set, "time_threshold", r->desc.time_threshold);
    cJSON_AddNumberToObject(set, "threshold", r->desc.threshold);
    cJSON_AddNumberToObject(set, "alpha", r->desc.alpha);
    cJSON_AddNumberToObject(set, "level", r->desc.level);
    cJSON_AddNumberToObject(set, "psnr_drop", r->desc.psnr_drop);
    cJSON_AddNumberToObject(set, "ssim_drop", r->desc.ssim_drop);
    cJSON_AddNumberToObject(set, "flip_rise", r->desc.flip_rise);
    cJSON_AddStringToObject(set, "time_counter", r->desc.time_counter);
    cJSON_AddBoolToObject(set, "counters_only", r->desc.counters_only);
    cJSON *sum = cJSON_AddObjectToObject(root, "summary");
    for (int v = COMPARE_PASS; v <= COMPARE_REGRESSION; v++)
        cJSON_AddNumberToObject(sum, compare_verdict_name((compare_verdict)v), (double)r->count[v]);
    compare__json_num(sum, "geomean_ratio", r->geomean);
    cJSON_AddNumberToObject(sum, "exit_code", compare_exit_code(r));
    cJSON *items = cJSON_AddArrayToObject(root, "configs");
    for (size_t i = 0; i < r->n_items; i++)
        cJSON_AddItemToArray(items, compare__json_item(&r->items[i]));
    cJSON_AddItemToObject(root, "added", compare__json_list(r->added, r->n_added));
    cJSON_AddItemToObject(root, "removed", compare__json_list(r->removed, r->n_removed));
    cJSON_AddItemToObject(root, "environment_differences", compare__json_list(r->env_diffs, r->n_env_diffs));
    cJSON_AddItemToObject(root, "warnings", compare__json_list(r->warnings, r->n_warnings));
    int rc = report_write_cjson(root, path);
    cJSON_Delete(root);
    return rc;
}
