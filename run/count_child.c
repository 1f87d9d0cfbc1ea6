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

/* ---- counting a batch of configurations ----------------------------------- */

/* The child counts its configurations in batches of at most
 * COUNT_CHILD__BATCH, in two phases.  Phase one prepares each
 * configuration of the batch in a GL context of its own (fresh, so no
 * configuration sees what another left in a context) and draws its warm-up
 * frames for every window it will count, with callgrind's instrumentation
 * off: the maps, meshes, programs and llvmpipe's JIT of every shader
 * variant happen here.  Phase two switches instrumentation on once, counts
 * every window of every configuration of the batch (each context made
 * current again), and switches it off.  Each switch discards every
 * translation Valgrind has made, so the driver's and LLVM's code is
 * translated again after it: switching once per batch instead of around
 * each window of each configuration made a child's warm-ups 2-10x shorter
 * (docs/counters.md, "In batches"). */
#define COUNT_CHILD__BATCH 8
/* A configuration whose mesh has at least this many triangles is heavy:
 * its frame is long (the reference mesh's, about 2^20 triangles, took
 * 2.3 s uninstrumented under Valgrind and 5.4 s instrumented), so it is
 * counted as soon as it is prepared, with instrumentation switched on
 * around each window's samples only, after that window's warm-up: an
 * instrumented frame to settle each window would cost more than
 * translating the rest again after the switches (docs/counters.md).  A
 * count, unlike a time, decides it the same way in every run. */
#define COUNT_CHILD__HEAVY_TRIANGLES (1u << 18)

/* One configuration of a batch: its context, scene, items and split. */
typedef struct cslot {
    mscene m;                   /* gl shared by the batch; r and rt its own */
    mconf c;
    int ctx;                    /* its context's index (gl_context_use) */
    int done;                   /* counted, or failed (said so) */
    int stages;                 /* its stage windows are counted */
    int heavy;                  /* COUNT_CHILD__HEAVY_TRIANGLES: counted at once, window by window */
    render_item full;           /* its item, while c.item follows the window counted */
    render_item minimal;        /* the minimal-fragment-shader item of the stage windows */
    int64_t prep_ns, warm_ns, stage_ns, count_ns;
} cslot;

static const char *const count_child__tag[CALLGRIND_WINDOWS] = {"", ".g", ".r", ".m"};

/* Makes window w's item and discard state current on slot k. */
static void count_child__window_state(cslot *k, callgrind_window w)
{
    k->c.item = w == CALLGRIND_RASTER || w == CALLGRIND_RESIDUAL ? k->minimal : k->full;
    if (w == CALLGRIND_GEOMETRY || w == CALLGRIND_RESIDUAL)
        glEnable(GL_RASTERIZER_DISCARD);
    else
        glDisable(GL_RASTERIZER_DISCARD);
}

/* The warm-up of the window whose state is current: `warm` frames of a
 * still configuration, or each counted view of a path once, and the
 * virtual texture's pages converged, so no first use of a view (a mip
 * level, a tessellation level, a page) and no JIT compilation falls in the
 * counted frames, as the timed run's untimed replay keeps them out. */
static void count_child__warm_frames(cslot *k, int warm)
{
    mscene *m = &k->m;
    mconf *c = &k->c;
    int step, frames = callgrind_path_frames(c->pc, &step);
    if (path_timing_frames(c->pc)) {
        for (int i = 0; i < frames; i++) {
            mscene_frame_at(m, c, i * step);
            mscene_vt_converge(m->r, c->item, c->pc->width, c->pc->height);
        }
    } else {
        mscene_frames(m, c, warm > 0 ? warm : 1);
        mscene_vt_converge(m->r, c->item, c->pc->width, c->pc->height);
    }
    glFinish();
}

/* `samples` samples of window w's counted frames, its state current and
 * warmed up, instrumentation on, collection off: the counted frames
 * (callgrind_path_frames: CALLGRIND_FRAMES from frame 0, or a camera
 * path's frames, every k-th), each ended by a glFinish (so the
 * rasteriser's work, on the calling thread with LP_NUM_THREADS=0, is
 * inside), collection on around each sample only, and one dump per sample
 * named "KEY.S" (window CALLGRIND_FULL), "KEY.g.S" (the same frames with
 * GL_RASTERIZER_DISCARD), "KEY.r.S" (the minimal-fragment-shader item) or
 * "KEY.m.S" (that item with discard).  Every sample is kept: the parent
 * leaves the allocator's instructions out, and what remains is equal from
 * the first sample on (docs/counters.md, "Repeatability"). */
static void count_child__samples(cslot *k, callgrind_window w, int samples)
{
    mscene *m = &k->m;
    mconf *c = &k->c;
    int step, frames = callgrind_path_frames(c->pc, &step);
    for (int s = 0; s < samples; s++) {
        char name[40];
        snprintf(name, sizeof name, "%s%s.%d", c->pc->key, count_child__tag[w], s);
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
}

/* Counts slot k's windows (its context current) and says "S KEY ok" and
 * "I KEY ok|failed REASON".  A light slot is counted in phase two, with
 * instrumentation on: before each window's samples it draws one frame
 * uncounted, the last view a sample draws, so the first sample follows
 * the same state as every later one (the context made current again, the
 * discard and the item switched since its warm-up).  A heavy one is
 * counted in phase one as soon as it is prepared, with instrumentation
 * switched on around each window's samples only, after that window's
 * warm-up (without stage windows, the full frame's is the one it was just
 * prepared with). */
static void count_child__count_slot(cslot *k, int samples)
{
    mconf *c = &k->c;
    int64_t t0 = dm_now_ns();
    mscene_say(k->m.job, "B %s", c->pc->key);
    int step, frames = callgrind_path_frames(c->pc, &step);
    for (int w = CALLGRIND_FULL; w < (k->stages ? CALLGRIND_WINDOWS : CALLGRIND_FULL + 1); w++) {
        count_child__window_state(k, (callgrind_window)w);
        if (!k->heavy)
            mscene_frame_at(&k->m, c, (frames - 1) * step);
        else if (w != CALLGRIND_FULL || k->stages)   /* the full frame's state changed by the minimal item */
            count_child__warm_frames(k, 1);
        if (k->heavy)
            CALLGRIND_START_INSTRUMENTATION;
        count_child__samples(k, (callgrind_window)w, samples);
        if (k->heavy)
            CALLGRIND_STOP_INSTRUMENTATION;
        if (w == CALLGRIND_FULL) {
            k->count_ns = dm_now_ns() - t0;
            t0 = dm_now_ns();
        }
    }
    if (k->heavy)
        fprintf(stderr, "instructions split: %s is heavy: counted as soon as prepared\n", c->pc->key);
    fprintf(stderr, "instructions split: %s prepare %.1f ms, warm-up %.1f ms, counted %.1f ms\n", c->pc->key,
            (double)k->prep_ns / 1e6, (double)k->warm_ns / 1e6, (double)k->count_ns / 1e6);
    if (k->stages) {
        k->stage_ns += dm_now_ns() - t0;
        fprintf(stderr, "instructions split: %s stage windows %.1f ms\n", c->pc->key, (double)k->stage_ns / 1e6);
        mscene_say(k->m.job, "S %s ok", c->pc->key);
    }
    int bad = gl_context_check_errors(&c->log) > 0;
    mscene_say(k->m.job, "I %s %s", c->pc->key, bad ? "failed GL error in the counted frames" : "ok");
    k->done = 1;
}

/* Phase one of slot k (its context current): prepare, warm up the full
 * frame (heavy: COUNT_CHILD__HEAVY_TRIANGLES), and, with stages asked for, build the minimal fragment shader's item of
 * the stage windows (geometry with rasterizer discard, raster with the
 * minimal fragment shader, and the minimal shader with discard for the
 * residual) and warm them up (a light slot; a heavy one warms each up
 * just before its samples).  Says "I KEY failed REASON" when it cannot be
 * prepared, "S KEY unavailable REASON" when its stages cannot be
 * isolated. */
static void count_child__prepare(cslot *k, int stages)
{
    mscene *m = &k->m;
    mconf *c = &k->c;
    const measure_job *job = m->job;
    int64_t t0 = dm_now_ns();
    int prc = render_prepare(m->r, c->pc->params, c->pc->n_params, &c->item, &c->log);
    k->prep_ns = dm_now_ns() - t0;
    if (gl_context_take_messages(m->gl, &c->log) > 0 || prc != 0) {
        mscene_say(job, "I %s failed %s", c->pc->key, prc == 0 ? "GL error while preparing" : dm_strerror(prc));
        k->done = 1;
        return;
    }
    k->full = c->item;
    int64_t t1 = dm_now_ns();
    count_child__warm_frames(k, CALLGRIND_WARMUP_FRAMES);
    k->warm_ns = dm_now_ns() - t1;
    render_item_info info = {0};
    render_get_info(m->r, c->item, &info);
    k->heavy = info.mesh_triangles >= COUNT_CHILD__HEAVY_TRIANGLES;
    if (!stages)
        return;
    int64_t ts = dm_now_ns();
    const char *why = mscene_isolation_problem(&info);
    if (why) {
        mscene_say(job, "S %s unavailable %s", c->pc->key, why);
        return;
    }
    dm_str log = {0};
    render_set_debug_view(m->r, RENDER_DEBUG_MINIMAL_FS);
    int rc = render_prepare(m->r, c->pc->params, c->pc->n_params, &k->minimal, &log);
    render_set_debug_view(m->r, RENDER_DEBUG_NONE);
    if (gl_context_take_messages(m->gl, &log) > 0 || rc != 0) {
        for (char *nl = strchr(log.buf ? log.buf : "", '\n'); nl; nl = strchr(nl, '\n'))
            *nl = ' ';   /* one protocol line */
        mscene_say(job, "S %s unavailable the minimal fragment shader cannot be built: %s", c->pc->key,
                   log.len ? dm_str_get(&log) : dm_strerror(rc));
        dm_str_free(&log);
        return;
    }
    dm_str_free(&log);
    k->stages = 1;
    if (!k->heavy) {
        for (int w = CALLGRIND_GEOMETRY; w < CALLGRIND_WINDOWS; w++) {
            count_child__window_state(k, (callgrind_window)w);
            count_child__warm_frames(k, 1);
        }
        count_child__window_state(k, CALLGRIND_FULL);
    }
    k->stage_ns = dm_now_ns() - ts;
}

/* Frees slot k's scene (its context current) and its log. */
static void count_child__free_slot(cslot *k)
{
    if (k->m.r && gl_context_use(k->m.gl, k->ctx) == 0) {
        if (k->minimal.id)
            render_release(k->m.r, k->minimal);
        target_destroy(&k->m.rt);
        render_destroy(k->m.r);
        if (k->ctx > 0)
            gl_context_drop(k->m.gl, k->ctx);
    }
    k->m.r = NULL;
    dm_str_free(&k->c.log);
}

/* Counts configurations [first, first + n) of the job, one batch; the
 * first slot uses context 0 (made by the caller), the others get contexts
 * of their own.  Returns 0, or DM_ERR_GL when a context cannot be made. */
static int count_child__batch(const measure_job *job, gl_context *gl, size_t first, size_t n, int samples,
                              int stages)
{
    cslot *ks = dm_xcalloc(n, sizeof *ks);
    int rc = 0;
    size_t made = 0;
    /* phase one: every configuration prepared and warmed up, uninstrumented
     * (a heavy one counted at once) */
    for (; made < n; made++) {
        cslot *k = &ks[made];
        k->m = (mscene){ .job = job, .gl = gl };
        k->c.pc = &job->configs[first + made];
        /* "W KEY": the child is on this key (a crash now fails it alone,
         * and a new child takes the batch's others); "B KEY" when counted */
        mscene_say(job, "W %s", k->c.pc->key);
        k->ctx = made == 0 ? 0 : gl_context_add(gl);
        if (k->ctx < 0 || gl_context_use(gl, k->ctx) != 0 || render_create(&k->m.r) != 0) {
            mscene_say(job, "B %s", k->c.pc->key);
            mscene_say(job, "I %s failed cannot create a fresh GL context", k->c.pc->key);
            rc = DM_ERR_GL;
            break;
        }
        count_child__prepare(k, stages);
        if (!k->done && k->heavy)
            count_child__count_slot(k, samples);
    }
    /* phase two: instrumentation switched on and off once for the light
     * ones.  Starting it resets callgrind's call stacks and its collection
     * state to off, so the toggles pair inside, and the calls into the
     * allocator made in the frames are seen from their callers. */
    CALLGRIND_START_INSTRUMENTATION;
    for (size_t i = 0; i < made; i++) {
        cslot *k = &ks[i];
        if (k->done)
            continue;
        if (gl_context_use(gl, k->ctx) != 0) {
            mscene_say(job, "B %s", k->c.pc->key);
            mscene_say(job, "I %s failed cannot make its GL context current again", k->c.pc->key);
            continue;
        }
        count_child__count_slot(k, samples);
    }
    CALLGRIND_STOP_INSTRUMENTATION;
    for (size_t i = made < n ? made + 1 : n; i-- > 0;)
        count_child__free_slot(&ks[i]);
    free(ks);
    return rc;
}

static int count_child__instructions(const measure_job *job, int samples, dm_str *err)
{
    gl_context *gl = NULL;
    int64_t t0 = dm_now_ns();
    int stages = callgrind_wants_stages(&job->sweep->measure);
    int rc = gl_context_create(NULL, &gl, err);
    /* where the child's time goes, in its log (bench/instructions_split.sh) */
    fprintf(stderr, "instructions split: context %.1f ms\n", (double)(dm_now_ns() - t0) / 1e6);
    if (rc == 0 && !RUNNING_ON_VALGRIND)
        dm_log(DM_LOG_WARN, "count_child__instructions: not running under Valgrind; nothing is counted");
    for (size_t first = 0; rc == 0 && first < job->n_configs; first += COUNT_CHILD__BATCH) {
        size_t n = job->n_configs - first;
        /* every configuration in a fresh GL context: what the driver keeps
         * per context (state caches, sampler views, upload buffers, the
         * hash tables of GL names) would otherwise carry what earlier
         * configurations left, and a count would depend on which ones ran
         * before it (docs/counters.md, "Repeatability") */
        if (first > 0 && (gl_context_use(gl, 0) != 0 || gl_context_renew(gl) != 0)) {
            mscene_say(job, "B %s", job->configs[first].key);
            mscene_say(job, "I %s failed cannot create a fresh GL context", job->configs[first].key);
            rc = DM_ERR_GL;
            break;
        }
        rc = count_child__batch(job, gl, first, n < COUNT_CHILD__BATCH ? n : COUNT_CHILD__BATCH, samples,
                                stages);
    }
    gl_context_destroy(gl);
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
