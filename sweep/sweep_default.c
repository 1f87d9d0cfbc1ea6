/* sweep_default.c — the embedded default sweeps (sweep_default_text,
 * sweep.h): what `dmbench run` measures without a sweep file. */
#include "sweep/sweep.h"
#include "techniques/technique.h"

#include <string.h>

/* The embedded default sweep: every technique that exists (registry order)
 * on a small grid of axes, the built-in procedural scene and maps; no files,
 * no network, no display.  %s is replaced by the technique list. */
static const char sweep_default__full_yaml[] =
    "name: default\n"
    "resolution: [480, 270]\n"
    "measure:\n"
    "  warmup_frames: 4\n"
    "  frames_per_sample: 8\n"
    "  samples: { min: 5, max: 30, target_ci: 0.03 }\n"
    "  max_seconds: 6\n"
    "scene:\n"
    "  camera: { distance: 3.0, azimuth: 30, elevation: 35, fov: 45 }\n"
    "  material: { maps: bricks, height_scale: 0.06 }\n"
    "sweep:\n"
    "  mesh: [plane, cube]\n"
    "  technique: [%s]\n"
    "  tess_level: [1, 16]\n"
    "  steps: [8, 32]\n"
    "  resolution: [[240, 135], [480, 270]]\n"
    "models:\n"
    "  - { name: pixel-cost, formula: \"a + b*SamplesPassed\", response: WallTime, group_by: [technique] }\n"
    "  - { name: pipeline-linear }\n";

static const char sweep_default__quick_yaml[] =
    "name: quick\n"
    "resolution: [160, 90]\n"
    "measure:\n"
    "  warmup_frames: 2\n"
    "  frames_per_sample: 4\n"
    "  samples: { min: 5, max: 8, target_ci: 0.05 }\n"
    "  max_seconds: 1\n"
    "sweep:\n"
    "  mesh: [plane]\n"
    "  technique: [%s]\n"
    "  resolution: [[80, 45], [160, 90]]\n";

const char *sweep_default_text(int quick)
{
    static char *text[2];
    if (!text[quick]) {
        dm_str list = {0};
        for (const char *const *t = technique_names(); *t; t++)   /* the reference is not measured */
            if (strcmp(*t, "reference-mesh") != 0)
                dm_str_printf(&list, "%s%s", list.len ? ", " : "", *t);
        text[quick] = dm_xasprintf(quick ? sweep_default__quick_yaml : sweep_default__full_yaml, dm_str_get(&list));
        dm_str_free(&list);
    }
    return text[quick];
}
