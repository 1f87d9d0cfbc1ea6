/* overhead.c — harness overhead (docs/measurement.md): the per-frame time dmbench
 * REPORTS for a configuration against a minimal raw-GL loop drawing the
 * same thing.
 *
 * Harness side: `dmbench run` on a one-configuration sweep (the default
 * sweep's resolution, scene and measure block); the figure is the median
 * WallTime of that configuration in results.json.
 * Raw side, in this process: its own EGL context, its own RGBA32F + depth32F
 * FBO, its own VAO built from mesh_build, and the program object and bound
 * map textures that techniques/render.c made for exactly the parameters
 * dmbench recorded (one render_draw sets the program's uniforms and binds the
 * maps; they persist).  A frame is glClear + glDrawElements; a sample is K
 * frames between two glFinish, K chosen as the harness does (at least
 * frames_per_sample, enough to last min_sample_ms) after the same warm-up.
 * Before timing, the raw frame is read back and compared bit for bit with
 * the renderer's frame: the work is the same work.
 *
 * Raw and harness measurements alternate in rounds (ABBA order), so drift
 * of a shared machine hits both; per round the ratio harness/raw is taken.
 * LP_NUM_THREADS is set to 1 unless set, as run/runner.c does.
 *
 * Usage: bench_overhead [ROUNDS]   (default 9; dmbench: DMBENCH_BIN or the
 * one built beside this benchmark).  Exit 0 when every configuration was
 * measured, 1 when the work could not be done or checked.
 *
 * bench_overhead --instructions: the same comparison in instructions, both
 * sides under Valgrind callgrind (LP_NUM_THREADS=0, collection only around
 * the counted frames and their closing glFinish): the harness figure is
 * the Instructions per frame dmbench records (its own Instructions pass,
 * run/callgrind.h); the raw figure comes from this program re-run under
 * callgrind (--raw-instructions) drawing the identical frame (checked bit
 * for bit) as many frames as dmbench counts.  Deterministic: one run each. */
#include <cjson/cJSON.h>
#include <epoxy/gl.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include <valgrind/callgrind.h>

#include "core/dm_error.h"
#include "core/dm_proc.h"
#include "core/dm_util.h"
#include "counters/counters.h"
#include "run/callgrind.h"
#include "run/gl_context.h"
#include "models/stats.h"
#include "techniques/mesh.h"
#include "techniques/render.h"

#define W 480
#define H 270
#define WARMUP_FRAMES 4
#define FRAMES_PER_SAMPLE 8
#define MIN_SAMPLE_MS 20.0
#define RAW_SAMPLES 7
#define MAX_ROUNDS 16

/* The configurations compared: technique, mesh, extra sweep axis line. */
typedef struct ov_conf {
    const char *technique, *mesh, *axis;
    dm_kv *params;              /* as dmbench recorded them */
    size_t n_params;
    render_item item;             /* the renderer's item: binds the maps before raw frames */
    GLuint prog, vao;
    GLsizei n_indices;
    int frames;                 /* frames per raw sample */
    double raw[MAX_ROUNDS], harness[MAX_ROUNDS];   /* ns/frame per round */
} ov_conf;

static ov_conf confs[] = {
    {.technique = "texture", .mesh = "plane"},
    {.technique = "normal", .mesh = "plane"},
    {.technique = "pom", .mesh = "plane", .axis = "  steps: [32]\n"},
};
#define N_CONFS (sizeof confs / sizeof confs[0])

static const char sweep_fmt[] =
    "name: overhead-%s\n"
    "resolution: [%d, %d]\n"
    "measure:\n"
    "  warmup_frames: %d\n"
    "  frames_per_sample: %d\n"
    "  samples: { min: 5, max: 30, target_ci: 0.03 }\n"
    "  max_seconds: 6\n"
    "%s"
    "scene:\n"
    "  camera: { distance: 3.0, azimuth: 30, elevation: 35, fov: 45 }\n"
    "  material: { maps: bricks, height_scale: 0.06 }\n"
    "sweep:\n"
    "  mesh: [%s]\n"
    "  technique: [%s]\n"
    "%s";

/* measure.counters for --instructions (else the default set) */
static const char *counters_line = "";

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(const double *x, size_t n)
{
    double *s = dm_xmalloc(n * sizeof *s);
    memcpy(s, x, n * sizeof *s);
    qsort(s, n, sizeof *s, cmp_double);
    double m = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    free(s);
    return m;
}

/* Runs `bin run sweep --out out` with its output in log; returns its exit
 * status (-1 when it could not be started or was killed). */
static int run_dmbench(const char *bin, const char *sweep, const char *out, const char *log)
{
    pid_t pid = dm_proc_fork();   /* dies with this program, like every dmbench child */
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
        }
        execl(bin, bin, "run", sweep, "--out", out, (char *)NULL);
        _exit(127);
    }
    int st = 0;
    if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
        return -1;
    return WEXITSTATUS(st);
}

/* Reads the single configuration of out/latest/results.json: its median
 * WallTime (ns/frame) and, when params is non-NULL, its parameters as text.
 * Returns 0, or DM_ERR_IO / DM_ERR_PARSE. */
static int read_result(const char *out, double *wall_ns, dm_kv **params, size_t *n_params)
{
    char *path = dm_xasprintf("%s/latest/results.json", out), *text = NULL;
    int rc = dm_read_file(path, &text, NULL);
    free(path);
    if (rc != 0)
        return rc;
    cJSON *root = cJSON_Parse(text);
    free(text);
    cJSON *c = cJSON_GetArrayItem(cJSON_GetObjectItem(root, "configs"), 0);
    cJSON *st = cJSON_GetObjectItem(c, "status");
    cJSON *med = cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetObjectItem(c, "counters"), "WallTime"),
                                     "median");
    rc = cJSON_IsString(st) && strcmp(st->valuestring, "ok") == 0 && cJSON_IsNumber(med) ? 0 : DM_ERR_PARSE;
    if (rc == 0)
        *wall_ns = med->valuedouble;
    cJSON *p, *ps = params && rc == 0 ? cJSON_GetObjectItem(c, "params") : NULL;
    cJSON_ArrayForEach(p, ps) {
        char num[64];
        if (cJSON_IsNumber(p))
            snprintf(num, sizeof num, "%.15g", p->valuedouble);
        dm_kv_push(params, n_params, p->string, cJSON_IsNumber(p) ? num : p->valuestring);
    }
    cJSON_Delete(root);
    return rc;
}

/* One harness measurement of configuration c: a fresh `dmbench run`. */
static int harness_measure(const char *bin, const char *dir, ov_conf *c, double *wall_ns, int first)
{
    char *sweep = dm_xasprintf("%s/%s.yaml", dir, c->technique);
    char *out = dm_xasprintf("%s/out-%s", dir, c->technique);
    char *log = dm_xasprintf("%s/%s.log", dir, c->technique);
    char *text = dm_xasprintf(sweep_fmt, c->technique, W, H, WARMUP_FRAMES, FRAMES_PER_SAMPLE,
                              counters_line, c->mesh, c->technique, c->axis ? c->axis : "");
    int rc = dm_write_file(sweep, text, strlen(text));
    if (rc == 0 && run_dmbench(bin, sweep, out, log) != 0)
        rc = DM_ERR_IO;
    if (rc == 0)
        rc = read_result(out, wall_ns, first ? &c->params : NULL, &c->n_params);
    if (rc != 0)
        fprintf(stderr, "bench_overhead: dmbench run of %s failed (see %s)\n", sweep, log);
    free(text);
    free(log);
    free(out);
    free(sweep);
    return rc;
}

/* Own VAO over a mesh_build of the configuration's mesh, laid out as the
 * renderer's vertex format (mesh.h: interleaved pos, nrm, uv, tan). */
static int raw_vao(ov_conf *c)
{
    const char *dens = dm_kv_get(c->params, c->n_params, "mesh_density");
    mesh_desc d = {.name = c->mesh, .density = dens ? atoi(dens) : 0};
    mesh_data md;
    if (mesh_build(&d, &md) != 0)
        return DM_ERR_ARG;
    GLuint b[2];
    glCreateVertexArrays(1, &c->vao);
    glCreateBuffers(2, b);
    glNamedBufferStorage(b[0], (GLsizeiptr)(md.n_vertices * sizeof(mesh_vertex)), md.vertices, 0);
    glNamedBufferStorage(b[1], (GLsizeiptr)(md.n_indices * sizeof(uint32_t)), md.indices, 0);
    glVertexArrayVertexBuffer(c->vao, 0, b[0], 0, sizeof(mesh_vertex));
    glVertexArrayElementBuffer(c->vao, b[1]);
    static const GLint comps[4] = {3, 3, 2, 4};
    static const GLuint offs[4] = {offsetof(mesh_vertex, pos), offsetof(mesh_vertex, nrm),
                                   offsetof(mesh_vertex, uv), offsetof(mesh_vertex, tan)};
    for (GLuint a = 0; a < 4; a++) {
        glEnableVertexArrayAttrib(c->vao, a);
        glVertexArrayAttribFormat(c->vao, a, comps[a], GL_FLOAT, GL_FALSE, offs[a]);
        glVertexArrayAttribBinding(c->vao, a, 0);
    }
    c->n_indices = (GLsizei)md.n_indices;
    mesh_free(&md);
    return 0;
}

static void raw_frames(const ov_conf *c, int frames)
{
    glUseProgram(c->prog);
    glBindVertexArray(c->vao);
    for (int f = 0; f < frames; f++) {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDrawElements(GL_TRIANGLES, c->n_indices, GL_UNSIGNED_INT, NULL);
    }
}

static double raw_sample(const ov_conf *c, int frames)
{
    glFinish();
    int64_t t0 = dm_now_ns();
    raw_frames(c, frames);
    glFinish();
    return (double)(dm_now_ns() - t0) / frames;
}

/* Frame of the renderer and of the raw loop read back from the bound FBO;
 * returns 1 when they are bit-identical and not empty. */
static int raw_same_image(render_ctx *r, render_item it, const ov_conf *c)
{
    size_t n = (size_t)W * H * 4;
    float *a = dm_xcalloc(n, sizeof *a), *b = dm_xcalloc(n, sizeof *b);
    render_draw(r, it, W, H);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, a);
    raw_frames(c, 1);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, b);
    size_t covered = 0;
    for (size_t i = 3; i < n; i += 4)
        covered += a[i] != 0.0f;
    int same = covered > 0 && memcmp(a, b, n * sizeof *a) == 0;
    free(a);
    free(b);
    return same;
}

/* Prepares the raw loop of c from the parameters dmbench recorded; warms up
 * as the harness does and picks the frames per sample. */
static int raw_prepare(render_ctx *r, ov_conf *c)
{
    dm_str log = {0};
    int rc = render_prepare(r, c->params, c->n_params, &c->item, &log);
    if (rc == 0)
        rc = render_draw(r, c->item, W, H);
    GLint prog = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    c->prog = (GLuint)prog;
    rc = rc ? rc : raw_vao(c);
    if (rc == 0 && !raw_same_image(r, c->item, c)) {
        fprintf(stderr, "bench_overhead: %s: raw frame differs from the renderer's\n", c->technique);
        rc = DM_ERR_GL;
    }
    if (rc != 0)
        fprintf(stderr, "bench_overhead: %s: cannot prepare (%s) %s\n", c->technique, dm_strerror(rc),
                dm_str_get(&log));
    dm_str_free(&log);
    if (rc != 0)
        return rc;
    raw_frames(c, WARMUP_FRAMES);
    double prev = raw_sample(c, FRAMES_PER_SAMPLE);
    for (int tries = 0; tries < 10; tries++) {
        double cur = raw_sample(c, FRAMES_PER_SAMPLE);
        if (fabs(cur - prev) <= 0.10 * prev)
            break;
        prev = cur;
    }
    double want = MIN_SAMPLE_MS * 1e6 / (prev > 1 ? prev : 1);
    c->frames = want > FRAMES_PER_SAMPLE ? (int)ceil(want) : FRAMES_PER_SAMPLE;
    return 0;
}

/* Median of RAW_SAMPLES raw samples; one untimed renderer frame first so
 * the maps of this configuration are the ones bound. */
static double raw_measure(render_ctx *r, const ov_conf *c)
{
    double s[RAW_SAMPLES];
    render_draw(r, c->item, W, H);
    raw_frames(c, 1);
    for (int i = 0; i < RAW_SAMPLES; i++)
        s[i] = raw_sample(c, c->frames);
    return median(s, RAW_SAMPLES);
}

/* The FBO of the raw loop: RGBA32F colour + 32F depth, as run/target.c. */
static void raw_target(void)
{
    GLuint tex[2], fbo;
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    glTextureStorage2D(tex[0], 1, GL_RGBA32F, W, H);
    glTextureStorage2D(tex[1], 1, GL_DEPTH_COMPONENT32F, W, H);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex[0], 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex[1], 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glViewport(0, 0, W, H);
}

/* Prints one configuration's figures and verdict.  d_i = harness_i/raw_i - 1
 * per round (raw and harness of a round are taken back to back, so drift
 * cancels); the verdict uses the 95 % CI of the median of d_i
 * (models/stats.h).  The target is symmetric ("within 3 % of"): "within
 * 3 %" when the whole CI lies inside +-3 %, "over 3 %" when it lies wholly
 * outside, else the spread of the repeats exceeds what the difference can
 * tell apart: too noisy to decide. */
static void report(const ov_conf *c, int rounds)
{
    double d[MAX_ROUNDS];
    for (int i = 0; i < rounds; i++)
        d[i] = c->harness[i] / c->raw[i] - 1;
    stats_summary r, h, dd;
    stats_summarize(c->raw, (size_t)rounds, 1, &r);
    stats_summarize(c->harness, (size_t)rounds, 1, &h);
    stats_summarize(d, (size_t)rounds, 1, &dd);
    const char *verdict = dd.ci_lo >= -0.03 && dd.ci_hi <= 0.03 ? "within 3 %"
                          : dd.ci_lo > 0.03 || dd.ci_hi < -0.03 ? "over 3 %"
                                                                : "too noisy to decide";
    printf("  %-8s raw     %8.3f ms/frame (rounds %.3f..%.3f, %d frames/sample)\n"
           "           harness %8.3f ms/frame (rounds %.3f..%.3f)\n"
           "           harness/raw - 1: median %+6.2f %%, 95 %% CI [%+.2f, %+.2f] %%: %s\n",
           c->technique, r.median / 1e6, r.min / 1e6, r.max / 1e6, c->frames, h.median / 1e6,
           h.min / 1e6, h.max / 1e6, 100 * dd.median, 100 * dd.ci_lo, 100 * dd.ci_hi, verdict);
}

/* ---- --instructions ------------------------------------------------------ */

/* Instructions per frame of the single configuration in out/latest. */
static int read_instructions(const char *out, double *per_frame)
{
    char *path = dm_xasprintf("%s/latest/results.json", out), *text = NULL;
    int rc = dm_read_file(path, &text, NULL);
    free(path);
    cJSON *root = rc == 0 ? cJSON_Parse(text) : NULL;
    free(text);
    cJSON *c = cJSON_GetArrayItem(cJSON_GetObjectItem(root, "configs"), 0);
    cJSON *m = cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetObjectItem(c, "counters"), "Instructions"),
                                   "median");
    rc = cJSON_IsNumber(m) ? 0 : DM_ERR_PARSE;
    if (rc == 0)
        *per_frame = m->valuedouble;
    cJSON_Delete(root);
    return rc;
}

/* The raw side under Valgrind (this program, --raw-instructions DIR TECH):
 * prepares the raw loop from the parameters dmbench recorded in
 * DIR/out-TECH, checks it draws the renderer's frame, warms up, then counts
 * `frames` frames ended by glFinish and dumps them as "raw". */
static int raw_instructions_child(const char *dir, const char *tech, int frames)
{
    ov_conf *c = NULL;
    for (size_t i = 0; i < N_CONFS; i++)
        c = strcmp(confs[i].technique, tech) == 0 ? &confs[i] : c;
    gl_context *gl = NULL;
    render_ctx *r = NULL;
    dm_str err = {0};
    char *out = dm_xasprintf("%s/out-%s", dir, tech);
    double ignored;
    int rc = c && gl_context_create(NULL, &gl, &err) == 0 && render_create(&r) == 0 ? 0 : DM_ERR_ARG;
    rc = rc ? rc : read_result(out, &ignored, &c->params, &c->n_params);
    if (rc == 0) {
        raw_target();
        dm_str log = {0};
        rc = render_prepare(r, c->params, c->n_params, &c->item, &log);
        rc = rc ? rc : render_draw(r, c->item, W, H);
        GLint prog = 0;
        glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
        c->prog = (GLuint)prog;
        rc = rc ? rc : raw_vao(c);
        rc = rc ? rc : raw_same_image(r, c->item, c) ? 0 : DM_ERR_GL;
        dm_str_free(&log);
    }
    if (rc == 0) {
        raw_frames(c, WARMUP_FRAMES);
        glFinish();
        CALLGRIND_TOGGLE_COLLECT;
        raw_frames(c, frames);
        glFinish();
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT("raw");
    }
    free(out);
    render_destroy(r);
    gl_context_destroy(gl);
    return rc == 0 ? 0 : 1;
}

/* Runs the raw side of c under callgrind; *per_frame from its dump. */
static int raw_instructions(const char *self, const char *dir, const ov_conf *c, int frames,
                            double *per_frame)
{
    char *vg = counters_valgrind_path();
    char *cg = dm_xasprintf("--callgrind-out-file=%s/raw-%s.cg", dir, c->technique);
    char *nf = dm_xasprintf("%d", frames);
    pid_t pid = vg ? dm_proc_fork() : -1;
    if (pid == 0) {
        setenv("LP_NUM_THREADS", "0", 1);
        execl(vg, vg, "--tool=callgrind", "--collect-atstart=no", "--smc-check=all-non-file", cg,
              "-q", self, "--raw-instructions", dir, c->technique, nf, (char *)NULL);
        _exit(127);
    }
    int st = 0, rc = pid > 0 && waitpid(pid, &st, 0) == pid && WIFEXITED(st) && WEXITSTATUS(st) == 0
                         ? 0 : DM_ERR_CHILD;
    char *dump = dm_xasprintf("%s/raw-%s.cg.1", dir, c->technique), *text = NULL, name[16];
    double totals = 0, alloc = 0;
    rc = rc ? rc : dm_read_file(dump, &text, NULL);
    rc = rc ? rc : callgrind_parse_dump(text, name, sizeof name, &totals, &alloc);
    if (rc == 0)
        *per_frame = (totals - alloc) / frames;   /* as Instructions: the allocator left out */
    else
        fprintf(stderr, "bench_overhead: raw %s under callgrind failed (%s)\n", c->technique,
                vg ? dm_strerror(rc) : "valgrind not found");
    free(text);
    free(dump);
    free(nf);
    free(cg);
    free(vg);
    return rc;
}

/* --instructions: one harness run and one raw run per configuration, both
 * counted under callgrind; prints instructions per frame and the overhead. */
static int instructions_main(const char *self, const char *bin)
{
    counters_line = "  counters: [WallTime, SamplesPassed, Instructions]\n";
    int frames = CALLGRIND_FRAMES, rc = 0;
    char dir[] = "/tmp/dmbench-overhead-XXXXXX";
    if (!mkdtemp(dir))
        return 1;
    printf("harness overhead in instructions (callgrind, LP_NUM_THREADS=0, %dx%d, %d counted frames, "
           "deterministic)\n", W, H, frames);
    for (size_t i = 0; rc == 0 && i < N_CONFS; i++) {
        ov_conf *c = &confs[i];
        double wall, harness = 0, raw = 0;
        rc = harness_measure(bin, dir, c, &wall, 0);
        char *out = dm_xasprintf("%s/out-%s", dir, c->technique);
        rc = rc ? rc : read_instructions(out, &harness);
        free(out);
        rc = rc ? rc : raw_instructions(self, dir, c, frames, &raw);
        if (rc == 0)
            printf("  %-8s raw %12.0f  harness %12.0f instructions/frame: overhead %+.3f %%%s\n",
                   c->technique, raw, harness, 100 * (harness / raw - 1),
                   fabs(harness / raw - 1) <= 0.01 ? " (within 1 %)" : " (over 1 %)");
    }
    printf("  (work dir %s)\n", dir);
    return rc == 0 ? 0 : 1;
}

int main(int argc, char **argv)
{
    const char *bin0 = getenv("DMBENCH_BIN") ? getenv("DMBENCH_BIN") : DM_DMBENCH_PATH;
    if (argc == 5 && strcmp(argv[1], "--raw-instructions") == 0)
        return raw_instructions_child(argv[2], argv[3], atoi(argv[4]));
    if (argc == 2 && strcmp(argv[1], "--instructions") == 0) {
        char self[4096];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        self[n > 0 ? n : 0] = '\0';
        return instructions_main(self, bin0);
    }
    int rounds = argc > 1 ? atoi(argv[1]) : 9;
    if (rounds < 1 || rounds > MAX_ROUNDS) {
        fprintf(stderr, "usage: bench_overhead [ROUNDS 1..%d]\n", MAX_ROUNDS);
        return 2;
    }
    const char *bin = getenv("DMBENCH_BIN") ? getenv("DMBENCH_BIN") : DM_DMBENCH_PATH;
    setenv("LP_NUM_THREADS", "1", 0);   /* as run/runner.c */
    char dir[] = "/tmp/dmbench-overhead-XXXXXX";
    gl_context *gl = NULL;
    render_ctx *r = NULL;
    dm_str err = {0};
    if (!mkdtemp(dir) || gl_context_create(NULL, &gl, &err) != 0 || render_create(&r) != 0) {
        fprintf(stderr, "bench_overhead: cannot set up: %s\n", dm_str_get(&err));
        return 1;
    }
    raw_target();
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < N_CONFS; i++) {   /* first run: parameters, warm caches */
        double ignored;
        rc = harness_measure(bin, dir, &confs[i], &ignored, 1);
        rc = rc ? rc : raw_prepare(r, &confs[i]);
    }
    for (int k = 0; rc == 0 && k < rounds; k++)
        for (size_t i = 0; rc == 0 && i < N_CONFS; i++) {
            ov_conf *c = &confs[i];
            int raw_first = (k % 2) == 0;
            if (raw_first)
                c->raw[k] = raw_measure(r, c);
            rc = harness_measure(bin, dir, c, &c->harness[k], 0);
            if (!raw_first)
                c->raw[k] = raw_measure(r, c);
        }
    if (rc == 0) {
        printf("harness overhead (docs/measurement.md): %dx%d, LP_NUM_THREADS=%s, %d interleaved rounds, "
               "raw = median of %d samples per round, harness = dmbench's reported median WallTime\n",
               W, H, getenv("LP_NUM_THREADS"), rounds, RAW_SAMPLES);
        for (size_t i = 0; i < N_CONFS; i++)
            report(&confs[i], rounds);
        printf("  (work dir %s)\n", dir);
    }
    for (size_t i = 0; i < N_CONFS; i++)
        dm_kv_free(confs[i].params, confs[i].n_params);
    render_destroy(r);
    gl_context_destroy(gl);
    dm_str_free(&err);
    return rc == 0 ? 0 : 1;
}
