/* Unit tests of techniques/user_technique: a user's GLSL file registered as
 * a technique, its parameters as axes, its source hash, the driver-log
 * mapping and the checks of the header (no GL). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "techniques/axes.h"
#include "techniques/shaders.h"
#include "techniques/technique.h"
#include "techniques/user_technique.h"

static char *example(const char *name)
{
    const char *src = getenv("DMBENCH_SOURCE_DIR");
    return dm_xasprintf("%s/examples/%s", src ? src : ".", name);
}

static void test_load_example(void **state)
{
    (void)state;
    char *path = example("relief.glsl");
    size_t n_tech = technique_count(), n_axes = axes_count();
    dm_str err = {0};
    const char *name = NULL;
    assert_int_equal(user_technique_load(path, &name, &err), 0);
    assert_string_equal(name, "relief");
    assert_int_equal(technique_count(), n_tech + 1);
    assert_int_equal(axes_count(), n_axes + 2);   /* relief_linear, relief_binary */
    const axis_info *a = axes_find("relief_linear");
    assert_non_null(a);
    assert_int_equal(a->kind, AXIS_INT);
    assert_true(a->min == 1 && a->max == 256);
    assert_string_equal(a->def, "16");
    assert_int_equal(axes_check("relief_binary", "17", &err), DM_ERR_ARG);   /* range 0..16 */
    const technique_desc *t = technique_find("relief");
    assert_non_null(t);
    assert_true(technique_reads_axis(t, "relief_binary"));
    assert_true(technique_reads_axis(t, "height_scale"));
    assert_false(technique_reads_axis(t, "steps"));
    /* the key's source hash is FNV-1a of the file's bytes */
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(dm_read_file(path, &text, &len), 0);
    assert_true(t->source_hash == dm_fnv1a64(text, len, DM_FNV_SEED));
    /* the technique axis takes the file and stands for it by name */
    const char *const *names = technique_names();
    int listed = 0;
    for (size_t i = 0; names[i]; i++)
        listed |= strcmp(names[i], "relief") == 0;
    assert_true(listed);
    char *canon = axes_canonical("technique", path);
    assert_string_equal(canon, "relief");
    /* loading the same file again registers nothing */
    assert_int_equal(user_technique_load(path, NULL, &err), 0);
    assert_int_equal(technique_count(), n_tech + 1);
    /* the fragment stage: the built-in one, the uniforms, then the file from line BASE + 1 */
    dm_str src = {0};
    assert_int_equal(shaders_compose(t->fs, t->defines, &src, &err), 0);
    assert_non_null(strstr(dm_str_get(&src), "#define SURF_USER\n"));
    assert_non_null(strstr(dm_str_get(&src), "uniform int u_relief_linear;\nuniform int u_relief_binary;\n"
                                             "#line 100001\n              "));   /* comments blanked */
    assert_non_null(strstr(dm_str_get(&src), "vec3 user_surface(vec2 uv, vec3 v)\n"));
    dm_str_free(&src);
    free(canon);
    free(text);
    free(path);
    dm_str_free(&err);
}

static void test_map_log(void **state)
{
    (void)state;
    char *path = example("pom-texel.glsl");
    dm_str err = {0}, out = {0};
    assert_int_equal(user_technique_load(path, NULL, &err), 0);
    const technique_desc *t = technique_find("pom-texel");
    user_technique_map_log(t,
                           "0:304(60): warning: `g_dx' used uninitialized\n"
                           "0:100012(3): error: `foo' undeclared\n"
                           "0:12(1): error: built-in line\n"
                           "error: linking failed", &out);
    char *want = dm_xasprintf("%s:12:3: error: `foo' undeclared\n0:12(1): error: built-in line\n"
                              "error: linking failed\n", path);
    assert_string_equal(dm_str_get(&out), want);
    /* a built-in technique's log is kept as it is */
    dm_str plain = {0};
    user_technique_map_log(technique_find("normal"), "0:100012(3): warning: w\n", &plain);
    assert_string_equal(dm_str_get(&plain), "0:100012(3): warning: w\n");
    dm_str_free(&plain);
    free(want);
    dm_str_free(&out);
    dm_str_free(&err);
    free(path);
}

/* Writes text to a temporary .glsl file and loads it; returns the code. */
static int load_text(const char *text, dm_str *err, char **path)
{
    char tmpl[] = "/tmp/dm_user_XXXXXX";
    int fd = mkstemp(tmpl);
    assert_true(fd >= 0);
    close(fd);
    *path = dm_xasprintf("%s.glsl", tmpl);
    rename(tmpl, *path);
    assert_int_equal(dm_write_file(*path, text, strlen(text)), 0);
    return user_technique_load(*path, NULL, err);
}

static void test_bad_headers(void **state)
{
    (void)state;
    static const struct { const char *text, *msg; } cases[] = {
        {"//@technique u1\n//@param height_scale float 0 1 0.5\n",
         ":2: parameter 'height_scale' collides with the built-in axis 'height_scale'"},
        {"//@technique u2\n//@param k int 1 4\n", ":2: @param needs NAME TYPE MIN MAX DEFAULT"},
        {"//@technique u3\n//@param k int 1 4 9\n", ":2: parameter 'k': default 9 is outside [1, 4]"},
        {"//@technique u4\n//@param k int 1 4.5 2\n", ":2: parameter 'k': MIN MAX DEFAULT must be int numbers"},
        {"//@technique U5\n", ":1: technique name 'U5': use lower-case letters"},
        {"//@technique u6\n//@params k int 1 4 2\n", ":2: unknown directive '@params'; valid directives: "
                                                     "@technique, @summary, @base, @param"},
        {"//@technique u7\n/* vec3 user_surface(vec2 uv, vec3 v) {} */\n", ": no entry point"},
        {"//@technique u8\nvec3 user_surface(vec2 uv, float v) { return vec3(0.0); }\n",
         ":2: entry point has the wrong signature `vec3 user_surface(vec2, float)`"},
    };
    size_t n_tech = technique_count(), n_axes = axes_count();
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dm_str err = {0};
        char *path = NULL, *text = dm_xasprintf("%s%s", cases[i].text,
                                                i < 6 ? "vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n" : "");
        assert_int_equal(load_text(text, &err, &path), DM_ERR_PARSE);
        char *want = dm_xasprintf("%s%s", path, cases[i].msg);
        if (strncmp(dm_str_get(&err), want, strlen(want)) != 0)
            fail_msg("case %zu: got '%s', want '%s...'", i, dm_str_get(&err), want);
        assert_int_equal(technique_count(), n_tech);   /* nothing registered */
        assert_int_equal(axes_count(), n_axes);
        unlink(path);
        free(want);
        free(text);
        free(path);
        dm_str_free(&err);
    }
}

/* Values the shader would not receive as recorded, names that would be a
 * second column or a second uniform, #include, and header text that is not
 * UTF-8 are refused at the header's line (issue 43). */
static void test_bad_headers_types_and_names(void **state)
{
    (void)state;
    static const char *const entry = "vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n";
    static const struct { const char *text, *msg; } cases[] = {
        {"//@technique r1\n//@param bign int 0 4294967296 1\n",
         ":2: parameter 'bign': MAX 4294967296 does not fit the GLSL type int (an int is -2147483648..2147483647)"},
        {"//@technique r2\n//@param negn int -2147483649 0 0\n", ":2: parameter 'negn': MIN -2147483649 does not fit the GLSL type int"},
        {"//@technique r3\n//@param bigf float 0 1e300 1\n", ":2: parameter 'bigf': MAX 1e300 does not fit the GLSL type float"},
        {"//@technique r4\n//@param tinyf float 0 1 1e-40\n", ":2: parameter 'tinyf': DEFAULT 1e-40 does not fit the GLSL type float"},
        {"//@technique r5\n//@param key int 0 1 0\n",
         ":2: parameter 'key' would be a second 'key' column of results.csv; reserved names: key, scene, status, reason, label, pareto"},
        {"//@technique r6\n//@param label float 0 1 0\n", ":2: parameter 'label' would be a second 'label' column"},
        {"//@technique r7\n\n//@param shininess float 0 1 0.5\n",
         ":3: parameter 'shininess' would declare the uniform u_shininess, which dmbench's fragment stages already declare"},
        {"//@technique r8\n//@param tess_level_x int 1 4 2\n//@param camera_pos float 0 1 0\n//@base tess-level\n"
         "float user_tess_level(vec3 a, vec3 b) { return 1.0; }\n",
         ":3: parameter 'camera_pos' would declare the uniform u_camera_pos, which dmbench's tess-level stages"},
        {"//@technique r9\n#include \"lighting.glsl\"\n", ":2: #include is not supported in a user technique"},
        {"//@technique r10\n  #  include <x>\n", ":2: #include is not supported"},
        {"//@technique r11\n//@summary caf\xe9\n", ":2: byte 0xe9 at column 15 is not UTF-8"},
        {"//@technique r12\n//@summary \xed\xa0\x80\n", ":2: byte 0xed at column 12 is not UTF-8"},
    };
    size_t n_tech = technique_count(), n_axes = axes_count();
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dm_str err = {0};
        char *path = NULL, *text = dm_xasprintf("%s%s", cases[i].text, strstr(cases[i].text, "user_") ? "" : entry);
        assert_int_equal(load_text(text, &err, &path), DM_ERR_PARSE);
        char *want = dm_xasprintf("%s%s", path, cases[i].msg);
        if (strncmp(dm_str_get(&err), want, strlen(want)) != 0)
            fail_msg("case %zu: got '%s', want '%s...'", i, dm_str_get(&err), want);
        dm_str again = {0};   /* the check without a file says the same */
        assert_int_equal(user_technique_check_text(path, text, &again), DM_ERR_PARSE);
        assert_string_equal(dm_str_get(&again), dm_str_get(&err));
        assert_int_equal(technique_count(), n_tech);   /* nothing registered */
        assert_int_equal(axes_count(), n_axes);
        unlink(path);
        dm_str_free(&again);
        free(want);
        free(text);
        free(path);
        dm_str_free(&err);
    }
    /* at the limits of the types, and UTF-8 text, it loads */
    dm_str err = {0};
    char *path = NULL, *ok = dm_xasprintf("//@technique limits\n//@summary caf\xc3\xa9 \xf0\x9f\x98\x80\n"
                                          "//@param lim_i int -2147483648 2147483647 0\n"
                                          "//@param lim_f float -3.4e38 3.4e38 1.2e-38\n%s", entry);
    assert_int_equal(load_text(ok, &err, &path), 0);
    unlink(path);
    free(path);
    free(ok);
    dm_str_free(&err);
}

/* An #include inside a comment is prose: the file loads, and the composed
 * stage has the comment blanked, so the composer does not expand it. */
static void test_include_in_comment(void **state)
{
    (void)state;
    dm_str err = {0}, src = {0};
    char *path = NULL;
    const char *text = "//@technique incomment\n/* how it was:\n#include \"nowhere.glsl\"\n*/\n"
                       "vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n";
    assert_int_equal(load_text(text, &err, &path), 0);
    const technique_desc *t = technique_find("incomment");
    assert_int_equal(shaders_compose(t->fs, t->defines, &src, &err), 0);
    assert_null(strstr(dm_str_get(&src), "nowhere.glsl"));
    assert_non_null(strstr(dm_str_get(&src), "#line 100001\n                      \n"));   /* lines kept */
    /* the hash is still the file's, comments included */
    assert_true(t->source_hash == dm_fnv1a64(text, strlen(text), DM_FNV_SEED));
    /* user_technique_source_check: the same text passes, an edit is named */
    dm_str why = {0};
    assert_int_equal(user_technique_source_check(path, t->source_hash, &why), 0);
    assert_int_equal(dm_write_file(path, "edited\n", 7), 0);
    assert_int_equal(user_technique_source_check(path, t->source_hash, &why), DM_ERR_ARG);
    char *want = dm_xasprintf("%s: the user technique's file changed since the run started", path);
    assert_non_null(strstr(dm_str_get(&why), want));
    unlink(path);
    dm_str_free(&why);
    assert_int_equal(user_technique_source_check(path, t->source_hash, &why), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&why), "cannot be read since the run started"));
    free(want);
    free(path);
    dm_str_free(&why);
    dm_str_free(&src);
    dm_str_free(&err);
}

/* The viewer's reload: a changed body is taken, a changed parameter is not. */
static void test_reload(void **state)
{
    (void)state;
    static const char *const head = "//@technique reloaded\n//@param reload_k int 1 8 2\n";
    char *text = dm_xasprintf("%svec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n", head);
    dm_str err = {0}, msg = {0};
    char *path = NULL;
    assert_int_equal(load_text(text, &err, &path), 0);
    const technique_desc *t = technique_find("reloaded");
    uint64_t h0 = t->source_hash;
    assert_int_equal(user_technique_reload(&msg), 0);              /* nothing changed */
    char *edited = dm_xasprintf("%svec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.25); }\n", head);
    assert_int_equal(dm_write_file(path, edited, strlen(edited)), 0);
    assert_int_equal(user_technique_reload(&msg), 1);
    assert_string_equal(dm_str_get(&msg), "");
    assert_true(t->source_hash == dm_fnv1a64(edited, strlen(edited), DM_FNV_SEED) && t->source_hash != h0);
    assert_non_null(strstr(user_technique_shader_source(t->fs), "return vec3(uv, 0.25);"));
    const char *renamed = "//@technique reloaded\n//@param reload_j int 1 8 2\n"
                          "vec3 user_surface(vec2 uv, vec3 v) { return vec3(uv, 0.5); }\n";
    assert_int_equal(dm_write_file(path, renamed, strlen(renamed)), 0);
    assert_int_equal(user_technique_reload(&msg), 0);              /* refused, old source kept */
    char *want = dm_xasprintf("%s: its name, base, functions or parameters changed; restart to use them\n", path);
    assert_string_equal(dm_str_get(&msg), want);
    assert_non_null(strstr(user_technique_shader_source(t->fs), "return vec3(uv, 0.25);"));
    unlink(path);
    free(want);
    free(edited);
    free(text);
    free(path);
    dm_str_free(&msg);
    dm_str_free(&err);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_reload),
             cmocka_unit_test(test_load_example),
             cmocka_unit_test(test_map_log),
             cmocka_unit_test(test_bad_headers),
             cmocka_unit_test(test_bad_headers_types_and_names),
             cmocka_unit_test(test_include_in_comment))
