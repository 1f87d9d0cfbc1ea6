// dm_image.cc — float RGBA images and their files, through OpenImageIO.
//
// The only C++ of core/.  Every function catches all exceptions (none may
// cross into C) and turns OIIO failures into DM_ERR_* codes with OIIO's
// message and the path in err.

#include "core/dm_image.h"

extern "C" {
#include "core/dm_error.h"
}

#include "core/dm_image_oiio.hh"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <strings.h>
#include <vector>

using namespace OIIO;
using dm_oiio::set_err;
using dm_oiio::wrap;

namespace {

bool ends_with_ci(const char *s, const char *suffix)
{
    size_t n = std::strlen(s), m = std::strlen(suffix);
    return n >= m && strcasecmp(s + n - m, suffix) == 0;
}


}  // namespace

int img_alloc(img *im, int w, int h)
{
    if (!im || w <= 0 || h <= 0)
        return DM_ERR_ARG;
    im->px = static_cast<float *>(std::calloc((size_t)w * (size_t)h * 4, sizeof(float)));
    if (!im->px)
        return DM_ERR_NOMEM;
    im->w = w;
    im->h = h;
    return 0;
}

void img_free(img *im)
{
    if (!im)
        return;
    std::free(im->px);
    im->px = nullptr;
    im->w = im->h = 0;
}

int img_save(const img *im, const char *path, char *err, size_t errlen)
{
    if (!im || !im->px || !path) {
        set_err(err, errlen, path, "no image or no path");
        return DM_ERR_ARG;
    }
    try {
        ImageBuf src = wrap(im);
        bool png = ends_with_ci(path, ".png");
        ImageBuf out;
        if (png) {
            out = ImageBufAlgo::clamp(src, 0.0f, 1.0f, false);
            out.set_write_format(TypeDesc::UINT8);
        } else {
            out.copy(src);
            out.set_write_format(TypeDesc::FLOAT);
        }
        if (!out.write(path)) {
            set_err(err, errlen, path, out.geterror());
            return DM_ERR_IO;
        }
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    return 0;
}

int img_load(const char *path, img *out, char *err, size_t errlen)
{
    if (!path || !out) {
        set_err(err, errlen, path, "no path or no output");
        return DM_ERR_ARG;
    }
    try {
        ImageBuf in(path);
        if (!in.read(0, 0, true, TypeDesc::FLOAT)) {
            set_err(err, errlen, path, in.geterror());
            return DM_ERR_IO;
        }
        const ImageSpec &s = in.spec();
        int nc = s.nchannels;
        int order[4] = {0, nc > 1 ? 1 : 0, nc > 2 ? 2 : 0, nc > 3 ? 3 : -1};
        float fill[4] = {0, 0, 0, 1};
        ImageBuf rgba = ImageBufAlgo::channels(in, 4, order, fill);
        img tmp = {0, 0, nullptr};
        int rc = img_alloc(&tmp, s.width, s.height);
        if (rc)
            return rc;
        rgba.get_pixels(ROI(0, s.width, 0, s.height, 0, 1, 0, 4), TypeDesc::FLOAT, tmp.px);
        *out = tmp;
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    return 0;
}

int img_downsample(const img *src, int factor, img *out)
{
    if (!src || !src->px || !out || factor <= 0 || src->w % factor || src->h % factor)
        return DM_ERR_ARG;
    img d = {0, 0, nullptr};
    int rc = img_alloc(&d, src->w / factor, src->h / factor);
    if (rc)
        return rc;
    double inv = 1.0 / ((double)factor * factor);
    for (int y = 0; y < d.h; y++)
        for (int x = 0; x < d.w; x++)
            for (int c = 0; c < 4; c++) {
                double sum = 0;
                for (int j = 0; j < factor; j++)
                    for (int i = 0; i < factor; i++)
                        sum += src->px[(((size_t)(y * factor + j) * src->w) + (size_t)(x * factor + i)) * 4 + c];
                d.px[((size_t)y * d.w + x) * 4 + c] = (float)(sum * inv);
            }
    *out = d;
    return 0;
}
