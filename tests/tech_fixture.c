/* tech_fixture.c — the GL fixture shared by the techniques GL tests: a
 * surfaceless context, a renderer and an RGBA32F + depth render target. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <epoxy/gl.h>
#include <stdio.h>

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
    if (tech_renderer_create(&F.r) != 0)
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
    tech_renderer_destroy(F.r);
    gl_context_destroy(F.ctx);
    return 0;
}
