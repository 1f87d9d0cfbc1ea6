/* libFuzzer target: the derived-counter expression evaluator must accept or
 * reject any input without crashing (deep nesting included); a rejection
 * names the formula, an acceptance gives a number. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "counters/counters_expr.h"

static int lookup(const char *name, size_t len, void *user, double *value, dm_str *err)
{
    (void)user;
    if (len == 1 && name[0] == 'x') {
        *value = 3.0;
        return 0;
    }
    dm_str_printf(err, "unknown counter '%.*s'", (int)(len > 32 ? 32 : len), name);
    return DM_ERR_UNKNOWN;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    dm_str err = {0};
    double v = 0;
    int rc = counters__expr_eval(text, lookup, NULL, &v, &err);
    if (rc == DM_ERR_PARSE && !strstr(dm_str_get(&err), "formula '"))
        abort();
    if (rc != 0 && !err.len)
        abort();
    dm_str_free(&err);
    free(text);
    return 0;
}
