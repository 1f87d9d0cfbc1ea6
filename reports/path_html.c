/* path_html.c — "Along the path" in report.html (docs/motion.md, "In the
 * report"): per scene, the configurations on a camera path with their
 * figures (p50/p95/p99, the 1 % low as a time and a frame rate, the
 * stutters with their frames, the replay spread and the noisy mark; where
 * quality along the path was asked, the temporal error, popping and the
 * temporal error map) in one table, then each one's frame-time plot and
 * quality plot side by side (svg_chart.c) and its filmstrip: the frames the
 * run wrote as images (dm_path_shot), a large view of one, buttons and keys
 * that step through them and flip the view between the frame, its
 * reference and their FLIP map (report.js), every image also a link.
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

/* FLIP or SSIM of reference frame `frame` of q as text (%.4g), or
 * "unavailable". */
static void path_html__frame_figure(dm_str *s, const dm_path_quality *q, const double *v, long frame)
{
    size_t i = q->every > 0 ? (size_t)(frame / q->every) : q->n;
    if (i < q->n && isfinite(v[i]))
        dm_str_printf(s, "%.4g", v[i]);
    else
        dm_str_cat(s, "unavailable");
}

/* A link to image rel under href, with its text; "not written" when rel is
 * missing or not a path inside the run. */
static void path_html__link(dm_str *s, const char *href, const char *rel, const char *text)
{
    if (!rel || !report__safe_relpath(rel)) {
        dm_str_printf(s, "<span class=\"missing\">%s not written</span>", text);
        return;
    }
    dm_str_cat(s, "<a href=\"");
    dm_str_cat_html(s, href);
    dm_str_cat_html(s, rel);
    dm_str_printf(s, "\">%s</a>", text);
}

/* One thumbnail of the strip: the frame (linked to its file), links to the
 * reference and FLIP map, and data-* the script reads: the three files and
 * the frame's figures. */
static void path_html__shot(dm_str *s, const dm_path_quality *q, const dm_path_shot *sh, const char *href)
{
    const char *kinds[3] = { sh->img_test, sh->img_ref, sh->img_flip };
    const char *names[3] = { "test", "ref", "flip" };
    dm_str_printf(s, "<figure class=\"film-shot\" data-frame=\"%ld\"", sh->frame);
    for (int k = 0; k < 3; k++) {
        dm_str_printf(s, " data-%s=\"", names[k]);
        if (kinds[k] && report__safe_relpath(kinds[k])) {
            dm_str_cat_html(s, href);
            dm_str_cat_html(s, kinds[k]);
        }
        dm_str_cat(s, "\"");
    }
    dm_str_cat(s, " data-flipv=\"");
    path_html__frame_figure(s, q, q->flip, sh->frame);
    dm_str_cat(s, "\" data-ssim=\"");
    path_html__frame_figure(s, q, q->ssim, sh->frame);
    dm_str_cat(s, "\">");
    if (sh->img_test && report__safe_relpath(sh->img_test)) {
        dm_str_cat(s, "<a href=\"");
        dm_str_cat_html(s, href);
        dm_str_cat_html(s, sh->img_test);
        dm_str_cat(s, "\"><img src=\"");
        dm_str_cat_html(s, href);
        dm_str_cat_html(s, sh->img_test);
        dm_str_printf(s, "\" alt=\"frame %ld\"></a>", sh->frame);
    }
    dm_str_printf(s, "<figcaption>frame %ld: ", sh->frame);
    path_html__link(s, href, sh->img_ref, "reference");
    dm_str_cat(s, " · ");
    path_html__link(s, href, sh->img_flip, "FLIP");
    dm_str_cat(s, "</figcaption></figure>");
}

/* The configuration's filmstrip (docs/reports.md, "Page order"): the
 * controls, the large view of its first written frame with the caption,
 * then the strip of every written frame (scrolling in its own box).  Without a
 * script the strip's links open every image; the controls need it.  When
 * quality along the path was computed but no frame was written, says why. */
static void path_html__film(dm_str *s, const report_model_row *r, const char *href)
{
    const dm_path_quality *q = &r->config->path_quality;
    const char *key = r->config->key ? r->config->key : "";
    if (!q->present)
        return;
    if (!q->n_shots) {
        dm_str_cat(s, "<p class=\"missing film-none\">No filmstrip for ");
        dm_str_cat_html(s, r->label);
        dm_str_cat(s, ": the run wrote no frame images (runs before dmbench wrote them have none; "
                      "otherwise the configuration's log says why)</p>\n");
        return;
    }
    const dm_path_shot *first = &q->shots[0];
    dm_str_cat(s, "<div class=\"film\" tabindex=\"0\" id=\"film-");
    dm_str_cat_html(s, key);
    dm_str_cat(s, "\" data-label=\"");
    dm_str_cat_html(s, r->label);
    dm_str_printf(s, "\" data-frames=\"%ld\"><h4>Filmstrip: ", q->frames);
    dm_str_cat_html(s, r->label);
    dm_str_printf(s, "</h4>\n<p class=\"const\">%zu of its %zu reference frames as the run wrote "
                     "them, each with its reference frame and their FLIP map (a long path's are "
                     "evenly spread, the first and last always among them).  ← → or the buttons "
                     "step through them; F or the button flips the view between the frame, its "
                     "reference and the FLIP map.</p>\n", q->n_shots, q->n);
    dm_str_cat(s, "<div class=\"film-tools\"><button type=\"button\" class=\"film-prev\">◀ previous"
                  "</button> <button type=\"button\" class=\"film-next\">next ▶</button> <button "
                  "type=\"button\" class=\"film-flip\">flip: frame → reference → FLIP (F)</button></div>\n"
                  "<figure class=\"film-view\"><img class=\"film-big\" src=\"");
    if (first->img_test && report__safe_relpath(first->img_test)) {
        dm_str_cat_html(s, href);
        dm_str_cat_html(s, first->img_test);
    }
    dm_str_printf(s, "\" alt=\"frame %ld\" data-kind=\"test\"><figcaption class=\"film-cap\">", first->frame);
    dm_str_cat_html(s, r->label);
    dm_str_printf(s, " — frame %ld of %ld, the technique's frame: FLIP ", first->frame, q->frames);
    path_html__frame_figure(s, q, q->flip, first->frame);
    dm_str_cat(s, ", SSIM ");
    path_html__frame_figure(s, q, q->ssim, first->frame);
    dm_str_cat(s, "</figcaption></figure>\n<div class=\"scroll film-strip\">");
    for (size_t i = 0; i < q->n_shots; i++)
        path_html__shot(s, q, &q->shots[i], href);
    dm_str_cat(s, "</div></div>\n");
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
            path_html__film(s, &m->rows[i], href ? href : "");
        }
    dm_str_cat(s, "</section>\n");
}
