/* drivers_report.h — one sweep measured on several drivers, side by side
 * (`dmbench drivers`, docs/drivers.md "One sweep on several drivers").
 *
 * The runs are matched by configuration key: the key does not contain the
 * driver, so the same configuration has the same key on every driver.
 * Each driver stays its own machine (its own run, environment and
 * fingerprint); this report only sets them beside each other: per
 * configuration its median WallTime, Instructions and SSIM on each driver,
 * whether the drivers rank the configurations alike (Kendall's tau-b of
 * the times, and of the qualities), and each scene's Pareto front (WallTime
 * against 1 - SSIM) on each driver. */
#ifndef REPORTS_DRIVERS_REPORT_H
#define REPORTS_DRIVERS_REPORT_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

typedef struct drivers_side {
    const char *driver;          /* the driver's name (run/drivers.h) */
    const dm_run_result *run;    /* NULL when the driver did not run */
    const char *why;             /* why not (left out, failed), else NULL */
} drivers_side;

/* Kendall's tau-b of x and y over the n pairs where both are finite (ties
 * counted as tau-b does); NaN with fewer than 2 such pairs or when either
 * side is constant. */
double drivers_kendall_tau(const double *x, const double *y, size_t n);

/* Resamplings of the bootstrap interval of tau in the report. */
#define DRIVERS_TAU_REPS 2000

/* Kendall's tau-b of the finite pairs of x and y (drivers_kendall_tau) and
 * its 95 % percentile bootstrap interval: the pairs resampled with
 * replacement reps times from seed (the same seed, the same interval),
 * *lo and *hi the 2.5th and 97.5th percentiles of the resampled taus that
 * are defined.  lo and hi are NaN when tau is, with fewer than 3 finite
 * pairs, or when fewer than half of the resamplings give a tau. */
double drivers_kendall_tau_ci(const double *x, const double *y, size_t n, size_t reps,
                              uint64_t seed, double *lo, double *hi);

/* Below this the calibration's movement counts as noise in the drift
 * check, however still each run was. */
#define DRIVERS_DRIFT_FLOOR 0.05

/* The drift check between the drivers' runs, from the CPU calibration
 * kernel each run times at its start and its end (start[k], end[k], ns; a
 * pure CPU workload, so any driver's run measures the same machine).  *moved
 * gets the largest run mean over the smallest, minus 1; *noise the largest
 * relative move within a run (|end - start| / mean), at least
 * DRIVERS_DRIFT_FLOOR.  Returns 1 when the machine's speed moved between
 * runs more than within one (moved > noise), 0 when not, -1 (moved and noise
 * NaN) with fewer than 2 runs that have both figures. */
int drivers_drift(const double *start, const double *end, size_t n, double *moved, double *noise);

/* Writes DIR/drivers.md and DIR/drivers.json.  0, or DM_ERR_IO /
 * DM_ERR_DISK (the disk refused the write) with the path and why in err. */
int drivers_report_write(const drivers_side *sides, size_t n, const char *dir, dm_str *err);

#endif
