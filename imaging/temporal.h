/* temporal.h — temporal stability of a rendered sequence against the
 * reference of the same path: shimmer, swimming and popping.
 *
 * Frames 0..n-1 of the test (T) and of the reference (R), all of one size.
 * With Y the luminance 0.2126 R + 0.7152 G + 0.0722 B of the stored
 * (linear) values, the temporal error of pixel p at step t = 1..n-1 is
 *
 *     e_t(p) = | (Y(T_t, p) − Y(T_{t−1}, p)) − (Y(R_t, p) − Y(R_{t−1}, p)) |
 *
 * how much the test's frame-to-frame change differs from the reference's:
 * 0 for a test that changes exactly as the reference does, whatever its
 * still error (a constant bias cancels), and the flicker's amplitude for a
 * test that flickers over a still reference.  It is summarised as the mean
 * and the 99th percentile (type 7) over every pixel and step, and mapped
 * per pixel as the mean over the steps.
 *
 * Popping is the largest jump of a per-frame error E_t (for example 1 −
 * SSIM or FLIP's mean of frame t against the reference frame t) between
 * consecutive frames: max_t |E_t − E_{t−1}|, and the t where it happens.
 *
 * docs/motion.md, "Temporal stability", gives the equations and the
 * ground-truth cases they are checked on.
 */
#ifndef IMAGING_TEMPORAL_H
#define IMAGING_TEMPORAL_H

#include <stddef.h>
#include "core/dm_image.h"

typedef struct temporal_stats {
    size_t steps;            /* n − 1 */
    double mean, p99;        /* of e over pixels and steps */
    double max;
    long nonfinite;          /* pixel-steps left out: a NaN or Inf in either sequence */
} temporal_stats;

/* The temporal error of test[0..n-1] against ref[0..n-1] (n >= 2, every
 * frame the size of ref[0], else DM_ERR_ARG).  map (optional) is allocated
 * at that size: R = G = B = the per-pixel mean of e, A = 1. */
int temporal_error(const img *test, const img *ref, size_t n, temporal_stats *out, img *map);

/* The same, one step at a time, so a caller holds two frames of each
 * sequence instead of all of them (run/mpath_quality.c): init for w×h,
 * one step per pair of consecutive frames, then finish, which fills out
 * and map as temporal_error does and releases the accumulator (also after
 * a failed step).  The e values of every pixel-step are kept for the 99th
 * percentile: one float each. */
typedef struct temporal_acc {
    int w, h;
    size_t steps, kept, cap;
    float *e;                /* the finite e values so far */
    double *sum;             /* per pixel: sum and count of finite e */
    size_t *cnt;
    double acc, max;
    long nonfinite;
} temporal_acc;

/* 0, or DM_ERR_ARG (w or h < 1). */
int temporal_acc_init(temporal_acc *a, int w, int h);
/* Adds step (t0 -> t1 of the test, r0 -> r1 of the reference): 0,
 * DM_ERR_ARG (a frame of another size or without pixels), DM_ERR_NOMEM. */
int temporal_acc_step(temporal_acc *a, const img *t0, const img *t1, const img *r0, const img *r1);
/* The summary of the steps added (DM_ERR_ARG, out NaN, when none was);
 * map as temporal_error's.  Releases a. */
int temporal_acc_finish(temporal_acc *a, temporal_stats *out, img *map);

/* Popping of the per-frame errors e[0..n-1]: the largest |e[t] − e[t−1]|,
 * with t in *at (optional); NaN when n < 2 or no two consecutive values
 * are finite. */
double temporal_popping(const double *e, size_t n, size_t *at);

#endif
