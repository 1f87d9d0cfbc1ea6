/* GL tests of the renderer's material maps on llvmpipe: format round trips
 * (read back from the driver's textures), TextureBytes from GL, the
 * normal-map mip chain, filters on a grazing checker, and the
 * virtual-texture values this driver leaves out. */
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
#include "techniques/maps.h"
#include "techniques/render.h"
#include "techniques/render_internal.h"
#include "tests/tech_spec.h"   /* white-box: the item's texture names */

static gl_context *ctx;
static render_ctx *R;

static int setup(void **state)
{
    (void)state;
    dm_str e = {0};
    int rc = gl_context_create(NULL, &ctx, &e);
    dm_str_free(&e);
    return rc || render_create(&R) ? -1 : 0;
}

static int teardown(void **state)
{
    (void)state;
    render_destroy(R);
    gl_context_destroy(ctx);
    return 0;
}

/* Prepares "k=v ..." on R and asserts the return code (tech_spec.h). */
static render_item prepare(const char *spec, int want, dm_str *log) { return spec_prepare(R, spec, want, log); }

/* Level-0 texels of map `which` (0 height, 1 normal, 2 albedo) as RGBA floats. */
static float *read_map(render_item it, int which, int size)
{
    GLuint tex = R->maps[R->items[it.id - 1].maps].tex[which];
    size_t n = (size_t)size * (size_t)size * 4;
    float *px = dm_xmalloc(n * sizeof(float));
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof(float)), px);
    assert_int_equal(glGetError(), GL_NO_ERROR);
    return px;
}

/* Mean angle in degrees between the stored normals of format fmt and the
 * exact float normals of the terrain set. */
static double normal_error(const char *fmt, const float *ref, int size)
{
    char spec[160];
    snprintf(spec, sizeof spec, "technique=normal maps=terrain texture_size=%d normal_format=%s", size, fmt);
    render_item it = prepare(spec, 0, NULL);
    float *px = read_map(it, 1, size);
    int two = strcmp(fmt, "rg8") == 0 || strcmp(fmt, "bc5") == 0, xa = strcmp(fmt, "bc3nm") == 0;
    double sum = 0;
    for (size_t i = 0; i < (size_t)size * (size_t)size; i++) {
        const float *p = &px[4 * i];
        double x = (xa ? p[3] : p[0]) * 2 - 1, y = p[1] * 2 - 1, z = p[2] * 2 - 1;
        if (two || xa)
            z = sqrt(fmax(0, 1 - x * x - y * y));
        double l = sqrt(x * x + y * y + z * z);
        double c = (x * ref[3 * i] + y * ref[3 * i + 1] + z * ref[3 * i + 2]) / l;
        sum += acos(fmin(1, c)) * 180 / 3.14159265358979323846;
    }
    free(px);
    render_release(R, it);
    return sum / ((double)size * size);
}

/* Normal formats, as S1 reports: two channels (rg8) lose little against
 * rgb8, rgba16f is near exact, BC5 (3Dc) and DXT5 with x in alpha beat BC1. */
static void test_normal_formats(void **state)
{
    (void)state;
    enum { S = 256 };
    maps_set m;
    maps_desc d = {.name = "terrain", .size = S};
    assert_int_equal(maps_generate(&d, &m), 0);
    double rgb8 = normal_error("rgb8", m.normal, S), rg8 = normal_error("rg8", m.normal, S);
    double f16 = normal_error("rgba16f", m.normal, S), bc1 = normal_error("bc1", m.normal, S);
    double bc3nm = normal_error("bc3nm", m.normal, S), bc5 = normal_error("bc5", m.normal, S);
    printf("mean angular error (deg): rgb8 %.4f rg8 %.4f rgba16f %.4f bc1 %.4f bc3nm %.4f bc5 %.4f\n",
           rgb8, rg8, f16, bc1, bc3nm, bc5);
    assert_true(rgb8 < 0.5);
    assert_true(rg8 < rgb8 + 0.25);   /* stated bound: within 0.25° of rgb8 */
    assert_true(f16 < 0.05);
    assert_true(bc5 < bc1);
    assert_true(bc3nm < bc1);
    maps_free(&m);
}

/* Height formats on the sine set: float formats exact, r16 within half a
 * step of 1/65535, r8 within half a step of 1/255, r16f within 2^-12. */
static void test_height_formats(void **state)
{
    (void)state;
    enum { S = 128 };
    static const struct { const char *fmt; double tol; } cases[] = {
        {"r32f", 0}, {"rgba32f", 0}, {"r16", 0.5 / 65535 + 1e-7}, {"r8", 0.5 / 255 + 1e-7},
        {"rgba8", 0.5 / 255 + 1e-7}, {"r16f", 1.0 / 4096},
    };
    maps_set m;
    maps_desc d = {.name = "sine", .size = S};
    assert_int_equal(maps_generate(&d, &m), 0);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char spec[128];
        snprintf(spec, sizeof spec, "technique=bump maps=sine texture_size=%d height_format=%s", S, cases[k].fmt);
        render_item it = prepare(spec, 0, NULL);
        float *px = read_map(it, 0, S);
        double worst = 0;
        for (size_t i = 0; i < S * S; i++)
            worst = fmax(worst, fabs((double)px[4 * i] - m.height[i]));
        printf("height %s: max error %.3g\n", cases[k].fmt, worst);
        assert_true(worst <= cases[k].tol);
        free(px);
        render_release(R, it);
    }
    maps_free(&m);
}

/* TextureBytes is what GL reports: a BC1 albedo chain is ceil(s/4)²·8 bytes
 * per level; an RGBA8 chain 4 bytes per texel. */
static void test_texture_bytes(void **state)
{
    (void)state;
    size_t bc1 = 0, rgba8 = 0;
    for (int s = 256; s >= 1; s /= 2) {
        bc1 += (size_t)((s + 3) / 4) * (size_t)((s + 3) / 4) * 8;
        rgba8 += (size_t)s * (size_t)s * 4;
    }
    render_item_info info;
    render_item a = prepare("technique=texture maps=checker texture_size=256 albedo_format=bc1", 0, NULL);
    assert_int_equal(render_get_info(R, a, &info), 0);
    assert_int_equal(info.texture_bytes, bc1);
    render_item b = prepare("technique=texture maps=checker texture_size=256 albedo_format=rgba8", 0, NULL);
    assert_int_equal(render_get_info(R, b, &info), 0);
    assert_int_equal(info.texture_bytes, rgba8);
    render_release(R, a);
    render_release(R, b);
}

/* The normal mip chain is the unnormalised mean: level 1 of the stored map
 * (rgba16f) equals the 2×2 mean of the encoded level-0 normals, so its
 * vectors are shorter than 1 where the normals differ (what Toksvig reads). */
static void test_normal_mips(void **state)
{
    (void)state;
    enum { S = 64 };
    render_item it = prepare("technique=normal maps=stones texture_size=64 normal_format=rgba16f", 0, NULL);
    GLuint tex = R->maps[R->items[it.id - 1].maps].tex[1];
    float *l0 = read_map(it, 1, S), *l1 = dm_xmalloc(32 * 32 * 4 * sizeof(float));
    glGetTextureImage(tex, 1, GL_RGBA, GL_FLOAT, 32 * 32 * 4 * sizeof(float), l1);
    double shortest = 1;
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) {
            double len2 = 0;
            for (int c = 0; c < 3; c++) {
                double mean = 0;
                for (int j = 0; j < 4; j++)
                    mean += 0.25 * l0[4 * ((2 * y + j / 2) * S + 2 * x + j % 2) + c];
                assert_float_equal(l1[4 * (y * 32 + x) + c], mean, 2e-3);
                len2 += (mean * 2 - 1) * (mean * 2 - 1);
            }
            shortest = fmin(shortest, sqrt(len2));
        }
    assert_true(shortest < 0.97);
    free(l0);
    free(l1);
    render_release(R, it);
}

/* Renders spec at w×h into a float target; returns the image. */
static img render(const char *spec, int w, int h)
{
    GLuint fbo, rb[2];
    glCreateFramebuffers(1, &fbo);
    glCreateRenderbuffers(2, rb);
    glNamedRenderbufferStorage(rb[0], GL_RGBA32F, w, h);
    glNamedRenderbufferStorage(rb[1], GL_DEPTH_COMPONENT24, w, h);
    glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    render_item it = prepare(spec, 0, NULL);
    assert_int_equal(render_draw(R, it, w, h), 0);
    img im;
    assert_int_equal(img_alloc(&im, w, h), 0);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, im.px);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
    render_release(R, it);
    return im;
}

static double rmse(const img *a, const img *b)
{
    double s = 0;
    for (size_t i = 0; i < (size_t)a->w * (size_t)a->h * 4; i++)
        s += (i % 4 == 3) ? 0 : (a->px[i] - b->px[i]) * (a->px[i] - b->px[i]);
    return sqrt(s / ((double)a->w * a->h * 3));
}

/* On a grazing checker: aniso16 is closer to a 4× supersampled reference
 * (the same configuration at 4× resolution, box-filtered) than trilinear,
 * which is closer than bilinear. */
static void test_filters(void **state)
{
    (void)state;
    static const char *const filters[] = {"bilinear", "trilinear", "aniso16"};
    const char *base = "technique=texture mesh=plane maps=checker texture_size=512 "
                       "camera.distance=2.2 camera.elevation=9 camera.azimuth=0";
    double err[3];
    for (int k = 0; k < 3; k++) {
        char spec[256];
        snprintf(spec, sizeof spec, "%s filter=%s", base, filters[k]);
        img lo = render(spec, 160, 90), hi = render(spec, 640, 360), ref;
        assert_int_equal(img_downsample(&hi, 4, &ref), 0);
        err[k] = rmse(&lo, &ref);
        img_free(&lo);
        img_free(&hi);
        img_free(&ref);
    }
    printf("RMSE vs 4x reference: bilinear %.4f trilinear %.4f aniso16 %.4f\n", err[0], err[1], err[2]);
    assert_true(err[2] < err[1]);
    assert_true(err[1] < err[0]);
}

/* anisoN above the driver's maximum is clamped and the prepare log says so;
 * sparse virtual texturing is refused where the driver lacks
 * GL_ARB_sparse_texture, with the extension named (where it has it, the
 * configuration is prepared: tests/e2e/drivers.sh measures it on zink). */
static void test_clamp_and_sparse(void **state)
{
    (void)state;
    dm_str log = {0};
    float saved = R->max_aniso;
    R->max_aniso = 4;   /* pretend a driver with a lower maximum */
    render_item it = prepare("technique=texture filter=aniso16 texture_size=64", 0, &log);
    R->max_aniso = saved;
    assert_non_null(strstr(dm_str_get(&log), "filter aniso16 clamped to anisotropy 4"));
    render_release(R, it);
    dm_str_free(&log);
    if (epoxy_has_gl_extension("GL_ARB_sparse_texture"))
        return;
    prepare("technique=texture virtual_texture=sparse texture_size=64", DM_ERR_UNSUPPORTED, &log);
    const char *why = "the driver lacks GL_ARB_sparse_texture, which virtual_texture=sparse needs";
    if (!strstr(dm_str_get(&log), why))
        fail_msg("log '%s' lacks '%s'", dm_str_get(&log), why);
    dm_str_free(&log);
}

DM_TEST_MAIN(setup, teardown,
             cmocka_unit_test(test_normal_formats),
             cmocka_unit_test(test_height_formats),
             cmocka_unit_test(test_texture_bytes),
             cmocka_unit_test(test_normal_mips),
             cmocka_unit_test(test_filters),
             cmocka_unit_test(test_clamp_and_sparse))
