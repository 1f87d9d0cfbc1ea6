/* cmd_view.c — `dmbench view [KEY=VALUE...]`: the options of the interactive
 * viewer.  This file turns the command line into a viewer_desc (the initial
 * configuration, from --config/--results and KEY=VALUE, and the --keys
 * script); the window loop is viewer/viewer.c.  See docs/viewer.md.
 */
#include "cli/cli.h"
#include "cli/params.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "viewer/viewer.h"
#include "viewer/viewer_script.h"
#include "reports/report.h"
#include "techniques/axes.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct view_args {
    dm_kv *kv;                   /* KEY=VALUE from the command line (canonical) */
    size_t n;
    const char *config, *results, *keys, *screenshot;
    int frames;                  /* 0 = until closed (or the script ends) */
    double timed_seconds;
} view_args;

/* --timed-seconds S with 0 < S <= 3600. */
static int view__timed(const cli_option *opt, const char *v, void *args, dm_str *err)
{
    char *end = NULL;
    double s = strtod(v, &end);
    if (!*v || *end || !(s > 0 && s <= 3600)) {
        dm_str_printf(err, "--%s expects 0 < S <= 3600, got '%s'", opt->name, v);
        return DM_ERR_ARG;
    }
    ((view_args *)args)->timed_seconds = s;
    return 0;
}

const cli_option cli_view_options[] = {
    CLI_STRING("config", view_args, config, "KEY",
               "the configuration with this key (or a unique prefix) in --results"),
    CLI_STRING("results", view_args, results, "DIR",
               "a run directory whose results.json holds --config"),
    { .name = "frames", .kind = CLI_OPT_INT, .offset = offsetof(view_args, frames), .value_name = "N",
      .min = 1, .max = 100000000, .help = "quit after N frames" },
    CLI_STRING("keys", view_args, keys, "SCRIPT",
               "typed input, one event per frame, then quit (docs/viewer.md)"),
    CLI_STRING("screenshot", view_args, screenshot, "FILE", "write the last frame as PNG"),
    { .name = "timed-seconds", .kind = CLI_OPT_DOUBLE, .value_name = "S", .parse = view__timed,
      .def = "20", .help = "duration of the timed test (T)" },
    CLI_OPT_END
};

/* The params of configuration `key` (or a unique prefix of it) in
 * DIR/results.json, then the command-line ones over them. */
static int view__from_results(const view_args *o, dm_kv **kv, size_t *n)
{
    char *path = dm_xasprintf("%s/results.json", o->results), err[512];
    dm_run_result run;
    int rc = report_read_json(path, &run, err, sizeof err);
    free(path);
    if (rc != 0)
        return cli_usage_error("view: %s", err);
    const dm_config_result *hit = NULL;
    int matches = 0;
    for (size_t i = 0; i < run.n_configs; i++)
        if (strncmp(run.configs[i].key, o->config, strlen(o->config)) == 0) {
            hit = &run.configs[i];
            matches++;
        }
    rc = matches == 1 ? -1
         : cli_usage_error("view: --config '%s' %s in %s/results.json (%zu configurations)",
                            o->config, matches ? "is ambiguous" : "not found", o->results, run.n_configs);
    for (size_t i = 0; hit && matches == 1 && i < hit->n_params; i++)
        if (!dm_kv_get(o->kv, o->n, hit->params[i].key))
            dm_kv_push(kv, n, hit->params[i].key, hit->params[i].value);
    dm_run_free(&run);
    return rc;
}

/* Options → initial configuration and script; -1 to go on. */
static int view__setup(view_args *a, int argc, char **argv, dm_kv **kv, size_t *n,
                       viewer_event **ev, size_t *n_ev)
{
    int rc = cli_params_parse("view", argc, argv, &a->kv, &a->n);
    if (rc < 0 && !a->config != !a->results)
        rc = cli_usage_error("view: --config KEY and --results DIR go together");
    if (rc < 0 && a->config)
        rc = view__from_results(a, kv, n);
    for (size_t i = 0; i < a->n; i++)
        dm_kv_push(kv, n, a->kv[i].key, a->kv[i].value);
    dm_str err = {0};
    if (rc < 0 && a->keys && viewer_script_parse(a->keys, ev, n_ev, &err) != 0)
        rc = cli_usage_error("view: %s", dm_str_get(&err));
    dm_str_free(&err);
    return rc;
}

/* `dmbench view`: the options into a viewer_desc, then the window loop;
 * the loop's DM_ERR_* mapped by dm_exit_from_error. */
int cli_view(const cli_command *self, int argc, char **argv)
{
    view_args args = {0}, *a = &args;
    int rc = cli_parse(self, argc, argv, a, &argc);
    dm_kv *kv = NULL;
    size_t n = 0, n_ev = 0;
    viewer_event *ev = NULL;
    if (rc < 0)
        rc = view__setup(a, argc, argv, &kv, &n, &ev, &n_ev);
    if (rc < 0) {
        viewer_desc d = { .params = kv, .n_params = n, .events = ev, .n_events = n_ev,
                          .scripted = a->keys != NULL, .frames = a->frames,
                          .screenshot = a->screenshot, .timed_seconds = a->timed_seconds };
        rc = dm_exit_from_error(viewer_run(&d));
    }
    dm_kv_free(kv, n);
    dm_kv_free(a->kv, a->n);
    free(ev);
    return rc;
}
