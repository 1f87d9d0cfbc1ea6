/* viewer.c — the window loop of `dmbench view`: every technique live in a GLFW window.
 *
 * The viewer is a thin loop around the batch path: the techniques renderer
 * draws the configuration into the window (framebuffer 0), the counters
 * library measures it (live every VIEWER__LIVE_EVERY frames, and the timed
 * test `T`), and input goes through viewer_state (keys, mouse, `--keys`
 * scripts alike).  Frame counts, scripts and a final screenshot make it
 * scriptable for tests; see docs/viewer.md.
 */
#include "viewer/viewer.h"
#include "core/dm_error.h"
#include "run/gl_context.h"
#include "viewer/viewer_measure.h"
#include "viewer/viewer_overlay.h"
#include "viewer/viewer_state.h"
#include "techniques/axes.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VIEWER__LIVE_EVERY 30
/* Frames between two looks at the user techniques' files (reload on change). */
#define VIEWER__RELOAD_EVERY 30

typedef struct viewer {
    viewer_desc d;               /* filled in: viewer_desc_defaults */
    viewer_state st;
    gl_context *gl;
    render_ctx *r;
    counters_context *cc;
    render_item item;              /* the last configuration that prepared */
    dm_kv *good;                 /* its params, restored when a change fails */
    size_t n_good;
    viewer_counters live;
    int live_due;                /* frame of the next live counters session */
    int gl_errors;
    int n_shots;
    int dragging, panning;       /* left / right button held */
    double mx, my;
    viewer_overlay *ov;          /* C: counters drawn as text */
} viewer;

viewer_desc viewer_desc_defaults(const viewer_desc *d)
{
    viewer_desc r = *d;
    if (!(r.timed_seconds > 0))
        r.timed_seconds = VIEWER_TIMED_SECONDS_DEFAULT;
    return r;
}

/* ---- input -------------------------------------------------------------- */

static void viewer__on_char(GLFWwindow *w, unsigned c)
{
    viewer_state_char(&((viewer *)glfwGetWindowUserPointer(w))->st, c);
}

static void viewer__on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS)
        viewer_state_special(&((viewer *)glfwGetWindowUserPointer(w))->st, VIEWER_KEY_ESC);
}

static void viewer__on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        v->dragging = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_RIGHT)
        v->panning = action == GLFW_PRESS;
    glfwGetCursorPos(w, &v->mx, &v->my);
}

static void viewer__on_cursor(GLFWwindow *w, double x, double y)
{
    viewer *v = glfwGetWindowUserPointer(w);
    if (v->dragging)
        viewer_state_orbit(&v->st, x - v->mx, y - v->my);
    else if (v->panning)
        viewer_state_pan(&v->st, x - v->mx, y - v->my);
    v->mx = x;
    v->my = y;
}

static void viewer__on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    viewer_state_zoom(&((viewer *)glfwGetWindowUserPointer(w))->st, dy);
}

static void viewer__apply_event(viewer *v, const viewer_event *e)
{
    switch (e->kind) {
    case VIEWER_EV_CHAR: viewer_state_char(&v->st, e->ch); break;
    case VIEWER_EV_ESC: viewer_state_special(&v->st, VIEWER_KEY_ESC); break;
    case VIEWER_EV_DRAG: viewer_state_orbit(&v->st, e->dx, e->dy); break;
    case VIEWER_EV_PAN: viewer_state_pan(&v->st, e->dx, e->dy); break;
    case VIEWER_EV_WHEEL: viewer_state_zoom(&v->st, e->dy); break;
    case VIEWER_EV_WAIT: break;
    }
}

/* ---- frames ------------------------------------------------------------- */

/* Re-prepares after a change.  A change that fails to prepare is reported
 * and undone; failing at startup (no item yet) returns DM_ERR_*. */
static int viewer__prepare(viewer *v)
{
    if (!v->st.dirty)
        return 0;
    v->st.dirty = 0;
    render_item item;
    dm_str log = {0};
    render_set_debug_view(v->r, v->st.normals ? RENDER_DEBUG_NORMALS : RENDER_DEBUG_NONE);
    int rc = render_prepare(v->r, v->st.params, v->st.n_params, &item, &log);
    if (rc != 0) {
        fprintf(stderr, "dmbench: view: cannot prepare this configuration (%s):\n%s",
                dm_strerror(rc), dm_str_get(&log));
        dm_str_free(&log);
        if (!v->item.id)
            return rc;
        viewer_state_restore(&v->st, v->good, v->n_good);   /* back to the last good one */
        return 0;
    }
    dm_str_free(&log);
    if (v->item.id)
        render_release(v->r, v->item);
    v->item = item;
    dm_kv_free(v->good, v->n_good);
    v->good = NULL;
    v->n_good = 0;
    for (size_t i = 0; i < v->st.n_params; i++)
        dm_kv_push(&v->good, &v->n_good, v->st.params[i].key, v->st.params[i].value);
    return 0;
}

static viewer_frame viewer__frame(viewer *v)
{
    viewer_frame f = {.r = v->r, .item = v->item, .wireframe = v->st.wireframe};
    glfwGetFramebufferSize(gl_context_window(v->gl), &f.w, &f.h);
    f.w = f.w > 0 ? f.w : 1;
    f.h = f.h > 0 ? f.h : 1;
    return f;
}

/* "dolly frame 12 (13 of 60)" while something moves with the frame, else "". */
static void viewer__where(const viewer *v, const char *sep, dm_str *out)
{
    if (!viewer_state_moves(&v->st))
        return;
    unsigned long long n = viewer_state_path_frames(&v->st);
    if (n > 0)
        dm_str_printf(out, "%s%s frame %llu (%llu of %llu)%s", sep, viewer_state_get(&v->st, "camera.path"),
                      v->st.frame, v->st.frame % n + 1, n, v->st.playing ? " playing" : "");
    else
        dm_str_printf(out, "%sframe %llu%s", sep, v->st.frame, v->st.playing ? " playing" : "");
}

static void viewer__title(viewer *v, const viewer_frame *f)
{
    dm_str t = {0};
    dm_str_printf(&t, "dmbench view: %s on %s %dx%d", viewer_state_get(&v->st, "technique"),
                  viewer_state_get(&v->st, "mesh"), f->w, f->h);
    viewer__where(v, ", ", &t);
    dm_str_cat(&t, " | ");
    viewer_counters_format(&v->live, "  ", &t);
    glfwSetWindowTitle(gl_context_window(v->gl), dm_str_get(&t));
    dm_str_free(&t);
}

/* C: the configuration and the live counters as text in the window. */
static void viewer__overlay(viewer *v, const viewer_frame *f)
{
    static const char *const shown[] = {"technique", "mesh", "filter", "tess_level", "steps",
                                        "height_scale", "light.azimuth"};
    const technique_desc *t = technique_find(viewer_state_get(&v->st, "technique"));
    dm_str text = {0};
    for (size_t i = 0; i < sizeof shown / sizeof *shown; i++)
        if (t && technique_reads_axis(t, shown[i]))
            dm_str_printf(&text, "%s %s\n", shown[i], viewer_state_get(&v->st, shown[i]));
    viewer_counters_format(&v->live, "\n", &text);
    dm_str_printf(&text, "\n%dx%d%s%s%s", f->w, f->h, v->st.wireframe ? "  wireframe" : "",
                  v->st.normals ? "  normals" : "", v->st.light_orbit ? "  light orbit" : "");
    viewer__where(v, "\n", &text);
    viewer_overlay_draw(&v->ov, dm_str_get(&text), f->w, f->h);
    dm_str_free(&text);
}

/* Writes the back buffer (the frame just drawn) as PNG. */
static int viewer__screenshot(const viewer_frame *f, const char *path)
{
    img im = {0};
    char err[512] = "";
    int rc = viewer_read_window(f->w, f->h, &im);
    rc = rc ? rc : img_save(&im, path, err, sizeof err);
    img_free(&im);
    if (rc != 0)
        fprintf(stderr, "dmbench: error: view: screenshot %s: %s\n", path, err);
    else
        printf("screenshot: %s (%dx%d)\n", path, f->w, f->h);
    return rc;
}

/* Carries out what the input asked for (help, timed test, screenshot). */
static void viewer__requests(viewer *v, const viewer_frame *f)
{
    if (v->st.want_help)
        fputs(viewer_state_help(), stdout);
    if (v->st.want_timed) {
        dm_str out = {0};
        printf("timed: %s for %.1f s...\n", viewer_state_get(&v->st, "technique"), v->d.timed_seconds);
        fflush(stdout);
        viewer_measure_timed(v->cc, f, v->d.timed_seconds, &out);
        fputs(dm_str_get(&out), stdout);
        dm_str_free(&out);
    }
    v->st.want_help = v->st.want_timed = 0;
}

/* Counts KHR_debug messages and glGetError codes since the last frame. */
static void viewer__check_gl(viewer *v, int frame)
{
    dm_str msgs = {0};
    int n = gl_context_take_messages(v->gl, &msgs) + gl_context_check_errors(&msgs);
    if (n > 0)
        fprintf(stderr, "dmbench: view: %d GL error(s) at frame %d:\n%s", n, frame, dm_str_get(&msgs));
    v->gl_errors += n;
    dm_str_free(&msgs);
}

/* One frame: input, light orbit, prepare, counters, requests, draw,
 * screenshot, swap.  The light orbit alone does not postpone the live
 * counters (they would never run while it is on). */
static int viewer__frame_step(viewer *v, int frame)
{
    glfwPollEvents();
    if ((size_t)frame < v->d.n_events)
        viewer__apply_event(v, &v->d.events[frame]);
    fputs(dm_str_get(&v->st.msg), stdout);
    dm_str_free(&v->st.msg);
    dm_str reload = {0};   /* a user technique's file edited on disk (user_technique.h) */
    if (frame % VIEWER__RELOAD_EVERY == 0 && user_technique_reload(&reload) > 0)
        v->st.dirty = 1;
    fputs(dm_str_get(&reload), stderr);
    dm_str_free(&reload);
    int changed = v->st.dirty;
    viewer_state_tick(&v->st);
    int rc = viewer__prepare(v);
    if (rc != 0)
        return rc;
    render_set_frame(v->r, v->item, v->st.frame);   /* A, >, <: the frame along camera.path */
    viewer_frame f = viewer__frame(v);
    if (changed)
        v->live_due = frame + 2;        /* after the first draw has JIT-compiled */
    if (frame == v->live_due) {
        dm_str log = {0};
        if (viewer_measure_live(v->cc, &f, &v->live, &log) != 0)
            fputs(dm_str_get(&log), stderr);
        dm_str_free(&log);
        viewer__title(v, &f);
        v->live_due = frame + VIEWER__LIVE_EVERY;
    } else if (v->st.playing) {
        viewer__title(v, &f);           /* the frame along the path, with the last counters */
    }
    viewer__requests(v, &f);
    viewer_draw(&f);
    if (v->st.overlay)
        viewer__overlay(v, &f);
    if (v->st.want_screenshot) {
        char name[64];
        snprintf(name, sizeof name, "viewer-%03d.png", v->n_shots++);
        viewer__screenshot(&f, name);
        v->st.want_screenshot = 0;
    }
    viewer__check_gl(v, frame);
    glfwSwapBuffers(gl_context_window(v->gl));
    return 0;
}

/* Runs frames until Esc / window close, --frames, or the end of --keys. */
static int viewer__loop(viewer *v)
{
    GLFWwindow *w = gl_context_window(v->gl);
    for (int frame = 0;; frame++) {
        if (v->d.frames ? frame >= v->d.frames : v->d.scripted && (size_t)frame > v->d.n_events)
            break;
        if (glfwWindowShouldClose(w) || v->st.want_quit)
            break;
        int rc = viewer__frame_step(v, frame);
        if (rc != 0)
            return rc;
    }
    if (v->d.screenshot) {             /* the last frame again, read before any swap */
        viewer_frame f = viewer__frame(v);
        viewer_draw(&f);
        if (v->st.overlay)
            viewer__overlay(v, &f);
        if (viewer__screenshot(&f, v->d.screenshot) != 0)
            return DM_ERR_IO;
        viewer__check_gl(v, -1);
    }
    return 0;
}

/* Window, renderer, counters and callbacks; 0 or DM_ERR_* (printed). */
static int viewer__open(viewer *v)
{
    int w = 0, h = 0;
    axes_parse_size2(viewer_state_get(&v->st, "resolution"), &w, &h);
    dm_str err = {0};
    int rc = gl_context_create(&(gl_context_desc){.backend = GL_BACKEND_GLFW_WINDOW, .width = w,
                                                  .height = h, .title = "dmbench view"},
                               &v->gl, &err);
    if (rc != 0) {
        fprintf(stderr, "dmbench: error: view: %s\n", dm_str_get(&err));
        dm_str_free(&err);
        return rc;
    }
    if (render_create(&v->r) != 0 || counters_context_create(&v->cc) != 0) {
        fprintf(stderr, "dmbench: error: view: no usable OpenGL 4.5 context for the renderer\n");
        return DM_ERR_GL;
    }
    GLFWwindow *win = gl_context_window(v->gl);
    glfwSetWindowUserPointer(win, v);
    glfwSetCharCallback(win, viewer__on_char);
    glfwSetKeyCallback(win, viewer__on_key);
    glfwSetMouseButtonCallback(win, viewer__on_button);
    glfwSetCursorPosCallback(win, viewer__on_cursor);
    glfwSetScrollCallback(win, viewer__on_scroll);
    return 0;
}

static void viewer__close(viewer *v)
{
    viewer_overlay_destroy(v->ov);
    counters_context_destroy(v->cc);
    render_destroy(v->r);
    gl_context_destroy(v->gl);
    viewer_state_free(&v->st);
    dm_kv_free(v->good, v->n_good);
}

int viewer_run(const viewer_desc *d)
{
    viewer v = { .d = viewer_desc_defaults(d) };
    viewer_state_init(&v.st, d->params, d->n_params);
    int rc = viewer__open(&v);
    if (rc == 0)
        rc = viewer__loop(&v);
    if (rc == 0 && v.gl_errors > 0) {
        fprintf(stderr, "dmbench: view: %d GL error(s) captured (KHR_debug / glGetError)\n",
                v.gl_errors);
        rc = DM_ERR_GL;
    }
    viewer__close(&v);
    return rc;
}
