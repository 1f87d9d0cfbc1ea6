/* cli_render.c — `dmbench render KEY=VALUE... --png out.png`: one image.
 * `--debug normals` renders the normals view (render.h, tech_debug_view). */
#include "cli.h"
#include "core/dm_error.h"
#include "run/gl_context.h"
#include "run/measure.h"
#include "reports/image.h"
#include "techniques/axes.h"
#include "techniques/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Parses KEY=VALUE arguments into params (validated); -1 to go on. */
static int render__args(int argc, char **argv, dm_kv **kv, size_t *n, const char **out, int *ss,
                        tech_debug_view *dbg)
{
    static const char *const valid[] = { "--png", "--exr", "--supersample", "--debug" };
    for (int i = 1; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        if (strcmp(argv[i], "--png") == 0 || strcmp(argv[i], "--exr") == 0) {
            if (!(*out = cli__value(argc, argv, &i)))
                return 2;
        } else if (strcmp(argv[i], "--supersample") == 0) {
            const char *v = cli__value(argc, argv, &i);
            if (!v || (*ss = atoi(v)) < 1 || *ss > 8)
                return cli__usage_error("render: --supersample expects 1..8");
        } else if (strcmp(argv[i], "--debug") == 0) {
            const char *v = cli__value(argc, argv, &i);
            if (!v || strcmp(v, "normals") != 0)
                return cli__usage_error("render: --debug expects 'normals'");
            *dbg = TECH_DEBUG_NORMALS;
        } else if (eq && argv[i][0] != '-') {
            *eq = '\0';
            dm_str err = {0};
            if (axes_check(argv[i], eq + 1, &err) != 0) {
                int rc = cli__usage_error("render: %s", dm_str_get(&err));
                dm_str_free(&err);
                return rc;
            }
            char *canon = axes_canonical(argv[i], eq + 1);
            dm_kv_push(kv, n, argv[i], canon);
            free(canon);
        } else {
            return cli__unknown_option("render", argv[i], valid, 4);
        }
    }
    if (!*out)
        return cli__usage_error("render: --png FILE (or --exr FILE) is required");
    return -1;
}

int cli_render(int argc, char **argv)
{
    dm_kv *kv = NULL;
    size_t n = 0;
    const char *out = NULL;
    int ss = 1, w = 0, h = 0;
    tech_debug_view dbg = TECH_DEBUG_NONE;
    int rc = render__args(argc, argv, &kv, &n, &out, &ss, &dbg);
    const char *res = dm_kv_get(kv, n, "resolution");
    if (sscanf(res ? res : axes_find("resolution")->def, "%dx%d", &w, &h) != 2)
        rc = cli__usage_error("render: bad resolution");
    gl_context *gl = NULL;
    tech_renderer *r = NULL;
    dm_str err = {0};
    if (rc < 0 && (gl_context_create(NULL, &gl, &err) != 0 || tech_renderer_create(&r) != 0)) {
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        rc = 1;
    }
    if (rc < 0)
        tech_renderer_set_debug_view(r, dbg);
    float *rgba = NULL;
    if (rc < 0 && measure_render_image(r, kv, n, w, h, ss, &rgba, NULL, &err) != 0) {
        fprintf(stderr, "dmbench: error: render failed:\n%s\n", dm_str_get(&err));
        rc = 1;
    }
    if (rc < 0) {
        img im = { w, h, rgba };
        char e[512];
        rc = img_save(&im, out, e, sizeof e) == 0 ? 0 : cli__usage_error("render: %s", e);
        if (rc == 0)
            printf("%s (%dx%d)\n", out, w, h);
    }
    free(rgba);
    dm_str_free(&err);
    dm_kv_free(kv, n);
    tech_renderer_destroy(r);
    gl_context_destroy(gl);
    return rc;
}
