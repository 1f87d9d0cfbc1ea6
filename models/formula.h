/* formula.h — the cost-model formula language: parse once, evaluate with
 * exact first derivatives.
 *
 * Grammar (precedence low to high; ^ is right-associative and binds tighter
 * than unary minus, so -a^2 = -(a^2) and a^b^c = a^(b^c)):
 *   expr    := term (('+' | '-') term)*
 *   term    := unary (('*' | '/') unary)*
 *   unary   := '-' unary | power
 *   power   := primary ('^' unary)?
 *   primary := NUMBER | NAME | FUNC '(' expr [',' expr] ')' | '(' expr ')'
 *   FUNC    := exp | log | sqrt (one argument) | min | max (two)
 * NAME is [A-Za-z_][A-Za-z0-9_]*.  A name listed in the variable list is
 * data; every other name is a free parameter, numbered in order of first
 * appearance (left to right).
 *
 * Derivatives are exact: evaluation is forward-mode automatic
 * differentiation with a dual number carrying the gradient w.r.t. all
 * parameters.  A formula owns a scratch workspace, so one formula object
 * must not be evaluated from two threads at once.
 */
#ifndef MODELS_FORMULA_H
#define MODELS_FORMULA_H

#include <stddef.h>
#include "core/dm_util.h"

typedef struct formula formula;

/* Parses text with the given variable names (copied).  Returns 0 and a new
 * formula in *out, or DM_ERR_PARSE with a message in err naming the 1-based
 * column and what was expected ("formula: column 7: expected ')' after
 * 'a + (b'"); *out is then NULL. */
int formula_parse(const char *text, const char *const *vars, size_t n_vars,
                  formula **out, dm_str *err);
void formula_free(formula *f);

const char *formula_text(const formula *f);
size_t formula_n_params(const formula *f);
const char *formula_param_name(const formula *f, size_t i);
/* Index of a parameter by name, or -1. */
long formula_param_index(const formula *f, const char *name);
/* 1 if variable `var` (index in the variable list) occurs in the formula. */
int formula_uses_var(const formula *f, size_t var);

/* Value at data row x (n_vars values) and parameters p (n_params values).
 * When grad is not NULL it receives the n_params partial derivatives.
 * Domain errors give NaN/Inf (as the C library does); callers check. */
double formula_eval(formula *f, const double *x, const double *p, double *grad);

/* 1 if the formula is affine in parameter i with all others held fixed
 * (structural test on the expression tree, so it is exact: "a + b*x^p" is
 * affine in a and b, not in p). */
int formula_param_is_linear(const formula *f, size_t i);
/* 1 if the formula is affine in all parameters jointly. */
int formula_is_linear(const formula *f);

/* Removes every top-level additive term (operand of the outermost chain of
 * binary + and -) that references variable `var`, replacing it by 0, and
 * renumbers the parameters (a formula that is a single term becomes "0").
 * The removed terms' source text is appended to removed ("b*x2", several
 * separated by ", ").  Returns the number of terms removed, 0 when `var` is
 * not used.  Afterwards `var` is not used; parameters that occurred only in
 * removed terms are gone (formula_n_params may drop to 0). */
size_t formula_drop_terms_with_var(formula *f, size_t var, dm_str *removed);

#endif
