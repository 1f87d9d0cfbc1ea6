/* render.h — turning a configuration into GL draws.
 *
 * The renderer owns every GL object of the techniques layer behind typed
 * handles: a program cache keyed by (technique, defines, driver), mesh and
 * map caches, so a sweep creates each resource once.  It draws into
 * whatever framebuffer is bound; render targets, timing and counters belong
 * to the caller (run/, viewer/, counters/).  Needs a current GL 4.5 context.
 */
#ifndef TECHNIQUES_RENDER_H
#define TECHNIQUES_RENDER_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

typedef struct render_ctx render_ctx;
typedef struct render_item { uint32_t id; } render_item;   /* 0 = invalid */

typedef struct render_item_info {
    size_t mesh_vertices, mesh_triangles;
    size_t mesh_bytes, texture_bytes;
    int64_t setup_ns;            /* compile/link/upload time spent preparing it */
    int program_cached;          /* 0 compiled now, 1 from the in-memory program cache,
                                    2 from the on-disk program-binary cache */
    int has_fs;                  /* the program has a fragment stage */
    int fs_discards;             /* its fragment shader can `discard` (fs_minimal.h) */
    int fs_writes_depth;         /* its fragment shader writes gl_FragDepth */
} render_item_info;

/* Returns 0 and a renderer, or DM_ERR_GL when no usable context is current. */
int render_create(render_ctx **out);
void render_destroy(render_ctx *r);
/* Enables the on-disk program-binary cache (ARB_get_program_binary) in
 * directory `dir` (created when first written; NULL disables).  Each program
 * is stored under a hash of its key (technique, defines, GL_RENDERER +
 * GL_VERSION) with the full key inside, so a changed driver or source never
 * loads a stale binary; a binary the driver rejects is recompiled and
 * rewritten.  Returns 0, or DM_ERR_UNSUPPORTED when the driver offers no
 * binary format (the cache then stays off). */
int render_set_cache_dir(render_ctx *r, const char *dir);

/* Debug views: every technique's fragment output replaced by a diagnostic. */
typedef enum render_debug_view {
    RENDER_DEBUG_NONE = 0,         /* the technique's own output */
    RENDER_DEBUG_NORMALS,          /* world-space shading normal (after bump, normal or
                                    parallax perturbation) as n*0.5+0.5, alpha 1 */
    RENDER_DEBUG_MINIMAL_FS,       /* stage isolation: the same stages, depth state and
                                    coverage with a minimal fragment shader
                                    (fs_minimal.h; the raster pass of docs/counters.md) */
    RENDER_DEBUG_LOOP_TRIPS        /* the technique's own shading, its parallax search loop
                                    counting trips: one fragment of each SIMD group (the
                                    first active one) adds 1 per iteration to the uint
                                    at shader storage binding RENDER_LOOP_TRIPS_BINDING
                                    (LoopTrips, docs/counters.md) */
} render_debug_view;
/* The binding the loop-trips view adds to; the counters library binds its
 * buffer there (run/mscene.c checks that the two agree). */
#define RENDER_LOOP_TRIPS_BINDING 7
/* Sets the debug view of the items prepared from now on (prepared items
 * keep theirs; it selects a program variant, #define DEBUG_NORMALS, part of
 * the program key).  Returns 0, or DM_ERR_ARG for an unknown view. */
int render_set_debug_view(render_ctx *r, render_debug_view view);

/* Prepares one configuration (params: axis → value; missing axes take their
 * defaults).  Returns 0 and a handle; DM_ERR_ARG/DM_ERR_UNKNOWN for bad
 * params (log says which); DM_ERR_SHADER with the driver's full info log
 * appended to `log`; DM_ERR_UNSUPPORTED when the driver lacks a feature. */
int render_prepare(render_ctx *r, const dm_kv *params, size_t n_params,
                 render_item *out, dm_str *log);
/* Makes, in this process and without GL, the procedural map set that
 * render_prepare of params would make (not a user's material, not a
 * virtual texture, smaller than MAPS_CACHE_MIN_SIZE): processes forked
 * afterwards copy it from the process's memo (techniques/maps.h) instead
 * of generating it, so a run whose scenes each measure in a child of
 * their own generates each set once.  Returns 1 when it made the set, 0
 * when the process has it already or params read none of that kind (or it
 * cannot be made: prepare then says why). */
int render_maps_preload(const dm_kv *params, size_t n_params);
/* Draws one frame of the item into the bound framebuffer (viewport w×h,
 * clears colour to 0 and depth to 1 first).  Does not glFinish. */
int render_draw(render_ctx *r, render_item item, int width, int height);
/* Sets the frame index the item's moving camera and lights follow
 * (camera.orbit_deg_per_frame, light.orbit_deg_per_frame: azimuths turned
 * by frame × degrees); 0 when prepared.  The runner sets the index of the
 * frame within its sample, so every sample, pass, reference and quality
 * image (frame 0) sees the same path.  Returns 0 or DM_ERR_ARG. */
int render_set_frame(render_ctx *r, render_item item, uint64_t frame);
int render_get_info(render_ctx *r, render_item item, render_item_info *out);
void render_release(render_ctx *r, render_item item);

/* The draw calls render_draw splits one frame of a tessellating
 * configuration into (llvmpipe's 16-bit batch limit, docs/displacement.md),
 * without GL: *patches the mesh's patches, *per_call the most one call
 * draws (every call but the last draws that many).  The mesh is built on
 * the CPU as render_prepare builds it.  Returns 0; DM_ERR_ARG when the
 * technique does not tessellate; DM_ERR_UNKNOWN or the mesh's error with
 * log saying why. */
int render_patch_calls(const dm_kv *params, size_t n_params, size_t *patches, size_t *per_call, dm_str *log);

/* A hook around each draw call of patches that render_draw makes: called
 * with begin 1 just before call `call` (0 for a frame's first call of
 * patches) and with begin 0 just after it, the frame's clear and state
 * already set.  Every patch draw is bracketed (the calls of
 * render_patch_calls, and with lod: object-* each object's); triangle
 * draws are not.  The caller brackets each call with its queries there
 * (TessWalkCalls, run/mscene.c).  hook NULL removes it. */
typedef void (*render_call_hook)(void *user, size_t call, int begin);
void render_set_call_hook(render_ctx *r, render_call_hook hook, void *user);

/* Virtual-texture statistics of an item, cumulative since it was prepared
 * (render_textures.c).  DM_ERR_UNAVAILABLE when the item does not use a
 * virtual texture. */
typedef struct render_vt_stats {
    uint64_t frames;
    uint64_t pages_resident;     /* now */
    uint64_t page_misses;        /* requested pages that were not resident */
    uint64_t upload_bytes;       /* bytes uploaded into the page cache */
    int64_t feedback_ns;         /* time spent in feedback passes and readback */
    uint64_t committed_bytes;    /* page storage now: committed pages (sparse), the cache (software) */
} render_vt_stats;
int render_get_vt_stats(render_ctx *r, render_item item, render_vt_stats *out);

#endif
