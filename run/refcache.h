/* refcache.h — on-disk cache of quality reference images (docs/sweep-files.md, Quality; docs/measurement.md, Setup reuse).
 *
 * A scene's reference (by default the configuration itself or
 * reference-mesh, 4x supersampled) is the most expensive image of a run and
 * is the same on every run of the same sweep: it is stored under the user's
 * cache directory and loaded instead of re-rendered.  An entry is keyed by
 * the text of everything that determines the image: the reference
 * technique's name, version and composed GLSL of every stage, every
 * parameter (sorted by name), the resolution, the supersampling factor and
 * the driver string (GL_RENDERER + GL_VERSION), and for a frame along a
 * camera path the frame (the path itself is among the parameters).  The
 * file name is a hash of
 * that text and the full text is stored inside, so a hash collision or a
 * changed key never loads a wrong image.  The key also holds the size and
 * modification time of the running binary: code that changes a reference's
 * pixels outside its shaders (CPU mesh displacement, map generation) comes
 * with a rebuild, which misses every entry of the previous build.
 *
 * File: magic "DMREF001", uint32 key length, key text, int32 w, int32 h,
 * w*h*4 float colour, w*h float depth; native byte order (per machine).
 */
#ifndef RUN_REFCACHE_H
#define RUN_REFCACHE_H

#include <stddef.h>
#include "core/dm_results.h"
#include "core/dm_util.h"

typedef struct refcache_desc {
    const dm_kv *params;         /* the reference render's parameters; "technique" required */
    size_t n_params;
    int width, height;           /* output size (after downsampling) */
    int supersample;             /* 0 = 1 */
    const char *driver;          /* GL_RENDERER + GL_VERSION; NULL = "" */
    int on_path;                 /* 1: frame `frame` of the params' camera path (a "frame N"
                                    line in the key); 0: the still image, keyed as before paths */
    unsigned long long frame;
} refcache_desc;

/* Directory of the reference cache: DMBENCH_CACHE_DIR/references, else the
 * XDG cache's dmbench/references (the root techniques/maps.h uses).  Caller
 * frees. */
char *refcache_dir(void);

/* Writes the key text of desc into key (replacing its content).  Returns 0,
 * DM_ERR_ARG without a technique or with a size < 1, DM_ERR_UNKNOWN for an
 * unknown technique, DM_ERR_NOTFOUND when a shader stage is not embedded. */
int refcache_key(const refcache_desc *desc, dm_str *key);

/* Loads the entry of `key` from dir: 0 and malloc'd w*h*4 colour and w*h
 * depth (depth may be NULL: not returned); DM_ERR_NOTFOUND when there is no
 * entry or it is for another key or size; DM_ERR_IO when it is truncated.
 * On failure *rgba and *depth are untouched. */
int refcache_load(const char *dir, const char *key, int w, int h, float **rgba, float **depth);

/* Stores an entry (dir created when missing; atomic replace), then trims
 * the cache to REFCACHE_MAX_BYTES.  Returns 0 or DM_ERR_IO. */
int refcache_store(const char *dir, const char *key, int w, int h, const float *rgba,
                   const float *depth);

/* The cache is per user and keyed by everything, so it only grows: after
 * each store the least recently used entries (a load refreshes an entry's
 * modification time) are removed until the entries total at most
 * max_bytes.  Returns the number of entries removed (0 when none or when
 * dir cannot be read). */
#define REFCACHE_MAX_BYTES (256ull << 20)
int refcache_trim(const char *dir, unsigned long long max_bytes);

#endif
