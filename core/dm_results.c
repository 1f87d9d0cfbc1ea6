#include "dm_results.h"
#include "dm_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int dm_result_column_reserved(const char *name)
{
    static const char *const cols[] = {DM_RESULT_LEAD_COLUMNS, DM_RESULT_TRAIL_COLUMNS,
                                        DM_RESULT_PATH_COLUMNS};
    for (size_t i = 0; name && i < sizeof cols / sizeof cols[0]; i++)
        if (strcmp(cols[i], name) == 0)
            return 1;
    return 0;
}

const char *dm_kv_get(const dm_kv *kv, size_t n, const char *key)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(kv[i].key, key) == 0)
            return kv[i].value;
    return NULL;
}

/* name, default (dm_results.h); each default equals the axis row's in
 * techniques/axes.c, which test_techniques_axes checks. */
static const char *const dm_results__left_out[][2] = {
    {"camera.orbit_deg_per_frame", "0"}, {"light.orbit_deg_per_frame", "0"},
    {"camera.path", "still"},            {"camera.path_ref_every", "0"},
    {"specular_map", "off"},             {"displaced_normals", "map"},
    {"tess_inner", "auto"},              {"tess_outer", "auto"},
    {"cull", "back"},                    {"attenuation", "inverse-quadratic"},
    {"parallax_bias", "0.5"},
};

const char *dm_param_left_out_default(const char *name)
{
    for (size_t i = 0; i < sizeof dm_results__left_out / sizeof dm_results__left_out[0]; i++)
        if (strcmp(dm_results__left_out[i][0], name) == 0)
            return dm_results__left_out[i][1];
    return NULL;
}

const char *dm_param_value(const dm_kv *params, size_t n, const char *name)
{
    const char *v = dm_kv_get(params, n, name);
    return v ? v : dm_param_left_out_default(name);
}

const dm_counter_result *dm_config_counter(const dm_config_result *c, const char *name)
{
    for (size_t i = 0; i < c->n_counters; i++)
        if (strcmp(c->counters[i].name, name) == 0)
            return &c->counters[i];
    return NULL;
}

const dm_fit_param *dm_fit_param_find(const dm_fit_result *f, const char *name)
{
    for (size_t i = 0; i < f->n_params; i++)
        if (strcmp(f->params[i].name, name) == 0)
            return &f->params[i];
    return NULL;
}

const dm_config_result *dm_run_config(const dm_run_result *run, const char *key)
{
    for (size_t i = 0; key && i < run->n_configs; i++)
        if (run->configs[i].key && strcmp(run->configs[i].key, key) == 0)
            return &run->configs[i];
    return NULL;
}

int dm_counter_read_check(dm_counter_result *c, const char *source)
{
    double v = c->has_samples ? c->median : c->value;
    if (!c->available || isfinite(v))
        return 0;
    char what[32];
    if (isnan(v))
        snprintf(what, sizeof what, "missing or NaN");
    else
        snprintf(what, sizeof what, "%s", v > 0 ? "+inf" : "-inf");
    free(c->unavailable_reason);
    c->unavailable_reason = dm_xasprintf("the %s read back from %s is %s, not a measured number",
                                         c->has_samples ? "median" : "value", source, what);
    c->available = 0;
    c->unreadable = 1;
    return 1;
}

int dm_run_has_counter(const dm_run_result *run, const char *name)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const dm_counter_result *r = run->configs[i].ok ? dm_config_counter(&run->configs[i], name) : NULL;
        if (r && r->available)
            return 1;
    }
    return 0;
}

int dm_run_param_varies(const dm_run_result *run, const dm_kv *k)
{
    for (size_t i = 0; i < run->n_configs; i++) {
        const char *v = dm_kv_get(run->configs[i].params, run->configs[i].n_params, k->key);
        if (!v || !k->value || strcmp(v, k->value) != 0)
            return 1;
    }
    return 0;
}

void dm_kv_push(dm_kv **kv, size_t *n, const char *key, const char *value)
{
    *kv = dm_xrealloc(*kv, (*n + 1) * sizeof **kv);
    (*kv)[*n].key = dm_xstrdup(key);
    (*kv)[*n].value = dm_xstrdup(value ? value : "");
    (*n)++;
}

void dm_kv_free(dm_kv *kv, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        free(kv[i].key);
        free(kv[i].value);
    }
    free(kv);
}

void dm_counter_result_free(dm_counter_result *c)
{
    free(c->name);
    free(c->unit);
    free(c->unavailable_reason);
    free(c->samples);
    memset(c, 0, sizeof *c);
}

void dm_config_result_free(dm_config_result *c)
{
    free(c->key);
    free(c->scene);
    dm_kv_free(c->params, c->n_params);
    free(c->reason);
    free(c->log);
    for (size_t i = 0; i < c->n_counters; i++)
        dm_counter_result_free(&c->counters[i]);
    free(c->counters);
    free(c->quality.reference);
    free(c->img_render);
    free(c->img_heatmap);
    free(c->img_reference);
    free(c->img_flip);
    free(c->path.frame_ns);
    free(c->path.stutter_at);
    free(c->path_quality.flip);
    free(c->path_quality.ssim);
    free(c->path_quality.img_temporal);
    free(c->path_quality.reason);
    for (size_t i = 0; i < c->path_quality.n_shots; i++) {
        free(c->path_quality.shots[i].img_test);
        free(c->path_quality.shots[i].img_ref);
        free(c->path_quality.shots[i].img_flip);
    }
    free(c->path_quality.shots);
    memset(c, 0, sizeof *c);
}

static void dm__strv_free(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

void dm_fit_result_free(dm_fit_result *f)
{
    free(f->model);
    free(f->formula);
    free(f->response);
    dm_kv_free(f->group, f->n_group);
    for (size_t i = 0; i < f->n_params; i++)
        free(f->params[i].name);
    free(f->params);
    free(f->termination);
    dm__strv_free(f->warnings, f->n_warnings);
    free(f->measured);
    free(f->predicted);
    free(f->cv_predicted);
    if (f->point_labels)
        dm__strv_free(f->point_labels, (size_t)f->n_points);
    memset(f, 0, sizeof *f);
}

static int dm__cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

size_t dm_run_noise_floor(const dm_run_result *run, double *floor, double *resolvable)
{
    double *v = calloc(run->n_configs + 1, sizeof *v);
    size_t m = 0;
    for (size_t i = 0; v && i < run->n_configs; i++) {
        const dm_counter_result *w = run->configs[i].ok ? dm_config_counter(&run->configs[i], "WallTime") : NULL;
        if (!w || !w->available)
            continue;
        double med = w->corrected ? w->corr_median : w->median;
        double hw = w->corrected ? (w->corr_ci_hi - w->corr_ci_lo) / 2 : (w->ci_hi - w->ci_lo) / 2;
        if (isfinite(hw) && med > 0)
            v[m++] = hw / med;
    }
    *floor = *resolvable = NAN;
    if (m) {
        qsort(v, m, sizeof *v, dm__cmp_double);
        *floor = m % 2 ? v[m / 2] : (v[m / 2 - 1] + v[m / 2]) / 2;
        *resolvable = sqrt(2.0) * *floor;
    }
    free(v);
    return m;
}

void dm_run_free(dm_run_result *run)
{
    free(run->id);
    free(run->sweep);
    free(run->started);
    free(run->finished);
    free(run->sweep_hash);
    dm_kv_free(run->environment, run->n_environment);
    free(run->timer_verdict);
    for (size_t i = 0; i < run->n_configs; i++)
        dm_config_result_free(&run->configs[i]);
    free(run->configs);
    for (size_t i = 0; i < run->n_left_out; i++) {
        dm_kv_free(run->left_out[i].params, run->left_out[i].n_params);
        free(run->left_out[i].reason);
    }
    free(run->left_out);
    for (size_t i = 0; i < run->n_fits; i++)
        dm_fit_result_free(&run->fits[i]);
    free(run->fits);
    dm__strv_free(run->warnings, run->n_warnings);
    for (size_t i = 0; i < run->n_rounds; i++) {
        free(run->rounds[i].scene);
        free(run->rounds[i].keys);
    }
    free(run->rounds);
    for (size_t i = 0; i < run->n_precision; i++) {
        free(run->precision[i].scene);
        free(run->precision[i].reason);
        free(run->precision[i].predictor);
    }
    free(run->precision);
    memset(run, 0, sizeof *run);
}
