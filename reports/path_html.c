/* path_html.c — "Along the path" in report.html (docs/motion.md, "In the
 * report"): per scene, the configurations on a camera path with their
 * figures (p50/p95/p99, the 1 % low as a time and a frame rate, the
 * stutters with their frames, the replay spread and the noisy mark; where
 * quality along the path was asked, the temporal error, popping and the
 * temporal error map) in one table, then each one's frame-time plot and
 * quality plot side by side (svg_chart.c).
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

/* A number of quality along the path, or "unavailable". */
static void path_html__q_cell(dm_str *s, double v)
{
    if (isfinite(v))
        dm_str_printf(s, "<td class=\"n\">%.4g</td>", v);
    else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td>");
}

/* The quality columns of a row: temporal error mean and p99, popping with
 * its frame, the temporal error map; the reason across them when it was
 * asked but not computed, blank when not asked. */
static void path_html__quality_cells(dm_str *s, const dm_path_quality *q, const char *href)
{
    if (!q->present) {
        dm_str_cat(s, "<td colspan=\"4\" class=\"missing\">");
        dm_str_cat_html(s, q->reason ? q->reason : "not asked");
        dm_str_cat(s, "</td>");
        return;
    }
    path_html__q_cell(s, q->temporal_mean);
    path_html__q_cell(s, q->temporal_p99);
    if (isfinite(q->popping) && q->popping_frame >= 0)
        dm_str_printf(s, "<td class=\"n\">%.4g (frame %ld)</td>", q->popping, q->popping_frame);
    else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td>");
    if (q->img_temporal && report__safe_relpath(q->img_temporal)) {
        dm_str_cat(s, "<td><a href=\"");
        dm_str_cat_html(s, href);
        dm_str_cat_html(s, q->img_temporal);
        dm_str_cat(s, "\">map</a></td>");
    } else {
        dm_str_cat(s, "<td class=\"missing\">none</td>");
    }
}

/* One configuration's row of the scene's table. */
static void path_html__row(dm_str *s, const report_model_row *r, int quality, const char *href)
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
    if (quality)
        path_html__quality_cells(s, &r->config->path_quality, href);
    dm_str_printf(s, "<td class=\"key\">%s</td></tr>\n", r->config->key ? r->config->key : "");
}

/* 1 when row i is on a camera path in scene si. */
static int path_html__in(const report_model *m, size_t i, size_t si)
{
    return m->rows[i].scene == si && m->rows[i].config->path.frames > 0;
}

void report__html_path_scene(dm_str *s, const report_model *m, size_t si, const char *href)
{
    size_t n = 0;
    int quality = 0;   /* some row asked for quality along its path */
    for (size_t i = 0; i < m->n_rows; i++)
        if (path_html__in(m, i, si)) {
            n++;
            quality |= m->rows[i].config->path_quality.present || m->rows[i].config->path_quality.reason;
        }
    if (!n)
        return;
    dm_str_printf(s, "<section class=\"path-scene\" id=\"path-%zu\"><h3>Along the path: ", si);
    dm_str_cat_html(s, m->scenes[si].label);
    dm_str_cat(s, "</h3>\n<p class=\"const\">A timing sample is one replay of the whole path; each frame's "
                  "time is the median of its replays.  p50/p95/p99 are over the frames, the 1 % low the "
                  "mean of the slowest ⌈F/100⌉ frames, a stutter a frame over 2 × p50, the replay spread "
                  "the median over frames of (max − min) / median of its replays (noisy over 10 %).");
    if (quality)
        dm_str_cat(s, "  Temporal error: how much the frame-to-frame change of the technique differs "
                      "from the reference's, per pixel and step between reference frames (mean and "
                      "99th percentile); popping: the largest jump of FLIP between consecutive reference "
                      "frames, at the frame it lands on.");
    dm_str_printf(s, "</p>\n<div class=\"scroll\"><table class=\"path\" id=\"path-tbl-%zu\"><thead><tr>"
                     "<th>configuration</th><th>frames × replays</th><th>p50 ms</th><th>p95 ms</th>"
                     "<th>p99 ms</th><th>1 %% low</th><th>stutters</th><th>replay spread</th>%s<th>key</th>"
                     "</tr></thead><tbody>\n", si,
                  quality ? "<th>temporal error mean</th><th>temporal error p99</th><th>popping</th>"
                            "<th>temporal error map</th>" : "");
    for (size_t i = 0; i < m->n_rows; i++)
        if (path_html__in(m, i, si))
            path_html__row(s, &m->rows[i], quality, href ? href : "");
    dm_str_cat(s, "</tbody></table></div>\n");
    report__svg_motion_front(s, m, si);
    /* each configuration's two plots side by side, shrinking to fit: the
     * style is inline, so report.css (in every report) stays as it is */
    for (size_t i = 0; i < m->n_rows; i++)
        if (path_html__in(m, i, si)) {
            dm_str_cat(s, "<div class=\"charts path-pair\" style=\"flex-wrap:wrap\"><div style=\"flex:1 1 320px;"
                          "max-width:720px\">");
            report__svg_path(s, &m->rows[i]);
            dm_str_cat(s, "</div><div style=\"flex:1 1 320px;max-width:720px\">");
            report__svg_path_quality(s, &m->rows[i]);
            dm_str_cat(s, "</div></div>\n");
        }
    dm_str_cat(s, "</section>\n");
}
