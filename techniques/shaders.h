/* shaders.h — GLSL sources embedded at build time (cmake/embed_glsl.cmake).
 *
 * Every .glsl file under techniques/glsl/ is compiled into the binary under its
 * file name.  A stage's text is composed as:
 *   "#version 450 core" + the given defines + the file, where each line
 *   `#include "other.glsl"` is replaced by that embedded file (recursively,
 *   at most 8 levels; each file is included once per stage).
 */
#ifndef TECHNIQUES_SHADERS_H
#define TECHNIQUES_SHADERS_H

#include "core/dm_util.h"

/* Source of `name`: an embedded file ("lighting.glsl") or one added with
 * shaders_add ("user:NAME"); NULL when absent. */
const char *shaders_source(const char *name);
/* Adds (or, for a name added before, replaces) the source of name.  Both
 * strings are the caller's and must outlive their use; the catalog adds
 * each user technique's composed stage (catalog.h).  0, or DM_ERR_RANGE
 * past 32 names. */
int shaders_add(const char *name, const char *source);
/* Composes the full text of one stage into out.  Returns 0, or
 * DM_ERR_NOTFOUND with the missing file named in err. */
int shaders_compose(const char *name, const char *defines, dm_str *out, dm_str *err);

#endif
