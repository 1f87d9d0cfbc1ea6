/* path_timing.c — a configuration on a camera path, timed frame by frame
 * (see path_timing.h). */
#include "run/path_timing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/frame_series.h"
#include "techniques/axes.h"

size_t path_timing_frames(const plan_config *pc)
{
    const char *path = dm_kv_get(pc->params, pc->n_params, "camera.path");
    if (!path || strcmp(path, "still") == 0)
        return 0;
    const char *f = dm_kv_get(pc->params, pc->n_params, "camera.path_frames");
    if (!f) {   /* the default is left out of the parameters */
        const axis_info *a = axes_find("camera.path_frames");
        f = a ? a->def : NULL;
    }
    long n = f ? strtol(f, NULL, 10) : 0;
    return n >= 2 ? (size_t)n : 2;   /* the renderer's own floor (render.c) */
}

void path_timing_prepare(mscene *m, mconf *c)
{
    c->path_frames = path_timing_frames(c->pc);
    if (!c->path_frames)
        return;
    c->frames = (int)c->path_frames;
    mscene_frames(m, c, c->frames);
    c->frame_ns = dm_xcalloc(c->path_frames, sizeof *c->frame_ns);
    c->path_ns = dm_xcalloc((c->cap ? c->cap : 1) * c->path_frames, sizeof *c->path_ns);
}

void path_timing_room(mconf *c)
{
    if (c->path_frames)
        c->path_ns = dm_xrealloc(c->path_ns, c->cap * c->path_frames * sizeof *c->path_ns);
}

void path_timing_record(const mscene *m, mconf *c, double *vals)
{
    if (!c->path_frames)
        return;
    double sum = 0;
    size_t n = 0;
    for (size_t f = 0; f < c->path_frames; f++) {
        double t = c->frame_ns[f];
        c->path_ns[c->n_samples * c->path_frames + f] = t;
        if (isfinite(t)) {
            sum += t;
            n++;
        }
    }
    for (size_t i = 0; i < m->n_timing; i++)
        if (strcmp(m->timing[i], "WallTime") == 0)
            vals[i] = n ? sum / (double)n : NAN;
}

/* models/frame_series' summary of p's series into p; NaN and "unknown"
 * noise when no frame time is finite. */
static void path_timing__summarize(dm_path_series *p)
{
    size_t *at = dm_xcalloc(p->frames, sizeof *at);
    frame_series_stats fs;
    if (frame_series_summarize(p->frame_ns, p->replays, p->frames, at, &fs) != 0) {
        p->p50 = p->p95 = p->p99 = p->low1_ns = p->low1_fps = p->replay_spread = NAN;
        p->noisy = -1;
        p->stutter_at = dm_xcalloc(1, sizeof *p->stutter_at);
        free(at);
        return;
    }
    p->p50 = fs.p50;
    p->p95 = fs.p95;
    p->p99 = fs.p99;
    p->low1_ns = fs.low1_ns;
    p->low1_fps = fs.low1_fps;
    p->replay_spread = fs.replay_spread;
    p->noisy = fs.noisy;
    p->n_stutters = fs.stutters;
    p->stutter_at = dm_xcalloc(fs.stutters + 1, sizeof *p->stutter_at);
    for (size_t i = 0; i < fs.stutters; i++)
        p->stutter_at[i] = (long)at[i];
    free(at);
}

void path_timing_collect(const mconf *c, dm_config_result *out)
{
    if (!c->path_frames || !c->n_samples)
        return;
    size_t n = c->n_samples * c->path_frames;
    out->path.frames = c->path_frames;
    out->path.replays = c->n_samples;
    out->path.frame_ns = dm_xmalloc(n * sizeof *out->path.frame_ns);
    memcpy(out->path.frame_ns, c->path_ns, n * sizeof *out->path.frame_ns);
    path_timing__summarize(&out->path);
}
