/* fraction.h — one grammar for a fraction, everywhere a user writes one:
 * every flag (`compare --time-threshold`, `--threshold`, `--tolerance`,
 * `--alpha`, `--ssim-drop`) and every sweep-file key (`samples.target_ci`).
 *
 *   5%     five percent            = 0.05
 *   0.05   a fraction              = 0.05
 *   5      refused: a bare number above 1 where a fraction is meant is
 *          ambiguous (5 % or 500 %?); the message gives both ways to say it.
 *
 * A percentage may exceed 100 % where the range allows it (`150%`); a bare
 * fraction never exceeds 1.  No spaces, no sign, finite only.
 */
#ifndef SWEEP_FRACTION_H
#define SWEEP_FRACTION_H

#include "core/dm_util.h"

/* The accepted range of a fraction: lo..hi, each end open or closed. */
typedef struct fraction_range {
    double lo, hi;           /* hi may be INFINITY (percentages only above 1) */
    int lo_open, hi_open;    /* 1: the bound itself is refused */
} fraction_range;

/* Parses text by the grammar above into *out.  `what` names the flag or
 * key for the message ("--time-threshold", "measure.samples.target_ci").
 * Returns 0; DM_ERR_ARG for text that is not a fraction or a percentage,
 * or a bare number above 1 (err names both ways to say it: "5%" or
 * "0.05"); DM_ERR_RANGE outside the range (err gives the range in
 * percent).  *out is unchanged on failure. */
int fraction_parse(const char *text, const char *what, const fraction_range *range, double *out,
                   dm_str *err);

#endif
