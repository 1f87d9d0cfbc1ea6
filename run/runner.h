/* runner.h — running a sweep end to end (README; docs/measurement.md; docs/scale-out.md).
 *
 * The runner process never touches GL: a first child probes the driver
 * (environment, timer calibration, extensions) and a second compiles the
 * user techniques, each with a deadline (probe.h); then each scene is
 * measured in a child process (measure.h) under a watchdog.  Every child
 * dies with the runner (core/dm_proc.h).  A crash or hang fails
 * only the configuration being worked on; a new child continues with the
 * rest.  Every finished configuration is committed to the SQLite store at
 * once and the samples of every finished round are checkpointed, so a kill
 * loses at most the round in flight and --resume continues.  A child that
 * cannot save (disk full, damaged store) stops the run with the reason, as do
 * three children in a row that finish nothing.  The output directory is
 * locked (flock) for the whole run.  The sweep's models are checked before
 * planning; at the end they are fitted and the report files are written
 * into the run directory.  docs/reliability.md has the promises.
 */
#ifndef RUN_RUNNER_H
#define RUN_RUNNER_H

#include <stdint.h>
#include "core/dm_util.h"
#include "sweep/sweep.h"

typedef struct runner_opts {
    const char *out_root;      /* NULL = "results" */
    int resume;                /* continue the newest run of the store */
    int shard_k, shard_n;      /* 0/0 = everything */
    uint64_t seed;             /* round order; 0 = 1 */
    double budget_s;           /* > 0: leave out configurations predicted to take longer */
    double extra_s;            /* > 0: seconds for extra rounds of the configurations short of
                                * samples.target_ci (--extra-time; docs/measurement.md) */
    const char *tag;           /* stored with the run */
    int dry_run;               /* print the plan (and estimates) to stdout; measure nothing */
    int count_jobs;            /* Instructions: children side by side; 0 = callgrind_jobs' default */
    int quiet, verbose;
} runner_opts;

/* Parses --shard "K/N" (decimal, 1 <= K <= N <= 1e6, nothing else around
 * it).  0, or DM_ERR_ARG with a message naming the value in err. */
int runner_parse_shard(const char *text, int *k, int *n, dm_str *err);
/* Parses --seed: a decimal integer 0 .. 2^64-1 without a sign.  0, or
 * DM_ERR_ARG with a message in err. */
int runner_parse_seed(const char *text, uint64_t *seed, dm_str *err);

/* Runs the sweep.  Returns 0 when the run completed (failed configurations
 * are results, not errors) and sets *run_dir (caller frees); DM_ERR_* with a
 * message in err when it could not run at all or was stopped: DM_ERR_BUSY
 * (--out locked by another run), DM_ERR_STORE (damaged store, disk full),
 * DM_ERR_CHILD (measuring processes that keep dying); see dm_exit_from_error().
 * With o->dry_run it plans (probing the driver for the left-out
 * configurations), prints the plan with the estimates a stored model of
 * o->out_root gives, creates nothing, returns 0 and leaves *run_dir untouched. */
int runner_run(const sweep *s, const runner_opts *o, char **run_dir, dm_str *err);

#endif
