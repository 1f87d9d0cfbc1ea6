/* inputs.h — the user's map and mesh files a run reads, held to one version.
 *
 * A sweep may name files of the user's: a mesh (`mesh: file:PATH`) and the
 * maps of a material (`maps: height=PATH;normal=PATH;albedo=PATH`).  Every
 * process of a run reads them again (each measuring child prepares its
 * scenes from the files; each counting child under Valgrind too), so a file
 * edited while the run goes would be measured in two versions under one
 * configuration key.  One run measures one version of each file:
 *
 * - inputs_collect (the runner, after planning) hashes every file the plan
 *   names (FNV-1a of its bytes) and keeps the hash and the file's stat
 *   (device, inode, size, modification and change times).  The registry is
 *   process-wide and is inherited by the forked measuring children.
 * - inputs_check (a measuring child before it commits a configuration; the
 *   runner after the Instructions pass) stats each file; only a file whose
 *   stat changed is hashed again, so the check costs a stat per file unless
 *   something touched it.  A touched file with the same bytes passes.
 * - The run's environment records each file as INPUTS_ENV_PREFIX PATH =
 *   HASH; --resume compares those with the files now (inputs_resume_check).
 *
 * Limit: a file changed and changed back between two checks (same bytes
 * again) is not seen; a run that read the other version in between is not
 * told apart.  Failing the run (exit 2, naming the file) is the caller's.
 */
#ifndef RUN_INPUTS_H
#define RUN_INPUTS_H

#include <stddef.h>
#include <stdint.h>

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "sweep/plan.h"

/* Prefix of the environment entries that record the files of a run. */
#define INPUTS_ENV_PREFIX "user_file."

/* Registers every user map and mesh file the plan's configurations name
 * (once each) with its hash now.  Returns 0, or DM_ERR_ARG with the file and
 * why in err when one cannot be read. */
int inputs_collect(const plan *p, dm_str *err);

size_t inputs_count(void);
const char *inputs_path(size_t i);
uint64_t inputs_hash(size_t i);

/* 0 when every registered file holds the bytes it held when registered;
 * DM_ERR_ARG with "PATH: the ... file changed since the run started (hash
 * H, now H2)" (or cannot be read) in err for the first that does not. */
int inputs_check(dm_str *err);

/* --resume: each INPUTS_ENV_PREFIX entry of the old run's environment must
 * name a file that holds the recorded bytes now.  Returns 0, or DM_ERR_ARG
 * naming the file and the run in err. */
int inputs_resume_check(const dm_kv *env, size_t n_env, const char *run_id, dm_str *err);

/* Pushes the INPUTS_ENV_PREFIX entries of the registered files. */
void inputs_record(dm_kv **env, size_t *n_env);

/* Empties the registry. */
void inputs_clear(void);

#endif
