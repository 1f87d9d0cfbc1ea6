/* compare.c — the regression gate's engine: matching, checks, verdicts
 * (see compare.h for the rules). */
#include "gate/compare.h"
#include "gate/compare_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_exit.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "run/env.h"
#include "models/compare_stats.h"
#include "models/stats.h"
#include "reports/report.h"

static const char *const compare__verdict_names[] = { "PASS", "SKIPPED", "IMPROVEMENT",
                                                      "INCONCLUSIVE", "REGRESSION" };

const char *compare_verdict_name(compare_verdict v)
{
    return (unsigned)v <= COMPARE_REGRESSION ? compare__verdict_names[v] : "?";
}

compare_desc compare_defaults(const compare_desc *d)
{
    compare_desc o = *d;
    o.time_threshold = o.time_threshold > 0 ? o.time_threshold : 0.05;
    o.threshold = o.threshold > 0 ? o.threshold : 0.005;
    o.alpha = o.alpha > 0 ? o.alpha : 0.01;
    o.level = o.level > 0 ? o.level : 0.95;
    o.psnr_drop = o.psnr_drop > 0 ? o.psnr_drop : 1.0;
    o.ssim_drop = o.ssim_drop > 0 ? o.ssim_drop : 0.01;
    o.flip_rise = o.flip_rise > 0 ? o.flip_rise : 0.005;
    o.time_counter = o.time_counter ? o.time_counter : "WallTime";
    o.run_spread = o.run_spread > 0 ? o.run_spread : COMPARE_RUN_SPREAD;
    return o;
}

static void compare__push(char ***list, size_t *n, char *text)
{
    DM_VEC_PUSH(*list, *n, text);
}

/* "k=v k=v" of the params that tell c apart within run r (all of them when
 * none do; its key when it has none). */
/* The configuration's one label (report_config_label: "cube 480×270 ·
 * pom steps=8"), the same as in the report; its key when it has none. */
static char *compare__label(const dm_config_result *c, const dm_run_result *r)
{
    dm_str s = {0};
    report_config_label(r, c, &s);
    if (!s.len)
        dm_str_cat(&s, c->key);
    return dm_str_take(&s);
}

static int compare__same_params(const dm_config_result *a, const dm_config_result *b)
{
    if (a->n_params != b->n_params)
        return 0;
    for (size_t i = 0; i < a->n_params; i++) {
        const char *v = dm_kv_get(b->params, b->n_params, a->params[i].key);
        if (!v || strcmp(v, a->params[i].value ? a->params[i].value : "") != 0)
            return 0;
    }
    return 1;
}

/* c of a user technique (not a built-in one, compare_desc.builtin_technique)? */
static int compare__user(const compare_desc *d, const dm_config_result *c)
{
    const char *t = dm_kv_get(c->params, c->n_params, "technique");
    return d->builtin_technique && t && !d->builtin_technique(t);
}

/* c's configuration in `other`: the one of the same key, or for a user
 * technique whose file changed, the one of identical parameters that has no
 * key in c's run (compare_desc.builtin_technique). */
static const dm_config_result *compare__counterpart(const compare_desc *d, const dm_config_result *c,
                                                    const dm_run_result *own, const dm_run_result *other)
{
    const dm_config_result *n = dm_run_config(other, c->key);
    for (size_t i = 0; !n && compare__user(d, c) && i < other->n_configs; i++)
        if (!dm_run_config(own, other->configs[i].key) && compare__same_params(c, &other->configs[i]))
            n = &other->configs[i];
    return n;
}

/* Lists fingerprint differences; returns their number. */
static size_t compare__env(const dm_run_result *a, const dm_run_result *b, int driver_only,
                           compare_result *out)
{
    static const char *const driver_keys[] = { "renderer", "gl_version", NULL };
    const char *const *keys = driver_only ? driver_keys : env_fingerprint_keys();
    for (; *keys; keys++) {
        const char *va = dm_kv_get(a->environment, a->n_environment, *keys);
        const char *vb = dm_kv_get(b->environment, b->n_environment, *keys);
        if ((va || vb) && (!va || !vb || strcmp(va, vb) != 0))
            compare__push(&out->env_diffs, &out->n_env_diffs,
                          dm_xasprintf("%s: '%s' (BASE) vs '%s' (NEW)", *keys, va ? va : "(absent)",
                                       vb ? vb : "(absent)"));
    }
    return out->n_env_diffs;
}

static double compare__tolerance(const compare_desc *d, const char *counter)
{
    for (size_t i = 0; i < d->n_tolerances; i++)
        if (strcmp(d->tolerances[i].counter, counter) == 0)
            return d->tolerances[i].rel;
    return 0.0;
}

static void compare__change(compare_item *it, const char *counter, double b, double n, const char *note)
{
    compare_change *c = dm_vec_push(&it->changes, &it->n_changes, NULL, sizeof *c);
    c->counter = dm_xstrdup(counter);
    c->base = b;
    c->new_ = n;
    c->note = dm_xstrdup(note);
}

/* Counters of the Cost group (counted under Valgrind: Instructions, the
 * stage counters and what is derived from them): Instructions and
 * InstructionsPerPixel gate by the threshold, the stage counters explain
 * its verdict (compare__stages), none by exact equality. */
static int compare__is_cost(const char *name)
{
    const counters_info *info = counters_find(name);
    return info && info->group && strcmp(info->group, "Cost") == 0;
}

/* Where the instructions changed: each stage's count base -> new and its
 * ratio, and the stage whose count changed most, when both runs have the
 * stage counters (docs/counters.md, "Stage costs"); otherwise how to get
 * them.  Appended to note. */
static void compare__stages(const dm_config_result *b, const dm_config_result *n, dm_str *note)
{
    static const char *const counter[] = {"GeometryInstructions", "RasterInstructions", "FragmentInstructions"};
    static const char *const stage[] = {"geometry", "raster", "fragment"};
    double vb[3], vn[3];
    for (int i = 0; i < 3; i++) {
        const dm_counter_result *cb = dm_config_counter(b, counter[i]), *cn = dm_config_counter(n, counter[i]);
        if (!cb || !cn || !cb->available || !cn->available) {
            dm_str_printf(note, "; which stage changed is unknown: %s not counted in both runs (add "
                          "GeometryInstructions, RasterInstructions, FragmentInstructions to "
                          "measure.counters)", counter[i]);
            return;
        }
        vb[i] = cb->value;
        vn[i] = cn->value;
    }
    int most = 0;
    dm_str_printf(note, "; by stage:");
    for (int i = 0; i < 3; i++) {
        if (fabs(vn[i] - vb[i]) > fabs(vn[most] - vb[most]))
            most = i;
        if (vb[i] > 0)
            dm_str_printf(note, " %s x%.4f (%+.0f)", stage[i], vn[i] / vb[i], vn[i] - vb[i]);
        else
            dm_str_printf(note, " %s %.0f -> %.0f", stage[i], vb[i], vn[i]);
    }
    dm_str_printf(note, "; %s %s most", stage[most], vn[most] >= vb[most] ? "grew" : "shrank");
}

/* Instructions on both sides decide the verdict by the threshold (exact
 * counts need no statistics).  Returns 1 when decided. */
static int compare__instructions(const compare_desc *d, const dm_config_result *b,
                                 const dm_config_result *n, compare_item *it)
{
    const dm_counter_result *cb = dm_config_counter(b, "Instructions");
    const dm_counter_result *cn = dm_config_counter(n, "Instructions");
    if (d->instr_off || !cb || !cn || !cb->available || !cn->available || !(cb->value > 0))
        return 0;
    it->instr = 1;
    it->instr_base = cb->value;
    it->instr_new = cn->value;
    double r = cn->value / cb->value, t = d->threshold;
    const dm_counter_result *pb = dm_config_counter(b, "InstructionsPerPixel");
    const dm_counter_result *pn = dm_config_counter(n, "InstructionsPerPixel");
    if (pb && pn && pb->available && pn->available && pb->value > 0 &&
        fabs(pn->value / pb->value - 1) > fabs(r - 1))
        r = pn->value / pb->value;    /* the larger relative change of the two */
    it->verdict = r > 1 + t ? COMPARE_REGRESSION : r < 1 - t ? COMPARE_IMPROVEMENT : COMPARE_PASS;
    dm_str note = {0};
    dm_str_printf(&note, "Instructions %+.3f%% (%.0f -> %.0f per frame; threshold %.2g%%)", (r - 1) * 100,
                  cb->value, cn->value, t * 100);
    if (it->verdict != COMPARE_PASS)
        compare__stages(b, n, &note);
    it->note = dm_str_take(&note);
    return 1;
}

/* The relative tolerance a deterministic counter always has: 0 for a count
 * (an integer, equal or changed), COMPARE_DERIVED_EPS for a floating value
 * (a derived ratio such as ShadingEfficiency = SamplesPassed /
 * FSInvocations), whose last bit depends on the order of the arithmetic
 * and on how it was written; its integer parts are compared exactly
 * beside it, so a real change is never hidden.  A counter the registry does
 * not know is compared exactly. */
static double compare__float_eps(const char *counter)
{
    const counters_info *info = counters_find(counter);
    return info && info->type == COUNTERS_TYPE_FLOAT64 ? COMPARE_DERIVED_EPS : 0.0;
}

/* Deterministic counters of BASE against NEW: a value outside the tolerance,
 * or a counter available on one side only, is a change. */
static void compare__deterministic(const compare_desc *d, const dm_config_result *b,
                                   const dm_config_result *n, compare_item *it)
{
    for (size_t i = 0; i < b->n_counters; i++) {
        const dm_counter_result *cb = &b->counters[i];
        const dm_counter_result *cn = dm_config_counter(n, cb->name);
        if (!cb->deterministic || !cn)
            continue;
        if (cb->unreadable || cn->unreadable) {
            char *note = dm_xasprintf("unavailable on %s: %s", cb->unreadable ? "BASE" : "NEW",
                                      (cb->unreadable ? cb : cn)->unavailable_reason);
            compare__change(it, cb->name, cb->value, cn->value, note);
            free(note);
            continue;
        }
        if (compare__is_cost(cb->name) && ((cb->available && cn->available) || d->instr_off))
            continue;          /* exact counts with a threshold: compare__instructions */
        if (cb->available != cn->available) {
            compare__change(it, cb->name, cb->value, cn->value,
                            cb->available ? "unavailable on NEW" : "unavailable on BASE");
            continue;
        }
        double tol = fmax(compare__tolerance(d, cb->name), compare__float_eps(cb->name));
        if (cb->available && !(fabs(cn->value - cb->value) <= tol * fabs(cb->value)))
            compare__change(it, cb->name, cb->value, cn->value, NULL);
    }
}

/* Quality drop over the limits; returns a note or NULL. */
static char *compare__quality(const compare_desc *d, const dm_config_result *b,
                              const dm_config_result *n, compare_item *it)
{
    if (!b->quality.present || !n->quality.present)
        return NULL;
    it->quality = 1;
    it->psnr_base = b->quality.psnr;
    it->psnr_new = n->quality.psnr;
    it->ssim_base = b->quality.ssim;
    it->ssim_new = n->quality.ssim;
    it->flip_base = b->quality.flip;
    it->flip_new = n->quality.flip;
    /* inf - inf is NaN (no drop); inf - finite is an infinite drop */
    double dp = it->psnr_base == it->psnr_new ? 0.0 : it->psnr_base - it->psnr_new;
    if (dp > d->psnr_drop)
        return dm_xasprintf("PSNR dropped %.2f dB (%.2f -> %.2f; limit %.2f dB)", dp, it->psnr_base,
                            it->psnr_new, d->psnr_drop);
    double ds = it->ssim_base - it->ssim_new;
    if (ds > d->ssim_drop)
        return dm_xasprintf("SSIM dropped %.4f (%.4f -> %.4f; limit %.4f)", ds, it->ssim_base,
                            it->ssim_new, d->ssim_drop);
    double df = it->flip_new - it->flip_base;    /* NaN (a side without FLIP): no check */
    if (df > d->flip_rise)
        return dm_xasprintf("FLIP rose %.4f (%.4f -> %.4f; limit %.4f)", df, it->flip_base,
                            it->flip_new, d->flip_rise);
    return NULL;
}

static char *compare__changes_note(const compare_item *it)
{
    dm_str s = {0};
    for (size_t i = 0; i < it->n_changes; i++) {
        const compare_change *c = &it->changes[i];
        if (c->note)
            dm_str_printf(&s, "%s%s %s", i ? "; " : "", c->counter, c->note);
        else
            dm_str_printf(&s, "%s%s changed %.17g -> %.17g", i ? "; " : "", c->counter, c->base,
                          c->new_);
    }
    return dm_str_take(&s);
}

/* Runs the non-timing checks of one matched pair; returns 1 when decided. */
static int compare__checks(const compare_desc *d, const dm_config_result *b,
                           const dm_config_result *n, compare_item *it)
{
    if (!b->ok && !n->ok) {
        it->verdict = COMPARE_SKIPPED;
        it->note = dm_xasprintf("failed on both sides (NEW: %s)", n->reason ? n->reason : "?");
        return 1;
    }
    if (!n->ok) {
        it->verdict = COMPARE_REGRESSION;
        it->note = dm_xasprintf("failed on NEW: %s", n->reason ? n->reason : "no reason");
        return 1;
    }
    if (!b->ok) {
        it->note = dm_xasprintf("failed on BASE, ok on NEW: not compared");
        return 1;
    }
    compare__deterministic(d, b, n, it);
    if (it->n_changes) {
        it->verdict = COMPARE_REGRESSION;
        it->note = compare__changes_note(it);
        return 1;
    }
    if (!d->counters_only && (it->note = compare__quality(d, b, n, it))) {
        it->verdict = COMPARE_REGRESSION;
        return 1;
    }
    return compare__instructions(d, b, n, it) || d->counters_only;
}

/* Bootstrap CI and Mann-Whitney p of the time counter, on the samples
 * blocked by round where a side has them (bb, bn: NULL for raw), and the
 * CI of the raw samples beside it; 0 when timed. */
static int compare__time_stats(const compare_desc *d, const dm_config_result *b,
                               const dm_config_result *n, const double *bb, const double *bn,
                               compare_item *it)
{
    const dm_counter_result *tb = dm_config_counter(b, d->time_counter);
    const dm_counter_result *tn = dm_config_counter(n, d->time_counter);
    if (!tb || !tn || !tb->available || !tn->available || !tb->n_samples || !tn->n_samples) {
        it->verdict = COMPARE_INCONCLUSIVE;
        it->extra_samples = -1;
        it->detectable = NAN;
        it->note = dm_xasprintf("no %s samples on %s: no change could be detected", d->time_counter,
                                !tb || !tb->available || !tb->n_samples ? "BASE" : "NEW");
        return -1;
    }
    compare_ratio cr;
    uint64_t seed = dm_fnv1a64(it->key, strlen(it->key), d->seed ^ DM_FNV_SEED);
    if (compare_stats_ratio_ci(tb->samples, tb->n_samples, tn->samples, tn->n_samples, d->level,
                               seed, &cr) != 0) {
        it->verdict = COMPARE_INCONCLUSIVE;
        it->extra_samples = -1;
        it->note = dm_xasprintf("%s: no finite samples or a zero median", d->time_counter);
        return -1;
    }
    it->timed = 1;
    it->ratio = cr.ratio;
    it->lo = it->lo_raw = cr.lo;
    it->hi = it->hi_raw = cr.hi;
    it->n_base = tb->n_samples;
    it->n_new = tn->n_samples;
    const double *xb = bb ? bb : tb->samples, *xn = bn ? bn : tn->samples;
    it->blocked = (bb || bn) && compare_stats_ratio_ci(xb, tb->n_samples, xn, tn->n_samples,
                                                       d->level, seed, &cr) == 0;
    if (it->blocked) {   /* the ratio of medians stays the raw one; the CI is the blocked one's */
        it->lo = cr.lo * it->ratio / cr.ratio;
        it->hi = cr.hi * it->ratio / cr.ratio;
    }
    it->p = compare_stats_mann_whitney(xn, tn->n_samples, xb, tb->n_samples, NULL);
    if (d->paired || d->replicated) {   /* pooled run minima: show what the ratio is of */
        it->median_base = stats_median(tb->samples, tb->n_samples);
        it->median_new = stats_median(tn->samples, tn->n_samples);
    }
    it->detectable = cr.ratio > 0 ? (cr.hi - cr.lo) / 2 / cr.ratio : NAN;
    return 0;
}

/* (distance of a CI bound from the ratio / distance of the threshold it
 * must clear from the ratio)^2: how much that side of the CI must shrink. */
static double compare__shrink(double r, double bound, double thr)
{
    double d = fabs(r - thr);
    return d > 1e-9 ? ((r - bound) / d) * ((r - bound) / d) : INFINITY;
}

/* Extra samples per side likely needed for the CI to clear the threshold(s)
 * it straddles, each side of the (possibly skewed) CI scaled on its own;
 * -1 when the ratio sits on a threshold. */
static long compare__extra_samples(double t, const compare_item *it)
{
    double r = it->ratio, f = 0;
    if (r > 1.0 + t)
        f = compare__shrink(r, it->lo, 1.0 + t);
    else if (r < 1.0 - t)
        f = compare__shrink(r, it->hi, 1.0 - t);
    else {
        if (it->lo < 1.0 - t)
            f = compare__shrink(r, it->lo, 1.0 - t);
        if (it->hi > 1.0 + t)
            f = fmax(f, compare__shrink(r, it->hi, 1.0 + t));
    }
    double n = (double)(it->n_base < it->n_new ? it->n_base : it->n_new);
    /* and at least enough for the detectable change to reach t */
    f = fmax(f, it->detectable > t ? (it->detectable / t) * (it->detectable / t) : 0);
    double need = ceil(n * f - n);
    return !isfinite(need) || need > 1e9 ? -1 : need < 1 ? 1 : (long)need;
}

/* An item whose CI cleared the threshold but not the machine interval:
 * INCONCLUSIVE, naming the machine's change and the remedy. */
static void compare__machine_held(const compare_desc *d, const compare_machine *m,
                                  compare_item *it)
{
    it->verdict = COMPARE_INCONCLUSIVE;
    it->machine_held = 1;
    it->extra_samples = -1;
    const char *why = m->contention && m->load_changed ? "contention, load changed"
                      : m->contention ? "contention" : m->load_changed ? "load changed"
                      : "between-run spread";
    it->note = dm_xasprintf("%s %.1f%% %s (CI %.3f..%.3f), within what the machine alone may "
                            "do between two runs (x%.3f..x%.3f: %s): use compare --paired (both "
                            "builds in alternating rounds)", d->time_counter,
                            fabs(it->ratio - 1) * 100, it->ratio > 1 ? "slower" : "faster",
                            it->lo, it->hi, m->lo, m->hi, why);
}

/* The three-way time verdict of a timed item, with q already set; the CI
 * must clear the threshold also after dividing by the machine interval. */
static void compare__time_verdict(const compare_desc *d, const compare_machine *m, compare_item *it)
{
    double t = d->time_threshold;
    int sig = it->q < d->alpha;
    if ((it->lo > 1.0 + t && it->lo / m->hi <= 1.0 + t && sig) ||
        (it->hi < 1.0 - t && it->hi / m->lo >= 1.0 - t && sig)) {
        compare__machine_held(d, m, it);
    } else if (it->lo > 1.0 + t && sig) {
        it->verdict = COMPARE_REGRESSION;
        it->note = dm_xasprintf("%s %.1f%% slower (CI %.3f..%.3f, q=%.2g)", d->time_counter,
                                (it->ratio - 1) * 100, it->lo, it->hi, it->q);
    } else if (it->hi < 1.0 - t && sig) {
        it->verdict = COMPARE_IMPROVEMENT;
        it->note = dm_xasprintf("%s %.1f%% faster", d->time_counter, (1 - it->ratio) * 100);
    } else if (it->lo >= 1.0 - t && it->hi <= 1.0 + t) {
        it->verdict = COMPARE_PASS;
    } else {
        it->verdict = COMPARE_INCONCLUSIVE;
        const char *unit = d->paired ? "rounds" : d->replicated ? "runs per side"
                                                    : "samples per side";
        char *head = dm_xasprintf("could detect changes >= %.1f%% (threshold %.1f%%)",
                                  it->detectable * 100, t * 100);
        if (it->lo > 1.0 + t || it->hi < 1.0 - t) {
            /* outside the band but q >= alpha: significance needs more data */
            double n = (double)(it->n_base < it->n_new ? it->n_base : it->n_new);
            it->extra_samples = (long)(n > 0 ? n : 1);
            it->note = dm_xasprintf("%s; CI outside the tolerance but not significant (q=%.2g >= "
                                    "%.2g): about %ld more %s", head, it->q, d->alpha,
                                    it->extra_samples, unit);
        } else {
            it->extra_samples = compare__extra_samples(t, it);
            it->note = it->extra_samples > COMPARE_ADVICE_MAX
                           ? dm_xasprintf("%s; CI %.3f..%.3f: more than %d %s: the difference is below "
                                          "what this machine can resolve", head, it->lo, it->hi,
                                          COMPARE_ADVICE_MAX, unit)
                       : it->extra_samples < 0
                           ? dm_xasprintf("%s; CI %.3f..%.3f straddles %.3f; more %s will not "
                                          "decide it", head, it->lo, it->hi,
                                          it->ratio > 1 ? 1 + t : 1 - t, unit)
                           : dm_xasprintf("%s; CI %.3f..%.3f: about %ld more %s", head,
                                          it->lo, it->hi, it->extra_samples, unit);
        }
        free(head);
    }
}

/* BH over the timed items, their verdicts, and the suite geometric mean. */
static void compare__timing(const compare_desc *d, compare_result *out, const int *pending)
{
    double *p = dm_xcalloc(out->n_items + 1, sizeof *p);
    size_t m = 0;
    for (size_t i = 0; i < out->n_items; i++)
        if (pending[i])
            p[m++] = isnan(out->items[i].p) ? 1.0 : out->items[i].p;
    compare_stats_bh(p, m, p);
    double logsum = 0;
    for (size_t i = 0, k = 0; i < out->n_items; i++) {
        if (!pending[i])
            continue;
        compare_item *it = &out->items[i];
        it->q = p[k++];
        compare__time_verdict(d, &out->machine, it);
        logsum += log(it->ratio);
        out->n_geomean++;
    }
    out->geomean = out->n_geomean ? exp(logsum / (double)out->n_geomean) : NAN;
    free(p);
}

static int compare__item_cmp(const void *a, const void *b)
{
    const compare_item *x = a, *y = b;
    if (x->verdict != y->verdict)
        return x->verdict > y->verdict ? -1 : 1;
    double rx = x->timed ? x->ratio : 0, ry = y->timed ? y->ratio : 0;
    if (rx != ry)
        return rx > ry ? -1 : 1;
    return strcmp(x->label, y->label);
}

/* The machine a configuration was measured on: its "machine" parameter in
 * a run merged from several machines (store/merge.h), else the run's
 * environment fingerprint. */
static const char *compare__machine(const dm_run_result *r, const dm_config_result *c)
{
    const char *m = dm_kv_get(c->params, c->n_params, "machine");
    return m ? m : dm_kv_get(r->environment, r->n_environment, "fingerprint");
}

/* 1 when any configuration of r carries a machine (a multi-machine merge). */
static int compare__multi_machine(const dm_run_result *r)
{
    for (size_t i = 0; i < r->n_configs; i++)
        if (dm_kv_get(r->configs[i].params, r->configs[i].n_params, "machine"))
            return 1;
    return 0;
}

/* Times of one configuration measured on two machines are never compared
 * (unless allow_env_mismatch; deterministic counters, counters_only, do not
 * depend on the machine): the item is inconclusive and says why.
 * Returns 1 when it was decided here. */
static int compare__other_machine(const compare_desc *d, const dm_run_result *base,
                                  const dm_config_result *b, const dm_run_result *new_,
                                  const dm_config_result *n, compare_item *it)
{
    const char *mb = compare__machine(base, b), *mn = compare__machine(new_, n);
    if (d->allow_env_mismatch || d->counters_only || (!mb && !mn) || (mb && mn && strcmp(mb, mn) == 0))
        return 0;
    it->verdict = COMPARE_INCONCLUSIVE;
    it->note = dm_xasprintf("measured on machine %s in BASE and %s in NEW: not compared "
                            "(timings of different machines are never pooled; "
                            "--allow-env-mismatch compares anyway)", mb ? mb : "?", mn ? mn : "?");
    return 1;
}

/* Matches configurations by key, lists added and removed ones; the time
 * statistics use the blocked samples blk_b / blk_n (compare__block). */
static int *compare__match(const compare_desc *d, const dm_run_result *base,
                           const dm_run_result *new_, double *const *blk_b,
                           double *const *blk_n, compare_result *out)
{
    out->items = dm_xcalloc(base->n_configs + 1, sizeof *out->items);
    int *pending = dm_xcalloc(base->n_configs + 1, sizeof *pending);
    for (size_t i = 0; i < base->n_configs; i++) {
        const dm_config_result *b = &base->configs[i], *n = compare__counterpart(d, b, base, new_);
        char *label = compare__label(b, base);
        if (n && strcmp(n->key, b->key) != 0) {   /* a user's edited GLSL file */
            char *was = label;
            label = dm_xasprintf("%s (technique source changed: key %s -> %s)", was, b->key, n->key);
            free(was);
        }
        if (!n) {
            compare__push(&out->removed, &out->n_removed, dm_xasprintf("%s [%s]", label, b->key));
            free(label);
            continue;
        }
        compare_item *it = &out->items[out->n_items];
        it->key = dm_xstrdup(b->key);
        it->label = label;
        dm_str name = {0};
        report_config_name(base, b, &name);
        it->name = dm_str_take(&name);
        it->p = it->q = NAN;
        const dm_counter_result *tb = dm_config_counter(b, d->time_counter);
        if (tb && tb->available && tb->has_samples && isfinite(tb->median))
            it->median_base = tb->median;
        const dm_counter_result *tn = dm_config_counter(n, d->time_counter);
        if (tn && tn->available && tn->has_samples && isfinite(tn->median))
            it->median_new = tn->median;   /* the JUnit time of every verdict */
        if (!compare__other_machine(d, base, b, new_, n, it) && !compare__checks(d, b, n, it))
            pending[out->n_items] =
                compare__time_stats(d, b, n, blk_b[i], blk_n[(size_t)(n - new_->configs)], it) == 0;
        out->n_items++;
    }
    for (size_t i = 0; i < new_->n_configs; i++)
        if (!compare__counterpart(d, &new_->configs[i], new_, base)) {
            char *label = compare__label(&new_->configs[i], new_);
            compare__push(&out->added, &out->n_added,
                          dm_xasprintf("%s [%s]", label, new_->configs[i].key));
            free(label);
        }
    return pending;
}

/* GPUTime marked partial in either run may not gate (docs/counters.md). */
static int compare__time_counter_ok(const compare_desc *d, const dm_run_result *r)
{
    for (size_t i = 0; i < r->n_configs; i++) {
        const dm_counter_result *c = dm_config_counter(&r->configs[i], d->time_counter);
        if (c && c->partial)
            return 0;
    }
    return 1;
}

static int compare__has_instructions(const dm_run_result *r)
{
    for (size_t i = 0; i < r->n_configs; i++)
        if (dm_config_counter(&r->configs[i], "Instructions"))
            return 1;
    return 0;
}

int compare_runs(const dm_run_result *base, const dm_run_result *new_, const compare_desc *d,
                 compare_result *out, dm_str *err)
{
    memset(out, 0, sizeof *out);
    out->desc = compare_defaults(d);
    out->geomean = NAN;
    out->base_id = dm_xstrdup(base->id);
    out->new_id = dm_xstrdup(new_->id);
    out->sweep = dm_xstrdup(new_->sweep);
    const compare_desc *o = &out->desc;
    /* A run merged from several machines is checked per configuration
     * (compare__other_machine); its run-level environment is one shard's. */
    int per_config = compare__multi_machine(base) || compare__multi_machine(new_);
    if ((!per_config || o->counters_only) && compare__env(base, new_, o->counters_only, out)) {
        if (!o->allow_env_mismatch) {
            dm_str_printf(err, "environment fingerprints differ (%zu key%s); pass "
                          "--allow-env-mismatch to compare anyway", out->n_env_diffs,
                          out->n_env_diffs == 1 ? "" : "s");
            return DM_ERR_ARG;
        }
        compare__push(&out->warnings, &out->n_warnings,
                      dm_xasprintf("environment fingerprints differ (%zu key%s); compared anyway "
                                   "because of --allow-env-mismatch", out->n_env_diffs,
                                   out->n_env_diffs == 1 ? "" : "s"));
    }
    if (!o->counters_only && (!compare__time_counter_ok(o, base) || !compare__time_counter_ok(o, new_))) {
        dm_str_printf(err, "%s is marked partial on this driver (the timer covers a fraction of "
                      "the work); it is never used to gate — use WallTime", o->time_counter);
        return DM_ERR_ARG;
    }
    const char *cpu_b = dm_kv_get(base->environment, base->n_environment, "cpu");
    const char *cpu_n = dm_kv_get(new_->environment, new_->n_environment, "cpu");
    if (cpu_b && cpu_n && strcmp(cpu_b, cpu_n) != 0 && compare__has_instructions(base)) {
        out->desc.instr_off = 1;
        compare__push(&out->warnings, &out->n_warnings,
                      dm_xasprintf("Instructions not compared: BASE was counted on '%s', NEW on '%s' "
                                   "(instruction counts depend on the CPU's instruction set)",
                                   cpu_b, cpu_n));
    }
    double **blk_b = compare__block(base, o->time_counter, o->no_blocking, &out->machine.base);
    double **blk_n = compare__block(new_, o->time_counter, o->no_blocking, &out->machine.new_);
    int *pending = compare__match(o, base, new_, blk_b, blk_n, out);
    compare__machine_checks(o, base, new_, pending, out);
    compare__timing(o, out, pending);
    free(pending);
    compare__blocked_free(blk_b, base->n_configs);
    compare__blocked_free(blk_n, new_->n_configs);
    qsort(out->items, out->n_items, sizeof *out->items, compare__item_cmp);
    for (size_t i = 0; i < out->n_items; i++)
        out->count[out->items[i].verdict]++;
    return 0;
}

int compare_check_alpha(double alpha, dm_str *err)
{
    if (alpha > 0 && alpha < 1)
        return 0;
    dm_str_printf(err, "--alpha %g: expected a significance level between 0 and 1 (exclusive), "
                  "e.g. 0.05", alpha);
    return DM_ERR_RANGE;
}

int compare_check_tolerance_counter(const char *counter, dm_str *err)
{
    if (counters_find(counter))
        return 0;
    const char **names = dm_xcalloc(counters_count() + 1, sizeof *names);
    for (size_t i = 0; i < counters_count(); i++)
        names[i] = counters_info_at(i)->name;
    const char *near = dm_closest(counter, names, counters_count());
    dm_str_printf(err, "--tolerance: unknown counter '%s'", counter);
    if (near)
        dm_str_printf(err, "; did you mean '%s'?", near);
    dm_str_cat(err, " (dmbench list counters shows them all)");
    free(names);
    return DM_ERR_UNKNOWN;
}

int compare_check_common(const compare_result *r, dm_str *err)
{
    if (r->n_items > 0)
        return 0;
    dm_str_printf(err, "the runs have no configuration in common (%zu only in the base, %zu only "
                  "in the new run): nothing was compared; were they made from the same sweep?",
                  r->n_removed, r->n_added);
    return DM_ERR_ARG;
}

int compare_exit_code(const compare_result *r)
{
    if (r->count[COMPARE_REGRESSION])
        return DM_EXIT_FAILED;
    return r->count[COMPARE_INCONCLUSIVE] ? DM_EXIT_INCONCLUSIVE : DM_EXIT_OK;
}

static void compare__free_list(char **list, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(list[i]);
    free(list);
}

void compare_result_free(compare_result *r)
{
    for (size_t i = 0; i < r->n_items; i++) {
        compare_item *it = &r->items[i];
        for (size_t k = 0; k < it->n_changes; k++) {
            free(it->changes[k].counter);
            free(it->changes[k].note);
        }
        free(it->changes);
        free(it->key);
        free(it->label);
        free(it->name);
        free(it->note);
    }
    free(r->items);
    compare__free_list(r->added, r->n_added);
    compare__free_list(r->removed, r->n_removed);
    compare__free_list(r->env_diffs, r->n_env_diffs);
    compare__free_list(r->warnings, r->n_warnings);
    free(r->machine.reason);
    free(r->base_id);
    free(r->new_id);
    free(r->sweep);
    memset(r, 0, sizeof *r);
}
