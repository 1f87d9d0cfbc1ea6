/* params.h — KEY=VALUE arguments that set sweep axes (`dmbench render`,
 * `dmbench view`): checked against the axis catalogue and canonicalised. */
#ifndef CLI_PARAMS_H
#define CLI_PARAMS_H

#include <stddef.h>
#include "core/dm_results.h"

/* Appends each argv[i] = "KEY=VALUE" to *kv (canonical value).  Returns -1
 * to go on, or DM_EXIT_USAGE after printing "<cmd>: ..." for an argument
 * without '=', an unknown axis or an invalid value (with the valid
 * choices).  The '=' of each argument is overwritten. */
int cli_params_parse(const char *cmd, int argc, char **argv, dm_kv **kv, size_t *n);

#endif
