/* compare_machine.c — what the runs say about the machine they ran on:
 * blocking by round within each run, and the checks that decide how far
 * the machine alone may have moved the times between BASE and NEW
 * (compare.h, docs/ci-gating.md "Timing between runs"). */
#include "gate/compare_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_util.h"
#include "models/blocking.h"
#include "models/stats.h"
#include "run/calibrate.h"

/* The time counter of c when it has samples, else NULL. */
static const dm_counter_result *compare__timed(const dm_config_result *c, const char *counter)
{
    const dm_counter_result *t = c->ok ? dm_config_counter(c, counter) : NULL;
    return t && t->available && t->n_samples ? t : NULL;
}

/* 1 when configuration j shares the scene of configuration i. */
static int compare__same_scene(const dm_config_result *a, const dm_config_result *b)
{
    return a->scene && b->scene && strcmp(a->scene, b->scene) == 0;
}

/* Blocks the scene of configuration `first` (its first configuration):
 * corrected copies into out[], the scene's round spread returned. */
static double compare__block_scene(const dm_run_result *r, size_t first, const char *counter,
                                   double **out)
{
    size_t n = 0, rounds = 0;
    size_t *idx = dm_xcalloc(r->n_configs + 1, sizeof *idx);
    blocking_series *s = dm_xcalloc(r->n_configs + 1, sizeof *s);
    for (size_t j = first; j < r->n_configs; j++) {
        const dm_counter_result *t = compare__timed(&r->configs[j], counter);
        if (t && compare__same_scene(&r->configs[first], &r->configs[j])) {
            idx[n] = j;
            s[n++] = (blocking_series){ t->samples, t->n_samples };
            rounds = t->n_samples > rounds ? t->n_samples : rounds;
        }
    }
    double spread = 0;
    if (n > BLOCKING_MIN_OTHERS) {
        double **dst = dm_xcalloc(n, sizeof *dst);
        for (size_t k = 0; k < n; k++)
            dst[k] = out[idx[k]] = dm_xcalloc(s[k].n + 1, sizeof **dst);
        blocking_correct(s, n, dst);
        double *f = dm_xcalloc(rounds + 1, sizeof *f);
        blocking_round_factors(s, n, f, rounds);
        spread = blocking_spread(f, rounds);
        free(f);
        free(dst);
    }
    free(s);
    free(idx);
    return spread;
}

/* Precision of one configuration's samples: CI half-width / median. */
static double compare__ci_rel(const double *x, size_t n)
{
    stats_summary su;
    return stats_summarize(x, n, 1, &su) == 0 ? su.ci_rel : NAN;
}

/* The side's precision figures, raw and blocked. */
static void compare__precision(const dm_run_result *r, const char *counter, double *const *blk,
                               compare_side_state *st)
{
    double *raw = dm_xcalloc(r->n_configs + 1, sizeof *raw);
    double *bl = dm_xcalloc(r->n_configs + 1, sizeof *bl);
    for (size_t i = 0; i < r->n_configs; i++) {
        const dm_counter_result *t = compare__timed(&r->configs[i], counter);
        if (!t)
            continue;
        raw[st->n_timed] = compare__ci_rel(t->samples, t->n_samples);
        bl[st->n_timed] = blk[i] ? compare__ci_rel(blk[i], t->n_samples) : raw[st->n_timed];
        st->n_precise_raw += raw[st->n_timed] <= 0.03;
        st->n_precise_blocked += bl[st->n_timed] <= 0.03;
        st->n_timed++;
    }
    st->ci_rel_raw = stats_median(raw, st->n_timed);
    st->ci_rel_blocked = stats_median(bl, st->n_timed);
    free(raw);
    free(bl);
}

/* The median of a counter's samples: what a ratio is of (in paired mode
 * the samples are the pooled run minima; the stored median is one run's). */
static double compare__sample_median(const dm_counter_result *t)
{
    return stats_median(t->samples, t->n_samples);
}

/* Median over configurations of median(wall) / median(CPUTime). */
static double compare__wall_per_cpu(const dm_run_result *r, const char *wall)
{
    double *v = dm_xcalloc(r->n_configs + 1, sizeof *v);
    size_t m = 0;
    for (size_t i = 0; i < r->n_configs; i++) {
        const dm_counter_result *w = compare__timed(&r->configs[i], wall);
        const dm_counter_result *c = compare__timed(&r->configs[i], "CPUTime");
        if (w && c && compare__sample_median(c) > 0)
            v[m++] = compare__sample_median(w) / compare__sample_median(c);
    }
    double x = m ? stats_median(v, m) : NAN;
    free(v);
    return x;
}

static double compare__load(const dm_run_result *r)
{
    const char *l = dm_kv_get(r->environment, r->n_environment, "load_average");
    char *end = NULL;
    double x = l ? strtod(l, &end) : NAN;
    return l && end != l && isfinite(x) ? x : NAN;
}

/* One calibration figure of the run's environment; NaN when absent. */
static double compare__env_num(const dm_run_result *r, const char *key)
{
    const char *v = dm_kv_get(r->environment, r->n_environment, key);
    char *end = NULL;
    double x = v ? strtod(v, &end) : NAN;
    return v && end != v && isfinite(x) && x > 0 ? x : NAN;
}

/* The run's calibration piece ("cpu" or "draw"): the mean of its start and
 * end figures (either alone when the other is missing); its drift from
 * start to end into *drift (kept when larger). */
static double compare__calibration(const dm_run_result *r, const char *piece, double *drift)
{
    double a = compare__env_num(r, calibrate_key(piece, "start"));
    double b = compare__env_num(r, calibrate_key(piece, "end"));
    if (isfinite(a) && isfinite(b))
        *drift = fmax(*drift, fabs(b / a - 1));
    return isfinite(a) && isfinite(b) ? (a + b) / 2 : isfinite(a) ? a : b;
}

double **compare__block(const dm_run_result *r, const char *counter, int no_blocking,
                        compare_side_state *st)
{
    memset(st, 0, sizeof *st);
    double **blk = dm_xcalloc(r->n_configs + 1, sizeof *blk);
    for (size_t i = 0; i < r->n_configs && !no_blocking; i++) {
        int seen = 0;   /* the scene's first configuration blocks the whole scene */
        for (size_t j = 0; j < i && !seen; j++)
            seen = compare__same_scene(&r->configs[i], &r->configs[j]);
        if (!seen && r->configs[i].scene)
            st->round_spread = fmax(st->round_spread, compare__block_scene(r, i, counter, blk));
    }
    compare__precision(r, counter, blk, st);
    st->load = compare__load(r);
    st->cal_cpu_ns = compare__calibration(r, "cpu", &st->cal_drift);
    st->cal_draw_ns = compare__calibration(r, "draw", &st->cal_drift);
    st->wall_per_cpu = compare__wall_per_cpu(r, counter);
    return blk;
}

void compare__blocked_free(double **blocked, size_t n)
{
    for (size_t i = 0; blocked && i < n; i++)
        free(blocked[i]);
    free(blocked);
}

/* Median over the configurations of both runs of median(NEW)/median(BASE)
 * of counter. */
static double compare__common_mode(const dm_run_result *base, const dm_run_result *new_,
                                   const char *counter)
{
    double *v = dm_xcalloc(base->n_configs + 1, sizeof *v);
    size_t m = 0;
    for (size_t i = 0; i < base->n_configs; i++) {
        const dm_counter_result *b = compare__timed(&base->configs[i], counter);
        for (size_t j = 0; b && compare__sample_median(b) > 0 && j < new_->n_configs; j++)
            if (strcmp(base->configs[i].key, new_->configs[j].key) == 0) {
                const dm_counter_result *n = compare__timed(&new_->configs[j], counter);
                if (n)
                    v[m++] = compare__sample_median(n) / compare__sample_median(b);
                break;
            }
    }
    double x = m ? stats_median(v, m) : NAN;
    free(v);
    return x;
}

/* The checks in words into m->reason (NULL when nothing changed). */
static void compare__machine_reason(const compare_desc *d, compare_machine *m)
{
    dm_str s = {0};
    if (m->contention)
        dm_str_printf(&s, "%s x%.2f while CPUTime x%.2f between the runs (contention: other "
                      "processes took the CPU)", d->time_counter, m->wall_ratio, m->cpu_ratio);
    if (m->load_changed)
        dm_str_printf(&s, "%sload average %.2f (BASE) -> %.2f (NEW)", s.len ? "; " : "",
                      m->base.load, m->new_.load);
    if (m->cal_changed)
        dm_str_printf(&s, "%sthe calibration workload took x%.2f (CPU kernel) and x%.2f (draw) "
                      "of BASE's time in NEW: the machine itself ran at another speed",
                      s.len ? "; " : "", m->cal_ratio, m->cal_draw_ratio);
    const char *side[2] = { "BASE", "NEW" };
    const compare_side_state *st[2] = { &m->base, &m->new_ };
    for (int i = 0; i < 2; i++)
        if (st[i]->cal_drift > COMPARE_CALIB_TOL)
            dm_str_printf(&s, "%sthe calibration workload moved %.0f%% between %s's start and end "
                          "(the machine changed during the run)", s.len ? "; " : "",
                          st[i]->cal_drift * 100, side[i]);
    m->reason = s.len ? dm_str_take(&s) : NULL;
    dm_str_free(&s);
}

void compare__machine_checks(const compare_desc *d, const dm_run_result *base,
                             const dm_run_result *new_,
                             const int *timed, compare_result *out)
{
    compare_machine *m = &out->machine;
    double *v = dm_xcalloc(out->n_items + 1, sizeof *v);
    size_t k = 0;
    for (size_t i = 0; i < out->n_items; i++)
        if (timed[i])
            v[k++] = out->items[i].ratio;
    m->wall_ratio = k ? stats_median(v, k) : NAN;
    free(v);
    m->cpu_ratio = strcmp(d->time_counter, "CPUTime") == 0
                       ? NAN : compare__common_mode(base, new_, "CPUTime");
    m->contention = isfinite(m->wall_ratio) && isfinite(m->cpu_ratio) && m->cpu_ratio > 0 &&
                    fabs(log(m->wall_ratio / m->cpu_ratio)) > log1p(COMPARE_CONTENTION_TOL);
    const char *cpus = dm_kv_get(new_->environment, new_->n_environment, "cpu_count");
    double tol = fmax(COMPARE_LOAD_TOL, (cpus ? atof(cpus) : 0) / 4);
    m->load_changed = isfinite(m->base.load) && isfinite(m->new_.load) &&
                      fabs(m->new_.load - m->base.load) >= tol;
    m->cal_ratio = m->new_.cal_cpu_ns / m->base.cal_cpu_ns;
    m->cal_draw_ratio = m->new_.cal_draw_ns / m->base.cal_draw_ns;
    m->cal_changed = (isfinite(m->cal_ratio) && fabs(log(m->cal_ratio)) > log1p(COMPARE_CALIB_TOL)) ||
                     (isfinite(m->cal_draw_ratio) &&
                      fabs(log(m->cal_draw_ratio)) > log1p(COMPARE_CALIB_TOL));
    m->wall_per_cal = m->wall_ratio / m->cal_ratio;
    compare__machine_reason(d, m);
    if (d->paired) {   /* ABBA rounds on one machine: its changes hit both sides ... */
        m->spread = 0;
        m->lo = m->hi = 1;
        if (m->contention) {   /* ... unless one side waited more: what CPU time does not explain */
            m->lo = fmin(1, m->wall_ratio / m->cpu_ratio);
            m->hi = fmax(1, m->wall_ratio / m->cpu_ratio);
        }
        return;
    }
    /* several runs a side: each run is one sample, so the between-run
     * spread is in the CI and the assumed floor is not needed */
    m->spread = d->replicated ? 0 : fmax(d->run_spread, fmax(m->base.round_spread,
                                                             m->new_.round_spread));
    m->lo = 1 / (1 + m->spread);
    m->hi = 1 + m->spread;
    if ((m->contention || m->load_changed) && isfinite(m->wall_ratio)) {
        m->lo = fmin(1, m->wall_ratio) / (1 + m->spread);
        m->hi = fmax(1, m->wall_ratio) * (1 + m->spread);
    }
    for (int i = 0; m->cal_changed && i < 2; i++) {   /* the machine's own change, measured */
        double c = i ? m->cal_draw_ratio : m->cal_ratio;
        if (isfinite(c)) {
            m->lo = fmin(m->lo, fmin(1, c) / (1 + m->spread));
            m->hi = fmax(m->hi, fmax(1, c) * (1 + m->spread));
        }
    }
}
