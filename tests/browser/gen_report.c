/* gen_report.c — writes the synthetic fixture run (tests/test_reports_fixture.h)
 * with its images into DIR, for the browser test.  Usage: gen_report DIR */
#include "reports/report.h"
#include "../test_reports_fixture.h"

#include <stdio.h>

int main(int argc, char **argv)
{
    char err[512] = "";
    if (argc != 2) {
        fprintf(stderr, "usage: gen_report DIR\n");
        return 2;
    }
    dm_run_result run;
    fixture_run(&run);
    int rc = fixture_images(argv[1], err, sizeof err);
    if (!rc)
        rc = report_write_run(&run, &(report_desc){.dir = argv[1]}, err, sizeof err);
    dm_run_free(&run);
    if (rc) {
        fprintf(stderr, "gen_report: %s\n", err);
        return 1;
    }
    return 0;
}
