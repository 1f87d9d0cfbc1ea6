/* drivers_report.c — one sweep on several drivers, side by side
 * (drivers_report.h).  The labels of configurations and scenes are the
 * reference run's report model's (report_model.h), built once; the times,
 * instruction counts and SSIM each driver measured are read from its
 * configurations, and the fronts here are the plain ones of WallTime
 * against 1 − SSIM on each driver, not the run's metric with its tolerance. */
#include "reports/drivers_report.h"
#include "reports/recommend.h"
#include "reports/report.h"
#include "reports/report_model.h"
#include "core/dm_error.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>

double drivers_kendall_tau(const double *x, const double *y, size_t n)
{
    double conc = 0, disc = 0, tx = 0, ty = 0;   /* tx, ty: pairs tied in x only / y only */
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i]))
            continue;
        m++;
        for (size_t j = i + 1; j < n; j++) {
            if (!isfinite(x[j]) || !isfinite(y[j]))
                continue;
            double dx = x[i] - x[j], dy = y[i] - y[j];
            if (dx == 0 && dy == 0)
                continue;
            if (dx == 0)
                tx++;
            else if (dy == 0)
                ty++;
            else if ((dx > 0) == (dy > 0))
                conc++;
            else
                disc++;
        }
    }
    double den = sqrt((conc + disc + tx) * (conc + disc + ty));
    return m < 2 || den == 0 ? NAN : (conc - disc) / den;
}

/* splitmix64: a small seeded stream, so the interval is repeatable. */
static uint64_t drivers__rng(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

static int drivers__cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double drivers_kendall_tau_ci(const double *x, const double *y, size_t n, size_t reps,
                              uint64_t seed, double *lo, double *hi)
{
    *lo = *hi = NAN;
    double *fx = dm_xcalloc(n + 1, sizeof *fx), *fy = dm_xcalloc(n + 1, sizeof *fy);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i]))
            fx[m] = x[i], fy[m++] = y[i];
    double tau = drivers_kendall_tau(fx, fy, m);
    double *bx = dm_xcalloc(m + 1, sizeof *bx), *by = dm_xcalloc(m + 1, sizeof *by);
    double *taus = dm_xcalloc(reps + 1, sizeof *taus);
    size_t got = 0;
    for (size_t r = 0; m >= 3 && isfinite(tau) && r < reps; r++) {
        for (size_t i = 0; i < m; i++) {
            size_t j = (size_t)(drivers__rng(&seed) % m);
            bx[i] = fx[j], by[i] = fy[j];
        }
        double t = drivers_kendall_tau(bx, by, m);
        if (isfinite(t))
            taus[got++] = t;
    }
    if (got > 0 && 2 * got >= reps) {
        qsort(taus, got, sizeof *taus, drivers__cmp_double);
        *lo = taus[(size_t)floor(0.025 * (double)(got - 1))];
        *hi = taus[(size_t)ceil(0.975 * (double)(got - 1))];
    }
    free(fx);
    free(fy);
    free(bx);
    free(by);
    free(taus);
    return tau;
}

int drivers_drift(const double *start, const double *end, size_t n, double *moved, double *noise)
{
    double lo = INFINITY, hi = 0, within = DRIVERS_DRIFT_FLOOR;
    size_t runs = 0;
    for (size_t k = 0; k < n; k++) {
        if (!(start[k] > 0) || !(end[k] > 0) || !isfinite(start[k]) || !isfinite(end[k]))
            continue;
        double mean = (start[k] + end[k]) / 2;
        lo = fmin(lo, mean), hi = fmax(hi, mean);
        within = fmax(within, fabs(end[k] - start[k]) / mean);
        runs++;
    }
    if (runs < 2) {
        *moved = *noise = NAN;
        return -1;
    }
    *moved = hi / lo - 1;
    *noise = within;
    return *moved > within;
}

/* ---- matching the runs ------------------------------------------------------ */

/* The configurations of the first run that ran, and each side's index of
 * the same key (-1 when absent or failed). */
typedef struct drivers__table {
    const dm_run_result *ref;    /* the first side that ran */
    report_model model;          /* its report model: the labels of rows and scenes */
    size_t n_rows;
    long *idx;                   /* n_rows x n_sides */
} drivers__table;

static void drivers__match(const drivers_side *s, size_t ns, drivers__table *t)
{
    memset(t, 0, sizeof *t);
    for (size_t k = 0; k < ns && !t->ref; k++)
        t->ref = s[k].run;
    if (!t->ref)
        return;
    report_model_build(&t->model, t->ref, NULL);   /* 0: the run is not NULL */
    t->n_rows = t->ref->n_configs;
    t->idx = dm_xcalloc(t->n_rows * ns + 1, sizeof *t->idx);
    for (size_t i = 0; i < t->n_rows; i++)
        for (size_t k = 0; k < ns; k++) {
            long found = -1;
            for (size_t j = 0; s[k].run && j < s[k].run->n_configs && found < 0; j++)
                if (strcmp(s[k].run->configs[j].key, t->ref->configs[i].key) == 0 &&
                    s[k].run->configs[j].ok)
                    found = (long)j;
            t->idx[i * ns + k] = found;
        }
}

static const dm_config_result *drivers__cfg(const drivers_side *s, size_t ns,
                                            const drivers__table *t, size_t row, size_t k)
{
    long j = t->idx[row * ns + k];
    return j < 0 ? NULL : &s[k].run->configs[j];
}

static double drivers__median(const dm_config_result *c, const char *counter)
{
    const dm_counter_result *r = c ? dm_config_counter(c, counter) : NULL;
    return r && r->available ? (r->has_samples ? r->median : r->value) : NAN;
}

/* The 95 % CI of the counter's median (from the run's statistics), NaN
 * when it has none. */
static void drivers__ci(const dm_config_result *c, const char *counter, double *ci)
{
    const dm_counter_result *r = c ? dm_config_counter(c, counter) : NULL;
    int ok = r && r->available && r->has_samples && isfinite(r->ci_lo) && isfinite(r->ci_hi);
    ci[0] = ok ? r->ci_lo : NAN;
    ci[1] = ok ? r->ci_hi : NAN;
}

static double drivers__ssim(const dm_config_result *c)
{
    return c && c->quality.present ? c->quality.ssim : NAN;
}

/* Row i's one label from the reference run's model (report_config_label),
 * e.g. "cube 160×90 · pom steps=8"; a configuration of another driver with
 * the same key has the same params and scene, so the same label. */
static const char *drivers__label(const drivers__table *t, size_t i)
{
    return t->model.rows[i].full_label;
}

/* The reference model's label of a scene (report_scene_label). */
static const char *drivers__scene_label(const drivers__table *t, const char *scene)
{
    for (size_t k = 0; k < t->model.n_scenes; k++)
        if (strcmp(t->model.scenes[k].name, scene) == 0)
            return t->model.scenes[k].label;
    return scene;
}

/* ---- agreement -------------------------------------------------------------- */

/* Kendall's tau of sides a and b over the rows both ran, of WallTime
 * (quality == 0) or of SSIM (quality == 1), with its bootstrap interval in
 * ci[2]; *pairs gets the rows used. */
static double drivers__tau(const drivers_side *s, size_t ns, const drivers__table *t, size_t a,
                           size_t b, int quality, size_t *pairs, double *ci)
{
    double *x = dm_xcalloc(t->n_rows + 1, sizeof *x), *y = dm_xcalloc(t->n_rows + 1, sizeof *y);
    size_t m = 0;
    for (size_t i = 0; i < t->n_rows; i++) {
        const dm_config_result *ca = drivers__cfg(s, ns, t, i, a), *cb = drivers__cfg(s, ns, t, i, b);
        if (!ca || !cb)
            continue;
        x[m] = quality ? drivers__ssim(ca) : drivers__median(ca, "WallTime");
        y[m] = quality ? drivers__ssim(cb) : drivers__median(cb, "WallTime");
        m += isfinite(x[m]) && isfinite(y[m]);
    }
    double tau = drivers_kendall_tau_ci(x, y, m, DRIVERS_TAU_REPS, 46, &ci[0], &ci[1]);
    free(x);
    free(y);
    *pairs = m;
    return tau;
}

/* The front of one scene on side k: its rows' indices into out (sorted by
 * time); returns how many. */
static size_t drivers__front(const drivers_side *s, size_t ns, const drivers__table *t, size_t k,
                             const char *scene, size_t *out)
{
    recommend_point *p = dm_xcalloc(t->n_rows + 1, sizeof *p);
    size_t *row = dm_xcalloc(t->n_rows + 1, sizeof *row), *f = dm_xcalloc(t->n_rows + 1, sizeof *f);
    size_t m = 0;
    for (size_t i = 0; i < t->n_rows; i++) {
        const dm_config_result *c = drivers__cfg(s, ns, t, i, k);
        if (!c || !c->scene || strcmp(c->scene, scene) != 0)
            continue;
        p[m] = (recommend_point){ .time = drivers__median(c, "WallTime"), .ci_lo = NAN, .ci_hi = NAN,
                                  .error = 1 - drivers__ssim(c) };
        row[m++] = i;
    }
    size_t nf = recommend_front(p, m, 0, f);   /* epsilon 0: the plain front */
    for (size_t i = 0; i < nf; i++)
        out[i] = row[f[i]];
    free(p);
    free(row);
    free(f);
    return nf;
}

/* 1 when row i is among the n rows of front f. */
static int drivers__on(const size_t *f, size_t n, size_t i)
{
    for (size_t k = 0; k < n; k++)
        if (f[k] == i)
            return 1;
    return 0;
}

/* Why row i, on side a's front, is not on side b's, into md: the row of
 * the same scene that dominates it on b (its time and 1 − SSIM no worse),
 * and whether the time CIs on b say so clearly or overlap (the data cannot
 * tell which is faster).  Adds the same as an object to jarr. */
static void drivers__why_off(const drivers_side *s, size_t ns, const drivers__table *t, size_t a,
                             size_t b, size_t i, dm_str *md, cJSON *jarr)
{
    const dm_config_result *cb = drivers__cfg(s, ns, t, i, b);
    const char *label = drivers__label(t, i);
    const char *dot = strstr(label, " · ");
    const char *name = dot ? dot + strlen(" · ") : label;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "key", t->ref->configs[i].key);
    cJSON_AddStringToObject(o, "on", s[a].driver);
    cJSON_AddStringToObject(o, "off", s[b].driver);
    dm_str_printf(md, "  - %s: on %s's front, not on %s's", name, s[a].driver, s[b].driver);
    double ti = drivers__median(cb, "WallTime"), ei = 1 - drivers__ssim(cb), ci[2], cd[2];
    drivers__ci(cb, "WallTime", ci);
    size_t best = SIZE_MAX;
    for (size_t j = 0; cb && j < t->n_rows; j++) {
        const dm_config_result *d = drivers__cfg(s, ns, t, j, b);
        if (j == i || !d || !d->scene || strcmp(d->scene, cb->scene) != 0)
            continue;
        double tj = drivers__median(d, "WallTime"), ej = 1 - drivers__ssim(d);
        if (tj <= ti && ej <= ei && (tj < ti || ej < ei) &&
            (best == SIZE_MAX || tj < drivers__median(drivers__cfg(s, ns, t, best, b), "WallTime")))
            best = j;
    }
    if (!cb || best == SIZE_MAX) {
        dm_str_printf(md, " (%s)\n", cb ? "no time or quality there" : "it did not run there");
        cJSON_AddStringToObject(o, "why", cb ? "no time or quality" : "did not run");
    } else {
        const dm_config_result *d = drivers__cfg(s, ns, t, best, b);
        drivers__ci(d, "WallTime", cd);
        int clear = isfinite(cd[1]) && isfinite(ci[0]) && cd[1] < ci[0];
        int same_time = !(drivers__median(d, "WallTime") < ti);
        const char *dl = drivers__label(t, best);
        const char *ddot = strstr(dl, " · ");
        dm_str_printf(md, ": there %s is %s (%.3g ms [%.3g, %.3g] against %.3g ms [%.3g, %.3g], "
                      "1 − SSIM %.4f against %.4f)%s\n", ddot ? ddot + strlen(" · ") : dl,
                      same_time ? "as fast and better" : "faster and no worse",
                      drivers__median(d, "WallTime") / 1e6, cd[0] / 1e6, cd[1] / 1e6, ti / 1e6,
                      ci[0] / 1e6, ci[1] / 1e6, 1 - drivers__ssim(d), ei,
                      same_time || clear ? ""
                                         : ": the time CIs overlap, so the data cannot say it is "
                                           "faster (within the noise)");
        cJSON_AddStringToObject(o, "dominated_by", d->key);
        cJSON_AddBoolToObject(o, "clear", same_time || clear);
    }
    cJSON_AddItemToArray(jarr, o);
}

/* The distinct scenes of the reference run, in order. */
static size_t drivers__scenes(const drivers__table *t, const char **out)
{
    size_t n = 0;
    for (size_t i = 0; i < t->n_rows; i++) {
        const char *sc = t->ref->configs[i].scene;
        int seen = !sc;
        for (size_t j = 0; j < n && !seen; j++)
            seen = strcmp(out[j], sc) == 0;
        if (!seen)
            out[n++] = sc;
    }
    return n;
}

/* ---- writing ---------------------------------------------------------------- */

static void drivers__fmt(dm_str *s, double v, const char *fmt)
{
    if (isfinite(v))
        dm_str_printf(s, fmt, v);
    else
        dm_str_cat(s, "—");
}

#define DRIVERS__STR2(x) #x
#define DRIVERS__STR(x) DRIVERS__STR2(x)

/* "v [lo, hi]", or "v (interval unavailable)", or "—". */
static void drivers__fmt_ci(dm_str *s, double v, const double *ci, const char *fmt)
{
    drivers__fmt(s, v, fmt);
    if (!isfinite(v))
        return;
    if (!isfinite(ci[0]) || !isfinite(ci[1])) {
        dm_str_cat(s, " (interval unavailable: too few configurations)");
        return;
    }
    dm_str_cat(s, " [");
    dm_str_printf(s, fmt, ci[0]);
    dm_str_cat(s, ", ");
    dm_str_printf(s, fmt, ci[1]);
    dm_str_cat(s, "]");
}

static void drivers__md_runs(const drivers_side *s, size_t ns, dm_str *md, cJSON *jd)
{
    dm_str_cat(md, "| driver | run | renderer | GL | fingerprint | configurations ok |\n"
                   "|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < ns; k++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "driver", s[k].driver);
        const dm_run_result *r = s[k].run;
        if (!r) {
            dm_str_printf(md, "| %s | — | %s | | | |\n", s[k].driver, s[k].why ? s[k].why : "did not run");
            cJSON_AddStringToObject(o, "why", s[k].why ? s[k].why : "did not run");
        } else {
            size_t ok = 0;
            for (size_t i = 0; i < r->n_configs; i++)
                ok += (size_t)r->configs[i].ok;
            const char *ren = dm_kv_get(r->environment, r->n_environment, "renderer");
            const char *gl = dm_kv_get(r->environment, r->n_environment, "gl_version");
            const char *fp = dm_kv_get(r->environment, r->n_environment, "fingerprint");
            dm_str_printf(md, "| %s | %s | %s | %s | %s | %zu of %zu |\n", s[k].driver, r->id,
                          ren ? ren : "?", gl ? gl : "?", fp ? fp : "?", ok, r->n_configs);
            cJSON_AddStringToObject(o, "run", r->id);
            cJSON_AddStringToObject(o, "renderer", ren ? ren : "");
            cJSON_AddStringToObject(o, "fingerprint", fp ? fp : "");
            cJSON_AddNumberToObject(o, "configs_ok", (double)ok);
        }
        cJSON_AddItemToArray(jd, o);
    }
}

/* The run's calibration figure (run/calibrate.h writes these keys into
 * the environment record), NaN when absent. */
static double drivers__env_num(const dm_run_result *r, const char *key)
{
    const char *v = dm_kv_get(r->environment, r->n_environment, key);
    char *end = NULL;
    double x = v ? strtod(v, &end) : NAN;
    return v && end != v ? x : NAN;
}

/* The drift check between the drivers' runs (drivers_drift), in words. */
static void drivers__md_drift(const drivers_side *s, size_t ns, dm_str *md, cJSON *root)
{
    double *st = dm_xcalloc(ns + 1, sizeof *st), *en = dm_xcalloc(ns + 1, sizeof *en);
    for (size_t k = 0; k < ns; k++) {
        st[k] = s[k].run ? drivers__env_num(s[k].run, "calibration_cpu_ns_start") : NAN;
        en[k] = s[k].run ? drivers__env_num(s[k].run, "calibration_cpu_ns_end") : NAN;
    }
    double moved, noise;
    int flag = drivers_drift(st, en, ns, &moved, &noise);
    cJSON *o = cJSON_AddObjectToObject(root, "drift");
    dm_str_cat(md, "\n## Did the machine's speed move between the drivers' runs?\n\n");
    if (flag < 0) {
        dm_str_cat(md, "Unavailable: fewer than two runs recorded the CPU calibration kernel at "
                       "their start and end.\n");
        cJSON_AddStringToObject(o, "unavailable", "fewer than two runs with the calibration");
    } else {
        dm_str_cat(md, "The CPU calibration kernel (the same work on any driver) took, per run "
                       "(start → end):");
        for (size_t k = 0; k < ns; k++)
            if (isfinite(st[k]) && isfinite(en[k]))
                dm_str_printf(md, " %s %.2f → %.2f ms;", s[k].driver, st[k] / 1e6, en[k] / 1e6);
        dm_str_printf(md, " the runs' means are %.0f %% apart, against %.0f %% within a run "
                          "(at least %.0f %%). ", moved * 100, noise * 100, DRIVERS_DRIFT_FLOOR * 100);
        dm_str_cat(md, flag ? "**The machine's speed moved between the drivers' runs more than "
                              "within one**: times of different drivers are not comparable at face "
                              "value (other processes, or the CPU's clock, changed); the taus and "
                              "fronts, which compare orders within each driver, suffer less. Run "
                              "`drivers` again on a quieter machine.\n"
                            : "No drift beyond the noise within a run.\n");
        cJSON_AddNumberToObject(o, "moved", moved);
        cJSON_AddNumberToObject(o, "noise", noise);
        cJSON_AddBoolToObject(o, "drifted", flag);
    }
    free(st);
    free(en);
}

static void drivers__md_rows(const drivers_side *s, size_t ns, const drivers__table *t, dm_str *md,
                             cJSON *jrows)
{
    dm_str_cat(md, "\n## Per configuration\n\nMedian WallTime per frame (ms) with its 95 % CI, "
                   "Instructions per frame (millions, counted: no interval) and SSIM against the "
                   "reference, per driver.\n\n| configuration |");
    for (size_t k = 0; k < ns; k++)
        if (s[k].run)
            dm_str_printf(md, " %s ms | %s Minstr | %s SSIM |", s[k].driver, s[k].driver, s[k].driver);
    dm_str_cat(md, "\n|---|");
    for (size_t k = 0; k < ns; k++)
        if (s[k].run)
            dm_str_cat(md, "---|---|---|");
    dm_str_cat(md, "\n");
    for (size_t i = 0; i < t->n_rows; i++) {
        const char *label = drivers__label(t, i);
        dm_str_printf(md, "| %s |", label);
        cJSON *o = cJSON_CreateObject(), *per = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "key", t->ref->configs[i].key);
        cJSON_AddStringToObject(o, "label", label);
        for (size_t k = 0; k < ns; k++) {
            if (!s[k].run)
                continue;
            const dm_config_result *c = drivers__cfg(s, ns, t, i, k);
            double ms = drivers__median(c, "WallTime") / 1e6, mi = drivers__median(c, "Instructions") / 1e6;
            double q = drivers__ssim(c);
            double ci[2];
            drivers__ci(c, "WallTime", ci);
            ci[0] /= 1e6, ci[1] /= 1e6;
            dm_str_cat(md, " ");
            if (isfinite(ms) && !isfinite(ci[0]))
                dm_str_printf(md, "%.3g (no CI)", ms);
            else
                drivers__fmt_ci(md, ms, ci, "%.3g");
            dm_str_cat(md, " | ");
            drivers__fmt(md, mi, "%.4g");
            dm_str_cat(md, " | ");
            drivers__fmt(md, q, "%.4f");
            dm_str_cat(md, " |");
            cJSON *d = cJSON_CreateObject();
            cJSON_AddNumberToObject(d, "WallTime_ms", ms);
            cJSON_AddNumberToObject(d, "WallTime_ci_lo_ms", ci[0]);
            cJSON_AddNumberToObject(d, "WallTime_ci_hi_ms", ci[1]);
            cJSON_AddNumberToObject(d, "Instructions", mi * 1e6);
            cJSON_AddNumberToObject(d, "SSIM", q);
            cJSON_AddItemToObject(per, s[k].driver, d);
        }
        dm_str_cat(md, "\n");
        cJSON_AddItemToObject(o, "drivers", per);
        cJSON_AddItemToArray(jrows, o);
    }
}

static void drivers__md_agreement(const drivers_side *s, size_t ns, const drivers__table *t,
                                  dm_str *md, cJSON *jagree)
{
    dm_str_cat(md, "\n## Do the drivers rank the configurations alike?\n\nKendall's tau-b over "
                   "the configurations both drivers ran: 1 = the same order, 0 = unrelated, "
                   "-1 = reversed; in brackets its 95 % bootstrap interval (the configurations "
                   "resampled " DRIVERS__STR(DRIVERS_TAU_REPS) " times, seed 46): with few "
                   "configurations it is wide, and a tau whose interval holds 0 does not show the "
                   "drivers agree.\n\n| drivers | configurations | tau of WallTime [95% CI] | tau of "
                   "SSIM [95% CI] |\n|---|---|---|---|\n");
    for (size_t a = 0; a < ns; a++)
        for (size_t b = a + 1; b < ns; b++) {
            if (!s[a].run || !s[b].run)
                continue;
            size_t pt = 0, pq = 0;
            double ct[2], cq[2];
            double tt = drivers__tau(s, ns, t, a, b, 0, &pt, ct);
            double tq = drivers__tau(s, ns, t, a, b, 1, &pq, cq);
            dm_str_printf(md, "| %s · %s | %zu | ", s[a].driver, s[b].driver, pt);
            drivers__fmt_ci(md, tt, ct, "%.3f");
            dm_str_cat(md, " | ");
            drivers__fmt_ci(md, tq, cq, "%.3f");
            dm_str_cat(md, " |\n");
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "a", s[a].driver);
            cJSON_AddStringToObject(o, "b", s[b].driver);
            cJSON_AddNumberToObject(o, "configs", (double)pt);
            cJSON_AddNumberToObject(o, "tau_walltime", tt);
            cJSON_AddNumberToObject(o, "tau_walltime_lo", ct[0]);
            cJSON_AddNumberToObject(o, "tau_walltime_hi", ct[1]);
            cJSON_AddNumberToObject(o, "tau_ssim", tq);
            cJSON_AddNumberToObject(o, "tau_ssim_lo", cq[0]);
            cJSON_AddNumberToObject(o, "tau_ssim_hi", cq[1]);
            cJSON_AddItemToArray(jagree, o);
        }
}

static void drivers__md_fronts(const drivers_side *s, size_t ns, const drivers__table *t,
                               dm_str *md, cJSON *jfronts)
{
    dm_str_cat(md, "\n## Pareto fronts per scene (WallTime against 1 − SSIM)\n\n");
    const char **scenes = dm_xcalloc(t->n_rows + 1, sizeof *scenes);
    size_t nsc = drivers__scenes(t, scenes);
    size_t *f = dm_xcalloc(t->n_rows + 1, sizeof *f), *f0 = dm_xcalloc(t->n_rows + 1, sizeof *f0);
    for (size_t sc = 0; sc < nsc; sc++) {
        const char *sl = drivers__scene_label(t, scenes[sc]);
        dm_str_printf(md, "**%s**\n\n", sl);
        cJSON *js = cJSON_CreateObject();
        size_t n0 = SIZE_MAX;
        int same = 1;
        for (size_t k = 0; k < ns; k++) {
            if (!s[k].run)
                continue;
            size_t nf = drivers__front(s, ns, t, k, scenes[sc], f);
            dm_str_printf(md, "- %s:", s[k].driver);
            cJSON *arr = cJSON_CreateArray();
            for (size_t i = 0; i < nf; i++) {
                const char *label = drivers__label(t, f[i]);
                const char *dot = strstr(label, " · ");   /* the scene is the heading */
                dm_str_printf(md, "%s %s", i ? " →" : "", dot ? dot + strlen(" · ") : label);
                cJSON_AddItemToArray(arr, cJSON_CreateString(t->ref->configs[f[i]].key));
            }
            dm_str_cat(md, "\n");
            cJSON_AddItemToObject(js, s[k].driver, arr);
            if (n0 == SIZE_MAX) {
                n0 = nf;
                memcpy(f0, f, nf * sizeof *f);
            } else {
                same = same && nf == n0 && memcmp(f0, f, nf * sizeof *f) == 0;
            }
        }
        if (same) {
            dm_str_cat(md, "\nThe fronts agree.\n\n");
        } else {   /* what differs, against the first driver that ran, with its uncertainty */
            dm_str_cat(md, "\nWhat differs:\n\n");
            cJSON *jd = cJSON_AddArrayToObject(js, "differences");
            size_t a = 0;
            while (!s[a].run)
                a++;
            size_t *fa = dm_xcalloc(t->n_rows + 1, sizeof *fa);
            size_t na = drivers__front(s, ns, t, a, scenes[sc], fa);
            for (size_t b = a + 1; b < ns; b++) {
                if (!s[b].run)
                    continue;
                size_t nb = drivers__front(s, ns, t, b, scenes[sc], f);
                for (size_t i = 0; i < na; i++)
                    if (!drivers__on(f, nb, fa[i]))
                        drivers__why_off(s, ns, t, a, b, fa[i], md, jd);
                for (size_t i = 0; i < nb; i++)
                    if (!drivers__on(fa, na, f[i]))
                        drivers__why_off(s, ns, t, b, a, f[i], md, jd);
            }
            dm_str_cat(md, "\n");
            free(fa);
        }
        cJSON_AddStringToObject(js, "scene", sl);
        cJSON_AddBoolToObject(js, "agree", same);
        cJSON_AddItemToObject(jfronts, scenes[sc], js);
    }
    free(f);
    free(f0);
    free(scenes);
}

int drivers_report_write(const drivers_side *sides, size_t n, const char *dir, dm_str *err)
{
    drivers__table t;
    drivers__match(sides, n, &t);
    dm_str md = {0};
    cJSON *root = cJSON_CreateObject(), *jd = cJSON_AddArrayToObject(root, "drivers");
    dm_str_cat(&md, "# One sweep on several drivers\n\nEach driver ran the sweep in its own run, "
                    "with its own environment and fingerprint: `dmbench compare` keeps them "
                    "apart as different machines. Configurations are matched by key.\n\n");
    drivers__md_runs(sides, n, &md, jd);
    if (t.ref) {
        drivers__md_drift(sides, n, &md, root);
        drivers__md_rows(sides, n, &t, &md, cJSON_AddArrayToObject(root, "configs"));
        drivers__md_agreement(sides, n, &t, &md, cJSON_AddArrayToObject(root, "agreement"));
        drivers__md_fronts(sides, n, &t, &md, cJSON_AddObjectToObject(root, "fronts"));
    } else {
        dm_str_cat(&md, "\nNo driver ran the sweep.\n");
    }
    report_json_exact_numbers(root);
    char *json = cJSON_Print(root);
    char *pm = dm_xasprintf("%s/drivers.md", dir), *pj = dm_xasprintf("%s/drivers.json", dir);
    int rc = 0;
    if ((rc = dm_write_file(pm, md.buf, md.len)) != 0)   /* DM_ERR_DISK: the machine's */
        dm_str_printf(err, "%s: cannot write: %s", pm, strerror(errno));
    else if ((rc = dm_write_file(pj, json, strlen(json))) != 0)
        dm_str_printf(err, "%s: cannot write: %s", pj, strerror(errno));
    free(pm);
    free(pj);
    free(json);
    cJSON_Delete(root);
    dm_str_free(&md);
    free(t.idx);
    report_model_free(&t.model);
    return rc;
}
