/* merge.h — uniting shard runs into one run, keeping machines apart.
 *
 * `dmbench merge` loads each shard's run from its store and hands it to
 * merge_add(); the rules live here so they can be tested without files:
 *
 *  - every run must come from the same sweep file (sweep_hash);
 *  - a run recorded as shard K/N (environment "shard", "shard_configs", see
 *    run/runner.c) may appear once: a second shard K/N is refused, as is a
 *    shard of another split (K/M with M != N);
 *  - a configuration key may appear in one run only (no silent "first
 *    wins"): two runs measuring the same key are refused;
 *  - merge_missing() lists the shards 1..N that were not given and those
 *    that are incomplete (fewer configurations than the shard planned, or a
 *    run that never finished);
 *  - runs measured on different machines (environment "fingerprint") are
 *    never pooled: merge_finish() gives each configuration the parameter
 *    "machine" = its fingerprint and appends " @ <fingerprint>" to its scene,
 *    so every per-scene table, Pareto front and chart of the report is per
 *    machine; it records "machine <fingerprint>" entries (CPU, renderer,
 *    shards) in the environment and a run warning that says so;
 *  - the rounds of every run are kept (their scenes tagged like the
 *    configurations'), each scene's precision entries dropped: a
 *    correction of one shard does not describe the union, and the caller
 *    computes it again over the merged rounds (run/precision.h).
 *
 * Errors: DM_ERR_ARG with a message naming the directories and values.
 */
#ifndef STORE_MERGE_H
#define STORE_MERGE_H

#include <stddef.h>

#include "core/dm_results.h"
#include "core/dm_util.h"

typedef struct merge_shard {
    char *dir;                 /* the run directory it came from */
    int k, n;                  /* 0/0: not a shard */
    long planned;              /* configurations the shard planned; -1 = unknown */
    size_t measured;           /* configurations it stored */
    int finished;              /* the run recorded a finish time */
    char *fingerprint;
    char *machine;             /* "<cpus> x <cpu>, <renderer>, LP_NUM_THREADS=<n>" */
} merge_shard;

typedef struct merge_state {
    dm_run_result out;         /* the merged run (environment of the first input) */
    size_t *config_src;        /* input (index) each of out.configs came from */
    size_t *round_src;         /* and each of out.rounds (their scenes are tagged alike) */
    merge_shard *inputs;
    size_t n_inputs;
} merge_state;

/* Moves run (from directory dir) into the merge if it may join; run is
 * released either way.  Returns 0, or DM_ERR_ARG with the reason in err and
 * the merge unchanged. */
int merge_add(merge_state *m, dm_run_result *run, const char *dir, dm_str *err);
/* Appends to out one line per missing or incomplete shard ("shard 3/4:
 * not given", "shard 2/4 (DIR): 3 of 5 configurations, the run did not
 * finish"); returns how many. */
size_t merge_missing(const merge_state *m, dm_str *out);
/* Number of distinct machine fingerprints among the inputs. */
size_t merge_machines(const merge_state *m);
/* Tags configurations by machine when there is more than one (see above)
 * and records which shards were merged.  Call once, after the last add. */
void merge_finish(merge_state *m);
void merge_free(merge_state *m);

#endif
