/* mquality.c — a measured configuration's image and its quality against
 * the scene's reference (see mquality.h). */
#include "run/mquality.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/quality.h"
#include "run/mpath_quality.h"

/* Sets the sweep's quality.reference axis values (e.g. normal_format) over
 * the reference's parameters *p, replacing the scene's or configuration's. */
static void mquality__reference_overrides(const sweep *s, dm_kv **p, size_t *n)
{
    for (size_t i = 0; i < s->n_ref_params; i++) {
        const dm_kv *o = &s->ref_params[i];
        size_t k = 0;
        while (k < *n && strcmp((*p)[k].key, o->key) != 0)
            k++;
        if (k == *n) {
            dm_kv_push(p, n, o->key, o->value);
            continue;
        }
        free((*p)[k].value);
        (*p)[k].value = dm_xstrdup(o->value);
    }
}

/* The parameters of c's reference into *p (caller frees with dm_kv_free). */
static void mquality__reference_params(const mscene *m, const mconf *c, dm_kv **p, size_t *n)
{
    const sweep *s = m->job->sweep;
    int per_config = !s->ref_technique || strcmp(s->ref_technique, "same") == 0;
    /* The reference technique renders the scene as the sweep defines it
     * (all scene axes, whether this configuration's technique reads them or
     * not); "same" renders the configuration itself. */
    if (per_config) {
        for (size_t i = 0; i < c->pc->n_params; i++)
            dm_kv_push(p, n, c->pc->params[i].key, c->pc->params[i].value);
    } else {
        for (size_t i = 0; i < c->pc->n_params; i++)
            if (!dm_kv_get(c->pc->scene_params, c->pc->n_scene_params, c->pc->params[i].key) &&
                strcmp(c->pc->params[i].key, "technique") != 0)
                dm_kv_push(p, n, c->pc->params[i].key, c->pc->params[i].value);
        for (size_t i = 0; i < c->pc->n_scene_params; i++)
            dm_kv_push(p, n, c->pc->scene_params[i].key, c->pc->scene_params[i].value);
        dm_kv_push(p, n, "technique", s->ref_technique);
        /* The ground truth samples plain textures: a virtual-texture
         * configuration is compared with the same maps unpaged, whichever
         * configuration of the scene this process measures first. */
        for (size_t i = 0; i < *n; i++)
            if (strcmp((*p)[i].key, "virtual_texture") == 0) {
                free((*p)[i].value);
                (*p)[i].value = dm_xstrdup("off");
            }
    }
    mquality__reference_overrides(s, p, n);
}

/* Renders the scene reference once (per process) for configuration c, of
 * the reference parameters p[0..n). */
static int mquality__reference(mscene *m, mconf *c, const dm_kv *p, size_t n)
{
    const sweep *s = m->job->sweep;
    int per_config = !s->ref_technique || strcmp(s->ref_technique, "same") == 0;
    if (m->ref_rgba && !per_config)
        return 0;                      /* one reference technique: one image per scene */
    free(m->ref_rgba);
    free(m->ref_depth);
    free(m->ref_path);
    m->ref_rgba = m->ref_depth = NULL;
    m->ref_path = NULL;
    int rc = mpath_reference_frame(m, p, n, c->pc->width, c->pc->height, 0, 0, &m->ref_rgba,
                                   &m->ref_depth, &c->ref_source, &c->log);
    if (rc == 0) {
        char name[64];
        const char *id = per_config ? c->pc->key : c->pc->scene;
        snprintf(name, sizeof name, "ref-%08llx.png",
                 (unsigned long long)(dm_fnv1a64(id, strlen(id), DM_FNV_SEED) & 0xffffffffULL));
        m->ref_path = dm_xstrdup(name);
        char *path = mscene_img_path(m->job, name);
        img im = { c->pc->width, c->pc->height, m->ref_rgba };
        char e[256];
        img_save(&im, path, e, sizeof e);
        free(path);
    }
    return rc;
}

/* FLIP of test against ref at the sweep's pixels per degree, and its map on
 * the fixed [0,1] scale (img/<key>-flip.png).  FLIP fields stay NaN ("not
 * computed") when it cannot be computed. */
static void mquality__flip(mscene *m, mconf *c, const img *ref, const img *test, dm_config_result *out)
{
    dm_quality *q = &out->quality;
    q->flip = q->flip_q1 = q->flip_median = q->flip_q3 = q->flip_max = q->flip_ppd = NAN;
    float *map = dm_xmalloc((size_t)ref->w * (size_t)ref->h * sizeof *map);
    flip_desc d = flip_defaults(&(flip_desc){ .ppd = m->job->sweep->flip_ppd });
    flip_stats st;
    if (flip_compare(ref, test, &d, &st, map) == 0) {
        q->flip = st.mean;
        q->flip_q1 = st.q1;
        q->flip_median = st.median;
        q->flip_q3 = st.q3;
        q->flip_max = st.max;
        q->flip_ppd = d.ppd;
        char e[256], name[64];
        snprintf(name, sizeof name, "%s-flip.png", c->pc->key);
        char *path = mscene_img_path(m->job, name);
        if (flip_map_save(map, ref->w, ref->h, path, e, sizeof e) == 0)
            out->img_flip = dm_xasprintf("img/%s", name);
        free(path);
    }
    free(map);
}

/* Image, quality and heatmap of a configuration against the scene reference. */
void mquality_measure(mscene *m, mconf *c, dm_config_result *out)
{
    int w = c->pc->width, h = c->pc->height;
    float *rgba = NULL, *depth = NULL;
    if (mscene_render_image(m->r, c->pc->params, c->pc->n_params, w, h, 1, &rgba, &depth, &c->log) != 0)
        return;
    img test = { w, h, rgba };
    char e[256], name[64];
    snprintf(name, sizeof name, "%s.png", c->pc->key);
    char *path = mscene_img_path(m->job, name);
    if (img_save(&test, path, e, sizeof e) == 0)
        out->img_render = dm_xasprintf("img/%s", name);
    free(path);
    dm_kv *rp = NULL;
    size_t nrp = 0;
    mquality__reference_params(m, c, &rp, &nrp);
    if (mquality__reference(m, c, rp, nrp) == 0) {
        img ref = { w, h, m->ref_rgba };
        img_metrics mt;
        dm_quality *q = &out->quality;
        if (img_compare(&ref, &test, 0.05, &mt) == 0) {
            q->present = 1;
            q->rmse = mt.rmse;
            q->psnr = mt.psnr;
            q->max_error = mt.max_error;
            q->pct_over_threshold = mt.pct_over;
        }
        quality_ssim(&ref, &test, &q->ssim);
        mquality__flip(m, c, &ref, &test, out);
        size_t np = (size_t)w * (size_t)h;
        unsigned char *ma = dm_xmalloc(np), *mb = dm_xmalloc(np);
        quality_coverage(&ref, ma);
        quality_coverage(&test, mb);
        q->silhouette_error = quality_silhouette_error(ma, mb, np);
        quality_depth_rmse(m->ref_depth, depth, ma, mb, np, &q->depth_rmse);
        q->crack_pixels = quality_crack_pixels(mb, w, h);
        q->nonfinite_pixels = quality_nonfinite_pixels(&test);
        const sweep *sw = m->job->sweep;
        const char *rt = sw->ref_technique;
        dm_str over = {0};
        for (size_t i = 0; i < sw->n_ref_params; i++)
            dm_str_printf(&over, "%s%s=%s", i ? " " : " (", sw->ref_params[i].key, sw->ref_params[i].value);
        q->reference = dm_xasprintf("%s%s%s, %dx supersampled",
                                    !rt || strcmp(rt, "same") == 0 ? "same configuration" : rt,
                                    dm_str_get(&over), sw->n_ref_params ? ")" : "", sw->supersample);
        dm_str_free(&over);
        free(ma);
        free(mb);
        /* The heatmap is the FLIP map: FLIP's fixed [0,1] scale is bounded
         * and perceptual, so no map saturates and a small difference is not
         * black, and it is the map `dmbench diff --heatmap` writes.  Both
         * keys name the one file, so older readers find a heatmap. */
        if (out->img_flip)
            out->img_heatmap = dm_xstrdup(out->img_flip);
        out->img_reference = dm_xasprintf("img/%s", m->ref_path);
    }
    /* the still figures above are frame 0's, as before paths; along a path
     * its frames against reference frames (mpath_quality.h) */
    if (mpath_quality_wanted(c->pc->params, c->pc->n_params))
        mpath_quality_measure(m, c, rp, nrp, out);
    dm_kv_free(rp, nrp);
    free(rgba);
    free(depth);
}

