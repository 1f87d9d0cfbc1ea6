/* counters_derive.c — derived counters over values supplied by the caller
 * (counters.h: counters_derive).  The session path evaluates derived
 * counters over one sample; this one evaluates them over summaries the
 * harness computes across samples (e.g. medians). */
#include "counters/counters.h"
#include "core/dm_error.h"
#include "counters/counters_expr.h"

#include <stdio.h>
#include <string.h>

typedef struct derive__ctx {
    counters_value_fn fn;
    void *user;
    int (*has)(const char *input, void *user);
    int all;
} derive__ctx;

static int derive__lookup(const char *name, size_t len, void *user, double *value, dm_str *err)
{
    derive__ctx *d = user;
    char buf[64];
    if (len >= sizeof buf)
        return DM_ERR_ARG;
    memcpy(buf, name, len);
    buf[len] = '\0';
    if (d->fn(buf, d->user, value) != 0) {
        dm_str_printf(err, "input %s is unavailable", buf);
        return DM_ERR_UNAVAILABLE;
    }
    return 0;
}

int counters_derive(const char *name, counters_value_fn value, void *user, double *out, dm_str *why)
{
    const counters_info *ci = counters_find(name);
    if (!ci || ci->backend != COUNTERS_BACKEND_DERIVED || !ci->formula)
        return DM_ERR_UNKNOWN;
    derive__ctx d = { .fn = value, .user = user };
    dm_str scratch = {0};
    int rc = counters__expr_eval(ci->formula, derive__lookup, &d, out, why ? why : &scratch);
    dm_str_free(&scratch);
    return rc == DM_ERR_UNAVAILABLE || rc == 0 ? rc : DM_ERR_UNAVAILABLE;
}

static void derive__check(const char *name, size_t len, void *user)
{
    derive__ctx *d = user;
    char buf[64];
    if (len >= sizeof buf) {
        d->all = 0;
        return;
    }
    memcpy(buf, name, len);
    buf[len] = '\0';
    if (!d->has(buf, d->user))
        d->all = 0;
}

int counters_derive_inputs(const char *name, int (*has)(const char *input, void *user), void *user)
{
    const counters_info *ci = counters_find(name);
    if (!ci || ci->backend != COUNTERS_BACKEND_DERIVED || !ci->formula)
        return 0;
    derive__ctx d = { .has = has, .user = user, .all = 1 };
    counters__expr_names(ci->formula, derive__check, &d);
    return d.all;
}
