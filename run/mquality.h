/* mquality.h — a measured configuration's image, and its quality against
 * the scene's reference (docs/measurement.md, Quality).
 *
 * The reference is rendered once per scene (or per configuration with
 * `reference: same`), loaded from the reference cache (run/refcache.h)
 * when an entry for exactly its inputs exists.  The configuration's image,
 * the reference and the FLIP map (which is also the heatmap: images.heatmap
 * and images.flip name the one file) are written to the run's img/ folder; RMSE, PSNR, max error, SSIM, FLIP, silhouette, depth
 * RMSE, crack and non-finite pixel counts go into the result.
 */
#ifndef RUN_MQUALITY_H
#define RUN_MQUALITY_H

#include "core/dm_results.h"
#include "run/mscene.h"

/* Renders c's image and fills out's quality and image paths; nothing when
 * the image cannot be rendered (the reason in c's log). */
void mquality_measure(mscene *m, mconf *c, dm_config_result *out);

#endif
