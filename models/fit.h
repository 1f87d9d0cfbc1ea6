/* fit.h — least-squares cost models fitted with Ceres (C++ bridge behind this C header).
 *
 * A model is a formula over variables (axes or counters) with free
 * parameters: "a + b*SamplesPassed", "a + b*tess_level^p".  Names that are
 * listed as variables are data; every other name is a parameter.  Functions:
 * + - * / ^, unary minus, parentheses, exp log sqrt min max.  Evaluated with
 * exact derivatives (forward-mode dual numbers in formula.c; the Ceres
 * bridge is fit_ceres.h).  Grammar and errors: formula.h.
 *
 * How a fit is done (numerical stability, docs/models.md):
 *  - Screening: a point is excluded (counted in n_excluded, one warning)
 *    when its response is non-finite or <= 0 or a variable the formula uses
 *    is non-finite.  Fewer usable points than parameters -> DM_ERR_ARG.
 *  - Constant columns (max - min <= 1e-12 max|value| over usable points):
 *    every top-level additive term using the variable is DROPPED with a
 *    warning naming the variable, its value and the term ("c*x2"); if no
 *    parameter is left the fit is refused (DM_ERR_ARG).
 *  - Near-collinear used variables (|corr| > 0.9999): warning naming both.
 *  - Scaling: residuals are r_i = (f(x_i) - y_i) / s_y with s_y = max y
 *    (desc.relative: s_y = y_i, each point's error in proportion to it),
 *    and Ceres solves for theta_j = p_j / s_j where s_j = 1/||dr/dp_j||
 *    (Jacobian column norm, recomputed at the start of every solve pass).
 *    This is feature scaling done in parameter space, so it works for any
 *    formula: for a linear term b*x it is exactly dividing x by its norm,
 *    and parameters are mapped back (p = s*theta) after each pass.
 *    Magnitudes 1e-9..1e9 fit to ~1e-12 relative (tests: "stiff").
 *  - Starting values: 1 for every parameter (clamped into its bounds).
 *    Parameters in which the formula is affine (structural test) are first
 *    solved with the nonlinear ones held (a linear least-squares pass,
 *    exact in one Gauss-Newton step), then all parameters together.
 *  - Robust loss: the scale is k * 1.4826 * MAD of the scaled residuals of
 *    the previous pass (k = 1.345 Huber, 2.3849 Cauchy; the usual 95%
 *    efficiency constants), floored at 1e-12; two reweighted passes.
 *  - Covariance: Ceres DENSE_SVD with null_space_rank = 0 on the scaled
 *    problem (so it is well conditioned unless the model truly is not); a
 *    rank-deficient Jacobian gives a warning and stderr = NaN (never a
 *    silently pseudo-inverted value).  stderr_j = sqrt(cov_jj) *
 *    sqrt(RSS / (n - p)); with n == p stderr is NaN with a warning.
 *  - Condition: out->condition = sigma_max / sigma_min of the Jacobian of
 *    that covariance pass (unit-norm columns, robust weights included), i.e.
 *    Belsley's scaled condition number; INFINITY when rank deficient (Ceres'
 *    test (sigma_min/sigma_max)^2 < 1e-14, so finite values are < 1e7).
 *    Above FIT_ILL_CONDITIONED (1e3) a warning names, in formula order, the
 *    two parameters with the largest components of the weakest direction
 *    (right singular vector of sigma_min): the least-squares perturbation
 *    bound makes a relative change e of the data move the parameters by up
 *    to about condition * e relative, so at 1e3 a 0.1 % timing change (below
 *    the noise here) can move that parameter combination by 100 %.
 *  - Output: r2 = 1 - RSS/TSS, rmse = sqrt(RSS/n), mape and cv_mape in
 *    PERCENT (mean |pred - y| / y * 100); cv_mape from k-fold CV (folds by
 *    a seeded shuffle, fold = position mod k, each refit from the full-fit
 *    parameters on the other folds, predicting the held-out points);
 *    termination = "CONVERGENCE after N iterations" (Ceres' type and the
 *    iterations summed over the passes); measured/predicted/point_labels
 *    cover the n_points usable points in input order.  A Ceres FAILURE is
 *    DM_ERR_NUMERIC; NO_CONVERGENCE is a usable fit with a warning.
 */
#ifndef MODELS_FIT_H
#define MODELS_FIT_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

/* Condition number above which a fit is reported ill-conditioned. */
#define FIT_ILL_CONDITIONED 1e3
/* A fit is reported poor (a warning; docs/models.md) when R² is below
 * FIT_POOR_R2 — it explains less than 80 % of the variation, so its terms
 * are not the costs they claim to be (the report then draws no per-stage
 * breakdown from it) — or when CV-MAPE, the error predicting held-out
 * configurations, is above FIT_POOR_CV_MAPE percent. */
#define FIT_POOR_R2 0.8
#define FIT_POOR_CV_MAPE 20.0

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
    int relative;                      /* 1: least squares of relative errors, (f - y) / y (weights
                                        * 1/y^2), so responses spanning orders of magnitude are fitted
                                        * in proportion; 0: of (f - y) / max y */
    uint64_t seed;                     /* fold assignment */
} fit_desc;

/* Fits the model.  Returns 0 and fills `out` (params ± stderr, r2, rmse,
 * mape, cv_mape, termination, warnings, measured/predicted); on refusal
 * (formula error, fewer usable points than parameters, ...) returns
 * DM_ERR_PARSE / DM_ERR_ARG / DM_ERR_NUMERIC with a message in err (parse
 * errors name the column; an unknown bound name is DM_ERR_UNKNOWN) and
 * leaves out zeroed. Non-finite or
 * non-positive responses are excluded and counted in out->n_excluded. */
int fit_run(const fit_desc *desc, dm_fit_result *out, dm_str *err);

#endif
