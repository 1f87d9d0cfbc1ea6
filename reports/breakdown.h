/* breakdown.h — which counter breakdown a scene's chart draws, decided once
 * per scene by the report model (report_model.c) and drawn by chart.c.
 *
 * Per configuration, in order of preference: the stage times its timed
 * isolation passes measured (GeometryTime, MinimalShadingTime) beside the
 * frame's median; else a cost model's estimate per stage when a fit of it
 * explains enough of the time (time-from-stages over the exact stage
 * counters before pipeline-linear over invocation counts); else the key
 * counters normalised to their maxima.  At most BREAKDOWN_MAX_BARS
 * configurations are drawn, the slowest.
 */
#ifndef REPORTS_BREAKDOWN_H
#define REPORTS_BREAKDOWN_H

#include <stddef.h>

#include "core/dm_results.h"

/* At most this many configurations get a bar group; the fastest are left out. */
#define BREAKDOWN_MAX_BARS 24
/* A per-stage estimate is drawn only from a fit at least this good (R²);
 * a poorer one would show invented stage times (docs/models.md). */
#define BREAKDOWN_MIN_STAGE_R2 0.8
/* Stages of the measured breakdown: geometry, setup+raster, fragment. */
#define BREAKDOWN_MEASURED_STAGES 3
#define BREAKDOWN_MAX_STAGES 5

/* A term of a cost model that splits frame time by stage: its parameter,
 * the counter it multiplies (NULL: the fixed cost) and its legend name. */
typedef struct breakdown_stage {
    const char *param, *counter, *name;
} breakdown_stage;

typedef struct breakdown_model {
    const char *model;
    const breakdown_stage *stages;
    size_t n;
    int exact;   /* its counters are the stage counters: drawn only where a configuration has them */
} breakdown_model;

typedef enum breakdown_kind {
    BREAKDOWN_NONE = 0,    /* nothing to draw */
    BREAKDOWN_MEASURED,    /* the timed isolation passes */
    BREAKDOWN_FIT,         /* a cost model's estimate per stage */
    BREAKDOWN_COUNTERS     /* the key counters, relative to each one's maximum */
} breakdown_kind;

typedef struct breakdown {
    breakdown_kind kind;
    const breakdown_model *fit;    /* BREAKDOWN_FIT: the model whose fits are drawn */
    const breakdown_model *poor;   /* BREAKDOWN_COUNTERS: a model fitted too poorly to draw, or NULL */
    double poor_r2;                /* its R² */
    size_t *bars;                  /* config indexes drawn, fastest first (malloc'd) */
    size_t n_bars;
    size_t skipped;                /* the fastest timed configurations left out */
    const char *counters[4];       /* BREAKDOWN_COUNTERS: the counters drawn */
    size_t n_counters;
    double hi_ms;                  /* the tallest stack or median, ms (MEASURED, FIT) */
} breakdown;

/* Chooses the breakdown of the n timed configurations rows (config indexes
 * into run, fastest first) into *out (zeroed first; breakdown_free). */
void breakdown_choose(const dm_run_result *run, const size_t *rows, size_t n, breakdown *out);
void breakdown_free(breakdown *b);

/* The fit of model m for c when it is good enough to draw (its group
 * matches c's params, R² >= BREAKDOWN_MIN_STAGE_R2), else NULL. */
const dm_fit_result *breakdown_fit(const dm_run_result *run, const dm_config_result *c,
                                   const breakdown_model *m);
/* Estimated ms of stage k of c under fit f of model m (param · counter; the
 * response is ns). */
double breakdown_stage_ms(const breakdown_model *m, const dm_fit_result *f, const dm_config_result *c,
                          size_t k);
/* Measured ms of stage k of c (geometry, setup and raster, fragment) from
 * its timed isolation passes: GeometryTime, MinimalShadingTime −
 * GeometryTime and WallTime − MinimalShadingTime (medians; a difference
 * that noise puts below 0 is 0); NaN when c has not both passes. */
double breakdown_measured_ms(const dm_config_result *c, size_t k);
/* Value of an available deterministic counter, else 0 (absent work). */
double breakdown_det_value(const dm_config_result *c, const char *name);

#endif
