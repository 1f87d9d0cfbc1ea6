/* user_technique.h — a user's GLSL file measured as a technique (docs/user-techniques.md).
 *
 * A user technique is one GLSL file: a header of `//@` lines declares its
 * name and its parameters, and the code defines the entry point
 *     vec3 user_surface(vec2 uv, vec3 v)
 * which gets the interpolated UV and the unit tangent-space view vector and
 * returns the UV of the visible point of the relief (xy) and its height in
 * the height field (z, 0..1; SURFACE_H0 for a flat technique).  The file is
 * appended to the built-in fragment stage (surface.frag.glsl with
 * SURF_USER), so shading, shadows and every counter see the surface the user
 * found, on the built-in vertex path.  With `//@base tess-level` the file
 * defines `float user_tess_level(vec3 a, vec3 b)` instead (the level of a
 * patch edge from its world-space endpoints) and is appended to
 * tess-displacement's control stage (tess.tcs.glsl with LOD_USER).  Each
 * `//@param NAME int|float MIN MAX DEFAULT` becomes a sweep axis NAME and
 * the uniform u_NAME.
 *
 * A sweep names the file as a value of the technique axis
 * (`technique: [pom, examples/relief.glsl]`, relative to the sweep file);
 * loading registers it under its declared name, which is the value that
 * configurations, keys and labels carry: user_technique.c parses the file
 * into a value, the catalog (catalog.h) registers it.  The configuration key includes a
 * hash of the file's text (technique_desc.source_hash).
 */
#ifndef TECHNIQUES_USER_TECHNIQUE_H
#define TECHNIQUES_USER_TECHNIQUE_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_util.h"
#include "techniques/axes.h"
#include "techniques/technique.h"

/* Most user techniques and parameters one process registers. */
#define USER_TECHNIQUE_MAX 16
#define USER_TECHNIQUE_MAX_PARAMS 8
/* The user's file starts at this line of the fragment stage (#line), so a
 * driver log line "0:LINE(COL)" with LINE above it is line LINE − BASE of
 * the user's file (Mesa prints source string 0 whatever #line says). */
#define USER_TECHNIQUE_LINE_BASE 100000

/* 1 when a technique-axis value names a user file (ends in ".glsl"). */
int user_technique_is_path(const char *value);
/* Reads, checks and registers the file at path (as given; the caller
 * resolves it).  Loading the same file with the same text again is a no-op.
 * On success *name (may be NULL) points at the registered name, valid for
 * the process.  Returns 0, or DM_ERR_IO (missing, unreadable, not a regular
 * file) / DM_ERR_PARSE (header, parameter or entry point) with
 * "path[:line]: message" in err; nothing is registered then. */
int user_technique_load(const char *path, const char **name, dm_str *err);

/* Checks text as the user technique file `path` without reading or
 * registering anything: the header (parameters against the axes registered
 * now) and the entry point, as user_technique_load does.  Returns 0, or
 * DM_ERR_PARSE with "path[:line]: message" in err.  (The fuzzer's entry.) */
int user_technique_check_text(const char *path, const char *text, dm_str *err);

/* 0 when the file at path still has the text whose FNV-1a hash is want
 * (technique_desc.source_hash of the technique loaded from it), else
 * DM_ERR_ARG with "path: ... changed since the run started (source hash
 * WANT, now HAVE)" or "... cannot be read ..." in err.  One run measures
 * one version of each source: a child that re-reads a file checks it. */
int user_technique_source_check(const char *path, uint64_t want, dm_str *err);

/* The environment entry of a run that records the source a user technique
 * was measured with: key USER_TECHNIQUE_ENV_PREFIX + name, value
 * "HASH PATH" (HASH: source_hash as 16 hex digits).  `run --resume` refuses
 * to continue a run whose recorded source no longer matches the file. */
#define USER_TECHNIQUE_ENV_PREFIX "user_source."

/* Re-reads every loaded file (the viewer's reload on change).  A file whose
 * text changed, with the same name and parameters, replaces the registered
 * source (and source_hash): the next program built from it uses the new
 * text.  A file that cannot be read, fails a check or changed its name or
 * parameters keeps the old source, with a line in msg.  Returns how many
 * changed. */
int user_technique_reload(dm_str *msg);

/* The registered user techniques and their parameter axes. */
size_t user_technique_count(void);
const technique_desc *user_technique_at(size_t i);
size_t user_technique_axis_count(void);
const axis_info *user_technique_axis_at(size_t i);
/* The registered technique whose value was this path (as loaded), or NULL. */
const technique_desc *user_technique_by_path(const char *path);
/* The file a user technique was loaded from, or NULL for a built-in one. */
const char *user_technique_path(const technique_desc *t);

/* Compiles and links loaded user technique i with renderer r (a current GL
 * context; user_technique_check.c).  Returns 0, or DM_ERR_PARSE with
 * "path: user technique 'NAME' does not compile; the driver says:" and the
 * driver's log, lines of the user's file as "path:line:column: ...", in
 * err, or another code with "path: user technique 'NAME' cannot be used:".
 * The driver's compiler may also crash or run for minutes on a user's file:
 * callers compile in a child with a deadline (run/probe.h). */
typedef struct render_ctx render_ctx;
int user_technique_check_program(render_ctx *r, size_t i, dm_str *err);

/* Source of a virtual shader name "user:NAME" (the built-in stage of its
 * base followed by the user's file), or NULL. */
const char *user_technique_shader_source(const char *name);
/* Appends a driver's info log to out with every line that refers to the
 * user's file ("0:100012(3): error: ...") rewritten as "path:12:3: error:
 * ..."; for a user technique the built-in code's warnings are dropped (they
 * are the same for every technique), everything else is kept. */
void user_technique_map_log(const technique_desc *t, const char *log, dm_str *out);

#endif
