/* shaders.c — GLSL sources by name (embedded, and added at run time) and
 * #include composition (see shaders.h). */
#include "techniques/shaders.h"

#include <string.h>

#include "core/dm_error.h"

struct shaders__entry { const char *name; const char *source; };
extern const struct shaders__entry shaders__table[];

#define SHADERS__MAX_DEPTH 8
#define SHADERS__MAX_FILES 32
#define SHADERS__MAX_ADDED 32

/* Sources added at run time (shaders_add): the user techniques' stages. */
static struct shaders__entry shaders__added[SHADERS__MAX_ADDED];
static size_t shaders__n_added;

const char *shaders_source(const char *name)
{
    for (size_t i = 0; name && shaders__table[i].name; i++)
        if (strcmp(shaders__table[i].name, name) == 0)
            return shaders__table[i].source;
    for (size_t i = 0; name && i < shaders__n_added; i++)
        if (strcmp(shaders__added[i].name, name) == 0)
            return shaders__added[i].source;
    return NULL;
}

int shaders_add(const char *name, const char *source)
{
    for (size_t i = 0; i < shaders__n_added; i++)
        if (strcmp(shaders__added[i].name, name) == 0) {
            shaders__added[i].source = source;
            return 0;
        }
    if (shaders__n_added == SHADERS__MAX_ADDED)
        return DM_ERR_RANGE;
    shaders__added[shaders__n_added++] = (struct shaders__entry){name, source};
    return 0;
}

typedef struct shaders__ctx {
    const char *seen[SHADERS__MAX_FILES];
    size_t n_seen;
    dm_str *out, *err;
} shaders__ctx;

/* Name inside `#include "name"` on this line, copied to buf; 0 if none. */
static int shaders__include_name(const char *line, size_t len, char *buf, size_t cap)
{
    const char *p = line, *end = line + len;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if ((size_t)(end - p) < 9 || strncmp(p, "#include", 8) != 0)
        return 0;
    const char *q = memchr(p, '"', (size_t)(end - p));
    const char *r = q ? memchr(q + 1, '"', (size_t)(end - q - 1)) : NULL;
    if (!r || (size_t)(r - q - 1) >= cap)
        return 0;
    memcpy(buf, q + 1, (size_t)(r - q - 1));
    buf[r - q - 1] = 0;
    return 1;
}

static int shaders__emit(shaders__ctx *c, const char *name, int depth)
{
    const char *src = shaders_source(name);
    if (!src || depth > SHADERS__MAX_DEPTH) {
        dm_str_printf(c->err, "shader '%s' %s\n", name, src ? "nested too deeply" : "not embedded");
        return DM_ERR_NOTFOUND;
    }
    for (size_t i = 0; i < c->n_seen; i++)
        if (c->seen[i] == src)
            return 0;
    if (c->n_seen < SHADERS__MAX_FILES)
        c->seen[c->n_seen++] = src;
    while (*src) {
        const char *nl = strchr(src, '\n');
        size_t len = nl ? (size_t)(nl - src) : strlen(src);
        char inc[128];
        if (shaders__include_name(src, len, inc, sizeof inc)) {
            int rc = shaders__emit(c, inc, depth + 1);
            if (rc)
                return rc;
        } else {
            dm_str_catn(c->out, src, len);
            dm_str_cat(c->out, "\n");
        }
        src += len + (nl ? 1 : 0);
    }
    return 0;
}

int shaders_compose(const char *name, const char *defines, dm_str *out, dm_str *err)
{
    shaders__ctx c = {.out = out, .err = err};
    dm_str_cat(out, "#version 450 core\n");
    if (defines)
        dm_str_cat(out, defines);
    return shaders__emit(&c, name, 0);
}
