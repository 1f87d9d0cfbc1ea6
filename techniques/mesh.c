/* mesh.c — built-in procedural meshes and tangent frames (see mesh.h). */
#include "techniques/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "techniques/mesh_scene.h"

#define MESH__PI 3.14159265358979323846f
#define MESH__CYL_STACKS 12

static const char *const mesh__names[] = {
    "plane", "cube", "triangle", "fullscreen", "cylinder", "sphere", "terrain", "asteroid",
    "seam", "halfflat", "asteroid-reduced", "s2-scene1", "s4-asteroids", "s4-asteroids-reduced", NULL
};

const char *const *mesh_names(void) { return mesh__names; }

/* Growable builder: vertices and indices appended in order. */
typedef struct mesh__builder {
    mesh_data *m;
    size_t cap_v, cap_i;
} mesh__builder;

static uint32_t mesh__vert(mesh__builder *b, const float p[3], const float n[3],
                           float u, float v)
{
    if (b->m->n_vertices == b->cap_v) {
        b->cap_v = b->cap_v ? b->cap_v * 2 : 64;
        b->m->vertices = dm_xrealloc(b->m->vertices, b->cap_v * sizeof(mesh_vertex));
    }
    mesh_vertex *out = &b->m->vertices[b->m->n_vertices];
    memset(out, 0, sizeof *out);
    memcpy(out->pos, p, sizeof out->pos);
    memcpy(out->nrm, n, sizeof out->nrm);
    out->uv[0] = u;
    out->uv[1] = v;
    return (uint32_t)b->m->n_vertices++;
}

static void mesh__tri(mesh__builder *b, uint32_t a, uint32_t c, uint32_t d)
{
    if (b->m->n_indices + 3 > b->cap_i) {
        b->cap_i = b->cap_i ? b->cap_i * 2 : 192;
        b->m->indices = dm_xrealloc(b->m->indices, b->cap_i * sizeof(uint32_t));
    }
    b->m->indices[b->m->n_indices++] = a;
    b->m->indices[b->m->n_indices++] = c;
    b->m->indices[b->m->n_indices++] = d;
}

/* Two triangles of the quad a,b,c,d given counter-clockwise from the front. */
static void mesh__quad(mesh__builder *b, uint32_t a, uint32_t c, uint32_t d, uint32_t e)
{
    mesh__tri(b, a, c, d);
    mesh__tri(b, a, d, e);
}

/* Ground plane y = 0 over [-1,1]², normal +Y, n×n vertices; u grows along +X
 * and v along -Z, so the tangent is +X with bitangent sign +1. */
static void mesh__plane(mesh__builder *b, int n)
{
    static const float up[3] = {0, 1, 0};
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float u = (float)i / (float)(n - 1), v = (float)j / (float)(n - 1);
            float p[3] = {2 * u - 1, 0, 1 - 2 * v};
            mesh__vert(b, p, up, u, v);
        }
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            uint32_t a = (uint32_t)(j * n + i);
            mesh__quad(b, a, a + 1, a + 1 + (uint32_t)n, a + (uint32_t)n);
        }
}

/* Cube [-1,1]³: 6 faces × 4 vertices with per-face UVs 0..1. */
static void mesh__cube(mesh__builder *b)
{
    /* Per face: normal, tangent (u axis), bitangent (v axis). */
    static const float f[6][3][3] = {
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    };
    static const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6; k++) {
        uint32_t first = 0;
        for (int c = 0; c < 4; c++) {
            float su = uv[c][0] * 2 - 1, sv = uv[c][1] * 2 - 1, p[3];
            for (int a = 0; a < 3; a++)
                p[a] = f[k][0][a] + su * f[k][1][a] + sv * f[k][2][a];
            uint32_t id = mesh__vert(b, p, f[k][0], uv[c][0], uv[c][1]);
            if (c == 0)
                first = id;
        }
        mesh__quad(b, first, first + 1, first + 2, first + 3);
    }
}

static void mesh__triangle(mesh__builder *b)
{
    static const float n[3] = {0, 0, 1};
    static const float p[3][3] = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    mesh__tri(b, mesh__vert(b, p[0], n, 0, 0), mesh__vert(b, p[1], n, 1, 0),
              mesh__vert(b, p[2], n, 0.5f, 1));
}

static void mesh__fullscreen(mesh__builder *b)
{
    static const float n[3] = {0, 0, 1};
    static const float p[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    uint32_t a = mesh__vert(b, p[0], n, 0, 0);
    mesh__vert(b, p[1], n, 1, 0);
    mesh__vert(b, p[2], n, 1, 1);
    mesh__vert(b, p[3], n, 0, 1);
    mesh__quad(b, a, a + 1, a + 2, a + 3);
    b->m->clip_space = 1;
}

/* One cap fan of the cylinder at height y (±1), `seg` triangles. */
static void mesh__cap(mesh__builder *b, int seg, float y)
{
    float n[3] = {0, y, 0}, c[3] = {0, y, 0};
    uint32_t centre = mesh__vert(b, c, n, 0.5f, 0.5f);
    for (int i = 0; i < seg; i++) {
        float a = 2 * MESH__PI * (float)i / (float)seg;
        float p[3] = {sinf(a), y, cosf(a)};
        mesh__vert(b, p, n, 0.5f + 0.5f * p[0], 0.5f - 0.5f * y * p[2]);
    }
    for (int i = 0; i < seg; i++) {
        uint32_t a = centre + 1 + (uint32_t)i, d = centre + 1 + (uint32_t)((i + 1) % seg);
        if (y > 0)
            mesh__tri(b, centre, a, d);
        else
            mesh__tri(b, centre, d, a);
    }
}

/* Cylinder radius 1, y in [-1,1]: seg × 12 side quads (seam duplicated for
 * UVs) + two fans: 26·seg triangles (1 508 at the default 58 segments). */
static void mesh__cylinder(mesh__builder *b, int seg)
{
    for (int j = 0; j <= MESH__CYL_STACKS; j++)
        for (int i = 0; i <= seg; i++) {
            float u = (float)i / (float)seg, v = (float)j / MESH__CYL_STACKS;
            float a = 2 * MESH__PI * u;
            float n[3] = {sinf(a), 0, cosf(a)}, p[3] = {n[0], 2 * v - 1, n[2]};
            mesh__vert(b, p, n, u, v);
        }
    uint32_t row = (uint32_t)seg + 1;
    for (uint32_t j = 0; j < MESH__CYL_STACKS; j++)
        for (uint32_t i = 0; i < (uint32_t)seg; i++) {
            uint32_t a = j * row + i;
            mesh__quad(b, a, a + 1, a + 1 + row, a + row);
        }
    mesh__cap(b, seg, 1);
    mesh__cap(b, seg, -1);
}


/* ---- tangents ---------------------------------------------------------- */

static float mesh__dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void mesh__cross(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Normalises v in place; returns 0 (v untouched) when its length is ~0. */
static int mesh__normalize(float v[3])
{
    float l = sqrtf(mesh__dot(v, v));
    if (!(l > 1e-12f) || !isfinite(l))
        return 0;
    for (int i = 0; i < 3; i++)
        v[i] /= l;
    return 1;
}

/* Adds the S1 tangent T and bitangent B of triangle (a,b,c) to acc (6 floats
 * per vertex) and its face normal to fn; skips degenerate UVs (M ≈ 0). */
static void mesh__accumulate(const mesh_data *m, const uint32_t *t, float *acc, float *fn)
{
    const mesh_vertex *v1 = &m->vertices[t[0]], *v2 = &m->vertices[t[1]], *v3 = &m->vertices[t[2]];
    float e12[3], e13[3], face[3];
    for (int i = 0; i < 3; i++) {
        e12[i] = v2->pos[i] - v1->pos[i];
        e13[i] = v3->pos[i] - v1->pos[i];
    }
    mesh__cross(e12, e13, face);
    float du12 = v2->uv[0] - v1->uv[0], dv12 = v2->uv[1] - v1->uv[1];
    float du13 = v3->uv[0] - v1->uv[0], dv13 = v3->uv[1] - v1->uv[1];
    float M = du12 * dv13 - du13 * dv12;
    for (int k = 0; k < 3; k++) {
        float *a = &acc[6 * (size_t)t[k]];
        for (int i = 0; i < 3; i++) {
            fn[3 * (size_t)t[k] + i] += face[i];
            if (fabsf(M) < 1e-12f)
                continue;
            a[i] += (dv13 * e12[i] - dv12 * e13[i]) / M;
            a[3 + i] += (-du13 * e12[i] + du12 * e13[i]) / M;
        }
    }
}

/* Any unit vector perpendicular to the unit vector n. */
static void mesh__perpendicular(const float n[3], float out[3])
{
    float ax[3] = {0, 0, 0};
    int k = fabsf(n[0]) <= fabsf(n[1]) ? 0 : 1;
    if (fabsf(n[2]) < fabsf(n[k]))
        k = 2;
    ax[k] = 1;
    float c[3];
    mesh__cross(n, ax, c);
    mesh__cross(c, n, out);
    mesh__normalize(out);
}

/* Final frame of one vertex from its accumulated T, B and face normal. */
static void mesh__frame(mesh_vertex *v, const float *acc, const float *fn)
{
    static const float up[3] = {0, 0, 1};
    if (!mesh__normalize(v->nrm)) {
        memcpy(v->nrm, fn, sizeof v->nrm);
        if (!mesh__normalize(v->nrm))
            memcpy(v->nrm, up, sizeof v->nrm);
    }
    float t[3], b[3] = {acc[3], acc[4], acc[5]}, c[3];
    float d = mesh__dot(v->nrm, acc);
    for (int i = 0; i < 3; i++)
        t[i] = acc[i] - v->nrm[i] * d;
    if (!mesh__normalize(t))
        mesh__perpendicular(v->nrm, t);
    mesh__cross(v->nrm, t, c);
    memcpy(v->tan, t, sizeof t);
    v->tan[3] = mesh__dot(c, b) < 0 ? -1.0f : 1.0f;
}

void mesh_generate_tangents(mesh_data *m)
{
    float *acc = dm_xcalloc(m->n_vertices ? m->n_vertices : 1, 6 * sizeof(float));
    float *fn = dm_xcalloc(m->n_vertices ? m->n_vertices : 1, 3 * sizeof(float));
    for (size_t i = 0; i + 2 < m->n_indices; i += 3)
        mesh__accumulate(m, &m->indices[i], acc, fn);
    for (size_t i = 0; i < m->n_vertices; i++)
        mesh__frame(&m->vertices[i], &acc[6 * i], &fn[3 * i]);
    free(acc);
    free(fn);
}

static void mesh__sphere(mesh__builder *b, int level);

/* Terrain height y(x, z) and its gradient: two octaves of rolling hills. */
static float mesh__terrain_y(float x, float z, float *dx, float *dz)
{
    float a = 2.1f * x + 0.3f, c = 1.7f * z, e = 5.3f * x + 2.0f * z;
    *dx = 0.12f * 2.1f * cosf(a) * cosf(c) + 0.05f * 5.3f * cosf(e);
    *dz = -0.12f * 1.7f * sinf(a) * sinf(c) + 0.05f * 2.0f * cosf(e);
    return 0.12f * sinf(a) * cosf(c) + 0.05f * sinf(e);
}

/* Terrain over [-1,1]² (XZ) of t×t square tiles, each tile two triangle
 * patches; corners are shared between tiles so the edge midpoints that
 * neighbouring patches compute their levels from coincide. */
static void mesh__terrain(mesh__builder *b, int t)
{
    int n = t + 1;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            float u = (float)i / (float)t, v = (float)j / (float)t, dx, dz;
            float p[3] = {2 * u - 1, 0, 1 - 2 * v};
            p[1] = mesh__terrain_y(p[0], p[2], &dx, &dz);
            float nr[3] = {-dx, 1, -dz};
            mesh__normalize(nr);
            mesh__vert(b, p, nr, u, v);
        }
    for (int j = 0; j < t; j++)
        for (int i = 0; i < t; i++) {
            uint32_t a = (uint32_t)(j * n + i);
            mesh__quad(b, a, a + 1, a + 1 + (uint32_t)n, a + (uint32_t)n);
        }
    /* The same tiles as quad patches, after the triangles: corner (0,0) of
     * the patch domain at the tile's lowest (u,v), counter-clockwise. */
    size_t nt = b->m->n_indices;
    b->m->indices = dm_xrealloc(b->m->indices, (nt + 4 * (size_t)t * (size_t)t) * sizeof(uint32_t));
    uint32_t *q = b->m->indices + nt;
    for (int j = 0; j < t; j++)
        for (int i = 0; i < t; i++, q += 4) {
            uint32_t a = (uint32_t)(j * n + i);
            q[0] = a;
            q[1] = a + 1;
            q[2] = a + 1 + (uint32_t)n;
            q[3] = a + (uint32_t)n;
        }
    b->m->n_quad_indices = 4 * (size_t)t * (size_t)t;
    b->cap_i = nt + b->m->n_quad_indices;
}

int mesh_patch_vertices(const char *name)
{
    return name && strcmp(name, "terrain") == 0 ? 4 : 3;
}

/* Asteroid radius along the unit direction p: 1 + three octaves of lumps. */
float mesh_asteroid_radius(const float p[3])
{
    float s1 = sinf(2.3f * p[0] + 1.0f) * sinf(2.9f * p[1] + 0.4f) * sinf(2.6f * p[2] + 2.0f);
    float s2 = sinf(5.1f * p[0] + 3.7f * p[1] + 0.5f) * cosf(4.7f * p[2] - 2.3f * p[0]);
    float s3 = sinf(11.0f * p[1] + 9.0f * p[2]) * sinf(10.0f * p[0] - 7.0f * p[2] + 1.0f);
    return 0.82f + 0.25f * s1 + 0.07f * s2 + 0.025f * s3;
}

/* Icosphere at `level` displaced radially by mesh_asteroid_radius on the
 * CPU; normals are left zero so mesh_generate_tangents rebuilds them from
 * the displaced faces. */
static void mesh__asteroid(mesh__builder *b, int level)
{
    mesh__sphere(b, level);
    for (size_t i = 0; i < b->m->n_vertices; i++) {
        mesh_vertex *v = &b->m->vertices[i];
        float r = mesh_asteroid_radius(v->pos);
        for (int k = 0; k < 3; k++) {
            v->pos[k] *= r;
            v->nrm[k] = 0;
        }
    }
}

void mesh_sphere_dir(float u, float v, float p[3])
{
    float lon = (u - 0.5f) * 2 * MESH__PI, lat = (v - 0.5f) * MESH__PI;
    p[0] = cosf(lat) * sinf(lon);
    p[1] = sinf(lat);
    p[2] = cosf(lat) * cosf(lon);
}

/* The reduced asteroid: the sphere scaled to MESH_ASTEROID_RMID, its unit
 * normals and UVs kept. */
static void mesh__asteroid_reduced(mesh__builder *b, int level)
{
    mesh__sphere(b, level);
    for (size_t i = 0; i < b->m->n_vertices; i++)
        for (int k = 0; k < 3; k++)
            b->m->vertices[i].pos[k] *= MESH_ASTEROID_RMID;
}

/* Plane y = 0 over [-1,1]² made of two halves of q×2q quads each (x < 0 and
 * x > 0).  The column x = 0 is duplicated: the right half's UVs are shifted
 * by (0.37, 0.21), so heights sampled on the two sides of the seam disagree
 * (a UV seam, study S4 (docs/studies.md) cracks).  When `flat_left` is set instead, every left
 * vertex except the shared column gets the one UV (0.5, 0.5): the height
 * map is constant there (the `halfflat` mesh of the flatness test). */
static void mesh__halves(mesh__builder *b, int q, int flat_left)
{
    static const float up[3] = {0, 1, 0};
    int cols = q + 1, rows = 2 * q + 1;
    for (int half = 0; half < 2; half++) {
        uint32_t base = (uint32_t)b->m->n_vertices;
        for (int j = 0; j < rows; j++)
            for (int i = 0; i < cols; i++) {
                float x = (float)(half * q + i) / (float)q - 1.0f, z = 1.0f - 2.0f * (float)j / (float)(rows - 1);
                float p[3] = {x, 0, z}, u = (x + 1) * 0.5f, v = (1 - z) * 0.5f;
                if (half == 1 && !flat_left) {
                    u += 0.37f;
                    v += 0.21f;
                }
                if (half == 0 && flat_left && i < q)
                    u = v = 0.5f;
                mesh__vert(b, p, up, u, v);
            }
        for (int j = 0; j + 1 < rows; j++)
            for (int i = 0; i < q; i++) {
                uint32_t a = base + (uint32_t)(j * cols + i);
                mesh__quad(b, a, a + 1, a + 1 + (uint32_t)cols, a + (uint32_t)cols);
            }
    }
}

int mesh_build(const mesh_desc *desc, mesh_data *out)
{
    const char *name = desc && desc->name ? desc->name : "plane";
    int d = desc ? desc->density : 0;
    if (mesh_scene_is(name))
        return mesh_scene_build(name, d, out);   /* several objects (mesh_scene.h) */
    int kind = -1;
    for (int i = 0; mesh__names[i]; i++)
        if (strcmp(name, mesh__names[i]) == 0)
            kind = i;
    if (kind < 0)
        return DM_ERR_UNKNOWN;
    static const int def[] = {2, 0, 0, 0, 58, 4, 16, 6, 4, 4, 2},
                     lo[] = {2, 0, 0, 0, 3, 0, 1, 0, 1, 1, 0},
                     hi[] = {1024, 1024, 1024, 1024, 1024, 7, 512, 7, 256, 256, 7};
    if (d == 0)
        d = def[kind];
    if (d < lo[kind] || d > hi[kind])
        return DM_ERR_RANGE;
    memset(out, 0, sizeof *out);
    mesh__builder b = {out, 0, 0};
    switch (kind) {
    case 0: mesh__plane(&b, d); break;
    case 1: mesh__cube(&b); break;
    case 2: mesh__triangle(&b); break;
    case 3: mesh__fullscreen(&b); break;
    case 4: mesh__cylinder(&b, d); break;
    case 5: mesh__sphere(&b, d); break;
    case 6: mesh__terrain(&b, d); break;
    case 7: mesh__asteroid(&b, d); break;
    case 10: mesh__asteroid_reduced(&b, d); break;
    default: mesh__halves(&b, d, kind == 9); break;
    }
    mesh_generate_tangents(out);
    return 0;
}

/* ---- icosphere ---------------------------------------------------------- */

typedef struct mesh__ico {
    float *p;          /* 3 per vertex, unit length */
    size_t n_p;
    uint32_t *t;       /* 3 per triangle */
    size_t n_t;
} mesh__ico;

/* Midpoint of edge (a,b), shared through an open-addressing edge table. */
static uint32_t mesh__midpoint(mesh__ico *s, uint64_t *keys, uint32_t *vals,
                               size_t mask, uint32_t a, uint32_t b)
{
    uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
    size_t h = (size_t)(dm_fnv1a64(&key, sizeof key, DM_FNV_SEED) & mask);
    while (keys[h] != UINT64_MAX && keys[h] != key)
        h = (h + 1) & mask;
    if (keys[h] == key)
        return vals[h];
    float *q = &s->p[3 * s->n_p];
    for (int i = 0; i < 3; i++)
        q[i] = s->p[3 * a + i] + s->p[3 * b + i];
    mesh__normalize(q);
    keys[h] = key;
    vals[h] = (uint32_t)s->n_p;
    return (uint32_t)s->n_p++;
}

/* One 1→4 subdivision of every triangle. */
static void mesh__subdivide(mesh__ico *s)
{
    size_t edges = s->n_t * 3 / 2, cap = 1;
    while (cap < 2 * edges)
        cap *= 2;
    uint64_t *keys = dm_xmalloc(cap * sizeof *keys);
    uint32_t *vals = dm_xmalloc(cap * sizeof *vals);
    memset(keys, 0xff, cap * sizeof *keys);
    s->p = dm_xrealloc(s->p, (s->n_p + edges) * 3 * sizeof(float));
    uint32_t *nt = dm_xmalloc(s->n_t * 12 * sizeof(uint32_t));
    for (size_t i = 0; i < s->n_t; i++) {
        uint32_t a = s->t[3 * i], b = s->t[3 * i + 1], c = s->t[3 * i + 2];
        uint32_t ab = mesh__midpoint(s, keys, vals, cap - 1, a, b);
        uint32_t bc = mesh__midpoint(s, keys, vals, cap - 1, b, c);
        uint32_t ca = mesh__midpoint(s, keys, vals, cap - 1, c, a);
        uint32_t q[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        memcpy(&nt[12 * i], q, sizeof q);
    }
    free(s->t);
    s->t = nt;
    s->n_t *= 4;
    free(keys);
    free(vals);
}

static void mesh__icosahedron(mesh__ico *s)
{
    const float g = 1.6180339887f;
    const float p[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    static const uint32_t t[60] = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11,
                                   1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                                   3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9,
                                   4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    s->p = dm_xmalloc(sizeof p);
    memcpy(s->p, p, sizeof p);
    s->n_p = 12;
    for (int i = 0; i < 12; i++)
        mesh__normalize(&s->p[3 * i]);
    s->t = dm_xmalloc(sizeof t);
    memcpy(s->t, t, sizeof t);
    s->n_t = 20;
}

/* Spherical u of a unit position: 0.5 + atan2(x, z)/2π (u grows toward +X
 * seen from +Z, like the cylinder). */
static float mesh__sphere_u(const float *p) { return 0.5f + atan2f(p[0], p[2]) / (2 * MESH__PI); }

/* Icosphere of radius 1 at subdivision level `level` (20·4^level triangles).
 * Triangles crossing the u seam get duplicated vertices with u + 1 so the
 * texture does not wrap backwards across them. */
static void mesh__sphere(mesh__builder *b, int level)
{
    mesh__ico s = {0};
    mesh__icosahedron(&s);
    for (int l = 0; l < level; l++)
        mesh__subdivide(&s);
    for (size_t i = 0; i < s.n_p; i++) {
        const float *p = &s.p[3 * i];
        mesh__vert(b, p, p, mesh__sphere_u(p), 0.5f + asinf(p[1]) / MESH__PI);
    }
    uint32_t *dup = dm_xmalloc(s.n_p * sizeof *dup);
    memset(dup, 0xff, s.n_p * sizeof *dup);
    for (size_t i = 0; i < s.n_t; i++) {
        uint32_t *t = &s.t[3 * i];
        float u[3], lo = 2, hi = -1;
        for (int k = 0; k < 3; k++) {
            u[k] = b->m->vertices[t[k]].uv[0];
            lo = fminf(lo, u[k]);
            hi = fmaxf(hi, u[k]);
        }
        for (int k = 0; k < 3 && hi - lo > 0.5f; k++) {
            if (u[k] >= 0.5f)
                continue;
            if (dup[t[k]] == UINT32_MAX) {
                mesh_vertex v = b->m->vertices[t[k]];
                dup[t[k]] = mesh__vert(b, v.pos, v.nrm, v.uv[0] + 1, v.uv[1]);
            }
            t[k] = dup[t[k]];
        }
        mesh__tri(b, t[0], t[1], t[2]);
    }
    free(dup);
    free(s.p);
    free(s.t);
}

/* Orders vertex indices by position bytes, then by index (qsort_r). */
static int mesh__pos_cmp(const void *a, const void *b, void *ctx)
{
    const mesh_data *m = ctx;
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    int c = memcmp(m->vertices[i].pos, m->vertices[j].pos, sizeof m->vertices[i].pos);
    return c ? c : (i > j) - (i < j);
}

void mesh_canonical(const mesh_data *m, float *uv, float *nrm)
{
    uint32_t *order = dm_xmalloc((m->n_vertices + 1) * sizeof *order);
    for (size_t i = 0; i < m->n_vertices; i++)
        order[i] = (uint32_t)i;
    qsort_r(order, m->n_vertices, sizeof *order, mesh__pos_cmp, (void *)m);
    for (size_t k = 0, first = 0; k < m->n_vertices; k++) {
        if (memcmp(m->vertices[order[k]].pos, m->vertices[order[first]].pos, sizeof m->vertices[0].pos))
            first = k;   /* a new position: the run's lowest index comes first */
        const mesh_vertex *c = &m->vertices[order[first]];
        memcpy(&uv[2 * order[k]], c->uv, 2 * sizeof(float));
        memcpy(&nrm[3 * order[k]], c->nrm, 3 * sizeof(float));
    }
    free(order);
}

size_t mesh_bytes(const mesh_data *m)
{
    return m->n_vertices * sizeof(mesh_vertex) + (m->n_indices + m->n_quad_indices) * sizeof(uint32_t);
}

void mesh_free(mesh_data *m)
{
    if (!m)
        return;
    free(m->vertices);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

/* ---- CPU subdivision and displacement (reference-mesh) ------------------- */

/* Bilinear sample of a size×size height map with wrap-around, texel centres
 * at (i + 0.5)/size as GL's REPEAT sampling. */
float mesh_height_bilinear(const float *height, int size, float u, float v)
{
    float s = u * (float)size - 0.5f, t = v * (float)size - 0.5f;
    float fs = floorf(s), ft = floorf(t);
    long x0 = (long)fs, y0 = (long)ft, n = size;
    float fx = s - fs, fy = t - ft;
    long xa = ((x0 % n) + n) % n, ya = ((y0 % n) + n) % n, xb = (xa + 1) % n, yb = (ya + 1) % n;
    float h00 = height[ya * n + xa], h10 = height[ya * n + xb];
    float h01 = height[yb * n + xa], h11 = height[yb * n + xb];
    float top = h00 + (h10 - h00) * fx, bot = h01 + (h11 - h01) * fx;
    return top + (bot - top) * fy;
}

/* Vertex at integer barycentric weights w[3]/k of triangle t: each field is
 * summed over the corners in increasing vertex-index order, so a point on
 * an edge shared by two triangles comes out bit-identical in both. */
static void mesh__blend(const mesh_data *m, const uint32_t *t, const int w[3], int k,
                        mesh_vertex *out)
{
    int o[3] = {0, 1, 2};
    for (int a = 0; a < 2; a++)
        for (int b = a + 1; b < 3; b++)
            if (t[o[b]] < t[o[a]]) {
                int x = o[a];
                o[a] = o[b];
                o[b] = x;
            }
    float *dst = (float *)out;
    const size_t nf = sizeof(mesh_vertex) / sizeof(float);
    memset(out, 0, sizeof *out);
    for (int c = 0; c < 3; c++) {
        const float *src = (const float *)&m->vertices[t[o[c]]];
        float wc = (float)w[o[c]] / (float)k;
        for (size_t f = 0; f < nf; f++)
            dst[f] += wc * src[f];
    }
    out->tan[3] = m->vertices[t[0]].tan[3];
}

int mesh_subdivide_displace(const mesh_data *in, int k, const float *height, int size,
                            float scale, mesh_data *out)
{
    if (!in || !out || k < 1 || (height && size < 1))
        return DM_ERR_ARG;
    mesh_data m = {0};
    mesh__builder b = {&m, 0, 0};
    for (size_t ti = 0; ti + 2 < in->n_indices; ti += 3) {
        const uint32_t *t = &in->indices[ti];
        uint32_t first = (uint32_t)m.n_vertices;
        for (int j = 0; j <= k; j++)
            for (int i = 0; i + j <= k; i++) {
                int w[3] = {k - i - j, i, j};
                mesh_vertex v;
                mesh__blend(in, t, w, k, &v);
                mesh__normalize(v.nrm);
                float d = height ? (mesh_height_bilinear(height, size, v.uv[0], v.uv[1]) - MESH_SURFACE_H0) * scale : 0;
                uint32_t id = mesh__vert(&b, v.pos, v.nrm, v.uv[0], v.uv[1]);
                for (int c = 0; c < 3; c++)
                    m.vertices[id].pos[c] += v.nrm[c] * d;
                memcpy(m.vertices[id].tan, v.tan, sizeof v.tan);
            }
        /* Row j starts at first + j(k+1) - j(j-1)/2 and holds k+1-j points. */
        for (int j = 0; j < k; j++) {
            uint32_t r0 = first + (uint32_t)(j * (k + 1) - j * (j - 1) / 2);
            uint32_t r1 = r0 + (uint32_t)(k + 1 - j);
            for (int i = 0; i + j < k; i++) {
                mesh__tri(&b, r0 + (uint32_t)i, r0 + (uint32_t)i + 1, r1 + (uint32_t)i);
                if (i + j + 1 < k)
                    mesh__tri(&b, r0 + (uint32_t)i + 1, r1 + (uint32_t)i + 1, r1 + (uint32_t)i);
            }
        }
    }
    m.clip_space = in->clip_space;
    *out = m;
    return 0;
}
