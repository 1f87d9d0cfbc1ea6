/* flip_run.c — FLIP of a stored run again at another viewing condition
 * (`dmbench report DIR --flip-ppd N`; see flip.h). */
#include "imaging/flip.h"
#include "reports/flip_run.h"
#include "reports/report_internal.h"

#include "core/dm_error.h"
#include "core/dm_util.h"

#include <stdio.h>
#include <stdlib.h>

/* One configuration: loads its render and reference from dir, computes
 * FLIP at ppd into q and writes the map as img/<key>-flip-ppd<N>.png. */
static int flip_run__config(dm_config_result *c, const char *dir, double ppd, dm_str *err)
{
    char e[512];
    img ref = {0}, test = {0};
    char *pr = dm_xasprintf("%s/%s", dir, c->img_reference), *pt = dm_xasprintf("%s/%s", dir, c->img_render);
    int rc = img_load(pr, &ref, e, sizeof e);
    rc = rc ? rc : img_load(pt, &test, e, sizeof e);
    float *map = rc ? NULL : malloc((size_t)ref.w * (size_t)ref.h * sizeof *map);
    flip_stats st;
    if (rc == 0)
        rc = map ? flip_compare(&ref, &test, &(flip_desc){ .ppd = ppd }, &st, map) : DM_ERR_NOMEM;
    if (rc == 0) {
        dm_quality *q = &c->quality;
        q->flip = st.mean, q->flip_q1 = st.q1, q->flip_median = st.median;
        q->flip_q3 = st.q3, q->flip_max = st.max, q->flip_ppd = ppd;
        char *rel = dm_xasprintf("img/%s-flip-ppd%g.png", c->key, ppd);
        char *path = dm_xasprintf("%s/%s", dir, rel);
        free(c->img_flip);
        c->img_flip = NULL;
        if (flip_map_save(map, ref.w, ref.h, path, e, sizeof e) == 0)
            c->img_flip = rel;
        else
            free(rel);
        free(path);
    } else {
        dm_str_printf(err, "configuration %s: %s", c->key, rc == DM_ERR_IO ? e : dm_strerror(rc));
    }
    free(map);
    img_free(&ref);
    img_free(&test);
    free(pr);
    free(pt);
    return rc;
}

int flip_run_recompute(dm_run_result *run, const char *dir, double ppd, dm_str *err)
{
    if (!run || !dir || !(ppd >= 1))
        return DM_ERR_ARG;
    for (size_t i = 0; i < run->n_configs; i++) {
        dm_config_result *c = &run->configs[i];
        if (!c->quality.present || !c->img_render || !c->img_reference ||
            !report__safe_relpath(c->img_render) || !report__safe_relpath(c->img_reference))
            continue;
        int rc = flip_run__config(c, dir, ppd, err);
        if (rc != 0)
            return rc;
    }
    return 0;
}
