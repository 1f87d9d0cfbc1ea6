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
#include "reports/pareto.h"

#include <math.h>
#include <plplot/plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CHART_MAX_LABEL 48

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
    plcol0(1);
    pladv(0);
    plvpor(0.1, 0.95, f->bottom > 0 ? f->bottom : 0.15, 0.9);
    plwind(f->x0, f->x1, f->y0, f->y1);
    plbox(f->categorical ? "bc" : "bcnst", 0, 0, "bcnstv", 0, 0);
    char t[CHART_MAX_LABEL];
    safe_label(f->title, t);
    pllab(f->xlabel, f->ylabel, t);
}

/* Ends the stream and appends its SVG (without prolog/namespaces) to s. */
static void chart_close(dm_str *s, const char *file)
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
    dm_str_cat(s, "<div class=\"chart\">");
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

/* ---- time per technique (bars) ------------------------------------------ */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of the config medians (ms) of one technique; NaN when none. */
static double technique_median_ms(const dm_run_result *run, const char *tech)
{
    double *v = dm_xcalloc(run->n_configs + 1, sizeof *v);
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_counter_result *t = report__frame_time(&run->configs[i]);
        if (t && run->configs[i].ok && strcmp(report__technique(&run->configs[i]), tech) == 0)
            v[n++] = t->median / 1e6;
    }
    qsort(v, n, sizeof *v, cmp_double);
    double m = n ? (n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2) : NAN;
    free(v);
    return m;
}

void report__html_charts_run(dm_str *s, const dm_run_result *run)
{
    const char **techs = NULL;
    size_t nt = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const char *t = report__technique(&run->configs[i]);
        size_t k = 0;
        while (k < nt && strcmp(techs[k], t) != 0)
            k++;
        if (k == nt && report__frame_time(&run->configs[i]) && run->configs[i].ok) {
            techs = dm_xrealloc(techs, (nt + 1) * sizeof *techs);
            techs[nt++] = t;
        }
    }
    char *file = nt ? chart_tmpname() : NULL;
    if (file) {
        double *h = dm_xcalloc(nt, sizeof *h), lo, hi;
        for (size_t k = 0; k < nt; k++)
            h[k] = technique_median_ms(run, techs[k]);
        padded_range(h, nt, &lo, &hi, 1);
        chart_frame f = {"Median frame time per technique", "", "ms", 0, (double)nt, 0, hi, 0.3, 1};
        dm_str_cat(s, "<h2>Time per technique</h2>\n");
        chart_open(file, &f);
        for (size_t k = 0; k < nt; k++) {
            PLFLT bx[4] = {k + 0.15, k + 0.15, k + 0.85, k + 0.85}, by[4] = {0, h[k], h[k], 0};
            char lab[CHART_MAX_LABEL];
            plcol0(3);
            plfill(4, bx, by);
            plcol0(1);
            safe_label(techs[k], lab);
            plmtex("bv", 0.5, (k + 0.5) / (double)nt, 1.0, lab);
        }
        chart_close(s, file);
        free(h);
        free(file);
    }
    free(techs);
}

/* ---- per scene: error vs time with the Pareto front ---------------------- */

/* Collects the scene's ok configs with a frame time: x = median ms,
 * y = 1 − SSIM (or RMSE when no config has SSIM).  Returns the count. */
static size_t scene_points(const dm_run_result *run, const char *scene, double **x, double **y,
                           const dm_config_result ***cfg, int *use_rmse)
{
    size_t n = 0;
    *x = dm_xcalloc(run->n_configs + 1, sizeof **x);
    *y = dm_xcalloc(run->n_configs + 1, sizeof **y);
    *cfg = dm_xcalloc(run->n_configs + 1, sizeof **cfg);
    *use_rmse = 1;
    for (size_t i = 0; i < run->n_configs; i++)
        if (run->configs[i].quality.present && isfinite(run->configs[i].quality.ssim))
            *use_rmse = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const dm_counter_result *t = report__frame_time(c);
        if (!c->ok || !t || !c->quality.present || strcmp(c->scene ? c->scene : "", scene) != 0)
            continue;
        (*x)[n] = t->median / 1e6;
        (*y)[n] = *use_rmse ? c->quality.rmse : 1.0 - c->quality.ssim;
        (*cfg)[n++] = c;
    }
    return n;
}

static void front_list(dm_str *s, const dm_config_result **cfg, const size_t *front, size_t m,
                       const double *x, const double *y)
{
    dm_str_cat(s, "<p>Pareto front (fastest first):</p><ol>");
    for (size_t k = 0; k < m; k++) {
        const dm_config_result *c = cfg[front[k]];
        dm_str_cat(s, "<li><code>");
        dm_str_cat_html(s, c->key);
        dm_str_cat(s, "</code> ");
        for (size_t p = 0; p < c->n_params; p++) {
            dm_str_cat(s, p ? ", " : "");
            dm_str_cat_html(s, c->params[p].key);
            dm_str_cat(s, "=");
            dm_str_cat_html(s, c->params[p].value);
        }
        dm_str_printf(s, ": %.4f ms, error %.4g</li>", x[front[k]], y[front[k]]);
    }
    dm_str_cat(s, "</ol>\n");
}

static void chart_pareto(dm_str *s, const dm_run_result *run, const char *scene)
{
    double *x, *y;
    const dm_config_result **cfg;
    int use_rmse;
    size_t n = scene_points(run, scene, &x, &y, &cfg, &use_rmse);
    char *file = n ? chart_tmpname() : NULL;
    if (file) {
        size_t *front = dm_xcalloc(n, sizeof *front);
        size_t m = pareto_front(x, y, n, front);
        chart_frame f = {"Error vs time", "median frame time (ms)", use_rmse ? "RMSE" : "1 - SSIM",
                         0, 0, 0, 0, 0.15, 0};
        padded_range(x, n, &f.x0, &f.x1, 0);
        padded_range(y, n, &f.y0, &f.y1, 0);
        chart_open(file, &f);
        plcol0(3);
        plpoin((PLINT)n, x, y, 4);
        PLFLT *fx = dm_xcalloc(m, sizeof *fx), *fy = dm_xcalloc(m, sizeof *fy);
        for (size_t k = 0; k < m; k++)
            fx[k] = x[front[k]], fy[k] = y[front[k]];
        plcol0(2);
        plline((PLINT)m, fx, fy);
        plpoin((PLINT)m, fx, fy, 17);
        chart_close(s, file);
        front_list(s, cfg, front, m, x, y);
        free(fx);
        free(fy);
        free(front);
        free(file);
    }
    free(x);
    free(y);
    free(cfg);
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
        chart_close(s, file);
        free(file);
    }
    free(ax);
    free(ay);
    free(x);
    free(y);
}

void report__html_charts_scene(dm_str *s, const dm_run_result *run, const char *scene)
{
    chart_pareto(s, run, scene);
    if (tess_varies(run, scene))
        chart_tess(s, run, scene);
}
