/* counters_gl.c — the few GL objects counters/ makes for its own probes:
 * an offscreen target, a tiny program, saved bindings, query reads. */
#include "counters_internal.h"
#include "core/dm_error.h"

#include <epoxy/gl.h>

void counters__glstate_save(counters__glstate *st)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &st->fbo);
    glGetIntegerv(GL_VIEWPORT, st->vp);
    glGetIntegerv(GL_CURRENT_PROGRAM, &st->prog);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &st->vao);
}

void counters__glstate_restore(const counters__glstate *st)
{
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)st->fbo);
    glViewport(st->vp[0], st->vp[1], st->vp[2], st->vp[3]);
    glUseProgram((GLuint)st->prog);
    glBindVertexArray((GLuint)st->vao);
}

/* Creates an RGBA8 renderbuffer FBO of w x h and an empty VAO, binds both
 * and sets the viewport.  DM_ERR_GL (nothing left allocated) if incomplete. */
int counters__target_create(counters__target *t, int w, int h)
{
    t->w = w;
    t->h = h;
    glGenRenderbuffers(1, &t->rb);
    glBindRenderbuffer(GL_RENDERBUFFER, t->rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->rb);
    glGenVertexArrays(1, &t->vao);
    glBindVertexArray(t->vao);
    glViewport(0, 0, w, h);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        counters__target_destroy(t);
        return DM_ERR_GL;
    }
    return 0;
}

void counters__target_destroy(counters__target *t)
{
    glDeleteVertexArrays(1, &t->vao);
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteRenderbuffers(1, &t->rb);
    t->vao = t->fbo = t->rb = 0;
}

static GLuint gl__shader(GLenum type, const char *src, dm_str *err)
{
    GLuint sh = glCreateShader(type);
    glShaderSource(sh, 1, &src, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        if (err)
            dm_str_printf(err, "counters: shader compile failed: %s", log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

int counters__program(const char *vs, const char *fs, unsigned *prog, dm_str *err)
{
    GLuint v = gl__shader(GL_VERTEX_SHADER, vs, err);
    GLuint f = v ? gl__shader(GL_FRAGMENT_SHADER, fs, err) : 0;
    if (!f) {
        glDeleteShader(v);
        return DM_ERR_SHADER;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        if (err)
            dm_str_cat(err, "counters: program link failed");
        glDeleteProgram(p);
        return DM_ERR_SHADER;
    }
    *prog = p;
    return 0;
}

int counters__query_read(unsigned q, uint64_t *out)
{
    GLuint64 v = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &v);
    if (glGetError() != GL_NO_ERROR)
        return DM_ERR_GL;
    *out = v;
    return 0;
}
