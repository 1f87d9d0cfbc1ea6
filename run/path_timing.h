/* path_timing.h — a configuration on a camera path, timed frame by frame
 * (docs/motion.md, "Frame times along a path"; docs/measurement.md).
 *
 * A timing sample of a path configuration is one replay of its whole path:
 * frames 0…F−1 from the same start in every sample, each frame finished
 * and timed on its own (mscene_session with c->frame_ns set).  The replay's
 * WallTime sample is the mean of its frame times, so the protocol, the CI,
 * the drift removal and the reports read it as any other sample; the S × F
 * frame times go to the result (dm_path_series) for models/frame_series.
 *
 * Usage, in the timed scene (run/measure.c):
 *     path_timing_prepare(m, c);            // after the warm-up
 *     ... mscene_session(...) per sample, then path_timing_record(m, c, vals);
 *     path_timing_collect(c, &out);         // with the counters
 * Each does nothing for a still configuration.
 */
#ifndef RUN_PATH_TIMING_H
#define RUN_PATH_TIMING_H

#include <stddef.h>

#include "core/dm_results.h"
#include "run/mscene.h"
#include "sweep/plan.h"

/* F, the frames of one pass along pc's camera path (camera.path_frames),
 * or 0 when its camera.path is still (or absent). */
size_t path_timing_frames(const plan_config *pc);

/* For a path configuration (after its warm-up): a sample becomes one
 * replay of F frames (c->frames = F), every frame of the path is drawn once
 * untimed (first-use costs of the views the warm-up did not reach), and the
 * per-frame buffers are made for c->cap replays. */
void path_timing_prepare(mscene *m, mconf *c);

/* Room for replay c->n_samples (grows with c->cap, measure.c's rows). */
void path_timing_room(mconf *c);

/* After a sample's session: keeps its frame times as replay c->n_samples
 * (called before n_samples counts it) and makes the WallTime value in
 * vals (m->timing order) the mean of its finite frame times, NaN when none
 * is finite. */
void path_timing_record(const mscene *m, mconf *c, double *vals);

/* The replays of c into out->path (a copy) with their summary
 * (models/frame_series.h), nothing for a still one. */
void path_timing_collect(const mconf *c, dm_config_result *out);

#endif
