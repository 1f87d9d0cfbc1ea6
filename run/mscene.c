/* mscene.c — one measuring process's scene state and the drawing, counter
 * and image operations every kind of measuring shares (see mscene.h). */
#include "run/mscene.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "imaging/image.h"

/* Draws at most this many frames to converge a virtual texture before an image. */
#define MSCENE_VT_CONVERGE_MAX 64

void mscene_say(const measure_job *job, const char *fmt, ...)
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
static void mscene__classify(mscene *m)
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
            ci->backend == COUNTERS_BACKEND_SHADER_COUNT || ci->backend == COUNTERS_BACKEND_PER_CALL)
            m->statistic[m->n_statistic++] = ci->name;
        else if (ci->backend == COUNTERS_BACKEND_CLOCK || ci->backend == COUNTERS_BACKEND_TIMER_QUERY) {
            if (ci->stops_sampling && m->stop_index < 0)
                m->stop_index = (int)m->n_timing;
            m->timing[m->n_timing++] = ci->name;
        }
    }
}

/* 1 when counter `name` is counted by the instrumented shader of the
 * loop-trips pass (LoopTrips, FragmentGroups). */
static int mscene__shader_counted(const char *name)
{
    const counters_info *ci = counters_find(name);
    return ci && ci->backend == COUNTERS_BACKEND_SHADER_COUNT;
}

void mscene_fail(mconf *c, const char *reason)
{
    if (c->failed)
        return;
    c->failed = 1;
    c->active = 0;
    c->reason = dm_xstrdup(reason);
}

/* Binds the scene's target at c's size (made or resized on first use;
 * rebound because image renders use their own).  Returns 0, or -1 with the
 * reason in c's log. */
static int mscene__bind_target(mscene *m, mconf *c)
{
    if (m->rt.w != c->pc->width || m->rt.h != c->pc->height) {
        target_destroy(&m->rt);
        if (target_create(&m->rt, c->pc->width, c->pc->height) != 0) {
            dm_str_printf(&c->log, "cannot create a %dx%d render target\n", c->pc->width, c->pc->height);
            return -1;
        }
    }
    target_bind(&m->rt);
    return 0;
}

/* Draws `frames` frames of one item into the scene's target. */
void mscene_frames(mscene *m, mconf *c, int frames)
{
    if (mscene__bind_target(m, c) != 0)
        return;
    for (int f = 0; f < frames; f++) {
        render_set_frame(m->r, c->item, (uint64_t)f);   /* orbits: frame f of every sample */
        render_draw(m->r, c->item, c->pc->width, c->pc->height);
    }
}

void mscene_frame_at(mscene *m, mconf *c, int frame)
{
    if (mscene__bind_target(m, c) != 0)
        return;
    render_set_frame(m->r, c->item, (uint64_t)frame);
    render_draw(m->r, c->item, c->pc->width, c->pc->height);
}

/* Draws frames 0..frames-1 of c's item, each finished (glFinish) and timed
 * on its own with the clock WallTime reads, into c->frame_ns: a path's
 * frames are not spilled into one another. */
static void mscene__frames_timed(mscene *m, mconf *c, int frames)
{
    if (mscene__bind_target(m, c) != 0)
        return;
    for (int f = 0; f < frames; f++) {
        int64_t t0 = dm_now_ns();
        render_set_frame(m->r, c->item, (uint64_t)f);
        render_draw(m->r, c->item, c->pc->width, c->pc->height);
        glFinish();
        c->frame_ns[f] = (double)(dm_now_ns() - t0);
    }
}

/* One fenced sample of K frames without a counter session: wall ns/frame. */
double mscene_plain_sample(mscene *m, mconf *c, int frames)
{
    glFinish();
    int64_t t0 = dm_now_ns();
    mscene_frames(m, c, frames);
    glFinish();
    return (double)(dm_now_ns() - t0) / frames;
}

/* 1 when counter `name` is counted around each draw call in a pass of
 * its own (TessWalkCalls), not by a session over the frame. */
static int mscene__per_call(const char *name)
{
    const counters_info *ci = counters_find(name);
    return ci && ci->backend == COUNTERS_BACKEND_PER_CALL;
}

/* The per-call session of mscene__call_counts: each draw call of patches
 * one sample, numbered by the call; the first error is kept. */
typedef struct mscene__calls { counters_session *s; int rc; size_t n; } mscene__calls;

static void mscene__call_hook(void *user, size_t call, int begin)
{
    mscene__calls *k = user;
    if (k->rc)
        return;
    k->rc = begin ? counters_sample_begin(k->s, (uint32_t)call) : counters_sample_end(k->s);
    k->n = call + 1;
}

/* Counts counters_tess_walk_inputs around each draw call of one frame of
 * c's item (a statistics session of its own, render_set_call_hook) into
 * *calls (malloc'd, COUNTERS_TESS_WALK_N per call, *n calls).  Returns 0,
 * or nonzero with the reason in *why (malloc'd). */
static int mscene__call_counts(mscene *m, mconf *c, double **calls, size_t *n, char **why)
{
    mscene__calls k = {0};
    int passes = 0, rc = counters_session_create(m->cc, &k.s);
    for (size_t j = 0; rc == 0 && j < COUNTERS_TESS_WALK_N; j++)
        rc = counters_enable(k.s, counters_tess_walk_inputs[j]);
    rc = rc ? rc : counters_num_passes(k.s, &passes);
    rc = rc ? rc : passes == 1 ? counters_pass_begin(k.s, 0) : DM_ERR_UNAVAILABLE;
    if (rc == 0) {
        render_set_call_hook(m->r, mscene__call_hook, &k);
        mscene_frames(m, c, 1);
        render_set_call_hook(m->r, NULL, NULL);
        rc = k.rc ? k.rc : counters_pass_end(k.s);
    }
    rc = rc ? rc : counters_session_end(k.s);
    *n = rc == 0 ? k.n : 0;
    *calls = dm_xcalloc(*n * COUNTERS_TESS_WALK_N + 1, sizeof **calls);
    for (size_t i = 0; rc == 0 && i < *n * COUNTERS_TESS_WALK_N; i++)
        rc = counters_result(k.s, (uint32_t)(i / COUNTERS_TESS_WALK_N),
                             counters_tess_walk_inputs[i % COUNTERS_TESS_WALK_N], &(*calls)[i]);
    if (rc == 0 && *n == 0)
        *why = dm_xstrdup("the frame drew no patches");
    else if (rc)
        *why = dm_xasprintf("the per-call statistics pass failed: %s",
                            k.s && counters_last_error(k.s)[0] ? counters_last_error(k.s) : dm_strerror(rc));
    counters_session_destroy(k.s);
    return rc ? rc : *n ? 0 : DM_ERR_UNAVAILABLE;
}

/* Why c's frame cannot have TessWalkCalls (malloc'd), or NULL; *one is
 * set when the frame is one draw call of patches (render_patch_calls;
 * lod: object-* draws each object apart). */
static char *mscene__walk_problem(mscene *m, const mconf *c, int *one)
{
    size_t patches = 0, per_call = 0;
    dm_str log = {0};
    int rc = render_patch_calls(c->pc->params, c->pc->n_params, &patches, &per_call, &log);
    char *why = rc == DM_ERR_ARG ? dm_xstrdup("the technique does not tessellate: no draw call of patches")
                : rc ? dm_xasprintf("its draw calls cannot be told: %s", dm_str_get(&log)) : NULL;
    dm_str_free(&log);
    for (size_t j = 0; !why && j < COUNTERS_TESS_WALK_N; j++) {
        const char *r = NULL;
        if (!counters_available(m->cc, counters_tess_walk_inputs[j], &r))
            why = dm_xasprintf("%s unavailable: %s", counters_tess_walk_inputs[j], r ? r : "on this driver");
    }
    const char *lod = dm_kv_get(c->pc->params, c->pc->n_params, "lod");
    *one = per_call >= patches && !(lod && strncmp(lod, "object-", 7) == 0);
    return why;
}

/* TessWalkCalls of c's frame (counters.h, counters_tess_walk), NaN with
 * *why (malloc'd) when unavailable.  A frame drawn in one call takes the
 * frame's own counts when names[0..n) counted them into values, with no
 * extra pass; otherwise one frame is drawn with each call counted apart
 * (its per-call counts go to c's log). */
static double mscene__tess_walk(mscene *m, mconf *c, const char **names, size_t n, const double *values,
                                char **why)
{
    int one = 0;
    if ((*why = mscene__walk_problem(m, c, &one)) != NULL)
        return NAN;
    double frame[COUNTERS_TESS_WALK_N];
    size_t found = 0;
    for (size_t j = 0; one && j < COUNTERS_TESS_WALK_N; j++)
        for (size_t i = 0; i < n; i++)
            if (strcmp(names[i], counters_tess_walk_inputs[j]) == 0 && isfinite(values[i])) {
                frame[j] = values[i];
                found++;
                break;
            }
    if (found == COUNTERS_TESS_WALK_N)
        return counters_tess_walk(frame, 1);
    double *calls = NULL;
    size_t nc = 0;
    double walk = mscene__call_counts(m, c, &calls, &nc, why) == 0 ? counters_tess_walk(calls, nc) : NAN;
    if (isfinite(walk)) {
        dm_str_printf(&c->log, "TessWalkCalls: %zu draw calls (TESInvocations, ClippingInputPrimitives, "
                      "ClippingOutputPrimitives):", nc);
        for (size_t k = 0; k < nc; k++)
            dm_str_printf(&c->log, " (%.0f, %.0f, %.0f)", calls[3 * k], calls[3 * k + 1], calls[3 * k + 2]);
        dm_str_cat(&c->log, "\n");
    }
    free(calls);
    return walk;
}

/* Runs one session over the given counters, K frames per pass; fills
 * values[i] (per frame) or NAN with reasons[i] set when unavailable.  A
 * per-call counter (TessWalkCalls) is counted after the session, in a
 * pass of its own (mscene__tess_walk). */
int mscene_session(mscene *m, mconf *c, const char **names, size_t n, int frames,
                            double *values, char **reasons)
{
    counters_session *s = NULL;
    int rc = counters_session_create(m->cc, &s);
    for (size_t i = 0; rc == 0 && i < n; i++)
        rc = mscene__per_call(names[i]) ? 0 : counters_enable(s, names[i]);
    int passes = 0;
    if (rc == 0)
        rc = counters_num_passes(s, &passes);
    for (int f = 0; c->frame_ns && f < frames; f++)
        c->frame_ns[f] = NAN;
    for (int p = 0; rc == 0 && p < passes; p++) {
        render_item full = c->item;
        if (counters_pass_minimal_fs(s, p))
            c->item = c->item_min;   /* the raster pass: the same draws, minimal fragment shading */
        if (counters_pass_loop_trips(s, p))
            c->item = c->item_trips;   /* the same draws, the search loop counting its trips */
        rc = counters_pass_begin(s, p);
        if (rc == 0 && c->item.id)   /* the stage passes' frames in their steady state */
            mscene_frames(m, c, counters_pass_warm_frames(s, p));
        rc = rc ? rc : counters_sample_begin(s, 0);
        int timed = c->frame_ns && strcmp(counters_pass_name(s, p), "timing") == 0;
        if (rc == 0 && c->item.id)
            (timed ? mscene__frames_timed : mscene_frames)(m, c, frames);
        c->item = full;
        rc = rc ? rc : counters_sample_end(s);
        rc = rc ? rc : counters_pass_end(s);
    }
    rc = rc ? rc : counters_session_end(s);
    for (size_t i = 0; rc == 0 && i < n; i++) {
        double v = NAN;
        if (mscene__per_call(names[i]))
            continue;
        int r = counters_result(s, 0, names[i], &v);
        values[i] = r == 0 ? v / frames : NAN;
        if (r != 0 && reasons && !reasons[i])
            reasons[i] = dm_xstrdup(counters_last_error(s));
        if (r == 0 && mscene__shader_counted(names[i]) && !c->item_trips.id) {
            values[i] = NAN;   /* the pass drew nothing: no count, not 0 */
            if (reasons && !reasons[i])
                reasons[i] = dm_xstrdup("the loop-counting variant of the program could not be built (see log)");
        }
    }
    if (rc != 0)
        dm_str_printf(&c->log, "counters: %s\n", s ? counters_last_error(s) : dm_strerror(rc));
    counters_session_destroy(s);
    for (size_t i = 0; rc == 0 && i < n; i++) {
        char *why = NULL;
        if (!mscene__per_call(names[i]))
            continue;
        values[i] = mscene__tess_walk(m, c, names, n, values, &why);
        if (why && reasons && !reasons[i])
            reasons[i] = why;
        else
            free(why);
    }
    return rc;
}

/* Why the stages of item `info` cannot be isolated, or NULL (docs/counters.md,
 * "Stage costs": what isolation changes). */
const char *mscene_isolation_problem(const render_item_info *info)
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
static int mscene__prepare_view(mscene *m, mconf *c, render_debug_view view, int frames, render_item *item)
{
    render_set_debug_view(m->r, view);
    int rc = render_prepare(m->r, c->pc->params, c->pc->n_params, item, &c->log);
    render_set_debug_view(m->r, RENDER_DEBUG_NONE);
    if (gl_context_take_messages(m->gl, &c->log) > 0 || rc != 0) {
        item->id = 0;
        return rc ? rc : DM_ERR_GL;
    }
    render_item full = c->item;
    c->item = *item;
    mscene_frames(m, c, frames);
    c->item = full;
    return 0;
}

/* The raster pass's item (MinimalShadingTime): the configuration with the
 * minimal fragment shader, warmed up (its JIT outside the samples); else
 * c->min_why says why there is none. */
void mscene_prepare_minimal(mscene *m, mconf *c)
{
    int wanted = 0;
    for (size_t i = 0; i < m->n_timing; i++)
        wanted |= strcmp(m->timing[i], "MinimalShadingTime") == 0;
    const char *why = wanted ? mscene_isolation_problem(&c->info) : NULL;
    if (!wanted || why) {
        c->min_why = why ? dm_xstrdup(why) : NULL;
        return;
    }
    int warm = m->job->sweep->measure.warmup_frames > 0 ? m->job->sweep->measure.warmup_frames : 1;
    if (mscene__prepare_view(m, c, RENDER_DEBUG_MINIMAL_FS, warm, &c->item_min) != 0)
        c->min_why = dm_xstrdup("the minimal fragment shader cannot be built (see log)");
}

_Static_assert(RENDER_LOOP_TRIPS_BINDING == COUNTERS_LOOP_TRIPS_BINDING,
               "the loop-trips shader and the counters library use one binding");

/* The LoopTrips pass's item, when names[0..n) ask for LoopTrips or
 * FragmentGroups: the configuration with its shader counting its SIMD
 * groups and their trips of the search loop, its first frame (the JIT)
 * drawn.  Left 0 when it cannot be built (the log says why): the pass then
 * draws nothing and mscene_session makes both unavailable. */
void mscene_prepare_trips(mscene *m, mconf *c, const char *const *names, size_t n)
{
    int wanted = 0;
    for (size_t i = 0; i < n; i++)
        wanted |= mscene__shader_counted(names[i]);
    if (!wanted)
        return;
    if (mscene__prepare_view(m, c, RENDER_DEBUG_LOOP_TRIPS, 1, &c->item_trips) != 0)
        dm_str_cat(&c->log, "LoopTrips, FragmentGroups: the counting shader cannot be built (above)\n");
}

char *mscene_img_path(const measure_job *job, const char *name)
{
    return dm_xasprintf("%s/img/%s", job->run_dir, name);
}

/* A virtual texture holds what earlier draws wanted (its cache may be
 * shared with other configurations): draws item at w×h until a frame loads
 * no page (at most MSCENE_VT_CONVERGE_MAX), so what follows — an image,
 * counted frames — sees the pages this view converges to, whatever was
 * drawn before.  Nothing for an item without a virtual texture. */
void mscene_vt_converge(struct render_ctx *r, render_item item, int w, int h)
{
    render_vt_stats vs0, vs1;
    if (render_get_vt_stats(r, item, &vs0) != 0)
        return;
    for (int f = 0; f < MSCENE_VT_CONVERGE_MAX; f++) {
        render_draw(r, item, w, h);
        render_get_vt_stats(r, item, &vs1);
        if (f > 0 && vs1.page_misses == vs0.page_misses)
            break;
        vs0 = vs1;
    }
}

int mscene_render_image(struct render_ctx *r, const dm_kv *params, size_t n_params,
                         int w, int h, int supersample, float **rgba, float **depth, dm_str *log)
{
    return mscene_render_frame(r, params, n_params, w, h, supersample, 0, rgba, depth, log);
}

int mscene_render_frame(struct render_ctx *r, const dm_kv *params, size_t n_params, int w, int h,
                        int supersample, uint64_t frame, float **rgba, float **depth, dm_str *log)
{
    render_item item;
    int rc = render_prepare(r, params, n_params, &item, log);
    if (rc != 0)
        return rc;
    render_set_frame(r, item, frame);
    int ss = supersample > 1 ? supersample : 1;
    target t;
    if ((rc = target_create(&t, w * ss, h * ss)) != 0) {
        dm_str_printf(log, "cannot create a %dx%d render target\n", w * ss, h * ss);
        return rc;
    }
    mscene_vt_converge(r, item, w * ss, h * ss);
    render_draw(r, item, w * ss, h * ss);
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

int mscene_setup(mscene *m, dm_str *err)
{
    int rc = gl_context_create(NULL, &m->gl, err);
    rc = rc ? rc : render_create(&m->r);
    if (rc == 0 && m->job->cache_dir && dm_mkdirs(m->job->cache_dir) == 0 &&
        render_set_cache_dir(m->r, m->job->cache_dir) != 0)
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
        mscene__classify(m);
    else if (!err->len)
        dm_str_printf(err, "cannot set up the measuring process: %s", dm_strerror(rc));
    return rc;
}

void mscene_teardown(mscene *m, mconf *cs, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(cs[i].reason);
        free(cs[i].min_why);
        dm_str_free(&cs[i].log);
        for (size_t k = 0; cs[i].timing && k < m->n_timing; k++)
            free(cs[i].timing[k]);
        free(cs[i].timing);
        free(cs[i].round_of);
        free(cs[i].stats);
        for (size_t k = 0; cs[i].stats_reason && k < m->n_statistic; k++)
            free(cs[i].stats_reason[k]);
        free(cs[i].stats_reason);
        free(cs[i].frame_ns);
        free(cs[i].path_ns);
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
    render_destroy(m->r);
    gl_context_destroy(m->gl);
}

