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
    /* Quad patches (terrain only, else 0): n_quad_indices more indices stored
     * right after the triangle list in `indices`, 4 per quad in the order of
     * the tessellator's quad domain (u,v) = (0,0), (1,0), (1,1), (0,1),
     * counter-clockwise seen from the front.  Tessellating techniques draw
     * these as 4-vertex patches; everything else draws the triangles. */
    size_t n_quad_indices;
    /* Objects (terrain-tiles only, else 0 = the whole mesh is one object):
     * the triangle list is runs of object_triangles triangles, one run per
     * object, as study S4 drew its terrain tile by tile (lod object-points /
     * object-cpu compute one level per object). */
    size_t object_triangles;
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
 *               triangles (1 508 by default, as in study S3 (docs/studies.md))
 *   sphere      icosphere of radius 1; density = subdivision level 0..7,
 *               default 4: 20·4^level triangles (5 120), seam vertices
 *               duplicated so u runs past 1 instead of wrapping back
 *   terrain     rolling hills over [-1,1]² (XZ), y in about ±0.17; density
 *               = tiles per side, 1..512, default 16: (d+1)² shared
 *               vertices, 2d² triangles; each tile is also one quad patch
 *               (n_quad_indices), neighbouring tiles share their edge
 *               vertices (study S4 (docs/studies.md))
 *   terrain-tiles  study S4's tiled surface: the hills of `terrain` over
 *               [-1,1]² as d×d tiles (density 1..256, default 8) of 2×2
 *               cells, 8 triangles per tile listed tile by tile
 *               (object_triangles 8), (2d+1)² shared vertices; no quad
 *               patches: S4's tiles are triangle patches
 *   asteroid    the original body of study S4 (docs/studies.md): icosphere of level density
 *               (0..7, default 6: 81 920 triangles) displaced radially on
 *               the CPU by mesh_asteroid_radius, normals rebuilt from the
 *               faces
 *   asteroid-reduced  the reduced body: an undisplaced icosphere of radius
 *               MESH_ASTEROID_RMID, level density (0..7, default 2: 320
 *               triangles), with the sphere's UVs; drawn with `maps:
 *               asteroid` (height and normal baked from the same
 *               mesh_asteroid_radius) and height_scale MESH_ASTEROID_SCALE a
 *               displacing technique rebuilds the original's shape
 *   seam        test mesh: plane y = 0 over [-1,1]² of two halves x<0, x>0,
 *               each density × 2·density quads (1..256, default 4), the
 *               column x = 0 duplicated with the right half's UVs shifted by
 *               (0.37, 0.21): a UV seam whose sampled heights disagree
 *   halfflat    test mesh: as seam without the shift, but every left-half
 *               vertex off the shared column has UV (0.5, 0.5), so any height
 *               map is constant (flat) over most of the left half
 *   s2-scene1, s4-asteroids, s4-asteroids-reduced  scenes of several
 *               objects (techniques/mesh_scene.h)
 * cube, triangle and fullscreen accept and ignore densities up to 1024. */
typedef struct mesh_desc {
    const char *name;       /* "plane", "cube", "triangle", "fullscreen", ... */
    int density;            /* 0 = mesh default; see above */
} mesh_desc;

/* Names of the built-in meshes, NULL-terminated, in the order of the row
 * table of mesh_list.c (which mesh_build and mesh_density_range read). */
const char *const *mesh_names(void);
/* Builds a built-in mesh (NULL desc or name = "plane") with tangents
 * generated.  Returns 0 and out owns its arrays (mesh_free), or
 * DM_ERR_UNKNOWN for an unknown name / DM_ERR_RANGE for a bad density, with
 * out untouched. */
int mesh_build(const mesh_desc *desc, mesh_data *out);
/* The densities built-in mesh `name` accepts: 0 stands for *def, and an
 * explicit density must lie in [*lo, *hi] (a scene with *lo > *hi takes
 * only 0).  Returns 0, or DM_ERR_UNKNOWN for a name that is not built in
 * (a user mesh file ignores its density). */
int mesh_density_range(const char *name, int *def, int *lo, int *hi);
/* Recomputes tangents from triangle edges and UV deltas (study S1 (docs/studies.md) formula),
 * accumulated per vertex and Gram–Schmidt orthonormalised against the
 * normal.  Degenerate UV triangles (|M| < 1e-12) add nothing; a vertex left
 * without a usable tangent gets a unit vector perpendicular to its normal
 * (built from the coordinate axis least aligned with it), and a zero normal
 * is replaced by the normalised sum of its triangles' face normals, or +Z.
 * The sign w = +1 when cross(N, T) points along the accumulated bitangent,
 * else -1.  Never produces NaN. */
void mesh_generate_tangents(mesh_data *m);
/* Radius of the `asteroid` body along the unit direction p, within
 * [MESH_ASTEROID_RMIN, MESH_ASTEROID_RMAX]: the one height function both the
 * CPU-displaced mesh and the baked `asteroid` maps sample. */
float mesh_asteroid_radius(const float p[3]);
/* Bounds of mesh_asteroid_radius (0.82 ± the sum of its amplitudes) and the
 * reduced mesh's radius and height_scale: with the displacement rule
 * P' = P + N (h − 0.5) scale, a point at radius RMID with the baked height
 * h = (r − RMIN) / (RMAX − RMIN) lands at radius r exactly when
 * scale = RMAX − RMIN. */
#define MESH_ASTEROID_RMIN 0.475f
#define MESH_ASTEROID_RMAX 1.165f
#define MESH_ASTEROID_RMID 0.82f
#define MESH_ASTEROID_SCALE 0.69f
/* Unit direction of the sphere UV (u, v) (u = 0.5 + atan2(x, z)/2π,
 * v = 0.5 + asin(y)/π, as the sphere and asteroid meshes assign them). */
void mesh_sphere_dir(float u, float v, float p[3]);
/* Number of vertices per tessellation patch of a built-in mesh: 4 when it
 * has quad patches (terrain), else 3. */
int mesh_patch_vertices(const char *name);
/* Bilinear sample at (u, v) of a size×size height map (row 0 = v 0) with
 * wrap-around and texel centres at (i + 0.5)/size, as GL REPEAT sampling. */
float mesh_height_bilinear(const float *height, int size, float u, float v);
/* Height of the base surface in the height map's 0..1 range: the one surface
 * convention of every technique that reads heights (SURFACE_H0 in the GLSL,
 * docs/techniques.md). */
#define MESH_SURFACE_H0 0.5f
/* Edge-length rule shared by tess-displacement's levels and the reference
 * mesh's splits: an edge f times longer than the mesh's median edge gets f
 * times the level / splits, f = max(1, floor(len / median + SLACK)) (at most
 * 64), so long edges such as the cylinder's cap spokes are sampled as
 * densely as the rest while meshes of near-equal edges keep f = 1.  The
 * slack absorbs rounding of lengths that are whole multiples (the GLSL rule
 * in tess.tcs.glsl is the same). */
#define MESH_EDGE_FACTOR_SLACK 0.01f
/* Median of the triangles' edge lengths (object units, every triangle's
 * three edges); *longest (if given) gets the longest.  0 for no triangles. */
float mesh_edge_median(const mesh_data *m, float *longest);
int mesh_edge_factor(float len, float median);
/* Splits every triangle of `in` into a barycentric grid (points on shared
 * edges are bit-identical in both triangles, also across UV seams and
 * creases) and, when height is given, moves every new vertex along its
 * interpolated unit normal by (h − MESH_SURFACE_H0)·scale, h =
 * mesh_height_bilinear at its interpolated UV.  An edge is split k·f times
 * (f = mesh_edge_factor of its length), a triangle's interior as its most
 * split edge; a point on a less split edge snaps to that edge's grid, so
 * the result is watertight (degenerate triangles, no T-junctions).  Points
 * on seam edges (two positions joined by edges of different vertices: a UV
 * seam, the cylinder's rim) and their corners read h at the corners'
 * canonical UVs and move along their averaged normals (mesh_canonical),
 * so both sides displace a shared point identically.
 * Normals and tangents stay those of the undisplaced surface (per-pixel
 * normals come from the height field).  Returns 0 and out owns its arrays,
 * or DM_ERR_ARG (k < 1). */
int mesh_subdivide_displace(const mesh_data *in, int k, const float *height, int size,
                            float scale, mesh_data *out);
/* Triangles mesh_subdivide_displace(m, k, ...) produces. */
size_t mesh_subdivide_cost(const mesh_data *m, int k);
/* Seam data for crack-free tessellation: vertices at the same position
 * (bit-identical) are one surface point; each gets the UV of the
 * lowest-index vertex at its position and the normalised sum of the unit
 * normals there (the lowest-index vertex's normal when all are equal, as
 * on a UV seam): uv 2, nrm 3 floats per vertex.  Patches on both sides of
 * a seam or a crease (the cylinder's rim) then sample and displace their
 * shared edge alike.  mesh_canonical_index also gives the lowest index at
 * each vertex's position (first, 1 per vertex); any output may be NULL. */
void mesh_canonical(const mesh_data *m, float *uv, float *nrm);
void mesh_canonical_index(const mesh_data *m, uint32_t *first, float *uv, float *nrm);
/* Bytes the mesh occupies on the GPU (vertex + index buffers). */
size_t mesh_bytes(const mesh_data *m);
void mesh_free(mesh_data *m);

#endif
