/* render.c — configurations to GL draws, with the program and item caches
 * (meshes: render_meshes.c; maps: render_textures.c).
 *
 * Scene conventions (shared by every technique):
 *  - camera: orbit around the target T = camera.target_x/y/z (default the
 *    origin); azimuth 0 / elevation 0 puts it on +Z of T looking at T,
 *    elevation turns it up toward +Y; perspective with the vertical fov in
 *    degrees, aspect from the viewport, near 0.05, far 100;
 *  - meshes are drawn in object space = world space (model = identity),
 *    counter-clockwise front faces, back faces culled unless cull=off;
 *    clip_space meshes (`fullscreen`) are drawn with identity matrices;
 *  - light i (of light_count) is a point light around T at azimuth +
 *    light.azimuth + i·45°, elevation min(elevation + light.elevation −
 *    10°·(i mod 3), 80°), distance light.distance × the camera distance
 *    (defaults 45°, 35°, 1.2; distance 0 puts every light at T); colour
 *    1.6/(1 + 0.25·(count − 1)); attenuation (axis) 1/(1 + 0.1 d + 0.05 d²)
 *    by default, S1's max(0, 1 − d²/r²) with r = light_radius, or none;
 *    ambient 0.08; shininess 48; Cook-Torrance f0 0.04, roughness = the
 *    roughness axis (u_roughness, default 0.35);
 *  - debug view normals (render_set_debug_view): light slots 0..3
 *    carry the origin and the world unit vectors, so the fragment stage
 *    recovers its tangent frame from their tangent-space images
 *    (surface.frag.glsl, DEBUG_NORMALS);
 *  - textures: unit 0 height (R, value in [0,1]), unit 1 normal (n·0.5+0.5),
 *    unit 2 albedo; CPU box-filtered mip chain, GL_REPEAT; the `filter` axis
 *    picks a sampler: nearest = NEAREST_MIPMAP_NEAREST, bilinear =
 *    LINEAR_MIPMAP_NEAREST, trilinear = LINEAR_MIPMAP_LINEAR, anisoN =
 *    trilinear + anisotropy min(N, GL_MAX_TEXTURE_MAX_ANISOTROPY).
 */
#include "techniques/render.h"

#include <epoxy/gl.h>
#include <cglm/cglm.h>
#include <ctype.h>
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/axes.h"
#include "techniques/shaders.h"
#include "techniques/technique.h"
#include "techniques/render_internal.h"
#include "techniques/render_meshes.h"
#include "techniques/mesh.h"
#include "techniques/user_mesh.h"
#include "techniques/user_technique.h"
#include "techniques/lod_cpu.h"
#include "techniques/fs_minimal.h"

static const char *const render__uniform_names[RU_COUNT] = {
    "u_model", "u_view_proj", "u_normal_mat", "u_camera_pos", "u_light_pos", "u_light_color",
    "u_light_count", "u_atten", "u_ambient", "u_shininess", "u_f0", "u_viewport",
    "u_normal_xy_scale", "u_lod_base", "u_tess_edge_ref", "u_lod_origin", "u_lod_object_dist",
    "u_lod_tile", "u_lod_tiled"
};

int render_create(render_ctx **out)
{
    /* glGetString returns NULL when no context is current. */
    const char *ren = (const char *)glGetString(GL_RENDERER);
    const char *ver = ren ? (const char *)glGetString(GL_VERSION) : NULL;
    if (!ren || !ver || epoxy_gl_version() < 45)
        return DM_ERR_GL;
    render_ctx *r = dm_xcalloc(1, sizeof *r);
    r->driver = dm_xasprintf("%s | %s", ren, ver);
    if (epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
        epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic"))
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &r->max_aniso);
    *out = r;
    return 0;
}

void render_destroy(render_ctx *r)
{
    if (!r)
        return;
    for (size_t i = 0; i < r->n_progs; i++) {
        glDeleteProgram(r->progs[i].id);
        free(r->progs[i].key);
        free(r->progs[i].axis_loc);
    }
    for (size_t i = 0; i < r->n_meshes; i++) {
        glDeleteVertexArrays(1, &r->meshes[i].vao);
        glDeleteBuffers(1, &r->meshes[i].vbo);
        glDeleteBuffers(1, &r->meshes[i].ibo);
        glDeleteBuffers(1, &r->meshes[i].seam_vbo);
        cull_free(&r->meshes[i].cull);
        free(r->meshes[i].cpu_pos);
        free(r->meshes[i].cpu_idx);
        free(r->meshes[i].key);
    }
    render__maps_destroy(r);
    for (size_t i = 0; i < r->n_items; i++) {
        free(r->items[i].axis_val);
        free(r->items[i].lod_levels);
        glDeleteBuffers(1, &r->items[i].lod_buf);
    }
    free(r->progs);
    free(r->meshes);
    free(r->items);
    free(r->driver);
    free(r->cache_dir);
    free(r);
}

int render_set_cache_dir(render_ctx *r, const char *dir)
{
    GLint formats = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    free(r->cache_dir);
    r->cache_dir = NULL;
    if (!dir)
        return 0;
    if (formats < 1)
        return DM_ERR_UNSUPPORTED;
    r->cache_dir = dm_xstrdup(dir);
    return 0;
}

int render_set_debug_view(render_ctx *r, render_debug_view view)
{
    if (!r || (view != RENDER_DEBUG_NONE && view != RENDER_DEBUG_NORMALS && view != RENDER_DEBUG_MINIMAL_FS &&
               view != RENDER_DEBUG_LOOP_TRIPS))
        return DM_ERR_ARG;
    r->debug_view = view;
    return 0;
}

/* ---- parameters --------------------------------------------------------- */

/* Validates every parameter; the technique may be a test-only one. */
static int render__validate(const render__cfg *c, const technique_desc **tech, dm_str *log)
{
    const char *tname = render__get(c, "technique");
    *tech = technique_find(tname);
    if (!*tech) {
        dm_str err = {0};
        int rc = axes_check("technique", tname, &err);
        dm_str_printf(log, "%s\n", dm_str_get(&err));
        dm_str_free(&err);
        return rc ? rc : DM_ERR_UNKNOWN;
    }
    for (size_t i = 0; i < c->n; i++) {
        if (!c->kv[i].key || strcmp(c->kv[i].key, "technique") == 0)
            continue;
        dm_str err = {0};
        int rc = axes_check(c->kv[i].key, c->kv[i].value, &err);
        if (rc)
            dm_str_printf(log, "%s\n", dm_str_get(&err));
        dm_str_free(&err);
        if (rc)
            return rc;
    }
    return 0;
}

/* The defines of a configuration's program: "#define AXIS_VALUE" for every
 * ENUM axis the technique declares, "#define AXIS_AUTO" for an integer axis
 * it declares at 'auto', and VT_SOFTWARE or VT_SPARSE (+
 * VT_FILTER_TRILINEAR) with virtual_texture=software or sparse.  Whatever changes a shader's control flow or
 * sampling path is compiled in, not switched by a uniform: llvmpipe 22.3
 * runs both sides of a branch on a uniform condition, so a switched-off
 * path would be measured as part of the technique (docs/techniques.md). */
static void render__defines(const technique_desc *t, const render__cfg *c, dm_str *out)
{
    if (t->defines)
        dm_str_cat(out, t->defines);
    if (t->tcs && mesh_patch_vertices(render__get(c, "mesh")) == 4)
        dm_str_cat(out, "#define TESS_QUADS\n");
    const char *vtv = render__get(c, "virtual_texture");
    if (strcmp(vtv, "software") == 0 || strcmp(vtv, "sparse") == 0) {
        dm_str_cat(out, strcmp(vtv, "sparse") == 0 ? "#define VT_SPARSE\n" : "#define VT_SOFTWARE\n");
        if (render__vt_filter(render__get(c, "filter")) == 2)
            dm_str_cat(out, "#define VT_FILTER_TRILINEAR\n");
    }
    for (size_t i = 0; t->axes && t->axes[i]; i++) {
        const axis_info *a = axes_find(t->axes[i]);
        if (!a || (a->kind != AXIS_ENUM && a->kind != AXIS_INT))
            continue;
        if (a->kind == AXIS_INT && strcmp(render__get(c, a->name), "auto") != 0)
            continue;
        char buf[128];
        snprintf(buf, sizeof buf, "%s_%s", a->name, render__get(c, a->name));
        for (char *p = buf; *p; p++)
            *p = *p == '-' || *p == '.' ? '_' : (char)toupper((unsigned char)*p);
        dm_str_printf(out, "#define %s\n", buf);
    }
}

/* ---- programs ----------------------------------------------------------- */

/* The inputs the compiler finds active in fragment shader src, one per
 * line as GL names them, from a separable program of that stage alone
 * (its inputs are the fragment stage's); NULL when it does not link. */
static char *render__fs_active_inputs(const char *src)
{
    GLuint prog = glCreateShaderProgramv(GL_FRAGMENT_SHADER, 1, &src);
    GLint ok = 0, n = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        glDeleteProgram(prog);
        return NULL;
    }
    glGetProgramInterfaceiv(prog, GL_PROGRAM_INPUT, GL_ACTIVE_RESOURCES, &n);
    dm_str names = {0};
    for (GLint i = 0; i < n; i++) {
        char name[256];
        GLsizei len = 0;
        glGetProgramResourceName(prog, GL_PROGRAM_INPUT, (GLuint)i, sizeof name, &len, name);
        dm_str_printf(&names, "%s\n", name);
    }
    glDeleteProgram(prog);
    char *list = dm_str_take(&names);
    return list ? list : dm_xstrdup("");
}

/* Replaces the composed fragment shader src by its minimal form
 * (fs_minimal.h, the stage-isolation raster pass), reading the inputs the
 * original reads; -1 with the reason in log. */
static int render__minimal_fs(dm_str *src, const char *tname, dm_str *log)
{
    dm_str min = {0}, why = {0};
    char *active = render__fs_active_inputs(dm_str_get(src));
    int rc = active ? fs_minimal_make(dm_str_get(src), active, &min, &why) : DM_ERR_SHADER;
    if (!active)
        dm_str_cat(&why, "the fragment shader does not link alone");
    free(active);
    if (rc != 0)
        dm_str_printf(log, "technique '%s': no minimal fragment shader: %s\n", tname, dm_str_get(&why));
    else {
        dm_str tmp = *src;
        *src = min;
        min = tmp;
    }
    dm_str_free(&min);
    dm_str_free(&why);
    return rc ? -1 : 0;
}

static GLuint render__compile(GLenum stage, const char *file, const char *defines,
                              const technique_desc *t, dm_str *log)
{
    const char *tname = t->name;
    dm_str src = {0}, err = {0};
    if (shaders_compose(file, defines, &src, &err)) {
        dm_str_printf(log, "technique '%s': %s", tname, dm_str_get(&err));
        dm_str_free(&src);
        dm_str_free(&err);
        return 0;
    }
    if (stage == GL_FRAGMENT_SHADER && defines && strstr(defines, FS_MINIMAL_DEFINE) &&
        render__minimal_fs(&src, tname, log) != 0)
        return 0;
    GLuint sh = glCreateShader(stage);
    const char *text = dm_str_get(&src);
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    dm_str_free(&src);
    GLint ok = 0, len = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok)
        return sh;
    glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
    char *info = dm_xcalloc(1, (size_t)len + 1);
    glGetShaderInfoLog(sh, len, NULL, info);
    dm_str_printf(log, "technique '%s': shader '%s' failed to compile:\n", tname, file);
    user_technique_map_log(t, info, log);   /* a user's lines as file:line:column */
    free(info);
    glDeleteShader(sh);
    return 0;
}

/* Compiles and links the technique's stages (retrievable: ask the driver to
 * keep a binary for the disk cache); returns 0 and fills log on failure. */
static GLuint render__link(const technique_desc *t, const char *defines, int retrievable,
                           dm_str *log)
{
    const char *files[5] = {t->vs, t->tcs, t->tes, t->gs, t->fs};
    static const GLenum stages[5] = {GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER,
                                     GL_TESS_EVALUATION_SHADER, GL_GEOMETRY_SHADER,
                                     GL_FRAGMENT_SHADER};
    GLuint prog = glCreateProgram(), sh[5] = {0};
    int failed = 0;
    for (int i = 0; i < 5; i++) {
        if (!files[i])
            continue;
        sh[i] = render__compile(stages[i], files[i], defines, t, log);
        if (!sh[i])
            failed = 1;
        else
            glAttachShader(prog, sh[i]);
    }
    GLint ok = 0;
    if (!failed) {
        if (retrievable)
            glProgramParameteri(prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
        glLinkProgram(prog);
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    }
    if (!failed && !ok) {
        GLint len = 0;
        glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
        char *info = dm_xcalloc(1, (size_t)len + 1);
        glGetProgramInfoLog(prog, len, NULL, info);
        dm_str_printf(log, "technique '%s': program failed to link:\n", t->name);
        user_technique_map_log(t, info, log);
        free(info);
    }
    for (int i = 0; i < 5; i++)
        if (sh[i])
            glDeleteShader(sh[i]);
    if (failed || !ok) {
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

/* File of a program key in the binary cache: "<dir>/<fnv64 of key>.glbin"
 * holding key, NUL, the GLenum binary format, then the binary. */
static char *render__binary_path(const render_ctx *r, const char *key)
{
    char hex[17];
    dm_hex64(dm_fnv1a64(key, strlen(key), DM_FNV_SEED), hex);
    return dm_xasprintf("%s/%s.glbin", r->cache_dir, hex);
}

/* Program from the on-disk cache, or 0 when absent, foreign or rejected. */
static GLuint render__binary_load(const render_ctx *r, const char *key)
{
    char *path = render__binary_path(r, key), *buf = NULL;
    size_t len = 0, klen = strlen(key) + 1;
    GLuint prog = 0;
    if (dm_read_file(path, &buf, &len) == 0 && len > klen + sizeof(GLenum) &&
        memcmp(buf, key, klen) == 0) {
        GLenum fmt;
        memcpy(&fmt, buf + klen, sizeof fmt);
        prog = glCreateProgram();
        glProgramBinary(prog, fmt, buf + klen + sizeof fmt, (GLsizei)(len - klen - sizeof fmt));
        GLint ok = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            glDeleteProgram(prog);
            prog = 0;
        }
    }
    while (glGetError() != GL_NO_ERROR)
        ;   /* a rejected binary may raise INVALID_ENUM; it is recompiled */
    free(buf);
    free(path);
    return prog;
}

/* Stores a linked program's binary; failures only cost the next compile. */
static void render__binary_save(const render_ctx *r, const char *key, GLuint prog)
{
    GLint blen = 0;
    glGetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &blen);
    if (blen <= 0 || dm_mkdirs(r->cache_dir) != 0)
        return;
    size_t klen = strlen(key) + 1;
    char *buf = dm_xmalloc(klen + sizeof(GLenum) + (size_t)blen);
    GLenum fmt = 0;
    GLsizei got = 0;
    memcpy(buf, key, klen);
    glGetProgramBinary(prog, blen, &got, &fmt, buf + klen + sizeof fmt);
    memcpy(buf + klen, &fmt, sizeof fmt);
    char *path = render__binary_path(r, key);
    if (got > 0 && dm_write_file(path, buf, klen + sizeof fmt + (size_t)got) != 0)
        dm_log(DM_LOG_WARN, "cannot write program cache file %s", path);
    free(path);
    free(buf);
}

/* Program of key from disk or compiled (and then stored); *from_disk set. */
static GLuint render__program_make(render_ctx *r, const technique_desc *t, const char *defines,
                                   const char *key, int *from_disk, dm_str *log)
{
    GLuint id = r->cache_dir ? render__binary_load(r, key) : 0;
    *from_disk = id != 0;
    if (id)
        return id;
    id = render__link(t, defines, r->cache_dir != NULL, log);
    if (id && r->cache_dir)
        render__binary_save(r, key, id);
    return id;
}

/* Finds or builds the program of (technique, defines, driver); *cached = 1
 * when it came from the cache.  DM_ERR_SHADER with the info log on failure. */
/* Hash of the technique's composed GLSL (every stage, with its includes and
 * defines), so the on-disk binary cache never loads a program built from an
 * older version of the shaders. */
static uint64_t render__source_hash(const technique_desc *t, const char *defines)
{
    const char *stages[5] = {t->vs, t->tcs, t->tes, t->gs, t->fs};
    uint64_t h = DM_FNV_SEED;
    for (int i = 0; i < 5; i++) {
        dm_str src = {0}, err = {0};
        if (stages[i] && shaders_compose(stages[i], defines, &src, &err) == 0)
            h = dm_fnv1a64(src.buf, src.len, h);
        h = dm_fnv1a64(&i, sizeof i, h);
        dm_str_free(&src);
        dm_str_free(&err);
    }
    return h;
}

static int render__program_get(render_ctx *r, const technique_desc *t, const char *defines,
                               size_t *idx, int *cached, dm_str *log)
{
    char hash[17];
    dm_hex64(render__source_hash(t, defines), hash);
    char *key = dm_xasprintf("%s\n%s\n%s\n%s", t->name, defines, r->driver, hash);
    for (size_t i = 0; i < r->n_progs; i++)
        if (strcmp(r->progs[i].key, key) == 0) {
            free(key);
            *idx = i;
            *cached = 1;
            return 0;
        }
    int from_disk = 0;
    GLuint id = render__program_make(r, t, defines, key, &from_disk, log);
    if (!id) {
        free(key);
        return DM_ERR_SHADER;
    }
    size_t n = RENDER__PUSH(r->progs, r->n_progs);
    render__program *p = &r->progs[n];
    p->key = key;
    p->id = id;
    for (int u = 0; u < RU_COUNT; u++)
        p->loc[u] = glGetUniformLocation(id, render__uniform_names[u]);
    p->axis_loc = dm_xmalloc(axes_count() * sizeof(GLint));
    for (size_t a = 0; a < axes_count(); a++) {
        char name[80];
        snprintf(name, sizeof name, "u_%s", axes_at(a)->name);
        for (char *c = name; *c; c++)
            *c = *c == '.' ? '_' : *c;
        p->axis_loc[a] = glGetUniformLocation(id, name);
    }
    *idx = n;
    *cached = from_disk ? 2 : 0;
    return 0;
}

/* ---- items ---------------------------------------------------------------- */

/* Fills the item's numeric uniforms and camera from the configuration. */
static void render__item_values(render__item *it, const render__cfg *c)
{
    static const char *const cam[12] = {"camera.distance", "camera.azimuth", "camera.elevation",
                                        "camera.fov", "camera.target_x", "camera.target_y",
                                        "camera.target_z", "light.azimuth", "light.elevation",
                                        "light.distance", "camera.orbit_deg_per_frame",
                                        "light.orbit_deg_per_frame"};
    float *dst[12] = {&it->cam[0], &it->cam[1], &it->cam[2], &it->cam[3], &it->target[0],
                      &it->target[1], &it->target[2], &it->light[0], &it->light[1], &it->light[2],
                      &it->orbit[0], &it->orbit[1]};
    for (int i = 0; i < 12; i++)
        *dst[i] = (float)atof(render__get(c, cam[i]));
    it->axis_val = dm_xcalloc(axes_count(), sizeof(double));
    for (size_t a = 0; a < axes_count(); a++) {
        const axis_info *ax = axes_at(a);
        if (ax->kind != AXIS_INT && ax->kind != AXIS_FLOAT)
            continue;
        const char *v = render__get(c, ax->name);
        it->axis_val[a] = strcmp(v, "auto") == 0 ? 0.0 : atof(v);
    }
    it->light_count = technique_reads_axis(it->tech, "light_count")
                          ? atoi(render__get(c, "light_count")) : 1;
    static const char *const paths[] = {"still", "orbit", "dolly", "flyover"};
    const char *path = render__get(c, "camera.path");
    for (int k = 0; k < 4; k++)
        if (path && strcmp(path, paths[k]) == 0)
            it->path_kind = k;
    it->path[0] = (float)atof(render__get(c, "camera.path_frames"));
    it->path[1] = (float)atof(render__get(c, "camera.dolly_to"));
    it->path[2] = (float)atof(render__get(c, "camera.flyover_height"));
}

/* What the item's fragment shader does that stage isolation must know
 * (render_item_info: has_fs, fs_discards, fs_writes_depth). */
static void render__fs_traits(render__item *it, const char *defines)
{
    dm_str src = {0}, err = {0};
    fs_traits tr = {0};
    it->info.has_fs = it->tech->fs != NULL;
    if (it->tech->fs && shaders_compose(it->tech->fs, defines, &src, &err) == 0)
        fs_minimal_traits(dm_str_get(&src), &tr);
    it->info.fs_discards = tr.discards;
    it->info.fs_writes_depth = tr.writes_depth;
    dm_str_free(&src);
    dm_str_free(&err);
}

static int render__prepare_resources(render_ctx *r, render__item *it, const render__cfg *c,
                                     dm_str *log)
{
    int cached = 0, rc;
    dm_str defs = {0};
    if (it->tech->requires_ext && !epoxy_has_gl_extension(it->tech->requires_ext)) {
        dm_str_printf(log, "technique '%s' needs %s, which this driver lacks\n", it->tech->name,
                      it->tech->requires_ext);
        return DM_ERR_UNSUPPORTED;
    }
    render__defines(it->tech, c, &defs);
    if (it->debug_view == RENDER_DEBUG_NORMALS)
        dm_str_cat(&defs, "#define DEBUG_NORMALS\n");
    render__fs_traits(it, dm_str_get(&defs));
    if (it->debug_view == RENDER_DEBUG_MINIMAL_FS)
        dm_str_cat(&defs, FS_MINIMAL_DEFINE);
    if (it->debug_view == RENDER_DEBUG_LOOP_TRIPS) {
        if (!epoxy_has_gl_extension("GL_ARB_shader_ballot")) {
            dm_str_free(&defs);
            dm_str_cat(log, "counting loop trips needs GL_ARB_shader_ballot, which this driver lacks\n");
            return DM_ERR_UNSUPPORTED;
        }
        dm_str_printf(&defs, "#extension GL_ARB_shader_ballot : require\n#define COUNT_LOOP_TRIPS %d\n",
                      RENDER_LOOP_TRIPS_BINDING);
    }
    rc = render__program_get(r, it->tech, dm_str_get(&defs), &it->prog, &cached, log);
    dm_str_free(&defs);
    if (!rc)
        rc = render__mesh_get(r, it->tech, c, &it->mesh, log);
    if (!rc)
        rc = render__maps_get(r, c, &it->maps, log);
    if (rc)
        return rc;
    it->sampler = render__sampler_get(r, render__get(c, "filter"));
    it->info.program_cached = cached;
    return 0;
}

/* Patches per draw call of a tessellating item.  llvmpipe (Mesa 22.3)
 * loses primitives when the tessellated vertices of one internal batch of
 * patches exceed 16-bit indices (a 320-patch draw at level 16 drops about a
 * tenth of its triangles; the counters still count them), so a draw is
 * split into calls of at most 65 535 / V patches, V = the most vertices one
 * triangle patch can produce at the item's highest level (lod distance can
 * reach 64, long edges get `edge_factor` times the level (mesh.h);
 * fractional spacing rounds up to the next even level + 2). */
static size_t render__patch_chunk(const render__cfg *c, int quads, int edge_factor)
{
    int L = atoi(render__get(c, "tess_level")) * edge_factor;
    const char *lod = render__get(c, "lod");
    if (strcmp(lod, "distance") == 0 || strcmp(lod, "cpu-per-patch") == 0 ||
        strncmp(lod, "object-", 7) == 0 || L > 64)
        L = 64;
    int half = (L + 3) / 2 + 1;
    size_t v = quads ? (size_t)(L + 3) * (size_t)(L + 3)
                     : 3 * (size_t)half * (size_t)(half + 1) + 1;
    return 65535 / v;
}

int render_patch_calls(const dm_kv *params, size_t n_params, size_t *patches, size_t *per_call, dm_str *log)
{
    render__cfg c = {params, n_params};
    const technique_desc *t = technique_find(render__get(&c, "technique"));
    *patches = *per_call = 0;
    if (!t) {
        dm_str_printf(log, "unknown technique '%s'", render__get(&c, "technique"));
        return DM_ERR_UNKNOWN;
    }
    if (!t->tcs && !t->tes)
        return DM_ERR_ARG;
    mesh_data md;
    mesh_desc d = {.name = render__get(&c, "mesh"), .density = atoi(render__get(&c, "mesh_density"))};
    int had_tangents = 0;
    int rc = strncmp(d.name, USER_MESH_PREFIX, strlen(USER_MESH_PREFIX)) == 0
             ? user_mesh_load(d.name + strlen(USER_MESH_PREFIX), &md, &had_tangents, log)
             : mesh_build(&d, &md);
    if (rc) {
        dm_str_printf(log, "mesh '%s' with density %d: %s", d.name, d.density, dm_strerror(rc));
        return rc;
    }
    float longest = 0;   /* as render__mesh_get: the long-edge rule is tessellation's */
    float median = t->tcs ? mesh_edge_median(&md, &longest) : 0;
    int quads = md.n_quad_indices && t->tcs;
    *patches = quads ? md.n_quad_indices / 4 : md.n_indices / 3;
    *per_call = render__patch_chunk(&c, quads, mesh_edge_factor(longest, median));
    mesh_free(&md);
    return 0;
}

/* visibility_test on: the item draws only the chunks of its triangle list
 * that can be seen (cull.h), each box padded by the largest displacement
 * |height_scale| · max(|h − 0.5|) of its height map. */
static void render__cull_setup(const render_ctx *r, render__item *it, const render__cfg *c)
{
    if (!technique_reads_axis(it->tech, "visibility_test") ||
        strcmp(render__get(c, "visibility_test"), "on") != 0 || !r->meshes[it->mesh].cull.n)
        return;
    const render__maps *mp = &r->maps[it->maps];
    float reach = fmaxf(fabsf(mp->h_hi - 0.5f), fabsf(mp->h_lo - 0.5f));
    it->cull = 1;
    it->cull_pad = fabsf((float)atof(render__get(c, "height_scale"))) * reach;
}

/* lod=object-points / object-cpu: the mesh's objects (lod_cpu.h), each
 * drawn by its own call with its own uniforms (a mesh of quad patches has
 * no object_triangles: it is one object). */
static void render__lod_objects_setup(const render_ctx *r, render__item *it, const char *lod)
{
    const render__mesh *m = &r->meshes[it->mesh];
    size_t n_tris = m->n_indices / 3, per = m->object_tris ? m->object_tris : n_tris;
    it->lod_objects = dm_xcalloc(per ? (n_tris + per - 1) / per + 1 : 1, sizeof(lod_object));
    it->n_lod_objects = lod_cpu_objects(m->cpu_pos, m->cpu_idx, n_tris, m->object_tris,
                                        it->lod_objects);
    it->lod_object_cpu = strcmp(lod, "object-cpu") == 0;
}

/* lod=cpu-per-patch: the item's per-patch level buffer (filled every draw by
 * render__lod_upload) and whether levels are per edge (crack_free);
 * object-points / object-cpu: the objects. */
static void render__lod_setup(const render_ctx *r, render__item *it, const render__cfg *c)
{
    const char *lod = render__get(c, "lod");
    if (it->tech->tcs && strncmp(lod, "object-", 7) == 0)
        render__lod_objects_setup(r, it, lod);
    if (!it->tech->tcs || strcmp(lod, "cpu-per-patch") != 0)
        return;
    const render__mesh *m = &r->meshes[it->mesh];
    size_t n = it->patch_vertices == 4 ? m->n_quad_indices / 4 : m->n_indices / 3;
    it->lod_levels = dm_xcalloc(n ? n : 1, 4 * sizeof(float));
    it->lod_per_edge = strcmp(render__get(c, "crack_free"), "on") == 0;
    glCreateBuffers(1, &it->lod_buf);
    glNamedBufferStorage(it->lod_buf, (GLsizeiptr)((n ? n : 1) * 4 * sizeof(float)), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
}

static void render__item_info(render_ctx *r, render__item *it)
{
    const render__mesh *m = &r->meshes[it->mesh];
    it->info.mesh_vertices = m->n_vertices;
    it->info.mesh_triangles = m->n_indices / 3;
    it->info.mesh_bytes = m->bytes;
    it->info.texture_bytes = render__maps_bytes(r, it);
}

int render_prepare(render_ctx *r, const dm_kv *params, size_t n_params, render_item *out,
                 dm_str *log)
{
    int64_t t0 = dm_now_ns();
    render__cfg c = {params, n_params};
    render__item it = {.debug_view = r ? r->debug_view : 0};
    dm_str scratch = {0};
    dm_str *l = log ? log : &scratch;
    int rc = r ? render__validate(&c, &it.tech, l) : DM_ERR_ARG;
    if (!rc)
        rc = render__prepare_resources(r, &it, &c, l);
    dm_str_free(&scratch);
    if (rc)
        return rc;
    render__item_values(&it, &c);
    render__cull_setup(r, &it, &c);
    if (it.tech->tcs || it.tech->tes) {
        it.patch_vertices = r->meshes[it.mesh].n_quad_indices && it.tech->tcs ? 4 : 3;
        it.patch_chunk = render__patch_chunk(&c, it.patch_vertices == 4,
                                             r->meshes[it.mesh].edge_factor_max);
        render__lod_setup(r, &it, &c);
    }
    it.cull_off = strcmp(render__get(&c, "cull"), "off") == 0;
    render__item_info(r, &it);
    it.used = 1;
    it.info.setup_ns = dm_now_ns() - t0;
    size_t n = RENDER__PUSH(r->items, r->n_items);
    r->items[n] = it;
    out->id = (uint32_t)(n + 1);
    return 0;
}

static render__item *render__item_of(render_ctx *r, render_item item)
{
    if (!r || item.id == 0 || item.id > r->n_items || !r->items[item.id - 1].used)
        return NULL;
    return &r->items[item.id - 1];
}

/* Light i of n, placed from the camera and the light.* axes around the
 * camera target (see the top comment). */
/* Degrees orbit k (0 camera, 1 lights) has turned by at the item's frame,
 * in [0, 360): exact for whole degrees, so frame k of an orbit equals a
 * static render at the turned azimuth. */
static float render__orbit(const render__item *it, int k)
{
    return (float)fmod((double)it->frame * (double)it->orbit[k], 360.0);
}

/* Frames of one pass along the item's camera path (camera.path_frames). */
static uint64_t render__path_frames(const render__item *it)
{
    return it->path[0] >= 2 ? (uint64_t)it->path[0] : 2;
}

/* The item's frame as a position along its camera path: *f = frame mod F,
 * returned as u = *f / (F − 1) in [0, 1]. */
static float render__path_u(const render__item *it, float *f)
{
    uint64_t n = render__path_frames(it);
    *f = (float)(it->frame % n);
    return *f / (float)(n - 1);
}

/* Camera azimuth in degrees: the camera.azimuth axis, turned by
 * camera.orbit_deg_per_frame and, on an orbit path, by 360°/F a frame (one
 * circle per pass).  The lights follow it. */
static float render__cam_azimuth(const render__item *it)
{
    float f = 0;
    render__path_u(it, &f);
    float turn = it->path_kind == RENDER__PATH_ORBIT ? 360.0f * f / (float)render__path_frames(it) : 0.0f;
    return it->cam[1] + render__orbit(it, 0) + turn;
}

static void render__light(const render__item *it, int i, float pos[3], float col[3])
{
    float az = glm_rad(render__cam_azimuth(it) + (it->light[0] + render__orbit(it, 1)) + 45.0f * (float)i);
    float el = glm_rad(fminf(it->cam[2] + it->light[1] - 10.0f * (float)(i % 3), 80.0f));
    float d = it->light[2] * it->cam[0];
    pos[0] = it->target[0] + d * cosf(el) * sinf(az);
    pos[1] = it->target[1] + d * sinf(el);
    pos[2] = it->target[2] + d * cosf(el) * cosf(az);
    float k = 1.6f / (1.0f + 0.25f * (float)(it->light_count - 1));
    col[0] = col[1] = col[2] = k;
}

/* The light slots of the normals view: the origin and the world unit
 * vectors, whose tangent-space images give the fragment its frame. */
static void render__debug_lights(float lp[][3])
{
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            lp[i][k] = i == k + 1 ? 1.0f : 0.0f;
}

/* Sets every uniform the program has (locations of -1 are ignored by GL). */
/* The orbit camera of the item: eye position and view-projection matrix
 * (identity for clip-space meshes).  The model matrix is the identity. */
static void render__camera(const render_ctx *r, const render__item *it, const float viewport[2],
                           vec3 eye, mat4 vp)
{
    float f = 0, u = render__path_u(it, &f);
    float az = glm_rad(render__cam_azimuth(it)), el = glm_rad(it->cam[2]), d = it->cam[0];
    if (it->path_kind == RENDER__PATH_DOLLY)   /* the distance from camera.distance to camera.dolly_to */
        d += (it->path[1] - d) * u;
    eye[0] = it->target[0] + d * cosf(el) * sinf(az);
    eye[1] = it->target[1] + d * sinf(el);
    eye[2] = it->target[2] + d * cosf(el) * cosf(az);
    vec3 centre = {it->target[0], it->target[1], it->target[2]};
    if (it->path_kind == RENDER__PATH_FLYOVER) {
        /* along the horizontal line through the target toward the camera's
         * azimuth, from camera.distance before it to as far beyond, at
         * camera.flyover_height h, looking at the ground 2h ahead */
        float hx = sinf(az), hz = cosf(az), s = d * (1.0f - 2.0f * u), h = it->path[2];
        eye[0] = it->target[0] + hx * s;
        eye[1] = it->target[1] + h;
        eye[2] = it->target[2] + hz * s;
        centre[0] = eye[0] - hx * 2.0f * h;
        centre[1] = it->target[1];
        centre[2] = eye[2] - hz * 2.0f * h;
    }
    mat4 view, proj;
    glm_mat4_identity(vp);
    if (!r->meshes[it->mesh].clip_space) {
        glm_lookat(eye, centre, (vec3){0, 1, 0}, view);
        glm_perspective(glm_rad(it->cam[3]), viewport[0] / viewport[1], 0.05f, 100.0f, proj);
        glm_mat4_mul(proj, view, vp);
    }
}

/* The factor on the normal map's x and y that makes it match the item's
 * height_scale (render__normal_height_scale; 1 for a user's normal file). */
static float render__normal_xy_scale(const render_ctx *r, const render__item *it)
{
    float made_for = r->maps[it->maps].normal_height_scale;
    const axis_info *hs = axes_find("height_scale");
    if (made_for <= 0 || !hs)
        return 1.0f;
    return (float)it->axis_val[hs - axes_at(0)] / made_for;
}

static void render__uniforms(render_ctx *r, const render__item *it, const float viewport[2])
{
    const render__program *p = &r->progs[it->prog];
    const GLint *L = p->loc;
    vec3 eye;
    mat4 model = GLM_MAT4_IDENTITY_INIT, vp;
    mat3 nmat = GLM_MAT3_IDENTITY_INIT;
    render__camera(r, it, viewport, eye, vp);
    float lp[RENDER__MAX_LIGHTS][3] = {{0}}, lc[RENDER__MAX_LIGHTS][3] = {{0}};
    for (int i = 0; i < it->light_count && i < RENDER__MAX_LIGHTS; i++)
        render__light(it, i, lp[i], lc[i]);
    if (it->debug_view == RENDER_DEBUG_NORMALS)
        render__debug_lights(lp);
    glUniformMatrix4fv(L[RU_MODEL], 1, GL_FALSE, (const float *)model);
    glUniformMatrix4fv(L[RU_VIEW_PROJ], 1, GL_FALSE, (const float *)vp);
    glUniformMatrix3fv(L[RU_NORMAL_MAT], 1, GL_FALSE, (const float *)nmat);
    glUniform3fv(L[RU_CAMERA_POS], 1, eye);
    glUniform3fv(L[RU_LIGHT_POS], RENDER__MAX_LIGHTS, &lp[0][0]);
    glUniform3fv(L[RU_LIGHT_COLOR], RENDER__MAX_LIGHTS, &lc[0][0]);
    glUniform1i(L[RU_LIGHT_COUNT], it->light_count);
    glUniform3f(L[RU_ATTEN], 1.0f, 0.1f, 0.05f);
    glUniform3f(L[RU_AMBIENT], 0.08f, 0.08f, 0.08f);
    glUniform1f(L[RU_SHININESS], 48.0f);
    glUniform1f(L[RU_F0], 0.04f);
    glUniform2f(L[RU_VIEWPORT], viewport[0], viewport[1]);
    glUniform1f(L[RU_NORMAL_XY_SCALE], render__normal_xy_scale(r, it));
    glUniform1f(L[RU_TESS_EDGE_REF], r->meshes[it->mesh].edge_median);
    for (size_t a = 0; a < axes_count(); a++) {
        if (p->axis_loc[a] < 0)
            continue;
        if (axes_at(a)->kind == AXIS_INT)
            glUniform1i(p->axis_loc[a], (GLint)it->axis_val[a]);
        else
            glUniform1f(p->axis_loc[a], (GLfloat)it->axis_val[a]);
    }
}

/* lod=cpu-per-patch: the levels of every patch for this draw's camera,
 * computed on the CPU (lod_cpu.h) and uploaded to the buffer the control
 * stage reads (binding 3). */
static void render__lod_upload(render_ctx *r, const render__item *it, const float viewport[2])
{
    const render__mesh *m = &r->meshes[it->mesh];
    int pn = it->patch_vertices;
    size_t n = pn == 4 ? m->n_quad_indices / 4 : m->n_indices / 3;
    const uint32_t *idx = m->cpu_idx + (pn == 4 ? m->n_indices : 0);
    vec3 eye;
    mat4 vp;
    render__camera(r, it, viewport, eye, vp);
    const axis_info *tl = axes_find("tess_level");
    lod_cpu_levels(m->cpu_pos, idx, n, pn, eye, (float)(int)it->axis_val[tl - axes_at(0)],
                   m->edge_median, it->lod_per_edge, it->lod_levels);
    glNamedBufferSubData(it->lod_buf, 0, (GLsizeiptr)(n * 4 * sizeof(float)), it->lod_levels);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, it->lod_buf);
}

/* Patches first .. first + n − 1 (indices, from base) in calls of at most
 * it->patch_chunk patches; u_lod_base = the first patch of each call.
 * Each call is bracketed by the call hook, when one is set. */
static void render__draw_patches(render_ctx *r, const render__item *it, size_t base,
                                 size_t first, size_t n)
{
    size_t pv = (size_t)it->patch_vertices, step = pv * it->patch_chunk;
    for (size_t i = first; i < first + n; i += step) {
        size_t k = first + n - i < step ? first + n - i : step;
        glUniform1i(r->progs[it->prog].loc[RU_LOD_BASE], (GLint)(i / pv));
        if (r->call_hook)
            r->call_hook(r->call_user, r->n_calls, 1);
        glDrawElements(GL_PATCHES, (GLsizei)k, GL_UNSIGNED_INT,
                       (const void *)((base + i) * sizeof(uint32_t)));
        if (r->call_hook)
            r->call_hook(r->call_user, r->n_calls, 0);
        r->n_calls++;
    }
}

/* lod=object-points / object-cpu: one call per object with its tile, its
 * origin and (object-cpu) its distance from the eye, computed now on the
 * CPU as S4 did at every frame. */
static void render__draw_objects(render_ctx *r, const render__item *it, const float viewport[2])
{
    const GLint *L = r->progs[it->prog].loc;
    const render__mesh *m = &r->meshes[it->mesh];
    vec3 eye;
    mat4 vp;
    render__camera(r, it, viewport, eye, vp);
    assert(it->patch_vertices == 3 || it->n_lod_objects == 1);
    glUniform1i(L[RU_LOD_TILED], m->object_tris != 0);
    for (size_t o = 0; o < it->n_lod_objects; o++) {
        const lod_object *ob = &it->lod_objects[o];
        glUniform4fv(L[RU_LOD_TILE], 1, ob->tile);
        glUniform3fv(L[RU_LOD_ORIGIN], 1, ob->origin);
        if (it->lod_object_cpu)
            glUniform1f(L[RU_LOD_OBJECT_DIST], lod_cpu_distance(eye, ob->centre));
        if (it->patch_vertices == 4)   /* quad patches: the whole mesh */
            render__draw_patches(r, it, m->n_indices, 0, m->n_quad_indices);
        else
            render__draw_patches(r, it, 0, 3 * ob->first_tri, 3 * ob->n_tris);
    }
}

/* The triangle list, or with it->cull only the chunks not culled under the
 * item's camera (the margin is the vertex stage's VISIBILITY_MARGIN). */
static void render__draw_triangles(render_ctx *r, const render__item *it, int width, int height)
{
    const render__mesh *m = &r->meshes[it->mesh];
    if (!it->cull) {
        glDrawElements(GL_TRIANGLES, (GLsizei)m->n_indices, GL_UNSIGNED_INT, NULL);
        return;
    }
    vec3 eye;
    mat4 vp;
    render__camera(r, it, (float[2]){(float)width, (float)height}, eye, vp);
    size_t *first = dm_xmalloc(2 * m->cull.n * sizeof(size_t)), *count = first + m->cull.n;
    size_t n = cull_visible(&m->cull, (const float *)vp, it->cull_pad, RENDER__VISIBILITY_MARGIN,
                            first, count);
    for (size_t i = 0; i < n; i++)
        glDrawElements(GL_TRIANGLES, (GLsizei)count[i], GL_UNSIGNED_INT,
                       (const void *)(first[i] * sizeof(uint32_t)));
    free(first);
}

void render_set_call_hook(render_ctx *r, render_call_hook hook, void *user)
{
    r->call_hook = hook;
    r->call_user = hook ? user : NULL;
}

int render_set_frame(render_ctx *r, render_item item, uint64_t frame)
{
    render__item *it = render__item_of(r, item);
    if (!it)
        return DM_ERR_ARG;
    it->frame = frame;
    return 0;
}

int render_draw(render_ctx *r, render_item item, int width, int height)
{
    render__item *it = render__item_of(r, item);
    if (!it || width < 1 || height < 1)
        return DM_ERR_ARG;
    const render__mesh *m = &r->meshes[it->mesh];
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    if (it->cull_off)
        glDisable(GL_CULL_FACE);
    else
        glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_BLEND);
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(r->progs[it->prog].id);
    render__uniforms(r, it, (float[2]){(float)width, (float)height});
    render__maps_bind(r, it);
    glBindVertexArray(m->vao);
    r->n_calls = 0;
    if (it->patch_chunk) {
        /* quad patches are stored after the triangles (mesh.h) */
        size_t pv = (size_t)it->patch_vertices;
        size_t base = pv == 4 ? m->n_indices : 0, total = pv == 4 ? m->n_quad_indices : m->n_indices;
        float vpt[2] = {(float)width, (float)height};
        glPatchParameteri(GL_PATCH_VERTICES, (GLint)pv);
        if (it->lod_buf)
            render__lod_upload(r, it, vpt);
        if (it->lod_objects)
            render__draw_objects(r, it, vpt);
        else
            render__draw_patches(r, it, base, 0, total);
    } else {
        render__draw_triangles(r, it, width, height);
    }
    glBindVertexArray(0);
    return 0;
}

int render_get_info(render_ctx *r, render_item item, render_item_info *out)
{
    render__item *it = render__item_of(r, item);
    if (!it)
        return DM_ERR_ARG;
    *out = it->info;
    return 0;
}

void render_release(render_ctx *r, render_item item)
{
    render__item *it = render__item_of(r, item);
    if (!it)
        return;
    free(it->axis_val);
    it->axis_val = NULL;
    free(it->lod_levels);
    it->lod_levels = NULL;
    free(it->lod_objects);
    it->lod_objects = NULL;
    glDeleteBuffers(1, &it->lod_buf);
    it->lod_buf = 0;
    it->used = 0;
}
