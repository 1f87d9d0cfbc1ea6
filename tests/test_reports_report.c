/* test_reports_report.c — results.json / results.csv / summary.md / report.html. */
#include "reports/report.h"
#include "reports/image.h"
#include "core/dm_error.h"
#include "core/dm_util.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include "test_reports_fixture.h"

/* noinline: GCC 12 otherwise mistakes the result for the address of the
 * local it was read through (-Wdangling-pointer false positive). */
__attribute__((noinline)) static char *slurp(const char *path)
{
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(dm_read_file(path, &text, &len), 0);
    return text;
}

static void test_json_round_trip(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_json_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *p1 = dm_xasprintf("%s/a.json", dir), *p2 = dm_xasprintf("%s/b.json", dir);
    dm_run_result run, back;
    fixture_run(&run);
    assert_int_equal(report_write_json(&run, p1), 0);
    assert_int_equal(report_read_json(p1, &back, err, sizeof err), 0);
    assert_int_equal(report_write_json(&back, p2), 0);
    char *t1 = slurp(p1), *t2 = slurp(p2);
    assert_string_equal(t1, t2);
    /* the contract's shapes */
    assert_non_null(strstr(t1, "\"steps\":\t32"));             /* canonical numbers are numbers */
    assert_non_null(strstr(t1, "\"scale\":\t\"1e6\""));        /* others stay strings */
    assert_non_null(strstr(t1, "\"PSNR\":\tnull"));
    assert_non_null(strstr(t1, "\"PSNR_infinite\":\ttrue"));
    assert_non_null(strstr(t1, "\"unavailable\":\t\"no timer query\""));
    assert_non_null(strstr(t1, "\"ci95\":\t[1000000, 1200000]"));
    /* values survive */
    assert_int_equal(back.n_configs, 3);
    assert_true(isinf(back.configs[0].quality.psnr));
    assert_float_equal(back.configs[1].quality.psnr, 38.25, 0);
    assert_string_equal(dm_kv_get(back.configs[0].params, back.configs[0].n_params, "steps"), "32");
    const dm_counter_result *w = dm_config_counter(&back.configs[0], "WallTime");
    assert_non_null(w);
    assert_int_equal(w->n_samples, 3);
    assert_float_equal(w->samples[2], 1.2e6, 0);
    const dm_counter_result *g = dm_config_counter(&back.configs[0], "GPUTime");
    assert_int_equal(g->available, 0);
    const dm_counter_result *t = dm_config_counter(&back.configs[0], "TESInvocations");
    assert_int_equal(t->deterministic, 1);
    assert_float_equal(t->value, 3169, 0);
    assert_int_equal(back.configs[2].ok, 0);
    assert_string_equal(back.configs[2].log, FIXTURE_LOG);
    assert_int_equal(back.n_left_out, 1);
    assert_int_equal(back.n_fits, 1);
    assert_float_equal(back.fits[0].params[1].stderr_, 0.25, 0);
    assert_string_equal(back.timer_verdict, "partial");
    free(t1);
    free(t2);
    dm_run_free(&back);
    dm_run_free(&run);
    unlink(p1);
    unlink(p2);
    free(p1);
    free(p2);
    rmdir(dir);
}

static void test_json_read_errors(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_jerr_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/bad.json", dir);
    dm_run_result r;
    assert_int_equal(dm_write_file(p, "{\"run\": {", 9), 0);
    assert_int_equal(report_read_json(p, &r, err, sizeof err), DM_ERR_PARSE);
    assert_non_null(strstr(err, p));
    assert_int_equal(dm_write_file(p, "{\"run\": {}}", 11), 0);
    assert_int_equal(report_read_json(p, &r, err, sizeof err), DM_ERR_PARSE);
    assert_non_null(strstr(err, "configs"));
    unlink(p);
    assert_int_equal(report_read_json(p, &r, err, sizeof err), DM_ERR_IO);
    free(p);
    rmdir(dir);
}

/* Minimal RFC 4180 reader: returns the number of records, and checks every
 * record has `cols` fields (cols = fields of the first record). */
static size_t csv_shape(const char *t, size_t *cols, char first_row_cell[][64], size_t maxc)
{
    size_t rows = 0, f = 0, len = 0;
    int quoted = 0;
    *cols = 0;
    for (const char *p = t; *p; p++) {
        if (quoted) {
            if (*p == '"' && p[1] == '"') { p++; if (rows == 1 && f < maxc && len < 63) first_row_cell[f][len++] = '"'; }
            else if (*p == '"') quoted = 0;
            else if (rows == 1 && f < maxc && len < 63) first_row_cell[f][len++] = *p;
        } else if (*p == '"') {
            quoted = 1;
        } else if (*p == ',') {
            if (rows == 1 && f < maxc) first_row_cell[f][len] = 0;
            f++, len = 0;
        } else if (*p == '\r' && p[1] == '\n') {
            if (rows == 1 && f < maxc) first_row_cell[f][len] = 0;
            p++;
            f++;
            if (rows == 0) *cols = f;
            assert_int_equal(f, *cols);
            rows++, f = 0, len = 0;
        } else if (rows == 1 && f < maxc && len < 63) {
            first_row_cell[f][len++] = *p;
        }
    }
    assert_int_equal(f, 0);   /* ends with CRLF */
    return rows;
}

static void test_csv_shape(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_csv_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/r.csv", dir);
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(report_write_csv(&run, p), 0);
    char *t = slurp(p);
    size_t cols;
    char cell[64][64];
    memset(cell, 0, sizeof cell);
    assert_int_equal(csv_shape(t, &cols, cell, 64), 4);   /* header + 3 configs */
    /* key scene status reason | technique mesh steps scale note tess_level |
     * WallTime ×3 | TESInvocations | 8 quality */
    assert_int_equal(cols, 4 + 6 + 3 + 1 + 8);
    assert_string_equal(cell[0], FIXTURE_KEY0);
    assert_string_equal(cell[8], "a,b \"quoted\"");   /* note param round-trips through quoting */
    assert_string_equal(cell[10], "1.1");              /* WallTime median, ms */
    assert_string_equal(cell[14], "0");                /* RMSE */
    assert_string_equal(cell[15], "inf");              /* PSNR */
    assert_non_null(strstr(t, "WallTime_median_ms"));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    rmdir(dir);
}

static void test_markdown(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_md_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/s.md", dir);
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(report_write_markdown(&run, p), 0);
    char *t = slurp(p);
    assert_non_null(strstr(t, "## Scene `" FIXTURE_SCENE "`"));
    /* rows sorted by time; CI as a relative half-width: 0.1/1.1 = 9.1 %, 0.05/2 = 2.5 % */
    assert_non_null(strstr(t, "| pom | 1.100 | ±9.1% | ∞ | 1.0000 | `" FIXTURE_KEY0 "` |"));
    assert_non_null(strstr(t, "| normal | 2.000 | ±2.5% | 38.25 dB | 0.9500 | `" FIXTURE_KEY1 "` |"));
    assert_true(strstr(t, "| pom |") < strstr(t, "| normal |"));
    /* pom is faster and exact (SSIM 1): it alone is the Pareto front */
    assert_non_null(strstr(t, "fastest first): pom (1.1 ms, SSIM 1.000)."));
    assert_non_null(strstr(t, FIXTURE_REASON));
    assert_non_null(strstr(t, FIXTURE_LEFT_REASON));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    rmdir(dir);
}

/* Every src="..." and href="..." in the page is an embedded PNG
 * (data:image/png;base64, starting with the PNG signature, "iVBORw0KGgo")
 * or names a file that exists relative to dir.  Counts the img srcs. */
static int all_refs_exist(const char *html, const char *dir, const char *attr, int *count)
{
    *count = 0;
    size_t al = strlen(attr);
    for (const char *p = strstr(html, attr); p; p = strstr(p + 1, attr)) {
        const char *b = p + al, *e = strchr(b, '"');
        if (strncmp(b, "data:", 5) == 0) {
            if (strncmp(b, "data:image/png;base64,iVBORw0KGgo", 33) != 0)
                return 0;
            (*count)++;
            continue;
        }
        char *rel = dm_xasprintf("%.*s", (int)(e - b), b);
        char *full = dm_xasprintf("%s/%s", dir, rel);
        int ok = rel[0] != '/' && !strstr(rel, "..") && dm_file_exists(full);
        free(rel);
        free(full);
        if (!ok)
            return 0;
        (*count)++;
    }
    return 1;
}

static void test_html_escaping_and_images(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_html_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    assert_int_equal(fixture_images(dir, err, sizeof err), 0);
    char *p = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(report_write_html(&run, dir, p), 0);
    char *t = slurp(p);
    assert_non_null(strstr(t, "&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert_null(strstr(t, "<script>alert"));
    assert_null(strstr(t, "<b>bold"));
    assert_non_null(strstr(t, "&lt;b&gt;bold&lt;/b&gt;"));
    assert_non_null(strstr(t, FIXTURE_KEY0));
    assert_non_null(strstr(t, FIXTURE_KEY1));
    assert_non_null(strstr(t, FIXTURE_KEY2));
    assert_non_null(strstr(t, "GPUTime is partial on this driver: it covers 1.5% of fenced wall time; "
                              "it is recorded, never used to fit or gate"));
    assert_null(strstr(t, "http://"));
    assert_null(strstr(t, "https://"));
    int n = 0;
    /* c0: 3 images, c1: render only (heatmap absolute, reference "..") */
    assert_true(all_refs_exist(t, dir, " src=\"", &n));
    assert_int_equal(n, 4);
    assert_true(all_refs_exist(t, dir, " href=\"", &n));
    assert_int_equal(n, 4);
    assert_non_null(strstr(t, "<a href=\"img/c0_heat.png\"><img src=\"data:image/png;base64,"));
    assert_non_null(strstr(t, "path refused: /etc/passwd"));
    assert_non_null(strstr(t, "path refused: ../outside.png"));
    free(t);
    dm_run_free(&run);
    fixture_images_remove(dir);
    unlink(p);
    free(p);
    rmdir(dir);
}

static void test_write_all(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_all_XXXXXX", err[512];
    static const char *names[] = {"results.json", "results.csv", "summary.md", "report.html"};
    assert_non_null(mkdtemp(dir));
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(report_write_all(&run, dir, err, sizeof err), 0);
    for (int i = 0; i < 4; i++) {
        char *p = dm_xasprintf("%s/%s", dir, names[i]);
        assert_true(dm_file_exists(p));
        unlink(p);
        free(p);
    }
    char *missing = dm_xasprintf("%s/no/such/dir", dir);
    assert_int_equal(report_write_all(&run, missing, err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "results.json"));
    free(missing);
    dm_run_free(&run);
    rmdir(dir);
}

/* A tessellation sweep: L = 1, 2, 4, 8 at 1, 2, 4, 8 ms with errors
 * (1 − SSIM) 0.20, 0.10, 0.05, 0.06, plus a technique with a hostile name at
 * 3 ms / 0.15.  Front (fastest first): L=1, L=2, L=4; L=8 is dominated by
 * L=4 and the hostile one by L=2. */
static void tess_run(dm_run_result *r)
{
    static const char *keys[] = {"00000000000000c0", "00000000000000c1", "00000000000000c2",
                                 "00000000000000c3", "00000000000000c4"};
    static const char *levels[] = {"1", "2", "4", "8", NULL};
    static const double ms[] = {1, 2, 4, 8, 3}, ssim[] = {0.80, 0.90, 0.95, 0.94, 0.85};
    memset(r, 0, sizeof *r);
    r->sweep = dm_xstrdup("tess");
    r->n_configs = 5;
    r->configs = dm_xcalloc(5, sizeof *r->configs);
    for (int i = 0; i < 5; i++) {
        dm_config_result *c = &r->configs[i];
        c->key = dm_xstrdup(keys[i]);
        c->scene = dm_xstrdup("s");
        c->ok = 1;
        dm_kv_push(&c->params, &c->n_params, "technique", levels[i] ? "tessdisp" : "<b>x#y</b>");
        dm_kv_push(&c->params, &c->n_params, "mesh", "plane");
        if (levels[i])
            dm_kv_push(&c->params, &c->n_params, "tess_level", levels[i]);
        c->n_counters = 1;
        c->counters = dm_xcalloc(1, sizeof *c->counters);
        fixture_timed(&c->counters[0], "WallTime", ms[i] * 0.9e6, ms[i] * 1e6, ms[i] * 1.1e6);
        fixture_quality(&c->quality, 30, ssim[i], 0.01);
    }
}

static void test_html_charts_and_front(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_chart_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    tess_run(&run);
    /* 40 reports × 3 charts: more than PLplot's 100 streams, so streams must be released */
    for (int i = 0; i < 40; i++)
        assert_int_equal(report_write_html(&run, NULL, p), 0);
    char *t = slurp(p);
    int svgs = 0;
    for (const char *q = strstr(t, "<svg"); q; q = strstr(q + 1, "<svg"))
        svgs++;
    assert_int_equal(svgs, 3);   /* time per technique, error vs time, time vs tess_level */
    assert_null(strstr(t, "http://"));
    assert_null(strstr(t, "<b>x"));
    const char *ol = strstr(t, "Pareto front (fastest first):</p><ol>");
    assert_non_null(ol);
    const char *end = strstr(ol, "</ol>");
    const char *k0 = strstr(ol, "00000000000000c0"), *k1 = strstr(ol, "00000000000000c1");
    const char *k2 = strstr(ol, "00000000000000c2"), *k3 = strstr(ol, "00000000000000c3");
    const char *k4 = strstr(ol, "00000000000000c4");
    assert_true(k0 && k1 && k2 && k0 < k1 && k1 < k2 && k2 < end);
    assert_true(!k3 || k3 > end);
    assert_true(!k4 || k4 > end);
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_json_round_trip),
        cmocka_unit_test(test_json_read_errors),
        cmocka_unit_test(test_csv_shape),
        cmocka_unit_test(test_markdown),
        cmocka_unit_test(test_html_escaping_and_images),
        cmocka_unit_test(test_write_all),
        cmocka_unit_test(test_html_charts_and_front),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
