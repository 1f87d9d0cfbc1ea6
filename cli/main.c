/* main.c — the dmbench command line (SPEC §1).
 *
 * Exit codes everywhere: 0 success, 1 a check failed / regression found,
 * 2 bad input or usage (the message names file:line and the valid choices),
 * 3 inconclusive (compare only).
 */
#include "core/dm_error.h"
#include "core/dm_util.h"
#include "cli/cli.h"
#include "run/callgrind.h"

#include <stdio.h>
#include <string.h>

typedef struct command {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *usage;
} command;

static int cmd_help(int argc, char **argv);

static const command commands[] = {
    { "run", cli_run, "run [SWEEP.yaml] [--out DIR] [--resume] [--shard K/N] [--budget SEC] [--seed N] [--tag NAME] [--quick] [--quiet|--verbose]" },
    { "report", cli_report, "report DIR [--metric NAME]  rebuild report.html, results.json, results.csv, summary.md" },
    { "fit", cli_fit, "fit DIR | --data FILE.csv  --formula F | --model NAME  [--response NAME] [--group-by A,B] [--loss huber|cauchy|none] [--json]" },
    { "compare", cli_compare, "compare BASE NEW [--threshold 0.5%] [--time-threshold 5%] [--alpha 0.01] [--tolerance C=REL] [--psnr-drop DB] [--ssim-drop X]\n"
      "                        [--counters-only] [--allow-env-mismatch] [--junit F] [--markdown F] [--json F]\n"
      "                        [--store FILE] [--base-tag T|--base-run ID|--baseline] [--new-tag T|--new-run ID]\n"
      "  dmbench compare --paired BASE_BINARY NEW_BINARY SWEEP [--rounds N]" },
    { "baseline", cli_baseline, "baseline accept RUN --reason TEXT [--store FILE] | baseline show [--store FILE]" },
    { "merge", cli_merge, "merge OUT DIR...      union of shard results into one run" },
    { "list", cli_list, "list techniques|axes|counters|meshes|textures|models  (counters: [--passes A,B,...] [--json])" },
    { "info", cli_info, "info [--json]         context, extensions, limits, timer validity" },
    { "render", cli_render, "render KEY=VALUE... --png out.png [--supersample N] [--debug normals]" },
    { "view", cli_view, "view [KEY=VALUE...] [--config KEY --results DIR] [--frames N] [--keys SCRIPT] [--screenshot F]" },
    { "help", cmd_help, "help                  this text" },
};

static int cmd_help(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    printf("dmbench — performance and quality of surface-detail rendering techniques\n\n"
           "usage: dmbench COMMAND [ARGS]\n\n");
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++)
        printf("  dmbench %s\n", commands[i].usage);
    printf("\nExit codes: 0 ok, 1 check failed/regression, 2 bad input, 3 inconclusive.\n"
           "Documentation: README.md and docs/ in the source tree.\n");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return cmd_help(0, NULL) == 0 ? 2 : 2;
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)
        return cmd_help(0, NULL);
    if (strcmp(argv[1], "--version") == 0) {
        printf("dmbench 0.1.0\n");
        return 0;
    }
    /* internal: the Instructions pass's child, started under Valgrind by the runner */
    if (strcmp(argv[1], "__instructions") == 0)
        return callgrind_child_main(argc - 1, argv + 1);
    const char *names[sizeof commands / sizeof *commands];
    for (size_t i = 0; i < sizeof commands / sizeof *commands; i++) {
        names[i] = commands[i].name;
        if (strcmp(argv[1], commands[i].name) == 0)
            return commands[i].fn(argc - 1, argv + 1);
    }
    dm_str msg = {0};
    dm_str_printf(&msg, "unknown command '%s'", argv[1]);
    const char *close = dm_closest(argv[1], names, sizeof names / sizeof *names);
    if (close)
        dm_str_printf(&msg, "; did you mean '%s'?", close);
    dm_str_cat(&msg, " valid commands: ");
    dm_str_cat_list(&msg, names, sizeof names / sizeof *names);
    fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&msg));
    dm_str_free(&msg);
    return 2;
}
