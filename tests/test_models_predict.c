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
#include "models/rng.h"
#include "models/stats.h"
#include "run/fitting.h"
#include "run/predict.h"

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

/* A synthetic pom frame: counts of one configuration and its Instructions
 * before the error law (the stage-instructions model's own terms). */
#define SYN_C0 2e5
#define SYN_PX 60.0
#define SYN_STEP 9.0
static void syn_counts(int w, int h, int d, int steps, double *vs, double *prim, double *fs, double *instr)
{
    double px = (double)w * h;
    *vs = 400.0 * d + 100;
    *prim = 300.0 * d * d;
    *fs = px * 0.5 + 2.0 * sqrt(px) * d;
    *instr = SYN_C0 + SYN_PX * *fs + SYN_STEP * *fs * steps;
}

/* A pom target never measured: its plan (density 1, WxH, `steps`; free
 * its params with dm_kv_free), its counts and its true Instructions. */
static void syn_target(int w, int h, int steps, plan_config *pc, double counts[PREDICT_N_COUNTS], double *instr)
{
    char res[32], st[16];
    snprintf(res, sizeof res, "%dx%d", w, h);
    snprintf(st, sizeof st, "%d", steps);
    *pc = (plan_config){ .key = "00000000000000ff" };
    dm_kv_push(&pc->params, &pc->n_params, "mesh_density", "1");
    dm_kv_push(&pc->params, &pc->n_params, "resolution", res);
    dm_kv_push(&pc->params, &pc->n_params, "steps", st);
    dm_kv_push(&pc->params, &pc->n_params, "technique", "pom");
    double vs, prim, fs;
    syn_counts(w, h, 1, steps, &vs, &prim, &fs, instr);
    const double c[PREDICT_N_COUNTS] = {vs, 0, prim, fs, NAN, NAN, NAN, NAN, NAN};
    memcpy(counts, c, sizeof c);
}

static void syn_counter(dm_config_result *c, const char *name, double v)
{
    dm_counter_result *r = dm_vec_push(&c->counters, &c->n_counters, NULL, sizeof *r);
    memset(r, 0, sizeof *r);
    r->name = dm_xstrdup(name);
    r->unit = dm_xstrdup("items");
    r->available = r->deterministic = 1;
    r->value = r->median = v;
}

/* One configuration of pom at WxH, density d, `steps`, its Instructions
 * the model's times exp(err) and, when wall > 0, a WallTime. */
static void syn_config(dm_run_result *run, int w, int h, int d, int steps, double err, double wall)
{
    dm_config_result *c = dm_vec_push(&run->configs, &run->n_configs, NULL, sizeof *c);
    memset(c, 0, sizeof *c);
    c->key = dm_xasprintf("%016zx", (size_t)(w * 7 + h * 13 + d * 1000 + steps * 100000));
    c->ok = 1;
    char v[32];
    dm_kv_push(&c->params, &c->n_params, "technique", "pom");
    snprintf(v, sizeof v, "%d", steps);
    dm_kv_push(&c->params, &c->n_params, "steps", v);
    snprintf(v, sizeof v, "%d", d);
    dm_kv_push(&c->params, &c->n_params, "mesh_density", v);
    snprintf(v, sizeof v, "%dx%d", w, h);
    dm_kv_push(&c->params, &c->n_params, "resolution", v);
    double vs, prim, fs, instr;
    syn_counts(w, h, d, steps, &vs, &prim, &fs, &instr);
    syn_counter(c, "VSInvocations", vs);
    syn_counter(c, "TESInvocations", 0);
    syn_counter(c, "ClippingOutputPrimitives", prim);
    syn_counter(c, "FSInvocations", fs);
    syn_counter(c, "Instructions", instr * exp(err));
    if (wall > 0)
        syn_counter(c, "WallTime", wall);
}

/* A standard normal variate (Box-Muller). */
static double syn_normal(rng_state *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    return sqrt(-2 * log(1 - u)) * cos(2 * M_PI * v);
}

/* Held-out groups' intervals cover a target at a step count never
 * measured.  The error law: ln(measured / model) = u_s + e, u_s ~ N(0,
 * SU) shared by the configurations of one step count (what a new value
 * of an axis brings), e ~ N(0, SE) each.  Fitted on steps 4, 8, 12, 16 x
 * three resolutions x two densities, the target at steps 20 (its own
 * u and e) lies in the Instructions interval in at least 90 % of the
 * trials, less 3 binomial SDs for T trials; and the bound is no wider
 * than twice the error law's own 90 % bound (1.645 sqrt(SU^2 + SE^2)),
 * so an interval too wide to mean anything fails too. */
#define SU 0.04
#define SE 0.01
#define TRIALS 60
static void group_coverage(void **state)
{
    (void)state;
    static const int res[3][2] = {{64, 64}, {96, 64}, {128, 96}};
    rng_state rng = rng_seed(49);
    int covered = 0;
    double *q = dm_xcalloc(TRIALS, sizeof *q);
    for (int t = 0; t < TRIALS; t++) {
        dm_run_result run = {0};
        for (int s = 4; s <= 16; s += 4) {
            double u = SU * syn_normal(&rng);
            for (int k = 0; k < 3; k++)
                for (int d = 1; d <= 2; d++)
                    syn_config(&run, res[k][0], res[k][1], d, s, u + SE * syn_normal(&rng), 0);
        }
        predict_model m;
        predict_fit(&run, 1, &m);
        plan_config pc;
        double counts[PREDICT_N_COUNTS], instr;
        syn_target(96, 64, 20, &pc, counts, &instr);
        double meas = instr * exp(SU * syn_normal(&rng) + SE * syn_normal(&rng));
        predict_result r;
        dm_str why = {0};
        assert_int_equal(predict_config(&m, &pc, counts, &r, &why), 0);
        assert_string_equal(r.calibration, "held-out groups");
        assert_non_null(strstr(r.calibration_why, "steps=20 never measured"));
        /* 4 step counts, 3 resolutions: a refit that predicts none of its
         * group (its fit refused) is not counted */
        assert_true(m.groups.n_groups >= 2 && m.groups.n_groups <= 7);
        assert_true(r.instr_lo > 0 && r.instr_lo < r.instr && r.instr < r.instr_hi);
        covered += r.instr_lo <= meas && meas <= r.instr_hi;
        q[t] = m.groups.instr_q;
        predict_result_free(&r);
        dm_str_free(&why);
        dm_kv_free(pc.params, pc.n_params);
        predict_free(&m);
        dm_run_free(&run);
    }
    double cov = (double)covered / TRIALS, tol = 3 * sqrt(0.9 * 0.1 / TRIALS);
    double law = 1.645 * sqrt(SU * SU + SE * SE), qmed = stats_median(q, TRIALS);
    fprintf(stderr, "held-out groups: %d of %d targets covered (%.3f, at least %.3f); median bound %.4f, "
            "the law's %.4f\n", covered, TRIALS, cov, 0.9 - tol, qmed, law);
    assert_true(cov >= 0.9 - tol);
    assert_true(qmed <= 2 * law);
    free(q);
}

/* An axis of two values is never held out (the rest would not vary it):
 * a target at a third resolution has no Instructions interval, and the
 * reason names the axis, its values and the rule. */
static void group_two_values(void **state)
{
    (void)state;
    dm_run_result run = {0};
    for (int s = 4; s <= 16; s += 4)
        for (int k = 0; k < 2; k++)
            syn_config(&run, k ? 128 : 64, k ? 96 : 64, 1, s, 0.001 * s * (k + 1), 0);
    predict_model m;
    predict_fit(&run, 1, &m);
    plan_config pc;
    double counts[PREDICT_N_COUNTS], instr;
    syn_target(160, 120, 8, &pc, counts, &instr);
    predict_result r;
    dm_str why = {0};
    assert_int_equal(predict_config(&m, &pc, counts, &r, &why), 0);
    assert_int_equal(m.groups.n_groups, 4);   /* the step counts only */
    assert_string_equal(r.calibration, "leave-one-out, groups unavailable");
    assert_true(isnan(r.instr_lo) && isnan(r.instr_hi));
    assert_string_equal(r.instr_why, "resolution=160x120 never measured by the runs, and the runs measured 2 "
                                     "values of resolution, and a group of them is held out only when the rest "
                                     "still vary it (3 values)");
    /* a step count measured, at a resolution measured: leave-one-out */
    predict_result_free(&r);
    dm_kv_free(pc.params, pc.n_params);
    syn_target(128, 96, 8, &pc, counts, &instr);
    assert_int_equal(predict_config(&m, &pc, counts, &r, &why), 0);
    assert_string_equal(r.calibration, "leave-one-out");
    assert_null(r.calibration_why);
    predict_result_free(&r);
    dm_str_free(&why);
    dm_kv_free(pc.params, pc.n_params);
    predict_free(&m);
    dm_run_free(&run);
}

/* The machine between runs: ten configurations measured by two runs, the
 * second's WallTime exp(0.01 i) times the first's (i = 1..10).  Each gives
 * 0.01 i sqrt((1 + 1/2) / 2), and the split-conformal bound of ten is the
 * ceil(11 x 0.9) = 10th smallest: 0.1 sqrt(0.75).  One run: 10 % (the
 * documented PREDICT_RUN_SPREAD), counted as 0 configurations. */
static void between_runs(void **state)
{
    (void)state;
    dm_run_result runs[2] = {{0}, {0}};
    for (int k = 0; k < 2; k++)
        for (int i = 1; i <= 10; i++)
            syn_config(&runs[k], 64 + 8 * i, 64, 1, 4 * (1 + i % 3), 0, 1e6 * exp(k * 0.01 * i));
    predict_model m;
    predict_fit(runs, 2, &m);
    fprintf(stderr, "between runs: %.9g over %d, want %.9g\n", m.between.q, m.between.n, 0.1 * sqrt(0.75));
    assert_int_equal(m.between.n, 10);
    assert_float_equal(m.between.q, 0.1 * sqrt(0.75), 1e-12);
    predict_free(&m);
    predict_fit(runs, 1, &m);
    assert_int_equal(m.between.n, 0);
    assert_float_equal(m.between.q, log1p(PREDICT_RUN_SPREAD), 1e-15);
    predict_free(&m);
    dm_run_free(&runs[0]);
    dm_run_free(&runs[1]);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(axes_only),
             cmocka_unit_test(resolution_pixels),
             cmocka_unit_test(stored_counters),
             cmocka_unit_test(refusals),
             cmocka_unit_test(missing_counter_term_dropped),
             cmocka_unit_test(group_coverage),
             cmocka_unit_test(group_two_values),
             cmocka_unit_test(between_runs))
