/* dm_image_bridge.h — the OpenImageIO bridges as modules loaded on first use.
 *
 * OpenImageIO brings about 250 shared libraries with it; linked into the
 * binary, the dynamic loader relocated all of them at every start (0.45 s
 * of CPU, 14 s under Valgrind), though most commands read or write no image.
 * So the code that calls OpenImageIO is built as two modules,
 * dmbench_oiio_core.so (core/dm_image_oiio.cc: files) and
 * dmbench_oiio_imaging.so (imaging/oiio_bridge.cc: comparisons, heatmaps,
 * thumbnails), and the C functions of dm_image.h and imaging/image.h load
 * them with dlopen when an image is first read or written.
 *
 * The functions below are the modules' C entry points, each named in the
 * module by its own name.  A build that defines DM_OIIO_STATIC links the
 * modules' sources into the program instead (the fuzz targets do). */
#ifndef CORE_DM_IMAGE_BRIDGE_H
#define CORE_DM_IMAGE_BRIDGE_H

#include <stddef.h>
#include "core/dm_image.h"

#ifdef __cplusplus
extern "C" {
#endif

#define DM_OIIO_CORE_MODULE "dmbench_oiio_core.so"
#define DM_OIIO_IMAGING_MODULE "dmbench_oiio_imaging.so"

/* Encodes im by path's extension into *bytes (malloc'd, *len bytes).
 * Returns 0, DM_ERR_IO (no format for the name, or encoding failed) or
 * DM_ERR_NOMEM (with no message: the caller says why), "path: reason" in
 * err. */
typedef int dm_oiio_encode_fn(const img *im, const char *path, unsigned char **bytes, size_t *len,
                              char *err, size_t errlen);
/* Decodes path (already checked by dm_input_file) into *out as RGBA float,
 * at most max_pixels pixels.  Returns 0, DM_ERR_IO with "path: reason" in
 * err, or DM_ERR_NOMEM with the image's size in *w, *h and no message. */
typedef int dm_oiio_load_fn(const char *path, size_t max_pixels, img *out, int *w, int *h,
                            char *err, size_t errlen);

dm_oiio_encode_fn dm_oiio_encode;
dm_oiio_load_fn dm_oiio_load;

/* The address of symbol `name` of module `module` (DM_OIIO_CORE_MODULE or
 * DM_OIIO_IMAGING_MODULE), loaded at the first call and kept; NULL when it
 * cannot be loaded, with "OpenImageIO bridge unavailable: why" in err.  The
 * module is looked for in the build tree's lib/ (the path this build was
 * configured with), in lib/ beside the program (a moved build tree), in
 * ../lib/dmbench/ from it (an install under another prefix), and in the
 * lib/dmbench/ of the prefix configured. */
void *dm_image_bridge(const char *module, const char *name, char *err, size_t errlen);
/* The error code of the calling thread's last failed dm_image_bridge:
 * DM_ERR_NOMEM when the module was there but its libraries could not be
 * mapped (an address-space limit, ulimit -v: exit 4, and err then says
 * so), else DM_ERR_IO (a module missing or damaged). */
int dm_image_bridge_failure(void);

/* Entry point fn (of type fn_fn) of module: from dm_image_bridge, or its
 * address in a DM_OIIO_STATIC build. */
#ifdef DM_OIIO_STATIC
#define DM_OIIO_FN(module, fn, err, errlen) (&fn)
#else
#define DM_OIIO_FN(module, fn, err, errlen) ((fn##_fn *)dm_image_bridge(module, #fn, err, errlen))
#endif

#ifdef __cplusplus
}
#endif

#endif
