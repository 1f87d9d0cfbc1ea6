/* fitting.h — cost models over a run's results (used by `run` and `fit`).
 *
 * Variables a formula may use: every counter of the run (its median for
 * timed counters, its value otherwise), every numeric axis,
 * `resolution` as the pixel count W×H, and FITTING_TESS_WALK (below).  A configuration missing a variable
 * or the response gets NaN there, which the fitter excludes and counts.
 * GPUTime is never used when the timer is partial (docs/counters.md).  Failed
 * configurations are not used.
 */
#ifndef RUN_FITTING_H
#define RUN_FITTING_H

#include <stddef.h>
#include "core/dm_results.h"
#include "models/fit.h"

typedef struct fitting_spec {
    const char *name;            /* built-in model name or a label */
    const char *formula;         /* NULL: the built-in model's formula */
    const char *response;        /* NULL: the model's default, else WallTime */
    const char *const *group_by; /* one fit per distinct value of these axes */
    size_t n_group_by;
    fit_loss loss;
    int relative;                /* fit relative errors (fit_desc.relative) */
} fitting_spec;

/* The group key that is not an axis: a configuration's shader variant,
 * i.e. its technique and the axes that change its shaders (non-scene enum
 * axes, integer axes set to "auto", virtual_texture), as text
 * "pom shadow=hard steps=auto" (fitting_variant).  Numeric axes that are
 * uniforms (steps, tess_level, light_count) are not part of it: a variant's
 * model predicts across them. */
#define FITTING_VARIANT "variant"

/* The variable that is neither a counter nor an axis: llvmpipe's vertex
 * walk of a tessellated frame, the sum over its draw calls of each call's
 * evaluations x primitives (docs/models.md, "Tessellation across draw
 * calls").  Measured: the configuration's FITTING_TESS_WALK_CALLS when it
 * has one (the counts taken around each call, only the calls the clipper
 * changed).  Otherwise approximated from the frame's TESInvocations x
 * ClippingOutputPrimitives and the calls render_draw splits the frame's
 * patches into (render_patch_calls), each call's counts in proportion to
 * its patches; 0 when the clipper passed every primitive unchanged
 * (ClippingInputPrimitives == ClippingOutputPrimitives, when counted: the
 * draw module then emits without walking).  A run has it when it has
 * TESInvocations and ClippingOutputPrimitives. */
#define FITTING_TESS_WALK "TessWalk"
/* The counter that measures it per draw call (counters.h, counters_tess_walk). */
#define FITTING_TESS_WALK_CALLS "TessWalkCalls"

/* The share of evaluations x primitives that walk covers when `patches`
 * are drawn in calls of at most per_call (0: one call): the sum over
 * calls of (its patches / patches)^2; 1 for one call. */
double fitting_call_share(size_t patches, size_t per_call);
char *fitting_variant(const dm_kv *params, size_t n);

/* Fits the spec to the run; appends one dm_fit_result per group to
 * fits/n.  A group that cannot be fitted adds a line to warnings.
 * Returns 0, or DM_ERR_UNKNOWN when the model is neither built in nor
 * given a formula (err lists the built-in models). */
int fitting_run(const fitting_spec *spec, const dm_run_result *run, dm_fit_result **fits,
                size_t *n, dm_str *warnings, dm_str *err);

/* Checks a sweep's models before anything is measured: a formula must
 * parse (with its bounds) and a fitted parameter must not look like a
 * misspelled counter or axis (a name of 4+ letters within dm_closest's
 * distance of one); a model without a formula must be built in.  0, or
 * DM_ERR_PARSE / DM_ERR_UNKNOWN with "FILE:LINE: models: NAME: ..." in err. */
struct sweep;
int fitting_check_models(const struct sweep *s, dm_str *err);

/* The same check for one formula (with its bounds), e.g. `fit --formula`:
 * 0, or DM_ERR_PARSE / DM_ERR_UNKNOWN with the reason in why ("'tess_levle'
 * would be a fitted parameter; did you mean 'tess_level'? ..."). */
int fitting_check_formula(const char *formula, dm_str *why);

/* Checks a name given to `fit`: with axis_only, a --group-by key (an axis
 * or FITTING_VARIANT), else a --response (a counter or an axis).  0, or
 * DM_ERR_UNKNOWN with "unknown ... 'NAME'; did you mean 'X'? valid ...". */
int fitting_check_name(const char *name, int axis_only, dm_str *why);

/* Predicts the response of a stored fit for a configuration that has not
 * been measured (the planner's --budget).  The configuration is given by
 * its axes (params, as planned: `resolution` is W×H) and its key.  Names of
 * the fit's formula that are not its fitted parameters are variables; each
 * takes the configuration's numeric axis value (resolution = pixel count)
 * or, failing that, the counter stored for the same key in the first of
 * runs (n_runs, newest first) that has it, with the rules of fitting_run
 * (failed configurations, unavailable counters and a partial GPUTime never).
 * Returns 0 and *value (> 0, finite); DM_ERR_NOTFOUND when the fit's group
 * does not contain the configuration or a variable has no value,
 * DM_ERR_PARSE for a fit without a valid formula, DM_ERR_NUMERIC when the
 * prediction is not a positive finite number; `why` then says why and
 * *value is NaN. */
int fitting_predict(const dm_fit_result *fit, const dm_kv *params, size_t n_params,
                    const char *key, const dm_run_result *runs, size_t n_runs, double *value,
                    dm_str *why);

/* fitting_predict for a fit of `train` whose formula keeps a term the fit
 * dropped because one of its variables had the same value in every
 * configuration of the group (a constant column: its cost is inside the
 * other terms): when this configuration has the same value of each such
 * variable the term counts 0, else DM_ERR_NOTFOUND with why naming the
 * variable, both values and the term ("the fitted runs never varied
 * TESInvocations in this group (0), this configuration has 100 ..."). */
int fitting_predict_dropped(const dm_fit_result *fit, const dm_run_result *train, const dm_kv *params,
                            size_t n_params, const char *key, const dm_run_result *runs, size_t n_runs,
                            double *value, dm_str *why);

#endif
