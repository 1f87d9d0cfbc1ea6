/* test_models_predict.c — predictions of stored fits for configurations not
 * measured yet (run/fitting.h fitting_predict, used by --budget). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "run/fitting.h"

/* A fit as the store gives it back: formula, named parameters, a group. */
static dm_fit_result make_fit(const char *formula, const char *const *names, const double *values,
                              size_t n, const char *group_key, const char *group_value)
{
    dm_fit_result f = { .model = dm_xstrdup("m"), .formula = dm_xstrdup(formula),
                        .response = dm_xstrdup("WallTime") };
    f.params = dm_xcalloc(n, sizeof *f.params);
    f.n_params = n;
    for (size_t i = 0; i < n; i++)
        f.params[i] = (dm_fit_param){ dm_xstrdup(names[i]), values[i], 0.1 };
    if (group_key)
        dm_kv_push(&f.group, &f.n_group, group_key, group_value);
    return f;
}

static int predict(const dm_fit_result *f, const dm_kv *kv, size_t n, const char *key,
                   const dm_run_result *runs, size_t n_runs, double *v, char *why, size_t cap)
{
    dm_str w = {0};
    int rc = fitting_predict(f, kv, n, key, runs, n_runs, v, &w);
    snprintf(why, cap, "%s", dm_str_get(&w));
    dm_str_free(&w);
    return rc;
}

/* tess-power a + b*L^p with a = 2e6, b = 1e4, p = 1.5 at L = 16:
 * 2e6 + 1e4 * 64 = 2.64e6 ns; only inside its group (mesh = plane). */
static void axes_only(void **state)
{
    (void)state;
    static const char *const names[] = { "a", "b", "p" };
    const double values[] = { 2e6, 1e4, 1.5 };
    dm_fit_result f = make_fit("a + b*tess_level^p", names, values, 3, "mesh", "plane");
    dm_kv *kv = NULL;
    size_t n = 0;
    dm_kv_push(&kv, &n, "mesh", "plane");
    dm_kv_push(&kv, &n, "tess_level", "16");
    double v;
    char why[256];
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), 0);
    assert_true(v == 2.64e6);
    free(kv[0].value);
    kv[0].value = dm_xstrdup("cube");
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), DM_ERR_NOTFOUND);
    assert_string_equal(why, "the configuration is not in the fit's group");
    assert_true(isnan(v));
    dm_kv_free(kv, n);
    dm_fit_result_free(&f);
}

/* resolution is the pixel count: a + b*resolution at 96x54 = 5184 px. */
static void resolution_pixels(void **state)
{
    (void)state;
    static const char *const names[] = { "a", "b" };
    const double values[] = { 1e5, 20.0 };
    dm_fit_result f = make_fit("a + b*resolution", names, values, 2, NULL, NULL);
    dm_kv *kv = NULL;
    size_t n = 0;
    dm_kv_push(&kv, &n, "resolution", "96x54");
    double v;
    char why[256];
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), 0);
    assert_true(v == 1e5 + 20.0 * 5184.0);
    dm_kv_free(kv, n);
    dm_fit_result_free(&f);
}

/* One stored run: configuration "k1" (ok) with SamplesPassed = 1000 and a
 * partial-timer GPUTime, "k2" failed with SamplesPassed = 5. */
static dm_run_result stored_run(void)
{
    dm_run_result run = { .id = dm_xstrdup("r1"), .timer_verdict = dm_xstrdup("partial") };
    run.configs = dm_xcalloc(2, sizeof *run.configs);
    run.n_configs = 2;
    const char *keys[] = { "k1", "k2" };
    const double samples[] = { 1000.0, 5.0 };
    for (size_t i = 0; i < 2; i++) {
        dm_config_result *c = &run.configs[i];
        c->key = dm_xstrdup(keys[i]);
        c->ok = i == 0;
        c->counters = dm_xcalloc(2, sizeof *c->counters);
        c->n_counters = 2;
        c->counters[0] = (dm_counter_result){ .name = dm_xstrdup("SamplesPassed"),
                                              .available = 1, .value = samples[i] };
        c->counters[1] = (dm_counter_result){ .name = dm_xstrdup("GPUTime"), .available = 1,
                                              .value = 7e5 };
    }
    return run;
}

static void stored_counters(void **state)
{
    (void)state;
    static const char *const names[] = { "c0", "c_px" };
    const double values[] = { 3e5, 150.0 };
    dm_fit_result f = make_fit("c0 + c_px*SamplesPassed", names, values, 2, NULL, NULL);
    dm_run_result run = stored_run();
    dm_kv *kv = NULL;
    size_t n = 0;
    dm_kv_push(&kv, &n, "mesh", "plane");
    double v;
    char why[256];
    /* No earlier run: falls back (the caller runs a pilot frame). */
    assert_int_equal(predict(&f, kv, n, "k1", NULL, 0, &v, why, sizeof why), DM_ERR_NOTFOUND);
    assert_string_equal(why, "'SamplesPassed' is neither an axis of the configuration nor a "
                        "counter stored for it");
    /* Stored for this exact key: 3e5 + 150 * 1000. */
    assert_int_equal(predict(&f, kv, n, "k1", &run, 1, &v, why, sizeof why), 0);
    assert_true(v == 4.5e5);
    /* A failed configuration's counters and other keys are not used. */
    assert_int_equal(predict(&f, kv, n, "k2", &run, 1, &v, why, sizeof why), DM_ERR_NOTFOUND);
    assert_int_equal(predict(&f, kv, n, "k3", &run, 1, &v, why, sizeof why), DM_ERR_NOTFOUND);
    dm_fit_result_free(&f);
    /* GPUTime of a run whose timer is partial is never a variable. */
    f = make_fit("c0 + c_px*GPUTime", names, values, 2, NULL, NULL);
    assert_int_equal(predict(&f, kv, n, "k1", &run, 1, &v, why, sizeof why), DM_ERR_NOTFOUND);
    free(run.timer_verdict);
    run.timer_verdict = dm_xstrdup("full");
    assert_int_equal(predict(&f, kv, n, "k1", &run, 1, &v, why, sizeof why), 0);
    assert_true(v == 3e5 + 150.0 * 7e5);
    dm_fit_result_free(&f);
    dm_kv_free(kv, n);
    dm_run_free(&run);
}

/* A parameter missing from the fit (its term was dropped) cannot be
 * evaluated; a non-positive prediction is refused; a bad formula too. */
static void refusals(void **state)
{
    (void)state;
    static const char *const names[] = { "a", "b" };
    const double values[] = { 1.0, -2.0 };
    dm_kv *kv = NULL;
    size_t n = 0;
    dm_kv_push(&kv, &n, "tess_level", "4");
    double v;
    char why[256];
    dm_fit_result f = make_fit("a + b*tess_level + c*tess_level^2", names, values, 2, NULL, NULL);
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), DM_ERR_NOTFOUND);
    assert_non_null(strstr(why, "'c' is neither"));
    dm_fit_result_free(&f);
    f = make_fit("a + b*tess_level", names, values, 2, NULL, NULL);
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), DM_ERR_NUMERIC);
    assert_string_equal(why, "the model predicts -7, not a positive time");
    dm_fit_result_free(&f);
    f = make_fit("a + (b", names, values, 2, NULL, NULL);
    assert_int_equal(predict(&f, kv, n, "k", NULL, 0, &v, why, sizeof why), DM_ERR_PARSE);
    dm_fit_result_free(&f);
    dm_kv_free(kv, n);
}

/* pipeline-linear on a run that did not record TESInvocations: the term is
 * dropped with a warning (not turned into a free parameter) and the other
 * coefficients are recovered exactly from noiseless data
 * WallTime = 1e5 + 2·VS + 3·Prim + 0.5·SP. */
static void missing_counter_term_dropped(void **state)
{
    (void)state;
    enum { N = 8 };
    static const char *const cn[] = { "VSInvocations", "ClippingOutputPrimitives", "SamplesPassed", "WallTime" };
    dm_run_result run = { 0 };
    run.configs = dm_xcalloc(N, sizeof *run.configs);
    run.n_configs = N;
    for (int i = 0; i < N; i++) {
        dm_config_result *c = &run.configs[i];
        char key[17];
        snprintf(key, sizeof key, "%016d", i);
        c->key = dm_xstrdup(key);
        c->ok = 1;
        double vs = 1000.0 * (i + 1), prim = 700.0 * ((i * 3) % N + 1), sp = 5e4 * ((i * 5) % N + 2);
        double v[4] = { vs, prim, sp, 1e5 + 2 * vs + 3 * prim + 0.5 * sp };
        c->counters = dm_xcalloc(4, sizeof *c->counters);
        c->n_counters = 4;
        for (int k = 0; k < 4; k++)
            c->counters[k] = (dm_counter_result){ .name = dm_xstrdup(cn[k]), .available = 1, .value = v[k],
                                                  .median = v[k] };
    }
    fitting_spec spec = { .name = "pipeline-linear", .loss = FIT_LOSS_NONE };
    dm_fit_result *fits = NULL;
    size_t nf = 0;
    dm_str warn = { 0 }, err = { 0 };
    assert_int_equal(fitting_run(&spec, &run, &fits, &nf, &warn, &err), 0);
    assert_non_null(strstr(dm_str_get(&warn), "term 'c_tes*TESInvocations' dropped"));
    assert_int_equal(nf, 1);
    assert_null(strstr(fits[0].formula, "TESInvocations"));
    static const char *const pn[] = { "c0", "c_vs", "c_prim", "c_px" };
    const double want[] = { 1e5, 2, 3, 0.5 };
    assert_int_equal(fits[0].n_params, 4);
    for (int k = 0; k < 4; k++) {
        assert_string_equal(fits[0].params[k].name, pn[k]);
        assert_float_equal(fits[0].params[k].value, want[k], 1e-6 * want[k]);
    }
    for (size_t i = 0; i < nf; i++)
        dm_fit_result_free(&fits[i]);
    free(fits);
    dm_str_free(&warn);
    dm_str_free(&err);
    dm_run_free(&run);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(axes_only),
             cmocka_unit_test(resolution_pixels),
             cmocka_unit_test(stored_counters),
             cmocka_unit_test(refusals),
             cmocka_unit_test(missing_counter_term_dropped))
