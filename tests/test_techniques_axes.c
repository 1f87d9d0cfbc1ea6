/* Unit tests of techniques/axes and the technique registry: catalog, value
 * checks, error messages, closest-match suggestions, canonical values. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "core/dm_results.h"
#include "techniques/axes.h"
#include "techniques/technique.h"

static void test_catalog(void **state)
{
    (void)state;
    static const char *const spec[] = {
        "technique", "mesh", "mesh_density", "resolution", "tess_level", "tess_spacing", "lod",
        "patch_cull", "crack_free", "tess_smooth", "height_scale", "offset_limit", "steps", "min_steps",
        "max_steps", "shadow", "lighting", "light_count", "roughness", "filter", "vertex_filter",
        "visibility_test", "height_format", "normal_format", "albedo_format", "texture_size",
        "virtual_texture", "vt_page_size", "vt_cache_pages", "toksvig", "camera.distance",
        "camera.azimuth", "camera.elevation", "camera.fov", "camera.target_x", "camera.target_y",
        "camera.target_z", "light.azimuth", "light.elevation", "light.distance",
        "camera.orbit_deg_per_frame", "light.orbit_deg_per_frame", "maps", "specular_map",
        "displaced_normals", "cull", "tess_inner", "tess_outer", "parallax_bias", "attenuation",
        "light_radius", "camera.path", "camera.path_frames", "camera.dolly_to",
        "camera.flyover_height", "camera.path_ref_every", NULL};
    for (size_t i = 0; spec[i]; i++)
        assert_non_null(axes_find(spec[i]));
    assert_int_equal(axes_count(), 56);
    static const char *const scene[] = {"mesh", "mesh_density", "resolution", "camera.distance",
        "camera.azimuth", "camera.elevation", "camera.fov", "maps", "texture_size", "filter",
        "albedo_format", "virtual_texture", "vt_page_size", "vt_cache_pages", "camera.target_x",
        "camera.target_y", "camera.target_z", "light.azimuth", "light.elevation",
        "light.distance", "camera.orbit_deg_per_frame", "light.orbit_deg_per_frame", "cull",
        "camera.path", "camera.path_frames", "camera.dolly_to", "camera.flyover_height",
        "camera.path_ref_every", NULL};
    size_t n_scene = 0;
    for (size_t i = 0; i < axes_count(); i++)
        n_scene += axes_at(i)->scene;
    for (size_t i = 0; scene[i]; i++)
        assert_int_equal(axes_find(scene[i])->scene, 1);
    assert_int_equal(n_scene, 29);   /* the 28 above + technique */
    assert_string_equal(axes_find("roughness")->def, "0.35");
    assert_int_equal(axes_find("roughness")->scene, 0);
    assert_string_equal(axes_find("light.distance")->def, "1.2");
    assert_string_equal(axes_find("resolution")->def, "640x360");
    assert_string_equal(axes_find("lighting")->def, "blinn-phong");
    assert_string_equal(axes_find("filter")->def, "trilinear");
    assert_null(axes_at(axes_count()));
    /* Every default passes its own check. */
    for (size_t i = 0; i < axes_count(); i++) {
        dm_str e = {0};
        assert_int_equal(axes_check(axes_at(i)->name, axes_at(i)->def, &e), 0);
        dm_str_free(&e);
    }
}

static void test_technique_choices(void **state)
{
    (void)state;
    const char *const *c = axes_find("technique")->choices;
    int has_normal = 0;
    for (size_t i = 0; c[i]; i++) {
        assert_string_not_equal(c[i], "debug-broken-shader");
        has_normal |= strcmp(c[i], "normal") == 0;
    }
    assert_true(has_normal);
    assert_non_null(technique_find("debug-broken-shader"));
    assert_int_equal(technique_find("debug-broken-shader")->test_only, 1);
    const technique_desc *n = technique_find("normal");
    assert_true(technique_reads_axis(n, "lighting"));
    assert_true(technique_reads_axis(n, "mesh"));
    assert_false(technique_reads_axis(n, "tess_level"));
    assert_false(technique_reads_axis(n, "no_such_axis"));
    /* Every declared axis exists in the catalog. */
    for (size_t i = 0; i < technique_count(); i++)
        for (size_t k = 0; technique_at(i)->axes && technique_at(i)->axes[k]; k++)
            assert_non_null(axes_find(technique_at(i)->axes[k]));
}

static void expect(const char *axis, const char *value, int code, const char *text)
{
    dm_str e = {0};
    assert_int_equal(axes_check(axis, value, &e), code);
    if (text)
        assert_non_null(strstr(dm_str_get(&e), text));
    else
        assert_int_equal(e.len, 0);
    dm_str_free(&e);
}

static void test_messages(void **state)
{
    (void)state;
    expect("tess_levle", "4", DM_ERR_UNKNOWN,
           "unknown axis 'tess_levle'; did you mean 'tess_level'? valid axes: technique, mesh, ");
    expect("zzzzzzzzzzzz", "4", DM_ERR_UNKNOWN, "unknown axis 'zzzzzzzzzzzz'; valid axes: technique");
    /* the mesh list grows with the mesh registry: its start and the suggestion */
    expect("mesh", "cubee", DM_ERR_ARG,
           "invalid value 'cubee' for mesh; expected one of: plane, cube, triangle, fullscreen, "
           "cylinder, sphere, terrain, asteroid, seam, halfflat");
    expect("mesh", "cubee", DM_ERR_ARG, " (did you mean 'cube'?)");
    expect("tess_level", "65", DM_ERR_ARG, "invalid value '65' for tess_level; expected an integer in [1, 64]");
    expect("tess_level", "3.5", DM_ERR_ARG, "expected an integer in [1, 64]");
    expect("tess_level", "64", 0, NULL);
    expect("tess_level", "1", 0, NULL);
    expect("tess_level", "0", DM_ERR_ARG, "[1, 64]");
    expect("height_scale", "-1", 0, NULL);
    expect("height_scale", "1.5", DM_ERR_ARG, "expected a number in [-1, 1]");
    expect("height_scale", "nan", DM_ERR_ARG, "expected a number");
    expect("steps", "auto", 0, NULL);
    expect("steps", "autox", DM_ERR_ARG, "expected an integer in [1, 512] or 'auto'");
    expect("resolution", "8192x1", 0, NULL);
    expect("resolution", "[1280, 720]", 0, NULL);
    expect("resolution", "8193x2", DM_ERR_ARG, "expected WxH with each side in [1, 8192]");
    expect("resolution", "0x10", DM_ERR_ARG, "WxH");
    expect("lighting", "cook-torrance", 0, NULL);
    expect("technique", "normall", DM_ERR_ARG, "(did you mean 'normal'?)");
    expect("technique", "debug-broken-shader", DM_ERR_ARG, "expected one of");
}

/* The axes of the studies' missing experiments (issue 19): defaults that
 * keep today's renders, who reads them, their conditions and messages. */
static const char *exp_value(const char *axis, void *ctx)
{
    const char *const *kv = ctx;
    for (size_t i = 0; kv && kv[i]; i += 2)
        if (strcmp(kv[i], axis) == 0)
            return kv[i + 1];
    return NULL;
}

static void test_experiment_axes(void **state)
{
    (void)state;
    assert_string_equal(axes_find("cull")->def, "back");
    assert_string_equal(axes_find("tess_inner")->def, "auto");
    assert_string_equal(axes_find("tess_outer")->def, "auto");
    assert_string_equal(axes_find("attenuation")->def, "inverse-quadratic");
    assert_string_equal(axes_find("parallax_bias")->def, "0.5");
    assert_string_equal(axes_find("lod")->def, "uniform");
    for (size_t i = 0; i < technique_count(); i++) {
        const technique_desc *t = technique_at(i);
        assert_int_equal(technique_reads_axis(t, "attenuation"), technique_reads_axis(t, "lighting"));
        assert_int_equal(technique_reads_axis(t, "light_radius"), technique_reads_axis(t, "lighting"));
        assert_int_equal(technique_reads_axis(t, "tess_inner"), t->tcs != NULL);
        assert_int_equal(technique_reads_axis(t, "tess_outer"), t->tcs != NULL);
        assert_int_equal(technique_reads_axis(t, "parallax_bias"), strcmp(t->name, "parallax") == 0);
        assert_true(technique_reads_axis(t, "cull"));
    }
    assert_true(technique_reads_axis(technique_find("vertex-displacement"), "height_format"));
    const char *s1[] = {"attenuation", "s1", NULL}, *cpu[] = {"lod", "cpu-per-patch", NULL};
    const char *in4[] = {"tess_inner", "4", "tess_outer", "2", NULL};
    const char *in4cpu[] = {"tess_inner", "4", "tess_outer", "2", "lod", "cpu-per-patch", NULL};
    const char *moved[] = {"cull", "off", "attenuation", "none", "parallax_bias", "0.25", NULL};
    const char *spelled[] = {"cull", "back", "parallax_bias", "0.50", NULL};
    assert_true(axes_condition_holds("light_radius", exp_value, (void *)s1));
    assert_false(axes_condition_holds("light_radius", exp_value, NULL));
    assert_true(axes_condition_holds("tess_inner", exp_value, (void *)in4));   /* lod uniform */
    assert_true(axes_condition_holds("tess_outer", exp_value, (void *)in4));
    assert_false(axes_condition_holds("tess_inner", exp_value, (void *)in4cpu));
    assert_false(axes_condition_holds("tess_outer", exp_value, (void *)cpu));
    /* at their defaults (spelled either way) the new axes stay out of keys */
    static const char *const keyless[] = {"tess_inner", "tess_outer", "cull", "attenuation",
                                          "parallax_bias", NULL};
    for (size_t i = 0; keyless[i]; i++) {
        assert_false(axes_condition_holds(keyless[i], exp_value, NULL));
        assert_false(axes_condition_holds(keyless[i], exp_value, (void *)spelled));
    }
    for (size_t i = 2; keyless[i]; i++)
        assert_true(axes_condition_holds(keyless[i], exp_value, (void *)moved));
    /* core's list of axes left out at their default (dm_param_value reads a
     * missing one as it) names each axis's own default, and the planner's
     * condition drops exactly that value */
    static const char *const left_out[] = {"camera.orbit_deg_per_frame", "light.orbit_deg_per_frame",
        "camera.path", "camera.path_ref_every", "specular_map", "displaced_normals", "tess_inner",
        "tess_outer", "cull", "attenuation", "parallax_bias", NULL};
    for (size_t i = 0; left_out[i]; i++) {
        const char *def = dm_param_left_out_default(left_out[i]);
        assert_non_null(def);
        assert_string_equal(def, axes_find(left_out[i])->def);
        assert_false(axes_condition_holds(left_out[i], exp_value, NULL));
        const char *at_def[] = {left_out[i], def, NULL};
        assert_false(axes_condition_holds(left_out[i], exp_value, (void *)at_def));
    }
    size_t n_axes = 0;
    const axis_info *rows = axes_builtin(&n_axes);
    size_t listed = 0;
    for (size_t i = 0; i < n_axes; i++)
        listed += dm_param_left_out_default(rows[i].name) != NULL;
    assert_int_equal(listed, 11);   /* no other axis is left out at its default */
    const char *cam_moved[] = {"camera.path", "dolly", "specular_map", "on", NULL};
    assert_true(axes_condition_holds("camera.path", exp_value, (void *)cam_moved));
    assert_true(axes_condition_holds("specular_map", exp_value, (void *)cam_moved));
    dm_kv kv[] = {{(char *)"cull", (char *)"off"}};
    assert_string_equal(dm_param_value(kv, 1, "cull"), "off");
    assert_string_equal(dm_param_value(kv, 1, "camera.path"), "still");
    assert_null(dm_param_value(kv, 1, "roughness"));
    /* axis, value, then the message (NULL: the value is valid) */
    static const char *const check[][3] = {
        {"cull", "front", "invalid value 'front' for cull; expected one of: back, off"},
        {"lod", "cpu-per-patch", NULL},
        {"lod", "cpu", "uniform, distance, cpu-per-patch, object-points, object-cpu, screen-edge, flatness, constant"},
        {"tess_inner", "auto", NULL},
        {"tess_outer", "64", NULL},
        {"tess_outer", "0", "expected an integer in [1, 64] or 'auto'"},
        {"attenuation", "linear", "expected one of: inverse-quadratic, s1, none"},
        {"light_radius", "0", "expected a number in [0.01, 1000]"},
        {"parallax_bias", "2.5", "expected a number in [-1, 2]"},
    };
    for (size_t i = 0; i < sizeof check / sizeof check[0]; i++)
        expect(check[i][0], check[i][1], check[i][2] ? DM_ERR_ARG : 0, check[i][2]);
    char *c = axes_canonical("tess_inner", "auto");
    assert_string_equal(c, "auto");
    free(c);
}

static const char *cond_value(const char *axis, void *ctx)
{
    return strcmp(axis, "lighting") == 0 ? (const char *)ctx : NULL;
}

static const char *orbit_value(const char *axis, void *ctx)
{
    return strstr(axis, "orbit_deg_per_frame") ? (const char *)ctx : NULL;
}

/* roughness matters only with lighting=cook-torrance (its only_if); axes
 * without a condition always hold; unknown axes never do. */
static void test_conditions(void **state)
{
    (void)state;
    assert_true(axes_condition_holds("roughness", cond_value, "cook-torrance"));
    assert_false(axes_condition_holds("roughness", cond_value, "blinn-phong"));
    assert_false(axes_condition_holds("roughness", NULL, NULL));   /* default blinn-phong */
    assert_false(axes_condition_holds("roughness", cond_value, NULL));
    assert_true(axes_condition_holds("light.azimuth", cond_value, "lambert"));
    assert_false(axes_condition_holds("no_such_axis", NULL, NULL));
    /* the orbits count only when moving, so still scenes keep their keys */
    assert_false(axes_condition_holds("camera.orbit_deg_per_frame", NULL, NULL));
    assert_false(axes_condition_holds("light.orbit_deg_per_frame", orbit_value, "0"));
    assert_true(axes_condition_holds("light.orbit_deg_per_frame", orbit_value, "1.5"));
    assert_true(axes_condition_holds("camera.orbit_deg_per_frame", orbit_value, "-2"));
    assert_false(axes_condition_holds("specular_map", NULL, NULL));
    assert_false(axes_condition_holds("displaced_normals", NULL, NULL));
    for (size_t i = 0; i < technique_count(); i++) {
        const technique_desc *t = technique_at(i);
        assert_int_equal(technique_reads_axis(t, "roughness"), technique_reads_axis(t, "lighting"));
    }
    expect("roughness", "0.005", DM_ERR_ARG, "expected a number in [0.01, 1]");
    expect("light.distance", "0", 0, NULL);
    expect("light.distance", "-1", DM_ERR_ARG, "expected a number in [0, 100]");
}

static void test_closest(void **state)
{
    (void)state;
    static const char *const names[] = {"plane", "cube", "sphere", NULL};
    assert_string_equal(dm_closest("cubee", names, 3), "cube");
    assert_string_equal(dm_closest("SPHERE", names, 3), "sphere");
    assert_string_equal(dm_closest("plan", names, 3), "plane");
    assert_null(dm_closest("torus-knot", names, 3));
}

static void test_canonical(void **state)
{
    (void)state;
    static const char *const cases[][3] = {
        {"resolution", "[1280, 720]", "1280x720"}, {"resolution", "1280 x 720", "1280x720"},
        {"tess_level", "064", "64"},               {"camera.distance", "3.0", "3"},
        {"height_scale", "0.060", "0.06"},          {"steps", "auto", "auto"},
        {"mesh", "cube", "cube"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *c = axes_canonical(cases[i][0], cases[i][1]);
        assert_non_null(c);
        assert_string_equal(c, cases[i][2]);
        free(c);
    }
    assert_null(axes_canonical("mesh", "cubee"));
    assert_null(axes_canonical("nope", "1"));
    int w = 0, h = 0;
    assert_int_equal(axes_parse_size2("[640, 360]", &w, &h), 0);
    assert_int_equal(w * 10000 + h, 6400360);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_catalog),
             cmocka_unit_test(test_technique_choices),
             cmocka_unit_test(test_messages),
             cmocka_unit_test(test_closest),
             cmocka_unit_test(test_canonical),
             cmocka_unit_test(test_conditions),
             cmocka_unit_test(test_experiment_axes))
