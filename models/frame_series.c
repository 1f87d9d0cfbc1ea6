/* frame_series.c — percentiles, 1 % lows and stutters of the frame times
 * along a replayed path (see frame_series.h for the definitions). */
#include "models/frame_series.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "models/stats.h"

/* Frame f's time: the median of its finite replays, into per[] (path
 * order, frames without one skipped, kept[f] = 1 for the others), and
 * its replay spread (max − min) / median into spread[*ns] when it has two
 * replays or more.  Returns the frames kept. */
static size_t frame_series__medians(const double *t, size_t replays, size_t frames, double *per, int *kept,
                                    double *spread, size_t *ns)
{
    double *col = dm_xcalloc(replays, sizeof *col);
    size_t n = 0;
    *ns = 0;
    for (size_t f = 0; f < frames; f++) {
        for (size_t s = 0; s < replays; s++)
            col[s] = t[s * frames + f];
        size_t m = 0;
        double *sorted = stats_sorted_finite(col, replays, &m);
        if (m > 0) {
            double med = stats_quantile_sorted(sorted, m, 0.5);
            per[n++] = med;
            kept[f] = 1;
            if (m > 1 && med > 0)
                spread[(*ns)++] = (sorted[m - 1] - sorted[0]) / med;
        }
        free(sorted);
    }
    free(col);
    return n;
}

/* The percentiles, the 1 % low and the stutters of the n frame times per[]
 * (path order; kept[] maps them back to frame indices). */
static void frame_series__figures(const double *per, size_t n, const int *kept, size_t frames,
                                  size_t *stutter_at, frame_series_stats *out)
{
    size_t m = 0;
    double *asc = stats_sorted_finite(per, n, &m);
    out->p50 = stats_quantile_sorted(asc, m, 0.50);
    out->p95 = stats_quantile_sorted(asc, m, 0.95);
    out->p99 = stats_quantile_sorted(asc, m, 0.99);
    out->low1_frames = (m + 99) / 100;
    double sum = 0;
    for (size_t i = 0; i < out->low1_frames; i++)   /* the slowest, from the top */
        sum += asc[m - 1 - i];
    out->low1_ns = sum / (double)out->low1_frames;
    out->low1_fps = out->low1_ns > 0 ? 1e9 / out->low1_ns : NAN;
    for (size_t f = 0, i = 0; f < frames; f++) {
        if (!kept[f])
            continue;
        if (per[i] > FRAME_SERIES_STUTTER * out->p50) {
            if (stutter_at)
                stutter_at[out->stutters] = f;
            out->stutters++;
        }
        i++;
    }
    free(asc);
}

int frame_series_summarize(const double *t, size_t replays, size_t frames, size_t *stutter_at,
                           frame_series_stats *out)
{
    memset(out, 0, sizeof *out);
    out->replay_spread = NAN;
    out->noisy = -1;
    if (!t || replays == 0 || frames == 0)
        return DM_ERR_ARG;
    double *per = dm_xcalloc(frames, sizeof *per), *spread = dm_xcalloc(frames, sizeof *spread);
    int *kept = dm_xcalloc(frames, sizeof *kept);
    size_t ns = 0, n = frame_series__medians(t, replays, frames, per, kept, spread, &ns);
    if (n > 0) {
        out->frames = n;
        out->replays = replays;
        frame_series__figures(per, n, kept, frames, stutter_at, out);
        if (ns > 0) {
            out->replay_spread = stats_median(spread, ns);
            out->noisy = out->replay_spread > FRAME_SERIES_NOISY;
        }
    }
    free(kept);
    free(spread);
    free(per);
    return n > 0 ? 0 : DM_ERR_ARG;
}
