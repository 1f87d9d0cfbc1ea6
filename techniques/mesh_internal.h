/* mesh_internal.h — the builders of the built-in meshes, shared by the
 * files of the mesh family: mesh.c defines the single meshes, mesh_scene.c
 * the scenes built from them, and mesh_list.c's row table {name, build,
 * default, lo, hi} names them all for mesh_build (mesh.h).  Nothing else
 * includes it.
 *
 * Each builder makes its mesh at density d, which the caller has checked
 * against the row's range and in which 0 has been replaced by the default,
 * with tangents; 0 and out owns its arrays, or a DM_ERR_* with out
 * untouched. */
#ifndef TECHNIQUES_MESH_INTERNAL_H
#define TECHNIQUES_MESH_INTERNAL_H

#include "techniques/mesh.h"

typedef int (*mesh__build_fn)(int d, mesh_data *out);

/* mesh.c: the single meshes (mesh.h says what density means for each). */
int mesh__build_plane(int d, mesh_data *out);
int mesh__build_cube(int d, mesh_data *out);
int mesh__build_triangle(int d, mesh_data *out);
int mesh__build_fullscreen(int d, mesh_data *out);
int mesh__build_cylinder(int d, mesh_data *out);
int mesh__build_sphere(int d, mesh_data *out);
int mesh__build_terrain(int d, mesh_data *out);
int mesh__build_asteroid(int d, mesh_data *out);
int mesh__build_seam(int d, mesh_data *out);
int mesh__build_halfflat(int d, mesh_data *out);
int mesh__build_asteroid_reduced(int d, mesh_data *out);
int mesh__build_terrain_tiles(int d, mesh_data *out);

#endif
