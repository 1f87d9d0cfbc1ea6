/* GL tests of the geometry techniques on llvmpipe (tess-displacement,
 * vertex-displacement, reference-mesh): exact tessellation counts against
 * the tessellation rules, culling, LOD, cracks and image equivalences. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/dm_util.h"
#include "run/gl_context.h"
#include "tests/tech_fixture.h"
#include "imaging/image.h"
#include "imaging/quality.h"
#include "techniques/mesh.h"
#include "techniques/render.h"

static int setup(void **state) { return techfix_setup(state, 256, 192); }

static render_item prepare(const char *spec) { return spec_prepare(F.r, spec, 0, NULL); }

/* Pipeline statistics of one draw of spec. */
typedef struct stats { GLuint64 tes, clip_out, patches; } stats;

static stats count(const char *spec)
{
    static const GLenum tgt[3] = {GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB,
                                  GL_CLIPPING_OUTPUT_PRIMITIVES_ARB, GL_TESS_CONTROL_SHADER_PATCHES_ARB};
    GLuint64 v[3];
    draw_queried(spec, tgt, 3, v);
    return (stats){v[0], v[1], v[2]};
}

/* Primitives submitted by one draw of spec (the pipeline statistic). */
static GLuint64 submitted(const char *spec)
{
    render_item it = prepare(spec);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    GLuint q;
    GLuint64 n = 0;
    glGenQueries(1, &q);
    glBeginQuery(GL_PRIMITIVES_SUBMITTED_ARB, q);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    glEndQuery(GL_PRIMITIVES_SUBMITTED_ARB);
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &q);
    render_release(F.r, it);
    return n;
}

/* Renders spec into im (allocated, row 0 = GL's bottom row). */
static void render_img(const char *spec, img *im)
{
    render_item it = prepare(spec);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    assert_int_equal(img_alloc(im, F.w, F.h), 0);
    glReadPixels(0, 0, F.w, F.h, GL_RGBA, GL_FLOAT, im->px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    render_release(F.r, it);
}

static double psnr_of(const char *ref, const char *test)
{
    img a, b;
    img_metrics m;
    render_img(ref, &a);
    render_img(test, &b);
    assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
    assert_int_equal(m.nonfinite, 0);
    img_free(&a);
    img_free(&b);
    return m.psnr;
}

/* The tessellation rule for one triangle patch with inner = outer = L and
 * equal spacing, L even: concentric rings of 3m vertices for m = L, L-2,
 * ..., 2 plus the centre vertex; the strip between ring m and ring m-2 holds
 * 3(2m-2) triangles. */
static void triangle_rule(int L, GLuint64 *vertices, GLuint64 *triangles)
{
    GLuint64 v = 1, t = 0;
    for (int m = L; m >= 2; m -= 2) {
        v += 3 * (GLuint64)m;
        t += 3 * (GLuint64)(2 * m - 2);
    }
    *vertices = v;
    *triangles = t;
}

static void test_rule_matches_known_counts(void **state)
{
    (void)state;
    GLuint64 v, t;
    triangle_rule(16, &v, &t);
    assert_int_equal(v, 217);
    triangle_rule(64, &v, &t);
    assert_int_equal(v, 3169);
    assert_int_equal(t, 6144);
}

static void test_exact_counts_every_even_level(void **state)
{
    (void)state;
    stats one = count("technique=tess-displacement mesh=triangle tess_level=1 camera.azimuth=0 "
                      "camera.elevation=0 height_scale=0");
    assert_int_equal(one.tes, 3);
    assert_int_equal(one.clip_out, 1);
    for (int L = 2; L <= 64; L += 2) {
        char spec[256];
        snprintf(spec, sizeof spec, "technique=tess-displacement mesh=triangle tess_level=%d "
                 "tess_spacing=equal camera.azimuth=0 camera.elevation=0 height_scale=0", L);
        stats s = count(spec);
        GLuint64 v, t;
        triangle_rule(L, &v, &t);
        assert_int_equal(s.patches, 1);
        assert_int_equal(s.tes, v);
        assert_int_equal(s.clip_out, t);
    }
}

static void test_patch_cull_back_facing(void **state)
{
    (void)state;
    const char *base = "technique=tess-displacement mesh=triangle tess_level=16 camera.azimuth=180 "
                       "camera.elevation=0";
    char spec[256];
    snprintf(spec, sizeof spec, "%s patch_cull=off", base);
    assert_int_equal(count(spec).tes, 217);
    snprintf(spec, sizeof spec, "%s patch_cull=on", base);
    assert_int_equal(count(spec).tes, 0);
    /* Facing the camera: nothing is culled. */
    assert_int_equal(count("technique=tess-displacement mesh=triangle tess_level=16 patch_cull=on "
                           "camera.azimuth=0 camera.elevation=0").tes, 217);
}

static long covered(const img *im)
{
    long n = 0;
    for (long i = 0; i < (long)im->w * im->h; i++)
        n += im->px[4 * i + 3] > 0.5f;
    return n;
}

/* Every patch of a many-patch mesh is tessellated (320 × 217 vertices) and
 * rasterised: the silhouette equals normal mapping's (llvmpipe dropped
 * primitives of large patch batches before render.c split the draw). */
static void test_every_patch_tessellated(void **state)
{
    (void)state;
    stats s = count("technique=tess-displacement mesh=sphere mesh_density=2 tess_level=16");
    assert_int_equal(s.patches, 320);
    assert_int_equal(s.tes, 320 * 217);
    img a, b;
    render_img("technique=normal mesh=sphere mesh_density=2", &a);
    render_img("technique=tess-displacement mesh=sphere mesh_density=2 tess_level=16 height_scale=0", &b);
    long ca = covered(&a), cb = covered(&b);
    assert_true(ca > 10000);
    assert_true(labs(ca - cb) <= 4);
    img_free(&a);
    img_free(&b);
}

/* lod distance: TES invocations fall strictly as the camera recedes. */
static void test_lod_distance_monotonic(void **state)
{
    (void)state;
    static const char *const cf[] = {"off", "on"};
    for (int k = 0; k < 2; k++) {
        GLuint64 prev = UINT64_MAX;
        for (double d = 1.5; d <= 12.0; d *= 2) {
            char spec[256];
            snprintf(spec, sizeof spec, "technique=tess-displacement mesh=plane mesh_density=5 "
                     "tess_level=64 lod=distance crack_free=%s camera.distance=%g", cf[k], d);
            stats st = count(spec);
            printf("lod distance crack_free=%s d=%g: TESInvocations %llu\n", cf[k], d,
                   (unsigned long long)st.tes);
            assert_true(st.tes < prev);
            prev = st.tes;
        }
        assert_true(prev > 0);
    }
}

/* Crack pixels of spec with back faces culled (render_draw culls them). */
static long cracks(const char *spec)
{
    img im;
    render_img(spec, &im);
    unsigned char *mask = malloc((size_t)im.w * (size_t)im.h);
    quality_coverage(&im, mask);
    long c = quality_crack_pixels(mask, im.w, im.h);
    free(mask);
    img_free(&im);
    return c;
}

/* base with crack_free off shows cracks, with crack_free on exactly none. */
static void expect_cracks_only_when_off(const char *what, const char *base)
{
    char spec[384];
    snprintf(spec, sizeof spec, "%s crack_free=off", base);
    long off = cracks(spec);
    snprintf(spec, sizeof spec, "%s crack_free=on", base);
    long on = cracks(spec);
    printf("CrackPixels %s: crack_free off %ld, on %ld\n", what, off, on);
    assert_true(off > 0);
    assert_int_equal(on, 0);
}

/* The seam mesh tears along its UV seam unless crack_free is on. */
static void test_cracks_at_uv_seam(void **state)
{
    (void)state;
    expect_cracks_only_when_off("seam mesh", "technique=tess-displacement mesh=seam tess_level=8 "
                                "height_scale=0.3 camera.azimuth=90 camera.elevation=25 camera.distance=2.6");
}

/* lod flatness on a half-flat height field: clearly fewer TES invocations
 * than uniform at the same level, at the same error against the reference. */
static void test_lod_flatness(void **state)
{
    (void)state;
    const char *base = "technique=tess-displacement mesh=halfflat tess_level=32 height_scale=0.1";
    char u[256], f[256], ref[256];
    snprintf(u, sizeof u, "%s lod=uniform", base);
    snprintf(f, sizeof f, "%s lod=flatness", base);
    snprintf(ref, sizeof ref, "technique=reference-mesh mesh=halfflat height_scale=0.1");
    stats su = count(u), sf = count(f);
    double pu = psnr_of(ref, u), pf = psnr_of(ref, f);
    printf("halfflat: TESInvocations uniform %llu, flatness %llu; PSNR vs reference %.2f / %.2f dB\n",
           (unsigned long long)su.tes, (unsigned long long)sf.tes, pu, pf);
    assert_true((double)sf.tes <= 0.7 * (double)su.tes);
    assert_true(pf >= pu - 0.5);
}

/* Terrain tiles are quad patches: one tile at level L (equal spacing) gives
 * the quad domain's (L+1)² vertices and 2L² triangles; a tile seen from
 * below is culled by patch_cull. */
static void test_terrain_quad_counts(void **state)
{
    (void)state;
    for (int L = 1; L <= 64; L = L < 4 ? L + 1 : L * 2) {
        char spec[256];
        snprintf(spec, sizeof spec, "technique=tess-displacement mesh=terrain mesh_density=1 "
                 "tess_level=%d tess_spacing=equal camera.elevation=60 camera.distance=6 height_scale=0", L);
        stats st = count(spec);
        assert_int_equal(st.patches, 1);
        assert_int_equal(st.tes, (GLuint64)(L + 1) * (GLuint64)(L + 1));
        assert_int_equal(st.clip_out, 2 * (GLuint64)L * (GLuint64)L);
    }
    const char *below = "technique=tess-displacement mesh=terrain mesh_density=1 tess_level=8 "
                        "camera.elevation=-60";
    char spec[256];
    snprintf(spec, sizeof spec, "%s patch_cull=off", below);
    assert_int_equal(count(spec).tes, 81);
    snprintf(spec, sizeof spec, "%s patch_cull=on", below);
    assert_int_equal(count(spec).tes, 0);
    /* 16 × 16 tiles, all drawn: 256 patches. */
    assert_int_equal(count("technique=tess-displacement mesh=terrain tess_level=4 camera.distance=6 "
                           "camera.elevation=70").patches, 256);
}

/* S4's terrain: with lod distance, neighbouring tiles get different levels;
 * per-patch levels tear the displaced surface, edge levels from shared
 * edges (crack_free on) do not.  The view is close, so the terrain's far
 * silhouette (where bumps can enclose a background pixel diagonally, which
 * CrackPixels would count) stays out of the image. */
static void test_terrain_cracks(void **state)
{
    (void)state;
    expect_cracks_only_when_off("terrain (quad patches, lod distance)",
                                "technique=tess-displacement mesh=terrain mesh_density=8 tess_level=24 "
                                "lod=distance height_scale=0.2 camera.distance=1.2 camera.elevation=60 "
                                "maps=stones");
    /* S4's tiled terrain with one level per tile (Tables 8.3 / 8.4): its
     * neighbouring tiles crack unless the tile sides take their own levels */
    for (int cpu = 0; cpu < 2; cpu++) {
        char base[256];
        snprintf(base, sizeof base, "technique=tess-displacement mesh=terrain-tiles mesh_density=8 "
                 "tess_level=24 lod=%s height_scale=0.2 camera.distance=1.2 camera.elevation=60 "
                 "maps=stones", cpu ? "object-cpu" : "object-points");
        expect_cracks_only_when_off(cpu ? "terrain-tiles, lod object-cpu" : "terrain-tiles, lod object-points",
                                    base);
    }
}

/* S4's experiment: the reduced asteroid (320 triangles) displaced by the
 * baked maps approaches the original (81 920 CPU-displaced triangles) as the
 * tessellation level grows, and is far closer than the undisplaced sphere:
 * silhouette error (1 − IoU of coverage) and PSNR of the lit images. */
static void test_asteroid_reduced_vs_original(void **state)
{
    (void)state;
    const char *cam = "camera.distance=3.2 lighting=lambert maps=asteroid texture_size=1024";
    char orig[256], spec[256];
    snprintf(orig, sizeof orig, "technique=phong mesh=asteroid %s", cam);
    img a;
    render_img(orig, &a);
    unsigned char *ma = malloc((size_t)a.w * a.h), *mb = malloc((size_t)a.w * a.h);
    quality_coverage(&a, ma);
    static const int levels[] = {0, 1, 4, 16};
    double sil[4], psnr[4];
    for (int i = 0; i < 4; i++) {
        if (levels[i] == 0)
            snprintf(spec, sizeof spec, "technique=normal mesh=asteroid-reduced %s", cam);
        else
            snprintf(spec, sizeof spec, "technique=tess-displacement mesh=asteroid-reduced "
                     "height_scale=%.2f tess_level=%d %s", MESH_ASTEROID_SCALE, levels[i], cam);
        img b;
        img_metrics m;
        render_img(spec, &b);
        quality_coverage(&b, mb);
        sil[i] = quality_silhouette_error(ma, mb, (size_t)a.w * a.h);
        assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
        assert_int_equal(m.nonfinite, 0);
        psnr[i] = m.psnr;
        printf("asteroid-reduced %s level %d vs original: silhouette error %.4f, PSNR %.2f dB\n",
               levels[i] ? "tess-displacement" : "normal (no displacement)", levels[i], sil[i], psnr[i]);
        img_free(&b);
    }
    assert_true(sil[3] < 0.03);
    assert_true(sil[3] < 0.25 * sil[0]);
    assert_true(sil[3] < sil[1]);
    assert_true(psnr[3] > psnr[1] + 1.0);
    assert_true(psnr[3] > psnr[0] + 3.0);
    free(ma);
    free(mb);
    img_free(&a);
}

/* Phong tessellation rounds a coarse sphere (80 triangles) toward the true
 * one: against a level-5 sphere (20 480 triangles) the silhouette error of
 * tess-displacement at level 8 (height_scale 0) drops clearly with
 * tess_smooth phong; at level 1 (no new vertices) smoothing changes nothing. */
static void test_phong_tessellation(void **state)
{
    (void)state;
    img fine;
    render_img("technique=normal mesh=sphere mesh_density=5 camera.distance=2.6", &fine);
    size_t n = (size_t)fine.w * fine.h;
    unsigned char *mf = malloc(n), *mt = malloc(n);
    quality_coverage(&fine, mf);
    double sil[2][2];
    static const char *const smooth[] = {"off", "phong"};
    static const int level[] = {1, 8};
    for (int s = 0; s < 2; s++)
        for (int l = 0; l < 2; l++) {
            char spec[256];
            img im;
            snprintf(spec, sizeof spec, "technique=tess-displacement mesh=sphere mesh_density=1 "
                     "camera.distance=2.6 height_scale=0 tess_level=%d tess_smooth=%s", level[l], smooth[s]);
            render_img(spec, &im);
            quality_coverage(&im, mt);
            sil[s][l] = quality_silhouette_error(mf, mt, n);
            img_free(&im);
        }
    printf("sphere level 1 vs level 5: silhouette error flat %.4f (L1) %.4f (L8), phong %.4f (L1) %.4f (L8)\n",
           sil[0][0], sil[0][1], sil[1][0], sil[1][1]);
    assert_true(sil[1][1] < 0.5 * sil[0][1]);
    assert_float_equal(sil[1][0], sil[0][0], 1e-12);
    free(mf);
    free(mt);
    img_free(&fine);
}

/* Manual bilinear (4 fetches + 2 lerps) matches the hardware filter. */
static void test_bilinear_manual_matches_hw(void **state)
{
    (void)state;
    double p = psnr_of("technique=vertex-displacement mesh=plane mesh_density=200 height_scale=0.1 "
                       "vertex_filter=bilinear-hw filter=bilinear",
                       "technique=vertex-displacement mesh=plane mesh_density=200 height_scale=0.1 "
                       "vertex_filter=bilinear-manual filter=bilinear");
    printf("bilinear-manual vs bilinear-hw: PSNR %.2f dB\n", p);
    assert_true(p >= 45.0);
}

static int64_t thread_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Median calling-thread CPU time of 5 draws (+ glFinish) of spec. */
static double draw_ms(const char *spec)
{
    render_item it = prepare(spec);
    double t[5];
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    glFinish();
    for (int i = 0; i < 5; i++) {
        int64_t t0 = thread_ns();
        assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
        glFinish();
        t[i] = (double)(thread_ns() - t0) / 1e6;
    }
    for (int i = 1; i < 5; i++)
        for (int j = i; j > 0 && t[j] < t[j - 1]; j--) {
            double x = t[j];
            t[j] = t[j - 1];
            t[j - 1] = x;
        }
    render_release(F.r, it);
    return t[2];
}

/* Vertex-shader invocations of one draw of spec. */
static GLuint64 vs_invocations(const char *spec)
{
    render_item it = prepare(spec);
    GLuint q;
    glGenQueries(1, &q);
    glBeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, q);
    assert_int_equal(render_draw(F.r, it, F.w, F.h), 0);
    glEndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
    GLuint64 n;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &q);
    render_release(F.r, it);
    return n;
}

/* visibility_test: the image is unchanged, and with about half the grid
 * off-screen (top view, fov 20°: rows with |z| > ~0.6 are out) the vertex
 * stage runs clearly less (chunk culling; the per-vertex skip alone saves
 * nothing on llvmpipe).  With the whole grid in view nothing is culled.
 * The vertex time of both is printed (with rasterizer discard). */
static void test_visibility_test(void **state)
{
    (void)state;
    static const char *const view[] = {"camera.azimuth=0 camera.elevation=89 camera.fov=20",
                                       "camera.distance=4"};
    for (int i = 0; i < 2; i++) {
        char a[320], b[320];
        snprintf(a, sizeof a, "technique=vertex-displacement mesh=plane mesh_density=400 "
                 "height_scale=0.1 vertex_filter=mip-lerp %s visibility_test=off", view[i]);
        snprintf(b, sizeof b, "technique=vertex-displacement mesh=plane mesh_density=400 "
                 "height_scale=0.1 vertex_filter=mip-lerp %s visibility_test=on", view[i]);
        double p = psnr_of(a, b);
        GLuint64 vs_off = vs_invocations(a), vs_on = vs_invocations(b);
        glEnable(GL_RASTERIZER_DISCARD);
        double off = draw_ms(a), on = draw_ms(b);
        glDisable(GL_RASTERIZER_DISCARD);
        printf("visibility test (%s): PSNR on vs off %.2f dB; VSInvocations off %llu, on %llu; "
               "vertex time off %.2f ms, on %.2f ms\n", view[i], p, (unsigned long long)vs_off,
               (unsigned long long)vs_on, off, on);
        assert_true(p >= 60.0);
        if (i == 0)
            assert_true((double)vs_on <= 0.85 * (double)vs_off);
        else
            assert_int_equal(vs_on, vs_off);
    }
}

/* The reference renders a lit, finite image, and level 64 is closer to it
 * than level 1. */
static void test_reference_mesh(void **state)
{
    (void)state;
    const char *ref = "technique=reference-mesh mesh=plane height_scale=0.1";
    img im;
    render_img(ref, &im);
    assert_int_equal(quality_nonfinite_pixels(&im), 0);
    double s = 0, s2 = 0, n = 0;
    for (long i = 0; i < (long)im.w * im.h; i++)
        if (im.px[4 * i + 3] > 0.5f) {
            double y = 0.2126 * im.px[4 * i] + 0.7152 * im.px[4 * i + 1] + 0.0722 * im.px[4 * i + 2];
            s += y;
            s2 += y * y;
            n++;
        }
    assert_true(n > 5000);
    assert_true(sqrt(s2 / n - (s / n) * (s / n)) > 0.02);
    img_free(&im);
    double p1 = psnr_of(ref, "technique=tess-displacement mesh=plane height_scale=0.1 tess_level=1");
    double p64 = psnr_of(ref, "technique=tess-displacement mesh=plane height_scale=0.1 tess_level=64");
    printf("vs reference-mesh: tess level 1 %.2f dB, level 64 %.2f dB\n", p1, p64);
    assert_true(p64 > p1 + 1.0);
}

/* height_scale 0 moves nothing: the image equals normal mapping's at
 * height_scale 0 (normal maps follow height_scale, so both are flat). */
static void test_scale_zero_equals_normal(void **state)
{
    (void)state;
    static const char *const meshes[] = {"plane", "cube", "sphere"};
    for (int i = 0; i < 3; i++) {
        char a[256], b[256];
        snprintf(a, sizeof a, "technique=normal mesh=%s height_scale=0", meshes[i]);
        snprintf(b, sizeof b, "technique=tess-displacement mesh=%s tess_level=16 height_scale=0", meshes[i]);
        double p = psnr_of(a, b);
        printf("scale 0 vs normal on %s: PSNR %.2f dB\n", meshes[i], p);
        assert_true(p >= 50.0);
    }
}

/* displaced_normals: height shades a displaced surface with the normal the
 * reference builds (from the height map by central differences, S3), so it
 * comes closer to the reference than the normal map does.  The procedural
 * normal map is made from the same height field, so the two images differ
 * only by how each normal is discretised: not bit-identical, but close. */
static void test_displaced_normals(void **state)
{
    (void)state;
    const char *ref = "technique=reference-mesh mesh=plane maps=stones height_scale=0.1 camera.elevation=40";
    static const char *const tech[2] = {"tess-displacement tess_level=32", "vertex-displacement mesh_density=256"};
    for (int i = 0; i < 2; i++) {
        char map[256], height[320];
        snprintf(map, sizeof map, "technique=%s mesh=plane maps=stones height_scale=0.1 camera.elevation=40", tech[i]);
        snprintf(height, sizeof height, "%s displaced_normals=height", map);
        double p_map = psnr_of(ref, map), p_height = psnr_of(ref, height), p_both = psnr_of(map, height);
        print_message("%s: PSNR against the reference %.2f dB (normal map), %.2f dB (height); "
                      "map vs height %.2f dB\n", tech[i], p_map, p_height, p_both);
        assert_true(p_height > p_map);
        assert_true(isfinite(p_both) && p_both > 25.0);
    }
}

/* The scene meshes through the pipeline: S2's scene 1 submits its 22 086
 * triangles; S4's reduced asteroid scene is 12 + 5·320 = 1 612 patches. */
static void test_scene_counts(void **state)
{
    (void)state;
    assert_int_equal(submitted("technique=normal mesh=s2-scene1"), 22086);
    assert_int_equal(submitted("technique=normal mesh=s4-asteroids mesh_density=2"), 12 + 5 * 320);
    stats s = count("technique=tess-displacement mesh=s4-asteroids-reduced maps=asteroid "
                    "height_scale=0.207 tess_level=1");
    assert_int_equal(s.patches, 1612);
    /* the 1 600 asteroid patches are evaluated at their 3 corners; the 12
     * skybox triangles' edges are hundreds of median edges long, so the
     * long-edge factor (mesh_edge_factor) takes them to the clamp, level 64:
     * 3 169 evaluations each (the triangle rule at 64, test_experiment_axes) */
    assert_int_equal(s.tes, 3 * 1600 + 12 * 3169);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_rule_matches_known_counts),
             cmocka_unit_test(test_exact_counts_every_even_level),
             cmocka_unit_test(test_patch_cull_back_facing),
             cmocka_unit_test(test_every_patch_tessellated),
             cmocka_unit_test(test_scale_zero_equals_normal),
             cmocka_unit_test(test_lod_distance_monotonic),
             cmocka_unit_test(test_cracks_at_uv_seam),
             cmocka_unit_test(test_lod_flatness),
             cmocka_unit_test(test_terrain_quad_counts),
             cmocka_unit_test(test_terrain_cracks),
             cmocka_unit_test(test_asteroid_reduced_vs_original),
             cmocka_unit_test(test_phong_tessellation),
             cmocka_unit_test(test_bilinear_manual_matches_hw),
             cmocka_unit_test(test_visibility_test),
             cmocka_unit_test(test_reference_mesh),
             cmocka_unit_test(test_scene_counts),
             cmocka_unit_test(test_displaced_normals))
