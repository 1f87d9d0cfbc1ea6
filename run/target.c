#include "target.h"
#include "core/dm_error.h"

#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

int target_create(target *t, int w, int h)
{
    memset(t, 0, sizeof *t);
    GLint max = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max);
    if (w < 1 || h < 1 || w > max || h > max)
        return DM_ERR_RANGE;
    t->w = w;
    t->h = h;
    glCreateTextures(GL_TEXTURE_2D, 1, &t->color);
    glTextureStorage2D(t->color, 1, GL_RGBA32F, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &t->depth);
    glTextureStorage2D(t->depth, 1, GL_DEPTH_COMPONENT32F, w, h);
    glCreateFramebuffers(1, &t->fbo);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->color, 0);
    glNamedFramebufferTexture(t->fbo, GL_DEPTH_ATTACHMENT, t->depth, 0);
    if (glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        target_destroy(t);
        return DM_ERR_GL;
    }
    target_bind(t);
    return 0;
}

void target_bind(const target *t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
}

/* Flips rows in place: GL reads bottom-up. */
static void target__flip(float *px, int w, int h, int channels)
{
    size_t row = (size_t)w * (size_t)channels;
    float *tmp = malloc(row * sizeof *tmp);
    if (!tmp)
        return;
    for (int y = 0; y < h / 2; y++) {
        float *a = px + (size_t)y * row, *b = px + (size_t)(h - 1 - y) * row;
        memcpy(tmp, a, row * sizeof *tmp);
        memcpy(a, b, row * sizeof *tmp);
        memcpy(b, tmp, row * sizeof *tmp);
    }
    free(tmp);
}

void target_read(const target *t, float *rgba, float *depth)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, t->w, t->h, GL_RGBA, GL_FLOAT, rgba);
    target__flip(rgba, t->w, t->h, 4);
    if (depth) {
        glReadPixels(0, 0, t->w, t->h, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
        target__flip(depth, t->w, t->h, 1);
    }
}

void target_destroy(target *t)
{
    if (t->fbo)
        glDeleteFramebuffers(1, &t->fbo);
    if (t->color)
        glDeleteTextures(1, &t->color);
    if (t->depth)
        glDeleteTextures(1, &t->depth);
    memset(t, 0, sizeof *t);
}
