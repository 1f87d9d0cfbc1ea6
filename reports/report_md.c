/* report_md.c — summary.md for CI logs: run header, a table per scene,
 * failures and left-out configurations with their reasons.  A row of the
 * writer table (report_write.c): labels, times, fronts, warnings and the
 * published section come from the report model (report_model.h); the
 * answer and its counters read the model too (answer.c); "Along the path"
 * reads each configuration's path series, "Quality along the path" its
 * path quality; failures, left-out
 * configurations and the proxy section read the run. */
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
static void report_md__cell(dm_str *s, const char *text)
{
    dm_str_cat_md(s, text);
}

static void report_md__params_text(dm_str *s, const dm_kv *kv, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (i)
            dm_str_cat(s, " ");
        report_md__cell(s, kv[i].key);
        dm_str_cat(s, "=");
        report_md__cell(s, kv[i].value);
    }
}

/* PSNR (unless it is the Pareto metric, whose column says it), SSIM and
 * the Pareto metric's shown value at its column's one precision. */
static void report_md__quality_cells(dm_str *s, const dm_quality *q, report_metric m)
{
    int psnr = m != REPORT_METRIC_PSNR;
    if (!q->present) {
        dm_str_cat(s, psnr ? " – | – | – |" : " – | – |");
        return;
    }
    if (psnr && isinf(q->psnr))
        dm_str_cat(s, " ∞ |");
    else if (psnr)
        dm_str_printf(s, " %.2f dB |", q->psnr);
    dm_str_printf(s, " %.4f |", q->ssim);
    double v = report_metric_shown(q, m);
    if (isinf(v)) {
        dm_str_cat(s, " ∞ |");
        return;
    }
    dm_str_cat(s, " ");
    dm_str_printf(s, report_metric_format(m), v);
    dm_str_cat(s, " |");
}

static void report_md__scene_table(dm_str *s, const report_model *m, const report_model_scene *sc)
{
    dm_str_cat(s, "\n## ");
    report_md__cell(s, sc->label);
    dm_str_cat(s, "\n\n");
    report_answer_scene(m, (size_t)(sc - m->scenes), REPORT_ANSWER_MD, s);
    int timed = sc->untimed == NULL, psnr = m->metric != REPORT_METRIC_PSNR;   /* else one PSNR column */
    if (timed) {
        dm_str_printf(s, "\nFront (best %s for its cost, fastest first): ", report_metric_label(m->metric));
        report_md__cell(s, sc->front_text);
        dm_str_printf(s, ".\n\n| configuration | median ms | 95%% CI | drift removed: ms [95%% CI] |%s SSIM | %s | "
                         "key |\n|---|---|---|---|%s---|---|---|\n", psnr ? " PSNR |" : "",
                      report_metric_label(m->metric), psnr ? "---|" : "");
    } else   /* counters only: the counters are above; quality and keys here */
        dm_str_printf(s, "\nQuality against the reference:\n\n| configuration |%s SSIM | %s | key |\n"
                         "|---|%s---|---|---|\n", psnr ? " PSNR |" : "", report_metric_label(m->metric),
                      psnr ? "---|" : "");
    for (size_t i = 0; i < sc->n_rows; i++) {
        const report_model_row *r = &m->rows[sc->rows[i]];
        dm_str_cat(s, "| ");
        report_md__cell(s, r->label);
        if (!timed) {
            dm_str_cat(s, " |");
        } else if (r->frame_time) {
            dm_str_printf(s, " | %s | %s", r->ms_text, r->ci_text);
            if (*r->marks_short) {
                dm_str_cat(s, " ");
                report_md__cell(s, r->marks_short);
            }
            dm_str_cat(s, " | ");
            report_md__cell(s, r->corrected ? r->corr_time_ci_text : "raw only");
            dm_str_cat(s, " |");
        } else
            dm_str_cat(s, " | unavailable | | |");
        report_md__quality_cells(s, &r->config->quality, m->metric);
        dm_str_printf(s, " `%s` |\n", r->config->key);
    }
}

/* Stutter frames listed in a cell before "…". */
#define REPORT_MD__STUTTERS_SHOWN 8

/* A time in ms at three decimals, or "unavailable" (no finite frame time). */
static void report_md__ms(dm_str *s, double ns)
{
    if (isfinite(ns))
        dm_str_printf(s, " %.3f |", ns / 1e6);
    else
        dm_str_cat(s, " unavailable |");
}

/* One configuration's row of "Along the path". */
static void report_md__path_row(dm_str *s, const report_model_row *r)
{
    const dm_path_series *p = &r->config->path;
    dm_str_cat(s, "| ");
    report_md__cell(s, r->name);
    dm_str_printf(s, " | %zu × %zu |", p->frames, p->replays);
    report_md__ms(s, p->p50);
    report_md__ms(s, p->p95);
    report_md__ms(s, p->p99);
    if (isfinite(p->low1_ns))
        dm_str_printf(s, " %.3f (%.0f fps) |", p->low1_ns / 1e6, p->low1_fps);
    else
        dm_str_cat(s, " unavailable |");
    dm_str_printf(s, " %zu", p->n_stutters);
    for (size_t i = 0; i < p->n_stutters && i < REPORT_MD__STUTTERS_SHOWN; i++)
        dm_str_printf(s, "%s%ld", i ? ", " : p->n_stutters == 1 ? " (frame " : " (frames ", p->stutter_at[i]);
    if (p->n_stutters)
        dm_str_cat(s, p->n_stutters > REPORT_MD__STUTTERS_SHOWN ? ", …)" : ")");
    if (p->noisy < 0)
        dm_str_cat(s, " | unknown (one replay) |");
    else
        dm_str_printf(s, " | %.1f %%%s |", 100 * p->replay_spread, p->noisy ? " ⚠ noisy" : "");
    dm_str_printf(s, " `%s` |\n", r->config->key);
}

/* "Along the path": the frame times of the configurations on a camera path
 * (docs/motion.md); nothing in a run without one. */
static void report_md__path_section(dm_str *s, const report_model *m)
{
    if (!m->n_path_rows)
        return;
    dm_str_cat(s, "\n## Along the path\n\nEach frame's time is the median of its replays; p50/p95/p99 "
                  "over the frames, the 1 % low the mean of the slowest ⌈F/100⌉, a stutter a frame over "
                  "2 × p50 (frame indices along the path), the replay spread the median over frames of "
                  "(max − min) / median of its replays (noisy over 10 %).\n\n"
                  "| configuration | frames × replays | p50 ms | p95 ms | p99 ms | 1 % low ms | stutters | "
                  "replay spread | key |\n|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < m->n_rows; i++)
        if (m->rows[i].config->path.frames)
            report_md__path_row(s, &m->rows[i]);
}

/* A figure of quality along the path at four significant digits, or
 * "unavailable". */
static void report_md__q(dm_str *s, double v)
{
    if (isfinite(v))
        dm_str_printf(s, " %.4g |", v);
    else
        dm_str_cat(s, " unavailable |");
}

/* "Quality along the path": per configuration that asked for it, its
 * temporal error, popping and map, or why they are missing
 * (docs/motion.md); nothing in a run where none asked. */
static void report_md__path_quality_section(dm_str *s, const report_model *m)
{
    size_t n = 0;
    for (size_t i = 0; i < m->n_rows; i++)
        n += m->rows[i].config->path_quality.present || m->rows[i].config->path_quality.reason;
    if (!n)
        return;
    dm_str_cat(s, "\n## Quality along the path\n\nTemporal error: how much the frame-to-frame change of the "
                  "technique differs from the reference's, per pixel and step between reference frames "
                  "(mean and 99th percentile); popping: the largest jump of FLIP between consecutive "
                  "reference frames, at the frame it lands on.\n\n"
                  "| configuration | reference frames | temporal error mean | temporal error p99 | popping | "
                  "temporal error map | key |\n|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < m->n_rows; i++) {
        const report_model_row *r = &m->rows[i];
        const dm_path_quality *q = &r->config->path_quality;
        if (!q->present && !q->reason)
            continue;
        dm_str_cat(s, "| ");
        report_md__cell(s, r->name);
        if (!q->present) {
            dm_str_cat(s, " | unavailable: ");
            report_md__cell(s, q->reason);
            dm_str_printf(s, " | | | | | `%s` |\n", r->config->key);
            continue;
        }
        dm_str_printf(s, " | %zu (every %ld of %ld) |", q->n, q->every, q->frames);
        report_md__q(s, q->temporal_mean);
        report_md__q(s, q->temporal_p99);
        if (isfinite(q->popping) && q->popping_frame >= 0)
            dm_str_printf(s, " %.4g (frame %ld) |", q->popping, q->popping_frame);
        else
            dm_str_cat(s, " unavailable |");
        dm_str_cat(s, " ");
        report_md__cell(s, q->img_temporal ? q->img_temporal : "none");
        dm_str_printf(s, " | `%s` |\n", r->config->key);
    }
}

/* Noisy configurations listed this many to a line. */
#define NOISY_PER_LINE 4

/* The noisy configurations by label with their CI and marks, a few per
 * indented line (under their warning). */
static void report_md__noisy_list(dm_str *s, const report_model *m)
{
    for (size_t i = 0; i < m->n_noisy; i++) {
        const report_model_row *r = &m->rows[m->noisy[i]];
        dm_str_cat(s, i % NOISY_PER_LINE ? "; " : "  - ");
        report_md__cell(s, r->full_label);
        dm_str_cat(s, " (");
        report_md__cell(s, r->marks + strlen("⚠ noisy: "));
        dm_str_cat(s, ")");
        dm_str_cat(s, i % NOISY_PER_LINE == NOISY_PER_LINE - 1 || i + 1 == m->n_noisy ? "\n" : "");
    }
}

static void report_md__failures(dm_str *s, const dm_run_result *run)
{
    dm_str_cat(s, "\n## Failed configurations\n\n");
    size_t n = 0;
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        if (c->ok)
            continue;
        dm_str_printf(s, "- `%s` ", c->key);
        report_md__params_text(s, c->params, c->n_params);
        dm_str_cat(s, ": ");
        report_md__cell(s, c->reason ? c->reason : "no reason recorded");
        dm_str_cat(s, "\n");
        n++;
    }
    if (!n)
        dm_str_cat(s, "None.\n");
    dm_str_cat(s, "\n## Left out\n\n");
    for (size_t i = 0; i < run->n_left_out; i++) {
        dm_str_cat(s, "- ");
        report_md__params_text(s, run->left_out[i].params, run->left_out[i].n_params);
        dm_str_cat(s, ": ");
        report_md__cell(s, run->left_out[i].reason);
        dm_str_cat(s, "\n");
    }
    if (!run->n_left_out)
        dm_str_cat(s, "None.\n");
}

/* Instructions as a proxy for frame time, and counters by pass. */
static void report_md__proxy_section(dm_str *s, const dm_run_result *run)
{
    report_proxy p;
    if (report_proxy_fit(run, &p) == 0) {
        dm_str_printf(s, "\n## Instructions as a proxy for frame time\n\nWallTime ≈ %.4g ns + %.4g ns × "
                      "Instructions over %zu configurations: R² = %.5f. Strays most:\n\n",
                      p.a_ns, p.ns_per_instruction, p.n, p.r2);
        for (size_t i = 0; i < p.n_strays; i++) {
            dm_str_cat(s, "- ");
            report_md__cell(s, p.strays[i].label);
            dm_str_printf(s, ": %.3f ms measured, %.3f ms predicted (%+.1f%%)\n", p.strays[i].wall_ns / 1e6,
                          p.strays[i].predicted_ns / 1e6, p.strays[i].residual_rel * 100);
        }
    }
    dm_str_cat(s, "\n## Counters by pass\n\n");
    report_proxy_passes_text(run, "\n\n", s);
}

int report__write_md(const report_model *m, const report_desc *d, const char *path)
{
    (void)d;
    const dm_run_result *run = m->run;
    dm_str s = {0};
    dm_str_cat(&s, "# dmbench run ");
    report_md__cell(&s, run->id);
    dm_str_cat(&s, "\n\n- sweep: ");
    report_md__cell(&s, run->sweep);
    dm_str_cat(&s, "\n- started: ");
    report_md__cell(&s, run->started);
    dm_str_cat(&s, "\n- renderer: ");
    report_md__cell(&s, dm_kv_get(run->environment, run->n_environment, "renderer"));
    dm_str_printf(&s, "\n- Pareto metric: %s (%s)", report_metric_name(m->metric),
                  report_metric_label(m->metric));
    dm_str_cat(&s, "\n- budget: ");
    if (!m->any_timed)
        dm_str_cat(&s, "none: no timing counter measured, so no budget or pick (the counters are in "
                       "each scene's table)");
    else if (m->budget_ms > 0)
        dm_str_printf(&s, "%g ms", m->budget_ms);
    else
        dm_str_cat(&s, "default per scene, the round number (1, 2, 5 x 10^n ms) between its fastest and "
                       "slowest lit times farthest (log scale) from every lit time (set one with report --budget-ms or quality.budget_ms)");
    dm_str_printf(&s, "\n- timer: %s (GPUTime covers %.1f%% of fenced wall time)\n",
                  run->timer_verdict ? run->timer_verdict : "unknown", run->gpu_time_coverage * 100);
    if (*m->constants) {
        dm_str_cat(&s, "- every scene: ");
        report_md__cell(&s, m->constants);
        dm_str_cat(&s, "\n");
    }
    if (*m->precision_text) {   /* noise floor and drift removal (docs/measurement.md) */
        dm_str_cat(&s, "- precision: ");
        report_md__cell(&s, m->precision_text);
        dm_str_cat(&s, "\n");
        for (size_t i = 0; i < m->n_scenes; i++) {
            const dm_scene_precision *p = m->scenes[i].precision;
            if (!p || p->corrected)
                continue;
            dm_str_cat(&s, "  - ");
            report_md__cell(&s, m->scenes[i].label);
            dm_str_cat(&s, ": ");
            report_md__cell(&s, p->reason ? p->reason : "no reason recorded");
            dm_str_cat(&s, "\n");
        }
    }
    char *const *w = m->warnings;   /* the list of results.json */
    for (size_t i = 0; i < m->n_warnings; i++) {
        dm_str_cat(&s, "- warning: ");
        report_md__cell(&s, w[i]);
        dm_str_cat(&s, "\n");
        if (strstr(w[i], " noisy configuration") && strstr(w[i], "compare their times with care"))
            report_md__noisy_list(&s, m);
    }
    for (size_t i = 0; i < m->n_scenes; i++)
        report_md__scene_table(&s, m, &m->scenes[i]);
    report_md__path_section(&s, m);
    report_md__path_quality_section(&s, m);
    report_md__failures(&s, run);
    dm_str_cat(&s, m->published_md);
    report_md__proxy_section(&s, run);
    int rc = report__save(&s, path);
    dm_str_free(&s);
    return rc;
}
