/* published_report.c — published figures beside measured ones (see
 * published_report.h). */
#include "reports/published_report.h"
#include "reports/report_internal.h"
#include "core/dm_error.h"
#include "core/dm_util.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

double report_pub_time_ratio(int is_fps, double value, double base)
{
    return is_fps ? base / value : value / base;
}

int report_pub_direction(double ratio)
{
    return ratio > 1 + REPORT_PUB_SAME_BAND ? 1 : ratio < 1 - REPORT_PUB_SAME_BAND ? -1 : 0;
}

report_pub_verdict report_pub_judge(double published_ratio, double measured_ratio)
{
    report_pub_verdict v;
    v.direction_agrees = report_pub_direction(published_ratio) == report_pub_direction(measured_ratio);
    v.factor = published_ratio > measured_ratio ? published_ratio / measured_ratio
                                                : measured_ratio / published_ratio;
    v.size_agrees = v.factor <= REPORT_PUB_SIZE_FACTOR;
    return v;
}

#define PUB__COLS 6

/* The table as text cells; header first.  n_rows/agree count data rows. */
typedef struct pub_table {
    char *title;             /* "study — table (gpu), unit" */
    char *(*cells)[PUB__COLS];
    size_t n_rows;
    size_t n_judged, n_agree;
} pub_table;

static const char *pub__str(const cJSON *o, const char *name)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, name);
    return cJSON_IsString(it) ? it->valuestring : NULL;
}

/* Median frame time (ns) of the ok configuration with this key; NaN with
 * *why set when it has none. */
static double pub__measured(const dm_run_result *run, const char *key, const char **why)
{
    for (size_t i = 0; key && i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (strcmp(c->key, key) != 0)
            continue;
        const dm_counter_result *t = c->ok ? report__frame_time(c) : NULL;
        *why = c->ok ? "no frame time" : "failed";
        return t && t->median > 0 ? t->median : NAN;
    }
    *why = "not measured (left out or in another shard)";
    return NAN;
}

/* The verdict cell of one row; counts it. */
static char *pub__verdict(pub_table *t, double pr, double mr, const char *why)
{
    if (!isfinite(mr))
        return dm_xasprintf("no comparison: %s", why);
    report_pub_verdict v = report_pub_judge(pr, mr);
    t->n_judged++;
    t->n_agree += v.direction_agrees && v.size_agrees;
    if (v.direction_agrees && v.size_agrees)
        return dm_xasprintf("agrees (within ×%.2f)", v.factor);
    return dm_xasprintf("%s%s%s (×%.2f apart)", v.direction_agrees ? "" : "direction differs",
                        v.direction_agrees || v.size_agrees ? "" : ", ",
                        v.size_agrees ? "" : "size differs", v.factor);
}

/* One data row from a values[] entry. */
static void pub__row(pub_table *t, const dm_run_result *run, const cJSON *e, int fps,
                     double pub_base, double meas_base, const char *unit, int is_base)
{
    const cJSON *val = cJSON_GetObjectItemCaseSensitive(e, "value");
    double pv = cJSON_IsNumber(val) ? val->valuedouble : NAN;
    const char *why = "", *label = pub__str(e, "label");
    double mv = pub__measured(run, pub__str(e, "key"), &why);
    double pr = report_pub_time_ratio(fps, pv, pub_base), mr = mv / meas_base;
    if (!isfinite(meas_base) && isfinite(mv))
        why = "the baseline has no frame time";
    char **row = t->cells[t->n_rows++];
    row[0] = dm_xasprintf("%s%s", label ? label : "?", is_base ? " (baseline)" : "");
    row[1] = dm_xasprintf("%.4g %s", pv, unit);
    row[2] = dm_xasprintf("%.3f", pr);
    row[3] = isfinite(mv) ? dm_xasprintf("%.3f ms", mv / 1e6) : dm_xstrdup("—");
    row[4] = isfinite(mr) ? dm_xasprintf("%.3f", mr) : dm_xstrdup("—");
    row[5] = is_base ? dm_xstrdup("baseline") : pub__verdict(t, pr, mr, why);
}

/* Builds the table from the parsed published.json; DM_ERR_PARSE when it is
 * not the shape published_write_json writes. */
static int pub__table(pub_table *t, const dm_run_result *run, const cJSON *root)
{
    const cJSON *vals = cJSON_GetObjectItemCaseSensitive(root, "values");
    const cJSON *src = cJSON_GetObjectItemCaseSensitive(root, "source");
    const char *unit = pub__str(root, "unit"), *base = pub__str(root, "baseline");
    if (!cJSON_IsArray(vals) || !unit || !base || !pub__str(src, "study"))
        return DM_ERR_PARSE;
    const cJSON *be = NULL, *e;
    cJSON_ArrayForEach(e, vals)
        if (pub__str(e, "label") && strcmp(pub__str(e, "label"), base) == 0)
            be = e;
    const cJSON *bv = cJSON_GetObjectItemCaseSensitive(be, "value");
    if (!cJSON_IsNumber(bv) || bv->valuedouble <= 0)
        return DM_ERR_PARSE;
    const char *why, *gpu = pub__str(src, "gpu");
    double meas_base = pub__measured(run, pub__str(be, "key"), &why);
    t->title = dm_xasprintf("%s — %s%s%s%s; published in %s", pub__str(src, "study"),
                            pub__str(src, "table") ? pub__str(src, "table") : "?", gpu ? " (" : "",
                            gpu ? gpu : "", gpu ? ")" : "", unit);
    t->cells = dm_xcalloc((size_t)cJSON_GetArraySize(vals) + 1, sizeof *t->cells);
    cJSON_ArrayForEach(e, vals)
        pub__row(t, run, e, strcmp(unit, "fps") == 0, bv->valuedouble, meas_base, unit, e == be);
    return 0;
}

static void pub__table_free(pub_table *t)
{
    for (size_t i = 0; i < t->n_rows; i++)
        for (int k = 0; k < PUB__COLS; k++)
            free(t->cells[i][k]);
    free(t->cells);
    free(t->title);
}

static const char *const pub__head[PUB__COLS] = {
    "configuration", "published", "published ratio", "measured (median)", "measured ratio", "verdict"
};

static const char pub__rule[] =
    "Ratios are frame time over the baseline's (a frame rate is inverted). A row agrees when the "
    "direction agrees (both slower than the baseline by more than 5 %, both faster by more than "
    "5 %, or both within ±5 %) and the two ratios are within a factor of 2 of each other.";

/* Writes the table as Markdown or HTML. */
static void pub__emit(dm_str *s, const pub_table *t, int html)
{
    void (*cat)(dm_str *, const char *) = html ? dm_str_cat_html : dm_str_cat_md;
    dm_str_cat(s, html ? "<h2 id=\"published\">Published figures beside ours</h2>\n<p>"
                       : "\n## Published figures beside ours\n\n");
    cat(s, t->title);
    dm_str_cat(s, html ? "</p>\n<p>" : "\n\n");
    cat(s, pub__rule);
    dm_str_printf(s, " %zu of %zu compared rows agree.%s", t->n_agree, t->n_judged,
                  html ? "</p>\n<table>\n" : "\n\n");
    for (size_t r = 0; r <= t->n_rows; r++) {
        dm_str_cat(s, html ? "<tr>" : "|");
        for (int k = 0; k < PUB__COLS; k++) {
            dm_str_cat(s, html ? (r ? (k && k < 5 ? "<td class=\"n\">" : "<td>") : "<th>") : " ");
            cat(s, r ? t->cells[r - 1][k] : pub__head[k]);
            dm_str_cat(s, html ? (r ? "</td>" : "</th>") : " |");
        }
        dm_str_cat(s, html ? "</tr>\n" : "\n");
        if (!html && r == 0)
            dm_str_cat(s, "|---|---:|---:|---:|---:|---|\n");
    }
    dm_str_cat(s, html ? "</table>\n" : "");
}

/* The section of one published.json into md (Markdown) and html (either
 * may be NULL), the file read once; nothing when it is absent. */
void report_published_sections(const dm_run_result *run, const char *path, dm_str *md,
                               dm_str *html)
{
    char *text = NULL;
    size_t len = 0;
    if (dm_input_file(path, NULL, 0) != 0 || dm_read_file(path, &text, &len) != 0)
        return;
    cJSON *root = cJSON_ParseWithLength(text, len);
    pub_table t = {0};
    int ok = pub__table(&t, run, root) == 0;
    dm_str *out[2] = {md, html};
    for (int h = 0; h < 2; h++) {
        dm_str *s = out[h];
        if (!s)
            continue;
        if (ok) {
            pub__emit(s, &t, h);
            continue;
        }
        dm_str_cat(s, h ? "<h2 id=\"published\">Published figures beside ours</h2>\n<p>" : "\n## Published figures beside ours\n\n");
        (h ? dm_str_cat_html : dm_str_cat_md)(s, path);
        dm_str_cat(s, h ? ": not a published.json this version writes</p>\n" : ": not a published.json this version writes\n");
    }
    pub__table_free(&t);
    cJSON_Delete(root);
    free(text);
}

char *report_published_path(const char *dir, const char *beside)
{
    const char *slash = beside ? strrchr(beside, '/') : NULL;
    return dir ? dm_xasprintf("%s/published.json", dir)
         : slash ? dm_xasprintf("%.*s/published.json", (int)(slash - beside), beside)
                 : dm_xstrdup("published.json");
}

void report_published_section(dm_str *s, const dm_run_result *run, const char *dir,
                              const char *beside, int html)
{
    char *path = report_published_path(dir, beside);
    report_published_sections(run, path, html ? NULL : s, html ? s : NULL);
    free(path);
}

int report_published_copy(const char *dir, const char *out, char *err, size_t errlen)
{
    char *from = dm_xasprintf("%s/published.json", dir), *to = dm_xasprintf("%s/published.json", out);
    int rc = 0;
    if (strcmp(dir, out) != 0 && dm_file_exists(from))
        rc = report__copy_file(from, to, err, errlen);
    free(from);
    free(to);
    return rc;
}
