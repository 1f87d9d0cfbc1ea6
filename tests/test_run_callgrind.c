/* test_run_callgrind.c — the Instructions pass's pure parts: a dump file's
 * trigger and totals, and the run's warning for samples that disagree. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "test_util.h"

#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "run/callgrind.h"

static callgrind_count counted(double a, double b)
{
    callgrind_count c = {.key = "0123456789abcdef", .counted = 1, .samples = {a, b}};
    return c;
}

static void test_parse_dump(void **state)
{
    (void)state;
    char name[64];
    double t = 0;
    assert_int_equal(callgrind_parse_dump("version: 1\ndesc: Trigger: Client Request: k.1\n"
                                          "events: Ir\ntotals: 12345\n", name, sizeof name, &t), 0);
    assert_string_equal(name, "k.1");
    assert_true(t == 12345.0);
    assert_int_equal(callgrind_parse_dump("desc: Trigger: Program termination\n", name, sizeof name, &t),
                     DM_ERR_PARSE);
}

/* The boundary is CALLGRIND_AGREE relative to the smaller sample, both ways. */
static void test_disagreement_boundary(void **state)
{
    (void)state;
    callgrind_count at = counted(1e8, 1e8 + 1e4), over = counted(1e8 + 1e4 + 1, 1e8);
    assert_null(callgrind_disagreement(&at));      /* exactly 1e-4: agrees */
    char *w = callgrind_disagreement(&over);       /* just above, in either order */
    assert_non_null(w);
    assert_non_null(strstr(w, "0123456789abcdef"));
    assert_non_null(strstr(w, "100000000 .. 100010001"));
    free(w);
}

static void test_disagreement_not_counted(void **state)
{
    (void)state;
    callgrind_count c = counted(1, 2);
    c.counted = 0;
    assert_null(callgrind_disagreement(&c));       /* unavailable or failed: no count to judge */
    callgrind_count same = counted(5e6, 5e6);
    assert_null(callgrind_disagreement(&same));
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_parse_dump),
             cmocka_unit_test(test_disagreement_boundary),
             cmocka_unit_test(test_disagreement_not_counted))
