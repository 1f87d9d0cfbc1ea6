/* chart.c — charts for report.html, drawn with PLplot's SVG driver and
 * inlined into the page.
 *
 * Each chart is drawn into a temporary SVG file (PLplot writes files only),
 * read back, stripped of its XML prolog, DOCTYPE and namespace attributes
 * (not needed inline in HTML, and they would be the page's only URLs), and
 * appended.  Labels that come from the data are reduced to a safe character
 * set before PLplot sees them (PLplot treats '#' as an escape; its SVG
 * driver already writes text as character references).  Charts are
 * decoration: if PLplot cannot write one, a note replaces it.
 *
 * The per-scene charts read the report model only: its rows (run order,
 * labels, techniques, frame times) and the breakdown it chose for the
 * scene (breakdown.h); the fit plots read the run's fits.
 */
#include "reports/breakdown.h"
#include "reports/report_internal.h"
#include "reports/report_model.h"

#include <math.h>
#include <plplot/plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CHART_MAX_LABEL 64

/* Colours of stacked / grouped series (cmap0 indexes from CHART_SERIES_COL0). */
#define CHART_SERIES 6
#define CHART_SERIES_COL0 4
static const PLINT chart_series_rgb[CHART_SERIES][3] = {
    {150, 150, 150}, {40, 90, 200}, {230, 140, 20}, {60, 160, 80}, {200, 30, 30}, {120, 60, 170} };

typedef struct chart_frame {
    const char *title, *xlabel, *ylabel;
    double x0, x1, y0, y1;
    double bottom;               /* viewport bottom (room for vertical labels) */
    int categorical;             /* x is categories: no numeric x labels */
} chart_frame;

/* Copies text into out keeping letters, digits and " _-.,=/:()+" only. */
static void chart__safe_label(const char *text, char out[CHART_MAX_LABEL])
{
    size_t n = 0;
    for (const char *p = text ? text : ""; *p && n < CHART_MAX_LABEL - 1; p++)
        out[n++] = (strchr(" _-.,=/:()+", *p) || (*p >= '0' && *p <= '9') ||
                    (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z')) ? *p : '?';
    out[n] = '\0';
}

/* Range [lo, hi] of v padded by 8 %; a flat or empty range gets a width. */
static void chart__padded_range(const double *v, size_t n, double *lo, double *hi, int from_zero)
{
    double a = INFINITY, b = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i])) {
            a = fmin(a, v[i]);
            b = fmax(b, v[i]);
        }
    if (!isfinite(a))
        a = 0, b = 1;
    if (from_zero)
        a = fmin(a, 0);
    double pad = b > a ? (b - a) * 0.08 : (fabs(a) > 0 ? fabs(a) * 0.1 : 1);
    *lo = from_zero && a >= 0 ? a : a - pad;
    *hi = b + pad;
}

/* Starts a new PLplot stream drawing into file; black on white. */
static void chart__open(const char *file, const chart_frame *f)
{
    PLINT strm;
    plmkstrm(&strm);
    plsdev("svg");
    plsfnam(file);
    plspage(0, 0, 720, 420, 0, 0);
    plscolbg(255, 255, 255);
    plinit();
    plscol0(1, 0, 0, 0);
    plscol0(2, 200, 30, 30);
    plscol0(3, 40, 90, 200);
    for (PLINT k = 0; k < CHART_SERIES; k++)
        plscol0(CHART_SERIES_COL0 + k, chart_series_rgb[k][0], chart_series_rgb[k][1],
                chart_series_rgb[k][2]);
    plcol0(1);
    pladv(0);
    plvpor(0.1, 0.95, f->bottom > 0 ? f->bottom : 0.15, 0.9);
    plwind(f->x0, f->x1, f->y0, f->y1);
    plbox(f->categorical ? "bc" : "bcnst", 0, 0, "bcnstv", 0, 0);
    char t[CHART_MAX_LABEL];
    chart__safe_label(f->title, t);
    pllab(f->xlabel, f->ylabel, t);
}

/* The number of charts already in the document s: this chart's ordinal. */
static size_t chart__ordinal(const dm_str *s)
{
    size_t n = 0;
    for (const char *p = s->buf; p && (p = strstr(p, "<div class=\"chart\"")) != NULL; p++)
        n++;
    return n;
}

/* Appends svg with its ids made unique in the document: PLplot names the
 * clip path of every chart "text-clipping0", so each id and its url(#…)
 * references get the chart's ordinal k ("c3-text-clipping0"). */
static void chart__cat_ids(dm_str *s, const char *svg, size_t k)
{
    static const char id[] = "text-clipping";
    for (const char *p; (p = strstr(svg, id)) != NULL; svg = p + strlen(id)) {
        dm_str_catn(s, svg, (size_t)(p - svg));
        dm_str_printf(s, "c%zu-%s", k, id);
    }
    dm_str_cat(s, svg);
}

/* Ends the stream and appends its SVG (without prolog/namespaces) to s,
 * in a <div> whose aria-label is the chart's title as drawn. */
static void chart__close(dm_str *s, const char *file, const char *title)
{
    plend1();
    char *svg = NULL;
    size_t len = 0;
    const char *start = NULL;
    if (dm_read_file(file, &svg, &len) == 0)
        start = strstr(svg, "<svg");
    unlink(file);
    if (!start) {
        dm_str_cat(s, "<p class=\"missing\">chart unavailable (PLplot wrote no SVG)</p>\n");
        free(svg);
        return;
    }
    static const char *drop[] = {"xmlns:xlink=\"", "xmlns=\""};
    for (int k = 0; k < 2; k++) {
        char *a = strstr(svg, drop[k]);
        char *e = a ? strchr(a + strlen(drop[k]), '"') : NULL;
        if (e)
            memset(a, ' ', (size_t)(e + 1 - a));
    }
    char t[CHART_MAX_LABEL];
    chart__safe_label(title, t);
    size_t k = chart__ordinal(s);
    dm_str_printf(s, "<div class=\"chart\" role=\"img\" aria-label=\"%s\">", t);
    chart__cat_ids(s, start, k);
    dm_str_cat(s, "</div>\n");
    free(svg);
}

/* A fresh temporary file name for one chart, or NULL. */
static char *chart__tmpname(void)
{
    char *name = dm_xstrdup("/tmp/dmbench_chart_XXXXXX");
    int fd = mkstemp(name);
    if (fd < 0) {
        free(name);
        return NULL;
    }
    close(fd);
    return name;
}

/* ---- per scene: time vs tess_level, one line per mesh/technique ---------- */

/* The tess_level of row r when it is a timed configuration of scene si, else NULL. */
static const char *chart__tess_level(const report_model_row *r, size_t si)
{
    const dm_config_result *c = r->config;
    const char *L = dm_kv_get(c->params, c->n_params, "tess_level");
    return L && c->ok && r->frame_time && r->scene == si ? L : NULL;
}

/* Points of one (mesh, technique) series of scene si sorted by tess_level
 * (ties in run order): x, the median y and its 95 % CI [lo, hi] in ms (the
 * median where the CI is unknown). */
static size_t chart__tess_series(const report_model *m, size_t si, const char *mesh, const char *tech,
                          double *x, double *y, double *lo, double *hi)
{
    size_t n = 0;
    for (size_t i = 0; i < m->n_rows; i++) {
        const report_model_row *r = &m->rows[i];
        const char *L = chart__tess_level(r, si);
        const char *me = dm_kv_get(r->config->params, r->config->n_params, "mesh");
        if (!L || strcmp(me ? me : "", mesh) != 0 || strcmp(r->technique, tech) != 0)
            continue;
        size_t k = n++;
        for (; k > 0 && x[k - 1] > strtod(L, NULL); k--)
            x[k] = x[k - 1], y[k] = y[k - 1], lo[k] = lo[k - 1], hi[k] = hi[k - 1];
        const dm_counter_result *t = r->frame_time;
        x[k] = strtod(L, NULL);
        y[k] = t->median / 1e6;
        lo[k] = (isfinite(t->ci_lo) ? t->ci_lo : t->median) / 1e6;
        hi[k] = (isfinite(t->ci_hi) ? t->ci_hi : t->median) / 1e6;
    }
    return n;
}

/* 1 when the scene has at least two distinct tess_level values. */
static int chart__tess_varies(const report_model *m, size_t si)
{
    const char *first = NULL;
    for (size_t i = 0; i < m->n_rows; i++) {
        const char *L = chart__tess_level(&m->rows[i], si);
        if (L && first && strcmp(first, L) != 0)
            return 1;
        first = L ? L : first;
    }
    return 0;
}

/* 1 when row i is the first of its (mesh, technique) series in the run. */
static int chart__tess_first_of_series(const report_model *m, size_t i)
{
    const dm_config_result *c = m->rows[i].config;
    const char *mesh = dm_kv_get(c->params, c->n_params, "mesh");
    for (size_t j = 0; j < i; j++) {
        const dm_config_result *d = m->rows[j].config;
        const char *mj = dm_kv_get(d->params, d->n_params, "mesh");
        if (strcmp(mj ? mj : "", mesh ? mesh : "") == 0 && strcmp(m->rows[j].technique, m->rows[i].technique) == 0)
            return 0;
    }
    return 1;
}

static void chart__tess(dm_str *s, const report_model *m, size_t si)
{
    size_t n = m->n_rows;
    double *ax = dm_xcalloc(2 * n + 1, sizeof *ax), *ay = dm_xcalloc(2 * n + 1, sizeof *ay);   /* median and CI top */
    double *x = dm_xcalloc(n + 1, sizeof *x), *y = dm_xcalloc(n + 1, sizeof *y);
    double *lo = dm_xcalloc(n + 1, sizeof *lo), *hi = dm_xcalloc(n + 1, sizeof *hi);
    size_t na = 0;
    for (size_t i = 0; i < n; i++) {   /* axis ranges over every series and its whiskers */
        const char *L = chart__tess_level(&m->rows[i], si);
        const dm_counter_result *t = m->rows[i].frame_time;
        if (!L)
            continue;
        ax[na] = strtod(L, NULL), ay[na++] = t->median / 1e6;
        if (isfinite(t->ci_hi))
            ax[na] = ax[na - 1], ay[na] = t->ci_hi / 1e6, na++;
    }
    char *file = chart__tmpname();
    if (file) {
        chart_frame f = {"Time vs tessellation level (whiskers: CI of the median)", "tess_level", "median ms", 0, 0, 0,
                         0, 0.15, 0};
        chart__padded_range(ax, na, &f.x0, &f.x1, 0);
        chart__padded_range(ay, na, &f.y0, &f.y1, 1);
        chart__open(file, &f);
        for (size_t i = 0; i < n; i++) {   /* each series drawn once, at its first config */
            const dm_config_result *c = m->rows[i].config;
            const char *mesh = dm_kv_get(c->params, c->n_params, "mesh");
            const char *tech = m->rows[i].technique;
            size_t k = chart__tess_first_of_series(m, i)
                           ? chart__tess_series(m, si, mesh ? mesh : "", tech, x, y, lo, hi) : 0;
            if (!k)
                continue;
            char lab[CHART_MAX_LABEL];
            chart__safe_label(tech, lab);   /* the mesh is the scene's, in the title of its section */
            plcol0(2 + (PLINT)(i % 2));
            plline((PLINT)k, x, y);
            plpoin((PLINT)k, x, y, 4);
            plerry((PLINT)k, x, lo, hi);
            plptex(x[k - 1], y[k - 1], 1, 0, 1.05, lab);
        }
        chart__close(s, file, f.title);
        free(file);
    }
    free(ax);
    free(ay);
    free(x);
    free(y);
    free(lo);
    free(hi);
}

/* ---- per scene: the counter breakdown the model chose (breakdown.h) ------- */

static void chart__bar(double x0, double x1, double y0, double y1, PLINT col)
{
    PLFLT bx[4] = {x0, x0, x1, x1}, by[4] = {y0, y1, y1, y0};
    plcol0(col);
    plfill(4, bx, by);
}

/* Labels the bar groups (vertical, small) and draws a colour legend on top. */
static void chart__bar_labels_and_legend(const report_model *m, const breakdown *b, const char *const *names,
                                  size_t nn, PLINT col0)
{
    plschr(0, 0.65);
    for (size_t k = 0; k < b->n_bars; k++) {
        char lab[CHART_MAX_LABEL];
        chart__safe_label(m->rows[b->bars[k]].label, lab);
        plcol0(1);
        plmtex("bv", 0.5, (k + 0.5) / (double)b->n_bars, 1.0, lab);
    }
    for (size_t i = 0; i < nn; i++) {
        plcol0(col0 + (PLINT)i);
        plmtex("t", 0.6, (i + 0.5) / (double)nn, 0.5, names[i]);
    }
    plschr(0, 1.0);
}

/* Stacked estimated stage times of the fitted model (left) beside the
 * measured median (right). */
static void chart__draw_stages(const report_model *m, const breakdown *b)
{
    const breakdown_model *fm = b->fit;
    const char *names[BREAKDOWN_MAX_STAGES + 1];
    for (size_t k = 0; k < fm->n; k++)
        names[k] = fm->stages[k].name;
    names[fm->n] = "measured";
    for (size_t i = 0; i < b->n_bars; i++) {
        const report_model_row *r = &m->rows[b->bars[i]];
        const dm_fit_result *fit = breakdown_fit(m->run, r->config, fm);
        double y = 0;
        for (size_t k = 0; fit && k < fm->n; k++) {
            double h = breakdown_stage_ms(fm, fit, r->config, k);
            chart__bar(i + 0.08, i + 0.5, y, y + h, CHART_SERIES_COL0 + (PLINT)k);
            y += h;
        }
        chart__bar(i + 0.5, i + 0.92, 0, r->frame_time->median / 1e6, CHART_SERIES_COL0 + (PLINT)fm->n);
    }
    chart__bar_labels_and_legend(m, b, names, fm->n + 1, CHART_SERIES_COL0);
}

/* Stacked measured stage times (left) beside the measured median (right). */
static void chart__draw_measured_stages(const report_model *m, const breakdown *b)
{
    static const char *const names[BREAKDOWN_MEASURED_STAGES + 1] = {"geometry", "setup+raster",
                                                                     "fragment", "frame"};
    for (size_t i = 0; i < b->n_bars; i++) {
        const report_model_row *r = &m->rows[b->bars[i]];
        double y = 0;
        for (size_t k = 0; k < BREAKDOWN_MEASURED_STAGES; k++) {
            double h = breakdown_measured_ms(r->config, k);
            if (isfinite(h)) {
                chart__bar(i + 0.08, i + 0.5, y, y + h, CHART_SERIES_COL0 + (PLINT)k);
                y += h;
            }
        }
        chart__bar(i + 0.5, i + 0.92, 0, r->frame_time->median / 1e6,
                   CHART_SERIES_COL0 + BREAKDOWN_MEASURED_STAGES);
    }
    chart__bar_labels_and_legend(m, b, names, BREAKDOWN_MEASURED_STAGES + 1, CHART_SERIES_COL0);
}

/* The key counters, each relative to its maximum over the bars. */
static void chart__draw_counters(const report_model *m, const breakdown *b)
{
    size_t nk = b->n_counters;
    for (size_t k = 0; k < nk; k++) {
        double max = 0;
        for (size_t i = 0; i < b->n_bars; i++)
            max = fmax(max, breakdown_det_value(m->rows[b->bars[i]].config, b->counters[k]));
        double w = 0.84 / (double)nk;
        for (size_t i = 0; i < b->n_bars; i++)
            chart__bar(i + 0.08 + k * w, i + 0.08 + (k + 1) * w, 0,
                       breakdown_det_value(m->rows[b->bars[i]].config, b->counters[k]) / max,
                       CHART_SERIES_COL0 + 1 + (PLINT)k);
    }
    chart__bar_labels_and_legend(m, b, b->counters, nk, CHART_SERIES_COL0 + 1);
}

/* The breakdown of scene si as the model chose it, with a note when a fit
 * was too poor to draw and when the fastest configurations are left out. */
static void chart__breakdown(dm_str *s, const report_model *m, const report_model_scene *sc)
{
    const breakdown *b = &sc->breakdown;
    if (b->kind == BREAKDOWN_NONE)
        return;
    int fitted = b->kind != BREAKDOWN_COUNTERS;
    size_t longest = 0;   /* the vertical bar labels need room below the frame */
    for (size_t i = 0; i < b->n_bars; i++)
        if (strlen(m->rows[b->bars[i]].label) > longest)
            longest = strlen(m->rows[b->bars[i]].label);
    double bottom = fmax(0.32, fmin(0.6, ((double)longest * 5.4 + 16) / 420.0));
    char *file = chart__tmpname();
    if (!file)
        return;
    char title[96];
    if (b->kind == BREAKDOWN_MEASURED)
        snprintf(title, sizeof title, "Measured time per stage (timed isolation passes)");
    else
        snprintf(title, sizeof title, "Estimated time per stage (%s fit)", b->fit ? b->fit->model : "");
    chart_frame f = {fitted ? title : "Key counters per configuration (relative to each maximum)",
                     "", fitted ? "ms" : "fraction of the maximum", 0, (double)b->n_bars, 0,
                     fitted ? b->hi_ms * 1.08 : 1.08, bottom, 1};
    chart__open(file, &f);
    if (b->kind == BREAKDOWN_MEASURED)
        chart__draw_measured_stages(m, b);
    else if (b->kind == BREAKDOWN_FIT)
        chart__draw_stages(m, b);
    else
        chart__draw_counters(m, b);
    chart__close(s, file, f.title);
    if (!fitted && b->poor)
        dm_str_printf(s, "<p class=\"const\">No per-stage breakdown: the %s fit "
                         "explains too little of the time (R² %.2f, below %.1f), so its stage "
                         "times would be invented; the key counters are shown instead.</p>\n",
                      b->poor->model, b->poor_r2, BREAKDOWN_MIN_STAGE_R2);
    if (b->skipped)
        dm_str_printf(s, "<p class=\"const\">The %zu fastest configurations are left out of this "
                         "chart (it shows the %d slowest); all are in the table.</p>\n",
                      b->skipped, BREAKDOWN_MAX_BARS);
    free(file);
}

void report__html_charts_scene(dm_str *s, const report_model *m, size_t si)
{
    if (chart__tess_varies(m, si))
        chart__tess(s, m, si);
    chart__breakdown(s, m, &m->scenes[si]);
}

/* ---- model fits: predicted vs measured, residuals ------------------------- */

/* Scale and unit of a fit's response: ms for a nanosecond counter. */
static double chart__response_scale(const dm_run_result *run, const dm_fit_result *f, const char **unit)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_counter_result *k = f->response ? dm_config_counter(&run->configs[i], f->response) : NULL;
        if (k && k->unit) {
            *unit = strcmp(k->unit, "ns") == 0 ? "ms" : k->unit;
            return strcmp(k->unit, "ns") == 0 ? 1e-6 : 1;
        }
    }
    *unit = "ms";   /* the built-in models all fit WallTime */
    return 1e-6;
}

/* Title "<what>: <model> <group>" reduced to the chart's character set. */
static void chart__fit_title(const dm_fit_result *f, const char *what, char out[CHART_MAX_LABEL])
{
    dm_str t = {0};
    dm_str_printf(&t, "%s: %s", what, f->model ? f->model : "?");
    for (size_t g = 0; g < f->n_group; g++)
        dm_str_printf(&t, " %s=%s", f->group[g].key, f->group[g].value);
    chart__safe_label(dm_str_get(&t), out);
    dm_str_free(&t);
}

/* Points (x, y) over the straight line from (x0, ly0) to (x1, ly1). */
static void chart__scatter(dm_str *s, const chart_frame *fr, const double *x, const double *y,
                           size_t n, double ly0, double ly1)
{
    char *file = chart__tmpname();
    if (!file)
        return;
    chart__open(file, fr);
    PLFLT lx[2] = {fr->x0, fr->x1}, ly[2] = {ly0, ly1};
    plcol0(2);
    plline(2, lx, ly);
    plcol0(3);
    plpoin((PLINT)n, x, y, 4);
    chart__close(s, file, fr->title);
    free(file);
}

/* Predicted (x) against measured (y), both scaled, over the line y = x. */
static void chart__fit_scatter(dm_str *s, const dm_fit_result *f, const double *p, const double *m,
                               size_t n, const char *unit)
{
    char title[CHART_MAX_LABEL], xl[32], yl[32];
    double *both = dm_xcalloc(2 * n, sizeof *both);
    memcpy(both, p, n * sizeof *p);
    memcpy(both + n, m, n * sizeof *m);
    chart__fit_title(f, "Predicted vs measured", title);
    snprintf(xl, sizeof xl, "predicted (%s)", unit);
    snprintf(yl, sizeof yl, "measured (%s)", unit);
    chart_frame fr = {title, xl, yl, 0, 0, 0, 0, 0.15, 0};
    chart__padded_range(both, 2 * n, &fr.x0, &fr.x1, 0);
    fr.y0 = fr.x0, fr.y1 = fr.x1;
    chart__scatter(s, &fr, p, m, n, fr.x0, fr.x1);
    free(both);
}

/* Residual in percent of the measured value against the prediction, over y = 0. */
static void chart__fit_residuals(dm_str *s, const dm_fit_result *f, const double *p, const double *m,
                                 size_t n, const char *unit)
{
    char title[CHART_MAX_LABEL], xl[32];
    double *r = dm_xcalloc(n + 1, sizeof *r);
    for (size_t i = 0; i < n; i++)
        r[i] = m[i] != 0 ? (m[i] - p[i]) / m[i] * 100 : NAN;
    chart__fit_title(f, "Residuals", title);
    snprintf(xl, sizeof xl, "predicted (%s)", unit);
    chart_frame fr = {title, xl, "(measured - predicted) / measured, %", 0, 0, 0, 0, 0.15, 0};
    chart__padded_range(p, n, &fr.x0, &fr.x1, 0);
    chart__padded_range(r, n, &fr.y0, &fr.y1, 0);
    fr.y0 = fmin(fr.y0, -1), fr.y1 = fmax(fr.y1, 1);   /* keep 0 inside */
    chart__scatter(s, &fr, p, r, n, 0, 0);
    free(r);
}

void report__html_charts_fit(dm_str *s, const dm_run_result *run, const dm_fit_result *f)
{
    size_t n = f->n_points > 0 && f->measured && f->predicted ? (size_t)f->n_points : 0;
    if (!n)
        return;
    const char *unit;
    double k = chart__response_scale(run, f, &unit);
    double *p = dm_xcalloc(n, sizeof *p), *m = dm_xcalloc(n, sizeof *m);
    for (size_t i = 0; i < n; i++)
        p[i] = f->predicted[i] * k, m[i] = f->measured[i] * k;
    chart__fit_scatter(s, f, p, m, n, unit);
    chart__fit_residuals(s, f, p, m, n, unit);
    free(p);
    free(m);
}
