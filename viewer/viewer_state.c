/* viewer_state.c — the viewer's configuration and input handling (see viewer_state.h). */
#include "viewer/viewer_state.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/axes.h"
#include "techniques/technique.h"

#define VIEWER__ORBIT_DEG_PER_PX 0.25
#define VIEWER__ZOOM_PER_NOTCH 0.9
#define VIEWER__HEIGHT_STEP 0.01

static const char *const viewer__camera_axes[] = {"camera.distance", "camera.azimuth",
                                                  "camera.elevation", "camera.fov",
                                                  "camera.target_x", "camera.target_y",
                                                  "camera.target_z"};
#define VIEWER__N_CAMERA_AXES (sizeof viewer__camera_axes / sizeof viewer__camera_axes[0])

void viewer_state_init(viewer_state *st, const dm_kv *kv, size_t n)
{
    memset(st, 0, sizeof *st);
    for (size_t i = 0; i < n; i++) {
        dm_kv_push(&st->params, &st->n_params, kv[i].key, kv[i].value);
        dm_kv_push(&st->initial, &st->n_initial, kv[i].key, kv[i].value);
    }
    st->dirty = 1;
}

void viewer_state_free(viewer_state *st)
{
    dm_kv_free(st->params, st->n_params);
    dm_kv_free(st->initial, st->n_initial);
    dm_str_free(&st->msg);
    memset(st, 0, sizeof *st);
}

void viewer_state_restore(viewer_state *st, const dm_kv *kv, size_t n)
{
    dm_kv_free(st->params, st->n_params);
    st->params = NULL;
    st->n_params = 0;
    for (size_t i = 0; i < n; i++)
        dm_kv_push(&st->params, &st->n_params, kv[i].key, kv[i].value);
    st->dirty = 0;
}

const char *viewer_state_get(const viewer_state *st, const char *axis)
{
    const char *v = dm_kv_get(st->params, st->n_params, axis);
    const axis_info *a = axes_find(axis);
    return v ? v : a ? a->def : NULL;
}

int viewer_state_set(viewer_state *st, const char *axis, const char *value)
{
    dm_str err = {0};
    int rc = axes_check(axis, value, &err);
    if (rc != 0) {
        dm_str_printf(&st->msg, "%s\n", dm_str_get(&err));
        dm_str_free(&err);
        return rc;
    }
    char *canon = axes_canonical(axis, value);
    const char *cur = viewer_state_get(st, axis);
    if (!cur || strcmp(cur, canon) != 0)
        st->dirty = 1;
    size_t i = 0;
    while (i < st->n_params && strcmp(st->params[i].key, axis) != 0)
        i++;
    if (i == st->n_params) {
        dm_kv_push(&st->params, &st->n_params, axis, canon);
    } else {
        free(st->params[i].value);
        st->params[i].value = dm_xstrdup(canon);
    }
    free(canon);
    return 0;
}

static const technique_desc *viewer__tech(const viewer_state *st)
{
    return technique_find(viewer_state_get(st, "technique"));
}

/* 1 when the current technique reads the axis; else says so in msg. */
static int viewer__reads(viewer_state *st, const char *axis, char key)
{
    const technique_desc *t = viewer__tech(st);
    if (t && technique_reads_axis(t, axis))
        return 1;
    dm_str_printf(&st->msg, "%c: technique '%s' does not read %s\n", key,
                  viewer_state_get(st, "technique"), axis);
    return 0;
}

/* Next value of an enum axis, wrapping around. */
static void viewer__cycle(viewer_state *st, const char *axis)
{
    const axis_info *a = axes_find(axis);
    const char *cur = viewer_state_get(st, axis);
    size_t n = 0, at = 0;
    while (a->choices[n]) {
        if (strcmp(a->choices[n], cur) == 0)
            at = n;
        n++;
    }
    viewer_state_set(st, axis, a->choices[(at + 1) % n]);
    dm_str_printf(&st->msg, "%s = %s\n", axis, viewer_state_get(st, axis));
}

/* Picks the n-th user-visible technique (registry order). */
static void viewer__pick_technique(viewer_state *st, size_t n)
{
    const char *const *names = technique_names();
    size_t count = 0;
    while (names[count])
        count++;
    if (n >= count) {
        dm_str_printf(&st->msg, "%zu: there are only %zu techniques\n", n + 1, count);
        return;
    }
    viewer_state_set(st, "technique", names[n]);
    dm_str_printf(&st->msg, "technique = %s\n", names[n]);
}

static void viewer__set_number(viewer_state *st, const char *axis, double v)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.4g", v);
    viewer_state_set(st, axis, buf);
}

/* ] doubles, [ halves the tessellation level (or the parallax steps),
 * within the axis range. */
static void viewer__level(viewer_state *st, int up)
{
    const technique_desc *t = viewer__tech(st);
    const char *axis = t && technique_reads_axis(t, "tess_level") ? "tess_level"
                       : t && technique_reads_axis(t, "steps")    ? "steps" : NULL;
    if (!axis) {
        dm_str_printf(&st->msg, "%c: technique '%s' reads neither tess_level nor steps\n",
                      up ? ']' : '[', viewer_state_get(st, "technique"));
        return;
    }
    const axis_info *a = axes_find(axis);
    const char *cur = viewer_state_get(st, axis);
    double v = strcmp(cur, "auto") == 0 ? atof(a->def) : atof(cur);
    v = up ? fmin(v * 2, a->max) : fmax(floor(v / 2), a->min);
    viewer__set_number(st, axis, v);
    dm_str_printf(&st->msg, "%s = %s\n", axis, viewer_state_get(st, axis));
}

static void viewer__height(viewer_state *st, double step)
{
    if (!viewer__reads(st, "height_scale", step > 0 ? 'h' : 'H'))
        return;
    const axis_info *a = axes_find("height_scale");
    double v = atof(viewer_state_get(st, "height_scale")) + step;
    viewer__set_number(st, "height_scale", fmin(fmax(v, a->min), a->max));
    dm_str_printf(&st->msg, "height_scale = %s\n", viewer_state_get(st, "height_scale"));
}

/* R: the camera axes, target included, as given on the command line (or
 * their defaults). */
static void viewer__reset_camera(viewer_state *st)
{
    for (size_t i = 0; i < VIEWER__N_CAMERA_AXES; i++) {
        const char *v = dm_kv_get(st->initial, st->n_initial, viewer__camera_axes[i]);
        viewer_state_set(st, viewer__camera_axes[i], v ? v : axes_find(viewer__camera_axes[i])->def);
    }
    dm_str_cat(&st->msg, "camera reset\n");
}

static void viewer__toggle(viewer_state *st, int *flag, const char *what)
{
    *flag = !*flag;
    dm_str_printf(&st->msg, "%s %s\n", what, *flag ? "on" : "off");
}

int viewer_state_moves(const viewer_state *st)
{
    return strcmp(viewer_state_get(st, "camera.path"), "still") != 0 ||
           atof(viewer_state_get(st, "camera.orbit_deg_per_frame")) != 0.0 ||
           atof(viewer_state_get(st, "light.orbit_deg_per_frame")) != 0.0;
}

unsigned long long viewer_state_path_frames(const viewer_state *st)
{
    if (strcmp(viewer_state_get(st, "camera.path"), "still") == 0)
        return 0;
    return strtoull(viewer_state_get(st, "camera.path_frames"), NULL, 10);
}

/* A (play / pause), > and < (one frame on / back, pausing): the frame index
 * along the path.  Back from frame 0 goes to the path's last frame. */
static void viewer__path_key(viewer_state *st, unsigned c)
{
    if (!viewer_state_moves(st)) {
        dm_str_printf(&st->msg, "%c: nothing moves with the frame: camera.path is still and no "
                      "orbit per frame is set (start with camera.path=orbit, dolly or flyover, or "
                      "camera.orbit_deg_per_frame=N; docs/motion.md)\n", c == 'a' ? 'A' : c);
        return;
    }
    unsigned long long n = viewer_state_path_frames(st);
    if (c == 'a' || c == 'A') {
        st->playing = !st->playing;
    } else {
        st->playing = 0;
        if (c == '>')
            st->frame++;
        else if (st->frame > 0)
            st->frame--;
        else if (n > 0)
            st->frame = n - 1;
    }
    if (n > 0)
        dm_str_printf(&st->msg, "%s %s, frame %llu (%llu of %llu along the path)\n",
                      viewer_state_get(st, "camera.path"), st->playing ? "playing" : "paused",
                      st->frame, st->frame % n + 1, n);
    else
        dm_str_printf(&st->msg, "orbit %s, frame %llu\n", st->playing ? "playing" : "paused",
                      st->frame);
}

void viewer_state_char(viewer_state *st, unsigned c)
{
    if (c >= '1' && c <= '9') {
        viewer__pick_technique(st, c - '1');
        return;
    }
    switch (c) {
    case '0': viewer__pick_technique(st, 9); break;
    case '[': viewer__level(st, 0); break;
    case ']': viewer__level(st, 1); break;
    case 'f': case 'F': viewer__cycle(st, "filter"); break;
    case 'm': case 'M': viewer__cycle(st, "mesh"); break;
    case 'p': case 'P':
        if (viewer__reads(st, "tess_spacing", 'P'))
            viewer__cycle(st, "tess_spacing");
        break;
    case 'h': viewer__height(st, VIEWER__HEIGHT_STEP); break;
    case 'H': viewer__height(st, -VIEWER__HEIGHT_STEP); break;
    case 'w': case 'W': viewer__toggle(st, &st->wireframe, "wireframe"); break;
    case 'c': case 'C': viewer__toggle(st, &st->overlay, "counters overlay"); break;
    case 'l': case 'L': viewer__toggle(st, &st->light_orbit, "light orbit"); break;
    case 'n': case 'N':
        viewer__toggle(st, &st->normals, "normals view");
        st->dirty = 1;                  /* a different program variant */
        break;
    case 'a': case 'A': case '>': case '<': viewer__path_key(st, c); break;
    case 't': case 'T': st->want_timed = 1; break;
    case 's': case 'S': st->want_screenshot = 1; break;
    case 'r': case 'R': viewer__reset_camera(st); break;
    case '?': st->want_help = 1; break;
    default: break;
    }
}

void viewer_state_special(viewer_state *st, viewer_special key)
{
    if (key == VIEWER_KEY_ESC)
        st->want_quit = 1;
}

void viewer_state_orbit(viewer_state *st, double dx, double dy)
{
    double az = atof(viewer_state_get(st, "camera.azimuth")) - dx * VIEWER__ORBIT_DEG_PER_PX;
    double el = atof(viewer_state_get(st, "camera.elevation")) + dy * VIEWER__ORBIT_DEG_PER_PX;
    az = fmod(az + 540.0, 360.0) - 180.0;     /* keep within [-180, 180) */
    viewer__set_number(st, "camera.azimuth", az);
    viewer__set_number(st, "camera.elevation", fmin(fmax(el, -89.0), 89.0));
}

void viewer_state_zoom(viewer_state *st, double wheel)
{
    double d = atof(viewer_state_get(st, "camera.distance")) * pow(VIEWER__ZOOM_PER_NOTCH, wheel);
    viewer__set_number(st, "camera.distance", fmin(fmax(d, 0.2), 50.0));
}

/* Writes a target coordinate rounded to 1e-6 world units (so cos 90° is
 * 0, not 6e-17) with more digits than viewer__set_number, so small pans
 * accumulate. */
static void viewer__set_precise(viewer_state *st, const char *axis, double v)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.9g", round(v * 1e6) / 1e6 + 0.0);
    viewer_state_set(st, axis, buf);
}

void viewer_state_pan(viewer_state *st, double dx, double dy)
{
    static const char *const t[3] = {"camera.target_x", "camera.target_y", "camera.target_z"};
    double az = atof(viewer_state_get(st, "camera.azimuth")) * M_PI / 180.0;
    double el = atof(viewer_state_get(st, "camera.elevation")) * M_PI / 180.0;
    double k = atof(viewer_state_get(st, "camera.distance")) * VIEWER_PAN_PER_PX;
    double right[3] = {cos(az), 0.0, -sin(az)};
    double up[3] = {-sin(el) * sin(az), cos(el), -sin(el) * cos(az)};
    for (int i = 0; i < 3; i++) {
        const axis_info *a = axes_find(t[i]);
        double v = atof(viewer_state_get(st, t[i])) + k * (-dx * right[i] + dy * up[i]);
        viewer__set_precise(st, t[i], fmin(fmax(v, a->min), a->max));
    }
}

void viewer_state_tick(viewer_state *st)
{
    if (st->playing)
        st->frame++;
    if (!st->light_orbit)
        return;
    double az = atof(viewer_state_get(st, "light.azimuth")) + VIEWER_LIGHT_ORBIT_DEG;
    viewer__set_number(st, "light.azimuth", fmod(az + 540.0, 360.0) - 180.0);
}

const char *viewer_state_help(void)
{
    return "keys:\n"
           "  1-9, 0   technique (registry order, `dmbench list techniques`)\n"
           "  [ ]      tessellation level (or parallax steps) halved / doubled\n"
           "  F        next texture filter        M  next mesh\n"
           "  P        next tessellation spacing  H / Shift+H  height scale +/- 0.01\n"
           "  W        wireframe                  C  counters overlay\n"
           "  T        timed test (median ns per frame + counters)\n"
           "  L        light orbit on/off         N  normals view on/off\n"
           "  S        screenshot PNG             R  reset camera (and pan)\n"
           "  A        play / pause camera.path   > / <  one frame on / back\n"
           "  ?        this help                  Esc  quit\n"
           "mouse: left drag orbits, right drag pans, wheel zooms\n";
}
