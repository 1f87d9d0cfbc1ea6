/* render_textures.c — material maps: generation, formats, mip chains,
 * samplers and binding (see render_textures.h).  Conventions (render.c's top
 * comment): unit 0 height (R, value in [0,1]), unit 1 normal (n·0.5+0.5),
 * unit 2 albedo; CPU box-filtered mip chain, GL_REPEAT; `filter` picks a
 * sampler: nearest = NEAREST_MIPMAP_NEAREST, bilinear = LINEAR_MIPMAP_NEAREST,
 * trilinear = LINEAR_MIPMAP_LINEAR, anisoN = trilinear + anisotropy
 * min(N, GL_MAX_TEXTURE_MAX_ANISOTROPY).
 */
#include "techniques/render_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/maps.h"

static const struct { const char *name; GLenum internal; } render__formats[] = {
    {"r8", GL_R8}, {"r16", GL_R16}, {"r16f", GL_R16F}, {"r32f", GL_R32F},
    {"rgba32f", GL_RGBA32F}, {"rgb8", GL_RGB8}, {"rgba8", GL_RGBA8}, {"rg8", GL_RG8},
    {"rgb16f", GL_RGB16F}, {"rgba16f", GL_RGBA16F}, {"srgb8_a8", GL_SRGB8_ALPHA8},
    {"bc1", GL_COMPRESSED_RGB_S3TC_DXT1_EXT}, {"bc3", GL_COMPRESSED_RGBA_S3TC_DXT5_EXT},
    {"bc5", GL_COMPRESSED_RG_RGTC2}, {"bc7", GL_COMPRESSED_RGBA_BPTC_UNORM},
};

static GLenum render__format(const char *name)
{
    for (size_t i = 0; i < sizeof render__formats / sizeof render__formats[0]; i++)
        if (strcmp(render__formats[i].name, name) == 0)
            return render__formats[i].internal;
    return 0;
}

/* 2×2 box filter of a size² image of ch channels into (size/2)². */
static void render__downsample(const float *src, int size, int ch, float *dst)
{
    int h = size / 2;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < h; x++)
            for (int c = 0; c < ch; c++) {
                size_t a = ((size_t)(2 * y) * (size_t)size + (size_t)(2 * x)) * (size_t)ch + (size_t)c;
                size_t row = (size_t)size * (size_t)ch;
                dst[((size_t)y * (size_t)h + (size_t)x) * (size_t)ch + (size_t)c] =
                    0.25f * (src[a] + src[a + (size_t)ch] + src[a + row] + src[a + row + (size_t)ch]);
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

/* Uploads one map (ch channels of float data) with a full CPU mip chain. */
static int render__upload(GLenum internal, const float *data, int size, int ch, GLuint *tex,
                          size_t *bytes)
{
    static const GLenum fmt[5] = {0, GL_RED, GL_RG, GL_RGB, GL_RGBA};
    int levels = 1;
    while ((size >> levels) >= 1)
        levels++;
    glCreateTextures(GL_TEXTURE_2D, 1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    float *buf = dm_xmalloc((size_t)size * (size_t)size * (size_t)ch * sizeof(float));
    memcpy(buf, data, (size_t)size * (size_t)size * (size_t)ch * sizeof(float));
    for (int l = 0, s = size; l < levels; l++, s /= 2) {
        glTexImage2D(GL_TEXTURE_2D, l, (GLint)internal, s, s, 0, fmt[ch], GL_FLOAT, buf);
        if (s > 1)
            render__downsample(buf, s, ch, buf);
    }
    free(buf);
    glTextureParameteri(*tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glBindTexture(GL_TEXTURE_2D, 0);
    if (glGetError() != GL_NO_ERROR)
        return DM_ERR_UNSUPPORTED;
    *bytes = render__texture_bytes(*tex, levels);
    return 0;
}

/* sRGB transfer function: linear [0,1] -> encoded. */
static float render__srgb_encode(float c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1 / 2.4f) - 0.055f;
}

/* Uploads the three maps: the normal map encoded n*0.5+0.5; the linear
 * albedo sRGB-encoded first when its format is an sRGB one, so sampling
 * returns the same linear values for every format. */
static int render__maps_upload(render__maps *m, const maps_set *s, const GLenum fmt[3])
{
    size_t texels = (size_t)s->size * (size_t)s->size;
    float *enc = dm_xmalloc(texels * 4 * sizeof(float));
    for (size_t i = 0; i < texels * 3; i++)
        enc[i] = s->normal[i] * 0.5f + 0.5f;
    int rc = render__upload(fmt[0], s->height, s->size, 1, &m->tex[0], &m->bytes[0]);
    if (!rc)
        rc = render__upload(fmt[1], enc, s->size, 3, &m->tex[1], &m->bytes[1]);
    const float *albedo = s->albedo;
    if (fmt[2] == GL_SRGB8_ALPHA8) {
        for (size_t i = 0; i < texels * 4; i++)
            enc[i] = i % 4 == 3 ? s->albedo[i] : render__srgb_encode(s->albedo[i]);
        albedo = enc;
    }
    if (!rc)
        rc = render__upload(fmt[2], albedo, s->size, 4, &m->tex[2], &m->bytes[2]);
    free(enc);
    return rc;
}

/* Finds or creates the textures of (maps, size, formats). */
int render__maps_get(tech_renderer *r, const render__cfg *c, size_t *idx, dm_str *log)
{
    const char *name = render__get(c, "maps");
    int size = atoi(render__get(c, "texture_size"));
    const char *f[3] = {render__get(c, "height_format"), render__get(c, "normal_format"),
                        render__get(c, "albedo_format")};
    char *key = dm_xasprintf("%s/%d/%s/%s/%s", name, size, f[0], f[1], f[2]);
    for (size_t i = 0; i < r->n_maps; i++)
        if (strcmp(r->maps[i].key, key) == 0) {
            free(key);
            *idx = i;
            return 0;
        }
    GLenum fmt[3] = {render__format(f[0]), render__format(f[1]), render__format(f[2])};
    maps_set s;
    maps_desc d = {.name = name, .size = size};
    int rc = maps_generate(&d, &s);
    if (rc) {
        dm_str_printf(log, "maps '%s' at %d texels: %s\n", name, size, dm_strerror(rc));
        free(key);
        return rc;
    }
    render__maps m = {.key = key};
    rc = render__maps_upload(&m, &s, fmt);
    maps_free(&s);
    if (rc) {
        dm_str_printf(log, "maps '%s': the driver cannot upload formats %s/%s/%s\n", name, f[0], f[1], f[2]);
        glDeleteTextures(3, m.tex);
        free(key);
        return rc;
    }
    *idx = RENDER__PUSH(r->maps, r->n_maps);
    r->maps[*idx] = m;
    return 0;
}

size_t render__sampler_get(tech_renderer *r, const char *filter)
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

void render__maps_bind(tech_renderer *r, const render__item *it)
{
    for (GLuint u = 0; u < 3; u++) {
        glBindTextureUnit(u, r->maps[it->maps].tex[u]);
        glBindSampler(u, r->samplers[it->sampler].id);
    }
}

size_t render__maps_bytes(tech_renderer *r, const render__item *it)
{
    size_t total = 0;
    for (int i = 0; i < 3; i++)
        if (it->tech->textures & (1u << i))
            total += r->maps[it->maps].bytes[i];
    return total;
}

void render__maps_destroy(tech_renderer *r)
{
    for (size_t i = 0; i < r->n_maps; i++) {
        glDeleteTextures(3, r->maps[i].tex);
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

int tech_item_vt_stats(tech_renderer *r, tech_item item, tech_vt_stats *out)
{
    (void)r;
    (void)item;
    (void)out;
    return DM_ERR_UNAVAILABLE;   /* no technique uses a virtual texture yet */
}
