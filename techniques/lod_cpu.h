/* lod_cpu.h — the CPU side of the distance levels of detail.
 *
 * lod=cpu-per-patch: every draw, for every patch, the level the control
 * stage's LOD_DISTANCE would compute (tess.tcs.glsl), in the same float
 * operations and order so both give the same tessellation; the renderer
 * uploads the levels to a buffer the control stage reads by patch
 * (render.c).  A check of the shader's levels, not one of study S4's
 * variants.
 *
 * lod=object-points / object-cpu (study S4, Tables 8.3 / 8.4): one level per
 * object.  lod_cpu_objects finds each object's tile, origin and
 * bounding-sphere centre once; object-cpu passes |eye − centre| as a
 * uniform at every draw (lod_cpu_distance), as S4 passed OpenSceneGraph's
 * getDistanceToViewPoint(getBound().center()).
 */
#ifndef TECHNIQUES_LOD_CPU_H
#define TECHNIQUES_LOD_CPU_H

#include <stddef.h>
#include <stdint.h>

/* Fills out[4·p .. 4·p+3] for each of n_patches patches of patch_n (3 or 4)
 * corners, corner k of patch p at pos[3·idx[patch_n·p + k]] (object space =
 * world space).  per_edge = 0: every slot = level / max(|eye − centre|,
 * 1e-3), centre = the corners' mean; per_edge = 1 (crack_free): slot i =
 * level / max(|eye − midpoint of outer edge i|, 1e-3), outer edge i as GL
 * numbers them (triangles: the edge opposite corner i; quads: u=0, v=0,
 * u=1, v=1), unused slots 0.  Each level is first multiplied by the long-edge
 * factor (mesh_edge_factor of the edge's length against edge_ref, the mesh's
 * median edge; per patch the largest of its edges'; edge_ref 0: factor 1),
 * as the shader does.  Levels are not clamped (the shader clamps). */
void lod_cpu_levels(const float *pos, const uint32_t *idx, size_t n_patches, int patch_n,
                    const float eye[3], float level, float edge_ref, int per_edge, float *out);

/* One object of lod object-points / object-cpu: triangles first_tri ..
 * first_tri + n_tris − 1 of the triangle list. */
typedef struct lod_object {
    size_t first_tri, n_tris;
    float tile[4];      /* its vertices' xmin, zmin, xmax, zmax (the tile's sides) */
    float origin[3];    /* tiled: the tile's centre on y = 0, else the mesh origin 0 */
    float centre[3];    /* bounding-sphere centre = its vertices' bounding-box centre */
} lod_object;

/* Splits n_tris triangles (3 indices each into pos, xyz per vertex) into
 * runs of object_tris (0: one object of all of them; a shorter last run
 * is an object too) and fills out[0 .. count−1]; returns the count, at most
 * max(1, ceil(n_tris / object_tris)), which out must hold.  n_tris 0: 0. */
size_t lod_cpu_objects(const float *pos, const uint32_t *idx, size_t n_tris, size_t object_tris,
                       lod_object *out);

/* |eye − p|: the distance object-cpu passes to the control stage. */
float lod_cpu_distance(const float eye[3], const float p[3]);

#endif
