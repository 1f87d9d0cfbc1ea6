/* test_models_fit.c — least-squares fits on synthetic data with known answers. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "models/fit.h"
#include "models/rng.h"

#define MAXN 128

static const char *const V2[] = { "x1", "x2" };

/* Standard normal deviate (Box-Muller) from the seeded generator. */
static double gauss(rng_state *r)
{
    double u = rng_uniform(r), v = rng_uniform(r);
    return sqrt(-2.0 * log(1.0 - u)) * cos(2.0 * M_PI * v);
}

static double rel(double got, double want)
{
    return fabs(got - want) / fabs(want);
}

static int has_warning(const dm_fit_result *r, const char *a, const char *b)
{
    for (size_t i = 0; i < r->n_warnings; i++)
        if (strstr(r->warnings[i], a) && (!b || strstr(r->warnings[i], b)))
            return 1;
    return 0;
}

static dm_fit_result run_ok(const fit_desc *d)
{
    dm_fit_result r;
    dm_str err = { 0 };
    int rc = fit_run(d, &r, &err);
    if (rc)
        fail_msg("fit_run: %s: %s", dm_errname(rc), dm_str_get(&err));
    dm_str_free(&err);
    return r;
}

static fit_desc desc2(const char *formula, const double *x, const double *y, size_t n)
{
    fit_desc d = { .formula = formula, .response = "t", .variables = V2, .n_vars = 2,
                   .x = x, .y = y, .n_points = n, .seed = 7 };
    return d;
}

/* y = 3 + 2 x1 + 0.5 x2 (+ sigma noise). */
static void make_linear(double *x, double *y, size_t n, double sigma, uint64_t seed)
{
    rng_state r = rng_seed(seed);
    for (size_t i = 0; i < n; i++) {
        x[2 * i] = (double)(i + 1);
        x[2 * i + 1] = (double)((i * 7) % 11 + 1);
        y[i] = 3.0 + 2.0 * x[2 * i] + 0.5 * x[2 * i + 1] + sigma * gauss(&r);
    }
}

static void exact_recovery(void **state)
{
    (void)state;
    double x[2 * 20], y[20];
    make_linear(x, y, 20, 0.0, 1);
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 20);
    dm_fit_result r = run_ok(&d);
    assert_int_equal(r.n_params, 3);
    assert_string_equal(r.params[0].name, "a");
    assert_true(rel(r.params[0].value, 3.0) < 1e-9);
    assert_true(rel(r.params[1].value, 2.0) < 1e-9);
    assert_true(rel(r.params[2].value, 0.5) < 1e-9);
    assert_true(fabs(r.r2 - 1.0) < 1e-12);
    assert_true(r.mape < 1e-7 && r.cv_mape < 1e-7);
    assert_int_equal(r.n_points, 20);
    assert_int_equal(r.n_excluded, 0);
    assert_int_equal(r.n_warnings, 0);
    assert_non_null(strstr(r.termination, "CONVERGENCE"));
    assert_true(r.measured[4] == y[4] && fabs(r.predicted[4] - y[4]) < 1e-9);
    /* every point held out once, and predicted exactly by the fit without it */
    for (size_t i = 0; i < 20; i++)
        assert_true(rel(r.cv_predicted[i], y[i]) < 1e-9);
    assert_string_equal(r.model, "a + b*x1 + c*x2");
    dm_fit_result_free(&r);
}

static void noisy_within_3_stderr(void **state)
{
    (void)state;
    double x[2 * 60], y[60];
    const double truth[] = { 3.0, 2.0, 0.5 };
    make_linear(x, y, 60, 0.3, 99);
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 60);
    dm_fit_result r = run_ok(&d);
    for (size_t j = 0; j < 3; j++) {
        assert_true(r.params[j].stderr_ > 0.0 && isfinite(r.params[j].stderr_));
        assert_true(fabs(r.params[j].value - truth[j]) < 3.0 * r.params[j].stderr_);
    }
    /* slope stderr for sigma 0.3, x1 = 1..60: about 0.3/sqrt(sum (x-xbar)^2) = 0.0017 */
    assert_true(r.params[1].stderr_ > 0.001 && r.params[1].stderr_ < 0.003);
    assert_true(r.cv_mape > 0.0 && isfinite(r.cv_mape));
    /* the held-out predictions kept are the ones CV-MAPE is made of */
    double ape = 0;
    for (size_t i = 0; i < 60; i++)
        ape += fabs(r.cv_predicted[i] - y[i]) / y[i];
    assert_true(rel(100 * ape / 60, r.cv_mape) < 1e-12);
    dm_fit_result_free(&r);
}

static void stiff(void **state)
{
    (void)state;
    enum { N = 30 };
    double x[2 * N], y[N];
    for (size_t i = 0; i < N; i++) {
        x[2 * i] = pow(10.0, 9.0 * (double)i / (N - 1));     /* 1 .. 1e9 */
        x[2 * i + 1] = 1.0 + 9.0 * (double)((i * 13) % N) / (N - 1); /* 1 .. 10 */
        y[i] = 1e-9 * x[2 * i] + 1e3 * x[2 * i + 1] + 5.0;
    }
    fit_desc d = desc2("a*x1 + b*x2 + c", x, y, N);
    dm_fit_result r = run_ok(&d);
    printf("stiff: a = %.12g (1e-9)  b = %.12g (1e3)  c = %.12g (5)  stderr %g %g %g  %s\n",
           r.params[0].value, r.params[1].value, r.params[2].value, r.params[0].stderr_,
           r.params[1].stderr_, r.params[2].stderr_, r.termination);
    assert_true(rel(r.params[0].value, 1e-9) < 1e-6);
    assert_true(rel(r.params[1].value, 1e3) < 1e-6);
    assert_true(rel(r.params[2].value, 5.0) < 1e-6);
    assert_int_equal(r.n_warnings, 0);
    dm_fit_result_free(&r);
}

/* y = 1 + 2 x1 + 3 x2 + noise; x2 = x1 + tiny (collinear) or independent. */
static double slope_stderr(int collinear, dm_fit_result *out)
{
    enum { N = 40 };
    double x[2 * N], y[N];
    rng_state r = rng_seed(5);
    for (size_t i = 0; i < N; i++) {
        x[2 * i] = 1.0 + (double)(i % 20);
        x[2 * i + 1] = collinear ? x[2 * i] + 0.02 * gauss(&r) : 1.0 + 19.0 * rng_uniform(&r);
        y[i] = 1.0 + 2.0 * x[2 * i] + 3.0 * x[2 * i + 1] + 0.01 * gauss(&r);
    }
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, N);
    *out = run_ok(&d);
    return out->params[1].stderr_;
}

static void near_collinear(void **state)
{
    (void)state;
    dm_fit_result good, bad;
    double s_good = slope_stderr(0, &good), s_bad = slope_stderr(1, &bad);
    printf("collinear: b = %.6g ± %.3g, c = %.6g ± %.3g (well-conditioned: b ± %.3g, c ± %.3g)"
           " ratio %.1f\n  warning: %s\n", bad.params[1].value, s_bad, bad.params[2].value,
           bad.params[2].stderr_, s_good, good.params[2].stderr_, s_bad / s_good,
           bad.n_warnings ? bad.warnings[0] : "(none)");
    assert_true(has_warning(&bad, "'x1' and 'x2'", "collinear"));
    assert_false(has_warning(&good, "collinear", NULL));
    assert_true(s_bad > 10.0 * s_good);
    assert_true(bad.params[2].stderr_ > 10.0 * good.params[2].stderr_);
    assert_true(bad.condition > FIT_ILL_CONDITIONED && good.condition < 10.0);
    assert_true(has_warning(&bad, "ill-conditioned", "parameters 'b' and 'c' are not separately"));
    assert_false(has_warning(&good, "ill-conditioned", NULL));
    dm_fit_result_free(&good);
    dm_fit_result_free(&bad);
}

static void exact_collinear_rank_deficient(void **state)
{
    (void)state;
    double x[2 * 10], y[10];
    for (size_t i = 0; i < 10; i++) {
        x[2 * i] = (double)(i + 1);
        x[2 * i + 1] = 2.0 * x[2 * i];
        y[i] = 1.0 + 4.0 * x[2 * i];
    }
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 10);
    dm_fit_result r = run_ok(&d);
    assert_true(has_warning(&r, "rank deficient", NULL));
    assert_true(isnan(r.params[1].stderr_));
    assert_true(isinf(r.condition));
    assert_false(has_warning(&r, "ill-conditioned", NULL));
    /* the prediction is still right: b + 2c = 4 */
    assert_true(fabs(r.params[1].value + 2.0 * r.params[2].value - 4.0) < 1e-8);
    dm_fit_result_free(&r);
}

static void too_few_points(void **state)
{
    (void)state;
    const double x[] = { 1, 2, 3, 4 }, y[] = { 1, 2 };
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 2);
    dm_fit_result r;
    dm_str err = { 0 };
    assert_int_equal(fit_run(&d, &r, &err), DM_ERR_ARG);
    assert_string_equal(dm_str_get(&err), "fit: 'a + b*x1 + c*x2' has 3 parameter(s) but only "
                        "2 usable point(s) (0 excluded); at least 3 needed");
    assert_null(r.params);
    dm_str_free(&err);
}

static void constant_column(void **state)
{
    (void)state;
    double x[2 * 10], y[10];
    for (size_t i = 0; i < 10; i++) {
        x[2 * i] = (double)(i + 1);
        x[2 * i + 1] = 5.0;
        y[i] = 2.0 + 3.0 * x[2 * i];
    }
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 10);
    dm_fit_result r = run_ok(&d);
    assert_true(has_warning(&r, "variable 'x2' is constant (= 5)", "'c*x2' dropped"));
    assert_int_equal(r.n_params, 2);
    assert_true(rel(r.params[0].value, 2.0) < 1e-9 && rel(r.params[1].value, 3.0) < 1e-9);
    dm_fit_result_free(&r);
    dm_str err = { 0 };
    d.formula = "c*x2";
    assert_int_equal(fit_run(&d, &r, &err), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&err), "variable 'x2' is constant (= 5)"));
    dm_str_free(&err);
}

/* y = 10 + 2 x, x = 1..100, noise 0.1; every 20th point tripled. */
static dm_fit_result outlier_fit(fit_loss loss)
{
    static double x[2 * 100], y[100];
    rng_state r = rng_seed(3);
    for (size_t i = 0; i < 100; i++) {
        x[2 * i] = (double)(i + 1);
        x[2 * i + 1] = 0.0;
        y[i] = 10.0 + 2.0 * x[2 * i] + 0.1 * gauss(&r);
        if (i % 20 == 3)
            y[i] *= 3.0;
    }
    fit_desc d = desc2("a + b*x1", x, y, 100);
    d.loss = loss;
    return run_ok(&d);
}

static void outliers_huber(void **state)
{
    (void)state;
    dm_fit_result none = outlier_fit(FIT_LOSS_NONE), huber = outlier_fit(FIT_LOSS_HUBER);
    dm_fit_result cauchy = outlier_fit(FIT_LOSS_CAUCHY);
    printf("outliers: none a = %.5g b = %.5g | huber a = %.5g b = %.5g | cauchy a = %.5g b = %.5g"
           " (true 10, 2)\n", none.params[0].value, none.params[1].value, huber.params[0].value,
           huber.params[1].value, cauchy.params[0].value, cauchy.params[1].value);
    assert_true(rel(huber.params[0].value, 10.0) < 0.02 && rel(huber.params[1].value, 2.0) < 0.02);
    assert_true(rel(cauchy.params[0].value, 10.0) < 0.02 && rel(cauchy.params[1].value, 2.0) < 0.02);
    assert_true(rel(none.params[0].value, 10.0) > 0.02 || rel(none.params[1].value, 2.0) > 0.02);
    dm_fit_result_free(&none);
    dm_fit_result_free(&huber);
    dm_fit_result_free(&cauchy);
}

static void bad_values_excluded(void **state)
{
    (void)state;
    double x[2 * 20], y[20];
    make_linear(x, y, 20, 0.0, 1);
    y[2] = NAN;
    y[5] = INFINITY;
    y[7] = -3.0;
    y[11] = 0.0;
    x[2 * 13 + 1] = NAN;
    const char *labels[20];
    char buf[20][16]; /* room for any int: -O1 with ASan cannot see i < 20 */
    for (int i = 0; i < 20; i++) {
        snprintf(buf[i], sizeof buf[i], "p%d", i);
        labels[i] = buf[i];
    }
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 20);
    d.point_labels = labels;
    dm_fit_result r = run_ok(&d);
    assert_int_equal(r.n_excluded, 5);
    assert_int_equal(r.n_points, 15);
    assert_true(has_warning(&r, "excluded 5 of 20 points: 4 with a non-finite or non-positive "
                            "response, 1 with a non-finite variable", NULL));
    assert_string_equal(r.point_labels[2], "p3");
    assert_true(rel(r.params[1].value, 2.0) < 1e-9);
    dm_fit_result_free(&r);
}

static void power_law(void **state)
{
    (void)state;
    static const char *const VL[] = { "L" };
    const double ps[] = { 0.5, 1.0, 2.0, 3.0 };
    double x[64], y[64];
    for (size_t k = 0; k < 4; k++) {
        for (size_t i = 0; i < 64; i++) {
            x[i] = (double)(i + 1);
            y[i] = 2.0 + 0.5 * pow(x[i], ps[k]);
        }
        fit_desc d = { .formula = "a + b*L^p", .variables = VL, .n_vars = 1, .x = x, .y = y,
                       .n_points = 64 };
        dm_fit_result r = run_ok(&d);
        assert_true(rel(r.params[0].value, 2.0) < 1e-6);
        assert_true(rel(r.params[1].value, 0.5) < 1e-6);
        assert_true(rel(r.params[2].value, ps[k]) < 1e-6);
        dm_fit_result_free(&r);
    }
}

static void bounds_and_errors(void **state)
{
    (void)state;
    double x[2 * 20], y[20];
    make_linear(x, y, 20, 0.0, 1);
    const fit_bound b[] = { { "b", -INFINITY, 1.5 } };
    fit_desc d = desc2("a + b*x1 + c*x2", x, y, 20);
    d.bounds = b;
    d.n_bounds = 1;
    dm_fit_result r = run_ok(&d);
    assert_true(fabs(r.params[1].value - 1.5) < 1e-9);
    dm_fit_result_free(&r);
    dm_str err = { 0 };
    const fit_bound bq[] = { { "q", 0, 1 } };
    d.bounds = bq;
    assert_int_equal(fit_run(&d, &r, &err), DM_ERR_UNKNOWN);
    assert_string_equal(dm_str_get(&err), "fit: bound on 'q', which is not a parameter of "
                        "'a + b*x1 + c*x2' (parameters: a b c)");
    dm_str_free(&err);
    d.n_bounds = 0;
    d.formula = "a + b*(x1";
    assert_int_equal(fit_run(&d, &r, &err), DM_ERR_PARSE);
    assert_string_equal(dm_str_get(&err), "formula: column 10: expected ')' after 'a + b*(x1'");
    dm_str_free(&err);
}

/* Bounds written after the formula: the same fit as a fit_bound (b capped
 * at 1.5 on y = 3 + 2 x1 + 0.5 x2), both forms of clause, the formula
 * recorded as written, and the errors. */
static void bounds_in_formula(void **state)
{
    (void)state;
    double x[2 * 20], y[20];
    make_linear(x, y, 20, 0.0, 1);
    fit_desc d = desc2("a + b*x1 + c*x2; b <= 1.5 ; 0 <= c <= 0.25", x, y, 20);
    dm_fit_result r = run_ok(&d);
    assert_true(fabs(r.params[1].value - 1.5) < 1e-9);
    assert_true(fabs(r.params[2].value - 0.25) < 1e-9);
    assert_string_equal(r.formula, "a + b*x1 + c*x2; b <= 1.5 ; 0 <= c <= 0.25");
    dm_fit_result_free(&r);
    d.formula = "a + b*x1 + c*x2; a >= 0";
    r = run_ok(&d);
    assert_true(fabs(r.params[0].value - 3.0) < 1e-6);   /* inactive bound */
    dm_fit_result_free(&r);
    static const struct { const char *f; int rc; const char *msg; } bad[] = {
        {"a + b*x1; b => 0", DM_ERR_PARSE,
         "formula: bound 1 ' b => 0': expected NAME >= NUMBER, NAME <= NUMBER or NUMBER <= NAME <= NUMBER"},
        {"a + b*x1; b >= 0; 2 <= a <= 1", DM_ERR_PARSE, "formula: bound 2 ' 2 <= a <= 1'"},
        {"a + b*x1; b >= 0;", DM_ERR_PARSE, "formula: bound 2 ''"},
        {"a + b*x1; q >= 0", DM_ERR_UNKNOWN, "fit: bound on 'q', which is not a parameter of 'a + b*x1'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        dm_str err = { 0 };
        d.formula = bad[i].f;
        assert_int_equal(fit_run(&d, &r, &err), bad[i].rc);
        if (!strstr(dm_str_get(&err), bad[i].msg))
            fail_msg("'%s': got '%s'", bad[i].f, dm_str_get(&err));
        dm_str_free(&err);
    }
}

/* Condition of J = [u/|u|, v/|v|] (linear model, unit-norm columns): the
 * eigenvalues of J^T J = [[1, c], [c, 1]] are 1 +- c with c = u.v/(|u||v|),
 * so the 2-norm condition of J is sqrt((1 + |c|) / (1 - |c|)). */
static double condition_2col(const double *u, const double *v, size_t n)
{
    double uv = 0.0, uu = 0.0, vv = 0.0;
    for (size_t i = 0; i < n; i++) {
        uv += u[i] * v[i];
        uu += u[i] * u[i];
        vv += v[i] * v[i];
    }
    double c = fabs(uv) / sqrt(uu * vv);
    return sqrt((1.0 + c) / (1.0 - c));
}

/* a + b*x1 over x1 = 1..10: columns 1 and x1, c = 55 / sqrt(10 * 385). */
static void condition_well_conditioned(void **state)
{
    (void)state;
    double x[2 * 10], y[10], ones[10], x1[10];
    for (size_t i = 0; i < 10; i++) {
        x[2 * i] = x1[i] = (double)(i + 1);
        x[2 * i + 1] = 0.0;
        ones[i] = 1.0;
        y[i] = 4.0 + 0.5 * x1[i];
    }
    fit_desc d = desc2("a + b*x1", x, y, 10);
    dm_fit_result r = run_ok(&d);
    double want = condition_2col(ones, x1, 10);
    assert_true(fabs(want - sqrt((1 + 55 / sqrt(3850.0)) / (1 - 55 / sqrt(3850.0)))) < 1e-12);
    printf("condition a + b*x1: %.12g (closed form %.12g)\n", r.condition, want);
    assert_true(rel(r.condition, want) < 1e-9);
    assert_true(r.condition > 1.0 && r.condition < 10.0);
    assert_false(has_warning(&r, "ill-conditioned", NULL));
    dm_fit_result_free(&r);
}

/* a*x1 + b*x2 with x2 = x1 +- 0.01: nearly parallel columns. */
static void condition_near_collinear(void **state)
{
    (void)state;
    double x[2 * 10], y[10], x1[10], x2[10];
    for (size_t i = 0; i < 10; i++) {
        x[2 * i] = x1[i] = (double)(i + 1);
        x[2 * i + 1] = x2[i] = x1[i] + (i % 2 ? 0.01 : -0.01);
        y[i] = 2.0 * x1[i] + 3.0 * x2[i];
    }
    fit_desc d = desc2("a*x1 + b*x2", x, y, 10);
    dm_fit_result r = run_ok(&d);
    double want = condition_2col(x1, x2, 10);
    printf("condition a*x1 + b*x2 (x2 = x1 +- 0.01): %.12g (closed form %.12g)\n  %s\n",
           r.condition, want, r.n_warnings ? r.warnings[r.n_warnings - 1] : "(no warning)");
    assert_true(want > FIT_ILL_CONDITIONED);
    assert_true(rel(r.condition, want) < 1e-6);
    assert_true(has_warning(&r, "ill-conditioned (condition", "parameters 'a' and 'b' are not "
                            "separately determined"));
    dm_fit_result_free(&r);
}

/* y = 50 + 2 x over x = 1..1000 (three orders of magnitude) with 5 %
 * multiplicative noise.  desc.relative minimises sum ((f - y) / y)^2: its
 * parameters are the weighted least squares with weights 1/y^2, computed
 * here by the normal equations; the small points are then predicted in
 * proportion, where the absolute fit lets the largest decide. */
static void relative_weights(void **state)
{
    (void)state;
    enum { N = 60 };
    double x[N], y[N];
    static const char *const V1[] = { "x" };
    rng_state g = rng_seed(5);
    for (size_t i = 0; i < N; i++) {
        x[i] = pow(10.0, 3.0 * (double)i / (N - 1));   /* 1 .. 1000 */
        y[i] = (50.0 + 2.0 * x[i]) * (1.0 + 0.05 * gauss(&g));
    }
    /* weighted normal equations for a + b x, w = 1/y^2 */
    double sw = 0, sx = 0, sxx = 0, sy = 0, sxy = 0;
    for (size_t i = 0; i < N; i++) {
        double w = 1.0 / (y[i] * y[i]);
        sw += w, sx += w * x[i], sxx += w * x[i] * x[i], sy += w * y[i], sxy += w * x[i] * y[i];
    }
    double det = sw * sxx - sx * sx, a = (sxx * sy - sx * sxy) / det, b = (sw * sxy - sx * sy) / det;
    fit_desc d = { .formula = "a + b*x", .response = "t", .variables = V1, .n_vars = 1, .x = x, .y = y,
                   .n_points = N, .seed = 7, .relative = 1 };
    dm_fit_result r = run_ok(&d);
    assert_true(rel(r.params[0].value, a) < 1e-7);
    assert_true(rel(r.params[1].value, b) < 1e-7);
    /* the known parameters within 3 standard errors */
    assert_true(fabs(r.params[0].value - 50.0) < 3 * r.params[0].stderr_);
    assert_true(fabs(r.params[1].value - 2.0) < 3 * r.params[1].stderr_);
    d.relative = 0;
    dm_fit_result ab = run_ok(&d);
    /* the ten smallest points: the relative fit's error is the smaller */
    double er = 0, ea = 0;
    for (size_t i = 0; i < 10; i++) {
        er += fabs(r.predicted[i] / y[i] - 1);
        ea += fabs(ab.predicted[i] / y[i] - 1);
    }
    assert_true(er < ea);
    assert_true(r.mape < ab.mape);
    dm_fit_result_free(&r);
    dm_fit_result_free(&ab);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(exact_recovery),
             cmocka_unit_test(noisy_within_3_stderr),
             cmocka_unit_test(stiff),
             cmocka_unit_test(near_collinear),
             cmocka_unit_test(exact_collinear_rank_deficient),
             cmocka_unit_test(too_few_points),
             cmocka_unit_test(constant_column),
             cmocka_unit_test(outliers_huber),
             cmocka_unit_test(bad_values_excluded),
             cmocka_unit_test(power_law),
             cmocka_unit_test(bounds_and_errors),
             cmocka_unit_test(bounds_in_formula),
             cmocka_unit_test(condition_well_conditioned),
             cmocka_unit_test(condition_near_collinear),
             cmocka_unit_test(relative_weights))
