/* cli_compare.c — placeholder until the regression gate lands. */
#include "cli.h"
int cli_compare(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli__usage_error("compare: not built yet");
}
int cli_baseline(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli__usage_error("baseline: not built yet");
}
