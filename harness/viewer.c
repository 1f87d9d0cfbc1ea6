/* viewer.c — placeholder until the interactive viewer lands. */
#include "cli.h"
int cli_view(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli__usage_error("view: not built yet");
}
