/* flip.c — LDR-FLIP (see flip.h).  "Eq. n" is equation n of Andersson et
 * al., HPG 2020; "§n" its section.  The colour pipeline (§4.1) and the
 * feature pipeline (§4.2) are separate stages; flip_map() combines them
 * (§4.3). */
#include "imaging/flip.h"

#include "core/dm_error.h"
#include "core/dm_util.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* §4.1: contrast sensitivity functions as sums of two Gaussians in the
 * frequency domain, A(f) = a1 e^(-b1 f^2) + a2 e^(-b2 f^2) (Eq. 1), with
 * these parameters per opponent channel (achromatic, red-green,
 * blue-yellow).  a2 = 0 makes the first two single Gaussians. */
static const double csf_a1[FLIP_CHANNELS] = { 1.0, 1.0, 34.1 };
static const double csf_b1[FLIP_CHANNELS] = { 0.0047, 0.0053, 0.04 };
static const double csf_a2[FLIP_CHANNELS] = { 0.0, 0.0, 13.5 };
static const double csf_b2[FLIP_CHANNELS] = { 1e-5, 1e-5, 0.025 };
#define CSF_B_MAX 0.04            /* largest b with a > 0: sets the radius (Eq. 3) */

#define FLIP_QC 0.7               /* colour-difference compression exponent (Eq. 6) */
#define FLIP_PC 0.4               /* knee of the colour mapping, fraction of cmax (Eq. 7) */
#define FLIP_PT 0.95              /* error at the knee (Eq. 7) */
#define FLIP_W 0.082              /* feature detector width, degrees (§4.2) */
#define FLIP_QF 0.5               /* feature-difference exponent (Eq. 9) */
#define HUNT_K 0.01               /* Hunt adjustment a*,b* *= 0.01 L* (Eq. 4) */

/* Linear sRGB (D65) -> CIE XYZ and back (IEC 61966-2-1). */
static const double rgb2xyz[3][3] = {
    { 0.4124564, 0.3575761, 0.1804375 },
    { 0.2126729, 0.7151522, 0.0721750 },
    { 0.0193339, 0.1191920, 0.9503041 } };
static const double xyz2rgb[3][3] = {
    { 3.2404542, -1.5371385, -0.4985314 },
    { -0.9692660, 1.8760108, 0.0415560 },
    { 0.0556434, -0.2040259, 1.0572252 } };

static void flip__mat3(const double m[3][3], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

/* Reference white: XYZ of linear RGB (1,1,1). */
static void flip__white(double w[3])
{
    const double one[3] = { 1, 1, 1 };
    flip__mat3(rgb2xyz, one, w);
}

static double flip__clamp01(double v)
{
    return !(v > 0) ? 0 : v > 1 ? 1 : v;        /* NaN -> 0: said elsewhere, not spread */
}

flip_desc flip_defaults(const flip_desc *d)
{
    flip_desc out = d ? *d : (flip_desc){0};
    if (out.ppd == 0)
        out.ppd = FLIP_DEFAULT_PPD;
    return out;
}

double flip_srgb_to_linear(double v)
{
    v = flip__clamp01(v);
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

/* YCxCz (§4.1): Y' = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn),
 * Cz = 200 (Y/Yn - Z/Zn): CIELAB without its cube root, linear in XYZ, so
 * filtering in it is filtering of light. */
void flip_linear_to_ycxcz(const double rgb[3], double out[3])
{
    double xyz[3], w[3];
    flip__mat3(rgb2xyz, rgb, xyz);
    flip__white(w);
    double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
    out[0] = 116 * y - 16;
    out[1] = 500 * (x - y);
    out[2] = 200 * (y - z);
}

void flip_ycxcz_to_linear(const double ycc[3], double rgb[3])
{
    double w[3];
    flip__white(w);
    double y = (ycc[0] + 16) / 116;
    double xyz[3] = { (ycc[1] / 500 + y) * w[0], y * w[1], (y - ycc[2] / 200) * w[2] };
    flip__mat3(xyz2rgb, xyz, rgb);
}

static double flip__lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

/* CIELAB of the clamped linear colour, then the Hunt adjustment
 * a*_H = 0.01 L* a*, b*_H = 0.01 L* b* (Eq. 4): chroma is seen less at low
 * luminance. */
void flip_linear_to_hunt_lab(const double rgb[3], double lab[3])
{
    double c[3] = { flip__clamp01(rgb[0]), flip__clamp01(rgb[1]), flip__clamp01(rgb[2]) }, xyz[3], w[3];
    flip__mat3(rgb2xyz, c, xyz);
    flip__white(w);
    double fx = flip__lab_f(xyz[0] / w[0]), fy = flip__lab_f(xyz[1] / w[1]), fz = flip__lab_f(xyz[2] / w[2]);
    double L = 116 * fy - 16;
    lab[0] = L;
    lab[1] = HUNT_K * L * 500 * (fx - fy);
    lab[2] = HUNT_K * L * 200 * (fy - fz);
}

/* HyAB (Eq. 5): city-block lightness plus Euclidean chroma, which holds
 * for large differences where Euclidean CIELAB does not. */
double flip_hyab(const double a[3], const double b[3])
{
    double da = a[1] - b[1], db = a[2] - b[2];
    return fabs(a[0] - b[0]) + sqrt(da * da + db * db);
}

/* cmax = (HyAB(Hunt(green), Hunt(blue)))^qc (Eq. 6): the largest
 * difference of two colours in the gamut, compressed. */
static double flip__cmax(void)
{
    const double g[3] = { 0, 1, 0 }, b[3] = { 0, 0, 1 };
    double lg[3], lb[3];
    flip_linear_to_hunt_lab(g, lg);
    flip_linear_to_hunt_lab(b, lb);
    return pow(flip_hyab(lg, lb), FLIP_QC);
}

/* Compression e = hyab^qc (Eq. 6) and the mapping to [0,1] (Eq. 7):
 * linear to pt at pc*cmax, then linear to 1 at cmax, so that small
 * differences get most of the range. */
static double flip__color_error(double hyab, double cmax)
{
    double e = pow(hyab, FLIP_QC), knee = FLIP_PC * cmax;
    if (e < knee)
        return FLIP_PT / knee * e;
    return FLIP_PT + (e - knee) / (cmax - knee) * (1 - FLIP_PT);
}

double flip_color_error(double hyab)
{
    return flip__color_error(hyab, flip__cmax());
}

/* Eq. 10: features raise the colour error's exponent towards 0. */
double flip_combine(double color_error, double feature_diff)
{
    return feature_diff == 0 ? color_error : pow(color_error, 1 - feature_diff);
}

/* Spatial-domain CSF (Eq. 2), the inverse Fourier transform of Eq. 1:
 * s(x) = a1 sqrt(pi/b1) e^(-pi^2 x^2/b1) + a2 sqrt(pi/b2) e^(-pi^2 x^2/b2),
 * x in degrees. */
double flip_csf_value(int channel, double x)
{
    double s = 0;
    const double a[2] = { csf_a1[channel], csf_a2[channel] }, b[2] = { csf_b1[channel], csf_b2[channel] };
    for (int k = 0; k < 2; k++)
        if (a[k] > 0)
            s += a[k] * sqrt(M_PI / b[k]) * exp(-M_PI * M_PI * x * x / b[k]);
    return s;
}

/* Eq. 3: r = ceil(3 sqrt(b_max / (2 pi^2)) * ppd), three standard
 * deviations of the widest Gaussian. */
int flip_csf_radius(double ppd)
{
    return (int)ceil(3 * sqrt(CSF_B_MAX / (2 * M_PI * M_PI)) * ppd);
}

/* §4.2: sigma = 0.5 w ppd pixels, radius ceil(3 sigma). */
double flip_feature_sigma(double ppd)
{
    return 0.5 * FLIP_W * ppd;
}

int flip_feature_radius(double ppd)
{
    return (int)ceil(3 * flip_feature_sigma(ppd));
}

/* Eq. 9: dF = (max(|dEdge|, |dPoint|) / sqrt(2))^qf. */
double flip_feature_diff(double edge_ref, double edge_test, double point_ref, double point_test)
{
    double de = fabs(edge_ref - edge_test), dp = fabs(point_ref - point_test);
    double m = (de > dp ? de : dp) / sqrt(2.0);
    m = m > 1 ? 1 : m;
    return FLIP_QF == 0.5 ? sqrt(m) : pow(m, FLIP_QF);
}

/* ---- Separable convolution with clamp-to-edge borders ---- */

typedef struct flip__plane {
    int w, h;
    float *v;
} flip__plane;

/* acc[x] += sum_i k[i] l[x+i] over i in [0, 2r], where k is symmetric
 * (sym = 1: k[i] = k[2r-i]) or antisymmetric (sym = -1): the pairs share a
 * multiply, and the loop over x runs over contiguous memory (vectorises). */
static void flip__conv_line(double *acc, const double *l, int w, const double *k, int r, int sym)
{
    for (int i = 0; i < r; i++) {
        double kv = k[i];
        const double *lo = l + i, *hi = l + 2 * r - i;
        if (sym > 0)
            for (int x = 0; x < w; x++)
                acc[x] += kv * (lo[x] + hi[x]);
        else
            for (int x = 0; x < w; x++)
                acc[x] += kv * (lo[x] - hi[x]);
    }
    double kc = k[r];
    for (int x = 0; x < w; x++)
        acc[x] += kc * l[x + r];
}

/* dst = src convolved along x (dir 0) or y (dir 1) with k[-r..r] of
 * symmetry sym (see flip__conv_line), borders extended.  The x pass copies each
 * row into a padded line; the y pass adds whole rows, so both inner loops
 * run over contiguous memory. */
static void flip__conv1(const flip__plane *src, float *dst, const double *k, int r, int dir, int sym)
{
    int w = src->w, h = src->h;
    double *acc = dm_xmalloc((size_t)w * sizeof *acc);        /* rows: OOM aborts */
    double *line = dm_xmalloc(((size_t)w + 2 * (size_t)r) * sizeof *line);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++)
            acc[x] = 0;
        if (dir == 0) {
            const float *row = src->v + (size_t)y * w;
            for (int i = 0; i < w + 2 * r; i++)
                line[i] = row[i < r ? 0 : i - r >= w ? w - 1 : i - r];
            flip__conv_line(acc, line, w, k, r, sym);
        } else {
            /* vertical: accumulate rows y-r..y+r with their taps, pairing
             * row y-r+i with row y+r-i */
            for (int i = 0; i < r; i++) {
                int y0 = y - r + i, y1 = y + r - i;
                const float *lo = src->v + (size_t)(y0 < 0 ? 0 : y0 >= h ? h - 1 : y0) * w;
                const float *hi = src->v + (size_t)(y1 < 0 ? 0 : y1 >= h ? h - 1 : y1) * w;
                double kv = k[i];
                if (sym > 0)
                    for (int x = 0; x < w; x++)
                        acc[x] += kv * ((double)lo[x] + hi[x]);
                else
                    for (int x = 0; x < w; x++)
                        acc[x] += kv * ((double)lo[x] - hi[x]);
            }
            const float *c = src->v + (size_t)y * w;
            for (int x = 0; x < w; x++)
                acc[x] += k[r] * c[x];
        }
        float *out = dst + (size_t)y * w;
        for (int x = 0; x < w; x++)
            out[x] = (float)acc[x];
    }
    free(line);
    free(acc);
}

/* out = src convolved with kx along x, then ky along y (symmetries sx, sy);
 * tmp holds w*h. */
static void flip__conv2(const flip__plane *src, float *tmp, float *out, const double *kx, int sx,
                        const double *ky, int sy, int r)
{
    flip__conv1(src, tmp, kx, r, 0, sx);
    flip__plane t = { src->w, src->h, tmp };
    flip__conv1(&t, out, ky, r, 1, sy);
}

/* Filters channel c of ycc (3 planes) in place with its CSF (Eq. 2),
 * normalised to sum 1 over the (2r+1)^2 kernel.  Each Gaussian term is
 * separable; the 2-D kernel's sum is the sum of the terms' sums, so the
 * separable result is the 2-D convolution exactly. */
static void flip__csf_filter(flip__plane *p, int c, double ppd, int r, float *tmp, float *acc, float *term)
{
    double g[2][2 * FLIP_MAX_RADIUS + 1], wt[2] = {0}, total = 0;
    const double a[2] = { csf_a1[c], csf_a2[c] }, b[2] = { csf_b1[c], csf_b2[c] };
    for (int k = 0; k < 2; k++) {
        double sum = 0;
        for (int i = -r; i <= r; i++) {
            double x = i / ppd;
            g[k][i + r] = exp(-M_PI * M_PI * x * x / b[k]);
            sum += g[k][i + r];
        }
        wt[k] = a[k] > 0 ? a[k] * sqrt(M_PI / b[k]) : 0;
        total += wt[k] * sum * sum;
    }
    size_t n = (size_t)p->w * p->h;
    memset(acc, 0, n * sizeof *acc);
    for (int k = 0; k < 2; k++) {
        if (wt[k] == 0)
            continue;
        flip__conv2(p, tmp, term, g[k], 1, g[k], 1, r);
        for (size_t i = 0; i < n; i++)
            acc[i] += (float)(wt[k] / total) * term[i];
    }
    memcpy(p->v, acc, n * sizeof *acc);
}

/* The 1-D feature kernels of §4.2 at ppd: gauss (sum 1), edge (first
 * derivative, positive part sums to 1, negative to -1) and point (second
 * derivative, likewise).  With gauss along the other axis the 2-D kernels
 * keep those sums, as the paper normalises them. */
static void flip__feature_kernels(double ppd, int r, double *gauss, double *edge, double *point)
{
    double sd = flip_feature_sigma(ppd), gs = 0, ep = 0, pp = 0, pn = 0;
    for (int i = -r; i <= r; i++) {
        double x = i, g = exp(-x * x / (2 * sd * sd));
        gauss[i + r] = g;
        edge[i + r] = -x * g;
        point[i + r] = (x * x / (sd * sd) - 1) * g;
        gs += g;
        ep += edge[i + r] > 0 ? edge[i + r] : 0;
        pp += point[i + r] > 0 ? point[i + r] : 0;
        pn += point[i + r] < 0 ? -point[i + r] : 0;
    }
    /* At very low ppd (sigma << 1 pixel) the off-centre taps underflow to
     * 0: no feature can be seen, and the kernels are 0 rather than 0/0. */
    for (int i = 0; i <= 2 * r; i++) {
        gauss[i] /= gs;
        edge[i] = ep > 0 ? edge[i] / ep : 0;
        double d = point[i] > 0 ? pp : pn;
        point[i] = d > 0 ? point[i] / d : 0;
    }
}

/* Edge and point magnitudes of luminance plane lum (§4.2, Eq. 8):
 * |(lum * Ex, lum * Ey)| and |(lum * Pxx, lum * Pyy)|.  The horizontal
 * Gaussian pass is shared by Ey and Pyy.  t2, t3, t4 hold w*h each. */
static void flip__features(const flip__plane *lum, double ppd, int r, float *t2, float *t3, float *t4,
                           float *edge_mag, float *point_mag)
{
    double g[2 * FLIP_MAX_RADIUS + 1], e[2 * FLIP_MAX_RADIUS + 1], p[2 * FLIP_MAX_RADIUS + 1];
    flip__feature_kernels(ppd, r, g, e, p);
    size_t n = (size_t)lum->w * lum->h;
    flip__plane hg = { lum->w, lum->h, t2 }, h = { lum->w, lum->h, t3 };
    flip__conv1(lum, t2, g, r, 0, 1);                   /* lum * g along x */
    flip__conv1(lum, t3, e, r, 0, -1);
    flip__conv1(&h, edge_mag, g, r, 1, 1);              /* d/dx */
    flip__conv1(&hg, t4, e, r, 1, -1);                  /* d/dy */
    for (size_t i = 0; i < n; i++)
        edge_mag[i] = sqrtf(edge_mag[i] * edge_mag[i] + t4[i] * t4[i]);
    flip__conv1(lum, t3, p, r, 0, 1);
    flip__conv1(&h, point_mag, g, r, 1, 1);             /* d2/dx2 */
    flip__conv1(&hg, t4, p, r, 1, 1);                   /* d2/dy2 */
    for (size_t i = 0; i < n; i++)
        point_mag[i] = sqrtf(point_mag[i] * point_mag[i] + t4[i] * t4[i]);
}

enum { P_Y, P_CX, P_CZ, P_LUM, P_EDGE, P_POINT, P_PER_IMAGE };
enum { P_TMP = 2 * P_PER_IMAGE, P_T2, P_T3, P_COUNT };

/* flip_srgb_to_linear of float v, by table when v is an 8-bit level k/255
 * (renders read back from 8-bit framebuffers and PNGs are): the table holds
 * the same function of the same value, so the result is identical. */
static double flip__srgb_lin_fast(float v, const double lut[256])
{
    float k = v * 255.0f + 0.5f;
    if (k >= 0 && k < 256) {
        int i = (int)k;
        if ((float)i / 255.0f == v)
            return lut[i];
    }
    return flip_srgb_to_linear(v);
}

/* Fills the three YCxCz planes and the luminance plane (Y/Yn, the
 * achromatic channel normalised to [0,1]) of im at planes[0..3]. */
static void flip__to_ycxcz(const img *im, float *planes[])
{
    size_t n = (size_t)im->w * im->h;
    double lut[256];
    for (int k = 0; k < 256; k++)
        lut[k] = flip_srgb_to_linear((float)k / 255.0f);
    for (size_t i = 0; i < n; i++) {
        const float *px = im->px + i * 4;
        double lin[3] = { flip__srgb_lin_fast(px[0], lut), flip__srgb_lin_fast(px[1], lut),
                          flip__srgb_lin_fast(px[2], lut) }, ycc[3];
        flip_linear_to_ycxcz(lin, ycc);
        for (int c = 0; c < 3; c++)
            planes[c][i] = (float)ycc[c];
        planes[P_LUM][i] = (float)((ycc[0] + 16) / 116);
    }
}

/* Both pipelines for one image: filtered YCxCz and feature magnitudes. */
static void flip__image(const img *im, double ppd, float *pl[], float *tmp, float *t2, float *t3)
{
    flip__to_ycxcz(im, pl);
    int rc = flip_csf_radius(ppd), rf = flip_feature_radius(ppd);
    for (int c = 0; c < 3; c++) {
        flip__plane p = { im->w, im->h, pl[c] };
        flip__csf_filter(&p, c, ppd, rc, tmp, t2, t3);
    }
    flip__plane lum = { im->w, im->h, pl[P_LUM] };
    flip__features(&lum, ppd, rf, tmp, t2, t3, pl[P_EDGE], pl[P_POINT]);
}

static double flip__pixel(float *const pl[], size_t i, double cmax)
{
    double lab[2][3];
    for (int k = 0; k < 2; k++) {
        float *const *q = pl + k * P_PER_IMAGE;
        double ycc[3] = { q[P_Y][i], q[P_CX][i], q[P_CZ][i] }, rgb[3];
        flip_ycxcz_to_linear(ycc, rgb);
        flip_linear_to_hunt_lab(rgb, lab[k]);
    }
    double ce = flip__color_error(flip_hyab(lab[0], lab[1]), cmax);
    double fd = flip_feature_diff(pl[P_EDGE][i], pl[P_PER_IMAGE + P_EDGE][i],
                                  pl[P_POINT][i], pl[P_PER_IMAGE + P_POINT][i]);
    return flip_combine(ce, fd);
}

int flip_map(const img *ref, const img *test, const flip_desc *d, float *map)
{
    flip_desc fd = flip_defaults(d);
    if (!ref || !test || !map || !ref->px || !test->px || ref->w != test->w || ref->h != test->h ||
        ref->w < 1 || ref->h < 1 || !isfinite(fd.ppd) || fd.ppd <= 0 ||
        flip_csf_radius(fd.ppd) > FLIP_MAX_RADIUS)
        return DM_ERR_ARG;
    size_t n = (size_t)ref->w * ref->h;
    float *buf = malloc(n * P_COUNT * sizeof *buf), *pl[P_COUNT];
    if (!buf)
        return DM_ERR_NOMEM;
    for (int k = 0; k < P_COUNT; k++)
        pl[k] = buf + (size_t)k * n;
    flip__image(ref, fd.ppd, pl, pl[P_TMP], pl[P_T2], pl[P_T3]);
    flip__image(test, fd.ppd, pl + P_PER_IMAGE, pl[P_TMP], pl[P_T2], pl[P_T3]);
    double cmax = flip__cmax();
    for (size_t i = 0; i < n; i++)
        map[i] = (float)flip__pixel(pl, i, cmax);
    free(buf);
    return 0;
}

/* Sorts n non-negative floats ascending: their bit patterns order like
 * unsigned integers, so two 16-bit LSD radix passes do it in O(n). */
static void flip__sort_nonneg(float *v, float *tmp, size_t n)
{
    for (int shift = 0; shift < 32; shift += 16) {
        size_t count[65537] = {0};
        for (size_t i = 0; i < n; i++) {
            uint32_t u;
            memcpy(&u, &v[i], sizeof u);
            count[((u >> shift) & 0xffff) + 1]++;
        }
        for (size_t k = 1; k <= 65536; k++)
            count[k] += count[k - 1];
        for (size_t i = 0; i < n; i++) {
            uint32_t u;
            memcpy(&u, &v[i], sizeof u);
            tmp[count[(u >> shift) & 0xffff]++] = v[i];
        }
        memcpy(v, tmp, n * sizeof *v);
    }
}

/* Smallest value v of sorted s[0..n) whose cumulative sum reaches q of the
 * total (weights = the values themselves); 0 when all are 0. */
static double flip__weighted_quantile(const float *s, size_t n, double total, double q)
{
    double acc = 0;
    for (size_t i = 0; i < n; i++) {
        acc += s[i];
        if (acc >= q * total && s[i] > 0)
            return s[i];
    }
    return n ? s[n - 1] : 0;
}

int flip_pool(const float *map, size_t n, flip_stats *out)
{
    if (!map || !out || n == 0)
        return DM_ERR_ARG;
    float *s = malloc(2 * n * sizeof *s);
    if (!s)
        return DM_ERR_NOMEM;
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += map[i];
    *out = (flip_stats){ .mean = sum / (double)n };
    for (size_t i = 0; i < n; i++)
        s[i] = map[i] > 0 ? map[i] : 0;          /* also turns -0 into +0 */
    flip__sort_nonneg(s, s + n, n);
    out->max = s[n - 1];
    out->q1 = flip__weighted_quantile(s, n, sum, 0.25);
    out->median = flip__weighted_quantile(s, n, sum, 0.5);
    out->q3 = flip__weighted_quantile(s, n, sum, 0.75);
    free(s);
    return 0;
}

int flip_compare(const img *ref, const img *test, const flip_desc *d, flip_stats *out, float *map)
{
    if (!ref || !out)
        return DM_ERR_ARG;
    size_t n = (size_t)(ref->w > 0 ? ref->w : 0) * (size_t)(ref->h > 0 ? ref->h : 0);
    float *m = map ? map : malloc((n ? n : 1) * sizeof *m);
    if (!m)
        return DM_ERR_NOMEM;
    int rc = flip_map(ref, test, d, m);
    flip_stats st;
    if (rc == 0)
        rc = flip_pool(m, n, &st);
    if (rc == 0)
        *out = st;
    if (!map)
        free(m);
    return rc;
}

/* Nine anchors at v = 0, 1/8, ..., 1: dark (low error recedes) to bright,
 * monotone in lightness so the order survives greyscale printing. */
static const float flip__ramp[9][3] = {
    { 0.000f, 0.000f, 0.016f }, { 0.110f, 0.065f, 0.275f }, { 0.315f, 0.070f, 0.485f },
    { 0.510f, 0.130f, 0.505f }, { 0.715f, 0.215f, 0.475f }, { 0.905f, 0.320f, 0.390f },
    { 0.985f, 0.535f, 0.380f }, { 0.995f, 0.760f, 0.545f }, { 0.988f, 0.990f, 0.750f } };

void flip_colormap(double v, float rgb[3])
{
    v = flip__clamp01(v) * 8;
    int i = v >= 8 ? 7 : (int)v;
    float t = (float)(v - i);
    for (int c = 0; c < 3; c++)
        rgb[c] = flip__ramp[i][c] + t * (flip__ramp[i + 1][c] - flip__ramp[i][c]);
}

int flip_map_save(const float *map, int w, int h, const char *path, char *err, size_t errlen)
{
    if (!map || w < 1 || h < 1 || !path)
        return DM_ERR_ARG;
    img im = {0};
    if (img_alloc(&im, w, h) != 0) {
        char why[160];
        snprintf(err, errlen, "%s: %s", path, dm_nomem_reason(why, sizeof why));
        return DM_ERR_NOMEM;
    }
    for (size_t i = 0; i < (size_t)w * h; i++) {
        flip_colormap(map[i], im.px + i * 4);
        im.px[i * 4 + 3] = 1;
    }
    int rc = img_save(&im, path, err, errlen);
    img_free(&im);
    return rc;
}
