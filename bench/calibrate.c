/* bench_calibrate — the calibration workload's own spread: N runs of it,
 * each in a fresh child as the runner does, and the spread of their
 * figures (each the shortest of 9 timings) (docs/ci-gating.md, "The calibration workload").
 *   build/bench/bench_calibrate [N]          (default 20)
 * LP_NUM_THREADS is 1 unless set, as in a run.  Prints the load average,
 * then per piece the median, min, max and the
 * largest |x / median - 1|. */
#include "run/calibrate.h"
#include "models/stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static void bench__piece(const char *name, const double *x, size_t n)
{
    double med = stats_median(x, n), lo = INFINITY, hi = -INFINITY, dev = 0;
    for (size_t i = 0; i < n; i++) {
        lo = fmin(lo, x[i]);
        hi = fmax(hi, x[i]);
        dev = fmax(dev, fabs(x[i] / med - 1));
    }
    printf("%-5s median %8.3f ms  min %8.3f  max %8.3f  largest deviation %5.1f %%\n", name,
           med / 1e6, lo / 1e6, hi / 1e6, dev * 100);
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? (size_t)strtoul(argv[1], NULL, 10) : 20;
    setenv("LP_NUM_THREADS", "1", 0);   /* as the runner measures, unless the user chose */
    n = n < 2 ? 2 : n;
    double *cpu = calloc(n, sizeof *cpu), *draw = calloc(n, sizeof *draw), load[3] = {0};
    FILE *f = fopen("/proc/loadavg", "r");
    if (f && fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3)
        load[0] = NAN;
    if (f)
        fclose(f);
    printf("calibration workload, %zu runs in fresh children; load average %.2f %.2f %.2f\n", n,
           load[0], load[1], load[2]);
    for (size_t i = 0; i < n; i++) {
        calibrate_result r;
        if (calibrate_in_child(&r) != 0) {
            fprintf(stderr, "bench_calibrate: run %zu gave no answer\n", i + 1);
            return 1;
        }
        cpu[i] = r.cpu_ns;
        draw[i] = r.draw_ns;
    }
    bench__piece("cpu", cpu, n);
    bench__piece("draw", draw, n);
    free(cpu);
    free(draw);
    return 0;
}
