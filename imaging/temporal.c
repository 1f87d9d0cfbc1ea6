/* temporal.c — the temporal error of a sequence against its reference and
 * the popping of a per-frame error (see temporal.h for the equations). */
#include "imaging/temporal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"

static double temporal__luma(const float *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int temporal__cmp(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

int temporal_error(const img *test, const img *ref, size_t n, temporal_stats *out, img *map)
{
    memset(out, 0, sizeof *out);
    out->mean = out->p99 = out->max = NAN;
    if (!test || !ref || n < 2 || !ref[0].px || ref[0].w <= 0 || ref[0].h <= 0)
        return DM_ERR_ARG;
    int w = ref[0].w, h = ref[0].h;
    for (size_t t = 0; t < n; t++)
        if (test[t].w != w || test[t].h != h || ref[t].w != w || ref[t].h != h || !test[t].px || !ref[t].px)
            return DM_ERR_ARG;
    size_t px = (size_t)w * (size_t)h, total = px * (n - 1), kept = 0;
    float *e = malloc(total * sizeof *e);
    double *sum = dm_xcalloc(px, sizeof *sum);
    size_t *cnt = dm_xcalloc(px, sizeof *cnt);
    if (!e) {
        free(sum);
        free(cnt);
        return DM_ERR_NOMEM;
    }
    double acc = 0, mx = 0;
    for (size_t t = 1; t < n; t++)
        for (size_t p = 0; p < px; p++) {
            double dt = temporal__luma(test[t].px + 4 * p) - temporal__luma(test[t - 1].px + 4 * p);
            double dr = temporal__luma(ref[t].px + 4 * p) - temporal__luma(ref[t - 1].px + 4 * p);
            double v = fabs(dt - dr);
            if (!isfinite(v)) {
                out->nonfinite++;
                continue;
            }
            e[kept++] = (float)v;
            acc += v;
            mx = v > mx ? v : mx;
            sum[p] += v;
            cnt[p]++;
        }
    out->steps = n - 1;
    int rc = 0;
    if (kept > 0) {
        out->mean = acc / (double)kept;
        out->max = mx;
        qsort(e, kept, sizeof *e, temporal__cmp);
        double pos = 0.99 * (double)(kept - 1);
        size_t lo = (size_t)floor(pos), hi = lo + 1 < kept ? lo + 1 : lo;
        out->p99 = e[lo] + (pos - (double)lo) * ((double)e[hi] - e[lo]);
    }
    if (map && (rc = img_alloc(map, w, h)) == 0)
        for (size_t p = 0; p < px; p++) {
            float v = cnt[p] ? (float)(sum[p] / (double)cnt[p]) : NAN;
            map->px[4 * p] = map->px[4 * p + 1] = map->px[4 * p + 2] = v;
            map->px[4 * p + 3] = 1.0f;
        }
    free(e);
    free(sum);
    free(cnt);
    return rc;
}

double temporal_popping(const double *e, size_t n, size_t *at)
{
    double best = NAN;
    for (size_t t = 1; e && t < n; t++) {
        double j = fabs(e[t] - e[t - 1]);
        if (isfinite(j) && !(j <= best)) {
            best = j;
            if (at)
                *at = t;
        }
    }
    return best;
}
