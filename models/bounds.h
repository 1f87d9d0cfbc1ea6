/* bounds.h — parameter bounds written after a cost-model formula.
 *
 *   "a + b*SamplesPassed; a >= 0; b >= 0"
 *   "a + b*tess_level^p; 0.5 <= p <= 3"
 *
 * Clauses follow the expression, each after a ';': NAME >= NUMBER,
 * NAME <= NUMBER, or NUMBER <= NAME <= NUMBER (spaces anywhere).  A name
 * that is not a parameter of the formula is refused by fit_run, with the
 * parameters listed.
 */
#ifndef MODELS_BOUNDS_H
#define MODELS_BOUNDS_H

#include <stddef.h>
#include "core/dm_util.h"
#include "models/fit.h"

/* Splits text into the expression (*expr, malloc'd) and its bounds
 * (*bounds, n_bounds; each param malloc'd; free with bounds_free).  Text
 * without ';' gives the whole text and no bounds.  Returns 0, or
 * DM_ERR_PARSE with "formula: bound N 'CLAUSE': expected ..." in err
 * (outputs untouched). */
int bounds_split(const char *text, char **expr, fit_bound **bounds, size_t *n_bounds, dm_str *err);
void bounds_free(fit_bound *bounds, size_t n);

#endif
