/* image_bridge.h — the entry points of the module dmbench_oiio_imaging.so
 * (imaging/oiio_bridge.cc), which imaging/image.c loads when an image is
 * first compared, mapped or shrunk (core/dm_image_bridge.h says why).  Each
 * does what the function of image.h of the same name without the dm_oiio_
 * prefix says, and is named in the module by its own name. */
#ifndef IMAGING_IMAGE_BRIDGE_H
#define IMAGING_IMAGE_BRIDGE_H

#include "imaging/image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef int dm_oiio_compare_fn(const img *a, const img *b, double threshold, img_metrics *out);
typedef int dm_oiio_heatmap_fn(const img *a, const img *b, double scale, const char *path, char *err,
                               size_t errlen);
typedef int dm_oiio_thumbnail_png_fn(const char *path, int max_dim, unsigned char **png, size_t *len,
                                     char *err, size_t errlen);

dm_oiio_compare_fn dm_oiio_compare;
dm_oiio_heatmap_fn dm_oiio_heatmap;
dm_oiio_thumbnail_png_fn dm_oiio_thumbnail_png;

#ifdef __cplusplus
}
#endif

#endif
