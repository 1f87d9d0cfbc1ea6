/* changepoint.c — change points across runs (changepoint.h). */
#include "models/changepoint.h"
#include "models/compare_stats.h"

#include "core/dm_util.h"

#include <math.h>
#include <stdlib.h>

size_t changepoint_find(const changepoint_series *runs, size_t n, double alpha, double threshold,
                        unsigned char *change, double *q)
{
    alpha = alpha > 0 ? alpha : 0.01;
    threshold = threshold > 0 ? threshold : 0.05;
    double *p = dm_xcalloc(n + 1, sizeof *p);
    unsigned char *none = dm_xcalloc(n + 1, 1);
    for (size_t i = 1; i < n; i++) {
        p[i] = compare_stats_mann_whitney(runs[i - 1].samples, runs[i - 1].n, runs[i].samples,
                                          runs[i].n, NULL);
        none[i] = isnan(p[i]);
        p[i] = none[i] ? 1 : p[i];   /* no test: never a change, and BH sees no NaN */
    }
    if (n > 1)
        compare_stats_bh(p + 1, n - 1, p + 1);
    size_t found = 0;
    for (size_t i = 0; i < n; i++) {
        double rel = i ? fabs(runs[i].median / runs[i - 1].median - 1) : 0;
        change[i] = i && !none[i] && p[i] < alpha && rel > threshold;
        found += change[i];
        if (q)
            q[i] = i && !none[i] ? p[i] : NAN;
    }
    free(p);
    free(none);
    return found;
}
