/* Frame times along a replayed path (models/frame_series.h) on series with
 * known answers: 200 frames of 1 ms with two 3 ms frames give p50 1 ms,
 * p99 1.02 ms (type 7: between the 198th and 199th smallest), a 1 % low of
 * 3 ms (the two slowest frames) and two stutters at their frame indices;
 * one slow replay of a frame is not a stutter (the median of the replays);
 * replays that disagree by 20 % mark the series noisy, by 1 % not; one
 * replay leaves the noise unknown; missing times are left out. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "core/dm_error.h"
#include "models/frame_series.h"
#include "test_util.h"

#define F 200
#define S 3

static void fill(double *t, double base)
{
    for (size_t i = 0; i < (size_t)F * S; i++)
        t[i] = base;
}

static void test_stutters_and_percentiles(void **state)
{
    (void)state;
    double t[F * S];
    fill(t, 1e6);
    for (size_t s = 0; s < S; s++)
        t[s * F + 50] = t[s * F + 150] = 3e6;
    size_t at[F];
    frame_series_stats st;
    assert_int_equal(frame_series_summarize(t, S, F, at, &st), 0);
    assert_int_equal(st.frames, F);
    assert_int_equal(st.replays, S);
    assert_float_equal(st.p50, 1e6, 1e-6);
    assert_float_equal(st.p95, 1e6, 1e-6);
    assert_float_equal(st.p99, 1.02e6, 1e-3);   /* 1 + 0.01 × (3 − 1) ms */
    assert_int_equal(st.low1_frames, 2);
    assert_float_equal(st.low1_ns, 3e6, 1e-6);
    assert_float_equal(st.low1_fps, 1e9 / 3e6, 1e-9);
    assert_int_equal(st.stutters, 2);
    assert_int_equal(at[0], 50);
    assert_int_equal(at[1], 150);
    assert_float_equal(st.replay_spread, 0, 0);
    assert_int_equal(st.noisy, 0);
}

static void test_one_slow_replay_is_not_a_stutter(void **state)
{
    (void)state;
    double t[F * S];
    fill(t, 1e6);
    t[1 * F + 70] = 9e6;   /* replay 1 only */
    frame_series_stats st;
    assert_int_equal(frame_series_summarize(t, S, F, NULL, &st), 0);
    assert_int_equal(st.stutters, 0);
    assert_float_equal(st.low1_ns, 1e6, 1e-6);
}

static void test_noise_of_the_replays(void **state)
{
    (void)state;
    double t[F * S];
    frame_series_stats st;
    for (size_t f = 0; f < F; f++) {   /* replays 0.9, 1.0, 1.1 ms: spread 0.2 */
        t[f] = 0.9e6;
        t[F + f] = 1.0e6;
        t[2 * F + f] = 1.1e6;
    }
    assert_int_equal(frame_series_summarize(t, S, F, NULL, &st), 0);
    assert_float_equal(st.replay_spread, 0.2, 1e-12);
    assert_int_equal(st.noisy, 1);
    for (size_t f = 0; f < F; f++) {   /* 0.995, 1.0, 1.005: spread 0.01 */
        t[f] = 0.995e6;
        t[2 * F + f] = 1.005e6;
    }
    assert_int_equal(frame_series_summarize(t, S, F, NULL, &st), 0);
    assert_float_equal(st.replay_spread, 0.01, 1e-12);
    assert_int_equal(st.noisy, 0);
    assert_int_equal(frame_series_summarize(t, 1, F, NULL, &st), 0);   /* one replay */
    assert_true(isnan(st.replay_spread));
    assert_int_equal(st.noisy, -1);
}

static void test_missing_times(void **state)
{
    (void)state;
    double t[4] = {NAN, 2e6, INFINITY, 4e6};   /* one replay of four frames */
    frame_series_stats st;
    assert_int_equal(frame_series_summarize(t, 1, 4, NULL, &st), 0);
    assert_int_equal(st.frames, 2);
    assert_float_equal(st.p50, 3e6, 1e-6);
    assert_int_equal(st.low1_frames, 1);
    assert_float_equal(st.low1_ns, 4e6, 1e-6);
    double none[2] = {NAN, NAN};
    assert_int_equal(frame_series_summarize(none, 1, 2, NULL, &st), DM_ERR_ARG);
    assert_int_equal(frame_series_summarize(NULL, 1, 2, NULL, &st), DM_ERR_ARG);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_stutters_and_percentiles),
             cmocka_unit_test(test_one_slow_replay_is_not_a_stutter),
             cmocka_unit_test(test_noise_of_the_replays),
             cmocka_unit_test(test_missing_times))
