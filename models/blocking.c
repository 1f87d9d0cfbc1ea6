/* blocking.c — blocking by round (see blocking.h). */
#include "models/blocking.h"

#include <math.h>
#include <stdlib.h>

#include "core/dm_util.h"
#include "models/stats.h"

/* Each series' median (NaN without a finite sample). */
static double *blocking__medians(const blocking_series *s, size_t n)
{
    double *m = dm_xcalloc(n + 1, sizeof *m);
    for (size_t i = 0; i < n; i++)
        m[i] = stats_median(s[i].x, s[i].n);
    return m;
}

/* Median of x_k[r] / median_k over the series k != skip with a finite
 * sample in round r; NaN when fewer than need of them. */
static double blocking__factor(const blocking_series *s, size_t n, const double *med, size_t r,
                               size_t skip, size_t need, double *tmp)
{
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (k != skip && r < s[k].n && isfinite(s[k].x[r]) && med[k] > 0)
            tmp[m++] = s[k].x[r] / med[k];
    return m >= need ? stats_median(tmp, m) : NAN;
}

size_t blocking_correct(const blocking_series *series, size_t n_series, double *const *out)
{
    double *med = blocking__medians(series, n_series);
    double *tmp = dm_xcalloc(n_series + 1, sizeof *tmp);
    size_t corrected = 0;
    for (size_t c = 0; c < n_series; c++) {
        int any = 0;
        for (size_t r = 0; r < series[c].n; r++) {
            double f = blocking__factor(series, n_series, med, r, c, BLOCKING_MIN_OTHERS, tmp);
            int use = isfinite(f) && f > 0;
            out[c][r] = use ? series[c].x[r] / f : series[c].x[r];
            any |= use;
        }
        corrected += (size_t)any;
    }
    free(tmp);
    free(med);
    return corrected;
}

size_t blocking_round_factors(const blocking_series *series, size_t n_series, double *factors,
                              size_t n_rounds)
{
    double *med = blocking__medians(series, n_series);
    double *tmp = dm_xcalloc(n_series + 1, sizeof *tmp);
    size_t found = 0;
    for (size_t r = 0; r < n_rounds; r++) {
        factors[r] = blocking__factor(series, n_series, med, r, (size_t)-1,
                                      BLOCKING_MIN_OTHERS + 1, tmp);
        found += isfinite(factors[r]);
    }
    free(tmp);
    free(med);
    return found;
}

double blocking_spread(const double *factors, size_t n)
{
    double lo = INFINITY, hi = -INFINITY;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(factors[i]) && factors[i] > 0) {
            lo = fmin(lo, log(factors[i]));
            hi = fmax(hi, log(factors[i]));
            m++;
        }
    return m < 2 ? 0.0 : exp((hi - lo) / 2) - 1;
}
