// oiio_bridge.cc — the only C++ of imaging/: OpenImageIO comparisons, heatmaps
// and thumbnails behind image.h, built as the module dmbench_oiio_imaging.so
// that imaging/image.c loads on first use (core/dm_image_bridge.h says why;
// buffers and files are core/dm_image.c's).  It calls nothing of the program.
//
// Every function catches all exceptions (none may cross into C) and turns
// OIIO failures into DM_ERR_* codes with OIIO's message and the path in err.

#include "imaging/image_bridge.h"

extern "C" {
#include "core/dm_error.h"
}

#include "core/dm_image_oiio.hh"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace OIIO;
using dm_oiio::set_err;
using dm_oiio::wrap;

namespace {


int same_size(const img *a, const img *b)
{
    return a && b && a->px && b->px && a->w == b->w && a->h == b->h;
}

}  // namespace

// PNG: 8-bit, values clamped to [0,1] first (OIIO would clamp too, but doing
// it here makes the contract explicit and NaN-safe: NaN becomes 0).
// Anything else (EXR, TIFF): float as stored.
// Loads any OIIO-readable file as RGBA float; 1-3 channel files get their
// missing channels filled (grey → RGB, alpha = 1).
// Exact block means.  OIIO's resize with a "box" filter was checked: at
// filter width 1 it differs from the block mean in the last float bits, at
// width 2 it blends neighbouring blocks; so the averaging is done here, in
// double, and every output pixel is exactly sum/factor² rounded once.
// RMSE/max error/over-threshold come from ImageBufAlgo::compare on the RGB
// channels; PSNR uses peak 1.0.  Non-finite values of b are counted here.
extern "C" int dm_oiio_compare(const img *a, const img *b, double threshold, img_metrics *out)
{
    if (!same_size(a, b) || !out)
        return DM_ERR_ARG;
    try {
        ImageBuf A = wrap(a), B = wrap(b);
        ROI rgb(0, a->w, 0, a->h, 0, 1, 0, 3);
        auto r = ImageBufAlgo::compare(A, B, (float)threshold, (float)threshold, rgb);
        /* r.error only says that some pixel failed the threshold */
        if (A.has_error() || B.has_error())
            return DM_ERR_NUMERIC;
        out->rmse = r.rms_error;
        out->psnr = r.rms_error == 0 ? INFINITY : 20.0 * std::log10(1.0 / r.rms_error);
        out->max_error = r.maxerror;
        out->pct_over = 100.0 * (double)r.nfail / ((double)a->w * a->h);
        long nf = 0;
        for (size_t i = 0, n = (size_t)b->w * b->h * 4; i < n; i++)
            nf += !std::isfinite(b->px[i]);
        out->nonfinite = nf;
    } catch (const std::exception &) {
        return DM_ERR_NUMERIC;
    }
    return 0;
}

extern "C" int dm_oiio_heatmap(const img *a, const img *b, double scale, const char *path,
                               char *err, size_t errlen)
{
    if (!same_size(a, b) || !path) {
        set_err(err, errlen, path, "images missing or of different sizes");
        return DM_ERR_ARG;
    }
    size_t n = (size_t)a->w * a->h;
    float *d = static_cast<float *>(std::malloc(n * sizeof(float)));
    if (!d)
        return DM_ERR_NOMEM;
    double mx = 0;
    for (size_t i = 0; i < n; i++) {
        float m = 0;
        for (int c = 0; c < 3; c++) {
            float e = std::fabs(a->px[i * 4 + c] - b->px[i * 4 + c]);
            m = std::isfinite(e) ? std::fmax(m, e) : 1e30f; // non-finite shows as hottest
        }
        d[i] = m;
        if (m < 1e30f)
            mx = std::fmax(mx, m);
    }
    double s = scale > 0 ? scale : (mx > 0 ? mx : 1.0);
    for (size_t i = 0; i < n; i++)
        d[i] = (float)std::fmin(1.0, d[i] / s);
    int rc = 0;
    try {
        ImageBuf diff(ImageSpec(a->w, a->h, 1, TypeDesc::FLOAT), d);
        ImageBuf hm = ImageBufAlgo::color_map(diff, 0, "inferno");
        hm.set_write_format(TypeDesc::UINT8);
        if (hm.has_error() || !hm.write(path)) {
            set_err(err, errlen, path, hm.geterror());
            rc = DM_ERR_IO;
        }
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        rc = DM_ERR_IO;
    }
    std::free(d);
    return rc;
}

extern "C" int dm_oiio_thumbnail_png(const char *path, int max_dim, unsigned char **png, size_t *len,
                                      char *err, size_t errlen)
{
    if (!path || !png || !len || max_dim <= 0) {
        set_err(err, errlen, path, "bad thumbnail arguments");
        return DM_ERR_ARG;
    }
    try {
        ImageBuf in(path);
        if (!in.read(0, 0, true, TypeDesc::FLOAT)) {
            set_err(err, errlen, path, in.geterror());
            return DM_ERR_IO;
        }
        const ImageSpec &s = in.spec();
        double k = std::min(1.0, (double)max_dim / std::max(s.width, s.height));
        int w = std::max(1, (int)(s.width * k + 0.5)), h = std::max(1, (int)(s.height * k + 0.5));
        ImageBuf small = (w == s.width && h == s.height)
            ? in : ImageBufAlgo::resize(in, "", 0, ROI(0, w, 0, h, 0, 1, 0, s.nchannels));
        std::vector<unsigned char> bytes;
        Filesystem::IOVecOutput vec(bytes);
        small.set_write_format(TypeDesc::UINT8);
        small.set_write_ioproxy(&vec);
        if (small.has_error() || !small.write("thumbnail.png", TypeUnknown, "png")) {
            set_err(err, errlen, path, small.geterror());
            return DM_ERR_IO;
        }
        unsigned char *out = static_cast<unsigned char *>(std::malloc(bytes.size() ? bytes.size() : 1));
        if (!out)
            return DM_ERR_NOMEM;
        std::memcpy(out, bytes.data(), bytes.size());
        *png = out;
        *len = bytes.size();
    } catch (const std::exception &e) {
        set_err(err, errlen, path, e.what());
        return DM_ERR_IO;
    }
    return 0;
}
