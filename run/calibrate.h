/* calibrate.h — the run's calibration workload: a fixed CPU-bound kernel
 * and a fixed draw, timed at the start and at the end of every run, so
 * that `dmbench compare` can tell a slower machine from slower code
 * (docs/ci-gating.md, "The calibration workload").
 *
 * Both pieces of work are the same in every dmbench build and on every
 * sweep: the kernel is 2^22 rounds of an integer and floating-point
 * recurrence, the draw one full-screen triangle of a fixed shader into a
 * 256x256 framebuffer, finished.  Each is timed CALIBRATE_REPS times after
 * CALIBRATE_WARMUP untimed repetitions; the shortest is kept (noise only
 * adds time). */
#ifndef RUN_CALIBRATE_H
#define RUN_CALIBRATE_H

#include "core/dm_util.h"

#define CALIBRATE_REPS 9
#define CALIBRATE_WARMUP 2

typedef struct calibrate_result {
    double cpu_ns;    /* shortest time of the CPU kernel; NaN when not measured */
    double draw_ns;   /* shortest time of the draw; NaN without a GL context */
} calibrate_result;

/* Times the CPU kernel, and the draw when a GL context is current
 * (gl_current != 0).  Never fails: what cannot be timed is NaN. */
void calibrate_measure(int gl_current, calibrate_result *out);

/* One short run of the CPU kernel (2^20 rounds, a quarter of the
 * workload's), timed (ns): the machine's speed at that moment, not its
 * best (no repetition, no minimum).  The measuring process takes one
 * before and one after every round of timing samples (run/measure.c), so
 * the drift of a run can be predicted from it; its times are compared with
 * each other within a run only. */
double calibrate_cpu_once(void);

/* Forks a child that creates a GL context and runs calibrate_measure;
 * waits for it (at most 60 s).  0 with *out set, or DM_ERR_CHILD when the
 * child gave no answer (out then holds NaNs). */
int calibrate_in_child(calibrate_result *out);

/* The environment keys of the run's calibration: "calibration_cpu_ns_start"
 * and the like.  which: "start" or "end"; piece: "cpu" or "draw".  Inline,
 * so gate/ reads the keys without linking the runner. */
static inline const char *calibrate_key(const char *piece, const char *which)
{
    int cpu = piece[0] == 'c', start = which[0] == 's';
    return cpu ? (start ? "calibration_cpu_ns_start" : "calibration_cpu_ns_end")
               : (start ? "calibration_draw_ns_start" : "calibration_draw_ns_end");
}

#endif
