/* catalog.h — the one registry of techniques and sweep axes.
 *
 * The catalog owns every list a lookup walks: the built-in techniques
 * (technique_list.c), the built-in axis rows (axes.c), and the user
 * techniques loaded so far with the axes their parameters declare.  The
 * technique axis's choices are its names; its row checks a value by loading
 * the user file it names (user_technique.c parses, the catalog registers).
 * No other file of techniques/ keeps a registry, and none calls back here
 * from below: axes.c checks values of a row it is given, user_technique.c
 * turns a file into a value, shaders.c composes sources by name (the
 * catalog adds the user stages to it).
 *
 * The lookups keep the names their callers have always used, declared where
 * they were: technique.h (technique_count, technique_at, technique_find,
 * technique_names, technique_reads_axis), axes.h (axes_count, axes_at,
 * axes_find, axes_check, axes_canonical, axes_condition_holds) and
 * user_technique.h (user_technique_load, _reload, _check_text, _count,
 * _at, _axis_count, _axis_at, _by_path, _path, _shader_source, _map_log).
 * All are safe to call from several threads; loading and reloading hold
 * one lock.
 */
#ifndef TECHNIQUES_CATALOG_H
#define TECHNIQUES_CATALOG_H

#include "techniques/axes.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

#endif
