/* pareto.c — Pareto front by pairwise dominance (n is a few hundred at most). */
#include "reports/pareto.h"

#include <math.h>
#include <stdlib.h>

static int dominates(const double *x, const double *y, size_t j, size_t i)
{
    return x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i]);
}

static int finite_point(const double *x, const double *y, size_t i)
{
    return isfinite(x[i]) && isfinite(y[i]);
}

size_t pareto_front(const double *x, const double *y, size_t n, size_t *out)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (!finite_point(x, y, i))
            continue;
        int dominated = 0;
        for (size_t j = 0; j < n && !dominated; j++)
            dominated = j != i && finite_point(x, y, j) && dominates(x, y, j, i);
        if (!dominated)
            out[m++] = i;
    }
    /* insertion sort by (x, y, index): m is small and it keeps ties stable */
    for (size_t a = 1; a < m; a++) {
        size_t v = out[a], b = a;
        while (b > 0 && (x[out[b - 1]] > x[v] || (x[out[b - 1]] == x[v] && y[out[b - 1]] > y[v]))) {
            out[b] = out[b - 1];
            b--;
        }
        out[b] = v;
    }
    return m;
}
