/* Planner: projection onto the axes a technique reads, dedupe counts,
 * stable keys, shards that are disjoint and cover everything. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "sweep/plan.h"
#include "sweep/sweep.h"

static void plan_text(const char *text, sweep *s, plan *p)
{
    dm_str err = {0};
    int rc = sweep_parse(text, "t.yaml", s, &err);
    if (rc)
        fail_msg("%s", dm_str_get(&err));
    assert_int_equal(plan_build(s, NULL, p, &err), 0);
    dm_str_free(&err);
}

/* normal does not read tess_level: 3 combinations fold into 1. */
static void test_fold_irrelevant_axis(void **state)
{
    (void)state;
    sweep s;
    plan p;
    plan_text("name: t\nsweep:\n  technique: [normal]\n  tess_level: [1, 32, 64]\n", &s, &p);
    assert_int_equal(p.n_combinations, 3);
    assert_int_equal(p.n_configs, 1);
    assert_int_equal(p.configs[0].folded, 3);
    assert_null(dm_kv_get(p.configs[0].params, p.configs[0].n_params, "tess_level"));
    assert_string_equal(dm_kv_get(p.configs[0].params, p.configs[0].n_params, "technique"), "normal");
    plan_free(&p);
    sweep_free(&s);
}

/* Scene axes are read by every technique: 2 meshes x 2 resolutions = 4. */
static void test_scene_axes_kept(void **state)
{
    (void)state;
    sweep s;
    plan p;
    plan_text("name: t\nsweep:\n  mesh: [plane, cube]\n  technique: [normal]\n"
              "  resolution: [[64, 32], [128, 64]]\n", &s, &p);
    assert_int_equal(p.n_combinations, 4);
    assert_int_equal(p.n_configs, 4);
    int found = 0;
    for (size_t i = 0; i < p.n_configs; i++) {
        if (strcmp(p.configs[i].scene, "cube@128x64") == 0) {
            found = 1;
            assert_int_equal(p.configs[i].width, 128);
            assert_int_equal(p.configs[i].height, 64);
        }
    }
    assert_true(found);
    plan_free(&p);
    sweep_free(&s);
}

/* Keys depend only on the projected parameters: the same configuration
 * planned from two different sweeps has the same key. */
static void test_keys_stable(void **state)
{
    (void)state;
    sweep a, b;
    plan pa, pb;
    plan_text("name: a\nsweep:\n  technique: [normal]\n  mesh: [cube]\n", &a, &pa);
    plan_text("name: b\nscene: { mesh: cube, camera: { distance: 3.000 } }\nsweep:\n"
              "  tess_level: [4, 8]\n  technique: [normal]\n", &b, &pb);
    assert_int_equal(pa.n_configs, 1);
    assert_int_equal(pb.n_configs, 1);
    assert_string_equal(pa.configs[0].key, pb.configs[0].key);
    assert_int_equal(strlen(pa.configs[0].key), 16);
    plan_free(&pa);
    plan_free(&pb);
    sweep_free(&a);
    sweep_free(&b);
}

static void test_shards_partition(void **state)
{
    (void)state;
    const char *text = "name: t\nsweep:\n  mesh: [plane, cube, triangle, fullscreen]\n"
                       "  technique: [normal]\n"
                       "  resolution: [[64, 32], [128, 64], [32, 32], [16, 16], [8, 8]]\n"
                       "  camera.elevation: [10, 20, 30]\n";
    sweep s;
    plan whole;
    plan_text(text, &s, &whole);
    assert_int_equal(whole.n_configs, 60);
    size_t total = 0;
    int *seen = calloc(whole.n_configs, sizeof *seen);
    for (int k = 1; k <= 3; k++) {
        plan part;
        dm_str err = {0};
        assert_int_equal(plan_build(&s, NULL, &part, &err), 0);
        assert_int_equal(plan_shard(&part, k, 3), 0);
        total += part.n_configs;
        for (size_t i = 0; i < part.n_configs; i++)
            for (size_t j = 0; j < whole.n_configs; j++)
                if (strcmp(part.configs[i].key, whole.configs[j].key) == 0)
                    seen[j]++;
        plan_free(&part);
    }
    assert_int_equal(total, whole.n_configs);
    for (size_t j = 0; j < whole.n_configs; j++)
        assert_int_equal(seen[j], 1);
    plan part;
    dm_str err = {0};
    assert_int_equal(plan_build(&s, NULL, &part, &err), 0);
    assert_int_equal(plan_shard(&part, 4, 3), DM_ERR_ARG);
    plan_free(&part);
    free(seen);
    plan_free(&whole);
    sweep_free(&s);
}

static void test_shuffle_is_seeded_permutation(void **state)
{
    (void)state;
    size_t a[50], b[50], c[50];
    plan_shuffle(a, 50, 7);
    plan_shuffle(b, 50, 7);
    plan_shuffle(c, 50, 8);
    assert_memory_equal(a, b, sizeof a);
    assert_true(memcmp(a, c, sizeof a) != 0);
    int hit[50] = {0};
    for (int i = 0; i < 50; i++)
        hit[a[i]]++;
    for (int i = 0; i < 50; i++)
        assert_int_equal(hit[i], 1);
}

/* roughness is read only under cook-torrance: 2 lighting models × 2
 * roughness values plan 1 + 2 configurations. */
static void test_conditional_axis_folds(void **state)
{
    (void)state;
    sweep s;
    plan p;
    plan_text("name: t\nsweep:\n  technique: [phong]\n  lighting: [blinn-phong, cook-torrance]\n"
              "  roughness: [0.1, 0.5]\n", &s, &p);
    assert_int_equal(p.n_combinations, 4);
    assert_int_equal(p.n_configs, 3);
    for (size_t i = 0; i < p.n_configs; i++) {
        const char *l = dm_kv_get(p.configs[i].params, p.configs[i].n_params, "lighting");
        const char *r = dm_kv_get(p.configs[i].params, p.configs[i].n_params, "roughness");
        assert_true((strcmp(l, "cook-torrance") == 0) == (r != NULL));
    }
    plan_free(&p);
    sweep_free(&s);
}

/* exclude: technique × mesh = 4 combinations, two entries drop 2 of them
 * (one by a list of values); the rest is planned as usual. */
static void test_exclude(void **state)
{
    (void)state;
    sweep s;
    plan p;
    plan_text("name: t\nsweep:\n  technique: [phong, tess-displacement]\n  mesh: [asteroid, asteroid-reduced]\n"
              "  tess_level: [1, 4]\n"
              "exclude:\n  - { technique: tess-displacement, mesh: asteroid }\n"
              "  - { technique: [phong], mesh: [asteroid-reduced] }\n", &s, &p);
    assert_int_equal(p.n_combinations, 8);
    assert_int_equal(p.n_excluded, 4);
    assert_int_equal(p.n_configs, 3);   /* phong@asteroid (tess_level folded), tess@reduced × 2 */
    for (size_t i = 0; i < p.n_configs; i++) {
        const char *t = dm_kv_get(p.configs[i].params, p.configs[i].n_params, "technique");
        const char *m = dm_kv_get(p.configs[i].params, p.configs[i].n_params, "mesh");
        assert_true((strcmp(t, "phong") == 0) == (strcmp(m, "asteroid") == 0));
    }
    plan_free(&p);
    sweep_free(&s);
}

/* Bad exclude entries name the file and line and the valid choices. */
static void test_exclude_errors(void **state)
{
    (void)state;
    static const struct { const char *text, *msg; } bad[] = {
        {"name: t\nsweep:\n  technique: [phong, pom]\nexclude:\n  - { mesh: cube }\n",
         "t.yaml:5: exclude names axis 'mesh', which the sweep block does not vary"},
        {"name: t\nsweep:\n  technique: [phong, pom]\nexclude:\n  - { technique: normal }\n",
         "t.yaml:5: exclude value 'normal' of technique is not one of the sweep's values (phong, pom)"},
        {"name: t\nsweep:\n  technique: [phong]\nexclude: { technique: phong }\n",
         "t.yaml:4:10: exclude: expected a list"},
        {"name: t\nsweep:\n  technique: [phong]\nexclude:\n  - { tecnique: phong }\n",
         "did you mean 'technique'?"},
        {"name: t\nsweep:\n  technique: [phong]\nexclude:\n  - {}\n", "an empty entry would exclude everything"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sweep s;
        dm_str err = {0};
        assert_int_equal(sweep_parse(bad[i].text, "t.yaml", &s, &err), DM_ERR_PARSE);
        if (!strstr(dm_str_get(&err), bad[i].msg))
            fail_msg("case %zu: '%s' lacks '%s'", i, dm_str_get(&err), bad[i].msg);
        dm_str_free(&err);
    }
}

/* A mesh_density beyond what the combination's mesh accepts is refused at
 * planning with the file, the axis' line and the mesh's valid densities;
 * the same density is fine for a mesh that takes it, 0 always is, and an
 * `exclude` of the pair plans the rest. */
/* Camera paths that cannot be drawn or compared are refused at the key's
 * line (scene: or sweep block), naming what is accepted: reference frames
 * past the path, a dolly that does not move, a flyover over a mesh that is
 * not a ground; the accepted neighbours plan. */
static void test_path_refusals(void **state)
{
    (void)state;
    static const struct { const char *text, *msg; } bad[] = {
        {"name: t\nscene:\n  camera.path: dolly\n  camera.path_frames: 12\n  camera.path_ref_every: 12\n"
         "sweep:\n  technique: [normal]\n",
         "t.yaml:5: camera.path_ref_every 12 is past the path's last frame (camera.path_frames 12: frames "
         "0..11); valid are 0 (the first and last frames) and 1..11"},
        {"name: t\nscene:\n  camera.path: dolly\n  camera.distance: 2\nsweep:\n  technique: [normal]\n"
         "  camera.dolly_to: [1, 2]\n",
         "t.yaml:7: camera.dolly_to 2 equals camera.distance 2: the dolly would not move; give another end "
         "distance (0.1..100), or camera.path still"},
        {"name: t\nscene:\n  mesh: cube\nsweep:\n  technique: [normal]\n  camera.path: [orbit, flyover]\n",
         "t.yaml:6: camera.path flyover flies at a height over a ground, and mesh 'cube' is not one; a "
         "flyover takes plane, terrain, terrain-tiles, halfflat, s2-scene1 or a file: mesh"},
        {"name: t\nscene:\n  camera.orbit_deg_per_frame: 2\n  camera.path_ref_every: 60\nsweep:\n"
         "  technique: [normal]\n",
         "t.yaml:4: camera.path_ref_every 60 is past the path's last frame (camera.path_frames 60: frames 0..59)"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sweep s;
        plan p;
        dm_str err = {0};
        assert_int_equal(sweep_parse(bad[i].text, "t.yaml", &s, &err), 0);
        assert_int_equal(plan_build(&s, NULL, &p, &err), DM_ERR_RANGE);
        if (!strstr(dm_str_get(&err), bad[i].msg))
            fail_msg("case %zu: '%s' lacks '%s'", i, dm_str_get(&err), bad[i].msg);
        dm_str_free(&err);
        sweep_free(&s);
    }
    static const char *const good[] = {   /* the last frame, a moving dolly, a flyover over the terrain, a still path's last frame */
        "name: t\nscene:\n  camera.path: dolly\n  camera.path_frames: 12\n  camera.path_ref_every: 11\n"
        "sweep:\n  technique: [normal]\n",
        "name: t\nscene:\n  camera.path: dolly\n  camera.distance: 2\n  camera.dolly_to: 1.9\n"
        "sweep:\n  technique: [normal]\n",
        "name: t\nscene:\n  mesh: terrain\n  camera.path: flyover\nsweep:\n  technique: [normal]\n",
        "name: t\nscene:\n  mesh: cube\n  camera.path_ref_every: 59\nsweep:\n  technique: [normal]\n",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        sweep s;
        plan p;
        dm_str err = {0};
        assert_int_equal(sweep_parse(good[i], "t.yaml", &s, &err), 0);
        if (plan_build(&s, NULL, &p, &err) != 0)
            fail_msg("good case %zu refused: %s", i, dm_str_get(&err));
        assert_int_equal(p.n_configs, 1);
        plan_free(&p);
        dm_str_free(&err);
        sweep_free(&s);
    }
}

static void test_density_out_of_mesh_range(void **state)
{
    (void)state;
    static const struct { const char *mesh, *dens, *msg; } bad[] = {
        {"[plane, sphere]", "[0, 9]",
         "t.yaml:5: mesh_density 9 is out of range for mesh 'sphere': valid are 1..7, and 0 for its default (4)"},
        {"[plane]", "[1]", "t.yaml:5: mesh_density 1 is out of range for mesh 'plane': valid are 2..1024, and 0 for its default (2)"},
        {"[s2-scene1]", "[2]", "mesh_density 2 is out of range for mesh 's2-scene1': it takes only 0"},
        {"[s4-asteroids]", "[8]", "valid are 1..7, and 0 for its default (3)"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, "name: t\nsweep:\n  technique: [phong]\n  mesh: %s\n  mesh_density: %s\n",
                 bad[i].mesh, bad[i].dens);
        sweep s;
        plan p;
        dm_str err = {0};
        assert_int_equal(sweep_parse(text, "t.yaml", &s, &err), 0);
        assert_int_equal(plan_build(&s, NULL, &p, &err), DM_ERR_RANGE);
        if (!strstr(dm_str_get(&err), bad[i].msg))
            fail_msg("case %zu: '%s' lacks '%s'", i, dm_str_get(&err), bad[i].msg);
        assert_int_equal(p.n_configs, 0);
        dm_str_free(&err);
        sweep_free(&s);
    }
    sweep sc;   /* under scene: its line there; the pair cannot be excluded */
    plan pc;
    dm_str err = {0};
    assert_int_equal(sweep_parse("name: t\nscene:\n  mesh: sphere\n  mesh_density: 8\nsweep:\n  technique: [phong]\n",
                                 "t.yaml", &sc, &err), 0);
    assert_int_equal(plan_build(&sc, NULL, &pc, &err), DM_ERR_RANGE);
    assert_string_equal(dm_str_get(&err), "t.yaml:4: mesh_density 8 is out of range for mesh 'sphere': "
                                          "valid are 1..7, and 0 for its default (4)");
    dm_str_free(&err);
    sweep_free(&sc);
    sweep s;
    plan p;
    plan_text("name: t\nsweep:\n  technique: [phong]\n  mesh: [plane, sphere]\n  mesh_density: [0, 7, 9]\n"
              "exclude:\n  - { mesh: sphere, mesh_density: 9 }\n", &s, &p);
    assert_int_equal(p.n_excluded, 1);
    assert_int_equal(p.n_configs, 5);   /* plane 0, 7, 9 and sphere 0, 7 */
    plan_free(&p);
    sweep_free(&s);
}

/* Progress of planning: nondecreasing, ending at the total. */
typedef struct progress_log { size_t calls, last, total; int monotonic; } progress_log;

static void on_progress(size_t done, size_t total, void *user)
{
    progress_log *l = user;
    l->monotonic &= done >= l->last && done <= total;
    l->calls++;
    l->last = done;
    l->total = total;
}

/* A large sweep through the hash index: 150 x 150 distinct camera values are
 * 22500 configurations with distinct keys, each folded once; 6000 copies of
 * one value are one configuration folded 6000 times; progress is reported. */
static void test_large_sweep_index(void **state)
{
    (void)state;
    dm_str t = {0}, err = {0};
    dm_str_cat(&t, "name: t\nsweep:\n  technique: [normal]\n  camera.azimuth: [");
    for (int i = 0; i < 150; i++)
        dm_str_printf(&t, "%s%d", i ? "," : "", i);
    dm_str_cat(&t, "]\n  camera.distance: [");
    for (int i = 0; i < 150; i++)
        dm_str_printf(&t, "%s%.2f", i ? "," : "", 1 + i * 0.01);
    dm_str_cat(&t, "]\n");
    sweep s;
    plan p;
    assert_int_equal(sweep_parse(dm_str_get(&t), "t.yaml", &s, &err), 0);
    progress_log l = { .monotonic = 1 };
    plan_build_desc d = { .progress = on_progress, .user = &l };
    assert_int_equal(plan_build(&s, &d, &p, &err), 0);
    assert_int_equal(p.n_configs, 22500);
    assert_true(l.monotonic && l.calls >= 5);
    assert_int_equal(l.last, 22500);
    for (size_t i = 1; i < p.n_configs; i++)
        assert_int_equal(p.configs[i].folded, 1);
    plan_free(&p);
    sweep_free(&s);
    t.len = 0;
    dm_str_cat(&t, "name: t\nsweep:\n  technique: [normal]\n  camera.distance: [");
    for (int i = 0; i < 6000; i++)
        dm_str_cat(&t, i ? ",3" : "3");
    dm_str_cat(&t, "]\n");
    assert_int_equal(sweep_parse(dm_str_get(&t), "t.yaml", &s, &err), 0);
    assert_int_equal(plan_build(&s, NULL, &p, &err), 0);
    assert_int_equal(p.n_configs, 1);
    assert_int_equal(p.configs[0].folded, 6000);
    plan_free(&p);
    sweep_free(&s);
    dm_str_free(&t);
    dm_str_free(&err);
}

/* has_ext for plan_filter_capabilities: user points at the one extension
 * the pretend driver has, or NULL for none. */
static int plan_test_has_ext(const char *ext, void *user)
{
    return user && strcmp(ext, (const char *)user) == 0;
}

/* virtual_texture=sparse is left out at plan time on a driver without
 * GL_ARB_sparse_texture, with the missing extension named, and planned on
 * a driver with it (zink: tests/e2e/drivers.sh measures it); off and
 * software stay on both. */
static void test_sparse_left_out(void **state)
{
    (void)state;
    static const char *const drivers[] = {NULL, "GL_ARB_sparse_texture"};
    for (int d = 0; d < 2; d++) {
        sweep s;
        plan p;
        plan_text("name: t\nsweep:\n  technique: [texture]\n"
                  "  virtual_texture: [off, software, sparse]\n", &s, &p);
        assert_int_equal(p.n_configs, 3);
        plan_filter_capabilities(&p, plan_test_has_ext, (void *)drivers[d]);
        assert_int_equal(p.n_configs, d ? 3 : 2);
        assert_int_equal(p.n_left_out, d ? 0 : 1);
        if (d == 0) {
            assert_string_equal(dm_kv_get(p.left_out[0].params, p.left_out[0].n_params,
                                          "virtual_texture"), "sparse");
            const char *why = "the driver lacks GL_ARB_sparse_texture, which virtual_texture=sparse needs";
            if (!strstr(p.left_out[0].reason, why))
                fail_msg("reason '%s' lacks '%s'", p.left_out[0].reason, why);
            for (size_t i = 0; i < p.n_configs; i++)
                assert_string_not_equal(dm_kv_get(p.configs[i].params, p.configs[i].n_params,
                                                  "virtual_texture"), "sparse");
        }
        plan_free(&p);
        sweep_free(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fold_irrelevant_axis),
        cmocka_unit_test(test_scene_axes_kept),
        cmocka_unit_test(test_exclude),
        cmocka_unit_test(test_conditional_axis_folds),
        cmocka_unit_test(test_exclude_errors),
        cmocka_unit_test(test_density_out_of_mesh_range),
        cmocka_unit_test(test_path_refusals),
        cmocka_unit_test(test_keys_stable),
        cmocka_unit_test(test_shards_partition),
        cmocka_unit_test(test_shuffle_is_seeded_permutation),
        cmocka_unit_test(test_large_sweep_index),
        cmocka_unit_test(test_sparse_left_out),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
