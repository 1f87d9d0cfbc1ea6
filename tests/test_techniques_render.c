/* GL integration tests of techniques/render on llvmpipe: images, caches,
 * shader failures, item info, and invariants between techniques. */
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

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "run/gl_context.h"
#include "tests/tech_fixture.h"
#include "techniques/render.h"
#include "techniques/technique.h"

static int setup(void **state) { return techfix_setup(state, 256, 144); }


static void test_normal_plane(void **state)
{
    (void)state;
    float *px = render("technique=normal mesh=plane");
    assert_int_equal(non_finite(px, npix()), 0);
    assert_true(luma_stddev(px, npix()) > 0.01);
    free(px);
}

static void test_fullscreen_coverage(void **state)
{
    (void)state;
    float *px = render("technique=normal mesh=fullscreen");
    for (size_t i = 0; i < npix(); i++)
        assert_true(px[4 * i + 3] == 1.0f);
    free(px);
    /* Sanity of the check: the plane at the default camera leaves background. */
    px = render("technique=normal mesh=plane camera.distance=8");
    size_t empty = 0;
    for (size_t i = 0; i < npix(); i++)
        empty += px[4 * i + 3] == 0.0f;
    assert_true(empty > 0);
    free(px);
}

static void test_program_cache(void **state)
{
    (void)state;
    render_ctx *r;
    assert_int_equal(render_create(&r), 0);
    dm_kv kv[2] = {{"technique", "normal"}, {"lighting", "lambert"}};
    render_item a, b;
    render_item_info ia, ib;
    assert_int_equal(render_prepare(r, kv, 2, &a, NULL), 0);
    assert_int_equal(render_prepare(r, kv, 2, &b, NULL), 0);
    assert_int_equal(render_get_info(r, a, &ia), 0);
    assert_int_equal(render_get_info(r, b, &ib), 0);
    assert_int_equal(ia.program_cached, 0);
    assert_int_equal(ib.program_cached, 1);
    assert_true(ia.setup_ns > 0);
    /* A different lighting define is a different program. */
    dm_kv kv2[2] = {{"technique", "normal"}, {"lighting", "phong"}};
    assert_int_equal(render_prepare(r, kv2, 2, &b, NULL), 0);
    assert_int_equal(render_get_info(r, b, &ib), 0);
    assert_int_equal(ib.program_cached, 0);
    render_release(r, a);
    assert_int_equal(render_get_info(r, a, &ia), DM_ERR_ARG);
    render_destroy(r);
}

static void test_broken_shader(void **state)
{
    (void)state;
    dm_kv kv[1] = {{"technique", "debug-broken-shader"}};
    render_item it = {0};
    dm_str log = {0};
    assert_int_equal(render_prepare(F.r, kv, 1, &it, &log), DM_ERR_SHADER);
    assert_int_equal(it.id, 0);
    assert_non_null(strstr(dm_str_get(&log), "error"));
    assert_non_null(strstr(dm_str_get(&log), "broken.frag.glsl"));
    dm_str_free(&log);
}

static void test_bad_params(void **state)
{
    (void)state;
    render_item it;
    dm_str log = {0};
    dm_kv a[1] = {{"tess_levle", "4"}};
    assert_int_equal(render_prepare(F.r, a, 1, &it, &log), DM_ERR_UNKNOWN);
    assert_non_null(strstr(dm_str_get(&log), "did you mean 'tess_level'?"));
    dm_str_free(&log);
    dm_kv b[1] = {{"technique", "nromal"}};
    assert_int_equal(render_prepare(F.r, b, 1, &it, &log), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&log), "expected one of"));
    dm_str_free(&log);
}

/* Sum over the mip chain of size² texels × bytes per texel. */
static size_t chain_bytes(size_t size, size_t bpp)
{
    size_t t = 0;
    for (; size >= 1; size /= 2)
        t += size * size * bpp;
    return t;
}

static void test_item_info(void **state)
{
    (void)state;
    dm_kv kv[3] = {{"technique", "normal"}, {"mesh", "cylinder"}, {"texture_size", "64"}};
    render_item it;
    render_item_info info;
    assert_int_equal(render_prepare(F.r, kv, 3, &it, NULL), 0);
    assert_int_equal(render_get_info(F.r, it, &info), 0);
    assert_int_equal(info.mesh_triangles, 1508);
    assert_int_equal(info.mesh_vertices, 59 * 13 + 2 * 59);
    assert_int_equal(info.mesh_bytes, info.mesh_vertices * 48 + 1508 * 3 * 4);
    /* normal map RGB8 (3 bytes) + albedo RGBA8 (4 bytes); height not sampled. */
    assert_int_equal(info.texture_bytes, chain_bytes(64, 3) + chain_bytes(64, 4));
    render_release(F.r, it);
}

/* Second renderer on the same cache dir loads the binary from disk; a
 * corrupted file is recompiled, never trusted. */
static void test_disk_cache(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_tech_cacheXXXXXX";
    assert_non_null(mkdtemp(dir));
    dm_kv kv[2] = {{"technique", "normal"}, {"lighting", "cook-torrance"}};
    render_item it;
    render_item_info info;
    for (int round = 0; round < 3; round++) {
        render_ctx *r;
        assert_int_equal(render_create(&r), 0);
        int rc = render_set_cache_dir(r, dir);
        if (rc == DM_ERR_UNSUPPORTED) {      /* driver without binary formats */
            render_destroy(r);
            skip();
        }
        assert_int_equal(rc, 0);
        assert_int_equal(render_prepare(r, kv, 2, &it, NULL), 0);
        assert_int_equal(render_get_info(r, it, &info), 0);
        assert_int_equal(info.program_cached, round == 1 ? 2 : 0);
        assert_int_equal(render_draw(r, it, F.w, F.h), 0);
        assert_int_equal(glGetError(), GL_NO_ERROR);
        render_destroy(r);
        if (round == 1) {                    /* corrupt every cached file */
            char cmd[128];
            snprintf(cmd, sizeof cmd, "for f in %s/*.glbin; do printf garbage > $f; done", dir);
            assert_int_equal(system(cmd), 0);
        }
    }
    test_rm_rf(dir);
}

/* TextureBytes of a compressed map: 64² BC1 albedo, 8 bytes per 4×4 block,
 * levels 64..1 = 256+64+16+4+1+1+1 blocks. */
static void test_compressed_bytes(void **state)
{
    (void)state;
    dm_kv kv[3] = {{"technique", "texture"}, {"albedo_format", "bc1"}, {"texture_size", "64"}};
    render_item it;
    render_item_info info;
    assert_int_equal(render_prepare(F.r, kv, 3, &it, NULL), 0);
    assert_int_equal(render_get_info(F.r, it, &info), 0);
    assert_int_equal(info.texture_bytes, (256 + 64 + 16 + 4 + 1 + 1 + 1) * 8);
    render_release(F.r, it);
}

/* Every user-visible technique renders a non-trivial, finite image. */
static void test_every_technique(void **state)
{
    (void)state;
    const char *const *names = technique_names();
    for (size_t i = 0; names[i]; i++) {
        char spec[128];
        snprintf(spec, sizeof spec, "technique=%s mesh=plane", names[i]);
        float *px = render(spec);
        assert_int_equal(non_finite(px, npix()), 0);
        if (luma_stddev(px, npix()) <= 0.01)
            fail_msg("%s renders a flat image", names[i]);
        free(px);
    }
}

/* With height_scale 0 the parallax family must equal normal mapping at
 * height_scale 0 (normal maps follow height_scale: both are flat then). */
static void test_parallax_scale_zero(void **state)
{
    (void)state;
    static const char *const variants[] = {
        "technique=parallax", "technique=parallax offset_limit=on",
        "technique=steep-parallax", "technique=steep-parallax steps=auto",
        "technique=pom", "technique=pom shadow=raytrace", "technique=pom shadow=soft", NULL};
    float *ref = render("technique=normal mesh=plane height_scale=0");
    for (size_t i = 0; variants[i]; i++) {
        char spec[160];
        snprintf(spec, sizeof spec, "%s mesh=plane height_scale=0", variants[i]);
        float *px = render(spec);
        double p = psnr(ref, px, npix());
        if (!(p >= 60.0))
            fail_msg("%s: PSNR %.2f dB against normal", variants[i], p);
        free(px);
    }
    free(ref);
    /* The check can fail: a real depth changes the image. */
    float *a = render("technique=normal mesh=plane");
    float *b = render("technique=pom mesh=plane height_scale=0.1");
    assert_true(psnr(a, b, npix()) < 40.0);
    free(a);
    free(b);
}

/* No NaN/Inf at grazing (1°) and top-down (89°) views, for every technique. */
static void test_extreme_elevations(void **state)
{
    (void)state;
    static const char *const extra[] = {"", "shadow=raytrace", "shadow=soft", "offset_limit=on"};
    for (size_t i = 0; i < technique_count(); i++) {
        const technique_desc *t = technique_at(i);
        if (t->test_only)
            continue;
        for (int e = 0; e < 2; e++)
            for (size_t x = 0; x < 4; x++) {
                if (x && !technique_reads_axis(t, x == 3 ? "offset_limit" : "shadow"))
                    continue;
                char spec[200];
                snprintf(spec, sizeof spec, "technique=%s mesh=plane camera.elevation=%d %s",
                         t->name, e ? 89 : 1, extra[x]);
                float *px = render(spec);
                if (non_finite(px, npix()))
                    fail_msg("%s: %zu non-finite values", spec, non_finite(px, npix()));
                free(px);
            }
    }
}

/* Each lighting model and 8 lights render finite, distinct images. */
static void test_lighting_models(void **state)
{
    (void)state;
    static const char *const models[] = {"lambert", "phong", "blinn-phong", "cook-torrance"};
    float *img[4];
    for (int i = 0; i < 4; i++) {
        char spec[128];
        snprintf(spec, sizeof spec, "technique=normal mesh=sphere light_count=8 lighting=%s", models[i]);
        img[i] = render(spec);
        assert_int_equal(non_finite(img[i], npix()), 0);
        assert_true(luma_stddev(img[i], npix()) > 0.01);
    }
    for (int i = 0; i < 4; i++)
        for (int k = i + 1; k < 4; k++)
            if (psnr(img[i], img[k], npix()) > 60)
                fail_msg("%s and %s render the same image", models[i], models[k]);
    for (int i = 0; i < 4; i++)
        free(img[i]);
    float *one = render("technique=normal mesh=sphere light_count=1");
    float *eight = render("technique=normal mesh=sphere light_count=8");
    assert_true(psnr(one, eight, npix()) < 50);
    free(one);
    free(eight);
}

/* Axes that must change the image do: shadows, filters, Toksvig; and a
 * two-channel BC5 normal map stays close to RGB8. */
static void test_axes_take_effect(void **state)
{
    (void)state;
    static const char *const pairs[][2] = {
        {"technique=pom height_scale=0.15 camera.distance=1.2",
         "technique=pom height_scale=0.15 camera.distance=1.2 shadow=raytrace"},
        {"technique=pom height_scale=0.15 camera.distance=1.2",
         "technique=pom height_scale=0.15 camera.distance=1.2 shadow=soft"},
        {"technique=steep-parallax steps=4", "technique=steep-parallax steps=64"},
        {"technique=parallax", "technique=parallax offset_limit=on"},
        {"technique=texture camera.elevation=3", "technique=texture camera.elevation=3 filter=aniso16"},
        {"technique=texture filter=nearest", "technique=texture filter=trilinear"},
        {"technique=normal mesh=sphere camera.distance=10",
         "technique=normal mesh=sphere camera.distance=10 toksvig=on"},
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        char a[200], b[200];
        snprintf(a, sizeof a, "%s mesh=plane", pairs[i][0]);
        snprintf(b, sizeof b, "%s mesh=plane", pairs[i][1]);
        float *pa = render(a), *pb = render(b);
        double p = psnr(pa, pb, npix());
        if (getenv("DM_TEST_VERBOSE"))
            fprintf(stderr, "%s | %s: %.1f dB\n", a, b, p);
        if (!(p < 60.0))   /* the invariants call >= 60 dB "equal" */
            fail_msg("'%s' and '%s' render the same (%.1f dB)", a, b, p);
        free(pa);
        free(pb);
    }
    float *rgb = render("technique=normal mesh=plane");
    float *bc5 = render("technique=normal mesh=plane normal_format=bc5");
    double p = psnr(rgb, bc5, npix());
    if (!(p > 30.0 && p < INFINITY))
        fail_msg("bc5 vs rgb8 normal map: %.1f dB", p);
    free(rgb);
    free(bc5);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_normal_plane),
             cmocka_unit_test(test_fullscreen_coverage),
             cmocka_unit_test(test_program_cache),
             cmocka_unit_test(test_broken_shader),
             cmocka_unit_test(test_bad_params),
             cmocka_unit_test(test_item_info),
             cmocka_unit_test(test_disk_cache),
             cmocka_unit_test(test_compressed_bytes),
             cmocka_unit_test(test_every_technique),
             cmocka_unit_test(test_parallax_scale_zero),
             cmocka_unit_test(test_extreme_elevations),
             cmocka_unit_test(test_lighting_models),
             cmocka_unit_test(test_axes_take_effect))
