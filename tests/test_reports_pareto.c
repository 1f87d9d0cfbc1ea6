/* test_reports_pareto.c — Pareto front on hand-checked point sets. */
#include "reports/pareto.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

/* Points (x = ms, y = error):
 *   0 (1, 9)  front: fastest
 *   1 (2, 5)  front
 *   2 (3, 6)  dominated by 1
 *   3 (4, 2)  front
 *   4 (5, 2)  dominated by 3 (equal error, slower)
 *   5 (6, 1)  front: most accurate
 *   6 (7, 8)  dominated by 1, 3, 5
 *   7 (NaN, 0) ignored (non-finite), must not knock out 5
 *   8 (2, 5)  equal to 1: both on the front */
static void test_front_known_points(void **state)
{
    (void)state;
    double x[] = {1, 2, 3, 4, 5, 6, 7, NAN, 2};
    double y[] = {9, 5, 6, 2, 2, 1, 8, 0, 5};
    size_t out[9];
    size_t m = pareto_front(x, y, 9, out);
    size_t expect[] = {0, 1, 8, 3, 5};
    assert_int_equal(m, 5);
    for (size_t i = 0; i < m; i++)
        assert_int_equal(out[i], expect[i]);
}

static void test_front_edge_cases(void **state)
{
    (void)state;
    size_t out[3];
    assert_int_equal(pareto_front(NULL, NULL, 0, out), 0);
    double x1[] = {3}, y1[] = {4};
    assert_int_equal(pareto_front(x1, y1, 1, out), 1);
    assert_int_equal(out[0], 0);
    /* one point better in both: it alone is the front */
    double x[] = {5, 1, 3}, y[] = {5, 1, 3};
    assert_int_equal(pareto_front(x, y, 3, out), 1);
    assert_int_equal(out[0], 1);
    /* a trade-off listed slowest first comes out sorted by time */
    double xs[] = {9, 5, 1}, ys[] = {1, 5, 9};
    assert_int_equal(pareto_front(xs, ys, 3, out), 3);
    assert_int_equal(out[0], 2);
    assert_int_equal(out[1], 1);
    assert_int_equal(out[2], 0);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_front_known_points),
             cmocka_unit_test(test_front_edge_cases))
