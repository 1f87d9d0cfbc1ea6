// tess.tes.glsl — evaluation stage of tess-displacement (S3): barycentric
// interpolation of position, normal, tangent and UV, the height read here
// and P' = P + N (h - h0) scale (displace.glsl).  Spacing by define
// (TESS_SPACING_EQUAL | TESS_SPACING_FRACTIONAL_EVEN | _ODD), ccw.
// CRACK_FREE_ON: vertices on a patch edge (one barycentric coordinate
// exactly 0) are displaced by h0, i.e. they depend only on the positions and
// normals the two patches share — seam-consistent by construction even where
// the UVs (and so the sampled heights) of a seam disagree; the price is that
// patch edges stay on the base surface.
#include "displace.glsl"

// TESS_SMOOTH_PHONG: Phong tessellation (Boubekeur & Alexa 2008) of the base
// surface before displacement: the interpolated point is projected onto the
// tangent plane of each corner, the projections are interpolated with the
// same weights and blended with the flat point by PHONG_ALPHA.  A point on a
// patch edge depends only on that edge's two corners, so shared edges agree.
// TESS_QUADS: quad patches, bilinear interpolation of the four corners
// (domain order (0,0), (1,0), (1,1), (0,1)); an edge vertex has u or v
// exactly 0 or 1.
#ifdef TESS_QUADS
#define TESS_DOMAIN quads
#define PATCH_N 4
#else
#define TESS_DOMAIN triangles
#define PATCH_N 3
#endif
#if defined(TESS_SPACING_FRACTIONAL_EVEN)
layout(TESS_DOMAIN, fractional_even_spacing, ccw) in;
#elif defined(TESS_SPACING_FRACTIONAL_ODD)
layout(TESS_DOMAIN, fractional_odd_spacing, ccw) in;
#else
layout(TESS_DOMAIN, equal_spacing, ccw) in;
#endif

in GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; } gi[];

void main()
{
#ifdef TESS_QUADS
    vec2 f = gl_TessCoord.xy;
    float w[PATCH_N] = float[PATCH_N]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), f.x * f.y,
                                      (1.0 - f.x) * f.y);
    bool on_edge = min(min(f.x, f.y), min(1.0 - f.x, 1.0 - f.y)) == 0.0;
#else
    vec3 b = gl_TessCoord;
    float w[PATCH_N] = float[PATCH_N](b.x, b.y, b.z);
    bool on_edge = min(b.x, min(b.y, b.z)) == 0.0;
#endif
    vec3 p = vec3(0.0), n = vec3(0.0);
    vec2 uv = vec2(0.0);
    vec4 t = vec4(0.0);
    for (int i = 0; i < PATCH_N; i++) {
        p += w[i] * gi[i].pos;
        n += w[i] * gi[i].nrm;
        uv += w[i] * gi[i].uv;
        t += w[i] * gi[i].tan;
    }
    t.w = gi[0].tan.w;
#ifdef TESS_SMOOTH_PHONG
    const float PHONG_ALPHA = 0.75;
    vec3 q = vec3(0.0);
    for (int i = 0; i < PATCH_N; i++) {
        vec3 ni = normalize(gi[i].nrm);
        q += w[i] * (p - dot(p - gi[i].pos, ni) * ni);
    }
    p = mix(p, q, PHONG_ALPHA);
#endif
    float h = textureLod(t_height, uv, 0.0).r;
#ifdef CRACK_FREE_ON
    if (on_edge)
        h = DISPLACE_H0;
#endif
    displace_emit(displace_point(p, n, h), uv, n, t);
}
