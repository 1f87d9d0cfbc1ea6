/* fs_minimal.c — the minimal fragment shader of the stage-isolation passes
 * (see fs_minimal.h).  A small scanner of the top level of a GLSL source:
 * comments removed, preprocessor lines kept as they are, function bodies
 * skipped, `in`/`out` declarations (plain or interface blocks) read. */
#include "techniques/fs_minimal.h"
#include "core/dm_error.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FSM__MAX_IO 64

typedef struct fsm_io {
    int out;              /* 0 in, 1 out */
    char type[32];
    char gl_name[96];     /* how GL names it: "SurfaceData.uv", "o_color" */
    char expr[96];        /* how main names it: "vi.uv", "o_color" */
    char count[64];       /* array size expression, "" when not an array */
} fsm_io;

typedef struct fsm_scan {
    fsm_io io[FSM__MAX_IO];
    size_t n;
    dm_str *why;
} fsm_scan;

/* src with comments replaced by spaces (newlines kept). */
static char *fsm__strip(const char *src)
{
    size_t n = strlen(src);
    char *s = dm_xmalloc(n + 1);
    for (size_t i = 0; i <= n; i++)
        s[i] = src[i];
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '/' && s[i + 1] == '/') {
            while (i < n && s[i] != '\n')
                s[i++] = ' ';
        } else if (s[i] == '/' && s[i + 1] == '*') {
            s[i] = s[i + 1] = ' ';
            for (i += 2; i < n && !(s[i] == '*' && s[i + 1] == '/'); i++)
                s[i] = s[i] == '\n' ? '\n' : ' ';
            if (i < n)
                s[i] = s[i + 1] = ' ';
            i++;
        }
    }
    return s;
}

static int fsm__ident(char c) { return isalnum((unsigned char)c) || c == '_'; }

/* Offset of the first whole-word occurrence of word in s, or -1. */
static long fsm__word(const char *s, const char *word)
{
    size_t wl = strlen(word);
    for (const char *p = strstr(s, word); p; p = strstr(p + 1, word))
        if ((p == s || !fsm__ident(p[-1])) && !fsm__ident(p[wl]))
            return p - s;
    return -1;
}

void fs_minimal_traits(const char *src, fs_traits *out)
{
    char *s = fsm__strip(src);
    out->discards = fsm__word(s, "discard") >= 0;
    out->writes_depth = fsm__word(s, "gl_FragDepth") >= 0;
    free(s);
}

/* Splits text [a, b) into tokens: identifiers/numbers, or single characters. */
static size_t fsm__tokens(const char *a, const char *b, char tok[][64], size_t cap)
{
    size_t n = 0;
    while (a < b && n < cap) {
        if (isspace((unsigned char)*a)) {
            a++;
            continue;
        }
        size_t len = 1;
        if (fsm__ident(*a))
            while (a + len < b && fsm__ident(a[len]))
                len++;
        len = len < 63 ? len : 63;
        memcpy(tok[n], a, len);
        tok[n++][len] = '\0';
        a += len;
    }
    return n;
}

static int fsm__qualifier(const char *t)
{
    static const char *const q[] = {"flat", "smooth", "noperspective", "centroid", "sample",
                                    "invariant", "precise", "highp", "mediump", "lowp"};
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
        if (strcmp(t, q[i]) == 0)
            return 1;
    return 0;
}

/* Index of the first token after layout(...) and qualifiers. */
static size_t fsm__skip_quals(char tok[][64], size_t n)
{
    size_t i = 0;
    while (i < n) {
        if (strcmp(tok[i], "layout") == 0 && i + 1 < n && tok[i + 1][0] == '(') {
            for (int d = 0; i < n; i++) {
                d += tok[i][0] == '(' ? 1 : tok[i][0] == ')' ? -1 : 0;
                if (d == 0 && tok[i][0] == ')')
                    break;
            }
            i++;
        } else if (fsm__qualifier(tok[i])) {
            i++;
        } else {
            break;
        }
    }
    return i;
}

/* Reads "TYPE NAME [N]" at tok[i..n) into one io row named prefix+NAME;
 * returns the index after it, or 0 when it is not that shape. */
static size_t fsm__member(fsm_scan *sc, int out, const char *prefix, const char *block, char tok[][64],
                          size_t i, size_t n)
{
    if (i + 1 >= n || !fsm__ident(tok[i][0]) || !fsm__ident(tok[i + 1][0]) || sc->n >= FSM__MAX_IO)
        return 0;
    fsm_io *io = &sc->io[sc->n++];
    memset(io, 0, sizeof *io);
    io->out = out;
    snprintf(io->type, sizeof io->type, "%s", tok[i]);
    snprintf(io->expr, sizeof io->expr, "%s%s", prefix, tok[i + 1]);
    snprintf(io->gl_name, sizeof io->gl_name, "%s%s%s", block, block[0] ? "." : "", tok[i + 1]);
    i += 2;
    if (i < n && tok[i][0] == '[') {
        dm_str c = {0};
        for (i++; i < n && tok[i][0] != ']'; i++)
            dm_str_printf(&c, "%s ", tok[i]);
        snprintf(io->count, sizeof io->count, "(%s)", c.len ? dm_str_get(&c) : "");
        if (!c.len)
            dm_str_printf(sc->why, "input or output %s is an unsized array", io->expr);
        dm_str_free(&c);
        i++;
    }
    return i;
}

/* One top-level statement [a, b): records it when it declares inputs or
 * outputs (a plain declaration or an interface block). */
static void fsm__statement(fsm_scan *sc, const char *a, const char *b)
{
    char tok[256][64];
    size_t n = fsm__tokens(a, b, tok, 256), i = fsm__skip_quals(tok, n);
    if (i >= n || (strcmp(tok[i], "in") != 0 && strcmp(tok[i], "out") != 0))
        return;
    int out = tok[i][0] == 'o';
    i++;
    if (i + 1 < n && tok[i + 1][0] == '{') {   /* in Block { members } inst; */
        size_t close = i + 2;
        while (close < n && tok[close][0] != '}')
            close++;
        char prefix[80] = "";
        if (close + 1 < n && fsm__ident(tok[close + 1][0]))
            snprintf(prefix, sizeof prefix, "%s.", tok[close + 1]);
        if (close + 2 < n && tok[close + 2][0] == '[')
            dm_str_printf(sc->why, "interface block %s is an array", tok[i]);
        for (size_t k = i + 2; k < close;) {
            k = fsm__skip_quals(tok + k, close - k) + k;
            size_t next = fsm__member(sc, out, prefix, tok[i], tok, k, close);
            if (!next)
                break;
            while (next < close && tok[next][0] == ';')
                next++;
            k = next;
        }
        return;
    }
    fsm__member(sc, out, "", "", tok, i, n);
}

/* Walks the top level of s: statements end at ';' outside braces; function
 * and struct bodies are skipped, interface blocks kept in their statement. */
static void fsm__scan(fsm_scan *sc, const char *s)
{
    const char *start = s;
    for (const char *p = s; *p; p++) {
        if (p == s || p[-1] == '\n') {   /* a preprocessor line: skipped */
            const char *q = p;
            while (*q == ' ' || *q == '\t')
                q++;
            if (*q == '#') {
                while (*q && !(*q == '\n' && q[-1] != '\\'))
                    q++;
                if (!*q)
                    break;
                p = q;
                start = q + 1;
                continue;
            }
        }
        if (*p == ';') {
            fsm__statement(sc, start, p);
            start = p + 1;
        } else if (*p == '{') {
            char tok[64][64];
            size_t n = fsm__tokens(start, p, tok, 64), i = fsm__skip_quals(tok, n);
            int io = i < n && (strcmp(tok[i], "in") == 0 || strcmp(tok[i], "out") == 0);
            int depth = 0;
            for (; *p; p++) {
                depth += *p == '{' ? 1 : *p == '}' ? -1 : 0;
                if (depth == 0 && *p == '}')
                    break;
            }
            if (!*p)
                break;
            if (!io)
                start = p + 1;   /* a function or struct body: not a declaration */
        }
    }
}

/* The sum of one value of type t, or NULL for a type the rewrite cannot read. */
static const char *fsm__sum_of(const char *t)
{
    static const char *const ok[] = {"float", "vec2", "vec3", "vec4", "int", "ivec2", "ivec3", "ivec4",
                                     "uint", "uvec2", "uvec3", "uvec4", "mat2", "mat3", "mat4"};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++)
        if (strcmp(t, ok[i]) == 0)
            return "dm__sum";
    return NULL;
}

static const char fsm__prelude[] =
    "\n// minimal fragment stage (dmbench stage isolation): reads every input once\n"
    "float dm__sum(float x) { return x; }\n"
    "float dm__sum(vec2 x) { return x.x + x.y; }\n"
    "float dm__sum(vec3 x) { return x.x + x.y + x.z; }\n"
    "float dm__sum(vec4 x) { return x.x + x.y + x.z + x.w; }\n"
    "float dm__sum(int x) { return float(x); }\n"
    "float dm__sum(ivec2 x) { return dm__sum(vec2(x)); }\n"
    "float dm__sum(ivec3 x) { return dm__sum(vec3(x)); }\n"
    "float dm__sum(ivec4 x) { return dm__sum(vec4(x)); }\n"
    "float dm__sum(uint x) { return float(x); }\n"
    "float dm__sum(uvec2 x) { return dm__sum(vec2(x)); }\n"
    "float dm__sum(uvec3 x) { return dm__sum(vec3(x)); }\n"
    "float dm__sum(uvec4 x) { return dm__sum(vec4(x)); }\n"
    "float dm__sum(mat2 x) { return dm__sum(x[0]) + dm__sum(x[1]); }\n"
    "float dm__sum(mat3 x) { return dm__sum(x[0]) + dm__sum(x[1]) + dm__sum(x[2]); }\n"
    "float dm__sum(mat4 x) { return dm__sum(x[0]) + dm__sum(x[1]) + dm__sum(x[2]) + dm__sum(x[3]); }\n";

/* 1 when input io is in the active list (NULL: all are); an array counts
 * when any of its elements is listed. */
static int fsm__active(const fsm_io *io, const char *active)
{
    if (!active)
        return 1;
    size_t len = strlen(io->gl_name);
    for (const char *l = active; *l;) {
        size_t ll = strcspn(l, "\n");
        if (ll >= len && strncmp(l, io->gl_name, len) == 0 && (ll == len || l[len] == '['))
            return 1;
        l += ll + (l[ll] ? 1 : 0);
    }
    return 0;
}

/* The new main: sums the active inputs, writes every output (and depth). */
static void fsm__main(const fsm_scan *sc, const char *active, int writes_depth, dm_str *o)
{
    dm_str_printf(o, "%svoid main()\n{\n    float dm_s = 0.0;\n", fsm__prelude);
    for (size_t i = 0; i < sc->n; i++) {
        const fsm_io *io = &sc->io[i];
        if (!io->out && !fsm__active(io, active))
            continue;
        const char *ix = io->count[0] ? "[dm_k]" : "";
        if (io->count[0])
            dm_str_printf(o, "    for (int dm_k = 0; dm_k < %s; dm_k++)\n    ", io->count);
        if (io->out)
            dm_str_printf(o, "    %s%s = %s(dm_s);\n", io->expr, ix, io->type);
        else
            dm_str_printf(o, "    dm_s += dm__sum(%s%s);\n", io->expr, ix);
    }
    if (writes_depth)
        dm_str_cat(o, "    gl_FragDepth = gl_FragCoord.z;\n");
    dm_str_cat(o, "}\n");
}

int fs_minimal_make(const char *src, const char *active, dm_str *out, dm_str *why)
{
    char *s = fsm__strip(src);
    fs_traits tr;
    fs_minimal_traits(src, &tr);
    fsm_scan sc = {.why = why};
    size_t why0 = why->len;
    long m = -1;
    for (long at = 0, k; (k = fsm__word(s + at, "main")) >= 0; at += k + 4) {
        const char *p = s + at + k + 4, *q = s + at + k;
        while (*p == ' ' || *p == '\t' || *p == '\n')
            p++;
        while (q > s && isspace((unsigned char)q[-1]))
            q--;
        if (*p == '(' && q - s >= 4 && strncmp(q - 4, "void", 4) == 0) {
            m = at + k;
            break;
        }
    }
    if (m < 0)
        dm_str_cat(why, "the fragment shader has no `void main(`");
    else
        fsm__scan(&sc, s);
    for (size_t i = 0; why->len == why0 && i < sc.n; i++)
        if (!sc.io[i].out && !fsm__sum_of(sc.io[i].type))
            dm_str_printf(why, "fragment input %s has type %s, which the minimal shader cannot read",
                          sc.io[i].expr, sc.io[i].type);
    if (why->len != why0) {
        free(s);
        return DM_ERR_PARSE;
    }
    dm_str_catn(out, s, (size_t)m);
    dm_str_cat(out, "dm__shade_main");
    dm_str_cat(out, s + m + 4);
    fsm__main(&sc, active, tr.writes_depth, out);
    free(s);
    return 0;
}
