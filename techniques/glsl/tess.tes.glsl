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

#if defined(TESS_SPACING_FRACTIONAL_EVEN)
layout(triangles, fractional_even_spacing, ccw) in;
#elif defined(TESS_SPACING_FRACTIONAL_ODD)
layout(triangles, fractional_odd_spacing, ccw) in;
#else
layout(triangles, equal_spacing, ccw) in;
#endif

in GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; } gi[];

void main()
{
    vec3 b = gl_TessCoord;
    vec3 p = b.x * gi[0].pos + b.y * gi[1].pos + b.z * gi[2].pos;
    vec3 n = b.x * gi[0].nrm + b.y * gi[1].nrm + b.z * gi[2].nrm;
    vec2 uv = b.x * gi[0].uv + b.y * gi[1].uv + b.z * gi[2].uv;
    vec4 t = b.x * gi[0].tan + b.y * gi[1].tan + b.z * gi[2].tan;
    t.w = gi[0].tan.w;
    float h = textureLod(t_height, uv, 0.0).r;
#ifdef CRACK_FREE_ON
    if (min(b.x, min(b.y, b.z)) == 0.0)
        h = DISPLACE_H0;
#endif
    displace_emit(displace_point(p, n, h), uv, n, t);
}
