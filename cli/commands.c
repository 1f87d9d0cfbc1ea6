/* commands.c — the command table, dispatch, help and --version. */
#include "cli.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#ifndef DM_GIT_REV
#define DM_GIT_REV "unknown"
#endif
#ifndef DM_VERSION
#define DM_VERSION "0.0.0"
#endif

static int commands__help(void *args, int argc, char **argv);
static int commands__gen_man(void *args, int argc, char **argv);
static int commands__gen_completion(void *args, int argc, char **argv);

static const cli_command cli_cmd_help = {
    .name = "help", .fn = commands__help, .summary = "this overview, or the help of one command",
    .synopsis = "[COMMAND]",
};
static const cli_command cli_cmd_gen_man = {
    .name = "__gen-man", .fn = commands__gen_man, .summary = "print the man page (build step)",
    .flags = CLI_CMD_HIDDEN,
};
static const char *const commands__shells[] = { "bash", "zsh", NULL };
static const cli_command cli_cmd_gen_completion = {
    .name = "__gen-completion", .fn = commands__gen_completion,
    .summary = "print a completion script (build step)", .synopsis = "bash|zsh",
    .pos_choices = commands__shells, .flags = CLI_CMD_HIDDEN,
};

/* The one list of commands, in the order help shows them. */
static const cli_command *const commands[] = {
    &cli_cmd_run, &cli_cmd_report, &cli_cmd_fit, &cli_cmd_compare, &cli_cmd_baseline,
    &cli_cmd_merge, &cli_cmd_list, &cli_cmd_info, &cli_cmd_render, &cli_cmd_view,
    &cli_cmd_help, &cli_cmd_gen_man, &cli_cmd_gen_completion,
};
#define COMMANDS__N (sizeof commands / sizeof *commands)

size_t cli_commands_count(void) { return COMMANDS__N; }

const cli_command *cli_commands_at(size_t i) { return i < COMMANDS__N ? commands[i] : NULL; }

const cli_command *cli_commands_find(const char *name)
{
    for (size_t i = 0; i < COMMANDS__N; i++)
        if (strcmp(commands[i]->name, name) == 0)
            return commands[i];
    return NULL;
}

const char *cli_version(void)
{
    return "dmbench " DM_VERSION " (git " DM_GIT_REV ")";
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "dmbench: error: ");
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return DM_EXIT_USAGE;
}

/* "usage: dmbench NAME SYNOPSIS [OPTIONS]", one line per form. */
static void commands__usage(const cli_command *c, FILE *f)
{
    const char *s = c->synopsis ? c->synopsis : "";
    int has_opts = cli_options_count(c->options) > 0;
    for (int first = 1;; first = 0) {
        size_t len = strcspn(s, "\n");
        fprintf(f, "%s dmbench %s%s%.*s%s\n", first ? "usage:" : "   or:", c->name,
                len ? " " : "", (int)len, s, first && has_opts ? " [OPTIONS]" : "");
        if (!s[len])
            break;
        s += len + 1;
    }
}

void cli_command_help(const cli_command *c, FILE *f)
{
    commands__usage(c, f);
    fprintf(f, "\n%s.\n", c->summary);
    if (c->description)
        fprintf(f, "\n%s\n", c->description);
    fprintf(f, "\noptions:\n");
    cli_options_print(c->options, f);
}

/* The overview: commands, exit codes, where to read more. */
static void commands__overview(FILE *f)
{
    fprintf(f, "%s — performance and quality of surface-detail rendering techniques\n\n"
               "usage: dmbench COMMAND [ARGS] [OPTIONS]\n"
               "       dmbench COMMAND --help | dmbench help COMMAND | dmbench --version\n\n"
               "commands:\n", cli_version());
    for (size_t i = 0; i < COMMANDS__N; i++)
        if (!(commands[i]->flags & CLI_CMD_HIDDEN))
            fprintf(f, "  %-10s %s\n", commands[i]->name, commands[i]->summary);
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
        if (!(commands[i]->flags & CLI_CMD_HIDDEN))
            names[n++] = commands[i]->name;
    dm_str msg = {0};
    dm_str_printf(&msg, "unknown command '%s'", name);
    dm_str_suggest(&msg, name, names, n, "commands");
    int rc = cli_usage_error("%s", dm_str_get(&msg));
    dm_str_free(&msg);
    return rc;
}

static int commands__help(void *args, int argc, char **argv)
{
    (void)args;
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

static int commands__gen_man(void *args, int argc, char **argv)
{
    (void)args;
    (void)argv;
    if (argc)
        return cli_usage_error("__gen-man takes no arguments");
    cli_gen_man(stdout);
    return DM_EXIT_OK;
}

static int commands__gen_completion(void *args, int argc, char **argv)
{
    (void)args;
    if (argc != 1 || cli_gen_completion(argv[0], stdout) != 0)
        return cli_usage_error("__gen-completion: expected one of: bash, zsh");
    return DM_EXIT_OK;
}

/* Parses the options of c and runs it. */
static int commands__run(const cli_command *c, int argc, char **argv)
{
    void *args = dm_xcalloc(1, c->args_size ? c->args_size : 1);
    int n_pos = 0, want_help = 0;
    int rc = cli_options_parse(c->name, c->options, argc, argv, args, &n_pos, &want_help);
    if (rc == 0 && want_help)
        cli_command_help(c, stdout);
    else if (rc == 0)
        rc = c->fn(args, n_pos, argv);
    if (c->free_args)
        c->free_args(args);
    free(args);
    return rc;
}

int cli_main(int argc, char **argv)
{
    if (argc < 2) {                    /* the overview, but a usage error */
        commands__overview(stdout);
        return DM_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)
        return commands__help(NULL, 0, NULL);
    if (strcmp(argv[1], "--version") == 0) {
        printf("%s\n", cli_version());
        return DM_EXIT_OK;
    }
    const cli_command *c = cli_commands_find(argv[1]);
    return c ? commands__run(c, argc - 1, argv + 1) : commands__unknown(argv[1]);
}
