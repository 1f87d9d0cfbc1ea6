/* counters_internal.h — what the counters/ sources share and nobody else sees:
 * the registry table with its backend details, the context struct, and the
 * small GL helpers (programs, offscreen targets, saved state) used by the
 * probes and the timer calibration.
 */
#ifndef COUNTERS_COUNTERS_INTERNAL_H
#define COUNTERS_COUNTERS_INTERNAL_H

#include "counters/counters.h"
#include "core/dm_util.h"

#define COUNTERS__MAX 64        /* upper bound on the registry size */
#define COUNTERS__MAX_HIDDEN 8

/* Which pass measures a counter (docs/counters.md: timing never shares with queries). */
typedef enum counters__pass {
    COUNTERS__PASS_NONE = 0,    /* caller-fed or derived: no pass */
    COUNTERS__PASS_TIMING,
    COUNTERS__PASS_GEOMETRY,
    COUNTERS__PASS_RASTER,      /* the caller draws with a minimal fragment shader (counters_pass_minimal_fs) */
    COUNTERS__PASS_STATS,
    COUNTERS__PASS_LOOPS,       /* the caller draws with its loop-trip instrumented shader (counters_pass_loop_trips) */
    COUNTERS__PASS_KINDS
} counters__pass;

/* What the driver must offer for a counter to be available. */
typedef enum counters__req {
    COUNTERS__REQ_NONE = 0,
    COUNTERS__REQ_PIPESTATS,    /* GL_ARB_pipeline_statistics_query */
    COUNTERS__REQ_TIMER,        /* GL_ARB_timer_query */
    COUNTERS__REQ_COMPUTE,      /* pipeline statistics + GL_ARB_compute_shader */
    COUNTERS__REQ_CALLGRIND,    /* Valgrind installed and a CPU renderer (llvmpipe, softpipe) */
    COUNTERS__REQ_BALLOT        /* GL_ARB_shader_ballot (subgroup election in the instrumented shader) */
} counters__req;

typedef struct counters__def {
    counters_info info;
    counters__pass pass;
    unsigned gl_target;         /* query target for GL-measured counters, else 0 */
    counters__req req;
} counters__def;

const counters__def *counters__def_at(size_t i);
int counters__index(const char *name);          /* -1 if unknown */

struct counters_context {
    char **exts;
    size_t nexts;
    char *hidden[COUNTERS__MAX_HIDDEN];
    size_t nhidden;
    double fs_per_pixel;        /* FSInvocations for one covered pixel; 0 = not measured */
    char fs_note[320];
    char gpu_note[320];
    int cpu_renderer;           /* GL_RENDERER is a CPU rasteriser: its "GPU" work is CPU instructions */
    char renderer[128];
    char callgrind_why[320];    /* why Instructions is unavailable; "" = available */
};

/* 1 if the driver offers ext and no test hid it. */
int counters__has_ext(const counters_context *ctx, const char *ext);
/* Availability of counter i; on 0, *why is a static reason. */
int counters__available_idx(const counters_context *ctx, int i, const char **why);

/* ---- GL helpers (counters_gl.c) --------------------------------------- */
/* Saved framebuffer, viewport, program and VAO bindings. */
typedef struct counters__glstate { int fbo, vp[4], prog, vao; } counters__glstate;
void counters__glstate_save(counters__glstate *st);
void counters__glstate_restore(const counters__glstate *st);

/* An offscreen RGBA8 target with its own VAO (no attributes: shaders use
 * gl_VertexID or uniforms), bound and with the viewport set on create. */
typedef struct counters__target { unsigned fbo, rb, vao; int w, h; } counters__target;
int counters__target_create(counters__target *t, int w, int h);
void counters__target_destroy(counters__target *t);

/* Compiles and links vs+fs (GLSL 450 core).  Returns 0 and *prog, or
 * DM_ERR_SHADER with the log in err (may be NULL). */
int counters__program(const char *vs, const char *fs, unsigned *prog, dm_str *err);

/* Reads a finished query's 64-bit result; DM_ERR_GL if GL reported an error. */
int counters__query_read(unsigned q, uint64_t *out);

#endif
