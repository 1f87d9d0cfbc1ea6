/* image.c — image.h's comparisons, heatmaps and thumbnails, each through the
 * OpenImageIO module dmbench_oiio_imaging.so (imaging/oiio_bridge.cc),
 * loaded at the first call (core/dm_image_bridge.h says why). */
#include "imaging/image.h"
#include "imaging/image_bridge.h"
#include "core/dm_image_bridge.h"
#include "core/dm_error.h"

#include <stdio.h>

int img_compare(const img *a, const img *b, double threshold, img_metrics *out)
{
    char why[512];
    dm_oiio_compare_fn *f = DM_OIIO_FN(DM_OIIO_IMAGING_MODULE, dm_oiio_compare, why, sizeof why);
    if (!f) {
        fprintf(stderr, "dmbench: %s\n", why);
        return dm_image_bridge_failure() == DM_ERR_NOMEM ? DM_ERR_NOMEM : DM_ERR_UNAVAILABLE;
    }
    return f(a, b, threshold, out);
}

int img_heatmap(const img *a, const img *b, double scale, const char *path, char *err, size_t errlen)
{
    dm_oiio_heatmap_fn *f = DM_OIIO_FN(DM_OIIO_IMAGING_MODULE, dm_oiio_heatmap, err, errlen);
    return f ? f(a, b, scale, path, err, errlen) : dm_image_bridge_failure();
}

int img_thumbnail_png(const char *path, int max_dim, unsigned char **png, size_t *len,
                      char *err, size_t errlen)
{
    dm_oiio_thumbnail_png_fn *f = DM_OIIO_FN(DM_OIIO_IMAGING_MODULE, dm_oiio_thumbnail_png, err, errlen);
    return f ? f(path, max_dim, png, len, err, errlen) : dm_image_bridge_failure();
}
