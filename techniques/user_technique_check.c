/* user_technique_check.c — compiling a loaded user technique once, before a
 * run, `render` or `predict` uses it (see user_technique.h). */
#include "techniques/user_technique.h"

#include <string.h>

#include "core/dm_error.h"
#include "techniques/render.h"

int user_technique_check_program(render_ctx *r, size_t i, dm_str *err)
{
    const technique_desc *t = user_technique_at(i);
    /* the smallest scene: only the program matters */
    dm_kv kv[] = {{(char *)"technique", (char *)t->name}, {(char *)"texture_size", (char *)"16"}};
    render_item item;
    dm_str log = {0};
    int rc = render_prepare(r, kv, sizeof kv / sizeof kv[0], &item, &log);
    if (rc == 0)
        render_release(r, item);
    else if (rc == DM_ERR_SHADER) {   /* the log's first line names the stage: said here */
        const char *all = dm_str_get(&log), *nl = strchr(all, '\n');
        const char *says = nl && nl[1 + strspn(nl + 1, " \t\r\n")] ? nl + 1 : all;
        dm_str_printf(err, "%s: user technique '%s' does not %s; the driver says:\n%s",
                      user_technique_path(t), t->name, strstr(all, "failed to link") ? "link" : "compile",
                      says[strspn(says, " \t\r\n")] ? says : "(nothing: the driver's log is empty)");
    } else
        dm_str_printf(err, "%s: user technique '%s' cannot be used: %s", user_technique_path(t),
                      t->name, dm_str_get(&log));
    dm_str_free(&log);
    return rc == DM_ERR_SHADER ? DM_ERR_PARSE : rc;
}
