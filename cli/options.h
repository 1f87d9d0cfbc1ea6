/* options.h — one option table per command, driving parsing, help, the man
 * page, shell completion and "did you mean".
 *
 * A command's options are a static table of cli_option rows ending with
 * CLI_OPT_END.  Each row names a long option, its kind, where the value goes
 * (an offset into the command's zero-initialised args struct), a value name
 * and a help line.  Because the table is data, `dmbench CMD --help`,
 * `dmbench help CMD`, the "valid options" list of an error, the generated
 * man page and the bash/zsh completions all come from the same rows and
 * cannot drift from what the parser accepts.
 *
 * Conversions by kind (a `parse` function replaces them):
 *   BOOL    no value; sets an int to 1
 *   STRING  const char * pointing into argv (nargs > 1: an array of them)
 *   INT     int; a whole number, within [min, max] when min < max
 *   UINT64  uint64_t; a non-negative whole number
 *   DOUBLE  double; within [min, max] when min < max
 *   CHOICE  int = index of the value in `choices`
 * `def` is the default as text: it is converted like a given value before
 * parsing (so the struct holds it) and shown in the help.
 */
#ifndef CLI_OPTIONS_H
#define CLI_OPTIONS_H

#include <stddef.h>
#include <stdio.h>
#include "core/dm_util.h"

typedef enum cli_opt_kind {
    CLI_OPT__END = 0,
    CLI_OPT_BOOL,
    CLI_OPT_STRING,
    CLI_OPT_INT,
    CLI_OPT_UINT64,
    CLI_OPT_DOUBLE,
    CLI_OPT_CHOICE
} cli_opt_kind;

typedef struct cli_option cli_option;

/* Converts and checks a value, writing into args (the whole args struct, so
 * an option may fill several fields or append to an array).  Returns 0, or
 * a DM_ERR_* with a message in err that follows "<command>: " — by
 * convention "--name 'value': expected ...". */
typedef int (*cli_opt_parse_fn)(const cli_option *opt, const char *value, void *args, dm_str *err);

struct cli_option {
    const char *name;                /* long name without the dashes: "out" */
    char short_name;                 /* 'o' for -o, or 0 */
    cli_opt_kind kind;
    size_t offset;                   /* of the destination in the args struct */
    const char *value_name;          /* "DIR"; FILE/DIR in it → file completion */
    const char *help;                /* one line */
    const char *const *choices;      /* CHOICE (NULL-terminated); else a completion hint */
    const char *def;                 /* default as text, or NULL */
    double min, max;                 /* INT/DOUBLE range when min < max */
    int nargs;                       /* STRING: values taken (0 means 1) */
    int repeat;                      /* 1: collects every use (else the last wins) */
    cli_opt_parse_fn parse;          /* replaces the conversion by kind */
};

#define CLI_OPT_END { 0 }
/* Rows for the two common cases, as git's OPT_BOOL and OPT_STRING: a flag
 * that sets an int field of the args struct T, and a string field. */
#define CLI_BOOL(name_, T, field, help_) \
    { .name = (name_), .kind = CLI_OPT_BOOL, .offset = offsetof(T, field), .help = (help_) }
#define CLI_STRING(name_, T, field, value_name_, help_)                           \
    { .name = (name_), .kind = CLI_OPT_STRING, .offset = offsetof(T, field), \
      .value_name = (value_name_), .help = (help_) }

/* Number of rows before CLI_OPT_END. */
size_t cli_options_count(const cli_option *opts);
/* The row for "--name" (or "-c" for a short name), or NULL. */
const cli_option *cli_options_find(const cli_option *opts, const char *arg);
/* Whether the option takes a value on the command line. */
int cli_option_takes_value(const cli_option *opt);
/* "--out DIR" (with the value names of nargs > 1) into s. */
void cli_option_label(const cli_option *opt, dm_str *s);

/* The index of v in opt->choices, or DM_ERR_ARG and "--name 'v': expected
 * one of: a, b (did you mean 'a'?)" in err.  For parse functions of choices
 * that map to something other than their index. */
int cli_option_choice(const cli_option *opt, const char *v, int *index, dm_str *err);

/* Parses argv[1..argc) of command `cmd` against opts into args (zeroed by
 * the caller; defaults are filled first).  Arguments that are not options
 * ("-" alone, anything after "--", anything not starting with '-') are moved,
 * in order, to argv[0..*n_pos).  -h/--help sets *want_help.  Returns 0, or
 * DM_EXIT_USAGE after printing "dmbench: error: <cmd>: ..." (an unknown
 * option with "did you mean" and the valid options, a missing or invalid
 * value). */
int cli_options_parse(const char *cmd, const cli_option *opts, int argc, char **argv, void *args,
                      int *n_pos, int *want_help);

/* Prints the option list ("  -o, --out DIR   help (default x)") to f. */
void cli_options_print(const cli_option *opts, FILE *f);

#endif
