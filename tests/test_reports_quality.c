/* test_reports_quality.c — SSIM, silhouette, depth, non-finite, crack metrics. */
#include "imaging/quality.h"
#include "core/dm_error.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

static void test_ssim_identical_is_one(void **state)
{
    (void)state;
    img a = {0};
    assert_int_equal(img_alloc(&a, 23, 17), 0);
    for (int i = 0; i < 23 * 17 * 4; i++)
        a.px[i] = (float)((i * 37) % 97) / 97.0f;
    double s = 0;
    assert_int_equal(quality_ssim(&a, &a, &s), 0);
    assert_true(s == 1.0);
    img_free(&a);
}

/* Constant image of luma c against itself + 0.1 on R, G and B.  The luma
 * weights sum to 1, so the second image has constant luma c + 0.1.  Inside
 * every window both variances and the covariance are 0, so the contrast-
 * structure term is (0 + C2)/(0 + C2) = 1 and SSIM is the luminance term:
 *     SSIM = (2 c (c + 0.1) + C1) / (c² + (c + 0.1)² + C1),  C1 = (0.01·1)².
 * With c = 0.5: (0.6 + 1e-4) / (0.25 + 0.36 + 1e-4) = 0.6001 / 0.6101. */
static void test_ssim_constant_offset_closed_form(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    assert_int_equal(img_alloc(&a, 16, 16), 0);
    assert_int_equal(img_alloc(&b, 16, 16), 0);
    test_img_fill(&a, 0.5f, 0.5f, 0.5f, 1.0f);
    test_img_fill(&b, 0.6f, 0.6f, 0.6f, 1.0f);
    double s = 0;
    assert_int_equal(quality_ssim(&a, &b, &s), 0);
    double ya = 0.5, yb = (double)0.6f;   /* luma of the stored floats */
    double expect = (2 * ya * yb + 1e-4) / (ya * ya + yb * yb + 1e-4);
    assert_float_equal(s, expect, 1e-9);
    assert_float_equal(s, 0.6001 / 0.6101, 1e-7);
    img_free(&a);
    img_free(&b);
}

/* Images smaller than the 11×11 window (quality.h): identical images give
 * exactly 1 at every size, the constant-offset closed form above holds with
 * the shrunken window too (any normalised weights give zero variances), a
 * tiny image with different structure scores below 1, and an empty image or
 * a size mismatch is refused. */
static void test_ssim_tiny_images(void **state)
{
    (void)state;
    static const int sizes[][2] = {{1, 1}, {2, 3}, {4, 4}, {10, 16}, {16, 10}, {11, 11}, {12, 5}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        img a = {0}, b = {0};
        int w = sizes[k][0], h = sizes[k][1];
        assert_int_equal(img_alloc(&a, w, h), 0);
        assert_int_equal(img_alloc(&b, w, h), 0);
        for (int i = 0; i < w * h * 4; i++)
            a.px[i] = (float)((i * 37) % 97) / 97.0f;
        double s = 0;
        assert_int_equal(quality_ssim(&a, &a, &s), 0);
        if (s != 1.0)
            fail_msg("%dx%d: SSIM of identical images %.17g, expected exactly 1", w, h, s);
        test_img_fill(&a, 0.5f, 0.5f, 0.5f, 1.0f);
        test_img_fill(&b, 0.6f, 0.6f, 0.6f, 1.0f);
        assert_int_equal(quality_ssim(&a, &b, &s), 0);
        double yb = (double)0.6f;
        assert_float_equal(s, (2 * 0.5 * yb + 1e-4) / (0.25 + yb * yb + 1e-4), 1e-9);
        if (w * h >= 4) {   /* a ramp against its mirror: same moments, other structure */
            for (int i = 0; i < w * h; i++)
                for (int c = 0; c < 3; c++) {
                    a.px[i * 4 + c] = (float)i / (float)(w * h);
                    b.px[i * 4 + c] = (float)(w * h - 1 - i) / (float)(w * h);
                }
            assert_int_equal(quality_ssim(&a, &b, &s), 0);
            if (!(s < 0.5))
                fail_msg("%dx%d: ramp against its mirror scored %.6f, expected < 0.5", w, h, s);
        }
        img_free(&a);
        img_free(&b);
    }
    img e = {0, 4, NULL}, c = {0}, d = {0};
    double s = 0;
    assert_int_equal(img_alloc(&c, 4, 4), 0);
    assert_int_equal(img_alloc(&d, 4, 5), 0);
    e.px = c.px;
    assert_int_equal(quality_ssim(&e, &e, &s), DM_ERR_ARG);
    assert_int_equal(quality_ssim(&c, &d, &s), DM_ERR_ARG);
    img_free(&c);
    img_free(&d);
}

static void test_ssim_structure_lowers_score(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    assert_int_equal(img_alloc(&a, 16, 16), 0);
    assert_int_equal(img_alloc(&b, 16, 16), 0);
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            float v = (float)((x + y) & 1);
            for (int c = 0; c < 3; c++) {
                a.px[(y * 16 + x) * 4 + c] = v;
                b.px[(y * 16 + x) * 4 + c] = 1.0f - v;   /* inverted checkerboard */
            }
        }
    double s = 0;
    assert_int_equal(quality_ssim(&a, &b, &s), 0);
    assert_true(s < 0.0);   /* anti-correlated structure: negative covariance */
    img_free(&a);
    img_free(&b);
}

/* 8×8 square at x = 4..11 against the same square shifted right by 2:
 * intersection 6×8 = 48, union 64 + 64 − 48 = 80, IoU 0.6, error 0.4. */
static void test_silhouette_shifted_square(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    unsigned char ma[400], mb[400];
    assert_int_equal(img_alloc(&a, 20, 20), 0);
    assert_int_equal(img_alloc(&b, 20, 20), 0);
    for (int y = 4; y < 12; y++)
        for (int x = 4; x < 12; x++) {
            a.px[(y * 20 + x) * 4 + 3] = 1.0f;
            b.px[(y * 20 + x + 2) * 4 + 3] = 0.75f;
        }
    b.px[3] = 0.5f;   /* exactly 0.5 is not covered (alpha > 0.5) */
    quality_coverage(&a, ma);
    quality_coverage(&b, mb);
    assert_float_equal(quality_silhouette_error(ma, mb, 400), 0.4, 1e-15);
    assert_true(quality_silhouette_error(ma, ma, 400) == 0.0);
    memset(ma, 0, sizeof ma);
    memset(mb, 0, sizeof mb);
    assert_true(quality_silhouette_error(ma, mb, 400) == 0.0);
    img_free(&a);
    img_free(&b);
}

static void test_depth_rmse_both_cover(void **state)
{
    (void)state;
    float da[4] = {1.0f, 2.0f, 3.0f, 4.0f};
    float db[4] = {1.5f, 2.0f, 100.0f, 3.0f};
    unsigned char ma[4] = {1, 1, 1, 1}, mb[4] = {1, 1, 0, 1};
    double r = -1;
    /* pixels 0, 1, 3: squared errors 0.25, 0, 1 → sqrt(1.25 / 3) */
    assert_int_equal(quality_depth_rmse(da, db, ma, mb, 4, &r), 0);
    assert_float_equal(r, sqrt(1.25 / 3.0), 1e-15);
    unsigned char none[4] = {0, 0, 0, 0};
    r = -1;
    assert_int_equal(quality_depth_rmse(da, db, ma, none, 4, &r), DM_ERR_UNAVAILABLE);
    assert_true(r == -1);
}

static void test_nonfinite_pixels(void **state)
{
    (void)state;
    img a = {0};
    assert_int_equal(img_alloc(&a, 4, 4), 0);
    a.px[0] = NAN;
    a.px[1] = INFINITY;           /* same pixel: counted once */
    a.px[5 * 4 + 3] = -INFINITY;  /* alpha counts too */
    a.px[9 * 4 + 2] = NAN;
    assert_int_equal(quality_nonfinite_pixels(&a), 3);
    img_free(&a);
}

/* Disc of radius 8 in 24×24; k = 6 pixels are cleared inside it: a plus of
 * 5 around the centre and 1 isolated pixel.  A notch cut from the rim is
 * connected to the outside and must not count. */
static void test_crack_pixels_holes_in_disc(void **state)
{
    (void)state;
    enum { W = 24, H = 24 };
    unsigned char m[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            m[y * W + x] = (x - 12) * (x - 12) + (y - 12) * (y - 12) <= 64;
    assert_int_equal(quality_crack_pixels(m, W, H), 0);
    m[12 * W + 12] = m[11 * W + 12] = m[13 * W + 12] = m[12 * W + 11] = m[12 * W + 13] = 0;
    m[8 * W + 9] = 0;
    m[12 * W + 20] = m[12 * W + 19] = 0;   /* notch open to the rim at x = 20 */
    assert_int_equal(quality_crack_pixels(m, W, H), 6);
    /* a fully covered image has no background at all */
    memset(m, 1, sizeof m);
    assert_int_equal(quality_crack_pixels(m, W, H), 0);
    /* a diagonal gap is not a 4-connection: the ring below encloses its centre */
    unsigned char r[5 * 5] = {
        0, 0, 0, 0, 0,
        0, 1, 1, 1, 0,
        0, 1, 0, 1, 0,
        0, 1, 1, 0, 0,
        0, 0, 0, 0, 0,
    };
    assert_int_equal(quality_crack_pixels(r, 5, 5), 1);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_ssim_identical_is_one),
             cmocka_unit_test(test_ssim_constant_offset_closed_form),
             cmocka_unit_test(test_ssim_tiny_images),
             cmocka_unit_test(test_ssim_structure_lowers_score),
             cmocka_unit_test(test_silhouette_shifted_square),
             cmocka_unit_test(test_depth_rmse_both_cover),
             cmocka_unit_test(test_nonfinite_pixels),
             cmocka_unit_test(test_crack_pixels_holes_in_disc))
