/* report_html.c — report.html: one self-contained file that opens offline.
 * A row of the writer table (report_write.c): labels, times, marks, rows,
 * fronts, picks, trends, warnings, the answer's sentences (answer.c), the
 * charts (svg_chart.c, chart.c), the stage bars, the gallery and the
 * published section come from the report model (report_model.h).  What is
 * not derived is read from the run as stored: its header and environment,
 * each configuration's params, counters and image paths, the failed and
 * left-out configurations, the fits and the proxy section.
 *
 * Inline CSS, no external URL, no script needed to read it; the style
 * sheet and the script (sorting, filtering, image flips) are report.css and
 * report.js, embedded at build time (report_assets.h).  Every string
 * that comes from the data (sweep, params, environment, reasons, logs) goes
 * through dm_str_cat_html.  Image paths must be relative and free of "..";
 * others are refused and shown as such, missing files are shown as missing.
 */
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/stage_bar.h"
#include "reports/published_report.h"
#include "reports/proxy.h"
#include "reports/answer.h"
#include "reports/report_assets.h"

#include "core/dm_error.h"
#include "imaging/flip.h"
#include "imaging/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>



static void html__esc(dm_str *s, const char *text)
{
    dm_str_cat_html(s, text ? text : "");
}

/* <tag>escaped text</tag> */
static void html__tagged(dm_str *s, const char *tag, const char *text)
{
    dm_str_printf(s, "<%s>", tag);
    html__esc(s, text);
    dm_str_printf(s, "</%s>", tag);
}

static void html__params_inline(dm_str *s, const dm_kv *kv, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        dm_str_cat(s, i ? ", " : "");
        html__esc(s, kv[i].key);
        dm_str_cat(s, "=");
        html__esc(s, kv[i].value);
    }
}

static void html__header(dm_str *s, const report_model *m)
{
    const dm_run_result *run = m->run;
    dm_str_cat(s, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                  "<meta name=\"viewport\" content=\"width=device-width\"><title>dmbench: ");
    html__esc(s, run->sweep);
    dm_str_printf(s, "</title><style>\n%s</style></head>\n<body>\n<h1>dmbench report: ", report_assets_css);
    html__esc(s, run->sweep);
    dm_str_cat(s, "</h1>\n<p>Run ");
    html__esc(s, run->id);
    dm_str_cat(s, ", started ");
    html__esc(s, run->started);
    if (run->finished) {
        dm_str_cat(s, ", finished ");
        html__esc(s, run->finished);
    }
    dm_str_cat(s, ".");
    if (*m->constants) {
        dm_str_cat(s, " Every scene: ");
        html__esc(s, m->constants);
        dm_str_cat(s, ".");
    }
    dm_str_cat(s, "</p>\n");
}

/* The environment, folded: the summary names the renderer and the load. */
static void html__environment(dm_str *s, const dm_run_result *run)
{
    const char *r = dm_kv_get(run->environment, run->n_environment, "renderer");
    const char *l = dm_kv_get(run->environment, run->n_environment, "load_average");
    dm_str_cat(s, "<details class=\"env\" id=\"environment\"><summary><b>Environment</b>: ");
    html__esc(s, r ? r : "renderer unknown");
    dm_str_cat(s, ", load average ");
    html__esc(s, l ? l : "unknown");
    dm_str_cat(s, "</summary>\n<table>");
    for (size_t i = 0; i < run->n_environment; i++) {
        dm_str_cat(s, "<tr>");
        html__tagged(s, "th", run->environment[i].key);
        html__tagged(s, "td", run->environment[i].value);
        dm_str_cat(s, "</tr>");
    }
    dm_str_cat(s, "</table></details>\n");
}

/* Table of contents: the answer, each scene, gallery, failures, fits. */
static void html__toc(dm_str *s, const report_model *m)
{
    const dm_run_result *run = m->run;
    dm_str_cat(s, "<nav class=\"toc\"><b>Contents:</b> <a href=\"#answer\">Answer</a>");
    for (size_t i = 0; i < m->n_scenes; i++) {
        dm_str_printf(s, "<a href=\"#scene-%zu\">", i);
        html__esc(s, m->scenes[i].label);
        dm_str_cat(s, "</a>");
    }
    dm_str_cat(s, "<a href=\"#gallery\">Gallery</a><a href=\"#warnings\">Warnings</a>"
                  "<a href=\"#failed\">Failed and left out</a>");
    if (run->n_fits)
        dm_str_cat(s, "<a href=\"#fits\">Model fits</a>");
    dm_str_cat(s, "<a href=\"#passes\">Counters by pass</a><a href=\"#environment\">Environment</a></nav>\n");
}

/* The timing marks of a row (noisy, bimodal) as a span with the reason. */
static void html__marks_html(dm_str *s, const report_model_row *r)
{
    if (*r->marks_short) {
        dm_str_cat(s, " <span class=\"noisy\" title=\"");
        html__esc(s, r->why);
        dm_str_cat(s, "\">");
        html__esc(s, r->marks_short);
        dm_str_cat(s, "</span>");
    }
}

/* The median and 95 % CI cells of a frame time, with the noise marks. */
static void html__time_cells(dm_str *s, const report_model_row *r)
{
    dm_str_printf(s, "<td class=\"n\">%s</td><td class=\"n\">%s", r->ms_text, r->ci_text);
    html__marks_html(s, r);
    if (r->corrected) {   /* beside the raw figures, never instead (docs/measurement.md) */
        dm_str_cat(s, "<br><span class=\"corr\" title=\"" REPORT_DRIFT_METHOD "\">drift removed: ");
        html__esc(s, r->corr_time_ci_text);
        dm_str_cat(s, "</span>");
    }
    dm_str_cat(s, "</td>");
}

/* Lists more than this many noisy configurations inside a collapsed <details>. */
#define NOISY_OPEN_MAX 8

/* The noisy configurations by label with their CI and marks, folded when
 * there are many; nothing when there is none. */
static void html__noisy_warning(dm_str *s, const report_model *m)
{
    size_t n = m->n_noisy;
    if (n) {
        dm_str_printf(s, "<div class=\"warn noisy\"><details%s><summary><b>%zu noisy configuration%s</b> "
                         "by label</summary><ul>", n > NOISY_OPEN_MAX ? "" : " open", n, n == 1 ? "" : "s");
        for (size_t i = 0; i < n; i++) {
            const report_model_row *r = &m->rows[m->noisy[i]];
            dm_str_cat(s, "<li>");
            html__esc(s, r->full_label);
            dm_str_printf(s, " %s", r->ci_text ? r->ci_text : "CI unknown");
            html__marks_html(s, r);
            dm_str_cat(s, "</li>");
        }
        dm_str_cat(s, "</ul></details></div>\n");
    }
}

/* The timer verdict, then every warning (report__warnings, the list of
 * results.json), the noisy configurations listed under theirs. */
static void html__timer_and_warnings(dm_str *s, const report_model *m)
{
    const dm_run_result *run = m->run;
    const char *v = run->timer_verdict ? run->timer_verdict : "unknown";
    dm_str_cat(s, "<h2 id=\"warnings\">Warnings</h2>\n<p>Timer verdict: <b>");
    html__esc(s, v);
    dm_str_printf(s, "</b> (GPUTime covers %.1f%% of fenced wall time).</p>\n",
                  run->gpu_time_coverage * 100);
    if (*m->precision_text) {   /* the noise floor and the drift removal */
        dm_str_cat(s, "<p class=\"precision\">");
        html__esc(s, m->precision_text);
        for (size_t i = 0; i < m->n_scenes; i++) {
            const dm_scene_precision *p = m->scenes[i].precision;
            if (!p || p->corrected)
                continue;
            dm_str_cat(s, "<br>");
            html__esc(s, m->scenes[i].label);
            dm_str_cat(s, ": ");
            html__esc(s, p->reason ? p->reason : "no reason recorded");
        }
        dm_str_cat(s, "</p>\n");
    }
    for (size_t i = 0; i < m->n_warnings; i++) {
        dm_str_cat(s, "<div class=\"warn\">");
        html__esc(s, m->warnings[i]);
        dm_str_cat(s, "</div>\n");
    }
    html__noisy_warning(s, m);
}

static void html__num_cell(dm_str *s, const char *fmt, double v)
{
    if (isnan(v))
        dm_str_cat(s, "<td class=\"n\">–</td>");
    else if (isinf(v))
        dm_str_cat(s, v > 0 ? "<td class=\"n\">∞</td>" : "<td class=\"n\">−∞</td>");
    else {
        dm_str_cat(s, "<td class=\"n\">");
        dm_str_printf(s, fmt, v);
        dm_str_cat(s, "</td>");
    }
}

/* Where report.html reads the run's images: dir (the run directory, to
 * embed and check files) and href (prefix of links, "" beside the run). */
typedef struct html_images {
    const char *dir;
    const char *href;
} html_images;

static void html__gallery_linked(dm_str *s, const html_images *im, const char *rel, const char *label,
                           const char *caption, long ref);
static void html__scene_pick_images(dm_str *s, const report_model *m, const report_model_scene *sc,
                                    const html_images *im);

/* Counters worth a column in the scene tables (the rest are in the CSV/JSON). */
static const char *const html__key_counters[] = {
    "VSInvocations", "TESInvocations", "ClippingOutputPrimitives", "SamplesPassed",
    "FSInvocations", "TextureBytes", "MeshTriangles" };

/* 1 when a configuration of the scene has a trend (the column is shown). */
static int html__scene_has_trends(const report_model *m, const report_model_scene *sc)
{
    for (size_t i = 0; i < sc->n_rows; i++)
        if (m->rows[sc->rows[i]].trend)
            return 1;
    return 0;
}

/* A sparkline of the medians (80 × 18 px, y from the series' min to max,
 * this run as a dot; the values in its hover title). */
static void html__trend_cell(dm_str *s, const report_trend *tr)
{
    if (!tr) {
        dm_str_cat(s, "<td></td>");
        return;
    }
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < tr->n; i++)
        if (isfinite(tr->median_ns[i]))
            lo = fmin(lo, tr->median_ns[i]), hi = fmax(hi, tr->median_ns[i]);
    double span = hi > lo ? hi - lo : 1, x = 0, y = 0;
    dm_str_printf(s, "<td class=\"trend\"><svg class=\"spark\" width=\"80\" height=\"18\" "
                     "viewBox=\"0 0 80 18\"><title>median ms, oldest first:");
    for (size_t i = 0; i < tr->n; i++)
        dm_str_printf(s, " %.3f", tr->median_ns[i] / 1e6);
    dm_str_cat(s, "</title><polyline fill=\"none\" stroke=\"#36c\" points=\"");
    for (size_t i = 0; i < tr->n; i++) {
        if (!isfinite(tr->median_ns[i]))
            continue;
        x = 3 + 74.0 * (double)i / (double)(tr->n - 1);
        y = 15 - 12 * (tr->median_ns[i] - lo) / span;
        dm_str_printf(s, "%.1f,%.1f ", x, y);
    }
    dm_str_printf(s, "\"/><circle cx=\"%.1f\" cy=\"%.1f\" r=\"2\" fill=\"#c33\"/></svg></td>", x, y);
}

/* A counter cell behind the "show all columns" toggle (class "more"). */
static void html__more_cell(dm_str *s, const dm_counter_result *c)
{
    if (!c) {
        dm_str_cat(s, "<td class=\"more\"></td>");
    } else if (!c->available) {
        dm_str_cat(s, "<td class=\"more missing\" title=\"");
        html__esc(s, c->unavailable_reason);
        dm_str_cat(s, "\">unavailable</td>");
    } else {
        dm_str_printf(s, "<td class=\"n more\">%.0f</td>", c->value);
    }
}

/* Key columns first (technique, varying axes, time, CI, errors, front),
 * then the counters, crack pixels and key (class "more"). */
static void html__scene_row(dm_str *s, const report_model *m, const report_model_row *r,
                            const char **params, size_t np, const char **det, size_t nd, int trends)
{
    const dm_config_result *c = r->config;
    int front = r->front;
    dm_str_printf(s, "<tr%s>", front ? " class=\"front\"" : "");
    html__tagged(s, "td", dm_kv_get(c->params, c->n_params, "technique"));
    for (size_t i = 0; i < np; i++)
        html__tagged(s, "td", dm_kv_get(c->params, c->n_params, params[i]));
    if (r->frame_time) {
        html__time_cells(s, r);
    } else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td><td></td>");
    if (trends)
        html__trend_cell(s, r->trend);
    const dm_quality *q = &c->quality;
    html__num_cell(s, report_metric_format(m->metric), r->shown);
    html__num_cell(s, "%.4f", q->present ? q->ssim : NAN);
    if (m->metric != REPORT_METRIC_PSNR)   /* else the metric's column is the PSNR */
        html__num_cell(s, "%.2f", q->present ? q->psnr : NAN);
    dm_str_cat(s, front ? "<td>★ front</td>" : "<td></td>");
    for (size_t i = 0; i < nd; i++)
        html__more_cell(s, dm_config_counter(c, det[i]));
    if (q->present)
        dm_str_printf(s, "<td class=\"n more\">%ld</td>", q->crack_pixels);
    else
        dm_str_cat(s, "<td class=\"n more\">–</td>");
    dm_str_cat(s, "<td class=\"key more\">");
    html__esc(s, c->key);
    dm_str_cat(s, "</td></tr>\n");
}

/* Filter box and column toggle above scene table si. */
static void html__table_tools(dm_str *s, size_t si)
{
    dm_str_printf(s, "<div class=\"tools\"><input class=\"filter\" data-table=\"tbl-%zu\" "
                     "placeholder=\"filter rows (e.g. pom)\" aria-label=\"filter rows\"> "
                     "<button class=\"more\" data-table=\"tbl-%zu\">show all columns</button> "
                     "<span class=\"const\">click a header to sort</span></div>\n", si, si);
}

static void html__scene_table(dm_str *s, const report_model *m, size_t si, const html_images *im)
{
    const report_model_scene *sc = &m->scenes[si];
    int trends = html__scene_has_trends(m, sc);
    size_t nv = 0, nd = 0;
    const char **varying = dm_xcalloc(sc->n_varying + 1, sizeof *varying), *det[8];
    for (size_t i = 0; i < sc->n_varying; i++)   /* the technique has its own column */
        if (strcmp(sc->varying[i], "technique") != 0)
            varying[nv++] = sc->varying[i];
    dm_str_printf(s, "<h2 id=\"scene-%zu\">Scene ", si);
    html__esc(s, sc->label);
    dm_str_cat(s, "</h2>\n<p class=\"const\">Same for every row: ");
    html__esc(s, sc->same);
    dm_str_cat(s, "(where the technique reads it; a blank cell below: the technique does not read that axis)</p>\n");
    for (size_t k = 0; k < sizeof html__key_counters / sizeof *html__key_counters; k++)
        for (size_t i = 0; i < m->n_rows; i++)   /* failed configurations too: every row of the scene */
            if (m->rows[i].scene == si && dm_config_counter(m->rows[i].config, html__key_counters[k])) {
                det[nd++] = html__key_counters[k];
                break;
            }
    html__table_tools(s, si);
    dm_str_printf(s, "<div class=\"scroll\"><table class=\"sortable hide-more\" id=\"tbl-%zu\"><thead>"
                     "<tr><th>technique</th>", si);
    for (size_t i = 0; i < nv; i++)
        html__tagged(s, "th", varying[i]);
    dm_str_printf(s, "<th>median ms</th><th>95%% CI</th>%s<th>%s</th><th>SSIM</th>%s"
                     "<th>Pareto</th>", trends ? "<th title=\"median ms in the earlier runs of this "
                     "configuration on this machine, this run last\">trend</th>" : "",
                  report_metric_label(m->metric), m->metric == REPORT_METRIC_PSNR ? "" : "<th>PSNR dB</th>");
    for (size_t i = 0; i < nd; i++) {
        dm_str_cat(s, "<th class=\"more\">");
        html__esc(s, det[i]);
        dm_str_cat(s, "</th>");
    }
    dm_str_cat(s, "<th class=\"more\">CrackPixels</th><th class=\"more\">key</th></tr></thead><tbody>\n");
    for (size_t i = 0; i < sc->n_rows; i++)
        html__scene_row(s, m, &m->rows[sc->rows[i]], varying, nv, det, nd, trends);
    dm_str_cat(s, "</tbody></table></div>\n");
    dm_str_cat(s, "<div class=\"charts\">\n");   /* side by side where the window is wide enough */
    html__scene_pick_images(s, m, sc, im);
    report__svg_scene(s, m, si);
    report__html_charts_scene(s, m, si);
    dm_str_cat(s, "</div>\n");
    free(varying);
}

#define THUMB_MAX_DIM 240

static void html__base64(dm_str *s, const unsigned char *d, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) |
                     (i + 2 < n ? d[i + 2] : 0);
        char q[4] = {tab[v >> 18 & 63], tab[v >> 12 & 63],
                     i + 1 < n ? tab[v >> 6 & 63] : '=', i + 2 < n ? tab[v & 63] : '='};
        dm_str_catn(s, q, 4);
    }
}

/* An embedded PNG thumbnail of a readable file, else the link. */
static void html__image_src(dm_str *s, const html_images *im, const char *full, const char *rel)
{
    unsigned char *png = NULL;
    size_t len = 0;
    char err[256];
    if (full && img_thumbnail_png(full, THUMB_MAX_DIM, &png, &len, err, sizeof err) == 0) {
        dm_str_cat(s, "data:image/png;base64,");
        html__base64(s, png, len);
        free(png);
        return;
    }
    if (full)
        dm_log(DM_LOG_WARN, "report.html: no thumbnail, linking the file: %s", err);
    html__esc(s, im->href);
    html__esc(s, rel);
}

/* 1 when rel can be shown; else a "missing"/"refused" figure is written. */
static int html__gallery_usable(dm_str *s, const html_images *im, const char *rel, const char *label)
{
    const char *why = !rel ? " image: none" : !report__safe_relpath(rel) ? " path refused: " : NULL;
    char *full = !why && im->dir ? dm_xasprintf("%s/%s", im->dir, rel) : NULL;
    if (full && !dm_file_exists(full))
        why = " image missing: ";
    free(full);
    if (!why)
        return 1;
    dm_str_printf(s, "<figure><span class=\"missing\">%s%s", label, why);
    html__esc(s, rel ? rel : "");
    dm_str_printf(s, "</span><figcaption>%s</figcaption></figure>", label);
    return 0;
}

/* A scene's reference, embedded once as a thumbnail (id refs[k] = "ref-K")
 * on a card of its own; data-full names the file, so a render flips to the
 * reference at the render's own size, not to the thumbnail. */
static void html__gallery_reference(dm_str *s, const html_images *im, const char *rel, size_t k)
{
    dm_str_cat(s, "<div class=\"pair ref\">");
    if (html__gallery_usable(s, im, rel, "reference")) {
        char *full = im->dir ? dm_xasprintf("%s/%s", im->dir, rel) : NULL;
        dm_str_printf(s, "<figure><a href=\"");
        html__esc(s, im->href);
        html__esc(s, rel);
        dm_str_printf(s, "\"><img id=\"ref-%zu\" data-full=\"", k);
        html__esc(s, im->href);
        html__esc(s, rel);
        dm_str_cat(s, "\" src=\"");
        html__image_src(s, im, full, rel);
        dm_str_cat(s, "\" alt=\"reference\"></a><figcaption><b>reference</b></figcaption></figure>");
        free(full);
    }
    dm_str_cat(s, "<p class=\"cap\">The reference the cards that follow are compared with; click a "
                  "render to flip it with the reference, full size.</p></div>");
}

/* A render or heatmap, linked (loaded from img/ beside the report, lazily);
 * a render flips to its reference on click. */
static void html__gallery_linked(dm_str *s, const html_images *im, const char *rel, const char *label,
                           const char *caption, long ref)
{
    if (!html__gallery_usable(s, im, rel, label))
        return;
    dm_str_cat(s, "<figure><img loading=\"lazy\" src=\"");
    html__esc(s, im->href);
    html__esc(s, rel);
    if (ref >= 0)
        dm_str_printf(s, "\" class=\"flip\" data-ref=\"ref-%ld", ref);
    dm_str_printf(s, "\" alt=\"%s: ", label);
    html__esc(s, caption);
    dm_str_printf(s, "\"><figcaption>%s · <a class=\"full\" href=\"", label);
    html__esc(s, im->href);
    html__esc(s, rel);
    dm_str_cat(s, "\">full size</a></figcaption></figure>");
}

/* The scene's pick (the model's recommendation) as its render and heatmap
 * beside the charts, so the answer's image is next to its numbers; nothing
 * without a pick. */
static void html__scene_pick_images(dm_str *s, const report_model *m, const report_model_scene *sc,
                                    const html_images *im)
{
    if (sc->rec.pick == RECOMMEND_NONE)
        return;
    const report_model_row *r = &m->rows[sc->rec.pick];
    const dm_config_result *c = r->config;
    dm_str cap = {0};
    dm_str_cat(s, "<div class=\"pair pick-images\">");
    html__gallery_linked(s, im, c->img_render, "render", r->label, -1);
    html__gallery_linked(s, im, c->img_heatmap, "heatmap", r->label, -1);
    dm_str_printf(&cap, "The pick: %s, %s", r->label, r->metric_text);
    dm_str_cat(s, "<p class=\"cap\">");
    html__esc(s, dm_str_get(&cap));
    dm_str_cat(s, "</p></div>\n");
    dm_str_free(&cap);
}

/* FLIP's fixed colour scale as a CSS gradient, from flip_colormap itself so
 * the legend cannot drift from the maps. */
static void html__flip_scale(dm_str *s)
{
    dm_str_cat(s, "<span class=\"scale\" style=\"background:linear-gradient(90deg");
    for (int i = 0; i <= 8; i++) {
        float c[3];
        flip_colormap(i / 8.0, c);
        dm_str_printf(s, ",#%02x%02x%02x", (int)lrintf(c[0] * 255), (int)lrintf(c[1] * 255),
                      (int)lrintf(c[2] * 255));
    }
    dm_str_cat(s, ")\"></span>");
}

/* Index of rel in refs (appended when new); *fresh = 1 when appended. */
static size_t html__gallery_ref_index(const char ***refs, size_t *n, const char *rel, int *fresh)
{
    for (size_t i = 0; i < *n; i++)
        if (strcmp((*refs)[i], rel) == 0) {
            *fresh = 0;
            return i;
        }
    *refs = dm_xrealloc(*refs, (*n + 1) * sizeof **refs);
    (*refs)[*n] = rel;
    *fresh = 1;
    return (*n)++;
}

/* The legends of a scene's maps, before its cards.  A run's heatmap is its
 * FLIP map: FLIP's fixed, bounded scale, stated as `dmbench diff --heatmap`
 * states it (FLIP_SCALE_TEXT).  An older run's |render − reference|
 * heatmap keeps its own legend: one absolute scale, with what saturates it
 * (a difference of a channel's whole range or more: lit values may pass
 * 1); its separate FLIP maps keep theirs. */
static void html__gallery_legend(dm_str *s, const report_model_scene *sc)
{
    if (sc->heatmap_flip) {
        dm_str_printf(s, "<p class=\"const\">Heatmap: " FLIP_SCALE_TEXT ", at %.3g pixels per "
                         "degree, the scale of <code>dmbench diff --heatmap</code>: 0 ", sc->flip_ppd);
        html__flip_scale(s);
        dm_str_cat(s, " 1, the same colour for the same error in every map, so maps compare side by "
                      "side; FLIP is bounded, so no map saturates (docs/flip.md). Click a render to "
                      "flip it with the reference.</p>\n");
    }
    if (sc->heatmap_diff)
        dm_str_printf(s, "<p class=\"const\">Heatmap: |render − reference| per pixel (largest "
                         "channel) on one absolute scale for every map, so maps compare side by side: "
                         "0 <span class=\"scale\"></span> 1, a channel's whole range; a larger "
                         "difference shows as 1. The largest difference in this scene (MaxError) is "
                         "%.3g%s. Click a render to flip it with the reference.</p>\n", sc->max_error,
                      sc->max_error > 1 ? ": its hottest pixels saturate the map" : "");
    if (sc->flips && sc->heatmap_diff) {
        dm_str_printf(s, "<p class=\"const\">FLIP map: " FLIP_SCALE_TEXT ", at %.3g pixels per "
                         "degree, one fixed scale for every map, so maps compare side by side: 0 ",
                      sc->flip_ppd);
        html__flip_scale(s);
        dm_str_cat(s, " 1 (docs/flip.md).</p>\n");
    }
}

/* The caption of a configuration's card: its values, on its maps' scales
 * (a FLIP heatmap's FLIP figures; an older heatmap's MaxError, marked
 * where it saturates that map). */
static void html__gallery_caption(dm_str *cap, const report_model_row *r)
{
    const dm_config_result *c = r->config;
    dm_str_printf(cap, "%s: %s", r->label, r->metric_text);
    if (!report_model_heatmap_is_flip(c))
        dm_str_printf(cap, ", MaxError %.3g%s", c->quality.max_error,
                      c->quality.max_error > 1 ? " (saturates the heatmap)" : "");
    if (c->img_flip)
        dm_str_printf(cap, ", FLIP %.4f (max %.3f)", c->quality.flip, c->quality.flip_max);
}

/* One scene's grid, its legends first: its reference(s) once, then render
 * and heatmap of each configuration, fastest first, each a card of one
 * width with its values below. */
static void html__gallery_scene(dm_str *s, const report_model *m, const report_model_scene *sc,
                                const html_images *im, const char ***refs, size_t *nrefs)
{
    dm_str_cat(s, "<h3>");
    html__esc(s, sc->label);
    dm_str_cat(s, "</h3>\n");
    html__gallery_legend(s, sc);
    dm_str_cat(s, "<div class=\"grid\">");
    for (size_t i = 0; i < sc->n_rows; i++) {
        const report_model_row *r = &m->rows[sc->rows[i]];
        const dm_config_result *c = r->config;
        long ref = -1;
        int fresh = 0;
        if (c->img_reference && report__safe_relpath(c->img_reference)) {
            ref = (long)html__gallery_ref_index(refs, nrefs, c->img_reference, &fresh);
            if (fresh)
                html__gallery_reference(s, im, c->img_reference, (size_t)ref);
        } else if (c->img_reference) {   /* a card that says it is refused */
            dm_str_cat(s, "<div class=\"pair ref\">");
            html__gallery_usable(s, im, c->img_reference, "reference");
            dm_str_cat(s, "</div>");
        }
        const char *label = r->label;
        dm_str_cat(s, "<div class=\"pair\">");
        html__gallery_linked(s, im, c->img_render, "render", label, ref);
        int flip_heat = report_model_heatmap_is_flip(c);
        html__gallery_linked(s, im, c->img_heatmap, flip_heat ? "heatmap (FLIP)" : "heatmap", label, -1);
        if (c->img_flip && !flip_heat)
            html__gallery_linked(s, im, c->img_flip, "FLIP", label, -1);
        /* the caption of the pair carries its values, on the legend's scale */
        dm_str cap = {0};
        html__gallery_caption(&cap, r);
        dm_str_cat(s, "<p class=\"cap\">");
        html__esc(s, dm_str_get(&cap));
        dm_str_cat(s, "</p></div>");
        dm_str_free(&cap);
    }
    dm_str_cat(s, "</div>\n");
}

static void html__gallery(dm_str *s, const report_model *m, const html_images *im)
{
    const char **refs = NULL;
    size_t nrefs = 0;
    dm_str_cat(s, "<h2 id=\"gallery\">Gallery</h2>\n<p>Per scene: the reference once (embedded), "
                  "then each configuration's render and heatmap side by side, fastest first, with "
                  "their values (files in img/ beside this report; \"full size\" opens one).</p>\n");
    for (size_t i = 0; i < m->n_scenes; i++)
        html__gallery_scene(s, m, &m->scenes[i], im, &refs, &nrefs);
    free(refs);
}

/* The failed configurations with their reasons and logs, then the
 * combinations the planner left out; each says "None." when it has none
 * (as summary.md does) instead of an empty heading or a header-only table. */
static void html__failed_and_left_out(dm_str *s, const dm_run_result *run)
{
    size_t failed = 0;
    dm_str_cat(s, "<h2 id=\"failed\">Failed configurations</h2>\n");
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (c->ok)
            continue;
        failed++;
        dm_str_cat(s, "<div class=\"fail\"><p><b>");
        html__esc(s, c->key);
        dm_str_cat(s, "</b> ");
        html__params_inline(s, c->params, c->n_params);
        dm_str_cat(s, ": ");
        html__esc(s, c->reason ? c->reason : "no reason recorded");
        dm_str_cat(s, "</p>");
        if (c->log)
            html__tagged(s, "pre", c->log);
        dm_str_cat(s, "</div>\n");
    }
    if (!failed)
        dm_str_cat(s, "<p class=\"const\">None.</p>\n");
    dm_str_cat(s, "<h2>Left out</h2>\n");
    if (!run->n_left_out) {
        dm_str_cat(s, "<p class=\"const\">None.</p>\n");
        return;
    }
    dm_str_cat(s, "<table><tr><th>params</th><th>reason</th></tr>\n");
    for (size_t i = 0; i < run->n_left_out; i++) {
        dm_str_cat(s, "<tr><td>");
        html__params_inline(s, run->left_out[i].params, run->left_out[i].n_params);
        dm_str_cat(s, "</td>");
        html__tagged(s, "td", run->left_out[i].reason);
        dm_str_cat(s, "</tr>\n");
    }
    dm_str_cat(s, "</table>\n");
}

/* Condition number: 0 = not computed (blank), ∞ = rank deficient. */
static void html__condition_cell(dm_str *s, double v)
{
    if (v == 0 || isnan(v))
        dm_str_cat(s, "<td class=\"missing\">not computed</td>");
    else if (isinf(v))
        dm_str_cat(s, "<td class=\"n fail\">∞ (rank deficient)</td>");
    else
        html__num_cell(s, "%.3g", v);
}

/* A fit worth its table row and plots: R² >= FIT_USABLE_R2 and full rank. */
#define FIT_USABLE_R2 0.8
static int html__fit_usable(const dm_fit_result *f)
{
    return isfinite(f->r2) && f->r2 >= FIT_USABLE_R2 && !isinf(f->condition) && f->n_params > 0;
}

/* A usable fit's row: model, group, each parameter with its stderr and
 * unit (the model's fit_units), R², CV MAPE, condition, points, warnings. */
static void html__fit_row(dm_str *s, const dm_fit_result *f, char *const *units)
{
    dm_str_cat(s, "<tr>");
    html__tagged(s, "td", f->model);
    dm_str_cat(s, "<td>");
    html__params_inline(s, f->group, f->n_group);
    dm_str_cat(s, "</td><td>");
    for (size_t k = 0; k < f->n_params; k++) {
        html__esc(s, f->params[k].name);
        dm_str_printf(s, " = %.3g", f->params[k].value);
        if (isfinite(f->params[k].stderr_))
            dm_str_printf(s, " ± %.2g", f->params[k].stderr_);
        if (*units[k]) {
            dm_str_cat(s, " ");
            html__esc(s, units[k]);
        }
        dm_str_cat(s, "<br>");
    }
    dm_str_cat(s, "</td>");
    html__num_cell(s, "%.4f", f->r2);
    html__num_cell(s, "%.4f", f->cv_mape);
    html__condition_cell(s, f->condition);
    dm_str_printf(s, "<td class=\"n\">%d</td><td>", f->n_points);
    for (size_t k = 0; k < f->n_warnings; k++) {
        html__esc(s, f->warnings[k]);
        dm_str_cat(s, "<br>");
    }
    dm_str_cat(s, "</td></tr>\n");
}

/* One line for a fit that did not work: model, group, R² and its first warning. */
static void html__fit_line(dm_str *s, const dm_fit_result *f)
{
    dm_str_cat(s, "<li>");
    html__esc(s, f->model);
    dm_str_cat(s, " (");
    html__params_inline(s, f->group, f->n_group);
    dm_str_printf(s, "): R² %.2f over %d points", f->r2, f->n_points);
    if (f->n_warnings) {
        dm_str_cat(s, "; ");
        html__esc(s, f->warnings[0]);
    }
    dm_str_cat(s, "</li>\n");
}

/* Usable fits with their table and plots; the others folded, one line each. */
static void html__fits(dm_str *s, const report_model *m)
{
    const dm_run_result *run = m->run;
    if (!run->n_fits)
        return;
    size_t bad = 0;
    for (size_t i = 0; i < run->n_fits; i++)
        bad += !html__fit_usable(&run->fits[i]);
    dm_str_cat(s, "<h2 id=\"fits\">Model fits</h2>\n");
    if (bad < run->n_fits) {
        dm_str_cat(s, "<table><tr><th>model</th><th>group</th><th>parameters ± stderr, unit</th>"
                      "<th>R²</th><th>CV MAPE</th><th title=\"2-norm condition number of the scaled "
                      "Jacobian; large means the parameters are poorly determined\">condition</th>"
                      "<th>points</th><th>warnings</th></tr>\n");
        for (size_t i = 0; i < run->n_fits; i++)
            if (html__fit_usable(&run->fits[i]))
                html__fit_row(s, &run->fits[i], m->fit_units[i]);
        dm_str_cat(s, "</table>\n");
        for (size_t i = 0; i < run->n_fits; i++)   /* plots on demand: two per fit */
            if (html__fit_usable(&run->fits[i])) {
                dm_str_cat(s, "<details class=\"fit-plots\"><summary>Plots: ");
                html__esc(s, run->fits[i].model);
                dm_str_cat(s, " ");
                html__params_inline(s, run->fits[i].group, run->fits[i].n_group);
                dm_str_cat(s, "</summary>\n");
                report__html_charts_fit(s, run, &run->fits[i]);
                dm_str_cat(s, "</details>\n");
            }
    }
    if (!bad)
        return;
    dm_str_printf(s, "<details class=\"fits-bad\"><summary>%zu fit%s not usable (R² below %.1f or "
                     "rank deficient): one line each</summary><ul>\n", bad, bad == 1 ? "" : "s",
                  FIT_USABLE_R2);
    for (size_t i = 0; i < run->n_fits; i++)
        if (!html__fit_usable(&run->fits[i]))
            html__fit_line(s, &run->fits[i]);
    dm_str_cat(s, "</ul></details>\n");
}

/* Instructions as a proxy for frame time (reports/proxy.h) and which
 * pass each counter came from. */
static void html__proxy_section(dm_str *s, const dm_run_result *run)
{
    report_proxy p;
    if (report_proxy_fit(run, &p) == 0) {
        dm_str_printf(s, "<h2 id=\"proxy\">Instructions as a proxy for frame time</h2>\n<p>WallTime ≈ %.4g ns + "
                      "%.4g ns × Instructions over %zu configurations: R² = %.5f.</p>\n"
                      "<table><tr><th>strays most</th><th>WallTime</th><th>predicted</th>"
                      "<th>residual</th></tr>\n", p.a_ns, p.ns_per_instruction, p.n, p.r2);
        for (size_t i = 0; i < p.n_strays; i++) {
            dm_str_cat(s, "<tr>");
            html__tagged(s, "td", p.strays[i].label);
            dm_str_printf(s, "<td class=\"n\">%.3f ms</td><td class=\"n\">%.3f ms</td>"
                          "<td class=\"n\">%+.1f%%</td></tr>\n", p.strays[i].wall_ns / 1e6,
                          p.strays[i].predicted_ns / 1e6, p.strays[i].residual_rel * 100);
        }
        dm_str_cat(s, "</table>\n");
    }
    dm_str passes = {0};
    report_proxy_passes_text(run, "\n", &passes);
    dm_str_cat(s, "<h2 id=\"passes\">Counters by pass</h2>\n<ul>\n");
    char *save = NULL;
    for (char *l = passes.buf ? strtok_r(passes.buf, "\n", &save) : NULL; l; l = strtok_r(NULL, "\n", &save))
        html__tagged(s, "li", l);
    dm_str_cat(s, "</ul>\n");
    dm_str_free(&passes);
}

/* "steps=32 filter=aniso" — the axes that vary in the scene, without technique. */
static const char *html__settings_text(const report_model_row *r)
{
    const char *sp = strchr(r->label, ' ');
    return sp ? sp + 1 : "";
}

/* One scene's answer: the recommendation in words, then its front as a
 * compact table, fastest first (the pick marked, cost relative to the
 * fastest lit configuration). */
static void html__answer_table(dm_str *s, const report_model *m, size_t si)
{
    const report_model_scene *sc = &m->scenes[si];
    const size_t *front = sc->front, nf = sc->n_front;
    const recommend_result *r = &sc->rec;
    const dm_counter_result *base = r->fastest != RECOMMEND_NONE ? m->rows[r->fastest].frame_time : NULL;
    int with_settings = 0;
    for (size_t i = 0; i < nf && !with_settings; i++)
        with_settings = *html__settings_text(&m->rows[front[i]]) != 0;
    dm_str_printf(s, "<section class=\"scene-answer\" id=\"answer-%zu\"><h3>", si);
    html__esc(s, sc->label);
    dm_str_cat(s, "</h3>\n");
    report_answer_scene(m, si, REPORT_ANSWER_HTML, s);
    if (sc->untimed) {   /* counters only: no front, the counters instead */
        dm_str_cat(s, "</section>\n");
        return;
    }
    dm_str_printf(s, "<div class=\"scroll\"><table class=\"answer front\" id=\"front-%zu\"><caption>"
                     "Front: best quality for its cost</caption><thead><tr><th>technique</th>%s"
                     "<th>median ms</th><th>95%% CI</th><th>%s</th><th>cost vs fastest lit</th>"
                     "</tr></thead><tbody>\n", si, with_settings ? "<th>settings</th>" : "",
                  report_metric_label(m->metric));
    if (!nf)
        dm_str_printf(s, "<tr><td colspan=\"6\" class=\"missing\">no configuration has both a time "
                         "and a %s measurement</td></tr>\n", report_metric_label(m->metric));
    for (size_t i = 0; i < nf; i++) {
        const report_model_row *row = &m->rows[front[i]];
        dm_str_printf(s, "<tr%s><td>", front[i] == r->pick ? " class=\"pick\"" : "");
        html__esc(s, row->technique);
        if (front[i] == r->pick)
            dm_str_cat(s, " <b>← pick</b>");
        if (row->family == RECOMMEND_UNLIT)
            dm_str_cat(s, " <span class=\"const\">(unlit baseline)</span>");
        dm_str_cat(s, "</td>");
        if (with_settings)
            html__tagged(s, "td", html__settings_text(row));
        html__time_cells(s, row);
        html__num_cell(s, report_metric_format(m->metric), row->shown);
        dm_str_printf(s, "<td class=\"n\">×%.2f</td></tr>\n",
                      base ? row->frame_time->median / base->median : NAN);
    }
    dm_str_cat(s, "</tbody></table></div></section>\n");
}

/* The answer first: per scene, the recommendation in words and the front
 * (the run's metric against median time). */
static void html__answer(dm_str *s, const report_model *model)
{
    report_metric m = model->metric;
    if (!model->any_timed) {
        dm_str_cat(s, "<h2 id=\"answer\">Answer: what was measured</h2>\n<p class=\"const\">No timing "
                      "counter was measured (the sweep's <code>counters:</code> have no WallTime), so "
                      "there is no frame budget and no pick: each scene shows the counters it measured, "
                      "per frame.</p>\n");
        dm_str_cat(s, "<div class=\"answers\">\n");
        for (size_t i = 0; i < model->n_scenes; i++)
            html__answer_table(s, model, i);
        dm_str_cat(s, "</div>\n");
        return;
    }
    dm_str_printf(s, "<h2 id=\"answer\">Answer: what to use</h2>\n<p class=\"const\">Quality is "
                     "<b>%s</b> (%s) against the reference; two values closer than %g are the "
                     "same quality and the cheaper configuration wins.  Times are the median frame "
                     "time with its 95%% CI; ⚠ marks a timing too noisy or bimodal to trust "
                     "(hover for the reason).  Unlit techniques are baselines, never the pick.  The default "
                     "budget is the round number (1, 2, 5 × 10ⁿ ms) between a scene's fastest and "
                     "slowest lit times that lies farthest, on a log scale, from every lit time, so "
                     "a little noise cannot move it; set yours with <code>dmbench report --budget-ms</code> or the "
                     "sweep key <code>quality.budget_ms</code>.</p>\n",
                  report_metric_name(m), report_metric_label(m), report_metric_epsilon(m));
    dm_str_cat(s, "<div class=\"answers\">\n");
    for (size_t i = 0; i < model->n_scenes; i++)
        html__answer_table(s, model, i);
    dm_str_cat(s, "</div>\n");
}

int report__write_html(const report_model *m, const report_desc *d, const char *path)
{
    const dm_run_result *run = m->run;
    html_images im = { m->dir, d && d->href ? d->href : "" };
    dm_str s = {0};
    /* by value: the answer, each scene's table and charts, the images, then
     * the diagnostics, and what only a maintainer reads at the end */
    html__header(&s, m);
    html__toc(&s, m);
    html__answer(&s, m);
    for (size_t i = 0; i < m->n_scenes; i++) {
        html__scene_table(&s, m, i, &im);
        report__html_path_scene(&s, m, i, im.href);   /* its camera paths (path_html.c) */
    }
    html__gallery(&s, m, &im);
    report_stage_bars(&s, m);   /* where each configuration's cost goes (stage_bar.c) */
    html__timer_and_warnings(&s, m);
    html__failed_and_left_out(&s, run);
    html__fits(&s, m);
    dm_str_cat(&s, m->published_html);
    html__proxy_section(&s, run);
    html__environment(&s, run);
    dm_str_printf(&s, "<script>\n%s</script>\n</body></html>\n", report_assets_js);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
