/* The drift removed from a finished run (run/precision.h) on synthetic runs
 * whose samples carry a known drift: a scene's configurations get corrected
 * WallTime figures that put the configurations sampled only while the
 * machine was slow back at the run's speed, the raw figures untouched, the
 * rounds as recorded deciding which sample was taken when; a scene too
 * small, or one without drift, keeps its raw figures with the reason; the
 * terminal lines count both. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_util.h"
#include "models/rng.h"
#include "models/stats.h"
#include "run/precision.h"
#include "test_util.h"

#define NR 16

/* A configuration of scene with WallTime samples x[0..n). */
static void config(dm_config_result *c, const char *key, const char *scene, const double *x, size_t n)
{
    *c = (dm_config_result){ .key = dm_xstrdup(key), .scene = dm_xstrdup(scene), .ok = 1, .n_counters = 1 };
    c->counters = dm_xcalloc(1, sizeof *c->counters);
    dm_counter_result *k = &c->counters[0];
    stats_summary su;
    stats_summarize(x, n, 1, &su);
    *k = (dm_counter_result){ .name = dm_xstrdup("WallTime"), .unit = dm_xstrdup("ns"), .available = 1,
                              .has_samples = 1, .n_samples = n, .median = su.median, .value = su.median,
                              .ci_lo = su.ci_lo, .ci_hi = su.ci_hi };
    k->samples = dm_xmalloc(n * sizeof *x);
    memcpy(k->samples, x, n * sizeof *x);
}

static void round_push(dm_run_result *run, const char *scene, const char *keys)
{
    dm_round *r = dm_vec_push(&run->rounds, &run->n_rounds, NULL, sizeof *r);
    *r = (dm_round){ .scene = dm_xstrdup(scene), .seq = (long)run->n_rounds - 1, .keys = dm_xstrdup(keys),
                     .calib_ns = NAN };
}

/* Scene "a": five configurations t = 1..5 ms; the machine is 25 % slow in
 * rounds 0-3; configurations 3 and 4 ("k3", "k4") stop after round 3, the
 * others sample all NR rounds, each round in its own order.  0.3 % noise.
 * Scene "b": two configurations.  Scene "c": four, no drift, 2 % noise. */
static void make_run(dm_run_result *run)
{
    *run = (dm_run_result){ .id = dm_xstrdup("r") };
    rng_state g = rng_seed(3);
    double x[5][NR];
    size_t n[5];
    for (size_t c = 0; c < 5; c++) {
        n[c] = c >= 3 ? 4 : NR;
        for (size_t r = 0; r < n[c]; r++)
            x[c][r] = 1e6 * (double)(c + 1) * (r < 4 ? 1.25 : 1.0) * (1 + 0.003 * (2 * rng_uniform(&g) - 1));
    }
    run->configs = dm_xcalloc(11, sizeof *run->configs);
    static const char *const keys[5] = { "k0", "k1", "k2", "k3", "k4" };
    for (size_t c = 0; c < 5; c++)
        config(&run->configs[run->n_configs++], keys[c], "a", x[c], n[c]);
    for (size_t r = 0; r < NR; r++)
        round_push(run, "a", r < 4 ? (r % 2 ? "k4 k2 k0 k3 k1" : "k1 k3 k0 k2 k4") : (r % 2 ? "k2 k0 k1" : "k1 k2 k0"));
    double y[NR];
    for (size_t r = 0; r < NR; r++)
        y[r] = 2e6 * (r % 3 ? 1.0 : 1.3);
    config(&run->configs[run->n_configs++], "b0", "b", y, NR);
    config(&run->configs[run->n_configs++], "b1", "b", y, NR);
    for (size_t c = 0; c < 4; c++) {
        for (size_t r = 0; r < NR; r++)
            y[r] = 1e6 * (double)(c + 1) * exp(0.02 * (2 * rng_uniform(&g) - 1) * 1.7);
        char key[8];
        snprintf(key, sizeof key, "c%zu", c);
        config(&run->configs[run->n_configs++], key, "c", y, NR);
    }
}

static void test_scenes(void **state)
{
    (void)state;
    dm_run_result run;
    make_run(&run);
    double raw3 = run.configs[3].counters[0].median, lo3 = run.configs[3].counters[0].ci_lo;
    assert_int_equal(precision_apply(&run, 1), 1);
    assert_int_equal(run.n_precision, 3);
    const dm_scene_precision *a = &run.precision[0], *b = &run.precision[1], *c = &run.precision[2];
    assert_string_equal(a->scene, "a");
    assert_true(a->corrected && !a->reason && a->n_rounds == NR);
    assert_string_equal(a->predictor, "common mode");
    assert_true(a->machine_spread > 0.05 && a->loo_noise < 0.01);
    assert_true(a->between_runs && isfinite(a->reference_spread) && a->reference_spread > 0);
    for (size_t k = 0; k < 5; k++) {
        const dm_counter_result *w = &run.configs[k].counters[0];
        double truth = 1e6 * (double)(k + 1);
        assert_true(w->corrected);
        assert_true(fabs(w->corr_median / truth - 1) < 0.01);
        assert_true(w->corr_ci_lo <= w->corr_median && w->corr_median <= w->corr_ci_hi);
        assert_true((w->corr_ci_hi - w->corr_ci_lo) / 2 / w->corr_median < 0.02);
        /* the between-run CI holds the within-run one and the median speed's uncertainty */
        assert_true(w->corr_between && w->corr_between_lo <= w->corr_ci_lo && w->corr_ci_hi <= w->corr_between_hi);
        /* and the run's slow drift: rounds 0-3 of 16 ran 25 % slow, so the
         * earlier half's median factor is √1.25 of the later's, the half
         * shift -log 1.25 / 2 = -0.112; the only corrected scene's, so the
         * slow drift is 0.112 / √2 = 0.079 and both ends of the CI stand
         * at least 1.96 × 0.079 = 0.155 from the median (log scale); the
         * upper end was already ~log 1.25 out (replicates drawing the slow
         * rounds), and the two add in quadrature */
        double slow = log(1.25) / 2 / sqrt(2.0);
        assert_true(log(w->corr_median / w->corr_between_lo) >= 1.96 * slow * 0.97);
        assert_true(log(w->corr_between_hi / w->corr_median) >= 1.96 * slow * 0.97);
        /* the lower end was within 0.3 % of the median before: now the slow term alone */
        assert_true(fabs(log(w->corr_median / w->corr_between_lo) - 1.96 * slow) < 0.003);
    }
    assert_true(fabs(a->half_shift + log(1.25) / 2) < 0.005);
    assert_true(a->reference_spread >= log(1.25) / 2 / sqrt(2.0) * 0.97);
    assert_true(isnan(b->half_shift) && isnan(c->half_shift));
    /* the raw figures of the early-stopped configuration are kept: 25 % slow */
    assert_true(run.configs[3].counters[0].median == raw3 && run.configs[3].counters[0].ci_lo == lo3);
    assert_true(fabs(raw3 / 4e6 - 1.25) < 0.01);
    assert_false(b->corrected);
    assert_non_null(strstr(b->reason, "fewer than 3 configurations"));
    assert_false(run.configs[5].counters[0].corrected);
    assert_false(run.configs[5].counters[0].corr_between);
    assert_false(b->between_runs);
    assert_false(c->corrected);
    assert_non_null(strstr(c->reason, "no drift to remove"));
    assert_true(isfinite(c->resolvable) && c->resolvable > 0);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    precision_print(&run, 0.03, f);
    fclose(f);
    assert_non_null(strstr(text, "1 of 3 scenes corrected"));
    assert_non_null(strstr(text, "dmbench: between runs: each corrected scene's median machine speed is known to ±"));
    assert_non_null(strstr(text, "dmbench: scene b: fewer than 3 configurations"));
    assert_non_null(strstr(text, "after the calibration workload (not timed"));
    free(text);
    dm_run_free(&run);
}

/* Without recorded rounds the samples are aligned by index, and the
 * scene says so; the early-stopped configurations still line up with the
 * first rounds here, so the correction holds. */
static void test_rounds_not_recorded(void **state)
{
    (void)state;
    dm_run_result run;
    make_run(&run);
    for (size_t i = 0; i < run.n_rounds; i++) {
        free(run.rounds[i].scene);
        free(run.rounds[i].keys);
    }
    free(run.rounds);
    run.rounds = NULL;
    run.n_rounds = 0;
    precision_apply(&run, 1);
    assert_true(run.precision[0].corrected);
    assert_non_null(strstr(run.precision[0].reason, "aligned by their index"));
    dm_run_free(&run);
}

/* A round record that names a configuration once more than it has samples
 * (a process killed after recording): aligned by index, said so. */
static void test_rounds_inconsistent(void **state)
{
    (void)state;
    dm_run_result run;
    make_run(&run);
    free(run.rounds[5].keys);
    run.rounds[5].keys = dm_xstrdup("k2 k0 k1 k3");
    precision_apply(&run, 1);
    assert_non_null(run.precision[0].reason);
    assert_non_null(strstr(run.precision[0].reason, "aligned by their index"));
    dm_run_free(&run);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_scenes),
             cmocka_unit_test(test_rounds_not_recorded),
             cmocka_unit_test(test_rounds_inconsistent))
