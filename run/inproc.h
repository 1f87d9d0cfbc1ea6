/* inproc.h — counts measured in the calling process, without a child: the
 * invocation counts `dmbench predict` multiplies by per-invocation costs.
 */
#ifndef RUN_INPROC_H
#define RUN_INPROC_H

#include <stddef.h>

#include "core/dm_util.h"
#include "sweep/plan.h"

/* The deterministic counters names[0..n_names) of configurations
 * cs[0..n) over one frame each (after one uncounted frame), in this
 * process (it creates and destroys its own GL context).  values is
 * n x n_names, row-major; NaN where a configuration cannot be prepared or
 * a counter is unavailable.  Returns 0 or DM_ERR_* (err) when the context
 * cannot be set up. */
int inproc_counts(const plan_config *cs, size_t n, const char *const *names, size_t n_names, double *values,
                  dm_str *err);

#endif
