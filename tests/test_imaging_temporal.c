/* Temporal stability (imaging/temporal.h) on sequences with known answers:
 * a still sequence has temporal error 0; a test with a constant bias
 * against a moving reference has 0 (it changes as the reference does); a
 * test that flickers by d over a still reference has mean and p99 d; when
 * half the pixels flicker, mean d/2, p99 d, and the map holds d on that
 * half and 0 on the other; a reference that moves while the test stays
 * still has the reference's change as its error; NaN pixels are counted
 * and left out; popping is the largest jump of the per-frame error, at its
 * frame; the step-by-step accumulator holds the same figures as the whole
 * sequences, with two frames at a time. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "core/dm_error.h"
#include "imaging/temporal.h"
#include "test_util.h"

#define W 8
#define H 4
#define N 6

/* Frame t of a sequence: grey v(t, x) in R, G and B (so the luminance is v). */
static void seq(img *f, double (*v)(int t, int x, void *), void *arg)
{
    for (int t = 0; t < N; t++) {
        assert_int_equal(img_alloc(&f[t], W, H), 0);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float *p = f[t].px + 4 * ((size_t)y * W + x);
                p[0] = p[1] = p[2] = (float)v(t, x, arg);
                p[3] = 1;
            }
    }
}

static void seq_free(img *f)
{
    for (int t = 0; t < N; t++)
        img_free(&f[t]);
}

static double v_still(int t, int x, void *a) { (void)t; (void)a; return 0.25 + 0.05 * x; }
static double v_moving(int t, int x, void *a) { (void)a; return 0.1 + 0.02 * x + 0.05 * t; }
static double v_biased(int t, int x, void *a) { return v_moving(t, x, a) + 0.125; }
static double v_flicker(int t, int x, void *a)
{
    double d = *(double *)a;
    return v_still(t, x, NULL) + (t % 2 ? d : 0);
}
static double v_half(int t, int x, void *a)
{
    double d = *(double *)a;
    return v_still(t, x, NULL) + (x < W / 2 && t % 2 ? d : 0);
}

static void test_still_and_bias(void **state)
{
    (void)state;
    img a[N], b[N], r[N], m[N];
    seq(a, v_still, NULL);
    seq(b, v_still, NULL);
    temporal_stats st;
    assert_int_equal(temporal_error(a, b, N, &st, NULL), 0);
    assert_int_equal(st.steps, N - 1);
    assert_float_equal(st.mean, 0, 0);
    assert_float_equal(st.p99, 0, 0);
    seq(r, v_moving, NULL);
    seq(m, v_biased, NULL);
    assert_int_equal(temporal_error(m, r, N, &st, NULL), 0);
    assert_float_equal(st.mean, 0, 1e-6);
    assert_float_equal(st.max, 0, 1e-6);
    /* the test stands still while the reference moves 0.05 a frame */
    assert_int_equal(temporal_error(a, r, N, &st, NULL), 0);
    assert_float_equal(st.mean, 0.05, 1e-6);
    assert_float_equal(st.p99, 0.05, 1e-6);
    seq_free(a);
    seq_free(b);
    seq_free(r);
    seq_free(m);
}

static void test_flicker(void **state)
{
    (void)state;
    double d = 0.1;
    img t[N], r[N], h[N], map = {0};
    seq(t, v_flicker, &d);
    seq(r, v_still, NULL);
    seq(h, v_half, &d);
    temporal_stats st;
    assert_int_equal(temporal_error(t, r, N, &st, NULL), 0);
    assert_float_equal(st.mean, d, 1e-6);
    assert_float_equal(st.p99, d, 1e-6);
    assert_int_equal(temporal_error(h, r, N, &st, &map), 0);
    assert_float_equal(st.mean, d / 2, 1e-6);
    assert_float_equal(st.p99, d, 1e-6);
    assert_int_equal(map.w, W);
    assert_int_equal(map.h, H);
    for (int x = 0; x < W; x++) {
        assert_float_equal(map.px[4 * x], x < W / 2 ? d : 0, 1e-6);
        assert_float_equal(map.px[4 * x + 3], 1, 0);
    }
    img_free(&map);
    seq_free(t);
    seq_free(r);
    seq_free(h);
}

static void test_bad_input_and_nonfinite(void **state)
{
    (void)state;
    img a[N], b[N];
    seq(a, v_still, NULL);
    seq(b, v_still, NULL);
    temporal_stats st;
    assert_int_equal(temporal_error(a, b, 1, &st, NULL), DM_ERR_ARG);   /* one frame: no step */
    assert_true(isnan(st.mean));
    a[3].w = W - 1;                                                      /* a frame of another size */
    assert_int_equal(temporal_error(a, b, N, &st, NULL), DM_ERR_ARG);
    a[3].w = W;
    a[2].px[0] = NAN;                                                    /* pixel 0 of frame 2: steps 2 and 3 */
    assert_int_equal(temporal_error(a, b, N, &st, NULL), 0);
    assert_int_equal(st.nonfinite, 2);
    assert_float_equal(st.mean, 0, 0);
    seq_free(a);
    seq_free(b);
}

/* The half-flicker case step by step, frames dropped as they are passed:
 * mean d/2, p99 d, the same map; a frame of another size is refused and a
 * finish without a step is an error with NaN figures. */
static void test_accumulator(void **state)
{
    (void)state;
    double d = 0.1;
    img h[N], r[N], map = {0};
    seq(h, v_half, &d);
    seq(r, v_still, NULL);
    temporal_acc a;
    temporal_stats st;
    assert_int_equal(temporal_acc_init(&a, W, H), 0);
    for (int t = 1; t < N; t++) {
        assert_int_equal(temporal_acc_step(&a, &h[t - 1], &h[t], &r[t - 1], &r[t]), 0);
        img_free(&h[t - 1]);
        img_free(&r[t - 1]);
    }
    img small = {W - 1, H, h[N - 1].px};
    assert_int_equal(temporal_acc_step(&a, &h[N - 1], &small, &r[N - 1], &r[N - 1]), DM_ERR_ARG);
    assert_int_equal(temporal_acc_finish(&a, &st, &map), 0);
    assert_int_equal(st.steps, N - 1);
    assert_float_equal(st.mean, d / 2, 1e-6);
    assert_float_equal(st.p99, d, 1e-6);
    for (int x = 0; x < W; x++)
        assert_float_equal(map.px[4 * (W + x)], x < W / 2 ? d : 0, 1e-6);
    img_free(&map);
    img_free(&h[N - 1]);
    img_free(&r[N - 1]);
    assert_int_equal(temporal_acc_init(&a, 0, H), DM_ERR_ARG);
    assert_int_equal(temporal_acc_init(&a, W, H), 0);
    assert_int_equal(temporal_acc_finish(&a, &st, NULL), DM_ERR_ARG);
    assert_true(isnan(st.mean) && isnan(st.p99));
}

static void test_popping(void **state)
{
    (void)state;
    double e[5] = {0.10, 0.11, 0.50, 0.52, 0.20};
    size_t at = 0;
    assert_float_equal(temporal_popping(e, 5, &at), 0.39, 1e-12);
    assert_int_equal(at, 2);
    double flat[3] = {0.3, 0.3, 0.3};
    assert_float_equal(temporal_popping(flat, 3, &at), 0, 0);
    assert_true(isnan(temporal_popping(e, 1, NULL)));
    double gaps[3] = {NAN, 0.2, NAN};
    assert_true(isnan(temporal_popping(gaps, 3, NULL)));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_still_and_bias),
             cmocka_unit_test(test_flicker),
             cmocka_unit_test(test_bad_input_and_nonfinite),
             cmocka_unit_test(test_accumulator),
             cmocka_unit_test(test_popping))
