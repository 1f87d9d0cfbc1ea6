/* sweep_paths.c — file-naming axis values relative to the sweep file (see
 * sweep_paths.h). */
#include "sweep/sweep_paths.h"

#include <stdlib.h>
#include <string.h>

#include "core/dm_util.h"
#include "techniques/user_mesh.h"
#include "techniques/user_technique.h"

char *sweep_paths_resolve(const char *sweep_path, const char *axis, char *text)
{
    size_t np = strlen(USER_MESH_PREFIX);
    const char *prefix;
    if (text && strcmp(axis, "mesh") == 0 && strncmp(text, USER_MESH_PREFIX, np) == 0)
        prefix = USER_MESH_PREFIX;
    else if (text && strcmp(axis, "technique") == 0 && user_technique_is_path(text))
        prefix = "";   /* a user technique's GLSL file (user_technique.h) */
    else
        return text;
    const char *path = text + strlen(prefix), *slash = strrchr(sweep_path, '/');
    if (path[0] == '/' || path[0] == '\0' || !slash)
        return text;
    char *out = dm_xasprintf("%s%.*s/%s", prefix, (int)(slash - sweep_path), sweep_path, path);
    free(text);
    return out;
}

const char *const sweep_paths_map_kinds[SWEEP_PATHS_MAPS] = { "height", "normal", "albedo" };

/* A user map path, made relative to the sweep file's directory. */
static char *sweep_paths__map(const char *sweep_path, const char *path)
{
    const char *slash = strrchr(sweep_path, '/');
    if (path[0] == '/' || !slash)
        return dm_xstrdup(path);
    return dm_xasprintf("%.*s/%s", (int)(slash - sweep_path), sweep_path, path);
}

char *sweep_paths_maps(const char *sweep_path, const char *const paths[SWEEP_PATHS_MAPS])
{
    dm_str v = {0};
    for (int k = 0; k < SWEEP_PATHS_MAPS; k++) {
        if (!paths[k])
            continue;
        char *path = sweep_paths__map(sweep_path, paths[k]);
        dm_str_printf(&v, "%s%s=", v.len ? ";" : "", sweep_paths_map_kinds[k]);
        for (const char *q = path; *q; q++)   /* a ';' in the path is written ";;" */
            dm_str_cat(&v, *q == ';' ? ";;" : (char[2]){ *q, 0 });
        free(path);
    }
    return v.len ? dm_str_take(&v) : NULL;
}
