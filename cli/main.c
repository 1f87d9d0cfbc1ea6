/* main.c — the dmbench command line: everything is in the command table
 * (cli/commands.c, cli/commands.h); exit codes are core/dm_exit.h. */
#include "cli/commands.h"

int main(int argc, char **argv)
{
    return cli_main(argc, argv);
}
