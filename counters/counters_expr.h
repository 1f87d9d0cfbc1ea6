/* counters_expr.h — the small formula language of derived counters.
 *
 * Grammar: expr = term {('+'|'-') term}; term = unary {('*'|'/') unary};
 * unary = '-' unary | primary; primary = number | name | '(' expr ')'.
 * Names are counter names resolved through a caller callback.  Internal to
 * counters/ (tests include it to check the evaluator on known inputs).
 */
#ifndef COUNTERS_COUNTERS_EXPR_H
#define COUNTERS_COUNTERS_EXPR_H

#include <stddef.h>
#include "core/dm_util.h"

/* Resolves name[0..len) to *value; returns 0 or a negative DM_ERR_* and
 * appends the reason to err. */
typedef int (*counters__expr_lookup)(const char *name, size_t len, void *user,
                                     double *value, dm_str *err);

/* Evaluates formula.  Returns 0 and *out; DM_ERR_PARSE on a malformed
 * formula; DM_ERR_UNAVAILABLE on a zero denominator ("value unavailable",
 * never infinite); or the lookup's code.  The reason is appended to err. */
int counters__expr_eval(const char *formula, counters__expr_lookup lookup, void *user,
                        double *out, dm_str *err);

/* Calls fn once per name occurrence in formula, in order. */
void counters__expr_names(const char *formula,
                          void (*fn)(const char *name, size_t len, void *user), void *user);

#endif
