/* mpath_quality.c — quality along a camera path and the cached reference
 * frame (see mpath_quality.h). */
#include "run/mpath_quality.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_image.h"
#include "imaging/flip.h"
#include "imaging/quality.h"
#include "imaging/temporal.h"
#include "run/refcache.h"
#include "techniques/axes.h"

long mpath_quality_every(long frames, long every)
{
    if (frames < 2 || every < 0 || every > frames - 1)
        return 0;
    return every == 0 ? frames - 1 : every;
}

size_t mpath_quality_count(long frames, long k)
{
    return k < 1 || frames < 1 ? 0 : (size_t)((frames - 1) / k) + 1;
}

size_t mpath_quality_shown(long frames, long k, size_t cap, long *out)
{
    size_t n = mpath_quality_count(frames, k);
    if (n == 0 || cap == 0)
        return 0;
    if (n <= cap || cap == 1) {
        size_t m = n <= cap ? n : 1;
        for (size_t i = 0; i < m; i++)
            out[i] = (long)i * k;
        return m;
    }
    /* round(j (n-1) / (cap-1)) in integers; the step is over 1, so distinct */
    uint64_t num = (uint64_t)(n - 1), den = (uint64_t)(cap - 1);
    for (size_t j = 0; j < cap; j++)
        out[j] = (long)((2 * (uint64_t)j * num + den) / (2 * den)) * k;
    return cap;
}

/* The value of axis name in params, else the axis default, as a long. */
static long mpath__axis_long(const dm_kv *p, size_t n, const char *name)
{
    const char *v = dm_kv_get(p, n, name);
    const axis_info *a = axes_find(name);
    return strtol(v ? v : a && a->def ? a->def : "0", NULL, 10);
}

int mpath_quality_wanted(const dm_kv *params, size_t n)
{
    const char *path = dm_kv_get(params, n, "camera.path");
    return (path && strcmp(path, "still") != 0) || mpath__axis_long(params, n, "camera.path_ref_every") != 0;
}

int mpath_reference_frame(mscene *m, const dm_kv *p, size_t n, int w, int h, int on_path,
                          uint64_t frame, float **rgba, float **depth, const char **source,
                          dm_str *log)
{
    const sweep *s = m->job->sweep;
    const char *renderer = (const char *)glGetString(GL_RENDERER), *version = (const char *)glGetString(GL_VERSION);
    char *driver = dm_xasprintf("%s | %s", renderer ? renderer : "?", version ? version : "?");
    refcache_desc d = {.params = p, .n_params = n, .width = w, .height = h,
                       .supersample = s->supersample, .driver = driver, .on_path = on_path,
                       .frame = frame};
    char *dir = m->job->cache_dir ? refcache_dir() : NULL;
    dm_str key = {0};
    int keyed = dir && refcache_key(&d, &key) == 0, rc = 0;
    const char *src = "cache";
    float *d_px = NULL;          /* the cache stores depth whether the caller wants it or not */
    if (!keyed || refcache_load(dir, dm_str_get(&key), w, h, rgba, &d_px) != 0) {
        src = "rendered";
        rc = mscene_render_frame(m->r, p, n, w, h, s->supersample, on_path ? frame : 0, rgba, &d_px, log);
        if (rc == 0 && keyed && refcache_store(dir, dm_str_get(&key), w, h, *rgba, d_px) != 0)
            dm_log(DM_LOG_WARN, "cannot write the reference cache in %s", dir);
    }
    if (depth && rc == 0)
        *depth = d_px;
    else
        free(d_px);
    if (source)
        *source = src;
    dm_str_free(&key);
    free(dir);
    free(driver);
    return rc;
}

/* The temporal map (luminance change per step, R of map) through FLIP's
 * ramp with MPATH_TEMPORAL_MAP_TOP at its top, as img/<key>-temporal.png;
 * a pixel with no finite step is drawn at the top (broken there, not
 * still).  The path relative to the run directory, or NULL. */
static char *mpath__save_map(mscene *m, mconf *c, const img *map)
{
    size_t np = (size_t)map->w * (size_t)map->h;
    float *v = dm_xmalloc(np * sizeof *v);
    for (size_t i = 0; i < np; i++) {
        float e = map->px[4 * i];
        v[i] = isfinite(e) ? (float)(e / MPATH_TEMPORAL_MAP_TOP) : 1.0f;
    }
    char name[96], err[256];
    snprintf(name, sizeof name, "%s-temporal.png", c->pc->key);
    char *path = mscene_img_path(m->job, name), *rel = NULL;
    if (flip_map_save(v, map->w, map->h, path, err, sizeof err) == 0)
        rel = dm_xasprintf("img/%s", name);
    else
        dm_str_printf(&c->log, "temporal error map not written: %s\n", err);
    free(path);
    free(v);
    return rel;
}

/* Renders frame `frame` of the configuration and of the reference into
 * test and ref; FLIP mean and SSIM of the pair into *flip and *ssim (NaN
 * where not computed), FLIP's map into map (w*h) when given.  0, or the
 * renderer's error (reason in c's log). */
static int mpath__frame(mscene *m, mconf *c, const dm_kv *ref_p, size_t n_ref, uint64_t frame,
                        img *test, img *ref, double *flip, double *ssim, size_t *cached, float *map)
{
    const char *source = NULL;
    int w = c->pc->width, h = c->pc->height;
    *test = (img){w, h, NULL};
    *ref = (img){w, h, NULL};
    int rc = mscene_render_frame(m->r, c->pc->params, c->pc->n_params, w, h, 1, frame, &test->px,
                                 NULL, &c->log);
    if (rc == 0)
        rc = mpath_reference_frame(m, ref_p, n_ref, w, h, 1, frame, &ref->px, NULL, &source, &c->log);
    if (rc != 0) {
        img_free(test);
        img_free(ref);
        return rc;
    }
    *cached += strcmp(source, "cache") == 0;
    flip_desc d = flip_defaults(&(flip_desc){ .ppd = m->job->sweep->flip_ppd });
    flip_stats st;
    *flip = flip_compare(ref, test, &d, &st, map) == 0 ? st.mean : NAN;
    if (quality_ssim(ref, test, ssim) != 0)
        *ssim = NAN;
    return 0;
}

/* Saves frame `frame`'s image im, or FLIP map map when given (im gives its
 * size), as img/<stem>-fNNN<suffix>.png.  Its path relative to the run
 * directory, or NULL with the reason in c's log.  With keep, a file the
 * run already has is kept: a reference frame shared by configurations with
 * the same reference is written once. */
static char *mpath__save(mscene *m, mconf *c, const char *stem, long frame, const char *suffix,
                         const img *im, const float *map, int keep)
{
    char name[128], err[256] = "";
    snprintf(name, sizeof name, "%s-f%03ld%s.png", stem, frame, suffix);
    char *path = mscene_img_path(m->job, name), *rel = NULL;
    int rc = 0;
    if (!keep || !dm_file_exists(path))
        rc = map ? flip_map_save(map, im->w, im->h, path, err, sizeof err)
                 : img_save(im, path, err, sizeof err);
    if (rc == 0)
        rel = dm_xasprintf("img/%s", name);
    else
        dm_str_printf(&c->log, "frame %ld of the path: image %s not written: %s\n", frame, name, err);
    free(path);
    return rel;
}

/* The filmstrip's images of frame `frame` (docs/motion.md, "In the
 * report"): the configuration's frame as img/<key>-path-fNNN.png, the
 * reference frame as img/<ref_stem>-fNNN.png and their FLIP map as
 * img/<key>-path-fNNN-flip.png (map NULL: FLIP was not computed, no map),
 * into a new shot of pq. */
static void mpath__shoot(mscene *m, mconf *c, const char *ref_stem, long frame, const img *test,
                         const img *ref, const float *map, dm_path_quality *pq)
{
    dm_path_shot *sh = dm_vec_push(&pq->shots, &pq->n_shots, NULL, sizeof *pq->shots);
    char stem[96];
    snprintf(stem, sizeof stem, "%s-path", c->pc->key);
    sh->frame = frame;
    sh->img_test = mpath__save(m, c, stem, frame, "", test, NULL, 0);
    sh->img_ref = mpath__save(m, c, ref_stem, frame, "", ref, NULL, 1);
    if (map)
        sh->img_flip = mpath__save(m, c, stem, frame, "-flip", test, map, 0);
}

/* The temporal error and map of the steps in acc (released here), and the
 * popping of the per-frame FLIP, into pq. */
static void mpath__summarise(mscene *m, mconf *c, temporal_acc *acc, dm_path_quality *pq)
{
    temporal_stats ts;
    img map = {0};
    if (temporal_acc_finish(acc, &ts, &map) == 0) {
        pq->temporal_mean = ts.mean;
        pq->temporal_p99 = ts.p99;
        pq->img_temporal = mpath__save_map(m, c, &map);
    }
    img_free(&map);
    size_t at = 0;
    pq->popping = temporal_popping(pq->flip, pq->n, &at);
    pq->popping_frame = isfinite(pq->popping) ? (long)at * pq->every : -1;
}

/* The stem of c's reference frames' images: "ref-" and 8 hex digits of a
 * hash of the reference's parameters (ref[0..n)) and size, as the still
 * reference is img/ref-<hash>.png.  The scene alone, the still rule's
 * key for a shared reference technique, does not hold the path, so the
 * parameters are hashed: configurations whose reference renders the same
 * frames share the files (into stem, 16 bytes). */
static void mpath__ref_stem(const mconf *c, const dm_kv *ref, size_t n, char stem[16])
{
    uint64_t h = DM_FNV_SEED;
    for (size_t i = 0; i < n; i++) {
        h = dm_fnv1a64(ref[i].key, strlen(ref[i].key) + 1, h);
        h = dm_fnv1a64(ref[i].value, strlen(ref[i].value) + 1, h);
    }
    int wh[2] = { c->pc->width, c->pc->height };
    h = dm_fnv1a64(wh, sizeof wh, h);
    snprintf(stem, 16, "ref-%08llx", (unsigned long long)(h & 0xffffffffULL));
}

/* Frames 0, K, 2K, ... of the configuration and the reference, compared as
 * they come: two frames of each are held at a time (the temporal error
 * takes each step as it is made), and the frames in shown[0..n_shown)
 * written as images as they pass.  0, or the first error with *failed the
 * frame it came at. */
static int mpath__frames(mscene *m, mconf *c, const dm_kv *ref, size_t n_ref, temporal_acc *acc,
                         dm_path_quality *pq, const long *shown, size_t n_shown, size_t *cached,
                         long *failed)
{
    img prev_t = {0}, prev_r = {0};
    char stem[16];
    mpath__ref_stem(c, ref, n_ref, stem);
    float *map = dm_xmalloc((size_t)c->pc->width * (size_t)c->pc->height * sizeof *map);
    size_t next = 0;   /* the next of shown[] to write */
    int rc = 0;
    for (size_t i = 0; i < pq->n && rc == 0; i++) {
        img t, r;
        uint64_t frame = (uint64_t)i * (uint64_t)pq->every;
        int shoot = next < n_shown && shown[next] == (long)frame;
        *failed = (long)frame;
        rc = mpath__frame(m, c, ref, n_ref, frame, &t, &r, &pq->flip[i], &pq->ssim[i], cached,
                          shoot ? map : NULL);
        if (rc != 0)
            break;
        if (shoot) {
            mpath__shoot(m, c, stem, (long)frame, &t, &r, isfinite(pq->flip[i]) ? map : NULL, pq);
            next++;
        }
        if (i > 0)
            rc = temporal_acc_step(acc, &prev_t, &t, &prev_r, &r);
        img_free(&prev_t);
        img_free(&prev_r);
        prev_t = t;
        prev_r = r;
    }
    img_free(&prev_t);
    img_free(&prev_r);
    free(map);
    return rc;
}

void mpath_quality_measure(mscene *m, mconf *c, const dm_kv *ref, size_t n_ref,
                           dm_config_result *out)
{
    dm_path_quality *pq = &out->path_quality;
    const dm_kv *p = c->pc->params;
    size_t np = c->pc->n_params;
    long asked = mpath__axis_long(p, np, "camera.path_ref_every");
    pq->frames = mpath__axis_long(p, np, "camera.path_frames");
    pq->every = mpath_quality_every(pq->frames, asked);
    pq->temporal_mean = pq->temporal_p99 = pq->popping = NAN;
    pq->popping_frame = -1;
    if (pq->every == 0) {
        pq->reason = dm_xasprintf("camera.path_ref_every=%ld: a pass of %ld frames has no second "
                                  "reference frame (K must be 0 or 1 to %ld)", asked, pq->frames,
                                  pq->frames - 1);
        return;
    }
    size_t n = mpath_quality_count(pq->frames, pq->every), cached = 0;
    pq->flip = dm_xcalloc(n, sizeof *pq->flip);
    pq->ssim = dm_xcalloc(n, sizeof *pq->ssim);
    pq->n = n;
    temporal_acc acc;
    long failed = 0, shown[MPATH_SHOTS_MAX];
    size_t n_shown = mpath_quality_shown(pq->frames, pq->every, MPATH_SHOTS_MAX, shown);
    int rc = temporal_acc_init(&acc, c->pc->width, c->pc->height);
    if (rc == 0)
        rc = mpath__frames(m, c, ref, n_ref, &acc, pq, shown, n_shown, &cached, &failed);
    if (rc == 0) {
        mpath__summarise(m, c, &acc, pq);
        pq->present = 1;
        dm_str_printf(&c->log, "quality along the path: %zu reference frames (every %ld of %ld), %zu "
                      "of them from the reference cache; %zu written as images\n", n, pq->every,
                      pq->frames, cached, pq->n_shots);
    } else {
        temporal_stats unused;
        temporal_acc_finish(&acc, &unused, NULL);
        pq->reason = dm_xasprintf("frame %ld of the path: %s (the log says why)", failed,
                                  dm_strerror(rc));
    }
}
