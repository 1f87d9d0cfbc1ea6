// dm_image.cc — float RGBA images and their files, through OpenImageIO.
//
// The only C++ of core/.  Every function catches all exceptions (none may
// cross into C) and turns OIIO failures into DM_ERR_* codes with OIIO's
// message and the path in err.

#include "core/dm_image.h"

extern "C" {
#include "core/dm_error.h"
#include "core/dm_util.h"
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
    // Encoded in memory, then written by dm_write_file: a temp file beside
    // path renamed over it, so a failed write leaves no partial file, and
    // errno (which OIIO's own writer loses) tells a full disk from a bad path.
    std::vector<unsigned char> bytes;
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
        Filesystem::IOVecOutput vec(bytes);
        out->set_write_ioproxy(&vec);
        if (out->has_error() || !out->write(path)) {
            std::string e = out->geterror();
            set_err(err, errlen, path, e.empty() ? "cannot encode the image" : e);
            return DM_ERR_IO;
        }
    } catch (const std::bad_alloc &) {
        char why[160];
        set_err(err, errlen, path, dm_nomem_reason(why, sizeof why));
        return DM_ERR_NOMEM;
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    int rc = dm_write_file(path, bytes.data(), bytes.size());
    if (rc)
        set_err(err, errlen, path, std::strerror(errno));
    return rc;
}

// Expands the n channels read into each pixel's first slots (stride 4) to
// RGBA: grey (1 channel) to RGB with alpha 1; grey+alpha (2 channels, the
// second alpha) to RGB and A; two other channels to R, G with B 0, alpha 1;
// RGB with alpha 1; four kept.
static void expand_to_rgba(float *px, size_t npix, int n, bool grey_alpha)
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

// The reason of a failed allocation of a w x h float RGBA image.
static std::string nomem_reason(int w, int h)
{
    char buf[256], why[160];
    std::snprintf(buf, sizeof buf, "a %dx%d image needs %.0f MB as float RGBA: %s", w, h,
                  (double)w * h * 4 * sizeof(float) / (1 << 20), dm_nomem_reason(why, sizeof why));
    return buf;
}

int img_load(const char *path, img *out, char *err, size_t errlen)
{
    if (!path || !out) {
        set_err(err, errlen, path, "no path or no output");
        return DM_ERR_ARG;
    }
    char why[256];
    int rc = dm_input_file(path, why, sizeof why);   // never open a FIFO or /dev/zero
    if (rc) {
        set_err(err, errlen, path, why);
        return rc == DM_ERR_NOTFOUND ? DM_ERR_IO : rc;
    }
    img tmp = {0, 0, nullptr};
    int w = 0, h = 0;
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
        w = s.width;
        h = s.height;
        if (w <= 0 || h <= 0 || s.depth > 1 || s.nchannels < 1 || s.deep) {
            set_err(err, errlen, path, "not a flat 2-D image with pixels");
            return DM_ERR_IO;
        }
        if ((double)w * h > IMG_MAX_PIXELS) {
            char m[160];
            double side = std::floor(std::sqrt((double)IMG_MAX_PIXELS));
            std::snprintf(m, sizeof m, "%dx%d pixels: more than an image may have (%.0fx%.0f)", w, h,
                          side, side);
            set_err(err, errlen, path, m);
            return DM_ERR_IO;
        }
        if ((rc = img_alloc(&tmp, w, h)) != 0) {
            set_err(err, errlen, path, nomem_reason(w, h));
            return rc;
        }
        int n = std::min(s.nchannels, 4);
        const std::string second = n == 2 ? s.channel_name(1) : "";
        bool grey_alpha = n == 2 && (s.alpha_channel == 1 || second == "A" || second == "Alpha");
        if (!in->read_image(0, 0, 0, n, TypeDesc::FLOAT, tmp.px, 4 * sizeof(float))) {
            std::string e = in->geterror();
            set_err(err, errlen, path, e.empty() ? "cannot decode the pixels" : e);
            img_free(&tmp);
            return DM_ERR_IO;
        }
        expand_to_rgba(tmp.px, (size_t)w * h, n, grey_alpha);
        *out = tmp;
    } catch (const std::bad_alloc &) {
        img_free(&tmp);
        set_err(err, errlen, path, nomem_reason(w, h));
        return DM_ERR_NOMEM;
    } catch (const std::exception &e) {
        img_free(&tmp);
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
