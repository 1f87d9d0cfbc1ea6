/* render_meshes.h — the meshes of the renderer (internal to techniques/).
 *
 * Owned by render_meshes.c: building a configuration's mesh (a built-in or
 * user mesh, the CPU-displaced reference mesh, the seam buffer of patch
 * meshes), uploading it and caching it by key in r->meshes.  render.c calls
 * only this function.
 */
#ifndef TECHNIQUES_RENDER_MESHES_H
#define TECHNIQUES_RENDER_MESHES_H

#include <stddef.h>
#include "core/dm_util.h"

struct render_ctx;
struct render__cfg;
struct technique_desc;

/* Finds or creates the mesh of the configuration's (mesh, density[,
 * displacement]) for technique t; *idx indexes r->meshes.  DM_ERR_* with a
 * message in log. */
int render__mesh_get(struct render_ctx *r, const struct technique_desc *t, const struct render__cfg *c,
                     size_t *idx, dm_str *log);

#endif
