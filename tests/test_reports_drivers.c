/* Kendall's tau-b of the side-by-side driver report (reports/drivers_report.h)
 * against values counted by hand. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "reports/drivers_report.h"

/* Same order 1, reversed -1; y = (3,4,1,2,5) against x = 1..5: of the 10
 * pairs 6 concordant and 4 discordant, tau = 0.2. */
static void test_tau_by_hand(void **state)
{
    (void)state;
    const double x[5] = { 1, 2, 3, 4, 5 }, same[5] = { 10, 20, 30, 40, 50 };
    const double rev[5] = { 5, 4, 3, 2, 1 }, y[5] = { 3, 4, 1, 2, 5 };
    assert_true(fabs(drivers_kendall_tau(x, same, 5) - 1) < 1e-15);
    assert_true(fabs(drivers_kendall_tau(x, rev, 5) + 1) < 1e-15);
    assert_true(fabs(drivers_kendall_tau(x, y, 5) - 0.2) < 1e-15);
}

/* Ties as tau-b counts them: x = (1,1,2), y = (1,2,3): one pair tied in x
 * only, two concordant: 2 / sqrt(3 * 2).  A non-finite value drops its
 * pair; a constant side or fewer than two pairs is NaN. */
static void test_tau_ties_and_gaps(void **state)
{
    (void)state;
    const double x[3] = { 1, 1, 2 }, y[3] = { 1, 2, 3 };
    assert_true(fabs(drivers_kendall_tau(x, y, 3) - 2 / sqrt(6)) < 1e-15);
    const double xn[4] = { 1, NAN, 2, 3 }, yn[4] = { 1, 5, 2, 3 };
    assert_true(fabs(drivers_kendall_tau(xn, yn, 4) - 1) < 1e-15);
    const double c[3] = { 7, 7, 7 };
    assert_true(isnan(drivers_kendall_tau(c, y, 3)));
    assert_true(isnan(drivers_kendall_tau(x, y, 1)));
}

/* The bootstrap interval of tau on known data: rankings that agree on
 * every pair give 1 in every resampling, so [1, 1]; reversed, [-1, -1];
 * y = (3,4,1,2,5) (tau 0.2 over 5 configurations) gives an interval that
 * holds 0.2 and also 0: five configurations cannot show the drivers rank
 * alike.  The same seed gives the same interval; under 3 finite pairs
 * there is none. */
static void test_tau_bootstrap(void **state)
{
    (void)state;
    const double x[8] = { 1, 2, 3, 4, 5, 6, 7, 8 }, same[8] = { 2, 3, 5, 7, 11, 13, 17, 19 };
    const double rev[8] = { 8, 7, 6, 5, 4, 3, 2, 1 };
    double lo, hi;
    assert_true(fabs(drivers_kendall_tau_ci(x, same, 8, 2000, 1, &lo, &hi) - 1) < 1e-15);
    assert_true(lo == 1 && hi == 1);
    assert_true(fabs(drivers_kendall_tau_ci(x, rev, 8, 2000, 1, &lo, &hi) + 1) < 1e-15);
    assert_true(lo == -1 && hi == -1);
    const double y[5] = { 3, 4, 1, 2, 5 };
    double lo2, hi2;
    assert_true(fabs(drivers_kendall_tau_ci(x, y, 5, 2000, 46, &lo, &hi) - 0.2) < 1e-15);
    assert_true(lo < 0 && 0.2 < hi && hi <= 1 && lo >= -1);
    drivers_kendall_tau_ci(x, y, 5, 2000, 46, &lo2, &hi2);
    assert_true(lo == lo2 && hi == hi2);
    /* a NaN drops its pair; two finite pairs left: a tau but no interval */
    const double xn[3] = { 1, NAN, 3 }, yn[3] = { 1, 2, 3 };
    assert_true(fabs(drivers_kendall_tau_ci(xn, yn, 3, 2000, 1, &lo, &hi) - 1) < 1e-15);
    assert_true(isnan(lo) && isnan(hi));
}

/* The drift check on made-up calibrations (ms): runs at 10 → 10.2 and
 * 10.1 → 10 moved 2 % and 1 % within themselves, their means 10.1 and
 * 10.05 are 0.5 % apart: under the 5 % floor, no drift.  A third run at 13
 * → 13.2 (mean 13.1, 30 % above 10.05) is drift; a run that moved 40 %
 * within itself (10 → 15, mean 12.5) makes the 25 % between runs noise.  One
 * run with both figures: unavailable. */
static void test_drift(void **state)
{
    (void)state;
    double moved, noise;
    const double s1[2] = { 10, 10.1 }, e1[2] = { 10.2, 10 };
    assert_int_equal(drivers_drift(s1, e1, 2, &moved, &noise), 0);
    assert_true(fabs(moved - (10.1 / 10.05 - 1)) < 1e-12 && fabs(noise - 0.05) < 1e-12);
    const double s2[3] = { 10, 10.1, 13 }, e2[3] = { 10.2, 10, 13.2 };
    assert_int_equal(drivers_drift(s2, e2, 3, &moved, &noise), 1);
    assert_true(fabs(moved - (13.1 / 10.05 - 1)) < 1e-12);
    const double s3[2] = { 10, 10 }, e3[2] = { 15, 10 };
    assert_int_equal(drivers_drift(s3, e3, 2, &moved, &noise), 0);
    assert_true(fabs(noise - 5.0 / 12.5) < 1e-12 && fabs(moved - 0.25) < 1e-12);
    const double s4[2] = { 10, NAN }, e4[2] = { 10.2, 10 };
    assert_int_equal(drivers_drift(s4, e4, 2, &moved, &noise), -1);
    assert_true(isnan(moved) && isnan(noise));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tau_by_hand),
        cmocka_unit_test(test_tau_ties_and_gaps),
        cmocka_unit_test(test_tau_bootstrap),
        cmocka_unit_test(test_drift),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
