/* runner_child.c — the children of a run and their supervision: the driver
 * probe, the Instructions pass, the measuring children of each scene with
 * their watchdog, and the progress lines (see runner_state.h). */
#include "run/runner_state.h"
#include "core/dm_error.h"
#include "core/dm_image_bridge.h"
#include "core/dm_proc.h"
#include "counters/counters.h"
#include "run/env.h"
#include "run/gl_context.h"
#include "run/inputs.h"
#include "run/measure.h"
#include "run/path_timing.h"
#include "run/probe.h"
#include "run/protocol.h"
#include "run/trends.h"
#include "techniques/axes.h"
#include "techniques/technique.h"

#include <epoxy/gl.h>
#include <math.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* ---- the probe child: environment, timer calibration, extensions ------- */

/* Loads the OpenImageIO modules in the run's own process, before it forks
 * any child: every measuring child writes images, and one that loaded the
 * modules itself spent 0.4 s of CPU relocating their 250 libraries (the
 * dynamic loader's symbol lookups: 0.42 s of a 0.9 s child on the e2e tiny
 * sweep), where a forked child inherits them mapped and relocated.  The
 * probe child then creates its GL context in a process holding the
 * modules, as every measuring child does, so an address-space limit too
 * tight for both (ulimit -v) still stops the run before any work.  Loading
 * them starts no thread of ours; the idle threads a library of theirs
 * starts (log4cplus's pool, through OpenVDB) do not follow a fork, and
 * every child leaves by _exit, never by the exit handlers that would join
 * them.  Returns 0, or DM_ERR_NOMEM (the libraries past ulimit -v) or
 * DM_ERR_IO (a module missing or damaged) with the reason in err. */
static int runner_child__images_load(dm_str *err)
{
#ifdef DM_OIIO_STATIC
    (void)err;
    return 0;
#else
    char why[1024];
    if (dm_image_bridge(DM_OIIO_CORE_MODULE, "dm_oiio_encode", why, sizeof why) &&
        dm_image_bridge(DM_OIIO_IMAGING_MODULE, "dm_oiio_compare", why, sizeof why))
        return 0;
    dm_str_cat(err, why);
    return dm_image_bridge_failure() == DM_ERR_NOMEM ? DM_ERR_NOMEM : DM_ERR_IO;
#endif
}

/* arg: non-zero int when the probe also times the run's start
 * calibration (run/calibrate.h), in the GL context it made anyway. */
static void runner_child__probe_child(int fd, void *arg)
{
    int calibrate = *(const int *)arg;
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
        if (calibrate) {
            calibrate_result start;
            calibrate_measure(1, &start);
            dm_str_printf(&out, "K\t%.0f\t%.0f\n", start.cpu_ns, start.draw_ns);
        }
        dm_kv_free(kv, n);
        gl_context_destroy(gl);
    }
    ssize_t w = write(fd, out.buf, out.len);
    (void)w;
    dm_str_free(&err);
    dm_str_free(&out);
}

/* Reads everything a child writes until EOF or timeout; returns the text. */
char *runner_child_read_all(int fd, int timeout_ms)
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

/* The driver probe: unless the run only plans (--dry-run), the OpenImageIO
 * modules loaded here first (runner_child__images_load); then environment,
 * timer calibration and extensions from a child (run/probe.h: it may hang
 * or crash, and the run must not), which also times the start calibration
 * (r->cal_start) of a new run that times something (r->times), in the GL
 * context it made anyway; then every user technique compiled in a
 * child of its own.  Returns 0, DM_ERR_GL (no usable driver, message in
 * err), DM_ERR_NOMEM / DM_ERR_IO (the modules do not load: past an
 * address-space limit, or missing) or the user check's code. */
int runner_child_probe(runner *r, dm_str *err)
{
    int loaded = r->o->dry_run ? 0 : runner_child__images_load(err);   /* a plan writes no image */
    if (loaded != 0)
        return loaded;
    /* the start calibration in the probe's own context: a run that starts
     * one (not --resume, not --dry-run) and times something */
    int calibrate = r->times && !r->o->resume && !r->o->dry_run;
    r->cal_start.cpu_ns = r->cal_start.draw_ns = NAN;
    dm_proc_result res;
    dm_proc_collect(runner_child__probe_child, &calibrate, probe_timeout_s(), &res);
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
        } else if (line[0] == 'K' && f2) {
            r->cal_start.cpu_ns = strtod(f1, NULL);
            r->cal_start.draw_ns = strtod(f2, NULL);
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

int runner_child_has_ext(const char *ext, void *user)
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
static void runner_child__label(const runner *r, const plan_config *c, dm_str *out)
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
            /* an axis left out at its default reads as it (as report.c reads it) */
            const char *v = strcmp(o->scene, c->scene) == 0 ? dm_param_value(o->params, o->n_params, c->params[k].key) : NULL;
            varies = v && strcmp(v, c->params[k].value) != 0;
        }
        if (varies)
            dm_str_printf(out, " %s=%s", c->params[k].key, c->params[k].value);
    }
}

/* The ETA's prior: the mean over the planned configurations of what the
 * protocol predicts before any frame time is known (protocol_predict_s at
 * 0 ns: the min_sample_ms floor of the samples).  A path configuration's
 * sample is one replay of its F frames with no such floor, so it adds 0,
 * not a still configuration's floor: its cost is known only from the
 * measured rate. */
static double runner_child__eta_prior(const runner *r)
{
    if (!r->p.n_configs)
        return 0;
    double sum = 0;
    for (size_t i = 0; i < r->p.n_configs; i++) {
        protocol_desc d;
        protocol_desc_from_measure(&d, &r->s->measure, 0);
        protocol_desc_on_path(&d, path_timing_frames(&r->p.configs[i]));
        sum += protocol_predict_s(&d, 0);
    }
    return sum / (double)r->p.n_configs;
}

/* "  ETA 42s" from the measured progress (run/protocol.h: protocol_eta_s).
 * A scene's configurations finish together after its rounds, so when its
 * first line comes the whole scene is done: the estimate counts the
 * configurations up to the scene's end as done in the time from the first
 * measuring process's start (the probe and the Instructions pass are not
 * progress), and the ones after it as left; "" until it is credible, and
 * on the last scene, where nothing is left. */
static void runner_child__eta(runner *r, char *buf, size_t len)
{
    int64_t now = dm_now_ns(), from = r->t_measure ? r->t_measure : r->t_start;
    size_t done = r->scene_end > r->done ? r->scene_end : r->done;
    r->t_last = now;
    buf[0] = 0;
    double left = protocol_eta_s(runner_child__eta_prior(r), done, (double)(now - from) / 1e9,
                                 r->total > done ? r->total - done : 0, r->total);
    if (isfinite(left))
        snprintf(buf, len, "  ETA %.0fs", left);
}

/* The progress line of a finished configuration; p99_ns and stutters are
 * its path's (docs/motion.md), stutters < 0 for a still configuration. */
static void runner_child__progress(runner *r, const plan_config *c, const char *status,
                             double median_ns, double ci_rel, double p99_ns, long stutters)
{
    r->done++;
    r->failed += strcmp(status, "ok") != 0;
    if (r->o->quiet)
        return;
    char eta[48];
    runner_child__eta(r, eta, sizeof eta);
    dm_str label = {0}, line = {0};
    runner_child__label(r, c, &label);
    if (strcmp(status, "ok") == 0 && !isfinite(median_ns))   /* a counters-only sweep: nothing timed */
        dm_str_printf(&line, "[%zu/%zu] %-44s counted (no timing counter)%s", r->done, r->total,
                      dm_str_get(&label), eta);
    else if (strcmp(status, "ok") == 0 && stutters >= 0)
        dm_str_printf(&line, "[%zu/%zu] %-44s %9.3f ms ±%4.1f%% · path p99 %.3f ms, %ld stutter%s%s",
                      r->done, r->total, dm_str_get(&label), median_ns / 1e6, ci_rel * 100, p99_ns / 1e6,
                      stutters, stutters == 1 ? "" : "s", eta);
    else if (strcmp(status, "ok") == 0)
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

static const plan_config *runner_child__find(const plan_config *cs, size_t n, const char *key)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(cs[i].key, key) == 0)
            return &cs[i];
    return NULL;
}

/* Records a configuration the child could not finish (crash, hang).
 * Returns 0, or DM_ERR_STORE (message in r->stop) when it cannot be saved. */
static int runner_child__fail_config(runner *r, const plan_config *c, const char *reason)
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
        runner_child__progress(r, c, reason, NAN, NAN, NAN, -1);
    return rc;
}

typedef struct runner_child__watched {
    pid_t pid;
    int fd;
    char current[17];
    int64_t last_ns;
    dm_str line;
} runner_child__watched;

/* A configuration that had extra samples (an "A" line): counted, and its
 * line kept for runner_child_extra_print. */
static void runner_child__extra_config(runner *r, const plan_config *c, size_t samples,
                                       double before, double after, double corrected)
{
    double target = r->s->measure.target_ci;
    int reached = protocol_extra_done(after, corrected, target);
    r->extra_configs += samples > 0;   /* "gave N of them more samples, and M reached it" */
    r->extra_reached += samples > 0 && reached;
    dm_str label = {0}, corr = {0};
    if (c)
        runner_child__label(r, c, &label);
    if (isfinite(corrected))
        dm_str_printf(&corr, " (±%.2f %% with the drift removed)", 100 * corrected);
    dm_str_printf(&r->extra_lines, "  %s: +%zu samples, CI ±%.2f %% -> ±%.2f %%%s%s\n",
                  c ? dm_str_get(&label) : "?", samples, 100 * before, 100 * after, dm_str_get(&corr),
                  reached ? " (target reached)" : "");
    dm_str_free(&label);
    dm_str_free(&corr);
}

void runner_child_extra_print(const runner *r, FILE *f)
{
    if (!(r->o->extra_s > 0))
        return;
    double target = 100 * r->s->measure.target_ci;
    if (!r->extra_scenes) {
        fprintf(f, "dmbench: extra rounds (--extra-time %g s): none needed, every configuration "
                "within ±%.1f %% or without a timing counter\n", r->o->extra_s, target);
        return;
    }
    fprintf(f, "dmbench: extra rounds (--extra-time %g s): %zu configuration%s short of "
            "±%.1f %%; %zu rounds in %.1f s gave %zu of them more samples, noisiest first, and %zu "
            "reached it; ended: %s\n", r->o->extra_s, r->extra_short, r->extra_short == 1 ? "" : "s",
            target, r->extra_rounds, (double)r->extra_ns / 1e9, r->extra_configs, r->extra_reached,
            r->extra_budget_scenes == 0 ? "targets reached in every scene"
            : r->extra_budget_scenes == r->extra_scenes ? "budget spent in every scene"
                                                        : "budget spent in some scenes");
    if (r->extra_budget_scenes && r->extra_budget_scenes < r->extra_scenes)
        fprintf(f, "dmbench: extra rounds: budget spent in %zu of %zu scenes, targets reached in "
                "the others\n", r->extra_budget_scenes, r->extra_scenes);
    char *b;
    fputs(dm_term_safe(dm_str_get(&r->extra_lines), &b), f);
    free(b);
}

/* Handles one line of child output; returns 1 when a config was finished. */
static void runner_child__line(runner *r, runner_child__watched *w, const plan_config *cs, size_t n,
                               char *line, int *done_flags)
{
    char key[17] = "", status[16] = "";
    double med = NAN, ci = NAN, corr = NAN;
    long long sampled = 0;
    double p99 = NAN;
    long stutters = -1;
    if (line[0] == 'B' && sscanf(line, "B %16s", key) == 1) {
        snprintf(w->current, sizeof w->current, "%s", key);
    } else if (line[0] == 'D' && sscanf(line, "D %16s %15s %lf %lf %lld %lf %ld", key, status, &med, &ci, &sampled,
                                         &p99, &stutters) >= 2) {
        const plan_config *c = runner_child__find(cs, n, key);
        r->measured_ns += sampled;
        if (c) {
            done_flags[c - cs] = 1;
            runner_child__progress(r, c, status, med, ci, p99, stutters);
        }
        w->current[0] = '\0';
    } else if (line[0] == 'A' && sscanf(line, "A %16s %lld %lf %lf %lf", key, &sampled, &med, &ci, &corr) >= 4) {
        runner_child__extra_config(r, runner_child__find(cs, n, key), (size_t)sampled, med, ci, corr);
    } else if (line[0] == 'R' && sscanf(line, "R %lf %lld %15s %lf", &med, &sampled, status, &ci) == 4) {
        r->extra_rounds += (size_t)med;
        r->extra_short += (size_t)ci;
        r->extra_ns += sampled;
        r->extra_scenes++;
        r->extra_budget_scenes += strcmp(status, "budget") == 0;
        r->extra_left_s -= (double)sampled / 1e9;
        r->extra_scene_s -= (double)sampled / 1e9;
    }
}

pid_t runner_child_spawn(runner *r, const plan_config *cs, size_t n, int *fd, int pilot)
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
                            .extra_s = pilot || !(r->extra_scene_s > 0) ? 0 : r->extra_scene_s,
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
static int runner_child__watch(runner *r, runner_child__watched *w, const plan_config *cs, size_t n, int *done_flags,
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
                runner_child__line(r, w, cs, n, line, done_flags);
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
#define RUNNER_CHILD__MAX_FUTILE 3

/* Why a child ended early (caller frees), or NULL when it just finished. */
static char *runner_child__why(const runner *r, int status, const char *fatal)
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
 * RUNNER_CHILD__MAX_FUTILE.  Returns 0 to go on, DM_ERR_STORE / DM_ERR_ARG /
 * DM_ERR_CHILD (reason in r->stop) to stop. */
static int runner_child__end(runner *r, const char *fatal, const char *why, size_t finished)
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
    if (r->futile < RUNNER_CHILD__MAX_FUTILE)
        return 0;
    dm_str_printf(&r->stop, "%d measuring processes in a row finished no configuration (last: %s)",
                  RUNNER_CHILD__MAX_FUTILE, why ? why : "it exited without a result");
    return DM_ERR_CHILD;
}

/* Runs one child on the configurations not done yet and records what it
 * finished in done[]; returns 0 or the code that stops the run. */
static int runner_child__scene_child(runner *r, const plan_config *cs, size_t n, int *done,
                               plan_config *remaining, size_t nt)
{
    runner_child__watched w = { .current = "" };
    w.pid = runner_child_spawn(r, remaining, nt, &w.fd, 0);
    char *fatal = NULL;
    int *tdone = dm_xcalloc(nt + 1, sizeof *tdone);
    int status = runner_child__watch(r, &w, remaining, nt, tdone, &fatal);
    close(w.fd);
    dm_str_free(&w.line);
    size_t finished = 0;
    for (size_t i = 0; i < nt; i++)
        if (tdone[i]) {
            done[runner_child__find(cs, n, remaining[i].key) - cs] = 1;
            finished++;
        }
    const plan_config *cur = w.current[0] ? runner_child__find(cs, n, w.current) : NULL;
    char *why = runner_child__why(r, status, fatal);
    int failing = why || (WIFEXITED(status) && WEXITSTATUS(status) != 0);
    int rc = runner_child__end(r, fatal, why, finished + failing);
    if (rc == 0 && why && cur) {
        rc = runner_child__fail_config(r, cur, why);
        done[cur - cs] = 1;
    } else if (rc == 0 && failing) {
        for (size_t i = 0; rc == 0 && i < n; i++)      /* no culprit: fail what is left */
            if (!done[i]) {
                rc = runner_child__fail_config(r, &cs[i], why ? why : "the measuring process failed");
                done[i] = 1;
            }
    }
    free(why);
    free(fatal);
    free(tdone);
    return rc;
}

/* Measures one scene, restarting a child after each crash or hang (at most
 * RUNNER_CHILD__MAX_FUTILE in a row that finish nothing).  Returns 0, or the code
 * that stops the run with the reason in r->stop. */
static int runner_child__scene(runner *r, const plan_config *cs, size_t n)
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
        rc = runner_child__scene_child(r, cs, n, done, remaining, nt);
        free(remaining);
    }
    free(done);
    return rc;
}

/* Input check of counters_derive_inputs that notes, in *user, an input
 * counted under callgrind; every input "is there", so all are visited. */
static int runner_child__callgrind_input(const char *input, void *user)
{
    const counters_info *ci = counters_find(input);
    if (ci && ci->backend == COUNTERS_BACKEND_CALLGRIND)
        *(int *)user = 1;
    return 1;
}

/* 1 when the sweep asks for a counter of the Instructions pass, by the
 * registry: a callgrind counter, or one derived from one. */
static int runner_child__wants_instructions(const sweep *s)
{
    for (size_t i = 0; i < s->measure.n_counters; i++) {
        const counters_info *ci = counters_find(s->measure.counters[i]);
        int via = 0;
        if (ci && ci->backend == COUNTERS_BACKEND_DERIVED)
            counters_derive_inputs(ci->name, runner_child__callgrind_input, &via);
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
int runner_child_instructions(runner *r, dm_str *err)
{
    if (!runner_child__wants_instructions(r->s))
        return 0;
    plan_config *uncounted = dm_xcalloc(r->p.n_configs + 1, sizeof *uncounted);
    size_t *order = dm_xcalloc(r->p.n_configs + 1, sizeof *order), nt = 0;
    /* in the --seed's order, as the timing rounds: a count must not depend on it */
    plan_shuffle(order, r->p.n_configs, r->o->seed ? r->o->seed : 1);
    for (size_t k = 0; k < r->p.n_configs; k++)
        if (store_config_done(r->st, r->run_id, r->p.configs[order[k]].key) != 1)
            uncounted[nt++] = r->p.configs[order[k]];
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
        int rc = callgrind_run(&d, uncounted, nt, r->instr, &why);
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
            free(uncounted);
            return rc;
        }
        if (rc != 0) {
            callgrind_counts_free(r->instr, nt);
            memset(r->instr, 0, nt * sizeof *r->instr);
            callgrind_mark_unavailable(r->instr, uncounted, nt, dm_str_get(&why));
        }
        dm_str_free(&why);
        free(dir);
    } else {
        callgrind_mark_unavailable(r->instr, uncounted, nt, r->instr_why);
    }
    r->instr_s = (double)(dm_now_ns() - t0) / 1e9;
    for (size_t i = 0; i < nt; i++) {
        if (r->instr[i].failed)
            runner_child__fail_config(r, &uncounted[i], r->instr[i].reason);
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
    free(uncounted);
    return 0;
}

/* Runs every scene: configurations grouped by scene, in plan order, until
 * one stops the run (0 or its code, reason in r->stop). */
int runner_child_scenes(runner *r)
{
    plan_config *cs = r->p.configs;
    size_t n = r->p.n_configs;
    int *taken = dm_xcalloc(n + 1, sizeof *taken);
    plan_config *group = dm_xcalloc(n + 1, sizeof *group);
    int rc = 0;
    r->t_measure = r->t_last = dm_now_ns();
    r->extra_left_s = r->o->extra_s;
    size_t scenes_left = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = 0;
        while (j < i && strcmp(cs[j].scene, cs[i].scene) != 0)
            j++;
        scenes_left += j == i;
    }
    for (size_t i = 0; rc == 0 && i < n; i++) {
        if (taken[i])
            continue;
        r->extra_scene_s = scenes_left ? r->extra_left_s / (double)scenes_left-- : 0;
        size_t ng = 0;
        for (size_t j = i; j < n; j++)
            if (!taken[j] && strcmp(cs[j].scene, cs[i].scene) == 0) {
                taken[j] = 1;
                group[ng++] = cs[j];
            }
        r->scene_end = r->done + ng;
        rc = runner_child__scene(r, group, ng);
    }
    free(group);
    free(taken);
    return rc;
}
