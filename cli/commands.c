/* commands.c — the command table, dispatch, the overview (help) and
 * --version, and the build steps that print the man page and completions
 * (gen.h) from the table.  No command calls back here: each gets its row
 * as `self` (cli.h). */
#include "commands.h"
#include "gen.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "run/callgrind.h"
#include "run/count_child.h"
#include "run/drivers.h"
#include "run/probe.h"

#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

static int commands__help(const cli_command *self, int argc, char **argv);
static int commands__gen_man(const cli_command *self, int argc, char **argv);
static int commands__gen_completion(const cli_command *self, int argc, char **argv);
static int commands__instructions(const cli_command *self, int argc, char **argv);

static const char *const commands__shells[] = { "bash", "zsh", NULL };

/* The one list of commands, in the order help shows them. */
static const cli_command commands__table[] = {
    { .name = "run", .fn = cli_run, .options = cli_run_options,
      .summary = "measure a sweep: every configuration, its counters, images and quality",
      .synopsis = "[SWEEP.yaml]",
      .description = "Without SWEEP.yaml the embedded default sweep runs (--quick: a smaller\n"
                     "version that takes seconds; --print-default shows the default sweep as YAML).\n"
                     "The report is written to DIR/<run-id>/report.html and each scene's\n"
                     "recommendation is printed at the end; see docs/sweep-files.md for the sweep\n"
                     "file and docs/scale-out.md for shards." },
    { .name = "report", .fn = cli_report, .options = cli_report_options, .synopsis = "DIR",
      .summary = "rebuild report.html, results.json, results.csv and summary.md of a run",
      .description = "DIR is a run directory (e.g. results/latest); its store is the\n"
                     "dmbench.sqlite beside it." },
    { .name = "fit", .fn = cli_fit, .options = cli_fit_options, .synopsis = "DIR\n--data FILE.csv",
      .summary = "fit a cost model to a run (or a CSV): parameters, standard errors, R², CV-MAPE",
      .description = "Exit 1 when nothing could be fitted (or the fit failed numerically)." },
    { .name = "predict", .fn = cli_predict, .options = cli_predict_options, .synopsis = "SWEEP --from RUN[,RUN...]", .summary = "predict each configuration's Instructions, stage shares and WallTime from measured runs (docs/models.md)" },
    { .name = "compare", .fn = cli_compare, .options = cli_compare_options,
      .summary = "regression gate: compare two runs (exit 0 pass, 1 regression, 3 inconclusive)",
      .synopsis = "BASE NEW\nBASE1,BASE2,... NEW1,NEW2,...\n--paired BASE_BINARY NEW_BINARY SWEEP [--rounds N]",
      .description =
          "A side is a PATH (a results.json, a run directory or an output root) or is\n"
          "taken from a store: --base-run ID | --base-tag NAME | --baseline for BASE,\n"
          "--new-run ID | --new-tag NAME for NEW.  The store is --base-store/--new-store,\n"
          "else --store, else results/dmbench.sqlite.  A side not taken from a store\n"
          "takes the next PATH.  Two separate runs cannot tell a slower machine from\n"
          "slower code: a time change the machine could explain (WallTime against\n"
          "CPUTime, load average, how far its rounds moved, --run-spread) is\n"
          "INCONCLUSIVE, not REGRESSION; --paired runs both builds in alternating\n"
          "rounds and is the way to gate time.  Several separate runs a side, comma-\n"
          "separated, are pooled one minimum per run, so their between-run spread is\n"
          "measured, not assumed (6 a side can reach q < 0.01).  Exit 2 bad input (also: environments\n"
          "differ), 4 environment failure.  See docs/ci-gating.md." },
    { .name = "baseline", .fn = cli_baseline, .options = cli_baseline_options,
      .pos_choices = cli_baseline_actions, .synopsis = "accept RUN --reason TEXT\nshow",
      .summary = "accept a run as the baseline of its sweep, or show the current baseline",
      .description = "RUN is a run directory (its store beside it) or, with --store, a run id." },
    { .name = "merge", .fn = cli_merge, .options = cli_merge_options, .synopsis = "OUT DIR...",
      .summary = "unite the runs of shards (run --shard K/N) into one run in OUT",
      .description = "Every DIR is a run directory of the same sweep file; each shard once, each\n"
                     "configuration once; missing or incomplete shards are refused unless\n"
                     "--allow-missing.  Shards of different machines are kept apart, never pooled.\n"
                     "OUT gets dmbench.sqlite, the merged run directory and 'latest'." },
    { .name = "slurm", .fn = cli_slurm, .options = cli_slurm_options,
      .synopsis = "[SWEEP.yaml] --shards N [-- SBATCH_ARG...]",
      .summary = "a Slurm job array, one task per shard, and a job that merges them",
      .description = "Writes DIR/slurm/shards.sbatch (the job array, one task per shard) and\n"
                     "DIR/slurm/merge.sbatch (runs `dmbench slurm --collect`, after the array with\n"
                     "afterany) and submits both with sbatch; --print writes them without\n"
                     "submitting.  Shards run into DIR/shards/sK; the merge goes to DIR/merged.\n"
                     "See docs/scale-out.md." },
    { .name = "export", .fn = cli_export, .options = cli_export_options, .synopsis = "RUN --format FORMAT",
      .summary = "a run in a format other benchmark tools read (Google Benchmark, Bencher, ...)",
      .description = "RUN is a run directory, a results.json, or with --store a run id.\n"
                     "See docs/exports.md." },
    { .name = "history", .fn = cli_history, .options = cli_history_options, .synopsis = "[KEY...]",
      .summary = "a configuration's median across runs on this machine, with change points",
      .description = "Without KEY, every timed configuration of the run (--technique and --scene\n"
                     "narrow it).  Only runs with the same machine fingerprint are shown." },
    { .name = "list", .fn = cli_list, .options = cli_list_options, .pos_choices = cli_list_lists,
      .summary = "list the techniques, axes, counters, meshes, textures, built-in models or sweep-file keys",
      .synopsis = "techniques|axes|counters|meshes|textures|models|keys",
      .description = "Each list comes from its registry; --json prints it as a JSON array.\n"
                     "'keys' prints the sweep-file key reference of docs/sweep-files.md.\n"
                     "Counters show their availability on this driver (with a GL context)." },
    { .name = "info", .fn = cli_info, .options = cli_info_options,
      .summary = "the GL context, extensions, limits and whether GPUTime can be trusted" },
    { .name = "render", .fn = cli_render, .options = cli_render_options,
      .summary = "render one configuration to an image", .synopsis = "[KEY=VALUE...] --png FILE",
      .description = "KEY=VALUE sets any axis of `dmbench list axes`; the others keep their\n"
                     "defaults.  The image equals what a run of the same configuration stores." },
    { .name = "diff", .fn = cli_diff, .options = cli_diff_options, .synopsis = "REF TEST",
      .summary = "every image metric of two image files (RMSE, PSNR, SSIM, FLIP, ...), and the FLIP map",
      .description = "REF and TEST are any images OpenImageIO reads (PNG, EXR, ...), of the same\n"
                     "size.  Non-finite pixels are counted and said, and count as 0.  Exit 0, or 2\n"
                     "for an unreadable file or different sizes.  See docs/flip.md." },
    { .name = "drivers", .fn = cli_drivers, .options = cli_drivers_options, .synopsis = "[SWEEP]",
      .summary = "one sweep on several drivers, each in its own run, set side by side",
      .description = "Runs `dmbench run SWEEP` once per driver with DMBENCH_DRIVER set, into\n"
                     "OUT/DRIVER/, and writes OUT/drivers.md and drivers.json: per configuration\n"
                     "time, Instructions and SSIM on each driver, whether the drivers rank the\n"
                     "configurations alike (Kendall's tau), and each scene's Pareto front.  A\n"
                     "driver not installed is left out with the reason; a failed run is said and\n"
                     "the next driver runs.  Exit 0, 2 bad input (or no driver installed), 4 a\n"
                     "driver's run failed.  See docs/drivers.md." },
    { .name = "view", .fn = cli_view, .options = cli_view_options, .synopsis = "[KEY=VALUE...]",
      .summary = "look at a configuration live in a window (needs a display or xvfb-run)",
      .description = "Keys: 1-9/0 technique, [ ] tessellation level or steps, F filter, M mesh,\n"
                     "P spacing, H/Shift+H height scale, W wireframe, L light orbit, N normals,\n"
                     "C counters overlay, T timed test, S screenshot, R reset camera, ? help,\n"
                     "Esc quit; left drag orbits, right drag pans, wheel zooms (docs/viewer.md)." },
    { .name = "help", .fn = commands__help, .synopsis = "[COMMAND]",
      .summary = "this overview, or the help of one command" },
    { .name = "__instructions", .fn = commands__instructions, .flags = CLI_CMD_HIDDEN,
      .synopsis = "SWEEP HASH KEY...",
      .summary = "the Instructions pass's child, started under Valgrind by the runner" },
    { .name = "__gen-man", .fn = commands__gen_man, .flags = CLI_CMD_HIDDEN,
      .summary = "print the man page (build step)" },
    { .name = "__gen-completion", .fn = commands__gen_completion, .synopsis = "bash|zsh",
      .pos_choices = commands__shells, .flags = CLI_CMD_HIDDEN,
      .summary = "print a completion script (build step)" },
};
#define COMMANDS__N (sizeof commands__table / sizeof *commands__table)

size_t cli_commands_count(void) { return COMMANDS__N; }

const cli_command *cli_commands_at(size_t i) { return i < COMMANDS__N ? &commands__table[i] : NULL; }

const cli_command *cli_commands_find(const char *name)
{
    for (size_t i = 0; i < COMMANDS__N; i++)
        if (strcmp(commands__table[i].name, name) == 0)
            return &commands__table[i];
    return NULL;
}

/* The overview: commands, exit codes, where to read more. */
static void commands__overview(FILE *f)
{
    fprintf(f, "%s — performance and quality of surface-detail rendering techniques\n\n"
               "usage: dmbench COMMAND [ARGS] [OPTIONS]\n"
               "       dmbench COMMAND --help | dmbench help COMMAND | dmbench --version\n\n"
               "commands:\n", cli_version());
    for (size_t i = 0; i < COMMANDS__N; i++)
        if (!(commands__table[i].flags & CLI_CMD_HIDDEN))
            fprintf(f, "  %-10s %s\n", commands__table[i].name, commands__table[i].summary);
    fprintf(f, "\nexit codes:\n");
    for (int code = 0; dm_exit_meaning(code); code++)
        fprintf(f, "  %d  %s\n", code, dm_exit_meaning(code));
    fprintf(f, "\nDocumentation: man dmbench, README.md and docs/ in the source tree.\n");
}

/* "unknown command" with did you mean and the valid commands; exit 2. */
static int commands__unknown(const char *name)
{
    const char *names[COMMANDS__N];
    size_t n = 0;
    for (size_t i = 0; i < COMMANDS__N; i++)
        if (!(commands__table[i].flags & CLI_CMD_HIDDEN))
            names[n++] = commands__table[i].name;
    dm_str msg = {0};
    dm_str_printf(&msg, "unknown command '%s'", name);
    dm_str_suggest(&msg, name, names, n, "commands");
    int rc = cli_usage_error("%s", dm_str_get(&msg));
    dm_str_free(&msg);
    return rc;
}

static int commands__help(const cli_command *self, int argc, char **argv)
{
    int rc = cli_parse(self, argc, argv, NULL, &argc);
    if (rc >= 0)
        return rc;
    if (argc > 1)
        return cli_usage_error("help: one command at most ('%s' and '%s')", argv[0], argv[1]);
    if (argc == 0) {
        commands__overview(stdout);
        return DM_EXIT_OK;
    }
    const cli_command *c = cli_commands_find(argv[0]);
    if (!c)
        return commands__unknown(argv[0]);
    cli_command_help(c, stdout);
    return DM_EXIT_OK;
}

/* The Instructions pass's child (run/count_child.h), which parses its own
 * arguments. */
static int commands__instructions(const cli_command *self, int argc, char **argv)
{
    (void)self;
    return count_child_main(argc, argv);
}

static int commands__gen_man(const cli_command *self, int argc, char **argv)
{
    int rc = cli_parse(self, argc, argv, NULL, &argc);
    if (rc < 0 && argc)
        rc = cli_usage_error("__gen-man takes no arguments");
    if (rc >= 0)
        return rc;
    cli_gen_man(commands__table, COMMANDS__N, stdout);
    return DM_EXIT_OK;
}

static int commands__gen_completion(const cli_command *self, int argc, char **argv)
{
    int rc = cli_parse(self, argc, argv, NULL, &argc);
    if (rc < 0 && (argc != 1 || cli_gen_completion(argv[0], commands__table, COMMANDS__N, stdout) != 0))
        rc = cli_usage_error("__gen-completion: expected one of: bash, zsh");
    return rc >= 0 ? rc : DM_EXIT_OK;
}

/* The exit code rc, unless what the command printed could not be written
 * (stdout on a full disk, /dev/full, a closed descriptor): the output is
 * lost, so a command that had succeeded exits DM_EXIT_ENV with the reason
 * instead of 0. */
static int commands__flush(int rc)
{
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout))
        return rc;
    fprintf(stderr, "dmbench: error: cannot write the standard output (%s); what was printed "
            "is lost: free space, or send it elsewhere\n", errno ? strerror(errno) : "write error");
    return rc == DM_EXIT_OK ? DM_EXIT_ENV : rc;
}

int cli_main(int argc, char **argv)
{
    /* Over a file-size limit (ulimit -f) a write fails with EFBIG and is
     * reported like a full disk (exit 4, the store intact), instead of
     * SIGXFSZ killing the process mid-write; measuring processes inherit it. */
    signal(SIGXFSZ, SIG_IGN);
    if (argc < 2) {                    /* the overview, but a usage error */
        commands__overview(stdout);
        return DM_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        commands__overview(stdout);
        return DM_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("%s\n", cli_version());
        return DM_EXIT_OK;
    }
    dm_str derr = {0};
    int drc = drivers_enter(argv, &derr);   /* returns only when no re-exec is due */
    if (drc) {
        int code = cli_error(drc, "%s", dm_str_get(&derr));
        dm_str_free(&derr);
        return code;
    }
    if (callgrind_env_jobs(&derr) < 0 || probe_env_check(&derr) != 0) {
        int code = cli_error(DM_ERR_ARG, "%s", dm_str_get(&derr));
        dm_str_free(&derr);
        return code;
    }
    const cli_command *c = cli_commands_find(argv[1]);
    return commands__flush(c ? c->fn(c, argc - 1, argv + 1) : commands__unknown(argv[1]));
}
