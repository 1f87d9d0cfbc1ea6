// displace.glsl — shared by the geometry-displacing stages (tess.tes.glsl,
// displace.vert.glsl): the height map, the displacement rule and the
// SurfaceData output that surface.frag.glsl lights.
//   P' = P + N * (h - SURFACE_H0) * u_height_scale
// SURFACE_H0 (common.glsl) is the one surface convention every technique
// that reads the height map shares; a flat map displaces nothing and
// height_scale 0 equals the undisplaced mesh.
#include "common.glsl"

layout(binding = 0) uniform sampler2D t_height;
uniform float u_height_scale;

out SurfaceData {
    vec2 uv;
    vec3 view_ts;                 // surface -> eye, tangent space, unnormalised
    vec3 light_ts[MAX_LIGHTS];    // surface -> light i, tangent space, unnormalised
} vo;

// Moves object-space p along n by the height h; returns the world position.
vec3 displace_point(vec3 p, vec3 n, float h)
{
    vec3 q = p + normalize(n) * (h - SURFACE_H0) * u_height_scale;
    return (u_model * vec4(q, 1.0)).xyz;
}

// Writes SurfaceData and gl_Position for world position wp with the
// undisplaced frame (n, t): the normal map perturbs the base surface.
void displace_emit(vec3 wp, vec2 uv, vec3 nrm, vec4 tan)
{
    vec3 n = normalize(u_normal_mat * nrm);
    vec3 t = mat3(u_model) * tan.xyz;
    t = normalize(t - n * dot(n, t));
    vec3 b = cross(n, t) * tan.w;
    mat3 to_ts = transpose(mat3(t, b, n));
    vo.uv = uv;
    vo.view_ts = to_ts * (u_camera_pos - wp);
    for (int i = 0; i < MAX_LIGHTS; i++)
        vo.light_ts[i] = to_ts * (u_light_pos[i] - wp);
    gl_Position = u_view_proj * vec4(wp, 1.0);
}
