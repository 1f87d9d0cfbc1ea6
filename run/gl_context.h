/* gl_context.h — creating an OpenGL 4.5 core context.
 *
 * Default backend: EGL surfaceless (EGL_PLATFORM_SURFACELESS_MESA, no X
 * server; render into FBOs).  GLFW (hidden or visible window) when asked and
 * a display exists.  KHR_debug messages are captured into a buffer the
 * caller drains per configuration (gl_context_take_messages).
 */
#ifndef RUN_GL_CONTEXT_H
#define RUN_GL_CONTEXT_H

#include "core/dm_util.h"

typedef enum gl_backend {
    GL_BACKEND_DEFAULT = 0,     /* EGL surfaceless */
    GL_BACKEND_EGL,
    GL_BACKEND_GLFW_HIDDEN,
    GL_BACKEND_GLFW_WINDOW
} gl_backend;

typedef struct gl_context_desc {
    gl_backend backend;
    int width, height;          /* GLFW window size; 0 = 640x480 */
    const char *title;
    int debug;                  /* 0 = on (KHR_debug capture), -1 = off */
} gl_context_desc;

typedef struct gl_context gl_context;

/* Creates the context and makes it current.  Returns 0, or DM_ERR_GL /
 * DM_ERR_UNSUPPORTED with a message in err (e.g. no display for GLFW). */
int gl_context_create(const gl_context_desc *desc, gl_context **out, dm_str *err);
void gl_context_destroy(gl_context *ctx);
/* Replaces an EGL context by a fresh one on the same display (the driver's
 * screen, its shader caches and JIT stay; every GL object, name and
 * per-context state of the old one is gone) and makes it current.
 * Returns 0, DM_ERR_UNSUPPORTED for a GLFW context, or DM_ERR_GL. */
int gl_context_renew(gl_context *ctx);
/* Creates one more EGL context on the same display (fresh, as
 * gl_context_renew makes) and makes it current; the others stay alive, each
 * to be made current again by gl_context_use with its index (the first
 * context is 0; gl_context_renew replaces the current one in place).
 * Returns the new index, or -1 (a GLFW context, or EGL failed: the old
 * context stays current). */
int gl_context_add(gl_context *ctx);
/* Makes context `index` (0, or one gl_context_add returned) current.
 * Returns 0, DM_ERR_UNSUPPORTED (no such context) or DM_ERR_GL. */
int gl_context_use(gl_context *ctx, int index);
/* Destroys context `index` (> 0, from gl_context_add); when it was
 * current, no context is current until gl_context_use. */
void gl_context_drop(gl_context *ctx, int index);
/* GLFW window handle (GLFWwindow*) or NULL for EGL. */
void *gl_context_window(gl_context *ctx);
/* Number of KHR_debug errors (type error or undefined behaviour) seen since
 * the last take; moves the text of those and of other medium/high-severity
 * messages (e.g. shader compiler warnings) into out (may be NULL). */
int gl_context_take_messages(gl_context *ctx, dm_str *out);
/* Drains glGetError; returns the number of errors and appends them to out. */
int gl_context_check_errors(dm_str *out);

#endif
