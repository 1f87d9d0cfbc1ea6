/* flip.h — LDR-FLIP, the perceptual difference of two images (docs/flip.md).
 *
 * Written from Andersson et al., "FLIP: A Difference Evaluator for
 * Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2), HPG
 * 2020.  Equation numbers in flip.c's comments are the paper's.
 *
 * Two pipelines meet in one function:
 *   colour:  sRGB -> linear RGB -> YCxCz -> contrast-sensitivity filter per
 *            channel (kernels set by pixels per degree) -> linear RGB,
 *            clamped -> CIELAB -> Hunt-adjusted L*a*b* -> HyAB distance ->
 *            compressed and mapped to [0,1];
 *   feature: edge (1st Gaussian derivative) and point (2nd derivative)
 *            detectors on the achromatic channel of both images;
 *   combine: error = colour ^ (1 - feature).
 * The per-pixel error is in [0,1]; 0 where the images agree.
 *
 * Inputs are display-referred (sRGB-encoded) RGB values, clamped to [0,1];
 * alpha is ignored.  Borders are extended (clamp-to-edge), so a flat image
 * filters to itself.  Every stage is a function so the tests can check it on
 * its own.
 */
#ifndef IMAGING_FLIP_H
#define IMAGING_FLIP_H

#include <stddef.h>
#include "core/dm_image.h"
#include "core/dm_results.h"
#include "core/dm_util.h"

/* FLIP's default viewing condition: a 0.7 m wide 3840-pixel monitor seen
 * from 0.7 m, 3840 * (0.7 / 0.7) * pi / 180 = 67.02 pixels per degree. */
#define FLIP_DEFAULT_PPD 67.020643276582255
/* How every FLIP map states its scale, word for word: the report's heatmap
 * legend and `dmbench diff --heatmap`'s help both print it, so the two
 * cannot say different things (flip_colormap draws the colours). */
#define FLIP_SCALE_TEXT "LDR-FLIP error per pixel on FLIP's fixed scale, 0 (black: no visible " \
                        "difference) to 1 (pale yellow: the largest)"
/* Largest kernel radius accepted (pixels); ppd above ~700 would exceed it. */
#define FLIP_MAX_RADIUS 128

/* Zero means default. */
typedef struct flip_desc {
    double ppd;              /* pixels per degree of visual angle; 0 = FLIP_DEFAULT_PPD */
} flip_desc;

/* Pooled error of a FLIP map.  The quartiles and median are weighted by the
 * error itself (the paper's weighted histogram, §5): median is the value
 * below which half of the summed error lies. */
typedef struct flip_stats {
    double mean, q1, median, q3, max;
} flip_stats;

enum { FLIP_ACHROMATIC, FLIP_RED_GREEN, FLIP_BLUE_YELLOW, FLIP_CHANNELS };

/* Fills in the defaults of d (NULL-safe for out only). */
flip_desc flip_defaults(const flip_desc *d);

/* Per-pixel FLIP error of test against ref (same size) into map (w*h floats,
 * caller-owned).  0, DM_ERR_ARG (sizes differ, empty image, ppd not finite
 * and > 0, or kernels wider than FLIP_MAX_RADIUS), DM_ERR_NOMEM. */
int flip_map(const img *ref, const img *test, const flip_desc *d, float *map);
/* Mean, weighted quartiles and maximum of n map values: 0, DM_ERR_ARG
 * (n = 0 or NULL), DM_ERR_NOMEM (*out untouched on failure). */
int flip_pool(const float *map, size_t n, flip_stats *out);
/* flip_map then flip_pool; map may be NULL (then it is allocated and freed
 * here).  Same return codes as flip_map; *out is untouched on failure. */
int flip_compare(const img *ref, const img *test, const flip_desc *d, flip_stats *out, float *map);

/* Colour of error v on FLIP's fixed scale: v in [0,1] (clamped) through a
 * perceptually ordered dark-purple -> red -> orange -> pale-yellow ramp
 * (our own nine anchors in the manner of magma, linearly interpolated). */
void flip_colormap(double v, float rgb[3]);
/* Writes map (w*h values in [0,1]) through flip_colormap as an image
 * (format by extension, as img_save): the same colour means the same error
 * in every map, so maps of two techniques compare side by side.  0,
 * DM_ERR_ARG, DM_ERR_NOMEM, or img_save's DM_ERR_DISK / DM_ERR_IO with the
 * reason in err; no partial file is left at path. */
int flip_map_save(const float *map, int w, int h, const char *path, char *err, size_t errlen);

/* ---- Stages (exposed for tests) ---- */

/* sRGB-encoded value in [0,1] -> linear. */
double flip_srgb_to_linear(double v);
/* Linear sRGB -> YCxCz (Y' = 116 Y/Yn - 16, Cx, Cz), white = RGB (1,1,1). */
void flip_linear_to_ycxcz(const double rgb[3], double out[3]);
void flip_ycxcz_to_linear(const double ycc[3], double rgb[3]);
/* Linear sRGB (clamped to [0,1] here) -> Hunt-adjusted L*a*b*. */
void flip_linear_to_hunt_lab(const double rgb[3], double lab[3]);
/* HyAB distance of two Hunt-adjusted L*a*b* colours. */
double flip_hyab(const double a[3], const double b[3]);
/* HyAB distance -> colour error in [0,1] (compression and mapping). */
double flip_color_error(double hyab);
/* Colour error and feature difference -> FLIP error. */
double flip_combine(double color_error, double feature_diff);
/* Radius of the contrast-sensitivity kernels at ppd (one for all channels). */
int flip_csf_radius(double ppd);
/* Spatial contrast-sensitivity value of channel at distance x degrees
 * (unnormalised). */
double flip_csf_value(int channel, double x);
/* Standard deviation (pixels) and radius of the feature detectors at ppd. */
double flip_feature_sigma(double ppd);
int flip_feature_radius(double ppd);
/* Feature difference in [0,1] from the edge and point magnitudes of the
 * reference and test achromatic channels. */
double flip_feature_diff(double edge_ref, double edge_test, double point_ref, double point_test);

#endif
