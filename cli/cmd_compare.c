/* cli_compare.c — `dmbench compare` and `dmbench baseline` (SPEC §9).
 *
 * Sides of a comparison (BASE first, then NEW):
 *   PATH                 a results.json, a run directory or an output root
 *   --base-run ID | --base-tag NAME | --baseline     BASE from a store
 *   --new-run ID  | --new-tag NAME                   NEW from a store
 * The store is --base-store / --new-store, else --store, else
 * results/dmbench.sqlite.  A side not taken from a store takes the next
 * positional PATH.  --baseline is the newest run accepted with
 * `dmbench baseline accept` for NEW's sweep.
 */
#include "cli.h"

#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "gate/compare.h"

#define CLI_DEFAULT_STORE "results/dmbench.sqlite"

typedef struct cli_side {
    const char *path, *store, *run, *tag;
    int baseline;
} cli_side;

typedef struct cli_compare_opts {
    compare_desc d;
    cli_side base, new_;
    const char *store;
    const char *positional[2];
    int n_positional;
    const char *junit, *markdown, *json;
    const char *paired[3];
    int rounds, quiet;
    compare_tolerance *tol;
} cli_compare_opts;

/* "5%" -> 0.05, "0.05" -> 0.05; -1 when not a non-negative number. */
static double cli__fraction(const char *v)
{
    char *end = NULL;
    double x = strtod(v, &end);
    if (end == v || !isfinite(x) || x < 0)
        return -1;
    if (*end == '%' && end[1] == '\0')
        return x / 100.0;
    return *end ? -1 : x;
}

/* A numeric option; returns -1 to go on, else an exit code. */
static int cli__num_opt(int argc, char **argv, int *i, double *out, int allow_percent)
{
    const char *opt = argv[*i], *v = cli__value(argc, argv, i);
    if (!v)
        return 2;
    double x = cli__fraction(v);
    if (x < 0 || (!allow_percent && strchr(v, '%')))
        return cli__usage_error("compare: %s '%s': expected a non-negative number%s", opt, v,
                                allow_percent ? " or a percentage such as 5%" : "");
    *out = x;
    return -1;
}

/* --tolerance COUNTER=REL */
static int cli__tolerance(cli_compare_opts *o, const char *v)
{
    const char *eq = strchr(v, '=');
    double rel = eq ? cli__fraction(eq + 1) : -1;
    if (!eq || eq == v || rel < 0)
        return cli__usage_error("compare: --tolerance '%s': expected COUNTER=REL, e.g. "
                                "FSInvocations=0.01 or FSInvocations=1%%", v);
    char *name = dm_xasprintf("%.*s", (int)(eq - v), v);
    dm_str e = {0};
    if (compare_check_tolerance_counter(name, &e) != 0) {
        cli__usage_error("compare: %s", dm_str_get(&e));
        dm_str_free(&e);
        free(name);
        return 2;
    }
    compare_tolerance *t = &o->tol[o->d.n_tolerances++];
    t->counter = name;
    t->rel = rel;
    return -1;
}

/* String-valued options: returns the slot for opt, or NULL. */
static const char **cli__string_slot(cli_compare_opts *o, const char *opt)
{
    struct { const char *name; const char **slot; } map[] = {
        { "--junit", &o->junit }, { "--markdown", &o->markdown }, { "--json", &o->json },
        { "--store", &o->store }, { "--base-store", &o->base.store }, { "--new-store", &o->new_.store },
        { "--base-run", &o->base.run }, { "--base-tag", &o->base.tag }, { "--new-run", &o->new_.run },
        { "--new-tag", &o->new_.tag }, { "--time-counter", &o->d.time_counter },
    };
    for (size_t i = 0; i < sizeof map / sizeof *map; i++)
        if (strcmp(opt, map[i].name) == 0)
            return map[i].slot;
    return NULL;
}

/* Numeric options: returns -1 to go on, an exit code, or 0 when opt is not one. */
static int cli__numeric(cli_compare_opts *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (strcmp(a, "--time-threshold") == 0)
        return cli__num_opt(argc, argv, i, &o->d.time_threshold, 1);
    if (strcmp(a, "--alpha") == 0) {
        int rc = cli__num_opt(argc, argv, i, &o->d.alpha, 0);
        dm_str e = {0};
        if (rc < 0 && compare_check_alpha(o->d.alpha, &e) != 0)
            rc = cli__usage_error("compare: %s", dm_str_get(&e));
        dm_str_free(&e);
        return rc;
    }
    if (strcmp(a, "--psnr-drop") == 0)
        return cli__num_opt(argc, argv, i, &o->d.psnr_drop, 0);
    if (strcmp(a, "--ssim-drop") == 0)
        return cli__num_opt(argc, argv, i, &o->d.ssim_drop, 0);
    if (strcmp(a, "--seed") == 0 || strcmp(a, "--rounds") == 0) {
        double x = 0;
        int rc = cli__num_opt(argc, argv, i, &x, 0);
        if (rc < 0 && x != floor(x))
            rc = cli__usage_error("compare: %s: expected an integer", a);
        if (a[2] == 's')
            o->d.seed = (uint64_t)x;
        else
            o->rounds = (int)x;
        return rc;
    }
    return 0;
}

static int cli__compare_options(int argc, char **argv, cli_compare_opts *o)
{
    static const char *const valid[] = {
        "--time-threshold", "--alpha", "--psnr-drop", "--ssim-drop", "--tolerance", "--time-counter",
        "--seed", "--counters-only", "--allow-env-mismatch", "--junit", "--markdown", "--json",
        "--store", "--base-store", "--new-store", "--base-run", "--base-tag", "--new-run",
        "--new-tag", "--baseline", "--paired", "--rounds", "--quiet" };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], **slot;
        int rc;
        if (a[0] != '-' || !a[1]) {
            if (o->n_positional == 2)
                return cli__usage_error("compare: too many arguments ('%s'): expected BASE NEW", a);
            o->positional[o->n_positional++] = a;
        } else if ((slot = cli__string_slot(o, a))) {
            if (!(*slot = cli__value(argc, argv, &i)))
                return 2;
        } else if ((rc = cli__numeric(o, argc, argv, &i)) != 0) {
            if (rc > 0)
                return rc;
        } else if (strcmp(a, "--tolerance") == 0) {
            const char *v = cli__value(argc, argv, &i);
            if (!v || (rc = cli__tolerance(o, v)) >= 0)
                return v ? rc : 2;
        } else if (strcmp(a, "--counters-only") == 0) {
            o->d.counters_only = 1;
        } else if (strcmp(a, "--allow-env-mismatch") == 0) {
            o->d.allow_env_mismatch = 1;
        } else if (strcmp(a, "--baseline") == 0) {
            o->base.baseline = 1;
        } else if (strcmp(a, "--quiet") == 0) {
            o->quiet = 1;
        } else if (strcmp(a, "--paired") == 0) {
            if (i + 3 >= argc)
                return cli__usage_error("compare: --paired needs BASE_BINARY NEW_BINARY SWEEP");
            for (int k = 0; k < 3; k++)
                o->paired[k] = argv[++i];
        } else {
            return cli__unknown_option("compare", a, valid, sizeof valid / sizeof *valid);
        }
    }
    return -1;
}

static int cli__from_store(const cli_side *s) { return s->baseline || s->run || s->tag; }

/* Loads one side from its store options or from path. */
static int cli__load_side(const cli_compare_opts *o, const cli_side *s, const char *path,
                          const char *sweep, dm_run_result *out, dm_str *err)
{
    const char *store = s->store ? s->store : o->store ? o->store : CLI_DEFAULT_STORE;
    if (s->baseline) {
        char *id = NULL, *reason = NULL;
        int rc = compare_baseline_latest(store, sweep, &id, &reason, err);
        if (rc == 0) {
            fprintf(stderr, "dmbench: baseline: run %s (accepted: %s)\n", id, reason ? reason : "");
            rc = compare_load_store(store, id, NULL, out, err);
        }
        free(id);
        free(reason);
        return rc;
    }
    if (s->run || s->tag)
        return compare_load_store(store, s->run, s->tag, out, err);
    return compare_load_path(path, out, err);
}

/* Both sides (NEW first: --baseline picks the baseline of NEW's sweep);
 * each side not taken from a store takes the next positional path. */
static int cli__load_sides(cli_compare_opts *o, dm_run_result *base, dm_run_result *new_, dm_str *err)
{
    if (o->paired[0]) {
        compare_paired_desc pd = { .base_binary = o->paired[0], .new_binary = o->paired[1],
                                   .sweep_path = o->paired[2], .rounds = o->rounds, .quiet = o->quiet };
        return compare_paired_run(&pd, base, new_, err);
    }
    int base_pos = !cli__from_store(&o->base), new_pos = !cli__from_store(&o->new_);
    if (o->n_positional != base_pos + new_pos) {
        dm_str_printf(err, "compare: expected %d path%s (BASE from %s, NEW from %s), got %d; "
                      "usage: dmbench compare BASE NEW", base_pos + new_pos,
                      base_pos + new_pos == 1 ? "" : "s", base_pos ? "a path" : "the store",
                      new_pos ? "a path" : "the store", o->n_positional);
        return DM_ERR_ARG;
    }
    int rc = cli__load_side(o, &o->new_, new_pos ? o->positional[base_pos] : NULL, NULL, new_, err);
    if (rc == 0)
        rc = cli__load_side(o, &o->base, base_pos ? o->positional[0] : NULL, new_->sweep, base, err);
    return rc;
}

static int cli__outputs(const cli_compare_opts *o, const compare_result *r)
{
    struct { const char *path; int (*fn)(const compare_result *, const char *); } w[] = {
        { o->markdown, compare_write_markdown }, { o->junit, compare_write_junit },
        { o->json, compare_write_json } };
    for (size_t i = 0; i < sizeof w / sizeof *w; i++)
        if (w[i].path && w[i].fn(r, w[i].path) != 0)
            return cli__usage_error("compare: cannot write %s", w[i].path);
    return 0;
}

/* Prints the error, frees everything, returns 2. */
static int cli__compare_fail(dm_str *err)
{
    fprintf(stderr, "dmbench: error: %s\n", dm_str_get(err));
    dm_str_free(err);
    return 2;
}

int cli_compare(int argc, char **argv)
{
    cli_compare_opts o = {0};
    o.tol = dm_xcalloc((size_t)argc, sizeof *o.tol);
    o.d.tolerances = o.tol;
    int rc = cli__compare_options(argc, argv, &o);
    dm_run_result base = {0}, new_ = {0};
    compare_result r = {0};
    dm_str err = {0};
    if (rc < 0 && o.paired[0] && o.n_positional)
        rc = cli__usage_error("compare: --paired takes no BASE/NEW paths ('%s')", o.positional[0]);
    if (rc < 0 && cli__load_sides(&o, &base, &new_, &err) != 0)
        rc = cli__compare_fail(&err);
    if (rc < 0) {
        int c = compare_runs(&base, &new_, &o.d, &r, &err);
        for (size_t i = 0; i < base.n_warnings + new_.n_warnings && o.paired[0]; i++)
            fprintf(stderr, "dmbench: warning: %s\n",
                    i < base.n_warnings ? base.warnings[i] : new_.warnings[i - base.n_warnings]);
        if (c == 0 && !o.paired[0])
            c = compare_check_common(&r, &err);
        if (c != 0) {
            for (size_t i = 0; i < r.n_env_diffs; i++)
                fprintf(stderr, "  %s\n", r.env_diffs[i]);
            rc = cli__compare_fail(&err);
        } else {
            for (size_t i = 0; i < r.n_warnings; i++)
                fprintf(stderr, "dmbench: warning: %s\n", r.warnings[i]);
            if (!o.quiet)
                compare_write_text(&r, stdout);
            rc = cli__outputs(&o, &r);
            rc = rc ? rc : compare_exit_code(&r);
        }
    }
    compare_result_free(&r);
    dm_run_free(&base);
    dm_run_free(&new_);
    for (size_t i = 0; i < o.d.n_tolerances; i++)
        free((char *)o.tol[i].counter);
    free(o.tol);
    dm_str_free(&err);
    return rc;
}

/* RUN as a run directory (store beside it, id = its name) or, with
 * --store, a run id. */
static int cli__baseline_target(const char *run, const char *store, char **store_path, char **id)
{
    struct stat st;
    char real[PATH_MAX];
    if (stat(run, &st) == 0 && S_ISDIR(st.st_mode) && realpath(run, real)) {
        char *a = dm_xstrdup(real), *b = dm_xstrdup(real);
        *id = dm_xstrdup(basename(a));
        *store_path = store ? dm_xstrdup(store) : dm_xasprintf("%s/dmbench.sqlite", dirname(b));
        free(a);
        free(b);
        return -1;
    }
    if (!store)
        return cli__usage_error("baseline: '%s' is not a run directory (give a run directory, or "
                                "--store FILE and a run id)", run);
    *store_path = dm_xstrdup(store);
    *id = dm_xstrdup(run);
    return -1;
}

int cli_baseline(int argc, char **argv)
{
    static const char *const valid[] = { "--reason", "--store" };
    const char *run = NULL, *reason = NULL, *store = NULL;
    if (argc < 2 || (strcmp(argv[1], "accept") != 0 && strcmp(argv[1], "show") != 0))
        return cli__usage_error("usage: dmbench baseline accept RUN --reason TEXT [--store FILE] | "
                                "baseline show [--store FILE]");
    int show = strcmp(argv[1], "show") == 0;
    for (int i = 2; i < argc; i++) {
        const char **slot = strcmp(argv[i], "--reason") == 0 ? &reason
                            : strcmp(argv[i], "--store") == 0 ? &store : NULL;
        if (slot && !(*slot = cli__value(argc, argv, &i)))
            return 2;
        if (!slot && argv[i][0] == '-')
            return cli__unknown_option("baseline", argv[i], valid, sizeof valid / sizeof *valid);
        if (!slot && run)
            return cli__usage_error("baseline: only one RUN may be given");
        if (!slot)
            run = argv[i];
    }
    dm_str err = {0};
    char *store_path = NULL, *id = NULL;
    int rc;
    if (show) {
        store_path = dm_xstrdup(store ? store : CLI_DEFAULT_STORE);
        char *why = NULL;
        rc = compare_baseline_latest(store_path, NULL, &id, &why, &err);
        if (rc == 0)
            printf("%s\t%s\n", id, why ? why : "");
        free(why);
    } else {
        if (!run)
            return cli__usage_error("baseline accept: missing RUN (a run directory, e.g. results/latest)");
        if ((rc = cli__baseline_target(run, store, &store_path, &id)) >= 0)
            return rc;
        rc = compare_baseline_accept(store_path, id, reason, &err);
        if (rc == 0)
            printf("accepted run %s as the baseline of %s\n", id, store_path);
    }
    if (rc)
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
    dm_str_free(&err);
    free(store_path);
    free(id);
    return rc ? 2 : 0;
}
