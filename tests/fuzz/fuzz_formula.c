/* libFuzzer target: the formula parser and the bound clauses after it must
 * accept or reject any input without crashing; an accepted formula
 * evaluates to a number or NaN, a rejection names a column or the bound. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "models/bounds.h"
#include "models/formula.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const vars[] = { "tess_level", "SamplesPassed", "VSInvocations" };
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    formula *f = NULL;
    dm_str err = {0};
    char *expr = NULL;
    fit_bound *bounds = NULL;
    size_t nb = 0;
    if (bounds_split(text, &expr, &bounds, &nb, &err) != 0) {
        if (!strstr(dm_str_get(&err), "formula: bound ") && !strstr(dm_str_get(&err), "formula: bounds of"))
            abort();
        dm_str_free(&err);
        free(text);
        return 0;
    }
    for (size_t i = 0; i < nb; i++)
        if (!(bounds[i].lo <= bounds[i].hi) || !bounds[i].param[0])
            abort();
    bounds_free(bounds, nb);
    free(text);
    text = expr;
    if (formula_parse(text, vars, 3, &f, &err) == 0) {
        double x[3] = { 16, 1e5, 1e3 }, p[64], g[64];
        size_t np = formula_n_params(f);
        for (size_t i = 0; i < np && i < 64; i++)
            p[i] = 1.0 + (double)i;
        if (np <= 64)
            (void)formula_eval(f, x, p, g);
        formula_free(f);
    } else if (!strstr(dm_str_get(&err), "column")) {
        abort();
    }
    dm_str_free(&err);
    free(text);
    return 0;
}
