// surface.vert.glsl — TBN in the vertex stage (study S1 (docs/studies.md) method 3): the view
// and light vectors are moved into tangent space and interpolated.
#include "common.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tan;

out SurfaceData {
    vec2 uv;
    vec3 view_ts;                 // surface -> eye, tangent space, unnormalised
    vec3 light_ts[MAX_LIGHTS];    // surface -> light i, tangent space, unnormalised
} vo;

void main()
{
    vec4 wp = u_model * vec4(a_pos, 1.0);
    vec3 n = normalize(u_normal_mat * a_nrm);
    vec3 t = mat3(u_model) * a_tan.xyz;
    t = normalize(t - n * dot(n, t));
    vec3 b = cross(n, t) * a_tan.w;
    mat3 to_ts = transpose(mat3(t, b, n));
    vo.uv = a_uv;
    vo.view_ts = to_ts * (u_camera_pos - wp.xyz);
    for (int i = 0; i < MAX_LIGHTS; i++)
        vo.light_ts[i] = to_ts * (u_light_pos[i] - wp.xyz);
    gl_Position = u_view_proj * wp;
}
