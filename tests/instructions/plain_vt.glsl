// plain_vt.glsl — test-only stand-in for techniques/glsl/vt.glsl with no
// virtual-texturing code at all: the maps are plain textures.  The binary
// dmbench_plainshader embeds it in place of vt.glsl; test_instructions_uber
// asserts that every technique with virtual_texture: off costs the same
// instructions with the real vt.glsl as with this file, so no switched-off
// path of the harness is measured as part of a technique.
vec4 map_sample(sampler2D t, vec2 uv, vec2 dx, vec2 dy) { return textureGrad(t, uv, dx, dy); }

vec2 map_size(sampler2D t) { return vec2(textureSize(t, 0)); }

void vt_feedback(vec2 uv0, vec2 uv, vec2 dx, vec2 dy) {}
