/* vt.c — software virtual texturing (see vt.h).
 *
 * Page ids pack (level << 28 | page y << 14 | page x).  The page table holds
 * per level and page (slot, level of the page in that slot): a resident page
 * points at itself, any other at its parent's entry, so the shader finds the
 * finest resident ancestor with one fetch.
 */
#include "techniques/vt.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/maps.h"

#define VT__NONE 0xFFFFFFFFu
#define VT__SUB 4              /* at most 4×4 level-0 samples per page texel */

struct vt {
    int kind, size, page, slot, per_row, n_slots, levels, budget, sparse;
    uint64_t committed;        /* sparse: pages committed now */
    GLuint staging[3], fbo[2]; /* sparse: a page of each map, read and draw framebuffers */
    GLuint phys[3], table, feedback, samplers[2];
    int fb_w, fb_h, fb_valid;
    uint32_t *slot_page;       /* page id in each slot, VT__NONE when free */
    uint64_t *slot_used;       /* frame the page was last wanted */
    uint16_t **tab;            /* per level: pages² × (slot, level) */
    int *dirty;                /* per level: x0, y0, x1, y1 (x1 <= x0: clean) */
    uint64_t frame;
    render_vt_stats st;
};

static uint32_t vt__id(int m, int x, int y) { return (uint32_t)m << 28 | (uint32_t)y << 14 | (uint32_t)x; }
static int vt__pages(const vt *v, int m) { return (v->size / v->page) >> m; }

static uint16_t *vt__entry(vt *v, int m, int x, int y)
{
    return &v->tab[m][2 * ((size_t)y * (size_t)vt__pages(v, m) + (size_t)x)];
}

static void vt__dirty(vt *v, int m, int x0, int y0, int x1, int y1)
{
    int *d = &v->dirty[4 * m];
    if (d[2] <= d[0]) {
        d[0] = x0, d[1] = y0, d[2] = x1, d[3] = y1;
        return;
    }
    d[0] = x0 < d[0] ? x0 : d[0];
    d[1] = y0 < d[1] ? y0 : d[1];
    d[2] = x1 > d[2] ? x1 : d[2];
    d[3] = y1 > d[3] ? y1 : d[3];
}

/* Re-derives every entry below page (m, x, y) that is not resident itself
 * from its parent, level by level downwards. */
static void vt__subtree(vt *v, int m, int x, int y)
{
    vt__dirty(v, m, x, y, x + 1, y + 1);
    for (int k = m - 1; k >= 0; k--) {
        int s = m - k, x0 = x << s, y0 = y << s, x1 = (x + 1) << s, y1 = (y + 1) << s;
        for (int j = y0; j < y1; j++)
            for (int i = x0; i < x1; i++) {
                uint16_t *e = vt__entry(v, k, i, j);
                if (e[1] != k || v->slot_page[e[0]] != vt__id(k, i, j))
                    memcpy(e, vt__entry(v, k + 1, i / 2, j / 2), 2 * sizeof *e);
            }
        vt__dirty(v, k, x0, y0, x1, y1);
    }
}

/* Uploads the dirty rectangle of every page-table level. */
static void vt__table_upload(vt *v)
{
    for (int m = 0; m < v->levels; m++) {
        int *d = &v->dirty[4 * m], n = vt__pages(v, m);
        if (d[2] <= d[0])
            continue;
        glPixelStorei(GL_UNPACK_ROW_LENGTH, n);
        glTextureSubImage2D(v->table, m, d[0], d[1], d[2] - d[0], d[3] - d[1], GL_RG_INTEGER,
                            GL_UNSIGNED_SHORT, vt__entry(v, m, d[0], d[1]));
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        d[0] = d[2] = 0;
    }
}

/* Fills one slot-sized page (m, px, py) with border: h (slot² heights),
 * n (slot² × 4 encoded normals), a (slot² × 4 albedo + specular).  A texel
 * of level m is the mean of k×k level-0 samples spaced d apart (k·d = 2^m,
 * k <= VT__SUB), normals by central differences over ±d: for m <= 2 exactly
 * the plain texture's box-filtered mip chain. */
static void vt__page(const vt *v, int m, int px, int py, float *h, float *n, float *a)
{
    long f = 1L << m, d = f > VT__SUB ? f / VT__SUB : 1, k = f / d, S = v->slot;
    long N = S * k + 2, off = d > 1 ? d / 2 : 0;
    long bx = ((long)px * v->page - VT_BORDER) * f + off - d, by = ((long)py * v->page - VT_BORDER) * f + off - d;
    float *H = dm_xmalloc((size_t)(N * N) * sizeof(float)), rgba[4], w = 1.0f / (float)(k * k);
    float s = 1.0f * MAPS_NORMAL_SCALE * (float)v->size * 0.5f / (float)d;
    memset(h, 0, (size_t)(S * S) * sizeof(float));
    memset(n, 0, (size_t)(S * S) * 4 * sizeof(float));
    memset(a, 0, (size_t)(S * S) * 4 * sizeof(float));
    for (long j = 0; j < N; j++)
        for (long i = 0; i < N; i++) {
            maps_texel(v->kind, v->size, bx + i * d, by + j * d, &H[j * N + i], rgba);
            if (i == 0 || j == 0 || i == N - 1 || j == N - 1)
                continue;
            size_t t = (size_t)(((j - 1) / k) * S + (i - 1) / k);
            for (int c = 0; c < 4; c++)
                a[4 * t + (size_t)c] += w * rgba[c];
        }
    for (long j = 1; j < N - 1; j++)
        for (long i = 1; i < N - 1; i++) {
            float gx = s * (H[j * N + i + 1] - H[j * N + i - 1]);
            float gy = s * (H[(j + 1) * N + i] - H[(j - 1) * N + i]);
            float l = sqrtf(gx * gx + gy * gy + 1);
            size_t t = (size_t)(((j - 1) / k) * S + (i - 1) / k);
            h[t] += w * H[j * N + i];
            n[4 * t] += w * (-gx / l * 0.5f + 0.5f);
            n[4 * t + 1] += w * (-gy / l * 0.5f + 0.5f);
            n[4 * t + 2] += w * (1 / l * 0.5f + 0.5f);
            n[4 * t + 3] += w;
        }
    free(H);
}

/* Commits or releases the p×p region at (x, y) of level m of sparse texture
 * tex (ARB_sparse_texture has no direct-state-access form). */
static void vt__commit(GLuint tex, int m, int x, int y, int p, GLboolean commit)
{
    GLint old = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &old);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexPageCommitmentARB(GL_TEXTURE_2D, m, x, y, 0, p, p, 1, commit);
    glBindTexture(GL_TEXTURE_2D, (GLuint)old);
}

/* Generates page id into slot and makes it resident in the page table. */
static void vt__load(vt *v, uint32_t id, int slot)
{
    int m = (int)(id >> 28), py = (int)(id >> 14 & 0x3FFF), px = (int)(id & 0x3FFF), S = v->slot;
    size_t t = (size_t)S * (size_t)S;
    float *buf = dm_xmalloc(t * 9 * sizeof(float));
    vt__page(v, m, px, py, buf, buf + t, buf + 5 * t);
    if (v->sparse) {   /* commit the page at its place and upload it without border */
        int x = px * v->page, y = py * v->page, P = v->page;
        for (int i = 0; i < 3; i++)
            vt__commit(v->phys[i], m, x, y, P, GL_TRUE);
        /* zink binds sparse memory on the queue asynchronously; an upload
         * issued before the binding completes is lost (the page reads
         * back as zero in some runs), so the commitment is waited for.
         * The page is then drawn in by a blit from a staging texture: with
         * Mesa 25.0 (zink on lavapipe) glTextureSubImage2D into a level
         * wider than one page lands with the wrong layout (read back, 87 %
         * of a page's texels differ; sampled, stripes), the blit does not. */
        glFinish();
        float *tight = dm_xmalloc((size_t)P * (size_t)P * 4 * sizeof *tight);
        for (int i = 0; i < 3; i++) {   /* the page without its border, rows packed */
            int ch = i ? 4 : 1;
            const float *src = buf + (i == 0 ? 0 : i == 1 ? t : 5 * t);
            for (int r = 0; r < P; r++)
                memcpy(tight + (size_t)r * (size_t)P * (size_t)ch,
                       src + ((size_t)(r + VT_BORDER) * (size_t)S + VT_BORDER) * (size_t)ch,
                       (size_t)P * (size_t)ch * sizeof *tight);
            glTextureSubImage2D(v->staging[i], 0, 0, 0, P, P, i ? GL_RGBA : GL_RED, GL_FLOAT, tight);
            glNamedFramebufferTexture(v->fbo[0], GL_COLOR_ATTACHMENT0, v->staging[i], 0);
            glNamedFramebufferTexture(v->fbo[1], GL_COLOR_ATTACHMENT0, v->phys[i], m);
            glBlitNamedFramebuffer(v->fbo[0], v->fbo[1], 0, 0, P, P, x, y, x + P, y + P, GL_COLOR_BUFFER_BIT,
                                   GL_NEAREST);
        }
        free(tight);
        v->committed++;
        v->st.upload_bytes += (size_t)P * (size_t)P * 12;
    } else {
        int sx = slot % v->per_row * S, sy = slot / v->per_row * S;
        glTextureSubImage2D(v->phys[0], 0, sx, sy, S, S, GL_RED, GL_FLOAT, buf);
        glTextureSubImage2D(v->phys[1], 0, sx, sy, S, S, GL_RGBA, GL_FLOAT, buf + t);
        glTextureSubImage2D(v->phys[2], 0, sx, sy, S, S, GL_RGBA, GL_FLOAT, buf + 5 * t);
        v->st.upload_bytes += t * 12;   /* R32F + RGBA8 + RGBA8 */
    }
    free(buf);
    v->slot_page[slot] = id;
    v->slot_used[slot] = v->frame;
    uint16_t *e = vt__entry(v, m, px, py);
    e[0] = (uint16_t)slot;
    e[1] = (uint16_t)m;
    vt__subtree(v, m, px, py);
}

/* A free slot, else the least recently wanted page not wanted this frame
 * (slot 0, the coarsest page, is never evicted); -1 when every slot is
 * wanted now.  The evicted page's entries fall back to its parent. */
static int vt__victim(vt *v)
{
    int best = -1;
    for (int s = 1; s < v->n_slots; s++) {
        if (v->slot_page[s] == VT__NONE)
            return s;
        if (v->slot_used[s] < v->frame && (best < 0 || v->slot_used[s] < v->slot_used[best]))
            best = s;
    }
    if (best < 0)
        return -1;
    uint32_t id = v->slot_page[best];
    int m = (int)(id >> 28), py = (int)(id >> 14 & 0x3FFF), px = (int)(id & 0x3FFF);
    v->slot_page[best] = VT__NONE;
    if (v->sparse) {
        for (int i = 0; i < 3; i++)
            vt__commit(v->phys[i], m, px * v->page, py * v->page, v->page, GL_FALSE);
        v->committed--;
    }
    memcpy(vt__entry(v, m, px, py), vt__entry(v, m + 1, px / 2, py / 2), 2 * sizeof(uint16_t));
    vt__subtree(v, m, px, py);
    return best;
}

static int vt__cmp_desc(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

/* Sorts ids coarse level first and removes duplicates and VT__NONE; returns the count. */
static size_t vt__unique(uint32_t *ids, size_t n)
{
    qsort(ids, n, sizeof *ids, vt__cmp_desc);
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (ids[i] != VT__NONE && (k == 0 || ids[k - 1] != ids[i]))
            ids[k++] = ids[i];
    return k;
}

/* The wanted pages of the last frame with all their ancestors; malloc'd. */
static uint32_t *vt__wanted(vt *v, size_t *count)
{
    size_t n = (size_t)v->fb_w * (size_t)v->fb_h;
    uint32_t *fb = dm_xmalloc(n * sizeof *fb);
    /* Shader-storage writes are incoherent: without the barrier llvmpipe
     * (which rasterizes when it flushes) returns the buffer as cleared
     * whenever nothing else flushed the frame, and every other frame's
     * requests were lost. */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(v->feedback, 0, (GLsizeiptr)(n * sizeof *fb), fb);
    n = vt__unique(fb, n);
    uint32_t *all = dm_xmalloc((n * (size_t)v->levels + 1) * sizeof *all);
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        int m = (int)(fb[i] >> 28), y = (int)(fb[i] >> 14 & 0x3FFF), x = (int)(fb[i] & 0x3FFF);
        for (; m < v->levels; m++, x /= 2, y /= 2)
            if (x < vt__pages(v, m) && y < vt__pages(v, m))
                all[k++] = vt__id(m, x, y);
    }
    free(fb);
    *count = vt__unique(all, k);
    return all;
}

/* Reads the feedback, marks wanted resident pages, loads missing ones
 * (coarse first) within the budget. */
static void vt__update(vt *v)
{
    int64_t t0 = dm_now_ns();
    size_t n, n_miss = 0;
    uint32_t *ids = vt__wanted(v, &n);
    for (size_t i = 0; i < n; i++) {
        int m = (int)(ids[i] >> 28), y = (int)(ids[i] >> 14 & 0x3FFF), x = (int)(ids[i] & 0x3FFF);
        uint16_t *e = vt__entry(v, m, x, y);
        if (e[1] == m && v->slot_page[e[0]] == ids[i])
            v->slot_used[e[0]] = v->frame;
        else
            ids[n_miss++] = ids[i];   /* order (coarse first) is kept */
    }
    v->st.page_misses += n_miss;
    v->st.feedback_ns += dm_now_ns() - t0;
    for (size_t i = 0; i < n_miss && i < (size_t)v->budget; i++) {
        int slot = vt__victim(v);
        if (slot < 0)
            break;
        vt__load(v, ids[i], slot);
    }
    free(ids);
}

static const GLenum vt__fmt[3] = {GL_R32F, GL_RGBA8, GL_RGBA8};
static const char *const vt__fmt_name[3] = {"r32f", "rgba8", "rgba8"};

/* Sparse: the three maps as sparse textures of size² with one level per
 * page level, nothing committed.  DM_ERR_UNSUPPORTED / DM_ERR_RANGE with
 * the GL error and the size in log. */
static int vt__sparse_create(vt *v, dm_str *log)
{
    GLint max = 0;
    glGetIntegerv(GL_MAX_SPARSE_TEXTURE_SIZE_ARB, &max);
    if (v->size > max) {
        dm_str_printf(log, "virtual_texture=sparse: texture_size %d exceeds the driver's "
                      "GL_MAX_SPARSE_TEXTURE_SIZE_ARB %d\n", v->size, max);
        return DM_ERR_RANGE;
    }
    for (int i = 0; i < 3; i++) {
        GLint px = 0, py = 0;
        glGetInternalformativ(GL_TEXTURE_2D, vt__fmt[i], GL_VIRTUAL_PAGE_SIZE_X_ARB, 1, &px);
        glGetInternalformativ(GL_TEXTURE_2D, vt__fmt[i], GL_VIRTUAL_PAGE_SIZE_Y_ARB, 1, &py);
        if (px < 1 || py < 1 || v->page % px || v->page % py) {
            dm_str_printf(log, "virtual_texture=sparse: vt_page_size %d is not a multiple of the driver's "
                          "sparse page of %s (%dx%d texels)\n", v->page, vt__fmt_name[i], px, py);
            return DM_ERR_RANGE;
        }
    }
    while (glGetError() != GL_NO_ERROR)
        ;
    glCreateTextures(GL_TEXTURE_2D, 3, v->phys);
    for (int i = 0; i < 3; i++) {
        glTextureParameteri(v->phys[i], GL_TEXTURE_SPARSE_ARB, GL_TRUE);
        glTextureParameteri(v->phys[i], GL_VIRTUAL_PAGE_SIZE_INDEX_ARB, 0);
        glTextureStorage2D(v->phys[i], v->levels, vt__fmt[i], v->size, v->size);
        GLint sparse_levels = 0;
        glGetTextureParameteriv(v->phys[i], GL_NUM_SPARSE_LEVELS_ARB, &sparse_levels);
        GLenum e = glGetError();
        if (e != GL_NO_ERROR || sparse_levels < v->levels) {
            dm_str_printf(log, "virtual_texture=sparse: a %dx%d %s sparse texture with %d levels: %s\n",
                          v->size, v->size, vt__fmt_name[i], v->levels,
                          e == GL_OUT_OF_MEMORY ? "GL_OUT_OF_MEMORY"
                          : e != GL_NO_ERROR    ? "GL error"
                                                : "its coarsest levels fall into the mip tail "
                                                  "(use a larger vt_page_size)");
            glDeleteTextures(3, v->phys);
    glDeleteTextures(3, v->staging);
    glDeleteFramebuffers(2, v->fbo);
            memset(v->phys, 0, sizeof v->phys);
            return e == GL_OUT_OF_MEMORY ? DM_ERR_RANGE : DM_ERR_UNSUPPORTED;
        }
    }
    return 0;
}

/* Mesa accepts a page commitment only up to the level range it computes
 * when it first validates a texture for a draw (texture_page_commitment:
 * "level > _MaxLevel" is GL_INVALID_VALUE until then), and a technique's
 * draws validate only the maps it samples.  One point drawn under
 * rasterizer discard by a program sampling all three maps validates them;
 * the state it touches is restored. */
static void vt__sparse_validate(vt *v)
{
    static const char *vs = "#version 450 core\nvoid main() { gl_Position = vec4(0, 0, 0, 1); }\n";
    static const char *fs =
        "#version 450 core\nlayout(binding = 0) uniform sampler2D a;\n"
        "layout(binding = 1) uniform sampler2D b;\nlayout(binding = 2) uniform sampler2D c;\n"
        "out vec4 o;\nvoid main() { o = textureLod(a, vec2(0.5), 0.0) + textureLod(b, vec2(0.5), 0.0)"
        " + textureLod(c, vec2(0.5), 0.0); }\n";
    GLint prog = 0, vao = 0, fbo = 0, active = 0, tex[3];
    GLboolean discard = glIsEnabled(GL_RASTERIZER_DISCARD);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int i = 0; i < 3; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex[i]);
    }
    glActiveTexture((GLenum)active);
    GLuint rb = 0, fb = 0;   /* a complete framebuffer: the surfaceless default one is not */
    glCreateRenderbuffers(1, &rb);
    glNamedRenderbufferStorage(rb, GL_RGBA8, 1, 1);
    glCreateFramebuffers(1, &fb);
    glNamedFramebufferRenderbuffer(fb, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb);
    GLuint p = glCreateShaderProgramv(GL_VERTEX_SHADER, 1, &vs), q = glCreateShaderProgramv(GL_FRAGMENT_SHADER, 1, &fs);
    GLuint pipe = 0, va = 0;
    glCreateProgramPipelines(1, &pipe);
    glUseProgramStages(pipe, GL_VERTEX_SHADER_BIT, p);
    glUseProgramStages(pipe, GL_FRAGMENT_SHADER_BIT, q);
    glCreateVertexArrays(1, &va);
    glUseProgram(0);
    glBindProgramPipeline(pipe);
    glBindVertexArray(va);
    for (GLuint u = 0; u < 3; u++)
        glBindTextureUnit(u, v->phys[u]);
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArrays(GL_POINTS, 0, 1);
    if (!discard)
        glDisable(GL_RASTERIZER_DISCARD);
    for (GLuint u = 0; u < 3; u++)
        glBindTextureUnit(u, (GLuint)tex[u]);
    glBindVertexArray((GLuint)vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)fbo);
    glDeleteFramebuffers(1, &fb);
    glDeleteRenderbuffers(1, &rb);
    glBindProgramPipeline(0);
    glUseProgram((GLuint)prog);
    glDeleteVertexArrays(1, &va);
    glDeleteProgramPipelines(1, &pipe);
    glDeleteProgram(p);
    glDeleteProgram(q);
}

/* Creates the GL objects of a validated desc. */
static int vt__gl_create(vt *v, dm_str *log)
{
    int phys = v->per_row * v->slot;
    if (v->sparse) {
        int rc = vt__sparse_create(v, log);
        if (rc)
            return rc;
        vt__sparse_validate(v);
        glCreateTextures(GL_TEXTURE_2D, 3, v->staging);
        for (int i = 0; i < 3; i++)
            glTextureStorage2D(v->staging[i], 1, vt__fmt[i], v->page, v->page);
        glCreateFramebuffers(2, v->fbo);
    } else {
        glCreateTextures(GL_TEXTURE_2D, 3, v->phys);
        for (int i = 0; i < 3; i++) {
            glTextureStorage2D(v->phys[i], 1, vt__fmt[i], phys, phys);
            glTextureParameteri(v->phys[i], GL_TEXTURE_MAX_LEVEL, 0);
        }
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &v->table);
    glTextureStorage2D(v->table, v->levels, GL_RG16UI, vt__pages(v, 0), vt__pages(v, 0));
    /* integer textures are incomplete with linear filters */
    glTextureParameteri(v->table, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(v->table, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateSamplers(2, v->samplers);
    for (int i = 0; i < 2; i++) {
        /* sparse: one level, the one the shader names (textureLod) */
        GLint f = i ? GL_LINEAR : GL_NEAREST;
        GLint fmin = !v->sparse ? f : i ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
        GLint wrap = v->sparse ? GL_REPEAT : GL_CLAMP_TO_EDGE;
        glSamplerParameteri(v->samplers[i], GL_TEXTURE_MIN_FILTER, fmin);
        glSamplerParameteri(v->samplers[i], GL_TEXTURE_MAG_FILTER, f);
        glSamplerParameteri(v->samplers[i], GL_TEXTURE_WRAP_S, wrap);
        glSamplerParameteri(v->samplers[i], GL_TEXTURE_WRAP_T, wrap);
    }
    glCreateBuffers(1, &v->feedback);
    return 0;
}

/* Checks the desc; fills size fields of v.  Message in log on failure. */
static int vt__check(const vt_desc *d, vt *v, dm_str *log)
{
    GLint max_tex = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
    v->kind = maps_kind(d->maps ? d->maps : "");
    if (v->kind < 0) {
        dm_str_printf(log, "virtual texture: maps '%s' is not a procedural set\n", d->maps ? d->maps : "");
        return DM_ERR_UNKNOWN;
    }
    int pow2 = d->size > 0 && d->page > 0 && !(d->size & (d->size - 1)) && !(d->page & (d->page - 1));
    if (!pow2 || d->page > d->size || d->size > VT_MAX_SIZE || d->size / d->page > 4096 || d->cache_pages < 2) {
        dm_str_printf(log, "virtual texture: texture_size %d and vt_page_size %d must be powers of two with "
                      "page <= size <= %d and size/page <= 4096; vt_cache_pages %d must be >= 2\n",
                      d->size, d->page, VT_MAX_SIZE, d->cache_pages);
        return DM_ERR_RANGE;
    }
    v->size = d->size;
    v->page = d->page;
    v->sparse = d->sparse;
    v->slot = d->page + 2 * VT_BORDER;
    v->per_row = (int)ceil(sqrt((double)d->cache_pages));
    v->n_slots = d->cache_pages;
    v->budget = d->budget > 0 ? d->budget : VT_UPLOAD_BUDGET;
    for (v->levels = 1; (d->size / d->page) >> v->levels; v->levels++)
        ;
    if (!v->sparse && (long)v->per_row * v->slot > max_tex) {
        dm_str_printf(log, "virtual texture: a cache of %d pages of %d texels needs a %dx%d texture; "
                      "GL_MAX_TEXTURE_SIZE is %d\n", d->cache_pages, v->slot, v->per_row * v->slot,
                      v->per_row * v->slot, max_tex);
        return DM_ERR_RANGE;
    }
    return 0;
}

int vt_create(const vt_desc *d, vt **out, dm_str *log)
{
    vt *v = dm_xcalloc(1, sizeof *v);
    int rc = vt__check(d, v, log);
    if (rc) {
        free(v);
        return rc;
    }
    v->slot_page = dm_xmalloc((size_t)v->n_slots * sizeof *v->slot_page);
    memset(v->slot_page, 0xFF, (size_t)v->n_slots * sizeof *v->slot_page);
    v->slot_used = dm_xcalloc((size_t)v->n_slots, sizeof *v->slot_used);
    v->tab = dm_xcalloc((size_t)v->levels, sizeof *v->tab);
    v->dirty = dm_xcalloc((size_t)v->levels * 4, sizeof *v->dirty);
    for (int m = 0; m < v->levels; m++)
        v->tab[m] = dm_xcalloc((size_t)vt__pages(v, m) * (size_t)vt__pages(v, m) * 2, sizeof(uint16_t));
    rc = vt__gl_create(v, log);
    if (rc) {
        vt_destroy(v);
        return rc;
    }
    vt__load(v, vt__id(v->levels - 1, 0, 0), 0);   /* the coarsest page, pinned in slot 0 */
    vt__table_upload(v);
    *out = v;
    return 0;
}

void vt_destroy(vt *v)
{
    if (!v)
        return;
    glDeleteTextures(3, v->phys);
    glDeleteTextures(3, v->staging);
    glDeleteFramebuffers(2, v->fbo);
    glDeleteTextures(1, &v->table);
    glDeleteSamplers(2, v->samplers);
    glDeleteBuffers(1, &v->feedback);
    for (int m = 0; m < v->levels; m++)
        free(v->tab[m]);
    free(v->tab);
    free(v->dirty);
    free(v->slot_page);
    free(v->slot_used);
    free(v);
}

/* Sets the vt.glsl uniforms of program (locations of -1 are ignored); the
 * program was compiled with VT_SOFTWARE (and VT_FILTER_TRILINEAR for
 * trilinear/anisotropic filters), see render__defines. */
static void vt__uniforms(const vt *v, GLuint p)
{
    glProgramUniform1f(p, glGetUniformLocation(p, "u_vt_size"), (float)v->size);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_vt_page"), (float)v->page);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_vt_border"), (float)VT_BORDER);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_vt_per_row"), v->per_row);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_vt_phys"), (float)(v->per_row * v->slot));
    glProgramUniform1i(p, glGetUniformLocation(p, "u_vt_levels"), v->levels);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_vt_fb_width"), v->fb_w);
}

void vt_frame(vt *v, GLuint program, int filter, int width, int height)
{
    int fw = (width + VT_FEEDBACK_SCALE - 1) / VT_FEEDBACK_SCALE;
    int fh = (height + VT_FEEDBACK_SCALE - 1) / VT_FEEDBACK_SCALE;
    v->frame++;
    if (v->fb_valid && fw == v->fb_w && fh == v->fb_h)
        vt__update(v);
    if (fw != v->fb_w || fh != v->fb_h) {
        v->fb_w = fw;
        v->fb_h = fh;
        glNamedBufferData(v->feedback, (GLsizeiptr)((size_t)fw * (size_t)fh * sizeof(uint32_t)), NULL, GL_DYNAMIC_READ);
    }
    vt__table_upload(v);
    GLuint none = VT__NONE;
    glClearNamedBufferData(v->feedback, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
    v->fb_valid = 1;
    for (GLuint u = 0; u < 3; u++) {
        glBindTextureUnit(u, v->phys[u]);
        glBindSampler(u, v->samplers[filter > 0]);
    }
    glBindTextureUnit(3, v->table);
    glBindSampler(3, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, v->feedback);
    vt__uniforms(v, program);
    v->st.frames++;
    v->st.pages_resident = 0;
    for (int s = 0; s < v->n_slots; s++)
        v->st.pages_resident += v->slot_page[s] != VT__NONE;
}

size_t vt_bytes(const vt *v)
{
    size_t phys = (size_t)v->per_row * (size_t)v->slot;
    size_t total = v->sparse ? (size_t)v->committed * (size_t)v->page * (size_t)v->page * 12
                             : phys * phys * 12;   /* R32F + RGBA8 + RGBA8 */
    for (int m = 0; m < v->levels; m++)
        total += (size_t)vt__pages(v, m) * (size_t)vt__pages(v, m) * 4;   /* RG16UI */
    return total;
}

void vt_get_stats(const vt *v, render_vt_stats *out)
{
    *out = v->st;
    size_t phys = (size_t)v->per_row * (size_t)v->slot;
    out->committed_bytes = v->sparse ? (uint64_t)v->committed * (uint64_t)v->page * (uint64_t)v->page * 12
                                     : (uint64_t)(phys * phys * 12);
}
