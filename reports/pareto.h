/* pareto.h — the Pareto front of (cost, error) points, lower-left is better. */
#ifndef REPORTS_PARETO_H
#define REPORTS_PARETO_H

#include <stddef.h>

/* Indices of the points no other point dominates (j dominates i when
 * x_j <= x_i and y_j <= y_i with at least one strict).  Points with a
 * non-finite coordinate are neither on the front nor dominate.  Equal points
 * are all on the front.  out (capacity n) receives the indices sorted by x,
 * then y, then index; returns how many. */
size_t pareto_front(const double *x, const double *y, size_t n, size_t *out);

#endif
