/* render_textures.c — material maps: generation, formats, mip chains,
 * samplers and binding (see render_textures.h).
 *
 * Conventions (render.c's top comment): unit 0 height (R, value in [0,1]),
 * unit 1 normal (n·0.5+0.5), unit 2 albedo (linear RGB; specular in A);
 * GL_REPEAT.  Mip chains are built on the CPU by a 2×2 box filter of the
 * linear values — for the normal map that is the plain average of the
 * encoded vectors, NOT renormalised, so the shader sees the shortened
 * filtered normal that Toksvig needs.  Each level is uploaded in strips of
 * RENDER__STRIP rows with glTextureSubImage2D into immutable storage, so a
 * 16384² map never exists as a whole float copy: level 0 rows are derived
 * from the compact set on the fly (normals by maps_normal_rows) and only
 * level 1 is held as floats.  Compressed formats are encoded by the driver
 * on upload; TextureBytes sums the level sizes GL reports.
 *
 * Storage per normal_format: rgb8/rgba8/rgb16f/rgba16f/rgba32f/bc1/bc3/bc7
 * get (x, y, z); rg8 and bc5 get (x, y) and the shader rebuilds
 * z = sqrt(1 − x² − y²); bc3nm stores (0, y, 0, x) — x in the separately
 * coded alpha block of DXT5 — and the shader reads .ag.  srgb8_a8 albedo is
 * sRGB-encoded before upload so every format samples the same linear values.
 *
 * `filter` picks a sampler: nearest = NEAREST_MIPMAP_NEAREST, bilinear =
 * LINEAR_MIPMAP_NEAREST, trilinear = LINEAR_MIPMAP_LINEAR, anisoN =
 * trilinear + anisotropy min(N, GL_MAX_TEXTURE_MAX_ANISOTROPY) — the prepare
 * log says when N was clamped.
 */
#include "techniques/render_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/axes.h"
#include "techniques/maps.h"
#include "techniques/mesh.h"
#include "techniques/technique.h"
#include "techniques/vt.h"

#define RENDER__STRIP 64   /* rows per upload strip (a multiple of the 4-row block) */

/* How level data (the map's linear channels) becomes upload data. */
enum render__enc { ENC_COPY, ENC_XY, ENC_XA, ENC_SRGB };

typedef struct render__format {
    const char *name;
    GLenum internal;
    int map;            /* 0 height, 1 normal, 2 albedo, -1 any */
    enum render__enc enc;
} render__format;

static const render__format render__formats[] = {
    {"rg8", GL_RG8, 1, ENC_XY}, {"bc5", GL_COMPRESSED_RG_RGTC2, 1, ENC_XY},
    {"bc3nm", GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, 1, ENC_XA},
    {"srgb8_a8", GL_SRGB8_ALPHA8, 2, ENC_SRGB},
    {"r8", GL_R8, -1, ENC_COPY}, {"r16", GL_R16, -1, ENC_COPY}, {"r16f", GL_R16F, -1, ENC_COPY},
    {"r32f", GL_R32F, -1, ENC_COPY}, {"rgba32f", GL_RGBA32F, -1, ENC_COPY},
    {"rgb8", GL_RGB8, -1, ENC_COPY}, {"rgba8", GL_RGBA8, -1, ENC_COPY},
    {"rgb16f", GL_RGB16F, -1, ENC_COPY}, {"rgba16f", GL_RGBA16F, -1, ENC_COPY},
    {"bc1", GL_COMPRESSED_RGB_S3TC_DXT1_EXT, -1, ENC_COPY},
    {"bc3", GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, -1, ENC_COPY},
    {"bc7", GL_COMPRESSED_RGBA_BPTC_UNORM, -1, ENC_COPY},
};

static const render__format *render__format_of(const char *name, int map)
{
    for (size_t i = 0; i < sizeof render__formats / sizeof render__formats[0]; i++)
        if (strcmp(render__formats[i].name, name) == 0 &&
            (render__formats[i].map < 0 || render__formats[i].map == map))
            return &render__formats[i];
    return NULL;
}

/* One map being uploaded: which map of the set, its linear channel count
 * (height 1, normal 3, albedo 4) and its format. */
typedef struct render__src {
    const maps_set *set;
    int map, ch;
    float strength;
    const render__format *fmt;
} render__src;

static int render__upload_channels(const render__src *m)
{
    return m->fmt->enc == ENC_XY ? 2 : m->fmt->enc == ENC_XA ? 4 : m->ch;
}

/* Level-0 rows [y0, y1) of the map in its linear channels. */
static void render__src_rows(const render__src *m, int y0, int y1, float *out)
{
    const maps_set *s = m->set;
    size_t n = (size_t)(y1 - y0) * (size_t)s->size, off = (size_t)y0 * (size_t)s->size;
    if (m->map == 0) {
        memcpy(out, s->height + off, n * sizeof(float));
    } else if (m->map == 1) {
        if (s->normal)
            memcpy(out, s->normal + 3 * off, 3 * n * sizeof(float));
        else
            maps_normal_rows(s->height, s->size, m->strength, y0, y1, out);
        for (size_t i = 0; i < 3 * n; i++)
            out[i] = out[i] * 0.5f + 0.5f;
    } else if (s->albedo8) {
        float lut[2][256];   /* [0] linear alpha, [1] sRGB-decoded colour */
        for (int v = 0; v < 256; v++) {
            lut[0][v] = (float)v / 255.0f;
            lut[1][v] = maps_srgb_decode(lut[0][v]);
        }
        for (size_t i = 0; i < 4 * n; i++)
            out[i] = lut[i % 4 != 3][s->albedo8[4 * off + i]];
    } else {
        for (size_t i = 0; i < n; i++) {
            memcpy(&out[4 * i], &s->albedo[4 * (off + i)], 3 * sizeof(float));
            out[4 * i + 3] = s->specular ? s->specular[off + i] : 1.0f;
        }
    }
}

/* n texels of linear channels (ch) → upload channels per the format. */
static void render__encode(const render__src *m, const float *in, size_t n, float *out)
{
    int ch = m->ch;
    for (size_t i = 0; i < n; i++) {
        const float *a = &in[i * (size_t)ch];
        switch (m->fmt->enc) {
        case ENC_XY:
            out[2 * i] = a[0];
            out[2 * i + 1] = a[1];
            break;
        case ENC_XA:
            out[4 * i] = 0.0f;
            out[4 * i + 1] = a[1];
            out[4 * i + 2] = 0.0f;
            out[4 * i + 3] = a[0];
            break;
        case ENC_SRGB:
            for (int c = 0; c < 4; c++)
                out[4 * i + (size_t)c] = c == 3 ? a[3] : maps_srgb_encode(a[c]);
            break;
        case ENC_COPY:
            memcpy(&out[i * (size_t)ch], a, (size_t)ch * sizeof(float));
            break;
        }
    }
}

/* 2×2 box filter of rows (2k rows of a w-wide image of ch channels) into
 * k rows of w/2 texels; dst may alias src (it is written behind the reads). */
static void render__downsample(const float *src, int w, int rows, int ch, float *dst)
{
    size_t h = (size_t)w / 2, c = (size_t)ch, row = (size_t)w * c;
    for (size_t y = 0; y < (size_t)rows / 2; y++)
        for (size_t x = 0; x < h; x++)
            for (size_t k = 0; k < c; k++) {
                size_t a = 2 * y * row + 2 * x * c + k;
                dst[(y * h + x) * c + k] = 0.25f * (src[a] + src[a + c] + src[a + row] + src[a + row + c]);
            }
}

/* Bytes of one texture, summed over its levels as the driver reports them. */
static size_t render__texture_bytes(GLuint tex, int levels)
{
    size_t total = 0;
    for (int l = 0; l < levels; l++) {
        GLint comp = 0, w = 0, h = 0, bits = 0, v;
        glGetTextureLevelParameteriv(tex, l, GL_TEXTURE_COMPRESSED, &comp);
        glGetTextureLevelParameteriv(tex, l, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(tex, l, GL_TEXTURE_HEIGHT, &h);
        if (comp) {
            glGetTextureLevelParameteriv(tex, l, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &v);
            total += (size_t)v;
            continue;
        }
        static const GLenum q[4] = {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE,
                                    GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE};
        for (int i = 0; i < 4; i++) {
            glGetTextureLevelParameteriv(tex, l, q[i], &v);
            bits += v;
        }
        total += (size_t)w * (size_t)h * (size_t)bits / 8;
    }
    return total;
}

/* Uploads rows [y0, y1) of level `level` (w wide) from linear rows `lin`. */
static void render__upload_rows(GLuint tex, const render__src *m, int level, int w, int y0,
                                 int y1, const float *lin, float *enc)
{
    static const GLenum fmt[5] = {0, GL_RED, GL_RG, GL_RGB, GL_RGBA};
    size_t n = (size_t)w * (size_t)(y1 - y0);
    render__encode(m, lin, n, enc);
    glTextureSubImage2D(tex, level, 0, y0, w, y1 - y0, fmt[render__upload_channels(m)], GL_FLOAT, enc);
}

/* Uploads one map with its full mip chain (see the top comment). */
static int render__upload(const render__src *m, GLuint *tex, size_t *bytes)
{
    int size = m->set->size, levels = 1, ch = m->ch;
    while ((size >> levels) >= 1)
        levels++;
    int strip = size < RENDER__STRIP ? size : RENDER__STRIP;
    size_t strip_n = (size_t)strip * (size_t)size * 4;
    float *lin = dm_xmalloc(strip_n * sizeof(float)), *enc = dm_xmalloc(strip_n * sizeof(float));
    float *next = dm_xmalloc(((size_t)size * (size_t)size / 4 + 1) * (size_t)ch * sizeof(float));
    glCreateTextures(GL_TEXTURE_2D, 1, tex);
    glTextureStorage2D(*tex, levels, m->fmt->internal, size, size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int y = 0; y < size; y += strip) {
        render__src_rows(m, y, y + strip, lin);
        render__upload_rows(*tex, m, 0, size, y, y + strip, lin, enc);
        if (size > 1)
            render__downsample(lin, size, strip, ch, next + (size_t)(y / 2) * (size_t)(size / 2) * (size_t)ch);
    }
    for (int l = 1, s = size / 2; l < levels; l++, s /= 2) {
        for (int y = 0; y < s; y += strip) {
            int y1 = y + strip < s ? y + strip : s;
            render__upload_rows(*tex, m, l, s, y, y1, next + (size_t)y * (size_t)s * (size_t)ch, enc);
        }
        if (s > 1)
            render__downsample(next, s, s, ch, next);
    }
    free(lin);
    free(enc);
    free(next);
    glTextureParameteri(*tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    if (glGetError() != GL_NO_ERROR)
        return DM_ERR_UNSUPPORTED;
    *bytes = render__texture_bytes(*tex, levels);
    return 0;
}

/* Uploads height, normal and albedo of the set in formats fmt[0..2]. */
static int render__maps_upload(render__maps *m, const maps_set *s, const render__format *fmt[3])
{
    size_t texels = (size_t)s->size * (size_t)s->size;
    m->h_lo = m->h_hi = s->height[0];
    for (size_t i = 1; i < texels; i++) {
        m->h_lo = fminf(m->h_lo, s->height[i]);
        m->h_hi = fmaxf(m->h_hi, s->height[i]);
    }
    static const int ch[3] = {1, 3, 4};
    int rc = 0;
    for (int i = 0; i < 3 && !rc; i++) {
        render__src src = {.set = s, .map = i, .ch = ch[i], .strength = 1.0f, .fmt = fmt[i]};
        rc = render__upload(&src, &m->tex[i], &m->bytes[i]);
    }
    return rc;
}

/* Logs an anisotropy request above the driver's maximum (it is clamped). */
static void render__note_clamp(const render_ctx *r, const char *filter, dm_str *log)
{
    if (strncmp(filter, "aniso", 5) != 0)
        return;
    float want = (float)atof(filter + 5);
    if (r->max_aniso <= 0)
        dm_str_printf(log, "filter %s: the driver has no anisotropic filtering; trilinear used\n", filter);
    else if (want > r->max_aniso)
        dm_str_printf(log, "filter %s clamped to anisotropy %g (GL_MAX_TEXTURE_MAX_ANISOTROPY)\n",
                      filter, (double)r->max_aniso);
}

static int render__has_ext(const char *ext, void *user)
{
    (void)user;
    return epoxy_has_gl_extension(ext);
}

/* `sparse` is refused with the reason (axes_value_refusal) where the
 * driver lacks GL_ARB_sparse_texture. */
static int render__sparse_check(const render__cfg *c, dm_str *log)
{
    char *why = axes_value_refusal("virtual_texture", render__get(c, "virtual_texture"),
                                   render__has_ext, NULL);
    if (!why)
        return 0;
    dm_str_printf(log, "%s\n", why);
    free(why);
    return DM_ERR_UNSUPPORTED;
}

/* virtual_texture=software|sparse covers the techniques whose maps are
 * sampled through the page table: the fragment-stage techniques
 * (surface.vert.glsl and surface.frag.glsl, vt.glsl) and the tessellated
 * ones (tess.vert, tess.tcs or a user's control stage, tess.tes.glsl reading
 * the height through vt_table.glsl), with the page formats of vt.h.
 * vertex-displacement fetches heights in the vertex stage, which has no
 * page-table path. */
static int render__vt_usable(const render__cfg *c, const render__format *fmt[3], dm_str *log)
{
    const technique_desc *t = technique_find(render__get(c, "technique"));
    const char *how = render__get(c, "virtual_texture");
    int fragment = t && !t->tcs && !t->tes && strcmp(t->vs, "surface.vert.glsl") == 0;
    int tess = t && t->tes && strcmp(t->tes, "tess.tes.glsl") == 0 && strcmp(t->vs, "tess.vert.glsl") == 0;
    if (t && (t->gs || !t->fs || strcmp(t->fs, "surface.frag.glsl") != 0 || !(fragment || tess))) {
        dm_str_printf(log, "virtual_texture=%s covers the fragment-stage and tessellated techniques only, "
                      "not '%s'\n", how, t->name);
        return DM_ERR_UNSUPPORTED;
    }
    if (fmt[0]->internal != GL_R32F || (fmt[1]->internal != GL_RGB8 && fmt[1]->internal != GL_RGBA8) ||
        fmt[2]->internal != GL_RGBA8) {
        dm_str_printf(log, "virtual_texture=%s stores pages as r32f height, rgb8 normal and rgba8 albedo; "
                      "got %s/%s/%s\n", how, fmt[0]->name, fmt[1]->name, fmt[2]->name);
        return DM_ERR_UNSUPPORTED;
    }
    return 0;
}

/* Creates the software or sparse virtual texture of the configuration. */
static int render__vt_make(render__maps *m, const render__cfg *c, dm_str *log)
{
    vt_desc d = {.maps = render__get(c, "maps"), .size = atoi(render__get(c, "texture_size")),
                 .page = atoi(render__get(c, "vt_page_size")),
                 .cache_pages = atoi(render__get(c, "vt_cache_pages")),
                 .sparse = strcmp(render__get(c, "virtual_texture"), "sparse") == 0};
    int64_t t0 = dm_now_ns();
    int rc = vt_create(&d, &m->vt, log);
    m->h_lo = 0;    /* procedural sets: heights in [0, 1] */
    m->h_hi = 1;
    if (!rc)
        dm_str_printf(log, "%s virtual texture %s %d² (pages %d, cache %d): created in %.1f ms\n",
                      d.sparse ? "sparse" : "software", d.maps, d.size, d.page, d.cache_pages,
                      (double)(dm_now_ns() - t0) / 1e6);
    return rc;
}

float render__normal_height_scale(const char *maps)
{
    if (maps_kind(maps) == maps_kind("asteroid"))
        return MESH_ASTEROID_SCALE;
    if (!maps_is_material(maps))
        return MAPS_NORMAL_HEIGHT_SCALE;
    for (const char *p = maps; p; p = strchr(p, ';')) {   /* entries "key=PATH" split by ';' */
        p += *p == ';';
        if (strncmp(p, "normal=", 7) == 0)
            return 0.0f;
    }
    return MAPS_NORMAL_HEIGHT_SCALE;
}

/* Generates (or loads from the disk cache, or from the user's files) and
 * uploads the maps of key. */
static int render__maps_make(render__maps *m, const char *name, int size,
                             const render__format *fmt[3], dm_str *log)
{
    maps_set s;
    maps_desc d = {.name = name, .size = size, .compact = 1};
    int rc = maps_is_material(name) ? maps_material_load(name, &s, log) : maps_get_cached(&d, NULL, &s);
    if (rc) {
        dm_str_printf(log, "\nmaps '%s' at %d texels: %s%s\n", name, size, dm_strerror(rc),
                      size > MAPS_MAX_SIZE ? " (larger maps need virtual_texture=software)" : "");
        return rc;
    }
    size = s.size;   /* user maps have their own size */
    int64_t t0 = dm_now_ns();
    rc = render__maps_upload(m, &s, fmt);
    dm_str_printf(log, "maps '%s' %d²: %s in %.1f ms, uploaded in %.1f ms\n", name, size,
                  maps_is_material(name) ? "read from the user's files"
                  : s.from_memory         ? "copied from this process's earlier set"
                  : s.from_cache          ? "loaded from the disk cache" : "generated",
                  (double)(s.from_cache || s.from_memory ? s.load_ns : s.gen_ns) / 1e6, (double)(dm_now_ns() - t0) / 1e6);
    maps_free(&s);
    if (rc) {
        dm_str_printf(log, "maps '%s': the driver cannot upload formats %s/%s/%s\n", name,
                      fmt[0]->name, fmt[1]->name, fmt[2]->name);
        glDeleteTextures(3, m->tex);
    }
    return rc;
}

int render_maps_preload(const dm_kv *params, size_t n_params)
{
    render__cfg c = {params, n_params};
    const char *name = render__get(&c, "maps"), *vt = render__get(&c, "virtual_texture");
    int size = atoi(render__get(&c, "texture_size"));
    if (!name || maps_is_material(name) || maps_kind(name) < 0 || !vt || strcmp(vt, "off") != 0 || size <= 0 ||
        size >= MAPS_CACHE_MIN_SIZE)
        return 0;
    maps_set s;
    maps_desc d = {.name = name, .size = size, .compact = 1};
    if (maps_in_memory(&d) || maps_get_cached(&d, NULL, &s) != 0)
        return 0;
    maps_free(&s);
    return 1;
}

int render__maps_get(render_ctx *r, const render__cfg *c, size_t *idx, dm_str *log)
{
    const char *name = render__get(c, "maps");
    int size = atoi(render__get(c, "texture_size"));
    int soft = strcmp(render__get(c, "virtual_texture"), "software") == 0;
    int sparse = strcmp(render__get(c, "virtual_texture"), "sparse") == 0;
    const char *f[3] = {render__get(c, "height_format"), render__get(c, "normal_format"),
                        render__get(c, "albedo_format")};
    const render__format *fmt[3];
    for (int i = 0; i < 3; i++)
        if (!(fmt[i] = render__format_of(f[i], i))) {
            dm_str_printf(log, "format '%s' is not known to the renderer\n", f[i]);
            return DM_ERR_ARG;
        }
    render__note_clamp(r, render__get(c, "filter"), log);
    int rc = render__sparse_check(c, log);
    if (!rc && (soft || sparse))
        rc = render__vt_usable(c, fmt, log);
    if (rc)
        return rc;
    char *key = soft || sparse ? dm_xasprintf("%s:%s/%d/%s/%s", sparse ? "sparse" : "vt", name, size,
                                              render__get(c, "vt_page_size"), render__get(c, "vt_cache_pages"))
                     : dm_xasprintf("%s/%d/%s/%s/%s", name, size, f[0], f[1], f[2]);
    for (size_t i = 0; i < r->n_maps; i++)
        if (strcmp(r->maps[i].key, key) == 0) {
            free(key);
            *idx = i;
            return 0;
        }
    render__maps m = {.key = key, .normal_height_scale = render__normal_height_scale(name)};
    rc = soft || sparse ? render__vt_make(&m, c, log) : render__maps_make(&m, name, size, fmt, log);
    if (rc) {
        free(key);
        return rc;
    }
    *idx = RENDER__PUSH(r->maps, r->n_maps);
    r->maps[*idx] = m;
    return 0;
}

size_t render__sampler_get(render_ctx *r, const char *filter)
{
    for (size_t i = 0; i < r->n_samplers; i++)
        if (strcmp(r->samplers[i].key, filter) == 0)
            return i;
    size_t n = RENDER__PUSH(r->samplers, r->n_samplers);
    GLuint s;
    glCreateSamplers(1, &s);
    GLint min = GL_LINEAR_MIPMAP_LINEAR, mag = GL_LINEAR;
    if (strcmp(filter, "nearest") == 0) {
        min = GL_NEAREST_MIPMAP_NEAREST;
        mag = GL_NEAREST;
    } else if (strcmp(filter, "bilinear") == 0) {
        min = GL_LINEAR_MIPMAP_NEAREST;
    }
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, min);
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, mag);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (strncmp(filter, "aniso", 5) == 0 && r->max_aniso > 0) {
        float a = (float)atoi(filter + 5);
        glSamplerParameterf(s, GL_TEXTURE_MAX_ANISOTROPY_EXT, a < r->max_aniso ? a : r->max_aniso);
    }
    r->samplers[n].key = dm_xstrdup(filter);
    r->samplers[n].id = s;
    return n;
}

int render__vt_filter(const char *filter)
{
    return strcmp(filter, "nearest") == 0 ? 0 : strcmp(filter, "bilinear") == 0 ? 1 : 2;
}

void render__maps_bind(render_ctx *r, const render__item *it)
{
    const render__maps *m = &r->maps[it->maps];
    GLint prog = 0, vp[4];
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    if (m->vt) {
        glGetIntegerv(GL_VIEWPORT, vp);
        vt_frame(m->vt, (GLuint)prog, render__vt_filter(r->samplers[it->sampler].key), vp[2], vp[3]);
        return;
    }
    for (GLuint u = 0; u < 3; u++) {
        glBindTextureUnit(u, m->tex[u]);
        glBindSampler(u, r->samplers[it->sampler].id);
    }
}

size_t render__maps_bytes(render_ctx *r, const render__item *it)
{
    const render__maps *m = &r->maps[it->maps];
    if (m->vt)
        return vt_bytes(m->vt);
    size_t total = 0;
    for (int i = 0; i < 3; i++)
        if (it->tech->textures & (1u << i))
            total += m->bytes[i];
    return total;
}

void render__maps_destroy(render_ctx *r)
{
    for (size_t i = 0; i < r->n_maps; i++) {
        glDeleteTextures(3, r->maps[i].tex);
        vt_destroy(r->maps[i].vt);
        free(r->maps[i].key);
    }
    for (size_t i = 0; i < r->n_samplers; i++) {
        glDeleteSamplers(1, &r->samplers[i].id);
        free(r->samplers[i].key);
    }
    free(r->maps);
    free(r->samplers);
    r->maps = NULL;
    r->samplers = NULL;
    r->n_maps = r->n_samplers = 0;
}

int render_get_vt_stats(render_ctx *r, render_item item, render_vt_stats *out)
{
    if (!r || !out || item.id == 0 || item.id > r->n_items || !r->items[item.id - 1].used)
        return DM_ERR_ARG;
    const render__maps *m = &r->maps[r->items[item.id - 1].maps];
    if (!m->vt)
        return DM_ERR_UNAVAILABLE;
    vt_get_stats(m->vt, out);
    return 0;
}
