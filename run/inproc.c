/* inproc.c — counts measured in the calling process, without a child:
 * the invocation counts `dmbench predict` reads (see inproc.h). */
#include "run/inproc.h"

#include <math.h>

#include "run/mscene.h"

int inproc_counts(const plan_config *cs, size_t n, const char *const *names, size_t n_names, double *values,
                  dm_str *err)
{
    sweep none = {0};
    measure_job job = { .sweep = &none, .configs = cs, .n_configs = n, .report_fd = -1 };
    mscene m = { .job = &job };
    int rc = gl_context_create(NULL, &m.gl, err);
    rc = rc ? rc : render_create(&m.r);
    rc = rc ? rc : counters_context_create(&m.cc);
    for (size_t i = 0; i < n * n_names; i++)
        values[i] = NAN;
    for (size_t i = 0; rc == 0 && i < n; i++) {
        mconf c = { .pc = &cs[i] };
        if (render_prepare(m.r, cs[i].params, cs[i].n_params, &c.item, &c.log) == 0) {
            mscene_frames(&m, &c, 1);   /* first use (JIT) outside the counted frame */
            mscene_prepare_trips(&m, &c, names, n_names);
            mscene_vt_converge(m.r, c.item, cs[i].width, cs[i].height);
            mscene_session(&m, &c, (const char **)names, n_names, 1, values + i * n_names, NULL);
            render_release(m.r, c.item);
            if (c.item_trips.id)
                render_release(m.r, c.item_trips);
        }
        gl_context_take_messages(m.gl, NULL);
        dm_str_free(&c.log);
    }
    if (m.gl)
        target_destroy(&m.rt);
    counters_context_destroy(m.cc);
    render_destroy(m.r);
    gl_context_destroy(m.gl);
    return rc;
}

