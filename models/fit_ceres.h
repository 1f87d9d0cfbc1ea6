/* fit_ceres.h — plain C interface to the Ceres solver (fit_ceres.cc is the
 * only C++ translation unit of models/).
 *
 * The problem is a sum of squared scalar residuals r_i(theta), one residual
 * block per point, all over one parameter block theta of n_params values.
 * The caller supplies residuals and exact Jacobian rows through a callback;
 * the bridge only configures Ceres (Levenberg-Marquardt, DENSE_QR, optional
 * robust loss, bounds, parameters held constant) and the covariance
 * (DENSE_SVD, null_space_rank = 0 so a rank-deficient Jacobian is reported
 * as cov_ok = 0 instead of being silently pseudo-inverted).  With the
 * covariance it also reports the 2-norm condition number of the Jacobian
 * the solver saw (from its singular values, Eigen's JacobiSVD).
 */
#ifndef MODELS_FIT_CERES_H
#define MODELS_FIT_CERES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes r_i(theta) into *r and, when jac is not NULL, dr_i/dtheta into
 * jac[0..n_params).  Returns 0, or nonzero when the value is not finite
 * (Ceres then rejects the step). */
typedef int (*fit_ceres_residual_fn)(void *user, size_t i, const double *theta,
                                     double *r, double *jac);

typedef enum fit_ceres_loss { FIT_CERES_LOSS_NONE = 0, FIT_CERES_LOSS_HUBER,
                              FIT_CERES_LOSS_CAUCHY } fit_ceres_loss;

typedef struct fit_ceres_problem {
    size_t n_params, n_residuals;
    fit_ceres_residual_fn residual;
    void *user;
    const double *lo, *hi;          /* n_params bounds each (+-INFINITY = none); NULL = none */
    const unsigned char *fixed;     /* n_params flags: held constant; NULL = none */
    fit_ceres_loss loss;
    double loss_scale;              /* residual magnitude where the loss turns robust */
    int max_iterations;             /* 0 = 200 */
    double *cov;                    /* n_params^2 row-major, filled when not NULL */
    double *weak_dir;               /* n_params: with cov, the right singular vector of
                                     * the smallest singular value of J (unit norm) */
} fit_ceres_problem;

typedef struct fit_ceres_summary {
    int usable;                     /* CONVERGENCE or NO_CONVERGENCE with a finite cost */
    int converged;
    int iterations;
    double final_cost;              /* 1/2 sum rho(r_i^2) */
    int cov_ok;                     /* covariance computed (Jacobian of full rank) */
    double condition;               /* with cov: sigma_max / sigma_min of the Jacobian at
                                     * the solution (>= 1); INFINITY when rank deficient
                                     * (Ceres' test: (sigma_min/sigma_max)^2 < 1e-14);
                                     * 0 when not computed */
    char termination[32];           /* "CONVERGENCE", "NO_CONVERGENCE", "FAILURE", ... */
    char message[160];              /* Ceres' reason */
} fit_ceres_summary;

/* Minimises from the starting point theta (n_params, updated in place).
 * Returns 0 (see summary->usable for the outcome), or DM_ERR_ARG for an
 * invalid problem (no parameters, all held constant). */
int fit_ceres_solve(const fit_ceres_problem *pb, double *theta, fit_ceres_summary *summary);

#ifdef __cplusplus
}
#endif

#endif
