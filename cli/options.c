/* options.c — the table-driven option parser and the option help. */
#include "options.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

size_t cli_options_count(const cli_option *opts)
{
    size_t n = 0;
    while (opts && opts[n].kind != CLI_OPT__END)
        n++;
    return n;
}

const cli_option *cli_options_find(const cli_option *opts, const char *arg)
{
    for (size_t i = 0; opts && opts[i].kind != CLI_OPT__END; i++) {
        const cli_option *o = &opts[i];
        if (arg[0] == '-' && arg[1] == '-' && strcmp(arg + 2, o->name) == 0)
            return o;
        if (o->short_name && arg[0] == '-' && arg[1] == o->short_name && !arg[2])
            return o;
    }
    return NULL;
}

int cli_option_takes_value(const cli_option *opt)
{
    return opt->kind != CLI_OPT_BOOL;
}

void cli_option_label(const cli_option *opt, dm_str *s)
{
    dm_str_printf(s, "--%s", opt->name);
    if (!cli_option_takes_value(opt))
        return;
    dm_str_printf(s, " %s", opt->value_name ? opt->value_name : "VALUE");
}

/* A number (a whole one for INT), within [min, max] when min < max.
 * 0 and *out, or DM_ERR_ARG with "--name 'v': expected ..." in err. */
static int options__number(const cli_option *o, const char *v, double *out, dm_str *err)
{
    int whole = o->kind == CLI_OPT_INT, ranged = o->min < o->max;
    char *end = NULL;
    errno = 0;
    double x = whole ? (double)strtol(v, &end, 10) : strtod(v, &end);
    int ok = *v && !*end && errno == 0 && isfinite(x) && !(ranged && (x < o->min || x > o->max));
    if (ok && whole && (x < INT32_MIN || x > INT32_MAX))
        ok = 0;
    if (!ok) {
        dm_str_printf(err, "--%s '%s': expected %s", o->name, v, whole ? "an integer" : "a number");
        if (ranged)
            dm_str_printf(err, whole ? " in %.0f..%.0f" : " in %g..%g", o->min, o->max);
        return DM_ERR_ARG;
    }
    *out = x;
    return 0;
}

static int options__uint64(const cli_option *o, const char *v, void *dst, dm_str *err)
{
    char *end = NULL;
    errno = 0;
    unsigned long long x = strtoull(v, &end, 10);
    if (!*v || *end || errno != 0 || v[0] == '-') {
        dm_str_printf(err, "--%s '%s': expected a non-negative integer", o->name, v);
        return DM_ERR_ARG;
    }
    *(uint64_t *)dst = (uint64_t)x;
    return 0;
}

int cli_option_choice(const cli_option *o, const char *v, int *dst, dm_str *err)
{
    size_t n = 0;
    for (; o->choices && o->choices[n]; n++)
        if (strcmp(o->choices[n], v) == 0) {
            *(int *)dst = (int)n;
            return 0;
        }
    dm_str_printf(err, "--%s '%s': ", o->name, v);
    dm_str_expected(err, v, o->choices, n);
    return DM_ERR_ARG;
}

/* Stores the value(s) of one option; 0 or DM_ERR_* with the message in err. */
static int options__store(const cli_option *o, const char *const *v, void *args, dm_str *err)
{
    void *dst = (char *)args + o->offset;
    if (o->parse)
        return o->parse(o, v[0], args, err);
    switch (o->kind) {
    case CLI_OPT_BOOL:
        *(int *)dst = 1;
        return 0;
    case CLI_OPT_STRING:
        for (int k = 0; k < (o->nargs > 1 ? o->nargs : 1); k++)
            ((const char **)dst)[k] = v[k];
        return 0;
    case CLI_OPT_INT:
    case CLI_OPT_DOUBLE: {
        double x = 0;
        int rc = options__number(o, v[0], &x, err);
        if (rc == 0 && o->kind == CLI_OPT_INT)
            *(int *)dst = (int)x;
        else if (rc == 0)
            *(double *)dst = x;
        return rc;
    }
    case CLI_OPT_UINT64: return options__uint64(o, v[0], dst, err);
    case CLI_OPT_CHOICE: return cli_option_choice(o, v[0], dst, err);
    case CLI_OPT__END: break;
    }
    return DM_ERR_ARG;
}

/* Prints "dmbench: error: <cmd>: <msg>"; returns DM_EXIT_USAGE. */
static int options__fail(const char *cmd, const dm_str *msg)
{
    fprintf(stderr, "dmbench: error: %s: %s\n", cmd, dm_str_get(msg));
    return DM_EXIT_USAGE;
}

/* The "unknown option" error: did you mean, and every valid option. */
static int options__unknown(const char *cmd, const cli_option *opts, const char *arg)
{
    size_t n = cli_options_count(opts);
    const char **names = dm_xcalloc(n + 1, sizeof *names);
    char **owned = dm_xcalloc(n + 1, sizeof *owned);
    for (size_t i = 0; i < n; i++)
        names[i] = owned[i] = dm_xasprintf("--%s", opts[i].name);
    names[n] = "--help";
    dm_str msg = {0};
    const char *eq = strchr(arg, '=');
    char *word = eq ? dm_xasprintf("%.*s", (int)(eq - arg), arg) : dm_xstrdup(arg);
    dm_str_printf(&msg, "unknown option '%s'", word);
    dm_str_suggest(&msg, word, names, n + 1, "options");
    int rc = options__fail(cmd, &msg);
    dm_str_free(&msg);
    free(word);
    for (size_t i = 0; i < n; i++)
        free(owned[i]);
    free(owned);
    free(names);
    return rc;
}

/* Fills in every default; the table's defaults must convert (asserted by
 * the option tests, which parse no arguments for every command). */
static int options__defaults(const char *cmd, const cli_option *opts, void *args)
{
    for (size_t i = 0; opts && opts[i].kind != CLI_OPT__END; i++) {
        if (!opts[i].def)
            continue;
        dm_str err = {0};
        const char *v[1] = { opts[i].def };
        int rc = options__store(&opts[i], v, args, &err);
        if (rc != 0) {
            options__fail(cmd, &err);
            dm_str_free(&err);
            return DM_EXIT_USAGE;
        }
    }
    return 0;
}

/* One option at argv[*i] (value after '=' or in the next arguments);
 * advances *i past its values.  0 or DM_EXIT_USAGE (printed). */
static int options__one(const char *cmd, const cli_option *o, int argc, char **argv, int *i, void *args)
{
    const char *eq = strchr(argv[*i], '=');
    int nargs = o->kind == CLI_OPT_STRING && o->nargs > 1 ? o->nargs : 1;
    const char *vals[8] = { NULL };
    dm_str err = {0};
    if (!cli_option_takes_value(o) && eq) {
        dm_str_printf(&err, "--%s takes no value ('%s')", o->name, argv[*i]);
    } else if (eq && nargs > 1) {
        dm_str_printf(&err, "--%s takes %s as separate arguments, not after '='", o->name,
                      o->value_name ? o->value_name : "its values");
    } else if (eq) {
        vals[0] = eq + 1;
    } else if (cli_option_takes_value(o)) {
        if (*i + nargs >= argc || nargs > 8)
            dm_str_printf(&err, "--%s needs %s", o->name,
                          nargs > 1 && o->value_name ? o->value_name : "a value");
        for (int k = 0; !err.len && k < nargs; k++)
            vals[k] = argv[++*i];
    }
    int rc = err.len ? DM_ERR_ARG : options__store(o, vals, args, &err);
    if (rc != 0)
        rc = options__fail(cmd, &err);
    dm_str_free(&err);
    return rc;
}

int cli_options_parse(const char *cmd, const cli_option *opts, int argc, char **argv, void *args,
                      int *n_pos, int *want_help)
{
    int rc = options__defaults(cmd, opts, args), only_pos = 0;
    *n_pos = 0;
    for (int i = 1; rc == 0 && i < argc; i++) {
        char *a = argv[i];
        if (only_pos || a[0] != '-' || !a[1]) {
            argv[(*n_pos)++] = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            only_pos = 1;
            continue;
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            *want_help = 1;
            continue;
        }
        char name[128];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(a, "="), a);
        const cli_option *o = cli_options_find(opts, name);
        rc = o ? options__one(cmd, o, argc, argv, &i, args) : options__unknown(cmd, opts, a);
    }
    return rc;
}

void cli_options_print(const cli_option *opts, FILE *f)
{
    for (size_t i = 0; opts && opts[i].kind != CLI_OPT__END; i++) {
        const cli_option *o = &opts[i];
        dm_str label = {0};
        if (o->short_name)
            dm_str_printf(&label, "-%c, ", o->short_name);
        cli_option_label(o, &label);
        if (label.len > 28)     /* a long label gets a line of its own */
            fprintf(f, "  %s\n  %-28s %s", dm_str_get(&label), "", o->help ? o->help : "");
        else
            fprintf(f, "  %-28s %s", dm_str_get(&label), o->help ? o->help : "");
        if (o->kind == CLI_OPT_CHOICE && o->choices) {
            fputs(" (", f);
            for (size_t k = 0; o->choices[k]; k++)
                fprintf(f, "%s%s", k ? "|" : "", o->choices[k]);
            fputc(')', f);
        }
        if (o->def)
            fprintf(f, " [default %s]", o->def);
        fputc('\n', f);
        dm_str_free(&label);
    }
    fprintf(f, "  %-28s %s\n", "-h, --help", "this help");
}
