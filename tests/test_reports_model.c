/* The report model (reports/report_model.h) of a run built here, checked
 * field by field against values worked out by hand: three scenes, a scene
 * with four timed configurations (one noisy, one off the front) and a
 * failed one, a scene of one, a scene without a frame time; trend lines,
 * a frame budget, image defects and a published.json that is not one. */
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

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/answer.h"
#include "reports/report.h"
#include "reports/report_model.h"
#include "test_reports_fixture.h"
#include "test_util.h"

#define SCENE_A "plane@160x90,light=sun"
#define SCENE_B "cube@160x90,light=sun"
#define SCENE_C "sphere@160x90,light=sun"

/* Configuration i: key "k<i>", the scene, technique, lighting, and steps
 * when not NULL; ok with WallTime [lo, med, hi] and SSIM ssim when med > 0. */
static void model_config(dm_run_result *run, size_t i, const char *scene, const char *tech,
                         const char *steps, double lo, double med, double hi, double ssim)
{
    dm_config_result *c = &run->configs[i];
    char key[24];
    snprintf(key, sizeof key, "k%zu", i);
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup(scene);
    dm_kv_push(&c->params, &c->n_params, "technique", tech);
    dm_kv_push(&c->params, &c->n_params, "lighting", "blinn-phong");
    if (steps)
        dm_kv_push(&c->params, &c->n_params, "steps", steps);
    c->ok = med > 0;
    if (!c->ok) {
        c->reason = dm_xstrdup("shader link failed");
        return;
    }
    c->n_counters = 1;
    c->counters = dm_xcalloc(1, sizeof *c->counters);
    fixture_timed(&c->counters[0], "WallTime", lo, med, hi);
    c->quality.present = 1;
    c->quality.ssim = ssim;
    c->quality.psnr = 30;
}

/*   k0 A pom steps=8    2.00 ms ±2.5 %   SSIM 0.95  front
 *   k1 A pom steps=32   4.00 ms ±25 %    SSIM 0.99  front, noisy
 *   k2 A normal         1.00 ms ±1.0 %   SSIM 0.80  front, 3 non-finite and 7 crack pixels
 *   k3 A pom steps=16   failed
 *   k4 B pom            1.00 ms ±1.0 %   SSIM 0.90  front (alone)
 *   k5 A parallax       3.00 ms ±1.0 %   SSIM 0.90  off the front (k0 is faster and better)
 *   k6 C pom            no frame time (a counter only) */
static void model_run(dm_run_result *run)
{
    memset(run, 0, sizeof *run);
    run->id = dm_xstrdup("20261129-000000");
    run->sweep = dm_xstrdup("model");
    run->timer_verdict = dm_xstrdup("ok");
    run->n_configs = 7;
    run->configs = dm_xcalloc(7, sizeof *run->configs);
    model_config(run, 0, SCENE_A, "pom", "8", 1.95e6, 2.0e6, 2.05e6, 0.95);
    model_config(run, 1, SCENE_A, "pom", "32", 3.0e6, 4.0e6, 5.0e6, 0.99);
    model_config(run, 2, SCENE_A, "normal", NULL, 0.99e6, 1.0e6, 1.01e6, 0.80);
    model_config(run, 3, SCENE_A, "pom", "16", 0, 0, 0, 0);
    model_config(run, 4, SCENE_B, "pom", "8", 0.99e6, 1.0e6, 1.01e6, 0.90);
    model_config(run, 5, SCENE_A, "parallax", NULL, 2.97e6, 3.0e6, 3.03e6, 0.90);
    dm_config_result *c6 = &run->configs[6];
    c6->key = dm_xstrdup("k6");
    c6->scene = dm_xstrdup(SCENE_C);
    dm_kv_push(&c6->params, &c6->n_params, "technique", "pom");
    c6->ok = 1;
    c6->n_counters = 1;
    c6->counters = dm_xcalloc(1, sizeof *c6->counters);
    fixture_det(&c6->counters[0], "VSInvocations", 4);
    run->configs[2].quality.nonfinite_pixels = 3;
    run->configs[2].quality.crack_pixels = 7;
    run->n_warnings = 1;
    run->warnings = dm_xcalloc(1, sizeof(char *));
    run->warnings[0] = dm_xstrdup("stored warning");
    assert_int_equal(report_budget_set(run, 2.5), 0);   /* ms: k2 and k0 fit, k5 and k1 do not */
}

static void assert_near(double a, double b)
{
    assert_true(fabs(a - b) < 1e-12);
}

static void test_model_rows(void **state)
{
    (void)state;
    dm_run_result run;
    model_run(&run);
    double med0[] = {1.5e6, 2.0e6}, med1[] = {4.0e6};
    report_trend items[] = {{.key = "k0", .median_ns = med0, .n = 2}, {.key = "k1", .median_ns = med1, .n = 1}};
    report_trends tr = {.items = items, .n = 2};
    report_model m;
    assert_int_equal(report_model_build(&m, &run, &(report_desc){.trends = &tr}), 0);
    assert_ptr_equal(m.run, &run);
    assert_int_equal(m.metric, REPORT_METRIC_SSIM);
    assert_string_equal(m.constants, "light=sun");
    assert_int_equal(m.n_rows, 7);

    const report_model_row *r = m.rows;
    assert_ptr_equal(r[0].config, &run.configs[0]);
    assert_string_equal(r[0].label, "pom steps=8");   /* steps varies in A (the failed k3 counts) */
    assert_string_equal(r[0].full_label, "plane 160×90 · pom steps=8");
    assert_string_equal(r[0].name, "plane 160×90 · pom steps=8");
    assert_ptr_equal(r[0].frame_time, &run.configs[0].counters[0]);
    assert_string_equal(r[0].ms_text, "2.00");
    assert_string_equal(r[0].ci_text, "±2.5%");          /* (2.05 − 1.95) / 2 / 2.00 */
    assert_string_equal(r[0].time_ci_text, "2.00 ms [1.95, 2.05]");
    assert_string_equal(r[0].marks, "");
    assert_int_equal(r[0].noisy, 0);
    assert_int_equal(r[0].front, 1);
    assert_near(r[0].error, 1 - 0.95);
    assert_ptr_equal(r[0].trend, &items[0]);
    assert_int_equal(r[0].scene, 0);

    assert_string_equal(r[1].label, "pom steps=32");
    assert_string_equal(r[1].ms_text, "4.00");
    assert_string_equal(r[1].ci_text, "±25%");            /* (5 − 3) / 2 / 4: over 10 %, no decimal */
    assert_int_equal(r[1].noisy, 1);
    assert_string_equal(r[1].marks, "⚠ noisy: CI ±25%");
    assert_string_equal(r[1].marks_short, "⚠ noisy");
    assert_true(strstr(r[1].why, "±5%") != NULL);
    assert_int_equal(r[1].front, 1);
    assert_null(r[1].trend);                              /* one run only: no line */

    assert_string_equal(r[2].label, "normal");
    assert_string_equal(r[2].ci_text, "±1.0%");
    assert_int_equal(r[2].nonfinite_pixels, 3);
    assert_int_equal(r[2].crack_pixels, 7);
    assert_int_equal(r[2].front, 1);

    assert_string_equal(r[3].label, "pom steps=16");
    assert_null(r[3].frame_time);
    assert_null(r[3].ms_text);
    assert_int_equal(r[3].front, 0);
    assert_true(isnan(r[3].error));

    assert_string_equal(r[4].label, "pom");               /* alone in B: nothing varies */
    assert_string_equal(r[4].full_label, "cube 160×90 · pom");
    assert_int_equal(r[4].scene, 1);
    assert_int_equal(r[4].front, 1);

    assert_string_equal(r[5].label, "parallax");
    assert_int_equal(r[5].front, 0);                      /* k0: faster and better */
    assert_near(r[5].error, 1 - 0.90);

    assert_null(r[6].frame_time);
    assert_int_equal(r[6].scene, 2);

    /* what the answer's sentences, the charts and the gallery read */
    assert_string_equal(r[0].technique, "pom");
    assert_int_equal(r[0].family, RECOMMEND_FRAGMENT);    /* lit, no tess_level or vertex_filter */
    assert_string_equal(r[0].metric_text, "SSIM 0.950");
    assert_string_equal(r[0].defects, "");
    assert_string_equal(r[0].defects_why, "");
    assert_string_equal(r[2].defects, "⚠ 7 crack pixels; ⚠ 3 NaN pixels");
    assert_non_null(strstr(r[2].defects_why, "background shows through"));
    assert_non_null(strstr(r[2].defects_why, "; the shader wrote NaN"));
    assert_string_equal(r[5].technique, "parallax");
    assert_string_equal(r[5].metric_text, "SSIM 0.900");
    assert_int_equal(r[6].family, RECOMMEND_UNLIT);      /* no lighting axis: a baseline */
    assert_near(m.budget_ms, 2.5);
    assert_int_equal(m.any_timed, 1);

    assert_ptr_equal(report_model_find(&m, "k5"), &r[5]);
    assert_null(report_model_find(&m, "nope"));
    report_model_free(&m);
    dm_run_free(&run);
}

static void test_model_scenes(void **state)
{
    (void)state;
    dm_run_result run;
    model_run(&run);
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_int_equal(m.n_scenes, 3);
    const report_model_scene *a = &m.scenes[0], *b = &m.scenes[1], *c = &m.scenes[2];
    assert_string_equal(a->name, SCENE_A);
    assert_string_equal(a->label, "plane 160×90");
    size_t rows[] = {2, 0, 5, 1};                         /* ok ones, by median: 1, 2, 3, 4 ms */
    assert_int_equal(a->n_rows, 4);
    assert_memory_equal(a->rows, rows, sizeof rows);
    assert_int_equal(a->n_varying, 2);                    /* lighting is the same everywhere */
    assert_string_equal(a->varying[0], "technique");
    assert_string_equal(a->varying[1], "steps");
    assert_string_equal(a->same, "lighting=blinn-phong ");   /* the technique has its own column */
    size_t front[] = {2, 0, 1};
    assert_int_equal(a->n_front, 3);
    assert_memory_equal(a->front, front, sizeof front);
    assert_null(a->untimed);
    assert_int_equal(a->n_points, 4);
    assert_near(a->rec.budget, 2.5e6);
    assert_int_equal(a->rec.pick, 0);                     /* best SSIM at or under 2.5 ms */
    assert_int_equal(a->rec.fastest, 2);
    assert_int_equal(a->rec.family_best[RECOMMEND_FRAGMENT], 0);
    assert_true(strstr(a->front_text, "normal") != NULL);

    assert_string_equal(b->label, "cube 160×90");
    assert_int_equal(b->n_rows, 1);
    assert_int_equal(b->rows[0], 4);
    assert_int_equal(b->n_front, 1);
    assert_int_equal(b->front[0], 4);
    assert_int_equal(b->n_varying, 0);
    assert_string_equal(b->same, "lighting=blinn-phong steps=8 ");
    assert_string_equal(c->same, "");

    assert_int_equal(c->n_rows, 1);
    assert_int_equal(c->n_front, 0);
    assert_string_equal(c->untimed, "no timing counter measured: no budget or pick");
    /* the gallery's legend: no MaxError or FLIP map in this run */
    assert_near(a->max_error, 0);
    assert_int_equal(a->flips, 0);
    assert_true(isnan(a->flip_ppd));
    /* the provisional flag and the counter table's columns */
    assert_int_equal(a->n_timed, 4);
    assert_int_equal(a->n_noisy, 1);                      /* k1 */
    assert_int_equal(a->provisional, 0);                  /* 1 of 4 is not most */
    assert_int_equal(a->n_det, 0);
    assert_int_equal(b->n_timed, 1);
    assert_int_equal(c->n_timed, 0);
    assert_int_equal(c->n_det, 1);
    assert_string_equal(c->det[0], "VSInvocations");

    /* warnings: one noisy configuration, one failure, then the stored line last */
    assert_int_equal(m.n_noisy, 1);
    assert_int_equal(m.noisy[0], 1);
    int noisy = 0, failed = 0;
    for (size_t i = 0; i < m.n_warnings; i++) {
        noisy += strstr(m.warnings[i], "1 noisy configuration") != NULL;
        failed += strstr(m.warnings[i], "1 configuration failed") != NULL;
    }
    assert_int_equal(noisy, 1);
    assert_int_equal(failed, 1);
    assert_string_equal(m.warnings[m.n_warnings - 1], "stored warning");
    /* results.csv's columns */
    assert_int_equal(m.n_params, 3);
    assert_string_equal(m.params[2], "steps");
    assert_int_equal(m.n_timed, 1);
    assert_string_equal(m.timed[0], "WallTime");
    assert_int_equal(m.n_det, 1);
    assert_string_equal(m.det[0], "VSInvocations");
    assert_string_equal(m.published_md, "");              /* no directory: none */
    report_model_free(&m);
    /* the largest MaxError over the scene's ok rows, and its FLIP maps' ppd */
    run.configs[0].quality.max_error = 1.25;
    run.configs[5].quality.max_error = 0.5;
    run.configs[3].quality.max_error = 9;                 /* failed: not a row */
    run.configs[5].img_flip = dm_xstrdup("img/k5_flip.png");
    run.configs[5].quality.flip_ppd = 67;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_near(m.scenes[0].max_error, 1.25);
    assert_int_equal(m.scenes[0].flips, 1);
    assert_near(m.scenes[0].flip_ppd, 67);
    assert_int_equal(m.scenes[1].flips, 0);
    report_model_free(&m);
    dm_run_free(&run);
}

/* published.json is read once, into both the Markdown and the HTML section. */
static void test_model_published(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_reports_model.XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *path = dm_xasprintf("%s/published.json", dir);
    assert_int_equal(dm_write_file(path, "{}", 2), 0);
    dm_run_result run;
    model_run(&run);
    report_model m;
    assert_int_equal(report_model_build(&m, &run, &(report_desc){.dir = dir}), 0);
    char *md = dm_xasprintf("\n## Published figures beside ours\n\n%s: not a published.json this version writes\n", path);
    char *html = dm_xasprintf("<h2 id=\"published\">Published figures beside ours</h2>\n<p>%s: not a "
                              "published.json this version writes</p>\n", path);
    assert_string_equal(m.published_md, md);
    assert_string_equal(m.published_html, html);
    free(md);
    free(html);
    report_model_free(&m);
    dm_run_free(&run);
    free(path);
    test_rm_rf(dir);
}

/* front.tex, a row of the writer table: each timed scene's front as a
 * booktabs table, fastest first, the pick marked; the untimed scene a
 * comment.  SSIM's shown metric is 1 − SSIM, at four decimals in its column:
 * 0.2000, 0.0500, 0.0100 and 0.1000. */
static void test_model_front_tex(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_reports_model.XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *path = dm_xasprintf("%s/front.tex", dir), err[256] = "";
    dm_run_result run;
    model_run(&run);
    report_desc d = {.file = "front.tex", .path = path};
    assert_int_equal(report_write_run(&run, &d, err, sizeof err), 0);
    char *tex = test_slurp(path);
    assert_string_equal(tex,
        "% front.tex: each scene's Pareto front, written by dmbench from run 20261129-000000.\n"
        "% \\input it; needs \\usepackage{booktabs}.\n\n"
        "\\begin{table}[htbp]\n\\centering\n"
        "\\caption{plane 160$\\times$90: the Pareto front (1 - SSIM against median frame time), fastest first}\n"
        "\\begin{tabular}{lrrr}\n\\toprule\n"
        "Configuration & Median (ms) & 95\\,\\% CI & 1 - SSIM \\\\\n\\midrule\n"
        "normal & 1.00 & $\\pm$1.0\\% & 0.2000 \\\\\n"
        "pom steps=8 (pick) & 2.00 & $\\pm$2.5\\% & 0.0500 \\\\\n"
        "pom steps=32 & 4.00 & $\\pm$25\\% & 0.0100 \\\\\n"
        "\\bottomrule\n\\end{tabular}\n\\end{table}\n\n"
        "\\begin{table}[htbp]\n\\centering\n"
        "\\caption{cube 160$\\times$90: the Pareto front (1 - SSIM against median frame time), fastest first}\n"
        "\\begin{tabular}{lrrr}\n\\toprule\n"
        "Configuration & Median (ms) & 95\\,\\% CI & 1 - SSIM \\\\\n\\midrule\n"
        "pom (pick) & 1.00 & $\\pm$1.0\\% & 0.1000 \\\\\n"
        "\\bottomrule\n\\end{tabular}\n\\end{table}\n\n"
        "% sphere 160×90: no frame time, no front\n\n");
    free(tex);
    /* a name that is no row of the table is refused, the rows listed */
    d.file = "front.pdf";
    assert_int_equal(report_write_run(&run, &d, err, sizeof err), DM_ERR_ARG);
    assert_non_null(strstr(err, "front.tex"));
    dm_run_free(&run);
    free(path);
    test_rm_rf(dir);
}

/* The answer's sentences and the terminal's lines come from the model
 * alone: a label changed in the model is the label they say, and a scene
 * whose timings are mostly noisy is provisional in both. */
static void test_model_answer(void **state)
{
    (void)state;
    dm_run_result run;
    model_run(&run);
    run.configs[5].counters[0].ci_lo = 1.0e6;             /* k5 noisy too: 2 of 4 is not most */
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_int_equal(m.scenes[0].n_noisy, 2);
    assert_int_equal(m.scenes[0].provisional, 0);
    free(m.rows[0].label);
    m.rows[0].label = dm_xstrdup("THE PICK");
    dm_str s = {0};
    report_answer_scene(&m, 0, REPORT_ANSWER_MD, &s);
    assert_non_null(strstr(dm_str_get(&s), "pick **THE PICK** (2.00 ms [1.95, 2.05], SSIM 0.950)."));
    assert_null(strstr(dm_str_get(&s), "Provisional"));
    dm_str_free(&s);
    m.scenes[0].provisional = 1;                          /* what the model says is what is written */
    m.scenes[0].noisy_majority = 1;
    m.scenes[0].n_noisy = 3;
    report_answer_terminal_model(&m, &s);
    assert_non_null(strstr(dm_str_get(&s), "plane 160×90: Provisional: 3 of 4 timings are noisy"));
    assert_non_null(strstr(dm_str_get(&s), "THE PICK"));
    /* the untimed scene: its reason, then its counters from the scene's columns */
    assert_non_null(strstr(dm_str_get(&s), "sphere 160×90: no timing counter measured: no budget or pick.\n"));
    assert_non_null(strstr(dm_str_get(&s), "VSInvocations"));
    dm_str_free(&s);
    report_counter_table(&m, 2, REPORT_ANSWER_MD, &s);
    assert_string_equal(dm_str_get(&s), "| configuration | VSInvocations |\n|---|---:|\n| pom | 4 |\n");
    dm_str_free(&s);
    report_model_free(&m);
    dm_run_free(&run);
}

/* A run of n timed configurations of one scene, medians 1, 2, … ms, each
 * with VSInvocations 100 × its rank. */
static void breakdown_run(dm_run_result *run, size_t n)
{
    memset(run, 0, sizeof *run);
    run->id = dm_xstrdup("b");
    run->n_configs = n;
    run->configs = dm_xcalloc(n, sizeof *run->configs);
    for (size_t i = 0; i < n; i++) {
        char key[24];
        snprintf(key, sizeof key, "k%zu", i);
        fixture_config(&run->configs[i], key, "pom", "plane", 4);
        double ms = (double)(i + 1) * 1e6;
        fixture_timed(&run->configs[i].counters[0], "WallTime", ms * 0.99, ms, ms * 1.01);
        fixture_det(&run->configs[i].counters[1], "VSInvocations", 100.0 * (double)(i + 1));
        run->configs[i].n_counters = 2;   /* room for the two timed passes */
    }
}

/* The counter breakdown each scene's chart draws is chosen in the model:
 * the key counters without a fit (naming a poor one), a good fit's stage
 * estimate, the measured passes before any fit, at most 24 bars. */
static void test_model_breakdown(void **state)
{
    (void)state;
    dm_run_result run;
    breakdown_run(&run, 3);
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    const breakdown *b = &m.scenes[0].breakdown;
    assert_int_equal(b->kind, BREAKDOWN_COUNTERS);
    assert_int_equal(b->n_counters, 1);
    assert_string_equal(b->counters[0], "VSInvocations");
    size_t bars[] = {0, 1, 2};
    assert_int_equal(b->n_bars, 3);
    assert_memory_equal(b->bars, bars, sizeof bars);
    assert_int_equal(b->skipped, 0);
    assert_null(b->poor);
    report_model_free(&m);

    /* 0.1 ms + 20 µs per vertex shader invocation, too poor to draw: named */
    fixture_fit2(&run, "pipeline-linear", "c0", 1e5, "c_vs", 2e4, 0.5);
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    b = &m.scenes[0].breakdown;
    assert_int_equal(b->kind, BREAKDOWN_COUNTERS);
    assert_string_equal(b->poor->model, "pipeline-linear");
    assert_near(b->poor_r2, 0.5);
    report_model_free(&m);

    run.fits[0].r2 = 0.9;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    b = &m.scenes[0].breakdown;
    assert_int_equal(b->kind, BREAKDOWN_FIT);
    assert_string_equal(b->fit->model, "pipeline-linear");
    assert_null(b->poor);
    assert_near(b->hi_ms, 0.1 + 300 * 0.02);              /* k2's stack over its 3 ms median */
    report_model_free(&m);

    dm_config_result *c = &run.configs[0];                /* k0's timed passes: measured first */
    c->n_counters = 4;
    fixture_timed(&c->counters[2], "GeometryTime", 0.9e5, 1e5, 1.1e5);
    fixture_timed(&c->counters[3], "MinimalShadingTime", 3.9e5, 4e5, 4.1e5);
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    b = &m.scenes[0].breakdown;
    assert_int_equal(b->kind, BREAKDOWN_MEASURED);
    assert_null(b->fit);
    assert_near(b->hi_ms, 3.0);                           /* k2's median: no stack is taller */
    assert_near(breakdown_measured_ms(c, 1), 0.3);        /* setup and raster: 0.4 − 0.1 ms */
    report_model_free(&m);
    dm_run_free(&run);

    breakdown_run(&run, BREAKDOWN_MAX_BARS + 2);         /* the two fastest left out */
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    b = &m.scenes[0].breakdown;
    assert_int_equal(b->skipped, 2);
    assert_int_equal(b->n_bars, BREAKDOWN_MAX_BARS);
    assert_int_equal(b->bars[0], 2);
    report_model_free(&m);
    dm_run_free(&run);
}

/* The units of fit parameters come from the formula and the response
 * counter's unit: a constant term has the response's unit, a factor of a
 * term the response's unit per the rest of the term; a parameter that leads
 * no term (an exponent) has none. */
static void test_model_fit_units(void **state)
{
    (void)state;
    dm_run_result run;
    fixture_run(&run);                                    /* WallTime in ns; fit "a + b*tess_level^p" */
    dm_fit_result *f = &run.fits[0];
    f->n_params = 3;
    f->params = dm_xrealloc(f->params, 3 * sizeof *f->params);
    f->params[2] = (dm_fit_param){.name = dm_xstrdup("p"), .value = 1.5, .stderr_ = NAN};
    report_model m;
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_string_equal(m.fit_units[0][0], "ns");
    assert_string_equal(m.fit_units[0][1], "ns per tess_level^p");
    assert_string_equal(m.fit_units[0][2], "");
    report_model_free(&m);
    free(f->formula);                                     /* a plain sum, a product, a name that only begins another */
    f->formula = dm_xstrdup("c0 + c_vs*VSInvocations + c_tp*TESInvocations*ClippingOutputPrimitives");
    free(f->params[0].name);
    f->params[0].name = dm_xstrdup("c");
    free(f->params[1].name);
    f->params[1].name = dm_xstrdup("c_tp");
    free(f->response);
    f->response = dm_xstrdup("Instructions");             /* no such counter in the run */
    assert_int_equal(report_model_build(&m, &run, NULL), 0);
    assert_string_equal(m.fit_units[0][0], "");
    assert_string_equal(m.fit_units[0][1], "units of Instructions per TESInvocations*ClippingOutputPrimitives");
    report_model_free(&m);
    dm_run_free(&run);
}

static void test_model_no_run(void **state)
{
    (void)state;
    report_model m;
    assert_int_equal(report_model_build(&m, NULL, NULL), DM_ERR_ARG);
    report_model_free(&m);   /* zeroed: nothing to free */
}

DM_TEST_MAIN(NULL, NULL, cmocka_unit_test(test_model_rows), cmocka_unit_test(test_model_scenes),
             cmocka_unit_test(test_model_published), cmocka_unit_test(test_model_front_tex),
             cmocka_unit_test(test_model_answer),
             cmocka_unit_test(test_model_breakdown),
             cmocka_unit_test(test_model_fit_units),
             cmocka_unit_test(test_model_no_run))
