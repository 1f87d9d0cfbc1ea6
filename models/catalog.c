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

static const fit_bound catalog__nonneg_geometry[] = {
    { "c0", 0, INFINITY }, { "c_vs", 0, INFINITY }, { "c_tes", 0, INFINITY }, { "c_tp", 0, INFINITY },
    { "c_prim", 0, INFINITY } };

static const fit_bound catalog__nonneg_raster[] = {
    { "c_fb", 0, INFINITY }, { "c_fs", 0, INFINITY }, { "c_edge", 0, INFINITY }, { "c_prim", 0, INFINITY } };

static const fit_bound catalog__nonneg_fragment[] = {
    { "c0", 0, INFINITY }, { "c_fs", 0, INFINITY }, { "c_px", 0, INFINITY }, { "c_step", 0, INFINITY },
    { "c_pstep", 0, INFINITY }, { "c_light", 0, INFINITY } };

static const fit_bound catalog__nonneg_trips[] = {
    { "c0", 0, INFINITY }, { "c_fs", 0, INFINITY }, { "c_px", 0, INFINITY }, { "c_trip", 0, INFINITY },
    { "c_light", 0, INFINITY } };

static const fit_bound catalog__nonneg_groups[] = {
    { "c0", 0, INFINITY }, { "c_grp", 0, INFINITY }, { "c_fs", 0, INFINITY }, { "c_trip", 0, INFINITY },
    { "c_light", 0, INFINITY } };

static const fit_bound catalog__nonneg2[] = { { "a", 0, INFINITY }, { "b", 0, INFINITY } };

static const fit_bound catalog__nonneg_geometry_time[] = {
    { "a", 0, INFINITY }, { "b", 0, INFINITY }, { "b_walk", 0, INFINITY } };

static const fit_bound catalog__nonneg_time_stages[] = {
    { "a", 0, INFINITY }, { "b_geo", 0, INFINITY }, { "b_raster", 0, INFINITY }, { "b_frag", 0, INFINITY } };

static const models_builtin catalog__models[] = {
    { "pipeline-linear",
      "c0 + c_vs*VSInvocations + c_tes*TESInvocations + c_prim*ClippingOutputPrimitives + c_px*SamplesPassed",
      "WallTime",
      "frame time as a non-negative sum of per-stage costs (vertex, tessellation, primitive, pixel)",
      catalog__nonneg5, 5, NULL, NULL },
    { "tess-power", "a + b*tess_level^p", "WallTime",
      "frame time against the tessellation level L: a + b*L^p", NULL, 0, NULL, NULL },
    { "resolution-linear", "a + b*SamplesPassed", "WallTime",
      "frame time against covered pixels: a fixed cost plus a cost per pixel", NULL, 0, NULL, NULL },
    /* one fit per shader variant: the costs per invocation are the variant's,
     * the invocation counts the configuration's (docs/models.md).  c_tp:
     * llvmpipe's draw module, each time it hands a batch of vertices on
     * (about every 12 primitives), resets the vertex ids of every vertex
     * the draw's tessellation produced -- a cost of evaluations x
     * primitives, measured at 0.50-0.54 instructions per
     * TESInvocations*ClippingOutputPrimitives on planes of 2-98 patches
     * and the cube at levels 4-16 (docs/counters.md). */
    { "stage-instructions",
      "c0 + c_vs*VSInvocations + c_tes*TESInvocations + c_tp*TessWalk"
      " + c_prim*ClippingOutputPrimitives + c_px*FSInvocations"
      " + c_step*FSInvocations*steps + c_light*FSInvocations*light_count",
      "Instructions",
      "instructions per frame of one shader variant: a cost per vertex, evaluation (growing with the "
      "draw's primitives), primitive and fragment invocation, the fragment's growing with steps and lights",
      catalog__nonneg_stage, 8, "variant", NULL },
    /* The three stage counters, each with the terms of its own stage
     * (docs/models.md, "Per-stage models"): geometry pays per vertex,
     * evaluation and primitive; setup and rasterization per framebuffer
     * pixel, per primitive and per 4x4 block run (FSInvocations counts 16
     * a block, once per triangle that touches it); shading per block and
     * per covered pixel, both growing with steps. */
    { "geometry-instructions",
      "c0 + c_vs*VSInvocations + c_tes*TESInvocations + c_tp*TessWalk"
      " + c_prim*ClippingOutputPrimitives",
      "GeometryInstructions",
      "instructions of the geometry stages of one shader variant: per vertex, evaluation and primitive, "
      "the evaluation's growing with the draw's primitives",
      catalog__nonneg_geometry, 5, "variant", NULL },
    /* Setup and rasterization pay per framebuffer pixel (resolution is the
     * pixel count: the frame's clear of colour and depth among it, which
     * rasterizer discard drops from the geometry pass),
     * per 4x4 block lane run, more per lane of a block the primitive only
     * partly covers (FSInvocations - SamplesPassed: the per-pixel coverage
     * masks a fully covered block skips), and per primitive.  No constant:
     * fitted over the default sweep it is 0 ± 1e4. */
    { "raster-instructions",
      "c_fb*resolution + c_fs*FSInvocations + c_edge*(FSInvocations - SamplesPassed)"
      " + c_prim*ClippingOutputPrimitives",
      "RasterInstructions",
      "instructions of setup and rasterization of one shader variant: per framebuffer pixel, fragment "
      "block lane run, lane a primitive leaves uncovered, and primitive",
      catalog__nonneg_raster, 4, "variant", NULL },
    { "fragment-instructions",
      "c0 + c_fs*FSInvocations + c_px*SamplesPassed + c_step*FSInvocations*steps + c_pstep*SamplesPassed*steps"
      " + c_light*FSInvocations*light_count",
      "FragmentInstructions",
      "instructions of fragment shading of one shader variant: per fragment invocation and covered pixel, "
      "growing with steps and lights",
      catalog__nonneg_fragment, 6, "variant", NULL },
    /* The loop's cost is what its SIMD groups run: a group iterates until
     * its slowest fragment is done, so with the same steps a scene whose
     * neighbouring fragments stop at more different steps (a sharp height
     * map, a lower resolution) pays more per fragment.  LoopTrips counts
     * exactly that (docs/counters.md, "Loop trips"). */
    { "fragment-trips",
      "c0 + c_fs*FSInvocations + c_px*SamplesPassed + c_trip*LoopTrips + c_light*FSInvocations*light_count",
      "FragmentInstructions",
      "instructions of fragment shading of one shader variant: per fragment invocation, covered pixel and "
      "trip of the search loop (LoopTrips), growing with lights",
      catalog__nonneg_trips, 5, "variant", "LoopTrips" },
    /* llvmpipe runs the fragment shader on a group of 8 fragments (4x2 of
     * a 4x4 block at 256 bits) only where the triangle covers one of them:
     * FragmentGroups counts those groups, and a group costs its shader
     * whatever its coverage.  A block a triangle touches still costs a
     * little on its own (c_fs: its coverage masks), and the search loop
     * its trips.  On the sphere of 5 120 triangles, where half the groups
     * of the touched blocks are empty, per-invocation and per-pixel costs
     * missed 288x192 by -7.6 % from 96x64 and 192x128; per group, by
     * -0.1 % (docs/models.md, "Fragment groups"). */
    { "fragment-groups",
      "c0 + c_grp*FragmentGroups + c_fs*FSInvocations + c_trip*LoopTrips + c_light*FragmentGroups*light_count",
      "FragmentInstructions",
      "instructions of fragment shading of one shader variant: per SIMD group of fragments run "
      "(FragmentGroups), per block a triangle touches, and per trip of the search loop (LoopTrips), "
      "growing with lights",
      catalog__nonneg_groups, 5, "variant", "FragmentGroups LoopTrips" },
    /* Each stage's own time, from the timed isolation passes: GeometryTime
     * (rasterizer discard), SetupRasterTime = MinimalShadingTime -
     * GeometryTime and FragmentTime = WallTime - MinimalShadingTime.  Each
     * stage's price of an instruction is fitted where that stage is the
     * whole response; fitted to WallTime instead (time-from-stages) the
     * geometry price rests on frames it is a few per cent of and does not
     * carry to frames it dominates.  b_walk: a cost the instructions do
     * not show, llvmpipe's draw module walking all of a tessellated draw's
     * vertices once per batch of primitives (c_tp of
     * geometry-instructions), a loop over a buffer that outgrows the
     * caches; fitted without it on bench/extrapolate_fit.yaml, the
     * 98-patch plane at level 16, 93 % walk, came out -36 % in geometry
     * time (docs/models.md, "Frame time by stage"). */
    { "geometry-time", "a + b*GeometryInstructions + b_walk*TessWalk",
      "GeometryTime",
      "time of the geometry stages (rasterizer discard pass) from their instructions, and per vertex "
      "the tessellated draw's vertex walk visits",
      catalog__nonneg_geometry_time, 3, NULL, NULL },
    { "raster-time", "a + b*RasterInstructions", "SetupRasterTime",
      "time of setup and rasterization (minimal-shader pass minus the geometry pass) from their instructions",
      catalog__nonneg2, 2, NULL, "MinimalShadingTime" },
    { "fragment-time", "a + b*FragmentInstructions", "FragmentTime",
      "time of fragment shading (the frame minus the minimal-shader pass) from its instructions",
      catalog__nonneg2, 2, NULL, "MinimalShadingTime" },
    { "time-from-instructions", "a + b*Instructions", "WallTime",
      "frame time from the frame's instructions: a fixed cost plus a time per instruction",
      catalog__nonneg2, 2, NULL, NULL },
    /* llvmpipe runs the geometry stages on the thread that draws, and
     * rasterizes and shades on all its threads, so an instruction of each
     * stage takes another time (docs/models.md, "Per-stage models"). */
    { "time-from-stages", "a + b_geo*GeometryInstructions + b_raster*RasterInstructions + b_frag*FragmentInstructions",
      "WallTime",
      "frame time from the instructions of each stage: a fixed cost plus a time per instruction of the "
      "geometry, raster and fragment stages",
      catalog__nonneg_time_stages, 4, NULL, NULL },
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
