/* tech_fixture.c — the GL fixture shared by the techniques GL tests: a
 * surfaceless context, a renderer and an RGBA32F + depth render target. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_util.h"

#include "tests/tech_fixture.h"

fixture F;

void target(int w, int h)
{
    if (F.fbo) {
        glDeleteFramebuffers(1, &F.fbo);
        glDeleteRenderbuffers(1, &F.color);
        glDeleteRenderbuffers(1, &F.depth);
    }
    glCreateFramebuffers(1, &F.fbo);
    glCreateRenderbuffers(1, &F.color);
    glCreateRenderbuffers(1, &F.depth);
    glNamedRenderbufferStorage(F.color, GL_RGBA32F, w, h);
    glNamedRenderbufferStorage(F.depth, GL_DEPTH_COMPONENT24, w, h);
    glNamedFramebufferRenderbuffer(F.fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, F.color);
    glNamedFramebufferRenderbuffer(F.fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, F.depth);
    assert_int_equal(glCheckNamedFramebufferStatus(F.fbo, GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    glBindFramebuffer(GL_FRAMEBUFFER, F.fbo);
    F.w = w;
    F.h = h;
}

int techfix_setup(void **state, int w, int h)
{
    (void)state;
    dm_str e = {0};
    if (gl_context_create(NULL, &F.ctx, &e) != 0) {
        fprintf(stderr, "no GL context: %s\n", dm_str_get(&e));
        return -1;
    }
    dm_str_free(&e);
    if (render_create(&F.r) != 0)
        return -1;
    target(w, h);
    return 0;
}

int teardown(void **state)
{
    (void)state;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &F.fbo);
    glDeleteRenderbuffers(1, &F.color);
    glDeleteRenderbuffers(1, &F.depth);
    render_destroy(F.r);
    gl_context_destroy(F.ctx);
    return 0;
}


/* Renders spec at the current target into a malloc'd RGBA float image. */
float *render(const char *spec)
{
    render_item it = spec_prepare(F.r, spec, 0, NULL);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    float *px = malloc((size_t)F.w * (size_t)F.h * 4 * sizeof(float));
    glReadPixels(0, 0, F.w, F.h, GL_RGBA, GL_FLOAT, px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    render_release(F.r, it);
    return px;
}

size_t non_finite(const float *px, size_t n)
{
    size_t bad = 0;
    for (size_t i = 0; i < 4 * n; i++)
        bad += !isfinite(px[i]);
    return bad;
}

double luma_stddev(const float *px, size_t n)
{
    double s = 0, s2 = 0;
    for (size_t i = 0; i < n; i++) {
        double y = 0.2126 * px[4 * i] + 0.7152 * px[4 * i + 1] + 0.0722 * px[4 * i + 2];
        s += y;
        s2 += y * y;
    }
    double m = s / (double)n;
    return sqrt(fmax(0, s2 / (double)n - m * m));
}

/* PSNR over RGB with peak 1; INFINITY when identical. */
double psnr(const float *a, const float *b, size_t n)
{
    double se = 0;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double d = (double)a[4 * i + (size_t)c] - (double)b[4 * i + (size_t)c];
            se += d * d;
        }
    double mse = se / (double)(3 * n);
    return mse == 0 ? INFINITY : 10 * log10(1 / mse);
}

size_t npix(void) { return (size_t)F.w * (size_t)F.h; }

size_t out_of_range(const float *px, size_t n)
{
    size_t bad = 0;
    for (size_t i = 0; i < n * 4; i++)
        bad += !isfinite(px[i]) || px[i] < 0.0f || px[i] > 1e4f;
    return bad;
}

void render_expect_in_range(const char *spec)
{
    float *px = render(spec);
    size_t bad = out_of_range(px, npix());
    if (bad)
        fail_msg("%s: %zu values non-finite or outside [0, 1e4]", spec, bad);
    free(px);
}

void draw_queried(const char *spec, const GLenum *targets, int n, GLuint64 *out)
{
    assert_true(n >= 1 && n <= 8);
    render_item it = spec_prepare(F.r, spec, 0, NULL);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    GLuint q[8];
    glGenQueries(n, q);
    for (int i = 0; i < n; i++)
        glBeginQuery(targets[i], q[i]);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    for (int i = 0; i < n; i++)
        glEndQuery(targets[i]);
    for (int i = 0; i < n; i++)
        glGetQueryObjectui64v(q[i], GL_QUERY_RESULT, &out[i]);
    glDeleteQueries(n, q);
    render_release(F.r, it);
}
