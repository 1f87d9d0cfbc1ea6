/* libFuzzer target: the CSV reader of `dmbench fit --data` must accept or
 * reject any file without crashing; a rejection names the file, an
 * accepted table has named columns and a whole number of rows. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/fit_data.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, "csv", "csv");
    fit_data d;
    dm_str err = {0};
    if (fit_data_load_csv(path, &d, &err) == 0) {
        if (!d.n_cols || !d.names)
            abort();
        for (size_t i = 0; i < d.n_cols; i++)
            if (!d.names[i] || !d.names[i][0])
                abort();
        fit_data_free(&d);
    } else if (!strstr(dm_str_get(&err), path)) {
        abort();
    }
    dm_str_free(&err);
    return 0;
}
