/* Unit tests of techniques/mesh: exact counts, tangent frames, bytes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/mesh.h"

static void build(const char *name, int density, mesh_data *m)
{
    mesh_desc d = {.name = name, .density = density};
    assert_int_equal(mesh_build(&d, m), 0);
}

static void test_counts(void **state)
{
    (void)state;
    static const struct { const char *name; int density; size_t v, t; } cases[] = {
        {"plane", 0, 4, 2},          {"plane", 2, 4, 2},
        {"plane", 3, 9, 8},          {"plane", 1024, 1024 * 1024, 2 * 1023 * 1023},
        {"cube", 0, 24, 12},         {"triangle", 0, 3, 1},
        {"fullscreen", 0, 4, 2},
        /* cylinder: (58+1)*(12+1) side + 2*(58+1) cap vertices; 2*58*12 + 2*58 triangles */
        {"cylinder", 0, 59 * 13 + 2 * 59, 1508},
        {"sphere", 0, 0, 5120},      {"sphere", 1, 0, 80},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        mesh_data m;
        build(cases[i].name, cases[i].density, &m);
        if (cases[i].v)
            assert_int_equal(m.n_vertices, cases[i].v);
        assert_int_equal(m.n_indices, 3 * cases[i].t);
        for (size_t k = 0; k < m.n_indices; k++)
            assert_true(m.indices[k] < m.n_vertices);
        assert_int_equal(m.clip_space, strcmp(cases[i].name, "fullscreen") == 0);
        mesh_free(&m);
    }
}

static void test_sphere_vertices(void **state)
{
    (void)state;
    /* Level 1 icosphere: 12 + 30 shared vertices, plus seam duplicates. */
    mesh_data m;
    build("sphere", 1, &m);
    assert_true(m.n_vertices >= 42 && m.n_vertices < 60);
    for (size_t i = 0; i < m.n_vertices; i++) {
        const float *p = m.vertices[i].pos;
        assert_float_equal(sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1.0f, 1e-5f);
    }
    mesh_free(&m);
}

static void test_bad_input(void **state)
{
    (void)state;
    mesh_data m;
    memset(&m, 0x5a, sizeof m);
    mesh_desc d = {.name = "cubee"};
    assert_int_equal(mesh_build(&d, &m), DM_ERR_UNKNOWN);
    assert_int_equal(m.n_vertices, 0x5a5a5a5a5a5a5a5aULL);   /* untouched */
    mesh_desc big = {.name = "plane", .density = 1025};
    assert_int_equal(mesh_build(&big, &m), DM_ERR_RANGE);
    mesh_desc one = {.name = "plane", .density = 1};
    assert_int_equal(mesh_build(&one, &m), DM_ERR_RANGE);
}

static void test_plane_tangents(void **state)
{
    (void)state;
    mesh_data m;
    build("plane", 5, &m);
    for (size_t i = 0; i < m.n_vertices; i++) {
        const mesh_vertex *v = &m.vertices[i];
        assert_float_equal(v->tan[0], 1.0f, 1e-6f);
        assert_float_equal(v->tan[1], 0.0f, 1e-6f);
        assert_float_equal(v->tan[2], 0.0f, 1e-6f);
        /* B = cross(N, T) * w must point where v grows: -Z. cross(+Y,+X) = -Z. */
        assert_float_equal(v->tan[3], 1.0f, 0.0f);
        assert_float_equal(v->nrm[1], 1.0f, 0.0f);
    }
    mesh_free(&m);
}

static void test_mirrored_uv_sign(void **state)
{
    (void)state;
    /* The triangle with u mirrored: bitangent sign flips to -1. */
    mesh_data m;
    build("triangle", 0, &m);
    for (size_t i = 0; i < 3; i++)
        m.vertices[i].uv[0] = 1.0f - m.vertices[i].uv[0];
    mesh_generate_tangents(&m);
    for (size_t i = 0; i < 3; i++) {
        assert_float_equal(m.vertices[i].tan[0], -1.0f, 1e-6f);
        assert_float_equal(m.vertices[i].tan[3], -1.0f, 0.0f);
    }
    mesh_free(&m);
}

static void assert_orthonormal_frame(const mesh_vertex *v)
{
    float n = 0, t = 0, d = 0;
    for (int k = 0; k < 3; k++) {
        assert_true(isfinite(v->nrm[k]) && isfinite(v->tan[k]));
        n += v->nrm[k] * v->nrm[k];
        t += v->tan[k] * v->tan[k];
        d += v->nrm[k] * v->tan[k];
    }
    assert_float_equal(n, 1.0f, 1e-5f);
    assert_float_equal(t, 1.0f, 1e-5f);
    assert_float_equal(d, 0.0f, 1e-5f);
    assert_true(v->tan[3] == 1.0f || v->tan[3] == -1.0f);
}

static void test_degenerate_frames(void **state)
{
    (void)state;
    mesh_data m;
    build("triangle", 0, &m);
    for (size_t i = 0; i < 3; i++) {       /* all UVs equal: M = 0 */
        m.vertices[i].uv[0] = 0.25f;
        m.vertices[i].uv[1] = 0.5f;
    }
    m.vertices[1].nrm[0] = m.vertices[1].nrm[1] = m.vertices[1].nrm[2] = 0;   /* zero normal */
    mesh_generate_tangents(&m);
    for (size_t i = 0; i < 3; i++)
        assert_orthonormal_frame(&m.vertices[i]);
    /* The zero normal falls back to the face normal, +Z. */
    assert_float_equal(m.vertices[1].nrm[2], 1.0f, 1e-6f);
    mesh_free(&m);
}

static void test_all_frames_finite(void **state)
{
    (void)state;
    const char *const *names = mesh_names();
    for (size_t i = 0; names[i]; i++) {
        mesh_data m;
        build(names[i], 0, &m);
        for (size_t k = 0; k < m.n_vertices; k++)
            assert_orthonormal_frame(&m.vertices[k]);
        mesh_free(&m);
    }
}

static size_t tris_of(const char *name, int density)
{
    mesh_data m;
    build(name, density, &m);
    size_t t = m.n_indices / 3;
    mesh_free(&m);
    return t;
}

/* The scenes of several objects (mesh_scene.h): S2's scene 1 has S2's
 * 22 086 triangles (plane 64² quads + level-4 sphere + 107×41-quad torus,
 * (108·42) torus vertices); S4's scenes are a 12-triangle inward skybox
 * drawn first plus 5 asteroid bodies, every count the sum of its parts. */
static void test_scenes(void **state)
{
    (void)state;
    mesh_data m, sphere;
    build("s2-scene1", 0, &m);
    build("sphere", 4, &sphere);
    assert_int_equal(m.n_indices / 3, 22086);
    assert_int_equal(8192 + 5120 + 2 * 107 * 41, 22086);
    assert_int_equal(m.n_vertices, 65 * 65 + sphere.n_vertices + 108 * 42);
    mesh_free(&sphere);
    mesh_free(&m);
    for (int level = 0; level <= 4; level++) {
        size_t body = 20u << (2 * level);
        assert_int_equal(tris_of("s4-asteroids", level), level ? 12 + 5 * body : 12 + 5 * 1280);
        assert_int_equal(tris_of("s4-asteroids-reduced", level), level ? 12 + 5 * body : 12 + 5 * 320);
    }
    /* the skybox comes first, faces inward (normals toward the origin, winding
     * reversed: the face normal from the winding agrees with the vertex normal) */
    build("s4-asteroids", 1, &m);
    for (size_t t = 0; t < 12; t++) {
        const float *a = m.vertices[m.indices[3 * t]].pos, *b = m.vertices[m.indices[3 * t + 1]].pos,
                    *c = m.vertices[m.indices[3 * t + 2]].pos;
        const float *n = m.vertices[m.indices[3 * t]].nrm;
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        assert_true(f[0] * n[0] + f[1] * n[1] + f[2] * n[2] > 0);
        assert_true(a[0] * n[0] + a[1] * n[1] + a[2] * n[2] < 0);
        assert_float_equal(fabsf(a[0]) + fabsf(a[1]) + fabsf(a[2]), 30.0f, 1e-4f);
    }
    mesh_free(&m);
    mesh_desc bad = {"s2-scene1", 2};
    assert_int_equal(mesh_build(&bad, &m), DM_ERR_RANGE);
    bad = (mesh_desc){"s4-asteroids", 8};
    assert_int_equal(mesh_build(&bad, &m), DM_ERR_RANGE);
}

static void test_bytes(void **state)
{
    (void)state;
    mesh_data m;
    build("cube", 0, &m);
    assert_int_equal(sizeof(mesh_vertex), 48);
    assert_int_equal(mesh_bytes(&m), 24 * 48 + 36 * 4);
    mesh_free(&m);
    build("plane", 0, &m);
    assert_int_equal(mesh_bytes(&m), 4 * 48 + 6 * 4);
    mesh_free(&m);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_counts),
             cmocka_unit_test(test_sphere_vertices),
             cmocka_unit_test(test_bad_input),
             cmocka_unit_test(test_plane_tangents),
             cmocka_unit_test(test_mirrored_uv_sign),
             cmocka_unit_test(test_degenerate_frames),
             cmocka_unit_test(test_all_frames_finite),
             cmocka_unit_test(test_bytes),
             cmocka_unit_test(test_scenes))
