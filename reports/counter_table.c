/* counter_table.c — the counters of a scene as a table (see answer.h),
 * from the report model: the scene's rows and counter names are its. */
#include "reports/answer.h"

#include "core/dm_table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A counter's value as shown: counts (items, bytes, or any value from 1 000
 * up) in plain grouped digits, ratios to four significant digits. */
static void table__value(const dm_counter_result *k, dm_str *out)
{
    if (!k) {
        dm_str_cat(out, "–");
        return;
    }
    if (!k->available || k->unreadable || !isfinite(k->value)) {
        dm_str_cat(out, "unavailable");
        return;
    }
    int count = (k->unit && (strcmp(k->unit, "items") == 0 || strcmp(k->unit, "bytes") == 0)) ||
                fabs(k->value) >= 1000 || k->value == round(k->value);
    if (count)
        dm_str_cat_count(out, k->value);
    else
        dm_str_printf(out, "%.4g", k->value);
}

/* The table's cells: header (configuration, then each counter of the
 * scene), a row per ok configuration of the scene, fastest first. */
static void table__build(const report_model *m, const report_model_scene *sc, dm_table *t)
{
    dm_table_row(t);
    dm_table_cell(t, "configuration");
    for (size_t k = 0; k < sc->n_det; k++)
        dm_table_cell(t, sc->det[k]);
    for (size_t i = 0; i < sc->n_rows; i++) {
        const report_model_row *r = &m->rows[sc->rows[i]];
        dm_table_row(t);
        dm_table_cell(t, r->label);
        for (size_t k = 0; k < sc->n_det; k++) {
            dm_str v = {0};
            table__value(dm_config_counter(r->config, sc->det[k]), &v);
            dm_table_cell(t, dm_str_get(&v));
            dm_str_free(&v);
        }
    }
}

/* Markdown: a pipe table, cells escaped. */
static void table__md(const dm_table *t, dm_str *out)
{
    for (size_t r = 0; r < t->n_rows; r++) {
        for (size_t c = 0; c < t->n_cells[r]; c++) {
            dm_str_cat(out, "| ");
            dm_str_cat_md(out, t->rows[r][c]);
            dm_str_cat(out, " ");
        }
        dm_str_cat(out, "|\n");
        if (r == 0) {
            for (size_t c = 0; c < t->n_cells[0]; c++)
                dm_str_cat(out, c ? "|---:" : "|---");
            dm_str_cat(out, "|\n");
        }
    }
}

static void table__html(const dm_table *t, dm_str *out)
{
    dm_str_cat(out, "<div class=\"scroll\"><table class=\"answer counters\"><caption>Counters per "
                    "frame</caption><thead><tr>");
    for (size_t r = 0; r < t->n_rows; r++) {
        for (size_t c = 0; c < t->n_cells[r]; c++) {
            dm_str_cat(out, r == 0 ? "<th>" : c ? "<td class=\"n\">" : "<td>");
            dm_str_cat_html(out, t->rows[r][c]);
            dm_str_cat(out, r == 0 ? "</th>" : "</td>");
        }
        dm_str_cat(out, r == 0 ? "</tr></thead><tbody>\n" : "</tr>\n");
        if (r + 1 < t->n_rows)
            dm_str_cat(out, "<tr>");
    }
    dm_str_cat(out, "</tbody></table></div>\n");
}

void report_counter_table(const report_model *m, size_t si, report_answer_format f, dm_str *out)
{
    dm_table t = {0};
    table__build(m, &m->scenes[si], &t);
    if (t.n_cells[0] < 2) {   /* nothing but the label column */
        dm_table_free(&t);
        return;
    }
    if (f == REPORT_ANSWER_HTML)
        table__html(&t, out);
    else if (f == REPORT_ANSWER_MD)
        table__md(&t, out);
    else
        dm_table_text(&t, "  ", REPORT_TERMINAL_WIDTH, out);
    dm_table_free(&t);
}
