/* test_run_callgrind.c — the Instructions pass's pure parts: a dump file's
 * trigger and totals, the run's warning for samples that disagree, and
 * how many counting children run side by side. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "test_util.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
                                          "events: Ir\ntotals: 12345\n", name, sizeof name, &t, NULL), 0);
    assert_string_equal(name, "k.1");
    assert_true(t == 12345.0);
    assert_int_equal(callgrind_parse_dump("desc: Trigger: Program termination\n", name, sizeof name, &t, NULL),
                     DM_ERR_PARSE);
}

/* The allocator's part of a dump is the inclusive cost of the calls into
 * it from outside: here draw calls realloc (inclusive 700, of which its
 * nested malloc 200 and memcpy 300 must not count twice), malloc again
 * through the compressed id (50), and free'2 (a recursion suffix, 30);
 * the call to memcpy from draw (1000) and realloc's own lines are not the
 * allocator's.  The functions' names are compressed ("(ID) name" once,
 * then "(ID)"), as callgrind writes them. */
static void test_parse_dump_allocator(void **state)
{
    (void)state;
    static const char dump[] =
        "version: 1\ncreator: callgrind-3.19.0\n"
        "desc: Trigger: Client Request: k.0\n"
        "positions: line\nevents: Ir\nsummary: 10000\n\n"
        "ob=(1) /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so\nfl=(1) ???\nfn=(1) draw\n0 7920\n"
        "cob=(2) /usr/lib/x86_64-linux-gnu/libc.so.6\ncfi=(2) ???\ncfn=(2) realloc\ncalls=3 0 \n0 700\n"
        "cob=(2)\ncfi=(2)\ncfn=(3) memcpy\ncalls=2 0 \n0 1000\n"
        "cob=(2)\ncfi=(2)\ncfn=(4) malloc\ncalls=1 0 \n0 50\n"
        "cob=(2)\ncfi=(2)\ncfn=(5) free'2\ncalls=1 0 \n0 30\n\n"
        "ob=(2)\nfl=(2)\nfn=(2)\n0 200\ncfn=(4)\ncalls=1 0 \n0 200\ncfn=(3)\ncalls=1 0 \n0 300\n\n"
        "fn=(4)\n0 250\n\nfn=(3)\n0 1300\n\nfn=(5)\n0 30\n\n"
        "totals: 10000\n";
    char name[64];
    double t = 0, alloc = -1;
    assert_int_equal(callgrind_parse_dump(dump, name, sizeof name, &t, &alloc), 0);
    assert_string_equal(name, "k.0");
    assert_true(t == 10000.0);
    assert_true(alloc == 700.0 + 50.0 + 30.0);
    /* Without the call graph (nothing called into the allocator) the part is 0. */
    assert_int_equal(callgrind_parse_dump("desc: Trigger: Client Request: k.1\nfn=(1) draw\n0 5\n"
                                          "totals: 5\n", name, sizeof name, &t, &alloc), 0);
    assert_true(alloc == 0.0);
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

/* How many counting children: what was asked, but never more than the
 * configurations; by default at least one and at most CALLGRIND_MAX_JOBS
 * (and no more than this machine's online CPUs). */
static void test_jobs(void **state)
{
    (void)state;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    unsetenv(CALLGRIND_JOBS_ENV);   /* ctest sets it for the suite */
    assert_int_equal(callgrind_jobs(3, 10), 3);
    assert_int_equal(callgrind_jobs(3, 2), 2);
    assert_int_equal(callgrind_jobs(1, 48), 1);
    assert_int_equal(callgrind_jobs(0, 0), 1);
    assert_int_equal(callgrind_jobs(5, 0), 1);
    int j = callgrind_jobs(0, 1000);
    assert_true(j >= 1 && j <= CALLGRIND_MAX_JOBS && j <= cpus);
    assert_int_equal(callgrind_jobs(0, 1), 1);
    /* the environment sets the default, never what was asked */
    dm_str err = {0};
    setenv(CALLGRIND_JOBS_ENV, "3", 1);
    assert_int_equal(callgrind_env_jobs(&err), 3);
    assert_int_equal(callgrind_jobs(0, 10), 3);
    assert_int_equal(callgrind_jobs(2, 10), 2);
    assert_int_equal(callgrind_jobs(0, 2), 2);
    static const char *const bad[] = {"257", "2x", "-1", " ", "1e3"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        setenv(CALLGRIND_JOBS_ENV, bad[i], 1);
        dm_str_free(&err);
        assert_int_equal(callgrind_env_jobs(&err), -1);
        assert_non_null(strstr(dm_str_get(&err), "0..256"));
        assert_int_equal(callgrind_jobs(0, 1000), j);   /* a bad value is the automatic default */
    }
    setenv(CALLGRIND_JOBS_ENV, "", 1);
    assert_int_equal(callgrind_env_jobs(&err), 0);
    setenv(CALLGRIND_JOBS_ENV, "0", 1);   /* as --count-jobs 0: automatic */
    assert_int_equal(callgrind_env_jobs(&err), 0);
    assert_int_equal(callgrind_jobs(0, 1000), j);
    unsetenv(CALLGRIND_JOBS_ENV);
    dm_str_free(&err);
}

/* The frames a path configuration counts: all F up to
 * CALLGRIND_PATH_FRAMES (16), then every ceil(F/16)-th below F; a still
 * one CALLGRIND_FRAMES. */
static void test_path_frames(void **state)
{
    (void)state;
    static const struct { const char *frames; int n, step; } cases[] = {
        {"2", 2, 1}, {"16", 16, 1}, {"17", 9, 2}, {"32", 16, 2}, {"33", 11, 3}, {"60", 15, 4},
        {"100000", 16, 6250},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        dm_kv kv[2] = {{.key = "camera.path", .value = "dolly"},
                       {.key = "camera.path_frames", .value = (char *)cases[i].frames}};
        plan_config pc = {.params = kv, .n_params = 2};
        int step = 0, n = callgrind_path_frames(&pc, &step);
        assert_int_equal(n, cases[i].n);
        assert_int_equal(step, cases[i].step);
        /* the last counted frame is inside the path */
        assert_true((n - 1) * step < atoi(cases[i].frames));
    }
    dm_kv still = {.key = "camera.path", .value = "still"};
    plan_config pc = {.params = &still, .n_params = 1};
    int step = 0;
    assert_int_equal(callgrind_path_frames(&pc, &step), CALLGRIND_FRAMES);
    assert_int_equal(step, 1);
    pc.n_params = 0;
    assert_int_equal(callgrind_path_frames(&pc, &step), CALLGRIND_FRAMES);
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
             cmocka_unit_test(test_parse_dump_allocator),
             cmocka_unit_test(test_disagreement_boundary),
             cmocka_unit_test(test_disagreement_not_counted),
             cmocka_unit_test(test_path_frames),
             cmocka_unit_test(test_jobs))
