/* Unit tests of store/: round trip of the whole results model (NaN
 * and ±Inf included), resume queries, replacement, copy between stores, run
 * listing, and the failures that could lose data: a process killed in the
 * middle of a transaction, a full disk, failing allocations, unopenable
 * paths.  Every test works on its own temporary database. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sqlite3.h>

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "store/store.h"

/* ---- fixtures ---------------------------------------------------------- */

typedef struct tmp { char dir[32]; char *db; } tmp;

static int tmp_setup(void **state)
{
    tmp *t = dm_xcalloc(1, sizeof *t);
    /* The store commits with synchronous=FULL, and the fault-injection
     * tests open and commit thousands of stores: on a disk each commit
     * waits for an fsync (the test took 27-86 s, of which ~10 s of CPU;
     * 15 s in tmpfs at load 5).  No
     * assertion here is about the disk surviving a power cut, so the
     * stores live in tmpfs where there is one; /tmp otherwise. */
    const char *base = access("/dev/shm", W_OK | X_OK) == 0 ? "/dev/shm" : "/tmp";
    snprintf(t->dir, sizeof t->dir, "%s/dmstoreXXXXXX", base);
    assert_non_null(mkdtemp(t->dir));
    t->db = dm_xasprintf("%s/results.sqlite", t->dir);
    *state = t;
    return 0;
}

static int tmp_teardown(void **state)
{
    tmp *t = *state;
    test_rm_rf(t->dir);
    free(t->db);
    free(t);
    return 0;
}

static store *open_ok(const char *path)
{
    store *s = NULL;
    dm_str err = {0};
    int rc = store_open(path, &s, &err);
    if (rc)
        fail_msg("store_open(%s) = %d: %s", path, rc, dm_str_get(&err));
    dm_str_free(&err);
    return s;
}

/* Runs a query returning one integer on the store's connection. */
static long sql_long(store *s, const char *sql)
{
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(store__db(s), sql, -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    long v = (long)sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
    return v;
}

static void assert_integrity_ok(store *s)
{
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(store__db(s), "PRAGMA integrity_check",
                                        -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    assert_string_equal((const char *)sqlite3_column_text(st, 0), "ok");
    sqlite3_finalize(st);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM pragma_foreign_key_check"), 0);
}

/* ---- synthetic results --------------------------------------------------- */

static char **strv(int n, ...)
{
    va_list ap;
    char **v = dm_xcalloc((size_t)n + 1, sizeof *v);
    va_start(ap, n);
    for (int i = 0; i < n; i++)
        v[i] = dm_xstrdup(va_arg(ap, const char *));
    va_end(ap);
    return v;
}

static double *dv(size_t n, double first, double step)
{
    double *v = dm_xmalloc(n * sizeof *v);
    for (size_t i = 0; i < n; i++)
        v[i] = first + step * (double)i;
    return v;
}

/* A counter with statistics all set to distinct values from base. */
static void counter_fill(dm_counter_result *k, const char *name, const char *unit,
                         double base)
{
    k->name = dm_xstrdup(name);
    k->unit = dm_xstrdup(unit);
    k->available = 1;
    k->value = base;
    double *stats[] = { &k->median, &k->mean, &k->min, &k->max, &k->stddev,
                        &k->mad, &k->cv, &k->ci_lo, &k->ci_hi };
    for (int i = 0; i < 9; i++)
        *stats[i] = base + 0.125 * i;
}

static void config_failed(dm_config_result *c, const char *key)
{
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup("plane/cam0/light0/brick/256x256");
    dm_kv_push(&c->params, &c->n_params, "technique", "pom");
    dm_kv_push(&c->params, &c->n_params, "steps", "32");
    c->ok = 0;
    c->reason = dm_xstrdup("shader link failed");
    c->log = dm_xstrdup("0:12(3): error: `foo' undeclared\n'quoted' \"x\"");
}

static void config_unavailable(dm_config_result *c, const char *key)
{
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup("sphere/cam0/light0/brick/256x256");
    dm_kv_push(&c->params, &c->n_params, "technique", "normal");
    c->ok = 1;
    c->n_counters = 2;
    c->counters = dm_xcalloc(2, sizeof *c->counters);
    counter_fill(&c->counters[0], "GPUTime", "ns", NAN);
    c->counters[0].available = 0;
    c->counters[0].partial = 1;
    c->counters[0].unavailable_reason = dm_xstrdup("no timer query");
    counter_fill(&c->counters[1], "TESInvocations", "items", 3169);
    c->counters[1].deterministic = 1;
}

/* ok config with n_samples raw samples (two non-finite) and quality. */
static void config_sampled(dm_config_result *c, const char *key, size_t n_samples)
{
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup("plane/cam1/light0/rock/512x512");
    dm_kv_push(&c->params, &c->n_params, "technique", "tessellation");
    dm_kv_push(&c->params, &c->n_params, "tess_level", "64");
    c->ok = 1;
    c->n_counters = 1;
    c->counters = dm_xcalloc(1, sizeof *c->counters);
    dm_counter_result *k = &c->counters[0];
    counter_fill(k, "WallTime", "ns", 1.25e6);
    k->has_samples = 1;
    k->n_samples = n_samples;
    k->samples = dv(n_samples, 1.2e6, 1234.5);
    k->samples[3] = NAN;
    k->samples[7] = INFINITY;
    k->n_outliers = 2;
    k->n_nonfinite = 2;
    k->cv = -INFINITY;
    dm_quality *q = &c->quality;
    *q = (dm_quality){ .present = 1, .rmse = 0.0, .psnr = INFINITY, .ssim = 1.0,
        .max_error = 1e-300, .pct_over_threshold = 0.5, .silhouette_error = NAN,
        .depth_rmse = 2.5e-7, .crack_pixels = 5, .nonfinite_pixels = 1L << 40,
        .flip = 0.125, .flip_q1 = 0.0625, .flip_median = 0.25, .flip_q3 = 0.5, .flip_max = 1,
        .flip_ppd = 67.0206 };
    q->reference = dm_xstrdup("reference-mesh 4x");
    c->img_render = dm_xstrdup("img/c.png");
    c->img_heatmap = dm_xstrdup("img/c-heat.png");
    c->img_reference = dm_xstrdup("img/ref.png");
    c->img_flip = dm_xstrdup("img/c-flip.png");
    /* quality along a path: a NaN in the series, no popping frame */
    dm_path_quality *pq = &c->path_quality;
    *pq = (dm_path_quality){ .present = 1, .frames = 12, .every = 4, .n = 3,
        .temporal_mean = 0.03125, .temporal_p99 = 0.5, .popping = NAN, .popping_frame = -1 };
    pq->flip = dv(3, 0.25, 0.125);
    pq->ssim = dv(3, 0.75, -0.0625);
    pq->flip[1] = NAN;
    pq->img_temporal = dm_xstrdup("img/c-temporal.png");
    /* two frames written for the filmstrip, the second without its FLIP map */
    pq->n_shots = 2;
    pq->shots = dm_xcalloc(2, sizeof *pq->shots);
    pq->shots[0] = (dm_path_shot){ 0, dm_xstrdup("img/c-path-f000.png"), dm_xstrdup("img/ref-1-f000.png"),
                                   dm_xstrdup("img/c-path-f000-flip.png") };
    pq->shots[1] = (dm_path_shot){ 8, dm_xstrdup("img/c-path-f008.png"), dm_xstrdup("img/ref-1-f008.png"),
                                   NULL };
}

/* Adds n sampled counters "C0".."C<n-1>" of n_samples each to c. */
static void add_counters(dm_config_result *c, size_t n, size_t n_samples)
{
    c->counters = dm_xrealloc(c->counters, (c->n_counters + n) * sizeof *c->counters);
    for (size_t i = 0; i < n; i++) {
        dm_counter_result *k = &c->counters[c->n_counters++];
        memset(k, 0, sizeof *k);
        char name[32];
        snprintf(name, sizeof name, "C%zu", i);
        counter_fill(k, name, "ns", (double)i);
        k->has_samples = 1;
        k->n_samples = n_samples;
        k->samples = dv(n_samples, (double)i, 0.5);
    }
}

static void fit_fill(dm_fit_result *f, double r2)
{
    f->model = dm_xstrdup("tess-power");
    f->formula = dm_xstrdup("a + b*L^p");
    f->response = dm_xstrdup("WallTime");
    dm_kv_push(&f->group, &f->n_group, "mesh", "plane");
    dm_kv_push(&f->group, &f->n_group, "material", "brick");
    f->n_params = 2;
    f->params = dm_xcalloc(2, sizeof *f->params);
    f->params[0] = (dm_fit_param){ dm_xstrdup("a"), 1.5e5, 3.0 };
    f->params[1] = (dm_fit_param){ dm_xstrdup("b"), -2.0, NAN };
    f->r2 = r2;
    f->rmse = 12.5;
    f->mape = 0.03;
    f->cv_mape = NAN;
    f->n_points = 3;
    f->n_excluded = 1;
    f->termination = dm_xstrdup("CONVERGENCE");
    f->condition = 1234.5;
    f->n_warnings = 2;
    f->warnings = strv(2, "near-collinear: b, p", "1 point excluded");
    f->measured = dv(3, 1.0, 2.0);
    f->predicted = dv(3, 1.5, 2.0);
    f->point_labels = strv(3, "k0", "k1", "k2");
}

static void left_out_fill(dm_left_out *l, const char *technique, const char *reason)
{
    dm_kv_push(&l->params, &l->n_params, "technique", technique);
    dm_kv_push(&l->params, &l->n_params, "mesh", "torus");
    l->reason = dm_xstrdup(reason);
}

static void run_fill(dm_run_result *r, const char *id, const char *started)
{
    memset(r, 0, sizeof *r);
    r->id = dm_xstrdup(id);
    r->sweep = dm_xstrdup("default");
    r->started = dm_xstrdup(started);
    r->sweep_hash = dm_xstrdup("0123456789abcdef");
    dm_kv_push(&r->environment, &r->n_environment, "renderer", "llvmpipe");
    dm_kv_push(&r->environment, &r->n_environment, "lp_num_threads", "1");
    dm_kv_push(&r->environment, &r->n_environment, "cpu", "x86 \xc3\xa9 2 cores");
    r->gpu_time_coverage = 0.01;
    r->timer_verdict = dm_xstrdup("partial");
    r->n_warnings = 1;
    r->warnings = strv(1, "GPUTime is partial on this driver");
}

/* The run of the round-trip test: 3 configs, 2 left out, 1 fit. */
static void run_full(dm_run_result *r, const char *id)
{
    run_fill(r, id, "2026-01-02T03:04:05Z");
    r->n_configs = 3;
    r->configs = dm_xcalloc(3, sizeof *r->configs);
    config_failed(&r->configs[0], "00000000000000aa");
    config_unavailable(&r->configs[1], "00000000000000bb");
    config_sampled(&r->configs[2], "00000000000000cc", 50);
    r->n_left_out = 2;
    r->left_out = dm_xcalloc(2, sizeof *r->left_out);
    left_out_fill(&r->left_out[0], "tessellation", "driver lacks feature X");
    left_out_fill(&r->left_out[1], "vt", "page size > texture");
    r->n_fits = 1;
    r->fits = dm_xcalloc(1, sizeof *r->fits);
    fit_fill(&r->fits[0], 0.99);
    /* two rounds of the sampled configuration's scene (one without a
     * calibration time), its precision, and its counter corrected */
    r->n_rounds = 2;
    r->rounds = dm_xcalloc(2, sizeof *r->rounds);
    for (long i = 0; i < 2; i++)
        r->rounds[i] = (dm_round){ .scene = dm_xstrdup(r->configs[2].scene), .seq = i,
                                   .keys = dm_xstrdup(i ? "00000000000000cc 00000000000000bb"
                                                        : "00000000000000bb 00000000000000cc"),
                                   .calib_ns = i ? NAN : 8123456.5 };
    r->n_precision = 1;
    r->precision = dm_xcalloc(1, sizeof *r->precision);
    r->precision[0] = (dm_scene_precision){ .scene = dm_xstrdup(r->configs[2].scene), .corrected = 1,
                                            .predictor = dm_xstrdup("common mode"), .n_rounds = 2,
                                            .machine_spread = 0.041, .raw_noise = 0.05, .loo_noise = 0.01,
                                            .calib_noise = NAN, .resolvable = 0.0123 };
    dm_counter_result *k = &r->configs[2].counters[0];
    k->corrected = 1;
    k->corr_median = k->median * 1.01;
    k->corr_ci_lo = k->median * 0.99;
    k->corr_ci_hi = INFINITY;
    /* its frame times along a camera path: 4 frames x 3 replays, one missing */
    dm_path_series *ps = &r->configs[2].path;
    ps->frames = 4;
    ps->replays = 3;
    ps->frame_ns = dv(12, 1.0e6, 2500.25);
    ps->frame_ns[5] = NAN;
    ps->p50 = 1.0e6;
    ps->p95 = 1.5e6;
    ps->p99 = INFINITY;
    ps->low1_ns = 2.0e6;
    ps->low1_fps = 500;
    ps->n_stutters = 2;
    ps->stutter_at = dm_xcalloc(2, sizeof *ps->stutter_at);
    ps->stutter_at[0] = 1;
    ps->stutter_at[1] = 3;
    ps->replay_spread = NAN;
    ps->noisy = -1;
}

/* Writes run r through the public calls; the run is left not finished. */
static void store_put_all(store *s, const dm_run_result *r, const char *tag)
{
    assert_int_equal(store_run_begin(s, r, tag), 0);
    for (size_t i = 0; i < r->n_configs; i++)
        assert_int_equal(store_config_put(s, r->id, &r->configs[i]), 0);
    for (size_t i = 0; i < r->n_left_out; i++)
        assert_int_equal(store_left_out_put(s, r->id, &r->left_out[i]), 0);
    for (size_t i = 0; i < r->n_fits; i++)
        assert_int_equal(store_fit_put(s, r->id, &r->fits[i]), 0);
    for (size_t i = 0; i < r->n_rounds; i++)
        assert_int_equal(store_round_put(s, r->id, &r->rounds[i]), 0);
    if (r->n_precision)
        assert_int_equal(store_precision_put(s, r->id, r), 0);
}

/* ---- field-by-field comparison --------------------------------------------- */

#define EQ_STR(a, b, what) eq_str((a), (b), (what))
static void eq_str(const char *a, const char *b, const char *what)
{
    if (!a || !b) {
        if (a != b)
            fail_msg("%s: '%s' vs '%s'", what, a ? a : "(null)", b ? b : "(null)");
        return;
    }
    if (strcmp(a, b) != 0)
        fail_msg("%s: '%s' vs '%s'", what, a, b);
}

/* Equal doubles, bit for bit (NaN equals NaN, +Inf only +Inf). */
static void eq_dbl(double a, double b, const char *what)
{
    if (memcmp(&a, &b, sizeof a) != 0 && !(isnan(a) && isnan(b)))
        fail_msg("%s: %.17g vs %.17g", what, a, b);
}

static void eq_doubles(const double *a, const double *b, size_t n, const char *what)
{
    assert_true((a == NULL) == (b == NULL));
    for (size_t i = 0; a && i < n; i++)
        eq_dbl(a[i], b[i], what);
}

static void eq_kv(const dm_kv *a, size_t na, const dm_kv *b, size_t nb)
{
    assert_int_equal(na, nb);
    for (size_t i = 0; i < na; i++) {
        EQ_STR(a[i].key, b[i].key, "kv key");
        EQ_STR(a[i].value, b[i].value, "kv value");
    }
}

static void eq_strv(char **a, size_t na, char **b, size_t nb)
{
    assert_int_equal(na, nb);
    for (size_t i = 0; i < na; i++)
        EQ_STR(a[i], b[i], "string list");
}

static void eq_counter(const dm_counter_result *a, const dm_counter_result *b)
{
    EQ_STR(a->name, b->name, "counter name");
    EQ_STR(a->unit, b->unit, "unit");
    EQ_STR(a->unavailable_reason, b->unavailable_reason, "unavailable_reason");
    assert_int_equal(a->available, b->available);
    assert_int_equal(a->deterministic, b->deterministic);
    assert_int_equal(a->partial, b->partial);
    assert_int_equal(a->has_samples, b->has_samples);
    assert_int_equal(a->n_samples, b->n_samples);
    eq_doubles(a->samples, b->samples, a->n_samples, "samples");
    const double sa[] = { a->value, a->median, a->mean, a->min, a->max,
        a->stddev, a->mad, a->cv, a->ci_lo, a->ci_hi };
    const double sb[] = { b->value, b->median, b->mean, b->min, b->max,
        b->stddev, b->mad, b->cv, b->ci_lo, b->ci_hi };
    eq_doubles(sa, sb, 10, "counter statistic");
    assert_int_equal(a->n_outliers, b->n_outliers);
    assert_int_equal(a->n_nonfinite, b->n_nonfinite);
    assert_int_equal(a->corrected, b->corrected);
    if (a->corrected) {
        const double ca[] = { a->corr_median, a->corr_ci_lo, a->corr_ci_hi };
        const double cb[] = { b->corr_median, b->corr_ci_lo, b->corr_ci_hi };
        eq_doubles(ca, cb, 3, "corrected figure");
    }
}

static void eq_quality(const dm_quality *a, const dm_quality *b)
{
    assert_int_equal(a->present, b->present);
    const double qa[] = { a->rmse, a->psnr, a->ssim, a->max_error,
        a->pct_over_threshold, a->silhouette_error, a->depth_rmse, a->flip, a->flip_q1,
        a->flip_median, a->flip_q3, a->flip_max, a->flip_ppd };
    const double qb[] = { b->rmse, b->psnr, b->ssim, b->max_error,
        b->pct_over_threshold, b->silhouette_error, b->depth_rmse, b->flip, b->flip_q1,
        b->flip_median, b->flip_q3, b->flip_max, b->flip_ppd };
    eq_doubles(qa, qb, 13, "quality");
    assert_int_equal(a->crack_pixels, b->crack_pixels);
    assert_int_equal(a->nonfinite_pixels, b->nonfinite_pixels);
    EQ_STR(a->reference, b->reference, "quality reference");
}

static void eq_config(const dm_config_result *a, const dm_config_result *b)
{
    EQ_STR(a->key, b->key, "config key");
    EQ_STR(a->scene, b->scene, "scene");
    eq_kv(a->params, a->n_params, b->params, b->n_params);
    assert_int_equal(a->ok, b->ok);
    EQ_STR(a->reason, b->reason, "reason");
    EQ_STR(a->log, b->log, "log");
    assert_int_equal(a->n_counters, b->n_counters);
    for (size_t i = 0; i < a->n_counters; i++)
        eq_counter(&a->counters[i], &b->counters[i]);
    eq_quality(&a->quality, &b->quality);
    assert_int_equal(a->path.frames, b->path.frames);
    assert_int_equal(a->path.replays, b->path.replays);
    assert_true((a->path.frame_ns == NULL) == (b->path.frame_ns == NULL));
    if (a->path.frame_ns)
        eq_doubles(a->path.frame_ns, b->path.frame_ns, a->path.frames * a->path.replays, "path frame_ns");
    const double pa[] = { a->path.p50, a->path.p95, a->path.p99, a->path.low1_ns, a->path.low1_fps,
                          a->path.replay_spread };
    const double pb[] = { b->path.p50, b->path.p95, b->path.p99, b->path.low1_ns, b->path.low1_fps,
                          b->path.replay_spread };
    eq_doubles(pa, pb, 6, "path summary");
    assert_int_equal(a->path.n_stutters, b->path.n_stutters);
    for (size_t i = 0; i < a->path.n_stutters; i++)
        assert_int_equal(a->path.stutter_at[i], b->path.stutter_at[i]);
    assert_int_equal(a->path.noisy, b->path.noisy);
    EQ_STR(a->img_render, b->img_render, "img_render");
    EQ_STR(a->img_heatmap, b->img_heatmap, "img_heatmap");
    EQ_STR(a->img_reference, b->img_reference, "img_reference");
    EQ_STR(a->img_flip, b->img_flip, "img_flip");
    const dm_path_quality *p = &a->path_quality, *q = &b->path_quality;
    assert_int_equal(p->present, q->present);
    EQ_STR(p->reason, q->reason, "path_quality reason");
    assert_int_equal(p->frames, q->frames);
    assert_int_equal(p->every, q->every);
    assert_int_equal(p->n, q->n);
    for (size_t i = 0; i < p->n; i++) {
        eq_dbl(p->flip[i], q->flip[i], "path FLIP");
        eq_dbl(p->ssim[i], q->ssim[i], "path SSIM");
    }
    eq_dbl(p->temporal_mean, q->temporal_mean, "temporal_mean");
    eq_dbl(p->temporal_p99, q->temporal_p99, "temporal_p99");
    eq_dbl(p->popping, q->popping, "popping");
    assert_int_equal(p->popping_frame, q->popping_frame);
    EQ_STR(p->img_temporal, q->img_temporal, "img_temporal");
    assert_int_equal(p->n_shots, q->n_shots);
    for (size_t i = 0; i < p->n_shots; i++) {
        assert_int_equal(p->shots[i].frame, q->shots[i].frame);
        EQ_STR(p->shots[i].img_test, q->shots[i].img_test, "shot img_test");
        EQ_STR(p->shots[i].img_ref, q->shots[i].img_ref, "shot img_ref");
        EQ_STR(p->shots[i].img_flip, q->shots[i].img_flip, "shot img_flip");
    }
}

static void eq_fit(const dm_fit_result *a, const dm_fit_result *b)
{
    EQ_STR(a->model, b->model, "model");
    EQ_STR(a->formula, b->formula, "formula");
    EQ_STR(a->response, b->response, "response");
    eq_kv(a->group, a->n_group, b->group, b->n_group);
    assert_int_equal(a->n_params, b->n_params);
    for (size_t i = 0; i < a->n_params; i++) {
        EQ_STR(a->params[i].name, b->params[i].name, "fit param");
        eq_dbl(a->params[i].value, b->params[i].value, "fit value");
        eq_dbl(a->params[i].stderr_, b->params[i].stderr_, "fit stderr");
    }
    const double fa[] = { a->r2, a->rmse, a->mape, a->cv_mape, a->condition };
    const double fb[] = { b->r2, b->rmse, b->mape, b->cv_mape, b->condition };
    eq_doubles(fa, fb, 5, "fit metric");
    assert_int_equal(a->n_points, b->n_points);
    assert_int_equal(a->n_excluded, b->n_excluded);
    EQ_STR(a->termination, b->termination, "termination");
    eq_strv(a->warnings, a->n_warnings, b->warnings, b->n_warnings);
    eq_doubles(a->measured, b->measured, (size_t)a->n_points, "measured");
    eq_doubles(a->predicted, b->predicted, (size_t)a->n_points, "predicted");
    assert_true((a->point_labels == NULL) == (b->point_labels == NULL));
    if (a->point_labels)
        eq_strv(a->point_labels, (size_t)a->n_points, b->point_labels,
                (size_t)b->n_points);
}

static void eq_run(const dm_run_result *a, const dm_run_result *b)
{
    EQ_STR(a->id, b->id, "id");
    EQ_STR(a->sweep, b->sweep, "sweep");
    EQ_STR(a->started, b->started, "started");
    EQ_STR(a->finished, b->finished, "finished");
    EQ_STR(a->sweep_hash, b->sweep_hash, "sweep_hash");
    eq_kv(a->environment, a->n_environment, b->environment, b->n_environment);
    eq_dbl(a->gpu_time_coverage, b->gpu_time_coverage, "coverage");
    EQ_STR(a->timer_verdict, b->timer_verdict, "timer_verdict");
    assert_int_equal(a->n_configs, b->n_configs);
    for (size_t i = 0; i < a->n_configs; i++)
        eq_config(&a->configs[i], &b->configs[i]);
    assert_int_equal(a->n_left_out, b->n_left_out);
    for (size_t i = 0; i < a->n_left_out; i++) {
        eq_kv(a->left_out[i].params, a->left_out[i].n_params,
              b->left_out[i].params, b->left_out[i].n_params);
        EQ_STR(a->left_out[i].reason, b->left_out[i].reason, "left_out reason");
    }
    assert_int_equal(a->n_fits, b->n_fits);
    for (size_t i = 0; i < a->n_fits; i++)
        eq_fit(&a->fits[i], &b->fits[i]);
    eq_strv(a->warnings, a->n_warnings, b->warnings, b->n_warnings);
    assert_int_equal(a->n_rounds, b->n_rounds);
    for (size_t i = 0; i < a->n_rounds; i++) {
        EQ_STR(a->rounds[i].scene, b->rounds[i].scene, "round scene");
        EQ_STR(a->rounds[i].keys, b->rounds[i].keys, "round keys");
        assert_int_equal(a->rounds[i].seq, b->rounds[i].seq);
        eq_dbl(a->rounds[i].calib_ns, b->rounds[i].calib_ns, "round calibration");
    }
    assert_int_equal(a->n_precision, b->n_precision);
    for (size_t i = 0; i < a->n_precision; i++) {
        const dm_scene_precision *p = &a->precision[i], *q = &b->precision[i];
        EQ_STR(p->scene, q->scene, "precision scene");
        EQ_STR(p->reason, q->reason, "precision reason");
        EQ_STR(p->predictor, q->predictor, "precision predictor");
        assert_int_equal(p->corrected, q->corrected);
        assert_int_equal(p->n_rounds, q->n_rounds);
        const double pa[] = { p->machine_spread, p->raw_noise, p->loo_noise, p->calib_noise, p->resolvable };
        const double pb[] = { q->machine_spread, q->raw_noise, q->loo_noise, q->calib_noise, q->resolvable };
        eq_doubles(pa, pb, 5, "precision figure");
    }
}

/* ---- tests ------------------------------------------------------------------ */

static void test_round_trip(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    run_full(&run, "run-1");
    store *s = open_ok(t->db);
    store_put_all(s, &run, NULL);
    assert_int_equal(store_run_finish(s, "run-1", "2026-01-02T04:00:00Z"), 0);
    run.finished = dm_xstrdup("2026-01-02T04:00:00Z");
    /* an entry known only at the run's end joins its environment, last */
    assert_int_equal(store_run_env_put(s, "run-1", "calibration_cpu_ns_end", "10123456"), 0);
    dm_kv_push(&run.environment, &run.n_environment, "calibration_cpu_ns_end", "10123456");
    assert_int_equal(store_run_env_put(s, "no-such-run", "k", "v"), DM_ERR_NOTFOUND);
    assert_int_equal(store_run_load(s, "run-1", &got), 0);
    eq_run(&run, &got);
    /* The sampled counter's 50 samples are one blob of 400 bytes. */
    assert_int_equal(sql_long(s, "SELECT length(data) FROM samples"), 400);
    assert_int_equal(sql_long(s, "PRAGMA user_version"), 8);
    dm_run_free(&got);
    store_close(s);
    /* ...and again from a fresh connection. */
    s = open_ok(t->db);
    assert_int_equal(store_run_load(s, "run-1", &got), 0);
    eq_run(&run, &got);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

static void test_done_and_replace(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    run_fill(&run, "r", "2026-01-01T00:00:00Z");
    dm_config_result a = {0}, b = {0}, a2 = {0};
    config_sampled(&a, "aaaa", 50);
    config_unavailable(&b, "bbbb");
    config_failed(&a2, "aaaa");
    store *s = open_ok(t->db);
    assert_int_equal(store_run_begin(s, &run, "nightly"), 0);
    assert_int_equal(store_config_done(s, "r", "aaaa"), 0);
    assert_int_equal(store_config_put(s, "r", &a), 0);
    assert_int_equal(store_config_done(s, "r", "aaaa"), 1);
    assert_int_equal(store_config_done(s, "other-run", "aaaa"), 0);
    assert_int_equal(store_config_put(s, "r", &b), 0);
    /* Re-put of key aaaa: replaced in place, its old counters and samples gone. */
    assert_int_equal(store_config_put(s, "r", &a2), 0);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM configs"), 2);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM configs WHERE key='aaaa'"), 1);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM counters"), 2);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM samples"), 0);
    assert_int_equal(store_run_load(s, "r", &got), 0);
    assert_int_equal(got.n_configs, 2);
    eq_config(&a2, &got.configs[0]);
    eq_config(&b, &got.configs[1]);
    dm_run_free(&got);
    dm_config_result_free(&a);
    dm_config_result_free(&b);
    dm_config_result_free(&a2);
    dm_run_free(&run);
    store_close(s);
}

static void test_fit_replace(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    run_fill(&run, "r", "2026-01-01T00:00:00Z");
    dm_fit_result f1 = {0}, f2 = {0}, other = {0};
    fit_fill(&f1, 0.5);
    fit_fill(&f2, 0.75);
    /* Same group, pairs in the other order: still the same fit. */
    dm_kv tmpkv = f2.group[0];
    f2.group[0] = f2.group[1];
    f2.group[1] = tmpkv;
    fit_fill(&other, 0.25);
    free(other.group[0].value);
    other.group[0].value = dm_xstrdup("sphere");
    store *s = open_ok(t->db);
    assert_int_equal(store_run_begin(s, &run, NULL), 0);
    assert_int_equal(store_fit_put(s, "r", &f1), 0);
    assert_int_equal(store_fit_put(s, "r", &other), 0);
    assert_int_equal(store_fit_put(s, "r", &f2), 0);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM fit_params"), 4);
    assert_int_equal(store_run_load(s, "r", &got), 0);
    assert_int_equal(got.n_fits, 2);
    eq_fit(&f2, &got.fits[0]);
    eq_fit(&other, &got.fits[1]);
    dm_run_free(&got);
    dm_fit_result_free(&f1);
    dm_fit_result_free(&f2);
    dm_fit_result_free(&other);
    dm_run_free(&run);
    store_close(s);
}

static void test_copy_run(void **state)
{
    tmp *t = *state;
    dm_run_result run, a, b;
    run_full(&run, "run-x");
    char *db2 = dm_xasprintf("%s/merged.sqlite", t->dir);
    store *src = open_ok(t->db), *dst = open_ok(db2);
    store_put_all(src, &run, "shard-1");
    assert_int_equal(store_run_finish(src, "run-x", "2026-01-02T05:00:00Z"), 0);
    assert_int_equal(store_copy_run(dst, src, "run-x"), 0);
    assert_int_equal(store_run_load(src, "run-x", &a), 0);
    assert_int_equal(store_run_load(dst, "run-x", &b), 0);
    eq_run(&a, &b);
    char *tag;
    assert_int_equal(store_run_tag(dst, "run-x", &tag), 0);
    assert_string_equal(tag, "shard-1");
    free(tag);
    assert_int_equal(store_copy_run(dst, src, "run-x"), DM_ERR_EXISTS);
    assert_int_equal(store_copy_run(dst, src, "absent"), DM_ERR_NOTFOUND);
    assert_non_null(strstr(store_last_error(dst), "absent"));
    assert_int_equal(sql_long(dst, "SELECT COUNT(*) FROM configs"), 3);
    assert_integrity_ok(dst);
    dm_run_free(&a);
    dm_run_free(&b);
    dm_run_free(&run);
    store_close(src);
    store_close(dst);
    free(db2);
}

static void begin(store *s, const char *id, const char *started, const char *tag)
{
    dm_run_result r;
    run_fill(&r, id, started);
    assert_int_equal(store_run_begin(s, &r, tag), 0);
    dm_run_free(&r);
}

static void test_latest_and_list(void **state)
{
    tmp *t = *state;
    store *s = open_ok(t->db);
    char *id = NULL, **ids;
    size_t n;
    assert_int_equal(store_latest_run(s, NULL, &id), DM_ERR_NOTFOUND);
    assert_int_equal(store_list_runs(s, &ids, &n), 0);
    assert_int_equal(n, 0);
    begin(s, "b", "2026-01-02T00:00:00Z", "nightly");
    begin(s, "c", "2026-01-03T00:00:00Z", NULL);
    begin(s, "a", "2026-01-01T00:00:00Z", "nightly");
    begin(s, "c2", "2026-01-03T00:00:00Z", "pr"); /* same start: later insert wins */
    assert_int_equal(store_latest_run(s, NULL, &id), 0);
    assert_string_equal(id, "c2");
    free(id);
    assert_int_equal(store_latest_run(s, "nightly", &id), 0);
    assert_string_equal(id, "b");
    free(id);
    assert_int_equal(store_latest_run(s, "none", &id), DM_ERR_NOTFOUND);
    assert_null(id);
    assert_int_equal(store_list_runs(s, &ids, &n), 0);
    assert_int_equal(n, 4);
    const char *want[] = { "c2", "c", "b", "a" };
    for (size_t i = 0; i < n; i++) {
        assert_string_equal(ids[i], want[i]);
        free(ids[i]);
    }
    free(ids);
    store_close(s);
}

static void test_misuse_and_bad_files(void **state)
{
    tmp *t = *state;
    dm_run_result run;
    dm_config_result c = {0};
    config_failed(&c, "k");
    run_fill(&run, "r", "2026-01-01T00:00:00Z");
    store *s = open_ok(t->db);
    assert_int_equal(store_config_put(s, "r", &c), DM_ERR_NOTFOUND);
    assert_non_null(strstr(store_last_error(s), "run 'r'"));
    assert_int_equal(store_run_finish(s, "r", "x"), DM_ERR_NOTFOUND);
    assert_int_equal(store_run_begin(s, &run, NULL), 0);
    assert_int_equal(store_run_begin(s, &run, NULL), DM_ERR_EXISTS);
    dm_run_result got;
    assert_int_equal(store_run_load(s, "nope", &got), DM_ERR_NOTFOUND);
    assert_null(got.id);
    store_close(s);
    dm_run_free(&run);
    dm_config_result_free(&c);

    /* A path below a regular file cannot be created: I/O error naming it. */
    char *file = dm_xasprintf("%s/plain", t->dir);
    assert_int_equal(dm_write_file(file, "not a database, just text\n", 26), 0);
    char *below = dm_xasprintf("%s/x.sqlite", file);
    dm_str err = {0};
    assert_int_equal(store_open(below, &s, &err), DM_ERR_IO);
    assert_null(s);
    assert_non_null(strstr(dm_str_get(&err), below));
    /* A file that is not a database: store error naming it, file untouched. */
    err.len = 0;
    assert_int_equal(store_open(file, &s, &err), DM_ERR_STORE);
    assert_non_null(strstr(dm_str_get(&err), file));
    assert_non_null(strstr(dm_str_get(&err), "not a database"));
    /* A database from a newer dmbench is refused. */
    sqlite3 *db;
    assert_int_equal(sqlite3_open(t->db, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "PRAGMA user_version=99", NULL, NULL, NULL), 0);
    sqlite3_close(db);
    err.len = 0;
    assert_int_equal(store_open(t->db, &s, &err), DM_ERR_STORE);
    assert_non_null(strstr(dm_str_get(&err), "written by a newer dmbench (schema version 99"));
    dm_str_free(&err);
    free(below);
    free(file);
}

static void remove_db(const char *db);

/* A checked store: a table dropped or a column lost is "damaged" at open
 * (DM_ERR_STORE naming the table or column), never a lookup failure later;
 * the file is not changed by the refused open. */
static void test_missing_table_or_column(void **state)
{
    tmp *t = *state;
    static const struct { const char *sql, *want; } cases[] = {
        { "DROP TABLE samples", "damaged: table 'samples' is missing" },
        { "DROP TABLE fit_labels", "damaged: table 'fit_labels' is missing" },
        { "ALTER TABLE configs DROP COLUMN q_ssim",
          "damaged: column 'q_ssim' of table 'configs' is missing" },
        { "ALTER TABLE runs RENAME COLUMN tag TO label",
          "damaged: column 'tag' of table 'runs' is missing" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        remove_db(t->db);
        store_close(open_ok(t->db));
        sqlite3 *db;
        assert_int_equal(sqlite3_open(t->db, &db), SQLITE_OK);
        assert_int_equal(sqlite3_exec(db, cases[i].sql, NULL, NULL, NULL), SQLITE_OK);
        sqlite3_close(db);
        char *before = NULL, *after = NULL;
        size_t n_before = 0, n_after = 0;
        assert_int_equal(dm_read_file(t->db, &before, &n_before), 0);
        store *s = NULL;
        dm_str err = {0};
        assert_int_equal(store_open(t->db, &s, &err), DM_ERR_STORE);
        assert_null(s);
        if (!strstr(dm_str_get(&err), cases[i].want))
            fail_msg("%s: got '%s', want '%s'", cases[i].sql, dm_str_get(&err), cases[i].want);
        assert_non_null(strstr(dm_str_get(&err), "restore dmbench.sqlite from a backup"));
        assert_int_equal(dm_read_file(t->db, &after, &n_after), 0);
        assert_int_equal(n_before, n_after);
        assert_memory_equal(before, after, n_before);
        free(before);
        free(after);
        dm_str_free(&err);
    }
}

/* A version-1 store (before fits had a condition column) opens: it is
 * migrated to the current version, its fits read back with condition 0 ("not
 * computed") and everything else intact; new fits keep their condition,
 * infinity included. */
/* SQL that takes the store back to before version 8, and what such a
 * store reads back: quality along a path without the frames written. */
#define PATH_SHOTS_DROPPED "DROP TABLE path_shots;"

static void path_shots_not_stored(dm_run_result *run)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        dm_path_quality *pq = &run->configs[i].path_quality;
        for (size_t k = 0; k < pq->n_shots; k++) {
            free(pq->shots[k].img_test);
            free(pq->shots[k].img_ref);
            free(pq->shots[k].img_flip);
        }
        free(pq->shots);
        pq->shots = NULL;
        pq->n_shots = 0;
    }
}

/* SQL that takes the store back to before version 7. */
#define PATH_QUALITY_DROPPED PATH_SHOTS_DROPPED "DROP TABLE path_quality;"

/* What a store from before version 7 reads back: no quality along a path. */
static void path_quality_not_computed(dm_run_result *run)
{
    path_shots_not_stored(run);
    for (size_t i = 0; i < run->n_configs; i++) {
        dm_path_quality *pq = &run->configs[i].path_quality;
        free(pq->flip);
        free(pq->ssim);
        free(pq->img_temporal);
        free(pq->reason);
        memset(pq, 0, sizeof *pq);
    }
}

/* SQL that takes the store back to before version 5. */
#define PRECISION_DROPPED                                                      \
    "ALTER TABLE counters DROP COLUMN corrected; ALTER TABLE counters DROP COLUMN corr_median;" \
    "ALTER TABLE counters DROP COLUMN corr_ci_lo; ALTER TABLE counters DROP COLUMN corr_ci_hi;" \
    "DROP TABLE rounds; DROP TABLE scene_precision;"

/* What a store from before version 5 reads back: no correction, no rounds. */
static void precision_not_computed(dm_run_result *run)
{
    path_quality_not_computed(run);
    for (size_t i = 0; i < run->n_configs; i++)
        for (size_t k = 0; k < run->configs[i].n_counters; k++)
            run->configs[i].counters[k].corrected = 0;
    dm_run_result keep = *run;
    run->n_rounds = run->n_precision = 0;
    run->rounds = NULL;
    run->precision = NULL;
    keep.n_configs = keep.n_left_out = keep.n_fits = keep.n_environment = keep.n_warnings = 0;
    keep.configs = NULL;
    keep.left_out = NULL;
    keep.fits = NULL;
    keep.environment = NULL;
    keep.warnings = NULL;
    keep.id = keep.sweep = keep.started = keep.finished = keep.sweep_hash = keep.timer_verdict = NULL;
    dm_run_free(&keep);   /* frees the rounds and precision only */
}

/* SQL that takes the store back to before version 6 (and 7), and what it
 * reads back: no frame times along a path, no quality along it. */
#define PATH_DROPPED PATH_QUALITY_DROPPED "DROP TABLE path_frames;"

static void path_not_stored(dm_run_result *run)
{
    path_quality_not_computed(run);
    for (size_t i = 0; i < run->n_configs; i++) {
        free(run->configs[i].path.frame_ns);
        free(run->configs[i].path.stutter_at);
        run->configs[i].path = (dm_path_series){0};
    }
}

/* SQL that takes the configs table back to before version 4. */
#define FLIP_COLUMNS_DROPPED                                                   \
    "ALTER TABLE configs DROP COLUMN q_flip; ALTER TABLE configs DROP COLUMN q_flip_q1;"  \
    "ALTER TABLE configs DROP COLUMN q_flip_median; ALTER TABLE configs DROP COLUMN q_flip_q3;" \
    "ALTER TABLE configs DROP COLUMN q_flip_max; ALTER TABLE configs DROP COLUMN q_flip_ppd;" \
    "ALTER TABLE configs DROP COLUMN img_flip;"

/* What a store from before version 4 reads back: FLIP not computed. */
static void flip_not_computed(dm_run_result *run)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        dm_quality *q = &run->configs[i].quality;
        q->flip = q->flip_q1 = q->flip_median = q->flip_q3 = q->flip_max = q->flip_ppd = NAN;
        free(run->configs[i].img_flip);
        run->configs[i].img_flip = NULL;
    }
}

/* A store of run_full("old") taken back to an older version by `undo`
 * (SQL ending in that version's PRAGMA user_version; `table`, when not
 * NULL, is checked to hold n rows first, so the undo drops something), then
 * opened again, which migrates it to the current version: the open store,
 * *run the full run. */
static store *open_downgraded(tmp *t, dm_run_result *run, const char *table, long n, const char *undo)
{
    run_full(run, "old");
    store *s = open_ok(t->db);
    store_put_all(s, run, NULL);
    if (table) {
        char q[96];
        snprintf(q, sizeof q, "SELECT count(*) FROM %s", table);
        assert_int_equal(sql_long(s, q), n);
    }
    store_close(s);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(t->db, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, undo, NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    s = open_ok(t->db);
    assert_int_equal(sql_long(s, "PRAGMA user_version"), 8);
    return s;
}

static void test_fit_condition_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    store *s = open_downgraded(t, &run, NULL, 0,
                               "ALTER TABLE fits DROP COLUMN condition;"
                               "DROP TABLE partial_samples;"   /* came with version 3 */
                               FLIP_COLUMNS_DROPPED PRECISION_DROPPED PATH_DROPPED
                               "PRAGMA user_version=1");
    assert_int_equal(store_run_load(s, "old", &got), 0);
    assert_true(got.fits[0].condition == 0.0);
    run.fits[0].condition = 0.0;
    flip_not_computed(&run);
    precision_not_computed(&run);
    path_not_stored(&run);
    eq_run(&run, &got);
    dm_run_free(&got);
    run.fits[0].condition = INFINITY;
    assert_int_equal(store_fit_put(s, "old", &run.fits[0]), 0);
    assert_int_equal(store_run_load(s, "old", &got), 0);
    assert_int_equal(got.n_fits, 1);
    assert_true(isinf(got.fits[0].condition) && got.fits[0].condition > 0);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

/* A version-3 store (before FLIP) opens migrated: its configurations read
 * back with FLIP NaN ("not computed") and no FLIP map, all else intact. */
static void test_flip_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    store *s = open_downgraded(t, &run, NULL, 0,
                               FLIP_COLUMNS_DROPPED PRECISION_DROPPED PATH_DROPPED "PRAGMA user_version=3");
    assert_int_equal(store_run_load(s, "old", &got), 0);
    flip_not_computed(&run);
    precision_not_computed(&run);
    path_not_stored(&run);
    eq_run(&run, &got);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

/* The run "old" of a migrated store reads back as run_full with what the
 * old version lacked taken out by strip; its configurations stored again
 * read back whole, into *got. */
static void migrated_then_whole(store *s, void (*strip)(dm_run_result *), dm_run_result *run,
                                dm_run_result *got)
{
    assert_int_equal(store_run_load(s, "old", got), 0);
    dm_run_result want;
    run_full(&want, "old");
    strip(&want);
    eq_run(&want, got);
    dm_run_free(got);
    dm_run_free(&want);
    for (size_t i = 0; i < run->n_configs; i++)
        assert_int_equal(store_config_put(s, "old", &run->configs[i]), 0);
    assert_int_equal(store_run_load(s, "old", got), 0);
    eq_run(run, got);
}

/* A version-6 store (before quality along a path) opens migrated: its
 * configurations read back without path quality, everything else intact;
 * a configuration stored afterwards keeps its series, NaN included. */
static void test_path_quality_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    store *s = open_downgraded(t, &run, "path_quality", 1,
                               PATH_QUALITY_DROPPED "PRAGMA user_version=6");
    migrated_then_whole(s, path_quality_not_computed, &run, &got);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

/* A version-7 store (before the filmstrip's frames) opens migrated: its
 * quality along a path reads back whole but with no frames written (the
 * report says why the filmstrip is absent); a configuration stored
 * afterwards keeps its frames, a missing FLIP map included. */
static void test_path_shots_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    store *s = open_downgraded(t, &run, "path_shots", 2,
                               PATH_SHOTS_DROPPED "PRAGMA user_version=7");
    migrated_then_whole(s, path_shots_not_stored, &run, &got);
    size_t with = 0;   /* the configuration with quality along its path */
    while (with < got.n_configs && !got.configs[with].path_quality.present)
        with++;
    assert_true(with < got.n_configs);
    assert_int_equal(got.configs[with].path_quality.n_shots, 2);
    assert_null(got.configs[with].path_quality.shots[1].img_flip);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

/* A version-4 store (before the drift correction) opens migrated: its
 * counters read back uncorrected (their raw figures intact), without rounds
 * or precision; a correction written afterwards reads back. */
/* A version-5 store (before path_frames) opens as version 7 and reads its
 * configurations without frame times; a path series written then reads
 * back whole, and one whose blob does not hold frames x replays values is
 * refused as damaged. */
static void test_path_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got, want;
    store *s = open_downgraded(t, &run, NULL, 0,
                               PATH_DROPPED "PRAGMA user_version=5");
    assert_int_equal(store_run_load(s, "old", &got), 0);
    run_full(&want, "old");
    path_not_stored(&want);
    eq_run(&want, &got);
    dm_run_free(&got);
    assert_int_equal(store_config_put(s, "old", &run.configs[2]), 0);
    assert_int_equal(sql_long(s, "SELECT length(data) FROM path_frames"), 12 * 8);
    assert_int_equal(store_run_load(s, "old", &got), 0);
    eq_config(&run.configs[2], &got.configs[2]);
    dm_run_free(&got);
    store_close(s);
    sqlite3 *db;
    assert_int_equal(sqlite3_open(t->db, &db), SQLITE_OK);
    assert_int_equal(sqlite3_exec(db, "UPDATE path_frames SET replays=4", NULL, NULL, NULL), SQLITE_OK);
    sqlite3_close(db);
    s = open_ok(t->db);
    assert_int_equal(store_run_load(s, "old", &got), DM_ERR_STORE);
    assert_non_null(strstr(store_last_error(s), "hold 12 values, not 4 frames x 4 replays"));
    dm_run_free(&got);
    dm_run_free(&want);
    dm_run_free(&run);
    store_close(s);
}

static void test_precision_migration(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    store *s = open_downgraded(t, &run, NULL, 0,
                               PRECISION_DROPPED PATH_DROPPED "PRAGMA user_version=4");
    assert_int_equal(store_run_load(s, "old", &got), 0);
    dm_run_result want;
    run_full(&want, "old");
    precision_not_computed(&want);
    path_not_stored(&want);
    eq_run(&want, &got);
    dm_run_free(&got);
    assert_int_equal(store_precision_put(s, "old", &run), 0);
    assert_int_equal(store_run_load(s, "old", &got), 0);
    assert_int_equal(got.n_precision, 1);
    assert_true(got.configs[2].counters[0].corrected == 1);
    assert_true(isinf(got.configs[2].counters[0].corr_ci_hi));
    assert_int_equal(store_precision_put(s, "no-such-run", &run), DM_ERR_NOTFOUND);
    assert_integrity_ok(s);
    dm_run_free(&got);
    dm_run_free(&want);
    dm_run_free(&run);
    store_close(s);
}

/* A full disk (max_page_count) makes a put fail: nothing of it is stored,
 * the rest is intact and the store opens again. */
static void test_disk_full(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    dm_config_result small = {0}, big = {0};
    config_unavailable(&small, "small");
    config_sampled(&big, "big", 100000);
    run_fill(&run, "r", "2026-01-01T00:00:00Z");
    store *s = open_ok(t->db);
    assert_int_equal(store_run_begin(s, &run, NULL), 0);
    assert_int_equal(store_config_put(s, "r", &small), 0);
    long pages = sql_long(s, "PRAGMA page_count");
    char *limit = dm_xasprintf("PRAGMA max_page_count=%ld", pages + 2);
    assert_int_equal(sqlite3_exec(store__db(s), limit, NULL, NULL, NULL), SQLITE_OK);
    assert_int_equal(store_config_put(s, "r", &big), DM_ERR_STORE);
    assert_non_null(strstr(store_last_error(s), "full"));
    assert_non_null(strstr(store_last_error(s), t->db));
    assert_int_equal(store_config_done(s, "r", "big"), 0);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM counters"), 2);
    store_close(s);
    s = open_ok(t->db);
    assert_integrity_ok(s);
    assert_int_equal(store_run_load(s, "r", &got), 0);
    assert_int_equal(got.n_configs, 1);
    eq_config(&small, &got.configs[0]);
    assert_int_equal(store_config_put(s, "r", &big), 0);   /* room again */
    assert_int_equal(store_config_done(s, "r", "big"), 1);
    dm_run_free(&got);
    dm_run_free(&run);
    dm_config_result_free(&small);
    dm_config_result_free(&big);
    free(limit);
    store_close(s);
}

/* ---- a process killed in the middle of a transaction --------------------------- */

typedef struct killer { sqlite3 *db; int base; int pipe_fd; const char *wal; } killer;

static off_t file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? st.st_size : -1;
}

/* Progress handler: once the 4th put has written 20 rows inside its open
 * transaction, report the WAL size and die without any cleanup. */
static int kill_mid_tx(void *arg)
{
    killer *k = arg;
    if (!sqlite3_get_autocommit(k->db) && sqlite3_total_changes(k->db) - k->base >= 20) {
        off_t wal = file_size(k->wal);
        if (write(k->pipe_fd, &wal, sizeof wal) != sizeof wal)
            _exit(3);
        raise(SIGKILL);
    }
    return 0;
}

static void child_puts_then_dies(const char *path, const char *wal, int fd)
{
    store *s;
    dm_run_result run;
    run_fill(&run, "r", "2026-01-01T00:00:00Z");
    if (store_open(path, &s, NULL) || store_run_begin(s, &run, NULL))
        _exit(1);
    for (int i = 0; i < 4; i++) {
        dm_config_result c = {0};
        char key[16];
        snprintf(key, sizeof key, "k%d", i);
        config_sampled(&c, key, 50);
        if (i == 3) {   /* big, tiny page cache: uncommitted pages reach the WAL */
            add_counters(&c, 40, 5000);
            sqlite3_exec(store__db(s), "PRAGMA cache_size=10", NULL, NULL, NULL);
            off_t committed = file_size(wal);
            if (write(fd, &committed, sizeof committed) != sizeof committed)
                _exit(3);
            static killer k;
            k = (killer){ store__db(s), sqlite3_total_changes(store__db(s)), fd, wal };
            sqlite3_progress_handler(store__db(s), 1, kill_mid_tx, &k);
        }
        if (store_config_put(s, "r", &c))
            _exit(2);
        dm_config_result_free(&c);
    }
    _exit(4);   /* the 4th put must not finish */
}

static void test_killed_mid_transaction(void **state)
{
    tmp *t = *state;
    char *wal = dm_xasprintf("%s-wal", t->db);
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(fds[0]);
        child_puts_then_dies(t->db, wal, fds[1]);
    }
    close(fds[1]);
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    if (!WIFSIGNALED(status))
        fail_msg("child exited with %d instead of being killed", WEXITSTATUS(status));
    assert_int_equal(WTERMSIG(status), SIGKILL);
    off_t committed = -1, at_kill = -1;
    assert_int_equal(read(fds[0], &committed, sizeof committed), sizeof committed);
    assert_int_equal(read(fds[0], &at_kill, sizeof at_kill), sizeof at_kill);
    close(fds[0]);
    /* Uncommitted frames of the 4th put were in the WAL when it died. */
    assert_true(at_kill > committed);

    store *s = open_ok(t->db);
    assert_integrity_ok(s);
    dm_run_result got;
    assert_int_equal(store_run_load(s, "r", &got), 0);
    assert_int_equal(got.n_configs, 3);
    for (int i = 0; i < 3; i++) {
        dm_config_result c = {0};
        char key[16];
        snprintf(key, sizeof key, "k%d", i);
        config_sampled(&c, key, 50);
        eq_config(&c, &got.configs[i]);
        dm_config_result_free(&c);
    }
    assert_int_equal(store_config_done(s, "r", "k3"), 0);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM counters WHERE key='k3'"), 0);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM samples WHERE key='k3'"), 0);
    dm_run_free(&got);
    store_close(s);
    free(wal);
}

/* ---- failing allocations (SQLite's allocator, installed by main) ---------------- */

static sqlite3_mem_methods fault_base;
static long fault_countdown;   /* > 0: the allocation that takes it to 0 fails */

static int fault_hit(void)
{
    return fault_countdown > 0 && --fault_countdown == 0;
}

static void *fault_malloc(int n)
{
    return fault_hit() ? NULL : fault_base.xMalloc(n);
}

static void *fault_realloc(void *p, int n)
{
    return fault_hit() ? NULL : fault_base.xRealloc(p, n);
}

static void fault_install(void)
{
    sqlite3_mem_methods m;
    if (sqlite3_config(SQLITE_CONFIG_GETMALLOC, &fault_base) != SQLITE_OK)
        abort();
    m = fault_base;
    m.xMalloc = fault_malloc;
    m.xRealloc = fault_realloc;
    if (sqlite3_config(SQLITE_CONFIG_MALLOC, &m) != SQLITE_OK)
        abort();
}

static void remove_db(const char *db)
{
    const char *sfx[] = { "", "-wal", "-shm" };
    for (int i = 0; i < 3; i++) {
        char *p = dm_xasprintf("%s%s", db, sfx[i]);
        unlink(p);
        free(p);
    }
}

/* Fails the 1st, 2nd, ... allocation of creating a store until none fails:
 * each failure is a clean error naming the path, and the file left behind
 * always opens afterwards as a sound, complete store.  Every point up to 200
 * (opening, pragmas, first statements), then every 23rd, and past 10000
 * (version 4's ALTER TABLEs, each re-reading the schema) every 61st: the
 * ~20000 points are mostly alike allocations of the schema script (run
 * twice: into the file, and into the in-memory reference the opened file is
 * checked against), and each round costs two fsync'd opens. */
static void test_open_alloc_faults(void **state)
{
    tmp *t = *state;
    long n, failures = 0;
    for (n = 1; n < 40000; n += n < 200 ? 1 : n < 10000 ? 23 : 61) {
        remove_db(t->db);
        store *s = NULL;
        dm_str err = {0};
        fault_countdown = n;
        int rc = store_open(t->db, &s, &err);
        int reached = fault_countdown == 0;
        fault_countdown = 0;
        if (rc) {
            failures++;
            assert_null(s);
            assert_true(rc == DM_ERR_STORE || rc == DM_ERR_IO);
            assert_non_null(strstr(dm_str_get(&err), t->db));
        }
        store_close(s);
        dm_str_free(&err);
        s = open_ok(t->db);
        assert_integrity_ok(s);
        assert_int_equal(sql_long(s, "PRAGMA user_version"), 8);
        store_close(s);
        if (!reached)
            break;
    }
    assert_true(n < 40000);
    assert_true(failures > 10);
    print_message("store_open: %ld allocation points, %ld clean failures\n", n, failures);
}

/* Fails each allocation of a put in turn: the put either succeeds completely
 * or leaves the store exactly as before. */
static void test_put_alloc_faults(void **state)
{
    tmp *t = *state;
    dm_run_result run, got;
    run_full(&run, "r");
    store *s = open_ok(t->db);
    assert_int_equal(store_run_begin(s, &run, NULL), 0);
    assert_int_equal(store_config_put(s, "r", &run.configs[0]), 0);
    long n, failures = 0;
    for (n = 1; n < 20000; n++) {
        fault_countdown = n;
        int rc = store_config_put(s, "r", &run.configs[2]);
        int reached = fault_countdown == 0;
        fault_countdown = 0;
        assert_true(rc == 0 || rc == DM_ERR_STORE);
        int done = store_config_done(s, "r", run.configs[2].key);
        assert_int_equal(done, rc == 0);
        if (rc) {
            failures++;
            assert_non_null(strstr(store_last_error(s), t->db));
        } else {
            /* Undo a success so the next round puts a new row again. */
            assert_int_equal(sqlite3_exec(store__db(s), "DELETE FROM configs WHERE"
                             " key='00000000000000cc'", NULL, NULL, NULL), SQLITE_OK);
        }
        if (!reached)
            break;
    }
    assert_true(n < 20000);
    assert_true(failures > 10);
    assert_integrity_ok(s);
    assert_int_equal(store_config_put(s, "r", &run.configs[2]), 0);
    assert_int_equal(store_run_load(s, "r", &got), 0);
    assert_int_equal(got.n_configs, 2);
    eq_config(&run.configs[0], &got.configs[0]);
    eq_config(&run.configs[2], &got.configs[1]);
    assert_int_equal(sql_long(s, "SELECT COUNT(*) FROM counters"), 1);
    print_message("store_config_put: %ld allocation points, %ld clean failures\n",
                  n, failures);
    dm_run_free(&got);
    dm_run_free(&run);
    store_close(s);
}

/* Round checkpoints: put/get round-trip every bit, a second put replaces
 * the first, and storing the finished configuration deletes them; a
 * damaged store is reported by store_check. */
static void test_partial_samples(void **state)
{
    tmp *t = *state;
    dm_run_result run;
    run_full(&run, "r");
    store *s = open_ok(t->db);
    assert_int_equal(store_run_begin(s, &run, NULL), 0);
    const char *names[2] = { "WallTime", "SamplesPassed" };
    double a[3] = { 1.5, NAN, -0.0 }, b[3] = { 7, 8, 9 }, *v[2] = { a, b }, *got = NULL;
    store_partial p = { .key = run.configs[0].key, .counters = names, .n_counters = 2,
                        .samples = v, .n_samples = 2, .sampling_ns = 42 };
    assert_int_equal(store_partial_put(s, "r", &p, 1), 0);
    p.n_samples = 3;
    assert_int_equal(store_partial_put(s, "r", &p, 1), 0);
    size_t n = 0;
    long ns = 0;
    assert_int_equal(store_partial_get(s, "r", p.key, "WallTime", &got, &n, &ns), 0);
    assert_int_equal(n, 3);
    assert_int_equal(ns, 42);
    assert_memory_equal(got, a, sizeof a);
    free(got);
    assert_int_equal(store_partial_get(s, "r", p.key, "GPUTime", &got, &n, &ns), DM_ERR_NOTFOUND);
    assert_int_equal(store_config_put(s, "r", &run.configs[0]), 0);
    assert_int_equal(store_partial_get(s, "r", p.key, "WallTime", &got, &n, &ns), DM_ERR_NOTFOUND);
    assert_int_equal(store_check(s, NULL), 0);
    store_close(s);
    dm_run_free(&run);
}

int main(void)
{
    fault_install();   /* before SQLite initialises; idle until armed */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_round_trip, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_done_and_replace, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_fit_replace, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_fit_condition_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_flip_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_path_shots_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_path_quality_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_precision_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_path_migration, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_partial_samples, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_copy_run, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_latest_and_list, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_misuse_and_bad_files, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_missing_table_or_column, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_disk_full, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_killed_mid_transaction, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_open_alloc_faults, tmp_setup, tmp_teardown),
        cmocka_unit_test_setup_teardown(test_put_alloc_faults, tmp_setup, tmp_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
