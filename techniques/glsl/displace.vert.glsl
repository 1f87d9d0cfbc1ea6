// displace.vert.glsl — vertex-stage displacement (S1 methods 5-9) and the
// reference mesh.  The height is fetched per vertex:
//   VERTEX_FILTER_NEAREST          the texel containing uv (texelFetch, wrap)
//   VERTEX_FILTER_BILINEAR_HW      textureLod(level 0) through the sampler of
//                                  the `filter` axis (bilinear unless nearest)
//   VERTEX_FILTER_BILINEAR_MANUAL  4 texelFetch + 2 lerps at level 0
//   VERTEX_FILTER_MIP              manual bilinear at the level nearest to
//                                  lod = (z/w)·maxLevel, z/w of the clip-space
//                                  position of the undisplaced vertex mapped
//                                  to [0,1] (S1's rule; with near 0.05 it
//                                  is close to maxLevel for most scenes)
//   VERTEX_FILTER_MIP_LERP         lerp of manual bilinear at floor(lod) and
//                                  floor(lod)+1
// DISPLACE_REFERENCE: the mesh was already displaced on the CPU (the
// reference-mesh technique): no fetch, positions are used as they are.
// VISIBILITY_TEST_ON: a vertex whose undisplaced clip position lies outside
// the view volume widened by VISIBILITY_MARGIN (relative to w) skips the
// fetch and the displacement (S1 §6.2.5).  The renderer also draws only the
// chunks of the triangle list whose padded bounds can be seen (cull.h,
// RENDER__VISIBILITY_MARGIN must equal VISIBILITY_MARGIN).
#include "displace.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tan;

const float VISIBILITY_MARGIN = 0.1;

// Manual bilinear filter of level `lvl` with wrap-around (texel centres at
// (i + 0.5) / size, as GL's REPEAT sampling).  The level's size is level
// 0's halved lvl times (GL's rule for a complete mip chain), not
// textureSize(t_height, lvl): llvmpipe answers that query with one lane's
// level for all 8 lanes of a vertex batch, so where `mip` switches level
// between neighbouring vertices, a vertex shaded in two batches got two
// sizes, two heights and a row of holes (docs/llvmpipe-findings.md).
float bilinear_manual(vec2 uv, int lvl)
{
    ivec2 sz = max(textureSize(t_height, 0) >> lvl, ivec2(1));
    vec2 st = uv * vec2(sz) - 0.5;
    ivec2 i0 = ivec2(floor(st));
    vec2 f = st - vec2(i0);
    ivec2 a = (i0 % sz + sz) % sz, b = (a + 1) % sz;
    float h00 = texelFetch(t_height, a, lvl).r;
    float h10 = texelFetch(t_height, ivec2(b.x, a.y), lvl).r;
    float h01 = texelFetch(t_height, ivec2(a.x, b.y), lvl).r;
    float h11 = texelFetch(t_height, b, lvl).r;
    return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

float fetch_height(vec2 uv, vec4 clip)
{
#if defined(VERTEX_FILTER_BILINEAR_HW)
    return textureLod(t_height, uv, 0.0).r;
#elif defined(VERTEX_FILTER_BILINEAR_MANUAL)
    return bilinear_manual(uv, 0);
#elif defined(VERTEX_FILTER_MIP) || defined(VERTEX_FILTER_MIP_LERP)
    float max_level = float(textureQueryLevels(t_height) - 1);
    float lod = clamp((clip.z / clip.w) * 0.5 + 0.5, 0.0, 1.0) * max_level;
#if defined(VERTEX_FILTER_MIP)
    return bilinear_manual(uv, int(lod + 0.5));
#else
    int l0 = int(floor(lod));
    int l1 = min(l0 + 1, int(max_level));
    return mix(bilinear_manual(uv, l0), bilinear_manual(uv, l1), lod - float(l0));
#endif
#else
    ivec2 sz = textureSize(t_height, 0);
    ivec2 i = ivec2(floor(fract(uv) * vec2(sz)));
    return texelFetch(t_height, min(i, sz - 1), 0).r;
#endif
}

bool visible(vec4 c)
{
    float w = abs(c.w) * (1.0 + VISIBILITY_MARGIN);
    return c.w > 0.0 && all(lessThanEqual(abs(c.xyz), vec3(w)));
}

void main()
{
#ifdef DISPLACE_REFERENCE
    displace_emit((u_model * vec4(a_pos, 1.0)).xyz, a_uv, a_nrm, a_tan);
#else
    vec4 clip = u_view_proj * (u_model * vec4(a_pos, 1.0));
    float h = SURFACE_H0;
#ifdef VISIBILITY_TEST_ON
    // llvmpipe runs vertex shaders 8 lanes wide under an execution mask and
    // emits no jump around a per-lane condition (an if or a loop), so the
    // skipped fetches still execute there: no saving on that driver.
    if (visible(clip))
#endif
        h = fetch_height(a_uv, clip);
    displace_emit(displace_point(a_pos, a_nrm, h), a_uv, a_nrm, a_tan);
#endif
}
