// normal-user.glsl — built-in `normal` written as a user technique: the
// visible point is the rasterised one at the base height, so the built-in
// normal mapping and lighting shade it (tests/user_technique/normal.sh
// compares it with `normal` bit for bit).
//@technique normal-user
//@summary plain normal mapping through the user-technique path

vec3 user_surface(vec2 uv, vec3 v)
{
    return vec3(uv, SURFACE_H0);
}
