/* The fraction grammar (sweep/fraction.h) that every flag and sweep-file
 * key shares: a percentage and a fraction mean the same double, a bare
 * number above 1 is refused naming both ways to say it, and the range and
 * the syntax are checked with their own codes. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "core/dm_error.h"
#include "sweep/fraction.h"
#include "test_util.h"

static const fraction_range any = { 0, INFINITY, 0, 0 };

static double parse_ok(const char *text, const fraction_range *r)
{
    double x = -1;
    dm_str err = {0};
    int rc = fraction_parse(text, "--x", r, &x, &err);
    if (rc)
        fail_msg("'%s': rc %d, %s", text, rc, dm_str_get(&err));
    dm_str_free(&err);
    return x;
}

/* rc and a message holding every one of the NULL-terminated needles. */
static void parse_bad(const char *text, const fraction_range *r, int want_rc, ...)
{
    double x = 42;
    dm_str err = {0};
    assert_int_equal(fraction_parse(text, "--x", r, &x, &err), want_rc);
    assert_true(x == 42);   /* unchanged */
    va_list ap;
    va_start(ap, want_rc);
    for (const char *n; (n = va_arg(ap, const char *));)
        if (!strstr(dm_str_get(&err), n))
            fail_msg("'%s': '%s' not in: %s", text, n, dm_str_get(&err));
    va_end(ap);
    dm_str_free(&err);
}

/* "P%" and its fraction are the same double, bit for bit. */
static void test_percent_equals_fraction(void **state)
{
    (void)state;
    const char *pairs[][2] = { { "5%", "0.05" }, { "3.3%", "0.033" }, { "0.5%", "0.005" },
                               { "100%", "1" }, { "0%", "0" }, { "12.5%", "0.125" },
                               { "0.01%", "0.0001" }, { "7%", "0.07" }, { "150%", "1.5" } };
    for (size_t i = 0; i < sizeof pairs / sizeof *pairs; i++) {
        double p = parse_ok(pairs[i][0], &any);
        double want = strtod(pairs[i][1], NULL);
        if (memcmp(&p, &want, sizeof p) != 0)
            fail_msg("%s gives %.17g, %s is %.17g", pairs[i][0], p, pairs[i][1], want);
        if (want <= 1)
            assert_true(parse_ok(pairs[i][1], &any) == p);
    }
    assert_true(parse_ok("5e1%", &any) == 0.5);   /* an exponent of its own */
    assert_true(parse_ok(".5", &any) == 0.5);
}

/* A bare number above 1 is refused with both ways to say it; exactly 1 is
 * 100 %. */
static void test_bare_above_one(void **state)
{
    (void)state;
    parse_bad("5", &any, DM_ERR_ARG, "--x '5'", "500 %", "5%", "0.05", NULL);
    parse_bad("1.5", &any, DM_ERR_ARG, "1.5%", "0.015", NULL);
    parse_bad("40", &any, DM_ERR_ARG, "40%", "0.4", NULL);
    assert_true(parse_ok("1", &any) == 1.0);
}

/* Syntax: no sign, no space, no words, no lone '%', nothing after it. */
static void test_syntax(void **state)
{
    (void)state;
    const char *bad[] = { "", "%", "abc", "-1", "+5%", " 5%", "5 %", "5%%", "5%x", "inf", "nan",
                          "0x10", "1e999%" };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        parse_bad(bad[i], &any, DM_ERR_ARG, "expected a percentage or a fraction", "5%", "0.05",
                  NULL);
    parse_bad(NULL, &any, DM_ERR_ARG, "(none)", NULL);
}

/* Range ends, open and closed, in percent in the message. */
static void test_range(void **state)
{
    (void)state;
    const fraction_range open01 = { 0, 1, 1, 1 }, half_open = { 0, 1, 1, 0 };
    parse_bad("0", &open01, DM_ERR_RANGE, "(0 %, 100 %)", NULL);
    parse_bad("0%", &open01, DM_ERR_RANGE, NULL);
    parse_bad("100%", &open01, DM_ERR_RANGE, NULL);
    parse_bad("1", &open01, DM_ERR_RANGE, NULL);
    parse_bad("150%", &half_open, DM_ERR_RANGE, "(0 %, 100 %]", NULL);
    assert_true(parse_ok("1", &half_open) == 1.0);
    assert_true(parse_ok("99.9%", &open01) == 0.999);
    assert_true(parse_ok("1e-9", &open01) == 1e-9);
    parse_bad("0", &(fraction_range){ 0, INFINITY, 1, 0 }, DM_ERR_RANGE, "(0 %, any)", NULL);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_percent_equals_fraction),
             cmocka_unit_test(test_bare_above_one),
             cmocka_unit_test(test_syntax),
             cmocka_unit_test(test_range))
