// dm_image_oiio.hh — helpers shared by the two OpenImageIO bridges
// (core/dm_image_oiio.cc and imaging/oiio_bridge.cc, the two modules).  C++ only, internal.
#ifndef CORE_DM_IMAGE_OIIO_HH
#define CORE_DM_IMAGE_OIIO_HH

#include "core/dm_image_bridge.h"   /* img, through the one header the modules share */

#include <OpenImageIO/imagebuf.h>
#include <cstdio>
#include <string>

namespace dm_oiio {

// "path: why" into err (when given), the form every bridge error takes.
inline void set_err(char *err, size_t errlen, const char *path, const std::string &why)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s: %s", path ? path : "(null)", why.c_str());
}

// Wraps the img's float buffer (no copy) as a 4-channel ImageBuf.
inline OIIO::ImageBuf wrap(const img *im)
{
    OIIO::ImageSpec spec(im->w, im->h, 4, OIIO::TypeDesc::FLOAT);
    return OIIO::ImageBuf(spec, const_cast<float *>(im->px));
}

}  // namespace dm_oiio

#endif
