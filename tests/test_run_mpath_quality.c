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
             cmocka_unit_test(test_wanted))
