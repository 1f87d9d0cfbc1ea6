/* info.c — what the driver offers and whether its timer can be trusted. */
#include "info.h"
#include "core/dm_exit.h"
#include "core/dm_error.h"
#include "counters/counters.h"
#include "run/env.h"
#include "run/gl_context.h"

#include <cjson/cJSON.h>
#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>

/* The extensions that matter to dmbench (docs/llvmpipe-findings.md). */
static const char *const info__exts[] = {
    "GL_ARB_tessellation_shader", "GL_ARB_pipeline_statistics_query", "GL_ARB_timer_query",
    "GL_ARB_query_buffer_object", "GL_ARB_get_program_binary", "GL_KHR_debug",
    "GL_ARB_texture_filter_anisotropic", "GL_EXT_texture_compression_s3tc",
    "GL_ARB_texture_compression_rgtc", "GL_ARB_texture_compression_bptc",
    "GL_KHR_texture_compression_astc_ldr", "GL_ARB_compute_shader", "GL_ARB_shader_clock",
    "GL_ARB_sparse_texture", "GL_AMD_performance_monitor", "GL_INTEL_performance_query",
    "GL_ARB_bindless_texture" };

static const struct { const char *name; GLenum pname; } info__limits[] = {
    { "max_tess_gen_level", GL_MAX_TESS_GEN_LEVEL },
    { "max_patch_vertices", GL_MAX_PATCH_VERTICES },
    { "max_texture_size", GL_MAX_TEXTURE_SIZE },
    { "max_texture_max_anisotropy", GL_MAX_TEXTURE_MAX_ANISOTROPY },
    { "max_vertex_texture_image_units", GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS },
    { "max_tess_evaluation_texture_image_units", GL_MAX_TESS_EVALUATION_TEXTURE_IMAGE_UNITS },
    { "max_renderbuffer_size", GL_MAX_RENDERBUFFER_SIZE },
    { "max_samples", GL_MAX_SAMPLES } };

static cJSON *info__collect(const counters_timer_calibration *cal)
{
    cJSON *root = cJSON_CreateObject();
    dm_kv *kv = NULL;
    size_t n = 0;
    env_collect(&kv, &n, 1);
    env_fingerprint(&kv, &n);
    cJSON *env = cJSON_AddObjectToObject(root, "environment");
    for (size_t i = 0; i < n; i++)
        cJSON_AddStringToObject(env, kv[i].key, kv[i].value);
    dm_kv_free(kv, n);
    cJSON *ext = cJSON_AddObjectToObject(root, "extensions");
    for (size_t i = 0; i < sizeof info__exts / sizeof *info__exts; i++)
        cJSON_AddBoolToObject(ext, info__exts[i], epoxy_has_gl_extension(info__exts[i]));
    cJSON *lim = cJSON_AddObjectToObject(root, "limits");
    for (size_t i = 0; i < sizeof info__limits / sizeof *info__limits; i++) {
        GLfloat v = 0;
        glGetFloatv(info__limits[i].pname, &v);
        cJSON_AddNumberToObject(lim, info__limits[i].name, v);
    }
    cJSON *t = cJSON_AddObjectToObject(root, "timer");
    cJSON_AddNumberToObject(t, "gpu_time_coverage", cal->coverage);
    cJSON_AddNumberToObject(t, "gpu_ns", cal->gpu_ns);
    cJSON_AddNumberToObject(t, "wall_ns", cal->wall_ns);
    cJSON_AddStringToObject(t, "verdict", cal->verdict);
    return root;
}

static void info__print_text(const cJSON *root)
{
    const cJSON *env = cJSON_GetObjectItem(root, "environment"), *it;
    printf("Environment\n");
    cJSON_ArrayForEach(it, env) printf("  %-22s %s\n", it->string, it->valuestring);
    printf("Extensions\n");
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(root, "extensions"))
        printf("  %-38s %s\n", it->string, cJSON_IsTrue(it) ? "yes" : "no");
    printf("Limits\n");
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(root, "limits"))
        printf("  %-42s %g\n", it->string, it->valuedouble);
    const cJSON *t = cJSON_GetObjectItem(root, "timer");
    double cov = cJSON_GetObjectItem(t, "gpu_time_coverage")->valuedouble;
    const char *verdict = cJSON_GetObjectItem(t, "verdict")->valuestring;
    printf("Timer calibration (GL_TIME_ELAPSED vs glFinish-fenced wall time on a heavy draw)\n");
    printf("  gpu %.3f ms, wall %.3f ms, coverage %.4f -> %s\n",
           cJSON_GetObjectItem(t, "gpu_ns")->valuedouble / 1e6,
           cJSON_GetObjectItem(t, "wall_ns")->valuedouble / 1e6, cov, verdict);
    if (verdict[0] == 'p')
        printf("  GPUTime is recorded but marked partial: it is never used to fit or gate.\n");
}

int info_main(int json)
{
    gl_context *gl = NULL;
    dm_str err = {0};
    int rc = env_check(&err);
    rc = rc ? rc : gl_context_create(NULL, &gl, &err);
    if (rc != 0) {   /* bad LP_NUM_THREADS: 2; no usable GL: 4, as for run */
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        dm_str_free(&err);
        return dm_exit_from_error(rc);
    }
    counters_context *cc = NULL;
    counters_timer_calibration cal = { .verdict = "unavailable" };
    if (counters_context_create(&cc) == 0)
        counters_calibrate_timer(cc, &cal);
    cJSON *root = info__collect(&cal);
    if (json) {
        char *s = cJSON_Print(root);
        puts(s);
        free(s);
    } else {
        info__print_text(root);
    }
    cJSON_Delete(root);
    counters_context_destroy(cc);
    gl_context_destroy(gl);
    return DM_EXIT_OK;
}
