/* axes.c — the built-in rows of the sweep axes and the checks of their
 * values (see axes.h); the registry of all axes is the catalog's. */
#include "techniques/axes.h"
#include "techniques/user_mesh.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "techniques/maps.h"

static const char *const axes__on_off[] = {"on", "off", NULL};
static const char *const axes__dnormals[] = {"map", "height", NULL};
static const char *const axes__spacing[] = {"equal", "fractional_even", "fractional_odd", NULL};
static const char *const axes__lod[] = {"uniform", "distance", "cpu-per-patch", "object-points",
                                        "object-cpu", "screen-edge", "flatness", "constant", NULL};
static const char *const axes__cull[] = {"back", "off", NULL};
static const char *const axes__atten[] = {"inverse-quadratic", "s1", "none", NULL};
static const char *const axes__smooth[] = {"off", "phong", NULL};
static const char *const axes__shadow[] = {"none", "raytrace", "soft", "soft-s2", NULL};
static const char *const axes__lighting[] = {"lambert", "phong", "blinn-phong", "cook-torrance", NULL};
static const char *const axes__filter[] = {"nearest", "bilinear", "trilinear", "aniso2",
                                           "aniso4", "aniso8", "aniso16", NULL};
static const char *const axes__vfilter[] = {"nearest", "bilinear-hw", "bilinear-manual",
                                            "mip", "mip-lerp", NULL};
static const char *const axes__hfmt[] = {"r8", "r16", "r16f", "r32f", "rgba8", "rgba32f", NULL};
static const char *const axes__nfmt[] = {"rgb8", "rgba8", "rg8", "rgb16f", "rgba16f", "rgba32f",
                                         "bc1", "bc3", "bc3nm", "bc5", "bc7", NULL};
static const char *const axes__afmt[] = {"rgba8", "srgb8_a8", "rgba16f", "rgba32f",
                                         "bc1", "bc3", "bc7", NULL};
static const char *const axes__vt[] = {"off", "software", "sparse", NULL};
static const char *const axes__path[] = {"still", "orbit", "dolly", "flyover", NULL};

static int axes__check_mesh(const axis_info *a, const char *value, dm_str *err);
static int axes__check_maps(const axis_info *a, const char *value, dm_str *err);
static int axes__check_enum(const axis_info *a, const char *value, dm_str *err);

#define E AXIS_ENUM
#define I AXIS_INT
#define F AXIS_FLOAT
/* choices of technique, mesh and maps come from their registries (the
 * catalog fills them in, and the technique row's check); technique and mesh
 * stay first and maps last. */
static const axis_info axes__table[] = {
    {"technique", E, NULL, 0, 0, "normal", 1, "surface-detail technique to render", NULL},
    {"mesh", E, NULL, 0, 0, "plane", 1, "built-in mesh", axes__check_mesh},
    {"mesh_density", I, NULL, 0, 1024, "0", 1,
     "mesh resolution (plane: vertices per side, sphere: subdivision level, cylinder: segments); 0 = mesh default", NULL},
    {"resolution", AXIS_SIZE2, NULL, 1, 8192, "640x360", 1, "render target size WxH", NULL},
    {"cull", E, axes__cull, 0, 0, "back", 1,
     "rasteriser face culling: back (back faces dropped) or off (both sides drawn)", NULL},
    {"tess_level", I, NULL, 1, 64, "1", 0, "tessellation level (inner = outer)", NULL},
    {"tess_inner", I, NULL, 1, 64, "auto", 0,
     "inner tessellation level with lod=uniform, or 'auto' (= tess_level)", NULL},
    {"tess_outer", I, NULL, 1, 64, "auto", 0,
     "every outer tessellation level with lod=uniform, or 'auto' (= tess_level)", NULL},
    {"tess_spacing", E, axes__spacing, 0, 0, "equal", 0, "tessellation spacing", NULL},
    {"lod", E, axes__lod, 0, 0, "uniform", 0, "how the tessellation level is chosen per patch", NULL},
    {"patch_cull", E, axes__on_off, 0, 0, "off", 0, "cull back-facing/off-screen patches in the control stage", NULL},
    {"crack_free", E, axes__on_off, 0, 0, "off", 0, "per-edge levels from edge midpoints so neighbours agree", NULL},
    {"tess_smooth", E, axes__smooth, 0, 0, "off", 0,
     "smooth base surface of tess-displacement: phong = Phong tessellation (alpha 0.75)", NULL},
    {"height_scale", F, NULL, -1, 1, "0.06", 0, "displacement / parallax depth in world units per height unit", NULL},
    {"parallax_bias", F, NULL, -1, 2, "0.5", 0,
     "plain parallax bias as a fraction of the depth: h' = (h - bias)·scale (0.5 = Kaneko's scale/2)", NULL},
    {"offset_limit", E, axes__on_off, 0, 0, "off", 0, "parallax offset limiting (Welsh): drop the division by V.z", NULL},
    {"steps", I, NULL, 1, 512, "32", 0, "parallax search steps, or 'auto' (min_steps..max_steps by view angle)", NULL},
    {"min_steps", I, NULL, 1, 512, "8", 0, "fewest steps of steps=auto (view along the normal)", NULL},
    {"max_steps", I, NULL, 1, 512, "64", 0, "most steps of steps=auto (grazing view)", NULL},
    {"shadow", E, axes__shadow, 0, 0, "none", 0, "self-shadowing from the height map", NULL},
    {"lighting", E, axes__lighting, 0, 0, "blinn-phong", 0, "lighting model", NULL},
    {"light_count", I, NULL, 1, 8, "1", 0, "number of point lights", NULL},
    {"attenuation", E, axes__atten, 0, 0, "inverse-quadratic", 0,
     "light falloff with distance d: 1/(1 + 0.1d + 0.05d²), s1 = max(0, 1 - d²/r²), or none", NULL},
    {"light_radius", F, NULL, 0.01, 1000, "10", 0,
     "r of attenuation=s1: the distance at which a light's contribution reaches 0", NULL},
    {"roughness", F, NULL, 0.01, 1, "0.35", 0,
     "Cook-Torrance Beckmann roughness m (read with lighting=cook-torrance only)", NULL},
    {"filter", E, axes__filter, 0, 0, "trilinear", 1, "texture filtering of the material maps", NULL},
    {"vertex_filter", E, axes__vfilter, 0, 0, "nearest", 0, "height-map filtering in the vertex stage", NULL},
    {"visibility_test", E, axes__on_off, 0, 0, "off", 0, "skip displacement of vertices outside the widened view volume", NULL},
    {"height_format", E, axes__hfmt, 0, 0, "r32f", 0, "internal format of the height map", NULL},
    {"normal_format", E, axes__nfmt, 0, 0, "rgb8", 0, "internal format of the normal map", NULL},
    {"albedo_format", E, axes__afmt, 0, 0, "rgba8", 1, "internal format of the albedo map", NULL},
    {"texture_size", I, NULL, 16, 65536, "512", 1,
     "texels per side of the material maps (above 16384 only with virtual_texture=software)", NULL},
    {"virtual_texture", E, axes__vt, 0, 0, "off", 1, "virtual texturing of the material maps", NULL},
    {"vt_page_size", I, NULL, 16, 1024, "128", 1, "virtual texture page size in texels", NULL},
    {"vt_cache_pages", I, NULL, 1, 65536, "256", 1, "pages in the physical page cache", NULL},
    {"toksvig", E, axes__on_off, 0, 0, "off", 0, "Toksvig specular anti-aliasing from the filtered normal length", NULL},
    {"specular_map", E, axes__on_off, 0, 0, "off", 0,
     "scale the specular term by the material's specular map (kept in the albedo's alpha), as S3 "
     "scales it by a specular texture", NULL},
    {"displaced_normals", E, axes__dnormals, 0, 0, "map", 0,
     "shading normals of a displacing technique: the normal map, or rebuilt from the height map (S3)", NULL},
    {"camera.distance", F, NULL, 0.1, 100, "3.0", 1, "orbit camera distance from its target (camera.target_*)", NULL},
    {"camera.azimuth", F, NULL, -360, 360, "30", 1, "orbit azimuth in degrees (0 = camera on +Z)", NULL},
    {"camera.elevation", F, NULL, -89.9, 89.9, "20", 1, "orbit elevation in degrees toward +Y", NULL},
    {"camera.fov", F, NULL, 1, 179, "45", 1, "vertical field of view in degrees", NULL},
    {"camera.target_x", F, NULL, -100, 100, "0", 1, "x of the point the camera orbits and looks at", NULL},
    {"camera.target_y", F, NULL, -100, 100, "0", 1, "y of the point the camera orbits and looks at", NULL},
    {"camera.target_z", F, NULL, -100, 100, "0", 1, "z of the point the camera orbits and looks at", NULL},
    {"light.azimuth", F, NULL, -360, 360, "45", 1,
     "degrees added to the camera azimuth for light 0 (light i adds i*45 more)", NULL},
    {"light.elevation", F, NULL, -180, 180, "35", 1,
     "degrees added to the camera elevation (light i: min(cam + this - 10*(i mod 3), 80))", NULL},
    {"light.distance", F, NULL, 0, 100, "1.2", 1,
     "light distance from the camera target as a multiple of camera.distance (0 = at the target)", NULL},
    {"camera.orbit_deg_per_frame", F, NULL, -360, 360, "0", 1,
     "degrees the camera azimuth turns per frame of a sample (0 = still; lights follow it)", NULL},
    {"light.orbit_deg_per_frame", F, NULL, -360, 360, "0", 1,
     "degrees the lights' azimuth turns per frame of a sample on top of the camera's (S2's light circles)", NULL},
    {"camera.path", E, axes__path, 0, 0, "still", 1,
     "the camera's path over camera.path_frames frames: orbit = one circle round the target, dolly = "
     "from camera.distance to camera.dolly_to, flyover = a straight line at camera.flyover_height "
     "(docs/motion.md)", NULL},
    {"camera.path_frames", I, NULL, 2, 100000, "60", 1, "frames of one pass along camera.path", NULL},
    {"camera.dolly_to", F, NULL, 0.1, 100, "1.0", 1, "camera distance at the end of a dolly", NULL},
    {"camera.flyover_height", F, NULL, 0.01, 100, "0.5", 1,
     "height of a flyover's line above the camera target", NULL},
    {"camera.path_ref_every", I, NULL, 0, 100000, "0", 1,
     "quality along the path: a reference every K-th frame of one pass (0 = the first and last "
     "frames only, two references; on a still path 0 = none; docs/motion.md)", NULL},
    {"maps", E, NULL, 0, 0, "bricks", 1,
     "procedural material maps, or user maps: height=PATH;normal=PATH;albedo=PATH", axes__check_maps},
};
#undef E
#undef I
#undef F

#define AXES__N (sizeof axes__table / sizeof axes__table[0])

const axis_info *axes_builtin(size_t *n)
{
    *n = AXES__N;
    return axes__table;
}

/* The built-in row called name, or NULL. */
static const axis_info *axes__builtin_find(const char *name)
{
    for (size_t i = 0; i < AXES__N; i++)
        if (strcmp(axes__table[i].name, name) == 0)
            return &axes__table[i];
    return NULL;
}

/* Parses a whole string as an integer / a finite real. */
static int axes__int(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    while (*end && isspace((unsigned char)*end))
        end++;
    if (errno || end == s || *end)
        return 0;
    *out = v;
    return 1;
}

static int axes__real(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    while (*end && isspace((unsigned char)*end))
        end++;
    if (errno || end == s || *end || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

int axes_parse_size2(const char *s, int *w, int *h)
{
    long a, b;
    char *end;
    while (*s == '[' || isspace((unsigned char)*s))
        s++;
    errno = 0;
    a = strtol(s, &end, 10);
    if (errno || end == s)
        return DM_ERR_ARG;
    s = end;
    while (isspace((unsigned char)*s))
        s++;
    if (*s != 'x' && *s != 'X' && *s != ',')
        return DM_ERR_ARG;
    s++;
    b = strtol(s, &end, 10);
    if (errno || end == s)
        return DM_ERR_ARG;
    while (*end == ']' || isspace((unsigned char)*end))
        end++;
    if (*end || a < 1 || a > 8192 || b < 1 || b > 8192)
        return DM_ERR_ARG;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

/* The mesh row: a built-in mesh, or a user mesh (mesh: "file:PATH")
 * validated at plan time by loading it through Assimp, so a missing or
 * corrupt file stops the run before any work. */
static int axes__check_mesh(const axis_info *a, const char *value, dm_str *err)
{
    if (strncmp(value, USER_MESH_PREFIX, strlen(USER_MESH_PREFIX)) != 0)
        return axes__check_enum(a, value, err);
    const char *path = value + strlen(USER_MESH_PREFIX);
    dm_str why = {0};
    int rc = user_mesh_check(path, &why);
    if (rc)
        dm_str_printf(err, "mesh file '%s' cannot be used: %s", path, dm_str_get(&why));
    dm_str_free(&why);
    return rc ? DM_ERR_ARG : 0;
}

/* The maps row: procedural maps, or user maps (maps.h). */
static int axes__check_maps(const axis_info *a, const char *value, dm_str *err)
{
    if (!maps_is_material(value))
        return axes__check_enum(a, value, err);
    int rc = maps_material_check(value, err);
    return rc == DM_ERR_NOMEM ? rc : rc ? DM_ERR_ARG : 0;
}

/* 1 for the integer axes that also take the word 'auto' (steps: chosen by
 * view angle; tess_inner / tess_outer: = tess_level). */
static int axes__takes_auto(const axis_info *a)
{
    return strcmp(a->name, "steps") == 0 || strcmp(a->name, "tess_inner") == 0 ||
           strcmp(a->name, "tess_outer") == 0;
}

/* Checks an enum value; appends "expected one of: ..." on failure. */
static int axes__check_enum(const axis_info *a, const char *value, dm_str *err)
{
    size_t n = 0;
    for (; a->choices && a->choices[n]; n++)
        if (strcmp(a->choices[n], value) == 0)
            return 0;
    dm_str_printf(err, "invalid value '%s' for %s; ", value, a->name);
    dm_str_expected(err, value, a->choices, n);
    return DM_ERR_ARG;
}

int axes_value_check(const axis_info *a, const char *value, dm_str *err)
{
    return a->check ? a->check(a, value, err) : axes_kind_check(a, value, err);
}

int axes_kind_check(const axis_info *a, const char *value, dm_str *err)
{
    long iv;
    double fv;
    int w, h;
    switch (a->kind) {
    case AXIS_ENUM:
        return axes__check_enum(a, value, err);
    case AXIS_INT:
        if (axes__takes_auto(a) && strcmp(value, "auto") == 0)
            return 0;
        if (axes__int(value, &iv) && iv >= a->min && iv <= a->max)
            return 0;
        dm_str_printf(err, "invalid value '%s' for %s; expected an integer in [%g, %g]%s", value,
                      a->name, a->min, a->max, axes__takes_auto(a) ? " or 'auto'" : "");
        return DM_ERR_ARG;
    case AXIS_FLOAT:
        if (axes__real(value, &fv) && fv >= a->min && fv <= a->max)
            return 0;
        dm_str_printf(err, "invalid value '%s' for %s; expected a number in [%g, %g]", value,
                      a->name, a->min, a->max);
        return DM_ERR_ARG;
    case AXIS_SIZE2:
        if (axes_parse_size2(value, &w, &h) == 0)
            return 0;
        dm_str_printf(err, "invalid value '%s' for %s; expected WxH with each side in [%g, %g]",
                      value, a->name, a->min, a->max);
        return DM_ERR_ARG;
    }
    return DM_ERR_ARG;
}

char *axes_value_canonical(const axis_info *a, const char *value)
{
    long iv;
    double fv;
    int w, h;
    if (a->kind == AXIS_INT && axes__int(value, &iv))
        return dm_xasprintf("%ld", iv);
    if (a->kind == AXIS_FLOAT && axes__real(value, &fv))
        return dm_xasprintf("%.9g", fv);
    if (a->kind == AXIS_SIZE2 && axes_parse_size2(value, &w, &h) == 0)
        return dm_xasprintf("%dx%d", w, h);
    return NULL;
}

/* Axes that matter only when another axis has one value (axes.h). */
static const struct {
    const char *axis, *when_axis, *when_value;
} axes__conditions[] = {
    {"roughness", "lighting", "cook-torrance"},
    {"camera.path_frames", "camera.path", "!still"},
    {"camera.dolly_to", "camera.path", "dolly"},
    {"camera.flyover_height", "camera.path", "flyover"},
    {"light_radius", "attenuation", "s1"},
    {"tess_inner", "lod", "uniform"},
    {"tess_outer", "lod", "uniform"},
};

/* One condition: the configuration's value of when_axis (canonical, so
 * "0.50" is "0.5") is want, or with "!X" is anything but X. */
static int axes__condition_row(const char *when_axis, const char *want,
                               const char *(*value)(const char *axis, void *ctx), void *ctx)
{
    const axis_info *when = axes__builtin_find(when_axis);
    const char *v = value ? value(when->name, ctx) : NULL;
    v = v ? v : when->def;
    dm_str scratch = {0};
    char *cv = axes_value_check(when, v, &scratch) == 0 ? axes_value_canonical(when, v) : NULL;
    dm_str_free(&scratch);
    int neg = want[0] == '!';
    int equal = strcmp(cv ? cv : v, want + neg) == 0;
    free(cv);
    return equal != neg;
}

int axes_conditions_hold(const char *name, const char *(*value)(const char *axis, void *ctx),
                         void *ctx)
{
    for (size_t i = 0; i < sizeof axes__conditions / sizeof axes__conditions[0]; i++)
        if (strcmp(axes__conditions[i].axis, name) == 0 &&
            !axes__condition_row(axes__conditions[i].when_axis, axes__conditions[i].when_value, value, ctx))
            return 0;   /* every row of the axis must hold */
    /* at its default an axis of dm_param_left_out_default's list renders as
     * before it existed and stays out of the configuration, so its key is
     * the one it had then */
    const char *def = dm_param_left_out_default(name);
    if (def) {
        char *want = dm_xasprintf("!%s", def);
        int holds = axes__condition_row(name, want, value, ctx);
        free(want);
        if (!holds)
            return 0;
    }
    return 1;
}

/* Axis values that need a driver extension, and those dmbench refuses even
 * where the extension exists because it does not implement them (axes.h). */
static const struct {
    const char *axis, *value, *ext, *unimplemented;
} axes__needs[] = {
    {"virtual_texture", "sparse", "GL_ARB_sparse_texture", NULL},
};

const char *axes_value_ext_at(size_t i)
{
    return i < sizeof axes__needs / sizeof axes__needs[0] ? axes__needs[i].ext : NULL;
}

char *axes_value_refusal(const char *axis, const char *value,
                         int (*has_ext)(const char *ext, void *user), void *user)
{
    for (size_t i = 0; i < sizeof axes__needs / sizeof axes__needs[0]; i++) {
        if (strcmp(axes__needs[i].axis, axis) != 0 || strcmp(axes__needs[i].value, value) != 0)
            continue;
        if (!has_ext(axes__needs[i].ext, user))
            return dm_xasprintf("the driver lacks %s, which %s=%s needs", axes__needs[i].ext, axis,
                                value);
        if (axes__needs[i].unimplemented)
            return dm_xasprintf("%s=%s: %s", axis, value, axes__needs[i].unimplemented);
    }
    return NULL;
}
