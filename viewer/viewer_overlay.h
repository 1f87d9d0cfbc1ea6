/* viewer_overlay.h — the `C` counters overlay: text drawn into the window.
 *
 * A built-in 3×5 pixel font (digits, A–Z, a little punctuation; lower case
 * is shown as upper case, unknown characters as '?') rasterised on the CPU
 * at an integer scale into an RGBA8 box (white on black), uploaded to a
 * texture and blitted to the top-left corner of framebuffer 0.  No shaders,
 * so it cannot disturb the techniques' GL state.
 */
#ifndef VIEWER_VIEWER_OVERLAY_H
#define VIEWER_VIEWER_OVERLAY_H

#include <stdint.h>

#define VIEWER_FONT_W 3
#define VIEWER_FONT_H 5

/* Rasterises text (lines split at '\n') at `scale` px per font pixel, with
 * one font pixel of spacing and margin: each character cell is
 * (VIEWER_FONT_W+1)*scale wide, each line (VIEWER_FONT_H+1)*scale high.
 * Returns a malloc'd top-down RGBA8 image and its size; NULL for empty text. */
uint8_t *viewer_font_raster(const char *text, int scale, int *w, int *h);

typedef struct viewer_overlay viewer_overlay;

/* Draws text into the top-left corner of framebuffer 0 (fb_w×fb_h).  The
 * GL objects are created on first use; *ov owns them. */
void viewer_overlay_draw(viewer_overlay **ov, const char *text, int fb_w, int fb_h);
void viewer_overlay_destroy(viewer_overlay *ov);

#endif
