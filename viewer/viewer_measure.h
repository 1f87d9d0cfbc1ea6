/* viewer_measure.h — the viewer's live counters, timed test and read-back.
 *
 * All of it runs on the viewer's window (framebuffer 0) with the counters
 * library and the techniques renderer that batch runs use: WallTime is the
 * glFinish-fenced wall time per frame (ns, as `dmbench run` reports it), the
 * others are pipeline-statistics / occlusion totals per frame.
 */
#ifndef VIEWER_VIEWER_MEASURE_H
#define VIEWER_VIEWER_MEASURE_H

#include "core/dm_util.h"
#include "counters/counters.h"
#include "imaging/image.h"
#include "techniques/render.h"

#define VIEWER_N_COUNTERS 5

/* Counter names shown live, in display order (WallTime first). */
extern const char *const viewer_counter_names[VIEWER_N_COUNTERS];

typedef struct viewer_counters {
    double value[VIEWER_N_COUNTERS];   /* per frame; NAN = unavailable */
} viewer_counters;

/* What the viewer draws: the item at w×h into framebuffer 0. */
typedef struct viewer_frame {
    render_ctx *r;
    render_item item;
    int w, h;
    int wireframe;
} viewer_frame;

/* Draws one frame (wireframe via glPolygonMode, restored afterwards). */
void viewer_draw(const viewer_frame *f);
/* One counters session of one frame per pass.  Returns 0, or the counters
 * error with counters_last_error() appended to log. */
int viewer_measure_live(counters_context *cc, const viewer_frame *f, viewer_counters *out,
                        dm_str *log);
/* Timed test: fenced samples of 4 frames for `seconds` (at least 5
 * samples), then one live session; appends the result line(s) to out:
 * "timed: WallTime median N ns/frame (M ms) ..." */
int viewer_measure_timed(counters_context *cc, const viewer_frame *f, double seconds, dm_str *out);
/* Appends "Name value" for each counter of c (WallTime in ms, "n/a" when
 * unavailable) to out, separated by sep. */
void viewer_counters_format(const viewer_counters *c, const char *sep, dm_str *out);
/* Reads the back buffer of framebuffer 0 (w×h) into a new img (row 0 top,
 * release with img_free): the frame exactly as drawn, before the swap. */
int viewer_read_window(int w, int h, img *out);

#endif
