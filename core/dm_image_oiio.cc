// dm_image_oiio.cc — image files through OpenImageIO: the module
// dmbench_oiio_core.so, which core/dm_image.c loads when an image is first
// read or written (core/dm_image_bridge.h says why).
//
// The only C++ of core/.  It calls nothing of the program (the module links
// OpenImageIO only): writing the bytes and the reasons of a failed
// allocation are dm_image.c's.  Every function catches all exceptions (none
// may cross into C) and turns OIIO failures into DM_ERR_* codes with OIIO's
// message and the path in err.

#include "core/dm_image_bridge.h"

extern "C" {
#include "core/dm_error.h"
}

#include "core/dm_image_oiio.hh"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
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

extern "C" int dm_oiio_encode(const img *im, const char *path, unsigned char **bytes, size_t *len,
                              char *err, size_t errlen)
{
    std::vector<unsigned char> buf;
    try {
        if (!ImageOutput::create(path)) {   // the format comes from the name
            OIIO::geterror();   // cleared: said here in the user's terms
            set_err(err, errlen, path, "no image format for this file name; end it in .png, .exr or .tif");
            return DM_ERR_IO;
        }
        ImageBuf src = wrap(im);
        ImageBuf clamped;
        ImageBuf *out = &src;
        if (ends_with_ci(path, ".png")) {
            clamped = ImageBufAlgo::clamp(src, 0.0f, 1.0f, false);
            clamped.set_write_format(TypeDesc::UINT8);
            out = &clamped;
        } else {
            src.set_write_format(TypeDesc::FLOAT);
        }
        Filesystem::IOVecOutput vec(buf);
        out->set_write_ioproxy(&vec);
        if (out->has_error() || !out->write(path)) {
            std::string e = out->geterror();
            set_err(err, errlen, path, e.empty() ? "cannot encode the image" : e);
            return DM_ERR_IO;
        }
    } catch (const std::bad_alloc &) {
        return DM_ERR_NOMEM;
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    *bytes = static_cast<unsigned char *>(std::malloc(buf.size() ? buf.size() : 1));
    if (!*bytes)
        return DM_ERR_NOMEM;
    std::memcpy(*bytes, buf.data(), buf.size());
    *len = buf.size();
    return 0;
}

// Expands the n channels read into each pixel's first slots (stride 4) to
// RGBA: grey (1 channel) to RGB with alpha 1; grey+alpha (2 channels, the
// second alpha) to RGB and A; two other channels to R, G with B 0, alpha 1;
// RGB with alpha 1; four kept.
static void dm_image_oiio__expand_to_rgba(float *px, size_t npix, int n, bool grey_alpha)
{
    for (size_t i = 0; i < npix; i++) {
        float *p = px + i * 4;
        if (n == 1)
            p[1] = p[2] = p[0], p[3] = 1.0f;
        else if (n == 2 && grey_alpha)
            p[3] = p[1], p[1] = p[2] = p[0];
        else if (n == 2)
            p[2] = 0.0f, p[3] = 1.0f;
        else if (n == 3)
            p[3] = 1.0f;
    }
}

extern "C" int dm_oiio_load(const char *path, size_t max_pixels, img *out, int *w, int *h,
                            char *err, size_t errlen)
{
    float *px = nullptr;
    try {
        // Read straight into the RGBA buffer (stride 4 floats): one copy of
        // the pixels in memory, and no OIIO buffer whose failed allocation
        // would go unnoticed.
        auto in = ImageInput::open(path);
        if (!in) {
            set_err(err, errlen, path, OIIO::geterror());
            return DM_ERR_IO;
        }
        const ImageSpec s = in->spec();
        *w = s.width;
        *h = s.height;
        if (s.width <= 0 || s.height <= 0 || s.depth > 1 || s.nchannels < 1 || s.deep) {
            set_err(err, errlen, path, "not a flat 2-D image with pixels");
            return DM_ERR_IO;
        }
        if ((double)s.width * s.height > (double)max_pixels) {
            char m[160];
            double side = std::floor(std::sqrt((double)max_pixels));
            std::snprintf(m, sizeof m, "%dx%d pixels: more than an image may have (%.0fx%.0f)", s.width,
                          s.height, side, side);
            set_err(err, errlen, path, m);
            return DM_ERR_IO;
        }
        px = static_cast<float *>(std::calloc((size_t)s.width * (size_t)s.height * 4, sizeof(float)));
        if (!px)
            return DM_ERR_NOMEM;
        int n = std::min(s.nchannels, 4);
        const std::string second = n == 2 ? s.channel_name(1) : "";
        bool grey_alpha = n == 2 && (s.alpha_channel == 1 || second == "A" || second == "Alpha");
        if (!in->read_image(0, 0, 0, n, TypeDesc::FLOAT, px, 4 * sizeof(float))) {
            std::string e = in->geterror();
            set_err(err, errlen, path, e.empty() ? "cannot decode the pixels" : e);
            std::free(px);
            return DM_ERR_IO;
        }
        dm_image_oiio__expand_to_rgba(px, (size_t)s.width * s.height, n, grey_alpha);
        out->w = s.width;
        out->h = s.height;
        out->px = px;
    } catch (const std::bad_alloc &) {
        std::free(px);
        return DM_ERR_NOMEM;
    } catch (const std::exception &e) {
        std::free(px);
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    return 0;
}
