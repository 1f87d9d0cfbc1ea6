/* Unit tests of techniques/fs_minimal.c (no GL): the minimal fragment
 * shader of the stage-isolation passes, as text. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <string.h>

#include "core/dm_error.h"
#include "techniques/fs_minimal.h"

static const char shader[] =
    "#version 450 core\n"
    "#define MAX_LIGHTS 4\n"
    "// a comment naming discard and gl_FragDepth does not count\n"
    "in SurfaceData {\n"
    "    vec2 uv;\n"
    "    vec3 view_ts;\n"
    "    vec3 light_ts[MAX_LIGHTS];\n"
    "} vi;\n"
    "flat in int v_id;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "uniform sampler2D t;\n"
    "struct S { float a; };\n"
    "float helper(in vec2 p) { return texture(t, p).r; }\n"
    "void main ()\n"
    "{\n"
    "    o_color = vec4(helper(vi.uv));\n"
    "}\n";

/* main is renamed, the new main reads only the active inputs (arrays
 * whole) and writes every output. */
static void test_minimal_reads_active_inputs(void **state)
{
    (void)state;
    dm_str out = {0}, why = {0};
    assert_int_equal(fs_minimal_make(shader, "SurfaceData.uv\nSurfaceData.light_ts[0]\n", &out, &why), 0);
    const char *s = dm_str_get(&out);
    assert_non_null(strstr(s, "void dm__shade_main ()"));
    assert_non_null(strstr(s, "dm_s += dm__sum(vi.uv);"));
    assert_non_null(strstr(s, "for (int dm_k = 0; dm_k < (MAX_LIGHTS ); dm_k++)"));
    assert_non_null(strstr(s, "dm_s += dm__sum(vi.light_ts[dm_k]);"));
    assert_null(strstr(s, "vi.view_ts)"));             /* not active in the original */
    assert_null(strstr(s, "dm__sum(v_id)"));
    assert_non_null(strstr(s, "o_color = vec4(dm_s);"));
    assert_null(strstr(s, "gl_FragDepth ="));          /* the original does not write depth */
    assert_null(strstr(s, "a comment"));               /* comments removed */
    dm_str_free(&out);
    assert_int_equal(fs_minimal_make(shader, NULL, &out, &why), 0);   /* NULL: every input */
    assert_non_null(strstr(dm_str_get(&out), "dm__sum(vi.view_ts)"));
    assert_non_null(strstr(dm_str_get(&out), "dm__sum(v_id)"));
    dm_str_free(&out);
    assert_int_equal((int)why.len, 0);
}

/* Depth writes and discards are found in code, not in comments; a depth
 * writer's minimal shader writes gl_FragCoord.z. */
static void test_traits_and_depth(void **state)
{
    (void)state;
    fs_traits t;
    fs_minimal_traits(shader, &t);
    assert_int_equal(t.discards, 0);
    assert_int_equal(t.writes_depth, 0);
    static const char depth[] = "#version 450 core\nin vec2 uv;\nout vec4 c;\n"
                                "void main() { if (uv.x > 0.5) discard; c = vec4(1); gl_FragDepth = uv.y; }\n";
    fs_minimal_traits(depth, &t);
    assert_int_equal(t.discards, 1);
    assert_int_equal(t.writes_depth, 1);
    dm_str out = {0}, why = {0};
    assert_int_equal(fs_minimal_make(depth, "uv\n", &out, &why), 0);
    assert_non_null(strstr(dm_str_get(&out), "gl_FragDepth = gl_FragCoord.z;"));
    assert_non_null(strstr(dm_str_get(&out), "dm_s += dm__sum(uv);"));
    assert_non_null(strstr(dm_str_get(&out), "c = vec4(dm_s);"));
    dm_str_free(&out);
}

/* Refusals name the reason: no main, an input type it cannot read. */
static void test_refusals(void **state)
{
    (void)state;
    dm_str out = {0}, why = {0};
    assert_int_equal(fs_minimal_make("#version 450 core\nout vec4 c;\n", NULL, &out, &why), DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&why), "no `void main(`"));
    dm_str_free(&why);
    assert_int_equal(fs_minimal_make("#version 450 core\nstruct T { float a; };\nin T t;\nout vec4 c;\n"
                                     "void main() { c = vec4(t.a); }\n", NULL, &out, &why), DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&why), "fragment input t has type T"));
    assert_int_equal((int)out.len, 0);
    dm_str_free(&why);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_minimal_reads_active_inputs),
             cmocka_unit_test(test_traits_and_depth),
             cmocka_unit_test(test_refusals))
