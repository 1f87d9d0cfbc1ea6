/* cli.h — the commands of the dmbench CLI; each returns a process exit code
 * (0 ok, 1 check failed, 2 bad input, 3 inconclusive).  argv[0] is the
 * command name. */
#ifndef HARNESS_CLI_H
#define HARNESS_CLI_H

#include <stddef.h>

#include "core/dm_util.h"

int cli_run(int argc, char **argv);
int cli_report(int argc, char **argv);
int cli_fit(int argc, char **argv);
int cli_list(int argc, char **argv);
int cli_info(int argc, char **argv);
int cli_render(int argc, char **argv);
int cli_compare(int argc, char **argv);   /* cmd_compare.c */
int cli_baseline(int argc, char **argv);  /* cmd_compare.c */
int cli_merge(int argc, char **argv);
int cli_view(int argc, char **argv);      /* cmd_view.c */

/* Shared helpers (cli.c). */
/* Prints "dmbench: error: <msg>" and returns 2. */
int cli__usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Rejects an unknown option, listing the valid ones; returns 2. */
int cli__unknown_option(const char *cmd, const char *opt, const char *const *valid, size_t n);
/* Loads the run of a run directory (the store in the directory above it)
 * into *run after checking that the store exists (nothing is created) and is
 * intact.  Returns 0, or DM_ERR_ARG (not a run directory, run not in the
 * store) / DM_ERR_STORE (damaged or unreadable store) with the message in
 * err; dm_exit_code() gives the exit code. */
struct dm_run_result;
int cli__load_run(const char *dir, struct dm_run_result *run, dm_str *err);
/* Value of "--opt VALUE": advances *i; NULL (after printing) when missing. */
const char *cli__value(int argc, char **argv, int *i);

#endif
