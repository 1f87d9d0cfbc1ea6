/* libFuzzer target: the sweep-file parser must accept or reject any input
 * without crashing, leaking or reading out of bounds, and a rejection must
 * carry a message naming the file. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "sweep/sweep.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    sweep s;
    dm_str err = {0};
    int rc = sweep_parse(text, "fuzz.yaml", &s, &err);
    if (rc == 0)
        sweep_free(&s);
    else if (strncmp(dm_str_get(&err), "fuzz.yaml:", 10) != 0)
        abort();                 /* every rejection names the file */
    dm_str_free(&err);
    free(text);
    return 0;
}
