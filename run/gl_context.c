#include "gl_context.h"
#include "core/dm_error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

struct gl_context {
    gl_backend backend;
    EGLDisplay dpy;
    EGLContext egl;             /* the current one: all[cur] */
    EGLContext *all;            /* every EGL context of the display made here, [0] the first */
    int n_all, cur;             /* cur -1: none current (gl_context_drop) */
    int debug;                  /* KHR_debug capture on every context */
    GLFWwindow *win;
    dm_str messages;
    int n_messages;
};

static void GLAPIENTRY gl__debug_cb(GLenum source, GLenum type, GLuint id, GLenum severity,
                                    GLsizei length, const GLchar *msg, const void *user)
{
    (void)source;
    (void)id;
    (void)length;
    gl_context *ctx = (gl_context *)user;
    int error = type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR;
    if (!error && (severity == GL_DEBUG_SEVERITY_NOTIFICATION || severity == GL_DEBUG_SEVERITY_LOW))
        return;
    /* Errors fail the configuration; other messages (shader compiler
     * warnings, performance notes) are kept in its log only. */
    ctx->n_messages += error;
    if (ctx->messages.len < 16384)
        dm_str_printf(&ctx->messages, "GL debug %s: %s\n", error ? "error" : "message", msg);
}

/* Why EGL could not initialise.  Under an address-space limit (ulimit -v)
 * Mesa cannot map llvmpipe's driver and code memory, and fails exactly as if
 * it were not installed; the limit, or ENOMEM left by the failed mapping,
 * names the real cause instead of sending the user to reinstall Mesa. */
#define GL__AS_SUSPECT ((rlim_t)8 << 30)   /* limits below 8 GB are suspected */

static void gl__egl_init_failure(int saved_errno, dm_str *err)
{
    struct rlimit as;
    int limited = getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY &&
                  as.rlim_cur < GL__AS_SUSPECT;
    if (limited)   /* llvmpipe maps its driver, LLVM and thread stacks: several hundred MB */
        dm_str_printf(err, "EGL: cannot initialise a surfaceless display: llvmpipe could not map "
                      "its memory under the address-space limit of %llu MB (ulimit -v %llu); "
                      "raise it (ulimit -v unlimited) and run again",
                      (unsigned long long)(as.rlim_cur >> 20),
                      (unsigned long long)(as.rlim_cur >> 10));
    else if (saved_errno == ENOMEM)
        dm_str_cat(err, "EGL: cannot initialise a surfaceless display: out of memory while "
                        "loading llvmpipe; free memory (or check ulimit -v) and run again");
    else
        dm_str_cat(err, "EGL: cannot initialise a surfaceless display "
                        "(is Mesa's EGL installed? run scripts/install-deps)");
}

/* KHR_debug capture on the current context (gl_context_create). */
static void gl__debug_output(gl_context *ctx)
{
    if (epoxy_has_gl_extension("GL_KHR_debug")) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(gl__debug_cb, ctx);
    }
}

static const EGLint gl__egl_attrs[] = {
    EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
    EGL_NONE };

static int gl__create_egl(gl_context *ctx, dm_str *err)
{
    errno = 0;
    /* Without an EGL vendor offering platform displays (no Mesa, a bad
     * __EGL_VENDOR_LIBRARY_FILENAMES, or its library not mappable) libepoxy
     * would abort on the call below: ask for the client extension first. */
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base")) {
        gl__egl_init_failure(errno, err);
        return DM_ERR_GL;
    }
    ctx->dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (ctx->dpy == EGL_NO_DISPLAY || !eglInitialize(ctx->dpy, &major, &minor)) {
        gl__egl_init_failure(errno, err);
        return DM_ERR_GL;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        dm_str_cat(err, "EGL: desktop OpenGL API not available");
        return DM_ERR_GL;
    }
    ctx->egl = eglCreateContext(ctx->dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, gl__egl_attrs);
    if (ctx->egl == EGL_NO_CONTEXT ||
        !eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl)) {
        dm_str_printf(err, "EGL: cannot create an OpenGL 4.5 core context (EGL error 0x%x)",
                      (unsigned)eglGetError());
        return DM_ERR_GL;
    }
    ctx->all = dm_xcalloc(1, sizeof *ctx->all);
    ctx->all[0] = ctx->egl;
    ctx->n_all = 1;
    return 0;
}

static int gl__create_glfw(gl_context *ctx, const gl_context_desc *d, dm_str *err)
{
    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        dm_str_cat(err, "no display available for a window (DISPLAY is not set); "
                        "run under xvfb-run, or use the headless commands (run, render)");
        return DM_ERR_UNSUPPORTED;
    }
    if (!glfwInit()) {
        dm_str_cat(err, "GLFW could not initialise (no usable display?); try xvfb-run");
        return DM_ERR_UNSUPPORTED;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, d->backend == GL_BACKEND_GLFW_WINDOW ? GLFW_TRUE : GLFW_FALSE);
    int w = d->width ? d->width : 640, h = d->height ? d->height : 480;
    ctx->win = glfwCreateWindow(w, h, d->title ? d->title : "dmbench", NULL, NULL);
    if (!ctx->win) {
        glfwTerminate();
        dm_str_cat(err, "GLFW could not create an OpenGL 4.5 core window");
        return DM_ERR_UNSUPPORTED;
    }
    glfwMakeContextCurrent(ctx->win);
    glfwSwapInterval(0);
    return 0;
}

int gl_context_create(const gl_context_desc *desc, gl_context **out, dm_str *err)
{
    gl_context_desc d = desc ? *desc : (gl_context_desc){0};
    if (d.backend == GL_BACKEND_DEFAULT)
        d.backend = GL_BACKEND_EGL;
    gl_context *ctx = dm_xcalloc(1, sizeof *ctx);
    ctx->backend = d.backend;
    int rc = d.backend == GL_BACKEND_EGL ? gl__create_egl(ctx, err) : gl__create_glfw(ctx, &d, err);
    if (rc != 0) {
        free(ctx);
        return rc;
    }
    if (epoxy_gl_version() < 45) {
        dm_str_printf(err, "OpenGL 4.5 required, the driver gives %d.%d",
                      epoxy_gl_version() / 10, epoxy_gl_version() % 10);
        gl_context_destroy(ctx);
        return DM_ERR_UNSUPPORTED;
    }
    ctx->debug = d.debug == 0;
    if (ctx->debug)
        gl__debug_output(ctx);
    *out = ctx;
    return 0;
}

/* A fresh EGL context on ctx's display, made current, with KHR_debug
 * capture when `debug`; EGL_NO_CONTEXT when it cannot be made. */
static EGLContext gl__fresh_egl(gl_context *ctx, int debug)
{
    EGLContext e = eglCreateContext(ctx->dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, gl__egl_attrs);
    if (e == EGL_NO_CONTEXT)
        return e;
    if (!eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, e)) {
        eglDestroyContext(ctx->dpy, e);
        return EGL_NO_CONTEXT;
    }
    if (debug)
        gl__debug_output(ctx);
    return e;
}

int gl_context_renew(gl_context *ctx)
{
    if (ctx->backend != GL_BACKEND_EGL)
        return DM_ERR_UNSUPPORTED;
    if (ctx->cur < 0)
        return DM_ERR_GL;
    eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(ctx->dpy, ctx->egl);
    ctx->egl = ctx->all[ctx->cur] = gl__fresh_egl(ctx, ctx->debug);
    return ctx->egl == EGL_NO_CONTEXT ? DM_ERR_GL : 0;
}

int gl_context_add(gl_context *ctx)
{
    if (ctx->backend != GL_BACKEND_EGL)
        return -1;
    EGLContext e = gl__fresh_egl(ctx, ctx->debug);
    if (e == EGL_NO_CONTEXT) {
        if (ctx->egl != EGL_NO_CONTEXT)   /* the old one stays current */
            eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl);
        return -1;
    }
    ctx->all = dm_xrealloc(ctx->all, (size_t)(ctx->n_all + 1) * sizeof *ctx->all);
    ctx->cur = ctx->n_all++;
    ctx->all[ctx->cur] = ctx->egl = e;
    return ctx->cur;
}

void gl_context_drop(gl_context *ctx, int index)
{
    if (ctx->backend != GL_BACKEND_EGL || index <= 0 || index >= ctx->n_all || ctx->all[index] == EGL_NO_CONTEXT)
        return;
    if (index == ctx->cur) {
        eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        ctx->egl = EGL_NO_CONTEXT;
        ctx->cur = -1;
    }
    eglDestroyContext(ctx->dpy, ctx->all[index]);
    ctx->all[index] = EGL_NO_CONTEXT;
}

int gl_context_use(gl_context *ctx, int index)
{
    if (ctx->backend != GL_BACKEND_EGL || index < 0 || index >= ctx->n_all || ctx->all[index] == EGL_NO_CONTEXT)
        return DM_ERR_UNSUPPORTED;
    if (index != ctx->cur && !eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->all[index]))
        return DM_ERR_GL;
    ctx->cur = index;
    ctx->egl = ctx->all[index];
    return 0;
}

void gl_context_destroy(gl_context *ctx)
{
    if (!ctx)
        return;
    if (ctx->backend == GL_BACKEND_EGL) {
        eglMakeCurrent(ctx->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        for (int i = 0; i < ctx->n_all; i++)
            if (ctx->all[i] != EGL_NO_CONTEXT)
                eglDestroyContext(ctx->dpy, ctx->all[i]);
        free(ctx->all);
        eglTerminate(ctx->dpy);
    } else if (ctx->win) {
        glfwDestroyWindow(ctx->win);
        glfwTerminate();
    }
    dm_str_free(&ctx->messages);
    free(ctx);
}

void *gl_context_window(gl_context *ctx) { return ctx->win; }

int gl_context_take_messages(gl_context *ctx, dm_str *out)
{
    int n = ctx->n_messages;
    if (out && ctx->messages.len)
        dm_str_cat(out, dm_str_get(&ctx->messages));
    dm_str_free(&ctx->messages);
    ctx->n_messages = 0;
    return n;
}

int gl_context_check_errors(dm_str *out)
{
    int n = 0;
    for (GLenum e; (e = glGetError()) != GL_NO_ERROR && n < 32; n++)
        if (out)
            dm_str_printf(out, "glGetError: 0x%04x\n", (unsigned)e);
    return n;
}
