/* compare_paired.c — paired mode of the regression gate: both binaries run
 * the same sweep in alternating rounds (ABBA), fresh processes, and each
 * side's samples are pooled per key (see compare.h). */
#include "gate/compare.h"
#include "models/stats.h"

#include <ftw.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_proc.h"

static int compare__rm_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

/* Runs `binary run SWEEP --out out --seed seed --quiet` in a child process
 * and waits; 0 when it exited 0. */
static int compare__spawn_run(const char *binary, const char *sweep, const char *out, int seed)
{
    char seed_text[16];
    snprintf(seed_text, sizeof seed_text, "%d", seed);
    pid_t pid = dm_proc_fork();
    if (pid < 0)
        return DM_ERR_CHILD;
    if (pid == 0) {
        char *argv[] = { (char *)binary, "run", (char *)sweep, "--out", (char *)out, "--seed",
                         seed_text, "--quiet", NULL };
        execv(binary, argv);
        fprintf(stderr, "dmbench: error: cannot execute %s\n", binary);
        _exit(127);
    }
    int status = 0;
    if (dm_proc_wait(pid, &status) < 0)
        return DM_ERR_CHILD;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : DM_ERR_CHILD;
}

/* Appends the samples of every sampled counter of c to the same counter of
 * into; a deterministic counter with a different value is a warning. */
static void compare__pool_config(dm_config_result *into, const dm_config_result *c,
                                 dm_run_result *run, int round)
{
    if (!c->ok && into->ok) {
        into->ok = 0;
        into->reason = dm_xasprintf("round %d: %s", round + 1, c->reason ? c->reason : "failed");
    }
    for (size_t i = 0; i < c->n_counters; i++) {
        const dm_counter_result *src = &c->counters[i];
        dm_counter_result *dst = (dm_counter_result *)dm_config_counter(into, src->name);
        if (!dst || !src->available || !dst->available)
            continue;
        if (src->n_samples && dst->has_samples) {
            dst->samples = dm_xrealloc(dst->samples, (dst->n_samples + src->n_samples) * sizeof(double));
            memcpy(dst->samples + dst->n_samples, src->samples, src->n_samples * sizeof(double));
            dst->n_samples += src->n_samples;
        } else if (src->deterministic && src->value != dst->value) {
            DM_VEC_PUSH(run->warnings, run->n_warnings,
                dm_xasprintf("%s of %s differs between rounds of one binary: %.17g vs %.17g",
                             src->name, c->key, dst->value, src->value));
        }
    }
}

/* Reduces every sampled counter of a run to one value, its minimum.  In
 * paired mode the unit of replication is the run: samples of one process
 * share its slow or fast periods, so pooling raw samples across runs
 * overstates the evidence (same-binary comparisons came out REGRESSION
 * twice in nine); the runs' summaries are independent.  The summary is the
 * minimum, chosen by evidence: noise on a shared machine only adds time,
 * and over 12 runs of one loop (320x240, LP_NUM_THREADS=1) the run-to-run
 * CV of a run's minimum frame time was 0.35 % against 0.85 % for its
 * median, so the pooled minima detect changes about 2.4x smaller for the
 * same number of rounds. */
static void compare__run_minima(dm_run_result *r)
{
    for (size_t i = 0; i < r->n_configs; i++)
        for (size_t k = 0; k < r->configs[i].n_counters; k++) {
            dm_counter_result *c = &r->configs[i].counters[k];
            if (!c->has_samples || c->n_samples == 0)
                continue;
            double m = c->samples[0];
            for (size_t j = 1; j < c->n_samples; j++)
                m = isfinite(c->samples[j]) && !(c->samples[j] >= m) ? c->samples[j] : m;
            c->samples[0] = m;
            c->n_samples = 1;
            c->value = c->median = m;
        }
}

int compare_paired_min_rounds(double alpha)
{
    double a = alpha > 0 && alpha < 1 ? alpha : 0.01, c = 2;   /* C(2n, n) for n = 1 */
    int n = 1;
    while (2 / c >= a && n < 1000)
        c = c * (2 * n + 1) * (2 * n + 2) / ((double)(n + 1) * (n + 1)), n++;
    return n;
}

void compare_pool_run(dm_run_result *pooled, dm_run_result *r, int round)
{
    compare__run_minima(r);
    if (round == 0) {
        *pooled = *r;
        memset(r, 0, sizeof *r);
        return;
    }
    for (size_t i = 0; i < r->n_configs; i++) {
        const dm_config_result *c = &r->configs[i];
        for (size_t k = 0; k < pooled->n_configs; k++)
            if (strcmp(pooled->configs[k].key, c->key) == 0)
                compare__pool_config(&pooled->configs[k], c, pooled, round);
    }
    dm_run_free(r);
}

/* One run of one side in its own directory, pooled into *side. */
static int compare__paired_one(const compare_paired_desc *d, const char *tmp, int is_new,
                               int round, dm_run_result *side, dm_str *err)
{
    const char *bin = is_new ? d->new_binary : d->base_binary;
    char *out = dm_xasprintf("%s/%s%d", tmp, is_new ? "new" : "base", round);
    if (!d->quiet)
        fprintf(stderr, "paired: round %d/%d: %s (%s)\n", round + 1, d->rounds, is_new ? "NEW" : "BASE", bin);
    int rc = compare__spawn_run(bin, d->sweep_path, out, round + 1);
    if (rc)
        dm_str_printf(err, "paired: %s run of round %d failed (%s %s)", is_new ? "NEW" : "BASE",
                      round + 1, bin, d->sweep_path);
    dm_run_result r;
    if (!rc && (rc = compare_load_path(out, &r, err)) == 0)
        compare_pool_run(side, &r, round);
    free(out);
    return rc;
}

int compare_paired_run(const compare_paired_desc *desc, dm_run_result *base, dm_run_result *new_,
                       dm_str *err)
{
    compare_paired_desc d = *desc;
    d.rounds = d.rounds > 0 ? d.rounds : COMPARE_PAIRED_ROUNDS;   /* one past compare_paired_min_rounds(0.01) */
    memset(base, 0, sizeof *base);
    memset(new_, 0, sizeof *new_);
    const char *tmpdir = getenv("TMPDIR");
    char *tmp = dm_xasprintf("%s/dmbench-paired-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
    if (!mkdtemp(tmp)) {
        dm_str_printf(err, "%s: cannot create a temporary directory", tmp);
        free(tmp);
        return DM_ERR_IO;
    }
    int rc = 0;
    for (int r = 0; rc == 0 && r < d.rounds; r++) {
        int first_new = r % 2;   /* ABBA: A B | B A | A B ... */
        rc = compare__paired_one(&d, tmp, first_new, r, first_new ? new_ : base, err);
        if (rc == 0)
            rc = compare__paired_one(&d, tmp, !first_new, r, first_new ? base : new_, err);
    }
    nftw(tmp, compare__rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    free(tmp);
    if (rc) {
        dm_run_free(base);
        dm_run_free(new_);
    }
    return rc;
}

/* 0, or DM_ERR_ARG with err set when run r (from paths[k]) is one of the
 * runs ids[0..k) already loaded from paths[0..k): a run listed twice (also
 * as `latest` and its id) would count its samples twice and shrink the
 * between-run spread to nothing. */
static int compare__once(char *const *ids, char *const *paths, size_t k, const dm_run_result *r,
                         dm_str *err)
{
    for (size_t j = 0; r->id && j < k; j++)
        if (ids[j] && strcmp(ids[j], r->id) == 0) {
            dm_str_printf(err, "compare: %s and %s are the same run (%s); name each run once",
                          paths[j], paths[k], r->id);
            return DM_ERR_ARG;
        }
    return 0;
}

int compare_load_paths(const char *list, dm_run_result *out, size_t *n_runs, dm_str *err)
{
    memset(out, 0, sizeof *out);
    *n_runs = 0;
    char **paths = NULL;
    size_t n = 0;
    int rc = dm_split_paths(list, "compare: the list", &paths, &n, err);
    char **ids = rc == 0 ? dm_xcalloc(n, sizeof *ids) : NULL;
    for (size_t k = 0; rc == 0 && k < n; k++) {
        dm_run_result r;
        if ((rc = compare_load_path(paths[k], &r, err)) != 0)
            break;
        ids[k] = dm_xstrdup(r.id);
        if ((rc = compare__once(ids, paths, k, &r, err)) != 0)
            dm_run_free(&r);
        else if (n == 1)
            *out = r;
        else
            compare_pool_run(out, &r, (int)k);
        *n_runs += rc == 0;
    }
    dm_strv_free(ids, ids ? n : 0);
    dm_strv_free(paths, n);
    if (rc) {
        dm_run_free(out);
        *n_runs = 0;
    }
    return rc;
}
