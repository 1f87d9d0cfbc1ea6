/* Unit tests of cli/options.c (the table-driven parser) and the command
 * table's invariants. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/dm_exit.h"
#include "core/dm_util.h"
#include "imaging/flip.h"

typedef struct t_args {
    int flag, num, choice;
    const char *name, *three[3];
    uint64_t big;
    double real;
} t_args;

static const char *const t_choices[] = { "alpha", "beta", "gamma", NULL };

static const cli_option t_options[] = {
    { .name = "flag", .short_name = 'f', .kind = CLI_OPT_BOOL, .offset = offsetof(t_args, flag), .help = "f" },
    { .name = "name", .kind = CLI_OPT_STRING, .offset = offsetof(t_args, name), .value_name = "N", .help = "n" },
    { .name = "num", .kind = CLI_OPT_INT, .offset = offsetof(t_args, num), .value_name = "K",
      .min = 1, .max = 8, .def = "3", .help = "k" },
    { .name = "big", .kind = CLI_OPT_UINT64, .offset = offsetof(t_args, big), .value_name = "B", .help = "b" },
    { .name = "real", .kind = CLI_OPT_DOUBLE, .offset = offsetof(t_args, real), .value_name = "R", .help = "r" },
    { .name = "pick", .kind = CLI_OPT_CHOICE, .offset = offsetof(t_args, choice), .value_name = "C",
      .choices = t_choices, .def = "beta", .help = "c" },
    { .name = "three", .kind = CLI_OPT_STRING, .offset = offsetof(t_args, three), .nargs = 3,
      .value_name = "A B C", .help = "3" },
    CLI_OPT_END
};

/* Parses a NULL-terminated argument list (argv[0] = "t"); the stderr text
 * goes to err (at most n bytes). */
static int t_parse(t_args *a, int *n_pos, char **pos, int *help, char *err, size_t n, ...)
{
    static char *argv[32];
    va_list ap;
    va_start(ap, n);
    int argc = 0;
    argv[argc++] = "t";
    for (char *s; (s = va_arg(ap, char *));)
        argv[argc++] = s;
    va_end(ap);
    fflush(stderr);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    memset(a, 0, sizeof *a);
    int rc = cli_options_parse("t", t_options, argc, argv, a, n_pos, help);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(tmp);
    size_t got = fread(err, 1, n - 1, tmp);
    err[got] = '\0';
    fclose(tmp);
    for (int i = 0; i < *n_pos; i++)
        pos[i] = argv[i];
    return rc;
}

static void test_kinds_and_positionals(void **state)
{
    (void)state;
    t_args a;
    int n = 0, help = 0;
    char *pos[32], err[1024];
    int rc = t_parse(&a, &n, pos, &help, err, sizeof err, "x", "-f", "--name=v=w", "--num", "8", "--big",
                     "18446744073709551615", "--real", "-2.5", "--pick", "gamma", "-", "--three", "p",
                     "q", "r", "--", "--flag", NULL);
    assert_int_equal(rc, 0);
    assert_string_equal(err, "");
    assert_int_equal(a.flag, 1);
    assert_string_equal(a.name, "v=w");
    assert_int_equal(a.num, 8);
    assert_true(a.big == UINT64_MAX);
    assert_true(a.real == -2.5);
    assert_int_equal(a.choice, 2);
    assert_string_equal(a.three[0], "p");
    assert_string_equal(a.three[2], "r");
    assert_int_equal(n, 3);          /* x, "-" and what follows "--" */
    assert_string_equal(pos[0], "x");
    assert_string_equal(pos[1], "-");
    assert_string_equal(pos[2], "--flag");
    assert_int_equal(help, 0);
}

static void test_defaults(void **state)
{
    (void)state;
    t_args a;
    int n = 0, help = 0;
    char *pos[32], err[1024];
    assert_int_equal(t_parse(&a, &n, pos, &help, err, sizeof err, "--help", NULL), 0);
    assert_int_equal(a.num, 3);       /* def "3" */
    assert_int_equal(a.choice, 1);    /* def "beta" */
    assert_int_equal(help, 1);
    assert_int_equal(n, 0);
}

/* Each bad input: exit 2 and exactly this message. */
static void test_errors(void **state)
{
    (void)state;
    static const struct { const char *args[4]; const char *msg; } cases[] = {
        { { "--nmae", "x" }, "dmbench: error: t: unknown option '--nmae'; did you mean '--name'? "
                             "valid options: --flag, --name, --num, --big, --real, --pick, --three, --help\n" },
        { { "--zzzzzzzz=1" }, "dmbench: error: t: unknown option '--zzzzzzzz'; valid options: --flag, "
                              "--name, --num, --big, --real, --pick, --three, --help\n" },
        { { "--num", "9" }, "dmbench: error: t: --num '9': expected an integer in 1..8\n" },
        { { "--num", "0" }, "dmbench: error: t: --num '0': expected an integer in 1..8\n" },
        { { "--num", "2x" }, "dmbench: error: t: --num '2x': expected an integer in 1..8\n" },
        { { "--big", "-5" }, "dmbench: error: t: --big '-5': expected a non-negative integer\n" },
        { { "--real", "nan" }, "dmbench: error: t: --real 'nan': expected a number\n" },
        { { "--pick", "gama" }, "dmbench: error: t: --pick 'gama': expected one of: alpha, beta, gamma "
                                "(did you mean 'gamma'?)\n" },
        { { "--name" }, "dmbench: error: t: --name needs a value\n" },
        { { "--three", "a", "b" }, "dmbench: error: t: --three needs A B C\n" },
        { { "--flag=1" }, "dmbench: error: t: --flag takes no value ('--flag=1')\n" },
        { { "--three=a", "b", "c" }, "dmbench: error: t: --three takes A B C as separate arguments, "
                                     "not after '='\n" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        t_args a;
        int n = 0, help = 0;
        char *pos[32], err[1024];
        const char *const *s = cases[i].args;
        int rc = t_parse(&a, &n, pos, &help, err, sizeof err, s[0], s[1], s[2], s[3], NULL);
        assert_int_equal(rc, DM_EXIT_USAGE);
        assert_string_equal(err, cases[i].msg);
    }
}

/* Every command of the table: a summary; options with help, unique names,
 * value names for values, no --help of their own; defaults that convert. */
static void test_command_table(void **state)
{
    (void)state;
    assert_true(cli_commands_count() >= 10);
    for (size_t i = 0; i < cli_commands_count(); i++) {
        const cli_command *c = cli_commands_at(i);
        assert_non_null(c->summary);
        assert_ptr_equal(cli_commands_find(c->name), c);
        for (size_t k = 0; k < cli_options_count(c->options); k++) {
            const cli_option *o = &c->options[k];
            assert_non_null(o->help);
            assert_string_not_equal(o->name, "help");
            assert_true(!cli_option_takes_value(o) || o->value_name);
            for (size_t j = 0; j < k; j++)
                assert_string_not_equal(o->name, c->options[j].name);
        }
        static _Alignas(max_align_t) char args[4096];
        memset(args, 0, sizeof args);
        char *argv[] = { (char *)c->name, NULL };
        int n = 0, help = 0;
        assert_int_equal(cli_options_parse(c->name, c->options, 1, argv, args, &n, &help), 0);
    }
    assert_null(cli_commands_find("nosuch"));
}

/* cli_parse answers --help of a command with its usage and option list
 * (DM_EXIT_OK, nothing else parsed) and stops at a bad option. */
static void test_help(void **state)
{
    (void)state;
    char *argv[] = { "run", "--help", "--bogus", NULL };
    static _Alignas(max_align_t) char args[4096];
    char text[8192];
    fflush(stdout);
    int saved = dup(1);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 1);
    int n = 0, rc = cli_parse(cli_commands_find("run"), 2, argv, args, &n);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    rewind(tmp);
    text[fread(text, 1, sizeof text - 1, tmp)] = '\0';
    fclose(tmp);
    assert_int_equal(rc, DM_EXIT_OK);
    assert_true(strncmp(text, "usage: dmbench run [SWEEP.yaml] [OPTIONS]\n", 42) == 0);
    assert_non_null(strstr(text, "\n  --shard K/N "));
    assert_non_null(strstr(text, "\n  --out DIR "));
    assert_non_null(strstr(text, "[default results]\n"));
    assert_non_null(strstr(text, "\n  -h, --help "));
}

/* `diff --heatmap` states its map's scale in the words of the report's
 * heatmap legend (FLIP_SCALE_TEXT; test_reports_report checks the legend),
 * and those words name FLIP's bounds. */
static void test_diff_heatmap_scale(void **state)
{
    (void)state;
    const cli_command *c = cli_commands_find("diff");
    assert_non_null(c);
    const cli_option *heat = NULL;
    for (size_t k = 0; k < cli_options_count(c->options); k++)
        if (strcmp(c->options[k].name, "heatmap") == 0)
            heat = &c->options[k];
    assert_non_null(heat);
    assert_non_null(strstr(heat->help, "the report's: " FLIP_SCALE_TEXT));
    assert_non_null(strstr(FLIP_SCALE_TEXT, "FLIP's fixed scale, 0 ("));
    assert_non_null(strstr(FLIP_SCALE_TEXT, ") to 1 ("));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_kinds_and_positionals),
             cmocka_unit_test(test_defaults),
             cmocka_unit_test(test_errors),
             cmocka_unit_test(test_command_table),
             cmocka_unit_test(test_help),
             cmocka_unit_test(test_diff_heatmap_scale))
