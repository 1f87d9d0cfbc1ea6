/* dm_image.c — float RGBA images and their files; the files through the
 * OpenImageIO module (core/dm_image_oiio.cc), loaded when an image is first
 * read or written (core/dm_image_bridge.h). */
#include "core/dm_image.h"
#include "core/dm_image_bridge.h"
#include "core/dm_error.h"
#include "core/dm_util.h"

#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int img_alloc(img *im, int w, int h)
{
    if (!im || w <= 0 || h <= 0)
        return DM_ERR_ARG;
    im->px = calloc((size_t)w * (size_t)h * 4, sizeof(float));
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
    free(im->px);
    im->px = NULL;
    im->w = im->h = 0;
}

/* "path: ..." into err, when given. */
__attribute__((format(printf, 3, 4)))
static void dm_image__err(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || !errlen)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* ---- the modules ---------------------------------------------------------- */

/* What the calling thread's last failed dm_image_bridge was (see there). */
static _Thread_local int dm_image__failure = DM_ERR_IO;

int dm_image_bridge_failure(void)
{
    return dm_image__failure;
}

#ifndef DM_OIIO_STATIC
static pthread_mutex_t dm_image__lock = PTHREAD_MUTEX_INITIALIZER;
static struct { const char *module; void *handle; } dm_image__loaded[2];

/* dlopen of dir/module; the handle, or NULL (with dlerror's reason in why
 * when the file is there but does not load). */
static void *dm_image__open(const char *dir, const char *module, char *why, size_t whylen)
{
    char *path = dm_xasprintf("%s/%s", dir, module);
    void *h = NULL;
    if (access(path, F_OK) == 0 && !(h = dlopen(path, RTLD_NOW | RTLD_LOCAL)))
        snprintf(why, whylen, "%s", dlerror());
    free(path);
    return h;
}

/* The module's handle, loaded at the first call; the caller holds the lock. */
static void *dm_image__module(const char *module, char *why, size_t whylen)
{
    size_t slot = 0;
    for (; slot < sizeof dm_image__loaded / sizeof *dm_image__loaded && dm_image__loaded[slot].module; slot++)
        if (strcmp(dm_image__loaded[slot].module, module) == 0)
            return dm_image__loaded[slot].handle;
    char exe[PATH_MAX] = "", *dirs[4];
    size_t nd = 0;
#ifdef DM_OIIO_BUILD_DIR
    dirs[nd++] = dm_xstrdup(DM_OIIO_BUILD_DIR);
#endif
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = n > 0 ? (exe[n] = '\0', strrchr(exe, '/')) : NULL;
    if (slash) {
        *slash = '\0';
        dirs[nd++] = dm_xasprintf("%s/lib", exe);              /* build/dmbench: build/lib */
        dirs[nd++] = dm_xasprintf("%s/../lib/dmbench", exe);   /* PREFIX/bin: PREFIX/lib/dmbench */
    }
#ifdef DM_OIIO_INSTALL_DIR
    dirs[nd++] = dm_xstrdup(DM_OIIO_INSTALL_DIR);
#endif
    why[0] = '\0';
    void *h = NULL;
    for (size_t i = 0; i < nd && !h && !why[0]; i++)
        h = dm_image__open(dirs[i], module, why, whylen);
    dm_str s = {0};
    for (size_t i = 0; i < nd; i++) {
        dm_str_printf(&s, "%s%s", i ? ", " : "", dirs[i]);
        free(dirs[i]);
    }
    if (!h && !why[0])
        snprintf(why, whylen, "no %s in %s", module, nd ? dm_str_get(&s) : "(no directory)");
    dm_str_free(&s);
    if (h && slot < sizeof dm_image__loaded / sizeof *dm_image__loaded)
        dm_image__loaded[slot].module = module, dm_image__loaded[slot].handle = h;
    return h;
}

void *dm_image_bridge(const char *module, const char *name, char *err, size_t errlen)
{
    char why[1024];
    pthread_mutex_lock(&dm_image__lock);
    void *h = dm_image__module(module, why, sizeof why);
    void *sym = h ? dlsym(h, name) : NULL;
    if (h && !sym)
        snprintf(why, sizeof why, "%s has no %s", module, name);
    pthread_mutex_unlock(&dm_image__lock);
    if (!sym) {
        /* the file is there but its libraries cannot be mapped: memory, not
         * the installation (dlerror has no errno; its text names the cause) */
        int nomem = h == NULL && (strstr(why, "failed to map segment") ||
                                  strstr(why, "annot allocate memory"));
        dm_image__failure = nomem ? DM_ERR_NOMEM : DM_ERR_IO;
        char r[160] = "";
        if (nomem)
            dm_nomem_reason(r, sizeof r);
        dm_image__err(err, errlen, "OpenImageIO bridge unavailable: %s%s%s", why,
                      nomem ? ": " : "", r);
    }
    return sym;
}
#endif

int img_save(const img *im, const char *path, char *err, size_t errlen)
{
    if (!im || !im->px || !path) {
        dm_image__err(err, errlen, "%s: no image or no path", path ? path : "(null)");
        return DM_ERR_ARG;
    }
    char why[1024];
    dm_oiio_encode_fn *encode = DM_OIIO_FN(DM_OIIO_CORE_MODULE, dm_oiio_encode, why, sizeof why);
    if (!encode) {
        dm_image__err(err, errlen, "%s: %s", path, why);
        return dm_image_bridge_failure();
    }
    /* Encoded in memory, then written by dm_write_file: a temp file beside
     * path renamed over it, so a failed write leaves no partial file, and
     * errno (which OIIO's own writer loses) tells a full disk from a bad path. */
    unsigned char *bytes = NULL;
    size_t len = 0;
    int rc = encode(im, path, &bytes, &len, err, errlen);
    if (rc == DM_ERR_NOMEM) {
        char r[160];
        dm_image__err(err, errlen, "%s: %s", path, dm_nomem_reason(r, sizeof r));
    }
    if (rc)
        return rc;
    rc = dm_write_file(path, bytes, len);
    if (rc)
        dm_image__err(err, errlen, "%s: %s", path, strerror(errno));
    free(bytes);
    return rc;
}

int img_load(const char *path, img *out, char *err, size_t errlen)
{
    if (!path || !out) {
        dm_image__err(err, errlen, "%s: no path or no output", path ? path : "(null)");
        return DM_ERR_ARG;
    }
    char why[1024];
    int rc = dm_input_file(path, why, sizeof why);   /* never open a FIFO or /dev/zero */
    if (rc) {
        dm_image__err(err, errlen, "%s: %s", path, why);
        return rc == DM_ERR_NOTFOUND ? DM_ERR_IO : rc;
    }
    dm_oiio_load_fn *load = DM_OIIO_FN(DM_OIIO_CORE_MODULE, dm_oiio_load, why, sizeof why);
    if (!load) {
        dm_image__err(err, errlen, "%s: %s", path, why);
        return dm_image_bridge_failure();
    }
    int w = 0, h = 0;
    img tmp = {0, 0, NULL};
    rc = load(path, IMG_MAX_PIXELS, &tmp, &w, &h, err, errlen);
    if (rc == DM_ERR_NOMEM) {
        char r[160];
        dm_image__err(err, errlen, "%s: a %dx%d image needs %.0f MB as float RGBA: %s", path, w, h,
                 (double)w * h * 4 * sizeof(float) / (1 << 20), dm_nomem_reason(r, sizeof r));
    }
    if (rc)
        return rc;
    *out = tmp;
    return 0;
}

int img_downsample(const img *src, int factor, img *out)
{
    if (!src || !src->px || !out || factor <= 0 || src->w % factor || src->h % factor)
        return DM_ERR_ARG;
    img d = {0, 0, NULL};
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
