#include "params.h"
#include "cli.h"
#include "core/dm_util.h"
#include "techniques/axes.h"

#include <stdlib.h>
#include <string.h>

int cli_params_parse(const char *cmd, int argc, char **argv, dm_kv **kv, size_t *n)
{
    for (int i = 0; i < argc; i++) {
        char *eq = strchr(argv[i], '=');
        if (!eq)
            return cli_usage_error("%s: '%s': expected KEY=VALUE (axes: dmbench list axes)", cmd, argv[i]);
        *eq = '\0';
        dm_str err = {0};
        if (axes_check(argv[i], eq + 1, &err) != 0) {
            int rc = cli_usage_error("%s: %s", cmd, dm_str_get(&err));
            dm_str_free(&err);
            return rc;
        }
        char *canon = axes_canonical(argv[i], eq + 1);
        dm_kv_push(kv, n, argv[i], canon);
        free(canon);
    }
    return -1;
}
