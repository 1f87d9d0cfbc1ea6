/* libFuzzer target: the user-technique header and entry-point checks
 * (techniques/user_technique.c) must accept or reject any text without
 * crashing, leaking or reading out of bounds, and a rejection must carry a
 * message naming the file. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "techniques/user_technique.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = '\0';
    dm_str err = {0};
    int rc = user_technique_check_text("fuzz.glsl", text, &err);
    if (rc != 0 && (rc != DM_ERR_PARSE || strncmp(dm_str_get(&err), "fuzz.glsl", 9) != 0))
        abort();                 /* every rejection is a parse error naming the file */
    dm_str_free(&err);
    free(text);
    return 0;
}
