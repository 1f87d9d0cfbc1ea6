/* plan.h — from a sweep to the configurations worth measuring (docs/sweep-files.md).
 *
 * The planner takes the cartesian product of the sweep's axes, projects each
 * combination onto the axes its technique reads (scene axes + the
 * technique's own list) and keeps one configuration per distinct
 * projection: `normal × tess_level [1,32,64]` is one configuration.  Keys are
 * a hash of the technique's name, version and projected parameters, so the
 * same configuration has the same key on every machine and run.
 */
#ifndef SWEEP_PLAN_H
#define SWEEP_PLAN_H

#include <stddef.h>
#include <stdint.h>
#include "core/dm_results.h"
#include "sweep/sweep.h"

typedef struct plan_config {
    char key[17];
    char *scene;             /* readable scene id: mesh@WxH[,param=value...] */
    dm_kv *params;           /* projected parameters, sorted by axis name */
    size_t n_params;
    dm_kv *scene_params;     /* every scene axis's value (read or not): the reference's scene */
    size_t n_scene_params;
    size_t folded;           /* combinations this configuration stands for */
    int width, height;       /* resolution */
} plan_config;

typedef struct plan {
    plan_config *configs;
    size_t n_configs;
    size_t n_combinations;   /* size of the cartesian product */
    size_t n_excluded;       /* combinations dropped by the sweep's `exclude` entries */
    dm_left_out *left_out;
    size_t n_left_out;
} plan;

/* Called every few thousand combinations and once at the end (done == total). */
typedef void (*plan_progress_fn)(size_t done, size_t total, void *user);
/* How to plan; zero (or a NULL desc) is the default. */
typedef struct plan_build_desc {
    plan_progress_fn progress;   /* NULL: no progress reports */
    void *user;                  /* progress's last argument */
} plan_build_desc;
/* Plans a sweep as d says (NULL: the default).  Returns 0, or DM_ERR_RANGE
 * when the product is larger than 1e6 combinations (err says so).  Linear in
 * the number of combinations (configurations are found by key in a hash
 * index). */
int plan_build(const sweep *s, const plan_build_desc *d, plan *out, dm_str *err);
/* Leaves out configurations whose technique needs an extension the driver
 * lacks (has_ext(name) == 0), and those with an axis value the driver or
 * dmbench cannot measure (axes_value_refusal), recording the reason. */
void plan_filter_capabilities(plan *p, int (*has_ext)(const char *ext, void *user), void *user);
/* Keeps the deterministic part K of N (1-based K), by key. 0 or DM_ERR_ARG. */
int plan_shard(plan *p, int k, int n);
/* Moves configuration i to left_out with a reason. */
void plan_leave_out(plan *p, size_t i, const char *reason);
/* Fills order[0..n) with a seeded shuffle of 0..n-1 (Fisher–Yates, splitmix64). */
void plan_shuffle(size_t *order, size_t n, uint64_t seed);
void plan_free(plan *p);

#endif
