/* published_report.h — the report section "Published figures beside ours"
 * (docs/sweep-files.md, Published figures; docs/reproductions.md).
 *
 * A run whose sweep had a `published:` block has published.json in its
 * directory: the study, table and GPU, the unit, the baseline label and one
 * value per label with the key of the configuration it names.  Absolute
 * figures cannot be compared across 15 years of hardware, so both sides are
 * shown as ratios of frame time to the baseline's (FPS is inverted: a ratio
 * of times), and each row gets a verdict:
 *   - direction agrees: both ratios are above 1.05 (slower than the
 *     baseline), both below 0.95 (faster), or both within [0.95, 1.05];
 *   - size agrees: the two ratios are within a factor of 2 of each other.
 */
#ifndef REPORTS_PUBLISHED_REPORT_H
#define REPORTS_PUBLISHED_REPORT_H

#include "core/dm_results.h"
#include "core/dm_util.h"

/* Band of "no difference" around a ratio of 1, and the size tolerance. */
#define REPORT_PUB_SAME_BAND 0.05
#define REPORT_PUB_SIZE_FACTOR 2.0

/* Ratio of frame times of a published value to the baseline's: value/base
 * for times (seconds, ms), base/value for frame rates (fps). */
double report_pub_time_ratio(int is_fps, double value, double base);
/* -1 faster than the baseline (ratio < 0.95), +1 slower (> 1.05), 0 within. */
int report_pub_direction(double ratio);

typedef struct report_pub_verdict {
    int direction_agrees;
    int size_agrees;
    double factor;           /* max(p/m, m/p) >= 1 */
} report_pub_verdict;
/* Compares a published ratio with a measured one (both > 0). */
report_pub_verdict report_pub_judge(double published_ratio, double measured_ratio);

/* Appends the section for the run directory `dir`, or when dir is NULL the
 * directory of the file `beside` (nothing when it has no published.json, a
 * line saying why when it cannot be read), as Markdown (html = 0) or HTML. */
void report_published_section(dm_str *s, const dm_run_result *run, const char *dir,
                              const char *beside, int html);
/* The same for the file at path, read once, into md (Markdown) and html
 * (either may be NULL): report_model.c keeps both. */
void report_published_sections(const dm_run_result *run, const char *path, dm_str *md,
                               dm_str *html);
/* dir/published.json, or published.json in the directory of the file
 * beside when dir is NULL (malloc'd). */
char *report_published_path(const char *dir, const char *beside);
/* Copies dir/published.json to out/published.json when it exists (a report
 * written elsewhere keeps its section).  0, or report__copy_file's code
 * (DM_ERR_DISK for a disk that refused the write) with the reason in err. */
int report_published_copy(const char *dir, const char *out, char *err, size_t errlen);

#endif
