/* axes.h — the catalog of sweep axes: names, kinds, valid values, defaults.
 *
 * A configuration is a set of (axis, value) strings.  This catalog is the one
 * place that says which names and values exist, so the sweep parser can
 * reject bad input with the valid choices and the planner can project a
 * combination onto the axes a technique reads (technique.h).
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
typedef struct axis_info {
    const char *name;
    axis_kind kind;
    const char *const *choices;   /* AXIS_ENUM: NULL-terminated */
    double min, max;              /* AXIS_INT / AXIS_FLOAT */
    const char *def;              /* default value as text */
    int scene;                    /* 1: read by every technique (scene axis) */
    const char *help;
} axis_info;

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
 * tess_outer lod=uniform; tess_inner, tess_outer, cull, attenuation,
 * parallax_bias, camera.orbit_deg_per_frame and light.orbit_deg_per_frame
 * count only away from their defaults (so configurations keep the keys they
 * had before these axes existed).  Every condition of an axis must hold.
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
