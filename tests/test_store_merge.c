/* Unit tests of store/merge.c: the rules of `dmbench merge` on runs built
 * in memory — a duplicated shard, shards of different splits, a key in two
 * runs and a different sweep are refused and leave the merge unchanged;
 * missing and incomplete shards are listed; runs of two machines are kept
 * apart (machine parameter, per-machine scenes, environment entries and a
 * warning), runs of one machine are not touched. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "core/dm_util.h"
#include "store/merge.h"

/* A finished run of sweep hash "h1" measured on fingerprint fp: shard
 * "K/N" (NULL = unsharded) planning `planned` configurations, holding the
 * configurations keys[0..n). */
static dm_run_result mk_run(const char *fp, const char *shard, int planned, const char *const *keys, size_t n)
{
    dm_run_result r = {0};
    r.id = dm_xstrdup("r");
    r.sweep = dm_xstrdup("s");
    r.sweep_hash = dm_xstrdup("h1");
    r.finished = dm_xstrdup("2026-01-01T00:00:00Z");
    dm_kv_push(&r.environment, &r.n_environment, "fingerprint", fp);
    dm_kv_push(&r.environment, &r.n_environment, "cpu", fp[0] == 'a' ? "CPU A" : "CPU B");
    dm_kv_push(&r.environment, &r.n_environment, "cpu_count", "2");
    if (shard) {
        char buf[16];
        snprintf(buf, sizeof buf, "%d", planned);
        dm_kv_push(&r.environment, &r.n_environment, "shard", shard);
        dm_kv_push(&r.environment, &r.n_environment, "shard_configs", buf);
    }
    r.configs = dm_xcalloc(n + 1, sizeof *r.configs);
    for (size_t i = 0; i < n; i++) {
        r.configs[i].key = dm_xstrdup(keys[i]);
        r.configs[i].scene = dm_xstrdup("plane@64x36");
        r.configs[i].ok = 1;
        dm_kv_push(&r.configs[i].params, &r.configs[i].n_params, "technique", "normal");
    }
    r.n_configs = n;
    /* one round naming every configuration, and a precision entry merge drops */
    r.rounds = dm_xcalloc(1, sizeof *r.rounds);
    dm_str named = {0};
    for (size_t i = 0; i < n; i++)
        dm_str_printf(&named, "%s%s", i ? " " : "", keys[i]);
    r.rounds[0] = (dm_round){ .scene = dm_xstrdup("plane@64x36"), .keys = dm_xstrdup(dm_str_get(&named)),
                              .calib_ns = 1e7 };
    dm_str_free(&named);
    r.n_rounds = 1;
    r.precision = dm_xcalloc(1, sizeof *r.precision);
    r.precision[0] = (dm_scene_precision){ .scene = dm_xstrdup("plane@64x36"), .corrected = 1 };
    r.n_precision = 1;
    return r;
}

static int add(merge_state *m, dm_run_result r, const char *dir, dm_str *err)
{
    return merge_add(m, &r, dir, err);
}

static void test_shards_once_each(void **state)
{
    (void)state;
    const char *k1[] = { "01", "02" }, *k2[] = { "03" }, *k2b[] = { "04" };
    merge_state m = {0};
    dm_str err = {0};
    assert_int_equal(add(&m, mk_run("aaaa", "1/3", 2, k1, 2), "s1", &err), 0);
    assert_int_equal(add(&m, mk_run("aaaa", "2/3", 1, k2, 1), "s2", &err), 0);
    /* the same shard again, even with other keys: refused */
    assert_int_equal(add(&m, mk_run("aaaa", "2/3", 1, k2b, 1), "s2again", &err), DM_ERR_ARG);
    assert_string_equal(dm_str_get(&err), "shard 2/3 given twice: s2 and s2again (each shard may be merged once)");
    dm_str_free(&err);
    /* a shard of another split */
    assert_int_equal(add(&m, mk_run("aaaa", "1/2", 1, k2b, 1), "t1", &err), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&err), "t1 is shard 1/2 but s1 is shard 1/3"));
    dm_str_free(&err);
    /* a key another run has */
    assert_int_equal(add(&m, mk_run("aaaa", NULL, 0, k2, 1), "whole", &err), DM_ERR_ARG);
    assert_non_null(strstr(dm_str_get(&err), "configuration 03 is in both s2 and whole"));
    dm_str_free(&err);
    /* refusals left the merge as it was */
    assert_int_equal(m.n_inputs, 2);
    assert_int_equal(m.out.n_configs, 3);
    dm_str miss = {0};
    assert_int_equal(merge_missing(&m, &miss), 1);
    assert_string_equal(dm_str_get(&miss), "shard 3/3: not given\n");
    dm_str_free(&miss);
    merge_free(&m);
}

static void test_other_sweep_refused(void **state)
{
    (void)state;
    const char *k1[] = { "01" }, *k2[] = { "02" };
    merge_state m = {0};
    dm_str err = {0};
    assert_int_equal(add(&m, mk_run("aaaa", "1/2", 1, k1, 1), "s1", &err), 0);
    dm_run_result r = mk_run("aaaa", "2/2", 1, k2, 1);
    free(r.sweep_hash);
    r.sweep_hash = dm_xstrdup("h2");
    assert_int_equal(merge_add(&m, &r, "s2", &err), DM_ERR_ARG);
    assert_string_equal(dm_str_get(&err), "s2 was made from a different sweep file (hash h2 vs h1)");
    dm_str_free(&err);
    merge_free(&m);
}

static void test_incomplete_shards(void **state)
{
    (void)state;
    const char *k1[] = { "01", "02" }, *k2[] = { "03" };
    merge_state m = {0};
    dm_str err = {0}, miss = {0};
    /* shard 1 planned 3 but stored 2; shard 2 stored all but never finished */
    assert_int_equal(add(&m, mk_run("aaaa", "1/2", 3, k1, 2), "s1", &err), 0);
    dm_run_result r = mk_run("aaaa", "2/2", 1, k2, 1);
    free(r.finished);
    r.finished = NULL;
    assert_int_equal(merge_add(&m, &r, "s2", &err), 0);
    assert_int_equal(merge_missing(&m, &miss), 2);
    assert_string_equal(dm_str_get(&miss), "shard 1/2 (s1): 2 of 3 configurations\n"
                                           "shard 2/2 (s2): 1 of 1 configurations, the run did not finish\n");
    dm_str_free(&miss);
    merge_free(&m);
}

static void test_machines_kept_apart(void **state)
{
    (void)state;
    const char *k1[] = { "01", "02" }, *k2[] = { "03" };
    merge_state m = {0};
    dm_str err = {0};
    assert_int_equal(add(&m, mk_run("aaaa", "1/2", 2, k1, 2), "s1", &err), 0);
    assert_int_equal(add(&m, mk_run("bbbb", "2/2", 1, k2, 1), "s2", &err), 0);
    assert_int_equal(merge_machines(&m), 2);
    merge_finish(&m);
    const char *want_fp[] = { "aaaa", "aaaa", "bbbb" };
    for (size_t i = 0; i < 3; i++) {
        const dm_config_result *c = &m.out.configs[i];
        assert_string_equal(dm_kv_get(c->params, c->n_params, "machine"), want_fp[i]);
        char *scene = dm_xasprintf("plane@64x36 @ %s", want_fp[i]);
        assert_string_equal(c->scene, scene);
        free(scene);
    }
    assert_string_equal(dm_kv_get(m.out.environment, m.out.n_environment, "machine aaaa"),
                        "2 x CPU A, ?, LP_NUM_THREADS=?; runs: s1");
    assert_string_equal(dm_kv_get(m.out.environment, m.out.n_environment, "machine bbbb"),
                        "2 x CPU B, ?, LP_NUM_THREADS=?; runs: s2");
    /* the rounds kept, their scenes tagged like the configurations'; the
     * shards' precision entries dropped (computed again over the union) */
    assert_int_equal(m.out.n_rounds, 2);
    assert_string_equal(m.out.rounds[0].scene, "plane@64x36 @ aaaa");
    assert_string_equal(m.out.rounds[0].keys, "01 02");
    assert_string_equal(m.out.rounds[1].scene, "plane@64x36 @ bbbb");
    assert_int_equal(m.out.n_precision, 0);
    assert_int_equal(m.out.n_warnings, 1);
    assert_non_null(strstr(m.out.warnings[0], "merged from 2 machines"));
    assert_non_null(strstr(m.out.warnings[0], "no samples are pooled across machines"));
    merge_free(&m);
}

static void test_one_machine_untouched(void **state)
{
    (void)state;
    const char *k1[] = { "01" }, *k2[] = { "02" };
    merge_state m = {0};
    dm_str err = {0};
    assert_int_equal(add(&m, mk_run("aaaa", "1/2", 1, k1, 1), "s1", &err), 0);
    assert_int_equal(add(&m, mk_run("aaaa", "2/2", 1, k2, 1), "s2", &err), 0);
    merge_finish(&m);
    assert_int_equal(merge_machines(&m), 1);
    for (size_t i = 0; i < m.out.n_configs; i++) {
        assert_null(dm_kv_get(m.out.configs[i].params, m.out.configs[i].n_params, "machine"));
        assert_string_equal(m.out.configs[i].scene, "plane@64x36");
    }
    assert_int_equal(m.out.n_rounds, 2);
    assert_string_equal(m.out.rounds[1].scene, "plane@64x36");
    assert_string_equal(m.out.rounds[1].keys, "02");
    assert_int_equal(m.out.n_warnings, 0);
    dm_str miss = {0};
    assert_int_equal(merge_missing(&m, &miss), 0);
    merge_free(&m);
}

DM_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_shards_once_each),
             cmocka_unit_test(test_other_sweep_refused),
             cmocka_unit_test(test_incomplete_shards),
             cmocka_unit_test(test_machines_kept_apart),
             cmocka_unit_test(test_one_machine_untouched))
