/* Unit tests of the geometry meshes: terrain, asteroid, seam and halfflat,
 * CPU subdivision + displacement, and user meshes through Assimp. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "techniques/cull.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/user_mesh.h"

static mesh_data build(const char *name, int density)
{
    mesh_desc d = {.name = name, .density = density};
    mesh_data m;
    assert_int_equal(mesh_build(&d, &m), 0);
    return m;
}

static void test_terrain(void **state)
{
    (void)state;
    mesh_data m = build("terrain", 4);
    assert_int_equal(m.n_vertices, 25);
    assert_int_equal(m.n_indices, 3 * 32);
    /* Corner (x=-1, z=1): y = 0.12 sin(-1.8) cos(1.7) + 0.05 sin(-3.3). */
    double y = 0.12 * sin(-1.8) * cos(1.7) + 0.05 * sin(-3.3);
    assert_float_equal(m.vertices[0].pos[1], y, 1e-5);
    /* Tiles share their corners: the centre vertex (2,2) is used by 6 triangles. */
    int uses = 0;
    for (size_t i = 0; i < m.n_indices; i++)
        uses += m.indices[i] == 12;
    assert_int_equal(uses, 6);
    assert_int_equal(mesh_build(&(mesh_desc){.name = "terrain", .density = 513}, &m), DM_ERR_RANGE);
    mesh_free(&m);
}

/* S4's tiled terrain: d×d tiles of 2×2 cells, 8 triangles per tile listed
 * tile by tile, the same surface as `terrain` at 2d cells, no quad
 * patches; every triangle of tile t lies inside its 2×2-cell square. */
static void test_terrain_tiles(void **state)
{
    (void)state;
    const int d = 3;
    mesh_data m = build("terrain-tiles", d), ref = build("terrain", 2 * d);
    assert_int_equal(m.n_vertices, 49);
    assert_int_equal(m.n_indices, 3 * 8 * d * d);
    assert_int_equal(m.object_triangles, 8);
    assert_int_equal(m.n_quad_indices, 0);
    assert_int_equal(mesh_patch_vertices("terrain-tiles"), 3);
    for (size_t v = 0; v < m.n_vertices; v++)
        for (int k = 0; k < 3; k++)
            assert_float_equal(m.vertices[v].pos[k], ref.vertices[v].pos[k], 0);
    const float cell = 2.0f / (float)(2 * d);
    for (size_t t = 0; t < (size_t)(d * d); t++) {
        float x0 = -1.0f + 2 * cell * (float)(t % d), z1 = 1.0f - 2 * cell * (float)(t / d);
        for (size_t i = 24 * t; i < 24 * (t + 1); i++) {
            const float *p = m.vertices[m.indices[i]].pos;
            assert_true(p[0] >= x0 - 1e-6f && p[0] <= x0 + 2 * cell + 1e-6f);
            assert_true(p[2] <= z1 + 1e-6f && p[2] >= z1 - 2 * cell - 1e-6f);
        }
    }
    assert_int_equal(mesh_build(&(mesh_desc){.name = "terrain-tiles", .density = 257}, &m), DM_ERR_RANGE);
    mesh_free(&m);
    mesh_free(&ref);
}

/* The terrain's tiles as quad patches: 4 indices per tile after the
 * triangles, corners in the quad domain's order (u,v) = (0,0), (1,0),
 * (1,1), (0,1), i.e. UV steps of +1/t along u then v; MeshBytes counts them. */
static void test_terrain_quads(void **state)
{
    (void)state;
    const int t = 4;
    mesh_data m = build("terrain", t);
    assert_int_equal(m.n_quad_indices, 4 * t * t);
    assert_int_equal(mesh_patch_vertices("terrain"), 4);
    assert_int_equal(mesh_patch_vertices("plane"), 3);
    static const float du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
    for (size_t q = 0; q < (size_t)(t * t); q++) {
        const uint32_t *c = &m.indices[m.n_indices + 4 * q];
        const float *uv0 = m.vertices[c[0]].uv;
        for (int k = 0; k < 4; k++) {
            assert_float_equal(m.vertices[c[k]].uv[0], uv0[0] + du[k] / t, 1e-6);
            assert_float_equal(m.vertices[c[k]].uv[1], uv0[1] + dv[k] / t, 1e-6);
        }
        /* the two triangles of the same tile use these corners */
        const uint32_t *tri = &m.indices[6 * q];
        assert_int_equal(tri[0], c[0]);
        assert_int_equal(tri[1], c[1]);
        assert_int_equal(tri[2], c[2]);
        assert_int_equal(tri[5], c[3]);
    }
    assert_int_equal(mesh_bytes(&m), 25 * sizeof(mesh_vertex) + (96 + 64) * sizeof(uint32_t));
    mesh_free(&m);
}

/* The reduced asteroid is the sphere at radius RMID with the sphere's UVs:
 * mesh_sphere_dir(uv) gives back each vertex's direction. */
static void test_asteroid_reduced(void **state)
{
    (void)state;
    mesh_data m = build("asteroid-reduced", 0);
    assert_int_equal(m.n_indices, 3 * 320);
    assert_int_equal(m.n_quad_indices, 0);
    for (size_t i = 0; i < m.n_vertices; i++) {
        const float *p = m.vertices[i].pos, *n = m.vertices[i].nrm;
        float r = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), d[3];
        assert_float_equal(r, MESH_ASTEROID_RMID, 1e-5);
        mesh_sphere_dir(m.vertices[i].uv[0], m.vertices[i].uv[1], d);
        for (int k = 0; k < 3; k++) {
            assert_float_equal(n[k], p[k] / r, 1e-5);
            assert_float_equal(d[k], p[k] / r, 2e-5);
        }
    }
    mesh_free(&m);
    mesh_desc bad = {.name = "asteroid-reduced", .density = 8};
    assert_int_equal(mesh_build(&bad, &m), DM_ERR_RANGE);
}

/* Surface point of the asteroid at sphere UV (u, v), in double. */
static void asteroid_point(double u, double v, double s[3])
{
    double lon = (u - 0.5) * 2 * M_PI, lat = (v - 0.5) * M_PI;
    float d[3] = {(float)(cos(lat) * sin(lon)), (float)sin(lat), (float)(cos(lat) * cos(lon))};
    double r = mesh_asteroid_radius(d);
    for (int k = 0; k < 3; k++)
        s[k] = r * d[k];
}

/* The `asteroid` maps are baked from the same function as the original
 * mesh: at every texel centre the height rebuilds the radius through the
 * displacement rule (RMID + (h − 0.5)·SCALE = r), and the normal equals
 * the normal of the parametric surface S(u,v) = r·d (cross product of
 * finite-difference partials, computed here independently) in the sphere's
 * tangent frame, within 0.5°.  Both layouts carry the baked normals. */
static void test_asteroid_maps_baked(void **state)
{
    (void)state;
    const int n = 64;
    maps_set full, compact;
    assert_int_equal(maps_generate(&(maps_desc){.name = "asteroid", .size = n}, &full), 0);
    assert_int_equal(maps_generate(&(maps_desc){.name = "asteroid", .size = n, .compact = 1}, &compact), 0);
    assert_non_null(compact.normal);
    double worst = 0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            size_t i = (size_t)y * n + (size_t)x;
            double u = (x + 0.5) / n, v = (y + 0.5) / n, s[3], su[3], sv[3], a[3], b[3];
            asteroid_point(u, v, s);
            double r = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            assert_float_equal(MESH_ASTEROID_RMID + (full.height[i] - 0.5) * MESH_ASTEROID_SCALE, r, 1e-5);
            assert_float_equal(compact.height[i], full.height[i], 0);
            for (int k = 0; k < 3; k++)
                assert_float_equal(compact.normal[3 * i + k], full.normal[3 * i + k], 0);
            if (y < 4 || y >= n - 4)
                continue;   /* the parametrisation degenerates near the poles */
            const double e = 1e-4;
            asteroid_point(u + e, v, a);
            asteroid_point(u - e, v, b);
            for (int k = 0; k < 3; k++)
                su[k] = a[k] - b[k];
            asteroid_point(u, v + e, a);
            asteroid_point(u, v - e, b);
            for (int k = 0; k < 3; k++)
                sv[k] = a[k] - b[k];
            double c[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                           su[0] * sv[1] - su[1] * sv[0]};
            double cl = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            double lon = (u - 0.5) * 2 * M_PI, lat = (v - 0.5) * M_PI;
            double T[3] = {cos(lon), 0, -sin(lon)};
            double B[3] = {-sin(lat) * sin(lon), cos(lat), -sin(lat) * cos(lon)};
            double N[3] = {cos(lat) * sin(lon), sin(lat), cos(lat) * cos(lon)};
            double ts[3] = {0, 0, 0};
            for (int k = 0; k < 3; k++) {
                ts[0] += c[k] * T[k] / cl;
                ts[1] += c[k] * B[k] / cl;
                ts[2] += c[k] * N[k] / cl;
            }
            const float *m = &full.normal[3 * i];
            double dot = ts[0] * m[0] + ts[1] * m[1] + ts[2] * m[2];
            double ang = acos(fmin(1.0, dot)) * 180 / M_PI;
            worst = fmax(worst, ang);
        }
    printf("asteroid maps: worst baked-normal angle vs the parametric normal %.4f deg\n", worst);
    assert_true(worst < 0.5);
    maps_free(&full);
    maps_free(&compact);
}

/* Chunked culling on a 10 × 10-quad plane (20 triangles per row = one
 * chunk per row; row j spans z in [0.8 − 0.2j, 1 − 0.2j]).  With clip
 * z = z + 1.5 (w = 1) a row is beyond the far plane z > w(1 + margin) when
 * its nearest z, less the pad, exceeds w(1 + margin) − 1.5: rows 0..6 go
 * with neither pad nor margin, 0..5 with pad 0.1, 0..3 with margin 0.5; the
 * rest is one merged range. */
static void test_cull_chunks(void **state)
{
    (void)state;
    mesh_data m = build("plane", 11);
    cull_set s;
    assert_int_equal(cull_build(&m, 20, &s), 0);
    assert_int_equal(s.n, 10);
    assert_float_equal(s.chunks[3].lo[2], 0.2f, 1e-6);
    assert_float_equal(s.chunks[3].hi[2], 0.4f, 1e-6);
    float mvp[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1.5f, 1};
    size_t first[10], count[10];
    static const struct { float pad, margin; size_t culled_rows; } cases[] = {
        {0, 0, 7}, {0.1f, 0, 6}, {0, 0.5f, 4}};
    for (int c = 0; c < 3; c++) {
        assert_int_equal(cull_visible(&s, mvp, cases[c].pad, cases[c].margin, first, count), 1);
        assert_int_equal(first[0], 60 * cases[c].culled_rows);
        assert_int_equal(count[0], 60 * (10 - cases[c].culled_rows));
    }
    /* Everything inside: one range covering the whole list. */
    mvp[14] = 0;
    assert_int_equal(cull_visible(&s, mvp, 0, 0, first, count), 1);
    assert_int_equal(first[0], 0);
    assert_int_equal(count[0], m.n_indices);
    /* A last, shorter chunk; a bad chunk size. */
    cull_free(&s);
    assert_int_equal(cull_build(&m, 64, &s), 0);
    assert_int_equal(s.n, 4);
    assert_int_equal(s.chunks[3].count, 3 * (200 - 3 * 64));
    cull_free(&s);
    assert_int_equal(cull_build(&m, 0, &s), DM_ERR_ARG);
    mesh_free(&m);
}

/* Seam data: on the seam mesh the duplicated middle column gets the left
 * half's UVs (the first vertex at each position); every vertex with a
 * unique position keeps its own UV and normal. */
static void test_canonical_seam(void **state)
{
    (void)state;
    mesh_data m = build("seam", 2);
    float *uv = malloc(m.n_vertices * 2 * sizeof(float)), *nrm = malloc(m.n_vertices * 3 * sizeof(float));
    mesh_canonical(&m, uv, nrm);
    size_t shifted = 0;
    for (size_t i = 0; i < m.n_vertices; i++) {
        size_t first = i;
        for (size_t j = 0; j < i; j++)
            if (memcmp(m.vertices[j].pos, m.vertices[i].pos, sizeof m.vertices[i].pos) == 0) {
                first = j;
                break;
            }
        assert_memory_equal(&uv[2 * i], m.vertices[first].uv, 2 * sizeof(float));
        assert_memory_equal(&nrm[3 * i], m.vertices[first].nrm, 3 * sizeof(float));
        shifted += first != i;
    }
    assert_int_equal(shifted, 5);   /* the column x = 0 of the right half: 2·2 + 1 vertices */
    free(uv);
    free(nrm);
    mesh_free(&m);
}

static void test_asteroid(void **state)
{
    (void)state;
    mesh_data m = build("asteroid", 2);
    assert_int_equal(m.n_indices, 3 * 320);
    for (size_t i = 0; i < m.n_vertices; i++) {
        const float *p = m.vertices[i].pos;
        float r = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        float u[3] = {p[0] / r, p[1] / r, p[2] / r};
        assert_float_equal(r, mesh_asteroid_radius(u), 1e-5);
        assert_true(r > 0.45f && r < 1.2f);
        const float *n = m.vertices[i].nrm;
        assert_float_equal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-4);
    }
    mesh_free(&m);
    m = build("asteroid", 0);
    assert_int_equal(m.n_indices, 3 * 81920);
    mesh_free(&m);
}

static void test_seam_and_halfflat(void **state)
{
    (void)state;
    mesh_data m = build("seam", 4);
    assert_int_equal(m.n_vertices, 2 * 5 * 9);
    assert_int_equal(m.n_indices, 3 * 2 * 4 * 8 * 2);
    /* Left half's last column (i = 4) and right half's first column (i = 0)
     * share positions; the right UVs are shifted by (0.37, 0.21). */
    for (int j = 0; j < 9; j++) {
        const mesh_vertex *l = &m.vertices[j * 5 + 4], *r = &m.vertices[45 + j * 5];
        assert_memory_equal(l->pos, r->pos, sizeof l->pos);
        assert_float_equal(l->pos[0], 0.0, 1e-6);
        assert_float_equal(r->uv[0] - l->uv[0], 0.37, 1e-6);
        assert_float_equal(r->uv[1] - l->uv[1], 0.21, 1e-6);
    }
    mesh_free(&m);
    m = build("halfflat", 4);
    for (size_t i = 0; i < m.n_vertices; i++) {
        const mesh_vertex *v = &m.vertices[i];
        if (v->pos[0] < -1e-6f) {
            assert_float_equal(v->uv[0], 0.5, 0);
            assert_float_equal(v->uv[1], 0.5, 0);
        } else {
            assert_float_equal(v->uv[0], (v->pos[0] + 1) * 0.5, 1e-6);
        }
    }
    mesh_free(&m);
}

static void test_height_bilinear(void **state)
{
    (void)state;
    const float h[4] = {0.0f, 1.0f, 0.5f, 0.25f};   /* row 0: 0 1, row 1: 0.5 0.25 */
    assert_float_equal(mesh_height_bilinear(h, 2, 0.25f, 0.25f), 0.0, 1e-6);
    assert_float_equal(mesh_height_bilinear(h, 2, 0.75f, 0.75f), 0.25, 1e-6);
    assert_float_equal(mesh_height_bilinear(h, 2, 0.5f, 0.25f), 0.5, 1e-6);
    assert_float_equal(mesh_height_bilinear(h, 2, 0.5f, 0.5f), (0 + 1 + 0.5 + 0.25) / 4, 1e-6);
    /* Wrap: u = 0 lies halfway between texel 1 (of the previous tile) and texel 0. */
    assert_float_equal(mesh_height_bilinear(h, 2, 0.0f, 0.25f), 0.5, 1e-6);
    assert_float_equal(mesh_height_bilinear(h, 2, 1.25f, -0.75f), 0.0, 1e-6);
}

static void test_subdivide_displace(void **state)
{
    (void)state;
    mesh_data t = build("triangle", 0), s;
    const float flat[1] = {0.75f};
    assert_int_equal(mesh_subdivide_displace(&t, 4, flat, 1, 0.4f, &s), 0);
    assert_int_equal(s.n_vertices, 15);
    assert_int_equal(s.n_indices, 3 * 16);
    for (size_t i = 0; i < s.n_vertices; i++)
        assert_float_equal(s.vertices[i].pos[2], 0.1, 1e-6);   /* (0.75-0.5)·0.4 along +Z */
    mesh_free(&s);
    assert_int_equal(mesh_subdivide_displace(&t, 0, NULL, 0, 0, &s), DM_ERR_ARG);
    mesh_free(&t);
    /* Two triangles sharing the plane's diagonal: k = 3 gives 2·10 vertices
     * over 16 distinct positions, shared edge points bit-identical. */
    mesh_data p = build("plane", 2);
    assert_int_equal(mesh_subdivide_displace(&p, 3, NULL, 0, 0, &s), 0);
    assert_int_equal(s.n_vertices, 20);
    size_t distinct = 0;
    for (size_t i = 0; i < s.n_vertices; i++) {
        int seen = 0;
        for (size_t j = 0; j < i && !seen; j++)
            seen = memcmp(s.vertices[i].pos, s.vertices[j].pos, sizeof s.vertices[i].pos) == 0;
        distinct += !seen;
    }
    assert_int_equal(distinct, 16);
    mesh_free(&s);
    mesh_free(&p);
}

/* Position ids: equal float bytes = one id (qsort of indices by bytes). */
static const mesh_data *pos_mesh;
static int pos_cmp(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    return memcmp(pos_mesh->vertices[i].pos, pos_mesh->vertices[j].pos, sizeof(float) * 3);
}

static int pair_cmp(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0]) - (x[0] < y[0]) : (x[1] > y[1]) - (x[1] < y[1]);
}

/* Edges (by position) of the non-degenerate triangles of m used by other
 * than exactly two triangles: 0 for a closed, watertight surface. */
static size_t open_edges(const mesh_data *m)
{
    size_t nv = m->n_vertices, nt = m->n_indices / 3, bad = 0;
    uint32_t *ord = malloc(2 * nv * sizeof *ord), *id = ord + nv;   /* one block */
    uint32_t *e = malloc(nt * 6 * sizeof *e), ne = 0;
    for (size_t i = 0; i < nv; i++)
        ord[i] = (uint32_t)i;
    pos_mesh = m;
    qsort(ord, nv, sizeof *ord, pos_cmp);
    for (size_t k = 0, cur = 0; k < nv; k++) {
        if (k && pos_cmp(&ord[k], &ord[k - 1]) != 0)
            cur++;
        id[ord[k]] = (uint32_t)cur;
    }
    for (size_t t = 0; t < nt; t++) {
        uint32_t v[3] = {id[m->indices[3 * t]], id[m->indices[3 * t + 1]], id[m->indices[3 * t + 2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
            continue;   /* snapped (degenerate) triangle */
        for (int c = 0; c < 3; c++, ne++) {
            uint32_t a = v[c], b = v[(c + 1) % 3];
            e[2 * ne] = a < b ? a : b;
            e[2 * ne + 1] = a < b ? b : a;
        }
    }
    qsort(e, ne, 2 * sizeof *e, pair_cmp);
    for (size_t lo = 0, hi; lo < ne; lo = hi) {
        for (hi = lo + 1; hi < ne && pair_cmp(&e[2 * hi], &e[2 * lo]) == 0; hi++)
            ;
        bad += hi - lo != 2;
    }
    free(e);
    free(ord);
    return bad;
}

/* The cylinder's reference: cap spokes (6× the median edge) get 6× the
 * splits, and the displaced mesh is closed — the rim (cap and side share
 * positions, not vertices) and the side's u = 0/1 seam displace alike, and
 * the less split rim edges snap instead of leaving T-junctions. */
static void test_subdivide_cylinder_watertight(void **state)
{
    (void)state;
    mesh_data c = build("cylinder", 0), s;
    float longest, med = mesh_edge_median(&c, &longest);
    assert_float_equal(med, 1.0 / 6.0, 1e-5);        /* a side's vertical edge */
    assert_int_equal(mesh_edge_factor(longest, med), 6);   /* a spoke */
    assert_int_equal(mesh_edge_factor(0.1986f, med), 1);   /* a side's diagonal */
    assert_int_equal(mesh_subdivide_cost(&c, 2), 4 * (1392 + 116 * 36));
    float h[64];
    for (int i = 0; i < 64; i++)
        h[i] = (float)((i * 37) % 64) / 63.0f;   /* rough, so any gap shows */
    assert_int_equal(mesh_subdivide_displace(&c, 2, h, 8, 0.2f, &s), 0);
    assert_int_equal(s.n_indices / 3, mesh_subdivide_cost(&c, 2));
    assert_int_equal(open_edges(&s), 0);
    mesh_free(&s);
    mesh_free(&c);
}

static char *write_tmp(const char *ext, const char *text)
{
    char *path = dm_xasprintf("/tmp/dm_geom_test_%d.%s", (int)getpid(), ext);
    assert_int_equal(dm_write_file(path, text, strlen(text)), 0);
    return path;
}

static void test_user_mesh_obj(void **state)
{
    (void)state;
    /* A 4×2 quad in XY with UVs along +X/+Y: fitted to x in [-1,1], y in
     * [-0.5,0.5]; tangents generated (+X, sign +1). */
    char *path = write_tmp("obj", "v 0 0 0\nv 4 0 0\nv 4 2 0\nv 0 2 0\n"
                                  "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                  "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
    mesh_data m;
    int had = -1;
    dm_str err = {0};
    assert_int_equal(user_mesh_load(path, &m, &had, &err), 0);
    assert_int_equal(had, 0);
    assert_int_equal(m.n_indices, 6);
    float lo = 9, hi = -9, ylo = 9, yhi = -9;
    for (size_t i = 0; i < m.n_vertices; i++) {
        lo = fminf(lo, m.vertices[i].pos[0]);
        hi = fmaxf(hi, m.vertices[i].pos[0]);
        ylo = fminf(ylo, m.vertices[i].pos[1]);
        yhi = fmaxf(yhi, m.vertices[i].pos[1]);
        assert_float_equal(m.vertices[i].tan[0], 1.0, 1e-5);
        assert_float_equal(m.vertices[i].tan[3], 1.0, 0);
        assert_float_equal(m.vertices[i].nrm[2], 1.0, 1e-5);
    }
    assert_float_equal(lo, -1.0, 1e-6);
    assert_float_equal(hi, 1.0, 1e-6);
    assert_float_equal(ylo, -0.5, 1e-6);
    assert_float_equal(yhi, 0.5, 1e-6);
    mesh_free(&m);
    unlink(path);
    free(path);
    assert_int_equal(user_mesh_load("/nonexistent/x.obj", &m, NULL, &err), DM_ERR_IO);
    assert_non_null(strstr(dm_str_get(&err), "/nonexistent/x.obj"));
    dm_str_free(&err);
}

static void test_user_mesh_ply_gltf(void **state)
{
    (void)state;
    char *ply = write_tmp("ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    mesh_data m;
    assert_int_equal(user_mesh_load(ply, &m, NULL, NULL), 0);
    assert_int_equal(m.n_vertices, 3);
    assert_int_equal(m.n_indices, 3);
    assert_float_equal(m.vertices[0].nrm[2], 1.0, 1e-5);   /* generated normal */
    mesh_free(&m);
    unlink(ply);
    free(ply);
    /* glTF 2.0, one triangle (0,0,0) (1,0,0) (0,1,0) as an embedded buffer. */
    char *gltf = write_tmp("gltf",
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]}]}");
    assert_int_equal(user_mesh_load(gltf, &m, NULL, NULL), 0);
    assert_int_equal(m.n_indices, 3);
    assert_int_equal(m.n_vertices, 3);
    mesh_free(&m);
    unlink(gltf);
    free(gltf);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_terrain),
             cmocka_unit_test(test_asteroid),
             cmocka_unit_test(test_terrain_quads),
             cmocka_unit_test(test_terrain_tiles),
             cmocka_unit_test(test_cull_chunks),
             cmocka_unit_test(test_canonical_seam),
             cmocka_unit_test(test_asteroid_reduced),
             cmocka_unit_test(test_asteroid_maps_baked),
             cmocka_unit_test(test_seam_and_halfflat),
             cmocka_unit_test(test_height_bilinear),
             cmocka_unit_test(test_subdivide_displace),
             cmocka_unit_test(test_subdivide_cylinder_watertight),
             cmocka_unit_test(test_user_mesh_obj),
             cmocka_unit_test(test_user_mesh_ply_gltf))
