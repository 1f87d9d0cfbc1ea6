/* counters_registry.c — the one table of counters (docs/counters.md), as data.
 *
 * Each row: public metadata (name, group, description, unit, type, backend,
 * deterministic, formula, who feeds a caller-fed value, whether its CI
 * stops sampling; the last two default to none) + which pass measures it, its GL query target and
 * what the driver must offer.  Derived counters are formulas over other rows
 * (evaluated by counters_expr.c).  Adding a counter is adding a row.
 */
#include "counters_internal.h"

#include <epoxy/gl.h>
#include <string.h>

#define NS    COUNTERS_UNIT_NS
#define ITEMS COUNTERS_UNIT_ITEMS
#define BYTES COUNTERS_UNIT_BYTES
#define RATIO COUNTERS_UNIT_RATIO
#define U64   COUNTERS_TYPE_UINT64
#define F64   COUNTERS_TYPE_FLOAT64
#define B_CLK COUNTERS_BACKEND_CLOCK
#define B_TQ  COUNTERS_BACKEND_TIMER_QUERY
#define B_PS  COUNTERS_BACKEND_PIPELINE_STATS
#define B_OCC COUNTERS_BACKEND_OCCLUSION
#define B_CPU COUNTERS_BACKEND_CPU_SIDE
#define B_DER COUNTERS_BACKEND_DERIVED
#define P_TIM COUNTERS__PASS_TIMING
#define P_GEO COUNTERS__PASS_GEOMETRY
#define P_RAS COUNTERS__PASS_RASTER
#define P_ST  COUNTERS__PASS_STATS
#define P_NO  COUNTERS__PASS_NONE
#define R_PS  COUNTERS__REQ_PIPESTATS
#define F_NO  COUNTERS_FEED_NONE, 0   /* not caller-fed, does not stop sampling */

static const counters__def counters__table[] = {
    /* ---- Timing ---- */
    {{"WallTime", "Timing", "Wall-clock time of the sample, glFinish before and after",
      NS, U64, B_CLK, 0, NULL, COUNTERS_FEED_NONE, 1}, P_TIM, 0, 0},
    {{"GPUTime", "Timing", "GL_TIME_ELAPSED query around the sample (check the timer calibration)",
      NS, U64, B_TQ, 0, NULL, F_NO}, P_TIM, GL_TIME_ELAPSED, COUNTERS__REQ_TIMER},
    {{"CPUTime", "Timing", "Process CPU time over the sample, all threads, including the final glFinish",
      NS, U64, B_CLK, 0, NULL, F_NO}, P_TIM, 0, 0},
    {{"SubmitTime", "Timing", "Calling-thread CPU time from sample begin until the closing glFinish (inside draw calls)",
      NS, U64, B_CLK, 0, NULL, F_NO}, P_TIM, 0, 0},
    {{"GeometryTime", "Timing", "Wall time of the same draws with GL_RASTERIZER_DISCARD (own pass)",
      NS, U64, B_CLK, 0, NULL, F_NO}, P_GEO, 0, 0},
    {{"MinimalShadingTime", "Timing", "Wall time of the same draws with a minimal fragment shader (own pass; "
      "docs/counters.md, Stage costs)",
      NS, U64, B_CLK, 0, NULL, F_NO}, P_RAS, 0, 0},
    {{"SetupTime", "Timing", "Compile, link and upload time, fed by the caller",
      NS, U64, B_CPU, 0, NULL, COUNTERS_FEED_SETUP_NS, 0}, P_NO, 0, 0},
    {{"WarmupTime", "Timing", "First-draw time (shader JIT), fed by the caller",
      NS, U64, B_CPU, 0, NULL, COUNTERS_FEED_WARMUP_NS, 0}, P_NO, 0, 0},
    /* ---- Vertex ---- */
    {{"VerticesSubmitted", "Vertex", "Vertices fetched by the vertex puller, repeats included",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_VERTICES_SUBMITTED_ARB, R_PS},
    {{"PrimitivesSubmitted", "Vertex", "Primitives assembled from the submitted vertices",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_PRIMITIVES_SUBMITTED_ARB, R_PS},
    {{"VSInvocations", "Vertex", "Vertex shader invocations (after post-transform vertex reuse)",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_VERTEX_SHADER_INVOCATIONS_ARB, R_PS},
    /* ---- Tessellation ---- */
    {{"TCSPatches", "Tessellation", "Patches processed by the tessellation control shader",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_TESS_CONTROL_SHADER_PATCHES_ARB, R_PS},
    {{"TESInvocations", "Tessellation", "Tessellation evaluation shader invocations",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB, R_PS},
    {{"TessWalkCalls", "Tessellation", "Sum over the frame's draw calls of patches that the clipper changed "
      "(ClippingInputPrimitives != ClippingOutputPrimitives) of the call's TESInvocations x "
      "ClippingOutputPrimitives: the steps of llvmpipe's vertex walk (pipeline statistics around each call, "
      "own pass of one frame; unavailable without tessellation; docs/counters.md, TessWalkCalls)",
      ITEMS, U64, COUNTERS_BACKEND_PER_CALL, 1, NULL, F_NO}, P_NO, 0, R_PS},
    /* ---- Geometry ---- */
    {{"GSInvocations", "Geometry", "Geometry shader invocations",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_GEOMETRY_SHADER_INVOCATIONS, R_PS},
    {{"GSPrimitivesEmitted", "Geometry", "Primitives emitted by the geometry shader",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB, R_PS},
    /* ---- PrimitiveAssembly ---- */
    {{"ClippingInputPrimitives", "PrimitiveAssembly", "Primitives entering the clipper",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_CLIPPING_INPUT_PRIMITIVES_ARB, R_PS},
    {{"ClippingOutputPrimitives", "PrimitiveAssembly", "Primitives leaving the clipper (to the rasterizer)",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_CLIPPING_OUTPUT_PRIMITIVES_ARB, R_PS},
    {{"PrimitivesGenerated", "PrimitiveAssembly", "GL_PRIMITIVES_GENERATED: primitives out of the last vertex-processing stage",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_PRIMITIVES_GENERATED, 0},
    /* ---- Fragment ---- */
    {{"FSInvocations", "Fragment", "Fragment shader invocations",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_FRAGMENT_SHADER_INVOCATIONS_ARB, R_PS},
    {{"SamplesPassed", "Fragment", "Samples that passed the depth and stencil tests (occlusion query)",
      ITEMS, U64, B_OCC, 1, NULL, F_NO}, P_ST, GL_SAMPLES_PASSED, 0},
    {{"LoopTrips", "Fragment", "Iterations of the parallax search loop as the fragment shader's SIMD groups "
      "run them: per group (subgroup) as many as its slowest active fragment needs (own pass with an "
      "instrumented shader; 0 without the loop; docs/counters.md, Loop trips)",
      ITEMS, U64, COUNTERS_BACKEND_SHADER_COUNT, 1, NULL, F_NO}, COUNTERS__PASS_LOOPS, 0, COUNTERS__REQ_BALLOT},
    {{"FragmentGroups", "Fragment", "SIMD groups of fragments the fragment shader runs: per triangle, each "
      "group of a 4x4 block (llvmpipe: 4x2 fragments at 256 bits) that holds a covered fragment (own pass "
      "with an instrumented shader, the LoopTrips pass; docs/counters.md, Fragment groups)",
      ITEMS, U64, COUNTERS_BACKEND_SHADER_COUNT, 1, NULL, F_NO}, COUNTERS__PASS_LOOPS, 0, COUNTERS__REQ_BALLOT},
    /* ---- Compute ---- */
    {{"ComputeInvocations", "Compute", "Compute shader invocations",
      ITEMS, U64, B_PS, 1, NULL, F_NO}, P_ST, GL_COMPUTE_SHADER_INVOCATIONS_ARB, COUNTERS__REQ_COMPUTE},
    /* ---- Memory (caller-fed) ---- */
    {{"TextureBytes", "Memory", "Bytes of texture storage (driver-reported sizes), fed by the caller",
      BYTES, U64, B_CPU, 1, NULL, COUNTERS_FEED_TEXTURE_BYTES, 0}, P_NO, 0, 0},
    {{"MeshBytes", "Memory", "Bytes of vertex and index buffers, fed by the caller",
      BYTES, U64, B_CPU, 1, NULL, COUNTERS_FEED_MESH_BYTES, 0}, P_NO, 0, 0},
    {{"MeshTriangles", "Memory", "Triangles of the mesh as submitted (before tessellation), fed by the caller",
      ITEMS, U64, B_CPU, 1, NULL, COUNTERS_FEED_MESH_TRIANGLES, 0}, P_NO, 0, 0},
    {{"VTPagesResident", "Memory", "Virtual-texture pages resident at the end of the configuration's samples",
      ITEMS, U64, B_CPU, 1, NULL, COUNTERS_FEED_VT_RESIDENT, 0}, P_NO, 0, 0},
    {{"VTPageMisses", "Memory", "Virtual-texture page requests not resident, over the configuration's samples",
      ITEMS, U64, B_CPU, 1, NULL, COUNTERS_FEED_VT_MISSES, 0}, P_NO, 0, 0},
    {{"VTUploadBytes", "Memory", "Bytes uploaded to the virtual texture over the configuration's samples",
      BYTES, U64, B_CPU, 1, NULL, COUNTERS_FEED_VT_UPLOAD_BYTES, 0}, P_NO, 0, 0},
    {{"VTCommittedBytes", "Memory", "Page storage of the virtual texture at the end of the configuration's "
      "samples: the committed pages (sparse) or the whole page cache (software)",
      BYTES, U64, B_CPU, 1, NULL, COUNTERS_FEED_VT_COMMITTED_BYTES, 0}, P_NO, 0, 0},
    /* ---- Scene (caller-fed, needed by derived counters) ---- */
    {{"ViewportPixels", "Scene", "Pixels of the viewport times frames in the sample, fed by the caller",
      ITEMS, U64, B_CPU, 1, NULL, COUNTERS_FEED_VIEWPORT_PIXELS, 0}, P_NO, 0, 0},
    /* ---- Cost (own child under Valgrind callgrind, run/callgrind.h) ---- */
    {{"Instructions", "Cost", "Instructions retired per frame by the measured frames (callgrind, collection only "
      "around K frames ended by glFinish, LP_NUM_THREADS=0; deterministic on CPU renderers)",
      ITEMS, U64, COUNTERS_BACKEND_CALLGRIND, 1, NULL, F_NO}, P_NO, 0, COUNTERS__REQ_CALLGRIND},
    {{"InstructionsPerPixel", "Cost", "Instructions per covered sample (Instructions / SamplesPassed)",
      RATIO, F64, B_DER, 1, "Instructions / SamplesPassed", F_NO}, P_NO, 0, 0},
    /* stage costs: isolation windows counted in the same child (docs/counters.md, "Stage costs") */
    {{"GeometryInstructions", "Cost", "Instructions per frame of the same frames with GL_RASTERIZER_DISCARD: "
      "vertex, tessellation, primitive assembly and clipping",
      ITEMS, U64, COUNTERS_BACKEND_CALLGRIND, 1, NULL, F_NO}, P_NO, 0, COUNTERS__REQ_CALLGRIND},
    {{"RasterInstructions", "Cost", "Instructions per frame of setup, rasterization, depth test and output: "
      "the frames with a minimal fragment shader minus GeometryInstructions",
      ITEMS, U64, COUNTERS_BACKEND_CALLGRIND, 1, NULL, F_NO}, P_NO, 0, COUNTERS__REQ_CALLGRIND},
    {{"FragmentInstructions", "Cost", "Instructions per frame of fragment shading: Instructions minus the "
      "frames with a minimal fragment shader",
      ITEMS, U64, COUNTERS_BACKEND_CALLGRIND, 1, NULL, F_NO}, P_NO, 0, COUNTERS__REQ_CALLGRIND},
    {{"StageResidual", "Cost", "GeometryInstructions minus the same frames with the minimal fragment shader "
      "and discard: geometry work the isolation changed (0 when exact)",
      ITEMS, F64, COUNTERS_BACKEND_CALLGRIND, 1, NULL, F_NO}, P_NO, 0, COUNTERS__REQ_CALLGRIND},
    {{"GeometryShare", "Cost", "Share of the frame's instructions in the geometry stages",
      RATIO, F64, B_DER, 1, "GeometryInstructions / Instructions", F_NO}, P_NO, 0, 0},
    {{"RasterShare", "Cost", "Share of the frame's instructions in setup and rasterization",
      RATIO, F64, B_DER, 1, "RasterInstructions / Instructions", F_NO}, P_NO, 0, 0},
    {{"FragmentShare", "Cost", "Share of the frame's instructions in fragment shading",
      RATIO, F64, B_DER, 1, "FragmentInstructions / Instructions", F_NO}, P_NO, 0, 0},
    {{"InstructionsPerVertex", "Cost", "Geometry instructions per vertex shader invocation",
      RATIO, F64, B_DER, 1, "GeometryInstructions / VSInvocations", F_NO}, P_NO, 0, 0},
    {{"InstructionsPerEvaluation", "Cost", "Geometry instructions per tessellation evaluation invocation "
      "(unavailable without tessellation)",
      RATIO, F64, B_DER, 1, "GeometryInstructions / TESInvocations", F_NO}, P_NO, 0, 0},
    {{"RasterInstructionsPerPixel", "Cost", "Setup and rasterization instructions per covered sample",
      RATIO, F64, B_DER, 1, "RasterInstructions / SamplesPassed", F_NO}, P_NO, 0, 0},
    {{"FragmentInstructionsPerPixel", "Cost", "Fragment shading instructions per covered sample",
      RATIO, F64, B_DER, 1, "FragmentInstructions / SamplesPassed", F_NO}, P_NO, 0, 0},
    /* ---- Derived ---- */
    {{"TessAmplification", "Derived", "TES invocations per tessellation patch",
      RATIO, F64, B_DER, 1, "TESInvocations / TCSPatches", F_NO}, P_NO, 0, 0},
    {{"VertexReuse", "Derived", "Submitted vertices per vertex shader invocation (post-transform reuse)",
      RATIO, F64, B_DER, 1, "VerticesSubmitted / VSInvocations", F_NO}, P_NO, 0, 0},
    {{"ClippedFraction", "Derived", "1 - clipper output / clipper input primitives (negative when clipping splits)",
      RATIO, F64, B_DER, 1, "1 - ClippingOutputPrimitives / ClippingInputPrimitives", F_NO}, P_NO, 0, 0},
    {{"PixelsPerTriangle", "Derived", "Samples passed per primitive reaching the rasterizer",
      RATIO, F64, B_DER, 1, "SamplesPassed / ClippingOutputPrimitives", F_NO}, P_NO, 0, 0},
    {{"Overdraw", "Derived", "Samples passed per viewport pixel (depth-tested overdraw; needs ViewportPixels)",
      RATIO, F64, B_DER, 1, "SamplesPassed / ViewportPixels", F_NO}, P_NO, 0, 0},
    {{"ShadingEfficiency", "Derived", "Samples passed per fragment shader invocation",
      RATIO, F64, B_DER, 1, "SamplesPassed / FSInvocations", F_NO}, P_NO, 0, 0},
    {{"RasterTime", "Derived", "Wall time minus geometry-only time (rasterization and shading)",
      NS, F64, B_DER, 0, "WallTime - GeometryTime", F_NO}, P_NO, 0, 0},
    {{"SetupRasterTime", "Derived", "Setup and rasterization time: minimal-shader time minus geometry-only time",
      NS, F64, B_DER, 0, "MinimalShadingTime - GeometryTime", F_NO}, P_NO, 0, 0},
    {{"FragmentTime", "Derived", "Fragment shading time: wall time minus minimal-shader time",
      NS, F64, B_DER, 0, "WallTime - MinimalShadingTime", F_NO}, P_NO, 0, 0},
    {{"TimePerPixel", "Derived", "Wall time per sample passed",
      NS, F64, B_DER, 0, "WallTime / SamplesPassed", F_NO}, P_NO, 0, 0},
};

#define COUNTERS__N (sizeof counters__table / sizeof counters__table[0])
_Static_assert(COUNTERS__N <= COUNTERS__MAX, "raise COUNTERS__MAX");

size_t counters_count(void) { return COUNTERS__N; }

const counters__def *counters__def_at(size_t i)
{
    return i < COUNTERS__N ? &counters__table[i] : NULL;
}

const counters_info *counters_info_at(size_t i)
{
    return i < COUNTERS__N ? &counters__table[i].info : NULL;
}

int counters__index(const char *name)
{
    for (size_t i = 0; name && i < COUNTERS__N; i++)
        if (strcmp(counters__table[i].info.name, name) == 0)
            return (int)i;
    return -1;
}

const counters_info *counters_find(const char *name)
{
    int i = counters__index(name);
    return i < 0 ? NULL : &counters__table[i].info;
}

const char *counters_unit_name(counters_unit u)
{
    switch (u) {
    case COUNTERS_UNIT_NS: return "ns";
    case COUNTERS_UNIT_ITEMS: return "items";
    case COUNTERS_UNIT_BYTES: return "bytes";
    case COUNTERS_UNIT_RATIO: return "ratio";
    case COUNTERS_UNIT_PERCENT: return "percent";
    }
    return "?";
}
