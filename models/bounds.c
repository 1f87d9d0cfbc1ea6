/* bounds.c — bound clauses after a formula (see bounds.h). */
#include "models/bounds.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

static char *bounds__strndup(const char *s, size_t n)
{
    char *d = dm_xmalloc(n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

/* Skips spaces; returns the new position. */
static const char *bounds__ws(const char *p)
{
    while (isspace((unsigned char)*p))
        p++;
    return p;
}

/* A finite number at *p (advanced); 0 when there is none. */
static int bounds__number(const char **p, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(*p, &end);
    if (end == *p || errno || !isfinite(*v))
        return 0;
    *p = bounds__ws(end);
    return 1;
}

/* A name [A-Za-z_][A-Za-z0-9_]* at *p (advanced), malloc'd; NULL when none. */
static char *bounds__name(const char **p)
{
    const char *s = *p;
    if (!(isalpha((unsigned char)*s) || *s == '_'))
        return NULL;
    while (isalnum((unsigned char)*s) || *s == '_')
        s++;
    char *name = bounds__strndup(*p, (size_t)(s - *p));
    *p = bounds__ws(s);
    return name;
}

/* One clause [p, e) into b; 0 when it is not one of the three forms. */
static int bounds__clause(const char *p, const char *e, fit_bound *b)
{
    char *text = bounds__strndup(p, (size_t)(e - p));
    const char *q = bounds__ws(text);
    double lo;
    b->lo = -INFINITY;
    b->hi = INFINITY;
    char *name = NULL;
    int ok = 0;
    if (bounds__number(&q, &lo)) {                          /* NUMBER <= NAME <= NUMBER */
        if (strncmp(q, "<=", 2) == 0 && (q = bounds__ws(q + 2), name = bounds__name(&q)) &&
            strncmp(q, "<=", 2) == 0) {
            q = bounds__ws(q + 2);
            b->lo = lo;
            ok = bounds__number(&q, &b->hi) && !*q && lo <= b->hi;
        }
    } else if ((name = bounds__name(&q)) != NULL) {          /* NAME >= NUMBER | NAME <= NUMBER */
        int ge = strncmp(q, ">=", 2) == 0, le = strncmp(q, "<=", 2) == 0;
        if (ge || le) {
            q = bounds__ws(q + 2);
            ok = bounds__number(&q, ge ? &b->lo : &b->hi) && !*q;
        }
    }
    free(text);
    if (!ok) {
        free(name);
        return 0;
    }
    b->param = name;
    return 1;
}

/* 0 when the bounds of every parameter leave some value (the highest lower
 * bound <= the lowest upper bound), else DM_ERR_PARSE naming the parameter:
 * the fit would otherwise silently break one of them. */
static int bounds__consistent(const fit_bound *b, size_t n, dm_str *err)
{
    for (size_t i = 0; i < n; i++) {
        double lo = b[i].lo, hi = b[i].hi;
        for (size_t j = 0; j < n; j++)
            if (strcmp(b[i].param, b[j].param) == 0) {
                lo = b[j].lo > lo ? b[j].lo : lo;
                hi = b[j].hi < hi ? b[j].hi : hi;
            }
        if (lo > hi) {
            dm_str_printf(err, "formula: bounds of '%s' contradict each other (it must be "
                          ">= %g and <= %g); no value satisfies them", b[i].param, lo, hi);
            return DM_ERR_PARSE;
        }
    }
    return 0;
}

int bounds_split(const char *text, char **expr, fit_bound **bounds, size_t *n_bounds, dm_str *err)
{
    const char *semi = strchr(text, ';');
    fit_bound *out = NULL;
    size_t n = 0;
    for (const char *p = semi; p && *p; ) {
        const char *e = strchr(p + 1, ';');
        e = e ? e : p + 1 + strlen(p + 1);
        out = dm_xrealloc(out, (n + 1) * sizeof *out);
        if (!bounds__clause(p + 1, e, &out[n])) {
            dm_str_printf(err, "formula: bound %zu '%.*s': expected NAME >= NUMBER, NAME <= NUMBER "
                          "or NUMBER <= NAME <= NUMBER", n + 1, (int)(e - p - 1), p + 1);
            bounds_free(out, n);
            return DM_ERR_PARSE;
        }
        n++;
        p = e;
    }
    if (bounds__consistent(out, n, err) != 0) {
        bounds_free(out, n);
        return DM_ERR_PARSE;
    }
    *expr = semi ? bounds__strndup(text, (size_t)(semi - text)) : dm_xstrdup(text);
    *bounds = out;
    *n_bounds = n;
    return 0;
}

void bounds_free(fit_bound *bounds, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free((char *)bounds[i].param);
    free(bounds);
}
