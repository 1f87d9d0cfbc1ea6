/* mesh.c — built-in procedural meshes and tangent frames (see mesh.h). */
#include "techniques/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "techniques/mesh_internal.h"

#define MESH__PI 3.14159265358979323846f
#define MESH__CYL_STACKS 12

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
static void mesh__cube(mesh__builder *b, int d)
{
    (void)d;   /* accepted and ignored (mesh.h) */
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

static void mesh__triangle(mesh__builder *b, int d)
{
    (void)d;   /* accepted and ignored (mesh.h) */
    static const float n[3] = {0, 0, 1};
    static const float p[3][3] = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    mesh__tri(b, mesh__vert(b, p[0], n, 0, 0), mesh__vert(b, p[1], n, 1, 0),
              mesh__vert(b, p[2], n, 0.5f, 1));
}

static void mesh__fullscreen(mesh__builder *b, int d)
{
    (void)d;   /* accepted and ignored (mesh.h) */
    static const float n[3] = {0, 0, 1};
    static const float p[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    uint32_t a = mesh__vert(b, p[0], n, 0, 0);
    mesh__vert(b, p[1], n, 1, 0);
    mesh__vert(b, p[2], n, 1, 1);
    mesh__vert(b, p[3], n, 0, 1);
    mesh__quad(b, a, a + 1, a + 2, a + 3);
    b->m->clip_space = 1;
}

/* Angle of the cylinder's segment boundary i of seg: one expression for the
 * side and the caps, and i = seg is i = 0, so the rim and the side's UV
 * seam share bit-identical positions (mesh_canonical joins them). */
static float mesh__cyl_angle(int i, int seg)
{
    return 2 * MESH__PI * (float)(i % seg) / (float)seg;
}

/* One cap fan of the cylinder at height y (±1), `seg` triangles. */
static void mesh__cap(mesh__builder *b, int seg, float y)
{
    float n[3] = {0, y, 0}, c[3] = {0, y, 0};
    uint32_t centre = mesh__vert(b, c, n, 0.5f, 0.5f);
    for (int i = 0; i < seg; i++) {
        float a = mesh__cyl_angle(i, seg);
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
            float a = mesh__cyl_angle(i, seg);
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
/* The (c+1)² vertices of the terrain's height field, row by row. */
static void mesh__terrain_grid(mesh__builder *b, int c)
{
    for (int j = 0; j <= c; j++)
        for (int i = 0; i <= c; i++) {
            float u = (float)i / (float)c, v = (float)j / (float)c, dx, dz;
            float p[3] = {2 * u - 1, 0, 1 - 2 * v};
            p[1] = mesh__terrain_y(p[0], p[2], &dx, &dz);
            float nr[3] = {-dx, 1, -dz};
            mesh__normalize(nr);
            mesh__vert(b, p, nr, u, v);
        }
}

static void mesh__terrain(mesh__builder *b, int t)
{
    int n = t + 1;
    mesh__terrain_grid(b, t);
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

/* Terrain of study S4's tiled surface: the same hills over [-1,1]² as
 * `terrain` at 2t cells per side, listed tile by tile (t×t tiles of 2×2
 * cells, 8 triangles each, tile rows from v = 0): one tile is one object
 * of S4's Tables 8.3/8.4, drawn with triangle patches. */
static void mesh__terrain_tiles(mesh__builder *b, int t)
{
    int c = 2 * t, n = c + 1;
    mesh__terrain_grid(b, c);
    for (int tj = 0; tj < t; tj++)
        for (int ti = 0; ti < t; ti++)
            for (int k = 0; k < 4; k++) {
                uint32_t a = (uint32_t)((2 * tj + k / 2) * n + 2 * ti + k % 2);
                mesh__quad(b, a, a + 1, a + 1 + (uint32_t)n, a + (uint32_t)n);
            }
    b->m->object_triangles = 8;
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

static void mesh__seam(mesh__builder *b, int q) { mesh__halves(b, q, 0); }
static void mesh__halfflat(mesh__builder *b, int q) { mesh__halves(b, q, 1); }

/* Builds one single mesh into out with fn at density d (in its range, not
 * 0: mesh_list.c checks), then its tangents.  Always 0. */
static int mesh__object(mesh_data *out, int d, void (*fn)(mesh__builder *b, int d))
{
    memset(out, 0, sizeof *out);
    mesh__builder b = {out, 0, 0};
    fn(&b, d);
    mesh_generate_tangents(out);
    return 0;
}

int mesh__build_plane(int d, mesh_data *out) { return mesh__object(out, d, mesh__plane); }
int mesh__build_cube(int d, mesh_data *out) { return mesh__object(out, d, mesh__cube); }
int mesh__build_triangle(int d, mesh_data *out) { return mesh__object(out, d, mesh__triangle); }
int mesh__build_fullscreen(int d, mesh_data *out) { return mesh__object(out, d, mesh__fullscreen); }
int mesh__build_cylinder(int d, mesh_data *out) { return mesh__object(out, d, mesh__cylinder); }
int mesh__build_sphere(int d, mesh_data *out) { return mesh__object(out, d, mesh__sphere); }
int mesh__build_terrain(int d, mesh_data *out) { return mesh__object(out, d, mesh__terrain); }
int mesh__build_asteroid(int d, mesh_data *out) { return mesh__object(out, d, mesh__asteroid); }
int mesh__build_seam(int d, mesh_data *out) { return mesh__object(out, d, mesh__seam); }
int mesh__build_halfflat(int d, mesh_data *out) { return mesh__object(out, d, mesh__halfflat); }
int mesh__build_asteroid_reduced(int d, mesh_data *out) { return mesh__object(out, d, mesh__asteroid_reduced); }
int mesh__build_terrain_tiles(int d, mesh_data *out) { return mesh__object(out, d, mesh__terrain_tiles); }

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

/* Sum of the unit normals of order[lo..hi) (one position), normalised; the
 * first vertex's normal when all are bit-identical (a UV seam). */
static void mesh__seam_normal(const mesh_data *m, const uint32_t *order, size_t lo, size_t hi,
                              float out[3])
{
    memcpy(out, m->vertices[order[lo]].nrm, 3 * sizeof(float));
    int same = 1;
    for (size_t k = lo + 1; k < hi; k++)
        same &= memcmp(m->vertices[order[k]].nrm, out, 3 * sizeof(float)) == 0;
    if (same)
        return;
    float sum[3] = {0, 0, 0};
    for (size_t k = lo; k < hi; k++)
        for (int c = 0; c < 3; c++)
            sum[c] += m->vertices[order[k]].nrm[c];
    if (mesh__normalize(sum))
        memcpy(out, sum, sizeof sum);
}

void mesh_canonical_index(const mesh_data *m, uint32_t *first, float *uv, float *nrm)
{
    uint32_t *order = dm_xmalloc((m->n_vertices + 1) * sizeof *order);
    for (size_t i = 0; i < m->n_vertices; i++)
        order[i] = (uint32_t)i;
    qsort_r(order, m->n_vertices, sizeof *order, mesh__pos_cmp, (void *)m);
    for (size_t lo = 0, hi; lo < m->n_vertices; lo = hi) {
        const mesh_vertex *c = &m->vertices[order[lo]];   /* the run's lowest index */
        for (hi = lo + 1; hi < m->n_vertices &&
             memcmp(m->vertices[order[hi]].pos, c->pos, sizeof c->pos) == 0; hi++)
            ;
        float n[3];
        if (nrm)
            mesh__seam_normal(m, order, lo, hi, n);
        for (size_t k = lo; k < hi; k++) {
            if (first)
                first[order[k]] = order[lo];
            if (uv)
                memcpy(&uv[2 * order[k]], c->uv, 2 * sizeof(float));
            if (nrm)
                memcpy(&nrm[3 * order[k]], n, sizeof n);
        }
    }
    free(order);
}

void mesh_canonical(const mesh_data *m, float *uv, float *nrm)
{
    mesh_canonical_index(m, NULL, uv, nrm);
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

/* ---- height map sampling (the reference-mesh displacement) ----------------- */

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

/* ---- edge lengths (per-edge levels and splits) ------------------------- */

static int mesh__float_cmp(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static float mesh__edge_len(const mesh_data *m, uint32_t a, uint32_t b)
{
    float d[3];
    for (int c = 0; c < 3; c++)
        d[c] = m->vertices[a].pos[c] - m->vertices[b].pos[c];
    return sqrtf(mesh__dot(d, d));
}

float mesh_edge_median(const mesh_data *m, float *longest)
{
    size_t n = m->n_indices - m->n_indices % 3;
    if (longest)
        *longest = 0;
    if (!n)
        return 0;
    float *len = dm_xmalloc(n * sizeof *len);
    for (size_t i = 0; i < n; i++)
        len[i] = mesh__edge_len(m, m->indices[i], m->indices[i - i % 3 + (i + 1) % 3]);
    qsort(len, n, sizeof *len, mesh__float_cmp);
    float med = len[n / 2];
    if (longest)
        *longest = len[n - 1];
    free(len);
    return med;
}

int mesh_edge_factor(float len, float median)
{
    if (!(median > 0))
        return 1;
    float f = floorf(len / median + MESH_EDGE_FACTOR_SLACK);
    return f < 1 ? 1 : f > 64 ? 64 : (int)f;
}

/* ---- CPU subdivision and displacement (reference-mesh) ------------------- */

/* What the subdivision of one mesh shares across its triangles. */
typedef struct mesh__sub {
    const mesh_data *in;
    uint32_t *first;          /* canonical (lowest-index) vertex at each position */
    float *cuv, *cnrm;        /* canonical UV and averaged normal per vertex */
    unsigned char *seam_edge; /* per index slot i: edge (i, next in triangle) is a seam */
    unsigned char *seam_vert; /* per vertex: on some seam edge */
    float median;
    int k;
    const float *height;
    int size;
    float scale;
} mesh__sub;

/* Edge record for seam detection: canonical pair, own pair, index slot. */
typedef struct mesh__edge { uint32_t ca, cb, a, b, slot; } mesh__edge;

static int mesh__edge_cmp(const void *x, const void *y)
{
    const mesh__edge *p = x, *q = y;
    const uint32_t u[4] = {p->ca, p->cb, p->a, p->b}, v[4] = {q->ca, q->cb, q->a, q->b};
    for (int i = 0; i < 4; i++)
        if (u[i] != v[i])
            return (u[i] > v[i]) - (u[i] < v[i]);
    return 0;
}

/* Marks seam edges: edges whose two positions are also joined by an edge of
 * other vertices (a UV seam or a crease such as the cylinder's rim). */
static void mesh__find_seams(mesh__sub *s)
{
    const mesh_data *m = s->in;
    size_t n = m->n_indices - m->n_indices % 3;
    mesh__edge *e = dm_xmalloc((n + 1) * sizeof *e);
    for (size_t i = 0; i < n; i++) {
        uint32_t a = m->indices[i], b = m->indices[i - i % 3 + (i + 1) % 3];
        uint32_t ca = s->first[a], cb = s->first[b];
        int swap = ca > cb || (ca == cb && a > b);
        e[i] = (mesh__edge){swap ? cb : ca, swap ? ca : cb, swap ? b : a, swap ? a : b, (uint32_t)i};
    }
    qsort(e, n, sizeof *e, mesh__edge_cmp);
    for (size_t lo = 0, hi; lo < n; lo = hi) {
        int seam = 0;
        for (hi = lo + 1; hi < n && e[hi].ca == e[lo].ca && e[hi].cb == e[lo].cb; hi++)
            seam |= e[hi].a != e[lo].a || e[hi].b != e[lo].b;
        for (size_t k = lo; seam && k < hi; k++) {
            s->seam_edge[e[k].slot] = 1;
            s->seam_vert[e[k].a] = s->seam_vert[e[k].b] = 1;
        }
    }
    free(e);
}

/* Blend of the triangle's corners with integer weights w[3]/k, summed in
 * increasing canonical-index order, so a point on an edge shared by two
 * triangles (also across a seam) comes out bit-identical in both. */
static void mesh__blend(const mesh__sub *s, const uint32_t *t, const int w[3], int k,
                        mesh_vertex *out)
{
    int o[3] = {0, 1, 2};
    for (int a = 0; a < 2; a++)
        for (int b = a + 1; b < 3; b++) {
            uint32_t fa = s->first[t[o[a]]], fb = s->first[t[o[b]]];
            if (fb < fa || (fb == fa && t[o[b]] < t[o[a]])) {
                int x = o[a];
                o[a] = o[b];
                o[b] = x;
            }
        }
    float *dst = (float *)out;
    const size_t nf = sizeof(mesh_vertex) / sizeof(float);
    memset(out, 0, sizeof *out);
    for (int c = 0; c < 3; c++) {
        const float *src = (const float *)&s->in->vertices[t[o[c]]];
        float wc = (float)w[o[c]] / (float)k;
        for (size_t f = 0; f < nf; f++)
            dst[f] += wc * src[f];
    }
    out->tan[3] = s->in->vertices[t[0]].tan[3];
}

/* Height UV and displacement direction of a seam point with weights w/k:
 * the corners' canonical UVs, unwrapped by whole tiles toward the smallest
 * (the maps tile), and their averaged normals. */
static void mesh__seam_data(const mesh__sub *s, const uint32_t *t, const int w[3], int k,
                            float uv[2], float n[3])
{
    float ref[2] = {1e30f, 1e30f};
    for (int c = 0; c < 3; c++) {
        const float *u = &s->cuv[2 * t[c]];
        if (w[c] > 0 && (u[0] < ref[0] || (u[0] == ref[0] && u[1] < ref[1])))
            memcpy(ref, u, sizeof ref);
    }
    memset(uv, 0, 2 * sizeof(float));
    memset(n, 0, 3 * sizeof(float));
    for (int c = 0; c < 3; c++) {
        float wc = (float)w[c] / (float)k;
        for (int d = 0; d < 2 && w[c] > 0; d++)
            uv[d] += wc * (s->cuv[2 * t[c] + d] + roundf(ref[d] - s->cuv[2 * t[c] + d]));
        for (int d = 0; d < 3; d++)
            n[d] += wc * s->cnrm[3 * t[c] + d];
    }
    mesh__normalize(n);
}

/* Grid point w/kt of triangle slot ti, displaced.  A point on an edge split
 * into fewer segments than kt snaps to the edge's own grid (degenerate
 * triangles, no T-junction); points on seam edges and seam corners take the
 * shared seam data. */
static void mesh__sub_point(const mesh__sub *s, size_t ti, int w[3], int kt, const int *ne,
                            mesh_vertex *v)
{
    const uint32_t *t = &s->in->indices[ti];
    int k = kt, zero = -1, nz = 0, seam = 0;
    for (int c = 0; c < 3; c++)
        if (w[c] == 0) {
            zero = c;
            nz++;
        }
    if (nz == 1) {   /* on the edge opposite corner `zero`: slot (zero + 1) */
        int a = (zero + 1) % 3, b = (zero + 2) % 3, n = ne[a];
        seam = s->seam_edge[ti + (size_t)a];
        if (n < kt) {
            w[a] = (int)lround((double)w[a] * n / kt);
            w[b] = n - w[a];
            k = n;
        }
    } else if (nz == 2) {
        for (int c = 0; c < 3; c++)
            seam |= w[c] > 0 && s->seam_vert[t[c]];
    }
    mesh__blend(s, t, w, k, v);
    mesh__normalize(v->nrm);
    float uv[2] = {v->uv[0], v->uv[1]}, dir[3];
    memcpy(dir, v->nrm, sizeof dir);
    if (seam)
        mesh__seam_data(s, t, w, k, uv, dir);
    float d = s->height ? (mesh_height_bilinear(s->height, s->size, uv[0], uv[1]) - MESH_SURFACE_H0) * s->scale : 0;
    for (int c = 0; c < 3; c++)
        v->pos[c] += dir[c] * d;
}

/* Splits of each edge of triangle slot ti (ne[i]: edge from corner i to
 * i+1) and of its interior (the largest). */
static int mesh__sub_splits(const mesh__sub *s, size_t ti, int ne[3])
{
    const uint32_t *t = &s->in->indices[ti];
    int kt = 0;
    for (int i = 0; i < 3; i++) {
        ne[i] = s->k * mesh_edge_factor(mesh__edge_len(s->in, t[i], t[(i + 1) % 3]), s->median);
        kt = ne[i] > kt ? ne[i] : kt;
    }
    return kt;
}

/* Appends triangle slot ti split kt² (a barycentric grid). */
static void mesh__sub_triangle(const mesh__sub *s, size_t ti, mesh__builder *b)
{
    int ne[3], kt = mesh__sub_splits(s, ti, ne);
    uint32_t first = (uint32_t)b->m->n_vertices;
    for (int j = 0; j <= kt; j++)
        for (int i = 0; i + j <= kt; i++) {
            int w[3] = {kt - i - j, i, j};
            mesh_vertex v;
            mesh__sub_point(s, ti, w, kt, ne, &v);
            uint32_t id = mesh__vert(b, v.pos, v.nrm, v.uv[0], v.uv[1]);
            memcpy(b->m->vertices[id].tan, v.tan, sizeof v.tan);
        }
    /* Row j starts at first + j(kt+1) - j(j-1)/2 and holds kt+1-j points. */
    for (int j = 0; j < kt; j++) {
        uint32_t r0 = first + (uint32_t)(j * (kt + 1) - j * (j - 1) / 2);
        uint32_t r1 = r0 + (uint32_t)(kt + 1 - j);
        for (int i = 0; i + j < kt; i++) {
            mesh__tri(b, r0 + (uint32_t)i, r0 + (uint32_t)i + 1, r1 + (uint32_t)i);
            if (i + j + 1 < kt)
                mesh__tri(b, r0 + (uint32_t)i + 1, r1 + (uint32_t)i + 1, r1 + (uint32_t)i);
        }
    }
}

size_t mesh_subdivide_cost(const mesh_data *m, int k)
{
    float med = mesh_edge_median(m, NULL);
    size_t sum = 0;
    for (size_t ti = 0; ti + 2 < m->n_indices; ti += 3) {
        int f = 1;
        for (int i = 0; i < 3; i++) {
            int fi = mesh_edge_factor(mesh__edge_len(m, m->indices[ti + i], m->indices[ti + (i + 1) % 3]), med);
            f = fi > f ? fi : f;
        }
        sum += (size_t)f * (size_t)f;
    }
    return sum * (size_t)k * (size_t)k;
}

int mesh_subdivide_displace(const mesh_data *in, int k, const float *height, int size,
                            float scale, mesh_data *out)
{
    if (!in || !out || k < 1 || (height && size < 1))
        return DM_ERR_ARG;
    size_t nv = in->n_vertices + 1;
    mesh__sub s = {in, dm_xmalloc(nv * sizeof(uint32_t)), dm_xmalloc(nv * 2 * sizeof(float)),
                   dm_xmalloc(nv * 3 * sizeof(float)), dm_xcalloc(in->n_indices + 1, 1),
                   dm_xcalloc(nv, 1), mesh_edge_median(in, NULL), k, height, size, scale};
    mesh_canonical_index(in, s.first, s.cuv, s.cnrm);
    mesh__find_seams(&s);
    mesh_data m = {0};
    mesh__builder b = {&m, 0, 0};
    for (size_t ti = 0; ti + 2 < in->n_indices; ti += 3)
        mesh__sub_triangle(&s, ti, &b);
    m.clip_space = in->clip_space;
    *out = m;
    free(s.first);
    free(s.cuv);
    free(s.cnrm);
    free(s.seam_edge);
    free(s.seam_vert);
    return 0;
}
