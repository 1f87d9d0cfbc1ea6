/* slurm.c — the scripts and commands of slurm.h. */
#include "run/slurm.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "store/store.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

void slurm_shell_quote(dm_str *out, const char *s)
{
    dm_str_cat(out, "'");
    for (; *s; s++)
        dm_str_cat(out, *s == '\'' ? "'\\''" : (char[]){ *s, 0 });
    dm_str_cat(out, "'");
}

/* Appends a path for an #SBATCH directive: sbatch splits those lines at
 * blanks outside quotes, ends them at an unquoted '#', and expands '%' in
 * file names, so the path goes in double quotes with '"' and '\\' escaped
 * and '%' doubled.  (Line breaks cannot be written; slurm_check_dir refuses
 * them.) */
static void slurm__directive_path(dm_str *out, const char *s)
{
    dm_str_cat(out, "\"");
    for (; *s; s++)
        dm_str_cat(out, *s == '"' ? "\\\"" : *s == '\\' ? "\\\\" : *s == '%' ? "%%"
                                                                    : (char[]){ *s, 0 });
    dm_str_cat(out, "\"");
}

/* Appends a job name made of the sweep name's letters, digits, '.', '_' and
 * '-' (anything else, markup and blanks included, becomes '_'), at most 64
 * bytes: squeue, sacct and mail show it unescaped. */
static void slurm__job_name(dm_str *out, const char *name)
{
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)name; *p && n < 64; p++, n++) {
        int ok = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
                 (*p >= '0' && *p <= '9') || *p == '.' || *p == '_' || *p == '-';
        dm_str_cat(out, ok ? (char[]){ (char)*p, 0 } : "_");
    }
}

int slurm_check_dir(const char *dir, dm_str *err)
{
    for (const unsigned char *p = (const unsigned char *)dir; *p; p++)
        if (*p < 0x20 || *p == 0x7f) {
            dm_str_cat(err, "the output directory's path holds a line break or another control "
                            "byte, which a #SBATCH line cannot carry; give another --out");
            return DM_ERR_ARG;
        }
    return 0;
}

static int slurm__save(const char *path, const dm_str *text, dm_str *err)
{
    int rc = dm_write_file(path, dm_str_get(text), text->len);
    if (rc == 0 && chmod(path, 0755) != 0)
        rc = DM_ERR_IO;
    if (rc)
        dm_str_printf(err, "%s: cannot write the job script: %s", path, strerror(errno));
    return rc;
}

/* The array script: task K runs shard K/N into DIR/shards/sK, continuing
 * (--resume) a run an earlier attempt left in that store. */
static void slurm__array_script(const slurm_desc *d, const char *name, dm_str *s)
{
    dm_str_printf(s, "#!/bin/bash\n# Written by dmbench slurm: task K runs shard K/%d of ",
                  d->shards);
    if (d->sweep)   /* a comment line: a line break in the path would end it */
        for (const unsigned char *p = (const unsigned char *)d->sweep; *p; p++)
            dm_str_cat(s, *p < 0x20 || *p == 0x7f ? "?" : (char[]){ (char)*p, 0 });
    else
        dm_str_cat(s, "the default sweep");
    dm_str_cat(s, ".\n#SBATCH --job-name=dmbench-");
    slurm__job_name(s, name);
    dm_str_cat(s, "\n#SBATCH --output=");
    slurm__directive_path(s, d->dir);
    dm_str_cat(s, "/slurm/logs/shard-%a.out\n#SBATCH --cpus-per-task=1\nset -euo pipefail\n"
                  "k=${SLURM_ARRAY_TASK_ID:?run this script with sbatch --array}\nout=");
    slurm_shell_quote(s, d->dir);
    dm_str_cat(s, "/shards/s$k\nresume=()\n"
                  "if [ -s \"$out/dmbench.sqlite\" ]; then resume=(--resume); fi\nexec ");
    slurm_shell_quote(s, d->dmbench);
    dm_str_cat(s, " run ");
    if (d->sweep) {
        slurm_shell_quote(s, d->sweep);
        dm_str_cat(s, " ");
    }
    dm_str_printf(s, "--shard \"$k/%d\" --out \"$out\" --quiet ${resume[@]+\"${resume[@]}\"}\n",
                  d->shards);
}

/* The merge job: reports failed shards with Slurm's reason, then merges. */
static void slurm__merge_script(const slurm_desc *d, const char *name, dm_str *s)
{
    dm_str_cat(s, "#!/bin/bash\n# Written by dmbench slurm: after the array (any outcome), "
                  "reports failed shards and merges the others.\n#SBATCH --job-name=dmbench-");
    slurm__job_name(s, name);
    dm_str_cat(s, "-merge\n#SBATCH --output=");
    slurm__directive_path(s, d->dir);
    dm_str_cat(s, "/slurm/logs/merge.out\n#SBATCH --cpus-per-task=1\nexec ");
    slurm_shell_quote(s, d->dmbench);
    dm_str_cat(s, " slurm --collect ");
    slurm_shell_quote(s, d->dir);
    dm_str_printf(s, " --shards %d --job \"${1:?the array job id}\"\n", d->shards);
}

int slurm_write_scripts(const slurm_desc *d, dm_str *err)
{
    char *logs = dm_xasprintf("%s/slurm/logs", d->dir);
    char *array = dm_xasprintf("%s/slurm/shards.sbatch", d->dir);
    char *merge = dm_xasprintf("%s/slurm/merge.sbatch", d->dir);
    dm_str a = {0}, m = {0};
    const char *name = d->name ? d->name : "sweep";
    slurm__array_script(d, name, &a);
    slurm__merge_script(d, name, &m);
    int rc = 0;
    if (dm_mkdirs(logs) != 0) {
        dm_str_printf(err, "%s: cannot create the directory", logs);
        rc = DM_ERR_IO;
    }
    rc = rc ? rc : slurm__save(array, &a, err);
    rc = rc ? rc : slurm__save(merge, &m, err);
    dm_str_free(&a);
    dm_str_free(&m);
    free(logs);
    free(array);
    free(merge);
    return rc;
}

void slurm_remove_scripts(const char *dir)
{
    static const char *const files[] = { "slurm/shards.sbatch", "slurm/merge.sbatch" };
    static const char *const dirs[] = { "slurm/logs", "slurm", "" };
    for (size_t i = 0; i < 2; i++) {
        char *p = dm_xasprintf("%s/%s", dir, files[i]);
        unlink(p);
        free(p);
    }
    for (size_t i = 0; i < 3; i++) {
        char *p = dm_xasprintf("%s/%s", dir, dirs[i]);
        rmdir(p);   /* only when empty */
        free(p);
    }
}

/* Loads the newest run of a shard's store; 0 or a reason in why. */
static int slurm__shard_run(const char *root, dm_run_result *run, char **id, dm_str *why)
{
    char *store_path = dm_xasprintf("%s/dmbench.sqlite", root);
    store *st = NULL;
    int rc = -1;
    if (!dm_file_exists(store_path))
        dm_str_cat(why, "no results (the task did not start, or failed before its first "
                        "configuration)");
    else if (store_open(store_path, &st, NULL) != 0 || store_latest_run(st, NULL, id) != 0 ||
             store_run_load(st, *id, run) != 0)
        dm_str_printf(why, "no readable run in %s", store_path);
    else
        rc = 0;
    store_close(st);
    free(store_path);
    return rc;
}

int slurm_shard_done(const char *dir, int k, int n, char **run_dir, dm_str *why)
{
    char *root = dm_xasprintf("%s/shards/s%d", dir, k), *id = NULL;
    dm_run_result run = {0};
    int done = 0;
    if (slurm__shard_run(root, &run, &id, why) == 0) {
        const char *shard = dm_kv_get(run.environment, run.n_environment, "shard");
        const char *planned = dm_kv_get(run.environment, run.n_environment, "shard_configs");
        char want[32];
        snprintf(want, sizeof want, "%d/%d", k, n);
        if (!shard || strcmp(shard, want) != 0)
            dm_str_printf(why, "%s/%s measures shard %s, not %s", root, id, shard ? shard : "none", want);
        else if (!run.finished || !planned || strtol(planned, NULL, 10) != (long)run.n_configs)
            dm_str_printf(why, "%zu of %s configurations measured%s", run.n_configs,
                          planned ? planned : "?", run.finished ? "" : ", the run did not finish");
        else
            done = 1;
        if (done && run_dir)
            *run_dir = dm_xasprintf("%s/%s", root, id);
    }
    dm_run_free(&run);
    free(id);
    free(root);
    return done;
}

int slurm_which(const char *prog, char **path)
{
    const char *env = getenv("PATH");
    char *copy = dm_xstrdup(env ? env : "/usr/bin:/bin"), *save = NULL;
    int rc = DM_ERR_NOTFOUND;
    for (char *d = strtok_r(copy, ":", &save); d && rc; d = strtok_r(NULL, ":", &save)) {
        char *p = dm_xasprintf("%s/%s", *d ? d : ".", prog);
        if (access(p, X_OK) == 0) {
            *path = p;
            rc = 0;
        } else {
            free(p);
        }
    }
    free(copy);
    return rc;
}

/* Reads all of fd into out and closes it. */
static void slurm__drain(int fd, dm_str *out)
{
    char buf[4096];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
        if (n > 0)
            dm_str_catn(out, buf, (size_t)n);
    close(fd);
}

int slurm_exec(char *const *argv, dm_str *out, dm_str *err_out)
{
    int po[2], pe[2];
    if (pipe(po) != 0 || pipe(pe) != 0) {
        dm_str_printf(err_out, "cannot run %s: %s", argv[0], strerror(errno));
        return -1;
    }
    pid_t pid = dm_proc_fork();
    if (pid == 0) {
        dup2(po[1], 1);
        dup2(pe[1], 2);
        close(po[0]);
        close(pe[0]);
        execv(argv[0], argv);
        fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    close(po[1]);
    close(pe[1]);
    if (pid < 0) {
        close(po[0]);
        close(pe[0]);
        dm_str_printf(err_out, "cannot run %s: %s", argv[0], strerror(errno));
        return -1;
    }
    slurm__drain(po[0], out);   /* Slurm's commands print little: no deadlock on pe */
    slurm__drain(pe[0], err_out);
    int status = 0;
    if (dm_proc_wait(pid, &status) < 0) {
        dm_str_printf(err_out, "cannot wait for %s: %s", argv[0], strerror(errno));
        return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Copies the "Name=value" fields named in names from scontrol's one-line
 * record into out. */
static void slurm__fields(const char *record, const char *const *names, size_t n, dm_str *out)
{
    for (size_t i = 0; i < n; i++) {
        char *pat = dm_xasprintf(" %s=", names[i]);
        const char *p = strstr(record, pat);
        if (p) {
            p++;
            dm_str_printf(out, "%s%.*s", out->len ? " " : "", (int)strcspn(p, " \n"), p);
        }
        free(pat);
    }
}

void slurm_task_state(const char *job, int k, dm_str *out)
{
    static const char *const names[] = { "JobState", "Reason", "ExitCode", "NodeList" };
    char *task = dm_xasprintf("%s_%d", job, k), *prog = NULL;
    dm_str o = {0}, e = {0};
    size_t before = out->len;
    if (slurm_which("scontrol", &prog) == 0) {
        char *argv[] = { prog, "show", "job", "-o", task, NULL };
        if (slurm_exec(argv, &o, &e) == 0)
            slurm__fields(dm_str_get(&o), names, 4, out);
        free(prog);
        prog = NULL;
    }
    if (out->len == before && slurm_which("sacct", &prog) == 0) {
        dm_str_free(&o);
        dm_str_free(&e);
        char *argv[] = { prog, "-n", "-X", "-P", "-j", task, "-o", "State,ExitCode,Reason", NULL };
        if (slurm_exec(argv, &o, &e) == 0 && o.len)
            dm_str_printf(out, "sacct: %.*s", (int)strcspn(dm_str_get(&o), "\n"), dm_str_get(&o));
        free(prog);
    }
    if (out->len == before)
        dm_str_printf(out, "Slurm no longer knows task %s", task);
    dm_str_free(&o);
    dm_str_free(&e);
    free(task);
}
