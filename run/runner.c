/* runner.c — the outline of a run in the parent process: its directory,
 * store, environment record and end (see runner.h; the children are
 * runner_child.c, the plan-time options runner_plan.c). */
#include "runner.h"
#include "run/runner_state.h"
#include "core/dm_error.h"
#include "core/dm_table.h"
#include "counters/counters.h"
#include "run/calibrate.h"
#include "run/env.h"
#include "run/fitting.h"
#include "run/inputs.h"
#include "run/precision.h"
#include "run/trends.h"
#include "sweep/published.h"
#include "reports/answer.h"
#include "reports/metric.h"
#include "techniques/maps.h"
#include "techniques/render.h"
#include "techniques/user_technique.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <sys/file.h>
#include <time.h>

/* ---- run directory, store, report ---------------------------------------------- */

/* Configurations of the run now in the store. */
static size_t runner__committed(runner *r)
{
    dm_run_result run = {0};
    size_t n = store_run_load(r->st, r->run_id, &run) == 0 ? run.n_configs : 0;
    dm_run_free(&run);
    return n;
}

/* How long a run waits for the lock of a run that has ended (its process
 * is gone) while that run's children, killed with it, are still exiting. */
#define RUNNER__LOCK_ORPHAN_WAIT_S 5.0

/* The lock of fd, waiting while the run recorded in it has ended: a run
 * killed by a signal dies at once, and its children (killed by
 * PR_SET_PDEATHSIG, core/dm_proc.c) hold the lock they inherited until
 * they have exited, which on a loaded machine takes a moment; so `kill`
 * then `--resume` does not find the directory busy.  pid is the recorded
 * holder's.  Returns flock's result. */
static int runner__lock_take(int fd, const char *pid)
{
    int rc = flock(fd, LOCK_EX | LOCK_NB);
    char *end = NULL;
    long holder = strtol(pid, &end, 10);
    if (rc == 0 || end == pid || *end || holder <= 0 || holder > INT_MAX || holder == (long)getpid())
        return rc;   /* no pid recorded that kill(2) could ask about: busy */
    for (int64_t t0 = dm_now_ns(); rc != 0 && (dm_now_ns() - t0) / 1e9 < RUNNER__LOCK_ORPHAN_WAIT_S;) {
        if (kill((pid_t)holder, 0) == 0 || errno != ESRCH)
            break;   /* the run itself is alive: busy */
        struct timespec nap = { 0, 50 * 1000 * 1000 };
        nanosleep(&nap, NULL);
        rc = flock(fd, LOCK_EX | LOCK_NB);
    }
    return rc;
}

/* Takes the lock of the output directory (flock on <root>/dmbench.lock,
 * held until the process and its children end, so a kill -9 never leaves
 * a stale lock).  DM_ERR_BUSY with the holder's pid when another process
 * has it: two runs on one store would measure the same configurations and
 * replace each other's results. */
static int runner__lock(runner *r, dm_str *err)
{
    char *path = dm_xasprintf("%s/dmbench.lock", r->root);
    r->lock_fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    int rc = 0;
    char pid[32] = "";
    if (r->lock_fd >= 0) {
        ssize_t got = pread(r->lock_fd, pid, sizeof pid - 1, 0);
        pid[got > 0 ? got : 0] = '\0';
        pid[strcspn(pid, "\n")] = '\0';
    }
    if (r->lock_fd < 0) {
        dm_str_printf(err, "%s: cannot create the lock file: %s", path, strerror(errno));
        rc = DM_ERR_IO;
    } else if (runner__lock_take(r->lock_fd, pid) != 0) {
        dm_str_printf(err, "%s is in use by another dmbench run (pid %s); wait for it to end "
                      "or give another --out", r->root, pid[0] ? pid : "unknown");
        rc = DM_ERR_BUSY;
    } else {
        char pid[32];
        int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
        if (ftruncate(r->lock_fd, 0) != 0 || pwrite(r->lock_fd, pid, (size_t)len, 0) != len)
            dm_log(DM_LOG_DEBUG, "%s: cannot record the pid", path);
    }
    free(path);
    return rc;
}

/* The shard a run measures, as recorded in its environment ("K/N"), or
 * "none" for an unsharded run; into buf. */
static void runner__shard_text(int k, int n, char buf[32])
{
    if (n > 0)
        snprintf(buf, 32, "%d/%d", k, n);
    else
        snprintf(buf, 32, "none");
}

/* --resume may only continue a run whose user techniques' files are those
 * it measured (the environment entries USER_TECHNIQUE_ENV_PREFIX NAME =
 * "HASH PATH" that runner__begin recorded): one run measures one version of
 * each source.  Returns 0, or DM_ERR_ARG naming the file in err. */
static int runner__resume_sources(const runner *r, const dm_run_result *old, dm_str *err)
{
    size_t np = strlen(USER_TECHNIQUE_ENV_PREFIX);
    for (size_t i = 0; i < user_technique_count(); i++) {
        const technique_desc *t = user_technique_at(i);
        const char *path = user_technique_path(t), *was = NULL;
        for (size_t k = 0; k < old->n_environment && !was; k++) {   /* by name, else by path */
            const dm_kv *e = &old->environment[k];
            const char *sp = strchr(e->value, ' ');
            if (strncmp(e->key, USER_TECHNIQUE_ENV_PREFIX, np) == 0 && sp &&
                (strcmp(e->key + np, t->name) == 0 || strcmp(sp + 1, path) == 0))
                was = e->value;
        }
        char now[17];
        dm_hex64(t->source_hash, now);
        if (!was || (strcspn(was, " ") == 16 && strncmp(was, now, 16) == 0))
            continue;
        dm_str_printf(err, "--resume: %s: the user technique's file changed since run %s measured it "
                      "(source hash %.*s, now %s); one run measures one version of each source: "
                      "restore the file to resume, or run without --resume to start a new run",
                      path, r->run_id, (int)strcspn(was, " "), was, now);
        return DM_ERR_ARG;
    }
    return 0;
}

/* --resume may only continue a run of the same sweep file and the same
 * shard: another shard's keys would be mixed into it silently; and of the
 * same user techniques' files (runner__resume_sources) and user map and
 * mesh files (inputs_resume_check).  Returns 0, or
 * DM_ERR_ARG with both shards (or the sweep or source mismatch) in err. */
static int runner__resume_check(const runner *r, const dm_run_result *old, dm_str *err)
{
    char hash[17], want[32];
    dm_hex64(r->s->hash, hash);
    if (!old->sweep_hash || strcmp(old->sweep_hash, hash) != 0) {
        dm_str_printf(err, "--resume: run %s was made from a different sweep file; "
                      "run without --resume to start a new run", r->run_id);
        return DM_ERR_ARG;
    }
    const char *had = dm_kv_get(old->environment, old->n_environment, "shard");
    runner__shard_text(r->o->shard_k, r->o->shard_n, want);
    if (strcmp(had ? had : "none", want) != 0) {
        char *was = had ? dm_xasprintf("shard %s", had) : dm_xstrdup("the whole sweep");
        char *now = r->o->shard_n ? dm_xasprintf("shard %s", want) : dm_xstrdup("the whole sweep");
        char *how = had ? dm_xasprintf("with --shard %s", had) : dm_xstrdup("without --shard");
        dm_str_printf(err, "--resume: run %s measures %s, not %s; resume it %s, or give another "
                      "--out for %s", r->run_id, was, now, how, now);
        free(was);
        free(now);
        free(how);
        return DM_ERR_ARG;
    }
    int rc = runner__resume_sources(r, old, err);
    return rc ? rc : inputs_resume_check(old->environment, old->n_environment, r->run_id, err);
}

static int runner__open(runner *r, dm_str *err)
{
    r->root = dm_xstrdup(r->o->out_root ? r->o->out_root : "results");
    r->store_path = dm_xasprintf("%s/dmbench.sqlite", r->root);
    r->cache_dir = dm_xasprintf("%s/cache/programs", r->root);
    if (r->o->resume && !dm_file_exists(r->store_path)) {
        dm_str_printf(err, "--resume: %s: no results store there, so no run to resume; "
                      "run without --resume to start one", r->root);
        return DM_ERR_ARG;
    }
    if (store_path_fits(r->store_path, err) != 0)
        return DM_ERR_ARG;      /* before the directory and its lock are made */
    if (dm_mkdirs(r->root) != 0 || access(r->root, W_OK) != 0) {
        dm_str_printf(err, "%s: cannot create or write the output directory", r->root);
        return DM_ERR_IO;
    }
    int rc = runner__lock(r, err);
    rc = rc ? rc : store_open(r->store_path, &r->st, err);
    rc = rc ? rc : store_check(r->st, err);
    if (rc != 0)
        return rc;
    if (r->o->resume) {
        if (store_latest_run(r->st, r->o->tag, &r->run_id) != 0) {
            dm_str_printf(err, "%s: --resume: no run to resume in this store", r->store_path);
            return DM_ERR_ARG;
        }
        dm_run_result old = {0};
        store_run_load(r->st, r->run_id, &old);
        rc = runner__resume_check(r, &old, err);
        dm_run_free(&old);
        if (rc != 0)
            return rc;
    } else {
        char stamp[32];
        time_t t = time(NULL);
        struct tm tm;
        gmtime_r(&t, &tm);
        strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
        r->run_id = dm_xstrdup(stamp);
        for (int k = 2; ; k++) {
            char *dir = dm_xasprintf("%s/%s", r->root, r->run_id);
            int exists = dm_file_exists(dir);
            free(dir);
            if (!exists)
                break;
            free(r->run_id);
            r->run_id = dm_xasprintf("%s-%d", stamp, k);
        }
    }
    r->run_dir = dm_xasprintf("%s/%s", r->root, r->run_id);
    char *img = dm_xasprintf("%s/img", r->run_dir);
    rc = dm_mkdirs(img) == 0 ? 0 : DM_ERR_IO;
    if (rc)
        dm_str_printf(err, "%s: cannot create the run directory", r->run_dir);
    free(img);
    return rc;
}

/* The procedural map sets of the configurations, made once here before
 * any measuring child is forked (render_maps_preload): each child, one a
 * scene, copies them instead of generating them again, and the first
 * configuration of a scene no longer pays the generation in its
 * SetupTime where the others did not.  At most MAPS_MEMO_SETS sets (what
 * the process keeps: more would push out the first). */
static void runner__maps_preload(const runner *r)
{
    size_t made = 0;
    for (size_t i = 0; i < r->p.n_configs && made < MAPS_MEMO_SETS; i++)
        made += (size_t)render_maps_preload(r->p.configs[i].params, r->p.configs[i].n_params);
}

/* 1 when the sweep asks for a counter that is not deterministic (a time):
 * only then do the calibration workload and the kernel around each round
 * mean anything, and a run of deterministic counters alone (a counting
 * gate) leaves them out. */
static int runner__times(const sweep *s)
{
    for (size_t i = 0; i < s->measure.n_counters; i++) {
        const counters_info *ci = counters_find(s->measure.counters[i]);
        if (ci && !ci->deterministic)
            return 1;
    }
    return 0;
}

/* Adds the calibration workload's two figures (run/calibrate.h) to the
 * environment as "calibration_*_ns_<which>": those of *given when it has
 * them (the start's, timed in the driver probe), else timed now in a
 * child. */
static void runner__calibrate(dm_kv **env, size_t *n_env, const char *which,
                              const calibrate_result *given)
{
    calibrate_result c = given ? *given : (calibrate_result){ NAN, NAN };
    if (!isfinite(c.cpu_ns) && calibrate_in_child(&c) != 0)
        dm_log(DM_LOG_WARN, "the %s calibration gave no answer; compare cannot use it", which);
    char buf[32];
    snprintf(buf, sizeof buf, "%.0f", c.cpu_ns);
    dm_kv_push(env, n_env, calibrate_key("cpu", which), buf);
    snprintf(buf, sizeof buf, "%.0f", c.draw_ns);
    dm_kv_push(env, n_env, calibrate_key("draw", which), buf);
}

static int runner__begin(runner *r)
{
    if (r->o->resume)
        return 0;
    dm_run_result *e = &r->env;
    e->id = dm_xstrdup(r->run_id);
    e->sweep = dm_xstrdup(r->s->name);
    char now[32], hash[17];
    dm_iso8601_now(now);
    e->started = dm_xstrdup(now);
    dm_hex64(r->s->hash, hash);
    e->sweep_hash = dm_xstrdup(hash);
    for (size_t i = 0; i < user_technique_count(); i++) {   /* the sources it measures */
        const technique_desc *t = user_technique_at(i);
        char src[17];
        dm_hex64(t->source_hash, src);
        char *key = dm_xasprintf("%s%s", USER_TECHNIQUE_ENV_PREFIX, t->name);
        char *val = dm_xasprintf("%s %s", src, user_technique_path(t));
        dm_kv_push(&e->environment, &e->n_environment, key, val);
        free(key);
        free(val);
    }
    inputs_record(&e->environment, &e->n_environment);   /* and the maps and meshes it reads */
    report_metric_set(e, r->s->pareto_metric);   /* so dmbench report redraws the same front */
    if (r->s->budget_ms > 0)
        report_budget_set(e, r->s->budget_ms);    /* and picks under the same budget */
    if (r->o->shard_n > 0) {
        /* merge checks duplicate and missing shards, and whether each one is
         * complete, from these two entries. */
        char buf[32];
        runner__shard_text(r->o->shard_k, r->o->shard_n, buf);
        dm_kv_push(&e->environment, &e->n_environment, "shard", buf);
        snprintf(buf, sizeof buf, "%zu", r->p.n_configs);
        dm_kv_push(&e->environment, &e->n_environment, "shard_configs", buf);
    }
    char seed[32];   /* the rounds' order (run/measure.c): a run's order can be replayed */
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)(r->o->seed ? r->o->seed : 1));
    dm_kv_push(&e->environment, &e->n_environment, "seed", seed);
    if (r->o->extra_s > 0) {   /* the extra rounds' budget, as given */
        char extra[32];
        snprintf(extra, sizeof extra, "%g", r->o->extra_s);
        dm_kv_push(&e->environment, &e->n_environment, "extra_time_s", extra);
    }
    if (r->times)
        runner__calibrate(&e->environment, &e->n_environment, "start", &r->cal_start);
    char *pub = dm_xasprintf("%s/published.json", r->run_dir);   /* for the report's section */
    int rc = r->s->published ? published_write_json(r->s->published, pub) : 0;
    free(pub);
    rc = rc ? rc : store_run_begin(r->st, e, r->o->tag);
    for (size_t i = 0; rc == 0 && i < r->p.n_left_out; i++)
        rc = store_left_out_put(r->st, r->run_id, &r->p.left_out[i]);
    return rc;
}

static void runner__latest_link(runner *r)
{
    char *link = dm_xasprintf("%s/latest", r->root);
    unlink(link);
    if (symlink(r->run_id, link) != 0)
        dm_log(DM_LOG_WARN, "%s: cannot create the 'latest' link", link);
    free(link);
}

/* Fits the sweep's models to the finished run and stores them. */
static void runner__fit(runner *r, dm_run_result *run)
{
    for (size_t i = 0; i < r->s->n_models; i++) {
        const sweep_model *m = &r->s->models[i];
        fitting_spec spec = { .name = m->name, .formula = m->formula, .response = m->response,
                              .group_by = (const char *const *)m->group_by,
                              .n_group_by = m->n_group_by };
        size_t first = run->n_fits;
        dm_str warn = {0}, err = {0};
        if (fitting_run(&spec, run, &run->fits, &run->n_fits, &warn, &err) != 0)
            dm_str_cat(&warn, dm_str_get(&err));
        for (size_t k = first; k < run->n_fits; k++)
            store_fit_put(r->st, r->run_id, &run->fits[k]);
        char *save = NULL;
        for (char *line = warn.buf ? strtok_r(warn.buf, "\n", &save) : NULL; line;
             line = strtok_r(NULL, "\n", &save)) {
            dm_log(DM_LOG_WARN, "%s", line);
            store_run_warning_put(r->st, r->run_id, line);
            DM_VEC_PUSH(run->warnings, run->n_warnings, dm_xstrdup(line));
        }
        dm_str_free(&warn);
        dm_str_free(&err);
    }
}

/* The end of a run: each scene's recommendation in one or two lines. */
static void runner__print_answer(const dm_run_result *run)
{
    dm_str a = {0};
    report_answer_terminal(run, &a);
    char *safe;
    fputs(dm_term_safe(dm_str_get(&a), &safe), stdout);
    free(safe);
    dm_str_free(&a);
}

static int runner__finish(runner *r, dm_str *err)
{
    char now[32];
    dm_iso8601_now(now);
    store_run_finish(r->st, r->run_id, now);
    dm_run_result run = {0};
    int rc = store_run_load(r->st, r->run_id, &run);
    if (rc == 0 && r->times && !dm_kv_get(run.environment, run.n_environment, calibrate_key("cpu", "end"))) {
        size_t had = run.n_environment;
        runner__calibrate(&run.environment, &run.n_environment, "end", NULL);
        for (size_t i = had; i < run.n_environment; i++)
            store_run_env_put(r->st, r->run_id, run.environment[i].key, run.environment[i].value);
    }
    if (rc == 0) {
        precision_apply(&run, r->o->seed ? r->o->seed : 1);   /* the drift removed, raw kept */
        if (store_precision_put(r->st, r->run_id, &run) != 0)
            dm_log(DM_LOG_WARN, "cannot store the figures with the drift removed: %s",
                   store_last_error(r->st));
        if (!r->o->quiet)
            precision_print(&run, r->s->measure.target_ci, stderr);
        runner__fit(r, &run);
        char e[512] = "";
        report_trends tr;
        run_trends(r->st, &run, &tr);   /* none on a store failure: the report goes on */
        rc = report_write_run(&run, &(report_desc){.dir = r->run_dir, .trends = &tr}, e, sizeof e);
        report_trends_free(&tr);
        if (rc)
            dm_str_printf(err, "report: %s", e);
        else if (!r->o->quiet)
            runner__print_answer(&run);
    } else {
        dm_str_printf(err, "store: cannot reload run %s: %s", r->run_id, store_last_error(r->st));
    }
    dm_run_free(&run);
    runner__latest_link(r);
    return rc;
}

static void runner__free(runner *r)
{
    if (r->lock_fd >= 0)
        close(r->lock_fd);
    dm_str_free(&r->stop);
    dm_str_free(&r->extra_lines);
    inputs_clear();
    plan_free(&r->p);
    store_close(r->st);
    free(r->root);
    free(r->run_id);
    free(r->store_path);
    free(r->cache_dir);
    for (size_t i = 0; i < r->n_exts; i++)
        free(r->exts[i]);
    free(r->exts);
    free(r->instr_why);
    callgrind_counts_free(r->instr, r->n_instr);
    free(r->instr);
    dm_run_free(&r->env);
}

/* Progress of planning on stderr: a line once a second after the first
 * second (on a terminal one line rewritten), so a big sweep is not silent. */
typedef struct runner__plan_tick {
    const runner *r;
    int64_t t0, last;
    int shown;
} runner__plan_tick;

static void runner__plan_progress(size_t done, size_t total, void *user)
{
    runner__plan_tick *t = user;
    int64_t now = dm_now_ns();
    if (t->r->o->quiet || (now - t->last < 1000000000 && done < total) ||
        (done == total && !t->shown) || now - t->t0 < 1000000000)
        return;
    t->last = now;
    t->shown = 1;
    fprintf(stderr, "%sdmbench: planning: %zu of %zu combinations (%.0f s)%s",
            t->r->tty ? "\r\033[K" : "", done, total, (double)(now - t->t0) / 1e9,
            t->r->tty && done < total ? "" : "\n");
}

static int runner__plan(runner *r, dm_str *err)
{
    runner__plan_tick t = { .r = r, .t0 = dm_now_ns() };
    t.last = t.t0;
    plan_build_desc d = { .progress = runner__plan_progress, .user = &t };
    return plan_build(r->s, &d, &r->p, err);
}

/* A decimal number in [lo, hi] spanning exactly [text, text+len): no sign,
 * no spaces; -1 when it is not one. */
static long long runner__decimal(const char *text, size_t len, long long lo, long long hi)
{
    if (len == 0 || len > 18)
        return -1;
    long long v = 0;
    for (size_t i = 0; i < len; i++) {
        if (text[i] < '0' || text[i] > '9')
            return -1;
        v = v * 10 + (text[i] - '0');
    }
    return v >= lo && v <= hi ? v : -1;
}

int runner_parse_shard(const char *text, int *k, int *n, dm_str *err)
{
    const char *slash = strchr(text, '/');
    long long kk = slash ? runner__decimal(text, (size_t)(slash - text), 1, 1000000) : -1;
    long long nn = slash ? runner__decimal(slash + 1, strlen(slash + 1), 1, 1000000) : -1;
    if (kk < 1 || nn < 1 || kk > nn) {
        dm_str_printf(err, "--shard '%s': expected K/N with 1 <= K <= N <= 1000000, e.g. 2/4", text);
        return DM_ERR_ARG;
    }
    *k = (int)kk;
    *n = (int)nn;
    return 0;
}

int runner_parse_seed(const char *text, uint64_t *seed, dm_str *err)
{
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (!(text[0] >= '0' && text[0] <= '9') || *end || errno == ERANGE) {
        dm_str_printf(err, "--seed '%s': expected a non-negative integer below 2^64", text);
        return DM_ERR_ARG;
    }
    *seed = v;
    return 0;
}

/* A line for the user on stderr, word-wrapped to RUNNER__COLUMNS (the
 * continuation indented four columns, as the answer). */
#define RUNNER__COLUMNS 100
static void runner__say(const char *text)
{
    dm_str s = {0};
    dm_wrap(text, "", "    ", RUNNER__COLUMNS, &s);
    fputs(dm_str_get(&s), stderr);
    dm_str_free(&s);
}

int runner_run(const sweep *s, const runner_opts *o, char **run_dir, dm_str *err)
{
    runner r = { .s = s, .o = o, .tty = isatty(2), .t_start = dm_now_ns(), .lock_fd = -1,
                 .times = runner__times(s) };
    /* llvmpipe rasterizes on one thread per core; on shared machines that
     * makes fenced timings several times noisier (docs/llvmpipe-findings.md), so measuring
     * processes use one rasterizer thread unless the user chose otherwise.
     * The value is recorded in the environment and the fingerprint. */
    int rc = env_check(err);                      /* the user's LP_NUM_THREADS, before it is recorded */
    setenv("LP_NUM_THREADS", "1", 0);
    rc = rc ? rc : fitting_check_models(s, err);  /* models: fail now, not after the run */
    rc = rc ? rc : runner__plan(&r, err);
    rc = rc ? rc : published_resolve(s->published, &r.p, s->path, err);   /* labels: exit 2 now */
    if (rc == 0 && o->shard_n && (rc = plan_shard(&r.p, o->shard_k, o->shard_n)) != 0)
        dm_str_printf(err, "--shard %d/%d: expected K/N with 1 <= K <= N", o->shard_k, o->shard_n);
    rc = rc ? rc : runner_child_probe(&r, err);
    if (rc == 0)
        plan_filter_capabilities(&r.p, runner_child_has_ext, &r);
    if (rc == 0 && o->dry_run) {
        runner_plan_dry_run(&r);
        runner__free(&r);
        return 0;
    }
    inputs_clear();
    rc = rc ? rc : inputs_collect(&r.p, err);     /* the maps and meshes: one version a run */
    rc = rc ? rc : runner__open(&r, err);
    if (rc == 0 && o->budget_s > 0 && !o->resume)
        runner_plan_budget(&r);
    rc = rc ? rc : runner__begin(&r);
    if (rc == 0) {
        r.total = r.p.n_configs;
        char *name_buf = NULL;
        if (!o->quiet) {
            dm_str line = {0};
            dm_str_printf(&line, "dmbench: %s: %zu combinations -> %zu configurations "
                          "(%zu excluded by the sweep, %zu folded: axes the technique does not "
                          "read), %zu left out; run %s",
                          dm_term_safe(s->name, &name_buf), r.p.n_combinations,
                          r.p.n_configs + r.p.n_left_out, r.p.n_excluded,
                          r.p.n_combinations - r.p.n_excluded - r.p.n_configs - r.p.n_left_out,
                          r.p.n_left_out, r.run_dir);
            runner__say(dm_str_get(&line));
            dm_str_free(&line);
        }
        free(name_buf);
        runner__maps_preload(&r);
        int changed = runner_child_instructions(&r, err);
        rc = changed ? changed : runner_child_scenes(&r);
        if (rc == 0 && !o->quiet)
            runner_child_extra_print(&r, stderr);
        if (rc == DM_ERR_ARG && !changed)   /* a measuring child found a user file changed */
            dm_str_printf(err, "%s; one run measures one version of each file: stopped the run "
                          "before it recorded anything for it; the %zu configurations committed "
                          "before are kept: restore the file and continue with --resume, or start "
                          "a new run", dm_str_get(&r.stop), runner__committed(&r));
        else if (rc != 0 && !changed)
            dm_str_printf(err, "%s; stopped the run: the %zu configurations committed before are "
                          "kept, continue with --resume once the cause is fixed",
                          dm_str_get(&r.stop), runner__committed(&r));
        rc = rc ? rc : runner__finish(&r, err);
        double wall = (double)(dm_now_ns() - r.t_start) / 1e9, meas = (double)r.measured_ns / 1e9;
        if (!o->quiet) {
            dm_str line = {0};
            dm_str_printf(&line, "dmbench: %zu configurations (%zu failed) in %.1f s; %.1f s in "
                          "measured frames, %.0f%% of the time outside them (setup, warm-up, "
                          "statistics, images)", r.done, r.failed, wall, meas,
                          wall > 0 ? 100 * (1 - meas / wall) : 0);
            runner__say(dm_str_get(&line));
            dm_str_free(&line);
        }
    }
    if (rc == 0 && run_dir)
        *run_dir = dm_xstrdup(r.run_dir);
    free(r.run_dir);
    runner__free(&r);
    return rc;
}
