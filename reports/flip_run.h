/* flip_run.h — FLIP of a stored run again at another viewing condition
 * (`dmbench report DIR --flip-ppd N`): imaging/flip.h over the run's
 * stored images, the results written back into the run. */
#ifndef REPORTS_FLIP_RUN_H
#define REPORTS_FLIP_RUN_H

#include "core/dm_results.h"
#include "core/dm_util.h"

/* FLIP of every configuration of run again at ppd, from the render and
 * reference files under the run directory dir (8-bit PNGs, so values
 * differ slightly from the run's, computed on float images); the maps are
 * written as dir/img/<key>-flip-ppd<N>.png and the configurations point to
 * them.  Configurations without both images keep their values.  0,
 * DM_ERR_ARG (ppd < 1), or the first failure (DM_ERR_IO ...) with the
 * configuration and reason in err. */
int flip_run_recompute(dm_run_result *run, const char *dir, double ppd, dm_str *err);

#endif
