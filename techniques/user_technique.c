/* user_technique.c — loading, checking and registering users' GLSL files (see user_technique.h). */
#include "techniques/user_technique.h"

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
static const char *const ut__fragment_axes[] = {
    "lighting", "light_count", "roughness", "specular_map", "attenuation", "light_radius",
    "normal_format", "toksvig", "height_scale", "height_format", "shadow", NULL};
/* A tessellation-level user technique: built-in tess-displacement's without
 * lod, tess_inner and tess_outer, which the user's function replaces. */
static const char *const ut__tess_axes[] = {
    "lighting", "light_count", "roughness", "specular_map", "attenuation", "light_radius",
    "normal_format", "toksvig", "height_scale", "tess_level", "tess_spacing", "patch_cull",
    "crack_free", "tess_smooth", "displaced_normals", NULL};
#define UT__MAX_BUILTIN 16

/* What a user file can be (`//@base`): the built-in stage its code is
 * appended to, the entry point it must define and the define that calls it. */
typedef struct ut__base {
    const char *name, *stage_file, *entry, *entry_types, *returns, *defines;
    const char *const *axes;
    const char *const *program;  /* the built-in stages of its program (their u_ names are taken) */
} ut__base;

static const char *const ut__fragment_program[] = {"surface.vert.glsl", "surface.frag.glsl", NULL};
static const char *const ut__tess_program[] = {"tess.vert.glsl", "tess.tcs.glsl", "tess.tes.glsl",
                                               "surface.frag.glsl", NULL};

static const ut__base ut__bases[] = {
    {"fragment", "surface.frag.glsl", "user_surface", "vec3 user_surface(vec2, vec3)",
     "vec3 user_surface(vec2 uv, vec3 v)` returning the visible point's UV (xy) and height (z)",
     "#define SURF_NORMAL_MAP\n#define SURF_USER\n", ut__fragment_axes, ut__fragment_program},
    {"tess-level", "tess.tcs.glsl", "user_tess_level", "float user_tess_level(vec3, vec3)",
     "float user_tess_level(vec3 a, vec3 b)` returning the tessellation level of the patch edge "
     "from a to b (world space)", "#define SURF_NORMAL_MAP\n#define LOD_USER\n", ut__tess_axes,
     ut__tess_program},
};
#define UT__N_BASES (sizeof ut__bases / sizeof ut__bases[0])

typedef struct ut__param {
    char name[64];
    axis_kind kind;
    double min, max;
    char def[32];
    char help[160];
    int line;                    /* of its `//@param` */
} ut__param;

typedef struct ut__tech {
    technique_desc desc;
    char name[64], summary[200], stage[80];   /* stage: "user:NAME", the composed stage */
    char defines[128];           /* the base's, + USER_COLOR when it defines user_color */
    int color;                   /* defines vec4 user_color(vec2 uv, vec3 v, vec3 at) */
    char *path, *text, *shader;
    const ut__base *base;        /* `//@base`, default fragment */
    const char *axes[UT__MAX_BUILTIN + USER_TECHNIQUE_MAX_PARAMS + 1];
    ut__param params[USER_TECHNIQUE_MAX_PARAMS];
    size_t n_params;
    int name_line;               /* line of `//@technique` */
} ut__tech;

static ut__tech ut__techs[USER_TECHNIQUE_MAX];
static size_t ut__n;
static axis_info ut__axes[USER_TECHNIQUE_MAX * USER_TECHNIQUE_MAX_PARAMS];
static size_t ut__n_axes;
static pthread_mutex_t ut__lock = PTHREAD_MUTEX_INITIALIZER;

void technique__names_changed(void);   /* technique.c: the technique axis's choices */

int user_technique_is_path(const char *value)
{
    size_t n = value ? strlen(value) : 0;
    return n > 5 && strcmp(value + n - 5, ".glsl") == 0;
}

size_t user_technique_count(void) { return ut__n; }
const technique_desc *user_technique_at(size_t i) { return i < ut__n ? &ut__techs[i].desc : NULL; }
size_t user_technique_axis_count(void) { return ut__n_axes; }
const axis_info *user_technique_axis_at(size_t i) { return i < ut__n_axes ? &ut__axes[i] : NULL; }

static ut__tech *ut__of(const technique_desc *t)
{
    for (size_t i = 0; t && i < ut__n; i++)
        if (&ut__techs[i].desc == t)
            return &ut__techs[i];
    return NULL;
}

const char *user_technique_path(const technique_desc *t)
{
    ut__tech *u = ut__of(t);
    return u ? u->path : NULL;
}

const technique_desc *user_technique_by_path(const char *path)
{
    for (size_t i = 0; path && i < ut__n; i++)
        if (strcmp(ut__techs[i].path, path) == 0)
            return &ut__techs[i].desc;
    return NULL;
}

const char *user_technique_shader_source(const char *name)
{
    for (size_t i = 0; name && i < ut__n; i++)
        if (strcmp(ut__techs[i].stage, name) == 0)
            return ut__techs[i].shader;
    return NULL;
}

/* ---- the header ----------------------------------------------------------- */

typedef struct ut__parse {
    const char *path;
    int line;
    dm_str *err;
    ut__tech *t;
    const ut__tech *self;        /* reloading: the registered technique of this file */
} ut__parse;

static int ut__fail(ut__parse *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int ut__fail(ut__parse *p, const char *fmt, ...)
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
static const char *ut__reserved_list(void)
{
    static const char *const cols[] = {DM_RESULT_LEAD_COLUMNS, DM_RESULT_TRAIL_COLUMNS};
    static char list[128];
    if (!list[0])
        for (size_t i = 0, off = 0; i < sizeof cols / sizeof cols[0]; i++)
            off += (size_t)snprintf(list + off, sizeof list - off, "%s%s", i ? ", " : "", cols[i]);
    return list;
}

/* 1 when s is a name of [a-z][a-z0-9_-]* (dash only when dash != 0). */
static int ut__name_ok(const char *s, int dash)
{
    if (!islower((unsigned char)s[0]))
        return 0;
    for (; *s; s++)
        if (!islower((unsigned char)*s) && !isdigit((unsigned char)*s) && *s != '_' &&
            !(dash && *s == '-'))
            return 0;
    return 1;
}

static int ut__number(const char *s, axis_kind kind, double *out)
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
static int ut__fits(axis_kind kind, double v)
{
    if (kind == AXIS_INT)
        return v >= INT32_MIN && v <= INT32_MAX;
    return fabs(v) <= FLT_MAX && (v == 0 || fabs(v) >= FLT_MIN);
}

/* The limits of the GLSL type of kind, for a message. */
static const char *ut__limits(axis_kind kind)
{
    return kind == AXIS_INT ? "an int is -2147483648..2147483647"
                            : "a float is finite, at most 3.40282347e+38 in magnitude and, other "
                              "than 0, at least 1.17549435e-38";
}

/* 1 when the identifier "u_" name appears in a built-in stage of the
 * program of base b (composed with its includes); the distinct names X of
 * the identifiers u_X found go to taken (", "-separated).  The user's
 * uniform u_NAME would be a second declaration of it. */
static int ut__uniform_taken(const ut__base *b, const char *name, dm_str *taken)
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
static int ut__param_line(ut__parse *p, char *rest)
{
    char name[64] = "", type[16] = "", lo[32] = "", hi[32] = "", def[32] = "";
    int used = 0;
    if (sscanf(rest, "%63s %15s %31s %31s %31s %n", name, type, lo, hi, def, &used) < 5)
        return ut__fail(p, "@param needs NAME TYPE MIN MAX DEFAULT (e.g. `//@param relief_steps int 4 "
                        "256 32`), got '%s'", rest);
    if (!ut__name_ok(name, 0))
        return ut__fail(p, "parameter name '%s': use lower-case letters, digits and '_', starting "
                        "with a letter", name);
    if (dm_result_column_reserved(name))
        return ut__fail(p, "parameter '%s' would be a second '%s' column of results.csv; reserved "
                        "names: %s", name, name, ut__reserved_list());
    if (p->t->n_params == USER_TECHNIQUE_MAX_PARAMS)
        return ut__fail(p, "more than %d parameters", USER_TECHNIQUE_MAX_PARAMS);
    for (size_t i = 0; i < p->t->n_params; i++)
        if (strcmp(p->t->params[i].name, name) == 0)
            return ut__fail(p, "parameter '%s' is declared twice", name);
    const axis_info *taken = axes_find(name);   /* built-in or another file's */
    for (size_t i = 0; taken && p->self && i < p->self->n_params; i++)
        if (strcmp(p->self->params[i].name, name) == 0)
            taken = NULL;   /* its own, when reloading */
    int user = taken >= ut__axes && taken < ut__axes + ut__n_axes;
    if (taken)
        return ut__fail(p, "parameter '%s' collides with the %s axis '%s'; choose another name "
                        "(`dmbench list axes` lists the names in use)", name,
                        user ? "user parameter" : "built-in", taken->name);
    ut__param *q = &p->t->params[p->t->n_params];
    if (strcmp(type, "int") == 0)
        q->kind = AXIS_INT;
    else if (strcmp(type, "float") == 0)
        q->kind = AXIS_FLOAT;
    else
        return ut__fail(p, "parameter '%s' has type '%s'; valid types: int, float", name, type);
    double d;
    if (!ut__number(lo, q->kind, &q->min) || !ut__number(hi, q->kind, &q->max) ||
        !ut__number(def, q->kind, &d))
        return ut__fail(p, "parameter '%s': MIN MAX DEFAULT must be %s numbers, got '%s %s %s'", name,
                        type, lo, hi, def);
    const char *what[] = {"MIN", "MAX", "DEFAULT"}, *text[] = {lo, hi, def};
    double vals[] = {q->min, q->max, d};
    for (int i = 0; i < 3; i++)
        if (!ut__fits(q->kind, vals[i]))
            return ut__fail(p, "parameter '%s': %s %s does not fit the GLSL type %s (%s)", name,
                            what[i], text[i], type, ut__limits(q->kind));
    if (q->min > q->max)
        return ut__fail(p, "parameter '%s' has an empty range [%s, %s] (MIN is above MAX)", name, lo,
                        hi);
    if (d < q->min || d > q->max)
        return ut__fail(p, "parameter '%s': default %s is outside [%s, %s]", name, def, lo, hi);
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
static int ut__directive(ut__parse *p, char *d)
{
    char *end = d + strlen(d);
    while (end > d && isspace((unsigned char)end[-1]))
        *--end = '\0';
    char *rest = d + strcspn(d, " \t");
    if (*rest)
        *rest++ = '\0';
    rest += strspn(rest, " \t");
    if (strcmp(d, "technique") == 0) {
        if (!ut__name_ok(rest, 1) || strlen(rest) >= sizeof p->t->name)
            return ut__fail(p, "technique name '%s': use lower-case letters, digits, '-' and '_', "
                            "starting with a letter", rest);
        if (*p->t->name)
            return ut__fail(p, "@technique is declared twice");
        snprintf(p->t->name, sizeof p->t->name, "%s", rest);
        p->t->name_line = p->line;
        return 0;
    }
    if (strcmp(d, "base") == 0) {
        for (size_t i = 0; i < UT__N_BASES; i++)
            if (strcmp(rest, ut__bases[i].name) == 0) {
                p->t->base = &ut__bases[i];
                return 0;
            }
        return ut__fail(p, "unknown base '%s'; valid bases: fragment, tess-level", rest);
    }
    if (strcmp(d, "summary") == 0) {
        snprintf(p->t->summary, sizeof p->t->summary, "%s", rest);
        return 0;
    }
    if (strcmp(d, "param") == 0) {
        if (!*p->t->name)
            return ut__fail(p, "@param before @technique: declare the technique's name first");
        return ut__param_line(p, rest);
    }
    return ut__fail(p, "unknown directive '@%s'; valid directives: @technique, @summary, @base, "
                    "@param", d);
}

/* Offset of the first byte of s[0..n) that is not well-formed UTF-8
 * (overlong forms and surrogates included), or n. */
static size_t ut__utf8_bad(const char *s, size_t n)
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
static int ut__header(ut__parse *p, const char *text)
{
    p->line = 0;
    for (const char *s = text; *s;) {
        const char *nl = strchr(s, '\n');
        size_t len = nl ? (size_t)(nl - s) : strlen(s);
        p->line++;
        const char *q = s + strspn(s, " \t");
        if ((size_t)(q - s) + 3 <= len && strncmp(q, "//@", 3) == 0) {
            size_t bad = ut__utf8_bad(s, len);
            if (bad < len)   /* a header's text is recorded (results, JSON): it must be text */
                return ut__fail(p, "byte 0x%02x at column %zu is not UTF-8: a `//@` line is recorded "
                                "as text; save the file as UTF-8", (unsigned char)s[bad], bad + 1);
            char *d = dm_xasprintf("%.*s", (int)(len - (size_t)(q - s) - 3), q + 3);
            int rc = ut__directive(p, d);
            free(d);
            if (rc)
                return rc;
        }
        s += len + (nl ? 1 : 0);
    }
    p->line = 0;
    if (!p->t->base)
        p->t->base = &ut__bases[0];
    for (size_t i = 0; i < p->t->n_params; i++) {   /* the base is known now */
        const ut__param *q = &p->t->params[i];
        dm_str taken = {0};
        if (ut__uniform_taken(p->t->base, q->name, &taken)) {
            p->line = q->line;
            ut__fail(p, "parameter '%s' would declare the uniform u_%s, which dmbench's %s stages "
                     "already declare; the names their u_ uniforms take: %s", q->name, q->name,
                     p->t->base->name, dm_str_get(&taken));
        }
        dm_str_free(&taken);
        if (p->line)
            return DM_ERR_PARSE;
    }
    if (!*p->t->name)
        return ut__fail(p, "no `//@technique NAME` line: a user technique declares its name");
    return 0;
}

/* ---- the entry point ------------------------------------------------------ */

/* The text with comments blanked (newlines kept, so offsets keep lines). */
static char *ut__strip_comments(const char *text)
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

static int ut__line_of(const char *text, const char *at)
{
    int line = 1;
    for (const char *c = text; c < at; c++)
        line += *c == '\n';
    return line;
}

/* The declaration "TYPE ENTRY(PARAMS)" at the identifier `id`, normalised
 * to single spaces, with parameter names dropped. */
static char *ut__signature(const char *code, const char *id, const char *entry)
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
static const char *ut__find_entry(const char *code, const char *entry)
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
static int ut__signature_ok(ut__parse *p, const char *code, const char *at, const char *entry,
                            const char *want, const char *declared)
{
    char *sig = ut__signature(code, at, entry);
    int rc = 0;
    if (strcmp(sig, want) != 0) {
        p->line = ut__line_of(code, at);
        rc = ut__fail(p, "entry point has the wrong signature `%s`; expected `%.*s`", sig,
                      (int)strcspn(declared, "`"), declared);
    }
    free(sig);
    return rc;
}

/* Checks that the code defines the entry point of its base, and the
 * optional colour function of a fragment-stage technique (sets t->color). */
static int ut__entry(ut__parse *p, const char *text)
{
    const ut__base *b = p->t->base;
    char *code = ut__strip_comments(text);
    for (const char *l = code; l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        const char *c = l + strspn(l, " \t");
        if (*c != '#')
            continue;
        c++;
        c += strspn(c, " \t");
        if (strncmp(c, "include", 7) == 0 && !(isalnum((unsigned char)c[7]) || c[7] == '_')) {
            p->line = ut__line_of(code, l);
            free(code);
            return ut__fail(p, "#include is not supported in a user technique: dmbench's built-in "
                            "%s stage has already included everything it offers "
                            "(docs/user-techniques.md); remove the line", b->name);
        }
    }
    const char *found = ut__find_entry(code, b->entry);
    const char *color = b == &ut__bases[0] ? ut__find_entry(code, "user_color") : NULL;
    int rc = 0;
    if (!found) {
        p->line = 0;
        rc = ut__fail(p, "no entry point: define `%s", b->returns);
    }
    rc = rc ? rc : ut__signature_ok(p, code, found, b->entry, b->entry_types, b->returns);
    if (rc == 0 && color)
        rc = ut__signature_ok(p, code, color, "user_color", "vec4 user_color(vec2, vec3, vec3)",
                              "vec4 user_color(vec2 uv, vec3 v, vec3 at)`");
    p->t->color = color != NULL;
    free(code);
    return rc;
}

/* ---- loading ---------------------------------------------------------------- */

/* The user's stage of t: the built-in stage of its base, the uniforms of the
 * parameters, then the user's file from line USER_TECHNIQUE_LINE_BASE + 1. */
static char *ut__compose(const ut__tech *t)
{
    dm_str s = {0};
    dm_str_printf(&s, "#include \"%s\"\n", t->base->stage_file);
    for (size_t i = 0; i < t->n_params; i++)
        dm_str_printf(&s, "uniform %s u_%s;\n", t->params[i].kind == AXIS_INT ? "int" : "float",
                      t->params[i].name);
    /* comments blanked (lines and columns kept): an `#include` line inside a
     * block comment is the user's prose, which the composer must not expand */
    char *code = ut__strip_comments(t->text);
    dm_str_printf(&s, "#line %d\n%s\n", USER_TECHNIQUE_LINE_BASE + 1, code);
    free(code);
    return dm_str_take(&s);
}

static int ut__read(const char *path, char **text, dm_str *err)
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

/* Publishes t (already filled) into the registry: its parameters become axes. */
static void ut__register(ut__tech *t)
{
    size_t n = 0;
    for (size_t i = 0; t->base->axes[i]; i++)
        t->axes[n++] = t->base->axes[i];
    for (size_t i = 0; i < t->n_params; i++) {
        ut__param *q = &t->params[i];
        ut__axes[ut__n_axes++] = (axis_info){.name = q->name, .kind = q->kind, .min = q->min,
                                             .max = q->max, .def = q->def, .help = q->help};
        t->axes[n++] = q->name;
    }
    t->axes[n] = NULL;
    memcpy(t->stage, "user:", 5);
    memcpy(t->stage + 5, t->name, strlen(t->name) + 1);   /* name < 64 bytes, stage 80 */
    t->shader = ut__compose(t);
    int tess = t->base != &ut__bases[0];   /* tess-level: the user's control stage */
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
    ut__n++;
    technique__names_changed();
}

static int ut__load_locked(const char *path, const char **name, dm_str *err)
{
    char *text = NULL;
    int rc = ut__read(path, &text, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < ut__n; i++)
        if (strcmp(ut__techs[i].path, path) == 0 && strcmp(ut__techs[i].text, text) == 0) {
            free(text);
            if (name)
                *name = ut__techs[i].name;
            return 0;   /* the same file again (a sweep parsed twice) */
        }
    if (ut__n == USER_TECHNIQUE_MAX) {
        free(text);
        dm_str_printf(err, "%s: more than %d user techniques in one run", path, USER_TECHNIQUE_MAX);
        return DM_ERR_RANGE;
    }
    ut__tech *t = &ut__techs[ut__n];
    memset(t, 0, sizeof *t);
    ut__parse p = {.path = path, .err = err, .t = t};
    rc = ut__header(&p, text);
    p.line = t->name_line;
    if (rc == 0 && technique_find(t->name))
        rc = ut__fail(&p, "technique name '%s' is taken (by %s); choose another in `//@technique`",
                      t->name, user_technique_path(technique_find(t->name))
                                   ? user_technique_path(technique_find(t->name)) : "a built-in technique");
    rc = rc ? rc : ut__entry(&p, text);
    if (rc) {
        free(text);
        memset(t, 0, sizeof *t);
        return rc;
    }
    t->path = dm_xstrdup(path);
    t->text = text;
    ut__register(t);
    if (name)
        *name = t->name;
    return 0;
}

static int ut__same_params(const ut__tech *a, const ut__tech *b)
{
    if (a->n_params != b->n_params)
        return 0;
    for (size_t i = 0; i < a->n_params; i++) {
        const ut__param *x = &a->params[i], *y = &b->params[i];
        if (strcmp(x->name, y->name) || x->kind != y->kind || x->min != y->min || x->max != y->max ||
            strcmp(x->def, y->def))
            return 0;
    }
    return 1;
}

/* Re-reads t's file: 1 when its text changed and was taken, 0 when it did
 * not change, a DM_ERR_* with a line in msg when it was refused. */
static int ut__reload_one(ut__tech *t, dm_str *msg)
{
    char *text = NULL;
    dm_str err = {0};
    int rc = ut__read(t->path, &text, &err);
    if (rc == 0 && strcmp(text, t->text) == 0) {
        free(text);
        return 0;
    }
    ut__tech *fresh = dm_xcalloc(1, sizeof *fresh);
    ut__parse p = {.path = t->path, .err = &err, .t = fresh, .self = t};
    rc = rc ? rc : ut__header(&p, text);
    rc = rc ? rc : ut__entry(&p, text);
    if (rc == 0 && (strcmp(fresh->name, t->name) != 0 || fresh->base != t->base || fresh->color != t->color ||
                    !ut__same_params(fresh, t)))
        rc = ut__fail(&p, "its name, base, functions or parameters changed; restart to use them");
    if (rc == 0) {
        free(t->text);
        free(t->shader);
        t->text = text;
        t->shader = ut__compose(t);
        t->desc.source_hash = dm_fnv1a64(text, strlen(text), DM_FNV_SEED);
    } else {
        dm_str_printf(msg, "%s\n", dm_str_get(&err));
        free(text);
    }
    free(fresh);
    dm_str_free(&err);
    return rc ? rc : 1;
}

int user_technique_reload(dm_str *msg)
{
    pthread_mutex_lock(&ut__lock);
    int changed = 0;
    for (size_t i = 0; i < ut__n; i++)
        changed += ut__reload_one(&ut__techs[i], msg) == 1;
    pthread_mutex_unlock(&ut__lock);
    return changed;
}

int user_technique_check_text(const char *path, const char *text, dm_str *err)
{
    pthread_mutex_lock(&ut__lock);
    ut__tech *t = dm_xcalloc(1, sizeof *t);
    ut__parse p = {.path = path, .err = err, .t = t};
    int rc = ut__header(&p, text);
    rc = rc ? rc : ut__entry(&p, text);
    free(t);
    pthread_mutex_unlock(&ut__lock);
    return rc;
}

int user_technique_source_check(const char *path, uint64_t want, dm_str *err)
{
    char *text = NULL, was[17], now[17];
    dm_str why = {0};
    int rc = ut__read(path, &text, &why);
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

int user_technique_load(const char *path, const char **name, dm_str *err)
{
    pthread_mutex_lock(&ut__lock);
    int rc = ut__load_locked(path, name, err);
    pthread_mutex_unlock(&ut__lock);
    return rc;
}

/* ---- driver logs ------------------------------------------------------------ */

void user_technique_map_log(const technique_desc *t, const char *log, dm_str *out)
{
    const char *path = user_technique_path(t);
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
