/* maps.h — procedural material maps (height, normal, albedo, specular).
 *
 * Maps are square images generated on the CPU, row 0 = v 0, and tile (every
 * set is periodic in u and v).  Height is one channel in [0,1]; the normal
 * map is tangent-space, unit vectors in [-1,1]^3 (z up, out of the surface),
 * derived from the height map by central differences with a stated strength
 * (maps_normal_rows) so the two agree; albedo is linear RGB, specular a
 * linear [0,1] intensity.
 *
 * Two layouts: the full one (float height, normal, albedo RGBA, specular —
 * for tests and small sets) and the compact one (desc.compact = 1: float
 * height and 8-bit sRGB albedo with linear specular in alpha; no normal
 * array, the caller derives normal rows on the fly) which is what the
 * renderer uses so a 16384² set costs 2 GiB, not 9.  Compact sets of at
 * least MAPS_CACHE_MIN_SIZE texels are cached on disk (maps_cache_dir) and
 * loaded instead of regenerated.
 */
#ifndef TECHNIQUES_MAPS_H
#define TECHNIQUES_MAPS_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_util.h"

typedef struct maps_desc {
    const char *name;       /* "bricks" (default), "stones", "terrain", "checker", "sine", "flat",
                             * "asteroid" (baked from mesh_asteroid_radius over the sphere UVs;
                             * its normal map is the body's true normal, filled in both layouts) */
    int size;               /* texels per side; 0 = 512 */
    float normal_strength;  /* 0 = 1.0: scale of height gradients into the normal */
    int compact;            /* 1: compact layout (see the top comment) */
} maps_desc;

typedef struct maps_set {
    int size;
    float *height;          /* size*size */
    float *normal;          /* size*size*3 (full layout only) */
    float *albedo;          /* size*size*4, alpha 1 (full layout only) */
    float *specular;        /* size*size (full layout only) */
    uint8_t *albedo8;       /* size*size*4: sRGB RGB + linear specular (compact only) */
    int64_t gen_ns;         /* time generating (0 when loaded from the cache) */
    int64_t load_ns;        /* time reading the cache file (0 when generated) */
    int from_cache;         /* 1 when loaded from the disk cache */
    int from_memory;        /* 1 when copied from this process's earlier set (maps_get_cached) */
} maps_set;

/* Texel counts per side accepted by maps_generate. */
#define MAPS_MIN_SIZE 16
#define MAPS_MAX_SIZE 16384
/* Compact sets this large or larger go through the disk cache. */
#define MAPS_CACHE_MIN_SIZE 1024
/* Smaller sets a process made or loaded: the last MAPS_MEMO_SETS are kept
 * in memory (maps_get_cached copies them). */
#define MAPS_MEMO_SETS 8
/* Gradient scale at normal_strength 1: the default height_scale 0.06 spread
 * over the 2 world units that the UV range 0..1 spans on the built-in plane,
 * so the normal map matches the displaced surface of the default scene. */
#define MAPS_NORMAL_SCALE 0.03f
/* The height_scale a normal map derived at normal_strength 1 matches: the
 * renderer scales such a map's x and y by height_scale / this before
 * normalising, which is exact for a normal derived from a height field. */
#define MAPS_NORMAL_HEIGHT_SCALE (2.0f * MAPS_NORMAL_SCALE)
/* The analytic sets: `sine` is h = 0.5 + 0.25 (sin 2πFu + sin 2πFv) with
 * F = MAPS_SINE_FREQ; `checker` has MAPS_CHECKER_SQUARES squares per side,
 * albedo 0.05 / 0.95, height 0.5. */
#define MAPS_SINE_FREQ 4
#define MAPS_CHECKER_SQUARES 32

const char *const *maps_names(void);   /* NULL-terminated */
/* Index of a set in maps_names(), or -1. */
int maps_kind(const char *name);
/* Level-0 texel (x, y) of a size² grid of set `kind` (coordinates wrap)
 * exactly as the compact layout stores it, decoded: the float height, the
 * linear albedo RGB of its 8-bit sRGB code, and the specular of its 8-bit
 * code in rgba[3].  The virtual texture builds its pages from this, so a
 * page equals the matching region of the plain texture. */
void maps_texel(int kind, long size, long x, long y, float *h, float rgba[4]);
/* Generates a set (no cache).  Returns 0, DM_ERR_UNKNOWN for an unknown set,
 * DM_ERR_RANGE for a bad size; out is untouched on failure. */
int maps_generate(const maps_desc *desc, maps_set *out);
/* Compact set (desc->compact is implied) from the cache directory `dir`
 * (NULL = maps_cache_dir()) when a file for (name, size) is there, else
 * generated and written there (a write failure is only logged).  Same
 * return codes as maps_generate. */
int maps_get_cached(const maps_desc *desc, const char *dir, maps_set *out);
/* 1 when maps_get_cached would copy the set from this process's memory. */
int maps_in_memory(const maps_desc *desc);
/* The cache directory: $DMBENCH_CACHE_DIR/maps, else
 * $XDG_CACHE_HOME/dmbench/maps, else $HOME/.cache/dmbench/maps (malloc'd). */
char *maps_cache_dir(void);
void maps_free(maps_set *m);
/* Normal rows [y0, y1) of a size×size height map by central differences
 * with wrap-around: g_u = (h[x+1] - h[x-1]) * size/2 is ∂h/∂u per unit of
 * UV (likewise g_v along rows), s = strength * MAPS_NORMAL_SCALE and
 * n = normalize(-s*g_u, -s*g_v, 1).  normal gets (y1-y0)*size*3 floats. */
void maps_normal_rows(const float *height, int size, float strength, int y0, int y1, float *normal);
/* All rows: maps_normal_rows(height, size, strength, 0, size, normal). */
void maps_normal_from_height(const float *height, int size, float strength, float *normal);
/* User maps ("material"): a `maps` value of the form
 * "height=PATH;normal=PATH;albedo=PATH" (any non-empty subset, any order)
 * names image files OpenImageIO reads.  Each must decode, be square with a
 * power-of-two side in [MAPS_MIN_SIZE, MAPS_MAX_SIZE], all of one size, and
 * hold only finite values.  A missing height is flat 0.5, a missing normal
 * is derived from the height (maps_normal_rows), a missing albedo is 0.75
 * grey.  Height is the file's first channel; normal files hold n·0.5+0.5;
 * albedo files are sRGB-encoded unless they are .exr (linear). */
int maps_is_material(const char *value);
/* Validates a material value; 0, or DM_ERR_ARG / DM_ERR_IO with a message
 * naming the key and the file appended to err (DM_ERR_NOMEM when a file's
 * pixels cannot be allocated: the machine's, not the file's). */
int maps_material_check(const char *value, dm_str *err);
/* The files of a material value: paths[0..2] = height, normal, albedo
 * (malloc'd, NULL where absent).  Returns 0, or DM_ERR_ARG with why in err
 * (every paths[k] NULL then). */
int maps_material_paths(const char *value, char *paths[3], dm_str *err);
/* Loads a material into a full-layout set; same codes and messages. */
int maps_material_load(const char *value, maps_set *out, dm_str *err);
/* sRGB transfer functions on [0,1]. */
float maps_srgb_encode(float linear);
float maps_srgb_decode(float encoded);
/* The 8-bit sRGB code of a linear value (what the compact sets store):
 * the number of thresholds maps_srgb_decode((k + 0.5) / 255), k = 0..254,
 * at or below it, i.e. the code nearest to 255 * maps_srgb_encode(x)
 * without a pow; NaN and values <= 0 give 0, values >= 1 give 255. */
uint8_t maps_srgb8(float linear);

#endif
