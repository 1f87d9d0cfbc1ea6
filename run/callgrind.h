/* callgrind.h — the Instructions pass (counter group "Cost"): retired
 * instructions of the measured frames, counted by Valgrind's callgrind in a
 * child of its own.
 *
 * Frames under Valgrind run ~300x slower, so they are never timed: a run
 * that asks for Instructions (or InstructionsPerPixel) first runs one child
 * `valgrind --tool=callgrind --collect-atstart=no --instr-atstart=no
 * dmbench __instructions SWEEP HASH [--source PATH HASH]... KEY...` with
 * LP_NUM_THREADS=0 (the rasteriser runs on the calling thread, so its work
 * is inside the counted window).  The child (run/count_child.h) prepares
 * and warms up a batch of configurations uninstrumented (Valgrind runs
 * that code without callgrind's per-instruction calls: the shaders' JIT
 * compilation from empty caches was 90-95 % of a child's time when it was
 * instrumented), then switches instrumentation on for the batch's counted
 * windows and collection on around CALLGRIND_SAMPLES samples of
 * CALLGRIND_FRAMES frames ended by glFinish, and dumps each sample under
 * the name "KEY.S"; it gets the configurations in the --seed's order.  The parent parses the dump files ("desc: Trigger: Client
 * Request: KEY.S", "totals: N") and leaves out the instructions of the C
 * allocator (the calls into malloc, realloc, free ...): what they cost
 * depends on the heap's history, i.e. on what the child did before
 * (llvmpipe's tessellation grows arrays by realloc, which copies or not
 * depending on the heap's layout; docs/counters.md, "Repeatability").  The timing child
 * that follows records the counts next to its own WallTime.
 *
 * Failure: a configuration the child was on when Valgrind crashed or the
 * watchdog killed it fails with Valgrind's message; the child is restarted
 * once per failure for the rest, and no configuration is tried twice.
 */
#ifndef RUN_CALLGRIND_H
#define RUN_CALLGRIND_H

#include <stddef.h>
#include "core/dm_util.h"
#include "run/callgrind_count.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

typedef struct callgrind_desc {
    const sweep *sweep;      /* its path names the source: a file, "<default>" or "<default --quick>" */
    const char *valgrind;    /* executable (counters_valgrind_path) */
    const char *self;        /* this dmbench binary; NULL = /proc/self/exe */
    const char *work_dir;    /* callgrind's files go here (created) */
    double timeout_s;        /* watchdog: no progress for this long kills the child */
    int jobs;                /* children side by side (callgrind_jobs); 0 = automatic */
    int quiet;
} callgrind_desc;

/* 1 when the sweep asks for a stage counter (GeometryInstructions,
 * RasterInstructions, FragmentInstructions, StageResidual) or a counter
 * derived from one:
 * the child then counts the stage windows too. */
int callgrind_wants_stages(const sweep_measure *sm);

/* 1 when counter `name` is one of the stage counters. */
int callgrind_is_stage_counter(const char *name);


/* The environment variable that sets the default of `run --count-jobs`
 * (the test suite sets it to 1: ctest already runs tests side by side). */
#define CALLGRIND_JOBS_ENV "DMBENCH_COUNT_JOBS"

/* The number CALLGRIND_JOBS_ENV asks for: 0 (automatic) when it is unset,
 * empty or 0, -1 with err when it is not a whole number in 0..256. */
int callgrind_env_jobs(dm_str *err);

/* How many Valgrind children count side by side: `asked` when > 0, else
 * CALLGRIND_JOBS_ENV when set, else the online CPUs up to
 * CALLGRIND_MAX_JOBS and the available memory's share (CALLGRIND_JOB_GIB
 * each); never more than the n configurations, at least 1.  Each child is single-threaded
 * (LP_NUM_THREADS=0) and a count does not depend on which child made it,
 * so the pass shortens with the cores; nothing is timed meanwhile. */
int callgrind_jobs(int asked, size_t n);

/* Counts the instructions of configurations cs[0..n) into out[0..n)
 * (zeroed by the caller; release with callgrind_counts_free).  Returns 0
 * when the child ran (per-configuration failures are in out), DM_ERR_* with
 * err when it could not be started at all, or DM_ERR_ARG with the files in
 * err when a child found the sweep file or a user technique's source
 * changed since the run started: every child is stopped then, and no
 * configuration fails for it (one run measures one version of each source). */
int callgrind_run(const callgrind_desc *d, const plan_config *cs, size_t n, callgrind_count *out,
                  dm_str *err);

/* Marks every configuration unavailable with `why` (Valgrind missing, not
 * a CPU renderer). */
void callgrind_mark_unavailable(callgrind_count *out, const plan_config *cs, size_t n,
                                const char *why);

/* Parses one callgrind dump file's text: the client-request trigger name
 * into name (up to cap-1 chars) and the totals; with allocator non-NULL,
 * also the inclusive cost of the calls into the C allocator (malloc, free,
 * calloc, realloc, the aligned variants) from functions outside it, which
 * Instructions leaves out: its cost depends on the heap's history, not on
 * the frame (docs/counters.md, "Repeatability").  Returns 0, or
 * DM_ERR_PARSE when it is not a client-request dump with totals. */
int callgrind_parse_dump(const char *text, char *name, size_t cap, double *totals, double *allocator);

void callgrind_counts_free(callgrind_count *c, size_t n);

/* The run's warning for a counted configuration whose samples differ by
 * more than CALLGRIND_AGREE (relative to the smaller), as a new string
 * naming the key and both counts; NULL when they agree or c is not counted. */
char *callgrind_disagreement(const callgrind_count *c);

/* The frames the Instructions pass counts of configuration c, a sample:
 * CALLGRIND_FRAMES for a still one; for one on a camera path of F frames
 * (run/path_timing.h) frames 0, k, 2k, ... below F with
 * k = ceil(F / CALLGRIND_PATH_FRAMES) (1 when F is at most that), so its
 * Instructions is the mean frame of the path, or of every k-th frame.
 * Returns how many frames, their step in *step. */
int callgrind_path_frames(const plan_config *c, int *step);

#endif
