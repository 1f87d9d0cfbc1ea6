//@technique nan
// the height of the right half of the surface is NaN, and so its colour
vec3 user_surface(vec2 uv, vec3 v)
{
    float zero = u_height_scale - u_height_scale;
    return vec3(uv, uv.x > 0.5 ? zero / zero : SURFACE_H0);
}
