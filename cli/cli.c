/* cli.c — what every command shares (cli.h): the option parser driven by
 * the command's row, its help, the error messages and the version line.
 * Nothing here knows the command table. */
#include "cli.h"
#include "core/dm_exit.h"

#include <stdarg.h>
#include <string.h>

#ifndef DM_GIT_REV
#define DM_GIT_REV "unknown"
#endif
#ifndef DM_VERSION
#define DM_VERSION "0.0.0"
#endif

const char *cli_version(void)
{
    return "dmbench " DM_VERSION " (git " DM_GIT_REV ")";
}

/* "dmbench: error: " + the message + newline on stderr, control bytes of
 * the message (a path or a value the user gave) shown as '?'. */
static void cli__verror(const char *fmt, va_list ap)
{
    dm_str msg = {0}, safe = {0};
    dm_str_vprintf(&msg, fmt, ap);
    dm_str_cat_term(&safe, dm_str_get(&msg));
    fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&safe));
    dm_str_free(&msg);
    dm_str_free(&safe);
}

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cli__verror(fmt, ap);
    va_end(ap);
    return DM_EXIT_USAGE;
}

int cli_error(int err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cli__verror(fmt, ap);
    va_end(ap);
    return dm_exit_from_error(err) == DM_EXIT_ENV ? DM_EXIT_ENV : DM_EXIT_USAGE;
}

/* "usage: dmbench NAME SYNOPSIS [OPTIONS]", one line per form. */
static void cli__usage(const cli_command *c, FILE *f)
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
    cli__usage(c, f);
    fprintf(f, "\n%s.\n", c->summary);
    if (c->description)
        fprintf(f, "\n%s\n", c->description);
    fprintf(f, "\noptions:\n");
    cli_options_print(c->options, f);
}

int cli_parse(const cli_command *self, int argc, char **argv, void *args, int *n_pos)
{
    int want_help = 0;
    int rc = cli_options_parse(self->name, self->options, argc, argv, args, n_pos, &want_help);
    if (rc == 0 && want_help)
        cli_command_help(self, stdout);
    return rc != 0 || want_help ? rc : -1;
}
