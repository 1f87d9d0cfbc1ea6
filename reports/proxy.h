/* proxy.h — is Instructions a good proxy for frame time on this machine?
 *
 * Across a run's configurations that have both WallTime (median, from the
 * timing child) and Instructions (per frame, from the Instructions pass
 * under Valgrind), fits WallTime ≈ a + b·Instructions by ordinary least
 * squares and reports R², b (ns per instruction) and the configurations
 * that stray most from the line (relative residual), e.g. memory-bound
 * texture fetches that cost more time than their instructions say.
 * Also names which pass each of the run's counters came from.
 */
#ifndef REPORTS_PROXY_H
#define REPORTS_PROXY_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

#define REPORT_PROXY_STRAYS 3

typedef struct report_proxy_stray {
    const char *key;          /* points into the run */
    char label[160];          /* "technique=pom mesh=plane ..." */
    double wall_ns, predicted_ns;
    double residual_rel;      /* (wall - predicted) / predicted */
} report_proxy_stray;

typedef struct report_proxy {
    size_t n;                 /* configurations with both counters */
    double a_ns;              /* intercept */
    double ns_per_instruction;   /* slope b */
    double r2;
    report_proxy_stray strays[REPORT_PROXY_STRAYS];
    size_t n_strays;          /* largest |residual_rel| first */
} report_proxy;

/* Fits the proxy over run's ok configurations.  Returns 0 and *out;
 * DM_ERR_UNAVAILABLE when fewer than 3 configurations have both counters
 * or the instruction counts do not vary (no line to fit). */
int report_proxy_fit(const dm_run_result *run, report_proxy *out);

/* Which pass a counter of a run came from: "instructions" (own child under
 * Valgrind, not timed), "timing" (timed samples in the normal child),
 * "statistics" (one frame in the normal child, queries or caller-fed) or
 * "derived" (formula over the others). */
const char *report_proxy_pass(const dm_counter_result *c);

/* Appends one line per pass present in run: "pass: A, B, C". */
void report_proxy_passes_text(const dm_run_result *run, const char *sep, dm_str *out);

#endif
