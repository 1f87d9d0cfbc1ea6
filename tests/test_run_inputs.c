/* test_run_inputs.c — the user's map and mesh files a run holds to one
 * version (run/inputs.c): collected once from a plan's parameters, a
 * touched file with the same bytes passes, an edit or a removal is named,
 * and --resume compares the recorded hashes with the files now. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "test_util.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "run/inputs.h"

static char dir[] = "/tmp/dm-inputs-XXXXXX";
static char mesh_path[256], map_path[256], normal_path[256];

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int setup(void **state)
{
    (void)state;
    if (!mkdtemp(dir))
        return -1;
    snprintf(mesh_path, sizeof mesh_path, "%s/m.obj", dir);
    snprintf(map_path, sizeof map_path, "%s/h.png", dir);
    snprintf(normal_path, sizeof normal_path, "%s/n;x.png", dir);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    inputs_clear();
    test_rm_rf(dir);
    return 0;
}

/* A plan of two configurations naming the mesh twice, a material with a
 * height and a normal map (';' in a path written ';;'), and built-ins. */
static void collect(void)
{
    write_text(mesh_path, "v 0 0 0\n");
    write_text(map_path, "height");
    write_text(normal_path, "normal");
    char *material = dm_xasprintf("height=%s;normal=%s/n;;x.png", map_path, dir);
    char *mesh = dm_xasprintf("file:%s", mesh_path);
    dm_kv p0[] = {{.key = "maps", .value = material}, {.key = "technique", .value = "pom"}};
    dm_kv s0[] = {{.key = "mesh", .value = mesh}};
    dm_kv p1[] = {{.key = "maps", .value = "bricks"}};
    dm_kv s1[] = {{.key = "mesh", .value = mesh}, {.key = "reference_mesh", .value = "cube"}};
    plan_config cs[2] = {{.params = p0, .n_params = 2, .scene_params = s0, .n_scene_params = 1},
                         {.params = p1, .n_params = 1, .scene_params = s1, .n_scene_params = 2}};
    plan p = {.configs = cs, .n_configs = 2};
    inputs_clear();
    dm_str err = {0};
    assert_int_equal(inputs_collect(&p, &err), 0);
    dm_str_free(&err);
    free(material);
    free(mesh);
}

static void test_collects_each_file_once(void **state)
{
    (void)state;
    collect();
    assert_int_equal(inputs_count(), 3);
    assert_string_equal(inputs_path(0), map_path);
    assert_string_equal(inputs_path(1), normal_path);
    assert_string_equal(inputs_path(2), mesh_path);
    /* FNV-1a of the bytes, computed independently */
    assert_true(inputs_hash(1) == dm_fnv1a64("normal", 6, DM_FNV_SEED));
    dm_str err = {0};
    assert_int_equal(inputs_check(&err), 0);
    assert_int_equal(err.len, 0);
    dm_str_free(&err);
}

static void test_touch_passes_edit_fails(void **state)
{
    (void)state;
    collect();
    struct timespec later[2] = {{.tv_sec = time(NULL) + 100}, {.tv_sec = time(NULL) + 100}};
    assert_int_equal(utimensat(AT_FDCWD, mesh_path, later, 0), 0);   /* touched: same bytes */
    dm_str err = {0};
    assert_int_equal(inputs_check(&err), 0);
    write_text(mesh_path, "v 1 0 0\n");   /* same size, other bytes */
    assert_int_equal(inputs_check(&err), DM_ERR_ARG);
    char *want = dm_xasprintf("%s: the mesh file changed since the run started", mesh_path);
    assert_non_null(strstr(dm_str_get(&err), want));
    free(want);
    dm_str_free(&err);
    write_text(mesh_path, "v 0 0 0\n");   /* restored */
    assert_int_equal(inputs_check(&err), 0);
    assert_int_equal(unlink(map_path), 0);
    assert_int_equal(inputs_check(&err), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&err), "the map file cannot be read since the run started"));
    dm_str_free(&err);
}

static void test_resume_compares_recorded(void **state)
{
    (void)state;
    collect();
    dm_kv *env = NULL;
    size_t n = 0;
    inputs_record(&env, &n);
    assert_int_equal(n, 3);
    char *key = dm_xasprintf("%s%s", INPUTS_ENV_PREFIX, mesh_path);
    assert_string_equal(env[2].key, key);
    free(key);
    dm_str err = {0};
    assert_int_equal(inputs_resume_check(env, n, "RUN", &err), 0);
    write_text(normal_path, "normal, edited");
    assert_int_equal(inputs_resume_check(env, n, "RUN", &err), DM_ERR_ARG);
    char *want = dm_xasprintf("--resume: %s: the file changed since run RUN measured it", normal_path);
    assert_non_null(strstr(dm_str_get(&err), want));
    free(want);
    dm_str_free(&err);
    dm_kv_free(env, n);
}

DM_TEST_MAIN(setup, teardown, cmocka_unit_test(test_collects_each_file_once),
             cmocka_unit_test(test_touch_passes_edit_fails),
             cmocka_unit_test(test_resume_compares_recorded))
