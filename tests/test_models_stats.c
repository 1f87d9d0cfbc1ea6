/* test_models_stats.c — descriptive statistics against hand-computed values. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "models/rng.h"
#include "models/stats.h"

static void quantile_type7(void **state)
{
    (void)state;
    const double x[] = { 4, 1, 3, 2 };              /* sorted 1 2 3 4 */
    /* h = (n-1) q: q=0.25 -> h=0.75 -> 1 + 0.75*(2-1) = 1.75 */
    assert_true(stats_quantile(x, 4, 0.25) == 1.75);
    assert_true(stats_quantile(x, 4, 0.5) == 2.5);
    assert_true(stats_quantile(x, 4, 0.9) == 3.7);  /* h = 2.7 -> 3 + 0.7 */
    assert_true(stats_quantile(x, 4, 0.0) == 1.0);
    assert_true(stats_quantile(x, 4, 1.0) == 4.0);
    assert_true(isnan(stats_quantile(x, 4, 1.5)));
    assert_true(isnan(stats_quantile(x, 0, 0.5)));
    const double y[] = { NAN, 5, INFINITY, 1, 3 };  /* finite: 1 3 5 */
    assert_true(stats_median(y, 5) == 3.0);
}

static void ci_rank_rule(void **state)
{
    (void)state;
    double cov;
    /* n = 10: P(B<=1) = 11/1024, coverage(k=2) = 1 - 22/1024 = 0.978515625;
     * k = 3 would give 1 - 2*56/1024 = 0.890625 < 0.95. */
    assert_int_equal(stats_median_ci_rank(10, 0.95, &cov), 2);
    assert_true(fabs(cov - 0.978515625) < 1e-12);
    /* n = 6: k = 1 gives 1 - 2/64 = 0.96875 */
    assert_int_equal(stats_median_ci_rank(6, 0.95, &cov), 1);
    assert_true(fabs(cov - 0.96875) < 1e-12);
    /* n = 5: k = 1 gives 1 - 2/32 = 0.9375 < 0.95: no interval */
    assert_int_equal(stats_median_ci_rank(5, 0.95, NULL), 0);
    /* n = 20: P(B<=5) = 21700/2^20 = 0.0206947; P(B<=6) = 60460/2^20 = 0.0576591
     * -> k = 6 (coverage 0.958611) */
    assert_int_equal(stats_median_ci_rank(20, 0.95, &cov), 6);
    assert_true(fabs(cov - (1.0 - 2.0 * 21700.0 / 1048576.0)) < 1e-12);
}

static void summary_n10(void **state)
{
    (void)state;
    const double x[] = { 10, 1, 9, 2, 8, 3, 7, 4, 6, 5, NAN, -INFINITY };
    stats_summary s;
    assert_int_equal(stats_summarize(x, 12, 1, &s), 0);
    assert_int_equal(s.n, 10);
    assert_int_equal(s.n_nonfinite, 2);
    assert_true(s.median == 5.5);
    assert_true(s.mean == 5.5);
    assert_true(s.min == 1 && s.max == 10);
    /* sum of squares about 5.5 = 82.5; /9 */
    assert_true(fabs(s.stddev - sqrt(82.5 / 9.0)) < 1e-12);
    assert_true(fabs(s.cv - sqrt(82.5 / 9.0) / 5.5) < 1e-12);
    /* |x - 5.5| = .5 .5 1.5 1.5 2.5 2.5 3.5 3.5 4.5 4.5 -> median 2.5 */
    assert_true(s.mad == 2.5);
    /* 2nd and 9th order statistics */
    assert_true(s.ci_lo == 2.0 && s.ci_hi == 9.0);
    assert_true(fabs(s.ci_rel - 3.5 / 5.5) < 1e-12);
    assert_int_equal(s.n_outliers, 0);
}

static void summary_outliers(void **state)
{
    (void)state;
    /* 1..9 and 100: Q1 = 3.25, Q3 = 7.75 (type 7), IQR 4.5, fences
     * -3.5 .. 14.5 -> only 100 is outside. */
    const double x[] = { 1, 2, 3, 4, 5, 6, 7, 8, 9, 100 };
    stats_summary s;
    assert_int_equal(stats_summarize(x, 10, 1, &s), 0);
    assert_int_equal(s.n_outliers, 1);
    assert_true(s.median == 5.5);
}

static void summary_small_bootstrap(void **state)
{
    (void)state;
    const double x[] = { 3, 1, 2 };
    stats_summary a, b;
    assert_int_equal(stats_summarize(x, 3, 42, &a), 0);
    assert_int_equal(stats_summarize(x, 3, 42, &b), 0);
    /* bootstrap medians of 3 values lie in [1, 3]; the 2.5% quantile of
     * 2000 medians is 1 (P(median = 1) = 7/27 > 2.5%), likewise 3 above. */
    assert_true(a.ci_lo == 1.0 && a.ci_hi == 3.0);
    assert_true(a.ci_lo == b.ci_lo && a.ci_hi == b.ci_hi);
    assert_true(isnan(a.stddev) == 0 && a.stddev == 1.0);
    const double one[] = { 7 };
    assert_int_equal(stats_summarize(one, 1, 42, &a), 0);
    assert_true(a.ci_lo == 7.0 && a.ci_hi == 7.0);
    assert_true(isnan(a.stddev));
    assert_true(a.mad == 0.0);
}

static void summary_empty(void **state)
{
    (void)state;
    const double x[] = { NAN, INFINITY };
    stats_summary s;
    assert_int_equal(stats_summarize(x, 2, 1, &s), DM_ERR_ARG);
    assert_int_equal(s.n_nonfinite, 2);
    assert_int_equal(s.n, 0);
}

/* The 90 % bound of held-out errors (stats_bound90), by hand: two errors
 * ±0.1 give mean 0, s = 0.1 sqrt(2), h = t(0.95, 1) s sqrt(3/2) =
 * 6.313752 × 0.1414214 × 1.2247449 = 1.0935744; ten errors of sizes 1..10
 * (signs mixed) give the ceil(11 × 0.9) = 10th smallest, 10; nineteen
 * give the 18th; one finite error (NaN skipped) gives none. */
static void bound90_by_hand(void **state)
{
    (void)state;
    const char *how = "x";
    assert_float_equal(stats_bound90((double[]){ 0.1, -0.1 }, 2, &how), 1.0935744, 1e-6);
    assert_string_equal(how, "normal");
    /* a bias counts whole: errors 0.2 and 0.4: mean 0.3, s = 0.1 sqrt(2) */
    assert_float_equal(stats_bound90((double[]){ 0.2, 0.4 }, 2, NULL), 0.3 + 1.0935744, 1e-6);
    double e[19];
    for (int i = 0; i < 19; i++)
        e[i] = (i % 2 ? -1 : 1) * (double)(i + 1);
    assert_true(stats_bound90(e, 10, &how) == 10);
    assert_string_equal(how, "conformal");
    assert_true(stats_bound90(e, 19, NULL) == 18);
    assert_true(isnan(stats_bound90((double[]){ 0.3, NAN }, 2, &how)));
    assert_null(how);
}

/* Normal errors (bias 0.05, SD 0.1), 2000 seeded draws of n = 2 .. 8 held
 * out and a new one: the bound holds the new one at least 89 % of the
 * time for every n (nominal 90 %), where the largest of the n held out
 * holds it about n / (n + 1) of the time (under 89 % for n <= 7). */
static void bound90_covers(void **state)
{
    (void)state;
    rng_state g = rng_seed(4);
    for (size_t n = 2; n <= 8; n++) {
        int hold = 0, hold_max = 0;
        for (int t = 0; t < 2000; t++) {
            double e[9], mx = 0;
            for (size_t i = 0; i <= n; i++) {
                double u = rng_uniform(&g), v = rng_uniform(&g);
                e[i] = 0.05 + 0.1 * sqrt(-2 * log(u > 1e-300 ? u : 1e-300)) * cos(2 * M_PI * v);
            }
            for (size_t i = 0; i < n; i++)
                mx = fmax(mx, fabs(e[i]));
            hold += fabs(e[n]) <= stats_bound90(e, n, NULL);
            hold_max += fabs(e[n]) <= mx;
        }
        print_message("n %zu: bound holds %.3f, the largest held out %.3f\n", n, hold / 2000.0, hold_max / 2000.0);
        assert_true(hold >= 0.89 * 2000);
        if (n <= 7)
            assert_true(hold_max < 0.89 * 2000);
    }
}

/* The median by selection is the sorted median exactly: by hand, then on
 * 3 000 random arrays of 1-120 values with many ties (values drawn from
 * 0..k), sorted and reversed runs, against stats_median (a sort). */
static void median_inplace_is_sorted_median(void **state)
{
    (void)state;
    double odd[] = {5, 1, 4, 2, 3}, even[] = {10, -2, 7, 7, 3, 100};
    assert_true(stats_median_inplace(odd, 5) == 3);
    assert_true(stats_median_inplace(even, 6) == 7);   /* (7 + 7) / 2 */
    double two[] = {2, 1}, one[] = {-4};
    assert_true(stats_median_inplace(two, 2) == 1.5);
    assert_true(stats_median_inplace(one, 1) == -4);
    assert_true(isnan(stats_median_inplace(one, 0)));
    rng_state g = rng_seed(11);
    double v[120], w[120];
    for (int t = 0; t < 3000; t++) {
        size_t m = 1 + rng_below(&g, 120), k = 1 + rng_below(&g, t % 3 ? 8 : 1000);
        for (size_t i = 0; i < m; i++) {
            v[i] = (double)rng_below(&g, k) - (double)k / 2;
            if (t % 7 == 0)
                v[i] = (double)i;              /* sorted */
            else if (t % 7 == 1)
                v[i] = (double)(m - i) * 0.5;  /* reversed */
            w[i] = v[i];
        }
        double want = stats_median(w, m), got = stats_median_inplace(v, m);
        if (got != want)
            fail_msg("array %d (%zu values): median %.17g by selection, %.17g sorted", t, m, got, want);
    }
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(median_inplace_is_sorted_median),
             cmocka_unit_test(quantile_type7),
             cmocka_unit_test(ci_rank_rule),
             cmocka_unit_test(summary_n10),
             cmocka_unit_test(summary_outliers),
             cmocka_unit_test(summary_small_bootstrap),
             cmocka_unit_test(summary_empty),
             cmocka_unit_test(bound90_by_hand),
             cmocka_unit_test(bound90_covers))
