/* svg_chart.c — the per-scene charts written as SVG by hand, so every label
 * is placed and sized by us and none is clipped:
 *  - error vs time: one point per configuration at (median ms, error) with
 *    a horizontal whisker for the 95 % CI of the median; each point carries
 *    a printed number (its row in the legend below the chart) and a hover
 *    title; front members are filled and joined by the front line;
 *  - time per configuration: one horizontal bar per configuration of the
 *    scene (never pooled across scenes), fastest first, with its CI whisker
 *    and its full label left of the bar (the SVG is as wide as the longest
 *    label needs).
 */
#include "reports/report_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SVG_CHAR_W 6.6     /* px per character of 11 px sans-serif (generous) */
#define SVG_W 720.0
#define SVG_H 340.0
#define SVG_L 64.0         /* plot area margins */
#define SVG_R 24.0
#define SVG_T 24.0
#define SVG_B 44.0

typedef struct svg_axis { double lo, hi; } svg_axis;

static double svg_x(svg_axis a, double v) { return SVG_L + (v - a.lo) / (a.hi - a.lo) * (SVG_W - SVG_L - SVG_R); }
static double svg_y(svg_axis a, double v) { return SVG_H - SVG_B - (v - a.lo) / (a.hi - a.lo) * (SVG_H - SVG_T - SVG_B); }

/* Opens <div class="chart" role="img" aria-label="title"><svg> of w × h
 * with the title drawn at the top (characters as &#xNN; references, the
 * way the PLplot charts write text). */
static void svg_open(dm_str *s, const char *title, double w, double h)
{
    dm_str_cat(s, "<div class=\"chart\" role=\"img\" aria-label=\"");
    dm_str_cat_html(s, title);
    dm_str_printf(s, "\"><svg viewBox=\"0 0 %.0f %.0f\" width=\"%.0f\" font-family=\"sans-serif\" "
                     "font-size=\"11\"><text x=\"4\" y=\"12\" font-weight=\"bold\">", w, h, w);
    for (const unsigned char *c = (const unsigned char *)title; *c; c++)
        dm_str_printf(s, "&#x%x;", (unsigned)*c);
    dm_str_cat(s, "</text>");
}

/* Five ticks of each axis with their numbers, and the axis titles. */
static void svg_axes(dm_str *s, svg_axis ax, svg_axis ay, const char *xt, const char *yt)
{
    dm_str_printf(s, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#888\"/>",
                  SVG_L, SVG_T, SVG_W - SVG_L - SVG_R, SVG_H - SVG_T - SVG_B);
    for (int k = 0; k <= 4; k++) {
        double vx = ax.lo + (ax.hi - ax.lo) * k / 4, vy = ay.lo + (ay.hi - ay.lo) * k / 4;
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%.3g</text>",
                      svg_x(ax, vx), SVG_H - SVG_B + 14, vx);
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.3g</text>",
                      SVG_L - 4, svg_y(ay, vy) + 4, vy);
    }
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", (SVG_L + SVG_W - SVG_R) / 2, SVG_H - 8);
    dm_str_cat_html(s, xt);
    dm_str_printf(s, "</text><text x=\"12\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 12 %.1f)\">",
                  (SVG_T + SVG_H - SVG_B) / 2, (SVG_T + SVG_H - SVG_B) / 2);
    dm_str_cat_html(s, yt);
    dm_str_cat(s, "</text>");
}

/* The hover title of configuration c: label, time with CI, error. */
static void svg_title(dm_str *s, const dm_run_result *run, const dm_config_result *c, double err,
                      report_metric m)
{
    const dm_counter_result *t = report__frame_time(c);
    dm_str label = {0};
    report__config_label(run, c, &label);
    dm_str_cat(s, "<title>");
    dm_str_cat_html(s, dm_str_get(&label));
    dm_str_printf(s, ": %.3f ms [%.3f, %.3f], %s %.4g</title>", t->median / 1e6, t->ci_lo / 1e6,
                  t->ci_hi / 1e6, report_metric_name(m), err);
    dm_str_free(&label);
}

static void svg_scatter(dm_str *s, const dm_run_result *run, const char *scene)
{
    size_t cap = run->n_configs + 1, *idx = dm_xcalloc(cap, sizeof *idx), *front;
    double *x = dm_xcalloc(cap, sizeof *x), *y = dm_xcalloc(cap, sizeof *y);
    report_metric m = report_metric_of_run(run);
    size_t n = report__pareto_points(run, scene, m, idx, x, y), nf = report__pareto(run, scene, &front);
    svg_axis ax = {0, 0}, ay = {INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++) {
        const dm_counter_result *t = report__frame_time(&run->configs[idx[i]]);
        ax.hi = fmax(ax.hi, isfinite(t->ci_hi) ? t->ci_hi / 1e6 : x[i] / 1e6);
        y[i] = report_metric_shown(&run->configs[idx[i]].quality, m);
        ay.lo = isfinite(y[i]) ? fmin(ay.lo, y[i]) : ay.lo;
        ay.hi = isfinite(y[i]) ? fmax(ay.hi, y[i]) : ay.hi;
    }
    ax.hi = ax.hi > 0 ? ax.hi * 1.06 : 1;
    ay.lo = m == REPORT_METRIC_PSNR && isfinite(ay.lo) ? ay.lo - 1 : 0;   /* errors from 0, dB not */
    ay.hi = isfinite(ay.hi) && ay.hi > ay.lo ? ay.hi + (ay.hi - ay.lo) * 0.12 : ay.lo + 1;
    for (size_t i = 0; i < n; i++)   /* identical image (PSNR +inf): at the top edge */
        y[i] = isfinite(y[i]) ? y[i] : ay.hi;
    if (n) {
        dm_str title = {0};
        dm_str_printf(&title, "Error vs time: %s", scene);
        svg_open(s, dm_str_get(&title), SVG_W, SVG_H);
        dm_str_free(&title);
        dm_str cap_x = {0}, cap_y = {0};
        dm_str_printf(&cap_x, "median frame time, ms (whisker: 95%% CI)");
        dm_str_printf(&cap_y, "%s", report_metric_label(m));
        svg_axes(s, ax, ay, dm_str_get(&cap_x), dm_str_get(&cap_y));
        dm_str_free(&cap_x);
        dm_str_free(&cap_y);
        dm_str_cat(s, "<polyline fill=\"none\" stroke=\"#2a7\" stroke-width=\"1.5\" points=\"");
        for (size_t k = 0; k < nf; k++) {
            const dm_config_result *c = &run->configs[front[k]];
            double v = report_metric_shown(&c->quality, m);
            dm_str_printf(s, "%.1f,%.1f ", svg_x(ax, report__frame_time(c)->median / 1e6),
                          svg_y(ay, isfinite(v) ? v : ay.hi));
        }
        dm_str_cat(s, "\"/>");
    }
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[idx[i]];
        const dm_counter_result *t = report__frame_time(c);
        int on = 0;
        for (size_t k = 0; k < nf; k++)
            on |= front[k] == idx[i];
        double px = svg_x(ax, x[i] / 1e6), py = svg_y(ay, y[i]);
        dm_str_cat(s, "<g>");
        svg_title(s, run, c, y[i], m);
        if (isfinite(t->ci_lo) && isfinite(t->ci_hi))
            dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#777\"/>",
                          svg_x(ax, t->ci_lo / 1e6), svg_x(ax, t->ci_hi / 1e6), py, py);
        dm_str_printf(s, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\" stroke=\"#164\"/>", px, py,
                      on ? "#2a7" : "#fff");
        int right = px > SVG_W - SVG_R - 30;
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\">%zu</text></g>",
                      px + (right ? -6 : 6), py - 5 < SVG_T + 10 ? py + 14 : py - 5,
                      right ? "end" : "start", i + 1);
    }
    if (n) {
        dm_str_cat(s, "</svg></div>\n<ol class=\"const legend\">");
        for (size_t i = 0; i < n; i++) {
            dm_str label = {0};
            report__config_label(run, &run->configs[idx[i]], &label);
            dm_str_cat(s, "<li>");
            dm_str_cat_html(s, dm_str_get(&label));
            dm_str_cat(s, "</li>");
            dm_str_free(&label);
        }
        dm_str_cat(s, "</ol>\n");
    }
    free(idx);
    free(x);
    free(y);
    free(front);
}

static void svg_bars(dm_str *s, const dm_run_result *run, const char *scene)
{
    size_t *rows, nr = report__scene_rows(run, scene, &rows), n = 0, longest = 0;
    double hi = 0;
    for (size_t i = 0; i < nr; i++) {
        const dm_counter_result *t = report__frame_time(&run->configs[rows[i]]);
        if (!t)
            continue;
        dm_str label = {0};
        report__config_label(run, &run->configs[rows[i]], &label);
        longest = strlen(dm_str_get(&label)) > longest ? strlen(dm_str_get(&label)) : longest;
        dm_str_free(&label);
        hi = fmax(hi, isfinite(t->ci_hi) ? t->ci_hi : t->median);
        rows[n++] = rows[i];
    }
    if (!n) {
        free(rows);
        return;
    }
    double lw = longest * SVG_CHAR_W + 12, bw = 420, rowh = 18, w = lw + bw + 70, h = n * rowh + 48;
    hi = hi / 1e6 * 1.04;
    dm_str title = {0};
    dm_str_printf(&title, "Time per configuration: %s", scene);
    svg_open(s, dm_str_get(&title), fmax(w, (double)title.len * SVG_CHAR_W * 1.2 + 8), h);
    dm_str_free(&title);
    dm_str_printf(s, "<text x=\"%.1f\" y=\"28\">median frame time, ms, this scene only "
                     "(whisker: 95%% CI)</text>", lw);
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        const dm_counter_result *t = report__frame_time(c);
        double y = 36 + i * rowh, x1 = lw + t->median / 1e6 / hi * bw;
        dm_str label = {0};
        report__config_label(run, c, &label);
        dm_str_printf(s, "<g><title>%.3f ms [%.3f, %.3f]</title><text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">",
                      t->median / 1e6, t->ci_lo / 1e6, t->ci_hi / 1e6, lw - 6, y + 11);
        dm_str_cat_html(s, dm_str_get(&label));
        dm_str_printf(s, "</text><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"12\" fill=\"#7aa6d8\"/>",
                      lw, y + 2, x1 - lw);
        if (isfinite(t->ci_lo) && isfinite(t->ci_hi))
            dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#333\"/>",
                          lw + t->ci_lo / 1e6 / hi * bw, lw + t->ci_hi / 1e6 / hi * bw, y + 8, y + 8);
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\">%.3g</text></g>",
                      lw + fmax(t->ci_hi / 1e6, t->median / 1e6) / hi * bw + 4, y + 11, t->median / 1e6);
        dm_str_free(&label);
    }
    dm_str_cat(s, "</svg></div>\n");
    free(rows);
}

void report__svg_scene(dm_str *s, const dm_run_result *run, const char *scene)
{
    svg_scatter(s, run, scene);
    svg_bars(s, run, scene);
}
