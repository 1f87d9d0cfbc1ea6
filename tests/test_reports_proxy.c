/* Unit tests of reports/proxy.c: the WallTime ≈ a + b·Instructions fit on
 * synthetic runs whose line and strays are known, the "unavailable" cases,
 * and which pass each counter is attributed to. */
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

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/proxy.h"

static void counter(dm_config_result *c, const char *name, double v, int samples, int det)
{
    c->counters = dm_xrealloc(c->counters, (c->n_counters + 1) * sizeof *c->counters);
    dm_counter_result *k = &c->counters[c->n_counters++];
    memset(k, 0, sizeof *k);
    k->name = dm_xstrdup(name);
    k->unit = dm_xstrdup("items");
    k->available = 1;
    k->deterministic = det;
    k->value = k->median = v;
    if (samples) {
        k->has_samples = 1;
        k->n_samples = 1;
        k->samples = dm_xmalloc(sizeof(double));
        k->samples[0] = v;
    }
}

/* n configurations on WallTime = 5e4 + 0.5 * I (I = 1e6 * (i + 1)); the
 * configuration `stray` (if < n) takes 30 % longer than the line. */
static void make(dm_run_result *r, size_t n, size_t stray)
{
    memset(r, 0, sizeof *r);
    r->id = dm_xstrdup("P");
    r->configs = dm_xcalloc(n, sizeof *r->configs);
    r->n_configs = n;
    for (size_t i = 0; i < n; i++) {
        dm_config_result *c = &r->configs[i];
        test_config_init(c, i);
        double instr = 1e6 * (double)(i + 1), wall = 5e4 + 0.5 * instr;
        counter(c, "WallTime", i == stray ? wall * 1.3 : wall, 1, 0);
        counter(c, "Instructions", instr, 1, 1);
        counter(c, "SamplesPassed", 1000, 0, 1);
        counter(c, "InstructionsPerPixel", instr / 1000, 0, 1);
    }
}

static void test_exact_line(void **state)
{
    (void)state;
    dm_run_result r;
    make(&r, 5, 99);
    report_proxy p;
    assert_int_equal(report_proxy_fit(&r, &p), 0);
    assert_int_equal(p.n, 5);
    assert_true(fabs(p.ns_per_instruction - 0.5) < 1e-12);
    assert_true(fabs(p.a_ns - 5e4) < 1e-6);
    assert_true(fabs(p.r2 - 1.0) < 1e-12);
    assert_true(fabs(p.strays[0].residual_rel) < 1e-12);
    dm_run_free(&r);
}

/* One configuration 30 % over the line: it strays most, and R² < 1. */
static void test_stray_first(void **state)
{
    (void)state;
    dm_run_result r;
    make(&r, 6, 2);
    report_proxy p;
    assert_int_equal(report_proxy_fit(&r, &p), 0);
    assert_int_equal(p.n_strays, REPORT_PROXY_STRAYS);
    assert_string_equal(p.strays[0].key, "0000000000000003");
    assert_string_equal(p.strays[0].label, "m2");   /* the scene; mesh is in it */
    assert_true(p.strays[0].residual_rel > 0.1);
    for (size_t i = 1; i < p.n_strays; i++)
        assert_true(fabs(p.strays[i].residual_rel) <= fabs(p.strays[i - 1].residual_rel));
    assert_true(p.r2 < 1.0 && p.r2 > 0.5);
    /* R² recomputed independently from the fitted line */
    double my = 0, sst = 0, sse = 0;
    for (size_t i = 0; i < 6; i++)
        my += r.configs[i].counters[0].median / 6;
    for (size_t i = 0; i < 6; i++) {
        double y = r.configs[i].counters[0].median, x = r.configs[i].counters[1].value;
        sst += (y - my) * (y - my);
        sse += pow(y - p.a_ns - p.ns_per_instruction * x, 2);
    }
    assert_true(fabs(p.r2 - (1 - sse / sst)) < 1e-9);
    dm_run_free(&r);
}

static void test_unavailable(void **state)
{
    (void)state;
    dm_run_result r;
    report_proxy p;
    make(&r, 2, 99);                           /* too few */
    assert_int_equal(report_proxy_fit(&r, &p), DM_ERR_UNAVAILABLE);
    dm_run_free(&r);
    make(&r, 4, 99);
    for (size_t i = 0; i < 4; i++)             /* counts do not vary: no line */
        r.configs[i].counters[1].value = 1e6;
    assert_int_equal(report_proxy_fit(&r, &p), DM_ERR_UNAVAILABLE);
    r.configs[0].counters[1].available = 0;    /* and unavailable ones are left out */
    r.configs[1].counters[1].value = 2e6;
    assert_int_equal(report_proxy_fit(&r, &p), 0);
    assert_int_equal(p.n, 3);
    dm_run_free(&r);
}

static void test_passes(void **state)
{
    (void)state;
    dm_run_result r;
    make(&r, 3, 99);
    const dm_config_result *c = &r.configs[0];
    assert_string_equal(report_proxy_pass(&c->counters[0]), "timing");
    assert_string_equal(report_proxy_pass(&c->counters[1]), "instructions");
    assert_string_equal(report_proxy_pass(&c->counters[2]), "statistics");
    assert_string_equal(report_proxy_pass(&c->counters[3]), "derived");
    dm_str s = {0};
    report_proxy_passes_text(&r, "\n", &s);
    assert_non_null(strstr(dm_str_get(&s), "under Valgrind callgrind, LP_NUM_THREADS=0, not timed: Instructions\n"));
    assert_non_null(strstr(dm_str_get(&s), "values: SamplesPassed\n"));
    assert_non_null(strstr(dm_str_get(&s), "derived (formulas over the above): InstructionsPerPixel\n"));
    dm_str_free(&s);
    dm_run_free(&r);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_exact_line),
             cmocka_unit_test(test_stray_first),
             cmocka_unit_test(test_unavailable),
             cmocka_unit_test(test_passes))
