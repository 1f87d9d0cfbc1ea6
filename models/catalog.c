#include "catalog.h"

#include <math.h>
#include <string.h>

static const fit_bound catalog__nonneg5[] = {
    { "c0", 0, INFINITY }, { "c_vs", 0, INFINITY }, { "c_tes", 0, INFINITY },
    { "c_prim", 0, INFINITY }, { "c_px", 0, INFINITY } };

static const fit_bound catalog__nonneg_stage[] = {
    { "c0", 0, INFINITY }, { "c_vs", 0, INFINITY }, { "c_tes", 0, INFINITY }, { "c_tp", 0, INFINITY },
    { "c_prim", 0, INFINITY }, { "c_px", 0, INFINITY }, { "c_step", 0, INFINITY },
    { "c_light", 0, INFINITY } };

static const fit_bound catalog__nonneg2[] = { { "a", 0, INFINITY }, { "b", 0, INFINITY } };

static const models_builtin catalog__models[] = {
    { "pipeline-linear",
      "c0 + c_vs*VSInvocations + c_tes*TESInvocations + c_prim*ClippingOutputPrimitives + c_px*SamplesPassed",
      "WallTime",
      "frame time as a non-negative sum of per-stage costs (vertex, tessellation, primitive, pixel)",
      catalog__nonneg5, 5, NULL },
    { "tess-power", "a + b*tess_level^p", "WallTime",
      "frame time against the tessellation level L: a + b*L^p", NULL, 0, NULL },
    { "resolution-linear", "a + b*SamplesPassed", "WallTime",
      "frame time against covered pixels: a fixed cost plus a cost per pixel", NULL, 0, NULL },
    /* one fit per shader variant: the costs per invocation are the variant's,
     * the invocation counts the configuration's (docs/models.md).  c_tp:
     * llvmpipe's evaluation stage costs more per invocation the more a
     * draw's patches are tessellated in all (TCSPatches*tess_level^2
     * triangles): measured quadratic in the draw's output, to 3.4 % on
     * planes of 2-98 patches at levels 2-16 (docs/counters.md); the term is
     * dropped where TCSPatches or tess_level was not recorded. */
    { "stage-instructions",
      "c0 + c_vs*VSInvocations + c_tes*TESInvocations + c_tp*TESInvocations*TCSPatches*tess_level^2"
      " + c_prim*ClippingOutputPrimitives + c_px*FSInvocations"
      " + c_step*FSInvocations*steps + c_light*FSInvocations*light_count",
      "Instructions",
      "instructions per frame of one shader variant: a cost per vertex, evaluation (growing with the "
      "draw's patches), primitive and fragment invocation, the fragment's growing with steps and lights",
      catalog__nonneg_stage, 8, "variant" },
    { "time-from-instructions", "a + b*Instructions", "WallTime",
      "frame time from the frame's instructions: a fixed cost plus a time per instruction",
      catalog__nonneg2, 2, NULL },
};

size_t models_builtin_count(void) { return sizeof catalog__models / sizeof *catalog__models; }

const models_builtin *models_builtin_at(size_t i)
{
    return i < models_builtin_count() ? &catalog__models[i] : NULL;
}

const models_builtin *models_builtin_find(const char *name)
{
    for (size_t i = 0; name && i < models_builtin_count(); i++)
        if (strcmp(catalog__models[i].name, name) == 0)
            return &catalog__models[i];
    return NULL;
}
