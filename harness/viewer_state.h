/* viewer_state.h — what the interactive viewer shows, and how input changes it.
 *
 * Pure data, no GL: the configuration (axis → value, the same strings as a
 * sweep or `dmbench render`), view toggles and the requests the main loop
 * carries out (screenshot, timed test, quit).  Keyboard characters, special
 * keys and mouse motion from GLFW callbacks and from `--keys` scripts go
 * through the same functions, so a script exercises exactly what a user does.
 * Camera = the camera.* axes: orbit and zoom change those values and the loop
 * re-prepares the item (the renderer caches programs, meshes and maps).
 */
#ifndef HARNESS_VIEWER_STATE_H
#define HARNESS_VIEWER_STATE_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

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
/* The key and mouse reference printed by `?`. */
const char *viewer_state_help(void);

#endif
