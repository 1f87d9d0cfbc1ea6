/* report_html.c — report.html: one self-contained file that opens offline.
 *
 * Inline CSS, no external URL, no script needed to read it.  Every string
 * that comes from the data (sweep, params, environment, reasons, logs) goes
 * through dm_str_cat_html.  Image paths must be relative and free of "..";
 * others are refused and shown as such, missing files are shown as missing.
 */
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/proxy.h"

#include "core/dm_error.h"
#include "reports/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *css =
    "body{font:14px/1.4 system-ui,sans-serif;margin:1.5em;color:#222;background:#fff}"
    "table{border-collapse:collapse;margin:.5em 0 1.5em}"
    "th,td{border:1px solid #ccc;padding:3px 7px;text-align:left;vertical-align:top}"
    "th{background:#f0f0f0}td.n{text-align:right;font-variant-numeric:tabular-nums}"
    ".warn{background:#fff3cd;border:1px solid #e0b000;padding:.6em;margin:.6em 0}"
    ".fail{color:#a00}.missing{color:#888;font-style:italic}"
    "pre{background:#f6f6f6;padding:.5em;overflow:auto;max-height:20em}"
    "figure{display:inline-block;margin:0 1em 1em 0}figure img{width:192px;image-rendering:pixelated;border:1px solid #ccc}"
    ".gal{margin-bottom:1em}.chart svg{max-width:100%;height:auto}"
    ".const{color:#555}td.key{font:11px monospace;color:#777}"
    "table.sortable th{cursor:pointer}table.sortable th:hover{background:#e4e4e4}";

/* Click a column header to sort by it (numbers numerically); the content is
 * complete without it. */
static const char *sort_js =
    "document.querySelectorAll('table.sortable th').forEach(function(th,i){"
    "th.title='click to sort';th.onclick=function(){var tb=th.closest('table').tBodies[0];"
    "var rows=Array.from(tb.rows),up=th.dataset.up!=='1';th.dataset.up=up?'1':'0';"
    "rows.sort(function(a,b){var x=a.cells[i].textContent,y=b.cells[i].textContent,"
    "p=parseFloat(x.replace(/[^0-9.eE+-]/g,'')),q=parseFloat(y.replace(/[^0-9.eE+-]/g,''));"
    "var r=(!isNaN(p)&&!isNaN(q))?p-q:x.localeCompare(y);return up?r:-r;});"
    "rows.forEach(function(r){tb.appendChild(r);});};});";

static void esc(dm_str *s, const char *text)
{
    dm_str_cat_html(s, text ? text : "");
}

/* <tag>escaped text</tag> */
static void tagged(dm_str *s, const char *tag, const char *text)
{
    dm_str_printf(s, "<%s>", tag);
    esc(s, text);
    dm_str_printf(s, "</%s>", tag);
}

static void params_inline(dm_str *s, const dm_kv *kv, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        dm_str_cat(s, i ? ", " : "");
        esc(s, kv[i].key);
        dm_str_cat(s, "=");
        esc(s, kv[i].value);
    }
}

static void header(dm_str *s, const dm_run_result *run)
{
    dm_str_cat(s, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                  "<meta name=\"viewport\" content=\"width=device-width\"><title>dmbench: ");
    esc(s, run->sweep);
    dm_str_printf(s, "</title><style>%s</style></head>\n<body>\n<h1>dmbench report: ", css);
    esc(s, run->sweep);
    dm_str_cat(s, "</h1>\n<p>Run ");
    esc(s, run->id);
    dm_str_cat(s, ", started ");
    esc(s, run->started);
    if (run->finished) {
        dm_str_cat(s, ", finished ");
        esc(s, run->finished);
    }
    dm_str_cat(s, ".</p>\n<h2>Environment</h2>\n<table>");
    for (size_t i = 0; i < run->n_environment; i++) {
        dm_str_cat(s, "<tr>");
        tagged(s, "th", run->environment[i].key);
        tagged(s, "td", run->environment[i].value);
        dm_str_cat(s, "</tr>");
    }
    dm_str_cat(s, "</table>\n");
}

/* Lists more than this many noisy configurations inside a collapsed <details>. */
#define NOISY_OPEN_MAX 8

/* The warning box naming every configuration whose timing is too noisy to
 * trust (report__noisy); nothing when there is none. */
static void noisy_warning(dm_str *s, const dm_run_result *run)
{
    size_t *idx, n = report__noisy_configs(run, &idx);
    if (n) {
        dm_str_printf(s, "<div class=\"warn noisy\">%s<b>%zu noisy configuration%s</b>: the 95%% CI "
                         "of the median frame time is wider than ±%.0f%% of the median (or unknown); "
                         "compare their times with care.%s<ul>",
                      n > NOISY_OPEN_MAX ? "<details><summary>" : "", n, n == 1 ? "" : "s",
                      REPORT__NOISY_CI_REL * 100, n > NOISY_OPEN_MAX ? "</summary>" : "");
        for (size_t i = 0; i < n; i++) {
            const dm_config_result *c = &run->configs[idx[i]];
            dm_str label = {0};
            report__config_label(run, c, &label);
            dm_str_cat(s, "<li>");
            esc(s, dm_str_get(&label));
            dm_str_cat(s, " <code>");
            esc(s, c->key);
            dm_str_cat(s, "</code> ");
            report__ci_text(report__frame_time(c), s);
            dm_str_cat(s, "</li>");
            dm_str_free(&label);
        }
        dm_str_printf(s, "</ul>%s</div>\n", n > NOISY_OPEN_MAX ? "</details>" : "");
    }
    free(idx);
}

static void timer_and_warnings(dm_str *s, const dm_run_result *run)
{
    const char *v = run->timer_verdict ? run->timer_verdict : "unknown";
    dm_str_cat(s, "<p>Timer verdict: <b>");
    esc(s, v);
    dm_str_printf(s, "</b> (GPUTime covers %.1f%% of fenced wall time).</p>\n",
                  run->gpu_time_coverage * 100);
    if (strcmp(v, "partial") == 0)
        dm_str_printf(s, "<div class=\"warn\">GPUTime is partial on this driver: it covers %.1f%% "
                         "of fenced wall time; it is recorded, never used to fit or gate.</div>\n",
                      run->gpu_time_coverage * 100);
    noisy_warning(s, run);
    dm_str q = {0};
    report__quality_warnings(run, &q);
    char *save = NULL;
    for (char *line = q.buf ? strtok_r(q.buf, "\n", &save) : NULL; line; line = strtok_r(NULL, "\n", &save)) {
        dm_str_cat(s, "<div class=\"warn\">");
        esc(s, line);
        dm_str_cat(s, "</div>\n");
    }
    dm_str_free(&q);
    for (size_t i = 0; i < run->n_warnings; i++) {
        dm_str_cat(s, "<div class=\"warn\">");
        esc(s, run->warnings[i]);
        dm_str_cat(s, "</div>\n");
    }
}

static void num_cell(dm_str *s, const char *fmt, double v)
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

static void counter_cell(dm_str *s, const dm_counter_result *c)
{
    if (!c)
        dm_str_cat(s, "<td></td>");
    else if (!c->available) {
        dm_str_cat(s, "<td class=\"missing\" title=\"");
        esc(s, c->unavailable_reason);
        dm_str_cat(s, "\">unavailable</td>");
    } else
        num_cell(s, "%.0f", c->value);
}

/* Counters worth a column in the scene tables (the rest are in the CSV/JSON). */
static const char *const key_counters[] = {
    "VSInvocations", "TESInvocations", "ClippingOutputPrimitives", "SamplesPassed",
    "FSInvocations", "TextureBytes", "MeshTriangles" };

/* 1 when config index i is one of the nf front members. */
static int on_front(const size_t *front, size_t nf, size_t i)
{
    for (size_t k = 0; k < nf; k++)
        if (front[k] == i)
            return 1;
    return 0;
}

static void scene_row(dm_str *s, const dm_run_result *run, size_t ci, const char **params,
                      size_t np, const char **det, size_t nd, int front)
{
    const dm_config_result *c = &run->configs[ci];
    dm_str_cat(s, "<tr>");
    tagged(s, "td", dm_kv_get(c->params, c->n_params, "technique"));
    for (size_t i = 0; i < np; i++)
        tagged(s, "td", dm_kv_get(c->params, c->n_params, params[i]));
    const dm_counter_result *t = report__frame_time(c);
    if (t)
        dm_str_printf(s, "<td class=\"n\">%.3f</td><td class=\"n\">±%.1f%%</td>", t->median / 1e6,
                      report__ci_rel(t) * 100);
    else
        dm_str_cat(s, "<td class=\"missing\">unavailable</td><td></td>");
    for (size_t i = 0; i < nd; i++)
        counter_cell(s, dm_config_counter(c, det[i]));
    const dm_quality *q = &c->quality;
    num_cell(s, "%.2f", q->present ? q->psnr : NAN);
    num_cell(s, "%.4f", q->present ? q->ssim : NAN);
    num_cell(s, "%.0f", q->present ? (double)q->crack_pixels : NAN);
    num_cell(s, "%.4g", report_metric_shown(q, report_metric_of_run(run)));
    dm_str_cat(s, front ? "<td>front</td>" : "<td></td>");
    dm_str_cat(s, "<td class=\"key\">");
    esc(s, c->key);
    dm_str_cat(s, "</td></tr>\n");
}

static void scene_table(dm_str *s, const dm_run_result *run, const char *scene)
{
    const char **params;
    size_t np = report__param_names(run, scene, &params), nv = 0, nd = 0;
    const char **varying = dm_xcalloc(np + 1, sizeof *varying), *det[8];
    dm_str_cat(s, "<h2>Scene ");
    esc(s, scene);
    dm_str_cat(s, "</h2>\n<p class=\"const\">Same for every row: ");
    for (size_t i = 0; i < np; i++) {
        if (strcmp(params[i], "technique") == 0)
            continue;
        if (report__param_varies(run, scene, params[i])) {
            varying[nv++] = params[i];
            continue;
        }
        const char *v = NULL;
        for (size_t k = 0; k < run->n_configs && !v; k++)
            if (run->configs[k].ok && strcmp(run->configs[k].scene ? run->configs[k].scene : "", scene) == 0)
                v = dm_kv_get(run->configs[k].params, run->configs[k].n_params, params[i]);
        if (!v)
            continue;
        esc(s, params[i]);
        dm_str_cat(s, "=");
        esc(s, v);
        dm_str_cat(s, " ");
    }
    dm_str_cat(s, "(where the technique reads it; a blank cell below: the technique does not read that axis)</p>\n");
    for (size_t k = 0; k < sizeof key_counters / sizeof *key_counters; k++)
        for (size_t i = 0; i < run->n_configs; i++)
            if (strcmp(run->configs[i].scene ? run->configs[i].scene : "", scene) == 0 &&
                dm_config_counter(&run->configs[i], key_counters[k])) {
                det[nd++] = key_counters[k];
                break;
            }
    dm_str_cat(s, "<table class=\"sortable\"><thead><tr><th>technique</th>");
    for (size_t i = 0; i < nv; i++)
        tagged(s, "th", varying[i]);
    dm_str_cat(s, "<th>median ms</th><th>95% CI</th>");
    for (size_t i = 0; i < nd; i++)
        tagged(s, "th", det[i]);
    dm_str_printf(s, "<th>PSNR dB</th><th>SSIM</th><th>CrackPixels</th><th>%s</th><th>Pareto</th>"
                     "<th>key</th></tr></thead><tbody>\n",
                  report_metric_label(report_metric_of_run(run)));
    size_t *rows, nr = report__scene_rows(run, scene, &rows), *front;
    size_t nf = report__pareto(run, scene, &front);
    for (size_t i = 0; i < nr; i++)
        scene_row(s, run, rows[i], varying, nv, det, nd, on_front(front, nf, rows[i]));
    dm_str_cat(s, "</tbody></table>\n");
    report__html_charts_scene(s, run, scene);
    free(front);
    free(rows);
    free(varying);
    free(params);
}

#define THUMB_MAX_DIM 192

static void base64(dm_str *s, const unsigned char *d, size_t n)
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

/* The src of a gallery image: an embedded PNG thumbnail (so report.html
 * alone shows it) when the file can be read, else the relative path. */
static void image_src(dm_str *s, const char *full, const char *rel)
{
    unsigned char *png = NULL;
    size_t len = 0;
    char err[256];
    if (full && img_thumbnail_png(full, THUMB_MAX_DIM, &png, &len, err, sizeof err) == 0) {
        dm_str_cat(s, "data:image/png;base64,");
        base64(s, png, len);
        free(png);
        return;
    }
    if (full)
        dm_log(DM_LOG_WARN, "report.html: no thumbnail, linking the file: %s", err);
    esc(s, rel);
}

/* One gallery image: refused when the path could leave the run directory,
 * "missing" when dir is given and the file is not there. */
static void gallery_image(dm_str *s, const char *dir, const char *rel, const char *label)
{
    dm_str_cat(s, "<figure>");
    if (!rel) {
        dm_str_printf(s, "<span class=\"missing\">no %s image</span>", label);
    } else if (!report__safe_relpath(rel)) {
        dm_str_printf(s, "<span class=\"missing\">%s path refused: ", label);
        esc(s, rel);
        dm_str_cat(s, "</span>");
    } else {
        char *full = dir ? dm_xasprintf("%s/%s", dir, rel) : NULL;
        if (full && !dm_file_exists(full)) {
            dm_str_printf(s, "<span class=\"missing\">%s image missing: ", label);
            esc(s, rel);
            dm_str_cat(s, "</span>");
        } else {
            dm_str_cat(s, "<a href=\"");
            esc(s, rel);
            dm_str_cat(s, "\"><img src=\"");
            image_src(s, full, rel);
            dm_str_printf(s, "\" alt=\"%s\"></a>", label);
        }
        free(full);
    }
    dm_str_printf(s, "<figcaption>%s</figcaption></figure>", label);
}

static void gallery(dm_str *s, const dm_run_result *run, const char *dir)
{
    dm_str_cat(s, "<h2>Gallery</h2>\n<p>reference | render | heatmap (|difference|, inferno)</p>\n");
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (!c->ok || (!c->img_render && !c->img_heatmap && !c->img_reference))
            continue;
        dm_str_cat(s, "<div class=\"gal\"><p><b>");
        esc(s, c->key);
        dm_str_cat(s, "</b> ");
        params_inline(s, c->params, c->n_params);
        dm_str_cat(s, "</p>");
        gallery_image(s, dir, c->img_reference, "reference");
        gallery_image(s, dir, c->img_render, "render");
        gallery_image(s, dir, c->img_heatmap, "heatmap");
        dm_str_cat(s, "</div>\n");
    }
}

static void failed_and_left_out(dm_str *s, const dm_run_result *run)
{
    dm_str_cat(s, "<h2>Failed configurations</h2>\n");
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (c->ok)
            continue;
        dm_str_cat(s, "<div class=\"fail\"><p><b>");
        esc(s, c->key);
        dm_str_cat(s, "</b> ");
        params_inline(s, c->params, c->n_params);
        dm_str_cat(s, ": ");
        esc(s, c->reason ? c->reason : "no reason recorded");
        dm_str_cat(s, "</p>");
        if (c->log)
            tagged(s, "pre", c->log);
        dm_str_cat(s, "</div>\n");
    }
    dm_str_cat(s, "<h2>Left out</h2>\n<table><tr><th>params</th><th>reason</th></tr>\n");
    for (size_t i = 0; i < run->n_left_out; i++) {
        dm_str_cat(s, "<tr><td>");
        params_inline(s, run->left_out[i].params, run->left_out[i].n_params);
        dm_str_cat(s, "</td>");
        tagged(s, "td", run->left_out[i].reason);
        dm_str_cat(s, "</tr>\n");
    }
    dm_str_cat(s, "</table>\n");
}

/* Condition number: 0 = not computed (blank), ∞ = rank deficient. */
static void condition_cell(dm_str *s, double v)
{
    if (v == 0 || isnan(v))
        dm_str_cat(s, "<td class=\"missing\">not computed</td>");
    else if (isinf(v))
        dm_str_cat(s, "<td class=\"n fail\">∞ (rank deficient)</td>");
    else
        num_cell(s, "%.3g", v);
}

static void fits(dm_str *s, const dm_run_result *run)
{
    if (!run->n_fits)
        return;
    dm_str_cat(s, "<h2>Model fits</h2>\n<table><tr><th>model</th><th>group</th><th>parameters ± stderr</th>"
                  "<th>R²</th><th>CV MAPE</th><th title=\"2-norm condition number of the scaled "
                  "Jacobian; large means the parameters are poorly determined\">condition</th>"
                  "<th>points</th><th>warnings</th></tr>\n");
    for (size_t i = 0; i < run->n_fits; i++) {
        const dm_fit_result *f = &run->fits[i];
        dm_str_cat(s, "<tr>");
        tagged(s, "td", f->model);
        dm_str_cat(s, "<td>");
        params_inline(s, f->group, f->n_group);
        dm_str_cat(s, "</td><td>");
        for (size_t k = 0; k < f->n_params; k++) {
            esc(s, f->params[k].name);
            dm_str_printf(s, " = %.6g ± %.3g<br>", f->params[k].value, f->params[k].stderr_);
        }
        dm_str_cat(s, "</td>");
        num_cell(s, "%.4f", f->r2);
        num_cell(s, "%.4f", f->cv_mape);
        condition_cell(s, f->condition);
        dm_str_printf(s, "<td class=\"n\">%d</td><td>", f->n_points);
        for (size_t k = 0; k < f->n_warnings; k++) {
            esc(s, f->warnings[k]);
            dm_str_cat(s, "<br>");
        }
        dm_str_cat(s, "</td></tr>\n");
    }
    dm_str_cat(s, "</table>\n");
    for (size_t i = 0; i < run->n_fits; i++)
        report__html_charts_fit(s, run, &run->fits[i]);
}

/* Instructions as a proxy for frame time (reports/proxy.h) and which
 * pass each counter came from. */
static void proxy_section(dm_str *s, const dm_run_result *run)
{
    report_proxy p;
    if (report_proxy_fit(run, &p) == 0) {
        dm_str_printf(s, "<h2>Instructions as a proxy for frame time</h2>\n<p>WallTime ≈ %.4g ns + "
                      "%.4g ns × Instructions over %zu configurations: R² = %.5f.</p>\n"
                      "<table><tr><th>strays most</th><th>WallTime</th><th>predicted</th>"
                      "<th>residual</th></tr>\n", p.a_ns, p.ns_per_instruction, p.n, p.r2);
        for (size_t i = 0; i < p.n_strays; i++) {
            dm_str_cat(s, "<tr>");
            tagged(s, "td", p.strays[i].label);
            dm_str_printf(s, "<td class=\"n\">%.3f ms</td><td class=\"n\">%.3f ms</td>"
                          "<td class=\"n\">%+.1f%%</td></tr>\n", p.strays[i].wall_ns / 1e6,
                          p.strays[i].predicted_ns / 1e6, p.strays[i].residual_rel * 100);
        }
        dm_str_cat(s, "</table>\n");
    }
    dm_str passes = {0};
    report_proxy_passes_text(run, "\n", &passes);
    dm_str_cat(s, "<h2>Counters by pass</h2>\n<ul>\n");
    char *save = NULL;
    for (char *l = passes.buf ? strtok_r(passes.buf, "\n", &save) : NULL; l; l = strtok_r(NULL, "\n", &save))
        tagged(s, "li", l);
    dm_str_cat(s, "</ul>\n");
    dm_str_free(&passes);
}

/* The answer first: per scene, which configurations give the best quality
 * for their cost (the Pareto front of the run's metric against median time). */
static void findings(dm_str *s, const dm_run_result *run)
{
    const char **scenes;
    size_t ns = report__scenes(run, &scenes);
    report_metric m = report_metric_of_run(run);
    dm_str_printf(s, "<h2>Findings</h2>\n<p>Best quality for its cost in each scene: the Pareto front "
                     "of error (metric <b>%s</b>: %s against the reference) and median frame time, "
                     "fastest first. Every other configuration is slower than one of these and not "
                     "better.</p>\n<ul>\n", report_metric_name(m), report_metric_label(m));
    for (size_t i = 0; i < ns; i++) {
        dm_str front = {0};
        report__pareto_text(run, scenes[i], &front);
        dm_str_cat(s, "<li><b>");
        esc(s, scenes[i]);
        dm_str_cat(s, "</b>: ");
        esc(s, dm_str_get(&front));
        dm_str_cat(s, "</li>\n");
        dm_str_free(&front);
    }
    dm_str_cat(s, "</ul>\n");
    free(scenes);
}

int report_write_html(const dm_run_result *run, const char *dir, const char *path)
{
    if (!run || !path)
        return DM_ERR_ARG;
    dm_str s = {0};
    header(&s, run);
    timer_and_warnings(&s, run);
    findings(&s, run);
    report__html_charts_run(&s, run);
    const char **scenes;
    size_t ns = report__scenes(run, &scenes);
    for (size_t i = 0; i < ns; i++)
        scene_table(&s, run, scenes[i]);
    free(scenes);
    gallery(&s, run, dir);
    failed_and_left_out(&s, run);
    fits(&s, run);
    proxy_section(&s, run);
    dm_str_printf(&s, "<script>%s</script>\n</body></html>\n", sort_js);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
