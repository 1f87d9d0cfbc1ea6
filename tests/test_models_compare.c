/* test_models_compare.c — regression-gate statistics against hand-computed values. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "models/compare_stats.h"

static void mann_whitney_exact(void **state)
{
    (void)state;
    double u;
    /* a = 1 2 3 below b = 4 5 6: U_a = 0; P(U <= 0) = 1/C(6,3) = 1/20 -> p = 0.1 */
    const double a1[] = { 1, 2, 3 }, b1[] = { 4, 5, 6 };
    assert_true(fabs(compare_stats_mann_whitney(a1, 3, b1, 3, &u) - 0.1) < 1e-15);
    assert_true(u == 0.0);
    /* a = 1 3 5, b = 2 4 6: ranks of a 1+3+5 = 9, U = 9 - 6 = 3.  Counts of
     * U = 0..9 for sizes 3,3: 1 1 2 3 3 3 3 2 1 1 -> P(U <= 3) = 7/20,
     * p = 0.7 */
    const double a2[] = { 5, 1, 3 }, b2[] = { 6, 2, 4 };
    assert_true(fabs(compare_stats_mann_whitney(a2, 3, b2, 3, &u) - 0.7) < 1e-15);
    assert_true(u == 3.0);
    /* symmetric: b against a has U = 9 - 3 = 6 and the same p */
    assert_true(fabs(compare_stats_mann_whitney(b2, 3, a2, 3, &u) - 0.7) < 1e-15);
    assert_true(u == 6.0);
    /* non-finite values are ignored */
    const double a3[] = { 1, NAN, 2, 3 };
    assert_true(fabs(compare_stats_mann_whitney(a3, 4, b1, 3, &u) - 0.1) < 1e-15);
    assert_true(isnan(compare_stats_mann_whitney(a1, 0, b1, 3, NULL)));
}

static void mann_whitney_ties_normal(void **state)
{
    (void)state;
    /* a = 1 2 2, b = 2 3 4: sorted 1 2 2 2 3 4, midranks 1 3 3 3 5 6.
     * R_a = 1+3+3 = 7, U = 7 - 6 = 1.  mu = 4.5, one tie group t = 3:
     * sum(t^3-t) = 24; var = 9/12 * (7 - 24/30) = 4.65.
     * z = (|1 - 4.5| - 0.5)/sqrt(4.65) = 1.391217..., p = erfc(z/sqrt 2)
     * = 0.16415972847851523 */
    const double a[] = { 1, 2, 2 }, b[] = { 2, 3, 4 };
    double u;
    assert_true(fabs(compare_stats_mann_whitney(a, 3, b, 3, &u) - 0.16415972847851523) < 1e-12);
    assert_true(u == 1.0);
    const double c[] = { 5, 5 }, d[] = { 5, 5, 5 };
    assert_true(compare_stats_mann_whitney(c, 2, d, 3, &u) == 1.0);
}

static void benjamini_hochberg(void **state)
{
    (void)state;
    /* ascending 0.005 0.01 0.03 0.04 -> p n/k = 0.02 0.02 0.04 0.04 */
    const double p[] = { 0.01, 0.04, 0.03, 0.005 };
    double q[4];
    compare_stats_bh(p, 4, q);
    assert_true(fabs(q[0] - 0.02) < 1e-15 && fabs(q[1] - 0.04) < 1e-15);
    assert_true(fabs(q[2] - 0.04) < 1e-15 && fabs(q[3] - 0.02) < 1e-15);
    /* monotone step-up: 0.02*2/1 = 0.04 is lowered to 0.03*2/2 = 0.03 */
    const double p2[] = { 0.02, 0.03 };
    compare_stats_bh(p2, 2, q);
    assert_true(fabs(q[0] - 0.03) < 1e-15 && fabs(q[1] - 0.03) < 1e-15);
    /* capped at 1 */
    const double p3[] = { 0.9, 0.8 };
    compare_stats_bh(p3, 2, q);
    assert_true(q[0] == 0.9 && q[1] == 0.9);
}

static void ratio_ci(void **state)
{
    (void)state;
    double base[10], slow[10];
    for (int i = 0; i < 10; i++) {
        base[i] = 100.0;
        slow[i] = 110.0;
    }
    compare_ratio r, r2;
    assert_int_equal(compare_stats_ratio_ci(base, 10, slow, 10, 0.95, 1, &r), 0);
    assert_true(fabs(r.ratio - 1.1) < 1e-15 && fabs(r.lo - 1.1) < 1e-15 && fabs(r.hi - 1.1) < 1e-15);
    for (int i = 0; i < 10; i++) {
        base[i] = 10.0 + i;
        slow[i] = 2.0 * base[i];
    }
    assert_int_equal(compare_stats_ratio_ci(base, 10, slow, 10, 0.95, 9, &r), 0);
    assert_int_equal(compare_stats_ratio_ci(base, 10, slow, 10, 0.95, 9, &r2), 0);
    assert_true(r.ratio == 2.0);
    assert_true(r.lo < 2.0 && r.hi > 2.0);
    /* extreme bounds: max(new)/min(base)-type limits 38/10 and 20/19 */
    assert_true(r.lo > 20.0 / 19.0 && r.hi < 38.0 / 10.0);
    assert_true(r.lo == r2.lo && r.hi == r2.hi);
    double zero[3] = { 0, 0, 0 };
    assert_int_equal(compare_stats_ratio_ci(zero, 3, slow, 10, 0.95, 9, &r), DM_ERR_ARG);
    assert_int_equal(compare_stats_ratio_ci(base, 10, slow, 10, 1.5, 9, &r), DM_ERR_ARG);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(mann_whitney_exact),
             cmocka_unit_test(mann_whitney_ties_normal),
             cmocka_unit_test(benjamini_hochberg),
             cmocka_unit_test(ratio_ci))
