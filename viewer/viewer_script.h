/* viewer_script.h — `dmbench view --keys SCRIPT`: input replayed frame by frame.
 *
 * Syntax (one event per frame, in order):
 *   any printable character   typed as by a user ('h' raises, 'H' = Shift+h
 *                             lowers the height scale; '?' is help)
 *   .                         wait one frame
 *   {wait:N}                  wait N frames
 *   {esc}                     the Escape key (quit)
 *   {drag:DX,DY}              left-button drag by DX, DY pixels (orbit)
 *   {pan:DX,DY}               right-button drag by DX, DY pixels (pan)
 *   {wheel:N}                 mouse wheel by N notches (zoom; may be negative)
 *   {space}, {dot}, {lbrace}  the characters ' ', '.', '{'
 * Whitespace between events is ignored; names are case-insensitive.
 */
#ifndef VIEWER_VIEWER_SCRIPT_H
#define VIEWER_VIEWER_SCRIPT_H

#include <stddef.h>
#include "core/dm_util.h"

typedef enum viewer_event_kind {
    VIEWER_EV_WAIT = 0,
    VIEWER_EV_CHAR,
    VIEWER_EV_ESC,
    VIEWER_EV_DRAG,
    VIEWER_EV_WHEEL,
    VIEWER_EV_PAN
} viewer_event_kind;

typedef struct viewer_event {
    viewer_event_kind kind;
    unsigned ch;                 /* VIEWER_EV_CHAR */
    double dx, dy;               /* VIEWER_EV_DRAG / _PAN: pixels; VIEWER_EV_WHEEL: dy notches */
} viewer_event;

/* Parses a script into *out (malloc'd, one event per frame; waits expanded)
 * and *n.  Returns 0, or DM_ERR_PARSE with the offending position and the
 * valid names in err (out untouched). */
int viewer_script_parse(const char *script, viewer_event **out, size_t *n, dm_str *err);

#endif
