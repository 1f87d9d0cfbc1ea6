/* cmd_info.c — `dmbench info`: context, extensions, limits, timer validity. */
#include "cli.h"
#include "run/info.h"

#include <stddef.h>

typedef struct info_args {
    int json;
} info_args;

static const cli_option info_options[] = {
    { .name = "json", .kind = CLI_OPT_BOOL, .offset = offsetof(info_args, json),
      .help = "print JSON" },
    CLI_OPT_END
};

static int info_cmd(void *args, int argc, char **argv)
{
    if (argc > 0)
        return cli_usage_error("info: takes no arguments ('%s')", argv[0]);
    return info_main(((info_args *)args)->json);
}

const cli_command cli_cmd_info = {
    .name = "info", .fn = info_cmd, .options = info_options, .args_size = sizeof(info_args),
    .summary = "the GL context, extensions, limits and whether GPUTime can be trusted",
};
