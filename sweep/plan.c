/* plan.c — cartesian product, projection, dedupe and keys (see plan.h). */
#include "plan.h"
#include "core/dm_error.h"
#include "techniques/axes.h"
#include "techniques/mesh.h"
#include "techniques/technique.h"

#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Axes that make up a scene: configurations of one scene share a reference
 * image and are measured in the same rounds. */
static const char *const plan__scene_axes[] = {
    "mesh", "resolution", "camera.distance", "camera.azimuth", "camera.elevation",
    "camera.fov", "camera.target_x", "camera.target_y", "camera.target_z", "maps", "lighting",
    "light_count", "light.azimuth", "light.elevation", "light.distance", "roughness",
    "height_scale", "camera.orbit_deg_per_frame", "light.orbit_deg_per_frame" };

static int plan__kv_cmp(const void *a, const void *b)
{
    return strcmp(((const dm_kv *)a)->key, ((const dm_kv *)b)->key);
}

/* Value of an axis in a combination: the sweep axis, else the scene
 * default, else the catalog default. */
static const char *plan__value(const sweep *s, const size_t *idx, const char *axis)
{
    for (size_t i = 0; i < s->n_axes; i++)
        if (strcmp(s->axes[i].name, axis) == 0)
            return s->axes[i].values[idx[i]];
    const char *v = dm_kv_get(s->scene, s->n_scene, axis);
    if (v)
        return v;
    const axis_info *a = axes_find(axis);
    return a ? a->def : NULL;
}

static void plan__key(plan_config *c, const technique_desc *t)
{
    uint64_t h = DM_FNV_SEED;
    char ver[32];
    snprintf(ver, sizeof ver, "v%d;", t->version);
    h = dm_fnv1a64(ver, strlen(ver), h);
    if (t->source_hash)   /* a user technique: its file's text (user_technique.h) */
        h = dm_fnv1a64(&t->source_hash, sizeof t->source_hash, h);
    for (size_t i = 0; i < c->n_params; i++) {
        h = dm_fnv1a64(c->params[i].key, strlen(c->params[i].key) + 1, h);
        h = dm_fnv1a64(c->params[i].value, strlen(c->params[i].value) + 1, h);
    }
    dm_hex64(h, c->key);
}

static char *plan__scene_id(const plan_config *c)
{
    dm_str s = {0};
    dm_str_printf(&s, "%s@%s", dm_kv_get(c->scene_params, c->n_scene_params, "mesh"),
                  dm_kv_get(c->scene_params, c->n_scene_params, "resolution"));
    for (size_t i = 2; i < sizeof plan__scene_axes / sizeof *plan__scene_axes; i++) {
        const char *v = dm_kv_get(c->scene_params, c->n_scene_params, plan__scene_axes[i]);
        const axis_info *a = axes_find(plan__scene_axes[i]);
        char *def = a ? axes_canonical(a->name, a->def) : NULL;
        if (v && def && strcmp(v, def) != 0)
            dm_str_printf(&s, ",%s=%s", plan__scene_axes[i], v);
        free(def);
    }
    return dm_str_take(&s);
}

/* A combination, for axes_condition_holds' value callback. */
typedef struct plan__combo {
    const sweep *s;
    const size_t *idx;
} plan__combo;

static const char *plan__combo_value(const char *axis, void *ctx)
{
    const plan__combo *c = ctx;
    return plan__value(c->s, c->idx, axis);
}

/* Projects one combination onto its technique's axes: those it reads whose
 * condition holds (roughness only under cook-torrance). */
static void plan__project(const sweep *s, const size_t *idx, plan_config *c)
{
    const technique_desc *t = technique_find(plan__value(s, idx, "technique"));
    plan__combo combo = {s, idx};
    memset(c, 0, sizeof *c);
    for (size_t i = 0; i < axes_count(); i++) {
        const axis_info *a = axes_at(i);
        if (strcmp(a->name, "technique") != 0 &&
            (!technique_reads_axis(t, a->name) || !axes_condition_holds(a->name, plan__combo_value, &combo)))
            continue;
        /* canonical text, so "3.0" and "3" are one configuration with one key */
        char *v = axes_canonical(a->name, plan__value(s, idx, a->name));
        dm_kv_push(&c->params, &c->n_params, a->name, v);
        free(v);
    }
    qsort(c->params, c->n_params, sizeof *c->params, plan__kv_cmp);
    for (size_t i = 0; i < sizeof plan__scene_axes / sizeof *plan__scene_axes; i++) {
        char *v = axes_canonical(plan__scene_axes[i], plan__value(s, idx, plan__scene_axes[i]));
        dm_kv_push(&c->scene_params, &c->n_scene_params, plan__scene_axes[i], v);
        free(v);
    }
    plan__key(c, t);
    c->scene = plan__scene_id(c);
    c->folded = 1;
    sscanf(dm_kv_get(c->params, c->n_params, "resolution"), "%dx%d", &c->width, &c->height);
}

static void plan__config_free(plan_config *c)
{
    free(c->scene);
    dm_kv_free(c->scene_params, c->n_scene_params);
    dm_kv_free(c->params, c->n_params);
}

/* Open-addressing index of the planned configurations by key, so adding
 * one is O(1) and planning 1e6 combinations stays linear. */
typedef struct plan__index {
    size_t *slot;            /* configuration index + 1; 0 = empty */
    size_t cap;              /* a power of two, kept > 2 * n_configs */
} plan__index;

static size_t *plan__slot(plan__index *ix, const plan *p, const char *key)
{
    size_t i = (size_t)strtoull(key, NULL, 16) & (ix->cap - 1);
    while (ix->slot[i] && strcmp(p->configs[ix->slot[i] - 1].key, key) != 0)
        i = (i + 1) & (ix->cap - 1);
    return &ix->slot[i];
}

static void plan__index_grow(plan__index *ix, const plan *p)
{
    free(ix->slot);
    ix->cap = ix->cap ? ix->cap * 2 : 1024;
    ix->slot = dm_xcalloc(ix->cap, sizeof *ix->slot);
    for (size_t i = 0; i < p->n_configs; i++)
        *plan__slot(ix, p, p->configs[i].key) = i + 1;
}

/* Adds c unless a configuration with the same key exists (then folds it). */
static void plan__add(plan *p, plan__index *ix, size_t *cap, plan_config *c)
{
    size_t *slot = plan__slot(ix, p, c->key);
    if (*slot) {
        p->configs[*slot - 1].folded++;
        plan__config_free(c);
        return;
    }
    if (p->n_configs == *cap) {
        *cap = *cap ? *cap * 2 : 64;
        p->configs = dm_xrealloc(p->configs, *cap * sizeof *p->configs);
    }
    p->configs[p->n_configs++] = *c;
    *slot = p->n_configs;
    if (p->n_configs * 2 >= ix->cap)
        plan__index_grow(ix, p);
}

/* 1 when the combination idx matches an `exclude` entry: for every axis of
 * the entry, the combination's value is one of the entry's values. */
static int plan__excluded(const sweep *s, const size_t *idx)
{
    for (size_t e = 0; e < s->n_excludes; e++) {
        int all = 1;
        for (size_t j = 0; all && j < s->excludes[e].n_axes; j++) {
            const sweep_axis *ea = &s->excludes[e].axes[j];
            const char *v = plan__value(s, idx, ea->name);
            int any = 0;
            for (size_t k = 0; v && k < ea->n_values; k++)
                any |= strcmp(v, ea->values[k]) == 0;
            all = any;
        }
        if (all)
            return 1;
    }
    return 0;
}

/* "path:line: " for the axis: its line in the sweep block, else in scene:;
 * "path: " when the catalog's default was used. */
static void plan__where(const sweep *s, const char *axis, dm_str *err)
{
    for (size_t i = 0; i < s->n_axes; i++)
        if (strcmp(s->axes[i].name, axis) == 0) {
            dm_str_printf(err, "%s:%d: ", s->path, s->axes[i].line);
            return;
        }
    for (size_t i = 0; i < s->n_scene; i++)
        if (strcmp(s->scene[i].key, axis) == 0 && s->scene_lines && s->scene_lines[i] > 0) {
            dm_str_printf(err, "%s:%d: ", s->path, s->scene_lines[i]);
            return;
        }
    dm_str_printf(err, "%s: ", s->path);
}

/* 0 when the combination's mesh_density is one its mesh accepts (0, the
 * mesh's default, or its range; a user mesh file ignores it), else
 * DM_ERR_RANGE with "path:line: ..." naming the valid densities in err.
 * The axis is read per combination, so an `exclude` can drop the pair. */
static int plan__check_density(const sweep *s, const size_t *idx, dm_str *err)
{
    const char *mesh = plan__value(s, idx, "mesh"), *dens = plan__value(s, idx, "mesh_density");
    int def, lo, hi, d = dens ? atoi(dens) : 0;
    if (d == 0 || !mesh || mesh_density_range(mesh, &def, &lo, &hi) != 0 || (d >= lo && d <= hi))
        return 0;
    int line = 0, mesh_axis = 0;
    for (size_t i = 0; i < s->n_axes; i++) {
        if (strcmp(s->axes[i].name, "mesh_density") == 0)
            line = s->axes[i].line;
        mesh_axis |= strcmp(s->axes[i].name, "mesh") == 0;
    }
    plan__where(s, "mesh_density", err);
    dm_str_printf(err, "mesh_density %d is out of range for mesh '%s': ", d, mesh);
    if (lo > hi)
        dm_str_printf(err, "it takes only 0 (the scene is fixed)");
    else
        dm_str_printf(err, "valid are %d..%d, and 0 for its default (%d)", lo > 1 ? lo : 1, hi, def);
    if (line > 0 && mesh_axis)
        dm_str_printf(err, "; give each mesh its own sweep file or drop the pair with "
                      "`exclude: [{mesh: [%s], mesh_density: [%d]}]`", mesh, d);
    return DM_ERR_RANGE;
}

/* Meshes a flyover can fly over: a ground along y = 0 (docs/motion.md). */
static int plan__is_ground(const char *mesh)
{
    static const char *const grounds[] = {"plane", "terrain", "terrain-tiles", "halfflat", "s2-scene1"};
    if (strncmp(mesh, "file:", 5) == 0)   /* a user's mesh: dmbench cannot tell, so it trusts it */
        return 1;
    for (size_t i = 0; i < sizeof grounds / sizeof grounds[0]; i++)
        if (strcmp(mesh, grounds[i]) == 0)
            return 1;
    return 0;
}

/* 0 when the combination's camera path can be drawn and compared: a dolly
 * that moves, a flyover over a ground, reference frames within the path;
 * else DM_ERR_RANGE with "path:line: ..." naming what is accepted. */
static int plan__check_path(const sweep *s, const size_t *idx, dm_str *err)
{
    const char *path = plan__value(s, idx, "camera.path");
    long frames = atol(plan__value(s, idx, "camera.path_frames"));
    long every = atol(plan__value(s, idx, "camera.path_ref_every"));
    if (every > frames - 1) {   /* on a still path too: its frames move with the orbits */
        plan__where(s, "camera.path_ref_every", err);
        dm_str_printf(err, "camera.path_ref_every %ld is past the path's last frame (camera.path_frames "
                      "%ld: frames 0..%ld); valid are 0 (the first and last frames) and 1..%ld",
                      every, frames, frames - 1, frames - 1);
        return DM_ERR_RANGE;
    }
    if (!path || strcmp(path, "still") == 0)
        return 0;
    const char *mesh = plan__value(s, idx, "mesh");
    if (strcmp(path, "flyover") == 0 && mesh && !plan__is_ground(mesh)) {
        int mesh_varies = 0;   /* name the key the sweep block varies: that is where to exclude */
        for (size_t i = 0; i < s->n_axes; i++)
            mesh_varies |= strcmp(s->axes[i].name, "mesh") == 0;
        plan__where(s, mesh_varies ? "mesh" : "camera.path", err);
        dm_str_printf(err, "camera.path flyover flies at a height over a ground, and mesh '%s' is "
                      "not one; a flyover takes plane, terrain, terrain-tiles, halfflat, s2-scene1 or a "
                      "file: mesh (orbit or dolly go round any mesh)", mesh);
        return DM_ERR_RANGE;
    }
    if (strcmp(path, "dolly") == 0) {
        double from = atof(plan__value(s, idx, "camera.distance"));
        double to = atof(plan__value(s, idx, "camera.dolly_to"));
        if (fabs(to - from) <= 1e-6 * fmax(fabs(from), 1.0)) {
            plan__where(s, "camera.dolly_to", err);
            dm_str_printf(err, "camera.dolly_to %g equals camera.distance %g: the dolly would not move; "
                          "give another end distance (0.1..100), or camera.path still", to, from);
            return DM_ERR_RANGE;
        }
    }
    return 0;
}

int plan_build(const sweep *s, const plan_build_desc *d, plan *out, dm_str *err)
{
    static const plan_build_desc defaults = {0};
    d = d ? d : &defaults;
    plan_progress_fn progress = d->progress;
    void *user = d->user;
    memset(out, 0, sizeof *out);
    size_t total = 1;
    for (size_t i = 0; i < s->n_axes; i++) {
        total *= s->axes[i].n_values;
        if (total > 1000000) {
            dm_str_printf(err, "%s: the sweep's cartesian product exceeds 1e6 combinations; "
                          "split it into several sweep files", s->path);
            return DM_ERR_RANGE;
        }
    }
    size_t *idx = dm_xcalloc(s->n_axes + 1, sizeof *idx);
    plan__index ix = {0};
    size_t cap = 0;
    plan__index_grow(&ix, out);
    for (size_t n = 0; n < total; n++) {
        plan_config c;
        if (progress && n % 4096 == 0)
            progress(n, total, user);
        if (plan__excluded(s, idx)) {
            out->n_excluded++;
        } else if (plan__check_density(s, idx, err) != 0 || plan__check_path(s, idx, err) != 0) {
            free(idx);
            free(ix.slot);
            plan_free(out);
            return DM_ERR_RANGE;
        } else {
            plan__project(s, idx, &c);
            plan__add(out, &ix, &cap, &c);
        }
        for (size_t i = 0; i < s->n_axes; i++) {      /* odometer over the axes */
            if (++idx[i] < s->axes[i].n_values)
                break;
            idx[i] = 0;
        }
    }
    free(idx);
    free(ix.slot);
    if (progress)
        progress(total, total, user);
    out->n_combinations = total;
    return 0;
}

/* Moves configuration i to left_out without closing the gap (the caller
 * compacts the array once, so leaving out many stays linear). */
static void plan__leave_out_at(plan *p, size_t i, const char *reason)
{
    plan_config *c = &p->configs[i];
    dm_left_out *l = dm_vec_push(&p->left_out, &p->n_left_out, NULL, sizeof *l);
    l->params = c->params;
    l->n_params = c->n_params;
    l->reason = dm_xstrdup(reason);
    free(c->scene);
    dm_kv_free(c->scene_params, c->n_scene_params);
}

void plan_leave_out(plan *p, size_t i, const char *reason)
{
    plan__leave_out_at(p, i, reason);
    memmove(&p->configs[i], &p->configs[i + 1], (p->n_configs - i - 1) * sizeof *p->configs);
    p->n_configs--;
}

void plan_filter_capabilities(plan *p, int (*has_ext)(const char *ext, void *user), void *user)
{
    size_t kept = 0;
    for (size_t i = 0; i < p->n_configs; i++) {
        const char *tname = dm_kv_get(p->configs[i].params, p->configs[i].n_params, "technique");
        const technique_desc *t = technique_find(tname);
        char *why = t && t->requires_ext && !has_ext(t->requires_ext, user)
            ? dm_xasprintf("the driver lacks %s, which %s needs", t->requires_ext, tname) : NULL;
        for (size_t k = 0; !why && k < p->configs[i].n_params; k++)
            why = axes_value_refusal(p->configs[i].params[k].key, p->configs[i].params[k].value,
                                     has_ext, user);
        if (why) {
            plan__leave_out_at(p, i, why);
            free(why);
            continue;
        }
        p->configs[kept++] = p->configs[i];
    }
    p->n_configs = kept;
}

int plan_shard(plan *p, int k, int n)
{
    if (n < 1 || k < 1 || k > n)
        return DM_ERR_ARG;
    size_t kept = 0;
    for (size_t i = 0; i < p->n_configs; i++) {
        uint64_t h = strtoull(p->configs[i].key, NULL, 16);
        if ((int)(h % (uint64_t)n) == k - 1)
            p->configs[kept++] = p->configs[i];
        else
            plan__config_free(&p->configs[i]);
    }
    p->n_configs = kept;
    return 0;
}

static uint64_t plan__splitmix(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

void plan_shuffle(size_t *order, size_t n, uint64_t seed)
{
    for (size_t i = 0; i < n; i++)
        order[i] = i;
    for (size_t i = n; i > 1; i--) {
        size_t j = (size_t)(plan__splitmix(&seed) % i);
        size_t t = order[i - 1];
        order[i - 1] = order[j];
        order[j] = t;
    }
}

void plan_free(plan *p)
{
    for (size_t i = 0; i < p->n_configs; i++)
        plan__config_free(&p->configs[i]);
    free(p->configs);
    for (size_t i = 0; i < p->n_left_out; i++) {
        dm_kv_free(p->left_out[i].params, p->left_out[i].n_params);
        free(p->left_out[i].reason);
    }
    free(p->left_out);
    memset(p, 0, sizeof *p);
}
