/* mesh_scene.h — built-in scenes of several objects drawn as one mesh.
 *
 * Some studies measure a scene, not an object: S2's scene 1 draws several
 * objects of 22 086 polygons in all, S4's larger scene several asteroids
 * inside a skybox.  These are mesh values like the single objects
 * (mesh.h), built from them: each object is a built-in mesh moved and
 * scaled into place and appended, so the counts are sums of the objects'
 * known counts.
 *   s2-scene1     S2's scene 1: a ground plane of 64×64 quads (8 192
 *                 triangles) at y = -0.6, an icosphere of level 4 (5 120) of
 *                 radius 0.32 and a torus of 107 × 41 quads (8 774; ring
 *                 radius 0.3, tube 0.11) on it: 22 086 triangles, S2's
 *                 count exactly; density is ignored (0 only)
 *   s4-asteroids  S4's larger scene: a skybox cube of half size
 *                 MESH_SCENE_SKYBOX facing inward (12 triangles, first in
 *                 the index buffer, so drawn first) and MESH_SCENE_ASTEROIDS
 *                 copies of the `asteroid` body (CPU-displaced) at scale
 *                 MESH_SCENE_ASTEROID_SCALE; density = their icosphere level
 *                 (0..7, default 3): 12 + 5·20·4^level triangles
 *   s4-asteroids-reduced  the same with `asteroid-reduced` bodies (default
 *                 level 2: 12 + 1 600 triangles), to be displaced by a
 *                 technique with `maps: asteroid` and height_scale
 *                 MESH_ASTEROID_SCALE × MESH_SCENE_ASTEROID_SCALE (0.207)
 * The skybox reaches beyond the [-1,1]³ box of the single meshes so that
 * the default orbit camera (distance 3) is inside it. */
#ifndef TECHNIQUES_MESH_SCENE_H
#define TECHNIQUES_MESH_SCENE_H

#include "techniques/mesh.h"

#define MESH_SCENE_SKYBOX 10.0f
#define MESH_SCENE_ASTEROIDS 5
#define MESH_SCENE_ASTEROID_SCALE 0.3f

/* The scenes above at density d (checked, 0 replaced by the default:
 * mesh_list.c's rows), with tangents; 0 and out owns its arrays, or a
 * DM_ERR_* with out untouched.  mesh_build (mesh.h) reaches them by name. */
int mesh_scene_build_s2(int d, mesh_data *out);
int mesh_scene_build_s4(int d, mesh_data *out);
int mesh_scene_build_s4_reduced(int d, mesh_data *out);

#endif
