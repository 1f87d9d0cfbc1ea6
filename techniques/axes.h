/* axes.h — sweep axes: their rows (names, kinds, valid values, defaults,
 * checks) and the lookups of the catalog.
 *
 * A configuration is a set of (axis, value) strings.  The built-in rows are
 * axes.c's table; the catalog (catalog.h) owns the registry of all axes,
 * built-in and user parameters, and answers the lookups below (axes_count,
 * axes_at, axes_find, axes_check, axes_canonical, axes_condition_holds), so
 * the sweep parser can reject bad input with the valid choices and the
 * planner can project a combination onto the axes a technique reads
 * (technique.h).  A row checks its own values: its `check`, or by kind.
 */
#ifndef TECHNIQUES_AXES_H
#define TECHNIQUES_AXES_H

#include <stddef.h>
#include "core/dm_util.h"

typedef enum axis_kind {
    AXIS_ENUM = 1,     /* one of choices[] */
    AXIS_INT,          /* integer in [min, max] */
    AXIS_FLOAT,        /* real in [min, max] */
    AXIS_SIZE2         /* "WxH" or a YAML pair [W, H] (resolution) */
} axis_kind;

/* Scene axes (scene = 1) are read by every technique: mesh, mesh_density,
 * resolution, cull, camera.* (with the orbit target camera.target_*), light.*
 * (light placement), maps, texture_size, filter, albedo_format (and
 * technique itself).  Every other axis is declared by the techniques that
 * read it (technique_desc.axes). */
typedef struct axis_info axis_info;
/* Checks value (not NULL) against row a: 0, or DM_ERR_ARG (DM_ERR_NOMEM,
 * DM_ERR_IO, DM_ERR_PARSE, DM_ERR_RANGE for a file the value names) with
 * what was expected in err.  The caller adds file:line. */
typedef int (*axis_check_fn)(const axis_info *a, const char *value, dm_str *err);

struct axis_info {
    const char *name;
    axis_kind kind;
    const char *const *choices;   /* AXIS_ENUM: NULL-terminated */
    double min, max;              /* AXIS_INT / AXIS_FLOAT */
    const char *def;              /* default value as text */
    int scene;                    /* 1: read by every technique (scene axis) */
    const char *help;
    axis_check_fn check;          /* NULL: by kind (axes_value_check) */
};

/* The built-in rows, in listing order (technique, mesh first, maps last);
 * *n gets their number.  The choices of technique, mesh and maps are NULL
 * here: the catalog fills them from their registries. */
const axis_info *axes_builtin(size_t *n);
/* Checks value against row a: a->check, else by kind (enum choices, integer
 * or real range, WxH; steps, tess_inner and tess_outer take 'auto'). */
int axes_value_check(const axis_info *a, const char *value, dm_str *err);
/* The check by kind alone (what a row's own check falls back to). */
int axes_kind_check(const axis_info *a, const char *value, dm_str *err);
/* The canonical text of a valid INT, FLOAT or SIZE2 value of row a
 * (malloc'd), or NULL for any other value (the value is then its own
 * canonical text, but for a user technique's file: catalog). */
char *axes_value_canonical(const axis_info *a, const char *value);
/* The built-in conditions of axis name hold (axes_condition_holds, without
 * the registry lookup of name). */
int axes_conditions_hold(const char *name, const char *(*value)(const char *axis, void *ctx),
                         void *ctx);

/* The catalog's lookups (catalog.c): the built-in rows, then the
 * parameters of the user techniques loaded so far. */
size_t axes_count(void);
const axis_info *axes_at(size_t i);
const axis_info *axes_find(const char *name);
/* Checks a value against its axis.  Returns 0, or DM_ERR_UNKNOWN (unknown
 * axis: err gets the valid names) / DM_ERR_ARG (bad value: err says what was
 * expected and lists the valid choices).  The caller adds file:line. */
int axes_check(const char *name, const char *value, dm_str *err);
/* Canonical text for a value ("1280x720" for [1280,720], trimmed numbers:
 * "064" -> "64", "3.0" -> "3").  Returns a malloc'd string, or NULL when the
 * value does not pass axes_check. */
char *axes_canonical(const char *name, const char *value);
/* 1 when the condition of axis `name` holds or it has none; 0 when it fails
 * or the axis is unknown.  Conditions (axes.c): roughness needs
 * lighting=cook-torrance, light_radius attenuation=s1, tess_inner and
 * tess_outer lod=uniform; the axes of dm_param_left_out_default
 * (core/dm_results.h: tess_inner, cull, camera.path, ...) count only away
 * from their defaults (so configurations keep the keys they had before
 * these axes existed).  Every condition of an axis must hold.
 * value(axis, ctx) gives the
 * configuration's value of an axis (NULL: the axis default).  The planner
 * drops an axis whose condition fails, as it drops axes a technique does not
 * read, so e.g. roughness folds unless lighting=cook-torrance. */
int axes_condition_holds(const char *name, const char *(*value)(const char *axis, void *ctx),
                         void *ctx);
/* Why a configuration with axis=value cannot be measured on a driver, as a
 * malloc'd reason, or NULL when it can.  Some values need an extension
 * (has_ext(ext, user) says whether the driver has it): without it the
 * reason names the extension.  virtual_texture=sparse is refused on every
 * driver (dmbench commits no sparse pages); the reason says so.  The planner
 * leaves such configurations out and the renderer refuses them. */
char *axes_value_refusal(const char *axis, const char *value,
                         int (*has_ext)(const char *ext, void *user), void *user);
/* The i-th extension an axis value needs (for the driver probe), or NULL
 * past the end. */
const char *axes_value_ext_at(size_t i);
/* Parses "WxH", "W,H" or "[W, H]" with each side in [1, 8192]; 0 or
 * DM_ERR_ARG (w, h untouched). */
int axes_parse_size2(const char *s, int *w, int *h);

#endif
