/* gen_report.c — writes the synthetic fixture run (tests/test_reports_fixture.h)
 * with its images into DIR, for the browser test, its first configuration's
 * heatmap its FLIP map (as runs write it) and a camera path's frame
 * times, its quality along the path and a filmstrip of three frames (0, 20
 * and 40, each with its reference and FLIP map: nine images of distinct
 * colours); and DIR/scale.txt, the words
 * every FLIP map's legend states its scale in (FLIP_SCALE_TEXT).  Usage:
 * gen_report DIR */
#include "reports/report.h"
#include "imaging/flip.h"
#include "../test_reports_fixture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The filmstrip's nine images: frames 0, 20, 40 of configuration 0 ×
 * (frame, reference, FLIP map), as a run names them, into q's shots and
 * written under dir, each an 8×8 image of its own colour. */
static int gen__film(const char *dir, dm_path_quality *q, char *err, size_t errlen)
{
    static const char *const fmt[3] = {"img/" FIXTURE_KEY0 "-path-f%03ld.png",
                                       "img/ref-0badf00d-f%03ld.png",
                                       "img/" FIXTURE_KEY0 "-path-f%03ld-flip.png"};
    img im = {0};
    int rc = img_alloc(&im, 8, 8);
    q->n_shots = 3;
    q->shots = dm_xcalloc(3, sizeof *q->shots);
    for (size_t i = 0; i < 3 && !rc; i++) {
        dm_path_shot *sh = &q->shots[i];
        sh->frame = 20 * (long)i;
        char **names[3] = {&sh->img_test, &sh->img_ref, &sh->img_flip};
        for (size_t k = 0; k < 3 && !rc; k++) {
            *names[k] = dm_xasprintf(fmt[k], sh->frame);
            for (int p = 0; p < 64; p++) {
                im.px[p * 4 + 0] = (float)i / 2.0f;
                im.px[p * 4 + 1] = (float)k / 2.0f;
                im.px[p * 4 + 2] = 0.5f;
                im.px[p * 4 + 3] = 1.0f;
            }
            char *path = dm_xasprintf("%s/%s", dir, *names[k]);
            rc = img_save(&im, path, err, errlen);
            free(path);
        }
    }
    img_free(&im);
    return rc;
}

int main(int argc, char **argv)
{
    char err[512] = "";
    if (argc != 2) {
        fprintf(stderr, "usage: gen_report DIR\n");
        return 2;
    }
    dm_run_result run;
    fixture_run(&run);
    dm_config_result *c = &run.configs[0];
    c->img_flip = dm_xstrdup(c->img_heatmap);
    c->quality.flip = 0.0452;
    c->quality.flip_max = 0.519;
    c->quality.flip_ppd = FLIP_DEFAULT_PPD;
    /* its camera path: 60 frames x 3 replays, a slow stretch and a stutter
     * at frame 41 ("Along the path") */
    dm_path_series *p = &c->path;
    p->frames = 60;
    p->replays = 3;
    p->frame_ns = dm_xcalloc(p->frames * p->replays, sizeof *p->frame_ns);
    for (size_t k = 0; k < p->replays; k++)
        for (size_t f = 0; f < p->frames; f++)
            p->frame_ns[k * p->frames + f] = (f == 41 ? 9e6 : 2e6 + 1e4 * (double)f) * (1 + 0.02 * (double)k);
    p->p50 = 2.3e6;
    p->p95 = 2.6e6;
    p->p99 = 6.2e6;
    p->low1_ns = 9.18e6;
    p->low1_fps = 1e9 / p->low1_ns;
    p->n_stutters = 1;
    p->stutter_at = dm_xcalloc(1, sizeof *p->stutter_at);
    p->stutter_at[0] = 41;
    p->replay_spread = 0.04;
    /* and its quality at every 20th frame */
    dm_path_quality *q = &c->path_quality;
    static const double flip[] = {0.05, 0.21, 0.07}, ssim[] = {0.93, 0.71, 0.9};
    *q = (dm_path_quality){.present = 1, .frames = 60, .every = 20, .n = 3, .temporal_mean = 0.012,
                           .temporal_p99 = 0.08, .popping = 0.16, .popping_frame = 20};
    q->flip = dm_xmalloc(sizeof flip);
    q->ssim = dm_xmalloc(sizeof ssim);
    memcpy(q->flip, flip, sizeof flip);
    memcpy(q->ssim, ssim, sizeof ssim);
    q->img_temporal = dm_xstrdup(c->img_heatmap);
    int rc = fixture_images(argv[1], err, sizeof err);
    if (!rc)
        rc = gen__film(argv[1], q, err, sizeof err);
    if (!rc) {
        char *path = dm_xasprintf("%s/scale.txt", argv[1]);
        rc = dm_write_file(path, FLIP_SCALE_TEXT, sizeof FLIP_SCALE_TEXT - 1);
        if (rc)
            snprintf(err, sizeof err, "cannot write %s", path);
        free(path);
    }
    if (!rc)
        rc = report_write_run(&run, &(report_desc){.dir = argv[1]}, err, sizeof err);
    dm_run_free(&run);
    if (rc) {
        fprintf(stderr, "gen_report: %s\n", err);
        return 1;
    }
    return 0;
}
