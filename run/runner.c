/* runner.c — orchestration of a run in the parent process (see runner.h). */
#include "runner.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "counters/counters.h"
#include "run/calibrate.h"
#include "run/callgrind.h"
#include "run/env.h"
#include "run/fitting.h"
#include "run/gl_context.h"
#include "run/inputs.h"
#include "run/measure.h"
#include "run/probe.h"
#include "run/predict.h"
#include "run/protocol.h"
#include "run/trends.h"
#include "sweep/plan.h"
#include "sweep/published.h"
#include "store/store.h"
#include "reports/answer.h"
#include "reports/metric.h"
#include "reports/report.h"
#include "techniques/axes.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct runner {
    const sweep *s;
    const runner_opts *o;
    plan p;
    store *st;
    char *root, *run_id, *run_dir, *store_path, *cache_dir;
    dm_run_result env;         /* environment + timer of the run */
    char **exts;               /* extensions the driver has (of those techniques need) */
    size_t n_exts;
    size_t done, total, failed;
    int64_t t_start;
    int64_t t_last;            /* the last progress line (ns) */
    size_t eta_done;           /* configurations done at the end of the last burst, */
    double eta_el;             /* and the seconds it took: the ETA's rate */
    int64_t measured_ns;       /* time inside timed samples, all configurations */
    int tty;
    char *instr_why;           /* why Instructions cannot be counted here; NULL = it can */
    callgrind_count *instr;    /* the Instructions pass (run/callgrind.h) */
    size_t n_instr;
    double instr_s;            /* wall time of that pass */
    int lock_fd;               /* flock on <out>/dmbench.lock, -1 when none */
    int futile;                /* measuring processes in a row that finished nothing */
    dm_str stop;               /* why the run stopped before its end (store failure, ...) */
} runner;

/* ---- the probe child: environment, timer calibration, extensions ------- */

static void runner__probe_child(int fd, void *arg)
{
    (void)arg;
    gl_context *gl = NULL;
    dm_str err = {0}, out = {0};
    if (gl_context_create(NULL, &gl, &err) != 0) {
        dm_str_printf(&out, "F\t%s\n", dm_str_get(&err));
    } else {
        dm_kv *kv = NULL;
        size_t n = 0;
        env_collect(&kv, &n, 1);
        for (size_t i = 0; i < n; i++)
            dm_str_printf(&out, "E\t%s\t%s\n", kv[i].key, kv[i].value);
        counters_context *cc = NULL;
        counters_timer_calibration cal = { .verdict = "unavailable" };
        if (counters_context_create(&cc) == 0)
            counters_calibrate_timer(cc, &cal);
        dm_str_printf(&out, "T\t%.6f\t%s\n", cal.coverage, cal.verdict);
        const char *why = NULL;
        if (cc && !counters_available(cc, "Instructions", &why))
            dm_str_printf(&out, "C\t%s\n", why ? why : "unavailable");
        for (size_t i = 0; i < technique_count(); i++) {
            const char *ext = technique_at(i)->requires_ext;
            if (ext && epoxy_has_gl_extension(ext))
                dm_str_printf(&out, "X\t%s\n", ext);
        }
        for (size_t i = 0; axes_value_ext_at(i); i++)
            if (epoxy_has_gl_extension(axes_value_ext_at(i)))
                dm_str_printf(&out, "X\t%s\n", axes_value_ext_at(i));
        counters_context_destroy(cc);
        dm_kv_free(kv, n);
        gl_context_destroy(gl);
    }
    ssize_t w = write(fd, out.buf, out.len);
    (void)w;
    dm_str_free(&err);
    dm_str_free(&out);
}

/* Reads everything a child writes until EOF or timeout; returns the text. */
static char *runner__read_all(int fd, int timeout_ms)
{
    dm_str s = {0};
    char buf[4096];
    struct pollfd pfd = { fd, POLLIN, 0 };
    while (poll(&pfd, 1, timeout_ms) > 0) {
        ssize_t n = read(fd, buf, sizeof buf);
        if (n <= 0)
            break;
        dm_str_catn(&s, buf, (size_t)n);
    }
    return dm_str_take(&s);
}

/* The driver probe: environment, timer calibration and extensions from a
 * child (run/probe.h: it may hang or crash, and the run must not); then
 * every user technique compiled in a child of its own.  Returns 0,
 * DM_ERR_GL (no usable driver, message in err) or the user check's code. */
static int runner__probe(runner *r, dm_str *err)
{
    dm_proc_result res;
    dm_proc_collect(runner__probe_child, NULL, probe_timeout_s(), &res);
    char *text = res.text;
    int rc = 0;
    r->env.timer_verdict = dm_xstrdup("unavailable");
    char *save = NULL;
    for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char *f1 = strchr(line, '\t'), *f2 = f1 ? strchr(f1 + 1, '\t') : NULL;
        if (f1)
            *f1++ = '\0';
        if (f2)
            *f2++ = '\0';
        if (line[0] == 'F' && f1) {
            dm_str_cat(err, f1);
            rc = DM_ERR_GL;
        } else if (line[0] == 'E' && f2) {
            dm_kv_push(&r->env.environment, &r->env.n_environment, f1, f2);
        } else if (line[0] == 'T' && f2) {
            r->env.gpu_time_coverage = strtod(f1, NULL);
            free(r->env.timer_verdict);
            r->env.timer_verdict = dm_xstrdup(f2);
        } else if (line[0] == 'C' && f1) {
            r->instr_why = dm_xstrdup(f1);
        } else if (line[0] == 'X' && f1) {
            DM_VEC_PUSH(r->exts, r->n_exts, dm_xstrdup(f1));
        }
    }
    free(text);
    if (rc == 0 && !dm_kv_get(r->env.environment, r->env.n_environment, "renderer")) {
        if (res.started)
            probe_no_answer("the driver probe", res.timed_out, res.status, res.seconds, err);
        else
            dm_str_printf(err, "cannot start the driver probe: %s", strerror(res.status));
        rc = DM_ERR_GL;
    }
    env_fingerprint(&r->env.environment, &r->env.n_environment);
    return rc ? rc : probe_user_techniques(err);
}

static int runner__has_ext(const char *ext, void *user)
{
    runner *r = user;
    for (size_t i = 0; i < r->n_exts; i++)
        if (strcmp(r->exts[i], ext) == 0)
            return 1;
    return 0;
}

/* ---- progress ------------------------------------------------------------ */

/* The configuration's label for progress lines: "plane 480×270 · pom
 * steps=8", the technique with the axes that take two or more values among
 * the plan's configurations of its scene. */
static void runner__label(const runner *r, const plan_config *c, dm_str *out)
{
    const char **all = dm_xcalloc(r->p.n_configs + 1, sizeof *all);
    for (size_t i = 0; i < r->p.n_configs; i++)
        all[i] = r->p.configs[i].scene;
    report_scene_label_among(c->scene, all, r->p.n_configs, out);   /* as the report names it */
    free(all);
    dm_str_printf(out, " · %s", dm_kv_get(c->params, c->n_params, "technique"));
    for (size_t k = 0; k < c->n_params; k++) {
        if (strcmp(c->params[k].key, "technique") == 0)
            continue;
        int varies = 0;
        for (size_t i = 0; i < r->p.n_configs && !varies; i++) {
            const plan_config *o = &r->p.configs[i];
            const char *v = strcmp(o->scene, c->scene) == 0 ? dm_kv_get(o->params, o->n_params, c->params[k].key) : NULL;
            varies = v && strcmp(v, c->params[k].value) != 0;
        }
        if (varies)
            dm_str_printf(out, " %s=%s", c->params[k].key, c->params[k].value);
    }
}

/* "  ETA 42s" from the rate of the finished bursts (a scene's configurations
 * finish together after its rounds), so the estimate never extrapolates
 * from the first, slowest moments; "" until a burst has finished. */
static void runner__eta(runner *r, char *buf, size_t len)
{
    int64_t now = dm_now_ns();
    if (r->done > 1 && now - r->t_last > 500000000)   /* a new burst: the previous one ended at t_last */
        r->eta_done = r->done - 1, r->eta_el = (double)(r->t_last - r->t_start) / 1e9;
    r->t_last = now;
    buf[0] = 0;
    if (r->eta_done && r->done < r->total)
        snprintf(buf, len, "  ETA %.0fs", r->eta_el / (double)r->eta_done * (double)(r->total - r->done));
}

static void runner__progress(runner *r, const plan_config *c, const char *status,
                             double median_ns, double ci_rel)
{
    r->done++;
    r->failed += strcmp(status, "ok") != 0;
    if (r->o->quiet)
        return;
    char eta[48];
    runner__eta(r, eta, sizeof eta);
    dm_str label = {0}, line = {0};
    runner__label(r, c, &label);
    if (strcmp(status, "ok") == 0)
        dm_str_printf(&line, "[%zu/%zu] %-44s %9.3f ms ±%4.1f%%%s", r->done, r->total,
                      dm_str_get(&label), median_ns / 1e6, ci_rel * 100, eta);
    else
        dm_str_printf(&line, "[%zu/%zu] %-44s FAILED (%s)%s", r->done, r->total, dm_str_get(&label),
                      status, eta);
    char *b;
    const char *safe = dm_term_safe(dm_str_get(&line), &b);   /* a scene names a user's map path */
    if (r->tty)
        fprintf(stderr, "\r\033[K%s%s", safe, r->done == r->total ? "\n" : "");
    else
        fprintf(stderr, "%s\n", safe);
    free(b);
    dm_str_free(&label);
    dm_str_free(&line);
}

/* ---- scene children -------------------------------------------------------- */

static const plan_config *runner__find(const plan_config *cs, size_t n, const char *key)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(cs[i].key, key) == 0)
            return &cs[i];
    return NULL;
}

/* Records a configuration the child could not finish (crash, hang).
 * Returns 0, or DM_ERR_STORE (message in r->stop) when it cannot be saved. */
static int runner__fail_config(runner *r, const plan_config *c, const char *reason)
{
    dm_config_result out = { .key = dm_xstrdup(c->key), .scene = dm_xstrdup(c->scene),
                             .ok = 0, .reason = dm_xstrdup(reason) };
    for (size_t i = 0; i < c->n_params; i++)
        dm_kv_push(&out.params, &out.n_params, c->params[i].key, c->params[i].value);
    int rc = store_config_put(r->st, r->run_id, &out) == 0 ? 0 : DM_ERR_STORE;
    if (rc)
        dm_str_printf(&r->stop, "cannot save configuration %s: %s", c->key,
                      store_last_error(r->st));
    dm_config_result_free(&out);
    if (rc == 0)
        runner__progress(r, c, reason, NAN, NAN);
    return rc;
}

typedef struct child_watch {
    pid_t pid;
    int fd;
    char current[17];
    int64_t last_ns;
    dm_str line;
} child_watch;

/* Handles one line of child output; returns 1 when a config was finished. */
static void runner__child_line(runner *r, child_watch *w, const plan_config *cs, size_t n,
                               char *line, int *done_flags)
{
    char key[17] = "", status[16] = "";
    double med = NAN, ci = NAN;
    long long sampled = 0;
    if (line[0] == 'B' && sscanf(line, "B %16s", key) == 1) {
        snprintf(w->current, sizeof w->current, "%s", key);
    } else if (line[0] == 'D' && sscanf(line, "D %16s %15s %lf %lf %lld", key, status, &med, &ci, &sampled) >= 2) {
        const plan_config *c = runner__find(cs, n, key);
        r->measured_ns += sampled;
        if (c) {
            done_flags[c - cs] = 1;
            runner__progress(r, c, status, med, ci);
        }
        w->current[0] = '\0';
    }
}

static pid_t runner__spawn(runner *r, const plan_config *cs, size_t n, int *fd, int pilot)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -1;
    pid_t pid = dm_proc_fork();   /* a killed runner takes its child along */
    if (pid == 0) {
        close(fds[0]);
        measure_job job = { .sweep = r->s, .configs = cs, .n_configs = n, .run_id = r->run_id,
                            .run_dir = r->run_dir, .store_path = r->store_path,
                            .cache_dir = r->cache_dir,
                            .seed = r->o->seed ? r->o->seed : 1,
                            .timer_partial = strcmp(r->env.timer_verdict, "full") != 0,
                            .report_fd = fds[1], .instructions = r->instr,
                            .n_instructions = r->n_instr };
        dm_str err = {0};
        int rc = pilot ? measure_pilot(&job, &err) : measure_scene(&job, &err);
        if (rc != 0)   /* 'S': the store cannot take results; 'F': anything else */
            dprintf(fds[1], "%c %s\n", rc == DM_ERR_STORE ? 'S' : 'F', dm_str_get(&err));
        _exit(rc ? 3 : 0);
    }
    close(fds[1]);
    *fd = fds[0];
    return pid;
}

/* Watches one child until it exits or the watchdog kills it.  Returns the
 * wait status (or -1 for a watchdog kill). */
static int runner__watch(runner *r, child_watch *w, const plan_config *cs, size_t n, int *done_flags,
                         char **fatal)
{
    double timeout_s = r->s->measure.timeout_s;
    w->last_ns = dm_now_ns();
    for (;;) {
        struct pollfd pfd = { w->fd, POLLIN, 0 };
        int pr = poll(&pfd, 1, 250);
        if (pr > 0) {
            char buf[4096];
            ssize_t got = read(w->fd, buf, sizeof buf);
            if (got <= 0)
                break;
            w->last_ns = dm_now_ns();
            for (ssize_t i = 0; i < got; i++) {
                if (buf[i] != '\n') {
                    dm_str_catn(&w->line, &buf[i], 1);
                    continue;
                }
                char *line = dm_str_take(&w->line);
                if ((line[0] == 'F' || line[0] == 'S' || line[0] == 'C') && line[1] && !*fatal)
                    *fatal = dm_xstrdup(line);
                runner__child_line(r, w, cs, n, line, done_flags);
                free(line);
            }
        } else if ((double)(dm_now_ns() - w->last_ns) / 1e9 > timeout_s) {
            kill(w->pid, SIGKILL);
            waitpid(w->pid, NULL, 0);
            return -1;
        }
    }
    int status = 0;
    waitpid(w->pid, &status, 0);
    return status;
}

/* Measuring processes in a row that may finish no configuration before the
 * run stops: a child that keeps dying before it saves anything (it cannot
 * set up, its store cannot be written) would otherwise be restarted forever. */
#define RUNNER__MAX_FUTILE 3

/* Why a child ended early (caller frees), or NULL when it just finished. */
static char *runner__child_why(const runner *r, int status, const char *fatal)
{
    if (status == -1)
        return dm_xasprintf("killed by the watchdog: no progress for %.0f s (measure.timeout_s)",
                            r->s->measure.timeout_s);
    if (WIFSIGNALED(status))
        return dm_xasprintf("the measuring process crashed (signal %d, %s)", WTERMSIG(status),
                            strsignal(WTERMSIG(status)));
    if (fatal)
        return dm_xasprintf("could not set up: %s", fatal + 2);
    return NULL;
}

/* Accounts one ended child: a store failure or a changed user file ('C')
 * stops the run at once; a child that finished nothing counts towards
 * RUNNER__MAX_FUTILE.  Returns 0 to go on, DM_ERR_STORE / DM_ERR_ARG /
 * DM_ERR_CHILD (reason in r->stop) to stop. */
static int runner__child_end(runner *r, const char *fatal, const char *why, size_t finished)
{
    if (fatal && fatal[0] == 'C') {   /* a user file changed: nothing was recorded for it */
        dm_str_cat(&r->stop, fatal + 2);
        return DM_ERR_ARG;
    }
    if (fatal && fatal[0] == 'S') {
        dm_str_printf(&r->stop, "the measuring process cannot save results: %s", fatal + 2);
        return DM_ERR_STORE;
    }
    r->futile = finished ? 0 : r->futile + 1;
    if (r->futile < RUNNER__MAX_FUTILE)
        return 0;
    dm_str_printf(&r->stop, "%d measuring processes in a row finished no configuration (last: %s)",
                  RUNNER__MAX_FUTILE, why ? why : "it exited without a result");
    return DM_ERR_CHILD;
}

/* Runs one child on the configurations not done yet and records what it
 * finished in done[]; returns 0 or the code that stops the run. */
static int runner__scene_child(runner *r, const plan_config *cs, size_t n, int *done,
                               plan_config *remaining, size_t nt)
{
    child_watch w = { .current = "" };
    w.pid = runner__spawn(r, remaining, nt, &w.fd, 0);
    char *fatal = NULL;
    int *tdone = dm_xcalloc(nt + 1, sizeof *tdone);
    int status = runner__watch(r, &w, remaining, nt, tdone, &fatal);
    close(w.fd);
    dm_str_free(&w.line);
    size_t finished = 0;
    for (size_t i = 0; i < nt; i++)
        if (tdone[i]) {
            done[runner__find(cs, n, remaining[i].key) - cs] = 1;
            finished++;
        }
    const plan_config *cur = w.current[0] ? runner__find(cs, n, w.current) : NULL;
    char *why = runner__child_why(r, status, fatal);
    int failing = why || (WIFEXITED(status) && WEXITSTATUS(status) != 0);
    int rc = runner__child_end(r, fatal, why, finished + failing);
    if (rc == 0 && why && cur) {
        rc = runner__fail_config(r, cur, why);
        done[cur - cs] = 1;
    } else if (rc == 0 && failing) {
        for (size_t i = 0; rc == 0 && i < n; i++)      /* no culprit: fail what is left */
            if (!done[i]) {
                rc = runner__fail_config(r, &cs[i], why ? why : "the measuring process failed");
                done[i] = 1;
            }
    }
    free(why);
    free(fatal);
    free(tdone);
    return rc;
}

/* Measures one scene, restarting a child after each crash or hang (at most
 * RUNNER__MAX_FUTILE in a row that finish nothing).  Returns 0, or the code
 * that stops the run with the reason in r->stop. */
static int runner__scene(runner *r, const plan_config *cs, size_t n)
{
    int *done = dm_xcalloc(n + 1, sizeof *done);
    int rc = 0;
    for (size_t i = 0; i < n; i++)
        done[i] = store_config_done(r->st, r->run_id, cs[i].key) == 1;
    while (rc == 0) {
        plan_config *remaining = dm_xcalloc(n + 1, sizeof *remaining);
        size_t nt = 0;
        for (size_t i = 0; i < n; i++)
            if (!done[i])
                remaining[nt++] = cs[i];
        if (nt == 0) {
            free(remaining);
            break;
        }
        rc = runner__scene_child(r, cs, n, done, remaining, nt);
        free(remaining);
    }
    free(done);
    return rc;
}

/* ---- --budget: a stored cost model, else a pilot frame ------------------------ */

/* Earlier runs searched for a cost model and counters (newest first). */
#define RUNNER__BUDGET_RUNS 16

/* Predicted seconds to measure a configuration from its frame time, as the
 * protocol sees it (run/protocol.h: protocol_predict_s). */
static double runner__predict(const sweep_measure *m, double frame_ns)
{
    protocol_desc d;
    protocol_desc_from_measure(&d, m, 0);
    return protocol_predict_s(&d, frame_ns);
}

/* What --budget knows from the store: earlier runs (newest first) and the
 * frame-time fits usable for predictions, sweep's own models first. */
typedef struct runner_budget {
    dm_run_result *runs;
    size_t n_runs;
    const dm_fit_result **fits;
    size_t n_fits;
    const char *fits_run;      /* run the fits come from */
    size_t by_model, by_pilot, by_instr;
    predict_model pm;          /* the instruction models of the stored runs (run/predict.h) */
    size_t pm_runs;            /* how many runs they were fitted to; 0: none */
} runner_budget;

static int runner__fit_usable(const dm_fit_result *f)
{
    return f->response && strcmp(f->response, "WallTime") == 0 && f->formula;
}

/* Position of the fit's model among the sweep's models, n_models if absent. */
static size_t runner__fit_rank(const runner *r, const dm_fit_result *f)
{
    size_t j = 0;
    while (j < r->s->n_models && strcmp(r->s->models[j].name, f->model) != 0)
        j++;
    return j;
}

/* Takes the usable fits of the newest run that has any: first those named
 * like the sweep's models (in the sweep's order), then the others. */
static void runner__budget_fits(runner *r, runner_budget *b)
{
    for (size_t k = 0; k < b->n_runs && b->n_fits == 0; k++) {
        const dm_run_result *run = &b->runs[k];
        b->fits = dm_xrealloc(b->fits, (run->n_fits + 1) * sizeof *b->fits);
        for (size_t rank = 0; rank <= r->s->n_models; rank++)
            for (size_t i = 0; i < run->n_fits; i++)
                if (runner__fit_rank(r, &run->fits[i]) == rank && runner__fit_usable(&run->fits[i]))
                    b->fits[b->n_fits++] = &run->fits[i];
        b->fits_run = b->n_fits ? run->id : NULL;
    }
}

/* 1 when a stored run was measured in this run's environment (same
 * fingerprint: renderer, GL version, LP_NUM_THREADS, CPU), so its frame
 * times and counters apply here. */
static int runner__same_machine(const runner *r, const dm_run_result *run)
{
    const char *a = dm_kv_get(run->environment, run->n_environment, "fingerprint");
    const char *b = dm_kv_get(r->env.environment, r->env.n_environment, "fingerprint");
    return a && b && strcmp(a, b) == 0;
}

/* Loads up to RUNNER__BUDGET_RUNS earlier runs of the store made on this
 * machine (newest first). */
static void runner__budget_load(runner *r, runner_budget *b)
{
    char **ids = NULL;
    size_t n = 0;
    if (store_list_runs(r->st, &ids, &n) != 0)
        n = 0;
    b->runs = dm_xcalloc(n + 1, sizeof *b->runs);
    for (size_t i = 0; i < n; i++) {
        dm_run_result *run = &b->runs[b->n_runs];
        if (b->n_runs < RUNNER__BUDGET_RUNS && store_run_load(r->st, ids[i], run) == 0) {
            if (runner__same_machine(r, run))
                b->n_runs++;
            else
                dm_run_free(run);
        }
        free(ids[i]);
    }
    free(ids);
    runner__budget_fits(r, b);
}

/* Fits the instruction models to the stored runs that have the counters
 * they read and WallTime (docs/models.md, "Prediction"). */
static void runner__budget_instr_models(runner_budget *b)
{
    dm_run_result *use = dm_xcalloc(b->n_runs + 1, sizeof *use);
    size_t n = 0;
    for (size_t k = 0; k < b->n_runs; k++) {
        if (dm_run_has_counter(&b->runs[k], "WallTime") && !predict_run_missing(&b->runs[k]))
            use[n++] = b->runs[k];   /* shallow: b->runs owns them */
    }
    if (n)
        predict_fit(use, n, &b->pm);
    b->pm_runs = n;
    free(use);
}

static void runner__budget_free(runner_budget *b)
{
    if (b->pm_runs)
        predict_free(&b->pm);
    for (size_t i = 0; i < b->n_runs; i++)
        dm_run_free(&b->runs[i]);
    free(b->runs);
    free(b->fits);
}

/* Leaves out the configuration with that key, if it is still planned. */
static void runner__leave_out_key(runner *r, const char *key, const char *why)
{
    for (size_t i = 0; i < r->p.n_configs; i++)
        if (strcmp(r->p.configs[i].key, key) == 0) {
            plan_leave_out(&r->p, i, why);
            return;
        }
}

/* Frame time (ns) of a planned configuration from the first stored fit that
 * can evaluate it; the fit in *used, or NULL (then NaN). */
static double runner__model_frame(const runner_budget *b, const plan_config *c,
                                  const dm_fit_result **used)
{
    *used = NULL;
    for (size_t i = 0; i < b->n_fits; i++) {
        double ns;
        dm_str why = {0};
        int rc = fitting_predict(b->fits[i], c->params, c->n_params, c->key, b->runs,
                                 b->n_runs, &ns, &why);
        if (rc != 0)   /* --verbose says why a pilot frame decides instead */
            dm_log(DM_LOG_DEBUG, "--budget %s: model %s cannot predict it: %s", c->key,
                   b->fits[i]->model, dm_str_get(&why));
        dm_str_free(&why);
        if (rc == 0) {
            *used = b->fits[i];
            return ns;
        }
    }
    return NAN;
}

/* The configurations with a model prediction are decided now; the others
 * are copied to pilot[] (returned count) for a pilot frame. */
static size_t runner__budget_by_model(runner *r, runner_budget *b, plan_config *pilot,
                                      char (*over)[17], char **why)
{
    size_t n_pilot = 0, n_over = 0;
    for (size_t i = 0; i < r->p.n_configs; i++) {
        const plan_config *c = &r->p.configs[i];
        const dm_fit_result *fit;
        double ns = runner__model_frame(b, c, &fit), t = runner__predict(&r->s->measure, ns);
        if (!fit) {
            pilot[n_pilot++] = *c;
            continue;
        }
        b->by_model++;
        if (t <= r->o->budget_s)
            continue;
        memcpy(over[n_over], c->key, sizeof over[n_over]);
        why[n_over++] = dm_xasprintf("over --budget %g s: model %s (run %s, cross-validated error "
                                     "%.0f%%) predicts %.3g ms/frame, so measuring would take "
                                     "about %.2g s", r->o->budget_s, fit->model, b->fits_run,
                                     fit->cv_mape, ns / 1e6, t);
    }
    for (size_t k = 0; k < n_over; k++) {
        runner__leave_out_key(r, over[k], why[k]);
        free(why[k]);
    }
    return n_pilot;
}

/* Runs the pilot child on configs and leaves out what would blow the budget. */
static void runner__budget_pilot(runner *r, runner_budget *b, const plan_config *cs, size_t n)
{
    int fd = -1;
    pid_t pid = runner__spawn(r, cs, n, &fd, 1);
    char *text = runner__read_all(fd, (int)(r->s->measure.timeout_s * 1000));
    close(fd);
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    runner__budget_instr_models(b);
    char *save = NULL;
    for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char key[17];
        int used = 0;
        double ns = NAN, counts[PREDICT_N_COUNTS];
        if (sscanf(line, "P %16s %lf%n", key, &ns, &used) != 2)
            continue;
        char *p = line + used;
        for (size_t k = 0; k < PREDICT_N_COUNTS; k++)
            counts[k] = strtod(p, &p);
        /* The instruction models when they predict it (a frame time from
         * quiet runs' fits, not one cold frame), else the pilot frame. */
        const plan_config *pc = NULL;
        for (size_t i = 0; i < n && !pc; i++)
            pc = strcmp(cs[i].key, key) == 0 ? &cs[i] : NULL;
        predict_result pr = { .wall_ns = NAN };
        dm_str pwhy = {0};
        int by_instr = pc && b->pm_runs && predict_config(&b->pm, pc, counts, &pr, &pwhy) == 0 &&
                       isfinite(pr.wall_ns) && pr.wall_ns > 0;
        if (pc && b->pm_runs && !by_instr)   /* --verbose says why the pilot frame decides */
            dm_log(DM_LOG_DEBUG, "--budget %s: the instruction models cannot predict it: %s", key,
                   pwhy.len ? dm_str_get(&pwhy) : "no WallTime fit");
        dm_str_free(&pwhy);
        double frame = by_instr ? pr.wall_ns : ns, t = runner__predict(&r->s->measure, frame);
        b->by_instr += by_instr;
        b->by_pilot += !by_instr;
        if (isfinite(frame) && t > r->o->budget_s) {
            char *why = by_instr
                ? dm_xasprintf("over --budget %g s: the instruction models (%zu stored run%s) predict "
                               "%.4g instructions and %.3g ms/frame [%.3g, %.3g], so measuring would take "
                               "about %.2g s", r->o->budget_s, b->pm_runs, b->pm_runs == 1 ? "" : "s", pr.instr,
                               frame / 1e6, pr.wall_lo / 1e6, pr.wall_hi / 1e6, t)
                : dm_xasprintf("over --budget %g s: a pilot frame took %.3g ms, so measuring "
                               "would take about %.2g s", r->o->budget_s, ns / 1e6, t);
            runner__leave_out_key(r, key, why);
            free(why);
        }
        predict_result_free(&pr);
    }
    free(text);
}

/* --budget: predicts each configuration's measuring time from a stored
 * cost model when one can be evaluated for it before measuring, else from a
 * pilot frame, and leaves out what would exceed the budget. */
static void runner__budget(runner *r)
{
    runner_budget b = {0};
    size_t n = r->p.n_configs, before = r->p.n_left_out;
    plan_config *pilot = dm_xcalloc(n + 1, sizeof *pilot);
    char (*over)[17] = dm_xcalloc(n + 1, sizeof *over);
    char **why = dm_xcalloc(n + 1, sizeof *why);
    runner__budget_load(r, &b);
    size_t n_pilot = runner__budget_by_model(r, &b, pilot, over, why);
    if (n_pilot)
        runner__budget_pilot(r, &b, pilot, n_pilot);
    if (!r->o->quiet)
        fprintf(stderr, "dmbench: --budget %g s: %zu configurations predicted by a cost model%s%s%s, "
                "%zu by the instruction models, %zu by a pilot frame; %zu left out\n", r->o->budget_s,
                b.by_model, b.fits_run ? " (run " : "", b.fits_run ? b.fits_run : "", b.fits_run ? ")" : "",
                b.by_instr, b.by_pilot, r->p.n_left_out - before);
    free(pilot);
    free(over);
    free(why);
    runner__budget_free(&b);
}

/* ---- --dry-run: the plan, printed, nothing measured ----------------------------- */

/* The values of the sweep's own axes in a configuration ("technique=pom
 * shadow=raytrace"), the part of it the user chose; axes the technique does
 * not read are absent (folded). */
static void runner__dry_label(const sweep *s, const dm_kv *params, size_t n, FILE *f)
{
    const char *tech = dm_kv_get(params, n, "technique");
    fprintf(f, "technique=%s", tech ? tech : "?");
    for (size_t i = 0; i < s->n_axes; i++) {
        const char *v = dm_kv_get(params, n, s->axes[i].name);
        if (v && strcmp(s->axes[i].name, "technique") != 0)
            fprintf(f, " %s=%s", s->axes[i].name, v);
    }
}

/* Opens the store of --out only when it exists (a dry run creates nothing),
 * and loads what --budget would know from it. */
static void runner__dry_models(runner *r, runner_budget *b)
{
    char *path = dm_xasprintf("%s/dmbench.sqlite", r->o->out_root ? r->o->out_root : "results");
    dm_str err = {0};
    if (dm_file_exists(path) && store_open(path, &r->st, &err) == 0)
        runner__budget_load(r, b);
    else if (dm_file_exists(path))
        dm_log(DM_LOG_WARN, "%s: cannot read the store, so no estimates: %s", path, dm_str_get(&err));
    dm_str_free(&err);
    free(path);
}

/* One planned configuration: key, scene, label, folded combinations and the
 * predicted measuring time (added to *total) where a stored model has one. */
static int runner__dry_config(runner *r, runner_budget *b, const plan_config *c, double *total)
{
    const dm_fit_result *fit = NULL;
    double ns = b->n_fits ? runner__model_frame(b, c, &fit) : NAN;
    printf("  %s  %s  ", c->key, c->scene);
    runner__dry_label(r->s, c->params, c->n_params, stdout);
    if (c->folded > 1)
        printf("  (%zu combinations folded)", c->folded);
    if (!fit) {
        printf("  estimate: none (no stored model predicts it)\n");
        return 0;
    }
    double t = runner__predict(&r->s->measure, ns);
    *total += t;
    printf("  estimate: %.3g ms/frame, %.2g s (model %s)\n", ns / 1e6, t, fit->model);
    return 1;
}

/* --dry-run: prints the counts, every planned configuration with its
 * estimate, the left-out ones with their reasons and the estimated total;
 * measures nothing and writes nothing. */
static void runner__dry_run(runner *r)
{
    const plan *p = &r->p;
    runner_budget b = {0};
    runner__dry_models(r, &b);
    printf("dry run of %s (%s): %zu combinations -> %zu configurations (%zu excluded by the "
           "sweep, %zu folded: axes the technique does not read); %zu planned, %zu left out; "
           "nothing is measured\n", r->s->name, r->s->path ? r->s->path : "<default>",
           p->n_combinations, p->n_configs + p->n_left_out, p->n_excluded,
           p->n_combinations - p->n_excluded - p->n_configs - p->n_left_out, p->n_configs,
           p->n_left_out);
    printf("planned configurations (%zu):\n", p->n_configs);
    double total = 0;
    size_t n_est = 0;
    for (size_t i = 0; i < p->n_configs; i++)
        n_est += (size_t)runner__dry_config(r, &b, &p->configs[i], &total);
    printf("left out (%zu):\n", p->n_left_out);
    for (size_t i = 0; i < p->n_left_out; i++) {
        printf("  ");
        runner__dry_label(r->s, p->left_out[i].params, p->left_out[i].n_params, stdout);
        printf(": %s\n", p->left_out[i].reason);
    }
    if (n_est)
        printf("estimated time: %.2g s for the %zu of %zu configurations a stored model predicts "
               "(run %s)%s\n", total, n_est, p->n_configs, b.fits_run,
               n_est < p->n_configs ? "; the others have no estimate" : "");
    else
        printf("estimated time: unknown (no stored run on this machine has a model that predicts "
               "these configurations)\n");
    runner__budget_free(&b);
}

/* ---- run directory, store, report ---------------------------------------------- */

/* Configurations of the run now in the store. */
static size_t runner__committed(runner *r)
{
    dm_run_result run = {0};
    size_t n = store_run_load(r->st, r->run_id, &run) == 0 ? run.n_configs : 0;
    dm_run_free(&run);
    return n;
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
    if (r->lock_fd < 0) {
        dm_str_printf(err, "%s: cannot create the lock file: %s", path, strerror(errno));
        rc = DM_ERR_IO;
    } else if (flock(r->lock_fd, LOCK_EX | LOCK_NB) != 0) {
        char pid[32] = "";
        ssize_t got = pread(r->lock_fd, pid, sizeof pid - 1, 0);
        pid[got > 0 ? got : 0] = '\0';
        pid[strcspn(pid, "\n")] = '\0';
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

/* Times the calibration workload (run/calibrate.h) in a child and adds
 * its two figures to the environment as "calibration_*_ns_<which>". */
static void runner__calibrate(dm_kv **env, size_t *n_env, const char *which)
{
    calibrate_result c;
    if (calibrate_in_child(&c) != 0)
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
    runner__calibrate(&e->environment, &e->n_environment, "start");
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
    if (rc == 0 && !dm_kv_get(run.environment, run.n_environment, calibrate_key("cpu", "end"))) {
        size_t had = run.n_environment;
        runner__calibrate(&run.environment, &run.n_environment, "end");
        for (size_t i = had; i < run.n_environment; i++)
            store_run_env_put(r->st, r->run_id, run.environment[i].key, run.environment[i].value);
    }
    if (rc == 0) {
        runner__fit(r, &run);
        char e[512] = "";
        report_trends tr;
        run_trends(r->st, &run, &tr);   /* none on a store failure: the report goes on */
        rc = report_write_all_trends(&run, r->run_dir, r->run_dir, &tr, e, sizeof e);
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

/* Input check of counters_derive_inputs that notes, in *user, an input
 * counted under callgrind; every input "is there", so all are visited. */
static int runner__callgrind_input(const char *input, void *user)
{
    const counters_info *ci = counters_find(input);
    if (ci && ci->backend == COUNTERS_BACKEND_CALLGRIND)
        *(int *)user = 1;
    return 1;
}

/* 1 when the sweep asks for a counter of the Instructions pass, by the
 * registry: a callgrind counter, or one derived from one. */
static int runner__wants_instructions(const sweep *s)
{
    for (size_t i = 0; i < s->measure.n_counters; i++) {
        const counters_info *ci = counters_find(s->measure.counters[i]);
        int via = 0;
        if (ci && ci->backend == COUNTERS_BACKEND_DERIVED)
            counters_derive_inputs(ci->name, runner__callgrind_input, &via);
        if (via || (ci && ci->backend == COUNTERS_BACKEND_CALLGRIND))
            return 1;
    }
    return 0;
}

/* The Instructions pass, before any timing child: children under Valgrind,
 * side by side, count every configuration still to do (run/callgrind.h).  Where it
 * cannot run here every configuration records Instructions as unavailable
 * with the reason; a configuration Valgrind crashed or hung on fails.
 * Returns 0, or DM_ERR_ARG with the file in err when a child found the
 * sweep file or a user technique's source changed since the run started, or
 * the runner found a user map or mesh changed after the pass (run/inputs.h):
 * the run stops, and no configuration is recorded for it. */
static int runner__instructions(runner *r, dm_str *err)
{
    if (!runner__wants_instructions(r->s))
        return 0;
    plan_config *todo = dm_xcalloc(r->p.n_configs + 1, sizeof *todo);
    size_t *order = dm_xcalloc(r->p.n_configs + 1, sizeof *order), nt = 0;
    /* in the --seed's order, as the timing rounds: a count must not depend on it */
    plan_shuffle(order, r->p.n_configs, r->o->seed ? r->o->seed : 1);
    for (size_t k = 0; k < r->p.n_configs; k++)
        if (store_config_done(r->st, r->run_id, r->p.configs[order[k]].key) != 1)
            todo[nt++] = r->p.configs[order[k]];
    free(order);
    r->instr = dm_xcalloc(nt + 1, sizeof *r->instr);
    r->n_instr = nt;
    char *vg = r->instr_why ? NULL : counters_valgrind_path();
    if (!vg && !r->instr_why)
        r->instr_why = dm_xstrdup("valgrind not found");
    int64_t t0 = dm_now_ns();
    if (vg && nt) {
        int jobs = callgrind_jobs(r->o->count_jobs, nt);
        if (!r->o->quiet)
            fprintf(stderr, "dmbench: counting the instructions of %zu configurations under Valgrind "
                    "in %d process%s side by side (callgrind, LP_NUM_THREADS=0; frames ~300x slower, "
                    "not timed; --count-jobs)\n", nt, jobs, jobs == 1 ? "" : "es");
        char *dir = dm_xasprintf("%s/callgrind", r->run_dir);
        callgrind_desc d = { .sweep = r->s, .valgrind = vg, .work_dir = dir, .jobs = jobs,
                             .timeout_s = 10 * r->s->measure.timeout_s, .quiet = r->o->quiet };
        dm_str why = {0};
        int rc = callgrind_run(&d, todo, nt, r->instr, &why);
        dm_str changed = {0};
        if (rc != DM_ERR_ARG && inputs_check(&changed) != 0) {   /* a map or mesh the children read */
            dm_str_free(&why);
            why = changed;
            rc = DM_ERR_ARG;
        } else {
            dm_str_free(&changed);
        }
        if (rc == DM_ERR_ARG) {   /* a source changed: nothing is recorded, the run stops */
            dm_str_printf(err, "%s; one run measures one version of each source: stopped the run "
                          "before it recorded anything for it; restore the file and continue with "
                          "--resume, or start a new run", dm_str_get(&why));
            dm_str_free(&why);
            free(dir);
            free(vg);
            free(todo);
            return rc;
        }
        if (rc != 0) {
            callgrind_counts_free(r->instr, nt);
            memset(r->instr, 0, nt * sizeof *r->instr);
            callgrind_mark_unavailable(r->instr, todo, nt, dm_str_get(&why));
        }
        dm_str_free(&why);
        free(dir);
    } else {
        callgrind_mark_unavailable(r->instr, todo, nt, r->instr_why);
    }
    r->instr_s = (double)(dm_now_ns() - t0) / 1e9;
    for (size_t i = 0; i < nt; i++) {
        if (r->instr[i].failed)
            runner__fail_config(r, &todo[i], r->instr[i].reason);
        char *w = callgrind_disagreement(&r->instr[i]);   /* a count that does not repeat */
        if (w) {
            dm_log(DM_LOG_WARN, "%s", w);
            store_run_warning_put(r->st, r->run_id, w);
            free(w);
        }
    }
    if (vg && nt && !r->o->quiet)
        fprintf(stderr, "dmbench: instructions counted in %.1f s\n", r->instr_s);
    free(vg);
    free(todo);
    return 0;
}

/* Runs every scene: configurations grouped by scene, in plan order, until
 * one stops the run (0 or its code, reason in r->stop). */
static int runner__scenes(runner *r)
{
    plan_config *cs = r->p.configs;
    size_t n = r->p.n_configs;
    int *taken = dm_xcalloc(n + 1, sizeof *taken);
    plan_config *group = dm_xcalloc(n + 1, sizeof *group);
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < n; i++) {
        if (taken[i])
            continue;
        size_t ng = 0;
        for (size_t j = i; j < n; j++)
            if (!taken[j] && strcmp(cs[j].scene, cs[i].scene) == 0) {
                taken[j] = 1;
                group[ng++] = cs[j];
            }
        rc = runner__scene(r, group, ng);
    }
    free(group);
    free(taken);
    return rc;
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
    return plan_build_progress(r->s, &r->p, err, runner__plan_progress, &t);
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

int runner_run(const sweep *s, const runner_opts *o, char **run_dir, dm_str *err)
{
    runner r = { .s = s, .o = o, .tty = isatty(2), .t_start = dm_now_ns(), .lock_fd = -1 };
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
    rc = rc ? rc : runner__probe(&r, err);
    if (rc == 0)
        plan_filter_capabilities(&r.p, runner__has_ext, &r);
    if (rc == 0 && o->dry_run) {
        runner__dry_run(&r);
        runner__free(&r);
        return 0;
    }
    inputs_clear();
    rc = rc ? rc : inputs_collect(&r.p, err);     /* the maps and meshes: one version a run */
    rc = rc ? rc : runner__open(&r, err);
    if (rc == 0 && o->budget_s > 0 && !o->resume)
        runner__budget(&r);
    rc = rc ? rc : runner__begin(&r);
    if (rc == 0) {
        r.total = r.p.n_configs;
        char *name_buf = NULL;
        if (!o->quiet)
            fprintf(stderr, "dmbench: %s: %zu combinations -> %zu configurations "
                    "(%zu excluded by the sweep, %zu folded: axes the technique does not read), "
                    "%zu left out; run %s\n",
                    dm_term_safe(s->name, &name_buf), r.p.n_combinations,
                    r.p.n_configs + r.p.n_left_out, r.p.n_excluded,
                    r.p.n_combinations - r.p.n_excluded - r.p.n_configs - r.p.n_left_out,
                    r.p.n_left_out, r.run_dir);
        free(name_buf);
        int changed = runner__instructions(&r, err);
        rc = changed ? changed : runner__scenes(&r);
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
        if (!o->quiet)
            fprintf(stderr, "dmbench: %zu configurations (%zu failed) in %.1f s; %.1f s in measured "
                    "frames, %.0f%% of the time outside them (setup, warm-up, statistics, images)\n",
                    r.done, r.failed, wall, meas, wall > 0 ? 100 * (1 - meas / wall) : 0);
    }
    if (rc == 0 && run_dir)
        *run_dir = dm_xstrdup(r.run_dir);
    free(r.run_dir);
    runner__free(&r);
    return rc;
}
