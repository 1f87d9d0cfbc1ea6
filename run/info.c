/* info.c — what the driver offers and whether its timer can be trusted. */
#include "info.h"
#include "core/dm_exit.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "counters/counters.h"
#include "run/env.h"
#include "run/gl_context.h"
#include "run/probe.h"

#include <cjson/cJSON.h>
#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

static void info__print_text(const cJSON *root, FILE *f)
{
    const cJSON *env = cJSON_GetObjectItem(root, "environment"), *it;
    fprintf(f, "Environment\n");
    cJSON_ArrayForEach(it, env) fprintf(f, "  %-22s %s\n", it->string, it->valuestring);
    fprintf(f, "Extensions\n");
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(root, "extensions"))
        fprintf(f, "  %-38s %s\n", it->string, cJSON_IsTrue(it) ? "yes" : "no");
    fprintf(f, "Limits\n");
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(root, "limits"))
        fprintf(f, "  %-42s %g\n", it->string, it->valuedouble);
    const cJSON *t = cJSON_GetObjectItem(root, "timer");
    double cov = cJSON_GetObjectItem(t, "gpu_time_coverage")->valuedouble;
    const char *verdict = cJSON_GetObjectItem(t, "verdict")->valuestring;
    fprintf(f, "Timer calibration (GL_TIME_ELAPSED vs glFinish-fenced wall time on a heavy draw)\n");
    fprintf(f, "  gpu %.3f ms, wall %.3f ms, coverage %.4f -> %s\n",
           cJSON_GetObjectItem(t, "gpu_ns")->valuedouble / 1e6,
           cJSON_GetObjectItem(t, "wall_ns")->valuedouble / 1e6, cov, verdict);
    if (verdict[0] == 'p')
        fprintf(f, "  GPUTime is recorded but marked partial: it is never used to fit or gate.\n");
}

/* The child: the context, the report formatted, sent as "O" and the text,
 * or "F CODE\tMESSAGE" when there is no usable context. */
static void info__child(int fd, void *arg)
{
    int json = *(const int *)arg;
    gl_context *gl = NULL;
    dm_str err = {0};
    int rc = gl_context_create(NULL, &gl, &err);
    if (rc != 0) {
        dprintf(fd, "F%d\t%s", rc, dm_str_get(&err));
        dm_str_free(&err);
        return;
    }
    counters_context *cc = NULL;
    counters_timer_calibration cal = { .verdict = "unavailable" };
    if (counters_context_create(&cc) == 0)
        counters_calibrate_timer(cc, &cal);
    cJSON *root = info__collect(&cal);
    char *text = NULL;
    size_t len = 0;
    if (json) {
        text = cJSON_Print(root);
        len = strlen(text);
    } else {
        FILE *f = open_memstream(&text, &len);
        info__print_text(root, f);
        fclose(f);
    }
    dm_str out = {0};
    dm_str_printf(&out, "O%s%s", text, json ? "\n" : "");
    for (size_t off = 0; off < out.len;) {   /* the whole report, or the parent sees it cut */
        ssize_t w = write(fd, out.buf + off, out.len - off);
        if (w <= 0)
            break;
        off += (size_t)w;
    }
    dm_str_free(&out);
    free(text);
    cJSON_Delete(root);
    counters_context_destroy(cc);
    gl_context_destroy(gl);
}

int info_main(int json)
{
    dm_str err = {0};
    int rc = env_check(&err);
    if (rc != 0) {   /* bad LP_NUM_THREADS: 2 */
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        dm_str_free(&err);
        return dm_exit_from_error(rc);
    }
    /* The driver is asked in a child with the probe's deadline: a driver
     * that hangs at start-up (zink without a Vulkan device) or crashes
     * makes `info` exit 4 with the reason, never hang. */
    dm_proc_result res;
    dm_proc_collect(info__child, &json, probe_timeout_s(), &res);
    if (res.text[0] == 'O') {
        fputs(res.text + 1, stdout);
        rc = DM_EXIT_OK;
    } else {
        char *tab = res.text[0] == 'F' ? strchr(res.text, '\t') : NULL;
        int e = tab ? (int)strtol(res.text + 1, NULL, 10) : DM_ERR_GL;
        if (tab)   /* no usable GL: 4, as for run */
            dm_str_cat(&err, tab + 1);
        else if (res.started)
            probe_no_answer("the driver", res.timed_out, res.status, res.seconds, &err);
        else
            dm_str_printf(&err, "cannot start a process to ask the driver: %s", strerror(res.status));
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        rc = dm_exit_from_error(e < 0 ? e : DM_ERR_GL);
    }
    free(res.text);
    dm_str_free(&err);
    return rc;
}
