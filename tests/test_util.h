/* test_util.h — what the cmocka test files share, so that each holds only
 * its own tests: the main() that runs them, reading a file, removing a
 * scratch directory, synthetic configurations and images of one colour.
 * Include it after <cmocka.h> (and the headers cmocka needs); everything
 * here is a macro or a static function, so a test that uses none of it pays
 * nothing. */
#ifndef TESTS_TEST_UTIL_H
#define TESTS_TEST_UTIL_H

#include <stdio.h>
#include <stdlib.h>

#include "core/dm_image.h"
#include "core/dm_results.h"
#include "core/dm_util.h"

/* main() of a test file: runs the cmocka_unit_test(...) entries given as the
 * remaining arguments as one group; setup and teardown are the group's
 * fixtures, or NULL.  Exits non-zero when a test fails. */
#define DM_TEST_MAIN(setup, teardown, ...)                        \
    int main(void)                                                \
    {                                                             \
        const struct CMUnitTest tests[] = { __VA_ARGS__ };        \
        return cmocka_run_group_tests(tests, setup, teardown);    \
    }

/* Removes dir and everything below it; fails the test if rm fails. */
static inline void test_rm_rf(const char *dir)
{
    char *cmd = dm_xasprintf("rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    free(cmd);
}

/* The whole file at path as a NUL-terminated string the caller frees; fails
 * the test if it cannot be read.  noinline: GCC 12 otherwise mistakes the
 * result for the address of the local it was read through
 * (-Wdangling-pointer false positive). */
__attribute__((noinline, unused)) static char *test_slurp(const char *path)
{
    char *text = NULL;
    assert_int_equal(dm_read_file(path, &text, NULL), 0);
    return text;
}

/* Makes c the i-th configuration of a synthetic run: its key the 16 hex
 * digits of i + 1, its scene and its one param mesh "m<i>", measured ok. */
static inline void test_config_init(dm_config_result *c, size_t i)
{
    char key[32], mesh[32];
    snprintf(key, sizeof key, "%016zx", i + 1);
    snprintf(mesh, sizeof mesh, "m%zu", i);
    c->key = dm_xstrdup(key);
    c->scene = dm_xstrdup(mesh);
    dm_kv_push(&c->params, &c->n_params, "mesh", mesh);
    c->ok = 1;
}

/* Sets every pixel of im to the colour (r, g, b, a). */
static inline void test_img_fill(img *im, float r, float g, float b, float a)
{
    for (int i = 0; i < im->w * im->h; i++) {
        im->px[i * 4 + 0] = r;
        im->px[i * 4 + 1] = g;
        im->px[i * 4 + 2] = b;
        im->px[i * 4 + 3] = a;
    }
}

#endif
