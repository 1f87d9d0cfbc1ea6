/* GL tests of the software virtual texture (techniques/vt.h) on llvmpipe:
 * at a size that also fits as a plain texture it converges to the plain
 * image, page misses reach 0 under a static camera, a cache smaller than
 * the working set degrades to coarser mips (never garbage), and a 65536²
 * texture runs without being materialised. */
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
#include "core/dm_image.h"
#include "core/dm_util.h"
#include "run/gl_context.h"
#include "tests/tech_spec.h"
#include "techniques/render.h"

enum { W = 192, H = 108 };
static gl_context *ctx;
static render_ctx *R;
static GLuint fbo, rb[2];

static int setup(void **state)
{
    (void)state;
    dm_str e = {0};
    int rc = gl_context_create(NULL, &ctx, &e);
    dm_str_free(&e);
    if (rc || render_create(&R))
        return -1;
    glCreateFramebuffers(1, &fbo);
    glCreateRenderbuffers(2, rb);
    glNamedRenderbufferStorage(rb[0], GL_RGBA32F, W, H);
    glNamedRenderbufferStorage(rb[1], GL_DEPTH_COMPONENT24, W, H);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
    render_destroy(R);
    gl_context_destroy(ctx);
    return 0;
}

/* Prepares "k=v ..." on R and asserts the return code (tech_spec.h). */
static render_item prepare(const char *spec, int want, dm_str *log) { return spec_prepare(R, spec, want, log); }

/* Draws one frame of it and reads it back into im (allocated by the caller). */
static void frame(render_item it, img *im)
{
    assert_int_equal(render_draw(R, it, W, H), 0);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, im->px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
}

/* PSNR over RGB (peak 1); -1 when any value is not finite. */
static double psnr(const img *a, const img *b)
{
    double s = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        if (!isfinite(a->px[i]) || !isfinite(b->px[i]))
            return -1;
        if (i % 4 != 3)
            s += (a->px[i] - b->px[i]) * (a->px[i] - b->px[i]);
    }
    return s == 0 ? 99 : 10 * log10(1.0 / (s / (W * H * 3.0)));
}

/* Draws frames until a frame has no page miss (at most max); returns the
 * number of frames drawn, the stats and the last image. */
static int converge(render_item it, int max, img *im, render_vt_stats *st)
{
    uint64_t before = 0;
    for (int f = 1; f <= max; f++) {
        frame(it, im);
        assert_int_equal(render_get_vt_stats(R, it, st), 0);
        if (f > 1 && st->page_misses == before)
            return f;
        before = st->page_misses;
    }
    return max + 1;
}

#define SCENE "mesh=plane texture_size=512 camera.distance=1.3 camera.elevation=40 resolution=192x108"

/* Largest difference of any channel of any pixel. */
static double max_error(const img *a, const img *b)
{
    double m = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        m = fmax(m, fabs(a->px[i] - b->px[i]));
    return m;
}

/* software = off after convergence, misses reach 0, the stats add up
 * (uploads are whole pages of 36² texels × 12 bytes).  PSNR >= 40 for
 * texture and normal; >= 30 for pom, whose ray-height comparisons turn the
 * sub-LSB difference between the shader's trilinear blend and the
 * sampler's into a few moved silhouette pixels; >= 35 for tess-displacement
 * (measured 39.9), whose evaluation stage reads its heights through the
 * page table at the finest resident level.  No seams: no pixel of the
 * texture image differs by more than 0.05 (a seam at a page border would
 * show the border texels of a wrong page). */
static void test_converges_to_plain(void **state)
{
    (void)state;
    static const char *const techs[] = {"texture", "normal", "pom", "tess-displacement tess_level=4"};
    static const double floor_db[] = {40, 40, 30, 35};
    for (int k = 0; k < 4; k++) {
        char off[256], soft[320];
        snprintf(off, sizeof off, "technique=%s maps=bricks " SCENE, techs[k]);
        snprintf(soft, sizeof soft, "%s virtual_texture=software vt_page_size=32 vt_cache_pages=256", off);
        img a, b;
        assert_int_equal(img_alloc(&a, W, H), 0);
        assert_int_equal(img_alloc(&b, W, H), 0);
        render_item io = prepare(off, 0, NULL), is = prepare(soft, 0, NULL);
        render_vt_stats st;
        assert_int_equal(render_get_vt_stats(R, io, &st), DM_ERR_UNAVAILABLE);
        frame(io, &a);
        int frames = converge(is, 40, &b, &st);
        double p = psnr(&a, &b);
        printf("%s: converged after %d frames, PSNR %.2f dB, %llu pages resident, %llu misses, "
               "%llu bytes uploaded\n", techs[k], frames, p, (unsigned long long)st.pages_resident,
               (unsigned long long)st.page_misses, (unsigned long long)st.upload_bytes);
        printf("%s: max error %.4f\n", techs[k], max_error(&a, &b));
        assert_true(frames <= 40);
        assert_true(p >= floor_db[k]);
        if (k == 0)
            assert_true(max_error(&a, &b) < 0.05);
        assert_int_equal(st.upload_bytes % (36 * 36 * 12), 0);
        assert_true(st.upload_bytes / (36 * 36 * 12) >= st.pages_resident);
        assert_true(st.feedback_ns > 0);
        render_release(R, io);
        render_release(R, is);
        img_free(&a);
        img_free(&b);
    }
}

/* A cache of 6 pages for a working set of dozens: the image stays finite
 * and close to the plain one at a coarser level (PSNR above a floor), the
 * cache stays full and the misses never stop. */
static void test_small_cache_degrades(void **state)
{
    (void)state;
    img a, b;
    assert_int_equal(img_alloc(&a, W, H), 0);
    assert_int_equal(img_alloc(&b, W, H), 0);
    render_item io = prepare("technique=texture maps=bricks " SCENE, 0, NULL);
    render_item is = prepare("technique=texture maps=bricks " SCENE
                           " virtual_texture=software vt_page_size=32 vt_cache_pages=6", 0, NULL);
    frame(io, &a);
    render_vt_stats st;
    int frames = converge(is, 12, &b, &st);
    double p = psnr(&a, &b);
    printf("cache of 6: PSNR %.2f dB after %d frames, %llu misses\n", p, frames,
           (unsigned long long)st.page_misses);
    assert_int_equal(frames, 13);   /* never converges */
    assert_int_equal(st.pages_resident, 6);
    assert_true(p > 18 && p < 40);
    render_release(R, io);
    render_release(R, is);
    img_free(&a);
    img_free(&b);
}

/* A 65536² terrain: pages on demand, texture memory of the cache and table
 * only (not the 17 GiB of a plain RGBA8 chain), finite image. */
static void test_huge(void **state)
{
    (void)state;
    img b;
    assert_int_equal(img_alloc(&b, W, H), 0);
    render_item is = prepare("technique=normal maps=terrain mesh=plane texture_size=65536 camera.distance=1.0 "
                           "camera.elevation=60 virtual_texture=software vt_page_size=128 vt_cache_pages=64",
                           0, NULL);
    render_item_info info;
    assert_int_equal(render_get_info(R, is, &info), 0);
    /* 8×8 slots of 132² texels × 12 bytes + RG16UI table levels 512² .. 1² */
    size_t want = (size_t)(8 * 132) * (8 * 132) * 12;
    for (size_t n = 512; n >= 1; n /= 2)
        want += n * n * 4;
    assert_int_equal(info.texture_bytes, want);
    render_vt_stats st;
    for (int f = 0; f < 4; f++)
        frame(is, &b);
    assert_int_equal(render_get_vt_stats(R, is, &st), 0);
    assert_true(psnr(&b, &b) == 99);   /* every value finite */
    assert_int_equal(st.frames, 4);
    assert_true(st.pages_resident > 1 && st.pages_resident <= 64);
    render_release(R, is);
    img_free(&b);
}

/* What the software virtual texture does not cover is refused with a reason. */
static void test_refusals(void **state)
{
    (void)state;
    dm_str log = {0};
    prepare("technique=normal normal_format=bc5 virtual_texture=software", DM_ERR_UNSUPPORTED, &log);
    assert_non_null(strstr(dm_str_get(&log), "virtual_texture=software stores pages as r32f height"));
    dm_str_free(&log);
    prepare("technique=vertex-displacement virtual_texture=software", DM_ERR_UNSUPPORTED, &log);
    assert_non_null(strstr(dm_str_get(&log), "covers the fragment-stage and tessellated techniques only, "
                                             "not 'vertex-displacement'"));
    dm_str_free(&log);
    prepare("technique=texture texture_size=1000 virtual_texture=software", DM_ERR_RANGE, &log);
    assert_non_null(strstr(dm_str_get(&log), "must be powers of two"));
    dm_str_free(&log);
    prepare("technique=texture texture_size=32768", DM_ERR_RANGE, &log);
    assert_non_null(strstr(dm_str_get(&log), "larger maps need virtual_texture=software"));
    dm_str_free(&log);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_converges_to_plain),
             cmocka_unit_test(test_small_cache_degrades),
             cmocka_unit_test(test_huge),
             cmocka_unit_test(test_refusals))
