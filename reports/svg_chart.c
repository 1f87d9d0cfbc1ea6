/* svg_chart.c — the per-scene charts written as SVG by hand, so every label
 * is placed and sized by us and none is clipped:
 *  - quality vs time, titled by the metric: one point per configuration at
 *    (median ms, the metric's value) with a horizontal whisker for the 95 %
 *    CI of the median, its colour and marker by technique family (legend in
 *    the corner), filled on the front, its label beside it where there is
 *    room (greedy placement, the front first) and a hover title; the time
 *    axis is log10 when it spans more than a decade; ticks are round
 *    (1-2-5);
 *  - time per configuration: one horizontal bar per configuration of the
 *    scene (never pooled across scenes), fastest first, with its CI whisker
 *    and its full label left of the bar (the SVG is as wide as the longest
 *    label needs);
 *  - frame time along a camera path, per configuration on one: the
 *    per-frame median of the replays against the frame index, the replays'
 *    min–max as a band, p50 and p99 as dashed lines, the stutters marked.
 * Both read the report model only: the scene's rows and front, each row's
 * label, frame time, texts, error and family.
 */
#include "reports/report_internal.h"
#include "reports/report_model.h"

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

/* Characters (not bytes) of UTF-8 text, for its drawn width. */
static size_t svg_chart__chars(const char *t)
{
    size_t n = 0;
    for (; *t; t++)
        n += ((unsigned char)*t & 0xC0) != 0x80;
    return n;
}

/* An axis: linear, or log10 when its values span more than a decade. */
typedef struct svg_axis { double lo, hi; int log; } svg_axis;

static double svg_chart__t(svg_axis a, double v)
{
    return a.log ? (log10(v) - log10(a.lo)) / (log10(a.hi) - log10(a.lo)) : (v - a.lo) / (a.hi - a.lo);
}
static double svg_chart__x(svg_axis a, double v)
{
    return SVG_L + svg_chart__t(a, v) * (SVG_W - SVG_L - SVG_R);
}

static double svg_chart__y(svg_axis a, double v)
{
    return SVG_H - SVG_B - svg_chart__t(a, v) * (SVG_H - SVG_T - SVG_B);
}

/* Opens <div class="chart" role="img" aria-label="what: label"><svg> of
 * w × h with that title drawn at the top. */
static void svg_chart__open(dm_str *s, const char *what, const char *label, double w, double h)
{
    dm_str_cat(s, "<div class=\"chart\" role=\"img\" aria-label=\"");
    dm_str_cat_html(s, what);
    dm_str_cat(s, ": ");
    dm_str_cat_html(s, label);
    dm_str_printf(s, "\"><svg viewBox=\"0 0 %.0f %.0f\" width=\"%.0f\" font-family=\"sans-serif\" "
                     "font-size=\"11\"><text x=\"4\" y=\"12\" font-weight=\"bold\">", w, h, w);
    dm_str_cat_html(s, what);
    dm_str_cat(s, ": ");
    dm_str_cat_html(s, label);
    dm_str_cat(s, "</text>");
}

/* Round tick values of an axis into v (room for 32): 1-2-5 per decade on a
 * log axis, else a 1, 2 or 5 × 10^k step giving four to eight ticks. */
static size_t svg_chart__ticks(svg_axis a, double *v)
{
    size_t n = 0;
    if (a.log) {
        for (double d = pow(10, floor(log10(a.lo))); d <= a.hi && n < 30; d *= 10)
            for (int k = 0; k < 3; k++) {
                double t = d * (k == 0 ? 1 : k == 1 ? 2 : 5);
                if (t >= a.lo && t <= a.hi)
                    v[n++] = t;
            }
        return n;
    }
    double raw = (a.hi - a.lo) / 5, mag = pow(10, floor(log10(raw))), step = mag;
    step = raw / mag >= 5 ? 5 * mag : raw / mag >= 2 ? 2 * mag : mag;
    for (double t = ceil(a.lo / step) * step; t <= a.hi + step * 1e-9 && n < 30; t += step)
        v[n++] = fabs(t) < step * 1e-9 ? 0 : t;
    return n;
}

/* The ticks of both axes with their numbers (%g: round values print
 * short), and the axis titles. */
static void svg_chart__axes(dm_str *s, svg_axis ax, svg_axis ay, const char *xt, const char *yt)
{
    double v[32];
    dm_str_printf(s, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#888\"/>",
                  SVG_L, SVG_T, SVG_W - SVG_L - SVG_R, SVG_H - SVG_T - SVG_B);
    for (size_t k = 0, n = svg_chart__ticks(ax, v); k < n; k++)
        dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#eee\"/>"
                         "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>",
                      svg_chart__x(ax, v[k]), svg_chart__x(ax, v[k]), SVG_T, SVG_H - SVG_B,
                      svg_chart__x(ax, v[k]), SVG_H - SVG_B + 14, v[k]);
    for (size_t k = 0, n = svg_chart__ticks(ay, v); k < n; k++)
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>", SVG_L - 4,
                      svg_chart__y(ay, v[k]) + 4, v[k]);
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", (SVG_L + SVG_W - SVG_R) / 2, SVG_H - 8);
    dm_str_cat_html(s, xt);
    dm_str_printf(s, "</text><text x=\"12\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 12 %.1f)\">",
                  (SVG_T + SVG_H - SVG_B) / 2, (SVG_T + SVG_H - SVG_B) / 2);
    dm_str_cat_html(s, yt);
    dm_str_cat(s, "</text>");
}

/* The hover title of a row: label, time with CI, the metric's value. */
static void svg_chart__title(dm_str *s, const report_model_row *r, double shown, report_metric m)
{
    dm_str text = {0};
    dm_str_printf(&text, "%s: %s, %s %.4g", r->label, r->time_ci_text, report_metric_name(m), shown);
    dm_str_cat(s, "<title>");
    dm_str_cat_html(s, dm_str_get(&text));
    dm_str_cat(s, "</title>");
    dm_str_free(&text);
}

/* The points of one scene's scatter: rows with a frame time and a finite
 * error, fastest first (their row indexes), median ms, shown error (an
 * infinite PSNR at the top edge), both axes and the label boxes placed so
 * far (x0, y0, x1, y1 each). */
typedef struct svg_points {
    size_t n, *idx, nbox;
    double *x, *y, *box;
    svg_axis ax, ay;
    report_metric m;
} svg_points;

static void svg_chart__points_load(svg_points *p, const report_model *m, const report_model_scene *sc)
{
    size_t cap = sc->n_rows + 1;
    p->idx = dm_xcalloc(cap, sizeof *p->idx);
    p->x = dm_xcalloc(cap, sizeof *p->x);
    p->y = dm_xcalloc(cap, sizeof *p->y);
    p->box = dm_xcalloc(cap * 2 * 4, sizeof *p->box);
    p->nbox = p->n = 0;
    p->m = m->metric;
    p->ax = (svg_axis){INFINITY, 0, 0};
    p->ay = (svg_axis){INFINITY, -INFINITY, 0};
    for (size_t i = 0; i < sc->n_rows; i++) {
        const report_model_row *r = &m->rows[sc->rows[i]];
        const dm_counter_result *t = r->frame_time;
        if (!t || !isfinite(r->error))
            continue;
        size_t k = p->n++;
        p->idx[k] = sc->rows[i];
        p->x[k] = t->median / 1e6;
        p->ax.hi = fmax(p->ax.hi, isfinite(t->ci_hi) ? t->ci_hi / 1e6 : p->x[k]);
        p->ax.lo = fmin(p->ax.lo, isfinite(t->ci_lo) && t->ci_lo > 0 ? t->ci_lo / 1e6 : p->x[k]);
        p->y[k] = r->shown;
        p->ay.lo = isfinite(p->y[k]) ? fmin(p->ay.lo, p->y[k]) : p->ay.lo;
        p->ay.hi = isfinite(p->y[k]) ? fmax(p->ay.hi, p->y[k]) : p->ay.hi;
    }
    p->ax.log = p->ax.lo > 0 && p->ax.hi > 10 * p->ax.lo;
    p->ax.lo = p->ax.log ? p->ax.lo / 1.15 : 0;
    p->ax.hi = p->ax.hi > 0 ? p->ax.hi * (p->ax.log ? 1.15 : 1.06) : 1;
    p->ay.lo = p->m == REPORT_METRIC_PSNR && isfinite(p->ay.lo) ? p->ay.lo - 1 : 0;   /* dB not from 0 */
    p->ay.hi = isfinite(p->ay.hi) && p->ay.hi > p->ay.lo ? p->ay.hi + (p->ay.hi - p->ay.lo) * 0.12
                                                         : p->ay.lo + 1;
    for (size_t i = 0; i < p->n; i++)
        p->y[i] = isfinite(p->y[i]) ? p->y[i] : p->ay.hi;
}

static void svg_chart__points_free(svg_points *p)
{
    free(p->idx);
    free(p->x);
    free(p->y);
    free(p->box);
}

/* Colour and marker per family (recommend_family order: unlit, fragment,
 * vertex, tessellation): colour-blind-safe hues, and a shape each so the
 * families differ in grey print too. */
static const char *const svg_family_colour[RECOMMEND_FAMILY_COUNT] = {"#777777", "#0072b2", "#d55e00", "#7b3294"};

static void svg_chart__marker(dm_str *s, recommend_family f, double x, double y, int filled)
{
    const char *c = svg_family_colour[f];
    const char *fill = filled ? c : "#fff";
    if (f == RECOMMEND_VERTEX)
        dm_str_printf(s, "<rect x=\"%.1f\" y=\"%.1f\" width=\"8\" height=\"8\"", x - 4, y - 4);
    else if (f == RECOMMEND_TESSELLATION)
        dm_str_printf(s, "<path d=\"M%.1f %.1fl5 9h-10z\"", x, y - 5);
    else if (f == RECOMMEND_UNLIT)
        dm_str_printf(s, "<path d=\"M%.1f %.1fl5 5l-5 5l-5 -5z\"", x, y - 5);
    else
        dm_str_printf(s, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4.5\"", x, y);
    dm_str_printf(s, " fill=\"%s\" stroke=\"%s\" stroke-width=\"1.5\"/>", fill, c);
}

/* 1 when the box (x0, y0)–(x1, y1) overlaps a placed label or leaves the plot. */
static int svg_chart__box_taken(const svg_points *p, double x0, double y0, double x1, double y1)
{
    if (x0 < SVG_L + 1 || x1 > SVG_W - 2 || y0 < SVG_T + 1 || y1 > SVG_H - SVG_B - 1)
        return 1;
    for (size_t k = 0; k < p->nbox; k++) {
        const double *b = &p->box[4 * k];
        if (x0 < b[2] && b[0] < x1 && y0 < b[3] && b[1] < y1)
            return 1;
    }
    return 0;
}

/* Places the label of a point at (px, py): beside it right or left, a line
 * up or down, farther out when taken; the markers are boxes too.  Returns
 * 0 and sets *tx, *ty, *end when a place is free. */
static int svg_chart__place(svg_points *p, double px, double py, double w, double *tx, double *ty, int *end)
{
    static const double dy[] = {4, -6, 14, -16, 24, -26, 34, -36};
    for (size_t k = 0; k < sizeof dy / sizeof *dy; k++)
        for (int side = 0; side < 2; side++) {
            double x0 = side ? px - 8 - w : px + 8, y1 = py + dy[k], y0 = y1 - 10;
            if (svg_chart__box_taken(p, x0, y0, x0 + w, y1 + 1))
                continue;
            double *b = &p->box[4 * p->nbox++];
            b[0] = x0, b[1] = y0, b[2] = x0 + w, b[3] = y1 + 1;
            *tx = side ? px - 8 : px + 8, *ty = y1, *end = side;
            return 0;
        }
    return -1;
}

/* Point i: hover title, CI whisker, the family's marker (filled on the front). */
static void svg_chart__point(dm_str *s, const report_model *m, svg_points *p, size_t i)
{
    const report_model_row *r = &m->rows[p->idx[i]];
    const dm_counter_result *t = r->frame_time;
    double px = svg_chart__x(p->ax, p->x[i]), py = svg_chart__y(p->ay, p->y[i]);
    dm_str_cat(s, "<g>");
    svg_chart__title(s, r, p->y[i], p->m);
    if (isfinite(t->ci_lo) && isfinite(t->ci_hi) && t->ci_lo > 0)
        dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#999\"/>",
                      svg_chart__x(p->ax, t->ci_lo / 1e6), svg_chart__x(p->ax, t->ci_hi / 1e6), py, py);
    svg_chart__marker(s, r->family, px, py, r->front);
    dm_str_cat(s, "</g>");
    double *b = &p->box[4 * p->nbox++];
    b[0] = px - 5, b[1] = py - 5, b[2] = px + 5, b[3] = py + 5;
}

/* The label beside point i, or none when no place is free (its hover
 * title still names it; the table below lists every configuration). */
static void svg_chart__point_label(dm_str *s, const report_model *m, svg_points *p, size_t i)
{
    const char *label = m->rows[p->idx[i]].label;
    double tx, ty;
    int end;
    if (svg_chart__place(p, svg_chart__x(p->ax, p->x[i]), svg_chart__y(p->ay, p->y[i]),
                         (double)svg_chart__chars(label) * 6.4, &tx, &ty, &end) == 0) {
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\"%s>", tx, ty,
                      end ? " text-anchor=\"end\"" : "");
        dm_str_cat_html(s, label);
        dm_str_cat(s, "</text>");
    }
}

/* The family legend in the top right corner of the plot. */
static void svg_chart__legend(dm_str *s, const report_model *m, const svg_points *p)
{
    int present[RECOMMEND_FAMILY_COUNT] = {0};
    for (size_t i = 0; i < p->n; i++)
        present[m->rows[p->idx[i]].family] = 1;
    double x = SVG_W - SVG_R - 6;
    for (int f = RECOMMEND_FAMILY_COUNT - 1; f >= 0; f--) {
        if (!present[f])
            continue;
        const char *name = recommend_family_name((recommend_family)f);
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" fill=\"%s\">%s</text>", x,
                      SVG_T - 8, svg_family_colour[f], name);
        x -= strlen(name) * 6.2 + 4;
        svg_chart__marker(s, (recommend_family)f, x - 5, SVG_T - 12, 1);
        x -= 18;
    }
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" fill=\"#555\">filled: on the "
                     "front</text>", x, SVG_T - 8);
}

static void svg_chart__scatter(dm_str *s, const report_model *m, const report_model_scene *sc)
{
    svg_points p;
    svg_chart__points_load(&p, m, sc);
    if (p.n) {
        dm_str what = {0};
        dm_str_printf(&what, "%s vs time", report_metric_label(p.m));
        svg_chart__open(s, dm_str_get(&what), sc->label, SVG_W, SVG_H);
        dm_str_free(&what);
        svg_chart__axes(s, p.ax, p.ay, p.ax.log ? "median frame time, ms, log scale (whisker: 95% CI)"
                                         : "median frame time, ms (whisker: 95% CI)",
                 report_metric_label(p.m));
        dm_str_printf(s, "<polyline fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 3\" points=\"");
        for (size_t k = 0; k < sc->n_front; k++)
            for (size_t i = 0; i < p.n; i++)
                if (p.idx[i] == sc->front[k])
                    dm_str_printf(s, "%.1f,%.1f ", svg_chart__x(p.ax, p.x[i]), svg_chart__y(p.ay, p.y[i]));
        dm_str_cat(s, "\"/>");
        for (size_t i = 0; i < p.n; i++)
            svg_chart__point(s, m, &p, i);
        for (size_t k = 0; k < sc->n_front; k++)   /* the front's labels first: they matter most */
            for (size_t i = 0; i < p.n; i++)
                if (p.idx[i] == sc->front[k])
                    svg_chart__point_label(s, m, &p, i);
        for (size_t i = 0; i < p.n; i++)
            if (!m->rows[p.idx[i]].front)
                svg_chart__point_label(s, m, &p, i);
        svg_chart__legend(s, m, &p);
        dm_str_cat(s, "</svg></div>\n");
    }
    svg_chart__points_free(&p);
}

static void svg_chart__bars(dm_str *s, const report_model *m, const report_model_scene *sc)
{
    size_t *rows = dm_xcalloc(sc->n_rows + 1, sizeof *rows), n = 0, longest = 0;
    double hi = 0;
    for (size_t i = 0; i < sc->n_rows; i++) {
        const report_model_row *r = &m->rows[sc->rows[i]];
        if (!r->frame_time)
            continue;
        longest = strlen(r->label) > longest ? strlen(r->label) : longest;
        hi = fmax(hi, isfinite(r->frame_time->ci_hi) ? r->frame_time->ci_hi : r->frame_time->median);
        rows[n++] = sc->rows[i];
    }
    if (!n) {
        free(rows);
        return;
    }
    double lw = longest * SVG_CHAR_W + 12, bw = 420, rowh = 18, w = lw + bw + 70, h = n * rowh + 48;
    hi = hi / 1e6 * 1.04;
    const char *what = "Time per configuration";
    double tw = (double)(svg_chart__chars(what) + 2 + svg_chart__chars(sc->label)) * SVG_CHAR_W * 1.2 + 8;
    svg_chart__open(s, what, sc->label, fmax(w, tw), h);
    dm_str_printf(s, "<text x=\"%.1f\" y=\"28\">median frame time, ms, this scene only "
                     "(whisker: 95%% CI)</text>", lw);
    for (size_t i = 0; i < n; i++) {
        const report_model_row *r = &m->rows[rows[i]];
        const dm_counter_result *t = r->frame_time;
        double y = 36 + i * rowh, x1 = lw + t->median / 1e6 / hi * bw;
        dm_str_printf(s, "<g><title>%.3f ms [%.3f, %.3f]</title><text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">",
                      t->median / 1e6, t->ci_lo / 1e6, t->ci_hi / 1e6, lw - 6, y + 11);
        dm_str_cat_html(s, r->label);
        dm_str_printf(s, "</text><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"12\" fill=\"#7aa6d8\"/>",
                      lw, y + 2, x1 - lw);
        if (isfinite(t->ci_lo) && isfinite(t->ci_hi))
            dm_str_printf(s, "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#333\"/>",
                          lw + t->ci_lo / 1e6 / hi * bw, lw + t->ci_hi / 1e6 / hi * bw, y + 8, y + 8);
        dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\">%s</text></g>",
                      lw + fmax(t->ci_hi / 1e6, t->median / 1e6) / hi * bw + 4, y + 11, r->ms_text);
    }
    dm_str_cat(s, "</svg></div>\n");
    free(rows);
}

/* A move (M) or line (L) to frame f's value v of a path plot, or nothing
 * for a NaN (the next finite value starts a new segment: *pen 0). */
static void svg_chart__path_to(dm_str *s, svg_axis ax, svg_axis ay, size_t f, double v, int *pen)
{
    if (!isfinite(v)) {
        *pen = 0;
        return;
    }
    dm_str_printf(s, "%s%.1f,%.1f ", *pen ? "L" : "M", svg_chart__x(ax, (double)f), svg_chart__y(ay, v));
    *pen = 1;
}

/* A horizontal line across the plot at v ms with its name and value at
 * the right end ("p99 3.06"). */
static void svg_chart__path_level(dm_str *s, svg_axis ax, svg_axis ay, const char *name, double v,
                                  const char *colour)
{
    if (!isfinite(v))
        return;
    double y = svg_chart__y(ay, v);
    dm_str_printf(s, "<line class=\"path-%s\" x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" "
                     "stroke=\"%s\" stroke-dasharray=\"5 3\"/><text x=\"%.1f\" y=\"%.1f\" "
                     "text-anchor=\"end\" fill=\"%s\">%s %.3g</text>",
                  name, svg_chart__x(ax, ax.lo), svg_chart__x(ax, ax.hi), y, y, colour,
                  svg_chart__x(ax, ax.hi) - 3, y - 3, colour, name, v);
}

void report__svg_path(dm_str *s, const report_model_row *r)
{
    const dm_path_series *p = &r->config->path;
    if (!r->path_ms || !p->frames)
        return;
    double hi = p->p99 / 1e6;
    for (size_t f = 0; f < p->frames; f++)
        if (isfinite(r->path_hi_ms[f]) && !(r->path_hi_ms[f] <= hi))
            hi = r->path_hi_ms[f];
    if (!(hi > 0))
        return;   /* no frame has a time */
    svg_axis ax = {0, p->frames > 1 ? (double)(p->frames - 1) : 1, 0}, ay = {0, hi * 1.08, 0};
    svg_chart__open(s, "Frame time along the path", r->label, SVG_W, SVG_H);
    svg_chart__axes(s, ax, ay, "frame along the path", "frame time, ms");
    /* the replays' min–max band: up along the max, back along the min */
    dm_str_cat(s, "<path class=\"path-band\" fill=\"#c9dcf0\" stroke=\"none\" d=\"");
    int pen = 0;
    for (size_t f = 0; f < p->frames; f++)
        svg_chart__path_to(s, ax, ay, f, r->path_hi_ms[f], &pen);
    for (size_t f = p->frames; f-- > 0;)
        svg_chart__path_to(s, ax, ay, f, r->path_lo_ms[f], &pen);
    dm_str_cat(s, "Z\"/>");
    svg_chart__path_level(s, ax, ay, "p50", p->p50 / 1e6, "#2a7a2a");
    svg_chart__path_level(s, ax, ay, "p99", p->p99 / 1e6, "#b85c00");
    /* the per-frame medians, their values also as data (the tests read them) */
    dm_str_cat(s, "<path class=\"path-median\" fill=\"none\" stroke=\"#1f4e8c\" stroke-width=\"1.5\" "
                  "data-ms=\"");
    for (size_t f = 0; f < p->frames; f++)
        dm_str_printf(s, f ? " %.9g" : "%.9g", r->path_ms[f]);
    dm_str_cat(s, "\" d=\"");
    pen = 0;
    for (size_t f = 0; f < p->frames; f++)
        svg_chart__path_to(s, ax, ay, f, r->path_ms[f], &pen);
    dm_str_cat(s, "\"/>");
    for (size_t i = 0; i < p->n_stutters; i++) {
        long f = p->stutter_at[i];
        if (f < 0 || (size_t)f >= p->frames || !isfinite(r->path_ms[f]))
            continue;
        dm_str_printf(s, "<circle class=\"path-stutter\" data-frame=\"%ld\" cx=\"%.1f\" cy=\"%.1f\" r=\"4\" "
                         "fill=\"#c0392b\"><title>frame %ld: %.3f ms, a stutter (over 2 × p50)</title></circle>",
                      f, svg_chart__x(ax, (double)f), svg_chart__y(ay, r->path_ms[f]), f, r->path_ms[f]);
    }
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" fill=\"#555\">line: median of %zu "
                     "replay%s; band: their min–max; red: stutters</text></svg></div>\n",
                  SVG_W - SVG_R, SVG_T - 8, p->replays, p->replays == 1 ? "" : "s");
}

/* One series of the quality plot: a line through the finite values of
 * err(v[i]) at frames i × every, a dot on each; v itself as data (name). */
static void svg_chart__quality_series(dm_str *s, svg_axis ax, svg_axis ay, const dm_path_quality *q,
                                      const double *v, int one_minus, const char *name, const char *colour)
{
    dm_str_printf(s, "<path class=\"path-%s\" fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" data-%s=\"",
                  name, colour, name);
    for (size_t i = 0; i < q->n; i++)
        dm_str_printf(s, i ? " %.9g" : "%.9g", v[i]);
    dm_str_cat(s, "\" d=\"");
    int pen = 0;
    for (size_t i = 0; i < q->n; i++)
        svg_chart__path_to(s, ax, ay, i * (size_t)q->every, one_minus ? 1 - v[i] : v[i], &pen);
    dm_str_cat(s, "\"/>");
    for (size_t i = 0; i < q->n; i++)
        if (isfinite(v[i]))
            dm_str_printf(s, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"%s\"><title>frame %zu: %s "
                             "%.4g</title></circle>", svg_chart__x(ax, (double)(i * (size_t)q->every)),
                          svg_chart__y(ay, one_minus ? 1 - v[i] : v[i]), colour, i * (size_t)q->every,
                          one_minus ? "SSIM" : "FLIP", v[i]);
}

void report__svg_path_quality(dm_str *s, const report_model_row *r)
{
    const dm_path_quality *q = &r->config->path_quality;
    if (!q->present || !q->n || q->every < 1 || q->frames < 1)
        return;
    double hi = 0;
    for (size_t i = 0; i < q->n; i++) {
        if (isfinite(q->flip[i]) && q->flip[i] > hi)
            hi = q->flip[i];
        if (isfinite(q->ssim[i]) && 1 - q->ssim[i] > hi)
            hi = 1 - q->ssim[i];
    }
    svg_axis ax = {0, q->frames > 1 ? (double)(q->frames - 1) : 1, 0}, ay = {0, hi > 0 ? hi * 1.1 : 1, 0};
    svg_chart__open(s, "Error at the reference frames", r->label, SVG_W, SVG_H);
    svg_chart__axes(s, ax, ay, "frame along the path", "error against the reference");
    if (isfinite(q->popping) && q->popping_frame >= 0 && q->popping_frame < q->frames) {
        double x = svg_chart__x(ax, (double)q->popping_frame);
        dm_str_printf(s, "<line class=\"path-popping\" x1=\"%.1f\" x2=\"%.1f\" y1=\"%.1f\" y2=\"%.1f\" "
                         "stroke=\"#c0392b\" stroke-dasharray=\"4 3\"/><text x=\"%.1f\" y=\"%.1f\" "
                         "text-anchor=\"%s\" fill=\"#c0392b\">popping %.3g (frame %ld)</text>",
                      x, x, SVG_T, SVG_H - SVG_B, x + (x > SVG_W / 2 ? -4 : 4), SVG_T + 12,
                      x > SVG_W / 2 ? "end" : "start", q->popping, q->popping_frame);
    }
    svg_chart__quality_series(s, ax, ay, q, q->flip, 0, "flip", "#1f4e8c");
    svg_chart__quality_series(s, ax, ay, q, q->ssim, 1, "ssim", "#2a7a2a");
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" fill=\"#555\"><tspan fill=\"#1f4e8c\">"
                     "FLIP mean</tspan> and <tspan fill=\"#2a7a2a\">1 − SSIM</tspan> at the reference "
                     "frames (every %ld)</text></svg></div>\n", SVG_W - SVG_R, SVG_T - 8, q->every);
}

void report__svg_motion_front(dm_str *s, const report_model *m, size_t si)
{
    const report_model_scene *sc = &m->scenes[si];
    if (sc->n_motion_points < 2)
        return;
    double tlo = INFINITY, thi = 0, ehi = 0;
    for (size_t i = 0; i < m->n_rows; i++) {
        const dm_config_result *c = m->rows[i].config;
        if (m->rows[i].scene != si || !c->path.frames || !c->path_quality.present ||
            !isfinite(c->path.p99) || !isfinite(c->path_quality.temporal_mean))
            continue;
        tlo = fmin(tlo, c->path.p99 / 1e6);
        thi = fmax(thi, c->path.p99 / 1e6);
        ehi = fmax(ehi, c->path_quality.temporal_mean);
    }
    double pad = (thi - tlo) * 0.08 + thi * 0.02;
    svg_axis ax = {fmax(0, tlo - pad), thi + pad * 3, 0}, ay = {0, ehi > 0 ? ehi * 1.1 : 1, 0};
    svg_chart__open(s, "In motion: temporal error vs p99 frame time", sc->label, SVG_W, SVG_H);
    svg_chart__axes(s, ax, ay, "p99 frame time along the path, ms", "temporal error, mean");
    dm_str_cat(s, "<polyline class=\"motion-front\" fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 3\" points=\"");
    for (size_t k = 0; k < sc->n_motion_front; k++) {
        const dm_config_result *c = m->rows[sc->motion_front[k]].config;
        dm_str_printf(s, "%.1f,%.1f ", svg_chart__x(ax, c->path.p99 / 1e6), svg_chart__y(ay, c->path_quality.temporal_mean));
    }
    dm_str_cat(s, "\"/>");
    for (size_t i = 0; i < m->n_rows; i++) {
        const report_model_row *r = &m->rows[i];
        const dm_config_result *c = r->config;
        if (r->scene != si || !c->path.frames || !c->path_quality.present || !isfinite(c->path.p99) ||
            !isfinite(c->path_quality.temporal_mean))
            continue;
        int on = 0;
        for (size_t k = 0; k < sc->n_motion_front; k++)
            on |= sc->motion_front[k] == i;
        double x = svg_chart__x(ax, c->path.p99 / 1e6), y = svg_chart__y(ay, c->path_quality.temporal_mean);
        dm_str_printf(s, "<g class=\"motion-point\"><title>");
        dm_str_cat_html(s, r->label);
        dm_str_printf(s, ": p99 %.3f ms, temporal error %.4g</title><circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" "
                         "fill=\"%s\" stroke=\"#1f4e8c\"/><text x=\"%.1f\" y=\"%.1f\">",
                      c->path.p99 / 1e6, c->path_quality.temporal_mean, x, y, on ? "#1f4e8c" : "#fff", x + 6, y - 5);
        dm_str_cat_html(s, r->technique);
        dm_str_cat(s, "</text></g>");
    }
    dm_str_printf(s, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" fill=\"#555\">filled: on the "
                     "front (lower and left is better)</text></svg></div>\n", SVG_W - SVG_R, SVG_T - 8);
}

void report__svg_scene(dm_str *s, const report_model *m, size_t si)
{
    svg_chart__scatter(s, m, &m->scenes[si]);
    svg_chart__bars(s, m, &m->scenes[si]);
}
