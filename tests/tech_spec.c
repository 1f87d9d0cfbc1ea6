/* tech_spec.c — see tech_spec.h. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "tests/tech_spec.h"

size_t parse(const char *spec, dm_kv kv[TECHFIX_MAX_PARAMS], char *buf, size_t cap)
{
    snprintf(buf, cap, "%s", spec);
    size_t n = 0;
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok && n < TECHFIX_MAX_PARAMS;
         tok = strtok_r(NULL, " ", &save)) {
        char *eq = strchr(tok, '=');
        assert_non_null(eq);
        *eq = 0;
        kv[n].key = tok;
        kv[n++].value = eq + 1;
    }
    return n;
}

render_item spec_prepare(render_ctx *r, const char *spec, int want, dm_str *log)
{
    char buf[1024];
    dm_kv kv[TECHFIX_MAX_PARAMS];
    size_t n = parse(spec, kv, buf, sizeof buf);
    render_item it = {0};
    dm_str scratch = {0};
    int rc = render_prepare(r, kv, n, &it, log ? log : &scratch);
    if (rc != want)
        fprintf(stderr, "%s: %s\n", spec, dm_str_get(log ? log : &scratch));
    dm_str_free(&scratch);
    assert_int_equal(rc, want);
    return it;
}
