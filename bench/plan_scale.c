/* bench_plan_scale — how long planning a sweep file takes (no GL, no
 * measuring): parse time, plan time, combinations and configurations.
 * Usage: bench_plan_scale SWEEP.yaml...   Figures only; run by hand. */
#include "core/dm_util.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

#include <stdio.h>

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        sweep s;
        plan p;
        dm_str err = {0};
        int64_t t0 = dm_now_ns();
        if (sweep_load(argv[i], &s, &err) != 0) {
            fprintf(stderr, "%s\n", dm_str_get(&err));
            return 2;
        }
        int64_t t1 = dm_now_ns();
        int rc = plan_build(&s, NULL, &p, &err);
        int64_t t2 = dm_now_ns();
        printf("%s: parse %.2f s, plan %.2f s: %zu combinations -> %zu configurations%s%s\n",
               argv[i], (t1 - t0) / 1e9, (t2 - t1) / 1e9, p.n_combinations, p.n_configs,
               rc ? "; " : "", rc ? dm_str_get(&err) : "");
        plan_free(&p);
        sweep_free(&s);
        dm_str_free(&err);
    }
    return 0;
}
