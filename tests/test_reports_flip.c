/* test_reports_flip.c — LDR-FLIP (imaging/flip.h).
 *
 * Expected values are computed here, by hand from the paper's formulas
 * (hand_* below, written apart from flip.c), or were printed by
 * tests/flip_reference.py, a pure-Python transcription of the paper run
 * once: python3 tests/flip_reference.py. */
#include "imaging/flip.h"
#include "reports/flip_run.h"
#include "core/dm_error.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#define PPD FLIP_DEFAULT_PPD

/* ---- The colour pipeline by hand, for a flat colour ---- */

static double hand_lin(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static double hand_f(double t)
{
    return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16) / 116;
}

/* sRGB-encoded colour -> Hunt-adjusted L*a*b* (D65 white of sRGB). */
static void hand_hunt_lab(const double srgb[3], double lab[3])
{
    double r = hand_lin(srgb[0]), g = hand_lin(srgb[1]), b = hand_lin(srgb[2]);
    double X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    double Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    double Xn = 0.4124564 + 0.3575761 + 0.1804375, Yn = 0.2126729 + 0.7151522 + 0.0721750,
           Zn = 0.0193339 + 0.1191920 + 0.9503041;
    double L = 116 * hand_f(Y / Yn) - 16;
    lab[0] = L;
    lab[1] = 0.01 * L * 500 * (hand_f(X / Xn) - hand_f(Y / Yn));
    lab[2] = 0.01 * L * 200 * (hand_f(Y / Yn) - hand_f(Z / Zn));
}

static double hand_hyab(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + hypot(a[1] - b[1], a[2] - b[2]);
}

/* HyAB -> compressed (^0.7) and mapped (pc 0.4, pt 0.95, cmax from pure
 * green vs pure blue). */
static double hand_flip_flat(const double c1[3], const double c2[3])
{
    const double green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
    double lg[3], lb[3], l1[3], l2[3];
    hand_hunt_lab(green, lg);
    hand_hunt_lab(blue, lb);
    hand_hunt_lab(c1, l1);
    hand_hunt_lab(c2, l2);
    double cmax = pow(hand_hyab(lg, lb), 0.7), e = pow(hand_hyab(l1, l2), 0.7);
    return e < 0.4 * cmax ? 0.95 / (0.4 * cmax) * e : 0.95 + (e - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

static void fill(img *im, int w, int h, const double c[3])
{
    assert_int_equal(img_alloc(im, w, h), 0);
    test_img_fill(im, (float)c[0], (float)c[1], (float)c[2], 1.0f);
}

static void set_px(img *im, int x, int y, double r, double g, double b)
{
    float *p = im->px + ((size_t)y * im->w + x) * 4;
    p[0] = (float)r, p[1] = (float)g, p[2] = (float)b;
}

static double flip_mean(const img *a, const img *b, double ppd, float *map)
{
    flip_stats st;
    flip_desc d = { .ppd = ppd };
    assert_int_equal(flip_compare(a, b, &d, &st, map), 0);
    return st.mean;
}

/* Pseudo-random image (fixed LCG). */
static void noise(img *im, int w, int h, unsigned seed)
{
    assert_int_equal(img_alloc(im, w, h), 0);
    for (int i = 0; i < w * h * 4; i++) {
        seed = seed * 1103515245u + 12345u;
        im->px[i] = (float)((seed >> 16) & 0x7fff) / 32767.0f;
    }
}

/* ---- Tests ---- */

static void test_flip_identical_is_zero_everywhere(void **state)
{
    (void)state;
    img a = {0};
    noise(&a, 37, 29, 7);
    float map[37 * 29];
    flip_stats st;
    assert_int_equal(flip_compare(&a, &a, NULL, &st, map), 0);
    for (int i = 0; i < 37 * 29; i++)
        assert_true(map[i] == 0.0f);
    assert_true(st.mean == 0 && st.median == 0 && st.q1 == 0 && st.q3 == 0 && st.max == 0);
    img_free(&a);
}

/* A flat image filters to itself (normalised kernels, extended borders) and
 * has no edges or points, so every pixel's error is the hand-computed
 * compressed HyAB of the two colours.  The chromatic-only pair is the next
 * test. */
static void test_flip_flat_pairs_match_hand_hyab(void **state)
{
    (void)state;
    const double pairs[][2][3] = {
        { { 0.5, 0.5, 0.5 }, { 0.6, 0.6, 0.6 } },       /* lightness only */
        { { 0.2, 0.4, 0.8 }, { 0.25, 0.35, 0.7 } },
        { { 0.8, 0.2, 0.2 }, { 0.2, 0.8, 0.2 } },       /* red vs green: large */
        { { 0.5, 0.5, 0.5 }, { 0.5, 0.5, 0.5 } },
    };
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
        img a = {0}, b = {0};
        fill(&a, 24, 16, pairs[k][0]);
        fill(&b, 24, 16, pairs[k][1]);
        float map[24 * 16];
        double mean = flip_mean(&a, &b, PPD, map);
        double want = hand_flip_flat(pairs[k][0], pairs[k][1]);
        print_message("pair %zu: flip %.9f hand %.9f\n", k, mean, want);
        assert_true(fabs(mean - want) < 1e-5);
        for (int i = 0; i < 24 * 16; i++)
            assert_true(fabs(map[i] - want) < 1e-5);
        img_free(&a);
        img_free(&b);
    }
}

/* A pair differing only in chromaticity: equal luminance Y, so L* is equal
 * and the HyAB distance is the a*b* term alone. */
static void test_flip_chromatic_only_pair(void **state)
{
    (void)state;
    /* c1 = (0.7, 0.5, 0.3); c2 = (0.5, g, 0.7) with g solved so that the
     * linear luminance Y (second row of the sRGB matrix) is equal. */
    double Y1 = 0.2126729 * hand_lin(0.7) + 0.7151522 * hand_lin(0.5) + 0.0721750 * hand_lin(0.3);
    double g2 = (Y1 - 0.2126729 * hand_lin(0.5) - 0.0721750 * hand_lin(0.7)) / 0.7151522;
    assert_true(g2 > 0 && g2 < 1);
    double s2 = 1.055 * pow(g2, 1 / 2.4) - 0.055;
    const double c1[3] = { 0.7, 0.5, 0.3 }, c2[3] = { 0.5, s2, 0.7 };
    double l1[3], l2[3];
    hand_hunt_lab(c1, l1);
    hand_hunt_lab(c2, l2);
    assert_true(fabs(l1[0] - l2[0]) < 1e-9);
    img a = {0}, b = {0};
    fill(&a, 20, 20, c1);
    fill(&b, 20, 20, c2);
    double mean = flip_mean(&a, &b, PPD, NULL);
    double want = hand_flip_flat(c1, c2);
    print_message("chromatic-only: flip %.9f hand %.9f\n", mean, want);
    assert_true(fabs(mean - want) < 1e-5);
    assert_true(want > 0.2);
    img_free(&a);
    img_free(&b);
}

/* FLIP is symmetric in its two images: every stage compares them by
 * absolute differences. */
static void test_flip_symmetric(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    noise(&a, 31, 23, 1);
    noise(&b, 31, 23, 2);
    float m1[31 * 23], m2[31 * 23];
    double e1 = flip_mean(&a, &b, PPD, m1), e2 = flip_mean(&b, &a, PPD, m2);
    assert_true(e1 == e2);
    for (int i = 0; i < 31 * 23; i++)
        assert_true(m1[i] == m2[i]);
    /* and mirroring both images mirrors the map */
    img am = {0}, bm = {0};
    assert_int_equal(img_alloc(&am, 31, 23), 0);
    assert_int_equal(img_alloc(&bm, 31, 23), 0);
    for (int y = 0; y < 23; y++)
        for (int x = 0; x < 31; x++)
            for (int c = 0; c < 4; c++) {
                am.px[(y * 31 + (30 - x)) * 4 + c] = a.px[(y * 31 + x) * 4 + c];
                bm.px[(y * 31 + (30 - x)) * 4 + c] = b.px[(y * 31 + x) * 4 + c];
            }
    flip_mean(&am, &bm, PPD, m2);
    for (int y = 0; y < 23; y++)
        for (int x = 0; x < 31; x++)
            assert_true(fabsf(m1[y * 31 + x] - m2[y * 31 + 30 - x]) < 1e-6f);
    img_free(&a);
    img_free(&b);
    img_free(&am);
    img_free(&bm);
}

/* A grey square of growing contrast on grey: the mean error grows. */
static void test_flip_monotone_in_perturbation(void **state)
{
    (void)state;
    const double grey[3] = { 0.5, 0.5, 0.5 };
    img a = {0};
    fill(&a, 32, 32, grey);
    double prev = 0;
    for (int k = 1; k <= 8; k++) {
        img b = {0};
        fill(&b, 32, 32, grey);
        for (int y = 12; y < 20; y++)
            for (int x = 12; x < 20; x++)
                set_px(&b, x, y, 0.5 + 0.05 * k, 0.5 + 0.05 * k, 0.5 + 0.05 * k);
        double e = flip_mean(&a, &b, PPD, NULL);
        print_message("square +%.2f: mean %.6f\n", 0.05 * k, e);
        assert_true(e > prev);
        prev = e;
        img_free(&b);
    }
    img_free(&a);
}

/* A single white pixel on black: the contrast-sensitivity filters spread
 * it into a colour difference, and the point detector sees it, which lifts
 * the error above the colour-only value (error = colour^(1 - feature)).
 * Values from tests/flip_reference.py (full 2-D kernels, plain Python):
 *   pixel    flip      colour-only  feature
 *   (16,16)  0.864917  0.832501     0.208369
 *   (19,16)  0.133713  0.093494     0.150979
 *   (16,22)  0.000044  0.000014     0.105720
 * flip.c keeps its planes in float; the compression's ^0.7 magnifies that
 * rounding for differences near 0, hence 1e-5 rather than 1e-6 there. */
static void test_flip_point_feature_raises_error(void **state)
{
    (void)state;
    const double black[3] = { 0, 0, 0 };
    img a = {0}, b = {0};
    fill(&a, 33, 33, black);
    fill(&b, 33, 33, black);
    set_px(&b, 16, 16, 1, 1, 1);
    float map[33 * 33];
    flip_mean(&a, &b, PPD, map);
    const struct { int x, y; double flip, colour; } want[] = {
        { 16, 16, 0.864917, 0.832501 }, { 19, 16, 0.133713, 0.093494 }, { 16, 22, 0.000044, 0.000014 } };
    for (size_t i = 0; i < 3; i++) {
        double v = map[want[i].y * 33 + want[i].x];
        print_message("dot (%d,%d): %.6f\n", want[i].x, want[i].y, v);
        assert_true(fabs(v - want[i].flip) < 1e-5);
        assert_true(v > want[i].colour);
    }
    assert_true(map[0] < 1e-6);
    img_free(&a);
    img_free(&b);
}

/* A step edge 0.2 | 0.8 moved by one pixel (x = 16 vs 17): on the moved
 * column the colour term alone decides (the edge magnitudes agree there);
 * four pixels either side the edge detector's response differs and lifts
 * the error 3-6x above the colour-only value.  From flip_reference.py:
 *   (12,8)  0.026475  colour-only 0.006720  feature 0.274078
 *   (16,8)  0.446683              0.446683          0
 *   (20,8)  0.009907              0.001735          0.274078 */
static void test_flip_edge_feature_raises_error(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    assert_int_equal(img_alloc(&a, 33, 17), 0);
    assert_int_equal(img_alloc(&b, 33, 17), 0);
    for (int y = 0; y < 17; y++)
        for (int x = 0; x < 33; x++) {
            double va = x < 16 ? 0.2 : 0.8, vb = x < 17 ? 0.2 : 0.8;
            set_px(&a, x, y, va, va, va);
            set_px(&b, x, y, vb, vb, vb);
            a.px[(y * 33 + x) * 4 + 3] = b.px[(y * 33 + x) * 4 + 3] = 1;
        }
    float map[33 * 17];
    flip_mean(&a, &b, PPD, map);
    const struct { int x; double flip, colour; } want[] = {
        { 12, 0.026475, 0.006720 }, { 16, 0.446683, 0.446683 }, { 20, 0.009907, 0.001735 } };
    for (size_t i = 0; i < 3; i++) {
        double v = map[8 * 33 + want[i].x];
        print_message("edge (%d,8): %.6f\n", want[i].x, v);
        assert_true(fabs(v - want[i].flip) < 2e-6);
        assert_true(v >= want[i].colour - 2e-6);
    }
    assert_true(map[8 * 33 + 12] > 3 * 0.006720);
    img_free(&a);
    img_free(&b);
}

static void test_flip_bounds(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    noise(&a, 40, 30, 3);
    noise(&b, 40, 30, 4);
    for (int i = 0; i < 40 * 30 * 4; i += 7)
        b.px[i] = (i / 7) % 2 ? 2.0f : -1.0f;       /* out of range: clamped */
    float map[40 * 30];
    flip_stats st;
    assert_int_equal(flip_compare(&a, &b, NULL, &st, map), 0);
    for (int i = 0; i < 40 * 30; i++)
        assert_true(map[i] >= 0 && map[i] <= 1);
    assert_true(st.q1 <= st.median && st.median <= st.q3 && st.q3 <= st.max && st.max <= 1);
    /* black vs white: the largest lightness difference */
    const double k0[3] = { 0, 0, 0 }, k1[3] = { 1, 1, 1 };
    img c = {0}, d = {0};
    fill(&c, 8, 8, k0);
    fill(&d, 8, 8, k1);
    double e = flip_mean(&c, &d, PPD, NULL);
    assert_true(e > 0.95 && e <= 1);
    img_free(&a);
    img_free(&b);
    img_free(&c);
    img_free(&d);
}

/* Eq. 3 and Eq. 2 at 67.02 ppd: r = ceil(3 sqrt(0.04 / (2 pi^2)) 67.02)
 * = ceil(9.0510) = 10; the feature sigma 0.5 * 0.082 * 67.02 = 2.7478 px,
 * radius ceil(8.243) = 9. */
static void test_flip_kernel_sizes(void **state)
{
    (void)state;
    assert_int_equal(flip_csf_radius(PPD), 10);
    assert_true(fabs(flip_feature_sigma(PPD) - 2.747846374) < 1e-8);
    assert_int_equal(flip_feature_radius(PPD), 9);
    assert_int_equal(flip_csf_radius(30), 5);      /* 3 * 0.045016 * 30 = 4.05 */
    /* Eq. 2 at x = 0 is a1 sqrt(pi/b1) + a2 sqrt(pi/b2) */
    assert_true(fabs(flip_csf_value(FLIP_ACHROMATIC, 0) - sqrt(M_PI / 0.0047)) < 1e-9);
    assert_true(fabs(flip_csf_value(FLIP_BLUE_YELLOW, 0) -
                     (34.1 * sqrt(M_PI / 0.04) + 13.5 * sqrt(M_PI / 0.025))) < 1e-9);
    /* and falls by e^-1 at x^2 = b1 / pi^2 for a single Gaussian */
    double x = sqrt(0.0053) / M_PI;
    assert_true(fabs(flip_csf_value(FLIP_RED_GREEN, x) / flip_csf_value(FLIP_RED_GREEN, 0) - exp(-1)) < 1e-12);
}

/* The pooled statistics: weights are the values themselves. */
static void test_flip_pool_weighted(void **state)
{
    (void)state;
    /* values 0,0,0.1,0.2,0.3,0.4: total 1.0; cumulative 0.1 0.3 0.6 1.0 */
    const float m[] = { 0.4f, 0.0f, 0.2f, 0.1f, 0.0f, 0.3f };
    flip_stats st;
    assert_int_equal(flip_pool(m, 6, &st), 0);
    assert_int_equal(flip_pool(m, 0, &st), DM_ERR_ARG);
    assert_true(fabs(st.mean - 1.0 / 6) < 1e-7);
    assert_true(fabsf((float)st.q1 - 0.2f) < 1e-7f);       /* 0.3 >= 0.25 */
    assert_true(fabsf((float)st.median - 0.3f) < 1e-7f);   /* 0.6 >= 0.5 */
    assert_true(fabsf((float)st.q3 - 0.4f) < 1e-7f);
    assert_true(fabsf((float)st.max - 0.4f) < 1e-7f);
}

static void test_flip_bad_args(void **state)
{
    (void)state;
    img a = {0}, b = {0}, b2 = {0};
    noise(&a, 8, 8, 1);
    noise(&b, 9, 8, 1);
    noise(&b2, 8, 8, 2);
    flip_stats st = { .mean = 42 };
    assert_int_equal(flip_compare(&a, &b, NULL, &st, NULL), DM_ERR_ARG);
    assert_true(st.mean == 42);
    flip_desc d = { .ppd = -1 };
    assert_int_equal(flip_compare(&a, &a, &d, &st, NULL), DM_ERR_ARG);
    d.ppd = NAN;
    assert_int_equal(flip_compare(&a, &a, &d, &st, NULL), DM_ERR_ARG);
    d.ppd = 1e6;                                   /* kernels too wide */
    assert_int_equal(flip_compare(&a, &a, &d, &st, NULL), DM_ERR_ARG);
    /* a tiny ppd: feature kernels underflow, still finite, in [0,1] */
    d.ppd = 0.01;
    assert_int_equal(flip_compare(&a, &b2, &d, &st, NULL), 0);
    assert_true(isfinite(st.mean) && st.max <= 1);
    img_free(&a);
    img_free(&b);
    img_free(&b2);
}

/* The same pair twice gives bit-identical maps. */
static void test_flip_stable(void **state)
{
    (void)state;
    img a = {0}, b = {0};
    noise(&a, 64, 48, 5);
    noise(&b, 64, 48, 6);
    double e1 = flip_mean(&a, &b, PPD, NULL), e2 = flip_mean(&a, &b, PPD, NULL);
    assert_true(e1 == e2);
    img_free(&a);
    img_free(&b);
}

/* report --flip-ppd: FLIP again from a run directory's 8-bit PNGs.  Flat
 * 128/255 against 153/255 grey gives the hand value of those levels at any
 * ppd; the map is written and pointed to; a configuration without images
 * keeps its values; an unreadable render is an error naming it. */
static void test_flip_run_recompute(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_flip_run_XXXXXX", e[256];
    assert_non_null(mkdtemp(dir));
    char *sub = dm_xasprintf("%s/img", dir), *pa = dm_xasprintf("%s/img/r.png", dir),
         *pb = dm_xasprintf("%s/img/t.png", dir);
    assert_int_equal(dm_mkdirs(sub), 0);
    const double g1[3] = { 128 / 255.0, 128 / 255.0, 128 / 255.0 }, g2[3] = { 153 / 255.0, 153 / 255.0, 153 / 255.0 };
    img a = {0}, b = {0};
    fill(&a, 16, 8, g1);
    fill(&b, 16, 8, g2);
    assert_int_equal(img_save(&a, pa, e, sizeof e), 0);
    assert_int_equal(img_save(&b, pb, e, sizeof e), 0);
    dm_run_result run = {0};
    run.n_configs = 2;
    run.configs = dm_xcalloc(2, sizeof *run.configs);
    for (int i = 0; i < 2; i++) {
        run.configs[i].key = dm_xstrdup(i ? "k1" : "k0");
        run.configs[i].quality.present = 1;
        run.configs[i].quality.flip = 0.5;
    }
    run.configs[0].img_reference = dm_xstrdup("img/r.png");
    run.configs[0].img_render = dm_xstrdup("img/t.png");
    dm_str err = {0};
    assert_int_equal(flip_run_recompute(&run, dir, 30, &err), 0);
    double want = hand_flip_flat(g1, g2);
    assert_true(fabs(run.configs[0].quality.flip - want) < 1e-5);
    assert_true(run.configs[0].quality.flip_ppd == 30);
    assert_string_equal(run.configs[0].img_flip, "img/k0-flip-ppd30.png");
    assert_true(run.configs[1].quality.flip == 0.5);
    char *map = dm_xasprintf("%s/img/k0-flip-ppd30.png", dir);
    assert_true(dm_file_exists(map));
    free(run.configs[0].img_render);
    run.configs[0].img_render = dm_xstrdup("img/missing.png");
    assert_int_equal(flip_run_recompute(&run, dir, 30, &err), DM_ERR_IO);
    assert_non_null(strstr(dm_str_get(&err), "configuration k0: "));
    assert_non_null(strstr(dm_str_get(&err), "missing.png"));
    assert_int_equal(flip_run_recompute(&run, dir, 0.5, &err), DM_ERR_ARG);
    dm_str_free(&err);
    dm_run_free(&run);
    img_free(&a);
    img_free(&b);
    test_rm_rf(dir);
    free(map);
    free(sub);
    free(pa);
    free(pb);
}

DM_TEST_MAIN(NULL, NULL,
    cmocka_unit_test(test_flip_run_recompute),
    cmocka_unit_test(test_flip_identical_is_zero_everywhere),
    cmocka_unit_test(test_flip_flat_pairs_match_hand_hyab),
    cmocka_unit_test(test_flip_chromatic_only_pair),
    cmocka_unit_test(test_flip_symmetric),
    cmocka_unit_test(test_flip_monotone_in_perturbation),
    cmocka_unit_test(test_flip_point_feature_raises_error),
    cmocka_unit_test(test_flip_edge_feature_raises_error),
    cmocka_unit_test(test_flip_bounds),
    cmocka_unit_test(test_flip_kernel_sizes),
    cmocka_unit_test(test_flip_pool_weighted),
    cmocka_unit_test(test_flip_bad_args),
    cmocka_unit_test(test_flip_stable))
