/* test_run_refcache.c — the on-disk reference-image cache: keys cover
 * every input, entries round-trip exactly, and anything else misses. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "test_util.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "run/refcache.h"
#include "techniques/axes.h"

#define W 5
#define H 3

static const dm_kv params[] = {
    {.key = "technique", .value = "pom"}, {.key = "mesh", .value = "plane"},
    {.key = "steps", .value = "32"},      {.key = "resolution", .value = "5x3"},
};
#define NP (sizeof params / sizeof params[0])

static char *key_of(const dm_kv *p, size_t n, int w, int h, int ss, const char *driver)
{
    refcache_desc d = {.params = p, .n_params = n, .width = w, .height = h, .supersample = ss,
                       .driver = driver};
    dm_str k = {0};
    assert_int_equal(refcache_key(&d, &k), 0);
    return dm_str_take(&k);
}

static void test_key_covers_inputs(void **state)
{
    (void)state;
    char *base = key_of(params, NP, W, H, 4, "llvmpipe | 4.5");
    dm_kv rev[NP];                                /* same parameters, other order */
    for (size_t i = 0; i < NP; i++)
        rev[i] = params[NP - 1 - i];
    char *same = key_of(rev, NP, W, H, 4, "llvmpipe | 4.5");
    assert_string_equal(base, same);
    dm_kv extra[NP + 1];                          /* an axis pom does not read: same image */
    memcpy(extra, params, sizeof params);
    extra[NP] = (dm_kv){.key = "tess_level", .value = "16"};
    char *unread = key_of(extra, NP + 1, W, H, 4, "llvmpipe | 4.5");
    assert_string_equal(base, unread);
    free(unread);
    /* an axis left out is the renderer's default: same key as given explicitly */
    extra[NP] = (dm_kv){.key = "shadow", .value = (char *)axes_find("shadow")->def};
    char *explicit_def = key_of(extra, NP + 1, W, H, 4, "llvmpipe | 4.5");
    assert_string_equal(explicit_def, base);
    extra[NP].value = "raytrace";
    char *shadow = key_of(extra, NP + 1, W, H, 4, "llvmpipe | 4.5");
    assert_string_not_equal(shadow, base);
    free(explicit_def);
    free(shadow);
    dm_kv steps[NP];
    memcpy(steps, params, sizeof steps);
    steps[2].value = "8";
    char *variants[] = {
        key_of(steps, NP, W, H, 4, "llvmpipe | 4.5"), key_of(params, NP - 1, W, H, 4, "llvmpipe | 4.5"),
        key_of(params, NP, W + 1, H, 4, "llvmpipe | 4.5"), key_of(params, NP, W, H, 2, "llvmpipe | 4.5"),
        key_of(params, NP, W, H, 4, "other | 4.5"),
    };
    for (size_t i = 0; i < sizeof variants / sizeof variants[0]; i++) {
        assert_string_not_equal(base, variants[i]);
        free(variants[i]);
    }
    assert_non_null(strstr(base, "technique pom version "));
    assert_non_null(strstr(base, "\nsteps=32\n"));
    free(same);
    free(base);
}

/* A frame along a camera path has its frame in the key; the still image
 * has no frame line, and K (camera.path_ref_every: which frames get a
 * reference, not how one looks) is in no key, so a still key is as it was
 * before paths. */
static void test_key_frames(void **state)
{
    (void)state;
    dm_kv p[NP + 2];
    memcpy(p, params, sizeof params);
    p[NP] = (dm_kv){.key = "camera.path", .value = "dolly"};
    p[NP + 1] = (dm_kv){.key = "camera.path_ref_every", .value = "3"};
    refcache_desc d = {.params = p, .n_params = NP + 2, .width = W, .height = H, .supersample = 4,
                       .driver = "llvmpipe | 4.5", .on_path = 1, .frame = 3};
    dm_str k3 = {0}, k6 = {0}, k3b = {0}, still = {0};
    assert_int_equal(refcache_key(&d, &k3), 0);
    d.frame = 6;
    assert_int_equal(refcache_key(&d, &k6), 0);
    assert_string_not_equal(dm_str_get(&k3), dm_str_get(&k6));
    assert_non_null(strstr(dm_str_get(&k3), "\nframe 3\n"));
    assert_non_null(strstr(dm_str_get(&k3), "\ncamera.path=dolly\n"));
    assert_null(strstr(dm_str_get(&k3), "path_ref_every"));
    p[NP + 1].value = "1";                         /* another K: the same frame 3 */
    d.frame = 3;
    assert_int_equal(refcache_key(&d, &k3b), 0);
    assert_string_equal(dm_str_get(&k3), dm_str_get(&k3b));
    char *base = key_of(params, NP, W, H, 4, "llvmpipe | 4.5");
    refcache_desc sd = {.params = params, .n_params = NP, .width = W, .height = H, .supersample = 4,
                        .driver = "llvmpipe | 4.5", .on_path = 0, .frame = 7};
    assert_int_equal(refcache_key(&sd, &still), 0);
    assert_string_equal(dm_str_get(&still), base);
    assert_null(strstr(base, "\nframe "));
    assert_null(strstr(base, "path_ref_every"));
    free(base);
    dm_str_free(&k3);
    dm_str_free(&k6);
    dm_str_free(&k3b);
    dm_str_free(&still);
}

static void test_key_refusals(void **state)
{
    (void)state;
    dm_str k = {0};
    refcache_desc d = {.params = params + 1, .n_params = NP - 1, .width = W, .height = H};
    assert_int_equal(refcache_key(&d, &k), DM_ERR_ARG);            /* no technique */
    dm_kv bad[1] = {{.key = "technique", .value = "no-such-technique"}};
    d = (refcache_desc){.params = bad, .n_params = 1, .width = W, .height = H};
    assert_int_equal(refcache_key(&d, &k), DM_ERR_UNKNOWN);
    d = (refcache_desc){.params = params, .n_params = NP, .width = 0, .height = H};
    assert_int_equal(refcache_key(&d, &k), DM_ERR_ARG);
    dm_str_free(&k);
}

static void test_dir_follows_env(void **state)
{
    (void)state;
    setenv("DMBENCH_CACHE_DIR", "/some/where", 1);
    char *d = refcache_dir();
    assert_string_equal(d, "/some/where/references");
    free(d);
}

/* A stored entry loads back bit for bit; another key or size misses; a
 * truncated entry is an I/O error; nothing is returned on failure. */
static void test_store_load(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_refcache_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *sub = NULL;
    assert_true(asprintf(&sub, "%s/references", dir) > 0);
    float rgba[W * H * 4], depth[W * H];
    for (int i = 0; i < W * H * 4; i++)
        rgba[i] = (float)i * 0.25f - 3.0f;
    for (int i = 0; i < W * H; i++)
        depth[i] = 1.0f / (float)(i + 1);
    char *key = key_of(params, NP, W, H, 4, "drv");
    float *a = NULL, *b = NULL;
    assert_int_equal(refcache_load(sub, key, W, H, &a, &b), DM_ERR_NOTFOUND);   /* empty cache */
    assert_int_equal(refcache_store(sub, key, W, H, rgba, depth), 0);           /* creates the dir */
    assert_int_equal(refcache_load(sub, key, W, H, &a, &b), 0);
    assert_memory_equal(a, rgba, sizeof rgba);
    assert_memory_equal(b, depth, sizeof depth);
    free(a);
    free(b);
    a = b = NULL;
    char *other = key_of(params, NP, W, H, 2, "drv");
    assert_int_equal(refcache_load(sub, other, W, H, &a, &b), DM_ERR_NOTFOUND);
    assert_int_equal(refcache_load(sub, key, W, H + 1, &a, &b), DM_ERR_NOTFOUND);
    assert_null(a);
    assert_null(b);
    /* truncate the entry by one float: an I/O error, nothing returned */
    char *cmd = NULL;
    assert_true(asprintf(&cmd, "for f in %s/*.dmref; do truncate -s -4 \"$f\"; done", sub) > 0);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(refcache_load(sub, key, W, H, &a, &b), DM_ERR_IO);
    assert_null(a);
    free(cmd);
    test_rm_rf(dir);
    free(other);
    free(key);
    free(sub);
}

/* Trimming removes the least recently used entries first: a load counts
 * as a use. */
static void test_trim_lru(void **state)
{
    (void)state;
    char dir[] = "/tmp/test_refcache_trim_XXXXXX";
    assert_non_null(mkdtemp(dir));
    float rgba[W * H * 4] = {0}, depth[W * H] = {0};
    char *keys[3];
    for (int i = 0; i < 3; i++) {
        keys[i] = key_of(params, NP, W, H, 4, i == 0 ? "a" : i == 1 ? "b" : "c");
        assert_int_equal(refcache_store(dir, keys[i], W, H, rgba, depth), 0);
        usleep(20000);                        /* distinct modification times */
    }
    float *a = NULL;
    assert_int_equal(refcache_load(dir, keys[0], W, H, &a, NULL), 0);   /* "a" used last now */
    free(a);
    struct stat st;
    /* every entry has the same size: room for two of them */
    DIR *d = opendir(dir);
    off_t size = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (strstr(e->d_name, ".dmref")) {
            char *p = NULL;
            assert_true(asprintf(&p, "%s/%s", dir, e->d_name) > 0);
            assert_int_equal(stat(p, &st), 0);
            size = st.st_size;
            free(p);
        }
    closedir(d);
    assert_true(size > 0);
    assert_int_equal(refcache_trim(dir, 3ull * (unsigned long long)size), 0);
    assert_int_equal(refcache_trim(dir, 2ull * (unsigned long long)size), 1);
    assert_int_equal(refcache_load(dir, keys[1], W, H, &a, NULL), DM_ERR_NOTFOUND);   /* "b": oldest */
    assert_int_equal(refcache_load(dir, keys[0], W, H, &a, NULL), 0);
    free(a);
    assert_int_equal(refcache_load(dir, keys[2], W, H, &a, NULL), 0);
    free(a);
    assert_int_equal(refcache_trim(dir, 0), 2);
    assert_int_equal(refcache_trim("/nonexistent/dir", 0), 0);
    assert_int_equal(rmdir(dir), 0);
    for (int i = 0; i < 3; i++)
        free(keys[i]);
}

/* ---- through dmbench: a second run loads the reference ------------------ */

static const char run_sweep[] =
    "name: refcache\n"
    "resolution: [64, 36]\n"
    "measure: { warmup_frames: 1, frames_per_sample: 1, min_sample_ms: 0,\n"
    "           samples: { min: 3, max: 3 }, counters: [WallTime] }\n"
    "scene: { camera: { elevation: %d } }\n"
    "sweep: { mesh: [plane], technique: [texture] }\n";

/* Runs a one-configuration sweep (camera elevation `elev`) with the cache
 * under dir; returns the configuration's SilhouetteError against its
 * reference, or -1. */
static double run_silhouette(const char *dir, int elev)
{
    char *sweep = NULL, *text = NULL, *cmd = NULL, *json = NULL, *path = NULL;
    assert_true(asprintf(&sweep, "%s/s.yaml", dir) > 0);
    assert_true(asprintf(&text, run_sweep, elev) > 0);
    FILE *f = fopen(sweep, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    assert_true(asprintf(&cmd, "\"%s\" run \"%s\" --out \"%s/out\" --quiet > /dev/null 2>&1",
                         getenv("DMBENCH_BINARY"), sweep, dir) > 0);
    assert_int_equal(system(cmd), 0);
    assert_true(asprintf(&path, "%s/out/latest/results.json", dir) > 0);
    size_t len = 0;
    assert_int_equal(dm_read_file(path, &json, &len), 0);
    cJSON *root = cJSON_Parse(json);
    cJSON *q = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(root, "configs"), 0), "quality");
    cJSON *se = cJSON_GetObjectItem(q, "SilhouetteError");
    double v = cJSON_IsNumber(se) ? se->valuedouble : -1;
    cJSON_Delete(root);
    free(json);
    free(path);
    free(cmd);
    free(text);
    free(sweep);
    return v;
}

/* Number of entries in dir; with blank = 1 also zeroes the pixels of each
 * (colour and depth after the header), so a loaded entry shows. */
static int entries(const char *dir, int blank)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (!strstr(e->d_name, ".dmref"))
            continue;
        n++;
        char *path = NULL, *buf = NULL;
        size_t len = 0;
        assert_true(asprintf(&path, "%s/%s", dir, e->d_name) > 0);
        if (blank && dm_read_file(path, &buf, &len) == 0) {
            uint32_t klen;
            memcpy(&klen, buf + 8, sizeof klen);
            size_t head = 8 + sizeof klen + klen + 8;
            assert_true(len > head);
            memset(buf + head, 0, len - head);
            assert_int_equal(dm_write_file(path, buf, len), 0);
        }
        free(buf);
        free(path);
    }
    closedir(d);
    return n;
}

/* Run 1 renders and stores the reference (a small silhouette error: the
 * reference-mesh against texture on a plane).  The entry is blanked; run 2
 * loads it, so the reference covers nothing and the error is exactly 1.
 * Run 3 changes the camera: a miss, rendered and stored as a second entry. */
static void test_second_run_loads(void **state)
{
    (void)state;
    assert_non_null(getenv("DMBENCH_BINARY"));
    char dir[] = "/tmp/test_refcache_run_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *root = NULL, *refs = NULL;
    assert_true(asprintf(&root, "%s/cache", dir) > 0);
    assert_true(asprintf(&refs, "%s/references", root) > 0);
    setenv("DMBENCH_CACHE_DIR", root, 1);
    double first = run_silhouette(dir, 35);
    assert_true(first >= 0 && first < 0.5);
    assert_int_equal(entries(refs, 1), 1);
    assert_true(run_silhouette(dir, 35) == 1.0);
    double other = run_silhouette(dir, 50);
    assert_true(other >= 0 && other < 0.5);
    assert_int_equal(entries(refs, 0), 2);
    test_rm_rf(dir);
    free(refs);
    free(root);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_key_covers_inputs),
             cmocka_unit_test(test_key_frames),
             cmocka_unit_test(test_key_refusals),
             cmocka_unit_test(test_dir_follows_env),
             cmocka_unit_test(test_store_load),
             cmocka_unit_test(test_trim_lru),
             cmocka_unit_test(test_second_run_loads))
