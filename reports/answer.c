/* answer.c — the recommendation of each scene in words (see answer.h). */
#include "reports/answer.h"
#include "reports/report.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"
#include "core/dm_table.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int report_budget_set(dm_run_result *run, double ms)
{
    if (!(ms > 0) || !isfinite(ms))
        return DM_ERR_ARG;
    char buf[32];
    report__fmt_num(ms, buf);
    for (size_t i = 0; i < run->n_environment; i++)
        if (strcmp(run->environment[i].key, REPORT_BUDGET_KEY) == 0) {
            free(run->environment[i].value);
            run->environment[i].value = dm_xstrdup(buf);
            return 0;
        }
    dm_kv_push(&run->environment, &run->n_environment, REPORT_BUDGET_KEY, buf);
    return 0;
}

double report_budget_ms(const dm_run_result *run)
{
    const char *v = dm_kv_get(run->environment, run->n_environment, REPORT_BUDGET_KEY);
    double ms = v ? strtod(v, NULL) : 0;
    return ms > 0 && isfinite(ms) ? ms : 0;
}

recommend_family report_family(const dm_config_result *c)
{
    if (dm_kv_get(c->params, c->n_params, "tess_level"))
        return RECOMMEND_TESSELLATION;
    if (dm_kv_get(c->params, c->n_params, "vertex_filter"))
        return RECOMMEND_VERTEX;
    if (!dm_kv_get(c->params, c->n_params, "lighting"))
        return RECOMMEND_UNLIT;
    return RECOMMEND_FRAGMENT;
}

/* The scene's points (ok configurations with a frame time) and their
 * config indexes; returns the count.  *p and *idx are malloc'd.  With
 * corrected, a frame time with the drift removed gives its corrected
 * median and CI (run/precision.h), the others their raw ones. */
static size_t answer__points(const dm_run_result *run, const char *scene, int corrected,
                             recommend_point **p, size_t **idx)
{
    size_t nr = report__scene_rows(run, scene, idx), n = 0;
    report_metric m = report_metric_of_run(run);
    *p = dm_xcalloc(nr + 1, sizeof **p);
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[(*idx)[i]];
        const dm_counter_result *t = report__frame_time(c);
        if (!t)
            continue;
        int corr = corrected && t->corrected;
        (*p)[n] = (recommend_point){corr ? t->corr_median : t->median, corr ? t->corr_ci_lo : t->ci_lo,
                                    corr ? t->corr_ci_hi : t->ci_hi, report_metric_error(&c->quality, m),
                                    report_family(c)};
        (*idx)[n++] = (*idx)[i];
    }
    return n;
}

static size_t answer__map(const size_t *idx, size_t i)
{
    return i == RECOMMEND_NONE ? RECOMMEND_NONE : idx[i];
}

double report_resolvable(const dm_run_result *run)
{
    double floor, resolvable;
    return dm_run_noise_floor(run, &floor, &resolvable) ? resolvable : NAN;
}

/* report_recommend on the raw or the corrected figures. */
static size_t answer__recommend(const dm_run_result *run, const char *scene, int corrected,
                                recommend_result *out)
{
    recommend_point *p;
    size_t *idx, n = answer__points(run, scene, corrected, &p, &idx);
    double res = report_resolvable(run);
    recommend_desc d = {.budget = report_budget_ms(run) * 1e6,
                        .epsilon = report_metric_epsilon(report_metric_of_run(run)),
                        .resolvable = isfinite(res) ? res : 0};
    recommend_scene(p, n, &d, out);
    out->pick = answer__map(idx, out->pick);
    out->pick_tie = answer__map(idx, out->pick_tie);
    out->fastest = answer__map(idx, out->fastest);
    out->knee = answer__map(idx, out->knee);
    for (int f = 0; f < RECOMMEND_FAMILY_COUNT; f++) {
        out->family_best[f] = answer__map(idx, out->family_best[f]);
        out->family_fastest[f] = answer__map(idx, out->family_fastest[f]);
    }
    free(p);
    free(idx);
    return n;
}

size_t report_recommend(const dm_run_result *run, const char *scene, recommend_result *out)
{
    return answer__recommend(run, scene, 0, out);
}

/* 1 when some ok configuration of the scene has its frame time corrected. */
static int answer__scene_corrected(const dm_run_result *run, const char *scene)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_config_result *c = &run->configs[i];
        const dm_counter_result *t = c->ok && c->scene && strcmp(c->scene, scene) == 0
                                         ? report__frame_time(c) : NULL;
        if (t && t->corrected)
            return 1;
    }
    return 0;
}

int report_recommend_corrected(const dm_run_result *run, const char *scene, recommend_result *out)
{
    if (!answer__scene_corrected(run, scene))
        return 0;
    answer__recommend(run, scene, 1, out);
    return 1;
}

int report_answer_disagree(const dm_run_result *run, const char *scene, dm_str *out)
{
    recommend_result r, c;
    if (report_untimed_reason(run, scene) || !report_recommend_corrected(run, scene, &c))
        return 0;
    size_t had = out->len;
    report_recommend(run, scene, &r);
    dm_str a = {0}, b = {0};
    if (r.pick != c.pick) {
        if (r.pick != RECOMMEND_NONE)
            report__config_label(run, &run->configs[r.pick], &a);
        if (c.pick != RECOMMEND_NONE)
            report__config_label(run, &run->configs[c.pick], &b);
        if (c.pick == RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed nothing fits the budget; the answer reads the raw figures.");
        else if (r.pick == RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick is %s; the answer reads the raw figures, where nothing "
                          "fits.", dm_str_get(&b));
        else
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick is %s, not %s; the answer reads the raw figures.",
                          dm_str_get(&b), dm_str_get(&a));
    } else if (r.pick_tie != c.pick_tie) {
        size_t t = c.pick_tie != RECOMMEND_NONE ? c.pick_tie : r.pick_tie;
        report__config_label(run, &run->configs[t], &b);
        if (c.pick_tie != RECOMMEND_NONE)
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick ties with %s%s.", dm_str_get(&b),
                          r.pick_tie != RECOMMEND_NONE ? " instead" : "");
        else
            dm_str_printf(out, "Raw and drift-corrected figures disagree: with the machine's drift "
                          "removed the pick does not tie with %s; its time is told apart.", dm_str_get(&b));
    }
    dm_str_free(&a);
    dm_str_free(&b);
    return out->len > had;
}


/* A writer of one format: text is escaped for it, strong is emphasised. */
typedef struct answer__w {
    dm_str *s;
    report_answer_format f;
} answer__w;

static void w_text(answer__w *w, const char *t)
{
    if (w->f == REPORT_ANSWER_HTML)
        dm_str_cat_html(w->s, t);
    else if (w->f == REPORT_ANSWER_MD)
        dm_str_cat_md(w->s, t);
    else
        dm_str_cat(w->s, t);
}

static void w_strong(answer__w *w, const char *t)
{
    static const char *const open[] = {"", "<b>", "**"}, *const close[] = {"", "</b>", "**"};
    dm_str_cat(w->s, open[w->f]);
    w_text(w, t);
    dm_str_cat(w->s, close[w->f]);
}

/* A warning mark: "⚠ noisy: CI −5%/+89%" (HTML: a span with the reason as title). */
static void w_mark(answer__w *w, const char *mark, const char *why)
{
    if (w->f == REPORT_ANSWER_HTML) {
        dm_str_cat(w->s, " <span class=\"noisy\" title=\"");
        dm_str_cat_html(w->s, why);
        dm_str_cat(w->s, "\">");
        dm_str_cat_html(w->s, mark);
        dm_str_cat(w->s, "</span>");
    } else {
        w_text(w, " ");
        w_text(w, mark);
    }
}

void report__timing_marks(const dm_config_result *c, int with_ci, dm_str *mark, dm_str *why)
{
    const dm_counter_result *t = report__frame_time(c);
    double lo, hi;
    size_t up = report__bimodal(t, &lo, &hi);
    if (report__noisy(c)) {
        dm_str_cat(mark, with_ci ? "⚠ noisy: " : "⚠ noisy");
        if (with_ci && isfinite(report__ci_rel(t)))
            dm_str_cat(mark, "CI ");
        if (with_ci)
            report__ci_text(t, mark);
        dm_str_printf(why, "the 95%% CI of the median is wider than ±%.0f%% of it (or unknown)",
                      REPORT__NOISY_CI_REL * 100);
    }
    size_t dl;
    const char *drift = report__drift(c, &dl);
    if (drift) {
        dm_str_printf(mark, "%s⚠ drift %+.3g %%", mark->len ? "; " : "",
                      strtod(drift + strlen("WallTime drifted"), NULL));
        dm_str_cat(why, why->len ? "; " : "");
        dm_str_catn(why, drift, dl);
    }
    if (up) {
        dm_str_printf(mark, "%s⚠ bimodal: %zu of %zu samples near ", mark->len ? "; " : "", up,
                      t->n_samples);
        report__ms_text(hi, mark);
        dm_str_cat(mark, " ms, the rest near ");
        report__ms_text(lo, mark);
        dm_str_printf(why, "%sthe samples form two groups: the machine was busy part of the time",
                      why->len ? "; " : "");
    }
}

/* "Provisional: 17 of 18 timings are noisy. " before a scene's pick when
 * more than half of its timed configurations are noisy (report__noisy):
 * the pick may change on a quieter run. */
static void answer__provisional(answer__w *w, const dm_run_result *run, const char *scene)
{
    size_t *rows, nr = report__scene_rows(run, scene, &rows), timed = 0, noisy = 0;
    for (size_t i = 0; i < nr; i++) {
        const dm_config_result *c = &run->configs[rows[i]];
        if (!report__frame_time(c))
            continue;
        timed++;
        noisy += report__noisy(c) != 0;
    }
    free(rows);
    if (timed < 2 || 2 * noisy <= timed)
        return;
    dm_str t = {0};
    dm_str_printf(&t, "Provisional: %zu of %zu timings are noisy (the machine was busy); ", noisy, timed);
    w_strong(w, dm_str_get(&t));
    dm_str_free(&t);
}

/* The defects of a configuration's image as one mark ("⚠ 128 crack
 * pixels; ⚠ 3 NaN pixels") and the reasons in words; nothing when the
 * image has none. */
static void answer__defects(const dm_config_result *c, dm_str *mark, dm_str *why)
{
    const dm_quality *q = &c->quality;
    if (q->present && q->crack_pixels > 0) {
        dm_str_printf(mark, "⚠ %ld crack pixel%s", q->crack_pixels, q->crack_pixels == 1 ? "" : "s");
        dm_str_cat(why, "background shows through the surface inside its silhouette (cracks between "
                        "patches or triangles)");
    }
    if (q->present && q->nonfinite_pixels > 0) {
        dm_str_printf(mark, "%s⚠ %ld NaN pixel%s", mark->len ? "; " : "", q->nonfinite_pixels,
                      q->nonfinite_pixels == 1 ? "" : "s");
        dm_str_printf(why, "%sthe shader wrote NaN or infinite values", why->len ? "; " : "");
    }
}

/* "label (4.43 ms [4.33, 4.53], SSIM 0.927) ⚠ noisy: … ⚠ 128 crack pixels" */
static void w_config(answer__w *w, const dm_run_result *run, size_t ci, int strong)
{
    const dm_config_result *c = &run->configs[ci];
    dm_str label = {0}, rest = {0}, mark = {0}, why = {0};
    report__config_label(run, c, &label);
    (strong ? w_strong : w_text)(w, dm_str_get(&label));
    dm_str_cat(&rest, " (");
    report__time_ci_text(report__frame_time(c), &rest);
    dm_str_cat(&rest, ", ");
    report_metric_text(&c->quality, report_metric_of_run(run), &rest);
    dm_str_cat(&rest, ")");
    w_text(w, dm_str_get(&rest));
    report__timing_marks(c, 1, &mark, &why);
    if (mark.len)
        w_mark(w, dm_str_get(&mark), dm_str_get(&why));
    dm_str_free(&mark);
    dm_str_free(&why);
    answer__defects(c, &mark, &why);   /* its image's defects beside it, not only in the warnings */
    if (mark.len)
        w_mark(w, dm_str_get(&mark), dm_str_get(&why));
    dm_str_free(&label);
    dm_str_free(&rest);
    dm_str_free(&mark);
    dm_str_free(&why);
}

/* "Under 20 ms" with how the budget was chosen. */
static void w_budget(answer__w *w, const recommend_result *r)
{
    dm_str b = {0};
    dm_str_printf(&b, "Under %g ms", r->budget / 1e6);
    w_strong(w, dm_str_get(&b));
    if (r->budget_default)
        w_text(w, w->f == REPORT_ANSWER_TEXT ? " (default budget; set one with report --budget-ms)"
                                             : " (default budget)");
    w_text(w, ": ");
    dm_str_free(&b);
}

static void w_pick(answer__w *w, const dm_run_result *run, const recommend_result *r)
{
    if (!(r->budget > 0)) {   /* no point with both a time and an error: no scale for a budget */
        dm_str t = {0};
        dm_str_printf(&t, "no configuration has both a frame time and a quality figure (%s) against the reference: "
                      "no budget or pick (each configuration's log says why its reference or "
                      "image is missing).", report_metric_name(report_metric_of_run(run)));
        w_text(w, dm_str_get(&t));
        dm_str_free(&t);
        return;
    }
    w_budget(w, r);
    if (r->pick == RECOMMEND_NONE) {
        w_text(w, "nothing fits");
        if (r->fastest != RECOMMEND_NONE) {
            w_text(w, "; the fastest is ");
            w_config(w, run, r->fastest, 1);
        }
        w_text(w, ".");
        if (r->near_miss != RECOMMEND_NONE) {
            w_text(w, " May fit: ");
            w_config(w, run, r->near_miss, 0);
            w_text(w, ": its CI reaches under the budget.");
        }
        return;
    }
    w_text(w, "pick ");
    w_config(w, run, r->pick, 1);
    w_text(w, ".");
    if (r->near_miss != RECOMMEND_NONE) {
        w_text(w, " May also fit: ");
        w_config(w, run, r->near_miss, 0);
        w_text(w, ": clearly better quality, and its CI reaches under the budget.");
    }
    if (r->pick_ci_over)
        w_text(w, " Its CI reaches past the budget: it may not fit on a busier run.");
    if (r->pick_tie != RECOMMEND_NONE) {
        dm_str t = {0};
        report__config_label(run, &run->configs[r->pick_tie], &t);
        const dm_counter_result *a = report__frame_time(&run->configs[r->pick]);
        const dm_counter_result *b = report__frame_time(&run->configs[r->pick_tie]);
        int overlap = a && b && b->ci_lo <= a->ci_hi && a->ci_lo <= b->ci_hi;
        w_text(w, " It ties with ");
        w_text(w, dm_str_get(&t));
        w_text(w, overlap ? " (the same quality within the metric's tolerance, and the time CIs overlap), "
                            "so either will do; the lower median is named."
                          : " (the same quality within the metric's tolerance, and the medians closer "
                            "than the run's smallest resolvable difference), so either will do; the "
                            "lower median is named.");
        dm_str_free(&t);
    }
}

/* The disagreement sentence (report_answer_disagree) after a pick, if any. */
static void answer__disagree(answer__w *w, const dm_run_result *run, const char *scene)
{
    dm_str d = {0};
    if (report_answer_disagree(run, scene, &d)) {
        w_text(w, " ");
        w_text(w, dm_str_get(&d));
    }
    dm_str_free(&d);
}

static void w_item(answer__w *w, int open)
{
    static const char *const a[] = {"\n  ", "<li>", "\n- "}, *const b[] = {"", "</li>", ""};
    dm_str_cat(w->s, open ? a[w->f] : b[w->f]);
}

static void w_families(answer__w *w, const dm_run_result *run, const recommend_result *r)
{
    int first = 1;
    for (int f = RECOMMEND_FRAGMENT; f < RECOMMEND_FAMILY_COUNT; f++) {
        if (r->family_fastest[f] == RECOMMEND_NONE)
            continue;
        w_text(w, first ? "Best of each family within the budget: " : "; ");
        first = 0;
        w_strong(w, recommend_family_name((recommend_family)f));
        w_text(w, " ");
        if (r->family_best[f] != RECOMMEND_NONE) {
            w_config(w, run, r->family_best[f], 0);
            continue;
        }
        w_text(w, "none fits, the fastest is ");
        w_config(w, run, r->family_fastest[f], 0);
    }
    if (!first)
        w_text(w, ".");
}

static void w_knee(answer__w *w, const dm_run_result *run, const recommend_result *r)
{
    if (r->knee == RECOMMEND_NONE) {
        w_text(w, "Knee of the front: none (fewer than three lit front members, or no bend).");
        return;
    }
    w_text(w, "Knee of the front (beyond it, each millisecond buys less quality): ");
    w_config(w, run, r->knee, 0);
    w_text(w, ".");
}

/* A scene without a frame time: why there is no answer, then its counters. */
static void answer__untimed(answer__w *w, const dm_run_result *run, const char *scene, const char *why)
{
    dm_str s = {0};
    dm_str_printf(&s, "%c%s.", toupper((unsigned char)why[0]), why + 1);
    dm_str_cat(w->s, w->f == REPORT_ANSWER_HTML ? "<p class=\"pick\">" : "");
    w_text(w, dm_str_get(&s));
    dm_str_cat(w->s, w->f == REPORT_ANSWER_HTML ? "</p>\n" : "\n\n");
    dm_str_free(&s);
    report_counter_table(run, scene, w->f, w->s);
}

void report_answer_scene(const dm_run_result *run, const char *scene, report_answer_format f,
                         dm_str *out)
{
    answer__w w = {out, f};
    const char *why = report_untimed_reason(run, scene);
    if (why) {
        answer__untimed(&w, run, scene, why);
        return;
    }
    recommend_result r;
    report_recommend(run, scene, &r);
    dm_str_cat(out, f == REPORT_ANSWER_HTML ? "<p class=\"pick\">" : "");
    answer__provisional(&w, run, scene);
    w_pick(&w, run, &r);
    answer__disagree(&w, run, scene);
    dm_str_cat(out, f == REPORT_ANSWER_HTML ? "</p>\n<ul class=\"rec\">" : f == REPORT_ANSWER_MD ? "\n" : "");
    w_item(&w, 1);
    w_knee(&w, run, &r);
    w_item(&w, 0);
    w_item(&w, 1);
    w_families(&w, run, &r);
    w_item(&w, 0);
    if (r.lit_only && r.family_fastest[RECOMMEND_UNLIT] != RECOMMEND_NONE) {
        dm_str t = {0};
        report__config_label(run, &run->configs[r.family_fastest[RECOMMEND_UNLIT]], &t);
        w_item(&w, 1);
        w_text(&w, dm_str_get(&t));
        w_text(&w, " is unlit: a baseline in the tables and on the front, never the pick.");
        w_item(&w, 0);
        dm_str_free(&t);
    }
    dm_str_cat(out, f == REPORT_ANSWER_HTML ? "</ul>\n" : "\n");
}

/* Terminal lines are at most this many columns (issue 46: answers of
 * 305-322 characters). */
#define ANSWER__COLUMNS 100

/* Appends text to out with each of its lines word-wrapped to
 * ANSWER__COLUMNS; a wrapped line goes on four columns deeper than it
 * started (deeper than the knee's two), so a scene's answer reads as one
 * paragraph and a script can join it back. */
static void answer__wrap(const char *text, dm_str *out)
{
    while (*text) {
        const char *nl = strchr(text, '\n');
        size_t len = nl ? (size_t)(nl - text) : strlen(text), lead = 0;
        while (lead < len && text[lead] == ' ')
            lead++;
        char *line = dm_xasprintf("%.*s", (int)(len - lead), text + lead);
        char *first = dm_xasprintf("%*s", (int)lead, ""), *indent = dm_xasprintf("%*s", (int)lead + 4, "");
        if (*line)
            dm_wrap(line, first, indent, ANSWER__COLUMNS, out);
        else
            dm_str_cat(out, "\n");
        free(line);
        free(first);
        free(indent);
        text += len + (nl != NULL);
    }
}

void report_answer_terminal(const dm_run_result *run, dm_str *out)
{
    const char **scenes;
    size_t ns = report__scenes(run, &scenes);
    for (size_t i = 0; i < ns; i++) {
        dm_str one = {0};
        answer__w w = {&one, REPORT_ANSWER_TEXT};
        recommend_result r;
        report_recommend(run, scenes[i], &r);
        dm_str l = {0};
        report_scene_label(run, scenes[i], &l);
        w_text(&w, dm_str_get(&l));
        dm_str_free(&l);
        w_text(&w, ": ");
        const char *why = report_untimed_reason(run, scenes[i]);
        if (why) {
            w_text(&w, why);
            w_text(&w, ".\n");
            answer__wrap(dm_str_get(&one), out);
            dm_str_free(&one);
            report_counter_table(run, scenes[i], REPORT_ANSWER_TEXT, &one);
            dm_str_cat(out, dm_str_get(&one));
            dm_str_free(&one);
            continue;
        }
        answer__provisional(&w, run, scenes[i]);
        w_pick(&w, run, &r);
        answer__disagree(&w, run, scenes[i]);
        w_text(&w, "\n  ");
        w_knee(&w, run, &r);
        answer__wrap(dm_str_get(&one), out);
        dm_str_free(&one);
    }
    free(scenes);
}
