/* fraction.c — the fraction grammar of fraction.h. */
#include "sweep/fraction.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"

/* "5%" -> 5 with *percent set, "0.05" -> 0.05; 0 when it is one of them. */
static int fraction__number(const char *text, double *x, int *percent)
{
    char *end = NULL;
    if (!text || !(isdigit((unsigned char)*text) || *text == '.') ||
        text[strspn(text, "0123456789.eE+-")] != (strchr(text, '%') ? '%' : '\0'))
        return -1;   /* decimal only: no sign, space, hex, "inf" */
    *x = strtod(text, &end);
    *percent = *end == '%';
    if (end == text || !isfinite(*x) || end[*percent] != '\0')
        return -1;
    return 0;
}

/* x% as the double nearest to x/100: the text with "e-2" appended and read
 * again, so "3.3%" is bit for bit the 0.033 that "0.033" gives (x / 100
 * rounds twice).  Text with an exponent of its own is divided. */
static double fraction__percent(const char *text, double x)
{
    size_t n = strcspn(text, "%");
    if (strpbrk(text, "eE") || n > 60)
        return x / 100;
    char buf[72];
    snprintf(buf, sizeof buf, "%.*se-2", (int)n, text);
    return strtod(buf, NULL);
}

static int fraction__inside(double x, const fraction_range *r)
{
    return (r->lo_open ? x > r->lo : x >= r->lo) && (r->hi_open ? x < r->hi : x <= r->hi);
}

/* "(0 %, 100 %]" */
static void fraction__range_text(const fraction_range *r, dm_str *s)
{
    dm_str_printf(s, "%s%g %%, ", r->lo_open ? "(" : "[", r->lo * 100);
    if (isinf(r->hi))
        dm_str_cat(s, "any)");
    else
        dm_str_printf(s, "%g %%%s", r->hi * 100, r->hi_open ? ")" : "]");
}

int fraction_parse(const char *text, const char *what, const fraction_range *range, double *out,
                   dm_str *err)
{
    double x;
    int percent;
    if (fraction__number(text, &x, &percent) != 0) {
        dm_str_printf(err, "%s '%s': expected a percentage or a fraction, e.g. 5%% or 0.05",
                      what, text ? text : "(none)");
        return DM_ERR_ARG;
    }
    if (!percent && x > 1) {
        dm_str_printf(err, "%s '%s': a bare number is a fraction (1 = 100 %%), so %g would be "
                      "%g %%; write %g%% or %g for %g percent", what, text, x, x * 100, x,
                      x / 100, x);
        return DM_ERR_ARG;
    }
    double v = percent ? fraction__percent(text, x) : x;
    if (!fraction__inside(v, range)) {
        dm_str_printf(err, "%s '%s': expected a value in ", what, text);
        fraction__range_text(range, err);
        dm_str_cat(err, ", written as a percentage (5%) or a fraction (0.05)");
        return DM_ERR_RANGE;
    }
    *out = v;
    return 0;
}
