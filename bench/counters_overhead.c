/* counters_overhead.c — what measuring costs: per-frame wall time of a fixed
 * moderate draw (fullscreen 64x64-vertex grid into a 512x512 FBO, K frames
 * per sample) with no session (raw clock + glFinish), inside a timing-pass
 * sample and inside a statistics-pass sample.  Modes alternate in rounds so
 * drift hits all alike; medians and overhead in percent are printed.
 * Asserts the work was done (SamplesPassed = K * 512 * 512). */
#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "counters/counters.h"
#include "run/gl_context.h"

#define SIZE 512
#define GRID 64
#define FRAMES 10
#define ROUNDS 15

enum { MODE_RAW, MODE_TIMING, MODE_STATS, MODES };
static const char *const mode_names[MODES] = {"raw (no session)", "timing pass", "statistics pass"};

static GLuint scene_setup(GLsizei *count)
{
    const char *vs = "#version 450 core\nlayout(location = 0) in vec2 p;\nout vec2 uv;\n"
                     "void main() { uv = p; gl_Position = vec4(p, 0.0, 1.0); }\n";
    const char *fs = "#version 450 core\nin vec2 uv;\nout vec4 c;\n"
                     "void main() { c = vec4(abs(sin(uv * 31.0)), 0.5, 1.0); }\n";
    GLuint p = glCreateProgram();
    const char *src[2] = {vs, fs};
    GLenum type[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint sh = glCreateShader(type[i]);
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        glAttachShader(p, sh);
        glDeleteShader(sh);
    }
    glLinkProgram(p);
    glUseProgram(p);
    float *xy = malloc(2 * GRID * GRID * sizeof *xy);
    unsigned *idx = malloc(6 * (GRID - 1) * (GRID - 1) * sizeof *idx), k = 0;
    for (int y = 0; y < GRID; y++)
        for (int x = 0; x < GRID; x++) {
            xy[2 * (y * GRID + x)] = -1.0f + 2.0f * (float)x / (GRID - 1);
            xy[2 * (y * GRID + x) + 1] = -1.0f + 2.0f * (float)y / (GRID - 1);
        }
    for (unsigned y = 0; y + 1 < GRID; y++)
        for (unsigned x = 0; x + 1 < GRID; x++) {
            unsigned a = y * GRID + x, tri[6] = {a, a + 1, a + GRID + 1, a, a + GRID + 1, a + GRID};
            for (int i = 0; i < 6; i++)
                idx[k++] = tri[i];
        }
    GLuint vao, b[2];
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, b);
    glBindBuffer(GL_ARRAY_BUFFER, b[0]);
    glBufferData(GL_ARRAY_BUFFER, 2 * GRID * GRID * sizeof *xy, xy, GL_STATIC_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, k * sizeof *idx, idx, GL_STATIC_DRAW);
    free(xy);
    free(idx);
    *count = (GLsizei)k;
    return p;
}

static void frames(GLsizei count)
{
    for (int f = 0; f < FRAMES; f++)
        glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, NULL);
}

/* One sample of FRAMES frames in the given mode; per-frame ns, fenced by
 * the outer clock.  *samples gets SamplesPassed in the statistics mode. */
static double run_mode(counters_context *ctx, int mode, GLsizei count, double *samples)
{
    counters_session *s = NULL;
    if (mode != MODE_RAW) {
        counters_session_create(ctx, &s);
        counters_enable(s, mode == MODE_TIMING ? "WallTime" : "SamplesPassed");
        counters_enable_group(s, mode == MODE_TIMING ? "Timing" : "Vertex");
        counters_pass_begin(s, 0);
    }
    glFinish();
    int64_t t0 = dm_now_ns();
    if (s)
        counters_sample_begin(s, 0);
    frames(count);
    if (s)
        counters_sample_end(s);
    glFinish();
    double ns = (double)(dm_now_ns() - t0) / FRAMES;
    if (s) {
        counters_pass_end(s);
        counters_session_end(s);
        if (mode == MODE_STATS && counters_result(s, 0, "SamplesPassed", samples))
            *samples = -1;
        counters_session_destroy(s);
    }
    return ns;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(void)
{
    gl_context *gl;
    dm_str err = {0};
    if (gl_context_create(NULL, &gl, &err)) {
        fprintf(stderr, "bench_counters_overhead: %s\n", dm_str_get(&err));
        return 1;
    }
    GLuint rb, fbo;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, SIZE, SIZE);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glViewport(0, 0, SIZE, SIZE);
    GLsizei count;
    scene_setup(&count);
    counters_context *ctx;
    counters_context_create(&ctx);
    double t[MODES][ROUNDS], samples = 0;
    run_mode(ctx, MODE_RAW, count, &samples);           /* warm-up: shader JIT */
    for (int r = 0; r < ROUNDS; r++)
        for (int m = 0; m < MODES; m++)
            t[(m + r) % MODES][r] = run_mode(ctx, (m + r) % MODES, count, &samples);
    if (samples != (double)FRAMES * SIZE * SIZE) {
        fprintf(stderr, "bench_counters_overhead: SamplesPassed %.0f, expected %d: work not done\n",
                samples, FRAMES * SIZE * SIZE);
        return 1;
    }
    printf("counters overhead: %dx%d grid into %dx%d, %d frames/sample, median of %d rounds\n",
           GRID, GRID, SIZE, SIZE, FRAMES, ROUNDS);
    double raw = 0;
    for (int m = 0; m < MODES; m++) {
        qsort(t[m], ROUNDS, sizeof t[m][0], cmp);
        double med = t[m][ROUNDS / 2];
        if (m == MODE_RAW)
            raw = med;
        printf("  %-18s %9.3f ms/frame  %+6.2f %%\n", mode_names[m], med / 1e6,
               100.0 * (med - raw) / raw);
    }
    counters_context_destroy(ctx);
    gl_context_destroy(gl);
    dm_str_free(&err);
    return 0;
}
