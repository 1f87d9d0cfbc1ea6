/* Unit tests of the geometry meshes: terrain, asteroid, seam and halfflat,
 * CPU subdivision + displacement, and user meshes through Assimp. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_terrain),
        cmocka_unit_test(test_asteroid),
        cmocka_unit_test(test_seam_and_halfflat),
        cmocka_unit_test(test_height_bilinear),
        cmocka_unit_test(test_subdivide_displace),
        cmocka_unit_test(test_user_mesh_obj),
        cmocka_unit_test(test_user_mesh_ply_gltf),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
