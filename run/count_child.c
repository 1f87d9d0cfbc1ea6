/* count_child.c — the counting child of the Instructions pass: `dmbench
 * __instructions`, run under Valgrind callgrind by run/callgrind.c (see
 * count_child.h). */
#include "run/count_child.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <valgrind/callgrind.h>

#include "core/dm_error.h"
#include "run/callgrind.h"
#include "run/mscene.h"
#include "run/path_timing.h"
#include "techniques/user_technique.h"

/* ---- counting one configuration ------------------------------------------ */

/* The counted window of one configuration: collection switched on around
 * its counted frames (callgrind_path_frames: CALLGRIND_FRAMES from frame
 * 0, or a camera path's frames, every k-th), each ended by a glFinish (so
 * the rasteriser's work, on the calling thread with LP_NUM_THREADS=0, is
 * inside), then one dump per sample named "KEY.S" (window CALLGRIND_FULL),
 * "KEY.g.S" (the same frames with GL_RASTERIZER_DISCARD), "KEY.r.S"
 * (c->item is then the minimal-fragment-shader item) or "KEY.m.S" (that
 * item with discard).  Setup, JIT compilation and the warm-up (`warm`
 * frames, or each counted frame of a path once) happen before, with
 * instrumentation and collection off: Valgrind runs them without
 * callgrind's per-instruction calls, and only the samples' frames are
 * instrumented.  Every sample is kept: the parent leaves the allocator's
 * instructions out, and what remains is equal from the first sample on
 * (docs/counters.md, "Repeatability").  Returns the nanoseconds of the
 * warm-up in *warm_ns and of the samples in *count_ns
 * (bench/instructions_split.sh). */
static void count_child__counted_samples(mscene *m, mconf *c, callgrind_window w, int warm, int samples,
                                         int64_t *warm_ns, int64_t *count_ns)
{
    static const char *const tag[CALLGRIND_WINDOWS] = {"", ".g", ".r", ".m"};
    int step, frames = callgrind_path_frames(c->pc, &step);
    int64_t t0 = dm_now_ns(), t1 = t0;
    if (path_timing_frames(c->pc)) {
        /* every counted view drawn once and its pages converged: the
         * first use of a view (a mip level, a tessellation level, a page)
         * is not counted, as the timed run's untimed replay keeps it out */
        for (int i = 0; i < frames; i++) {
            mscene_frame_at(m, c, i * step);
            mscene_vt_converge(m->r, c->item, c->pc->width, c->pc->height);
        }
    } else {
        mscene_frames(m, c, warm > 0 ? warm : 1);
        mscene_vt_converge(m->r, c->item, c->pc->width, c->pc->height);   /* no page generation counted */
    }
    if (w == CALLGRIND_GEOMETRY || w == CALLGRIND_RESIDUAL)
        glEnable(GL_RASTERIZER_DISCARD);
    t1 = dm_now_ns();
    /* Instrumented from here to the last dump only (Valgrind runs with
     * --instr-atstart=no): starting discards every translation and resets
     * callgrind's call stacks and its collection state to off, so the
     * toggles pair inside, and the calls into the allocator made in the
     * frames are seen from their callers as before. */
    CALLGRIND_START_INSTRUMENTATION;
    for (int s = 0; s < samples; s++) {
        char name[40];
        snprintf(name, sizeof name, "%s%s.%d", c->pc->key, tag[w], s);
        glFinish();
        CALLGRIND_TOGGLE_COLLECT;
        /* each frame finished on its own, as the timed replay does: frames
         * drawn back to back without one are not all rasterised (measured:
         * two identical frames counted 12 % less each than one) */
        for (int i = 0; i < frames; i++) {
            mscene_frame_at(m, c, i * step);
            glFinish();
        }
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(name);
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    glDisable(GL_RASTERIZER_DISCARD);
    *warm_ns = t1 - t0;
    *count_ns = dm_now_ns() - t1;
}

/* The stage windows of a prepared, counted configuration (geometry with
 * rasterizer discard, raster with the minimal fragment shader, and the
 * minimal shader with discard for the residual), reported
 * as "S KEY ok" or "S KEY unavailable REASON". */
static void count_child__stage_windows(mscene *m, mconf *c, int samples)
{
    render_item_info info = {0};
    render_get_info(m->r, c->item, &info);
    const char *why = mscene_isolation_problem(&info);
    if (why) {
        mscene_say(m->job, "S %s unavailable %s", c->pc->key, why);
        return;
    }
    int64_t warm_ns = 0, count_ns = 0;
    count_child__counted_samples(m, c, CALLGRIND_GEOMETRY, 1, samples, &warm_ns, &count_ns);
    render_item full = c->item, minimal = {0};
    dm_str log = {0};
    render_set_debug_view(m->r, RENDER_DEBUG_MINIMAL_FS);
    int rc = render_prepare(m->r, c->pc->params, c->pc->n_params, &minimal, &log);
    render_set_debug_view(m->r, RENDER_DEBUG_NONE);
    if (gl_context_take_messages(m->gl, &log) > 0 || rc != 0) {
        for (char *nl = strchr(log.buf ? log.buf : "", '\n'); nl; nl = strchr(nl, '\n'))
            *nl = ' ';   /* one protocol line */
        mscene_say(m->job, "S %s unavailable the minimal fragment shader cannot be built: %s", c->pc->key,
                     log.len ? dm_str_get(&log) : dm_strerror(rc));
        dm_str_free(&log);
        return;
    }
    dm_str_free(&log);
    c->item = minimal;
    count_child__counted_samples(m, c, CALLGRIND_RASTER, 1, samples, &warm_ns, &count_ns);
    count_child__counted_samples(m, c, CALLGRIND_RESIDUAL, 1, samples, &warm_ns, &count_ns);
    c->item = full;
    render_release(m->r, minimal);
    mscene_say(m->job, "S %s ok", c->pc->key);
}

/* Counts configuration c (prepare, warm-up, samples, stage windows) and
 * says "I KEY ok" or "I KEY failed REASON". */
static void count_child__count_one(mscene *m, mconf *c, int samples, int stages)
{
    const measure_job *job = m->job;
    int64_t tp = dm_now_ns(), warm_ns = 0, count_ns = 0;
    int prc = render_prepare(m->r, c->pc->params, c->pc->n_params, &c->item, &c->log);
    int64_t prep_ns = dm_now_ns() - tp;
    if (gl_context_take_messages(m->gl, &c->log) > 0 || prc != 0) {
        mscene_say(job, "I %s failed %s", c->pc->key, prc == 0 ? "GL error while preparing" : dm_strerror(prc));
        return;
    }
    count_child__counted_samples(m, c, CALLGRIND_FULL, CALLGRIND_WARMUP_FRAMES, samples, &warm_ns, &count_ns);
    fprintf(stderr, "instructions split: %s prepare %.1f ms, warm-up %.1f ms, counted %.1f ms\n", c->pc->key,
            (double)prep_ns / 1e6, (double)warm_ns / 1e6, (double)count_ns / 1e6);
    if (stages) {
        int64_t ts = dm_now_ns();
        count_child__stage_windows(m, c, samples);
        fprintf(stderr, "instructions split: %s stage windows %.1f ms\n", c->pc->key,
                (double)(dm_now_ns() - ts) / 1e6);
    }
    int bad = gl_context_check_errors(&c->log) > 0;
    mscene_say(job, "I %s %s", c->pc->key, bad ? "failed GL error in the counted frames" : "ok");
}

static int count_child__instructions(const measure_job *job, int samples, dm_str *err)
{
    mscene m = { .job = job };
    int64_t t0 = dm_now_ns();
    int stages = callgrind_wants_stages(&job->sweep->measure);
    int rc = gl_context_create(NULL, &m.gl, err);
    rc = rc ? rc : render_create(&m.r);
    /* where the child's time goes, in its log (bench/instructions_split.sh) */
    fprintf(stderr, "instructions split: context %.1f ms\n", (double)(dm_now_ns() - t0) / 1e6);
    if (rc == 0 && !RUNNING_ON_VALGRIND)
        dm_log(DM_LOG_WARN, "count_child__instructions: not running under Valgrind; nothing is counted");
    mconf *cs = dm_xcalloc(job->n_configs + 1, sizeof *cs);
    for (size_t i = 0; rc == 0 && i < job->n_configs; i++) {
        mconf *c = &cs[i];
        c->pc = &job->configs[i];
        mscene_say(job, "B %s", c->pc->key);
        if (i > 0) {
            /* Every configuration in a fresh GL context: what the driver
             * keeps per context (state caches, sampler views, upload
             * buffers, the hash tables of GL names) would otherwise carry
             * what earlier configurations left, and a count would depend on
             * which ones ran before it (docs/counters.md, "Repeatability"). */
            target_destroy(&m.rt);
            render_destroy(m.r);
            m.r = NULL;
            if (gl_context_renew(m.gl) != 0 || render_create(&m.r) != 0) {
                mscene_say(job, "I %s failed cannot create a fresh GL context", c->pc->key);
                rc = DM_ERR_GL;
                break;
            }
        }
        count_child__count_one(&m, c, samples, stages);
    }
    for (size_t i = 0; i < job->n_configs; i++)
        dm_str_free(&cs[i].log);
    free(cs);
    if (m.gl)
        target_destroy(&m.rt);
    render_destroy(m.r);
    gl_context_destroy(m.gl);
    return rc;
}

/* ---- the child process --------------------------------------------------- */

static int count_child__load_sweep(const char *source, sweep *s, dm_str *err)
{
    if (strcmp(source, "<default>") == 0 || strcmp(source, "<default --quick>") == 0) {
        int quick = strcmp(source, "<default>") != 0;
        return sweep_parse(sweep_default_text(quick), source, s, err);
    }
    return sweep_load(source, s, err);
}

/* Puts this process's malloc in a mode whose work does not depend on what
 * the process did before.  llvmpipe's tessellation path (Mesa 22.3) grows
 * its output arrays with one realloc per patch; on the brk heap a realloc
 * copies the block whenever its neighbour is in use, so how much a frame
 * copies depended on the heap's history (earlier configurations, a cold or
 * warm shader and map cache): 12-25 % spread in a frame's count.  From
 * CALLGRIND_MMAP_THRESHOLD up a block is mmapped and grows by mremap
 * (kernel work, not counted), and a heap top that is never padded or kept
 * leaves no spare room that would put a large block on the heap instead.
 * Fixing the threshold also stops glibc from raising it as blocks are
 * freed.  Measured in docs/counters.md ("Repeatability"). */
static void count_child__fixed_allocator(void)
{
    mallopt(M_MMAP_THRESHOLD, CALLGRIND_MMAP_THRESHOLD);
    mallopt(M_TOP_PAD, 0);
    mallopt(M_TRIM_THRESHOLD, CALLGRIND_MMAP_THRESHOLD);
}

static int count_child__run(int argc, char **argv) __attribute__((noinline));

/* Set in the counting child: arc4random_buf then returns a fixed stream. */
static int count_child__fixed_entropy;

/* glibc's arc4random_buf, replaced for the whole process: the executable
 * exports this definition (cli/CMakeLists.txt), so every library's call
 * binds to it.  Outside the counting child it is the kernel's randomness,
 * as glibc's.  In the child it is a fixed stream: Mesa parses its driconf
 * files with expat when the GL context is created, and expat salts its
 * hash tables from arc4random_buf.  A new salt per process frees the
 * parser's blocks in another order, the driver's later blocks land at
 * other offsets in their page, and glibc's memcmp, which takes another
 * path when an operand is near a page end, counted up to 190 instructions
 * a frame more or less (software virtual texturing, docs/counters.md,
 * "Repeatability").  Nothing in the child needs unpredictable bytes. */
void arc4random_buf(void *buf, size_t n)
{
    unsigned char *b = buf;
    if (count_child__fixed_entropy) {
        uint64_t x = 0x9e3779b97f4a7c15u;
        for (size_t i = 0; i < n; i++) {
            x = x * 6364136223846793005u + 1442695040888963407u;
            b[i] = (unsigned char)(x >> 56);
        }
        return;
    }
    while (n > 0) {
        ssize_t r = getrandom(b, n, 0);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            abort();   /* as glibc's: no randomness is not an error to return */
        b += r;
        n -= (size_t)r;
    }
}

/* The counting child works on a stack that starts at the same offset in
 * its page in every process.  The stack main is handed starts below the
 * arguments and the environment, so it moves with their length (a longer
 * run directory, another key count, one more variable), and with it every
 * structure the driver compares on the stack: 1 670 115 and 1 670 171
 * instructions for one frame with environments 13 and 26 bytes apart
 * (docs/counters.md, "Repeatability").  Giving up the bytes above the next
 * page boundary puts every deeper frame at a fixed offset.  (A thread of
 * its own, with a new stack and malloc arena, was tried: the driver's
 * shader-cache thread then frees into that arena at its own pace, and
 * cold-cache counts spread more.) */
int count_child_main(int argc, char **argv)
{
    count_child__fixed_allocator();
    count_child__fixed_entropy = 1;
    char here = 0;
    size_t off = (size_t)((uintptr_t)&here % CALLGRIND_STACK_ALIGN);
    volatile char pad[off + 1];
    pad[off] = here;
    return count_child__run(argc, argv) + pad[off];
}

/* The child's check that it measures what the run measures: the sweep file
 * (hash want) and each `--source PATH HASH` of argv[*a...] (advanced past
 * them) as loaded (loaded != 0) or, when loading failed, as on disk now.
 * Appends "FILE changed since the run started ..." to changed for each
 * that differs. */
static void count_child__sources(const char *path, const sweep *s, int loaded, const char *want, int argc,
                        char **argv, int *a, dm_str *changed)
{
    char have[17] = "";
    char *text = NULL;
    size_t len = 0;
    if (loaded)
        dm_hex64(s->hash, have);
    else if (path[0] != '<' && dm_read_file(path, &text, &len) == 0 && text)
        dm_hex64(dm_fnv1a64(text, strlen(text), DM_FNV_SEED), have);
    free(text);
    if (have[0] && strcmp(have, want) != 0)
        dm_str_printf(changed, "%s: the sweep file changed since the run started (hash %s, now %s)",
                      path, want, have);
    for (; *a + 2 < argc && strcmp(argv[*a], "--source") == 0; *a += 3) {
        const char *file = argv[*a + 1];
        uint64_t h = strtoull(argv[*a + 2], NULL, 16);
        const technique_desc *t = loaded ? user_technique_by_path(file) : NULL;
        if (t && t->source_hash == h)
            continue;
        dm_str one = {0};
        if (user_technique_source_check(file, h, &one) != 0)
            dm_str_printf(changed, "%s%s", changed->len ? "; " : "", dm_str_get(&one));
        else if (t) {   /* loaded another text than the file holds now: changed twice */
            char now[17];
            dm_hex64(t->source_hash, now);
            dm_str_printf(changed, "%s%s: the user technique's file changed while the run was "
                          "going (source hash %s, read %s)", changed->len ? "; " : "", file,
                          argv[*a + 2], now);
        }
        dm_str_free(&one);
    }
}

static int count_child__run(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: dmbench __instructions SWEEP HASH [--source PATH HASH]... KEY... "
                "(run by dmbench itself)\n");
        return 2;
    }
    sweep s = {0};
    plan p = {0};
    dm_str err = {0}, changed = {0};
    int rc = count_child__load_sweep(argv[1], &s, &err), a = 3;
    count_child__sources(argv[1], &s, rc == 0, argv[2], argc, argv, &a, &changed);
    if (changed.len) {   /* one line: the run stops with it, nothing fails */
        for (char *c = changed.buf; *c; c++)
            *c = *c == '\n' ? ' ' : *c;
        printf("C %s\n", dm_str_get(&changed));
        fflush(stdout);
        sweep_free(&s);
        dm_str_free(&changed);
        dm_str_free(&err);
        return 3;
    }
    dm_str_free(&changed);
    rc = rc ? rc : plan_build(&s, NULL, &p, &err);
    plan_config *cs = dm_xcalloc((size_t)argc + 1, sizeof *cs);
    size_t n = 0;
    for (; rc == 0 && a < argc; a++)
        for (size_t i = 0; i < p.n_configs; i++)
            if (strcmp(p.configs[i].key, argv[a]) == 0)
                cs[n++] = p.configs[i];
    measure_job job = { .sweep = &s, .configs = cs, .n_configs = n, .report_fd = 1 };
    rc = rc ? rc : count_child__instructions(&job, CALLGRIND_SAMPLES, &err);
    if (rc != 0)
        fprintf(stderr, "dmbench __instructions: %s\n", dm_str_get(&err));
    free(cs);
    plan_free(&p);
    sweep_free(&s);
    dm_str_free(&err);
    return rc ? 3 : 0;
}
