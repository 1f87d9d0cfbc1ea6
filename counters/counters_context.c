/* counters_context.c — probing the current GL context once: extensions,
 * availability with reasons, and what counters really count on this driver
 * (measured, never guessed from the renderer name). */
#include "counters_internal.h"
#include "core/dm_error.h"
#include "counters_expr.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define EXT_PIPESTATS "GL_ARB_pipeline_statistics_query"
#define EXT_TIMER     "GL_ARB_timer_query"
#define EXT_COMPUTE   "GL_ARB_compute_shader"
#define EXT_BALLOT    "GL_ARB_shader_ballot"

int counters__has_ext(const counters_context *ctx, const char *ext)
{
    for (size_t i = 0; i < ctx->nhidden; i++)
        if (strcmp(ctx->hidden[i], ext) == 0)
            return 0;
    for (size_t i = 0; i < ctx->nexts; i++)
        if (strcmp(ctx->exts[i], ext) == 0)
            return 1;
    return 0;
}

static int ctx__req_ok(const counters_context *ctx, counters__req req, const char **why)
{
    static const char *const lacks_ps = "driver lacks " EXT_PIPESTATS;
    static const char *const lacks_tq = "driver lacks " EXT_TIMER;
    static const char *const lacks_cs = "driver lacks " EXT_COMPUTE;
    int ps = counters__has_ext(ctx, EXT_PIPESTATS);
    switch (req) {
    case COUNTERS__REQ_NONE: return 1;
    case COUNTERS__REQ_PIPESTATS: *why = lacks_ps; return ps;
    case COUNTERS__REQ_TIMER: *why = lacks_tq; return counters__has_ext(ctx, EXT_TIMER);
    case COUNTERS__REQ_COMPUTE:
        *why = ps ? lacks_cs : lacks_ps;
        return ps && counters__has_ext(ctx, EXT_COMPUTE);
    case COUNTERS__REQ_CALLGRIND:
        *why = ctx->callgrind_why;
        return ctx->callgrind_why[0] == '\0';
    case COUNTERS__REQ_BALLOT:
        *why = "driver lacks " EXT_BALLOT " (the instrumented shader elects one fragment per SIMD group)";
        return counters__has_ext(ctx, EXT_BALLOT);
    }
    return 0;
}

typedef struct ctx__dep { const counters_context *ctx; int ok; const char *why; } ctx__dep;

static void ctx__dep_check(const char *name, size_t len, void *user)
{
    ctx__dep *d = user;
    char buf[64];
    snprintf(buf, sizeof buf, "%.*s", (int)len, name);
    const char *why = "formula names an unknown counter";
    int i = counters__index(buf);
    if (d->ok && (i < 0 || !counters__available_idx(d->ctx, i, &why))) {
        d->ok = 0;
        d->why = why;
    }
}

/* A derived counter is available when all its inputs are; its reason is
 * the first missing input's reason. */
int counters__available_idx(const counters_context *ctx, int i, const char **why)
{
    const counters__def *d = counters__def_at((size_t)i);
    if (!d) {
        *why = "unknown counter";
        return 0;
    }
    if (d->info.formula) {
        ctx__dep dep = {ctx, 1, NULL};
        counters__expr_names(d->info.formula, ctx__dep_check, &dep);
        *why = dep.why;
        return dep.ok;
    }
    return ctx__req_ok(ctx, d->req, why);
}

int counters_available(const counters_context *ctx, const char *name, const char **reason)
{
    const char *why = NULL;
    int ok = counters__available_idx(ctx, counters__index(name), &why);
    if (reason)
        *reason = ok ? NULL : why;
    return ok;
}

void counters_context_hide_extension(counters_context *ctx, const char *ext)
{
    if (ctx->nhidden < COUNTERS__MAX_HIDDEN)
        ctx->hidden[ctx->nhidden++] = dm_xstrdup(ext);
}

static void ctx__load_exts(counters_context *ctx)
{
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    ctx->exts = dm_xcalloc((size_t)(n > 0 ? n : 1), sizeof *ctx->exts);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e)
            ctx->exts[ctx->nexts++] = dm_xstrdup(e);
    }
}

/* Measures FSInvocations for one covered pixel: a single point at the
 * centre of pixel (1,1) of an 8x8 target.  Returns the ratio
 * FSInvocations/SamplesPassed, or 0 if it could not be measured. */
static double ctx__probe_fs_granularity(void)
{
    static const char *vs = "#version 450 core\n"
        "void main() { gl_Position = vec4(-0.625, -0.625, 0.0, 1.0); }\n";
    static const char *fs = "#version 450 core\nout vec4 c;\n"
        "void main() { c = vec4(1.0); }\n";
    counters__glstate st;
    counters__glstate_save(&st);
    counters__target t;
    unsigned prog = 0;
    double ratio = 0;
    if (counters__target_create(&t, 8, 8) == 0) {
        if (counters__program(vs, fs, &prog, NULL) == 0) {
            GLuint q[2];
            glGenQueries(2, q);
            glUseProgram(prog);
            glPointSize(1.0f);
            glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q[0]);
            glBeginQuery(GL_SAMPLES_PASSED, q[1]);
            glDrawArrays(GL_POINTS, 0, 1);
            glEndQuery(GL_SAMPLES_PASSED);
            glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
            uint64_t fsi = 0, sp = 0;
            if (!counters__query_read(q[0], &fsi) && !counters__query_read(q[1], &sp) && sp == 1)
                ratio = (double)fsi;
            glDeleteQueries(2, q);
            glDeleteProgram(prog);
        }
        counters__target_destroy(&t);
    }
    counters__glstate_restore(&st);
    return ratio;
}

static void ctx__fs_note(counters_context *ctx)
{
    double r = ctx->fs_per_pixel;
    if (r == 16.0)
        snprintf(ctx->fs_note, sizeof ctx->fs_note,
                 "counted per 4x4 pixel block on this driver (measured: 1 covered pixel -> "
                 "16 invocations), before the depth test; values are multiples of 16 and "
                 "over-count edges; use SamplesPassed for covered pixels");
    else if (r > 1.0)
        snprintf(ctx->fs_note, sizeof ctx->fs_note,
                 "counted in blocks on this driver (measured: 1 covered pixel -> %.0f "
                 "invocations); use SamplesPassed for covered pixels", r);
    else
        snprintf(ctx->fs_note, sizeof ctx->fs_note, "%s%s",
                 counters_find("FSInvocations")->description,
                 r == 1.0 ? " (measured: 1 per covered pixel)" : " (granularity not measured)");
}

char *counters_valgrind_path(void)
{
    const char *env = getenv("DMBENCH_VALGRIND");
    if (env && *env)
        return access(env, X_OK) == 0 ? dm_xstrdup(env) : NULL;
    const char *path = getenv("PATH");
    char *copy = dm_xstrdup(path ? path : "/usr/bin:/bin"), *save = NULL, *found = NULL;
    for (char *dir = strtok_r(copy, ":", &save); dir && !found; dir = strtok_r(NULL, ":", &save)) {
        char *cand = dm_xasprintf("%s/valgrind", *dir ? dir : ".");
        if (access(cand, X_OK) == 0)
            found = cand;
        else
            free(cand);
    }
    free(copy);
    return found;
}

/* Decides once whether Instructions can be counted here: instruction counts
 * are the cost of rendering only when the rasteriser is CPU code (llvmpipe,
 * softpipe: the one place the renderer's name decides, because no GL query
 * says "software"), and they need Valgrind. */
static void ctx__callgrind_probe(counters_context *ctx)
{
    const char *r = (const char *)glGetString(GL_RENDERER);
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", r ? r : "?");
    ctx->cpu_renderer = r && (strstr(r, "llvmpipe") || strstr(r, "softpipe"));
    char *vg = counters_valgrind_path();
    if (!ctx->cpu_renderer)
        snprintf(ctx->callgrind_why, sizeof ctx->callgrind_why,
                 "not a CPU renderer ('%s'): instructions of the calling process are not the cost "
                 "of rendering on a GPU", ctx->renderer);
    else if (!vg)
        snprintf(ctx->callgrind_why, sizeof ctx->callgrind_why,
                 "valgrind not found (%s); scripts/install-deps installs it",
                 getenv("DMBENCH_VALGRIND") ? "DMBENCH_VALGRIND is not an executable" : "not on PATH");
    free(vg);
}

int counters_context_create(counters_context **out)
{
    counters_context *ctx = dm_xcalloc(1, sizeof *ctx);
    ctx__load_exts(ctx);
    if (counters__has_ext(ctx, EXT_PIPESTATS))
        ctx->fs_per_pixel = ctx__probe_fs_granularity();
    ctx__fs_note(ctx);
    ctx__callgrind_probe(ctx);
    snprintf(ctx->gpu_note, sizeof ctx->gpu_note, "%s; coverage not calibrated yet",
             counters_find("GPUTime")->description);
    *out = ctx;
    return 0;
}

void counters_context_destroy(counters_context *ctx)
{
    if (!ctx)
        return;
    for (size_t i = 0; i < ctx->nexts; i++)
        free(ctx->exts[i]);
    for (size_t i = 0; i < ctx->nhidden; i++)
        free(ctx->hidden[i]);
    free(ctx->exts);
    free(ctx);
}

const char *counters_driver_note(const counters_context *ctx, const char *name)
{
    const counters_info *info = counters_find(name);
    if (!info)
        return NULL;
    if (strcmp(name, "FSInvocations") == 0)
        return ctx->fs_note;
    if (strcmp(name, "GPUTime") == 0)
        return ctx->gpu_note;
    return info->description;
}
