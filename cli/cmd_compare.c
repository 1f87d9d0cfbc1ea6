/* cmd_compare.c — `dmbench compare` (docs/ci-gating.md).
 *
 * Sides of a comparison (BASE first, then NEW):
 *   PATH                 a results.json, a run directory or an output root
 *   PATH,PATH,...        several separate runs of one side, pooled one
 *                        minimum per run (compare_load_paths)
 *   --base-run ID | --base-tag NAME | --baseline     BASE from a store
 *   --new-run ID  | --new-tag NAME                   NEW from a store
 * The store is --base-store / --new-store, else --store, else
 * results/dmbench.sqlite.  A side not taken from a store takes the next
 * positional PATH.  --baseline is the newest run accepted with
 * `dmbench baseline accept` for NEW's sweep.
 */
#include "cli.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "gate/compare.h"
#include "sweep/fraction.h"
#include "techniques/technique.h"

#define CLI_DEFAULT_STORE "results/dmbench.sqlite"

typedef struct cli_side {
    const char *path, *store, *run, *tag;
    int baseline;
} cli_side;

typedef struct cli_compare_opts {
    compare_desc d;
    size_t n_runs[2];        /* runs pooled into BASE, NEW (0 from a store) */
    cli_side base, new_;
    const char *store;
    char **positional;
    int n_positional;
    const char *junit, *markdown, *json;
    const char *paired[3];
    int rounds, quiet, only_changed;
    compare_tolerance *tol;
} cli_compare_opts;

/* A non-negative number (--psnr-drop, in dB) into the compare_desc field
 * of the option's offset. */
static int compare__number(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    char *end = NULL;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x) || x < 0) {
        dm_str_printf(err, "--%s '%s': expected a non-negative number", opt->name, v);
        return DM_ERR_ARG;
    }
    *(double *)((char *)args + opt->offset) = x;
    return 0;
}

/* The range of each fraction flag (sweep/fraction.h grammar: 5% or 0.05).
 * 0 is refused where it would silently mean "the default". */
static const struct { const char *flag; fraction_range range; } compare__fractions[] = {
    { "time-threshold", { 0, INFINITY, 1, 0 } },   /* a time change; above 100 % as a percentage */
    { "threshold", { 0, 1, 1, 1 } },               /* an Instructions change */
    { "alpha", { 0, 1, 1, 1 } },                   /* a significance level */
    { "ssim-drop", { 0, 1, 1, 0 } },               /* SSIM is in [0, 1] */
    { "flip-rise", { 0, 1, 1, 0 } },               /* FLIP is in [0, 1] */
    { "run-spread", { 0, INFINITY, 1, 0 } },       /* the machine's between-run spread */
};

/* A fraction flag (the table above) into its compare_desc field. */
static int compare__fraction(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    for (size_t i = 0; i < sizeof compare__fractions / sizeof *compare__fractions; i++)
        if (strcmp(compare__fractions[i].flag, opt->name) == 0) {
            char *what = dm_xasprintf("--%s", opt->name);
            int rc = fraction_parse(v, what, &compare__fractions[i].range,
                                    (double *)((char *)args + opt->offset), err);
            free(what);
            return rc;
        }
    assert(!"a fraction flag without a range");
    return DM_ERR_ARG;
}

/* --tolerance COUNTER=REL, repeatable. */
static int compare__tolerance(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    cli_compare_opts *o = args;
    const char *eq = strchr(v, '=');
    if (!eq || eq == v) {
        dm_str_printf(err, "--%s '%s': expected COUNTER=REL, e.g. FSInvocations=0.01 or "
                      "FSInvocations=1%%", opt->name, v);
        return DM_ERR_ARG;
    }
    static const fraction_range any = { 0, INFINITY, 0, 0 };
    double rel = 0;
    char *name = dm_xasprintf("%.*s", (int)(eq - v), v);
    char *what = dm_xasprintf("--%s %s", opt->name, name);
    int rc = fraction_parse(eq + 1, what, &any, &rel, err);
    free(what);
    if (rc) {
        free(name);
        return rc;
    }
    if (compare_check_tolerance_counter(name, err) != 0) {   /* a misspelled counter */
        free(name);
        return DM_ERR_UNKNOWN;
    }
    o->tol = dm_xrealloc(o->tol, (o->d.n_tolerances + 1) * sizeof *o->tol);
    o->tol[o->d.n_tolerances].counter = name;
    o->tol[o->d.n_tolerances++].rel = rel;
    o->d.tolerances = o->tol;
    return 0;
}

static void compare__free_tolerances(cli_compare_opts *o)
{
    for (size_t i = 0; i < o->d.n_tolerances; i++)
        free((char *)o->tol[i].counter);
    free(o->tol);
}

#define COMPARE__OFF(field) offsetof(cli_compare_opts, field)
const cli_option cli_compare_options[] = {
    { .name = "time-threshold", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.time_threshold),
      .value_name = "REL", .parse = compare__fraction,
      .help = "smallest time change that counts, 5% or 0.05 (a bare 5 is refused) [default 5%]" },
    { .name = "threshold", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.threshold),
      .value_name = "REL", .parse = compare__fraction,
      .help = "smallest Instructions change that counts, 0.5% or 0.005 [default 0.5%]" },
    { .name = "alpha", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.alpha), .value_name = "P",
      .parse = compare__fraction, .help = "significance level of the time test, 1% or 0.01 [default 1%]" },
    { .name = "psnr-drop", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.psnr_drop),
      .value_name = "DB", .parse = compare__number, .help = "largest PSNR loss that passes [default 1 dB]" },
    { .name = "ssim-drop", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.ssim_drop),
      .value_name = "X", .parse = compare__fraction,
      .help = "largest SSIM loss that passes, 1% or 0.01 [default 0.01]" },
    { .name = "flip-rise", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.flip_rise),
      .value_name = "X", .parse = compare__fraction,
      .help = "largest rise of the mean FLIP error that passes, 0.5% or 0.005 [default 0.005]" },
    { .name = "tolerance", .kind = CLI_OPT_STRING, .value_name = "COUNTER=REL",
      .parse = compare__tolerance, .repeat = 1, .help = "relative tolerance of one counter (repeatable)" },
    CLI_STRING("time-counter", cli_compare_opts, d.time_counter, "NAME",
               "the counter the time test uses [default WallTime]"),
    { .name = "seed", .kind = CLI_OPT_UINT64, .offset = COMPARE__OFF(d.seed), .value_name = "N",
      .help = "seed of the bootstrap resampling" },
    CLI_BOOL("counters-only", cli_compare_opts, d.counters_only,
             "compare the deterministic counters only (no timing, no noise)"),
    { .name = "run-spread", .kind = CLI_OPT_DOUBLE, .offset = COMPARE__OFF(d.run_spread),
      .value_name = "REL", .parse = compare__fraction,
      .help = "how far this machine's speed moves between two runs, 10% or 0.1; a time change "
              "within it is not a regression without --paired [default 10%]" },
    CLI_BOOL("no-blocking", cli_compare_opts, d.no_blocking,
             "time CIs of the raw samples, not blocked by round"),
    CLI_BOOL("allow-env-mismatch", cli_compare_opts, d.allow_env_mismatch,
             "compare runs from different environments (fingerprints)"),
    CLI_STRING("junit", cli_compare_opts, junit, "FILE", "write a JUnit XML report"),
    CLI_STRING("markdown", cli_compare_opts, markdown, "FILE",
               "write a Markdown report for a PR comment (always, also when nothing compared)"),
    CLI_BOOL("only-changed", cli_compare_opts, only_changed,
             "--markdown: only what changed (no PASS rows)"),
    CLI_STRING("json", cli_compare_opts, json, "FILE", "write a JSON report"),
    { .name = "store", .kind = CLI_OPT_STRING, .offset = COMPARE__OFF(store), .value_name = "FILE",
      .help = "the store of both sides [default " CLI_DEFAULT_STORE "]" },
    CLI_STRING("base-store", cli_compare_opts, base.store, "FILE",
               "the store of BASE (over --store)"),
    CLI_STRING("new-store", cli_compare_opts, new_.store, "FILE",
               "the store of NEW (over --store)"),
    CLI_STRING("base-run", cli_compare_opts, base.run, "ID", "BASE is this run of the store"),
    CLI_STRING("base-tag", cli_compare_opts, base.tag, "NAME",
               "BASE is the newest run of the store with this tag"),
    CLI_BOOL("baseline", cli_compare_opts, base.baseline,
             "BASE is the accepted baseline of NEW's sweep (dmbench baseline accept)"),
    CLI_STRING("new-run", cli_compare_opts, new_.run, "ID", "NEW is this run of the store"),
    CLI_STRING("new-tag", cli_compare_opts, new_.tag, "NAME",
               "NEW is the newest run of the store with this tag"),
    { .name = "paired", .kind = CLI_OPT_STRING, .offset = COMPARE__OFF(paired), .nargs = 3,
      .value_name = "BASE_BINARY NEW_BINARY SWEEP",
      .help = "run both binaries on SWEEP in alternating rounds and compare" },
    { .name = "rounds", .kind = CLI_OPT_INT, .offset = COMPARE__OFF(rounds), .value_name = "N",
      .min = 1, .max = 1000000,
      .help = "--paired: rounds per binary (default 6; at least 5 at --alpha 0.01 unless --counters-only)" },
    CLI_BOOL("quiet", cli_compare_opts, quiet,
             "no text report on stdout (files and exit code only)"),
    CLI_OPT_END
};

static int compare__from_store(const cli_side *s) { return s->baseline || s->run || s->tag; }

/* Loads one side from its store options or from path (a comma-separated
 * list pools several runs; their number into *n_runs). */
static int compare__load_side(const cli_compare_opts *o, const cli_side *s, const char *path,
                          const char *sweep, dm_run_result *out, size_t *n_runs, dm_str *err)
{
    const char *store = s->store ? s->store : o->store ? o->store : CLI_DEFAULT_STORE;
    if (s->baseline) {
        char *id = NULL, *reason = NULL;
        int rc = compare_baseline_latest(store, sweep, &id, &reason, err);
        if (rc == 0) {
            char *buf = NULL;
            fprintf(stderr, "dmbench: baseline: run %s (accepted: %s)\n", id, dm_term_safe(reason, &buf));
            free(buf);
            rc = compare_load_store(store, id, NULL, out, err);
        }
        free(id);
        free(reason);
        return rc;
    }
    if (s->run || s->tag)
        return compare_load_store(store, s->run, s->tag, out, err);
    return compare_load_paths(path, out, n_runs, err);
}

/* Several runs on one side only: the other side's between-run spread
 * cannot be estimated, so the comparison could not say more than one run
 * a side does. */
static int compare__check_replicas(cli_compare_opts *o, dm_str *err)
{
    size_t b = o->n_runs[0] ? o->n_runs[0] : 1, n = o->n_runs[1] ? o->n_runs[1] : 1;
    if ((b > 1) != (n > 1)) {
        dm_str_printf(err, "compare: BASE has %zu run%s and NEW %zu: give both sides several runs "
                      "(BASE1,BASE2,... NEW1,NEW2,...), or one each", b, b == 1 ? "" : "s", n);
        return DM_ERR_ARG;
    }
    o->d.replicated = b > 1;
    return 0;
}

/* Both sides (NEW first: --baseline picks the baseline of NEW's sweep);
 * each side not taken from a store takes the next positional path. */
static int compare__load_sides(cli_compare_opts *o, dm_run_result *base, dm_run_result *new_, dm_str *err)
{
    if (o->paired[0]) {
        compare_paired_desc pd = { .base_binary = o->paired[0], .new_binary = o->paired[1],
                                   .sweep_path = o->paired[2], .rounds = o->rounds, .quiet = o->quiet };
        return compare_paired_run(&pd, base, new_, err);
    }
    int base_pos = !compare__from_store(&o->base), new_pos = !compare__from_store(&o->new_);
    if (o->n_positional != base_pos + new_pos) {
        dm_str_printf(err, "compare: expected %d path%s (BASE from %s, NEW from %s), got %d; "
                      "usage: dmbench compare BASE NEW", base_pos + new_pos,
                      base_pos + new_pos == 1 ? "" : "s", base_pos ? "a path" : "the store",
                      new_pos ? "a path" : "the store", o->n_positional);
        return DM_ERR_ARG;
    }
    int rc = compare__load_side(o, &o->new_, new_pos ? o->positional[base_pos] : NULL, NULL, new_,
                            &o->n_runs[1], err);
    if (rc == 0)
        rc = compare__load_side(o, &o->base, base_pos ? o->positional[0] : NULL, new_->sweep, base,
                            &o->n_runs[0], err);
    return rc ? rc : compare__check_replicas(o, err);
}

static int compare__outputs(const cli_compare_opts *o, const compare_result *r)
{
    compare_md_desc md = { .only_changed = o->only_changed };
    int e = o->markdown ? compare_write_markdown(r, &md, o->markdown) : 0;
    if (e)   /* 4 when the disk refused it (full, ulimit -f), else 2 */
        return cli_error(e, "compare: cannot write %s: %s", o->markdown, strerror(errno));
    struct { const char *path; int (*fn)(const compare_result *, const char *); } w[] = {
        { o->junit, compare_write_junit }, { o->json, compare_write_json } };
    for (size_t i = 0; i < sizeof w / sizeof *w; i++)
        if (w[i].path && (e = w[i].fn(r, w[i].path)) != 0)
            return cli_error(e, "compare: cannot write %s: %s", w[i].path, strerror(errno));
    return 0;
}

/* Prints the error (and writes it as the Markdown report, so a CI step
 * that posts the file always finds one), frees err, returns the exit code
 * of e (cli_error): 4 for a damaged or newer store, 2 otherwise. */
static int compare__compare_fail(const cli_compare_opts *o, const compare_result *r, int e,
                             dm_str *err)
{
    int rc = cli_error(e, "%s", dm_str_get(err));
    if (o->markdown && compare_write_markdown(r, &(compare_md_desc){ .none = 1, .reason = dm_str_get(err) }, o->markdown) != 0)
        fprintf(stderr, "dmbench: error: compare: cannot write %s\n", o->markdown);
    dm_str_free(err);
    return rc;
}

/* --rounds that can reach a timing verdict (compare_paired_min_rounds at
 * the --alpha given), unless --counters-only; and the default raised to
 * that minimum.  -1 to go on, else the exit code (2). */
static int compare__check_rounds(cli_compare_opts *o)
{
    int min = compare_paired_min_rounds(o->d.alpha);
    if (o->rounds && !o->paired[0])
        return cli_usage_error("compare: --rounds %d: rounds are for --paired only", o->rounds);
    if (o->rounds && o->rounds < min && !o->d.counters_only)
        return cli_usage_error("compare: --rounds %d: too few to reach a verdict: the paired test "
                               "(Mann-Whitney, exact, two-sided) cannot get under --alpha %g with "
                               "fewer than %d rounds per binary; give --rounds %d or more (or "
                               "--counters-only)", o->rounds, o->d.alpha > 0 ? o->d.alpha : 0.01, min, min);
    if (!o->rounds && o->paired[0])
        o->rounds = min > COMPARE_PAIRED_ROUNDS ? min : COMPARE_PAIRED_ROUNDS;
    return -1;
}

static int compare__builtin_technique(const char *name) { return technique_find(name) != NULL; }

/* `dmbench compare`: both sides, the comparison, its text and files;
 * the exit code of the verdicts (compare_exit_code). */
int cli_compare(const cli_command *self, int argc, char **argv)
{
    cli_compare_opts o = {0};
    int rc = cli_parse(self, argc, argv, &o, &argc);
    o.positional = argv;
    o.n_positional = argc;
    o.d.paired = o.paired[0] != NULL;   /* pooled minimum times (compare.h) */
    o.d.builtin_technique = compare__builtin_technique;   /* a user's edited GLSL file: paired */
    if (rc < 0 && argc > 2)
        rc = cli_usage_error("compare: too many arguments ('%s'): expected BASE NEW", argv[2]);
    dm_run_result base = {0}, new_ = {0};
    compare_result r = {0};
    dm_str err = {0};
    if (rc < 0 && o.paired[0] && o.n_positional)
        rc = cli_usage_error("compare: --paired takes no BASE/NEW paths ('%s')", o.positional[0]);
    rc = rc < 0 ? compare__check_rounds(&o) : rc;
    int e = 0;
    if (rc < 0 && (e = compare__load_sides(&o, &base, &new_, &err)) != 0)
        rc = compare__compare_fail(&o, NULL, e, &err);
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
            rc = compare__compare_fail(&o, &r, c, &err);
        } else {
            for (size_t i = 0; i < r.n_warnings; i++)
                fprintf(stderr, "dmbench: warning: %s\n", r.warnings[i]);
            if (!o.quiet)
                compare_write_text(&r, stdout);
            rc = compare__outputs(&o, &r);
            rc = rc ? rc : compare_exit_code(&r);
        }
    }
    compare_result_free(&r);
    dm_run_free(&base);
    dm_run_free(&new_);
    compare__free_tolerances(&o);
    dm_str_free(&err);
    return rc;
}

