/* compare_internal.h — what the gate's files share (not a public API). */
#ifndef GATE_COMPARE_INTERNAL_H
#define GATE_COMPARE_INTERNAL_H

#include "gate/compare.h"

/* The time counter's samples of every configuration of r blocked by round
 * (models/blocking.h) within its scene: out[i] for r->configs[i], NULL
 * where nothing was corrected (or no_blocking); *st gets the run's state
 * (load, wall_per_cpu, round spread, precision raw and blocked).  Free with
 * compare__blocked_free. */
double **compare__block(const dm_run_result *r, const char *counter, int no_blocking,
                        compare_side_state *st);
void compare__blocked_free(double **blocked, size_t n);

/* The machine checks of out->machine (sides already set by compare__block):
 * the common mode over the timed items (timed[i] for out->items[i]), the
 * CPUTime common mode over the matched configurations, contention, load,
 * and the machine interval; [1, 1] in paired mode. */
void compare__machine_checks(const compare_desc *d, const dm_run_result *base,
                             const dm_run_result *new_,
                             const int *timed, compare_result *out);

#endif
