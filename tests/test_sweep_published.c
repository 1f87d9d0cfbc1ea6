/* The `published:` block at plan time (sweep/published.h): every label names
 * exactly one planned configuration (its key is recorded), an unknown label
 * gets a did-you-mean over the planned labels, an ambiguous one is refused,
 * and published.json carries the resolved keys. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/dm_error.h"
#include "sweep/plan.h"
#include "sweep/published.h"
#include "sweep/sweep.h"

static const char sweep_head[] =
    "name: pub\n"
    "resolution: [64, 36]\n"
    "sweep:\n"
    "  mesh: [plane]\n"
    "  technique: [phong, pom]\n"
    "  steps: [8, 32]\n"
    "  resolution: [[64, 36], [128, 72]]\n"
    "published:\n"
    "  source: { study: \"A study (2010)\", table: \"Table 3\", gpu: \"GPU X\" }\n"
    "  unit: fps\n"
    "  baseline: phong resolution=64x36\n"
    "  values:\n"
    "    phong resolution=64x36: 200\n";

/* Parses sweep_head + extra and plans it; returns published_resolve's code. */
static int resolve(const char *extra, sweep *s, plan *p, dm_str *err)
{
    char *text = NULL;
    assert_true(asprintf(&text, "%s%s", sweep_head, extra) > 0);
    dm_str perr = {0};
    assert_int_equal(sweep_parse(text, "pub.yaml", s, &perr), 0);
    free(text);
    assert_int_equal(plan_build(s, NULL, p, &perr), 0);
    dm_str_free(&perr);
    return published_resolve(s->published, p, s->path, err);
}

static const plan_config *find(const plan *p, const char *tech, const char *steps, const char *res)
{
    for (size_t i = 0; i < p->n_configs; i++) {
        const plan_config *c = &p->configs[i];
        const char *st = dm_kv_get(c->params, c->n_params, "steps");
        if (strcmp(dm_kv_get(c->params, c->n_params, "technique"), tech) == 0 &&
            strcmp(dm_kv_get(c->params, c->n_params, "resolution"), res) == 0 &&
            (!steps || (st && strcmp(st, steps) == 0)))
            return c;
    }
    return NULL;
}

static void test_labels_resolve_to_keys(void **state)
{
    (void)state;
    sweep s;
    plan p;
    dm_str err = {0};
    /* word order is free and values are canonicalised ("128 x 72" spelled 128x72) */
    assert_int_equal(resolve("    pom steps=32 resolution=128x72: 50\n"
                             "    resolution=64x36 steps=8 pom: 120.5\n", &s, &p, &err), 0);
    published *pb = s.published;
    assert_int_equal(pb->n_values, 3);
    assert_string_equal(pb->unit, "fps");
    assert_string_equal(pb->gpu, "GPU X");
    assert_int_equal(pb->values[2].line, 15);
    assert_true(pb->values[2].value == 120.5);
    assert_string_equal(pb->values[0].key, find(&p, "phong", NULL, "64x36")->key);
    assert_string_equal(pb->values[1].key, find(&p, "pom", "32", "128x72")->key);
    assert_string_equal(pb->values[2].key, find(&p, "pom", "8", "64x36")->key);
    /* the canonical label of each planned configuration names itself */
    for (size_t i = 0; i < p.n_configs; i++) {
        dm_str l = {0};
        published_plan_label(&p, i, &l);
        published one = { .values = &(published_value){ .label = (char *)dm_str_get(&l), .line = 1 },
                          .n_values = 1 };
        assert_int_equal(published_resolve(&one, &p, "x", &err), 0);
        assert_string_equal(one.values[0].key, p.configs[i].key);
        dm_str_free(&l);
    }
    char dir[] = "/tmp/dm_pub_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char *path = NULL;
    assert_true(asprintf(&path, "%s/published.json", dir) > 0);
    assert_int_equal(published_write_json(pb, path), 0);
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(dm_read_file(path, &text, &len), 0);
    assert_non_null(strstr(text, pb->values[1].key));
    assert_non_null(strstr(text, "\"baseline\":\t\"phong resolution=64x36\""));
    free(text);
    unlink(path);
    rmdir(dir);
    free(path);
    plan_free(&p);
    sweep_free(&s);
}

/* A label line added to the sweep must be refused at plan time with `want`. */
static void refused(const char *extra, const char *want)
{
    sweep s;
    plan p;
    dm_str err = {0};
    assert_int_equal(resolve(extra, &s, &p, &err), DM_ERR_PARSE);
    if (!strstr(dm_str_get(&err), want))
        fail_msg("message '%s' lacks '%s'", dm_str_get(&err), want);
    dm_str_free(&err);
    plan_free(&p);
    sweep_free(&s);
}

static void test_unknown_label(void **state)
{
    (void)state;
    refused("    pom steps=16 resolution=64x36: 80\n",
            "pub.yaml:14: published label 'pom steps=16 resolution=64x36' names no planned "
            "configuration; did you mean 'pom resolution=64x36 steps=8'? valid planned labels: "
            "phong resolution=64x36, pom resolution=64x36 steps=8, pom resolution=64x36 steps=32, "
            "phong resolution=128x72, pom resolution=128x72 steps=8, pom resolution=128x72 steps=32");
    refused("    normal resolution=64x36: 80\n", "'normal resolution=64x36' names no planned");
}

static void test_ambiguous_label(void **state)
{
    (void)state;
    refused("    pom steps=8: 80\n", "pub.yaml:14: published label 'pom steps=8' matches 2 planned "
            "configurations; add axis=value words until one is left, e.g. 'pom resolution=64x36 steps=8'");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_labels_resolve_to_keys),
        cmocka_unit_test(test_unknown_label),
        cmocka_unit_test(test_ambiguous_label),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
