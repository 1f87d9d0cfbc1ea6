/* fit.c — least-squares cost models: data screening, scaling, solving via
 * the Ceres bridge, statistics and cross-validation (see fit.h). */
#include "models/bounds.h"
#include "models/fit.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "models/fit_ceres.h"
#include "models/formula.h"
#include "models/rng.h"
#include "models/stats.h"

/* The data and scratch space shared by every solve of one fit_run. */
typedef struct fit__ctx {
    const fit_desc *d;
    formula *f;
    size_t P;
    const size_t *rows;             /* rows of the current solve */
    size_t m;
    double s_y;                     /* response scale: max y over the rows */
    int relative;                   /* each residual over its own y (fit_desc.relative) */
    double *scale;                  /* P: parameter p_j = theta_j * scale_j */
    double *p, *grad;               /* P scratch */
    double *weak;                   /* P: weakest direction of the covariance pass */
    const double *lo, *hi;          /* P bounds on p */
} fit__ctx;

/* ---- warnings and messages ------------------------------------------------ */

static void fit__warn(dm_fit_result *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void fit__warn(dm_fit_result *r, const char *fmt, ...)
{
    dm_str s = { 0 };
    va_list ap;
    va_start(ap, fmt);
    dm_str_vprintf(&s, fmt, ap);
    va_end(ap);
    DM_VEC_PUSH(r->warnings, r->n_warnings, dm_str_take(&s));
}

static const double *fit__row(const fit_desc *d, size_t row)
{
    return d->x + row * d->n_vars;
}

/* ---- residuals in scaled space ------------------------------------------- */

/* What a residual of row is divided by: its own response for a relative
 * fit (weights 1/y^2), else the rows' largest response. */
static double fit__yscale(const fit__ctx *c, size_t row)
{
    return c->relative ? c->d->y[row] : c->s_y;
}

/* r_i = (f(x_i; p) - y_i) / fit__yscale with p = theta * scale (element-wise). */
static int fit__residual(void *user, size_t i, const double *theta, double *r, double *jac)
{
    fit__ctx *c = user;
    size_t row = c->rows[i];
    for (size_t j = 0; j < c->P; j++)
        c->p[j] = theta[j] * c->scale[j];
    double v = formula_eval(c->f, fit__row(c->d, row), c->p, jac ? c->grad : NULL);
    double sy = fit__yscale(c, row);
    *r = (v - c->d->y[row]) / sy;
    if (!isfinite(*r))
        return -1;
    for (size_t j = 0; jac && j < c->P; j++) {
        jac[j] = c->grad[j] * c->scale[j] / sy;
        if (!isfinite(jac[j]))
            return -1;
    }
    return 0;
}

/* Jacobi column scaling at p: scale_j = 1 / ||d r / d p_j||, so that every
 * column of the Jacobian Ceres sees has unit norm (1 for a dead column). */
static void fit__column_scales(fit__ctx *c, const double *p)
{
    double *ss = dm_xcalloc(c->P, sizeof *ss);
    for (size_t i = 0; i < c->m; i++) {
        formula_eval(c->f, fit__row(c->d, c->rows[i]), p, c->grad);
        double sy = fit__yscale(c, c->rows[i]);
        for (size_t j = 0; j < c->P; j++)
            ss[j] += (c->grad[j] / sy) * (c->grad[j] / sy);
    }
    for (size_t j = 0; j < c->P; j++)
        c->scale[j] = (ss[j] > 0.0 && isfinite(ss[j])) ? 1.0 / sqrt(ss[j]) : 1.0;
    free(ss);
}

/* Scaled residuals of the current rows at p into r (m values). */
static void fit__residuals(fit__ctx *c, const double *p, double *r)
{
    for (size_t i = 0; i < c->m; i++) {
        size_t row = c->rows[i];
        r[i] = (formula_eval(c->f, fit__row(c->d, row), p, NULL) - c->d->y[row]) / fit__yscale(c, row);
    }
}

/* One Ceres solve from p (updated) with scales recomputed at p.  cov, when
 * not NULL, receives (J^T J)^-1 in p space for the scaled residuals.
 * Returns 1 when the solution is usable. */
static int fit__pass(fit__ctx *c, double *p, const unsigned char *fixed, fit_ceres_loss loss,
                     double loss_scale, double *cov, fit_ceres_summary *sum)
{
    size_t P = c->P;
    double *theta = dm_xmalloc(3 * P * sizeof *theta), *lo = theta + P, *hi = lo + P;
    fit__column_scales(c, p);
    for (size_t j = 0; j < P; j++) {
        theta[j] = p[j] / c->scale[j];
        lo[j] = c->lo[j] / c->scale[j];
        hi[j] = c->hi[j] / c->scale[j];
    }
    fit_ceres_problem pb = { .n_params = P, .n_residuals = c->m, .residual = fit__residual,
                             .user = c, .lo = lo, .hi = hi, .fixed = fixed, .loss = loss,
                             .loss_scale = loss_scale, .cov = cov,
                             .weak_dir = cov ? c->weak : NULL };
    int iters = sum->iterations;
    int ok = fit_ceres_solve(&pb, theta, sum) == 0 && sum->usable;
    sum->iterations += iters;
    for (size_t j = 0; ok && j < P; j++)
        p[j] = theta[j] * c->scale[j];
    for (size_t j = 0; cov && j < P * P; j++)
        cov[j] *= c->scale[j / P] * c->scale[j % P];
    free(theta);
    return ok;
}

/* Robust spread of the scaled residuals at p: 1.4826 * MAD (consistent
 * with sigma for normal errors), floored at 1e-12 (an exact fit). */
static double fit__robust_sigma(fit__ctx *c, const double *p)
{
    double *r = dm_xmalloc(c->m * sizeof *r);
    fit__residuals(c, p, r);
    double med = stats_median(r, c->m);
    for (size_t i = 0; i < c->m; i++)
        r[i] = fabs(r[i] - med);
    double s = 1.4826 * stats_median(r, c->m);
    free(r);
    return s > 1e-12 ? s : 1e-12;
}

/* The full solve on c->rows from the start p (updated): linear parameters
 * first with the nonlinear ones held, then all, then (robust loss) two
 * reweighted rounds, then the covariance pass.  Returns 1 when usable. */
static int fit__solve(fit__ctx *c, double *p, fit_loss loss, double *cov, fit_ceres_summary *sum)
{
    size_t P = c->P, n_lin = 0;
    unsigned char *fixed = dm_xcalloc(P, 1);
    c->s_y = 0.0;
    for (size_t i = 0; i < c->m; i++)
        c->s_y = fmax(c->s_y, c->d->y[c->rows[i]]);
    for (size_t j = 0; j < P; j++) {
        fixed[j] = !formula_param_is_linear(c->f, j);
        n_lin += !fixed[j];
    }
    memset(sum, 0, sizeof *sum);
    int ok = 1;
    if (n_lin > 0 && n_lin < P)
        ok = fit__pass(c, p, fixed, FIT_CERES_LOSS_NONE, 0.0, NULL, sum);
    ok = ok && fit__pass(c, p, NULL, FIT_CERES_LOSS_NONE, 0.0, NULL, sum);
    fit_ceres_loss cl = loss == FIT_LOSS_HUBER ? FIT_CERES_LOSS_HUBER
                      : loss == FIT_LOSS_CAUCHY ? FIT_CERES_LOSS_CAUCHY : FIT_CERES_LOSS_NONE;
    double k = cl == FIT_CERES_LOSS_HUBER ? 1.345 : 2.3849, a = 0.0;
    for (int round = 0; ok && cl != FIT_CERES_LOSS_NONE && round < 2; round++) {
        a = k * fit__robust_sigma(c, p);
        ok = fit__pass(c, p, NULL, cl, a, NULL, sum);
    }
    if (ok && cov)
        ok = fit__pass(c, p, NULL, cl, a, cov, sum);
    free(fixed);
    return ok;
}

/* ---- screening ------------------------------------------------------------ */

static int fit__validate(const fit_desc *d, dm_str *err)
{
    if (!d->formula) {
        dm_str_cat(err, "fit: no formula given");
        return DM_ERR_ARG;
    }
    if (d->n_points && (!d->y || (d->n_vars && !d->x))) {
        dm_str_cat(err, "fit: data arrays missing (x or y is NULL)");
        return DM_ERR_ARG;
    }
    for (size_t i = 0; i < d->n_bounds; i++)
        if (!(d->bounds[i].lo <= d->bounds[i].hi)) {
            dm_str_printf(err, "fit: bound on '%s': lower %g is above upper %g",
                          d->bounds[i].param, d->bounds[i].lo, d->bounds[i].hi);
            return DM_ERR_ARG;
        }
    return 0;
}

/* Every bound must name a parameter of the (unreduced) formula. */
static int fit__check_bound_names(const fit_desc *d, const formula *f, dm_str *err)
{
    for (size_t i = 0; i < d->n_bounds; i++) {
        if (formula_param_index(f, d->bounds[i].param) >= 0)
            continue;
        dm_str_printf(err, "fit: bound on '%s', which is not a parameter of '%s' (parameters:",
                      d->bounds[i].param, d->formula);
        for (size_t j = 0; j < formula_n_params(f); j++)
            dm_str_printf(err, " %s", formula_param_name(f, j));
        dm_str_cat(err, ")");
        return DM_ERR_UNKNOWN;
    }
    return 0;
}

/* Usable rows: finite positive response and finite values of every variable
 * the formula uses.  Returns the malloc'd row list, count in *m. */
static size_t *fit__usable_rows(const fit_desc *d, const formula *f, size_t *m, dm_fit_result *r)
{
    size_t *rows = dm_xmalloc((d->n_points ? d->n_points : 1) * sizeof *rows);
    size_t bad_y = 0, bad_x = 0;
    *m = 0;
    for (size_t i = 0; i < d->n_points; i++) {
        int ok_x = 1;
        for (size_t v = 0; v < d->n_vars; v++)
            ok_x &= isfinite(fit__row(d, i)[v]) || !formula_uses_var(f, v);
        if (!(isfinite(d->y[i]) && d->y[i] > 0.0))
            bad_y++;
        else if (!ok_x)
            bad_x++;
        else
            rows[(*m)++] = i;
    }
    r->n_excluded = (int)(bad_y + bad_x);
    if (bad_y + bad_x)
        fit__warn(r, "excluded %zu of %zu points: %zu with a non-finite or non-positive response, "
                  "%zu with a non-finite variable", bad_y + bad_x, d->n_points, bad_y, bad_x);
    return rows;
}

static void fit__var_range(const fit_desc *d, const size_t *rows, size_t m, size_t v,
                           double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < m; i++) {
        *lo = fmin(*lo, fit__row(d, rows[i])[v]);
        *hi = fmax(*hi, fit__row(d, rows[i])[v]);
    }
}

static int fit__is_constant(const fit_desc *d, const size_t *rows, size_t m, size_t v)
{
    double lo, hi;
    fit__var_range(d, rows, m, v, &lo, &hi);
    return hi - lo <= 1e-12 * fmax(fabs(lo), fabs(hi));
}

/* Constant columns: the terms using them are dropped with a warning; when
 * no parameter is left the fit is refused (DM_ERR_ARG). */
static int fit__drop_constant(const fit_desc *d, formula *f, const size_t *rows, size_t m,
                              dm_fit_result *r, dm_str *err)
{
    for (size_t v = 0; v < d->n_vars; v++) {
        if (!formula_uses_var(f, v) || !fit__is_constant(d, rows, m, v))
            continue;
        dm_str removed = { 0 };
        double value = fit__row(d, rows[0])[v];
        formula_drop_terms_with_var(f, v, &removed);
        if (formula_n_params(f) == 0) {
            dm_str_printf(err, "fit: variable '%s' is constant (= %g) over the %zu usable points; "
                          "without its term(s) '%s' the formula '%s' has no parameter left",
                          d->variables[v], value, m, dm_str_get(&removed), d->formula);
            dm_str_free(&removed);
            return DM_ERR_ARG;
        }
        fit__warn(r, "variable '%s' is constant (= %g) over the %zu usable points: its effect "
                  "cannot be told apart from a constant, term(s) '%s' dropped",
                  d->variables[v], value, m, dm_str_get(&removed));
        dm_str_free(&removed);
    }
    return 0;
}

static double fit__corr(const fit_desc *d, const size_t *rows, size_t m, size_t u, size_t v)
{
    double mu = 0.0, mv = 0.0, suu = 0.0, svv = 0.0, suv = 0.0;
    for (size_t i = 0; i < m; i++) {
        mu += fit__row(d, rows[i])[u] / (double)m;
        mv += fit__row(d, rows[i])[v] / (double)m;
    }
    for (size_t i = 0; i < m; i++) {
        double a = fit__row(d, rows[i])[u] - mu, b = fit__row(d, rows[i])[v] - mv;
        suu += a * a;
        svv += b * b;
        suv += a * b;
    }
    return suv / sqrt(suu * svv);
}

/* Warns about every pair of used variables with |corr| > 0.9999. */
static void fit__warn_collinear(const fit_desc *d, const formula *f, const size_t *rows,
                                size_t m, dm_fit_result *r)
{
    /* Only the variables the formula uses: a table of 10^5 columns has
     * 5*10^9 pairs, a formula a handful of variables. */
    size_t *used = dm_xcalloc(d->n_vars ? d->n_vars : 1, sizeof *used), n_used = 0;
    for (size_t v = 0; v < d->n_vars; v++)
        if (formula_uses_var(f, v))
            used[n_used++] = v;
    for (size_t i = 0; i < n_used; i++)
        for (size_t j = i + 1; j < n_used; j++) {
            size_t u = used[i], v = used[j];
            double c = fit__corr(d, rows, m, u, v);
            if (fabs(c) > 0.9999)
                fit__warn(r, "variables '%s' and '%s' are nearly collinear (corr = %.6f): "
                          "their coefficients are poorly determined", d->variables[u],
                          d->variables[v], c);
        }
    free(used);
}

/* Bounds of the current parameters (+-INFINITY when none) and a feasible
 * start: 1 clamped into the bounds. */
static void fit__bounds_and_start(const fit_desc *d, const formula *f, double *lo, double *hi,
                                  double *p)
{
    for (size_t j = 0; j < formula_n_params(f); j++) {
        lo[j] = -INFINITY;
        hi[j] = INFINITY;
        for (size_t i = 0; i < d->n_bounds; i++)
            if (!strcmp(d->bounds[i].param, formula_param_name(f, j))) {
                lo[j] = d->bounds[i].lo;
                hi[j] = d->bounds[i].hi;
            }
        p[j] = fmin(fmax(1.0, lo[j]), hi[j]);
    }
}

/* ---- results --------------------------------------------------------------- */

/* Parameters, stderr = sqrt(diag cov) * sqrt(RSS/(n-p)) (scaled residuals,
 * so the response scale cancels), and the goodness-of-fit figures. */
static int fit__dcmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Residual variance (in the solver's scaled units) behind the standard
 * errors.  Least squares: RSS / (m - P).  A robust loss: the square of the
 * residuals' normalised MAD (1.4826 * MAD) times m / (m - P), so outliers
 * the loss discounts do not inflate the errors of the inliers' fit. */
static double fit__residual_var(const fit__ctx *c, const dm_fit_result *r, double rss_scaled)
{
    size_t m = c->m, P = c->P;
    if (m <= P)
        return NAN;
    if (c->d->loss != FIT_LOSS_HUBER && c->d->loss != FIT_LOSS_CAUCHY)
        return rss_scaled / (double)(m - P);
    double *e = dm_xmalloc(m * sizeof *e);
    for (size_t i = 0; i < m; i++)
        e[i] = (r->predicted[i] - r->measured[i]) / (c->relative ? r->measured[i] : c->s_y);
    qsort(e, m, sizeof *e, fit__dcmp);
    double med = e[m / 2];
    for (size_t i = 0; i < m; i++)
        e[i] = fabs(e[i] - med);
    qsort(e, m, sizeof *e, fit__dcmp);
    double sigma = 1.4826 * e[m / 2];
    free(e);
    return sigma * sigma * (double)m / (double)(m - P);
}

static void fit__fill(fit__ctx *c, const double *p, const double *cov, int cov_ok,
                      dm_fit_result *r)
{
    const fit_desc *d = c->d;
    size_t m = c->m, P = c->P;
    double rss = 0.0, rss_scaled = 0.0, tss = 0.0, ape = 0.0, mean = 0.0;
    r->measured = dm_xmalloc(m * sizeof *r->measured);
    r->predicted = dm_xmalloc(m * sizeof *r->predicted);
    r->cv_predicted = dm_xmalloc(m * sizeof *r->cv_predicted);
    for (size_t i = 0; i < m; i++)
        r->cv_predicted[i] = NAN;   /* until cross-validation predicts it */
    for (size_t i = 0; i < m; i++)
        mean += d->y[c->rows[i]] / (double)m;
    for (size_t i = 0; i < m; i++) {
        double y = d->y[c->rows[i]];
        double f = formula_eval(c->f, fit__row(d, c->rows[i]), p, NULL);
        r->measured[i] = y;
        r->predicted[i] = f;
        rss += (f - y) * (f - y);
        rss_scaled += pow((f - y) / fit__yscale(c, c->rows[i]), 2);
        tss += (y - mean) * (y - mean);
        ape += fabs(f - y) / y;
    }
    r->n_points = (int)m;
    r->r2 = tss > 0.0 ? 1.0 - rss / tss : NAN;
    r->rmse = sqrt(rss / (double)m);
    r->mape = 100.0 * ape / (double)m;
    double s2 = fit__residual_var(c, r, rss_scaled);
    r->params = dm_xcalloc(P, sizeof *r->params);
    r->n_params = P;
    for (size_t j = 0; j < P; j++) {
        r->params[j].name = dm_xstrdup(formula_param_name(c->f, j));
        r->params[j].value = p[j];
        r->params[j].stderr_ = cov_ok ? sqrt(cov[j * P + j] * s2) : NAN;
    }
    if (d->point_labels) {
        r->point_labels = dm_xcalloc(m, sizeof *r->point_labels);
        for (size_t i = 0; i < m; i++)
            r->point_labels[i] = dm_xstrdup(d->point_labels[c->rows[i]]);
    }
}

/* k-fold cross-validated MAPE (percent): seeded shuffle, fold = position
 * mod k, refit on the other folds from p_full, predict the held-out rows
 * (each one's prediction in r->cv_predicted, in the order of rows). */
static double fit__cv_mape(fit__ctx *c, const size_t *rows, size_t m, const double *p_full,
                           dm_fit_result *r)
{
    const fit_desc *d = c->d;
    size_t k = d->folds > 0 ? (size_t)d->folds : (m < 5 ? m : 5), n_pred = 0;
    k = k > m ? m : k;
    if (k < 2) {
        fit__warn(r, "cross-validation skipped: needs at least 2 folds");
        return NAN;
    }
    size_t *perm = dm_xmalloc(2 * m * sizeof *perm), *train = perm + m;   /* perm: positions in rows */
    double *p = dm_xmalloc(c->P * sizeof *p), ape = 0.0;
    rng_state rng = rng_seed(d->seed);
    for (size_t i = 0; i < m; i++)
        perm[i] = i;
    for (size_t i = m; i > 1; i--) {
        size_t j = rng_below(&rng, i), t = perm[i - 1];
        perm[i - 1] = perm[j];
        perm[j] = t;
    }
    for (size_t fold = 0; fold < k; fold++) {
        size_t nt = 0;
        for (size_t i = 0; i < m; i++)
            if (i % k != fold)
                train[nt++] = rows[perm[i]];
        fit_ceres_summary sum;
        memcpy(p, p_full, c->P * sizeof *p);
        c->rows = train;
        c->m = nt;
        if (nt < c->P || !fit__solve(c, p, d->loss, NULL, &sum))
            continue;
        for (size_t i = fold; i < m; i += k) {
            double y = d->y[rows[perm[i]]], f = formula_eval(c->f, fit__row(d, rows[perm[i]]), p, NULL);
            r->cv_predicted[perm[i]] = f;
            ape += fabs(f - y) / y;
            n_pred++;
        }
    }
    free(perm);
    free(p);
    if (n_pred == 0)
        fit__warn(r, "cross-validation failed: no fold could be refitted");
    return n_pred ? 100.0 * ape / (double)n_pred : NAN;
}

/* Index of the largest |w[j]| over j != skip (skip >= n: none skipped). */
static size_t fit__argmax_abs(const double *w, size_t n, size_t skip)
{
    size_t best = skip == 0 ? 1 : 0;
    for (size_t j = 0; j < n; j++)
        if (j != skip && fabs(w[j]) > fabs(w[best]))
            best = j;
    return best;
}

/* Records the condition number; above FIT_ILL_CONDITIONED (finite: an
 * infinite one already has the rank-deficiency warning) warns naming the
 * two parameters that dominate the weakest direction (largest |components|
 * of the right singular vector of sigma_min, in the scaled space). */
static void fit__condition(const fit__ctx *c, double condition, dm_fit_result *r)
{
    r->condition = condition;
    if (!isfinite(condition) || condition <= FIT_ILL_CONDITIONED || c->P < 2)
        return;
    size_t a = fit__argmax_abs(c->weak, c->P, c->P), b = fit__argmax_abs(c->weak, c->P, a);
    if (b < a) {                      /* named in formula order */
        size_t t = a;
        a = b;
        b = t;
    }
    fit__warn(r, "ill-conditioned (condition %.3g > %g): parameters '%s' and '%s' are not "
              "separately determined by these data; only a combination of them is",
              condition, FIT_ILL_CONDITIONED, formula_param_name(c->f, a),
              formula_param_name(c->f, b));
}

/* Warns when the fit explains too little (R² < FIT_POOR_R2) or predicts
 * held-out points badly (CV-MAPE > FIT_POOR_CV_MAPE %). */
static void fit__warn_poor(dm_fit_result *r)
{
    if (isfinite(r->r2) && r->r2 < FIT_POOR_R2)
        fit__warn(r, "poor fit: R² %.3f is below %.1f; the model explains little of the variation, "
                  "so its parameters are not the costs they stand for", r->r2, FIT_POOR_R2);
    if (isfinite(r->cv_mape) && r->cv_mape > FIT_POOR_CV_MAPE)
        fit__warn(r, "poor prediction: CV-MAPE %.1f%% is above %.0f%%; held-out configurations "
                  "are predicted badly", r->cv_mape, FIT_POOR_CV_MAPE);
}

/* Solves on rows and fills r; DM_ERR_NUMERIC when Ceres fails. */
static int fit__fit(fit__ctx *c, size_t *rows, size_t m, dm_fit_result *r, dm_str *err)
{
    size_t P = c->P;
    double *p = dm_xmalloc((P * P + 3 * P) * sizeof *p), *lo = p + P, *hi = lo + P, *cov = hi + P;
    fit_ceres_summary sum;
    fit__bounds_and_start(c->d, c->f, lo, hi, p);
    c->lo = lo;
    c->hi = hi;
    c->rows = rows;
    c->m = m;
    int rc = 0;
    if (!fit__solve(c, p, c->d->loss, cov, &sum)) {
        dm_str_printf(err, "fit: '%s': the solver failed (%s: %s)", c->d->formula,
                      sum.termination, sum.message);
        rc = DM_ERR_NUMERIC;
        goto out;
    }
    r->termination = dm_xasprintf("%s after %d iterations", sum.termination, sum.iterations);
    if (!sum.converged)
        fit__warn(r, "the solver did not converge: %s", sum.message);
    if (m == P)
        fit__warn(r, "as many points as parameters (%zu): no residual degrees of freedom, "
                  "standard errors unavailable", m);
    else if (!sum.cov_ok)
        fit__warn(r, "the Jacobian is rank deficient at the solution: the parameters are not "
                  "identifiable from these data (standard errors set to NaN)");
    fit__condition(c, sum.condition, r);
    fit__fill(c, p, cov, sum.cov_ok, r);
    r->cv_mape = fit__cv_mape(c, rows, m, p, r);
    fit__warn_poor(r);
    if (!isfinite(r->rmse)) {   /* e.g. responses near 1e308: the residuals overflow */
        dm_str_printf(err, "fit: '%s': the fit is not finite (RMSE %g): the values are too large "
                      "for double precision; rescale the data", c->d->formula, r->rmse);
        rc = DM_ERR_NUMERIC;
    }
out:
    free(p);
    return rc;
}

/* fit_run on a formula whose bound clauses are already split off: desc has
 * the expression and every bound; full is the text as the user wrote it
 * (recorded in the result). */
static int fit__run(const fit_desc *desc, const char *full, dm_fit_result *out, dm_str *err)
{
    formula *f = NULL;
    dm_fit_result r = { 0 };
    size_t m = 0, *rows = NULL;
    memset(out, 0, sizeof *out);
    int rc = fit__validate(desc, err);
    rc = rc ? rc : formula_parse(desc->formula, desc->variables, desc->n_vars, &f, err);
    rc = rc ? rc : fit__check_bound_names(desc, f, err);
    if (rc)
        goto out;
    rows = fit__usable_rows(desc, f, &m, &r);
    if (m > 0 && (rc = fit__drop_constant(desc, f, rows, m, &r, err)) != 0)
        goto out;
    size_t P = formula_n_params(f);
    if (P == 0 || m < P) {
        dm_str_printf(err, "fit: '%s' has %zu parameter(s) but only %zu usable point(s) "
                      "(%d excluded); at least %zu needed", desc->formula, P, m, r.n_excluded,
                      P ? P : 1);
        rc = DM_ERR_ARG;
        goto out;
    }
    fit__warn_collinear(desc, f, rows, m, &r);
    fit__ctx c = { .d = desc, .f = f, .P = P, .relative = desc->relative };
    c.scale = dm_xmalloc(4 * P * sizeof *c.scale);
    c.p = c.scale + P;
    c.grad = c.p + P;
    c.weak = c.grad + P;
    rc = fit__fit(&c, rows, m, &r, err);
    free(c.scale);
    if (rc)
        goto out;
    r.model = dm_xstrdup(desc->model ? desc->model : full);
    r.formula = dm_xstrdup(full);
    r.response = dm_xstrdup(desc->response);
    *out = r;
    memset(&r, 0, sizeof r);
out:
    dm_fit_result_free(&r);
    free(rows);
    formula_free(f);
    return rc;
}

int fit_run(const fit_desc *desc, dm_fit_result *out, dm_str *err)
{
    if (!desc->formula)
        return fit__run(desc, NULL, out, err);   /* fit__validate reports it */
    char *expr = NULL;
    fit_bound *extra = NULL;
    size_t n_extra = 0;
    memset(out, 0, sizeof *out);
    int rc = bounds_split(desc->formula, &expr, &extra, &n_extra, err);
    if (rc)
        return rc;
    fit_desc d = *desc;
    fit_bound *all = dm_xcalloc(desc->n_bounds + n_extra + 1, sizeof *all);
    if (desc->n_bounds)
        memcpy(all, desc->bounds, desc->n_bounds * sizeof *all);
    if (n_extra)
        memcpy(all + desc->n_bounds, extra, n_extra * sizeof *all);
    d.formula = expr;
    d.bounds = all;
    d.n_bounds = desc->n_bounds + n_extra;
    rc = fit__run(&d, desc->formula, out, err);
    free(all);
    bounds_free(extra, n_extra);
    free(expr);
    return rc;
}
