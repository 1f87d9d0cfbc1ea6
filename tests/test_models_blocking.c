/* Blocking by round (models/blocking.h) on synthetic rounds with known
 * common factors: the factors are found, removing them narrows the spread
 * of every configuration without moving its median, a configuration's own
 * outlier is not removed (leave-one-out), and a scene too small to block is
 * left as it is. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "models/blocking.h"
#include "models/stats.h"
#include "test_util.h"

#define NC 5
#define NR 9

/* x[c][r] = (c+1) * round[r] * (1 + 0.002 * ((c*7 + r*3) % 5 - 2)). */
static void fill(double x[NC][NR], const double *round)
{
    for (size_t c = 0; c < NC; c++)
        for (size_t r = 0; r < NR; r++)
            x[c][r] = (double)(c + 1) * round[r] * (1 + 0.002 * (double)((c * 7 + r * 3) % 5) - 0.004);
}

static void test_factors_and_correction(void **state)
{
    (void)state;
    const double round[NR] = { 1, 1.02, 0.98, 0.77, 1, 1.01, 0.99, 1.2, 1 };
    double x[NC][NR], y[NC][NR], f[NR];
    fill(x, round);
    blocking_series s[NC];
    double *out[NC];
    for (size_t c = 0; c < NC; c++) {
        s[c] = (blocking_series){ x[c], NR };
        out[c] = y[c];
    }
    assert_int_equal(blocking_round_factors(s, NC, f, NR), NR);
    assert_true(fabs(f[3] - 0.77) < 0.01 && fabs(f[7] - 1.2) < 0.01);
    assert_true(fabs(blocking_spread(f, NR) - (exp((log(1.2) - log(0.77)) / 2) - 1)) < 0.01);
    assert_int_equal(blocking_correct(s, NC, out), NC);
    for (size_t c = 0; c < NC; c++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t r = 0; r < NR; r++)
            lo = fmin(lo, y[c][r]), hi = fmax(hi, y[c][r]);
        assert_true((hi - lo) / (double)(c + 1) < 0.02);            /* was 0.43 */
        assert_true(fabs(stats_median(y[c], NR) / stats_median(x[c], NR) - 1) < 0.01);
    }
}

/* Configuration 0 alone is 30 % slow in round 4: the others do not share
 * it, so its correction leaves it (its own sample never makes its factor). */
static void test_own_outlier_kept(void **state)
{
    (void)state;
    const double round[NR] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
    double x[NC][NR], y[NC][NR];
    fill(x, round);
    x[0][4] *= 1.3;
    blocking_series s[NC];
    double *out[NC];
    for (size_t c = 0; c < NC; c++) {
        s[c] = (blocking_series){ x[c], NR };
        out[c] = y[c];
    }
    blocking_correct(s, NC, out);
    assert_true(y[0][4] / x[0][4] > 0.99);
}

/* Two configurations are too few (each would have one other): unchanged;
 * a NaN sample stays NaN and enters no factor. */
static void test_too_few_and_nonfinite(void **state)
{
    (void)state;
    double a[3] = { 1, 2, 3 }, b[3] = { 2, 4, 6 }, ya[3], yb[3];
    blocking_series s[2] = { { a, 3 }, { b, 3 } };
    double *out[2] = { ya, yb };
    assert_int_equal(blocking_correct(s, 2, out), 0);
    assert_memory_equal(ya, a, sizeof a);
    assert_memory_equal(yb, b, sizeof b);
    double x[NC][NR], y[NC][NR];
    const double round[NR] = { 1, 1, 1, 1, 1, 1, 1, 1, 1 };
    fill(x, round);
    x[2][1] = NAN;
    blocking_series t[NC];
    double *o[NC];
    for (size_t c = 0; c < NC; c++) {
        t[c] = (blocking_series){ x[c], NR };
        o[c] = y[c];
    }
    blocking_correct(t, NC, o);
    assert_true(isnan(y[2][1]) && isfinite(y[3][1]));
    assert_true(blocking_spread((double[]){ 1.0 }, 1) == 0);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_factors_and_correction),
             cmocka_unit_test(test_own_outlier_kept),
             cmocka_unit_test(test_too_few_and_nonfinite))
