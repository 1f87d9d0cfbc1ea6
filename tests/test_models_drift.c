/* Drift removal (models/drift.h) on synthetic scenes with known times,
 * known drift and known noise: a drift multiplied into the times is removed
 * to within the noise (the corrected CIs cover the known value, and are
 * narrow where the raw ones are wide); with no drift the corrected CIs
 * still cover the true value at least as often as the raw ones and are no
 * narrower (the correction's uncertainty is in them); the calibration
 * figure that follows the drift is the better predictor when the common
 * mode is absent; between two runs whose machines differ by a known common
 * factor the between-run CI covers the truth where the within-run one,
 * conditional on the run's median speed, does not; the preview for extra
 * rounds (point_only) is the corrected samples' own median and CI,
 * checked against values computed here by hand; a scene too small is
 * left raw with the reason. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/drift.h"
#include "models/rng.h"
#include "test_util.h"

#define NC 6
#define NR 20

/* A standard normal by Box-Muller from the seeded generator. */
static double gauss(rng_state *g)
{
    double u = rng_uniform(g), v = rng_uniform(g);
    return sqrt(-2 * log(u > 1e-300 ? u : 1e-300)) * cos(2 * M_PI * v);
}

/* x[c][r] = t[c] * d[r] * exp(noise * N(0,1)); t[c] = 1 + c ms. */
static void scene(double *x, const double *d, double noise, rng_state *g)
{
    for (size_t c = 0; c < NC; c++)
        for (size_t r = 0; r < NR; r++)
            x[c * NR + r] = 1e6 * (double)(c + 1) * d[r] * exp(noise * gauss(g));
}

static double median_of(const double *v, size_t n)
{
    double t[NR];
    memcpy(t, v, n * sizeof *v);
    for (size_t i = 1; i < n; i++)
        for (size_t j = i; j > 0 && t[j - 1] > t[j]; j--) {
            double s = t[j];
            t[j] = t[j - 1];
            t[j - 1] = s;
        }
    return n % 2 ? t[n / 2] : (t[n / 2 - 1] + t[n / 2]) / 2;
}

/* A drift of ±20 % with 0.5 % noise: every corrected median is
 * t[c] × median(d) within 1 %, the corrected CI covers it and is under
 * ±1.5 %, the raw CI is over ±5 %, and the round factors follow d. */
static void test_known_drift_removed(void **state)
{
    (void)state;
    rng_state g = rng_seed(7);
    double d[NR], x[NC * NR];
    for (size_t r = 0; r < NR; r++)
        d[r] = 1 + 0.2 * sin(1.7 * (double)r);
    scene(x, d, 0.005, &g);
    double md = median_of(d, NR);
    drift_result out;
    assert_int_equal(drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .seed = 3 }, &out), 0);
    assert_true(out.corrected && out.helps);
    for (size_t c = 0; c < NC; c++) {
        const drift_config *k = &out.configs[c];
        double truth = 1e6 * (double)(c + 1) * md;
        assert_int_equal(k->n, NR);
        assert_true(fabs(k->median / truth - 1) < 0.01);
        assert_true(k->lo <= truth && truth <= k->hi);
        assert_true((k->hi - k->lo) / 2 / k->median < 0.015);
        assert_true((k->raw_hi - k->raw_lo) / 2 / k->raw_median > 0.05);
    }
    for (size_t r = 0; r < NR; r++)
        assert_true(fabs(out.round_factor[r] / (d[r] / md) - 1) < 0.01);
    assert_true(out.loo_noise < 0.01 && out.raw_noise > 0.05);
    assert_true(out.machine_spread > 0.05);
    drift_result_free(&out);
}

/* No drift, 2 % noise, 200 scenes: the corrected CI covers the true time
 * at least 93 % of the time (nominal 95 %), no less often than the raw CI
 * less 2 points, and its mean width is at least the raw one's — the
 * correction adds the noise of its own estimate and never narrows the CI
 * of samples it cannot improve; the run reports that it does not help. */
static void test_no_drift_not_narrower(void **state)
{
    (void)state;
    rng_state g = rng_seed(11);
    double d[NR], x[NC * NR];
    for (size_t r = 0; r < NR; r++)
        d[r] = 1;
    size_t cover = 0, cover_raw = 0, n = 0, helped = 0;
    double w = 0, w_raw = 0;
    for (int trial = 0; trial < 200; trial++) {
        scene(x, d, 0.02, &g);
        drift_result out;
        drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .seed = (uint64_t)trial,
                                     .bootstrap = 200 }, &out);
        assert_true(out.corrected);
        helped += (size_t)out.helps;
        for (size_t c = 0; c < NC; c++) {
            const drift_config *k = &out.configs[c];
            double truth = 1e6 * (double)(c + 1);
            cover += k->lo <= truth && truth <= k->hi;
            cover_raw += k->raw_lo <= truth && truth <= k->raw_hi;
            w += (k->hi - k->lo) / truth;
            w_raw += (k->raw_hi - k->raw_lo) / truth;
            n++;
        }
        drift_result_free(&out);
    }
    print_message("no drift: coverage corrected %.3f raw %.3f, width corrected %.4f raw %.4f, helped %zu/200\n",
                  (double)cover / n, (double)cover_raw / n, w / n, w_raw / n, helped);
    assert_true((double)cover / n >= 0.93);
    assert_true(cover + n / 50 >= cover_raw);
    assert_true(w >= w_raw);
    assert_true(helped < 10);
}

/* Configurations that stopped early (3 of 6 have 5 samples, taken while
 * the machine was 20 % slow): the correction puts them at the run's median
 * speed, where the raw median is 20 % off. */
static void test_early_stop_rebased(void **state)
{
    (void)state;
    rng_state g = rng_seed(5);
    double d[NR], x[NC * NR];
    for (size_t r = 0; r < NR; r++)
        d[r] = r < 5 ? 1.2 : 1.0;
    scene(x, d, 0.003, &g);
    for (size_t c = 0; c < 3; c++)
        for (size_t r = 5; r < NR; r++)
            x[c * NR + r] = NAN;
    drift_result out;
    drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .seed = 1 }, &out);
    assert_true(out.corrected);
    for (size_t c = 0; c < 3; c++) {
        double truth = 1e6 * (double)(c + 1);
        assert_int_equal(out.configs[c].n, 5);
        assert_true(fabs(out.configs[c].raw_median / truth - 1.2) < 0.01);
        assert_true(fabs(out.configs[c].median / truth - 1) < 0.01);
        assert_true(out.configs[c].lo <= truth && truth <= out.configs[c].hi);
    }
    drift_result_free(&out);
}

/* A calibration workload whose time follows the drift exactly predicts
 * it: the noise left after dividing by its ratio is the configurations'
 * own noise; a round without calibration is left out of that figure. */
static void test_calibration_predictor(void **state)
{
    (void)state;
    rng_state g = rng_seed(9);
    double d[NR], x[NC * NR], cal[NR];
    for (size_t r = 0; r < NR; r++) {
        d[r] = 1 + 0.15 * sin((double)r);
        cal[r] = 5e6 * d[r];
    }
    scene(x, d, 0.004, &g);
    drift_result out;
    drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .calib = cal, .seed = 1 }, &out);
    assert_true(out.corrected);
    assert_true(out.calib_noise < 0.006 && out.raw_noise > 0.05);
    assert_true(out.calib_spread > 0.05);
    cal[3] = NAN;   /* a round without calibration is left out, not zero */
    drift_result_free(&out);
    drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .calib = cal, .seed = 1 }, &out);
    assert_true(out.calib_noise < 0.006);
    drift_result_free(&out);
}

/* One run of a stationary machine: each round's speed drawn afresh,
 * log-normal with median k and spread 8 %, 2 % noise per sample. */
static void run_of(double *x, double k, rng_state *g)
{
    double d[NR];
    for (size_t r = 0; r < NR; r++)
        d[r] = k * exp(0.08 * gauss(g));
    scene(x, d, 0.02, g);
}

/* 100 pairs of runs, the second on a machine 4 % slower throughout (the
 * truth: t[c] in run A, 1.04 t[c] in run B, the machine's median speed
 * being 1).  The between-run CI contains the configuration's true time in
 * at least 90 % of (trial, configuration) cases, in both runs, and always
 * contains the within-run CI; the within-run CI, conditional on each run's
 * own median speed, contains it in under 80 % (it leaves that speed's
 * uncertainty out, which is the point); and after dividing run B by the
 * known 1.04 the two runs' between-run CIs overlap in at least 95 % of
 * cases (the agreement target). */
static void test_between_runs_cover(void **state)
{
    (void)state;
    rng_state g = rng_seed(21);
    double xa[NC * NR], xb[NC * NR];
    const double k = 1.04;
    size_t cover_b = 0, cover_w = 0, agree = 0, n = 0;
    for (int trial = 0; trial < 100; trial++) {
        run_of(xa, 1, &g);
        run_of(xb, k, &g);
        drift_result a, b;
        drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = xa, .seed = (uint64_t)trial,
                                     .bootstrap = 200 }, &a);
        drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = xb, .seed = (uint64_t)trial + 1000,
                                     .bootstrap = 200 }, &b);
        assert_true(a.corrected && b.corrected);
        assert_true(isfinite(a.reference_spread) && a.reference_spread > 0);
        for (size_t c = 0; c < NC; c++) {
            const drift_config *p = &a.configs[c], *q = &b.configs[c];
            double t = 1e6 * (double)(c + 1);
            assert_true(p->between_lo <= p->lo && p->hi <= p->between_hi);
            assert_true(q->between_lo <= q->lo && q->hi <= q->between_hi);
            cover_b += (p->between_lo <= t && t <= p->between_hi) + (q->between_lo <= k * t && k * t <= q->between_hi);
            cover_w += (p->lo <= t && t <= p->hi) + (q->lo <= k * t && k * t <= q->hi);
            agree += p->between_lo <= q->between_hi / k && q->between_lo / k <= p->between_hi;
            n++;
        }
        drift_result_free(&a);
        drift_result_free(&b);
    }
    print_message("between runs: truth covered by the between-run CI %.3f, the within-run CI %.3f; "
                  "runs agree after the known factor %.3f\n", (double)cover_b / (2.0 * (double)n),
                  (double)cover_w / (2.0 * (double)n), (double)agree / (double)n);
    assert_true((double)cover_b >= 0.90 * 2.0 * (double)n);
    assert_true((double)cover_w < 0.80 * 2.0 * (double)n);
    assert_true((double)agree >= 0.95 * (double)n);
}

/* The bootstrap's block: n^(1/3) rounds, rounded, at least 1. */
static void test_block_rounds(void **state)
{
    (void)state;
    assert_int_equal(drift_block_rounds(0), 1);
    assert_int_equal(drift_block_rounds(3), 1);
    assert_int_equal(drift_block_rounds(4), 2);
    assert_int_equal(drift_block_rounds(42), 3);
    assert_int_equal(drift_block_rounds(43), 4);
    assert_int_equal(drift_block_rounds(91), 4);
    assert_int_equal(drift_block_rounds(92), 5);
}

/* The half shift: the later half's median round factor against the
 * earlier half's, the middle round of an odd count left out, NaN rounds
 * skipped, NaN with fewer than six. */
static void test_half_shift(void **state)
{
    (void)state;
    const double even[] = { 1.1, 1.1, 1.1, 1.0, 1.0, 1.0 };
    assert_float_equal(drift_half_shift(even, 6), -log(1.1), 1e-12);
    /* halves {1.0, 1.2, 1.1} and {1.3, 1.5, 1.4}: medians 1.1 and 1.4; 9.9 the middle */
    const double odd[] = { 1.0, 1.2, 1.1, 9.9, 1.3, 1.5, 1.4 };
    assert_float_equal(drift_half_shift(odd, 7), log(1.4 / 1.1), 1e-12);
    const double gaps[] = { 1.0, NAN, 1.0, 1.0, NAN, 1.2, 1.2, 1.2 };
    assert_float_equal(drift_half_shift(gaps, 8), log(1.2), 1e-12);
    assert_true(isnan(drift_half_shift(gaps, 7)));   /* five finite */
    const double flat[] = { 1, 1, 1, 1, 1, 1, 1, 1 };
    assert_float_equal(drift_half_shift(flat, 8), 0, 0);
}

/* A host whose speed in a round depends on the last round's (log speed an
 * AR(1) series, correlation 0.4 from round to round, spread 8 %; 60
 * rounds, 2 % noise per sample), as the quiet default runs' rounds do:
 * 100 pairs of runs as above.  Rounds drawn one by one leave out how far
 * a correlated series' median moves: the between-run CI covered the
 * truth in 82.3 % of cases, and with blocks of drift_block_rounds (4)
 * rounds in 87.8 % (at correlation 0.6: 70.0 and 81.3 %).  Blocks of
 * n^(1/3) rounds take back part of what independent draws leave out, not
 * all of it; the test holds them to 4 points more and 85 %. */
#define NRA 60
#define RHO 0.4
static void test_between_runs_correlated_rounds(void **state)
{
    (void)state;
    size_t cover[2] = { 0, 0 }, n = 0;
    for (int blocked = 0; blocked < 2; blocked++) {
        rng_state g = rng_seed(33);
        for (int trial = 0; trial < 100; trial++) {
            double x[NC * NRA];
            double ls = 0.08 * gauss(&g);
            for (size_t r = 0; r < NRA; r++) {
                ls = RHO * ls + sqrt(1 - RHO * RHO) * 0.08 * gauss(&g);
                for (size_t c = 0; c < NC; c++)
                    x[c * NRA + r] = 1e6 * (double)(c + 1) * exp(ls + 0.02 * gauss(&g));
            }
            drift_result a;
            drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NRA, .x = x, .seed = (uint64_t)trial,
                                         .bootstrap = 200, .block = blocked ? 0 : 1 }, &a);
            assert_true(a.corrected);
            for (size_t c = 0; c < NC; c++) {
                double t = 1e6 * (double)(c + 1);
                cover[blocked] += a.configs[c].between_lo <= t && t <= a.configs[c].between_hi;
            }
            n += blocked == 0 ? NC : 0;
            drift_result_free(&a);
        }
    }
    print_message("correlated rounds: truth covered by the between-run CI %.3f with rounds drawn one by one, "
                  "%.3f in blocks of %zu\n", (double)cover[0] / (double)n, (double)cover[1] / (double)n,
                  drift_block_rounds(NRA));
    assert_true(cover[1] >= cover[0] + n / 25);   /* 4 points more, at least */
    assert_true((double)cover[1] >= 0.85 * (double)n);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The preview for extra rounds (point_only): five configurations follow
 * the drift exactly and one has 3 % noise of its own, so the common mode
 * without it is known: log d[r] less the median of log d.  Its corrected
 * samples are therefore x[0][r] / (d[r] / exp(that median)), and the
 * preview's median and CI are the median and the binomial order-statistic
 * interval of those, computed here by sorting; no bootstrap: no between-run
 * CI, no reference spread. */
static void test_point_only_known_answer(void **state)
{
    (void)state;
    rng_state g = rng_seed(17);
    double d[NR], x[NC * NR], ld[NR], y[NR];
    for (size_t r = 0; r < NR; r++) {
        d[r] = 1 + 0.25 * sin(0.9 * (double)r);
        ld[r] = log(d[r]);
    }
    scene(x, d, 0, &g);
    for (size_t r = 0; r < NR; r++)
        x[r] *= exp(0.03 * gauss(&g));
    qsort(ld, NR, sizeof *ld, cmp_double);
    double centre = (ld[NR / 2 - 1] + ld[NR / 2]) / 2;
    for (size_t r = 0; r < NR; r++)
        y[r] = x[r] / exp(log(d[r]) - centre);
    qsort(y, NR, sizeof *y, cmp_double);
    /* the largest k with P(k <= B <= n - k) >= 0.95 for B ~ Binomial(20, 1/2) */
    size_t k = 0;
    for (size_t j = 1; 2 * j <= NR; j++) {
        double tail = 0;
        for (size_t i = 0; i < j; i++)
            tail += exp(lgamma(NR + 1.0) - lgamma((double)i + 1) - lgamma((double)(NR - i) + 1) - NR * log(2.0));
        if (1 - 2 * tail < 0.95)
            break;
        k = j;
    }
    assert_int_equal(k, 6);
    drift_result out;
    drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .seed = 2, .point_only = 1 }, &out);
    assert_true(out.corrected);
    const drift_config *c = &out.configs[0];
    print_message("point only: median %.6g (by hand %.6g), CI [%.6g, %.6g] (by hand [%.6g, %.6g])\n",
                  c->median, (y[NR / 2 - 1] + y[NR / 2]) / 2, c->lo, c->hi, y[k - 1], y[NR - k]);
    assert_true(fabs(c->median / ((y[NR / 2 - 1] + y[NR / 2]) / 2) - 1) < 1e-9);
    assert_true(fabs(c->lo / y[k - 1] - 1) < 1e-9 && fabs(c->hi / y[NR - k] - 1) < 1e-9);
    assert_true(isnan(c->between_lo) && isnan(c->between_hi) && isnan(out.reference_spread));
    drift_result full;
    drift_correct(&(drift_desc){ .n_configs = NC, .n_rounds = NR, .x = x, .seed = 2, .bootstrap = 200 }, &full);
    assert_true(full.configs[0].median == c->median);   /* the same point correction */
    assert_true(full.configs[0].lo <= c->lo && c->hi <= full.configs[0].hi);   /* the hull is wider */
    drift_result_free(&full);
    drift_result_free(&out);
}

/* Two configurations: raw figures only, with the reason; fewer than 3
 * rounds with 3 configurations: the same; no samples: DM_ERR_ARG. */
static void test_too_small(void **state)
{
    (void)state;
    double x[2 * 4] = { 1, 2, 3, 4, 2, 4, 6, 8 };
    drift_result out;
    assert_int_equal(drift_correct(&(drift_desc){ .n_configs = 2, .n_rounds = 4, .x = x }, &out), 0);
    assert_false(out.corrected);
    assert_non_null(strstr(out.why, "fewer than 3 configurations"));
    assert_true(out.configs[1].raw_median == 5 && isnan(out.configs[1].median));
    assert_true(isnan(out.configs[1].between_lo) && isnan(out.configs[1].between_hi));
    assert_true(isnan(out.reference_spread));
    drift_result_free(&out);
    double y[3 * 4] = { 1, 2, NAN, NAN, 1, 2, NAN, NAN, 1, NAN, 3, 3 };
    assert_int_equal(drift_correct(&(drift_desc){ .n_configs = 3, .n_rounds = 4, .x = y }, &out), 0);
    assert_false(out.corrected);
    assert_non_null(strstr(out.why, "fewer than 3 rounds"));
    drift_result_free(&out);
    assert_int_not_equal(drift_correct(&(drift_desc){ .n_configs = 0, .n_rounds = 4, .x = y }, &out), 0);
    drift_result_free(&out);
    assert_true(fabs(drift_robust_sd((double[]){ 1, 2, 3, NAN }, 4) - 1.4826) < 1e-12);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_known_drift_removed),
             cmocka_unit_test(test_no_drift_not_narrower),
             cmocka_unit_test(test_early_stop_rebased),
             cmocka_unit_test(test_calibration_predictor),
             cmocka_unit_test(test_between_runs_cover),
             cmocka_unit_test(test_block_rounds),
             cmocka_unit_test(test_half_shift),
             cmocka_unit_test(test_between_runs_correlated_rounds),
             cmocka_unit_test(test_point_only_known_answer),
             cmocka_unit_test(test_too_small))
