// tess.tcs.glsl — control stage of tess-displacement: levels and culling.
//   LOD_UNIFORM (default)  every level = u_tess_level
//   LOD_DISTANCE           level = u_tess_level / distance(camera, point)  (S4)
//   LOD_SCREEN_EDGE        level = projected edge length in pixels / TESS_TARGET_PX,
//                          at most u_tess_level
//   LOD_FLATNESS           u_tess_level where the height sampled at a few
//                          points varies by more than FLAT_EPS, else 1
// CRACK_FREE_ON: outer level i from the edge opposite vertex i alone (its
// midpoint / endpoints / samples along it), so the two patches sharing an
// edge agree; inner = the largest outer.  Otherwise one level per patch.
// PATCH_CULL_ON: levels 0 (patch discarded) when the patch faces away from
// the camera or all its vertices lie outside one clip plane widened by
// CULL_MARGIN (relative to w) — displacement can move it back into view.
#include "common.glsl"

layout(vertices = 3) out;

layout(binding = 0) uniform sampler2D t_height;
uniform int u_tess_level;
uniform float u_height_scale;
uniform vec2 u_viewport;

const float TESS_TARGET_PX = 8.0;
const float FLAT_EPS = 1e-3;     // world units of displacement range
const float CULL_MARGIN = 0.1;

in GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; } gi[];
out GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; } go[];

vec3 wpos(int i) { return (u_model * vec4(gi[i].pos, 1.0)).xyz; }

vec2 screen(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return c.xy / max(c.w, 1e-4) * 0.5 * u_viewport;
}

// Height range (world units) over n+1 samples between uv a and b.
float range_along(vec2 a, vec2 b, int n)
{
    float lo = 1e9, hi = -1e9;
    for (int k = 0; k <= n; k++) {
        float h = textureLod(t_height, mix(a, b, float(k) / float(n)), 0.0).r;
        lo = min(lo, h);
        hi = max(hi, h);
    }
    return (hi - lo) * abs(u_height_scale);
}

float edge_level(int a, int b)
{
#if defined(LOD_DISTANCE)
    return float(u_tess_level) / max(distance(u_camera_pos, 0.5 * (wpos(a) + wpos(b))), 1e-3);
#elif defined(LOD_SCREEN_EDGE)
    return min(distance(screen(wpos(a)), screen(wpos(b))) / TESS_TARGET_PX, float(u_tess_level));
#elif defined(LOD_FLATNESS)
    return range_along(gi[a].uv, gi[b].uv, 8) > FLAT_EPS ? float(u_tess_level) : 1.0;
#else
    return float(u_tess_level);
#endif
}

float patch_level()
{
#if defined(LOD_DISTANCE)
    return float(u_tess_level) / max(distance(u_camera_pos, (wpos(0) + wpos(1) + wpos(2)) / 3.0), 1e-3);
#elif defined(LOD_FLATNESS)
    // Three edges and three medians: 6 × 9 samples over the patch.
    vec2 c = (gi[0].uv + gi[1].uv + gi[2].uv) / 3.0;
    float r = 0.0;
    for (int i = 0; i < 3; i++)
        r = max(r, max(range_along(gi[i].uv, gi[(i + 1) % 3].uv, 8), range_along(gi[i].uv, c, 8)));
    return r > FLAT_EPS ? float(u_tess_level) : 1.0;
#else
    return max(edge_level(0, 1), max(edge_level(1, 2), edge_level(2, 0)));
#endif
}

bool culled()
{
#ifdef PATCH_CULL_ON
    vec3 p0 = wpos(0), p1 = wpos(1), p2 = wpos(2);
    if (dot(cross(p1 - p0, p2 - p0), u_camera_pos - p0) < 0.0)
        return true;
    vec4 c[3];
    for (int i = 0; i < 3; i++)
        c[i] = u_view_proj * vec4(wpos(i), 1.0);
    for (int ax = 0; ax < 3; ax++) {
        bool lo = true, hi = true;
        for (int i = 0; i < 3; i++) {
            float w = c[i].w * (1.0 + CULL_MARGIN);
            lo = lo && c[i][ax] < -w;
            hi = hi && c[i][ax] > w;
        }
        if (lo || hi)
            return true;
    }
#endif
    return false;
}

void main()
{
    go[gl_InvocationID].pos = gi[gl_InvocationID].pos;
    go[gl_InvocationID].nrm = gi[gl_InvocationID].nrm;
    go[gl_InvocationID].uv = gi[gl_InvocationID].uv;
    go[gl_InvocationID].tan = gi[gl_InvocationID].tan;
    // Every invocation computes the same levels (no early return: llvmpipe
    // drops patches when only invocation 0 writes them).
    if (culled()) {
        gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = 0.0;
        gl_TessLevelInner[0] = 0.0;
        return;
    }
#ifdef CRACK_FREE_ON
    float e0 = clamp(edge_level(1, 2), 1.0, 64.0);
    float e1 = clamp(edge_level(2, 0), 1.0, 64.0);
    float e2 = clamp(edge_level(0, 1), 1.0, 64.0);
    gl_TessLevelOuter[0] = e0;
    gl_TessLevelOuter[1] = e1;
    gl_TessLevelOuter[2] = e2;
    gl_TessLevelInner[0] = max(e0, max(e1, e2));
#else
    float l = clamp(patch_level(), 1.0, 64.0);
    gl_TessLevelOuter[0] = gl_TessLevelOuter[1] = gl_TessLevelOuter[2] = l;
    gl_TessLevelInner[0] = l;
#endif
}
