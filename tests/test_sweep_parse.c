/* Sweep-file parsing: defaults, scene mapping, and the corpus of malformed
 * files in tests/data/bad-sweeps (each declares the line and message it must
 * produce in its first line: "# expect: LINE: text"). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "sweep/sweep.h"

static const char *src_dir(void)
{
    const char *d = getenv("DMBENCH_SOURCE_DIR");
    return d ? d : ".";
}

static void test_defaults_and_scene(void **state)
{
    (void)state;
    const char *text =
        "name: s3\n"
        "resolution: [1280, 720]\n"
        "scene:\n"
        "  camera: { distance: 3.0, azimuth: 30, elevation: 20, fov: 45 }\n"
        "  lights: { model: blinn-phong, count: 2 }\n"
        "  material: { maps: bricks, height_scale: 0.06 }\n"
        "sweep:\n"
        "  mesh: [cube, plane]\n"
        "  technique: [normal]\n"
        "  resolution: [[640, 360], \"320x180\"]\n";
    sweep s;
    dm_str err = {0};
    assert_int_equal(sweep_parse(text, "t.yaml", &s, &err), 0);
    assert_string_equal(s.name, "s3");
    assert_string_equal(dm_kv_get(s.scene, s.n_scene, "resolution"), "1280x720");
    assert_string_equal(dm_kv_get(s.scene, s.n_scene, "light_count"), "2");
    assert_string_equal(dm_kv_get(s.scene, s.n_scene, "lighting"), "blinn-phong");
    assert_string_equal(dm_kv_get(s.scene, s.n_scene, "maps"), "bricks");
    assert_int_equal(s.n_axes, 3);
    assert_string_equal(s.axes[2].name, "resolution");
    assert_int_equal(s.axes[2].n_values, 2);
    assert_string_equal(s.axes[2].values[0], "640x360");
    assert_string_equal(s.axes[2].values[1], "320x180");
    assert_int_equal(s.axes[0].line, 8);
    /* measure defaults (docs/sweep-files.md) */
    assert_int_equal(s.measure.warmup_frames, 8);
    assert_int_equal(s.measure.frames_per_sample, 16);
    assert_int_equal(s.measure.samples_min, 5);
    assert_int_equal(s.measure.samples_max, 30);
    assert_true(s.measure.target_ci == 0.03);
    assert_int_equal(s.supersample, 4);
    assert_string_equal(s.pareto_metric, "ssim");
    assert_true(s.measure.n_counters > 0);
    sweep_free(&s);
    dm_str_free(&err);
}

static void test_quality_section(void **state)
{
    (void)state;
    const char *text =
        "name: q\n"
        "quality:\n"
        "  pareto_metric: depth-rmse\n"
        "  reference: { technique: same, supersample: 2 }\n"
        "sweep:\n"
        "  technique: [normal]\n";
    sweep s;
    dm_str err = {0};
    int rc = sweep_parse(text, "q.yaml", &s, &err);
    if (rc)
        fail_msg("%s", dm_str_get(&err));
    assert_string_equal(s.pareto_metric, "depth-rmse");
    assert_string_equal(s.ref_technique, "same");
    assert_int_equal(s.supersample, 2);
    sweep_free(&s);
    dm_str_free(&err);
}

/* quality.reference takes axis values besides technique and supersample
 * (canonical, in file order); the unknown and unreadable ones are in the
 * bad-sweeps corpus. */
static void test_reference_overrides(void **state)
{
    (void)state;
    const char *text =
        "name: q\n"
        "quality:\n"
        "  reference: { normal_format: rgba32f, technique: normal, height_scale: 0.12 }\n"
        "sweep:\n"
        "  technique: [normal]\n";
    sweep s;
    dm_str err = {0};
    int rc = sweep_parse(text, "q.yaml", &s, &err);
    if (rc)
        fail_msg("%s", dm_str_get(&err));
    assert_string_equal(s.ref_technique, "normal");
    assert_int_equal(s.n_ref_params, 2);
    assert_string_equal(s.ref_params[0].key, "normal_format");
    assert_string_equal(s.ref_params[0].value, "rgba32f");
    assert_string_equal(s.ref_params[1].key, "height_scale");
    assert_string_equal(s.ref_params[1].value, "0.12");
    assert_int_equal(s.supersample, 4);
    sweep_free(&s);
    dm_str_free(&err);
}

static void test_default_sweeps_parse(void **state)
{
    (void)state;
    for (int quick = 0; quick < 2; quick++) {
        sweep s;
        dm_str err = {0};
        int rc = sweep_parse(sweep_default_text(quick), "<default>", &s, &err);
        if (rc)
            fprintf(stderr, "%s\n", dm_str_get(&err));
        assert_int_equal(rc, 0);
        sweep_free(&s);
        dm_str_free(&err);
    }
}

static void test_missing_file(void **state)
{
    (void)state;
    sweep s;
    dm_str err = {0};
    assert_int_equal(sweep_load("/nonexistent/sweep.yaml", &s, &err), DM_ERR_IO);
    assert_non_null(strstr(dm_str_get(&err), "/nonexistent/sweep.yaml"));
    dm_str_free(&err);
}

/* Each file of the corpus must fail with its declared line and message. */
static void test_bad_corpus(void **state)
{
    (void)state;
    char *dir = NULL;
    asprintf(&dir, "%s/tests/data/bad-sweeps", src_dir());
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (!strstr(e->d_name, ".yaml"))
            continue;
        char *path = NULL;
        asprintf(&path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "r");
        char first[512] = "";
        assert_non_null(fgets(first, sizeof first, f));
        fclose(f);
        first[strcspn(first, "\n")] = '\0';
        int line = 0, off = 0;
        assert_int_equal(sscanf(first, "# expect: %d: %n", &line, &off), 1);
        const char *want = first + off;
        sweep s;
        dm_str err = {0};
        int rc = sweep_load(path, &s, &err);
        char prefix[600];
        snprintf(prefix, sizeof prefix, "%s:%d:", path, line);
        if (rc != DM_ERR_PARSE || strncmp(dm_str_get(&err), prefix, strlen(prefix)) != 0 ||
            !strstr(dm_str_get(&err), want))
            fail_msg("%s: rc %d, message '%s'; expected line %d and '%s'", e->d_name, rc,
                     dm_str_get(&err), line, want);
        dm_str_free(&err);
        free(path);
        n++;
    }
    closedir(d);
    free(dir);
    assert_true(n >= 20);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_scene),
        cmocka_unit_test(test_default_sweeps_parse),
        cmocka_unit_test(test_quality_section),
        cmocka_unit_test(test_reference_overrides),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_bad_corpus),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
