/* runner.h — running a sweep end to end (SPEC §1, §5, §10).
 *
 * The runner process never touches GL: a first child probes the driver
 * (environment, timer calibration, extensions); then each scene is measured
 * in a child process (measure.h) under a watchdog.  A crash or hang fails
 * only the configuration being worked on; a new child continues with the
 * rest.  Every finished configuration is committed to the SQLite store at
 * once, so --resume loses nothing.  At the end the sweep's models are
 * fitted and the report files are written into the run directory.
 */
#ifndef HARNESS_RUNNER_H
#define HARNESS_RUNNER_H

#include <stdint.h>
#include "core/dm_util.h"
#include "sweep/sweep.h"

typedef struct runner_opts {
    const char *out_root;      /* NULL = "results" */
    int resume;                /* continue the newest run of the store */
    int shard_k, shard_n;      /* 0/0 = everything */
    uint64_t seed;             /* round order; 0 = 1 */
    double budget_s;           /* > 0: leave out configurations predicted to take longer */
    const char *tag;           /* stored with the run */
    int dry_run;               /* print the plan (and estimates) to stdout; measure nothing */
    int quiet, verbose;
} runner_opts;

/* Runs the sweep.  Returns 0 when the run completed (failed configurations
 * are results, not errors) and sets *run_dir (caller frees); DM_ERR_* with a
 * message in err when it could not run at all.  With o->dry_run it plans
 * (probing the driver for the left-out configurations), prints the plan with
 * the estimates a stored model of o->out_root gives, creates nothing,
 * returns 0 and leaves *run_dir untouched. */
int runner_run(const sweep *s, const runner_opts *o, char **run_dir, dm_str *err);

#endif
