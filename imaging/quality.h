/* quality.h — image-quality metrics of a render against its reference (docs/sweep-files.md, Quality).
 *
 * Pure C over the float RGBA images of image.h; no OpenImageIO needed.
 * Coverage masks are one byte per pixel, 1 = covered, row-major like img.
 */
#ifndef IMAGING_QUALITY_H
#define IMAGING_QUALITY_H

#include "imaging/image.h"

/* Mean SSIM of the luma (Y = 0.2126 R + 0.7152 G + 0.0722 B) of a and b:
 * Gaussian 11×11 window, sigma 1.5, K1 = 0.01, K2 = 0.03, L = 1, averaged
 * over the window positions fully inside the image (no padding).
 * Images narrower or shorter than 11 pixels: the window along that axis
 * has as many taps as the image has pixels (the same sigma, centred, the
 * weights renormalised), so a 4×4 image is one 4×4 window and a 1×1 image
 * compares its single pixel (luminance term only); identical images give
 * exactly 1 at every size.  DM_ERR_ARG when sizes differ or an image is
 * empty. */
int quality_ssim(const img *a, const img *b, double *ssim);

/* Coverage mask of an image: alpha > 0.5.  mask must hold w*h bytes. */
void quality_coverage(const img *im, unsigned char *mask);

/* 1 − IoU of two coverage masks of n pixels; 0 when both are empty. */
double quality_silhouette_error(const unsigned char *ma, const unsigned char *mb, size_t n);

/* RMSE of depth over the pixels both masks cover.  Returns DM_ERR_UNAVAILABLE
 * (and *rmse untouched) when no pixel is covered by both. */
int quality_depth_rmse(const float *da, const float *db, const unsigned char *ma,
                       const unsigned char *mb, size_t n, double *rmse);

/* Number of pixels with at least one non-finite (NaN/Inf) channel. */
long quality_nonfinite_pixels(const img *im);

/* Background pixels (mask 0) not 4-connected to the image border through
 * background: holes and cracks in the rendered surface.  -1 on OOM. */
long quality_crack_pixels(const unsigned char *mask, int w, int h);

#endif
