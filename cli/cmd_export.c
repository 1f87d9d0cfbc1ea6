/* cmd_export.c — `dmbench export RUN --format F [-o FILE] [--store DB]`: one
 * run in the JSON another benchmark tool reads (reports/export.h).
 *
 * RUN is a run directory, its results.json or an output root holding
 * `latest`; with --store it is a run id in that store.  Output goes to FILE
 * (written atomically) or stdout.  docs/exports.md has one example per format.
 */
#include "cli.h"
#include "core/dm_error.h"
#include "gate/compare.h"
#include "reports/export.h"
#include "reports/report_model.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct export__opts {
    const char *run, *format, *out, *store;
} export__opts;

const char *const cli_export_formats[] = { "gbench", "bmf", "gab-smaller", "gab-bigger", NULL };

/* --format: the names of reports/export.c (cli_export_formats lists them for
 * help and completion; export__bad_format names the registry's list). */
const cli_option cli_export_options[] = {
    { .name = "format", .kind = CLI_OPT_STRING, .offset = offsetof(export__opts, format),
      .value_name = "FORMAT", .choices = cli_export_formats,
      .help = "gbench (Google Benchmark JSON), bmf (Bencher), gab-smaller|gab-bigger (github-action-benchmark)" },
    { .name = "output", .short_name = 'o', .kind = CLI_OPT_STRING, .offset = offsetof(export__opts, out),
      .value_name = "FILE", .help = "write to FILE instead of standard output" },
    CLI_STRING("store", export__opts, store, "DB", "take RUN (a run id) from this store"),
    CLI_OPT_END
};

/* Positional RUN and the required --format; returns -1 to go on or an exit code. */
static int export__options(const cli_command *self, int argc, char **argv, export__opts *o)
{
    int rc = cli_parse(self, argc, argv, o, &argc);
    if (rc >= 0)
        return rc;
    if (argc > 1)
        return cli_usage_error("export: one RUN only ('%s' and '%s')", argv[0], argv[1]);
    o->run = argc ? argv[0] : NULL;
    if (!o->run)
        return cli_usage_error("export: usage: dmbench export RUN --format gbench|bmf|gab-smaller|gab-bigger "
                               "[-o FILE] [--store DB]");
    if (!o->format)
        return cli_usage_error("export: --format is required (gbench, bmf, gab-smaller or gab-bigger; "
                               "docs/exports.md)");
    return -1;
}

/* "--format 'x' is not a format; did you mean 'y'? valid choices: a, b, ..." */
static int export__bad_format(const char *name)
{
    size_t n;
    const export_format *f = export_formats(&n);
    const char *names[8];
    dm_str msg = {0};
    for (size_t i = 0; i < n && i < 8; i++)
        names[i] = f[i].name;
    dm_str_printf(&msg, "export: --format '%s' is not a format", name);
    dm_str_suggest(&msg, name, names, n < 8 ? n : 8, "choices");
    int rc = cli_usage_error("%s", dm_str_get(&msg));
    dm_str_free(&msg);
    return rc;
}

int cli_export(const cli_command *self, int argc, char **argv)
{
    export__opts o = {0};
    int rc = export__options(self, argc, argv, &o);
    const export_format *f = rc < 0 ? export_find(o.format) : NULL;
    if (rc < 0 && !f)
        rc = export__bad_format(o.format);
    dm_run_result run = {0};
    dm_str err = {0};
    int e = 0;
    if (rc < 0 && (e = o.store ? compare_load_store(o.store, o.run, NULL, &run, &err)
                               : compare_load_path(o.run, &run, &err)) != 0)
        rc = cli_error(e, "export: %s", dm_str_get(&err));
    report_model m = {0};
    if (rc < 0 && report_model_build(&m, &run, NULL) != 0)
        rc = cli_error(DM_ERR_ARG, "export: no run");
    if (rc < 0 && export_write(&m, f, o.out) != 0)
        rc = cli_usage_error("export: cannot write %s", o.out ? o.out : "stdout");
    report_model_free(&m);
    if (rc < 0 && o.out && strcmp(o.out, "-") != 0)
        fprintf(stderr, "export: %s (%s) written to %s\n", f->name, f->what, o.out);
    dm_run_free(&run);
    dm_str_free(&err);
    return rc < 0 ? 0 : rc;
}
