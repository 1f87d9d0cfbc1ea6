/* quality.c — SSIM, silhouette, depth, non-finite and crack metrics. */
#include "imaging/quality.h"

#include "core/dm_error.h"
#include "core/dm_util.h"

#include <math.h>
#include <stdlib.h>

#define SSIM_WIN 11
#define SSIM_SIGMA 1.5
#define SSIM_C1 (0.01 * 0.01)   /* (K1 L)^2, L = 1 */
#define SSIM_C2 (0.03 * 0.03)   /* (K2 L)^2 */

enum { F_A, F_B, F_AA, F_BB, F_AB, F_COUNT };

static double quality__luma(const float *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/* Normalised 1-D Gaussian of n taps (n <= SSIM_WIN), centred on (n-1)/2,
 * sigma SSIM_SIGMA; the 2-D window is the outer product of one such vector
 * per axis.  n = SSIM_WIN gives the standard window. */
static void quality__gauss_weights(int n, double w[SSIM_WIN])
{
    double sum = 0, c = (n - 1) / 2.0;
    for (int i = 0; i < n; i++) {
        double x = i - c;
        w[i] = exp(-x * x / (2 * SSIM_SIGMA * SSIM_SIGMA));
        sum += w[i];
    }
    for (int i = 0; i < n; i++)
        w[i] /= sum;
}

/* Horizontal "valid" pass of the five fields (a, b, a², b², ab) with the
 * nx-tap window gx into hp, which holds F_COUNT planes of (w-nx+1) × h. */
static void quality__ssim_hpass(const img *a, const img *b, const double *gx, int nx, double *hp)
{
    int ow = a->w - nx + 1;
    size_t plane = (size_t)ow * a->h;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < ow; x++) {
            double s[F_COUNT] = {0};
            for (int k = 0; k < nx; k++) {
                size_t i = ((size_t)y * a->w + (size_t)(x + k)) * 4;
                double ya = quality__luma(a->px + i), yb = quality__luma(b->px + i);
                s[F_A] += gx[k] * ya;
                s[F_B] += gx[k] * yb;
                s[F_AA] += gx[k] * ya * ya;
                s[F_BB] += gx[k] * yb * yb;
                s[F_AB] += gx[k] * ya * yb;
            }
            for (int f = 0; f < F_COUNT; f++)
                hp[f * plane + (size_t)y * ow + x] = s[f];
        }
}

/* SSIM of one window from its weighted moments.  Written so that a == b
 * gives exactly 1 (2·μa·μb equals μa²+μb² bit for bit, σab equals σa²). */
static double quality__ssim_window(const double m[F_COUNT])
{
    double va = m[F_AA] - m[F_A] * m[F_A];
    double vb = m[F_BB] - m[F_B] * m[F_B];
    double cov = m[F_AB] - m[F_A] * m[F_B];
    double num = (2 * m[F_A] * m[F_B] + SSIM_C1) * (2 * cov + SSIM_C2);
    double den = (m[F_A] * m[F_A] + m[F_B] * m[F_B] + SSIM_C1) * (va + vb + SSIM_C2);
    return num / den;
}

int quality_ssim(const img *a, const img *b, double *ssim)
{
    if (!a || !b || !ssim || !a->px || !b->px || a->w != b->w || a->h != b->h ||
        a->w < 1 || a->h < 1)
        return DM_ERR_ARG;
    /* An image narrower or shorter than the window gets a window as wide
     * or tall as the image along that axis (quality.h). */
    int nx = a->w < SSIM_WIN ? a->w : SSIM_WIN, ny = a->h < SSIM_WIN ? a->h : SSIM_WIN;
    double gx[SSIM_WIN], gy[SSIM_WIN];
    quality__gauss_weights(nx, gx);
    quality__gauss_weights(ny, gy);
    int ow = a->w - nx + 1, oh = a->h - ny + 1;
    size_t plane = (size_t)ow * a->h;
    double *hp = malloc(plane * F_COUNT * sizeof *hp);
    if (!hp)
        return DM_ERR_NOMEM;
    quality__ssim_hpass(a, b, gx, nx, hp);
    double total = 0;
    for (int y = 0; y < oh; y++)
        for (int x = 0; x < ow; x++) {
            double m[F_COUNT] = {0};
            for (int f = 0; f < F_COUNT; f++)
                for (int k = 0; k < ny; k++)
                    m[f] += gy[k] * hp[f * plane + (size_t)(y + k) * ow + x];
            total += quality__ssim_window(m);
        }
    free(hp);
    *ssim = total / ((double)ow * oh);
    return 0;
}

void quality_coverage(const img *im, unsigned char *mask)
{
    size_t n = (size_t)im->w * im->h;
    for (size_t i = 0; i < n; i++)
        mask[i] = im->px[i * 4 + 3] > 0.5f;
}

double quality_silhouette_error(const unsigned char *ma, const unsigned char *mb, size_t n)
{
    size_t inter = 0, uni = 0;
    for (size_t i = 0; i < n; i++) {
        inter += ma[i] && mb[i];
        uni += ma[i] || mb[i];
    }
    return uni ? 1.0 - (double)inter / (double)uni : 0.0;
}

int quality_depth_rmse(const float *da, const float *db, const unsigned char *ma,
                       const unsigned char *mb, size_t n, double *rmse)
{
    double sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        if (!ma[i] || !mb[i])
            continue;
        double d = (double)da[i] - (double)db[i];
        sum += d * d;
        count++;
    }
    if (!count)
        return DM_ERR_UNAVAILABLE;
    *rmse = sqrt(sum / (double)count);
    return 0;
}

long quality_nonfinite_pixels(const img *im)
{
    long count = 0;
    size_t n = (size_t)im->w * im->h;
    for (size_t i = 0; i < n; i++) {
        const float *p = im->px + i * 4;
        count += !(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) && isfinite(p[3]));
    }
    return count;
}

/* Pushes background pixel i onto the stack unless seen or covered. */
static void quality__crack_push(const unsigned char *mask, unsigned char *seen, size_t *stack,
                                size_t *top, size_t i)
{
    if (mask[i] || seen[i])
        return;
    seen[i] = 1;
    stack[(*top)++] = i;
}

long quality_crack_pixels(const unsigned char *mask, int w, int h)
{
    size_t n = (size_t)w * h;
    unsigned char *seen = calloc(n ? n : 1, 1);
    size_t *stack = malloc((n ? n : 1) * sizeof *stack);
    if (!seen || !stack) {
        free(seen);
        free(stack);
        return -1;
    }
    size_t top = 0;
    for (int x = 0; x < w; x++) {
        quality__crack_push(mask, seen, stack, &top, (size_t)x);
        quality__crack_push(mask, seen, stack, &top, (size_t)(h - 1) * w + x);
    }
    for (int y = 0; y < h; y++) {
        quality__crack_push(mask, seen, stack, &top, (size_t)y * w);
        quality__crack_push(mask, seen, stack, &top, (size_t)y * w + (w - 1));
    }
    while (top) {   /* flood fill over 4-neighbours through background */
        size_t i = stack[--top];
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
        if (x > 0) quality__crack_push(mask, seen, stack, &top, i - 1);
        if (x < w - 1) quality__crack_push(mask, seen, stack, &top, i + 1);
        if (y > 0) quality__crack_push(mask, seen, stack, &top, i - (size_t)w);
        if (y < h - 1) quality__crack_push(mask, seen, stack, &top, i + (size_t)w);
    }
    long cracks = 0;
    for (size_t i = 0; i < n; i++)
        cracks += !mask[i] && !seen[i];
    free(seen);
    free(stack);
    return cracks;
}
