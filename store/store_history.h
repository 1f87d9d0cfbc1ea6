/* store_history.h — one configuration across runs (`dmbench history`, the
 * report's trend lines).
 *
 * A configuration is the same across runs when its key is (the hash of the
 * parameters it reads); timings are comparable only on the same machine, so
 * a history is restricted to runs whose environment "fingerprint" matches.
 */
#ifndef STORE_STORE_HISTORY_H
#define STORE_STORE_HISTORY_H

#include <stddef.h>

#include "store/store.h"

typedef struct store_history_point {
    char *run_id, *started;
    double median, ci_lo, ci_hi;   /* WallTime per frame, ns */
    double *samples;               /* WallTime samples (ns), n_samples of them */
    size_t n_samples;
    double instructions;           /* "Instructions" counter (value or median); NaN when absent */
} store_history_point;

/* Every ok measurement of configuration key that has a WallTime, in runs
 * whose environment fingerprint equals fingerprint (NULL: any), oldest first
 * (by started, then insertion).  *out is malloc'd (NULL when *n is 0); free
 * with store_history_free.  0 or DM_ERR_STORE. */
int store_history(store *s, const char *key, const char *fingerprint,
                  store_history_point **out, size_t *n);
void store_history_free(store_history_point *p, size_t n);

/* The environment "fingerprint" of run_id into *fp (caller frees; NULL when
 * the run has none).  0, DM_ERR_NOTFOUND or DM_ERR_STORE. */
int store_run_fingerprint(store *s, const char *run_id, char **fp);

#endif
