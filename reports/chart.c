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
 */
#include "reports/report_internal.h"

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
static void safe_label(const char *text, char out[CHART_MAX_LABEL])
{
    size_t n = 0;
    for (const char *p = text ? text : ""; *p && n < CHART_MAX_LABEL - 1; p++)
        out[n++] = (strchr(" _-.,=/:()+", *p) || (*p >= '0' && *p <= '9') ||
                    (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z')) ? *p : '?';
    out[n] = '\0';
}

/* Range [lo, hi] of v padded by 8 %; a flat or empty range gets a width. */
static void padded_range(const double *v, size_t n, double *lo, double *hi, int from_zero)
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
static void chart_open(const char *file, const chart_frame *f)
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
    safe_label(f->title, t);
    pllab(f->xlabel, f->ylabel, t);
}

/* Ends the stream and appends its SVG (without prolog/namespaces) to s,
 * in a <div> whose aria-label is the chart's title as drawn. */
static void chart_close(dm_str *s, const char *file, const char *title)
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
    safe_label(title, t);
    dm_str_printf(s, "<div class=\"chart\" role=\"img\" aria-label=\"%s\">", t);
    dm_str_cat(s, start);
    dm_str_cat(s, "</div>\n");
    free(svg);
}

/* A fresh temporary file name for one chart, or NULL. */
static char *chart_tmpname(void)
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

/* Points of one (mesh, technique) series sorted by tess_level. */
static size_t tess_series(const dm_run_result *run, const char *scene, const char *mesh,
                          const char *tech, double *x, double *y)
{
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const char *L = dm_kv_get(c->params, c->n_params, "tess_level");
        const char *m = dm_kv_get(c->params, c->n_params, "mesh");
        const dm_counter_result *t = report__frame_time(c);
        if (!c->ok || !t || !L || strcmp(c->scene ? c->scene : "", scene) != 0 ||
            strcmp(m ? m : "", mesh) != 0 || strcmp(report__technique(c), tech) != 0)
            continue;
        size_t k = n++;
        for (; k > 0 && x[k - 1] > strtod(L, NULL); k--)
            x[k] = x[k - 1], y[k] = y[k - 1];
        x[k] = strtod(L, NULL);
        y[k] = t->median / 1e6;
    }
    return n;
}

/* 1 when the scene has at least two distinct tess_level values. */
static int tess_varies(const dm_run_result *run, const char *scene)
{
    const char *first = NULL;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const char *L = dm_kv_get(c->params, c->n_params, "tess_level");
        if (!L || !c->ok || !report__frame_time(c) || strcmp(c->scene ? c->scene : "", scene) != 0)
            continue;
        if (first && strcmp(first, L) != 0)
            return 1;
        first = L;
    }
    return 0;
}

static void chart_tess(dm_str *s, const dm_run_result *run, const char *scene)
{
    size_t n = run->n_configs;
    double *ax = dm_xcalloc(n + 1, sizeof *ax), *ay = dm_xcalloc(n + 1, sizeof *ay);
    double *x = dm_xcalloc(n + 1, sizeof *x), *y = dm_xcalloc(n + 1, sizeof *y);
    size_t na = 0;
    for (size_t i = 0; i < n; i++) {   /* axis ranges over every series */
        const dm_config_result *c = &run->configs[i];
        const char *L = dm_kv_get(c->params, c->n_params, "tess_level");
        const dm_counter_result *t = report__frame_time(c);
        if (L && t && c->ok && strcmp(c->scene ? c->scene : "", scene) == 0)
            ax[na] = strtod(L, NULL), ay[na++] = t->median / 1e6;
    }
    char *file = chart_tmpname();
    if (file) {
        chart_frame f = {"Time vs tessellation level", "tess_level", "ms", 0, 0, 0, 0, 0.15, 0};
        padded_range(ax, na, &f.x0, &f.x1, 0);
        padded_range(ay, na, &f.y0, &f.y1, 1);
        chart_open(file, &f);
        for (size_t i = 0; i < n; i++) {   /* each series drawn once, at its first config */
            const dm_config_result *c = &run->configs[i];
            const char *mesh = dm_kv_get(c->params, c->n_params, "mesh");
            const char *tech = report__technique(c);
            int first = 1;
            for (size_t j = 0; j < i && first; j++) {
                const char *mj = dm_kv_get(run->configs[j].params, run->configs[j].n_params, "mesh");
                first = !(strcmp(mj ? mj : "", mesh ? mesh : "") == 0 &&
                          strcmp(report__technique(&run->configs[j]), tech) == 0);
            }
            size_t m = first ? tess_series(run, scene, mesh ? mesh : "", tech, x, y) : 0;
            if (!m)
                continue;
            char lab[CHART_MAX_LABEL], raw[2 * CHART_MAX_LABEL];
            snprintf(raw, sizeof raw, "%s/%s", mesh ? mesh : "", tech);
            safe_label(raw, lab);
            plcol0(2 + (PLINT)(i % 2));
            plline((PLINT)m, x, y);
            plpoin((PLINT)m, x, y, 4);
            plptex(x[m - 1], y[m - 1], 1, 0, 1.05, lab);
        }
        chart_close(s, file, f.title);
        free(file);
    }
    free(ax);
    free(ay);
    free(x);
    free(y);
}

/* ---- per scene: counter breakdown per configuration ----------------------- */

/* At most this many configurations get a bar group; the fastest are left out. */
#define CHART_MAX_BARS 24

/* The models whose terms split frame time by stage: each term's parameter,
 * the counter it multiplies (NULL: the fixed cost) and its legend name.
 * time-from-stages (over the exact stage counters) is preferred to
 * pipeline-linear (over invocation counts) where a configuration has both. */
typedef struct { const char *param, *counter, *name; } chart_stage;
typedef struct {
    const char *model;
    const chart_stage *stages;
    size_t n;
    int exact;   /* its counters are the stage counters: drawn only where a configuration has them */
} chart_model;
static const chart_stage chart_stages_pl[] = {
    {"c0", NULL, "fixed"}, {"c_vs", "VSInvocations", "vertex"},
    {"c_tes", "TESInvocations", "tessellation"}, {"c_prim", "ClippingOutputPrimitives", "primitives"},
    {"c_px", "SamplesPassed", "pixels"} };
static const chart_stage chart_stages_ts[] = {
    {"a", NULL, "fixed"}, {"b_geo", "GeometryInstructions", "geometry"},
    {"b_raster", "RasterInstructions", "raster"}, {"b_frag", "FragmentInstructions", "fragment"} };
static const chart_model chart_models[] = {
    {"time-from-stages", chart_stages_ts, sizeof chart_stages_ts / sizeof *chart_stages_ts, 1},
    {"pipeline-linear", chart_stages_pl, sizeof chart_stages_pl / sizeof *chart_stages_pl, 0} };
#define CHART_N_MODELS (sizeof chart_models / sizeof *chart_models)
#define CHART_MAX_STAGES 5

static void bar(double x0, double x1, double y0, double y1, PLINT col)
{
    PLFLT bx[4] = {x0, x0, x1, x1}, by[4] = {y0, y1, y1, y0};
    plcol0(col);
    plfill(4, bx, by);
}

/* Value of an available deterministic counter, else 0 (absent work). */
static double det_value(const dm_config_result *c, const char *name)
{
    const dm_counter_result *k = name ? dm_config_counter(c, name) : NULL;
    return k && k->available && k->deterministic && isfinite(k->value) ? k->value : 0;
}

static double fit_param(const dm_fit_result *f, const char *name)
{
    const dm_fit_param *p = dm_fit_param_find(f, name);
    return p ? p->value : NAN;
}

/* A per-stage breakdown is drawn only from a fit at least this good (R²);
 * a poorer one would show invented stage times (docs/models.md). */
#define CHART_MIN_STAGE_R2 0.8

/* The fit of model m whose group matches c's params, any quality (NULL
 * when none); a model of the exact stage counters only where c has them. */
static const dm_fit_result *model_fit_any(const dm_run_result *run, const dm_config_result *c,
                                          const chart_model *m)
{
    for (size_t k = 0; m->exact && k < m->n; k++)
        if (m->stages[k].counter && !(det_value(c, m->stages[k].counter) > 0))
            return NULL;
    for (size_t i = 0; i < run->n_fits; i++) {
        const dm_fit_result *f = &run->fits[i];
        int match = f->model && strcmp(f->model, m->model) == 0 && isfinite(fit_param(f, m->stages[0].param));
        for (size_t g = 0; match && g < f->n_group; g++) {
            const char *v = dm_kv_get(c->params, c->n_params, f->group[g].key);
            match = v && strcmp(v, f->group[g].value) == 0;
        }
        if (match)
            return f;
    }
    return NULL;
}

/* The fit of model m for c when it is good enough to draw. */
static const dm_fit_result *model_fit(const dm_run_result *run, const dm_config_result *c, const chart_model *m)
{
    const dm_fit_result *f = model_fit_any(run, c, m);
    return f && isfinite(f->r2) && f->r2 >= CHART_MIN_STAGE_R2 ? f : NULL;
}

/* Estimated ms of stage k of c under fit f of model m (param · counter; the
 * response is ns). */
static double stage_ms(const chart_model *m, const dm_fit_result *f, const dm_config_result *c, size_t k)
{
    double v = fit_param(f, m->stages[k].param);
    double n = m->stages[k].counter ? det_value(c, m->stages[k].counter) : 1;
    return isfinite(v) ? v * n / 1e6 : 0;
}

/* Measured ms of stage k of c (geometry, setup and raster, fragment) from
 * its timed isolation passes: GeometryTime, MinimalShadingTime −
 * GeometryTime and WallTime − MinimalShadingTime (medians; a difference
 * that noise puts below 0 is 0); NaN when c has not both passes. */
static double measured_stage_ms(const dm_config_result *c, size_t k)
{
    const dm_counter_result *g = dm_config_counter(c, "GeometryTime");
    const dm_counter_result *m = dm_config_counter(c, "MinimalShadingTime"), *w = report__frame_time(c);
    if (!g || !m || !w || !g->available || !m->available || !isfinite(g->median) || !isfinite(m->median))
        return NAN;
    double v = k == 0 ? g->median : k == 1 ? m->median - g->median : w->median - m->median;
    return fmax(0, v) / 1e6;
}
#define CHART_MEASURED_STAGES 3

/* Labels the bar groups (vertical, small) and draws a colour legend on top. */
static void bar_labels_and_legend(const dm_run_result *run, const size_t *rows, size_t n,
                                  const char *const *names, size_t nn, PLINT col0)
{
    plschr(0, 0.65);
    for (size_t k = 0; k < n; k++) {
        dm_str label = {0};
        char lab[CHART_MAX_LABEL];
        report__config_label(run, &run->configs[rows[k]], &label);
        safe_label(dm_str_get(&label), lab);
        plcol0(1);
        plmtex("bv", 0.5, (k + 0.5) / (double)n, 1.0, lab);
        dm_str_free(&label);
    }
    for (size_t i = 0; i < nn; i++) {
        plcol0(col0 + (PLINT)i);
        plmtex("t", 0.6, (i + 0.5) / (double)nn, 0.5, names[i]);
    }
    plschr(0, 1.0);
}

/* Stacked estimated stage times of model m (left) beside the measured
 * median (right). */
static void draw_stages(const dm_run_result *run, const size_t *rows, size_t n, const chart_model *m)
{
    const char *names[CHART_MAX_STAGES + 1];
    for (size_t k = 0; k < m->n; k++)
        names[k] = m->stages[k].name;
    names[m->n] = "measured";
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        const dm_fit_result *fit = model_fit(run, c, m);
        double y = 0;
        for (size_t k = 0; fit && k < m->n; k++) {
            double h = stage_ms(m, fit, c, k);
            bar(i + 0.08, i + 0.5, y, y + h, CHART_SERIES_COL0 + (PLINT)k);
            y += h;
        }
        bar(i + 0.5, i + 0.92, 0, report__frame_time(c)->median / 1e6, CHART_SERIES_COL0 + (PLINT)m->n);
    }
    bar_labels_and_legend(run, rows, n, names, m->n + 1, CHART_SERIES_COL0);
}

/* Stacked measured stage times (left) beside the measured median (right). */
static void draw_measured_stages(const dm_run_result *run, const size_t *rows, size_t n)
{
    static const char *const names[CHART_MEASURED_STAGES + 1] = {"geometry", "setup+raster", "fragment",
                                                                 "frame"};
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        double y = 0;
        for (size_t k = 0; k < CHART_MEASURED_STAGES; k++) {
            double h = measured_stage_ms(c, k);
            if (isfinite(h)) {
                bar(i + 0.08, i + 0.5, y, y + h, CHART_SERIES_COL0 + (PLINT)k);
                y += h;
            }
        }
        bar(i + 0.5, i + 0.92, 0, report__frame_time(c)->median / 1e6, CHART_SERIES_COL0 + CHART_MEASURED_STAGES);
    }
    bar_labels_and_legend(run, rows, n, names, CHART_MEASURED_STAGES + 1, CHART_SERIES_COL0);
}

/* The key counters shown relative to each one's maximum over the bars. */
static size_t key_counters(const dm_run_result *run, const size_t *rows, size_t n, const char *out[4])
{
    static const char *const want[] = {"VSInvocations", "TESInvocations", "ClippingOutputPrimitives",
                                       "FSInvocations", "SamplesPassed"};
    size_t m = 0;
    for (size_t k = 0; k < 5; k++) {
        int have = 0;
        for (size_t i = 0; i < n && !have; i++)
            have = det_value(&run->configs[rows[i]], want[k]) > 0;
        if (have && !(k == 4 && m && strcmp(out[m - 1], "FSInvocations") == 0))
            out[m++] = want[k];   /* SamplesPassed only when FSInvocations is missing */
    }
    return m;
}

static void draw_counters(const dm_run_result *run, const size_t *rows, size_t n,
                          const char *const *names, size_t nk)
{
    for (size_t k = 0; k < nk; k++) {
        double max = 0;
        for (size_t i = 0; i < n; i++)
            max = fmax(max, det_value(&run->configs[rows[i]], names[k]));
        double w = 0.84 / (double)nk;
        for (size_t i = 0; i < n; i++)
            bar(i + 0.08 + k * w, i + 0.08 + (k + 1) * w, 0,
                det_value(&run->configs[rows[i]], names[k]) / max, CHART_SERIES_COL0 + 1 + (PLINT)k);
    }
    bar_labels_and_legend(run, rows, n, names, nk, CHART_SERIES_COL0 + 1);
}

/* Per configuration: the stage times its timed isolation passes measured
 * next to the frame's median, where the run has them; else a model's
 * estimate per stage when a fit exists (time-from-stages over the exact
 * stage counters before pipeline-linear); else the key counters
 * normalised to their maxima.  At most CHART_MAX_BARS configurations, the slowest;
 * a note says how many were left out. */
static void chart_breakdown(dm_str *s, const dm_run_result *run, const char *scene)
{
    size_t *rows, nr = 0, nall = report__scene_rows(run, scene, &rows);
    for (size_t i = 0; i < nall; i++)   /* keep the timed ones, still fastest first */
        if (report__frame_time(&run->configs[rows[i]]))
            rows[nr++] = rows[i];
    size_t skip = nr > CHART_MAX_BARS ? nr - CHART_MAX_BARS : 0, n = nr - skip, nk = 0;
    const size_t *shown = rows + skip;
    const char *names[4];
    int measured = 0;   /* the timed passes, measured, before any fit's estimate */
    for (size_t i = 0; i < n && !measured; i++)
        measured = isfinite(measured_stage_ms(&run->configs[shown[i]], 0));
    /* the first model with a fit good enough for some configuration shown */
    const chart_model *m = NULL, *poor = NULL;
    double hi = 0, poor_r2 = NAN;
    for (size_t j = 0; j < CHART_N_MODELS && !m && !measured; j++)
        for (size_t i = 0; i < n && !m; i++) {
            const dm_config_result *c = &run->configs[shown[i]];
            const dm_fit_result *any = model_fit_any(run, c, &chart_models[j]);
            if (model_fit(run, c, &chart_models[j]))
                m = &chart_models[j];
            else if (any && !poor) {
                poor = &chart_models[j];
                poor_r2 = any->r2;
            }
        }
    int fitted = m != NULL || measured;
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[shown[i]];
        const dm_fit_result *f = m ? model_fit(run, c, m) : NULL;
        double sum = 0;
        for (size_t k = 0; f && k < m->n; k++)
            sum += stage_ms(m, f, c, k);
        for (size_t k = 0; measured && k < CHART_MEASURED_STAGES; k++) {
            double h = measured_stage_ms(c, k);
            sum += isfinite(h) ? h : 0;
        }
        hi = fmax(hi, fmax(sum, report__frame_time(c)->median / 1e6));
    }
    if (!fitted)
        nk = key_counters(run, shown, n, names);
    size_t longest = 0;   /* the vertical bar labels need room below the frame */
    for (size_t i = 0; i < n; i++) {
        dm_str label = {0};
        report__config_label(run, &run->configs[shown[i]], &label);
        longest = label.len > longest ? label.len : longest;
        dm_str_free(&label);
    }
    double bottom = fmax(0.32, fmin(0.6, ((double)longest * 5.4 + 16) / 420.0));
    char *file = (fitted || nk) && n ? chart_tmpname() : NULL;
    if (file) {
        char title[96];
        if (measured)
            snprintf(title, sizeof title, "Measured time per stage (timed isolation passes)");
        else
            snprintf(title, sizeof title, "Estimated time per stage (%s fit)", m ? m->model : "");
        chart_frame f = {fitted ? title : "Key counters per configuration (relative to each maximum)",
                         "", fitted ? "ms" : "fraction of the maximum", 0, (double)n, 0,
                         fitted ? hi * 1.08 : 1.08, bottom, 1};
        chart_open(file, &f);
        if (measured)
            draw_measured_stages(run, shown, n);
        else if (fitted)
            draw_stages(run, shown, n, m);
        else
            draw_counters(run, shown, n, names, nk);
        chart_close(s, file, f.title);
        if (!fitted && poor)
            dm_str_printf(s, "<p class=\"const\">No per-stage breakdown: the %s fit "
                             "explains too little of the time (R² %.2f, below %.1f), so its stage "
                             "times would be invented; the key counters are shown instead.</p>\n",
                          poor->model, poor_r2, CHART_MIN_STAGE_R2);
        if (skip)
            dm_str_printf(s, "<p class=\"const\">The %zu fastest configurations are left out of this "
                             "chart (it shows the %d slowest); all are in the table.</p>\n",
                          skip, CHART_MAX_BARS);
        free(file);
    }
    free(rows);
}

void report__html_charts_scene(dm_str *s, const dm_run_result *run, const char *scene)
{
    if (tess_varies(run, scene))
        chart_tess(s, run, scene);
    chart_breakdown(s, run, scene);
}

/* ---- model fits: predicted vs measured, residuals ------------------------- */

/* Scale and unit of a fit's response: ms for a nanosecond counter. */
static double response_scale(const dm_run_result *run, const dm_fit_result *f, const char **unit)
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
static void fit_title(const dm_fit_result *f, const char *what, char out[CHART_MAX_LABEL])
{
    dm_str t = {0};
    dm_str_printf(&t, "%s: %s", what, f->model ? f->model : "?");
    for (size_t g = 0; g < f->n_group; g++)
        dm_str_printf(&t, " %s=%s", f->group[g].key, f->group[g].value);
    safe_label(dm_str_get(&t), out);
    dm_str_free(&t);
}

/* Points (x, y) over the straight line from (x0, ly0) to (x1, ly1). */
static void chart_scatter(dm_str *s, const chart_frame *fr, const double *x, const double *y,
                          size_t n, double ly0, double ly1)
{
    char *file = chart_tmpname();
    if (!file)
        return;
    chart_open(file, fr);
    PLFLT lx[2] = {fr->x0, fr->x1}, ly[2] = {ly0, ly1};
    plcol0(2);
    plline(2, lx, ly);
    plcol0(3);
    plpoin((PLINT)n, x, y, 4);
    chart_close(s, file, fr->title);
    free(file);
}

/* Predicted (x) against measured (y), both scaled, over the line y = x. */
static void chart_fit_scatter(dm_str *s, const dm_fit_result *f, const double *p, const double *m,
                              size_t n, const char *unit)
{
    char title[CHART_MAX_LABEL], xl[32], yl[32];
    double *both = dm_xcalloc(2 * n, sizeof *both);
    memcpy(both, p, n * sizeof *p);
    memcpy(both + n, m, n * sizeof *m);
    fit_title(f, "Predicted vs measured", title);
    snprintf(xl, sizeof xl, "predicted (%s)", unit);
    snprintf(yl, sizeof yl, "measured (%s)", unit);
    chart_frame fr = {title, xl, yl, 0, 0, 0, 0, 0.15, 0};
    padded_range(both, 2 * n, &fr.x0, &fr.x1, 0);
    fr.y0 = fr.x0, fr.y1 = fr.x1;
    chart_scatter(s, &fr, p, m, n, fr.x0, fr.x1);
    free(both);
}

/* Residual in percent of the measured value against the prediction, over y = 0. */
static void chart_fit_residuals(dm_str *s, const dm_fit_result *f, const double *p, const double *m,
                                size_t n, const char *unit)
{
    char title[CHART_MAX_LABEL], xl[32];
    double *r = dm_xcalloc(n + 1, sizeof *r);
    for (size_t i = 0; i < n; i++)
        r[i] = m[i] != 0 ? (m[i] - p[i]) / m[i] * 100 : NAN;
    fit_title(f, "Residuals", title);
    snprintf(xl, sizeof xl, "predicted (%s)", unit);
    chart_frame fr = {title, xl, "(measured - predicted) / measured, %", 0, 0, 0, 0, 0.15, 0};
    padded_range(p, n, &fr.x0, &fr.x1, 0);
    padded_range(r, n, &fr.y0, &fr.y1, 0);
    fr.y0 = fmin(fr.y0, -1), fr.y1 = fmax(fr.y1, 1);   /* keep 0 inside */
    chart_scatter(s, &fr, p, r, n, 0, 0);
    free(r);
}

void report__html_charts_fit(dm_str *s, const dm_run_result *run, const dm_fit_result *f)
{
    size_t n = f->n_points > 0 && f->measured && f->predicted ? (size_t)f->n_points : 0;
    if (!n)
        return;
    const char *unit;
    double k = response_scale(run, f, &unit);
    double *p = dm_xcalloc(n, sizeof *p), *m = dm_xcalloc(n, sizeof *m);
    for (size_t i = 0; i < n; i++)
        p[i] = f->predicted[i] * k, m[i] = f->measured[i] * k;
    chart_fit_scatter(s, f, p, m, n, unit);
    chart_fit_residuals(s, f, p, m, n, unit);
    free(p);
    free(m);
}
