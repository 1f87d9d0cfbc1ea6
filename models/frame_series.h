/* frame_series.h — statistics of the frame times along a camera path.
 *
 * A path of F frames is replayed S times, identically (the same camera and
 * lights at frame f in every replay); t[s * F + f] is the time of frame f
 * in replay s, in nanoseconds.  Non-finite times count as missing.
 *
 * Definitions (docs/motion.md, "Frame times along a path"):
 *   frame time   of frame f: the median of its S replays (one slow replay
 *                of a frame does not make it a stutter);
 *   p50/p95/p99  type-7 quantiles of the F frame times;
 *   1 % low      the mean of the slowest ceil(F / 100) frame times, as a
 *                time and as a frame rate (1e9 / time);
 *   stutter      a frame whose time is over FRAME_SERIES_STUTTER times the
 *                p50; their count and their frame indices;
 *   replay spread  for each frame, (max − min) / median over its replays;
 *                the series' spread is the median over frames.  Over
 *                FRAME_SERIES_NOISY the series is noisy: the replays of the
 *                same frame disagree more than the percentiles can be read
 *                to.  With one replay the spread cannot be measured.
 */
#ifndef MODELS_FRAME_SERIES_H
#define MODELS_FRAME_SERIES_H

#include <stddef.h>

#define FRAME_SERIES_STUTTER 2.0
#define FRAME_SERIES_NOISY 0.10

typedef struct frame_series_stats {
    size_t frames;           /* frames with at least one finite replay */
    size_t replays;
    double p50, p95, p99;    /* ns */
    double low1_ns, low1_fps;
    size_t low1_frames;      /* frames averaged in the 1 % low */
    size_t stutters;
    double replay_spread;    /* NaN with one replay */
    int noisy;               /* 1 noisy, 0 not, -1 unknown (one replay) */
} frame_series_stats;

/* Summarises t (replays × frames, row = replay).  stutter_at (optional, room
 * for `frames` entries) receives the stutters' frame indices in path order.
 * Returns 0, or DM_ERR_ARG when there is no finite time (out zeroed). */
int frame_series_summarize(const double *t, size_t replays, size_t frames, size_t *stutter_at,
                           frame_series_stats *out);

#endif
