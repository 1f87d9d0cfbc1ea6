// tess-uniform.glsl — built-in tess-displacement's `lod: uniform` written as
// a user level function: every edge gets tess_level (on the plane every
// edge is of the median length, so the built-in's long-edge factor is 1).
//@technique tess-uniform
//@base tess-level
//@summary uniform tessellation through the user-technique path

float user_tess_level(vec3 a, vec3 b)
{
    return float(u_tess_level);
}
