// tess-view.glsl — a tessellation level from the distance to the
// camera and the height field's relief: an edge of world length L seen from
// distance d covers about L/d of the view; it gets enough segments that
// each covers `tess_view_step` of it, scaled by `tess_relief_gain` times
// the displacement depth, within [1, tess_level].  A user's LOD heuristic
// measured against built-in tess-displacement's lod axis
// (docs/user-techniques.md).
//@technique tess-view
//@base tess-level
//@summary tessellation level from the edge's angular size and the relief depth
//@param tess_view_step float 0.001 1 0.02 angular size (radians) per segment
//@param tess_relief_gain float 0 100 10 extra segments per world unit of displacement depth

float user_tess_level(vec3 a, vec3 b)
{
    vec3 mid = 0.5 * (a + b);
    float angle = distance(a, b) / max(distance(u_camera_pos, mid), 1e-3);
    float level = angle / u_tess_view_step * (1.0 + u_tess_relief_gain * abs(u_height_scale));
    return clamp(level, 1.0, float(u_tess_level));
}
