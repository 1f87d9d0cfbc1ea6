/* test_run_tess_calls.c — TessWalkCalls on llvmpipe (docs/counters.md,
 * "TessWalkCalls"): the plane at 242 patches and level 16 is drawn in two
 * calls of 197 and 45 patches.  Bracketed here with raw GL queries through
 * the renderer's call hook (not the counters library), the calls' counts
 * add up to the frame's own, and the TessWalkCalls that `predict`'s
 * in-process counts give (run/inproc.c, through run/mscene.c and the
 * counters library) is the sum, worked here by hand, of TESInvocations x
 * ClippingOutputPrimitives over the calls the clipper changed.  A frame
 * of one call takes the frame's own counts; a technique without
 * tessellation has none. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/dm_util.h"
#include "run/gl_context.h"
#include "run/inproc.h"
#include "run/target.h"
#include "techniques/render.h"

enum { W = 96, H = 64, MAX_CALLS = 8, N_STATS = 4 };
/* TESInvocations, clipper in, clipper out, patches: raw GL targets */
static const GLenum stat_target[N_STATS] = {GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB,
                                            GL_CLIPPING_INPUT_PRIMITIVES_ARB, GL_CLIPPING_OUTPUT_PRIMITIVES_ARB,
                                            GL_TESS_CONTROL_SHADER_PATCHES_ARB};

/* The bench's `calls` pair: the plane under its camera (clipped). */
static void calls_config(plan_config *pc, const char *technique, const char *density, const char *level)
{
    memset(pc, 0, sizeof *pc);
    snprintf(pc->key, sizeof pc->key, "%s", "00000000000000aa");
    pc->width = W;
    pc->height = H;
    dm_kv_push(&pc->params, &pc->n_params, "camera.azimuth", "30");
    dm_kv_push(&pc->params, &pc->n_params, "camera.distance", "3.0");
    dm_kv_push(&pc->params, &pc->n_params, "camera.elevation", "35");
    dm_kv_push(&pc->params, &pc->n_params, "camera.fov", "45");
    dm_kv_push(&pc->params, &pc->n_params, "mesh", "plane");
    dm_kv_push(&pc->params, &pc->n_params, "mesh_density", density);
    dm_kv_push(&pc->params, &pc->n_params, "resolution", "96x64");
    dm_kv_push(&pc->params, &pc->n_params, "technique", technique);
    if (level)
        dm_kv_push(&pc->params, &pc->n_params, "tess_level", level);
}

/* Raw queries around each call (the hook) or around the whole frame. */
typedef struct raw { GLuint q[MAX_CALLS][N_STATS]; size_t n; } raw;

static void raw_begin(GLuint *q)
{
    glGenQueries(N_STATS, q);
    for (int j = 0; j < N_STATS; j++)
        glBeginQuery(stat_target[j], q[j]);
}

static void raw_end(void)
{
    for (int j = N_STATS; j-- > 0;)
        glEndQuery(stat_target[j]);
}

static void raw_hook(void *user, size_t call, int begin)
{
    raw *r = user;
    assert_true(call < MAX_CALLS);
    if (begin)
        raw_begin(r->q[call]);
    else
        raw_end();
    r->n = call + 1;
}

static void raw_read(GLuint *q, double *v)
{
    for (int j = 0; j < N_STATS; j++) {
        GLuint64 x = 0;
        glGetQueryObjectui64v(q[j], GL_QUERY_RESULT, &x);
        v[j] = (double)x;
    }
    glDeleteQueries(N_STATS, q);
}

/* Draws pc once per call bracketed and once whole: calls[k][j] and frame[j]
 * (j as stat_target); returns the calls. */
static size_t raw_counts(const plan_config *pc, double calls[MAX_CALLS][N_STATS], double frame[N_STATS])
{
    gl_context *gl = NULL;
    render_ctx *r = NULL;
    target t;
    dm_str err = {0}, log = {0};
    assert_int_equal(gl_context_create(NULL, &gl, &err), 0);
    assert_int_equal(render_create(&r), 0);
    assert_int_equal(target_create(&t, W, H), 0);
    target_bind(&t);
    render_item it;
    assert_int_equal(render_prepare(r, pc->params, pc->n_params, &it, &log), 0);
    assert_int_equal(render_draw(r, it, W, H), 0);   /* the JIT outside the counts */
    raw k = {0};
    render_set_call_hook(r, raw_hook, &k);
    assert_int_equal(render_draw(r, it, W, H), 0);
    render_set_call_hook(r, NULL, NULL);
    GLuint fq[N_STATS];
    raw_begin(fq);
    assert_int_equal(render_draw(r, it, W, H), 0);
    raw_end();
    for (size_t c = 0; c < k.n; c++)
        raw_read(k.q[c], calls[c]);
    raw_read(fq, frame);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    render_release(r, it);
    target_destroy(&t);
    render_destroy(r);
    gl_context_destroy(gl);
    dm_str_free(&err);
    dm_str_free(&log);
    return k.n;
}

/* TESInvocations, ClippingInputPrimitives, ClippingOutputPrimitives and
 * TessWalkCalls of pc as predict counts them, in its own context. */
static void inproc(const plan_config *pc, double v[4])
{
    static const char *const names[4] = {"TESInvocations", "ClippingInputPrimitives", "ClippingOutputPrimitives",
                                         "TessWalkCalls"};
    dm_str err = {0};
    assert_int_equal(inproc_counts(pc, 1, names, 4, v, &err), 0);
    dm_str_free(&err);
}

static void test_two_calls(void **state)
{
    (void)state;
    plan_config pc;
    calls_config(&pc, "tess-displacement", "12", "16");
    double calls[MAX_CALLS][N_STATS], frame[N_STATS], sum[N_STATS] = {0}, walk = 0;
    size_t n = raw_counts(&pc, calls, frame);
    assert_int_equal((int)n, 2);
    assert_true(calls[0][3] == 197 && calls[1][3] == 45);   /* render_patch_calls' split */
    for (size_t c = 0; c < n; c++) {
        fprintf(stderr, "call %zu: %.0f patches, %.0f evaluations, clipper %.0f in, %.0f out\n", c, calls[c][3],
                calls[c][0], calls[c][1], calls[c][2]);
        for (int j = 0; j < N_STATS; j++)
            sum[j] += calls[c][j];
        if (calls[c][1] != calls[c][2])
            walk += calls[c][0] * calls[c][2];
    }
    for (int j = 0; j < N_STATS; j++)   /* the calls add up to the frame exactly */
        assert_true(sum[j] == frame[j]);
    double v[4];
    inproc(&pc, v);
    fprintf(stderr, "frame: %.0f evaluations, %.0f in, %.0f out; TessWalkCalls %.0f (by hand %.0f); "
            "by patch shares %.0f\n", v[0], v[1], v[2], v[3], walk,
            frame[0] * frame[2] * (197.0 * 197 + 45.0 * 45) / (242.0 * 242));
    for (int j = 0; j < 3; j++)
        assert_true(v[j] == frame[j]);
    assert_true(walk > 0);
    assert_true(v[3] == walk);
    dm_kv_free(pc.params, pc.n_params);
}

/* One call (98 patches at level 8): the frame's own counts, no extra pass. */
static void test_one_call(void **state)
{
    (void)state;
    plan_config pc;
    calls_config(&pc, "tess-displacement", "8", "8");
    double calls[MAX_CALLS][N_STATS], frame[N_STATS], v[4];
    assert_int_equal((int)raw_counts(&pc, calls, frame), 1);
    assert_true(calls[0][3] == 98);
    inproc(&pc, v);
    assert_true(frame[1] != frame[2]);   /* clipped under this camera */
    assert_true(v[3] == frame[0] * frame[2]);
    dm_kv_free(pc.params, pc.n_params);
}

/* No tessellation: no call of patches, no figure (NaN, never 0). */
static void test_untessellated(void **state)
{
    (void)state;
    plan_config pc;
    calls_config(&pc, "normal", "8", NULL);
    double v[4];
    inproc(&pc, v);
    assert_true(v[0] == 0);
    assert_true(isnan(v[3]));
    dm_kv_free(pc.params, pc.n_params);
}

DM_TEST_MAIN(NULL, NULL, cmocka_unit_test(test_two_calls), cmocka_unit_test(test_one_call),
             cmocka_unit_test(test_untessellated))
