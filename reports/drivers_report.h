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

/* Writes DIR/drivers.md and DIR/drivers.json.  0, or DM_ERR_IO /
 * DM_ERR_DISK (the disk refused the write) with the path and why in err. */
int drivers_report_write(const drivers_side *sides, size_t n, const char *dir, dm_str *err);

#endif
