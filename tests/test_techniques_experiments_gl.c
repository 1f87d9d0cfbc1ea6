/* GL tests of the axes of the studies' missing experiments (issue 19) on
 * llvmpipe: lod=cpu-per-patch gives the shader distance LOD's exact counts,
 * lod=object-points / object-cpu (S4 Tables 8.3 / 8.4) give the counts of
 * their per-tile levels computed here from the mesh,
 * tess_inner / tess_outer give the triangle tessellation rule's counts,
 * cull=off rasterises the back faces, attenuation=s1 matches
 * max(0, 1 - d²/r²) at a known distance, vertex-displacement's height moves
 * by the height format's quantisation, parallax_bias shifts the image; each
 * default renders exactly as the configuration that spells today's values. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/tech_fixture.h"
#include "techniques/lod_cpu.h"
#include "techniques/mesh.h"
#include "techniques/render.h"

static int setup(void **state) { return techfix_setup(state, 256, 192); }

/* Pipeline statistics of one draw of spec (after a warm-up draw). */
typedef struct stats { GLuint64 tes, clip_in, clip_out, fs; } stats;

static stats count(const char *spec)
{
    static const GLenum tgt[4] = {GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB,
                                  GL_CLIPPING_INPUT_PRIMITIVES_ARB,
                                  GL_CLIPPING_OUTPUT_PRIMITIVES_ARB,
                                  GL_FRAGMENT_SHADER_INVOCATIONS_ARB};
    GLuint64 v[4];
    draw_queried(spec, tgt, 4, v);
    return (stats){v[0], v[1], v[2], v[3]};
}

/* 1 when spec a and spec b render bit-identical images. */
static int same_image(const char *a, const char *b)
{
    float *pa = render(a), *pb = render(b);
    int same = memcmp(pa, pb, npix() * 4 * sizeof(float)) == 0;
    free(pa);
    free(pb);
    return same;
}

/* Pixels whose alpha is set (the clear colour is 0, every draw writes 1). */
static size_t covered(const char *spec)
{
    float *px = render(spec);
    size_t n = 0;
    for (size_t i = 0; i < npix(); i++)
        n += px[4 * i + 3] > 0.5f;
    free(px);
    return n;
}

/* ---- lod = cpu-per-patch -------------------------------------------------- */

/* Triangle patches (sphere) and quad patches (terrain) close enough for
 * the distance levels to vary from patch to patch; the cylinder's cap
 * spokes carry a long-edge factor of 6 (mesh_edge_factor), which the CPU
 * side must apply as the shader does. */
static const char *const lod_scene[3] = {
    "mesh=sphere mesh_density=2 camera.distance=2.2 tess_level=12",
    "mesh=terrain camera.distance=1.6 camera.elevation=35 tess_level=10",
    "mesh=cylinder camera.distance=2.5 camera.elevation=50 tess_level=4",
};

/* The shader's distance LOD and the same LOD computed on the CPU give the
 * same tessellation: identical evaluation and primitive counts, and the
 * same image, with one level per patch and per edge (crack_free). */
static void test_lod_cpu_equals_shader(void **state)
{
    (void)state;
    for (int s = 0; s < 3; s++)
        for (int cf = 0; cf < 2; cf++) {
            char a[256], b[256], u[256];
            const char *crack = cf ? "crack_free=on" : "crack_free=off";
            snprintf(a, sizeof a, "technique=tess-displacement %s %s lod=distance", lod_scene[s], crack);
            snprintf(b, sizeof b, "technique=tess-displacement %s %s lod=cpu-per-patch", lod_scene[s], crack);
            snprintf(u, sizeof u, "technique=tess-displacement %s %s lod=uniform", lod_scene[s], crack);
            stats sa = count(a), sb = count(b), su = count(u);
            printf("%s %s: shader LOD %llu evaluations / %llu primitives, CPU LOD %llu / %llu, "
                   "uniform %llu\n", lod_scene[s], crack, (unsigned long long)sa.tes,
                   (unsigned long long)sa.clip_out, (unsigned long long)sb.tes,
                   (unsigned long long)sb.clip_out, (unsigned long long)su.tes);
            assert_int_equal(sa.tes, sb.tes);
            assert_int_equal(sa.clip_in, sb.clip_in);
            assert_int_equal(sa.clip_out, sb.clip_out);
            assert_true(sa.tes != su.tes);   /* the level does depend on distance here */
            assert_true(same_image(a, b));
        }
}

/* The CPU levels follow level / distance: a patch twice as far gets half
 * the level; per-edge levels use the edge opposite each corner. */
static void test_lod_cpu_levels(void **state)
{
    (void)state;
    const float pos[] = {0, 0, 0, 3, 0, 0, 0, 3, 0, /* patch 0 */ 0, 0, 6, 3, 0, 6, 0, 3, 6};
    const uint32_t idx[] = {0, 1, 2, 3, 4, 5};
    const float eye[3] = {1, 1, -2};
    float out[8];
    lod_cpu_levels(pos, idx, 2, 3, eye, 12.0f, 0.0f, 0, out);
    assert_float_equal(out[0], 12.0f / 2.0f, 1e-6);      /* centre (1,1,0) at distance 2 */
    assert_float_equal(out[3], 12.0f / 2.0f, 1e-6);
    assert_float_equal(out[4], 12.0f / 8.0f, 1e-6);      /* centre (1,1,6) at distance 8 */
    lod_cpu_levels(pos, idx, 1, 3, eye, 12.0f, 0.0f, 1, out);
    /* edge 0 = corners 1-2, midpoint (1.5,1.5,0): distance sqrt(0.5 + 4) */
    assert_float_equal(out[0], 12.0f / sqrtf(4.5f), 1e-5);
    /* edge 2 = corners 0-1, midpoint (1.5,0,0): distance sqrt(0.25 + 1 + 4) */
    assert_float_equal(out[2], 12.0f / sqrtf(5.25f), 1e-5);
    assert_float_equal(out[3], 0.0f, 0);
}

/* ---- lod = object-points / object-cpu (S4 Tables 8.3 / 8.4) --------------- */

/* Objects of a small mesh: two runs of one triangle and a run of the
 * whole mesh; bounds, tile origin on y = 0 and bounding-box centre. */
static void test_lod_cpu_objects(void **state)
{
    (void)state;
    const float pos[] = {0, 1, 0, 2, 3, 0, 0, 1, 4, /* */ 2, -1, 4, 6, 1, 4, 2, 1, 8};
    const uint32_t idx[] = {0, 1, 2, 3, 4, 5};
    lod_object o[3];
    assert_int_equal(lod_cpu_objects(pos, idx, 2, 1, o), 2);
    assert_int_equal(o[1].first_tri, 1);
    assert_int_equal(o[1].n_tris, 1);
    const float tile0[4] = {0, 0, 2, 4}, tile1[4] = {2, 4, 6, 8};
    for (int k = 0; k < 4; k++) {
        assert_float_equal(o[0].tile[k], tile0[k], 0);
        assert_float_equal(o[1].tile[k], tile1[k], 0);
    }
    assert_float_equal(o[1].origin[0], 4.0f, 0);
    assert_float_equal(o[1].origin[1], 0.0f, 0);     /* the tile's base plane */
    assert_float_equal(o[1].origin[2], 6.0f, 0);
    assert_float_equal(o[1].centre[1], 0.0f, 0);     /* y from -1 to 1 */
    assert_float_equal(o[0].centre[1], 2.0f, 0);     /* y from 1 to 3 */
    assert_int_equal(lod_cpu_objects(pos, idx, 2, 0, o), 1);   /* untiled: one object */
    assert_int_equal(o[0].n_tris, 2);
    assert_float_equal(o[0].origin[0], 0.0f, 0);      /* the mesh's own origin */
    assert_float_equal(o[0].centre[2], 4.0f, 0);
    const float eye[3] = {3, 4, 0}, at[3] = {0, 0, 0};
    assert_float_equal(lod_cpu_distance(eye, at), 5.0f, 1e-6);
}

/* Vertices of one triangle patch, equal spacing, levels already rounded
 * up: the outer ring o0 + o1 + o2, then inner rings of n−2, n−4, ...
 * segments per side (3m vertices, m = 0: the centre); inner 1 under an
 * outer above 1 counts as 2; all levels 1: the triangle itself. */
static GLuint64 tri_vertices(int n, const int o[3])
{
    if (n == 1 && o[0] == 1 && o[1] == 1 && o[2] == 1)
        return 3;
    n = n == 1 ? 2 : n;
    GLuint64 v = (GLuint64)(o[0] + o[1] + o[2]);
    for (int m = n - 2; m >= 0; m -= 2)
        v += m ? 3 * (GLuint64)m : 1;
    return v;
}

static int lvl(double l) { return (int)ceil(fmin(fmax(l, 1.0), 64.0)); }

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* The evaluations S4's per-tile levels give on terrain-tiles of d tiles at
 * level L seen from eye: per tile (8 consecutive triangles) the object's
 * distance is from the tile centre on y = 0 (cpu = 0, Table 8.3) or from
 * the centre of the tile's bounding box (cpu = 1, Table 8.4); an outer
 * edge lying on a side of the tile takes that side's centre (y = 0). */
static GLuint64 tiles_expected(int d, int L, const double eye[3], int cpu)
{
    mesh_data m;
    assert_int_equal(mesh_build(&(mesh_desc){.name = "terrain-tiles", .density = d}, &m), 0);
    assert_int_equal(m.object_triangles, 8);
    GLuint64 total = 0;
    for (size_t t = 0; t < m.n_indices / 24; t++) {
        const uint32_t *ix = m.indices + 24 * t;
        double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
        for (int i = 0; i < 24; i++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], m.vertices[ix[i]].pos[k]);
                hi[k] = fmax(hi[k], m.vertices[ix[i]].pos[k]);
            }
        double c[3] = {0.5 * (lo[0] + hi[0]), cpu ? 0.5 * (lo[1] + hi[1]) : 0.0, 0.5 * (lo[2] + hi[2])};
        double obj = L / dist3(eye, c);
        for (int tri = 0; tri < 8; tri++) {
            int o[3];
            for (int e = 0; e < 3; e++) {
                const float *a = m.vertices[ix[3 * tri + (e + 1) % 3]].pos;
                const float *b = m.vertices[ix[3 * tri + (e + 2) % 3]].pos;
                double side[3] = {c[0], 0.0, c[2]};
                int on = 1;
                if (a[0] == b[0] && (a[0] == lo[0] || a[0] == hi[0]))
                    side[0] = a[0];
                else if (a[2] == b[2] && (a[2] == lo[2] || a[2] == hi[2]))
                    side[2] = a[2];
                else
                    on = 0;
                o[e] = lvl(on ? L / dist3(eye, side) : obj);
            }
            total += tri_vertices(lvl(obj), o);
        }
    }
    mesh_free(&m);
    return total;
}

/* S4's two LOD variants on its tiled terrain of triangle patches: the
 * evaluation counts are those of the per-tile levels computed above, and
 * the two differ (the tile's origin on its base plane against its
 * bounding-sphere centre), as S4's VSVerticesIn did (393 508 / 393 176). */
static void test_lod_object_counts(void **state)
{
    (void)state;
    static const struct { int d, L; double dist, az, el; } v[] = {
        {8, 12, 1.6, 30, 35}, {4, 20, 2.5, 200, 50}, {8, 32, 1.1, 75, 20}};
    for (size_t i = 0; i < sizeof v / sizeof *v; i++) {
        double az = v[i].az * M_PI / 180, el = v[i].el * M_PI / 180;
        double eye[3] = {v[i].dist * cos(el) * sin(az), v[i].dist * sin(el), v[i].dist * cos(el) * cos(az)};
        GLuint64 e[2];
        for (int cpu = 0; cpu < 2; cpu++) {
            char spec[320];
            snprintf(spec, sizeof spec, "technique=tess-displacement mesh=terrain-tiles mesh_density=%d "
                     "tess_level=%d crack_free=on cull=off lod=%s camera.distance=%g "
                     "camera.azimuth=%g camera.elevation=%g", v[i].d, v[i].L,
                     cpu ? "object-cpu" : "object-points", v[i].dist, v[i].az, v[i].el);
            e[cpu] = tiles_expected(v[i].d, v[i].L, eye, cpu);
            stats s = count(spec);
            printf("%s: %llu evaluations, expected %llu\n", spec, (unsigned long long)s.tes,
                   (unsigned long long)e[cpu]);
            assert_int_equal(s.tes, e[cpu]);
        }
        assert_true(e[0] != e[1]);
    }
}

/* Without crack_free every edge of a tile takes the tile's level: the
 * count is the sum over tiles of 8 patches at that one level. */
static void test_lod_object_uncracked_levels(void **state)
{
    (void)state;
    double eye[3] = {0, 1.6 * sin(35 * M_PI / 180), 1.6 * cos(35 * M_PI / 180)};
    mesh_data m;
    assert_int_equal(mesh_build(&(mesh_desc){.name = "terrain-tiles", .density = 4}, &m), 0);
    GLuint64 want = 0;
    for (size_t t = 0; t < m.n_indices / 24; t++) {
        double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
        for (int i = 0; i < 24; i++) {
            const float *p = m.vertices[m.indices[24 * t + (size_t)i]].pos;
            lo[0] = fmin(lo[0], p[0]), hi[0] = fmax(hi[0], p[0]);
            lo[1] = fmin(lo[1], p[2]), hi[1] = fmax(hi[1], p[2]);
        }
        double c[3] = {0.5 * (lo[0] + hi[0]), 0, 0.5 * (lo[1] + hi[1])};
        int l = lvl(16 / dist3(eye, c));
        want += 8 * tri_vertices(l, (const int[3]){l, l, l});
    }
    mesh_free(&m);
    stats s = count("technique=tess-displacement mesh=terrain-tiles mesh_density=4 tess_level=16 "
                    "crack_free=off lod=object-points camera.distance=1.6 camera.azimuth=0 "
                    "camera.elevation=35");
    assert_int_equal(s.tes, want);
}

/* A mesh of quad patches is one object: every quad of the terrain takes
 * the level L / d, d from the mesh origin (object-points) or from the
 * centre of its bounding box (object-cpu), and evaluates (l+1)² vertices. */
static void test_lod_object_quads(void **state)
{
    (void)state;
    mesh_data m;
    assert_int_equal(mesh_build(&(mesh_desc){.name = "terrain", .density = 2}, &m), 0);
    double lo = 1e9, hi = -1e9;
    for (size_t v = 0; v < m.n_vertices; v++)
        lo = fmin(lo, m.vertices[v].pos[1]), hi = fmax(hi, m.vertices[v].pos[1]);
    mesh_free(&m);
    const double el = 40 * M_PI / 180, eye[3] = {0, 1.3 * sin(el), 1.3 * cos(el)};
    for (int cpu = 0; cpu < 2; cpu++) {
        double c[3] = {0, cpu ? 0.5 * (lo + hi) : 0, 0};
        int l = lvl(20 / dist3(eye, c));
        char spec[256];
        snprintf(spec, sizeof spec, "technique=tess-displacement mesh=terrain mesh_density=2 "
                 "tess_level=20 crack_free=on lod=%s camera.distance=1.3 camera.azimuth=0 "
                 "camera.elevation=40", cpu ? "object-cpu" : "object-points");
        assert_int_equal(count(spec).tes, 4 * (GLuint64)(l + 1) * (GLuint64)(l + 1));
    }
}

/* ---- tess_inner / tess_outer --------------------------------------------- */

/* The tessellation rule for one triangle patch, equal spacing, inner level
 * n and all three outer levels o: the outer ring has 3o vertices; inner
 * rings of m = n-2, n-4, ... segments per side have 3m vertices (m = 0: the
 * centre alone); between the outer ring and the first inner ring lie
 * 3(o + n - 2) triangles, between rings m and m-2 3(2m - 2), and an
 * innermost ring of m = 1 is one triangle.  An inner level 1 with an outer
 * level above 1 is tessellated as 2 (GL: 1 + epsilon, rounded up); all
 * levels 1 give the patch itself. */
static void tri_rule(int n, int o, GLuint64 *vertices, GLuint64 *triangles)
{
    if (n == 1 && o == 1) {
        *vertices = 3;
        *triangles = 1;
        return;
    }
    n = n == 1 ? 2 : n;
    GLuint64 v = 3 * (GLuint64)o, t = 3 * (GLuint64)(o + n - 2);
    for (int m = n - 2; m >= 0; m -= 2) {
        v += m ? 3 * (GLuint64)m : 1;
        t += m >= 2 ? 3 * (GLuint64)(2 * m - 2) : (GLuint64)(m == 1);
    }
    *vertices = v;
    *triangles = t;
}

static void test_inner_outer_counts(void **state)
{
    (void)state;
    GLuint64 v, t;
    tri_rule(4, 1, &v, &t);          /* 3 corners + ring of 6 + centre; 9 + 6 */
    assert_int_equal(v, 10);
    assert_int_equal(t, 15);
    tri_rule(1, 4, &v, &t);          /* 12 on the outer ring + centre; a fan of 12 */
    assert_int_equal(v, 13);
    assert_int_equal(t, 12);
    tri_rule(64, 64, &v, &t);        /* S4: one triangle at level 64 */
    assert_int_equal(v, 3169);
    assert_int_equal(t, 6144);
    static const int inner[] = {1, 2, 3, 4, 7, 16, 33}, outer[] = {1, 2, 5, 16, 64};
    for (size_t i = 0; i < sizeof inner / sizeof *inner; i++)
        for (size_t o = 0; o < sizeof outer / sizeof *outer; o++) {
            char spec[256];
            snprintf(spec, sizeof spec, "technique=tess-displacement mesh=triangle tess_level=9 "
                     "tess_inner=%d tess_outer=%d camera.azimuth=0 camera.elevation=0 "
                     "height_scale=0", inner[i], outer[o]);
            stats s = count(spec);
            tri_rule(inner[i], outer[o], &v, &t);
            if (s.tes != v || s.clip_out != t)
                printf("inner %d outer %d: %llu evaluations, %llu primitives; rule %llu, %llu\n",
                       inner[i], outer[o], (unsigned long long)s.tes,
                       (unsigned long long)s.clip_out, (unsigned long long)v, (unsigned long long)t);
            assert_int_equal(s.tes, v);
            assert_int_equal(s.clip_out, t);
        }
    /* auto = tess_level: the default renders and counts as inner = outer = level */
    const char *def = "technique=tess-displacement mesh=sphere mesh_density=2 tess_level=6";
    const char *expl = "technique=tess-displacement mesh=sphere mesh_density=2 tess_level=6 "
                       "tess_inner=6 tess_outer=6";
    assert_true(same_image(def, expl));
    assert_int_equal(count(def).tes, count(expl).tes);
}

/* ---- cull ---------------------------------------------------------------- */

/* From inside the closed cube (half-size 1, camera 0.5 from its centre)
 * every face is a back face: cull=back draws nothing, cull=off covers every
 * pixel.  Outside it (distance 8, all of it in view) cull=off also draws
 * the 6 back triangles: the image stays the same (they are hidden), the
 * fragment work grows (llvmpipe counts all 12 triangles in the clipping
 * stage either way: its culling comes after). */
static void test_cull_axis(void **state)
{
    (void)state;
    assert_int_equal(covered("technique=phong mesh=cube camera.distance=0.5"), 0);
    assert_int_equal(covered("technique=phong mesh=cube camera.distance=0.5 cull=off"), npix());
    const char *back = "technique=phong mesh=cube camera.distance=8",
               *off = "technique=phong mesh=cube camera.distance=8 cull=off";
    stats sb = count(back), so = count(off);
    printf("cube from outside: cull=back %llu fragment invocations, cull=off %llu\n",
           (unsigned long long)sb.fs, (unsigned long long)so.fs);
    assert_int_equal(sb.clip_in, 12);
    assert_int_equal(so.clip_in, 12);
    assert_true(so.fs > sb.fs);
    assert_true(same_image(back, off));
    assert_true(same_image(back, "technique=phong mesh=cube camera.distance=8 cull=back"));
    /* a plane seen from below */
    assert_int_equal(covered("technique=phong mesh=plane camera.elevation=-30"), 0);
    assert_true(covered("technique=phong mesh=plane camera.elevation=-30 cull=off") > npix() / 10);
}

/* ---- attenuation ----------------------------------------------------------- */

/* The centre pixel's colour of each of n specs ("BASE SUFFIX") on a 65×65
 * target: c[i] for suffix[i]. */
static void centre_colours(const char *base, const char *const *suffix, int n, float (*c)[3])
{
    target(65, 65);
    for (int i = 0; i < n; i++) {
        char spec[256];
        snprintf(spec, sizeof spec, "%s %s", base, suffix[i]);
        float *px = render(spec);
        memcpy(c[i], px + 4 * (32 * 65 + 32), sizeof c[i]);
        free(px);
    }
    target(256, 192);
}

/* Centre pixel of an odd-sized target: the ray through the camera target,
 * the origin, a point of the plane at distance light.distance ·
 * camera.distance = 1.2 · 3 = 3.6 from light 0.  The lit part of a pixel
 * is attenuation × (the same diffuse + specular), so against a render where
 * s1's radius is below 3.6 (attenuation 0: ambient only) the ratio of the
 * lit parts is the ratio of attenuations: s1 with r = 7.2 gives
 * 1 - 3.6²/7.2² = 0.75, the default 1/(1 + 0.1·3.6 + 0.05·3.6²) = 1/2.008,
 * none 1. */
static void test_attenuation_s1(void **state)
{
    (void)state;
    const char *base = "technique=phong mesh=plane maps=flat";
    static const char *const suffix[4] = {"attenuation=s1 light_radius=3.5",
                                          "attenuation=s1 light_radius=7.2", "",
                                          "attenuation=none"};
    float c[4][3];
    centre_colours(base, suffix, 4, c);
    double inv = 1.0 / (1.0 + 0.1 * 3.6 + 0.05 * 3.6 * 3.6);
    for (int k = 0; k < 3; k++) {
        double lit_s1 = c[1][k] - c[0][k], lit_inv = c[2][k] - c[0][k], lit_none = c[3][k] - c[0][k];
        printf("channel %d: ambient %.6f, s1 %.6f, inverse-quadratic %.6f, none %.6f\n", k,
               c[0][k], lit_s1, lit_inv, lit_none);
        assert_true(lit_none > 0.05);
        assert_float_equal(lit_s1 / lit_none, 0.75, 1e-4);
        assert_float_equal(lit_inv / lit_none, inv, 1e-4);
    }
    /* the default is today's inverse-quadratic falloff */
    assert_true(same_image(base, "technique=phong mesh=plane maps=flat attenuation=inverse-quadratic"));
}

/* ---- shadow = soft-s2 --------------------------------------------------------- */

/* S2's soft shadow with its own constants: on the flat map every sample's
 * penetration is h - h0 - t = -t, the largest of (-t)(5.1 - t) over
 * t = 0.88 .. 0.22 is at t = 0.22, so the light's term is scaled by
 * (1 + 0.22 * 4.88) * 0.45 = 0.93312 (the ambient term is not shadowed;
 * a light attenuated to 0 gives the ambient-only image). */
static void test_shadow_soft_s2(void **state)
{
    (void)state;
    static const char *const suffix[3] = {"light_radius=1 shadow=none", "light_radius=50 shadow=none",
                                          "light_radius=50 shadow=soft-s2"};
    float c[3][3];
    centre_colours("technique=pom mesh=plane maps=flat lighting=lambert attenuation=s1", suffix, 3, c);
    for (int k = 0; k < 3; k++) {
        double lit = c[1][k] - c[0][k], s2 = c[2][k] - c[0][k];
        printf("channel %d: ambient %.6f, lit %.6f, soft-s2 %.6f (ratio %.6f)\n", k, c[0][k], lit,
               s2, s2 / lit);
        assert_true(lit > 0.05);
        assert_float_equal(s2 / lit, (1.0 + 0.22 * 4.88) * 0.45, 1e-4);
    }
}

/* ---- height_format in vertex-displacement --------------------------------- */

/* View-space depth of the centre pixel (centre row and column of the
 * target), from the depth buffer and the renderer's near 0.05 / far 100. */
static double centre_depth(const char *spec)
{
    float *px = render(spec);
    free(px);
    float z;
    glReadPixels(F.w / 2, F.h / 2, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &z);
    double n = 0.05, f = 100, ndc = 2.0 * z - 1.0;
    return 2.0 * n * f / (f + n - ndc * (f - n));
}

/* The flat map's height 0.5 is exact in r32f but 128/255 in r8 and
 * 32768/65535 in r16: with height_scale 1 the r8 plane lies
 * (128/255 - 0.5) = 0.00196 world units higher, seen from straight above
 * 0.00196 nearer the camera; r16's offset is 128 times smaller. */
static void test_vertex_height_format(void **state)
{
    (void)state;
    target(65, 65);
    const char *base = "technique=vertex-displacement mesh=plane maps=flat height_scale=1 "
                       "camera.elevation=89.9";
    char spec[160];
    double d32 = centre_depth(base);
    snprintf(spec, sizeof spec, "%s height_format=r8", base);
    double d8 = centre_depth(spec);
    snprintf(spec, sizeof spec, "%s height_format=r16", base);
    double d16 = centre_depth(spec);
    double want8 = 128.0 / 255.0 - 0.5;
    printf("centre depth r32f %.7f, r8 %.7f (nearer by %.7f, expected %.7f), r16 %.7f\n", d32, d8,
           d32 - d8, want8, d16);
    assert_float_equal(d32, 3.0, 1e-3);
    assert_float_equal(d32 - d8, want8, 0.1 * want8);
    assert_true(fabs(d32 - d16) < 0.1 * want8);
    snprintf(spec, sizeof spec, "%s height_format=r32f", base);
    assert_true(same_image(base, spec));
    target(256, 192);
}

/* ---- parallax_bias ------------------------------------------------------- */

static void test_parallax_bias(void **state)
{
    (void)state;
    const char *def = "technique=parallax mesh=plane maps=bricks height_scale=0.1";
    assert_true(same_image(def, "technique=parallax mesh=plane maps=bricks height_scale=0.1 "
                                "parallax_bias=0.5"));
    float *a = render(def);
    float *b = render("technique=parallax mesh=plane maps=bricks height_scale=0.1 parallax_bias=0");
    double p = psnr(a, b, npix());
    printf("parallax_bias 0 against the default 0.5: PSNR %.2f dB\n", p);
    assert_true(isfinite(p) && p < 40.0);
    free(a);
    free(b);
    /* with no depth the bias has nothing to scale */
    assert_true(same_image("technique=parallax mesh=plane height_scale=0",
                           "technique=parallax mesh=plane height_scale=0 parallax_bias=1"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lod_cpu_levels),
        cmocka_unit_test(test_lod_cpu_equals_shader),
        cmocka_unit_test(test_lod_cpu_objects),
        cmocka_unit_test(test_lod_object_counts),
        cmocka_unit_test(test_lod_object_uncracked_levels),
        cmocka_unit_test(test_lod_object_quads),
        cmocka_unit_test(test_inner_outer_counts),
        cmocka_unit_test(test_cull_axis),
        cmocka_unit_test(test_attenuation_s1),
        cmocka_unit_test(test_shadow_soft_s2),
        cmocka_unit_test(test_vertex_height_format),
        cmocka_unit_test(test_parallax_bias),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
