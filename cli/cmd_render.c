/* cmd_render.c — `dmbench render KEY=VALUE... --png out.png`: one image.
 * `--debug normals` renders the normals view (render.h, render_debug_view). */
#include "cli.h"
#include "cli/params.h"
#include "core/dm_error.h"
#include "core/dm_exit.h"
#include "run/env.h"
#include "run/gl_context.h"
#include "run/mscene.h"
#include "run/probe.h"
#include "imaging/image.h"
#include "techniques/axes.h"
#include "techniques/render.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct render_args {
    const char *out;           /* --png or --exr: the format follows the file's extension */
    int supersample, debug, frame;
} render_args;

static const char *const render__debug_views[] = { "none", "normals", NULL };

const cli_option cli_render_options[] = {
    CLI_STRING("png", render_args, out, "FILE", "write the image to FILE (PNG)"),
    CLI_STRING("exr", render_args, out, "FILE", "write the image to FILE (EXR keeps float values)"),
    { .name = "supersample", .kind = CLI_OPT_INT, .offset = offsetof(render_args, supersample),
      .value_name = "N", .help = "render at N×N samples per pixel and box-filter down",
      .def = "1", .min = 1, .max = 8 },
    { .name = "debug", .kind = CLI_OPT_CHOICE, .offset = offsetof(render_args, debug),
      .value_name = "VIEW", .choices = render__debug_views, .def = "none",
      .help = "a debug view instead of the shading (normals: world-space normal·0.5+0.5)" },
    { .name = "frame", .kind = CLI_OPT_INT, .offset = offsetof(render_args, frame), .value_name = "N",
      .def = "0", .min = 0, .max = 1000000000,
      .help = "draw frame N: orbits turned and camera.path followed to it (docs/motion.md)" },
    CLI_OPT_END
};

/* `dmbench render KEY=VALUE... --png FILE`: one image of one
 * configuration; exit 1 when it cannot be drawn, 2 for bad input. */
int cli_render(const cli_command *self, int argc, char **argv)
{
    render_args args = {0}, *a = &args;
    int rc = cli_parse(self, argc, argv, a, &argc);
    dm_kv *kv = NULL;
    size_t n = 0;
    const char *out = a->out;
    int ss = a->supersample, w = 0, h = 0;
    render_debug_view dbg = a->debug ? RENDER_DEBUG_NORMALS : RENDER_DEBUG_NONE;
    if (rc < 0)
        rc = cli_params_parse("render", argc, argv, &kv, &n);
    if (rc < 0 && !out)
        rc = cli_usage_error("render: --png FILE (or --exr FILE) is required");
    const char *res = dm_kv_get(kv, n, "resolution");
    if (rc < 0 && sscanf(res ? res : axes_find("resolution")->def, "%dx%d", &w, &h) != 2)
        rc = cli_usage_error("render: bad resolution");
    gl_context *gl = NULL;
    render_ctx *r = NULL;
    dm_str err = {0};
    int e = rc < 0 ? env_check(&err) : 0;
    if (rc < 0 && e == 0)   /* a user's GLSL that crashes or hangs the compiler: in a child */
        e = probe_user_techniques(&err);
    if (rc < 0 && e == 0 && (e = gl_context_create(NULL, &gl, &err)) == 0 &&
        render_create(&r) != 0)
        e = DM_ERR_GL;
    if (rc < 0 && e != 0) {   /* no usable GL is the machine's: exit 4, as for run; the user's GLSL: 2 */
        fprintf(stderr, "dmbench: error: %s\n", dm_str_get(&err));
        rc = dm_exit_from_error(e);
    }
    if (rc < 0)
        render_set_debug_view(r, dbg);
    float *rgba = NULL;
    if (rc < 0 && mscene_render_frame(r, kv, n, w, h, ss, (uint64_t)a->frame, &rgba, NULL, &err) != 0) {
        fprintf(stderr, "dmbench: error: render failed:\n%s\n", dm_str_get(&err));
        rc = DM_EXIT_FAILED;
    }
    if (rc < 0) {
        img im = { w, h, rgba };
        char e[512];
        int se = img_save(&im, out, e, sizeof e);   /* a full disk or ulimit -f: 4 */
        rc = se == 0 ? DM_EXIT_OK : cli_error(se, "render: %s", e);
        if (rc == 0)
            printf("%s (%dx%d)\n", out, w, h);
    }
    free(rgba);
    dm_str_free(&err);
    dm_kv_free(kv, n);
    render_destroy(r);
    gl_context_destroy(gl);
    return rc;
}
