/* sweep_yaml.h — guards on a loaded libyaml document that know nothing of
 * sweeps: the parser runs them before it reads a key. */
#ifndef SWEEP_SWEEP_YAML_H
#define SWEEP_SWEEP_YAML_H

#include <yaml.h>

#include "core/dm_util.h"

/* Deepest nesting of YAML collections a sweep file may have (the deepest
 * real one is 4: models, a model, group_by, ...). */
#define SWEEP_YAML_MAX_DEPTH 16

/* Refuses a document nested deeper than SWEEP_YAML_MAX_DEPTH: 0, or
 * DM_ERR_PARSE with "path:line:col: nested deeper than ..." appended to err.
 * Without recursion: libyaml numbers a collection before its children, so
 * one pass in node order gives every node its depth. */
int sweep_yaml_depth_check(yaml_document_t *doc, const char *path, dm_str *err);

#endif
