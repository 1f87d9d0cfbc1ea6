/* test_models_formula.c — formula parser, errors, exact derivatives. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_error.h"
#include "models/formula.h"

static const char *const vars[] = { "x", "L" };

static formula *parse_ok(const char *text)
{
    formula *f = NULL;
    dm_str err = { 0 };
    int rc = formula_parse(text, vars, 2, &f, &err);
    if (rc)
        fail_msg("parse '%s': %s", text, dm_str_get(&err));
    dm_str_free(&err);
    return f;
}

static void expect_error(const char *text, const char *msg)
{
    formula *f = (formula *)1;
    dm_str err = { 0 };
    assert_int_equal(formula_parse(text, vars, 2, &f, &err), DM_ERR_PARSE);
    assert_null(f);
    assert_string_equal(dm_str_get(&err), msg);
    dm_str_free(&err);
}

static void parse_errors_name_column(void **state)
{
    (void)state;
    expect_error("a + (b", "formula: column 7: expected ')' after 'a + (b'");
    expect_error("", "formula: column 1: expected a number, a name or '(' at the start");
    expect_error("a + * b", "formula: column 5: expected a number, a name or '(' after 'a +'");
    expect_error("a b", "formula: column 3: expected an operator or the end of the formula after 'a'");
    expect_error("a + x # 2", "formula: column 7: unexpected character '#'");
    expect_error("foo(x)", "formula: column 1: unknown function 'foo' (valid: exp, log, sqrt, min, max)");
    expect_error("min(a x)", "formula: column 7: expected ',' after 'min(a'");
    expect_error("exp(a", "formula: column 6: expected ')' after 'exp(a'");
}

static void params_in_order_and_values(void **state)
{
    (void)state;
    formula *f = parse_ok("a + b*L^p - c/x");
    assert_int_equal(formula_n_params(f), 4);
    assert_string_equal(formula_param_name(f, 0), "a");
    assert_string_equal(formula_param_name(f, 1), "b");
    assert_string_equal(formula_param_name(f, 2), "p");
    assert_string_equal(formula_param_name(f, 3), "c");
    assert_int_equal(formula_param_index(f, "c"), 3);
    assert_int_equal(formula_param_index(f, "x"), -1);
    const double x[] = { 4.0, 8.0 }, p[] = { 1.0, 2.0, 1.0 / 3.0, 6.0 };
    double g[4];
    /* 1 + 2*8^(1/3) - 6/4 = 1 + 4 - 1.5 */
    assert_true(fabs(formula_eval(f, x, p, g) - 3.5) < 1e-14);
    /* d/da = 1, d/db = 8^(1/3) = 2, d/dp = b*L^p*ln L = 4 ln 8, d/dc = -1/4 */
    assert_true(g[0] == 1.0);
    assert_true(fabs(g[1] - 2.0) < 1e-14);
    assert_true(fabs(g[2] - 4.0 * log(8.0)) < 1e-13);
    assert_true(g[3] == -0.25);
    assert_true(formula_param_is_linear(f, 0) && formula_param_is_linear(f, 1));
    assert_false(formula_param_is_linear(f, 2));
    assert_true(formula_param_is_linear(f, 3));             /* c/x: affine in c */
    assert_false(formula_is_linear(f));
    formula_free(f);
}

static void precedence_and_functions(void **state)
{
    (void)state;
    const double x[] = { 2.0, 3.0 };
    formula *f = parse_ok("-x^2 + 2^3^2 + sqrt(16) + exp(0) + log(1) + min(x, L) * max(x, L)");
    /* -(4) + 2^9 + 4 + 1 + 0 + 2*3 = 519 */
    assert_true(formula_eval(f, x, NULL, NULL) == 519.0);
    assert_int_equal(formula_n_params(f), 0);
    formula_free(f);
    f = parse_ok("exp(k*x) + log(a*L) + sqrt(s) + min(m, x)");
    const double p[] = { 0.5, 2.0, 9.0, 1.0 };
    double g[4];
    double v = formula_eval(f, x, p, g);
    assert_true(fabs(v - (exp(1.0) + log(6.0) + 3.0 + 1.0)) < 1e-14);
    assert_true(fabs(g[0] - 2.0 * exp(1.0)) < 1e-14);  /* x e^{kx} */
    assert_true(fabs(g[1] - 0.5) < 1e-14);              /* L/(aL) = 1/a */
    assert_true(fabs(g[2] - 1.0 / 6.0) < 1e-14);        /* 1/(2 sqrt s) */
    assert_true(g[3] == 1.0);                            /* m < x selected */
    formula_free(f);
}

static void linearity(void **state)
{
    (void)state;
    formula *f = parse_ok("c0 + c1*x + c2*L/4 - (c3*x)*L");
    assert_true(formula_is_linear(f));
    formula_free(f);
    f = parse_ok("a*b*x");
    assert_false(formula_is_linear(f));
    assert_true(formula_param_is_linear(f, 0) && formula_param_is_linear(f, 1));
    formula_free(f);
    f = parse_ok("x/a");
    assert_false(formula_param_is_linear(f, 0));
    formula_free(f);
}

static void drop_terms(void **state)
{
    (void)state;
    formula *f = parse_ok("a + b*x - c*L^p");
    dm_str removed = { 0 };
    assert_int_equal(formula_drop_terms_with_var(f, 1, &removed), 1);
    assert_string_equal(dm_str_get(&removed), "c*L^p");
    assert_int_equal(formula_n_params(f), 2);
    assert_false(formula_uses_var(f, 1));
    const double x[] = { 3.0, 100.0 }, p[] = { 1.0, 2.0 };
    assert_true(formula_eval(f, x, p, NULL) == 7.0);
    dm_str_free(&removed);
    assert_int_equal(formula_drop_terms_with_var(f, 1, &removed), 0);
    formula_free(f);
    f = parse_ok("exp(a*x)");
    assert_int_equal(formula_drop_terms_with_var(f, 0, &removed), 1);
    assert_string_equal(dm_str_get(&removed), "exp(a*x)");
    assert_int_equal(formula_n_params(f), 0);
    dm_str_free(&removed);
    formula_free(f);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(parse_errors_name_column),
             cmocka_unit_test(params_in_order_and_values),
             cmocka_unit_test(precedence_and_functions),
             cmocka_unit_test(linearity),
             cmocka_unit_test(drop_terms))
