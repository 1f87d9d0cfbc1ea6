/* export.h — a run's results in the JSON that other benchmark tools read.
 *
 * One reporter interface, one reporter per format (docs/exports.md has an
 * example of each):
 *  - gbench       Google Benchmark JSON ({context, benchmarks[]}), one
 *                 "iteration" entry per timed configuration: real_time =
 *                 median WallTime, cpu_time = median CPUTime (else WallTime),
 *                 time_unit "ns", iterations = timing samples; SSIM, PSNR and
 *                 deterministic counters as user counters.  compare.py
 *                 (libbenchmark-tools) compares two of them.
 *  - bmf          Bencher Metric Format: {name: {latency: {value, lower_value,
 *                 upper_value}, ssim: {value}, psnr-db: {value},
 *                 <counter-kebab>: {value}}}; latency in ns from the median
 *                 and its 95 % CI.
 *  - gab-smaller  github-action-benchmark customSmallerIsBetter: [{name, unit,
 *                 value, range, extra}], the median WallTime in ms and RMSE.
 *  - gab-bigger   customBiggerIsBetter: SSIM and PSNR (dB).
 * The formats read only the report model; benchmark names are its rows'
 * names (report_config_name), e.g. "plane@480x270/pom steps=32"
 * (a metric other than the time gets " (SSIM)" etc. in the gab forms).
 * Failed configurations, configurations without a WallTime and non-finite
 * values (JSON cannot hold them, e.g. PSNR of identical images) are left out.
 */
#ifndef REPORTS_EXPORT_H
#define REPORTS_EXPORT_H

#include "core/dm_results.h"

struct cJSON;
struct report_model;

typedef struct export_format {
    const char *name;        /* --format value */
    const char *what;        /* one line for usage and errors */
    struct cJSON *(*build)(const struct report_model *m);   /* caller deletes */
} export_format;

/* The format called name, or NULL. */
const export_format *export_find(const char *name);
/* All formats, *n of them (for usage and "valid choices"). */
const export_format *export_formats(size_t *n);
/* Writes the run of the report model m (report_model.h: the names, times
 * and fronts the report shows) in format f to path (atomically; "-" or
 * NULL: stdout), pretty printed with a final newline.  0, DM_ERR_NOMEM or
 * DM_ERR_IO. */
int export_write(const struct report_model *m, const export_format *f, const char *path);

#endif
