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
#include "sweep/sweep_paths.h"
#include "test_util.h"

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

/* Parses text into s, failing the test with the parser's message. */
static void parse_ok(const char *text, sweep *s)
{
    dm_str err = {0};
    if (sweep_parse(text, "q.yaml", s, &err) != 0)
        fail_msg("%s", dm_str_get(&err));
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
    parse_ok(text, &s);
    assert_string_equal(s.pareto_metric, "depth-rmse");
    assert_string_equal(s.ref_technique, "same");
    assert_int_equal(s.supersample, 2);
    sweep_free(&s);
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
    parse_ok(text, &s);
    assert_string_equal(s.ref_technique, "normal");
    assert_int_equal(s.n_ref_params, 2);
    assert_string_equal(s.ref_params[0].key, "normal_format");
    assert_string_equal(s.ref_params[0].value, "rgba32f");
    assert_string_equal(s.ref_params[1].key, "height_scale");
    assert_string_equal(s.ref_params[1].value, "0.12");
    assert_int_equal(s.supersample, 4);
    sweep_free(&s);
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

/* A sweep text holding `line` (a "key: value" line, or an axis line for a
 * "*" row) at the place of `section`: nested mappings for "a.b", an entry
 * of the list for "models[]" and "exclude[]". */
static void key_text(const char *section, const char *line, dm_str *t)
{
    if (strcmp(section, "models[]") == 0) {
        dm_str_printf(t, "models:\n  - %s%s\n", strncmp(line, "name:", 5) ? "name: m\n    " : "", line);
        return;
    }
    if (strcmp(section, "exclude[]") == 0) {
        dm_str_printf(t, "sweep:\n  technique: [phong, normal]\nexclude:\n  - { %s }\n", line);
        return;
    }
    int depth = 0;
    for (const char *p = section; *p; depth++) {
        const char *dot = strchr(p, '.');
        size_t n = dot ? (size_t)(dot - p) : strlen(p);
        dm_str_printf(t, "%*s%.*s:\n", 2 * depth, "", (int)n, p);
        p += n + (dot != NULL);
    }
    dm_str_printf(t, "%*s%s\n", 2 * depth, "", line);
}

/* Every row of the key table is a key the parser takes: its example, put in
 * its section, parses (a map file row is accepted as a key and the file is
 * then looked for); an unknown key in a section without axes is refused
 * with every key of that section listed. */
static void test_key_table(void **state)
{
    (void)state;
    size_t n = sweep_keys_count(), examples = 0;
    assert_true(n >= 30);
    for (size_t i = 0; i < n; i++) {
        const sweep_key *k = sweep_keys_at(i);
        if (!k->example)
            continue;
        dm_str line = {0}, text = {0}, err = {0};
        if (strcmp(k->name, "*") == 0)
            dm_str_cat(&line, k->example);
        else
            dm_str_printf(&line, "%s: %s", k->name, k->example);
        key_text(k->section, dm_str_get(&line), &text);
        sweep s;
        int rc = sweep_parse(dm_str_get(&text), "keys.yaml", &s, &err);
        if (strcmp(k->type, "file path") == 0) {
            assert_int_equal(rc, DM_ERR_PARSE);
            assert_non_null(strstr(dm_str_get(&err), k->example));
        } else {
            if (rc)
                fail_msg("%s.%s: %s\n%s", k->section, k->name, dm_str_get(&err), dm_str_get(&text));
            sweep_free(&s);
        }
        examples++;
        dm_str_free(&line), dm_str_free(&text), dm_str_free(&err);
    }
    assert_true(examples >= 25);
    for (size_t i = 0; i < n; i++) {
        const sweep_key *k = sweep_keys_at(i);
        if (i && strcmp(k->section, sweep_keys_at(i - 1)->section) == 0)
            continue;
        if (strcmp(k->section, "scene") == 0 || strcmp(k->section, "sweep") == 0 ||
            strcmp(k->section, "exclude[]") == 0)
            continue;                  /* keys there are axes: "unknown axis", tested by the corpus */
        dm_str text = {0}, err = {0};
        key_text(k->section, "zzz_unknown: 1", &text);
        sweep s;
        assert_int_equal(sweep_parse(dm_str_get(&text), "keys.yaml", &s, &err), DM_ERR_PARSE);
        const char *msg = dm_str_get(&err), *valid = strstr(msg, "valid keys: ");
        assert_non_null(strstr(msg, "unknown key 'zzz_unknown'"));
        assert_non_null(valid);
        for (size_t j = i; j < n && strcmp(sweep_keys_at(j)->section, k->section) == 0; j++)
            if (strcmp(sweep_keys_at(j)->name, "*") != 0 && !strstr(valid, sweep_keys_at(j)->name))
                fail_msg("%s: '%s' missing from: %s", k->section, sweep_keys_at(j)->name, msg);
        dm_str_free(&text), dm_str_free(&err);
    }
}

/* Numeric defaults come from the key table only when a key is absent: an
 * explicit 0 stays 0, and samples.max follows a larger samples.min. */
static void test_numeric_defaults(void **state)
{
    (void)state;
    sweep s;
    dm_str err = {0};
    assert_int_equal(sweep_parse("measure:\n  warmup_frames: 0\n  min_sample_ms: 0\n"
                                 "  samples: { min: 40 }\n", "d.yaml", &s, &err), 0);
    assert_int_equal(s.measure.warmup_frames, 0);
    assert_true(s.measure.min_sample_ms == 0);
    assert_int_equal(s.measure.samples_min, 40);
    assert_int_equal(s.measure.samples_max, 40);
    assert_int_equal(s.measure.frames_per_sample, 16);
    assert_true(s.measure.max_seconds == 10 && s.measure.timeout_s == 120);
    sweep_free(&s);
    assert_int_equal(sweep_parse("measure:\n  samples: { min: 9, max: 6 }\n", "d.yaml", &s, &err),
                     DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&err), "max (6) is less than min (9)"));
    dm_str_free(&err);
}

/* samples.target_ci takes the fraction grammar of every flag: 3% and 0.03
 * are one double; a bare 3 is refused (tests/data/bad-sweeps/43-*). */
static void test_target_ci_percent(void **state)
{
    (void)state;
    const char *texts[] = { "measure:\n  samples: { target_ci: 3% }\n",
                            "measure:\n  samples: { target_ci: 0.03 }\n",
                            "measure:\n  samples:\n    target_ci: \"3%\"\n" };
    for (size_t i = 0; i < 3; i++) {
        sweep s;
        parse_ok(texts[i], &s);
        assert_true(s.measure.target_ci == 0.03);
        sweep_free(&s);
    }
    sweep s;
    dm_str err = {0};
    assert_int_equal(sweep_parse("measure:\n  samples: { target_ci: 3 }\n", "t.yaml", &s, &err),
                     DM_ERR_PARSE);
    assert_non_null(strstr(dm_str_get(&err), "t.yaml:2:"));
    assert_non_null(strstr(dm_str_get(&err), "write 3% or 0.03"));
    dm_str_free(&err);
}

/* scene.material's files as one maps value: relative paths follow the sweep
 * file, absolute ones stay, a ';' is doubled, kinds in height/normal/albedo
 * order whatever is given. */
static void test_user_maps_value(void **state)
{
    (void)state;
    const char *some[SWEEP_PATHS_MAPS] = { "h.png", NULL, "/abs/a;b.png" };
    char *v = sweep_paths_maps("studies/s.yaml", some);
    assert_string_equal(v, "height=studies/h.png;albedo=/abs/a;;b.png");
    free(v);
    const char *normal_only[SWEEP_PATHS_MAPS] = { NULL, "n.png", NULL };
    v = sweep_paths_maps("s.yaml", normal_only);   /* no directory: the path as given */
    assert_string_equal(v, "normal=n.png");
    free(v);
    const char *none[SWEEP_PATHS_MAPS] = { NULL, NULL, NULL };
    assert_null(sweep_paths_maps("studies/s.yaml", none));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_defaults_and_scene),
             cmocka_unit_test(test_default_sweeps_parse),
             cmocka_unit_test(test_quality_section),
             cmocka_unit_test(test_reference_overrides),
             cmocka_unit_test(test_missing_file),
             cmocka_unit_test(test_bad_corpus),
             cmocka_unit_test(test_key_table),
             cmocka_unit_test(test_numeric_defaults),
             cmocka_unit_test(test_target_ci_percent),
             cmocka_unit_test(test_user_maps_value))
