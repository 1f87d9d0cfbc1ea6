/* lod_cpu.c — distance LOD on the CPU (see lod_cpu.h). */
#include "techniques/lod_cpu.h"
#include "techniques/mesh.h"

#include <math.h>

float lod_cpu_distance(const float eye[3], const float p[3])
{
    float dx = eye[0] - p[0], dy = eye[1] - p[1], dz = eye[2] - p[2];
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

/* level / max(|eye − p|, 1e-3), as GLSL's distance() then a division. */
static float lod_cpu__at(const float eye[3], const float p[3], float level)
{
    return level / fmaxf(lod_cpu_distance(eye, p), 1e-3f);
}

/* Corners of outer edge i (tess.tcs.glsl, outer_edge). */
static void lod_cpu__edge(int patch_n, int i, int *a, int *b)
{
    static const int tri[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    static const int quad[4][2] = {{0, 3}, {0, 1}, {1, 2}, {3, 2}};
    *a = patch_n == 4 ? quad[i][0] : tri[i][0];
    *b = patch_n == 4 ? quad[i][1] : tri[i][1];
}

/* The long-edge factor of the edge a-b (tess.tcs.glsl, edge_factor). */
static float lod_cpu__factor(const float *a, const float *b, float edge_ref)
{
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return (float)mesh_edge_factor(sqrtf(dx * dx + dy * dy + dz * dz), edge_ref);
}

/* The four slots of one patch whose corners are c[0..patch_n-1]. */
static void lod_cpu__patch(const float *c[4], int patch_n, const float eye[3], float level,
                           float edge_ref, int per_edge, float out[4])
{
    out[0] = out[1] = out[2] = out[3] = 0.0f;
    if (per_edge) {
        for (int i = 0; i < patch_n; i++) {
            int a, b;
            lod_cpu__edge(patch_n, i, &a, &b);
            float m[3];
            for (int k = 0; k < 3; k++)
                m[k] = 0.5f * (c[a][k] + c[b][k]);
            out[i] = lod_cpu__at(eye, m, lod_cpu__factor(c[a], c[b], edge_ref) * level);
        }
        return;
    }
    float f = 1.0f;   /* the patch's largest factor (patch_factor) */
    for (int i = 0; i < patch_n; i++)
        f = fmaxf(f, lod_cpu__factor(c[i], c[(i + 1) % patch_n], edge_ref));
    float centre[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < patch_n; i++)
        for (int k = 0; k < 3; k++)
            centre[k] += c[i][k];
    for (int k = 0; k < 3; k++)
        centre[k] /= (float)patch_n;
    out[0] = out[1] = out[2] = out[3] = lod_cpu__at(eye, centre, f * level);
}

void lod_cpu_levels(const float *pos, const uint32_t *idx, size_t n_patches, int patch_n,
                    const float eye[3], float level, float edge_ref, int per_edge, float *out)
{
    for (size_t p = 0; p < n_patches; p++) {
        const float *c[4] = {0};
        for (int i = 0; i < patch_n; i++)
            c[i] = pos + 3 * (size_t)idx[(size_t)patch_n * p + (size_t)i];
        lod_cpu__patch(c, patch_n, eye, level, edge_ref, per_edge, out + 4 * p);
    }
}

/* Bounds, origin and centre of the triangles of one object. */
static void lod_cpu__object(const float *pos, const uint32_t *idx, int tiled, lod_object *o)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 3 * o->first_tri; i < 3 * (o->first_tri + o->n_tris); i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], pos[3 * (size_t)idx[i] + (size_t)k]);
            hi[k] = fmaxf(hi[k], pos[3 * (size_t)idx[i] + (size_t)k]);
        }
    float tile[4] = {lo[0], lo[2], hi[0], hi[2]};
    for (int k = 0; k < 4; k++)
        o->tile[k] = tile[k];
    for (int k = 0; k < 3; k++) {
        o->centre[k] = 0.5f * (lo[k] + hi[k]);
        o->origin[k] = tiled && k != 1 ? o->centre[k] : 0.0f;
    }
}

size_t lod_cpu_objects(const float *pos, const uint32_t *idx, size_t n_tris, size_t object_tris,
                       lod_object *out)
{
    size_t run = object_tris ? object_tris : n_tris, n = 0;
    for (size_t first = 0; first < n_tris; first += run, n++) {
        out[n].first_tri = first;
        out[n].n_tris = n_tris - first < run ? n_tris - first : run;
        lod_cpu__object(pos, idx, object_tris != 0, &out[n]);
    }
    return n;
}
