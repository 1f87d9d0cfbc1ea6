/* slurm.h — a sweep as a Slurm job array: the scripts, submission, and the
 * state of each shard (for `dmbench slurm`; no GL).
 *
 * Layout of an output directory DIR (docs/scale-out.md):
 *   DIR/shards/s<K>/          `dmbench run --shard K/N --out` of task K
 *   DIR/merged/               `dmbench merge` of the shards (report in latest/)
 *   DIR/slurm/shards.sbatch   the array script (task K runs shard K/N)
 *   DIR/slurm/merge.sbatch    the merge job (after the array, in any outcome)
 *   DIR/slurm/logs/           shard-<K>.out, merge.out
 * Whether a shard is done is read from its results store, never from a file
 * of dmbench slurm, so a failed submission leaves nothing --resume could
 * misread.
 */
#ifndef RUN_SLURM_H
#define RUN_SLURM_H

#include "core/dm_util.h"

typedef struct slurm_desc {
    const char *dmbench;       /* absolute path of the binary tasks run (required) */
    const char *sweep;         /* absolute path of the sweep file; NULL = default sweep */
    const char *name;          /* sweep name, for job names (NULL = "sweep") */
    const char *dir;           /* absolute output directory DIR (required) */
    int shards;                /* N >= 1 */
} slurm_desc;

/* Appends s as one single-quoted shell word (for scripts and for lines
 * printed to be copied into a shell). */
void slurm_shell_quote(dm_str *out, const char *s);
/* 0 when dir can be written into #SBATCH lines (the scripts quote blanks,
 * quotes, '#' and '%'); DM_ERR_ARG with the reason in err when it holds a
 * line break or another control byte. */
int slurm_check_dir(const char *dir, dm_str *err);
/* Writes DIR/slurm/shards.sbatch and merge.sbatch (atomically, mode 0755)
 * and makes DIR/slurm/logs.  The array range is not in the script: it is
 * given to sbatch (--array), so --resume can submit only some shards.
 * Returns 0 or DM_ERR_IO with the path in err. */
int slurm_write_scripts(const slurm_desc *d, dm_str *err);
/* Removes what slurm_write_scripts wrote, and the directories it made
 * when they are empty (after a rejected submission). */
void slurm_remove_scripts(const char *dir);
/* Whether shard k of n in DIR is complete: 1 (and *run_dir, caller frees)
 * when its newest run finished with every configuration the shard planned,
 * 0 when not (why says what is missing), never an error. */
int slurm_shard_done(const char *dir, int k, int n, char **run_dir, dm_str *why);
/* Full path of an executable on PATH into *path (caller frees), or
 * DM_ERR_NOTFOUND. */
int slurm_which(const char *prog, char **path);
/* Runs argv (argv[0] a path) and captures its stdout and stderr.  Returns
 * its exit status, 128+signal, or -1 (err_out says why) if it did not run. */
int slurm_exec(char *const *argv, dm_str *out, dm_str *err_out);
/* Appends Slurm's view of array task job_k ("JobState=FAILED
 * Reason=NonZeroExitCode ExitCode=2:0"), from scontrol, else sacct, else
 * "Slurm no longer knows it". */
void slurm_task_state(const char *job, int k, dm_str *out);

#endif
