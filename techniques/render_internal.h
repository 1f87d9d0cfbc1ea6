/* render_internal.h — the renderer's shared internals (techniques/ only).
 *
 * render.c owns programs, items and drawing; render_meshes.c the meshes
 * (render_meshes.h); render_textures.c the maps and samplers
 * (render_textures.h).  All three see the renderer struct.
 */
#ifndef TECHNIQUES_RENDER_INTERNAL_H
#define TECHNIQUES_RENDER_INTERNAL_H

#include <epoxy/gl.h>
#include <stddef.h>
#include <string.h>
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "techniques/axes.h"
#include "techniques/cull.h"
#include "techniques/lod_cpu.h"
#include "techniques/render.h"
#include "techniques/render_textures.h"
#include "techniques/technique.h"

#define RENDER__MAX_LIGHTS 8
/* Triangle budget of cpu_displace meshes: k = floor(sqrt(budget / triangles))
 * clamped to 1..512 splits of every edge. */
#define RENDER__REFERENCE_TRIANGLES (1u << 20)
/* visibility_test: triangles per culling chunk (a 400² grid has 156 chunks)
 * and the widening of the clip volume, relative to w — the vertex stage's
 * VISIBILITY_MARGIN (displace.vert.glsl) */
#define RENDER__CULL_CHUNK 2048
#define RENDER__VISIBILITY_MARGIN 0.1f

/* camera.path values, in the axis's order (axes.c). */
enum { RENDER__PATH_STILL, RENDER__PATH_ORBIT, RENDER__PATH_DOLLY, RENDER__PATH_FLYOVER };

/* u_roughness is the roughness axis's uniform (set with every numeric axis). */
enum render__uniform {
    RU_MODEL, RU_VIEW_PROJ, RU_NORMAL_MAT, RU_CAMERA_POS, RU_LIGHT_POS, RU_LIGHT_COLOR,
    RU_LIGHT_COUNT, RU_ATTEN, RU_AMBIENT, RU_SHININESS, RU_F0, RU_VIEWPORT, RU_NORMAL_XY_SCALE,
    RU_LOD_BASE, RU_TESS_EDGE_REF, RU_LOD_ORIGIN, RU_LOD_OBJECT_DIST, RU_LOD_TILE, RU_LOD_TILED,
    RU_COUNT
};

typedef struct render__program {
    char *key;
    GLuint id;
    GLint loc[RU_COUNT];
    GLint *axis_loc;             /* per axis index: location of u_<axis>, or -1 */
} render__program;

typedef struct render__mesh {
    char *key;
    GLuint vao, vbo, ibo;
    size_t n_vertices, n_indices, bytes;
    size_t n_quad_indices;       /* quad patches after the triangles (mesh.h), 0 = none */
    cull_set cull;               /* triangle chunks with bounds (visibility_test), n = 0: none */
    GLuint seam_vbo;             /* patch meshes: canonical UV + normal per vertex, else 0 */
    float edge_median;           /* median edge length (mesh_edge_median): u_tess_edge_ref */
    int edge_factor_max;         /* largest mesh_edge_factor of its edges */
    int clip_space;
    size_t object_tris;          /* triangles per object (mesh.h object_triangles), 0 = one */
    float *cpu_pos;              /* patch meshes: xyz per vertex kept for the CPU's LOD */
    uint32_t *cpu_idx;           /* patch meshes: the index list (triangles, then quads) */
} render__mesh;

typedef struct render__item {
    int used;
    const technique_desc *tech;
    size_t prog, mesh, maps, sampler;
    float cam[4];                /* distance, azimuth, elevation, fov */
    float target[3];             /* camera.target_x/y/z: orbit centre */
    float light[3];              /* light.azimuth, light.elevation, light.distance */
    float orbit[2];              /* camera/light.orbit_deg_per_frame */
    uint64_t frame;              /* frame index the orbits turn by (render_set_frame) */
    int path_kind;               /* camera.path: RENDER__PATH_* */
    float path[3];               /* camera.path_frames, camera.dolly_to, camera.flyover_height */
    int debug_view;              /* render_debug_view it was prepared with */
    double *axis_val;            /* per axis index: numeric value (steps auto = 0) */
    int light_count;
    size_t patch_chunk;          /* patches per draw call (0 = one call), see render.c */
    int patch_vertices;          /* 3 (triangle patches) or 4 (quad patches, TESS_QUADS) */
    int cull;                    /* visibility_test on: draw only the chunks that can be seen */
    float cull_pad;              /* largest displacement, object units */
    int cull_off;                /* cull=off: back faces are rasterised too */
    GLuint lod_buf;              /* lod=cpu-per-patch: per-patch levels (lod_cpu.h), else 0 */
    float *lod_levels;           /* CPU side of lod_buf, 4 floats per patch */
    int lod_per_edge;            /* crack_free on: one level per outer edge */
    lod_object *lod_objects;     /* lod=object-points / object-cpu: one draw each, else NULL */
    size_t n_lod_objects;
    int lod_object_cpu;          /* object-cpu: the distance comes from the CPU */
    render_item_info info;
} render__item;

struct render_ctx {
    char *driver;                /* GL_RENDERER + GL_VERSION, part of program keys */
    char *cache_dir;             /* on-disk program binaries, NULL = off */
    float max_aniso;             /* 0 when anisotropic filtering is absent */
    int debug_view;              /* render_debug_view of the next prepared items */
    render__program *progs;
    size_t n_progs;
    render__mesh *meshes;
    size_t n_meshes;
    render__maps *maps;
    size_t n_maps;
    render__sampler *samplers;
    size_t n_samplers;
    render__item *items;
    size_t n_items;
    render_call_hook call_hook;  /* around each patch draw call (render_set_call_hook), NULL = none */
    void *call_user;
    size_t n_calls;              /* patch draw calls made so far in the frame being drawn */
};

typedef struct render__cfg {
    const dm_kv *kv;
    size_t n;
} render__cfg;

/* Grows a cache array by one zeroed element; returns its index. */
#define RENDER__PUSH(arr, n) \
    ((arr) = dm_xrealloc((arr), ((n) + 1) * sizeof *(arr)), \
     memset(&(arr)[(n)], 0, sizeof *(arr)), (n)++)

/* Value of axis `name`: the given parameter, else the axis default.  Inline
 * here, so render_textures.c reads parameters without calling back into
 * render.c (no circle of files). */
static inline const char *render__get(const render__cfg *c, const char *name)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->kv[i].key && strcmp(c->kv[i].key, name) == 0)
            return c->kv[i].value;
    const axis_info *a = axes_find(name);
    return a ? a->def : NULL;
}

#endif
