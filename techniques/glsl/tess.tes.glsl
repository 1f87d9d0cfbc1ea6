// tess.tes.glsl — evaluation stage of tess-displacement (S3): barycentric
// interpolation of position, normal, tangent and UV, the height read here
// and P' = P + N (h - h0) scale (displace.glsl).  Spacing by define
// (TESS_SPACING_EQUAL | TESS_SPACING_FRACTIONAL_EVEN | _ODD), ccw.
// CRACK_FREE_ON: a vertex on a patch edge (one barycentric coordinate, or u
// or v of a quad, exactly 0 or 1) reads its height at the interpolated
// *seam* UVs of the edge's corners and moves along their interpolated seam
// normals: the UV and normal of the first mesh vertex at each corner's
// position (render.c, mesh_canonical), which both patches of an edge share
// even where a UV seam gives them different UVs.  The seam UVs are unwrapped
// by whole tiles (the maps tile) toward the edge's smallest seam UV, so the
// two patches interpolate the same values in either corner order.
#include "displace.glsl"

// The height at uv.  Through the virtual texture (VT_SOFTWARE, VT_SPARSE)
// it is read from the finest resident page covering uv at level 0: what is
// resident is decided by the fragment stage's feedback, so where the
// fragments asked for a coarser level the surface is displaced by that
// level's heights (docs/textures.md).  Plain: level 0 of the height map.
#if defined(VT_SOFTWARE) || defined(VT_SPARSE)
#include "vt_table.glsl"
float tes_height(vec2 uv)
{
#ifdef VT_SPARSE
    return textureLod(t_height, uv, vt_resident(uv, 0)).r;
#else
    return textureLod(t_height, vt_phys_uv(uv, 0), 0.0).r;
#endif
}
#else
float tes_height(vec2 uv) { return textureLod(t_height, uv, 0.0).r; }
#endif

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

in GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; vec2 seam_uv; vec3 seam_nrm; } gi[];

// Corner normal of the smooth base: the seam normal under CRACK_FREE_ON so
// that Phong tessellation of a shared edge agrees too.
vec3 corner_nrm(int i)
{
#ifdef CRACK_FREE_ON
    return normalize(gi[i].seam_nrm);
#else
    return normalize(gi[i].nrm);
#endif
}

#ifdef CRACK_FREE_ON
// Height UV and displacement normal of an edge point with weights w (the
// corners off the edge have weight 0), from the corners' seam data.
void seam_edge(float w[PATCH_N], out vec2 uv, out vec3 n)
{
    vec2 ref = vec2(1e30);
    for (int i = 0; i < PATCH_N; i++) {
        vec2 c = gi[i].seam_uv;
        if (w[i] > 0.0 && (c.x < ref.x || (c.x == ref.x && c.y < ref.y)))
            ref = c;
    }
    uv = vec2(0.0);
    n = vec3(0.0);
    for (int i = 0; i < PATCH_N; i++)
        if (w[i] > 0.0) {
            uv += w[i] * (gi[i].seam_uv + round(ref - gi[i].seam_uv));
            n += w[i] * gi[i].seam_nrm;
        }
}
#endif

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
        vec3 ni = corner_nrm(i);
        q += w[i] * (p - dot(p - gi[i].pos, ni) * ni);
    }
    p = mix(p, q, PHONG_ALPHA);
#endif
    float h = tes_height(uv);
    vec3 dn = n;
#ifdef CRACK_FREE_ON
    if (on_edge) {
        vec2 su;
        seam_edge(w, su, dn);
        h = tes_height(su);
    }
#endif
    displace_emit(displace_point(p, dn, h), uv, n, t);
}
