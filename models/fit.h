/* fit.h — least-squares cost models fitted with Ceres (C++ bridge behind this C header).
 *
 * A model is a formula over variables (axes or counters) with free
 * parameters: "a + b*SamplesPassed", "a + b*tess_level^p".  Names that are
 * listed as variables are data; every other name is a parameter.  Functions:
 * + - * / ^, unary minus, parentheses, exp log sqrt min max.  Evaluated with
 * exact derivatives (ceres::Jet).  Features are scaled before solving and
 * parameters unscaled after.
 */
#ifndef MODELS_FIT_H
#define MODELS_FIT_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

typedef enum fit_loss { FIT_LOSS_DEFAULT = 0, FIT_LOSS_NONE, FIT_LOSS_HUBER, FIT_LOSS_CAUCHY } fit_loss;

typedef struct fit_bound {
    const char *param;
    double lo, hi;            /* use -INFINITY / INFINITY for none */
} fit_bound;

typedef struct fit_desc {
    const char *model;                 /* name recorded in the result; NULL = formula */
    const char *formula;               /* required */
    const char *response;              /* name of y, recorded */
    const char *const *variables;      /* n_vars names */
    size_t n_vars;
    const double *x;                   /* n_points rows of n_vars values, row-major */
    const double *y;                   /* n_points */
    size_t n_points;
    const char *const *point_labels;   /* optional, n_points */
    const fit_bound *bounds;
    size_t n_bounds;
    fit_loss loss;                     /* default: none */
    int folds;                         /* k-fold CV; 0 = min(5, n_points) */
    uint64_t seed;                     /* fold assignment */
} fit_desc;

/* Fits the model.  Returns 0 and fills `out` (params ± stderr, r2, rmse,
 * mape, cv_mape, termination, warnings, measured/predicted); on refusal
 * (formula error, fewer usable points than parameters, ...) returns
 * DM_ERR_PARSE / DM_ERR_ARG / DM_ERR_NUMERIC with a message in err (parse
 * errors name the column) and leaves out zeroed. Non-finite or
 * non-positive responses are excluded and counted in out->n_excluded. */
int fit_run(const fit_desc *desc, dm_fit_result *out, dm_str *err);

#endif
