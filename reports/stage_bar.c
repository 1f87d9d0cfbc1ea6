/* stage_bar.c — the report's stacked stage bars (see stage_bar.h): the
 * rows and their labels are the report model's, the stage counters each
 * row's configuration's. */
#include "reports/stage_bar.h"
#include "counters/counters.h"

#include <math.h>
#include <stdio.h>

/* The counter's value, NaN when absent or unavailable. */
static double bar__value(const dm_config_result *c, const char *name)
{
    const dm_counter_result *r = dm_config_counter(c, name);
    return r && r->available ? r->value : NAN;
}

/* "1 234.5" or "–" for a per-invocation cell. */
static void bar__cell(dm_str *s, double v)
{
    if (isfinite(v))
        dm_str_printf(s, "<td class=\"n\">%.1f</td>", v);
    else
        dm_str_cat(s, "<td class=\"n\">–</td>");
}

/* One row: label, bar (three segments, widths = shares), verdict, costs. */
static void bar__row(dm_str *s, const report_model_row *r, const double part[3])
{
    static const char *const name[3] = {"geometry", "raster", "fragment"};
    static const char *const colour[3] = {"#4e79a7", "#f28e2b", "#59a14f"};
    const dm_config_result *c = r->config;
    double total = part[0] + part[1] + part[2];
    dm_str verdict = {0}, hover = {0};
    counters_stage_verdict(part[0], part[1], part[2], &verdict);
    double pv = bar__value(c, "InstructionsPerVertex"), pe = bar__value(c, "InstructionsPerEvaluation"),
           pp = bar__value(c, "FragmentInstructionsPerPixel");
    dm_str_printf(&hover, "%.0f instructions per frame", total);
    if (isfinite(pv))
        dm_str_printf(&hover, "; %.1f per vertex", pv);
    if (isfinite(pe))
        dm_str_printf(&hover, "; %.1f per evaluation", pe);
    if (isfinite(pp))
        dm_str_printf(&hover, "; %.1f fragment instructions per covered pixel", pp);
    dm_str_cat(s, "<tr><td>");
    dm_str_cat_html(s, r->label);
    dm_str_cat(s, "</td><td><div class=\"stagebar\" style=\"display:flex;width:240px;height:14px\" title=\"");
    dm_str_cat_html(s, dm_str_get(&hover));
    dm_str_cat(s, "\">");
    for (int k = 0; k < 3; k++)
        dm_str_printf(s, "<div style=\"width:%.2f%%;background:%s\" title=\"%s %.1f %%\"></div>", 100 * part[k] / total,
                      colour[k], name[k], 100 * part[k] / total);
    dm_str_cat(s, "</div></td><td>");
    dm_str_cat_html(s, dm_str_get(&verdict));
    dm_str_cat(s, "</td>");
    bar__cell(s, pv);
    bar__cell(s, pe);
    bar__cell(s, pp);
    dm_str_cat(s, "</tr>\n");
    dm_str_free(&verdict);
    dm_str_free(&hover);
}

void report_stage_bars(dm_str *s, const report_model *m)
{
    size_t shown = 0;
    for (size_t i = 0; i < m->n_rows; i++) {
        const dm_config_result *c = m->rows[i].config;
        double part[3] = {bar__value(c, "GeometryInstructions"), bar__value(c, "RasterInstructions"),
                          bar__value(c, "FragmentInstructions")};
        dm_str probe = {0};
        int ok = c->ok && counters_stage_verdict(part[0], part[1], part[2], &probe) == 0;
        dm_str_free(&probe);
        if (!ok)
            continue;
        if (shown++ == 0)
            dm_str_cat(s, "<h2 id=\"stages\">Where the instructions go</h2>\n<p>Instructions per frame by "
                          "stage, counted exactly with isolation passes (geometry: rasterizer discard; "
                          "raster: a minimal fragment shader; fragment: the rest), "
                          "<span style=\"color:#4e79a7\">■</span> geometry "
                          "<span style=\"color:#f28e2b\">■</span> raster "
                          "<span style=\"color:#59a14f\">■</span> fragment.</p>\n"
                          "<table><tr><th>configuration</th><th>stages</th><th>verdict</th>"
                          "<th>per vertex</th><th>per evaluation</th><th>fragment per pixel</th></tr>\n");
        bar__row(s, &m->rows[i], part);
    }
    if (shown)
        dm_str_cat(s, "</table>\n");
}
