/* test_reports_report.c — results.json / results.csv / summary.md / report.html. */
#include "reports/report.h"
#include "imaging/flip.h"
#include "reports/report_internal.h"
#include "reports/metric.h"
#include "reports/answer.h"
#include "reports/report_model.h"
#include "imaging/image.h"
#include "core/dm_error.h"
#include "core/dm_util.h"

#include <float.h>
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
#include "test_util.h"

#include "test_reports_fixture.h"

/* One file of the report writer table to path (report_write_run). */
static int write_report_file(const dm_run_result *run, const char *file, const char *dir,
                             const char *path, const char *href)
{
    char err[512];
    report_desc d = {.dir = dir, .href = href, .file = file, .path = path};
    return report_write_run(run, &d, err, sizeof err);
}

static void test_json_round_trip(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_json_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *p1 = dm_xasprintf("%s/a.json", dir), *p2 = dm_xasprintf("%s/b.json", dir);
    dm_run_result run, back;
    fixture_run(&run);
    assert_int_equal(write_report_file(&run, "results.json", NULL, p1, NULL), 0);
    assert_int_equal(report_read_json(p1, &back, err, sizeof err), 0);
    assert_int_equal(write_report_file(&back, "results.json", NULL, p2, NULL), 0);
    char *t1 = test_slurp(p1), *t2 = test_slurp(p2);
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
    test_rm_rf(dir);
}

/* A configuration on a camera path: results.json's "path" object reads back
 * to the same text, its series bit for bit; a still run's files have no
 * path object, column or table; a "path" whose series does not hold one
 * time per frame for each replay is refused with what is wrong. */
static void test_json_path(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_path_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *p1 = dm_xasprintf("%s/a.json", dir), *p2 = dm_xasprintf("%s/b.json", dir);
    char *csv = dm_xasprintf("%s/r.csv", dir), *md = dm_xasprintf("%s/s.md", dir);
    dm_run_result run, back;
    fixture_run(&run);
    assert_int_equal(write_report_file(&run, "results.json", NULL, p1, NULL), 0);
    assert_int_equal(write_report_file(&run, "results.csv", NULL, csv, NULL), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    char *t = test_slurp(p1), *tc = test_slurp(csv), *tm = test_slurp(md);
    assert_null(strstr(t, "\"path\""));
    assert_null(strstr(tc, "path_p99_ms"));
    assert_null(strstr(tm, "Along the path"));
    free(t);
    free(tc);
    free(tm);
    /* 3 frames x 2 replays, one time missing: figures as models/frame_series gives them */
    dm_path_series *ps = &run.configs[0].path;
    static const double ns[] = {1.0e6, 3.1e6, 1.1e6, 1.0e6 / 3, NAN, 1.3e6};
    ps->frames = 3;
    ps->replays = 2;
    ps->frame_ns = dm_xmalloc(sizeof ns);
    memcpy(ps->frame_ns, ns, sizeof ns);
    ps->p50 = 1.2e6 / 7;   /* not a round number of ms */
    ps->p95 = 2.9e6;
    ps->p99 = 3.06e6;
    ps->low1_ns = 3.1e6;
    ps->low1_fps = 1e9 / 3.1e6;
    ps->n_stutters = 1;
    ps->stutter_at = dm_xcalloc(1, sizeof *ps->stutter_at);
    ps->stutter_at[0] = 1;
    ps->replay_spread = NAN;
    ps->noisy = -1;
    assert_int_equal(write_report_file(&run, "results.json", NULL, p1, NULL), 0);
    assert_int_equal(report_read_json(p1, &back, err, sizeof err), 0);
    assert_int_equal(write_report_file(&back, "results.json", NULL, p2, NULL), 0);
    char *t1 = test_slurp(p1), *t2 = test_slurp(p2);
    assert_string_equal(t1, t2);
    assert_non_null(strstr(t1, "\"stutter_frames\":\t[1]"));
    assert_non_null(strstr(t1, "\"noisy\":\t\"unknown\""));
    assert_non_null(strstr(t1, "\"replay_spread\":\tnull"));
    assert_non_null(strstr(t1, "\"one_percent_low_ms\":\t3.1,"));
    const dm_path_series *b = &back.configs[0].path;
    assert_int_equal(b->frames, 3);
    assert_int_equal(b->replays, 2);
    assert_memory_equal(b->frame_ns, ns, 4 * sizeof *ns);   /* bit for bit */
    assert_true(isnan(b->frame_ns[4]));
    assert_true(b->frame_ns[5] == 1.3e6);
    assert_int_equal(b->n_stutters, 1);
    assert_int_equal(b->stutter_at[0], 1);
    assert_int_equal(b->noisy, -1);
    assert_int_equal(back.configs[1].path.frames, 0);
    assert_int_equal(write_report_file(&back, "results.csv", NULL, csv, NULL), 0);
    assert_int_equal(write_report_file(&back, "summary.md", NULL, md, NULL), 0);
    tc = test_slurp(csv);
    tm = test_slurp(md);
    assert_non_null(strstr(tc, ",path_p99_ms,"));
    /* p99, 1 % low ms and fps, stutters; no quality along the path: empty */
    assert_non_null(strstr(tc, ",3.06,3.1,322.580645,1,,,,\r\n"));
    assert_non_null(strstr(tc, ",path_stutters,path_temporal_error_mean,path_temporal_error_p99,path_popping,"
                               "path_popping_frame\r\n"));
    assert_non_null(strstr(tm, "## Along the path"));
    assert_non_null(strstr(tm, "| 3 × 2 | 0.171 | 2.900 | 3.060 | 3.100 (323 fps) | 1 (frame 1) | "
                               "unknown (one replay) |"));
    free(tc);
    free(tm);
    dm_run_free(&back);
    /* a row short of its frames, then one replay too many */
    static const struct { const char *from, *to, *why; } bad[] = {
        {"[1000000, 3100000, 1100000]", "[1000000, 3100000]", "does not hold one time per frame"},
        {"\"replays\":\t2", "\"replays\":\t3", "not one array per replay"},
        {"\"stutter_frames\":\t[1]", "\"stutter_frames\":\t[3]", "not a frame index of the path"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char *at = strstr(t1, bad[i].from);
        assert_non_null(at);
        dm_str e = {0};
        dm_str_catn(&e, t1, (size_t)(at - t1));
        dm_str_cat(&e, bad[i].to);
        dm_str_cat(&e, at + strlen(bad[i].from));
        assert_int_equal(dm_write_file(p2, e.buf, e.len), 0);
        assert_int_equal(report_read_json(p2, &back, err, sizeof err), DM_ERR_PARSE);
        assert_non_null(strstr(err, bad[i].why));
        dm_str_free(&e);
    }
    free(t1);
    free(t2);
    dm_run_free(&run);
    unlink(p1);
    unlink(p2);
    unlink(csv);
    unlink(md);
    free(p1);
    free(p2);
    free(csv);
    free(md);
    test_rm_rf(dir);
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
    test_rm_rf(dir);
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
    assert_int_equal(write_report_file(&run, "results.csv", NULL, p, NULL), 0);
    char *t = test_slurp(p);
    size_t cols;
    char cell[64][64];
    memset(cell, 0, sizeof cell);
    assert_int_equal(csv_shape(t, &cols, cell, 64), 4);   /* header + 3 configs */
    /* key scene status reason | technique mesh steps scale note tess_level |
     * WallTime ×3 | TESInvocations | 11 quality (FLIP mean, median, max last) | label pareto |
     * WallTime drift-corrected ×3, drift_correction */
    assert_int_equal(cols, 4 + 6 + 3 + 1 + 11 + 2 + 4);
    assert_string_equal(cell[0], FIXTURE_KEY0);
    assert_string_equal(cell[8], "a,b \"quoted\"");   /* note param round-trips through quoting */
    assert_string_equal(cell[10], "1.1");              /* WallTime median, ms */
    assert_string_equal(cell[14], "0");                /* RMSE */
    assert_string_equal(cell[15], "inf");              /* PSNR_dB */
    assert_non_null(strstr(t, ",PSNR_dB,"));
    assert_non_null(strstr(t, ",label,pareto,WallTime_corr_median_ms,WallTime_corr_ci_lo_ms,"
                              "WallTime_corr_ci_hi_ms,drift_correction\r\n"));
    assert_string_equal(cell[27], "");   /* no drift record: no corrected figures ... */
    assert_string_equal(cell[30], "no drift record for its scene; raw figures only");   /* ... and why */
    assert_non_null(strstr(t, "WallTime_median_ms"));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* The fixture with WallTime drift-corrected: pom (unlit: never the pick
 * while a lit one is there) to 1.0 ms [0.98, 1.02] (raw 1.1 [1.0, 1.2]),
 * normal to 1.8 ms [1.75, 1.85] (raw 2.0 [1.95, 2.05]), and the scene's
 * record, under a 1.9 ms budget: on the raw figures nothing fits, on the
 * corrected ones normal does. */
static void fixture_corrected(dm_run_result *run)
{
    fixture_run(run);
    dm_counter_result *w = (dm_counter_result *)dm_config_counter(&run->configs[0], "WallTime");
    w->corrected = 1;
    w->corr_median = 1.0e6;
    w->corr_ci_lo = 0.98e6;
    w->corr_ci_hi = 1.02e6;
    w->corr_between = 1;
    w->corr_between_lo = 0.95e6;
    w->corr_between_hi = 1.06e6;
    w = (dm_counter_result *)dm_config_counter(&run->configs[1], "WallTime");
    w->corrected = 1;
    w->corr_median = 1.8e6;
    w->corr_ci_lo = 1.75e6;
    w->corr_ci_hi = 1.85e6;
    run->precision = dm_xcalloc(1, sizeof *run->precision);
    run->n_precision = 1;
    run->precision[0] = (dm_scene_precision){ .scene = dm_xstrdup(FIXTURE_SCENE), .corrected = 1,
                                              .predictor = dm_xstrdup("common mode"), .n_rounds = 12,
                                              .machine_spread = 0.08, .raw_noise = 0.1, .loo_noise = 0.04,
                                              .calib_noise = NAN, .resolvable = 0.03,
                                              .between_runs = 1, .reference_spread = 0.0125 };
    assert_int_equal(report_budget_set(run, 1.9), 0);
}

/* The terminal answer joined back into one line per paragraph: a wrapped
 * line goes on four or more columns deeper (answer.c), and the join puts
 * back the one space the wrap took.  Also asserts every line fits 100
 * columns (code points: the answer uses no wide characters). */
static char *answer_joined(const char *text)
{
    dm_str out = {0};
    size_t col = 0;
    for (const char *p = text; *p; p++) {
        if (*p == '\n' && strncmp(p + 1, "    ", 4) == 0) {
            while (p[1] == ' ')
                p++;
            dm_str_cat(&out, " ");
            col = 0;
            continue;
        }
        col = *p == '\n' ? 0 : col + ((*p & 0xC0) != 0x80);
        assert_true(col <= 100);
        dm_str_catn(&out, p, 1);
    }
    return dm_str_take(&out);
}

/* The terminal's answer for run, joined (answer_joined). */
static char *run_answer_joined(const dm_run_result *run)
{
    dm_str t = {0};
    report_answer_terminal(run, &t);
    char *a = answer_joined(dm_str_get(&t));
    dm_str_free(&t);
    return a;
}

/* Two lit configurations of one family, of equal quality, whose time CIs
 * overlap: the pick is the one whose key sorts first, whatever order the
 * run stored them in (the order they were measured) and whichever median
 * is lower (another run's noise), so two runs name the same pick. */
static void test_tie_named_by_key(void **state)
{
    (void)state;
    static const double med[2][2] = { { 1.00e6, 1.04e6 }, { 1.04e6, 1.00e6 } };
    for (int order = 0; order < 2; order++)
        for (int m = 0; m < 2; m++) {
            dm_run_result run;
            memset(&run, 0, sizeof run);
            run.n_configs = 2;
            run.configs = dm_xcalloc(2, sizeof *run.configs);
            static const char *const key[2] = { "bbbb000000000000", "aaaa000000000000" };
            for (int i = 0; i < 2; i++) {
                dm_config_result *c = &run.configs[order ? 1 - i : i];
                fixture_config(c, key[i], i ? "normal" : "bump", "plane", 1);
                dm_kv_push(&c->params, &c->n_params, "lighting", "blinn-phong");
                fixture_timed(&c->counters[0], "WallTime", med[m][i] * 0.95, med[m][i], med[m][i] * 1.05);
                fixture_quality(&c->quality, 40, 0.95, 0.01);
            }
            recommend_result r;
            report_recommend(&run, FIXTURE_SCENE, &r);
            assert_int_not_equal(r.pick, RECOMMEND_NONE);
            assert_int_not_equal(r.pick_tie, RECOMMEND_NONE);
            assert_string_equal(run.configs[r.pick].key, "aaaa000000000000");
            assert_string_equal(run.configs[r.pick_tie].key, "bbbb000000000000");
            char *a = run_answer_joined(&run);   /* the terminal's answer names it, and says why */
            assert_non_null(strstr(a, "pick normal ("));
            assert_non_null(strstr(a, "It ties with bump"));
            assert_non_null(strstr(a, "the first by configuration key is named"));
            free(a);
            dm_run_free(&run);
        }
}

/* The near miss names its own configuration when the run stores the
 * scene's configurations in another order than their keys (the points are
 * sorted by key; the near miss was once left as a point index). */
static void test_near_miss_named(void **state)
{
    (void)state;
    dm_run_result run;
    memset(&run, 0, sizeof run);
    run.n_configs = 3;
    run.configs = dm_xcalloc(3, sizeof *run.configs);
    static const char *const key[3] = { "cccc000000000000", "aaaa000000000000", "bbbb000000000000" };
    static const char *const tech[3] = { "bump", "pom", "normal" };
    static const double med[3] = { 1.0e6, 2.1e6, 1.5e6 }, lo[3] = { 0.98e6, 1.9e6, 1.47e6 };
    static const double ssim[3] = { 0.90, 0.99, 0.96 };
    for (int i = 0; i < 3; i++) {
        dm_config_result *c = &run.configs[i];
        fixture_config(c, key[i], tech[i], "plane", 1);
        dm_kv_push(&c->params, &c->n_params, "lighting", "blinn-phong");
        fixture_timed(&c->counters[0], "WallTime", lo[i], med[i], 2 * med[i] - lo[i]);
        fixture_quality(&c->quality, 40, ssim[i], 0.01);
    }
    assert_int_equal(report_budget_set(&run, 2), 0);
    recommend_result r;
    report_recommend(&run, FIXTURE_SCENE, &r);
    /* normal (1.5 ms) is the best within 2 ms; pom (2.1 ms, CI from 1.9)
     * is clearly better and may also fit */
    assert_int_equal(r.pick, 2);
    assert_int_equal(r.near_miss, 1);
    char *a = run_answer_joined(&run);
    assert_non_null(strstr(a, "pick normal ("));
    assert_non_null(strstr(a, "May also fit: pom ("));
    free(a);
    dm_run_free(&run);
}

/* Raw and corrected figures side by side in every file, the noise floor
 * and the verdict on which they disagree. */
static void test_corrected_figures(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_corr_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    char *pc = dm_xasprintf("%s/r.csv", dir), *pm = dm_xasprintf("%s/s.md", dir);
    char *pj = dm_xasprintf("%s/a.json", dir), *pj2 = dm_xasprintf("%s/b.json", dir);
    char *ph = dm_xasprintf("%s/r.html", dir);
    dm_run_result run, back;
    fixture_corrected(&run);
    /* the floor: the median of the corrected half-widths 0.02 and 0.05 / 1.8 */
    double floor, res, want = (0.02 + 0.05 / 1.8) / 2;
    assert_int_equal(dm_run_noise_floor(&run, &floor, &res), 2);
    assert_float_equal(floor, want, 1e-15);
    assert_float_equal(res, want * sqrt(2.0), 1e-15);   /* 3.378 % */
    /* the verdicts: nothing fits raw, normal fits corrected */
    recommend_result r, c;
    report_recommend(&run, FIXTURE_SCENE, &r);
    assert_int_equal(r.pick, RECOMMEND_NONE);
    assert_int_equal(report_recommend_corrected(&run, FIXTURE_SCENE, &c), 1);
    assert_int_equal(c.pick, 1);
    dm_str d = {0};
    assert_int_equal(report_answer_disagree(&run, FIXTURE_SCENE, &d), 1);
    assert_string_equal(dm_str_get(&d), "Raw and drift-corrected figures disagree: with the machine's "
                        "drift removed the pick is normal mesh=plane; the answer reads the raw figures, "
                        "where nothing fits.");
    dm_str_free(&d);
    /* results.csv: the corrected columns and the method */
    assert_int_equal(write_report_file(&run, "results.csv", NULL, pc, NULL), 0);
    char *t = test_slurp(pc);
    size_t cols;
    char cell[64][64];
    memset(cell, 0, sizeof cell);
    assert_int_equal(csv_shape(t, &cols, cell, 64), 4);
    assert_string_equal(cell[10], "1.1");
    assert_string_equal(cell[27], "1");
    assert_string_equal(cell[28], "0.98");
    assert_string_equal(cell[29], "1.02");
    assert_int_equal(strncmp(cell[30], REPORT_DRIFT_METHOD, 63), 0);
    free(t);
    /* summary.md: both times in the row, the precision line, the disagreement */
    assert_int_equal(write_report_file(&run, "summary.md", NULL, pm, NULL), 0);
    t = test_slurp(pm);
    assert_non_null(strstr(t, "| pom mesh=plane | 1.10 | ±9.1% ⚠ noisy | 1.00 ms [0.980, 1.02] | "));
    assert_non_null(strstr(t, "| normal mesh=plane | 2.00 | ±2.5% | 1.80 ms [1.75, 1.85] | "));
    assert_non_null(strstr(t, "- precision: Noise floor ±"));
    assert_non_null(strstr(t, "over 2 configurations); the smallest difference between two configurations "
                              "this run resolves is 3.4 %"));
    assert_non_null(strstr(t, "removed in 1 of 1 scenes"));
    assert_non_null(strstr(t, "with the machine's drift removed the pick is normal mesh=plane"));
    free(t);
    /* report.html: the corrected time under the raw CI, the precision paragraph */
    assert_int_equal(write_report_file(&run, "report.html", NULL, ph, NULL), 0);
    t = test_slurp(ph);
    assert_non_null(strstr(t, "drift removed: 1.00 ms [0.980, 1.02]</span>"));
    assert_non_null(strstr(t, "<p class=\"precision\">Noise floor"));
    assert_non_null(strstr(t, "drift removed the pick is normal mesh=plane"));
    free(t);
    /* results.json: corrected beside raw, the precision record; it reads back the same */
    assert_int_equal(write_report_file(&run, "results.json", NULL, pj, NULL), 0);
    assert_int_equal(report_read_json(pj, &back, err, sizeof err), 0);
    assert_int_equal(write_report_file(&back, "results.json", NULL, pj2, NULL), 0);
    char *t2 = test_slurp(pj2);
    t = test_slurp(pj);
    assert_string_equal(t, t2);
    assert_non_null(strstr(t, "\"corrected\":\t{\n"));
    assert_non_null(strstr(t, "\"ci95\":\t[980000, 1020000]"));
    /* the between-run CI where computed; null with the reason where not */
    assert_non_null(strstr(t, "\"ci95_between_runs\":\t[950000, 1060000]"));
    assert_non_null(strstr(t, "\"ci95_between_runs\":\tnull"));
    assert_non_null(strstr(t, "\"between_runs_unavailable\":\t\"" REPORT_BETWEEN_UNAVAILABLE "\""));
    assert_non_null(strstr(t, "\"reference_spread\":\t0.0125"));
    assert_non_null(strstr(t, "\"predictor\":\t\"common mode\""));
    assert_non_null(strstr(t, "\"disagreement\":\t\"Raw and drift-corrected figures disagree"));
    const dm_counter_result *w = dm_config_counter(&back.configs[0], "WallTime");
    assert_int_equal(w->corrected, 1);
    assert_float_equal(w->corr_median, 1.0e6, 0);
    assert_int_equal(back.n_precision, 1);
    assert_float_equal(back.precision[0].loo_noise, 0.04, 0);
    assert_true(isnan(back.precision[0].calib_noise));
    free(t);
    free(t2);
    dm_run_free(&back);
    dm_run_free(&run);
    const char *files[] = {pc, pm, pj, pj2, ph};
    for (size_t i = 0; i < 5; i++) {
        unlink(files[i]);
        free((char *)files[i]);
    }
    test_rm_rf(dir);
}

static void test_markdown(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_md_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/s.md", dir);
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, p, NULL), 0);
    char *t = test_slurp(p);
    assert_non_null(strstr(t, "## " FIXTURE_SCENE "\n"));
    /* rows sorted by time; CI as a relative half-width: 0.1/1.1 = 9.1 %, 0.05/2 = 2.5 % */
    /* last quality column: the default Pareto metric, 1 − SSIM, at one
     * precision for the column (0.0000 and 0.0500, not 0 and 0.05) */
    assert_non_null(strstr(t, "- Pareto metric: ssim (1 - SSIM)\n"));
    assert_non_null(strstr(t, "| drift removed: ms [95% CI] | PSNR | SSIM | 1 - SSIM | key |"));
    /* three significant digits; ±9.1 % is noisy (over ±5 %): marked in the row */
    /* the failed sphere configuration makes mesh an axis of the scene's labels */
    assert_non_null(strstr(t, "| pom mesh=plane | 1.10 | ±9.1% ⚠ noisy | raw only | ∞ | 1.0000 | 0.0000 | `" FIXTURE_KEY0 "` |"));
    assert_non_null(strstr(t, "| normal mesh=plane | 2.00 | ±2.5% | raw only | 38.25 dB | 0.9500 | 0.0500 | `" FIXTURE_KEY1 "` |"));
    assert_true(strstr(t, "| pom mesh=plane |") < strstr(t, "| normal mesh=plane |"));
    /* pom is faster and exact (SSIM 1): it alone is the Pareto front */
    assert_non_null(strstr(t, "Front (best 1 - SSIM for its cost, fastest first): "
                              "pom mesh=plane (1.1 ms, SSIM 1.000)."));
    assert_non_null(strstr(t, FIXTURE_REASON));
    assert_non_null(strstr(t, FIXTURE_LEFT_REASON));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* Every src="..." and href="..." in the page is an embedded PNG
 * (data:image/png;base64, starting with the PNG signature, "iVBORw0KGgo"),
 * an anchor in the page ("#...", not counted) or names a file that exists
 * relative to dir.  Counts the rest. */
static int all_refs_exist(const char *html, const char *dir, const char *attr, int *count)
{
    *count = 0;
    size_t al = strlen(attr);
    for (const char *p = strstr(html, attr); p; p = strstr(p + 1, attr)) {
        const char *b = p + al, *e = strchr(b, '"');
        if (*b == '#')
            continue;
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

/* A configuration with a FLIP map: the gallery shows it with its mean and
 * maximum in the caption, and the fixed scale drawn from flip_colormap
 * (anchor 0 = #000004, anchor 1 = #fcfcbf). */
static void test_html_flip_maps(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_flip_XXXXXX", err[512];
    assert_non_null(mkdtemp(dir));
    assert_int_equal(fixture_images(dir, err, sizeof err), 0);
    char *p = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    fixture_run(&run);
    dm_config_result *c = &run.configs[0];
    c->img_flip = dm_xstrdup(fixture_img_files[2]);
    c->quality.flip = 0.04521;
    c->quality.flip_max = 0.5192;
    c->quality.flip_ppd = 67.0206;
    c->quality.max_error = 1.36;
    assert_int_equal(write_report_file(&run, "report.html", dir, p, NULL), 0);
    char *t = test_slurp(p);
    /* c0's heatmap is its FLIP map (one file under both keys): one card,
     * its legend FLIP's scale in the words of `diff --heatmap`'s help,
     * before the cards, and no MaxError in its caption (no saturation) */
    assert_non_null(strstr(t, "src=\"img/c0_heat.png\" alt=\"heatmap (FLIP): "));
    assert_null(strstr(t, "alt=\"FLIP: "));
    const char *cap = strstr(t, ", FLIP 0.0452 (max 0.519)</p>");
    assert_non_null(cap);
    while (cap > t && strncmp(cap, "<p class=\"cap\">", 15) != 0)
        cap--;
    assert_null(memmem(cap, (size_t)(strstr(cap, "</p>") - cap), "MaxError", 8));
    const char *legend = strstr(t, "<p class=\"const\">Heatmap: " FLIP_SCALE_TEXT ", at 67 pixels per degree");
    assert_non_null(legend);
    assert_true(legend < strstr(t, "<div class=\"grid\">"));
    assert_non_null(strstr(legend, "background:linear-gradient(90deg,#000004,"));
    assert_non_null(strstr(legend, ",#fcfcbf)\"></span> 1, the same colour"));
    assert_null(strstr(t, "saturates the heatmap"));
    free(t);
    /* an older run: the heatmap a |render − reference| map, the FLIP map a
     * file of its own; both legends, both cards, MaxError marked */
    free(c->img_flip);
    c->img_flip = dm_xstrdup(fixture_img_files[3]);
    assert_int_equal(write_report_file(&run, "report.html", dir, p, NULL), 0);
    t = test_slurp(p);
    assert_non_null(strstr(t, "src=\"img/c0_heat.png\" alt=\"heatmap: "));
    assert_non_null(strstr(t, "alt=\"FLIP: "));
    assert_non_null(strstr(t, "Heatmap: |render − reference|"));
    assert_non_null(strstr(t, "FLIP map: " FLIP_SCALE_TEXT ", at 67 pixels per degree"));
    assert_non_null(strstr(t, ", MaxError 1.36 (saturates the heatmap), FLIP 0.0452 (max 0.519)</p>"));
    free(t);
    dm_run_free(&run);
    fixture_images_remove(dir);
    unlink(p);
    free(p);
    test_rm_rf(dir);
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
    assert_int_equal(write_report_file(&run, "report.html", dir, p, NULL), 0);
    char *t = test_slurp(p);
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
    /* c0: 3 images, c1: render only (heatmap absolute, reference ".."),
     * and c1's render again beside its scene's charts: c1 is the pick (the
     * scene's only lit configuration) */
    assert_non_null(strstr(t, "<div class=\"pair pick-images\"><figure><img loading=\"lazy\" "
                              "src=\"img/c1_render.png\""));
    assert_true(all_refs_exist(t, dir, " src=\"", &n));
    assert_int_equal(n, 5);
    /* the reference is embedded once and links its file; renders and
     * heatmaps load from img/ beside the report, each with a full-size
     * link (c0 render and heatmap, c1 render twice) */
    assert_true(all_refs_exist(t, dir, " href=\"", &n));
    assert_int_equal(n, 5);
    /* the reference's card: its thumbnail, and its file for a full-size flip */
    assert_non_null(strstr(t, "<div class=\"pair ref\"><figure><a href=\"img/c0_ref.png\"><img id=\"ref-0\" "
                              "data-full=\"img/c0_ref.png\" src=\"data:image/png;base64,"));
    assert_non_null(strstr(t, "<img loading=\"lazy\" src=\"img/c0_render.png\" class=\"flip\" data-ref=\"ref-0\""));
    assert_non_null(strstr(t, "<img loading=\"lazy\" src=\"img/c0_heat.png\" alt=\"heatmap: "));
    assert_non_null(strstr(t, "heatmap · <a class=\"full\" href=\"img/c0_heat.png\">full size</a>"));
    assert_non_null(strstr(t, "<span class=\"scale\"></span>"));
    /* written elsewhere (report --out): links go to the run directory */
    char *other = dm_xasprintf("%s/other.html", dir);
    assert_int_equal(write_report_file(&run, "report.html", dir, other, "/abs/run/"), 0);
    char *o = test_slurp(other);
    assert_non_null(strstr(o, "<a href=\"/abs/run/img/c0_ref.png\">"));
    assert_non_null(strstr(o, "src=\"/abs/run/img/c0_heat.png\""));
    free(o);
    unlink(other);
    free(other);
    assert_non_null(strstr(t, "path refused: /etc/passwd"));
    assert_non_null(strstr(t, "path refused: ../outside.png"));
    /* the fit's parameters with their units (ns: WallTime's) */
    assert_non_null(strstr(t, "<th>parameters ± stderr, unit</th>"));
    assert_non_null(strstr(t, "<td>a = 1 ± 0.5 ns<br>b = 2 ± 0.25 ns per tess_level^p<br></td>"));
    /* the legend before the cards, its scale stated with the largest
     * difference: c1's MaxError, 4 × RMSE 0.0122 */
    assert_true(strstr(t, "Heatmap: |render − reference|") < strstr(t, "<div class=\"grid\">"));
    assert_non_null(strstr(t, "The largest difference in this scene (MaxError) is 0.0488. Click"));
    assert_null(strstr(t, "saturate"));
    assert_non_null(strstr(t, "<h2 id=\"failed\">Failed configurations</h2>\n<div class=\"fail\">"));
    assert_non_null(strstr(t, "<h2>Left out</h2>\n<table><tr><th>params</th>"));
    free(t);
    /* a difference past a channel's range saturates the map: the legend and
     * the caption say so; no left-out configuration: "None.", no empty table */
    run.configs[1].quality.max_error = 1.36;
    size_t left = run.n_left_out;
    run.n_left_out = 0;
    assert_int_equal(write_report_file(&run, "report.html", dir, p, NULL), 0);
    run.n_left_out = left;
    t = test_slurp(p);
    assert_non_null(strstr(t, "(MaxError) is 1.36: its hottest pixels saturate the map."));
    assert_non_null(strstr(t, ", MaxError 1.36 (saturates the heatmap)</p>"));
    assert_non_null(strstr(t, "<h2>Left out</h2>\n<p class=\"const\">None.</p>"));
    assert_null(strstr(t, "<th>params</th>"));
    free(t);
    dm_run_free(&run);
    fixture_images_remove(dir);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

static void test_write_all(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_all_XXXXXX", err[512];
    static const char *names[] = {"results.json", "results.csv", "summary.md", "report.html"};
    assert_non_null(mkdtemp(dir));
    dm_run_result run;
    fixture_run(&run);
    assert_int_equal(report_write_run(&run, &(report_desc){.dir = dir}, err, sizeof err), 0);
    for (int i = 0; i < 4; i++) {
        char *p = dm_xasprintf("%s/%s", dir, names[i]);
        assert_true(dm_file_exists(p));
        unlink(p);
        free(p);
    }
    char *missing = dm_xasprintf("%s/no/such/dir", dir);
    assert_int_equal(report_write_run(&run, &(report_desc){.dir = missing}, err, sizeof err), DM_ERR_IO);
    assert_non_null(strstr(err, "results.json"));
    free(missing);
    dm_run_free(&run);
    test_rm_rf(dir);
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
        assert_int_equal(write_report_file(&run, "report.html", NULL, p, NULL), 0);
    char *t = test_slurp(p);
    int svgs = 0;
    for (const char *q = strstr(t, "<svg"); q; q = strstr(q + 1, "<svg"))
        svgs++;
    assert_int_equal(svgs, 3);   /* error vs time, time per configuration, time vs tess_level */
    assert_null(strstr(t, "http://"));
    assert_null(strstr(t, "<b>x"));
    /* the answer table comes first, before any scene table or chart */
    const char *ol = strstr(t, "<table class=\"answer front\" id=\"front-0\">");
    assert_non_null(ol);
    assert_true(ol < strstr(t, "<svg") && ol < strstr(t, "id=\"tbl-0\"") && ol < strstr(t, "id=\"environment\""));
    const char *end = strstr(ol, "</table>");
    /* ms ± CI and the cost relative to the fastest; L=2 and L=4 CIs (±10 %)
     * do not overlap their predecessor's, so nothing is marked tied.  The
     * default budget is 3 ms (1, 2, 4 and 8 ms: three gaps of a factor 2,
     * and the one between 2 and 4 ms splits the four in half; 3 ms is the
     * roundest value in its middle half, 2.38-3.36 ms); with a budget of 5
     * ms set, L=4 is the pick and L=2 a plain row */
    recommend_result rec;
    report_recommend(&run, "s", &rec);
    assert_int_equal(rec.budget_default, 1);
    assert_true(fabs(rec.budget - 3e6) < 1);
    assert_string_equal(dm_kv_get(run.configs[rec.pick].params, run.configs[rec.pick].n_params, "tess_level"), "2");
    assert_int_equal(report_budget_set(&run, 5), 0);
    assert_int_equal(write_report_file(&run, "report.html", NULL, p, NULL), 0);
    free(t);
    t = test_slurp(p);
    ol = strstr(t, "<table class=\"answer front\" id=\"front-0\">");
    end = strstr(ol, "</table>");
    assert_non_null(strstr(ol, "<td>tessdisp</td><td>tess_level=2</td><td class=\"n\">2.00</td><td class=\"n\">±10%"));
    assert_non_null(strstr(ol, "<tr class=\"pick\"><td>tessdisp <b>← pick</b></td><td>tess_level=4</td>"));
    assert_non_null(strstr(ol, "×4.00</td>"));
    assert_true(!strstr(ol, "tied with") || strstr(ol, "tied with") > end);
    const char *k0 = strstr(ol, "tess_level=1<"), *k1 = strstr(ol, "tess_level=2<");
    const char *k2 = strstr(ol, "tess_level=4<"), *k3 = strstr(ol, "tess_level=8<");
    const char *k4 = strstr(ol, "x#y");
    assert_true(k0 && k1 && k2 && k0 < k1 && k1 < k2 && k2 < end);
    assert_true(!k3 || k3 > end);
    assert_true(!k4 || k4 > end);
    free(t);
    /* L=2's CI reaching down into L=1's: of different quality, so no tie is
     * said (times are tied only between equal qualities); one pick */
    run.configs[1].counters[0].ci_lo = 1.0e6;
    assert_int_equal(write_report_file(&run, "report.html", NULL, p, NULL), 0);
    t = test_slurp(p);
    ol = strstr(t, "id=\"front-0\"");
    assert_null(strstr(t, "≈ tied"));
    const char *pick = strstr(ol, "← pick");
    assert_true(pick && pick < strstr(ol, "</table>"));
    assert_null(strstr(pick + 1, "← pick"));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* Four configurations at 1, 2, 3, 4 ms whose fronts differ by metric:
 *   c0: SSIM 0.80, RMSE 0.05, PSNR 30, depth NaN
 *   c1: SSIM 0.90, RMSE 0.06, PSNR 35, depth 0.3
 *   c2: SSIM 0.95, RMSE 0.02, PSNR ∞,  depth 0.1
 *   c3: SSIM 0.85, RMSE 0.01, PSNR 40, depth 0.2
 * ssim (1 − SSIM .20 .10 .05 .15): c0 c1 c2 (c3 dominated by c2)
 * rmse: c0 c2 c3 (c1 slower and worse than c0)
 * psnr (higher is better; ∞ is best): c0 c1 c2 (c3 dominated by c2)
 * depth-rmse (c0 has none): c1 c2 (c3 dominated by c2) */
static void metric_run(dm_run_result *r)
{
    static const double ssim[] = {0.80, 0.90, 0.95, 0.85}, rmse[] = {0.05, 0.06, 0.02, 0.01};
    static const double psnr[] = {30, 35, INFINITY, 40}, depth[] = {NAN, 0.3, 0.1, 0.2};
    memset(r, 0, sizeof *r);
    r->sweep = dm_xstrdup("metrics");
    r->n_configs = 4;
    r->configs = dm_xcalloc(4, sizeof *r->configs);
    for (int i = 0; i < 4; i++) {
        dm_config_result *c = &r->configs[i];
        c->key = dm_xasprintf("00000000000000d%d", i);
        c->scene = dm_xstrdup("s");
        c->ok = 1;
        dm_kv_push(&c->params, &c->n_params, "technique", "pom");
        char steps[8];
        snprintf(steps, sizeof steps, "%d", 8 << i);
        dm_kv_push(&c->params, &c->n_params, "steps", steps);
        c->n_counters = 1;
        c->counters = dm_xcalloc(1, sizeof *c->counters);
        fixture_timed(&c->counters[0], "WallTime", (i + 1) * 0.99e6, (i + 1) * 1e6, (i + 1) * 1.01e6);
        fixture_quality(&c->quality, psnr[i], ssim[i], rmse[i]);
        c->quality.depth_rmse = depth[i];
    }
}

static void assert_front(const dm_run_result *run, const char *metric, const size_t *want, size_t n)
{
    size_t *front, nf = report__pareto(run, "s", &front);
    if (nf != n)
        fail_msg("%s: %zu front members, want %zu", metric, nf, n);
    for (size_t i = 0; i < n; i++)
        if (front[i] != want[i])
            fail_msg("%s: front[%zu] = c%zu, want c%zu", metric, i, front[i], want[i]);
    free(front);
}

static void test_metric_fronts(void **state)
{
    (void)state;
    dm_run_result run;
    metric_run(&run);
    static const size_t by_ssim[] = {0, 1, 2}, by_rmse[] = {0, 2, 3}, by_depth[] = {1, 2};
    assert_front(&run, "default", by_ssim, 3);
    assert_int_equal(report_metric_set(&run, "rmse"), 0);
    assert_front(&run, "rmse", by_rmse, 3);
    assert_int_equal(report_metric_set(&run, "max-error"), 0);   /* fixture: 4 × RMSE */
    assert_front(&run, "max-error", by_rmse, 3);
    assert_int_equal(report_metric_set(&run, "psnr"), 0);
    assert_front(&run, "psnr", by_ssim, 3);
    assert_int_equal(report_metric_set(&run, "depth-rmse"), 0);
    assert_front(&run, "depth-rmse", by_depth, 2);
    assert_int_equal(report_metric_set(&run, "ssim"), 0);
    assert_front(&run, "ssim", by_ssim, 3);
    /* set replaces, never duplicates; a bad name leaves the run as it was */
    assert_int_equal(report_metric_set(&run, "1-ssim"), DM_ERR_ARG);
    size_t seen = 0;
    for (size_t i = 0; i < run.n_environment; i++)
        seen += strcmp(run.environment[i].key, REPORT_METRIC_KEY) == 0;
    assert_int_equal(seen, 1);
    assert_string_equal(dm_kv_get(run.environment, run.n_environment, REPORT_METRIC_KEY), "ssim");
    dm_run_free(&run);
}

static void test_metric_names(void **state)
{
    (void)state;
    report_metric m = REPORT_METRIC_COUNT;
    assert_int_equal(report_metric_parse("silhouette", &m), 0);
    assert_int_equal(m, REPORT_METRIC_SILHOUETTE);
    assert_int_equal(report_metric_parse("SSIM", &m), DM_ERR_ARG);
    assert_int_equal(report_metric_parse(NULL, &m), DM_ERR_ARG);
    assert_int_equal(m, REPORT_METRIC_SILHOUETTE);
    dm_str e = {0};
    report_metric_unknown("dpeth-rmse", &e);
    assert_string_equal(dm_str_get(&e), "unknown metric 'dpeth-rmse'; did you mean 'depth-rmse'? "
                                         "valid metrics: ssim, psnr, rmse, max-error, silhouette, depth-rmse, flip");
    dm_str_free(&e);
    dm_quality q = {.present = 1, .psnr = INFINITY, .ssim = 0.25};
    assert_true(report_metric_error(&q, REPORT_METRIC_PSNR) == -DBL_MAX);
    assert_true(report_metric_error(&q, REPORT_METRIC_SSIM) == 0.75);
    q.psnr = 20;
    assert_true(report_metric_error(&q, REPORT_METRIC_PSNR) == -20);
    assert_true(report_metric_shown(&q, REPORT_METRIC_PSNR) == 20);
    q.present = 0;
    assert_true(isnan(report_metric_error(&q, REPORT_METRIC_SSIM)));
}

/* The chosen metric is named in summary.md, the HTML table, chart and front. */
/* An axis left out of a configuration at its default reads as that default
 * (dm_param_value): pom with cull off beside pom at the default cull varies
 * in cull, so the first is labelled "pom cull=off" and the second "pom";
 * without the second the axis does not vary and neither label names it. */
static void test_label_default_left_out(void **state)
{
    (void)state;
    dm_run_result r;
    memset(&r, 0, sizeof r);
    r.sweep = dm_xstrdup("cull");
    r.n_configs = 2;
    r.configs = dm_xcalloc(2, sizeof *r.configs);
    for (int i = 0; i < 2; i++) {
        dm_config_result *c = &r.configs[i];
        c->key = dm_xasprintf("00000000000000d%d", i);
        c->scene = dm_xstrdup("s");
        c->ok = 1;
        dm_kv_push(&c->params, &c->n_params, "technique", "pom");
        if (i == 0)
            dm_kv_push(&c->params, &c->n_params, "cull", "off");
    }
    dm_str l0 = {0}, l1 = {0};
    report_config_label(&r, &r.configs[0], &l0);
    report_config_label(&r, &r.configs[1], &l1);
    assert_non_null(strstr(dm_str_get(&l0), "pom cull=off"));
    assert_null(strstr(dm_str_get(&l1), "cull"));
    assert_int_equal(report__param_varies(&r, "s", "cull"), 1);
    r.n_configs = 1;   /* alone, the left-out default is not a variation */
    assert_int_equal(report__param_varies(&r, "s", "cull"), 0);
    dm_str_free(&l0);
    report_config_label(&r, &r.configs[0], &l0);
    assert_null(strstr(dm_str_get(&l0), "cull"));
    r.n_configs = 2;
    dm_str_free(&l0);
    dm_str_free(&l1);
    dm_run_free(&r);
}

static void test_metric_in_files(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_metric_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *md = dm_xasprintf("%s/summary.md", dir), *html = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    metric_run(&run);
    assert_int_equal(report_metric_set(&run, "rmse"), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    char *t = test_slurp(md);
    assert_non_null(strstr(t, "- Pareto metric: rmse (RMSE)\n"));
    assert_non_null(strstr(t, "Front (best RMSE for its cost, fastest first): "
                              "pom steps=8 (1 ms, RMSE 0.05); then pom steps=32 (3 ms, RMSE 0.02); "
                              "then pom steps=64 (4 ms, RMSE 0.01)."));
    assert_non_null(strstr(t, "| PSNR | SSIM | RMSE | key |"));
    free(t);
    t = test_slurp(html);
    assert_non_null(strstr(t, "<th>95% CI</th><th>RMSE</th><th>SSIM</th><th>PSNR dB</th><th>Pareto</th>"));
    int marks = 0;   /* c0, c2, c3 marked in the table; c1 not */
    for (const char *q = strstr(t, "<td>★ front</td>"); q; q = strstr(q + 1, "<td>★ front</td>"))
        marks++;
    assert_int_equal(marks, 3);
    assert_non_null(strstr(t, "<td class=\"n\">0.0600</td><td class=\"n\">0.9000</td><td class=\"n\">35.00</td><td></td>"));
    assert_non_null(strstr(t, "Quality is <b>rmse</b> (RMSE) against the reference"));
    assert_non_null(strstr(t, "<th>RMSE</th><th>cost vs fastest lit</th>"));
    free(t);
    /* under psnr, one PSNR column: the metric's, at two decimals (35.00) */
    assert_int_equal(report_metric_set(&run, "psnr"), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    t = test_slurp(md);
    assert_non_null(strstr(t, "| configuration | median ms | 95% CI | drift removed: ms [95% CI] | SSIM | "
                              "PSNR (dB, higher is better) | key |\n|---|---|---|---|---|---|---|\n"));
    assert_null(strstr(t, "| PSNR |"));
    assert_non_null(strstr(t, " | 0.9000 | 35.00 | `"));
    free(t);
    t = test_slurp(html);
    assert_non_null(strstr(t, "<th>PSNR (dB, higher is better)</th><th>SSIM</th><th>Pareto</th>"));
    assert_null(strstr(t, "PSNR dB"));
    assert_non_null(strstr(t, "<td class=\"n\">35.00</td><td class=\"n\">0.9000</td><td>"));
    free(t);
    dm_run_free(&run);
    unlink(md);
    unlink(html);
    free(md);
    free(html);
    test_rm_rf(dir);
}

/* n configurations "pom steps=i", key 00000000000000eI (I in hex), whose
 * WallTime CI half-width is rel[i] of a 1 ms median (NaN: CI unknown). */
static void noisy_run(dm_run_result *r, const double *rel, size_t n)
{
    memset(r, 0, sizeof *r);
    r->sweep = dm_xstrdup("noise");
    r->n_configs = n;
    r->configs = dm_xcalloc(n, sizeof *r->configs);
    for (size_t i = 0; i < n; i++) {
        dm_config_result *c = &r->configs[i];
        c->key = dm_xasprintf("00000000000000e%zx", i);
        c->scene = dm_xstrdup("s");
        c->ok = 1;
        char steps[24];
        snprintf(steps, sizeof steps, "%zu", i);
        dm_kv_push(&c->params, &c->n_params, "technique", "pom");
        dm_kv_push(&c->params, &c->n_params, "steps", steps);
        c->n_counters = 1;
        c->counters = dm_xcalloc(1, sizeof *c->counters);
        fixture_timed(&c->counters[0], "WallTime", 1e6 * (1 - rel[i]), 1e6, 1e6 * (1 + rel[i]));
    }
}

/* The text of the first element starting with `open` up to `close`. */
__attribute__((noinline)) static char *between(const char *t, const char *open, const char *close)
{
    const char *a = strstr(t, open), *b = a ? strstr(a, close) : NULL;
    assert_non_null(b);
    return dm_xasprintf("%.*s", (int)(b - a), a);
}

/* Noisy = ok with a CI half-width over 5 % of the median, or unknown:
 * e0 1 %, e1 4.9 %, e2 5.1 %, e3 20 %, e4 failed (50 %), e5 unknown, e6 no
 * WallTime at all.  Exactly e2, e3 and e5 are named. */
static void test_noisy_warning(void **state)
{
    (void)state;
    static const double rel[] = {0.01, 0.049, 0.051, 0.20, 0.5, 0.0, 0.0};
    char dir[] = "/tmp/dm_reports_noisy_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *md = dm_xasprintf("%s/summary.md", dir), *html = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    noisy_run(&run, rel, 7);
    run.configs[4].ok = 0;
    run.configs[4].reason = dm_xstrdup("crashed");
    run.configs[5].counters[0].ci_lo = run.configs[5].counters[0].ci_hi = NAN;
    free(run.configs[6].counters[0].name);
    run.configs[6].counters[0].name = dm_xstrdup("CPUTime");
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    char *t = test_slurp(md);
    char *line = between(t, "- warning: ", "\n");
    assert_string_equal(line, "- warning: 3 noisy configurations: the 95% CI of the median frame time "
                              "is wider than ±5% of the median (or unknown); compare their times with care.");
    free(line);
    /* by label, a few to a line (no hashes) */
    line = between(t, "  - s · ", "\n");
    assert_string_equal(line, "  - s · pom steps=2 (CI ±5.1%); s · pom steps=3 (CI ±20%); "
                              "s · pom steps=5 (CI unknown)");
    free(line);
    free(t);
    t = test_slurp(html);
    char *box = between(t, "<div class=\"warn noisy\">", "</div>");
    assert_non_null(strstr(box, "<b>3 noisy configurations</b>"));
    assert_non_null(strstr(box, "<details open>"));
    static const char *named[] = {"s · pom steps=2 ±5.1%", "s · pom steps=3 ±20%", "s · pom steps=5 CI unknown"};
    for (int i = 0; i < 3; i++)
        assert_non_null(strstr(box, named[i]));
    for (int i = 0; i < 7; i++) {
        char label[32];
        snprintf(label, sizeof label, "pom steps=%d ", i);
        assert_int_equal(strstr(box, label) != NULL, i == 2 || i == 3 || i == 5);
    }
    free(box);
    free(t);
    dm_run_free(&run);
    /* many noisy ones: the list is collapsed; none: no box, no warning line */
    double many[12];
    for (int i = 0; i < 12; i++)
        many[i] = 0.1;
    noisy_run(&run, many, 12);
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    t = test_slurp(html);
    assert_non_null(strstr(t, "<div class=\"warn noisy\"><details><summary><b>12 noisy configurations</b>"));
    free(t);
    dm_run_free(&run);
    noisy_run(&run, many, 1);
    run.configs[0].counters[0].ci_lo = 0.99e6;
    run.configs[0].counters[0].ci_hi = 1.01e6;
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    t = test_slurp(html);
    assert_null(strstr(t, "warn noisy"));
    assert_null(strstr(t, "⚠ noisy"));
    free(t);
    t = test_slurp(md);
    assert_null(strstr(t, "noisy"));
    free(t);
    dm_run_free(&run);
    unlink(md);
    unlink(html);
    free(md);
    free(html);
    test_rm_rf(dir);
}

/* Header warnings about images and failures: exactly the failed one, the
 * one with non-finite pixels and the one with crack pixels are named, in
 * summary.md and report.html; a clean run has none. */
static void test_quality_warnings(void **state)
{
    (void)state;
    static const double rel[] = {0.01, 0.01, 0.01, 0.01};
    char dir[] = "/tmp/dm_reports_qwarn_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *md = dm_xasprintf("%s/summary.md", dir), *html = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    noisy_run(&run, rel, 4);
    run.configs[1].ok = 0;
    run.configs[1].reason = dm_xstrdup("shader failed");
    run.configs[2].quality.present = run.configs[3].quality.present = run.configs[0].quality.present = 1;
    run.configs[2].quality.nonfinite_pixels = 3;
    run.configs[3].quality.crack_pixels = 5;
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    assert_int_equal(write_report_file(&run, "report.html", NULL, html, NULL), 0);
    char *t = test_slurp(md);
    assert_non_null(strstr(t, "- warning: 1 configuration failed (see Failed configurations, with the reasons)\n"));
    assert_non_null(strstr(t, "- warning: 1 configuration with non-finite pixels: s · pom steps=2 "
                              "(3)\n"));
    assert_non_null(strstr(t, "- warning: 1 configuration with crack pixels (background enclosed by the "
                              "surface): s · pom steps=3 (5)\n"));
    assert_null(strstr(t, "e0] ("));
    free(t);
    t = test_slurp(html);
    assert_non_null(strstr(t, "<div class=\"warn\">1 configuration with crack pixels (background enclosed "
                              "by the surface): s · pom steps=3 (5)</div>"));
    assert_non_null(strstr(t, "<div class=\"warn\">1 configuration failed"));
    free(t);
    dm_run_free(&run);
    noisy_run(&run, rel, 2);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    t = test_slurp(md);
    assert_null(strstr(t, "- warning:"));
    free(t);
    dm_run_free(&run);
    unlink(md);
    unlink(html);
    free(md);
    free(html);
    test_rm_rf(dir);
}

/* The chart titles of an HTML page in order: every chart is one
 * <div class="chart" ... aria-label="T"> holding exactly one <svg> whose
 * text includes T (PLplot writes characters as &#xNN; references, the
 * hand-written charts escaped HTML). */
static size_t chart_titles(const char *html, char titles[][96], size_t max)
{
    static const char open[] = "<div class=\"chart\" role=\"img\" aria-label=\"";
    size_t n = 0;
    for (const char *p = strstr(html, open); p && n < max; p = strstr(p + 1, open)) {
        const char *t = p + strlen(open), *q = strchr(t, '"');
        snprintf(titles[n], 96, "%.*s", (int)(q - t), t);
        const char *svg = strstr(q, "<svg"), *end = strstr(q, "</svg>");
        assert_true(svg && end && svg == q + 2);         /* '">' then the svg */
        const char *next = strstr(svg + 1, "<svg");
        assert_true(!next || next > end);
        dm_str enc = {0};
        for (const char *c = titles[n]; *c; c++)
            dm_str_printf(&enc, "&#x%x;", (unsigned)(unsigned char)*c);
        char *body = dm_xasprintf("%.*s", (int)(end - svg), svg);
        if (!strstr(body, dm_str_get(&enc)) && !strstr(body, titles[n]))
            fail_msg("chart '%s': title not drawn in its SVG", titles[n]);
        free(body);
        dm_str_free(&enc);
        n++;
    }
    size_t svgs = 0;
    for (const char *q = strstr(html, "<svg"); q; q = strstr(q + 1, "<svg"))
        svgs++;
    assert_int_equal(svgs, n);
    return n;
}

static char *html_of(const dm_run_result *run, const char *path)
{
    assert_int_equal(write_report_file(run, "report.html", NULL, path, NULL), 0);
    return test_slurp(path);
}

/* The numbers of an attribute name="a b c" after at, into v (room for n);
 * how many. */
static size_t attr_numbers(const char *at, const char *name, double *v, size_t n)
{
    char *key = dm_xasprintf("%s=\"", name);
    const char *q = strstr(at, key);
    size_t k = 0;
    assert_non_null(q);
    q += strlen(key);
    free(key);
    while (*q != '"' && k < n) {
        char *end;
        v[k++] = strtod(q, &end);
        assert_true(end > q);
        q = end;
    }
    return k;
}

/* report.html along a camera path: a hand-made configuration of 3 frames ×
 * 2 replays with one time missing gets the scene's "Along the path" table
 * with its figures and a frame-time plot whose points are the per-frame
 * medians of its replays (computed here: (1.0 + 1/3) / 2, 3.1 alone, (1.1 +
 * 1.3) / 2 ms), the replays' min-max band, p50 and p99 lines and its stutter
 * at frame 1; a still run's page has none of them. */
static void test_html_path(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_reports_hpath_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *path = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    fixture_run(&run);
    char *still = html_of(&run, path);
    assert_null(strstr(still, "Along the path"));
    assert_null(strstr(still, "path-median"));
    free(still);
    dm_path_series *ps = &run.configs[0].path;
    static const double ns[] = {1.0e6, 3.1e6, 1.1e6, 1.0e6 / 3, NAN, 1.3e6};
    *ps = (dm_path_series){.frames = 3, .replays = 2, .p50 = 1.2e6, .p95 = 2.89e6, .p99 = 3.058e6,
                           .low1_ns = 3.1e6, .low1_fps = 1e9 / 3.1e6, .n_stutters = 1,
                           .replay_spread = 0.4, .noisy = 1};
    ps->frame_ns = dm_xmalloc(sizeof ns);
    memcpy(ps->frame_ns, ns, sizeof ns);
    ps->stutter_at = dm_xcalloc(1, sizeof *ps->stutter_at);
    ps->stutter_at[0] = 1;
    char *html = html_of(&run, path);
    const char *sec = strstr(html, "<section class=\"path-scene\" id=\"path-0\"><h3>Along the path: ");
    assert_non_null(sec);
    assert_non_null(strstr(sec, "<td class=\"n\">3 × 2</td><td class=\"n\">1.200</td><td class=\"n\">2.890</td>"
                                "<td class=\"n\">3.058</td><td class=\"n\">3.100 ms (323 fps)</td>"
                                "<td class=\"n\">1 (frame 1)</td><td class=\"n\" title="));
    assert_non_null(strstr(sec, "40.0 % <span class=\"noisy\">⚠ noisy</span>"));
    const char *plot = strstr(sec, "aria-label=\"Frame time along the path: ");
    assert_non_null(plot);
    double want[3] = {(1.0 + 1.0 / 3) / 2, 3.1, (1.1 + 1.3) / 2}, got[4], band[8];
    assert_int_equal(attr_numbers(strstr(plot, "class=\"path-median\""), "data-ms", got, 4), 3);
    for (size_t f = 0; f < 3; f++)
        assert_true(fabs(got[f] - want[f]) < 1e-8);
    /* the median line: one point per frame, the slowest (frame 1) highest */
    const char *d = strstr(strstr(plot, "class=\"path-median\""), " d=\"");
    double x[3], y[3];
    assert_int_equal(sscanf(d, " d=\"M%lf,%lf L%lf,%lf L%lf,%lf \"", &x[0], &y[0], &x[1], &y[1], &x[2], &y[2]), 6);
    assert_true(x[0] < x[1] && x[1] < x[2] && y[1] < y[2] && y[2] < y[0]);
    /* the band: up along the max (1.0, 3.1, 1.3), back along the min (1.1, 3.1, 1/3) */
    const char *b = strstr(plot, "class=\"path-band\"");
    assert_non_null(b);
    assert_int_equal(sscanf(strstr(b, " d=\""), " d=\"M%lf,%lf L%lf,%lf L%lf,%lf L%lf,%lf L%lf,%lf L%lf,%lf Z",
                            &band[0], &band[1], &band[2], &band[3], &band[4], &band[5], &band[6], &band[7],
                            &got[0], &got[1], &got[2], &got[3]), 12);
    /* (y grows downward) frame 0's max 1.0 and frame 2's 1.3 over their
     * medians, frame 1's one time on it, the mins 1.1 and 1/3 under them */
    assert_true(band[1] < y[0] && fabs(band[3] - y[1]) < 1e-9 && band[5] < y[2]);
    assert_true(band[7] > y[2] && fabs(got[1] - y[1]) < 1e-9 && got[3] > y[0]);
    assert_non_null(strstr(plot, "class=\"path-p50\""));
    assert_non_null(strstr(plot, ">p99 3.06</text>"));
    assert_non_null(strstr(plot, "<circle class=\"path-stutter\" data-frame=\"1\""));
    assert_null(strstr(html, "temporal error mean"));   /* no quality along the path asked */
    assert_null(strstr(html, "path-flip"));
    free(html);
    /* quality along the path at every frame: FLIP 0.1, 0.5, 0.2; SSIM 0.9, 0.6, 0.85 */
    dm_path_quality *q = &run.configs[0].path_quality;
    static const double flip[] = {0.1, 0.5, 0.2}, ssim[] = {0.9, 0.6, 0.85};
    *q = (dm_path_quality){.present = 1, .frames = 3, .every = 1, .n = 3, .temporal_mean = 0.0125,
                           .temporal_p99 = 0.0625, .popping = 0.4, .popping_frame = 1};
    q->flip = dm_xmalloc(sizeof flip);
    q->ssim = dm_xmalloc(sizeof ssim);
    memcpy(q->flip, flip, sizeof flip);
    memcpy(q->ssim, ssim, sizeof ssim);
    q->img_temporal = dm_xstrdup("img/c0-temporal.png");
    html = html_of(&run, path);
    sec = strstr(html, "<section class=\"path-scene\" id=\"path-0\">");
    assert_non_null(sec);
    assert_non_null(strstr(sec, "<td class=\"n\">0.0125</td><td class=\"n\">0.0625</td>"
                                "<td class=\"n\">0.4 (frame 1)</td><td><a href=\"img/c0-temporal.png\">map</a></td>"));
    plot = strstr(sec, "aria-label=\"Error at the reference frames: ");
    assert_non_null(plot);
    assert_int_equal(attr_numbers(strstr(plot, "class=\"path-flip\""), "data-flip", got, 4), 3);
    assert_int_equal(attr_numbers(strstr(plot, "class=\"path-ssim\""), "data-ssim", got + 3, 1), 1);
    for (size_t f = 0; f < 3; f++)
        assert_true(got[f] == flip[f]);
    assert_true(got[3] == ssim[0]);
    /* 1 − SSIM drawn: frame 1's 0.4 above frame 0's 0.1 (y grows downward) */
    d = strstr(strstr(plot, "class=\"path-ssim\""), " d=\"");
    assert_int_equal(sscanf(d, " d=\"M%lf,%lf L%lf,%lf L%lf,%lf \"", &x[0], &y[0], &x[1], &y[1], &x[2], &y[2]), 6);
    assert_true(y[1] < y[2] && y[2] < y[0]);
    assert_non_null(strstr(plot, ">popping 0.4 (frame 1)</text>"));
    /* no frame written (a run from before the filmstrip): it says why */
    assert_non_null(strstr(sec, "<p class=\"missing film-none\">No filmstrip for "));
    assert_null(strstr(sec, "class=\"film\""));
    free(html);
    /* frames 0 and 2 written, frame 2 without its FLIP map: the large view
     * starts at frame 0's image, each thumbnail carries its three files and
     * its reference frame's FLIP and SSIM (0.2 and 0.85 at frame 2) */
    q->n_shots = 2;
    q->shots = dm_xcalloc(2, sizeof *q->shots);
    q->shots[0] = (dm_path_shot){0, dm_xstrdup("img/c0-path-f000.png"), dm_xstrdup("img/ref-1-f000.png"),
                                 dm_xstrdup("img/c0-path-f000-flip.png")};
    q->shots[1] = (dm_path_shot){2, dm_xstrdup("img/c0-path-f002.png"), dm_xstrdup("img/ref-1-f002.png"), NULL};
    html = html_of(&run, path);
    sec = strstr(html, "<section class=\"path-scene\" id=\"path-0\">");
    assert_null(strstr(sec, "No filmstrip"));
    const char *film = strstr(sec, "<div class=\"film\" tabindex=\"0\" id=\"film-");
    assert_non_null(film);
    assert_non_null(strstr(film, "<img class=\"film-big\" src=\"img/c0-path-f000.png\""));
    assert_non_null(strstr(film, "frame 0 of 3, the technique's frame: FLIP 0.1, SSIM 0.9</figcaption>"));
    assert_non_null(strstr(film, "<figure class=\"film-shot\" data-frame=\"2\" data-test=\"img/c0-path-f002.png\" "
                                 "data-ref=\"img/ref-1-f002.png\" data-flip=\"\" data-flipv=\"0.2\" "
                                 "data-ssim=\"0.85\"><a href=\"img/c0-path-f002.png\">"));
    assert_non_null(strstr(film, "<a href=\"img/ref-1-f000.png\">reference</a> · "
                                 "<a href=\"img/c0-path-f000-flip.png\">FLIP</a>"));
    assert_non_null(strstr(film, "<span class=\"missing\">FLIP not written</span>"));
    assert_non_null(strstr(film, "class=\"scroll film-strip\""));
    free(html);
    /* results.json lists them and reads them back */
    char *js = dm_xasprintf("%s/r.json", dir);
    assert_int_equal(write_report_file(&run, "results.json", NULL, js, NULL), 0);
    char *tj = test_slurp(js);
    assert_non_null(strstr(tj, "\"frames_shown\""));
    dm_run_result back = {0};
    char jerr[256] = "";
    assert_int_equal(report_read_json(js, &back, jerr, sizeof jerr), 0);
    const dm_path_quality *bq = &back.configs[0].path_quality;
    assert_int_equal(bq->n_shots, 2);
    assert_int_equal(bq->shots[1].frame, 2);
    assert_string_equal(bq->shots[0].img_flip, "img/c0-path-f000-flip.png");
    assert_string_equal(bq->shots[1].img_ref, "img/ref-1-f002.png");
    assert_null(bq->shots[1].img_flip);
    dm_run_free(&back);
    free(tj);
    unlink(js);
    free(js);
    /* the CSV's and summary.md's temporal figures */
    char *csv = dm_xasprintf("%s/r.csv", dir), *md = dm_xasprintf("%s/s.md", dir);
    assert_int_equal(write_report_file(&run, "results.csv", NULL, csv, NULL), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    char *tc = test_slurp(csv), *tm = test_slurp(md);
    assert_non_null(strstr(tc, ",3.1,322.580645,1,0.0125,0.0625,0.4,1\r\n"));
    assert_non_null(strstr(tm, "## Quality along the path"));
    assert_non_null(strstr(tm, " | 3 (every 1 of 3) | 0.0125 | 0.0625 | 0.4 (frame 1) | img/c0-temporal.png | `"));
    q->present = 0;   /* asked, not computed: the reason, no figure */
    q->reason = dm_xstrdup("the reference frame 1 failed");
    assert_int_equal(write_report_file(&run, "results.csv", NULL, csv, NULL), 0);
    assert_int_equal(write_report_file(&run, "summary.md", NULL, md, NULL), 0);
    free(tc);
    free(tm);
    tc = test_slurp(csv);
    tm = test_slurp(md);
    assert_non_null(strstr(tc, ",3.1,322.580645,1,,,,\r\n"));
    assert_non_null(strstr(tm, " | unavailable: the reference frame 1 failed | | | | | `"));
    free(tc);
    free(tm);
    unlink(csv);
    unlink(md);
    free(csv);
    free(md);
    dm_run_free(&run);
    unlink(path);
    test_rm_rf(dir);
    free(path);
}

/* Gives fixture configuration c a 2-frame path with p99 p99_ns and
 * quality along it with temporal error mean te. */
static void motion_config(dm_config_result *c, double p99_ns, double te)
{
    c->path = (dm_path_series){.frames = 2, .replays = 1, .p50 = p99_ns, .p95 = p99_ns, .p99 = p99_ns,
                               .low1_ns = p99_ns, .low1_fps = 1e9 / p99_ns, .replay_spread = NAN, .noisy = -1};
    c->path.frame_ns = dm_xcalloc(2, sizeof *c->path.frame_ns);
    c->path.frame_ns[0] = c->path.frame_ns[1] = p99_ns;
    c->path.stutter_at = dm_xcalloc(1, sizeof *c->path.stutter_at);
    c->path_quality = (dm_path_quality){.present = 1, .frames = 2, .every = 1, .n = 2, .temporal_mean = te,
                                        .temporal_p99 = te, .popping = 0, .popping_frame = 1};
    c->path_quality.flip = dm_xcalloc(2, sizeof *c->path_quality.flip);
    c->path_quality.ssim = dm_xcalloc(2, sizeof *c->path_quality.ssim);
}

/* The second front of a scene, temporal error against p99 frame time: pom
 * (p99 3.058 ms, 0.0125) and normal (2.5 ms, 0.02) are both on it, normal
 * first; the steadiest under the scene's budget is pom when its p99 fits,
 * else normal when its does, else none; then normal made steadier as well
 * as faster (0.01) leaves pom off the front.  The answer says it in words;
 * a scene with one such configuration gets no sentence. */
static void test_motion_front(void **state)
{
    (void)state;
    dm_run_result run;
    fixture_run(&run);
    motion_config(&run.configs[0], 3.058e6, 0.0125);
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_int_equal(m.scenes[0].n_motion_points, 1);
    dm_str a = {0};
    report_answer_scene(&m, 0, REPORT_ANSWER_MD, &a);
    assert_null(strstr(dm_str_get(&a), "In motion"));
    dm_str_free(&a);
    report_model_free(&m);
    motion_config(&run.configs[1], 2.5e6, 0.02);
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    const report_model_scene *sc = &m.scenes[0];
    assert_int_equal(sc->n_motion_points, 2);
    assert_int_equal(sc->n_motion_front, 2);
    assert_int_equal(sc->motion_front[0], 1);
    assert_int_equal(sc->motion_front[1], 0);
    double b = sc->rec.budget;
    assert_true(b > 0);
    size_t want = b >= 3.058e6 ? 0 : b >= 2.5e6 ? 1 : RECOMMEND_NONE;
    assert_int_equal(sc->motion_pick, want);
    report_answer_scene(&m, 0, REPORT_ANSWER_MD, &a);
    const char *t = dm_str_get(&a);
    assert_non_null(strstr(t, "In motion (temporal error against p99 frame time along the path): "));
    assert_non_null(strstr(t, "Front, fastest first: normal mesh=plane (p99 2.5 ms, temporal error 0.02), "
                              "pom mesh=plane (p99 3.06 ms, temporal error 0.0125)."));
    if (want == 0)   /* normal is the fixture scene's still pick */
        assert_non_null(strstr(t, "is **pom mesh=plane** (p99 3.06 ms, temporal error 0.0125), not the "
                                  "still pick's technique (normal)."));
    dm_str_free(&a);
    report_model_free(&m);
    run.configs[1].path_quality.temporal_mean = 0.01;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_int_equal(m.scenes[0].n_motion_front, 1);
    assert_int_equal(m.scenes[0].motion_front[0], 1);
    report_model_free(&m);
    dm_run_free(&run);
}

/* The fixture: one fit (tess-power, 2 points), key counters, no pipeline
 * fit, one tess_level value: error vs time and time per configuration of
 * its one scene (never a chart pooling scenes), the key counter bars, and
 * the fit's two plots.  Without its fit: no fit plot. */
static void test_html_chart_set(void **state)
{
    (void)state;
    static const char *want[] = {
        "1 - SSIM vs time: plane/cam0/sun/stone/64x64", "Time per configuration: plane/cam0/sun/stone/64x64",
        "Key counters per configuration (relative to each maximum)",
        "Predicted vs measured: tess-power mesh=plane", "Residuals: tess-power mesh=plane" };
    char dir[] = "/tmp/dm_reports_charts_XXXXXX", titles[8][96];
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/report.html", dir);
    dm_run_result run;
    fixture_run(&run);
    char *t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 5);
    for (size_t i = 0; i < 5; i++)
        assert_string_equal(titles[i], want[i]);
    assert_non_null(strstr(t, "<th>points</th>"));
    assert_non_null(strstr(t, "<td class=\"missing\">not computed</td>"));   /* condition 0 */
    free(t);
    run.fits[0].condition = 1234.5;
    t = html_of(&run, p);
    assert_non_null(strstr(t, "<td class=\"n\">0.0400</td><td class=\"n\">1.23e+03</td>"));
    free(t);
    run.fits[0].condition = INFINITY;
    t = html_of(&run, p);
    /* a rank-deficient fit folds to one line, without its plots */
    assert_non_null(strstr(t, "1 fit not usable (R² below 0.8 or rank deficient): one line each"));
    assert_null(strstr(t, "Predicted vs measured"));
    free(t);
    dm_fit_result_free(&run.fits[0]);
    run.n_fits = 0;
    t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 3);
    assert_null(strstr(t, "Predicted vs measured"));
    assert_null(strstr(t, "Residuals"));
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* 30 configurations with a pipeline-linear fit: the breakdown shows the
 * stage estimate, caps at the 24 slowest and says the 6 fastest are left out. */
static void test_html_breakdown_fit_and_cap(void **state)
{
    (void)state;
    double rel[30];
    for (int i = 0; i < 30; i++)
        rel[i] = 0.01;
    dm_run_result run;
    noisy_run(&run, rel, 30);
    for (size_t i = 0; i < 30; i++) {
        dm_config_result *c = &run.configs[i];
        c->counters = dm_xrealloc(c->counters, 2 * sizeof *c->counters);
        fixture_det(&c->counters[1], "SamplesPassed", 1000.0 * (double)(i + 1));
        c->n_counters = 2;
    }
    fixture_fit2(&run, "pipeline-linear", "c0", 2e5, "c_px", 30, 0.95);
    dm_fit_result *f = run.fits;
    char dir[] = "/tmp/dm_reports_bd_XXXXXX", titles[8][96];
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/report.html", dir);
    char *t = html_of(&run, p);
    size_t n = chart_titles(t, titles, 8);
    assert_int_equal(n, 2);   /* time per configuration and breakdown (no quality: no error chart; no points: no fit plots) */
    assert_string_equal(titles[1], "Estimated time per stage (pipeline-linear fit)");
    assert_non_null(strstr(t, "The 6 fastest configurations are left out of this chart (it shows "
                              "the 24 slowest); all are in the table."));
    assert_null(strstr(t, "No per-stage breakdown"));
    free(t);
    /* a poor fit (R² 0.37 < 0.8) is not drawn as stage times: counters and a note */
    f->r2 = 0.37;
    t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 2);
    assert_string_equal(titles[1], "Key counters per configuration (relative to each maximum)");
    assert_non_null(strstr(t, "No per-stage breakdown: the pipeline-linear fit explains too little of "
                              "the time (R² 0.37, below 0.8)"));
    free(t);
    /* without the fit: the key counter bars, same cap */
    dm_fit_result_free(&run.fits[0]);
    run.n_fits = 0;
    t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 2);
    assert_string_equal(titles[1], "Key counters per configuration (relative to each maximum)");
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* With the stage counters and a time-from-stages fit, the breakdown is that
 * fit's time per stage over the exact stage instructions, before the
 * pipeline-linear fit the run also has; without the stage counters, the
 * pipeline-linear one again; with the timed stage passes, what they
 * measured, before either fit. */
static void test_html_breakdown_time_from_stages(void **state)
{
    (void)state;
    double rel[4] = {0.01, 0.01, 0.01, 0.01};
    dm_run_result run;
    noisy_run(&run, rel, 4);
    static const char *const stage[3] = {"GeometryInstructions", "RasterInstructions", "FragmentInstructions"};
    for (size_t i = 0; i < 4; i++) {
        dm_config_result *c = &run.configs[i];
        c->counters = dm_xrealloc(c->counters, 7 * sizeof *c->counters);
        fixture_det(&c->counters[1], "SamplesPassed", 1000.0 * (double)(i + 1));
        for (int k = 0; k < 3; k++)
            fixture_det(&c->counters[2 + k], stage[k], 1e6 * (double)(k + 1));
        /* the timed isolation passes, used from the last step on */
        fixture_timed(&c->counters[5], "GeometryTime", 0.9e5, 1e5, 1.1e5);
        fixture_timed(&c->counters[6], "MinimalShadingTime", 3.9e5, 4e5, 4.1e5);
        c->n_counters = 5;
    }
    static const char *const model[2] = {"pipeline-linear", "time-from-stages"};
    static const char *const pname[2][4] = {{"c0", "c_px"}, {"a", "b_geo", "b_raster", "b_frag"}};
    static const double pval[2][4] = {{2e5, 30}, {1e4, 0.3, 0.07, 0.14}};
    run.n_fits = 2;
    run.fits = dm_xcalloc(2, sizeof *run.fits);
    for (int j = 0; j < 2; j++) {
        dm_fit_result *f = &run.fits[j];
        f->model = dm_xstrdup(model[j]);
        f->response = dm_xstrdup("WallTime");
        f->n_params = j ? 4 : 2;
        f->params = dm_xcalloc(f->n_params, sizeof *f->params);
        for (size_t k = 0; k < f->n_params; k++) {
            f->params[k].name = dm_xstrdup(pname[j][k]);
            f->params[k].value = pval[j][k];
        }
        f->r2 = 0.95;
    }
    char dir[] = "/tmp/dm_reports_ts_XXXXXX", titles[8][96];
    assert_non_null(mkdtemp(dir));
    char *p = dm_xasprintf("%s/report.html", dir);
    char *t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 2);
    assert_string_equal(titles[1], "Estimated time per stage (time-from-stages fit)");
    free(t);
    for (size_t i = 0; i < 4; i++)   /* no stage counters: pipeline-linear */
        run.configs[i].n_counters = 2;
    t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 2);
    assert_string_equal(titles[1], "Estimated time per stage (pipeline-linear fit)");
    free(t);
    /* the timed passes measured: the measured stage times, before any fit */
    for (size_t i = 0; i < 4; i++)
        run.configs[i].n_counters = 7;
    t = html_of(&run, p);
    assert_int_equal(chart_titles(t, titles, 8), 2);
    assert_string_equal(titles[1], "Measured time per stage (timed isolation passes)");
    free(t);
    dm_run_free(&run);
    unlink(p);
    free(p);
    test_rm_rf(dir);
}

/* results.json "warnings" is the report's list word for word (summary.md's
 * "- warning:" lines, report.html's warn boxes), drift is marked in the
 * table with its reason, and read → write keeps the list as it was. */
static void test_warnings_everywhere(void **state)
{
    (void)state;
    static const double rel[] = {0.01, 0.20, 0.01};
    char dir[] = "/tmp/dm_reports_warn_XXXXXX";
    assert_non_null(mkdtemp(dir));
    dm_run_result run, back;
    noisy_run(&run, rel, 3);
    run.configs[2].log = dm_xstrdup("WallTime drifted -9.9 % over its 15 samples (a trend, not noise)\n");
    run.timer_verdict = dm_xstrdup("partial");
    run.gpu_time_coverage = 0.015;
    char e[256];
    assert_int_equal(report_write_run(&run, &(report_desc){.dir = dir}, e, sizeof e), 0);
    char *jp = dm_xasprintf("%s/results.json", dir), *md = dm_xasprintf("%s/summary.md", dir);
    char *html = dm_xasprintf("%s/report.html", dir);
    assert_int_equal(report_read_json(jp, &back, e, sizeof e), 0);
    static const char *want[] = {
        "GPUTime is partial on this driver: it covers 1.5% of fenced wall time; it is recorded, never "
        "used to fit or gate.",
        "1 noisy configuration: the 95% CI of the median frame time is wider than ±5% of the median "
        "(or unknown); compare their times with care.",
        "1 configuration drifted while sampling (a trend, not noise: the machine's load or clock "
        "changed): s · pom steps=2 (-9.9 %)"};
    assert_int_equal(back.n_warnings, 3);
    char *m = test_slurp(md), *h = test_slurp(html);
    for (size_t i = 0; i < 3; i++) {
        assert_string_equal(back.warnings[i], want[i]);
        char *line = dm_xasprintf("- warning: %s\n", want[i]);
        assert_non_null(strstr(m, line));
        free(line);
        dm_str esc = {0};
        dm_str_cat(&esc, "<div class=\"warn\">");
        dm_str_cat_html(&esc, want[i]);
        dm_str_cat(&esc, "</div>");
        assert_non_null(strstr(h, dm_str_get(&esc)));
        dm_str_free(&esc);
    }
    /* the drifted row carries its mark and the log line as the reason */
    assert_non_null(strstr(h, "title=\"WallTime drifted -9.9 % over its 15 samples (a trend, not noise)\">⚠ drift -9.9 %</span>"));
    assert_non_null(strstr(m, "⚠ drift -9.9 %"));
    /* read → write: the same list, not doubled */
    assert_int_equal(write_report_file(&back, "results.json", NULL, jp, NULL), 0);
    dm_run_result again;
    assert_int_equal(report_read_json(jp, &again, e, sizeof e), 0);
    assert_int_equal(again.n_warnings, 3);
    free(m);
    free(h);
    dm_run_free(&again);
    dm_run_free(&back);
    dm_run_free(&run);
    free(jp);
    free(md);
    free(html);
    test_rm_rf(dir);
}

/* A timed run whose configurations have no quality (no reference could be
 * compared): the answer says so, never "Under 0 ms: nothing fits". */
static void test_answer_without_quality(void **state)
{
    (void)state;
    dm_run_result run = {0};
    fixture_run(&run);
    for (size_t i = 0; i < run.n_configs; i++) {   /* no figure (the reference text stays, freed below) */
        dm_quality *q = &run.configs[i].quality;
        q->present = 0;
        q->psnr = q->ssim = q->rmse = q->max_error = q->flip = q->silhouette_error = q->depth_rmse = NAN;
    }
    dm_str t = {0};
    report_answer_terminal(&run, &t);
    char *j = answer_joined(dm_str_get(&t));
    assert_non_null(strstr(j, "no configuration has both a frame time and a quality "
                              "figure (ssim) against the reference: no budget or pick"));
    assert_null(strstr(j, "Under 0 ms"));
    free(j);
    dm_str_free(&t);
    dm_run_free(&run);
}

/* A pick with cracks and NaN pixels carries them beside the answer. */
static void test_answer_defects(void **state)
{
    (void)state;
    dm_run_result run = {0};
    fixture_run(&run);
    for (size_t i = 0; i < run.n_configs; i++) {
        run.configs[i].quality.crack_pixels = 128;
        run.configs[i].quality.nonfinite_pixels = 1;
    }
    dm_str t = {0};
    report_answer_terminal(&run, &t);
    assert_true(strstr(dm_str_get(&t), "\n    "));   /* the answer is long enough to be wrapped */
    char *j = answer_joined(dm_str_get(&t));
    assert_non_null(strstr(j, "pick "));
    assert_non_null(strstr(j, "⚠ 128 crack pixels; ⚠ 1 NaN pixel"));
    free(j);
    dm_str_free(&t);
    dm_run_free(&run);
}

/* Most timings noisy: a run-level warning with the load, and each scene's
 * pick marked provisional; not when only some are. */
static void test_busy_machine(void **state)
{
    (void)state;
    static const double most[] = {0.20, 0.30, 0.01, 0.40}, few[] = {0.20, 0.01, 0.01, 0.01};
    dm_run_result run;
    noisy_run(&run, most, 4);
    dm_kv_push(&run.environment, &run.n_environment, "load_average", "3.10 2.50 1.00");
    dm_kv_push(&run.environment, &run.n_environment, "cpu_count", "2");
    char **w;
    size_t nw = report__warnings(&run, &w), found = 0;
    for (size_t i = 0; i < nw; i++)
        found += strcmp(w[i], "The machine was busy: 3 of 4 timings are noisy (load average 3.10 at "
                              "the start on 2 CPUs); every pick is provisional: run again on a quieter "
                              "machine, or give the samples more time (measure.max_seconds, "
                              "measure.samples.max).") == 0;
    assert_int_equal(found, 1);
    report__warnings_free(w, nw);
    dm_str t = {0};
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    report_answer_scene(&m, 0, REPORT_ANSWER_MD, &t);
    report_model_free(&m);
    assert_non_null(strstr(dm_str_get(&t), "Provisional: 3 of 4 timings are noisy"));
    dm_str_free(&t);
    dm_run_free(&run);
    noisy_run(&run, few, 4);
    nw = report__warnings(&run, &w);
    for (size_t i = 0; i < nw; i++)
        assert_null(strstr(w[i], "The machine was busy"));
    report__warnings_free(w, nw);
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    report_answer_scene(&m, 0, REPORT_ANSWER_MD, &t);
    report_model_free(&m);
    assert_null(strstr(dm_str_get(&t), "Provisional"));
    dm_str_free(&t);
    dm_run_free(&run);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_busy_machine),
             cmocka_unit_test(test_answer_defects),
             cmocka_unit_test(test_answer_without_quality),
             cmocka_unit_test(test_json_round_trip),
             cmocka_unit_test(test_json_read_errors),
             cmocka_unit_test(test_json_path),
             cmocka_unit_test(test_html_path),
             cmocka_unit_test(test_motion_front),
             cmocka_unit_test(test_csv_shape),
             cmocka_unit_test(test_markdown),
             cmocka_unit_test(test_tie_named_by_key),
             cmocka_unit_test(test_near_miss_named),
             cmocka_unit_test(test_corrected_figures),
             cmocka_unit_test(test_html_escaping_and_images),
             cmocka_unit_test(test_html_flip_maps),
             cmocka_unit_test(test_write_all),
             cmocka_unit_test(test_html_charts_and_front),
             cmocka_unit_test(test_metric_fronts),
             cmocka_unit_test(test_metric_names),
             cmocka_unit_test(test_label_default_left_out),
        cmocka_unit_test(test_metric_in_files),
             cmocka_unit_test(test_noisy_warning),
             cmocka_unit_test(test_warnings_everywhere),
             cmocka_unit_test(test_quality_warnings),
             cmocka_unit_test(test_html_chart_set),
             cmocka_unit_test(test_html_breakdown_fit_and_cap),
             cmocka_unit_test(test_html_breakdown_time_from_stages))
