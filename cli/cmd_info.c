/* cmd_info.c — `dmbench info`: context, extensions, limits, timer validity. */
#include "cli.h"
#include "run/info.h"

#include <stddef.h>

typedef struct info_args {
    int json;
} info_args;

const cli_option cli_info_options[] = {
    CLI_BOOL("json", info_args, json, "print JSON"),
    CLI_OPT_END
};

int cli_info(const cli_command *self, int argc, char **argv)
{
    info_args a = {0};
    int rc = cli_parse(self, argc, argv, &a, &argc);
    if (rc < 0 && argc > 0)
        rc = cli_usage_error("info: takes no arguments ('%s')", argv[0]);
    return rc >= 0 ? rc : info_main(a.json);
}
