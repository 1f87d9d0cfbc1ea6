/* viewer_state.h — what the interactive viewer shows, and how input changes it.
 *
 * Pure data, no GL: the configuration (axis → value, the same strings as a
 * sweep or `dmbench render`), view toggles and the requests the main loop
 * carries out (screenshot, timed test, quit).  Keyboard characters, special
 * keys and mouse motion from GLFW callbacks and from `--keys` scripts go
 * through the same functions, so a script exercises exactly what a user does.
 * Camera = the camera.* axes: orbit, pan (camera.target_*) and zoom change
 * those values and the loop re-prepares the item (the renderer caches
 * programs, meshes and maps).  The light orbit (L) advances light.azimuth by
 * VIEWER_LIGHT_ORBIT_DEG once per frame (viewer_state_tick), so a --frames /
 * --keys run is deterministic.
 */
#ifndef VIEWER_VIEWER_STATE_H
#define VIEWER_VIEWER_STATE_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

/* L: degrees light.azimuth advances per frame while the light orbit is on. */
#define VIEWER_LIGHT_ORBIT_DEG 2.0
/* Right-drag pan: world units the target moves per pixel per unit of
 * camera.distance (viewer_state_pan). */
#define VIEWER_PAN_PER_PX 0.002

typedef enum viewer_special {
    VIEWER_KEY_ESC = 1
} viewer_special;

typedef struct viewer_state {
    dm_kv *params;               /* current configuration (canonical values) */
    size_t n_params;
    dm_kv *initial;              /* as given on the command line, for R (camera reset) */
    size_t n_initial;
    int dirty;                   /* params changed: re-prepare before the next frame */
    int wireframe, overlay;      /* W, C */
    int light_orbit, normals;    /* L, N (normals: the renderer's normals view) */
    int playing;                 /* A: the frame index advances once per frame */
    unsigned long long frame;    /* the frame drawn (render_set_frame): the position
                                    along camera.path and the orbits' turn */
    int want_screenshot, want_timed, want_help, want_quit;
    dm_str msg;                  /* feedback for the user, drained by the loop */
} viewer_state;

/* Copies the configuration (the caller keeps its kv).  Missing axes take
 * their catalog defaults when read. */
void viewer_state_init(viewer_state *st, const dm_kv *kv, size_t n);
void viewer_state_free(viewer_state *st);
/* Replaces the current configuration (not the command-line one R returns
 * to) without marking it dirty: undoes a change that failed to prepare. */
void viewer_state_restore(viewer_state *st, const dm_kv *kv, size_t n);
/* Value of an axis in the current configuration, else its default. */
const char *viewer_state_get(const viewer_state *st, const char *axis);
/* Sets an axis (value canonicalised); marks the state dirty when it changed.
 * DM_ERR_ARG/DM_ERR_UNKNOWN (message in st->msg) when the value is invalid. */
int viewer_state_set(viewer_state *st, const char *axis, const char *value);
/* A typed character (after Shift: 'H' is Shift+h).  Unknown keys are
 * ignored; keys that cannot act on the current technique say why in msg. */
void viewer_state_char(viewer_state *st, unsigned codepoint);
void viewer_state_special(viewer_state *st, viewer_special key);
/* Mouse: drag by (dx, dy) pixels with the left button orbits; wheel zooms
 * (positive = closer). */
void viewer_state_orbit(viewer_state *st, double dx, double dy);
void viewer_state_zoom(viewer_state *st, double wheel);
/* Right-button drag by (dx, dy) pixels (x right, y down) pans: the target
 * camera.target_* moves by distance·VIEWER_PAN_PER_PX·(−dx·right + dy·up),
 * right = (cos az, 0, −sin az) and up = (−sin el sin az, cos el, −sin el cos az)
 * the camera's screen axes, so the scene follows the cursor; each
 * coordinate is rounded to 1e-6 world units and kept in the axis range. */
void viewer_state_pan(viewer_state *st, double dx, double dy);
/* Once per frame, after input: advances light.azimuth by
 * VIEWER_LIGHT_ORBIT_DEG while the light orbit is on (wrapped to
 * [-180, 180)), and the frame index by one while a path plays (A).  The
 * frame index is what `dmbench render --frame N` draws: the position along
 * camera.path (frame mod camera.path_frames) and the turn of
 * camera.orbit_deg_per_frame / light.orbit_deg_per_frame. */
void viewer_state_tick(viewer_state *st);
/* 1 when the frame index changes the picture: a camera.path other than
 * still, or a non-zero camera/light orbit per frame. */
int viewer_state_moves(const viewer_state *st);
/* Frames of one pass along camera.path (camera.path_frames), 0 on the still
 * path (the frame index then only turns the orbits). */
unsigned long long viewer_state_path_frames(const viewer_state *st);
/* The key and mouse reference printed by `?`. */
const char *viewer_state_help(void);

#endif
