/* GL integration tests of counters/ on the EGL surfaceless context.
 *
 * Each test draws its own geometry with raw GL (own FBO, VAO/VBO, a tiny
 * shader) so every expected value is computed here independently:
 * covered pixels of a fullscreen quad, vertex-cache reuse of an indexed
 * grid, clipper output of a triangle crossing a clip plane, pass plans and
 * misuse codes.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "core/dm_error.h"
#include "counters/counters.h"
#include "counters/counters_internal.h"
#include "run/gl_context.h"

#define W 64
#define H 48

typedef struct fixture {
    gl_context *gl;
    counters_context *ctx;
    GLuint fbo, rb, prog;
} fixture;

typedef struct mesh { GLuint vao, vbo, ibo; GLsizei count; int indexed; } mesh;

static fixture F;

static GLuint make_program(void)
{
    const char *vs = "#version 450 core\nlayout(location = 0) in vec2 p;\n"
                     "void main() { gl_Position = vec4(p, 0.0, 1.0); }\n";
    const char *fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    unsigned p = 0;
    assert_int_equal(counters__program(vs, fs, &p, NULL), 0);   /* the module's own builder */
    return p;
}

static int setup(void **state)
{
    (void)state;
    dm_str err = {0};
    if (gl_context_create(NULL, &F.gl, &err)) {
        fprintf(stderr, "%s\n", dm_str_get(&err));
        return -1;
    }
    glGenRenderbuffers(1, &F.rb);
    glBindRenderbuffer(GL_RENDERBUFFER, F.rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    glGenFramebuffers(1, &F.fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, F.fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, F.rb);
    glViewport(0, 0, W, H);
    F.prog = make_program();
    glUseProgram(F.prog);
    return counters_context_create(&F.ctx);
}

static int teardown(void **state)
{
    (void)state;
    counters_context_destroy(F.ctx);
    glDeleteProgram(F.prog);
    glDeleteFramebuffers(1, &F.fbo);
    glDeleteRenderbuffers(1, &F.rb);
    gl_context_destroy(F.gl);
    return 0;
}

static mesh mesh_make(const float *xy, size_t nverts, const unsigned *idx, size_t nidx)
{
    mesh m = {0};
    glGenVertexArrays(1, &m.vao);
    glBindVertexArray(m.vao);
    glGenBuffers(1, &m.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nverts * 2 * sizeof(float)), xy, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray(0);
    if (idx) {
        glGenBuffers(1, &m.ibo);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(nidx * sizeof(unsigned)), idx, GL_STATIC_DRAW);
    }
    m.indexed = idx != NULL;
    m.count = (GLsizei)(idx ? nidx : nverts);
    return m;
}

static void mesh_draw(const mesh *m)
{
    glBindVertexArray(m->vao);
    if (m->indexed)
        glDrawElements(GL_TRIANGLES, m->count, GL_UNSIGNED_INT, NULL);
    else
        glDrawArrays(GL_TRIANGLES, 0, m->count);
}

static void mesh_free(mesh *m)
{
    glDeleteBuffers(1, &m->vbo);
    glDeleteBuffers(1, &m->ibo);
    glDeleteVertexArrays(1, &m->vao);
}

/* Two triangles covering clip space exactly. */
static mesh quad(void)
{
    static const float xy[] = {-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1};
    return mesh_make(xy, 6, NULL, 0);
}

/* Session over names, all passes, one sample (id 0) drawing m `draws` times. */
static counters_session *measure(counters_context *ctx, const char *const *names, size_t n,
                                 const mesh *m, int draws)
{
    counters_session *s;
    assert_int_equal(counters_session_create(ctx, &s), 0);
    for (size_t i = 0; i < n; i++)
        assert_int_equal(counters_enable(s, names[i]), 0);
    int passes = -1;
    assert_int_equal(counters_num_passes(s, &passes), 0);
    for (int p = 0; p < passes; p++) {
        assert_int_equal(counters_pass_begin(s, p), 0);
        assert_int_equal(counters_sample_begin(s, 0), 0);
        for (int d = 0; d < draws; d++)
            mesh_draw(m);
        assert_int_equal(counters_sample_end(s), 0);
        assert_int_equal(counters_pass_end(s), 0);
    }
    assert_int_equal(counters_session_end(s), 0);
    return s;
}

static double result(counters_session *s, const char *name)
{
    double v = -1;
    int rc = counters_result(s, 0, name, &v);
    if (rc)
        fail_msg("%s: %s (%s)", name, dm_errname(rc), counters_last_error(s));
    return v;
}

static void test_fullscreen_quad_samples(void **state)
{
    (void)state;
    mesh m = quad();
    const char *names[] = {"SamplesPassed", "FSInvocations", "PrimitivesSubmitted",
                           "ClippingInputPrimitives", "ClippingOutputPrimitives",
                           "ShadingEfficiency", "Overdraw"};
    counters_session *s = measure(F.ctx, names, 7, &m, 1);
    double sp = result(s, "SamplesPassed"), fsi = result(s, "FSInvocations");
    assert_int_equal((long)sp, W * H);
    assert_int_equal((long)result(s, "PrimitivesSubmitted"), 2);
    assert_int_equal((long)result(s, "ClippingInputPrimitives"), 2);
    assert_int_equal((long)result(s, "ClippingOutputPrimitives"), 2);   /* nothing crosses a plane */
    /* Block-granular counting: at least one invocation per covered pixel and,
     * with the 4x4 blocks this driver was measured to use, a multiple of 16. */
    assert_true(fsi >= sp);
    if (strstr(counters_driver_note(F.ctx, "FSInvocations"), "4x4"))
        assert_int_equal((long)fsi % 16, 0);
    assert_true(result(s, "ShadingEfficiency") == sp / fsi);
    /* Overdraw needs the caller's ViewportPixels: unset means unavailable. */
    double v;
    assert_int_equal(counters_result(s, 0, "Overdraw", &v), DM_ERR_UNAVAILABLE);
    assert_non_null(strstr(counters_last_error(s), "ViewportPixels"));
    assert_int_equal(counters_set_value(s, 0, "ViewportPixels", W * H), 0);
    assert_true(result(s, "Overdraw") == 1.0);
    assert_int_equal(counters_set_value(s, 0, "ViewportPixels", 0), 0);
    assert_int_equal(counters_result(s, 0, "Overdraw", &v), DM_ERR_UNAVAILABLE);
    assert_non_null(strstr(counters_last_error(s), "zero denominator"));
    counters_session_destroy(s);
    mesh_free(&m);
}

/* Post-transform vertex reuse of llvmpipe's draw module, modelled
 * independently: the index stream is cut into segments of 1023 indices
 * (341 triangles); each segment starts with an empty cache; inside a
 * segment an index is shaded again unless the direct-mapped cache slot
 * (index mod 256) still holds it.  Measured to match N = 2..200 exactly. */
static unsigned long model_vs_invocations(const unsigned *idx, size_t n)
{
    unsigned long shaded = 0;
    long slot[256];
    for (size_t i = 0; i < n; i++) {
        if (i % 1023 == 0)
            memset(slot, 0xff, sizeof slot);
        if (slot[idx[i] % 256] != (long)idx[i]) {
            slot[idx[i] % 256] = (long)idx[i];
            shaded++;
        }
    }
    return shaded;
}

static mesh grid(unsigned n, unsigned long *model)
{
    float *xy = malloc(2 * n * n * sizeof *xy);
    size_t nidx = 6 * (size_t)(n - 1) * (n - 1), k = 0;
    unsigned *idx = malloc(nidx * sizeof *idx);
    for (unsigned y = 0; y < n; y++)
        for (unsigned x = 0; x < n; x++) {
            xy[2 * (y * n + x)] = -0.9f + 1.8f * (float)x / (float)(n - 1);
            xy[2 * (y * n + x) + 1] = -0.9f + 1.8f * (float)y / (float)(n - 1);
        }
    for (unsigned y = 0; y + 1 < n; y++)
        for (unsigned x = 0; x + 1 < n; x++) {
            unsigned a = y * n + x, b = a + 1, c = a + n, d = c + 1;
            unsigned tri[6] = {a, b, d, a, d, c};
            memcpy(&idx[k], tri, sizeof tri);
            k += 6;
        }
    *model = model_vs_invocations(idx, nidx);
    mesh m = mesh_make(xy, (size_t)n * n, idx, nidx);
    free(xy);
    free(idx);
    return m;
}

static void test_grid_vertex_reuse(void **state)
{
    (void)state;
    static const unsigned sizes[] = {2, 8, 16, 32, 64};
    const char *names[] = {"VSInvocations", "PrimitivesSubmitted", "VerticesSubmitted", "VertexReuse"};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        unsigned n = sizes[i];
        unsigned long model;
        mesh m = grid(n, &model);
        counters_session *s = measure(F.ctx, names, 4, &m, 1);
        unsigned long quads = (unsigned long)(n - 1) * (n - 1);
        double vs = result(s, "VSInvocations");
        if (6 * quads <= 1023)   /* one segment, no slot collisions: every vertex once */
            assert_int_equal((unsigned long)vs, (unsigned long)n * n);
        assert_int_equal((unsigned long)vs, model);
        assert_int_equal((unsigned long)result(s, "PrimitivesSubmitted"), 2 * quads);
        assert_int_equal((unsigned long)result(s, "VerticesSubmitted"), 6 * quads);
        assert_true(result(s, "VertexReuse") == (double)(6 * quads) / (double)model);
        counters_session_destroy(s);
        mesh_free(&m);
    }
}

/* A triangle crossing the x = +1 plane with one vertex outside becomes a
 * quadrilateral (2 triangles); with two vertices outside it stays a
 * triangle (1).  The driver clips for real here (no guard band). */
static void test_clipping(void **state)
{
    (void)state;
    static const float one_out[] = {0.0f, -0.5f, 2.0f, -0.5f, 0.0f, 0.5f};
    static const float two_out[] = {0.5f, -0.5f, 3.0f, -0.5f, 3.0f, 0.5f};
    const char *names[] = {"ClippingInputPrimitives", "ClippingOutputPrimitives",
                           "PrimitivesGenerated", "ClippedFraction", "PixelsPerTriangle",
                           "SamplesPassed"};
    mesh a = mesh_make(one_out, 3, NULL, 0), b = mesh_make(two_out, 3, NULL, 0);
    counters_session *s = measure(F.ctx, names, 6, &a, 1);
    assert_int_equal((long)result(s, "ClippingInputPrimitives"), 1);
    assert_int_equal((long)result(s, "ClippingOutputPrimitives"), 2);
    assert_int_equal((long)result(s, "PrimitivesGenerated"), 1);   /* before clipping */
    assert_true(result(s, "ClippedFraction") == -1.0);
    assert_true(result(s, "PixelsPerTriangle") == result(s, "SamplesPassed") / 2.0);
    counters_session_destroy(s);
    s = measure(F.ctx, names, 6, &b, 1);
    assert_int_equal((long)result(s, "ClippingOutputPrimitives"), 1);
    assert_true(result(s, "ClippedFraction") == 0.0);
    counters_session_destroy(s);
    mesh_free(&a);
    mesh_free(&b);
}

/* Without tessellation both TES inputs are 0: the ratio is unavailable. */
static void test_zero_denominator_unavailable(void **state)
{
    (void)state;
    mesh m = quad();
    const char *names[] = {"TessAmplification"};
    counters_session *s = measure(F.ctx, names, 1, &m, 1);
    assert_int_equal((long)result(s, "TCSPatches"), 0);     /* input enabled by the formula */
    double v = 42;
    assert_int_equal(counters_result(s, 0, "TessAmplification", &v), DM_ERR_UNAVAILABLE);
    assert_true(v == 42);
    assert_non_null(strstr(counters_last_error(s), "zero denominator"));
    counters_session_destroy(s);
    mesh_free(&m);
}

static void test_fs_block_note(void **state)
{
    (void)state;
    /* The probe drew one 1-pixel point; on a block-counting driver the
     * note says how many invocations it took. */
    const char *note = counters_driver_note(F.ctx, "FSInvocations");
    assert_non_null(note);
    assert_true(strstr(note, "measured") != NULL);
    assert_null(counters_driver_note(F.ctx, "Nope"));
    assert_string_equal(counters_driver_note(F.ctx, "VSInvocations"),
                        counters_find("VSInvocations")->description);
}

static int plan_of(const char *const *names, size_t n, const char *expect)
{
    counters_session *s;
    counters_session_create(F.ctx, &s);
    for (size_t i = 0; i < n; i++)
        assert_int_equal(counters_enable(s, names[i]), 0);
    int passes = -1;
    counters_num_passes(s, &passes);
    char buf[128] = "";
    for (int p = 0; p < passes; p++) {
        strcat(buf, p ? "," : "");
        strcat(buf, counters_pass_name(s, p));
    }
    assert_string_equal(buf, expect);
    assert_null(counters_pass_name(s, passes));
    counters_session_destroy(s);
    return passes;
}

static void test_pass_plans(void **state)
{
    (void)state;
    const char *a[] = {"WallTime", "VSInvocations"};
    assert_int_equal(plan_of(a, 2, "timing,statistics"), 2);
    assert_int_equal(plan_of(a + 1, 1, "statistics"), 1);
    const char *b[] = {"WallTime", "VSInvocations", "GeometryTime"};
    assert_int_equal(plan_of(b, 3, "timing,geometry,statistics"), 3);
    const char *c[] = {"RasterTime"};                /* WallTime - GeometryTime */
    assert_int_equal(plan_of(c, 1, "timing,geometry"), 2);
    /* the stage passes, and the untimed frame each draws before its
     * sample (the timing and statistics passes none) */
    const char *g[] = {"WallTime", "VSInvocations", "GeometryTime", "MinimalShadingTime"};
    assert_int_equal(plan_of(g, 4, "timing,geometry,raster,statistics"), 4);
    counters_session *w;
    counters_session_create(F.ctx, &w);
    for (size_t i = 0; i < 4; i++)
        counters_enable(w, g[i]);
    int np;
    counters_num_passes(w, &np);
    for (int p = 0; p < np; p++)
        assert_int_equal(counters_pass_warm_frames(w, p),
                         strcmp(counters_pass_name(w, p), "geometry") == 0 ||
                         strcmp(counters_pass_name(w, p), "raster") == 0);
    assert_int_equal(counters_pass_warm_frames(w, np), 0);
    counters_session_destroy(w);
    const char *d[] = {"TextureBytes", "SetupTime"}; /* caller-fed: no pass */
    assert_int_equal(plan_of(d, 2, ""), 0);
    const char *e[] = {"SamplesPassed", "FSInvocations", "PrimitivesGenerated", "GPUTime", "CPUTime"};
    assert_int_equal(plan_of(e, 5, "timing,statistics"), 2);
    counters_session *s;
    counters_session_create(F.ctx, &s);
    assert_int_equal(counters_enable(s, "Bogus"), DM_ERR_UNKNOWN);
    assert_int_equal(counters_enable_group(s, "Bogus"), DM_ERR_UNKNOWN);
    assert_int_equal(counters_enable_group(s, "Vertex"), 0);
    int passes;
    counters_num_passes(s, &passes);
    assert_int_equal(passes, 1);
    counters_session_destroy(s);
}

static void test_plan_describe(void **state)
{
    (void)state;
    dm_str out = {0};
    const char *a[] = {"WallTime", "VertexReuse", "TextureBytes"};
    assert_int_equal(counters_plan_describe(F.ctx, a, 3, &out), 0);
    assert_string_equal(dm_str_get(&out),
        "2 passes\n"
        "pass 0 timing: WallTime\n"
        "pass 1 statistics: VerticesSubmitted, VSInvocations\n"
        "caller-fed: TextureBytes\n"
        "derived: VertexReuse = VerticesSubmitted / VSInvocations\n");
    dm_str_free(&out);
    const char *b[] = {"WallTime", "Bogus"};
    assert_int_equal(counters_plan_describe(F.ctx, b, 2, &out), DM_ERR_UNKNOWN);
    assert_non_null(strstr(dm_str_get(&out), "unknown counter 'Bogus'"));
    dm_str_free(&out);
    counters_context *ctx;
    counters_context_create(&ctx);
    counters_context_hide_extension(ctx, "GL_ARB_pipeline_statistics_query");
    assert_int_equal(counters_plan_describe(ctx, b, 1, &out), 0);
    const char *c[] = {"WallTime", "VSInvocations"};
    dm_str_free(&out);
    assert_int_equal(counters_plan_describe(ctx, c, 2, &out), 0);
    assert_string_equal(dm_str_get(&out),
        "1 pass\n"
        "pass 0 timing: WallTime\n"
        "unavailable: VSInvocations (driver lacks GL_ARB_pipeline_statistics_query)\n");
    dm_str_free(&out);
    counters_context_destroy(ctx);
    /* LoopTrips and FragmentGroups: one pass of their own after the
     * statistics (one instrumented shader counts both), unavailable
     * without subgroup election */
    const char *t[] = {"WallTime", "FSInvocations", "LoopTrips", "FragmentGroups"};
    assert_int_equal(counters_plan_describe(F.ctx, t, 4, &out), 0);
    assert_string_equal(dm_str_get(&out),
        "3 passes\n"
        "pass 0 timing: WallTime\n"
        "pass 1 statistics: FSInvocations\n"
        "pass 2 loop trips: LoopTrips, FragmentGroups\n");
    dm_str_free(&out);
    counters_context_create(&ctx);
    counters_context_hide_extension(ctx, "GL_ARB_shader_ballot");
    assert_int_equal(counters_plan_describe(ctx, t, 4, &out), 0);
    assert_non_null(strstr(dm_str_get(&out), "unavailable: LoopTrips (driver lacks GL_ARB_shader_ballot"));
    assert_non_null(strstr(dm_str_get(&out), ", FragmentGroups (driver lacks GL_ARB_shader_ballot"));
    dm_str_free(&out);
    counters_context_destroy(ctx);
}

static void test_misuse(void **state)
{
    (void)state;
    counters_session *s;
    counters_session_create(F.ctx, &s);
    counters_enable(s, "WallTime");
    counters_enable(s, "SamplesPassed");
    double v;
    assert_int_equal(counters_result(s, 0, "WallTime", &v), DM_ERR_MISUSE);
    assert_non_null(strstr(counters_last_error(s), "before counters_session_end"));
    assert_int_equal(counters_sample_begin(s, 0), DM_ERR_MISUSE);     /* no pass */
    assert_int_equal(counters_pass_begin(s, 1), DM_ERR_MISUSE);       /* out of order */
    assert_non_null(strstr(counters_last_error(s), "expected pass 0"));
    assert_int_equal(counters_pass_begin(s, 0), 0);
    assert_int_equal(counters_pass_begin(s, 0), DM_ERR_MISUSE);       /* twice */
    assert_int_equal(counters_enable(s, "VSInvocations"), DM_ERR_MISUSE);
    assert_int_equal(counters_sample_begin(s, 3), 0);
    assert_int_equal(counters_sample_begin(s, 4), DM_ERR_MISUSE);     /* nested */
    assert_non_null(strstr(counters_last_error(s), "nested"));
    assert_int_equal(counters_pass_end(s), DM_ERR_MISUSE);            /* sample open */
    assert_int_equal(counters_sample_end(s), 0);
    assert_int_equal(counters_sample_end(s), DM_ERR_MISUSE);
    assert_int_equal(counters_sample_begin(s, 3), DM_ERR_MISUSE);     /* same id twice */
    assert_int_equal(counters_pass_end(s), 0);
    assert_int_equal(counters_session_end(s), DM_ERR_MISUSE);         /* 1 of 2 passes */
    assert_non_null(strstr(counters_last_error(s), "after 1 of 2 passes"));
    assert_int_equal(counters_pass_begin(s, 1), 0);
    assert_int_equal(counters_sample_begin(s, 5), DM_ERR_MISUSE);     /* ids differ */
    assert_non_null(strstr(counters_last_error(s), "sample ids must match"));
    assert_int_equal(counters_pass_end(s), DM_ERR_MISUSE);            /* too few samples */
    assert_int_equal(counters_sample_begin(s, 3), 0);
    assert_int_equal(counters_sample_end(s), 0);
    assert_int_equal(counters_pass_end(s), 0);
    assert_int_equal(counters_pass_begin(s, 2), DM_ERR_MISUSE);       /* no such pass */
    assert_int_equal(counters_session_end(s), 0);
    assert_int_equal(counters_session_end(s), DM_ERR_MISUSE);
    assert_int_equal(counters_result(s, 3, "SamplesPassed", &v), 0);
    assert_true(v == 0.0);                                            /* nothing drawn */
    assert_int_equal(counters_result(s, 9, "WallTime", &v), DM_ERR_NOTFOUND);
    assert_int_equal(counters_result(s, 3, "VSInvocations", &v), DM_ERR_NOTFOUND);
    assert_int_equal(counters_result(s, 3, "Nope", &v), DM_ERR_UNKNOWN);
    assert_int_equal(counters_set_value(s, 3, "WallTime", 1), DM_ERR_ARG);
    counters_session_destroy(s);
}

static void test_hidden_pipeline_statistics(void **state)
{
    (void)state;
    counters_context *ctx;
    assert_int_equal(counters_context_create(&ctx), 0);
    const char *why = NULL;
    assert_int_equal(counters_available(ctx, "VSInvocations", &why), 1);
    counters_context_hide_extension(ctx, "GL_ARB_pipeline_statistics_query");
    assert_int_equal(counters_available(ctx, "VSInvocations", &why), 0);
    assert_string_equal(why, "driver lacks GL_ARB_pipeline_statistics_query");
    assert_int_equal(counters_available(ctx, "VertexReuse", &why), 0);
    assert_string_equal(why, "driver lacks GL_ARB_pipeline_statistics_query");
    assert_int_equal(counters_available(ctx, "SamplesPassed", &why), 1);   /* occlusion is core */
    assert_int_equal(counters_available(ctx, "WallTime", &why), 1);
    mesh m = quad();
    const char *names[] = {"WallTime", "VSInvocations"};
    counters_session *s = measure(ctx, names, 2, &m, 1);
    int passes;
    counters_num_passes(s, &passes);
    assert_int_equal(passes, 1);                  /* the statistics pass has nothing left */
    double v = -1;
    assert_int_equal(counters_result(s, 0, "VSInvocations", &v), DM_ERR_UNAVAILABLE);
    assert_true(v == -1);
    assert_non_null(strstr(counters_last_error(s), "driver lacks GL_ARB_pipeline_statistics_query"));
    assert_true(result(s, "WallTime") > 0);
    counters_session_destroy(s);
    mesh_free(&m);
    counters_context_destroy(ctx);
}

/* Timing and geometry passes: clocks are positive, the geometry pass runs
 * with GL_RASTERIZER_DISCARD on and restores it, GPUTime is plausible. */
static void test_timing_and_geometry_passes(void **state)
{
    (void)state;
    mesh m = quad();
    counters_session *s;
    counters_session_create(F.ctx, &s);
    const char *names[] = {"WallTime", "CPUTime", "SubmitTime", "GPUTime", "GeometryTime", "RasterTime"};
    for (size_t i = 0; i < 6; i++)
        assert_int_equal(counters_enable(s, names[i]), 0);
    int passes;
    counters_num_passes(s, &passes);
    assert_int_equal(passes, 2);
    for (int p = 0; p < passes; p++) {
        counters_pass_begin(s, p);
        for (uint32_t id = 10; id < 12; id++) {
            counters_sample_begin(s, id);
            int geometry = strcmp(counters_pass_name(s, p), "geometry") == 0;
            assert_int_equal(glIsEnabled(GL_RASTERIZER_DISCARD), geometry);
            mesh_draw(&m);
            counters_sample_end(s);
        }
        counters_pass_end(s);
        assert_false(glIsEnabled(GL_RASTERIZER_DISCARD));
    }
    counters_set_value(s, 10, "SetupTime", 1234);
    assert_int_equal(counters_session_end(s), 0);
    double wall, geo, raster, gpu, setup, v;
    for (uint32_t id = 10; id < 12; id++) {
        assert_int_equal(counters_result(s, id, "WallTime", &wall), 0);
        assert_int_equal(counters_result(s, id, "GeometryTime", &geo), 0);
        assert_int_equal(counters_result(s, id, "RasterTime", &raster), 0);
        assert_true(wall > 0 && geo > 0);
        assert_true(raster == wall - geo);
        int rc = counters_result(s, id, "GPUTime", &gpu);
        assert_true(rc == 0 || rc == DM_ERR_UNAVAILABLE);
        if (rc == 0)
            assert_true(gpu <= 1.5 * wall + 1e6);
        assert_int_equal(counters_result(s, id, "CPUTime", &v), 0);
        assert_int_equal(counters_result(s, id, "SubmitTime", &v), 0);
    }
    assert_int_equal(counters_result(s, 10, "SetupTime", &setup), 0);
    assert_true(setup == 1234);
    assert_int_equal(counters_result(s, 11, "SetupTime", &setup), DM_ERR_UNAVAILABLE);
    assert_non_null(strstr(counters_last_error(s), "not set by the caller"));
    counters_session_destroy(s);
    mesh_free(&m);
}

/* Two samples with different work in one session keep their own totals. */
static void test_samples_are_separate(void **state)
{
    (void)state;
    mesh m = quad();
    counters_session *s;
    counters_session_create(F.ctx, &s);
    counters_enable(s, "SamplesPassed");
    counters_pass_begin(s, 0);
    for (uint32_t id = 1; id <= 3; id++) {
        counters_sample_begin(s, id);
        for (uint32_t d = 0; d < id; d++)
            mesh_draw(&m);
        counters_sample_end(s);
    }
    counters_pass_end(s);
    counters_session_end(s);
    for (uint32_t id = 1; id <= 3; id++) {
        double v;
        assert_int_equal(counters_result(s, id, "SamplesPassed", &v), 0);
        assert_int_equal((long)v, (long)id * W * H);
    }
    counters_session_destroy(s);
    mesh_free(&m);
}

static void test_calibration(void **state)
{
    (void)state;
    counters_timer_calibration cal;
    assert_int_equal(counters_calibrate_timer(F.ctx, &cal), 0);
    assert_true(cal.wall_ns > 5e6 && cal.wall_ns < 3e9);   /* a real, fenced heavy draw */
    assert_true(cal.coverage == cal.gpu_ns / cal.wall_ns);
    assert_string_equal(cal.verdict, cal.coverage < 0.5 ? "partial" : "full");
    assert_non_null(strstr(counters_driver_note(F.ctx, "GPUTime"), cal.verdict));
    GLint fbo;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    assert_int_equal(fbo, (GLint)F.fbo);                   /* caller's state restored */
    counters_context *ctx;
    counters_context_create(&ctx);
    counters_context_hide_extension(ctx, "GL_ARB_timer_query");
    assert_int_equal(counters_calibrate_timer(ctx, &cal), DM_ERR_UNAVAILABLE);
    assert_string_equal(cal.verdict, "unavailable");
    counters_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fullscreen_quad_samples),
        cmocka_unit_test(test_grid_vertex_reuse),
        cmocka_unit_test(test_clipping),
        cmocka_unit_test(test_zero_denominator_unavailable),
        cmocka_unit_test(test_fs_block_note),
        cmocka_unit_test(test_pass_plans),
        cmocka_unit_test(test_plan_describe),
        cmocka_unit_test(test_misuse),
        cmocka_unit_test(test_hidden_pipeline_statistics),
        cmocka_unit_test(test_timing_and_geometry_passes),
        cmocka_unit_test(test_samples_are_separate),
        cmocka_unit_test(test_calibration),
    };
    if (getenv("COUNTERS_TEST_FILTER"))         /* run one test by hand, e.g. under ASan */
        cmocka_set_test_filter(getenv("COUNTERS_TEST_FILTER"));
    return cmocka_run_group_tests(tests, setup, teardown);
}
