/* Unit tests of techniques/maps: the procedural sets, their analytic
 * properties, the compact layout and the disk cache. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_util.h"
#include "core/dm_image.h"
#include "techniques/axes.h"
#include "techniques/maps.h"

static const double PI = 3.14159265358979323846;

/* Every set: heights in [0,1], unit normals facing out, tiling (the
 * normal of column 0 uses column size-1: checked by generating twice the
 * same data), alpha 1, specular in [0,1]. */
static void test_all_sets(void **state)
{
    (void)state;
    const char *const *names = maps_names();
    size_t count = 0;
    for (size_t k = 0; names[k]; k++, count++) {
        maps_set m;
        maps_desc d = {.name = names[k], .size = 64};
        assert_int_equal(maps_generate(&d, &m), 0);
        for (size_t i = 0; i < 64 * 64; i++) {
            const float *n = &m.normal[3 * i];
            assert_true(m.height[i] >= 0 && m.height[i] <= 1);
            assert_float_equal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-5);
            assert_true(n[2] > 0);
            assert_true(m.albedo[4 * i + 3] == 1.0f);
            assert_true(m.specular[i] >= 0 && m.specular[i] <= 1);
        }
        maps_free(&m);
    }
    assert_int_equal(count, 7);   /* bricks stones terrain checker sine flat asteroid */
}

/* sine: h = 0.5 + 0.25 (sin kx + sin ky) at texel centres, and its normal
 * from central differences in closed form: (h[x+1] − h[x−1]) = 0.5 cos(k u)
 * sin(k/S), so g_u = 0.25 S cos(k u) sin(k/S) with k = 2πF. */
static void test_sine_exact(void **state)
{
    (void)state;
    enum { S = 128 };
    maps_set m;
    maps_desc d = {.name = "sine", .size = S, .normal_strength = 2.0f};
    assert_int_equal(maps_generate(&d, &m), 0);
    const double k = 2 * PI * MAPS_SINE_FREQ, s = 2.0 * MAPS_NORMAL_SCALE;
    for (int y = 0; y < S; y += 7)
        for (int x = 0; x < S; x += 5) {
            double u = (x + 0.5) / S, v = (y + 0.5) / S;
            assert_float_equal(m.height[y * S + x], 0.5 + 0.25 * (sin(k * u) + sin(k * v)), 1e-6);
            double gu = 0.25 * S * cos(k * u) * sin(k / S), gv = 0.25 * S * cos(k * v) * sin(k / S);
            double l = sqrt(s * s * (gu * gu + gv * gv) + 1);
            const float *n = &m.normal[3 * (y * S + x)];
            assert_float_equal(n[0], -s * gu / l, 2e-5);
            assert_float_equal(n[1], -s * gv / l, 2e-5);
            assert_float_equal(n[2], 1 / l, 2e-5);
        }
    maps_free(&m);
}

/* checker: MAPS_CHECKER_SQUARES squares per side; 256/32 = 8 texels each. */
static void test_checker(void **state)
{
    (void)state;
    maps_set m;
    maps_desc d = {.name = "checker", .size = 256};
    assert_int_equal(maps_generate(&d, &m), 0);
    assert_float_equal(m.albedo[0], 0.05, 1e-7);
    assert_float_equal(m.albedo[4 * 7], 0.05, 1e-7);
    assert_float_equal(m.albedo[4 * 8], 0.95, 1e-7);
    assert_float_equal(m.albedo[4 * (8 * 256 + 8)], 0.05, 1e-7);
    assert_float_equal(m.albedo[4 * (8 * 256)], 0.95, 1e-7);
    assert_true(m.height[1000] == 0.5f && m.normal[3 * 1000 + 2] == 1.0f);
    maps_free(&m);
}

/* stones and terrain have relief (a range of heights) and are deterministic. */
static void test_relief(void **state)
{
    (void)state;
    static const char *const sets[] = {"stones", "terrain"};
    for (int k = 0; k < 2; k++) {
        maps_set a, b;
        maps_desc d = {.name = sets[k], .size = 128};
        assert_int_equal(maps_generate(&d, &a), 0);
        assert_int_equal(maps_generate(&d, &b), 0);
        float lo = 1, hi = 0;
        for (size_t i = 0; i < 128 * 128; i++) {
            lo = fminf(lo, a.height[i]);
            hi = fmaxf(hi, a.height[i]);
        }
        assert_true(hi - lo > 0.5f);
        assert_memory_equal(a.height, b.height, 128 * 128 * sizeof(float));
        maps_free(&a);
        maps_free(&b);
    }
}

/* The compact layout has the same heights; albedo8 = round(255·sRGB(albedo))
 * (±1 at a rounding boundary) and alpha = round(255·specular); no normal/float albedo arrays. */
static void test_compact(void **state)
{
    (void)state;
    maps_set f, c;
    maps_desc d = {.name = "stones", .size = 64};
    assert_int_equal(maps_generate(&d, &f), 0);
    d.compact = 1;
    assert_int_equal(maps_generate(&d, &c), 0);
    assert_null(c.normal);
    assert_null(c.albedo);
    assert_memory_equal(f.height, c.height, 64 * 64 * sizeof(float));
    for (size_t i = 0; i < 64 * 64; i++) {
        for (int ch = 0; ch < 3; ch++)
            assert_in_range(c.albedo8[4 * i + (size_t)ch] - lrintf(255.0f * maps_srgb_encode(f.albedo[4 * i + (size_t)ch])) + 1, 0, 2);
        assert_int_equal(c.albedo8[4 * i + 3], lrintf(255.0f * f.specular[i]));
    }
    maps_free(&f);
    maps_free(&c);
}

/* Normal rows equal the matching rows of the whole map. */
static void test_normal_rows(void **state)
{
    (void)state;
    maps_set m;
    maps_desc d = {.name = "terrain", .size = 64};
    assert_int_equal(maps_generate(&d, &m), 0);
    float rows[3 * 64 * 5];
    maps_normal_rows(m.height, 64, 1.0f, 59, 64, rows);
    assert_memory_equal(rows, &m.normal[3 * 64 * 59], sizeof rows);
    maps_free(&m);
}

/* sRGB: the standard's fixed points and a round trip. */
static void test_srgb(void **state)
{
    (void)state;
    assert_float_equal(maps_srgb_encode(0.0031308f), 0.04045, 1e-5);
    assert_float_equal(maps_srgb_encode(0.5f), 0.735357, 1e-5);
    assert_float_equal(maps_srgb_decode(0.735357f), 0.5, 1e-5);
    for (float x = 0; x <= 1; x += 0.01f)
        assert_float_equal(maps_srgb_decode(maps_srgb_encode(x)), x, 1e-5);
}

/* The 8-bit code the compact sets store: the count of the thresholds
 * decode((k + 0.5)/255) at or below x, counted here one by one, at every
 * threshold, its neighbouring floats and 200 001 values of [0, 1]; and
 * the ends (NaN, negative, 1 and above). */
static float srgb8_thresh[255];

static int srgb8_by_count(float x)
{
    int n = 0;
    for (int k = 0; k < 255; k++)
        n += srgb8_thresh[k] <= x;
    return n;
}

static void test_srgb8(void **state)
{
    (void)state;
    for (int k = 0; k < 255; k++)
        srgb8_thresh[k] = maps_srgb_decode(((float)k + 0.5f) / 255.0f);
    for (int k = 0; k < 255; k++) {
        float t = srgb8_thresh[k];
        float xs[3] = {nextafterf(t, 0.0f), t, nextafterf(t, 2.0f)};
        for (int i = 0; i < 3; i++)
            assert_int_equal(maps_srgb8(xs[i]), srgb8_by_count(xs[i]));
    }
    for (int i = 0; i <= 200000; i++) {
        float x = (float)i / 200000.0f;
        if (maps_srgb8(x) != srgb8_by_count(x))
            fail_msg("maps_srgb8(%.9g) = %d, the thresholds say %d", (double)x, maps_srgb8(x), srgb8_by_count(x));
    }
    assert_int_equal(maps_srgb8(NAN), 0);
    assert_int_equal(maps_srgb8(-0.5f), 0);
    assert_int_equal(maps_srgb8(0.0f), 0);
    assert_int_equal(maps_srgb8(1.0f), 255);
    assert_int_equal(maps_srgb8(7.0f), 255);
    assert_int_equal(maps_srgb8(0.5f), 188);   /* 255 * 0.735357 = 187.5 + 0.019 */
}

/* The disk cache: the first call generates and writes, the second loads
 * the same bytes; a corrupt file is regenerated; sizes below
 * MAPS_CACHE_MIN_SIZE never touch the directory. */
static void test_cache(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm-mapcache-XXXXXX";
    assert_non_null(mkdtemp(dir));
    maps_set a, b, c;
    maps_desc d = {.name = "checker", .size = MAPS_CACHE_MIN_SIZE};
    assert_int_equal(maps_get_cached(&d, dir, &a), 0);
    assert_int_equal(a.from_cache, 0);
    assert_true(a.gen_ns > 0);
    assert_int_equal(maps_get_cached(&d, dir, &b), 0);
    assert_int_equal(b.from_cache, 1);
    size_t n = (size_t)MAPS_CACHE_MIN_SIZE * MAPS_CACHE_MIN_SIZE;
    assert_memory_equal(a.height, b.height, n * sizeof(float));
    assert_memory_equal(a.albedo8, b.albedo8, n * 4);
    char *path = dm_xasprintf("%s/checker-%d.dmmaps", dir, MAPS_CACHE_MIN_SIZE);
    assert_int_equal(dm_write_file(path, "garbage", 7), 0);
    assert_int_equal(maps_get_cached(&d, dir, &c), 0);
    assert_int_equal(c.from_cache, 0);
    assert_memory_equal(a.height, c.height, n * sizeof(float));
    maps_free(&c);
    assert_int_equal(maps_get_cached(&d, dir, &c), 0);
    assert_int_equal(c.from_cache, 1);   /* the bad file was replaced */
    /* 4 KB overwritten in the middle (magic and size intact): not used */
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    char junk[4096];
    memset(junk, 0x5a, sizeof junk);
    assert_int_equal(fseek(f, (long)(n * sizeof(float) / 2), SEEK_SET), 0);
    assert_int_equal(fwrite(junk, 1, sizeof junk, f), sizeof junk);
    assert_int_equal(fclose(f), 0);
    maps_free(&c);
    assert_int_equal(maps_get_cached(&d, dir, &c), 0);
    assert_int_equal(c.from_cache, 0);
    assert_memory_equal(a.height, c.height, n * sizeof(float));
    maps_desc small = {.name = "checker", .size = 64}, other = {.name = "checker", .size = 32};
    maps_set s;
    assert_false(maps_in_memory(&other));
    assert_int_equal(maps_get_cached(&small, dir, &s), 0);
    assert_int_equal(s.from_cache, 0);
    assert_true(maps_in_memory(&small));   /* the next one copies it */
    assert_false(maps_in_memory(&other));
    assert_false(maps_in_memory(&d));      /* the disk cache's size: never in memory */
    char *spath = dm_xasprintf("%s/checker-64.dmmaps", dir);
    assert_false(dm_file_exists(spath));
    remove(path);
    remove(dir);
    free(path);
    free(spath);
    maps_free(&a);
    maps_free(&b);
    maps_free(&c);
    maps_free(&s);
}

static void test_bad_input(void **state)
{
    (void)state;
    maps_set m;
    maps_desc u = {.name = "stonez"}, s = {.name = "terrain", .size = MAPS_MAX_SIZE * 2};
    assert_int_equal(maps_generate(&u, &m), DM_ERR_UNKNOWN);
    assert_int_equal(maps_generate(&s, &m), DM_ERR_RANGE);
    assert_int_equal(maps_get_cached(&u, "/nonexistent", &m), DM_ERR_UNKNOWN);
}

/* The cache directory follows DMBENCH_CACHE_DIR, then XDG_CACHE_HOME. */
static void test_cache_dir(void **state)
{
    (void)state;
    setenv("DMBENCH_CACHE_DIR", "/x/dm", 1);
    char *a = maps_cache_dir();
    assert_string_equal(a, "/x/dm/maps");
    unsetenv("DMBENCH_CACHE_DIR");
    setenv("XDG_CACHE_HOME", "/x/xdg", 1);
    char *b = maps_cache_dir();
    assert_string_equal(b, "/x/xdg/dmbench/maps");
    free(a);
    free(b);
}

/* Writes a w×h EXR whose R channel is f(i) (G, B = R, A 1). */
static void write_exr(const char *path, int w, int h, float (*f)(size_t))
{
    img im;
    assert_int_equal(img_alloc(&im, w, h), 0);
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        for (int c = 0; c < 4; c++)
            im.px[4 * i + (size_t)c] = c == 3 ? 1.0f : f(i);
    char why[256];
    assert_int_equal(img_save(&im, path, why, sizeof why), 0);
    img_free(&im);
}

static float ramp(size_t i) { return (float)(i % 32) / 31.0f; }
static float with_nan(size_t i) { return i == 17 ? NAN : 0.5f; }

/* Expects axes_check("maps", value) to fail naming `text`. */
static void expect_bad(const char *value, const char *text)
{
    dm_str e = {0};
    assert_int_equal(axes_check("maps", value, &e), DM_ERR_ARG);
    if (!strstr(dm_str_get(&e), text))
        fail_msg("'%s' not in '%s'", text, dm_str_get(&e));
    dm_str_free(&e);
}

/* User maps: a valid EXR height map passes plan-time validation and loads
 * exactly (normals derived from it); each kind of bad input is rejected with
 * the file named. */
static void test_user_maps(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm-usermaps-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *good = dm_xasprintf("%s/h.exr", dir), *odd = dm_xasprintf("%s/odd.exr", dir);
    char *nan = dm_xasprintf("%s/nan.exr", dir), *small = dm_xasprintf("%s/s.exr", dir);
    write_exr(good, 32, 32, ramp);
    write_exr(odd, 48, 48, ramp);
    write_exr(nan, 32, 32, with_nan);
    write_exr(small, 16, 16, ramp);
    char *v = dm_xasprintf("height=%s", good);
    dm_str e = {0};
    assert_int_equal(axes_check("maps", v, &e), 0);
    maps_set m;
    assert_int_equal(maps_material_load(v, &m, &e), 0);
    assert_int_equal(m.size, 32);
    for (size_t i = 0; i < 32 * 32; i++)
        assert_true(m.height[i] == ramp(i));
    float n[3 * 32 * 32];
    maps_normal_from_height(m.height, 32, 1.0f, n);
    assert_memory_equal(n, m.normal, sizeof n);
    assert_float_equal(m.albedo[0], 0.75, 1e-7);
    maps_free(&m);
    char *b1 = dm_xasprintf("height=%s/missing.png", dir), *b2 = dm_xasprintf("normal=%s", odd);
    char *b3 = dm_xasprintf("albedo=%s", nan), *b4 = dm_xasprintf("height=%s;albedo=%s", good, small);
    char *b5 = dm_xasprintf("heigth=%s", good);
    expect_bad(b1, "material height map '");
    expect_bad(b1, "missing.png' cannot be read");
    expect_bad(b2, "odd.exr' (48x48) must be square with a power-of-two side");
    expect_bad(b3, "nan.exr' (32x32) holds non-finite values");
    expect_bad(b4, "s.exr' (16x16) differs in size from the other maps");
    expect_bad(b5, "invalid material entry 'heigth=");
    char *all[] = {good, odd, nan, small, v, b1, b2, b3, b4, b5};
    for (int i = 0; i < 4; i++)
        remove(all[i]);
    remove(dir);
    for (int i = 0; i < 10; i++)
        free(all[i]);
    dm_str_free(&e);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_all_sets),
             cmocka_unit_test(test_sine_exact),
             cmocka_unit_test(test_checker),
             cmocka_unit_test(test_relief),
             cmocka_unit_test(test_compact),
             cmocka_unit_test(test_normal_rows),
             cmocka_unit_test(test_srgb),
             cmocka_unit_test(test_srgb8),
             cmocka_unit_test(test_cache),
             cmocka_unit_test(test_bad_input),
             cmocka_unit_test(test_cache_dir),
             cmocka_unit_test(test_user_maps))
