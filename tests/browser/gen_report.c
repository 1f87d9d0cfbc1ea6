/* gen_report.c — writes the synthetic fixture run (tests/test_reports_fixture.h)
 * with its images into DIR, for the browser test, its first configuration's
 * heatmap its FLIP map (as runs write it); and DIR/scale.txt, the words
 * every FLIP map's legend states its scale in (FLIP_SCALE_TEXT).  Usage:
 * gen_report DIR */
#include "reports/report.h"
#include "imaging/flip.h"
#include "../test_reports_fixture.h"

#include <stdio.h>
#include <stdlib.h>

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
    int rc = fixture_images(argv[1], err, sizeof err);
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
