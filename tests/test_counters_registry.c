/* Unit tests of counters/ without GL: the registry table and the formula
 * evaluator of derived counters on known inputs. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <stdlib.h>
#include <string.h>
#include <stdio.h>
#include <math.h>

#include "core/dm_error.h"
#include "counters/counters.h"
#include "counters/counters_expr.h"

/* Every counter docs/counters.md names, with its group. */
static const char *const spec_counters[][2] = {
    {"WallTime", "Timing"}, {"GPUTime", "Timing"}, {"CPUTime", "Timing"},
    {"SubmitTime", "Timing"}, {"GeometryTime", "Timing"}, {"SetupTime", "Timing"},
    {"WarmupTime", "Timing"}, {"VerticesSubmitted", "Vertex"},
    {"PrimitivesSubmitted", "Vertex"}, {"VSInvocations", "Vertex"},
    {"TCSPatches", "Tessellation"}, {"TESInvocations", "Tessellation"}, {"TessWalkCalls", "Tessellation"},
    {"GSInvocations", "Geometry"}, {"GSPrimitivesEmitted", "Geometry"},
    {"ClippingInputPrimitives", "PrimitiveAssembly"},
    {"ClippingOutputPrimitives", "PrimitiveAssembly"},
    {"PrimitivesGenerated", "PrimitiveAssembly"}, {"FSInvocations", "Fragment"},
    {"SamplesPassed", "Fragment"}, {"TextureBytes", "Memory"}, {"MeshBytes", "Memory"},
    {"VTPagesResident", "Memory"}, {"VTPageMisses", "Memory"}, {"VTUploadBytes", "Memory"},
    {"TessAmplification", "Derived"}, {"VertexReuse", "Derived"},
    {"ClippedFraction", "Derived"}, {"PixelsPerTriangle", "Derived"},
    {"Overdraw", "Derived"}, {"ShadingEfficiency", "Derived"},
    {"RasterTime", "Derived"}, {"TimePerPixel", "Derived"},
};

static void test_registry_has_spec_counters(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof spec_counters / sizeof spec_counters[0]; i++) {
        const counters_info *c = counters_find(spec_counters[i][0]);
        if (!c)
            fail_msg("counter %s missing from the registry", spec_counters[i][0]);
        assert_string_equal(c->group, spec_counters[i][1]);
        assert_true(strlen(c->description) > 10);
        assert_int_equal(c->backend == COUNTERS_BACKEND_DERIVED, c->formula != NULL);
    }
    assert_null(counters_find("NoSuchCounter"));
    assert_null(counters_find(NULL));
    assert_null(counters_info_at(counters_count()));
    assert_string_equal(counters_unit_name(COUNTERS_UNIT_NS), "ns");
    assert_string_equal(counters_unit_name(COUNTERS_UNIT_BYTES), "bytes");
    assert_string_equal(counters_unit_name(COUNTERS_UNIT_RATIO), "ratio");
}

static void test_registry_names_unique_and_typed(void **state)
{
    (void)state;
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *c = counters_info_at(i);
        assert_ptr_equal(counters_find(c->name), c);      /* unique: find returns this row */
        assert_true(c->unit >= COUNTERS_UNIT_NS && c->unit <= COUNTERS_UNIT_PERCENT);
        assert_true(c->type == COUNTERS_TYPE_UINT64 || c->type == COUNTERS_TYPE_FLOAT64);
        /* Timing from clocks is never deterministic; pipeline counts are. */
        if (c->backend == COUNTERS_BACKEND_CLOCK || c->backend == COUNTERS_BACKEND_TIMER_QUERY)
            assert_int_equal(c->deterministic, 0);
        if (c->backend == COUNTERS_BACKEND_PIPELINE_STATS || c->backend == COUNTERS_BACKEND_OCCLUSION ||
            c->backend == COUNTERS_BACKEND_PER_CALL)
            assert_int_equal(c->deterministic, 1);
    }
    /* a per-call counter is summed from pipeline statistics read around each call */
    for (size_t j = 0; j < COUNTERS_TESS_WALK_N; j++) {
        const counters_info *c = counters_find(counters_tess_walk_inputs[j]);
        assert_non_null(c);
        assert_int_equal(c->backend, COUNTERS_BACKEND_PIPELINE_STATS);
    }
    assert_int_equal(counters_find("TessWalkCalls")->backend, COUNTERS_BACKEND_PER_CALL);
}

/* Lookup over a fixed table: A=6, B=3, Z=0; "Bad" is unavailable. */
static int lookup(const char *name, size_t len, void *user, double *v, dm_str *err)
{
    (void)user;
    static const struct { const char *n; double v; } tab[] = {{"A", 6}, {"B", 3}, {"Z", 0}};
    for (size_t i = 0; i < 3; i++)
        if (strlen(tab[i].n) == len && memcmp(tab[i].n, name, len) == 0) {
            *v = tab[i].v;
            return 0;
        }
    dm_str_printf(err, "%.*s unavailable", (int)len, name);
    return DM_ERR_UNAVAILABLE;
}

static int eval(const char *f, double *v, dm_str *err)
{
    dm_str_free(err);
    return counters__expr_eval(f, lookup, NULL, v, err);
}

static void test_expr_known_inputs(void **state)
{
    (void)state;
    dm_str err = {0};
    double v = -1;
    assert_int_equal(eval("A / B", &v, &err), 0);
    assert_true(v == 2.0);
    assert_int_equal(eval("1 - B / A", &v, &err), 0);
    assert_true(v == 0.5);
    assert_int_equal(eval("(A + B) * 2 - -B", &v, &err), 0);
    assert_true(v == 21.0);
    assert_int_equal(eval("A - B - 1", &v, &err), 0);     /* left associative */
    assert_true(v == 2.0);
    assert_int_equal(eval("A / B / 2", &v, &err), 0);
    assert_true(v == 1.0);
    assert_int_equal(eval("A*B+A/B", &v, &err), 0);       /* precedence */
    assert_true(v == 20.0);
    v = 7;
    assert_int_equal(eval("A / Z", &v, &err), DM_ERR_UNAVAILABLE);
    assert_non_null(strstr(dm_str_get(&err), "zero denominator"));
    assert_true(v == 7.0);                                /* untouched on failure */
    assert_int_equal(eval("A / (B - 3)", &v, &err), DM_ERR_UNAVAILABLE);
    assert_int_equal(eval("Z / A", &v, &err), 0);         /* zero numerator is fine */
    assert_true(v == 0.0);
    assert_int_equal(eval("A + Bad", &v, &err), DM_ERR_UNAVAILABLE);
    assert_string_equal(dm_str_get(&err), "Bad unavailable");
    dm_str_free(&err);
}

static void test_expr_syntax_errors(void **state)
{
    (void)state;
    dm_str err = {0};
    double v;
    assert_int_equal(eval("A +", &v, &err), DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&err), "unexpected end"));
    assert_int_equal(eval("(A + B", &v, &err), DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&err), "expected ')'"));
    assert_int_equal(eval("A B", &v, &err), DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&err), "offset 2"));
    assert_int_equal(eval("A $ B", &v, &err), DM_ERR_PARSE);
    assert_int_equal(eval("", &v, &err), DM_ERR_PARSE);
    dm_str_free(&err);
}

static void collect(const char *name, size_t len, void *user)
{
    dm_str *s = user;
    dm_str_catn(s, name, len);
    dm_str_cat(s, ",");
}

/* Every derived formula parses and names only registered counters. */
static void test_derived_formulas_resolve(void **state)
{
    (void)state;
    dm_str names = {0};
    counters__expr_names("1 - ClippingOutputPrimitives / ClippingInputPrimitives + 2.5e3", collect, &names);
    assert_string_equal(dm_str_get(&names), "ClippingOutputPrimitives,ClippingInputPrimitives,");
    dm_str_free(&names);
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *c = counters_info_at(i);
        if (!c->formula)
            continue;
        counters__expr_names(c->formula, collect, &names);
        char *list = dm_str_take(&names), *save = NULL;
        for (char *t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save))
            if (!counters_find(t))
                fail_msg("%s: formula names unknown counter %s", c->name, t);
        free(list);
    }
}

/* The columns run/measure.c reads instead of names: only caller-fed rows
 * have a feed, each feed is on one row, the ten fed by dmbench are the ones
 * expected; exactly one counter stops sampling, WallTime, a timed one. */
static void test_feeds_and_stop_counter(void **state)
{
    (void)state;
    static const struct { const char *name; counters_feed feed; } fed[] = {
        {"SetupTime", COUNTERS_FEED_SETUP_NS}, {"WarmupTime", COUNTERS_FEED_WARMUP_NS},
        {"TextureBytes", COUNTERS_FEED_TEXTURE_BYTES}, {"MeshBytes", COUNTERS_FEED_MESH_BYTES},
        {"MeshTriangles", COUNTERS_FEED_MESH_TRIANGLES}, {"ViewportPixels", COUNTERS_FEED_VIEWPORT_PIXELS},
        {"VTPagesResident", COUNTERS_FEED_VT_RESIDENT}, {"VTPageMisses", COUNTERS_FEED_VT_MISSES},
        {"VTUploadBytes", COUNTERS_FEED_VT_UPLOAD_BYTES}, {"VTCommittedBytes", COUNTERS_FEED_VT_COMMITTED_BYTES},
    };
    size_t n_fed = 0, n_stop = 0;
    for (size_t i = 0; i < counters_count(); i++) {
        const counters_info *c = counters_info_at(i);
        if (c->feed != COUNTERS_FEED_NONE) {
            assert_int_equal(c->backend, COUNTERS_BACKEND_CPU_SIDE);
            n_fed++;
        }
        if (c->stops_sampling) {
            assert_string_equal(c->name, "WallTime");
            assert_int_equal(c->backend, COUNTERS_BACKEND_CLOCK);
            n_stop++;
        }
    }
    assert_int_equal(n_fed, sizeof fed / sizeof fed[0]);
    assert_int_equal(n_stop, 1);
    for (size_t i = 0; i < sizeof fed / sizeof fed[0]; i++)
        assert_int_equal(counters_find(fed[i].name)->feed, fed[i].feed);
}

/* The bottleneck verdict: shares of the sum, decreasing, whole percent;
 * unavailable for a negative, non-finite or empty split. */
static void test_stage_verdict(void **state)
{
    (void)state;
    dm_str s = {0};
    assert_int_equal(counters_stage_verdict(9.0, 4.0, 87.0, &s), 0);
    assert_string_equal(dm_str_get(&s), "fragment 87 %, geometry 9 %, raster 4 %");
    dm_str_free(&s);
    assert_int_equal(counters_stage_verdict(1.0, 2.0, 1.0, &s), 0);   /* 25/50/25: ties keep fragment first */
    assert_string_equal(dm_str_get(&s), "raster 50 %, fragment 25 %, geometry 25 %");
    dm_str_free(&s);
    assert_int_equal(counters_stage_verdict(-1.0, 2.0, 1.0, &s), DM_ERR_UNAVAILABLE);
    assert_int_equal(counters_stage_verdict(0.0, 0.0, 0.0, &s), DM_ERR_UNAVAILABLE);
    assert_int_equal(counters_stage_verdict(NAN, 1.0, 1.0, &s), DM_ERR_UNAVAILABLE);
    assert_int_equal((int)s.len, 0);
}

/* The stage counters are counted in the Instructions pass, and the shares
 * and per-invocation counters are formulas over them. */
static void test_stage_counters_registered(void **state)
{
    (void)state;
    static const char *const counted[] = {"GeometryInstructions", "RasterInstructions", "FragmentInstructions",
                                          "StageResidual"};
    for (size_t i = 0; i < 4; i++) {
        const counters_info *ci = counters_find(counted[i]);
        assert_non_null(ci);
        assert_int_equal(ci->backend, COUNTERS_BACKEND_CALLGRIND);
        assert_int_equal(ci->deterministic, 1);
    }
    static const char *const derived[][2] = {
        {"GeometryShare", "GeometryInstructions / Instructions"},
        {"RasterShare", "RasterInstructions / Instructions"},
        {"FragmentShare", "FragmentInstructions / Instructions"},
        {"InstructionsPerVertex", "GeometryInstructions / VSInvocations"},
        {"InstructionsPerEvaluation", "GeometryInstructions / TESInvocations"},
        {"FragmentInstructionsPerPixel", "FragmentInstructions / SamplesPassed"}};
    for (size_t i = 0; i < sizeof derived / sizeof derived[0]; i++) {
        const counters_info *ci = counters_find(derived[i][0]);
        assert_non_null(ci);
        assert_string_equal(ci->formula, derived[i][1]);
    }
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_registry_has_spec_counters),
             cmocka_unit_test(test_registry_names_unique_and_typed),
             cmocka_unit_test(test_expr_known_inputs),
             cmocka_unit_test(test_expr_syntax_errors),
             cmocka_unit_test(test_derived_formulas_resolve),
             cmocka_unit_test(test_feeds_and_stop_counter),
             cmocka_unit_test(test_stage_verdict),
             cmocka_unit_test(test_stage_counters_registered))
