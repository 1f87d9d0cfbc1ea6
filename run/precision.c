/* precision.c — drift removed from a finished run, noise floor (see precision.h). */
#include "run/precision.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_table.h"
#include "core/dm_util.h"
#include "models/drift.h"
#include "models/stats.h"

/* One scene laid out by round: its configurations (indices into the run)
 * and, for each, the round of each of its WallTime samples. */
typedef struct precision__scene {
    const char *name;
    size_t *cfg, nc;
    size_t **round_of;       /* round_of[c][j]: the round of sample j of configuration c */
    size_t *n;               /* WallTime samples of each configuration */
    size_t nr;
    double *calib;           /* nr values, NULL when the rounds were not recorded */
    int aligned;             /* 1: by the recorded rounds; 0: by sample index */
} precision__scene;

static const dm_counter_result *precision__wall(const dm_config_result *c)
{
    const dm_counter_result *w = c->ok ? dm_config_counter(c, "WallTime") : NULL;
    return w && w->available && w->has_samples && w->n_samples ? w : NULL;
}

static int precision__timed(const dm_counter_result *k)
{
    return k->available && k->has_samples && k->n_samples && !k->deterministic && k->unit &&
           strcmp(k->unit, "ns") == 0;
}

/* 1 when the space-separated list keys names key. */
static int precision__names(const char *keys, const char *key)
{
    size_t n = strlen(key);
    for (const char *p = keys; p && (p = strstr(p, key)) != NULL; p += n)
        if ((p == keys || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

/* Lays scene's samples out by the recorded rounds when every configuration
 * has exactly one sample per round that names it; else by sample index
 * (aligned 0: rounds not recorded, or an interrupted process lost one). */
static void precision__layout(const dm_run_result *run, precision__scene *s)
{
    size_t max_n = 0, nr = 0;
    for (size_t c = 0; c < s->nc; c++) {
        s->n[c] = precision__wall(&run->configs[s->cfg[c]])->n_samples;
        s->round_of[c] = dm_xcalloc(s->n[c] + 1, sizeof **s->round_of);
        max_n = s->n[c] > max_n ? s->n[c] : max_n;
    }
    for (size_t r = 0; r < run->n_rounds; r++)
        nr += strcmp(run->rounds[r].scene, s->name) == 0;
    s->aligned = nr > 0;
    s->calib = dm_xcalloc(nr + 1, sizeof *s->calib);
    for (size_t c = 0; c < s->nc && s->aligned; c++) {
        const char *key = run->configs[s->cfg[c]].key;
        size_t j = 0, k = 0;
        for (size_t r = 0; r < run->n_rounds; r++) {
            if (strcmp(run->rounds[r].scene, s->name) != 0)
                continue;
            s->calib[k] = run->rounds[r].calib_ns;
            if (precision__names(run->rounds[r].keys, key)) {
                if (j < s->n[c])
                    s->round_of[c][j] = k;
                j++;
            }
            k++;
        }
        s->aligned = j == s->n[c];
    }
    s->nr = s->aligned ? nr : max_n;
    for (size_t c = 0; c < s->nc && !s->aligned; c++)
        for (size_t j = 0; j < s->n[c]; j++)
            s->round_of[c][j] = j;
    if (!s->aligned) {
        free(s->calib);
        s->calib = NULL;
    }
}

static void precision__scene_free(precision__scene *s)
{
    for (size_t c = 0; c < s->nc; c++)
        free(s->round_of[c]);
    free(s->round_of);
    free(s->n);
    free(s->cfg);
    free(s->calib);
}

/* The configurations of the scene named like run->configs[first]. */
static void precision__collect(const dm_run_result *run, size_t first, precision__scene *s)
{
    *s = (precision__scene){ .name = run->configs[first].scene };
    s->cfg = dm_xcalloc(run->n_configs + 1, sizeof *s->cfg);
    for (size_t i = first; i < run->n_configs; i++)
        if (run->configs[i].scene && strcmp(run->configs[i].scene, s->name) == 0 &&
            precision__wall(&run->configs[i]))
            s->cfg[s->nc++] = i;
    s->round_of = dm_xcalloc(s->nc + 1, sizeof *s->round_of);
    s->n = dm_xcalloc(s->nc + 1, sizeof *s->n);
    precision__layout(run, s);
}

/* Sets the corrected figures of counter `name` of the scene's
 * configurations from the drift result d. */
static void precision__set(dm_run_result *run, const precision__scene *s, const char *name,
                           const drift_result *d)
{
    for (size_t c = 0; d->corrected && c < s->nc; c++) {
        dm_counter_result *k = (dm_counter_result *)dm_config_counter(&run->configs[s->cfg[c]], name);
        const drift_config *e = &d->configs[c];
        if (k && isfinite(e->median) && isfinite(e->lo) && isfinite(e->hi)) {
            k->corrected = 1;
            k->corr_median = e->median;
            k->corr_ci_lo = e->lo;
            k->corr_ci_hi = e->hi;
            k->corr_between = isfinite(e->between_lo) && isfinite(e->between_hi);
            k->corr_between_lo = e->between_lo;
            k->corr_between_hi = e->between_hi;
        }
    }
}

/* Corrects counter `name` of the scene's configurations into *out (caller
 * frees); nothing is set in the run. */
static void precision__counter(const dm_run_result *run, const precision__scene *s, const char *name,
                               uint64_t seed, drift_result *out)
{
    double *x = dm_xcalloc(s->nc * s->nr + 1, sizeof *x);
    for (size_t i = 0; i < s->nc * s->nr; i++)
        x[i] = NAN;
    for (size_t c = 0; c < s->nc; c++) {
        const dm_counter_result *k = dm_config_counter(&run->configs[s->cfg[c]], name);
        if (k && precision__timed(k) && k->n_samples == s->n[c])
            for (size_t j = 0; j < s->n[c]; j++)
                x[c * s->nr + s->round_of[c][j]] = k->samples[j];
    }
    drift_correct(&(drift_desc){ .n_configs = s->nc, .n_rounds = s->nr, .x = x, .calib = s->calib,
                                 .seed = seed }, out);
    free(x);
}

/* Median of the finite v[0..n) (reorders v); NaN when none. */
static double precision__median(double *v, size_t n)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i]))
            v[m++] = v[i];
    return stats_median_inplace(v, m);
}

/* Which figure predicted the drift better: the one that leaves the least
 * spread, when it leaves less than the raw samples have. */
static const char *precision__predictor(const drift_result *d)
{
    double best = fmin(d->loo_noise, isfinite(d->calib_noise) ? d->calib_noise : INFINITY);
    if (!(best < d->raw_noise))
        return "neither";
    return best == d->loo_noise ? "common mode" : "calibration";
}

/* The scene's precision entry from its WallTime drift result. */
static void precision__entry(const dm_run_result *run, const precision__scene *s, const drift_result *d,
                             int keep, dm_scene_precision *p)
{
    *p = (dm_scene_precision){ .scene = dm_xstrdup(s->name), .corrected = keep,
                               .n_rounds = (int)d->n_rounds_used, .machine_spread = d->machine_spread,
                               .raw_noise = d->raw_noise, .loo_noise = d->loo_noise,
                               .calib_noise = d->calib_noise, .between_runs = keep,
                               .reference_spread = keep ? d->reference_spread : NAN,
                               .half_shift = keep ? d->half_shift : NAN };
    if (!d->corrected)
        p->reason = dm_xasprintf("%s; raw figures only", d->why);
    else if (!keep)
        p->reason = dm_xasprintf("no drift to remove: the rounds' common mode moved ±%.2f %%, no more "
                                 "than twice the ±%.2f %% the configurations' own noise gives it; raw "
                                 "figures only", 100 * d->machine_spread, 100 * d->factor_noise);
    else if (!s->aligned)
        p->reason = dm_xstrdup("rounds not recorded for every sample (a run from before they were, or "
                               "an interrupted measuring process): samples aligned by their index");
    p->predictor = d->corrected ? dm_xstrdup(precision__predictor(d)) : NULL;
    double *hw = dm_xcalloc(s->nc + 1, sizeof *hw);
    for (size_t c = 0; c < s->nc; c++) {
        const dm_counter_result *w = precision__wall(&run->configs[s->cfg[c]]);
        hw[c] = w->corrected ? (w->corr_ci_hi - w->corr_ci_lo) / 2 / w->corr_median
                             : (w->ci_hi - w->ci_lo) / 2 / w->median;
    }
    p->resolvable = sqrt(2.0) * precision__median(hw, s->nc);
    free(hw);
}

/* Corrects one scene: WallTime decides whether the correction is kept,
 * then every other timed counter follows it. */
static int precision__scene_apply(dm_run_result *run, size_t first, uint64_t seed, dm_scene_precision *p)
{
    precision__scene s;
    precision__collect(run, first, &s);
    drift_result wd;
    precision__counter(run, &s, "WallTime", seed, &wd);
    int keep = wd.corrected && wd.helps;
    if (keep)
        precision__set(run, &s, "WallTime", &wd);
    const dm_config_result *c0 = &run->configs[first];
    for (size_t k = 0; keep && k < c0->n_counters; k++) {
        if (strcmp(c0->counters[k].name, "WallTime") == 0 || !precision__timed(&c0->counters[k]))
            continue;
        drift_result o;
        precision__counter(run, &s, c0->counters[k].name, seed, &o);
        precision__set(run, &s, c0->counters[k].name, &o);
        drift_result_free(&o);
    }
    precision__entry(run, &s, &wd, keep, p);
    drift_result_free(&wd);
    precision__scene_free(&s);
    return keep;
}

/* The run's slow drift: the root mean square over its corrected scenes of
 * their half shifts, divided by √2 (the two halves of a scene taken as two
 * independent draws of the host's level, as two runs are); NaN when no
 * corrected scene measured one. */
static double precision__slow_drift(const dm_run_result *run)
{
    double ss = 0;
    size_t m = 0;
    for (size_t i = 0; i < run->n_precision; i++)
        if (run->precision[i].between_runs && isfinite(run->precision[i].half_shift)) {
            ss += run->precision[i].half_shift * run->precision[i].half_shift;
            m++;
        }
    return m ? sqrt(ss / (double)m / 2) : NAN;
}

/* One end of a between-run CI around median m widened on a log scale by a
 * normal term of SD sd: its log distance from m and 1.96 sd in quadrature. */
static double precision__widen(double m, double end, double sd)
{
    double d = fabs(log(end / m)), w = sqrt(d * d + 1.96 * sd * 1.96 * sd);
    return end < m ? m * exp(-w) : m * exp(w);
}

/* The run's slow drift into every between-run figure of its corrected
 * scenes (run/precision.h): the CIs widened, the reference spread with it. */
static void precision__add_slow(dm_run_result *run)
{
    double sd = precision__slow_drift(run);
    if (!isfinite(sd))
        return;
    for (size_t i = 0; i < run->n_precision; i++) {
        dm_scene_precision *p = &run->precision[i];
        if (!p->between_runs)
            continue;
        p->reference_spread = hypot(p->reference_spread, sd);
        for (size_t c = 0; c < run->n_configs; c++) {
            dm_config_result *cf = &run->configs[c];
            if (!cf->scene || strcmp(cf->scene, p->scene) != 0)
                continue;
            for (size_t k = 0; k < cf->n_counters; k++) {
                dm_counter_result *w = &cf->counters[k];
                if (!w->corr_between || !(w->corr_median > 0) || !(w->corr_between_lo > 0))
                    continue;
                w->corr_between_lo = precision__widen(w->corr_median, w->corr_between_lo, sd);
                w->corr_between_hi = precision__widen(w->corr_median, w->corr_between_hi, sd);
            }
        }
    }
}

size_t precision_apply(dm_run_result *run, uint64_t seed)
{
    for (size_t i = 0; i < run->n_precision; i++) {
        free(run->precision[i].scene);
        free(run->precision[i].reason);
        free(run->precision[i].predictor);
    }
    free(run->precision);
    run->precision = NULL;
    run->n_precision = 0;
    for (size_t i = 0; i < run->n_configs; i++)   /* a merged run's shards corrected alone */
        for (size_t k = 0; k < run->configs[i].n_counters; k++) {
            dm_counter_result *c = &run->configs[i].counters[k];
            c->corrected = 0;
            c->corr_median = c->corr_ci_lo = c->corr_ci_hi = 0;
            c->corr_between = 0;
            c->corr_between_lo = c->corr_between_hi = 0;
        }
    size_t corrected = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        int seen = !precision__wall(c) || !c->scene;
        for (size_t k = 0; k < i && !seen; k++)
            seen = run->configs[k].scene && precision__wall(&run->configs[k]) &&
                   strcmp(run->configs[k].scene, c->scene) == 0;
        if (seen)
            continue;
        dm_scene_precision *p = dm_vec_push(&run->precision, &run->n_precision, NULL, sizeof *p);
        corrected += (size_t)precision__scene_apply(run, i, seed + i, p);
    }
    precision__add_slow(run);
    return corrected;
}

/* Percent of a relative figure, or "unavailable" into buf. */
static const char *precision__pct(double v, char buf[32])
{
    if (isfinite(v))
        snprintf(buf, 32, "%.2f %%", 100 * v);
    else
        snprintf(buf, 32, "unavailable");
    return buf;
}

/* One line for the user, word-wrapped to 100 columns with continuations
 * four columns in (as the runner's own lines). */
__attribute__((format(printf, 2, 3)))
static void precision__say(FILE *f, const char *fmt, ...)
{
    dm_str line = {0}, wrapped = {0};
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(&line, fmt, ap);
    va_end(ap);
    if (line.len && line.buf[line.len - 1] == '\n')
        line.buf[--line.len] = '\0';
    dm_wrap(dm_str_get(&line), "", "    ", 100, &wrapped);
    fputs(dm_str_get(&wrapped), f);
    dm_str_free(&line);
    dm_str_free(&wrapped);
}

/* The line on comparing with another run: how well each corrected scene
 * knows its median machine speed, and the configurations within target_ci
 * by the between-run CI (raw where not corrected); nothing when no scene
 * has the figure. */
static void precision__print_between(const dm_run_result *run, double target_ci, size_t n, FILE *f)
{
    double *ref = dm_xcalloc(run->n_precision + 1, sizeof *ref);
    size_t m = 0, in = 0;
    for (size_t i = 0; i < run->n_precision; i++)
        if (run->precision[i].between_runs)
            ref[m++] = run->precision[i].reference_spread;
    for (size_t i = 0; m && i < run->n_configs; i++) {
        const dm_counter_result *w = precision__wall(&run->configs[i]);
        if (w)
            in += w->corr_between ? (w->corr_between_hi - w->corr_between_lo) / 2 <= target_ci * w->corr_median
                                  : (w->ci_hi - w->ci_lo) / 2 <= target_ci * w->median;
    }
    char b[32];
    if (m)
        precision__say(f, "dmbench: between runs: each corrected scene's median machine speed is known to "
                "±%s (median over scenes, robust SD); with it, %zu of %zu within ±%g %% for comparing with "
                "another run (results.json: corrected.ci95_between_runs)\n",
                precision__pct(precision__median(ref, m), b), in, n, 100 * target_ci);
    free(ref);
}

void precision_print(const dm_run_result *run, double target_ci, FILE *f)
{
    size_t n = 0, raw_in = 0, corr_in = 0, n_corr_scenes = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_counter_result *w = precision__wall(&run->configs[i]);
        if (!w)
            continue;
        n++;
        raw_in += (w->ci_hi - w->ci_lo) / 2 <= target_ci * w->median;
        corr_in += w->corrected ? (w->corr_ci_hi - w->corr_ci_lo) / 2 <= target_ci * w->corr_median
                                : (w->ci_hi - w->ci_lo) / 2 <= target_ci * w->median;
    }
    if (!n)
        return;
    double *v[4];
    for (int k = 0; k < 4; k++)
        v[k] = dm_xcalloc(run->n_precision + 1, sizeof **v);
    int any_calib = 0;
    for (size_t i = 0; i < run->n_precision; i++) {
        const dm_scene_precision *p = &run->precision[i];
        n_corr_scenes += (size_t)p->corrected;
        v[0][i] = p->machine_spread;
        v[1][i] = p->raw_noise;
        v[2][i] = p->loo_noise;
        v[3][i] = p->calib_noise;
        any_calib |= isfinite(p->calib_noise);
    }
    double floor, resolvable;
    dm_run_noise_floor(run, &floor, &resolvable);
    char b[5][32];
    precision__say(f, "dmbench: precision (WallTime, 95 %% CI within ±%g %%): %zu of %zu raw, %zu of %zu with "
            "the machine's drift removed (%zu of %zu scenes corrected)\n", 100 * target_ci, raw_in, n,
            corr_in, n, n_corr_scenes, run->n_precision);
    precision__say(f, "dmbench: noise floor ±%s (median CI half-width); the smallest difference this run "
            "resolves: %s\n", precision__pct(floor, b[0]), precision__pct(resolvable, b[1]));
    precision__say(f, "dmbench: the machine's speed moved ±%s between rounds; the samples' spread: %s raw, "
            "%s after the rounds' common mode, %s after the calibration workload%s (medians over scenes)\n",
            precision__pct(precision__median(v[0], run->n_precision), b[2]),
            precision__pct(precision__median(v[1], run->n_precision), b[3]),
            precision__pct(precision__median(v[2], run->n_precision), b[4]),
            any_calib ? precision__pct(precision__median(v[3], run->n_precision), b[0]) : "unavailable",
            any_calib ? "" : " (not timed in the rounds)");
    precision__print_between(run, target_ci, n, f);
    for (size_t i = 0; i < run->n_precision; i++)
        if (run->precision[i].reason)
            precision__say(f, "dmbench: scene %s: %s\n", run->precision[i].scene, run->precision[i].reason);
    for (int k = 0; k < 4; k++)
        free(v[k]);
}
