/* mpath_quality.h — quality along a camera path, and the cached reference
 * frame it and the still quality (run/mquality.h) draw from
 * (docs/motion.md, "Quality along a path").
 *
 * A configuration on a path of F frames (camera.path_frames) gets a
 * reference every K-th frame of one pass, K = camera.path_ref_every:
 * frames 0, K, 2K, ... up to F − 1.  At each of them its own frame is
 * rendered and compared: FLIP mean and SSIM per reference frame, the
 * temporal error (imaging/temporal.h) over the steps from one reference
 * frame to the next, and popping, the largest jump of the per-frame FLIP
 * between consecutive reference frames.  Only the reference frames are
 * rendered (no figure reads the others), and they are compared as they
 * come: two frames of each sequence are held at a time, plus one float per
 * pixel and step for the temporal error's percentile and one FLIP map.  Up
 * to MPATH_SHOTS_MAX of them are written as images as they pass (the
 * frame, the reference frame, their FLIP map) for the report's filmstrip.
 *
 * K = 0 (the default) is two references, the pass's first and last frames
 * (K = F − 1): a default 60-frame path's references cost two still
 * references.  K = 1 compares every frame.  A still path gets this only
 * when K is set (its frames then move only with camera.orbit_deg_per_frame
 * and light.orbit_deg_per_frame; without them every frame is the same and
 * the temporal error is 0).
 *
 * Reference frames are cached like still references (run/refcache.h) with
 * the frame in the key, so a second run of the same path renders none.
 */
#ifndef RUN_MPATH_QUALITY_H
#define RUN_MPATH_QUALITY_H

#include <stddef.h>
#include <stdint.h>

#include "core/dm_results.h"
#include "run/mscene.h"

/* The temporal error map (img/<key>-temporal.png) is drawn through FLIP's
 * colour ramp with this luminance change per step at its top (a change of
 * a quarter of the range between reference frames is pale yellow). */
#define MPATH_TEMPORAL_MAP_TOP 0.25

/* At most this many reference frames of a configuration are written as
 * images for the report's filmstrip (img/<key>-path-fNNN.png, its
 * reference and FLIP map): evenly spread over the reference frames, the
 * first and last always among them, so K = 1 on a long path writes 3 × 16
 * files, not 3 per frame (docs/motion.md, "In the report"). */
#define MPATH_SHOTS_MAX 16

/* K as used on a pass of `frames` frames with camera.path_ref_every =
 * every: every itself when 1 <= every <= frames − 1; frames − 1 for 0 (the
 * default rule); 0 when every > frames − 1 or frames < 2 (no second
 * reference frame: refused). */
long mpath_quality_every(long frames, long every);
/* The number of reference frames 0, k, 2k, ... <= frames − 1 (0 when k < 1). */
size_t mpath_quality_count(long frames, long k);

/* The frames along a pass of `frames` frames with reference frames every
 * k-th (0, k, 2k, ... <= frames − 1; n of them) that are written as images,
 * at most cap: all n when n <= cap, else reference frame
 * round(j · (n − 1) / (cap − 1)) for j = 0 ... cap − 1 (halves rounded up),
 * so the first and last are always written and the rest evenly between.
 * Fills out[0 .. returned) in increasing order (out holds at least cap)
 * and returns how many: 0 when k < 1 or cap is 0; frame 0 alone for cap 1. */
size_t mpath_quality_shown(long frames, long k, size_t cap, long *out);

/* 1 when a configuration of these params gets quality along its path:
 * camera.path is not still, or camera.path_ref_every is set (not 0). */
int mpath_quality_wanted(const dm_kv *params, size_t n);

/* The reference image of params p at w×h — frame `frame` of its camera path
 * when on_path, else the still image (keyed as before paths) — loaded from
 * the reference cache when an entry for exactly these inputs exists, else
 * rendered at the sweep's supersampling and stored there.  The cache is off
 * with the program cache (job->cache_dir NULL).  *source (optional) gets
 * "cache" or "rendered".  0, or the renderer's error with the reason in
 * log. */
int mpath_reference_frame(mscene *m, const dm_kv *p, size_t n, int w, int h, int on_path,
                          uint64_t frame, float **rgba, float **depth, const char **source,
                          dm_str *log);

/* Quality along c's path against the reference parameters ref[0..n_ref):
 * fills out->path_quality (present, or its reason when it cannot be
 * computed) and writes img/<key>-temporal.png and the frames chosen by
 * mpath_quality_shown (img/<key>-path-fNNN.png, -fNNN-flip.png and
 * img/ref-<hash>-fNNN.png, listed in path_quality.shots; an image that
 * cannot be written is left out of its shot with the reason in c's log). */
void mpath_quality_measure(mscene *m, mconf *c, const dm_kv *ref, size_t n_ref,
                           dm_config_result *out);

#endif
