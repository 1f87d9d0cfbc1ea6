/* formula.c — tokenizer, recursive-descent parser, forward-mode AD evaluator
 * for the cost-model formula language (see formula.h). */
#include "models/formula.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

#define FORMULA__XSTR(x) #x
#define FORMULA__STR(x) FORMULA__XSTR(x)

typedef enum formula__op {
    OP_NUM, OP_VAR, OP_PARAM, OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_NEG,
    OP_EXP, OP_LOG, OP_SQRT, OP_MIN, OP_MAX
} formula__op;

typedef struct formula__node {
    formula__op op;
    double num;
    size_t index;                   /* variable or parameter index */
    char *name;                     /* parameter name (owned) */
    struct formula__node *a, *b;
    size_t start, end;              /* source span [start, end) */
    size_t slot;                    /* workspace slot */
    size_t height;                  /* levels of the subtree (a leaf is 1) */
} formula__node;

/* Nesting the parser accepts (parentheses, signs, powers, function calls)
 * and the height of the tree (a sum of many terms is a tall tree): the
 * parser and the evaluator recurse, so hostile input must not reach the
 * end of the stack. */
#define FORMULA__MAX_NESTING 200
#define FORMULA__MAX_HEIGHT 2000

struct formula {
    char *text;
    formula__node *root;
    char **params;                  /* borrowed from the nodes */
    size_t n_params, n_vars, n_nodes;
    double *work;                   /* n_nodes * (n_params + 1) */
};

/* ---- tokenizer ---------------------------------------------------------- */

typedef enum { TK_END, TK_NUM, TK_NAME, TK_OP } formula__tk;

typedef struct formula__parser {
    const char *text;
    const char *const *vars;
    size_t n_vars;
    size_t pos;                     /* scan position after the current token */
    formula__tk tk;
    char ch;                        /* operator character for TK_OP */
    double num;
    size_t start, end;              /* current token span */
    dm_str *err;
    int failed;
    int nesting;                    /* formula__unary calls in progress */
} formula__parser;

/* Reports the first error only: "formula: column C: expected X after 'P'". */
static void formula__expected(formula__parser *ps, const char *what)
{
    if (ps->failed++)
        return;
    size_t n = ps->start;
    while (n > 0 && isspace((unsigned char)ps->text[n - 1]))
        n--;
    if (n == 0)
        dm_str_printf(ps->err, "formula: column %zu: expected %s at the start",
                      ps->start + 1, what);
    else
        dm_str_printf(ps->err, "formula: column %zu: expected %s after '%.*s'",
                      ps->start + 1, what, (int)n, ps->text);
}

static void formula__fail(formula__parser *ps, const char *msg)
{
    if (!ps->failed++)
        dm_str_printf(ps->err, "formula: column %zu: %s", ps->start + 1, msg);
}

static size_t formula__scan_number(const char *t, size_t i)
{
    while (isdigit((unsigned char)t[i]))
        i++;
    if (t[i] == '.')
        for (i++; isdigit((unsigned char)t[i]); i++) {}
    if (t[i] == 'e' || t[i] == 'E') {
        size_t j = i + 1;
        if (t[j] == '+' || t[j] == '-')
            j++;
        if (isdigit((unsigned char)t[j]))
            for (i = j; isdigit((unsigned char)t[i]); i++) {}
    }
    return i;
}

/* Advances to the next token; an unknown character is a parse error. */
static void formula__next(formula__parser *ps)
{
    const char *t = ps->text;
    size_t i = ps->pos;
    while (isspace((unsigned char)t[i]))
        i++;
    ps->start = i;
    if (!t[i]) {
        ps->tk = TK_END;
    } else if (isdigit((unsigned char)t[i]) || (t[i] == '.' && isdigit((unsigned char)t[i + 1]))) {
        i = formula__scan_number(t, i);
        char *tmp = strndup(t + ps->start, i - ps->start);
        ps->num = strtod(tmp, NULL);
        free(tmp);
        ps->tk = TK_NUM;
    } else if (isalpha((unsigned char)t[i]) || t[i] == '_') {
        while (isalnum((unsigned char)t[i]) || t[i] == '_')
            i++;
        ps->tk = TK_NAME;
    } else if (strchr("+-*/^(),", t[i])) {
        ps->ch = t[i++];
        ps->tk = TK_OP;
    } else {
        char msg[64];
        snprintf(msg, sizeof msg, "unexpected character '%c'", t[i]);
        formula__fail(ps, msg);
        ps->tk = TK_END;
    }
    ps->end = ps->pos = i;
}

static int formula__is_op(const formula__parser *ps, char c)
{
    return ps->tk == TK_OP && ps->ch == c;
}

/* ---- tree --------------------------------------------------------------- */

static formula__node *formula__node_new(formula__op op, size_t start)
{
    formula__node *n = dm_xcalloc(1, sizeof *n);
    n->op = op;
    n->start = n->end = start;
    n->height = 1;
    return n;
}

static void formula__node_free(formula__node *n)
{
    if (!n)
        return;
    formula__node_free(n->a);
    formula__node_free(n->b);
    free(n->name);
    free(n);
}

static formula__node *formula__binary(formula__op op, formula__node *a, formula__node *b)
{
    if (!a || !b) {
        formula__node_free(a);
        formula__node_free(b);
        return NULL;
    }
    formula__node *n = formula__node_new(op, a->start);
    n->a = a;
    n->b = b;
    n->end = b->end;
    n->height = 1 + (a->height > b->height ? a->height : b->height);
    return n;
}

/* ---- parser ------------------------------------------------------------- */

static formula__node *formula__expr(formula__parser *ps);
static formula__node *formula__unary(formula__parser *ps);
static formula__node *formula__tall(formula__parser *ps, formula__node *n);

static const struct { const char *name; formula__op op; int arity; } formula__funcs[] = {
    { "exp", OP_EXP, 1 }, { "log", OP_LOG, 1 }, { "sqrt", OP_SQRT, 1 },
    { "min", OP_MIN, 2 }, { "max", OP_MAX, 2 },
};

/* Parses "(arg [, arg])" after a function name; n is the function node. */
static formula__node *formula__call(formula__parser *ps, formula__node *n, int arity)
{
    formula__next(ps);                               /* '(' */
    n->a = formula__expr(ps);
    if (n->a && arity == 2) {
        if (!formula__is_op(ps, ','))
            formula__expected(ps, "','");
        else {
            formula__next(ps);
            n->b = formula__expr(ps);
        }
    }
    if (!ps->failed && !formula__is_op(ps, ')'))
        formula__expected(ps, "')'");
    if (ps->failed) {
        formula__node_free(n);
        return NULL;
    }
    n->end = ps->end;
    n->height = 1 + (n->a->height > (n->b ? n->b->height : 0) ? n->a->height : n->b->height);
    formula__next(ps);
    return n;
}

static formula__node *formula__name(formula__parser *ps)
{
    size_t len = ps->end - ps->start;
    const char *s = ps->text + ps->start;
    size_t start = ps->start;
    formula__next(ps);
    if (formula__is_op(ps, '(')) {
        for (size_t i = 0; i < sizeof formula__funcs / sizeof formula__funcs[0]; i++)
            if (strlen(formula__funcs[i].name) == len && !strncmp(s, formula__funcs[i].name, len))
                return formula__call(ps, formula__node_new(formula__funcs[i].op, start),
                                     formula__funcs[i].arity);
        char msg[160];
        snprintf(msg, sizeof msg, "unknown function '%.*s' (valid: exp, log, sqrt, min, max)",
                 (int)(len > 64 ? 64 : len), s);
        ps->start = start;
        formula__fail(ps, msg);
        return NULL;
    }
    formula__node *n = formula__node_new(OP_PARAM, start);
    n->end = start + len;
    for (size_t i = 0; i < ps->n_vars; i++)
        if (strlen(ps->vars[i]) == len && !strncmp(s, ps->vars[i], len)) {
            n->op = OP_VAR;
            n->index = i;
            return n;
        }
    n->name = strndup(s, len);
    return n;
}

static formula__node *formula__primary(formula__parser *ps)
{
    if (ps->tk == TK_NUM) {
        formula__node *n = formula__node_new(OP_NUM, ps->start);
        n->num = ps->num;
        n->end = ps->end;
        formula__next(ps);
        return n;
    }
    if (ps->tk == TK_NAME)
        return formula__name(ps);
    if (!formula__is_op(ps, '(')) {
        formula__expected(ps, "a number, a name or '('");
        return NULL;
    }
    size_t start = ps->start;
    formula__next(ps);
    formula__node *n = formula__expr(ps);
    if (n && !formula__is_op(ps, ')'))
        formula__expected(ps, "')'");
    if (ps->failed) {
        formula__node_free(n);
        return NULL;
    }
    n->start = start;                                /* span includes the parentheses */
    n->end = ps->end;
    formula__next(ps);
    return n;
}

static formula__node *formula__power(formula__parser *ps)
{
    formula__node *base = formula__primary(ps);
    if (!base || !formula__is_op(ps, '^'))
        return base;
    formula__next(ps);
    return formula__tall(ps, formula__binary(OP_POW, base, formula__unary(ps)));
}

static formula__node *formula__unary_body(formula__parser *ps)
{
    if (!formula__is_op(ps, '-'))
        return formula__power(ps);
    size_t start = ps->start;
    formula__next(ps);
    formula__node *a = formula__unary(ps);
    if (!a)
        return NULL;
    formula__node *n = formula__node_new(OP_NEG, start);
    n->a = a;
    n->end = a->end;
    n->height = a->height + 1;
    return n;
}

/* Every recursion of the parser passes here: refuses nesting deeper than
 * FORMULA__MAX_NESTING with a clear error instead of overflowing the stack. */
static formula__node *formula__unary(formula__parser *ps)
{
    if (ps->nesting >= FORMULA__MAX_NESTING) {
        formula__fail(ps, "nested deeper than " FORMULA__STR(FORMULA__MAX_NESTING)
                      " levels (parentheses, minus signs, powers or calls); simplify it");
        return NULL;
    }
    ps->nesting++;
    formula__node *n = formula__unary_body(ps);
    ps->nesting--;
    return n;
}

/* Refuses a tree taller than FORMULA__MAX_HEIGHT (a sum or product of
 * thousands of terms); n is freed then. */
static formula__node *formula__tall(formula__parser *ps, formula__node *n)
{
    if (!n || n->height <= FORMULA__MAX_HEIGHT)
        return n;
    formula__fail(ps, "more than " FORMULA__STR(FORMULA__MAX_HEIGHT)
                  " operations in a row; simplify it");
    formula__node_free(n);
    return NULL;
}

static formula__node *formula__term(formula__parser *ps)
{
    formula__node *n = formula__unary(ps);
    while (n && (formula__is_op(ps, '*') || formula__is_op(ps, '/'))) {
        formula__op op = ps->ch == '*' ? OP_MUL : OP_DIV;
        formula__next(ps);
        n = formula__tall(ps, formula__binary(op, n, formula__unary(ps)));
    }
    return n;
}

static formula__node *formula__expr(formula__parser *ps)
{
    formula__node *n = formula__term(ps);
    while (n && (formula__is_op(ps, '+') || formula__is_op(ps, '-'))) {
        formula__op op = ps->ch == '+' ? OP_ADD : OP_SUB;
        formula__next(ps);
        n = formula__tall(ps, formula__binary(op, n, formula__term(ps)));
    }
    return n;
}

/* ---- parameter numbering and workspace ------------------------------------ */

/* Numbers parameters in order of first appearance and assigns slots. */
static void formula__index(formula *f, formula__node *n)
{
    if (!n)
        return;
    formula__index(f, n->a);
    formula__index(f, n->b);
    n->slot = f->n_nodes++;
    if (n->op != OP_PARAM)
        return;
    for (size_t i = 0; i < f->n_params; i++)
        if (!strcmp(f->params[i], n->name)) {
            n->index = i;
            return;
        }
    f->params = dm_xrealloc(f->params, (f->n_params + 1) * sizeof *f->params);
    n->index = f->n_params;
    f->params[f->n_params++] = n->name;
}

static void formula__reindex(formula *f)
{
    free(f->params);
    free(f->work);
    f->params = NULL;
    f->n_params = f->n_nodes = 0;
    formula__index(f, f->root);
    f->work = dm_xcalloc(f->n_nodes * (f->n_params + 1), sizeof *f->work);
}

int formula_parse(const char *text, const char *const *vars, size_t n_vars,
                  formula **out, dm_str *err)
{
    formula__parser ps = { .text = text, .vars = vars, .n_vars = n_vars, .err = err };
    *out = NULL;
    formula__next(&ps);
    formula__node *root = ps.failed ? NULL : formula__expr(&ps);
    if (root && ps.tk != TK_END)
        formula__expected(&ps, "an operator or the end of the formula");
    if (ps.failed) {
        formula__node_free(root);
        return DM_ERR_PARSE;
    }
    formula *f = dm_xcalloc(1, sizeof *f);
    f->text = dm_xstrdup(text);
    f->root = root;
    f->n_vars = n_vars;
    formula__reindex(f);
    *out = f;
    return 0;
}

void formula_free(formula *f)
{
    if (!f)
        return;
    formula__node_free(f->root);
    free(f->params);
    free(f->work);
    free(f->text);
    free(f);
}

const char *formula_text(const formula *f) { return f->text; }
size_t formula_n_params(const formula *f) { return f->n_params; }
const char *formula_param_name(const formula *f, size_t i) { return f->params[i]; }

long formula_param_index(const formula *f, const char *name)
{
    for (size_t i = 0; i < f->n_params; i++)
        if (!strcmp(f->params[i], name))
            return (long)i;
    return -1;
}

static int formula__uses_var(const formula__node *n, size_t var)
{
    if (!n)
        return 0;
    if (n->op == OP_VAR && n->index == var)
        return 1;
    return formula__uses_var(n->a, var) || formula__uses_var(n->b, var);
}

int formula_uses_var(const formula *f, size_t var)
{
    return formula__uses_var(f->root, var);
}

/* ---- evaluation (forward-mode AD) ---------------------------------------- */

/* Evaluates n into its slot: slot[0] value, slot[1..P] gradient (when g). */
static const double *formula__eval(formula *f, const formula__node *n,
                                   const double *x, const double *p, int g)
{
    size_t P = f->n_params;
    double *o = f->work + n->slot * (P + 1);
    const double *a = n->a ? formula__eval(f, n->a, x, p, g) : NULL;
    const double *b = n->b ? formula__eval(f, n->b, x, p, g) : NULL;
    double av = a ? a[0] : 0.0, bv = b ? b[0] : 0.0, v = 0.0, ca = 0.0, cb = 0.0;
    int bdep = 0;
    switch (n->op) {
    case OP_NUM:   v = n->num; break;
    case OP_VAR:   v = x[n->index]; break;
    case OP_PARAM: v = p[n->index]; break;
    case OP_ADD:   v = av + bv; ca = 1.0; cb = 1.0; break;
    case OP_SUB:   v = av - bv; ca = 1.0; cb = -1.0; break;
    case OP_NEG:   v = -av; ca = -1.0; break;
    case OP_MUL:   v = av * bv; ca = bv; cb = av; break;
    case OP_DIV:   v = av / bv; ca = 1.0 / bv; cb = -v / bv; break;
    case OP_POW:
        v = pow(av, bv);
        ca = bv == 0.0 ? 0.0 : bv * pow(av, bv - 1.0);
        for (size_t j = 0; g && j < P; j++)
            bdep |= b[1 + j] != 0.0;
        cb = bdep ? v * log(av) : 0.0;               /* log only when the exponent varies */
        break;
    case OP_EXP:   v = exp(av); ca = v; break;
    case OP_LOG:   v = log(av); ca = 1.0 / av; break;
    case OP_SQRT:  v = sqrt(av); ca = 0.5 / v; break;
    case OP_MIN:   v = av <= bv ? av : bv; ca = av <= bv; cb = !(av <= bv); break;
    case OP_MAX:   v = av >= bv ? av : bv; ca = av >= bv; cb = !(av >= bv); break;
    }
    o[0] = v;
    for (size_t j = 0; g && j < P; j++)
        o[1 + j] = (a && a[1 + j] != 0.0 ? ca * a[1 + j] : 0.0)
                 + (b && b[1 + j] != 0.0 ? cb * b[1 + j] : 0.0);
    if (g && n->op == OP_PARAM)
        o[1 + n->index] = 1.0;
    return o;
}

double formula_eval(formula *f, const double *x, const double *p, double *grad)
{
    const double *o = formula__eval(f, f->root, x, p, grad != NULL);
    if (grad)
        memcpy(grad, o + 1, f->n_params * sizeof *grad);
    return o[0];
}

/* ---- structure ------------------------------------------------------------ */

/* Degree in the parameter(s) selected by `which` (SIZE_MAX = all): 0 none,
 * 1 affine, 2 anything else. */
static int formula__degree(const formula__node *n, size_t which)
{
    int da = n->a ? formula__degree(n->a, which) : 0;
    int db = n->b ? formula__degree(n->b, which) : 0;
    switch (n->op) {
    case OP_NUM: case OP_VAR: return 0;
    case OP_PARAM: return which == SIZE_MAX || n->index == which;
    case OP_ADD: case OP_SUB: return da > db ? da : db;
    case OP_NEG: return da;
    case OP_MUL: return da + db > 2 ? 2 : da + db;
    case OP_DIV: return db ? 2 : da;
    default: return (da || db) ? 2 : 0;
    }
}

int formula_param_is_linear(const formula *f, size_t i)
{
    return formula__degree(f->root, i) <= 1;
}

int formula_is_linear(const formula *f)
{
    return formula__degree(f->root, SIZE_MAX) <= 1;
}

/* Replaces the terms of the additive chain at *slot that use var by 0. */
static size_t formula__drop(formula *f, formula__node **slot, size_t var, dm_str *removed)
{
    formula__node *n = *slot;
    if (n->op == OP_ADD || n->op == OP_SUB)
        return formula__drop(f, &n->a, var, removed) + formula__drop(f, &n->b, var, removed);
    if (!formula__uses_var(n, var))
        return 0;
    if (removed->len)
        dm_str_cat(removed, ", ");
    dm_str_catn(removed, f->text + n->start, n->end - n->start);
    formula__node *zero = formula__node_new(OP_NUM, n->start);
    zero->end = n->end;
    formula__node_free(n);
    *slot = zero;
    return 1;
}

size_t formula_drop_terms_with_var(formula *f, size_t var, dm_str *removed)
{
    size_t k = formula__drop(f, &f->root, var, removed);
    if (k)
        formula__reindex(f);
    return k;
}
