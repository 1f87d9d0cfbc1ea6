/* render_textures.h — the material maps of the renderer (internal to techniques/).
 *
 * Owned by render_textures.c: generating or loading maps, uploading them in
 * the requested formats with their mip chains, samplers for the `filter`
 * axis, and binding them for a draw.  render.c calls only these functions.
 */
#ifndef TECHNIQUES_RENDER_TEXTURES_H
#define TECHNIQUES_RENDER_TEXTURES_H

#include <epoxy/gl.h>
#include <stddef.h>
#include "core/dm_util.h"

struct render_ctx;
struct render__item;
struct render__cfg;

struct vt;

typedef struct render__maps {
    char *key;
    GLuint tex[3];               /* height, normal, albedo (0 with a virtual texture) */
    size_t bytes[3];
    struct vt *vt;               /* virtual_texture=software, else NULL */
    float h_lo, h_hi;            /* range of the height map (0, 1 with a virtual texture) */
    float normal_height_scale;   /* the height_scale the normal map was made for (its x, y
                                    are scaled by height_scale / this); 0 = a user's
                                    normal file, used as it is */
} render__maps;

typedef struct render__sampler {
    char *key;
    GLuint id;
} render__sampler;

/* The height_scale the normal map of a `maps` value was made for:
 * MESH_ASTEROID_SCALE for `asteroid` (its baked true normals), 0 for a
 * material with a normal file (used as it is), else
 * MAPS_NORMAL_HEIGHT_SCALE (derived from the height map). */
float render__normal_height_scale(const char *maps);
/* Finds or creates the textures of the configuration's (maps, size,
 * formats); *idx indexes r->maps.  DM_ERR_* with a message in log. */
int render__maps_get(struct render_ctx *r, const struct render__cfg *c, size_t *idx, dm_str *log);
/* Finds or creates the sampler of a `filter` value; returns its index. */
size_t render__sampler_get(struct render_ctx *r, const char *filter);
/* Binds the item's maps and sampler to units 0 (height), 1 (normal), 2 (albedo). */
void render__maps_bind(struct render_ctx *r, const struct render__item *it);
/* vt.glsl filter class of a `filter` value: 0 nearest, 1 bilinear, 2
 * trilinear or anisotropic (VT_FILTER_TRILINEAR). */
int render__vt_filter(const char *filter);
/* Bytes of the maps the item's technique samples. */
size_t render__maps_bytes(struct render_ctx *r, const struct render__item *it);
/* Releases every map and sampler of the renderer. */
void render__maps_destroy(struct render_ctx *r);

#endif
