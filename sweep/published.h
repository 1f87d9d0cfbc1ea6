/* published.h — a sweep file's `published:` block (docs/sweep-files.md,
 * "Published figures"): the figures a study printed for the configurations
 * the sweep reproduces, so the report can set them beside the measured ones
 * as ratios to a baseline configuration.
 *
 *   published:
 *     source: { study: "...", table: "Table 2", gpu: "GeForce 8600 GT" }
 *     unit: fps                 # fps | seconds | ms
 *     baseline: phong
 *     values: { phong: 160, "pom steps=32": 95 }
 *
 * A label is a technique name and/or axis=value words; it names the one
 * planned configuration whose technique and parameters all match.
 */
#ifndef SWEEP_PUBLISHED_H
#define SWEEP_PUBLISHED_H

#include <stddef.h>
#include <yaml.h>
#include "core/dm_util.h"

struct plan;

typedef struct published_value {
    char *label;             /* as written in the sweep file */
    double value;            /* in `unit`, > 0 and finite */
    int line;                /* 1-based line in the sweep file */
    char key[17];            /* the planned configuration's key ("" until resolved) */
} published_value;

typedef struct published {
    char *study, *table, *gpu;   /* source; gpu may be NULL */
    char *unit;              /* "fps", "seconds" or "ms" */
    char *baseline;          /* one of the values' labels */
    published_value *values;
    size_t n_values;
    int line;                /* line of the `published:` key */
} published;

/* Parses the value node of `published:` (a mapping) from a libyaml document.
 * Returns 0 with *out allocated, or DM_ERR_PARSE with "path:line:col: ..."
 * in err naming the valid choices (unknown key or unit, a value that is not
 * a finite positive number, a baseline that is not one of the labels). */
int published_parse(yaml_document_t *doc, yaml_node_t *map, const char *path,
                     published **out, dm_str *err);
/* Resolves every label to the one planned configuration it names (fills
 * values[].key).  DM_ERR_PARSE with "path:line: ..." when a label matches no
 * configuration (did-you-mean over the planned labels) or several. */
int published_resolve(published *p, const struct plan *pl, const char *path, dm_str *err);
/* The planned configuration's canonical label: its technique, then
 * " axis=value" for each parameter that takes two or more values in the
 * plan.  Appends to out. */
void published_plan_label(const struct plan *pl, size_t i, dm_str *out);
/* Writes the resolved block as JSON (the run directory's published.json,
 * read by reports/published_report.h).  0 or dm_write_file's DM_ERR_IO /
 * DM_ERR_DISK (errno says why). */
int published_write_json(const published *p, const char *path);
void published_free(published *p);

#endif
