/* env.h — the environment a run was measured in (docs/measurement.md).
 *
 * Collected in the measuring process (it needs a current GL context):
 * renderer, GL/GLSL versions, Mesa and LLVM versions as the driver reports
 * them, LP_NUM_THREADS, CPU model and count, load average, harness git
 * revision.  The fingerprint hashes what must match for two runs to be
 * comparable: renderer (incl. LLVM), GL version string, LP_NUM_THREADS and
 * CPU model and count.
 */
#ifndef HARNESS_ENV_H
#define HARNESS_ENV_H

#include <stddef.h>
#include "core/dm_results.h"

/* Appends environment key/values to kv.  GL keys are skipped when no
 * context is current (gl = 0). */
void env_collect(dm_kv **kv, size_t *n, int gl);
/* Computes the fingerprint over the keys above and appends "fingerprint". */
void env_fingerprint(dm_kv **kv, size_t *n);
/* Keys the fingerprint covers, NULL-terminated (compare lists differences). */
const char *const *env_fingerprint_keys(void);

#endif
