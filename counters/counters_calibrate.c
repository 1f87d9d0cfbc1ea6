/* counters_calibrate.c — how much of the work GL_TIME_ELAPSED covers,
 * measured on a fragment-bound draw of our own (docs/counters.md). */
#include "counters_internal.h"
#include "core/dm_error.h"

#include <epoxy/gl.h>
#include <stdio.h>

#define CAL_SIZE 512
#define CAL_REPS 3
/* Each draw aims at ~25 ms: every run's driver probe pays the three, so
 * 100 ms draws cost a tiny run a fifth of its time; the ratio barely moves
 * (llvmpipe: 0.0162 at 25 ms, 0.0168-0.0170 at 100 ms; docs/counters.md). */
#define CAL_TARGET_NS 25e6

static const char *cal__vs = "#version 450 core\n"
    "void main() {\n"
    "    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);\n"
    "    gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";
static const char *cal__fs = "#version 450 core\n"
    "uniform int u_iters;\nout vec4 c;\n"
    "void main() {\n"
    "    float a = gl_FragCoord.x * 0.001, b = gl_FragCoord.y * 0.001;\n"
    "    for (int i = 0; i < u_iters; i++) {\n"
    "        a = fract(sin(a * 12.9898 + b) * 43758.5453);\n"
    "        b = b * 0.999 + a * 0.001;\n"
    "    }\n"
    "    c = vec4(a, b, 0.0, 1.0);\n"
    "}\n";

/* One fenced draw with iters loop iterations; wall ns, and gpu ns if q. */
static double cal__draw(unsigned prog, int iters, unsigned q, uint64_t *gpu)
{
    glUniform1i(glGetUniformLocation(prog, "u_iters"), iters);
    glFinish();
    int64_t t0 = dm_now_ns();
    if (q)
        glBeginQuery(GL_TIME_ELAPSED, q);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (q)
        glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    double wall = (double)(dm_now_ns() - t0);
    if (q && counters__query_read(q, gpu))
        *gpu = UINT64_MAX;              /* rejected below like a raw timestamp */
    return wall;
}

static void cal__sort3(double *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
            double t = v[j]; v[j] = v[j - 1]; v[j - 1] = t;
        }
}

/* Scales the loop count so one draw takes about CAL_TARGET_NS, then takes
 * CAL_REPS timed draws; fills out with the median-coverage draw.  Returns 0,
 * or DM_ERR_UNAVAILABLE when no draw gave a plausible timer value. */
static int cal__measure(unsigned prog, counters_timer_calibration *out)
{
    cal__draw(prog, 1, 0, NULL);        /* first draw JIT-compiles */
    double t = cal__draw(prog, 64, 0, NULL);
    double scaled = 64.0 * CAL_TARGET_NS / (t > 1.0 ? t : 1.0);
    int iters = scaled < 16 ? 16 : scaled > 65536 ? 65536 : (int)scaled;
    double cov[CAL_REPS], gpu[CAL_REPS], wall[CAL_REPS];
    int n = 0;
    GLuint q;
    glGenQueries(1, &q);
    for (int r = 0; r < CAL_REPS; r++) {
        uint64_t g = 0;
        double w = cal__draw(prog, iters, q, &g);
        if ((double)g > 1.5 * w + 1e6)
            continue;                   /* not a duration */
        cov[n] = (double)g / w; gpu[n] = (double)g; wall[n] = w;
        n++;
    }
    glDeleteQueries(1, &q);
    if (n == 0)
        return DM_ERR_UNAVAILABLE;
    double sorted[CAL_REPS];
    for (int i = 0; i < n; i++)
        sorted[i] = cov[i];
    cal__sort3(sorted, n);
    int m = 0;
    while (cov[m] != sorted[n / 2])
        m++;
    out->coverage = cov[m];
    out->gpu_ns = gpu[m];
    out->wall_ns = wall[m];
    out->verdict = out->coverage < 0.5 ? "partial" : "full";
    return 0;
}

int counters_calibrate_timer(counters_context *ctx, counters_timer_calibration *out)
{
    *out = (counters_timer_calibration){0, 0, 0, "unavailable"};
    if (!counters__has_ext(ctx, "GL_ARB_timer_query"))
        return DM_ERR_UNAVAILABLE;
    counters__glstate st;
    counters__glstate_save(&st);
    counters__target tgt;
    unsigned prog = 0;
    int rc = counters__target_create(&tgt, CAL_SIZE, CAL_SIZE);
    if (rc == 0) {
        rc = counters__program(cal__vs, cal__fs, &prog, NULL);
        if (rc == 0) {
            glUseProgram(prog);
            rc = cal__measure(prog, out);
            glDeleteProgram(prog);
        }
        counters__target_destroy(&tgt);
    }
    counters__glstate_restore(&st);
    if (rc == 0)
        snprintf(ctx->gpu_note, sizeof ctx->gpu_note,
                 "GL_TIME_ELAPSED covered %.1f%% of fenced wall time on a fragment-bound "
                 "calibration draw: %s%s", 100.0 * out->coverage, out->verdict,
                 out->coverage < 0.5 ? " (recorded, never used to gate or fit)" : "");
    return rc;
}
