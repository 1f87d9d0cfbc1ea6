/* bench_flip — time of LDR-FLIP (imaging/flip.h) on a synthetic W×H pair
 * (smooth gradient vs the same with noise), one thread, best of N runs.
 * Usage: bench_flip [W H [RUNS]] (default 1920 1080 3).  Figures only. */
#include "core/dm_util.h"
#include "imaging/flip.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* CPU time of this process, s: the machine may be shared, wall time is not
 * the work. */
static double cpu_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + t.tv_nsec / 1e9;
}

int main(int argc, char **argv)
{
    int w = argc > 2 ? atoi(argv[1]) : 1920, h = argc > 2 ? atoi(argv[2]) : 1080;
    int runs = argc > 3 ? atoi(argv[3]) : 3;
    img a = {0}, b = {0};
    if (w < 1 || h < 1 || runs < 1 || img_alloc(&a, w, h) || img_alloc(&b, w, h)) {
        fprintf(stderr, "usage: bench_flip [W H [RUNS]]\n");
        return 2;
    }
    unsigned seed = 1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 4; c++) {
                size_t i = ((size_t)y * w + x) * 4 + c;
                seed = seed * 1103515245u + 12345u;
                a.px[i] = (float)(x + y * (c + 1)) / (float)(w + 3 * h);
                b.px[i] = a.px[i] + (float)((int)(seed >> 16 & 255) - 128) / 2048.0f;
            }
    double best = 1e30, best_cpu = 1e30;
    flip_stats st = {0};
    for (int r = 0; r < runs; r++) {
        int64_t t0 = dm_now_ns();
        double c0 = cpu_s();
        if (flip_compare(&a, &b, NULL, &st, NULL) != 0) {
            fprintf(stderr, "flip_compare failed\n");
            return 1;
        }
        double s = (dm_now_ns() - t0) / 1e9, c = cpu_s() - c0;
        best = s < best ? s : best;
        best_cpu = c < best_cpu ? c : best_cpu;
    }
    /* the work was done: noise of this size gives a clearly non-zero mean */
    if (!(st.mean > 0)) {
        fprintf(stderr, "FLIP mean %g: no work done?\n", st.mean);
        return 1;
    }
    printf("FLIP %dx%d at %.2f ppd, best of %d: %.3f s CPU (%.1f Mpixel/s), %.3f s wall; "
           "mean %.4f, median %.4f, max %.4f\n", w, h, FLIP_DEFAULT_PPD, runs, best_cpu,
           w * (double)h / best_cpu / 1e6, best, st.mean, st.median, st.max);
    img_free(&a);
    img_free(&b);
    return 0;
}
