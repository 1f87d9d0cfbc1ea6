// tess.tcs.glsl — control stage of tess-displacement: levels and culling.
//   LOD_UNIFORM (default)  every level = u_tess_level
//   LOD_DISTANCE           level = u_tess_level / distance(camera, point)  (S4)
//   LOD_CPU_PER_PATCH      the same levels computed on the CPU every draw
//                          (lod_cpu.h) and read from cpu_levels[patch]
//   LOD_OBJECT_POINTS      one level per object (S4 Table 8.3): the object's
//                          origin and a helper point 100 units away along z
//                          transformed here; level = u_tess_level / distance
//                          (in object units) of the origin from the eye
//   LOD_OBJECT_CPU         one level per object (S4 Table 8.4): the CPU gives
//                          the distance from the eye to the object's
//                          bounding-sphere centre (u_lod_object_dist) and
//                          this stage divides u_tess_level by it
//                          The two OBJECT modes under CRACK_FREE_ON take an
//                          outer edge lying on a side of the object's tile
//                          (u_lod_tile) from that side's centre, as S4's
//                          border vertices did, by the helper points;
//                          every other edge and the inner level take the
//                          object's level.  The long-edge factor is not
//                          applied (S4 had none).
//   LOD_SCREEN_EDGE        level = projected edge length in pixels / TESS_TARGET_PX,
//                          at most u_tess_level
//   LOD_FLATNESS           u_tess_level where the height sampled at a few
//                          points varies by more than FLAT_EPS, else 1
//   LOD_CONSTANT           every outer and inner level = u_tess_level, no
//                          long-edge factor: S3's control stage, as S3 set it
// LOD_UNIFORM: u_tess_outer / u_tess_inner replace the outer / inner
// levels, S4's separate levels, unless TESS_OUTER_AUTO / TESS_INNER_AUTO
// (their axis is 'auto': u_tess_level) compiles that out.
// Long edges: under LOD_UNIFORM, LOD_DISTANCE and LOD_FLATNESS an edge
// f = max(1, floor(length / u_tess_edge_ref + 0.01)) times longer than the
// mesh's median edge (u_tess_edge_ref, object units) gets f times the level
// (techniques/mesh.h, mesh_edge_factor), so the cylinder's cap spokes are
// sampled like its sides; meshes of near-equal edges keep f = 1.
// LOD_USER: a user technique's level function (user_technique.c), its
// file appended to this one: level of an edge = user_tess_level(a, b) of
// its world-space endpoints; the patch takes the largest, as LOD_UNIFORM.
// CRACK_FREE_ON: outer level i from the edge opposite vertex i alone (its
// midpoint / endpoints / samples along it), so the two patches sharing an
// edge agree; inner = the largest outer.  Otherwise one level per patch.
// PATCH_CULL_ON: levels 0 (patch discarded) when the patch faces away from
// the camera or all its vertices lie outside one clip plane widened by
// CULL_MARGIN (relative to w) — displacement can move it back into view.
// TESS_QUADS: 4-vertex quad patches (the terrain tiles, study S4 (docs/studies.md)), corners
// in domain order (0,0), (1,0), (1,1), (0,1); outer level i belongs to
// edge u=0, v=0, u=1, v=1 as GL defines them, inner 0 / 1 to the u / v
// direction.  Otherwise triangle patches: outer level i belongs to the edge
// opposite vertex i.
#include "common.glsl"

#ifdef TESS_QUADS
#define PATCH_N 4
#else
#define PATCH_N 3
#endif

layout(vertices = PATCH_N) out;

layout(binding = 0) uniform sampler2D t_height;
uniform int u_tess_level;
uniform float u_height_scale;
uniform vec2 u_viewport;
uniform int u_tess_inner;
uniform int u_tess_outer;

#ifdef LOD_CPU_PER_PATCH
// Per patch: the outer levels (per edge under CRACK_FREE_ON, else the patch
// level in every slot), unclamped; patch = u_lod_base + gl_PrimitiveID.
layout(std430, binding = 3) readonly buffer CpuLevels { vec4 cpu_levels[]; };
uniform int u_lod_base;     // first patch of this draw call
#endif
uniform float u_tess_edge_ref;
#if defined(LOD_OBJECT_POINTS) || defined(LOD_OBJECT_CPU)
#define LOD_OBJECT
uniform vec3 u_lod_origin;       // the object's origin, object space (points)
uniform float u_lod_object_dist; // eye to bounding-sphere centre (cpu)
uniform vec4 u_lod_tile;         // the tile's xmin, zmin, xmax, zmax
uniform int u_lod_tiled;         // 0: the object has no tile sides
#endif

const float TESS_TARGET_PX = 8.0;
const float FLAT_EPS = 1e-3;     // world units of displacement range
const float CULL_MARGIN = 0.1;

in GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; vec2 seam_uv; vec3 seam_nrm; } gi[];
out GeomData { vec3 pos; vec3 nrm; vec2 uv; vec4 tan; vec2 seam_uv; vec3 seam_nrm; } go[];

vec3 wpos(int i) { return (u_model * vec4(gi[i].pos, 1.0)).xyz; }

vec2 screen(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return c.xy / max(c.w, 1e-4) * 0.5 * u_viewport;
}

// Height range (world units) over n+1 samples between uv a and b.
float range_along(vec2 a, vec2 b, int n)
{
    float lo = 1e9, hi = -1e9;
    for (int k = 0; k <= n; k++) {
        float h = textureLod(t_height, mix(a, b, float(k) / float(n)), 0.0).r;
        lo = min(lo, h);
        hi = max(hi, h);
    }
    return (hi - lo) * abs(u_height_scale);
}

// Long-edge factor of the edge a-b (see the top comment); 1 under
// LOD_CONSTANT, which takes u_tess_level as it is.
float edge_factor(int a, int b)
{
#ifdef LOD_CONSTANT
    return 1.0;
#else
    float f = u_tess_edge_ref > 0.0 ? floor(distance(gi[a].pos, gi[b].pos) / u_tess_edge_ref + 0.01) : 1.0;
    return clamp(f, 1.0, 64.0);
#endif
}

#ifdef LOD_USER
float user_tess_level(vec3 a, vec3 b);   // the user's file (docs/user-techniques.md)
#endif

float edge_level(int a, int b)
{
#if defined(LOD_USER)
    return user_tess_level(wpos(a), wpos(b));
#elif defined(LOD_DISTANCE)
    return edge_factor(a, b) * float(u_tess_level) / max(distance(u_camera_pos, 0.5 * (wpos(a) + wpos(b))), 1e-3);
#elif defined(LOD_SCREEN_EDGE)
    return min(distance(screen(wpos(a)), screen(wpos(b))) / TESS_TARGET_PX, float(u_tess_level));
#elif defined(LOD_FLATNESS)
    return range_along(gi[a].uv, gi[b].uv, 8) > FLAT_EPS ? edge_factor(a, b) * float(u_tess_level) : 1.0;
#else
    return edge_factor(a, b) * float(u_tess_level);
#endif
}

// Largest long-edge factor of the patch's edges.
float patch_factor()
{
    float f = 1.0;
    for (int i = 0; i < PATCH_N; i++)
        f = max(f, edge_factor(i, (i + 1) % PATCH_N));
    return f;
}

// Corners of outer edge i: for triangles the edge opposite vertex i, for
// quads the GL order u=0 (0-3), v=0 (0-1), u=1 (1-2), v=1 (3-2).
ivec2 outer_edge(int i)
{
#ifdef TESS_QUADS
    const ivec2 e[4] = ivec2[4](ivec2(0, 3), ivec2(0, 1), ivec2(1, 2), ivec2(3, 2));
#else
    const ivec2 e[3] = ivec2[3](ivec2(1, 2), ivec2(2, 0), ivec2(0, 1));
#endif
    return e[i];
}

#ifdef LOD_OBJECT
// S4's two helper points: the distance from the eye of object-space point o
// in object units, 100 · |o'| / |o' − h'| where o' and h' are o and
// o + (0, 0, 100) after the model transform, relative to the eye (the view
// rotation keeps lengths, so world space minus the eye stands for view space).
float helper_distance(vec3 o)
{
    vec3 p = (u_model * vec4(o, 1.0)).xyz - u_camera_pos;
    vec3 q = (u_model * vec4(o + vec3(0.0, 0.0, 100.0), 1.0)).xyz - u_camera_pos;
    return 100.0 * (length(p) / distance(p, q));
}

float object_level()
{
#ifdef LOD_OBJECT_CPU
    float d = u_lod_object_dist;
#else
    float d = helper_distance(u_lod_origin);
#endif
    return float(u_tess_level) / max(d, 1e-3);
}

// Outer edge i: on a side of the tile, the level of that side's centre
// (y = 0); else the object's level.
float object_edge_level(int i)
{
    ivec2 ab = outer_edge(i);
    vec3 a = gi[ab.x].pos, b = gi[ab.y].pos;
    vec4 t = u_lod_tile;
    vec2 mid = 0.5 * (t.xy + t.zw);
    vec3 c;
    if (u_lod_tiled == 0)
        return object_level();
    if (a.x == t.x && b.x == t.x)
        c = vec3(t.x, 0.0, mid.y);
    else if (a.x == t.z && b.x == t.z)
        c = vec3(t.z, 0.0, mid.y);
    else if (a.z == t.y && b.z == t.y)
        c = vec3(mid.x, 0.0, t.y);
    else if (a.z == t.w && b.z == t.w)
        c = vec3(mid.x, 0.0, t.w);
    else
        return object_level();
    return float(u_tess_level) / max(helper_distance(c), 1e-3);
}
#endif

vec3 patch_centre()
{
    vec3 c = vec3(0.0);
    for (int i = 0; i < PATCH_N; i++)
        c += wpos(i);
    return c / float(PATCH_N);
}

float patch_level()
{
#if defined(LOD_OBJECT)
    return object_level();
#elif defined(LOD_CPU_PER_PATCH)
    return cpu_levels[u_lod_base + gl_PrimitiveID].x;
#elif defined(LOD_DISTANCE)
    return patch_factor() * float(u_tess_level) / max(distance(u_camera_pos, patch_centre()), 1e-3);
#elif defined(LOD_FLATNESS)
    // Every edge and every corner-to-centre line: 2 × PATCH_N × 9 samples.
    vec2 c = vec2(0.0);
    for (int i = 0; i < PATCH_N; i++)
        c += gi[i].uv / float(PATCH_N);
    float r = 0.0;
    for (int i = 0; i < PATCH_N; i++)
        r = max(r, max(range_along(gi[i].uv, gi[(i + 1) % PATCH_N].uv, 8), range_along(gi[i].uv, c, 8)));
    return r > FLAT_EPS ? patch_factor() * float(u_tess_level) : 1.0;
#else
    float l = 0.0;
    for (int i = 0; i < PATCH_N; i++)
        l = max(l, edge_level(i, (i + 1) % PATCH_N));
    return l;
#endif
}


// Outer level i of CRACK_FREE_ON: the level of its edge alone.
float outer_level(int i)
{
#if defined(LOD_OBJECT)
    return object_edge_level(i);
#elif defined(LOD_CPU_PER_PATCH)
    return cpu_levels[u_lod_base + gl_PrimitiveID][i];
#else
    ivec2 ab = outer_edge(i);
    return edge_level(ab.x, ab.y);
#endif
}

// LOD_UNIFORM: the tess_outer / tess_inner axes where they are not auto.
void fixed_levels()
{
#if defined(LOD_UNIFORM) && !defined(TESS_OUTER_AUTO)
    for (int i = 0; i < PATCH_N; i++)
        gl_TessLevelOuter[i] = clamp(float(u_tess_outer), 1.0, 64.0);
#endif
#if defined(LOD_UNIFORM) && !defined(TESS_INNER_AUTO)
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = clamp(float(u_tess_inner), 1.0, 64.0);
#endif
}

bool culled()
{
#ifdef PATCH_CULL_ON
#ifdef TESS_QUADS
    vec3 face = cross(wpos(2) - wpos(0), wpos(3) - wpos(1));   // diagonals
#else
    vec3 face = cross(wpos(1) - wpos(0), wpos(2) - wpos(0));
#endif
    if (dot(face, u_camera_pos - patch_centre()) < 0.0)
        return true;
    vec4 c[PATCH_N];
    for (int i = 0; i < PATCH_N; i++)
        c[i] = u_view_proj * vec4(wpos(i), 1.0);
    for (int ax = 0; ax < 3; ax++) {
        bool lo = true, hi = true;
        for (int i = 0; i < PATCH_N; i++) {
            float w = c[i].w * (1.0 + CULL_MARGIN);
            lo = lo && c[i][ax] < -w;
            hi = hi && c[i][ax] > w;
        }
        if (lo || hi)
            return true;
    }
#endif
    return false;
}

void main()
{
    go[gl_InvocationID].pos = gi[gl_InvocationID].pos;
    go[gl_InvocationID].nrm = gi[gl_InvocationID].nrm;
    go[gl_InvocationID].uv = gi[gl_InvocationID].uv;
    go[gl_InvocationID].tan = gi[gl_InvocationID].tan;
    go[gl_InvocationID].seam_uv = gi[gl_InvocationID].seam_uv;
    go[gl_InvocationID].seam_nrm = gi[gl_InvocationID].seam_nrm;
    // Every invocation computes the same levels (no early return: llvmpipe
    // drops patches when only invocation 0 writes them).
    if (culled()) {
        for (int i = 0; i < 4; i++)
            gl_TessLevelOuter[i] = 0.0;
        gl_TessLevelInner[0] = gl_TessLevelInner[1] = 0.0;
        return;
    }
#ifdef CRACK_FREE_ON
    float e[PATCH_N];
    for (int i = 0; i < PATCH_N; i++) {
        e[i] = clamp(outer_level(i), 1.0, 64.0);
        gl_TessLevelOuter[i] = e[i];
    }
#ifdef TESS_QUADS
    gl_TessLevelInner[0] = max(e[1], e[3]);   // along u: the edges v=0 and v=1
    gl_TessLevelInner[1] = max(e[0], e[2]);
#elif defined(LOD_OBJECT)
    gl_TessLevelInner[0] = clamp(object_level(), 1.0, 64.0);   // S4: from the object's centre
#else
    gl_TessLevelInner[0] = max(e[0], max(e[1], e[2]));
#endif
#else
    float l = clamp(patch_level(), 1.0, 64.0);
    for (int i = 0; i < PATCH_N; i++)
        gl_TessLevelOuter[i] = l;
    gl_TessLevelInner[0] = gl_TessLevelInner[1] = l;
#endif
    fixed_levels();
}
