/* test_models_budget.c — end to end: `dmbench run --budget` predicts from the
 * cost model a previous run of the same store fitted, and falls back to a
 * pilot frame in a store without one (tests/e2e/tiny.yaml: 4 configurations,
 * model resolution-cost = a + b*SamplesPassed with a, b >= 0, SamplesPassed
 * stored per key: the bounds keep every prediction positive — unbounded, a
 * noisy run could fit a < 0 and predict a non-positive time for the smallest
 * configuration, which --budget rightly refuses and measures instead). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "test_util.h"

#include "core/dm_util.h"

/* Runs dmbench with the arguments that fmt makes, prints its stderr to the
 * test log (so that it is there when an assertion fails) and returns it;
 * fails the test when dmbench fails. */
__attribute__((format(printf, 1, 2))) static char *dmbench(const char *fmt, ...)
{
    const char *bin = getenv("DMBENCH_BINARY");
    assert_non_null(bin);
    va_list ap;
    va_start(ap, fmt);
    dm_str args = {0};
    dm_str_vprintf(&args, fmt, ap);
    va_end(ap);
    char *cmd = dm_xasprintf("'%s' %s 2>&1 >/dev/null", bin, dm_str_get(&args));
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    dm_str out = {0};
    assert_int_equal(dm_read_stream(p, &out), 0);
    int status = pclose(p);
    printf("%s", dm_str_get(&out));
    if (status != 0)
        printf("dmbench %s exited with %d\n", dm_str_get(&args), status);
    assert_int_equal(status, 0);
    free(cmd);
    dm_str_free(&args);
    return dm_str_take(&out);
}

static void budget_from_stored_model(void **state)
{
    (void)state;
    char dir[] = "/tmp/dm_budget_XXXXXX";
    assert_non_null(mkdtemp(dir));
    const char *src = getenv("DMBENCH_SOURCE_DIR");
    assert_non_null(src);
    char *yaml = dm_xasprintf("%s/tests/e2e/tiny.yaml", src);
    /* A store without fits: every configuration gets a pilot frame. */
    char *err = dmbench("run '%s' --out '%s/fresh' --budget 0.000001", yaml, dir);
    assert_non_null(strstr(err, "--budget 1e-06 s: 0 configurations predicted by a cost model, "
                           "0 by the instruction models, 4 by a pilot frame; 4 left out"));
    free(err);
    /* A measured run stores its fit; the next run predicts from it. */
    free(dmbench("run '%s' --out '%s/s' --quiet", yaml, dir));
    err = dmbench("run '%s' --out '%s/s' --budget 0.000001", yaml, dir);
    assert_non_null(strstr(err, "4 configurations predicted by a cost model (run "));
    assert_non_null(strstr(err, "0 by the instruction models, 0 by a pilot frame; 4 left out"));
    free(err);
    char *json_path = dm_xasprintf("%s/s/latest/results.json", dir);
    char *json = test_slurp(json_path);
    free(json_path);
    assert_non_null(strstr(json, "over --budget 1e-06 s: model resolution-cost (run "));
    assert_null(strstr(json, "a pilot frame took"));
    free(json);
    test_rm_rf(dir);
    free(yaml);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(budget_from_stored_model))
