/* measure.h — measuring the configurations of one scene (docs/measurement.md), in the
 * process that owns the GL context (a child of the runner).
 *
 * Per configuration: prepare (SetupTime), warm up until the JIT is done and
 * two consecutive samples agree (WarmupTime; warm-up samples are K frames, or
 * fewer when K frames would outlast min_sample_ms), one statistics pass of one
 * frame (deterministic counters; with TessWalkCalls, for a frame of several
 * draw calls of patches, one more frame with each call counted apart), then timing samples of K frames fenced by
 * glFinish taken in rounds over the scene's configurations in a seeded
 * shuffled order, until the 95% CI of the median is within the target or the
 * limits are reached.  Then the image, its quality against the scene's
 * reference (loaded from the reference cache, run/refcache.h, when the
 * job has a cache_dir), and one store transaction.  After every round the
 * samples of the configurations still sampling are checkpointed (one
 * transaction) and a configuration prepared by a later process continues
 * from its checkpoint, so a kill loses at most the round in flight.  With --verbose each
 * configuration logs its warm-up and where its time went.  Progress lines go to report_fd:
 * "B <key>" before work on a key, "D <key> <status> <median_ns> <ci_rel>
 * <sampling_ns>" after it is committed (sampling_ns: time in its timed samples).
 * The measuring decisions (warm-up, frames per sample, when to stop, drift)
 * are asked of run/protocol.h; this file renders, reads clocks and stores.
 */
#ifndef RUN_MEASURE_H
#define RUN_MEASURE_H

#include <stddef.h>
#include <stdint.h>
#include "run/callgrind_count.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"


typedef struct measure_job {
    const sweep *sweep;
    const plan_config *configs;   /* configurations of one scene still to do */
    size_t n_configs;
    const char *run_id;
    const char *run_dir;          /* images go to run_dir/img/ */
    const char *store_path;
    const char *cache_dir;        /* program-binary cache, NULL = off */
    uint64_t seed;
    double extra_s;               /* seconds this scene may spend in extra rounds for the
                                   * configurations short of samples.target_ci (--extra-time);
                                   * 0: none.  Lines "A <key> <extra samples> <ci_rel before>
                                   * <ci_rel after>" before such a configuration's "D", and one
                                   * "R <rounds> <spent_ns> <why> <configurations short>"
                                   * when the extra rounds end (none when none was short) */
    int timer_partial;            /* GPUTime covers only part of the work */
    int report_fd;                /* -1: no progress lines */
    const callgrind_count *instructions;   /* the Instructions pass (run/callgrind.h) */
    size_t n_instructions;        /* 0: Instructions not asked for */
} measure_job;

/* Measures and commits every configuration of the job.  A configuration
 * that fails (shader, GL error, unsupported) is committed as failed with its
 * reason; the function returns 0 unless the context, store or target could
 * not be set up (DM_ERR_*, message in err) or the store refuses a write
 * (DM_ERR_STORE: it stops at once, nothing later could be saved), or a
 * user map or mesh changed since the run started (DM_ERR_ARG, after a
 * "C WHAT CHANGED" line: run/inputs.h). */
int measure_scene(const measure_job *job, dm_str *err);

/* Pilot for --budget: prepares each configuration of the job and times one
 * warm frame (glFinish-fenced), reporting "P <key> <frame_ns> <counts>"
 * lines, the counts predict_counts' (run/predict.h) of that frame (NaN when
 * it cannot be prepared or the driver lacks a count).  Returns 0 or DM_ERR_* (err) on setup failure. */
int measure_pilot(const measure_job *job, dm_str *err);

#endif
