// pom-texel.glsl — parallax occlusion mapping whose step count follows the
// length of the view ray's footprint in height-map texels (one step per
// `texel_rate` texels crossed, within [texel_min_steps, texel_max_steps]),
// instead of built-in pom's fixed count or its mix by the view angle.  A
// ray seen from above crosses few texels and gets few steps; a grazing ray
// crosses many.  The hit is refined like built-in pom: the secant between
// the last two samples.  Written against dmbench's user-technique contract
// (docs/user-techniques.md).
//@technique pom-texel
//@summary POM with one search step per height-map texel the view ray crosses
//@param texel_rate float 0.25 16 2 texels crossed per search step
//@param texel_min_steps int 1 64 4 fewest steps
//@param texel_max_steps int 1 512 64 most steps

vec3 user_surface(vec2 uv, vec3 v)
{
    vec2 span = v.xy / max(v.z, PARALLAX_MIN_VZ) * u_height_scale * UV_PER_WORLD;
    float texels = length(span * map_size(t_height));
    int n = max(min(int(ceil(texels / u_texel_rate)), u_texel_max_steps), u_texel_min_steps);
    float layer = 1.0 / float(n);
    vec2 p = uv + span * (1.0 - SURFACE_H0), prev_p = p;
    float d = 0.0, gap = 1.0 - height_at(p), prev_gap = gap, prev_d = 0.0;
    for (int i = 0; i < n && d < gap; i++) {
        prev_p = p; prev_d = d; prev_gap = gap;
        p -= span * layer;
        d += layer;
        gap = 1.0 - height_at(p);
    }
    // secant: where the ray's depth meets the field's depth between the two
    float after = gap - d, before = prev_gap - prev_d, den = after - before;
    float w = abs(den) > 1e-6 ? clamp(after / den, 0.0, 1.0) : 0.0;
    return vec3(mix(p, prev_p, w), 1.0 - mix(d, prev_d, w));
}
