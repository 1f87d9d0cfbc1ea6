/* cli.h — what every command of the dmbench command line shares: the
 * command row, the option parser driven by it, help and error messages.
 *
 * The command table (commands.h, commands.c) lists every command: its name,
 * its function, a one-line summary, the positional synopsis, a description
 * and its option table (options.h).  main() dispatches through it, and
 * help, `dmbench help CMD`, the man page and the bash/zsh completions
 * (gen.h) are generated from it, so none of them can drift from what the
 * parser takes.  The table calls the commands and the commands call only
 * this header's functions (cli.c), never the table: a command gets its own
 * row as `self` and hands it to cli_parse.
 *
 * Adding a command `dmbench foo`:
 *   1. cli/cmd_foo.c: `typedef struct foo_args {...} foo_args;`, the table
 *      `const cli_option cli_foo_options[] = { { .name = "out", .kind =
 *      CLI_OPT_STRING, .offset = offsetof(foo_args, out), .value_name =
 *      "DIR", .help = "..." }, ..., CLI_OPT_END };` and
 *          int cli_foo(const cli_command *self, int argc, char **argv)
 *          {
 *              foo_args a = {0};
 *              int rc = cli_parse(self, argc, argv, &a, &argc);
 *              if (rc >= 0)
 *                  return rc;
 *              ... argv[0..argc) are now the positional arguments ...
 *   2. Its declarations in commands.h, a row in the table of
 *      cli/commands.c, and cmd_foo.c in cli/CMakeLists.txt.
 *   3. Its options in the expected lists of tests/cli/options.sh.
 * Value checks beyond the kinds go in a cli_opt_parse_fn beside the table.
 * A command returns a dm_exit code (core/dm_exit.h); errors are printed as
 * "dmbench: error: <command>: ..." (cli_usage_error).
 */
#ifndef CLI_CLI_H
#define CLI_CLI_H

#include <stddef.h>
#include "cli/options.h"

typedef struct cli_command cli_command;

/* self is the command's row of the table; argv[0] is the command name.
 * Returns a dm_exit code. */
typedef int (*cli_command_fn)(const cli_command *self, int argc, char **argv);

enum { CLI_CMD_HIDDEN = 1 };   /* not in help, man page or completion */

struct cli_command {
    const char *name;
    cli_command_fn fn;
    const cli_option *options;    /* ends with CLI_OPT_END; NULL for none */
    const char *summary;          /* one line, lower case, no full stop */
    const char *synopsis;         /* positionals; '\n' between alternative forms */
    const char *description;      /* more text for help and the man page, or NULL */
    const char *const *pos_choices;/* first positional's choices (completion), or NULL */
    unsigned flags;
};

#include "core/dm_util.h"

/* `dmbench drivers` on sweep_path (NULL: the default sweep) with --drivers
 * list (NULL: the sweep's `drivers:`, else every installed driver) and
 * --interleave shards (0: the default); `run` calls it for a sweep with
 * `drivers:`.  Its runs have CLI_DRIVERS_CHILD set. */
int cli_drivers_main(const char *sweep_path, const char *list, const char *out, const char *seed,
                     int quiet, int interleave);
#define CLI_DRIVERS_CHILD "DMBENCH_DRIVERS_CHILD"
/* `run SWEEP --dry-run` for a sweep with `drivers:`: each driver's plan, in
 * a run under that driver (a driver not installed is printed as left out
 * with the reason); returns the worst exit status of the plans. */
struct sweep;
int cli_drivers_dry_run(const char *sweep_path, const struct sweep *s, const char *out);
/* `dmbench merge OUT DIR...` (slurm --collect calls it too): merges the
 * runs of the n run directories dirs into OUT; allow_missing as
 * --allow-missing.  Returns a dm_exit code. */
int cli_merge_dirs(const char *out, char **dirs, int n, int allow_missing);

/* Parses the options of command self (from its table) into args, which
 * the caller zeroed; argv[0] is the command's name.  Returns -1 to go on,
 * with the positional arguments moved to argv[0..*n_pos); DM_EXIT_OK after
 * printing --help; DM_EXIT_USAGE after printing an error. */
int cli_parse(const cli_command *self, int argc, char **argv, void *args, int *n_pos);

/* `dmbench CMD --help` of one command, to f. */
void cli_command_help(const cli_command *c, FILE *f);
/* The version line: "dmbench 0.1.0 (git <rev>)". */
const char *cli_version(void);

/* Prints "dmbench: error: <msg>" (control bytes as '?') and returns DM_EXIT_USAGE. */
int cli_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Prints "dmbench: error: <msg>" and returns the exit code of a failure
 * that err (a DM_ERR_* code) caused: DM_EXIT_ENV for what
 * dm_exit_from_error calls the machine's (a damaged, newer or full store,
 * an output in use, a disk full, an allocation refused, no usable GL,
 * children that keep dying), DM_EXIT_USAGE for everything else, so one
 * condition has one exit code whichever command meets it
 * (docs/reliability.md). */
int cli_error(int err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Loads the run of a run directory (the store in the directory above it)
 * into *run after checking that the store exists (nothing is created) and is
 * intact.  Returns 0, or DM_ERR_ARG (not a run directory, run not in the
 * store) / DM_ERR_STORE (damaged or unreadable store) with the message in
 * err; dm_exit_from_error() gives the exit code. */
struct dm_run_result;
/* A run directory's store (the dmbench.sqlite in the directory above it)
 * and run id (its name), both malloc'd.  Returns 0, or DM_ERR_ARG with the
 * message in err: no such directory, no store beside it, or a results root
 * given where one of its runs is meant (the message names DIR/latest). */
int cli_run_locate(const char *dir, char **store_path, char **run_id, dm_str *err);
int cli_load_run(const char *dir, struct dm_run_result *run, dm_str *err);

#endif
