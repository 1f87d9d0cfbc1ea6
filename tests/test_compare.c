/* Unit tests of the regression gate (gate/): verdicts on
 * synthetic runs with known differences, fingerprint checks, failed and
 * added/removed configurations, quality limits, outputs, loading from
 * results.json / run directories / the store, and accepted baselines. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "gate/compare.h"
#include "run/calibrate.h"
#include "store/store.h"
#include "models/rng.h"
#include "models/stats.h"
#include "reports/report.h"

/* One file of the report writer table to path (report_write_run). */
static int write_report_file(const dm_run_result *run, const char *file, const char *dir,
                             const char *path, const char *href)
{
    char err[512];
    report_desc d = {.dir = dir, .href = href, .file = file, .path = path};
    return report_write_run(run, &d, err, sizeof err);
}

/* ---- synthetic runs ----------------------------------------------------- */

/* Standard normal deviate (Box-Muller) from a seeded generator. */
static double gauss(rng_state *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    return sqrt(-2.0 * log(1.0 - u)) * cos(2.0 * M_PI * v);
}

static void set_env(dm_run_result *r, const char *cpu)
{
    dm_kv_push(&r->environment, &r->n_environment, "renderer", "llvmpipe (LLVM 15.0.6, 256 bits)");
    dm_kv_push(&r->environment, &r->n_environment, "gl_version", "4.5 (Core Profile) Mesa 22.3.6");
    dm_kv_push(&r->environment, &r->n_environment, "lp_num_threads", "1");
    dm_kv_push(&r->environment, &r->n_environment, "cpu", cpu);
    dm_kv_push(&r->environment, &r->n_environment, "cpu_count", "2");
}

/* WallTime with n samples around median_ns with relative noise cv. */
static void timed(dm_counter_result *c, size_t n, double median_ns, double cv, uint64_t seed)
{
    rng_state r = rng_seed(seed);
    c->name = dm_xstrdup("WallTime");
    c->unit = dm_xstrdup("ns");
    c->available = c->has_samples = 1;
    c->n_samples = n;
    c->samples = dm_xcalloc(n, sizeof(double));
    for (size_t i = 0; i < n; i++)
        c->samples[i] = median_ns * (1.0 + cv * gauss(&r));
    c->value = c->median = median_ns;
}

static void det(dm_counter_result *c, const char *name, double v)
{
    c->name = dm_xstrdup(name);
    c->unit = dm_xstrdup("items");
    c->available = c->deterministic = 1;
    c->value = v;
}

/* A run of n_cfg configurations (mesh=m<i>), each with WallTime (n samples,
 * median 1e6*(i+1)*scale, noise cv; samples seeded by seed+i),
 * TESInvocations 3169 and SamplesPassed 1000*(i+1), and quality PSNR 40,
 * SSIM 0.98. */
static void make_run(dm_run_result *r, const char *id, size_t n_cfg, size_t n, double scale,
                     double cv, uint64_t seed)
{
    memset(r, 0, sizeof *r);
    r->id = dm_xstrdup(id);
    r->sweep = dm_xstrdup("synthetic");
    r->started = dm_xstrdup("2026-01-01T00:00:00Z");
    r->timer_verdict = dm_xstrdup("partial");
    set_env(r, "Test CPU @ 3GHz");
    r->n_configs = n_cfg;
    r->configs = dm_xcalloc(n_cfg, sizeof *r->configs);
    for (size_t i = 0; i < n_cfg; i++) {
        dm_config_result *c = &r->configs[i];
        test_config_init(c, i);
        dm_kv_push(&c->params, &c->n_params, "technique", "normal");
        c->n_counters = 3;
        c->counters = dm_xcalloc(3, sizeof *c->counters);
        timed(&c->counters[0], n, 1e6 * (double)(i + 1) * scale, cv, seed + i);
        det(&c->counters[1], "TESInvocations", 3169);
        det(&c->counters[2], "SamplesPassed", 1000.0 * (double)(i + 1));
        c->quality.present = 1;
        c->quality.psnr = 40;
        c->quality.ssim = 0.98;
    }
}

static dm_counter_result *counter(dm_run_result *r, size_t cfg, const char *name)
{
    return (dm_counter_result *)dm_config_counter(&r->configs[cfg], name);
}

static int run_compare(const dm_run_result *b, const dm_run_result *n, const compare_desc *d,
                       compare_result *out)
{
    dm_str err = {0};
    int rc = compare_runs(b, n, d, out, &err);
    dm_str_free(&err);
    return rc;
}

static const compare_item *item(const compare_result *r, const char *key)
{
    for (size_t i = 0; i < r->n_items; i++)
        if (strcmp(r->items[i].key, key) == 0)
            return &r->items[i];
    fail_msg("no item %s", key);
    return NULL;
}

/* ---- verdicts ----------------------------------------------------------- */

static void test_self_all_pass(void **state)
{
    (void)state;
    dm_run_result a;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &a, &d, &r), 0);
    assert_int_equal(r.n_items, 3);
    assert_int_equal(r.count[COMPARE_PASS], 3);
    for (size_t i = 0; i < 3; i++) {
        assert_true(r.items[i].timed);
        assert_true(r.items[i].ratio == 1.0);   /* same samples: same medians */
        assert_true(r.items[i].lo >= 0.95 && r.items[i].hi <= 1.05);
        assert_null(r.items[i].note);
    }
    assert_true(fabs(r.geomean - 1.0) < 1e-15);
    assert_int_equal(r.n_geomean, 3);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
}

static void test_deterministic_change(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 2, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 2, 30, 1.0, 0.02, 100);
    counter(&b, 1, "TESInvocations")->value = 3170;
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    const compare_item *it = item(&r, "0000000000000002");
    assert_int_equal(it->verdict, COMPARE_REGRESSION);
    assert_int_equal(it->n_changes, 1);
    assert_string_equal(it->changes[0].counter, "TESInvocations");
    assert_true(it->changes[0].base == 3169 && it->changes[0].new_ == 3170);
    assert_string_equal(it->note, "TESInvocations changed 3169 -> 3170");
    assert_int_equal(r.items[0].verdict, COMPARE_REGRESSION);   /* worst first */
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_PASS);
    assert_int_equal(compare_exit_code(&r), 1);
    compare_result_free(&r);
    /* a tolerance of 1e-3 admits 1/3169 = 3.2e-4; 1e-4 does not */
    compare_tolerance tol = { "TESInvocations", 1e-3 };
    d.tolerances = &tol;
    d.n_tolerances = 1;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    tol.rel = 1e-4;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 1);
    compare_result_free(&r);
    /* a counter unavailable on NEW is a change too */
    counter(&b, 1, "TESInvocations")->value = 3169;
    counter(&b, 0, "SamplesPassed")->available = 0;
    d.n_tolerances = 0;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_string_equal(item(&r, "0000000000000001")->note, "SamplesPassed unavailable on NEW");
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_slowdown_20_percent_regression(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 4, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 4, 30, 1.2, 0.02, 200);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 4);
    for (size_t i = 0; i < 4; i++) {
        const compare_item *it = &r.items[i];
        assert_true(it->lo > 1.05);
        assert_true(it->ratio > 1.15 && it->ratio < 1.25);
        assert_true(it->q < 0.01);
        assert_non_null(strstr(it->note, "slower"));
    }
    assert_true(r.geomean > 1.15 && r.geomean < 1.25);
    assert_int_equal(compare_exit_code(&r), 1);
    compare_result_free(&r);
    /* the other way round it is an improvement, which passes */
    assert_int_equal(run_compare(&b, &a, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_IMPROVEMENT], 4);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_slowdown_1_percent_pass(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 4, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 4, 30, 1.01, 0.02, 200);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_PASS], 4);
    for (size_t i = 0; i < 4; i++)
        assert_true(r.items[i].lo >= 0.95 && r.items[i].hi <= 1.05);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_huge_noise_inconclusive(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 10, 1.0, 0.4, 100);
    make_run(&b, "B", 3, 10, 1.0, 0.4, 200);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 3);
    assert_int_equal(r.count[COMPARE_REGRESSION], 0);
    for (size_t i = 0; i < 3; i++) {
        const compare_item *it = &r.items[i];
        assert_true(it->lo < 0.95 || it->hi > 1.05);
        /* the estimate follows its formula: n f - n, f the larger squared
         * ratio of (CI side length) / (distance to the threshold it crosses) */
        double rr = it->ratio, f = 0;
        if (it->lo < 0.95 && rr >= 0.95)
            f = pow((rr - it->lo) / (rr - 0.95), 2);
        if (it->hi > 1.05 && rr <= 1.05)
            f = fmax(f, pow((it->hi - rr) / (1.05 - rr), 2));
        if (rr > 1.05)
            f = pow((rr - it->lo) / (rr - 1.05), 2);
        if (rr < 0.95)
            f = pow((it->hi - rr) / (0.95 - rr), 2);
        /* ... and at least enough for the detectable change to reach 5 % */
        double det = (it->hi - it->lo) / 2 / rr;
        assert_true(fabs(it->detectable - det) <= 1e-12);
        assert_true(det > 0.05);
        f = fmax(f, pow(det / 0.05, 2));
        double need = ceil(10 * f - 10);
        assert_int_equal(it->extra_samples, need < 1 ? 1 : (long)need);
        assert_true(it->extra_samples > 0);
    }
    assert_int_equal(compare_exit_code(&r), 3);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* Every INCONCLUSIVE names the smallest change its data could detect
 * (the CI half-width over the ratio), in the note and in the JSON field. */
static void test_inconclusive_states_detectable(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 10, 1.0, 0.1, 100);
    make_run(&b, "B", 3, 10, 1.0, 0.1, 200);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    for (size_t i = 0; i < r.n_items; i++) {
        const compare_item *it = &r.items[i];
        if (it->verdict != COMPARE_INCONCLUSIVE)
            continue;
        char want[96];
        snprintf(want, sizeof want, "could detect changes >= %.1f%% (threshold 5.0%%)",
                 (it->hi - it->lo) / 2 / it->ratio * 100);
        assert_non_null(strstr(it->note, want));
        /* "about N more samples per side", or past COMPARE_ADVICE_MAX "more than 100 samples per side" */
        assert_non_null(strstr(it->note, "samples per side"));
        assert_non_null(strstr(it->note, "more"));
    }
    assert_true(r.count[COMPARE_INCONCLUSIVE] > 0);
    compare_result_free(&r);
    d.paired = 1;      /* paired mode counts rounds */
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    for (size_t i = 0; i < r.n_items; i++)
        if (r.items[i].verdict == COMPARE_INCONCLUSIVE)
            assert_non_null(strstr(r.items[i].note, " rounds"));
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* A run against itself passes however noisy it is: the same samples on
 * both sides are a ratio of exactly 1, never INCONCLUSIVE. */
static void test_identical_noisy_pass(void **state)
{
    (void)state;
    dm_run_result a;
    make_run(&a, "A", 4, 5, 1.0, 0.4, 100);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &a, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_PASS], 4);
    for (size_t i = 0; i < r.n_items; i++) {
        assert_true(r.items[i].timed);
        assert_true(r.items[i].lo == 1.0);
        assert_true(r.items[i].hi == 1.0);
    }
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
}

/* Adds Instructions (per frame) to every configuration of r. */
static void add_instructions(dm_run_result *r, double per_frame)
{
    for (size_t i = 0; i < r->n_configs; i++) {
        dm_config_result *c = &r->configs[i];
        c->counters = dm_xrealloc(c->counters, (c->n_counters + 1) * sizeof *c->counters);
        memset(&c->counters[c->n_counters], 0, sizeof *c->counters);
        det(&c->counters[c->n_counters++], "Instructions", per_frame * (double)(i + 1));
    }
}

/* Instructions decide by the threshold alone, whatever the timing noise:
 * +0.6 % is REGRESSION at 0.5 % and PASS at 1 %, +0.4 % PASS, -1 %
 * IMPROVEMENT; unavailable on NEW is a change. */
static void test_instructions_threshold(void **state)
{
    (void)state;
    static const struct { double scale, threshold; compare_verdict want; int exit_code; } cases[] = {
        { 1.006, 0, COMPARE_REGRESSION, 1 }, { 1.006, 0.01, COMPARE_PASS, 0 },
        { 1.004, 0, COMPARE_PASS, 0 }, { 0.99, 0, COMPARE_IMPROVEMENT, 0 }, { 1.0, 0, COMPARE_PASS, 0 },
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        dm_run_result a, b;
        make_run(&a, "A", 3, 5, 1.0, 0.4, 100);   /* timing far too noisy to decide */
        make_run(&b, "B", 3, 5, 1.0, 0.4, 200);
        add_instructions(&a, 1e9);
        add_instructions(&b, 1e9 * cases[k].scale);
        compare_desc d = { .threshold = cases[k].threshold };
        compare_result r;
        assert_int_equal(run_compare(&a, &b, &d, &r), 0);
        for (size_t i = 0; i < r.n_items; i++) {
            assert_int_equal(r.items[i].verdict, cases[k].want);
            assert_true(r.items[i].instr);
            assert_true(fabs(r.items[i].instr_new / r.items[i].instr_base - cases[k].scale) <= 1e-12);
        }
        assert_int_equal(compare_exit_code(&r), cases[k].exit_code);
        compare_result_free(&r);
        dm_run_free(&a);
        dm_run_free(&b);
    }
    dm_run_result a, b;
    make_run(&a, "A", 2, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 2, 30, 1.0, 0.02, 100);
    add_instructions(&a, 1e9);
    add_instructions(&b, 1e9);
    counter(&b, 0, "Instructions")->available = 0;
    compare_desc d = { .counters_only = 1 };
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_REGRESSION);
    assert_non_null(strstr(item(&r, "0000000000000001")->note, "Instructions unavailable on NEW"));
    assert_int_equal(item(&r, "0000000000000002")->verdict, COMPARE_PASS);
    compare_result_free(&r);
    /* counted on another CPU: not compared (JIT target and libc pick other
     * code), said in a warning; a 10 % change then passes */
    counter(&b, 0, "Instructions")->available = 1;
    counter(&b, 0, "Instructions")->value *= 1.1;
    free(b.environment[3].value);
    b.environment[3].value = dm_xstrdup("Other CPU");
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_PASS], 2);
    assert_int_equal(r.n_warnings, 1);
    assert_non_null(strstr(r.warnings[0], "Instructions not compared"));
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_env_mismatch(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 2, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 2, 30, 1.0, 0.02, 100);
    free(b.environment[3].value);
    b.environment[3].value = dm_xstrdup("Other CPU");
    compare_desc d = {0};
    compare_result r;
    dm_str err = {0};
    assert_int_equal(compare_runs(&a, &b, &d, &r, &err), DM_ERR_ARG);
    assert_int_equal(r.n_env_diffs, 1);
    assert_string_equal(r.env_diffs[0], "cpu: 'Test CPU @ 3GHz' (BASE) vs 'Other CPU' (NEW)");
    assert_non_null(strstr(dm_str_get(&err), "--allow-env-mismatch"));
    dm_str_free(&err);
    compare_result_free(&r);
    d.allow_env_mismatch = 1;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.n_warnings, 1);
    assert_non_null(strstr(r.warnings[0], "differ"));
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    /* counters only: a CPU change does not matter, a driver change does */
    d.allow_env_mismatch = 0;
    d.counters_only = 1;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.n_warnings, 0);
    assert_int_equal(r.count[COMPARE_PASS], 2);
    assert_int_equal(r.n_geomean, 0);
    assert_false(r.items[0].timed);
    compare_result_free(&r);
    free(b.environment[1].value);
    b.environment[1].value = dm_xstrdup("4.5 (Core Profile) Mesa 23.0.0");
    assert_int_equal(run_compare(&a, &b, &d, &r), DM_ERR_ARG);
    assert_int_equal(r.n_env_diffs, 1);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_counters_only_ignores_time(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 2, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 2, 30, 2.0, 0.02, 200);
    compare_desc d = { .counters_only = 1 };
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    counter(&b, 0, "SamplesPassed")->value = 999;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 1);
    assert_string_equal(r.items[0].note, "SamplesPassed changed 1000 -> 999");
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_failed_added_removed(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 3, 30, 1.0, 0.02, 100);
    b.configs[0].ok = 0;
    b.configs[0].reason = dm_xstrdup("shader link failed");
    free(b.configs[2].key);
    b.configs[2].key = dm_xstrdup("00000000000000ff");
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.n_items, 2);
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_REGRESSION);
    assert_string_equal(item(&r, "0000000000000001")->note, "failed on NEW: shader link failed");
    assert_int_equal(r.n_removed, 1);
    assert_string_equal(r.removed[0], "m2 · normal [0000000000000003]");   /* the one label */
    assert_int_equal(r.n_added, 1);
    assert_string_equal(r.added[0], "m2 · normal [00000000000000ff]");
    compare_result_free(&r);
    /* failed on both sides: skipped, not a regression */
    a.configs[0].ok = 0;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_SKIPPED);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* "normal" stands for a user technique here: everything else is built in. */
static int only_normal_is_user(const char *technique) { return strcmp(technique, "normal") != 0; }

/* A user technique's key changes with its file: the configurations of equal
 * parameters are paired and compared, the label says the source changed;
 * a built-in technique's changed key stays removed + added. */
static void test_user_technique_source_changed(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 3, 30, 1.0, 0.02, 100);
    free(b.configs[2].key);
    b.configs[2].key = dm_xstrdup("00000000000000ff");
    compare_desc d = {.builtin_technique = only_normal_is_user};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.n_items, 3);
    assert_int_equal(r.n_removed + r.n_added, 0);
    dm_str want = {0};
    report_config_label(&a, &a.configs[2], &want);
    dm_str_cat(&want, " (technique source changed: key 0000000000000003 -> 00000000000000ff)");
    assert_string_equal(item(&r, "0000000000000003")->label, dm_str_get(&want));
    dm_str_free(&want);
    compare_result_free(&r);
    d.builtin_technique = NULL;   /* every technique built in: not paired */
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.n_items, 2);
    assert_int_equal(r.n_removed, 1);
    assert_int_equal(r.n_added, 1);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_quality_drop(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 3, 30, 1.0, 0.02, 100);
    b.configs[0].quality.psnr = 38.5;     /* 1.5 dB drop > 1 dB */
    b.configs[1].quality.psnr = 39.5;     /* 0.5 dB: within the limit */
    b.configs[2].quality.ssim = 0.965;    /* 0.015 > 0.01 */
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_REGRESSION);
    assert_non_null(strstr(item(&r, "0000000000000001")->note, "PSNR dropped 1.50 dB"));
    assert_int_equal(item(&r, "0000000000000002")->verdict, COMPARE_PASS);
    assert_int_equal(item(&r, "0000000000000003")->verdict, COMPARE_REGRESSION);
    assert_non_null(strstr(item(&r, "0000000000000003")->note, "SSIM dropped 0.0150"));
    compare_result_free(&r);
    /* identical images (infinite PSNR) on both sides: no drop */
    a.configs[1].quality.psnr = b.configs[1].quality.psnr = INFINITY;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(item(&r, "0000000000000002")->verdict, COMPARE_PASS);
    compare_result_free(&r);
    d.psnr_drop = 2.0;
    d.ssim_drop = 0.02;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* FLIP: a rise of the mean over flip_rise (default 0.005) fails; at the
 * limit passes; a side without FLIP (NaN, runs from before it) is not
 * checked. */
static void test_flip_rise(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 3, 30, 1.0, 0.02, 100);
    for (size_t i = 0; i < 3; i++)
        a.configs[i].quality.flip = 0.0400;
    b.configs[0].quality.flip = 0.0460;   /* +0.006 > 0.005 */
    b.configs[1].quality.flip = 0.0450;   /* +0.005: at the limit */
    b.configs[2].quality.flip = NAN;      /* not computed on NEW */
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(item(&r, "0000000000000001")->verdict, COMPARE_REGRESSION);
    assert_string_equal(item(&r, "0000000000000001")->note,
                        "FLIP rose 0.0060 (0.0400 -> 0.0460; limit 0.0050)");
    assert_int_equal(item(&r, "0000000000000002")->verdict, COMPARE_PASS);
    assert_int_equal(item(&r, "0000000000000003")->verdict, COMPARE_PASS);
    assert_true(r.desc.flip_rise == 0.005);
    compare_result_free(&r);
    d.flip_rise = 0.01;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

static void test_partial_gputime_refused(void **state)
{
    (void)state;
    dm_run_result a;
    make_run(&a, "A", 1, 30, 1.0, 0.02, 100);
    free(a.configs[0].counters[0].name);
    a.configs[0].counters[0].name = dm_xstrdup("GPUTime");
    a.configs[0].counters[0].partial = 1;
    compare_desc d = { .time_counter = "GPUTime" };
    compare_result r;
    assert_int_equal(run_compare(&a, &a, &d, &r), DM_ERR_ARG);
    compare_result_free(&r);
    dm_run_free(&a);
}

/* ---- files, outputs, store, baselines ---------------------------------- */

typedef struct tmp { char dir[32]; } tmp;

static int tmp_setup(void **state)
{
    tmp *t = dm_xcalloc(1, sizeof *t);
    strcpy(t->dir, "/tmp/dmcompareXXXXXX");
    assert_non_null(mkdtemp(t->dir));
    *state = t;
    return 0;
}

static int tmp_teardown(void **state)
{
    tmp *t = *state;
    test_rm_rf(t->dir);
    free(t);
    return 0;
}

static void test_json_roundtrip_and_outputs(void **state)
{
    tmp *t = *state;
    dm_run_result a, b, la, lb;
    make_run(&a, "A", 3, 30, 1.0, 0.02, 100);
    make_run(&b, "B", 3, 30, 1.0, 0.02, 100);
    counter(&b, 2, "TESInvocations")->value = 6144;
    char *dir = dm_xasprintf("%s/run-b", t->dir), *fa = dm_xasprintf("%s/a.json", t->dir);
    char *fb = dm_xasprintf("%s/results.json", dir);
    assert_int_equal(dm_mkdirs(dir), 0);
    assert_int_equal(write_report_file(&a, "results.json", NULL, fa, NULL), 0);
    assert_int_equal(write_report_file(&b, "results.json", NULL, fb, NULL), 0);
    dm_str err = {0};
    assert_int_equal(compare_load_path(fa, &la, &err), 0);
    assert_int_equal(compare_load_path(dir, &lb, &err), 0);   /* a run directory */
    dm_run_result none;
    assert_int_equal(compare_load_path("/nonexistent/x.json", &none, &err), DM_ERR_NOTFOUND);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(compare_runs(&la, &lb, &d, &r, &err), 0);
    assert_int_equal(compare_exit_code(&r), 1);
    assert_string_equal(r.items[0].note, "TESInvocations changed 3169 -> 6144");
    char *md = dm_xasprintf("%s/c.md", t->dir), *ju = dm_xasprintf("%s/c.xml", t->dir);
    char *js = dm_xasprintf("%s/c.json", t->dir);
    assert_int_equal(compare_write_markdown(&r, NULL, md), 0);
    assert_int_equal(compare_write_junit(&r, ju), 0);
    assert_int_equal(compare_write_json(&r, js), 0);
    char *text = test_slurp(md);
    assert_non_null(strstr(text, "| Configuration | Base | New | Ratio | Change | 95% CI of ratio | Verdict | Note |"));
    assert_non_null(strstr(text, "| m2 · normal | 3.000 ms | 3.000 ms | "));
    assert_non_null(strstr(text, " REGRESSION | TESInvocations changed 3169 → 6144 |"));
    free(text);
    text = test_slurp(ju);
    assert_non_null(strstr(text, "tests=\"3\" failures=\"1\""));
    assert_non_null(strstr(text, "<failure message=\"REGRESSION: TESInvocations changed 3169 -&gt; 6144\"/>"));
    assert_null(strstr(text, "time=\"0\""));
    for (size_t i = 0; i < lb.n_configs; i++) {   /* each test case's time: NEW's median, seconds */
        const dm_counter_result *w = dm_config_counter(&lb.configs[i], "WallTime");
        char *want = dm_xasprintf("[%s]\" time=\"%.9f\">", lb.configs[i].key, w->median / 1e9);
        assert_true(w->median > 0);
        assert_non_null(strstr(text, want));
        free(want);
    }
    free(text);
    text = test_slurp(js);
    assert_non_null(strstr(text, "\"REGRESSION\":\t1"));
    assert_non_null(strstr(text, "\"exit_code\":\t1"));
    /* a changed counter and the quality carry base and new values */
    assert_non_null(strstr(text, "\"counter\":\t\"TESInvocations\",\n"));
    assert_non_null(strstr(text, "\"base\":\t3169,\n"));
    assert_non_null(strstr(text, "\"new\":\t6144"));
    assert_non_null(strstr(text, "\"PSNR_base\":\t40,\n"));
    assert_non_null(strstr(text, "\"SSIM_new\":\t0.98"));
    free(text);
    free(md);
    free(ju);
    free(js);
    compare_result_free(&r);
    dm_str_free(&err);
    dm_run_free(&a);
    dm_run_free(&b);
    dm_run_free(&la);
    dm_run_free(&lb);
    free(dir);
    free(fa);
    free(fb);
}

/* A store with runs r1 (tag "main") and r2 (tag "pr"). */
static char *make_store(const char *dir)
{
    char *path = dm_xasprintf("%s/dmbench.sqlite", dir);
    store *s = NULL;
    dm_str err = {0};
    assert_int_equal(store_open(path, &s, &err), 0);
    const char *ids[] = { "r1", "r2" }, *tags[] = { "main", "pr" };
    for (int k = 0; k < 2; k++) {
        dm_run_result run;
        make_run(&run, ids[k], 2, 10, 1.0 + k, 0.02, 100);
        free(run.started);
        run.started = dm_xasprintf("2026-01-0%dT00:00:00Z", k + 1);
        assert_int_equal(store_run_begin(s, &run, tags[k]), 0);
        for (size_t i = 0; i < run.n_configs; i++)
            assert_int_equal(store_config_put(s, ids[k], &run.configs[i]), 0);
        dm_run_free(&run);
    }
    store_close(s);
    dm_str_free(&err);
    return path;
}

static void test_store_and_baselines(void **state)
{
    tmp *t = *state;
    char *path = make_store(t->dir);
    dm_run_result a, b;
    dm_str err = {0};
    assert_int_equal(compare_load_store(path, NULL, "main", &a, &err), 0);
    assert_string_equal(a.id, "r1");
    assert_int_equal(compare_load_store(path, "r2", NULL, &b, &err), 0);
    assert_int_equal(b.n_configs, 2);
    dm_run_free(&a);
    dm_run_free(&b);
    assert_int_equal(compare_load_store(path, NULL, "nope", &a, &err), DM_ERR_NOTFOUND);
    /* baselines */
    char *id = NULL, *why = NULL;
    assert_int_equal(compare_baseline_latest(path, NULL, &id, NULL, &err), DM_ERR_NOTFOUND);
    assert_int_equal(compare_baseline_accept(path, "r1", "", &err), DM_ERR_ARG);
    assert_int_equal(compare_baseline_accept(path, "r9", "x", &err), DM_ERR_NOTFOUND);
    assert_int_equal(compare_baseline_accept(path, "r1", "first", &err), 0);
    assert_int_equal(compare_baseline_accept(path, "r2", "2x slower on purpose", &err), 0);
    assert_int_equal(compare_baseline_latest(path, "synthetic", &id, &why, &err), 0);
    assert_string_equal(id, "r2");
    assert_string_equal(why, "2x slower on purpose");
    free(id);
    free(why);
    assert_int_equal(compare_baseline_latest(path, "other-sweep", &id, NULL, &err), DM_ERR_NOTFOUND);
    char *bl = compare_baselines_path(path), *text = test_slurp(bl);
    assert_non_null(strstr(text, "\"reason\":\t\"first\""));
    free(text);
    free(bl);
    dm_str_free(&err);
    free(path);
}

/* ---- exact counters through the store and results.json (issue 27) ----- */

/* ShadingEfficiency = 705/1160 (its 15-digit text reads back one ULP off),
 * its integer parts, and WallTime samples of full precision. */
static void add_shading(dm_run_result *r)
{
    for (size_t i = 0; i < r->n_configs; i++) {
        dm_config_result *c = &r->configs[i];
        c->counters = dm_xrealloc(c->counters, (c->n_counters + 2) * sizeof *c->counters);
        memset(&c->counters[c->n_counters], 0, 2 * sizeof *c->counters);
        det(&c->counters[c->n_counters++], "FSInvocations", 1160);
        det(&c->counters[c->n_counters], "ShadingEfficiency", 0.60775862068965514);
        free(c->counters[c->n_counters].unit);
        c->counters[c->n_counters++].unit = dm_xstrdup("ratio");
    }
}

/* The two ways one run is read back must agree bit for bit. */
static void assert_same_bits(const dm_run_result *a, const dm_run_result *b)
{
    assert_int_equal(a->n_configs, b->n_configs);
    for (size_t i = 0; i < a->n_configs; i++)
        for (size_t k = 0; k < a->configs[i].n_counters; k++) {
            const dm_counter_result *x = &a->configs[i].counters[k];
            const dm_counter_result *y = dm_config_counter(&b->configs[i], x->name);
            assert_non_null(y);
            assert_memory_equal(&x->value, &y->value, sizeof x->value);
            assert_int_equal(x->n_samples, y->n_samples);
            if (x->n_samples)
                assert_memory_equal(x->samples, y->samples, x->n_samples * sizeof *x->samples);
        }
}

/* Runs A and B (the same measurements) each in the store and in a
 * results.json; the counters gate passes in all four pairings and the
 * sides read back identical doubles. */
static void test_store_file_four_pairings(void **state)
{
    tmp *t = *state;
    char *path = dm_xasprintf("%s/dmbench.sqlite", t->dir);
    const char *ids[] = { "A", "B" };
    char *files[2];
    store *s = NULL;
    dm_str err = {0};
    assert_int_equal(store_open(path, &s, &err), 0);
    for (int k = 0; k < 2; k++) {
        dm_run_result run;
        make_run(&run, ids[k], 3, 12, 1.0 / 3.0, 0.02, 7);
        add_shading(&run);
        assert_int_equal(store_run_begin(s, &run, NULL), 0);
        for (size_t i = 0; i < run.n_configs; i++)
            assert_int_equal(store_config_put(s, ids[k], &run.configs[i]), 0);
        files[k] = dm_xasprintf("%s/%s.json", t->dir, ids[k]);
        assert_int_equal(write_report_file(&run, "results.json", NULL, files[k], NULL), 0);
        dm_run_free(&run);
    }
    store_close(s);
    dm_run_result side[2][2];   /* [run][0 store, 1 file] */
    for (int k = 0; k < 2; k++) {
        assert_int_equal(compare_load_store(path, ids[k], NULL, &side[k][0], &err), 0);
        assert_int_equal(compare_load_path(files[k], &side[k][1], &err), 0);
        assert_same_bits(&side[k][0], &side[k][1]);
        assert_true(dm_config_counter(&side[k][1].configs[0], "ShadingEfficiency")->value ==
                    0.60775862068965514);
    }
    for (int fb = 0; fb < 2; fb++)
        for (int fn = 0; fn < 2; fn++) {
            compare_desc d = { .counters_only = 1 };
            compare_result r;
            assert_int_equal(run_compare(&side[0][fb], &side[1][fn], &d, &r), 0);
            assert_int_equal(r.count[COMPARE_PASS], 3);
            assert_int_equal(compare_exit_code(&r), 0);
            compare_result_free(&r);
        }
    for (int k = 0; k < 2; k++) {
        dm_run_free(&side[k][0]);
        dm_run_free(&side[k][1]);
        free(files[k]);
    }
    dm_str_free(&err);
    free(path);
}

/* A floating derived counter within COMPARE_DERIVED_EPS passes; beyond it,
 * and any change of an integer count, is a change. */
static void test_derived_epsilon(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_run(&a, "A", 2, 10, 1.0, 0.02, 1);
    make_run(&b, "B", 2, 10, 1.0, 0.02, 1);
    add_shading(&a);
    add_shading(&b);
    counter(&b, 0, "ShadingEfficiency")->value = nextafter(0.60775862068965514, 1.0);
    compare_desc d = { .counters_only = 1 };
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(compare_exit_code(&r), 0);
    compare_result_free(&r);
    counter(&b, 0, "ShadingEfficiency")->value = 0.60775862068965514 * (1 + 1e-11);
    counter(&b, 1, "FSInvocations")->value = 1161;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 2);
    assert_non_null(strstr(item(&r, "0000000000000001")->note, "ShadingEfficiency changed"));
    assert_string_equal(item(&r, "0000000000000002")->note, "FSInvocations changed 1160 -> 1161");
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* ---- timing between runs (issue 27, item 1) ----------------------------- */

/* A run of n_cfg configurations sharing one scene, measured in n rounds:
 * WallTime of configuration i in round r = 1e6 (i+1) * scale * round[r] *
 * (1 + cv N(0,1)) (round NULL: 1), CPUTime = WallTime / cpu_scale, and the
 * load average at its start. */
static void make_scene_run(dm_run_result *r, const char *id, size_t n_cfg, size_t n, double scale,
                           double cpu_scale, double cv, uint64_t seed, double load,
                           const double *round)
{
    make_run(r, id, n_cfg, n, scale, cv, seed);
    char buf[64];
    snprintf(buf, sizeof buf, "%.2f 0.00 0.00", load);
    dm_kv_push(&r->environment, &r->n_environment, "load_average", buf);
    for (size_t i = 0; i < n_cfg; i++) {
        dm_config_result *c = &r->configs[i];
        free(c->scene);
        c->scene = dm_xstrdup("plane@96x54");
        dm_counter_result *w = &c->counters[0];
        for (size_t k = 0; round && k < n; k++)
            w->samples[k] *= round[k];
        c->counters = dm_xrealloc(c->counters, (c->n_counters + 1) * sizeof *c->counters);
        w = &c->counters[0];
        dm_counter_result *cpu = &c->counters[c->n_counters++];
        memset(cpu, 0, sizeof *cpu);
        timed(cpu, n, 1, 0, 0);
        free(cpu->name);
        cpu->name = dm_xstrdup("CPUTime");
        for (size_t k = 0; k < n; k++)
            cpu->samples[k] = w->samples[k] / cpu_scale;
        w->median = w->value = stats_median(w->samples, n);
        cpu->median = cpu->value = stats_median(cpu->samples, n);
    }
}

/* Two runs of one binary, the second on a machine that became 8 % slower
 * between them (CPU time too: a host that slowed the CPU) — within the
 * between-run spread: the within-run CI alone clears 5 %, yet the verdict
 * is not REGRESSION, and the note says why and what to do. */
static void test_between_run_shift_within_spread(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_scene_run(&a, "A", 6, 20, 1.0, 1.0, 0.01, 10, 0.8, NULL);
    make_scene_run(&b, "B", 6, 20, 1.08, 1.0, 0.01, 50, 0.9, NULL);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 6);
    for (size_t i = 0; i < r.n_items; i++) {
        const compare_item *it = &r.items[i];
        assert_true(it->machine_held && it->lo > 1.05);   /* the old rule said REGRESSION */
        assert_non_null(strstr(it->note, "compare --paired"));
    }
    assert_true(!r.machine.contention && !r.machine.load_changed && r.machine.reason == NULL);
    assert_true(r.machine.spread == COMPARE_RUN_SPREAD);
    assert_int_equal(compare_exit_code(&r), 3);
    compare_result_free(&r);
    /* the same data from paired rounds (ABBA on one machine): REGRESSION */
    d.paired = 1;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* The two runs: WallTime x1.53 while CPUTime x1.08 and the load
 * average moved: contention, named in words, never REGRESSION.  A
 * configuration that slowed far beyond the machine's change still is. */
static void test_contention_is_named_not_regression(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_scene_run(&a, "A", 6, 20, 1.0, 1.0, 0.02, 10, 0.7, NULL);
    make_scene_run(&b, "B", 6, 20, 1.53, 1.53 / 1.08, 0.02, 50, 3.5, NULL);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 6);
    assert_true(r.machine.contention && r.machine.load_changed);
    assert_true(fabs(r.machine.wall_ratio - 1.53) < 0.02 && fabs(r.machine.cpu_ratio - 1.08) < 0.02);
    char want[96];
    snprintf(want, sizeof want, "WallTime x%.2f while CPUTime x%.2f", r.machine.wall_ratio,
             r.machine.cpu_ratio);
    assert_non_null(strstr(r.machine.reason, want));
    assert_non_null(strstr(r.machine.reason, "load average 0.70 (BASE) -> 3.50 (NEW)"));
    assert_non_null(strstr(r.items[0].note, "contention"));
    compare_result_free(&r);
    /* configuration 3 truly 2x slower on top of the machine's change */
    dm_counter_result *w = counter(&b, 3, "WallTime");
    for (size_t k = 0; k < w->n_samples; k++)
        w->samples[k] *= 2;
    w->median *= 2;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 1);
    assert_string_equal(r.items[0].key, "0000000000000004");
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* Paired rounds where one side waited more (WallTime x1.6, CPUTime x1.0):
 * the wait is not the code's — INCONCLUSIVE; a real change moves CPU time
 * with WallTime and stays REGRESSION. */
static void test_paired_contention(void **state)
{
    (void)state;
    dm_run_result a, b, c;
    make_scene_run(&a, "A", 6, 12, 1.0, 1.0, 0.01, 10, 0.8, NULL);
    make_scene_run(&b, "B", 6, 12, 1.6, 1.6, 0.01, 50, 0.8, NULL);   /* waits, no more work */
    make_scene_run(&c, "C", 6, 12, 1.3, 1.0, 0.01, 50, 0.8, NULL);   /* 30 % more work */
    compare_desc d = { .paired = 1 };
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_true(r.machine.contention && fabs(r.machine.hi - 1.6) < 0.05);
    assert_int_equal(r.count[COMPARE_REGRESSION], 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 6);
    compare_result_free(&r);
    assert_int_equal(run_compare(&a, &c, &d, &r), 0);
    assert_true(!r.machine.contention && r.machine.hi == 1);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
    dm_run_free(&c);
}

/* A true shift beyond the between-run spread is REGRESSION. */
static void test_shift_beyond_spread_regression(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_scene_run(&a, "A", 6, 20, 1.0, 1.0, 0.02, 10, 0.8, NULL);
    make_scene_run(&b, "B", 6, 20, 1.30, 1.0 / 1.30 * 1.30, 0.02, 50, 0.8, NULL);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    assert_int_equal(compare_exit_code(&r), 1);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* The run's calibration workload, as the runner records it. */
static void set_calibration(dm_run_result *r, double cpu_start, double cpu_end, double draw)
{
    char buf[32];
    const double v[4] = { cpu_start, cpu_end, draw, draw };
    const char *piece[4] = { "cpu", "cpu", "draw", "draw" }, *which[4] = { "start", "end", "start", "end" };
    for (int i = 0; i < 4; i++) {
        snprintf(buf, sizeof buf, "%.0f", v[i]);
        dm_kv_push(&r->environment, &r->n_environment, calibrate_key(piece[i], which[i]), buf);
    }
}

/* The 30 % shift above, but NEW's calibration workload also took 1.30x as
 * long: the machine itself was slower, so the shift is INCONCLUSIVE and the
 * reason names the calibration; the ratio divided by it is shown.  With an
 * unchanged calibration the shift stays REGRESSION; a calibration that
 * moved 20 % within one run is named (the rounds' spread, not it, widens
 * the interval). */
static void test_calibration_names_slower_machine(void **state)
{
    (void)state;
    dm_run_result a, b;
    make_scene_run(&a, "A", 6, 20, 1.0, 1.0, 0.02, 10, 0.8, NULL);
    make_scene_run(&b, "B", 6, 20, 1.30, 1.0, 0.02, 50, 0.8, NULL);
    set_calibration(&a, 10e6, 10e6, 3e6);
    set_calibration(&b, 13e6, 13e6, 3.9e6);
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 6);
    assert_true(r.machine.cal_changed && fabs(r.machine.cal_ratio - 1.3) < 1e-9);
    assert_true(fabs(r.machine.cal_draw_ratio - 1.3) < 1e-9);
    assert_true(fabs(r.machine.wall_per_cal - r.machine.wall_ratio / 1.3) < 1e-12);
    assert_non_null(strstr(r.machine.reason, "the calibration workload took x1.30 (CPU kernel) "
                                             "and x1.30 (draw) of BASE's time in NEW"));
    assert_true(r.machine.hi >= 1.3 * (1 + COMPARE_RUN_SPREAD) - 1e-9);
    compare_result_free(&r);
    dm_run_free(&b);
    make_scene_run(&b, "B", 6, 20, 1.30, 1.0, 0.02, 50, 0.8, NULL);
    set_calibration(&b, 10.1e6, 9.9e6, 3e6);   /* the same machine: the code is slower */
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_true(!r.machine.cal_changed && r.machine.reason == NULL);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    compare_result_free(&r);
    dm_run_free(&a);
    make_scene_run(&a, "A", 6, 20, 1.0, 1.0, 0.02, 10, 0.8, NULL);
    set_calibration(&a, 10e6, 12e6, 3e6);      /* BASE's machine slowed 20 % during the run */
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_true(fabs(r.machine.base.cal_drift - 0.2) < 1e-9);
    assert_true(r.machine.spread == COMPARE_RUN_SPREAD);   /* named, not a wider interval */
    assert_non_null(strstr(r.machine.reason, "moved 20% between BASE's start and end"));
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* One side of n separate runs, run k's machine at speed factor[k]
 * (times scale), pooled as `compare BASE1,BASE2,... NEW1,...` pools them. */
static void pooled_side(dm_run_result *side, const char *id, const double *factor, size_t n,
                        double scale, uint64_t seed)
{
    memset(side, 0, sizeof *side);
    for (size_t k = 0; k < n; k++) {
        dm_run_result r;
        make_scene_run(&r, id, 6, 20, scale * factor[k], 1.0, 0.01, seed + 7 * k, 0.8, NULL);
        compare_pool_run(side, &r, (int)k);
    }
}

/* Several runs a side: the machine moves each run by up to 10 % while the
 * samples within a run agree to 1 %.  The same code on both sides is never
 * a REGRESSION, although one run a side with the within-run statistics
 * alone (no between-run allowance) calls every configuration one; 30 %
 * slower code is REGRESSION on every configuration; an 8 % change with
 * steady runs, INCONCLUSIVE from one run a side, is decided by six. */
static void test_replicated_runs(void **state)
{
    (void)state;
    const double fb[6] = { 0.95, 1.07, 1.00, 1.04, 0.97, 1.10 };
    const double fn[6] = { 1.08, 0.96, 1.06, 0.99, 1.02, 0.94 };
    compare_desc d = { .replicated = 1 };
    compare_result r;
    dm_run_result a, b;
    pooled_side(&a, "A", fb, 6, 1.0, 10);
    pooled_side(&b, "B", fn, 6, 1.0, 50);
    assert_int_equal(a.configs[0].counters[0].n_samples, 6);   /* one minimum per run */
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION] + r.count[COMPARE_IMPROVEMENT], 0);
    assert_true(r.machine.spread == 0 && r.machine.hi == 1);   /* measured, not assumed */
    compare_result_free(&r);
    dm_run_free(&b);
    dm_run_result a1, b1;                  /* the first run of each side, alone */
    make_scene_run(&a1, "A", 6, 20, fb[0], 1.0, 0.01, 10, 0.8, NULL);
    make_scene_run(&b1, "B", 6, 20, fn[0], 1.0, 0.01, 50, 0.8, NULL);
    compare_desc one = { .run_spread = 1e-6 };
    assert_int_equal(run_compare(&a1, &b1, &one, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);      /* what within-run statistics say */
    compare_result_free(&r);
    dm_run_free(&a1);
    dm_run_free(&b1);
    pooled_side(&b, "B", fn, 6, 1.30, 50);
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    assert_non_null(strstr(r.items[0].note, "slower"));
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
    const double steady[6] = { 1.00, 1.01, 0.995, 1.005, 0.99, 1.0 };
    pooled_side(&a, "A", steady, 6, 1.0, 10);
    pooled_side(&b, "B", steady, 6, 1.08, 50);
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    assert_int_equal(r.count[COMPARE_REGRESSION], 6);
    compare_result_free(&r);
    make_scene_run(&a1, "A", 6, 20, 1.0, 1.0, 0.01, 10, 0.8, NULL);
    make_scene_run(&b1, "B", 6, 20, 1.08, 1.0, 0.01, 50, 0.8, NULL);
    compare_desc plain = {0};
    assert_int_equal(run_compare(&a1, &b1, &plain, &r), 0);
    assert_int_equal(r.count[COMPARE_INCONCLUSIVE], 6);
    compare_result_free(&r);
    dm_run_free(&a1);
    dm_run_free(&b1);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* Blocking by round: the noisy day, one round of every
 * configuration at 0.77 of the others (12.0 ms where the rest are near
 * 15.5) and a slow drift.  The blocked CI is narrower than the raw one,
 * both are reported, and the round spread enters the machine interval. */
static void test_blocking_narrows_ci(void **state)
{
    (void)state;
    double round[16];
    for (size_t k = 0; k < 16; k++)
        round[k] = (k == 5 ? 0.77 : 1.0) * (1 + 0.06 * sin((double)k));
    dm_run_result a, b;
    make_scene_run(&a, "A", 8, 16, 1.0, 1.0, 0.01, 10, 0.8, round);
    make_scene_run(&b, "B", 8, 16, 1.0, 1.0, 0.01, 50, 0.8, round);
    compare_desc d = { .paired = 1 };
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    for (size_t i = 0; i < r.n_items; i++) {
        const compare_item *it = &r.items[i];
        assert_true(it->blocked);
        assert_true(it->hi - it->lo < 0.6 * (it->hi_raw - it->lo_raw));
    }
    assert_true(r.machine.base.ci_rel_blocked < 0.5 * r.machine.base.ci_rel_raw);
    assert_true(r.machine.base.n_precise_blocked > r.machine.base.n_precise_raw);
    assert_true(r.machine.base.round_spread > 0.15);
    assert_int_equal(r.count[COMPARE_PASS], 8);
    compare_result_free(&r);
    d.no_blocking = 1;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    for (size_t i = 0; i < r.n_items; i++)
        assert_true(!r.items[i].blocked && r.items[i].lo == r.items[i].lo_raw);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

/* ---- the PR comment (issue 27, item 5) ------------------------------------ */

/* 400 configurations with long names, one changed: the headline counts, the changed row
 * first and in full, PASS rows in <details>, the size under the limit with
 * a note of what was cut; --only-changed drops the PASS rows; a comparison
 * that did not happen still writes a file saying why. */
/* The fewest paired rounds that can reach a verdict: the smallest n with
 * 2 / C(2n, n) < alpha (C(8,4) = 70, C(10,5) = 252, C(14,7) = 3432). */
static void test_paired_min_rounds(void **state)
{
    (void)state;
    assert_int_equal(compare_paired_min_rounds(0.01), 5);    /* 2/252 < 0.01 <= 2/70 */
    assert_int_equal(compare_paired_min_rounds(0.05), 4);    /* 2/70 < 0.05 <= 2/20 */
    assert_int_equal(compare_paired_min_rounds(0.001), 7);   /* 2/3432 < 0.001 <= 2/924 */
    assert_int_equal(compare_paired_min_rounds(0), 5);       /* not given: the default 0.01 */
    assert_true(COMPARE_PAIRED_ROUNDS >= compare_paired_min_rounds(0.01));
}

static void test_markdown_pr_comment(void **state)
{
    tmp *t = *state;
    dm_run_result a, b;
    make_run(&a, "A", 400, 6, 1.0, 0.02, 3);
    make_run(&b, "B", 400, 6, 1.0, 0.02, 3);
    for (size_t i = 0; i < 400; i++) {   /* a user's map paths: long names */
        char maps[200];
        snprintf(maps, sizeof maps, "height=/home/user/project/assets/terrain/heights/tile-%03zu-"
                 "of-the-large-survey-area-at-full-resolution.png", i);
        dm_kv_push(&a.configs[i].params, &a.configs[i].n_params, "maps", maps);
        dm_kv_push(&b.configs[i].params, &b.configs[i].n_params, "maps", maps);
        free(a.configs[i].scene);
        free(b.configs[i].scene);
        a.configs[i].scene = dm_xstrdup("survey");
        b.configs[i].scene = dm_xstrdup("survey");
    }
    counter(&b, 300, "TESInvocations")->value = 6144;
    compare_desc d = {0};
    compare_result r;
    assert_int_equal(run_compare(&a, &b, &d, &r), 0);
    char *md = dm_xasprintf("%s/pr.md", t->dir);
    assert_int_equal(compare_write_markdown(&r, NULL, md), 0);
    char *text = test_slurp(md);
    assert_true(strlen(text) <= COMPARE_MD_MAX);
    const char *head = "## dmbench compare: REGRESSION — 1 regressed, 0 inconclusive, 0 "
                       "improved, 399 passed of 400 configurations\n";
    assert_true(strncmp(text, head, strlen(head)) == 0);
    const char *row = strstr(text, "| survey · normal mesh=m300 maps=height=/home/user/project/assets/"
                                   "terrain/heights/tile-300-of-the-large-survey-area-at-full-"
                                   "resolution.png | 301.000 ms | 301.000 ms | – | – | – | REGRESSION | "
                                   "TESInvocations changed 3169 → 6144 |");
    const char *details = strstr(text, "<details><summary>399 PASS</summary>");
    assert_non_null(row);
    assert_non_null(details);
    assert_true(row < details);
    assert_non_null(strstr(text, "rows cut to stay under 60000 characters"));
    assert_non_null(strstr(text, "</details>"));
    free(text);
    compare_md_desc only = { .only_changed = 1 };
    assert_int_equal(compare_write_markdown(&r, &only, md), 0);
    text = test_slurp(md);
    assert_null(strstr(text, "<details>"));
    assert_null(strstr(text, "rows cut"));
    assert_true(strlen(text) < 2000);   /* the head, the machine's lines and one row */
    free(text);
    compare_md_desc tiny = { .max_chars = 1200 };
    assert_int_equal(compare_write_markdown(&r, &tiny, md), 0);
    text = test_slurp(md);
    assert_true(strlen(text) <= 1200);
    assert_non_null(strstr(text, "rows cut to stay under 1200 characters"));
    free(text);
    assert_int_equal(compare_write_markdown(&r, &(compare_md_desc){ .none = 1, .reason = "the runs have no configuration in common" }, md), 0);
    text = test_slurp(md);
    assert_non_null(strstr(text, "## dmbench compare: nothing compared\n\nthe runs have no "
                                 "configuration in common\n"));
    free(text);
    assert_int_equal(compare_write_markdown(NULL, &(compare_md_desc){ .none = 1 }, md), 0);
    text = test_slurp(md);   /* without a result or a reason: the headline alone */
    assert_string_equal(text, "## dmbench compare: nothing compared\n\nno reason given\n");
    free(text);
    free(md);
    compare_result_free(&r);
    dm_run_free(&a);
    dm_run_free(&b);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_self_all_pass),
             cmocka_unit_test(test_deterministic_change),
             cmocka_unit_test(test_slowdown_20_percent_regression),
             cmocka_unit_test(test_slowdown_1_percent_pass),
             cmocka_unit_test(test_huge_noise_inconclusive),
             cmocka_unit_test(test_env_mismatch),
             cmocka_unit_test(test_counters_only_ignores_time),
             cmocka_unit_test(test_failed_added_removed),
             cmocka_unit_test(test_user_technique_source_changed),
             cmocka_unit_test(test_quality_drop),
             cmocka_unit_test(test_flip_rise),
             cmocka_unit_test(test_inconclusive_states_detectable),
             cmocka_unit_test(test_identical_noisy_pass),
             cmocka_unit_test(test_instructions_threshold),
             cmocka_unit_test(test_partial_gputime_refused),
             cmocka_unit_test_setup_teardown(test_json_roundtrip_and_outputs, tmp_setup, tmp_teardown),
             cmocka_unit_test_setup_teardown(test_store_and_baselines, tmp_setup, tmp_teardown),
             cmocka_unit_test_setup_teardown(test_store_file_four_pairings, tmp_setup, tmp_teardown),
             cmocka_unit_test(test_derived_epsilon),
             cmocka_unit_test(test_between_run_shift_within_spread),
             cmocka_unit_test(test_contention_is_named_not_regression),
             cmocka_unit_test(test_shift_beyond_spread_regression),
        cmocka_unit_test(test_calibration_names_slower_machine),
        cmocka_unit_test(test_replicated_runs),
             cmocka_unit_test(test_paired_contention),
             cmocka_unit_test(test_blocking_narrows_ci),
             cmocka_unit_test(test_paired_min_rounds),
             cmocka_unit_test_setup_teardown(test_markdown_pr_comment, tmp_setup, tmp_teardown))
