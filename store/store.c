/* store.c — the results store on SQLite.
 *
 * This file maps the results model (core/dm_results.h) to rows and back,
 * one transaction per operation.  The tables, their migrations and the
 * check that a file has them are in store_schema.c; the statements in
 * store_sql.h; preparing, binding and reading them (doubles as blobs, NaN as
 * NULL) and the error messages in store_sql.c.
 *
 * Durability: WAL journal with synchronous=FULL.  A configuration takes
 * seconds to measure, so one fsync per commit costs nothing measurable, and
 * with FULL a committed configuration also survives a power loss (NORMAL
 * only survives a process crash).  Every write goes through store__tx(): one
 * BEGIN IMMEDIATE … COMMIT, rolled back on any failure.
 */
#include "store/store.h"
#include "store/store_sql.h"
#include "core/dm_error.h"

#include <sqlite3.h>

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- transactions ---------------------------------------------------------- */

/* Writes item (of the type its function names) as part of run. */
typedef int (*store__writer)(store *s, const char *run, const void *item);

/* Arguments of one store operation, for store__tx. */
typedef struct store__call {
    const char *run;
    const void *item;
    const char *text;
    void *out;
    store__writer write;   /* for store__put */
} store__call;

typedef int (*store__fn)(store *s, const store__call *c);

/* Runs fn inside one transaction (BEGIN IMMEDIATE when write): commits when
 * fn returns 0, otherwise (or when COMMIT fails) rolls back, keeping fn's
 * error message, so the database is unchanged. */
static int store__tx(store *s, int write, store__fn fn, const store__call *c)
{
    int rc = store_sql_exec(s, write ? STORE_SQL_BEGIN_WRITE : STORE_SQL_BEGIN_READ,
                         NULL, "");
    if (rc < 0)
        return rc;
    rc = fn(s, c);
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_COMMIT, NULL, "");
    if (rc < 0 && !sqlite3_get_autocommit(s->db)) {
        sqlite3_stmt *st = store_sql_query(s, STORE_SQL_ROLLBACK, NULL, "");
        if (st) {
            sqlite3_step(st);
            sqlite3_reset(st);
        }
    }
    return rc;
}

/* 0 if run exists, DM_ERR_NOTFOUND (with a message) if not. */
static int store__need_run(store *s, const char *run)
{
    long one;
    store_sql_owner o = { run, NULL, 0 };
    int rc = store_sql_scalar(s, &one, STORE_SQL_RUN_EXISTS, &o, "");
    if (rc == DM_ERR_NOTFOUND)
        return store_sql_failf(s, rc, "run '%s' is not in the store", run);
    return rc;
}

/* ---- writing (inside a transaction) ------------------------------------------ */

static int store__kv_write(store *s, enum store_sql id, const store_sql_owner *o,
                           const dm_kv *kv, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++)
        rc = store_sql_exec(s, id, o, "tt", kv[i].key, kv[i].value);
    return rc;
}

static int store__strv_write(store *s, enum store_sql id, const store_sql_owner *o,
                             char *const *v, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++)
        rc = store_sql_exec(s, id, o, "t", v[i]);
    return rc;
}

static int store__counter_write(store *s, const store_sql_owner *o,
                                const dm_counter_result *k)
{
    int rc = store_sql_exec(s, STORE_SQL_CTR_INS, o, "ttitiidi" "ddddddddd" "ii" "iddd",
        k->name, k->unit, k->available, k->unavailable_reason, k->deterministic,
        k->partial, k->value, k->has_samples,
        k->median, k->mean, k->min, k->max, k->stddev, k->mad, k->cv, k->ci_lo,
        k->ci_hi, k->n_outliers, k->n_nonfinite, k->corrected, k->corr_median,
        k->corr_ci_lo, k->corr_ci_hi);
    if (rc == 0 && k->has_samples && k->samples)
        rc = store_sql_exec(s, STORE_SQL_SMP_INS, o, "tb", k->name, k->samples,
                         k->n_samples);
    return rc;
}

static int store__config_row(store *s, const store_sql_owner *o,
                             const dm_config_result *c)
{
    const dm_quality *q = &c->quality;
    return store_sql_exec(s, STORE_SQL_CFG_INS, o, "ttttiddddddd" "lltttt" "ddddddt",
        c->scene, c->ok ? "ok" : "failed", c->reason, c->log, q->present,
        q->rmse, q->psnr, q->ssim, q->max_error, q->pct_over_threshold,
        q->silhouette_error, q->depth_rmse, q->crack_pixels,
        q->nonfinite_pixels, q->reference, c->img_render, c->img_heatmap,
        c->img_reference, q->flip, q->flip_q1, q->flip_median, q->flip_q3,
        q->flip_max, q->flip_ppd, c->img_flip);
}

/* The frame times of a configuration on a camera path and their summary
 * (the stutters' indices as a blob of doubles). */
static int store__path_write(store *s, const store_sql_owner *o, const dm_path_series *p)
{
    double *at = dm_xmalloc((p->n_stutters + 1) * sizeof *at);
    for (size_t i = 0; i < p->n_stutters; i++)
        at[i] = (double)p->stutter_at[i];
    int rc = store_sql_exec(s, STORE_SQL_PATH_INS, o, "llb" "ddddd" "bdi", (long)p->frames,
                            (long)p->replays, p->frame_ns, p->frames * p->replays, p->p50, p->p95,
                            p->p99, p->low1_ns, p->low1_fps, at, p->n_stutters, p->replay_spread,
                            p->noisy);
    free(at);
    return rc;
}

/* Replaces configuration item (a dm_config_result) of run, keeping its
 * position when it existed. */
static int store__config_write(store *s, const char *run, const void *item)
{
    const dm_config_result *c = item;
    store_sql_owner o = { run, c->key, 0 };
    if (!c->key)
        return store_sql_failf(s, DM_ERR_ARG, "configuration without a key");
    int rc = store_sql_scalar(s, &o.seq, STORE_SQL_CFG_SEQ, &o, "");
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_CFG_DEL, &o, "");
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_PART_DEL, &o, "");
    if (rc == 0)
        rc = store__config_row(s, &o, c);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_CPAR_INS, &o, c->params, c->n_params);
    for (size_t i = 0; i < c->n_counters && rc == 0; i++)
        rc = store__counter_write(s, &o, &c->counters[i]);
    if (rc == 0 && c->path.frames && c->path.frame_ns)
        rc = store__path_write(s, &o, &c->path);
    const dm_path_quality *pq = &c->path_quality;
    if (rc == 0 && (pq->present || pq->reason))
        rc = store_sql_exec(s, STORE_SQL_PQ_INS, &o, "itlldddltbb", pq->present, pq->reason,
                            pq->frames, pq->every, pq->temporal_mean, pq->temporal_p99,
                            pq->popping, pq->popping_frame, pq->img_temporal, pq->flip, pq->n,
                            pq->ssim, pq->n);
    for (size_t i = 0; i < pq->n_shots && rc == 0; i++) {
        const dm_path_shot *sh = &pq->shots[i];
        store_sql_owner so = { run, c->key, (long)i };
        rc = store_sql_exec(s, STORE_SQL_SHOT_INS, &so, "lttt", sh->frame, sh->img_test,
                            sh->img_ref, sh->img_flip);
    }
    return rc;
}

/* Appends item (a dm_left_out) to the configurations run left out. */
static int store__left_out_write(store *s, const char *run, const void *item)
{
    const dm_left_out *l = item;
    store_sql_owner o = { run, NULL, 0 };
    int rc = store_sql_scalar(s, &o.seq, STORE_SQL_LO_SEQ, &o, "");
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_LO_INS, &o, "t", l->reason);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_LOPAR_INS, &o, l->params, l->n_params);
    return rc;
}

static int store__kv_cmp(const void *a, const void *b)
{
    const dm_kv *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : strcmp(x->value ? x->value : "", y->value ? y->value : "");
}

/* A fit group's identity: its pairs sorted, "key\x1fvalue\x1e" each. */
static char *store__group_key(const dm_kv *kv, size_t n)
{
    dm_kv *sorted = dm_xmalloc((n + 1) * sizeof *sorted);
    if (n)
        memcpy(sorted, kv, n * sizeof *sorted);
    qsort(sorted, n, sizeof *sorted, store__kv_cmp);
    dm_str k = {0};
    for (size_t i = 0; i < n; i++)
        dm_str_printf(&k, "%s\x1f%s\x1e", sorted[i].key,
                      sorted[i].value ? sorted[i].value : "");
    free(sorted);
    return dm_str_take(&k);
}

static int store__fit_children(store *s, const store_sql_owner *o,
                               const dm_fit_result *f)
{
    int rc = store__kv_write(s, STORE_SQL_FGRP_INS, o, f->group, f->n_group);
    for (size_t i = 0; i < f->n_params && rc == 0; i++)
        rc = store_sql_exec(s, STORE_SQL_FPAR_INS, o, "tdd", f->params[i].name,
                         f->params[i].value, f->params[i].stderr_);
    if (rc == 0)
        rc = store__strv_write(s, STORE_SQL_FWARN_INS, o, f->warnings,
                               f->n_warnings);
    for (int i = 0; f->point_labels && i < f->n_points && rc == 0; i++)
        rc = store_sql_exec(s, STORE_SQL_FLBL_INS, o, "it", i, f->point_labels[i]);
    return rc;
}

/* Replaces the fit of the same model and group as item (a dm_fit_result),
 * keeping its position. */
static int store__fit_write(store *s, const char *run, const void *item)
{
    const dm_fit_result *f = item;
    if (!f->model || f->n_points < 0)
        return store_sql_failf(s, DM_ERR_ARG, "fit without a model name or with "
                            "a negative point count");
    size_t np = (size_t)f->n_points;
    char *gk = store__group_key(f->group, f->n_group);
    store_sql_owner o = { run, NULL, 0 };
    int rc = store_sql_scalar(s, &o.seq, STORE_SQL_FIT_SEQ, &o, "tt", f->model, gk);
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_FIT_DEL, &o, "");
    if (rc == 0)
        rc = store_sql_exec(s, STORE_SQL_FIT_INS, &o, "ttttddddiitbbd", f->model,
            gk, f->formula, f->response, f->r2, f->rmse, f->mape, f->cv_mape,
            f->n_points, f->n_excluded, f->termination, f->measured, np,
            f->predicted, np, f->condition);
    free(gk);
    if (rc == 0)
        rc = store__fit_children(s, &o, f);
    return rc;
}

/* Inserts the run row, environment and warnings; DM_ERR_EXISTS if present. */
static int store__run_write(store *s, const dm_run_result *r, const char *tag)
{
    store_sql_owner o = { r->id, NULL, 0 };
    long one;
    int rc = store_sql_scalar(s, &one, STORE_SQL_RUN_EXISTS, &o, "");
    if (rc == 0)
        return store_sql_failf(s, DM_ERR_EXISTS, "run '%s' already exists", r->id);
    if (rc != DM_ERR_NOTFOUND)
        return rc;
    rc = store_sql_exec(s, STORE_SQL_RUN_INS, &o, "ttttdtt", r->sweep, r->started,
                     r->finished, r->sweep_hash, r->gpu_time_coverage,
                     r->timer_verdict, tag);
    if (rc == 0)
        rc = store__kv_write(s, STORE_SQL_ENV_INS, &o, r->environment,
                             r->n_environment);
    if (rc == 0)
        rc = store__strv_write(s, STORE_SQL_RWARN_INS, &o, r->warnings,
                               r->n_warnings);
    return rc;
}

/* ---- reading ------------------------------------------------------------------ */

static int store__kv_read(store *s, enum store_sql id, const store_sql_owner *o,
                          dm_kv **kv, size_t *n)
{
    sqlite3_stmt *st = store_sql_query(s, id, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        dm_kv *e = dm_vec_push(kv, n, NULL, sizeof *e);
        e->key = store_sql_col_str(st, 0);
        e->value = store_sql_col_str(st, 1);
    }
    return rc;
}

static int store__strv_read(store *s, enum store_sql id, const store_sql_owner *o,
                            char ***v, size_t *n)
{
    sqlite3_stmt *st = store_sql_query(s, id, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1)
        *(char **)dm_vec_push(v, n, NULL, sizeof **v) = store_sql_col_str(st, 0);
    return rc;
}

/* Reads a query's first column as integers (the seq of left-out / fits). */
static void store__push_seq(sqlite3_stmt *st, long **seqs, size_t *n)
{
    *(long *)dm_vec_push(seqs, n, NULL, sizeof **seqs) = (long)sqlite3_column_int64(st, 0);
}

static void store__counter_cols(sqlite3_stmt *st, dm_counter_result *k)
{
    k->name = store_sql_col_str(st, 0);
    k->unit = store_sql_col_str(st, 1);
    k->available = sqlite3_column_int(st, 2);
    k->unavailable_reason = store_sql_col_str(st, 3);
    k->deterministic = sqlite3_column_int(st, 4);
    k->partial = sqlite3_column_int(st, 5);
    k->value = store_sql_col_double(st, 6);
    k->has_samples = sqlite3_column_int(st, 7);
    double *stats[] = { &k->median, &k->mean, &k->min, &k->max, &k->stddev,
                        &k->mad, &k->cv, &k->ci_lo, &k->ci_hi };
    for (int i = 0; i < 9; i++)
        *stats[i] = store_sql_col_double(st, 8 + i);
    k->n_outliers = sqlite3_column_int(st, 17);
    k->n_nonfinite = sqlite3_column_int(st, 18);
    k->corrected = sqlite3_column_int(st, 19);
    k->corr_median = store_sql_col_double(st, 20);
    k->corr_ci_lo = store_sql_col_double(st, 21);
    k->corr_ci_hi = store_sql_col_double(st, 22);
}

static int store__samples_read(store *s, const store_sql_owner *o, dm_counter_result *k)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_SMP_SEL, o, "t", k->name);
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc == 1) {
        k->samples = store_sql_col_doubles(st, 0, &k->n_samples);
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

static int store__counters_read(store *s, const store_sql_owner *o, dm_config_result *c)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_CTR_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1)
        store__counter_cols(st, dm_vec_push(&c->counters, &c->n_counters, NULL,
                                            sizeof *c->counters));
    for (size_t i = 0; i < c->n_counters && rc == 0; i++)
        if (c->counters[i].has_samples)
            rc = store__samples_read(s, o, &c->counters[i]);
    for (size_t i = 0; i < c->n_counters; i++)
        dm_counter_read_check(&c->counters[i], "the results store");
    return rc;
}

/* The frame times of configuration o.key when it is on a camera path
 * (nothing for a still one); a row whose data does not hold frames ×
 * replays values is damaged: DM_ERR_STORE. */
static int store__path_read(store *s, const store_sql_owner *o, dm_config_result *c)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_PATH_SEL, o, "");
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc != 1)
        return rc;
    size_t n = 0, ns = 0;
    dm_path_series *p = &c->path;
    p->frames = (size_t)sqlite3_column_int64(st, 0);
    p->replays = (size_t)sqlite3_column_int64(st, 1);
    p->frame_ns = store_sql_col_doubles(st, 2, &n);
    double *f[] = { &p->p50, &p->p95, &p->p99, &p->low1_ns, &p->low1_fps };
    for (int i = 0; i < 5; i++)
        *f[i] = store_sql_col_double(st, 3 + i);
    double *at = store_sql_col_doubles(st, 8, &ns);
    p->stutter_at = dm_xcalloc(ns + 1, sizeof *p->stutter_at);
    for (size_t i = 0; at && i < ns; i++)
        p->stutter_at[i] = (long)at[i];
    p->n_stutters = at ? ns : 0;
    free(at);
    p->replay_spread = store_sql_col_double(st, 9);
    p->noisy = sqlite3_column_int(st, 10);
    sqlite3_reset(st);
    if (n != c->path.frames * c->path.replays || !c->path.frames)
        return store_sql_failf(s, DM_ERR_STORE, "configuration %s: its path's frame times hold %zu "
                               "values, not %zu frames x %zu replays", o->key, n, c->path.frames,
                               c->path.replays);
    return 0;
}

static void store__config_cols(sqlite3_stmt *st, dm_config_result *c)
{
    dm_quality *q = &c->quality;
    c->key = store_sql_col_str(st, 0);
    c->scene = store_sql_col_str(st, 1);
    c->ok = sqlite3_column_text(st, 2) &&
            strcmp((const char *)sqlite3_column_text(st, 2), "ok") == 0;
    c->reason = store_sql_col_str(st, 3);
    c->log = store_sql_col_str(st, 4);
    q->present = sqlite3_column_int(st, 5);
    double *m[] = { &q->rmse, &q->psnr, &q->ssim, &q->max_error,
                    &q->pct_over_threshold, &q->silhouette_error, &q->depth_rmse };
    for (int i = 0; i < 7; i++)
        *m[i] = store_sql_col_double(st, 6 + i);
    q->crack_pixels = (long)sqlite3_column_int64(st, 13);
    q->nonfinite_pixels = (long)sqlite3_column_int64(st, 14);
    q->reference = store_sql_col_str(st, 15);
    c->img_render = store_sql_col_str(st, 16);
    c->img_heatmap = store_sql_col_str(st, 17);
    c->img_reference = store_sql_col_str(st, 18);
    double *f[] = { &q->flip, &q->flip_q1, &q->flip_median, &q->flip_q3, &q->flip_max, &q->flip_ppd };
    for (int i = 0; i < 6; i++)
        *f[i] = store_sql_col_double(st, 19 + i);
    c->img_flip = store_sql_col_str(st, 25);
}

/* The configuration's quality along its path, when it has a row. */
static int store__path_quality_read(store *s, const store_sql_owner *o, dm_path_quality *pq)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_PQ_SEL, o, "");
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc != 1)
        return rc;
    pq->present = sqlite3_column_int(st, 0);
    pq->reason = store_sql_col_str(st, 1);
    pq->frames = (long)sqlite3_column_int64(st, 2);
    pq->every = (long)sqlite3_column_int64(st, 3);
    pq->temporal_mean = store_sql_col_double(st, 4);
    pq->temporal_p99 = store_sql_col_double(st, 5);
    pq->popping = store_sql_col_double(st, 6);
    pq->popping_frame = sqlite3_column_type(st, 7) == SQLITE_NULL ? -1 : (long)sqlite3_column_int64(st, 7);
    pq->img_temporal = store_sql_col_str(st, 8);
    size_t ns = 0;
    pq->flip = store_sql_col_doubles(st, 9, &pq->n);
    pq->ssim = store_sql_col_doubles(st, 10, &ns);
    if (ns < pq->n)
        pq->n = ns;
    sqlite3_reset(st);
    st = store_sql_query(s, STORE_SQL_SHOT_SEL, o, "");
    rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        dm_path_shot *sh = dm_vec_push(&pq->shots, &pq->n_shots, NULL, sizeof *pq->shots);
        sh->frame = (long)sqlite3_column_int64(st, 0);
        sh->img_test = store_sql_col_str(st, 1);
        sh->img_ref = store_sql_col_str(st, 2);
        sh->img_flip = store_sql_col_str(st, 3);
    }
    return rc;
}

static int store__configs_read(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_CFG_SEL, &o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1)
        store__config_cols(st, dm_vec_push(&r->configs, &r->n_configs, NULL,
                                           sizeof *r->configs));
    for (size_t i = 0; i < r->n_configs && rc == 0; i++) {
        dm_config_result *c = &r->configs[i];
        o.key = c->key;
        rc = store__kv_read(s, STORE_SQL_CPAR_SEL, &o, &c->params, &c->n_params);
        if (rc == 0)
            rc = store__counters_read(s, &o, c);
        if (rc == 0)
            rc = store__path_read(s, &o, c);
        if (rc == 0)
            rc = store__path_quality_read(s, &o, &c->path_quality);
    }
    return rc;
}

static int store__left_out_read(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_LO_SEL, &o, "");
    long *seqs = NULL;
    size_t n_seqs = 0;
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        store__push_seq(st, &seqs, &n_seqs);
        dm_left_out *l = dm_vec_push(&r->left_out, &r->n_left_out, NULL, sizeof *l);
        l->reason = store_sql_col_str(st, 1);
    }
    for (size_t i = 0; i < r->n_left_out && rc == 0; i++) {
        dm_left_out *l = &r->left_out[i];
        o.seq = seqs[i];
        rc = store__kv_read(s, STORE_SQL_LOPAR_SEL, &o, &l->params, &l->n_params);
    }
    free(seqs);
    return rc;
}

static int store__fit_params_read(store *s, const store_sql_owner *o, dm_fit_result *f)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_FPAR_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        dm_fit_param *p = dm_vec_push(&f->params, &f->n_params, NULL, sizeof *p);
        p->name = store_sql_col_str(st, 0);
        p->value = store_sql_col_double(st, 1);
        p->stderr_ = store_sql_col_double(st, 2);
    }
    return rc;
}

static int store__fit_labels_read(store *s, const store_sql_owner *o, dm_fit_result *f)
{
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_FLBL_SEL, o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        long i = (long)sqlite3_column_int64(st, 0);
        if (!f->point_labels)
            f->point_labels = dm_xcalloc((size_t)f->n_points + 1, sizeof(char *));
        if (i >= 0 && i < f->n_points && !f->point_labels[i])
            f->point_labels[i] = store_sql_col_str(st, 1);
    }
    return rc;
}

/* Fills the columns of one fit row; DM_ERR_STORE when its point arrays do
 * not hold n_points values. */
static int store__fit_cols(store *s, sqlite3_stmt *st, dm_fit_result *f)
{
    size_t nm = 0, np = 0;
    f->model = store_sql_col_str(st, 1);
    f->formula = store_sql_col_str(st, 2);
    f->response = store_sql_col_str(st, 3);
    f->r2 = store_sql_col_double(st, 4);
    f->rmse = store_sql_col_double(st, 5);
    f->mape = store_sql_col_double(st, 6);
    f->cv_mape = store_sql_col_double(st, 7);
    f->n_points = sqlite3_column_int(st, 8);
    f->n_excluded = sqlite3_column_int(st, 9);
    f->termination = store_sql_col_str(st, 10);
    f->measured = store_sql_col_doubles(st, 11, &nm);
    f->predicted = store_sql_col_doubles(st, 12, &np);
    f->condition = store_sql_col_double(st, 13);
    if (f->n_points < 0 || (f->measured && nm != (size_t)f->n_points) ||
        (f->predicted && np != (size_t)f->n_points)) {
        f->n_points = 0;
        return store_sql_failf(s, DM_ERR_STORE, "fit '%s': point arrays do not "
                            "hold n_points values", f->model);
    }
    return 0;
}

static int store__fit_children_read(store *s, const store_sql_owner *o,
                                    dm_fit_result *f)
{
    int rc = store__kv_read(s, STORE_SQL_FGRP_SEL, o, &f->group, &f->n_group);
    if (rc == 0)
        rc = store__fit_params_read(s, o, f);
    if (rc == 0)
        rc = store__strv_read(s, STORE_SQL_FWARN_SEL, o, &f->warnings,
                              &f->n_warnings);
    if (rc == 0)
        rc = store__fit_labels_read(s, o, f);
    return rc;
}

static int store__fits_read(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_FIT_SEL, &o, "");
    long *seqs = NULL;
    size_t n_seqs = 0;
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        store__push_seq(st, &seqs, &n_seqs);
        if (store__fit_cols(s, st, dm_vec_push(&r->fits, &r->n_fits, NULL,
                                               sizeof *r->fits)) < 0) {
            sqlite3_reset(st);
            rc = DM_ERR_STORE;
        }
    }
    for (size_t i = 0; i < r->n_fits && rc == 0; i++) {
        o.seq = seqs[i];
        rc = store__fit_children_read(s, &o, &r->fits[i]);
    }
    free(seqs);
    return rc;
}

static int store__run_row(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_RUN_SEL, &o, "");
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc == 0)
        return store_sql_failf(s, DM_ERR_NOTFOUND, "run '%s' is not in the store",
                            r->id);
    if (rc < 0)
        return rc;
    r->sweep = store_sql_col_str(st, 0);
    r->started = store_sql_col_str(st, 1);
    r->finished = store_sql_col_str(st, 2);
    r->sweep_hash = store_sql_col_str(st, 3);
    r->gpu_time_coverage = store_sql_col_double(st, 4);
    r->timer_verdict = store_sql_col_str(st, 5);
    sqlite3_reset(st);
    return 0;
}

/* Reads everything of run r->id into r = c->out (in a read transaction). */
static int store__rounds_read(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_ROUND_SEL, &o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        dm_round *d = dm_vec_push(&r->rounds, &r->n_rounds, NULL, sizeof *d);
        d->scene = store_sql_col_str(st, 0);
        d->seq = (long)sqlite3_column_int64(st, 1);
        d->keys = store_sql_col_str(st, 2);
        d->calib_ns = store_sql_col_double(st, 3);
    }
    return rc;
}

static int store__precision_read(store *s, dm_run_result *r)
{
    store_sql_owner o = { r->id, NULL, 0 };
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_PREC_SEL, &o, "");
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && (rc = store_sql_row(s, st)) == 1) {
        dm_scene_precision *p = dm_vec_push(&r->precision, &r->n_precision, NULL, sizeof *p);
        p->scene = store_sql_col_str(st, 0);
        p->corrected = sqlite3_column_int(st, 1);
        p->reason = store_sql_col_str(st, 2);
        p->predictor = store_sql_col_str(st, 3);
        p->n_rounds = sqlite3_column_int(st, 4);
        double *f[] = { &p->machine_spread, &p->raw_noise, &p->loo_noise, &p->calib_noise, &p->resolvable };
        for (int i = 0; i < 5; i++)
            *f[i] = store_sql_col_double(st, 5 + i);
        p->reference_spread = p->half_shift = NAN;   /* between-run figures: not kept in the store */
    }
    return rc;
}

static int store__run_read(store *s, const store__call *c)
{
    dm_run_result *r = c->out;
    store_sql_owner o = { r->id, NULL, 0 };
    int rc = store__run_row(s, r);
    if (rc == 0)
        rc = store__kv_read(s, STORE_SQL_ENV_SEL, &o, &r->environment,
                            &r->n_environment);
    if (rc == 0)
        rc = store__strv_read(s, STORE_SQL_RWARN_SEL, &o, &r->warnings,
                              &r->n_warnings);
    if (rc == 0)
        rc = store__configs_read(s, r);
    if (rc == 0)
        rc = store__left_out_read(s, r);
    if (rc == 0)
        rc = store__fits_read(s, r);
    if (rc == 0)
        rc = store__rounds_read(s, r);
    if (rc == 0)
        rc = store__precision_read(s, r);
    return rc;
}

/* ---- opening ------------------------------------------------------------------ */

/* Brings the schema to STORE_SCHEMA_VERSION (store_schema_migrate); a newer
 * schema is refused. */
static int store__migrate(store *s)
{
    long found = 0;
    int rc = store_schema_migrate(s->db, &found);
    if (rc == STORE_SCHEMA_NEWER)
        return store_sql_failf(s, DM_ERR_STORE, "the results store was written by a newer dmbench "
                            "(schema version %ld; this one reads up to %d): open it with that "
                            "dmbench, or give another --out", found, STORE_SCHEMA_VERSION);
    if (rc == SQLITE_OK)
        return 0;
    rc = store_sql_fail(s, "creating the schema");
    if (!sqlite3_get_autocommit(s->db))
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return rc;
}

/* Checks that every table and column of the schema is in the file.  A table
 * dropped or a column lost (a hand edit, a partial restore, another program)
 * makes the store damaged now, at open, instead of a "run not found" or a
 * half-read run later.  0, or DM_ERR_STORE naming the first table or column
 * missing. */
static int store__verify_schema(store *s)
{
    char *table = NULL, *column = NULL;
    int rc = store_schema_missing(s->db, &table, &column);
    if (rc != SQLITE_OK)
        rc = store_sql_fail(s, "checking the schema");
    else if (column)
        rc = store_sql_failf(s, DM_ERR_STORE, "the results store is damaged: column '%s' of table "
                          "'%s' is missing; restore dmbench.sqlite from a backup, or give another "
                          "--out", column, table);
    else if (table)
        rc = store_sql_failf(s, DM_ERR_STORE, "the results store is damaged: table '%s' is missing; "
                          "restore dmbench.sqlite from a backup, or give another --out", table);
    free(table);
    free(column);
    return rc;
}

/* Opening failures caused by the path are I/O errors (the user's); a disk
 * that refuses the write (full, ulimit -f: dm_disk_errno) is DM_ERR_DISK; the
 * rest (not a database, corrupt, out of memory) are store errors. */
static int store__open_code(store *s, int rc)
{
    int prim = rc & 0xff;
    if (prim == SQLITE_FULL || (prim == SQLITE_IOERR && s->db && dm_disk_errno(sqlite3_system_errno(s->db))))
        return DM_ERR_DISK;
    return prim == SQLITE_CANTOPEN || prim == SQLITE_READONLY ||
           prim == SQLITE_PERM || prim == SQLITE_IOERR ? DM_ERR_IO : DM_ERR_STORE;
}

static int store__connect(store *s)
{
    int rc = sqlite3_open_v2(s->path, &s->db,
                             SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_busy_timeout(s->db, 5000);
    if (rc == SQLITE_OK)
        rc = sqlite3_exec(s->db, "PRAGMA foreign_keys=ON;"
                          "PRAGMA journal_mode=WAL;PRAGMA synchronous=FULL",
                          NULL, NULL, NULL);
    if (rc != SQLITE_OK) {
        int code = store__open_code(s, s->db ? sqlite3_extended_errcode(s->db) : rc);
        store_sql_fail(s, "cannot open the results store");
        return code;
    }
    rc = store__migrate(s);
    return rc ? rc : store__verify_schema(s);
}

int store_path_fits(const char *path, dm_str *err)
{
    sqlite3_vfs *vfs = sqlite3_vfs_find(NULL);
    char cwd[PATH_MAX] = "";
    size_t len = strlen(path);
    if (path[0] != '/')
        len += (getcwd(cwd, sizeof cwd) ? strlen(cwd) : 0) + 1;
    /* its rollback journal ("-journal") must fit the limit too */
    if (!vfs || len + 8 <= (size_t)vfs->mxPathname)
        return 0;
    dm_str_printf(err, "%s: the results store's path would be %zu bytes long; SQLite opens at most "
                  "%d: give a shorter --out", path, len, vfs->mxPathname - 8);
    return DM_ERR_ARG;
}

int store_open(const char *path, store **out, dm_str *err)
{
    *out = NULL;
    if (!path) {
        if (err)
            dm_str_cat(err, "results store: no path given");
        return DM_ERR_ARG;
    }
    store *s = dm_xcalloc(1, sizeof *s);
    s->path = dm_xstrdup(path);
    int rc = store__connect(s);
    if (rc < 0) {
        if (err)
            dm_str_cat(err, store_last_error(s));
        store_close(s);
        return rc;
    }
    *out = s;
    return 0;
}

int store_check(store *s, dm_str *err)
{
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(s->db, "PRAGMA quick_check(1)", -1, &st, NULL);
    int step = rc == SQLITE_OK ? sqlite3_step(st) : rc;
    const char *res = step == SQLITE_ROW ? (const char *)sqlite3_column_text(st, 0) : NULL;
    int ok = res && strcmp(res, "ok") == 0;
    if (!ok) {
        char *why = dm_xstrdup(res ? res : sqlite3_errmsg(s->db));
        for (char *p = why; *p; p++)
            *p = *p == '\n' ? ' ' : *p;
        store_sql_failf(s, DM_ERR_STORE, "the results store is damaged (%s); restore it from a "
                     "backup or give another --out", why);
        free(why);
    }
    sqlite3_finalize(st);
    if (!ok && err)
        dm_str_cat(err, store_last_error(s));
    return ok ? 0 : DM_ERR_STORE;
}

void store_close(store *s)
{
    if (!s)
        return;
    for (int i = 0; i < STORE_SQL_COUNT; i++)
        sqlite3_finalize(s->st[i]);
    sqlite3_close(s->db);
    free(s->path);
    dm_str_free(&s->err);
    free(s);
}

/* ---- public operations ---------------------------------------------------------- */

static int store__begin_fn(store *s, const store__call *c)
{
    return store__run_write(s, c->item, c->text);
}

int store_run_begin(store *s, const dm_run_result *run, const char *tag)
{
    if (!run || !run->id)
        return store_sql_failf(s, DM_ERR_ARG, "run without an id");
    store__call c = { .item = run, .text = tag };
    return store__tx(s, 1, store__begin_fn, &c);
}

static int store__put_fn(store *s, const store__call *c)
{
    int rc = store__need_run(s, c->run);
    return rc ? rc : c->write(s, c->run, c->item);
}

/* Writes item into run run_id with write, in one write transaction;
 * DM_ERR_NOTFOUND (and nothing written) when the run is not in the store. */
static int store__put(store *s, const char *run_id, const void *item, store__writer write)
{
    store__call c = { .run = run_id, .item = item, .write = write };
    return store__tx(s, 1, store__put_fn, &c);
}

static int store__warning_write(store *s, const char *run, const void *text)
{
    store_sql_owner o = { run, NULL, 0 };
    return store_sql_exec(s, STORE_SQL_RWARN_INS, &o, "t", (const char *)text);
}

int store_run_warning_put(store *s, const char *run_id, const char *text)
{
    return store__put(s, run_id, text, store__warning_write);
}

static int store__env_write(store *s, const char *run, const void *kv)
{
    store_sql_owner o = { run, NULL, 0 };
    return store__kv_write(s, STORE_SQL_ENV_INS, &o, kv, 1);
}

int store_run_env_put(store *s, const char *run_id, const char *key, const char *value)
{
    dm_kv kv = { (char *)key, (char *)value };
    return store__put(s, run_id, &kv, store__env_write);
}

int store_config_put(store *s, const char *run_id, const dm_config_result *cfg)
{
    return store__put(s, run_id, cfg, store__config_write);
}

static int store__partial_fn(store *s, const store__call *c)
{
    const store_partial *items = c->item;
    size_t n = *(const size_t *)c->out;
    int rc = store__need_run(s, c->run);
    for (size_t i = 0; rc == 0 && i < n; i++) {
        store_sql_owner o = { c->run, items[i].key, 0 };
        rc = store_sql_exec(s, STORE_SQL_PART_DEL, &o, "");
        for (size_t k = 0; rc == 0 && k < items[i].n_counters; k++)
            rc = store_sql_exec(s, STORE_SQL_PART_INS, &o, "tbl", items[i].counters[k],
                             items[i].samples[k], items[i].n_samples, items[i].sampling_ns);
    }
    return rc;
}

int store_partial_put(store *s, const char *run_id, const store_partial *items, size_t n)
{
    store__call c = { .run = run_id, .item = items, .out = &n };
    return store__tx(s, 1, store__partial_fn, &c);
}

int store_partial_get(store *s, const char *run_id, const char *key, const char *counter,
                      double **v, size_t *n, long *sampling_ns)
{
    store_sql_owner o = { run_id, key, 0 };
    *v = NULL;
    *n = 0;
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_PART_SEL, &o, "t", counter);
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc != 1)
        return rc < 0 ? rc : DM_ERR_NOTFOUND;
    *v = store_sql_col_doubles(st, 0, n);
    *sampling_ns = (long)sqlite3_column_int64(st, 1);
    sqlite3_reset(st);
    return 0;
}

static int store__round_write(store *s, const char *run, const void *item)
{
    const dm_round *d = item;
    store_sql_owner o = { run, NULL, 0 };
    return store_sql_exec(s, STORE_SQL_ROUND_INS, &o, "ttd", d->scene, d->keys, d->calib_ns);
}

int store_round_put(store *s, const char *run_id, const dm_round *r)
{
    return store__put(s, run_id, r, store__round_write);
}

static int store__precision_row(store *s, const char *run, const dm_scene_precision *p)
{
    store_sql_owner o = { run, NULL, 0 };
    return store_sql_exec(s, STORE_SQL_PREC_INS, &o, "tittiddddd", p->scene, p->corrected,
                          p->reason, p->predictor, p->n_rounds, p->machine_spread,
                          p->raw_noise, p->loo_noise, p->calib_noise, p->resolvable);
}

/* Every scene's precision row and every corrected counter of the run
 * (a dm_run_result). */
static int store__precision_write(store *s, const char *run, const void *item)
{
    const dm_run_result *r = item;
    int rc = 0;
    for (size_t i = 0; i < r->n_precision && rc == 0; i++)
        rc = store__precision_row(s, run, &r->precision[i]);
    for (size_t i = 0; i < r->n_configs && rc == 0; i++) {
        store_sql_owner o = { run, r->configs[i].key, 0 };
        for (size_t k = 0; k < r->configs[i].n_counters && rc == 0; k++) {
            const dm_counter_result *c = &r->configs[i].counters[k];
            if (c->corrected)
                rc = store_sql_exec(s, STORE_SQL_CTR_CORR, &o, "tiddd", c->name, c->corrected,
                                    c->corr_median, c->corr_ci_lo, c->corr_ci_hi);
        }
    }
    return rc;
}

int store_precision_put(store *s, const char *run_id, const dm_run_result *run)
{
    return store__put(s, run_id, run, store__precision_write);
}

int store_left_out_put(store *s, const char *run_id, const dm_left_out *l)
{
    return store__put(s, run_id, l, store__left_out_write);
}

int store_fit_put(store *s, const char *run_id, const dm_fit_result *f)
{
    return store__put(s, run_id, f, store__fit_write);
}

static int store__finish_write(store *s, const char *run, const void *iso)
{
    store_sql_owner o = { run, NULL, 0 };
    return store_sql_exec(s, STORE_SQL_RUN_FINISH, &o, "t", (const char *)iso);
}

int store_run_finish(store *s, const char *run_id, const char *finished_iso)
{
    return store__put(s, run_id, finished_iso, store__finish_write);
}

int store_config_done(store *s, const char *run_id, const char *key)
{
    long one;
    store_sql_owner o = { run_id, key, 0 };
    int rc = store_sql_scalar(s, &one, STORE_SQL_CFG_DONE, &o, "");
    return rc == 0 ? 1 : rc == DM_ERR_NOTFOUND ? 0 : rc;
}

int store_run_load(store *s, const char *run_id, dm_run_result *out)
{
    memset(out, 0, sizeof *out);
    out->id = dm_xstrdup(run_id);
    store__call c = { .run = run_id, .out = out };
    int rc = store__tx(s, 0, store__run_read, &c);
    if (rc < 0)
        dm_run_free(out);
    return rc;
}

int store_run_tag(store *s, const char *run_id, char **tag)
{
    store_sql_owner o = { run_id, NULL, 0 };
    *tag = NULL;
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_RUN_TAG, &o, "");
    int rc = st ? store_sql_row(s, st) : DM_ERR_STORE;
    if (rc == 0)
        return store_sql_failf(s, DM_ERR_NOTFOUND, "run '%s' is not in the store",
                            run_id);
    if (rc == 1) {
        *tag = store_sql_col_str(st, 0);
        sqlite3_reset(st);
        rc = 0;
    }
    return rc;
}

/* Run ids newest first, only those tagged tag unless it is NULL, at most
 * max of them; on failure *ids is NULL and *n 0. */
static int store__runs(store *s, const char *tag, size_t max, char ***ids, size_t *n)
{
    *ids = NULL;
    *n = 0;
    sqlite3_stmt *st = store_sql_query(s, STORE_SQL_RUN_LIST, NULL, "t", tag);
    int rc = st ? 1 : DM_ERR_STORE;
    while (rc == 1 && *n < max && (rc = store_sql_row(s, st)) == 1)
        *(char **)dm_vec_push(ids, n, NULL, sizeof **ids) = store_sql_col_str(st, 0);
    if (rc == 1)
        sqlite3_reset(st);
    if (rc >= 0)
        return 0;
    for (size_t i = 0; i < *n; i++)
        free((*ids)[i]);
    free(*ids);
    *ids = NULL;
    *n = 0;
    return rc;
}

int store_latest_run(store *s, const char *tag, char **id)
{
    char **ids;
    size_t n;
    *id = NULL;
    int rc = store__runs(s, tag, 1, &ids, &n);
    if (rc == 0 && n == 0)
        return store_sql_failf(s, DM_ERR_NOTFOUND, "no run%s%s in the store",
                            tag ? " tagged " : "", tag ? tag : "");
    if (rc == 0)
        *id = ids[0];
    free(ids);
    return rc;
}

int store_list_runs(store *s, char ***ids, size_t *n)
{
    return store__runs(s, NULL, (size_t)-1, ids, n);
}

/* Writes every part of the loaded run c->item, tagged c->text. */
static int store__copy_fn(store *s, const store__call *c)
{
    const dm_run_result *r = c->item;
    int rc = store__run_write(s, r, c->text);
    for (size_t i = 0; i < r->n_configs && rc == 0; i++)
        rc = store__config_write(s, r->id, &r->configs[i]);
    for (size_t i = 0; i < r->n_left_out && rc == 0; i++)
        rc = store__left_out_write(s, r->id, &r->left_out[i]);
    for (size_t i = 0; i < r->n_fits && rc == 0; i++)
        rc = store__fit_write(s, r->id, &r->fits[i]);
    for (size_t i = 0; i < r->n_rounds && rc == 0; i++)
        rc = store__round_write(s, r->id, &r->rounds[i]);
    for (size_t i = 0; i < r->n_precision && rc == 0; i++)
        rc = store__precision_row(s, r->id, &r->precision[i]);
    return rc;
}

int store_copy_run(store *dst, store *src, const char *run_id)
{
    dm_run_result r;
    char *tag = NULL;
    int rc = store_run_load(src, run_id, &r);
    if (rc == 0)
        rc = store_run_tag(src, run_id, &tag);
    if (rc < 0) {
        store_sql_failf(dst, rc, "copying run '%s': %s", run_id, store_last_error(src));
    } else {
        store__call c = { .run = run_id, .item = &r, .text = tag };
        rc = store__tx(dst, 1, store__copy_fn, &c);
    }
    free(tag);
    dm_run_free(&r);
    return rc;
}
