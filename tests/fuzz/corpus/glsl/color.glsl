//@technique c
//@summary café
//@param c_f float -1e38 1e38 0 help
/* #include "x" */
vec4 user_color(vec2 uv, vec3 v, vec3 at) { return vec4(1.0); }
vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }
