/* runner_plan.c — what a run decides before it measures: --budget (a
 * stored cost model, else a pilot frame) and --dry-run (see runner_state.h). */
#include "run/runner_state.h"
#include "run/fitting.h"
#include "run/path_timing.h"
#include "run/predict.h"
#include "run/protocol.h"
#include "reports/report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* ---- --budget: a stored cost model, else a pilot frame ------------------------ */

/* Earlier runs searched for a cost model and counters (newest first). */
#define RUNNER_PLAN__BUDGET_RUNS 16

/* Predicted seconds to measure configuration c (NULL: a still one) from
 * its frame time, as the protocol sees it (run/protocol.h:
 * protocol_predict_s; a sample of a path configuration is one replay of
 * its F frames). */
static double runner_plan__predict(const sweep_measure *m, const plan_config *c, double frame_ns)
{
    protocol_desc d;
    protocol_desc_from_measure(&d, m, 0);
    protocol_desc_on_path(&d, c ? path_timing_frames(c) : 0);
    return protocol_predict_s(&d, frame_ns);
}

/* What --budget knows from the store: earlier runs (newest first) and the
 * frame-time fits usable for predictions, sweep's own models first. */
typedef struct runner_plan__known {
    dm_run_result *runs;
    size_t n_runs;
    const dm_fit_result **fits;
    size_t n_fits;
    const char *fits_run;      /* run the fits come from */
    size_t by_model, by_pilot, by_instr;
    predict_model pm;          /* the instruction models of the stored runs (run/predict.h) */
    size_t pm_runs;            /* how many runs they were fitted to; 0: none */
} runner_plan__known;

static int runner_plan__fit_usable(const dm_fit_result *f)
{
    return f->response && strcmp(f->response, "WallTime") == 0 && f->formula;
}

/* Position of the fit's model among the sweep's models, n_models if absent. */
static size_t runner_plan__fit_rank(const runner *r, const dm_fit_result *f)
{
    size_t j = 0;
    while (j < r->s->n_models && strcmp(r->s->models[j].name, f->model) != 0)
        j++;
    return j;
}

/* Takes the usable fits of the newest run that has any: first those named
 * like the sweep's models (in the sweep's order), then the others. */
static void runner_plan__budget_fits(runner *r, runner_plan__known *b)
{
    for (size_t k = 0; k < b->n_runs && b->n_fits == 0; k++) {
        const dm_run_result *run = &b->runs[k];
        b->fits = dm_xrealloc(b->fits, (run->n_fits + 1) * sizeof *b->fits);
        for (size_t rank = 0; rank <= r->s->n_models; rank++)
            for (size_t i = 0; i < run->n_fits; i++)
                if (runner_plan__fit_rank(r, &run->fits[i]) == rank && runner_plan__fit_usable(&run->fits[i]))
                    b->fits[b->n_fits++] = &run->fits[i];
        b->fits_run = b->n_fits ? run->id : NULL;
    }
}

/* 1 when a stored run was measured in this run's environment (same
 * fingerprint: renderer, GL version, LP_NUM_THREADS, CPU), so its frame
 * times and counters apply here. */
static int runner_plan__same_machine(const runner *r, const dm_run_result *run)
{
    const char *a = dm_kv_get(run->environment, run->n_environment, "fingerprint");
    const char *b = dm_kv_get(r->env.environment, r->env.n_environment, "fingerprint");
    return a && b && strcmp(a, b) == 0;
}

/* Loads up to RUNNER_PLAN__BUDGET_RUNS earlier runs of the store made on this
 * machine (newest first). */
static void runner_plan__budget_load(runner *r, runner_plan__known *b)
{
    char **ids = NULL;
    size_t n = 0;
    if (store_list_runs(r->st, &ids, &n) != 0)
        n = 0;
    b->runs = dm_xcalloc(n + 1, sizeof *b->runs);
    for (size_t i = 0; i < n; i++) {
        dm_run_result *run = &b->runs[b->n_runs];
        if (b->n_runs < RUNNER_PLAN__BUDGET_RUNS && store_run_load(r->st, ids[i], run) == 0) {
            if (runner_plan__same_machine(r, run))
                b->n_runs++;
            else
                dm_run_free(run);
        }
        free(ids[i]);
    }
    free(ids);
    runner_plan__budget_fits(r, b);
}

/* Fits the instruction models to the stored runs that have the counters
 * they read and WallTime (docs/models.md, "Prediction"). */
static void runner_plan__budget_instr_models(runner_plan__known *b)
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

static void runner_plan__budget_free(runner_plan__known *b)
{
    if (b->pm_runs)
        predict_free(&b->pm);
    for (size_t i = 0; i < b->n_runs; i++)
        dm_run_free(&b->runs[i]);
    free(b->runs);
    free(b->fits);
}

/* Leaves out the configuration with that key, if it is still planned. */
static void runner_plan__leave_out_key(runner *r, const char *key, const char *why)
{
    for (size_t i = 0; i < r->p.n_configs; i++)
        if (strcmp(r->p.configs[i].key, key) == 0) {
            plan_leave_out(&r->p, i, why);
            return;
        }
}

/* Frame time (ns) of a planned configuration from the first stored fit that
 * can evaluate it; the fit in *used, or NULL (then NaN). */
static double runner_plan__model_frame(const runner_plan__known *b, const plan_config *c,
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
static size_t runner_plan__budget_by_model(runner *r, runner_plan__known *b, plan_config *pilot,
                                      char (*over)[17], char **why)
{
    size_t n_pilot = 0, n_over = 0;
    for (size_t i = 0; i < r->p.n_configs; i++) {
        const plan_config *c = &r->p.configs[i];
        const dm_fit_result *fit;
        double ns = runner_plan__model_frame(b, c, &fit), t = runner_plan__predict(&r->s->measure, c, ns);
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
        runner_plan__leave_out_key(r, over[k], why[k]);
        free(why[k]);
    }
    return n_pilot;
}

/* Runs the pilot child on configs and leaves out what would blow the budget. */
static void runner_plan__budget_pilot(runner *r, runner_plan__known *b, const plan_config *cs, size_t n)
{
    int fd = -1;
    pid_t pid = runner_child_spawn(r, cs, n, &fd, 1);
    char *text = runner_child_read_all(fd, (int)(r->s->measure.timeout_s * 1000));
    close(fd);
    kill(pid, SIGKILL);
    waitpid(pid, NULL, 0);
    runner_plan__budget_instr_models(b);
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
        double frame = by_instr ? pr.wall_ns : ns, t = runner_plan__predict(&r->s->measure, pc, frame);
        b->by_instr += by_instr;
        b->by_pilot += !by_instr;
        if (isfinite(frame) && t > r->o->budget_s) {
            char iv[64] = "[interval unavailable]";   /* never "[nan, nan]" (predict_result.wall_why) */
            if (by_instr && isfinite(pr.wall_lo) && isfinite(pr.wall_hi))
                snprintf(iv, sizeof iv, "[%.3g, %.3g]", pr.wall_lo / 1e6, pr.wall_hi / 1e6);
            char *why = by_instr
                ? dm_xasprintf("over --budget %g s: the instruction models (%zu stored run%s) predict "
                               "%.4g instructions and %.3g ms/frame %s, so measuring would take "
                               "about %.2g s", r->o->budget_s, b->pm_runs, b->pm_runs == 1 ? "" : "s", pr.instr,
                               frame / 1e6, iv, t)
                : dm_xasprintf("over --budget %g s: a pilot frame took %.3g ms, so measuring "
                               "would take about %.2g s", r->o->budget_s, ns / 1e6, t);
            runner_plan__leave_out_key(r, key, why);
            free(why);
        }
        predict_result_free(&pr);
    }
    free(text);
}

/* --budget: predicts each configuration's measuring time from a stored
 * cost model when one can be evaluated for it before measuring, else from a
 * pilot frame, and leaves out what would exceed the budget. */
void runner_plan_budget(runner *r)
{
    runner_plan__known b = {0};
    size_t n = r->p.n_configs, before = r->p.n_left_out;
    plan_config *pilot = dm_xcalloc(n + 1, sizeof *pilot);
    char (*over)[17] = dm_xcalloc(n + 1, sizeof *over);
    char **why = dm_xcalloc(n + 1, sizeof *why);
    runner_plan__budget_load(r, &b);
    size_t n_pilot = runner_plan__budget_by_model(r, &b, pilot, over, why);
    if (n_pilot)
        runner_plan__budget_pilot(r, &b, pilot, n_pilot);
    if (!r->o->quiet)
        fprintf(stderr, "dmbench: --budget %g s: %zu configurations predicted by a cost model%s%s%s, "
                "%zu by the instruction models, %zu by a pilot frame; %zu left out\n", r->o->budget_s,
                b.by_model, b.fits_run ? " (run " : "", b.fits_run ? b.fits_run : "", b.fits_run ? ")" : "",
                b.by_instr, b.by_pilot, r->p.n_left_out - before);
    free(pilot);
    free(over);
    free(why);
    runner_plan__budget_free(&b);
}

/* ---- --dry-run: the plan, printed, nothing measured ----------------------------- */

/* The values of the sweep's own axes in a configuration ("technique=pom
 * shadow=raytrace"), the part of it the user chose; axes the technique does
 * not read are absent (folded). */
static void runner_plan__dry_label(const sweep *s, const dm_kv *params, size_t n, FILE *f)
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
static void runner_plan__dry_models(runner *r, runner_plan__known *b)
{
    char *path = dm_xasprintf("%s/dmbench.sqlite", r->o->out_root ? r->o->out_root : "results");
    dm_str err = {0};
    if (dm_file_exists(path) && store_open(path, &r->st, &err) == 0)
        runner_plan__budget_load(r, b);
    else if (dm_file_exists(path))
        dm_log(DM_LOG_WARN, "%s: cannot read the store, so no estimates: %s", path, dm_str_get(&err));
    dm_str_free(&err);
    free(path);
}

/* One planned configuration: key, its label (the one form of every file and
 * the terminal: report_config_label over the planned configurations, lab),
 * folded combinations and the predicted measuring time (added to *total)
 * where a stored model has one. */
static int runner_plan__dry_config(runner *r, runner_plan__known *b, const plan_config *c,
                                   const dm_run_result *lab, size_t i, double *total)
{
    const dm_fit_result *fit = NULL;
    double ns = b->n_fits ? runner_plan__model_frame(b, c, &fit) : NAN;
    dm_str label = {0};
    report_config_label(lab, &lab->configs[i], &label);
    printf("  %s  %s", c->key, dm_str_get(&label));
    dm_str_free(&label);
    if (c->folded > 1)
        printf("  (%zu combinations folded)", c->folded);
    if (!fit) {
        printf("  estimate: none (no stored model predicts it)\n");
        return 0;
    }
    double t = runner_plan__predict(&r->s->measure, c, ns);
    *total += t;
    printf("  estimate: %.3g ms/frame, %.2g s (model %s)\n", ns / 1e6, t, fit->model);
    return 1;
}

/* --dry-run: prints the counts, every planned configuration with its
 * estimate, the left-out ones with their reasons and the estimated total;
 * measures nothing and writes nothing. */
void runner_plan_dry_run(runner *r)
{
    const plan *p = &r->p;
    runner_plan__known b = {0};
    runner_plan__dry_models(r, &b);
    printf("dry run of %s (%s): %zu combinations -> %zu configurations (%zu excluded by the "
           "sweep, %zu folded: axes the technique does not read); %zu planned, %zu left out; "
           "nothing is measured\n", r->s->name, r->s->path ? r->s->path : "<default>",
           p->n_combinations, p->n_configs + p->n_left_out, p->n_excluded,
           p->n_combinations - p->n_excluded - p->n_configs - p->n_left_out, p->n_configs,
           p->n_left_out);
    printf("planned configurations (%zu):\n", p->n_configs);
    double total = 0;
    size_t n_est = 0;
    dm_run_result lab = {0};   /* the planned configurations as a run, for their labels (borrowed) */
    lab.configs = dm_xcalloc(p->n_configs + 1, sizeof *lab.configs);
    lab.n_configs = p->n_configs;
    for (size_t i = 0; i < p->n_configs; i++)
        lab.configs[i] = (dm_config_result){ .key = (char *)p->configs[i].key, .scene = p->configs[i].scene,
                                             .params = p->configs[i].params,
                                             .n_params = p->configs[i].n_params, .ok = 1 };
    for (size_t i = 0; i < p->n_configs; i++)
        n_est += (size_t)runner_plan__dry_config(r, &b, &p->configs[i], &lab, i, &total);
    free(lab.configs);
    printf("left out (%zu):\n", p->n_left_out);
    for (size_t i = 0; i < p->n_left_out; i++) {
        printf("  ");
        runner_plan__dry_label(r->s, p->left_out[i].params, p->left_out[i].n_params, stdout);
        printf(": %s\n", p->left_out[i].reason);
    }
    if (n_est)
        printf("estimated time: %.2g s for the %zu of %zu configurations a stored model predicts "
               "(run %s)%s\n", total, n_est, p->n_configs, b.fits_run,
               n_est < p->n_configs ? "; the others have no estimate" : "");
    else
        printf("estimated time: unknown (no stored run on this machine has a model that predicts "
               "these configurations)\n");
    runner_plan__budget_free(&b);
}
