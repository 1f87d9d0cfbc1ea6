/* test_reports_image.c — the OpenImageIO bridge (imaging/image.h). */
#include "imaging/image.h"
#include "core/dm_error.h"
#include "imaging/quality.h"
#include "imaging/flip.h"

#include <math.h>
#include <signal.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>
#include <cmocka.h>
#include "test_util.h"

static void test_downsample_block_means(void **state)
{
    (void)state;
    img src = {0}, dst = {0};
    assert_int_equal(img_alloc(&src, 4, 4), 0);
    for (int i = 0; i < 4 * 4 * 4; i++)
        src.px[i] = (float)((i * 7919) % 101) / 16.0f;   /* arbitrary, exact in binary */
    assert_int_equal(img_downsample(&src, 2, &dst), 0);
    assert_int_equal(dst.w, 2);
    assert_int_equal(dst.h, 2);
    for (int by = 0; by < 2; by++)
        for (int bx = 0; bx < 2; bx++)
            for (int c = 0; c < 4; c++) {
                float s = 0;
                for (int j = 0; j < 2; j++)
                    for (int i = 0; i < 2; i++)
                        s += src.px[((by * 2 + j) * 4 + bx * 2 + i) * 4 + c];
                assert_true(dst.px[(by * 2 + bx) * 4 + c] == s / 4.0f);
            }
    img bad = {0};
    assert_int_equal(img_downsample(&src, 3, &bad), DM_ERR_ARG);   /* 4 not divisible by 3 */
    img_free(&src);
    img_free(&dst);
}

static void test_compare_identical_and_offset(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    img_metrics m;
    assert_int_equal(img_alloc(&a, 16, 8), 0);
    assert_int_equal(img_alloc(&b, 16, 8), 0);
    test_img_fill(&a, 0.5f, 0.25f, 0.125f, 1.0f);
    test_img_fill(&b, 0.5f, 0.25f, 0.125f, 1.0f);
    assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
    assert_true(m.rmse == 0.0);
    assert_true(isinf(m.psnr) && m.psnr > 0);
    assert_true(m.max_error == 0.0);
    assert_true(m.pct_over == 0.0);
    assert_int_equal(m.nonfinite, 0);

    /* +0.1 on every RGB channel: RMSE is the offset, PSNR = 20 log10(1/offset) = 20 dB
     * (up to the float rounding of the stored values, computed here exactly). */
    test_img_fill(&b, 0.6f, 0.35f, 0.225f, 1.0f);
    double d = (double)(0.6f - 0.5f);
    assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
    assert_float_equal(m.rmse, 0.1, 1e-6);
    assert_float_equal(m.rmse, d, 1e-7);
    assert_float_equal(m.psnr, 20.0, 1e-5);
    assert_float_equal(m.max_error, d, 1e-6);
    assert_true(m.pct_over == 100.0);
    assert_int_equal(img_compare(&a, &b, 0.2, &m), 0);   /* 0.1 is under a 0.2 threshold */
    assert_true(m.pct_over == 0.0);
    /* half the pixels get a NaN in green */
    for (int i = 0; i < 16 * 4; i++)
        b.px[i * 4 + 1] = NAN;
    assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
    assert_int_equal(m.nonfinite, 64);
    img c = {0};
    assert_int_equal(img_alloc(&c, 8, 8), 0);
    assert_int_equal(img_compare(&a, &c, 0.05, &m), DM_ERR_ARG);
    img_free(&a);
    img_free(&b);
    img_free(&c);
}

static void test_save_load_png_exr(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_img_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char png[256], exr[256], err[512];
    snprintf(png, sizeof png, "%s/a.png", dir);
    snprintf(exr, sizeof exr, "%s/a.exr", dir);
    img a = {0}, l = {0};
    assert_int_equal(img_alloc(&a, 5, 3), 0);
    test_img_fill(&a, 2.0f, 0.5f, -1.0f, 1.0f);
    a.px[0] = 0.123456789f;
    assert_int_equal(img_save(&a, png, err, sizeof err), 0);
    assert_int_equal(img_load(png, &l, err, sizeof err), 0);
    assert_int_equal(l.w, 5);
    assert_int_equal(l.h, 3);
    assert_float_equal(l.px[4], 1.0, 0);        /* clamped */
    assert_float_equal(l.px[5], 128.0 / 255.0, 1e-6); /* 0.5 → 128 */
    assert_float_equal(l.px[6], 0.0, 0);        /* clamped */
    img_free(&l);
    assert_int_equal(img_save(&a, exr, err, sizeof err), 0);
    assert_int_equal(img_load(exr, &l, err, sizeof err), 0);
    assert_true(memcmp(l.px, a.px, 5 * 3 * 4 * sizeof(float)) == 0);
    img_free(&l);
    assert_int_equal(img_save(&a, "/nonexistent-dir/x.png", err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent-dir/x.png"));
    assert_int_equal(img_load("/nonexistent-dir/y.exr", &l, err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent-dir/y.exr"));
    unlink(png);
    unlink(exr);
    rmdir(dir);
    img_free(&a);
}

static void test_heatmap_inferno(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_hm_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256], err[512];
    snprintf(path, sizeof path, "%s/h.png", dir);
    img a = {0}, b = {0}, h = {0};
    assert_int_equal(img_alloc(&a, 4, 1), 0);
    assert_int_equal(img_alloc(&b, 4, 1), 0);
    test_img_fill(&a, 0, 0, 0, 1);
    test_img_fill(&b, 0, 0, 0, 1);
    b.px[1 * 4 + 2] = 0.5f;   /* pixel 1: half of the scale */
    b.px[2 * 4 + 0] = 1.0f;   /* pixel 2: full scale */
    b.px[3 * 4 + 1] = 3.0f;   /* pixel 3: beyond the scale, clamps */
    assert_int_equal(img_heatmap(&a, &b, 1.0, path, err, sizeof err), 0);
    assert_int_equal(img_load(path, &h, err, sizeof err), 0);
    /* inferno: 0 is near-black, 1 is pale yellow; both ends and monotone luminance */
    const float *p0 = h.px, *p1 = h.px + 4, *p2 = h.px + 8, *p3 = h.px + 12;
    assert_true(p0[0] < 0.05f && p0[1] < 0.05f && p0[2] < 0.1f);
    assert_true(p2[0] > 0.9f && p2[1] > 0.9f && p2[2] < 0.75f);
    assert_true(p1[0] + p1[1] > p0[0] + p0[1] && p1[0] + p1[1] < p2[0] + p2[1]);
    assert_memory_equal(p2, p3, 3 * sizeof(float));
    unlink(path);
    rmdir(dir);
    img_free(&a);
    img_free(&b);
    img_free(&h);
}

/* The report's heatmap is the FLIP map on FLIP's fixed scale: a difference
 * of 0.05 in one channel of a flat grey shows as a visible colour.  On a
 * flat image the contrast-sensitivity filters (normalised) leave the
 * colours as they are and the feature detectors see nothing, so the error
 * is the colour pipeline's alone, computed here from the stages: linear ->
 * Hunt L*a*b* -> HyAB -> colour error.  The pixel of the saved PNG is that
 * error's colour on the ramp (8 bits), and that colour is over the
 * visibility floor: its brightest channel at least 10 % of the range,
 * where the old |render − reference| map on its 0..1 scale (inferno at
 * 0.05) was under 4 %. */
static void test_heatmap_flip_small_difference(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_fh_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256], err[512];
    snprintf(path, sizeof path, "%s/f.png", dir);
    img a = {0}, b = {0}, h = {0};
    assert_int_equal(img_alloc(&a, 32, 32), 0);
    assert_int_equal(img_alloc(&b, 32, 32), 0);
    test_img_fill(&a, 0.5f, 0.5f, 0.5f, 1);
    test_img_fill(&b, 0.55f, 0.5f, 0.5f, 1);
    double la[3], lb[3], ra[3], rb[3];
    for (int i = 0; i < 3; i++) {
        ra[i] = flip_srgb_to_linear(a.px[i]);
        rb[i] = flip_srgb_to_linear(b.px[i]);
    }
    flip_linear_to_hunt_lab(ra, la);
    flip_linear_to_hunt_lab(rb, lb);
    double want = flip_color_error(flip_hyab(la, lb));
    float *map = malloc(32 * 32 * sizeof *map);
    flip_desc d = flip_defaults(NULL);
    assert_int_equal(flip_map(&a, &b, &d, map), 0);
    assert_float_equal(map[16 * 32 + 16], want, 1e-3);
    assert_int_equal(flip_map_save(map, 32, 32, path, err, sizeof err), 0);
    assert_int_equal(img_load(path, &h, err, sizeof err), 0);
    float rgb[3];
    flip_colormap(want, rgb);
    const float *px = h.px + 4 * (16 * 32 + 16);
    float bright = 0;
    for (int i = 0; i < 3; i++) {
        assert_float_equal(px[i], rgb[i], 1.5 / 255);
        bright = px[i] > bright ? px[i] : bright;
    }
    print_message("0.05 in red on grey 0.5: FLIP %.4f, map pixel %.3f %.3f %.3f\n", want, px[0], px[1],
                  px[2]);
    assert_true(bright >= 0.10f);
    img_free(&h);
    assert_int_equal(img_heatmap(&a, &b, 1.0, path, err, sizeof err), 0);
    assert_int_equal(img_load(path, &h, err, sizeof err), 0);
    px = h.px + 4 * (16 * 32 + 16);
    assert_true(px[0] < 0.04f && px[1] < 0.04f && px[2] < 0.04f);
    free(map);
    unlink(path);
    rmdir(dir);
    img_free(&a);
    img_free(&b);
    img_free(&h);
}

/* The same pixels in two channel layouts (tests/data/images, written by
 * oiiotool): grey+alpha and RGBA, 8 and 16 bits; grey, RGB and opaque RGBA.
 * Each pair loads to the same RGBA floats, so RMSE and the silhouette error
 * are exactly 0 (grey+alpha was once read as (Y, A, Y, 1)). */
static void test_load_channel_layouts(void **state)
{
    (void)state;
    static const char *pairs[][2] = {
        { "grey-alpha.png", "rgba.png" }, { "grey-alpha16.png", "rgba16.png" },
        { "grey.png", "rgb.png" }, { "rgb.png", "rgba-opaque.png" }, { "grey.png", "rgba-opaque.png" },
    };
    const char *src = getenv("DMBENCH_SOURCE_DIR");
    assert_non_null(src);
    for (size_t i = 0; i < sizeof pairs / sizeof *pairs; i++) {
        img a = {0}, b = {0};
        char err[512];
        char *pa = dm_xasprintf("%s/tests/data/images/%s", src, pairs[i][0]);
        char *pb = dm_xasprintf("%s/tests/data/images/%s", src, pairs[i][1]);
        assert_int_equal(img_load(pa, &a, err, sizeof err), 0);
        assert_int_equal(img_load(pb, &b, err, sizeof err), 0);
        assert_int_equal(a.w, 4);
        assert_int_equal(b.h, 4);
        assert_memory_equal(a.px, b.px, 4 * 4 * 4 * sizeof(float));
        img_metrics m;
        assert_int_equal(img_compare(&a, &b, 0.05, &m), 0);
        assert_true(m.rmse == 0.0);
        unsigned char ma[16], mb[16];
        quality_coverage(&a, ma);
        quality_coverage(&b, mb);
        assert_true(quality_silhouette_error(ma, mb, 16) == 0.0);
        if (i < 2) {   /* grey+alpha: alpha 0 on half the pixels, 0.6 on the others */
            assert_true(a.px[3] == 0.0f);
            assert_float_equal(a.px[2 * 4 + 3], 0.6, 0.002);
            assert_true(a.px[2 * 4 + 0] == a.px[2 * 4 + 1] && a.px[2 * 4 + 1] == a.px[2 * 4 + 2]);
        }
        img_free(&a);
        img_free(&b);
        free(pa);
        free(pb);
    }
}

/* What img_load refuses, at once and without reading: a device, a
 * symlink to /dev/zero (DM_ERR_ARG), a header claiming more than
 * IMG_MAX_PIXELS (DM_ERR_IO, before any allocation). */
static void test_load_refused(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_img_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *ln = dm_xasprintf("%s/zero.png", dir), *huge = dm_xasprintf("%s/huge.png", dir);
    assert_int_equal(symlink("/dev/zero", ln), 0);
    img l = {0};
    assert_int_equal(img_load("/dev/zero", &l, err, sizeof err), DM_ERR_ARG);
    assert_non_null(strstr(err, "not a regular file"));
    assert_int_equal(img_load(ln, &l, err, sizeof err), DM_ERR_ARG);
    /* a PNG of 20000 x 20000 grey pixels with an empty IDAT */
    static const unsigned char hdr[] = {
        0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
        0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20, 8, 0, 0, 0, 0, 0xc6, 0x1b, 0x19, 0xe5,
        0, 0, 0, 0, 'I', 'D', 'A', 'T', 0x35, 0xaf, 0x06, 0x1e,
        0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82 };
    assert_int_equal(dm_write_file(huge, hdr, sizeof hdr), 0);
    assert_int_equal(img_load(huge, &l, err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "20000x20000"));
    assert_null(l.px);
    unlink(ln);
    unlink(huge);
    rmdir(dir);
    free(ln);
    free(huge);
}

/* img_save past a file-size limit (ulimit -f, SIGXFSZ ignored as dmbench
 * does): DM_ERR_DISK naming the path and why, the old file kept and no
 * temp file left; to a directory that does not exist: DM_ERR_IO with the
 * reason, never an empty one. */
static void test_save_disk_refused(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_img_XXXXXX", err[512] = "";
    assert_non_null(mkdtemp(dir));
    char *path = dm_xasprintf("%s/m.exr", dir);
    img a = {0};
    assert_int_equal(img_alloc(&a, 64, 64), 0);
    for (size_t i = 0; i < 64 * 64 * 4; i++)   /* noise: it does not compress below 4 KB */
        a.px[i] = (float)((i * 2654435761u) % 1000003u) / 1000003.0f;
    assert_int_equal(dm_write_file(path, "old", 3), 0);
    struct rlimit old, lim;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
    lim = old;
    lim.rlim_cur = 4096;   /* the EXR holds 64 KB of floats */
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    int rc = img_save(&a, path, err, sizeof err);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
    signal(SIGXFSZ, prev);
    assert_int_equal(rc, DM_ERR_DISK);
    assert_non_null(strstr(err, "File too large"));
    char *text = test_slurp(path);
    assert_string_equal(text, "old");
    free(text);
    char *cmd = dm_xasprintf("test $(ls -A '%s' | wc -l) = 1", dir);
    assert_int_equal(system(cmd), 0);   /* m.exr only: no temp file */
    free(cmd);
    assert_int_equal(img_save(&a, "/nonexistent-dir/m.png", err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "/nonexistent-dir/m.png: No such file or directory"));
    test_rm_rf(dir);
    img_free(&a);
    free(path);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_load_channel_layouts),
             cmocka_unit_test(test_load_refused),
             cmocka_unit_test(test_save_disk_refused),
             cmocka_unit_test(test_downsample_block_means),
             cmocka_unit_test(test_compare_identical_and_offset),
             cmocka_unit_test(test_save_load_png_exr),
             cmocka_unit_test(test_heatmap_inferno),
             cmocka_unit_test(test_heatmap_flip_small_difference))
