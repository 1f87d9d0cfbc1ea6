/* counters_derive.c — derived counters over values supplied by the caller
 * (counters.h: counters_derive).  The session path evaluates derived
 * counters over one sample; this one evaluates them over summaries the
 * the caller computes across samples (e.g. medians: run/measure.c). */
#include "counters/counters.h"
#include "core/dm_error.h"
#include "counters/counters_expr.h"

#include <math.h>
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

const char *const counters_tess_walk_inputs[COUNTERS_TESS_WALK_N] = {
    "TESInvocations", "ClippingInputPrimitives", "ClippingOutputPrimitives"};

double counters_tess_walk(const double *calls, size_t n_calls)
{
    double walk = n_calls ? 0 : NAN;
    for (size_t k = 0; k < n_calls; k++) {
        const double *c = calls + k * COUNTERS_TESS_WALK_N;   /* TES, clipper in, clipper out */
        if (!(isfinite(c[0]) && isfinite(c[1]) && isfinite(c[2])))
            return NAN;
        if (c[1] != c[2])
            walk += c[0] * c[2];
    }
    return walk;
}

/* Share of part in total, as a rounded percentage. */
static int derive__pct(double part, double total)
{
    return (int)lround(100.0 * part / total);
}

int counters_stage_verdict(double geometry, double raster, double fragment, dm_str *out)
{
    double total = geometry + raster + fragment;
    if (!(isfinite(total) && total > 0 && geometry >= 0 && raster >= 0 && fragment >= 0))
        return DM_ERR_UNAVAILABLE;
    struct { const char *name; double v; } st[3] = {{"fragment", fragment}, {"geometry", geometry},
                                                   {"raster", raster}};
    for (int i = 1; i < 3; i++)   /* decreasing share; ties keep this order */
        for (int j = i; j > 0 && st[j].v > st[j - 1].v; j--) {
            __typeof__(st[0]) t = st[j];
            st[j] = st[j - 1];
            st[j - 1] = t;
        }
    dm_str_printf(out, "%s %d %%, %s %d %%, %s %d %%", st[0].name, derive__pct(st[0].v, total), st[1].name,
                  derive__pct(st[1].v, total), st[2].name, derive__pct(st[2].v, total));
    return 0;
}
