/* report_tex.c — front.tex: each scene's Pareto front as a LaTeX table
 * (booktabs), to \input into a paper or thesis.  Reads only the report
 * model (report_model.h); one row of the writer table (report_write.c).
 *
 * Per timed scene with a front: a table environment whose caption names the
 * scene and the error metric, rows fastest first (configuration label,
 * median ms, 95 % CI, the metric as the report shows it), the scene's pick
 * marked "(pick)".  A scene without a frame time or without a front is a
 * comment line saying why.  Text from the sweep is escaped for LaTeX; ×, ±,
 * − and · become math. */
#include "reports/report_internal.h"
#include "reports/report_model.h"

#include <math.h>
#include <string.h>

/* text with LaTeX's special characters escaped and the report's few
 * non-ASCII signs as math; other UTF-8 passes through (inputenc). */
static void tex__esc(dm_str *s, const char *text)
{
    static const struct { const char *from, *to; } map[] = {
        {"\\", "\\textbackslash{}"}, {"&", "\\&"}, {"%", "\\%"}, {"$", "\\$"}, {"#", "\\#"},
        {"_", "\\_"}, {"{", "\\{"}, {"}", "\\}"}, {"~", "\\textasciitilde{}"},
        {"^", "\\textasciicircum{}"}, {"×", "$\\times$"}, {"±", "$\\pm$"}, {"−", "$-$"},
        {"·", "$\\cdot$"},
    };
    for (const char *p = text ? text : ""; *p;) {
        size_t k = 0, n = sizeof map / sizeof *map;
        while (k < n && strncmp(p, map[k].from, strlen(map[k].from)) != 0)
            k++;
        if (k < n) {
            dm_str_cat(s, map[k].to);
            p += strlen(map[k].from);
        } else
            dm_str_catn(s, p++, 1);
    }
}

/* The metric as the report shows it: four significant digits, ∞, or "--". */
static void tex__metric(dm_str *s, double v, report_metric m)
{
    if (isnan(v))
        dm_str_cat(s, "--");
    else if (isinf(v))
        dm_str_cat(s, v > 0 ? "$\\infty$" : "$-\\infty$");
    else   /* one precision for the column, as in the report's tables */
        dm_str_printf(s, report_metric_format(m), v);
}

static void tex__scene(dm_str *s, const report_model *m, const report_model_scene *sc)
{
    const char *metric = report_metric_label(m->metric);
    if (sc->untimed || !sc->n_front) {   /* a comment: the label needs no escaping there */
        dm_str_printf(s, "%% %s: ", sc->label);
        if (sc->untimed)
            dm_str_cat(s, "no frame time, no front\n\n");
        else
            dm_str_printf(s, "no configuration with a time and a %s, no front\n\n", metric);
        return;
    }
    dm_str_cat(s, "\\begin{table}[htbp]\n\\centering\n\\caption{");
    tex__esc(s, sc->label);
    dm_str_cat(s, ": the Pareto front (");
    tex__esc(s, metric);
    dm_str_cat(s, " against median frame time), fastest first}\n\\begin{tabular}{lrrr}\n\\toprule\n"
                  "Configuration & Median (ms) & 95\\,\\% CI & ");
    tex__esc(s, metric);
    dm_str_cat(s, " \\\\\n\\midrule\n");
    for (size_t i = 0; i < sc->n_front; i++) {
        const report_model_row *r = &m->rows[sc->front[i]];
        tex__esc(s, r->label);
        dm_str_cat(s, sc->front[i] == sc->rec.pick ? " (pick) & " : " & ");
        tex__esc(s, r->ms_text);
        dm_str_cat(s, " & ");
        tex__esc(s, r->ci_text);
        dm_str_cat(s, " & ");
        tex__metric(s, r->shown, m->metric);
        dm_str_cat(s, " \\\\\n");
    }
    dm_str_cat(s, "\\bottomrule\n\\end{tabular}\n\\end{table}\n\n");
}

int report__write_tex(const report_model *m, const report_desc *d, const char *path)
{
    (void)d;
    dm_str s = {0};
    dm_str_cat(&s, "% front.tex: each scene's Pareto front, written by dmbench from run ");
    dm_str_cat(&s, m->run->id ? m->run->id : "?");
    dm_str_cat(&s, ".\n% \\input it; needs \\usepackage{booktabs}.\n\n");
    for (size_t i = 0; i < m->n_scenes; i++)
        tex__scene(&s, m, &m->scenes[i]);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
