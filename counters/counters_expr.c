/* counters_expr.c — recursive-descent evaluator for derived-counter formulas. */
#include "counters_expr.h"
#include "core/dm_error.h"

#include <ctype.h>
#include <stdlib.h>

typedef struct expr__p {
    const char *s, *formula;
    counters__expr_lookup lookup;
    void *user;
    dm_str *err;
    int nesting;          /* expr__unary calls in progress */
} expr__p;

/* Deepest nesting of parentheses and signs: the evaluator recurses, so
 * hostile input gets an error instead of overflowing the stack. */
#define EXPR__MAX_NESTING 200

static int expr__sum(expr__p *p, double *v);

static int expr__isname(int c, int first)
{
    return isalpha(c) || c == '_' || (!first && isdigit(c));
}

static void expr__ws(expr__p *p)
{
    while (isspace((unsigned char)*p->s))
        p->s++;
}

static int expr__syntax(expr__p *p, const char *what)
{
    dm_str_printf(p->err, "formula '%s': %s at offset %d", p->formula, what,
                  (int)(p->s - p->formula));
    return DM_ERR_PARSE;
}

/* primary = number | name | '(' sum ')' */
static int expr__primary(expr__p *p, double *v)
{
    expr__ws(p);
    unsigned char c = (unsigned char)*p->s;
    if (c == '(') {
        p->s++;
        int rc = expr__sum(p, v);
        if (rc)
            return rc;
        expr__ws(p);
        if (*p->s != ')')
            return expr__syntax(p, "expected ')'");
        p->s++;
        return 0;
    }
    if (isdigit(c) || c == '.') {
        char *end;
        *v = strtod(p->s, &end);
        p->s = end;
        return 0;
    }
    if (!expr__isname(c, 1))
        return expr__syntax(p, c ? "expected a number, a name or '('" : "unexpected end");
    const char *start = p->s;
    while (expr__isname((unsigned char)*p->s, 0))
        p->s++;
    return p->lookup(start, (size_t)(p->s - start), p->user, v, p->err);
}

static int expr__unary(expr__p *p, double *v)
{
    expr__ws(p);
    if (p->nesting >= EXPR__MAX_NESTING)
        return expr__syntax(p, "nested deeper than 200 levels (parentheses or minus signs)");
    p->nesting++;
    int rc;
    if (*p->s != '-') {
        rc = expr__primary(p, v);
    } else {
        p->s++;
        rc = expr__unary(p, v);
        *v = -*v;
    }
    p->nesting--;
    return rc;
}

/* term = unary {('*'|'/') unary}; a zero denominator is unavailable. */
static int expr__term(expr__p *p, double *v)
{
    int rc = expr__unary(p, v);
    for (expr__ws(p); !rc && (*p->s == '*' || *p->s == '/'); expr__ws(p)) {
        char op = *p->s++;
        double r;
        rc = expr__unary(p, &r);
        if (rc)
            break;
        if (op == '/' && r == 0.0) {
            dm_str_printf(p->err, "zero denominator in '%s'", p->formula);
            return DM_ERR_UNAVAILABLE;
        }
        *v = op == '*' ? *v * r : *v / r;
    }
    return rc;
}

static int expr__sum(expr__p *p, double *v)
{
    int rc = expr__term(p, v);
    for (expr__ws(p); !rc && (*p->s == '+' || *p->s == '-'); expr__ws(p)) {
        char op = *p->s++;
        double r;
        rc = expr__term(p, &r);
        *v = op == '+' ? *v + r : *v - r;
    }
    return rc;
}

int counters__expr_eval(const char *formula, counters__expr_lookup lookup, void *user,
                        double *out, dm_str *err)
{
    expr__p p = { .s = formula, .formula = formula, .lookup = lookup, .user = user, .err = err };
    double v = 0;
    int rc = expr__sum(&p, &v);
    if (rc)
        return rc;
    expr__ws(&p);
    if (*p.s)
        return expr__syntax(&p, "unexpected trailing text");
    *out = v;
    return 0;
}

void counters__expr_names(const char *formula,
                          void (*fn)(const char *name, size_t len, void *user), void *user)
{
    const char *s = formula;
    while (*s) {
        if (isdigit((unsigned char)*s) || *s == '.') {
            while (isalnum((unsigned char)*s) || *s == '.')
                s++;   /* numbers (and exponents) are not names */
        } else if (expr__isname((unsigned char)*s, 1)) {
            const char *start = s;
            while (expr__isname((unsigned char)*s, 0))
                s++;
            fn(start, (size_t)(s - start), user);
        } else {
            s++;
        }
    }
}
