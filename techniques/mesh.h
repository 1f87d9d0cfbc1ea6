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

typedef struct mesh_desc {
    const char *name;       /* "plane", "cube", "triangle", "fullscreen", ... */
    int density;            /* 0 = mesh default; plane: vertices per side */
} mesh_desc;

/* Names of the built-in meshes, NULL-terminated. */
const char *const *mesh_names(void);
/* Builds a built-in mesh.  Returns 0, or DM_ERR_UNKNOWN for an unknown name
 * (out untouched) or DM_ERR_RANGE for a bad density. */
int mesh_build(const mesh_desc *desc, mesh_data *out);
/* Recomputes tangents from triangle edges and UV deltas (SEEDS S1 formula),
 * accumulated per vertex and Gram–Schmidt orthonormalised against the
 * normal.  Degenerate UV triangles (|M| tiny) and zero normals get a defined
 * fallback frame; never produces NaN. */
void mesh_generate_tangents(mesh_data *m);
/* Bytes the mesh occupies on the GPU (vertex + index buffers). */
size_t mesh_bytes(const mesh_data *m);
void mesh_free(mesh_data *m);

#endif
