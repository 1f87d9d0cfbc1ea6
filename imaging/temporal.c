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

static int temporal__same_size(const img *im, int w, int h)
{
    return im && im->px && im->w == w && im->h == h;
}

int temporal_acc_init(temporal_acc *a, int w, int h)
{
    memset(a, 0, sizeof *a);
    if (w <= 0 || h <= 0)
        return DM_ERR_ARG;
    size_t px = (size_t)w * (size_t)h;
    a->w = w;
    a->h = h;
    a->sum = dm_xcalloc(px, sizeof *a->sum);
    a->cnt = dm_xcalloc(px, sizeof *a->cnt);
    return 0;
}

int temporal_acc_step(temporal_acc *a, const img *t0, const img *t1, const img *r0, const img *r1)
{
    int w = a->w, h = a->h;
    if (!temporal__same_size(t0, w, h) || !temporal__same_size(t1, w, h) ||
        !temporal__same_size(r0, w, h) || !temporal__same_size(r1, w, h))
        return DM_ERR_ARG;
    size_t px = (size_t)w * (size_t)h;
    if (a->kept + px > a->cap) {
        size_t cap = a->cap ? 2 * a->cap : px;
        while (cap < a->kept + px)
            cap *= 2;
        float *e = realloc(a->e, cap * sizeof *e);
        if (!e)
            return DM_ERR_NOMEM;
        a->e = e;
        a->cap = cap;
    }
    for (size_t p = 0; p < px; p++) {
        double dt = temporal__luma(t1->px + 4 * p) - temporal__luma(t0->px + 4 * p);
        double dr = temporal__luma(r1->px + 4 * p) - temporal__luma(r0->px + 4 * p);
        double v = fabs(dt - dr);
        if (!isfinite(v)) {
            a->nonfinite++;
            continue;
        }
        a->e[a->kept++] = (float)v;
        a->acc += v;
        a->max = v > a->max ? v : a->max;
        a->sum[p] += v;
        a->cnt[p]++;
    }
    a->steps++;
    return 0;
}

int temporal_acc_finish(temporal_acc *a, temporal_stats *out, img *map)
{
    memset(out, 0, sizeof *out);
    out->mean = out->p99 = out->max = NAN;
    out->steps = a->steps;
    out->nonfinite = a->nonfinite;
    int rc = a->steps ? 0 : DM_ERR_ARG;
    if (a->kept > 0) {
        out->mean = a->acc / (double)a->kept;
        out->max = a->max;
        qsort(a->e, a->kept, sizeof *a->e, temporal__cmp);
        double pos = 0.99 * (double)(a->kept - 1);
        size_t lo = (size_t)floor(pos), hi = lo + 1 < a->kept ? lo + 1 : lo;
        out->p99 = a->e[lo] + (pos - (double)lo) * ((double)a->e[hi] - a->e[lo]);
    }
    size_t px = (size_t)a->w * (size_t)a->h;
    if (rc == 0 && map && (rc = img_alloc(map, a->w, a->h)) == 0)
        for (size_t p = 0; p < px; p++) {
            float v = a->cnt[p] ? (float)(a->sum[p] / (double)a->cnt[p]) : NAN;
            map->px[4 * p] = map->px[4 * p + 1] = map->px[4 * p + 2] = v;
            map->px[4 * p + 3] = 1.0f;
        }
    free(a->e);
    free(a->sum);
    free(a->cnt);
    memset(a, 0, sizeof *a);
    return rc;
}

int temporal_error(const img *test, const img *ref, size_t n, temporal_stats *out, img *map)
{
    memset(out, 0, sizeof *out);
    out->mean = out->p99 = out->max = NAN;
    if (!test || !ref || n < 2 || !ref[0].px || ref[0].w <= 0 || ref[0].h <= 0)
        return DM_ERR_ARG;
    int w = ref[0].w, h = ref[0].h;
    for (size_t t = 0; t < n; t++)
        if (!temporal__same_size(&test[t], w, h) || !temporal__same_size(&ref[t], w, h))
            return DM_ERR_ARG;
    temporal_acc a;
    int rc = temporal_acc_init(&a, w, h);
    for (size_t t = 1; rc == 0 && t < n; t++)
        rc = temporal_acc_step(&a, &test[t - 1], &test[t], &ref[t - 1], &ref[t]);
    int frc = temporal_acc_finish(&a, out, map);
    return rc ? rc : frc;
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
