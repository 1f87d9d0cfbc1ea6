/* Published figures beside measured ones (reports/published_report.h): the
 * ratio of times (FPS inverted), the ±5 % direction band, the factor-of-2
 * size rule, and the Markdown/HTML section built from a run directory's
 * published.json, all on hand-computed numbers. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_results.h"
#include "reports/published_report.h"

static void test_ratios_and_verdicts(void **state)
{
    (void)state;
    assert_true(fabs(report_pub_time_ratio(1, 80, 100) - 1.25) < 1e-12);  /* 100 fps -> 80 fps */
    assert_true(fabs(report_pub_time_ratio(0, 5, 2) - 2.5) < 1e-12);      /* 2 ms -> 5 ms */
    assert_int_equal(report_pub_direction(1.06), 1);
    assert_int_equal(report_pub_direction(0.94), -1);
    assert_int_equal(report_pub_direction(1.04), 0);
    assert_int_equal(report_pub_direction(0.96), 0);
    report_pub_verdict v = report_pub_judge(1.25, 2.6);   /* both slower, 2.08x apart */
    assert_true(v.direction_agrees && !v.size_agrees);
    assert_true(fabs(v.factor - 2.08) < 1e-12);
    v = report_pub_judge(1.25, 0.9);                      /* slower vs faster */
    assert_true(!v.direction_agrees && v.size_agrees);
    assert_true(fabs(v.factor - 1.25 / 0.9) < 1e-12);
    v = report_pub_judge(1.02, 0.97);                     /* both within the band */
    assert_true(v.direction_agrees && v.size_agrees);
    v = report_pub_judge(3.0, 1.6);                       /* 1.875x apart: agrees */
    assert_true(v.direction_agrees && v.size_agrees && fabs(v.factor - 1.875) < 1e-12);
    v = report_pub_judge(0.5, 1.0);                       /* faster vs same */
    assert_false(v.direction_agrees);
}

static void config(dm_config_result *c, const char *key, double median_ns, int ok)
{
    memset(c, 0, sizeof *c);
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup("plane@64x36");
    c->ok = ok;
    c->n_counters = 1;
    c->counters = dm_xcalloc(1, sizeof *c->counters);
    dm_counter_result *t = c->counters;
    t->name = dm_xstrdup("WallTime");
    t->unit = dm_xstrdup("ns");
    t->available = t->has_samples = 1;
    t->n_samples = 1;
    t->samples = dm_xcalloc(1, sizeof(double));
    t->samples[0] = t->median = t->value = median_ns;
}

static void test_section(void **state)
{
    (void)state;
    dm_run_result run = {0};
    run.n_configs = 3;
    run.configs = dm_xcalloc(3, sizeof *run.configs);
    config(&run.configs[0], "aaaaaaaaaaaaaaaa", 2e6, 1);
    config(&run.configs[1], "bbbbbbbbbbbbbbbb", 3e6, 1);
    config(&run.configs[2], "cccccccccccccccc", 5e6, 0);
    char dir[] = "/tmp/dm_pubrep_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *path = dm_xasprintf("%s/published.json", dir);
    const char *json =
        "{\"source\": {\"study\": \"S (2010)\", \"table\": \"Table 2\", \"gpu\": \"G<1>\"},"
        " \"unit\": \"fps\", \"baseline\": \"a\", \"values\": ["
        " {\"label\": \"a\", \"key\": \"aaaaaaaaaaaaaaaa\", \"value\": 120},"
        " {\"label\": \"b\", \"key\": \"bbbbbbbbbbbbbbbb\", \"value\": 60},"
        " {\"label\": \"c\", \"key\": \"cccccccccccccccc\", \"value\": 30},"
        " {\"label\": \"d\", \"key\": \"dddddddddddddddd\", \"value\": 240}]}";
    assert_int_equal(dm_write_file(path, json, strlen(json)), 0);
    dm_str md = {0}, html = {0}, none = {0};
    report_published_section(&md, &run, dir, NULL, 0);
    report_published_section(&html, &run, NULL, path, 1);   /* the directory of a file beside it */
    report_published_section(&none, &run, "/nonexistent-dir", NULL, 0);
    const char *m = dm_str_get(&md), *h = dm_str_get(&html);
    assert_non_null(strstr(m, "## Published figures beside ours"));
    assert_non_null(strstr(m, "S (2010) — Table 2 (G&lt;1&gt;); published in fps"));
    assert_non_null(strstr(m, "| a (baseline) | 120 fps | 1.000 | 2.000 ms | 1.000 | baseline |"));
    /* 120/60 = 2.000 published, 3/2 = 1.500 measured: 1.33x apart */
    assert_non_null(strstr(m, "| b | 60 fps | 2.000 | 3.000 ms | 1.500 | agrees (within ×1.33) |"));
    assert_non_null(strstr(m, "| c | 30 fps | 4.000 | — | — | no comparison: failed |"));
    assert_non_null(strstr(m, "| d | 240 fps | 0.500 | — | — | no comparison: not measured"));
    assert_non_null(strstr(m, "1 of 1 compared rows agree."));
    assert_non_null(strstr(h, "<h2 id=\"published\">Published figures beside ours</h2>"));
    assert_non_null(strstr(h, "<td>b</td><td class=\"n\">60 fps</td><td class=\"n\">2.000</td>"));
    assert_non_null(strstr(h, "G&lt;1&gt;"));
    assert_int_equal(none.len, 0);
    dm_str_free(&md);
    dm_str_free(&html);
    dm_str_free(&none);
    unlink(path);
    rmdir(dir);
    free(path);
    dm_run_free(&run);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ratios_and_verdicts),
        cmocka_unit_test(test_section),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
