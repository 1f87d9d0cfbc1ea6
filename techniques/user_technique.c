/* user_technique.c — a user's GLSL file parsed and checked into a value
 * (user_technique_internal.h); registering it is the catalog's
 * (catalog.c), so nothing here reads or changes a registry. */
#include "techniques/user_technique_internal.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/dm_error.h"
#include "core/dm_results.h"
#include "techniques/shaders.h"

/* The built-in axes a fragment-stage user technique reads: those of
 * built-in pom (lighting, maps' formats, depth, shadows) without its
 * search's steps, which a user technique declares as its own parameters. */
static const char *const user_technique__fragment_axes[] = {
    "lighting", "light_count", "roughness", "specular_map", "attenuation", "light_radius",
    "normal_format", "toksvig", "height_scale", "height_format", "shadow", NULL};
/* A tessellation-level user technique: built-in tess-displacement's without
 * lod, tess_inner and tess_outer, which the user's function replaces. */
static const char *const user_technique__tess_axes[] = {
    "lighting", "light_count", "roughness", "specular_map", "attenuation", "light_radius",
    "normal_format", "toksvig", "height_scale", "tess_level", "tess_spacing", "patch_cull",
    "crack_free", "tess_smooth", "displaced_normals", NULL};

static const char *const user_technique__fragment_program[] = {"surface.vert.glsl",
                                                                 "surface.frag.glsl", NULL};
static const char *const user_technique__tess_program[] = {"tess.vert.glsl", "tess.tcs.glsl", "tess.tes.glsl",
                                               "surface.frag.glsl", NULL};

static const user_technique__base user_technique__bases[] = {
    {"fragment", "surface.frag.glsl", "user_surface", "vec3 user_surface(vec2, vec3)",
     "vec3 user_surface(vec2 uv, vec3 v)` returning the visible point's UV (xy) and height (z)",
     "#define SURF_NORMAL_MAP\n#define SURF_USER\n", user_technique__fragment_axes, user_technique__fragment_program},
    {"tess-level", "tess.tcs.glsl", "user_tess_level", "float user_tess_level(vec3, vec3)",
     "float user_tess_level(vec3 a, vec3 b)` returning the tessellation level of the patch edge "
     "from a to b (world space)", "#define SURF_NORMAL_MAP\n#define LOD_USER\n", user_technique__tess_axes,
     user_technique__tess_program},
};
#define USER_TECHNIQUE__N_BASES (sizeof user_technique__bases / sizeof user_technique__bases[0])

int user_technique_is_path(const char *value)
{
    size_t n = value ? strlen(value) : 0;
    return n > 5 && strcmp(value + n - 5, ".glsl") == 0;
}

/* ---- the header ----------------------------------------------------------- */

int user_technique__fail(user_technique__parse *p, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (p->line > 0)
        dm_str_printf(p->err, "%s:%d: ", p->path, p->line);
    else
        dm_str_printf(p->err, "%s: ", p->path);
    dm_str_vprintf(p->err, fmt, ap);
    va_end(ap);
    return DM_ERR_PARSE;
}

/* The names a parameter may not take as results.csv's columns, "a, b, ...". */
static const char *user_technique__reserved_list(void)
{
    static const char *const cols[] = {DM_RESULT_LEAD_COLUMNS, DM_RESULT_TRAIL_COLUMNS};
    static char list[128];
    if (!list[0])
        for (size_t i = 0, off = 0; i < sizeof cols / sizeof cols[0]; i++)
            off += (size_t)snprintf(list + off, sizeof list - off, "%s%s", i ? ", " : "", cols[i]);
    return list;
}

/* 1 when s is a name of [a-z][a-z0-9_-]* (dash only when dash != 0). */
static int user_technique__name_ok(const char *s, int dash)
{
    if (!islower((unsigned char)s[0]))
        return 0;
    for (; *s; s++)
        if (!islower((unsigned char)*s) && !isdigit((unsigned char)*s) && *s != '_' &&
            !(dash && *s == '-'))
            return 0;
    return 1;
}

static int user_technique__number(const char *s, axis_kind kind, double *out)
{
    char *end;
    errno = 0;
    double v = kind == AXIS_INT ? (double)strtol(s, &end, 10) : strtod(s, &end);
    if (errno || end == s || *end || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

/* 1 when v, a MIN, MAX or DEFAULT of a header, is a value the GLSL type of
 * kind holds as written (int: 32-bit; float: finite and, unless 0, not below
 * the smallest normal float, which a driver may flush to 0), so the value a
 * configuration records is the one the shader receives. */
static int user_technique__fits(axis_kind kind, double v)
{
    if (kind == AXIS_INT)
        return v >= INT32_MIN && v <= INT32_MAX;
    return fabs(v) <= FLT_MAX && (v == 0 || fabs(v) >= FLT_MIN);
}

/* The limits of the GLSL type of kind, for a message. */
static const char *user_technique__limits(axis_kind kind)
{
    return kind == AXIS_INT ? "an int is -2147483648..2147483647"
                            : "a float is finite, at most 3.40282347e+38 in magnitude and, other "
                              "than 0, at least 1.17549435e-38";
}

/* 1 when the identifier "u_" name appears in a built-in stage of the
 * program of base b (composed with its includes); the distinct names X of
 * the identifiers u_X found go to taken (", "-separated).  The user's
 * uniform u_NAME would be a second declaration of it. */
static int user_technique__uniform_taken(const user_technique__base *b, const char *name, dm_str *taken)
{
    const char **seen = NULL;
    size_t n_seen = 0;
    int hit = 0;
    char *defines = dm_xasprintf("%s#define USER_COLOR\n", b->defines);
    for (size_t f = 0; b->program[f]; f++) {
        dm_str text = {0}, err = {0};
        shaders_compose(b->program[f], defines, &text, &err);
        const char *t = dm_str_get(&text);
        for (const char *c = strstr(t, "u_"); c; c = strstr(c + 2, "u_")) {
            if (c > t && (isalnum((unsigned char)c[-1]) || c[-1] == '_'))
                continue;
            size_t len = strspn(c + 2, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_");
            if (len == 0)
                continue;
            char *id = dm_xasprintf("%.*s", (int)len, c + 2);
            hit |= strcmp(id, name) == 0;
            int dup = 0;
            for (size_t i = 0; i < n_seen && !dup; i++)
                dup = strcmp(seen[i], id) == 0;
            if (dup) {
                free(id);
                continue;
            }
            DM_VEC_PUSH(seen, n_seen, id);
            dm_str_printf(taken, "%s%s", n_seen > 1 ? ", " : "", id);
        }
        dm_str_free(&text);
        dm_str_free(&err);
    }
    for (size_t i = 0; i < n_seen; i++)
        free((char *)seen[i]);
    free(seen);
    free(defines);
    return hit;
}

/* //@param NAME TYPE MIN MAX DEFAULT [help...] */
static int user_technique__param_line(user_technique__parse *p, char *rest)
{
    char name[64] = "", type[16] = "", lo[32] = "", hi[32] = "", def[32] = "";
    int used = 0;
    if (sscanf(rest, "%63s %15s %31s %31s %31s %n", name, type, lo, hi, def, &used) < 5)
        return user_technique__fail(p, "@param needs NAME TYPE MIN MAX DEFAULT (e.g. `//@param "
                                       "relief_steps int 4 256 32`), got '%s'", rest);
    if (!user_technique__name_ok(name, 0))
        return user_technique__fail(p, "parameter name '%s': use lower-case letters, digits and '_', "
                                       "starting with a letter", name);
    if (dm_result_column_reserved(name))
        return user_technique__fail(p, "parameter '%s' would be a second '%s' column of results.csv; "
                                       "reserved names: %s", name, name, user_technique__reserved_list());
    if (p->t->n_params == USER_TECHNIQUE_MAX_PARAMS)
        return user_technique__fail(p, "more than %d parameters", USER_TECHNIQUE_MAX_PARAMS);
    for (size_t i = 0; i < p->t->n_params; i++)
        if (strcmp(p->t->params[i].name, name) == 0)
            return user_technique__fail(p, "parameter '%s' is declared twice", name);
    const char *taken = p->taken ? p->taken(name, p->taken_ctx) : NULL;   /* built-in or another file's */
    for (size_t i = 0; taken && p->self && i < p->self->n_params; i++)
        if (strcmp(p->self->params[i].name, name) == 0)
            taken = NULL;   /* its own, when reloading */
    if (taken)
        return user_technique__fail(p, "parameter '%s' collides with the %s axis '%s'; choose another name "
                        "(`dmbench list axes` lists the names in use)", name, taken, name);
    user_technique__param *q = &p->t->params[p->t->n_params];
    if (strcmp(type, "int") == 0)
        q->kind = AXIS_INT;
    else if (strcmp(type, "float") == 0)
        q->kind = AXIS_FLOAT;
    else
        return user_technique__fail(p, "parameter '%s' has type '%s'; valid types: int, float", name, type);
    double d;
    if (!user_technique__number(lo, q->kind, &q->min) || !user_technique__number(hi, q->kind, &q->max) ||
        !user_technique__number(def, q->kind, &d))
        return user_technique__fail(p, "parameter '%s': MIN MAX DEFAULT must be %s numbers, got '%s %s "
                                       "%s'", name, type, lo, hi, def);
    const char *what[] = {"MIN", "MAX", "DEFAULT"}, *text[] = {lo, hi, def};
    double vals[] = {q->min, q->max, d};
    for (int i = 0; i < 3; i++)
        if (!user_technique__fits(q->kind, vals[i]))
            return user_technique__fail(p, "parameter '%s': %s %s does not fit the GLSL type %s (%s)", name,
                            what[i], text[i], type, user_technique__limits(q->kind));
    if (q->min > q->max)
        return user_technique__fail(p, "parameter '%s' has an empty range [%s, %s] (MIN is above MAX)",
                                    name, lo, hi);
    if (d < q->min || d > q->max)
        return user_technique__fail(p, "parameter '%s': default %s is outside [%s, %s]", name, def, lo, hi);
    snprintf(q->name, sizeof q->name, "%s", name);
    q->line = p->line;
    snprintf(q->def, sizeof q->def, q->kind == AXIS_INT ? "%.0f" : "%.9g", d);
    char *help = dm_xasprintf("user parameter of %s%s%s", p->t->name, rest[used] ? ": " : "",
                              rest + used);
    snprintf(q->help, sizeof q->help, "%s", help);   /* a copy: help is not q's storage */
    free(help);
    p->t->n_params++;
    return 0;
}

/* One `//@` line (text after "//@"). */
static int user_technique__directive(user_technique__parse *p, char *d)
{
    char *end = d + strlen(d);
    while (end > d && isspace((unsigned char)end[-1]))
        *--end = '\0';
    char *rest = d + strcspn(d, " \t");
    if (*rest)
        *rest++ = '\0';
    rest += strspn(rest, " \t");
    if (strcmp(d, "technique") == 0) {
        if (!user_technique__name_ok(rest, 1) || strlen(rest) >= sizeof p->t->name)
            return user_technique__fail(p, "technique name '%s': use lower-case letters, digits, '-' "
                                           "and '_', starting with a letter", rest);
        if (*p->t->name)
            return user_technique__fail(p, "@technique is declared twice");
        snprintf(p->t->name, sizeof p->t->name, "%s", rest);
        p->t->name_line = p->line;
        return 0;
    }
    if (strcmp(d, "base") == 0) {
        for (size_t i = 0; i < USER_TECHNIQUE__N_BASES; i++)
            if (strcmp(rest, user_technique__bases[i].name) == 0) {
                p->t->base = &user_technique__bases[i];
                return 0;
            }
        return user_technique__fail(p, "unknown base '%s'; valid bases: fragment, tess-level", rest);
    }
    if (strcmp(d, "summary") == 0) {
        snprintf(p->t->summary, sizeof p->t->summary, "%s", rest);
        return 0;
    }
    if (strcmp(d, "param") == 0) {
        if (!*p->t->name)
            return user_technique__fail(p, "@param before @technique: declare the technique's name first");
        return user_technique__param_line(p, rest);
    }
    return user_technique__fail(p, "unknown directive '@%s'; valid directives: @technique, @summary, @base, "
                    "@param", d);
}

/* Offset of the first byte of s[0..n) that is not well-formed UTF-8
 * (overlong forms and surrogates included), or n. */
static size_t user_technique__utf8_bad(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    for (size_t i = 0; i < n;) {
        unsigned c = u[i];
        size_t len = c < 0x80 ? 1 : c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3
                   : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
        if (len == 0 || i + len > n)
            return i;
        for (size_t k = 1; k < len; k++)
            if ((u[i + k] & 0xc0) != 0x80)
                return i;
        unsigned c1 = len > 1 ? u[i + 1] : 0x80;
        if ((c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 > 0x9f) || (c == 0xf0 && c1 < 0x90) ||
            (c == 0xf4 && c1 > 0x8f))
            return i;
        i += len;
    }
    return n;
}

/* Reads every `//@` line of the text. */
int user_technique__header(user_technique__parse *p, const char *text)
{
    p->line = 0;
    for (const char *s = text; *s;) {
        const char *nl = strchr(s, '\n');
        size_t len = nl ? (size_t)(nl - s) : strlen(s);
        p->line++;
        const char *q = s + strspn(s, " \t");
        if ((size_t)(q - s) + 3 <= len && strncmp(q, "//@", 3) == 0) {
            size_t bad = user_technique__utf8_bad(s, len);
            if (bad < len)   /* a header's text is recorded (results, JSON): it must be text */
                return user_technique__fail(p, "byte 0x%02x at column %zu is not UTF-8: a `//@` line is "
                                               "recorded as text; save the file as UTF-8",
                                            (unsigned char)s[bad], bad + 1);
            char *d = dm_xasprintf("%.*s", (int)(len - (size_t)(q - s) - 3), q + 3);
            int rc = user_technique__directive(p, d);
            free(d);
            if (rc)
                return rc;
        }
        s += len + (nl ? 1 : 0);
    }
    p->line = 0;
    if (!p->t->base)
        p->t->base = &user_technique__bases[0];
    for (size_t i = 0; i < p->t->n_params; i++) {   /* the base is known now */
        const user_technique__param *q = &p->t->params[i];
        dm_str taken = {0};
        if (user_technique__uniform_taken(p->t->base, q->name, &taken)) {
            p->line = q->line;
            user_technique__fail(p, "parameter '%s' would declare the uniform u_%s, which dmbench's %s "
                                    "stages already declare; the names their u_ uniforms take: %s",
                                 q->name, q->name, p->t->base->name, dm_str_get(&taken));
        }
        dm_str_free(&taken);
        if (p->line)
            return DM_ERR_PARSE;
    }
    if (!*p->t->name)
        return user_technique__fail(p, "no `//@technique NAME` line: a user technique declares its name");
    return 0;
}

/* ---- the entry point ------------------------------------------------------ */

/* The text with comments blanked (newlines kept, so offsets keep lines). */
static char *user_technique__strip_comments(const char *text)
{
    char *s = dm_xstrdup(text);
    for (char *c = s; *c; c++) {
        if (c[0] == '/' && c[1] == '/') {
            while (*c && *c != '\n')
                *c++ = ' ';
            if (!*c)
                break;
        } else if (c[0] == '/' && c[1] == '*') {
            for (; *c && !(c[0] == '*' && c[1] == '/'); c++)
                *c = *c == '\n' ? '\n' : ' ';
            if (!*c)
                break;
            c[0] = c[1] = ' ';
            c++;
        }
    }
    return s;
}

static int user_technique__line_of(const char *text, const char *at)
{
    int line = 1;
    for (const char *c = text; c < at; c++)
        line += *c == '\n';
    return line;
}

/* The declaration "TYPE ENTRY(PARAMS)" at the identifier `id`, normalised
 * to single spaces, with parameter names dropped. */
static char *user_technique__signature(const char *code, const char *id, const char *entry)
{
    const char *b = id;
    while (b > code && isspace((unsigned char)b[-1]))
        b--;
    const char *e = b;
    while (b > code && (isalnum((unsigned char)b[-1]) || b[-1] == '_'))
        b--;
    dm_str s = {0};
    dm_str_catn(&s, b, (size_t)(e - b));
    dm_str_printf(&s, " %s(", entry);
    const char *c = strchr(id, '(');
    const char *close = c ? strchr(c, ')') : NULL;
    if (!close) {
        dm_str_cat(&s, "...");
        return dm_str_take(&s);
    }
    char *params = dm_xasprintf("%.*s", (int)(close - c - 1), c + 1);
    char *save = NULL;
    int first = 1;
    for (char *prm = strtok_r(params, ",", &save); prm; prm = strtok_r(NULL, ",", &save)) {
        char *words[8];
        int n = 0;
        char *ws = NULL;
        for (char *w = strtok_r(prm, " \t\r\n", &ws); w && n < 8; w = strtok_r(NULL, " \t\r\n", &ws))
            if (strcmp(w, "in") != 0 && strcmp(w, "const") != 0)
                words[n++] = w;
        dm_str_printf(&s, "%s%s", first ? "" : ", ", n >= 2 ? words[n - 2] : n ? words[0] : "");
        first = 0;
    }
    free(params);
    dm_str_cat(&s, ")");
    return dm_str_take(&s);
}

/* The definition of function `entry` in code (comments blanked), or NULL. */
static const char *user_technique__find_entry(const char *code, const char *entry)
{
    for (const char *c = strstr(code, entry); c; c = strstr(c + 1, entry)) {
        int start = c == code || !(isalnum((unsigned char)c[-1]) || c[-1] == '_');
        const char *after = c + strlen(entry);
        after += strspn(after, " \t\r\n");
        if (start && *after == '(')
            return c;
    }
    return NULL;
}

/* Checks the signature of the entry found at `at`: types as `want`
 * ("vec3 user_surface(vec2, vec3)"), `declared` the declaration to show. */
static int user_technique__signature_ok(user_technique__parse *p, const char *code, const char *at,
                                        const char *entry, const char *want, const char *declared)
{
    char *sig = user_technique__signature(code, at, entry);
    int rc = 0;
    if (strcmp(sig, want) != 0) {
        p->line = user_technique__line_of(code, at);
        rc = user_technique__fail(p, "entry point has the wrong signature `%s`; expected `%.*s`", sig,
                      (int)strcspn(declared, "`"), declared);
    }
    free(sig);
    return rc;
}

/* Checks that the code defines the entry point of its base, and the
 * optional colour function of a fragment-stage technique (sets t->color). */
int user_technique__entry(user_technique__parse *p, const char *text)
{
    const user_technique__base *b = p->t->base;
    char *code = user_technique__strip_comments(text);
    for (const char *l = code; l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        const char *c = l + strspn(l, " \t");
        if (*c != '#')
            continue;
        c++;
        c += strspn(c, " \t");
        if (strncmp(c, "include", 7) == 0 && !(isalnum((unsigned char)c[7]) || c[7] == '_')) {
            p->line = user_technique__line_of(code, l);
            free(code);
            return user_technique__fail(p, "#include is not supported in a user technique: dmbench's "
                                           "built-in %s stage has already included everything it offers "
                            "(docs/user-techniques.md); remove the line", b->name);
        }
    }
    const char *found = user_technique__find_entry(code, b->entry);
    const char *color =
        b == &user_technique__bases[0] ? user_technique__find_entry(code, "user_color") : NULL;
    int rc = 0;
    if (!found) {
        p->line = 0;
        rc = user_technique__fail(p, "no entry point: define `%s", b->returns);
    }
    rc = rc ? rc : user_technique__signature_ok(p, code, found, b->entry, b->entry_types, b->returns);
    if (rc == 0 && color)
        rc = user_technique__signature_ok(p, code, color, "user_color", "vec4 user_color(vec2, vec3, vec3)",
                              "vec4 user_color(vec2 uv, vec3 v, vec3 at)`");
    p->t->color = color != NULL;
    free(code);
    return rc;
}

/* ---- loading ---------------------------------------------------------------- */

/* The user's stage of t: the built-in stage of its base, the uniforms of the
 * parameters, then the user's file from line USER_TECHNIQUE_LINE_BASE + 1. */
char *user_technique__compose(const user_technique__tech *t)
{
    dm_str s = {0};
    dm_str_printf(&s, "#include \"%s\"\n", t->base->stage_file);
    for (size_t i = 0; i < t->n_params; i++)
        dm_str_printf(&s, "uniform %s u_%s;\n", t->params[i].kind == AXIS_INT ? "int" : "float",
                      t->params[i].name);
    /* comments blanked (lines and columns kept): an `#include` line inside a
     * block comment is the user's prose, which the composer must not expand */
    char *code = user_technique__strip_comments(t->text);
    dm_str_printf(&s, "#line %d\n%s\n", USER_TECHNIQUE_LINE_BASE + 1, code);
    free(code);
    return dm_str_take(&s);
}

int user_technique__read(const char *path, char **text, dm_str *err)
{
    size_t len = 0;
    char why[256];
    int rc = dm_input_file(path, why, sizeof why);
    if (rc == DM_ERR_NOTFOUND) {
        dm_str_printf(err, "%s: technique file not found", path);
        return DM_ERR_IO;
    }
    if (rc) {
        dm_str_printf(err, "%s: technique file is %s", path, why);
        return DM_ERR_IO;
    }
    if (dm_read_file(path, text, &len) != 0) {
        dm_str_printf(err, "%s: cannot read the technique file: %s", path, strerror(errno));
        return DM_ERR_IO;
    }
    if (memchr(*text, '\0', len)) {
        dm_str_printf(err, "%s: a NUL byte: a technique file is GLSL text", path);
        free(*text);
        *text = NULL;
        return DM_ERR_PARSE;
    }
    return 0;
}

void user_technique__fill(user_technique__tech *t)
{
    size_t n = 0;
    for (size_t i = 0; t->base->axes[i]; i++)
        t->axes[n++] = t->base->axes[i];
    for (size_t i = 0; i < t->n_params; i++) {
        user_technique__param *q = &t->params[i];
        q->axis = (axis_info){.name = q->name, .kind = q->kind, .min = q->min, .max = q->max,
                              .def = q->def, .help = q->help};
        t->axes[n++] = q->name;
    }
    t->axes[n] = NULL;
    memcpy(t->stage, "user:", 5);
    memcpy(t->stage + 5, t->name, strlen(t->name) + 1);   /* name < 64 bytes, stage 80 */
    t->shader = user_technique__compose(t);
    int tess = t->base != &user_technique__bases[0];   /* tess-level: the user's control stage */
    snprintf(t->defines, sizeof t->defines, "%s%s", t->base->defines,
             t->color ? "#define USER_COLOR\n" : "");
    t->desc = (technique_desc){
        .name = t->name, .summary = *t->summary ? t->summary : "user technique",
        .vs = tess ? "tess.vert.glsl" : "surface.vert.glsl", .tcs = tess ? t->stage : NULL,
        .tes = tess ? "tess.tes.glsl" : NULL, .fs = tess ? "surface.frag.glsl" : t->stage,
        .defines = t->defines, .textures = TECH_TEX_HEIGHT | TECH_TEX_NORMAL | TECH_TEX_ALBEDO,
        .axes = t->axes, .version = 1,
        .uniforms = "those of the built-in stage of its base, plus u_<param> of each @param",
        .source_hash = dm_fnv1a64(t->text, strlen(t->text), DM_FNV_SEED)};
}

int user_technique__same_params(const user_technique__tech *a, const user_technique__tech *b)
{
    if (a->n_params != b->n_params)
        return 0;
    for (size_t i = 0; i < a->n_params; i++) {
        const user_technique__param *x = &a->params[i], *y = &b->params[i];
        if (strcmp(x->name, y->name) || x->kind != y->kind || x->min != y->min || x->max != y->max ||
            strcmp(x->def, y->def))
            return 0;
    }
    return 1;
}

int user_technique_source_check(const char *path, uint64_t want, dm_str *err)
{
    char *text = NULL, was[17], now[17];
    dm_str why = {0};
    int rc = user_technique__read(path, &text, &why);
    uint64_t have = text ? dm_fnv1a64(text, strlen(text), DM_FNV_SEED) : 0;
    dm_hex64(want, was);
    dm_hex64(have, now);
    if (rc != 0)
        dm_str_printf(err, "%s: the user technique's file cannot be read since the run started (%s)",
                      path, dm_str_get(&why));
    else if (have != want)
        dm_str_printf(err, "%s: the user technique's file changed since the run started (source hash "
                      "%s, now %s)", path, was, now);
    free(text);
    dm_str_free(&why);
    return rc ? DM_ERR_ARG : have != want ? DM_ERR_ARG : 0;
}

/* ---- driver logs ------------------------------------------------------------ */

void user_technique__map_log(const char *path, const char *log, dm_str *out)
{
    for (const char *s = log ? log : ""; *s;) {
        const char *nl = strchr(s, '\n');
        size_t len = nl ? (size_t)(nl - s) : strlen(s);
        int src = -1, line = 0, col = 0, used = 0;
        int located = sscanf(s, "%d:%d(%d): %n", &src, &line, &col, &used) == 3 && used > 0 &&
                      (size_t)used <= len;
        if (path && located && line > USER_TECHNIQUE_LINE_BASE)
            dm_str_printf(out, "%s:%d:%d: %.*s\n", path, line - USER_TECHNIQUE_LINE_BASE, col,
                          (int)(len - (size_t)used), s + used);
        else if (path && located && strncmp(s + used, "warning", 7) == 0)
            ;   /* the built-in stage's own warning */
        else
            dm_str_printf(out, "%.*s\n", (int)len, s);
        s += len + (nl ? 1 : 0);
    }
}
