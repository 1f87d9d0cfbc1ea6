/* store.h — the results store: one SQLite database, the single source of results.
 *
 * The runner commits every finished configuration in its own transaction, so
 * a crash, a kill or a full disk never loses a committed configuration and
 * never leaves a half-written one; `--resume` asks store_config_done();
 * reports reload a whole run with store_run_load(); `dmbench merge` uses
 * store_copy_run().  The store persists and reloads exactly the model of
 * core/dm_results.h (NaN and ±Inf included).  The schema is documented at the
 * top of store_schema.c.
 *
 * Errors: every function returns 0 or a negative DM_ERR_* code.  Every SQLite
 * failure is DM_ERR_STORE, with a message naming the database path and
 * SQLite's own message in store_last_error().  A store handle is used by one
 * thread at a time.
 */
#ifndef STORE_STORE_H
#define STORE_STORE_H

#include <stddef.h>

#include "core/dm_results.h"
#include "core/dm_util.h"

typedef struct store store;

/* Opens or creates the database at path (WAL journal, synchronous=FULL so a
 * committed configuration also survives a power loss, busy_timeout 5 s,
 * foreign keys on) and creates or migrates the schema (PRAGMA user_version).
 * Then checks that every table and column the schema defines is there.
 * Returns 0 and *out, or DM_ERR_IO (the file cannot be opened or created) /
 * DM_ERR_STORE (not a database, newer schema, a table or column missing:
 * "the results store is damaged", any other SQLite failure) with
 * the path and SQLite's message appended to err (err may be NULL); *out is
 * then NULL. */
int store_open(const char *path, store **out, dm_str *err);
/* 0 when a store at path (relative to the working directory) can be opened
 * by SQLite, whose file layer refuses an absolute path, "-journal"
 * appended, longer than its limit (512 bytes with the unix VFS); else
 * DM_ERR_ARG with the length and the limit in err.  For checking an --out
 * before anything is created. */
int store_path_fits(const char *path, dm_str *err);
/* Checks the database's structure (PRAGMA quick_check: every page, index and
 * record readable, O(size) reads, no writes).  0 when intact; DM_ERR_STORE
 * with "damaged" and SQLite's first finding in err (and store_last_error)
 * when not, so nothing writes into a damaged store or reads half a run. */
int store_check(store *s, dm_str *err);
/* Closes the database; NULL is ignored. */
void store_close(store *s);
/* Message of the last failure of s ("" when none). Valid until the next call. */
const char *store_last_error(const store *s);

/* Inserts the run row: id, sweep, started, finished (normally NULL),
 * sweep_hash, environment, timer coverage/verdict, the run warnings present
 * now, and a tag (NULL for none).  Configurations, left-out and fits of run
 * are NOT written (use the calls below).  DM_ERR_EXISTS if the id exists,
 * DM_ERR_ARG if run->id is NULL. */
int store_run_begin(store *s, const dm_run_result *run, const char *tag);
/* Appends one run warning. DM_ERR_NOTFOUND if the run is absent. */
int store_run_warning_put(store *s, const char *run_id, const char *text);
/* Appends one environment entry (key, value) to the run: what is known
 * only at its end, such as the closing calibration.  DM_ERR_NOTFOUND if the
 * run is absent. */
int store_run_env_put(store *s, const char *run_id, const char *key, const char *value);
/* Writes one finished configuration (status, reason, log, params, every
 * counter with all its raw samples, quality, image paths) in ONE transaction.
 * A previous configuration of the same (run, key) is replaced and keeps its
 * position in the run.  On any failure the transaction is rolled back and
 * the store is unchanged.  DM_ERR_NOTFOUND if the run is absent, DM_ERR_ARG
 * if c->key is NULL. */
int store_config_put(store *s, const char *run_id, const dm_config_result *c);
/* Timing samples of one configuration still being measured (a checkpoint). */
typedef struct store_partial {
    const char *key;
    const char *const *counters;     /* n_counters names */
    size_t n_counters;
    double *const *samples;          /* per counter: n_samples values */
    size_t n_samples;
    long sampling_ns;                /* time spent in those samples */
} store_partial;
/* Replaces the checkpoints of n configurations in ONE transaction (the
 * measuring process calls it after every round, so a kill loses at most the
 * round in flight).  store_config_put() of a key deletes its checkpoint. */
int store_partial_put(store *s, const char *run_id, const store_partial *items, size_t n);
/* The checkpointed samples of one counter of a configuration (*v malloc'd,
 * *n values) and the sampling time.  DM_ERR_NOTFOUND when there are none. */
int store_partial_get(store *s, const char *run_id, const char *key, const char *counter,
                      double **v, size_t *n, long *sampling_ns);
/* Appends one round of a scene (r->seq is ignored: the next of that scene
 * is taken), in one transaction. */
int store_round_put(store *s, const char *run_id, const dm_round *r);
/* Writes run->precision (replacing a scene's row) and the corrected
 * figures of every counter with corrected set, in one transaction; the
 * raw figures are not touched. */
int store_precision_put(store *s, const char *run_id, const dm_run_result *run);
/* Appends one left-out configuration (params + reason), in one transaction. */
int store_left_out_put(store *s, const char *run_id, const dm_left_out *l);
/* Writes one fit (params, warnings, predicted/measured, point labels) in one
 * transaction; replaces a fit of the same model and group (the group's pairs
 * in any order), which keeps its position. */
int store_fit_put(store *s, const char *run_id, const dm_fit_result *f);
/* Records the finish time. DM_ERR_NOTFOUND if the run is absent. */
int store_run_finish(store *s, const char *run_id, const char *finished_iso);

/* 1 if a configuration with that key is stored for the run, 0 if not, <0 on
 * error. */
int store_config_done(store *s, const char *run_id, const char *key);
/* Loads the whole run into *out (which the caller later releases with
 * dm_run_free): configurations and left-out in insertion order (a replaced
 * configuration keeps its place), fits in insertion order.  Reads one
 * consistent snapshot.  DM_ERR_NOTFOUND if absent; on any failure *out is
 * zeroed. */
int store_run_load(store *s, const char *run_id, dm_run_result *out);
/* Tag given to store_run_begin (NULL when none) into *tag (caller frees).
 * DM_ERR_NOTFOUND if the run is absent. */
int store_run_tag(store *s, const char *run_id, char **tag);
/* Newest run id (by started, then insertion), only among runs with that tag
 * when tag is not NULL; DM_ERR_NOTFOUND when none.  Caller frees *id. */
int store_latest_run(store *s, const char *tag, char **id);
/* Lists run ids, newest first (same order as store_latest_run).  The caller
 * frees each id and the array (*ids is NULL when *n is 0). */
int store_list_runs(store *s, char ***ids, size_t *n);
/* Copies every row of run run_id of src into dst (for `dmbench merge`), in
 * one transaction of dst.  DM_ERR_NOTFOUND if src lacks the run,
 * DM_ERR_EXISTS if dst already has it; dst is unchanged on failure. */
int store_copy_run(store *dst, store *src, const char *run_id);

/* ---- for tests and diagnostics ------------------------------------------ */
struct sqlite3;
/* The underlying connection (fault injection, integrity checks). */
struct sqlite3 *store__db(store *s);

#endif
