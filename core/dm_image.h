/* dm_image.h — float RGBA images and their files (OpenImageIO behind a C header).
 *
 * An img is RGBA32F, row-major, row 0 at the top (run/target.c flips GL's
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
/* Saves by extension (.png, .exr, .tif), encoded in memory and written with
 * dm_write_file (no partial file is ever left at path).  Returns 0,
 * DM_ERR_DISK (the disk refused the write: exit 4), DM_ERR_IO (an unknown
 * extension, a directory that does not exist or cannot be written) or
 * DM_ERR_NOMEM, with "path: reason" (strerror for a write) in err. */
int img_save(const img *im, const char *path, char *err, size_t errlen);
/* The most pixels img_load reads: 16384x16384, the largest map (4 GB as
 * float RGBA); a header claiming more is refused before any allocation.  A
 * build may lower it (the fuzz target of the reader does, so that a header
 * claiming a large image does not count as a runaway allocation). */
#ifndef IMG_MAX_PIXELS
#define IMG_MAX_PIXELS ((size_t)16384 * 16384)
#endif
/* Loads any format OpenImageIO reads, converted to RGBA float: grey to RGB
 * with alpha 1, grey+alpha to RGB and A, RGB with alpha 1, the first four
 * channels of more.  The path passes dm_input_file first (a FIFO or a device
 * is never opened).  Returns 0; DM_ERR_ARG (not a regular file), DM_ERR_IO
 * (missing, unreadable, not an image, more than IMG_MAX_PIXELS) or
 * DM_ERR_NOMEM (its pixels could not be allocated: the machine's, exit 4),
 * with "path: reason" in err. */
int img_load(const char *path, img *out, char *err, size_t errlen);
/* Box-filter downsample by an integer factor: exact block means. */
int img_downsample(const img *src, int factor, img *out);

#ifdef __cplusplus
}
#endif

#endif
