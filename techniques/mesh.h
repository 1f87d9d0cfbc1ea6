/* mesh.h — CPU-side meshes: built-in procedural meshes and tangent frames.
 *
 * Every mesh is an indexed triangle list of interleaved vertices with
 * position, normal, UV and tangent (xyz + bitangent sign in w).  Meshes are
 * built in object space, centred on the origin, fitting the unit cube
 * [-1,1]^3 unless stated.  `triangle` and `fullscreen` are test meshes with
 * exactly known coverage: `fullscreen` is already in clip space (drawn with
 * an identity transform it covers the viewport exactly), `triangle` is one
 * triangle facing +Z (toward the default camera).
 */
#ifndef TECHNIQUES_MESH_H
#define TECHNIQUES_MESH_H

#include <stddef.h>
#include <stdint.h>

typedef struct mesh_vertex {
    float pos[3];
    float nrm[3];
    float uv[2];
    float tan[4];   /* tangent xyz, w = bitangent sign (+1/-1) */
} mesh_vertex;

typedef struct mesh_data {
    mesh_vertex *vertices;
    size_t n_vertices;
    uint32_t *indices;
    size_t n_indices;       /* multiple of 3 */
    int clip_space;         /* 1: positions are clip-space, draw with identity MVP */
} mesh_data;

/* Built-in meshes and what density means for each (0 = the default):
 *   plane       XZ ground plane over [-1,1]², normal +Y, u along +X, v along
 *               -Z; density = vertices per side, 2..1024, default 2
 *               (4 vertices, 2 triangles); (d-1)²·2 triangles
 *   cube        [-1,1]³, 24 vertices, 12 triangles, UV 0..1 per face
 *   triangle    one triangle in the XY plane facing +Z inside [-1,1]
 *   fullscreen  clip-space quad, 4 vertices, 2 triangles, z = 0, clip_space
 *   cylinder    radius 1, y in [-1,1]; density = segments, 3..1024, default
 *               58: segments × 12 side quads + two fans = 26·segments
 *               triangles (1 508 by default, as in SEEDS S3)
 *   sphere      icosphere of radius 1; density = subdivision level 0..7,
 *               default 4: 20·4^level triangles (5 120), seam vertices
 *               duplicated so u runs past 1 instead of wrapping back
 * cube, triangle and fullscreen accept and ignore densities up to 1024. */
typedef struct mesh_desc {
    const char *name;       /* "plane", "cube", "triangle", "fullscreen", ... */
    int density;            /* 0 = mesh default; see above */
} mesh_desc;

/* Names of the built-in meshes, NULL-terminated. */
const char *const *mesh_names(void);
/* Builds a built-in mesh (NULL desc or name = "plane") with tangents
 * generated.  Returns 0 and out owns its arrays (mesh_free), or
 * DM_ERR_UNKNOWN for an unknown name / DM_ERR_RANGE for a bad density, with
 * out untouched. */
int mesh_build(const mesh_desc *desc, mesh_data *out);
/* Recomputes tangents from triangle edges and UV deltas (SEEDS S1 formula),
 * accumulated per vertex and Gram–Schmidt orthonormalised against the
 * normal.  Degenerate UV triangles (|M| < 1e-12) add nothing; a vertex left
 * without a usable tangent gets a unit vector perpendicular to its normal
 * (built from the coordinate axis least aligned with it), and a zero normal
 * is replaced by the normalised sum of its triangles' face normals, or +Z.
 * The sign w = +1 when cross(N, T) points along the accumulated bitangent,
 * else -1.  Never produces NaN. */
void mesh_generate_tangents(mesh_data *m);
/* Bytes the mesh occupies on the GPU (vertex + index buffers). */
size_t mesh_bytes(const mesh_data *m);
void mesh_free(mesh_data *m);

#endif
