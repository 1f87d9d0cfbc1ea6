/* cull.h — coarse CPU culling of a triangle list in chunks (the part of
 * `visibility_test: on` that saves work on every driver).
 *
 * A mesh's triangle list is cut into chunks of consecutive triangles; each
 * chunk keeps the axis-aligned bounds of the vertices it references.  Per
 * frame, a chunk is left out when its bounds, padded by the largest
 * displacement, lie entirely outside one plane of the clip volume widened by
 * a margin relative to w: then every triangle of it is invisible whether or
 * not its vertices are displaced, so drawing only the other chunks gives the
 * same image with fewer vertices shaded.  The built-in grids list their
 * triangles row by row, so chunks are bands of rows. */
#ifndef TECHNIQUES_CULL_H
#define TECHNIQUES_CULL_H

#include <stddef.h>

#include "techniques/mesh.h"

typedef struct cull_chunk {
    size_t first, count;    /* index range in the mesh's triangle list */
    float lo[3], hi[3];     /* bounds of the referenced vertices (object space) */
} cull_chunk;

typedef struct cull_set {
    cull_chunk *chunks;
    size_t n;
} cull_set;

/* Cuts m's triangles into chunks of tris_per_chunk (≥ 1; the last may be
 * shorter).  Returns 0, or DM_ERR_ARG for a mesh without triangles or a zero
 * chunk size (out left empty). */
int cull_build(const mesh_data *m, size_t tris_per_chunk, cull_set *out);
/* Index ranges to draw under the clip matrix mvp (column-major 4×4, model
 * included): the chunks not culled, consecutive ones merged.  pad widens
 * every box in object units, margin widens the clip volume (|x|,|y|,|z| ≤
 * w·(1 + margin)).  first/count need room for s->n ranges; returns the
 * number of ranges. */
size_t cull_visible(const cull_set *s, const float mvp[16], float pad, float margin,
                    size_t *first, size_t *count);
void cull_free(cull_set *s);

#endif
