/* cmd_predict.c — `dmbench predict SWEEP --from RUN[,RUN...]`: each
 * configuration's Instructions, stage shares and WallTime, predicted from
 * per-variant costs fitted to measured runs (docs/models.md, "Prediction").
 *
 * The invocation counts of the new configurations are read exactly, with
 * one frame each of a statistics pass in this process (no Valgrind, no
 * timing); the costs per invocation come from the fits of run/predict.c
 * (per shader variant and stage).  A configuration of a variant the runs
 * never measured is listed with the reason, never guessed. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_table.h"
#include "reports/answer.h"
#include "reports/report.h"
#include "run/env.h"
#include "run/gl_context.h"
#include "run/inproc.h"
#include "run/predict.h"
#include "run/probe.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct predict_args {
    const char *from;
    int allow_env_mismatch;
    int json, csv;
} predict_args;

const cli_option cli_predict_options[] = {
    CLI_STRING("from", predict_args, from, "RUN[,RUN...]",
               "run directories whose configurations the models are fitted to (required)"),
    CLI_BOOL("allow-env-mismatch", predict_args, allow_env_mismatch,
             "use runs of another machine fingerprint (their instruction counts may not hold here)"),
    CLI_BOOL("json", predict_args, json,
             "print the predictions as JSON on stdout: per configuration its key, label, each predicted "
             "counter with its interval or why there is none, the model and whether it extrapolates"),
    CLI_BOOL("csv", predict_args, csv, "print the same fields as CSV on stdout, one line per configuration"),
    CLI_OPT_END
};

/* Refuses (exit 2) a run without a counter the fits need, naming it and
 * the sweep option that adds it; -1 to go on. */
static int predict__check_counters(const dm_run_result *runs, size_t n, char **dirs)
{
    for (size_t k = 0; k < n; k++) {
        const char *miss = predict_run_missing(&runs[k]);
        if (miss)
            return cli_usage_error("predict: %s has no counter '%s': add %s to measure.counters of "
                                   "its sweep and run it again (docs/models.md)", dirs[k], miss, miss);
    }
    return -1;
}

/* Refuses (exit 2) runs of another machine fingerprint, naming the keys
 * that differ (the fingerprint's keys but LP_NUM_THREADS), unless allowed;
 * -1 to go on. */
static int predict__check_env(const dm_run_result *runs, size_t n, char **dirs, int allow)
{
    dm_str err = {0}, diff = {0};
    gl_context *gl = NULL;
    dm_kv *here = NULL;
    size_t nh = 0;
    int gl_ok = gl_context_create(NULL, &gl, &err) == 0;
    env_collect(&here, &nh, gl_ok);
    gl_context_destroy(gl);
    for (size_t k = 0; k < n; k++)
        for (const char *const *key = env_fingerprint_keys(); *key; key++) {
            if (strcmp(*key, "lp_num_threads") == 0)
                continue;   /* a setting of the timed runs; the counting child always uses 0 */
            const char *a = dm_kv_get(runs[k].environment, runs[k].n_environment, *key);
            const char *b = dm_kv_get(here, nh, *key);
            if ((a || b) && (!a || !b || strcmp(a, b) != 0))
                dm_str_printf(&diff, "%s%s: %s (run %s, here %s)", diff.len ? "; " : "", dirs[k], *key,
                              a ? a : "none", b ? b : "none");
        }
    int rc = -1;
    if (diff.len && !allow)
        rc = cli_usage_error("predict: runs of another machine fingerprint: %s; their costs may not hold "
                             "here (--allow-env-mismatch uses them anyway)", dm_str_get(&diff));
    else if (diff.len)
        fprintf(stderr, "dmbench: predict: warning: machine fingerprints differ: %s\n", dm_str_get(&diff));
    dm_kv_free(here, nh);
    dm_str_free(&diff);
    dm_str_free(&err);
    return rc;
}

/* One configuration to predict: its label (the one label form), and its
 * prediction or why there is none. */
typedef struct predict__row {
    const plan_config *pc;
    char *label;
    int ok;
    predict_result r;
    dm_str why;        /* not predicted: why (never guessed) */
} predict__row;

static const char *const predict__stage_names[3] = {"geometry", "raster", "fragment"};
static const char *const predict__part_counters[3] = {"GeometryInstructions", "RasterInstructions",
                                                      "FragmentInstructions"};

/* Predicts every configuration of p; labels as report_config_label gives
 * them over the plan's configurations (the scene, then the technique and
 * the axes that vary in its scene). */
static predict__row *predict__rows(const predict_model *m, const plan *p, const double *counts)
{
    predict__row *rows = dm_xcalloc(p->n_configs + 1, sizeof *rows);
    dm_run_result shallow = { .configs = dm_xcalloc(p->n_configs + 1, sizeof *shallow.configs),
                              .n_configs = p->n_configs };
    for (size_t i = 0; i < p->n_configs; i++)
        shallow.configs[i] = (dm_config_result){ .key = p->configs[i].key, .scene = p->configs[i].scene,
                                                 .params = p->configs[i].params,
                                                 .n_params = p->configs[i].n_params, .ok = 1 };
    for (size_t i = 0; i < p->n_configs; i++) {
        predict__row *w = &rows[i];
        dm_str l = {0};
        report_config_label(&shallow, &shallow.configs[i], &l);
        w->label = dm_str_take(&l);
        w->pc = &p->configs[i];
        w->ok = predict_config(m, w->pc, counts + i * PREDICT_N_COUNTS, &w->r, &w->why) == 0;
    }
    free(shallow.configs);
    return rows;
}

static void predict__rows_free(predict__row *rows, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(rows[i].label);
        predict_result_free(&rows[i].r);
        dm_str_free(&rows[i].why);
    }
    free(rows);
}

static int predict__has_interval(double lo, double hi)
{
    return isfinite(lo) && isfinite(hi);
}

/* What every predicted row shares, said once under the table (NULL: the
 * rows differ, and each says its own). */
typedef struct predict__common {
    const char *part_why;   /* the reason for no stage shares */
    const char *instr_by;   /* where the Instructions come from */
    const char *wall_by;    /* WallTime's way, over the rows that do not override it */
    const char *calibration;/* the intervals' calibration */
    const char *blocked;    /* why held-out groups cannot calibrate a new value */
} predict__common;

/* a when b is the same text, else NULL (both may be NULL) */
static const char *predict__same(const char *a, const char *b)
{
    return a && b && strcmp(a, b) == 0 ? a : NULL;
}

/* "Instructions by X, WallTime by Y; intervals by Z", each part only where
 * the rows differ on it (a row whose WallTime way is overridden says so
 * in its own words). */
static void predict__models(const predict_result *r, const predict__common *c, dm_str *out)
{
    size_t had = out->len;
    if (!c->instr_by)
        dm_str_printf(out, "Instructions by %s", r->instr_by);
    if (r->wall_by && !r->wall_override && !c->wall_by)
        dm_str_printf(out, "%sWallTime by %s", out->len > had ? ", " : "", r->wall_by);
    if (r->calibration && !c->calibration)
        dm_str_printf(out, "%sintervals by %s", out->len > had ? "; " : "", r->calibration);
    if (out->len > had)
        dm_str_cat(out, ". ");
}

/* 1 when some predicted row's WallTime way is overridden */
static int predict__overridden(const predict__row *rows, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (rows[i].ok && rows[i].r.wall_override)
            return 1;
    return 0;
}

static void predict__common_of(const predict__row *rows, size_t n, predict__common *c)
{
    memset(c, 0, sizeof *c);
    int first = 1, first_wall = 1;
    for (size_t i = 0; i < n; i++) {
        if (!rows[i].ok)
            continue;
        const predict_result *r = &rows[i].r;
        c->part_why = first ? r->part_why : predict__same(c->part_why, r->part_why);
        c->instr_by = first ? r->instr_by : predict__same(c->instr_by, r->instr_by);
        c->calibration = first ? r->calibration : predict__same(c->calibration, r->calibration);
        c->blocked = first ? r->instr_blocked : predict__same(c->blocked, r->instr_blocked);
        first = 0;
        if (r->wall_by && !r->wall_override) {
            c->wall_by = first_wall ? r->wall_by : predict__same(c->wall_by, r->wall_by);
            first_wall = 0;
        }
    }
}

/* The note under a row: stage shares, the models used, how far beyond the
 * runs, and why a value or an interval is unavailable (what every row
 * shares is left to the line under the table). */
static void predict__note(const predict_result *r, const predict__common *c, dm_str *note)
{
    double sum = r->part[0] + r->part[1] + r->part[2];
    if (isfinite(sum) && sum > 0)
        dm_str_printf(note, "Stages: geometry %.0f %%, raster %.0f %%, fragment %.0f %%. ", 100 * r->part[0] / sum,
                      100 * r->part[1] / sum, 100 * r->part[2] / sum);
    else if (!c->part_why)
        dm_str_printf(note, "Stages unavailable: %s. ", r->part_why ? r->part_why : "no reason recorded");
    predict__models(r, c, note);
    if (r->wall_override)
        dm_str_printf(note, "WallTime by %s: %s. ", r->wall_by, r->wall_override);
    if (r->beyond_stage >= 0)
        dm_str_printf(note, "Extrapolated %.2f×: the %s part beyond the largest the runs measured. ",
                      r->beyond, predict__stage_names[r->beyond_stage]);
    if (r->calibration_why && !r->instr_why)
        dm_str_printf(note, "New axis value: %s. ", r->calibration_why);
    if (r->instr_why && c->blocked)   /* the reason is said once, under the table */
        dm_str_printf(note, "Instructions interval unavailable: %s. ", r->calibration_why);
    else if (r->instr_why)
        dm_str_printf(note, "Instructions interval unavailable: %s. ", r->instr_why);
    else if (r->instr_pooled)
        dm_str_printf(note, "Instructions interval: %s. ", r->instr_pooled);
    if (r->wall_why)
        dm_str_printf(note, "WallTime %sunavailable: %s.", r->wall_by ? "interval " : "", r->wall_why);
    while (note->len && note->buf[note->len - 1] == ' ')
        note->buf[--note->len] = '\0';
}

/* The table on stdout (the terminal): at most REPORT_TERMINAL_WIDTH
 * columns, the notes wrapped under each row; then what was not predicted. */
static void predict__print_table(const predict__row *rows, size_t n)
{
    dm_table t = {0};
    dm_table_row(&t);
    static const char *const head[] = {"key", "configuration", "Instructions", "±interval",
                                       "WallTime ms [interval]"};
    for (size_t k = 0; k < sizeof head / sizeof *head; k++)
        dm_table_cell(&t, head[k]);
    t.n_left = 2;
    predict__common common;
    predict__common_of(rows, n, &common);
    dm_str unpred = {0};
    for (size_t i = 0; i < n; i++) {
        const predict__row *w = &rows[i];
        if (!w->ok) {
            dm_str line = {0};
            dm_str_printf(&line, "%s  %s: %s", w->pc->key, w->label, dm_str_get(&w->why));
            dm_wrap(dm_str_get(&line), "  ", "      ", REPORT_TERMINAL_WIDTH, &unpred);
            dm_str_free(&line);
            continue;
        }
        const predict_result *r = &w->r;
        dm_str c = {0}, note = {0};
        dm_table_row(&t);
        dm_table_cell(&t, w->pc->key);
        dm_table_cell(&t, w->label);
        dm_str_cat_count(&c, r->instr);
        dm_table_cell(&t, dm_str_get(&c));
        c.len = 0;
        if (predict__has_interval(r->instr_lo, r->instr_hi))
            dm_str_printf(&c, "±%.1f %%", 100 * (r->instr_hi - r->instr) / r->instr);
        dm_table_cell(&t, c.len ? dm_str_get(&c) : "unavailable");
        c.len = 0;
        if (isfinite(r->wall_ns) && predict__has_interval(r->wall_lo, r->wall_hi))
            dm_str_printf(&c, "%.3f [%.3f, %.3f]", r->wall_ns / 1e6, r->wall_lo / 1e6, r->wall_hi / 1e6);
        else if (isfinite(r->wall_ns))
            dm_str_printf(&c, "%.3f [unavailable]", r->wall_ns / 1e6);
        dm_table_cell(&t, c.len ? dm_str_get(&c) : "unavailable");
        predict__note(r, &common, &note);
        dm_table_note(&t, dm_str_get(&note));
        dm_str_free(&c);
        dm_str_free(&note);
    }
    dm_str out = {0};
    if (t.n_rows > 1)
        dm_table_text(&t, "", REPORT_TERMINAL_WIDTH, &out);
    else
        dm_str_cat(&out, "no configuration could be predicted\n");
    if (t.n_rows > 1) {   /* what every row shares */
        dm_str all = {0};
        dm_str_cat(&all, "Every configuration: ");
        size_t empty = all.len;
        if (common.instr_by)
            dm_str_printf(&all, "Instructions by %s", common.instr_by);
        if (common.wall_by)
            dm_str_printf(&all, "%sWallTime by %s%s", all.len > empty ? ", " : "", common.wall_by,
                          predict__overridden(rows, n) ? " (unless its row says otherwise)" : "");
        if (common.calibration)
            dm_str_printf(&all, "%sintervals by %s", all.len > empty ? "; " : "", common.calibration);
        if (common.part_why)
            dm_str_printf(&all, "%sstage shares unavailable: %s", all.len > empty ? "; " : "", common.part_why);
        if (all.len > empty)
            dm_str_cat(&all, ".");
        if (common.blocked)
            dm_str_printf(&all, "%sNo Instructions interval at a value the runs never measured: %s.",
                          all.len > empty ? " " : "", common.blocked);
        if (all.len > empty)
            dm_wrap(dm_str_get(&all), "", "  ", REPORT_TERMINAL_WIDTH, &out);
        dm_str_free(&all);
    }
    if (unpred.len) {
        dm_str_cat(&out, "not predicted (never guessed):\n");
        dm_str_cat(&out, dm_str_get(&unpred));
    }
    char *b;
    fputs(dm_term_safe(dm_str_get(&out), &b), stdout);
    free(b);
    dm_str_free(&out);
    dm_str_free(&unpred);
    dm_table_free(&t);
}

/* {"value": v, "interval": [lo, hi] | "unavailable", "interval_reason": why, "model": by} */
static cJSON *predict__json_value(double v, double lo, double hi, const char *why, const char *by,
                                  const char *unit)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "unit", unit);
    if (!isfinite(v)) {
        cJSON_AddStringToObject(o, "unavailable", why ? why : "no reason recorded");
        return o;
    }
    cJSON_AddNumberToObject(o, "value", v);
    if (predict__has_interval(lo, hi)) {
        cJSON *iv = cJSON_AddArrayToObject(o, "interval");
        cJSON_AddItemToArray(iv, cJSON_CreateNumber(lo));
        cJSON_AddItemToArray(iv, cJSON_CreateNumber(hi));
    } else {
        cJSON_AddStringToObject(o, "interval", "unavailable");
        cJSON_AddStringToObject(o, "interval_reason", why ? why : "no reason recorded");
    }
    if (by)
        cJSON_AddStringToObject(o, "model", by);
    return o;
}

static cJSON *predict__json_row(const predict__row *w)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "key", w->pc->key);
    cJSON_AddStringToObject(o, "label", w->label);
    cJSON_AddStringToObject(o, "scene", w->pc->scene);
    cJSON *params = cJSON_AddObjectToObject(o, "params");
    for (size_t k = 0; k < w->pc->n_params; k++)
        cJSON_AddStringToObject(params, w->pc->params[k].key, w->pc->params[k].value);
    cJSON_AddStringToObject(o, "variant", w->r.variant ? w->r.variant : "");
    cJSON_AddBoolToObject(o, "predicted", w->ok);
    if (!w->ok) {
        cJSON_AddStringToObject(o, "reason", dm_str_get(&w->why));
        return o;
    }
    const predict_result *r = &w->r;
    cJSON *cs = cJSON_AddObjectToObject(o, "counters");
    cJSON *ins = predict__json_value(r->instr, r->instr_lo, r->instr_hi, r->instr_why, r->instr_by, "instructions");
    if (r->instr_pooled && !r->instr_why)
        cJSON_AddStringToObject(ins, "interval_note", r->instr_pooled);
    cJSON_AddItemToObject(cs, "Instructions", ins);
    for (int s = 0; s < 3; s++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "unit", "instructions");
        if (isfinite(r->part[s]))
            cJSON_AddNumberToObject(p, "value", r->part[s]);
        else
            cJSON_AddStringToObject(p, "unavailable", r->part_why ? r->part_why : "no reason recorded");
        cJSON_AddItemToObject(cs, predict__part_counters[s], p);
    }
    cJSON *wt = predict__json_value(r->wall_ns, r->wall_lo, r->wall_hi, r->wall_why, r->wall_by, "ns");
    if (r->wall_override)
        cJSON_AddStringToObject(wt, "model_override", r->wall_override);
    cJSON_AddItemToObject(cs, "WallTime", wt);
    if (isfinite(r->part[0] + r->part[1] + r->part[2]))
        cJSON_AddBoolToObject(o, "extrapolates", r->beyond_stage >= 0);
    else   /* how far beyond the runs is known from the stage parts alone */
        cJSON_AddNullToObject(o, "extrapolates");
    if (r->calibration)
        cJSON_AddStringToObject(o, "interval_calibration", r->calibration);
    if (r->calibration_why)
        cJSON_AddStringToObject(o, "calibration_reason", r->calibration_why);
    if (r->beyond_stage >= 0) {
        cJSON *e = cJSON_AddObjectToObject(o, "extrapolation");
        cJSON_AddStringToObject(e, "stage", predict__stage_names[r->beyond_stage]);
        cJSON_AddNumberToObject(e, "factor", r->beyond);
    }
    return o;
}

/* Each way of predicting WallTime: its held-out error, whether used, or
 * why the runs do not allow it. */
static void predict__json_ways(const predict_model *m, cJSON *root)
{
    cJSON *ways = cJSON_AddArrayToObject(root, "wall_time_ways");
    for (int w = 0; w < PREDICT_N_WAYS; w++) {
        const predict_way_score *x = &m->way[w];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "way", predict_way_names[w]);
        if (x->why)
            cJSON_AddStringToObject(o, "unavailable", x->why);
        else if (isfinite(x->cv_mape))
            cJSON_AddNumberToObject(o, "heldout_mape", x->cv_mape);
        cJSON_AddNumberToObject(o, "heldout_n", x->n);
        if (isfinite(x->q)) {
            cJSON_AddNumberToObject(o, "heldout_log_bound_90", x->q);
            cJSON_AddStringToObject(o, "heldout_bound_rule", x->q_how);
        }
        cJSON_AddBoolToObject(o, "used", m->way_used == w);
        cJSON_AddItemToArray(ways, o);
    }
}

/* How the intervals are calibrated: the held-out groups (axes, groups,
 * each response's bound or null) and the machine between runs. */
static void predict__json_calibration(const predict_model *m, cJSON *root)
{
    const predict_groups *g = &m->groups;
    cJSON *o = cJSON_AddObjectToObject(root, "interval_calibration");
    cJSON *ax = cJSON_AddObjectToObject(o, "axes");
    for (size_t a = 0; a < g->n_axes; a++)
        cJSON_AddNumberToObject(ax, g->axes[a].key, g->axes[a].n_values);
    cJSON_AddNumberToObject(o, "group_min_values", PREDICT_GROUP_VALUES);
    cJSON_AddNumberToObject(o, "groups_held_out", g->n_groups);
    const double q[2] = {g->instr_q, g->wall_q};
    const int nq[2] = {g->instr_n, g->wall_n};
    static const char *const name[2] = {"groups_instructions", "groups_wall_time"};
    for (int k = 0; k < 2; k++) {
        cJSON *x = cJSON_AddObjectToObject(o, name[k]);
        cJSON_AddNumberToObject(x, "n", nq[k]);
        if (isfinite(q[k]))
            cJSON_AddNumberToObject(x, "log_bound_90", q[k]);
        else
            cJSON_AddNullToObject(x, "log_bound_90");
    }
    cJSON *b = cJSON_AddObjectToObject(o, "between_runs");
    cJSON_AddNumberToObject(b, "log_bound_90", m->between.q);
    cJSON_AddNumberToObject(b, "configurations", m->between.n);
    cJSON_AddStringToObject(b, "source", m->between.n ? "configurations measured in two runs" : "PREDICT_RUN_SPREAD");
}

/* The JSON document on stdout: {"predictions": [...], "left_out": [...],
 * "wall_time_ways": [...], "interval_calibration": {...}}. */
static void predict__print_json(const predict_model *m, const predict__row *rows, size_t n, const char *left)
{
    cJSON *root = cJSON_CreateObject(), *a = cJSON_AddArrayToObject(root, "predictions");
    for (size_t i = 0; i < n; i++)
        cJSON_AddItemToArray(a, predict__json_row(&rows[i]));
    predict__json_ways(m, root);
    predict__json_calibration(m, root);
    cJSON *lo = cJSON_AddArrayToObject(root, "left_out");
    for (const char *p = left; p && *p;) {
        size_t len = strcspn(p, "\n");
        char *line = dm_xstrdup(p + strspn(p, " "));
        line[len - (size_t)(strspn(p, " "))] = '\0';
        cJSON_AddItemToArray(lo, cJSON_CreateString(line));
        free(line);
        p += len + (p[len] == '\n');
    }
    char *text = cJSON_Print(root);
    printf("%s\n", text);
    free(text);
    cJSON_Delete(root);
}

/* A CSV field (RFC 4180: quoted when it holds a comma, a quote or a line break). */
static void predict__csv_field(dm_str *s, const char *text, int first)
{
    if (!first)
        dm_str_cat(s, ",");
    if (!text || !text[strcspn(text, ",\"\r\n")]) {
        dm_str_cat(s, text ? text : "");
        return;
    }
    dm_str_cat(s, "\"");
    for (const char *p = text; *p; p++)
        dm_str_catn(s, *p == '"' ? "\"\"" : p, *p == '"' ? 2 : 1);
    dm_str_cat(s, "\"");
}

static void predict__csv_num(dm_str *s, double v)
{
    char buf[40] = "";
    if (isfinite(v))
        snprintf(buf, sizeof buf, "%.17g", v);
    predict__csv_field(s, buf, 0);
}

/* One line per configuration, the JSON's fields flattened. */
static void predict__print_csv(const predict__row *rows, size_t n)
{
    dm_str s = {0};
    dm_str_cat(&s, "key,label,predicted,reason,Instructions,Instructions_lo,Instructions_hi,Instructions_model,"
                   "Instructions_unavailable,GeometryInstructions,RasterInstructions,FragmentInstructions,"
                   "stages_unavailable,WallTime_ns,WallTime_lo_ns,WallTime_hi_ns,WallTime_model,"
                   "WallTime_unavailable,extrapolates,extrapolated_stage,extrapolated_factor,"
                   "interval_calibration,calibration_reason\n");
    for (size_t i = 0; i < n; i++) {
        const predict__row *w = &rows[i];
        const predict_result *r = &w->r;
        int iv = predict__has_interval(r->instr_lo, r->instr_hi), wv = predict__has_interval(r->wall_lo, r->wall_hi);
        predict__csv_field(&s, w->pc->key, 1);
        predict__csv_field(&s, w->label, 0);
        predict__csv_field(&s, w->ok ? "yes" : "no", 0);
        predict__csv_field(&s, w->ok ? "" : dm_str_get(&w->why), 0);
        predict__csv_num(&s, w->ok ? r->instr : NAN);
        predict__csv_num(&s, w->ok && iv ? r->instr_lo : NAN);
        predict__csv_num(&s, w->ok && iv ? r->instr_hi : NAN);
        predict__csv_field(&s, w->ok ? r->instr_by : "", 0);
        predict__csv_field(&s, w->ok && r->instr_why ? r->instr_why : "", 0);
        for (int k = 0; k < 3; k++)
            predict__csv_num(&s, w->ok ? r->part[k] : NAN);
        predict__csv_field(&s, w->ok && r->part_why ? r->part_why : "", 0);
        predict__csv_num(&s, w->ok ? r->wall_ns : NAN);
        predict__csv_num(&s, w->ok && wv ? r->wall_lo : NAN);
        predict__csv_num(&s, w->ok && wv ? r->wall_hi : NAN);
        predict__csv_field(&s, w->ok && r->wall_by ? r->wall_by : "", 0);
        predict__csv_field(&s, w->ok && r->wall_why ? r->wall_why : "", 0);
        int known = w->ok && isfinite(r->part[0] + r->part[1] + r->part[2]);
        predict__csv_field(&s, !w->ok ? "" : !known ? "unknown" : r->beyond_stage >= 0 ? "yes" : "no", 0);
        predict__csv_field(&s, w->ok && r->beyond_stage >= 0 ? predict__stage_names[r->beyond_stage] : "", 0);
        predict__csv_num(&s, w->ok && r->beyond_stage >= 0 ? r->beyond : NAN);
        predict__csv_field(&s, w->ok && r->calibration ? r->calibration : "", 0);
        predict__csv_field(&s, w->ok && r->calibration_why ? r->calibration_why : "", 0);
        dm_str_cat(&s, "\n");
    }
    fputs(dm_str_get(&s), stdout);
    dm_str_free(&s);
}

/* How well each variant's Instructions predicted the runs' own
 * configurations held out of the fits: the stage models' sum, and the
 * one-formula stage-instructions beside it. */
static void predict__heldout_text(const predict_model *m, dm_str *out)
{
    if (m->n_heldout)
        dm_str_cat(out, "held-out error of Instructions on the runs' configurations (k-fold CV-MAPE), per variant:\n");
    for (size_t i = 0; i < m->n_heldout; i++) {
        const predict_heldout *h = &m->heldout[i];
        const dm_fit_result *one = predict_fit_of(m->instr, m->n_instr, h->variant);
        int use_one = predict_heldout_prefers_one(m, one);
        dm_str l = {0};
        dm_wrap(h->variant, "  ", "      ", REPORT_TERMINAL_WIDTH, out);
        dm_str_cat(&l, "stages summed ");
        if (isfinite(h->cv_mape))
            dm_str_printf(&l, "%5.2f %% over %d configurations%s", h->cv_mape, h->n, use_one ? "" : " (used)");
        else
            dm_str_printf(&l, "%sunavailable: too few configurations to hold one out (%zu measured)",
                          use_one ? "" : "(used) ", predict_variant_count(m, h->variant));
        if (one && isfinite(one->cv_mape))
            dm_str_printf(&l, "; stage-instructions %5.2f %%%s", one->cv_mape, use_one ? " (used)" : "");
        dm_wrap(dm_str_get(&l), "    ", "      ", REPORT_TERMINAL_WIDTH, out);
        dm_str_free(&l);
    }
}

/* Which rule bounds a way's held-out errors (models/stats.h
 * stats_bound90), in words. */
static const char *predict__bound_rule(const predict_way_score *w)
{
    if (!w->q_how)
        return "no bound (fewer than 2)";
    return strcmp(w->q_how, "conformal") == 0 ? "the split-conformal bound"
                                              : "the normal-theory bound (fewer than 9)";
}

/* How well each way of predicting WallTime did on the runs' own
 * configurations held out of its fits, and which one is used: the lowest,
 * never one above PREDICT_MAX_HELDOUT (docs/models.md, "Prediction"). */
static void predict__time_heldout_text(const predict_model *m, dm_str *out)
{
    dm_str l = {0};
    for (int w = 0; w < PREDICT_N_WAYS; w++) {
        const predict_way_score *x = &m->way[w];
        dm_str_printf(&l, "%s%s", w ? "; " : "", w == PREDICT_WAY_STAGE_TIMES ? "stage times summed" : predict_way_names[w]);
        if (x->why)
            dm_str_printf(&l, " unavailable: %s", x->why);
        else if (!isfinite(x->cv_mape))
            dm_str_cat(&l, " unavailable (too few configurations to hold one out)");
        else
            dm_str_printf(&l, " %.2f %% over %d configurations%s", x->cv_mape, x->n,
                          m->way_used == w ? " (used)" : x->cv_mape > PREDICT_MAX_HELDOUT ? " (over 50 %: never used)" : "");
    }
    dm_str_cat(out, "held-out error of WallTime on the runs' configurations (k-fold CV-MAPE):\n");
    dm_wrap(dm_str_get(&l), "  ", "    ", REPORT_TERMINAL_WIDTH, out);
    l.len = 0;
    if (m->way_used >= 0)
        dm_str_printf(&l, "used: %s, the lowest held-out error; an interval holds %.0f %% of held-out frames "
                      "by %s of its %d held out", predict_way_names[m->way_used], 100 * PREDICT_COVERAGE,
                      predict__bound_rule(&m->way[m->way_used]), m->way[m->way_used].n);
    else if (m->way[0].why && m->way[1].why && m->way[2].why)
        dm_str_cat(&l, "WallTime not predicted: no way is available");
    else
        dm_str_printf(&l, "WallTime not predicted: no way held out within %.0f %%", PREDICT_MAX_HELDOUT);
    dm_wrap(dm_str_get(&l), "  ", "    ", REPORT_TERMINAL_WIDTH, out);
    dm_str_free(&l);
}

/* How the intervals are calibrated (docs/models.md, "Intervals"): at an
 * axis value the runs measured, by leave-one-out; at one they never did,
 * by held-out groups too (the wider), or without an Instructions interval
 * where the axis cannot be held out; and the machine between runs. */
static void predict__calibration_text(const predict_model *m, dm_str *out)
{
    const predict_groups *g = &m->groups;
    dm_str l = {0};
    dm_str_cat(out, "interval calibration (at a value the runs measured: leave-one-out; at a new one:\n"
                    "  the wider of that and held-out groups):\n");
    dm_str_cat(&l, "numeric axes the runs vary, and their values:");
    int swept = 0;
    for (size_t a = 0; a < g->n_axes; a++)
        if (g->axes[a].n_values > 1)
            dm_str_printf(&l, "%s %s %d", swept++ ? "," : "", g->axes[a].key, g->axes[a].n_values);
    if (!swept)
        dm_str_cat(&l, " none");
    dm_str_printf(&l, "; an axis of %d values or more is held out a value at a time", PREDICT_GROUP_VALUES);
    if (g->n_groups >= 2)
        dm_str_printf(&l, ": %d groups, Instructions ±%.1f %% (of %d), WallTime ±%.1f %% (of %d)", g->n_groups,
                      100 * expm1(g->instr_q), g->instr_n, 100 * expm1(g->wall_q), g->wall_n);
    else
        dm_str_printf(&l, ": %d group%s held out, too few for a bound", g->n_groups, g->n_groups == 1 ? "" : "s");
    dm_wrap(dm_str_get(&l), "  ", "    ", REPORT_TERMINAL_WIDTH, out);
    l.len = 0;
    if (m->between.n)
        dm_str_printf(&l, "the machine between runs: ±%.1f %% in every WallTime interval (%d configurations "
                      "measured in two runs, a new run against their mean)", 100 * expm1(m->between.q),
                      m->between.n);
    else
        dm_str_printf(&l, "the machine between runs: ±%.0f %% in every WallTime interval (the runs share no "
                      "configuration; compare's --run-spread default)", 100 * PREDICT_RUN_SPREAD);
    dm_wrap(dm_str_get(&l), "  ", "    ", REPORT_TERMINAL_WIDTH, out);
    dm_str_free(&l);
}

/* Loads the --from runs into *runs (n of them, dirs[] their names); -1 when
 * all loaded, else the exit code.  Each run once: a run named twice (also
 * as `latest` and its id) would weigh its points double in every fit. */
static int predict__load(const char *from, dm_run_result **runs, char ***dirs, size_t *n)
{
    dm_str err = {0};
    size_t np = 0;
    int rc = dm_split_paths(from, "predict: --from", dirs, &np, &err) ? cli_usage_error("%s", dm_str_get(&err)) : 0;
    for (size_t k = 0; rc == 0 && k < np; k++) {
        dm_run_result r = {0};
        int lrc = cli_load_run((*dirs)[k], &r, &err);
        if (lrc != 0) {
            rc = cli_error(lrc, "predict: --from %s", dm_str_get(&err));
            break;
        }
        for (size_t j = 0; rc == 0 && j < *n; j++)
            if (strcmp((*runs)[j].id, r.id) == 0)
                rc = cli_usage_error("predict: --from names run %s twice (%s and %s); name each run once",
                                     r.id, (*dirs)[j], (*dirs)[k]);
        DM_VEC_PUSH(*runs, *n, r);
    }
    for (size_t k = *n; k < np; k++)   /* dirs[] holds one name a loaded run */
        free((*dirs)[k]);
    dm_str_free(&err);
    return rc ? rc : -1;
}

int cli_predict(const cli_command *self, int argc, char **argv)
{
    predict_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
    if (rc < 0 && argc != 1)
        rc = cli_usage_error("predict: give one sweep file (the configurations to predict)");
    if (rc < 0 && a.json && a.csv)
        rc = cli_usage_error("predict: --json and --csv both given; choose one output");
    if (rc < 0 && !a.from)
        rc = cli_usage_error("predict: --from RUN[,RUN...] is required (the measured runs)");
    if (rc >= 0)
        return rc;
    sweep s = {0};
    plan p = {0};
    dm_str err = {0};
    if (sweep_load(argv[0], &s, &err) != 0 || plan_build(&s, NULL, &p, &err) != 0)
        rc = cli_usage_error("%s", dm_str_get(&err));
    int prc = rc < 0 ? probe_user_techniques(&err) : 0;   /* compiled in a child: it may crash */
    if (prc != 0)
        rc = cli_error(prc, "predict: %s", dm_str_get(&err));
    dm_run_result *runs = NULL;
    char **dirs = NULL;
    size_t nr = 0;
    rc = rc < 0 ? predict__load(a.from, &runs, &dirs, &nr) : rc;
    rc = rc < 0 ? predict__check_counters(runs, nr, dirs) : rc;
    rc = rc < 0 ? predict__check_env(runs, nr, dirs, a.allow_env_mismatch) : rc;
    double *counts = rc < 0 ? dm_xcalloc(p.n_configs * PREDICT_N_COUNTS + 1, sizeof *counts) : NULL;
    if (rc < 0 && inproc_counts(p.configs, p.n_configs, predict_counts, PREDICT_N_COUNTS, counts, &err) != 0)
        rc = cli_error(DM_ERR_GL, "predict: %s", dm_str_get(&err));
    if (rc < 0) {
        predict_model m;
        predict_fit(runs, nr, &m);
        predict__row *rows = predict__rows(&m, &p, counts);
        dm_str left = {0}, tail = {0};
        predict_left_out(runs, nr, &left);
        if (a.json) {
            predict__print_json(&m, rows, p.n_configs, dm_str_get(&left));
        } else if (a.csv) {
            predict__print_csv(rows, p.n_configs);
        } else {
            predict__print_table(rows, p.n_configs);
            if (left.len) {
                dm_str_cat(&tail, "left out of the fits (a counter they need is unavailable there):\n");
                dm_str_cat(&tail, dm_str_get(&left));
            }
            predict__heldout_text(&m, &tail);
            predict__time_heldout_text(&m, &tail);
            predict__calibration_text(&m, &tail);
            char *b;
            fputs(dm_term_safe(dm_str_get(&tail), &b), stdout);
            free(b);
        }
        dm_str_free(&left);
        dm_str_free(&tail);
        predict__rows_free(rows, p.n_configs);
        predict_free(&m);
        rc = DM_EXIT_OK;
    }
    free(counts);
    for (size_t k = 0; k < nr; k++) {
        dm_run_free(&runs[k]);
        free(dirs[k]);
    }
    free(runs);
    free(dirs);
    plan_free(&p);
    sweep_free(&s);
    dm_str_free(&err);
    return rc;
}
