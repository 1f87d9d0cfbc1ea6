/* viewer.h — the interactive viewer: one configuration live in a GLFW window.
 *
 * viewer_run opens the window (size = the resolution axis), draws the
 * configuration with the techniques renderer every frame, takes keys and
 * mouse input (or a scripted event list) through viewer_state, measures live
 * counters and the timed test, and closes on Esc, window close, after
 * `frames` frames or at the end of the script.  The command line
 * (cli/cmd_view.c) fills a viewer_desc; nothing here parses arguments.
 */
#ifndef VIEWER_VIEWER_H
#define VIEWER_VIEWER_H

#include <stddef.h>
#include "core/dm_results.h"
#include "viewer/viewer_script.h"

/* T: seconds of the timed test when viewer_desc.timed_seconds is 0. */
#define VIEWER_TIMED_SECONDS_DEFAULT 20.0

/* Zero means default for every field. */
typedef struct viewer_desc {
    const dm_kv *params;         /* the initial configuration (canonical values) */
    size_t n_params;
    const viewer_event *events;  /* scripted input, one event per frame */
    size_t n_events;
    int scripted;                /* 1: stop after the script's last event */
    int frames;                  /* > 0: stop after this many frames */
    const char *screenshot;      /* PNG of the last frame, or NULL */
    double timed_seconds;        /* T duration; 0 → VIEWER_TIMED_SECONDS_DEFAULT */
} viewer_desc;

/* The desc with its defaults filled in. */
viewer_desc viewer_desc_defaults(const viewer_desc *d);
/* Runs the window until it is closed (see above).  Returns 0; DM_ERR_UNSUPPORTED
 * when no window can be opened (no display: the message names xvfb-run);
 * DM_ERR_GL when the renderer has no usable context or GL errors were
 * captured; the prepare error when the initial configuration cannot be
 * drawn; DM_ERR_IO when the screenshot cannot be written.  Messages go to
 * stderr. */
int viewer_run(const viewer_desc *d);

#endif
