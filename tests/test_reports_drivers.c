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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tau_by_hand),
        cmocka_unit_test(test_tau_ties_and_gaps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
