// common.glsl — declarations shared by the surface stages.
#define MAX_LIGHTS 8
// The built-in plane maps 2 world units onto the UV range 0..1: a depth of
// u_height_scale world units is u_height_scale * UV_PER_WORLD in UV units.
#define UV_PER_WORLD 0.5
// The one surface convention (docs/techniques.md): the mesh is the base
// surface and lies at height h = SURFACE_H0 of the height field's 0..1
// range, so a point of height h is (h - SURFACE_H0)·u_height_scale world
// units above it along the normal — for the displacing techniques, the
// reference mesh (mesh.c) and the parallax family alike.  The procedural
// maps centre their heights on 0.5 (`flat` is 0.5 everywhere).
#define SURFACE_H0 0.5

uniform mat4 u_model;
uniform mat4 u_view_proj;
uniform mat3 u_normal_mat;
uniform vec3 u_camera_pos;
uniform vec3 u_light_pos[MAX_LIGHTS];
uniform int u_light_count;
