/* test_reports_stage_bar.c — the report's stacked stage bars
 * (reports/stage_bar.c) on made-up runs: shares as widths, the verdict,
 * per-invocation costs; no section without stage counters. */
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

#include "reports/stage_bar.h"

static void counter(dm_config_result *c, const char *name, double v, int available)
{
    dm_counter_result *r = dm_vec_push(&c->counters, &c->n_counters, NULL, sizeof *r);
    memset(r, 0, sizeof *r);
    r->name = dm_xstrdup(name);
    r->unit = dm_xstrdup("items");
    r->available = available;
    r->value = v;
}

static dm_config_result *config(dm_run_result *run, const char *technique)
{
    dm_config_result *c = dm_vec_push(&run->configs, &run->n_configs, NULL, sizeof *c);
    memset(c, 0, sizeof *c);
    c->key = dm_xasprintf("%016zx", run->n_configs);
    c->scene = dm_xstrdup("cube@64x64");
    c->ok = 1;
    dm_kv_push(&c->params, &c->n_params, "technique", technique);
    return c;
}

static void test_bars(void **state)
{
    (void)state;
    dm_run_result run = {0};
    dm_config_result *c = config(&run, "pom");
    counter(c, "GeometryInstructions", 50000, 1);     /* 5 % */
    counter(c, "RasterInstructions", 150000, 1);      /* 15 % */
    counter(c, "FragmentInstructions", 800000, 1);    /* 80 % */
    counter(c, "InstructionsPerVertex", 2083.3, 1);
    counter(c, "InstructionsPerEvaluation", NAN, 0);
    counter(c, "FragmentInstructionsPerPixel", 195.3, 1);
    c = config(&run, "normal");                       /* stage counters unavailable: no row */
    counter(c, "GeometryInstructions", NAN, 0);
    counter(c, "RasterInstructions", NAN, 0);
    counter(c, "FragmentInstructions", NAN, 0);
    dm_str s = {0};
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    report_stage_bars(&s, &m);
    report_model_free(&m);
    const char *h = dm_str_get(&s);
    assert_non_null(strstr(h, "<h2 id=\"stages\">Where the instructions go</h2>"));
    assert_non_null(strstr(h, "fragment 80 %, raster 15 %, geometry 5 %"));
    assert_non_null(strstr(h, "width:5.00%;background:#4e79a7\" title=\"geometry 5.0 %\""));
    assert_non_null(strstr(h, "width:80.00%"));
    assert_non_null(strstr(h, "1000000 instructions per frame; 2083.3 per vertex; 195.3 fragment"));
    assert_non_null(strstr(h, "<td class=\"n\">–</td>"));   /* no evaluation stage */
    assert_null(strstr(h, "normal"));
    dm_str_free(&s);
    run.configs[0].ok = 0;                            /* a failed configuration is not drawn */
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    report_stage_bars(&s, &m);
    report_model_free(&m);
    assert_int_equal((int)s.len, 0);
    dm_str_free(&s);
    dm_run_free(&run);
}

DM_TEST_MAIN(NULL, NULL, cmocka_unit_test(test_bars))
