/* Unit tests of techniques/maps: flat and bricks maps, normals from height. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/maps.h"

static void test_flat(void **state)
{
    (void)state;
    maps_set m;
    maps_desc d = {.name = "flat", .size = 32};
    assert_int_equal(maps_generate(&d, &m), 0);
    assert_int_equal(m.size, 32);
    for (size_t i = 0; i < 32 * 32; i++) {
        assert_true(m.height[i] == 0.5f);
        assert_true(m.normal[3 * i] == 0.0f && m.normal[3 * i + 1] == 0.0f);
        assert_true(m.normal[3 * i + 2] == 1.0f);
        assert_true(m.albedo[4 * i + 3] == 1.0f);
    }
    maps_free(&m);
}

static void test_bricks(void **state)
{
    (void)state;
    maps_set a, b;
    maps_desc d = {.size = 128};   /* name NULL = bricks */
    assert_int_equal(maps_generate(&d, &a), 0);
    assert_int_equal(maps_generate(&d, &b), 0);
    float lo = 1, hi = 0;
    for (size_t i = 0; i < 128 * 128; i++) {
        const float *n = &a.normal[3 * i];
        assert_float_equal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
        assert_true(n[2] > 0);
        assert_true(a.height[i] >= 0 && a.height[i] <= 1);
        lo = fminf(lo, a.height[i]);
        hi = fmaxf(hi, a.height[i]);
    }
    /* Mortar low, bricks high. */
    assert_true(lo < 0.25f);
    assert_true(hi > 0.75f);
    /* Deterministic: same input, same bytes. */
    assert_memory_equal(a.height, b.height, 128 * 128 * sizeof(float));
    assert_memory_equal(a.albedo, b.albedo, 128 * 128 * 4 * sizeof(float));
    maps_free(&a);
    maps_free(&b);
}

static void test_bad_input(void **state)
{
    (void)state;
    maps_set m;
    maps_desc u = {.name = "brickz"}, s = {.name = "flat", .size = 8};
    assert_int_equal(maps_generate(&u, &m), DM_ERR_UNKNOWN);
    assert_int_equal(maps_generate(&s, &m), DM_ERR_RANGE);
}

static void test_normal_formula(void **state)
{
    (void)state;
    /* h(x) = 0.5 + 0.25 sin(2πx/S): the central difference is exactly
     * 0.25 (sin(2π(x+1)/S) - sin(2π(x-1)/S)) = 0.5 cos(2πx/S) sin(2π/S). */
    enum { S = 64 };
    const double pi = 3.14159265358979323846;
    float h[S * S], n[S * S * 3];
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++)
            h[y * S + x] = (float)(0.5 + 0.25 * sin(2 * pi * x / S));
    float strength = 2.0f;
    maps_normal_from_height(h, S, strength, n);
    for (int x = 0; x < S; x++) {
        double diff = 0.5 * cos(2 * pi * x / S) * sin(2 * pi / S);
        double gu = diff * S / 2 * strength * MAPS_NORMAL_SCALE;
        double l = sqrt(gu * gu + 1);
        const float *v = &n[3 * (5 * S + x)];
        assert_float_equal(v[0], -gu / l, 2e-5);
        assert_float_equal(v[1], 0.0, 1e-7);
        assert_float_equal(v[2], 1 / l, 2e-5);
    }
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_flat),
             cmocka_unit_test(test_bricks),
             cmocka_unit_test(test_bad_input),
             cmocka_unit_test(test_normal_formula))
