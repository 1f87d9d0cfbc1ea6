/* measure.c — the timed scene: the measurement protocol for one scene's
 * configurations, their counters and their commit (see measure.h). */
#include "measure.h"
#include "core/dm_error.h"
#include "run/calibrate.h"
#include "run/callgrind.h"
#include "run/inputs.h"
#include "run/mquality.h"
#include "run/path_timing.h"
#include "run/predict.h"
#include "models/stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Warm-up of a prepared configuration, as the protocol asks (run/protocol.h):
 * the first frame alone, the rest of warmup_frames, then samples until two
 * consecutive ones agree; sets c->frames (frames per timing sample) and
 * c->warmup_ns.  llvmpipe JIT-compiles a program's variant at its first
 * draw, also when the program came from the binary cache: on a warm second
 * run of the default sweep the first frame took a median 2.5 ms (up to
 * 23 ms) more than the steady frame, and the frames after it were steady. */
static void measure__warmup(mscene *m, mconf *c)
{
    int64_t t0 = dm_now_ns();
    protocol_warmup w;
    dm_str seq = {0};
    for (int f = protocol_warmup_begin(&m->pd, &w); f > 0;) {
        int agreeing = w.stage == PROTOCOL_WARMUP_AGREE_STAGE;
        double ns = mscene_plain_sample(m, c, f);
        if (agreeing)
            dm_str_printf(&seq, "%s%.2f", seq.len ? " " : "", ns / 1e6);
        f = protocol_warmup_next(&m->pd, &w, ns);
    }
    dm_log(DM_LOG_DEBUG, "warm-up %s: program %s, first frame %.2f ms, then %.2f ms/frame; "
           "samples of %d frames: %s ms/frame", c->pc->key,
           c->info.program_cached == 2 ? "from the binary cache" : c->info.program_cached ? "in memory" : "compiled",
           w.first_ns / 1e6, w.rest_ns / 1e6, w.sample_frames, dm_str_get(&seq));
    dm_str_free(&seq);
    c->frames = protocol_sample_frames(&m->pd, w.settled_ns);
    c->warmup_ns = dm_now_ns() - t0;
}

/* Continues from the samples a killed process checkpointed for this
 * configuration (same counters, same count for each); at most
 * samples_max - 1 are taken, so at least one more is measured here.  A
 * path configuration is measured from scratch: its frame times are not
 * checkpointed, and its replays must be its samples. */
static void measure__restore(mscene *m, mconf *c)
{
    size_t cap = protocol_resume_limit(&m->pd), got = 0;
    long ns = 0;
    if (c->path_frames)
        return;
    for (size_t i = 0; i < m->n_timing; i++) {
        double *v = NULL;
        size_t n = 0;
        if (store_partial_get(m->st, m->job->run_id, c->pc->key, m->timing[i], &v, &n, &ns) != 0 ||
            (i > 0 && n != got)) {
            free(v);
            return;   /* partial or none: measure from scratch */
        }
        got = n;
        memcpy(c->timing[i], v, (n < cap ? n : cap) * sizeof *v);
        free(v);
    }
    c->n_samples = got < cap ? got : cap;
    c->sampling_ns = ns;
    if (c->n_samples)
        dm_str_printf(&c->log, "continued from %zu timing samples checkpointed by an "
                      "interrupted process\n", c->n_samples);
}

/* Prepare + warm-up + statistics pass for one configuration. */
static void measure__prepare(mscene *m, mconf *c)
{
    const sweep_measure *sm = &m->job->sweep->measure;
    mscene_say(m->job, "B %s", c->pc->key);
    /* Test hook for the watchdog: DMBENCH_TEST_HANG=<technique> blocks this
     * process when it reaches that technique.  (A shader cannot hang
     * llvmpipe: its JIT caps shader loops, so tests hang the process.) */
    const char *hang = getenv("DMBENCH_TEST_HANG");
    if (hang && strcmp(hang, dm_kv_get(c->pc->params, c->pc->n_params, "technique")) == 0)
        for (;;)
            pause();
    int rc = render_prepare(m->r, c->pc->params, c->pc->n_params, &c->item, &c->log);
    /* compiler warnings and errors of this configuration's programs go to its own log */
    if (gl_context_take_messages(m->gl, &c->log) > 0 && rc == 0) {
        mscene_fail(c, "GL error while preparing the configuration (see log)");
        return;
    }
    if (rc != 0) {
        mscene_fail(c, rc == DM_ERR_SHADER ? "shader compile or link failed (see log)"
                         : rc == DM_ERR_UNSUPPORTED ? "not supported by this driver (see log)"
                                                    : "could not prepare the configuration (see log)");
        return;
    }
    render_get_info(m->r, c->item, &c->info);
    mscene_prepare_minimal(m, c);
    mscene_prepare_trips(m, c, m->statistic, m->n_statistic);
    measure__warmup(m, c);
    c->stats = dm_xcalloc(m->n_statistic + 1, sizeof *c->stats);
    c->stats_reason = dm_xcalloc(m->n_statistic + 1, sizeof *c->stats_reason);
    int64_t t0 = dm_now_ns();
    if (m->n_statistic)
        mscene_session(m, c, m->statistic, m->n_statistic, 1, c->stats, c->stats_reason);
    c->stats_ns = dm_now_ns() - t0;
    c->timing = dm_xcalloc(m->n_timing + 1, sizeof *c->timing);
    for (size_t i = 0; i < m->n_timing; i++)
        c->timing[i] = dm_xcalloc((size_t)sm->samples_max, sizeof **c->timing);
    c->cap = (size_t)sm->samples_max;
    c->round_of = dm_xcalloc(c->cap + 1, sizeof *c->round_of);
    c->corr_ci_rel = NAN;
    path_timing_prepare(m, c);
    c->active = 1;
    measure__restore(m, c);
    for (size_t j = 0; j < c->n_samples; j++)
        c->round_of[j] = SIZE_MAX;   /* taken by another process: not in this one's rounds */
}

/* Checkpoints the samples of every configuration still sampling, in one
 * transaction after a round: a kill then loses at most the round in flight.
 * Returns 0 or DM_ERR_STORE (message in err). */
static int measure__checkpoint(mscene *m, mconf *cs, size_t n, dm_str *err)
{
    store_partial *items = dm_xcalloc(n + 1, sizeof *items);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if ((cs[i].active || cs[i].extra) && !cs[i].failed && cs[i].n_samples)
            items[k++] = (store_partial){ .key = cs[i].pc->key, .counters = m->timing,
                                          .n_counters = m->n_timing, .samples = cs[i].timing,
                                          .n_samples = cs[i].n_samples,
                                          .sampling_ns = (long)cs[i].sampling_ns };
    int rc = k ? store_partial_put(m->st, m->job->run_id, items, k) : 0;
    if (rc != 0)
        dm_str_printf(err, "cannot checkpoint the samples of a round: %s", store_last_error(m->st));
    free(items);
    return rc ? DM_ERR_STORE : 0;
}

/* Records a finished round of the scene: the configurations it sampled in
 * their order, and the calibration kernel's time around it (the drift's
 * second predictor, models/drift.h).  A round that sampled nothing is not
 * recorded.  Returns 0 or DM_ERR_STORE (message in err). */
static int measure__round(mscene *m, const dm_str *keys, double calib_ns, dm_str *err)
{
    if (!keys->len || !m->job->n_configs)
        return 0;
    dm_round r = { .scene = (char *)m->job->configs[0].scene, .keys = (char *)dm_str_get(keys),
                   .calib_ns = calib_ns };
    int rc = store_round_put(m->st, m->job->run_id, &r);
    if (rc != 0)
        dm_str_printf(err, "cannot record a round: %s", store_last_error(m->st));
    return rc ? DM_ERR_STORE : 0;
}

/* Room for one more sample in every timing row of c (extra rounds go past
 * samples.max). */
static void measure__room(mscene *m, mconf *c)
{
    if (c->n_samples < c->cap)
        return;
    c->cap = c->cap ? 2 * c->cap : 8;
    for (size_t i = 0; i < m->n_timing; i++)
        c->timing[i] = dm_xrealloc(c->timing[i], c->cap * sizeof **c->timing);
    c->round_of = dm_xrealloc(c->round_of, c->cap * sizeof *c->round_of);
    path_timing_room(c);
}

/* Test hook for the extra rounds: DMBENCH_TEST_NOISY=<technique> scales
 * the stop counter's samples of that technique by a factor in [0.4, 1.6]
 * drawn from its key and the sample's index, so that one configuration
 * stays short of a ±15 % target for tens of samples (it reaches it after
 * some 30 to 60, depending on the machine's own spread). */
static void measure__test_noise(const mscene *m, const mconf *c, double *vals)
{
    const char *noisy = getenv("DMBENCH_TEST_NOISY");
    if (!noisy || m->stop_index < 0 || strcmp(noisy, dm_kv_get(c->pc->params, c->pc->n_params, "technique")) != 0)
        return;
    uint64_t h = 1469598103934665603u ^ c->n_samples;
    for (const char *p = c->pc->key; *p; p++)
        h = (h ^ (unsigned char)*p) * 1099511628211u;
    h ^= h >> 29;
    vals[m->stop_index] *= 0.4 + 1.2 * (double)(h % 1000003) / 1000002.0;
}

/* The end of c's sampling in its log: a drifting stop counter, and the
 * protocol's stop reason with --verbose. */
static void measure__stopped(mscene *m, mconf *c)
{
    const protocol_decision *d = &c->last;
    if (d->drifting && m->stop_index >= 0)
        dm_str_printf(&c->log, "%s drifted %+.1f %% over its %zu samples (a trend, not noise: the "
                      "machine's load or clock changed while sampling)\n", m->timing[m->stop_index],
                      100 * d->drift, c->n_samples);
    dm_log(DM_LOG_DEBUG, "sampling %s: %zu samples (%zu in extra rounds), stop: %s, CI ±%.2f %%",
           c->pc->key, c->n_samples, c->n_extra, protocol_stop_name(d->stop), 100 * d->ci_rel);
}

/* Takes one timing sample of a configuration and asks the protocol whether
 * it stops.  In the scene's rounds (extra == 0) a configuration that stops
 * short of its target waits for extra rounds (c->extra) when the job has
 * time for them; in an extra round (extra == 1) it stops waiting once its
 * CI is within the target. */
static void measure__timing_sample(mscene *m, mconf *c, int extra)
{
    measure__room(m, c);
    double *vals = dm_xcalloc(m->n_timing + 1, sizeof *vals);
    mscene_say(m->job, "B %s", c->pc->key);
    int64_t t0 = dm_now_ns();
    render_vt_stats v0, v1;
    int vt = render_get_vt_stats(m->r, c->item, &v0) == 0;
    if (mscene_session(m, c, m->timing, m->n_timing, c->frames, vals, NULL) != 0) {
        mscene_fail(c, "counter session failed (see log)");
        free(vals);
        return;
    }
    if (vt && render_get_vt_stats(m->r, c->item, &v1) == 0) {   /* the VT may be shared: its own deltas */
        c->has_vt = 1;
        c->vt.page_misses += v1.page_misses - v0.page_misses;
        c->vt.upload_bytes += v1.upload_bytes - v0.upload_bytes;
        c->vt.pages_resident = v1.pages_resident;
        c->vt.committed_bytes = v1.committed_bytes;
    }
    path_timing_record(m, c, vals);
    measure__test_noise(m, c, vals);
    for (size_t i = 0; i < m->n_timing; i++)
        c->timing[i][c->n_samples] = vals[i];
    c->round_of[c->n_samples] = m->n_rounds;
    c->n_samples++;
    c->sampling_ns += dm_now_ns() - t0;
    free(vals);
    const double *x = m->stop_index >= 0 ? c->timing[m->stop_index] : NULL;
    double elapsed = (double)c->sampling_ns / 1e9;   /* its own samples only, not the round's */
    protocol_decision d = protocol_decide(&m->pd, x, c->n_samples, elapsed);
    c->last = d;
    c->ci_rel = d.ci_rel;
    if (extra) {   /* measure__extra decides, on the CI the figure will be judged by */
        c->n_extra++;
        return;
    }
    if (d.stop == PROTOCOL_CONTINUE)
        return;
    c->active = 0;
    /* With extra time every timed configuration waits for the scene's
     * rounds to end, even one whose raw CI converged: on few samples the
     * drift's removal can widen its CI past the target (docs/measurement.md,
     * "Extra rounds"), and measure__extra judges it by that CI. */
    c->extra = m->job->extra_s > 0 && x;
    c->ci_rel_before = d.ci_rel;
}

static void measure__counter_timed(dm_counter_result *r, const double *x, size_t n, uint64_t seed)
{
    stats_summary su;
    r->has_samples = 1;
    r->samples = dm_xmalloc((n ? n : 1) * sizeof *r->samples);
    memcpy(r->samples, x, n * sizeof *x);
    r->n_samples = n;
    if (stats_summarize(x, n, seed, &su) != 0) {
        r->available = 0;
        r->unavailable_reason = dm_xstrdup("no finite sample");
        return;
    }
    r->value = r->median = su.median;
    r->mean = su.mean;
    r->min = su.min;
    r->max = su.max;
    r->stddev = su.stddev;
    r->mad = su.mad;
    r->cv = su.cv;
    r->ci_lo = su.ci_lo;
    r->ci_hi = su.ci_hi;
    r->n_outliers = su.n_outliers;
    r->n_nonfinite = (int)su.n_nonfinite;
}

static dm_counter_result *measure__push(dm_config_result *out, const char *name)
{
    const counters_info *ci = counters_find(name);
    dm_counter_result *r = dm_vec_push(&out->counters, &out->n_counters, NULL, sizeof *r);
    memset(r, 0, sizeof *r);
    r->name = dm_xstrdup(name);
    r->unit = dm_xstrdup(ci ? counters_unit_name(ci->unit) : "items");
    r->deterministic = ci ? ci->deterministic : 0;
    r->available = 1;
    return r;
}

/* Value of a caller-fed counter for configuration c, by its registry feed;
 * NaN when nothing feeds it. */
static double measure__fed(const mconf *c, counters_feed feed)
{
    switch (feed) {
    case COUNTERS_FEED_SETUP_NS: return (double)c->info.setup_ns;
    case COUNTERS_FEED_WARMUP_NS: return (double)c->warmup_ns;
    case COUNTERS_FEED_TEXTURE_BYTES: return (double)c->info.texture_bytes;
    case COUNTERS_FEED_MESH_BYTES: return (double)c->info.mesh_bytes;
    case COUNTERS_FEED_MESH_TRIANGLES: return (double)c->info.mesh_triangles;
    case COUNTERS_FEED_VIEWPORT_PIXELS: return (double)c->pc->width * c->pc->height;
    case COUNTERS_FEED_VT_RESIDENT: return c->has_vt ? (double)c->vt.pages_resident : NAN;
    case COUNTERS_FEED_VT_MISSES: return c->has_vt ? (double)c->vt.page_misses : NAN;
    case COUNTERS_FEED_VT_UPLOAD_BYTES: return c->has_vt ? (double)c->vt.upload_bytes : NAN;
    case COUNTERS_FEED_VT_COMMITTED_BYTES: return c->has_vt ? (double)c->vt.committed_bytes : NAN;
    case COUNTERS_FEED_NONE: break;
    }
    return NAN;
}

/* Value of a counter for derived formulas: the median of timed counters,
 * the value of the others; a caller-fed counter the sweep did not list
 * (ViewportPixels) is fed all the same. */
typedef struct derive_env { const dm_config_result *out; const mconf *c; } derive_env;

static int measure__derive_value(const char *name, void *user, double *value)
{
    const derive_env *e = user;
    const dm_counter_result *r = dm_config_counter(e->out, name);
    const counters_info *ci = counters_find(name);
    if (!r && ci && ci->feed != COUNTERS_FEED_NONE) {
        *value = measure__fed(e->c, ci->feed);
        return 0;
    }
    if (!r || !r->available || r->partial)
        return DM_ERR_UNAVAILABLE;
    *value = r->value;
    return 0;
}

static int measure__derive_has(const char *name, void *user)
{
    const derive_env *e = user;
    const counters_info *ci = counters_find(name);
    return (ci && ci->feed != COUNTERS_FEED_NONE) || dm_config_counter(e->out, name) != NULL;
}

/* Adds every derived counter whose inputs were all collected (docs/counters.md:
 * formulas over the above); a zero denominator is unavailable, not infinite. */
static void measure__derived(const mconf *c, dm_config_result *out)
{
    derive_env e = { out, c };
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *ci = counters_info_at(i);
        if (ci->backend != COUNTERS_BACKEND_DERIVED || !counters_derive_inputs(ci->name, measure__derive_has, &e))
            continue;
        double v = NAN;
        dm_str why = {0};
        int rc = counters_derive(ci->name, measure__derive_value, &e, &v, &why);
        dm_counter_result *r = measure__push(out, ci->name);
        r->value = v;
        if (rc != 0) {
            r->available = 0;
            r->unavailable_reason = dm_xstrdup(why.len ? dm_str_get(&why) : "unavailable");
        }
        dm_str_free(&why);
    }
}

/* The stage counters of a counted configuration (docs/counters.md, "Stage
 * costs"), per sample: geometry = the discard window G; raster = the
 * minimal-shader window R minus the same with discard M (the minimal
 * program's own geometry, so a change of the geometry's work by the
 * minimal shader does not enter raster); fragment = full − G − raster;
 * residual = G − M (that change); unavailable with the reason when
 * the windows were not counted. */
static void measure__stage_counters(mconf *c, const callgrind_count *k, uint64_t seed, dm_config_result *out)
{
    static const char *const names[] = {"GeometryInstructions", "RasterInstructions", "FragmentInstructions",
                                        "StageResidual"};
    double part[4] = {NAN, NAN, NAN, NAN};
    for (int st = 0; st < 4; st++) {
        dm_counter_result *r = measure__push(out, names[st]);
        if (!k || !k->staged) {
            r->available = 0;
            r->unavailable_reason = dm_xstrdup(k && k->stage_reason ? k->stage_reason
                                               : k && k->reason ? k->reason : "not counted");
            continue;
        }
        double v[CALLGRIND_SAMPLES];
        for (int s = 0; s < CALLGRIND_SAMPLES; s++) {
            double g = k->window[CALLGRIND_GEOMETRY][s], m = k->window[CALLGRIND_RESIDUAL][s];
            double raster = k->window[CALLGRIND_RASTER][s] - m;   /* the minimal program's own geometry out */
            double parts[4] = {g, raster, k->samples[s] - g - raster, g - m};
            v[s] = parts[st];
        }
        measure__counter_timed(r, v, CALLGRIND_SAMPLES, seed);
        part[st] = r->value;
        if (r->value < 0 && st < 3)
            dm_str_printf(&c->log, "%s: negative (%.0f per frame): the isolation passes did not "
                          "nest here, see docs/counters.md\n", names[st], r->value);
    }
    dm_str verdict = {0};   /* the bottleneck verdict, in the configuration's log */
    if (counters_stage_verdict(part[0], part[1], part[2], &verdict) == 0)
        dm_str_printf(&c->log, "stages (instructions): %s\n", dm_str_get(&verdict));
    dm_str_free(&verdict);
}

/* Instructions of configuration c from the Instructions pass (its own
 * child under Valgrind): the per-frame count of each sample, or unavailable
 * with the pass's reason.  Samples that disagree are noted in the log.
 * With stage counters asked for, also their three counters. */
static void measure__instructions(mscene *m, mconf *c, dm_config_result *out)
{
    const callgrind_count *k = NULL;
    for (size_t i = 0; i < m->job->n_instructions && !k; i++)
        if (strcmp(m->job->instructions[i].key, c->pc->key) == 0)
            k = &m->job->instructions[i];
    if (!m->job->n_instructions)
        return;
    dm_counter_result *r = measure__push(out, "Instructions");
    if (!k || !k->counted) {
        r->available = 0;
        r->unavailable_reason = dm_xstrdup(k && k->reason ? k->reason : "not counted");
    } else {
        measure__counter_timed(r, k->samples, CALLGRIND_SAMPLES, m->job->seed);
        if (k->allocator[0] > 0)
            dm_str_printf(&c->log, "Instructions: the C allocator's %.0f instructions per frame (%.2g %% "
                          "of the frame) left out, see docs/counters.md\n", k->allocator[0],
                          100 * k->allocator[0] / (k->allocator[0] + k->samples[0]));
        if (r->max - r->min > CALLGRIND_AGREE * r->min)
            dm_str_printf(&c->log, "Instructions: samples disagree (%.0f .. %.0f per frame)\n", r->min, r->max);
    }
    if (callgrind_wants_stages(&m->job->sweep->measure))
        measure__stage_counters(c, k, m->job->seed, out);
}

/* Fills the counters of a finished configuration into out. */
static void measure__collect(mscene *m, mconf *c, dm_config_result *out)
{
    const sweep_measure *sm = &m->job->sweep->measure;
    for (size_t i = 0; i < m->n_timing; i++) {
        dm_counter_result *r = measure__push(out, m->timing[i]);
        const char *why = NULL;
        if (!counters_available(m->cc, m->timing[i], &why)) {
            r->available = 0;
            r->unavailable_reason = dm_xstrdup(why ? why : "unavailable on this driver");
            continue;
        }
        if (c->min_why && strcmp(m->timing[i], "MinimalShadingTime") == 0) {
            r->available = 0;
            r->unavailable_reason = dm_xstrdup(c->min_why);
            continue;
        }
        measure__counter_timed(r, c->timing[i], c->n_samples, m->job->seed);
        /* GL_TIME_ELAPSED covers only part of the work on some drivers */
        r->partial = counters_find(m->timing[i])->backend == COUNTERS_BACKEND_TIMER_QUERY && m->job->timer_partial;
    }
    for (size_t i = 0; i < m->n_statistic; i++) {
        dm_counter_result *r = measure__push(out, m->statistic[i]);
        r->value = c->stats[i];
        if (!isfinite(c->stats[i])) {
            r->available = 0;
            r->unavailable_reason = dm_xstrdup(c->stats_reason[i] ? c->stats_reason[i]
                                                                  : "unavailable on this driver");
        }
    }
    for (size_t i = 0; i < sm->n_counters; i++) {
        const counters_info *ci = counters_find(sm->counters[i]);
        double v = ci ? measure__fed(c, ci->feed) : NAN;
        if (ci && isfinite(v))
            measure__push(out, ci->name)->value = v;
    }
    measure__instructions(m, c, out);
    measure__derived(c, out);
}

/* Builds the result of a configuration and commits it in one transaction.
 * Returns 0, or DM_ERR_STORE (message in err) when the store cannot take it
 * (disk full, damaged database): the caller stops, as no later
 * configuration could be saved either; or DM_ERR_ARG, with a 'C' line to
 * the runner, when a user map or mesh file changed since the run started
 * (run/inputs.h): nothing is recorded for it, and the run stops. */
static int measure__commit(mscene *m, mconf *c, dm_str *err)
{
    dm_config_result out = {0};
    out.key = dm_xstrdup(c->pc->key);
    out.scene = dm_xstrdup(c->pc->scene);
    for (size_t i = 0; i < c->pc->n_params; i++)
        dm_kv_push(&out.params, &out.n_params, c->pc->params[i].key, c->pc->params[i].value);
    if (!c->failed && c->n_samples)
        measure__stopped(m, c);
    if (c->n_extra || isfinite(c->corr_ci_rel)) {
        int done = protocol_extra_done(c->ci_rel, c->corr_ci_rel, m->pd.target_ci);
        dm_str_printf(&c->log, "%zu samples in extra rounds (--extra-time): %s CI ±%.2f %% -> ±%.2f %%",
                      c->n_extra, m->timing[m->stop_index], 100 * c->ci_rel_before, 100 * c->ci_rel);
        if (isfinite(c->corr_ci_rel))
            dm_str_printf(&c->log, " (±%.2f %% with the machine's drift removed)", 100 * c->corr_ci_rel);
        dm_str_printf(&c->log, ", target ±%.2f %% %s\n", 100 * m->pd.target_ci,
                      done ? "reached" : "not reached (the budget was spent)");
    }
    if (!c->failed) {
        int64_t t0 = dm_now_ns();
        measure__collect(m, c, &out);
        path_timing_collect(c, &out);
        mquality_measure(m, c, &out);
        c->quality_ns = dm_now_ns() - t0;
    }
    dm_log(DM_LOG_DEBUG, "measure %s: setup %.1f ms, warm-up %.1f ms, statistics %.1f ms, sampling %.1f ms, "
           "images+quality %.1f ms (reference %s)", c->pc->key, c->info.setup_ns / 1e6, c->warmup_ns / 1e6,
           c->stats_ns / 1e6, c->sampling_ns / 1e6, c->quality_ns / 1e6, c->ref_source ? c->ref_source : "reused");
    dm_str glmsg = {0};
    if (gl_context_take_messages(m->gl, &glmsg) + gl_context_check_errors(&glmsg) > 0)
        mscene_fail(c, "GL error during the configuration (see log)");
    dm_str_cat(&c->log, dm_str_get(&glmsg));
    dm_str_free(&glmsg);
    out.ok = !c->failed;
    out.reason = dm_xstrdup(c->reason);
    out.log = c->log.len ? dm_xstrdup(dm_str_get(&c->log)) : NULL;
    dm_str changed = {0};
    if (inputs_check(&changed) != 0) {   /* measured from another version: record nothing */
        for (char *p = changed.buf; *p; p++)
            if (*p == '\n' || *p == '\r')
                *p = ' ';
        mscene_say(m->job, "C %s", dm_str_get(&changed));
        dm_str_cat(err, dm_str_get(&changed));
        dm_str_free(&changed);
        dm_config_result_free(&out);
        return DM_ERR_ARG;
    }
    int rc = store_config_put(m->st, m->job->run_id, &out);
    if (rc == 0 && (c->n_extra || isfinite(c->corr_ci_rel)))
        mscene_say(m->job, "A %s %zu %.4f %.4f %.4f", c->pc->key, c->n_extra, c->ci_rel_before, c->ci_rel,
                   c->corr_ci_rel);
    const dm_counter_result *wt = m->stop_index >= 0 ? dm_config_counter(&out, m->timing[m->stop_index]) : NULL;
    double ci = wt && wt->median > 0 ? (wt->ci_hi - wt->ci_lo) / 2 / wt->median : NAN;
    if (rc == 0 && out.path.frames)   /* on a camera path: its p99 and stutters too */
        mscene_say(m->job, "D %s %s %.0f %.4f %lld %.0f %zu", c->pc->key, out.ok ? "ok" : "failed",
                   wt ? wt->median : NAN, ci, (long long)c->sampling_ns, out.path.p99, out.path.n_stutters);
    else if (rc == 0)
        mscene_say(m->job, "D %s %s %.0f %.4f %lld", c->pc->key, out.ok ? "ok" : "failed",
                     wt ? wt->median : NAN, ci, (long long)c->sampling_ns);
    else
        dm_str_printf(err, "cannot save configuration %s: %s", c->pc->key,
                      store_last_error(m->st));
    dm_config_result_free(&out);
    return rc == 0 ? 0 : DM_ERR_STORE;
}

int measure_pilot(const measure_job *job, dm_str *err)
{
    mscene m = { .job = job };
    int rc = mscene_setup(&m, err);
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        mconf *c = &cs[i];
        c->pc = &job->configs[i];
        mscene_say(job, "B %s", c->pc->key);
        double ns = NAN, counts[PREDICT_N_COUNTS];
        for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
            counts[k] = NAN;
        if (render_prepare(m.r, c->pc->params, c->pc->n_params, &c->item, &c->log) == 0) {
            mscene_frames(&m, c, 2);             /* JIT and first-use costs */
            ns = mscene_plain_sample(&m, c, 1);
            mscene_prepare_trips(&m, c, predict_counts, PREDICT_N_COUNTS);
            /* and its invocation counts, for a prediction from the
             * instruction models (run --budget) */
            mscene_session(&m, c, (const char **)predict_counts, PREDICT_N_COUNTS, 1, counts, NULL);
        }
        gl_context_take_messages(m.gl, NULL);
        dm_str line = {0};
        dm_str_printf(&line, "P %s %.0f", c->pc->key, ns);
        for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
            dm_str_printf(&line, " %.17g", counts[k]);
        mscene_say(job, "%s", dm_str_get(&line));
        dm_str_free(&line);
    }
    mscene_teardown(&m, cs, rc == 0 ? job->n_configs : 0);
    return rc;
}

/* What a round costs besides its samples: the calibration kernel around
 * it, recording it and the checkpoint (not the commits, which each
 * configuration pays once whatever the rounds). */
typedef struct measure__overhead { int64_t ns; size_t rounds; } measure__overhead;

/* The calibration kernel before a round (its time counted in o); NaN,
 * and no kernel, in a scene that times nothing (its counters are all
 * deterministic: there is no drift to predict). */
static double measure__round_begin(const mscene *m, measure__overhead *o)
{
    if (m->n_timing == 0)
        return NAN;
    int64_t t0 = dm_now_ns();
    double cal = calibrate_cpu_once();   /* the machine's speed around the round */
    o->ns += dm_now_ns() - t0;
    return cal;
}

/* The end of a round: the kernel again, the round recorded with the
 * kernel's mean time, and the samples of the configurations still
 * sampling (or waiting for extra rounds) checkpointed; the time counted
 * in o.  Returns 0 or DM_ERR_STORE (err). */
static int measure__round_end(mscene *m, mconf *cs, size_t n, const dm_str *keys, double cal0,
                              measure__overhead *o, dm_str *err)
{
    int64_t t0 = dm_now_ns();
    int rc = measure__round(m, keys, isfinite(cal0) ? (cal0 + calibrate_cpu_once()) / 2 : NAN, err);
    m->n_rounds += keys->len > 0;   /* as measure__round records it */
    if (rc == 0)
        rc = measure__checkpoint(m, cs, n, err);
    o->ns += dm_now_ns() - t0;
    o->rounds++;
    return rc;
}

/* The mean cost of a round besides its samples so far (s), 0 before one. */
static double measure__overhead_s(const measure__overhead *o)
{
    return o->rounds ? (double)o->ns / 1e9 / (double)o->rounds : 0;
}

/* Each configuration's stop-counter CI with the drift removed, from the
 * samples of this process's rounds (protocol_extra_corrected), into
 * ci[0..n) (NaN: decide by the raw CI).  Returns 1 when the drift was
 * removed. */
static int measure__corrected_ci(const mscene *m, const mconf *cs, size_t n, double *ci)
{
    size_t nr = m->n_rounds;
    if (m->stop_index < 0 || nr == 0)
        return 0;
    double *x = dm_xcalloc(n * nr + 1, sizeof *x);
    for (size_t i = 0; i < n * nr; i++)
        x[i] = NAN;
    for (size_t c = 0; c < n; c++)
        for (size_t j = 0; !cs[c].failed && j < cs[c].n_samples; j++)
            if (cs[c].round_of[j] < nr)
                x[c * nr + cs[c].round_of[j]] = cs[c].timing[m->stop_index][j];
    int removed = protocol_extra_corrected(x, n, nr, m->job->seed, ci);
    free(x);
    return removed;
}

/* Commits a configuration the extra rounds are done with: corr is its CI
 * with the drift removed (NaN: raw figures decide).  One whose raw CI had
 * converged in the scene's rounds and that took no extra sample commits
 * as the scene's rounds left it. */
static int measure__extra_commit(mscene *m, mconf *c, double corr, int64_t *committing, dm_str *err)
{
    int64_t c0 = dm_now_ns();
    c->extra = 0;
    int untouched = c->n_extra == 0 && c->ci_rel_before <= m->pd.target_ci &&
                    protocol_extra_done(c->ci_rel, corr, m->pd.target_ci);
    c->corr_ci_rel = untouched ? NAN : corr;
    int rc = measure__commit(m, c, err);
    *committing += dm_now_ns() - c0;   /* images and quality: not the rounds' time */
    return rc;
}

/* The extra rounds after the scene's rounds: while the job's extra_s
 * lasts, every timed configuration that is short of its target -- judged
 * by the figure it will be stored with (protocol_extra_done): its CI with
 * the scene's drift removed where that is removed, whatever its raw CI,
 * else its raw CI -- gets one more sample per round, the widest first as
 * far as the time left allows (protocol_extra_round), sampled in a fresh
 * seeded order like every round and recorded as a round (the drift's
 * model reads them as any other).  Before each round the scene's drift is
 * removed again from all its samples so far; a configuration is committed
 * once done, or when the rounds end; then one "R" line says how many
 * rounds, the time they took, and why they ended.  Returns 0 or the first
 * commit's or store's error (err). */
static int measure__extra(mscene *m, mconf *cs, size_t n, measure__overhead *over, dm_str *err)
{
    const measure_job *job = m->job;
    size_t *wait = dm_xcalloc(n + 1, sizeof *wait), *pick = dm_xcalloc(n + 1, sizeof *pick);
    size_t *order = dm_xcalloc(n + 1, sizeof *order), rounds = 0;
    double *ci = dm_xcalloc(n + 1, sizeof *ci), *sample_s = dm_xcalloc(n + 1, sizeof *sample_s);
    double *corr = dm_xcalloc(n + 1, sizeof *corr);
    int64_t t0 = dm_now_ns(), committing = 0;
    protocol_extra_why why = PROTOCOL_EXTRA_REACHED;
    int rc = 0;
    size_t any = 0, short_of = 0;
    for (size_t i = 0; i < n; i++)
        any += cs[i].extra != 0;
    while (rc == 0 && any) {
        size_t nw = 0;
        int removed = measure__corrected_ci(m, cs, n, corr);
        for (size_t i = 0; rc == 0 && i < n; i++) {
            if (!cs[i].extra)
                continue;
            double k = removed ? corr[i] : NAN;
            if (cs[i].failed || protocol_extra_done(cs[i].ci_rel, k, m->pd.target_ci)) {
                rc = measure__extra_commit(m, &cs[i], k, &committing, err);
                short_of += rounds == 0 && isfinite(cs[i].corr_ci_rel);   /* short raw, done corrected */
                continue;
            }
            wait[nw] = i;
            ci[nw] = isfinite(k) ? k : cs[i].ci_rel;   /* as protocol_extra_done judges it */
            sample_s[nw++] = (double)cs[i].sampling_ns / 1e9 / (double)cs[i].n_samples;
        }
        short_of += rounds == 0 ? nw : 0;
        if (rc != 0 || nw == 0)
            break;
        /* what is left once this round's own cost (the mean so far) is paid */
        double left = job->extra_s - (double)(dm_now_ns() - t0 - committing) / 1e9 - measure__overhead_s(over);
        double bar = removed ? PROTOCOL_EXTRA_CLEAR * m->pd.target_ci : m->pd.target_ci;
        size_t np = protocol_extra_round(ci, sample_s, nw, bar, left, pick, &why);
        if (np == 0)
            break;
        plan_shuffle(order, np, job->seed + 0x9e3779b97f4a7c15u * ++rounds);   /* blocks the drift */
        dm_str keys = {0};
        double cal0 = measure__round_begin(m, over);
        for (size_t k = 0; rc == 0 && k < np; k++) {
            mconf *c = &cs[wait[pick[order[k]]]];
            dm_str_printf(&keys, "%s%s", keys.len ? " " : "", c->pc->key);
            measure__timing_sample(m, c, 1);
        }
        rc = rc ? rc : measure__round_end(m, cs, n, &keys, cal0, over, err);
        dm_str_free(&keys);
    }
    int64_t spent = dm_now_ns() - t0 - committing;
    int removed = rc == 0 && any && measure__corrected_ci(m, cs, n, corr);
    for (size_t i = 0; rc == 0 && i < n; i++)
        if (cs[i].extra)   /* the budget ended them */
            rc = measure__extra_commit(m, &cs[i], removed ? corr[i] : NAN, &committing, err);
    if (short_of)
        mscene_say(job, "R %zu %lld %s %zu", rounds, (long long)spent,
                   why == PROTOCOL_EXTRA_BUDGET ? "budget" : "reached", short_of);
    free(wait);
    free(pick);
    free(order);
    free(ci);
    free(corr);
    free(sample_s);
    return rc;
}

int measure_scene(const measure_job *job, dm_str *err)
{
    mscene m = { .job = job };
    int rc = mscene_setup(&m, err), set_up = rc == 0;
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        cs[i].pc = &job->configs[i];
        measure__prepare(&m, &cs[i]);
        if (cs[i].failed)
            rc = measure__commit(&m, &cs[i], err);
    }
    size_t *order = dm_xcalloc(job->n_configs + 1, sizeof *order);
    measure__overhead over = {0};
    for (uint64_t round = 0, active = 1; rc == 0 && active; round++) {
        active = 0;
        plan_shuffle(order, job->n_configs, job->seed + round);
        dm_str keys = {0};
        double cal0 = measure__round_begin(&m, &over);
        for (size_t k = 0; k < job->n_configs; k++) {
            mconf *c = &cs[order[k]];
            if (!c->active)
                continue;
            dm_str_printf(&keys, "%s%s", keys.len ? " " : "", c->pc->key);
            measure__timing_sample(&m, c, 0);
            if (!c->active && !c->extra)
                rc = measure__commit(&m, c, err);
            active |= (uint64_t)c->active;
            if (rc != 0)
                break;
        }
        rc = rc ? rc : measure__round_end(&m, cs, job->n_configs, &keys, cal0, &over, err);
        dm_str_free(&keys);
    }
    rc = rc ? rc : measure__extra(&m, cs, job->n_configs, &over, err);
    free(order);
    mscene_teardown(&m, cs, set_up ? job->n_configs : 0);
    return rc;
}

