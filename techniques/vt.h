/* vt.h — software virtual texturing of the material maps (techniques/ only).
 *
 * A virtual texture of size² texels (up to 65536², never materialised) is
 * cut into pages of `page` texels per mip level; pages are generated on
 * demand from a procedural set (maps_texel) and copied, with a border of
 * VT_BORDER texels on every side for hardware bilinear filtering, into
 * slots of three physical cache textures (height R32F, normal RGBA8 =
 * n·0.5+0.5, albedo RGBA8 linear with specular in A).  A page table (RG16UI,
 * one mip level per page level) gives for every page the slot of the finest
 * resident page covering it and that page's level, so a miss falls back to
 * the coarser resident mip; the one page of the coarsest level is always
 * resident.  The fragment shader (glsl/vt.glsl) writes (level, page x,
 * page y) of what it wanted into a feedback buffer at 1/VT_FEEDBACK_SCALE
 * of the resolution; the next frame reads it back, keeps the requested
 * pages and their ancestors, evicts the least recently used pages not
 * wanted this frame, and generates at most VT_UPLOAD_BUDGET pages, coarse
 * levels first.  See docs/textures.md for the diagram.
 *
 * Sparse (desc.sparse, virtual_texture=sparse, GL_ARB_sparse_texture): the
 * three maps are sparse textures of size² texels with one mip level per
 * page level, and "a slot" is a committed page: the same feedback, LRU and
 * budget commit a page (glTexPageCommitmentARB) and upload it without
 * border where the software path copies it into a slot, and uncommit the
 * victim.  Without ARB_sparse_texture2 the shader cannot ask whether a
 * texel is resident, so it samples the level the page table names (the
 * finest resident ancestor; this scheme is ours: S3 states none and reads
 * its sparse textures with plain texture()); pages must be at least the
 * driver's virtual page size of each format.
 */
#ifndef TECHNIQUES_VT_H
#define TECHNIQUES_VT_H

#include <epoxy/gl.h>
#include <stdint.h>
#include "core/dm_util.h"
#include "techniques/render.h"

#define VT_BORDER 2            /* texels of border on each side of a page */
#define VT_FEEDBACK_SCALE 4    /* feedback at 1/4 of the resolution per axis */
#define VT_UPLOAD_BUDGET 16    /* pages generated and uploaded per frame */
#define VT_MAX_SIZE 65536      /* largest virtual size (page ids pack 14 bits per axis) */

typedef struct vt_desc {
    const char *maps;          /* procedural set name */
    int size;                  /* virtual texels per side, a power of two */
    int page;                  /* page texels per side, a power of two <= size */
    int cache_pages;           /* slots in the physical cache (>= 2) */
    int budget;                /* pages per frame; 0 = VT_UPLOAD_BUDGET */
    int sparse;                /* 1: GL_ARB_sparse_texture (see below) */
} vt_desc;

typedef struct vt vt;

/* Creates the cache, page table and feedback buffer and makes the coarsest
 * page resident.  DM_ERR_ARG / DM_ERR_UNKNOWN / DM_ERR_RANGE with a message
 * in log (bad set, sizes not powers of two, a cache larger than
 * GL_MAX_TEXTURE_SIZE allows). */
int vt_create(const vt_desc *d, vt **out, dm_str *log);
void vt_destroy(vt *v);
/* Once per frame, before the draw, with the program in use: reads back the
 * previous frame's feedback, updates the cache within the budget, binds the
 * physical textures to units 0-2 (GL_NEAREST or GL_LINEAR, no mips, clamped),
 * the page table to unit 3 and the cleared feedback buffer to SSBO binding
 * 0, and sets the u_vt* uniforms of `program` (vt.glsl, compiled with
 * VT_SOFTWARE).  filter: 0 nearest, 1 bilinear, 2 trilinear (anisotropic =
 * trilinear); the program's VT_FILTER_TRILINEAR must match it. */
void vt_frame(vt *v, GLuint program, int filter, int width, int height);
/* Bytes of the physical textures and the page table (from their formats). */
size_t vt_bytes(const vt *v);
void vt_get_stats(const vt *v, render_vt_stats *out);

#endif
