/* env.h — the environment a run was measured in (docs/measurement.md).
 *
 * Collected in the measuring process (it needs a current GL context):
 * renderer, GL/GLSL versions, Mesa and LLVM versions as the driver reports
 * them, LP_NUM_THREADS, CPU model and count, load average, harness git
 * revision.  The fingerprint hashes what must match for two runs to be
 * comparable: renderer (incl. LLVM), GL version string, LP_NUM_THREADS and
 * CPU model and count.
 */
#ifndef RUN_ENV_H
#define RUN_ENV_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

/* llvmpipe's rasteriser threads: LP_NUM_THREADS takes 0 (rasterise on the
 * calling thread) to ENV_LP_MAX_THREADS; Mesa reads other text as 0 and
 * clamps larger numbers, so the value recorded would not be the one used. */
#define ENV_LP_MAX_THREADS 32
/* Checks LP_NUM_THREADS when it is set: 0, or DM_ERR_ARG with a message
 * naming the variable, its value and the valid range appended to err. */
int env_check(dm_str *err);
/* Appends environment key/values to kv.  GL keys are skipped when no
 * context is current (gl = 0). */
void env_collect(dm_kv **kv, size_t *n, int gl);
/* Computes the fingerprint over the keys above and appends "fingerprint". */
void env_fingerprint(dm_kv **kv, size_t *n);
/* Keys the fingerprint covers, NULL-terminated (compare lists differences). */
const char *const *env_fingerprint_keys(void);

#endif
