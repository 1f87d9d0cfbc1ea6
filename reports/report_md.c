/* report_md.c — summary.md for CI logs: run header, a table per scene,
 * failures and left-out configurations with their reasons. */
#include "reports/report.h"
#include "reports/report_internal.h"
#include "reports/published_report.h"
#include "reports/proxy.h"
#include "reports/answer.h"

#include "core/dm_error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Table-cell text: plain text only (dm_str_cat_md: '|', HTML, control bytes). */
static void cell(dm_str *s, const char *text)
{
    dm_str_cat_md(s, text);
}

static void params_text(dm_str *s, const dm_kv *kv, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (i)
            dm_str_cat(s, " ");
        cell(s, kv[i].key);
        dm_str_cat(s, "=");
        cell(s, kv[i].value);
    }
}

/* PSNR, SSIM and the Pareto metric's shown value. */
static void quality_cells(dm_str *s, const dm_quality *q, report_metric m)
{
    if (!q->present) {
        dm_str_cat(s, " – | – | – |");
        return;
    }
    if (isinf(q->psnr))
        dm_str_cat(s, " ∞ |");
    else
        dm_str_printf(s, " %.2f dB |", q->psnr);
    dm_str_printf(s, " %.4f |", q->ssim);
    double v = report_metric_shown(q, m);
    if (isinf(v))
        dm_str_cat(s, " ∞ |");
    else
        dm_str_printf(s, " %.4g |", v);
}

static void scene_table(dm_str *s, const dm_run_result *run, const char *scene)
{
    dm_str l = {0};
    report_scene_label(run, scene, &l);
    dm_str_cat(s, "\n## ");
    cell(s, dm_str_get(&l));
    dm_str_cat(s, "\n\n");
    dm_str_free(&l);
    report_answer_scene(run, scene, REPORT_ANSWER_MD, s);
    report_metric m = report_metric_of_run(run);
    int timed = report_untimed_reason(run, scene) == NULL;
    if (timed) {
        dm_str_printf(s, "\nFront (best %s for its cost, fastest first): ", report_metric_label(m));
        dm_str front = {0};
        report__pareto_text(run, scene, &front);
        cell(s, dm_str_get(&front));
        dm_str_free(&front);
        dm_str_printf(s, ".\n\n| configuration | median ms | 95%% CI | PSNR | SSIM | %s | key |\n"
                         "|---|---|---|---|---|---|---|\n", report_metric_label(m));
    } else   /* counters only: the counters are above; quality and keys here */
        dm_str_printf(s, "\nQuality against the reference:\n\n| configuration | PSNR | SSIM | %s | key |\n"
                         "|---|---|---|---|---|\n", report_metric_label(m));
    size_t *rows, nr = report__scene_rows(run, scene, &rows);
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        const dm_counter_result *t = report__frame_time(c);
        dm_str label = {0};
        report__config_label(run, c, &label);
        dm_str_cat(s, "| ");
        cell(s, dm_str_get(&label));
        dm_str_free(&label);
        if (!timed) {
            dm_str_cat(s, " |");
        } else if (t) {
            dm_str mark = {0}, why = {0};
            dm_str_cat(s, " | ");
            report__ms_text(t->median, s);
            dm_str_cat(s, " | ");
            report__ci_text(t, s);
            report__timing_marks(c, 0, &mark, &why);
            if (mark.len) {
                dm_str_cat(s, " ");
                cell(s, dm_str_get(&mark));
            }
            dm_str_cat(s, " |");
            dm_str_free(&mark);
            dm_str_free(&why);
        } else
            dm_str_cat(s, " | unavailable | |");
        quality_cells(s, &c->quality, m);
        dm_str_printf(s, " `%s` |\n", c->key);
    }
    free(rows);
}

/* Noisy configurations listed this many to a line. */
#define NOISY_PER_LINE 4

/* The noisy configurations by label with their CI and marks, a few per
 * indented line (under their warning). */
static void noisy_list(dm_str *s, const dm_run_result *run)
{
    size_t *idx, n = report__noisy_configs(run, &idx);
    for (size_t i = 0; i < n; i++) {
        const dm_config_result *c = &run->configs[idx[i]];
        dm_str label = {0}, mark = {0}, why = {0};
        report_config_label(run, c, &label);
        dm_str_cat(s, i % NOISY_PER_LINE ? "; " : "  - ");
        cell(s, dm_str_get(&label));
        report__timing_marks(c, 1, &mark, &why);
        dm_str_cat(s, " (");
        cell(s, dm_str_get(&mark) + strlen("⚠ noisy: "));
        dm_str_cat(s, ")");
        dm_str_cat(s, i % NOISY_PER_LINE == NOISY_PER_LINE - 1 || i + 1 == n ? "\n" : "");
        dm_str_free(&label);
        dm_str_free(&mark);
        dm_str_free(&why);
    }
    free(idx);
}

static void failures(dm_str *s, const dm_run_result *run)
{
    dm_str_cat(s, "\n## Failed configurations\n\n");
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (c->ok)
            continue;
        dm_str_printf(s, "- `%s` ", c->key);
        params_text(s, c->params, c->n_params);
        dm_str_cat(s, ": ");
        cell(s, c->reason ? c->reason : "no reason recorded");
        dm_str_cat(s, "\n");
        n++;
    }
    if (!n)
        dm_str_cat(s, "None.\n");
    dm_str_cat(s, "\n## Left out\n\n");
    for (size_t i = 0; i < run->n_left_out; i++) {
        dm_str_cat(s, "- ");
        params_text(s, run->left_out[i].params, run->left_out[i].n_params);
        dm_str_cat(s, ": ");
        cell(s, run->left_out[i].reason);
        dm_str_cat(s, "\n");
    }
    if (!run->n_left_out)
        dm_str_cat(s, "None.\n");
}

/* Instructions as a proxy for frame time, and counters by pass. */
static void proxy_section(dm_str *s, const dm_run_result *run)
{
    report_proxy p;
    if (report_proxy_fit(run, &p) == 0) {
        dm_str_printf(s, "\n## Instructions as a proxy for frame time\n\nWallTime ≈ %.4g ns + %.4g ns × "
                      "Instructions over %zu configurations: R² = %.5f. Strays most:\n\n",
                      p.a_ns, p.ns_per_instruction, p.n, p.r2);
        for (size_t i = 0; i < p.n_strays; i++) {
            dm_str_cat(s, "- ");
            cell(s, p.strays[i].label);
            dm_str_printf(s, ": %.3f ms measured, %.3f ms predicted (%+.1f%%)\n", p.strays[i].wall_ns / 1e6,
                          p.strays[i].predicted_ns / 1e6, p.strays[i].residual_rel * 100);
        }
    }
    dm_str_cat(s, "\n## Counters by pass\n\n");
    report_proxy_passes_text(run, "\n\n", s);
}

int report_write_markdown(const dm_run_result *run, const char *path)
{
    if (!run || !path)
        return DM_ERR_ARG;
    dm_str s = {0};
    dm_str_cat(&s, "# dmbench run ");
    cell(&s, run->id);
    dm_str_cat(&s, "\n\n- sweep: ");
    cell(&s, run->sweep);
    dm_str_cat(&s, "\n- started: ");
    cell(&s, run->started);
    dm_str_cat(&s, "\n- renderer: ");
    cell(&s, dm_kv_get(run->environment, run->n_environment, "renderer"));
    dm_str_printf(&s, "\n- Pareto metric: %s (%s)", report_metric_name(report_metric_of_run(run)),
                  report_metric_label(report_metric_of_run(run)));
    dm_str_cat(&s, "\n- budget: ");
    if (!report_run_timed(run))
        dm_str_cat(&s, "none: no timing counter measured, so no budget or pick (the counters are in "
                       "each scene's table)");
    else if (report_budget_ms(run) > 0)
        dm_str_printf(&s, "%g ms", report_budget_ms(run));
    else
        dm_str_cat(&s, "default per scene, a round number midway (log scale) between its fastest and "
                       "slowest lit times (set one with report --budget-ms or quality.budget_ms)");
    dm_str_printf(&s, "\n- timer: %s (GPUTime covers %.1f%% of fenced wall time)\n",
                  run->timer_verdict ? run->timer_verdict : "unknown", run->gpu_time_coverage * 100);
    dm_str k = {0};
    report_scene_constants(run, &k);
    if (k.len) {
        dm_str_cat(&s, "- every scene: ");
        cell(&s, dm_str_get(&k));
        dm_str_cat(&s, "\n");
    }
    dm_str_free(&k);
    char **w;
    size_t nw = report__warnings(run, &w);   /* the list of results.json */
    for (size_t i = 0; i < nw; i++) {
        dm_str_cat(&s, "- warning: ");
        cell(&s, w[i]);
        dm_str_cat(&s, "\n");
        if (strstr(w[i], " noisy configuration") && strstr(w[i], "compare their times with care"))
            noisy_list(&s, run);
    }
    report__warnings_free(w, nw);
    const char **scenes;
    size_t ns = report__scenes(run, &scenes);
    for (size_t i = 0; i < ns; i++)
        scene_table(&s, run, scenes[i]);
    free(scenes);
    failures(&s, run);
    report_published_section(&s, run, NULL, path, 0);
    proxy_section(&s, run);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
