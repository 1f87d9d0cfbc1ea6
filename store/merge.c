/* merge.c — the rules of merge.h. */
#include "store/merge.h"
#include "core/dm_error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *merge__env(const dm_run_result *r, const char *key)
{
    return dm_kv_get(r->environment, r->n_environment, key);
}

/* Reads the shard a run measured from its environment into sh. */
static void merge__describe(merge_shard *sh, const dm_run_result *run, const char *dir)
{
    const char *shard = merge__env(run, "shard"), *planned = merge__env(run, "shard_configs");
    const char *fp = merge__env(run, "fingerprint");
    sh->dir = dm_xstrdup(dir);
    if (!shard || sscanf(shard, "%d/%d", &sh->k, &sh->n) != 2)
        sh->k = sh->n = 0;
    sh->planned = planned ? strtol(planned, NULL, 10) : -1;
    sh->measured = run->n_configs;
    sh->finished = run->finished != NULL;
    sh->fingerprint = dm_xstrdup(fp ? fp : "unknown");
    const char *cpus = merge__env(run, "cpu_count"), *cpu = merge__env(run, "cpu");
    const char *renderer = merge__env(run, "renderer"), *lp = merge__env(run, "lp_num_threads");
    sh->machine = dm_xasprintf("%s x %s, %s, LP_NUM_THREADS=%s", cpus ? cpus : "?",
                               cpu ? cpu : "?", renderer ? renderer : "?", lp ? lp : "?");
}

/* Refuses a shard given twice or from another split; 0 or DM_ERR_ARG. */
static int merge__check_shard(const merge_state *m, const merge_shard *sh, dm_str *err)
{
    for (size_t i = 0; i < m->n_inputs; i++) {
        const merge_shard *o = &m->inputs[i];
        if (sh->n && o->n && sh->n != o->n) {
            dm_str_printf(err, "%s is shard %d/%d but %s is shard %d/%d: shards of different "
                          "splits cannot be merged", sh->dir, sh->k, sh->n, o->dir, o->k, o->n);
            return DM_ERR_ARG;
        }
        if (sh->n && sh->k == o->k && sh->n == o->n) {
            dm_str_printf(err, "shard %d/%d given twice: %s and %s (each shard may be merged "
                          "once)", sh->k, sh->n, o->dir, sh->dir);
            return DM_ERR_ARG;
        }
    }
    return 0;
}

/* Refuses a run that measured a key another input already has. */
static int merge__check_keys(const merge_state *m, const dm_run_result *run, const char *dir,
                             dm_str *err)
{
    for (size_t i = 0; i < run->n_configs; i++)
        for (size_t j = 0; j < m->out.n_configs; j++)
            if (strcmp(m->out.configs[j].key, run->configs[i].key) == 0) {
                dm_str_printf(err, "configuration %s is in both %s and %s: a configuration may "
                              "come from one run only (the same shard merged twice, or "
                              "overlapping runs?)", run->configs[i].key,
                              m->inputs[m->config_src[j]].dir, dir);
                return DM_ERR_ARG;
            }
    return 0;
}

/* Appends run's configurations, left-outs and warnings to the merge (moving
 * them); src is the input's index. */
static void merge__take(merge_state *m, dm_run_result *run, size_t src)
{
    dm_run_result *d = &m->out;
    d->configs = dm_xrealloc(d->configs, (d->n_configs + run->n_configs + 1) * sizeof *d->configs);
    m->config_src = dm_xrealloc(m->config_src, (d->n_configs + run->n_configs + 1) * sizeof *m->config_src);
    for (size_t i = 0; i < run->n_configs; i++) {
        m->config_src[d->n_configs] = src;
        d->configs[d->n_configs++] = run->configs[i];
    }
    run->n_configs = 0;
    d->left_out = dm_xrealloc(d->left_out, (d->n_left_out + run->n_left_out + 1) * sizeof *d->left_out);
    if (run->n_left_out)   /* left_out is NULL when empty: no memcpy from NULL */
        memcpy(d->left_out + d->n_left_out, run->left_out, run->n_left_out * sizeof *run->left_out);
    d->n_left_out += run->n_left_out;
    run->n_left_out = 0;
    d->rounds = dm_xrealloc(d->rounds, (d->n_rounds + run->n_rounds + 1) * sizeof *d->rounds);
    m->round_src = dm_xrealloc(m->round_src, (d->n_rounds + run->n_rounds + 1) * sizeof *m->round_src);
    for (size_t i = 0; i < run->n_rounds; i++) {
        m->round_src[d->n_rounds] = src;
        d->rounds[d->n_rounds++] = run->rounds[i];
    }
    run->n_rounds = 0;
    d->warnings = dm_xrealloc(d->warnings, (d->n_warnings + run->n_warnings + 1) * sizeof *d->warnings);
    for (size_t i = 0; i < run->n_warnings; i++)
        d->warnings[d->n_warnings++] = dm_xasprintf("%s: %s", m->inputs[src].dir, run->warnings[i]);
}

/* The first run gives the merge its id, sweep, environment and timer; its
 * configurations, left-outs and warnings are taken like any other's, and
 * its fits are dropped: a fit to one shard does not describe the union. */
static void merge__first(merge_state *m, dm_run_result *run)
{
    m->out = (dm_run_result){ .id = run->id, .sweep = run->sweep, .started = run->started,
                              .finished = run->finished, .sweep_hash = run->sweep_hash,
                              .environment = run->environment, .n_environment = run->n_environment,
                              .gpu_time_coverage = run->gpu_time_coverage,
                              .timer_verdict = run->timer_verdict };
    run->id = run->sweep = run->started = run->finished = run->sweep_hash = NULL;
    run->timer_verdict = NULL;
    run->environment = NULL;
    run->n_environment = 0;
}

int merge_add(merge_state *m, dm_run_result *run, const char *dir, dm_str *err)
{
    merge_shard sh = {0};
    merge__describe(&sh, run, dir);
    int rc = 0;
    if (m->n_inputs && (!run->sweep_hash || !m->out.sweep_hash ||
                        strcmp(run->sweep_hash, m->out.sweep_hash) != 0)) {
        dm_str_printf(err, "%s was made from a different sweep file (hash %s vs %s)", dir,
                      run->sweep_hash ? run->sweep_hash : "?",
                      m->out.sweep_hash ? m->out.sweep_hash : "?");
        rc = DM_ERR_ARG;
    }
    rc = rc ? rc : merge__check_shard(m, &sh, err);
    rc = rc ? rc : merge__check_keys(m, run, dir, err);
    if (rc == 0) {
        DM_VEC_PUSH(m->inputs, m->n_inputs, sh);
        if (m->n_inputs == 1)
            merge__first(m, run);
        merge__take(m, run, m->n_inputs - 1);
    } else {
        free(sh.dir);
        free(sh.fingerprint);
        free(sh.machine);
    }
    dm_run_free(run);
    return rc;
}

size_t merge_missing(const merge_state *m, dm_str *out)
{
    int n = 0;
    for (size_t i = 0; i < m->n_inputs; i++)
        n = m->inputs[i].n > n ? m->inputs[i].n : n;
    size_t count = 0;
    for (int k = 1; k <= n; k++) {
        const merge_shard *sh = NULL;
        for (size_t i = 0; i < m->n_inputs && !sh; i++)
            if (m->inputs[i].k == k)
                sh = &m->inputs[i];
        if (!sh) {
            dm_str_printf(out, "shard %d/%d: not given\n", k, n);
            count++;
        } else if (!sh->finished || (sh->planned >= 0 && (size_t)sh->planned != sh->measured)) {
            dm_str_printf(out, "shard %d/%d (%s): %zu of %ld configurations%s\n", k, n, sh->dir,
                          sh->measured, sh->planned, sh->finished ? "" : ", the run did not finish");
            count++;
        }
    }
    return count;
}

size_t merge_machines(const merge_state *m)
{
    size_t n = 0;
    for (size_t i = 0; i < m->n_inputs; i++) {
        size_t j = 0;
        while (j < i && strcmp(m->inputs[j].fingerprint, m->inputs[i].fingerprint) != 0)
            j++;
        n += j == i;
    }
    return n;
}

/* Records "machine <fp>" = "<description>; runs: DIR..." for every machine. */
static void merge__describe_machines(merge_state *m)
{
    for (size_t i = 0; i < m->n_inputs; i++) {
        size_t j = 0;
        while (j < i && strcmp(m->inputs[j].fingerprint, m->inputs[i].fingerprint) != 0)
            j++;
        if (j < i)
            continue;
        dm_str d = {0};
        dm_str_printf(&d, "%s; runs:", m->inputs[i].machine);
        for (size_t k = i; k < m->n_inputs; k++)
            if (strcmp(m->inputs[k].fingerprint, m->inputs[i].fingerprint) == 0)
                dm_str_printf(&d, " %s", m->inputs[k].dir);
        char *key = dm_xasprintf("machine %s", m->inputs[i].fingerprint);
        dm_kv_push(&m->out.environment, &m->out.n_environment, key, dm_str_get(&d));
        free(key);
        dm_str_free(&d);
    }
}

/* Gives configuration c the machine parameter and a per-machine scene. */
static void merge__tag(dm_config_result *c, const char *fp)
{
    dm_kv_push(&c->params, &c->n_params, "machine", fp);
    char *scene = dm_xasprintf("%s @ %s", c->scene ? c->scene : "?", fp);
    free(c->scene);
    c->scene = scene;
}

void merge_finish(merge_state *m)
{
    size_t machines = merge_machines(m);
    if (machines < 2)
        return;
    merge__describe_machines(m);
    for (size_t i = 0; i < m->out.n_configs; i++)
        merge__tag(&m->out.configs[i], m->inputs[m->config_src[i]].fingerprint);
    for (size_t i = 0; i < m->out.n_rounds; i++) {
        char *scene = dm_xasprintf("%s @ %s", m->out.rounds[i].scene, m->inputs[m->round_src[i]].fingerprint);
        free(m->out.rounds[i].scene);
        m->out.rounds[i].scene = scene;
    }
    m->out.warnings = dm_xrealloc(m->out.warnings, (m->out.n_warnings + 1) * sizeof *m->out.warnings);
    m->out.warnings[m->out.n_warnings++] =
        dm_xasprintf("merged from %zu machines (environment fingerprints differ; see the "
                     "'machine ...' entries of the environment): every configuration carries the "
                     "parameter 'machine' and its scene ends in '@ <fingerprint>', so tables, "
                     "fronts and charts are per machine and no samples are pooled across "
                     "machines; compare times only within one machine", machines);
}

void merge_free(merge_state *m)
{
    for (size_t i = 0; i < m->n_inputs; i++) {
        free(m->inputs[i].dir);
        free(m->inputs[i].fingerprint);
        free(m->inputs[i].machine);
    }
    free(m->inputs);
    free(m->config_src);
    free(m->round_src);
    dm_run_free(&m->out);
    memset(m, 0, sizeof *m);
}
