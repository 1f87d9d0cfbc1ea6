/* mscene.h — one measuring process's scene state, and what every kind of
 * measuring does with it: the GL context, renderer, counters context and
 * store of a process, the configurations it prepares, their frames, counter
 * sessions and images.
 *
 * Four kinds of process measure: the timed scene child and the --budget
 * pilot (run/measure.h), the counting child under Valgrind
 * (run/count_child.h), and the in-process counts of `predict`
 * (run/inproc.h); quality images are run/mquality.h.  Each of them builds
 * on this file, which calls none of them.
 *
 * Progress lines to the job's report_fd (mscene_say) are the runner's
 * protocol: "B KEY" before work on a key, then what the kind of process
 * reports (measure.h, count_child.h).
 */
#ifndef RUN_MSCENE_H
#define RUN_MSCENE_H

#include <stddef.h>
#include <stdint.h>

#include "core/dm_util.h"
#include "counters/counters.h"
#include "run/gl_context.h"
#include "run/measure.h"
#include "run/protocol.h"
#include "run/target.h"
#include "store/store.h"
#include "techniques/render.h"

/* State of one configuration while its scene is measured. */
typedef struct mconf {
    const plan_config *pc;
    render_item item;
    render_item item_min;         /* minimal-fragment-shader item for the raster pass (MinimalShadingTime), 0 = none */
    char *min_why;              /* why there is none although the sweep asks for MinimalShadingTime */
    render_item item_trips;       /* loop-trip counting item for the LoopTrips pass, 0 = none */
    render_item_info info;
    int active;                 /* still sampling */
    int failed;
    char *reason;
    dm_str log;
    int64_t warmup_ns;
    int64_t sampling_ns;        /* time spent in its own timing samples */
    int64_t stats_ns, quality_ns;   /* statistics pass; images and quality (--verbose log) */
    const char *ref_source;     /* "cache", "rendered", NULL: the scene's, made before */
    int frames;                 /* frames per timing sample (>= K, see min_sample_ms) */
    double **timing;            /* per timing counter: per-frame samples */
    size_t n_samples;
    size_t cap;                 /* samples each timing[] row holds (samples.max, grown by extra rounds) */
    int extra;                  /* stopped short of its target: waits for extra rounds (--extra-time) */
    size_t n_extra;             /* samples taken in extra rounds */
    double ci_rel, ci_rel_before;   /* the stop counter's CI now, and when the extra rounds began */
    double corr_ci_rel;         /* its CI with the drift removed when that decided its extra rounds
                                   (protocol_extra_corrected), NaN when the raw CI did */
    size_t *round_of;           /* the round (of this process) of each sample; SIZE_MAX: restored
                                   from a checkpoint (cap entries) */
    protocol_decision last;     /* the protocol's last decision (its drift goes to the log) */
    double *stats;              /* per statistics counter: per-frame value (NAN = unavailable) */
    char **stats_reason;
    int has_vt;                 /* virtual-textured: vt holds its samples' figures */
    render_vt_stats vt;           /* misses and upload bytes summed over its samples, the rest at the last */
    size_t path_frames;         /* F of its camera path (run/path_timing.h), 0: still */
    double *frame_ns;           /* a path configuration: the timing pass of mscene_session times
                                   each of its frames here (`frames` entries); NULL: still */
    double *path_ns;            /* its replays so far, row = replay (cap × path_frames) */
} mconf;

typedef struct mscene {
    const measure_job *job;
    gl_context *gl;
    render_ctx *r;
    counters_context *cc;
    store *st;
    const char **timing;        /* enabled counters by kind */
    size_t n_timing;
    const char **statistic;
    size_t n_statistic;
    int stop_index;             /* timing[] index of the counter that stops sampling, -1: none */
    size_t n_rounds;            /* rounds recorded by this process (the index of the next) */
    protocol_desc pd;           /* the measuring decisions' settings (run/protocol.h) */
    target rt;                  /* the scene's render target (one resolution per scene) */
    float *ref_rgba, *ref_depth;   /* scene reference, rendered on first use */
    char *ref_path;
} mscene;

/* One line to the job's report_fd (nothing when it is -1). */
void mscene_say(const measure_job *job, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Creates the process's GL context, renderer (program cache in
 * job->cache_dir), counters context (DMBENCH_HIDE_EXTENSIONS honoured) and
 * store, and sorts the sweep's counters into timed and statistics ones.
 * Returns 0, or DM_ERR_* with the reason in err. */
int mscene_setup(mscene *m, dm_str *err);
/* Frees cs[0..n) and everything mscene_setup made. */
void mscene_teardown(mscene *m, mconf *cs, size_t n);

/* Marks c failed with the first reason given; it stops sampling. */
void mscene_fail(mconf *c, const char *reason);
/* Draws `frames` frames of c's item into the scene's target. */
void mscene_frames(mscene *m, mconf *c, int frames);
/* Draws frame `frame` of c's item (its camera path's view) into the
 * scene's target, unfinished: the Instructions pass counts a path's frames
 * one at a time, each with its glFinish (run/count_child.c). */
void mscene_frame_at(mscene *m, mconf *c, int frame);
/* One glFinish-fenced sample of `frames` frames without counters: ns/frame. */
double mscene_plain_sample(mscene *m, mconf *c, int frames);
/* One counter session over names[0..n), `frames` frames a pass: values[i]
 * per frame, NaN (and reasons[i], when given) where unavailable.  With
 * c->frame_ns set, the timing pass finishes the GL work of each frame and
 * times it on its own into c->frame_ns[0..frames) (NaN when no timing pass
 * ran). */
int mscene_session(mscene *m, mconf *c, const char **names, size_t n, int frames, double *values,
                   char **reasons);

/* Why the stages of an item cannot be isolated (docs/counters.md), or NULL. */
const char *mscene_isolation_problem(const render_item_info *info);
/* The raster pass's item (MinimalShadingTime) when the sweep asks for it;
 * else c->min_why says why there is none. */
void mscene_prepare_minimal(mscene *m, mconf *c);
/* The LoopTrips pass's item when names[0..n) ask for LoopTrips or FragmentGroups. */
void mscene_prepare_trips(mscene *m, mconf *c, const char *const *names, size_t n);

/* The path of image `name` of the job's run (run_dir/img/NAME; caller frees). */
char *mscene_img_path(const measure_job *job, const char *name);
/* Draws a virtual-textured item until a frame loads no page (at most 64
 * frames); nothing for an item without a virtual texture. */
void mscene_vt_converge(struct render_ctx *r, render_item item, int w, int h);
/* Renders one configuration into a float image (w*h*4, row 0 top);
 * supersample >= 1 renders at that multiple and box-filters down.  A
 * virtual-textured configuration is first converged (mscene_vt_converge),
 * so its image does not depend on earlier draws.  Used for quality
 * references and images, and `dmbench render`. */
int mscene_render_image(struct render_ctx *r, const dm_kv *params, size_t n_params, int w, int h,
                        int supersample, float **rgba, float **depth, dm_str *log);
/* mscene_render_image of frame `frame` of the configuration (its orbits
 * turned and its camera.path followed to that frame; render_set_frame). */
int mscene_render_frame(struct render_ctx *r, const dm_kv *params, size_t n_params, int w, int h,
                        int supersample, uint64_t frame, float **rgba, float **depth, dm_str *log);

#endif
