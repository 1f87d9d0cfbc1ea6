/* sweep.h — sweep files (docs/sweep-files.md): parsing and validation.
 *
 * A sweep file says what to render (scene defaults and axes whose cartesian
 * product is planned), how to measure it, what quality reference to use and
 * which cost models to fit.  Everything is validated before any work: an
 * unknown key, axis, value, technique or counter is DM_ERR_PARSE with
 * "file:line:column: message" in err, listing the valid choices.
 */
#ifndef SWEEP_SWEEP_H
#define SWEEP_SWEEP_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

/* Longest sweep name in bytes: it titles reports, Slurm jobs and terminal
 * lines, so a megabyte of name is refused at parse time. */
#define SWEEP_NAME_MAX 200

typedef struct sweep_axis {
    char *name;
    char **values;           /* canonical text values */
    size_t n_values;
    int line;                /* 1-based line of the axis in the file */
} sweep_axis;

/* One `exclude:` entry: the combinations whose value of every listed axis
 * is one of its values are not planned. */
typedef struct sweep_exclude {
    sweep_axis *axes;
    size_t n_axes;
    int line;
} sweep_exclude;

typedef struct sweep_model {
    char *name;
    char *formula;           /* NULL = built-in model named `name` */
    char *response;          /* default "WallTime" */
    char **group_by;
    size_t n_group_by;
    int line;
} sweep_model;

typedef struct sweep_measure {
    int warmup_frames;       /* minimum warm-up frames (default 8) */
    int frames_per_sample;   /* K (default 16); raised per configuration so that */
    double min_sample_ms;    /* a sample lasts at least this long (default 20; 0 = K exactly) */
    int samples_min;         /* default 5 */
    int samples_max;         /* default 30 */
    double target_ci;        /* relative half-width of the median's 95% CI (default 0.03) */
    double timeout_s;        /* watchdog per configuration (default 120) */
    double max_seconds;      /* time cap of sampling per configuration (default 10) */
    char **counters;         /* counter names (default: WallTime + statistics set) */
    size_t n_counters;
} sweep_measure;

typedef struct sweep {
    char *path;              /* file name used in messages ("<default>" if embedded) */
    char *name;
    dm_kv *scene;            /* scene defaults, axis name -> canonical value */
    size_t n_scene;
    int *scene_lines;        /* the 1-based line of each scene default (0: none) */
    sweep_axis *axes;
    size_t n_axes;
    sweep_measure measure;
    char *ref_technique;     /* quality reference technique; NULL = same config supersampled */
    int supersample;         /* default 4 */
    dm_kv *ref_params;       /* quality.reference axis overrides (axis -> canonical value),
                                set over the reference's parameters; e.g. normal_format */
    size_t n_ref_params;
    char *pareto_metric;     /* quality.pareto_metric: a reports/metric.h name (default "ssim") */
    double flip_ppd;         /* quality.flip_ppd: FLIP's pixels per degree (default 67.0206) */
    double budget_ms;        /* quality.budget_ms: the report's frame budget; 0 = per-scene default */
    sweep_model *models;
    size_t n_models;
    sweep_exclude *excludes;
    size_t n_excludes;
    struct published *published;  /* `published:` block (sweep/published.h), NULL when absent */
    char **drivers;          /* `drivers:` names, as written (checked by `dmbench drivers`, which
                                knows the drivers); NULL when absent */
    int *driver_lines;       /* the line of each name */
    size_t n_drivers;
    uint64_t hash;           /* FNV-1a of the file text */
} sweep;

/* Parses and validates a sweep from text; `path` names it in messages.
 * Returns 0, or DM_ERR_PARSE with "path:line:col: ..." in err (out zeroed);
 * DM_ERR_NOMEM (same message) when a map it names is too large for the
 * memory the process may use: the machine's failure, exit 4. */
int sweep_parse(const char *text, const char *path, sweep *out, dm_str *err);
/* Reads and parses a file; DM_ERR_IO with the path and why when it cannot
 * be read (missing, or not a regular file: dm_input_file). */
int sweep_load(const char *path, sweep *out, dm_str *err);
/* The embedded default sweep (README); quick = the short version for tests. */
const char *sweep_default_text(int quick);
void sweep_free(sweep *s);

/* One key a sweep file may hold: a row of the parser's key table, which is
 * the only list of keys (the parser looks keys up in it, and
 * docs/sweep-files.md's key reference is generated from it). */
typedef struct sweep_key {
    const char *section;     /* "" = top level, "measure.samples", "models[]" (each entry) ... */
    const char *name;        /* "*" = any axis name */
    const char *type;        /* what the value is, for the docs */
    const char *deflt;       /* the default, for the docs */
    const char *doc;         /* what it means */
    const char *example;     /* a valid value (NULL for a mapping or a list of mappings) */
} sweep_key;

size_t sweep_keys_count(void);
const sweep_key *sweep_keys_at(size_t i);
/* The key reference of docs/sweep-files.md: one Markdown table per
 * section, in table order, from the same rows the parser uses. */
void sweep_keys_markdown(dm_str *out);

#endif
