/* callgrind.h — the Instructions pass (counter group "Cost"): retired
 * instructions of the measured frames, counted by Valgrind's callgrind in a
 * child of its own.
 *
 * Frames under Valgrind run ~300x slower, so they are never timed: a run
 * that asks for Instructions (or InstructionsPerPixel) first runs one child
 * `valgrind --tool=callgrind --collect-atstart=no dmbench __instructions
 * SWEEP HASH [--source PATH HASH]... KEY...` with LP_NUM_THREADS=0 (the rasteriser runs on the
 * calling thread, so its work is inside the counted window).  The child
 * (measure_instructions) prepares and warms up each configuration with
 * collection off, then switches collection on around CALLGRIND_SAMPLES
 * samples of CALLGRIND_FRAMES frames ended by glFinish and dumps each
 * sample under the name "KEY.S"; it gets the configurations in the
 * --seed's order.  The parent parses the dump files ("desc: Trigger: Client
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
#include "sweep/plan.h"
#include "sweep/sweep.h"

/* Samples per configuration; they must agree (the count is deterministic). */
#define CALLGRIND_SAMPLES 2
/* Frames per sample, and warm-up frames before the first: every frame of a
 * configuration does the same work once the first has compiled its shaders
 * and touched its maps, and with the allocator left out the count repeats
 * to the instruction, so one frame (its draws and the glFinish that
 * completes them, as a presented frame would) is the count per frame.  At
 * ~300x slower frames under Valgrind, every frame not counted is cost. */
#define CALLGRIND_FRAMES 1
#define CALLGRIND_WARMUP_FRAMES 1
/* Samples whose counts differ by more than this relative amount are a
 * warning of the run (results.json, report) and in the configuration's log.
 * Within one child they agreed to <= 3.1e-5 everywhere measured; counts of
 * separate children can still differ more on tessellation (docs/counters.md,
 * "Repeatability"). */
#define CALLGRIND_AGREE 1e-4
/* The counting child's malloc: blocks from this size up are mmapped, the
 * heap's top is neither padded nor kept (docs/counters.md, "Repeatability"). */
#define CALLGRIND_MMAP_THRESHOLD 4096
/* The counting child's stack starts at the same offset in a page of this
 * size in every process, whatever the length of its arguments and
 * environment. */
#define CALLGRIND_STACK_ALIGN 4096
/* At most this many counting children by default, and no more than one
 * per CALLGRIND_JOB_GIB of available memory: each is a Valgrind of dmbench
 * and llvmpipe (measured: 0.5 GiB resident at 480x270). */
#define CALLGRIND_MAX_JOBS 8
#define CALLGRIND_JOB_GIB 2.0

/* The stage-isolation windows of a configuration whose sweep asks for a
 * stage counter (callgrind_wants_stages; docs/counters.md, "Stage costs"),
 * counted in the same child after the full frame's samples: the same
 * frames with GL_RASTERIZER_DISCARD (dumps "KEY.g.S") and with the minimal
 * fragment shader (techniques/fs_minimal.h, dumps "KEY.r.S"). */
typedef enum callgrind_window {
    CALLGRIND_FULL = 0,      /* the frame as measured: Instructions */
    CALLGRIND_GEOMETRY,      /* rasterizer discard: vertex, tessellation, assembly, clipping */
    CALLGRIND_RASTER,        /* minimal fragment shader: geometry + setup + rasterization */
    CALLGRIND_RESIDUAL,      /* minimal fragment shader with rasterizer discard ("KEY.m.S"):
                                equals GEOMETRY when the minimal shader kept the geometry's work */
    CALLGRIND_WINDOWS
} callgrind_window;

/* The result of one configuration. */
typedef struct callgrind_count {
    char key[17];
    int counted;             /* samples[] are set */
    double samples[CALLGRIND_SAMPLES];   /* instructions per frame, one per sample, allocator left out */
    double allocator[CALLGRIND_SAMPLES]; /* the C allocator's instructions per frame, left out of samples */
    int staged;              /* window[] are set (stage counters) */
    double window[CALLGRIND_WINDOWS][CALLGRIND_SAMPLES];   /* per frame; [FULL] = samples */
    char *stage_reason;      /* why the stage counters are unavailable, NULL when staged */
    int failed;              /* Valgrind crashed or timed out on it: the configuration fails */
    char *reason;            /* why not counted (unavailable or failed), NULL when counted */
} callgrind_count;

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

/* The child: `dmbench __instructions SWEEP HASH [--source PATH HASH]...
 * KEY...` (argv[0] is "__instructions").  Loads the sweep named by SWEEP,
 * checks its hash and that of each user technique's file (the text it
 * loaded, or the file on disk when loading failed), measures the keys
 * under Valgrind, writes "B KEY" / "S KEY ok|unavailable REASON" (stage
 * windows, when asked) / "I KEY ok|failed REASON" lines to stdout, or one
 * "C WHAT CHANGED" line and nothing else when a file changed.  Returns the
 * process exit code. */
int callgrind_child_main(int argc, char **argv);

#endif
