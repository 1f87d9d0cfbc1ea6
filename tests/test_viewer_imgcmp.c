/* test_viewer_imgcmp.c — helper of test_viewer.sh: `test_viewer_imgcmp A B MIN_PSNR`
 * exits 0 when A is not uniform and PSNR(A against B) >= MIN_PSNR dB, else 1
 * (2 on bad usage or unreadable images); prints the figures either way. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "imaging/image.h"

/* 1 when every pixel of im has the RGB of the first one. */
static int uniform(const img *im)
{
    for (size_t i = 0; i < (size_t)im->w * (size_t)im->h; i++)
        if (memcmp(&im->px[4 * i], im->px, 3 * sizeof(float)) != 0)
            return 0;
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s A.png B.png MIN_PSNR\n", argv[0]);
        return 2;
    }
    img a = {0}, b = {0};
    img_metrics m;
    char err[512] = "different sizes";
    if (img_load(argv[1], &a, err, sizeof err) != 0 || img_load(argv[2], &b, err, sizeof err) != 0 ||
        img_compare(&b, &a, 0.05, &m) != 0) {
        fprintf(stderr, "%s: cannot compare %s and %s: %s\n", argv[0], argv[1], argv[2], err);
        return 2;
    }
    int flat = uniform(&a), ok = !flat && m.psnr >= atof(argv[3]);
    printf("%s vs %s: %dx%d PSNR %.2f dB, RMSE %.6f, max error %.4f, %s\n", argv[1], argv[2], a.w,
           a.h, m.psnr, m.rmse, m.max_error, flat ? "UNIFORM" : "non-uniform");
    img_free(&a);
    img_free(&b);
    return ok ? 0 : 1;
}
