/* lod_cpu.h — distance level of detail computed on the CPU (lod=cpu-distance).
 *
 * S4 compares the distance LOD computed in the control shader with the same
 * LOD computed on the CPU and handed to the shader.  This is that CPU side:
 * every draw, for every patch, the level the control stage's LOD_DISTANCE
 * would compute (tess.tcs.glsl), in the same float operations and order so
 * both give the same tessellation.  The renderer uploads the levels to a
 * buffer the control stage reads by patch (render.c).
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

#endif
