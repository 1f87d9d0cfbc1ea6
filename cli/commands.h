/* commands.h — the command table of the dmbench command line and the
 * entry points it names.
 *
 * Only main.c, the table (commands.c) and the tests include this header:
 * a command never reaches the table (it gets its own row as `self`), so
 * the table is the one file that knows every command.  What the commands
 * share is cli.h. */
#ifndef CLI_COMMANDS_H
#define CLI_COMMANDS_H

#include <stddef.h>
#include "cli/cli.h"

/* One cmd_<name>.c each: the command and its option table. */
int cli_run(const cli_command *self, int argc, char **argv);
int cli_report(const cli_command *self, int argc, char **argv);
int cli_fit(const cli_command *self, int argc, char **argv);
int cli_predict(const cli_command *self, int argc, char **argv);
int cli_compare(const cli_command *self, int argc, char **argv);
int cli_baseline(const cli_command *self, int argc, char **argv);
int cli_merge(const cli_command *self, int argc, char **argv);
int cli_slurm(const cli_command *self, int argc, char **argv);
int cli_export(const cli_command *self, int argc, char **argv);
int cli_history(const cli_command *self, int argc, char **argv);
int cli_list(const cli_command *self, int argc, char **argv);
int cli_info(const cli_command *self, int argc, char **argv);
int cli_render(const cli_command *self, int argc, char **argv);
int cli_diff(const cli_command *self, int argc, char **argv);
int cli_drivers(const cli_command *self, int argc, char **argv);
int cli_view(const cli_command *self, int argc, char **argv);
extern const cli_option cli_run_options[], cli_report_options[], cli_fit_options[],
    cli_predict_options[], cli_compare_options[], cli_baseline_options[], cli_list_options[],
    cli_info_options[], cli_render_options[], cli_diff_options[], cli_drivers_options[],
    cli_view_options[], cli_merge_options[], cli_slurm_options[], cli_export_options[],
    cli_history_options[];
/* A command's positional choices (completion). */
extern const char *const cli_list_lists[], *const cli_baseline_actions[], *const cli_export_formats[];

/* The command table, in help order, hidden ones included. */
size_t cli_commands_count(void);
const cli_command *cli_commands_at(size_t i);
/* The command called name, or NULL. */
const cli_command *cli_commands_find(const char *name);
/* Runs `dmbench argv[1] ...`; returns the process exit code. */
int cli_main(int argc, char **argv);

#endif
