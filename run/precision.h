/* precision.h — a finished run's figures with the machine's drift removed,
 * beside the raw ones, and its noise floor (docs/measurement.md, "Drift
 * removed").
 *
 * After the last configuration is committed the runner hands the loaded
 * run to precision_apply: for every scene it lays the samples of each
 * timed counter (unit ns) out by round — the rounds the measuring process
 * recorded (dm_round: the configurations in the order sampled), so sample
 * j of a configuration is the j-th round that names it — and asks
 * models/drift.h for the corrected median and CI of each configuration.
 * The scene's WallTime decides whether the correction is kept: when the
 * common mode cannot be measured (fewer than 3 configurations or rounds)
 * or finds no drift to remove (models/drift.h: the round factors spread
 * no more than twice what the configurations' own noise gives them), the
 * configurations keep their raw figures only, and the scene's
 * dm_scene_precision says why.  The raw figures are never changed.
 *
 * The between-run CIs then take the run's slow drift: the host's speed
 * moves between runs by more than the bootstrap over blocks of a few
 * rounds sees (on quiet runs a scene's every configuration moved together
 * by ±2-11 % from one run to the next).  How far it moves on the scale of
 * a scene is measured by each corrected scene's half shift (models/drift.h:
 * its later rounds' median speed against its earlier rounds'); the run's
 * slow drift is their root mean square over the corrected scenes, /√2 (the
 * two halves as two independent draws of the host's level, as two runs
 * are).  Every between-run CI of those scenes is widened by 1.96 times it
 * (in quadrature, log scale) and each scene's reference_spread takes it in
 * quadrature too.  The within-run CIs are untouched: the slow drift moves
 * every configuration of a scene alike and cancels inside the run.
 *
 * Pure: no GL, no clock; precision_print writes to the FILE it is given.
 *
 *   precision_apply(&run, seed);
 *   store_precision_put(st, run.id, &run);
 *   precision_print(&run, target_ci, stderr);
 */
#ifndef RUN_PRECISION_H
#define RUN_PRECISION_H

#include <stdint.h>
#include <stdio.h>

#include "core/dm_results.h"

/* Fills run->precision (one entry per scene with timed samples, replacing
 * any) and the corrected figures of the timed counters of run's
 * configurations (every earlier correction is cleared first: `merge`
 * computes it again over the union of its shards' rounds).  seed: of the bootstrap.  Returns the number of scenes
 * corrected. */
size_t precision_apply(dm_run_result *run, uint64_t seed);

/* Lines for the terminal: WallTime configurations within target_ci raw
 * and with the drift removed, the noise floor and the smallest difference
 * the run resolves, how far the machine moved and which predicted it
 * better (the rounds' common mode or the calibration workload), how well
 * the corrected scenes know their median machine speed and the
 * configurations within target_ci by the between-run CI, and each scene
 * left raw with the reason. */
void precision_print(const dm_run_result *run, double target_ci, FILE *f);

#endif
