// normal-color.glsl — built-in `normal` with its shading written out in
// user_color() as well: normal map, ambient and the lights' loop with the
// built-in lighting helpers (tests/user_technique/contract.sh compares it
// with `normal` bit for bit).
//@technique normal-color
//@summary plain normal mapping, shaded by the user's colour function

vec3 user_surface(vec2 uv, vec3 v)
{
    return vec3(uv, SURFACE_H0);
}

vec4 user_color(vec2 uv, vec3 v, vec3 at)
{
    vec3 albedo = map_sample(t_albedo, uv, g_dx, g_dy).rgb;
    float nlen;
    vec3 n = surface_normal(uv, nlen);
    vec3 c = u_ambient * albedo;
    for (int i = 0; i < u_light_count && i < MAX_LIGHTS; i++)
        c += lighting_light(n, v, vi.light_ts[i] - at, u_light_color[i], albedo, nlen);
    return vec4(c, 1.0);
}
