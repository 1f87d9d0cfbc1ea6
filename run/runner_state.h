/* runner_state.h — the state of one run in the parent process, shared by
 * the files of the runner and by nothing else:
 *
 *   runner.c        the outline of a run (runner_run), its directory,
 *                   store, environment record and end (fits, report);
 *   runner_plan.c   what is decided before measuring: --budget (a stored
 *                   cost model, else a pilot child) and --dry-run;
 *   runner_child.c  the children and their supervision: the driver probe,
 *                   the Instructions pass, the measuring children of each
 *                   scene with their watchdog, and the progress lines.
 *
 * runner.c calls the other two, runner_plan.c calls runner_child.c, and
 * runner_child.c calls neither.
 */
#ifndef RUN_RUNNER_STATE_H
#define RUN_RUNNER_STATE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/types.h>

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "run/calibrate.h"
#include "run/callgrind.h"
#include "run/runner.h"
#include "store/store.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

typedef struct runner {
    const sweep *s;
    const runner_opts *o;
    plan p;
    store *st;
    char *root, *run_id, *run_dir, *store_path, *cache_dir;
    dm_run_result env;         /* environment + timer of the run */
    int times;                 /* the sweep asks for a timed counter (runner_times) */
    calibrate_result cal_start;   /* the start calibration, timed in the probe child (NaN: none) */
    char **exts;               /* extensions the driver has (of those techniques need) */
    size_t n_exts;
    size_t done, total, failed;
    int64_t t_start;
    int64_t t_measure;         /* the first measuring process's start (ns); 0 before */
    int64_t t_last;            /* the last progress line (ns) */
    size_t scene_end;          /* configurations done once the scene being measured is */
    int64_t measured_ns;       /* time inside timed samples, all configurations */
    int tty;
    char *instr_why;           /* why Instructions cannot be counted here; NULL = it can */
    callgrind_count *instr;    /* the Instructions pass (run/callgrind.h) */
    size_t n_instr;
    double instr_s;            /* wall time of that pass */
    int lock_fd;               /* flock on <out>/dmbench.lock, -1 when none */
    int futile;                /* measuring processes in a row that finished nothing */
    dm_str stop;               /* why the run stopped before its end (store failure, ...) */
    /* extra rounds (--extra-time): what is left, what the scene being measured may spend, and
     * what they did (runner_child_extra_print) */
    double extra_left_s, extra_scene_s;
    size_t extra_rounds, extra_short, extra_configs, extra_reached, extra_scenes, extra_budget_scenes;
    int64_t extra_ns;
    dm_str extra_lines;        /* one line per configuration that had extra samples */
} runner;

/* ---- runner_child.c -------------------------------------------------------- */

/* Loads the OpenImageIO modules into the run's process (not for a dry run:
 * every child forked later inherits them), then runs the driver probe in a
 * child: the environment record, the timer's calibration, the extensions
 * techniques need and (a new run that times something) the start
 * calibration, into r.  Returns 0, or DM_ERR_* with the reason in err. */
int runner_child_probe(runner *r, dm_str *err);
/* plan_filter_capabilities' callback: 1 when the probe found extension ext. */
int runner_child_has_ext(const char *ext, void *user);
/* Everything a child writes to fd until it closes or timeout_ms pass
 * without a byte (caller frees). */
char *runner_child_read_all(int fd, int timeout_ms);
/* Forks a measuring child on configurations cs[0..n) (the --budget pilot
 * when pilot != 0); its progress lines come on *fd.  Returns its pid, or
 * -1. */
pid_t runner_child_spawn(runner *r, const plan_config *cs, size_t n, int *fd, int pilot);
/* The Instructions pass: counting children under Valgrind for every
 * configuration still to do.  Returns 0, or DM_ERR_ARG with the file in
 * err when a source, map or mesh changed since the run started. */
int runner_child_instructions(runner *r, dm_str *err);
/* Measures every scene, a child at a time with its watchdog, until one
 * stops the run (0, or its code with the reason in r->stop).  The
 * --extra-time left is shared out scene by scene: a scene may spend what
 * is left divided by the scenes still to measure (so what one leaves
 * unspent goes to the next). */
int runner_child_scenes(runner *r);
/* The extra rounds' account to f: rounds, time, the configurations that
 * had them (CI before and after) and why they ended; nothing without
 * --extra-time. */
void runner_child_extra_print(const runner *r, FILE *f);

/* ---- runner_plan.c ---------------------------------------------------------- */

/* --budget: leaves out the configurations a stored cost model (else a
 * pilot frame) predicts would not fit in the time budget. */
void runner_plan_budget(runner *r);
/* --dry-run: prints the plan, its predicted time, and measures nothing. */
void runner_plan_dry_run(runner *r);

#endif
