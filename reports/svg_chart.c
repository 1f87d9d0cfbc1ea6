/* svg_chart.c — the per-scene charts written as SVG by hand, so every label
 * is placed and sized by us and none is clipped:
 *  - error vs time: one point per configuration at (median ms, error) with
 *    a horizontal whisker for the 95 % CI of the median; each point carries
 *    a printed number (its row in the legend below the chart; points drawn
 *    on top of each other share one label, "3,4") and a hover title; front
 *    members are filled and joined by the front line;
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

/* The points of one scene's scatter: config indexes, median ms, shown
 * error (an infinite PSNR at the top edge), the front and both axes. */
typedef struct svg_points {
    size_t n, nf, *idx, *front;
    double *x, *y;
    svg_axis ax, ay;
    report_metric m;
} svg_points;

static void svg_points_load(svg_points *p, const dm_run_result *run, const char *scene)
{
    size_t cap = run->n_configs + 1;
    p->idx = dm_xcalloc(cap, sizeof *p->idx);
    p->x = dm_xcalloc(cap, sizeof *p->x);
    p->y = dm_xcalloc(cap, sizeof *p->y);
    p->m = report_metric_of_run(run);
    p->n = report__pareto_points(run, scene, p->m, p->idx, p->x, p->y);
    p->nf = report__pareto(run, scene, &p->front);
    p->ax = (svg_axis){0, 0};
    p->ay = (svg_axis){INFINITY, -INFINITY};
    for (size_t i = 0; i < p->n; i++) {
        const dm_counter_result *t = report__frame_time(&run->configs[p->idx[i]]);
        p->x[i] /= 1e6;
        p->ax.hi = fmax(p->ax.hi, isfinite(t->ci_hi) ? t->ci_hi / 1e6 : p->x[i]);
        p->y[i] = report_metric_shown(&run->configs[p->idx[i]].quality, p->m);
        p->ay.lo = isfinite(p->y[i]) ? fmin(p->ay.lo, p->y[i]) : p->ay.lo;
        p->ay.hi = isfinite(p->y[i]) ? fmax(p->ay.hi, p->y[i]) : p->ay.hi;
    }
    p->ax.hi = p->ax.hi > 0 ? p->ax.hi * 1.06 : 1;
    p->ay.lo = p->m == REPORT_METRIC_PSNR && isfinite(p->ay.lo) ? p->ay.lo - 1 : 0;   /* dB not from 0 */
    p->ay.hi = isfinite(p->ay.hi) && p->ay.hi > p->ay.lo ? p->ay.hi + (p->ay.hi - p->ay.lo) * 0.12
                                                         : p->ay.lo + 1;
    for (size_t i = 0; i < p->n; i++)
        p->y[i] = isfinite(p->y[i]) ? p->y[i] : p->ay.hi;
}

static void svg_points_free(svg_points *p)
{
    free(p->idx);
    free(p->x);
    free(p->y);
    free(p->front);
}

/* 1 when points i and j are drawn within 7 px of each other. */
static int svg_near(const svg_points *p, size_t i, size_t j)
{
    return fabs(svg_x(p->ax, p->x[i]) - svg_x(p->ax, p->x[j])) < 7 &&
           fabs(svg_y(p->ay, p->y[i]) - svg_y(p->ay, p->y[j])) < 7;
}

/* The printed number of point i: "3" or, for points drawn on top of each
 * other, "3,4" at the first of them and nothing at the others. */
static void svg_number(const svg_points *p, size_t i, dm_str *out)
{
    for (size_t j = 0; j < i; j++)
        if (svg_near(p, i, j))
            return;
    dm_str_printf(out, "%zu", i + 1);
    for (size_t j = i + 1; j < p->n; j++)
        if (svg_near(p, i, j))
            dm_str_printf(out, ",%zu", j + 1);
}

/* Point i: hover title, CI whisker, circle (filled on the front), number. */
static void svg_point(dm_str *s, const dm_run_result *run, const svg_points *p, size_t i)
{
    const dm_config_result *c = &run->configs[p->idx[i]];
    const dm_counter_result *t = report__frame_time(c);
    int on = 0;
    for (size_t k = 0; k < p->nf; k++)
        on |= p->front[k] == p->idx[i];
    double px = svg_x(p->ax, p->x[i]), py = svg_y(p->ay, p->y[i]);
    int right = px > SVG_W - SVG_R - 30;
    dm_str_cat(s, "<g>");
    svg_title(s, run, c, p->y[i], p->m);
    if (isfinite(t->ci_lo) && isfinite(t->ci_hi))
        dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#777\"/>",
                      svg_x(p->ax, t->ci_lo / 1e6), svg_x(p->ax, t->ci_hi / 1e6), py, py);
    dm_str_printf(s, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\" stroke=\"#164\"/>", px, py,
                  on ? "#2a7" : "#fff");
    dm_str num = {0};
    svg_number(p, i, &num);
    if (num.len)
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\">%s</text>",
                      px + (right ? -6 : 6), py - 5 < SVG_T + 10 ? py + 14 : py - 5,
                      right ? "end" : "start", dm_str_get(&num));
    dm_str_cat(s, "</g>");
    dm_str_free(&num);
}

/* The numbered legend under the chart: point i + 1 is configuration i. */
static void svg_legend(dm_str *s, const dm_run_result *run, const svg_points *p)
{
    dm_str_cat(s, "<ol class=\"const legend\">");
    for (size_t i = 0; i < p->n; i++) {
        dm_str label = {0};
        report__config_label(run, &run->configs[p->idx[i]], &label);
        dm_str_cat(s, "<li>");
        dm_str_cat_html(s, dm_str_get(&label));
        dm_str_cat(s, "</li>");
        dm_str_free(&label);
    }
    dm_str_cat(s, "</ol>\n");
}

static void svg_scatter(dm_str *s, const dm_run_result *run, const char *scene)
{
    svg_points p;
    svg_points_load(&p, run, scene);
    if (p.n) {
        dm_str title = {0};
        dm_str_printf(&title, "Error vs time: %s", scene);
        svg_open(s, dm_str_get(&title), SVG_W, SVG_H);
        dm_str_free(&title);
        svg_axes(s, p.ax, p.ay, "median frame time, ms (whisker: 95% CI)", report_metric_label(p.m));
        dm_str_cat(s, "<polyline fill=\"none\" stroke=\"#2a7\" stroke-width=\"1.5\" points=\"");
        for (size_t k = 0; k < p.nf; k++)
            for (size_t i = 0; i < p.n; i++)
                if (p.idx[i] == p.front[k])
                    dm_str_printf(s, "%.1f,%.1f ", svg_x(p.ax, p.x[i]), svg_y(p.ay, p.y[i]));
        dm_str_cat(s, "\"/>");
        for (size_t i = 0; i < p.n; i++)
            svg_point(s, run, &p, i);
        dm_str_cat(s, "</svg></div>\n");
        svg_legend(s, run, &p);
    }
    svg_points_free(&p);
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
