/* test_models_changepoint.c — change points across runs (models/changepoint.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include "models/changepoint.h"
#include "models/rng.h"

#define N 20

/* N samples uniform in level × [0.99, 1.01]; their median into *median. */
static void samples(double *v, double level, uint64_t seed, double *median)
{
    rng_state r = rng_seed(seed);
    for (size_t i = 0; i < N; i++)
        v[i] = level * (0.99 + 0.02 * rng_uniform(&r));
    *median = level;
}

/* Runs at 1, 1, 1, 1.2, 1.21, 1.02: changes at run 3 (+20 %) and run 5
 * (−16 %); run 4 is within 5 % of run 3. */
static void finds_the_jumps(void **state)
{
    (void)state;
    static const double level[] = {1, 1, 1, 1.2, 1.21, 1.02};
    double v[6][N];
    changepoint_series s[6];
    for (size_t i = 0; i < 6; i++) {
        samples(v[i], level[i], 7 + i, &s[i].median);
        s[i].samples = v[i];
        s[i].n = N;
    }
    unsigned char change[6];
    double q[6];
    assert_int_equal(changepoint_find(s, 6, 0, 0, change, q), 2);
    static const unsigned char want[] = {0, 0, 0, 1, 0, 1};
    for (size_t i = 0; i < 6; i++)
        assert_int_equal(change[i], want[i]);
    assert_true(isnan(q[0]));
    assert_true(q[3] < 1e-4 && q[5] < 1e-4);
    /* run 4 differs significantly from run 3 (+1 %, 20 samples each) but by
     * less than the 5 % threshold: not a change */
    assert_true(q[4] < 0.01);
    /* with a 0.5 % threshold it is */
    assert_int_equal(changepoint_find(s, 6, 0, 0.005, change, NULL), 3);
    assert_int_equal(change[4], 1);
}

/* No samples on one side: no test, never a change; one run: nothing. */
static void no_samples_no_change(void **state)
{
    (void)state;
    double a[N], b[N];
    changepoint_series s[2];
    samples(a, 1, 1, &s[0].median);
    samples(b, 2, 2, &s[1].median);
    s[0].samples = a;
    s[0].n = N;
    s[1].samples = b;
    s[1].n = 0;
    unsigned char change[2];
    double q[2];
    assert_int_equal(changepoint_find(s, 2, 0, 0, change, q), 0);
    assert_true(isnan(q[1]));
    s[1].n = N;
    assert_int_equal(changepoint_find(s, 2, 0, 0, change, q), 1);
    assert_int_equal(changepoint_find(s, 1, 0, 0, change, q), 0);
    assert_int_equal(change[0], 0);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(finds_the_jumps),
             cmocka_unit_test(no_samples_no_change))
