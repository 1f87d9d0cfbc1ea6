/* path_html.c — "Along the path" in report.html (docs/motion.md, "In the
 * report"): per scene, the configurations on a camera path with their
 * figures (p50/p95/p99, the 1 % low as a time and a frame rate, the
 * stutters with their frames, the replay spread and the noisy mark) in one
 * table, then each one's frame-time plot (svg_chart.c: report__svg_path).
 * Reads the report model only; a scene without a path configuration, and
 * so a still run, gets nothing.
 */
#include "reports/report_internal.h"
#include "reports/report_model.h"

#include <math.h>

/* Stutter frames listed in a cell; the rest are "…" (the plot marks all). */
#define PATH_HTML__STUTTERS_SHOWN 8

static void path_html__ms_cell(dm_str *s, double ns)
{
    if (isfinite(ns))
        dm_str_printf(s, "<td class=\"n\">%.3f</td>", ns / 1e6);
    else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td>");
}

/* One configuration's row of the scene's table. */
static void path_html__row(dm_str *s, const report_model_row *r)
{
    const dm_path_series *p = &r->config->path;
    dm_str_cat(s, "<tr><td>");
    dm_str_cat_html(s, r->label);
    dm_str_printf(s, "</td><td class=\"n\">%zu × %zu</td>", p->frames, p->replays);
    path_html__ms_cell(s, p->p50);
    path_html__ms_cell(s, p->p95);
    path_html__ms_cell(s, p->p99);
    if (isfinite(p->low1_ns))
        dm_str_printf(s, "<td class=\"n\">%.3f ms (%.0f fps)</td>", p->low1_ns / 1e6, p->low1_fps);
    else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td>");
    dm_str_printf(s, "<td class=\"n\">%zu", p->n_stutters);
    for (size_t i = 0; i < p->n_stutters && i < PATH_HTML__STUTTERS_SHOWN; i++)
        dm_str_printf(s, "%s%ld", i ? ", " : p->n_stutters == 1 ? " (frame " : " (frames ", p->stutter_at[i]);
    if (p->n_stutters)
        dm_str_cat(s, p->n_stutters > PATH_HTML__STUTTERS_SHOWN ? ", …)" : ")");
    if (p->noisy < 0)
        dm_str_cat(s, "</td><td title=\"one replay: nothing to compare it with\">unknown (one replay)</td>");
    else if (p->noisy)
        dm_str_printf(s, "</td><td class=\"n\" title=\"the replays of a frame differ by over 10 %% of its "
                         "median: the series is noisy\">%.1f %% <span class=\"noisy\">⚠ noisy</span></td>",
                      100 * p->replay_spread);
    else
        dm_str_printf(s, "</td><td class=\"n\">%.1f %%</td>", 100 * p->replay_spread);
    dm_str_printf(s, "<td class=\"key\">%s</td></tr>\n", r->config->key ? r->config->key : "");
}

void report__html_path_scene(dm_str *s, const report_model *m, size_t si)
{
    size_t n = 0;
    for (size_t i = 0; i < m->n_rows; i++)
        n += m->rows[i].scene == si && m->rows[i].config->path.frames > 0;
    if (!n)
        return;
    dm_str_printf(s, "<section class=\"path-scene\" id=\"path-%zu\"><h3>Along the path: ", si);
    dm_str_cat_html(s, m->scenes[si].label);
    dm_str_cat(s, "</h3>\n<p class=\"const\">A timing sample is one replay of the whole path; each frame's "
                  "time is the median of its replays.  p50/p95/p99 are over the frames, the 1 % low the "
                  "mean of the slowest ⌈F/100⌉ frames, a stutter a frame over 2 × p50, the replay spread "
                  "the median over frames of (max − min) / median of its replays (noisy over 10 %).</p>\n");
    dm_str_printf(s, "<div class=\"scroll\"><table class=\"path\" id=\"path-tbl-%zu\"><thead><tr>"
                     "<th>configuration</th><th>frames × replays</th><th>p50 ms</th><th>p95 ms</th>"
                     "<th>p99 ms</th><th>1 %% low</th><th>stutters</th><th>replay spread</th><th>key</th>"
                     "</tr></thead><tbody>\n", si);
    for (size_t i = 0; i < m->n_rows; i++)
        if (m->rows[i].scene == si && m->rows[i].config->path.frames > 0)
            path_html__row(s, &m->rows[i]);
    dm_str_cat(s, "</tbody></table></div>\n<div class=\"charts\">\n");
    for (size_t i = 0; i < m->n_rows; i++)
        if (m->rows[i].scene == si && m->rows[i].config->path.frames > 0)
            report__svg_path(s, &m->rows[i]);
    dm_str_cat(s, "</div></section>\n");
}
