/* dm_image.h — float RGBA images and their files (OpenImageIO behind a C header).
 *
 * An img is RGBA32F, row-major, row 0 at the top (the harness flips GL's
 * bottom-up rows when reading back).  PNG output is 8-bit with values
 * clamped to [0,1]; EXR keeps floats.  Layer-neutral: techniques/ reads and
 * caches maps with it, reports/ writes renders and heatmaps.
 */
#ifndef CORE_DM_IMAGE_H
#define CORE_DM_IMAGE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct img {
    int w, h;
    float *px;               /* w*h*4 floats, owned */
} img;

int img_alloc(img *im, int w, int h);        /* zero-filled; DM_ERR_NOMEM */
void img_free(img *im);
/* Saves by extension (.png, .exr, .tif).  DM_ERR_IO with the reason in err. */
int img_save(const img *im, const char *path, char *err, size_t errlen);
/* Loads any format OpenImageIO reads, converted to RGBA float (missing
 * channels: grey replicated, alpha 1).  DM_ERR_IO with the reason in err. */
int img_load(const char *path, img *out, char *err, size_t errlen);
/* Box-filter downsample by an integer factor: exact block means. */
int img_downsample(const img *src, int factor, img *out);

#ifdef __cplusplus
}
#endif

#endif
