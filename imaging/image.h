/* image.h — image comparison, heatmaps and thumbnails (OpenImageIO bridge).
 * Buffers and files: core/dm_image.h, included here.
 *
 * An img is RGBA32F, row-major, row 0 at the top (the harness flips GL's
 * bottom-up rows when reading back).  PNG output is 8-bit with values
 * clamped to [0,1]; EXR keeps floats.
 */
#ifndef IMAGING_IMAGE_H
#define IMAGING_IMAGE_H

#include <stddef.h>
#include "core/dm_image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct img_metrics {
    double rmse, psnr;       /* over RGB; psnr = INFINITY when identical */
    double max_error;
    double pct_over;         /* percent of pixels with any channel error > threshold */
    long nonfinite;          /* NaN/Inf values in b (the test image) */
} img_metrics;

/* RGB metrics of b against reference a (same size, else DM_ERR_ARG);
 * threshold for pct_over (e.g. 0.05). */
int img_compare(const img *a, const img *b, double threshold, img_metrics *out);
/* Writes |a-b| (max over RGB, scaled so `scale` maps to 1) through the
 * inferno colour map as PNG.  scale <= 0 = auto (max difference). */
int img_heatmap(const img *a, const img *b, double scale, const char *path, char *err, size_t errlen);
/* Reads the image at path, shrinks it to fit max_dim × max_dim (aspect kept,
 * never enlarged; OIIO resize, default filter) and encodes it as an 8-bit
 * PNG in memory: *png is malloc'd, *len its size.  DM_ERR_IO (reason and path
 * in err) when the file cannot be read or encoded; DM_ERR_ARG on bad args. */
int img_thumbnail_png(const char *path, int max_dim, unsigned char **png, size_t *len,
                      char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
