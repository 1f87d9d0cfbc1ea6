/* test_reports_fixture.h — a synthetic run for the report tests and the
 * browser test generator: 2 ok configurations (one with refused image
 * paths), 1 failed with a shader log holding markup, a hostile sweep name,
 * a left-out configuration, a fit and a warning; and its pieces (a timed or
 * counted counter, a quality record), which test_reports_model.c builds its
 * own run from.  Every function is static and marked unused, so a file may
 * take only the pieces it needs. */
#ifndef TEST_REPORTS_FIXTURE_H
#define TEST_REPORTS_FIXTURE_H

#include "core/dm_results.h"
#include "core/dm_util.h"
#include "imaging/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FIXTURE_KEY0 "0123456789abcdef"
#define FIXTURE_KEY1 "fedcba9876543210"
#define FIXTURE_KEY2 "00000000deadbeef"
#define FIXTURE_SCENE "plane/cam0/sun/stone/64x64"
#define FIXTURE_LOG "0:12(3): error: <b>bold</b> syntax error"
#define FIXTURE_REASON "shader link failed"
#define FIXTURE_LEFT_REASON "needs GL_ARB_bindless_texture"

__attribute__((unused)) static const char *fixture_img_files[] = {
    "img/c0_ref.png", "img/c0_render.png", "img/c0_heat.png",
    "img/c1_render.png"};

__attribute__((unused)) static void fixture_timed(dm_counter_result *c, const char *name, double lo, double med, double hi)
{
    memset(c, 0, sizeof *c);
    c->name = dm_xstrdup(name);
    c->unit = dm_xstrdup("ns");
    c->available = c->has_samples = 1;
    c->n_samples = 3;
    c->samples = dm_xcalloc(3, sizeof(double));
    c->samples[0] = lo;
    c->samples[1] = med;
    c->samples[2] = hi;
    c->value = c->median = c->mean = med;
    c->min = c->ci_lo = lo;
    c->max = c->ci_hi = hi;
    c->stddev = (hi - lo) / 2;
    c->mad = (hi - med);
    c->cv = c->stddev / med;
}

__attribute__((unused)) static void fixture_det(dm_counter_result *c, const char *name, double v)
{
    memset(c, 0, sizeof *c);
    c->name = dm_xstrdup(name);
    c->unit = dm_xstrdup("items");
    c->available = c->deterministic = 1;
    c->value = v;
}

__attribute__((unused)) static void fixture_unavailable(dm_counter_result *c, const char *name)
{
    memset(c, 0, sizeof *c);
    c->name = dm_xstrdup(name);
    c->unit = dm_xstrdup("ns");
    c->unavailable_reason = dm_xstrdup("no timer query");
}

__attribute__((unused)) static void fixture_quality(dm_quality *q, double psnr, double ssim, double rmse)
{
    q->present = 1;
    q->psnr = psnr;
    q->ssim = ssim;
    q->rmse = rmse;
    q->max_error = rmse * 4;
    q->reference = dm_xstrdup("reference-mesh 4x supersampled");
}

/* Names configuration c of the fixture's scene: key, technique and mesh,
 * with room for n_counters counters (ok when it has any). */
__attribute__((unused)) static void fixture_config(dm_config_result *c, const char *key, const char *technique,
                           const char *mesh, size_t n_counters)
{
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup(FIXTURE_SCENE);
    dm_kv_push(&c->params, &c->n_params, "technique", technique);
    dm_kv_push(&c->params, &c->n_params, "mesh", mesh);
    c->ok = n_counters > 0;
    c->n_counters = n_counters;
    c->counters = n_counters ? dm_xcalloc(n_counters, sizeof *c->counters) : NULL;
}

__attribute__((unused)) static void fixture_configs(dm_run_result *r)
{
    r->n_configs = 3;
    r->configs = dm_xcalloc(3, sizeof *r->configs);
    dm_config_result *c = r->configs;
    fixture_config(&c[0], FIXTURE_KEY0, "pom", "plane", 3);
    dm_kv_push(&c[0].params, &c[0].n_params, "steps", "32");
    dm_kv_push(&c[0].params, &c[0].n_params, "scale", "1e6");
    dm_kv_push(&c[0].params, &c[0].n_params, "note", "a,b \"quoted\"");
    fixture_timed(&c[0].counters[0], "WallTime", 1.0e6, 1.1e6, 1.2e6);
    fixture_unavailable(&c[0].counters[1], "GPUTime");
    fixture_det(&c[0].counters[2], "TESInvocations", 3169);
    fixture_quality(&c[0].quality, INFINITY, 1.0, 0.0);
    c[0].img_reference = dm_xstrdup(fixture_img_files[0]);
    c[0].img_render = dm_xstrdup(fixture_img_files[1]);
    c[0].img_heatmap = dm_xstrdup(fixture_img_files[2]);

    fixture_config(&c[1], FIXTURE_KEY1, "normal", "plane", 2);
    dm_kv_push(&c[1].params, &c[1].n_params, "tess_level", "4");
    fixture_timed(&c[1].counters[0], "WallTime", 1.95e6, 2.0e6, 2.05e6);
    fixture_det(&c[1].counters[1], "TESInvocations", 100);
    fixture_quality(&c[1].quality, 38.25, 0.95, 0.0122);
    c[1].img_render = dm_xstrdup(fixture_img_files[3]);
    c[1].img_heatmap = dm_xstrdup("/etc/passwd");
    c[1].img_reference = dm_xstrdup("../outside.png");

    fixture_config(&c[2], FIXTURE_KEY2, "pom", "sphere", 0);   /* failed */
    c[2].reason = dm_xstrdup(FIXTURE_REASON);
    c[2].log = dm_xstrdup(FIXTURE_LOG);
}

__attribute__((unused)) static void fixture_fit(dm_run_result *r)
{
    r->n_fits = 1;
    r->fits = dm_xcalloc(1, sizeof *r->fits);
    dm_fit_result *f = r->fits;
    f->model = dm_xstrdup("tess-power");
    f->formula = dm_xstrdup("a + b*tess_level^p");
    f->response = dm_xstrdup("WallTime");
    dm_kv_push(&f->group, &f->n_group, "mesh", "plane");
    f->n_params = 2;
    f->params = dm_xcalloc(2, sizeof *f->params);
    f->params[0].name = dm_xstrdup("a");
    f->params[0].value = 1.0;
    f->params[0].stderr_ = 0.5;
    f->params[1].name = dm_xstrdup("b");
    f->params[1].value = 2.0;
    f->params[1].stderr_ = 0.25;
    f->r2 = 0.99;
    f->cv_mape = 0.04;
    f->n_points = 2;
    f->measured = dm_xcalloc(2, sizeof(double));
    f->predicted = dm_xcalloc(2, sizeof(double));
    f->measured[0] = 1.1e6;
    f->measured[1] = 2.0e6;
    f->predicted[0] = 1.05e6;
    f->predicted[1] = 2.1e6;
    f->point_labels = dm_xcalloc(2, sizeof(char *));
    f->point_labels[0] = dm_xstrdup(FIXTURE_KEY0);
    f->point_labels[1] = dm_xstrdup(FIXTURE_KEY1);
    f->termination = dm_xstrdup("CONVERGENCE");
    f->n_warnings = 1;
    f->warnings = dm_xcalloc(1, sizeof(char *));
    f->warnings[0] = dm_xstrdup("only 2 points for 3 parameters");
}

/* Makes a fit of model on WallTime with two parameters (p0 = v0, p1 = v1)
 * and R² r2 the run's one fit (over no group: every configuration). */
__attribute__((unused)) static void fixture_fit2(dm_run_result *r, const char *model, const char *p0, double v0,
                                                 const char *p1, double v1, double r2)
{
    r->n_fits = 1;
    r->fits = dm_xcalloc(1, sizeof *r->fits);
    dm_fit_result *f = r->fits;
    f->model = dm_xstrdup(model);
    f->response = dm_xstrdup("WallTime");
    f->n_params = 2;
    f->params = dm_xcalloc(2, sizeof *f->params);
    f->params[0].name = dm_xstrdup(p0);
    f->params[0].value = v0;
    f->params[1].name = dm_xstrdup(p1);
    f->params[1].value = v1;
    f->r2 = r2;
}

__attribute__((unused)) static void fixture_run(dm_run_result *r)
{
    memset(r, 0, sizeof *r);
    r->id = dm_xstrdup("20261121T230424Z");
    r->sweep = dm_xstrdup("<script>alert(1)</script>");
    r->started = dm_xstrdup("2026-11-21T23:04:24Z");
    r->sweep_hash = dm_xstrdup("feedfacecafebeef");
    dm_kv_push(&r->environment, &r->n_environment, "renderer", "llvmpipe (LLVM 15.0.6, 256 bits)");
    dm_kv_push(&r->environment, &r->n_environment, "gl_version", "4.5 (Core Profile) Mesa 22.3.6");
    dm_kv_push(&r->environment, &r->n_environment, "lp_num_threads", "1");
    r->gpu_time_coverage = 0.015;
    r->timer_verdict = dm_xstrdup("partial");
    fixture_configs(r);
    r->n_left_out = 1;
    r->left_out = dm_xcalloc(1, sizeof *r->left_out);
    dm_kv_push(&r->left_out[0].params, &r->left_out[0].n_params, "technique", "svt");
    r->left_out[0].reason = dm_xstrdup(FIXTURE_LEFT_REASON);
    fixture_fit(r);
    r->n_warnings = 1;
    r->warnings = dm_xcalloc(1, sizeof(char *));
    r->warnings[0] = dm_xstrdup("load average rose from 0.2 to 1.9 during the run");
}

/* Writes the 4 images the fixture's configs name (16×16 gradients) under dir. */
__attribute__((unused)) static int fixture_images(const char *dir, char *err, size_t errlen)
{
    char *sub = dm_xasprintf("%s/img", dir);
    int rc = dm_mkdirs(sub);
    free(sub);
    img im = {0};
    if (rc || (rc = img_alloc(&im, 16, 16)))
        return rc;
    for (size_t f = 0; f < 4 && !rc; f++) {
        for (int i = 0; i < 16 * 16; i++) {
            im.px[i * 4 + 0] = (float)(i % 16) / 15.0f;
            im.px[i * 4 + 1] = (float)(i / 16) / 15.0f;
            im.px[i * 4 + 2] = (float)f / 3.0f;
            im.px[i * 4 + 3] = 1.0f;
        }
        char *p = dm_xasprintf("%s/%s", dir, fixture_img_files[f]);
        rc = img_save(&im, p, err, errlen);
        free(p);
    }
    img_free(&im);
    return rc;
}

__attribute__((unused)) static void fixture_images_remove(const char *dir)
{
    for (size_t f = 0; f < 4; f++) {
        char *p = dm_xasprintf("%s/%s", dir, fixture_img_files[f]);
        unlink(p);
        free(p);
    }
    char *sub = dm_xasprintf("%s/img", dir);
    rmdir(sub);
    free(sub);
}

#endif
