/* cmd_slurm.c — `dmbench slurm`: a sweep as a Slurm job array.
 *
 *   dmbench slurm [SWEEP] --shards N [--out DIR] [--partition P] [--time T]
 *                 [--print] [--resume] [-- SBATCH_ARG...]
 *   dmbench slurm --collect DIR --shards N --job ID     (the merge job runs this)
 *
 * Submission writes the job scripts under DIR/slurm (run/slurm.h), submits the array
 * (one task per shard) and a merge job that depends on it with afterany:
 * with afterok a failed task would leave the merge job pending forever and
 * nobody would report the failure.  The merge job (--collect) names every
 * shard that is not complete with Slurm's state and reason, merges the
 * others into DIR/merged and exits 1 if any shard failed.
 */
#include "cli.h"
#include "core/dm_error.h"
#include "run/slurm.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct slurm_args {
    const char *sweep, *out, *partition, *time, *collect, *job;
    int shards, print, resume;
    char **extra;              /* after "--": given to sbatch as they are */
    int n_extra;
} slurm_args;

const cli_option cli_slurm_options[] = {
    { .name = "shards", .kind = CLI_OPT_INT, .offset = offsetof(slurm_args, shards),
      .value_name = "N", .min = 1, .max = 10000, .help = "tasks of the job array, one shard each (required)" },
    { .name = "out", .kind = CLI_OPT_STRING, .offset = offsetof(slurm_args, out), .value_name = "DIR",
      .def = "results/slurm", .help = "shards go to DIR/shards/sK, the merged run to DIR/merged" },
    CLI_STRING("partition", slurm_args, partition, "P", "sbatch --partition"),
    CLI_STRING("time", slurm_args, time, "T", "sbatch --time of each task"),
    CLI_BOOL("print", slurm_args, print, "write the job scripts without submitting them"),
    CLI_BOOL("resume", slurm_args, resume, "submit only the shards that are missing or incomplete"),
    CLI_STRING("collect", slurm_args, collect, "DIR", "(the merge job) merge the shards under DIR"),
    CLI_STRING("job", slurm_args, job, "ID", "(the merge job, with --collect) the array's job id"),
    CLI_OPT_END
};

/* Parses slurm's options (self: its row of the command table) into a: options, then [SWEEP], then "--" and the
 * arguments for sbatch as they are.  Returns -1 to go on or an exit code. */
static int slurm__args(const cli_command *self, int argc, char **argv, slurm_args *a)
{
    int d = 1;
    while (d < argc && strcmp(argv[d], "--") != 0)
        d++;
    if (d < argc) {             /* everything after "--" goes to sbatch untouched */
        a->extra = argv + d + 1;
        a->n_extra = argc - d - 1;
    }
    int n = d, rc = cli_parse(self, d, argv, a, &n);
    if (rc >= 0)
        return rc;
    if (n > 1)
        return cli_usage_error("slurm: only one sweep file may be given ('%s' and '%s')", argv[0], argv[1]);
    a->sweep = n ? argv[0] : NULL;
    if (!a->shards)
        return cli_usage_error("usage: dmbench slurm [SWEEP] --shards N [--out DIR] [--partition P] "
                               "[--time T] [--print] [--resume] [-- SBATCH_ARG...]");
    if (a->collect && !a->job)
        return cli_usage_error("slurm: --collect DIR needs --job ID (the array's job id)");
    return -1;
}

/* Loads the sweep and counts its configurations; refuses more shards than
 * configurations.  Fills name (caller frees).  -1 to go on or exit code. */
static int slurm__plan(const slurm_args *a, char **name)
{
    sweep s;
    plan p = {0};
    dm_str err = {0};
    int rc = a->sweep ? sweep_load(a->sweep, &s, &err)
                      : sweep_parse(sweep_default_text(0), "<default>", &s, &err);
    if (rc != 0) {
        rc = cli_usage_error("%s", dm_str_get(&err));
        dm_str_free(&err);
        return rc;
    }
    rc = plan_build(&s, NULL, &p, &err) != 0 ? cli_usage_error("%s", dm_str_get(&err)) : -1;
    if (rc < 0 && (size_t)a->shards > p.n_configs)
        rc = cli_usage_error("slurm: --shards %d: %s plans only %zu configurations; use at most "
                              "%zu shards", a->shards, s.path, p.n_configs, p.n_configs);
    if (rc < 0)
        *name = dm_xstrdup(s.name ? s.name : "sweep");
    plan_free(&p);
    sweep_free(&s);
    dm_str_free(&err);
    return rc;
}

/* The shards to submit, as sbatch's --array list ("1-4" or "2,4"), or
 * NULL when every shard is complete.  Without --resume, refuses a DIR that
 * already holds shard results.  -1 to go on or an exit code. */
static int slurm__pending(const slurm_args *a, const char *dir, char **list)
{
    dm_str s = {0};
    int found = 0, pending = 0;
    for (int k = 1; k <= a->shards; k++) {
        char *store_path = dm_xasprintf("%s/shards/s%d/dmbench.sqlite", dir, k);
        dm_str why = {0};
        found |= dm_file_exists(store_path);
        if (!a->resume || !slurm_shard_done(dir, k, a->shards, NULL, &why)) {
            dm_str_printf(&s, "%s%d", pending++ ? "," : "", k);
            if (a->resume && !a->print)
                fprintf(stderr, "dmbench: slurm: shard %d/%d to run: %s\n", k, a->shards, dm_str_get(&why));
        }
        dm_str_free(&why);
        free(store_path);
    }
    if (found && !a->resume) {
        dm_str_free(&s);
        return cli_usage_error("slurm: %s already holds shard results; continue them with "
                                "--resume, or give another --out", dir);
    }
    *list = pending == a->shards ? dm_xasprintf("1-%d", a->shards) : pending ? dm_str_take(&s) : NULL;
    dm_str_free(&s);
    return -1;
}

/* Runs sbatch --parsable with the common options and args; the job id into
 * *id (caller frees).  On rejection prints Slurm's message and returns 1. */
static int slurm__sbatch(const slurm_args *a, const char *sbatch, char **args, int n_args, char **id)
{
    char **argv = dm_xcalloc((size_t)(a->n_extra + n_args + 8), sizeof *argv);
    int n = 0;
    argv[n++] = (char *)sbatch;
    argv[n++] = "--parsable";
    char *part = a->partition ? dm_xasprintf("--partition=%s", a->partition) : NULL;
    char *time = a->time ? dm_xasprintf("--time=%s", a->time) : NULL;
    if (part) argv[n++] = part;
    if (time) argv[n++] = time;
    for (int i = 0; i < a->n_extra; i++)
        argv[n++] = a->extra[i];
    for (int i = 0; i < n_args; i++)
        argv[n++] = args[i];
    dm_str out = {0}, err = {0};
    int st = slurm_exec(argv, &out, &err), rc = 0;
    long job = out.len ? strtol(dm_str_get(&out), NULL, 10) : 0;
    if (st != 0 || job <= 0) {
        fprintf(stderr, "dmbench: error: slurm: sbatch refused the job (exit %d): %s%s", st,
                err.len ? dm_str_get(&err) : dm_str_get(&out), err.len || out.len ? "" : "(no message)\n");
        rc = 1;
    } else {
        *id = dm_xasprintf("%ld", job);
    }
    dm_str_free(&out);
    dm_str_free(&err);
    free(part);
    free(time);
    free(argv);
    return rc;
}

/* Cancels a job that was submitted before a later submission failed. */
static void slurm__cancel(const char *id)
{
    char *scancel = NULL;
    if (slurm_which("scancel", &scancel) != 0)
        return;
    char *argv[] = { scancel, (char *)id, NULL };
    dm_str o = {0}, e = {0};
    slurm_exec(argv, &o, &e);
    dm_str_free(&o);
    dm_str_free(&e);
    free(scancel);
}

/* Submits the array (when list) and the merge job; prints the job ids. */
static int slurm__submit(const slurm_args *a, const char *dir, const char *list, const char *sbatch)
{
    char *array_script = dm_xasprintf("%s/slurm/shards.sbatch", dir);
    char *merge_script = dm_xasprintf("%s/slurm/merge.sbatch", dir);
    char *array_opt = list ? dm_xasprintf("--array=%s", list) : NULL, *array_id = NULL, *merge_id = NULL;
    char *dep = NULL;
    char *args1[] = { array_opt, array_script };
    int rc = list ? slurm__sbatch(a, sbatch, args1, 2, &array_id) : 0;
    if (rc == 0) {
        dep = array_id ? dm_xasprintf("--dependency=afterany:%s", array_id) : NULL;
        char *args2[] = { dep ? dep : merge_script, dep ? merge_script : (char *)"0",
                          dep ? array_id : NULL };
        rc = slurm__sbatch(a, sbatch, args2, dep ? 3 : 2, &merge_id);
        if (rc != 0 && array_id)
            slurm__cancel(array_id);
    }
    if (rc == 0) {
        if (array_id)
            printf("array job: %s (shards %s of %d)\n", array_id, list, a->shards);
        else
            printf("every shard is complete: only the merge job was submitted\n");
        printf("merge job: %s\nlogs: %s/slurm/logs/\nreport when done: %s/merged/latest/report.html\n",
               merge_id, dir, dir);
    }
    free(array_script);
    free(merge_script);
    free(array_opt);
    free(array_id);
    free(merge_id);
    free(dep);
    return rc;
}

/* Absolute paths of the binary, the sweep and DIR (made). -1 or exit code. */
static int slurm__paths(const slurm_args *a, slurm_desc *d, char *bin, char *sweep, char *dir)
{
    char *out = dm_xstrdup(a->out);
    dm_str err = {0};
    int rc = -1;
    if (!realpath("/proc/self/exe", bin))
        rc = cli_usage_error("slurm: cannot find the dmbench binary (/proc/self/exe)");
    else if (a->sweep && !realpath(a->sweep, sweep))
        rc = cli_usage_error("slurm: %s: no such sweep file", a->sweep);
    else if (dm_mkdirs(out) != 0 || !realpath(out, dir) || access(dir, W_OK) != 0)
        rc = cli_usage_error("slurm: %s: cannot create or write the output directory", out);
    else if (slurm_check_dir(dir, &err) != 0)
        rc = cli_usage_error("slurm: --out: %s", dm_str_get(&err));
    dm_str_free(&err);
    d->dmbench = bin;
    d->sweep = a->sweep ? sweep : NULL;
    d->dir = dir;
    d->shards = a->shards;
    free(out);
    return rc;
}

/* Prints the scripts written and the commands that submit them, for
 * copying into a shell: every path is one single-quoted word, so a path
 * with blanks, ';' or '$(...)' is passed as it is and runs nothing. */
static void slurm__print_submit(const char *dir, const char *list)
{
    char *array = dm_xasprintf("%s/slurm/shards.sbatch", dir);
    char *merge = dm_xasprintf("%s/slurm/merge.sbatch", dir);
    dm_str s = {0};
    dm_str_printf(&s, "%s\n%s\nsubmit with: ", array, merge);
    if (list) {
        dm_str_printf(&s, "sbatch --array=%s ", list);
        slurm_shell_quote(&s, array);
        dm_str_cat(&s, ", then sbatch --dependency=afterany:<array job id> ");
    } else {   /* every shard is complete: only the merge job is left */
        dm_str_cat(&s, "sbatch ");
    }
    slurm_shell_quote(&s, merge);
    dm_str_cat(&s, list ? " <array job id>\n" : " 0\n");
    char *buf = NULL;
    fputs(dm_term_safe(dm_str_get(&s), &buf), stdout);
    free(buf);
    dm_str_free(&s);
    free(array);
    free(merge);
}

static int slurm__main(const slurm_args *a)
{
    char *name = NULL, *sbatch = NULL, *list = NULL;
    char bin[PATH_MAX], sweep[PATH_MAX], dir[PATH_MAX];
    slurm_desc d = {0};
    dm_str err = {0};
    int rc = slurm__plan(a, &name);
    if (rc < 0 && !a->print && slurm_which("sbatch", &sbatch) != 0)
        rc = cli_usage_error("slurm: sbatch not found on PATH: install Slurm's client commands "
                              "(Debian/Ubuntu package slurm-client, or slurm-wlm for a whole "
                              "node), or use --print to only write the job scripts");
    rc = rc < 0 ? slurm__paths(a, &d, bin, sweep, dir) : rc;
    d.name = name;
    rc = rc < 0 ? slurm__pending(a, dir, &list) : rc;
    if (rc < 0 && slurm_write_scripts(&d, &err) != 0)
        rc = cli_usage_error("slurm: %s", dm_str_get(&err));
    if (rc < 0 && a->print) {
        slurm__print_submit(dir, list);
        rc = 0;
    } else if (rc < 0) {
        rc = slurm__submit(a, dir, list, sbatch);
        if (rc != 0)
            slurm_remove_scripts(dir);   /* nothing half-written is left behind */
    }
    free(name);
    free(sbatch);
    free(list);
    dm_str_free(&err);
    return rc;
}

/* The merge job: reports shards that are not complete, merges the rest. */
static int slurm__collect(const slurm_args *a)
{
    char **argv = dm_xcalloc((size_t)a->shards + 4, sizeof *argv);
    int argc = 0, failed = 0;
    argv[argc++] = "merge";
    argv[argc++] = dm_xasprintf("%s/merged", a->collect);
    for (int k = 1; k <= a->shards; k++) {
        char *run_dir = NULL;
        dm_str why = {0}, state = {0};
        if (slurm_shard_done(a->collect, k, a->shards, &run_dir, &why)) {
            argv[argc++] = run_dir;
        } else {
            slurm_task_state(a->job, k, &state);
            fprintf(stderr, "dmbench: slurm: shard %d/%d failed: %s; Slurm: %s; log: "
                    "%s/slurm/logs/shard-%d.out\n", k, a->shards, dm_str_get(&why),
                    dm_str_get(&state), a->collect, k);
            failed++;
        }
        dm_str_free(&why);
        dm_str_free(&state);
    }
    int rc = 1;
    if (failed < a->shards)
        rc = cli_merge_dirs(argv[1], argv + 2, argc - 2, failed > 0);
    if (failed)
        fprintf(stderr, "dmbench: slurm: %d of %d shards failed%s; re-submit them with the same "
                "dmbench slurm command plus --resume\n", failed, a->shards,
                failed < a->shards ? " (merged the others)" : "");
    for (int i = 1; i < argc; i++)
        free(argv[i]);
    free(argv);
    return failed ? 1 : rc;
}

int cli_slurm(const cli_command *self, int argc, char **argv)
{
    slurm_args a = {0};
    int rc = slurm__args(self, argc, argv, &a);
    if (rc >= 0)
        return rc;
    return a.collect ? slurm__collect(&a) : slurm__main(&a);
}
