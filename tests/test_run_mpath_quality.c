/* Quality along a path (run/mpath_quality.h), its pure parts: which frames
 * get a reference (K's default rule and its bounds) and which
 * configurations ask for it.  The rendering is run by test_e2e_motion_ladder. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "run/mpath_quality.h"
#include "test_util.h"

/* K = 0 is F − 1 (two references: the first and last frame); 1..F−1 is
 * itself; above F − 1, negative, or a pass of fewer than 2 frames: 0. */
static void test_every(void **state)
{
    (void)state;
    assert_int_equal(mpath_quality_every(60, 0), 59);
    assert_int_equal(mpath_quality_count(60, 59), 2);            /* frames 0 and 59 */
    assert_int_equal(mpath_quality_every(60, 1), 1);
    assert_int_equal(mpath_quality_count(60, 1), 60);
    assert_int_equal(mpath_quality_every(12, 5), 5);
    assert_int_equal(mpath_quality_count(12, 5), 3);             /* 0, 5, 10 */
    assert_int_equal(mpath_quality_every(12, 11), 11);
    assert_int_equal(mpath_quality_every(12, 12), 0);            /* no second frame */
    assert_int_equal(mpath_quality_every(12, -1), 0);
    assert_int_equal(mpath_quality_every(1, 0), 0);
    assert_int_equal(mpath_quality_every(2, 0), 1);
    assert_int_equal(mpath_quality_count(2, 1), 2);
    assert_int_equal(mpath_quality_count(12, 0), 0);
    assert_int_equal(mpath_quality_count(60, 20), 3);            /* 0, 20, 40 */
}

static void shown_is(long frames, long k, size_t cap, const long *want, size_t n_want)
{
    long got[32] = {0};
    size_t n = mpath_quality_shown(frames, k, cap, got);
    assert_int_equal(n, n_want);
    for (size_t i = 0; i < n; i++)
        assert_int_equal(got[i], want[i]);
}

/* The frames written as images (MPATH_SHOTS_MAX): every reference frame
 * up to the cap, else round(j (n − 1) / (cap − 1)) of the n reference
 * frames, worked out by hand below. */
static void test_shown(void **state)
{
    (void)state;
    assert_int_equal(MPATH_SHOTS_MAX, 16);
    long all12[12];
    for (long i = 0; i < 12; i++)
        all12[i] = i;
    shown_is(12, 1, 16, all12, 12);                           /* 12 <= 16: all */
    shown_is(60, 59, 16, (long[]){0, 59}, 2);                 /* the default K */
    shown_is(10, 1, 4, (long[]){0, 3, 6, 9}, 4);              /* j · 9 / 3 */
    shown_is(21, 2, 4, (long[]){0, 6, 14, 20}, 4);            /* indices 0, 3.33, 6.67, 10 of 0..10 */
    shown_is(6, 1, 5, (long[]){0, 1, 3, 4, 5}, 5);            /* 2.5 rounds up */
    /* 17 frames into 16: j · 16 / 15 skips only index 8 (7.47 → 7, 8.53 → 9) */
    shown_is(17, 1, 16, (long[]){0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15, 16}, 16);
    /* K = 1 on 100 000 frames: 16, not 100 000; j · 99 999 / 15 */
    long big[16];
    size_t n = mpath_quality_shown(100000, 1, MPATH_SHOTS_MAX, big);
    assert_int_equal(n, 16);
    assert_int_equal(big[0], 0);
    assert_int_equal(big[1], 6667);                           /* 6666.6 */
    assert_int_equal(big[2], 13333);                          /* 13333.2 */
    assert_int_equal(big[3], 20000);                          /* 19999.8 */
    assert_int_equal(big[8], 53333);                          /* 53332.8 */
    assert_int_equal(big[15], 99999);
    shown_is(12, 1, 1, (long[]){0}, 1);                       /* cap 1: the first only */
    shown_is(12, 1, 0, NULL, 0);
    shown_is(12, 0, 16, NULL, 0);                             /* no K: nothing */
}

/* A path other than still asks; a still one only with K set. */
static void test_wanted(void **state)
{
    (void)state;
    dm_kv dolly[] = {{.key = "technique", .value = "pom"}, {.key = "camera.path", .value = "dolly"}};
    dm_kv still[] = {{.key = "technique", .value = "pom"}, {.key = "camera.path", .value = "still"}};
    dm_kv none[] = {{.key = "technique", .value = "pom"}};
    dm_kv k[] = {{.key = "technique", .value = "pom"}, {.key = "camera.path_ref_every", .value = "20"}};
    dm_kv k0[] = {{.key = "technique", .value = "pom"}, {.key = "camera.path_ref_every", .value = "0"}};
    assert_true(mpath_quality_wanted(dolly, 2));
    assert_false(mpath_quality_wanted(still, 2));
    assert_false(mpath_quality_wanted(none, 1));
    assert_true(mpath_quality_wanted(k, 2));
    assert_false(mpath_quality_wanted(k0, 2));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_every),
             cmocka_unit_test(test_shown),
             cmocka_unit_test(test_wanted))
