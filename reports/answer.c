/* answer.c — the recommendation of each scene in words (see answer.h),
 * written from the report model alone: labels, times with their CIs, marks,
 * defects, the recommendation and the provisional flag are the model's. */
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

/* A writer of one format: text is escaped for it, strong is emphasised. */
typedef struct answer__w {
    dm_str *s;
    report_answer_format f;
} answer__w;

static void answer__text(answer__w *w, const char *t)
{
    if (w->f == REPORT_ANSWER_HTML)
        dm_str_cat_html(w->s, t);
    else if (w->f == REPORT_ANSWER_MD)
        dm_str_cat_md(w->s, t);
    else
        dm_str_cat(w->s, t);
}

static void answer__strong(answer__w *w, const char *t)
{
    static const char *const open[] = {"", "<b>", "**"}, *const close[] = {"", "</b>", "**"};
    dm_str_cat(w->s, open[w->f]);
    answer__text(w, t);
    dm_str_cat(w->s, close[w->f]);
}

/* A warning mark: "⚠ noisy: CI −5%/+89%" (HTML: a span with the reason as title). */
static void answer__mark(answer__w *w, const char *mark, const char *why)
{
    if (w->f == REPORT_ANSWER_HTML) {
        dm_str_cat(w->s, " <span class=\"noisy\" title=\"");
        dm_str_cat_html(w->s, why);
        dm_str_cat(w->s, "\">");
        dm_str_cat_html(w->s, mark);
        dm_str_cat(w->s, "</span>");
    } else {
        answer__text(w, " ");
        answer__text(w, mark);
    }
}

/* "Provisional: 17 of 18 timings are noisy. " before a scene's pick when
 * more than half of its timed configurations are noisy, and "Provisional:
 * with the times anywhere in their CIs the default budget could as well
 * be ..." when the times' CIs allow the
 * default budget another gap of the scene's times and so another pick (the
 * model's provisional flag): the pick may change on another run. */
static void answer__provisional(answer__w *w, const report_model *m, const report_model_scene *sc)
{
    if (!sc->provisional)
        return;
    dm_str t = {0};
    if (sc->noisy_majority)
        dm_str_printf(&t, "Provisional: %zu of %zu timings are noisy (the machine was busy)", sc->n_noisy,
                      sc->n_timed);
    const recommend_result *r = &sc->rec;
    if (r->budget_moves) {
        dm_str_printf(&t, "%s with the times anywhere in their CIs the default budget could as well be "
                      "%g ms, ", sc->noisy_majority ? ", and" : "Provisional:", r->moved_budget / 1e6);
        if (r->moved_pick == RECOMMEND_NONE)
            dm_str_cat(&t, "where nothing fits");
        else
            dm_str_printf(&t, "where the pick is %s", m->rows[r->moved_pick].label);
        dm_str_cat(&t, " (set a budget with report --budget-ms)");
    }
    answer__strong(w, dm_str_get(&t));
    answer__text(w, "; ");
    dm_str_free(&t);
}

/* "label (4.43 ms [4.33, 4.53], SSIM 0.927) ⚠ noisy: … ⚠ 128 crack pixels":
 * the row of configuration ci, its image's defects beside it (not only in
 * the warnings). */
static void answer__config(answer__w *w, const report_model *m, size_t ci, int strong)
{
    const report_model_row *r = &m->rows[ci];
    dm_str rest = {0};
    (strong ? answer__strong : answer__text)(w, r->label);
    dm_str_printf(&rest, " (%s, %s)", r->time_ci_text, r->metric_text);
    answer__text(w, dm_str_get(&rest));
    if (*r->marks)
        answer__mark(w, r->marks, r->why);
    if (*r->defects)
        answer__mark(w, r->defects, r->defects_why);
    dm_str_free(&rest);
}

/* "Under 20 ms" with how the budget was chosen. */
static void answer__budget(answer__w *w, const recommend_result *r)
{
    dm_str b = {0};
    dm_str_printf(&b, "Under %g ms", r->budget / 1e6);
    answer__strong(w, dm_str_get(&b));
    if (r->budget_default)
        answer__text(w, w->f == REPORT_ANSWER_TEXT ? " (default budget; set one with report --budget-ms)"
                                             : " (default budget)");
    answer__text(w, ": ");
    dm_str_free(&b);
}

static void answer__pick(answer__w *w, const report_model *m, const recommend_result *r)
{
    if (!(r->budget > 0)) {   /* no point with both a time and an error: no scale for a budget */
        dm_str t = {0};
        dm_str_printf(&t, "no configuration has both a frame time and a quality figure (%s) against the reference: "
                      "no budget or pick (each configuration's log says why its reference or "
                      "image is missing).", report_metric_name(m->metric));
        answer__text(w, dm_str_get(&t));
        dm_str_free(&t);
        return;
    }
    answer__budget(w, r);
    if (r->pick == RECOMMEND_NONE) {
        answer__text(w, "nothing fits");
        if (r->fastest != RECOMMEND_NONE) {
            answer__text(w, "; the fastest is ");
            answer__config(w, m, r->fastest, 1);
        }
        answer__text(w, ".");
        if (r->near_miss != RECOMMEND_NONE) {
            answer__text(w, " May fit: ");
            answer__config(w, m, r->near_miss, 0);
            answer__text(w, ": its CI reaches under the budget.");
        }
        return;
    }
    answer__text(w, "pick ");
    answer__config(w, m, r->pick, 1);
    answer__text(w, ".");
    if (r->near_miss != RECOMMEND_NONE) {
        answer__text(w, " May also fit: ");
        answer__config(w, m, r->near_miss, 0);
        answer__text(w, ": clearly better quality, and its CI reaches under the budget.");
    }
    if (r->pick_ci_over)
        answer__text(w, " Its CI reaches past the budget: it may not fit on a busier run.");
    if (r->pick_tie != RECOMMEND_NONE) {
        const dm_counter_result *a = m->rows[r->pick].frame_time, *b = m->rows[r->pick_tie].frame_time;
        int overlap = a && b && b->ci_lo <= a->ci_hi && a->ci_lo <= b->ci_hi;
        answer__text(w, " It ties with ");
        answer__text(w, m->rows[r->pick_tie].label);
        answer__text(w, overlap ? " (the same quality within the metric's tolerance, and the time CIs overlap), "
                                  "so either will do; "
                                : " (the same quality within the metric's tolerance, and the medians closer "
                                  "than the run's smallest resolvable difference), so either will do; ");
        answer__text(w, m->rows[r->pick].family != m->rows[r->pick_tie].family
                        ? "the simpler pipeline is named."
                        : "the first by configuration key is named (a choice the noise cannot move).");
    }
}

/* The disagreement sentence of the scene (report_answer_disagree, in the
 * model) after its pick, if any. */
static void answer__disagree(answer__w *w, const report_model_scene *sc)
{
    if (sc->disagree) {
        answer__text(w, " ");
        answer__text(w, sc->disagree);
    }
}

static void answer__item(answer__w *w, int open)
{
    static const char *const a[] = {"\n  ", "<li>", "\n- "}, *const b[] = {"", "</li>", ""};
    dm_str_cat(w->s, open ? a[w->f] : b[w->f]);
}

static void answer__families(answer__w *w, const report_model *m, const recommend_result *r)
{
    int first = 1;
    for (int f = RECOMMEND_FRAGMENT; f < RECOMMEND_FAMILY_COUNT; f++) {
        if (r->family_fastest[f] == RECOMMEND_NONE)
            continue;
        answer__text(w, first ? "Best of each family within the budget: " : "; ");
        first = 0;
        answer__strong(w, recommend_family_name((recommend_family)f));
        answer__text(w, " ");
        if (r->family_best[f] != RECOMMEND_NONE) {
            answer__config(w, m, r->family_best[f], 0);
            continue;
        }
        answer__text(w, "none fits, the fastest is ");
        answer__config(w, m, r->family_fastest[f], 0);
    }
    if (!first)
        answer__text(w, ".");
}

static void answer__knee(answer__w *w, const report_model *m, const recommend_result *r)
{
    if (r->knee == RECOMMEND_NONE) {
        answer__text(w, "Knee of the front: none (fewer than three lit front members, or no bend).");
        return;
    }
    answer__text(w, "Knee of the front (beyond it, each millisecond buys less quality): ");
    answer__config(w, m, r->knee, 0);
    answer__text(w, ".");
}

/* A scene without a frame time: why there is no answer, then its counters. */
static void answer__untimed(answer__w *w, const report_model *m, size_t si)
{
    const char *why = m->scenes[si].untimed;
    dm_str s = {0};
    dm_str_printf(&s, "%c%s.", toupper((unsigned char)why[0]), why + 1);
    dm_str_cat(w->s, w->f == REPORT_ANSWER_HTML ? "<p class=\"pick\">" : "");
    answer__text(w, dm_str_get(&s));
    dm_str_cat(w->s, w->f == REPORT_ANSWER_HTML ? "</p>\n" : "\n\n");
    dm_str_free(&s);
    report_counter_table(m, si, w->f, w->s);
}

/* "label (p99 6.20 ms, temporal error 0.012)": row ci on the second front. */
static void answer__motion_config(answer__w *w, const report_model *m, size_t ci, int strong)
{
    const report_model_row *r = &m->rows[ci];
    dm_str rest = {0};
    (strong ? answer__strong : answer__text)(w, r->label);
    dm_str_printf(&rest, " (p99 %.3g ms, temporal error %.3g)", r->config->path.p99 / 1e6,
                  r->config->path_quality.temporal_mean);
    answer__text(w, dm_str_get(&rest));
    dm_str_free(&rest);
}

/* In motion (docs/motion.md, "In the report"): the second front, temporal
 * error against p99 frame time, its steadiest member within the budget,
 * and whether its technique is the still pick's.  Nothing in a scene with
 * fewer than two configurations that have both figures. */
static void answer__motion(answer__w *w, const report_model *m, const report_model_scene *sc)
{
    if (sc->n_motion_points < 2)
        return;
    answer__item(w, 1);
    answer__text(w, "In motion (temporal error against p99 frame time along the path): ");
    if (sc->motion_pick == RECOMMEND_NONE) {
        dm_str t = {0};
        dm_str_printf(&t, "no configuration's p99 is under %g ms; the front, fastest first: ", sc->rec.budget / 1e6);
        answer__text(w, dm_str_get(&t));
        dm_str_free(&t);
    } else {
        dm_str t = {0};
        dm_str_printf(&t, "the steadiest with a p99 under %g ms is ", sc->rec.budget / 1e6);
        answer__text(w, dm_str_get(&t));
        dm_str_free(&t);
        answer__motion_config(w, m, sc->motion_pick, 1);
        const recommend_result *r = &sc->rec;
        if (r->pick != RECOMMEND_NONE) {
            int same = strcmp(m->rows[sc->motion_pick].technique, m->rows[r->pick].technique) == 0;
            answer__text(w, same ? ", the still pick's technique too" : ", not the still pick's technique (");
            if (!same) {
                answer__text(w, m->rows[r->pick].technique);
                answer__text(w, ")");
            }
        }
        answer__text(w, ". Front, fastest first: ");
    }
    for (size_t k = 0; k < sc->n_motion_front; k++) {
        if (k)
            answer__text(w, ", ");
        answer__motion_config(w, m, sc->motion_front[k], 0);
    }
    answer__text(w, ".");
    answer__item(w, 0);
}

void report_answer_scene(const report_model *m, size_t si, report_answer_format f, dm_str *out)
{
    answer__w w = {out, f};
    const report_model_scene *sc = &m->scenes[si];
    if (sc->untimed) {
        answer__untimed(&w, m, si);
        return;
    }
    const recommend_result *r = &sc->rec;
    dm_str_cat(out, f == REPORT_ANSWER_HTML ? "<p class=\"pick\">" : "");
    answer__provisional(&w, m, sc);
    answer__pick(&w, m, r);
    answer__disagree(&w, sc);
    dm_str_cat(out, f == REPORT_ANSWER_HTML ? "</p>\n<ul class=\"rec\">" : f == REPORT_ANSWER_MD ? "\n" : "");
    answer__item(&w, 1);
    answer__knee(&w, m, r);
    answer__item(&w, 0);
    answer__item(&w, 1);
    answer__families(&w, m, r);
    answer__item(&w, 0);
    answer__motion(&w, m, sc);
    if (r->lit_only && r->family_fastest[RECOMMEND_UNLIT] != RECOMMEND_NONE) {
        answer__item(&w, 1);
        answer__text(&w, m->rows[r->family_fastest[RECOMMEND_UNLIT]].label);
        answer__text(&w, " is unlit: a baseline in the tables and on the front, never the pick.");
        answer__item(&w, 0);
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

void report_answer_terminal_model(const report_model *m, dm_str *out)
{
    for (size_t i = 0; i < m->n_scenes; i++) {
        const report_model_scene *sc = &m->scenes[i];
        dm_str one = {0};
        answer__w w = {&one, REPORT_ANSWER_TEXT};
        answer__text(&w, sc->label);
        answer__text(&w, ": ");
        if (sc->untimed) {
            answer__text(&w, sc->untimed);
            answer__text(&w, ".\n");
            answer__wrap(dm_str_get(&one), out);
            dm_str_free(&one);
            report_counter_table(m, i, REPORT_ANSWER_TEXT, &one);
            dm_str_cat(out, dm_str_get(&one));
            dm_str_free(&one);
            continue;
        }
        answer__provisional(&w, m, sc);
        answer__pick(&w, m, &sc->rec);
        answer__disagree(&w, sc);
        answer__text(&w, "\n  ");
        answer__knee(&w, m, &sc->rec);
        answer__wrap(dm_str_get(&one), out);
        dm_str_free(&one);
    }
}
