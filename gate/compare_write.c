/* compare_write.c — the regression gate's outputs: terminal table, Markdown,
 * JUnit XML and JSON (see compare.h). */
#include "gate/compare.h"
#include "reports/report.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_table.h"

/* The ratio and q columns of an item, as the text, Markdown and JUnit
 * outputs print them. */
typedef struct compare__cells {
    char ratio[64];   /* "1.012 [0.998, 1.025]", "1.00004 (instructions)" or "-" */
    char q[16];       /* the q-value, "-" when the item is not timed */
} compare__cells;

static compare__cells compare__item_cells(const compare_item *it)
{
    compare__cells c = { .q = "-" };
    if (it->instr)
        snprintf(c.ratio, sizeof c.ratio, "%.5f (instructions)", it->instr_new / it->instr_base);
    else if (it->timed)
        snprintf(c.ratio, sizeof c.ratio, "%.3f [%.3f, %.3f]", it->ratio, it->lo, it->hi);
    else
        snprintf(c.ratio, sizeof c.ratio, "-");
    if (it->timed)
        snprintf(c.q, sizeof c.q, "%.2g", it->q);
    return c;
}

static void compare__summary(const compare_result *r, dm_str *s)
{
    dm_str_printf(s, "%zu configuration%s: %zu REGRESSION, %zu INCONCLUSIVE, %zu IMPROVEMENT, "
                  "%zu PASS, %zu SKIPPED; %zu added, %zu removed",
                  r->n_items, r->n_items == 1 ? "" : "s", r->count[COMPARE_REGRESSION],
                  r->count[COMPARE_INCONCLUSIVE], r->count[COMPARE_IMPROVEMENT],
                  r->count[COMPARE_PASS], r->count[COMPARE_SKIPPED], r->n_added, r->n_removed);
    if (r->n_geomean)
        dm_str_printf(s, "; suite geometric-mean %s ratio %.4f over %zu", r->desc.time_counter,
                      r->geomean, r->n_geomean);
}

/* One side's machine figures: "load 0.70, WallTime/CPUTime 1.01, rounds
 * moved ±4.2 %". */
static void compare__side_text(const compare_side_state *st, dm_str *s)
{
    if (isfinite(st->load))
        dm_str_printf(s, "load %.2f, ", st->load);
    if (isfinite(st->wall_per_cpu))
        dm_str_printf(s, "WallTime/CPUTime %.2f, ", st->wall_per_cpu);
    dm_str_printf(s, "rounds moved ±%.1f%%", st->round_spread * 100);
    if (isfinite(st->cal_cpu_ns))
        dm_str_printf(s, ", calibration %.2f ms CPU", st->cal_cpu_ns / 1e6);
    if (isfinite(st->cal_draw_ns))
        dm_str_printf(s, " / %.2f ms draw", st->cal_draw_ns / 1e6);
}

/* The precision of one side, raw and blocked by round, against the target
 * (95 % CI within ±3 % for 90 % of the configurations). */
static void compare__precision_text(const char *side, const compare_side_state *st, dm_str *s)
{
    if (!st->n_timed)
        return;
    size_t best = st->n_precise_blocked > st->n_precise_raw ? st->n_precise_blocked
                                                             : st->n_precise_raw;
    dm_str_printf(s, "precision %s: median CI ±%.1f%% raw, ±%.1f%% blocked by round; within "
                  "±3%%: %zu/%zu raw, %zu/%zu blocked (target 90%%: ", side,
                  st->ci_rel_raw * 100, st->ci_rel_blocked * 100, st->n_precise_raw, st->n_timed,
                  st->n_precise_blocked, st->n_timed);
    if ((double)best >= 0.9 * (double)st->n_timed)
        dm_str_cat(s, "met)\n");
    else if (st->wall_per_cpu > 1.2)   /* CPU time is what the work took; the rest was waiting */
        dm_str_printf(s, "missed: the run had 1/%.1f of a CPU, WallTime/CPUTime %.2f: other "
                      "processes shared the cores)\n", st->wall_per_cpu, st->wall_per_cpu);
    else if (st->round_spread > 0.05)
        dm_str_printf(s, "missed: the machine's speed moved ±%.0f%% between rounds)\n",
                      st->round_spread * 100);
    else
        dm_str_cat(s, "missed: noise within rounds; take more samples)\n");
}

/* The machine checks in lines: both sides, what changed, the interval,
 * how many verdicts it held, and the precision of each side. */
static void compare__machine_text(const compare_result *r, dm_str *s)
{
    const compare_machine *m = &r->machine;
    if (!r->n_geomean)
        return;
    dm_str_cat(s, "machine: BASE ");
    compare__side_text(&m->base, s);
    dm_str_cat(s, "; NEW ");
    compare__side_text(&m->new_, s);
    dm_str_printf(s, "\nmachine: %s\n", m->reason ? m->reason : "no change seen between the runs");
    if (isfinite(m->wall_per_cal) && !r->desc.paired)
        dm_str_printf(s, "machine: %s common mode x%.3f, x%.3f once divided by the calibration "
                      "kernel's x%.3f (shown only: verdicts do not use it)\n", r->desc.time_counter,
                      m->wall_ratio, m->wall_per_cal, m->cal_ratio);
    size_t held = 0;
    for (size_t i = 0; i < r->n_items; i++)
        held += (size_t)r->items[i].machine_held;
    int widened = m->lo < 1 || m->hi > 1;
    if (r->desc.paired && !widened)
        dm_str_cat(s, "machine: paired rounds on one machine: its changes hit both sides\n");
    else if (r->desc.replicated)
        dm_str_printf(s, "machine: several separate runs per side, each one sample (its minimum "
                      "time): the between-run spread is in the CI, not assumed; the machine checks "
                      "(first runs) allow x%.3f..x%.3f, %zu verdict%s held INCONCLUSIVE by it\n",
                      m->lo, m->hi, held, held == 1 ? "" : "s");
    else if (r->desc.paired)
        dm_str_printf(s, "machine: paired rounds on one machine, but one side waited more "
                      "(WallTime moved beyond CPUTime): x%.3f..x%.3f of it is not attributed; "
                      "%zu verdict%s held INCONCLUSIVE\n", m->lo, m->hi, held,
                      held == 1 ? "" : "s");
    else
        dm_str_printf(s, "machine: between two runs the machine alone may move times by "
                      "x%.3f..x%.3f (between-run spread %.0f%%); %zu verdict%s held INCONCLUSIVE "
                      "by it (compare --paired decides them)\n", m->lo, m->hi, m->spread * 100,
                      held, held == 1 ? "" : "s");
    compare__precision_text("BASE", &m->base, s);
    compare__precision_text("NEW", &m->new_, s);
}

/* The text output's lines are at most this many columns (issue 46: lines
 * of up to 374 characters). */
#define COMPARE__COLUMNS 100

/* Writes each line of text to f word-wrapped to COMPARE__COLUMNS after
 * first (a fixed-width prefix kept as it is), the continuations indented
 * by four columns (a script joins them back on a newline and four spaces). */
static void compare__put(FILE *f, const char *first, const char *text)
{
    dm_str s = {0};
    while (*text) {
        size_t len = strcspn(text, "\n");
        char *line = dm_xasprintf("%.*s", (int)len, text);
        dm_wrap(line, first, "    ", COMPARE__COLUMNS, &s);
        free(line);
        first = "";
        text += len + (text[len] == '\n');
    }
    fputs(dm_str_get(&s), f);
    dm_str_free(&s);
}

static void compare__text_list(FILE *f, const char *title, char **list, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char *b;
        char *line = dm_xasprintf("%s: %s", title, dm_term_safe(list[i], &b));
        compare__put(f, "", line);
        free(line);
        free(b);
    }
}

void compare_write_text(const compare_result *r, FILE *f)
{
    char *b1, *b2, *b3;
    char *head = dm_xasprintf("compare BASE %s -> NEW %s (%s; instructions threshold %.2g%%, time "
                              "threshold %.1f%%, alpha %.3g%s)",
                              dm_term_safe(r->base_id ? r->base_id : "?", &b1),
                              dm_term_safe(r->new_id ? r->new_id : "?", &b2),
                              dm_term_safe(r->sweep ? r->sweep : "?", &b3),
                              r->desc.threshold * 100, r->desc.time_threshold * 100, r->desc.alpha,
                              r->desc.counters_only ? ", counters only" : "");
    compare__put(f, "", head);
    free(head);
    free(b1);
    free(b2);
    free(b3);
    fprintf(f, "%-12s  %-26s  %-8s  %-16s  %s\n", "verdict", "ratio [95% CI]", "q", "key",
            "configuration / note");
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        compare__cells cell = compare__item_cells(it);
        char *b1, *b2;
        char *cols = dm_xasprintf("%-12s  %-26s  %-8s  %-16s  ", compare_verdict_name(it->verdict),
                                  cell.ratio, cell.q, it->key);
        char *rest = dm_xasprintf("%s%s%s", dm_term_safe(it->label, &b1), it->note ? " — " : "",
                                  it->note ? dm_term_safe(it->note, &b2) : (b2 = NULL, ""));
        compare__put(f, cols, rest);
        free(cols);
        free(rest);
        free(b1);
        free(b2);
    }
    compare__text_list(f, "added", r->added, r->n_added);
    compare__text_list(f, "removed", r->removed, r->n_removed);
    compare__text_list(f, "environment", r->env_diffs, r->n_env_diffs);
    compare__text_list(f, "warning", r->warnings, r->n_warnings);
    dm_str s = {0};
    compare__machine_text(r, &s);
    compare__summary(r, &s);
    compare__put(f, "", dm_str_get(&s));
    dm_str_free(&s);
}

static int compare__write(dm_str *s, const char *path)
{
    int rc = dm_write_file(path, dm_str_get(s), s->len);   /* DM_ERR_DISK or IO, errno says why */
    dm_str_free(s);
    return rc;
}

/* Markdown text as plain text that reads the same raw and rendered: no
 * HTML entities; "->", ">=" and "<=" as arrows and signs, any other '<'
 * and the characters Markdown would act on inside a line ('|' ends a cell,
 * '*' '_' '`' '[' ']' '\' '&') escaped with a backslash, line breaks as
 * spaces, other control bytes as '?'.  A sweep name or a map path can then
 * neither break the table nor bring raw HTML into a PR comment. */
static void compare__md_cell(dm_str *s, const char *text)
{
    for (const char *p = text ? text : ""; *p; p++) {
        unsigned char ch = (unsigned char)*p;
        if (p[0] == '-' && p[1] == '>')
            dm_str_cat(s, "→"), p++;
        else if (p[0] == '>' && p[1] == '=')
            dm_str_cat(s, "≥"), p++;
        else if (p[0] == '<' && p[1] == '=')
            dm_str_cat(s, "≤"), p++;
        else if (ch == '\n' || ch == '\r' || ch == '\t')
            dm_str_cat(s, " ");
        else if (ch < 0x20 || ch == 0x7f)
            dm_str_cat(s, "?");
        else if (strchr("|*_`[]\\&<>", ch)) {
            char e[3] = {'\\', (char)ch, 0};
            dm_str_cat(s, e);
        } else
            dm_str_catn(s, p, 1);
    }
}

/* Base and New of a row, one precision per kind: a time in ms to three
 * decimals, an instruction count in plain grouped digits. */
static void compare__md_value(dm_str *s, double v, int instr)
{
    if (!(v > 0))
        dm_str_cat(s, "–");
    else if (instr) {
        dm_str_cat_count(s, v);
        dm_str_cat(s, " instr");
    } else
        dm_str_printf(s, "%.3f ms", v / 1e6);
}

/* The note of a changed row, whole (the row budget cuts rows, never words). */
static void compare__md_note(dm_str *s, const compare_item *it)
{
    if (it->machine_held) {
        dm_str_cat(s, "within what the machine may do between runs (see above)");
        return;
    }
    if (it->note)
        compare__md_cell(s, it->note);
}

/* One table row; changed rows carry verdict and note.  Ratio to four
 * decimals, the signed change in percent to two, the CI to three. */
static void compare__md_row(dm_str *s, const compare_item *it, int changed)
{
    dm_str_cat(s, "| ");
    compare__md_cell(s, it->name ? it->name : it->label);
    dm_str_cat(s, " | ");
    compare__md_value(s, it->instr ? it->instr_base : it->median_base, it->instr);
    dm_str_cat(s, " | ");
    compare__md_value(s, it->instr ? it->instr_new : it->median_new, it->instr);
    double ratio = it->instr ? it->instr_new / it->instr_base : it->timed ? it->ratio : NAN;
    if (isfinite(ratio))
        dm_str_printf(s, " | %.4f | %s%.2f %% |", ratio, ratio >= 1 ? "+" : "−", fabs(ratio - 1) * 100);
    else
        dm_str_cat(s, " | – | – |");
    if (it->timed && !it->instr)
        dm_str_printf(s, " %.3f–%.3f |", it->lo, it->hi);
    else
        dm_str_cat(s, " – |");
    if (changed) {
        dm_str_printf(s, " %s | ", compare_verdict_name(it->verdict));
        compare__md_note(s, it);
        dm_str_cat(s, " |");
    }
    dm_str_cat(s, "\n");
}

/* The load and precision lines stdout prints, as a list (nothing without
 * timing verdicts). */
static void compare__md_machine(const compare_result *r, dm_str *s)
{
    dm_str mt = {0};
    compare__machine_text(r, &mt);
    if (mt.len)
        dm_str_cat(s, "\n");
    for (const char *p = dm_str_get(&mt); *p;) {
        size_t len = strcspn(p, "\n");
        char *line = dm_xstrdup(p);
        line[len] = '\0';
        dm_str_cat(s, "- ");
        compare__md_cell(s, line);
        dm_str_cat(s, "\n");
        free(line);
        p += len + (p[len] == '\n');
    }
    dm_str_free(&mt);
}

static const char *compare__md_verdict(const compare_result *r)
{
    return r->count[COMPARE_REGRESSION] ? "REGRESSION"
           : r->count[COMPARE_INCONCLUSIVE] ? "INCONCLUSIVE" : "PASS";
}

/* Headline, settings and machine line. */
static void compare__md_head(const compare_result *r, dm_str *s)
{
    dm_str_printf(s, "## dmbench compare: %s — %zu regressed, %zu inconclusive, %zu improved, "
                  "%zu passed of %zu configurations\n\n", compare__md_verdict(r),
                  r->count[COMPARE_REGRESSION], r->count[COMPARE_INCONCLUSIVE],
                  r->count[COMPARE_IMPROVEMENT], r->count[COMPARE_PASS], r->n_items);
    dm_str_cat(s, "BASE ");
    compare__md_cell(s, r->base_id ? r->base_id : "?");
    dm_str_cat(s, " → NEW ");
    compare__md_cell(s, r->new_id ? r->new_id : "?");
    dm_str_cat(s, " · sweep ");
    compare__md_cell(s, r->sweep ? r->sweep : "?");
    if (r->n_geomean)
        dm_str_printf(s, " · geometric mean ×%.3f", r->geomean);
    dm_str_printf(s, " · thresholds: time %.1f%%, instructions %.2g%%\n",
                  r->desc.time_threshold * 100, r->desc.threshold * 100);
    size_t held = 0;
    for (size_t i = 0; i < r->n_items; i++)
        held += (size_t)r->items[i].machine_held;
    if (held) {
        dm_str_cat(s, "\n> Machine: ");
        compare__md_cell(s, r->machine.reason ? r->machine.reason : "no change seen, but one run per "
                         "side cannot tell the machine's between-run spread from the code");
        dm_str_printf(s, ". Between two runs the machine alone may move times by "
                      "×%.2f..×%.2f, so %zu timing verdict%s stay INCONCLUSIVE: run "
                      "`dmbench compare --paired BASE_BIN NEW_BIN SWEEP` to decide them.\n",
                      r->machine.lo, r->machine.hi, held, held == 1 ? "" : "s");
    }
}

/* "- added: ..." lines, at most 20 of a list. */
static void compare__md_list(dm_str *s, const char *title, char **list, size_t n)
{
    for (size_t i = 0; i < n && i < 20; i++) {
        dm_str_printf(s, "- %s: ", title);
        compare__md_cell(s, list[i]);
        dm_str_cat(s, "\n");
    }
    if (n > 20)
        dm_str_printf(s, "- … and %zu more %s\n", n - 20, title);
}

static void compare__md_tail(const compare_result *r, dm_str *s)
{
    if (r->n_added || r->n_removed)
        dm_str_cat(s, "\n");
    compare__md_list(s, "added", r->added, r->n_added);
    compare__md_list(s, "removed", r->removed, r->n_removed);
    for (size_t i = 0; i < r->n_warnings; i++) {
        dm_str_cat(s, "\n> warning: ");
        compare__md_cell(s, r->warnings[i]);
        dm_str_cat(s, "\n");
    }
}

/* Appends the rows of one kind (changed or PASS) while they fit in budget;
 * returns how many were cut. */
static size_t compare__md_rows(const compare_result *r, int changed, size_t budget, dm_str *s,
                               size_t *written)
{
    size_t cut = 0;
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        if ((it->verdict != COMPARE_PASS) != changed)
            continue;
        dm_str row = {0};
        compare__md_row(&row, it, changed);
        if (s->len + row.len <= budget) {
            dm_str_cat(s, dm_str_get(&row));
            (*written)++;
        } else
            cut++;
        dm_str_free(&row);
    }
    return cut;
}

/* The Markdown of a comparison that happened. */
static int compare__md_compared(const compare_result *r, const compare_md_desc *d, const char *path)
{
    size_t max = d->max_chars ? d->max_chars : COMPARE_MD_MAX;
    dm_str s = {0}, tail = {0};
    dm_str machine = {0};
    compare__md_head(r, &s);
    compare__md_tail(r, &tail);
    compare__md_machine(r, &machine);
    if (s.len + machine.len + tail.len + 400 <= max)   /* under a tiny limit the rows come first */
        dm_str_cat(&s, dm_str_get(&machine));
    dm_str_free(&machine);
    size_t reserve = tail.len + 400, budget = max > reserve ? max - reserve : 0, n = 0, cut = 0;
    size_t n_pass = r->count[COMPARE_PASS], n_changed = r->n_items - n_pass;
    if (n_changed) {
        dm_str_cat(&s, "\n| Configuration | Base | New | Ratio | Change | 95% CI of ratio | Verdict | Note |\n"
                       "|---|---:|---:|---:|---:|---:|---|---|\n");
        cut += compare__md_rows(r, 1, budget, &s, &n);
    } else if (r->n_items)
        dm_str_cat(&s, "\nNothing changed.\n");
    if (n_pass && !d->only_changed) {
        dm_str_printf(&s, "\n<details><summary>%zu PASS</summary>\n\n"
                          "| Configuration | Base | New | Ratio | Change | 95%% CI of ratio |\n"
                          "|---|---:|---:|---:|---:|---:|\n",
                      n_pass);
        cut += compare__md_rows(r, 0, budget, &s, &n);
        dm_str_cat(&s, "\n</details>\n");
    }
    if (cut)
        dm_str_printf(&s, "\n_%zu of %zu rows cut to stay under %zu characters (a GitHub comment "
                      "holds 65536); the full comparison is in the --json and --junit files._\n",
                      cut, cut + n, max);
    dm_str_cat(&s, dm_str_get(&tail));
    dm_str_free(&tail);
    return compare__write(&s, path);
}

/* The Markdown of a comparison that did not happen, for reason. */
static int compare__md_none(const char *reason, const compare_result *r, const char *path)
{
    dm_str s = {0};
    dm_str_cat(&s, "## dmbench compare: nothing compared\n\n");
    compare__md_cell(&s, reason ? reason : "no reason given");
    dm_str_cat(&s, "\n");
    for (size_t i = 0; r && i < r->n_env_diffs; i++) {
        dm_str_cat(&s, "- ");
        compare__md_cell(&s, r->env_diffs[i]);
        dm_str_cat(&s, "\n");
    }
    if (r && (r->n_added || r->n_removed))
        dm_str_printf(&s, "\n%zu configuration%s only in BASE, %zu only in NEW.\n", r->n_removed,
                      r->n_removed == 1 ? "" : "s", r->n_added);
    return compare__write(&s, path);
}

int compare_write_markdown(const compare_result *r, const compare_md_desc *d, const char *path)
{
    static const compare_md_desc defaults = {0};
    d = d ? d : &defaults;
    return d->none ? compare__md_none(d->reason, r, path) : compare__md_compared(r, d, path);
}

int compare_write_junit(const compare_result *r, const char *path)
{
    dm_str s = {0};
    size_t skipped = r->count[COMPARE_INCONCLUSIVE] + r->count[COMPARE_SKIPPED];
    dm_str_cat(&s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"");
    dm_str_cat_html(&s, r->sweep ? r->sweep : "dmbench");
    dm_str_printf(&s, "\" tests=\"%zu\" failures=\"%zu\" errors=\"0\" skipped=\"%zu\">\n",
                  r->n_items, r->count[COMPARE_REGRESSION], skipped);
    for (size_t i = 0; i < r->n_items; i++) {
        const compare_item *it = &r->items[i];
        compare__cells cell = compare__item_cells(it);
        dm_str_cat(&s, "  <testcase classname=\"dmbench.compare\" name=\"");
        dm_str_cat_html(&s, it->name ? it->name : it->label);   /* the one label of the report */
        dm_str_printf(&s, " [%s]\" time=\"%.9f\">\n", it->key, it->median_new / 1e9);
        const char *tag = it->verdict == COMPARE_REGRESSION ? "failure"
                          : it->verdict == COMPARE_INCONCLUSIVE || it->verdict == COMPARE_SKIPPED
                              ? "skipped" : NULL;
        if (tag) {
            dm_str_printf(&s, "    <%s message=\"%s: ", tag, compare_verdict_name(it->verdict));
            dm_str_cat_html(&s, it->note ? it->note : "");
            dm_str_printf(&s, "\"/>\n");
        }
        dm_str_printf(&s, "    <system-out>verdict=%s ratio=%s", compare_verdict_name(it->verdict), cell.ratio);
        if (it->median_new > 0)
            dm_str_printf(&s, " median_ms=%.6g", it->median_new / 1e6);
        if (it->note) {
            dm_str_cat(&s, " note=");
            dm_str_cat_html(&s, it->note);
        }
        dm_str_cat(&s, "</system-out>\n  </testcase>\n");
    }
    dm_str_cat(&s, "</testsuite>\n</testsuites>\n");
    return compare__write(&s, path);
}

/* A number, or null when not finite (JSON has no NaN/Inf). */
static void compare__json_num(cJSON *o, const char *name, double v)
{
    if (isfinite(v))
        cJSON_AddNumberToObject(o, name, v);
    else
        cJSON_AddNullToObject(o, name);
}

/* A value of BASE and NEW as the members PREFIXbase and PREFIXnew. */
static void compare__json_base_new(cJSON *o, const char *prefix, double base, double new_)
{
    char name[32];
    snprintf(name, sizeof name, "%sbase", prefix);
    compare__json_num(o, name, base);
    snprintf(name, sizeof name, "%snew", prefix);
    compare__json_num(o, name, new_);
}

static cJSON *compare__json_side(const compare_side_state *st)
{
    cJSON *o = cJSON_CreateObject();
    compare__json_num(o, "load", st->load);
    compare__json_num(o, "wall_per_cpu", st->wall_per_cpu);
    compare__json_num(o, "round_spread", st->round_spread);
    cJSON_AddNumberToObject(o, "timed", (double)st->n_timed);
    cJSON_AddNumberToObject(o, "precise_raw", (double)st->n_precise_raw);
    cJSON_AddNumberToObject(o, "precise_blocked", (double)st->n_precise_blocked);
    compare__json_num(o, "ci_rel_raw", st->ci_rel_raw);
    compare__json_num(o, "ci_rel_blocked", st->ci_rel_blocked);
    return o;
}

static void compare__json_machine(cJSON *root, const compare_machine *m)
{
    cJSON *o = cJSON_AddObjectToObject(root, "machine");
    cJSON_AddItemToObject(o, "base", compare__json_side(&m->base));
    cJSON_AddItemToObject(o, "new", compare__json_side(&m->new_));
    compare__json_num(o, "wall_ratio", m->wall_ratio);
    compare__json_num(o, "cpu_ratio", m->cpu_ratio);
    cJSON_AddBoolToObject(o, "contention", m->contention);
    cJSON_AddBoolToObject(o, "load_changed", m->load_changed);
    compare__json_num(o, "spread", m->spread);
    compare__json_num(o, "lo", m->lo);
    compare__json_num(o, "hi", m->hi);
    if (m->reason)
        cJSON_AddStringToObject(o, "reason", m->reason);
    else
        cJSON_AddNullToObject(o, "reason");
}

static cJSON *compare__json_list(char **list, size_t n)
{
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++)
        cJSON_AddItemToArray(a, cJSON_CreateString(list[i]));
    return a;
}

static cJSON *compare__json_item(const compare_item *it)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "key", it->key);
    cJSON_AddStringToObject(o, "configuration", it->label);
    cJSON_AddStringToObject(o, "verdict", compare_verdict_name(it->verdict));
    if (it->note)
        cJSON_AddStringToObject(o, "note", it->note);
    else
        cJSON_AddNullToObject(o, "note");
    if (it->timed) {
        compare__json_num(o, "ratio", it->ratio);
        cJSON *ci = cJSON_AddArrayToObject(o, "ci95");
        cJSON_AddItemToArray(ci, isfinite(it->lo) ? cJSON_CreateNumber(it->lo) : cJSON_CreateNull());
        cJSON_AddItemToArray(ci, isfinite(it->hi) ? cJSON_CreateNumber(it->hi) : cJSON_CreateNull());
        cJSON *raw = cJSON_AddArrayToObject(o, "ci95_raw");   /* not blocked by round */
        cJSON_AddItemToArray(raw, isfinite(it->lo_raw) ? cJSON_CreateNumber(it->lo_raw) : cJSON_CreateNull());
        cJSON_AddItemToArray(raw, isfinite(it->hi_raw) ? cJSON_CreateNumber(it->hi_raw) : cJSON_CreateNull());
        cJSON_AddBoolToObject(o, "blocked", it->blocked);
        cJSON_AddBoolToObject(o, "machine_held", it->machine_held);
        compare__json_num(o, "p", it->p);
        compare__json_num(o, "q", it->q);
        cJSON_AddNumberToObject(o, "n_base", (double)it->n_base);
        cJSON_AddNumberToObject(o, "n_new", (double)it->n_new);
        compare__json_num(o, "detectable", it->detectable);
    }
    if (it->instr) {
        cJSON_AddNumberToObject(o, "instructions_base", it->instr_base);
        cJSON_AddNumberToObject(o, "instructions_new", it->instr_new);
        cJSON_AddNumberToObject(o, "instructions_ratio", it->instr_new / it->instr_base);
    }
    if (it->verdict == COMPARE_INCONCLUSIVE)
        cJSON_AddNumberToObject(o, "extra_samples", (double)it->extra_samples);
    cJSON *ch = cJSON_AddArrayToObject(o, "changes");
    for (size_t k = 0; k < it->n_changes; k++) {
        cJSON *c = cJSON_CreateObject();
        cJSON_AddStringToObject(c, "counter", it->changes[k].counter);
        compare__json_base_new(c, "", it->changes[k].base, it->changes[k].new_);
        if (it->changes[k].note)
            cJSON_AddStringToObject(c, "note", it->changes[k].note);
        cJSON_AddItemToArray(ch, c);
    }
    if (it->quality) {
        cJSON *q = cJSON_AddObjectToObject(o, "quality");
        compare__json_base_new(q, "PSNR_", it->psnr_base, it->psnr_new);
        compare__json_base_new(q, "SSIM_", it->ssim_base, it->ssim_new);
        compare__json_base_new(q, "FLIP_", it->flip_base, it->flip_new);
    }
    return o;
}

int compare_write_json(const compare_result *r, const char *path)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "base", r->base_id ? r->base_id : "");
    cJSON_AddStringToObject(root, "new", r->new_id ? r->new_id : "");
    cJSON *set = cJSON_AddObjectToObject(root, "settings");
    cJSON_AddNumberToObject(set, "time_threshold", r->desc.time_threshold);
    cJSON_AddNumberToObject(set, "threshold", r->desc.threshold);
    cJSON_AddNumberToObject(set, "alpha", r->desc.alpha);
    cJSON_AddNumberToObject(set, "level", r->desc.level);
    cJSON_AddNumberToObject(set, "psnr_drop", r->desc.psnr_drop);
    cJSON_AddNumberToObject(set, "ssim_drop", r->desc.ssim_drop);
    cJSON_AddNumberToObject(set, "flip_rise", r->desc.flip_rise);
    cJSON_AddStringToObject(set, "time_counter", r->desc.time_counter);
    cJSON_AddBoolToObject(set, "counters_only", r->desc.counters_only);
    cJSON *tol = cJSON_AddObjectToObject(set, "tolerances");
    for (size_t i = 0; i < r->desc.n_tolerances; i++)
        cJSON_AddNumberToObject(tol, r->desc.tolerances[i].counter, r->desc.tolerances[i].rel);
    compare__json_num(set, "run_spread", r->desc.run_spread);
    cJSON_AddBoolToObject(set, "blocking", !r->desc.no_blocking);
    compare__json_machine(root, &r->machine);
    cJSON *sum = cJSON_AddObjectToObject(root, "summary");
    for (int v = COMPARE_PASS; v <= COMPARE_REGRESSION; v++)
        cJSON_AddNumberToObject(sum, compare_verdict_name((compare_verdict)v), (double)r->count[v]);
    compare__json_num(sum, "geomean_ratio", r->geomean);
    cJSON_AddNumberToObject(sum, "exit_code", compare_exit_code(r));
    cJSON *items = cJSON_AddArrayToObject(root, "configs");
    for (size_t i = 0; i < r->n_items; i++)
        cJSON_AddItemToArray(items, compare__json_item(&r->items[i]));
    cJSON_AddItemToObject(root, "added", compare__json_list(r->added, r->n_added));
    cJSON_AddItemToObject(root, "removed", compare__json_list(r->removed, r->n_removed));
    cJSON_AddItemToObject(root, "environment_differences", compare__json_list(r->env_diffs, r->n_env_diffs));
    cJSON_AddItemToObject(root, "warnings", compare__json_list(r->warnings, r->n_warnings));
    int rc = report_write_cjson(root, path);
    cJSON_Delete(root);
    return rc;
}
