#include "params.h"
#include "cli.h"
#include "core/dm_util.h"
#include "techniques/axes.h"

#include <stdlib.h>
#include <string.h>

/* technique= is taken first: a user's GLSL file declares axes (user_technique.h). */
static int params__first(const char *arg) { return strncmp(arg, "technique=", 10) == 0; }

int cli_params_parse(const char *cmd, int argc, char **argv, dm_kv **kv, size_t *n)
{
    for (int k = 0; k < 2 * argc; k++) {
        int i = k % argc;
        if (params__first(argv[i]) != (k < argc))
            continue;
        char *eq = strchr(argv[i], '=');
        if (!eq)
            return cli_usage_error("%s: '%s': expected KEY=VALUE (axes: dmbench list axes)", cmd, argv[i]);
        char *key = dm_xasprintf("%.*s", (int)(eq - argv[i]), argv[i]);
        dm_str err = {0};
        int rc = axes_check(key, eq + 1, &err) ? cli_usage_error("%s: %s", cmd, dm_str_get(&err)) : -1;
        char *canon = rc < 0 ? axes_canonical(key, eq + 1) : NULL;
        if (canon)
            dm_kv_push(kv, n, key, canon);
        free(canon);
        free(key);
        dm_str_free(&err);
        if (rc >= 0)
            return rc;
    }
    return -1;
}
