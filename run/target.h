/* target.h — offscreen render targets: RGBA32F colour + 32F depth FBO.
 *
 * Every configuration renders into one of these at the sweep's resolution
 * (and the quality reference at a multiple of it).  Read-back flips GL's
 * bottom-up rows so row 0 is the top of the image, as reports/ expects.
 */
#ifndef RUN_TARGET_H
#define RUN_TARGET_H

#include <stdint.h>

typedef struct target { uint32_t fbo, color, depth; int w, h; } target;

/* Creates and binds a w×h target.  DM_ERR_GL if incomplete, DM_ERR_RANGE
 * if larger than the driver allows. */
int target_create(target *t, int w, int h);
void target_bind(const target *t);
/* Reads colour (w*h*4 floats) and, if depth != NULL, depth (w*h floats). */
void target_read(const target *t, float *rgba, float *depth);
void target_destroy(target *t);

#endif
