/* stage_bar.h — the report's "Where the instructions go": per configuration
 * with stage counters (docs/counters.md, "Stage costs"), a stacked bar of
 * its geometry, raster and fragment shares, its bottleneck verdict and its
 * per-invocation costs (in the table, and on hover over the bar). */
#ifndef REPORTS_STAGE_BAR_H
#define REPORTS_STAGE_BAR_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "reports/report_model.h"

/* Appends the section for the model's rows (run order, each labelled as in
 * its scene's table) to s; nothing when no configuration of the run has all
 * three stage counters available. */
void report_stage_bars(dm_str *s, const report_model *m);

#endif
