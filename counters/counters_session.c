/* counters_session.c — sessions, the pass plan, samples and results.
 *
 * State machine: SETUP (enable) -> passes 0..n-1 in order, each bracketing
 * the same sample ids -> ENDED (queries read, results available).  The plan
 * has at most one pass per kind (timing, geometry, statistics), in that
 * order, and only kinds with an available enabled counter.  The loop-trips
 * pass binds a two-uint buffer (LoopTrips, FragmentGroups) at
 * COUNTERS_LOOP_TRIPS_BINDING around each sample, zeroed at its start and
 * read at its end.
 */
#include "counters_internal.h"
#include "counters_expr.h"
#include "core/dm_error.h"

#include <epoxy/gl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { S_SETUP, S_BETWEEN, S_IN_PASS, S_IN_SAMPLE, S_ENDED };
enum { V_NONE = 0, V_HAVE, V_UNAVAILABLE };

typedef struct sess__sample {
    uint32_t id;
    int measured;                       /* seen in pass 0 */
    double timing_wall;                 /* fenced wall time of the timing pass, 0 = none */
    double val[COUNTERS__MAX];
    unsigned char state[COUNTERS__MAX]; /* V_* */
    char *why[COUNTERS__MAX];           /* owned reason when V_UNAVAILABLE */
    unsigned query[COUNTERS__MAX];      /* GL query name, 0 = none */
} sess__sample;

struct counters_session {
    counters_context *ctx;
    unsigned char enabled[COUNTERS__MAX];
    counters__pass plan[COUNTERS__PASS_KINDS];
    int nplan, locked, state, pass;
    sess__sample *samples;
    size_t nsamples, cap;
    size_t *order, norder;              /* sample indices in pass-0 order */
    size_t cursor, cur;                 /* position in this pass; current sample */
    int64_t t0, cpu0, th0;
    GLboolean discard_was;
    GLuint trips_buf;                   /* the loop-trips pass's counter buffer, 0 = none */
    char err[512];
};

static const char *const sess__pass_names[COUNTERS__PASS_KINDS] = {
    NULL, "timing", "geometry", "raster", "statistics", "loop trips"};

static int sess__fail(counters_session *s, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int sess__fail(counters_session *s, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->err, sizeof s->err, fmt, ap);
    va_end(ap);
    return code;
}

int counters_pass_minimal_fs(const counters_session *s, int pass)
{
    return pass >= 0 && pass < s->nplan && s->plan[pass] == COUNTERS__PASS_RASTER;
}

int counters_pass_loop_trips(const counters_session *s, int pass)
{
    return pass >= 0 && pass < s->nplan && s->plan[pass] == COUNTERS__PASS_LOOPS;
}

int counters_pass_warm_frames(const counters_session *s, int pass)
{
    return pass >= 0 && pass < s->nplan &&
           (s->plan[pass] == COUNTERS__PASS_GEOMETRY || s->plan[pass] == COUNTERS__PASS_RASTER);
}

const char *counters_last_error(const counters_session *s)
{
    return s->err;
}

int counters_session_create(counters_context *ctx, counters_session **out)
{
    counters_session *s = dm_xcalloc(1, sizeof *s);
    s->ctx = ctx;
    *out = s;
    return 0;
}

void counters_session_destroy(counters_session *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->nsamples; i++)
        for (size_t c = 0; c < COUNTERS__MAX; c++) {
            free(s->samples[i].why[c]);
            if (s->samples[i].query[c])
                glDeleteQueries(1, &s->samples[i].query[c]);
        }
    if (s->trips_buf)
        glDeleteBuffers(1, &s->trips_buf);
    free(s->samples);
    free(s->order);
    free(s);
}

/* ---- enabling and the plan ------------------------------------------- */

static int sess__enable_idx(counters_session *s, int i);

static void sess__enable_dep(const char *name, size_t len, void *user)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%.*s", (int)len, name);
    int i = counters__index(buf);
    if (i >= 0)
        sess__enable_idx(user, i);
}

/* Enables counter i and, for a derived counter, its inputs. */
static int sess__enable_idx(counters_session *s, int i)
{
    s->enabled[i] = 1;
    const char *f = counters__def_at((size_t)i)->info.formula;
    if (f)
        counters__expr_names(f, sess__enable_dep, s);
    return 0;
}

int counters_enable(counters_session *s, const char *name)
{
    int i = counters__index(name);
    if (i < 0)
        return sess__fail(s, DM_ERR_UNKNOWN, "unknown counter '%s' (see dmbench list counters)",
                          name ? name : "(null)");
    if (s->locked)
        return sess__fail(s, DM_ERR_MISUSE, "counters_enable('%s') after the first pass began", name);
    return sess__enable_idx(s, i);
}

int counters_enable_group(counters_session *s, const char *group)
{
    int found = 0;
    for (size_t i = 0; i < counters_count(); i++)
        if (group && strcmp(counters_info_at(i)->group, group) == 0) {
            int rc = counters_enable(s, counters_info_at(i)->name);
            if (rc)
                return rc;
            found = 1;
        }
    return found ? 0 : sess__fail(s, DM_ERR_UNKNOWN, "unknown counter group '%s'",
                                  group ? group : "(null)");
}

/* Does pass kind k have an enabled counter the driver can provide? */
static int sess__kind_needed(const counters_session *s, counters__pass k)
{
    for (size_t i = 0; i < counters_count(); i++) {
        const char *why;
        if (s->enabled[i] && counters__def_at(i)->pass == k &&
            counters__available_idx(s->ctx, (int)i, &why))
            return 1;
    }
    return 0;
}

static void sess__make_plan(counters_session *s)
{
    s->nplan = 0;
    for (int k = COUNTERS__PASS_TIMING; k < COUNTERS__PASS_KINDS; k++)
        if (sess__kind_needed(s, (counters__pass)k))
            s->plan[s->nplan++] = (counters__pass)k;
}

int counters_num_passes(counters_session *s, int *passes)
{
    if (!s->locked)
        sess__make_plan(s);
    *passes = s->nplan;
    return 0;
}

const char *counters_pass_name(counters_session *s, int pass)
{
    if (!s->locked)
        sess__make_plan(s);
    return pass >= 0 && pass < s->nplan ? sess__pass_names[s->plan[pass]] : NULL;
}

/* ---- passes ------------------------------------------------------------ */

int counters_pass_begin(counters_session *s, int pass)
{
    if (s->state == S_IN_PASS || s->state == S_IN_SAMPLE)
        return sess__fail(s, DM_ERR_MISUSE, "counters_pass_begin(%d) while pass %d is open",
                          pass, s->pass);
    if (s->state == S_ENDED)
        return sess__fail(s, DM_ERR_MISUSE, "counters_pass_begin(%d) after counters_session_end", pass);
    if (!s->locked) {
        sess__make_plan(s);
        s->locked = 1;
    }
    int expect = s->state == S_SETUP ? 0 : s->pass + 1;
    if (pass != expect || pass >= s->nplan)
        return sess__fail(s, DM_ERR_MISUSE, "counters_pass_begin(%d): passes run in order, "
                          "expected pass %d of %d", pass, expect, s->nplan);
    s->pass = pass;
    s->state = S_IN_PASS;
    s->cursor = 0;
    if (s->plan[pass] == COUNTERS__PASS_GEOMETRY) {
        s->discard_was = glIsEnabled(GL_RASTERIZER_DISCARD);
        glEnable(GL_RASTERIZER_DISCARD);
    }
    return 0;
}

int counters_pass_end(counters_session *s)
{
    if (s->state != S_IN_PASS)
        return sess__fail(s, DM_ERR_MISUSE, "counters_pass_end: %s",
                          s->state == S_IN_SAMPLE ? "a sample is still open" : "no pass is open");
    if (s->pass > 0 && s->cursor != s->norder)
        return sess__fail(s, DM_ERR_MISUSE, "pass %d took %zu samples, pass 0 took %zu: "
                          "every pass must bracket the same samples", s->pass, s->cursor, s->norder);
    if (s->plan[s->pass] == COUNTERS__PASS_GEOMETRY && !s->discard_was)
        glDisable(GL_RASTERIZER_DISCARD);
    s->state = S_BETWEEN;
    return 0;
}

/* ---- samples ------------------------------------------------------------ */

static sess__sample *sess__find(counters_session *s, uint32_t id, size_t *idx)
{
    for (size_t i = 0; i < s->nsamples; i++)
        if (s->samples[i].id == id) {
            if (idx)
                *idx = i;
            return &s->samples[i];
        }
    return NULL;
}

static size_t sess__get(counters_session *s, uint32_t id)
{
    size_t i;
    if (sess__find(s, id, &i))
        return i;
    if (s->nsamples == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 8;
        s->samples = dm_xrealloc(s->samples, s->cap * sizeof *s->samples);
    }
    memset(&s->samples[s->nsamples], 0, sizeof *s->samples);
    s->samples[s->nsamples].id = id;
    return s->nsamples++;
}

/* Chooses the sample record for id in the current pass: pass 0 defines
 * the sample list, later passes must repeat it in the same order. */
static int sess__pick(counters_session *s, uint32_t id)
{
    if (s->pass == 0) {
        size_t i = sess__get(s, id);
        if (s->samples[i].measured)
            return sess__fail(s, DM_ERR_MISUSE, "sample %u used twice in pass 0", id);
        s->samples[i].measured = 1;
        DM_VEC_PUSH(s->order, s->norder, i);
        s->cur = i;
        return 0;
    }
    if (s->cursor >= s->norder || s->samples[s->order[s->cursor]].id != id)
        return sess__fail(s, DM_ERR_MISUSE, "pass %d sample #%zu has id %u but pass 0 %s",
                          s->pass, s->cursor, id, s->cursor >= s->norder ? "had fewer samples"
                          : "used a different id there: sample ids must match between passes");
    s->cur = s->order[s->cursor];
    return 0;
}

/* Begins one query per enabled, available counter of the current pass kind. */
static void sess__begin_queries(counters_session *s, sess__sample *smp)
{
    counters__pass kind = s->plan[s->pass];
    for (size_t i = 0; i < counters_count(); i++) {
        const counters__def *d = counters__def_at(i);
        const char *why;
        if (!s->enabled[i] || d->pass != kind || !d->gl_target ||
            !counters__available_idx(s->ctx, (int)i, &why))
            continue;
        glGenQueries(1, &smp->query[i]);
        glBeginQuery(d->gl_target, smp->query[i]);
    }
}

static void sess__end_queries(counters_session *s, sess__sample *smp)
{
    counters__pass kind = s->plan[s->pass];
    for (size_t i = counters_count(); i-- > 0;) {
        const counters__def *d = counters__def_at(i);
        if (smp->query[i] && d->pass == kind)
            glEndQuery(d->gl_target);
    }
}

int counters_sample_begin(counters_session *s, uint32_t sample_id)
{
    if (s->state != S_IN_PASS)
        return sess__fail(s, DM_ERR_MISUSE, "counters_sample_begin(%u): %s", sample_id,
                          s->state == S_IN_SAMPLE ? "samples cannot be nested"
                          : "no pass is open");
    int rc = sess__pick(s, sample_id);
    if (rc)
        return rc;
    s->state = S_IN_SAMPLE;
    if (s->plan[s->pass] == COUNTERS__PASS_LOOPS) {
        static const GLuint zero[2] = {0, 0};
        if (!s->trips_buf)
            glGenBuffers(1, &s->trips_buf);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->trips_buf);
        glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, GL_DYNAMIC_READ);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, COUNTERS_LOOP_TRIPS_BINDING, s->trips_buf);
    }
    if (s->plan[s->pass] != COUNTERS__PASS_STATS)
        glFinish();                     /* start from an idle pipeline */
    sess__begin_queries(s, &s->samples[s->cur]);
    s->t0 = dm_now_ns();
    s->cpu0 = dm_cpu_ns();
    s->th0 = dm_thread_cpu_ns();
    return 0;
}

static void sess__store(counters_session *s, sess__sample *smp, const char *name, double v)
{
    int i = counters__index(name);
    if (s->enabled[i]) {
        smp->val[i] = v;
        smp->state[i] = V_HAVE;
    }
}

int counters_sample_end(counters_session *s)
{
    if (s->state != S_IN_SAMPLE)
        return sess__fail(s, DM_ERR_MISUSE, "counters_sample_end without counters_sample_begin");
    sess__sample *smp = &s->samples[s->cur];
    int64_t submit = dm_thread_cpu_ns() - s->th0;
    sess__end_queries(s, smp);
    if (s->plan[s->pass] != COUNTERS__PASS_STATS)
        glFinish();
    int64_t wall = dm_now_ns() - s->t0, cpu = dm_cpu_ns() - s->cpu0;
    if (s->plan[s->pass] == COUNTERS__PASS_TIMING) {
        smp->timing_wall = (double)wall;
        sess__store(s, smp, "WallTime", (double)wall);
        sess__store(s, smp, "CPUTime", (double)cpu);
        sess__store(s, smp, "SubmitTime", (double)submit);
    } else if (s->plan[s->pass] == COUNTERS__PASS_GEOMETRY) {
        sess__store(s, smp, "GeometryTime", (double)wall);
    } else if (s->plan[s->pass] == COUNTERS__PASS_RASTER) {
        sess__store(s, smp, "MinimalShadingTime", (double)wall);
    } else if (s->plan[s->pass] == COUNTERS__PASS_LOOPS) {
        GLuint trips[2] = {0, 0};
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->trips_buf);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof trips, trips);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, COUNTERS_LOOP_TRIPS_BINDING, 0);
        sess__store(s, smp, "LoopTrips", (double)trips[0]);
        sess__store(s, smp, "FragmentGroups", (double)trips[1]);
    }
    s->cursor++;
    s->state = S_IN_PASS;
    return 0;
}

int counters_set_value(counters_session *s, uint32_t sample_id, const char *name, double value)
{
    int i = counters__index(name);
    if (i < 0)
        return sess__fail(s, DM_ERR_UNKNOWN, "unknown counter '%s'", name ? name : "(null)");
    if (counters__def_at((size_t)i)->info.backend != COUNTERS_BACKEND_CPU_SIDE)
        return sess__fail(s, DM_ERR_ARG, "counter '%s' is measured, not fed by the caller", name);
    s->enabled[i] = 1;                  /* caller-fed counters never change the plan */
    sess__sample *smp = &s->samples[sess__get(s, sample_id)];
    smp->val[i] = value;
    smp->state[i] = V_HAVE;
    return 0;
}

/* ---- ending and results --------------------------------------------- */

static void sess__unavailable(sess__sample *smp, size_t i, char *why)
{
    free(smp->why[i]);
    smp->why[i] = why;
    smp->state[i] = V_UNAVAILABLE;
}

/* Reads query i of smp.  A timer result larger than the fenced wall time of
 * the same sample is not a duration (an un-started query has been seen to
 * return a raw timestamp on llvmpipe) and is rejected as unavailable. */
static void sess__read_query(sess__sample *smp, size_t i)
{
    uint64_t v = 0;
    const counters__def *d = counters__def_at(i);
    if (counters__query_read(smp->query[i], &v)) {
        sess__unavailable(smp, i, dm_xasprintf("GL error reading the %s query", d->info.name));
    } else if (d->gl_target == GL_TIME_ELAPSED && (double)v > 1.5 * smp->timing_wall + 1e6) {
        sess__unavailable(smp, i, dm_xasprintf("timer query returned %llu ns, more than the "
                          "sample's fenced wall time %.0f ns: not a duration",
                          (unsigned long long)v, smp->timing_wall));
    } else {
        smp->val[i] = (double)v;
        smp->state[i] = V_HAVE;
    }
    glDeleteQueries(1, &smp->query[i]);
    smp->query[i] = 0;
}

int counters_session_end(counters_session *s)
{
    if (s->state == S_IN_PASS || s->state == S_IN_SAMPLE || s->state == S_ENDED)
        return sess__fail(s, DM_ERR_MISUSE, "counters_session_end: %s",
                          s->state == S_ENDED ? "session already ended" : "a pass is still open");
    if (!s->locked)
        sess__make_plan(s);
    int done = s->state == S_SETUP ? 0 : s->pass + 1;
    if (done != s->nplan)
        return sess__fail(s, DM_ERR_MISUSE, "counters_session_end after %d of %d passes",
                          done, s->nplan);
    s->locked = 1;
    for (size_t k = 0; k < s->nsamples; k++)
        for (size_t i = 0; i < counters_count(); i++)
            if (s->samples[k].query[i])
                sess__read_query(&s->samples[k], i);
    s->state = S_ENDED;
    return 0;
}

typedef struct sess__ctx { counters_session *s; sess__sample *smp; int depth; } sess__ctx;

static int sess__value(sess__ctx *c, int i, double *v, dm_str *err);

static int sess__lookup(const char *name, size_t len, void *user, double *v, dm_str *err)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%.*s", (int)len, name);
    int i = counters__index(buf);
    if (i < 0) {
        dm_str_printf(err, "formula names unknown counter '%s'", buf);
        return DM_ERR_UNKNOWN;
    }
    return sess__value(user, i, v, err);
}

/* Value of enabled counter i in c->smp, or DM_ERR_UNAVAILABLE with why. */
static int sess__value(sess__ctx *c, int i, double *v, dm_str *err)
{
    const counters__def *d = counters__def_at((size_t)i);
    const char *why = NULL;
    if (!counters__available_idx(c->s->ctx, i, &why)) {
        dm_str_printf(err, "%s unavailable: %s", d->info.name, why);
        return DM_ERR_UNAVAILABLE;
    }
    if (d->info.formula) {
        if (++c->depth > 8) {
            dm_str_printf(err, "%s: formulas nest too deeply", d->info.name);
            return DM_ERR_PARSE;
        }
        int rc = counters__expr_eval(d->info.formula, sess__lookup, c, v, err);
        c->depth--;
        return rc;
    }
    switch (c->smp->state[i]) {
    case V_HAVE: *v = c->smp->val[i]; return 0;
    case V_UNAVAILABLE: dm_str_printf(err, "%s unavailable: %s", d->info.name, c->smp->why[i]); break;
    default:
        dm_str_printf(err, "%s unavailable: %s for sample %u", d->info.name,
                      d->pass == COUNTERS__PASS_NONE ? "not set by the caller" : "not measured",
                      c->smp->id);
    }
    return DM_ERR_UNAVAILABLE;
}

int counters_result(counters_session *s, uint32_t sample_id, const char *name, double *value)
{
    int i = counters__index(name);
    if (i < 0)
        return sess__fail(s, DM_ERR_UNKNOWN, "unknown counter '%s'", name ? name : "(null)");
    if (s->state != S_ENDED)
        return sess__fail(s, DM_ERR_MISUSE, "counters_result('%s') before counters_session_end", name);
    if (!s->enabled[i])
        return sess__fail(s, DM_ERR_NOTFOUND, "counter '%s' was not enabled", name);
    sess__ctx c = {s, sess__find(s, sample_id, NULL), 0};
    if (!c.smp)
        return sess__fail(s, DM_ERR_NOTFOUND, "no sample %u in this session", sample_id);
    dm_str err = {0};
    int rc = sess__value(&c, i, value, &err);
    if (rc)
        snprintf(s->err, sizeof s->err, "%s", dm_str_get(&err));
    dm_str_free(&err);
    return rc;
}

/* ---- plan description -------------------------------------------------- */

/* Appends "<label>: A, B" for the enabled counters matching pred (none: nothing). */
static void sess__list(const counters_session *s, dm_str *out, const char *label,
                       int (*pred)(const counters_session *, size_t, const void *), const void *arg)
{
    int first = 1;
    for (size_t i = 0; i < counters_count(); i++) {
        if (!s->enabled[i] || !pred(s, i, arg))
            continue;
        const counters_info *c = counters_info_at(i);
        const char *why = NULL;
        dm_str_printf(out, "%s%s", first ? label : ", ", c->name);
        if (c->formula)
            dm_str_printf(out, " = %s", c->formula);
        else if (!counters__available_idx(s->ctx, (int)i, &why))
            dm_str_printf(out, " (%s)", why);
        first = 0;
    }
    if (!first)
        dm_str_cat(out, "\n");
}

static int sess__in_pass(const counters_session *s, size_t i, const void *kind)
{
    const char *why;
    return counters__def_at(i)->pass == *(const counters__pass *)kind &&
           counters__available_idx(s->ctx, (int)i, &why);
}

static int sess__is_backend(const counters_session *s, size_t i, const void *b)
{
    (void)s;
    return counters_info_at(i)->backend == *(const counters_backend *)b;
}

static int sess__is_unavailable(const counters_session *s, size_t i, const void *arg)
{
    (void)arg;
    const char *why;
    return !counters_info_at(i)->formula && !counters__available_idx(s->ctx, (int)i, &why);
}

int counters_plan_describe(counters_context *ctx, const char *const *names, size_t n, dm_str *out)
{
    counters_session *s;
    counters_session_create(ctx, &s);
    for (size_t i = 0; i < n; i++)
        if (counters_enable(s, names[i])) {
            dm_str_cat(out, s->err);
            counters_session_destroy(s);
            return DM_ERR_UNKNOWN;
        }
    sess__make_plan(s);
    dm_str_printf(out, "%d pass%s\n", s->nplan, s->nplan == 1 ? "" : "es");
    for (int p = 0; p < s->nplan; p++) {
        char label[64];
        snprintf(label, sizeof label, "pass %d %s: ", p, sess__pass_names[s->plan[p]]);
        sess__list(s, out, label, sess__in_pass, &s->plan[p]);
    }
    const counters_backend cpu = COUNTERS_BACKEND_CPU_SIDE, der = COUNTERS_BACKEND_DERIVED;
    sess__list(s, out, "caller-fed: ", sess__is_backend, &cpu);
    sess__list(s, out, "derived: ", sess__is_backend, &der);
    const counters_backend cg = COUNTERS_BACKEND_CALLGRIND;
    sess__list(s, out, "callgrind child (own process under Valgrind, frames not timed): ",
               sess__is_backend, &cg);
    const counters_backend pc = COUNTERS_BACKEND_PER_CALL;
    sess__list(s, out, "per draw call (own pass of one frame, statistics around each call): ",
               sess__is_backend, &pc);
    sess__list(s, out, "unavailable: ", sess__is_unavailable, NULL);
    counters_session_destroy(s);
    return 0;
}
