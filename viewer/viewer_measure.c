/* viewer_measure.c — live counters, timed test, read-back (see viewer_measure.h). */
#include "viewer/viewer_measure.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "models/stats.h"

#define VIEWER__FRAMES_PER_SAMPLE 4
#define VIEWER__MIN_SAMPLES 5

const char *const viewer_counter_names[VIEWER_N_COUNTERS] = {
    "WallTime", "VSInvocations", "TESInvocations", "PrimitivesGenerated", "SamplesPassed"};

void viewer_draw(const viewer_frame *f)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (f->wireframe)
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    render_draw(f->r, f->item, f->w, f->h);
    if (f->wireframe)
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

int viewer_measure_live(counters_context *cc, const viewer_frame *f, viewer_counters *out,
                        dm_str *log)
{
    counters_session *s = NULL;
    int rc = counters_session_create(cc, &s), passes = 0;
    for (int i = 0; rc == 0 && i < VIEWER_N_COUNTERS; i++)
        rc = counters_enable(s, viewer_counter_names[i]);
    rc = rc ? rc : counters_num_passes(s, &passes);
    for (int p = 0; rc == 0 && p < passes; p++) {
        rc = counters_pass_begin(s, p);
        rc = rc ? rc : counters_sample_begin(s, 0);
        if (rc == 0)
            viewer_draw(f);
        rc = rc ? rc : counters_sample_end(s);
        rc = rc ? rc : counters_pass_end(s);
    }
    rc = rc ? rc : counters_session_end(s);
    for (int i = 0; i < VIEWER_N_COUNTERS; i++) {
        double v = NAN;
        out->value[i] = rc == 0 && counters_result(s, 0, viewer_counter_names[i], &v) == 0 ? v : NAN;
    }
    if (rc != 0)
        dm_str_printf(log, "counters: %s\n", s ? counters_last_error(s) : dm_strerror(rc));
    counters_session_destroy(s);
    return rc;
}

void viewer_counters_format(const viewer_counters *c, const char *sep_between, dm_str *out)
{
    for (int i = 0; i < VIEWER_N_COUNTERS; i++) {
        const char *sep = i ? sep_between : "";
        if (isnan(c->value[i]))
            dm_str_printf(out, "%s%s n/a", sep, viewer_counter_names[i]);
        else if (i == 0)
            dm_str_printf(out, "%s%s %.3f ms", sep, viewer_counter_names[i], c->value[i] / 1e6);
        else
            dm_str_printf(out, "%s%s %.0f", sep, viewer_counter_names[i], c->value[i]);
    }
}

/* One glFinish-fenced sample of K frames: wall ns per frame. */
static double viewer__sample(const viewer_frame *f)
{
    glFinish();
    int64_t t0 = dm_now_ns();
    for (int i = 0; i < VIEWER__FRAMES_PER_SAMPLE; i++)
        viewer_draw(f);
    glFinish();
    return (double)(dm_now_ns() - t0) / VIEWER__FRAMES_PER_SAMPLE;
}

int viewer_measure_timed(counters_context *cc, const viewer_frame *f, double seconds, dm_str *out)
{
    size_t n = 0, cap = 64;
    double *x = dm_xmalloc(cap * sizeof *x);
    viewer__sample(f);                           /* warm-up */
    int64_t t0 = dm_now_ns(), limit = (int64_t)(seconds * 1e9);
    while (n < VIEWER__MIN_SAMPLES || dm_now_ns() - t0 < limit) {
        if (n == cap)
            x = dm_xrealloc(x, (cap *= 2) * sizeof *x);
        x[n++] = viewer__sample(f);
    }
    double took = (double)(dm_now_ns() - t0) / 1e9;
    stats_summary s;
    int rc = stats_summarize(x, n, 1, &s);
    free(x);
    if (rc != 0)
        return rc;
    dm_str_printf(out, "timed: WallTime median %.0f ns/frame (%.3f ms), 95%% CI [%.0f, %.0f] ns, "
                  "cv %.3f, %zu samples x %d frames in %.1f s\n", s.median, s.median / 1e6,
                  s.ci_lo, s.ci_hi, s.cv, n, VIEWER__FRAMES_PER_SAMPLE, took);
    viewer_counters c;
    rc = viewer_measure_live(cc, f, &c, out);
    dm_str_cat(out, "timed: per frame: ");
    viewer_counters_format(&c, "  ", out);
    dm_str_cat(out, "\n");
    return rc;
}

int viewer_read_window(int w, int h, img *out)
{
    int rc = img_alloc(out, w, h);
    if (rc != 0)
        return rc;
    float *tmp = dm_xmalloc((size_t)w * (size_t)h * 4 * sizeof *tmp);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, tmp);
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h; y++)        /* GL rows are bottom-up */
        memcpy(out->px + (size_t)y * row, tmp + (size_t)(h - 1 - y) * row, row * sizeof *tmp);
    free(tmp);
    return 0;
}
