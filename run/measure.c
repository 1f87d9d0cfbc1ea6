/* measure.c — the measurement protocol for one scene (see measure.h). */
#include "measure.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "run/callgrind.h"
#include "run/gl_context.h"
#include "run/inputs.h"
#include "run/predict.h"
#include "run/protocol.h"
#include "run/refcache.h"
#include "store/store.h"
#include "run/target.h"
#include "models/stats.h"
#include "reports/image.h"
#include "reports/flip.h"
#include "reports/quality.h"
#include "techniques/render.h"

#include <epoxy/gl.h>
#include <valgrind/callgrind.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Draws at most this many frames to converge a virtual texture before an image. */
#define MEASURE_VT_CONVERGE_MAX 64

/* State of one configuration while its scene is measured. */
typedef struct mconf {
    const plan_config *pc;
    tech_item item;
    tech_item item_min;         /* minimal-fragment-shader item for the raster pass (MinimalShadingTime), 0 = none */
    char *min_why;              /* why there is none although the sweep asks for MinimalShadingTime */
    tech_item item_trips;       /* loop-trip counting item for the LoopTrips pass, 0 = none */
    tech_item_info info;
    int active;                 /* still sampling */
    int failed;
    char *reason;
    dm_str log;
    int64_t warmup_ns;
    int64_t sampling_ns;        /* time spent in its own timing samples */
    int64_t stats_ns, quality_ns;   /* statistics pass; images and quality (--verbose log) */
    const char *ref_source;     /* "cache", "rendered", NULL: the scene's, made before */
    int frames;                 /* frames per timing sample (>= K, see min_sample_ms) */
    double **timing;            /* per timing counter: per-frame samples */
    size_t n_samples;
    double *stats;              /* per statistics counter: per-frame value (NAN = unavailable) */
    char **stats_reason;
    int has_vt;                 /* virtual-textured: vt holds its samples' figures */
    tech_vt_stats vt;           /* misses and upload bytes summed over its samples, the rest at the last */
} mconf;

typedef struct mscene {
    const measure_job *job;
    gl_context *gl;
    tech_renderer *r;
    counters_context *cc;
    store *st;
    const char **timing;        /* enabled counters by kind */
    size_t n_timing;
    const char **statistic;
    size_t n_statistic;
    int stop_index;             /* timing[] index of the counter that stops sampling, -1: none */
    protocol_desc pd;           /* the measuring decisions' settings (run/protocol.h) */
    target rt;                  /* the scene's render target (one resolution per scene) */
    float *ref_rgba, *ref_depth;   /* scene reference, rendered on first use */
    char *ref_path;
} mscene;

static void measure__say(const measure_job *job, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

static void measure__say(const measure_job *job, const char *fmt, ...)
{
    if (job->report_fd < 0)
        return;
    dm_str s = {0};
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(&s, fmt, ap);
    va_end(ap);
    dm_str_cat(&s, "\n");
    ssize_t w = write(job->report_fd, s.buf, s.len);
    (void)w;
    dm_str_free(&s);
}

/* Sorts the sweep's counters, by their registry backend, into those read in
 * timed passes and those read in the one-frame statistics pass; caller-fed
 * counters (their registry feed) are filled from the renderer, derived ones
 * by formula.  The timed counter flagged stops_sampling drives the stop rule. */
static void measure__classify(mscene *m)
{
    const sweep_measure *sm = &m->job->sweep->measure;
    m->timing = dm_xcalloc(sm->n_counters, sizeof *m->timing);
    m->statistic = dm_xcalloc(sm->n_counters, sizeof *m->statistic);
    m->stop_index = -1;
    for (size_t i = 0; i < sm->n_counters; i++) {
        const counters_info *ci = counters_find(sm->counters[i]);
        if (!ci)
            continue;
        if (ci->backend == COUNTERS_BACKEND_PIPELINE_STATS || ci->backend == COUNTERS_BACKEND_OCCLUSION ||
            ci->backend == COUNTERS_BACKEND_SHADER_COUNT)
            m->statistic[m->n_statistic++] = ci->name;
        else if (ci->backend == COUNTERS_BACKEND_CLOCK || ci->backend == COUNTERS_BACKEND_TIMER_QUERY) {
            if (ci->stops_sampling && m->stop_index < 0)
                m->stop_index = (int)m->n_timing;
            m->timing[m->n_timing++] = ci->name;
        }
    }
}

static void measure__fail(mconf *c, const char *reason)
{
    if (c->failed)
        return;
    c->failed = 1;
    c->active = 0;
    c->reason = dm_xstrdup(reason);
}

/* Draws `frames` frames of one item into the scene's target (made or
 * resized on first use; rebound because image renders use their own). */
static void measure__frames(mscene *m, mconf *c, int frames)
{
    if (m->rt.w != c->pc->width || m->rt.h != c->pc->height) {
        target_destroy(&m->rt);
        if (target_create(&m->rt, c->pc->width, c->pc->height) != 0) {
            dm_str_printf(&c->log, "cannot create a %dx%d render target\n", c->pc->width, c->pc->height);
            return;
        }
    }
    target_bind(&m->rt);
    for (int f = 0; f < frames; f++) {
        tech_set_frame(m->r, c->item, (uint64_t)f);   /* orbits: frame f of every sample */
        tech_draw(m->r, c->item, c->pc->width, c->pc->height);
    }
}

/* One fenced sample of K frames without a counter session: wall ns/frame. */
static double measure__plain_sample(mscene *m, mconf *c, int frames)
{
    glFinish();
    int64_t t0 = dm_now_ns();
    measure__frames(m, c, frames);
    glFinish();
    return (double)(dm_now_ns() - t0) / frames;
}

/* Runs one session over the given counters, K frames per pass; fills
 * values[i] (per frame) or NAN with reasons[i] set when unavailable. */
static int measure__session(mscene *m, mconf *c, const char **names, size_t n, int frames,
                            double *values, char **reasons)
{
    counters_session *s = NULL;
    int rc = counters_session_create(m->cc, &s);
    for (size_t i = 0; rc == 0 && i < n; i++)
        rc = counters_enable(s, names[i]);
    int passes = 0;
    if (rc == 0)
        rc = counters_num_passes(s, &passes);
    for (int p = 0; rc == 0 && p < passes; p++) {
        tech_item full = c->item;
        if (counters_pass_minimal_fs(s, p))
            c->item = c->item_min;   /* the raster pass: the same draws, minimal fragment shading */
        if (counters_pass_loop_trips(s, p))
            c->item = c->item_trips;   /* the same draws, the search loop counting its trips */
        rc = counters_pass_begin(s, p);
        if (rc == 0 && c->item.id)   /* the stage passes' frames in their steady state */
            measure__frames(m, c, counters_pass_warm_frames(s, p));
        rc = rc ? rc : counters_sample_begin(s, 0);
        if (rc == 0 && c->item.id)
            measure__frames(m, c, frames);
        c->item = full;
        rc = rc ? rc : counters_sample_end(s);
        rc = rc ? rc : counters_pass_end(s);
    }
    rc = rc ? rc : counters_session_end(s);
    for (size_t i = 0; rc == 0 && i < n; i++) {
        double v = NAN;
        int r = counters_result(s, 0, names[i], &v);
        values[i] = r == 0 ? v / frames : NAN;
        if (r != 0 && reasons && !reasons[i])
            reasons[i] = dm_xstrdup(counters_last_error(s));
        if (r == 0 && strcmp(names[i], "LoopTrips") == 0 && !c->item_trips.id) {
            values[i] = NAN;   /* the pass drew nothing: no count, not 0 */
            if (reasons && !reasons[i])
                reasons[i] = dm_xstrdup("the loop-counting variant of the program could not be built (see log)");
        }
    }
    if (rc != 0)
        dm_str_printf(&c->log, "counters: %s\n", s ? counters_last_error(s) : dm_strerror(rc));
    counters_session_destroy(s);
    return rc;
}

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
        double ns = measure__plain_sample(m, c, f);
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
 * samples_max - 1 are taken, so at least one more is measured here. */
static void measure__restore(mscene *m, mconf *c)
{
    size_t cap = protocol_resume_limit(&m->pd), got = 0;
    long ns = 0;
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

/* Why the stages of item `info` cannot be isolated, or NULL (docs/counters.md,
 * "Stage costs": what isolation changes). */
static const char *measure__isolation_problem(const tech_item_info *info)
{
    if (!info->has_fs)
        return "no fragment stage: nothing to isolate";
    if (info->fs_discards)
        return "the fragment shader can discard: the minimal shader would keep the fragments it drops, "
               "so setup and raster would include their depth and colour writes";
    return NULL;
}

/* Prepares c's configuration again with debug view `view` into *item and
 * draws `frames` frames of it (its JIT outside any sample).  Returns 0, or
 * nonzero with item->id 0 when it cannot be built (the reason in c's log). */
static int measure__prepare_view(mscene *m, mconf *c, tech_debug_view view, int frames, tech_item *item)
{
    tech_renderer_set_debug_view(m->r, view);
    int rc = tech_prepare(m->r, c->pc->params, c->pc->n_params, item, &c->log);
    tech_renderer_set_debug_view(m->r, TECH_DEBUG_NONE);
    if (gl_context_take_messages(m->gl, &c->log) > 0 || rc != 0) {
        item->id = 0;
        return rc ? rc : DM_ERR_GL;
    }
    tech_item full = c->item;
    c->item = *item;
    measure__frames(m, c, frames);
    c->item = full;
    return 0;
}

/* The raster pass's item (MinimalShadingTime): the configuration with the
 * minimal fragment shader, warmed up (its JIT outside the samples); else
 * c->min_why says why there is none. */
static void measure__prepare_minimal(mscene *m, mconf *c)
{
    int wanted = 0;
    for (size_t i = 0; i < m->n_timing; i++)
        wanted |= strcmp(m->timing[i], "MinimalShadingTime") == 0;
    const char *why = wanted ? measure__isolation_problem(&c->info) : NULL;
    if (!wanted || why) {
        c->min_why = why ? dm_xstrdup(why) : NULL;
        return;
    }
    int warm = m->job->sweep->measure.warmup_frames > 0 ? m->job->sweep->measure.warmup_frames : 1;
    if (measure__prepare_view(m, c, TECH_DEBUG_MINIMAL_FS, warm, &c->item_min) != 0)
        c->min_why = dm_xstrdup("the minimal fragment shader cannot be built (see log)");
}

_Static_assert(TECH_LOOP_TRIPS_BINDING == COUNTERS_LOOP_TRIPS_BINDING,
               "the loop-trips shader and the counters library use one binding");

/* The LoopTrips pass's item, when names[0..n) ask for LoopTrips: the
 * configuration with its search loop counting trips, its first frame (the
 * JIT) drawn.  Left 0 when it cannot be built (the log says why): the pass
 * then draws nothing and measure__session makes LoopTrips unavailable. */
static void measure__prepare_trips(mscene *m, mconf *c, const char *const *names, size_t n)
{
    int wanted = 0;
    for (size_t i = 0; i < n; i++)
        wanted |= strcmp(names[i], "LoopTrips") == 0;
    if (!wanted)
        return;
    if (measure__prepare_view(m, c, TECH_DEBUG_LOOP_TRIPS, 1, &c->item_trips) != 0)
        dm_str_cat(&c->log, "LoopTrips: the counting shader cannot be built (above)\n");
}

/* Prepare + warm-up + statistics pass for one configuration. */
static void measure__prepare(mscene *m, mconf *c)
{
    const sweep_measure *sm = &m->job->sweep->measure;
    measure__say(m->job, "B %s", c->pc->key);
    /* Test hook for the watchdog: DMBENCH_TEST_HANG=<technique> blocks this
     * process when it reaches that technique.  (A shader cannot hang
     * llvmpipe: its JIT caps shader loops, so tests hang the process.) */
    const char *hang = getenv("DMBENCH_TEST_HANG");
    if (hang && strcmp(hang, dm_kv_get(c->pc->params, c->pc->n_params, "technique")) == 0)
        for (;;)
            pause();
    int rc = tech_prepare(m->r, c->pc->params, c->pc->n_params, &c->item, &c->log);
    /* compiler warnings and errors of this configuration's programs go to its own log */
    if (gl_context_take_messages(m->gl, &c->log) > 0 && rc == 0) {
        measure__fail(c, "GL error while preparing the configuration (see log)");
        return;
    }
    if (rc != 0) {
        measure__fail(c, rc == DM_ERR_SHADER ? "shader compile or link failed (see log)"
                         : rc == DM_ERR_UNSUPPORTED ? "not supported by this driver (see log)"
                                                    : "could not prepare the configuration (see log)");
        return;
    }
    tech_item_get_info(m->r, c->item, &c->info);
    measure__prepare_minimal(m, c);
    measure__prepare_trips(m, c, m->statistic, m->n_statistic);
    measure__warmup(m, c);
    c->stats = dm_xcalloc(m->n_statistic + 1, sizeof *c->stats);
    c->stats_reason = dm_xcalloc(m->n_statistic + 1, sizeof *c->stats_reason);
    int64_t t0 = dm_now_ns();
    if (m->n_statistic)
        measure__session(m, c, m->statistic, m->n_statistic, 1, c->stats, c->stats_reason);
    c->stats_ns = dm_now_ns() - t0;
    c->timing = dm_xcalloc(m->n_timing + 1, sizeof *c->timing);
    for (size_t i = 0; i < m->n_timing; i++)
        c->timing[i] = dm_xcalloc((size_t)sm->samples_max, sizeof **c->timing);
    c->active = 1;
    measure__restore(m, c);
}

/* Checkpoints the samples of every configuration still sampling, in one
 * transaction after a round: a kill then loses at most the round in flight.
 * Returns 0 or DM_ERR_STORE (message in err). */
static int measure__checkpoint(mscene *m, mconf *cs, size_t n, dm_str *err)
{
    store_partial *items = dm_xcalloc(n + 1, sizeof *items);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (cs[i].active && !cs[i].failed && cs[i].n_samples)
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

/* Takes one timing sample of a configuration and asks the protocol whether
 * it stops; a drifting stop counter is noted in the configuration's log. */
static void measure__timing_sample(mscene *m, mconf *c)
{
    double *vals = dm_xcalloc(m->n_timing + 1, sizeof *vals);
    measure__say(m->job, "B %s", c->pc->key);
    int64_t t0 = dm_now_ns();
    tech_vt_stats v0, v1;
    int vt = tech_item_vt_stats(m->r, c->item, &v0) == 0;
    if (measure__session(m, c, m->timing, m->n_timing, c->frames, vals, NULL) != 0) {
        measure__fail(c, "counter session failed (see log)");
        free(vals);
        return;
    }
    if (vt && tech_item_vt_stats(m->r, c->item, &v1) == 0) {   /* the VT may be shared: its own deltas */
        c->has_vt = 1;
        c->vt.page_misses += v1.page_misses - v0.page_misses;
        c->vt.upload_bytes += v1.upload_bytes - v0.upload_bytes;
        c->vt.pages_resident = v1.pages_resident;
        c->vt.committed_bytes = v1.committed_bytes;
    }
    for (size_t i = 0; i < m->n_timing; i++)
        c->timing[i][c->n_samples] = vals[i];
    c->n_samples++;
    c->sampling_ns += dm_now_ns() - t0;
    free(vals);
    const double *x = m->stop_index >= 0 ? c->timing[m->stop_index] : NULL;
    double elapsed = (double)c->sampling_ns / 1e9;   /* its own samples only, not the round's */
    protocol_decision d = protocol_decide(&m->pd, x, c->n_samples, elapsed);
    if (d.stop == PROTOCOL_CONTINUE)
        return;
    c->active = 0;
    if (d.drifting)
        dm_str_printf(&c->log, "%s drifted %+.1f %% over its %zu samples (a trend, not noise: the "
                      "machine's load or clock changed while sampling)\n", m->timing[m->stop_index],
                      100 * d.drift, c->n_samples);
    dm_log(DM_LOG_DEBUG, "sampling %s: %zu samples, stop: %s, CI ±%.2f %%", c->pc->key, c->n_samples,
           protocol_stop_name(d.stop), 100 * d.ci_rel);
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

static char *measure__img_path(const measure_job *job, const char *name)
{
    return dm_xasprintf("%s/img/%s", job->run_dir, name);
}

/* A virtual texture holds what earlier draws wanted (its cache may be
 * shared with other configurations): draws item at w×h until a frame loads
 * no page (at most MEASURE_VT_CONVERGE_MAX), so what follows — an image,
 * counted frames — sees the pages this view converges to, whatever was
 * drawn before.  Nothing for an item without a virtual texture. */
static void measure__vt_converge(struct tech_renderer *r, tech_item item, int w, int h)
{
    tech_vt_stats vs0, vs1;
    if (tech_item_vt_stats(r, item, &vs0) != 0)
        return;
    for (int f = 0; f < MEASURE_VT_CONVERGE_MAX; f++) {
        tech_draw(r, item, w, h);
        tech_item_vt_stats(r, item, &vs1);
        if (f > 0 && vs1.page_misses == vs0.page_misses)
            break;
        vs0 = vs1;
    }
}

int measure_render_image(struct tech_renderer *r, const dm_kv *params, size_t n_params,
                         int w, int h, int supersample, float **rgba, float **depth, dm_str *log)
{
    tech_item item;
    int rc = tech_prepare(r, params, n_params, &item, log);
    if (rc != 0)
        return rc;
    int ss = supersample > 1 ? supersample : 1;
    target t;
    if ((rc = target_create(&t, w * ss, h * ss)) != 0) {
        dm_str_printf(log, "cannot create a %dx%d render target\n", w * ss, h * ss);
        return rc;
    }
    measure__vt_converge(r, item, w * ss, h * ss);
    tech_draw(r, item, w * ss, h * ss);
    img big = {0}, small = {0};
    img_alloc(&big, w * ss, h * ss);
    float *d = depth ? dm_xmalloc((size_t)w * (size_t)h * ss * ss * sizeof *d) : NULL;
    target_read(&t, big.px, d);
    target_destroy(&t);
    if (ss > 1) {
        img_downsample(&big, ss, &small);
        img_free(&big);
        big = small;
        if (d) {   /* depth: nearest sample of each block's first texel */
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    d[(size_t)y * (size_t)w + (size_t)x] = d[(size_t)(y * ss) * (size_t)(w * ss) + (size_t)(x * ss)];
        }
    }
    *rgba = big.px;
    if (depth)
        *depth = d;
    return 0;
}

/* The reference image of parameters p at c's resolution into m->ref_*:
 * loaded from the reference cache (refcache.h) when an entry for exactly
 * these inputs exists, else rendered and stored there.  The cache is off
 * with the program cache (job->cache_dir NULL). */
static int measure__reference_image(mscene *m, const dm_kv *p, size_t n, mconf *c)
{
    const sweep *s = m->job->sweep;
    int w = c->pc->width, h = c->pc->height;
    const char *renderer = (const char *)glGetString(GL_RENDERER), *version = (const char *)glGetString(GL_VERSION);
    char *driver = dm_xasprintf("%s | %s", renderer ? renderer : "?", version ? version : "?");
    refcache_desc d = {.params = p, .n_params = n, .width = w, .height = h,
                       .supersample = s->supersample, .driver = driver};
    char *dir = m->job->cache_dir ? refcache_dir() : NULL;
    dm_str key = {0};
    int keyed = dir && refcache_key(&d, &key) == 0, rc = 0;
    c->ref_source = "cache";
    if (!keyed || refcache_load(dir, dm_str_get(&key), w, h, &m->ref_rgba, &m->ref_depth) != 0) {
        c->ref_source = "rendered";
        rc = measure_render_image(m->r, p, n, w, h, s->supersample, &m->ref_rgba, &m->ref_depth, &c->log);
        if (rc == 0 && keyed && refcache_store(dir, dm_str_get(&key), w, h, m->ref_rgba, m->ref_depth) != 0)
            dm_log(DM_LOG_WARN, "cannot write the reference cache in %s", dir);
    }
    dm_str_free(&key);
    free(dir);
    free(driver);
    return rc;
}

/* Sets the sweep's quality.reference axis values (e.g. normal_format) over
 * the reference's parameters *p, replacing the scene's or configuration's. */
static void measure__reference_overrides(const sweep *s, dm_kv **p, size_t *n)
{
    for (size_t i = 0; i < s->n_ref_params; i++) {
        const dm_kv *o = &s->ref_params[i];
        size_t k = 0;
        while (k < *n && strcmp((*p)[k].key, o->key) != 0)
            k++;
        if (k == *n) {
            dm_kv_push(p, n, o->key, o->value);
            continue;
        }
        free((*p)[k].value);
        (*p)[k].value = dm_xstrdup(o->value);
    }
}

/* Renders the scene reference once (per process) for configuration c. */
static int measure__reference(mscene *m, mconf *c)
{
    const sweep *s = m->job->sweep;
    int per_config = !s->ref_technique || strcmp(s->ref_technique, "same") == 0;
    if (m->ref_rgba && !per_config)
        return 0;                      /* one reference technique: one image per scene */
    free(m->ref_rgba);
    free(m->ref_depth);
    free(m->ref_path);
    m->ref_rgba = m->ref_depth = NULL;
    m->ref_path = NULL;
    /* The reference technique renders the scene as the sweep defines it
     * (all scene axes, whether this configuration's technique reads them or
     * not); "same" renders the configuration itself. */
    dm_kv *p = NULL;
    size_t n = 0;
    if (per_config) {
        for (size_t i = 0; i < c->pc->n_params; i++)
            dm_kv_push(&p, &n, c->pc->params[i].key, c->pc->params[i].value);
    } else {
        for (size_t i = 0; i < c->pc->n_params; i++)
            if (!dm_kv_get(c->pc->scene_params, c->pc->n_scene_params, c->pc->params[i].key) &&
                strcmp(c->pc->params[i].key, "technique") != 0)
                dm_kv_push(&p, &n, c->pc->params[i].key, c->pc->params[i].value);
        for (size_t i = 0; i < c->pc->n_scene_params; i++)
            dm_kv_push(&p, &n, c->pc->scene_params[i].key, c->pc->scene_params[i].value);
        dm_kv_push(&p, &n, "technique", s->ref_technique);
        /* The ground truth samples plain textures: a virtual-texture
         * configuration is compared with the same maps unpaged, whichever
         * configuration of the scene this process measures first. */
        for (size_t i = 0; i < n; i++)
            if (strcmp(p[i].key, "virtual_texture") == 0) {
                free(p[i].value);
                p[i].value = dm_xstrdup("off");
            }
    }
    measure__reference_overrides(s, &p, &n);
    int rc = measure__reference_image(m, p, n, c);
    dm_kv_free(p, n);
    if (rc == 0) {
        char name[64];
        const char *id = per_config ? c->pc->key : c->pc->scene;
        snprintf(name, sizeof name, "ref-%08llx.png",
                 (unsigned long long)(dm_fnv1a64(id, strlen(id), DM_FNV_SEED) & 0xffffffffULL));
        m->ref_path = dm_xstrdup(name);
        char *path = measure__img_path(m->job, name);
        img im = { c->pc->width, c->pc->height, m->ref_rgba };
        char e[256];
        img_save(&im, path, e, sizeof e);
        free(path);
    }
    return rc;
}

/* FLIP of test against ref at the sweep's pixels per degree, and its map on
 * the fixed [0,1] scale (img/<key>-flip.png).  FLIP fields stay NaN ("not
 * computed") when it cannot be computed. */
static void measure__flip(mscene *m, mconf *c, const img *ref, const img *test, dm_config_result *out)
{
    dm_quality *q = &out->quality;
    q->flip = q->flip_q1 = q->flip_median = q->flip_q3 = q->flip_max = q->flip_ppd = NAN;
    float *map = dm_xmalloc((size_t)ref->w * (size_t)ref->h * sizeof *map);
    flip_desc d = flip_defaults(&(flip_desc){ .ppd = m->job->sweep->flip_ppd });
    flip_stats st;
    if (flip_compare(ref, test, &d, &st, map) == 0) {
        q->flip = st.mean;
        q->flip_q1 = st.q1;
        q->flip_median = st.median;
        q->flip_q3 = st.q3;
        q->flip_max = st.max;
        q->flip_ppd = d.ppd;
        char e[256], name[64];
        snprintf(name, sizeof name, "%s-flip.png", c->pc->key);
        char *path = measure__img_path(m->job, name);
        if (flip_map_save(map, ref->w, ref->h, path, e, sizeof e) == 0)
            out->img_flip = dm_xasprintf("img/%s", name);
        free(path);
    }
    free(map);
}

/* Image, quality and heatmap of a configuration against the scene reference. */
static void measure__quality(mscene *m, mconf *c, dm_config_result *out)
{
    int w = c->pc->width, h = c->pc->height;
    float *rgba = NULL, *depth = NULL;
    if (measure_render_image(m->r, c->pc->params, c->pc->n_params, w, h, 1, &rgba, &depth, &c->log) != 0)
        return;
    img test = { w, h, rgba };
    char e[256], name[64];
    snprintf(name, sizeof name, "%s.png", c->pc->key);
    char *path = measure__img_path(m->job, name);
    if (img_save(&test, path, e, sizeof e) == 0)
        out->img_render = dm_xasprintf("img/%s", name);
    free(path);
    if (measure__reference(m, c) == 0) {
        img ref = { w, h, m->ref_rgba };
        img_metrics mt;
        dm_quality *q = &out->quality;
        if (img_compare(&ref, &test, 0.05, &mt) == 0) {
            q->present = 1;
            q->rmse = mt.rmse;
            q->psnr = mt.psnr;
            q->max_error = mt.max_error;
            q->pct_over_threshold = mt.pct_over;
        }
        quality_ssim(&ref, &test, &q->ssim);
        measure__flip(m, c, &ref, &test, out);
        size_t np = (size_t)w * (size_t)h;
        unsigned char *ma = dm_xmalloc(np), *mb = dm_xmalloc(np);
        quality_coverage(&ref, ma);
        quality_coverage(&test, mb);
        q->silhouette_error = quality_silhouette_error(ma, mb, np);
        quality_depth_rmse(m->ref_depth, depth, ma, mb, np, &q->depth_rmse);
        q->crack_pixels = quality_crack_pixels(mb, w, h);
        q->nonfinite_pixels = quality_nonfinite_pixels(&test);
        const sweep *sw = m->job->sweep;
        const char *rt = sw->ref_technique;
        dm_str over = {0};
        for (size_t i = 0; i < sw->n_ref_params; i++)
            dm_str_printf(&over, "%s%s=%s", i ? " " : " (", sw->ref_params[i].key, sw->ref_params[i].value);
        q->reference = dm_xasprintf("%s%s%s, %dx supersampled",
                                    !rt || strcmp(rt, "same") == 0 ? "same configuration" : rt,
                                    dm_str_get(&over), sw->n_ref_params ? ")" : "", sw->supersample);
        dm_str_free(&over);
        free(ma);
        free(mb);
        snprintf(name, sizeof name, "%s-diff.png", c->pc->key);
        path = measure__img_path(m->job, name);
        /* one absolute scale for every map: a channel difference of 1 (the
         * whole range) is the colour map's top, so maps compare side by side */
        if (img_heatmap(&ref, &test, 1.0, path, e, sizeof e) == 0)
            out->img_heatmap = dm_xasprintf("img/%s", name);
        free(path);
        out->img_reference = dm_xasprintf("img/%s", m->ref_path);
    }
    free(rgba);
    free(depth);
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
    if (!c->failed) {
        int64_t t0 = dm_now_ns();
        measure__collect(m, c, &out);
        measure__quality(m, c, &out);
        c->quality_ns = dm_now_ns() - t0;
    }
    dm_log(DM_LOG_DEBUG, "measure %s: setup %.1f ms, warm-up %.1f ms, statistics %.1f ms, sampling %.1f ms, "
           "images+quality %.1f ms (reference %s)", c->pc->key, c->info.setup_ns / 1e6, c->warmup_ns / 1e6,
           c->stats_ns / 1e6, c->sampling_ns / 1e6, c->quality_ns / 1e6, c->ref_source ? c->ref_source : "reused");
    dm_str glmsg = {0};
    if (gl_context_take_messages(m->gl, &glmsg) + gl_context_check_errors(&glmsg) > 0)
        measure__fail(c, "GL error during the configuration (see log)");
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
        measure__say(m->job, "C %s", dm_str_get(&changed));
        dm_str_cat(err, dm_str_get(&changed));
        dm_str_free(&changed);
        dm_config_result_free(&out);
        return DM_ERR_ARG;
    }
    int rc = store_config_put(m->st, m->job->run_id, &out);
    const dm_counter_result *wt = m->stop_index >= 0 ? dm_config_counter(&out, m->timing[m->stop_index]) : NULL;
    double ci = wt && wt->median > 0 ? (wt->ci_hi - wt->ci_lo) / 2 / wt->median : NAN;
    if (rc == 0)
        measure__say(m->job, "D %s %s %.0f %.4f %lld", c->pc->key, out.ok ? "ok" : "failed",
                     wt ? wt->median : NAN, ci, (long long)c->sampling_ns);
    else
        dm_str_printf(err, "cannot save configuration %s: %s", c->pc->key,
                      store_last_error(m->st));
    dm_config_result_free(&out);
    return rc == 0 ? 0 : DM_ERR_STORE;
}

static int measure__setup(mscene *m, dm_str *err)
{
    int rc = gl_context_create(NULL, &m->gl, err);
    rc = rc ? rc : tech_renderer_create(&m->r);
    if (rc == 0 && m->job->cache_dir && dm_mkdirs(m->job->cache_dir) == 0 &&
        tech_renderer_set_cache_dir(m->r, m->job->cache_dir) != 0)
        dm_log(DM_LOG_DEBUG, "program binaries cannot be cached on this driver");
    rc = rc ? rc : counters_context_create(&m->cc);
    /* DMBENCH_HIDE_EXTENSIONS=GL_A,GL_B makes the counters behave as on a
     * driver without them, so "unavailable" can be tested end to end. */
    const char *hide = getenv("DMBENCH_HIDE_EXTENSIONS");
    if (rc == 0 && hide) {
        char *copy = dm_xstrdup(hide), *save = NULL;
        for (char *t = strtok_r(copy, ",", &save); t; t = strtok_r(NULL, ",", &save))
            counters_context_hide_extension(m->cc, t);
        free(copy);
    }
    rc = rc ? rc : store_open(m->job->store_path, &m->st, err);
    protocol_desc_from_measure(&m->pd, &m->job->sweep->measure, m->job->seed);
    if (rc == 0)
        measure__classify(m);
    else if (!err->len)
        dm_str_printf(err, "cannot set up the measuring process: %s", dm_strerror(rc));
    return rc;
}

static void measure__teardown(mscene *m, mconf *cs, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(cs[i].reason);
        free(cs[i].min_why);
        dm_str_free(&cs[i].log);
        for (size_t k = 0; cs[i].timing && k < m->n_timing; k++)
            free(cs[i].timing[k]);
        free(cs[i].timing);
        free(cs[i].stats);
        for (size_t k = 0; cs[i].stats_reason && k < m->n_statistic; k++)
            free(cs[i].stats_reason[k]);
        free(cs[i].stats_reason);
    }
    free(cs);
    free(m->timing);
    free(m->statistic);
    free(m->ref_rgba);
    free(m->ref_depth);
    free(m->ref_path);
    if (m->gl)
        target_destroy(&m->rt);
    store_close(m->st);
    counters_context_destroy(m->cc);
    tech_renderer_destroy(m->r);
    gl_context_destroy(m->gl);
}

int measure_pilot(const measure_job *job, dm_str *err)
{
    mscene m = { .job = job };
    int rc = measure__setup(&m, err);
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        mconf *c = &cs[i];
        c->pc = &job->configs[i];
        measure__say(job, "B %s", c->pc->key);
        double ns = NAN, counts[PREDICT_N_COUNTS];
        for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
            counts[k] = NAN;
        if (tech_prepare(m.r, c->pc->params, c->pc->n_params, &c->item, &c->log) == 0) {
            measure__frames(&m, c, 2);             /* JIT and first-use costs */
            ns = measure__plain_sample(&m, c, 1);
            measure__prepare_trips(&m, c, predict_counts, PREDICT_N_COUNTS);
            /* and its invocation counts, for a prediction from the
             * instruction models (run --budget) */
            measure__session(&m, c, (const char **)predict_counts, PREDICT_N_COUNTS, 1, counts, NULL);
        }
        gl_context_take_messages(m.gl, NULL);
        dm_str line = {0};
        dm_str_printf(&line, "P %s %.0f", c->pc->key, ns);
        for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
            dm_str_printf(&line, " %.17g", counts[k]);
        measure__say(job, "%s", dm_str_get(&line));
        dm_str_free(&line);
    }
    measure__teardown(&m, cs, rc == 0 ? job->n_configs : 0);
    return rc;
}

/* The counted window of one configuration: collection switched on around
 * `frames` frames and the glFinish that ends them (so the rasteriser's work,
 * on the calling thread with LP_NUM_THREADS=0, is inside), then one dump
 * per sample named "KEY.S" (window CALLGRIND_FULL), "KEY.g.S" (the same
 * frames with GL_RASTERIZER_DISCARD), "KEY.r.S" (c->item is then the
 * minimal-fragment-shader item) or "KEY.m.S" (that item with discard).
 * Setup, JIT compilation and `warm` warm-up frames happen before, with
 * collection off.  Every sample is kept: the parent leaves the allocator's
 * instructions out, and what remains is equal from the first sample on
 * (docs/counters.md, "Repeatability").  Returns the nanoseconds of the
 * warm-up in *warm_ns and of the samples in *count_ns
 * (bench/instructions_split.sh). */
static void measure__counted_samples(mscene *m, mconf *c, callgrind_window w, int warm, int frames,
                                     int samples, int64_t *warm_ns, int64_t *count_ns)
{
    static const char *const tag[CALLGRIND_WINDOWS] = {"", ".g", ".r", ".m"};
    int64_t t0 = dm_now_ns(), t1 = t0;
    measure__frames(m, c, warm > 0 ? warm : 1);
    measure__vt_converge(m->r, c->item, c->pc->width, c->pc->height);   /* no page generation counted */
    if (w == CALLGRIND_GEOMETRY || w == CALLGRIND_RESIDUAL)
        glEnable(GL_RASTERIZER_DISCARD);
    t1 = dm_now_ns();
    for (int s = 0; s < samples; s++) {
        char name[40];
        snprintf(name, sizeof name, "%s%s.%d", c->pc->key, tag[w], s);
        glFinish();
        CALLGRIND_TOGGLE_COLLECT;
        measure__frames(m, c, frames);
        glFinish();
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(name);
    }
    glDisable(GL_RASTERIZER_DISCARD);
    *warm_ns = t1 - t0;
    *count_ns = dm_now_ns() - t1;
}

/* The stage windows of a prepared, counted configuration (geometry with
 * rasterizer discard, raster with the minimal fragment shader, and the
 * minimal shader with discard for the residual), reported
 * as "S KEY ok" or "S KEY unavailable REASON". */
static void measure__stage_windows(mscene *m, mconf *c, int frames, int samples)
{
    tech_item_info info = {0};
    tech_item_get_info(m->r, c->item, &info);
    const char *why = measure__isolation_problem(&info);
    if (why) {
        measure__say(m->job, "S %s unavailable %s", c->pc->key, why);
        return;
    }
    int64_t warm_ns = 0, count_ns = 0;
    measure__counted_samples(m, c, CALLGRIND_GEOMETRY, 1, frames, samples, &warm_ns, &count_ns);
    tech_item full = c->item, minimal = {0};
    dm_str log = {0};
    tech_renderer_set_debug_view(m->r, TECH_DEBUG_MINIMAL_FS);
    int rc = tech_prepare(m->r, c->pc->params, c->pc->n_params, &minimal, &log);
    tech_renderer_set_debug_view(m->r, TECH_DEBUG_NONE);
    if (gl_context_take_messages(m->gl, &log) > 0 || rc != 0) {
        for (char *nl = strchr(log.buf ? log.buf : "", '\n'); nl; nl = strchr(nl, '\n'))
            *nl = ' ';   /* one protocol line */
        measure__say(m->job, "S %s unavailable the minimal fragment shader cannot be built: %s", c->pc->key,
                     log.len ? dm_str_get(&log) : dm_strerror(rc));
        dm_str_free(&log);
        return;
    }
    dm_str_free(&log);
    c->item = minimal;
    measure__counted_samples(m, c, CALLGRIND_RASTER, 1, frames, samples, &warm_ns, &count_ns);
    measure__counted_samples(m, c, CALLGRIND_RESIDUAL, 1, frames, samples, &warm_ns, &count_ns);
    c->item = full;
    tech_release(m->r, minimal);
    measure__say(m->job, "S %s ok", c->pc->key);
}

/* Counts configuration c (prepare, warm-up, samples, stage windows) and
 * says "I KEY ok" or "I KEY failed REASON". */
static void measure__count_one(mscene *m, mconf *c, int frames, int samples, int stages)
{
    const measure_job *job = m->job;
    int64_t tp = dm_now_ns(), warm_ns = 0, count_ns = 0;
    int prc = tech_prepare(m->r, c->pc->params, c->pc->n_params, &c->item, &c->log);
    int64_t prep_ns = dm_now_ns() - tp;
    if (gl_context_take_messages(m->gl, &c->log) > 0 || prc != 0) {
        measure__say(job, "I %s failed %s", c->pc->key, prc == 0 ? "GL error while preparing" : dm_strerror(prc));
        return;
    }
    measure__counted_samples(m, c, CALLGRIND_FULL, CALLGRIND_WARMUP_FRAMES, frames, samples, &warm_ns, &count_ns);
    fprintf(stderr, "instructions split: %s prepare %.1f ms, warm-up %.1f ms, counted %.1f ms\n", c->pc->key,
            (double)prep_ns / 1e6, (double)warm_ns / 1e6, (double)count_ns / 1e6);
    if (stages) {
        int64_t ts = dm_now_ns();
        measure__stage_windows(m, c, frames, samples);
        fprintf(stderr, "instructions split: %s stage windows %.1f ms\n", c->pc->key,
                (double)(dm_now_ns() - ts) / 1e6);
    }
    int bad = gl_context_check_errors(&c->log) > 0;
    measure__say(job, "I %s %s", c->pc->key, bad ? "failed GL error in the counted frames" : "ok");
}

int measure_instructions(const measure_job *job, int frames, int samples, dm_str *err)
{
    mscene m = { .job = job };
    int64_t t0 = dm_now_ns();
    int stages = callgrind_wants_stages(&job->sweep->measure);
    int rc = gl_context_create(NULL, &m.gl, err);
    rc = rc ? rc : tech_renderer_create(&m.r);
    /* where the child's time goes, in its log (bench/instructions_split.sh) */
    fprintf(stderr, "instructions split: context %.1f ms\n", (double)(dm_now_ns() - t0) / 1e6);
    if (rc == 0 && !RUNNING_ON_VALGRIND)
        dm_log(DM_LOG_WARN, "measure_instructions: not running under Valgrind; nothing is counted");
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        mconf *c = &cs[i];
        c->pc = &job->configs[i];
        measure__say(job, "B %s", c->pc->key);
        if (i > 0) {
            /* Every configuration in a fresh GL context: what the driver
             * keeps per context (state caches, sampler views, upload
             * buffers, the hash tables of GL names) would otherwise carry
             * what earlier configurations left, and a count would depend on
             * which ones ran before it (docs/counters.md, "Repeatability"). */
            target_destroy(&m.rt);
            tech_renderer_destroy(m.r);
            m.r = NULL;
            if (gl_context_renew(m.gl) != 0 || tech_renderer_create(&m.r) != 0) {
                measure__say(job, "I %s failed cannot create a fresh GL context", c->pc->key);
                rc = DM_ERR_GL;
                break;
            }
        }
        measure__count_one(&m, c, frames, samples, stages);
    }
    for (size_t i = 0; i < job->n_configs; i++)
        dm_str_free(&cs[i].log);
    free(cs);
    if (m.gl)
        target_destroy(&m.rt);
    tech_renderer_destroy(m.r);
    gl_context_destroy(m.gl);
    return rc;
}

int measure_counts(const plan_config *cs, size_t n, const char *const *names, size_t n_names, double *values,
                   dm_str *err)
{
    sweep none = {0};
    measure_job job = { .sweep = &none, .configs = cs, .n_configs = n, .report_fd = -1 };
    mscene m = { .job = &job };
    int rc = gl_context_create(NULL, &m.gl, err);
    rc = rc ? rc : tech_renderer_create(&m.r);
    rc = rc ? rc : counters_context_create(&m.cc);
    for (size_t i = 0; i < n * n_names; i++)
        values[i] = NAN;
    for (size_t i = 0; rc == 0 && i < n; i++) {
        mconf c = { .pc = &cs[i] };
        if (tech_prepare(m.r, cs[i].params, cs[i].n_params, &c.item, &c.log) == 0) {
            measure__frames(&m, &c, 1);   /* first use (JIT) outside the counted frame */
            measure__prepare_trips(&m, &c, names, n_names);
            measure__vt_converge(m.r, c.item, cs[i].width, cs[i].height);
            measure__session(&m, &c, (const char **)names, n_names, 1, values + i * n_names, NULL);
            tech_release(m.r, c.item);
            if (c.item_trips.id)
                tech_release(m.r, c.item_trips);
        }
        gl_context_take_messages(m.gl, NULL);
        dm_str_free(&c.log);
    }
    if (m.gl)
        target_destroy(&m.rt);
    counters_context_destroy(m.cc);
    tech_renderer_destroy(m.r);
    gl_context_destroy(m.gl);
    return rc;
}

int measure_scene(const measure_job *job, dm_str *err)
{
    mscene m = { .job = job };
    int rc = measure__setup(&m, err), set_up = rc == 0;
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        cs[i].pc = &job->configs[i];
        measure__prepare(&m, &cs[i]);
        if (cs[i].failed)
            rc = measure__commit(&m, &cs[i], err);
    }
    size_t *order = dm_xcalloc(job->n_configs + 1, sizeof *order);
    for (uint64_t round = 0, active = 1; rc == 0 && active; round++) {
        active = 0;
        plan_shuffle(order, job->n_configs, job->seed + round);
        for (size_t k = 0; k < job->n_configs; k++) {
            mconf *c = &cs[order[k]];
            if (!c->active)
                continue;
            measure__timing_sample(&m, c);
            if (!c->active)
                rc = measure__commit(&m, c, err);
            else
                active = 1;
            if (rc != 0)
                break;
        }
        if (rc == 0 && active)
            rc = measure__checkpoint(&m, cs, job->n_configs, err);
    }
    free(order);
    measure__teardown(&m, cs, set_up ? job->n_configs : 0);
    return rc;
}
