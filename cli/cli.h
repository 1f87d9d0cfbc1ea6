/* cli.h — the commands of the dmbench command line.
 *
 * Each command is one cli_command in its own cli/cmd_<name>.c: a name, a
 * one-line summary, the positional synopsis, an option table (options.h)
 * and a function.  cli/commands.c lists them in one table and main()
 * dispatches through it: it parses the options into a zeroed args struct of
 * args_size bytes, answers --help, and calls fn with the struct and the
 * positional arguments.  Help, `dmbench help CMD`, the man page and the
 * bash/zsh completions are generated from the same table.
 *
 * Adding a command `dmbench foo`:
 *   1. cli/cmd_foo.c: a `typedef struct foo_args {...} foo_args;`, a
 *      `static const cli_option foo_options[] = { {.name = "out", .kind =
 *      CLI_OPT_STRING, .offset = offsetof(foo_args, out), .value_name =
 *      "DIR", .help = "..."}, ..., CLI_OPT_END };`, a
 *      `static int foo_main(void *args, int argc, char **argv)` (argv holds
 *      only the positional arguments) and
 *      `const cli_command cli_cmd_foo = { .name = "foo", .fn = foo_main,
 *      .summary = "...", .synopsis = "ARG...", .options = foo_options,
 *      .args_size = sizeof(foo_args) };`.
 *   2. `extern const cli_command cli_cmd_foo;` below and `&cli_cmd_foo` in
 *      the table of cli/commands.c; cmd_foo.c in cli/CMakeLists.txt.
 *   3. Add its options to the expected lists in tests/cli/options.sh.
 * Value checks beyond the kinds go in a cli_opt_parse_fn beside the table.
 * A command returns a dm_exit code (core/dm_exit.h); errors are printed as
 * "dmbench: error: <command>: ..." (cli_usage_error).
 */
#ifndef CLI_CLI_H
#define CLI_CLI_H

#include <stddef.h>
#include "cli/options.h"

/* fn: args is the parsed args struct, argv[0..argc) the positional
 * arguments.  Returns a dm_exit code. */
typedef int (*cli_command_fn)(void *args, int argc, char **argv);

enum { CLI_CMD_HIDDEN = 1 };   /* not in help, man page or completion */

typedef struct cli_command {
    const char *name;
    cli_command_fn fn;
    const char *summary;          /* one line, lower case, no full stop */
    const char *synopsis;         /* positionals; '\n' between alternative forms */
    const char *description;      /* more text for help and the man page, or NULL */
    const cli_option *options;    /* ends with CLI_OPT_END; NULL for none */
    size_t args_size;             /* of the struct the options fill (0: none) */
    void (*free_args)(void *args);/* frees what option parse functions allocated */
    const char *const *pos_choices;/* first positional's choices (completion), or NULL */
    unsigned flags;
} cli_command;

extern const cli_command cli_cmd_run, cli_cmd_report, cli_cmd_fit, cli_cmd_compare,
    cli_cmd_baseline, cli_cmd_merge, cli_cmd_list, cli_cmd_info, cli_cmd_render, cli_cmd_view;

/* The command table (commands.c), in help order, hidden ones included. */
size_t cli_commands_count(void);
const cli_command *cli_commands_at(size_t i);
/* The command called name, or NULL. */
const cli_command *cli_commands_find(const char *name);
/* Runs `dmbench argv[1] ...`; returns the process exit code. */
int cli_main(int argc, char **argv);
/* `dmbench CMD --help` of one command, to f. */
void cli_command_help(const cli_command *c, FILE *f);
/* The version line: "dmbench 0.1.0 (git <rev>)". */
const char *cli_version(void);

/* Generated documents (gen.c): the man page and completion scripts. */
void cli_gen_man(FILE *f);
/* shell: "bash" or "zsh"; DM_ERR_ARG for another. */
int cli_gen_completion(const char *shell, FILE *f);

/* Prints "dmbench: error: <msg>" and returns DM_EXIT_USAGE. */
int cli_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
