/* frame_series.c — percentiles, 1 % lows and stutters of the frame times
 * along a replayed path (see frame_series.h for the definitions). */
#include "models/frame_series.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "models/stats.h"

static int frame_series__desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

int frame_series_summarize(const double *t, size_t replays, size_t frames, size_t *stutter_at,
                           frame_series_stats *out)
{
    memset(out, 0, sizeof *out);
    out->replay_spread = NAN;
    out->noisy = -1;
    if (!t || replays == 0 || frames == 0)
        return DM_ERR_ARG;
    double *per = dm_xcalloc(frames, sizeof *per), *col = dm_xcalloc(replays, sizeof *col);
    double *spread = dm_xcalloc(frames, sizeof *spread);
    size_t n = 0, ns = 0;
    int *kept = dm_xcalloc(frames, sizeof *kept);
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
                spread[ns++] = (sorted[m - 1] - sorted[0]) / med;
        }
        free(sorted);
    }
    int rc = 0;
    if (n == 0) {
        rc = DM_ERR_ARG;
    } else {
        out->frames = n;
        out->replays = replays;
        double *s = dm_xmalloc(n * sizeof *s);
        memcpy(s, per, n * sizeof *s);
        qsort(s, n, sizeof *s, frame_series__desc);   /* slowest first */
        double *asc = stats_sorted_finite(per, n, &n);
        out->p50 = stats_quantile_sorted(asc, n, 0.50);
        out->p95 = stats_quantile_sorted(asc, n, 0.95);
        out->p99 = stats_quantile_sorted(asc, n, 0.99);
        out->low1_frames = (n + 99) / 100;
        double sum = 0;
        for (size_t i = 0; i < out->low1_frames; i++)
            sum += s[i];
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
        if (ns > 0) {
            out->replay_spread = stats_median(spread, ns);
            out->noisy = out->replay_spread > FRAME_SERIES_NOISY;
        }
        free(asc);
        free(s);
    }
    free(kept);
    free(spread);
    free(col);
    free(per);
    return rc;
}
