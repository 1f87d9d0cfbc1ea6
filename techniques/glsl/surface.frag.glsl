// surface.frag.glsl — every fragment-stage technique, chosen by #define
// (see technique_list.c): SURF_UNLIT, SURF_NORMAL_MAP, SURF_BUMP,
// SURF_PARALLAX 1|2|3, OFFSET_LIMIT_ON, SHADOW_RAYTRACE|SHADOW_SOFT,
// NORMAL_FORMAT_RG8|NORMAL_FORMAT_BC5 (two channels, z reconstructed),
// NORMAL_FORMAT_BC3NM (DXT5 with x in alpha: x,y = .a,.g, z reconstructed).
// A reconstructed z makes the normal unit length again, so Toksvig sees no
// shortening with the two-channel formats (nlen = 1).
// SURF_USER: a user technique (user_technique.c) — the user's file follows
// this one and defines user_surface(), which replaces parallax_uv(): it
// returns the visible point's UV and height, and shading, shadows and the
// lit point's offset follow as for pom; with USER_COLOR the user's
// user_color() shades that point instead.
// DEBUG_NORMALS (the renderer's normals view): the output is the world-space
// shading normal n*0.5+0.5.  The renderer then puts light slots 0..3 at the
// origin and the world unit vectors X, Y, Z, so light_ts[k] - light_ts[0] is
// the tangent-space image of world axis k: a row of the tangent-to-world
// frame of every vertex stage, with no change to SurfaceData.
#include "lighting.glsl"
#include "vt.glsl"

// DISPLACED_NORMALS_HEIGHT (displacing techniques, displaced_normals:
// height): shade with the normal rebuilt from the height map by central
// differences (SURF_BUMP), as S3 does after displacement, not the normal map.
#ifdef DISPLACED_NORMALS_HEIGHT
#undef SURF_NORMAL_MAP
#define SURF_BUMP
#endif

#ifndef SURF_PARALLAX
#define SURF_PARALLAX 0
#endif

layout(binding = 0) uniform sampler2D t_height;
layout(binding = 1) uniform sampler2D t_normal;
layout(binding = 2) uniform sampler2D t_albedo;
uniform float u_height_scale;
// Normal maps follow height_scale: x and y of the map's normal are scaled
// by u_normal_xy_scale = height_scale / the height_scale the map was made
// for (render.c; 1 for a user's normal file) before normalising — exact
// for a normal derived from a height field, n ∝ (−k·∂h/∂u, −k·∂h/∂v, 1).
uniform float u_normal_xy_scale;
// steps: a loop bound stays a uniform (a renderer sets it per material);
// steps = auto is compiled in (STEPS_AUTO): min_steps at normal view ..
// max_steps at grazing.
uniform int u_steps;
uniform int u_min_steps;
uniform int u_max_steps;
uniform float u_parallax_bias;   // plain parallax: bias as a fraction of the depth (0.5 default)

in SurfaceData {
    vec2 uv;
    vec3 view_ts;
    vec3 light_ts[MAX_LIGHTS];
} vi;

layout(location = 0) out vec4 o_color;

// V.z is clamped to at least this before dividing by it (Kaneko parallax and
// the searches), so grazing views give a long but finite offset.
const float PARALLAX_MIN_VZ = 0.05;

vec2 g_dx, g_dy;   // UV derivatives taken once in uniform control flow

float height_at(vec2 uv) { return map_sample(t_height, uv, g_dx, g_dy).r; }

#ifdef COUNT_LOOP_TRIPS
// LoopTrips (docs/counters.md): the first active fragment of each SIMD
// group adds one per iteration, so a group counts as many trips as its
// slowest fragment runs; FragmentGroups: it adds one as main() starts, so
// each group the driver runs counts once.  Only in the counting variant of
// the program.
layout(std430, binding = COUNT_LOOP_TRIPS) buffer LoopTrips { uint loop_trips; uint frag_groups; };
#endif

#if SURF_PARALLAX >= 2
int search_steps(vec3 v)
{
#ifdef STEPS_AUTO
    int n = int(mix(float(u_max_steps), float(u_min_steps), abs(v.z)));
#else
    int n = u_steps;
#endif
    return clamp(n, 1, 512);
}

// Steep search (and POM refinement).  The base surface (the mesh) lies at
// h = SURFACE_H0 inside the slab of heights 0..1 (displace.glsl, the same
// surface the displacing techniques and the reference mesh build), so the
// view ray through the base point uv enters the slab's top, h = 1, at
// uv + (1 - SURFACE_H0)·span and leaves its bottom at uv - SURFACE_H0·span,
// span = V.xy/V.z·scale.  The search starts at the entry and walks layers
// of depth 1/n toward the exit; returns the UV where the ray meets the field.
vec2 parallax_search(vec2 uv, vec3 v)
{
    int n = search_steps(v);
    float layer = 1.0 / float(n);
    vec2 span = v.xy / max(v.z, PARALLAX_MIN_VZ) * u_height_scale * UV_PER_WORLD;
    vec2 delta = -span * layer;
    uv += span * (1.0 - SURFACE_H0);
    float cur = 0.0, map = 1.0 - height_at(uv);
    vec2 prev_uv = uv;
    float prev = 0.0, prev_map = map;
    for (int i = 0; i < n && cur < map; i++) {
#ifdef COUNT_LOOP_TRIPS
        if (readFirstInvocationARB(gl_SubGroupInvocationARB) == gl_SubGroupInvocationARB)
            atomicAdd(loop_trips, 1u);
#endif
        prev_uv = uv; prev = cur; prev_map = map;
        uv += delta;
        cur += layer;
        map = 1.0 - height_at(uv);
    }
#if SURF_PARALLAX == 3
    float after = map - cur, before = prev_map - prev, den = after - before;
    float w = abs(den) > 1e-6 ? clamp(after / den, 0.0, 1.0) : 0.0;
    uv = mix(uv, prev_uv, w);
#endif
    return uv;
}
#endif

#ifdef SURF_USER
vec3 user_surface(vec2 uv, vec3 v);   // the user's file (docs/user-techniques.md)
#endif
#ifdef USER_COLOR
vec4 user_color(vec2 uv, vec3 v, vec3 at);   // optional: the user's shading of that point
#endif

vec2 parallax_uv(vec2 uv, vec3 v)
{
#if SURF_PARALLAX == 1
    // h' = (h - bias)·scale: with the default u_parallax_bias = SURFACE_H0
    // the offset to the point of the same surface as the search's (Kaneko's
    // scale/2); the parallax_bias axis moves the reference height.
    float scale = u_height_scale * UV_PER_WORLD, bias = scale * u_parallax_bias;
    float hp = height_at(uv) * scale - bias;
#ifdef OFFSET_LIMIT_ON
    return uv + hp * v.xy;                                  // Welsh
#else
    return uv + hp * v.xy / max(v.z, PARALLAX_MIN_VZ);      // Kaneko
#endif
#elif SURF_PARALLAX >= 2
    return parallax_search(uv, v);
#else
    return uv;
#endif
}

// Tangent-space normal at uv; nlen gets the filtered length (Toksvig).
vec3 surface_normal(vec2 uv, out float nlen)
{
    nlen = 1.0;
#if defined(SURF_NORMAL_MAP)
    vec4 t = map_sample(t_normal, uv, g_dx, g_dy);
#ifdef NORMAL_FORMAT_BC3NM
    vec3 n = vec3(t.a, t.g, 0.0) * 2.0 - 1.0;
#else
    vec3 n = t.xyz * 2.0 - 1.0;
#endif
#if defined(NORMAL_FORMAT_RG8) || defined(NORMAL_FORMAT_BC5) || defined(NORMAL_FORMAT_BC3NM)
    n.z = sqrt(max(0.0, 1.0 - dot(n.xy, n.xy)));
#endif
    nlen = length(n);
    n.xy *= u_normal_xy_scale;
    float len = length(n);
    return len > 1e-6 ? n / len : vec3(0.0, 0.0, 1.0);
#elif defined(SURF_BUMP)
    vec2 ts = map_size(t_height);
    vec2 du = vec2(1.0 / ts.x, 0.0), dv = vec2(0.0, 1.0 / ts.y);
    float k = u_height_scale * UV_PER_WORLD;
    float gu = (height_at(uv + du) - height_at(uv - du)) * ts.x * 0.5;
    float gv = (height_at(uv + dv) - height_at(uv - dv)) * ts.y * 0.5;
    return normalize(vec3(-k * gu, -k * gv, 1.0));
#else
    return vec3(0.0, 0.0, 1.0);
#endif
}

// Self-shadowing toward light direction l (tangent space, unit) from uv.
float self_shadow(vec2 uv, vec3 l)
{
#if (SURF_PARALLAX == 3 || defined(SURF_USER)) && (defined(SHADOW_RAYTRACE) || defined(SHADOW_SOFT) || defined(SHADOW_SOFT_S2))
    if (l.z <= 0.0)
        return 1.0;
    float h0 = height_at(uv);
    vec2 span = l.xy / max(l.z, PARALLAX_MIN_VZ) * u_height_scale * UV_PER_WORLD * (1.0 - h0);
#ifdef SHADOW_RAYTRACE
    // March toward the light in 30 steps; shadowed where the field is above the ray.
    for (int i = 1; i <= 30; i++) {
        float t = float(i) / 30.0;
        if (height_at(uv + span * t) > h0 + (1.0 - h0) * t + 1e-3)
            return 0.0;
    }
    return 1.0;
#elif defined(SHADOW_SOFT_S2)
    // S2's soft shadow with its own constants (its listing in section
    // 5.4.7.2): the same 7 samples at 0.88 .. 0.22 of the ray, penetration
    // h - h0 - t scaled by 5.1 - t (4.22 .. 4.88), shadow = (1 - max) * 0.45,
    // unclamped: S2 lets unshadowed fragments brighten (1 - max > 1) and
    // scales every fragment by 0.45.  The ray is dmbench's (toward the top
    // of the height slab), S2's ray was the light's xy times the bump scale.
    float occ = -1e9;
    for (int i = 0; i < 7; i++) {
        float t = 0.88 - 0.11 * float(i);
        occ = max(occ, (height_at(uv + span * t) - h0 - t) * (5.1 - t));
    }
    return (1.0 - occ) * 0.45;
#else
    // Soft (Tatarchuk 2006): 7 samples at 0.88 .. 0.22 of the ray, the
    // deepest penetration weighted toward the surface darkens most;
    // SOFT_SHADOW_SHARPNESS turns height units of penetration into shadow.
    const float SOFT_SHADOW_SHARPNESS = 32.0;
    float occ = 0.0;
    for (int i = 0; i < 7; i++) {
        float t = 0.88 - 0.11 * float(i);
        float above = height_at(uv + span * t) - (h0 + (1.0 - h0) * t);
        occ = max(occ, above * SOFT_SHADOW_SHARPNESS * (1.0 - t));
    }
    return 1.0 - clamp(occ, 0.0, 1.0);
#endif
#else
    return 1.0;
#endif
}

#ifdef DEBUG_NORMALS
// World-space normal of tangent-space n (see the top comment).
vec3 debug_world_normal(vec3 n)
{
    vec3 w = vec3(dot(vi.light_ts[1] - vi.light_ts[0], n), dot(vi.light_ts[2] - vi.light_ts[0], n),
                  dot(vi.light_ts[3] - vi.light_ts[0], n));
    float len = length(w);
    return len > 1e-6 ? w / len : vec3(0.0, 0.0, 1.0);
}
#endif

void main()
{
#ifdef COUNT_LOOP_TRIPS
    if (readFirstInvocationARB(gl_SubGroupInvocationARB) == gl_SubGroupInvocationARB)
        atomicAdd(frag_groups, 1u);
#endif
    g_dx = dFdx(vi.uv);
    g_dy = dFdy(vi.uv);
    vec3 v = normalize(vi.view_ts);
#ifdef SURF_USER
    vec3 surf = user_surface(vi.uv, v);
    vec2 uv = surf.xy;
#else
    vec2 uv = parallax_uv(vi.uv, v);
#endif
    vt_feedback(vi.uv, uv, g_dx, g_dy);
#ifdef SURF_USER
    vec3 at = vec3((uv - vi.uv) / UV_PER_WORLD, (surf.z - SURFACE_H0) * u_height_scale);
    v = normalize(vi.view_ts - at);
#elif SURF_PARALLAX > 0
    // Light the point of the relief that was found, not the base point the
    // rasteriser gave: its tangent-space offset from the base point (the
    // same surface the reference mesh displaces) moves the eye and lights.
    vec3 at = vec3((uv - vi.uv) / UV_PER_WORLD, (height_at(uv) - SURFACE_H0) * u_height_scale);
    v = normalize(vi.view_ts - at);
#else
    const vec3 at = vec3(0.0);
#endif
    vec3 albedo = map_sample(t_albedo, uv, g_dx, g_dy).rgb;
#ifdef SPECULAR_MAP_ON
    lighting_spec_k = map_sample(t_albedo, uv, g_dx, g_dy).a;   // specular in A (render_textures.c)
#endif
#if defined(DEBUG_NORMALS)
    float nlen;
    o_color = vec4(debug_world_normal(surface_normal(uv, nlen)) * 0.5 + 0.5, 1.0);
#elif defined(USER_COLOR)
    o_color = user_color(uv, v, at);
#elif defined(SURF_UNLIT)
    o_color = vec4(albedo, 1.0);
#else
    float nlen;
    vec3 n = surface_normal(uv, nlen);
    vec3 c = u_ambient * albedo;
    for (int i = 0; i < u_light_count && i < MAX_LIGHTS; i++)
        c += self_shadow(uv, normalize(vi.light_ts[i] - at))
           * lighting_light(n, v, vi.light_ts[i] - at, u_light_color[i], albedo, nlen);
    o_color = vec4(c, 1.0);
#endif
}
