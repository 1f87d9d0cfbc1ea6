// relief.glsl — relief mapping: a linear search along the view ray for the
// first sample under the height field, then a binary search between that
// sample and the one before it.  Written against dmbench's user-technique
// contract (docs/user-techniques.md).
//@technique relief
//@summary relief mapping: linear search, then binary refinement
//@param relief_linear int 1 256 16 linear search steps
//@param relief_binary int 0 16 6 binary refinement steps

// The view ray crosses the height slab from depth 0 (height 1) at
// start = uv + span·(1 − SURFACE_H0) to depth 1 (height 0) at start − span;
// at depth d it is at start − span·d, below the field where d ≥ 1 − h.
bool relief_below(vec2 start, vec2 span, float d)
{
    return d >= 1.0 - height_at(start - span * d);
}

vec3 user_surface(vec2 uv, vec3 v)
{
    vec2 span = v.xy / max(v.z, PARALLAX_MIN_VZ) * u_height_scale * UV_PER_WORLD;
    vec2 start = uv + span * (1.0 - SURFACE_H0);
    float step = 1.0 / float(max(u_relief_linear, 1));
    float d = 0.0;
    for (int i = 0; i < u_relief_linear && !relief_below(start, span, d); i++)
        d += step;
    float lo = max(d - step, 0.0), hi = min(d, 1.0);
    for (int i = 0; i < u_relief_binary; i++) {
        float mid = 0.5 * (lo + hi);
        if (relief_below(start, span, mid))
            hi = mid;
        else
            lo = mid;
    }
    return vec3(start - span * hi, 1.0 - hi);
}
