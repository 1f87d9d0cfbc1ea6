/* libFuzzer target: the image reader of `dmbench diff` and of user maps
 * (img_load, core/dm_image.cc) must accept or reject any file without
 * crashing, reading past its buffer or hanging.  An accepted image has a
 * size within IMG_MAX_PIXELS (lowered for this target in CMakeLists.txt)
 * and w*h*4 readable floats; a rejection is one of the codes img_load
 * documents, leaves the output untouched and names the file.  The file's
 * name ends in .img, so OpenImageIO tries every reader it has on it, as it
 * does for a `diff` argument whose extension it does not know. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_image.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, "image", "img");
    img im = {0, 0, NULL};
    char err[512] = "";
    int rc = img_load(path, &im, err, sizeof err);
    if (rc == 0) {
        if (im.w <= 0 || im.h <= 0 || !im.px || (size_t)im.w * (size_t)im.h > IMG_MAX_PIXELS)
            abort();
        volatile float sum = 0;   /* every float is there (ASan checks the reads) */
        for (size_t i = 0, n = (size_t)im.w * im.h * 4; i < n; i++)
            sum += im.px[i];
        (void)sum;
        img_free(&im);
    } else if ((rc != DM_ERR_IO && rc != DM_ERR_ARG && rc != DM_ERR_NOMEM) || im.px ||
               !strstr(err, path) || strlen(err) <= strlen(path) + 2) {
        abort();
    }
    return 0;
}
