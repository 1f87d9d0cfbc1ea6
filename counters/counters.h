/* counters.h — a GPUPerfAPI-shaped counter library over GL queries and clocks.
 *
 * Usage (mirrors GPUPerfAPI's session/pass/sample workflow, study S4 (docs/studies.md)):
 *
 *   counters_context *ctx;  counters_context_create(&ctx);   // GL current; probes once
 *   counters_session *s;    counters_session_create(ctx, &s);
 *   counters_enable(s, "WallTime"); counters_enable(s, "VSInvocations");
 *   int passes; counters_num_passes(s, &passes);             // 2 here: timing, statistics
 *   for (int p = 0; p < passes; p++) {
 *       counters_pass_begin(s, p);
 *       counters_sample_begin(s, 0);  draw K frames;  counters_sample_end(s);
 *       counters_pass_end(s);
 *   }
 *   counters_session_end(s);
 *   double v; counters_result(s, 0, "VSInvocations", &v);   // DM_ERR_UNAVAILABLE if the driver lacks it
 *
 * Rules: samples are not nested and must use the same ids in every pass;
 * passes run in order 0..n-1; results are read after counters_session_end.
 * Misuse returns DM_ERR_MISUSE and counters_last_error() says what was wrong.
 * Timing counters never share a pass with statistics queries.  Values are
 * totals over the sample (the caller divides by frames per sample).
 * A counter the driver cannot provide is unavailable with a reason, never 0.
 */
#ifndef COUNTERS_COUNTERS_H
#define COUNTERS_COUNTERS_H

#include <stddef.h>
#include <stdint.h>

#include "core/dm_util.h"   /* dm_str */

typedef enum counters_unit {
    COUNTERS_UNIT_NS = 1, COUNTERS_UNIT_ITEMS, COUNTERS_UNIT_BYTES,
    COUNTERS_UNIT_RATIO, COUNTERS_UNIT_PERCENT
} counters_unit;

typedef enum counters_type {
    COUNTERS_TYPE_UINT64 = 1, COUNTERS_TYPE_FLOAT64
} counters_type;

typedef enum counters_backend {
    COUNTERS_BACKEND_CLOCK = 1,    /* CPU clocks around glFinish */
    COUNTERS_BACKEND_TIMER_QUERY,  /* GL_TIME_ELAPSED / GL_TIMESTAMP */
    COUNTERS_BACKEND_PIPELINE_STATS,
    COUNTERS_BACKEND_OCCLUSION,    /* GL_SAMPLES_PASSED */
    COUNTERS_BACKEND_CPU_SIDE,     /* set by the caller (bytes, VT counters) */
    COUNTERS_BACKEND_DERIVED,      /* formula over other counters */
    COUNTERS_BACKEND_CALLGRIND,    /* instructions counted under Valgrind, own child (run/callgrind.h) */
    COUNTERS_BACKEND_SHADER_COUNT, /* an instrumented variant of the caller's shader adds to a buffer
                                      (counters_pass_loop_trips) */
    COUNTERS_BACKEND_PER_CALL      /* pipeline statistics around each draw call of one frame, in a
                                      session of the caller's own (counters_tess_walk) */
} counters_backend;

/* Who supplies the value of a caller-fed (COUNTERS_BACKEND_CPU_SIDE)
 * counter when dmbench measures a configuration (run/measure.c reads this
 * column instead of matching names); NONE: a pass measures it, a formula
 * derives it, or nothing in dmbench feeds it yet. */
typedef enum counters_feed {
    COUNTERS_FEED_NONE = 0,
    COUNTERS_FEED_SETUP_NS,        /* the renderer's prepare time */
    COUNTERS_FEED_WARMUP_NS,       /* the warm-up's time */
    COUNTERS_FEED_TEXTURE_BYTES,   /* the renderer's item: texture storage */
    COUNTERS_FEED_MESH_BYTES,      /* the renderer's item: vertex and index buffers */
    COUNTERS_FEED_MESH_TRIANGLES,  /* the renderer's item: triangles submitted */
    COUNTERS_FEED_VIEWPORT_PIXELS, /* the render target: width x height */
    COUNTERS_FEED_VT_RESIDENT,     /* virtual texture: pages resident at sample end */
    COUNTERS_FEED_VT_MISSES,       /* virtual texture: misses in the configuration's samples */
    COUNTERS_FEED_VT_UPLOAD_BYTES, /* virtual texture: bytes uploaded in its samples */
    COUNTERS_FEED_VT_COMMITTED_BYTES /* virtual texture: page storage committed at sample end */
} counters_feed;

typedef struct counters_info {
    const char *name;
    const char *group;          /* "Timing", "Vertex", ... (docs/counters.md) */
    const char *description;    /* what it counts in general */
    counters_unit unit;
    counters_type type;
    counters_backend backend;
    int deterministic;          /* same scene + driver => same value */
    const char *formula;        /* derived counters only */
    counters_feed feed;         /* caller-fed counters: where the value comes from */
    int stops_sampling;         /* timed counter whose CI decides when sampling stops */
} counters_info;

typedef struct counters_context counters_context;
typedef struct counters_session counters_session;

/* ---- registry (no GL needed) ------------------------------------------ */
size_t counters_count(void);
const counters_info *counters_info_at(size_t i);
const counters_info *counters_find(const char *name);   /* NULL if unknown */
const char *counters_unit_name(counters_unit u);        /* "ns", "items", ... */

/* ---- context: probes the current GL context once ----------------------- */
int counters_context_create(counters_context **out);
void counters_context_destroy(counters_context *ctx);
/* 1 if available; else 0 and *reason (static or owned by ctx). */
int counters_available(const counters_context *ctx, const char *name, const char **reason);
/* What the counter really counts on this driver (e.g. per-4x4-block
 * FSInvocations on llvmpipe), or the generic description. */
const char *counters_driver_note(const counters_context *ctx, const char *name);
/* The Valgrind executable that counts the Cost group (Instructions): the
 * path in DMBENCH_VALGRIND when set (tests point it at a missing file),
 * else "valgrind" found on PATH.  Returns a malloc'd path or NULL. */
char *counters_valgrind_path(void);
/* Test hook: pretend an extension is missing ("GL_ARB_pipeline_statistics_query"). */
void counters_context_hide_extension(counters_context *ctx, const char *ext);

/* ---- sessions ------------------------------------------------------------ */
int counters_session_create(counters_context *ctx, counters_session **out);
void counters_session_destroy(counters_session *s);
int counters_enable(counters_session *s, const char *name);        /* DM_ERR_UNKNOWN */
int counters_enable_group(counters_session *s, const char *group);
int counters_num_passes(counters_session *s, int *passes);
/* Describes pass p ("timing", "geometry", "raster", "statistics", "loop trips"), for plans. */
const char *counters_pass_name(counters_session *s, int pass);
/* 1 when, in pass p, the caller must draw the same work with a minimal
 * fragment shader (same geometry, depth state and coverage; the raster
 * pass of MinimalShadingTime, docs/counters.md "Stage costs"). */
int counters_pass_minimal_fs(const counters_session *s, int pass);
/* The shader storage binding the loop-trips pass binds its counter buffer
 * to (two uints; the instrumented shader adds 1 to the first per SIMD
 * group per iteration of the parallax search loop, docs/counters.md "Loop
 * trips", and 1 to the second per SIMD group it runs, "Fragment groups"). */
#define COUNTERS_LOOP_TRIPS_BINDING 7
/* 1 when, in pass p, the caller must draw the same work with its loop-trip
 * instrumented shader (LoopTrips, FragmentGroups). */
int counters_pass_loop_trips(const counters_session *s, int pass);
/* Untimed frames the caller draws in pass p after counters_pass_begin and
 * before the pass's sample: 1 in the geometry and raster passes, whose
 * timed frames follow a switch of state (rasterizer discard, the minimal
 * program) that llvmpipe pays for in the first frame after it (docs/
 * counters.md, "The same split as times"); 0 in the others. */
int counters_pass_warm_frames(const counters_session *s, int pass);
/* Appends the pass plan of the selection names[0..n) as text to out
 * ("dmbench list counters --passes A,B"): the pass count, each pass with its
 * counters, then caller-fed, derived (with formulas) and unavailable
 * counters (with reasons).  DM_ERR_UNKNOWN (message in out) for an unknown
 * name.  Needs a context (availability decides the plan). */
int counters_plan_describe(counters_context *ctx, const char *const *names, size_t n, dm_str *out);
int counters_pass_begin(counters_session *s, int pass);
int counters_pass_end(counters_session *s);
int counters_sample_begin(counters_session *s, uint32_t sample_id);
int counters_sample_end(counters_session *s);
/* Caller-fed values (CPU_SIDE counters: TextureBytes, MeshBytes, SetupTime...). */
int counters_set_value(counters_session *s, uint32_t sample_id, const char *name, double value);
int counters_session_end(counters_session *s);
/* Reads a value after counters_session_end.  DM_ERR_UNAVAILABLE (reason via
 * counters_last_error) for unavailable counters or zero denominators of
 * derived counters; DM_ERR_NOTFOUND for unknown samples / not enabled. */
int counters_result(counters_session *s, uint32_t sample_id, const char *name, double *value);
const char *counters_last_error(const counters_session *s);

/* ---- derived counters over caller-supplied values -------------------------
 * Evaluates the formula of derived counter `name` with the values that
 * `value` supplies for its inputs (e.g. medians of a finished measurement).
 * Returns 0 and *out; DM_ERR_UNKNOWN (not a derived counter);
 * DM_ERR_UNAVAILABLE with the reason in why when an input is unavailable or
 * a denominator is zero (never an infinity). */
typedef int (*counters_value_fn)(const char *name, void *user, double *value);
int counters_derive(const char *name, counters_value_fn value, void *user, double *out, dm_str *why);
/* 1 when every input of derived counter `name` satisfies has(input, user). */
int counters_derive_inputs(const char *name, int (*has)(const char *input, void *user), void *user);

/* ---- per draw call ----------------------------------------------------------
 * TessWalkCalls (backend COUNTERS_BACKEND_PER_CALL, docs/counters.md
 * "TessWalkCalls"): the caller runs one statistics session over
 * counters_tess_walk_inputs, draws one frame and brackets each of its
 * draw calls of patches in a sample of its own (sample k = call k), then
 * reads the calls' counts into calls[k * COUNTERS_TESS_WALK_N + j], j in
 * the order of counters_tess_walk_inputs.  counters_tess_walk sums, over
 * the calls the clipper changed (ClippingInputPrimitives !=
 * ClippingOutputPrimitives: llvmpipe's draw module walks a call's vertices
 * only when it clips), the call's TESInvocations x ClippingOutputPrimitives.
 * Returns the sum, 0 when no call was clipped, NaN when n_calls is 0 or a
 * count is not finite. */
#define COUNTERS_TESS_WALK_N 3
extern const char *const counters_tess_walk_inputs[COUNTERS_TESS_WALK_N];
double counters_tess_walk(const double *calls, size_t n_calls);

/* ---- stage costs ------------------------------------------------------------
 * The bottleneck verdict of a configuration from its stage counters
 * (GeometryInstructions, RasterInstructions, FragmentInstructions, or the
 * matching times): the three shares of their sum in decreasing order,
 * rounded to whole percent, e.g. "fragment 87 %, geometry 9 %, raster 4 %",
 * appended to out.  DM_ERR_UNAVAILABLE (out unchanged) when a part is
 * negative or not finite or the sum is not positive. */
int counters_stage_verdict(double geometry, double raster, double fragment, dm_str *out);

/* ---- timer calibration (docs/counters.md) -----------------------------------------
 * Runs a heavy draw of its own (fragment-bound, into an internal FBO) and
 * compares GL_TIME_ELAPSED with glFinish-fenced wall time.  coverage =
 * GPUTime / WallTime; verdict "partial" below 0.5, else "full".  Decided by
 * measurement, never by the renderer's name.  Returns DM_ERR_UNAVAILABLE
 * (verdict "unavailable") without ARB_timer_query. */
typedef struct counters_timer_calibration {
    double gpu_ns, wall_ns, coverage;
    const char *verdict;        /* "partial" | "full" | "unavailable" */
} counters_timer_calibration;
int counters_calibrate_timer(counters_context *ctx, counters_timer_calibration *out);
#endif
