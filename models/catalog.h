/* catalog.h — built-in cost models (docs/models.md): a name, a formula and bounds.
 *
 * Built-in models are formulas like any user formula; the catalog only
 * gives them names and non-negativity bounds where physics demands them
 * (a cost per vertex cannot be negative).
 */
#ifndef MODELS_CATALOG_H
#define MODELS_CATALOG_H

#include <stddef.h>
#include "models/fit.h"

typedef struct models_builtin {
    const char *name;
    const char *formula;
    const char *response;          /* default response */
    const char *description;
    const fit_bound *bounds;
    size_t n_bounds;
    const char *group_by;          /* default --group-by (one key), NULL: one fit */
    const char *requires;          /* the counters the model is about, separated by spaces,
                                      which a run must have (their terms are not dropped as
                                      a technique's unread axis would be); NULL: none beyond
                                      the response */
} models_builtin;

size_t models_builtin_count(void);
const models_builtin *models_builtin_at(size_t i);
/* NULL when `name` is not a built-in model. */
const models_builtin *models_builtin_find(const char *name);

#endif
