// vt.glsl — sampling the material maps, plain or through the software
// virtual texture (techniques/vt.h), and the virtual texture's feedback.
// The path is compiled in, never switched by a uniform: a driver may run
// both sides of a branch on a uniform condition (llvmpipe 22.3 does), and
// the untaken virtual-texture side would then be measured as part of every
// technique (docs/techniques.md, "What a configuration's shader contains").
// Without VT_SOFTWARE: plain textures on units 0-2 (textureGrad).
// VT_SOFTWARE (virtual_texture: software): units 0-2 hold the physical page
// caches, unit 3 the page table (per level and page: slot, level of the
// resident page used); the level of detail is computed here from the UV
// derivatives; without VT_FILTER_TRILINEAR (nearest, bilinear) a sample
// reads round(lod), with it (trilinear, anisotropic) it blends floor(lod)
// and the next level; lod is clamped to the page levels.
// VT_SPARSE (virtual_texture: sparse, GL_ARB_sparse_texture): units 0-2
// are the sparse maps themselves, one mip level per page level; the page
// table gives the level of the finest resident page covering uv, and the
// sample reads that level (no residency query without ARB_sparse_texture2).
#if defined(VT_SOFTWARE) || defined(VT_SPARSE)
#include "vt_table.glsl"
uniform int u_vt_fb_width;    // feedback row length
layout(std430, binding = 0) buffer VtFeedback { uint vt_fb[]; };

const int VT_FEEDBACK_SCALE = 4;   // = VT_FEEDBACK_SCALE in vt.h

#ifdef VT_SPARSE
vec4 vt_sample(sampler2D t, vec2 uv, vec2 dx, vec2 dy)
{
    float lod = clamp(vt_lod(dx, dy), 0.0, float(u_vt_levels - 1));
#ifndef VT_FILTER_TRILINEAR
    return textureLod(t, uv, vt_resident(uv, int(lod + 0.5)));
#else
    int m0 = int(lod);
    vec4 c0 = textureLod(t, uv, vt_resident(uv, m0));
    if (m0 + 1 >= u_vt_levels)
        return c0;
    return mix(c0, textureLod(t, uv, vt_resident(uv, m0 + 1)), lod - float(m0));
#endif
}
#else
vec4 vt_sample(sampler2D t, vec2 uv, vec2 dx, vec2 dy)
{
    float lod = clamp(vt_lod(dx, dy), 0.0, float(u_vt_levels - 1));
#ifndef VT_FILTER_TRILINEAR
    return textureLod(t, vt_phys_uv(uv, int(lod + 0.5)), 0.0);
#else
    int m0 = int(lod);
    vec4 c0 = textureLod(t, vt_phys_uv(uv, m0), 0.0);
    if (m0 + 1 >= u_vt_levels)
        return c0;
    return mix(c0, textureLod(t, vt_phys_uv(uv, m0 + 1), 0.0), lod - float(m0));
#endif
}
#endif

vec4 map_sample(sampler2D t, vec2 uv, vec2 dx, vec2 dy) { return vt_sample(t, uv, dx, dy); }

// Texels per side of the maps: the virtual size.
vec2 map_size(sampler2D t) { return vec2(u_vt_size); }

// One fragment in VT_FEEDBACK_SCALE² records the page it wants: in a
// checkerboard of feedback texels, the page at the shaded uv and the page at
// the interpolated uv0 (parallax searches march between the two).
void vt_feedback(vec2 uv0, vec2 uv, vec2 dx, vec2 dy)
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (p.x % VT_FEEDBACK_SCALE != 0 || p.y % VT_FEEDBACK_SCALE != 0)
        return;
    if (((p.x + p.y) / VT_FEEDBACK_SCALE) % 2 != 0)
        uv = uv0;
    float lod = clamp(vt_lod(dx, dy), 0.0, float(u_vt_levels - 1));
#ifdef VT_FILTER_TRILINEAR
    int m = int(lod);
#else
    int m = int(lod + 0.5);
#endif
    ivec2 pg = vt_page_of(fract(uv), m);
    vt_fb[(p.y / VT_FEEDBACK_SCALE) * u_vt_fb_width + p.x / VT_FEEDBACK_SCALE] =
        uint(m) << 28 | uint(pg.y) << 14 | uint(pg.x);
}

#else   // plain textures

vec4 map_sample(sampler2D t, vec2 uv, vec2 dx, vec2 dy) { return textureGrad(t, uv, dx, dy); }

vec2 map_size(sampler2D t) { return vec2(textureSize(t, 0)); }

void vt_feedback(vec2 uv0, vec2 uv, vec2 dx, vec2 dy) {}

#endif
