/* report.h — results.json, results.csv, summary.md and report.html for one run.
 *
 * Reads only the in-memory results model (core/dm_results.h); never touches
 * GL or runs anything.  Every string from a sweep file or the environment
 * is HTML-escaped.  Image paths are relative to the run directory and are
 * refused if they would leave it.
 */
#ifndef REPORTS_REPORT_H
#define REPORTS_REPORT_H

#include "core/dm_results.h"

/* Writes all four files into dir.  Returns 0 or DM_ERR_IO (err says which file). */
int report_write_all(const dm_run_result *run, const char *dir, char *err, size_t errlen);
int report_write_json(const dm_run_result *run, const char *path);
int report_write_csv(const dm_run_result *run, const char *path);
int report_write_markdown(const dm_run_result *run, const char *path);
int report_write_html(const dm_run_result *run, const char *dir, const char *path);
/* Reads a results.json back (for compare/merge).  DM_ERR_PARSE with err. */
int report_read_json(const char *path, dm_run_result *out, char *err, size_t errlen);

#endif
