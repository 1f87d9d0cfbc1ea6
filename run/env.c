#include "env.h"
#include "core/dm_error.h"
#include "core/dm_util.h"
#include "run/drivers.h"

#include <epoxy/gl.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef DM_GIT_REV
#define DM_GIT_REV "unknown"
#endif

static const char *const env__fp_keys[] = { "renderer", "gl_version", "lp_num_threads",
                                            "cpu", "cpu_count", NULL };

const char *const *env_fingerprint_keys(void) { return env__fp_keys; }

/* CPU model from /proc/cpuinfo ("unknown" when absent). */
static char *env__cpu_model(void)
{
    char *text = NULL;
    if (dm_read_file("/proc/cpuinfo", &text, NULL) != 0)
        return dm_xstrdup("unknown");
    char *line = strstr(text, "model name");
    char *model = NULL;
    if (line && (line = strchr(line, ':'))) {
        line += 2;
        size_t n = strcspn(line, "\n");
        model = dm_xmalloc(n + 1);
        memcpy(model, line, n);
        model[n] = '\0';
    }
    free(text);
    return model ? model : dm_xstrdup("unknown");
}

int env_check(dm_str *err)
{
    const char *lp = getenv("LP_NUM_THREADS");
    if (!lp)
        return 0;
    char *end = NULL;
    errno = 0;
    long v = strtol(lp, &end, 10);
    int digits = *lp >= '0' && *lp <= '9';   /* no sign, no space: exactly what was meant */
    if (digits && errno == 0 && *end == '\0' && v >= 0 && v <= ENV_LP_MAX_THREADS)
        return 0;
    char *buf = NULL;
    dm_str_printf(err, "LP_NUM_THREADS='%.40s': expected a whole number of llvmpipe rasteriser "
                  "threads from 0 to %d (0: rasterise on the calling thread); unset it to "
                  "measure with 1", dm_term_safe(lp, &buf), ENV_LP_MAX_THREADS);
    free(buf);
    return DM_ERR_ARG;
}

void env_collect(dm_kv **kv, size_t *n, int gl)
{
    if (gl) {
        dm_kv_push(kv, n, "renderer", (const char *)glGetString(GL_RENDERER));
        dm_kv_push(kv, n, "gl_version", (const char *)glGetString(GL_VERSION));
        dm_kv_push(kv, n, "glsl_version", (const char *)glGetString(GL_SHADING_LANGUAGE_VERSION));
        dm_kv_push(kv, n, "vendor", (const char *)glGetString(GL_VENDOR));
    }
    dm_kv_push(kv, n, "driver", drivers_current());
    const char *lp = getenv("LP_NUM_THREADS");
    dm_kv_push(kv, n, "lp_num_threads", lp ? lp : "default");
    char *cpu = env__cpu_model();
    dm_kv_push(kv, n, "cpu", cpu);
    free(cpu);
    char buf[64];
    snprintf(buf, sizeof buf, "%ld", sysconf(_SC_NPROCESSORS_ONLN));
    dm_kv_push(kv, n, "cpu_count", buf);
    double load[3] = { 0, 0, 0 };
    if (getloadavg(load, 3) == 3) {
        snprintf(buf, sizeof buf, "%.2f %.2f %.2f", load[0], load[1], load[2]);
        dm_kv_push(kv, n, "load_average", buf);
    }
    dm_kv_push(kv, n, "git_revision", DM_GIT_REV);
    dm_kv_push(kv, n, "harness_version", "0.1.0");
}

void env_fingerprint(dm_kv **kv, size_t *n)
{
    uint64_t h = DM_FNV_SEED;
    for (const char *const *k = env__fp_keys; *k; k++) {
        const char *v = dm_kv_get(*kv, *n, *k);
        h = dm_fnv1a64(*k, strlen(*k) + 1, h);
        h = dm_fnv1a64(v ? v : "", v ? strlen(v) + 1 : 1, h);
    }
    char hex[17];
    dm_hex64(h, hex);
    dm_kv_push(kv, n, "fingerprint", hex);
}
