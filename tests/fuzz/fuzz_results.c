/* libFuzzer target: results.json as `dmbench compare` reads it.  Any input
 * is loaded or refused without crashing; a loaded file compared with
 * itself gives a finite positive geometric mean whenever it timed anything
 * (no "-nan" from negative or mistyped times). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gate/compare.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, "results", "json");
    dm_run_result run;
    dm_str err = {0};
    if (compare_load_path(path, &run, &err) == 0) {
        compare_desc d = { .allow_env_mismatch = 1 };
        compare_result r;
        dm_str e2 = {0};
        if (compare_runs(&run, &run, &d, &r, &e2) == 0 && r.n_geomean &&
            !(isfinite(r.geomean) && r.geomean > 0))
            abort();
        compare_result_free(&r);
        dm_str_free(&e2);
        dm_run_free(&run);
    } else if (!err.len) {
        abort();
    }
    dm_str_free(&err);
    return 0;
}
